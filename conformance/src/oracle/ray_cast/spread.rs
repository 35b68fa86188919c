//! The ray cast near a sample: how far clipping and then snapping can move a fragment's values.
//!
//! A rasterizer that clips a triangle and then snaps the polygon's vertices draws values no
//! exact ray cast at the sample gives, because the cut vertices moved. They are still the exact
//! values of a nearby point. Take the fan triangle covering sample `s`, with snapped vertices
//! `p̂ⱼ = pⱼ + eⱼ` (each `eⱼ` within `δ` on each axis), their own `wⱼ`, their barycentrics `Bⱼ`
//! in the input triangle and their window depths `dⱼ`. With screen weights `μ` (`s = Σ μⱼ p̂ⱼ`,
//! `μ ≥ 0`, `Σ μ = 1`) it reports barycentrics `Σ λⱼ Bⱼ` with `λⱼ ∝ μⱼ / wⱼ`, and depth
//! `Σ μⱼ dⱼ`. The exact polygon point with homogeneous weights `λ` has exactly those values,
//! and it projects to `s' = Σ μⱼ pⱼ = s − Σ μⱼ eⱼ`, within `δ` of `s` on each axis. So the
//! fragment's values are the exact values at some point of the box `s ± δ`.
//!
//! Barycentrics and window depth are linear-fractional in the sample's NDC position
//! (`nᵢ / Σ nⱼ` and `Σ nᵢ zᵢ / Σ nᵢ wᵢ`, each `nᵢ` affine), so where the denominators keep
//! their sign their level sets are lines, and their extremes over the box lie at its corners:
//! the bound is the largest difference between a corner and the sample itself.

use refrast::DrawState;

use crate::oracle::raster::window_depth;

/// The input triangle's plane at one NDC point, whether or not the point is inside the triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneValue {
    /// Perspective-correct barycentrics.
    pub barycentric: [f64; 3],
    /// Window depth, unclamped.
    pub depth: f64,
}

/// The plane at a sample and how far its values move within the box around it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// The values at the sample itself.
    pub at: PlaneValue,
    /// The largest change of any barycentric between the sample and a point of the box.
    pub barycentric: f64,
    /// The largest change of the window depth between the sample and a point of the box.
    pub depth: f64,
}

/// How much larger than a denominator the sum of its terms' magnitudes may be.
///
/// Every quantity here is a sum of products of inputs, each rounded within about `6ε` of that
/// magnitude, so at 2^20 the values are within `6ε·2^20 ≈ 1.4e-9` of exact: far below any
/// profile's precision (2^-18 ≈ 3.8e-6 for the reference). Closer to edge-on, no bound is given.
pub(super) const CANCELLATION: f64 = 1_048_576.0;

/// Whether a computed `sum` is far enough from zero, for terms of total `magnitude`, that its
/// sign and its quotients are settled.
fn settled(sum: f64, magnitude: f64) -> bool {
    sum.is_finite() && magnitude.is_finite() && magnitude <= CANCELLATION * sum.abs()
}

/// The plane at NDC `(nx, ny)` with the signs of its two denominators (barycentric, depth);
/// `None` where the ray is (nearly) parallel to the plane or rounding could decide a sign.
pub(super) fn plane_at(
    tri: &[[f64; 4]; 3],
    nx: f64,
    ny: f64,
    state: &DrawState,
) -> Option<(PlaneValue, [bool; 2])> {
    let u = tri.map(|p| p[0] - nx * p[3]);
    let v = tri.map(|p| p[1] - ny * p[3]);
    // Magnitudes of u and v before cancellation, which bound their rounding and their products'.
    let au = tri.map(|p| p[0].abs() + (nx * p[3]).abs());
    let av = tri.map(|p| p[1].abs() + (ny * p[3]).abs());
    let pairs = [(1, 2), (2, 0), (0, 1)];
    let n = pairs.map(|(j, k)| u[j] * v[k] - u[k] * v[j]);
    let an = pairs.map(|(j, k)| au[j] * av[k] + au[k] * av[j]);
    let d: f64 = n.iter().sum();
    let ad: f64 = an.iter().sum();
    let zs: f64 = (0..3).map(|i| n[i] * tri[i][2]).sum();
    let ws: f64 = (0..3).map(|i| n[i] * tri[i][3]).sum();
    let az: f64 = (0..3).map(|i| an[i] * tri[i][2].abs()).sum();
    let aw: f64 = (0..3).map(|i| an[i] * tri[i][3].abs()).sum();
    if !settled(d, ad) || !settled(ws, aw) {
        return None;
    }
    let zw = zs / ws;
    // The quotient's error: the numerator's over |ws|, plus |z/w| times the denominator's.
    if !settled(ws, az + zw.abs() * aw) {
        return None;
    }
    let value = PlaneValue {
        barycentric: n.map(|ni| ni / d),
        depth: window_depth(state, zw),
    };
    Some((value, [d > 0.0, ws > 0.0]))
}

