//! The vertices three or more triangles of a mesh share, where an implementation places them,
//! and the samples on or near them: what Vulkan and OpenGL leave open, and what a float
//! profile's rounding cannot decide.

use std::collections::BTreeMap;

use refrast::Profile;

use crate::oracle::facing::snap_candidates;
use crate::scene::Scene;

/// Where an implementation with `profile` may place each vertex of `scene` that three or more
/// of its triangles share, in pixels: each grid point the profile lets it snap to
/// ([`snap_candidates`]), or without a grid its exact projection; vertices at `w ≤ 0` have none.
#[must_use]
pub fn vertices_of_three(scene: &Scene, profile: &Profile) -> Vec<[f64; 2]> {
    let mut users: BTreeMap<[u32; 4], u32> = BTreeMap::new();
    for t in &scene.triangles {
        for &i in t {
            if let Some(p) = scene.positions.get(i as usize) {
                *users.entry(p.map(f32::to_bits)).or_default() += 1;
            }
        }
    }
    let (w, h) = (scene.width, scene.height);
    users
        .into_iter()
        .filter(|&(_, n)| n >= 3)
        .flat_map(|(bits, _)| {
            let p = bits.map(f32::from_bits);
            if p[3].is_nan() || p[3] <= 0.0 {
                return Vec::new();
            }
            match profile.snapping.grid_bits() {
                Some(grid) => {
                    let one = f64::from(1u32 << grid.min(16));
                    snap_candidates(p, w, h, profile)
                        .unwrap_or_default()
                        .into_iter()
                        .map(|(x, y)| [x as f64 / one, y as f64 / one])
                        .collect()
                }
                None => vec![crate::oracle::raster::project(w, h, p.map(f64::from))],
            }
        })
        .collect()
}

/// The samples lying exactly on a vertex three or more triangles of the scene share, as the
/// profile places it (snapped, or exactly projected without a grid).
pub fn samples_on_vertices_of_three(scene: &Scene, profile: &Profile) -> Vec<(u32, u32)> {
    vertices_of_three(scene, profile)
        .into_iter()
        .filter_map(|[x, y]| {
            let on = |c: f64, side: u32| {
                let c = c - 0.5;
                (c.fract() == 0.0 && (0.0..f64::from(side)).contains(&c)).then_some(c as u32)
            };
            Some((on(x, scene.width)?, on(y, scene.height)?))
        })
        .collect()
}

/// The samples within the band of a vertex three or more triangles share, for a profile with
/// no grid: its edge functions, rounded, can be exactly antisymmetric, so that a shared edge is
/// crossed alike from both sides, but around a vertex of three the rounded signs of different
/// edges need not agree, and a sample a hair from it may fall in two triangles or in none (a
/// correct f32 client's did, 6.8e-7 px from one). A grid's exact arithmetic has no such hair.
pub fn samples_near_vertices_of_three(scene: &Scene, profile: &Profile) -> Vec<(u32, u32)> {
    let band = profile.band_px();
    let mut near = Vec::new();
    for [vx, vy] in vertices_of_three(scene, profile) {
        // The sample centres around the vertex: pixel (x, y)'s is at (x + 1/2, y + 1/2).
        let (x0, y0) = ((vx - 0.5).floor(), (vy - 0.5).floor());
        for (x, y) in [(x0, y0), (x0 + 1.0, y0), (x0, y0 + 1.0), (x0 + 1.0, y0 + 1.0)] {
            let inside =
                (0.0..f64::from(scene.width)).contains(&x) && (0.0..f64::from(scene.height)).contains(&y);
            if inside && (x + 0.5 - vx).hypot(y + 0.5 - vy) < band {
                near.push((x as u32, y as u32));
            }
        }
    }
    near
}
