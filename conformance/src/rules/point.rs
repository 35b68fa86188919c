//! Points of size one: the pixel holding the point, exact ties on pixel edges, and depth.

use refrast::{PointClipping, Profile, Rasterizer, Spec};

use super::common::precision;
use super::level::Level;
use super::samples::{
    cell, compare_samples, counts, expect_covered, grid, point_bits, positions, sample_fragments,
};
use super::viewport_depth::varied_depth;
use super::{Family, Rule, needs};
use crate::oracle::facing::snap_candidates;
use crate::oracle::raster::{Point, clamp_depth, outside_depth_planes, project, window_depth};
use crate::runner::{property, property_for};
use crate::scene::PrimitiveScene;
use crate::strategy::primitive as points;
use crate::violation::{Expect, Findings, Violation, plural};

/// The implementation draws points.
const POINTS: super::Need = needs(|p| p.points, "no points");
/// Points on a snapping grid with a tie rule: their coverage has one exact answer.
const EXACT_POINTS: super::Need = needs(
    |p| p.points && point_bits(p).is_some() && p.fill.is_some(),
    "no points on a snapping grid with a tie rule",
);

/// Which pixel owns a point on a pixel's edge is a refrast convention.
macro_rules! point_ties {
    () => {
        "Vulkan (Basic Point Rasterization) covers the samples inside the point's square but, like OpenGL 4.6 §14.4, names no tie rule for a sample on its edge (a point on a pixel edge puts two centres on its boundary), and D3D11.3 draws a point as a quad under the triangle rules: only the pixel holding the point, away from pixel edges, is required"
    };
}

/// A point drawn pop-free breaks Vulkan's text but not its conformance tests.
macro_rules! pop_free {
    () => {
        "Vulkan's Primitive Clipping discards a point outside the view volume under VK_POINT_CLIPPING_BEHAVIOR_ALL_CLIP_PLANES, but its conformance tests accept one drawn pop-free (the samples its square reaches inside the viewport): dEQP-VK.clipping.clip_volume.clipped.large_points passes when every point is drawn (the CTS change \"allow pop-free clipping\", 2017) and no CTS test checks size-1 points there; lavapipe, SwiftShader and NVIDIA's driver all draw them. Required: what the CTS checks; beyond it: the text's discard"
    };
}

/// Which pixel owns a point on a pixel's edge is a refrast convention.
const POINT_TIES: &str = point_ties!();
/// Pop-free points are beyond Vulkan's conformance tests, not a failure of them.
pub(super) const POP_FREE: &str = pop_free!();
/// Under Vulkan, both.
const POINT_TIES_AND_POP_FREE: &str = concat!(point_ties!(), "; and ", pop_free!());

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::exact(Family::Point, "point.square.exact")
            .sentence("A point inside the view volume covers the samples its one-pixel square covers under the fill convention; a point outside it covers none.")
            .source("Vulkan 1.4, Basic Point Rasterization and Primitive Clipping (under VK_POINT_CLIPPING_BEHAVIOR_ALL_CLIP_PLANES, a point outside the view volume is discarded); D3D11.3 §3.4.6, §15.14.2")
            .cases(1500)
            .needs(EXACT_POINTS)
            .every_spec(Level::Partly {
                part: |r, cfg| property(r, cfg, points::points(), check_pixel_holding),
                note: POINT_TIES,
            })
            .vulkan(Level::Partly {
                part: |r, cfg| property(r, cfg, points::points(), check_pixel_holding_as_cts),
                note: POINT_TIES_AND_POP_FREE,
            })
            .run(|r, cfg| property(r, cfg, points::points(), check_square_exact)),
        Rule::invariant(Family::Point, "point.pixel.holding")
            .sentence("A point covers the pixel that holds it and no other, points within the tolerance band of a pixel edge aside; one outside the viewport covers nothing (under OpenGL and D3D11.3, at most the samples its square reaches inside; declared pop-free, and under OpenGL ES, exactly those).")
            .source("Vulkan 1.4, Basic Point Rasterization; seed 002 (a point is the pixel it falls in)")
            .cases(1500)
            .needs(POINTS)
            .vulkan(Level::Partly {
                part: |r, cfg| property(r, cfg, points::points(), check_pixel_holding_as_cts),
                note: POP_FREE,
            })
            .run(|r, cfg| property(r, cfg, points::points(), check_pixel_holding)),
        Rule::invariant(Family::Point, "point.depth.vertex")
            .sentence("A point's fragments carry its vertex's window depth (through the viewport's depth range, where declared; clamped to it with depth clipping off, where declared) and barycentrics (1, 0, 0), within the claimed precision.")
            .source("Vulkan 1.4, Basic Point Rasterization (\"all fragments produced in rasterizing a point are assigned the same associated data\")")
            .cases(800)
            .needs(POINTS)
            .run(|r, cfg| property_for(r, cfg, |p| varied_depth(p, points::points()), check_depth)),
    ]
}

