//! The procedural meshes: counts, shared edges, outward normals, the winding the renderer sees.

use std::collections::HashMap;

use glam::{Mat4, Vec3, Vec4};
use refrast::CullMode;
use refrast::camera::{Camera, Projection};
use refrast::pipeline::{Framebuffer, Mesh, Renderer};
use refrast_render::shapes::{MAX_DIVISIONS, ShapeError, cuboid, outward, plane, sphere, star, text, torus};

/// How often each directed edge `(from, to)` occurs.
fn directed_edges(mesh: &Mesh) -> HashMap<(u32, u32), usize> {
    let mut edges = HashMap::new();
    for &[a, b, c] in &mesh.triangles {
        for edge in [(a, b), (b, c), (c, a)] {
            *edges.entry(edge).or_insert(0) += 1;
        }
    }
    edges
}

/// Closed and consistently wound: every directed edge once, and its reverse once.
fn assert_closed(mesh: &Mesh, name: &str) {
    let edges = directed_edges(mesh);
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "{name}: edge {a}->{b} used {n} times in one direction");
        assert_eq!(
            edges.get(&(b, a)),
            Some(&1),
            "{name}: edge {a}->{b} has no opposite twin"
        );
    }
}

/// A consistently wound surface with a border: no directed edge twice; returns the border's
/// edge count (edges without an opposite twin).
fn border_edges(mesh: &Mesh, name: &str) -> usize {
    let edges = directed_edges(mesh);
    assert!(
        edges.values().all(|&n| n == 1),
        "{name}: a directed edge used twice"
    );
    edges
        .keys()
        .filter(|&&(a, b)| !edges.contains_key(&(b, a)))
        .count()
}

/// Indices in range, positions finite and in `[-1, 1]³`, normals unit, every triangle's
/// outward direction along its corners' normals, no zero-area triangle, no unused vertex.
fn assert_well_formed(mesh: &Mesh, name: &str) {
    let n = mesh.vertices.len();
    let mut used = vec![false; n];
    for &t in &mesh.triangles {
        assert!(t.iter().all(|&i| (i as usize) < n), "{name}: {t:?} out of range");
        t.iter().for_each(|&i| used[i as usize] = true);
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
        let out = outward(a.position, b.position, c.position);
        assert!(out.length() > 1e-9, "{name}: {t:?} has zero area");
        for v in [a, b, c] {
            assert!(
                out.dot(v.normal) > 0.0,
                "{name}: {t:?} winds against normal {}",
                v.normal
            );
        }
    }
    assert!(used.iter().all(|&u| u), "{name}: a vertex no triangle uses");
    for v in &mesh.vertices {
        assert!(
            v.position.is_finite() && v.position.abs().max_element() <= 1.0 + 1e-6,
            "{name}: {}",
            v.position
        );
        assert!(
            (v.normal.length() - 1.0).abs() < 1e-5,
            "{name}: normal {}",
            v.normal
        );
        assert!(v.color.cmpge(Vec4::ZERO).all() && v.color.cmple(Vec4::ONE).all());
        assert!(v.uv.cmpge(glam::Vec2::ZERO).all() && v.uv.cmple(glam::Vec2::ONE).all());
    }
}

/// Colours are not all one: interpolation has something to show.
fn assert_colourful(mesh: &Mesh, name: &str) {
    let first = mesh.vertices[0].color;
    assert!(
        mesh.vertices
            .iter()
            .any(|v| (v.color - first).abs().max_element() > 0.1),
        "{name}: one colour"
    );
}

#[test]
fn plane_counts_and_shared_edges() {
    for n in [1, 2, 7] {
        let mesh = plane(n);
        assert_eq!(mesh.vertices.len() as u32, (n + 1) * (n + 1));
        assert_eq!(mesh.triangles.len() as u32, 2 * n * n);
        assert_eq!(
            border_edges(&mesh, "plane") as u32,
            4 * n,
            "only the square's rim is border"
        );
        assert_well_formed(&mesh, "plane");
        assert!(
            mesh.vertices
                .iter()
                .all(|v| v.position.z == 0.0 && v.normal == Vec3::NEG_Z)
        );
    }
    assert_colourful(&plane(4), "plane");
}

