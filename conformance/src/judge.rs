//! One rule judged on one rasterizer: its property run, the verdict read under the claimed
//! specification's level, a hint, a picture; or one counterexample replayed.

use std::sync::Arc;
use std::time::{Duration, Instant};

use refrast::Rasterizer;

use crate::report::{CaseFile, Exhibit, Part, RuleReport, Status};
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

/// What to run, and how.
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
    /// Called with every input, shrinking included, before it is checked (for a progress
    /// display, and for the parent of a rule's child process to name the case a hang is on).
    pub announce: Option<Announce>,
    /// How long one case may take before a rule run in a child process ([`crate::isolate`])
    /// fails as hung.
    pub case_timeout: Duration,
    /// Wall time per rule after which no new case starts and shrinking stops, for slow
    /// implementations (a rasterizer in another language behind a pipe); `None` runs every case.
    pub budget: Option<Duration>,
    /// Stop at the first rule that fails: the rules after it are not run and are listed in
    /// [`crate::Report::not_run`] (for a quick answer, and for mutation testing).
    pub fail_fast: bool,
    /// The most data, in bytes, each rule's child process (and a `--exec` child) may allocate
    /// ([`refrast_pipe::contain`]); `None` sets no limit.
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
            announce: None,
            case_timeout: DEFAULT_CASE_TIMEOUT,
            budget: None,
            fail_fast: false,
            memory_limit: Some(refrast_pipe::contain::DEFAULT_MEMORY_LIMIT),
        }
    }
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

/// Runs one rule against `rasterizer` and reports it, with the files of a failure gathered
/// ([`RuleReport::exhibit`]) but not written.
pub fn run_rule(rule: &Rule, rasterizer: &mut dyn Rasterizer, options: &Options) -> RuleReport {
    let start = Instant::now();
    // Without a case to replay, every case is the rule's own: none can be unfit.
    let mut report = judge(rule, rasterizer, options, None).unwrap_or_else(|why| RuleReport {
        status: Status::Crash,
        message: Some(format!("the suite replayed a case it was not given: {why}")),
        ..RuleReport::new(rule, options.seed, 1)
    });
    report.seconds = start.elapsed().as_secs_f64();
    report
}

/// Replays one counterexample ([`CaseFile`]) on `rasterizer`: its rule's check on that case
/// alone, fitted to the rasterizer's profile, reported as a certification reports the rule
/// (message, details, hint, picture and the case again); an error when the file names no rule
/// or its case is not an input of that rule.
pub fn replay(
    case: &CaseFile,
    rasterizer: &mut dyn Rasterizer,
    options: &Options,
) -> Result<RuleReport, String> {
    let rule = catalogue()
        .into_iter()
        .find(|r| r.id == case.rule)
        .ok_or_else(|| format!("no rule is called '{}'; `refrast rules` lists them", case.rule))?;
    let start = Instant::now();
    let mut report = judge(&rule, rasterizer, options, Some(case))
        .map_err(|why| format!("the case is not an input of {}: {why}", rule.id))?;
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// [`run_rule`] without the clock; with `replay`, that one case instead of generated ones, and
/// then an error when the case is not an input of the rule's property.
fn judge(
    rule: &Rule,
    rasterizer: &mut dyn Rasterizer,
    options: &Options,
    replay: Option<&CaseFile>,
) -> Result<RuleReport, String> {
    let profile = guarded(|| rasterizer.profile());
    let band = profile.as_ref().map_or(1, |p| p.tolerance_subpixels.max(1));
    let mut report = RuleReport::new(rule, options.seed, band);
    let crash = |mut report: RuleReport, message: String| {
        report.status = Status::Crash;
        report.message = Some(message);
        Ok(report)
    };
    let profile = match profile {
        Ok(profile) => profile,
        Err(what) => return crash(report, format!("profile() panicked: {what}")),
    };
    if let Err(reason) = rule.applies(&profile) {
        report.status = Status::NotApplicable;
        report.message = Some(reason.to_owned());
        return Ok(report);
    }
    let cfg = RunConfig {
        cases: if replay.is_some() {
            1
        } else {
            cases_for(rule, options)
        },
        seed: options.seed,
        announce: options.announce,
        budget: options.budget,
        orient: !rule.keeps_winding,
        replay: replay.map(|c| Arc::new(c.case.clone())),
    };
    report.planned = cfg.cases;
    // What the claimed specification requires runs first where it requires only part of the
    // rule: a failure there is a failure; one only the whole rule finds is beyond it. A replay
    // runs the part its case failed.
    let level = rule.levels.of(profile.spec);
    // What the required part ran, said with a failure beyond it (its cases are not the rule's).
    let mut required_part = None;
    let (verdict, beyond) = match (level, replay.map(|c| c.part)) {
        (Level::Required, _) => ((rule.run)(rasterizer, &cfg), false),
        (Level::Partly { part, .. }, Some(Part::Required)) => (part(rasterizer, &cfg), false),
        (Level::Partly { .. }, Some(Part::Rule)) => ((rule.run)(rasterizer, &cfg), true),
        (Level::Partly { part, .. }, None) => match part(rasterizer, &cfg) {
            failed @ Verdict::Fail { .. } => (failed, false),
            Verdict::Pass { cases, budget_spent } => {
                required_part = Some(if budget_spent {
                    format!("; the required part passed {cases} cases before the time budget ran out")
                } else {
                    format!("; the required part passed all {cases} cases")
                });
                ((rule.run)(rasterizer, &cfg), true)
            }
            unfit @ Verdict::Unreadable(_) => (unfit, false),
        },
        (Level::Undefined(_) | Level::NotCovered(_), _) => ((rule.run)(rasterizer, &cfg), true),
    };
    // The property that failed: the required part's, or the whole rule's.
    let (failed, part): (Run, Part) = match level {
        Level::Partly { part, .. } if !beyond => (part, Part::Required),
        _ => (rule.run, Part::Rule),
    };
    match verdict {
        Verdict::Pass { cases, budget_spent } => {
            report.cases = cases;
            report.budget_spent = budget_spent;
        }
        Verdict::Unreadable(why) => return Err(why),
        Verdict::Fail {
            cases,
            counterexample,
            case,
            shrinking_cut,
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
            let mut verify = |r: &mut dyn Rasterizer| {
                let more = RunConfig {
                    cases: cases_for(rule, options).min(HINT_CASES),
                    announce: None,
                    replay: None,
                    ..cfg.clone()
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
            report.shrinking_cut = shrinking_cut;
            report.case_file = case.map(|case| CaseFile {
                rule: rule.id.to_owned(),
                part,
                implementation: profile.name.clone(),
                seed: options.seed,
                case: *case,
            });
            let mut caption = vec![format!("{} on {}: {violation}", rule.id, profile.name)];
            caption.extend(violation.details.iter().skip(1).cloned());
            report.exhibit = Some(Exhibit::new(
                &profile.name,
                rule.id,
                violation.picture.map(|p| *p),
                caption,
            ));
        }
    }
    Ok(report)
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
