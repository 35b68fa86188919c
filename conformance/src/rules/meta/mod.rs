//! Metamorphic relations: changes to the input that must leave coverage alone, or move it predictably.

use super::level::{EDGES_NOT_PINNED, Level, STRIP_ORDER_NOT_PINNED, ZERO_AREA_LINE};
use super::{CULLING, Family, Rule, needs};
use crate::runner::{property, property_for};
use crate::strategy;

mod facing;
mod order;
mod strip;
mod translate;

pub use facing::{
    check_culled_both, check_culling, check_degenerate, check_degenerate_off_line, check_facing,
    check_lines_points_front,
};
use facing::{cull_both_scene, cull_scene, degenerate_scene, facing_scene, lines_or_points};
pub use order::{
    check_batch_away_from_edges, check_batch_independent, check_reversal, check_reversal_away_from_edges,
    check_rotation, check_rotation_away_from_edges,
};
pub use strip::{check_same_as_list, check_same_as_list_away_from_edges};
pub use translate::{Translated, check_subpixel_translation, check_translation, check_viewport_neutral};

/// The implementation culls both faces.
const CULL_BOTH: super::Need = needs(|p| p.state.cull_both, "no culling of both faces");

/// The implementation draws triangle strips.
const STRIPS: super::Need = needs(|p| p.state.triangle_strips, "no triangle strips");

/// The implementation draws triangle fans.
const FANS: super::Need = needs(|p| p.state.triangle_fans, "no triangle fans");

