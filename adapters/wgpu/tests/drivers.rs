//! Mesa's lavapipe, llvmpipe and softpipe, each in a process of its own (softpipe is chosen by an
//! environment variable read when Mesa loads): the findings checked by hand (README, "Certified
//! implementations"), then every rule, its verdict pinned.
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
use refrast_conformance::isolate::{certify_isolated, serve_rule};
use refrast_wgpu::{Driver, Gpu};

use common::{Pinned, tally};
use findings::findings;

const RULE_ENV: &str = "WGPU_TEST_RULE";
const DRIVER_ENV: &str = "WGPU_TEST_DRIVER";
const FINDINGS_ENV: &str = "WGPU_TEST_FINDINGS";
/// The exit code of a findings child whose driver is missing.
const UNAVAILABLE: i32 = 3;

/// The verdicts at [`CASES`] cases a rule under each driver's measured profile
/// (`tests/measured.rs`): Vulkan for lavapipe, OpenGL for llvmpipe and softpipe (README,
/// "Certified implementations", for each failure).
fn pinned(d: Driver) -> Pinned {
    match d {
        Driver::Lavapipe => Pinned {
            fail: LAVAPIPE_FAIL,
            beyond: LAVAPIPE_BEYOND,
            not_applicable: NOT_APPLICABLE,
        },
        Driver::Softpipe => Pinned {
            fail: SOFTPIPE_FAIL,
            beyond: SOFTPIPE_BEYOND,
            not_applicable: SOFTPIPE_NOT_APPLICABLE,
        },
        _ => Pinned {
            fail: LLVMPIPE_FAIL,
            beyond: MESA_BEYOND,
            not_applicable: NOT_APPLICABLE,
        },
    }
}

// How each moved from the pins of the hand-written profiles (8-bit grid, snapping to nearest,
// 8 bits of precision; every failure a failure), and why:
// - `bary.sum.one` now fails, at case 5: the corner finding (NaN screen weights, Mesa's clipper).
//   It fails the same at 1ca24fb under the old profiles (checked); the old pin was stale.
// - `bary.range.unit` (pass → fail), `bary.screen.reconstructs-sample`, `bary.equal-w.affine`
//   (fail): NaN screen weights on clipped triangles near the viewport (the clipper's 0/0,
//   findings "noperspective outputs" and "a corner of the view volume"). Vulkan and OpenGL
//   bound no interpolation error far out, but a NaN is no convex combination of the polygon's
//   vertex values, and near the viewport the values are required (docs/levels.md).
// - `robust.bit-patterns.sane-output` (lavapipe, llvmpipe) still fails: fragments outside the
//   framebuffer, which the scissor forbids whatever the input (the first Mesa finding); the
//   snapped wedge's depth outside [0, 1] is beyond Vulkan and OpenGL ("z_f is undefined").
// - lavapipe's `robust.non-finite.discarded` (w = +∞ drawn): beyond, as Vulkan leaves it
//   undefined; it now fails at case 24.
// - softpipe: no grid and no tie rule measured (float edges), so `fill.top-left.exact` and
//   `fill.brute-force.exact` stay n/a; its `robust.bit-patterns.sane-output` failure at 300 cases
//   is the w = 0 finding with a vertex at 1.9·10¹⁴ (beyond 2³²): beyond. At the default cases
//   `clip.mesh.watertight`, `meta.rotation.same-coverage` and `meta.reversal.flips-facing` still
//   fail (README); the last two are pinned through the weights-summing-to-0 finding.
const LLVMPIPE_FAIL: &str = "bary.sum.one bary.range.unit bary.screen.reconstructs-sample bary.equal-w.affine \
    robust.bit-patterns.sane-output";
const LAVAPIPE_FAIL: &str = LLVMPIPE_FAIL;
const MESA_BEYOND: &str = "";
const LAVAPIPE_BEYOND: &str = "robust.non-finite.discarded";
const SOFTPIPE_FAIL: &str = "fill.mesh.exactly-once fill.fan.exactly-once fill.projected-mesh.exactly-once \
    bary.sum.one bary.range.unit bary.screen.reconstructs-sample bary.equal-w.affine";
const SOFTPIPE_BEYOND: &str = "robust.bit-patterns.sane-output";
const NOT_APPLICABLE: &str = "fill.guard-band.exact clip.gl-range.matches-raycast";
/// Softpipe claims no grid and no tie rule: no exact rule applies.
const SOFTPIPE_NOT_APPLICABLE: &str =
    "fill.guard-band.exact clip.gl-range.matches-raycast fill.top-left.exact fill.brute-force.exact";
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

/// Certifies `d` rule by rule in child processes; the rules whose verdict is not the pinned one.
fn verdicts(d: Driver, command: &dyn Fn(&refrast_conformance::Rule) -> Command) -> Vec<String> {
    let report = certify_isolated(command, &options(), |_| {}).expect("the driver was there a moment ago");
    println!("{}", tally(d.name(), &report, CASES));
    pinned(d)
        .moved(&report)
        .into_iter()
        .map(|m| format!("{}: {m}", d.name()))
        .collect()
}
