//! Lines and points (labs 002 and 004): an exact integer DDA with depth and a parameter `t`.

use crate::fixed::COORD_LIMIT;
use crate::viewport::Viewport;

/// A line endpoint or point in raster space (pixels) with its window depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineVertex {
    /// x in pixels.
    pub x: f64,
    /// y in pixels, growing downwards.
    pub y: f64,
    /// Window depth.
    pub depth: f64,
}

/// A pixel of a line or point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFragment {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Position along the line in `[0, 1]`, 0 at the first endpoint; interpolate attributes by it.
    pub t: f64,
    /// Depth interpolated linearly in `t`.
    pub depth: f64,
}

/// The pixel holding a raster position, or `None` when it is not finite or beyond [`COORD_LIMIT`].
fn pixel_of(v: &LineVertex) -> Option<(i64, i64)> {
    let ok = |c: f64| c.is_finite() && c.abs() <= COORD_LIMIT;
    (ok(v.x) && ok(v.y) && v.depth.is_finite()).then(|| (v.x.floor() as i64, v.y.floor() as i64))
}

/// `num / den` rounded to the nearest integer, ties to even, exactly (`den > 0`).
fn div_round_even(num: i64, den: i64) -> i64 {
    let (q, r) = (num.div_euclid(den), num.rem_euclid(den));
    match (2 * r).cmp(&den) {
        std::cmp::Ordering::Less => q,
        std::cmp::Ordering::Greater => q + 1,
        std::cmp::Ordering::Equal => q + (q & 1),
    }
}

/// Rasterizes the segment `a → b` with one pixel per step along its major axis (a DDA).
///
/// The endpoints' pixels are joined by `max(|Δx|, |Δy|) + 1` pixels; step `i` takes the pixel
/// `p_a + Δ·i/n` rounded half to even in exact integers, so the line is 8-connected, contains
/// both endpoint pixels and covers the same pixels drawn `b → a`. Pixels outside the viewport
/// are skipped; an endpoint that is not finite or out of range draws nothing. Returns the count.
pub fn rasterize_line(
    a: LineVertex,
    b: LineVertex,
    viewport: Viewport,
    mut emit: impl FnMut(LineFragment),
) -> usize {
    let (Some((ax, ay)), Some((bx, by))) = (pixel_of(&a), pixel_of(&b)) else {
        return 0;
    };
    let (dx, dy) = (bx - ax, by - ay);
    let n = dx.abs().max(dy.abs());
    let mut count = 0;
    for i in 0..=n {
        let (x, y, t) = if n == 0 {
            (ax, ay, 0.0)
        } else {
            let x = div_round_even(ax * n + dx * i, n);
            let y = div_round_even(ay * n + dy * i, n);
            (x, y, i as f64 / n as f64)
        };
        if x < 0 || y < 0 || x >= i64::from(viewport.width()) || y >= i64::from(viewport.height()) {
            continue;
        }
        count += 1;
        emit(LineFragment {
            x: x as u32,
            y: y as u32,
            t,
            depth: a.depth + (b.depth - a.depth) * t,
        });
    }
    count
}

/// The pixel holding point `p`, if it lies in the viewport and is finite.
#[must_use]
pub fn rasterize_point(p: LineVertex, viewport: Viewport) -> Option<LineFragment> {
    let (x, y) = pixel_of(&p)?;
    let inside =
        (0..i64::from(viewport.width())).contains(&x) && (0..i64::from(viewport.height())).contains(&y);
    inside.then_some(LineFragment {
        x: x as u32,
        y: y as u32,
        t: 0.0,
        depth: p.depth,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> LineVertex {
        LineVertex { x, y, depth: 0.0 }
    }

    fn pixels(a: LineVertex, b: LineVertex) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        rasterize_line(a, b, Viewport::new(64, 64).unwrap(), |f| out.push((f.x, f.y)));
        out
    }

    #[test]
    fn lab002_interpolation_example() {
        // Lab 002 interpolates (4, 2) to (1, 8) in 4 steps: (4,2), (3,4), (2,6), (1,8). With one
        // pixel per row (Δy = 6 is the major axis) the DDA visits 7 pixels through those four.
        let line = pixels(v(4.5, 2.5), v(1.5, 8.5));
        assert_eq!(line.len(), 7);
        for p in [(4, 2), (3, 4), (2, 6), (1, 8)] {
            assert!(line.contains(&p), "{p:?} missing from {line:?}");
        }
    }

    #[test]
    fn reversed_line_covers_the_same_pixels() {
        let (a, b) = (v(3.2, 40.9), v(50.7, 17.1));
        let mut forward = pixels(a, b);
        let mut backward = pixels(b, a);
        forward.sort_unstable();
        backward.sort_unstable();
        assert_eq!(forward, backward);
    }

    #[test]
    fn t_runs_from_zero_to_one_and_depth_follows() {
        let mut ts = Vec::new();
        let a = LineVertex {
            x: 0.5,
            y: 0.5,
            depth: 0.2,
        };
        let b = LineVertex {
            x: 10.5,
            y: 3.5,
            depth: 0.7,
        };
        rasterize_line(a, b, Viewport::new(16, 16).unwrap(), |f| ts.push((f.t, f.depth)));
        assert_eq!(ts.len(), 11);
        assert_eq!(ts[0], (0.0, 0.2));
        assert_eq!(ts[10].0, 1.0);
        approx::assert_relative_eq!(ts[10].1, 0.7);
    }

    /// Nearest, ties to even, also for negative numerators and a denominator of one.
    #[test]
    fn division_rounds_to_nearest_and_ties_to_even() {
        let cases = [
            (5, 2, 2),
            (7, 2, 4),
            (-5, 2, -2),
            (6, 2, 3),
            (8, 3, 3),
            (7, 3, 2),
            (5, 1, 5),
        ];
        for (num, den, want) in cases {
            assert_eq!(div_round_even(num, den), want, "{num}/{den}");
        }
    }

    /// A line leaving the viewport across one side stops at that side's last column or row.
    #[test]
    fn a_line_stops_at_the_viewport_edge_it_crosses() {
        let line = pixels(v(60.5, 5.5), v(70.5, 6.5));
        assert_eq!(line.len(), 4, "{line:?}");
        assert!(line.iter().all(|&(x, y)| x < 64 && y < 64), "{line:?}");
        let down = pixels(v(5.5, 60.5), v(6.5, 70.5));
        assert_eq!(down.len(), 4, "{down:?}");
        let left = pixels(v(-5.5, 5.5), v(3.5, 6.5));
        assert_eq!(left.len(), 4, "{left:?}");
        let up = pixels(v(5.5, -5.5), v(6.5, 3.5));
        assert_eq!(up.len(), 4, "{up:?}");
        // The count returned is the pixels emitted.
        assert_eq!(
            rasterize_line(v(60.5, 5.5), v(70.5, 6.5), Viewport::new(64, 64).unwrap(), |_| {}),
            4
        );
    }

    #[test]
    fn bad_endpoints_draw_nothing() {
        let vp = Viewport::new(8, 8).unwrap();
        assert_eq!(rasterize_line(v(f64::NAN, 1.0), v(2.0, 2.0), vp, |_| {}), 0);
        assert_eq!(rasterize_line(v(1.0, 1.0), v(1e9, 2.0), vp, |_| {}), 0);
        assert!(rasterize_point(v(f64::INFINITY, 0.0), vp).is_none());
        assert!(rasterize_point(v(-0.5, 0.0), vp).is_none());
        assert_eq!(rasterize_point(v(7.9, 0.0), vp).map(|f| (f.x, f.y)), Some((7, 0)));
    }
}
