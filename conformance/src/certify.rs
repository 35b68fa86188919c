//! Certification: every applicable rule against one rasterizer, summed up as a report.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use refrast::{Features, FillConvention, Profile, Rasterizer, SnapAccuracy};
use serde::{Deserialize, Serialize};

use crate::picture;
use crate::rules::{Family, Kind, Level, Rule, catalogue, hint};
use crate::runner::{Announce, DEFAULT_SEED, RunConfig, Verdict, guarded};
use crate::violation::Counts;

/// How long one case may take by default: far more than any correct rasterizer needs for the
/// suite's small scenes (a GPU through an API takes milliseconds), short enough that a hang
/// costs a run little.
pub const DEFAULT_CASE_TIMEOUT: Duration = Duration::from_secs(20);

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
    /// Only rules whose ID matches this glob (`*` matches anything; no `*` means a prefix).
    pub rule: Option<String>,
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
}

impl Default for Options {
    fn default() -> Self {
        Self {
            cases: None,
            scale: 1,
            seed: DEFAULT_SEED,
            rule: None,
            report_dir: None,
            announce: None,
            case_timeout: DEFAULT_CASE_TIMEOUT,
            budget: None,
            fail_fast: false,
        }
    }
}

/// A rule's outcome.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Status {
    /// Every case held.
    #[serde(rename = "pass")]
    Pass,
    /// A case failed.
    #[serde(rename = "fail")]
    Fail,
    /// The rule does not apply to the profile.
    #[serde(rename = "n/a")]
    NotApplicable,
    /// A case failed, on something the specification the profile claims does not require
    /// ([`RuleReport::spec_note`] says why): not a failure of conformance, and not a pass.
    #[serde(rename = "beyond-spec")]
    BeyondSpec,
}

impl Status {
    /// As printed: `pass`, `FAIL`, `n/a`, `BEYOND` (beyond the claimed specification).
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::Fail => "FAIL",
            Self::NotApplicable => "n/a",
            Self::BeyondSpec => "BEYOND",
        }
    }
}

/// One rule's line in the report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RuleReport {
    /// The rule's ID.
    pub id: String,
    /// Its family.
    pub family: Family,
    /// Invariant or exact.
    pub kind: Kind,
    /// Pass, fail or not applicable.
    pub status: Status,
    /// Cases tried (0 when not applicable): up to the failing one, or fewer than planned when
    /// the time budget ran out.
    pub cases: u32,
    /// Cases the rule would have tried (0 when not applicable).
    #[serde(default)]
    pub planned: u32,
    /// Whether the time budget ran out before every planned case was tried.
    #[serde(default)]
    pub budget_spent: bool,
    /// The generator's seed.
    pub seed: u64,
    /// The tolerance band used, in subpixels.
    pub tolerance_subpixels: u32,
    /// Why it failed, or why it does not apply.
    pub message: Option<String>,
    /// The numbers behind a failure, one line per wrong sample (the first few).
    #[serde(default)]
    pub details: Vec<String>,
    /// Sample tallies of a failed coverage check.
    pub counts: Option<Counts>,
    /// For [`Status::BeyondSpec`]: what the claimed specification says instead, with its sentence.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spec_note: Option<String>,
    /// Where the failure has the shape of a misdeclared profile, one line saying so, with the
    /// bug that looks the same.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hint: Option<String>,
    /// The shrunk failing input, as Rust.
    pub counterexample: Option<String>,
    /// The counterexample picture, if one was written.
    pub picture: Option<PathBuf>,
    /// Seconds the rule took where it ran (in its child process, for an isolated rule; from the
    /// parent's side when the child died without a report).
    #[serde(default)]
    pub seconds: f64,
}

