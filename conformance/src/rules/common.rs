//! Helpers shared by the rule families: running the rasterizer, oracles over scenes, tolerances.

use std::collections::{BTreeMap, HashMap};

use refrast::{CullMode, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, SubpixelBits};

use crate::oracle::facing::snapped_variants;
use crate::oracle::outline::{OutlinePoint, distance_to_outline, visible_outline};
use crate::oracle::raster::{ndc_offset, sample_centre, sample_ndc, to_ndc, unclipped};
use crate::oracle::ray_cast::{Hit, cut_rounding_px, ray_cast, spread};
use crate::picture::{finite_outlines, scene_outlines};
use crate::scene::Scene;
use crate::violation::{Expect, Violation, compare_coverage, count_fragments};

/// The precision a profile claims: barycentrics and window depth within this of their exact
/// values (`2^-precision_bits`). Bounds derived from it: a barycentric outside `[0, 1]`, or a
/// depth outside its vertices' range, by at most this; a sum of three barycentrics off 1 by at
/// most three times this.
///
/// At the reference's 18 bits: the perspective correction `(sᵢ/wᵢ) / Σ sⱼ/wⱼ` adds only
/// positive terms, so an f32 implementation on exact edge values loses about ten ulps of 1
/// (≈ 2^-20.7); 2^-18 allows about six times that. At 14 bits (an f32 rasterizer evaluating plane
/// equations): `a + b·x + c·y` over a 128-px target cancels up to 7 of f32's 24 bits for a
/// one-pixel triangle, setup and the perspective division a few more.
#[must_use]
pub fn precision(profile: &Profile) -> f64 {
    0.5f64.powi(i32::from(profile.precision_bits.min(52)))
}

/// The rasterizer's fragments for `scene`; an error, a fragment outside the viewport or one
/// naming a primitive the draw does not have becomes a violation.
///
/// Checked here, before any rule counts coverage, because counting drops such fragments and
/// would then report a difference that is not the one that happened.
pub fn fragments(r: &mut dyn Rasterizer, scene: &Scene) -> Result<Vec<Fragment>, Violation> {
    let frags = r
        .rasterize(&scene.draw())
        .map_err(|e| Violation::new(format!("rasterize returned an error: {e}")))?;
    let (w, h) = (scene.width, scene.height);
    let outside: Vec<&Fragment> = frags.iter().filter(|f| f.x >= w || f.y >= h).collect();
    if let Some(f) = outside.first() {
        return Err(Violation::new(format!(
            "{} fragments outside the {w}×{h} viewport, the first at ({}, {}) of primitive {}",
            outside.len(),
            f.x,
            f.y,
            f.primitive
        )));
    }
    let n = scene.triangles.len();
    if let Some(f) = frags.iter().find(|f| f.primitive as usize >= n) {
        return Err(Violation::at(
            (f.x, f.y),
            format!(
                "the fragment at ({}, {}) names primitive {} of a draw of {n} triangles",
                f.x, f.y, f.primitive
            ),
        ));
    }
    Ok(frags)
}

/// The reference configured as the profile says, for exact rules: `None` without a grid of
/// 1..=8 bits and a tie rule.
#[must_use]
pub fn reference_for(profile: &Profile) -> Option<Reference> {
    let subpixel_bits = SubpixelBits::new(profile.snapping.grid_bits()?).ok()?;
    Some(Reference::new(ReferenceConfig {
        subpixel_bits,
        fill: profile.fill?,
        ..ReferenceConfig::default()
    }))
}

