//! Triangle strips and fans: each draws what the triangle list of its triangles draws, each
//! triangle in the vertex order Vulkan gives it ([`refrast::Draw::triangle`]), so that every
//! other triangle of a strip is reversed and keeps the strip's facing.
//!
//! Both rules compare the implementation with itself (the strip or fan, then the same
//! triangles as a list), so they hold whatever its conventions; its list is judged by every
//! other rule.

use std::collections::HashMap;

use proptest::prelude::*;
use refrast::{Fragment, Profile, Rasterizer, Topology};

use super::order::resolvable;
use super::translate::{near_edge, snap_slack};
use crate::oracle::raster;
use crate::rules::common::{precision, screen_defined};
use crate::rules::samples::{
    cell_counts, difference_counts, difference_picture, keys, resolved, sample_fragments,
};
use crate::scene::{PrimitiveScene, Scene};
use crate::strategy::primitive;
use crate::violation::{Findings, Violation, plural};

/// Strips at every sample count `p` draws them at.
pub(super) fn strips(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    of(p, Topology::TriangleStrip)
}

/// Fans at every sample count `p` draws them at.
pub(super) fn fans(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    of(p, Topology::TriangleFan)
}

/// Strips or fans (`topology`) at every sample count `p` draws them at.
fn of(p: &Profile, topology: Topology) -> BoxedStrategy<PrimitiveScene> {
    let counts = p
        .sample_counts()
        .into_iter()
        .filter(|&n| p.draws(topology, n))
        .collect();
    primitive::strips_or_fans(topology, counts).boxed()
}

/// A strip or fan draws as its triangles do in a list, sample for sample and value for value.
pub fn check_same_as_list(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    compare_with_list(r, case, false)
}

/// [`check_same_as_list`] but what [`Unpinned`] leaves out: what every specification requires
/// ([`crate::rules::level::STRIP_ORDER_NOT_PINNED`]).
pub fn check_same_as_list_away_from_edges(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
) -> Result<(), Violation> {
    compare_with_list(r, case, true)
}

/// What a comparison leaves out at the level the specifications require, where a strip's
/// triangle may be made from its vertices in another order than the list's (OpenGL's
/// rotation): coverage near an edge of one of the list's triangles, or on one the near or far
/// plane cuts; values and facing of a triangle any plane cuts, or too thin for the claimed
/// precision (as `meta.rotation.same-coverage` leaves them). Nothing at the exact level.
struct Unpinned {
    /// Per pixel, row-major, whether its coverage is left out; empty at the exact level.
    pixels: Vec<bool>,
    /// The viewport's width, to index `pixels`.
    width: u32,
    /// Per triangle of the list, whether its values and facing are left out; empty at the
    /// exact level.
    values: Vec<bool>,
}

impl Unpinned {
    fn new(list: &PrimitiveScene, profile: &Profile, away_from_edges: bool) -> Self {
        let scene = &list.scene;
        let (width, height) = (scene.width, scene.height);
        let mut unpinned = Self {
            pixels: Vec::new(),
            width,
            values: Vec::new(),
        };
        if !away_from_edges {
            return unpinned;
        }
        unpinned.pixels = vec![false; (width * height) as usize];
        // Samples other than the centre lie up to √2/2 px from it.
        let spread = if list.samples > 1 {
            std::f64::consts::FRAC_1_SQRT_2
        } else {
            0.0
        };
        let limit = profile.band_px() + snap_slack(profile) + spread;
        for &t in &scene.triangles {
            let alone = Scene {
                triangles: vec![t],
                ..scene.clone()
            };
            let Some(corners) = t
                .iter()
                .map(|&i| scene.positions.get(i as usize).copied())
                .collect::<Option<Vec<_>>>()
            else {
                // A vertex the draw does not have: the draw is refused, nothing is compared.
                unpinned.values.push(true);
                continue;
            };
            let corners = [corners[0], corners[1], corners[2]];
            let unclipped = raster::unclipped(&corners, &scene.state);
            unpinned.values.push(!unclipped || !resolvable(&alone, profile));
            let projectable = corners
                .iter()
                .all(|p| p[3] > 0.0 && p.iter().all(|c| c.is_finite()));
            if !projectable {
                // No shape on screen to measure an edge from: every pixel is left out.
                unpinned.pixels.iter_mut().for_each(|p| *p = true);
                continue;
            }
            let depth_cut = corners
                .iter()
                .any(|&[_, _, z, w]| raster::outside_depth_planes(&scene.state, f64::from(z), f64::from(w)));
            let points = corners.map(|p| raster::project(width, height, p.map(f64::from)));
            let reach = limit + 1.0;
            let span = |k: usize, side: u32| {
                let lo = points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min) - reach;
                let hi = points.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max) + reach;
                let clamp = |v: f64| v.clamp(0.0, f64::from(side)) as u32;
                clamp(lo.floor())..clamp(hi.ceil())
            };
            for y in span(1, height) {
                for x in span(0, width) {
                    if depth_cut || near_edge(&alone, profile.snapping, x, y, limit) {
                        unpinned.pixels[(y * width + x) as usize] = true;
                    }
                }
            }
        }
        unpinned
    }

    /// Whether coverage at pixel `(x, y)` is left out.
    fn at(&self, x: u32, y: u32) -> bool {
        x < self.width
            && self
                .pixels
                .get(y as usize * self.width as usize + x as usize)
                .copied()
                .unwrap_or(false)
    }

    /// Whether the values and facing of triangle `primitive` are left out.
    fn values_of(&self, primitive: u32) -> bool {
        !self.values.is_empty() && self.values.get(primitive as usize).is_none_or(|&skip| skip)
    }
}