#[test]
fn star_counts_and_fan() {
    let mesh = star(5);
    assert_eq!(mesh.vertices.len(), 11);
    assert_eq!(mesh.triangles.len(), 10);
    assert!(
        mesh.triangles.iter().all(|t| t[0] == 0),
        "every triangle shares the centre"
    );
    assert_eq!(border_edges(&mesh, "star"), 10, "the rim");
    assert_well_formed(&mesh, "star");
    assert_colourful(&mesh, "star");
    let tips: Vec<Vec4> = (0..5).map(|k| mesh.vertices[1 + 2 * k].color).collect();
    assert!(tips.windows(2).all(|w| w[0] != w[1]), "tips differ in colour");
}

#[test]
fn text_cells_share_edges_across_glyphs() {
    let mesh = text("Hi!");
    assert_well_formed(&mesh, "text");
    assert_colourful(&mesh, "text");
    let border = border_edges(&mesh, "text");
    // Cells sharing edges: far fewer border edges than 4 per cell.
    let cells = mesh.triangles.len() / 2;
    assert!(border < 4 * cells / 2, "{border} border edges for {cells} cells");
    // The string spans [-1, 1] in x (H's left column is lit, '!' does not reach the right edge).
    let xs = mesh.vertices.iter().map(|v| v.position.x);
    assert_eq!(xs.clone().fold(f32::INFINITY, f32::min), -1.0);
    assert!(xs.fold(f32::NEG_INFINITY, f32::max) <= 1.0);
    // Two touching glyphs: a full block next to a full block share one column of 9 corners.
    let blocks = text("\u{2588}\u{2588}");
    assert_eq!(blocks.vertices.len(), 17 * 9);
    assert_eq!(border_edges(&blocks, "blocks"), 2 * 16 + 2 * 8);
}

#[test]
fn text_unknown_characters_and_limits() {
    assert_eq!(
        text("\u{1F600}").triangles,
        text("?").triangles,
        "unknown shows as '?'"
    );
    assert!(text("").vertices.is_empty() && text("   ").triangles.is_empty());
    let long = "x".repeat(5000);
    assert_eq!(
        text(&long).triangles.len(),
        text(&"x".repeat(1024)).triangles.len()
    );
}

#[test]
fn torus_is_closed_with_outward_normals() {
    let mesh = torus(0.7, 0.25, 24, 12).expect("valid radii");
    assert_eq!(mesh.vertices.len(), 24 * 12);
    assert_eq!(mesh.triangles.len(), 2 * 24 * 12);
    assert_closed(&mesh, "torus");
    assert_well_formed(&mesh, "torus");
    assert_colourful(&mesh, "torus");
    for v in &mesh.vertices {
        let centre = Vec3::new(v.position.x, v.position.y, 0.0).normalize() * 0.7;
        assert!(
            (v.position - centre).dot(v.normal) > 0.0,
            "normal points into the tube"
        );
    }
}

#[test]
fn torus_refuses_bad_radii() {
    for (major, minor) in [
        (0.5, 0.5),
        (0.5, 0.0),
        (f32::NAN, 0.1),
        (1.0, f32::INFINITY),
        (-1.0, 0.2),
    ] {
        assert!(
            matches!(torus(major, minor, 8, 8), Err(ShapeError::TorusRadii { .. })),
            "{major} {minor}"
        );
    }
}

#[test]
fn sphere_is_closed_at_seam_and_poles() {
    for (s, r) in [(3, 2), (16, 9), (32, 16)] {
        let mesh = sphere(s, r);
        assert_eq!(mesh.vertices.len() as u32, s * (r - 1) + 2);
        assert_eq!(mesh.triangles.len() as u32, 2 * s * (r - 1));
        assert_closed(&mesh, "sphere");
        assert_well_formed(&mesh, "sphere");
        assert!(mesh.vertices.iter().all(|v| v.position.dot(v.normal) > 0.99));
    }
    assert_colourful(&sphere(8, 4), "sphere");
}

