//! What `certify` prints: each rule's lines (message, details, hint, picture, the case and
//! how to replay it) and each implementation's closing summary; `replay` prints the same.

use refrast_conformance::{Report, RuleReport, Status};

use super::progress::Progress;

/// The closing lines of one implementation: tallies, time, profile; or why it was refused.
pub fn summarise(out: &Progress, report: &Report, seconds: f64) {
    let p = &report.profile;
    if let Some(why) = &report.refused {
        out.line(&format!("{}: REFUSED: {why}\n", p.name));
        return;
    }
    let (pass, fail, na) = report.tally();
    let beyond = match report.beyond_spec() {
        0 => String::new(),
        n => format!(", {n} beyond {}", p.spec),
    };
    out.line(&format!(
        "{}: {pass} passed, {fail} failed{beyond}, {na} not applicable ({:.1} s); profile: {}, {}, depth {}, band {} px, claims {}",
        p.name,
        seconds,
        p.snapping,
        p.fill,
        p.depth,
        p.band_px,
        p.spec
    ));
    if !p.about.is_empty() {
        out.line(&format!("  reports itself as: {}", p.about));
    }
    out.line(&format!("  features: {}", p.features.join("; ")));
    let cut: Vec<&str> = report
        .rules
        .iter()
        .filter(|r| r.budget_spent)
        .map(|r| r.id.as_str())
        .collect();
    if !cut.is_empty() {
        out.line(&format!(
            "  the time budget cut {} short (fewer cases than planned; a pass there is weaker): {}; \
             --budget SECONDS gives each rule more time",
            plural(cut.len(), "rule"),
            cut.join(", ")
        ));
    }
    if !report.not_run.is_empty() {
        out.line(&format!(
            "  --fail-fast: {} rules not run after the first failure: {}",
            report.not_run.len(),
            report.not_run.join(", ")
        ));
    }
    out.line("");
}

/// How `refrast replay` reaches an implementation: `--impl NAME`, or `--exec 'COMMAND'`.
pub fn reach(name: &str, is_exec: bool) -> String {
    if is_exec {
        format!("--exec {}", shell_words::quote(name))
    } else {
        format!("--impl {}", shell_words::quote(name))
    }
}

/// `n` and a noun, singular or plural (`vertex`, `vertices`).
pub fn plural(n: usize, noun: &str) -> String {
    match (n, noun) {
        (1, _) => format!("1 {noun}"),
        (_, "vertex") => format!("{n} vertices"),
        _ => format!("{n} {noun}s"),
    }
}

/// One rule's line, and for a failure its message, details, picture, counterexample and the
/// command that replays it (reaching the implementation with `reach`).
pub fn print_rule(out: &Progress, r: &RuleReport, reach: &str) {
    for line in rule_lines(r, reach) {
        out.line(&line);
    }
}

/// The lines [`print_rule`] prints.
pub fn rule_lines(r: &RuleReport, reach: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let cases = if r.budget_spent {
        format!("{:>6} of {} cases (time budget spent)", r.cases, r.planned)
    } else {
        format!("{:>6} cases", r.cases)
    };
    lines.push(format!(
        "{:<4}  {:<38} {:<9} {cases}",
        r.status.label(),
        r.id,
        r.kind,
    ));
    match r.status {
        Status::Pass => {}
        Status::NotApplicable => lines.push(format!(
            "      not applicable: {}",
            r.message.as_deref().unwrap_or("")
        )),
        Status::Fail | Status::BeyondSpec | Status::Crash | Status::Timeout | Status::Flake => {
            if let Some(note) = &r.spec_note {
                lines.push(format!("      beyond the specification: {note}"));
            }
            lines.push(format!("      {}", r.message.as_deref().unwrap_or("")));
            for detail in r.details.iter().skip(1) {
                lines.push(format!("        {detail}"));
            }
            if let Some(hint) = &r.hint {
                lines.push(format!("      hint: {hint}"));
            }
            if let Some(p) = &r.picture {
                lines.push(format!("      picture: {}", p.display()));
            }
            if let Some(path) = &r.case_path {
                lines.push(format!(
                    "      the case as data (JSON): {}; replay it alone: refrast replay {reach} {}",
                    path.display(),
                    shell_words::quote(&path.to_string_lossy()),
                ));
            }
            if let Some(why) = &r.shrinking_cut {
                lines.push(format!("      the counterexample may not be minimal: {why}"));
            }
            // A child in another language gets the case as data; Rust gets code to paste.
            let rust = r.counterexample.as_deref().filter(|c| !c.is_empty());
            match (&r.case_file, rust) {
                (Some(case), _) if reach.starts_with("--exec") => {
                    lines.push("      shrunk counterexample, as data (docs/json.md):".to_owned());
                    lines.extend(case.to_json().lines().map(|line| format!("        {line}")));
                }
                (_, Some(input)) => {
                    lines.push(
                        "      shrunk counterexample (after use refrast::*; use refrast_conformance::*;):"
                            .to_owned(),
                    );
                    lines.extend(input.lines().map(|line| format!("        {line}")));
                }
                (_, None) => {}
            }
        }
    }
    lines
}
