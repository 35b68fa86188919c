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
//! - **Perspective weights** `(λₖ/wₖ) / Σ λⱼ/wⱼ` are one f64 reciprocal per fragment, eight
//!   lanes at once in rows with more than four kept samples, one lane at a time otherwise (the
//!   same operations, so the same bits): corners' `1/w` can differ by 10^80 for f32 inputs,
//!   which f32 cannot hold (`robust.bit-patterns.sane-output` found NaNs).
//! - **Barycentrics** mix the corners' own barycentrics with those weights in f32. Inside the
//!   triangle every weight is in `[0, 1]` and every term positive, so nothing cancels: a
//!   barycentric is within a few ulps of 1 (≈ 2^-21) of its exact value, under the bound `fast`
//!   claims with room ([`PRECISION_BITS`]).
//!
//! Every operation is a separate IEEE multiply or add in a fixed order (no fused multiply-add,
//! which not every level has), so every SIMD level and the scalar code give the same bits.

use refrast::stage::Varyings;
use refrast::{Fragment, ViewportDepth};

use crate::back::{LANES, Lanes, for_each_lane};

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
    /// Depth at corner 0, the polygon's depth bias added.
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
    /// The viewport's depth range, lower end first: what depth is clamped to.
    depth_bounds: [f32; 2],
}

