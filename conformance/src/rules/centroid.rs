//! Centroid interpolation: at several samples, a triangle drawn under centroid interpolation
//! gives its fragments in a pixel barycentrics evaluated at a location inside both the pixel
//! and the triangle (every specification), one location for all of them, and under a refrast
//! claim the location D3D11.3 §3.5.5 names: the pixel centre where the triangle covers every
//! sample, else the first covered sample the mask keeps.
//!
//! The oracle is the ray cast (`oracle::ray_cast`) on each snapped triangle the profile
//! allows, through the location the barycentrics name (reconstructed on that triangle, with
//! screen weights `∝ bᵢ·wᵢ`) or through the location the rule names: no code shared with the
//! reference.

use std::collections::BTreeMap;

use refrast::{DrawState, Fragment, Rasterizer};

use super::cast::snapped_triangles;
use super::common::precision;
use super::level::{Level, NO_BARYCENTRICS};
use super::sample_depth::sample_at;
use super::samples::{positions, sample_fragments};
use super::{Family, Need, PERSPECTIVE_BARYCENTRICS, Rule, needs};
use crate::oracle::outline::segment_distance;
use crate::oracle::raster::{project, to_ndc, unclipped};
use crate::oracle::ray_cast::ray_cast;
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::strategy::{self, primitive};
use crate::violation::{Findings, Violation, plural};

/// A snapped triangle in clip space, as `snapped_triangles` gives them.
type Clip = [[f64; 4]; 3];

/// What the rules read of a case: its first triangle's snapped forms, its fragments by pixel,
/// the declared sample positions and the claimed precision.
struct Centroids {
    tris: Vec<Clip>,
    pixels: BTreeMap<(u32, u32), Vec<Fragment>>,
    positions: Vec<[u8; 2]>,
    eps: f64,
    bits: u32,
}

impl Centroids {
    /// The case's fragments of its first triangle by pixel; `None` where the rule judges
    /// nothing (no triangle, or one the view volume clips, whose cut vertices snap as the
    /// implementation chooses).
    fn of(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<Option<Self>, Violation> {
        let profile = r.profile();
        let scene = &case.scene;
        let Some(first) = scene.triangles.first() else {
            return Ok(None);
        };
        if !unclipped(&first.map(|i| scene.positions[i as usize]), &scene.state) {
            return Ok(None);
        }
        let tris = snapped_triangles(scene, 0, &profile);
        if tris.is_empty() {
            return Ok(None);
        }
        let mut pixels: BTreeMap<(u32, u32), Vec<Fragment>> = BTreeMap::new();
        for f in sample_fragments(r, case)?
            .into_iter()
            .filter(|f| f.primitive == 0)
        {
            pixels.entry((f.x, f.y)).or_default().push(f);
        }
        Ok(Some(Self {
            tris,
            pixels,
            positions: positions(r, case),
            eps: precision(&profile),
            bits: u32::from(case.samples.min(32)),
        }))
    }
}

/// The ray cast's barycentrics at `s` (pixels) on triangle `t`; `None` where the ray misses.
fn cast(t: &Clip, case: &PrimitiveScene, s: [f64; 2]) -> Option<[f64; 3]> {
    let [nx, ny] = to_ndc(case.scene.width, case.scene.height, s[0], s[1]);
    ray_cast(t, nx, ny, &case.scene.state).map(|hit| hit.barycentric)
}

/// The largest difference between a fragment's barycentrics and `want`.
fn off(f: &Fragment, want: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (f64::from(f.barycentric[k]) - want[k]).abs())
        .fold(0.0, f64::max)
}

/// Where on the screen barycentrics `b` of triangle `t` lie: screen weights `bᵢ·wᵢ`,
/// normalised (a perspective-correct weight is a screen weight over `w`, renormalised).
fn location(t: &Clip, case: &PrimitiveScene, b: [f32; 3]) -> Option<[f64; 2]> {
    let q: [f64; 3] = std::array::from_fn(|i| f64::from(b[i]) * t[i][3]);
    let sum: f64 = q.iter().sum();
    if sum.abs() < f64::MIN_POSITIVE || !sum.is_finite() {
        return None;
    }
    let v = t.map(|p| project(case.scene.width, case.scene.height, p));
    Some([0, 1].map(|c| (0..3).map(|i| q[i] / sum * v[i][c]).sum()))
}

