//! Barycentrics: they sum to one, stay in range, are one at their vertex, and equal the ray cast.

use refrast::Rasterizer;

use super::common::{fragments, precision, raycast_fragments, slack_note, snapped_triangle};
use super::{Family, PERSPECTIVE_BARYCENTRICS, Rule, SCREEN_BARYCENTRICS};
use crate::oracle::outline::{distance_to_outline, visible_outline};
use crate::oracle::raster::{project, sample_centre, unclipped};
use crate::runner::property;
use crate::scene::Scene;
use crate::strategy;
use crate::violation::{Findings, Violation, plural};

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Bary, "bary.sum.one")
            .sentence("Every fragment's barycentrics sum to 1 within three times the claimed precision (2^-18 for the reference).")
            .source("Vulkan 1.4 §28.7.5 (a + b + c = 1)")
            .cases(5000)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .run(|r, cfg| property(r, cfg, strategy::float_scene(), check_sum_one)),
        Rule::invariant(Family::Bary, "bary.range.unit")
            .sentence("Barycentrics of samples outside the tolerance band lie in [0, 1] within the claimed precision.")
            .source("Vulkan 1.4 §28.7.5 (clipped polygons: convex combinations)")
            .cases(5000)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .run(|r, cfg| property(r, cfg, strategy::crossing_scene(), check_in_range)),
        Rule::invariant(Family::Bary, "bary.vertex.one")
            .sentence("A covered sample exactly on a vertex has weight 1 for that vertex and 0 for the others.")
            .source("Vulkan 1.4 §28.7.5 (aᵢ = 1 at vertex i)")
            .cases(10000)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .run(|r, cfg| property(r, cfg, strategy::perspective_inside_scene(), check_vertex_one)),
        Rule::invariant(Family::Bary, "bary.perspective.matches-raycast")
            .sentence("Perspective-correct barycentrics equal those of the ray-cast hit within the claimed precision (2^-18 for the reference); on a clipped triangle also within how far they move when the sample moves one grid step (its cut vertices are snapped).")
            .source("seed 002 (q/z interpolation); Vulkan 1.4 §28.7.5")
            .cases(5000)
            .needs(PERSPECTIVE_BARYCENTRICS)
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
            .run(|r, cfg| property(r, cfg, strategy::inside_or_crossing_scene(), check_reconstructs)),
        Rule::invariant(Family::Bary, "bary.equal-w.affine")
            .sentence("With equal w at every vertex, perspective-correct and screen-space barycentrics agree within the claimed precision, on clipped triangles (half the cases) too.")
            .source("conformance-anchors (d5: perspective equals linear when all w are equal); Vulkan 1.4, Clipping Shader Outputs")
            .cases(5000)
            .needs(SCREEN_BARYCENTRICS)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .run(|r, cfg| property(r, cfg, equal_w_scene(), check_equal_w)),
    ]
}

/// Grid scenes with one `w` for all three vertices.
fn equal_w_scene() -> impl proptest::strategy::Strategy<Value = Scene> {
    use proptest::prelude::*;
    let inside = (strategy::inside_scene(), 0.1f32..4.0).prop_map(|(mut s, w)| {
        for p in &mut s.positions {
            *p = p.map(|c| c * w);
        }
        s
    });
    prop_oneof![inside, strategy::equal_w_crossing_scene()]
}

/// Every fragment's barycentrics sum to 1 within three times [`precision`].
pub fn check_sum_one(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    // Each within the claimed precision of its exact value, which sum to 1.
    let eps = 3.0 * precision(&r.profile()) as f32;
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        let sum: f32 = f.barycentric.iter().sum();
        if (sum - 1.0).abs() > eps {
            found.add((f.x, f.y), || {
                format!("{:?} has {:?}, summing to {sum}", (f.x, f.y), f.barycentric)
            });
        }
    }
    found.verdict(|n| {
        format!(
            "barycentrics not summing to 1 within three times the claimed precision at {}",
            plural(n, "fragment")
        )
    })
}

