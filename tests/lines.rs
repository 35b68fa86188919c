//! Lines and points through the pipeline (labs 002 and 004): clipping, depth, colour along `t`.

use glam::{Mat4, Vec3, Vec4};
use refrast::CompareOp;
use refrast::pipeline::{Framebuffer, Renderer, Vertex, to_rgba8};

const CLEAR: [u8; 4] = [0, 0, 0, 255];

fn target() -> Framebuffer {
    let mut t = Framebuffer::new(32, 32).unwrap();
    t.clear(CLEAR, 1.0);
    t
}

fn lit(t: &Framebuffer) -> Vec<(u32, u32)> {
    (0..32)
        .flat_map(|y| (0..32).map(move |x| (x, y)))
        .filter(|&(x, y)| t.pixel(x, y) != Some(CLEAR))
        .collect()
}

/// A vertex at an NDC position with depth z (identity matrices make clip = NDC, w = 1).
fn v(x: f32, y: f32, z: f32, rgb: Vec3) -> Vertex {
    Vertex::colored(Vec3::new(x, y, z), rgb)
}

#[test]
fn a_horizontal_line_runs_from_red_to_blue() {
    let mut t = target();
    // NDC x from −1 + 1/32 to 1 − 1/32 is raster x from 0.5 to 31.5 on row 15.
    let ends = [
        v(-1.0 + 1.0 / 32.0, 1.0 / 32.0, 0.5, Vec3::X),
        v(1.0 - 1.0 / 32.0, 1.0 / 32.0, 0.5, Vec3::Z),
    ];
    let n = Renderer::default().draw_lines(&mut t, &ends, &[[0, 1]], Mat4::IDENTITY);
    assert_eq!(n, 32);
    assert!(lit(&t).iter().all(|&(_, y)| y == 15));
    assert_eq!(t.pixel(0, 15), Some([255, 0, 0, 255]));
    assert_eq!(t.pixel(31, 15), Some([0, 0, 255, 255]));
    // Halfway (t = 15/31) the colour is the mix.
    assert_eq!(
        t.pixel(15, 15).unwrap(),
        to_rgba8(Vec4::new(1.0, 0.0, 0.0, 1.0).lerp(Vec4::new(0.0, 0.0, 1.0, 1.0), 15.0 / 31.0))
    );
}

#[test]
fn a_line_crossing_the_near_plane_keeps_its_front_part() {
    let mut t = target();
    // z from 0.9 to −0.9 along x: the near plane z = 0 is at x_ndc = 0, raster x = 16.
    // (Not from 1: depth 1 fails LESS against a buffer cleared to 1.)
    let ends = [
        v(-1.0 + 1.0 / 32.0, 0.0, 0.9, Vec3::ONE),
        v(1.0 - 1.0 / 32.0, 0.0, -0.9, Vec3::ONE),
    ];
    Renderer::default().draw_lines(&mut t, &ends, &[[0, 1]], Mat4::IDENTITY);
    let xs: Vec<u32> = lit(&t).iter().map(|p| p.0).collect();
    // From the pixel holding raster x = ½ to the one holding the clipped end at x = 16.
    assert_eq!(xs, (0..=16).collect::<Vec<u32>>());
}

#[test]
fn lines_behind_the_eye_draw_nothing_and_bad_indices_are_skipped() {
    let mut t = target();
    let behind = [v(-0.5, 0.0, -0.5, Vec3::ONE), v(0.5, 0.0, -0.2, Vec3::ONE)];
    assert_eq!(
        Renderer::default().draw_lines(&mut t, &behind, &[[0, 1], [0, 7]], Mat4::IDENTITY),
        0
    );
    assert!(lit(&t).is_empty());
}

#[test]
fn lines_are_depth_tested() {
    let mut t = target();
    let renderer = Renderer::default();
    let near = [v(-0.9, 0.0, 0.2, Vec3::X), v(0.9, 0.0, 0.2, Vec3::X)];
    let far = [v(0.0, -0.9, 0.8, Vec3::Y), v(0.0, 0.9, 0.8, Vec3::Y)];
    renderer.draw_lines(&mut t, &near, &[[0, 1]], Mat4::IDENTITY);
    renderer.draw_lines(&mut t, &far, &[[0, 1]], Mat4::IDENTITY);
    // Where they cross, the nearer red line stays; elsewhere the green one shows.
    assert_eq!(t.pixel(16, 16), Some([255, 0, 0, 255]));
    assert_eq!(t.pixel(16, 5), Some([0, 255, 0, 255]));
}

