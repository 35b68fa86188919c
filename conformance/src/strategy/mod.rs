//! Strategies: free functions that build valid input rather than filter it.
//!
//! Grid strategies work in units of 1/256 pixel (8 subpixel bits) on power-of-two viewports,
//! so clip coordinates are exact in f32 and every implementation sees the same raster points.

use proptest::prelude::*;
use refrast::{DepthRange, Profile};
use spade::{DelaunayTriangulation, Point2, Triangulation};

use crate::scene::{Scene, clip_of};

mod exact;
pub mod primitive;
pub mod reach;
mod sliver;
mod visibility;

pub use exact::{FINE_BITS, exact_scene, guard_band_scene};
pub use sliver::{flipped_sliver, zero_area_across_near};
pub use visibility::{cyclic_scene, interpenetrating_scene};

/// Subpixel units per pixel in grid strategies.
pub const GRID: i64 = 256;

/// Viewport sides used by most rules: small enough to picture, large enough for variety.
///
/// Strategies put the viewport size last in their tuples: proptest shrinks tuple elements in
/// order and never returns to an earlier one, so the geometry shrinks first (to the fewest
/// triangles) and the size after.
pub fn side() -> impl Strategy<Value = u32> {
    prop_oneof![Just(16u32), Just(32), Just(64)]
}

/// Viewport sides of any shape, for rules whose oracle is a ray cast with a band: mostly
/// [`side`], and a quarter of the time any side from 1 to 100 px (odd, prime, not a multiple of
/// 8 or of a tile), where the NDC-to-raster transform is no longer exact in binary.
pub fn any_side() -> impl Strategy<Value = u32> {
    prop_oneof![3 => side(), 1 => 1u32..=100]
}

/// An offset in grid units: often on whole or half pixels (ties for the fill rule), at every
/// scale from a subpixel to far outside any viewport.
pub fn grid_offset() -> impl Strategy<Value = i64> {
    prop_oneof![
        3 => -8 * GRID..8 * GRID,
        2 => (-16i64..16).prop_map(|p| p * GRID),
        2 => (-32i64..32).prop_map(|p| p * GRID / 2),
        2 => -48 * GRID..48 * GRID,
        1 => -(1500 * GRID)..(1500 * GRID),
    ]
}

/// A grid triangle: an anchor on a sample centre or anywhere near a 64-px viewport, and two
/// offsets from it, sometimes making a horizontal or vertical edge.
///
/// Independent of the viewport size, so shrinking never regenerates it.
pub fn grid_triangle() -> impl Strategy<Value = [(i64, i64); 3]> {
    let anchor = prop_oneof![
        (-4i64..68, -4i64..68).prop_map(|(x, y)| (x * GRID + GRID / 2, y * GRID + GRID / 2)),
        (-16 * GRID..80 * GRID, -16 * GRID..80 * GRID),
    ];
    (
        anchor,
        (grid_offset(), grid_offset()),
        (grid_offset(), grid_offset()),
        0..5u8,
    )
        .prop_map(|(a, (bx, by), (cx, cy), shape)| {
            let (b, mut c) = ((a.0 + bx, a.1 + by), (a.0 + cx, a.1 + cy));
            match shape {
                0 => c.1 = a.1,
                1 => c.0 = b.0,
                _ => {}
            }
            [a, b, c]
        })
}

/// A scene of one grid triangle at depth ½ on a power-of-two viewport.
pub fn grid_scene() -> impl Strategy<Value = Scene> {
    (grid_triangle(), side(), side()).prop_map(|(t, w, h)| Scene::from_subpixels(w, h, 8, &[t], 0.5))
}

/// A scene of one grid triangle whose vertices have their own `w` in [0.1, 4] and depth in
/// [0, 1]: perspective, but every projected vertex is still exactly on the grid.
pub fn perspective_grid_scene() -> impl Strategy<Value = Scene> {
    perspective(grid_triangle())
}

/// One grid triangle from `triangle` with its own `w` in [0.1, 4] and depth in [0, 1] per vertex.
fn perspective(triangle: impl Strategy<Value = [(i64, i64); 3]>) -> impl Strategy<Value = Scene> {
    (
        triangle,
        prop::array::uniform3((0.1f32..4.0, 0.0f32..1.0)),
        side(),
        side(),
    )
        .prop_map(|(t, wz, w, h)| {
            let positions = (0..3)
                .map(|i| clip_of(w, h, 8, t[i].0, t[i].1, wz[i].1, wz[i].0))
                .collect();
            Scene::new(w, h, positions, vec![[0, 1, 2]])
        })
}

