//! Coverage and the fill rule: watertight meshes counted per sample, exact ownership.

use refrast::{CullMode, Fragment, Profile, Rasterizer};

use super::common::{compare_sets, fragments, reference_for, same_coverage};
use super::level::{Level, NO_TIE_RULE, SHARED_EDGE_ONLY};
use super::mesh::{Relax, check_mesh_coverage};
use super::{EXACT_COVERAGE, Family, GUARD_BAND, REFERENCE_PROFILE, Rule};
use crate::oracle::facing::{Turn, snapped_variants};
use crate::oracle::raster::Point;
use crate::oracle::{brute_force, raster};
use crate::runner::{property, property_for};
use crate::scene::{Scene, clip_of};
use crate::strategy;
use crate::violation::Violation;

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Fill, "fill.mesh.exactly-once")
            .sentence("A spade triangulation of grid points and the viewport corners covers every sample exactly once.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (shared edges covered by exactly one polygon); OpenGL 4.6 §14.6.1")
            .cases(2000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::mesh_scene(), check_exactly_once_between_two),
                note: SHARED_EDGE_ONLY,
            })
            .run(|r, cfg| property(r, cfg, strategy::mesh_scene(), check_exactly_once)),
        Rule::invariant(Family::Fill, "fill.fan.exactly-once")
            .sentence("A fan around an interior vertex on a sample centre covers its interior samples exactly once.")
            .source("piglit triangle-rasterization-overdraw; Vulkan 1.4, Basic Polygon Rasterization (shared edges covered by exactly one polygon)")
            .cases(3000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::fan_scene(), check_exactly_once_between_two),
                note: SHARED_EDGE_ONLY,
            })
            .run(|r, cfg| property(r, cfg, strategy::fan_scene(), check_exactly_once)),
        Rule::invariant(Family::Fill, "fill.rotated-quad.exactly-once")
            .sentence("A rotated quad split on either diagonal covers its interior samples exactly once.")
            .source("dEQP-VK.rasterization.fill_rules.basic_quad*")
            .cases(3000)
            .run(|r, cfg| property(r, cfg, strategy::rotated_quad_scene(), check_exactly_once)),
        Rule::invariant(Family::Fill, "fill.projected-mesh.exactly-once")
            .sentence("A viewport-covering mesh with w in [0.1, 4] per vertex covers every sample exactly once.")
            .source("dEQP-VK.rasterization.fill_rules.projected")
            .cases(2000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::projected_mesh_scene(), check_exactly_once_between_two),
                note: SHARED_EDGE_ONLY,
            })
            .run(|r, cfg| property(r, cfg, strategy::projected_mesh_scene(), check_exactly_once)),
        Rule::invariant(Family::Fill, "fill.interior.matches-raycast")
            .sentence("Samples farther than the tolerance band from every edge are covered exactly when the ray through them hits the triangle.")
            .source("seed 000 (rasterization and ray casting answer one question); dEQP triangle verifier")
            .cases(5000)
            .run(|r, cfg| property(r, cfg, strategy::float_scene(), check_exactly_once)),
        Rule::exact(Family::Fill, "fill.top-left.exact")
            .sentence("Coverage of a triangle needing no clipping, in perspective and off the grid (on snap ties if it rounds them to even), equals the reference's under the same subpixel bits and fill convention.")
            .source("D3D11.3 §3.4.2.1 (top-left rule), §15.16 (16.8 snapping), §3.2.4.1 (ties to even)")
            .cases(20000)
            .needs(REFERENCE_PROFILE)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property_for(r, cfg, strategy::exact_scene, check_exactly_once),
                note: NO_TIE_RULE,
            })
            .run(|r, cfg| property_for(r, cfg, strategy::exact_scene, check_matches_reference)),
        Rule::exact(Family::Fill, "fill.guard-band.exact")
            .sentence("Coverage of a triangle reaching outside the viewport as far as the declared guard band (up to 8192 px) equals the brute-force oracle, as a guard band promises.")
            .source("D3D11.3 §15.4 (guard band); raqote #107 (overflow at large coordinates)")
            .cases(5000)
            .needs(EXACT_COVERAGE)
            .needs(GUARD_BAND)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| {
                    property_for(r, cfg, |p| strategy::guard_band_scene(p.features.guard_band), check_exactly_once)
                },
                note: NO_TIE_RULE,
            })
            .run(|r, cfg| {
                property_for(r, cfg, |p| strategy::guard_band_scene(p.features.guard_band), check_guard_band)
            }),
        Rule::exact(Family::Fill, "fill.brute-force.exact")
            .sentence("Coverage of an unclipped triangle, in perspective and off the grid (on snap ties if it rounds them to even), equals the brute-force oracle (i128 orient2d, explicit fill bias) at every pixel.")
            .source("Giesen, Triangle rasterization in practice; piglit triangle-rasterization; D3D11.3 §3.2.4.1")
            .cases(20000)
            .needs(EXACT_COVERAGE)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property_for(r, cfg, strategy::exact_scene, check_exactly_once),
                note: NO_TIE_RULE,
            })
            .run(|r, cfg| property_for(r, cfg, strategy::exact_scene, check_matches_brute_force)),
    ]
}

