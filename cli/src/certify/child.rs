//! `refrast run-rule`, the child `certify` starts for each rule of a built-in, and the command
//! that starts it.

use std::path::PathBuf;
use std::process::{Command, ExitCode};
use std::time::Duration;

use refrast_conformance::Options;

use super::positive_seconds;

/// This program again, running one rule of one built-in (`refrast run-rule`).
pub(super) fn run_rule_command(implementation: &str, rule: &str, options: &Options) -> Command {
    let mut command = this_program();
    command.args(["run-rule", "--impl", implementation, "--rule", rule]);
    command.args(["--seed", &options.seed.to_string()]);
    if let Some(cases) = options.cases {
        command.args(["--cases", &cases.to_string()]);
    }
    command.args(["--scale", &options.scale.to_string()]);
    if let Some(budget) = options.budget {
        command.args(["--budget", &budget.as_secs_f64().to_string()]);
    }
    command
}

/// This program, for a child that builds a built-in: with a runtime folder for the drivers
/// when this process has none, so that Mesa's EGL does not print `XDG_RUNTIME_DIR is invalid`
/// into every failure message.
pub fn this_program() -> Command {
    let exe = std::env::current_exe().unwrap_or_else(|_| PathBuf::from("refrast"));
    let mut command = Command::new(exe);
    if let Some(dir) = runtime_dir() {
        command.env("XDG_RUNTIME_DIR", dir);
    }
    command
}

/// A private runtime folder (mode 0700, in the temporary folder) when `XDG_RUNTIME_DIR` is
/// unset or names no folder; `None` when it is fine or none can be made.
fn runtime_dir() -> Option<PathBuf> {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| std::path::Path::new(&d).is_dir()) {
        return None;
    }
    let dir = std::env::temp_dir().join(format!("refrast-runtime-{}", user()));
    let mut builder = std::fs::DirBuilder::new();
    builder.recursive(true);
    #[cfg(unix)]
    std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
    builder.create(&dir).ok()?;
    Some(dir)
}

/// Who runs this, for a per-user folder name.
fn user() -> String {
    std::env::var("USER")
        .or_else(|_| std::env::var("LOGNAME"))
        .unwrap_or_else(|_| "user".to_owned())
        .chars()
        .filter(char::is_ascii_alphanumeric)
        .collect()
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
    /// Seconds of wall time after which no new case starts.
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    budget: Option<f64>,
}

/// Runs `refrast run-rule`: one rule, spoken to the parent on stdout ([`refrast_conformance::isolate`]).
pub fn run_rule(args: &RunRuleArgs) -> ExitCode {
    let Some(b) = refrast_registry::all()
        .into_iter()
        .find(|b| b.name == args.implementation)
    else {
        eprintln!("error: no implementation named '{}'", args.implementation);
        return ExitCode::from(2);
    };
    let options = Options {
        cases: args.cases,
        scale: args.scale,
        seed: args.seed,
        budget: args.budget.map(Duration::from_secs_f64),
        ..Options::default()
    };
    if refrast_conformance::isolate::serve_rule(&args.rule, || b.build(), &options) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    }
}
