//! Metamorphic relations of vertex and draw order: rotating a triangle's vertices, reversing its
//! winding, drawing its triangles together, alone or in reverse order.

use std::collections::{BTreeSet, HashMap};

use refrast::{CullMode, Fragment, FrontFace, Profile, Rasterizer};

use super::translate;
use crate::oracle::raster;
use crate::rules::EXACT_COVERAGE;
use crate::rules::common::{check_draws_nothing, compare_sets, fragments, precision};
use crate::scene::Scene;
use crate::violation::{Findings, Violation, plural};

/// How a triangle was drawn again: where each weight went, whether its facing flips, in words.
struct Redrawn<'a> {
    /// `map[k]` is where weight k went.
    map: [usize; 3],
    /// Whether the facing flips.
    flip: bool,
    /// What was done, for messages.
    what: &'a str,
}

/// Compares two fragment lists of one triangle drawn two ways (`how`), exactly at edges with
/// `at_edges` where the profile has exact coverage.
fn compare_permuted(
    profile: &Profile,
    scene: &Scene,
    base: &[Fragment],
    other: &[Fragment],
    how: Redrawn<'_>,
    at_edges: bool,
) -> Result<(), Violation> {
    let Redrawn { map, flip, what } = how;
    if at_edges && EXACT_COVERAGE.check(profile).is_ok() {
        // With exact coverage the same edges give the same samples, whatever the vertex order.
        compare_sets(scene, other, base, what)?;
    } else {
        // Without it, a sample within the band of an edge may go either way, and which way may
        // depend on the order the vertices come in; farther in, coverage must not change.
        let covered =
            |frags: &[Fragment]| -> BTreeSet<(u32, u32)> { frags.iter().map(|f| (f.x, f.y)).collect() };
        let (before, after) = (covered(base), covered(other));
        let mut found = Findings::new();
        for &(x, y) in before.symmetric_difference(&after) {
            if !translate::near_edge(
                scene,
                profile.snapping,
                x,
                y,
                profile.band_px() + translate::snap_slack(profile),
            ) {
                let how = if after.contains(&(x, y)) { "gained" } else { "lost" };
                found.add((x, y), || format!("{how} {:?}", (x, y)));
            }
        }
        found.verdict(|n| {
            format!(
                "{what}: coverage changed at {} away from every edge",
                plural(n, "sample")
            )
        })?;
    }
    // A clipped triangle is drawn as a fan that starts at another vertex once rotated, and its
    // new vertices snap differently: only unclipped barycentrics must match. Each draw is within
    // the claimed precision of the exact values, so the two are within twice that of each other.
    // On a triangle too thin for the claimed precision (its area below 2^-precision of its
    // extent squared: softpipe's 1.2e-8 px² across 2.3 px), the weights two vertex orders give
    // may differ by more than their whole range, which no specification bounds ("accurate to
    // about 1 part in 10^5" per operation); there they are not compared.
    let p = scene.corners(0);
    let unclipped = raster::unclipped(&p, &scene.state);
    let weighed = unclipped && profile.features.perspective_barycentrics && resolvable(scene, profile);
    // Fragment pairs by pixel (one triangle covers a pixel once), in row order.
    let by_pixel: HashMap<(u32, u32), &Fragment> = other.iter().map(|f| ((f.x, f.y), f)).collect();
    let mut base_sorted: Vec<&Fragment> = base.iter().collect();
    base_sorted.sort_by_key(|f| (f.y, f.x));
    let pairs = base_sorted
        .iter()
        .filter_map(|a| by_pixel.get(&(a.x, a.y)).map(|b| (*a, *b)));
    let mut facing = Findings::new();
    let mut weights = Findings::new();
    for (a, b) in pairs {
        if (a.front_facing == b.front_facing) == flip {
            facing.add((a.x, a.y), || {
                format!("{:?} is {} then {}", (a.x, a.y), a.front_facing, b.front_facing)
            });
        }
        let moved_apart = map.iter().enumerate().any(|(k, &to)| {
            f64::from((a.barycentric[k] - b.barycentric[to]).abs()) > 2.0 * precision(profile)
        });
        if weighed && moved_apart {
            weights.add((a.x, a.y), || {
                format!(
                    "{:?} has {:?} then {:?}",
                    (a.x, a.y),
                    a.barycentric,
                    b.barycentric
                )
            });
        }
    }
    facing.verdict(|n| format!("{what}: the facing is wrong at {}", plural(n, "fragment")))?;
    weights.verdict(|n| {
        format!(
            "{what}: barycentrics did not move with their vertices at {}",
            plural(n, "fragment")
        )
    })
}

