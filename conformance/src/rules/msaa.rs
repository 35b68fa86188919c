//! Multisampling: coverage at each declared sample position, per-sample watertightness, samples
//! where the pattern puts them, per-sample depth and depth test, lines and points per sample.

use refrast::{FillConvention, Fragment, LineRule, Profile, Rasterizer};

use super::level::{Level, NO_BARYCENTRICS, NO_TIE_RULE, SHARED_EDGE_ONLY};
pub use super::sample_depth::{check_depth, check_depth_resolved, check_resolve};
use super::samples::{
    cell, cells, compare_samples, counts, endpoint_bits, expect_covered, grid, positions, sample_fragments,
    within_guard_band,
};
use super::vertices::vertices_of_three;
use super::{DEPTH_TEST, EXACT_COVERAGE, Family, PERSPECTIVE_BARYCENTRICS, Rule, needs};
use crate::oracle::facing::{Turn, snapped_variants};
use crate::oracle::outline::segment_distance;
use crate::oracle::raster::{Point, ndc_offset, project};
use crate::oracle::segment::SampleGrid;
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::scene::Scene;
use proptest::strategy::Strategy;

use crate::strategy::{self, primitive};
use crate::violation::{Expect, Violation};

/// Why only the depth buffer's samples are required under Vulkan and OpenGL.
const FRAGCOORD_Z: &str = "Vulkan (FragCoord: \"the z component of FragCoord is the interpolated depth value of the primitive\") and OpenGL 4.6 (gl_FragCoord) move only x and y to the sample under sample shading, and name no location for z, so a GPU's sample fragments, read from the shader, may carry one depth for every sample; the depth test's own values are each sample's (Vulkan, Depth Test: \"the sample's depth value z_f\"): only the depth buffer is required";

/// The implementation declares a sample count above one.
const MULTISAMPLE: super::Need = needs(|p| !p.multisample.is_empty(), "no sample count above one");
/// Lines or points at a sample count above one.
const MULTISAMPLE_AREAS: super::Need = needs(
    |p| !p.multisample.is_empty() && endpoint_bits(p).is_some() && (p.points || p.lines.is_some()),
    "no lines or points at a sample count above one",
);

/// Why diamond-exit lines at several samples are judged under Vulkan (and refrast) only.
const DIAMOND_SAMPLES: &str = "OpenGL 4.6 §14.5.4 draws every line under multisampling as the samples inside its rectangle, whatever rule it follows at one sample, and D3D11.3 §3.5.4.1 says aliased lines do not work per sample: a profile's diamond-exit lines are not judged at several samples there (its points and area lines are, in full); Vulkan's Bresenham lines cover the pixels they cover at one sample, all their samples";

