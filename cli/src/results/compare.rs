//! `refrast compare OLD.json NEW.json`: what changed between two runs, per implementation.

use std::collections::BTreeSet;

use refrast_conformance::{Report, Status, catalogue};

use super::{Document, Entry, Outcome};

/// How one rule moved between two runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Move {
    /// A failure (fail, crash, timeout, flake) where there was none.
    Regressed,
    /// A pass where there was a failure.
    Fixed,
    /// Another status, neither of those (fail to crash, pass to n/a, fail to beyond-spec).
    Changed,
    /// In the new run only (a new rule, or one the old run did not select).
    Added,
    /// In the old run only.
    Removed,
}

impl Move {
    fn label(self) -> &'static str {
        match self {
            Self::Regressed => "REGRESSED",
            Self::Fixed => "fixed",
            Self::Changed => "changed",
            Self::Added => "added",
            Self::Removed => "removed",
        }
    }
}

/// One rule that moved.
#[derive(Clone, Debug, PartialEq)]
pub struct RuleMove {
    /// Which way.
    pub kind: Move,
    /// The rule.
    pub id: String,
    /// Its status in the old run (`None`: not run).
    pub old: Option<Status>,
    /// Its status in the new run (`None`: not run).
    pub new: Option<Status>,
    /// The new run's message.
    pub message: Option<String>,
}

/// One implementation's changes, or what happened to it as a whole.
#[derive(Clone, Debug, PartialEq)]
pub struct Changes {
    /// The implementation, as the command line named it.
    pub name: String,
    /// Each rule that moved.
    pub moves: Vec<RuleMove>,
    /// How the entry as a whole changed, when it was not certified in both runs.
    pub entry: Option<String>,
    /// Whether the entry as a whole regressed (certified before, failed to start now).
    pub entry_regressed: bool,
    /// Rules certified in both runs.
    pub compared: usize,
}

impl Changes {
    /// Whether anything got worse.
    #[must_use]
    pub fn regressed(&self) -> bool {
        self.entry_regressed || self.moves.iter().any(|m| m.kind == Move::Regressed)
    }
}

/// The changes from `old` to `new`, one per implementation in either (new's order first).
#[must_use]
pub fn compare(old: &Document, new: &Document) -> Vec<Changes> {
    let mut names: Vec<&str> = new.implementations.iter().map(|e| e.subject.name()).collect();
    for e in &old.implementations {
        if !names.contains(&e.subject.name()) {
            names.push(e.subject.name());
        }
    }
    names
        .into_iter()
        .map(|name| {
            let find = |d: &'_ Document| -> Option<Entry> {
                d.implementations
                    .iter()
                    .find(|e| e.subject.name() == name)
                    .cloned()
            };
            changes(name, find(old).as_ref(), find(new).as_ref())
        })
        .collect()
}

fn changes(name: &str, old: Option<&Entry>, new: Option<&Entry>) -> Changes {
    let mut c = Changes {
        name: name.to_owned(),
        moves: Vec::new(),
        entry: None,
        entry_regressed: false,
        compared: 0,
    };
    let (old_report, new_report) = (old.and_then(Entry::report), new.and_then(Entry::report));
    match (old_report, new_report) {
        (Some(o), Some(n)) => rule_moves(&mut c, o, n),
        _ => {
            c.entry = Some(format!("{} -> {}", state(old), state(new)));
            c.entry_regressed = new.is_some_and(|n| !n.passed()) && old.is_none_or(Entry::passed);
        }
    }
    c
}

/// What an entry was, in a word or two.
fn state(entry: Option<&Entry>) -> String {
    match entry.map(|e| &e.outcome) {
        None => "absent".into(),
        Some(Outcome::Certified(r)) if r.refused.is_some() => "refused".into(),
        Some(Outcome::Certified(r)) => {
            let (pass, fail, na) = r.tally();
            format!("certified ({pass} passed, {fail} failed, {na} n/a)")
        }
        Some(Outcome::FailedToStart { .. }) => "failed to start".into(),
        Some(Outcome::Skipped { skipped, .. }) => format!("skipped ({skipped})"),
    }
}