/// Whether triangle 0 of `scene`, as projected, is wide enough for the precision `profile`
/// claims to give its weights meaning: its area at least `2^-precision` of its extent squared
/// (the error of weights computed at that precision grows as extent² / area).
pub(super) fn resolvable(scene: &Scene, profile: &Profile) -> bool {
    let p = scene
        .positions_of(0)
        .map(|v| raster::project(scene.width, scene.height, v));
    let area =
        ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])).abs() / 2.0;
    let extent = (0..3)
        .map(|k| (p[k][0] - p[(k + 1) % 3][0]).hypot(p[k][1] - p[(k + 1) % 3][1]))
        .fold(0.0, f64::max);
    area >= precision(profile) * extent * extent
}

/// Rotating the vertex order keeps coverage and rotates barycentrics.
pub fn check_rotation(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    rotation(r, scene, true)
}

/// [`check_rotation`] away from edges: what Vulkan and OpenGL require ([`crate::rules::level::EDGES_NOT_PINNED`]).
pub fn check_rotation_away_from_edges(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    rotation(r, scene, false)
}

/// Rotates the vertex order; exact at edges with `at_edges` where the profile has exact coverage.
fn rotation(r: &mut dyn Rasterizer, scene: &Scene, at_edges: bool) -> Result<(), Violation> {
    let base = fragments(r, scene)?;
    let mut rotated = scene.clone();
    let [a, b, c] = scene.triangles[0];
    rotated.triangles[0] = [b, c, a];
    // Vertex a is now third: weight 0 moved to slot 2, 1 to 0, 2 to 1.
    compare_permuted(
        &r.profile(),
        scene,
        &base,
        &fragments(r, &rotated)?,
        Redrawn {
            map: [2, 0, 1],
            flip: false,
            what: "after rotating the vertices",
        },
        at_edges,
    )
}

/// Reversing the winding keeps coverage, swaps barycentrics, flips facing.
///
/// Under a cull mode the rasterizer cannot switch off, the reversed triangle faces the culled
/// way: told the other front face too it faces front again and keeps its facing; with one front
/// face, it must vanish.
pub fn check_reversal(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    reversal(r, scene, true)
}

/// [`check_reversal`] away from edges: what Vulkan and OpenGL require ([`crate::rules::level::EDGES_NOT_PINNED`]).
pub fn check_reversal_away_from_edges(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    reversal(r, scene, false)
}

