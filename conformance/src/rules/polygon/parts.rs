//! A triangle in line or point mode against the same implementation's line list of its edges
//! or point list of its vertices: what each triangle must draw, and the judgement.

use refrast::{COORD_LIMIT, CullMode, Fragment, PolygonMode, Profile, Rasterizer, Topology};

use crate::oracle::brute_force::orient2d;
use crate::oracle::facing::{Turn, snapped_variants};
use crate::oracle::raster::{project, unclipped};
use crate::rules::robust::within_float_range;
use crate::rules::samples::{
    cells, counts, difference_counts, difference_picture, sample_fragments, unattributed_fragments,
};
use crate::scene::{PrimitiveScene, Scene};
use crate::violation::{Violation, plural};

/// The triangles of `case` (in [`refrast::Draw::triangle`]'s order) as a line list of their
/// edges, `3i + e` the edge from corner `e` to corner `e + 1` (reversed: from `e + 1` to
/// `e`), or as a point list of their corners, `3i + k` corner `k`; filled.
#[must_use]
fn as_parts(case: &PrimitiveScene, mode: PolygonMode, reversed: bool) -> PrimitiveScene {
    let list = case.as_list();
    let indices = list
        .scene
        .triangles
        .iter()
        .flat_map(|&[a, b, c]| match mode {
            PolygonMode::Point => vec![a, b, c],
            _ if reversed => vec![b, a, c, b, a, c],
            _ => vec![a, b, b, c, c, a],
        })
        .collect();
    let topology = if mode == PolygonMode::Point {
        Topology::PointList
    } else {
        Topology::LineList
    };
    let mut parts = PrimitiveScene {
        topology,
        indices,
        ..list
    };
    parts.scene.triangles.clear();
    // The draw's cull mode, which lines and points ignore (so a profile that culls one way
    // only is sent the parts too).
    parts.scene.state.polygon_mode = PolygonMode::Fill;
    parts
}

/// Whether no implementation clips triangle `t` of `case`'s list: every corner inside the
/// depth planes and the viewport itself (a point outside it is clipped away).
pub(super) fn inside_viewport(case: &PrimitiveScene, t: [[f32; 4]; 3]) -> bool {
    let (w, h) = (f64::from(case.scene.width), f64::from(case.scene.height));
    unclipped(&t, &case.scene.state)
        && t.iter().all(|&p| {
            let [x, y] = project(case.scene.width, case.scene.height, p.map(f64::from));
            (0.0..=w).contains(&x) && (0.0..=h).contains(&y)
        })
}

/// Whether clip-space `p` projects onto a raster position refrast can snap: `w > 0`, and
/// within ±[`COORD_LIMIT`] pixels.
fn has_raster_position(case: &PrimitiveScene, p: [f32; 4]) -> bool {
    let [x, y] = project(case.scene.width, case.scene.height, p.map(f64::from));
    p[3] > 0.0 && x.abs() < COORD_LIMIT && y.abs() < COORD_LIMIT
}

/// What one triangle of a case must draw: nothing (`shown` false), or per sample between
/// `least` and `most` fragments.
struct Expected {
    /// Whether it is drawn at all (not culled, not of zero area).
    shown: bool,
    /// How it turns, for the message.
    turn: Turn,
    /// The fewest fragments per sample.
    least: Vec<u32>,
    /// The most fragments per sample.
    most: Vec<u32>,
    /// Whether it may draw nothing at all instead.
    may_vanish: bool,
}

