//! JUnit XML for a CI's test tab: a `testsuite` per implementation, a `testcase` per rule.
//!
//! Valid against the Jenkins JUnit schema committed in `cli/tests/data/junit-10.xsd` (checked by
//! `cli/tests/integration/results.rs` with xmllint). A failing rule is a `failure` (a `fail` or a `flake`) or
//! an `error` (a `crash` or a `timeout`) with its message, counterexample and the command that
//! reproduces it; `n/a` and `beyond-spec` are `skipped` with why. Under expectation files a
//! verdict they accept is `skipped` ("expected fail: …"), so the tab shows only what changed,
//! and an unexpected pass is a `failure` of type `unexpected-pass`.

use std::fmt::Write as _;

use refrast_conformance::expect::Expectations;
use refrast_conformance::{RuleReport, Status};

use super::{Document, Entry, Outcome, markup_entity, reproduce};

/// The document as JUnit XML; `expect` decides which verdicts are expected.
#[must_use]
pub fn junit(doc: &Document, expect: Option<&Expectations>) -> String {
    let suites: Vec<Suite> = doc
        .implementations
        .iter()
        .map(|e| suite(doc, e, expect))
        .collect();
    let (tests, failures, errors) = suites.iter().fold((0, 0, 0), |(t, f, e), s| {
        (t + s.tests, f + s.failures, e + s.errors)
    });
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<testsuites name=\"refrast certify\" tests=\"{tests}\" failures=\"{failures}\" errors=\"{errors}\" \
         time=\"{:.3}\">",
        doc.run.seconds.max(0.0)
    );
    for s in suites {
        x.push_str(&s.xml);
    }
    x.push_str("</testsuites>\n");
    x
}

/// One implementation's suite and its tallies.
struct Suite {
    xml: String,
    tests: usize,
    failures: usize,
    errors: usize,
}

