//! Strategies for lines, points and multisampled triangles, mostly on the 8-bit grid of
//! power-of-two viewports, so that every implementation snaps their ends to the same points.

use proptest::prelude::*;
use refrast::{CompareOp, CullMode, DrawState, Interpolation, Scissor, Setting, Topology};

use super::{GRID, side};
use crate::scene::PrimitiveScene;
use crate::scene::{Scene, clip_of};

/// A line end or point coordinate: on sample centres, pixel corners and half-way (the ties
/// of every line rule), or anywhere, up to two pixels beyond a 16 to 64-px viewport.
fn coordinate() -> impl Strategy<Value = i64> {
    prop_oneof![
        3 => -2 * GRID..66 * GRID,
        1 => (-2i64..66).prop_map(|p| p * GRID + GRID / 2),
        1 => (-2i64..66).prop_map(|p| p * GRID),
        1 => (-4i64..132).prop_map(|p| p * GRID / 2 + GRID / 4),
    ]
}

/// A segment: two ends, the second often along an axis, on a diagonal, or within a pixel.
pub(super) fn segment() -> impl Strategy<Value = [(i64, i64); 2]> {
    (
        (coordinate(), coordinate()),
        (coordinate(), coordinate()),
        0..8u8,
        -2 * GRID..2 * GRID,
    )
        .prop_map(|(a, mut b, shape, short)| {
            match shape {
                0 => b.1 = a.1,
                1 => b.0 = a.0,
                2 => b.1 = a.1 + (b.0 - a.0),
                3 => b.1 = a.1 - (b.0 - a.0),
                4 => b = (a.0 + short, a.1 + short / 3),
                _ => {}
            }
            [a, b]
        })
}

/// Grid points to clip-space positions at `w = 1`, depths in `[0, 1]`.
fn positions(w: u32, h: u32, points: &[(i64, i64)], zs: &[f32]) -> Vec<[f32; 4]> {
    points
        .iter()
        .enumerate()
        .map(|(i, &(x, y))| clip_of(w, h, 8, x, y, zs[i % zs.len()], 1.0))
        .collect()
}

/// One to four segments as a line list, exactly on the grid, no clipping but at the guard band.
pub fn line_list() -> impl Strategy<Value = PrimitiveScene> {
    (
        prop::collection::vec(segment(), 1..5),
        prop::collection::vec(0.0f32..1.0, 1..9),
        side(),
        side(),
    )
        .prop_map(|(segments, zs, w, h)| {
            let points: Vec<(i64, i64)> = segments.iter().flatten().copied().collect();
            let indices = (0..points.len() as u32).collect();
            PrimitiveScene::of(w, h, positions(w, h, &points, &zs), Topology::LineList, indices)
        })
}

/// A strip of two to six vertices, exactly on the grid; half of them monotone in x (every
/// segment x-major, left to right), where Vulkan forbids duplicate fragments at the joints.
pub fn line_strip() -> impl Strategy<Value = PrimitiveScene> {
    let free = prop::collection::vec((coordinate(), coordinate()), 2..7);
    let monotone = (
        (coordinate(), coordinate()),
        prop::collection::vec((1..8 * GRID, -1..1i64, 0..GRID), 1..6),
    )
        .prop_map(|(start, steps)| {
            let mut points = vec![start];
            for (dx, sign, dy) in steps {
                let last = points[points.len() - 1];
                // |dy| ≤ dx keeps each segment x-major.
                points.push((last.0 + dx, last.1 + (sign | 1) * dy.min(dx)));
            }
            points
        });
    (
        prop_oneof![free, monotone],
        prop::collection::vec(0.0f32..1.0, 1..9),
        side(),
        side(),
    )
        .prop_map(|(points, zs, w, h)| {
            let indices = (0..points.len() as u32).collect();
            PrimitiveScene::of(w, h, positions(w, h, &points, &zs), Topology::LineStrip, indices)
        })
}

/// Either kind of line scene.
pub fn lines() -> impl Strategy<Value = PrimitiveScene> {
    prop_oneof![line_list(), line_strip()]
}

/// One segment whose ends have their own `w` in `[0.2, 4]` and depth in `[0, 1]`: perspective,
/// inside the view volume, the ends no longer exactly on the grid.
pub fn perspective_line() -> impl Strategy<Value = PrimitiveScene> {
    (
        segment(),
        prop::array::uniform2((0.2f32..4.0, 0.0f32..1.0)),
        side(),
        side(),
    )
        .prop_map(|(s, wz, w, h)| {
            let positions = (0..2)
                .map(|i| clip_of(w, h, 8, s[i].0, s[i].1, wz[i].1, wz[i].0))
                .collect();
            PrimitiveScene::of(w, h, positions, Topology::LineList, vec![0, 1])
        })
}

