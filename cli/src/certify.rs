//! `refrast certify`: run the catalogue against built-in implementations, print, write reports.

use std::path::PathBuf;
use std::process::{Command, ExitCode};
use std::time::{Duration, Instant};

use refrast_conformance::isolate::certify_isolated;
use refrast_conformance::{
    BuiltIn, Options, Process, Report, RuleReport, Status, Unavailable, catalogue, matches,
};
use serde::Serialize;

use crate::{all_builtins, say};

/// Arguments of `refrast certify`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Implementation to certify (repeatable; see `refrast impls`) [default: every correct
    /// built-in, unless --exec is given].
    #[arg(long = "impl", value_name = "NAME")]
    impls: Vec<String>,
    /// A rasterizer in any language to certify: the command that starts it, speaking the pipe
    /// protocol of PROTOCOL.md (repeatable; certified after the --impl ones).
    #[arg(long = "exec", value_name = "CMD")]
    execs: Vec<String>,
    /// Seconds of wall time per rule after which no new case starts; the report says how many
    /// ran [default: 10 for --exec, none for built-ins].
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    budget: Option<f64>,
    /// Cases per rule [default: PROPTEST_CASES, else each rule's own].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    cases: Option<u32>,
    /// Multiply the cases per rule by N (nightly runs use 10).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=1000))]
    scale: u32,
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
    /// Seconds one case may take before the rule fails as hung (for --exec: one draw).
    #[arg(long, value_name = "SECONDS", default_value_t = refrast_conformance::DEFAULT_CASE_TIMEOUT.as_secs_f64(),
          value_parser = positive_seconds)]
    case_timeout: f64,
    /// Stop at the first failing rule: the rules and implementations after it are not run.
    #[arg(long)]
    fail_fast: bool,
    /// Run the rules in this process instead of one child process each (for a debugger or a
    /// profiler; a rasterizer that hangs or aborts then stops the whole run).
    #[arg(long)]
    in_process: bool,
}

/// A finite, positive number of seconds.
fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s.is_finite() && s > 0.0 => Ok(s),
        _ => Err(format!("'{text}' is not a positive number of seconds")),
    }
}

/// The time budget per rule of an --exec rasterizer unless --budget says otherwise: a Python
/// rasterizer gets through the catalogue in a few minutes.
const DEFAULT_EXEC_BUDGET: Duration = Duration::from_secs(10);

/// One implementation's entry in the JSON report.
#[derive(Serialize)]
#[serde(untagged)]
enum Entry {
    /// Certified: the report.
    Certified(Report),
    /// A child that could not be started or did not complete its handshake: a failure.
    FailedToStart {
        /// The command line.
        implementation: String,
        /// Why, with the end of its stderr.
        failed_to_start: String,
    },
    /// Not available on this machine, and why.
    Skipped {
        /// Its name.
        implementation: String,
        /// Why it was skipped.
        skipped: String,
    },
}

