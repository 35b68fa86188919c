//! Barycentrics: they sum to one, stay in range, are one at their vertex, and equal the ray cast.

use refrast::{Fragment, Rasterizer};

use super::cast::{Expected, raycast_fragments, slack_note, snapped_triangles};
use super::common::{Values, check_values_finite, fragments, precision, reaches_far};
use super::level::{FAR_VALUES, Level, NO_BARYCENTRICS};
use super::weights::{Weights, declared, exact_weights, judge_weights, weights};
use super::{
    ANY_BARYCENTRICS, Family, PERSPECTIVE_BARYCENTRICS, Rule, SCREEN_BARYCENTRICS, VERTEX_ON_SAMPLE,
};
use crate::oracle::facing::snap_candidates;
use crate::oracle::outline::{distance_to_outline, visible_outline};
use crate::oracle::raster::{project, sample_centre, unclipped};
use crate::runner::property;
use crate::scene::Scene;
use crate::strategy;
use crate::violation::{Findings, Violation, plural};

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Bary, "bary.sum.one")
            .sentence("Every fragment's barycentrics (perspective-correct and screen-space, whichever the profile declares) sum to 1 within three times the claimed precision (2^-18 for the reference).")
            .source("Vulkan 1.4, Basic Polygon Rasterization (a + b + c = 1)")
            .cases(5000)
            .needs(ANY_BARYCENTRICS)
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| property(r, cfg, strategy::float_scene(), check_sum_one)),
        Rule::invariant(Family::Bary, "bary.range.unit")
            .sentence("Barycentrics (of either declared kind) of samples outside the tolerance band lie in [0, 1] within the claimed precision.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (clipped polygons: convex combinations)")
            .cases(5000)
            .needs(ANY_BARYCENTRICS)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::crossing_scene(), check_in_range_where_bounded),
                note: FAR_VALUES,
            })
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| property(r, cfg, strategy::crossing_scene(), check_in_range)),
        Rule::invariant(Family::Bary, "bary.vertex.one")
            .sentence("A covered sample exactly on a snapped vertex has weight 1 for that vertex and 0 for the others (in either declared kind of barycentrics); without a grid, a sample within 10^-3 px of a vertex has the exact weights there.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (barycentric coordinates a = A(p p_b p_c)/A(p_a p_b p_c): 1 at p_a, 0 at the others)")
            .cases(10000)
            .needs(ANY_BARYCENTRICS)
            .needs(VERTEX_ON_SAMPLE)
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| property(r, cfg, strategy::perspective_inside_scene(), check_vertex_one)),
        Rule::invariant(Family::Bary, "bary.perspective.matches-raycast")
            .sentence("Perspective-correct barycentrics equal those of the ray-cast hit within the claimed precision (2^-18 for the reference); on a clipped triangle also within how far they move when the sample moves one grid step (its cut vertices are snapped).")
            .source("seed 002 (q/z interpolation); Vulkan 1.4, Basic Polygon Rasterization")
            .cases(5000)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| {
                    property(r, cfg, strategy::inside_or_crossing_scene(), check_matches_raycast_where_bounded)
                },
                note: FAR_VALUES,
            })
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| {
                property(
                    r,
                    cfg,
                    strategy::inside_or_crossing_scene(),
                    check_matches_raycast,
                )
            }),
        Rule::invariant(Family::Bary, "bary.screen.reconstructs-sample")
            .sentence("Screen-space barycentrics weight the projected vertices to the sample position; on a clipped triangle (half the cases) to within one grid step per axis of it, since its cut vertices are snapped.")
            .source("seed 000 (P = W0·V0 + W1·V1 + W2·V2); Vulkan 1.4, Clipping Shader Outputs (NoPerspective outputs at cut vertices vary linearly in framebuffer space)")
            .cases(5000)
            .needs(SCREEN_BARYCENTRICS)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::inside_or_crossing_scene(), check_reconstructs_where_bounded),
                note: FAR_VALUES,
            })
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| property(r, cfg, strategy::inside_or_crossing_scene(), check_reconstructs)),
        Rule::invariant(Family::Bary, "bary.equal-w.affine")
            .sentence("With equal w at every vertex, perspective-correct and screen-space barycentrics agree within the claimed precision, on clipped triangles (half the cases) too.")
            .source("refrast's own property (perspective equals linear when all w are equal); Vulkan 1.4, Clipping Shader Outputs")
            .cases(5000)
            .needs(SCREEN_BARYCENTRICS)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, equal_w_scene(), check_equal_w_where_bounded),
                note: FAR_VALUES,
            })
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| property(r, cfg, equal_w_scene(), check_equal_w)),
    ]
}

