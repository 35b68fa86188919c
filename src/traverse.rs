//! Traversal: fan a snapped polygon, visit the pixels of a rectangle, keep the samples it covers.

use crate::edge::FillConvention;
use crate::fixed::{FixedPoint, SubpixelBits};
use crate::project::RasterVertex;
use crate::setup::{PixelRect, TriangleSetup, Winding};

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
