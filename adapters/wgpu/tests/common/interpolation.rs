//! Where a driver evaluates a `sample`-qualified perspective input, shared by the lavapipe and
//! SwiftShader findings (docs/certified.md, "a sample's perspective divide at the pixel
//! centre"): each sample fragment's barycentrics set against the perspective-correct formula
//! with its numerator and its `1/w` denominator evaluated at chosen points.

use refrast::{Draw, Fragment, Viewport};

/// A triangle well inside a 16×16 target at 4 samples with `w` of 0.25, 1 and 4, so that
/// `1/w` varies across a pixel by up to a few percent.
pub fn perspective_triangle() -> Draw {
    let clip = |x: f32, y: f32, z: f32, w: f32| [x * w, y * w, z * w, w];
    let mut draw = Draw::new(
        Viewport::new(16, 16).expect("a viewport"),
        vec![
            clip(-0.9, -0.9, 0.3, 0.25),
            clip(0.9, -0.8, 0.5, 1.0),
            clip(-0.1, 0.9, 0.7, 4.0),
        ],
        vec![[0, 1, 2]],
    )
    .at_samples(4);
    draw.state.clip_far = true;
    draw
}

/// Vulkan's standard 4 sample locations, in pixels from the pixel's top-left corner.
const STANDARD_4: [[f64; 2]; 4] = [[0.375, 0.125], [0.875, 0.375], [0.125, 0.625], [0.625, 0.875]];

/// The largest difference, over `frags` of `draw`'s one triangle, between a fragment's
/// barycentrics and the perspective-correct formula with the numerators `λᵢ/wᵢ` at the sample
/// and the denominator `Σ λⱼ/wⱼ` at the sample (`centre` false: the formula itself) or at the
/// pixel centre (`centre` true), the vertices snapped to `bits` bits.
pub fn largest_misfit(draw: &Draw, frags: &[Fragment], bits: u32, centre: bool) -> f64 {
    largest_misfit_at(draw, frags, bits, centre, |f| Some(usize::from(f.sample) % 4))
}

/// [`largest_misfit`] with the numerators at the sample `location` names (the centre for none).
pub fn largest_misfit_at(
    draw: &Draw,
    frags: &[Fragment],
    bits: u32,
    centre: bool,
    location: impl Fn(&Fragment) -> Option<usize>,
) -> f64 {
    let (width, height) = (
        f64::from(draw.viewport.width()),
        f64::from(draw.viewport.height()),
    );
    let one = f64::from(1u32 << bits);
    let p = &draw.positions;
    let raster: Vec<[f64; 2]> = p
        .iter()
        .map(|v| {
            let (x, y, w) = (f64::from(v[0]), f64::from(v[1]), f64::from(v[3]));
            [
                ((x / w + 1.0) / 2.0 * width * one).round() / one,
                ((1.0 - y / w) / 2.0 * height * one).round() / one,
            ]
        })
        .collect();
    let w: Vec<f64> = p.iter().map(|v| f64::from(v[3])).collect();
    let lambda = |s: [f64; 2]| {
        let [a, b, c] = [raster[0], raster[1], raster[2]];
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let l0 = ((b[0] - s[0]) * (c[1] - s[1]) - (b[1] - s[1]) * (c[0] - s[0])) / area;
        let l1 = ((c[0] - s[0]) * (a[1] - s[1]) - (c[1] - s[1]) * (a[0] - s[0])) / area;
        [l0, l1, 1.0 - l0 - l1]
    };
    frags
        .iter()
        .map(|f| {
            let (x, y) = (f64::from(f.x), f64::from(f.y));
            let at = match location(f) {
                Some(sample) => [x + STANDARD_4[sample][0], y + STANDARD_4[sample][1]],
                None => [x + 0.5, y + 0.5],
            };
            let over = if centre { [x + 0.5, y + 0.5] } else { at };
            let (n, d) = (lambda(at), lambda(over));
            let denominator: f64 = (0..3).map(|i| d[i] / w[i]).sum();
            (0..3)
                .map(|i| (f64::from(f.barycentric[i]) - n[i] / w[i] / denominator).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// How far from 1 the barycentrics of `frags` sum, at most.
pub fn largest_sum_error(frags: &[Fragment]) -> f64 {
    frags
        .iter()
        .map(|f| (f.barycentric.iter().map(|&b| f64::from(b)).sum::<f64>() - 1.0).abs())
        .fold(0.0, f64::max)
}