/// The counts above one a rasterizer declares.
fn counts_of(d: &Profile) -> Vec<u8> {
    d.sample_counts().into_iter().filter(|&n| n > 1).collect()
}

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::exact(Family::Msaa, "msaa.coverage.exact")
            .sentence("At each declared sample count, a triangle covers exactly the samples the brute-force oracle finds at the declared sample positions under the fill convention.")
            .source("Vulkan 1.4, Multisampling (standard sample locations) and Basic Polygon Rasterization; D3D11.3 §3.5 (multisample rules)")
            .cases(2000)
            .needs(MULTISAMPLE)
            .needs(EXACT_COVERAGE)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property_for(r, cfg, |d| primitive::multisampled(triangles(), counts_of(d)), check_coverage_away_from_edges),
                note: NO_TIE_RULE,
            })
            .run(|r, cfg| property_for(r, cfg, |d| primitive::multisampled(triangles(), counts_of(d)), check_coverage_exact)),
        Rule::invariant(Family::Msaa, "msaa.mesh.exactly-once")
            .sentence("At each declared sample count, a mesh covering the viewport covers every sample exactly once.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (shared edges, per sample); dEQP-VK.rasterization.fill_rules.*multisample*")
            .cases(800)
            .needs(MULTISAMPLE)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property_for(r, cfg, |d| primitive::multisampled(strategy::mesh_scene(), counts_of(d)), check_mesh_between_two),
                note: SHARED_EDGE_ONLY,
            })
            .run(|r, cfg| property_for(r, cfg, |d| primitive::multisampled(strategy::mesh_scene(), counts_of(d)), check_mesh_once)),
        Rule::invariant(Family::Msaa, "msaa.sample.where-declared")
            .sentence("Sample k's coverage equals the one-sample coverage of the triangle moved by the pixel centre minus sample k's declared position.")
            .source("Vulkan 1.4, Multisampling (sample locations); dEQP-VK.multisample.sample_locations")
            .cases(1500)
            .needs(MULTISAMPLE)
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |p| {
                        let bits = p.snapping.grid_bits().unwrap_or(8);
                        primitive::multisampled(triangles().prop_map(move |s| primitive::on_grid(s, bits)), counts_of(p))
                    },
                    check_positions,
                )
            }),
        Rule::invariant(Family::Msaa, "msaa.depth.per-sample")
            .sentence("Each sample's depth is the triangle's screen-linear depth at that sample's position, not at the pixel's centre, within the claimed precision: in its sample fragments and in the depth buffer the depth test leaves.")
            .source("Vulkan 1.4, Basic Polygon Rasterization (the depth value z for a sample) and Depth Test (the sample's depth value z_f); D3D11.3 §3.5.1, §3.5.4")
            .cases(1000)
            .needs(MULTISAMPLE)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| {
                    property_for(r, cfg, |d| primitive::multisampled(strategy::perspective_inside_scene(), counts_of(d)), check_depth_resolved)
                },
                note: FRAGCOORD_Z,
            })
            .run(|r, cfg| {
                property_for(r, cfg, |d| primitive::multisampled(strategy::perspective_inside_scene(), counts_of(d)), check_depth)
            }),
        Rule::invariant(Family::Msaa, "msaa.bary.at-sample")
            .sentence("At each declared sample count, a sample fragment of a triangle inside the view volume carries the perspective-correct barycentrics of the ray-cast hit through its sample's declared position (not the pixel centre's), within the claimed precision: a shader input interpolated at the sample, as under sample shading.")
            .source("Vulkan 1.4, Interpolation Decorations (\"If the Sample decoration is used, the interpolation position used for the variable must be at the position of the sample being shaded\") and Sample Shading; OpenGL 4.6 §14.3.1.1 and OpenGL ES 3.2 §13.4.1 (\"each set of values is evaluated at the sample location\"); dEQP-VK.pipeline.*.multisample_interpolation.sample_qualifier*, dEQP-VK.pipeline.*.sample_locations_ext.verify_interpolation")
            .cases(1000)
            .needs(MULTISAMPLE)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |d| primitive::multisampled(strategy::perspective_inside_scene(), counts_of(d)),
                    super::sample_bary::check_barycentrics_at_samples,
                )
            }),
        Rule::invariant(Family::Msaa, "msaa.resolve.per-sample")
            .sentence("The depth and primitive buffers resolved at several samples equal the draw's sample fragments replayed through its depth test one sample at a time, each at the triangle's own depth at that sample (not the depth a fragment reports), samples within the band of an edge or where two compared depths are within precision aside.")
            .source("Vulkan 1.4, Depth Test (per sample); seed 001 (4× supersampled depth buffer)")
            .cases(500)
            .needs(MULTISAMPLE)
            .needs(DEPTH_TEST)
            .run(|r, cfg| {
                property_for(r, cfg, |d| primitive::multisampled(strategy::overlapping_scene(), counts_of(d)), check_resolve)
            }),
        Rule::invariant(Family::Msaa, "msaa.lines-points.per-sample")
            .sentence("At each declared sample count, points and rectangle or parallelogram lines cover the samples inside their shapes at the declared positions, the tolerance band aside; diamond-exit lines cover every sample of the pixels the rule gives, and no other.")
            .source("Vulkan 1.4, Basic Point Rasterization and Basic Line Segment Rasterization (per-sample coverage), Bresenham Line Segment Rasterization (\"Bresenham lines cover the same pixels regardless of the number of rasterization samples, and cover all samples in those pixels\")")
            .cases(800)
            .needs(MULTISAMPLE_AREAS)
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, areas, check_lines_points_beside_diamonds),
                note: DIAMOND_SAMPLES,
            })
            .vulkan(Level::Partly {
                part: |r, cfg| property_for(r, cfg, areas, check_lines_points_as_cts),
                note: super::point::POP_FREE,
            })
            .run(|r, cfg| property_for(r, cfg, areas, check_lines_points)),
    ]
}

