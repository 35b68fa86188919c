//! Procedural meshes like the labs' (seed 004's plane, star, text and torus), plus a sphere and a box.
//!
//! Every shape is indexed with shared vertices along its interior edges (adjacent triangles
//! share corners by index, so the meshes show double coverage or cracks at shared edges), has
//! per-vertex colours that vary across it, unit outward normals, and is centred on the origin
//! within about `[-1, 1]³`. Flat shapes lie in `z = 0` and face `-z`: a camera at `(0, 0, -3)`
//! looking towards `+z` sees their front.
//!
//! Winding: triangles turn counter-clockwise seen from outside, so they are front faces under
//! refrast's default [`refrast::FrontFace::CounterClockwise`]. refrast's world is left-handed
//! (x right, y up, z into the screen), so for a front face `(a, b, c)` the outward normal is
//! `(c - a) × (b - a)` with the usual cross product ([`outward`]).
//!
//! Counts are clamped, floats are checked: segment and subdivision counts outside their range
//! are clamped into it (at most [`MAX_DIVISIONS`], so indices never overflow `u32`), text is cut
//! at [`MAX_TEXT_CHARS`]; a torus or cuboid with non-finite or inverted sizes is a [`ShapeError`].

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};
use refrast::pipeline::{Mesh, Vertex};

/// The most subdivisions, segments, rings or star points any shape takes (more are clamped).
pub const MAX_DIVISIONS: u32 = 1024;

/// The most characters [`text`] draws (the rest are dropped).
pub const MAX_TEXT_CHARS: usize = 1024;

/// Sizes a shape cannot be built from.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// A torus needs finite radii with `0 < minor < major` (else it self-intersects or is empty).
    #[error("a torus needs finite radii with 0 < minor < major, got major {major} and minor {minor}")]
    TorusRadii {
        /// The ring's radius.
        major: f32,
        /// The tube's radius.
        minor: f32,
    },
    /// A cuboid needs finite corners.
    #[error("a cuboid needs finite corners, got {min} and {max}")]
    CuboidCorners {
        /// One corner.
        min: Vec3,
        /// The opposite corner.
        max: Vec3,
    },
}

/// The outward normal direction (not normalised) of a front-facing triangle `(a, b, c)`:
/// refrast's world is left-handed, so counter-clockwise seen from outside is `(c - a) × (b - a)`.
#[must_use]
pub fn outward(a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    (c - a).cross(b - a)
}

/// A saturated, light colour from a hue in turns (`0` red, `1/3` green, `2/3` blue): cosine
/// ramps, smooth and pleasant enough to show interpolation.
fn hue(turns: f32) -> Vec3 {
    let channel = |offset: f32| 0.55 + 0.4 * (TAU * (turns - offset)).cos();
    Vec3::new(channel(0.0), channel(1.0 / 3.0), channel(2.0 / 3.0))
}

/// A vertex with all its attributes, opaque.
fn vertex(position: Vec3, rgb: Vec3, normal: Vec3, uv: Vec2) -> Vertex {
    Vertex {
        position,
        color: rgb.extend(1.0),
        normal,
        uv,
    }
}

