//! Interpolation, `fast`'s own: depth and barycentrics as f32 planes over the exact edge values,
//! set up once per triangle, with no division per sample for depth.
//!
//! A covered sample's edge values `e₀, e₁, e₂` are exact integers summing to twice the area
//! `A`, so `λₖ = eₖ / A` are its screen weights.
//!
//! - **Depth** is `z₀ + e₁·g₁ + e₂·g₂` with `gₖ = (zₖ − z₀) / A`, in f64 lanes on the exact
//!   values, then rounded to f32: a corner's depth can lie far outside `[0, 1]` (a clipped
//!   polygon's corner on the guard band, far clipping off), and in f32 the error would scale
//!   with that range instead of with the result. In f64 it stays within an f32 ulp.
//! - **Perspective weights** `(λₖ/wₖ) / Σ λⱼ/wⱼ` are one scalar f64 reciprocal per fragment
//!   (scalar f64 costs what scalar f32 does): corners' `1/w` can differ by 10^80 for f32
//!   inputs, which f32 cannot hold (`robust.bit-patterns.sane-output` found NaNs).
//! - **Barycentrics** mix the corners' own barycentrics with those weights in f32. Inside the
//!   triangle every weight is in `[0, 1]` and every term positive, so nothing cancels: a
//!   barycentric is within a few ulps of 1 (≈ 2^-21) of its exact value, under the bound `fast`
//!   claims with room ([`PRECISION_BITS`]).
//!
//! Every operation is a separate IEEE multiply or add in a fixed order (no fused multiply-add,
//! which not every level has), so every SIMD level and the scalar code give the same bits.

use refrast::Fragment;
use refrast::stage::Varyings;

use crate::back::LANES;

/// The precision `fast` claims: depth and barycentrics within 2^-18 of their exact values.
///
/// The error analysis above gives about 2^-20.7 for a barycentric and less for depth;
/// `tests/interpolation.rs` measures it against the reference on random scenes.
pub const PRECISION_BITS: u8 = 18;

/// One triangle's interpolation: what its covered samples need, in f32.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Planes {
    /// The triangle's index in the draw.
    pub primitive: u32,
    /// Whether it faces the viewer.
    pub front_facing: bool,
    /// Depth at corner 0.
    z0: f64,
    /// Depth's change per unit of `e₁` and of `e₂`: `(zₖ − z₀) / A`.
    gz: [f64; 2],
    /// `1 / A`, which turns edge values into screen weights.
    inv_area: f64,
    /// Each corner's `1/w`, scaled so that the largest is 1 (the correction is scale-free).
    inv_w: [f64; 3],
    /// Each corner's barycentrics in the input triangle.
    barycentric: [[f32; 3]; 3],
    /// Each corner's screen barycentrics in the input triangle, when it has them.
    screen: Option<[[f32; 3]; 3]>,
}

impl Planes {
    /// Sets up a triangle with `corners` in its setup's order (the order of its edge values)
    /// and twice its area `area2` (positive, the sum of its edge values).
    pub fn new(primitive: u32, front_facing: bool, corners: [&Varyings; 3], area2: i64) -> Self {
        let inv_area = 1.0 / area2 as f64;
        let max_inv_w = corners.iter().map(|c| c.inv_w).fold(0.0, f64::max);
        let to_f32 = |v: glam::DVec3| v.as_vec3().to_array();
        let mut screen = Some([[0.0; 3]; 3]);
        for (k, c) in corners.iter().enumerate() {
            screen = screen.zip(c.screen).map(|(mut s, b)| {
                s[k] = to_f32(b);
                s
            });
        }
        Self {
            primitive,
            front_facing,
            z0: corners[0].depth,
            gz: [1, 2].map(|k| (corners[k].depth - corners[0].depth) * inv_area),
            inv_area,
            inv_w: corners.map(|c| c.inv_w / max_inv_w),
            barycentric: corners.map(|c| to_f32(c.barycentric)),
            screen,
        }
    }

    /// Window depth at eight samples from their exact edge values `e`, clamped to `[0, 1]`.
    #[inline(always)]
    pub fn depth(&self, e: &[[f64; LANES]; 3]) -> [f32; LANES] {
        let mut depth = [0.0; LANES];
        for (i, d) in depth.iter_mut().enumerate() {
            let z = ((self.z0 + e[1][i] * self.gz[0]) + e[2][i] * self.gz[1]) as f32;
            // `clamp` is two comparisons (`max`/`min` may differ in zero signs and NaNs by level).
            *d = z.clamp(0.0, 1.0);
        }
        depth
    }

    /// The fragment at pixel `(x, y)` with exact edge values `e` and depth `depth` (from
    /// [`depth`](Self::depth)).
    #[inline]
    pub fn fragment(&self, x: u32, y: u32, e: [f64; 3], depth: f32) -> Fragment {
        let screen = [e[0] * self.inv_area, e[1] * self.inv_area, e[2] * self.inv_area];
        let q = [
            screen[0] * self.inv_w[0],
            screen[1] * self.inv_w[1],
            screen[2] * self.inv_w[2],
        ];
        let r = 1.0 / ((q[0] + q[1]) + q[2]);
        let p = [(q[0] * r) as f32, (q[1] * r) as f32, (q[2] * r) as f32];
        let s = [screen[0] as f32, screen[1] as f32, screen[2] as f32];
        #[inline(always)]
        fn mix(corners: &[[f32; 3]; 3], w: [f32; 3]) -> [f32; 3] {
            let c = |i: usize| (corners[0][i] * w[0] + corners[1][i] * w[1]) + corners[2][i] * w[2];
            [c(0), c(1), c(2)]
        }
        Fragment {
            x,
            y,
            primitive: self.primitive,
            depth,
            barycentric: mix(&self.barycentric, p),
            screen_barycentric: self.screen.map(|b| mix(&b, s)),
            front_facing: self.front_facing,
        }
    }
}
