//! Counterexample pictures: the zoomed pixel grid, samples coloured by class, outlines on top.
//!
//! Colours follow dEQP: missing purple, unexpected red, double-covered blue, don't-care yellow;
//! rightly covered samples are light grey, rightly empty ones dark grey.

use std::path::Path;

use image::{Rgba, RgbaImage};
use refrast::stage::{LineVertex, rasterize_line};
use refrast::{Fragment, Viewport};

use crate::oracle::outline::{OutlinePoint, visible_outline};
use crate::scene::Scene;
use crate::violation::{Class, Picture, count_fragments};

/// Colour of a sample class.
#[must_use]
pub fn colour(class: Class) -> [u8; 4] {
    match class {
        Class::Empty => [48, 48, 48, 255],
        Class::Covered => [200, 200, 200, 255],
        Class::Missing => [160, 32, 240, 255],
        Class::Unexpected => [230, 30, 30, 255],
        Class::Double => [40, 90, 255, 255],
        Class::DontCare => [240, 220, 40, 255],
    }
}

/// The finite part of each outline, in raster space: what a picture draws.
#[must_use]
pub fn finite_outlines(outlines: &[Vec<OutlinePoint>]) -> Vec<Vec<[f64; 2]>> {
    outlines
        .iter()
        .map(|o| o.iter().filter(|p| p.finite).map(|p| p.position).collect())
        .collect()
}

/// The visible outline of every triangle of `scene` whose indices are in range.
#[must_use]
pub fn scene_outlines(scene: &Scene) -> Vec<Vec<[f64; 2]>> {
    let outlines: Vec<Vec<OutlinePoint>> = (0..scene.triangles.len())
        .filter(|&t| {
            scene.triangles[t]
                .iter()
                .all(|&i| (i as usize) < scene.positions.len())
        })
        .map(|t| visible_outline(&scene.positions_of(t), scene.width, scene.height, &scene.state))
        .collect();
    finite_outlines(&outlines)
}

/// A picture of `fragments` of `scene`: covered once grey, more often blue, `sample` (the one a
/// failure is about) red, with the triangles' outlines.
#[must_use]
pub fn of_fragments(scene: &Scene, fragments: &[Fragment], sample: Option<(u32, u32)>) -> Picture {
    let (w, h) = (scene.width, scene.height);
    let mut classes: Vec<Class> = count_fragments(fragments, w, h)
        .iter()
        .map(|&n| match n {
            0 => Class::Empty,
            1 => Class::Covered,
            _ => Class::Double,
        })
        .collect();
    if let Some((x, y)) = sample.filter(|&(x, y)| x < w && y < h) {
        classes[y as usize * w as usize + x as usize] = Class::Unexpected;
    }
    Picture {
        width: w,
        height: h,
        classes,
        outlines: scene_outlines(scene),
    }
}

/// Pixels per viewport pixel: about 512 px across, between 4 and 32.
#[must_use]
pub fn zoom(width: u32, height: u32) -> u32 {
    (512 / width.max(height)).clamp(4, 32)
}

/// Renders the picture: one `zoom × zoom` cell per pixel, a grid, the outlines in white.
#[must_use]
pub fn render(picture: &Picture) -> RgbaImage {
    let z = zoom(picture.width, picture.height);
    let (w, h) = (picture.width * z, picture.height * z);
    let mut img = RgbaImage::new(w, h);
    for (i, class) in picture.classes.iter().enumerate() {
        let (px, py) = (i as u32 % picture.width, i as u32 / picture.width);
        let c = colour(*class);
        for dy in 0..z {
            for dx in 0..z {
                let edge = dx == 0 || dy == 0;
                let shade = if edge { c.map(|v| v / 2 + 10) } else { c };
                img.put_pixel(
                    px * z + dx,
                    py * z + dy,
                    Rgba([shade[0], shade[1], shade[2], 255]),
                );
            }
        }
        // The sample point itself, a dark dot at the cell centre.
        if z >= 8 {
            img.put_pixel(px * z + z / 2, py * z + z / 2, Rgba([0, 0, 0, 255]));
        }
    }
    let Ok(viewport) = Viewport::new(w, h) else {
        return img;
    };
    let zf = f64::from(z);
    let bounds = [-1.0, -1.0, f64::from(w) + 1.0, f64::from(h) + 1.0];
    for outline in &picture.outlines {
        for (i, a) in outline.iter().enumerate() {
            let b = outline[(i + 1) % outline.len()];
            let scaled = |p: [f64; 2]| [p[0] * zf, p[1] * zf];
            let Some((a, b)) = clip_to_rect(scaled(*a), scaled(b), bounds) else {
                continue;
            };
            let end = |p: [f64; 2]| LineVertex {
                x: p[0],
                y: p[1],
                depth: 0.0,
            };
            rasterize_line(end(a), end(b), viewport, |f| {
                img.put_pixel(f.x, f.y, Rgba([255, 255, 255, 255]));
            });
        }
    }
    img
}

/// The part of segment `a b` inside `[x0, y0, x1, y1]` (Liang–Barsky), if any.
fn clip_to_rect(a: [f64; 2], b: [f64; 2], r: [f64; 4]) -> Option<([f64; 2], [f64; 2])> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a[0] - r[0]),
        (dx, r[2] - a[0]),
        (-dy, a[1] - r[1]),
        (dy, r[3] - a[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1 && t0.is_finite() && t1.is_finite())
        .then(|| ([a[0] + t0 * dx, a[1] + t0 * dy], [a[0] + t1 * dx, a[1] + t1 * dy]))
}

/// Writes the picture as a PNG.
pub fn save(picture: &Picture, path: &Path) -> Result<(), image::ImageError> {
    render(picture).save_with_format(path, image::ImageFormat::Png)
}
