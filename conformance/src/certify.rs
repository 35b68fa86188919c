//! Certification: every applicable rule against one rasterizer, summed up as a report.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::thread;
use std::time::{Duration, Instant};

use refrast::Rasterizer;

use crate::picture;
use crate::report::{ProfileReport, Report, RuleReport, Status};
use crate::rules::{Level, Rule, Run, catalogue, hint};
use crate::runner::{Announce, DEFAULT_SEED, RunConfig, Verdict, guarded};

/// How long one case may take by default: far more than any correct rasterizer needs for the
/// suite's small scenes (a GPU through an API takes milliseconds), short enough that a hang
/// costs a run little.
pub const DEFAULT_CASE_TIMEOUT: Duration = Duration::from_secs(20);

/// Cases of a failed rule a hint must pass, beside the failing one, before it is printed: one
/// case can agree with a wrong reading by chance (a truncating rasterizer's small triangle with
/// another tie rule's coverage), a hundred seldom do.
const HINT_CASES: u32 = 100;

/// What to run and where to write pictures.
#[derive(Clone, Debug)]
pub struct Options {
    /// Cases per rule. `None` reads the `PROPTEST_CASES` environment variable (as proptest
    /// itself does), and without it takes each rule's default: set `Some` to be independent of
    /// the environment.
    pub cases: Option<u32>,
    /// Multiplies the cases per rule, whichever way they were chosen (for nightly runs at 10×).
    pub scale: u32,
    /// Seed of the case generator.
    pub seed: u64,
    /// Only rules whose ID matches one of these globs (`*` matches anything; no `*` means a
    /// prefix); empty selects every rule.
    pub rules: Vec<String>,
    /// Only this part of the selected rules ([`Shard`]), for runs split across machines.
    pub shard: Option<Shard>,
    /// Where to write counterexample pictures; `None` writes none.
    pub report_dir: Option<PathBuf>,
    /// Called with every input before it is checked ([`RunConfig::announce`]).
    pub announce: Option<Announce>,
    /// How long one case may take before a rule run in a child process ([`crate::isolate`])
    /// fails as hung.
    pub case_timeout: Duration,
    /// Wall time per rule after which no new case starts ([`RunConfig::budget`]); `None` runs
    /// every case.
    pub budget: Option<Duration>,
    /// Stop at the first rule that fails: the rules after it are not run and are listed in
    /// [`Report::not_run`] (for a quick answer, and for mutation testing).
    pub fail_fast: bool,
    /// The most data, in bytes, each rule's child process (and a `--exec` child) may allocate
    /// ([`crate::contain`]); `None` sets no limit.
    pub memory_limit: Option<u64>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            cases: None,
            scale: 1,
            seed: DEFAULT_SEED,
            rules: Vec::new(),
            shard: None,
            report_dir: None,
            announce: None,
            case_timeout: DEFAULT_CASE_TIMEOUT,
            budget: None,
            fail_fast: false,
            memory_limit: Some(crate::contain::DEFAULT_MEMORY_LIMIT),
        }
    }
}

/// Whether a rule ID matches a `--rule` pattern: a glob with `*`, or a prefix when there is none.
#[must_use]
pub fn matches(pattern: &str, id: &str) -> bool {
    if pattern.contains('*') {
        matches_glob(pattern, id)
    } else {
        id.starts_with(pattern)
    }
}

/// Whether a rule ID matches a glob, where `*` matches any run of characters (without `*`,
/// the ID itself).
#[must_use]
pub fn matches_glob(pattern: &str, id: &str) -> bool {
    if !pattern.contains('*') {
        return pattern == id;
    }
    let parts: Vec<&str> = pattern.split('*').collect();
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !id.starts_with(first) || !id[first.len()..].ends_with(last) || id.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &id[first.len()..id.len() - last.len()];
    for part in &parts[1..parts.len() - 1] {
        match rest.find(part) {
            Some(i) => rest = &rest[i + part.len()..],
            None => return false,
        }
    }
    true
}

/// Cases for a rule: the option, else `PROPTEST_CASES`, else the rule's default; times the scale.
#[must_use]
pub fn cases_for(rule: &Rule, options: &Options) -> u32 {
    options
        .cases
        .or_else(|| std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()))
        .unwrap_or(rule.default_cases)
        .saturating_mul(options.scale.max(1))
}

/// Runs one rule against `rasterizer` and reports it, writing a picture on failure.
pub fn run_rule(rule: &Rule, rasterizer: &mut dyn Rasterizer, options: &Options) -> RuleReport {
    let start = Instant::now();
    let mut report = judge(rule, rasterizer, options);
    report.seconds = start.elapsed().as_secs_f64();
    report
}

