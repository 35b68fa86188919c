//! What a mesh should cover, sample by sample: once inside, never outside, either within the
//! tolerance band of a boundary or a cut, and what a cull mode or a specification leaves open.

use std::collections::BTreeMap;

use refrast::{CullMode, Profile, Rasterizer};

use super::common::fragments;
use super::vertices::{samples_near_vertices_of_three, samples_on_vertices_of_three};
use super::why;
use crate::oracle::outline::{OutlinePoint, distance_to_outline, row_reach, visible_outline};
use crate::oracle::raster::{sample_centre, sample_ndc};
use crate::oracle::ray_cast::{CutRounding, HitTest};
use crate::picture::finite_outlines;
use crate::scene::Scene;
use crate::violation::{Expect, Violation, compare_coverage, count_fragments};

/// What a coverage check leaves to the implementation beyond refrast's conventions, for a
/// specification that requires less ([`super::level::Level::Partly`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Relax {
    /// A sample exactly on a vertex shared by three or more triangles, where the profile puts
    /// it ([`super::vertices::vertices_of_three`]), may be covered any number of times: Vulkan's and OpenGL's
    /// exactly-once speaks of two polygons on either side of an edge
    /// ([`super::level::SHARED_EDGE_ONLY`]). Applied by [`check_mesh_coverage`], which knows
    /// the profile.
    pub vertices_of_three: bool,
    /// A shared edge ending at a vertex made by clipping is a boundary (with the band and the
    /// clipper's rounding): two triangles need not cut it at the same point
    /// ([`super::level::CUT_VERTICES`]).
    pub cut_shared_edges: bool,
}

impl Relax {
    /// All of refrast's conventions.
    pub const NONE: Relax = Relax {
        vertices_of_three: false,
        cut_shared_edges: false,
    };
}

