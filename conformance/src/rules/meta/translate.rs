//! Moves that must leave coverage alone away from edges: whole pixels, one subpixel, a larger
//! viewport.

use std::collections::BTreeSet;

use proptest::prelude::*;
use refrast::{Profile, Rasterizer, SnapAccuracy, Snapping};

use crate::oracle::outline::segment_distance;
use crate::oracle::raster::{self, sample_centre};
use crate::rules::common::{coverage_set, fragments};
use crate::scene::{Case, CaseData, Scene};
use crate::strategy;
use crate::violation::{Findings, Violation, plural};

/// A scene and a translation in whole pixels.
#[derive(Clone, Debug)]
pub struct Translated {
    /// The scene (`w = 1`).
    pub scene: Scene,
    /// Pixels right.
    pub dx: i32,
    /// Pixels down.
    pub dy: i32,
}

impl Case for Translated {
    fn reductions(&self) -> Vec<Self> {
        let (dx, dy) = (self.dx, self.dy);
        self.scene
            .reductions()
            .into_iter()
            .map(|scene| Self { scene, dx, dy })
            .collect()
    }

    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn scene_mut(&mut self) -> &mut Scene {
        &mut self.scene
    }

    fn data(&self) -> CaseData {
        CaseData {
            translate: Some([self.dx, self.dy]),
            ..CaseData::of_draw(self.scene.draw_data())
        }
    }

    fn from_data(data: &CaseData) -> Result<Self, String> {
        let [dx, dy] = data
            .translate
            .ok_or("this rule's cases move the draw: the case has no translate")?;
        if data.poison.is_some() {
            return Err("this rule's cases have no poison".into());
        }
        let scene = data.draw.triangle_scene()?;
        Ok(Self { scene, dx, dy })
    }
}

pub(super) fn translated() -> impl Strategy<Value = Translated> {
    (strategy::grid_scene(), -12i32..12, -12i32..12).prop_map(|(scene, dx, dy)| Translated { scene, dx, dy })
}

/// Triangle 0's vertices in raster space as the rasterizer places them: snapped to its grid,
/// or where they project without one; `None` when a vertex has no projection.
fn placed(scene: &Scene, snapping: Snapping) -> Option<[[f64; 2]; 3]> {
    let [a, b, c] = scene.triangles[0].map(|i| {
        let p = scene.positions[i as usize];
        match snapping.grid_bits() {
            Some(bits) => {
                let unit = 1.0 / f64::from(1u32 << bits.min(16));
                let (px, py) = raster::snap(p, scene.width, scene.height, bits)?;
                Some([px as f64 * unit, py as f64 * unit])
            }
            None => (p[3] > 0.0).then(|| raster::project(scene.width, scene.height, p.map(f64::from))),
        }
    });
    Some([a?, b?, c?])
}

/// Whether sample `(x, y)` lies within `limit` pixels of an edge of triangle 0 as placed by
/// `snapping`; true when a vertex has no projection (the triangle is then judged elsewhere).
pub(super) fn near_edge(scene: &Scene, snapping: Snapping, x: u32, y: u32, limit: f64) -> bool {
    let Some(p) = placed(scene, snapping) else {
        return true;
    };
    let s = sample_centre(x, y);
    (0..3).any(|k| segment_distance(p[k], p[(k + 1) % 3], s) <= limit)
}

/// How far from an edge two correct drawings of one triangle may differ: clipping at a
/// different viewport border snaps new vertices, moving an edge by up to the band, on either side;
/// and where the profile lets a vertex snap to either of two grid points, one more grid step.
fn clip_slack(profile: &Profile) -> f64 {
    2.0 * profile.band_px() + snap_slack(profile)
}

/// How far a vertex may snap from where the oracle's nearest-even snap puts it: nothing where
/// the profile claims exactly that, one grid step where it may round a tie either way or land
/// within one step ([`refrast::SnapAccuracy::WithinOneStep`]).
pub(super) fn snap_slack(profile: &Profile) -> f64 {
    let f = &profile.features;
    if f.snap == SnapAccuracy::Nearest && f.ties_to_even {
        0.0
    } else {
        profile.snapping.unit_px()
    }
}

