//! The checks of the clip- and cull-distance rules.

use refrast::{Fragment, Profile, Rasterizer, Topology};

use super::{primitive_corners, without_clip, without_distances};
use crate::oracle::distance::{Cut, Outline, segment_cut};
use crate::oracle::raster::project;
use crate::rules::samples::{
    cell, cell_counts, cells, compare_samples, counts, difference_counts, difference_picture, keys,
    positions, sample_fragments,
};
use crate::scene::PrimitiveScene;
use crate::violation::{Expect, Violation, plural};

/// How far beyond the profile's tolerance band a sample must lie from a cut to be judged, in
/// pixels: the cut vertex is computed in floating point before it is snapped (in f32, at clip
/// coordinates within 6 of 0, about 2^-20 of the viewport: far under 1/16 of a pixel at 64 px).
const CUT_SLACK_PX: f64 = 1.0 / 16.0;

/// How far a sample may lie from its pixel's centre, where the checks evaluate the oracle for
/// every sample of a pixel, and a line's coverage is decided (√2/2, rounded up).
const SAMPLE_REACH_PX: f64 = 0.75;

/// How near the line where a distance is 0 a sample may be taken to lie on it, in pixels: the
/// oracle's f64 rounding of a cut through a sample centre, with room to spare (a sample's
/// distance rounds to exactly 0 only within about 10^-14 px of the line).
const ZERO_LINE_PX: f64 = 1e-6;

/// The band around a cut or an outline within which a sample is not judged.
fn band(profile: &Profile) -> f64 {
    profile.band_px() + CUT_SLACK_PX
}

/// Clip distance `j` at the corners of triangle `t` of the case's scene.
fn clip_at(case: &PrimitiveScene, corners: &[u32], j: usize) -> Vec<f64> {
    corners
        .iter()
        .map(|&v| f64::from(case.scene.distances.clip_of(v)[j]))
        .collect()
}

/// Whether no clip distance is negative at any of `corners`: nothing is cut.
fn uncut(case: &PrimitiveScene, corners: &[u32]) -> bool {
    corners
        .iter()
        .all(|&v| case.scene.distances.clip_of(v).iter().all(|&d| d >= 0.0))
}

/// The fragments of primitive `p`, as keys.
fn of_primitive(frags: &[Fragment], p: usize) -> Vec<(u32, u32, u8, u32)> {
    keys(frags.iter().filter(|f| f.primitive as usize == p))
}

/// A primitive nothing cuts draws exactly what it draws without distances.
fn compare_uncut(
    case: &PrimitiveScene,
    got: &[Fragment],
    want: &[Fragment],
    p: usize,
    what: &str,
) -> Result<(), Violation> {
    if of_primitive(got, p) == of_primitive(want, p) {
        return Ok(());
    }
    let only = |f: &[Fragment]| -> Vec<Fragment> {
        f.iter().filter(|f| f.primitive as usize == p).copied().collect()
    };
    let (g, w) = (cell_counts(case, &only(got)), cell_counts(case, &only(want)));
    let mut violation = Violation::new(format!(
        "{what} {p}, with no clip distance negative at any vertex, draws other fragments than without distances"
    ));
    violation.counts = Some(Box::new(difference_counts(&g, &w)));
    violation.picture = Some(Box::new(difference_picture(case, &g, &w, Vec::new())));
    Err(violation)
}

