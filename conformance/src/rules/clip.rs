//! Clipping: nothing from behind the eye, the interior preserved, shared edges watertight.

use proptest::prelude::*;
use refrast::DepthRange;

use super::common::check_draws_nothing;
use super::fill::{
    check_exactly_once, check_exactly_once_between_two_cuts_apart, check_exactly_once_cuts_apart,
};
use super::level::{CUT_VERTICES, CUT_VERTICES_AND_SHARED_EDGES, Level, NO_GL_RANGE};
use super::{CLIPS_IN_3D, FAR_CLIPPING, Family, GL_DEPTH_RANGE, Rule};
use crate::runner::property;
use crate::scene::Scene;
use crate::strategy;

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Clip, "clip.behind-eye.empty")
            .needs(CLIPS_IN_3D)
            .sentence("A triangle wholly behind the eye (w < 0) draws nothing, with depth clipping off too where declared; one wholly before the near plane draws nothing where the draw clips at it.")
            .source("MIT 6.837 seed 001 (why clip: w ≤ 0); Vulkan 1.4, Primitive Clipping (−w_c ≤ x_c ≤ w_c holds for no point with w_c < 0, whether depth is clipped or not)")
            .cases(10000)
            .run(|r, cfg| property(r, cfg, behind_scene(), check_draws_nothing)),
        Rule::invariant(Family::Clip, "clip.interior.matches-raycast")
            .needs(CLIPS_IN_3D)
            .sentence("A triangle crossing clip planes, w = 0, or reaching ±30000·w covers exactly the samples its ray cast hits, outside the tolerance band (widened along cuts by what an f32 clipper's rounding may move them: 2^-19 of the coordinates they come from). Known limit: clipping x and y at the viewport and snapping the vertices that makes (reference-full-clip) can miss samples along such a cut (seen at seed 8 before the generator reached w = 0 and any viewport side; not at seeds 1–20 since).")
            .source("dEQP-GLES3.functional.clipping.*; refrast's own property (clipping keeps the interior)")
            .cases(5000)
            .run(|r, cfg| property(r, cfg, strategy::crossing_scene(), check_exactly_once)),
        Rule::invariant(Family::Clip, "clip.mesh.watertight")
            .needs(CLIPS_IN_3D)
            .sentence("A viewport-covering mesh whose shared edges cross the near plane covers each visible sample exactly once. Known limit: at 4 subpixel bits, snapping the vertices the near plane makes on a sliver can fold its clipped polygon and open a hole (reference-4bit, at seeds 13 and 15 of 1–20).")
            .source("dEQP fill_rules.clipped_*; nvdiffrast #225; seed 004 (Sutherland–Hodgman)")
            .cases(1500)
            .every_spec(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::clipped_mesh_scene(), check_exactly_once_cuts_apart),
                note: CUT_VERTICES,
            })
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| {
                    property(r, cfg, strategy::clipped_mesh_scene(), check_exactly_once_between_two_cuts_apart)
                },
                note: CUT_VERTICES_AND_SHARED_EDGES,
            })
            .run(|r, cfg| property(r, cfg, strategy::clipped_mesh_scene(), check_exactly_once)),
        Rule::invariant(Family::Clip, "clip.crossing-quad.watertight")
            .needs(CLIPS_IN_3D)
            .sentence("A quad with corners at ±30000·w whose shared diagonal crosses the near plane inside the viewport leaves no hole there.")
            .source("dEQP-GLES3.functional.clipping (±30000·w); refrast convention (ARCHITECTURE.md, Conventions: clipping)")
            .cases(3000)
            .every_spec(Level::Partly {
                part: |r, cfg| property(r, cfg, crossing_quad_scene(), check_exactly_once_cuts_apart),
                note: CUT_VERTICES,
            })
            .run(|r, cfg| property(r, cfg, crossing_quad_scene(), check_exactly_once)),
        Rule::invariant(Family::Clip, "clip.far.respected")
            .needs(CLIPS_IN_3D)
            .sentence("With far clipping on, samples whose hit lies beyond z = w are not covered, the rest as the ray cast says.")
            .source("Vulkan 1.4, Primitive Clipping (z ≤ w); seed 004 (six planes)")
            .cases(3000)
            .needs(FAR_CLIPPING)
            .run(|r, cfg| property(r, cfg, far_scene(), check_exactly_once)),
        Rule::invariant(Family::Clip, "clip.gl-range.matches-raycast")
            .needs(CLIPS_IN_3D)
            .sentence("Under the −w ≤ z ≤ w clip volume, coverage matches the ray cast against that volume.")
            .source("OpenGL 4.6 §13.7; Vulkan VK_EXT_depth_clip_control")
            .cases(3000)
            .needs(GL_DEPTH_RANGE)
            .d3d11(Level::NotCovered(NO_GL_RANGE))
            .run(|r, cfg| property(r, cfg, gl_scene(), check_exactly_once)),
    ]
}

