//! Lines where the 8-bit grid at `w = 1` never takes them: ends off the declared grid and in
//! perspective, and an end behind the eye (points beyond it are `primitive::points`').

use proptest::prelude::*;
use refrast::{Profile, Topology};

use super::primitive::segment;
use super::{FINE_BITS, GRID, side};
use crate::oracle::raster::to_ndc;
use crate::scene::{PrimitiveScene, clip_of};

/// A line end's `w`, and whether its position must then lie on the grid: 1 or a power of two
/// (`x·w` and `x/w` exact, so an off-grid end or a tie stays where it was put), or anything in
/// [0.25, 4), the end then on the grid, where the division's last-bit error rounds away (as
/// `strategy::exact_scene` places triangle vertices).
fn end_w() -> impl Strategy<Value = (f32, bool)> {
    prop_oneof![
        1 => Just((1.0f32, false)),
        1 => (-2i32..=2).prop_map(|k| (2f32.powi(k), false)),
        1 => (0.25f32..4.0).prop_map(|w| (w, true)),
    ]
}

/// A coordinate in 1/512 px ([`FINE_BITS`]) from one in 1/256 px, `odd` half a unit down:
/// on a grid `step` units wide when `on_grid`, else off it, on an exact tie only where the
/// profile says how ties round (`ties`).
fn fine(c: i64, odd: bool, step: i64, on_grid: bool, ties: bool) -> i64 {
    let c = 2 * c - i64::from(odd);
    if on_grid {
        c - c.rem_euclid(step)
    } else if !ties && step > 1 && c.rem_euclid(step) == step / 2 {
        c + 1
    } else {
        c
    }
}

/// One to four segments (a list, or a strip of their ends) whose ends lie off the grid the
/// profile snaps line ends to, half a 1/256-px unit off any 8-bit grid and on its exact snap
/// ties where the profile declares how ties round, with each end's own `w` ([`end_w`]) and
/// depth: where truncation, flooring and rounding disagree.
pub fn off_grid_lines(profile: &Profile) -> impl Strategy<Value = PrimitiveScene> + use<> {
    let snapping = profile.endpoint_snapping.unwrap_or(profile.snapping);
    let bits = snapping.grid_bits().unwrap_or(8).min(16);
    let ties = profile.features.ties_to_even;
    let step = 1i64 << FINE_BITS.saturating_sub(bits);
    let end = || (any::<(bool, bool)>(), end_w(), 0.0f32..1.0);
    (
        prop::collection::vec((segment(), end(), end()), 1..5),
        any::<bool>(),
        side(),
        side(),
    )
        .prop_map(move |(segments, strip, width, height)| {
            let positions: Vec<[f32; 4]> = segments
                .iter()
                .flat_map(|(s, a, b)| [(s[0], a), (s[1], b)])
                .map(|((x, y), &((ox, oy), (w, on_grid), z))| {
                    let (x, y) = (fine(x, ox, step, on_grid, ties), fine(y, oy, step, on_grid, ties));
                    clip_of(width, height, FINE_BITS, x, y, z, w)
                })
                .collect();
            let n = positions.len() as u32;
            let (topology, indices) = if strip {
                (Topology::LineStrip, (0..n).step_by(2).chain([n - 1]).collect())
            } else {
                (Topology::LineList, (0..n).collect())
            };
            PrimitiveScene::of(width, height, positions, topology, indices)
        })
}

/// Lines on the 8-bit grid at `w = 1` ([`super::primitive::lines`]) two times in three, else
/// [`off_grid_lines`] for `profile`.
pub fn any_lines(profile: &Profile) -> impl Strategy<Value = PrimitiveScene> + use<> {
    prop_oneof![2 => super::primitive::lines(), 1 => off_grid_lines(profile)]
}

/// One segment from an end in front of the near plane (`w` in [0.25, 4), `z/w` in
/// [0.05, 1)) to one beyond it, often behind the eye: through a point `c` on the plane `z = 0`
/// (on the 8-bit grid, its own `w`) and on to `k` times as far (`k` in [1.05, 6)), so that the
/// far end's `w` takes any sign; or to an end at `w = 0` exactly, `z` negative.
pub fn behind_eye_line() -> impl Strategy<Value = PrimitiveScene> {
    let front = (0.25f32..4.0, 0.05f32..1.0);
    let beyond = prop_oneof![
        (0.25f32..4.0, 1.05f64..6.0).prop_map(|(wc, k)| Err((wc, k))),
        (-2.0f32..-0.05, (-GRID..GRID, -GRID..GRID)).prop_map(|(z, xy)| Ok((z, xy))),
    ];
    (segment(), front, beyond, side(), side()).prop_map(|(s, (wa, za), beyond, width, height)| {
        let a = clip_of(width, height, 8, s[0].0, s[0].1, za, wa);
        let b = match beyond {
            Err((wc, k)) => {
                let c = clip_of(width, height, 8, s[1].0, s[1].1, 0.0, wc);
                let far = |i: usize| (f64::from(a[i]) + k * (f64::from(c[i]) - f64::from(a[i]))) as f32;
                [far(0), far(1), far(2), far(3)]
            }
            Ok((z, (dx, dy))) => {
                // A direction in NDC-sized units, as a vertex at w = 0 has no position.
                let [nx, ny] = to_ndc(
                    width,
                    height,
                    (s[1].0 + dx) as f64 / 256.0,
                    (s[1].1 + dy) as f64 / 256.0,
                );
                [nx as f32, ny as f32, z, 0.0]
            }
        };
        PrimitiveScene::of(width, height, vec![a, b], Topology::LineList, vec![0, 1])
    })
}