/// Triangles cut by their clip distances cover the oracle's part of them outside the band; an
/// uncut one draws as without distances.
pub fn check_half_space(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let cut = sample_fragments(r, case)?;
    let whole = sample_fragments(r, &without_distances(case))?;
    let band = band(&profile);
    let (w, h) = (case.scene.width, case.scene.height);
    for (t, corners) in primitive_corners(case).iter().enumerate() {
        let positions = case.scene.positions_of(t);
        if uncut(case, corners) {
            // Where a distance is 0 at a corner, the samples at its zero (that corner, or the
            // edge to another such corner) interpolate to 0 give or take rounding: either way.
            let zeros: Vec<Cut> = (0..case.scene.distances.clip)
                .map(|j| clip_at(case, corners, j))
                .filter(|d| d.contains(&0.0))
                .filter_map(|d| Cut::of_triangle(w, h, positions, [d[0], d[1], d[2]]))
                .collect();
            if zeros.is_empty() {
                compare_uncut(case, &cut, &whole, t, "triangle")?;
                continue;
            }
            let without = counts(case, &whole, Some(t as u32));
            let mut expected = vec![Expect::Zero; cells(case)];
            for y in 0..h {
                for x in 0..w {
                    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let i = cell(case, x, y, 0);
                    expected[i] = match without[i] {
                        0 => Expect::Zero,
                        _ if zeros.iter().any(|c| c.signed_px(cx, cy).abs() <= band) => Expect::ZeroOrOne,
                        _ => Expect::One,
                    };
                }
            }
            compare_samples(
                case,
                &counts(case, &cut, Some(t as u32)),
                &expected,
                &format!(
                    "triangle {t}, no clip distance negative at a corner, covering what it covers without them (but where a distance is 0, either way)"
                ),
            )?;
            continue;
        }
        let Some(outline) = Outline::of_triangle(w, h, positions) else {
            continue;
        };
        let Some(cuts) = (0..case.scene.distances.clip)
            .map(|j| {
                let d = clip_at(case, corners, j);
                Cut::of_triangle(w, h, positions, [d[0], d[1], d[2]])
            })
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let mut expected = vec![Expect::ZeroOrOne; cells(case)];
        for y in 0..h {
            for x in 0..w {
                let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let o = outline.signed_px(cx, cy);
                let c = cuts
                    .iter()
                    .map(|c| c.signed_px(cx, cy))
                    .fold(f64::INFINITY, f64::min);
                expected[cell(case, x, y, 0)] = if o < -band || c < -band {
                    Expect::Zero
                } else if o > band && c > band {
                    Expect::One
                } else {
                    Expect::ZeroOrOne
                };
            }
        }
        compare_samples(
            case,
            &counts(case, &cut, Some(t as u32)),
            &expected,
            &format!("triangle {t} covered where its clip distances are positive, and only there"),
        )?;
    }
    Ok(())
}

/// The three draws of a complementarity case: with `d`, with `−d`, without it.
struct Complement {
    with: Vec<Fragment>,
    negated: Vec<Fragment>,
    without: Vec<Fragment>,
}