/// Triangles all behind the eye (half of them with depth clipping off, which `fit` turns back
/// on for a profile without it), or all in front of it but before the near plane.
///
/// Before the near plane means `z < −w`, which is before it under both clip volumes: a
/// profile supporting only OpenGL's `−w ≤ z` has `fit` move the draw to that range, and a
/// vertex with `−w ≤ z < 0` would then be visible.
fn behind_scene() -> impl Strategy<Value = Scene> {
    let behind =
        (-2.0f32..2.0, -2.0f32..2.0, -1.0f32..1.0, -4.0f32..-0.01).prop_map(|(x, y, z, w)| [x, y, z, w]);
    let before_near = (-2.0f32..2.0, -2.0f32..2.0, 0.001f32..4.0, 0.01f32..4.0)
        .prop_map(|(x, y, k, w)| [x * w, y * w, -w - k, w]);
    (
        strategy::side(),
        prop_oneof![
            (prop::array::uniform3(behind), any::<bool>()),
            (prop::array::uniform3(before_near), Just(true)),
        ],
    )
        .prop_map(|(s, (v, clip_near))| {
            let mut scene = Scene::new(s, s, v.to_vec(), vec![[0, 1, 2]]);
            scene.state.clip_near = clip_near;
            scene
        })
}

/// Two triangles sharing a diagonal from 30000·w behind the near plane to 30000·w in front of
/// it, crossing the plane at a point inside the viewport; the other corners lie far to either side.
fn crossing_quad_scene() -> impl Strategy<Value = Scene> {
    let unit = -0.9f32..0.9;
    (
        unit.clone(),
        unit,
        0.0f32..std::f32::consts::TAU,
        0.05f32..0.95,
        prop::array::uniform4(0.5f32..2.0),
        strategy::side(),
    )
        .prop_map(|(cx, cy, angle, at, w, s)| {
            let (dy, dx) = angle.sin_cos();
            let far = 30000.0;
            // The diagonal P→Q passes through (cx, cy); z runs from −at to 1 − at along it.
            let corner = |t: f32, side: f32, z: f32, w: f32| {
                let (x, y) = (cx + far * (t * dx - side * dy), cy + far * (t * dy + side * dx));
                [x * w, y * w, z * w, w]
            };
            let positions = vec![
                corner(-1.0, 0.0, -at, w[0]),
                corner(1.0, 0.0, 1.0 - at, w[1]),
                corner(0.0, 1.0, 0.5, w[2]),
                corner(0.0, -1.0, 0.5, w[3]),
            ];
            Scene::new(s, s, positions, vec![[0, 1, 2], [1, 0, 3]])
        })
}

/// Crossing triangles with far clipping on and depths reaching past the far plane, and before
/// the near one, under either clip volume (the far plane is `z = w` in both).
fn far_scene() -> impl Strategy<Value = Scene> {
    (float_scene_with_z(-0.5..2.5), any::<bool>()).prop_map(|(mut s, gl)| {
        s.state.clip_far = true;
        if gl {
            s.state.depth_range = DepthRange::NegativeOneToOne;
        }
        s
    })
}

/// Triangles under the OpenGL clip volume with depths crossing z = −w, with far clipping on or off.
fn gl_scene() -> impl Strategy<Value = Scene> {
    (float_scene_with_z(-2.0..1.5), any::<bool>()).prop_map(|(mut s, far)| {
        s.state.depth_range = DepthRange::NegativeOneToOne;
        s.state.clip_far = far;
        s
    })
}

/// A [`strategy::float_scene`] whose vertices get z/w from `z_over_w` instead.
fn float_scene_with_z(z_over_w: std::ops::Range<f32>) -> impl Strategy<Value = Scene> {
    (strategy::float_scene(), prop::array::uniform3(z_over_w)).prop_map(|(mut s, z)| {
        for (p, z) in s.positions.iter_mut().zip(z) {
            p[2] = z * p[3];
        }
        s
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::oracle::raster::near_distance;

    /// Every vertex `behind_scene` makes is outside the near plane of both clip volumes, so a
    /// profile that only has OpenGL's `−w ≤ z` (to which `fit` moves the draw) must draw
    /// nothing too. Before, "before the near plane" meant `z < 0`, visible under GL.
    #[test]
    fn behind_scenes_are_invisible_under_either_volume() {
        for scene in strategy::samples(behind_scene(), 2000) {
            for p in &scene.positions {
                let [_, _, z, w] = *p;
                // Without near clipping only what lies behind the eye is sure to be invisible.
                assert!(scene.state.clip_near || w < 0.0, "{p:?} with depth clipping off");
                for range in [DepthRange::ZeroToOne, DepthRange::NegativeOneToOne] {
                    assert!(
                        w < 0.0 || near_distance(range, z, w) < 0.0,
                        "{p:?} under {range:?}"
                    );
                }
            }
        }
    }
}
