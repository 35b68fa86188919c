//! The catalogue as `cargo test` tests: one test per rule, named by its ID.
//!
//! In an outside crate, add a test target with `harness = false` (in `Cargo.toml`:
//! `[[test]] name = "conformance" harness = false`) whose `tests/conformance.rs` is one line
//! (here for the reference; pass your own constructor):
//!
//! ```text
//! fn main() { refrast_conformance::run_as_tests(refrast::Reference::default) }
//! ```
//!
//! `cargo test -- --list` then reads like the spec; `cargo test -- fill.` runs one family.
//! Rules that do not apply to the profile are reported as ignored, never as passed, even under
//! `--include-ignored` (then they say `n/a` and why).

use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use libtest_mimic::{Arguments, Completion, Failed, Trial};
use refrast::{Profile, Rasterizer};

use crate::isolate::{ChildRun, run_rule_isolated, serve_rule};
use crate::judge::{DEFAULT_CASE_TIMEOUT, Options, run_rule};
use crate::report::{RuleReport, Status};
use crate::rules::catalogue;
use crate::runner::{DEFAULT_SEED, guarded};
use crate::violation::plural;

/// Set in a child of the harness: the one rule it runs.
const RULE_ENV: &str = "REFRAST_RUN_RULE";

/// The options the environment asks for.
fn options_from_env() -> Options {
    let var = |name: &str| std::env::var(name).ok();
    Options {
        seed: var("REFRAST_SEED")
            .and_then(|s| s.parse().ok())
            .unwrap_or(DEFAULT_SEED),
        case_timeout: var("REFRAST_CASE_TIMEOUT")
            .and_then(|s| s.parse().ok())
            .map_or(DEFAULT_CASE_TIMEOUT, Duration::from_secs_f64),
        budget: var("REFRAST_BUDGET")
            .and_then(|s| s.parse().ok())
            .filter(|s: &f64| s.is_finite() && *s > 0.0)
            .map(Duration::from_secs_f64),
        ..Options::default()
    }
}

/// Where the failures' files go: `REFRAST_REPORT`, else `target/refrast-report`.
fn report_dir() -> PathBuf {
    std::env::var_os("REFRAST_REPORT").map_or_else(|| PathBuf::from("target/refrast-report"), PathBuf::from)
}