/// Grid scenes with one `w` for all three vertices, unclipped or clipped.
fn equal_w_scene() -> impl proptest::strategy::Strategy<Value = Scene> {
    use proptest::prelude::*;
    prop_oneof![equal_w_inside_scene(), strategy::equal_w_crossing_scene()]
}

/// Grid scenes inside the viewport with one `w` for all three vertices.
fn equal_w_inside_scene() -> impl proptest::strategy::Strategy<Value = Scene> {
    use proptest::prelude::*;
    (strategy::inside_scene(), 0.1f32..4.0).prop_map(|(mut s, w)| {
        for p in &mut s.positions {
            *p = p.map(|c| c * w);
        }
        s
    })
}

/// Every fragment's barycentrics of each declared kind sum to 1 within three times
/// [`precision`].
pub fn check_sum_one(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    // Each within the claimed precision of its exact value, which sum to 1.
    let eps = 3.0 * precision(&r.profile()) as f32;
    judge_weights(
        r,
        scene,
        |_, kind, b| {
            let sum: f32 = b.iter().sum();
            ((sum - 1.0).abs() > eps || sum.is_nan())
                .then(|| format!("{} {b:?}, summing to {sum}", kind.name()))
        },
        |n| {
            format!(
                "barycentrics not summing to 1 within three times the claimed precision at {}",
                plural(n, "fragment")
            )
        },
    )
}

/// Barycentrics of each declared kind of samples outside the band lie in [0, 1] within
/// [`precision`]; those within it, only where they must be finite.
pub fn check_in_range(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let eps = precision(&profile) as f32;
    let band = profile.band_px();
    let outline = visible_outline(&scene.positions_of(0), scene.width, scene.height, &scene.state);
    judge_weights(
        r,
        scene,
        |f, kind, b| {
            if distance_to_outline(&outline, sample_centre(f.x, f.y), |_, _| true) < band {
                return None;
            }
            b.iter()
                .find(|&&c| !(-eps..=1.0 + eps).contains(&c))
                .map(|c| format!("{c} in {} {b:?}", kind.name()))
        },
        |n| {
            format!(
                "a barycentric outside [0, 1] at {} away from every edge",
                plural(n, "fragment")
            )
        },
    )
}

