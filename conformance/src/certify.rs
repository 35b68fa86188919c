//! Certification: every applicable rule against one rasterizer, summed up as a report.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::thread;

use refrast::Rasterizer;

use crate::judge::{Options, run_rule};
use crate::report::{ProfileReport, Report, RuleReport};
use crate::rules::{Rule, catalogue};
use crate::runner::guarded;

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

/// Certifies `rasterizer` against every rule selected by `options`, calling `progress` after each
/// with its report, which it may complete (say, with the paths [`RuleReport::save_exhibit`] sets).
///
/// ```
/// use refrast::Reference;
/// use refrast_conformance::{Options, certify};
///
/// let options = Options { rules: vec!["fill.top-left.exact".into()], cases: Some(8), ..Options::default() };
/// let folder = std::env::temp_dir().join("my-refrast-report");
/// let report = certify(&mut Reference::default(), &options, |rule| {
///     // A failure's picture and case, written where this program wants them.
///     if let Err(why) = rule.save_exhibit(&folder) {
///         eprintln!("warning: {why}");
///     }
/// });
/// assert!(report.passed(), "{report:#?}");
/// ```
pub fn certify(
    rasterizer: &mut dyn Rasterizer,
    options: &Options,
    mut progress: impl FnMut(&mut RuleReport),
) -> Report {
    let profile = ProfileReport::of(rasterizer);
    if let Some(refused) = refusal(rasterizer) {
        return report_of(profile, (Vec::new(), Vec::new()), Some(refused));
    }
    let run = |rule: &Rule| {
        let mut report = run_rule(rule, rasterizer, options);
        progress(&mut report);
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
    progress: impl FnMut(&mut RuleReport) + Send,
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
        let mut report = run_rule(rule, *rasterizer, options);
        drop(rasterizer);
        (progress.lock().unwrap_or_else(PoisonError::into_inner))(&mut report);
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
