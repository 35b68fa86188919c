//! Traversal: fan a snapped polygon, visit the pixels of a rectangle, keep the samples it covers.

use crate::edge::FillConvention;
use crate::fixed::{FixedPoint, SubpixelBits};
use crate::project::RasterVertex;
use crate::setup::{TriangleSetup, Winding};
use crate::viewport::Viewport;

/// A half-open rectangle of pixels, `x0..x1 × y0..y1`, always inside a viewport.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelRect {
    pub(crate) x0: u32,
    pub(crate) y0: u32,
    pub(crate) x1: u32,
    pub(crate) y1: u32,
}

impl PixelRect {
    /// First column, last column + 1, first row, last row + 1.
    #[must_use]
    pub fn bounds(self) -> (u32, u32, u32, u32) {
        (self.x0, self.x1, self.y0, self.y1)
    }

    /// The whole viewport.
    #[must_use]
    pub fn of_viewport(viewport: Viewport) -> Self {
        Self {
            x0: 0,
            y0: 0,
            x1: viewport.width(),
            y1: viewport.height(),
        }
    }

    /// The pixels whose samples lie in the bounding box of `points`, clamped to the viewport.
    ///
    /// `None` when no sample of the viewport lies in the box.
    #[must_use]
    pub fn bounding(
        points: impl IntoIterator<Item = FixedPoint>,
        bits: SubpixelBits,
        viewport: Viewport,
    ) -> Option<Self> {
        let (one, half) = (bits.one(), bits.one() / 2);
        let mut points = points.into_iter();
        let p = points.next()?;
        let ((min_x, min_y), (max_x, max_y)) = points.fold(((p.x, p.y), (p.x, p.y)), |(lo, hi), p| {
            ((lo.0.min(p.x), lo.1.min(p.y)), (hi.0.max(p.x), hi.1.max(p.y)))
        });
        // Pixel px has its sample at px·one + half: the first with sample ≥ min, the last with sample ≤ max.
        let first = |min: i64| bits.pixel_of(min - half + one - 1);
        let last = |max: i64| bits.pixel_of(max - half);
        let clamp = |v: i64, side: u32| v.clamp(0, i64::from(side)) as u32;
        let rect = Self {
            x0: clamp(first(min_x), viewport.width()),
            y0: clamp(first(min_y), viewport.height()),
            x1: clamp(last(max_x) + 1, viewport.width()),
            y1: clamp(last(max_y) + 1, viewport.height()),
        };
        (rect.x0 < rect.x1 && rect.y0 < rect.y1).then_some(rect)
    }
}

/// One triangle of a convex polygon's fan.
///
/// Snapping can make a sliver of a clipped polygon's fan turn the other way from the polygon.
/// Counting such a sliver as −1 makes coverage the winding number of the snapped outline, so a
/// fan never covers a sample twice nor one outside its outline.
#[derive(Clone, Copy, Debug)]
pub struct FanTriangle {
    /// The set-up triangle, with its own winding.
    pub setup: TriangleSetup,
    /// The polygon vertex indices of the triangle's input vertices.
    pub corners: [usize; 3],
}

impl FanTriangle {
    /// The fan of a triangle drawn whole: the triangle itself.
    #[must_use]
    pub fn whole(setup: TriangleSetup) -> Self {
        Self {
            setup,
            corners: [0, 1, 2],
        }
    }
}

/// Fans the snapped polygon `raster` from its first vertex into `fan`, leaving out the
/// zero-area triangles (they cover nothing).
pub fn build_fan(raster: &[RasterVertex], fill: FillConvention, fan: &mut Vec<FanTriangle>) {
    fan.clear();
    for i in 1..raster.len().saturating_sub(1) {
        let corners = [0, i, i + 1];
        if let Some(setup) = TriangleSetup::new(corners.map(|c| raster[c].position), fill) {
            fan.push(FanTriangle { setup, corners });
        }
    }
}

/// A covered sample and the fan triangle that covers it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Hit {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Index of the covering triangle in the fan.
    pub triangle: usize,
    /// The exact edge values there; `values[k] / area2` is the weight of setup vertex k.
    pub values: [i64; 3],
}

