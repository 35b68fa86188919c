//! The viewport's depth range and depth clamping: window depth is `minDepth + (maxDepth −
//! minDepth)·z/w` (reversed when `minDepth > maxDepth`), and with depth clipping off nothing is
//! cut at the near or far plane, its depth clamped to the range instead.
//!
//! Both rules are the ray cast's (`rules::cast`) under the draw's state: the oracle maps `z/w`
//! through the viewport's range with Vulkan's `o_z` and `p_z` and leaves out the planes the draw
//! does not clip at, written apart from the reference's `ViewportDepth`.

use std::fmt;

use proptest::prelude::*;
use refrast::{DepthConvention, Profile, Rasterizer, ViewportDepth};

use super::common::precision;
use super::depth::{
    check_depth_matches_raycast, check_depth_matches_raycast_where_bounded, every_fragment_written,
    replay_differences, writes_every_fragment,
};
use super::fill::check_exactly_once;
use super::level::{EYE_CROSSING_UNCLIPPED, FAR_VALUES, Level};
use super::{CLIPS_IN_3D, Family, Need, Rule, Z_OVER_W_DEPTH, needs};
use crate::runner::property_for;
use crate::scene::{Case, Scene};
use crate::strategy;
use crate::violation::{Violation, plural};

/// The implementation honours a viewport depth range other than `[0, 1]`.
const VIEWPORT_DEPTH: Need = needs(|p| p.state.honours_viewport_depth(), "no viewport depth range");

/// The implementation draws with depth clipping off.
const UNCLIPPED_DEPTH: Need = needs(|p| p.state.unclipped_depth, "no unclipped depth");

/// What the specifications say of the viewport's depth range.
const RANGE_SOURCE: &str = "Vulkan 1.4, Controlling the Viewport (o_z = minDepth, p_z = maxDepth − minDepth; \"minDepth can be less than, equal to, or greater than maxDepth\") and Depth Clamping and Range Adjustment; OpenGL 4.6 §13.8.1 and OpenGL ES 3.2 §12.6.1 (DepthRange); D3D11.3 §15.6 (MinDepth ≤ MaxDepth, §15.6.1); dEQP-VK.draw.inverted_depth_ranges.*";

/// What they say of depth clipping off.
const CLAMP_SOURCE: &str = "Vulkan 1.4, Primitive Clipping (\"Depth clipping is disabled when depthClampEnable is VK_TRUE\") and Depth Clamping and Range Adjustment (z_f clamped to [min(n, f), max(n, f)]); OpenGL 4.6 §13.7 and §17.3.4 (DEPTH_CLAMP); OpenGL ES 3.2 has it only through EXT_depth_clamp; D3D11.3 §15.4 (DepthClipEnable) and §15.6, §17.10 (depth clamped to the viewport's range); dEQP-VK.clipping.clip_volume.depth_clamp.*";

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Depth, "depth.viewport.maps-range")
            .sentence("Fragment depth is the ray-cast hit's z/w through the viewport's depth range, minDepth + (maxDepth − minDepth)·z/w (under −w ≤ z ≤ w, (maxDepth + minDepth)/2 + (maxDepth − minDepth)/2·z/w), within the claimed precision, for any minDepth and maxDepth in [0, 1], equal or reversed (maxDepth below minDepth) where declared; on a clipped triangle also within how far it moves when the sample moves one grid step.")
            .source(RANGE_SOURCE)
            .cases(3000)
            .needs(Z_OVER_W_DEPTH)
            .needs(VIEWPORT_DEPTH)
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, ranged_scene, check_depth_matches_raycast_where_bounded),
                note: FAR_VALUES,
            })
            .run(|r, cfg| property_for(r, cfg, ranged_scene, check_depth_matches_raycast)),
        Rule::invariant(Family::Clip, "clip.unclipped-depth.clamped")
            .sentence("With depth clipping off, a triangle crossing the near and far planes (and w = 0) covers exactly the samples whose ray-cast hit lies in front of the eye, nothing cut at either plane, outside the tolerance band; and each fragment's depth is the hit's window depth clamped to the viewport's depth range [min(minDepth, maxDepth), max(minDepth, maxDepth)], within the claimed precision, as is what the depth test writes.")
            .source(CLAMP_SOURCE)
            .cases(3000)
            .needs(CLIPS_IN_3D)
            .needs(UNCLIPPED_DEPTH)
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, unclipped_in_front, check_clamped_where_bounded),
                note: EYE_CROSSING_UNCLIPPED,
            })
            .run(|r, cfg| property_for(r, cfg, unclipped_scene, check_clamped)),
    ]
}

/// Depth ranges worth drawing: the whole one reversed, a single depth, each end alone, and any
/// two depths in either order (the profile's fit puts a reversed one in order where only
/// ordered ones are declared).
pub fn viewport_depth() -> impl Strategy<Value = ViewportDepth> {
    let end = prop_oneof![Just(0.0f32), Just(1.0), Just(0.5), 0.0f32..=1.0];
    (end.clone(), end).prop_map(|(min, max)| ViewportDepth { min, max })
}