/// Triangle `t` as the rasterizer may draw it: each vertex at a grid point the profile lets it
/// snap to ([`snapped_variants`]), refrast's own choice first, put back into clip space at its
/// own `w` and `z` (unsnapped without a grid). Empty unless every `w > 0`.
///
/// The oracles compare against these, not the f32 input, so that rounding the input on a sliver
/// triangle does not count against the rasterizer.
#[must_use]
pub fn snapped_triangles(scene: &Scene, t: usize, profile: &Profile) -> Vec<[[f64; 4]; 3]> {
    let corners = scene.corners(t);
    let Some(bits) = profile.snapping.grid_bits() else {
        let tri = scene.positions_of(t);
        return if tri.iter().all(|v| v[3] > 0.0) {
            vec![tri]
        } else {
            Vec::new()
        };
    };
    let one = f64::from(1u32 << bits.min(16));
    let Some(variants) = snapped_variants(&corners, scene.width, scene.height, profile) else {
        return Vec::new();
    };
    variants
        .into_iter()
        .map(|v| {
            std::array::from_fn(|k| {
                let [nx, ny] = to_ndc(
                    scene.width,
                    scene.height,
                    v[k].0 as f64 / one,
                    v[k].1 as f64 / one,
                );
                let [_, _, z, w] = corners[k].map(f64::from);
                [nx * w, ny * w, z, w]
            })
        })
        .collect()
}

/// What the ray cast expects of one fragment: its barycentrics and window depth (unclamped),
/// each within a slack on top of the profile's precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Expected {
    /// Perspective-correct barycentrics.
    pub barycentric: [f64; 3],
    /// Window depth, unclamped.
    pub depth: f64,
    /// How far the barycentrics may be off besides the precision: 0 when nothing is clipped.
    pub barycentric_slack: f64,
    /// How far the depth may be off besides the precision: 0 when nothing is clipped.
    pub depth_slack: f64,
}

/// Fragments of triangle 0, each with what the ray cast expects at its sample, and where the
/// profile lets a vertex snap to more than one grid point, what it expects of the others.
pub struct RayCast {
    /// Each fragment with refrast's own expectation (the vertices snapped to nearest, even).
    pub pairs: Vec<(Fragment, Expected)>,
    /// The other snapped triangles the profile allows (none for an exact snap or a clipped
    /// triangle, whose slack already covers a grid step).
    others: Vec<[[f64; 4]; 3]>,
    width: u32,
    height: u32,
    state: refrast::DrawState,
}

impl RayCast {
    /// Whether `accepts` holds for the expectation at `f` of any other snapped triangle.
    pub fn another_snap_accepts(&self, f: &Fragment, accepts: impl Fn(&Expected) -> bool) -> bool {
        let [nx, ny] = sample_ndc(self.width, self.height, f.x, f.y);
        self.others
            .iter()
            .filter_map(|tri| ray_cast(tri, nx, ny, &self.state))
            .any(|hit| accepts(&Expected::exact(hit)))
    }
}

/// Each fragment of triangle 0 paired with what the ray cast expects at its sample.
///
/// A triangle inside the clip volume is cast exactly as drawn (snapped, [`snapped_triangles`]);
/// fragments whose ray misses (a covered sample on an edge, a hair outside in f64) are left
/// out. A triangle that may be clipped is cast unsnapped, and the slack is the ray cast's
/// [`spread`] over one grid step around the sample: the cut vertices are snapped, and every
/// vertex of the polygon may move by that much (one step whichever way the grid rounds, or the
/// band's unit without a grid). Fragments are left out where no bound exists (the box reaches
/// the plane's horizon) or where the ray cast sees the triangle neither at the sample nor at a
/// corner of the box (a covered sample there is for the coverage rules to judge).
pub fn raycast_fragments(r: &mut dyn Rasterizer, scene: &Scene) -> Result<RayCast, Violation> {
    let profile = r.profile();
    let frags = fragments(r, scene)?;
    Ok(raycast_expectations(&profile, scene, frags))
}

