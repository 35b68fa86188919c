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
//! Rules that do not apply to the profile are reported as ignored, never as passed.

use std::path::PathBuf;
use std::sync::Arc;

use libtest_mimic::{Arguments, Failed, Trial};
use refrast::Rasterizer;

use crate::certify::{Options, Status, run_rule};
use crate::rules::catalogue;
use crate::runner::DEFAULT_SEED;

/// Runs every rule against rasterizers made by `make`, as a test harness, then exits.
///
/// Case counts follow `PROPTEST_CASES` (else each rule's default); `REFRAST_SEED` sets the
/// seed; counterexample pictures go to `REFRAST_REPORT` (default `target/refrast-report`).
pub fn run_as_tests<R, F>(make: F) -> !
where
    R: Rasterizer + 'static,
    F: Fn() -> R + Send + Sync + 'static,
{
    let args = Arguments::from_args();
    let make = Arc::new(make);
    let profile = make().profile();
    let options = Arc::new(Options {
        cases: None,
        seed: std::env::var("REFRAST_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(DEFAULT_SEED),
        rule: None,
        report_dir: Some(
            std::env::var_os("REFRAST_REPORT")
                .map_or_else(|| PathBuf::from("target/refrast-report"), PathBuf::from),
        ),
    });
    let trials = catalogue()
        .into_iter()
        .map(|rule| {
            let ignored = rule.applies(&profile).is_err();
            let (id, family) = (rule.id, rule.family);
            let (make, options) = (Arc::clone(&make), Arc::clone(&options));
            Trial::test(id, move || {
                let mut r = make();
                let report = run_rule(&rule, &mut r, &options);
                match report.status {
                    Status::Pass | Status::NotApplicable => Ok(()),
                    Status::Fail => Err(Failed::from(failure_text(&report))),
                }
            })
            .with_kind(family.name())
            .with_ignored_flag(ignored)
        })
        .collect();
    libtest_mimic::run(&args, trials).exit()
}

/// A failed rule as a test failure message: what, the counts, the input as Rust, the picture.
#[must_use]
pub fn failure_text(report: &crate::certify::RuleReport) -> String {
    let mut text = format!(
        "rule {} failed (seed {}, {} cases, band {} subpixels): {}",
        report.id,
        report.seed,
        report.cases,
        report.tolerance_subpixels,
        report.message.as_deref().unwrap_or("")
    );
    if let Some(input) = &report.counterexample {
        text.push_str("\nshrunk counterexample:\n");
        text.push_str(input);
    }
    if let Some(p) = &report.picture {
        text.push_str(&format!("\npicture: {}", p.display()));
    }
    text
}