/// The profile as the report prints it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProfileReport {
    /// Declared name.
    pub name: String,
    /// What the implementation reports itself to be ([`Rasterizer::about`]).
    #[serde(default)]
    pub about: String,
    /// Snapping: a grid's bits, or none.
    pub snapping: String,
    /// Tie rule on edges, or none.
    pub fill: String,
    /// Depth convention.
    pub depth: String,
    /// Tolerance band in grid steps, as declared.
    pub tolerance_subpixels: u32,
    /// The band used, in pixels.
    pub band_px: f64,
    /// Optional abilities declared, and the supported values of each draw-state setting.
    pub features: Vec<String>,
    /// The specification it claims to follow ([`refrast::Spec::title`]).
    #[serde(default)]
    pub spec: String,
}

impl ProfileReport {
    /// The report of `rasterizer`'s profile, with what it says about itself; a panic in either
    /// is reported as the name.
    #[must_use]
    pub fn of(rasterizer: &dyn Rasterizer) -> Self {
        match guarded(|| (rasterizer.profile(), rasterizer.about())) {
            Ok((profile, about)) => Self {
                about,
                ..Self::from(&profile)
            },
            Err(what) => Self {
                name: format!("unknown (profile() or about() panicked: {what})"),
                ..Self::unknown()
            },
        }
    }
}

impl From<&Profile> for ProfileReport {
    fn from(p: &Profile) -> Self {
        Self {
            name: p.name.clone(),
            about: String::new(),
            snapping: p.snapping.to_string(),
            fill: fill_name(p.fill).to_owned(),
            depth: format!("{:?}", p.depth),
            tolerance_subpixels: p.tolerance_subpixels,
            band_px: p.band_px(),
            features: feature_list(&p.features),
            spec: p.spec.title().to_owned(),
        }
    }
}

impl ProfileReport {
    /// A profile nobody reported (every rule's process died before it could).
    #[must_use]
    pub fn unknown() -> Self {
        Self {
            name: "unknown (no rule's process reported a profile)".into(),
            about: String::new(),
            snapping: String::new(),
            fill: String::new(),
            depth: String::new(),
            tolerance_subpixels: 1,
            band_px: 0.0,
            features: Vec::new(),
            spec: String::new(),
        }
    }
}

/// A tie rule as reports print it.
#[must_use]
pub fn fill_name(fill: Option<FillConvention>) -> &'static str {
    fill.map_or("no tie rule", FillConvention::name)
}

/// The abilities a profile declares, then each setting's supported values.
#[must_use]
pub fn feature_list(f: &Features) -> Vec<String> {
    let abilities = [
        (f.perspective_barycentrics, "perspective-barycentrics"),
        (f.screen_barycentrics, "screen-barycentrics"),
        (f.depth_test, "depth-test"),
        (f.ties_to_even, "ties-to-even"),
        (f.snap == SnapAccuracy::WithinOneStep, "snap within one step"),
        (f.zero_area_before_clipping, "zero-area-before-clipping"),
    ];
    let mut list: Vec<String> = abilities
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, name)| (*name).to_owned())
        .collect();
    match f.guard_band {
        0 => {}
        u32::MAX => list.push("guard-band unbounded".to_owned()),
        px => list.push(format!("guard-band {px} px")),
    }
    list.push(format!("cull {:?}", f.cull_modes));
    list.push(format!("front faces {:?}", f.front_faces));
    list.push(format!("compare {:?}", f.compare_ops));
    list.push(format!("depth writes {:?}", f.depth_writes));
    list.push(format!("far clipping {:?}", f.far_clipping));
    list.push(format!("depth ranges {:?}", f.depth_ranges));
    list
}

/// The whole certification of one implementation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The implementation's name.
    pub implementation: String,
    /// Its declared profile.
    pub profile: ProfileReport,
    /// One entry per rule run.
    pub rules: Vec<RuleReport>,
    /// The selected rules left unrun after a failure under [`Options::fail_fast`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_run: Vec<String>,
    /// Why no rule ran: a profile the suite cannot judge ([`Profile::judgeable`]), with what to
    /// declare instead. A refused implementation has not passed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refused: Option<String>,
}