/// A grid triangle within the top-left 16 × 16 pixels (every viewport side is at least 16):
/// it needs no clipping, so no implementation moves its edges. Vertices often sit on sample
/// centres or pixel edges; a sixth of the triangles lie within one pixel (sub-pixel
/// triangles, which the other branches almost never make).
pub fn inside_triangle() -> impl Strategy<Value = [(i64, i64); 3]> {
    let coordinate = || {
        prop_oneof![
            2 => 0..=16 * GRID,
            1 => (0i64..16).prop_map(|p| p * GRID + GRID / 2),
            1 => (0i64..=16).prop_map(|p| p * GRID),
        ]
    };
    let within_one_pixel = ((0i64..16, 0i64..16), prop::array::uniform3((0..=GRID, 0..=GRID)))
        .prop_map(|((px, py), t)| t.map(|(x, y)| (px * GRID + x, py * GRID + y)));
    prop_oneof![5 => prop::array::uniform3((coordinate(), coordinate())), 1 => within_one_pixel]
}

/// One triangle inside the viewport at depth ½, `w = 1`.
pub fn inside_scene() -> impl Strategy<Value = Scene> {
    (inside_triangle(), side(), side()).prop_map(|(t, w, h)| Scene::from_subpixels(w, h, 8, &[t], 0.5))
}

/// One triangle inside the viewport with its own `w` in [0.1, 4] and depth in [0, 1] per vertex.
pub fn perspective_inside_scene() -> impl Strategy<Value = Scene> {
    perspective(inside_triangle())
}

/// `scenes` under either clip volume the profile supports: where it supports both, half of them
/// move to OpenGL's `−w ≤ z ≤ w`; where only that one, all of them. A scene moved there has each
/// `z` mapped to `2z − w`, so that every vertex keeps its window depth.
///
/// For the depth rules, which otherwise would never see the OpenGL range's window depth
/// `(z/w + 1)/2` (mutation testing found it unjudged); a profile with one range gets scenes
/// drawn as generated under it, not moved into the other and clipped by its near plane.
pub fn either_depth_range<S: Strategy<Value = Scene>>(
    profile: &Profile,
    scenes: S,
) -> impl Strategy<Value = Scene> + use<S> {
    let ranges = profile.features.depth_ranges;
    let gl_only = !ranges.contains(DepthRange::ZeroToOne);
    let both = ranges.contains(DepthRange::NegativeOneToOne) && !gl_only;
    (scenes, any::<bool>()).prop_map(move |(mut scene, coin)| {
        if gl_only || (both && coin) {
            scene.state.depth_range = DepthRange::NegativeOneToOne;
            for p in &mut scene.positions {
                p[2] = 2.0 * p[2] - p[3];
            }
        }
        scene
    })
}

/// A clip-space triangle anywhere near the view volume, off any grid, with `w` in [0.1, 4].
pub fn float_scene() -> impl Strategy<Value = Scene> {
    let vertex = (-1.6f32..1.6, -1.6f32..1.6, 0.0f32..1.0, 0.1f32..4.0)
        .prop_map(|(x, y, z, w)| [x * w, y * w, z * w, w]);
    (any_side(), any_side(), prop::array::uniform3(vertex))
        .prop_map(|(w, h, v)| Scene::new(w, h, v.to_vec(), vec![[0, 1, 2]]))
}

/// Delaunay-triangulates grid points (clamped to the viewport) plus its corners with spade.
///
/// The corners make the mesh cover the whole viewport. Each vertex gets its own `w` from
/// `ws` (cycled) and `z` from `zs`: clip position `(x_ndc·w, y_ndc·w, z·w, w)`.
#[must_use]
pub fn triangulate(width: u32, height: u32, points: &[(i64, i64)], ws: &[f32], zs: &[f32]) -> Scene {
    let (wmax, hmax) = (i64::from(width) * GRID, i64::from(height) * GRID);
    let corners = [(0, 0), (wmax, 0), (wmax, hmax), (0, hmax)];
    let mut mesh: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
    for &(x, y) in corners.iter().chain(points) {
        let (x, y) = (x.clamp(0, wmax), y.clamp(0, hmax));
        // Grid points are small integers: exact in f64, always valid for spade.
        let _ = mesh.insert(Point2::new(x as f64, y as f64));
    }
    let positions = mesh
        .vertices()
        .enumerate()
        .map(|(i, v)| {
            let p = v.position();
            let w = ws.get(i % ws.len().max(1)).copied().unwrap_or(1.0);
            let z = zs.get(i % zs.len().max(1)).copied().unwrap_or(0.5);
            clip_of(width, height, 8, p.x as i64, p.y as i64, z, w)
        })
        .collect();
    let triangles = mesh
        .inner_faces()
        .map(|f| f.vertices().map(|v| v.fix().index() as u32))
        .collect();
    Scene::new(width, height, positions, triangles)
}