/// [`run_rule`] without the clock.
fn judge(rule: &Rule, rasterizer: &mut dyn Rasterizer, options: &Options) -> RuleReport {
    let profile = guarded(|| rasterizer.profile());
    let mut report = RuleReport {
        id: rule.id.to_owned(),
        family: rule.family,
        kind: rule.kind,
        status: Status::Pass,
        cases: 0,
        planned: 0,
        budget_spent: false,
        seed: options.seed,
        tolerance_subpixels: profile.as_ref().map_or(1, |p| p.tolerance_subpixels.max(1)),
        message: None,
        details: Vec::new(),
        counts: None,
        spec_note: None,
        hint: None,
        counterexample: None,
        picture: None,
        seconds: 0.0,
    };
    let profile = match profile {
        Ok(profile) => profile,
        Err(what) => {
            report.status = Status::Crash;
            report.message = Some(format!("profile() panicked: {what}"));
            return report;
        }
    };
    let primitives = match guarded(|| rasterizer.primitive_profile()) {
        Ok(primitives) => primitives,
        Err(what) => {
            report.status = Status::Crash;
            report.message = Some(format!("primitive_profile() panicked: {what}"));
            return report;
        }
    };
    if let Err(reason) = rule.applies(&profile, &primitives) {
        report.status = Status::NotApplicable;
        report.message = Some(reason.to_owned());
        return report;
    }
    let cfg = RunConfig {
        cases: cases_for(rule, options),
        seed: options.seed,
        announce: options.announce,
        budget: options.budget,
        orient: !rule.keeps_winding,
    };
    report.planned = cfg.cases;
    // What the claimed specification requires runs first where it requires only part of the
    // rule: a failure there is a failure; one only the whole rule finds is beyond it.
    let level = rule.levels.of(profile.spec);
    // What the required part ran, said with a failure beyond it (its cases are not the rule's).
    let mut required_part = None;
    let (verdict, beyond) = match level {
        Level::Required => ((rule.run)(rasterizer, &cfg), false),
        Level::Partly { part, .. } => match part(rasterizer, &cfg) {
            failed @ Verdict::Fail { .. } => (failed, false),
            Verdict::Pass { cases, budget_spent } => {
                required_part = Some(if budget_spent {
                    format!("; the required part passed {cases} cases before the time budget ran out")
                } else {
                    format!("; the required part passed all {cases} cases")
                });
                ((rule.run)(rasterizer, &cfg), true)
            }
        },
        Level::Undefined(_) | Level::NotCovered(_) => ((rule.run)(rasterizer, &cfg), true),
    };
    match verdict {
        Verdict::Pass { cases, budget_spent } => {
            report.cases = cases;
            report.budget_spent = budget_spent;
        }
        Verdict::Fail {
            cases,
            counterexample,
            violation,
            scene,
            replay,
        } => {
            report.cases = cases;
            // A crash, a hang or a flake is what it is under every specification.
            report.status = violation.status;
            if beyond
                && violation.status == Status::Fail
                && let Some(note) = level.note()
            {
                report.status = Status::BeyondSpec;
                report.spec_note = Some(format!(
                    "not required by {}: {note}{}",
                    profile.spec.title(),
                    required_part.unwrap_or_default()
                ));
            }
            // The property that failed: the required part's, or the whole rule's.
            let failed: Run = match level {
                Level::Partly { part, .. } if !beyond => part,
                _ => rule.run,
            };
            let mut verify = |r: &mut dyn Rasterizer| {
                let more = RunConfig {
                    cases: cfg.cases.min(HINT_CASES),
                    announce: None,
                    ..cfg
                };
                replay.as_ref().is_some_and(|replay| replay.run(r).is_ok())
                    && matches!(failed(r, &more), Verdict::Pass { .. })
            };
            report.hint = scene.and_then(|s| {
                guarded(|| hint::diagnose(rasterizer, rule, &s, &mut verify))
                    .ok()
                    .flatten()
            });
            report.message = Some(violation.to_string());
            report.details = violation.details.clone();
            report.counts = violation.counts.as_deref().copied();
            report.counterexample = Some(counterexample);
            if let (Some(dir), Some(pic)) = (&options.report_dir, &violation.picture) {
                let mut caption = vec![format!("{} on {}: {violation}", rule.id, profile.name)];
                caption.extend(violation.details.iter().skip(1).cloned());
                report.picture = write_picture(dir, &profile.name, rule.id, pic, &caption);
            }
        }
    }
    report
}