/// Visits every sample in `rect` whose winding number in the fan is one, for a polygon that
/// turns as `winding` says (fan triangles turning the other way count −1).
///
/// Edge values are stepped incrementally along each row, started exactly at each row's first
/// sample, so every value is the exact `orient2d` of that sample.
pub fn traverse(
    fan: &[FanTriangle],
    winding: Winding,
    rect: PixelRect,
    bits: SubpixelBits,
    row: &mut Vec<[i64; 3]>,
    mut visit: impl FnMut(Hit),
) {
    let one = bits.one();
    let agrees = |t: &FanTriangle| t.setup.winding() == winding;
    if let [single] = fan {
        // Alone, a triangle turned over by snapping has winding −1 everywhere: it draws nothing.
        if agrees(single) {
            traverse_triangle(single, rect, bits, visit);
        }
        return;
    }
    for y in rect.y0..rect.y1 {
        let start = FixedPoint::pixel_sample(i64::from(rect.x0), i64::from(y), bits);
        row.clear();
        row.extend(fan.iter().map(|t| t.setup.edge_values(start)));
        for x in rect.x0..rect.x1 {
            let mut count = 0;
            let mut first = None;
            for (i, (t, values)) in fan.iter().zip(row.iter()).enumerate() {
                if t.setup.is_inside(*values) {
                    let agrees = agrees(t);
                    count += if agrees { 1 } else { -1 };
                    if agrees && first.is_none() {
                        first = Some(i);
                    }
                }
            }
            if let (1, Some(triangle)) = (count, first) {
                visit(Hit {
                    x,
                    y,
                    triangle,
                    values: row[triangle],
                });
            }
            for (t, values) in fan.iter().zip(row.iter_mut()) {
                for (value, edge) in values.iter_mut().zip(&t.setup.edges) {
                    *value += edge.pixel_step_x(one);
                }
            }
        }
    }
}

/// The common case of a fan of one agreeing triangle: the winding number is just "inside".
fn traverse_triangle(t: &FanTriangle, rect: PixelRect, bits: SubpixelBits, mut visit: impl FnMut(Hit)) {
    let one = bits.one();
    let steps = t.setup.edges.map(|e| e.pixel_step_x(one));
    for y in rect.y0..rect.y1 {
        let mut values =
            t.setup
                .edge_values(FixedPoint::pixel_sample(i64::from(rect.x0), i64::from(y), bits));
        for x in rect.x0..rect.x1 {
            if t.setup.is_inside(values) {
                visit(Hit {
                    x,
                    y,
                    triangle: 0,
                    values,
                });
            }
            for (value, step) in values.iter_mut().zip(steps) {
                *value += step;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box of samples between (2.5, 3.2) and (4.6, 6.5) px on 8 bits: columns 2..5 and
    /// rows 3..7, as `bounds()` reads them back (first, end, first, end; a public accessor the
    /// reference never calls); a box holding no sample is none.
    #[test]
    fn a_bounding_box_reads_back_its_columns_and_rows() {
        let bits = SubpixelBits::DEFAULT;
        let points = [(2.5, 3.2), (4.6, 6.5)].map(|(x, y)| FixedPoint::snap(x, y, bits).unwrap());
        let rect = PixelRect::bounding(points, bits, Viewport::new(16, 16).unwrap()).unwrap();
        assert_eq!(rect.bounds(), (2, 5, 3, 7));
        // Between two columns of samples there is no pixel, whatever the rows hold.
        for thin in [[(2.6, 3.2), (2.9, 6.5)], [(2.5, 3.6), (4.6, 3.9)]] {
            let thin = thin.map(|(x, y)| FixedPoint::snap(x, y, bits).unwrap());
            assert_eq!(
                PixelRect::bounding(thin, bits, Viewport::new(16, 16).unwrap()),
                None
            );
        }
    }

    /// A set-up triangle on the 8-bit grid, vertices in 1/256 px.
    fn triangle(v: [(i64, i64); 3]) -> FanTriangle {
        let points = v.map(|(x, y)| FixedPoint::new(x, y).expect("in range"));
        FanTriangle::whole(TriangleSetup::new(points, FillConvention::TopLeft).expect("nonzero area"))
    }

    /// Where a fold puts a turned-over triangle over two that agree with the polygon, the
    /// sample has winding number one: it is drawn once, by the first agreeing triangle, even
    /// when the turned-over one comes first in the fan.
    #[test]
    fn a_turned_over_triangle_cancels_one_agreeing_cover() {
        let big = [(0, 0), (4096, 0), (0, 4096)];
        let turned = triangle([big[0], big[2], big[1]]);
        let (first, second) = (triangle(big), triangle([(0, 0), (2048, 0), (0, 2048)]));
        let winding = first.setup.winding();
        assert_ne!(turned.setup.winding(), winding);
        assert_eq!(second.setup.winding(), winding);
        let rect = PixelRect {
            x0: 0,
            y0: 0,
            x1: 2,
            y1: 2,
        };
        let mut hits = Vec::new();
        let fan = [turned, first, second];
        traverse(&fan, winding, rect, SubpixelBits::DEFAULT, &mut Vec::new(), |h| {
            hits.push((h.x, h.y, h.triangle));
        });
        assert_eq!(hits, [(0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]);
    }
}
