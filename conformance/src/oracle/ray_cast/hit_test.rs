//! [`super::ray_hits`] for many rays at one triangle: the filter's numerators set up once.
//!
//! With `u = x − nx·w` and `v = y − ny·w`, each barycentric numerator
//! `nᵢ = uⱼvₖ − uₖvⱼ` is exactly `cᵢ₀ + cᵢ₁·nx + cᵢ₂·ny` (the `nx·ny` terms cancel), with
//! `cᵢ₀ = xⱼyₖ − xₖyⱼ`, `cᵢ₁ = wⱼyₖ − wₖyⱼ` negated, `cᵢ₂ = xⱼwₖ − xₖwⱼ` negated. The
//! coefficients are computed once, each with its error bound, so a ray costs two products a
//! numerator instead of five; the signs are decided as [`super::ray_cast`]'s filter decides
//! them, and the exact solve runs where one is unsure. A triangle every ray misses for one
//! reason (its projected area, or its hits' `w`, zero for every ray) is found once, exactly.
//!
//! The numerators' sum and their weightings of z and w are affine too. For rays within
//! [`REACH`] of the NDC origin (every sample of the viewport), all six come with one error
//! bound each, set up once ([`Affine`]): a ray costs two products a function and no error
//! arithmetic. Where that bound leaves a sign unsure, the per-ray bounds are tried, then the
//! exact solve.

use refrast::DrawState;

use super::{Bounded, EPS, Sums, UNDERFLOW, add, exact, mul, sub};

/// How far from the NDC origin, in each coordinate, [`Affine`]'s one bound holds: every
/// sample of the viewport lies within ±1.
const REACH: f64 = 2.0;

/// An affine function of the ray's NDC point, `c₀ + c₁·nx + c₂·ny`, evaluated in that order,
/// with one error bound for every point within [`REACH`].
#[derive(Clone, Copy, Debug)]
struct Affine {
    c: [f64; 3],
    err: f64,
}

impl Affine {
    /// The function with coefficients `c` (each with its error): the bound is the filter's
    /// own error model for `add(add(c₀, mul(c₁, nx)), mul(c₂, ny))` (`super::Bounded`), each
    /// magnitude replaced by its largest value within [`REACH`], a rounded result's by one
    /// ulp-step more. Every term of that model grows with the magnitudes, so the bound holds
    /// wherever the per-ray one does.
    fn of(c: [Bounded; 3]) -> Self {
        let up = 1.0 + EPS;
        let product = |c: Bounded| {
            let most = c.v.abs() * REACH * up;
            (most, c.err * REACH + EPS * most + UNDERFLOW)
        };
        let ((m1, e1), (m2, e2)) = (product(c[1]), product(c[2]));
        let m01 = (c[0].v.abs() + m1) * up;
        let e01 = c[0].err + e1 + EPS * m01 + UNDERFLOW;
        let m = (m01 + m2) * up;
        Affine {
            c: c.map(|b| b.v),
            err: e01 + e2 + EPS * m + UNDERFLOW,
        }
    }

    /// Its value at `(nx, ny)` with the uniform bound.
    #[inline]
    fn at(&self, nx: f64, ny: f64) -> Bounded {
        Bounded {
            v: (self.c[0] + self.c[1] * nx) + self.c[2] * ny,
            err: self.err,
        }
    }
}

/// One triangle's numerators as affine functions of the ray's NDC point, with error bounds.
pub struct HitTest {
    tri: [[f64; 4]; 3],
    state: DrawState,
    /// `[cᵢ₀, cᵢ₁, cᵢ₂]` per numerator.
    n: [[Bounded; 3]; 3],
    /// The numerators, then their sum and their weightings of z and w, with uniform bounds.
    affine: [Affine; 6],
    /// Whether every ray misses, known for the whole triangle ([`exact::misses_every_ray`]).
    never: bool,
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
        // The sums are linear in the numerators: `Sums::of`, coefficient by coefficient.
        let sums = [0, 1, 2].map(|c| Sums::of(tri, &[n[0][c], n[1][c], n[2][c]]));
        let (d, nz, nw) = (sums.map(|s| s.d), sums.map(|s| s.nz), sums.map(|s| s.nw));
        // Only a function with no coefficient surely non-zero can be zero for every ray: the
        // exact test runs for those alone.
        let maybe_zero = |c: &[Bounded; 3]| !c.iter().any(|b| b.sure());
        let never = (maybe_zero(&d) || maybe_zero(&nw)) && exact::misses_every_ray(tri);
        let affine = [n[0], n[1], n[2], d, nz, nw].map(Affine::of);
        HitTest {
            tri: *tri,
            state: *state,
            n,
            affine,
            never,
        }
    }

    /// Whether the ray through NDC point `(nx, ny)` hits the triangle: [`super::ray_hits`].
    #[must_use]
    pub fn hits(&self, nx: f64, ny: f64) -> bool {
        if self.never {
            return false;
        }
        if nx.abs() <= REACH && ny.abs() <= REACH {
            let [n0, n1, n2, d, nz, nw] = self.affine.map(|f| f.at(nx, ny));
            if let Some(hit) = (Sums { d, nz, nw }).decide(&[n0, n1, n2], &self.state) {
                return hit;
            }
        }
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

    /// Triangles the `clipping` fuzz target's seeds hold, each missed by every ray for one
    /// reason, found once (`misses_every_ray`) where the filter was unsure at every sample:
    /// a corner repeated, and two corners on the line through the eye with `w` of either sign.
    #[test]
    fn triangles_every_ray_misses_are_found_once() {
        let repeated = [
            [53125.80859375, 53125.80859375, 0.87158203125, 2.65625],
            [-4.720831871032715, -6.179998397827148, -0.00048828125, -0.03125],
            [53125.80859375, 53125.80859375, 0.87158203125, 2.65625],
        ];
        let through_eye = [
            [0.0, 0.0, 0.0, -2.5625],
            [18.711660385131836, -0.05722220614552498, -0.0009765625, -0.0625],
            [0.0, 0.0, 0.0, 0.009999999776482582],
        ];
        let seen = [
            [-1.0, -1.0, 0.5, 1.0],
            [-1.0, 1.0, -0.5, 1.0],
            [1.0, -1.0, -0.5, 1.0],
        ];
        let state = DrawState::default();
        for (tri, never) in [(repeated, true), (through_eye, true), (seen, false)] {
            let test = HitTest::new(&tri, &state);
            assert_eq!(test.never, never, "{tri:?}");
            let mut hits = 0;
            for i in -8..=8 {
                for j in -8..=8 {
                    let (nx, ny) = (f64::from(i) / 8.0, f64::from(j) / 8.0);
                    assert_eq!(
                        test.hits(nx, ny),
                        ray_hits(&tri, nx, ny, &state),
                        "{tri:?} at {nx}, {ny}"
                    );
                    hits += usize::from(test.hits(nx, ny));
                }
            }
            assert_eq!(hits == 0, never, "{tri:?}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The set-up numerators decide every ray as `ray_hits` does.
        #[test]
        fn set_up_numerators_decide_as_ray_hits((tri, nx, ny, state) in ray_case()) {
            prop_assert_eq!(HitTest::new(&tri, &state).hits(nx, ny), ray_hits(&tri, nx, ny, &state));
        }
    }
}