fn rule_moves(c: &mut Changes, old: &Report, new: &Report) {
    let ids: BTreeSet<&str> = old
        .rules
        .iter()
        .chain(&new.rules)
        .map(|r| r.id.as_str())
        .collect();
    let order = catalogue();
    let mut ids: Vec<&str> = ids.into_iter().collect();
    ids.sort_by_key(|id| order.iter().position(|r| r.id == *id).unwrap_or(usize::MAX));
    for id in ids {
        let o = old.rules.iter().find(|r| r.id == id);
        let n = new.rules.iter().find(|r| r.id == id);
        let (os, ns) = (o.map(|r| r.status), n.map(|r| r.status));
        let message = n.and_then(|r| r.message.clone());
        let kind = match (os, ns) {
            (Some(a), Some(b)) if a == b => {
                c.compared += 1;
                continue;
            }
            (Some(a), Some(b)) => {
                c.compared += 1;
                if b.is_failure() && !a.is_failure() {
                    Move::Regressed
                } else if a.is_failure() && b == Status::Pass {
                    Move::Fixed
                } else {
                    Move::Changed
                }
            }
            (None, Some(_)) => Move::Added,
            (Some(_), None) => Move::Removed,
            (None, None) => continue,
        };
        c.moves.push(RuleMove {
            kind,
            id: id.to_owned(),
            old: os,
            new: ns,
            message,
        });
    }
}

/// The comparison as text: a line per implementation, then a line per moved rule.
#[must_use]
pub fn text(all: &[Changes]) -> String {
    let mut out = String::new();
    for c in all {
        if let Some(entry) = &c.entry {
            let mark = if c.entry_regressed { "REGRESSED: " } else { "" };
            out.push_str(&format!("{}: {mark}{entry}\n", c.name));
            continue;
        }
        let count = |m: Move| c.moves.iter().filter(|x| x.kind == m).count();
        if c.moves.is_empty() {
            out.push_str(&format!("{}: no change ({} rules)\n", c.name, c.compared));
            continue;
        }
        out.push_str(&format!(
            "{}: {} regressed, {} fixed, {} changed, {} added, {} removed ({} rules in both)\n",
            c.name,
            count(Move::Regressed),
            count(Move::Fixed),
            count(Move::Changed),
            count(Move::Added),
            count(Move::Removed),
            c.compared
        ));
        let mut moves = c.moves.clone();
        moves.sort_by_key(|m| m.kind);
        let word = |s: Option<Status>| s.map_or("-", Status::word);
        for RuleMove {
            kind,
            id,
            old: o,
            new: n,
            message,
        } in moves
        {
            let why = message
                .as_deref()
                .filter(|_| kind == Move::Regressed || kind == Move::Changed)
                .and_then(|m| m.lines().next())
                .map(|m| format!("  ({m})"))
                .unwrap_or_default();
            out.push_str(&format!(
                "  {:<9}  {id:<38} {} -> {}{why}\n",
                kind.label(),
                word(o),
                word(n)
            ));
        }
    }
    out
}

/// Warnings about options that differ between the runs, which can move verdicts by themselves.
#[must_use]
pub fn warnings(old: &Document, new: &Document) -> Vec<String> {
    let (a, b) = (&old.run.options, &new.run.options);
    let mut w = Vec::new();
    if a.seed != b.seed {
        w.push(format!("the seeds differ ({} and {})", a.seed, b.seed));
    }
    if (a.cases, &a.proptest_cases, a.scale) != (b.cases, &b.proptest_cases, b.scale) {
        w.push("the cases per rule differ".to_owned());
    }
    if a.budget != b.budget {
        w.push("the time budgets differ".to_owned());
    }
    w.into_iter()
        .map(|x| format!("warning: {x}: verdicts that depend on the cases may move by that alone"))
        .collect()
}

/// Arguments of `refrast compare`.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The earlier run's `certify --json` report (the baseline).
    old: std::path::PathBuf,
    /// The later run's.
    new: std::path::PathBuf,
}

/// Runs `refrast compare`: 0 when nothing regressed, 1 when something did, 2 when a report
/// cannot be read.
pub fn run(args: &CompareArgs) -> std::process::ExitCode {
    let (old, new) = match (Document::load(&args.old), Document::load(&args.new)) {
        (Ok(old), Ok(new)) => (old, new),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("error: {e}");
            return std::process::ExitCode::from(2);
        }
    };
    for w in warnings(&old, &new) {
        eprintln!("{w}");
    }
    let all = compare(&old, &new);
    crate::say(text(&all).trim_end());
    if all.iter().any(Changes::regressed) {
        std::process::ExitCode::FAILURE
    } else {
        std::process::ExitCode::SUCCESS
    }
}
