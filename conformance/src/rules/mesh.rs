//! What a mesh should cover, sample by sample: once inside, never outside, either within the
//! tolerance band of a boundary or a cut, and what a cull mode or a specification leaves open.

use std::collections::HashMap;

use refrast::{CullMode, Profile, Rasterizer};

use super::common::fragments;
use crate::oracle::outline::{OutlinePoint, distance_to_outline, visible_outline};
use crate::oracle::raster::{sample_centre, sample_ndc};
use crate::oracle::ray_cast::{cut_rounding_px, ray_cast};
use crate::picture::finite_outlines;
use crate::scene::Scene;
use crate::violation::{Expect, Violation, compare_coverage, count_fragments};

/// Ray-cast expectations for a scene whose triangles do not overlap (one triangle, or a mesh).
///
/// A sample inside some triangle should be covered exactly once, one outside all should not
/// be covered, except within `band` pixels of an outline segment that is not a shared edge:
/// the mesh boundary and the cuts made by clip planes (there, any count is accepted: a cut
/// vertex snapped over a neighbour's sample makes it count twice); cuts are widened by how far
/// an f32 clipper may move them ([`cut_rounding_px`]). Shared edges get no band,
/// so a crack along them is caught exactly, and so is an overlap, except within the band of a
/// shared edge ending at a cut vertex, where one or two is right ([`Expect::OneOrTwo`]).
#[must_use]
pub fn mesh_expectation(scene: &Scene, band: f64) -> (Vec<Expect>, Vec<Vec<[f64; 2]>>) {
    mesh_expectation_with(scene, band, Relax::NONE)
}

/// What a coverage check leaves to the implementation beyond refrast's conventions, for a
/// specification that requires less ([`super::level::Level::Partly`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Relax {
    /// A sample exactly on a vertex shared by three or more triangles may be covered any number
    /// of times: Vulkan's and OpenGL's exactly-once speaks of two polygons on either side of
    /// an edge ([`super::level::SHARED_EDGE_ONLY`]).
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

/// [`mesh_expectation`], leaving to the implementation what `relax` says.
#[must_use]
pub fn mesh_expectation_with(scene: &Scene, band: f64, relax: Relax) -> (Vec<Expect>, Vec<Vec<[f64; 2]>>) {
    // Shared means identical endpoints (Vulkan's wording), whatever the vertex indices.
    let key = |i: u32| scene.positions[i as usize].map(f32::to_bits);
    let edge = |t: &[u32; 3], k: usize| {
        let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
        if a <= b { (a, b) } else { (b, a) }
    };
    let mut edge_use: HashMap<([u32; 4], [u32; 4]), u32> = HashMap::new();
    for t in &scene.triangles {
        for k in 0..3 {
            *edge_use.entry(edge(t, k)).or_default() += 1;
        }
    }
    let tris: Vec<[[f64; 4]; 3]> = (0..scene.triangles.len())
        .map(|t| scene.positions_of(t))
        .collect();
    let outlines: Vec<Vec<OutlinePoint>> = tris
        .iter()
        .map(|t| visible_outline(t, scene.width, scene.height, &scene.state))
        .collect();
    let shared: Vec<u8> = scene
        .triangles
        .iter()
        .map(|t| {
            (0..3)
                .filter(|&k| edge_use[&edge(t, k)] > 1)
                .fold(0u8, |mask, k| mask | (1 << k))
        })
        .collect();
    let mut expected = Vec::with_capacity(scene.width as usize * scene.height as usize);
    for y in 0..scene.height {
        for x in 0..scene.width {
            let [nx, ny] = sample_ndc(scene.width, scene.height, x, y);
            let s = sample_centre(x, y);
            let near_boundary = outlines.iter().zip(&shared).any(|(o, &sh)| {
                // Segments not lying on a shared input edge: the boundary and the cuts.
                distance_to_outline(o, s, |a, b| a.edges & b.edges & sh == 0) < band
            }) || outlines.iter().zip(&tris).zip(&shared).any(|((o, t), &sh)| {
                // Cuts by a plane also move by an f32 clipper's rounding; so, relaxed, does a
                // shared edge ending at one.
                let cut = |a: &OutlinePoint, b: &OutlinePoint| {
                    a.edges & b.edges == 0
                        || (relax.cut_shared_edges
                            && a.edges & b.edges & sh != 0
                            && (a.is_cut() || b.is_cut()))
                };
                let d = distance_to_outline(o, s, cut);
                d.is_finite() && d < band + cut_rounding_px(t, scene.width, scene.height, s, &scene.state)
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
    if relax.vertices_of_three {
        for (x, y) in samples_on_vertices_of_three(scene) {
            expected[(y * scene.width + x) as usize] = Expect::ZeroOrOne;
        }
    }
    (expected, finite_outlines(&outlines))
}

/// The samples lying exactly on a vertex (as drawn, `w > 0`) that three or more triangles of
/// the scene share.
fn samples_on_vertices_of_three(scene: &Scene) -> Vec<(u32, u32)> {
    let mut users: HashMap<[u32; 4], u32> = HashMap::new();
    for t in &scene.triangles {
        for &i in t {
            if let Some(p) = scene.positions.get(i as usize) {
                *users.entry(p.map(f32::to_bits)).or_default() += 1;
            }
        }
    }
    users
        .into_iter()
        .filter(|&(_, n)| n >= 3)
        .filter_map(|(bits, _)| {
            let p = bits.map(f32::from_bits).map(f64::from);
            if p[3] <= 0.0 {
                return None;
            }
            let [x, y] = crate::oracle::raster::project(scene.width, scene.height, p).map(|c| c - 0.5);
            let on = |c: f64, side: u32| c.fract() == 0.0 && (0.0..f64::from(side)).contains(&c);
            (on(x, scene.width) && on(y, scene.height)).then_some((x as u32, y as u32))
        })
        .collect()
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
        return mesh_expectation_with(scene, band, relax);
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
    let (with, outlines) = mesh_expectation_with(&keeping(true), band, relax);
    if drawn.iter().all(Option::is_some) {
        return (with, outlines);
    }
    let (without, _) = mesh_expectation_with(&keeping(false), band, relax);
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
/// `relax` says.
pub fn check_mesh_coverage(
    r: &mut dyn Rasterizer,
    scene: &Scene,
    what: &str,
    relax: Relax,
) -> Result<(), Violation> {
    let profile = r.profile();
    let frags = fragments(r, scene)?;
    let (expected, outlines) = drawn_expectation(scene, &profile, profile.band_px(), relax);
    let counts = count_fragments(&frags, scene.width, scene.height);
    compare_coverage(&counts, &expected, scene.width, scene.height, outlines, what)
}