/// The longest side of `t` on the screen, in pixels: what a barycentric error of 1 moves a
/// location by at most.
fn extent(t: &Clip, case: &PrimitiveScene) -> f64 {
    let v = t.map(|p| project(case.scene.width, case.scene.height, p));
    (0..3)
        .map(|i| {
            let j = (i + 1) % 3;
            (v[i][0] - v[j][0]).hypot(v[i][1] - v[j][1])
        })
        .fold(0.0, f64::max)
}

/// Whether `f`'s barycentrics are those of a point inside its pixel and the triangle, on some
/// snapped form of it: the location they name lies in the pixel, to within what the claimed
/// precision moves it (`eps` of a weight moves it up to the longest side times the spread of
/// `w`), and casts back to them within the precision (a location outside the triangle casts
/// no hit, or other weights); one a hair outside every form (on an edge, in f64) passes with no
/// weight below `−eps`. A sample on the pixel's border (the 16-sample pattern has some) is
/// inside.
fn inside_pixel_and_triangle(c: &Centroids, case: &PrimitiveScene, f: &Fragment) -> bool {
    let pixel = [f64::from(f.x), f64::from(f.y)];
    c.tris.iter().any(|t| {
        let Some(p) = location(t, case, f.barycentric) else {
            return false;
        };
        let moved = [0, 1].map(|k| p[k].clamp(pixel[k], pixel[k] + 1.0));
        let away = (p[0] - moved[0]).hypot(p[1] - moved[1]);
        let spread =
            t.iter().map(|v| v[3]).fold(0.0, f64::max) / t.iter().map(|v| v[3]).fold(f64::INFINITY, f64::min);
        let near = away <= 2.0 * c.eps * extent(t, case) * spread;
        near && match cast(t, case, p) {
            Some(want) => off(f, want) <= c.eps,
            None => f.barycentric.iter().all(|&b| f64::from(b) >= -c.eps),
        }
    })
}

/// Each fragment of an unclipped first triangle under centroid interpolation carries the
/// barycentrics of a point inside both its pixel and the triangle: what Vulkan, OpenGL and
/// OpenGL ES require of a centroid.
pub fn check_inside(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    match Centroids::of(r, case)? {
        Some(c) => judge_inside(&c, case),
        None => Ok(()),
    }
}

/// [`check_inside`] on what was read.
fn judge_inside(c: &Centroids, case: &PrimitiveScene) -> Result<(), Violation> {
    let mut found = Findings::new();
    for f in c.pixels.values().flatten() {
        if inside_pixel_and_triangle(c, case, f) {
            continue;
        }
        found.add((f.x, f.y), || {
            let at = location(&c.tris[0], case, f.barycentric)
                .map_or_else(String::new, |p| format!(" (a location at ({:.4}, {:.4}))", p[0], p[1]));
            format!(
                "({}, {}) sample {}: barycentrics {:?}{at} lie outside the pixel or the triangle, beyond 2^-{} of it",
                f.x,
                f.y,
                f.sample,
                f.barycentric,
                c.eps.log2().abs()
            )
        });
    }
    found.verdict(|n| {
        format!(
            "{} carry a centroid outside their pixel or their triangle",
            plural(n, "sample fragment")
        )
    })
}

/// Whether sample `s` (pixels) may be covered by some snapped form, and whether it surely is
/// by every one: inside and off every edge (a sample on an edge is the fill rule's to decide).
fn coverage(c: &Centroids, case: &PrimitiveScene, s: [f64; 2]) -> (bool, bool) {
    let (mut may, mut surely) = (false, true);
    for t in &c.tris {
        let v = t.map(|p| project(case.scene.width, case.scene.height, p));
        let on_edge = (0..3).any(|i| segment_distance(v[i], v[(i + 1) % 3], s) < 1e-9);
        let hit = cast(t, case, s).is_some();
        may |= hit || on_edge;
        surely &= hit && !on_edge;
    }
    (may, surely)
}

