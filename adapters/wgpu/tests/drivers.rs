//! Mesa's lavapipe, llvmpipe and softpipe, each in a process of its own (softpipe is chosen by an
//! environment variable read when Mesa loads): the findings checked by hand (docs/certified.md,
//! "Findings"), then every rule, its verdict checked against `expectations/NAME.txt`.
//!
//! A driver that is not installed is skipped with its reason printed; with
//! `REFRAST_REQUIRE_DRIVERS=1` (set by `.ci/run`, which installs Mesa) it fails instead.

#[path = "common/verdicts.rs"]
mod common;
#[path = "drivers/findings.rs"]
mod findings;
#[path = "common/interpolation.rs"]
mod interpolation;
#[path = "drivers/lines.rs"]
mod lines;
#[path = "drivers/masks.rs"]
mod masks;
#[path = "drivers/resolved.rs"]
mod resolved;
#[path = "drivers/softpipe.rs"]
mod softpipe;

use std::time::Duration;

use refrast_conformance::Options;
use refrast_wgpu::Driver;

use common::{Certification, run};

/// Cases per rule: fewer than `.ci/run`'s defaults, so that `cargo test` stays short; the
/// verdicts that differ between the two are `may-fail` in the expectation files.
const CASES: u32 = 300;

/// The options of every pinned certification.
fn options() -> Options {
    Options {
        cases: Some(CASES),
        case_timeout: Duration::from_secs(60),
        ..Options::default()
    }
}

fn main() {
    run(&Certification {
        drivers: &[Driver::Lavapipe, Driver::Llvmpipe, Driver::Softpipe],
        required: "REFRAST_REQUIRE_DRIVERS",
        cases: CASES,
        options,
        findings: findings::findings,
    });
}