fn write_picture(
    dir: &Path,
    implementation: &str,
    id: &str,
    pic: &crate::violation::Picture,
    caption: &[String],
) -> Option<PathBuf> {
    let safe: String = implementation
        .chars()
        .map(|c| if c.is_alphanumeric() || c == '-' { c } else { '_' })
        .collect();
    let path = dir.join(format!("{safe}__{id}.png"));
    std::fs::create_dir_all(dir).ok()?;
    picture::save(pic, caption, &path).ok()?;
    Some(path)
}

/// Certifies `rasterizer` against every rule selected by `options`, calling `progress` after each.
pub fn certify(
    rasterizer: &mut dyn Rasterizer,
    options: &Options,
    mut progress: impl FnMut(&RuleReport),
) -> Report {
    let profile = ProfileReport::of(rasterizer);
    if let Some(refused) = refusal(rasterizer) {
        return report_of(profile, (Vec::new(), Vec::new()), Some(refused));
    }
    let run = |rule: &Rule| {
        let report = run_rule(rule, rasterizer, options);
        progress(&report);
        Ok::<_, std::convert::Infallible>(report)
    };
    let Ok(ran) = run_selected(options, run);
    report_of(profile, ran, None)
}

/// [`certify`] with one rule at a time on each of `rasterizers`, copies of one implementation
/// (say one `--exec` child each): the same report as [`certify`] on the first but for times,
/// the profile being the first's.
pub fn certify_with<R: Rasterizer + Send>(
    rasterizers: &mut [R],
    options: &Options,
    progress: impl FnMut(&RuleReport) + Send,
) -> Report {
    match rasterizers {
        [] => {
            let why = "no rasterizer was given to certify".to_owned();
            return report_of(ProfileReport::unknown(), (Vec::new(), Vec::new()), Some(why));
        }
        [only] => return certify(only, options, progress),
        [first, ..] => {
            if let Some(refused) = refusal(first) {
                return report_of(ProfileReport::of(first), (Vec::new(), Vec::new()), Some(refused));
            }
        }
    }
    let profile = ProfileReport::of(&rasterizers[0]);
    let workers: Vec<Mutex<&mut R>> = rasterizers.iter_mut().map(Mutex::new).collect();
    let progress = Mutex::new(progress);
    let run = |worker: usize, rule: &Rule| {
        // Each worker locks only its own rasterizer: never contended.
        let mut rasterizer = workers[worker].lock().unwrap_or_else(PoisonError::into_inner);
        let report = run_rule(rule, *rasterizer, options);
        drop(rasterizer);
        (progress.lock().unwrap_or_else(PoisonError::into_inner))(&report);
        Ok::<_, std::convert::Infallible>(report)
    };
    let Ok(ran) = run_selected_jobs(options, workers.len(), run);
    report_of(profile, ran, None)
}

/// A report of `profile`'s implementation: the rules run and those left unrun, or why none ran.
fn report_of(
    profile: ProfileReport,
    (rules, not_run): (Vec<RuleReport>, Vec<String>),
    refused: Option<String>,
) -> Report {
    Report {
        implementation: profile.name.clone(),
        profile,
        rules,
        not_run,
        refused,
    }
}

/// Why the suite refuses to judge `rasterizer` before any rule runs: a profile it cannot judge
/// ([`refrast::Profile::judgeable`]); `None` when it can. A panicking `profile()` is left to the rules,
/// which each report it.
#[must_use]
pub fn refusal(rasterizer: &dyn Rasterizer) -> Option<String> {
    let profile = guarded(|| rasterizer.profile()).ok()?;
    profile
        .judgeable()
        .err()
        .map(|why| format!("{why}; nothing was run"))
}

