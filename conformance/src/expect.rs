//! Expectation files: the verdicts a team expects of an implementation, kept beside its code,
//! so that a run is judged against them (a changed verdict either way is news) rather than
//! against "every rule passes".
//!
//! The format (docs/expectations.md): `#` starts a comment; a `taken` line states the options
//! the file was taken at (`taken cases=default seed=… scale=1 budget=none`); `[NAME]` opens the
//! section of the implementation `refrast impls` or `--exec` calls NAME; then one line per rule
//! that does not simply pass, `PATTERN STATUS  # why`. PATTERN is a rule ID or a glob with `*`;
//! STATUS is a status word (`fail`, `crash`, `timeout`, `flake`, `beyond-spec`, `n/a`, `pass`),
//! several joined by `|`, or `may-fail` (`pass|fail|beyond-spec|flake`) for a verdict that
//! depends on the cases or the seed. The last line that matches a rule decides; a rule no line
//! matches is expected to pass.

use std::fmt;

use crate::certify::matches_glob;
use crate::judge::Options;
use crate::report::{Report, Status};
use crate::rules::catalogue;

/// The statuses `may-fail` accepts: any verdict on the answers, never a crash or a hang.
pub const MAY_FAIL: [Status; 4] = [Status::Pass, Status::Fail, Status::BeyondSpec, Status::Flake];

/// The options a file was taken at, as its `taken` line states them.
#[derive(Clone, Debug, PartialEq)]
pub struct Taken {
    /// Cases per rule; `None` is each rule's default.
    pub cases: Option<u32>,
    /// The generator's seed.
    pub seed: u64,
    /// The multiplier of the cases.
    pub scale: u32,
    /// Seconds per rule after which no case starts; `None` runs every case.
    pub budget: Option<f64>,
}

impl Taken {
    /// The options of a run, as a `taken` line states them.
    #[must_use]
    pub fn of(options: &Options) -> Self {
        Self {
            cases: options.cases,
            seed: options.seed,
            scale: options.scale.max(1),
            budget: options.budget.map(|b| b.as_secs_f64()),
        }
    }

    /// Parses the words after `taken`; `Err` names the word it cannot read.
    fn parse(words: &str) -> Result<Self, String> {
        let mut taken = Self {
            cases: None,
            seed: crate::runner::DEFAULT_SEED,
            scale: 1,
            budget: None,
        };
        for word in words.split_whitespace() {
            let bad =
                || format!("`{word}` is not one of cases=N|default, seed=N, scale=N, budget=SECONDS|none");
            let (key, value) = word.split_once('=').ok_or_else(bad)?;
            match (key, value) {
                ("cases", "default") => taken.cases = None,
                ("cases", n) => taken.cases = Some(n.parse().map_err(|_| bad())?),
                ("seed", n) => taken.seed = n.parse().map_err(|_| bad())?,
                ("scale", n) => taken.scale = n.parse().map_err(|_| bad())?,
                ("budget", "none") => taken.budget = None,
                ("budget", s) => taken.budget = Some(s.parse().map_err(|_| bad())?),
                _ => return Err(bad()),
            }
        }
        Ok(taken)
    }
}

impl fmt::Display for Taken {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let cases = self.cases.map_or_else(|| "default".to_owned(), |n| n.to_string());
        let budget = self.budget.map_or_else(|| "none".to_owned(), |b| b.to_string());
        write!(
            f,
            "taken cases={cases} seed={} scale={} budget={budget}",
            self.seed, self.scale
        )
    }
}

/// One expectation: a pattern, the statuses it accepts, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Expectation {
    /// A rule ID, or a glob with `*`.
    pub pattern: String,
    /// The statuses accepted.
    pub accepts: Vec<Status>,
    /// The status as written (`fail`, `may-fail`, `fail|flake`).
    pub written: String,
    /// The comment after `#`, if any.
    pub why: Option<String>,
}

impl Expectation {
    /// Whether this line speaks of rule `id`.
    #[must_use]
    pub fn matches(&self, id: &str) -> bool {
        matches_glob(&self.pattern, id)
    }
}

/// The expectations of one implementation.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// The implementation's name: a built-in's, or an `--exec` command line.
    pub name: String,
    /// Its lines, in file order.
    pub lines: Vec<Expectation>,
}

impl Section {
    /// The statuses accepted for rule `id` (the last matching line's; pass when none matches),
    /// and that line.
    #[must_use]
    pub fn expected(&self, id: &str) -> (Vec<Status>, Option<&Expectation>) {
        match self.lines.iter().rev().find(|l| l.matches(id)) {
            Some(line) => (line.accepts.clone(), Some(line)),
            None => (vec![Status::Pass], None),
        }
    }
}

