//! Edge functions (Pineda 1988) and the fill rule that breaks ties on shared edges.

use crate::fixed::FixedPoint;

/// Twice the signed area of `a, b, c`: positive when they turn clockwise on screen (y down).
///
/// Exact for every point: coordinates are at most [`FixedPoint::LIMIT`] = 2^23, so each
/// product is below 2^48.
#[doc(alias = "edge function")]
#[doc(alias = "determinant")]
#[doc(alias = "cross")]
#[must_use]
#[inline]
pub fn orient2d(a: FixedPoint, b: FixedPoint, c: FixedPoint) -> i64 {
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

/// Which edges own the samples that lie exactly on them.
///
/// Each convention is a fixed infinitesimal nudge of the sample: top-left moves it right by ε and
/// down by ε², so a sample on an edge counts as inside when the nudged sample is inside. Because
/// the nudge is one point for all triangles, every convention is watertight: a sample on an edge
/// shared by two triangles belongs to exactly one of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum FillConvention {
    /// D3D11 §3.4: top edges (horizontal, above the triangle) and left edges own their samples.
    #[default]
    TopLeft,
    /// Top and right edges own their samples.
    TopRight,
    /// Bottom and left edges own their samples (GL's "bottom-left" in llvmpipe).
    BottomLeft,
    /// Bottom and right edges own their samples.
    BottomRight,
}

impl FillConvention {
    /// Every convention, for listing and for tests.
    pub const ALL: [FillConvention; 4] = [Self::TopLeft, Self::TopRight, Self::BottomLeft, Self::BottomRight];

    /// Whether edge `a → b` of a clockwise (positive [`orient2d`]) triangle owns its samples.
    ///
    /// The one place where a fill convention is decided. The sample is nudged by
    /// `(sx·ε, sy·ε²)`; the edge function then changes by `(a.y − b.y)·sx·ε + (b.x − a.x)·sy·ε²`,
    /// whose sign is that of the first term unless the edge is horizontal.
    #[must_use]
    #[inline]
    pub fn owns_edge(self, a: FixedPoint, b: FixedPoint) -> bool {
        let (sx, sy) = match self {
            Self::TopLeft => (1, 1),
            Self::TopRight => (-1, 1),
            Self::BottomLeft => (1, -1),
            Self::BottomRight => (-1, -1),
        };
        let (step_x, step_y) = (a.y - b.y, b.x - a.x);
        if step_x != 0 {
            step_x * sx > 0
        } else {
            step_y * sy > 0
        }
    }

    /// The convention's name as the CLI and reports print it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::TopLeft => "top-left",
            Self::TopRight => "top-right",
            Self::BottomLeft => "bottom-left",
            Self::BottomRight => "bottom-right",
        }
    }
}

/// Whether edge `a → b` of a clockwise triangle is a top or a left edge (D3D11 §3.4).
///
/// A top edge is horizontal with the triangle below it (it runs left to right when clockwise);
/// a left edge is not horizontal and has the triangle on its right (it runs upwards).
#[must_use]
pub fn is_top_left(a: FixedPoint, b: FixedPoint) -> bool {
    FillConvention::TopLeft.owns_edge(a, b)
}

/// The edge function of `a → b` set up for stepping, with the fill rule folded into a bias.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeFunction {
    origin: FixedPoint,
    /// Change of the edge function per subpixel step in x.
    step_x: i64,
    /// Change of the edge function per subpixel step in y.
    step_y: i64,
    /// 0 when the edge owns its samples, −1 otherwise: a sample is inside when `value + bias ≥ 0`.
    bias: i64,
}

impl EdgeFunction {
    /// Sets up edge `a → b` of a clockwise triangle under `fill`.
    #[must_use]
    #[inline]
    pub fn new(a: FixedPoint, b: FixedPoint, fill: FillConvention) -> Self {
        Self {
            origin: a,
            step_x: a.y - b.y,
            step_y: b.x - a.x,
            bias: if fill.owns_edge(a, b) { 0 } else { -1 },
        }
    }

    /// The exact edge function at `p`, equal to `orient2d(a, b, p)`.
    #[must_use]
    #[inline]
    pub fn value(&self, p: FixedPoint) -> i64 {
        self.step_x * (p.x - self.origin.x) + self.step_y * (p.y - self.origin.y)
    }

    /// How much the value changes from one pixel to the next in x (`one` subpixel units per pixel).
    #[must_use]
    #[inline]
    pub fn pixel_step_x(&self, one: i64) -> i64 {
        self.step_x * one
    }

    /// The value with the fill rule folded in: non-negative exactly when the sample is inside.
    #[must_use]
    #[inline]
    pub fn biased(&self, value: i64) -> i64 {
        value + self.bias
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: i64, y: i64) -> FixedPoint {
        FixedPoint::new(x, y).unwrap()
    }

    #[test]
    fn orient2d_is_positive_for_clockwise_on_screen() {
        // Top-left, top-right, bottom: clockwise as seen with y pointing down.
        assert_eq!(orient2d(p(0, 0), p(10, 0), p(5, 10)), 100);
        assert_eq!(orient2d(p(0, 0), p(5, 10), p(10, 0)), -100);
        assert_eq!(orient2d(p(0, 0), p(5, 5), p(10, 10)), 0);
    }

    #[test]
    fn edge_function_value_matches_orient2d() {
        let (a, b, q) = (p(-7, 3), p(11, -5), p(4, 9));
        let e = EdgeFunction::new(a, b, FillConvention::TopLeft);
        assert_eq!(e.value(q), orient2d(a, b, q));
    }

    /// The names are the words the pipe protocol (`fill top-left`) and the reports use.
    #[test]
    fn conventions_are_named_as_the_protocol_spells_them() {
        let names = FillConvention::ALL.map(FillConvention::name);
        assert_eq!(names, ["top-left", "top-right", "bottom-left", "bottom-right"]);
    }

    #[test]
    fn opposite_conventions_own_opposite_directions() {
        for (a, b) in [(p(0, 0), p(4, 0)), (p(0, 0), p(0, 4)), (p(0, 0), p(3, -7))] {
            for fill in FillConvention::ALL {
                // Reversing an edge flips which side the triangle is on, so ownership flips too.
                assert_ne!(fill.owns_edge(a, b), fill.owns_edge(b, a), "{fill:?} {a:?} {b:?}");
            }
            assert_eq!(
                FillConvention::TopLeft.owns_edge(a, b),
                FillConvention::BottomRight.owns_edge(b, a)
            );
        }
    }
}