/// One segment crossing the near plane: the first end in front (`z` in `[0.05, 1]`), the
/// second behind (`z` in `[−1, −0.05]`), both at `w = 1`, so the cut lies on the drawn line.
pub fn near_crossing_line() -> impl Strategy<Value = PrimitiveScene> {
    (segment(), 0.05f32..1.0, -1.0f32..-0.05, side(), side()).prop_map(|(s, front, behind, w, h)| {
        let positions = vec![
            clip_of(w, h, 8, s[0].0, s[0].1, front, 1.0),
            clip_of(w, h, 8, s[1].0, s[1].1, behind, 1.0),
        ];
        PrimitiveScene::of(w, h, positions, Topology::LineList, vec![0, 1])
    })
}

/// A point's vertex: on the grid ([`coordinate`]) at `w` 1 or in [0.25, 4) with `z/w` in
/// [0, 1) most of the time; else behind the eye (`w` 0 or negative), before the near plane
/// (`z` negative), on either depth plane exactly, or past the far one.
pub fn point_vertex() -> impl Strategy<Value = (i64, i64, f32, f32)> {
    let w = prop_oneof![Just(1.0f32), 0.25f32..4.0];
    let depth = prop_oneof![
        6 => (0.0f32..1.0, w.clone()),
        1 => (prop_oneof![Just(0.0f32), Just(1.0), -1.0f32..-0.001, 1.001f32..2.0], w),
        1 => (-1.0f32..1.0, prop_oneof![Just(0.0f32), -4.0f32..-0.05]),
    ];
    ((coordinate(), coordinate()), depth).prop_map(|((x, y), (z, w))| (x, y, z, w))
}

/// A point list of one to six points over their vertices and up to three unused ones, half the
/// time in order (point `i` at vertex `i`), else through indices in any order, with repeats.
pub fn points() -> impl Strategy<Value = PrimitiveScene> {
    let picks = prop_oneof![
        Just(None),
        prop::collection::vec(any::<prop::sample::Index>(), 1..7).prop_map(Some)
    ];
    (
        prop::collection::vec(point_vertex(), 1..7),
        0..4usize,
        picks,
        side(),
        side(),
    )
        .prop_map(|(vertices, unused, picks, width, height)| {
            let n = vertices.len();
            let mut positions: Vec<[f32; 4]> = vertices
                .iter()
                .map(|&(x, y, z, w)| {
                    if w > 0.0 {
                        clip_of(width, height, 8, x, y, z, w)
                    } else {
                        // Behind the eye: the position at w = 1 turned through the eye (or
                        // flattened onto it), z as drawn.
                        let [px, py, _, _] = clip_of(width, height, 8, x, y, 0.0, 1.0);
                        let s = if w == 0.0 { 1.0 } else { w };
                        [px * s, py * s, z, w]
                    }
                })
                .collect();
            let indices = match picks {
                None => (0..n as u32).collect(),
                Some(picks) => {
                    positions.extend(std::iter::repeat_n([0.0, 0.0, 0.5, 1.0], unused));
                    let all = positions.len();
                    picks.iter().map(|i| i.index(all) as u32).collect()
                }
            };
            PrimitiveScene::of(width, height, positions, Topology::PointList, indices)
        })
}

/// `scenes` drawn at one of `counts` samples per pixel (the counts above one a profile declares).
pub fn multisampled(
    scenes: impl Strategy<Value = Scene>,
    counts: Vec<u8>,
) -> impl Strategy<Value = PrimitiveScene> {
    let counts = if counts.is_empty() { vec![1] } else { counts };
    (scenes, prop::sample::select(counts)).prop_map(|(scene, n)| PrimitiveScene::triangles(scene, n))
}

/// `scenes` of lines or points drawn at one of `counts` samples per pixel.
pub fn multisampled_primitives(
    scenes: impl Strategy<Value = PrimitiveScene>,
    counts: Vec<u8>,
) -> impl Strategy<Value = PrimitiveScene> {
    let counts = if counts.is_empty() { vec![1] } else { counts };
    (scenes, prop::sample::select(counts)).prop_map(|(scene, samples)| PrimitiveScene { samples, ..scene })
}

