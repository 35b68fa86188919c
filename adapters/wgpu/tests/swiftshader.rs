//! SwiftShader by hand (README, "Certified implementations"): every failure class of `refrast
//! certify --impl swiftshader` reduced to a minimal draw and pinned (`findings`), and the probes
//! that measure what neither Vulkan nor the driver reports (`probes`: tie rule, snapping near
//! ties, ties to even, guard band, interpolation precision), run on SwiftShader and on lavapipe
//! beside it, each on its own grid.
//!
//! Each driver runs in a child process of its own: SwiftShader is chosen by `VK_ICD_FILENAMES`,
//! which the Vulkan loader reads when it starts. A driver that is not installed is skipped with
//! its reason printed; with `REFRAST_REQUIRE_SWIFTSHADER=1` a missing SwiftShader fails instead
//! (`.ci/run` installs Mesa but not Chromium, so `REFRAST_REQUIRE_DRIVERS` does not ask for it).

#[path = "swiftshader/findings.rs"]
mod findings;
#[path = "swiftshader/probes.rs"]
mod probes;

use std::process::Command;
use std::time::Duration;

use refrast::{
    ClipMode, Draw, Fragment, Rasterizer, Reference, ReferenceConfig, Snapping, SubpixelBits, Viewport,
};
use refrast_conformance::isolate::{certify_isolated, serve_rule};
use refrast_conformance::{Options, Status};
use refrast_wgpu::{Driver, Gpu};

const CHILD_ENV: &str = "SWIFTSHADER_TEST_DRIVER";
const RULE_ENV: &str = "SWIFTSHADER_TEST_RULE";
/// The exit code of a child whose driver is missing.
const UNAVAILABLE: i32 = 3;
/// SwiftShader's failures at [`CASES`] cases a rule, each a class checked by hand (`findings`);
/// `n/a`: `fill.guard-band.exact` and `clip.gl-range.matches-raycast`; every other rule passes.
/// At the default cases also `bary.range.unit`, `bary.screen.reconstructs-sample`,
/// `bary.equal-w.affine` (f32 planes, finding 5), `depth.range.vertices` (a near cut the rule
/// should not draw, finding 6) and `clip.interior.matches-raycast` (w = 0, finding 1) fail.
const FAIL: &str = "bary.perspective.matches-raycast depth.screen-linear.matches-raycast \
    robust.non-finite.discarded robust.bit-patterns.sane-output robust.output.well-formed";
const NOT_APPLICABLE: &str = "fill.guard-band.exact clip.gl-range.matches-raycast";
const CASES: u32 = 300;

/// The options of the pinned certification: a budget per rule, since shrinking
/// `robust.bit-patterns.sane-output` on SwiftShader takes minutes (its failure comes at case 2).
fn options() -> Options {
    Options {
        cases: Some(CASES),
        case_timeout: Duration::from_secs(60),
        budget: Some(Duration::from_secs(20)),
        ..Options::default()
    }
}

fn main() {
    if let Ok(id) = std::env::var(RULE_ENV) {
        let served = serve_rule(
            &id,
            || Ok(Box::new(Gpu::new(Driver::Swiftshader)?) as Box<dyn Rasterizer>),
            &options(),
        );
        std::process::exit(if served { 0 } else { 2 });
    }
    if let Ok(name) = std::env::var(CHILD_ENV) {
        let d = Driver::ALL
            .into_iter()
            .find(|d| d.name() == name)
            .expect("a driver name");
        let mut gpu = match Gpu::new(d) {
            Ok(gpu) => gpu,
            Err(why) => {
                println!("{why}");
                std::process::exit(UNAVAILABLE);
            }
        };
        if d == Driver::Swiftshader {
            findings::swiftshader(&mut gpu);
        }
        probes::run(d, &mut gpu);
        std::process::exit(0);
    }
    let required = std::env::var("REFRAST_REQUIRE_SWIFTSHADER").as_deref() == Ok("1");
    let exe = std::env::current_exe().expect("this test binary");
    for d in [Driver::Swiftshader, Driver::Lavapipe] {
        let mut child = Command::new(&exe);
        for (name, value) in d.env() {
            child.env(name, value);
        }
        let output = child.env(CHILD_ENV, d.name()).output().expect("the child starts");
        let stdout = String::from_utf8_lossy(&output.stdout);
        if output.status.code() == Some(UNAVAILABLE) {
            assert!(
                !(required && d == Driver::Swiftshader),
                "REFRAST_REQUIRE_SWIFTSHADER is set, but {stdout}"
            );
            println!("{}: SKIPPED: {stdout}", d.name());
            continue;
        }
        assert!(
            output.status.success(),
            "{}: a hand-checked finding or probe moved:\n{stdout}\n{}",
            d.name(),
            String::from_utf8_lossy(&output.stderr)
        );
        print!("{stdout}");
        if d == Driver::Swiftshader {
            verdicts(&|rule| {
                let mut c = Command::new(&exe);
                for (name, value) in d.env() {
                    c.env(name, value);
                }
                c.env(RULE_ENV, rule.id);
                c
            });
        }
    }
}

