//! `refrast run-rule`, the child `certify` starts for each rule of a built-in, and the command
//! that starts it.

use std::path::PathBuf;
use std::process::{Command, ExitCode};
use std::time::Duration;

use refrast_conformance::Options;

use super::positive_seconds;
use crate::all_builtins;

/// This program again, running one rule of one built-in (`refrast run-rule`).
pub(super) fn run_rule_command(implementation: &str, rule: &str, options: &Options) -> Command {
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
