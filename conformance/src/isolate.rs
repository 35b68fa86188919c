//! Rules run in child processes, so that a rasterizer that hangs, aborts or crashes fails the
//! rule it was running, with a message, and the run goes on.
//!
//! The parent starts one child per rule (a command the caller builds: `refrast run-rule …`, or
//! the test binary itself for [`crate::run_as_tests`]). The child builds the rasterizer, runs
//! the rule with [`serve_rule`] and speaks one JSON object a line on its stdout, each after
//! [`MARK`]: its profile (or why it cannot be built here), then the report. Every case is
//! counted in a case log (`isolate/case_log.rs`) before it is checked (or, in a child started
//! without one, sent as a line with its text); a child that stops without a report is run
//! again to write the text of the case it stopped on (`isolate/watch.rs`). Lines without the
//! mark are the rasterizer's own output and are kept for
//! the failure message. Building in the child means an implementation that needs its own
//! environment (a driver chosen by an environment variable) gets it there.
//!
//! The parent gives each case [`Options::case_timeout`]: a child that starts no case for longer
//! is killed and the rule fails as hung, on the last case it announced. A child that exits without a report
//! failed the same way, with its exit status or signal and the end of its stderr.

use std::io::Write;
use std::process::{Command, Stdio};
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::Duration;

use refrast::{Rasterizer, Unavailable};
use serde::{Deserialize, Serialize};

mod case_log;
mod watch;

use case_log::{CASE_LOG_ENV, CaseLog};
use watch::{Outcome, Watch};

use crate::certify::{refusal, run_selected_jobs};
use crate::judge::{Options, cases_for, run_rule};
use crate::report::{Exhibit, ProfileReport, Report, RuleReport, Status};
use crate::rules::{Rule, catalogue};

/// The prefix of every protocol line on the child's stdout.
pub const MARK: &str = "@refrast-rule ";

/// The longest line read from a child: a report with its details fits many times over; a
/// longer line is cut, so a child printing without newlines cannot fill refrast's memory.
const MAX_LINE: usize = 16 << 20;

/// How long a child that has sent its report, or closed its stdout, may take to exit before it
/// is killed (with its process group).
const EXIT_GRACE: Duration = Duration::from_secs(5);

/// One line from a child.
#[derive(Debug, Serialize, Deserialize)]
enum Message {
    /// The rasterizer's profile, once built.
    Profile(Box<ProfileReport>),
    /// Why the rasterizer cannot be built in this process.
    Unavailable(String),
    /// Why the suite refuses to judge the rasterizer's profile ([`crate::refusal`]).
    Refused(String),
    /// The input about to be checked, as Rust, from a child without a case log.
    Case(String),
    /// The rule's outcome, with its exhibit (which the report's JSON leaves out) beside it.
    Report(Box<RuleReport>, Option<Box<Exhibit>>),
}

/// Writes one protocol line to stdout.
fn send(message: &Message) {
    let line = serde_json::to_string(message).unwrap_or_default();
    let mut out = std::io::stdout().lock();
    // A parent that stopped listening has killed us or is about to: nothing to do on failure.
    let _ = writeln!(out, "{MARK}{line}").and_then(|()| out.flush());
}

/// Announces an input to the parent: in the case log, or as a line where there is none.
fn announce(input: &dyn std::fmt::Debug) {
    if !case_log::write(input) {
        send(&Message::Case(format!("{input:?}")));
    }
}

/// Child side: builds the rasterizer and runs rule `id` against it, announcing its profile and
/// every case, and writes the report. Returns `false` when no rule has that ID (after saying
/// so on stderr).
pub fn serve_rule(
    id: &str,
    build: impl FnOnce() -> Result<Box<dyn Rasterizer>, Unavailable>,
    options: &Options,
) -> bool {
    let Some(rule) = catalogue().into_iter().find(|r| r.id == id) else {
        eprintln!("error: no rule with ID '{id}'; `refrast rules` lists them");
        return false;
    };
    let mut rasterizer = match build() {
        Ok(r) => r,
        Err(why) => {
            send(&Message::Unavailable(why.0));
            return true;
        }
    };
    send(&Message::Profile(Box::new(ProfileReport::of(
        rasterizer.as_ref(),
    ))));
    if let Some(why) = refusal(rasterizer.as_ref()) {
        send(&Message::Refused(why));
        return true;
    }
    let options = Options {
        announce: Some(announce),
        ..options.clone()
    };
    let mut report = run_rule(&rule, rasterizer.as_mut(), &options);
    let exhibit = report.exhibit.take().map(Box::new);
    send(&Message::Report(Box::new(report), exhibit));
    true
}

/// How one rule went in its child.
#[derive(Debug)]
pub enum ChildRun {
    /// The rule ran (or found it does not apply), with the profile the child reported.
    Ran(Box<RuleReport>, Option<Box<ProfileReport>>),
    /// The rasterizer cannot be built where the child runs.
    Unavailable(Unavailable),
    /// The suite cannot judge the rasterizer's profile: what to declare instead.
    Refused(String, Option<Box<ProfileReport>>),
}

/// Parent side: certifies the implementation the children build, each rule in a child started
/// by `command(rule)`, calling `progress` after each rule. `Err` when the first child says it
/// cannot build the implementation here.
pub fn certify_isolated(
    command: &(dyn Fn(&Rule) -> Command + Sync),
    options: &Options,
    progress: impl FnMut(&mut RuleReport) + Send,
) -> Result<Report, Unavailable> {
    certify_isolated_jobs(command, options, 1, progress)
}