/// Ray-cast expectations for a scene whose triangles do not overlap (one triangle, or a mesh).
///
/// A sample inside some triangle should be covered exactly once, one outside all should not
/// be covered, except within `band` pixels of an outline segment that is not a shared edge:
/// the mesh boundary and the cuts made by clip planes (there, any count is accepted: a cut
/// vertex snapped over a neighbour's sample makes it count twice); cuts are widened by how far
/// an f32 clipper may move them ([`CutRounding`]). Shared edges get no band,
/// so a crack along them is caught exactly, and so is an overlap, except within the band of a
/// shared edge ending at a cut vertex, where one or two is right ([`Expect::OneOrTwo`]).
/// `relax` leaves to the implementation what it says of cuts ([`Relax::NONE`] leaves nothing;
/// its vertices of three are [`check_mesh_coverage`]'s, which knows where the profile puts them).
#[must_use]
pub fn mesh_expectation(scene: &Scene, band: f64, relax: Relax) -> (Vec<Expect>, Vec<Vec<[f64; 2]>>) {
    let shared = shared_edges(scene);
    let tris: Vec<[[f64; 4]; 3]> = (0..scene.triangles.len())
        .map(|t| scene.positions_of(t))
        .collect();
    let outlines: Vec<Vec<OutlinePoint>> = tris
        .iter()
        .map(|t| visible_outline(t, scene.width, scene.height, &scene.state))
        .collect();
    let (width, height) = (scene.width, scene.height);
    let at = |x: u32, y: u32| (y * width + x) as usize;
    let samples = width as usize * height as usize;
    // Per sample, whether any triangle puts it near a boundary, near a cut vertex, inside.
    let (mut near_boundary, mut near_cut_vertex, mut inside) =
        (vec![false; samples], vec![false; samples], vec![false; samples]);
    for ((o, t), &sh) in outlines.iter().zip(&tris).zip(&shared) {
        // Only samples this triangle can reach: within `band` of its outline, or inside it.
        let [xs, ys] = Reach::of(o).samples(band, width, height);
        let interior = Interior::of(o);
        let hit_test = HitTest::new(t, &scene.state);
        // Segments not lying on a shared input edge (the boundary and the cuts), and segments
        // ending at a cut vertex; an outline with none (a mesh's inner triangle, an unclipped
        // one) is at no distance from any sample.
        let boundary = |a: &OutlinePoint, b: &OutlinePoint| a.edges & b.edges & sh == 0;
        let at_cut = |a: &OutlinePoint, b: &OutlinePoint| a.is_cut() || b.is_cut();
        let has = |keep: &dyn Fn(&OutlinePoint, &OutlinePoint) -> bool| {
            (0..o.len()).any(|k| keep(&o[k], &o[(k + 1) % o.len()]))
        };
        let (has_boundary, has_cut) = (has(&boundary), has(&at_cut));
        for y in ys {
            // Only samples in a row's stretches within the band of such segments can be near
            // one (issue 47): the distance is asked of those alone.
            let sy = sample_centre(0, y)[1];
            let boundary_reach = has_boundary.then(|| row_reach(o, sy, band, boundary));
            let cut_reach = has_cut.then(|| row_reach(o, sy, band, at_cut));
            for x in xs.clone() {
                let (i, s) = (at(x, y), sample_centre(x, y));
                if !near_boundary[i]
                    && within(boundary_reach.as_deref(), s[0])
                    && distance_to_outline(o, s, boundary) < band
                {
                    near_boundary[i] = true;
                }
                if !near_cut_vertex[i]
                    && within(cut_reach.as_deref(), s[0])
                    && distance_to_outline(o, s, at_cut) < band
                {
                    near_cut_vertex[i] = true;
                }
                if !inside[i] {
                    inside[i] = interior.contains(s).unwrap_or_else(|| {
                        let [nx, ny] = sample_ndc(width, height, x, y);
                        hit_test.hits(nx, ny)
                    });
                }
            }
        }
        // Cuts by a plane also move by an f32 clipper's rounding, which has no bound worth a
        // box (infinite where the plane is seen edge-on); so, relaxed, does a shared edge ending
        // at one. Only outlines with such a segment can add anything here.
        let cut = |a: &OutlinePoint, b: &OutlinePoint| {
            a.edges & b.edges == 0
                || (relax.cut_shared_edges && a.edges & b.edges & sh != 0 && (a.is_cut() || b.is_cut()))
        };
        if !(0..o.len()).any(|k| cut(&o[k], &o[(k + 1) % o.len()])) {
            continue;
        }
        let rounding = CutRounding::new(t, width, height, &scene.state);
        for y in 0..height {
            // Where the rounding is bounded along the row, only samples within the band and
            // that bound of a cut can be near one: the rest are skipped (issue 47).
            let bound = rounding.bound_in_row(y);
            let reach = bound
                .is_finite()
                .then(|| row_reach(o, sample_centre(0, y)[1], band + bound, cut));
            for x in 0..width {
                let (i, s) = (at(x, y), sample_centre(x, y));
                if near_boundary[i] {
                    continue;
                }
                if reach.is_some() && !within(reach.as_deref(), s[0]) {
                    continue;
                }
                let d = distance_to_outline(o, s, cut);
                // The rounding is never negative: within the band, it need not be computed;
                // nor beyond the band and the row's bound on it.
                near_boundary[i] =
                    d < band || (d.is_finite() && d < band + bound && d < band + rounding.at(s));
            }
        }
    }
    let expected: Vec<Expect> = (0..samples)
        .map(|i| match (near_boundary[i], near_cut_vertex[i], inside[i]) {
            (true, _, _) => Expect::ZeroOrOne,
            (false, true, true) => Expect::OneOrTwo,
            (false, _, true) => Expect::One,
            (false, _, false) => Expect::Zero,
        })
        .collect();
    (expected, finite_outlines(&outlines))
}

/// Whether `x` lies in one of a row's `stretches` (from [`row_reach`]); `false` without any,
/// where no segment was kept.
fn within(stretches: Option<&[(f64, f64)]>, x: f64) -> bool {
    stretches.is_some_and(|s| s.iter().any(|&(lo, hi)| lo <= x && x <= hi))
}

