//! Following one rule's child: its protocol lines, its case log and its end; and, when it
//! dies or hangs, a second run that names the input it stopped on.
//!
//! The first run logs only a count a case, so no case pays for its text (a tenth of
//! `certify`'s time on the reference, issue 47). A child that stops without a report stopped
//! on case N of a run its seed repeats: a second run writes the text of case N on, and stops
//! there again where the stop belongs to the input.

use std::io::Read;
use std::process::{Command, ExitStatus};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::thread;
use std::time::{Duration, Instant};

use refrast::Unavailable;

use super::case_log::{CASE_TEXT_FROM_ENV, CaseLog};
use super::{ChildRun, EXIT_GRACE, MARK, MAX_LINE, Message, blank};
use crate::judge::Options;
use crate::report::{ProfileReport, RuleReport, Status};
use crate::rules::Rule;
use refrast_pipe::contain::{Contained, memory_note};
use refrast_pipe::{Tail, for_each_line, status_words};

/// How often the parent reads a child's case log for progress: often enough for a progress
/// display, rarely enough to cost nothing beside a case.
const LOG_POLL: Duration = Duration::from_millis(100);

/// What a child printed, as the reader thread passes it on.
enum Line {
    Message(Message),
    Other(String),
    Closed,
}

/// How a child stopped without a report.
pub(super) enum Stopped {
    /// It exited or was killed, with its status when known.
    Ended(Option<ExitStatus>),
    /// It started no case within the case timeout, and was ended.
    Hung,
    /// A second run went past the case it is to name, and was ended.
    WentOn,
}

/// What one run of a child came to.
pub(super) enum Outcome {
    /// It said how the rule went, or why it could not run it.
    Said(ChildRun),
    /// It stopped without saying, with the end of its own output.
    Stopped(Stopped, String),
    /// It could not be started: why.
    NotStarted(std::io::Error),
}

/// What the parent has seen of a rule's child so far.
pub(super) struct Watch<'a> {
    pub(super) rule: &'a Rule,
    pub(super) options: &'a Options,
    pub(super) started: Instant,
    /// The profile the child reported, once it has.
    pub(super) profile: Option<Box<ProfileReport>>,
    /// The last input it announced with its text.
    pub(super) last_case: Option<String>,
    /// How many inputs it announced (shrinking's included).
    pub(super) cases_seen: u64,
}

impl<'a> Watch<'a> {
    /// Nothing seen yet of a child running `rule`.
    pub(super) fn new(rule: &'a Rule, options: &'a Options) -> Self {
        Watch {
            rule,
            options,
            started: Instant::now(),
            profile: None,
            last_case: None,
            cases_seen: 0,
        }
    }

