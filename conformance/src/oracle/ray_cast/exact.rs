//! The ray cast in exact integers: the fallback when f64 cannot be sure of a sign.
//!
//! Every finite f64 is `m·2^e` with an integer `m`, so scaling a set of them by one power of two
//! makes them all integers. The homogeneous solve is then additions and products of big
//! integers with no division and no gcd; only the final ratios become floats (correctly
//! rounded). Common positive factors change neither a sign nor a ratio, so every decision is
//! the one exact rationals would make, about twenty times faster.

use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{Float, ToPrimitive, Zero};
use refrast::DrawState;

use super::Hit;
use crate::oracle::raster::{near_distance, window_depth};

/// `xs` times one power of two `2^-e`, with `e ≤ 0` the smallest exponent among them, so that
/// all are integers; `None` if any is not finite.
fn common_scale(xs: &[f64]) -> Option<(Vec<BigInt>, u32)> {
    if xs.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let parts: Vec<(BigInt, i32)> = xs
        .iter()
        .map(|&x| {
            let (mantissa, exponent, sign) = Float::integer_decode(x);
            (BigInt::from(sign) * BigInt::from(mantissa), i32::from(exponent))
        })
        .collect();
    let e = parts
        .iter()
        .filter(|(m, _)| !m.is_zero())
        .map(|&(_, e)| e)
        .min()
        .unwrap_or(0)
        .min(0);
    let scaled = parts
        .into_iter()
        .map(|(m, k)| if m.is_zero() { m } else { m << (k - e) as usize })
        .collect();
    Some((scaled, e.unsigned_abs()))
}

/// `n / d` as the nearest f64 (`None` for 0/0).
fn ratio(n: &BigInt, d: &BigInt) -> Option<f64> {
    BigRational::new_raw(n.clone(), d.clone()).to_f64()
}

/// The exact solve of a visible hit: barycentric numerators, their sum, and the numerators
/// of z and w (all times one positive factor).
struct Solved {
    n: [BigInt; 3],
    d: BigInt,
    z: BigInt,
    w: BigInt,
}

