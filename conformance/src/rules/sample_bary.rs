//! Interpolation at the sample: at several samples a fragment is one sample of its pixel, and
//! its perspective-correct barycentrics are the triangle's at that sample's declared position,
//! as a shader's `sample`-qualified input is under sample shading, not the pixel centre's.
//!
//! The oracle is the ray cast (`oracle::ray_cast`), sent through the sample's position on each
//! snapped triangle the profile allows: no code shared with the reference.

use refrast::{Fragment, Rasterizer};

use super::cast::snapped_triangles;
use super::common::precision;
use super::sample_depth::sample_at;
use super::samples::{positions, sample_fragments};
use crate::oracle::raster::{to_ndc, unclipped};
use crate::oracle::ray_cast::ray_cast;
use crate::scene::PrimitiveScene;
use crate::violation::{Findings, Violation, plural};

/// The ray cast's barycentrics at `s` (in pixels) on each snapped triangle of `case`'s first
/// triangle; empty where every ray misses (a covered sample on an edge, a hair outside in f64).
fn cast_at(tris: &[[[f64; 4]; 3]], case: &PrimitiveScene, s: [f64; 2]) -> Vec<[f64; 3]> {
    let [nx, ny] = to_ndc(case.scene.width, case.scene.height, s[0], s[1]);
    tris.iter()
        .filter_map(|t| ray_cast(t, nx, ny, &case.scene.state))
        .map(|hit| hit.barycentric)
        .collect()
}

/// The largest difference between a fragment's barycentrics and `want`.
fn off(f: &Fragment, want: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (f64::from(f.barycentric[k]) - want[k]).abs())
        .fold(0.0, f64::max)
}

/// Each sample fragment of an unclipped first triangle carries the ray cast's perspective
/// barycentrics at its sample's declared position, within the claimed precision, for some way
/// the profile lets the vertices snap.
pub fn check_barycentrics_at_samples(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let scene = &case.scene;
    let Some(first) = scene.triangles.first() else {
        return Ok(());
    };
    // A clipped triangle's cut vertices are snapped as the implementation chooses: the
    // coverage-free question here is the sample's location, which an unclipped one answers.
    if !unclipped(&first.map(|i| scene.positions[i as usize]), &scene.state) {
        return Ok(());
    }
    let tris = snapped_triangles(scene, 0, &profile);
    if tris.is_empty() {
        return Ok(());
    }
    let eps = precision(&profile);
    let positions = positions(r, case);
    let frags = sample_fragments(r, case)?;
    let mut found = Findings::new();
    for f in frags.iter().filter(|f| f.primitive == 0) {
        let s = sample_at(&positions, f.x, f.y, f.sample);
        let wants = cast_at(&tris, case, s);
        if wants.is_empty() || wants.iter().any(|&w| off(f, w) <= eps) {
            continue;
        }
        let centre = cast_at(&tris[..1], case, [f64::from(f.x) + 0.5, f64::from(f.y) + 0.5]);
        found.add((f.x, f.y), || {
            let at_centre = match centre.first() {
                Some(&c) if off(f, c) <= eps => " (the pixel centre's)".to_owned(),
                Some(c) => format!("; the pixel centre's are {c:?}"),
                None => String::new(),
            };
            format!(
                "({}, {}) sample {} at ({:.4}, {:.4}): barycentrics {:?}{at_centre}, where the ray cast through the sample gives {:?} (off by {:.3e}, more than 2^-{})",
                f.x,
                f.y,
                f.sample,
                s[0],
                s[1],
                f.barycentric,
                wants[0],
                off(f, wants[0]),
                profile.precision_bits
            )
        });
    }
    found.verdict(|n| {
        format!(
            "{} carry other barycentrics than the triangle's at their sample's position",
            plural(n, "sample fragment")
        )
    })
}

#[cfg(test)]
mod tests {
    use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference};

    use super::check_barycentrics_at_samples;
    use crate::scene::{PrimitiveScene, Scene};

    /// The reference with every fragment's barycentrics those of its pixel's sample 0.
    struct FirstSampleBarycentrics(Reference);

    impl Rasterizer for FirstSampleBarycentrics {
        fn profile(&self) -> Profile {
            self.0.profile()
        }

        fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
            let mut frags = self.0.rasterize(draw)?;
            let firsts: Vec<Fragment> = frags.iter().filter(|f| f.sample == 0).copied().collect();
            for f in &mut frags {
                if let Some(first) = firsts
                    .iter()
                    .find(|g| (g.x, g.y, g.primitive) == (f.x, f.y, f.primitive))
                {
                    f.barycentric = first.barycentric;
                }
            }
            Ok(frags)
        }
    }

    /// A triangle in perspective over a 16×16 target at 4 samples.
    fn case() -> PrimitiveScene {
        let scene = Scene::new(
            16,
            16,
            vec![
                [-0.9, -0.8, 0.2, 1.0],
                [1.6, -1.2, 0.5, 2.0],
                [-0.2, 3.0, 0.9, 4.0],
            ],
            vec![[0, 1, 2]],
        );
        PrimitiveScene::triangles(scene, 4)
    }

    /// The reference's per-sample barycentrics pass; one value per pixel does not.
    #[test]
    fn per_sample_barycentrics_pass_and_one_per_pixel_fails() {
        assert!(check_barycentrics_at_samples(&mut Reference::default(), &case()).is_ok());
        let err = check_barycentrics_at_samples(&mut FirstSampleBarycentrics(Reference::default()), &case())
            .expect_err("sample 0's barycentrics at every sample");
        assert!(
            err.message.contains("at their sample's position"),
            "{}",
            err.message
        );
    }
}
