//! Built-ins' rules in parallel: `jobs` workers start one child process per rule, in catalogue
//! order, and the results are reported in that order, so that the lines and the reports are
//! those of a sequential run but for the times.
//!
//! Under `--fail-fast`, a rule starts only while no rule before it (in implementation, then
//! catalogue, order) has failed; results of later rules already in flight when one fails are
//! dropped, and those rules are listed as not run, exactly as a sequential run lists them. A
//! child that finds its implementation cannot be built here stops the others of that
//! implementation, which is then skipped with the reason.

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

use indicatif::ProgressBar;
use refrast_conformance::isolate::{ChildRun, run_rule_watched};
use refrast_conformance::{Options, ProfileReport, Report, Rule, RuleReport, cases_for};
use refrast_registry::BuiltIn;

use super::child::run_rule_command;
use super::progress::Progress;
use super::{print_rule, reach, summarise};
use crate::results::{Entry, Outcome, Subject};
use refrast_conformance::selected;

/// What became of one (implementation, rule) task.
enum Done {
    /// The rule ran in its child: the report, the profile it reported, when it started and ended.
    Ran(Box<RuleReport>, Option<Box<ProfileReport>>, Instant, Instant),
    /// The child says the implementation cannot be built here.
    Unavailable(String),
    /// The child says the suite cannot judge the implementation's profile, and why.
    Refused(String, Option<Box<ProfileReport>>),
    /// Never started: a failure came before it under `--fail-fast`, or its implementation is
    /// unavailable.
    NotStarted,
}

/// Certifies `builtins`, each rule in a child, `jobs` at a time: an entry per implementation
/// certified (or skipped), and the names of those left uncertified after a failure under `--fail-fast`.
pub fn certify_builtins(
    builtins: &[BuiltIn],
    options: &Options,
    dir: &Path,
    jobs: usize,
    out: &Progress,
) -> (Vec<Entry>, Vec<String>) {
    let rules = selected(options);
    let total = builtins.len() * rules.len();
    if total == 0 {
        return (Vec::new(), Vec::new());
    }
    let bars: Vec<ProgressBar> = builtins
        .iter()
        .map(|b| out.implementation(&b.name, rules.len()))
        .collect();
    let run = Run {
        builtins,
        rules: &rules,
        options,
        dir,
        out,
        bars: &bars,
        next: AtomicUsize::new(0),
        stop_at: AtomicUsize::new(usize::MAX),
        unavailable: builtins.iter().map(|_| AtomicBool::new(false)).collect(),
        emitter: Mutex::new(Emitter {
            slots: (0..total).map(|_| None).collect(),
            next: 0,
            current: Building::default(),
            entries: Vec::new(),
            left: Vec::new(),
            stopped: false,
        }),
    };
    let workers = jobs.clamp(1, total);
    match rayon::ThreadPoolBuilder::new().num_threads(workers).build() {
        Ok(pool) => pool.scope(|scope| {
            for _ in 0..workers {
                scope.spawn(|_| run.work());
            }
        }),
        // No threads to be had: the same work, one rule at a time, on this one.
        Err(_) => run.work(),
    }
    let emitter = run.emitter.into_inner().unwrap_or_else(PoisonError::into_inner);
    (emitter.entries, emitter.left)
}

/// What the workers share.
struct Run<'a> {
    builtins: &'a [BuiltIn],
    rules: &'a [Rule],
    options: &'a Options,
    /// Where each failure's files go.
    dir: &'a Path,
    out: &'a Progress,
    bars: &'a [ProgressBar],
    /// The next task to start: implementation `next / rules`, rule `next % rules`.
    next: AtomicUsize,
    /// Tasks from this one on do not start: one before it failed under `--fail-fast`.
    stop_at: AtomicUsize,
    /// Per implementation: a child found it cannot be built here, or its profile refused.
    unavailable: Vec<AtomicBool>,
    emitter: Mutex<Emitter>,
}

impl Run<'_> {
    /// One worker: takes tasks in order until none is left, handing each result to the emitter.
    fn work(&self) {
        let total = self.builtins.len() * self.rules.len();
        loop {
            let task = self.next.fetch_add(1, Ordering::SeqCst);
            if task >= total {
                return;
            }
            let done = self.run(task);
            self.bars[task / self.rules.len()].inc(1);
            self.emitter
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .arrive(self, task, done);
        }
    }

    /// Runs one task in its child, unless a failure before it or its implementation's absence
    /// says not to.
    fn run(&self, task: usize) -> Done {
        let (i, j) = (task / self.rules.len(), task % self.rules.len());
        if task >= self.stop_at.load(Ordering::SeqCst) || self.unavailable[i].load(Ordering::SeqCst) {
            return Done::NotStarted;
        }
        let (b, rule) = (&self.builtins[i], &self.rules[j]);
        let line = self.out.rule(&b.name, rule.id, cases_for(rule, self.options));
        let mut command = run_rule_command(&b.name, rule.id, self.options);
        command.envs(b.env.iter().map(|(k, v)| (k, v)));
        let start = Instant::now();
        let outcome = run_rule_watched(rule, command, self.options, &mut |n| line.set_position(n as u64));
        self.out.done(&line);
        match outcome {
            ChildRun::Unavailable(why) => {
                self.unavailable[i].store(true, Ordering::SeqCst);
                Done::Unavailable(why.to_string())
            }
            ChildRun::Refused(why, profile) => {
                self.unavailable[i].store(true, Ordering::SeqCst);
                Done::Refused(why, profile)
            }
            ChildRun::Ran(mut report, profile) => {
                super::save_exhibit(&mut report, self.dir, self.out);
                if report.status.is_failure() && self.options.fail_fast {
                    self.stop_at.fetch_min(task + 1, Ordering::SeqCst);
                }
                Done::Ran(report, profile, start, Instant::now())
            }
        }
    }
}

