//! Lines and points through the pipeline (labs 002 and 004): clipping, depth, colour along `t`.
//!
//! The pipeline draws them through the reference's certified paths: lines by the diamond-exit
//! rule (a segment leaves out the pixel whose diamond holds its last end; a line on a row's
//! boundary, nudged up by ε², is drawn in the row above), points as one-pixel squares under
//! the top-left rule.

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
    // Centre to centre: the last pixel's diamond holds the end, so it is left out (a strip's
    // next segment draws it).
    assert_eq!(n, 31);
    assert!(lit(&t).iter().all(|&(_, y)| y == 15));
    assert_eq!(t.pixel(0, 15), Some([255, 0, 0, 255]));
    assert_eq!(t.pixel(31, 15), Some(CLEAR));
    assert_eq!(
        t.pixel(30, 15).unwrap(),
        to_rgba8(Vec4::new(1.0, 0.0, 0.0, 1.0).lerp(Vec4::new(0.0, 0.0, 1.0, 1.0), 30.0 / 31.0))
    );
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
    // From pixel 0 to the clipped end at x = 16, on row 15 (the line y = 16 nudged up): the end
    // lies on pixel corners, outside every diamond, and the last diamond left is pixel 15's.
    assert_eq!(xs, (0..=15).collect::<Vec<u32>>());
    assert!(lit(&t).iter().all(|&(_, y)| y == 15));
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
    // Row 15 and column 15 (each line on a pixel boundary, nudged up and left): where they
    // cross, the nearer red line stays; elsewhere the green one shows.
    assert_eq!(t.pixel(15, 15), Some([255, 0, 0, 255]));
    assert_eq!(t.pixel(15, 5), Some([0, 255, 0, 255]));
}

#[test]
fn points_land_in_the_pixel_holding_them() {
    let mut t = target();
    let mut renderer = Renderer::default();
    renderer.state.depth.compare = CompareOp::Always;
    let points = [
        v(1.0 / 32.0, -1.0 / 32.0, 0.5, Vec3::X), // raster (16.5, 16.5)
        v(-1.0 + 0.1 / 32.0, 1.0 - 0.4 / 32.0, 0.5, Vec3::Y), // raster (0.05, 0.2): pixel (0, 0)
        v(0.0, 0.0, -0.5, Vec3::Z),               // before the near plane: not drawn
        v(3.0, 0.0, 0.5, Vec3::Z),                // off screen: not drawn
        v(f32::NAN, 0.0, 0.5, Vec3::Z),           // not finite: not drawn
    ];
    assert_eq!(renderer.draw_points(&mut t, &points, Mat4::IDENTITY), 2);
    assert_eq!(lit(&t), vec![(0, 0), (16, 16)]);
    assert_eq!(t.pixel(16, 16), Some([255, 0, 0, 255]));
}

/// A point on a pixel corner: its square's top and left sides own the centre on them, so it
/// lands in the pixel above and to the left (raster (16, 16) in pixel (15, 15)), as two
/// triangles under the top-left rule would draw it.
#[test]
fn a_point_on_a_pixel_corner_takes_the_pixel_above_left() {
    let mut t = target();
    let mut renderer = Renderer::default();
    renderer.state.depth.compare = CompareOp::Always;
    assert_eq!(
        renderer.draw_points(&mut t, &[v(0.0, 0.0, 0.5, Vec3::X)], Mat4::IDENTITY),
        1
    );
    assert_eq!(lit(&t), vec![(15, 15)]);
}

/// With w = 2 every position is halved on screen: a point at (0.53125, 0.46875) lands in pixel
/// (20, 12) (raster (20.25, 12.25)), a line at y = 0.46875 from x = −0.5 to 0.5 runs along row
/// 12 from 12 to 19 (its end at x = 20 lies outside pixel 20's diamond), and a point before
/// the near plane is not drawn although it would project inside.
#[test]
fn points_and_lines_are_divided_by_w() {
    let w2 = Mat4::from_cols(Vec4::X, Vec4::Y, Vec4::Z, Vec4::new(0.0, 0.0, 0.0, 2.0));
    let mut t = target();
    let points = [v(0.53125, 0.46875, 0.5, Vec3::X), v(0.0, 0.0, -0.5, Vec3::X)];
    assert_eq!(Renderer::default().draw_points(&mut t, &points, w2), 1);
    assert_eq!(lit(&t), vec![(20, 12)]);
    let mut t = target();
    let ends = [v(-0.5, 0.46875, 0.5, Vec3::X), v(0.5, 0.46875, 0.5, Vec3::X)];
    assert_eq!(Renderer::default().draw_lines(&mut t, &ends, &[[0, 1]], w2), 8);
    assert_eq!(lit(&t), (12..=19).map(|x| (x, 12)).collect::<Vec<_>>());
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
    // Raster x: −0.9 → 1.6, 0.3 → 20.8, on row 15 (y = 16 nudged up); pixel 11's centre
    // projects at s = (11.5 − 1.6)/19.2 = 0.52. The 3D parameter is (s/3) / ((1 − s)/1 + s/3)
    // = 0.26: red 188. Screen-linear would give 123.
    let p = t.pixel(11, 15).unwrap();
    assert!(p[0] > 170 && p[2] < 85, "{p:?}");
}