/// `cases` with a scissor rectangle, in 64ths of the viewport's sides: from empty to past its
/// right and bottom sides, thin strips and single pixels included; it shrinks toward the
/// top-left corner and toward nothing. Culling, the compare op and depth writes vary too, so
/// the scissor is seen with each (the profile's fit keeps what it supports).
pub fn scissored(cases: impl Strategy<Value = PrimitiveScene>) -> impl Strategy<Value = PrimitiveScene> {
    let state = (
        prop::sample::select(CullMode::VALUES),
        prop::sample::select(CompareOp::VALUES),
        any::<bool>(),
    );
    (cases, 0u32..=68, 0u32..=68, 0u32..=72, 0u32..=72, state).prop_map(|(mut case, x, y, w, h, state)| {
        let (width, height) = (case.scene.width, case.scene.height);
        (
            case.scene.state.cull,
            case.scene.state.depth.compare,
            case.scene.state.depth.write,
        ) = state;
        case.scene.state.scissor = Some(Scissor {
            x: x * width / 64,
            y: y * height / 64,
            width: w * width / 64,
            height: h * height / 64,
        });
        case
    })
}

/// `cases` with a sample mask: no sample kept, one, all but one, or any 32 bits (those at and
/// above the sample count among them, which mean nothing); it shrinks toward keeping sample 0
/// alone. The compare op and depth writes vary too, so the mask is seen with each.
pub fn sample_masked(cases: impl Strategy<Value = PrimitiveScene>) -> impl Strategy<Value = PrimitiveScene> {
    let state = (prop::sample::select(CompareOp::VALUES), any::<bool>());
    (cases, 0u8..4, 0u8..16, any::<u32>(), state).prop_map(|(mut case, kind, bit, bits, state)| {
        let one = 1u32 << (bit % case.samples.max(1));
        (case.scene.state.depth.compare, case.scene.state.depth.write) = state;
        case.scene.state.sample_mask = match kind {
            0 => one,
            1 => !one,
            2 => 0,
            // All ones would mask nothing: clear a kept bit.
            _ if bits == u32::MAX => !one,
            _ => bits,
        };
        case
    })
}

/// `cases` drawn under centroid interpolation, half of them with a sample mask that keeps at
/// least one of the count's samples (all but one, or any bits besides); it shrinks toward no
/// mask. Masked, the first covered sample the mask keeps is not always the first covered.
pub fn centroid(cases: impl Strategy<Value = PrimitiveScene>) -> impl Strategy<Value = PrimitiveScene> {
    (cases, 0u8..4, 0u8..16, any::<u32>()).prop_map(|(mut case, kind, bit, bits)| {
        let one = 1u32 << (bit % case.samples.max(1));
        case.scene.state.interpolation = Interpolation::Centroid;
        case.scene.state.sample_mask = match kind {
            0 | 1 => DrawState::ALL_SAMPLES,
            2 => !one,
            _ => bits | one,
        };
        case
    })
}

/// One triangle over 20×16 at a sample count `d` declares, drawn conservatively: under
/// `under` by underestimation, else by overestimation with an extra size of 0, the most `d`
/// honours, or between. A quarter of the triangles are collinear (zero area before snapping)
/// and a quarter a sixteenth of a grid step off collinear (zero area once snapped to `d`'s
/// grid, where it has 8 bits or fewer; a real sliver on a finer one); the rest anywhere,
/// reaching a little past the viewport.
pub fn conservative(d: &refrast::Profile, under: bool) -> impl Strategy<Value = PrimitiveScene> + use<> {
    let bits = d.snapping.grid_bits().unwrap_or(8).min(8);
    let max_extra = d.state.conservative.map_or(0.0, |c| c.max_extra);
    let counts = d.sample_counts();
    let one = 1i64 << bits;
    let coord = move |side: i64| (-2 * one)..((side + 2) * one);
    let vertex = (coord(20), coord(16));
    (
        [vertex.clone(), vertex.clone(), vertex],
        0u8..4,
        prop::sample::select(counts),
        0u8..3,
        0.0f32..=1.0,
    )
        .prop_map(move |(mut t, kind, samples, size, fraction)| {
            // Collinear: the third vertex halfway between the first two, on the grid.
            if kind >= 2 {
                t[1] = (
                    t[0].0 + 2 * ((t[1].0 - t[0].0) / 2),
                    t[0].1 + 2 * ((t[1].1 - t[0].1) / 2),
                );
                t[2] = ((t[0].0 + t[1].0) / 2, (t[0].1 + t[1].1) / 2);
            }
            // Sixteenths of a grid step: the last kind moved off the line by one.
            let mut fine = t.map(|(x, y)| (x * 16, y * 16));
            if kind == 3 {
                fine[2].1 += 1;
            }
            let mut scene = Scene::from_subpixels(20, 16, bits + 4, &[fine], 0.5);
            scene.state.conservative = Some(if under {
                refrast::Conservative::Underestimate
            } else {
                refrast::Conservative::Overestimate {
                    extra: [0.0, max_extra, max_extra * fraction][usize::from(size)],
                }
            });
            PrimitiveScene::triangles(scene, samples)
        })
}