/// A covered sample on a vertex has weight 1 there and 0 elsewhere, in each declared kind.
pub fn check_vertex_one(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let eps = precision(&profile);
    let tri = scene.positions_of(0);
    let corners = scene.corners(0);
    let projected = tri.map(|v| project(scene.width, scene.height, v));
    // On a grid, a vertex is on a sample exactly as the profile places it: where every way the
    // profile lets it snap puts it there (snapping within one step may move one a hair off the
    // sample to the next grid point); its weights there are (1, 0, 0) exactly, and never two
    // vertices are on one sample (they would make a triangle with no area there).
    let on_grid = |k: usize, x: u32, y: u32| match profile.snapping.grid_bits() {
        // A whole-pixel grid has no point on a sample centre (the rule is n/a there).
        Some(0) | None => false,
        Some(bits) => {
            let half = i128::from(1u32 << bits.min(16)) / 2;
            let sample = (i128::from(x) * 2 * half + half, i128::from(y) * 2 * half + half);
            snap_candidates(corners[k], scene.width, scene.height, &profile).is_some_and(|c| c == [sample])
        }
    };
    // Without a grid, a vertex within 1e-3 px of the sample is near enough to judge, against
    // the exact weights at the sample (a vertex 3e-7 px off a sample on a sliver weighs 0.81
    // there, not 1; two vertices may be that near at once).
    let near = |k: usize, x: u32, y: u32| {
        let (p, s) = (projected[k], sample_centre(x, y));
        profile.snapping.grid_bits().is_none() && (p[0] - s[0]).abs() < 1e-3 && (p[1] - s[1]).abs() < 1e-3
    };
    let mut found = Findings::new();
    let frags = fragments(r, scene)?;
    for kind in declared(&profile) {
        for f in &frags {
            let s = sample_centre(f.x, f.y);
            let want = if let Some(k) = (0..3).find(|&k| on_grid(k, f.x, f.y)) {
                if (0..3).filter(|&j| on_grid(j, f.x, f.y)).count() > 1 {
                    continue;
                }
                let mut unit = [0.0; 3];
                unit[k] = 1.0;
                unit
            } else if (0..3).any(|k| near(k, f.x, f.y)) {
                let Some(exact) = exact_weights(projected, tri.map(|v| v[3]), s, kind) else {
                    continue;
                };
                exact
            } else {
                continue;
            };
            // Missing or undefined ones are bary.sum.one's and bary.range.unit's to judge.
            let Weights::Judged(b) = weights(scene, f, kind) else {
                continue;
            };
            if (0..3).any(|i| (f64::from(b[i]) - want[i]).abs() > eps) {
                found.add((f.x, f.y), || {
                    format!(
                        "{:?} lies on a vertex, whose {} weights there are {want:?}, but has {b:?}",
                        (f.x, f.y),
                        kind.name()
                    )
                });
            }
        }
    }
    found.verdict(|n| format!("a vertex not weighted 1 at {} on it", plural(n, "sample")))
}