impl Complement {
    fn draw(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<Self, Violation> {
        let mut negated = case.clone();
        negated.scene.distances = case.scene.distances.with_clip_negated(0);
        Ok(Self {
            with: sample_fragments(r, case)?,
            negated: sample_fragments(r, &negated)?,
            without: sample_fragments(r, &without_clip(case, Some(0)))?,
        })
    }
}

/// The draws by `d` and `−d` cover each sample of the draw without `d` once between them: every
/// sample compared where `d` is the only clip distance and the mesh lies inside the clip
/// volume, else those away from the cut.
///
/// Where another cut (a second distance, the near plane) bounds the region `d` cuts, the cut
/// vertex on that boundary is snapped off its line, so the two parts' outline there is not the
/// whole's, even for refrast: the samples next to that point are the implementation's.
pub fn check_complementarity(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let exact = case.scene.distances.clip == 1 && inside_clip_volume(case);
    complementarity(r, case, !exact)
}

/// Whether every vertex lies inside the clip volume, so that no plane of it cuts anything.
fn inside_clip_volume(case: &PrimitiveScene) -> bool {
    case.scene.positions.iter().all(|p| {
        let w = p[3];
        w > 0.0 && p[0].abs() <= w && p[1].abs() <= w && (0.0..=w).contains(&p[2])
    })
}

/// The raster edges of triangle `t` whose two corners have clip distance 0 equal to 0.
fn zero_edges(case: &PrimitiveScene, t: usize, corners: &[u32]) -> Vec<[[f64; 2]; 2]> {
    let (w, h) = (case.scene.width, case.scene.height);
    let positions = case.scene.positions_of(t);
    if !positions.iter().all(|p| p[3] > 0.0) {
        return Vec::new();
    }
    let d = clip_at(case, corners, 0);
    let raster = positions.map(|p| project(w, h, p));
    (0..3)
        .filter(|&k| d[k] == 0.0 && d[(k + 1) % 3] == 0.0)
        .map(|k| [raster[k], raster[(k + 1) % 3]])
        .collect()
}

/// The distance in pixels from `p` to the line through `edge`.
fn line_distance([a, b]: [[f64; 2]; 2], p: [f64; 2]) -> f64 {
    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
    let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    if length == 0.0 {
        (p[0] - a[0]).hypot(p[1] - a[1])
    } else {
        cross.abs() / length
    }
}

/// Where each sample of the case's count lies in its pixel, in pixels from the top-left corner.
fn sample_positions(r: &dyn Rasterizer, case: &PrimitiveScene) -> Vec<[f64; 2]> {
    positions(r, case)
        .iter()
        .map(|&[u, v]| [f64::from(u) / 16.0, f64::from(v) / 16.0])
        .collect()
}

/// Triangle `t`'s cuts but that of clip distance 0: its other clip distances', and the depth
/// planes' it is clipped at (a plane of the clip volume cuts as a distance does: `z`, `z + w`,
/// `w − z`).
fn other_cuts(case: &PrimitiveScene, t: usize, corners: &[u32]) -> Vec<Cut> {
    let (w, h) = (case.scene.width, case.scene.height);
    let positions = case.scene.positions_of(t);
    let state = &case.scene.state;
    let mut planes: Vec<[f64; 3]> = (1..case.scene.distances.clip)
        .map(|j| {
            let d = clip_at(case, corners, j);
            [d[0], d[1], d[2]]
        })
        .collect();
    if state.clip_near {
        planes.push(positions.map(|p| match state.depth_range {
            refrast::DepthRange::ZeroToOne => p[2],
            refrast::DepthRange::NegativeOneToOne => p[2] + p[3],
        }));
    }
    if state.clip_far {
        planes.push(positions.map(|p| p[3] - p[2]));
    }
    planes
        .into_iter()
        .filter_map(|d| Cut::of_triangle(w, h, positions, d))
        .collect()
}

/// [`check_complementarity`] with the samples within the band of the cut left out, always.
pub fn check_complementarity_away(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    complementarity(r, case, true)
}

fn complementarity(r: &mut dyn Rasterizer, case: &PrimitiveScene, away: bool) -> Result<(), Violation> {
    let profile = r.profile();
    let drawn = Complement::draw(r, case)?;
    let margin = band(&profile) + SAMPLE_REACH_PX;
    let (w, h) = (case.scene.width, case.scene.height);
    let corners = primitive_corners(case);
    // Each triangle's cut by d and outline, where its corners project.
    let shapes: Vec<Option<(Outline, Cut)>> = corners
        .iter()
        .enumerate()
        .map(|(t, c)| {
            let positions = case.scene.positions_of(t);
            let d = clip_at(case, c, 0);
            Some((
                Outline::of_triangle(w, h, positions)?,
                Cut::of_triangle(w, h, positions, [d[0], d[1], d[2]])?,
            ))
        })
        .collect();
    // Every other cut too: where one bounds the region d cuts, the parts' outline is not the
    // whole's (the cut vertex there is computed from other ends, in whatever order it clips).
    let others: Vec<Vec<Cut>> = (0..corners.len())
        .map(|t| other_cuts(case, t, &corners[t]))
        .collect();
    let near_a_cut = |x: u32, y: u32| {
        let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        shapes.iter().zip(&others).any(|(shape, others)| {
            let Some((outline, cut)) = shape else {
                return false;
            };
            outline.signed_px(cx, cy) > -margin
                && std::iter::once(cut)
                    .chain(others)
                    .any(|c| c.signed_px(cx, cy).abs() <= margin)
        })
    };
    let both: Vec<&Fragment> = drawn.with.iter().chain(&drawn.negated).collect();
    let mut got = cell_counts(case, both.iter().copied());
    // A triangle where d is 0 at every corner is inside both half-spaces (0 is kept): both
    // draws cover it whole, nothing cuts it.
    let zero: Vec<bool> = corners
        .iter()
        .map(|c| clip_at(case, c, 0).iter().all(|&d| d == 0.0))
        .collect();
    let twice = drawn
        .without
        .iter()
        .filter(|f| zero.get(f.primitive as usize).copied().unwrap_or(false));
    let want: Vec<u32> = cell_counts(case, &drawn.without)
        .iter()
        .zip(cell_counts(case, twice))
        .map(|(once, again)| once + again)
        .collect();
    // A sample where d is 0 is inside both half-spaces (0 is kept): a rasterizer testing each
    // sample's distance, as D3D11.3 words it, draws it twice, one that cuts the polygon once.
    // It is 0 on the line of the cut, and on an edge whose two corners have d = 0, which the
    // implementation snaps: within the band of that edge.
    let zero_edges: Vec<Vec<[[f64; 2]; 2]>> = corners
        .iter()
        .enumerate()
        .map(|(t, c)| zero_edges(case, t, c))
        .collect();
    let sample_at = sample_positions(r, case);
    for y in 0..h {
        for x in 0..w {
            for (k, &[sx, sy]) in sample_at.iter().enumerate() {
                let (px, py) = (f64::from(x) + sx, f64::from(y) + sy);
                let twice = shapes.iter().zip(&zero_edges).any(|(shape, edges)| {
                    let Some((outline, cut)) = shape else {
                        return false;
                    };
                    outline.signed_px(px, py) > -margin
                        && (cut.signed_px(px, py).abs() < ZERO_LINE_PX
                            || edges
                                .iter()
                                .any(|&e| line_distance(e, [px, py]) <= band(&profile)))
                });
                let i = cell(case, x, y, k as u8);
                if twice && got[i] == want[i] + 1 {
                    got[i] = want[i];
                }
            }
        }
    }
    if away {
        for y in 0..h {
            for x in 0..w {
                if near_a_cut(x, y) {
                    for k in 0..case.samples {
                        let i = cell(case, x, y, k);
                        got[i] = want[i];
                    }
                }
            }
        }
    }
    if got != want {
        let counts = difference_counts(&got, &want);
        let where_ = if away { " away from the cuts" } else { "" };
        let mut violation = Violation::new(format!(
            "the draws by clip distance d and by −d together cover {} less and {} more than the draw without d{where_}: each sample it covers must be covered once between them (twice where d is 0 at every corner of its triangle)",
            plural(counts.missing, "sample"),
            plural(counts.unexpected, "sample"),
        ));
        violation.counts = Some(Box::new(counts));
        violation.picture = Some(Box::new(difference_picture(case, &got, &want, Vec::new())));
        return Err(violation);
    }
    check_sides(case, &drawn, &shapes, &others, margin)
}

/// Inside a triangle no depth plane cuts and away from its cuts, the draw by `d` covers what the
/// draw without `d` does on the positive side and nothing on the negative, the draw by `−d`
/// the other way round.
fn check_sides(
    case: &PrimitiveScene,
    drawn: &Complement,
    shapes: &[Option<(Outline, Cut)>],
    others: &[Vec<Cut>],
    margin: f64,
) -> Result<(), Violation> {
    let (w, h) = (case.scene.width, case.scene.height);
    for (t, shape) in shapes.iter().enumerate() {
        let Some((outline, cut)) = shape else {
            continue;
        };
        // The outline is the triangle's only where no depth plane cuts it.
        if case
            .scene
            .positions_of(t)
            .iter()
            .any(|p| !(0.0..=p[3]).contains(&p[2]))
        {
            continue;
        }
        let without = counts(case, &drawn.without, Some(t as u32));
        for (side, frags) in [(1.0, &drawn.with), (-1.0, &drawn.negated)] {
            let got = counts(case, frags, Some(t as u32));
            let mut expected = vec![Expect::ZeroOrOne; cells(case)];
            for y in 0..h {
                for x in 0..w {
                    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let near_another = others[t].iter().any(|c| c.signed_px(cx, cy).abs() <= margin);
                    if outline.signed_px(cx, cy) <= margin || near_another {
                        continue;
                    }
                    let c = side * cut.signed_px(cx, cy);
                    for k in 0..case.samples {
                        let i = cell(case, x, y, k);
                        expected[i] = match (c > margin, c < -margin, without[i]) {
                            (true, _, 0) | (_, true, _) => Expect::Zero,
                            (true, _, _) => Expect::One,
                            _ => Expect::ZeroOrOne,
                        };
                    }
                }
            }
            let name = if side > 0.0 { "d" } else { "−d" };
            compare_samples(
                case,
                &got,
                &expected,
                &format!("triangle {t} drawn by {name} only where {name} is positive"),
            )?;
        }
    }
    Ok(())
}

/// Points with a negative clip distance are gone, the rest drawn as without; segments draw
/// nothing clearly beyond a cut, and as without where nothing cuts them.
pub fn check_lines_points(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let cut = sample_fragments(r, case)?;
    let whole = sample_fragments(r, &without_distances(case))?;
    let margin = band(&profile) + SAMPLE_REACH_PX;
    let (w, h) = (case.scene.width, case.scene.height);
    let is_point = case.topology == Topology::PointList;
    for (p, corners) in primitive_corners(case).iter().enumerate() {
        let zero_ends: Vec<usize> = (0..corners.len())
            .filter(|&k| case.scene.distances.clip_of(corners[k]).contains(&0.0))
            .collect();
        if uncut(case, corners) && (is_point || zero_ends.is_empty()) {
            compare_uncut(case, &cut, &whole, p, if is_point { "point" } else { "segment" })?;
            continue;
        }
        if uncut(case, corners) {
            // A distance 0 at an end interpolates to 0, give or take rounding, near it (all
            // along, where it is 0 at both): there a sample may go either way.
            check_zero_ends(case, &cut, &whole, p, corners, &zero_ends, margin)?;
            continue;
        }
        let mine: Vec<&Fragment> = cut.iter().filter(|f| f.primitive as usize == p).collect();
        let Some(first) = mine.first() else {
            continue;
        };
        if is_point {
            return Err(Violation::at(
                (first.x, first.y),
                format!(
                    "point {p} has a negative clip distance {:?}, yet covers {} (the first at ({}, {}))",
                    case.scene.distances.clip_of(corners[0]),
                    plural(mine.len(), "sample"),
                    first.x,
                    first.y
                ),
            ));
        }
        let ends = [0, 1].map(|k| case.scene.positions[corners[k] as usize].map(f64::from));
        if !ends.iter().all(|e| e[3] > 0.0) {
            continue;
        }
        let [a, b] = ends.map(|e| project(w, h, e));
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        for j in 0..case.scene.distances.clip {
            let d = clip_at(case, corners, j);
            let beyond = |f: &&&Fragment| match segment_cut(ends, [d[0], d[1]]) {
                Err(kept) => !kept,
                Ok(_) if length == 0.0 => false,
                Ok((at, kept_before)) => {
                    let (cx, cy) = (f64::from(f.x) + 0.5, f64::from(f.y) + 0.5);
                    let t = ((cx - a[0]) * (b[0] - a[0]) + (cy - a[1]) * (b[1] - a[1])) / (length * length);
                    let past = (t - at) * length;
                    if kept_before {
                        past > margin
                    } else {
                        -past > margin
                    }
                }
            };
            if let Some(f) = mine.iter().find(beyond) {
                return Err(Violation::at(
                    (f.x, f.y),
                    format!(
                        "segment {p} covers ({}, {}) sample {}, where its clip distance {j} (from {} to {} along it) is negative beyond the tolerance band",
                        f.x, f.y, f.sample, d[0], d[1]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Segment `p`, no clip distance negative at its ends but some 0 at `zero_ends`: drawn where it
/// is drawn without distances, and there everywhere farther than `margin` from such an end
/// (nothing required where a distance is 0 at both ends).
fn check_zero_ends(
    case: &PrimitiveScene,
    cut: &[Fragment],
    whole: &[Fragment],
    p: usize,
    corners: &[u32],
    zero_ends: &[usize],
    margin: f64,
) -> Result<(), Violation> {
    let (w, h) = (case.scene.width, case.scene.height);
    let d = &case.scene.distances;
    let everywhere = (0..d.clip).any(|j| corners.iter().all(|&v| d.clip_of(v)[j] == 0.0));
    let ends: Vec<[f64; 2]> = zero_ends
        .iter()
        .map(|&k| project(w, h, case.scene.positions[corners[k] as usize].map(f64::from)))
        .collect();
    let without = counts(case, whole, Some(p as u32));
    let mut expected = vec![Expect::Zero; cells(case)];
    for y in 0..h {
        for x in 0..w {
            let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            let near = everywhere || ends.iter().any(|e| (e[0] - cx).hypot(e[1] - cy) <= margin);
            for k in 0..case.samples {
                let i = cell(case, x, y, k);
                expected[i] = match without[i] {
                    0 => Expect::Zero,
                    _ if near => Expect::ZeroOrOne,
                    _ => Expect::One,
                };
            }
        }
    }
    compare_samples(
        case,
        &counts(case, cut, Some(p as u32)),
        &expected,
        &format!(
            "segment {p}, no clip distance negative at an end, covering what it covers without them (but near an end where a distance is 0, either way)"
        ),
    )
}

/// A primitive every vertex of which is negative in one cull distance draws nothing; every
/// other draws as it does without cull distances.
pub fn check_culls(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let got = sample_fragments(r, case)?;
    let whole = sample_fragments(r, &without_distances(case))?;
    let d = &case.scene.distances;
    let culled: Vec<bool> = primitive_corners(case)
        .iter()
        .map(|corners| (0..d.cull).any(|j| corners.iter().all(|&v| d.cull_of(v)[j] < 0.0)))
        .collect();
    let kept = |f: &&Fragment| !culled.get(f.primitive as usize).copied().unwrap_or(false);
    let want: Vec<Fragment> = whole.iter().filter(kept).copied().collect();
    if keys(&got) == keys(&want) {
        return Ok(());
    }
    let wrong = (0..culled.len())
        .find(|&p| of_primitive(&got, p) != of_primitive(&want, p))
        .unwrap_or(0);
    let corners = &primitive_corners(case)[wrong];
    let values: Vec<&[f32]> = corners.iter().map(|&v| d.cull_of(v)).collect();
    let message = if culled[wrong] {
        format!(
            "primitive {wrong} is drawn, though every vertex is negative in one cull distance (its vertices' cull distances: {values:?})"
        )
    } else {
        format!(
            "primitive {wrong} draws other fragments than without cull distances, though no cull distance is negative at all its vertices ({values:?})"
        )
    };
    let (g, w) = (cell_counts(case, &got), cell_counts(case, &want));
    let mut violation = Violation::new(message);
    violation.counts = Some(Box::new(difference_counts(&g, &w)));
    violation.picture = Some(Box::new(difference_picture(case, &g, &w, Vec::new())));
    Err(violation)
}