/// Point `i`'s clip-space position.
fn point(case: &PrimitiveScene, i: usize) -> [f32; 4] {
    case.scene.positions[case.indices[i] as usize]
}

/// What a point whose centre lies outside the viewport in x or y must draw of its square.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Outside {
    /// Nothing: clipping discards it.
    Nothing,
    /// The samples its square reaches inside the viewport ("pop-free").
    Square,
    /// Either: the specification leaves it open.
    Either,
}

/// What a point outside the viewport in x/y must draw, for an implementation that claims
/// `spec` and declares `clipping`; `cts` reads Vulkan as its conformance tests do (either).
///
/// Declared `UserClipPlanesOnly`, and under OpenGL ES 3.2 (§12.5: a point is discarded only
/// outside the near and far planes), it is kept. OpenGL 4.6 §13.7 lets an implementation keep
/// it and D3D11.3 draws points as clipped quads (§3.4.6): either. Vulkan's text discards it
/// under `ALL_CLIP_PLANES` (Primitive Clipping), as refrast does, but the CTS's own test of it
/// (dEQP-VK.clipping.clip_volume.clipped.large_points) accepts an image with every point drawn
/// ("allow pop-free clipping", 2017), and every Vulkan implementation measured draws it.
fn outside_xy(spec: Spec, clipping: PointClipping, cts: bool) -> Outside {
    match (clipping, spec) {
        (PointClipping::UserClipPlanesOnly, _) | (_, Spec::OpenGlEs) => Outside::Square,
        (_, Spec::OpenGl | Spec::D3d11) => Outside::Either,
        (_, Spec::Vulkan) if cts => Outside::Either,
        _ => Outside::Nothing,
    }
}

/// Whether point `i` lies inside the view volume, decided in clip space as clipping is, before
/// the viewport transform and snapping: a point a hair below the viewport is discarded even
/// where a coarse grid snaps it onto the viewport's edge. With `xy` false, only the near and
/// far planes count (a point kept pop-free).
fn in_view(case: &PrimitiveScene, i: usize, xy: bool) -> bool {
    let [x, y, z, w] = point(case, i).map(f64::from);
    let state = &case.scene.state;
    w > 0.0 && (!xy || ((-w..=w).contains(&x) && (-w..=w).contains(&y))) && !outside_depth_planes(state, z, w)
}

/// Whether clipping must discard point `i` for being behind the eye or beyond a depth plane:
/// `Some(true)` it must, `Some(false)` it lies within them (the viewport's sides are
/// [`outside_xy`]'s), `None` either way.
///
/// Either way at `w = 0` exactly (no raster position; inside the view volume only at its apex),
/// and under declared user-planes-only clipping, which discards a point only at a user clip
/// plane (Vulkan, `VK_POINT_CLIPPING_BEHAVIOR_USER_CLIP_PLANES_ONLY`). Behind the eye (`w < 0`)
/// no point lies inside the clip volume (`−w ≤ x ≤ w` has no solution), so every specification
/// discards it, but where depth clipping is off and the specification may keep a point beyond
/// the viewport's sides, which then holds it.
fn depth_clipped(case: &PrimitiveScene, i: usize, profile: &Profile) -> Option<bool> {
    let [_, _, z, w] = point(case, i).map(f64::from);
    let state = &case.scene.state;
    if w == 0.0 || profile.point_clipping == PointClipping::UserClipPlanesOnly {
        return (w > 0.0 && !outside_depth_planes(state, z, w)).then_some(false);
    }
    if outside_depth_planes(state, z, w) {
        return Some(true);
    }
    if w > 0.0 {
        return Some(false);
    }
    let kept_beyond_sides = outside_xy(profile.spec, profile.point_clipping, true) != Outside::Nothing;
    (state.clip_near || !kept_beyond_sides).then_some(true)
}

/// Each point's samples equal the square oracle's on its snapped position.
pub fn check_square_exact(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let (Some(bits), Some(fill)) = (point_bits(&profile), profile.fill) else {
        return Ok(());
    };
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let g = grid(case, bits, &positions);
    // The grid points the profile may snap each point to (one, unless it may round either way).
    let on_ends = Profile {
        snapping: refrast::Snapping::Grid(bits),
        ..profile.clone()
    };
    for i in 0..case.indices.len() {
        let got = counts(case, &frags, Some(i as u32));
        match depth_clipped(case, i, &profile) {
            None => continue,
            Some(true) => {
                let what = format!("nothing for point {i}, which clipping discards");
                compare_samples(case, &got, &expect_covered(case, &[]), &what)?;
                continue;
            }
            Some(false) => {}
        }
        let Some(candidates) = snap_candidates(point(case, i), case.scene.width, case.scene.height, &on_ends)
        else {
            continue;
        };
        let what = format!("the point square oracle for point {i}");
        let xy = outside_xy(profile.spec, profile.point_clipping, false) != Outside::Square;
        let judged = |p: Point| {
            let covered = if in_view(case, i, xy) {
                g.point(p, fill)
            } else {
                Vec::new()
            };
            compare_samples(case, &got, &expect_covered(case, &covered), &what)
        };
        let first = judged(candidates[0]);
        if first.is_err() && candidates[1..].iter().any(|&p| judged(p).is_ok()) {
            continue;
        }
        first?;
    }
    Ok(())
}

