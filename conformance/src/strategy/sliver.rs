//! Two classes of input the other generators never reach: slivers that snapping turns over,
//! and triangles of zero area on screen that the near plane cuts.

use proptest::prelude::*;
use refrast::Profile;

use super::{GRID, side};
use crate::scene::{Scene, clip_of};

/// An unclipped sliver whose winding snapping reverses: on the profile's grid (8 bits without
/// one) its snapped area has one sign and its unsnapped area the other, and a sample lies on its
/// snapped long edge, so it covers that sample (under a tie rule owning the edge) and its facing
/// and culling show which area the rasterizer followed.
///
/// In grid units from the sample, snapped: `A = (−L, 0)`, `B = (L, 0)`, `C = (F, 1)`, twice the
/// area `2L > 0`. Unsnapped, each vertex moved by `e₀, e₁, e₂ ∈ [0.3, 0.45]` of a unit: `A` up,
/// `B` down, `C` up, so twice the area is `2L(1 − e₂ + e₀) − (e₀ + e₁)(F + L)`, below
/// `2.3L − 0.6(F + L) < 0` once `F ≥ 3L`. Then turned by one of the square's eight symmetries,
/// its vertices in any order, each vertex at its own power-of-two `w` (exact in f32), off any
/// snap tie by at least 0.05 of a unit.
pub fn flipped_sliver(profile: &Profile) -> impl Strategy<Value = Scene> + use<> {
    let bits = profile.snapping.grid_bits().unwrap_or(8).min(16);
    let unit = 1.0 / f64::from(1u32 << bits);
    (
        (3i64..12, 2.0f64..4.0),
        prop::array::uniform3(0.3f64..0.45),
        (0..8u8, 0..3usize, any::<bool>()),
        prop::array::uniform3(-1i32..=1),
        (4u32..12, 4u32..12),
        side(),
    )
        .prop_map(
            move |((l, d), e, (symmetry, rotation, reversed), ws, (px, py), s)| {
                let l_f = l as f64;
                let far = (d * l_f).ceil() + l_f;
                // Offsets in grid units: snapped grid point plus the unsnapped nudge.
                let corners = [(-l_f, 0.0, -e[0]), (l_f, 0.0, e[1]), (far, 1.0, -e[2])];
                let mut vertices = corners.map(|(x, y, nudge)| symmetric(symmetry, x, y + nudge));
                vertices.rotate_left(rotation);
                if reversed {
                    vertices.swap(1, 2);
                }
                let centre = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                let positions = vertices
                    .iter()
                    .zip(ws)
                    .map(|(&(x, y), k)| {
                        let w = 2f32.powi(k);
                        // In 1/2^16-pixel units, so the nudges survive: exact in f64 and in f32
                        // on power-of-two sides (at most 24 significant bits).
                        let fine = |c: f64, o: f64| ((c + o * unit) * f64::from(1u32 << 16)).round() as i64;
                        clip_of(s, s, 16, fine(centre.0, x), fine(centre.1, y), 0.5, w)
                    })
                    .collect();
                Scene::new(s, s, positions, vec![[0, 1, 2]])
            },
        )
}

/// `(x, y)` under the `k`-th symmetry of the square: rotations by quarter turns, then a mirror.
fn symmetric(k: u8, x: f64, y: f64) -> (f64, f64) {
    let (x, y) = match k % 4 {
        0 => (x, y),
        1 => (-y, x),
        2 => (-x, -y),
        _ => (y, -x),
    };
    if k >= 4 { (-x, y) } else { (x, y) }
}

/// A triangle of zero area on screen that the near plane cuts: every `w > 0`, the three vertices
/// projecting onto one line through points of the half-pixel lattice, one of them before the
/// near plane of either clip volume (`z/w = −1.5`). The reference decides zero area on its
/// snapped input and draws nothing; an implementation that clips first may snap the cut vertex
/// off the line and draw a sliver along it, which Vulkan allows.
pub fn zero_area_across_near() -> impl Strategy<Value = Scene> {
    let half = GRID / 2;
    let point = || (0i64..64, 0i64..64);
    (
        (point(), point()),
        prop::array::uniform3(-2i64..4),
        prop::array::uniform3(-2i32..=2),
        (0..3usize, prop::array::uniform2(0.1f32..0.9)),
        side(),
    )
        .prop_map(move |((a, b), k, ws, (before, depths), s)| {
            let (a, b) = ((a.0 * half, a.1 * half), (b.0 * half, b.1 * half));
            // On the line through a and b, at whole multiples of b − a: exact on the lattice.
            let on_line = |k: i64| (a.0 + k * (b.0 - a.0), a.1 + k * (b.1 - a.1));
            let mut depth = depths.into_iter();
            let positions = (0..3)
                .map(|i| {
                    let (x, y) = on_line(k[i]);
                    let z = if i == before {
                        -1.5
                    } else {
                        depth.next().unwrap_or(0.5)
                    };
                    clip_of(s, s, 8, x, y, z, 2f32.powi(ws[i]))
                })
                .collect();
            Scene::new(s, s, positions, vec![[0, 1, 2]])
        })
}

#[cfg(test)]
mod tests {
    use refrast::{Rasterizer, Reference, ReferenceConfig, SubpixelBits};

    use super::*;
    use crate::oracle::brute_force::orient2d;
    use crate::oracle::raster::{project, snap};
    use crate::strategy::samples;

    /// On 8- and 4-bit grids, every generated sliver's snapped and unsnapped areas have
    /// opposite signs, and none of its coordinates is within 0.05 of a unit of a snap tie.
    #[test]
    fn slivers_turn_over_when_snapped() {
        for bits in [8, 4] {
            let profile = Reference::new(ReferenceConfig {
                subpixel_bits: SubpixelBits::new(bits).expect("in range"),
                ..ReferenceConfig::default()
            })
            .profile();
            let one = f64::from(1u32 << bits);
            for scene in samples(flipped_sliver(&profile), 500) {
                let p = scene.corners(0);
                let snapped: Vec<_> = p
                    .iter()
                    .map(|&v| snap(v, scene.width, scene.height, bits).expect("projects"))
                    .collect();
                let raster = p.map(|v| project(scene.width, scene.height, v.map(f64::from)));
                let unsnapped = (raster[1][0] - raster[0][0]) * (raster[2][1] - raster[0][1])
                    - (raster[1][1] - raster[0][1]) * (raster[2][0] - raster[0][0]);
                let area = orient2d(snapped[0], snapped[1], snapped[2]);
                assert!(area != 0 && (area > 0) != (unsnapped > 0.0), "{scene:?}");
                for c in raster.iter().flatten() {
                    let frac = (c * one).fract().abs();
                    assert!((frac - 0.5).abs() > 0.05, "{c} is near a tie: {scene:?}");
                }
            }
        }
    }

    /// Every generated triangle has every w > 0, one vertex before the near plane of either
    /// volume, and its three vertices exactly on one line on screen.
    #[test]
    fn zero_area_triangles_cross_the_near_plane_on_one_line() {
        for scene in samples(zero_area_across_near(), 500) {
            let p = scene.corners(0).map(|v| v.map(f64::from));
            assert!(p.iter().all(|v| v[3] > 0.0));
            assert_eq!(p.iter().filter(|v| v[2] < -v[3]).count(), 1);
            let r = p.map(|v| project(scene.width, scene.height, v));
            let cross = (r[1][0] - r[0][0]) * (r[2][1] - r[0][1]) - (r[1][1] - r[0][1]) * (r[2][0] - r[0][0]);
            assert_eq!(cross, 0.0, "{scene:?}");
        }
    }
}
