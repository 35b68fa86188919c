//! Polygon modes: a triangle in line mode draws its edges as line segments, in point mode its
//! vertices as points, after it was clipped, faced and possibly culled as a filled one.
//!
//! The coverage rules compare the implementation with itself: a triangle in line mode with its
//! own line list of the triangle's edges, in point mode with its own point list of the
//! triangle's vertices. The line and point families judge those lists against their oracles, so
//! together they hold the modes to the declared line and point rules, whatever those are. Which
//! triangles draw at all (culling, zero area) and how each faces come from the facing oracle.

use proptest::prelude::*;
use proptest::strategy::Union;
use refrast::{CullMode, FrontFace, PolygonMode, Profile, Rasterizer, Setting, Topology};

use super::level::Level;
use super::samples::sample_fragments;
use super::{Family, Need, Rule, needs};
use crate::oracle::facing::Turn;
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::strategy::{self, primitive};
use crate::violation::{Findings, Violation, plural};

mod parts;
use parts::{compare_with_parts, inside_viewport};

/// What every specification says of the modes.
const SOURCE: &str = "Vulkan 1.4, VkPolygonMode (\"the polygon is clipped and possibly culled before these modes are applied\"; LINE: \"polygon edges are drawn as line segments\", POINT: \"polygon vertices are drawn as points\"); OpenGL 4.6 §14.6.4 (PolygonMode); D3D11.3 D3D11_FILL_WIREFRAME; dEQP-VK.rasterization.culling.*_line and *_point, dEQP-VK.rasterization.line_continuity.polygon-mode-lines";

/// What the specifications leave open, so that only triangles no plane cuts are compared there,
/// each edge against both of its directions.
const EDGES_OPEN: &str = "Vulkan and OpenGL 4.6 core say nothing of edges made by clipping (OpenGL's compatibility profile draws them, D3D11.3 §15.13 and Mesa's frustum planes do not), nor which way round an edge is drawn (the diamond-exit rule's ends depend on it), nor whether a sample two edges cover gets two fragments or one: refrast draws the original edges' visible parts, 0 → 1, 1 → 2, 2 → 0, each fragment of each; the specifications are held to triangles inside the viewport and the depth planes, to each edge drawn either way round, and to at least one fragment where two edges meet, a strip's or fan's samples compared as a whole (a GPU's fragment names its triangle only through its flat values, which bary.flat.provoking-vertex judges)";

/// D3D11.3 pins which edges are drawn, but not where a cut falls.
const EDGES_D3D: &str = "D3D11.3 §15.13 draws only the original edges' visible parts, as refrast does, but where a cut falls is the implementation's arithmetic, and it says neither which way round an edge is drawn (the aliased line rule's ends depend on it) nor whether a sample two edges cover gets two fragments or one: it is held to triangles inside the viewport and the depth planes, to each edge drawn either way round, and to at least one fragment where two edges meet, a strip's or fan's samples compared as a whole (a GPU's fragment names its triangle only through its flat values, which bary.flat.provoking-vertex judges)";

/// The same for vertices: points made by clipping, and one fragment where two vertices' points
/// overlap.
const VERTICES_OPEN: &str = "Vulkan and OpenGL 4.6 core say nothing of vertices made by clipping (OpenGL's compatibility profile draws those that start a boundary edge), nor whether a sample two vertices' points cover gets two fragments or one: refrast draws the original vertices inside the view volume, each fragment of each; the specifications are held to triangles inside the viewport and the depth planes, and to at least one fragment where two points overlap, a strip's or fan's samples compared as a whole (a GPU's fragment names its triangle only through its flat values, which bary.flat.provoking-vertex judges)";

/// Where the specifications' facing and refrast's part: the visible polygon of zero area.
const FACING_OPEN: &str = "Vulkan and OpenGL take a clipped polygon's facing from its visible area, and call a polygon of zero area back-facing: where the near plane leaves only an edge of a triangle (two corners on it, the third behind), that edge is drawn in line mode and back-facing, whatever sign det[x y w] gives the triangle (refrast's convention, Olano–Greer's); so the specifications are held to triangles no plane cuts, of lists (a GPU's fragment of a strip or fan names its triangle only through its flat values, which bary.flat.provoking-vertex judges)";

/// D3D11.3 has no point fill mode.
const NO_D3D_POINTS: &str =
    "D3D11.3's D3D11_FILL_MODE has wireframe and solid only: no point mode to hold to anything";

