//! `lab003-area-average`: anti-aliasing by area averaging, as seed 003 (CS174, "Z-Buffer
//! Algorithm", its cons) describes it: a pixel's colour is the polygon's and the background's,
//! weighted by how much of the pixel's area the polygon covers.
//!
//! What the seed says, and what this module therefore does:
//!
//! - **The covered fraction** of each pixel: the projected polygon cut to the pixel's square
//!   (Sutherland–Hodgman in 2D, [`covered_part`]), its area by the shoelace formula, in
//!   `f64` on unsnapped coordinates. This is the "expensive" pixel area calculation.
//! - **A fraction told as samples**: refrast's contract has no fractional coverage, so at `n`
//!   samples per pixel the pixel reports `round(n · fraction)` covered samples ([`covered_count`]),
//!   the fraction as near as `n` samples can say it. The samples it names are those deepest
//!   inside the polygon (by their least distance inside an edge), so a pixel that is half covered
//!   names the samples on the covered side. At one sample a pixel is drawn when at least half of
//!   it is covered.
//! - **Depth and barycentrics** averaged over the covered part, as its colour is: their values
//!   at the covered part's centroid ([`covered_part`]), from the polygon's planes (seed 003's
//!   plane equation; seed 002's perspective-correct weights), the same for every named sample.
//!
//! Clipping, projection and culling come first ([`screen::polygons`]). It declares 1, 2, 4, 8 and
//! 16 samples at Vulkan's standard positions, since where its samples are is a choice it makes.
//! It has no depth test of its own: the colours it would blend are not part of the contract.

use refrast::{
    DepthConvention, Draw, DrawError, Fragment, Profile, Rasterizer, SamplePattern, Snapping, Spec, Topology,
};

use super::screen::{self, ScreenPolygon, area2};

/// Seed 003's area averaging, its fractions told as the declared samples.
#[derive(Clone, Copy, Debug, Default)]
pub struct AreaAverage;

/// The sample counts above one it declares (one sample, the pixel centre, needs no declaring).
const COUNTS: [u8; 4] = [2, 4, 8, 16];

/// The part of pixel `(x, y)`'s unit square that the convex polygon `corners` covers: its area
/// (the covered fraction) and its centroid; `None` when it covers none.
#[must_use]
pub fn covered_part(corners: &[[f64; 2]], x: u32, y: u32) -> Option<(f64, [f64; 2])> {
    let (x0, y0) = (f64::from(x), f64::from(y));
    // The square's four sides, each as (axis, bound, keep below): kept when the coordinate is ≥ or ≤ it.
    let sides = [
        (0, x0, false),
        (0, x0 + 1.0, true),
        (1, y0, false),
        (1, y0 + 1.0, true),
    ];
    let mut polygon = corners.to_vec();
    for (axis, bound, below) in sides {
        let inside = |p: &[f64; 2]| if below { p[axis] <= bound } else { p[axis] >= bound };
        let mut cut = Vec::with_capacity(polygon.len() + 1);
        for i in 0..polygon.len() {
            let (p, q) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            if inside(&p) {
                cut.push(p);
            }
            if inside(&p) != inside(&q) {
                let t = (bound - p[axis]) / (q[axis] - p[axis]);
                let mut r = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                r[axis] = bound;
                cut.push(r);
            }
        }
        polygon = cut;
        if polygon.len() < 3 {
            return None;
        }
    }
    let doubled = area2(&polygon);
    if doubled == 0.0 || !doubled.is_finite() {
        return None;
    }
    // The centroid of a polygon: Σ (p + q)·(p × q) / (3 · doubled area).
    let mut c = [0.0; 2];
    for i in 0..polygon.len() {
        let (p, q) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let cross = p[0] * q[1] - q[0] * p[1];
        c[0] += (p[0] + q[0]) * cross;
        c[1] += (p[1] + q[1]) * cross;
    }
    Some(((doubled * 0.5).abs(), c.map(|v| v / (3.0 * doubled))))
}

/// How many of `n` samples a covered `fraction` is told as: the nearest count.
#[must_use]
pub fn covered_count(fraction: f64, n: u8) -> usize {
    (fraction * f64::from(n)).round().clamp(0.0, f64::from(n)) as usize
}

/// How far inside the polygon `(x, y)` lies: its least signed distance to an edge's line.
fn depth_inside(corners: &[[f64; 2]], x: f64, y: f64) -> f64 {
    let sign = area2(corners).signum();
    (0..corners.len())
        .map(|i| {
            let (p, q) = (corners[i], corners[(i + 1) % corners.len()]);
            let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
            sign * (ex * (y - p[1]) - ey * (x - p[0])) / ex.hypot(ey)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The sample fragments of one polygon at `pattern`'s positions.
fn draw_polygon(poly: &ScreenPolygon, draw: &Draw, pattern: SamplePattern, out: &mut Vec<Fragment>) {
    let vp = draw.viewport;
    let bound = |axis: usize, size: u32| {
        let (lo, hi) = poly
            .corners
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c[axis]), hi.max(c[axis]))
            });
        let lo = lo.floor().max(0.0) as u32;
        let hi = (hi.ceil().min(f64::from(size)) as u32).max(lo);
        lo..hi
    };
    let n = pattern.count();
    for y in bound(1, vp.height()) {
        for x in bound(0, vp.width()) {
            let Some((fraction, [cx, cy])) = covered_part(&poly.corners, x, y) else {
                continue;
            };
            let count = covered_count(fraction, n);
            if count == 0 {
                continue;
            }
            // Averaged over the covered part, a quantity linear on screen is its value at the
            // part's centroid: one depth and one set of weights for the whole pixel.
            let depth = poly.depth.at(cx, cy).clamp(0.0, 1.0) as f32;
            let barycentric = poly.barycentric_at(cx, cy).map(|b| b as f32);
            let at = |s: usize| {
                let [sx, sy] = pattern.positions()[s];
                (
                    f64::from(x) + f64::from(sx) / 16.0,
                    f64::from(y) + f64::from(sy) / 16.0,
                )
            };
            let mut order: Vec<usize> = (0..usize::from(n)).collect();
            order.sort_by(|&i, &j| {
                let (di, dj) = (at(i), at(j));
                depth_inside(&poly.corners, dj.0, dj.1).total_cmp(&depth_inside(&poly.corners, di.0, di.1))
            });
            for &s in &order[..count] {
                out.push(Fragment {
                    x,
                    y,
                    sample: s as u8,
                    primitive: poly.primitive,
                    depth,
                    barycentric,
                    flat: None,
                    screen_barycentric: None,
                    front_facing: poly.front_facing,
                });
            }
        }
    }
}

impl Rasterizer for AreaAverage {
    fn profile(&self) -> Profile {
        Profile {
            name: "lab003-area-average".into(),
            // Areas in f64 on the projected coordinates: no grid.
            snapping: Snapping::Float,
            // A fraction has no ties to break: no tie rule.
            fill: None,
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: 1,
            // f64 plane equations on exact inputs, as the reference.
            precision_bits: 18,
            features: screen::features(false),
            spec: Spec::Refrast,
            multisample: COUNTS
                .iter()
                .filter_map(|&n| SamplePattern::standard(n))
                .collect(),
            ..Profile::default()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        draw.validate()?;
        let pattern = self.profile().pattern(draw.samples);
        let (Some(pattern), Topology::TriangleList) = (pattern, draw.topology) else {
            return Err(DrawError::Unsupported(draw.describe()));
        };
        let mut out = Vec::new();
        for poly in screen::polygons(draw) {
            draw_polygon(&poly, draw, pattern, &mut out);
        }
        Ok(out)
    }
}
