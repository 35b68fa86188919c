//! Golden tests: the five lab 000 scenes, as coverage masks, full images and analytic colours.
//!
//! Masks (`tests/golden/<test>.txt`, 80 × 60, `.` empty, a digit the visible primitive) are
//! compared exactly; so are the 640 × 480 PNGs. `REFRAST_BLESS=1 cargo test --test golden`
//! rewrites them after an intended change: review the diff before committing.

use std::path::PathBuf;

use approx::assert_abs_diff_eq;
use glam::{DVec2, Vec3};
use refrast::scenes::{self, CLEAR};
use refrast::{Rasterizer, Traversal, Viewport};
use refrast_conformance::oracle::raster;

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name)
}

fn bless() -> bool {
    std::env::var_os("REFRAST_BLESS").is_some()
}

/// The scene's visible-primitive mask at `width × height`, one text row per pixel row.
fn mask(scene: &str, width: u32, height: u32) -> String {
    let setup = scenes::build(scene, width as f32 / height as f32).unwrap();
    let viewport = Viewport::new(width, height).unwrap();
    let mut reference = setup.renderer.reference.clone();
    let resolved = reference.resolve(&setup.draw(viewport)).unwrap();
    let mut text = String::new();
    for row in resolved.primitive.chunks(width as usize) {
        text.extend(
            row.iter()
                .map(|p| p.map_or('.', |id| char::from(b'0' + id as u8))),
        );
        text.push('\n');
    }
    text
}

