//! Seed 002's room: a Cornell box of side 2 at the origin with a short red and a tall blue
//! block inside, in the lab's colours, seen from (0, 0, −3.001).
//!
//! The lab gives its corners on a 555-unit box (the classic Cornell box measurements), scales
//! them into `[−1, 1]³` and mirrors x and y for its y-down camera. Our world is y-up, so we
//! mirror x only: the picture is the lab's.

use glam::{Vec3, Vec4};
use refrast::pipeline::{Mesh, Vertex};

/// The Cornell box's side in the lab's units.
const SIDE: f32 = 555.0;

/// The lab's wall and block colours (reflectances).
const RED: Vec3 = Vec3::new(0.75, 0.15, 0.15);
const YELLOW: Vec3 = Vec3::new(0.75, 0.75, 0.15);
const GREEN: Vec3 = Vec3::new(0.15, 0.75, 0.15);
const CYAN: Vec3 = Vec3::new(0.15, 0.75, 0.75);
const BLUE: Vec3 = Vec3::new(0.15, 0.15, 0.75);
const PURPLE: Vec3 = Vec3::new(0.75, 0.15, 0.75);
const WHITE: Vec3 = Vec3::new(0.75, 0.75, 0.75);

/// Where the lab's camera is.
pub const EYE: Vec3 = Vec3::new(0.0, 0.0, -3.001);

/// The lab's field of view: its focal length equals the image's side, so the half-angle's
/// tangent is ½.
#[must_use]
pub fn fov_y_degrees() -> f32 {
    2.0 * 0.5f32.atan().to_degrees()
}

/// A lab corner (0..555 on each axis) in our world: scaled into `[−1, 1]`, x mirrored.
fn corner(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(1.0 - 2.0 * x / SIDE, 2.0 * y / SIDE - 1.0, 2.0 * z / SIDE - 1.0)
}

/// The eight corners A–H of a block standing on the floor: four floor corners and a height.
fn block(floor: [[f32; 2]; 4], height: f32) -> [Vec3; 8] {
    let [a, b, c, d] = floor.map(|[x, z]| corner(x, 0.0, z));
    let [e, f, g, h] = floor.map(|[x, z]| corner(x, height, z));
    [a, b, c, d, e, f, g, h]
}

/// The lab's ten triangles of a block (no bottom), as indices into its corners A–H.
const BLOCK_TRIANGLES: [[usize; 3]; 10] = [
    [4, 1, 0],
    [4, 5, 1],
    [5, 3, 1],
    [5, 7, 3],
    [7, 2, 3],
    [7, 6, 2],
    [6, 4, 2],
    [4, 0, 2],
    [6, 5, 4],
    [6, 7, 5],
];

/// The room, the short block and the tall block: 30 triangles, each with its own three
/// vertices carrying the face's normal and colour, as the lab's triangles do.
#[must_use]
pub fn room() -> Mesh {
    let mut mesh = Mesh::default();
    let mut push = |corners: [Vec3; 3], color: Vec3| {
        let normal = crate::shapes::outward(corners[0], corners[1], corners[2]).normalize_or_zero();
        let base = mesh.vertices.len() as u32;
        for position in corners {
            mesh.vertices.push(Vertex {
                position,
                color: Vec4::from((color, 1.0)),
                normal,
                ..Vertex::default()
            });
        }
        mesh.triangles.push([base, base + 1, base + 2]);
    };
    let [a, b, c, d, e, f, g, h] = [
        corner(SIDE, 0.0, 0.0),
        corner(0.0, 0.0, 0.0),
        corner(SIDE, 0.0, SIDE),
        corner(0.0, 0.0, SIDE),
        corner(SIDE, SIDE, 0.0),
        corner(0.0, SIDE, 0.0),
        corner(SIDE, SIDE, SIDE),
        corner(0.0, SIDE, SIDE),
    ];
    let walls = [
        ([c, b, a], GREEN),
        ([c, d, b], GREEN),
        ([a, e, c], PURPLE),
        ([c, e, g], PURPLE),
        ([f, b, d], YELLOW),
        ([h, f, d], YELLOW),
        ([e, f, g], CYAN),
        ([f, h, g], CYAN),
        ([g, d, c], WHITE),
        ([g, h, d], WHITE),
    ];
    for (corners, color) in walls {
        push(corners, color);
    }
    let short = block(
        [[290.0, 114.0], [130.0, 65.0], [240.0, 272.0], [82.0, 225.0]],
        165.0,
    );
    let tall = block(
        [[423.0, 247.0], [265.0, 296.0], [472.0, 406.0], [314.0, 456.0]],
        330.0,
    );
    for (corners, color) in [(short, RED), (tall, BLUE)] {
        for t in BLOCK_TRIANGLES {
            push(t.map(|i| corners[i]), color);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_room_fills_the_unit_cube_with_the_floor_below() {
        let mesh = room();
        assert_eq!(mesh.triangles.len(), 30);
        let (lo, hi) = crate::geometry::bounds(&mesh).unwrap();
        assert!((lo - Vec3::splat(-1.0)).length() < 1e-6 && (hi - Vec3::ONE).length() < 1e-6);
        // The floor (green) lies at y = −1, the ceiling (cyan) at y = +1.
        let at = |color: Vec3| mesh.vertices.iter().filter(move |v| v.color.truncate() == color);
        assert!(at(GREEN).all(|v| v.position.y == -1.0));
        assert!(at(CYAN).all(|v| v.position.y == 1.0));
        // The back wall is the far one, at z = +1; the blocks stand on the floor.
        assert!(at(WHITE).all(|v| v.position.z == 1.0));
        assert!(
            at(BLUE)
                .chain(at(RED))
                .all(|v| v.position.y >= -1.0 && v.position.y < 0.3)
        );
        // Every normal is a unit axis-aligned or horizontal vector.
        assert!(
            mesh.vertices
                .iter()
                .all(|v| (v.normal.length() - 1.0).abs() < 1e-5)
        );
    }

    #[test]
    fn the_lab_camera_sees_the_whole_room() {
        // At distance 2.001 from the front face, a half-angle of atan(½) reaches 1.0005 > 1.
        let reach = (EYE.z.abs() - 1.0) * (fov_y_degrees() / 2.0).to_radians().tan();
        assert!(reach > 1.0 && reach < 1.001, "{reach}");
    }
}