/// The two triangles of quad `a b c d`, listed counter-clockwise seen from its front, split
/// along `a c`.
fn quad([a, b, c, d]: [u32; 4]) -> [[u32; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

/// Texture coordinates of a point of the flat shapes: `[-1, 1]²` onto `[0, 1]²`, v up.
fn flat_uv(x: f32, y: f32) -> Vec2 {
    Vec2::new((x + 1.0) / 2.0, (y + 1.0) / 2.0)
}

/// A square `[-1, 1]²` in `z = 0`, facing `-z`, cut into `n × n` quads of two triangles each
/// (`n` clamped to `1..=MAX_DIVISIONS`); colours blend four corner hues.
#[must_use]
pub fn plane(subdivisions: u32) -> Mesh {
    let n = subdivisions.clamp(1, MAX_DIVISIONS);
    let side = n + 1;
    let corner = [hue(0.0), hue(0.15), hue(0.45), hue(0.75)];
    let mut vertices = Vec::with_capacity((side * side) as usize);
    for j in 0..side {
        for i in 0..side {
            let (s, t) = (i as f32 / n as f32, j as f32 / n as f32);
            let (x, y) = (2.0 * s - 1.0, 2.0 * t - 1.0);
            let bottom = corner[0].lerp(corner[1], s);
            let top = corner[3].lerp(corner[2], s);
            vertices.push(vertex(
                Vec3::new(x, y, 0.0),
                bottom.lerp(top, t),
                Vec3::NEG_Z,
                flat_uv(x, y),
            ));
        }
    }
    let at = |i: u32, j: u32| j * side + i;
    let triangles = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .flat_map(|(i, j)| quad([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]))
        .collect();
    Mesh { vertices, triangles }
}

/// A flat star in `z = 0` facing `-z`: a centre vertex and `2 · points` rim vertices at radii
/// 1 (tips, one hue each) and 0.4 alternately, fanned from the centre (`points` clamped to
/// `3..=MAX_DIVISIONS`): many thin triangles sharing one vertex.
#[must_use]
pub fn star(points: u32) -> Mesh {
    let p = points.clamp(3, MAX_DIVISIONS);
    let rim = 2 * p;
    let mut vertices = vec![vertex(Vec3::ZERO, Vec3::ONE, Vec3::NEG_Z, flat_uv(0.0, 0.0))];
    for k in 0..rim {
        let angle = PI / 2.0 + PI * k as f32 / p as f32;
        let (radius, rgb) = if k % 2 == 0 {
            (1.0, hue(k as f32 / rim as f32))
        } else {
            (0.4, hue(k as f32 / rim as f32).lerp(Vec3::ONE, 0.5))
        };
        let (x, y) = (radius * angle.cos(), radius * angle.sin());
        vertices.push(vertex(Vec3::new(x, y, 0.0), rgb, Vec3::NEG_Z, flat_uv(x, y)));
    }
    // Angles grow counter-clockwise with x right and y up, as the default camera sees them.
    let triangles = (0..rim).map(|k| [0, 1 + k, 1 + (k + 1) % rim]).collect();
    Mesh { vertices, triangles }
}

/// Seed 003's cases for the painter's algorithm: on the left three bars in a pinwheel, each over
/// the next where they cross (a cycle), on the right two triangles passing through each other.
/// No order of whole triangles draws either right; a depth buffer does.
#[must_use]
pub fn overlaps() -> Mesh {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let mut quad = |corners: [Vec3; 4], rgb: Vec3| {
        let base = vertices.len() as u32;
        vertices.extend(corners.map(|p| vertex(p, rgb, Vec3::NEG_Z, flat_uv(p.x, p.y))));
        triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    };
    // Bar k along u_k on the line p·n_k = h, depth growing along it: where bars k and k + 1
    // cross, bar k is at t = −√3·h and bar k + 1 at +√3·h, so bar k is the nearer.
    let (centre, h, half_width, length, slope) = (Vec3::new(-1.2, 0.0, 0.0), 0.25, 0.12, 1.0, 0.4);
    for k in 0..3 {
        let angle = PI / 2.0 + TAU * k as f32 / 3.0;
        let u = Vec3::new(angle.cos(), angle.sin(), 0.0);
        let n = Vec3::new(-u.y, u.x, 0.0);
        let at = |t: f32, side: f32| centre + n * (h + side * half_width) + u * t + Vec3::Z * (slope * t);
        quad(
            [
                at(-length, -1.0),
                at(length, -1.0),
                at(length, 1.0),
                at(-length, 1.0),
            ],
            hue(k as f32 / 3.0),
        );
    }
    // A level triangle and one tilted through it along x.
    let right = Vec3::new(1.2, 0.0, 0.0);
    let triangle = |tilt: f32, turn: f32| {
        [0.0f32, 1.0, 2.0].map(|k| {
            let a = PI / 2.0 + turn + TAU * k / 3.0;
            let p = Vec3::new(a.cos(), a.sin(), 0.0);
            right + p + Vec3::Z * (tilt * p.x)
        })
    };
    for (k, (tilt, turn)) in [(0.0, 0.0), (0.8, PI)].into_iter().enumerate() {
        let base = vertices.len() as u32;
        let rgb = hue(0.15 + 0.5 * k as f32);
        vertices.extend(triangle(tilt, turn).map(|p| vertex(p, rgb, Vec3::NEG_Z, flat_uv(p.x, p.y))));
        triangles.push([base, base + 1, base + 2]);
    }
    Mesh { vertices, triangles }
}

/// The 8×8 glyph of `ch` from `font8x8` (basic, Latin, Greek, blocks, box drawing), `?` for any
/// other character; row 0 is the top, bit 0 the leftmost column. Public for the viewer's status
/// line, which writes in the same font.
#[must_use]
pub fn glyph(ch: char) -> [u8; 8] {
    use font8x8::{BASIC_FONTS, BLOCK_FONTS, BOX_FONTS, GREEK_FONTS, LATIN_FONTS, UnicodeFonts};
    BASIC_FONTS
        .get(ch)
        .or_else(|| LATIN_FONTS.get(ch))
        .or_else(|| GREEK_FONTS.get(ch))
        .or_else(|| BLOCK_FONTS.get(ch))
        .or_else(|| BOX_FONTS.get(ch))
        .or_else(|| BASIC_FONTS.get('?'))
        .unwrap_or([0xff; 8])
}

/// Flat text in `z = 0` facing `-z`: each lit cell of the `font8x8` glyphs is a quad, all on one
/// vertex grid so that neighbouring cells share their edges exactly; scaled so the string spans
/// `[-1, 1]` in x, centred in y; a rainbow from left to right. Only the corners of lit cells
/// are vertices (a point-mode draw shows no stray points); characters past [`MAX_TEXT_CHARS`]
/// are dropped, and an empty or blank string gives an empty mesh.
#[must_use]
pub fn text(s: &str) -> Mesh {
    let glyphs: Vec<[u8; 8]> = s.chars().take(MAX_TEXT_CHARS).map(glyph).collect();
    let columns = 8 * glyphs.len() as u32;
    let cell = 2.0 / columns.max(1) as f32;
    let lit = |i: u32, j: u32| glyphs[(i / 8) as usize][j as usize] & (1 << (i % 8)) != 0;
    // One grid of (columns + 1) × 9 corners, row 0 on top; a corner becomes a vertex when first used.
    let mut index = vec![None; (columns as usize + 1) * 9];
    let mut vertices = Vec::new();
    let mut corner = |i: u32, j: u32| -> u32 {
        let slot = &mut index[j as usize * (columns as usize + 1) + i as usize];
        *slot.get_or_insert_with(|| {
            let (x, y) = (-1.0 + cell * i as f32, cell * (4.0 - j as f32));
            let rgb = hue(i as f32 / columns as f32 * 0.8).lerp(Vec3::splat(0.2), j as f32 / 16.0);
            vertices.push(vertex(Vec3::new(x, y, 0.0), rgb, Vec3::NEG_Z, flat_uv(x, y)));
            vertices.len() as u32 - 1
        })
    };
    let mut triangles = Vec::new();
    for j in 0..8 {
        for i in (0..columns).filter(|&i| lit(i, j)) {
            // Row j runs down the screen: its lower corners are on grid row j + 1.
            let corners = [
                corner(i, j + 1),
                corner(i + 1, j + 1),
                corner(i + 1, j),
                corner(i, j),
            ];
            triangles.extend(quad(corners));
        }
    }
    Mesh { vertices, triangles }
}

/// A torus around the z axis (its hole faces the default camera): ring radius `major`, tube
/// radius `minor`, `segments` around the ring and `rings` around the tube (both clamped to
/// `3..=MAX_DIVISIONS`). The seams share vertices, so it is watertight; uv is
/// `(around the ring, around the tube)`, and across each seam it runs back to 0 (a texture
/// shows squeezed in the last strip). It fits `[-1, 1]³` when `major + minor ≤ 1`.
pub fn torus(major: f32, minor: f32, segments: u32, rings: u32) -> Result<Mesh, ShapeError> {
    if !(major.is_finite() && minor.is_finite() && 0.0 < minor && minor < major) {
        return Err(ShapeError::TorusRadii { major, minor });
    }
    let (s, r) = (segments.clamp(3, MAX_DIVISIONS), rings.clamp(3, MAX_DIVISIONS));
    let mut vertices = Vec::with_capacity((s * r) as usize);
    for i in 0..s {
        let theta = TAU * i as f32 / s as f32;
        let radial = Vec3::new(theta.cos(), theta.sin(), 0.0);
        for j in 0..r {
            let phi = TAU * j as f32 / r as f32;
            let normal = radial * phi.cos() + Vec3::Z * phi.sin();
            let rgb = hue(i as f32 / s as f32).lerp(Vec3::splat(0.15), 0.35 * (1.0 - phi.cos()));
            let uv = Vec2::new(i as f32 / s as f32, j as f32 / r as f32);
            vertices.push(vertex(radial * major + normal * minor, rgb, normal, uv));
        }
    }
    let at = |i: u32, j: u32| (i % s) * r + j % r;
    // Around the tube first, then along the ring: counter-clockwise seen from outside.
    let triangles = (0..s)
        .flat_map(|i| (0..r).map(move |j| (i, j)))
        .flat_map(|(i, j)| quad([at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)]))
        .collect();
    Ok(Mesh { vertices, triangles })
}

/// A unit sphere with poles on the y axis: `segments` around (clamped to `3..=MAX_DIVISIONS`)
/// and `rings` from pole to pole (clamped to `2..=MAX_DIVISIONS`); one vertex per pole and
/// shared seam vertices make it watertight. Colours follow the normal; uv is
/// `(longitude, latitude)` with the same seam as [`torus`].
#[must_use]
pub fn sphere(segments: u32, rings: u32) -> Mesh {
    let (s, r) = (segments.clamp(3, MAX_DIVISIONS), rings.clamp(2, MAX_DIVISIONS));
    let point = |normal: Vec3, uv: Vec2| vertex(normal, 0.55 + 0.4 * normal, normal, uv);
    let mut vertices = vec![point(Vec3::Y, Vec2::new(0.5, 1.0))];
    for k in 1..r {
        let phi = PI * k as f32 / r as f32;
        for i in 0..s {
            let theta = TAU * i as f32 / s as f32;
            let normal = Vec3::new(phi.sin() * theta.cos(), phi.cos(), phi.sin() * theta.sin());
            vertices.push(point(
                normal,
                Vec2::new(i as f32 / s as f32, 1.0 - k as f32 / r as f32),
            ));
        }
    }
    let south = vertices.len() as u32;
    vertices.push(point(Vec3::NEG_Y, Vec2::new(0.5, 0.0)));
    // Latitude ring k (1..r), segment i; rings wrap at the seam.
    let at = |k: u32, i: u32| 1 + (k - 1) * s + i % s;
    let mut triangles = Vec::with_capacity((2 * s * (r - 1)) as usize);
    triangles.extend((0..s).map(|i| [0, at(1, i), at(1, i + 1)]));
    for k in 1..r - 1 {
        triangles.extend((0..s).flat_map(|i| quad([at(k, i), at(k + 1, i), at(k + 1, i + 1), at(k, i + 1)])));
    }
    triangles.extend((0..s).map(|i| [at(r - 1, i), south, at(r - 1, i + 1)]));
    Mesh { vertices, triangles }
}

/// An axis-aligned box between two corners (in any order): 6 faces of 2 triangles, 4 vertices
/// each (hard edges: face normals, one colour per face, uv `[0, 1]²` per face).
pub fn cuboid(min: Vec3, max: Vec3) -> Result<Mesh, ShapeError> {
    if !(min.is_finite() && max.is_finite()) {
        return Err(ShapeError::CuboidCorners { min, max });
    }
    let (lo, size) = (min.min(max), (max - min).abs());
    // Each face: its outward normal and the edges s, t with t × s = normal, so that
    // a, a + s, a + s + t, a + t turns counter-clockwise seen from outside.
    let faces = [
        (Vec3::NEG_Z, Vec3::X, Vec3::Y),
        (Vec3::Z, Vec3::Y, Vec3::X),
        (Vec3::NEG_X, Vec3::Y, Vec3::Z),
        (Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::NEG_Y, Vec3::Z, Vec3::X),
        (Vec3::Y, Vec3::X, Vec3::Z),
    ];
    let mut mesh = Mesh::default();
    for (f, (normal, s, t)) in faces.into_iter().enumerate() {
        // The face's corner nearest `lo`: on the far side along a positive normal.
        let a = lo + size * normal.max(Vec3::ZERO);
        let rgb = hue(f as f32 / 6.0);
        let base = mesh.vertices.len() as u32;
        let corners = [
            (Vec3::ZERO, Vec2::ZERO),
            (s, Vec2::X),
            (s + t, Vec2::ONE),
            (t, Vec2::Y),
        ];
        mesh.vertices
            .extend(corners.map(|(offset, uv)| vertex(a + size * offset, rgb, normal, uv)));
        mesh.triangles.extend(quad([base, base + 1, base + 2, base + 3]));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outward_of_a_front_facing_flat_triangle_points_at_the_default_camera() {
        // Counter-clockwise as seen from (0, 0, -3) with x right and y up.
        assert_eq!(outward(Vec3::ZERO, Vec3::X, Vec3::Y), Vec3::NEG_Z);
    }

    #[test]
    fn hue_stays_in_gamut() {
        for k in 0..100 {
            let c = hue(k as f32 / 37.0);
            assert!(c.cmpge(Vec3::ZERO).all() && c.cmple(Vec3::ONE).all(), "{c}");
        }
    }
}