/// `cases` drawn half of the time with a [`viewport_depth`] range where `p` declares ranges,
/// and half of the time with depth clipping off where it declares that, each vertex's `z/w`
/// then stretched from `[0, 1]` to `[−1, 2]`, before the near and beyond the far plane: for the
/// line and point depth rules, whose values go through the range and the clamp as triangles' do.
pub fn varied_depth<C, S>(p: &Profile, cases: S) -> BoxedStrategy<C>
where
    C: Case + Clone + fmt::Debug + 'static,
    S: Strategy<Value = C> + 'static,
{
    let (ranges, unclipped) = (p.state.honours_viewport_depth(), p.state.unclipped_depth);
    (cases, viewport_depth(), any::<bool>(), any::<bool>())
        .prop_map(move |(mut case, range, ranged, stretched)| {
            let scene = case.scene_mut();
            if ranges && ranged {
                scene.state.viewport_depth = range;
            }
            if unclipped && stretched {
                scene.state.clip_near = false;
                scene.state.clip_far = false;
                for v in &mut scene.positions {
                    v[2] = 3.0 * v[2] - v[3];
                }
            }
            case
        })
        .boxed()
}

/// Triangles inside the viewport or crossing the clip planes, under either clip volume the
/// profile supports, each drawn with a [`viewport_depth`] range.
fn ranged_scene(p: &Profile) -> BoxedStrategy<Scene> {
    (
        strategy::either_depth_range(p, strategy::inside_or_crossing_scene()),
        viewport_depth(),
    )
        .prop_map(|(mut s, range)| {
            s.state.viewport_depth = range;
            s
        })
        .boxed()
}

/// Triangles crossing the near and far planes and `w = 0`, drawn with depth clipping off under
/// a [`viewport_depth`] range, in either clip volume the profile supports.
fn unclipped_scene(p: &Profile) -> BoxedStrategy<Scene> {
    unclipped(p, prop_oneof![strategy::crossing_scene(), deep_scene()])
}

/// [`unclipped_scene`] wholly in front of the eye: what every specification requires
/// ([`EYE_CROSSING_UNCLIPPED`]).
fn unclipped_in_front(p: &Profile) -> BoxedStrategy<Scene> {
    unclipped(p, deep_scene())
}

/// `scenes` drawn with depth clipping off under a [`viewport_depth`] range, in either clip
/// volume the profile supports.
fn unclipped<S: Strategy<Value = Scene> + 'static>(p: &Profile, scenes: S) -> BoxedStrategy<Scene> {
    (strategy::either_depth_range(p, scenes), viewport_depth())
        .prop_map(|(mut s, range)| {
            s.state.clip_near = false;
            s.state.clip_far = false;
            s.state.viewport_depth = range;
            s
        })
        .boxed()
}

/// A triangle in front of the eye whose vertices lie well before the near plane and beyond
/// the far one: z/w from −3 to 4.
fn deep_scene() -> impl Strategy<Value = Scene> {
    (strategy::float_scene(), prop::array::uniform3(-3.0f32..4.0)).prop_map(|(mut s, z)| {
        for (p, z) in s.positions.iter_mut().zip(z) {
            p[2] = z * p[3];
        }
        s
    })
}

/// Coverage as the ray cast without depth planes, then depth clamped (where depth is z/w), in
/// the fragments and in the depth buffer.
pub fn check_clamped(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    check_exactly_once(r, scene)?;
    if r.profile().depth == DepthConvention::ScreenLinearZOverW {
        check_depth_matches_raycast(r, scene)?;
    }
    check_buffer(r, scene)
}

/// [`check_clamped`] with depth judged only where the specifications bound it ([`FAR_VALUES`]).
fn check_clamped_where_bounded(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    check_exactly_once(r, scene)?;
    if r.profile().depth == DepthConvention::ScreenLinearZOverW {
        check_depth_matches_raycast_where_bounded(r, scene)?;
    }
    check_buffer(r, scene)
}

/// Where the implementation runs its own depth test, the buffer it leaves with every fragment
/// written (`Always`, writes on) is its fragments replayed, within the claimed precision: the
/// clamp is the depth test's, not only the fragment's (a GPU's fragments come from the shader's
/// FragCoord.z, which no specification clamps nor ties to the tested depth bit for bit, so its
/// adapter may clamp them itself).
fn check_buffer(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    if !writes_every_fragment(&profile) {
        return Ok(());
    }
    let eps = precision(&profile);
    replay_differences(r, &every_fragment_written(scene), Some(eps))?.verdict(|n| {
        format!(
            "with every fragment written, the depth buffer differs from the fragments (clamped to \
             the viewport's depth range) by more than the claimed precision at {}",
            plural(n, "pixel")
        )
    })
}