/// The locations a refrast centroid may be at in a pixel whose kept covered samples are
/// those of `frags`: the centre where every sample may be covered, the first kept covered
/// sample where not every one surely is; each with what the message calls it.
fn allowed(
    c: &Centroids,
    case: &PrimitiveScene,
    x: u32,
    y: u32,
    frags: &[Fragment],
) -> Vec<([f64; 2], String)> {
    let state: &DrawState = &case.scene.state;
    let emitted = frags.iter().fold(0u64, |m, f| m | 1 << f.sample.min(63));
    let (mut all_may, mut all_surely) = (true, true);
    for k in 0..c.bits as u8 {
        if state.passes_sample_mask(k) {
            let covered = emitted >> k & 1 == 1;
            all_may &= covered;
            all_surely &= covered;
        } else {
            let (may, surely) = coverage(c, case, sample_at(&c.positions, x, y, k));
            all_may &= may;
            all_surely &= surely;
        }
    }
    let mut out = Vec::new();
    if all_may {
        let why = format!("the pixel centre (all {} samples covered)", c.bits);
        out.push(([f64::from(x) + 0.5, f64::from(y) + 0.5], why));
    }
    if !all_surely && let Some(first) = frags.iter().map(|f| f.sample).min() {
        let why = format!("sample {first}, the first covered sample the mask keeps");
        out.push((sample_at(&c.positions, x, y, first), why));
    }
    out
}

/// Each pixel's fragments of an unclipped first triangle under centroid interpolation carry
/// one set of barycentrics, the ray cast's at the pixel centre where the triangle covers every
/// sample (the mask aside), else at the first covered sample the mask keeps, within the
/// claimed precision, besides lying inside the pixel and the triangle ([`check_inside`]).
pub fn check_centroid(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some(c) = Centroids::of(r, case)? else {
        return Ok(());
    };
    judge_inside(&c, case)?;
    let mut found = Findings::new();
    for (&(x, y), frags) in &c.pixels {
        let first = frags[0];
        if let Some(other) = frags
            .iter()
            .find(|f| off(f, first.barycentric.map(f64::from)) > c.eps)
        {
            found.add((x, y), || {
                format!(
                    "({x}, {y}): sample {} has barycentrics {:?} and sample {} {:?}, where a centroid is one location for the pixel",
                    first.sample, first.barycentric, other.sample, other.barycentric
                )
            });
            continue;
        }
        let places = allowed(&c, case, x, y, frags);
        let wants: Vec<(Vec<[f64; 3]>, &String)> = places
            .iter()
            .map(|(s, why)| (c.tris.iter().filter_map(|t| cast(t, case, *s)).collect(), why))
            .collect();
        // A location on an edge may cast no hit in f64: nothing there to compare with.
        if wants
            .iter()
            .any(|(casts, _)| casts.is_empty() || casts.iter().any(|&w| off(&first, w) <= c.eps))
        {
            continue;
        }
        found.add((x, y), || {
            let named: Vec<String> = wants
                .iter()
                .map(|(casts, why)| format!("{why}: {:?}", casts[0]))
                .collect();
            format!(
                "({x}, {y}): barycentrics {:?}, where the centroid is {}",
                first.barycentric,
                named.join(", or ")
            )
        });
    }
    found.verdict(|n| {
        format!(
            "{} carry other barycentrics than the triangle's at the centre where it covers every sample, else at its first covered sample the mask keeps",
            plural(n, "pixel")
        )
    })
}

/// What every specification says of centroid interpolation.
const SOURCE: &str = "Vulkan 1.4, Interpolation Decorations (\"If the Centroid decoration is used, the interpolation position used for the variable must also fall within the bounds of the primitive being rasterized\"); OpenGL 4.6 §15.1 and GLSL 4.60 §4.5 (\"a location that lies in both the pixel and in the primitive being rendered\"), OpenGL ES 3.2 §14.1; D3D11.3 §3.5.5 (Centroid Sampling of Attributes); dEQP-VK.pipeline.*.multisample_interpolation.centroid_qualifier_inside_primitive, dEQP-GLES31.functional.shaders.multisample_interpolation.interpolate_at_centroid.*";

/// What Vulkan and OpenGL leave to the implementation.
const ANY_INSIDE: &str = "Vulkan 1.4 (Interpolation Decorations) and OpenGL 4.6 / OpenGL ES 3.2 (GLSL §4.5) require only that the location lie in both the pixel and the primitive (GLSL: \"a single value may be assigned to that variable for all samples in the pixel\", not must); the centre where every sample is covered, else the first covered sample the mask keeps, and one location per pixel, are D3D11.3 §3.5.5's and refrast's";