/// `scene` with every vertex (at `w = 1`) moved to the nearest point of a grid of `bits`
/// subpixel bits, so that moving it by whole grid steps moves its snapped vertices alike
/// (off the grid, rounding half to even is no translation: 0.5 rounds to 0 and 1.5 to 2).
#[must_use]
pub fn on_grid(mut scene: Scene, bits: u8) -> Scene {
    let (w, h) = (scene.width, scene.height);
    for p in &mut scene.positions {
        if p[3] != 1.0 {
            continue;
        }
        let [x, y] = crate::oracle::raster::project(w, h, p.map(f64::from));
        let one = f64::from(1u32 << bits.min(16));
        *p = clip_of(
            w,
            h,
            bits,
            (x * one).round() as i64,
            (y * one).round() as i64,
            p[2],
            1.0,
        );
    }
    scene
}

/// A strip or fan over `scene`'s positions: 3 to 12 indices drawn from them, in any order and
/// with repeats (so zero-area triangles too); its state is the scene's.
fn over(scene: Scene, topology: Topology, picks: &[prop::sample::Index]) -> PrimitiveScene {
    let n = scene.positions.len();
    let indices = picks.iter().map(|i| i.index(n) as u32).collect();
    let (width, height) = (scene.width, scene.height);
    let mut case = PrimitiveScene::of(width, height, scene.positions.clone(), topology, indices);
    case.scene.state = scene.state;
    case
}

/// Vertices for a strip or fan of consistent winding on the 8-bit grid: a zigzag between two
/// rows that may fold back (a strip), or a rim turning round a hub (a fan, the hub first); `w`
/// of 1 or varied, `z` from before the near plane to beyond the far one, so that some triangles
/// are clipped by either.
fn shaped(topology: Topology) -> impl Strategy<Value = PrimitiveScene> {
    (
        side(),
        side(),
        (coordinate(), coordinate(), coordinate()),
        prop::collection::vec((-4 * GRID..24 * GRID, -GRID..GRID), 2..10),
        prop::collection::vec(-0.3f32..1.2, 1..6),
        prop::collection::vec(0.25f32..3.0, 1..4),
        any::<bool>(),
    )
        .prop_map(move |(w, h, (x0, y0, y1), steps, zs, ws, flat_w)| {
            let ws = if flat_w { vec![1.0] } else { ws };
            let mut points = Vec::new();
            if topology == Topology::TriangleFan {
                // The hub, then rim points at growing angles (a step's first number, in 1/256 turn).
                points.push((x0, y0));
                let radius = (y1 - y0).abs().max(GRID);
                let mut turn = 0i64;
                for &(step, wobble) in &steps {
                    turn += step.rem_euclid(64 * GRID) / GRID;
                    let angle = turn as f64 * std::f64::consts::TAU / 256.0;
                    let r = (radius + wobble) as f64;
                    points.push((x0 + (r * angle.cos()) as i64, y0 + (r * angle.sin()) as i64));
                }
            } else {
                let mut x = x0;
                for (k, &(step, wobble)) in steps.iter().chain(&[(GRID, 0), (GRID, 0)]).enumerate() {
                    let y = if k % 2 == 0 { y0 } else { y1 };
                    points.push((x, y + wobble));
                    x += step / 2;
                }
            }
            let positions = points
                .iter()
                .enumerate()
                .map(|(i, &(x, y))| clip_of(w, h, 8, x, y, zs[i % zs.len()], ws[i % ws.len()]))
                .collect();
            let indices = (0..points.len() as u32).collect();
            PrimitiveScene::of(w, h, positions, topology, indices)
        })
}

/// Triangle strips or fans (`topology`): shaped ones of consistent winding ([`shaped`]), or
/// indices picked from a mesh's, a clipped mesh's or overlapping triangles' vertices; under
/// every cull mode (both faces too) and front face (the profile's fit keeps what it
/// supports), at one of `counts` samples per pixel.
pub fn strips_or_fans(topology: Topology, counts: Vec<u8>) -> impl Strategy<Value = PrimitiveScene> {
    let scenes = prop_oneof![
        super::mesh_scene(),
        super::clipped_mesh_scene(),
        super::overlapping_scene()
    ];
    let picked = (scenes, prop::collection::vec(any::<prop::sample::Index>(), 3..12))
        .prop_map(move |(scene, picks)| over(scene, topology, &picks));
    let cases = prop_oneof![shaped(topology), picked];
    let culls = [CullMode::VALUES, &[CullMode::FrontAndBack]].concat();
    let state = (
        prop::sample::select(culls),
        prop::sample::select(refrast::FrontFace::VALUES),
    );
    let faced = (cases, state).prop_map(|(mut case, (cull, front_face))| {
        (case.scene.state.cull, case.scene.state.front_face) = (cull, front_face);
        case
    });
    multisampled_primitives(faced, counts)
}
