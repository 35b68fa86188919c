//! `refrast certify`: run the catalogue against built-in implementations, print, write reports.

mod child;
mod lines;
mod progress;
mod run;
mod schedule;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Instant, SystemTime};

use refrast::Rasterizer;

use refrast_conformance::{Options, Report, RuleReport, catalogue, matches, selected};
use refrast_pipe::Process;

pub use child::{RunRuleArgs, run_rule, this_program};
pub use lines::{plural, print_rule, reach, rule_lines, summarise};
use progress::Progress;
pub use run::RunArgs;

use crate::results::outputs::{OutputArgs, Outputs, write_outputs};
use crate::results::{DEFAULT_EXEC_BUDGET, Document, Entry, Host, Outcome, Run, SCHEMA_VERSION, Subject};
use refrast_registry::{BuiltIn, Origin};

use crate::say;

/// The built-ins `pattern` names: one by its name, or every one a glob with `*` matches (in
/// `refrast impls` order); an error that lists the names when none is found.
fn find_builtins(pattern: &str) -> Result<Vec<BuiltIn>, String> {
    if !pattern.contains('*') {
        return refrast_registry::find(pattern).map(|b| vec![b]);
    }
    let found: Vec<BuiltIn> = refrast_registry::all()
        .into_iter()
        .filter(|b| matches(pattern, &b.name))
        .collect();
    if found.is_empty() {
        return Err(format!(
            "no implementation's name matches '{pattern}'; `refrast impls` lists them"
        ));
    }
    Ok(found)
}

/// Arguments of `refrast certify`.
#[derive(clap::Args, Debug)]
pub struct CertifyArgs {
    /// Implementation to certify (repeatable; see `refrast impls`), or a glob of their names
    /// (`'restricted:*'`, `'mutant:*'`) [default: every correct built-in, unless --exec is given].
    #[arg(long = "impl", value_name = "NAME")]
    impls: Vec<String>,
    /// A rasterizer in any language to certify: the command that starts it, speaking the pipe
    /// protocol of docs/protocol.md (repeatable; certified after the --impl ones).
    #[arg(long = "exec", value_name = "CMD")]
    execs: Vec<String>,
    /// How the run goes: cases, seed, rules, limits, jobs.
    #[command(flatten)]
    pub run: RunArgs,
    /// Where its results go.
    #[command(flatten)]
    pub outputs: OutputArgs,
    /// Write the verdicts seen to FILE as expectations (keeping the comments and the may-fail
    /// lines of FILE, or of --expect, that still hold).
    #[arg(long, value_name = "FILE")]
    update_expectations: Option<PathBuf>,
}

/// A finite, positive number of seconds.
pub fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s.is_finite() && s > 0.0 => Ok(s),
        _ => Err(format!("'{text}' is not a positive number of seconds")),
    }
}

