//! SwiftShader by hand (docs/certified.md, "Findings"): every failure class of `refrast
//! certify --impl swiftshader` reduced to a minimal draw and pinned (`findings`), then every rule,
//! its verdict checked against `expectations/swiftshader.txt` under the measured profile. The
//! probes that measured that profile are library code now (`refrast_wgpu::probe`), their
//! choices pinned in `tests/measured.rs`.
//!
//! SwiftShader runs in a child process of its own: it is chosen by `VK_ICD_FILENAMES`, which the
//! Vulkan loader reads when it starts. Without it installed it is skipped with its reason
//! printed; with `REFRAST_REQUIRE_SWIFTSHADER=1` its absence fails instead.

#[path = "common/verdicts.rs"]
mod common;
#[path = "swiftshader/distances.rs"]
mod distances;
#[path = "swiftshader/findings.rs"]
mod findings;
#[path = "common/interpolation.rs"]
mod interpolation;
#[path = "swiftshader/lines.rs"]
mod lines;

use std::time::Duration;

use refrast::{ClipMode, Draw, Fragment, Rasterizer, Reference, ReferenceConfig, SubpixelBits, Viewport};
use refrast_conformance::Options;
use refrast_wgpu::Driver;

use common::{Certification, run};

/// Cases per rule; the verdicts that differ from `.ci/run`'s (each rule's default cases, two
/// minutes a rule) are `may-fail` in `expectations/swiftshader.txt`, which says why each
/// failure is what it is.
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
    run(&Certification {
        drivers: &[Driver::Swiftshader],
        required: "REFRAST_REQUIRE_SWIFTSHADER",
        cases: CASES,
        options,
        findings: |_, gpu| findings::swiftshader(gpu),
    });
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