/// OpenGL ES 3.2 has no polygon modes.
const NO_ES_MODES: &str = "OpenGL ES 3.2 has no PolygonMode (GL_NV_polygon_mode and GL_ANGLE_polygon_mode are extensions): nothing to hold a driver judged by it to";

/// The implementation draws triangles in line mode, by a declared line rule.
const LINE_MODE: Need = needs(
    |p| p.state.polygon_modes.contains(PolygonMode::Line) && p.lines.is_some(),
    "no polygon line mode (with a line rule)",
);

/// The implementation draws triangles in point mode, with points declared.
const POINT_MODE: Need = needs(
    |p| p.state.polygon_modes.contains(PolygonMode::Point) && p.points,
    "no polygon point mode (with points)",
);

/// The implementation draws triangles in line or point mode.
const ANY_MODE: Need = needs(
    |p| !p.state.polygon_modes.is_empty(),
    "no polygon line or point mode",
);

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Line, "line.polygon-mode.edges")
            .sentence("A triangle in line mode draws exactly what the same implementation's line list of its edges (first to second, second to third, third to first; the visible part of each where clipping cuts it) draws, each fragment naming the triangle; one its cull mode discards, or of zero area, draws nothing. Strips and fans alike, under every cull mode and front face.")
            .source(SOURCE)
            .cases(600)
            .needs(LINE_MODE)
            .keeps_winding()
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, line_cases, check_edges_inside),
                note: EDGES_OPEN,
            })
            .d3d11(Level::Partly {
                part: |r, cfg| property_for(r, cfg, line_cases, check_edges_inside),
                note: EDGES_D3D,
            })
            .opengles(Level::NotCovered(NO_ES_MODES))
            .run(|r, cfg| property_for(r, cfg, line_cases, check_edges)),
        Rule::invariant(Family::Point, "point.polygon-mode.vertices")
            .sentence("A triangle in point mode draws exactly what the same implementation's point list of its vertices draws, each fragment naming the triangle; one its cull mode discards, or of zero area, draws nothing. Strips and fans alike, under every cull mode and front face.")
            .source(SOURCE)
            .cases(600)
            .needs(POINT_MODE)
            .keeps_winding()
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property_for(r, cfg, point_cases, check_vertices_inside),
                note: VERTICES_OPEN,
            })
            .opengles(Level::NotCovered(NO_ES_MODES))
            .d3d11(Level::NotCovered(NO_D3D_POINTS))
            .run(|r, cfg| property_for(r, cfg, point_cases, check_vertices)),
        Rule::invariant(Family::Meta, "meta.polygon-mode.facing")
            .sentence("Every fragment of a triangle in line or point mode reports the triangle's facing (its snapped signed area, or det[x y w] when clipped), not a line's or a point's front-facing.")
            .source("Vulkan 1.4, VkPolygonMode and FrontFacing (a polygon's fragments carry its facing, whatever its mode); OpenGL 4.6 §14.6.4 and §15.2.2 (gl_FrontFacing of a polygon rasterized as lines or points is the polygon's); dEQP-VK.rasterization.culling.*_line, *_point")
            .cases(600)
            .needs(ANY_MODE)
            .keeps_winding()
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, any_mode_cases, check_facing_inside),
                note: FACING_OPEN,
            })
            .opengles(Level::NotCovered(NO_ES_MODES))
            .run(|r, cfg| property_for(r, cfg, any_mode_cases, check_facing)),
    ]
}

/// Triangle lists (meshes, clipped meshes, overlapping and near-crossing triangles), strips and
/// fans where declared, under every cull mode and front face, drawn in `mode` at each sample
/// count `p` draws both triangles and `mode`'s primitive at.
fn polygon_cases(p: &Profile, mode: PolygonMode) -> BoxedStrategy<PrimitiveScene> {
    let other = if mode == PolygonMode::Point {
        Topology::PointList
    } else {
        Topology::LineList
    };
    let counts = |topology: Topology| -> Vec<u8> {
        p.sample_counts()
            .into_iter()
            .filter(|&n| p.draws(topology, n) && p.draws(other, n))
            .collect()
    };
    let scenes = prop_oneof![
        strategy::mesh_scene(),
        strategy::clipped_mesh_scene(),
        strategy::overlapping_scene(),
        strategy::crossing_scene()
    ];
    let culls = [CullMode::VALUES, &[CullMode::FrontAndBack]].concat();
    let lists = (
        primitive::multisampled(scenes, counts(Topology::TriangleList)),
        prop::sample::select(culls),
        prop::sample::select(FrontFace::VALUES),
    )
        .prop_map(|(mut case, cull, front_face)| {
            (case.scene.state.cull, case.scene.state.front_face) = (cull, front_face);
            case
        });
    let mut kinds = vec![lists.boxed()];
    for topology in [Topology::TriangleStrip, Topology::TriangleFan] {
        if p.draws(topology, 1) {
            kinds.push(primitive::strips_or_fans(topology, counts(topology)).boxed());
        }
    }
    Union::new(kinds)
        .prop_map(move |mut case| {
            case.scene.state.polygon_mode = mode;
            case
        })
        .boxed()
}