#[test]
fn cuboid_faces_point_outward() {
    let mesh = cuboid(Vec3::splat(0.5), Vec3::splat(-0.5)).expect("finite corners");
    assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (24, 12));
    assert_well_formed(&mesh, "cuboid");
    for &[a, b, c] in &mesh.triangles {
        let [a, b, c] = [a, b, c].map(|i| mesh.vertices[i as usize].position);
        let centroid = (a + b + c) / 3.0;
        assert!(outward(a, b, c).dot(centroid) > 0.0, "a face points inward");
    }
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    assert!(matches!(
        cuboid(nan, Vec3::ONE),
        Err(ShapeError::CuboidCorners { .. })
    ));
}

#[test]
fn counts_are_clamped() {
    assert_eq!(plane(0).triangles.len(), 2);
    assert_eq!(star(0).triangles.len(), 6);
    assert_eq!(sphere(0, 0).triangles.len(), 6);
    assert_eq!(
        torus(0.6, 0.3, 1, u32::MAX).map(|m| m.vertices.len()),
        Ok(3 * MAX_DIVISIONS as usize)
    );
}

/// Pixels drawn by the default renderer with `cull`, from `eye` looking at the origin, and
/// their mean depth.
fn drawn(mesh: &Mesh, eye: Vec3, cull: CullMode) -> (usize, f32) {
    let mut renderer = Renderer::default();
    renderer.state.cull = cull;
    let mut target = Framebuffer::new(48, 48).expect("a small target");
    let projection = Projection::Perspective {
        fov_y: 1.0,
        aspect: 1.0,
        near: 0.1,
        far: 10.0,
    };
    let view_projection = projection.matrix() * Camera::look_at(eye, Vec3::ZERO).view();
    renderer
        .draw_mesh(&mut target, mesh, Mat4::IDENTITY, view_projection, |_| {
            Some(Vec4::ONE)
        })
        .expect("draws");
    let depths: Vec<f32> = target.depth().iter().copied().filter(|&d| d < 1.0).collect();
    (
        depths.len(),
        depths.iter().sum::<f32>() / depths.len().max(1) as f32,
    )
}

#[test]
fn flat_shapes_are_front_facing_from_the_default_camera() {
    let front = Vec3::new(0.0, 0.0, -3.0);
    for (name, mesh) in [("plane", plane(3)), ("star", star(6)), ("text", text("AB"))] {
        assert!(
            drawn(&mesh, front, CullMode::Back).0 > 50,
            "{name} is culled from the front"
        );
        assert_eq!(
            drawn(&mesh, -front, CullMode::Back).0,
            0,
            "{name} is drawn from behind"
        );
    }
}

#[test]
fn closed_shapes_face_out_from_every_side() {
    let torus = torus(0.6, 0.3, 16, 8).expect("valid");
    let cube = cuboid(Vec3::splat(-0.5), Vec3::splat(0.5)).expect("valid");
    for (name, mesh) in [("sphere", sphere(16, 8)), ("torus", torus), ("cuboid", cube)] {
        for eye in [Vec3::NEG_Z, Vec3::Z, Vec3::X, Vec3::new(0.3, 1.0, -0.2)] {
            // Front faces are the near side: nearer on average than the back faces behind them.
            let (front, near) = drawn(&mesh, eye * 3.0, CullMode::Back);
            let (back, far) = drawn(&mesh, eye * 3.0, CullMode::Front);
            assert!(
                front > 50 && back > 50,
                "{name} from {eye}: {front} and {back} pixels"
            );
            assert!(
                near < far,
                "{name} from {eye}: front faces at depth {near}, back at {far}"
            );
        }
    }
}
