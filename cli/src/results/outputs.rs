//! What a run leaves behind: the HTML page, the JSON document, JUnit XML, the verdicts judged
//! against expectation files and written back to one, and the exit code they make.

use std::path::PathBuf;
use std::process::ExitCode;

use refrast_conformance::expect::{self, Expectations, Mismatch, Taken};
use refrast_conformance::{Options, Rule};

use super::{Document, Outcome, html, junit};
use crate::say;

/// Where to write what, and the expectations to judge against.
pub struct Outputs {
    /// Folder of index.html and the pictures.
    pub report: PathBuf,
    /// `--json`.
    pub json: Option<PathBuf>,
    /// `--junit`.
    pub junit: Option<PathBuf>,
    /// The `--expect` files, read; `None` without any.
    pub expect: Option<Expectations>,
    /// `--update-expectations`.
    pub update: Option<PathBuf>,
}

/// Where a run's results go: the flags `certify` and `merge` share.
#[derive(clap::Args, Clone, Debug)]
pub struct OutputArgs {
    /// Folder for the report: index.html (a self-contained page: summary, profiles, a table per
    /// implementation, each failure with its picture, counterexample and the command that
    /// reproduces it, a matrix when several are certified) and the counterexample pictures
    /// (`merge` links those its shards wrote).
    #[arg(long, value_name = "DIR", default_value = "refrast-report")]
    pub report: PathBuf,
    /// Also write the report as JSON: the run's metadata and one entry per implementation
    /// (docs/json.md gives the schema).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Also write the report as JUnit XML, a testsuite per implementation and a testcase per
    /// rule, for a CI's test tab (under --expect, expected verdicts are skipped testcases).
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Judge the verdicts against an expectation file (docs/expectations.md; repeatable): exit
    /// 0 when every verdict is as expected, 1 on an unexpected failure or an unexpected pass.
    #[arg(long, value_name = "FILE")]
    pub expect: Vec<PathBuf>,
}

impl Outputs {
    /// The outputs `args` ask for, with `update` for `--update-expectations`; reads the
    /// expectation files, and `Err` names the file and line to fix.
    pub fn new(args: &OutputArgs, update: Option<PathBuf>) -> Result<Self, String> {
        let expect = if args.expect.is_empty() {
            None
        } else {
            Some(Expectations::load(&args.expect)?)
        };
        Ok(Self {
            report: args.report.clone(),
            json: args.json.clone(),
            junit: args.junit.clone(),
            expect,
            update,
        })
    }

    /// Warnings for expectation files taken at other options than `options`.
    #[must_use]
    pub fn warnings(&self, options: &Options) -> Vec<String> {
        self.expect
            .as_ref()
            .map(|e| e.warnings(&Taken::of(options)))
            .unwrap_or_default()
    }
}

/// Writes every output `outputs` asks for and says which; returns the run's exit code: 2 when
/// an output could not be written, else under expectations 1 on any surprise, and without
/// them 1 when anything failed.
pub fn write_outputs(doc: &Document, rules: &[Rule], outputs: &Outputs) -> ExitCode {
    let mut failed_to_write = false;
    let mut wrote = |what: Result<PathBuf, String>| match what {
        Ok(path) => say(&format!("wrote {}", path.display())),
        Err(e) => {
            eprintln!("error: {e}");
            failed_to_write = true;
        }
    };
    let page = html::Page { doc, rules };
    wrote(html::write(&outputs.report, &page).map_err(|e| {
        format!(
            "could not write {}: {e}",
            outputs.report.join("index.html").display()
        )
    }));
    if let Some(path) = &outputs.json {
        wrote(doc.save(path).map(|()| path.clone()));
    }
    if let Some(path) = &outputs.junit {
        let xml = junit::junit(doc, outputs.expect.as_ref());
        wrote(
            std::fs::write(path, xml)
                .map(|()| path.clone())
                .map_err(|e| format!("could not write {}: {e}", path.display())),
        );
    }
    if let Some(path) = &outputs.update {
        wrote(update(doc, outputs, path));
    }
    let surprised = outputs.expect.as_ref().map(|e| judge(doc, e));
    if failed_to_write {
        return ExitCode::from(2);
    }
    let failed = match surprised {
        Some(surprised) => surprised,
        None => !doc.implementations.iter().all(super::Entry::passed),
    };
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Prints every verdict the expectations do not accept; whether there was any (an
/// implementation that failed to start, was refused or was not available is always one).
fn judge(doc: &Document, expect: &Expectations) -> bool {
    let mut mismatches: Vec<Mismatch> = Vec::new();
    let mut other: Vec<String> = Vec::new();
    let mut expected_failures = 0;
    let mut judged = 0;
    for entry in &doc.implementations {
        let name = entry.subject.name();
        match &entry.outcome {
            Outcome::Certified(report) if report.refused.is_some() => {
                other.push(format!(
                    "REFUSED: {name}: {}",
                    report.refused.as_deref().unwrap_or("")
                ));
            }
            Outcome::Certified(report) => {
                judged += report.rules.len();
                let found = expect.check(name, report);
                expected_failures += report
                    .rules
                    .iter()
                    .filter(|r| r.status.is_failure() && !found.iter().any(|m| m.rule == r.id))
                    .count();
                if expect.section(name).is_none() {
                    say(&format!(
                        "expectations: no section [{name}]: every rule of it is expected to pass"
                    ));
                }
                mismatches.extend(found);
            }
            Outcome::FailedToStart { failed_to_start, .. } => {
                other.push(format!("FAILED TO START: {name}: {failed_to_start}"));
            }
            Outcome::Skipped { skipped, .. } => {
                other.push(format!("NOT AVAILABLE: {name}: {skipped}"));
            }
        }
    }
    if mismatches.is_empty() && other.is_empty() {
        say(&format!(
            "expectations: every verdict as expected ({judged} rules judged, {expected_failures} expected failures)"
        ));
        return false;
    }
    say(&format!(
        "expectations: {} not as expected (docs/expectations.md):",
        mismatches.len() + other.len()
    ));
    for line in other {
        say(&format!("  {line}"));
    }
    for m in &mismatches {
        say(&format!("  {m}"));
    }
    say("  a fix or a new finding? check it, then --update-expectations FILE writes what this run saw");
    true
}

/// Writes the verdicts seen to `path`, keeping what still holds of the file there and of the
/// `--expect` files.
fn update(doc: &Document, outputs: &Outputs, path: &PathBuf) -> Result<PathBuf, String> {
    let mut old = outputs.expect.clone().unwrap_or_default();
    if path.exists() && !doc.run.options.expect.contains(path) {
        let there = Expectations::load(std::slice::from_ref(path))?;
        for section in there.sections {
            if old.section(&section.name).is_none() {
                old.sections.push(section);
            }
        }
    }
    let seen: Vec<(&str, &refrast_conformance::Report)> = doc
        .implementations
        .iter()
        .filter_map(|e| {
            e.report()
                .filter(|r| r.refused.is_none())
                .map(|r| (e.subject.name(), r))
        })
        .collect();
    let o = &doc.run.options;
    let taken = Taken {
        cases: o.cases,
        seed: o.seed,
        scale: o.scale,
        budget: o.budget,
    };
    std::fs::write(path, expect::write(&old, &taken, &seen))
        .map(|()| path.clone())
        .map_err(|e| format!("could not write {}: {e}", path.display()))
}