/// Points and lines, each where the profile declares them (lines on and off the grid), at each
/// sample count above one it declares.
fn areas(d: &Profile) -> impl Strategy<Value = PrimitiveScene> + use<> {
    let mut kinds = Vec::new();
    if d.points {
        kinds.push(primitive::points().boxed());
    }
    if d.lines.is_some() || kinds.is_empty() {
        kinds.push(crate::strategy::reach::any_lines(d).boxed());
    }
    primitive::multisampled_primitives(proptest::strategy::Union::new(kinds), counts_of(d))
}

/// Triangles on the grid at `w = 1`, inside a 16-px corner or anywhere near the viewport.
fn triangles() -> impl proptest::strategy::Strategy<Value = Scene> {
    proptest::prop_oneof![strategy::inside_scene(), strategy::grid_scene()]
}

/// Whether the snapped triangle is culled under the scene's state.
fn culled(case: &PrimitiveScene, t: &[Point; 3]) -> bool {
    let turn = match crate::oracle::brute_force::orient2d(t[0], t[1], t[2]).signum() {
        1 => Turn::Clockwise,
        -1 => Turn::CounterClockwise,
        _ => Turn::Degenerate,
    };
    turn.drawn(&case.scene.state) == Some(false)
}

/// Per-sample expectations from the oracle for triangle 0 snapped as `t`; with `band` > 0, the
/// samples within it of an edge are not judged.
fn triangle_expectations(
    case: &PrimitiveScene,
    g: &SampleGrid<'_>,
    t: [Point; 3],
    fill: refrast::FillConvention,
    band: f64,
) -> Vec<Expect> {
    let covered = if culled(case, &t) {
        Vec::new()
    } else {
        g.triangle(t, fill)
    };
    let mut expected = expect_covered(case, &covered);
    if band > 0.0 {
        let one = f64::from(1u32 << g.bits);
        let v = t.map(|p| [p.0 as f64 / one, p.1 as f64 / one]);
        let s = t.map(|p| g.scale(p));
        let lo = (s[0].0.min(s[1].0).min(s[2].0), s[0].1.min(s[1].1).min(s[2].1));
        let hi = (s[0].0.max(s[1].0).max(s[2].0), s[0].1.max(s[1].1).max(s[2].1));
        let (xs, ys) = g.pixels_near(lo, hi);
        for y in ys {
            for x in xs.clone() {
                for (k, &[u, w]) in g.positions.iter().enumerate() {
                    let s = [
                        f64::from(x) + f64::from(u) / 16.0,
                        f64::from(y) + f64::from(w) / 16.0,
                    ];
                    if (0..3).any(|i| segment_distance(v[i], v[(i + 1) % 3], s) < band) {
                        expected[cell(case, x, y, k as u8)] = Expect::ZeroOrOne;
                    }
                }
            }
        }
    }
    expected
}

fn compare_with_oracle(r: &mut dyn Rasterizer, case: &PrimitiveScene, band: f64) -> Result<(), Violation> {
    let profile = r.profile();
    let (Some(bits), Some(fill)) = (profile.snapping.grid_bits(), profile.fill) else {
        return Ok(());
    };
    if !within_guard_band(case, &profile) {
        return Ok(());
    }
    let frags = sample_fragments(r, case)?;
    let Some(variants) = snapped_variants(
        &case.scene.corners(0),
        case.scene.width,
        case.scene.height,
        &profile,
    ) else {
        return Ok(());
    };
    let positions = positions(r, case);
    let g = grid(case, bits.min(16), &positions);
    let got = counts(case, &frags, None);
    let first = triangle_expectations(case, &g, variants[0], fill, band);
    let verdict = compare_samples(case, &got, &first, "the per-sample brute-force oracle");
    // Another way the profile may snap the vertices that explains every sample is no failure.
    if verdict.is_err()
        && variants[1..].iter().any(|&t| {
            compare_samples(case, &got, &triangle_expectations(case, &g, t, fill, band), "").is_ok()
        })
    {
        return Ok(());
    }
    verdict
}