/// The implementation draws lines or points.
const LINES_OR_POINTS: super::Need = needs(|p| p.lines.is_some() || p.points, "no lines or points");

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Meta, "meta.rotation.same-coverage")
            .sentence("Rotating a triangle's vertex order leaves its coverage unchanged and rotates its barycentrics.")
            .source("refrast's own metamorphic property (an llvmpipe comment admits attributes change under rotation); DRTK #9")
            .cases(10000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::perspective_grid_scene(), check_rotation_away_from_edges),
                note: EDGES_NOT_PINNED,
            })
            .run(|r, cfg| property(r, cfg, strategy::perspective_grid_scene(), check_rotation)),
        Rule::invariant(Family::Meta, "meta.reversal.flips-facing")
            .sentence("Reversing a triangle's winding keeps its coverage, swaps two barycentrics and flips its facing.")
            .source("refrast's own metamorphic property; Vulkan 1.4, Basic Polygon Rasterization")
            .cases(10000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::perspective_grid_scene(), check_reversal_away_from_edges),
                note: EDGES_NOT_PINNED,
            })
            .run(|r, cfg| property(r, cfg, strategy::perspective_grid_scene(), check_reversal)),
        Rule::invariant(Family::Meta, "meta.translate.whole-pixels")
            .sentence("Moving a triangle by whole pixels moves its coverage by the same pixels (near an edge, clipping may differ by the band).")
            .source("OpenGL 4.6 §14.2 (invariance under integer translation); refrast's own metamorphic property")
            .cases(10000)
            .run(|r, cfg| property(r, cfg, translate::translated(), check_translation)),
        Rule::invariant(Family::Meta, "meta.translate.one-subpixel")
            .sentence("Moving a triangle by one subpixel unit changes only samples within one unit (plus the band) of an edge.")
            .source("refrast's own metamorphic property (translation by 2^-bits)")
            .cases(10000)
            .run(|r, cfg| property(r, cfg, strategy::grid_scene(), check_subpixel_translation)),
        Rule::invariant(Family::Meta, "meta.viewport.neutral")
            .sentence("A triangle at the same raster position in a viewport twice as large covers the same samples (near an edge, clipping may differ by the band).")
            .source("Vulkan 1.4, Controlling the Viewport (the viewport transform) and Basic Polygon Rasterization (coverage is decided at sample points in framebuffer space); refrast's own metamorphic property")
            .cases(5000)
            .run(|r, cfg| property(r, cfg, strategy::grid_scene(), check_viewport_neutral)),
        Rule::invariant(Family::Meta, "meta.batch.independent")
            .sentence("Each triangle of a draw covers the same samples as when drawn alone, in any submission order.")
            .source("refrast's own metamorphic property (tile, thread and traversal-order independence); piglit quad-invariance")
            .cases(3000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::overlapping_scene(), check_batch_away_from_edges),
                note: EDGES_NOT_PINNED,
            })
            .run(|r, cfg| property(r, cfg, strategy::overlapping_scene(), check_batch_independent)),
        Rule::invariant(Family::Meta, "meta.cull.by-facing")
            .sentence("Culling removes exactly the fragments of triangles with the culled facing (a sliver by its snapped area), under either front face.")
            .source("dEQP-VK.rasterization.culling.*; seed 003 (back-face culling)")
            .cases(3000)
            .needs(CULLING)
            .keeps_winding()
            .run(|r, cfg| property_for(r, cfg, cull_scene, check_culling)),
        Rule::invariant(Family::Meta, "meta.cull.both-faces")
            .sentence("With both faces culled, no triangle draws a fragment, whatever its facing, clipped or not (lines and points are drawn as with culling off: meta.facing.lines-points-front).")
            .source("Vulkan 1.4, Basic Polygon Rasterization (VK_CULL_MODE_FRONT_AND_BACK); OpenGL 4.6 §14.6.1 and OpenGL ES 3.2 §13.7.1 (CullFace(FRONT_AND_BACK)); dEQP-VK.rasterization.culling.both_*")
            .cases(1000)
            .needs(CULL_BOTH)
            .keeps_winding()
            .run(|r, cfg| property_for(r, cfg, cull_both_scene, check_culled_both)),
        Rule::invariant(Family::Meta, "meta.strip.same-as-list")
            .sentence("A triangle strip draws what the list of its triangles draws, triangle i as vertices i, i + 1 + i mod 2, i + 2 − i mod 2 (every other one reversed, so the strip keeps one facing): the same samples, primitive ids, facing, depth and barycentrics, under every cull mode and front face, and the same depth-test result.")
            .source("Vulkan 1.4, Triangle Strips (drawing-triangle-strips) and the barycentric order table (primsrast-barycentric-order-table); OpenGL 4.6 §10.1.6 and OpenGL ES 3.2 §10.1.5 (the same triangles, each rotated: coverage and facing agree); D3D11.3 §8.10; dEQP-VK.rasterization.primitives.triangle_strip")
            .cases(600)
            .needs(STRIPS)
            .keeps_winding()
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, strip::strips, check_same_as_list_away_from_edges),
                note: STRIP_ORDER_NOT_PINNED,
            })
            .run(|r, cfg| property_for(r, cfg, strip::strips, check_same_as_list)),
        Rule::invariant(Family::Meta, "meta.fan.same-as-list")
            .sentence("A triangle fan draws what the list of its triangles draws, triangle i as vertices i + 1, i + 2, 0 (the hub last): the same samples, primitive ids, facing, depth and barycentrics, under every cull mode and front face, and the same depth-test result.")
            .source("Vulkan 1.4, Triangle Fans (drawing-triangle-fans) and the barycentric order table (primsrast-barycentric-order-table); OpenGL 4.6 §10.1.7 and OpenGL ES 3.2 §10.1.6 (hub first, the same triangles rotated); D3D11.3 has none (§25.1); dEQP-VK.rasterization.primitives.triangle_fan")
            .cases(600)
            .needs(FANS)
            .keeps_winding()
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, strip::fans, check_same_as_list_away_from_edges),
                note: STRIP_ORDER_NOT_PINNED,
            })
            .run(|r, cfg| property_for(r, cfg, strip::fans, check_same_as_list)),
        Rule::invariant(Family::Meta, "meta.facing.from-winding")
            .sentence("A fragment is front-facing exactly when its triangle turns on screen the way the front face says: by its snapped signed area (also for a sliver that snapping turns over), or by the sign of det[x y w] when it is clipped; a triangle its cull mode discards draws nothing.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (polygon facing from the signed area); Olano and Greer 1997 (facing of clipped triangles); seed 003 (back-face culling)")
            .cases(6000)
            .keeps_winding()
            .run(|r, cfg| property_for(r, cfg, facing_scene, check_facing)),
        Rule::invariant(Family::Meta, "meta.facing.lines-points-front")
            .sentence("Every fragment of a line or point reports front-facing, and no cull mode or front face changes which samples a line or point covers.")
            .source("Vulkan 1.4, FrontFacing (non-zero for a non-polygon primitive) and VkCullModeFlagBits (triangle culling); D3D11.3 §15.12 (lines and points are front-facing), §3.4.6 (cull modes never remove points); OpenGL 4.6 §15.2.2 (fragments of points and lines are front-facing)")
            .cases(300)
            .needs(LINES_OR_POINTS)
            .keeps_winding()
            .run(|r, cfg| property_for(r, cfg, lines_or_points, check_lines_points_front)),
        Rule::invariant(Family::Meta, "meta.degenerate.empty")
            .sentence("Zero-area triangles (collinear or repeated vertices, on sample centres too) draw nothing; without a guard band, those needing no x/y clipping; one the near plane cuts, nothing where the profile decides zero area before clipping, else nothing away from its line.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (a sample is covered when inside the polygon, and zero area leaves no inside; zero area is back-facing); D3D11.3 §15.11.1")
            .cases(10000)
            .every_spec(Level::Partly {
                part: |r, cfg| property(r, cfg, degenerate_scene(), check_degenerate_off_line),
                note: ZERO_AREA_LINE,
            })
            .run(|r, cfg| property(r, cfg, degenerate_scene(), check_degenerate)),
    ]
}
