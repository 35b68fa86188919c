//! The per-sample form of [`super::cut_rounding_px`] that the per-triangle one replaced, kept so
//! tests can show both compute the same bound.

use refrast::DrawState;

use super::super::spread::plane_at;
use super::CLIP_ROUNDING;
use crate::oracle::raster::{near_distance, to_ndc};

/// How far, in pixels, an f32 clipper may move the cuts of `tri` near raster point `s`, from
/// five full evaluations of the plane: the bound as it was first written.
#[must_use]
pub fn cut_rounding_px(tri: &[[f64; 4]; 3], width: u32, height: u32, s: [f64; 2], state: &DrawState) -> f64 {
    let range = state.depth_range;
    let distance = |plane: usize, p: &[f64; 4]| match plane {
        0 => p[3],
        1 => near_distance(range, p[2], p[3]),
        _ => p[3] - p[2],
    };
    let cuts = |plane: usize| {
        [true, state.clip_near, state.clip_far][plane] && tri.iter().any(|v| distance(plane, v) < 0.0)
    };
    let planes = [cuts(0), cuts(1), cuts(2)];
    if planes == [false; 3] {
        return 0.0;
    }
    let at = |x: f64, y: f64| {
        let [nx, ny] = to_ndc(width, height, x, y);
        plane_at(tri, nx, ny, state).map(|(value, _)| value.barycentric)
    };
    let h = 0.5;
    let (Some(b), Some(left), Some(right), Some(up), Some(down)) = (
        at(s[0], s[1]),
        at(s[0] - h, s[1]),
        at(s[0] + h, s[1]),
        at(s[0], s[1] - h),
        at(s[0], s[1] + h),
    ) else {
        return f64::INFINITY;
    };
    let w: f64 = (0..3).map(|i| b[i] * tri[i][3]).sum();
    if w <= 0.0 {
        return 0.0;
    }
    let size = |v: &[f64; 4]| v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let e = CLIP_ROUNDING * (0..3).map(|i| b[i].abs() * size(&tri[i])).sum::<f64>();
    let [nx, ny] = to_ndc(width, height, s[0], s[1]);
    let half = f64::from(width.max(height)) * 0.5;
    let moved = e * (1.0 + nx.abs() + ny.abs()) / w * half;
    let across = (0..3)
        .filter(|&plane| planes[plane])
        .map(|plane| {
            let value = |b: [f64; 3]| (0..3).map(|i| b[i] * distance(plane, &tri[i])).sum::<f64>();
            let gradient =
                ((value(right) - value(left)) / (2.0 * h)).hypot((value(down) - value(up)) / (2.0 * h));
            2.0 * e / gradient
        })
        .fold(0.0, f64::max);
    moved + across
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;
    use refrast::{CullMode, DepthRange, DrawState};

    use super::super::cut_rounding_px as fast;
    use super::cut_rounding_px as reference;
    use super::{near_distance, plane_at, to_ndc};

    /// A clip-space coordinate from zero through tiny to ±1e5, as f32 holds it.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(0.0),
            -2.0f64..2.0,
            (-7i32..=5, any::<bool>(), 1.0f64..10.0).prop_map(|(e, negative, m)| if negative {
                -m
            } else {
                m
            } * 10f64.powi(e)),
        ]
        .prop_map(|c| f64::from(c as f32))
    }

    fn vertex() -> impl Strategy<Value = [f64; 4]> {
        [coordinate(), coordinate(), coordinate(), coordinate()]
    }

    /// Any triangle, or one whose plane passes within `10^-k` of the eye, so that it is seen
    /// nearly edge-on everywhere and the cancellation checks decide the bound.
    fn triangle() -> impl Strategy<Value = [[f64; 4]; 3]> {
        prop_oneof![
            [vertex(), vertex(), vertex()],
            (vertex(), vertex(), -3.0f64..3.0, -3.0f64..3.0, vertex(), 2i32..12).prop_map(
                |(a, b, s, t, nudge, k)| {
                    let c: [f64; 4] = std::array::from_fn(|i| {
                        f64::from((s * a[i] + t * b[i] + nudge[i] * 10f64.powi(-k)) as f32)
                    });
                    [a, b, c]
                }
            ),
        ]
    }

    fn state() -> impl Strategy<Value = DrawState> {
        (
            any::<bool>(),
            prop_oneof![Just(DepthRange::ZeroToOne), Just(DepthRange::NegativeOneToOne)],
        )
            .prop_map(|(clip_far, depth_range)| DrawState {
                cull: CullMode::None,
                clip_far,
                depth_range,
                ..DrawState::default()
            })
    }

    /// Whether `new` is `old` up to the rounding of either form at `s`: relative 1e-9, or more
    /// where the quantities they divide by cancel; `None` where `old` found the plane edge-on.
    fn rounding_apart(
        tri: &[[f64; 4]; 3],
        width: u32,
        height: u32,
        s: [f64; 2],
        state: &DrawState,
    ) -> Option<f64> {
        let h = 0.5;
        let points = [
            s,
            [s[0] - h, s[1]],
            [s[0] + h, s[1]],
            [s[0], s[1] - h],
            [s[0], s[1] + h],
        ]
        .map(|[x, y]| to_ndc(width, height, x, y));
        let mut b = [[0.0; 3]; 5];
        for (k, p) in points.iter().enumerate() {
            b[k] = plane_at(tri, p[0], p[1], state)?.0.barycentric;
        }
        // plane_at's sums and their terms' magnitudes, which bound their rounding.
        let terms = |[nx, ny]: [f64; 2]| {
            let u = tri.map(|p| (p[0] - nx * p[3], p[0].abs() + (nx * p[3]).abs()));
            let v = tri.map(|p| (p[1] - ny * p[3], p[1].abs() + (ny * p[3]).abs()));
            [(1, 2), (2, 0), (0, 1)].map(|(j, k)| {
                (
                    u[j].0 * v[k].0 - u[k].0 * v[j].0,
                    u[j].1 * v[k].1 + u[k].1 * v[j].1,
                )
            })
        };
        let t = points.map(terms);
        let d = t.map(|t| t.iter().map(|x| x.0).sum::<f64>());
        let ad = t.map(|t| t.iter().map(|x| x.1).sum::<f64>());
        let kappa_d = (0..5).map(|k| ad[k] / d[k].abs()).fold(0.0, f64::max);
        let ws: f64 = (0..3).map(|i| t[0][i].0 * tri[i][3]).sum();
        let aw: f64 = (0..3).map(|i| t[0][i].1 * tri[i][3].abs()).sum();
        let size = tri.map(|v| v.iter().fold(0.0f64, |m, c| m.max(c.abs())));
        let kappa_e = (0..3).map(|i| t[0][i].1 * size[i]).sum::<f64>()
            / (0..3).map(|i| t[0][i].0.abs() * size[i]).sum::<f64>();
        let range = state.depth_range;
        let worst = [0, 1, 2]
            .map(|k| tri.map(|v| [v[3], near_distance(range, v[2], v[3]), v[3] - v[2]][k]))
            .into_iter()
            .enumerate()
            .filter(|&(k, f)| [true, state.clip_near, state.clip_far][k] && f.iter().any(|&d| d < 0.0))
            .map(|(_, f)| {
                let v = b.map(|b| (0..3).map(|i| b[i] * f[i]).sum::<f64>());
                let an_f = t.map(|t| (0..3).map(|i| t[i].1 * f[i].abs()).sum::<f64>());
                // Each value's rounding, either way, and that of the difference as one quotient.
                let old = (1..5)
                    .map(|k| (an_f[k] + ad[k] * v[k].abs()) / d[k].abs())
                    .fold(0.0, f64::max);
                let step = (points[2][0] - points[1][0])
                    .abs()
                    .max((points[4][1] - points[3][1]).abs());
                let new = an_f.iter().fold(0.0f64, |m, &x| m.max(x))
                    * ad.iter().fold(0.0f64, |m, &x| m.max(x))
                    / (d[1] * d[2]).abs().min((d[3] * d[4]).abs())
                    * step;
                let gradient = ((v[2] - v[1]) / (2.0 * h)).hypot((v[4] - v[3]) / (2.0 * h));
                (old + new) / (2.0 * h) / gradient
            })
            .fold(0.0, f64::max);
        // Some 20 roundings of each magnitude on each side: 64 of them covers both.
        Some(1e-9f64.max(64.0 * f64::EPSILON * (kappa_d + aw / ws.abs() + kappa_e + worst)))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// Per triangle or per sample, the bound is the same at every sample of the viewport
        /// and half a pixel around it, up to rounding, and infinite where the plane is edge-on.
        #[test]
        fn per_triangle_setup_computes_the_same_bound(
            tri in triangle(),
            state in state(),
            (width, height) in prop_oneof![Just((1u32, 1u32)), Just((7, 5)), Just((16, 16)), Just((64, 3))],
        ) {
            for y in 0..=2 * height {
                for x in 0..=2 * width {
                    let s = [f64::from(x) * 0.5, f64::from(y) * 0.5];
                    let (old, new) = (reference(&tri, width, height, s, &state), fast(&tri, width, height, s, &state));
                    if old == 0.0 || old == new {
                        prop_assert_eq!(old, new, "at {:?}", s);
                        continue;
                    }
                    let Some(slack) = rounding_apart(&tri, width, height, s, &state) else {
                        prop_assert!(new == f64::INFINITY, "at {s:?}: edge-on, yet {new}");
                        continue;
                    };
                    let agree = (old - new).abs() <= slack * old.abs().max(new.abs());
                    prop_assert!(agree, "at {s:?}: {old} before, {new} now, {slack} apart at most");
                }
            }
        }
    }
}
