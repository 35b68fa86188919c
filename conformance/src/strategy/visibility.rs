//! Scenes no order of whole triangles can draw right: two triangles passing through each other,
//! and three bars overlapping in a cycle (seed 003: the painter's algorithm "cannot handle cyclic
//! or intersecting polygons").
//!
//! Both are built so that at every overlap each surface is nearer over a region several pixels
//! wide, with a depth gap far above any claimed precision a pixel away from where they meet:
//! only a per-sample depth test resolves them.

use std::f64::consts::TAU;

use proptest::prelude::*;

use crate::scene::Scene;

/// Viewport sides: wide enough that every overlap holds pixel centres on both sides.
fn side() -> impl Strategy<Value = u32> {
    prop_oneof![Just(48u32), Just(64)]
}

/// An NDC point as a clip-space vertex at `w = 1`.
fn vertex(x: f64, y: f64, z: f64) -> [f32; 4] {
    [x as f32, y as f32, z as f32, 1.0]
}

/// Two triangles around the viewport's centre: one tilted in depth, one level, crossing it.
///
/// Triangle 0 has corners at radius `r0` around `c` and depth `½ + g·(p − c)` with slope `|g|`
/// in `[0.3, 0.5]`; triangle 1, at radius `r1` around a point within 0.05 of `c`, lies at depth
/// `½ + δ` with `|δ| ≤ 0.03`. Both contain the disc of radius 0.22 around `c` (inradii of at
/// least 0.3, centres at most 0.071 apart), and the line where they meet lies within
/// `0.03/0.3 = 0.1` of `c`, so each is nearer on one side of it.
pub fn interpenetrating_scene() -> impl Strategy<Value = Scene> {
    (
        side(),
        (-0.05f64..0.05, -0.05f64..0.05),
        (0.6f64..0.9, 0.0f64..TAU, 0.3f64..0.5, 0.0f64..TAU),
        (
            0.6f64..0.9,
            0.0f64..TAU,
            (-0.05f64..0.05, -0.05f64..0.05),
            -0.03f64..0.03,
        ),
    )
        .prop_map(
            |(s, (cx, cy), (r0, phi0, slope, dir), (r1, phi1, (dx, dy), delta))| {
                // Keep |g|·r0 ≤ 0.45, so depth stays in [0.05, 0.95].
                let slope = slope.min(0.45 / r0);
                let (gx, gy) = (slope * dir.cos(), slope * dir.sin());
                let corner = |r: f64, phi: f64, k: usize, (ox, oy): (f64, f64)| {
                    let a = phi + TAU * k as f64 / 3.0;
                    (ox + r * a.cos(), oy + r * a.sin())
                };
                let mut positions = Vec::new();
                for k in 0..3 {
                    let (x, y) = corner(r0, phi0, k, (cx, cy));
                    positions.push(vertex(x, y, 0.5 + gx * (x - cx) + gy * (y - cy)));
                }
                for k in 0..3 {
                    let (x, y) = corner(r1, phi1, k, (cx + dx, cy + dy));
                    positions.push(vertex(x, y, 0.5 + delta));
                }
                Scene::new(s, s, positions, vec![[0, 1, 2], [3, 4, 5]])
            },
        )
}

/// Three bars in a pinwheel, each drawn as two triangles, each over the next where they cross.
///
/// Bar `k` runs along `u_k` (at `φ + k·120°`) on the line `p·n_k = h`, `n_k` its normal, with
/// depth `½ + a·t` at `t` along it. Bars `k` and `k + 1` cross at `t = −√3·h` on bar `k` and
/// `t = +√3·h` on bar `k + 1`, so bar `k` is nearer there by `2√3·a·h ≥ 0.12`: a cycle. The third
/// bar passes `3h` from each crossing, far outside its half-width.
pub fn cyclic_scene() -> impl Strategy<Value = Scene> {
    (
        side(),
        (-0.03f64..0.03, -0.03f64..0.03),
        (0.0f64..TAU, 0.18f64..0.28, 0.05f64..0.09, 0.2f64..0.45),
    )
        .prop_map(|(s, (cx, cy), (phi, h, half_width, a))| {
            let length = 0.85;
            let mut positions = Vec::new();
            let mut triangles = Vec::new();
            for k in 0..3 {
                let angle = phi + TAU * k as f64 / 3.0;
                let (ux, uy) = (angle.cos(), angle.sin());
                let (nx, ny) = (-uy, ux);
                let corner = |t: f64, side: f64| {
                    let off = h + side * half_width;
                    let (x, y) = (cx + off * nx + t * ux, cy + off * ny + t * uy);
                    vertex(x, y, 0.5 + a * t)
                };
                let base = positions.len() as u32;
                positions.extend([
                    corner(-length, -1.0),
                    corner(length, -1.0),
                    corner(length, 1.0),
                    corner(-length, 1.0),
                ]);
                triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
            }
            Scene::new(s, s, positions, triangles)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::oracle::raster::project;
    use crate::strategy::samples;

    /// Whether pixel centre `p` lies inside the projected triangle, and its depth there.
    fn depth_at(scene: &Scene, t: usize, p: [f64; 2]) -> Option<f64> {
        let v = scene
            .positions_of(t)
            .map(|q| project(scene.width, scene.height, q));
        let z = scene.positions_of(t).map(|q| q[2] / q[3]);
        let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        let w = [e(v[1], v[2]), e(v[2], v[0]), e(v[0], v[1])];
        let area: f64 = w.iter().sum();
        let inside = w.iter().all(|&x| x * area.signum() > 1e-9 * area.abs());
        inside.then(|| (w[0] * z[0] + w[1] * z[1] + w[2] * z[2]) / area)
    }

    /// Over every pixel centre covered by surfaces `a` and `b` (sets of triangles), how many each
    /// is nearer at by more than `gap`.
    fn wins(scene: &Scene, a: &[usize], b: &[usize], gap: f64) -> (usize, usize) {
        let mut count = (0, 0);
        for y in 0..scene.height {
            for x in 0..scene.width {
                let p = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                let near = |s: &[usize]| s.iter().find_map(|&t| depth_at(scene, t, p));
                if let (Some(za), Some(zb)) = (near(a), near(b)) {
                    if za + gap < zb {
                        count.0 += 1;
                    } else if zb + gap < za {
                        count.1 += 1;
                    }
                }
            }
        }
        count
    }

    #[test]
    fn interpenetrating_triangles_each_win_part_of_their_overlap() {
        for scene in samples(interpenetrating_scene(), 200) {
            let (a, b) = wins(&scene, &[0], &[1], 1e-3);
            assert!(a >= 3 && b >= 3, "{a} / {b} pixels: {scene:?}");
        }
    }

    #[test]
    fn cyclic_bars_each_hide_the_next_and_no_order_exists() {
        for scene in samples(cyclic_scene(), 200) {
            for k in 0..3 {
                let (this, next) = ([2 * k, 2 * k + 1], [2 * ((k + 1) % 3), 2 * ((k + 1) % 3) + 1]);
                let (a, b) = wins(&scene, &this, &next, 1e-3);
                assert!(
                    a >= 3 && b == 0,
                    "bar {k} over the next at {a}, under at {b}: {scene:?}"
                );
            }
        }
    }
}