/// Perspective-correct barycentrics equal the ray cast's: of the snapped triangle, or for a
/// clipped one within its spread over a grid step ([`raycast_fragments`]).
pub fn check_matches_raycast(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let eps = precision(&profile);
    let mut found = Findings::new();
    let cast = raycast_fragments(r, scene)?;
    let off = |f: &Fragment, want: &Expected| {
        (0..3)
            .map(|k| (f64::from(f.barycentric[k]) - want.barycentric[k]).abs())
            .fold(0.0, f64::max)
    };
    for &(f, want) in &cast.pairs {
        let off_by = off(&f, &want);
        if off_by > eps + want.barycentric_slack
            && !cast.another_snap_accepts(&f, |w| off(&f, w) <= eps + w.barycentric_slack)
        {
            let off = off_by;
            found.add((f.x, f.y), || {
                format!(
                    "{:?} has {:?}, the ray cast {:?} (off by {off:.3e}{})",
                    (f.x, f.y),
                    f.barycentric,
                    want.barycentric,
                    slack_note(want.barycentric_slack, &profile)
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "barycentrics off the ray cast's by more than the claimed precision at {}",
            plural(n, "fragment")
        )
    })
}

/// Screen-space barycentrics weight the snapped vertices to the sample position (for some way
/// the profile lets them snap); on a clipped triangle, the unsnapped ones to within one grid
/// step per axis of it.
///
/// Why the step: a rasterizer that clips then snaps reports at sample `s` the weights `μⱼ` of
/// the snapped polygon vertices `p'ⱼ` (`s = Σ μⱼ p'ⱼ`) applied to their exact screen weights,
/// which give back the exact vertices `pⱼ`; so the weights give back `Σ μⱼ pⱼ`, within
/// `max |pⱼ − p'ⱼ|` (one grid step per axis) of `s`. Triangles with a vertex at `w ≤ 0` have no
/// screen shape and are not judged.
pub fn check_reconstructs(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let eps = precision(&profile);
    let exact = scene.corners(0);
    let (tris, slack) = if unclipped(&exact, &scene.state) {
        (snapped_triangles(scene, 0, &profile), 0.0)
    } else if exact.iter().all(|v| v[3] > 0.0) {
        (
            vec![scene.positions_of(0)],
            std::f64::consts::SQRT_2 * profile.snapping.unit_px(),
        )
    } else {
        return Ok(());
    };
    if tris.is_empty() {
        return Ok(());
    }
    let projected: Vec<[[f64; 2]; 3]> = tris
        .iter()
        .map(|tri| tri.map(|v| project(scene.width, scene.height, v)))
        .collect();
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        let Some(b) = f.screen_barycentric else {
            return Err(Violation::at(
                (f.x, f.y),
                "the profile declares screen-space barycentrics, but a fragment has none",
            ));
        };
        let b = b.map(f64::from);
        let s = sample_centre(f.x, f.y);
        // Weights within eps each move the point by at most 3·eps·extent; NaN weights fail.
        let miss = |p: &[[f64; 2]; 3]| {
            let extent = p.iter().flatten().fold(1.0f64, |m, c| m.max(c.abs()));
            let at = [0, 1].map(|c| b[0] * p[0][c] + b[1] * p[1][c] + b[2] * p[2][c]);
            let off = (at[0] - s[0]).hypot(at[1] - s[1]);
            (off.is_nan() || off > 3.0 * eps * extent + slack).then_some((at, off))
        };
        if let Some((at, off)) = miss(&projected[0])
            && projected[1..].iter().all(|p| miss(p).is_some())
        {
            found.add((f.x, f.y), || {
                format!(
                    "{:?}: screen barycentrics {b:?} give {at:?}, {off:.3e} px away",
                    (f.x, f.y)
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "screen barycentrics that do not give back the sample at {}",
            plural(n, "fragment")
        )
    })
}

/// With equal w, perspective-correct and screen-space barycentrics agree.
pub fn check_equal_w(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let eps = precision(&r.profile());
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        let Some(s) = f.screen_barycentric else {
            return Err(Violation::at(
                (f.x, f.y),
                "the profile declares screen-space barycentrics, but a fragment has none",
            ));
        };
        let apart = |k: usize| f64::from((f.barycentric[k] - s[k]).abs());
        if (0..3).any(|k| apart(k).is_nan() || apart(k) > eps) {
            found.add((f.x, f.y), || {
                format!("{:?}: perspective {:?}, screen {s:?}", (f.x, f.y), f.barycentric)
            });
        }
    }
    found.verdict(|n| {
        format!(
            "perspective and screen barycentrics apart, with equal w, at {}",
            plural(n, "fragment")
        )
    })
}

/// Both kinds of barycentrics, not depth.
const BARYCENTRICS: Values = Values {
    depth: false,
    perspective: true,
    screen: true,
};

/// [`check_in_range`] where the triangle stays near the viewport, finite barycentrics elsewhere.
pub fn check_in_range_where_bounded(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    if reaches_far(scene) {
        check_values_finite(r, scene, BARYCENTRICS)
    } else {
        check_in_range(r, scene)
    }
}

/// [`check_matches_raycast`] where the triangle stays near the viewport, finite perspective
/// barycentrics elsewhere.
pub fn check_matches_raycast_where_bounded(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    if reaches_far(scene) {
        let perspective = Values {
            screen: false,
            ..BARYCENTRICS
        };
        check_values_finite(r, scene, perspective)
    } else {
        check_matches_raycast(r, scene)
    }
}

/// [`check_reconstructs`] where the triangle stays near the viewport, finite screen-space
/// barycentrics elsewhere.
pub fn check_reconstructs_where_bounded(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    if reaches_far(scene) {
        let screen = Values {
            perspective: false,
            ..BARYCENTRICS
        };
        check_values_finite(r, scene, screen)
    } else {
        check_reconstructs(r, scene)
    }
}

/// [`check_equal_w`] where the triangle stays near the viewport, finite barycentrics elsewhere.
pub fn check_equal_w_where_bounded(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    if reaches_far(scene) {
        check_values_finite(r, scene, BARYCENTRICS)
    } else {
        check_equal_w(r, scene)
    }
}
