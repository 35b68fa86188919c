//! `refrast merge A.json B.json …`: the shards of one run (`certify --shard I/N`) joined into
//! the report the run would have made in one piece, times aside.

use std::path::PathBuf;
use std::process::ExitCode;

use refrast_conformance::{Report, catalogue};

use super::outputs::{OutputArgs, Outputs, write_outputs};
use super::{Document, Entry, Outcome};

/// The documents joined: implementations in order of first appearance, each one's rules in
/// catalogue order. `Err` when they are not parts of one run (other seeds, cases, rules, or
/// refrast) or when two hold the same rule of the same implementation.
pub fn merge(docs: &[(String, Document)]) -> Result<Document, String> {
    let Some((first_name, first)) = docs.first() else {
        return Err("nothing to merge: give the JSON reports of certify --shard".into());
    };
    let mut run = first.run.clone();
    for (name, doc) in &docs[1..] {
        let (a, b) = (&first.run.options, &doc.run.options);
        let differs = [
            (a.seed != b.seed, "seed"),
            (
                a.cases != b.cases || a.proptest_cases != b.proptest_cases,
                "cases",
            ),
            (a.scale != b.scale, "scale"),
            (a.rules != b.rules, "rules"),
            (a.budget != b.budget, "budget"),
            (
                a.case_timeout.to_bits() != b.case_timeout.to_bits(),
                "case timeout",
            ),
            (
                first.run.refrast_version != doc.run.refrast_version
                    || first.run.git_revision != doc.run.git_revision,
                "refrast",
            ),
        ];
        if let Some((_, what)) = differs.iter().find(|(d, _)| *d) {
            return Err(format!(
                "{name} and {first_name} differ in their {what}: they are not shards of one run"
            ));
        }
        run.seconds = run.seconds.max(doc.run.seconds);
        run.started = run.started.clone().min(doc.run.started.clone());
    }
    run.options.shard = None;
    run.command = std::iter::once("refrast merge".to_owned())
        .chain(docs.iter().map(|(n, _)| n.clone()))
        .collect();
    let mut implementations: Vec<Entry> = Vec::new();
    let mut not_certified: Vec<String> = Vec::new();
    for (name, doc) in docs {
        for entry in &doc.implementations {
            match implementations.iter_mut().find(|e| e.subject == entry.subject) {
                None => implementations.push(entry.clone()),
                Some(kept) => join(kept, entry, name)?,
            }
        }
        for left in &doc.not_certified {
            if !not_certified.contains(left) {
                not_certified.push(left.clone());
            }
        }
    }
    let order = catalogue();
    for entry in &mut implementations {
        if let Outcome::Certified(report) = &mut entry.outcome {
            report
                .rules
                .sort_by_key(|r| order.iter().position(|x| x.id == r.id).unwrap_or(usize::MAX));
            report
                .not_run
                .sort_by_key(|id| order.iter().position(|x| x.id == *id).unwrap_or(usize::MAX));
        }
    }
    Ok(Document {
        schema_version: first.schema_version,
        run,
        implementations,
        not_certified,
    })
}

/// Joins `more` (from the file `name`) into `kept`, an entry of the same subject.
fn join(kept: &mut Entry, more: &Entry, name: &str) -> Result<(), String> {
    match (&mut kept.outcome, &more.outcome) {
        (Outcome::Certified(a), Outcome::Certified(b)) => add_rules(a, b, name),
        // One shard could certify it and another not: what did not go well is kept.
        (Outcome::Certified(_), other @ (Outcome::FailedToStart { .. } | Outcome::Skipped { .. })) => {
            kept.outcome = other.clone();
            Ok(())
        }
        _ => Ok(()),
    }
}

/// Adds `b`'s rules to `a`; a rule in both is an error.
fn add_rules(a: &mut Report, b: &Report, name: &str) -> Result<(), String> {
    for r in &b.rules {
        if a.rules.iter().any(|x| x.id == r.id) {
            return Err(format!(
                "{name}: rule {} of {} is in another report too: were the shards' ranges the same?",
                r.id, a.implementation
            ));
        }
        a.rules.push(r.clone());
    }
    for id in &b.not_run {
        if !a.not_run.contains(id) {
            a.not_run.push(id.clone());
        }
    }
    if a.refused.is_none() {
        a.refused.clone_from(&b.refused);
    }
    Ok(())
}

/// Arguments of `refrast merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shards' `certify --json` reports.
    #[arg(required = true, value_name = "REPORT.json")]
    reports: Vec<PathBuf>,
    /// Where the merged results go.
    #[command(flatten)]
    outputs: OutputArgs,
}

/// Runs `refrast merge`: the exit code `certify` would have given the run in one piece; 2
/// when the reports cannot be read or are not shards of one run.
pub fn run(args: &MergeArgs) -> ExitCode {
    let mut docs = Vec::new();
    for path in &args.reports {
        match Document::load(path) {
            Ok(doc) => docs.push((path.display().to_string(), doc)),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    }
    let merged = match merge(&docs) {
        Ok(merged) => merged,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let outputs = match Outputs::new(&args.outputs, None) {
        Ok(outputs) => outputs,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    for entry in &merged.implementations {
        crate::say(&tally(entry));
    }
    let order = catalogue();
    let rules: Vec<_> =
        order
            .into_iter()
            .filter(|rule| {
                merged.implementations.iter().filter_map(Entry::report).any(|r| {
                    r.rules.iter().any(|x| x.id == rule.id) || r.not_run.iter().any(|x| x == rule.id)
                })
            })
            .collect();
    write_outputs(&merged, &rules, &outputs)
}

/// One implementation's closing line.
fn tally(entry: &Entry) -> String {
    let name = entry.subject.name();
    match &entry.outcome {
        Outcome::Certified(r) if r.refused.is_some() => format!("{name}: REFUSED"),
        Outcome::Certified(r) => {
            let (pass, fail, na) = r.tally();
            format!(
                "{name}: {pass} passed, {fail} failed, {} beyond the claimed specification, {na} not applicable",
                r.beyond_spec()
            )
        }
        Outcome::FailedToStart { .. } => format!("{name}: FAILED TO START"),
        Outcome::Skipped { skipped, .. } => format!("{name}: SKIPPED: {skipped}"),
    }
}
