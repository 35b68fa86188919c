//! The lab pipeline's framebuffer and shading hook, through their public API.

use glam::{DVec2, Mat4, Vec2, Vec3, Vec4};
use refrast::pipeline::{Framebuffer, Mesh, Renderer, Vertex};

/// A new framebuffer is opaque black at depth 1; its slices hold every pixel, a write
/// through them shows at its (x, y), and just past either side there is no pixel.
#[test]
fn a_framebuffer_reads_back_what_was_written() {
    let mut fb = Framebuffer::new(3, 2).unwrap();
    assert_eq!((fb.color().len(), fb.depth().len()), (6, 6));
    assert_eq!(fb.pixel(2, 1), Some([0, 0, 0, 255]));
    assert!(fb.depth().iter().all(|&d| d == 1.0));
    let i = fb.viewport().index(2, 1);
    fb.color_mut()[i] = [9, 8, 7, 6];
    fb.depth_mut()[i] = 0.25;
    assert_eq!(
        (fb.pixel(2, 1), fb.color()[i], fb.depth()[i]),
        (Some([9, 8, 7, 6]), [9, 8, 7, 6], 0.25)
    );
    assert_eq!((fb.pixel(3, 0), fb.pixel(0, 2)), (None, None));
    fb.clear([1, 2, 3, 4], 0.5);
    assert_eq!(fb.pixel(0, 0), Some([1, 2, 3, 4]));
    assert!(fb.depth().iter().all(|&d| d == 0.5));
}

/// Every attribute the shader sees is its vertices' values mixed by the fragment's weights,
/// positions and normals in world space: checked against weights computed here, from the
/// sample and the vertices' raster positions (w = 1, on the grid, so nothing is snapped).
#[test]
fn the_shader_sees_attributes_mixed_by_the_fragment_weights() {
    let raster = [(1.0, 1.0), (15.0, 2.0), (3.0, 14.0)];
    let ndc = raster.map(|(x, y): (f32, f32)| Vec3::new(x / 8.0 - 1.0, 1.0 - y / 8.0, 0.25));
    let model = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0)) * Mat4::from_scale(Vec3::new(2.0, 3.0, 4.0));
    let (e, n) = (
        [Vec3::X, Vec3::Y, Vec3::Z],
        [Vec3::X, Vec3::new(0.0, 1.0, 1.0), Vec3::ONE],
    );
    // No weight meets a zero attribute, so every term of every mix shows.
    let uv = [Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0), Vec2::new(2.0, 3.0)];
    let vertices = (0..3)
        .map(|k| Vertex {
            position: ndc[k],
            color: e[k].extend(1.0),
            normal: n[k],
            uv: uv[k],
        })
        .collect();
    let mesh = Mesh {
        vertices,
        triangles: vec![[0, 1, 2]],
    };
    let mut target = Framebuffer::new(16, 16).unwrap();
    let seen = std::cell::RefCell::new(Vec::new());
    Renderer::default()
        .draw_mesh(&mut target, &mesh, model, model.inverse(), |input| {
            seen.borrow_mut().push(*input);
            Some(Vec4::ONE)
        })
        .unwrap();
    let seen = seen.into_inner();
    assert!(seen.len() > 50, "{} fragments", seen.len());
    let [a, b, c] = raster.map(|(x, y)| DVec2::new(f64::from(x), f64::from(y)));
    let cross = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    for input in seen {
        let s = DVec2::new(f64::from(input.x) + 0.5, f64::from(input.y) + 0.5);
        let area = cross(a, b, c);
        let w = [cross(s, b, c), cross(a, s, c), cross(a, b, s)].map(|v| (v / area) as f32);
        let mix = |v: [Vec3; 3]| v[0] * w[0] + v[1] * w[1] + v[2] * w[2];
        let normal_matrix = model.inverse().transpose();
        // 2^-18 is the reference's precision; the f32 sums here add a few ulps of 4.
        let close = |got: Vec4, want: Vec4| (got - want).abs().max_element() < 1e-4;
        assert!(
            close(input.color, Vec4::new(w[0], w[1], w[2], 1.0)),
            "{input:?} {w:?}"
        );
        assert!(
            close(
                input.uv.extend(0.0).extend(0.0),
                (uv[0] * w[0] + uv[1] * w[1] + uv[2] * w[2])
                    .extend(0.0)
                    .extend(0.0)
            ),
            "{input:?}"
        );
        let position = model.transform_point3(mix(ndc));
        assert!(
            close(input.position.extend(0.0), position.extend(0.0)),
            "{input:?} {position}"
        );
        let normal = normal_matrix.transform_vector3(mix(n));
        assert!(
            close(input.normal.extend(0.0), normal.extend(0.0)),
            "{input:?} {normal}"
        );
    }
}

/// What `save_png` writes reads back as the colour buffer, pixel for pixel.
#[cfg(feature = "png")]
#[test]
fn a_saved_png_reads_back_as_its_colour_buffer() {
    let mut fb = Framebuffer::new(4, 3).unwrap();
    fb.color_mut()[5] = [200, 100, 50, 255];
    let path = std::env::temp_dir().join(format!("refrast-framebuffer-{}.png", std::process::id()));
    fb.save_png(&path).unwrap();
    let back = image::open(&path).map(|i| i.to_rgba8());
    let _ = std::fs::remove_file(&path);
    let back = back.unwrap();
    assert_eq!(back.get_pixel(1, 1).0, [200, 100, 50, 255]);
    assert_eq!(back, fb.to_image());
}
