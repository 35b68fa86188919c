//! Helpers shared by the rule families: running the rasterizer, oracles over scenes, tolerances.

use std::collections::BTreeMap;

use refrast::{
    DepthRange, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, SnapAccuracy, SnapRounding,
    SubpixelBits,
};

use crate::oracle::outline::{distance_to_outline, visible_outline};
use crate::oracle::raster::{sample_centre, sample_ndc};
use crate::oracle::ray_cast::ray_hits;
use crate::picture::scene_outlines;
use crate::scene::Scene;
use crate::violation::{Expect, Violation, compare_coverage, count_fragments, plural};

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
        .map_err(|e| Violation::of_draw_error("rasterize", &e))?;
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

/// Whether the screen-space barycentrics of `scene`'s triangle `primitive` are defined: every
/// vertex at `w > 0`, so that the triangle has a shape on screen. A vertex at `w ≤ 0` leaves
/// them undefined, in the reference (which gives none) and every specification; an index out
/// of range says no.
#[must_use]
pub fn screen_defined(scene: &Scene, primitive: u32) -> bool {
    scene.triangles.get(primitive as usize).is_some_and(|t| {
        t.iter()
            .all(|&i| scene.positions.get(i as usize).is_some_and(|p| p[3] > 0.0))
    })
}

/// The reference configured as the profile says, for exact rules: `None` without a grid of
/// 1..=8 bits and a tie rule. It snaps as the profile's one choice where it declares one
/// (floor, truncation), else to the nearest point, half to even: the first of the
/// [`snap_candidates`](crate::oracle::facing::snap_candidates), whose others the rules try.
#[must_use]
pub fn reference_for(profile: &Profile) -> Option<Reference> {
    let subpixel_bits = SubpixelBits::new(profile.snapping.grid_bits()?).ok()?;
    let snap_rounding = match profile.features.snap {
        SnapAccuracy::Floor => SnapRounding::Floor,
        SnapAccuracy::TowardZero => SnapRounding::TowardZero,
        SnapAccuracy::Nearest | SnapAccuracy::WithinOneStep => SnapRounding::NearestEven,
    };
    Some(Reference::new(ReferenceConfig {
        subpixel_bits,
        fill: profile.fill?,
        snap_rounding,
        ..ReferenceConfig::default()
    }))
}

/// Checks that a scene draws no fragment at all (triangles the eye cannot see, zero area).
pub fn check_draws_nothing(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let frags = fragments(r, scene)?;
    match frags.first() {
        None => Ok(()),
        Some(f) => {
            let why =
                invisible(scene, f.primitive as usize).map_or_else(String::new, |why| format!(": {why}"));
            Err(Violation::at(
                (f.x, f.y),
                format!(
                    "{} drawn where none should be, the first at {:?} by triangle {}{why}",
                    plural(frags.len(), "fragment"),
                    (f.x, f.y),
                    f.primitive
                ),
            ))
        }
    }
}

/// Why triangle `t` of `scene` draws nothing, and what draws it anyway, when the clip volume
/// says so: wholly behind the eye, wholly before the near plane or beyond the far one; `None`
/// for another reason (zero area, culling) or a triangle that is not there.
fn invisible(scene: &Scene, t: usize) -> Option<String> {
    let corners = scene
        .triangles
        .get(t)?
        .map(|i| scene.positions.get(i as usize).copied());
    let [Some(a), Some(b), Some(c)] = corners else {
        return None;
    };
    let v = [a, b, c];
    let near = |p: [f32; 4]| match scene.state.depth_range {
        DepthRange::ZeroToOne => p[2] < 0.0,
        DepthRange::NegativeOneToOne => p[2] < -p[3],
    };
    let plane = match scene.state.depth_range {
        DepthRange::ZeroToOne => "z < 0",
        DepthRange::NegativeOneToOne => "z < -w",
    };
    let listed = |f: fn([f32; 4]) -> f32| v.map(|p| format!("{:.4e}", f(p))).join(", ");
    if v.iter().all(|p| p[3] < 0.0) {
        Some(format!(
            "its vertices all have w < 0 ({}): it lies behind the eye, where dividing by w \
             mirrors it onto the screen; clip against the near plane (or drop a triangle wholly \
             outside it) before dividing",
            listed(|p| p[3])
        ))
    } else if scene.state.clip_near && v.iter().all(|&p| near(p)) {
        Some(format!(
            "its vertices all have {plane} (z = {}; w = {}): it lies wholly before the near \
             plane; clip against the near plane (or drop a triangle wholly outside it)",
            listed(|p| p[2]),
            listed(|p| p[3])
        ))
    } else if scene.state.clip_far && v.iter().all(|p| p[2] > p[3]) {
        Some(format!(
            "its vertices all have z > w (z = {}; w = {}) and the draw asks for far clipping: \
             it lies wholly beyond the far plane",
            listed(|p| p[2]),
            listed(|p| p[3])
        ))
    } else {
        None
    }
}

/// Coverage as a sorted list of `(primitive, x, y)`.
#[must_use]
pub fn coverage_set(frags: &[Fragment]) -> Vec<(u32, u32, u32)> {
    let mut v: Vec<_> = frags.iter().map(|f| (f.primitive, f.x, f.y)).collect();
    v.sort_unstable();
    v
}

/// Whether two lists of fragments cover the same samples with the same primitives, as many
/// times each: [`coverage_set`]s compared, sorted row by row, the order rasterizers emit
/// fragments in, so the sorts mostly find their input sorted already.
#[must_use]
pub fn same_coverage(a: &[Fragment], b: &[Fragment]) -> bool {
    let rows = |frags: &[Fragment]| {
        let mut v: Vec<_> = frags.iter().map(|f| (f.primitive, f.y, f.x)).collect();
        v.sort_unstable();
        v
    };
    a.len() == b.len() && rows(a) == rows(b)
}

/// A picture-carrying violation comparing two coverages of the same scene.
pub fn compare_sets(scene: &Scene, got: &[Fragment], want: &[Fragment], what: &str) -> Result<(), Violation> {
    if same_coverage(got, want) {
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
                && ray_hits(&tri, nx, ny, &scene.state)
        })
}

/// Whether triangle 0 reaches far out: a vertex whose x or y is more than [`FAR`] times the
/// largest `|w|` of the three (thousands of pixels beyond the viewport, where f32 plane equations
/// lose whole pixels and no specification bounds the error, [`super::level::FAR_VALUES`]).
/// A vertex at `w ≤ 0` alone is not far: clipping it happens in clip space, where nothing is
/// divided by it.
#[must_use]
pub fn reaches_far(scene: &Scene) -> bool {
    let corners = scene.corners(0).map(|p| p.map(f64::from));
    let w = corners.iter().map(|p| p[3].abs()).fold(0.0, f64::max);
    corners
        .iter()
        .any(|p| p[0].abs().max(p[1].abs()) > FAR * w || p.iter().any(|c| !c.is_finite()))
}

/// How many times its largest `|w|` a vertex's x or y may be before [`reaches_far`] says so:
/// NDC ±1000, 8000 px from the centre of a 16-px viewport.
pub const FAR: f64 = 1000.0;

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