/// Every sample is covered as often as the ray-cast mesh says: once inside, never outside.
pub fn check_exactly_once(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    check_mesh_coverage(r, scene, "each sample inside exactly once", Relax::NONE)
}

/// [`check_exactly_once`] but for samples exactly on a vertex three or more triangles share:
/// what Vulkan's and OpenGL's exactly-once requires ([`SHARED_EDGE_ONLY`]).
pub fn check_exactly_once_between_two(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let relax = Relax {
        vertices_of_three: true,
        ..Relax::NONE
    };
    check_mesh_coverage(r, scene, "samples on shared edges exactly once", relax)
}

/// [`check_exactly_once`] with a shared edge ending at a cut vertex judged as a boundary: what
/// every specification requires of clipped shared edges ([`super::level::CUT_VERTICES`]).
pub fn check_exactly_once_cuts_apart(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let relax = Relax {
        cut_shared_edges: true,
        ..Relax::NONE
    };
    check_mesh_coverage(r, scene, "away from cut shared edges", relax)
}

/// [`check_exactly_once_cuts_apart`] and [`check_exactly_once_between_two`] at once: what
/// Vulkan and OpenGL require of a clipped mesh (cut shared edges and vertices of three aside).
pub fn check_exactly_once_between_two_cuts_apart(
    r: &mut dyn Rasterizer,
    scene: &Scene,
) -> Result<(), Violation> {
    let relax = Relax {
        vertices_of_three: true,
        cut_shared_edges: true,
    };
    check_mesh_coverage(
        r,
        scene,
        "away from cut shared edges, samples on shared edges exactly once",
        relax,
    )
}

/// Coverage bit-identical to the reference under the same profile: snapping each vertex where
/// the profile lets it snap ([`snapped_variants`]), and culling it either way where its facing
/// is unsure.
pub fn check_matches_reference(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    // Where the triangle needs clipping, the cut vertices are each implementation's own rounding.
    if !raster::unclipped(&scene.corners(0), &scene.state) {
        return Ok(());
    }
    let profile = r.profile();
    let got = fragments(r, scene)?;
    let Some(mut reference) = reference_for(&profile) else {
        return Ok(());
    };
    let want = fragments(&mut reference, scene)?;
    let verdict = compare_sets(scene, &got, &want, "the reference with the same profile");
    if verdict.is_err() {
        let bits = profile.snapping.grid_bits().unwrap_or(8);
        for variant in exact_variants(scene, &profile) {
            let mut placed = on_grid(scene, variant, bits);
            if same_coverage(&fragments(&mut reference, &placed)?, &got) {
                return Ok(());
            }
            if unsure_under_culling(scene, &profile) {
                placed.state.cull = CullMode::None;
                if got.is_empty() || same_coverage(&fragments(&mut reference, &placed)?, &got) {
                    return Ok(());
                }
            }
        }
    }
    verdict
}

