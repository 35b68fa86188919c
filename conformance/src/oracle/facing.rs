//! Which way a triangle turns on screen for an implementation with a given profile, and whether
//! every correct such implementation must agree.
//!
//! A rule that draws under a cull mode orients what it draws to face front and expects the
//! culled triangles absent; both need the winding an implementation will see. That is the sign
//! of the snapped area for a triangle drawn whole (D3D11.3 §15.11: "Culling of primitives is
//! done after they are snapped"; Vulkan's facing comes from the area "computed in framebuffer
//! coordinates", which keep `subPixelPrecisionBits`), even for a sliver whose unsnapped area has
//! the other sign, and of `det[x y w]` for one the near or far plane cuts (Olano–Greer). Where a
//! correct implementation may see the other sign (a vertex whose rounding the profile leaves
//! open, a triangle clipped at x/y beyond the guard band, a clipped polygon seen edge-on), the
//! winding is [`Turn::Unsure`] and a rule must accept either.

use refrast::{DrawState, Profile};

use super::brute_force::orient2d;
use super::outline::visible_outline;
use super::raster::{Point, on_grid, outside_depth_planes, project, to_raster};

/// How a triangle turns on screen as an implementation with some profile may see it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    /// Clockwise on screen (y down), whatever a correct implementation's rounding.
    Clockwise,
    /// Counter-clockwise on screen.
    CounterClockwise,
    /// Zero area as drawn: no sample is covered, whatever the facing (Vulkan: back-facing).
    Degenerate,
    /// Correct implementations may see either sign: a rule must accept both.
    Unsure,
}

impl Turn {
    /// The turn of a signed doubled area, with y down: positive is clockwise.
    fn of_sign(area2: f64) -> Self {
        if area2 > 0.0 {
            Self::Clockwise
        } else if area2 < 0.0 {
            Self::CounterClockwise
        } else {
            Self::Degenerate
        }
    }

    /// The same triangle with its winding reversed.
    #[must_use]
    pub fn reversed(self) -> Self {
        match self {
            Self::Clockwise => Self::CounterClockwise,
            Self::CounterClockwise => Self::Clockwise,
            other => other,
        }
    }

    /// Whether a triangle turning this way is drawn under `state`: `Some(false)` when it is
    /// culled or has zero area, `None` when that depends on which correct rounding happens.
    #[must_use]
    pub fn drawn(self, state: &DrawState) -> Option<bool> {
        // Both faces culled: not drawn, whichever way it turns.
        if state.cull.culls(true) && state.cull.culls(false) {
            return Some(false);
        }
        let front = self.front_facing(state)?;
        Some(!state.cull.culls(front))
    }

    /// Whether it faces front under `state`'s front face; `Some(false)` for zero area (back),
    /// `None` when unsure.
    #[must_use]
    pub fn front_facing(self, state: &DrawState) -> Option<bool> {
        let clockwise = match self {
            Self::Clockwise => true,
            Self::CounterClockwise => false,
            Self::Degenerate => return Some(false),
            Self::Unsure => return None,
        };
        Some(clockwise == (state.front_face == refrast::FrontFace::Clockwise))
    }
}

/// The grid points an implementation with `profile` may snap a clip-space position to, per its
/// snapping claims ([`SnapAccuracy::candidates`](refrast::SnapAccuracy::candidates)): the nearest (both at an exact tie unless it
/// rounds ties to even), either neighbour on each axis ([`SnapAccuracy::WithinOneStep`](refrast::SnapAccuracy::WithinOneStep)), or
/// the one floor or truncation gives; refrast's choice (nearest, half to even) first. `None` when the position does not project to a point [`on_grid`] or
/// the profile has no grid.
#[must_use]
pub fn snap_candidates(p: [f32; 4], width: u32, height: u32, profile: &Profile) -> Option<Vec<Point>> {
    let bits = profile.snapping.grid_bits()?.min(16);
    let [x, y, _, w] = p.map(f64::from);
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let scale = f64::from(1u32 << bits);
    let [rx, ry] = to_raster(width, height, x / w, y / w).map(|c| c * scale);
    if !(on_grid(rx) && on_grid(ry)) {
        return None;
    }
    let f = &profile.features;
    let axis = |v: f64| -> Vec<i128> {
        f.snap
            .candidates(v, f.ties_to_even)
            .into_iter()
            .map(|c| c as i128)
            .collect()
    };
    let (xs, ys) = (axis(rx), axis(ry));
    Some(xs.iter().flat_map(|&x| ys.iter().map(move |&y| (x, y))).collect())
}