/// One or more expectation files, read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Expectations {
    /// Each file's `taken` line, with the file's name.
    pub taken: Vec<(String, Taken)>,
    /// Every section of every file.
    pub sections: Vec<Section>,
}

/// How a verdict differs from its expectation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surprise {
    /// A failure (fail, crash, timeout, flake) where none was expected.
    Failure,
    /// A pass where a failure was expected: tighten the file.
    Pass,
    /// Another status than expected, neither a new failure nor a new pass.
    Changed,
}

/// A verdict its expectation does not accept.
#[derive(Clone, Debug, PartialEq)]
pub struct Mismatch {
    /// The implementation's section name.
    pub implementation: String,
    /// The rule.
    pub rule: String,
    /// What the expectation accepts, as written (`pass` where no line matched).
    pub expected: String,
    /// What the run found.
    pub got: Status,
    /// Which way it moved.
    pub surprise: Surprise,
    /// The rule's message, if any.
    pub message: Option<String>,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.surprise {
            Surprise::Failure => "UNEXPECTED FAILURE",
            Surprise::Pass => "UNEXPECTED PASS",
            Surprise::Changed => "CHANGED",
        };
        write!(
            f,
            "{what}: {} {}: expected {}, got {}",
            self.implementation, self.rule, self.expected, self.got
        )?;
        if let Some(m) = &self.message {
            let first = m.lines().next().unwrap_or("");
            write!(f, " ({first})")?;
        }
        Ok(())
    }
}

impl Expectations {
    /// Parses one file's text; `origin` (its path) names it in errors, as `origin:line: why`.
    pub fn parse(text: &str, origin: &str) -> Result<Self, String> {
        let mut out = Self::default();
        for (n, raw) in text.lines().enumerate() {
            let at = |why: String| format!("{origin}:{}: {why}", n + 1);
            let (body, why) = match raw.split_once('#') {
                Some((body, why)) => (body.trim(), Some(why.trim().to_owned()).filter(|w| !w.is_empty())),
                None => (raw.trim(), None),
            };
            if body.is_empty() {
                continue;
            }
            if let Some(name) = body.strip_prefix('[') {
                let name = name
                    .strip_suffix(']')
                    .ok_or_else(|| at(format!("`{body}` opens a section but does not end in `]`")))?
                    .trim();
                if name.is_empty() {
                    return Err(at("a section needs a name: [lavapipe], [python3 my.py]".into()));
                }
                out.sections.push(Section {
                    name: name.to_owned(),
                    lines: Vec::new(),
                });
                continue;
            }
            if let Some(words) = body.strip_prefix("taken ") {
                out.taken
                    .push((origin.to_owned(), Taken::parse(words).map_err(at)?));
                continue;
            }
            let Some(section) = out.sections.last_mut() else {
                return Err(at(format!(
                    "`{body}` comes before any [section]; name the implementation first"
                )));
            };
            let words: Vec<&str> = body.split_whitespace().collect();
            let [pattern, written] = words[..] else {
                return Err(at(format!("`{body}` is not `RULE STATUS`")));
            };
            let accepts = accepted(written).map_err(at)?;
            if !catalogue().iter().any(|r| matches_glob(pattern, r.id)) {
                return Err(at(format!(
                    "`{pattern}` matches no rule; `refrast rules` lists them"
                )));
            }
            section.lines.push(Expectation {
                pattern: pattern.to_owned(),
                accepts,
                written: written.to_owned(),
                why,
            });
        }
        Ok(out)
    }

    /// Reads and joins the files at `paths`; two sections of one name are an error.
    pub fn load(paths: &[std::path::PathBuf]) -> Result<Self, String> {
        let mut all = Self::default();
        for path in paths {
            let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
            let file = Self::parse(&text, &path.display().to_string())?;
            for section in &file.sections {
                if all.section(&section.name).is_some()
                    || file.sections.iter().filter(|s| s.name == section.name).count() > 1
                {
                    return Err(format!(
                        "{}: the section [{}] is given twice; keep one per implementation",
                        path.display(),
                        section.name
                    ));
                }
            }
            all.taken.extend(file.taken);
            all.sections.extend(file.sections);
        }
        Ok(all)
    }

    /// The section of `implementation`, if any.
    #[must_use]
    pub fn section(&self, implementation: &str) -> Option<&Section> {
        self.sections.iter().find(|s| s.name == implementation)
    }

