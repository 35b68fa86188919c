//! Mesa's lavapipe, llvmpipe and softpipe, each in a process of its own (softpipe is chosen by an
//! environment variable read when Mesa loads): the findings checked by hand (docs/certified.md,
//! "Findings"), then every rule, its verdict checked against `expectations/NAME.txt`.
//!
//! A driver that is not installed is skipped with its reason printed; with
//! `REFRAST_REQUIRE_DRIVERS=1` (set by `.ci/run`, which installs Mesa) it fails instead.

use std::process::Command;
use std::time::Duration;

#[path = "common/verdicts.rs"]
mod common;
#[path = "drivers/findings.rs"]
mod findings;

use refrast::Rasterizer;
use refrast_conformance::Options;
use refrast_conformance::isolate::{certify_isolated_jobs, serve_rule};
use refrast_wgpu::{Driver, Gpu};

use common::{jobs, moved, tally};
use findings::findings;

const RULE_ENV: &str = "WGPU_TEST_RULE";
const DRIVER_ENV: &str = "WGPU_TEST_DRIVER";
const FINDINGS_ENV: &str = "WGPU_TEST_FINDINGS";
/// The exit code of a findings child whose driver is missing.
const UNAVAILABLE: i32 = 3;

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

/// The driver `--impl` calls `name`.
fn driver(name: &str) -> Driver {
    Driver::ALL
        .into_iter()
        .find(|d| d.name() == name)
        .expect("a driver name")
}

fn main() {
    if let (Ok(id), Ok(name)) = (std::env::var(RULE_ENV), std::env::var(DRIVER_ENV)) {
        let d = driver(&name);
        let served = serve_rule(
            &id,
            || Ok(Box::new(Gpu::new(d)?) as Box<dyn Rasterizer>),
            &options(),
        );
        std::process::exit(if served { 0 } else { 2 });
    }
    if let Ok(name) = std::env::var(FINDINGS_ENV) {
        let mut gpu = match Gpu::new(driver(&name)) {
            Ok(gpu) => gpu,
            Err(why) => {
                println!("{why}");
                std::process::exit(UNAVAILABLE);
            }
        };
        findings(driver(&name), &mut gpu);
        std::process::exit(0);
    }
    let required = std::env::var("REFRAST_REQUIRE_DRIVERS").as_deref() == Ok("1");
    let exe = std::env::current_exe().expect("this test binary");
    let with_env = |d: Driver| {
        let mut c = Command::new(&exe);
        for (name, value) in d.env() {
            c.env(name, value);
        }
        c
    };
    let mut moved = Vec::new();
    for d in [Driver::Lavapipe, Driver::Llvmpipe, Driver::Softpipe] {
        let output = with_env(d)
            .env(FINDINGS_ENV, d.name())
            .output()
            .expect("the child starts");
        let stdout = String::from_utf8_lossy(&output.stdout);
        if output.status.code() == Some(UNAVAILABLE) {
            assert!(
                !required,
                "{}: REFRAST_REQUIRE_DRIVERS is set, but {stdout}",
                d.name()
            );
            println!("{}: SKIPPED: {stdout}", d.name());
            continue;
        }
        assert!(
            output.status.success(),
            "{}: a hand-checked finding moved:\n{stdout}\n{}",
            d.name(),
            String::from_utf8_lossy(&output.stderr)
        );
        print!("{stdout}");
        moved.extend(verdicts(d, &|rule| {
            let mut c = with_env(d);
            c.env(RULE_ENV, rule.id).env(DRIVER_ENV, d.name());
            c
        }));
    }
    assert!(moved.is_empty(), "verdicts moved:\n{}", moved.join("\n"));
}

/// Certifies `d` rule by rule in child processes; the rules whose verdict is not as expected.
fn verdicts(d: Driver, command: &(dyn Fn(&refrast_conformance::Rule) -> Command + Sync)) -> Vec<String> {
    let report = certify_isolated_jobs(command, &options(), jobs(), |_| {})
        .expect("the driver was there a moment ago");
    println!("{}", tally(d.name(), &report, CASES));
    moved(d.name(), &report)
}