/// Coverage per sample equals the oracle's at the declared positions.
pub fn check_coverage_exact(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    compare_with_oracle(r, case, 0.0)
}

/// [`check_coverage_exact`] for the samples farther than the band from every edge.
pub fn check_coverage_away_from_edges(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
) -> Result<(), Violation> {
    let band = r.profile().band_px();
    compare_with_oracle(r, case, band)
}

/// Every sample of the viewport once; with `vertices_aside`, samples on a mesh vertex unjudged.
fn mesh_once(r: &mut dyn Rasterizer, case: &PrimitiveScene, vertices_aside: bool) -> Result<(), Violation> {
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let (w, h) = (case.scene.width, case.scene.height);
    let mut expected = vec![Expect::One; cells(case)];
    // A sample on the viewport's left or top side lies on the mesh's outline: covered under a
    // convention owning left (top) edges, not under one owning right (bottom) edges, either way
    // without a tie rule.
    let fill = r.profile().fill;
    let owned = |left: bool, top: bool| match fill {
        None => Expect::ZeroOrOne,
        Some(f) => {
            let owns_left = matches!(f, FillConvention::TopLeft | FillConvention::BottomLeft);
            let owns_top = matches!(f, FillConvention::TopLeft | FillConvention::TopRight);
            if (!left || owns_left) && (!top || owns_top) {
                Expect::One
            } else {
                Expect::Zero
            }
        }
    };
    for y in 0..h {
        for x in 0..w {
            for (k, &[u, v]) in positions.iter().enumerate() {
                let (left, top) = (x == 0 && u == 0, y == 0 && v == 0);
                if left || top {
                    expected[cell(case, x, y, k as u8)] = owned(left, top);
                }
            }
        }
    }
    if vertices_aside {
        // Where the profile puts each vertex shared by three or more triangles, snapped.
        for [x, y] in vertices_of_three(&case.scene, &r.profile()) {
            for (k, &[u, v]) in positions.iter().enumerate() {
                let (sx, sy) = (x - f64::from(u) / 16.0, y - f64::from(v) / 16.0);
                if sx.fract() == 0.0
                    && sy.fract() == 0.0
                    && sx >= 0.0
                    && sy >= 0.0
                    && sx < f64::from(w)
                    && sy < f64::from(h)
                {
                    expected[cell(case, sx as u32, sy as u32, k as u8)] = Expect::ZeroOrOne;
                }
            }
        }
    }
    compare_samples(
        case,
        &counts(case, &frags, None),
        &expected,
        "one triangle per sample",
    )
}

/// A viewport-covering mesh covers each sample once.
pub fn check_mesh_once(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    mesh_once(r, case, false)
}

/// [`check_mesh_once`], samples on vertices (shared by three or more triangles) aside.
pub fn check_mesh_between_two(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    mesh_once(r, case, true)
}