/// Every way an implementation with `profile` may snap triangle `tri`: one triangle per
/// combination of its vertices' [`snap_candidates`] (at most 64), refrast's own first. `None`
/// when a vertex does not project or the profile has no grid.
#[must_use]
pub fn snapped_variants(
    tri: &[[f32; 4]; 3],
    width: u32,
    height: u32,
    profile: &Profile,
) -> Option<Vec<[Point; 3]>> {
    let [a, b, c] = tri.map(|p| snap_candidates(p, width, height, profile));
    let (a, b, c) = (a?, b?, c?);
    let mut out = Vec::with_capacity(a.len() * b.len() * c.len());
    for &pa in &a {
        for &pb in &b {
            for &pc in &c {
                out.push([pa, pb, pc]);
            }
        }
    }
    Some(out)
}

/// How triangle `tri` turns on screen for an implementation with `profile` drawing it under
/// `state` on a `width × height` target.
#[must_use]
pub fn turn(tri: &[[f32; 4]; 3], width: u32, height: u32, state: &DrawState, profile: &Profile) -> Turn {
    let wide = tri.map(|p| p.map(f64::from));
    if wide.iter().flatten().any(|c| !c.is_finite()) {
        return Turn::Unsure;
    }
    let cut = wide
        .iter()
        .any(|&[_, _, z, w]| w <= 0.0 || outside_depth_planes(state, z, w));
    let band = profile.band_px();
    if cut {
        return clipped_turn(&wide, width, height, state, band);
    }
    let raster = wide.map(|p| project(width, height, p));
    let unsnapped = area2(&raster);
    if !unsnapped.is_finite() {
        return Turn::Unsure;
    }
    let reach = f64::from(profile.features.guard_band);
    let beyond = raster.iter().any(|&[x, y]| {
        !(-reach..=f64::from(width) + reach).contains(&x)
            || !(-reach..=f64::from(height) + reach).contains(&y)
    });
    let Some(variants) = snapped_variants(tri, width, height, profile) else {
        // No grid: the float area decides, unless rounding at the band's scale could flip it.
        return if unsnapped.abs() <= margin(&raster, band) {
            if unsnapped == 0.0 {
                Turn::Degenerate
            } else {
                Turn::Unsure
            }
        } else {
            Turn::of_sign(unsnapped)
        };
    };
    let signs: Vec<i128> = variants
        .iter()
        .map(|v| orient2d(v[0], v[1], v[2]).signum())
        .collect();
    if signs.iter().all(|&s| s == 0) {
        return Turn::Degenerate;
    }
    let first = signs[0];
    if signs.iter().any(|&s| s != first) {
        // The profile's snapping may land a vertex either side of the line through the others.
        return Turn::Unsure;
    }
    // Beyond the guard band x/y clipping may cut it, and the implementation takes facing from
    // its snapped, clipped polygon: sure only where that cannot turn the other way.
    if beyond && (unsnapped.signum() != first as f64 || unsnapped.abs() <= margin(&raster, band)) {
        return Turn::Unsure;
    }
    Turn::of_sign(first as f64)
}

/// The turn of a triangle the near or far plane (or `w ≤ 0`) cuts: its visible outline's, sure
/// only where snapping its cut vertices by the band cannot turn it over.
fn clipped_turn(tri: &[[f64; 4]; 3], width: u32, height: u32, state: &DrawState, band: f64) -> Turn {
    let outline = visible_outline(tri, width, height, state);
    if outline.is_empty() {
        return Turn::Degenerate;
    }
    // `det[x y w] < 0` is clockwise on screen (y down), for any signs of w (Olano–Greer).
    let [a, b, c] = tri.map(|p| [p[0], p[1], p[3]]);
    let terms = [
        a[0] * (b[1] * c[2] - c[1] * b[2]),
        -a[1] * (b[0] * c[2] - c[0] * b[2]),
        a[2] * (b[0] * c[1] - c[0] * b[1]),
    ];
    let det: f64 = terms.iter().sum();
    let size: f64 = terms.iter().map(|t| t.abs()).sum();
    if det.abs() <= 1e-9 * size {
        return Turn::Unsure;
    }
    let sign = Turn::of_sign(-det);
    if outline.iter().all(|p| p.finite) {
        let points: Vec<[f64; 2]> = outline.iter().map(|p| p.position).collect();
        if area2(&points).abs() <= margin(&points, band) {
            return Turn::Unsure;
        }
    }
    sign
}

