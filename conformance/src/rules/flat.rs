//! Flat values: every fragment carries the vertex whose flat (not interpolated) values it
//! takes, its primitive's provoking vertex under the draw's mode, whatever the topology, the
//! sample count, and clipping (a cut triangle keeps its provoking vertex's values, even when
//! that vertex is cut away).

use proptest::prelude::*;
use proptest::strategy::Union;
use refrast::{PolygonMode, Profile, ProvokingVertex, Rasterizer, Topology};

use super::samples::sample_fragments;
use super::{Family, Need, Rule, needs};
use crate::oracle::provoking::provoking_vertex;
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::strategy::{self, primitive};
use crate::violation::{Findings, Violation, plural};

/// Where each specification says which vertex provokes.
const SOURCE: &str = "Vulkan 1.4, the topology sections' provoking vertex (drawing-primitive-topologies) and VK_EXT_provoking_vertex; OpenGL 4.6 §13.6 Flatshading (Table 13.2); OpenGL ES 3.2 §12.4 Flatshading (Table 12.3, the last vertex); D3D11.3 §8.14 Leading Vertex (the first); dEQP-VK.rasterization.flatshading.*, dEQP-VK.rasterization.provoking_vertex.*";

/// The implementation reports flat values.
const FLAT: Need = needs(|p| !p.state.flat.is_empty(), "no flat values");

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Bary, "bary.flat.provoking-vertex")
            .sentence("Every fragment carries the flat values of its primitive's provoking vertex under the draw's mode, for every topology and sample count it draws: first, a triangle list's 3i, a strip's i, a fan's i + 1, a line list's 2i, a line strip's i; last, 3i + 2, i + 2, i + 2, 2i + 1, i + 1; a point its own; also where clipping cuts that vertex away, and in line and point mode (where declared) the triangle's.")
            .source(SOURCE)
            .cases(500)
            .needs(FLAT)
            .run(|r, cfg| property_for(r, cfg, flat_draws, check_provoking)),
    ]
}

/// Every topology `p` draws, at each sample count it draws it at: triangles that cross the
/// near plane or overlap, strips and fans (some cut by the near or far plane), lines and
/// points; under either provoking mode (the profile's fit keeps the ones it declares).
fn flat_draws(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let counts = |topology: Topology| -> Vec<u8> {
        p.sample_counts()
            .into_iter()
            .filter(|&n| p.draws(topology, n))
            .collect()
    };
    let triangles = prop_oneof![
        strategy::crossing_scene(),
        strategy::clipped_mesh_scene(),
        strategy::overlapping_scene()
    ];
    let mut kinds = vec![primitive::multisampled(triangles, counts(Topology::TriangleList)).boxed()];
    for topology in [Topology::TriangleStrip, Topology::TriangleFan] {
        if p.draws(topology, 1) {
            kinds.push(primitive::strips_or_fans(topology, counts(topology)).boxed());
        }
    }
    if p.lines.is_some() {
        let lines = prop_oneof![primitive::lines(), primitive::line_strip()];
        kinds.push(primitive::multisampled_primitives(lines, counts(Topology::LineList)).boxed());
    }
    if p.points {
        kinds.push(
            primitive::multisampled_primitives(primitive::points(), counts(Topology::PointList)).boxed(),
        );
    }
    let modes = prop::sample::select(vec![ProvokingVertex::First, ProvokingVertex::Last]);
    // Triangles at one sample in each polygon mode declared too: a triangle's edges and vertices
    // carry its provoking vertex, not a line's or a point's.
    let polygon_modes: Vec<PolygonMode> = [PolygonMode::Fill]
        .into_iter()
        .chain(p.state.polygon_modes.values())
        .collect();
    (Union::new(kinds), modes, prop::sample::select(polygon_modes))
        .prop_map(|(mut case, mode, polygon_mode)| {
            case.scene.state.provoking_vertex = mode;
            if case.topology.is_triangles() && case.samples == 1 {
                case.scene.state.polygon_mode = polygon_mode;
            }
            case
        })
        .boxed()
}

/// Every fragment's flat vertex is its primitive's provoking vertex.
pub fn check_provoking(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let draw = case.draw();
    let fragments = sample_fragments(r, case)?;
    let mode = match draw.state.provoking_vertex {
        ProvokingVertex::First => "first",
        ProvokingVertex::Last => "last",
    };
    let mut found = Findings::new();
    for f in &fragments {
        let want = provoking_vertex(&draw, f.primitive as usize);
        if f.flat != want {
            found.add((f.x, f.y), || {
                let shown = |v: Option<u32>| v.map_or("none".to_owned(), |v| format!("vertex {v}"));
                format!(
                    "({}, {}) sample {} of {} primitive {}: the flat values of {}, where its provoking vertex under the {mode} mode is {}",
                    f.x,
                    f.y,
                    f.sample,
                    draw.topology,
                    f.primitive,
                    shown(f.flat),
                    shown(want)
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "{} carry another vertex's flat values than their primitive's provoking vertex",
            plural(n, "fragment")
        )
    })
}
