//! Interpolation precision on triangles drawn whole: how far the driver's barycentrics and depth
//! are from exact.
//!
//! Every vertex is on the grid and has w a power of two, so snapping moves nothing and the exact
//! values (f64 from the vertices as drawn) are what a perfect implementation gives. The
//! triangles, all inside a 32×32 target, in one draw: 9 diagonal wedges 29 px long and 1/16 to 1
//! px wide with w ratios of 32:1, 1000 slivers (an apex anywhere, the opposite edge at most 8 grid
//! steps long) and 200 ordinary triangles, with w from 1/8 to 4 and window depth 1/4, 1/2 or 3/4
//! at each vertex. Clipped triangles are left out: Vulkan and OpenGL hold a clipped polygon's
//! values only to being a convex combination (docs/levels.md), and the suite judges them so.

use refrast::{DrawError, Fragment};

use super::{Raster, batch, clip};

/// The largest errors seen, per kind of output.
#[derive(Clone, Debug, PartialEq)]
pub struct Precision {
    /// Triangles drawn.
    pub triangles: usize,
    /// Fragments read.
    pub fragments: usize,
    /// Perspective-correct barycentrics.
    pub perspective: f64,
    /// Screen-space barycentrics.
    pub screen: f64,
    /// Window depth.
    pub depth: f64,
}

impl Precision {
    /// The bits kept on every output: `-log2` of the largest error (∞ for none at all).
    #[must_use]
    pub fn bits(&self) -> f64 {
        -self.perspective.max(self.screen).max(self.depth).log2()
    }

    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        let b = |e: f64| -e.log2();
        format!(
            "measured {:.1} on {} unclipped slivers and triangles (perspective 2^-{:.1}, screen \
             2^-{:.1}, depth 2^-{:.1})",
            self.bits(),
            self.triangles,
            b(self.perspective),
            b(self.screen),
            b(self.depth)
        )
    }
}

/// One triangle: framebuffer vertices, w and window depth per vertex.
struct Triangle {
    p: [[f64; 2]; 3],
    w: [f64; 3],
    d: [f64; 3],
}

/// Twice the signed area of `a, b, c`.
fn area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The triangles, on a grid of `bits` (at most 8, so every coordinate is exact in f32).
fn triangles(bits: u8) -> Vec<Triangle> {
    let one = f64::from(1u32 << bits.min(8));
    let mut out = Vec::new();
    for delta in [1.0 / 16.0, 0.25, 1.0] {
        for (w0, w1) in [(4.0, 0.125), (0.125, 4.0), (1.0, 1.0)] {
            out.push(Triangle {
                p: [[1.5, 1.5], [30.5, 30.5 - delta], [30.5 - delta, 30.5]],
                w: [w0, w1, w1],
                d: [0.25, 0.75, 0.5],
            });
        }
    }
    let mut state = 0x1234_5678u64;
    let mut next = move |n: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % n
    };
    let ws = [0.125, 0.25, 0.5, 1.0, 2.0, 4.0];
    let ds = [0.25, 0.5, 0.75];
    let side = 32 * one as u64;
    for i in 0..1200 {
        let mut grid = |n: u64| next(n) as f64 / one;
        let a = [grid(side), grid(side)];
        let b = [grid(side), grid(side)];
        let c = if i < 1000 {
            let near = |v: f64, d: f64| (v + d - 8.0 / one).clamp(0.0, 32.0);
            [near(b[0], grid(17)), near(b[1], grid(17))]
        } else {
            [grid(side), grid(side)]
        };
        let w = [(); 3].map(|()| ws[next(6) as usize]);
        let d = [(); 3].map(|()| ds[next(3) as usize]);
        if area(a, b, c) != 0.0 {
            out.push(Triangle { p: [a, b, c], w, d });
        }
    }
    out
}

/// The largest difference of a triple from the exact one; NaN counts as 1.
fn apart(got: [f32; 3], want: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let e = (f64::from(got[k]) - want[k]).abs();
            if e.is_nan() { 1.0 } else { e }
        })
        .fold(0.0, f64::max)
}

/// Draws them in one draw and compares every fragment with exact arithmetic.
pub fn probe(draw: &mut Raster<'_>, bits: u8) -> Result<Precision, DrawError> {
    let tris = triangles(bits);
    let positions = tris
        .iter()
        .flat_map(|t| (0..3).map(|i| clip(32, 32, t.p[i], t.d[i], t.w[i])))
        .collect();
    let frags = draw(&batch(32, 32, positions))?;
    let mut precision = Precision {
        triangles: tris.len(),
        fragments: 0,
        perspective: 0.0,
        screen: 0.0,
        depth: 0.0,
    };
    for f in &frags {
        let Some(t) = tris.get(f.primitive as usize) else {
            continue;
        };
        let (persp, screen) = exact(t, f);
        precision.fragments += 1;
        precision.perspective = precision.perspective.max(apart(f.barycentric, persp));
        if let Some(s) = f.screen_barycentric {
            precision.screen = precision.screen.max(apart(s, screen));
        }
        let depth: f64 = (0..3).map(|i| screen[i] * t.d[i]).sum();
        precision.depth = precision.depth.max(apart([f.depth; 3], [depth; 3]));
    }
    Ok(precision)
}

/// Perspective-correct and screen-space barycentrics of `f`'s sample in `t`, in f64.
fn exact(t: &Triangle, f: &Fragment) -> ([f64; 3], [f64; 3]) {
    let s = [f64::from(f.x) + 0.5, f64::from(f.y) + 0.5];
    let p = t.p;
    let whole = area(p[0], p[1], p[2]);
    let screen = [
        area(s, p[1], p[2]) / whole,
        area(p[0], s, p[2]) / whole,
        area(p[0], p[1], s) / whole,
    ];
    let over_w = [0, 1, 2].map(|i| screen[i] / t.w[i]);
    let sum: f64 = over_w.iter().sum();
    (over_w.map(|v| v / sum), screen)
}