/// Part `index` of `count` (1-based, as `--shard 2/3` says): every `count`-th of the selected
/// rules in catalogue order, starting at the `index`-th, so that the parts are disjoint, cover
/// every rule, and do not depend on anything but the selection.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Shard {
    /// Which part, from 1.
    pub index: u32,
    /// How many parts.
    pub count: u32,
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `I/N` with 1 ≤ I ≤ N.
    fn from_str(text: &str) -> Result<Self, String> {
        let bad = || format!("'{text}' is not a shard; give I/N with 1 <= I <= N, e.g. 2/3");
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The rules `options` selects, in catalogue order: those matching any of its patterns (all
/// when there are none), then its shard's part of them.
#[must_use]
pub fn selected(options: &Options) -> Vec<Rule> {
    catalogue()
        .into_iter()
        .filter(|rule| options.rules.is_empty() || options.rules.iter().any(|p| matches(p, rule.id)))
        .enumerate()
        .filter(|(i, _)| {
            options
                .shard
                .is_none_or(|s| u32::try_from(*i).is_ok_and(|i| i % s.count == s.index - 1))
        })
        .map(|(_, rule)| rule)
        .collect()
}

/// Runs `run` on each rule `options` selects, in catalogue order, until one fails under
/// [`Options::fail_fast`] or `run` gives an error: the reports, and the IDs of rules left unrun.
pub fn run_selected<E>(
    options: &Options,
    mut run: impl FnMut(&Rule) -> Result<RuleReport, E>,
) -> Result<(Vec<RuleReport>, Vec<String>), E> {
    let selected = selected(options);
    let mut reports = Vec::new();
    for (i, rule) in selected.iter().enumerate() {
        let result = run(rule);
        let halts = halts(&result, options);
        reports.push(result?);
        if halts {
            return Ok((reports, not_run_after(&selected, i)));
        }
    }
    Ok((reports, Vec::new()))
}

/// [`run_selected`] with up to `jobs` rules running at once, on threads of this process: the
/// same reports in the same order, and the same rules left unrun, as one at a time (a rule
/// already running when an earlier one stops the run is dropped). `run` is told which of the
/// `jobs` workers (`0..jobs`) runs the rule, so each can own what it draws with.
pub fn run_selected_jobs<E: Send>(
    options: &Options,
    jobs: usize,
    run: impl Fn(usize, &Rule) -> Result<RuleReport, E> + Sync,
) -> Result<(Vec<RuleReport>, Vec<String>), E> {
    let selected = selected(options);
    let next = AtomicUsize::new(0);
    // The earliest rule, in catalogue order, after which no rule may start or be kept.
    let stop = AtomicUsize::new(usize::MAX);
    let slots: Vec<Mutex<Option<Result<RuleReport, E>>>> =
        selected.iter().map(|_| Mutex::new(None)).collect();
    thread::scope(|scope| {
        for worker in 0..jobs.clamp(1, selected.len().max(1)) {
            let (next, stop, slots, selected, run) = (&next, &stop, &slots, &selected, &run);
            scope.spawn(move || {
                loop {
                    // Rules are handed out in order, so every rule before `stop` has started.
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    if i >= selected.len() || i > stop.load(Ordering::SeqCst) {
                        break;
                    }
                    let result = run(worker, &selected[i]);
                    if halts(&result, options) {
                        stop.fetch_min(i, Ordering::SeqCst);
                    }
                    *slots[i].lock().unwrap_or_else(PoisonError::into_inner) = Some(result);
                }
            });
        }
    });
    let stop = stop.into_inner();
    let mut reports = Vec::new();
    for slot in slots.into_iter().take(stop.saturating_add(1)) {
        if let Some(result) = slot.into_inner().unwrap_or_else(PoisonError::into_inner) {
            reports.push(result?);
        }
    }
    let not_run = if stop < selected.len() {
        not_run_after(&selected, stop)
    } else {
        Vec::new()
    };
    Ok((reports, not_run))
}

/// Whether a rule's outcome ends the run: an error, or a failure under [`Options::fail_fast`].
fn halts<E>(result: &Result<RuleReport, E>, options: &Options) -> bool {
    result
        .as_ref()
        .map_or(true, |r| r.status.is_failure() && options.fail_fast)
}

/// The IDs of the selected rules after the `i`-th, which a stop at it leaves unrun.
fn not_run_after(selected: &[Rule], i: usize) -> Vec<String> {
    selected[i + 1..].iter().map(|r| r.id.to_owned()).collect()
}

#[cfg(test)]
mod tests {
    use refrast::Reference;

    use super::{Options, certify, certify_with, matches};

    /// Two copies certify as one does: the same rules, verdicts, cases and counterexamples.
    #[test]
    fn copies_certify_as_one() {
        let options = Options {
            cases: Some(16),
            rules: vec!["fill.*".to_owned(), "robust.*".to_owned()],
            ..Options::default()
        };
        let summary = |r: &crate::Report| {
            r.rules
                .iter()
                .map(|r| (r.id.clone(), r.status, r.cases, r.counterexample.clone()))
                .collect::<Vec<_>>()
        };
        let one = certify(&mut Reference::default(), &options, |_| {});
        let two = certify_with(
            &mut [Reference::default(), Reference::default()],
            &options,
            |_| {},
        );
        assert_eq!(summary(&two), summary(&one));
        assert_eq!(two.profile, one.profile);
        assert!(!one.rules.is_empty());
    }

    #[test]
    fn patterns_are_globs_or_prefixes() {
        assert!(matches("fill.*", "fill.mesh.exactly-once"));
        assert!(matches("fill", "fill.mesh.exactly-once"));
        assert!(matches("*.exact", "fill.top-left.exact"));
        assert!(matches("*mesh*", "clip.mesh.watertight"));
        assert!(!matches("depth.*", "fill.mesh.exactly-once"));
        assert!(!matches("*.exact", "fill.mesh.exactly-once"));
    }
}
