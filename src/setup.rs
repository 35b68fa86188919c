//! Triangle setup: orientation, edge functions and the pixel bounds worth visiting.

use crate::edge::{EdgeFunction, FillConvention, orient2d};
use crate::fixed::{FixedPoint, SubpixelBits};
use crate::viewport::Viewport;

/// Which way a triangle turns as seen on screen, from the sign of its snapped [`orient2d`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Winding {
    /// Clockwise on screen (positive `orient2d` with y down).
    Clockwise,
    /// Counter-clockwise on screen.
    CounterClockwise,
    /// Zero area after snapping: covers nothing and counts as back-facing (Vulkan, D3D11).
    Degenerate,
}

impl Winding {
    /// The winding of a triangle with doubled signed area `area2`.
    #[must_use]
    pub fn from_area2(area2: i64) -> Self {
        match area2.signum() {
            1 => Self::Clockwise,
            -1 => Self::CounterClockwise,
            _ => Self::Degenerate,
        }
    }
}

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
    pub fn bounding(points: &[FixedPoint], bits: SubpixelBits, viewport: Viewport) -> Option<Self> {
        let (one, half) = (bits.one(), bits.one() / 2);
        let min_x = points.iter().map(|p| p.x).min()?;
        let max_x = points.iter().map(|p| p.x).max()?;
        let min_y = points.iter().map(|p| p.y).min()?;
        let max_y = points.iter().map(|p| p.y).max()?;
        // Pixel px has its sample at px·one + half: the first with sample ≥ min, the last with sample ≤ max.
        let first = |min: i64| (min - half + one - 1).div_euclid(one);
        let last = |max: i64| (max - half).div_euclid(one);
        let clamp = |v: i64, side: u32| v.clamp(0, i64::from(side)) as u32;
        let rect = Self {
            x0: clamp(first(min_x), viewport.width()),
            y0: clamp(first(min_y), viewport.height()),
            x1: clamp(last(max_x) + 1, viewport.width()),
            y1: clamp(last(max_y) + 1, viewport.height()),
        };
        (rect.x0 < rect.x1 && rect.y0 < rect.y1).then_some(rect)
    }

    /// The smallest rectangle holding both.
    #[must_use]
    pub fn union(self, other: Self) -> Self {
        Self {
            x0: self.x0.min(other.x0),
            y0: self.y0.min(other.y0),
            x1: self.x1.max(other.x1),
            y1: self.y1.max(other.y1),
        }
    }
}

/// A non-degenerate snapped triangle ready for traversal, reordered to turn clockwise.
#[derive(Clone, Copy, Debug)]
pub struct TriangleSetup {
    /// The vertices in clockwise order.
    pub(crate) vertices: [FixedPoint; 3],
    /// `order[k]` is the input position of `vertices[k]` (the input is reordered when counter-clockwise).
    pub(crate) order: [usize; 3],
    /// `edges[k]` is the edge opposite `vertices[k]`, so its value is vertex k's barycentric weight.
    pub(crate) edges: [EdgeFunction; 3],
    /// Twice the (positive) area, the sum of the three edge values at any point.
    pub(crate) area2: i64,
}

impl TriangleSetup {
    /// Sets up `v` under `fill`; `None` for a zero-area triangle.
    #[must_use]
    pub fn new(v: [FixedPoint; 3], fill: FillConvention) -> Option<Self> {
        let area2 = orient2d(v[0], v[1], v[2]);
        let order = match Winding::from_area2(area2) {
            Winding::Clockwise => [0, 1, 2],
            Winding::CounterClockwise => [0, 2, 1],
            Winding::Degenerate => return None,
        };
        let [a, b, c] = order.map(|i| v[i]);
        Some(Self {
            vertices: [a, b, c],
            order,
            edges: [
                EdgeFunction::new(b, c, fill),
                EdgeFunction::new(c, a, fill),
                EdgeFunction::new(a, b, fill),
            ],
            area2: area2.abs(),
        })
    }

    /// The vertices in clockwise order.
    #[must_use]
    pub fn vertices(&self) -> [FixedPoint; 3] {
        self.vertices
    }

    /// `order()[k]` is the input position of `vertices()[k]`.
    #[must_use]
    pub fn order(&self) -> [usize; 3] {
        self.order
    }

    /// Twice the triangle's (positive) area in square subpixel units.
    #[must_use]
    pub fn area2(&self) -> i64 {
        self.area2
    }

    /// The three edge values at `p` (exact), whether or not `p` is inside.
    #[must_use]
    #[inline]
    pub fn edge_values(&self, p: FixedPoint) -> [i64; 3] {
        self.edges.map(|e| e.value(p))
    }

    /// Whether edge values mean inside under the fill rule: every biased value is non-negative.
    #[must_use]
    #[inline]
    pub fn is_inside(&self, values: [i64; 3]) -> bool {
        // One sign test: the OR of the three is negative exactly when one of them is.
        let [a, b, c] = [0, 1, 2].map(|k| self.edges[k].biased(values[k]));
        a | b | c >= 0
    }
}
