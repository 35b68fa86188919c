//! Depth: within the vertices' range, equal to the ray cast, independent of draw order.

use proptest::prelude::*;
use refrast::{CompareOp, DepthState, Profile, Rasterizer, Resolved};

use super::cast::{Expected, raycast_fragments, slack_note};
use super::common::{Values, check_values_finite, fragments, precision, reaches_far};
use super::level::{FAR_VALUES, Level};
use super::{DEPTH_TEST, EXTREME_OPS, EXTREME_WINS, Family, Rule, Z_OVER_W_DEPTH};
use crate::oracle::raster::{depth_bounds, replay_depth, window_depth};
use crate::runner::{property, property_for};
use crate::scene::Scene;
use crate::strategy;
use crate::violation::{Findings, Violation, plural};

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Depth, "depth.range.vertices")
            .sentence("The depth of an unclipped triangle's fragment lies between its vertices' smallest and largest z/w.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (depth is interpolated linearly); seed 000")
            .cases(5000)
            .needs(Z_OVER_W_DEPTH)
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |p| strategy::either_depth_range(p, strategy::perspective_inside_scene()),
                    check_within_vertices,
                )
            }),
        Rule::invariant(Family::Depth, "depth.screen-linear.matches-raycast")
            .sentence("Fragment depth equals z/w at the ray-cast hit within the claimed precision (2^-18 for the reference); on a clipped triangle also within how far it moves when the sample moves one grid step (its cut vertices are snapped).")
            .source("Vulkan 1.4, Basic Polygon Rasterization (z_f linear in framebuffer space); D3D11.3 §15.16.2, §16.3.1")
            .cases(5000)
            .needs(Z_OVER_W_DEPTH)
            .every_spec(Level::Partly {
                part: |r, cfg| {
                    property_for(
                        r,
                        cfg,
                        |p| strategy::either_depth_range(p, strategy::inside_or_crossing_scene()),
                        check_depth_matches_raycast_where_bounded,
                    )
                },
                note: FAR_VALUES,
            })
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |p| strategy::either_depth_range(p, strategy::inside_or_crossing_scene()),
                    check_depth_matches_raycast,
                )
            }),
        Rule::invariant(Family::Depth, "depth.order.independent")
            .sentence("After a depth test keeping the nearest fragment (Less, else LessOrEqual; or the farthest, Greater, else GreaterOrEqual, against a clear depth of 0) the depth buffer is identical under every submission order, and the primitive ids too where depths differ.")
            .source("seed 000 (depth buffer); refrast's own property: a LESS test is order-independent for distinct depths")
            .cases(3000)
            .needs(EXTREME_WINS)
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |p| with_extreme_depth(p, strategy::overlapping_scene()),
                    check_order_independent,
                )
            }),
        Rule::invariant(Family::Depth, "depth.intersecting.nearest-wins")
            .sentence("Where two triangles pass through each other, or three bars overlap in a cycle, the depth test keeping the nearest (or farthest) fragment leaves each surface where it is nearer: the resolved buffers are the fragments replayed through it, which no order of whole triangles gives.")
            .source("seed 003 (the painter's algorithm cannot handle cyclic or intersecting polygons; the z-buffer can); Vulkan 1.4, Depth Test")
            .cases(300)
            .needs(EXTREME_WINS)
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |p| {
                        let visibility = prop_oneof![strategy::interpenetrating_scene(), strategy::cyclic_scene()];
                        with_extreme_depth(p, visibility)
                    },
                    check_resolve,
                )
            }),
        Rule::invariant(Family::Depth, "depth.resolve.matches-fragments")
            .sentence("The resolved depth and id buffers are the fragments replayed in primitive order through the draw's compare op and write mask.")
            .source("Vulkan 1.4, Depth Test; seed 000")
            .cases(3000)
            .needs(DEPTH_TEST)
            .run(|r, cfg| property(r, cfg, depth_state_scene(), check_resolve)),
    ]
}

/// The depth test under which the buffer does not depend on draw order: the first supported
/// op of [`EXTREME_OPS`] with writes on, against a clear depth it can beat (1 for the ops
/// keeping the nearest, 0 for those keeping the farthest).
#[must_use]
pub fn extreme_depth(profile: &Profile) -> DepthState {
    let compare = EXTREME_OPS
        .into_iter()
        .find(|&op| profile.features.compare_ops.contains(op))
        .unwrap_or(CompareOp::Less);
    let nearest = matches!(compare, CompareOp::Less | CompareOp::LessOrEqual);
    DepthState {
        compare,
        write: true,
        clear: if nearest { 1.0 } else { 0.0 },
    }
}

/// `scenes` drawn under [`extreme_depth`]'s test for `profile`.
fn with_extreme_depth<S: Strategy<Value = Scene>>(
    profile: &Profile,
    scenes: S,
) -> impl Strategy<Value = Scene> + use<S> {
    let depth = extreme_depth(profile);
    scenes.prop_map(move |mut s| {
        s.state.depth = depth;
        s
    })
}