/// Each triangle drawn in `case`'s mode against its parts: per sample, the count the parts
/// give (under `freedom`, between one where any part surely covers it and the sum of each
/// part's larger count either way round, on triangles no plane cuts). Under `freedom` a strip's
/// or fan's samples are compared as a whole: which of its triangles a fragment names is
/// `bary.flat.provoking-vertex`'s question (a GPU's fragment names its triangle only through
/// its flat values, which SwiftShader takes from each edge's own first vertex).
pub(super) fn compare_with_parts(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    mode: PolygonMode,
    freedom: bool,
) -> Result<(), Violation> {
    if case.scene.state.polygon_mode != mode {
        return Ok(());
    }
    let whole = freedom && case.topology != Topology::TriangleList;
    let drawn = if whole {
        unattributed_fragments(r, case)?
    } else {
        sample_fragments(r, case)?
    };
    let forward_case = as_parts(case, mode, false);
    let forward = sample_fragments(r, &forward_case)?;
    let backward = if freedom && mode == PolygonMode::Line {
        sample_fragments(r, &as_parts(case, mode, true))?
    } else {
        forward.clone()
    };
    let list = case.as_list();
    let profile = r.profile();
    let turns = list.scene.turns(&profile);
    let what = if mode == PolygonMode::Point {
        "point list of its vertices"
    } else {
        "line list of its edges"
    };
    let mut all = Expected {
        shown: false,
        turn: Turn::Unsure,
        least: vec![0; cells(case)],
        most: vec![0; cells(case)],
        may_vanish: false,
    };
    for (i, &turn) in turns.iter().enumerate() {
        let Some(expected) = expected(
            &profile,
            case,
            (&list, i, turn),
            freedom,
            (&forward_case, [&forward, &backward]),
        ) else {
            if whole {
                // A triangle not judged draws what it draws: the whole is unknown.
                return Ok(());
            }
            continue;
        };
        if whole {
            for c in 0..all.least.len() {
                all.least[c] += expected.least[c];
                all.most[c] += expected.most[c];
            }
            continue;
        }
        let got = counts(case, &drawn, Some(i as u32));
        judge(case, &got, &expected, freedom, || format!("triangle {i}"), what)?;
    }
    if whole {
        all.shown = true;
        let got = counts(case, &drawn, None);
        let name = || {
            format!(
                "the {}'s triangles",
                case.topology.name().replace("triangle-", "")
            )
        };
        judge(case, &got, &all, freedom, name, &what.replace("its", "their"))?;
    }
    Ok(())
}

/// What triangle `i` of `list`, turning `turn`, must draw, from the parts' fragments drawn
/// forward and backward;
/// `None` when it is not judged (cut by a plane under `freedom`, a turn correct
/// implementations may see either way, zero area where that is not refrast's to decide).
fn expected(
    profile: &Profile,
    case: &PrimitiveScene,
    (list, i, turn): (&PrimitiveScene, usize, Turn),
    freedom: bool,
    (parts, [forward, backward]): (&PrimitiveScene, [&[Fragment]; 2]),
) -> Option<Expected> {
    let corners = list.scene.corners(i);
    if freedom && !inside_viewport(case, corners) {
        return None;
    }
    let all_project = corners.iter().all(|p| p[3] > 0.0);
    let positioned = corners.iter().all(|&p| has_raster_position(case, p));
    // Zero area decided on the snapped input before clipping (refrast's convention, where the
    // profile claims it): a flat triangle the near plane cuts draws nothing either.
    let turn = match (
        freedom || !positioned || !profile.features.zero_area_before_clipping,
        turn,
    ) {
        (false, Turn::Clockwise | Turn::CounterClockwise | Turn::Unsure) => {
            match flat_before_clipping(case, &corners, profile) {
                Some(true) => Turn::Degenerate,
                Some(false) => turn,
                None => return None,
            }
        }
        _ => turn,
    };
    let shown = match turn {
        Turn::Degenerate if freedom || !all_project => return None,
        // refrast decides zero area before clipping only where every corner has a raster
        // position; else it clips the triangle and keeps it, flat, by the sign of `det[x y w]`:
        // its edges drawn, or nothing where that sign is culled (`may_vanish`).
        Turn::Degenerate => !positioned,
        other => other.drawn(&case.scene.state)?,
    };
    let (mut least, mut most) = (vec![0; cells(case)], vec![0; cells(case)]);
    if shown {
        for part in 0..3 {
            let primitive = Some(3 * i as u32 + part);
            let (f, b) = (
                counts(parts, forward, primitive),
                counts(parts, backward, primitive),
            );
            for c in 0..least.len() {
                least[c] += f[c].min(b[c]);
                most[c] += f[c].max(b[c]);
            }
        }
    }
    Some(Expected {
        shown,
        turn,
        least,
        most,
        // Where a corner has no raster position (w ≤ 0, or beyond ±COORD_LIMIT px), refrast
        // may find none for a vertex of the clipped polygon either, and then draws nothing of
        // the triangle in any mode (`DrawStats::degenerate`), as it fills nothing of it; so
        // where a coordinate is beyond the float range, since its f64 cut may then cancel a
        // cut vertex's w to 0 (a corner at w = 4e21 cut against one at 3e-38).
        may_vanish: !freedom && (!positioned || !within_float_range(&alone(case, corners))),
    })
}

