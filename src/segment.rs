//! Lines and points on snapped end points, decided exactly in integers: the diamond-exit rule,
//! rectangles and parallelograms one pixel wide, and points one pixel square.
//!
//! Ties are broken as the fill convention nudges a sample ([`FillConvention::owns_edge`]):
//! by `(±ε, ±ε²)`, so a sample on the edge of a line's rectangle or a point's square is
//! covered as a polygon's would be. The diamond-exit rule nudges the end points instead, by
//! `−(ε, ε²)`, as Vulkan and OpenGL state it. Every value is a polynomial in ε compared by the
//! sign of its first non-zero coefficient ([`Nudged`]).

use std::cmp::Ordering;

use crate::edge::FillConvention;
use crate::fixed::FixedPoint;
use crate::primitive::LineRule;

/// `v[0] + v[1]·ε + v[2]·ε²` for an infinitesimal `ε > 0`: the exact value of a nudged quantity.
pub type Nudged = [i128; 3];

/// The sign of a nudged value: that of its first non-zero coefficient.
#[must_use]
pub fn sign(v: Nudged) -> Ordering {
    v.into_iter()
        .map(|c| c.cmp(&0))
        .find(|&o| o != Ordering::Equal)
        .unwrap_or(Ordering::Equal)
}

fn sub(a: Nudged, b: Nudged) -> Nudged {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn abs(v: Nudged) -> Nudged {
    if sign(v) == Ordering::Less {
        v.map(|c| -c)
    } else {
        v
    }
}

fn less(a: Nudged, b: Nudged) -> bool {
    sign(sub(a, b)) == Ordering::Less
}

/// `a < v < b` (or `b < v < a`): strictly between the two.
fn between(v: Nudged, a: Nudged, b: Nudged) -> bool {
    (less(a, v) && less(v, b)) || (less(b, v) && less(v, a))
}

/// The product of two nudged values, to ε².
fn mul(a: Nudged, b: Nudged) -> Nudged {
    [
        a[0] * b[0],
        a[0] * b[1] + a[1] * b[0],
        a[0] * b[2] + a[1] * b[1] + a[2] * b[0],
    ]
}

/// The nudge a fill convention gives a sample, `(sx·ε, sy·ε²)`: top-left moves it right and down.
#[must_use]
pub fn sample_nudge(fill: FillConvention) -> (i128, i128) {
    // The one convention, read back from `owns_edge`: a vertical edge running up owns its
    // samples when the nudge is to the right; a horizontal one running right, when it is down.
    let at = |x, y| FixedPoint { x, y };
    let sx = if fill.owns_edge(at(0, 1), at(0, 0)) { 1 } else { -1 };
    let sy = if fill.owns_edge(at(0, 0), at(1, 0)) { 1 } else { -1 };
    (sx, sy)
}

/// A sample's coordinates nudged as `fill` says.
fn nudged_sample(s: FixedPoint, fill: FillConvention) -> (Nudged, Nudged) {
    let (sx, sy) = sample_nudge(fill);
    ([i128::from(s.x), sx, 0], [i128::from(s.y), 0, sy])
}

/// Whether `p`, nudged by `−(ε, ε²)`, lies in the open diamond `|x − c.x| + |y − c.y| < half`.
#[must_use]
pub fn in_diamond(p: FixedPoint, c: FixedPoint, half: i64) -> bool {
    let dx = abs([i128::from(p.x - c.x), -1, 0]);
    let dy = abs([i128::from(p.y - c.y), 0, -1]);
    less(
        [dx[0] + dy[0], dx[1] + dy[1], dx[2] + dy[2]],
        [i128::from(half), 0, 0],
    )
}

/// Whether segment `a → b`, both ends nudged by `−(ε, ε²)`, meets the open diamond of radius
/// `half` at `c`.
///
/// The L1 distance to `c` along a segment is convex and piecewise linear, so its least value
/// lies at an end or where the segment crosses the vertical or horizontal through `c`.
#[must_use]
pub fn meets_diamond(a: FixedPoint, b: FixedPoint, c: FixedPoint, half: i64) -> bool {
    if in_diamond(a, c, half) || in_diamond(b, c, half) {
        return true;
    }
    let (dx, dy) = (i128::from(b.x - a.x), i128::from(b.y - a.y));
    let (ax, ay) = (i128::from(a.x - c.x), i128::from(a.y - c.y));
    let half = i128::from(half);
    // Crossing x = c.x at s = (c.x − a.x + ε)/dx; there |y − c.y| = |n|/|dx|.
    let vertical = dx != 0 && {
        let t = [-ax, 1, 0];
        let n = [ay * dx - ax * dy, dy, -dx];
        between(t, [0; 3], [dx, 0, 0]) && less(abs(n), [half * dx.abs(), 0, 0])
    };
    // Crossing y = c.y at s = (c.y − a.y + ε²)/dy; there |x − c.x| = |m|/|dy|.
    let horizontal = dy != 0 && {
        let t = [-ay, 0, 1];
        let m = [ax * dy - ay * dx, -dy, dx];
        between(t, [0; 3], [dy, 0, 0]) && less(abs(m), [half * dy.abs(), 0, 0])
    };
    vertical || horizontal
}

/// The diamond-exit rule at the pixel whose centre is `c`: the segment meets its diamond and
/// does not end in it.
#[must_use]
pub fn diamond_exit(a: FixedPoint, b: FixedPoint, c: FixedPoint, half: i64) -> bool {
    meets_diamond(a, b, c, half) && !in_diamond(b, c, half)
}

/// Whether sample `s`, nudged as `fill` says, lies inside the rectangle of half-width `half`
/// along segment `a → b`, from end to end.
#[must_use]
pub fn in_rectangle(a: FixedPoint, b: FixedPoint, s: FixedPoint, half: i64, fill: FillConvention) -> bool {
    let Relative {
        dx,
        dy,
        rx,
        ry,
        cross,
    } = relative(a, b, s, fill);
    let length2 = dx * dx + dy * dy;
    if length2 == 0 {
        return false;
    }
    // Across: the distance to the line is |cross| / length; along: dot / length.
    let dot = [0, 1, 2].map(|k| rx[k] * dx + ry[k] * dy);
    let half = i128::from(half);
    less(mul(cross, cross), [half * half * length2, 0, 0]) && between(dot, [0; 3], [length2, 0, 0])
}

/// Whether sample `s`, nudged as `fill` says, lies inside the parallelogram along `a → b`
/// whose short sides, `2·half` long, lie along the minor axis through the end points (x is
/// the major axis when the two are equal).
#[must_use]
pub fn in_parallelogram(
    a: FixedPoint,
    b: FixedPoint,
    s: FixedPoint,
    half: i64,
    fill: FillConvention,
) -> bool {
    let Relative {
        dx,
        dy,
        rx,
        ry,
        cross,
    } = relative(a, b, s, fill);
    if dx == 0 && dy == 0 {
        return false;
    }
    let half = i128::from(half);
    // Across the major axis the offset from the line is |cross| / |major|.
    let (major, along) = if dx.abs() >= dy.abs() { (dx, rx) } else { (dy, ry) };
    less(abs(cross), [half * major.abs(), 0, 0]) && between(along, [0; 3], [major, 0, 0])
}

/// Sample `s`, nudged as `fill` says, relative to segment `a → b`.
struct Relative {
    /// The segment's run in x.
    dx: i128,
    /// The segment's run in y.
    dy: i128,
    /// The nudged sample's x minus `a`'s.
    rx: Nudged,
    /// The nudged sample's y minus `a`'s.
    ry: Nudged,
    /// `(b − a) × (s − a)`: the sample's offset across the line, times the segment's length.
    cross: Nudged,
}

fn relative(a: FixedPoint, b: FixedPoint, s: FixedPoint, fill: FillConvention) -> Relative {
    let (dx, dy) = (i128::from(b.x - a.x), i128::from(b.y - a.y));
    let (sx, sy) = nudged_sample(s, fill);
    let (rx, ry) = (sub(sx, [i128::from(a.x), 0, 0]), sub(sy, [i128::from(a.y), 0, 0]));
    let cross = sub(ry.map(|c| c * dx), rx.map(|c| c * dy));
    Relative {
        dx,
        dy,
        rx,
        ry,
        cross,
    }
}

/// Whether sample `s`, nudged as `fill` says, lies inside the square of half-side `half`
/// centred on `p`.
#[must_use]
pub fn in_point_square(p: FixedPoint, s: FixedPoint, half: i64, fill: FillConvention) -> bool {
    let (sx, sy) = nudged_sample(s, fill);
    let half = i128::from(half);
    let inside = |v: Nudged, centre: i64| {
        let d = sub(v, [i128::from(centre), 0, 0]);
        less(abs(d), [half, 0, 0])
    };
    inside(sx, p.x) && inside(sy, p.y)
}

/// Whether `rule` covers a sample of a segment `a → b`: for the diamond-exit rule `s` is the
/// pixel's centre (the rule is per pixel), for the others any sample.
#[must_use]
pub fn covers(
    rule: LineRule,
    a: FixedPoint,
    b: FixedPoint,
    s: FixedPoint,
    half: i64,
    fill: FillConvention,
) -> bool {
    match rule {
        LineRule::DiamondExit => diamond_exit(a, b, s, half),
        LineRule::Rectangle => in_rectangle(a, b, s, half, fill),
        LineRule::Parallelogram => in_parallelogram(a, b, s, half, fill),
    }
}

/// The pixels a segment `a → b` may cover under any line rule, along its major axis: each
/// column (or row) within one pixel of its span and inside `window` (`[width, height]` pixels
/// from the origin), and in it the five pixels nearest the line.
///
/// Every rule covers only samples within `half·√2` of the segment across its major axis, so
/// no covered pixel lies further than two rows (columns) from the line's pixel there. The
/// window keeps a segment clipped at the guard band, thousands of pixels long, to the columns
/// that can hold a fragment.
pub fn candidates(a: FixedPoint, b: FixedPoint, one: i64, window: [i64; 2], mut visit: impl FnMut(i64, i64)) {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    if dx == 0 && dy == 0 {
        return;
    }
    let x_major = dx.abs() >= dy.abs();
    // Along the major axis u, across it v: swap x and y for a y-major segment.
    let (au, av, du, dv, extent) = if x_major {
        (a.x, a.y, dx, dy, window[0])
    } else {
        (a.y, a.x, dy, dx, window[1])
    };
    let (lo, hi) = (au.min(au + du), au.max(au + du));
    let half = one / 2;
    for pu in (lo.div_euclid(one) - 1).max(0)..=(hi.div_euclid(one) + 1).min(extent - 1) {
        let cu = pu * one + half;
        // The line at the column's centre: av + (cu − au)·dv/du, floored exactly.
        let v = i128::from(av) + (i128::from(cu - au) * i128::from(dv)).div_euclid(i128::from(du));
        let pv = i64::try_from(v.div_euclid(i128::from(one))).unwrap_or(i64::MAX - 2);
        for qv in pv - 2..=pv + 2 {
            if x_major { visit(pu, qv) } else { visit(qv, pu) }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE: i64 = 256;
    const HALF: i64 = 128;

    fn px(x: f64, y: f64) -> FixedPoint {
        FixedPoint {
            x: (x * ONE as f64) as i64,
            y: (y * ONE as f64) as i64,
        }
    }

    fn centre(x: i64, y: i64) -> FixedPoint {
        FixedPoint {
            x: x * ONE + HALF,
            y: y * ONE + HALF,
        }
    }

    fn diamond_pixels(a: FixedPoint, b: FixedPoint) -> Vec<(i64, i64)> {
        let mut out = Vec::new();
        candidates(a, b, ONE, [64, 64], |x, y| {
            if diamond_exit(a, b, centre(x, y), HALF) {
                out.push((x, y));
            }
        });
        out.sort_unstable();
        out
    }

    /// A horizontal segment from centre to centre draws its first pixel, not its last.
    #[test]
    fn a_horizontal_segment_draws_from_its_start_to_before_its_end() {
        assert_eq!(
            diamond_pixels(px(0.5, 0.5), px(4.5, 0.5)),
            [(0, 0), (1, 0), (2, 0), (3, 0)]
        );
        assert_eq!(
            diamond_pixels(px(4.5, 0.5), px(0.5, 0.5)),
            [(1, 0), (2, 0), (3, 0), (4, 0)]
        );
    }

    /// A diagonal x = y through the centres: one pixel per column; a segment that starts on a
    /// diamond's corner is decided by the nudge.
    #[test]
    fn a_diagonal_draws_one_pixel_per_column() {
        let line = diamond_pixels(px(0.5, 0.5), px(5.5, 5.5));
        assert_eq!(line, [(0, 0), (1, 1), (2, 2), (3, 3), (4, 4)]);
        // From the left corner of pixel (0, 0)'s diamond, rightwards: nudged left, the start
        // lies outside the diamond, and the segment enters it: pixel (0, 0) is drawn.
        assert!(diamond_exit(px(0.0, 0.5), px(3.0, 0.5), centre(0, 0), HALF));
        // Ending on pixel (2, 0)'s left corner: nudged left, the end lies outside that diamond,
        // which the segment never enters.
        assert!(!meets_diamond(px(0.0, 0.5), px(2.0, 0.5), centre(2, 0), HALF));
    }

    /// A zero-length segment draws nothing; a segment wholly inside one diamond draws nothing.
    #[test]
    fn short_segments_inside_one_diamond_draw_nothing() {
        assert!(diamond_pixels(px(1.5, 1.5), px(1.5, 1.5)).is_empty());
        assert!(diamond_pixels(px(1.4, 1.5), px(1.6, 1.5)).is_empty());
    }

    /// The rectangle one pixel wide along a horizontal segment through row centres covers
    /// half-open: the top edge owns its samples under top-left, the bottom one does not.
    #[test]
    fn rectangles_break_ties_as_polygons() {
        let fill = FillConvention::TopLeft;
        // Along y = 1 the rectangle spans rows' centres 0.5 and 1.5: its top and bottom edges.
        let (a, b) = (px(0.0, 1.0), px(4.0, 1.0));
        assert!(in_rectangle(a, b, centre(1, 0), HALF, fill), "top edge owns");
        assert!(
            !in_rectangle(a, b, centre(1, 1), HALF, fill),
            "bottom edge does not"
        );
        // The left end owns, the right end does not.
        let (a, b) = (px(0.5, 0.5), px(3.5, 0.5));
        assert!(in_rectangle(a, b, centre(0, 0), HALF, fill));
        assert!(!in_rectangle(a, b, centre(3, 0), HALF, fill));
        assert!(in_parallelogram(a, b, centre(0, 0), HALF, fill));
        assert!(!in_parallelogram(a, b, centre(3, 0), HALF, fill));
        // A 45° segment: the parallelogram reaches half a pixel vertically, the rectangle
        // half a pixel across, √2/2 vertically.
        let (a, b) = (px(0.0, 0.0), px(8.0, 8.0));
        assert!(!in_parallelogram(a, b, px(4.0, 4.6), HALF, fill));
        assert!(in_rectangle(a, b, px(4.0, 4.6), HALF, fill));
        assert!(in_parallelogram(a, b, px(4.0, 4.45), HALF, fill));
    }

    /// Points own the top and left sides of their square under top-left.
    #[test]
    fn a_point_covers_the_pixel_its_square_holds_the_centre_of() {
        let fill = FillConvention::TopLeft;
        assert!(in_point_square(px(2.3, 1.7), centre(2, 1), HALF, fill));
        assert!(
            in_point_square(px(3.0, 2.0), centre(2, 1), HALF, fill),
            "left and top sides own"
        );
        assert!(!in_point_square(px(3.0, 2.0), centre(3, 2), HALF, fill));
        assert_eq!(sample_nudge(FillConvention::TopLeft), (1, 1));
        assert_eq!(sample_nudge(FillConvention::BottomRight), (-1, -1));
    }
}