    /// Every rule of `report` whose verdict the section of `implementation` does not accept
    /// (every rule is expected to pass where there is no section).
    #[must_use]
    pub fn check(&self, implementation: &str, report: &Report) -> Vec<Mismatch> {
        let empty = Section {
            name: implementation.to_owned(),
            lines: Vec::new(),
        };
        let section = self.section(implementation).unwrap_or(&empty);
        report
            .rules
            .iter()
            .filter_map(|r| {
                let (accepts, line) = section.expected(&r.id);
                if accepts.contains(&r.status) {
                    return None;
                }
                let surprise = if r.status.is_failure() {
                    Surprise::Failure
                } else if r.status == Status::Pass {
                    Surprise::Pass
                } else {
                    Surprise::Changed
                };
                Some(Mismatch {
                    implementation: implementation.to_owned(),
                    rule: r.id.clone(),
                    expected: line.map_or_else(|| "pass".to_owned(), |l| l.written.clone()),
                    got: r.status,
                    surprise,
                    message: r.message.clone(),
                })
            })
            .collect()
    }

    /// Warnings about options that differ from those a file was taken at.
    #[must_use]
    pub fn warnings(&self, run: &Taken) -> Vec<String> {
        self.taken
            .iter()
            .filter(|(_, taken)| taken != run)
            .map(|(file, taken)| {
                format!(
                    "warning: {file} was {taken}, this run is {run}; verdicts that depend on the cases \
                     or the seed may differ"
                )
            })
            .collect()
    }
}

/// The statuses a STATUS word accepts.
fn accepted(written: &str) -> Result<Vec<Status>, String> {
    if written == "may-fail" {
        return Ok(MAY_FAIL.to_vec());
    }
    written
        .split('|')
        .map(|w| {
            Status::from_word(w).ok_or_else(|| {
                format!(
                    "`{w}` is not a status; use pass, fail, crash, timeout, flake, beyond-spec, n/a, \
                     may-fail, or several joined by |"
                )
            })
        })
        .collect()
}

/// An expectation file of what `seen` found, taken at `taken`: lines of `old` that still hold
/// are kept with their comments (a `may-fail` stays one), other verdicts are written as seen
/// with their message, and sections of implementations not in `seen` are kept as they were.
#[must_use]
pub fn write(old: &Expectations, taken: &Taken, seen: &[(&str, &Report)]) -> String {
    let mut text = String::from(
        "# refrast expectations (docs/expectations.md): one line per rule that does not simply\n\
         # pass, `RULE STATUS  # why`; checked by `refrast certify --expect FILE`.\n",
    );
    text.push_str(&format!("{taken}\n"));
    for (name, report) in seen {
        text.push_str(&format!("\n[{name}]\n"));
        let section = old.section(name);
        let mut lines: Vec<(String, String, Option<String>)> = Vec::new();
        for r in &report.rules {
            let kept = section.map(|s| s.expected(&r.id)).and_then(|(accepts, line)| {
                line.filter(|_| accepts.contains(&r.status))
                    .map(|l| (l.written.clone(), l.why.clone()))
            });
            match kept {
                Some((written, why)) if written != "pass" => lines.push((r.id.clone(), written, why)),
                Some(_) => {}
                None if r.status == Status::Pass => {}
                None => {
                    let why = r.message.as_deref().and_then(|m| m.lines().next()).map(short);
                    lines.push((r.id.clone(), r.status.word().to_owned(), why));
                }
            }
        }
        // Lines about rules this run did not run (another --rule or --shard) are kept.
        if let Some(s) = section {
            for l in &s.lines {
                if !report.rules.iter().any(|r| l.matches(&r.id)) {
                    lines.push((l.pattern.clone(), l.written.clone(), l.why.clone()));
                }
            }
        }
        let width = lines.iter().map(|(id, _, _)| id.len()).max().unwrap_or(0);
        for (id, written, why) in lines {
            let line = match why {
                Some(why) => format!("{id:<width$}  {written:<11}  # {why}"),
                None => format!("{id:<width$}  {written}"),
            };
            text.push_str(line.trim_end());
            text.push('\n');
        }
    }
    for s in &old.sections {
        if seen.iter().any(|(name, _)| *name == s.name) {
            continue;
        }
        text.push_str(&format!("\n[{}]\n", s.name));
        for l in &s.lines {
            match &l.why {
                Some(why) => text.push_str(&format!("{}  {}  # {why}\n", l.pattern, l.written)),
                None => text.push_str(&format!("{}  {}\n", l.pattern, l.written)),
            }
        }
    }
    text
}

/// A message cut to one short line for a comment.
fn short(message: &str) -> String {
    const MOST: usize = 100;
    let message = message.replace('#', "no.");
    if message.chars().count() <= MOST {
        return message;
    }
    let cut: String = message.chars().take(MOST).collect();
    format!("{cut}…")
}
