//! Counterexample pictures: the zoomed pixel grid, samples coloured by class, outlines on top.
//!
//! Colours follow dEQP: missing purple, unexpected red, double-covered blue, don't-care yellow;
//! rightly covered samples are light grey, rightly empty ones dark grey. Triangles are outlined
//! in white where they are visible. Below the grid a caption repeats the legend, then what went
//! wrong with its numbers, one line per wrong sample (the first few).

use image::{Rgba, RgbaImage};
use refrast::stage::{LineVertex, rasterize_line};
use refrast::{Fragment, Viewport};

use crate::oracle::outline::{OutlinePoint, visible_outline};
use refrast::Topology;

use crate::scene::{PrimitiveScene, Scene};
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

/// The outlines a picture of `case` draws: its triangles', each segment, or each point's square,
/// in pixels.
#[must_use]
pub fn primitive_outlines(case: &PrimitiveScene) -> Vec<Vec<[f64; 2]>> {
    let (w, h) = (case.scene.width, case.scene.height);
    let raster = |p: [f32; 4]| {
        let p = p.map(f64::from);
        crate::oracle::raster::project(w, h, p)
    };
    match case.topology {
        Topology::TriangleList => scene_outlines(&case.scene),
        Topology::TriangleStrip | Topology::TriangleFan => scene_outlines(&case.as_list().scene),
        Topology::LineList | Topology::LineStrip => (0..case.primitive_count())
            .filter_map(|i| case.segment(i))
            .filter(|ends| ends.iter().all(|p| p[3] > 0.0))
            .map(|ends| ends.map(raster).to_vec())
            .collect(),
        Topology::PointList => case
            .indices
            .iter()
            .map(|&i| case.scene.positions[i as usize])
            .filter(|p| p[3] > 0.0)
            .map(|p| {
                let [x, y] = raster(p);
                vec![
                    [x - 0.5, y - 0.5],
                    [x + 0.5, y - 0.5],
                    [x + 0.5, y + 0.5],
                    [x - 0.5, y + 0.5],
                ]
            })
            .collect(),
    }
}

