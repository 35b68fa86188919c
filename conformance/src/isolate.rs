//! Rules run in child processes, so that a rasterizer that hangs, aborts or crashes fails the
//! rule it was running, with a message, and the run goes on.
//!
//! The parent starts one child per rule (a command the caller builds: `refrast run-rule …`, or
//! the test binary itself for [`crate::run_as_tests`]). The child builds the rasterizer, runs
//! the rule with [`serve_rule`] and speaks one JSON object a line on its stdout, each after
//! [`MARK`]: its profile (or why it cannot be built here), then the report. Every case is
//! written to a [`case_log`] before it is checked (or, in a child started without one, sent
//! as a line too). Lines without the mark are the rasterizer's own output and are kept for
//! the failure message. Building in the child means an implementation that needs its own
//! environment (a driver chosen by an environment variable) gets it there.
//!
//! The parent gives each case [`Options::case_timeout`]: a child that starts no case for longer
//! is killed and the rule fails as hung, on the last case it announced. A child that exits without a report
//! failed the same way, with its exit status or signal and the end of its stderr.

use std::io::{Read, Write};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::thread;
use std::time::{Duration, Instant};

use refrast::{Rasterizer, Unavailable};
use serde::{Deserialize, Serialize};

mod case_log;

use case_log::{CASE_LOG_ENV, CaseLog};

use crate::certify::{refusal, run_selected_jobs};
use crate::judge::{Options, cases_for, run_rule};
use crate::report::{Exhibit, ProfileReport, Report, RuleReport, Status};
use crate::rules::{Rule, catalogue};
use refrast_pipe::contain::{Contained, memory_note};
use refrast_pipe::{Tail, for_each_line, status_words};

/// The prefix of every protocol line on the child's stdout.
pub const MARK: &str = "@refrast-rule ";

/// The longest line read from a child: a report with its details fits many times over; a
/// longer line is cut, so a child printing without newlines cannot fill refrast's memory.
const MAX_LINE: usize = 16 << 20;

/// How long a child that has sent its report, or closed its stdout, may take to exit before it
/// is killed (with its process group).
const EXIT_GRACE: Duration = Duration::from_secs(5);

/// How often the parent reads a child's case log for progress: often enough for a progress
/// display, rarely enough to cost nothing beside a case.
const LOG_POLL: Duration = Duration::from_millis(100);

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

/// A report of `rule` with nothing run yet.
fn blank(rule: &Rule, options: &Options, tolerance_subpixels: u32) -> RuleReport {
    RuleReport {
        planned: cases_for(rule, options),
        ..RuleReport::new(rule, options.seed, tolerance_subpixels)
    }
}

/// What a child printed, as the reader thread passes it on.
enum Line {
    Message(Message),
    Other(String),
    Closed,
}

/// Runs one rule in a child started by `command`; a hang is a `timeout`, a child that dies
/// without a report a `crash`.
pub fn run_rule_isolated(rule: &Rule, command: Command, options: &Options) -> ChildRun {
    run_rule_watched(rule, command, options, &mut |_| {})
}

/// [`run_rule_isolated`], calling `on_case` with the count of inputs the child has announced
/// so far (shrinking's included) as each arrives: for a progress display.
pub fn run_rule_watched(
    rule: &Rule,
    mut command: Command,
    options: &Options,
    on_case: &mut dyn FnMut(usize),
) -> ChildRun {
    let mut watch = Watch {
        rule,
        options,
        started: Instant::now(),
        profile: None,
        last_case: None,
        cases_seen: 0,
    };
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
    let mut child = match Contained::spawn(&mut command, options.memory_limit) {
        Ok(child) => child,
        Err(e) => {
            return watch.failed(
                Status::Crash,
                format!("could not start the rule's process {program}: {e}"),
            );
        }
    };
    let stderr = child.child.stderr.take().map(collect_tail);
    let rx = child.child.stdout.take().map(read_lines);
    let mut own_output = Tail::default();
    let mut last_word = Instant::now();
    loop {
        let left = options.case_timeout.saturating_sub(last_word.elapsed());
        let wait = if log.is_some() { left.min(LOG_POLL) } else { left };
        let line = rx.as_ref().map_or(Ok(Line::Closed), |rx| rx.recv_timeout(wait));
        if let Some(count) = log.as_ref().map(CaseLog::count)
            && count != 0
            && count != watch.cases_seen
        {
            watch.cases_seen = count;
            on_case(usize::try_from(count).unwrap_or(usize::MAX));
            last_word = Instant::now();
        }
        match line {
            Ok(Line::Message(Message::Case(input))) => {
                watch.cases_seen += 1;
                on_case(usize::try_from(watch.cases_seen).unwrap_or(usize::MAX));
                watch.last_case = Some(input);
                last_word = Instant::now();
            }
            Ok(Line::Message(Message::Profile(reported))) => {
                watch.profile = Some(reported);
                last_word = Instant::now();
            }
            Ok(Line::Message(Message::Unavailable(why))) => {
                finish(&mut child);
                return ChildRun::Unavailable(Unavailable(why));
            }
            Ok(Line::Message(Message::Refused(why))) => {
                finish(&mut child);
                return ChildRun::Refused(why, watch.profile);
            }
            Ok(Line::Message(Message::Report(mut report, exhibit))) => {
                finish(&mut child);
                report.exhibit = exhibit.map(|e| *e);
                return ChildRun::Ran(report, watch.profile);
            }
            Ok(Line::Other(line)) => own_output.push(&line),
            Ok(Line::Closed) | Err(RecvTimeoutError::Disconnected) => {
                let status = finish(&mut child);
                watch.read(log.as_ref());
                let output = join_output(stderr, &own_output, options.memory_limit);
                let message = format!(
                    "the rasterizer's process ended without a verdict ({}) during case {}{output}",
                    describe(status),
                    watch.cases_seen
                );
                return watch.failed(Status::Crash, message);
            }
            Err(RecvTimeoutError::Timeout) if last_word.elapsed() < options.case_timeout => {}
            Err(RecvTimeoutError::Timeout) => {
                child.end();
                watch.read(log.as_ref());
                let output = join_output(stderr, &own_output, options.memory_limit);
                let message = format!(
                    "no answer within {} s on case {}: the rasterizer hangs on it (or is far too slow; \
                     --case-timeout sets the limit){output}",
                    options.case_timeout.as_secs_f64(),
                    watch.cases_seen
                );
                return watch.failed(Status::Timeout, message);
            }
        }
    }
}

