//! User clip and cull distances: a primitive is drawn only where each of its clip distances,
//! interpolated perspective-correctly, is `≥ 0`, and not at all when every vertex is negative
//! in one cull distance.
//!
//! Where the distances cut, the oracle is the cut line in raster space ([`Cut`]), judged
//! outside the tolerance band of it and of the triangle's outline; where they cut nothing, or
//! only cull, the implementation is compared with its own draw without them, exactly. The
//! property dEQP calls complementarity, a draw by `d` and by `−d` covering together each sample
//! of the draw without `d` once, is exact.
//!
//! [`Cut`]: crate::oracle::distance::Cut

use std::ops::RangeInclusive;

use proptest::prelude::*;
use proptest::strategy::Union;
use refrast::{Distances, Profile};

use super::level::Level;
use super::{Family, Need, Rule, needs};
use crate::runner::property_for;
use crate::scene::{PrimitiveScene, Scene};
use crate::strategy::{self, primitive};

mod check;
pub use check::{check_complementarity, check_culls, check_half_space, check_lines_points};

/// What every specification says of clip distances.
const CLIP_SOURCE: &str = "Vulkan 1.4, Primitive Clipping (ClipDistance: \"the clip half-space ... where the interpolated clip distance is ≥ 0\", interpolated perspective-correctly); OpenGL 4.6 §13.5 (gl_ClipDistance, CLIP_DISTANCEi); D3D11.3 §15.4.1 (SV_ClipDistance: rasterization only where the interpolated distances are ≥ 0); dEQP-VK.clipping.user_defined.clip_distance*";

/// What every specification says of cull distances.
const CULL_SOURCE: &str = "Vulkan 1.4, Primitive Clipping (CullDistance: \"If the cull distance for any enabled cull half-space is negative for all of the vertices of the primitive under consideration, the primitive is discarded\"); OpenGL 4.6 §13.5 (gl_CullDistance); D3D11.3 §15.4.2 (SV_CullDistance); dEQP-VK.clipping.user_defined.clip_cull_distance*";

/// The complementarity criterion.
const COMPLEMENT_SOURCE: &str = "Vulkan 1.4, Primitive Clipping (\"primitives must not be missing any pixels, and pixels must not be drawn twice in regions where those primitives are cut by the clip planes\", of a draw with dᵢ and again with −dᵢ); OpenGL 4.6 §13.5 (the same criterion); dEQP-VK.clipping.user_defined.complementarity.*";

/// D3D11.3 has no complementarity sentence.
const COMPLEMENT_D3D: &str = "D3D11.3 §15.4.1 tests each sample's interpolated distance and says nothing of a draw by −d beside one by d: where its arithmetic puts a sample on the cut is the implementation's, so samples within the tolerance band of a cut are not compared (a draw that covers them twice or never is beyond D3D11.3)";

/// OpenGL ES 3.2 has no clip or cull distances.
const NO_ES_DISTANCES: &str = "OpenGL ES 3.2 has no gl_ClipDistance or gl_CullDistance (EXT_clip_cull_distance is an extension): nothing to hold a driver judged by it to";

/// The implementation honours clip distances.
const CLIP: Need = needs(|p| p.state.clip_distances > 0, "no clip distances");

/// The implementation honours cull distances.
const CULL: Need = needs(|p| p.state.cull_distances > 0, "no cull distances");