/// The triangle of `corners` alone, under `case`'s viewport and state.
fn alone(case: &PrimitiveScene, corners: [[f32; 4]; 3]) -> Scene {
    let mut scene = Scene::new(
        case.scene.width,
        case.scene.height,
        corners.to_vec(),
        vec![[0, 1, 2]],
    );
    scene.state = case.scene.state;
    scene
}

/// Whether every way `profile` may snap `corners` leaves no area (`Some(true)`), none does
/// (`Some(false)`), or the ways disagree (`None`); `Some(false)` without a grid.
fn flat_before_clipping(case: &PrimitiveScene, corners: &[[f32; 4]; 3], profile: &Profile) -> Option<bool> {
    let Some(variants) = snapped_variants(corners, case.scene.width, case.scene.height, profile) else {
        return Some(false);
    };
    let flat = variants
        .iter()
        .filter(|v| orient2d(v[0], v[1], v[2]) == 0)
        .count();
    match flat {
        0 => Some(false),
        n if n == variants.len() => Some(true),
        _ => None,
    }
}

/// `got` against `expected`: exactly its least counts, or under `freedom` between one where
/// the least is any and the most.
fn judge(
    case: &PrimitiveScene,
    got: &[u32],
    expected: &Expected,
    freedom: bool,
    name: impl Fn() -> String,
    what: &str,
) -> Result<(), Violation> {
    let want: Vec<u32> = (0..got.len())
        .map(|c| {
            if freedom {
                got[c].clamp(expected.least[c].min(1), expected.most[c])
            } else {
                expected.least[c]
            }
        })
        .collect();
    if got == want || (expected.may_vanish && got.iter().all(|&n| n == 0)) {
        return Ok(());
    }
    let state = &case.scene.state;
    let mode = state.polygon_mode.name();
    let why = if expected.shown {
        let subject = name();
        let verb = if subject.starts_with("triangle ") {
            "draws"
        } else {
            "draw"
        };
        format!("{subject} in {mode} mode {verb} other samples than the {what} draws")
    } else {
        let reason = match expected.turn {
            Turn::Degenerate => "has zero area".to_owned(),
            _ if state.cull == CullMode::FrontAndBack => "is culled with both faces".to_owned(),
            t => format!(
                "faces {} and {:?} culling discards it",
                if t.front_facing(state) == Some(true) {
                    "front"
                } else {
                    "back"
                },
                state.cull
            ),
        };
        format!(
            "{} {reason}, but in {mode} mode it draws {}",
            name(),
            plural(got.iter().sum::<u32>() as usize, "fragment")
        )
    };
    let mut violation = Violation::new(why);
    violation.counts = Some(Box::new(difference_counts(got, &want)));
    violation.picture = Some(Box::new(difference_picture(case, got, &want, Vec::new())));
    Err(violation)
}