/// Twice the signed area of a polygon in raster space (y down): positive when clockwise.
fn area2(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (p, q) = (points[i], points[(i + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum()
}

/// How far a polygon's doubled area may move when each vertex moves by up to `band` pixels:
/// twice the perimeter times the band, plus the band's square per vertex; plus what f64
/// rounding of [`area2`]'s shoelace sum may lose (huge coordinates cancel).
fn margin(points: &[[f64; 2]], band: f64) -> f64 {
    let n = points.len();
    let (perimeter, size) = (0..n).fold((0.0, 0.0), |(perimeter, size), i| {
        let (p, q) = (points[i], points[(i + 1) % n]);
        (
            perimeter + (q[0] - p[0]).hypot(q[1] - p[1]),
            size + (p[0] * q[1]).abs() + (q[0] * p[1]).abs(),
        )
    });
    let rounding = (n + 2) as f64 * f64::EPSILON * size;
    2.0 * band * perimeter + 4.0 * band * band * n as f64 + rounding
}

#[cfg(test)]
mod tests {
    use refrast::{CullMode, FrontFace, Rasterizer, Reference, ReferenceConfig, SnapRounding};

    use super::*;
    use refrast::SnapAccuracy;

    fn reference() -> Profile {
        Reference::default().profile()
    }

    /// A shrunk case from judging restricted profiles on every rule (docs/profiles.md):
    /// clockwise on screen, culled under back-face culling with counter-clockwise front faces,
    /// drawn once reversed.
    #[test]
    fn a_clockwise_triangle_is_culled_as_a_back_face() {
        let tri = [
            [-1.0, 1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, -1.0, 0.5, 1.0],
        ];
        let t = [tri[2], tri[0], tri[1]];
        let state = DrawState {
            cull: CullMode::Back,
            ..DrawState::default()
        };
        let turn = turn(&t, 16, 16, &state, &reference());
        assert_eq!(turn, Turn::Clockwise);
        assert_eq!(turn.drawn(&state), Some(false));
        assert_eq!(turn.reversed().drawn(&state), Some(true));
        let cw = DrawState {
            front_face: FrontFace::Clockwise,
            ..state
        };
        assert_eq!(turn.drawn(&cw), Some(true));
    }

    /// Found by the `robustness` fuzz target in CI: vertices near f32::MAX snapped to grid
    /// points whose i128 products overflowed. Beyond 2^60 grid steps there is no grid point; a
    /// huge triangle's turn comes from floats, sure only well clear of their rounding.
    #[test]
    fn huge_coordinates_turn_without_overflow() {
        let state = DrawState::default();
        let big = f32::MAX;
        let wide = [
            [-big, -big, 0.5, 1.0],
            [big, -big, 0.5, 1.0],
            [0.0, big, 0.5, 1.0],
        ];
        assert_eq!(snap_candidates(wide[0], 16, 16, &reference()), None);
        assert_eq!(turn(&wide, 16, 16, &state, &reference()), Turn::CounterClockwise);
        // Three nearly collinear huge points: f64 cannot tell their side.
        let line = [[-big, -big, 0.5, 1.0], [big, big, 0.5, 1.0], [0.0, 1.0, 0.5, 1.0]];
        assert_eq!(turn(&line, 16, 16, &state, &reference()), Turn::Unsure);
    }

    /// On a 4-bit grid, a vertex exactly on a snap tie has two places unless ties go to even;
    /// within one step, every vertex off the grid has two per axis.
    #[test]
    fn candidates_follow_the_snapping_claims() {
        let four = |snap, ties_to_even| {
            let mut p = Reference::new(ReferenceConfig {
                subpixel_bits: refrast::SubpixelBits::new(4).expect("4 bits"),
                ..ReferenceConfig::default()
            })
            .profile();
            p.features.snap = snap;
            p.features.ties_to_even = ties_to_even;
            p
        };
        // Raster x = 1 + 1/32 px: halfway between 16/16 and 17/16; y = 8 exactly.
        let nx = ((1.0 + 1.0 / 32.0) / 16.0 * 2.0 - 1.0) as f32;
        let p = [nx, 0.0, 0.5, 1.0];
        let at = |profile: &Profile| snap_candidates(p, 16, 16, profile).expect("projects");
        assert_eq!(at(&four(SnapAccuracy::Nearest, true)), [(16, 128)]);
        assert_eq!(at(&four(SnapAccuracy::Nearest, false)), [(16, 128), (17, 128)]);
        assert_eq!(
            at(&four(SnapAccuracy::WithinOneStep, true)),
            [(16, 128), (17, 128)]
        );
        // Off a tie, within one step: the nearest first, then the other neighbour.
        let q = [((1.0 + 3.0 / 64.0) / 16.0 * 2.0 - 1.0) as f32, 0.0, 0.5, 1.0];
        let within = snap_candidates(q, 16, 16, &four(SnapAccuracy::WithinOneStep, true));
        assert_eq!(within.expect("projects"), [(17, 128), (16, 128)]);
        // Floor and truncation: one point each, apart left of the viewport (raster x < 0).
        let at_q = |snap| snap_candidates(q, 16, 16, &four(snap, false)).expect("projects");
        assert_eq!(at_q(SnapAccuracy::Floor), [(16, 128)]);
        assert_eq!(at_q(SnapAccuracy::TowardZero), [(16, 128)]);
        let left = [((-1.0 - 3.0 / 64.0) / 16.0 * 2.0 - 1.0) as f32, 0.0, 0.5, 1.0];
        let at_left = |snap| snap_candidates(left, 16, 16, &four(snap, false)).expect("projects");
        assert_eq!(at_left(SnapAccuracy::Floor), [(-17, 128)]);
        assert_eq!(at_left(SnapAccuracy::TowardZero), [(-16, 128)]);
        assert_eq!(snap_candidates([0.0, 0.0, 0.0, -1.0], 16, 16, &reference()), None);
    }

    /// A sliver that snapping turns over turns as snapped, and one whose snapped area is zero
    /// draws nothing.
    #[test]
    fn a_sliver_turns_as_snapped() {
        let profile = Reference::new(ReferenceConfig {
            snap_rounding: SnapRounding::NearestEven,
            ..ReferenceConfig::default()
        })
        .profile();
        let state = DrawState::default();
        // Raster (1, 1), (9, 1.001), (5, 1.0025): unsnapped clockwise, snapped (1/256 px grid)
        // to (256, 256), (2304, 256), (1280, 257): also clockwise, sure.
        let at = |x: f64, y: f64| [(x / 8.0 - 1.0) as f32, (1.0 - y / 8.0) as f32, 0.5, 1.0];
        let sure = [at(1.0, 1.0), at(9.0, 1.001), at(5.0, 1.0025)];
        assert_eq!(turn(&sure, 16, 16, &state, &profile), Turn::Clockwise);
        // (5, 1.0004) snaps onto the line y = 1: zero area as drawn.
        let flat = [at(1.0, 1.0), at(9.0, 1.0), at(5.0, 1.0004)];
        assert_eq!(turn(&flat, 16, 16, &state, &profile), Turn::Degenerate);
        // (5, 1.0019) snaps onto y = 1 and (9, 1.0021) to 1 + 1/256: snapped clockwise, but the
        // unsnapped third vertex lies above the line through the first two (1.0038 at x = 9),
        // so the unsnapped triangle turns counter-clockwise.
        let flipped = [at(1.0, 1.0), at(5.0, 1.0019), at(9.0, 1.0021)];
        assert_eq!(turn(&flipped, 16, 16, &state, &profile), Turn::Clockwise);
    }

    /// A triangle crossing the near plane turns as `det[x y w]` says, and a sliver of one seen
    /// edge-on is unsure.
    #[test]
    fn a_clipped_triangle_turns_by_its_determinant() {
        let state = DrawState::default();
        let ccw = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, -0.5, 1.0],
        ];
        assert_eq!(turn(&ccw, 16, 16, &state, &reference()), Turn::CounterClockwise);
        let cw = [ccw[0], ccw[2], ccw[1]];
        assert_eq!(turn(&cw, 16, 16, &state, &reference()), Turn::Clockwise);
        let edge_on = [[-0.5, 0.0, 0.5, 1.0], [0.5, 0.0, 0.5, 1.0], [0.0, 0.0, -0.5, 1.0]];
        assert_ne!(turn(&edge_on, 16, 16, &state, &reference()), Turn::Clockwise);
        assert_ne!(
            turn(&edge_on, 16, 16, &state, &reference()),
            Turn::CounterClockwise
        );
    }
}