/// The implementation honours clip distances and draws lines or points.
const CLIP_LINES_POINTS: Need = needs(
    |p| p.state.clip_distances > 0 && (p.lines.is_some() || p.points),
    "no clip distances on lines or points",
);

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Clip, "clip.distance.half-space")
            .sentence("A triangle with clip distances covers the samples inside it where every distance, interpolated perspective-correctly, is positive, and none where one is negative (outside the tolerance band of the cut and of its outline); one whose distances are nowhere negative at its corners draws exactly what it draws without them.")
            .source(CLIP_SOURCE)
            .cases(400)
            .needs(CLIP)
            .opengles(Level::NotCovered(NO_ES_DISTANCES))
            .run(|r, cfg| property_for(r, cfg, half_space_cases, check_half_space)),
        Rule::invariant(Family::Clip, "clip.distance.complementarity")
            .sentence("A mesh drawn with a clip distance d and again with −d covers, over the two draws, each sample the mesh covers without d exactly once (every sample where d is the only clip distance and no plane of the clip volume cuts the mesh; else those outside the tolerance band of the cut), and each side of a cut only as the sign of d says: a watertight mesh stays watertight under any clip distance.")
            .source(COMPLEMENT_SOURCE)
            .cases(300)
            .needs(CLIP)
            .d3d11(Level::Partly {
                part: |r, cfg| property_for(r, cfg, complement_cases, check::check_complementarity_away),
                note: COMPLEMENT_D3D,
            })
            .opengles(Level::NotCovered(NO_ES_DISTANCES))
            .run(|r, cfg| property_for(r, cfg, complement_cases, check_complementarity)),
        Rule::invariant(Family::Clip, "clip.distance.lines-points")
            .sentence("A point with a negative clip distance is not drawn, and one without draws as it does without distances; a segment draws nothing where a distance, interpolated perspective-correctly, is negative (beyond the tolerance band of the cut), and exactly what it draws without them where no end has a negative one.")
            .source(CLIP_SOURCE)
            .cases(400)
            .needs(CLIP_LINES_POINTS)
            .opengles(Level::NotCovered(NO_ES_DISTANCES))
            .run(|r, cfg| property_for(r, cfg, line_point_cases, check_lines_points)),
        Rule::invariant(Family::Clip, "clip.cull-distance.discards")
            .sentence("A primitive (triangle, segment or point) every vertex of which has a negative value of one cull distance draws nothing (−0 is not negative); every other draws exactly what it draws without cull distances.")
            .source(CULL_SOURCE)
            .cases(400)
            .needs(CULL)
            .opengles(Level::NotCovered(NO_ES_DISTANCES))
            .run(|r, cfg| property_for(r, cfg, cull_cases, check_culls)),
    ]
}

/// One to four triangles anywhere within half a viewport beyond its sides, each corner with
/// its own `w` in `[¼, 4]` and depth inside the clip volume: perspective, no depth plane cut.
fn perspective_triangles() -> impl Strategy<Value = Scene> {
    let corner = (-1.5f32..1.5, -1.5f32..1.5, 0.05f32..0.95, 0.25f32..4.0)
        .prop_map(|(x, y, z, w)| [x * w, y * w, z * w, w]);
    (
        prop::collection::vec(prop::array::uniform3(corner), 1..5),
        strategy::side(),
    )
        .prop_map(|(triangles, side)| {
            let positions = triangles.iter().flatten().copied().collect();
            let indices = (0..triangles.len() as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            Scene::new(side, side, positions, indices)
        })
}

/// A clip distance's value at a vertex: anywhere in `[−2, 2]`, or exactly 0 (on the cut).
fn clip_value() -> impl Strategy<Value = f32> {
    prop_oneof![6 => -2.0f32..2.0, 1 => Just(0.0f32)]
}

/// A cull distance's value: negative, positive, or a zero of either sign (`−0` is not negative).
fn cull_value() -> impl Strategy<Value = f32> {
    prop::sample::select(vec![-1.0f32, -0.5, -0.0, 0.0, 0.5, 1.0])
}

/// `cases` with `clip` clip distances and `cull` cull distances at every vertex, their values
/// drawn from `clip_values` and `cull_values`.
fn with_distances(
    cases: impl Strategy<Value = PrimitiveScene> + 'static,
    clip: RangeInclusive<usize>,
    cull: RangeInclusive<usize>,
    clip_values: fn() -> BoxedStrategy<f32>,
    cull_values: fn() -> BoxedStrategy<f32>,
) -> BoxedStrategy<PrimitiveScene> {
    (cases, clip, cull)
        .prop_flat_map(move |(case, clip, cull)| {
            let n = case.scene.positions.len();
            (
                Just(case),
                prop::collection::vec(clip_values(), n * clip),
                prop::collection::vec(cull_values(), n * cull),
                Just((clip, cull)),
            )
        })
        .prop_map(|(mut case, clips, culls, (clip, cull))| {
            let values = (0..case.scene.positions.len())
                .flat_map(|v| {
                    clips[v * clip..(v + 1) * clip]
                        .iter()
                        .chain(&culls[v * cull..(v + 1) * cull])
                        .copied()
                        .collect::<Vec<_>>()
                })
                .collect();
            case.scene.distances = Distances { clip, cull, values };
            case
        })
        .boxed()
}

fn boxed_clip() -> BoxedStrategy<f32> {
    clip_value().boxed()
}

fn boxed_cull() -> BoxedStrategy<f32> {
    cull_value().boxed()
}

/// How many clip distances to draw with: one to three, as many as `p` declares.
fn clip_counts(p: &Profile) -> RangeInclusive<usize> {
    1..=p.state.clip_distances.clamp(1, 3)
}

/// Perspective triangles at one sample, with clip distances.
fn half_space_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let triangles = perspective_triangles().prop_map(|s| PrimitiveScene::triangles(s, 1));
    with_distances(triangles, clip_counts(p), 0..=0, boxed_clip, boxed_cull)
}