/// What the parent has seen of a rule's child so far.
struct Watch<'a> {
    rule: &'a Rule,
    options: &'a Options,
    started: Instant,
    /// The profile the child reported, once it has.
    profile: Option<Box<ProfileReport>>,
    /// The last input it announced.
    last_case: Option<String>,
    /// How many inputs it announced (shrinking's included).
    cases_seen: u64,
}

impl Watch<'_> {
    /// Takes the count and the last input from the log of a child that is gone, where it
    /// wrote one (a child that could not open it announced its cases as lines).
    fn read(&mut self, log: Option<&CaseLog>) {
        if let Some(last) = log.and_then(CaseLog::last) {
            self.cases_seen = log.map_or(0, CaseLog::count);
            self.last_case = Some(last);
        }
    }

    /// The rule's report when the child gave none: `status`, `message`, the last case announced.
    fn failed(self, status: Status, message: String) -> ChildRun {
        let tolerance = self.profile.as_ref().map_or(1, |p| p.tolerance_subpixels.max(1));
        let report = RuleReport {
            status,
            // Announced inputs include shrinking's, so this may count more than were generated.
            cases: u32::try_from(self.cases_seen).unwrap_or(u32::MAX),
            message: Some(message),
            counterexample: self.last_case,
            seconds: self.started.elapsed().as_secs_f64(),
            ..blank(self.rule, self.options, tolerance)
        };
        ChildRun::Ran(Box::new(report), self.profile)
    }
}

/// The child's stdout, line by line, read on a thread of its own: protocol messages parsed,
/// anything else kept as its own output, then `Closed`. Bounded: the parent takes lines as they
/// come, and a flood waits for it.
fn read_lines(stdout: std::process::ChildStdout) -> mpsc::Receiver<Line> {
    let (tx, rx) = mpsc::sync_channel(64);
    thread::spawn(move || {
        for_each_line(stdout, MAX_LINE, |line, cut| {
            let line = String::from_utf8_lossy(line);
            let parsed = match line.strip_prefix(MARK) {
                Some(_) if cut => Line::Other(format!("(a protocol line longer than {MAX_LINE} bytes, cut)")),
                Some(json) => match serde_json::from_str(json) {
                    Ok(message) => Line::Message(message),
                    Err(e) => Line::Other(format!("(a garbled protocol line: {e})")),
                },
                None => Line::Other(line.into_owned()),
            };
            tx.send(parsed).is_ok()
        });
        let _ = tx.send(Line::Closed);
    });
    rx
}

/// Lets a child that is done exit, within [`EXIT_GRACE`], then ends it and its group; its exit
/// status when it exited on its own.
fn finish(child: &mut Contained) -> Option<ExitStatus> {
    child.wait_for(EXIT_GRACE);
    child.end()
}

/// An exit status in words: a code, or the signal that ended the process.
fn describe(status: Option<ExitStatus>) -> String {
    status.map_or_else(|| "exit status unknown".into(), status_words)
}

/// Reads a stream to its end on a thread of its own, keeping its tail.
fn collect_tail(stream: impl Read + Send + 'static) -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    thread::spawn(move || {
        let mut tail = Tail::default();
        for_each_line(stream, 2 * refrast_pipe::KEPT_OUTPUT, |line, _| {
            tail.push(&String::from_utf8_lossy(line));
            true
        });
        let _ = tx.send(tail.0);
    });
    rx
}

/// The child's stderr and stray stdout, ready to append to a message, with a note when the
/// stderr says it ran out of memory under `limit`. The child's group is gone, so stderr
/// closes; should something still hold it, what came within a second is not waited for.
fn join_output(stderr: Option<mpsc::Receiver<String>>, stdout: &Tail, limit: Option<u64>) -> String {
    let stderr = Tail(
        stderr
            .and_then(|rx| rx.recv_timeout(Duration::from_secs(1)).ok())
            .unwrap_or_default(),
    );
    let mut text = memory_note(stderr.end(), limit);
    for (name, tail) in [("stderr", &stderr), ("stdout", stdout)] {
        if !tail.end().is_empty() {
            text.push_str(&format!("; its {name} ends:\n{}", tail.end()));
        }
    }
    text
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