/// Runs `refrast certify`: 0 when every applicable rule passes (under --expect: when every
/// verdict is as expected), 1 when one fails (or surprises), 2 on a usage error.
pub fn run(args: &CertifyArgs) -> ExitCode {
    let when = SystemTime::now();
    let clock = Instant::now();
    let chosen = match choose(args) {
        Ok(chosen) => chosen,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let outputs = match Outputs::new(&args.outputs, args.update_expectations.clone()) {
        Ok(outputs) => outputs,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let options = args.run.options();
    let report = args.outputs.report.as_path();
    let exec_options = Options {
        budget: Some(options.budget.unwrap_or(DEFAULT_EXEC_BUDGET)),
        ..options.clone()
    };
    let jobs = args.run.jobs();
    for warning in outputs.warnings(&options) {
        eprintln!("{warning}");
    }
    let out = Progress::detect();
    let mut entries: Vec<Entry> = Vec::new();
    let mut left: Vec<String> = Vec::new();
    let stop = |entries: &[Entry], left: &[String]| {
        !left.is_empty() || entries.last().is_some_and(|e| args.run.fail_fast && !e.passed())
    };
    if args.run.in_process {
        for b in &chosen {
            if stop(&entries, &left) {
                left.push(b.name.clone());
            } else {
                entries.push(Entry {
                    subject: Subject::BuiltIn(b.name.clone()),
                    outcome: certify_in_process(b, &options, report, &out),
                });
            }
        }
    } else {
        (entries, left) = schedule::certify_builtins(&chosen, &options, report, jobs, &out);
    }
    for command in &args.execs {
        if stop(&entries, &left) {
            left.push(command.clone());
        } else {
            entries.push(Entry {
                subject: Subject::Exec(command.clone()),
                outcome: certify_exec(command, &exec_options, report, jobs, &out),
            });
        }
    }
    out.clear();
    if !left.is_empty() {
        say(&format!("--fail-fast: not certified: {}", left.join(", ")));
    }
    let unavailable: Vec<&str> = entries
        .iter()
        .filter(|e| matches!(e.outcome, Outcome::Skipped { .. }))
        .map(|e| e.subject.name())
        .collect();
    if !unavailable.is_empty() {
        say(&format!(
            "not certified, unavailable on this machine (the SKIPPED lines above say what is missing): {}",
            unavailable.join(", ")
        ));
    }
    let doc = Document {
        schema_version: SCHEMA_VERSION,
        run: Run {
            refrast_version: env!("CARGO_PKG_VERSION").to_owned(),
            git_revision: crate::results::git_revision().to_owned(),
            started: crate::results::rfc3339(when),
            seconds: clock.elapsed().as_secs_f64(),
            host: Host::this(),
            command: std::env::args_os()
                .map(|a| a.to_string_lossy().into_owned())
                .collect(),
            options: args.run.recorded(&args.outputs.expect),
        },
        implementations: entries,
        not_certified: left,
    };
    write_outputs(&doc, &selected(&options), &outputs)
}

/// The built-ins `--impl` names (every correct one when none is named and no `--exec` is
/// given), after checking `--exec` command lines and `--rule` patterns.
fn choose(args: &CertifyArgs) -> Result<Vec<BuiltIn>, String> {
    for command in &args.execs {
        refrast_pipe::split_command(command).map_err(|e| format!("--exec: {e}"))?;
    }
    for pattern in &args.run.rule {
        if !catalogue().iter().any(|r| matches(pattern, r.id)) {
            return Err(format!("no rule matches '{pattern}'; `refrast rules` lists them"));
        }
    }
    if args.impls.is_empty() && !args.execs.is_empty() {
        return Ok(Vec::new());
    }
    if args.impls.is_empty() {
        return Ok(refrast_registry::all()
            .into_iter()
            .filter(|b| b.origin == Origin::Ours)
            .collect());
    }
    let mut chosen = Vec::new();
    for name in &args.impls {
        chosen.extend(find_builtins(name)?);
    }
    Ok(chosen)
}

/// Certifies one built-in in this process, one rule after another, each failure's files
/// written into `report`; skips it, saying why, when it cannot be built here.
fn certify_in_process(b: &BuiltIn, options: &Options, report: &Path, out: &Progress) -> Outcome {
    out.line(&format!("== {} (seed {})", b.name, options.seed));
    let start = Instant::now();
    let mut rasterizer = match b.build() {
        Ok(r) => r,
        Err(why) => {
            out.line(&format!("== {}: SKIPPED: {why}\n", b.name));
            return Outcome::Skipped {
                implementation: b.name.clone(),
                skipped: why.to_string(),
            };
        }
    };
    let report = one_at_a_time(&b.name, false, options, report, out, |progress| {
        refrast_conformance::certify(rasterizer.as_mut(), options, progress)
    });
    summarise(out, &report, start.elapsed().as_secs_f64());
    Outcome::Certified(Box::new(report))
}

/// Certifies a rasterizer in child processes, `jobs` of them (one rule at a time each), each
/// started once and reused: the [`Process`] turns a crash, a hang or garbage into a failed
/// draw, and restarts its child. Each failure's files are written into `report`.
fn certify_exec(command: &str, options: &Options, report: &Path, jobs: usize, out: &Progress) -> Outcome {
    out.line(&format!("== {command} (seed {}, pipe protocol)", options.seed));
    let start = Instant::now();
    let spawn = || Process::try_spawn_limited(command, options.case_timeout, options.memory_limit);
    let mut children = match spawn() {
        Ok(process) => vec![process],
        Err(why) => {
            out.line(&format!("FAILED TO START: {why}\n"));
            return Outcome::FailedToStart {
                implementation: command.to_owned(),
                failed_to_start: why.to_string(),
            };
        }
    };
    // More children for the other jobs, each with the same handshake; one that does not start,
    // or declares another profile than the first, leaves the run with the children it has.
    while children.len() < jobs.min(selected(options).len()) {
        let why = match spawn() {
            Ok(process) if process.profile() == children[0].profile() => {
                children.push(process);
                continue;
            }
            Ok(_) => "declared another profile than the first".to_owned(),
            Err(why) => format!("did not start ({why})"),
        };
        let n = children.len();
        out.line(&format!("  child {} {why}: {n} at a time", n + 1));
        break;
    }
    let report = one_at_a_time(command, true, options, report, out, |progress| {
        refrast_conformance::certify_with(&mut children, options, progress)
    });
    summarise(out, &report, start.elapsed().as_secs_f64());
    let restarts: u32 = children.iter().map(|p| p.starts() - 1).sum();
    if restarts > 0 {
        out.line(&format!(
            "  the children were restarted {restarts} times after misbehaving\n"
        ));
    }
    Outcome::Certified(Box::new(report))
}

/// Writes a failure's files into `dir` ([`RuleReport::save_exhibit`]), warning when one cannot
/// be written: the verdict stands without its picture.
fn save_exhibit(report: &mut RuleReport, dir: &Path, out: &Progress) {
    if let Err(why) = report.save_exhibit(dir) {
        out.warn(&format!("warning: {why}"));
    }
}

/// Runs `certify` (which calls its argument after each rule) with a bar for `name` and a line
/// for the rule in flight, writing each failure's files into `dir` and printing each rule's
/// result.
fn one_at_a_time(
    name: &str,
    is_exec: bool,
    options: &Options,
    dir: &Path,
    out: &Progress,
    certify: impl FnOnce(&mut (dyn FnMut(&mut RuleReport) + Send)) -> Report,
) -> Report {
    let rules = selected(options);
    let bar = out.implementation(name, rules.len());
    let mut line = rules.first().map(|r| out.rule(name, r.id, 0));
    let mut done = 0;
    // Rules finish in any order on several children; they print in catalogue order, each as
    // soon as every rule before it has printed.
    let mut arrived: Vec<Option<RuleReport>> = vec![None; rules.len()];
    let mut printed = 0;
    let reach = reach(name, is_exec);
    let report = certify(&mut |report: &mut RuleReport| {
        save_exhibit(report, dir, out);
        match rules.iter().position(|r| r.id == report.id) {
            Some(i) => arrived[i] = Some(report.clone()),
            None => print_rule(out, report, &reach),
        }
        while let Some(next) = arrived.get_mut(printed).and_then(Option::take) {
            print_rule(out, &next, &reach);
            printed += 1;
        }
        bar.inc(1);
        done += 1;
        if let Some(line) = line.take() {
            out.done(&line);
        }
        line = rules.get(done).map(|r| out.rule(name, r.id, 0));
    });
    if let Some(line) = line {
        out.done(&line);
    }
    bar.finish_and_clear();
    report
}