/// Meshes over the viewport (some in perspective, some cut by the near plane) at each sample
/// count `p` declares, with clip distances.
fn complement_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let meshes = prop_oneof![
        strategy::mesh_scene(),
        strategy::projected_mesh_scene(),
        strategy::clipped_mesh_scene()
    ];
    let cases = primitive::multisampled(meshes, p.sample_counts()).boxed();
    // One distance half the time: the cases judged at every sample.
    prop_oneof![
        with_distances(cases.clone(), 1..=1, 0..=0, boxed_clip, boxed_cull),
        with_distances(cases, clip_counts(p), 0..=0, boxed_clip, boxed_cull),
    ]
    .boxed()
}

/// Lines (on the grid, in perspective) and points, as `p` draws them, with clip distances.
fn line_point_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let mut kinds: Vec<BoxedStrategy<PrimitiveScene>> = Vec::new();
    if p.lines.is_some() {
        kinds.push(primitive::lines().boxed());
        kinds.push(primitive::perspective_line().boxed());
    }
    if p.points {
        kinds.push(primitive::points().boxed());
    }
    with_distances(Union::new(kinds), clip_counts(p), 0..=0, boxed_clip, boxed_cull)
}

/// Triangles, lines and points as `p` draws them, with one or two cull distances (and
/// sometimes a clip distance beside, which must not change which primitives are culled).
fn cull_cases(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let mut kinds: Vec<BoxedStrategy<PrimitiveScene>> = vec![
        prop_oneof![strategy::mesh_scene(), strategy::overlapping_scene()]
            .prop_map(|s| PrimitiveScene::triangles(s, 1))
            .boxed(),
    ];
    if p.lines.is_some() {
        kinds.push(primitive::lines().boxed());
    }
    if p.points {
        kinds.push(primitive::points().boxed());
    }
    let cull = 1..=p.state.cull_distances.clamp(1, 2);
    with_distances(Union::new(kinds), 0..=0, cull, boxed_clip, boxed_cull)
}

/// Each primitive's vertex indices, as the draw makes them.
fn primitive_corners(case: &PrimitiveScene) -> Vec<Vec<u32>> {
    let draw = case.draw();
    (0..draw.primitive_count())
        .filter_map(|i| draw.primitive(i).map(|p| p.into_owned()))
        .collect()
}

/// The case drawn without clip distance `k` (all of them when `None`), its cull distances kept.
fn without_clip(case: &PrimitiveScene, k: Option<usize>) -> PrimitiveScene {
    let mut out = case.clone();
    let d = &case.scene.distances;
    let keep = |j: usize| k.is_some_and(|k| k != j);
    let values = (0..case.scene.positions.len() as u32)
        .flat_map(|v| {
            let clips = d.clip_of(v).iter().enumerate().filter(|(j, _)| keep(*j));
            clips
                .map(|(_, &x)| x)
                .chain(d.cull_of(v).iter().copied())
                .collect::<Vec<_>>()
        })
        .collect();
    let clip = (0..d.clip).filter(|&j| keep(j)).count();
    out.scene.distances = Distances {
        clip,
        cull: d.cull,
        values,
    };
    out
}

/// The case drawn with no distances at all.
fn without_distances(case: &PrimitiveScene) -> PrimitiveScene {
    let mut out = case.clone();
    out.scene.distances = Distances::default();
    out
}