impl Report {
    /// Whether it was judged and every applicable rule passed.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.refused.is_none() && self.rules.iter().all(|r| r.status != Status::Fail)
    }

    /// How many rules failed only on what the claimed specification does not require.
    #[must_use]
    pub fn beyond_spec(&self) -> usize {
        self.rules
            .iter()
            .filter(|r| r.status == Status::BeyondSpec)
            .count()
    }

    /// How many rules passed, failed, and did not apply ([`Report::beyond_spec`] counts the rest).
    #[must_use]
    pub fn tally(&self) -> (usize, usize, usize) {
        let n = |s| self.rules.iter().filter(|r| r.status == s).count();
        (n(Status::Pass), n(Status::Fail), n(Status::NotApplicable))
    }
}

/// Whether a rule ID matches a pattern: a glob with `*`, or a prefix when there is none.
#[must_use]
pub fn matches(pattern: &str, id: &str) -> bool {
    if !pattern.contains('*') {
        return id.starts_with(pattern);
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
            report.status = Status::Fail;
            report.message = Some(format!("profile() panicked: {what}"));
            return report;
        }
    };
    if let Err(reason) = rule.applies(&profile) {
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
    let (verdict, beyond) = match level {
        Level::Required => ((rule.run)(rasterizer, &cfg), false),
        Level::Partly { part, .. } => match part(rasterizer, &cfg) {
            failed @ Verdict::Fail { .. } => (failed, false),
            Verdict::Pass { .. } => ((rule.run)(rasterizer, &cfg), true),
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
        } => {
            report.cases = cases;
            report.status = Status::Fail;
            if beyond && let Some(note) = level.note() {
                report.status = Status::BeyondSpec;
                report.spec_note = Some(format!("not required by {}: {note}", profile.spec.title()));
            }
            report.hint = scene.and_then(|s| guarded(|| hint::diagnose(rasterizer, rule, &s)).ok().flatten());
            report.message = Some(violation.to_string());
            report.details = violation.details.clone();
            report.counts = violation.counts;
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
        return Report {
            implementation: profile.name.clone(),
            profile,
            rules: Vec::new(),
            not_run: Vec::new(),
            refused: Some(refused),
        };
    }
    let run = |rule: &Rule| {
        let report = run_rule(rule, rasterizer, options);
        progress(&report);
        Ok::<_, std::convert::Infallible>(report)
    };
    let Ok((rules, not_run)) = run_selected(options, run);
    Report {
        implementation: profile.name.clone(),
        profile,
        rules,
        not_run,
        refused: None,
    }
}

/// Why the suite refuses to judge `rasterizer` before any rule runs: a profile it cannot judge
/// ([`Profile::judgeable`]); `None` when it can. A panicking `profile()` is left to the rules,
/// which each report it.
#[must_use]
pub fn refusal(rasterizer: &dyn Rasterizer) -> Option<String> {
    let profile = guarded(|| rasterizer.profile()).ok()?;
    profile
        .judgeable()
        .err()
        .map(|why| format!("{why}; nothing was run"))
}

/// Runs `run` on each rule `options` selects, in catalogue order, until one fails under
/// [`Options::fail_fast`] or `run` gives an error: the reports, and the IDs of rules left unrun.
pub fn run_selected<E>(
    options: &Options,
    mut run: impl FnMut(&Rule) -> Result<RuleReport, E>,
) -> Result<(Vec<RuleReport>, Vec<String>), E> {
    let selected: Vec<Rule> = catalogue()
        .into_iter()
        .filter(|rule| options.rule.as_deref().is_none_or(|p| matches(p, rule.id)))
        .collect();
    let mut reports = Vec::new();
    for (i, rule) in selected.iter().enumerate() {
        let report = run(rule)?;
        let failed = report.status == Status::Fail;
        reports.push(report);
        if failed && options.fail_fast {
            let not_run = selected[i + 1..].iter().map(|r| r.id.to_owned()).collect();
            return Ok((reports, not_run));
        }
    }
    Ok((reports, Vec::new()))
}

#[cfg(test)]
mod tests {
    use super::matches;

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