/// A picture of `fragments` of `scene`: covered once grey, more often blue, `samples` (those a
/// failure is about) red, with the triangles' outlines.
#[must_use]
pub fn of_fragments(scene: &Scene, fragments: &[Fragment], samples: &[(u32, u32)]) -> Picture {
    let (w, h) = (scene.width, scene.height);
    let mut classes: Vec<Class> = count_fragments(fragments, w, h)
        .iter()
        .map(|&n| match n {
            0 => Class::Empty,
            1 => Class::Covered,
            _ => Class::Double,
        })
        .collect();
    for &(x, y) in samples.iter().filter(|&&(x, y)| x < w && y < h) {
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

/// Height of a caption line in pixels (8×8 glyphs and a 2-pixel gap).
const LINE: u32 = 10;

/// The legend: each class's name in its own colour.
const LEGEND: [(Class, &str); 6] = [
    (Class::Covered, "covered"),
    (Class::Empty, "empty"),
    (Class::Missing, "missing"),
    (Class::Unexpected, "wrong"),
    (Class::Double, "double"),
    (Class::DontCare, "don't care"),
];

/// Pixels of margin kept around the wrong samples when a picture is cropped to them: enough
/// to see the edges that pass by them.
pub const MARGIN: u32 = 4;

/// The smallest side a cropped picture keeps, in pixels: so that a lone wrong sample is still
/// shown among its neighbours.
pub const LEAST_SIDE: u32 = 16;

/// The part of a picture worth showing: a window around its wrong samples (missing, unexpected,
/// double), with [`MARGIN`] pixels around them and sides of at least [`LEAST_SIDE`], when that
/// window shows at most half of the viewport; `None` (show it whole) otherwise, and for a
/// picture without wrong samples. Returns `[x0, y0, width, height]`.
#[must_use]
pub fn focus(picture: &Picture) -> Option<[u32; 4]> {
    let (w, h) = (picture.width, picture.height);
    let wrong = |c: &Class| matches!(c, Class::Missing | Class::Unexpected | Class::Double);
    let mut bounds: Option<[u32; 4]> = None;
    for (i, _) in picture.classes.iter().enumerate().filter(|(_, c)| wrong(c)) {
        let (x, y) = (i as u32 % w, i as u32 / w);
        let b = bounds.get_or_insert([x, y, x, y]);
        *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    let [x0, y0, x1, y1] = bounds?;
    // One axis: the span [lo, hi] widened by the margin and to the least side, inside 0..side.
    let span = |lo: u32, hi: u32, side: u32| {
        let (mut a, mut b) = (lo.saturating_sub(MARGIN), (hi + MARGIN).min(side - 1));
        // One pixel at a time, on the side with less room taken, so that the side is exact.
        while b - a + 1 < LEAST_SIDE.min(side) {
            if a > 0 && (b + 1 >= side || lo - a <= b - hi) {
                a -= 1;
            } else {
                b += 1;
            }
        }
        (a, b - a + 1)
    };
    let ((cx, cw), (cy, ch)) = (span(x0, x1, w), span(y0, y1, h));
    (u64::from(cw) * u64::from(ch) * 2 <= u64::from(w) * u64::from(h)).then_some([cx, cy, cw, ch])
}

/// The window `[x0, y0, width, height]` of `picture`, its outlines moved with it.
#[must_use]
pub fn crop(picture: &Picture, [x0, y0, cw, ch]: [u32; 4]) -> Picture {
    let classes = (y0..y0 + ch)
        .flat_map(|y| (x0..x0 + cw).map(move |x| (x, y)))
        .map(|(x, y)| picture.classes[(y * picture.width + x) as usize])
        .collect();
    let (dx, dy) = (f64::from(x0), f64::from(y0));
    Picture {
        width: cw,
        height: ch,
        classes,
        outlines: picture
            .outlines
            .iter()
            .map(|o| o.iter().map(|p| [p[0] - dx, p[1] - dy]).collect())
            .collect(),
    }
}

/// The picture with a caption below it: the legend, then `lines` wrapped to its width. Where
/// the wrong samples lie in a small part of the viewport ([`focus`]), only that part is drawn,
/// larger, and the caption's first line says which part it is.
#[must_use]
pub fn render_with_caption(picture: &Picture, lines: &[String]) -> RgbaImage {
    if let Some(window @ [x0, y0, cw, ch]) = focus(picture) {
        let mut said = vec![format!(
            "shown: pixels x {x0}..{} and y {y0}..{} of the {}x{} viewport, around the wrong samples",
            x0 + cw - 1,
            y0 + ch - 1,
            picture.width,
            picture.height
        )];
        said.extend(lines.iter().cloned());
        return render_whole(&crop(picture, window), &said);
    }
    render_whole(picture, lines)
}

/// [`render_with_caption`] of the whole picture.
fn render_whole(picture: &Picture, lines: &[String]) -> RgbaImage {
    let grid = render(picture);
    // At least wide enough for the legend, so a small viewport still says what colours mean.
    let width = grid.width().max(8 * 70);
    let columns = (width / 8 - 1) as usize;
    let wrapped: Vec<String> = lines.iter().flat_map(|l| wrap(l, columns)).collect();
    let caption = LINE * (2 + wrapped.len() as u32) + 4;
    let mut img = RgbaImage::from_pixel(width, grid.height() + caption, Rgba([16, 16, 16, 255]));
    image::imageops::replace(&mut img, &grid, 0, 0);
    let mut x = 4;
    let y = grid.height() + 4;
    for (class, name) in LEGEND {
        let c = colour(class);
        // Dark grey on dark grey would vanish: empty samples are named in light grey.
        let c = if class == Class::Empty {
            [120, 120, 120, 255]
        } else {
            c
        };
        x = draw_text(&mut img, x, y, name, c) + 12;
    }
    draw_text(&mut img, x, y, "(white: outlines)", [255, 255, 255, 255]);
    for (i, line) in wrapped.iter().enumerate() {
        draw_text(
            &mut img,
            4,
            y + LINE * (i as u32 + 1) + 4,
            line,
            [235, 235, 235, 255],
        );
    }
    img
}

/// `text` cut into lines of at most `columns` characters, at spaces where it can be.
fn wrap(text: &str, columns: usize) -> Vec<String> {
    let mut out = Vec::new();
    for paragraph in text.lines() {
        let mut line = String::new();
        for word in paragraph.split(' ') {
            if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > columns {
                out.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
            while line.chars().count() > columns {
                let rest: String = line.chars().skip(columns).collect();
                out.push(line.chars().take(columns).collect());
                line = rest;
            }
        }
        out.push(line);
    }
    out
}

/// Draws `text` from `(x, y)` in 8×8 glyphs and returns where it ends; characters without a
/// glyph show as `?`.
fn draw_text(img: &mut RgbaImage, x: u32, y: u32, text: &str, colour: [u8; 4]) -> u32 {
    use font8x8::{BASIC_FONTS, GREEK_FONTS, LATIN_FONTS, UnicodeFonts};
    let mut x = x;
    for ch in text.chars() {
        let glyph = BASIC_FONTS
            .get(ch)
            .or_else(|| LATIN_FONTS.get(ch))
            .or_else(|| GREEK_FONTS.get(ch))
            .or_else(|| BASIC_FONTS.get('?'))
            .unwrap_or([0; 8]);
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                let (px, py) = (x + col, y + row as u32);
                if bits & (1 << col) != 0 && px < img.width() && py < img.height() {
                    img.put_pixel(px, py, Rgba(colour));
                }
            }
        }
        x += 8;
    }
    x
}

/// The picture with its caption, encoded as a PNG in memory: the runner decides where it goes.
pub fn png(picture: &Picture, caption: &[String]) -> Result<Vec<u8>, image::ImageError> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    render_with_caption(picture, caption).write_to(&mut bytes, image::ImageFormat::Png)?;
    Ok(bytes.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `width`×`height` picture, empty but for `wrong` samples double-covered.
    fn with_doubles(width: u32, height: u32, wrong: &[(u32, u32)]) -> Picture {
        let mut classes = vec![Class::Empty; (width * height) as usize];
        for &(x, y) in wrong {
            classes[(y * width + x) as usize] = Class::Double;
        }
        Picture {
            width,
            height,
            classes,
            outlines: vec![vec![[0.0, 0.0], [16.0, 64.0], [0.0, 64.0]]],
        }
    }

    /// One double-covered sample in a 16×64 viewport (issue 43's) is shown in a 16×16 window
    /// around it, the sample and the outlines moved with the window.
    #[test]
    fn a_lone_wrong_sample_in_a_tall_viewport_is_cropped_to() {
        let picture = with_doubles(16, 64, &[(5, 40)]);
        let window = focus(&picture).expect("a window");
        assert_eq!(window, [0, 32, 16, 16]);
        let cropped = crop(&picture, window);
        assert_eq!(cropped.classes[(8 * 16 + 5) as usize], Class::Double);
        assert_eq!(cropped.outlines[0][1], [16.0, 32.0]);
    }

    /// A small viewport, and wrong samples spread over a large one, are shown whole.
    #[test]
    fn small_or_spread_pictures_are_shown_whole() {
        assert_eq!(focus(&with_doubles(16, 16, &[(5, 5)])), None);
        assert_eq!(focus(&with_doubles(64, 64, &[(2, 2), (60, 60)])), None);
        assert_eq!(focus(&with_doubles(64, 64, &[])), None);
    }
}
