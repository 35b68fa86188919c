//! [`super::ray_hits`] for many rays at one triangle: the filter's numerators set up once.
//!
//! With `u = x − nx·w` and `v = y − ny·w`, each barycentric numerator
//! `nᵢ = uⱼvₖ − uₖvⱼ` is exactly `cᵢ₀ + cᵢ₁·nx + cᵢ₂·ny` (the `nx·ny` terms cancel), with
//! `cᵢ₀ = xⱼyₖ − xₖyⱼ`, `cᵢ₁ = wⱼyₖ − wₖyⱼ` negated, `cᵢ₂ = xⱼwₖ − xₖwⱼ` negated. The
//! coefficients are computed once, each with its error bound, so a ray costs two products a
//! numerator instead of five; the signs are decided as [`super::ray_cast`]'s filter decides
//! them, and the exact solve runs where one is unsure.

use refrast::DrawState;

use super::{Bounded, add, exact, mul, sub};
use crate::oracle::raster::near_distance;

/// One triangle's numerators as affine functions of the ray's NDC point, with error bounds.
pub struct HitTest {
    tri: [[f64; 4]; 3],
    state: DrawState,
    /// `[cᵢ₀, cᵢ₁, cᵢ₂]` per numerator.
    n: [[Bounded; 3]; 3],
}

impl HitTest {
    /// The numerators of `tri` under `state`.
    #[must_use]
    pub fn new(tri: &[[f64; 4]; 3], state: &DrawState) -> Self {
        let e = Bounded::exact;
        let cross = |j: usize, k: usize, a: usize, b: usize| {
            sub(mul(e(tri[j][a]), e(tri[k][b])), mul(e(tri[k][a]), e(tri[j][b])))
        };
        let negate = |b: Bounded| Bounded { v: -b.v, err: b.err };
        let n = std::array::from_fn(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            [
                cross(j, k, 0, 1),
                negate(cross(j, k, 3, 1)),
                negate(cross(j, k, 0, 3)),
            ]
        });
        HitTest {
            tri: *tri,
            state: *state,
            n,
        }
    }

    /// Whether the ray through NDC point `(nx, ny)` hits the triangle: [`super::ray_hits`].
    #[must_use]
    pub fn hits(&self, nx: f64, ny: f64) -> bool {
        let e = Bounded::exact;
        let n = self
            .n
            .map(|[c0, c1, c2]| add(add(c0, mul(c1, e(nx))), mul(c2, e(ny))));
        let d = add(add(n[0], n[1]), n[2]);
        let weighted = |k: usize| {
            add(
                add(mul(n[0], e(self.tri[0][k])), mul(n[1], e(self.tri[1][k]))),
                mul(n[2], e(self.tri[2][k])),
            )
        };
        let (nz, nw) = (weighted(2), weighted(3));
        let state = &self.state;
        let near = near_distance(state.depth_range, nz, nw);
        let far = sub(nw, nz);
        let s = d.v.signum();
        // Hit: every numerator, w and the enabled plane distances of the denominator's sign.
        let signs_sure = [d, n[0], n[1], n[2], nw].iter().all(|b| b.sure())
            && (!state.clip_near || near.sure())
            && (!state.clip_far || far.sure());
        if signs_sure {
            return n.iter().all(|ni| ni.v * s > 0.0)
                && nw.v * s > 0.0
                && (!state.clip_near || near.v * s > 0.0)
                && (!state.clip_far || far.v * s > 0.0);
        }
        let misses = |x: &Bounded| x.sure() && x.v * s < 0.0;
        let missed = n.iter().any(misses)
            || misses(&nw)
            || (state.clip_near && misses(&near))
            || (state.clip_far && misses(&far));
        if d.sure() && missed {
            return false;
        }
        exact::ray_hits_exact(&self.tri, nx, ny, state)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::oracle::ray_cast::ray_hits;

    /// Coordinates where the bounds matter: integers and halves (rays through edges and
    /// vertices), small ranges, and extremes of f32.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            4 => (-4i32..=4).prop_map(|k| f64::from(k) * 0.5),
            4 => -2.0f64..2.0,
            1 => (-30000.0f32..30000.0).prop_map(f64::from),
            1 => prop_oneof![Just(1e-30), Just(-3e-38), Just(3e38), Just(0.0), Just(-0.0)],
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The set-up numerators decide every ray as `ray_hits` does: rays on edges and
        /// through vertices, triangles nearly edge-on, every clipping state.
        #[test]
        fn set_up_numerators_decide_as_ray_hits(
            tri in prop::array::uniform3(prop::array::uniform4(coordinate())),
            nx in prop_oneof![(-4i32..=4).prop_map(|k| f64::from(k) * 0.5), -2.0f64..2.0],
            ny in prop_oneof![(-4i32..=4).prop_map(|k| f64::from(k) * 0.5), -2.0f64..2.0],
            clip in (any::<bool>(), any::<bool>(), any::<bool>()),
            (on_edge, edge_on, t, u) in (any::<bool>(), any::<bool>(), 0.0f64..1.0, -0.5f64..1.5),
        ) {
            let mut tri = tri;
            if edge_on {
                tri[2] = std::array::from_fn(|k| tri[0][k] + u * (tri[1][k] - tri[0][k]));
            }
            let ndc = |p: [f64; 4]| [p[0] / p[3], p[1] / p[3]];
            let (a, b) = (ndc(tri[0]), ndc(tri[1]));
            let (nx, ny) = if on_edge { (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])) } else { (nx, ny) };
            let state = DrawState {
                depth_range: if clip.0 { refrast::DepthRange::NegativeOneToOne } else { refrast::DepthRange::ZeroToOne },
                clip_near: clip.1,
                clip_far: clip.2,
                ..DrawState::default()
            };
            prop_assert_eq!(HitTest::new(&tri, &state).hits(nx, ny), ray_hits(&tri, nx, ny, &state));
        }
    }
}