/// [`raycast_fragments`] for fragments already drawn: what the ray cast expects of each of
/// `frags` for a rasterizer with `profile` drawing `scene`.
#[must_use]
pub fn raycast_expectations(profile: &Profile, scene: &Scene, frags: Vec<Fragment>) -> RayCast {
    let state = scene.state;
    let (w, h) = (scene.width, scene.height);
    let mut cast = RayCast {
        pairs: Vec::new(),
        others: Vec::new(),
        width: w,
        height: h,
        state,
    };
    let Some(corners) = scene
        .triangles
        .first()
        .map(|t| t.map(|i| scene.positions[i as usize]))
    else {
        return cast;
    };
    if unclipped(&corners, state.depth_range, state.clip_far) {
        let mut tris = snapped_triangles(scene, 0, profile).into_iter();
        let Some(tri) = tris.next() else {
            return cast;
        };
        cast.others = tris.collect();
        cast.pairs = frags
            .into_iter()
            .filter(|f| f.primitive == 0)
            .filter_map(|f| {
                let [nx, ny] = sample_ndc(w, h, f.x, f.y);
                let hit = ray_cast(&tri, nx, ny, &state)?;
                Some((f, Expected::exact(hit)))
            })
            .collect();
        return cast;
    }
    let tri = scene.positions_of(0);
    let step = profile.snapping.unit_px();
    let half = ndc_offset(w, h, step, step).map(f64::abs);
    cast.pairs = frags
        .into_iter()
        .filter(|f| f.primitive == 0)
        .filter_map(|f| {
            let [nx, ny] = sample_ndc(w, h, f.x, f.y);
            // The bound speaks of a visible point within the box; where the ray cast sees none
            // at the sample or a corner, the fragment is the coverage rules' business.
            let corners = [(0.0, 0.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)];
            corners
                .iter()
                .find_map(|(sx, sy)| ray_cast(&tri, nx + sx * half[0], ny + sy * half[1], &state))?;
            let s = spread(&tri, nx, ny, half, state.depth_range)?;
            let expected = Expected {
                barycentric: s.at.barycentric,
                depth: s.at.depth,
                barycentric_slack: s.barycentric,
                depth_slack: s.depth,
            };
            Some((f, expected))
        })
        .collect();
    cast
}

/// ", allowed …" naming the slack a clipped triangle's snapped cut vertices earn, if any.
pub fn slack_note(slack: f64) -> String {
    if slack > 0.0 {
        format!(", allowed {slack:.3e} more because the clipped polygon's vertices are snapped")
    } else {
        String::new()
    }
}

impl Expected {
    /// An exact ray-cast hit: no slack.
    fn exact(hit: Hit) -> Self {
        Self {
            barycentric: hit.barycentric,
            depth: hit.depth,
            barycentric_slack: 0.0,
            depth_slack: 0.0,
        }
    }
}

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

/// Checks that a scene draws no fragment at all (triangles the eye cannot see, zero area).
pub fn check_draws_nothing(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let frags = fragments(r, scene)?;
    match frags.first() {
        None => Ok(()),
        Some(f) => Err(Violation::at(
            (f.x, f.y),
            format!(
                "{} fragments drawn where none should be, the first at {:?}",
                frags.len(),
                (f.x, f.y)
            ),
        )),
    }
}

/// Coverage as a sorted list of `(primitive, x, y)`.
#[must_use]
pub fn coverage_set(frags: &[Fragment]) -> Vec<(u32, u32, u32)> {
    let mut v: Vec<_> = frags.iter().map(|f| (f.primitive, f.x, f.y)).collect();
    v.sort_unstable();
    v
}

