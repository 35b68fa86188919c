//! What the renderer needs to know about a mesh besides its triangles: bounds, edges, normals.

use std::collections::BTreeSet;

use glam::Vec3;
use refrast::pipeline::Mesh;

/// The axis-aligned bounds `(min, max)` of the finite vertex positions, or `None` if there are none.
#[must_use]
pub fn bounds(mesh: &Mesh) -> Option<(Vec3, Vec3)> {
    mesh.vertices
        .iter()
        .map(|v| v.position)
        .filter(|p| p.is_finite())
        .fold(None, |acc, p| match acc {
            None => Some((p, p)),
            Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
        })
}

/// Each undirected edge of the mesh once, lower index first: what wire mode draws.
#[must_use]
pub fn edges(mesh: &Mesh) -> Vec<[u32; 2]> {
    let set: BTreeSet<[u32; 2]> = mesh
        .triangles
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    set.into_iter().collect()
}

/// The unnormalised outward normal of triangle `t` ([`crate::shapes::outward`]): its length
/// is twice the area.
#[must_use]
pub fn face_normal(mesh: &Mesh, t: [u32; 3]) -> Vec3 {
    let [a, b, c] = t.map(|i| mesh.vertices[i as usize].position);
    crate::shapes::outward(a, b, c)
}

/// A mesh from a right-handed file (OBJ's and most PLY's convention: y up, the front towards
/// +z) in refrast's left-handed world: z negated, normals with it, and each triangle's winding
/// reversed so that its front stays its front. The front then faces the framing camera at −z.
#[must_use]
pub fn to_left_handed(mut mesh: Mesh) -> Mesh {
    for v in &mut mesh.vertices {
        v.position.z = -v.position.z;
        v.normal.z = -v.normal.z;
    }
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    mesh
}

/// Replaces every vertex normal by the area-weighted mean of the normals of the triangles
/// around it, for meshes whose file gives none (Gouraud's vertex normals).
///
/// Every triangle index must be in range (as [`crate::load`] guarantees). A vertex that no
/// triangle uses keeps a zero normal, which lighting treats as ambient only.
pub fn smooth_normals(mesh: &mut Mesh) {
    let mut sums = vec![Vec3::ZERO; mesh.vertices.len()];
    for &t in &mesh.triangles {
        let n = face_normal(mesh, t);
        if n.is_finite() {
            for i in t {
                sums[i as usize] += n;
            }
        }
    }
    for (v, n) in mesh.vertices.iter_mut().zip(sums) {
        v.normal = n.normalize_or_zero();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use refrast::pipeline::Vertex;

    fn quad() -> Mesh {
        let at = |x, y| Vertex::colored(Vec3::new(x, y, 0.0), Vec3::ONE);
        Mesh {
            vertices: vec![at(0.0, 0.0), at(1.0, 0.0), at(1.0, 1.0), at(0.0, 1.0)],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn a_quad_has_five_edges_and_unit_normals() {
        let mut mesh = quad();
        assert_eq!(edges(&mesh), vec![[0, 1], [0, 2], [0, 3], [1, 2], [2, 3]]);
        // Counter-clockwise in the xy plane seen from −z is the side facing −z.
        assert_eq!(face_normal(&mesh, [0, 1, 2]), -Vec3::Z);
        smooth_normals(&mut mesh);
        assert!(mesh.vertices.iter().all(|v| v.normal == -Vec3::Z));
        // Mirrored into the left-handed world, the same triangles face +z, wound the other way.
        let mirrored = to_left_handed(mesh.clone());
        assert_eq!(mirrored.triangles, vec![[0, 2, 1], [0, 3, 2]]);
        assert!(mirrored.vertices.iter().all(|v| v.normal == Vec3::Z));
        assert_eq!(face_normal(&mirrored, [0, 2, 1]), Vec3::Z);
        assert_eq!(bounds(&mesh), Some((Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0))));
    }

    #[test]
    fn smooth_normals_weigh_by_area_and_skip_unused_vertices() {
        let at = |x, y, z| Vertex::colored(Vec3::new(x, y, z), Vec3::ONE);
        // A big triangle in z = 0 and a small one in x = 0 share vertex 0.
        let mut mesh = Mesh {
            vertices: vec![
                at(0.0, 0.0, 0.0),
                at(4.0, 0.0, 0.0),
                at(0.0, 4.0, 0.0),
                at(0.0, 1.0, 0.0),
                at(0.0, 0.0, 1.0),
                at(9.0, 9.0, 9.0),
            ],
            triangles: vec![[0, 1, 2], [0, 3, 4]],
        };
        smooth_normals(&mut mesh);
        let n = mesh.vertices[0].normal;
        assert!(
            (n + (Vec3::new(1.0, 0.0, 16.0)).normalize()).length() < 1e-6,
            "{n}"
        );
        assert_eq!(mesh.vertices[5].normal, Vec3::ZERO);
        assert_eq!(bounds(&Mesh::default()), None);
    }
}