/// Each point covers the samples of the pixel holding it, the band around pixel edges aside;
/// a point beyond the viewport (by more than the band) covers what its declared point clipping
/// and claimed specification say (`outside_xy`).
pub fn check_pixel_holding(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    pixel_holding(r, case, false)
}

/// [`check_pixel_holding`] as Vulkan's conformance tests read point clipping: a point outside
/// the viewport may draw the samples its square reaches inside.
pub fn check_pixel_holding_as_cts(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    pixel_holding(r, case, true)
}

fn pixel_holding(r: &mut dyn Rasterizer, case: &PrimitiveScene, cts: bool) -> Result<(), Violation> {
    // A point snapped to a coarser grid than the triangles' (softpipe's are, its triangles
    // not) moves up to half a step of it, which the triangles' band may not cover.
    let profile = r.profile();
    let band = match point_bits(&profile) {
        Some(bits) => profile.band_px().max((-f64::from(bits) - 1.0).exp2()),
        None => profile.band_px(),
    };
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let (w, h) = (case.scene.width, case.scene.height);
    for i in 0..case.indices.len() {
        let p = point(case, i);
        match depth_clipped(case, i, &profile) {
            None => continue,
            Some(true) => {
                let what = format!("nothing for point {i}, which clipping discards");
                let got = counts(case, &frags, Some(i as u32));
                compare_samples(case, &got, &expect_covered(case, &[]), &what)?;
                continue;
            }
            Some(false) => {}
        }
        let [px, py] = project(w, h, p.map(f64::from));
        let outside = px < -band || py < -band || px > f64::from(w) + band || py > f64::from(h) + band;
        let drawn = if outside {
            outside_xy(profile.spec, profile.point_clipping, cts)
        } else {
            Outside::Square
        };
        // Within the band of the viewport's side, clipping may keep it or not, either way.
        let near_border = drawn != Outside::Square
            || [px, py, f64::from(w) - px, f64::from(h) - py]
                .iter()
                .any(|d| d.abs() <= band);
        let mut expected = vec![Expect::Zero; super::samples::cells(case)];
        if drawn != Outside::Nothing {
            for y in 0..h {
                for x in 0..w {
                    for (k, &[u, v]) in positions.iter().enumerate() {
                        let s = [
                            f64::from(x) + f64::from(u) / 16.0,
                            f64::from(y) + f64::from(v) / 16.0,
                        ];
                        let d = (s[0] - px).abs().max((s[1] - py).abs());
                        expected[cell(case, x, y, k as u8)] = if near_border && d < 0.5 + band {
                            Expect::ZeroOrOne
                        } else if d < 0.5 - band {
                            Expect::One
                        } else if d > 0.5 + band {
                            Expect::Zero
                        } else {
                            Expect::ZeroOrOne
                        };
                    }
                }
            }
        }
        let what = format!("the pixel holding point {i} at ({px}, {py})");
        compare_samples(case, &counts(case, &frags, Some(i as u32)), &expected, &what)?;
    }
    Ok(())
}

/// Every fragment of a point has its vertex's window depth and barycentrics `(1, 0, 0)`.
pub fn check_depth(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let frags = sample_fragments(r, case)?;
    let p = precision(&profile);
    let mut found = Findings::new();
    for f in &frags {
        let v = point(case, f.primitive as usize);
        let want = clamp_depth(
            &case.scene.state,
            window_depth(&case.scene.state, f64::from(v[2]) / f64::from(v[3])),
        );
        let bary_off = profile.features.perspective_barycentrics
            && (f64::from(f.barycentric[0]) - 1.0)
                .abs()
                .max(f64::from(f.barycentric[1]).abs())
                .max(f64::from(f.barycentric[2]).abs())
                > p;
        if (f64::from(f.depth) - want).abs() > 2.0 * p || bary_off {
            found.add((f.x, f.y), || {
                format!(
                    "({}, {}) sample {} of point {}: depth {}, barycentrics {:?}; expected depth {want}, (1, 0, 0)",
                    f.x, f.y, f.sample, f.primitive, f.depth, f.barycentric
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "{} of points carry other values than their vertex's",
            plural(n, "fragment")
        )
    })
}