/// Per triangle, bit k set when its edge k (from corner k to k+1) is shared with another
/// triangle. Shared means identical endpoints (Vulkan's wording), whatever the vertex indices.
fn shared_edges(scene: &Scene) -> Vec<u8> {
    let key = |i: u32| scene.positions[i as usize].map(f32::to_bits);
    let edge = |t: &[u32; 3], k: usize| {
        let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
        if a <= b { (a, b) } else { (b, a) }
    };
    let mut edge_use: BTreeMap<([u32; 4], [u32; 4]), u32> = BTreeMap::new();
    for t in &scene.triangles {
        for k in 0..3 {
            *edge_use.entry(edge(t, k)).or_default() += 1;
        }
    }
    scene
        .triangles
        .iter()
        .map(|t| {
            (0..3)
                .filter(|&k| edge_use[&edge(t, k)] > 1)
                .fold(0u8, |mask, k| mask | (1 << k))
        })
        .collect()
}

/// The box holding an outline whose points are all finite, widened by their rounding: a sample
/// outside it is farther from every segment than from the box, and no ray through it hits the
/// triangle's visible part (whose corners the outline's points are).
struct Reach(Option<[f64; 4]>);

impl Reach {
    /// The box of `outline`, or none (every sample can be reached) when it has a point at
    /// infinity or no point at all.
    fn of(outline: &[OutlinePoint]) -> Self {
        if outline.is_empty()
            || outline
                .iter()
                .any(|p| !p.finite || !p.position.iter().all(|c| c.is_finite()))
        {
            return Self(None);
        }
        let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
        for p in outline {
            let [x, y] = p.position;
            b = [b[0].min(x), b[1].max(x), b[2].min(y), b[3].max(y)];
        }
        // The points come out of f64 clipping and projection, each within a few ulps of its
        // exact value; a pixel plus 2^-30 of the largest coordinate is far beyond that.
        let size = b.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let slack = 1.0 + size / f64::from(1u32 << 30);
        Self(Some([b[0] - slack, b[1] + slack, b[2] - slack, b[3] + slack]))
    }

    /// The columns and rows of a `width`×`height` viewport whose samples lie within `band`
    /// pixels of the box: every sample, without a box.
    fn samples(&self, band: f64, width: u32, height: u32) -> [std::ops::Range<u32>; 2] {
        let Some([x0, x1, y0, y1]) = self.0 else {
            return [0..width, 0..height];
        };
        // Sample `i` lies at `i + ½`: the first with `i + ½ ≥ lo − band`, up to the last with
        // `i + ½ ≤ hi + band`, clamped to the viewport (the casts saturate).
        let span = |lo: f64, hi: f64, side: u32| {
            let first = (lo - band - 0.5).ceil().max(0.0) as u32;
            let end = ((hi + band - 0.5).floor() + 1.0).clamp(0.0, f64::from(side)) as u32;
            first.min(side)..end.max(first.min(side))
        };
        [span(x0, x1, width), span(y0, y1, height)]
    }
}

/// An unclipped triangle's projection, for deciding samples clearly inside or outside it in
/// screen space without a ray cast: its three points (all finite, none made by a cut) with
/// their edge functions. Every point of such a triangle lies in front of the eye and within
/// the near and far planes (each a linear bound its corners meet), so a ray through a sample
/// inside its projection hits it where `ray_cast` counts the hit, and one outside misses.
struct Interior(Option<[[f64; 2]; 3]>);

impl Interior {
    /// The triangle's projection, when its outline is the whole triangle.
    fn of(outline: &[OutlinePoint]) -> Self {
        let whole = outline.len() == 3 && outline.iter().all(|p| p.finite && !p.is_cut());
        Self(whole.then(|| [0, 1, 2].map(|k| outline[k].position)))
    }