/// [`certify_isolated`] with up to `jobs` rules' children running at once: the same report
/// but for times (a rasterizer whose children share a device may want 1).
pub fn certify_isolated_jobs(
    command: &(dyn Fn(&Rule) -> Command + Sync),
    options: &Options,
    jobs: usize,
    progress: impl FnMut(&mut RuleReport) + Send,
) -> Result<Report, Unavailable> {
    let profile = Mutex::new(None);
    let refused = Mutex::new(None);
    let progress = Mutex::new(progress);
    let ran = run_selected_jobs(options, jobs, |_, rule| {
        match run_rule_isolated(rule, command(rule), options) {
            ChildRun::Unavailable(why) => Err(Stop::Unavailable(why)),
            ChildRun::Refused(why, reported) => {
                *lock(&profile) = reported;
                *lock(&refused) = Some(why);
                Err(Stop::Refused)
            }
            ChildRun::Ran(mut report, reported) => {
                let mut profile = lock(&profile);
                *profile = profile.take().or(reported);
                drop(profile);
                (lock(&progress))(&mut report);
                Ok(*report)
            }
        }
    });
    let (rules, not_run) = match ran {
        Ok(ran) => ran,
        Err(Stop::Unavailable(why)) => return Err(why),
        Err(Stop::Refused) => (Vec::new(), Vec::new()),
    };
    let profile = lock(&profile).take().map_or_else(ProfileReport::unknown, |p| *p);
    Ok(Report {
        implementation: profile.name.clone(),
        profile,
        rules,
        not_run,
        refused: lock(&refused).take(),
    })
}

/// `m`'s value, even after a thread panicked holding it (each holder leaves it whole).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Why [`certify_isolated`] stops before the last rule.
enum Stop {
    Unavailable(Unavailable),
    Refused,
}

/// Runs one rule in a child started by `command`; a hang is a `timeout`, a child that dies
/// without a report a `crash`.
pub fn run_rule_isolated(rule: &Rule, command: Command, options: &Options) -> ChildRun {
    run_rule_watched(rule, command, options, &mut |_| {})
}

/// [`run_rule_isolated`], calling `on_case` with the count of inputs the child has announced
/// so far (shrinking's included) as it polls them: for a progress display.
pub fn run_rule_watched(
    rule: &Rule,
    mut command: Command,
    options: &Options,
    on_case: &mut dyn FnMut(usize),
) -> ChildRun {
    let mut watch = Watch::new(rule, options);
    let program = format!("{:?}", command.get_program());
    // Without a log (the temp directory unwritable) the child announces each case as a line.
    let log = CaseLog::new().ok();
    if let Some(log) = &log {
        command.env(CASE_LOG_ENV, log.path());
    }
    command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .stdin(Stdio::null());
    match watch.follow(&mut command, log.as_ref(), on_case, None) {
        Outcome::Said(run) => run,
        Outcome::NotStarted(e) => watch.failed(
            Status::Crash,
            format!("could not start the rule's process {program}: {e}"),
        ),
        Outcome::Stopped(stopped, output) => watch.stopped(&stopped, &output, &mut command, log.as_ref()),
    }
}

/// A report of `rule` with nothing run yet.
fn blank(rule: &Rule, options: &Options, tolerance_subpixels: u32) -> RuleReport {
    RuleReport {
        planned: cases_for(rule, options),
        ..RuleReport::new(rule, options.seed, tolerance_subpixels)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certify::{run_selected, selected};

    /// Rule `i`'s outcome in a scripted run: every fifth fails, and the 23rd is an error.
    fn scripted(rule: &Rule, options: &Options) -> Result<RuleReport, String> {
        let i = selected(options)
            .iter()
            .position(|r| r.id == rule.id)
            .unwrap_or(0);
        if i == 23 {
            return Err(format!("error at {}", rule.id));
        }
        let mut report = blank(rule, options, 1);
        if i % 5 == 4 {
            report.status = Status::Fail;
        }
        Ok(report)
    }

    /// Reports, order, unrun rules and errors are those of one rule at a time, whatever the
    /// number of jobs: with and without fail-fast, with and without an error in the run.
    #[test]
    fn jobs_change_nothing_but_times() {
        let summary = |r: Result<(Vec<RuleReport>, Vec<String>), String>| {
            r.map(|(reports, left)| {
                (
                    reports
                        .iter()
                        .map(|r| (r.id.clone(), r.status))
                        .collect::<Vec<_>>(),
                    left,
                )
            })
        };
        for fail_fast in [false, true] {
            for rules in [vec![], vec!["fill.*".to_owned(), "depth.*".to_owned()]] {
                let options = Options {
                    fail_fast,
                    rules,
                    ..Options::default()
                };
                let one = summary(run_selected(&options, |rule| scripted(rule, &options)));
                for jobs in [1, 2, 3, 8, 100] {
                    let many = summary(run_selected_jobs(&options, jobs, |_, rule| {
                        scripted(rule, &options)
                    }));
                    assert_eq!(many, one, "jobs {jobs}, fail-fast {fail_fast}");
                }
            }
        }
    }
}