/// Moving by whole pixels moves coverage alike, except near an edge.
pub fn check_translation(r: &mut dyn Rasterizer, t: &Translated) -> Result<(), Violation> {
    let s = &t.scene;
    let profile = r.profile();
    let mut moved = s.clone();
    // Exact in f32: short dyadic fractions on power-of-two viewports, and w = 1.
    let [ox, oy] = raster::ndc_offset(s.width, s.height, f64::from(t.dx), f64::from(t.dy)).map(|c| c as f32);
    for p in &mut moved.positions {
        p[0] += ox * p[3];
        p[1] += oy * p[3];
    }
    let shift = |x: u32, y: u32, dx: i32, dy: i32| -> Option<(u32, u32)> {
        let (x, y) = (i64::from(x) + i64::from(dx), i64::from(y) + i64::from(dy));
        (x >= 0 && y >= 0 && x < i64::from(s.width) && y < i64::from(s.height))
            .then_some((x as u32, y as u32))
    };
    let want: BTreeSet<(u32, u32)> = fragments(r, s)?
        .iter()
        .filter_map(|f| shift(f.x, f.y, t.dx, t.dy))
        .collect();
    // Only samples whose pre-image is inside the viewport can be compared.
    let got: BTreeSet<(u32, u32)> = fragments(r, &moved)?
        .iter()
        .filter(|f| shift(f.x, f.y, -t.dx, -t.dy).is_some())
        .map(|f| (f.x, f.y))
        .collect();
    let mut found = Findings::new();
    for &(x, y) in want.symmetric_difference(&got) {
        if !near_edge(&moved, profile.snapping, x, y, clip_slack(&profile)) {
            let how = if got.contains(&(x, y)) { "gained" } else { "lost" };
            found.add((x, y), || format!("{how} {:?}", (x, y)));
        }
    }
    found.verdict(|n| {
        format!(
            "moved by ({}, {}) px, the triangle changed {} away from every edge",
            t.dx,
            t.dy,
            plural(n, "sample")
        )
    })
}

/// Moving by one subpixel changes only samples near an edge.
pub fn check_subpixel_translation(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let unit = profile.snapping.unit_px();
    let mut moved = scene.clone();
    let step = raster::ndc_offset(scene.width, scene.height, unit, 0.0)[0] as f32;
    for p in &mut moved.positions {
        p[0] += step * p[3];
    }
    let (a, b) = (fragments(r, scene)?, fragments(r, &moved)?);
    let (sa, sb) = (coverage_set(&a), coverage_set(&b));
    let changed = sa
        .iter()
        .filter(|p| !sb.contains(p))
        .chain(sb.iter().filter(|p| !sa.contains(p)));
    let Some(pts) = placed(scene, profile.snapping) else {
        return Ok(());
    };
    let limit = unit + profile.band_px() + snap_slack(&profile);
    let mut found = Findings::new();
    for &(_, x, y) in changed {
        let s = sample_centre(x, y);
        let d = (0..3)
            .map(|k| segment_distance(pts[k], pts[(k + 1) % 3], s))
            .fold(f64::INFINITY, f64::min);
        if d > limit + unit {
            found.add((x, y), || format!("{:?}, {d:.4} px from every edge", (x, y)));
        }
    }
    found.verdict(|n| {
        format!(
            "moving {} right changed {} away from every edge",
            step_words(&profile),
            plural(n, "sample")
        )
    })
}

/// One step of the profile's unit in words: a subpixel of its grid, or without a grid the
/// float tolerance's unit in pixels (a float profile has no subpixels).
fn step_words(profile: &Profile) -> String {
    match profile.snapping.grid_bits() {
        Some(bits) => format!("one subpixel (1/{} px)", 1u32 << bits.min(16)),
        None => format!("{} px (the float tolerance's unit)", profile.snapping.unit_px()),
    }
}

/// A viewport twice as large changes coverage only near an edge.
pub fn check_viewport_neutral(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let mut big = scene.clone();
    big.width *= 2;
    big.height *= 2;
    for p in &mut big.positions {
        // The same raster position in a viewport twice as large.
        let [x, y, _, w] = p.map(f64::from);
        let [rx, ry] = raster::to_raster(scene.width, scene.height, x / w, y / w);
        let [nx, ny] = raster::to_ndc(big.width, big.height, rx, ry);
        p[0] = (nx * w) as f32;
        p[1] = (ny * w) as f32;
    }
    let small: BTreeSet<(u32, u32)> = fragments(r, scene)?.iter().map(|f| (f.x, f.y)).collect();
    let large: BTreeSet<(u32, u32)> = fragments(r, &big)?
        .iter()
        .filter(|f| f.x < scene.width && f.y < scene.height)
        .map(|f| (f.x, f.y))
        .collect();
    let mut found = Findings::new();
    for &(x, y) in small.symmetric_difference(&large) {
        if !near_edge(scene, profile.snapping, x, y, clip_slack(&profile)) {
            let how = if large.contains(&(x, y)) { "gains" } else { "loses" };
            found.add((x, y), || format!("{how} {:?}", (x, y)));
        }
    }
    found.verdict(|n| {
        format!(
            "in a viewport twice as large the triangle changes {} away from every edge",
            plural(n, "sample")
        )
    })
}