    /// Runs `command` (whose stdio the caller has set) to its end, following its lines and
    /// `log`; with `until`, ends it as soon as it starts a case past that one.
    pub(super) fn follow(
        &mut self,
        command: &mut Command,
        log: Option<&CaseLog>,
        on_case: &mut dyn FnMut(usize),
        until: Option<u64>,
    ) -> Outcome {
        let options = self.options;
        let mut child = match Contained::spawn(command, options.memory_limit) {
            Ok(child) => child,
            Err(e) => return Outcome::NotStarted(e),
        };
        let stderr = child.child.stderr.take().map(collect_tail);
        let rx = child.child.stdout.take().map(read_lines);
        let mut own_output = Tail::default();
        let mut last_word = Instant::now();
        let stopped = loop {
            let left = options.case_timeout.saturating_sub(last_word.elapsed());
            let wait = if log.is_some() { left.min(LOG_POLL) } else { left };
            let line = rx.as_ref().map_or(Ok(Line::Closed), |rx| rx.recv_timeout(wait));
            if let Some(count) = log.map(CaseLog::count)
                && count != 0
                && count != self.cases_seen
            {
                self.cases_seen = count;
                on_case(usize::try_from(count).unwrap_or(usize::MAX));
                last_word = Instant::now();
                if until.is_some_and(|n| count > n) {
                    child.end();
                    break Stopped::WentOn;
                }
            }
            match line {
                Ok(Line::Message(Message::Case(input))) => {
                    self.cases_seen += 1;
                    on_case(usize::try_from(self.cases_seen).unwrap_or(usize::MAX));
                    self.last_case = Some(input);
                    last_word = Instant::now();
                }
                Ok(Line::Message(Message::Profile(reported))) => {
                    self.profile = Some(reported);
                    last_word = Instant::now();
                }
                Ok(Line::Message(Message::Unavailable(why))) => {
                    finish(&mut child);
                    return Outcome::Said(ChildRun::Unavailable(Unavailable(why)));
                }
                Ok(Line::Message(Message::Refused(why))) => {
                    finish(&mut child);
                    return Outcome::Said(ChildRun::Refused(why, self.profile.take()));
                }
                Ok(Line::Message(Message::Report(mut report, exhibit))) => {
                    finish(&mut child);
                    report.exhibit = exhibit.map(|e| *e);
                    return Outcome::Said(ChildRun::Ran(report, self.profile.take()));
                }
                Ok(Line::Other(line)) => own_output.push(&line),
                Ok(Line::Closed) | Err(RecvTimeoutError::Disconnected) => {
                    break Stopped::Ended(finish(&mut child));
                }
                Err(RecvTimeoutError::Timeout) if last_word.elapsed() < options.case_timeout => {}
                Err(RecvTimeoutError::Timeout) => {
                    child.end();
                    break Stopped::Hung;
                }
            }
        };
        if let Some(count) = log.map(CaseLog::count).filter(|&n| n != 0) {
            self.cases_seen = count;
        }
        let output = join_output(stderr, &own_output, options.memory_limit);
        Outcome::Stopped(stopped, output)
    }

    /// The rule's report for a child that stopped as `stopped`, on the last case it started,
    /// named by a second run of `command` where `log` has no text of it.
    pub(super) fn stopped(
        mut self,
        stopped: &Stopped,
        output: &str,
        command: &mut Command,
        log: Option<&CaseLog>,
    ) -> ChildRun {
        let case = self.cases_seen;
        let mut note = String::new();
        // A child that could not open its log announced its cases as lines, with their text.
        if let Some(log) = log
            && case > 0
            && log.count() > 0
        {
            match name_case(self.rule, self.options, command, log, case) {
                Ok(text) => self.last_case = Some(text),
                Err(why) => note = why,
            }
        }
        let (status, message) = match stopped {
            Stopped::Hung => (
                Status::Timeout,
                format!(
                    "no answer within {} s on case {case}: the rasterizer hangs on it (or is far too slow; \
                     --case-timeout sets the limit){note}{output}",
                    self.options.case_timeout.as_secs_f64(),
                ),
            ),
            Stopped::Ended(status) => (
                Status::Crash,
                format!(
                    "the rasterizer's process ended without a verdict ({}) during case {case}{note}{output}",
                    describe(*status),
                ),
            ),
            Stopped::WentOn => (
                Status::Crash,
                format!("the rasterizer's process stopped on case {case}{note}{output}"),
            ),
        };
        self.failed(status, message)
    }

    /// The rule's report when the child gave none: `status`, `message`, the last case announced.
    pub(super) fn failed(self, status: Status, message: String) -> ChildRun {
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

/// The text of case `n` of a child of `command` that stopped on it: a second run writes the
/// text of every case from `n` on into `log` and is ended past it. `Err` with a note for the
/// message where that run does not stop on case `n` too.
fn name_case(
    rule: &Rule,
    options: &Options,
    command: &mut Command,
    log: &CaseLog,
    n: u64,
) -> Result<String, String> {
    command.env(CASE_TEXT_FROM_ENV, n.to_string());
    let mut again = Watch::new(rule, options);
    let outcome = again.follow(command, Some(log), &mut |_| {}, Some(n));
    let stopped_there =
        matches!(outcome, Outcome::Stopped(Stopped::Ended(_) | Stopped::Hung, _)) && again.cases_seen == n;
    match log.last() {
        Some(text) if stopped_there => Ok(text),
        _ => Err(
            " (a second run, to name that input, did not stop on it: what stopped the first \
                  may not be the input alone)"
                .to_owned(),
        ),
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
