//! Strategies for the exact rules, built from the profile: they reach a snap tie only when the
//! profile says how ties round, and outside the viewport only as far as its guard band.

use proptest::prelude::*;
use refrast::{GUARD_BAND_REACH, Profile};

use super::{GRID, grid_triangle, inside_triangle, side};
use crate::scene::{Scene, clip_of};

/// Subpixel bits of [`exact_scene`]'s coordinates: one finer than [`GRID`]'s 8, so that an odd
/// coordinate lies exactly halfway between two points of an 8-bit grid.
pub const FINE_BITS: u8 = 9;

/// One triangle needing no clipping, for the exact rules: off the profile's grid, on its exact
/// snap ties if it declares how ties round (`ties_to_even`), and in perspective.
///
/// Each vertex's `w` is 1, a power of two (so that `x·w` and `x/w` are exact and a tie stays a
/// tie), or anything in [0.1, 4) with the vertex then on the profile's grid, where an ulp of
/// error in the division rounds away. `z/w` is in [0, 1.5): past the far plane a fifth of the
/// time, which changes coverage only where far clipping is on (the rules then skip the case).
pub fn exact_scene(profile: &Profile) -> impl Strategy<Value = Scene> + use<> {
    let bits = profile.snapping.grid_bits().unwrap_or(8).min(16);
    let ties = profile.features.ties_to_even;
    // 1/512-px units between two points of the profile's grid (1 when it is finer).
    let step = 1i64 << FINE_BITS.saturating_sub(bits);
    let w = prop_oneof![
        2 => Just((1.0f32, false)),
        1 => (-3i32..=2).prop_map(|k| (2f32.powi(k), false)),
        1 => (0.1f32..4.0).prop_map(|w| (w, true)),
    ];
    let depth = prop_oneof![4 => 0.0f32..1.0, 1 => 1.0f32..1.5];
    (
        inside_triangle(),
        prop::array::uniform3((prop::bool::weighted(0.3), prop::bool::weighted(0.3))),
        prop::array::uniform3((w, depth)),
        side(),
        side(),
    )
        .prop_map(move |(t, halves, wz, width, height)| {
            let positions = (0..3)
                .map(|i| {
                    let ((w, on_grid), z) = wz[i];
                    let place = |c: i64, half: bool| {
                        // Half a 1/256-px unit down, never below 0: still inside the viewport.
                        let c = (c * ((1 << FINE_BITS) / GRID) - i64::from(half)).max(0);
                        fine_coordinate(c, step, on_grid, ties)
                    };
                    let (x, y) = (place(t[i].0, halves[i].0), place(t[i].1, halves[i].1));
                    clip_of(width, height, FINE_BITS, x, y, z, w)
                })
                .collect();
            Scene::new(width, height, positions, vec![[0, 1, 2]])
        })
}

/// A 1/512-px coordinate placed for a grid `step` units wide: on the grid (`on_grid`), or off
/// it but never on an exact tie unless `ties` (one unit up from a tie is off it).
fn fine_coordinate(c: i64, step: i64, on_grid: bool, ties: bool) -> i64 {
    if on_grid {
        c - c.rem_euclid(step)
    } else if !ties && step > 1 && c.rem_euclid(step) == step / 2 {
        c + 1
    } else {
        c
    }
}

/// One grid triangle reaching outside the viewport as far as the declared guard band, at most
/// the reference's ([`GUARD_BAND_REACH`]): a quarter of the time with two vertices anywhere
/// that far out, otherwise a [`grid_triangle`] with each coordinate clamped to that reach.
///
/// The reach is counted from the top-left 16 × 16 pixels, which every viewport side contains.
pub fn guard_band_scene(reach_px: u32) -> impl Strategy<Value = Scene> + use<> {
    let reach = i64::from(reach_px.min(GUARD_BAND_REACH)) * GRID;
    let within = move |c: i64| c.clamp(-reach, 16 * GRID + reach);
    let far = move || (-reach..=16 * GRID + reach, -reach..=16 * GRID + reach);
    let triangle = prop_oneof![
        3 => grid_triangle(),
        1 => (grid_triangle(), far(), far()).prop_map(|([a, _, _], b, c)| [a, b, c]),
    ];
    (triangle, side(), side()).prop_map(move |(t, w, h)| {
        let t = t.map(|(x, y)| (within(x), within(y)));
        Scene::from_subpixels(w, h, 8, &[t], 0.5)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a 4-bit grid (32 fine units a step) a tie is 16 units past a grid point: kept only
    /// when ties are declared, moved one unit off otherwise, and rounded down onto the grid when
    /// the vertex must sit on it.
    #[test]
    fn a_coordinate_meets_a_tie_only_when_ties_are_declared() {
        assert_eq!(fine_coordinate(48, 32, false, true), 48);
        assert_eq!(fine_coordinate(48, 32, false, false), 49);
        assert_eq!(fine_coordinate(47, 32, false, false), 47);
        assert_eq!(fine_coordinate(48, 32, true, true), 32);
        // At 8 bits every odd coordinate is a tie; at 9 bits or more none is.
        assert_eq!(fine_coordinate(7, 2, false, false), 8);
        assert_eq!(fine_coordinate(7, 1, false, false), 7);
    }
}