#[test]
fn points_land_in_the_pixel_holding_them() {
    let mut t = target();
    let mut renderer = Renderer::default();
    renderer.state.depth.compare = CompareOp::Always;
    let points = [
        v(0.0, 0.0, 0.5, Vec3::X),               // raster (16, 16)
        v(-1.0 + 0.1 / 32.0, 1.0, 0.5, Vec3::Y), // raster (0.05, 0): pixel (0, 0)
        v(0.0, 0.0, -0.5, Vec3::Z),              // before the near plane: not drawn
        v(3.0, 0.0, 0.5, Vec3::Z),               // off screen: not drawn
        v(f32::NAN, 0.0, 0.5, Vec3::Z),          // not finite: not drawn
    ];
    assert_eq!(renderer.draw_points(&mut t, &points, Mat4::IDENTITY), 2);
    assert_eq!(lit(&t), vec![(0, 0), (16, 16)]);
    assert_eq!(t.pixel(16, 16), Some([255, 0, 0, 255]));
}

/// With w = 2 every position is halved on screen: a point at (0.5, 0.5) lands in pixel
/// (20, 12), a line at y = 0.5 from x = −0.5 to 0.5 runs along row 12 from 12 to 20, and a
/// point before the near plane is not drawn although it would project inside.
#[test]
fn points_and_lines_are_divided_by_w() {
    let w2 = Mat4::from_cols(Vec4::X, Vec4::Y, Vec4::Z, Vec4::new(0.0, 0.0, 0.0, 2.0));
    let mut t = target();
    let points = [v(0.5, 0.5, 0.5, Vec3::X), v(0.0, 0.0, -0.5, Vec3::X)];
    assert_eq!(Renderer::default().draw_points(&mut t, &points, w2), 1);
    assert_eq!(lit(&t), vec![(20, 12)]);
    let mut t = target();
    let ends = [v(-0.5, 0.5, 0.5, Vec3::X), v(0.5, 0.5, 0.5, Vec3::X)];
    assert_eq!(Renderer::default().draw_lines(&mut t, &ends, &[[0, 1]], w2), 9);
    assert_eq!(lit(&t), (12..=20).map(|x| (x, 12)).collect::<Vec<_>>());
}

/// A w that overflows f32 is not finite, so the point is not drawn, though x/w, y/w and z/w
/// are all 0 and it lies inside every clip plane.
#[test]
fn a_point_whose_w_overflows_is_not_drawn() {
    // Clip position (0, 0, 0.5, 2y): y = 3e38 makes w = +∞.
    let w_from_y = Mat4::from_cols(
        Vec4::ZERO,
        Vec4::new(0.0, 0.0, 0.0, 2.0),
        Vec4::ZERO,
        Vec4::new(0.0, 0.0, 0.5, 0.0),
    );
    let mut t = target();
    let point = [Vertex::colored(Vec3::new(0.0, 3e38, 0.0), Vec3::X)];
    assert_eq!(Renderer::default().draw_points(&mut t, &point, w_from_y), 0);
    assert!(lit(&t).is_empty());
}

#[test]
fn line_colour_is_perspective_correct() {
    let mut t = target();
    // From w = 1 to w = 3: the screen midpoint is only a quarter of the way along in 3D.
    let far = Vertex::colored(Vec3::new(0.9, 0.0, 3.0), Vec3::Z);
    let near = Vertex::colored(Vec3::new(-0.9, 0.0, 1.0), Vec3::X);
    // w = z: x_ndc = x / z, so the ends project to −0.9 and 0.3.
    let w_from_z = Mat4::from_cols(Vec4::X, Vec4::Y, Vec4::new(0.0, 0.0, 0.5, 1.0), Vec4::ZERO);
    Renderer::default().draw_lines(&mut t, &[near, far], &[[0, 1]], w_from_z);
    // Raster x: −0.9 → 1.6, 0.3 → 20.8, 19 steps; pixel 11 is step 10, s = 10/19. The 3D
    // parameter is (s/3) / ((1 − s)/1 + s/3) = 0.27: red 186. Screen-linear would give 121.
    let p = t.pixel(11, 16).unwrap();
    assert!(p[0] > 170 && p[2] < 85, "{p:?}");
}