/// Grid points within 64 × 64 pixels: on sample centres, pixel edges, or anywhere. Points
/// beyond a smaller viewport are clamped onto its border by [`triangulate`].
pub fn mesh_points(max: usize) -> impl Strategy<Value = Vec<(i64, i64)>> {
    let coordinate = || {
        prop_oneof![
            2 => 0..=64 * GRID,
            1 => (0i64..64).prop_map(|p| p * GRID + GRID / 2),
            1 => (0i64..=64).prop_map(|p| p * GRID),
        ]
    };
    prop::collection::vec((coordinate(), coordinate()), 0..max)
}

/// A spade mesh covering a square viewport, `w = 1`.
///
/// Square, so that even the bare two-triangle mesh of the corners has a diagonal through
/// sample centres: a shrunk counterexample can always lose every interior point.
pub fn mesh_scene() -> impl Strategy<Value = Scene> {
    (mesh_points(24), side()).prop_map(|(points, s)| triangulate(s, s, &points, &[1.0], &[0.5]))
}

/// A spade mesh covering the viewport with `w` varied per vertex in [0.1, 4].
pub fn projected_mesh_scene() -> impl Strategy<Value = Scene> {
    (mesh_points(24), prop::collection::vec(0.1f32..4.0, 1..8), side())
        .prop_map(|(points, ws, s)| triangulate(s, s, &points, &ws, &[0.5]))
}

/// A spade mesh whose vertex depths straddle the near plane (`z` in [−1, 1]), so shared edges
/// cross it and get clipped.
pub fn clipped_mesh_scene() -> impl Strategy<Value = Scene> {
    (
        mesh_points(16),
        prop::collection::vec(0.3f32..3.0, 1..6),
        prop::collection::vec(-1.0f32..1.0, 2..9),
        any_side(),
        any_side(),
    )
        .prop_map(|(points, ws, zs, w, h)| triangulate(w, h, &points, &ws, &zs))
}

/// A fan of triangles around an interior vertex on a sample centre, its rim on sample centres
/// (so spokes pass through samples) or pixel corners.
///
/// The rim always holds the four axis points at radius `r`, so every angular gap is at most a
/// right angle and the fan is a star around its centre: no triangle wraps round over the others.
pub fn fan_scene() -> impl Strategy<Value = Scene> {
    let extra = prop::collection::vec((-31i64..=31, -31i64..=31, prop::bool::ANY), 0..10);
    (extra, 2i64..32, side()).prop_map(|(extra, r, s)| {
        let c = i64::from(s) / 2;
        let r_max = c - 1;
        let r = r.min(r_max);
        let centre = (c * GRID + GRID / 2, c * GRID + GRID / 2);
        // Offsets from the centre in half pixels: even = sample centre, odd = pixel corner.
        let mut rim: Vec<(i64, i64)> = vec![(2 * r, 0), (0, 2 * r), (-2 * r, 0), (0, -2 * r)];
        rim.extend(
            extra
                .iter()
                .map(|&(dx, dy, corner)| (dx.clamp(-r_max, r_max), dy.clamp(-r_max, r_max), corner))
                .filter(|&(dx, dy, _)| (dx, dy) != (0, 0))
                .map(|(dx, dy, corner)| {
                    let h = i64::from(corner);
                    (2 * dx + h, 2 * dy + h)
                }),
        );
        rim.sort_by(|a, b| {
            (a.1 as f64)
                .atan2(a.0 as f64)
                .total_cmp(&(b.1 as f64).atan2(b.0 as f64))
                .then(a.0.abs().cmp(&b.0.abs()))
        });
        rim.dedup();
        let point = |(dx, dy): (i64, i64)| (centre.0 + dx * GRID / 2, centre.1 + dy * GRID / 2);
        let tris: Vec<_> = (0..rim.len())
            .map(|i| [centre, point(rim[i]), point(rim[(i + 1) % rim.len()])])
            .collect();
        Scene::from_subpixels(s, s, 8, &tris, 0.5)
    })
}