/// Barycentrics of samples outside the band lie in [0, 1] within [`precision`].
pub fn check_in_range(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let eps = precision(&r.profile()) as f32;
    let band = r.profile().band_px();
    let outline = visible_outline(&scene.positions_of(0), scene.width, scene.height, &scene.state);
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        let s = sample_centre(f.x, f.y);
        if distance_to_outline(&outline, s, |_, _| true) < band {
            continue;
        }
        if let Some(b) = f.barycentric.iter().find(|&&b| !(-eps..=1.0 + eps).contains(&b)) {
            found.add((f.x, f.y), || {
                format!("{:?} has {b} in {:?}", (f.x, f.y), f.barycentric)
            });
        }
    }
    found.verdict(|n| {
        format!(
            "a barycentric outside [0, 1] at {} away from every edge",
            plural(n, "fragment")
        )
    })
}

/// A covered sample on a vertex has weight 1 there and 0 elsewhere.
pub fn check_vertex_one(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let eps = precision(&r.profile()) as f32;
    let tri = scene.positions_of(0);
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        let s = sample_centre(f.x, f.y);
        for (k, v) in tri.iter().enumerate() {
            let p = project(scene.width, scene.height, *v);
            // Grid vertices are exact to f32 rounding of x·w: well within 1e-3 px of a sample.
            if (p[0] - s[0]).abs() < 1e-3 && (p[1] - s[1]).abs() < 1e-3 {
                let b = f.barycentric;
                let ok = (0..3).all(|i| (b[i] - if i == k { 1.0 } else { 0.0 }).abs() <= eps);
                if !ok {
                    found.add((f.x, f.y), || {
                        format!("{:?} lies on vertex {k} but has {b:?}", (f.x, f.y))
                    });
                }
            }
        }
    }
    found.verdict(|n| format!("a vertex not weighted 1 at {} on it", plural(n, "sample")))
}

/// Perspective-correct barycentrics equal the ray cast's: of the snapped triangle, or for a
/// clipped one within its spread over a grid step ([`raycast_fragments`]).
pub fn check_matches_raycast(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let eps = precision(&r.profile());
    let mut found = Findings::new();
    for (f, want) in raycast_fragments(r, scene)? {
        let off = (0..3)
            .map(|k| (f64::from(f.barycentric[k]) - want.barycentric[k]).abs())
            .fold(0.0, f64::max);
        if off > eps + want.barycentric_slack {
            found.add((f.x, f.y), || {
                format!(
                    "{:?} has {:?}, the ray cast {:?} (off by {off:.3e}{})",
                    (f.x, f.y),
                    f.barycentric,
                    want.barycentric,
                    slack_note(want.barycentric_slack)
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

/// Screen-space barycentrics weight the snapped vertices to the sample position; on a clipped
/// triangle, the unsnapped ones to within one grid step per axis of it.
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
    let (tri, slack) = if unclipped(&exact, scene.state.depth_range, scene.state.clip_far) {
        let Some(tri) = snapped_triangle(scene, 0, profile.snapping) else {
            return Ok(());
        };
        (tri, 0.0)
    } else if exact.iter().all(|v| v[3] > 0.0) {
        (
            scene.positions_of(0),
            std::f64::consts::SQRT_2 * profile.snapping.unit_px(),
        )
    } else {
        return Ok(());
    };
    let p = tri.map(|v| project(scene.width, scene.height, v));
    let extent = p.iter().flatten().fold(1.0f64, |m, c| m.max(c.abs()));
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        let Some(b) = f.screen_barycentric else {
            return Err(Violation::at(
                (f.x, f.y),
                "the profile declares screen-space barycentrics, but a fragment has none",
            ));
        };
        let b = b.map(f64::from);
        let at = [0, 1].map(|c| b[0] * p[0][c] + b[1] * p[1][c] + b[2] * p[2][c]);
        let s = sample_centre(f.x, f.y);
        // Weights within eps each move the point by at most 3·eps·extent; NaN weights fail.
        let off = (at[0] - s[0]).hypot(at[1] - s[1]);
        if off.is_nan() || off > 3.0 * eps * extent + slack {
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