fn depth_state_scene() -> impl Strategy<Value = Scene> {
    let op = prop_oneof![
        Just(CompareOp::Never),
        Just(CompareOp::Less),
        Just(CompareOp::Equal),
        Just(CompareOp::LessOrEqual),
        Just(CompareOp::Greater),
        Just(CompareOp::NotEqual),
        Just(CompareOp::GreaterOrEqual),
        Just(CompareOp::Always),
    ];
    (
        strategy::overlapping_scene(),
        op,
        any::<bool>(),
        prop_oneof![Just(1.0f32), Just(0.0), 0.0f32..1.0],
        any::<bool>(),
    )
        .prop_map(|(mut s, compare, write, clear, repeat)| {
            s.state.depth = DepthState {
                compare,
                write,
                clear,
            };
            // The first triangle drawn again on top of the last: every fragment of the copy ties
            // with the original's depth, so Equal, LessOrEqual, GreaterOrEqual and NotEqual
            // meet exact ties (random depths never tie; docs/reach.md).
            if repeat && let Some(&first) = s.triangles.first() {
                s.triangles.push(first);
                // Flat at the clear value (0 or 1 are exact in every interpolation), so that
                // Equal passes against the clear value too.
                if clear == 0.0 || clear == 1.0 {
                    for i in first {
                        let p = &mut s.positions[i as usize];
                        p[2] = clear * p[3];
                    }
                }
            }
            s
        })
}

/// Depth stays between the vertices' smallest and largest z/w.
pub fn check_within_vertices(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let eps = precision(&r.profile()) as f32;
    let z: Vec<f32> = scene
        .positions
        .iter()
        .map(|p| window_depth(&scene.state, f64::from(p[2] / p[3])) as f32)
        .collect();
    let (lo, hi) = z
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), &v| (l.min(v), h.max(v)));
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        if f.depth < lo - eps || f.depth > hi + eps {
            found.add((f.x, f.y), || format!("{:?} has depth {}", (f.x, f.y), f.depth));
        }
    }
    found.verdict(|n| {
        format!(
            "depth outside the vertices' [{lo}, {hi}] at {}",
            plural(n, "fragment")
        )
    })
}

/// Depth equals z/w at the ray-cast hit: of the snapped triangle, or for a clipped one within
/// its spread over a grid step ([`raycast_fragments`]).
pub fn check_depth_matches_raycast(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let eps = precision(&profile);
    let mut found = Findings::new();
    let cast = raycast_fragments(r, scene)?;
    // Clamping moves two values no further apart, so the slack still holds.
    let [lo, hi] = depth_bounds(&scene.state);
    let off = |f: &refrast::Fragment, want: &Expected| (f64::from(f.depth) - want.depth.clamp(lo, hi)).abs();
    // Whether the first wrong fragment lies where the ray cast's depth is clamped, and its own
    // is not: depth beyond the far plane (far clipping off) or before the near one.
    let mut unclamped = None;
    for &(f, want) in &cast.pairs {
        let depth = want.depth.clamp(lo, hi);
        let off_by = off(&f, &want);
        if off_by > eps + want.depth_slack
            && !cast.another_snap_accepts(&f, |w| off(&f, w) <= eps + w.depth_slack)
        {
            unclamped.get_or_insert(
                (want.depth > hi && f64::from(f.depth) > hi) || (want.depth < lo && f64::from(f.depth) < lo),
            );
            let off = off_by;
            found.add((f.x, f.y), || {
                format!(
                    "{:?} has depth {}, the ray cast {depth} (off by {off:.3e}{})",
                    (f.x, f.y),
                    f.depth,
                    slack_note(want.depth_slack, &profile)
                )
            });
        }
    }
    found.verdict(|n| {
        let clamp = if unclamped == Some(true) {
            " (the first lies outside the clip volume's depth range, which the draw does not clip \
             at: there depth is clamped to the viewport's depth range, so clamp the fragment's depth)"
        } else {
            ""
        };
        format!(
            "depth off the ray cast's by more than the claimed precision at {}{clamp}",
            plural(n, "fragment")
        )
    })
}

/// The scene with its triangles in the order `order` (entries are original indices).
fn reorder(scene: &Scene, order: &[usize]) -> Scene {
    let mut s = scene.clone();
    s.triangles = order.iter().map(|&i| scene.triangles[i]).collect();
    s
}

/// Whether the implementation runs its own depth test and can be asked to write every fragment
/// (`Always`, writes on): then the buffer it leaves shows each fragment's stored depth.
pub(super) fn writes_every_fragment(profile: &Profile) -> bool {
    let f = &profile.features;
    f.depth_test && f.compare_ops.contains(CompareOp::Always) && f.depth_writes.contains(true)
}

/// `scene` with a depth test that writes every fragment (`Always`, writes on, its own clear).
pub(super) fn every_fragment_written(scene: &Scene) -> Scene {
    let mut every = scene.clone();
    every.state.depth = DepthState {
        compare: CompareOp::Always,
        write: true,
        clear: scene.state.depth.clear,
    };
    every
}