/// The plane at NDC `(nx, ny)` and its spread over the box `± half` (NDC) around it.
///
/// `None` when a denominator may change sign in the box (the ray turns parallel to the
/// plane: the values there are unbounded) or is too close to zero to evaluate.
#[must_use]
pub fn spread(tri: &[[f64; 4]; 3], nx: f64, ny: f64, half: [f64; 2], state: &DrawState) -> Option<Spread> {
    let (at, signs) = plane_at(tri, nx, ny, state)?;
    let mut out = Spread {
        at,
        barycentric: 0.0,
        depth: 0.0,
    };
    // Both denominators are affine in (nx, ny): the same sign at the four corners means the
    // same sign everywhere in the box.
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        let (corner, corner_signs) = plane_at(tri, nx + sx * half[0], ny + sy * half[1], state)?;
        if corner_signs != signs {
            return None;
        }
        for k in 0..3 {
            out.barycentric = out
                .barycentric
                .max((corner.barycentric[k] - at.barycentric[k]).abs());
        }
        out.depth = out.depth.max((corner.depth - at.depth).abs());
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use refrast::DepthRange;

    use super::*;

    /// The default state under clip volume `range`.
    fn volume(range: DepthRange) -> DrawState {
        DrawState {
            depth_range: range,
            ..DrawState::default()
        }
    }

    /// At w = 1 everything is affine: the spread is the gradient times the box, exactly.
    #[test]
    fn an_affine_plane_spreads_by_its_gradient() {
        // b₁ = (x + 1)/2 and z = 0.25 + 0.5·b₁: gradients ½ and ¼ per NDC unit.
        let tri = [
            [-1.0, 0.0, 0.25, 1.0],
            [1.0, 0.0, 0.75, 1.0],
            [-1.0, 2.0, 0.25, 1.0],
        ];
        let s = spread(&tri, 0.0, 0.5, [0.01, 0.02], &volume(DepthRange::ZeroToOne)).unwrap();
        assert!((s.at.barycentric[1] - 0.5).abs() < 1e-15, "{s:?}");
        assert!((s.at.depth - 0.5).abs() < 1e-15, "{s:?}");
        // b₂ = y/2 moves by 0.01 over ±0.02; b₀ = 1 − b₁ − b₂ by 0.005 + 0.01.
        assert!((s.barycentric - 0.015).abs() < 1e-12, "{s:?}");
        assert!((s.depth - 0.0025).abs() < 1e-12, "{s:?}");
    }

    /// Perspective bends the values; every point of the box stays within the bound.
    #[test]
    fn points_inside_the_box_stay_within_the_spread() {
        let tri = [
            [-1.0, -1.0, 0.1, 1.0],
            [6.0, -2.0, 1.0, 3.0],
            [0.0, 3.0, 0.5, 0.5],
        ];
        let half = [0.05, 0.03];
        let s = spread(&tri, 0.1, 0.2, half, &volume(DepthRange::NegativeOneToOne)).unwrap();
        for i in 0..=10 {
            for j in 0..=10 {
                let (fx, fy) = (f64::from(i) / 5.0 - 1.0, f64::from(j) / 5.0 - 1.0);
                let (p, _) = plane_at(
                    &tri,
                    0.1 + fx * half[0],
                    0.2 + fy * half[1],
                    &volume(DepthRange::NegativeOneToOne),
                )
                .unwrap();
                for k in 0..3 {
                    assert!((p.barycentric[k] - s.at.barycentric[k]).abs() <= s.barycentric + 1e-12);
                }
                assert!((p.depth - s.at.depth).abs() <= s.depth + 1e-12);
            }
        }
        assert!(s.barycentric > 0.0 && s.depth > 0.0);
    }

    use proptest::strategy::Strategy;

    proptest::proptest! {
        /// Any triangle, any box: wherever a bound is given, every point of a 9 × 9 lattice
        /// over the box stays within it (up to the 2^-20 cancellation's rounding).
        #[test]
        fn the_corners_bound_the_whole_box(
            tri in proptest::array::uniform3((-3.0f64..3.0, -3.0f64..3.0, 0.0f64..1.0, 0.5f64..3.0)
                .prop_map(|(x, y, z, w)| [x, y, z, w])),
            centre in proptest::array::uniform2(-1.0f64..1.0),
            half in proptest::array::uniform2(0.0f64..0.1),
        ) {
            let range = &volume(DepthRange::ZeroToOne);
            // With every w positive the plane is rarely edge-on, so most cases give a bound.
            if let Some(s) = spread(&tri, centre[0], centre[1], half, range) {
                for i in 0..=8 {
                    for j in 0..=8 {
                        let (fx, fy) = (f64::from(i) / 4.0 - 1.0, f64::from(j) / 4.0 - 1.0);
                        let at = (centre[0] + fx * half[0], centre[1] + fy * half[1]);
                        let Some((p, _)) = plane_at(&tri, at.0, at.1, range) else { continue };
                        let slack = 1e-6 * (1.0 + s.barycentric + s.depth);
                        for k in 0..3 {
                            proptest::prop_assert!(
                                (p.barycentric[k] - s.at.barycentric[k]).abs() <= s.barycentric + slack
                            );
                        }
                        proptest::prop_assert!((p.depth - s.at.depth).abs() <= s.depth + slack);
                    }
                }
            }
        }
    }

    /// A box the plane's horizon passes through has no bound.
    #[test]
    fn a_box_across_the_horizon_has_no_bound() {
        // The plane's points (b₁, b₂, ·, 1 − b₁) reach x/w = b₁/(1 − b₁) → −1 only as b₁ → ∞:
        // the vertical line x = −1 is its horizon, where the ray runs parallel to it.
        let tri = [[0.0, 0.0, 0.5, 1.0], [1.0, 0.0, 0.5, 0.0], [0.0, 1.0, 0.5, 1.0]];
        assert!(spread(&tri, 0.5, 0.2, [0.1, 0.1], &volume(DepthRange::ZeroToOne)).is_some());
        assert!(spread(&tri, -0.95, 0.2, [0.1, 0.1], &volume(DepthRange::ZeroToOne)).is_none());
    }
}