/// Runs every rule against rasterizers made by `make`, as a test harness, then exits.
///
/// Each rule runs in a child process (this test binary again), so a rasterizer that hangs,
/// aborts or crashes fails that rule with a message and the others still run.
///
/// Environment: `PROPTEST_CASES` sets the cases per rule (else each rule's default);
/// `REFRAST_SEED` the seed; `REFRAST_REPORT` where counterexample pictures go (default
/// `target/refrast-report`); `REFRAST_CASE_TIMEOUT` the seconds one case may take (default 20);
/// `REFRAST_BUDGET` the seconds per rule after which no new case starts (for a slow rasterizer,
/// such as a `refrast_pipe::Process` running Python); `REFRAST_FAIL_FAST=1` fails every rule not yet
/// started once one has failed, without running it (for a quick answer, and for mutation
/// testing); `REFRAST_IN_PROCESS=1` runs the rules in this process instead (for a debugger or a
/// profiler; a hang then hangs the test).
pub fn run_as_tests<R, F>(make: F) -> !
where
    R: Rasterizer + 'static,
    F: Fn() -> R + Send + Sync + 'static,
{
    let options = Arc::new(options_from_env());
    if let Ok(id) = std::env::var(RULE_ENV) {
        let served = serve_rule(&id, || Ok(Box::new(make())), &options);
        std::process::exit(if served { 0 } else { 2 });
    }
    let flag = |name: &str| std::env::var_os(name).is_some_and(|v| v != "0");
    let (in_process, fail_fast) = (flag("REFRAST_IN_PROCESS"), flag("REFRAST_FAIL_FAST"));
    let failed = Arc::new(AtomicBool::new(false));
    let args = Arguments::from_args();
    let make = Arc::new(make);
    let profile = match guarded(|| make().profile()) {
        Ok(declared) => declared,
        Err(what) => {
            eprintln!("error: the rasterizer's constructor or profile() panicked: {what}");
            std::process::exit(101);
        }
    };
    // A profile the suite cannot judge fails before any rule runs, with what to declare.
    if let Err(why) = profile.judgeable() {
        eprintln!(
            "error: refrast cannot judge {}: {why}; no rule was run",
            profile.name
        );
        std::process::exit(101);
    }
    let trials = catalogue()
        .into_iter()
        .map(|rule| {
            let ignored = rule.applies(&profile).is_err();
            let (id, family) = (rule.id, rule.family);
            let (make, options, failed) = (Arc::clone(&make), Arc::clone(&options), Arc::clone(&failed));
            let declared = profile.clone();
            Trial::ignorable_test(id, move || {
                if fail_fast && failed.load(Ordering::SeqCst) {
                    return Err(Failed::from(
                        "not run: an earlier rule failed (REFRAST_FAIL_FAST)",
                    ));
                }
                let mut report = if in_process {
                    run_rule(&rule, &mut make(), &options)
                } else {
                    let exe =
                        std::env::current_exe().map_err(|e| format!("cannot find this test binary: {e}"))?;
                    let mut child = Command::new(exe);
                    child.env(RULE_ENV, rule.id);
                    match run_rule_isolated(&rule, child, &options) {
                        ChildRun::Ran(report, _) => *report,
                        ChildRun::Unavailable(why) => {
                            return Err(Failed::from(format!(
                                "the rasterizer cannot be built in a child: {why}"
                            )));
                        }
                        ChildRun::Refused(why, _) => return Err(Failed::from(format!("refused: {why}"))),
                    }
                };
                // A file that cannot be written costs the failure its picture, not its verdict.
                if let Err(why) = report.save_exhibit(&report_dir()) {
                    eprintln!("warning: {why}");
                }
                match report.status {
                    Status::Pass => Ok(Completion::Completed),
                    Status::NotApplicable => Ok(Completion::ignored_with(format!(
                        "n/a: {}",
                        report.message.as_deref().unwrap_or("")
                    ))),
                    // Not a failure of conformance, not a pass: shown as ignored, with why.
                    Status::BeyondSpec => Ok(Completion::ignored_with(format!(
                        "beyond the specification ({}): {}",
                        report.spec_note.as_deref().unwrap_or(""),
                        failure_text(&report, &declared)
                    ))),
                    Status::Fail | Status::Crash | Status::Timeout | Status::Flake => {
                        failed.store(true, Ordering::SeqCst);
                        Err(Failed::from(failure_text(&report, &declared)))
                    }
                }
            })
            .with_kind(family.name())
            .with_ignored_flag(ignored)
        })
        .collect();
    libtest_mimic::run(&args, trials).exit()
}

/// A failed rule as a test failure message: what, the counts, the band in the words of
/// `profile` ([`band_words`]), the input as Rust, the picture.
#[must_use]
pub fn failure_text(report: &RuleReport, profile: &Profile) -> String {
    let mut text = format!(
        "rule {} failed ({}; seed {}, {} cases, {}): {}",
        report.id,
        report.status,
        report.seed,
        report.cases,
        band_words(profile),
        report.message.as_deref().unwrap_or("")
    );
    for detail in report.details.iter().skip(1) {
        text.push_str(&format!("\n  {detail}"));
    }
    if let Some(hint) = &report.hint {
        text.push_str(&format!("\nhint: {hint}"));
    }
    if let Some(input) = &report.counterexample {
        text.push_str("\nshrunk counterexample:\n");
        text.push_str(input);
    }
    if let Some(p) = &report.picture {
        text.push_str(&format!("\npicture: {}", p.display()));
    }
    text
}

/// The tolerance band in the words of `profile`: in subpixels of its grid, or for a float
/// profile (no grid) in the unit its tolerance counts.
#[must_use]
pub fn band_words(profile: &Profile) -> String {
    let (px, steps) = (profile.band_px(), profile.tolerance_subpixels.max(1) as usize);
    match profile.snapping.grid_bits() {
        Some(bits) => format!(
            "band {px} px: {} of the {bits}-bit grid",
            plural(steps, "subpixel")
        ),
        None => format!(
            "band {px} px: {steps} × {} px, a float profile's tolerance unit (no grid)",
            profile.snapping.unit_px()
        ),
    }
}

#[cfg(test)]
mod tests {
    use refrast::{Profile, Rasterizer, Reference, Snapping};

    use super::band_words;

    /// A float profile's band names no subpixel; a gridded one's names its grid.
    #[test]
    fn the_band_is_said_in_the_profiles_words() {
        let grid = Reference::default().profile();
        let float = Profile {
            snapping: Snapping::Float,
            ..grid.clone()
        };
        let said = band_words(&float);
        assert!(!said.contains("subpixel") && said.contains("no grid"), "{said}");
        assert!(band_words(&grid).contains("subpixel"), "{}", band_words(&grid));
    }
}
