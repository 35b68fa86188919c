//! Traversal: visit the pixels of a bounding box and keep the samples a polygon's fan covers.

use crate::fixed::{FixedPoint, SubpixelBits};
use crate::setup::{PixelRect, TriangleSetup};

/// One triangle of a convex polygon's fan, with its turn relative to the whole polygon.
///
/// Snapping can make a sliver of a clipped polygon's fan turn the other way. Counting such a
/// sliver as −1 makes coverage the winding number of the snapped outline, so a fan never
/// covers a sample twice nor one outside its outline.
#[derive(Clone, Copy, Debug)]
pub struct FanTriangle {
    /// The set-up triangle.
    pub setup: TriangleSetup,
    /// `true` when it turns the same way as the polygon.
    pub agrees: bool,
    /// The polygon vertex indices of the triangle's input vertices.
    pub corners: [usize; 3],
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

/// Visits every sample in `rect` whose winding number in the fan is one.
///
/// Edge values are stepped incrementally along each row, started exactly at each row's first
/// sample, so every value is the exact `orient2d` of that sample.
pub fn traverse(
    fan: &[FanTriangle],
    rect: PixelRect,
    bits: SubpixelBits,
    row: &mut Vec<[i64; 3]>,
    mut visit: impl FnMut(Hit),
) {
    let one = bits.one();
    if let [single] = fan {
        // Alone, a triangle turned over by snapping has winding −1 everywhere: it draws nothing.
        if single.agrees {
            traverse_triangle(single, rect, bits, visit);
        }
        return;
    }
    for y in rect.y0..rect.y1 {
        let start = FixedPoint::pixel_sample(i64::from(rect.x0), i64::from(y), bits);
        row.clear();
        row.extend(fan.iter().map(|t| t.setup.edge_values(start)));
        for x in rect.x0..rect.x1 {
            let mut winding = 0;
            let mut first = None;
            for (i, (t, values)) in fan.iter().zip(row.iter()).enumerate() {
                if t.setup.is_inside(*values) {
                    winding += if t.agrees { 1 } else { -1 };
                    if t.agrees && first.is_none() {
                        first = Some(i);
                    }
                }
            }
            if let (1, Some(triangle)) = (winding, first) {
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