/// A picture-carrying violation comparing two coverages of the same scene.
pub fn compare_sets(scene: &Scene, got: &[Fragment], want: &[Fragment], what: &str) -> Result<(), Violation> {
    if coverage_set(got) == coverage_set(want) {
        return Ok(());
    }
    let counts = count_fragments(got, scene.width, scene.height);
    let want_counts = count_fragments(want, scene.width, scene.height);
    let expected: Vec<Expect> = want_counts
        .iter()
        .map(|&n| if n == 0 { Expect::Zero } else { Expect::One })
        .collect();
    match compare_coverage(
        &counts,
        &expected,
        scene.width,
        scene.height,
        scene_outlines(scene),
        what,
    ) {
        Err(v) => Err(v),
        // Same per-pixel counts but different owners: name the first sample whose owners differ.
        Ok(()) => {
            let owners = |frags: &[Fragment]| {
                let mut by_sample: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
                for f in frags {
                    by_sample.entry((f.y, f.x)).or_default().push(f.primitive);
                }
                by_sample.values_mut().for_each(|ids| ids.sort_unstable());
                by_sample
            };
            let (got, want) = (owners(got), owners(want));
            let none = Vec::new();
            let first = got
                .keys()
                .chain(want.keys())
                .filter(|k| got.get(k).unwrap_or(&none) != want.get(k).unwrap_or(&none))
                .min();
            Err(match first {
                Some(&(y, x)) => Violation::at(
                    (x, y),
                    format!(
                        "{what}: same samples covered, but by different primitives: ({x}, {y}) by {:?}, expected {:?}",
                        got.get(&(y, x)).unwrap_or(&none),
                        want.get(&(y, x)).unwrap_or(&none)
                    ),
                ),
                None => Violation::new(format!("{what}: the same fragments in another multiplicity")),
            })
        }
    }
}

/// A sample of the viewport inside triangle `t`'s visible part and farther than `margin`
/// pixels from its outline, if there is one.
pub fn deep_sample(scene: &Scene, t: usize, margin: f64) -> Option<(u32, u32)> {
    let tri = scene.positions_of(t);
    let outline = visible_outline(&tri, scene.width, scene.height, &scene.state);
    (0..scene.height)
        .flat_map(|y| (0..scene.width).map(move |x| (x, y)))
        .find(|&(x, y)| {
            let [nx, ny] = sample_ndc(scene.width, scene.height, x, y);
            distance_to_outline(&outline, sample_centre(x, y), |_, _| true) > margin
                && ray_cast(&tri, nx, ny, &scene.state).is_some()
        })
}

/// Whether triangle 0 reaches far from the viewport: a vertex at `w ≤ 0`, or one projecting
/// farther than the viewport's own width or height beyond its sides. There floating-point
/// interpolation is not bounded by any specification ([`super::level::FAR_VALUES`]).
#[must_use]
pub fn reaches_far(scene: &Scene) -> bool {
    scene.corners(0).iter().any(|&p| {
        let w = f64::from(p[3]);
        if w.is_nan() || w <= 0.0 {
            return true;
        }
        let [x, y] = crate::oracle::raster::project(scene.width, scene.height, p.map(f64::from));
        let (sw, sh) = (f64::from(scene.width), f64::from(scene.height));
        !(-sw..=2.0 * sw).contains(&x) || !(-sh..=2.0 * sh).contains(&y)
    })
}

/// Which of a fragment's values a rule judges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Values {
    /// Window depth.
    pub depth: bool,
    /// Perspective-correct barycentrics (where declared).
    pub perspective: bool,
    /// Screen-space barycentrics (where declared).
    pub screen: bool,
}

/// Every value of every fragment that `values` names (and the profile declares) is finite:
/// what every specification asks of values it does not bound ([`reaches_far`]).
pub fn check_values_finite(r: &mut dyn Rasterizer, scene: &Scene, values: Values) -> Result<(), Violation> {
    let features = r.profile().features;
    let mut found = crate::violation::Findings::new();
    for f in fragments(r, scene)? {
        let screen = (values.screen && features.screen_barycentrics)
            .then_some(f.screen_barycentric)
            .flatten();
        let finite = (!values.depth || f.depth.is_finite())
            && (!(values.perspective && features.perspective_barycentrics)
                || f.barycentric.iter().all(|b| b.is_finite()))
            && screen.is_none_or(|s| s.iter().all(|b| b.is_finite()));
        if !finite {
            found.add((f.x, f.y), || format!("{f:?} has a value that is not finite"));
        }
    }
    found.verdict(|n| {
        format!(
            "{} with a value that is not finite",
            crate::violation::plural(n, "fragment")
        )
    })
}
