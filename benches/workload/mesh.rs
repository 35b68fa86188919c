//! A workload scene as a mesh in NDC, for the benchmarks that draw through refrast's pipeline
//! with identity matrices (`benches/reference.rs`, `fast/benches/fast.rs`).

use glam::{Vec3, Vec4};
use refrast::pipeline::{Mesh, Vertex};

use super::workload::{HEIGHT, WIDTH};

/// The raster-space triangles of [`super::workload::scene`] as a mesh in NDC, each vertex in its
/// triangle's colour, drawn with the identity.
pub fn ndc_mesh(triangles: &[([Vec3; 3], Vec4)]) -> Mesh {
    let to_ndc = |p: Vec3| {
        Vec3::new(
            p.x / WIDTH as f32 * 2.0 - 1.0,
            1.0 - p.y / HEIGHT as f32 * 2.0,
            p.z,
        )
    };
    let vertices = triangles
        .iter()
        .flat_map(|(t, c)| {
            t.map(|p| Vertex {
                position: to_ndc(p),
                color: *c,
                ..Vertex::default()
            })
        })
        .collect();
    let indices = (0..triangles.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    Mesh {
        vertices,
        triangles: indices,
    }
}
