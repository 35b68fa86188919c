//! `refrast certify`: run the catalogue against built-in implementations, print, write reports.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use refrast_conformance::{BuiltIn, Options, Report, RuleReport, Status, catalogue, matches};

use crate::{all_builtins, say};

/// Arguments of `refrast certify`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Implementation to certify (repeatable; see `refrast impls`) [default: every correct built-in].
    #[arg(long = "impl", value_name = "NAME")]
    impls: Vec<String>,
    /// Cases per rule [default: PROPTEST_CASES, else each rule's own].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    cases: Option<u32>,
    /// Seed of the case generator.
    #[arg(long, value_name = "S", default_value_t = refrast_conformance::DEFAULT_SEED)]
    seed: u64,
    /// Only rules matching this glob (`fill.*`, `*.exact`); without `*`, a prefix.
    #[arg(long, value_name = "PATTERN")]
    rule: Option<String>,
    /// Folder for counterexample pictures.
    #[arg(long, value_name = "DIR", default_value = "refrast-report")]
    report: PathBuf,
    /// Also write the report as JSON (an array, one entry per implementation).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

/// Runs `refrast certify`: 0 when every applicable rule passes, 1 when one fails, 2 on a usage error.
pub fn run(args: &Args) -> ExitCode {
    let chosen: Vec<BuiltIn> = if args.impls.is_empty() {
        all_builtins().into_iter().filter(|b| b.correct).collect()
    } else {
        let mut chosen = Vec::new();
        for name in &args.impls {
            match all_builtins().into_iter().find(|b| &b.name == name) {
                Some(b) => chosen.push(b),
                None => {
                    let names: Vec<_> = all_builtins().into_iter().map(|b| b.name).collect();
                    eprintln!(
                        "error: no implementation named '{name}'; the built-ins are: {}",
                        names.join(", ")
                    );
                    return ExitCode::from(2);
                }
            }
        }
        chosen
    };
    if let Some(pattern) = &args.rule
        && !catalogue().iter().any(|r| matches(pattern, r.id))
    {
        eprintln!("error: no rule matches '{pattern}'; `refrast rules` lists them");
        return ExitCode::from(2);
    }
    let options = Options {
        cases: args.cases,
        seed: args.seed,
        rule: args.rule.clone(),
        report_dir: Some(args.report.clone()),
    };
    let mut reports = Vec::new();
    for b in &chosen {
        reports.push(certify_one(b, &options));
    }
    if let Some(path) = &args.json {
        let json = serde_json::to_string_pretty(&reports).expect("reports serialise");
        if let Err(e) = std::fs::write(path, json) {
            eprintln!("error: could not write {}: {e}", path.display());
            return ExitCode::from(2);
        }
        say(&format!("wrote {}", path.display()));
    }
    if reports.iter().all(Report::passed) {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn certify_one(b: &BuiltIn, options: &Options) -> Report {
    let mut rasterizer = (b.make)();
    let p = rasterizer.profile();
    say(&format!(
        "== {}: {}, {}, depth {:?}, band {} px, seed {}",
        p.name,
        p.snapping,
        refrast_conformance::fill_name(p.fill),
        p.depth,
        p.band_px(),
        options.seed
    ));
    let start = Instant::now();
    let report = refrast_conformance::certify(rasterizer.as_mut(), options, print_rule);
    let (pass, fail, na) = report.tally();
    say(&format!(
        "{}: {pass} passed, {fail} failed, {na} not applicable ({:.1} s)\n",
        p.name,
        start.elapsed().as_secs_f64()
    ));
    report
}

fn print_rule(r: &RuleReport) {
    say(&format!(
        "{:<4}  {:<38} {:<9} {:>6} cases",
        r.status.label(),
        r.id,
        r.kind,
        r.cases
    ));
    match r.status {
        Status::Pass => {}
        Status::NotApplicable => say(&format!(
            "      not applicable: {}",
            r.message.as_deref().unwrap_or("")
        )),
        Status::Fail => {
            say(&format!("      {}", r.message.as_deref().unwrap_or("")));
            if let Some(p) = &r.picture {
                say(&format!("      picture: {}", p.display()));
            }
            if let Some(input) = &r.counterexample {
                say("      shrunk counterexample (after use refrast::*; use refrast_conformance::*;):");
                for line in input.lines() {
                    say(&format!("        {line}"));
                }
            }
        }
    }
}