/// The strip or fan against its list: coverage and ids, then values, then (where `r`
/// resolves) the depth test's buffers, leaving out what [`Unpinned`] says.
fn compare_with_list(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    away_from_edges: bool,
) -> Result<(), Violation> {
    let profile = r.profile();
    let list = case.as_list();
    let skip = Unpinned::new(&list, &profile, away_from_edges);
    let drawn = sample_fragments(r, case)?;
    let listed = sample_fragments(r, &list)?;
    let judged = |frags: &[Fragment]| -> Vec<Fragment> {
        frags.iter().filter(|f| !skip.at(f.x, f.y)).copied().collect()
    };
    let (got, want) = (judged(&drawn), judged(&listed));
    if keys(&got) != keys(&want) {
        return Err(coverage_differs(case, &got, &want));
    }
    compare_values(case, &list.scene, &profile, &skip, &drawn, &listed)?;
    if profile.features.depth_test {
        compare_resolves(r, case, &list, &profile, &skip, &listed)?;
    }
    Ok(())
}

/// The violation of a strip or fan covering other samples than its list.
fn coverage_differs(case: &PrimitiveScene, got: &[Fragment], want: &[Fragment]) -> Violation {
    let (gc, wc) = (cell_counts(case, got), cell_counts(case, want));
    let message = if gc == wc {
        format!(
            "the {} covers the samples its triangles cover as a list, but names other triangles for them",
            case.topology
        )
    } else {
        let (lost, added) = gc.iter().zip(&wc).fold((0, 0), |(l, a), (&g, &w)| {
            (l + w.saturating_sub(g), a + g.saturating_sub(w))
        });
        format!(
            "the {} covers other samples than its triangles drawn as a list: {lost} missing, {added} more",
            case.topology
        )
    };
    let mut violation = Violation::new(message);
    violation.counts = Some(Box::new(difference_counts(&gc, &wc)));
    violation.picture = Some(Box::new(difference_picture(case, &gc, &wc, Vec::new())));
    violation
}

