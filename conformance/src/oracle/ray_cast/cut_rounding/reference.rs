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
    let cuts = |plane: usize| (plane < 2 || state.clip_far) && tri.iter().any(|v| distance(plane, v) < 0.0);
    let planes = [cuts(0), cuts(1), cuts(2)];
    if planes == [false; 3] {
        return 0.0;
    }
    let at = |x: f64, y: f64| {
        let [nx, ny] = to_ndc(width, height, x, y);
        plane_at(tri, nx, ny, range).map(|(value, _)| value.barycentric)
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

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// Per triangle or per sample, the bound is the same at every sample of the viewport
        /// and half a pixel around it, up to rounding (relative 1e-9), and infinite at the same
        /// samples.
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
                    let agree = old == new || (old - new).abs() <= 1e-9 * old.abs().max(new.abs());
                    prop_assert!(agree, "at {s:?}: {old} before, {new} now");
                }
            }
        }
    }
}