/// [`polygon_cases`] in line mode.
fn line_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    polygon_cases(p, PolygonMode::Line)
}

/// [`polygon_cases`] in point mode.
fn point_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    polygon_cases(p, PolygonMode::Point)
}

/// Either mode the profile declares.
fn any_mode_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let modes: Vec<PolygonMode> = p.state.polygon_modes.values().collect();
    let modes = if modes.is_empty() {
        vec![PolygonMode::Line]
    } else {
        modes
    };
    let p = p.clone();
    prop::sample::select(modes)
        .prop_flat_map(move |mode| polygon_cases(&p, mode))
        .boxed()
}

/// Line mode against the line list of the edges, exactly, every triangle.
pub fn check_edges(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    compare_with_parts(r, case, PolygonMode::Line, false)
}

/// Line mode against the line list of the edges drawn either way round, triangles no plane
/// cuts, at least one fragment where edges meet.
pub fn check_edges_inside(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    compare_with_parts(r, case, PolygonMode::Line, true)
}

/// Point mode against the point list of the vertices, exactly, every triangle.
pub fn check_vertices(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    compare_with_parts(r, case, PolygonMode::Point, false)
}

/// Point mode against the point list of the vertices, triangles no plane cuts, at least one
/// fragment where points overlap.
pub fn check_vertices_inside(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    compare_with_parts(r, case, PolygonMode::Point, true)
}

/// Every fragment of a triangle whose turn is sure reports the facing that turn gives.
pub fn check_facing(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    facing_of(r, case, false)
}

/// [`check_facing`] on the triangles of lists that no plane cuts: a clipped triangle's facing is
/// its visible polygon's, of zero area (so back-facing, Vulkan says) where two corners lie on
/// the near plane and the third behind it, whatever `det[x y w]` says; and a strip's or fan's
/// fragment names its triangle only through its flat values on a GPU.
pub fn check_facing_inside(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    facing_of(r, case, true)
}

/// Each fragment's facing against its triangle's sure turn; under `freedom` only list triangles
/// no plane cuts.
fn facing_of(r: &mut dyn Rasterizer, case: &PrimitiveScene, freedom: bool) -> Result<(), Violation> {
    let mode = case.scene.state.polygon_mode;
    if mode == PolygonMode::Fill || (freedom && case.topology != Topology::TriangleList) {
        return Ok(());
    }
    let profile = r.profile();
    let drawn = sample_fragments(r, case)?;
    let list = case.as_list();
    let turns: Vec<Turn> = list
        .scene
        .turns(&profile)
        .into_iter()
        .enumerate()
        .map(|(i, t)| {
            if freedom && !inside_viewport(case, list.scene.corners(i)) {
                Turn::Unsure
            } else {
                t
            }
        })
        .collect();
    let mut found = Findings::new();
    for f in &drawn {
        let Some(front) = turns.get(f.primitive as usize).and_then(|t| {
            t.front_facing(&case.scene.state)
                .filter(|_| *t != Turn::Degenerate)
        }) else {
            continue;
        };
        if f.front_facing != front {
            found.add((f.x, f.y), || {
                format!(
                    "({}, {}) sample {} of triangle {} in {} mode says front_facing = {}, but the triangle faces {}",
                    f.x,
                    f.y,
                    f.sample,
                    f.primitive,
                    mode.name(),
                    f.front_facing,
                    if front { "front" } else { "back" }
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "{} in {} mode report another facing than their triangle's",
            plural(n, "fragment"),
            mode.name()
        )
    })
}