/// Each fragment both draws has one facing, and depth and barycentrics within twice the
/// declared precision of each other (each is within it of the exact value). A value the list
/// gives that is not finite is no standard (the `bary.` and `robust.` rules judge it), so the
/// strip's is not compared with it.
fn compare_values(
    case: &PrimitiveScene,
    list: &Scene,
    profile: &Profile,
    skip: &Unpinned,
    drawn: &[Fragment],
    listed: &[Fragment],
) -> Result<(), Violation> {
    let tolerance = 2.0 * precision(profile);
    let by_key: HashMap<_, &Fragment> = listed
        .iter()
        .map(|f| ((f.x, f.y, f.sample, f.primitive), f))
        .collect();
    // Within the tolerance of a finite list value; a NaN or infinity against one is not.
    let within = |a: &[f32], b: &[f32]| {
        a.iter()
            .zip(b)
            .all(|(&p, &q)| !q.is_finite() || (f64::from(p) - f64::from(q)).abs() <= tolerance)
    };
    let f = &profile.features;
    let mut found = Findings::new();
    for got in drawn {
        let Some(want) = by_key.get(&(got.x, got.y, got.sample, got.primitive)) else {
            continue;
        };
        let mut wrong = Vec::new();
        let values = !skip.values_of(got.primitive);
        if values && !skip.at(got.x, got.y) && got.front_facing != want.front_facing {
            wrong.push(format!(
                "faces {} where the list's triangle faces {}",
                facing(got.front_facing),
                facing(want.front_facing)
            ));
        }
        if values && !within(&[got.depth], &[want.depth]) {
            wrong.push(format!("depth {:?} against {:?}", got.depth, want.depth));
        }
        if values && f.perspective_barycentrics && !within(&got.barycentric, &want.barycentric) {
            wrong.push(format!(
                "barycentrics {:?} against {:?}",
                got.barycentric, want.barycentric
            ));
        }
        if let (Some(g), Some(w)) = (got.screen_barycentric, want.screen_barycentric)
            && values
            && f.screen_barycentrics
            && screen_defined(list, got.primitive)
            && !within(&g, &w)
        {
            wrong.push(format!("screen barycentrics {g:?} against {w:?}"));
        }
        if !wrong.is_empty() {
            found.add((got.x, got.y), || {
                format!(
                    "({}, {}) sample {} of triangle {}: {}",
                    got.x,
                    got.y,
                    got.sample,
                    got.primitive,
                    wrong.join(", ")
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "the {} gives {} other values than its triangles drawn as a list (beyond twice the declared 2^-{} each)",
            case.topology,
            plural(n, "sample"),
            profile.precision_bits
        )
    })
}

/// A facing as a sentence names it.
fn facing(front: bool) -> &'static str {
    if front { "front" } else { "back" }
}

/// The depth test leaves the same depth and primitive at each judged sample after the strip
/// or fan as after its list; where the two name different triangles, their depths there are
/// within twice the precision (either may then win). Samples whose values [`Unpinned`] leaves
/// out are left out here too.
fn compare_resolves(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    list: &PrimitiveScene,
    profile: &Profile,
    skip: &Unpinned,
    listed: &[Fragment],
) -> Result<(), Violation> {
    let tolerance = 2.0 * precision(profile);
    let (drawn, want) = (resolved(r, &case.draw())?, resolved(r, &list.draw())?);
    let depth_of: HashMap<_, f32> = listed
        .iter()
        .map(|f| ((f.x, f.y, f.sample, f.primitive), f.depth))
        .collect();
    let close =
        |a: f32, b: f32| (f64::from(a) - f64::from(b)).abs() <= tolerance || a.to_bits() == b.to_bits();
    let mut found = Findings::new();
    for y in 0..case.scene.height {
        for x in 0..case.scene.width {
            if skip.at(x, y) {
                continue;
            }
            for s in 0..case.samples {
                let i = drawn.index(x, y, s);
                let (gp, wp) = (drawn.primitive[i], want.primitive[i]);
                if [gp, wp].into_iter().flatten().any(|p| skip.values_of(p)) {
                    continue;
                }
                // Two depths within the tolerance may fall either way of the test: two triangles'
                // (either wins) or one's and the clear value (drawn or not).
                let depth = |p: Option<u32>| match p {
                    Some(p) => depth_of.get(&(x, y, s, p)).copied(),
                    None => Some(case.scene.state.depth.clear),
                };
                let tie = match (depth(gp), depth(wp)) {
                    (Some(a), Some(b)) => close(a, b),
                    _ => false,
                };
                let same = (gp == wp || tie) && close(drawn.depth[i], want.depth[i]);
                if !same {
                    found.add((x, y), || {
                        format!(
                            "({x}, {y}) sample {s}: depth {:?} and triangle {gp:?}, where the list leaves depth {:?} and triangle {wp:?}",
                            drawn.depth[i], want.depth[i]
                        )
                    });
                }
            }
        }
    }
    found.verdict(|n| {
        format!(
            "after the {}, the depth test leaves {} other than after its triangles drawn as a list",
            case.topology,
            plural(n, "sample")
        )
    })
}