/// The rasterizer's resolved buffers; an error, or buffers of the wrong size, is a violation.
pub(super) fn resolve(r: &mut dyn Rasterizer, scene: &Scene) -> Result<Resolved, Violation> {
    let resolved = r
        .resolve(&scene.draw())
        .map_err(|e| Violation::of_draw_error("resolve", &e))?;
    let pixels = scene.width as usize * scene.height as usize;
    if resolved.depth.len() != pixels || resolved.primitive.len() != pixels {
        return Err(Violation::new(format!(
            "resolve returned {} depths and {} ids for a {}×{} viewport ({pixels} pixels)",
            resolved.depth.len(),
            resolved.primitive.len(),
            scene.width,
            scene.height
        )));
    }
    let n = scene.triangles.len();
    if let Some(i) = resolved
        .primitive
        .iter()
        .position(|p| p.is_some_and(|p| p as usize >= n))
    {
        let (x, y) = (i as u32 % scene.width, i as u32 / scene.width);
        return Err(Violation::at(
            (x, y),
            format!(
                "resolve names primitive {:?} at {:?}, but the draw has {n}",
                resolved.primitive[i],
                (x, y)
            ),
        ));
    }
    Ok(resolved)
}

/// The resolved buffers do not depend on submission order (ids where depths differ).
pub fn check_order_independent(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let n = scene.triangles.len();
    let base = resolve(r, scene)?;
    // Ties: how many fragments reach each pixel's winning depth; with several, either may own it.
    let mut ties = vec![0u32; base.depth.len()];
    for f in fragments(r, scene)? {
        let i = f.y as usize * scene.width as usize + f.x as usize;
        if f.x < scene.width && f.y < scene.height && f.depth == base.depth[i] {
            ties[i] += 1;
        }
    }
    let reversed: Vec<usize> = (0..n).rev().collect();
    let rotated: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    for order in [reversed, rotated] {
        let other = resolve(r, &reorder(scene, &order))?;
        let mut found = Findings::new();
        for (i, &pixel_ties) in ties.iter().enumerate() {
            let (x, y) = (i as u32 % scene.width, i as u32 / scene.width);
            let mapped = other.primitive[i].map(|p| order[p as usize] as u32);
            let depth_differs = base.depth[i].to_bits() != other.depth[i].to_bits();
            if depth_differs || (pixel_ties <= 1 && mapped != base.primitive[i]) {
                found.add((x, y), || {
                    format!(
                        "{:?}: depth {} and primitive {:?} in API order, {} and {mapped:?} in order {order:?}",
                        (x, y),
                        base.depth[i],
                        base.primitive[i],
                        other.depth[i]
                    )
                });
            }
        }
        found.verdict(|n| format!("another draw order resolves {} differently", plural(n, "pixel")))?;
    }
    Ok(())
}

/// `resolve` equals the fragments replayed through the draw's depth state.
pub fn check_resolve(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    replay_differences(r, scene, None)?.verdict(|n| {
        format!(
            "the resolved buffers differ from the fragments replayed at {}",
            plural(n, "pixel")
        )
    })
}

/// The pixels where `resolve` differs from the fragments replayed through the draw's depth
/// state: in the primitive, or in depth bit for bit (`tolerance` `None`) or by more than it.
pub(super) fn replay_differences(
    r: &mut dyn Rasterizer,
    scene: &Scene,
    tolerance: Option<f64>,
) -> Result<Findings, Violation> {
    let got = resolve(r, scene)?;
    let (depths, ids) = replay_depth(
        scene.state.depth,
        scene.width,
        scene.height,
        &fragments(r, scene)?,
    );
    let differs = |a: f32, b: f32| match tolerance {
        None => a.to_bits() != b.to_bits(),
        Some(eps) => (f64::from(a) - f64::from(b)).abs() > eps,
    };
    let mut found = Findings::new();
    for i in 0..depths.len() {
        if differs(got.depth[i], depths[i]) || got.primitive[i] != ids[i] {
            let (x, y) = (i as u32 % scene.width, i as u32 / scene.width);
            found.add((x, y), || {
                format!(
                    "{:?}: resolved ({}, {:?}), its fragments replayed ({}, {:?})",
                    (x, y),
                    got.depth[i],
                    got.primitive[i],
                    depths[i],
                    ids[i]
                )
            });
        }
    }
    Ok(found)
}

/// [`check_depth_matches_raycast`] where the triangle stays near the viewport, finite values
/// elsewhere.
pub fn check_depth_matches_raycast_where_bounded(
    r: &mut dyn Rasterizer,
    scene: &Scene,
) -> Result<(), Violation> {
    if reaches_far(scene) {
        let depth = Values {
            depth: true,
            perspective: false,
            screen: false,
        };
        check_values_finite(r, scene, depth)
    } else {
        check_depth_matches_raycast(r, scene)
    }
}