/// Runs `refrast certify`: 0 when every applicable rule passes, 1 when one fails, 2 on a usage error.
pub fn run(args: &Args) -> ExitCode {
    let chosen: Vec<BuiltIn> = if args.impls.is_empty() && !args.execs.is_empty() {
        Vec::new()
    } else if args.impls.is_empty() {
        all_builtins()
            .into_iter()
            .filter(|b| b.origin == refrast_conformance::Origin::Ours)
            .collect()
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
    for command in &args.execs {
        if let Err(e) = refrast_conformance::process::split_command(command) {
            eprintln!("error: --exec: {e}");
            return ExitCode::from(2);
        }
    }
    if let Some(pattern) = &args.rule
        && !catalogue().iter().any(|r| matches(pattern, r.id))
    {
        eprintln!("error: no rule matches '{pattern}'; `refrast rules` lists them");
        return ExitCode::from(2);
    }
    let options = Options {
        cases: args.cases,
        scale: args.scale,
        seed: args.seed,
        rule: args.rule.clone(),
        report_dir: Some(args.report.clone()),
        case_timeout: Duration::from_secs_f64(args.case_timeout),
        budget: args.budget.map(Duration::from_secs_f64),
        fail_fast: args.fail_fast,
        ..Options::default()
    };
    let exec_options = Options {
        budget: Some(options.budget.unwrap_or(DEFAULT_EXEC_BUDGET)),
        ..options.clone()
    };
    let jobs = chosen
        .iter()
        .map(|b| (b.name.clone(), Job::BuiltIn(b)))
        .chain(args.execs.iter().map(|c| (c.clone(), Job::Exec(c))));
    let mut reports = Vec::new();
    let mut left: Vec<String> = Vec::new();
    for (name, job) in jobs {
        if !left.is_empty() || reports.last().is_some_and(|e| args.fail_fast && !passed(e)) {
            left.push(name);
            continue;
        }
        reports.push(match job {
            Job::BuiltIn(b) => certify_one(b, &options, args.in_process),
            Job::Exec(command) => certify_exec(command, &exec_options),
        });
    }
    if !left.is_empty() {
        say(&format!("--fail-fast: not certified: {}", left.join(", ")));
    }
    if let Some(path) = &args.json {
        let json = serde_json::to_string_pretty(&reports).expect("reports serialise");
        if let Err(e) = std::fs::write(path, json) {
            eprintln!("error: could not write {}: {e}", path.display());
            return ExitCode::from(2);
        }
        say(&format!("wrote {}", path.display()));
    }
    if reports.iter().all(passed) {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// What to certify: a built-in, or a command speaking the pipe protocol.
enum Job<'a> {
    BuiltIn(&'a BuiltIn),
    Exec(&'a str),
}

/// Whether an entry counts as passed: certified with no failing rule, or skipped.
fn passed(entry: &Entry) -> bool {
    match entry {
        Entry::Certified(report) => report.passed(),
        Entry::FailedToStart { .. } => false,
        Entry::Skipped { .. } => true,
    }
}

/// Certifies one built-in, each rule in a child process unless `in_process`; skips it, saying
/// why, when it cannot be built here.
fn certify_one(b: &BuiltIn, options: &Options, in_process: bool) -> Entry {
    let skipped = |why: Unavailable| {
        say(&format!("== {}: SKIPPED: {why}\n", b.name));
        Entry::Skipped {
            implementation: b.name.clone(),
            skipped: why.to_string(),
        }
    };
    say(&format!("== {} (seed {})", b.name, options.seed));
    let start = Instant::now();
    let report = if in_process {
        match b.build() {
            Ok(mut r) => refrast_conformance::certify(r.as_mut(), options, print_rule),
            Err(why) => return skipped(why),
        }
    } else {
        // Each rule's process builds the implementation itself, in the environment it needs.
        let command = |rule: &refrast_conformance::Rule| {
            let mut command = run_rule_command(&b.name, rule.id, options);
            command.envs(b.env.iter().map(|(k, v)| (k, v)));
            command
        };
        match certify_isolated(&command, options, print_rule) {
            Ok(report) => report,
            Err(why) => return skipped(why),
        }
    };
    summarise(&report, start);
    Entry::Certified(report)
}

/// Certifies a rasterizer in a child process, started once and reused, in this process: the
/// [`Process`] turns a crash, a hang or garbage into a failed draw, and restarts the child.
fn certify_exec(command: &str, options: &Options) -> Entry {
    say(&format!("== {command} (seed {}, pipe protocol)", options.seed));
    let start = Instant::now();
    let mut process = match Process::try_spawn_with(command, options.case_timeout) {
        Ok(process) => process,
        Err(why) => {
            say(&format!("FAILED TO START: {why}\n"));
            return Entry::FailedToStart {
                implementation: command.to_owned(),
                failed_to_start: why.to_string(),
            };
        }
    };
    let report = refrast_conformance::certify(&mut process, options, print_rule);
    summarise(&report, start);
    if process.starts() > 1 {
        say(&format!(
            "  the child was restarted {} times after misbehaving\n",
            process.starts() - 1
        ));
    }
    Entry::Certified(report)
}

/// The closing lines of one implementation: tallies, time, profile.
fn summarise(report: &Report, start: Instant) {
    let p = &report.profile;
    let (pass, fail, na) = report.tally();
    say(&format!(
        "{}: {pass} passed, {fail} failed, {na} not applicable ({:.1} s); profile: {}, {}, depth {}, band {} px",
        p.name,
        start.elapsed().as_secs_f64(),
        p.snapping,
        p.fill,
        p.depth,
        p.band_px
    ));
    if !p.about.is_empty() {
        say(&format!("  reports itself as: {}", p.about));
    }
    say(&format!("  features: {}", p.features.join("; ")));
    if !report.not_run.is_empty() {
        say(&format!(
            "  --fail-fast: {} rules not run after the first failure: {}",
            report.not_run.len(),
            report.not_run.join(", ")
        ));
    }
    say("");
}

/// This program again, running one rule of one built-in (`refrast run-rule`).
fn run_rule_command(implementation: &str, rule: &str, options: &Options) -> Command {
    let exe = std::env::current_exe().unwrap_or_else(|_| PathBuf::from("refrast"));
    let mut command = Command::new(exe);
    command.args(["run-rule", "--impl", implementation, "--rule", rule]);
    command.args(["--seed", &options.seed.to_string()]);
    if let Some(cases) = options.cases {
        command.args(["--cases", &cases.to_string()]);
    }
    command.args(["--scale", &options.scale.to_string()]);
    if let Some(budget) = options.budget {
        command.args(["--budget", &budget.as_secs_f64().to_string()]);
    }
    if let Some(dir) = &options.report_dir {
        command.arg("--report").arg(dir);
    }
    command
}

/// Arguments of the hidden `refrast run-rule`, the child `certify` starts for each rule.
#[derive(clap::Args, Debug)]
pub struct RunRuleArgs {
    /// The built-in to run.
    #[arg(long = "impl", value_name = "NAME")]
    implementation: String,
    /// The rule's ID.
    #[arg(long, value_name = "ID")]
    rule: String,
    /// Cases [default: PROPTEST_CASES, else the rule's own].
    #[arg(long, value_name = "N")]
    cases: Option<u32>,
    /// Multiply the cases by N.
    #[arg(long, value_name = "N", default_value_t = 1)]
    scale: u32,
    /// Seed of the case generator.
    #[arg(long, value_name = "S", default_value_t = refrast_conformance::DEFAULT_SEED)]
    seed: u64,
    /// Folder for the counterexample picture.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// Seconds of wall time after which no new case starts.
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    budget: Option<f64>,
}

/// Runs `refrast run-rule`: one rule, spoken to the parent on stdout ([`refrast_conformance::isolate`]).
pub fn run_rule(args: &RunRuleArgs) -> ExitCode {
    let Some(b) = all_builtins().into_iter().find(|b| b.name == args.implementation) else {
        eprintln!("error: no implementation named '{}'", args.implementation);
        return ExitCode::from(2);
    };
    let options = Options {
        cases: args.cases,
        scale: args.scale,
        seed: args.seed,
        report_dir: args.report.clone(),
        budget: args.budget.map(Duration::from_secs_f64),
        ..Options::default()
    };
    if refrast_conformance::isolate::serve_rule(&args.rule, || b.build(), &options) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    }
}

fn print_rule(r: &RuleReport) {
    let cases = if r.budget_spent {
        format!("{:>6} of {} cases (time budget spent)", r.cases, r.planned)
    } else {
        format!("{:>6} cases", r.cases)
    };
    say(&format!(
        "{:<4}  {:<38} {:<9} {cases}",
        r.status.label(),
        r.id,
        r.kind,
    ));
    match r.status {
        Status::Pass => {}
        Status::NotApplicable => say(&format!(
            "      not applicable: {}",
            r.message.as_deref().unwrap_or("")
        )),
        Status::Fail => {
            say(&format!("      {}", r.message.as_deref().unwrap_or("")));
            for detail in r.details.iter().skip(1) {
                say(&format!("        {detail}"));
            }
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