/// The implementation honours centroid interpolation at some sample count above one.
const CENTROID: Need = needs(
    |p| p.state.centroid && !p.multisample.is_empty(),
    "no centroid interpolation at a sample count above one",
);

/// The counts above one a rasterizer declares.
fn counts_of(d: &refrast::Profile) -> Vec<u8> {
    d.sample_counts().into_iter().filter(|&n| n > 1).collect()
}

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Msaa, "msaa.bary.centroid")
            .sentence("At each declared sample count, under centroid interpolation the fragments of a triangle inside the view volume in one pixel carry one set of perspective-correct barycentrics, the ray cast's at a location inside both the pixel and the triangle: the pixel centre where the triangle covers every sample of the pixel (the sample mask aside), else its first covered sample the mask keeps, within the claimed precision.")
            .source(SOURCE)
            .cases(800)
            .needs(CENTROID)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property_for(r, cfg, centroid_draws, check_inside),
                note: ANY_INSIDE,
            })
            .d3d11(Level::NotCovered(NO_BARYCENTRICS))
            .run(|r, cfg| property_for(r, cfg, centroid_draws, check_centroid)),
    ]
}

/// Triangles in perspective inside the view volume at each declared count above one, under
/// centroid interpolation, half of them masked.
fn centroid_draws(d: &refrast::Profile) -> impl proptest::strategy::Strategy<Value = PrimitiveScene> + use<> {
    primitive::centroid(primitive::multisampled(
        strategy::perspective_inside_scene(),
        counts_of(d),
    ))
}

#[cfg(test)]
mod tests {
    use refrast::{Draw, DrawError, Fragment, Interpolation, Profile, Rasterizer, Reference};

    use super::{check_centroid, check_inside};
    use crate::scene::{PrimitiveScene, Scene};

    /// The reference drawing every centroid at the sample (`Sample`), or at the centre of the
    /// one-sample draw (`Centre`).
    struct Misplaced(Interpolation);

    impl Rasterizer for Misplaced {
        fn profile(&self) -> Profile {
            Reference::default().profile()
        }

        fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
            let mut at = draw.clone();
            at.state.interpolation = Interpolation::Sample;
            let mut frags = Reference::default().rasterize(&at)?;
            if self.0 == Interpolation::Centroid {
                let centres = Reference::default().rasterize(&Draw { samples: 1, ..at })?;
                for f in &mut frags {
                    f.barycentric = centres
                        .iter()
                        .find(|c| (c.x, c.y, c.primitive) == (f.x, f.y, f.primitive))
                        .map_or([-1.0; 3], |c| c.barycentric);
                }
            }
            Ok(frags)
        }
    }

    /// A triangle in perspective over a 16×16 target at 4 samples, under centroid.
    fn case(mask: u32) -> PrimitiveScene {
        let mut scene = Scene::new(
            16,
            16,
            vec![
                [-0.9, -0.8, 0.2, 1.0],
                [1.6, -1.2, 0.5, 2.0],
                [-0.2, 3.0, 0.9, 4.0],
            ],
            vec![[0, 1, 2]],
        );
        scene.state.interpolation = Interpolation::Centroid;
        scene.state.sample_mask = mask;
        PrimitiveScene::triangles(scene, 4)
    }

    /// The reference passes, masked or not; a value per sample lies inside the pixel and the
    /// triangle but is not one centroid; the one-sample draw's values (the centre's, or none
    /// where the centre is uncovered) fail even Vulkan's part.
    #[test]
    fn the_reference_passes_and_misplaced_centroids_fail() {
        for mask in [u32::MAX, 0b1010, 0b0100] {
            assert_eq!(check_centroid(&mut Reference::default(), &case(mask)), Ok(()));
            let per_sample = &mut Misplaced(Interpolation::Sample);
            assert_eq!(check_inside(per_sample, &case(mask)), Ok(()));
            let err = check_centroid(per_sample, &case(mask)).expect_err("a value per sample");
            assert!(err.message.contains("pixel"), "{}", err.message);
            let err =
                check_inside(&mut Misplaced(Interpolation::Centroid), &case(mask)).expect_err("the centre");
            assert!(
                err.message.contains("outside their pixel or their triangle"),
                "{}",
                err.message
            );
        }
    }
}
