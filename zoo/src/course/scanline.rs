//! `lab003-scanline-zbuffer`: the scanline z-buffer of seed 003 (CS174, "Z-Buffer Algorithm"),
//! built as its steps 1–3 and its speed-ups describe it.
//!
//! What the seed says, and what this module therefore does:
//!
//! - **One scanline at a time** (step 1): rows top to bottom, each sampled at its centre
//!   `y + ½`. The depth buffer is **one row wide** ([`RowBuffer`]), cleared at each row: memory
//!   in proportion to the width, not the area.
//! - **An active polygon list** (step 2, with the bounding-box speed-up): each face is bucketed by
//!   its `y_min`; a face joins the list at the first row at or below its `y_min` and leaves after
//!   the row above its `y_max`. The list is kept in the order faces join it (by `y_min`), which
//!   is the order a row's spans are depth-tested.
//! - **Span ends from x-intercepts** (step 3): each edge of a face that the row's centre crosses,
//!   from its top end (included) to its bottom end (excluded), gives an intercept; the span runs
//!   over the pixel centres from the left intercept (included) to the right (excluded). Those
//!   half-open ends are the top-left rule, decided in `f64` on unsnapped coordinates.
//! - **Incremental depth** along the span: `z` at the first pixel from the face's plane, then
//!   `z += −A/C` per pixel, in `f32` as a student's `float` would. The barycentrics are stepped
//!   the same way as seed 002's `q/z` (weights over `w` and `1/w`, divided per pixel).
//! - **The test**: each of a row's fragments against the row buffer with the draw's compare op and
//!   write mask, in the list's order.
//!
//! Clipping, projection and culling come first ([`screen::polygons`]). Accumulating in `f32`
//! drifts along a span by about one `f32` step of the value per pixel, so it claims 14 bits of
//! interpolation precision (the value the profiles use for an `f32` plane-equation rasterizer),
//! not the reference's 18.

use refrast::{
    DepthConvention, Draw, DrawError, FillConvention, Fragment, Profile, Rasterizer, Resolved, Snapping, Spec,
};

use super::screen::{self, ScreenPolygon};

/// Seed 003's scanline z-buffer: an active polygon list, x-intercept spans, a one-row depth buffer.
#[derive(Clone, Copy, Debug, Default)]
pub struct ScanlineZBuffer;

/// The depth and primitive-id buffers of one row: the scanline z-buffer's whole memory.
#[derive(Clone, Debug, PartialEq)]
pub struct RowBuffer {
    /// Depth per pixel of the row.
    pub depth: Vec<f32>,
    /// The primitive last passing the test at each pixel of the row.
    pub primitive: Vec<Option<u32>>,
}

/// Where the row's centre `yc` crosses the polygon: the left and right x-intercepts of the edges
/// it crosses, each edge from its top end (included) to its bottom end (excluded).
#[must_use]
pub fn intercepts(corners: &[[f64; 2]], yc: f64) -> Option<(f64, f64)> {
    let mut xs = (0..corners.len()).filter_map(|i| {
        let (p, q) = (corners[i], corners[(i + 1) % corners.len()]);
        let (top, bottom) = if p[1] <= q[1] { (p, q) } else { (q, p) };
        (top[1] <= yc && yc < bottom[1])
            .then(|| top[0] + (yc - top[1]) * (bottom[0] - top[0]) / (bottom[1] - top[1]))
    });
    let first = xs.next()?;
    let (left, right) = xs.fold((first, first), |(l, r), x| (l.min(x), r.max(x)));
    (left < right).then_some((left, right))
}

/// The fragments of one polygon on row `y`, depth and barycentrics stepped along the span.
fn span(poly: &ScreenPolygon, y: u32, width: u32, out: &mut Vec<Fragment>) {
    let yc = f64::from(y) + 0.5;
    let Some((left, right)) = intercepts(&poly.corners, yc) else {
        return;
    };
    // Pixel x is in the span when left ≤ x + ½ < right.
    let first = (left - 0.5).ceil().max(0.0);
    let end = (right - 0.5).ceil().min(f64::from(width));
    if first >= end {
        return;
    }
    let x0 = first + 0.5;
    let mut z = poly.depth.at(x0, yc) as f32;
    let dz = poly.depth.a as f32;
    let mut q = poly.w_inverse.at(x0, yc) as f32;
    let dq = poly.w_inverse.a as f32;
    let mut b = poly.weights_over_w.map(|p| p.at(x0, yc) as f32);
    let db = poly.weights_over_w.map(|p| p.a as f32);
    for x in first as u32..end as u32 {
        let barycentric = b.map(|b| b / q);
        out.push(Fragment {
            x,
            y,
            sample: 0,
            primitive: poly.primitive,
            depth: z.clamp(0.0, 1.0),
            barycentric,
            flat: None,
            screen_barycentric: None,
            front_facing: poly.front_facing,
        });
        z += dz;
        q += dq;
        for k in 0..3 {
            b[k] += db[k];
        }
    }
}

/// Runs the scanline loop, handing each row's fragments, in the active list's order, to `row`.
fn scan(draw: &Draw, mut row: impl FnMut(u32, &[Fragment])) {
    let (width, height) = (draw.viewport.width(), draw.viewport.height());
    let mut faces = screen::polygons(draw);
    // The edge table: faces bucketed by y_min (a stable sort keeps submission order within one).
    faces.sort_by(|a, b| a.y_range().0.total_cmp(&b.y_range().0));
    let mut next = 0;
    let mut active: Vec<&ScreenPolygon> = Vec::new();
    let mut fragments = Vec::new();
    for y in 0..height {
        let yc = f64::from(y) + 0.5;
        while next < faces.len() && faces[next].y_range().0 <= yc {
            active.push(&faces[next]);
            next += 1;
        }
        active.retain(|p| p.y_range().1 > yc);
        fragments.clear();
        for poly in &active {
            span(poly, y, width, &mut fragments);
        }
        row(y, &fragments);
    }
}

impl Rasterizer for ScanlineZBuffer {
    fn profile(&self) -> Profile {
        Profile {
            name: "lab003-scanline-zbuffer".into(),
            // Intercepts in f64 on the projected coordinates: no grid.
            snapping: Snapping::Float,
            // Half-open spans and edges own the top and left edges.
            fill: Some(FillConvention::TopLeft),
            // The plane equation of z/w, stepped along the row.
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: 1,
            // f32 accumulation along a span (module documentation).
            precision_bits: 14,
            features: screen::features(true),
            spec: Spec::Refrast,
            ..Profile::default()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        draw.validate()?;
        let mut out = Vec::new();
        scan(draw, |_, row| out.extend_from_slice(row));
        Ok(out)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        draw.validate()?;
        let viewport = draw.viewport;
        let width = viewport.width() as usize;
        let mut resolved = Resolved {
            viewport,
            samples: 1,
            depth: Vec::with_capacity(viewport.pixel_count()),
            primitive: Vec::with_capacity(viewport.pixel_count()),
        };
        let mut buffer = RowBuffer {
            depth: vec![draw.state.depth.clear; width],
            primitive: vec![None; width],
        };
        scan(draw, |_, row| {
            buffer.depth.fill(draw.state.depth.clear);
            buffer.primitive.fill(None);
            for f in row {
                let x = f.x as usize;
                if draw.state.depth.test_and_write(f.depth, &mut buffer.depth[x]) {
                    buffer.primitive[x] = Some(f.primitive);
                }
            }
            resolved.depth.extend_from_slice(&buffer.depth);
            resolved.primitive.extend_from_slice(&buffer.primitive);
        });
        Ok(resolved)
    }
}