/// A quad rotated by any angle, split along one of its diagonals (dEQP `fill_rules`).
pub fn rotated_quad_scene() -> impl Strategy<Value = Scene> {
    (
        side(),
        0.0f64..std::f64::consts::TAU,
        0.2f64..0.9,
        0.2f64..0.9,
        prop::bool::ANY,
        -0.3f64..0.3,
        -0.3f64..0.3,
    )
        .prop_map(|(s, angle, hw, hh, other_diagonal, cx, cy)| {
            let (sin, cos) = angle.sin_cos();
            let half = f64::from(s) / 2.0;
            let corner = |u: f64, v: f64| {
                let (x, y) = (u * hw * half, v * hh * half);
                let px = half * (1.0 + cx) + x * cos - y * sin;
                let py = half * (1.0 + cy) + x * sin + y * cos;
                // On the grid, so the quad's four corners are shared exactly.
                (
                    (px * GRID as f64).round() as i64,
                    (py * GRID as f64).round() as i64,
                )
            };
            let q = [
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ];
            let tris = if other_diagonal {
                [[q[0], q[1], q[3]], [q[1], q[2], q[3]]]
            } else {
                [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
            };
            Scene::from_subpixels(s, s, 8, &tris, 0.5)
        })
}

/// A triangle crossing clip planes: some vertices behind the eye (w < 0), at the eye's plane
/// (w = 0), exactly on the near or far plane, before the near plane, or far outside the view at
/// up to ±30000·w (as dEQP's clipping tests), on a viewport of any shape.
pub fn crossing_scene() -> impl Strategy<Value = Scene> {
    let scaled = (
        crossing_coordinate(),
        crossing_coordinate(),
        crossing_depth(),
        prop_oneof![3 => 0.2f32..3.0, 1 => -2.0f32..-0.1],
    )
        .prop_map(|(x, y, z, w)| [x * w.abs(), y * w.abs(), z * w.abs(), w]);
    // A vertex at w = 0 has no projection: its x, y, z are taken as they are, not scaled by w.
    let at_eye_plane =
        (crossing_coordinate(), crossing_coordinate(), -1.0f32..1.0).prop_map(|(x, y, z)| [x, y, z, 0.0]);
    let vertex = prop_oneof![6 => scaled, 1 => at_eye_plane];
    (any_side(), any_side(), prop::array::uniform3(vertex))
        .prop_map(|(w, h, v)| Scene::new(w, h, v.to_vec(), vec![[0, 1, 2]]))
}

/// [`crossing_scene`]'s x/w, y/w and z/w with one `w > 0` for all three vertices: clipped by
/// the x, y, near and far planes, and interpolated alike perspective-correctly or not.
pub fn equal_w_crossing_scene() -> impl Strategy<Value = Scene> {
    let vertex = (crossing_coordinate(), crossing_coordinate(), crossing_depth());
    (any_side(), any_side(), prop::array::uniform3(vertex), 0.2f32..3.0).prop_map(|(width, height, v, w)| {
        let positions = v.iter().map(|&(x, y, z)| [x * w, y * w, z * w, w]).collect();
        Scene::new(width, height, positions, vec![[0, 1, 2]])
    })
}

/// x/w or y/w for [`crossing_scene`]: mostly near the view volume, else up to ±30000 or exactly
/// there (dEQP's clipping extent).
fn crossing_coordinate() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        3 => -1.5f32..1.5,
        1 => -30000.0f32..30000.0,
        1 => prop_oneof![Just(-30000.0f32), Just(30000.0)],
    ]
}

/// z/w for [`crossing_scene`]: anywhere from before the near plane to past the far one, or
/// exactly on either.
fn crossing_depth() -> impl Strategy<Value = f32> {
    prop_oneof![4 => -1.0f32..1.2, 1 => Just(0.0f32), 1 => Just(1.0f32)]
}

/// Half [`perspective_inside_scene`], which nothing clips, half [`crossing_scene`]: for the
/// rules that compare interpolation with the ray cast, and the culling rule, clipped or not.
pub fn inside_or_crossing_scene() -> impl Strategy<Value = Scene> {
    prop_oneof![perspective_inside_scene(), crossing_scene()]
}

/// A few overlapping and intersecting grid triangles with random depth per vertex.
pub fn overlapping_scene() -> impl Strategy<Value = Scene> {
    (
        prop::collection::vec((grid_triangle(), prop::array::uniform3(0.0f32..1.0)), 2..6),
        side(),
    )
        .prop_map(|(tris, s)| {
            let mut positions = Vec::new();
            for (t, z) in &tris {
                positions.extend((0..3).map(|i| clip_of(s, s, 8, t[i].0, t[i].1, z[i], 1.0)));
            }
            let indices = (0..tris.len() as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            Scene::new(s, s, positions, indices)
        })
}

/// `n` values of `strategy` from proptest's deterministic runner, for tests of the generators.
#[cfg(test)]
pub(crate) fn samples<S: Strategy>(strategy: S, n: usize) -> Vec<S::Value> {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    (0..n)
        .map(|_| {
            strategy
                .new_tree(&mut runner)
                .expect("the strategy makes values")
                .current()
        })
        .collect()
}
