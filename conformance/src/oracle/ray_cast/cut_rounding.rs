//! How far a clipper computing in f32 may move a cut that a clip plane makes.
//!
//! Clip coordinates are f32, and Vulkan bounds no clipping precision: a clipper may compute
//! each cut vertex `A + t(B − A)`, `t = d_A / (d_A − d_B)`, in f32. Each such step rounds
//! the vertex within a few ulps of the coordinates it comes from, and a polygon clipped by up
//! to six planes gathers up to six steps: at most about 28 ulps of the largest coordinate, so
//! `2^-19` of it ([`CLIP_ROUNDING`]) bounds the error `E` of every clip-space component.
//! Cut vertices are convex combinations of the input vertices, so near a sample whose ray hits
//! the triangle's plane at `X = Σ bᵢ Vᵢ`, `E ≤ 2^-19 · Σ |bᵢ| |Vᵢ|∞`. That moves the cut two
//! ways: the plane distance `d` (a sum of two coordinates, so off by `2E`) of the computed cut
//! is zero where the exact one is within `2E`, which lies `2E / |∇d|` pixels away; and the cut
//! vertices' x, y and w move their projection by `E · (1 + |x/w| + |y/w|) / w` in NDC.
//!
//! For an f32 clipper these are real: lavapipe's clipper covers a sample 0.005 px beyond a far-plane
//! cut that runs from a vertex at x = −30000, w = 0 (`clip_rounding_covers_lavapipes_far_cut`).

use refrast::DrawState;

use super::spread::plane_at;
use crate::oracle::raster::{near_distance, to_ndc};

/// Bound on the rounding of a cut vertex's clip coordinates, relative to the largest
/// coordinate it comes from: 32 units in the last place of f32 (`2^-24`), above the 28 of six
/// clipping steps.
pub const CLIP_ROUNDING: f64 = 1.0 / 524_288.0;

#[cfg(test)]
pub(crate) mod reference;

/// How far, in pixels, an f32 clipper may move the cuts of `tri` near raster point `s`: 0 when
/// no plane cuts the triangle, infinity where the triangle's plane cannot be evaluated there
/// (seen edge-on).
#[must_use]
pub fn cut_rounding_px(tri: &[[f64; 4]; 3], width: u32, height: u32, s: [f64; 2], state: &DrawState) -> f64 {
    let range = state.depth_range;
    // The signed distances to the planes that clip: w = 0, near, and far when enabled (a match,
    // not a table of function pointers: it runs for every sample of a clipped triangle).
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
        // The plane is behind the eye along this ray: nothing visible projects here.
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
    use refrast::{CullMode, DepthRange, DrawState};

    use super::*;
    use crate::oracle::outline::{distance_to_outline, visible_outline};
    use crate::oracle::raster::sample_centre;
    use crate::rules::mesh::mesh_expectation;
    use crate::scene::Scene;
    use crate::violation::Expect;

    fn far_clipped() -> DrawState {
        DrawState {
            cull: CullMode::None,
            clip_far: true,
            depth_range: DepthRange::ZeroToOne,
            ..DrawState::default()
        }
    }

    /// The distance from pixel `(x, y)`'s sample to the cuts of `scene`'s triangle, and how
    /// far rounding may move them there.
    fn cut_and_rounding(scene: &Scene, x: u32, y: u32) -> (f64, f64) {
        let tri = scene.positions_of(0);
        let s = sample_centre(x, y);
        let outline = visible_outline(&tri, scene.width, scene.height, &scene.state);
        let d = distance_to_outline(&outline, s, |a, b| a.edges & b.edges == 0);
        (
            d,
            cut_rounding_px(&tri, scene.width, scene.height, s, &scene.state),
        )
    }

    /// lavapipe's `clip.interior` counterexample (case 612 at the default seed): it covers
    /// (12, 29), 0.005 px beyond a far-plane cut running from a vertex at x = −30000, w = 0.
    /// Before the cuts knew about rounding, that sample had to stay uncovered.
    #[test]
    fn clip_rounding_covers_lavapipes_far_cut() {
        let mut scene = Scene::new(
            16,
            32,
            vec![
                [2.395_028_4, 0.0, 1.855_659_2, 1.855_659_2],
                [0.0, -3000.0, -0.080_122_16, -0.1],
                [-30000.0, 1.276_549_9, -0.230_131_86, 0.0],
            ],
            vec![[0, 1, 2]],
        );
        scene.state = far_clipped();
        let (d, r) = cut_and_rounding(&scene, 12, 29);
        assert!(d > 1.0 / 256.0, "outside the band: {d}");
        assert!(d < 1.0 / 256.0 + r, "within rounding: {d} vs {r}");
        let (expected, _) = mesh_expectation(&scene, 1.0 / 256.0);
        assert_eq!(expected[29 * 16 + 12], Expect::ZeroOrOne);
    }

    /// llvmpipe's and softpipe's (case 1597): vertices at x = −44078 and y = −32420.
    #[test]
    fn clip_rounding_covers_llvmpipes_near_cut() {
        let mut scene = Scene::new(
            39,
            64,
            vec![
                [0.0, 0.202_146_25, 0.0, 0.2],
                [-44_078.234, 0.0, 2.702_006, 2.274_348_3],
                [-1.688_258_2, -32_420.537, -0.415_350_94, 1.907_600_2],
            ],
            vec![[0, 1, 2]],
        );
        scene.state = far_clipped();
        let (expected, _) = mesh_expectation(&scene, 1.0 / 256.0);
        let strict = |x: u32, y: u32| {
            let (d, r) = cut_and_rounding(&scene, x, y);
            d >= 1.0 / 256.0 && d < 1.0 / 256.0 + r
        };
        let loosened: Vec<_> = (0..64)
            .flat_map(|y| (0..39).map(move |x| (x, y)))
            .filter(|&(x, y)| strict(x, y))
            .collect();
        assert!(
            !loosened.is_empty(),
            "some sample depends on the clipper's rounding"
        );
        for (x, y) in loosened {
            assert_eq!(expected[(y * 39 + x) as usize], Expect::ZeroOrOne, "({x}, {y})");
        }
    }

    /// Near the view volume (coordinates within 1.5) the rounding stays under half the 1/256-px
    /// band of an 8-bit grid (0.28 of it at worst here), so cuts are judged nearly as sharply as
    /// before.
    #[test]
    fn ordinary_cuts_move_by_little() {
        let tri = [
            [-0.5, -0.5, -0.5, 1.0],
            [0.9, -0.2, 0.7, 1.5],
            [0.1, 0.8, 1.4, 1.2],
        ];
        let state = far_clipped();
        let worst = (0..64)
            .flat_map(|y| (0..64).map(move |x| sample_centre(x, y)))
            .map(|s| cut_rounding_px(&tri, 64, 64, s, &state))
            .fold(0.0, f64::max);
        assert!(worst < 0.5 / 256.0, "{worst}");
    }

    /// Nothing cut, nothing moved.
    #[test]
    fn uncut_triangles_have_no_rounding() {
        let tri = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, 1.0],
        ];
        assert_eq!(cut_rounding_px(&tri, 16, 16, [8.0, 8.0], &far_clipped()), 0.0);
    }
}