impl Planes {
    /// Sets up a triangle with `corners` in its setup's order (the order of its edge values)
    /// and twice its area `area2` (positive, the sum of its edge values), drawn with the
    /// viewport depth range `range` and its polygon's depth bias `offset`.
    pub fn new(
        primitive: u32,
        front_facing: bool,
        corners: [&Varyings; 3],
        area2: i64,
        range: ViewportDepth,
        offset: f64,
    ) -> Self {
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
            // The bias is one value for the whole plane: added where it starts.
            z0: corners[0].depth + offset,
            gz: [1, 2].map(|k| (corners[k].depth - corners[0].depth) * inv_area),
            inv_area,
            inv_w: corners.map(|c| c.inv_w / max_inv_w),
            barycentric: corners.map(|c| to_f32(c.barycentric)),
            screen,
            depth_bounds: [range.min.min(range.max), range.min.max(range.max)],
        }
    }

    /// A value read from fields spread over it, for bringing it into the cache (a hint: which
    /// lines they fall in is the compiler's layout).
    #[inline(always)]
    pub fn warm(&self) -> u32 {
        let floats = self.z0.to_bits() ^ self.inv_w[2].to_bits() ^ self.inv_area.to_bits();
        let corners = self.barycentric[0][0].to_bits() ^ self.barycentric[2][2].to_bits();
        self.primitive ^ corners ^ floats as u32 ^ u32::from(self.screen.is_some())
    }

    /// Window depth at eight samples from their exact edge values `e`, clamped to the
    /// viewport's depth range (as [`ViewportDepth::fragment_depth`] does, in the same order).
    #[inline(always)]
    pub fn depth(&self, e: &[[f64; LANES]; 3]) -> [f32; LANES] {
        let mut depth = [0.0; LANES];
        for (i, d) in depth.iter_mut().enumerate() {
            let z = ((self.z0 + e[1][i] * self.gz[0]) + e[2][i] * self.gz[1]) as f32;
            // `clamp` is two comparisons (`max`/`min` may differ in zero signs and NaNs by level).
            *d = z.clamp(self.depth_bounds[0], self.depth_bounds[1]);
        }
        depth
    }

    /// Bounds of [`depth`](Self::depth), least first, at every sample of a rectangle whose
    /// corner samples have the exact edge values `corners`: what a block's depth test can be
    /// decided on before any sample (Greene's hierarchical z); `None` where a corner is not
    /// finite.
    ///
    /// Depth is linear in the edge values, so over a rectangle it is least and greatest at
    /// corners. Each sample's `f64` sum, and each corner's here, is within `3·2^-53` of the
    /// magnitude `|z₀| + |e₁·g₁| + |e₂·g₂|` of the exact value, a convex function, so largest
    /// at a corner too: the extreme corners widened by `2^-48` of the largest magnitude bound
    /// every sample. Rounding to `f32` and the clamp keep the order.
    #[inline(always)]
    pub fn depth_bounds(&self, corners: &[[f64; 3]; 4]) -> Option<[f32; 2]> {
        let (mut least, mut most, mut magnitude) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
        for e in corners {
            let (a, b) = (e[1] * self.gz[0], e[2] * self.gz[1]);
            let size = self.z0.abs() + a.abs() + b.abs();
            if !size.is_finite() {
                return None;
            }
            let z = (self.z0 + a) + b;
            least = least.min(z);
            most = most.max(z);
            magnitude = magnitude.max(size);
        }
        let margin = magnitude * f64::powi(2.0, -48);
        let [low, high] = self.depth_bounds;
        Some([least - margin, most + margin].map(|z| (z as f32).clamp(low, high)))
    }

    /// The perspective-correct and screen barycentrics of `N` samples with exact edge values
    /// `e` (edge by edge, then lane by lane), each as three arrays of `N` lanes: the one
    /// formula, run on eight lanes at once (vectorised) or on one.
    #[inline(always)]
    fn barycentrics<const N: usize>(&self, e: [[f64; N]; 3]) -> [[[f32; N]; 3]; 2] {
        let mut screen = [[0.0f64; N]; 3];
        let mut q = [[0.0f64; N]; 3];
        for k in 0..3 {
            for i in 0..N {
                screen[k][i] = e[k][i] * self.inv_area;
                q[k][i] = screen[k][i] * self.inv_w[k];
            }
        }
        let (mut p, mut s) = ([[0.0f32; N]; 3], [[0.0f32; N]; 3]);
        for i in 0..N {
            let r = 1.0 / ((q[0][i] + q[1][i]) + q[2][i]);
            for k in 0..3 {
                p[k][i] = (q[k][i] * r) as f32;
                s[k][i] = screen[k][i] as f32;
            }
        }
        /// Each corner's barycentrics mixed with the lanes' weights `w`.
        #[inline(always)]
        fn mix<const N: usize>(corners: &[[f32; 3]; 3], w: &[[f32; N]; 3]) -> [[f32; N]; 3] {
            let mut out = [[0.0; N]; 3];
            for (c, out) in out.iter_mut().enumerate() {
                for (i, out) in out.iter_mut().enumerate() {
                    *out = (corners[0][c] * w[0][i] + corners[1][c] * w[1][i]) + corners[2][c] * w[2][i];
                }
            }
            out
        }
        let screen = self.screen.as_ref().map_or([[0.0; N]; 3], |b| mix(b, &s));
        [mix(&self.barycentric, &p), screen]
    }

    /// Lane `lane` of `row` as a fragment, with its depth among `depth` and its barycentrics.
    #[inline(always)]
    fn fragment(
        &self,
        row: &Lanes,
        lane: usize,
        depth: &[f32; LANES],
        barycentric: [f32; 3],
        screen: [f32; 3],
    ) -> Fragment {
        Fragment {
            x: row.x0 + lane as u32,
            y: row.y,
            sample: 0,
            primitive: self.primitive,
            depth: depth[lane],
            barycentric,
            // No flat values: the profile declares none (StateSupport::flat empty).
            flat: None,
            screen_barycentric: self.screen.map(|_| screen),
            front_facing: self.front_facing,
        }
    }

    /// Visits the fragments of the lanes of `row` in `mask`, in lane order, with their depths
    /// `depth` (from [`depth`](Self::depth)).
    ///
    /// With more than four such lanes, the barycentrics of all eight are computed first, in a
    /// loop the compiler vectorises (an uncovered lane may hold anything and is never read);
    /// with fewer, lane by lane. Both run [`barycentrics`](Self::barycentrics), so the bits
    /// are the same.
    #[inline(always)]
    pub fn fragments(
        &self,
        row: &Lanes,
        mask: u32,
        depth: &[f32; LANES],
        mut visit: impl FnMut(usize, Fragment),
    ) {
        let e = &row.e;
        if mask.count_ones() > 4 {
            let [b, s] = self.barycentrics(*e);
            let at = |w: &[[f32; LANES]; 3], i: usize| [w[0][i], w[1][i], w[2][i]];
            for_each_lane(
                mask,
                #[inline(always)]
                |lane| visit(lane, self.fragment(row, lane, depth, at(&b, lane), at(&s, lane))),
            );
        } else {
            for_each_lane(
                mask,
                #[inline(always)]
                |lane| {
                    let [b, s] = self.barycentrics([[e[0][lane]], [e[1][lane]], [e[2][lane]]]);
                    let at = |w: [[f32; 1]; 3]| [w[0][0], w[1][0], w[2][0]];
                    visit(lane, self.fragment(row, lane, depth, at(b), at(s)));
                },
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::*;

    proptest! {
        /// [`Planes::depth_bounds`] of a block's corners hold the depth of every sample of the
        /// block, as the lanes compute it: planes steep and flat, depths near zero and far
        /// outside the range, biased, clamped to a range either way round.
        #[test]
        fn depth_bounds_hold_every_sample_of_the_block(
            depths in prop::array::uniform3(prop_oneof![-2.0f64..2.0, -1e9f64..1e9, Just(0.5)]),
            area2 in prop_oneof![1i64..1000, 1i64..(1 << 45)],
            offset in prop_oneof![Just(0.0), -1e-3f64..1e-3],
            range in (0.0f32..1.0, 0.0f32..1.0),
            start in prop::array::uniform2(-(1i64 << 45)..(1i64 << 45)),
            dx in prop::array::uniform2(-(1i64 << 30)..(1i64 << 30)),
            dy in prop::array::uniform2(-(1i64 << 30)..(1i64 << 30)),
            size in (1u32..=8, 1u32..=8),
        ) {
            let corner = |depth| Varyings {
                depth,
                inv_w: 1.0,
                barycentric: DVec3::X,
                screen: None,
            };
            let corners = depths.map(corner);
            let range = ViewportDepth { min: range.0, max: range.1 };
            let planes = Planes::new(0, true, [&corners[0], &corners[1], &corners[2]], area2, range, offset);
            // Edge values 1 and 2 (depth reads no others) at sample (x, y) of the block.
            let value = |k: usize, x: u32, y: u32| start[k] + i64::from(x) * dx[k] + i64::from(y) * dy[k];
            let (w, h) = size;
            let corner_values = [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)]
                .map(|(x, y)| [0.0, value(0, x, y) as f64, value(1, x, y) as f64]);
            let Some([floor, ceiling]) = planes.depth_bounds(&corner_values) else {
                return Err(TestCaseError::reject("a corner's depth is not finite"));
            };
            for y in 0..h {
                // As a row's lanes hold them: the row's first value, plus the lane times the step.
                let mut e = [[0.0; LANES]; 3];
                for k in 0..2 {
                    for (i, e) in e[k + 1].iter_mut().enumerate() {
                        *e = value(k, 0, y) as f64 + i as f64 * dx[k] as f64;
                    }
                }
                let depth = planes.depth(&e);
                for (x, &d) in depth.iter().enumerate().take(w as usize) {
                    prop_assert!(
                        floor <= d && d <= ceiling,
                        "sample ({x}, {y}): depth {d} outside [{floor}, {ceiling}]"
                    );
                }
            }
        }
    }

    /// A row's fragments are the same bits whether its barycentrics come eight lanes at once
    /// (more than four kept) or lane by lane (four or fewer).
    #[test]
    fn dense_and_sparse_rows_give_the_same_bits() {
        let corner = |depth, inv_w, b: [f64; 3]| Varyings {
            depth,
            inv_w,
            barycentric: DVec3::from(b),
            screen: Some(DVec3::from(b)),
        };
        let corners = [
            corner(0.25, 1.0, [1.0, 0.0, 0.0]),
            corner(0.5, 0.37, [0.0, 1.0, 0.0]),
            corner(0.9, 0.011, [0.0, 0.0, 1.0]),
        ];
        let area2 = 1_000_003;
        let planes = Planes::new(
            7,
            true,
            [&corners[0], &corners[1], &corners[2]],
            area2,
            ViewportDepth::FULL,
            0.0,
        );
        let e1: [f64; LANES] = std::array::from_fn(|i| 1237.0 * i as f64 + 3.0);
        let e2: [f64; LANES] = std::array::from_fn(|i| 98_765.0 - 4099.0 * i as f64);
        let e0 = std::array::from_fn(|i| area2 as f64 - e1[i] - e2[i]);
        let row = Lanes {
            x0: 16,
            y: 3,
            n: 8,
            mask: 0xff,
            e: [e0, e1, e2],
        };
        let depth = planes.depth(&row.e);
        let bits = |f: Fragment| {
            let b = f.barycentric.map(f32::to_bits);
            (
                f.x,
                f.depth.to_bits(),
                b,
                f.screen_barycentric.map(|s| s.map(f32::to_bits)),
            )
        };
        let mut dense = Vec::new();
        planes.fragments(&row, 0xff, &depth, |_, f| dense.push(bits(f)));
        let mut sparse = Vec::new();
        for lane in 0..LANES {
            planes.fragments(&row, 1 << lane, &depth, |_, f| sparse.push(bits(f)));
        }
        assert_eq!(dense.len(), LANES);
        assert_eq!(dense, sparse);
    }
}