fn check_mask(test: &str, scene: &str) {
    let got = mask(scene, 80, 60);
    let path = golden_path(&format!("{test}.txt"));
    if bless() {
        std::fs::write(&path, &got).unwrap();
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; run with REFRAST_BLESS=1 to create it", path.display()));
    assert!(
        got == want,
        "{test}: mask differs from {}\n--- got ---\n{got}",
        path.display()
    );
}

fn check_png(test: &str, scene: &str) {
    let got = scenes::render(scene, 640, 480).unwrap().to_image();
    let path = golden_path(&format!("{test}.png"));
    if bless() {
        got.save(&path).unwrap();
    }
    let want = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; run with REFRAST_BLESS=1 to create it", path.display()))
        .to_rgba8();
    let differing = got.pixels().zip(want.pixels()).filter(|(a, b)| a != b).count();
    assert_eq!(got.dimensions(), want.dimensions());
    assert_eq!(
        differing,
        0,
        "{test}: {differing} pixels differ from {}",
        path.display()
    );
}

/// Where lab 000 projects a world point: view = world + (0, 0, 10), then x/(aspect·tan30·z), y/(tan30·z).
fn lab_project(p: Vec3, width: f64, height: f64) -> DVec2 {
    let tan = 30f64.to_radians().tan();
    let (x, y, z) = (f64::from(p.x), f64::from(p.y), f64::from(p.z) + 10.0);
    let (w, h) = (width as u32, height as u32);
    DVec2::from(raster::to_raster(
        w,
        h,
        x / (width / height * tan * z),
        y / (tan * z),
    ))
}

#[test]
fn lab000_ndc_mask() {
    check_mask("lab000_ndc_mask", "lab000-ndc");
}

#[test]
fn lab000_world_mask() {
    check_mask("lab000_world_mask", "lab000-world");
}

#[test]
fn lab000_rgb_mask() {
    check_mask("lab000_rgb_mask", "lab000-rgb");
}

#[test]
fn lab000_depth_mask() {
    check_mask("lab000_depth_mask", "lab000-depth");
}

#[test]
fn lab000_bbox_mask() {
    check_mask("lab000_bbox_mask", "lab000-bbox");
}

#[test]
fn lab000_ndc_png() {
    check_png("lab000_ndc_png", "lab000-ndc");
}

#[test]
fn lab000_world_png() {
    check_png("lab000_world_png", "lab000-world");
}

#[test]
fn lab000_rgb_png() {
    check_png("lab000_rgb_png", "lab000-rgb");
}

#[test]
fn lab000_depth_png() {
    check_png("lab000_depth_png", "lab000-depth");
}

#[test]
fn lab000_bbox_png() {
    check_png("lab000_bbox_png", "lab000-bbox");
}

#[test]
fn bounding_box_traversal_changes_nothing() {
    assert_eq!(mask("lab000-depth", 640, 480), mask("lab000-bbox", 640, 480));
}

/// Only `lab000-bbox` walks bounding boxes (the pictures cannot tell: the test above).
#[test]
fn the_bbox_scene_is_the_one_walking_bounding_boxes() {
    let traversal = |scene| {
        scenes::build(scene, 4.0 / 3.0)
            .unwrap()
            .renderer
            .reference
            .config()
            .traversal
    };
    assert_eq!(traversal("lab000-bbox"), Traversal::BoundingBox);
    assert_eq!(traversal("lab000-depth"), Traversal::Viewport);
}

/// An unknown scene's error names it and lists the scenes there are.
#[test]
fn an_unknown_scene_is_named_with_the_list() {
    let message = scenes::render("lab999", 8, 8).unwrap_err().to_string();
    assert!(
        message.contains("'lab999'") && message.contains("lab000-bbox"),
        "{message}"
    );
}

#[test]
fn ndc_triangle_lands_where_the_lab_says() {
    // (0, .5), (.5, −.5), (−.5, −.5) on 80 × 60 → raster (40, 15), (60, 45), (20, 45).
    let m = mask("lab000-ndc", 80, 60);
    let rows: Vec<&str> = m.lines().collect();
    let covered_rows: Vec<usize> = (0..60).filter(|&y| rows[y].contains('0')).collect();
    // Row 15 (sample y = 15.5) spans x in 40 ± 1/3, between the samples 39.5 and 40.5; row 16
    // spans 40 ± 1, so it is the first covered. Row 44 is the last whose sample is above y = 45.
    assert_eq!((covered_rows[0], *covered_rows.last().unwrap()), (16, 44));
    // Row 44 (sample y = 44.5) spans x in [20.33, 59.67]: samples 20.5 ..= 59.5.
    let row = rows[44];
    assert_eq!((row.find('0'), row.rfind('0')), (Some(20), Some(59)));
}

#[test]
fn rgb_colours_follow_the_barycentrics() {
    let (w, h) = (640.0, 480.0);
    let target = scenes::render("lab000-rgb", 640, 480).unwrap();
    // The triangle lies at constant depth, so screen-space barycentrics are exact here.
    let v = [
        lab_project(Vec3::new(0.0, 4.0, 2.0), w, h),
        lab_project(Vec3::new(3.0, -2.0, 2.0), w, h),
        lab_project(Vec3::new(-3.0, -2.0, 2.0), w, h),
    ];
    let cross = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let area = cross(v[0], v[1], v[2]);
    let mut checked = 0;
    for y in (0..480).step_by(5) {
        for x in (0..640).step_by(5) {
            let p = DVec2::from(raster::sample_centre(x, y));
            let weights =
                [cross(v[1], v[2], p), cross(v[2], v[0], p), cross(v[0], v[1], p)].map(|e| e / area);
            let pixel = target.pixel(x, y).unwrap();
            // A weight above 0.01 puts the sample over 1.8 px inside every edge (the smallest
            // altitude is 186 px), far beyond the < 1/256 px snapping moves an edge: surely covered.
            if weights.iter().all(|&b| b > 0.01) {
                for channel in 0..3 {
                    // Expected red, green, blue are the weights of vertices 0, 1, 2. Tolerance: 0.5
                    // for the rounding to 8 bits plus 0.5 for the f32 pipeline and snapped vertices.
                    assert_abs_diff_eq!(f64::from(pixel[channel]), weights[channel] * 255.0, epsilon = 1.0);
                }
                checked += 1;
            } else if weights.iter().any(|&b| b < -0.01) {
                assert_eq!(pixel, CLEAR, "pixel ({x}, {y}) is outside the triangle");
            }
        }
    }
    // The triangle covers about 21 600 px², so a 5-px grid holds about 860 samples, most interior.
    assert!(checked > 600, "only {checked} interior pixels checked");
}

#[test]
fn red_triangle_hides_the_rgb_one() {
    let target = scenes::render("lab000-depth", 640, 480).unwrap();
    // The red triangle's centroid (0, 0, 0) projects to the screen centre, in front of the RGB one.
    let c = lab_project(Vec3::ZERO, 640.0, 480.0);
    assert_eq!(target.pixel(c.x as u32, c.y as u32 + 10), Some([255, 0, 0, 255]));
    // Near the RGB triangle's lower left corner, outside the red one, blue dominates.
    let corner = lab_project(Vec3::new(-2.8, -1.9, 2.0), 640.0, 480.0);
    let pixel = target.pixel(corner.x as u32, corner.y as u32).unwrap();
    assert!(pixel[2] > 200 && pixel[0] < 40, "{pixel:?}");
}