    /// `Some(inside)` when `s` is farther from every edge than the points' rounding could
    /// move it; `None` (cast the ray) near an edge, on a triangle seen edge-on, or for a
    /// clipped triangle.
    fn contains(&self, s: [f64; 2]) -> Option<bool> {
        let p = self.0?;
        let mut sign = 0.0f64;
        let mut inside = true;
        for k in 0..3 {
            let (a, b) = (p[k], p[(k + 1) % 3]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let (sx, sy) = (s[0] - a[0], s[1] - a[1]);
            let e = dx * sy - dy * sx;
            // The points are within a few ulps of their exact values; a millionth of the
            // terms' size is far more than that and their products' rounding together.
            let margin = 1e-6 * (dx.abs() + dy.abs()) * (sx.abs() + sy.abs()) + f64::MIN_POSITIVE;
            if !e.is_finite() || e.abs() <= margin {
                return None;
            }
            if sign == 0.0 {
                sign = e.signum();
            }
            inside &= e.signum() == sign;
        }
        if !inside {
            // Clearly outside one edge, clearly inside another: outside, whichever way the
            // triangle turns, unless it is seen edge-on, which only the ray cast decides.
            return Some(false).filter(|_| area_sure(p));
        }
        Some(true).filter(|_| area_sure(p))
    }
}

/// Whether the projection's area is clearly not zero (else the triangle may be seen edge-on,
/// where the ray cast hits nothing).
fn area_sure(p: [[f64; 2]; 3]) -> bool {
    let (ux, uy) = (p[1][0] - p[0][0], p[1][1] - p[0][1]);
    let (vx, vy) = (p[2][0] - p[0][0], p[2][1] - p[0][1]);
    let area = ux * vy - uy * vx;
    area.is_finite() && area.abs() > 1e-6 * (ux.abs() + uy.abs()) * (vx.abs() + vy.abs())
}

/// [`mesh_expectation`] of what the scene's state draws for a rasterizer with `profile`: a
/// triangle its cull mode surely discards is expected absent, and where a triangle's facing is
/// unsure ([`crate::oracle::facing::Turn::Unsure`]) whatever either outcome allows.
#[must_use]
pub fn drawn_expectation(
    scene: &Scene,
    profile: &Profile,
    band: f64,
    relax: Relax,
) -> (Vec<Expect>, Vec<Vec<[f64; 2]>>) {
    if scene.state.cull == CullMode::None {
        return mesh_expectation(scene, band, relax);
    }
    let drawn: Vec<Option<bool>> = scene
        .turns(profile)
        .iter()
        .map(|t| t.drawn(&scene.state))
        .collect();
    let keeping = |unsure: bool| {
        let mut kept = scene.clone();
        kept.triangles = (0..scene.triangles.len())
            .filter(|&t| drawn[t].unwrap_or(unsure))
            .map(|t| scene.triangles[t])
            .collect();
        kept
    };
    let (with, outlines) = mesh_expectation(&keeping(true), band, relax);
    if drawn.iter().all(Option::is_some) {
        return (with, outlines);
    }
    let (without, _) = mesh_expectation(&keeping(false), band, relax);
    let either = with
        .iter()
        .zip(&without)
        .map(|(&a, &b)| match (a, b) {
            _ if a == b => a,
            (Expect::One, Expect::OneOrTwo) | (Expect::OneOrTwo, Expect::One) => Expect::OneOrTwo,
            _ => Expect::ZeroOrOne,
        })
        .collect();
    (either, outlines)
}

/// Checks a scene's coverage against [`drawn_expectation`], leaving to the implementation what
/// `relax` says; `what` says what a mesh is expected to cover (a scene of one triangle is no
/// mesh, and its message says so), and each wrong sample is described by [`why::describe`].
pub fn check_mesh_coverage(
    r: &mut dyn Rasterizer,
    scene: &Scene,
    what: &str,
    relax: Relax,
) -> Result<(), Violation> {
    let profile = r.profile();
    let frags = fragments(r, scene)?;
    let (mut expected, outlines) = drawn_expectation(scene, &profile, profile.band_px(), relax);
    if relax.vertices_of_three {
        for (x, y) in samples_on_vertices_of_three(scene, &profile) {
            expected[(y * scene.width + x) as usize] = Expect::ZeroOrOne;
        }
    }
    if profile.snapping.grid_bits().is_none() {
        for (x, y) in samples_near_vertices_of_three(scene, &profile) {
            expected[(y * scene.width + x) as usize] = Expect::ZeroOrOne;
        }
    }
    let counts = count_fragments(&frags, scene.width, scene.height);
    let what = expectation_words(scene, what);
    compare_coverage(&counts, &expected, scene.width, scene.height, outlines, &what).map_err(|mut v| {
        if let Some(picture) = &v.picture {
            let found = why::describe(scene, &frags, &picture.classes, profile.snapping.grid_bits());
            if let Err(described) = found.verdict(|_| v.message.clone()) {
                v.message = described.message;
                v.samples = described.samples;
                v.details = described.details;
            }
        }
        v
    })
}

/// What the ray cast expects of `scene`, in words: of a mesh, with `what` (which samples count
/// once); of one triangle, that it covers the samples its ray cast hits, once each.
fn expectation_words(scene: &Scene, what: &str) -> String {
    if scene.triangles.len() == 1 {
        "the ray cast of its one triangle (each sample it hits covered once, no other)".to_owned()
    } else {
        format!(
            "the ray-cast mesh of {} triangles ({what})",
            scene.triangles.len()
        )
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::oracle::ray_cast::{ray_cast, reference_cut_rounding_px};
    use crate::strategy::{clipped_mesh_scene, crossing_scene, fan_scene, mesh_scene, projected_mesh_scene};

    /// The expectation sample by sample over every triangle, without boxes, with the cut
    /// rounding evaluated per sample: what [`mesh_expectation`] computed before it skipped
    /// the samples a triangle cannot reach and set the rounding up once per triangle.
    fn direct(scene: &Scene, band: f64, relax: Relax) -> Vec<Expect> {
        let tris: Vec<_> = (0..scene.triangles.len())
            .map(|t| scene.positions_of(t))
            .collect();
        let outlines: Vec<_> = tris
            .iter()
            .map(|t| visible_outline(t, scene.width, scene.height, &scene.state))
            .collect();
        let shared = shared_edges(scene);
        let mut expected = Vec::new();
        for y in 0..scene.height {
            for x in 0..scene.width {
                let [nx, ny] = sample_ndc(scene.width, scene.height, x, y);
                let s = sample_centre(x, y);
                let near_boundary = outlines
                    .iter()
                    .zip(&shared)
                    .any(|(o, &sh)| distance_to_outline(o, s, |a, b| a.edges & b.edges & sh == 0) < band)
                    || outlines.iter().zip(&tris).zip(&shared).any(|((o, t), &sh)| {
                        let cut = |a: &OutlinePoint, b: &OutlinePoint| {
                            a.edges & b.edges == 0
                                || (relax.cut_shared_edges
                                    && a.edges & b.edges & sh != 0
                                    && (a.is_cut() || b.is_cut()))
                        };
                        let d = distance_to_outline(o, s, cut);
                        d.is_finite()
                            && d < band
                                + reference_cut_rounding_px(t, scene.width, scene.height, s, &scene.state)
                    });
                let near_cut_vertex = outlines
                    .iter()
                    .any(|o| distance_to_outline(o, s, |a, b| a.is_cut() || b.is_cut()) < band);
                let inside = tris.iter().any(|t| ray_cast(t, nx, ny, &scene.state).is_some());
                expected.push(match (near_boundary, near_cut_vertex, inside) {
                    (true, _, _) => Expect::ZeroOrOne,
                    (false, true, true) => Expect::OneOrTwo,
                    (false, _, true) => Expect::One,
                    (false, _, false) => Expect::Zero,
                });
            }
        }
        expected
    }

    fn any_scene() -> impl Strategy<Value = Scene> {
        prop_oneof![
            mesh_scene(),
            projected_mesh_scene(),
            clipped_mesh_scene(),
            crossing_scene(),
            fan_scene()
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Skipping the samples out of a triangle's reach, deciding those clearly inside or
        /// outside an unclipped one in screen space, and setting the cut rounding up once per
        /// triangle change no expectation, at the bands profiles declare and with either
        /// relaxation.
        #[test]
        fn shortcuts_change_no_expectation(
            scene in any_scene(),
            band in prop_oneof![Just(0.0), Just(1.0 / 256.0), Just(0.125), Just(1.0)],
            cuts in any::<bool>(),
        ) {
            let relax = Relax { vertices_of_three: false, cut_shared_edges: cuts };
            let (got, _) = mesh_expectation(&scene, band, relax);
            prop_assert_eq!(got, direct(&scene, band, relax));
        }
    }
}