/// The implementation whose results are being reported.
#[derive(Default)]
struct Building {
    rules: Vec<RuleReport>,
    /// The first profile a child reported, in catalogue order.
    profile: Option<Box<ProfileReport>>,
    /// From the first of its rules to start to the last to end.
    span: Option<(Instant, Instant)>,
    /// Unavailable here: its remaining results are ignored.
    skipped: bool,
}

/// Reports results in task order as they become contiguous.
struct Emitter {
    slots: Vec<Option<Done>>,
    /// The first task not yet reported.
    next: usize,
    current: Building,
    entries: Vec<Entry>,
    /// Implementations not certified after a failure under `--fail-fast`.
    left: Vec<String>,
    /// A failure under `--fail-fast` has been reported: nothing after it is.
    stopped: bool,
}

impl Emitter {
    /// Stores `done` for `task`, then reports every result now contiguous with those reported.
    fn arrive(&mut self, run: &Run<'_>, task: usize, done: Done) {
        self.slots[task] = Some(done);
        while let Some(done) = self.slots.get_mut(self.next).and_then(Option::take) {
            self.report(run, self.next, done);
            self.next += 1;
        }
    }

    /// Reports one task's result: the header before an implementation's first rule, the rule's
    /// line, and the summary after its last (or after its failure under `--fail-fast`).
    fn report(&mut self, run: &Run<'_>, task: usize, done: Done) {
        let count = run.rules.len();
        let (i, j) = (task / count, task % count);
        let b = &run.builtins[i];
        if self.stopped {
            if j == 0 {
                self.left.push(b.name.clone());
                run.bars[i].abandon_with_message("not run (--fail-fast)");
            }
            return;
        }
        if j == 0 {
            run.out
                .line(&format!("== {} (seed {})", b.name, run.options.seed));
            self.current = Building::default();
        }
        if self.current.skipped {
            return;
        }
        match done {
            Done::Ran(report, profile, start, end) => {
                print_rule(run.out, &report, &reach(&b.name, false));
                let failed = report.status.is_failure();
                self.current.rules.push(*report);
                self.current.profile = self.current.profile.take().or(profile);
                let (first, last) = self.current.span.unwrap_or((start, end));
                self.current.span = Some((first.min(start), last.max(end)));
                if failed && run.options.fail_fast {
                    let not_run = run.rules[j + 1..].iter().map(|r| r.id.to_owned()).collect();
                    self.finish(run, i, not_run);
                    self.stopped = true;
                    return;
                }
            }
            Done::Unavailable(why) => {
                run.out.line(&format!("== {}: SKIPPED: {why}\n", b.name));
                run.bars[i].abandon_with_message("skipped");
                self.entries.push(Entry {
                    subject: Subject::BuiltIn(b.name.clone()),
                    outcome: Outcome::Skipped {
                        implementation: b.name.clone(),
                        skipped: why,
                    },
                });
                self.current.skipped = true;
                return;
            }
            Done::Refused(why, profile) => {
                run.out.line(&format!("== {}: REFUSED: {why}\n", b.name));
                run.bars[i].abandon_with_message("refused");
                let profile = profile.map_or_else(ProfileReport::unknown, |p| *p);
                let report = Report {
                    implementation: profile.name.clone(),
                    profile,
                    rules: Vec::new(),
                    not_run: Vec::new(),
                    refused: Some(why),
                };
                self.entries.push(Entry {
                    subject: Subject::BuiltIn(b.name.clone()),
                    outcome: Outcome::Certified(Box::new(report)),
                });
                self.current.skipped = true;
                return;
            }
            // Only after an unavailable rule or a failure, both handled above; kept as not run.
            Done::NotStarted => {}
        }
        if j + 1 == count {
            let not_run = run.rules.iter().map(|r| r.id.to_owned());
            let ran: Vec<&str> = self.current.rules.iter().map(|r| r.id.as_str()).collect();
            let not_run = not_run.filter(|id| !ran.contains(&id.as_str())).collect();
            self.finish(run, i, not_run);
        }
    }

    /// Closes implementation `i`: its report, summary and entry.
    fn finish(&mut self, run: &Run<'_>, i: usize, not_run: Vec<String>) {
        let built = std::mem::take(&mut self.current);
        let profile = built.profile.map_or_else(ProfileReport::unknown, |p| *p);
        let report = Report {
            implementation: profile.name.clone(),
            profile,
            rules: built.rules,
            not_run,
            refused: None,
        };
        let seconds = built
            .span
            .map_or(0.0, |(first, last)| (last - first).as_secs_f64());
        let (_, failed, _) = report.tally();
        run.bars[i].finish_with_message(if failed == 0 {
            "passed".to_owned()
        } else {
            format!("{failed} failed")
        });
        summarise(run.out, &report, seconds);
        let name = run.builtins[i].name.clone();
        self.entries.push(Entry {
            subject: Subject::BuiltIn(name),
            outcome: Outcome::Certified(Box::new(report)),
        });
    }
}