/// Reverses the winding; exact at edges with `at_edges` where the profile has exact coverage.
fn reversal(r: &mut dyn Rasterizer, scene: &Scene, at_edges: bool) -> Result<(), Violation> {
    let profile = r.profile();
    let base = fragments(r, scene)?;
    let mut reversed = scene.clone();
    let [a, b, c] = scene.triangles[0];
    reversed.triangles[0] = [a, c, b];
    if scene.state.cull != CullMode::None {
        let other = match scene.state.front_face {
            FrontFace::CounterClockwise => FrontFace::Clockwise,
            FrontFace::Clockwise => FrontFace::CounterClockwise,
        };
        if profile.features.front_faces.contains(other) {
            reversed.state.front_face = other;
            let flipped = fragments(r, &reversed)?;
            return compare_permuted(
                &profile,
                scene,
                &base,
                &flipped,
                Redrawn {
                    map: [0, 2, 1],
                    flip: false,
                    what: &format!("after reversing the winding and the front face (to {other:?})"),
                },
                at_edges,
            );
        }
        let turn = reversed.turns(&profile)[0];
        match turn.drawn(&reversed.state) {
            Some(false) => {
                return check_draws_nothing(r, &reversed).map_err(|mut v| {
                    v.message = format!(
                        "reversed, the triangle faces back under {:?} culling and {:?} front faces, yet {}",
                        reversed.state.cull, reversed.state.front_face, v.message
                    );
                    v
                });
            }
            // Where the facing is unsure, culling it or not are both right.
            None => return Ok(()),
            Some(true) => {}
        }
    }
    compare_permuted(
        &profile,
        scene,
        &base,
        &fragments(r, &reversed)?,
        Redrawn {
            map: [0, 2, 1],
            flip: true,
            what: "after reversing the winding",
        },
        at_edges,
    )
}

/// Each triangle covers the same samples alone, together, in any order.
pub fn check_batch_independent(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let together = fragments(r, scene)?;
    for (i, t) in scene.triangles.iter().enumerate() {
        let mut alone = scene.clone();
        alone.triangles = vec![*t];
        let want = fragments(r, &alone)?;
        let got: Vec<Fragment> = together
            .iter()
            .filter(|f| f.primitive == i as u32)
            .map(|f| Fragment { primitive: 0, ..*f })
            .collect();
        compare_sets(&alone, &got, &want, &format!("triangle {i} drawn alone"))?;
    }
    let mut reversed = scene.clone();
    reversed.triangles.reverse();
    let n = scene.triangles.len() as u32;
    let back: Vec<Fragment> = fragments(r, &reversed)?
        .into_iter()
        .map(|f| Fragment {
            // A primitive id out of range stays out of range instead of wrapping into one.
            primitive: (n - 1).checked_sub(f.primitive).unwrap_or(u32::MAX),
            ..f
        })
        .collect();
    compare_sets(scene, &back, &together, "the draw in reverse order")
}

/// [`check_batch_independent`] away from edges: each triangle drawn together, alone and in
/// reverse order covers the same samples but within the band (and a grid step where the
/// profile's snapping is not exact) of its edges: what Vulkan and OpenGL require
/// ([`crate::rules::level::EDGES_NOT_PINNED`]).
pub fn check_batch_away_from_edges(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let limit = profile.band_px() + translate::snap_slack(&profile);
    let together = fragments(r, scene)?;
    let mut reversed = scene.clone();
    reversed.triangles.reverse();
    let back = fragments(r, &reversed)?;
    let n = scene.triangles.len();
    let mut found = Findings::new();
    for (i, t) in scene.triangles.iter().enumerate() {
        let mut alone = scene.clone();
        alone.triangles = vec![*t];
        let alone = alone.compact();
        let covered = |frags: &[Fragment], id: usize| -> BTreeSet<(u32, u32)> {
            frags
                .iter()
                .filter(|f| f.primitive as usize == id)
                .map(|f| (f.x, f.y))
                .collect()
        };
        let want = covered(&fragments(r, &alone)?, 0);
        for (how, got) in [
            ("together", covered(&together, i)),
            ("in reverse order", covered(&back, n - 1 - i)),
        ] {
            for &(x, y) in want.symmetric_difference(&got) {
                if !translate::near_edge(&alone, profile.snapping, x, y, limit) {
                    let change = if got.contains(&(x, y)) { "gains" } else { "loses" };
                    found.add((x, y), || {
                        format!("triangle {i} drawn {how} {change} {:?}", (x, y))
                    });
                }
            }
        }
    }
    found.verdict(|n| {
        format!(
            "triangles drawn together differ from drawn alone at {} away from every edge",
            plural(n, "sample")
        )
    })
}