/// The hit of [`super::ray_cast`] decided exactly, before any ratio; `None` for a miss and
/// for non-finite input.
fn solve(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Option<Solved> {
    let (n, p) = numerators(tri, nx, ny)?;
    let c = |i: usize, k: usize| &p[4 * i + k];
    let d = &n[0] + &n[1] + &n[2];
    let sign = d.sign();
    if sign == Sign::NoSign {
        return None;
    }
    // x / d > 0 and x / d ≥ 0, without dividing.
    let positive = |x: &BigInt| x.sign() == sign;
    let non_negative = |x: &BigInt| x.is_zero() || positive(x);
    if !n.iter().all(non_negative) {
        return None;
    }
    let weighted = |k: usize| &n[0] * c(0, k) + &n[1] * c(1, k) + &n[2] * c(2, k);
    let (z, w) = (weighted(2), weighted(3));
    let near = !state.clip_near || non_negative(&near_distance(state.depth_range, z.clone(), w.clone()));
    let beyond_far = state.clip_far && positive(&(&z - &w));
    if !positive(&w) || !near || beyond_far {
        return None;
    }
    Some(Solved { n, d, z, w })
}

/// The barycentric numerators of the ray through `(nx, ny)` at `tri`, times one positive
/// factor, with the triangle's coordinates scaled to integers by [`common_scale`]; `None` for
/// non-finite input.
fn numerators(tri: &[[f64; 4]; 3], nx: f64, ny: f64) -> Option<([BigInt; 3], Vec<BigInt>)> {
    let flat: Vec<f64> = tri.iter().flatten().copied().collect();
    let (p, _) = common_scale(&flat)?;
    let (q, shift) = common_scale(&[nx, ny])?;
    let c = |i: usize, k: usize| &p[4 * i + k];
    // u = x − nx·w and v = y − ny·w, all times 2^(shift − e_tri): (X << shift) − NX·W.
    let u: [BigInt; 3] = std::array::from_fn(|i| (c(i, 0) << shift) - &q[0] * c(i, 3));
    let v: [BigInt; 3] = std::array::from_fn(|i| (c(i, 1) << shift) - &q[1] * c(i, 3));
    let n = [
        &u[1] * &v[2] - &u[2] * &v[1],
        &u[2] * &v[0] - &u[0] * &v[2],
        &u[0] * &v[1] - &u[1] * &v[0],
    ];
    Some((n, p))
}

/// Whether every ray misses `tri` for a reason that holds for all of them: the numerators'
/// sum (the projected triangle's area) or their weighting of `w` (the hit's `w`, which must be
/// positive) is zero for every ray. Both are affine in the ray's NDC point (the `nx·ny` terms
/// cancel), so zero everywhere where zero at three rays not on one line. `false` for
/// non-finite input, which [`solve`] misses anyway.
///
/// Such triangles (a corner repeated; a plane through the eye, two corners on one line
/// through it) left the f64 filter unsure at every sample, each then solved here (issue 47).
pub(super) fn misses_every_ray(tri: &[[f64; 4]; 3]) -> bool {
    let at = |nx: f64, ny: f64| {
        let (n, p) = numerators(tri, nx, ny)?;
        let w = &n[0] * &p[3] + &n[1] * &p[7] + &n[2] * &p[11];
        Some((&n[0] + &n[1] + &n[2], w))
    };
    let (Some(a), Some(b), Some(c)) = (at(0.0, 0.0), at(1.0, 0.0), at(0.0, 1.0)) else {
        return false;
    };
    let rays = [a, b, c];
    rays.iter().all(|(d, _)| d.is_zero()) || rays.iter().all(|(_, w)| w.is_zero())
}

/// [`super::ray_cast`] decided exactly; `None` for non-finite input.
pub(super) fn ray_cast_exact(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Option<Hit> {
    let Solved { n, d, z, w } = solve(tri, nx, ny, state)?;
    let zw = ratio(&z, &w)?;
    let depth = window_depth(state, zw);
    Some(Hit {
        barycentric: [ratio(&n[0], &d)?, ratio(&n[1], &d)?, ratio(&n[2], &d)?],
        depth,
        clockwise: d.sign() == Sign::Minus,
    })
}

/// Whether [`ray_cast_exact`] hits, without its ratios: the same decisions (its ratios have
/// non-zero denominators, so each is an f64).
pub(super) fn ray_hits_exact(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> bool {
    solve(tri, nx, ny, state).is_some()
}

#[cfg(test)]
mod tests {
    use num_traits::Signed;
    use proptest::prelude::*;
    use refrast::DepthRange;

    use super::*;

    /// The same solve in reduced rationals, written plainly: the integer path must agree.
    fn ray_cast_rational(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Option<Hit> {
        let q = |x: f64| BigRational::from_float(x);
        let (qx, qy) = (q(nx)?, q(ny)?);
        let p: Vec<[BigRational; 4]> = tri
            .iter()
            .map(|v| Some([q(v[0])?, q(v[1])?, q(v[2])?, q(v[3])?]))
            .collect::<Option<_>>()?;
        let u: Vec<BigRational> = p.iter().map(|v| &v[0] - &qx * &v[3]).collect();
        let v: Vec<BigRational> = p.iter().map(|v| &v[1] - &qy * &v[3]).collect();
        let n = [
            &u[1] * &v[2] - &u[2] * &v[1],
            &u[2] * &v[0] - &u[0] * &v[2],
            &u[0] * &v[1] - &u[1] * &v[0],
        ];
        let d = &n[0] + &n[1] + &n[2];
        if d.is_zero() {
            return None;
        }
        let b: Vec<BigRational> = n.iter().map(|ni| ni / &d).collect();
        if b.iter().any(Signed::is_negative) {
            return None;
        }
        let at = |k: usize| &b[0] * &p[0][k] + &b[1] * &p[1][k] + &b[2] * &p[2][k];
        let (z, w) = (at(2), at(3));
        let near = !state.clip_near || !near_distance(state.depth_range, z.clone(), w.clone()).is_negative();
        if !w.is_positive() || !near || (state.clip_far && z > w) {
            return None;
        }
        let zw = (&z / &w).to_f64()?;
        let depth = window_depth(state, zw);
        Some(Hit {
            barycentric: [b[0].to_f64()?, b[1].to_f64()?, b[2].to_f64()?],
            depth,
            clockwise: d.is_negative(),
        })
    }

    /// Coordinates that make exact decisions matter: integers, halves, tiny and huge values,
    /// and zeros, so rays graze edges and vertices and triangles turn edge-on.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            (-4i32..=4).prop_map(|k| f64::from(k) * 0.5),
            -2.0f64..2.0,
            (-30000.0f64..30000.0),
            prop_oneof![Just(1e-300), Just(-3e-310), Just(1e300), Just(0.0), Just(-0.0)],
        ]
    }

    fn state() -> impl Strategy<Value = DrawState> {
        (any::<bool>(), any::<bool>(), any::<bool>()).prop_map(|(gl, clip_far, clip_near)| DrawState {
            depth_range: if gl {
                DepthRange::NegativeOneToOne
            } else {
                DepthRange::ZeroToOne
            },
            clip_far,
            clip_near,
            viewport_depth: refrast::ViewportDepth { min: 0.75, max: 0.25 },
            ..DrawState::default()
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1500))]

        #[test]
        fn integers_decide_as_rationals_do(
            tri in prop::array::uniform3(prop::array::uniform4(coordinate())),
            nx in coordinate(),
            ny in coordinate(),
            state in state(),
        ) {
            let hit = ray_cast_exact(&tri, nx, ny, &state);
            prop_assert_eq!(ray_hits_exact(&tri, nx, ny, &state), hit.is_some());
            prop_assert_eq!(hit, ray_cast_rational(&tri, nx, ny, &state));
        }
    }

    #[test]
    fn a_ray_through_a_shared_vertex_hits_it() {
        let tri = [[0.0, 0.0, 0.25, 1.0], [1.0, 0.0, 0.5, 1.0], [0.0, 1.0, 0.75, 1.0]];
        let hit = ray_cast_exact(&tri, 0.0, 0.0, &DrawState::default()).expect("a vertex is inside");
        assert_eq!(
            hit,
            Hit {
                barycentric: [1.0, 0.0, 0.0],
                depth: 0.25,
                // Counter-clockwise in NDC with y up, so counter-clockwise on screen too.
                clockwise: false,
            }
        );
        assert_eq!(
            ray_cast_exact(&tri, 0.5, 0.5, &DrawState::default()).map(|h| h.barycentric),
            Some([0.0, 0.5, 0.5])
        );
        assert_eq!(
            ray_cast_exact(&tri, 0.5, 0.5 + 1e-16, &DrawState::default()),
            None
        );
        assert_eq!(ray_cast_exact(&tri, f64::NAN, 0.0, &DrawState::default()), None);
    }
}