/// Certifies SwiftShader rule by rule in child processes; each verdict must be the pinned one.
fn verdicts(command: &dyn Fn(&refrast_conformance::Rule) -> Command) {
    let report = certify_isolated(command, &options(), |_| {}).expect("SwiftShader was there a moment ago");
    let (pass, fail, na) = report.tally();
    println!("swiftshader: {pass} passed, {fail} failed, {na} not applicable ({CASES} cases per rule)");
    let listed = |list: &str, id: &str| list.split_whitespace().any(|f| f == id);
    let expected = |id: &str| {
        if listed(FAIL, id) {
            Status::Fail
        } else if listed(NOT_APPLICABLE, id) {
            Status::NotApplicable
        } else {
            Status::Pass
        }
    };
    let wrong: Vec<String> = report
        .rules
        .iter()
        .filter(|r| r.status != expected(&r.id))
        .map(|r| {
            format!(
                "{}: expected {}, got {} ({:?})",
                r.id,
                expected(&r.id).label(),
                r.status.label(),
                r.message
            )
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "swiftshader's verdicts moved:\n{}",
        wrong.join("\n")
    );
}

/// The driver's grid: its subpixel bits.
pub fn bits_of(gpu: &Gpu) -> u8 {
    match gpu.profile().snapping {
        Snapping::Grid(bits) => bits,
        Snapping::Float => panic!("a Vulkan driver snaps"),
    }
}

/// A draw of `positions` three at a time on a `width`×`height` target, far clipping on (WebGPU
/// cannot turn it off).
pub fn draw(width: u32, height: u32, positions: Vec<[f32; 4]>) -> Draw {
    let n = u32::try_from(positions.len() / 3).expect("a few triangles");
    let triangles = (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut draw = Draw::new(
        Viewport::new(width, height).expect("a viewport"),
        positions,
        triangles,
    );
    draw.state.clip_far = true;
    draw
}

/// The reference's fragments on a `bits` grid, top-left, clipping x/y at the guard band
/// (`GuardBand`: exact for every triangle the viewport's 8192-px band holds) or the viewport.
pub fn reference(bits: u8, clip: ClipMode, draw: &Draw) -> Vec<Fragment> {
    Reference::new(ReferenceConfig {
        subpixel_bits: SubpixelBits::new(bits).expect("1 to 8 bits"),
        clip,
        ..ReferenceConfig::default()
    })
    .rasterize(draw)
    .expect("the reference draws")
}

/// The fragments at pixel `(x, y)`.
pub fn at(frags: &[Fragment], x: u32, y: u32) -> Vec<Fragment> {
    frags.iter().filter(|f| (f.x, f.y) == (x, y)).copied().collect()
}

/// Clip-space position of framebuffer point `(x, y)` (pixels, y down) at depth `z` and `w`:
/// exact when `w` is a power of two and the point is on a grid of at most 16 bits.
pub fn clip_of(width: u32, height: u32, x: f64, y: f64, z: f64, w: f32) -> [f32; 4] {
    let w64 = f64::from(w);
    let nx = 2.0 * x / f64::from(width) - 1.0;
    let ny = 1.0 - 2.0 * y / f64::from(height);
    [(nx * w64) as f32, (ny * w64) as f32, (z * w64) as f32, w]
}

/// Perspective-correct and screen-space barycentrics, in f64, at framebuffer point `s` of the
/// triangle with framebuffer vertices `p` (as snapped) and clip `w`.
pub fn exact_barycentrics(p: [[f64; 2]; 3], w: [f64; 3], s: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let area =
        |a: [f64; 2], b: [f64; 2], c: [f64; 2]| (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let whole = area(p[0], p[1], p[2]);
    let screen = [
        area(s, p[1], p[2]) / whole,
        area(p[0], s, p[2]) / whole,
        area(p[0], p[1], s) / whole,
    ];
    let over_w = [screen[0] / w[0], screen[1] / w[1], screen[2] / w[2]];
    let sum: f64 = over_w.iter().sum();
    (over_w.map(|v| v / sum), screen)
}

/// The largest difference of two weight triples.
pub fn apart(a: [f32; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (f64::from(a[k]) - b[k]).abs()).fold(0.0, f64::max)
}