/// Coverage of an unclipped triangle bit-identical to the brute-force oracle.
pub fn check_matches_brute_force(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let p = scene.corners(0);
    // The oracle knows nothing of clipping: triangles leaving the view volume are not judged here.
    if !raster::unclipped(&p, &scene.state) {
        return Ok(());
    }
    compare_brute_force(r, scene)
}

/// Coverage of a triangle inside the guard band (x/y no farther out than the profile's reach, z
/// and w inside) equal to the oracle.
pub fn check_guard_band(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let range = scene.state.depth_range;
    let reach = f64::from(r.profile().features.guard_band);
    let within = |c: f64, side: u32| (-reach..=f64::from(side) + reach).contains(&c);
    let inside = scene.positions.iter().all(|&p @ [_, _, z, w]| {
        let [x, y] = raster::project(scene.width, scene.height, p.map(f64::from));
        w > 0.0
            && raster::near_distance(range, z, w) >= 0.0
            && z <= w
            && within(x, scene.width)
            && within(y, scene.height)
    });
    if !inside {
        return Ok(());
    }
    compare_brute_force(r, scene)
}

/// The implementation's coverage of triangle 0 against the brute-force oracle's, for some way
/// the profile lets its vertices snap, culled by the snapped triangle's facing (or either way
/// where that facing is unsure).
fn compare_brute_force(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let got = fragments(r, scene)?;
    let Some(fill) = profile.fill else {
        return Ok(());
    };
    let Some(variants) = snapped_variants(&scene.corners(0), scene.width, scene.height, &profile) else {
        return Ok(());
    };
    let bits = profile.snapping.grid_bits().unwrap_or(8).min(16);
    let unsure = unsure_under_culling(scene, &profile);
    let coverage = |t: [Point; 3], culled: bool| -> Vec<Fragment> {
        if culled {
            return Vec::new();
        }
        brute_force::coverage(t, scene.width, scene.height, bits, fill)
            .into_iter()
            .map(|(x, y)| Fragment {
                x,
                y,
                front_facing: true,
                ..Fragment::default()
            })
            .collect()
    };
    let culled = |t: &[Point; 3]| {
        let turn = match brute_force::orient2d(t[0], t[1], t[2]).signum() {
            1 => Turn::Clockwise,
            -1 => Turn::CounterClockwise,
            _ => Turn::Degenerate,
        };
        turn.drawn(&scene.state) == Some(false)
    };
    let first = coverage(variants[0], culled(&variants[0]));
    let verdict = compare_sets(scene, &got, &first, "the brute-force oracle");
    if verdict.is_err() {
        let explained = variants.iter().any(|t| {
            same_coverage(&coverage(*t, culled(t)), &got)
                || (unsure && (got.is_empty() || same_coverage(&coverage(*t, false), &got)))
        });
        if explained {
            return Ok(());
        }
    }
    verdict
}

/// The snapped triangles other than refrast's own that triangle 0 may become under the
/// profile's snapping claims (ties, [`refrast::SnapAccuracy`]).
fn exact_variants(scene: &Scene, profile: &Profile) -> Vec<[Point; 3]> {
    snapped_variants(&scene.corners(0), scene.width, scene.height, profile)
        .map(|v| v.into_iter().skip(1).collect())
        .unwrap_or_default()
}

/// Whether triangle 0's facing is unsure under a cull mode: a correct implementation may then
/// draw it or cull it.
fn unsure_under_culling(scene: &Scene, profile: &Profile) -> bool {
    scene.state.cull != CullMode::None && scene.turns(profile)[0] == Turn::Unsure
}

/// The scene with triangle 0's vertices moved exactly onto the grid points `t` (in `2^-bits`
/// pixel units), each keeping its own `z` and `w`: the reference then snaps them there.
fn on_grid(scene: &Scene, t: [Point; 3], bits: u8) -> Scene {
    let mut placed = scene.clone();
    let corners = scene.corners(0);
    for (k, &i) in scene.triangles[0].iter().enumerate() {
        let [_, _, z, w] = corners[k];
        let (x, y) = (t[k].0 as i64, t[k].1 as i64);
        placed.positions[i as usize] = clip_of(scene.width, scene.height, bits, x, y, z / w, w);
    }
    placed
}