/// Sample k of each pixel is covered exactly when the centre is, the triangle moved by
/// `centre − position(k)`; samples within the band of a moved edge aside unless coverage is exact.
pub fn check_positions(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let exact = EXACT_COVERAGE.check(&profile).is_ok();
    let band = if exact { 0.0 } else { profile.band_px() };
    if !within_guard_band(case, &profile) {
        return Ok(());
    }
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let (w, h) = (case.scene.width, case.scene.height);
    let got = counts(case, &frags, None);
    let mut expected = vec![Expect::Zero; cells(case)];
    for (k, &[u, v]) in positions.iter().enumerate() {
        let (dx, dy) = ((8.0 - f64::from(u)) / 16.0, (8.0 - f64::from(v)) / 16.0);
        let [ox, oy] = ndc_offset(w, h, dx, dy);
        let mut moved = case.scene.clone();
        for p in &mut moved.positions {
            p[0] += (ox * f64::from(p[3])) as f32;
            p[1] += (oy * f64::from(p[3])) as f32;
        }
        // Moved half a pixel, a triangle on the viewport's edge may need x/y clipping.
        if !within_guard_band(&PrimitiveScene::triangles(moved.clone(), 1), &profile) {
            return Ok(());
        }
        let centre: Vec<Fragment> = r
            .rasterize(&moved.draw())
            .map_err(|e| Violation::of_draw_error("rasterize (one sample, moved)", &e))?;
        for f in centre.iter().filter(|f| f.x < w && f.y < h) {
            let i = cell(case, f.x, f.y, k as u8);
            expected[i] = if expected[i] == Expect::Zero {
                Expect::One
            } else {
                Expect::OneOrTwo
            };
        }
        if band > 0.0 {
            for t in 0..moved.triangles.len() {
                let c = moved.positions_of(t).map(|p| project(w, h, p));
                for y in 0..h {
                    for x in 0..w {
                        let s = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                        if (0..3).any(|i| segment_distance(c[i], c[(i + 1) % 3], s) < band) {
                            expected[cell(case, x, y, k as u8)] = Expect::ZeroOrOne;
                        }
                    }
                }
            }
        }
    }
    compare_samples(
        case,
        &got,
        &expected,
        "the one-sample coverage of the triangle moved to each sample",
    )
}

/// Points and lines at several samples against their per-sample oracles: diamond-exit lines
/// bit for bit, every sample of each pixel the rule gives.
pub fn check_lines_points(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    match (case.topology, r.profile().lines) {
        (refrast::Topology::PointList, _) => super::point::check_pixel_holding(r, case),
        (_, Some(LineRule::DiamondExit)) => super::line::check_diamond_exact(r, case),
        _ => super::line::check_area(r, case),
    }
}

/// [`check_lines_points`] as Vulkan's conformance tests read point clipping
/// ([`super::point::check_pixel_holding_as_cts`]), and diamond-exit lines by Vulkan's own
/// sentence: the pixels its one-sample draw covers, every sample of them
/// ([`check_same_pixels_every_sample`]).
pub fn check_lines_points_as_cts(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    match (case.topology, r.profile().lines) {
        (refrast::Topology::PointList, _) => super::point::check_pixel_holding_as_cts(r, case),
        (_, Some(LineRule::DiamondExit)) => check_same_pixels_every_sample(r, case),
        _ => super::line::check_area(r, case),
    }
}

/// [`check_lines_points`] but for diamond-exit lines, which OpenGL and D3D11.3 do not draw
/// per sample.
pub fn check_lines_points_beside_diamonds(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
) -> Result<(), Violation> {
    match (case.topology, r.profile().lines) {
        (refrast::Topology::PointList, _) => super::point::check_pixel_holding(r, case),
        (_, Some(LineRule::DiamondExit)) => Ok(()),
        _ => super::line::check_area(r, case),
    }
}

/// Each line covers, at several samples, every sample of the pixels it covers at one and no
/// other: Vulkan decides Bresenham coverage per pixel.
pub fn check_same_pixels_every_sample(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
) -> Result<(), Violation> {
    let frags = sample_fragments(r, case)?;
    let one = PrimitiveScene {
        samples: 1,
        ..case.clone()
    };
    let single = sample_fragments(r, &one)?;
    for i in 0..case.primitive_count() as u32 {
        let mut expected = vec![Expect::Zero; cells(case)];
        for f in single.iter().filter(|f| f.primitive == i) {
            for k in 0..case.samples {
                expected[cell(case, f.x, f.y, k)] = Expect::One;
            }
        }
        let what = format!("every sample of the pixels segment {i} covers at one sample");
        compare_samples(case, &counts(case, &frags, Some(i)), &expected, &what)?;
    }
    Ok(())
}
