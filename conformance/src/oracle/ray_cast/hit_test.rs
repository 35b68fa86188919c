//! [`super::ray_hits`] for many rays at one triangle: the filter's numerators set up once.
//!
//! With `u = x − nx·w` and `v = y − ny·w`, each barycentric numerator
//! `nᵢ = uⱼvₖ − uₖvⱼ` is exactly `cᵢ₀ + cᵢ₁·nx + cᵢ₂·ny` (the `nx·ny` terms cancel), with
//! `cᵢ₀ = xⱼyₖ − xₖyⱼ`, `cᵢ₁ = wⱼyₖ − wₖyⱼ` negated, `cᵢ₂ = xⱼwₖ − xₖwⱼ` negated. The
//! coefficients are computed once, each with its error bound, so a ray costs two products a
//! numerator instead of five; the signs are decided as [`super::ray_cast`]'s filter decides
//! them, and the exact solve runs where one is unsure.

use refrast::DrawState;

use super::{Bounded, Sums, add, exact, mul, sub};

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
        Sums::of(&self.tri, &n)
            .decide(&n, &self.state)
            .unwrap_or_else(|| exact::ray_hits_exact(&self.tri, nx, ny, &self.state))
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::oracle::ray_cast::ray_hits;
    use crate::oracle::ray_cast::tests::ray_case;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The set-up numerators decide every ray as `ray_hits` does.
        #[test]
        fn set_up_numerators_decide_as_ray_hits((tri, nx, ny, state) in ray_case()) {
            prop_assert_eq!(HitTest::new(&tri, &state).hits(nx, ny), ray_hits(&tri, nx, ny, &state));
        }
    }
}