/// What one rule's testcase holds.
enum Case {
    Passed,
    Skipped(String),
    Failure { kind: &'static str, message: String },
    Error { kind: &'static str, message: String },
}

/// One implementation's `<testsuite>`: its properties, and a testcase per rule (or the one
/// `certify` case of an implementation skipped, refused or that failed to start).
fn suite(doc: &Document, entry: &Entry, expect: Option<&Expectations>) -> Suite {
    let name = entry.subject.name();
    let cases = testcases(doc, entry, expect);
    let count = |of: fn(&Case) -> bool| cases.iter().filter(|c| of(&c.case)).count();
    let failures = count(|c| matches!(c, Case::Failure { .. }));
    let errors = count(|c| matches!(c, Case::Error { .. }));
    let skipped = count(|c| matches!(c, Case::Skipped(_)));
    let seconds: f64 = cases.iter().map(|c| c.seconds).sum();
    let mut x = String::new();
    let _ = writeln!(
        x,
        "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\" skipped=\"{skipped}\" \
         time=\"{seconds:.3}\" timestamp=\"{}\" hostname=\"{}\">",
        esc(name),
        cases.len(),
        esc(doc.run.started.trim_end_matches('Z')),
        esc(&doc.run.host.name)
    );
    properties(&mut x, doc, entry);
    for c in &cases {
        testcase(&mut x, name, c);
    }
    x.push_str("  </testsuite>\n");
    Suite {
        xml: x,
        tests: cases.len(),
        failures,
        errors,
    }
}

/// One testcase of a suite: a rule, or the one `certify` case of an implementation that did not
/// get as far as its rules.
struct Testcase {
    /// The rule's ID, or `certify`.
    id: String,
    /// Its seconds.
    seconds: f64,
    /// What JUnit calls its outcome.
    case: Case,
    /// The text of a failure or an error.
    body: String,
}

/// An entry's testcases: one per rule, or one `certify` case saying why there are none.
fn testcases(doc: &Document, entry: &Entry, expect: Option<&Expectations>) -> Vec<Testcase> {
    let certify = |case: Case| {
        vec![Testcase {
            id: "certify".into(),
            seconds: 0.0,
            case,
            body: String::new(),
        }]
    };
    match &entry.outcome {
        Outcome::Skipped { skipped, .. } => certify(Case::Skipped(format!("skipped: {skipped}"))),
        Outcome::FailedToStart { failed_to_start, .. } => certify(Case::Error {
            kind: "failed-to-start",
            message: failed_to_start.clone(),
        }),
        Outcome::Certified(report) if report.refused.is_some() => certify(Case::Error {
            kind: "refused",
            message: report.refused.clone().unwrap_or_default(),
        }),
        Outcome::Certified(report) => {
            let section = expect.map(|e| e.section(entry.subject.name()));
            report
                .rules
                .iter()
                .map(|r| {
                    let expected = section.map(|s| {
                        s.map_or((vec![Status::Pass], None), |s| {
                            let (accepts, line) = s.expected(&r.id);
                            (accepts, line.map(|l| l.written.clone()))
                        })
                    });
                    Testcase {
                        id: r.id.clone(),
                        seconds: r.seconds,
                        case: case_of(r, expected),
                        body: detail(doc, entry, r),
                    }
                })
                .collect()
        }
    }
}

/// The suite's `<properties>`: how the run was made, and the profile certified.
fn properties(x: &mut String, doc: &Document, entry: &Entry) {
    x.push_str("    <properties>\n");
    let o = &doc.run.options;
    let mut properties = vec![
        ("seed", o.seed.to_string()),
        (
            "cases",
            o.cases.map_or_else(|| "default".to_owned(), |c| c.to_string()),
        ),
        ("scale", o.scale.to_string()),
        ("refrast", doc.run.refrast_version.clone()),
        ("git-revision", doc.run.git_revision.clone()),
    ];
    if let Some(report) = entry.report() {
        properties.push(("profile", report.profile.name.clone()));
        properties.push(("claims", report.profile.spec.clone()));
    }
    for (k, v) in properties {
        let _ = writeln!(x, "      <property name=\"{k}\" value=\"{}\"/>", esc(&v));
    }
    x.push_str("    </properties>\n");
}

/// One `<testcase>` of the suite `name`.
fn testcase(x: &mut String, name: &str, c: &Testcase) {
    let open = format!(
        "    <testcase classname=\"refrast.{}\" name=\"{}\" time=\"{:.3}\"",
        esc(name),
        esc(&c.id),
        c.seconds
    );
    match &c.case {
        Case::Passed => {
            let _ = writeln!(x, "{open}/>");
        }
        Case::Skipped(why) => {
            let _ = writeln!(
                x,
                "{open}>\n      <skipped message=\"{}\"/>\n    </testcase>",
                esc(why)
            );
        }
        Case::Failure { kind, message } | Case::Error { kind, message } => {
            let tag = if matches!(c.case, Case::Failure { .. }) {
                "failure"
            } else {
                "error"
            };
            let _ = writeln!(
                x,
                "{open}>\n      <{tag} message=\"{}\" type=\"{kind}\">{}</{tag}>\n    </testcase>",
                esc(message),
                esc_text(&c.body)
            );
        }
    }
}

/// The testcase of a rule: its status, or under expectations (the accepted statuses and the
/// line's status as written) whether the status was expected.
fn case_of(r: &RuleReport, expected: Option<(Vec<Status>, Option<String>)>) -> Case {
    let message = r.message.clone().unwrap_or_default();
    if let Some((accepts, written)) = expected {
        let written = written.unwrap_or_else(|| "pass".to_owned());
        if accepts.contains(&r.status) && r.status != Status::Pass {
            return Case::Skipped(format!("expected {written}, got {}: {message}", r.status));
        }
        if !accepts.contains(&r.status) && r.status == Status::Pass {
            return Case::Failure {
                kind: "unexpected-pass",
                message: format!("expected {written}, got pass: tighten the expectations"),
            };
        }
    }
    match r.status {
        Status::Pass => Case::Passed,
        Status::NotApplicable => Case::Skipped(format!("not applicable: {message}")),
        Status::BeyondSpec => Case::Skipped(format!(
            "beyond the specification: {}",
            r.spec_note.as_deref().unwrap_or(&message)
        )),
        Status::Fail => Case::Failure {
            kind: "fail",
            message,
        },
        Status::Flake => Case::Failure {
            kind: "flake",
            message,
        },
        Status::Crash => Case::Error {
            kind: "crash",
            message,
        },
        Status::Timeout => Case::Error {
            kind: "timeout",
            message,
        },
    }
}

/// The text of a failing testcase: message, details, counterexample, and how to reproduce it.
fn detail(doc: &Document, entry: &Entry, r: &RuleReport) -> String {
    if !(r.status.is_failure() || r.status == Status::BeyondSpec) {
        return String::new();
    }
    let mut text = r.message.clone().unwrap_or_default();
    for d in r.details.iter().skip(1) {
        let _ = write!(text, "\n  {d}");
    }
    if let Some(c) = &r.counterexample {
        let _ = write!(text, "\ncounterexample:\n{c}");
    }
    let _ = write!(
        text,
        "\nreproduce: {}",
        reproduce(&doc.run.options, &entry.subject, r)
    );
    text
}

/// `text` as an element's content: [`esc`], but lines kept as lines.
fn esc_text(text: &str) -> String {
    esc(text).replace("&#10;", "\n")
}

/// `text` safe in XML 1.0 attributes and text: markup escaped, line breaks and tabs as
/// character references (an attribute would fold them), control characters XML cannot hold
/// written as `\u{…}`.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if let Some(entity) = markup_entity(c) {
            out.push_str(entity);
            continue;
        }
        match c {
            '\n' => out.push_str("&#10;"),
            '\t' => out.push_str("&#9;"),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::esc;

    #[test]
    fn escapes_markup_and_characters_xml_cannot_hold() {
        assert_eq!(esc("<a b=\"c\">&'"), "&lt;a b=&quot;c&quot;&gt;&amp;&#39;");
        assert_eq!(esc("a\u{0}b\u{1b}"), "a\\u{0}b\\u{1b}");
        assert_eq!(esc("line\nnext"), "line&#10;next");
    }
}
