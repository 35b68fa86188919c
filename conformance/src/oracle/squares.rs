//! Pixel squares against triangles and polygons on the screen, in f64: whether and how far
//! they meet, a triangle grown at its edges, one holding a point. The conservative
//! rasterization rules' oracle; nothing here is shared with the reference, which decides the
//! same questions in subpixel integers.

use super::outline::segment_distance;

/// A triangle on the screen, in pixels.
pub type Screen = [[f64; 2]; 3];

/// Twice the area below which a triangle on the screen has none: snapped forms come back from
/// clip space a few ulps off their grid, where a real area is at least a grid step squared
/// (2^-32 px² on a 16-bit grid).
pub const NO_AREA: f64 = 1e-12;

/// Whether `t` has no area (within [`NO_AREA`]).
pub fn flat(t: &Screen) -> bool {
    area2(t).abs() < NO_AREA
}

/// Whether the input triangle `t`, projected from f32 clip coordinates, is collinear: twice its
/// area within 2^-20 of its longest side squared (f32 rounding of collinear points), where a
/// triangle a sixteenth of an 8-bit grid step off its line has thousands of times more.
pub fn collinear(t: &Screen) -> bool {
    let longest = (0..3)
        .map(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)
        })
        .fold(0.0, f64::max);
    area2(t).abs() <= longest * 0.5f64.powi(20)
}

/// Twice the signed area of `t`.
pub fn area2(t: &Screen) -> f64 {
    (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0])
}

/// The part of convex polygon `poly` inside the closed box `[x0, x1] × [y0, y1]`
/// (Sutherland–Hodgman); empty where they do not meet. A zero-area polygon clips as its hull.
pub fn clip_to_box(poly: &[[f64; 2]], [x0, y0, x1, y1]: [f64; 4]) -> Vec<[f64; 2]> {
    let mut out = poly.to_vec();
    let sides: [(usize, f64, f64); 4] = [(0, x0, 1.0), (0, x1, -1.0), (1, y0, 1.0), (1, y1, -1.0)];
    for (axis, at, sign) in sides {
        let inside = |p: &[f64; 2]| (p[axis] - at) * sign >= 0.0;
        let input = std::mem::take(&mut out);
        for (i, p) in input.iter().enumerate() {
            let q = input[(i + 1) % input.len()];
            if inside(p) {
                out.push(*p);
            }
            if inside(p) != inside(&q) {
                let t = (at - p[axis]) / (q[axis] - p[axis]);
                out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

/// The distance between convex polygon `t` and the box `[x0, x1] × [y0, y1]`; 0 where they
/// meet, infinite for no polygon.
pub fn distance(t: &[[f64; 2]], b: [f64; 4]) -> f64 {
    if !clip_to_box(t, b).is_empty() {
        return 0.0;
    }
    let n = t.len();
    let [x0, y0, x1, y1] = b;
    let to_box = |p: [f64; 2]| {
        let dx = (x0 - p[0]).max(p[0] - x1).max(0.0);
        let dy = (y0 - p[1]).max(p[1] - y1).max(0.0);
        dx.hypot(dy)
    };
    let corners = [[x0, y0], [x1, y0], [x0, y1], [x1, y1]];
    let vertices = t.iter().map(|&p| to_box(p));
    let edges = corners
        .iter()
        .flat_map(|&c| (0..n).map(move |k| segment_distance(t[k], t[(k + 1) % n], c)));
    vertices.chain(edges).fold(f64::INFINITY, f64::min)
}

/// `t` with each edge pushed out by `d·(|nx| + |ny|)` pixels (`d` at an axis-aligned edge, `d√2`
/// at a diagonal: a `2d`-wide square swept along it, the most "in X and Y equally" may mean),
/// its corners mitered; `None` for no area.
pub fn mitered(t: &Screen, d: f64) -> Option<Screen> {
    let turn = area2(t);
    if flat(t) {
        return None;
    }
    // Edge k from vertex k to k + 1, as a line n·p = c with n its outward unit normal.
    let line = |k: usize| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
        let len = ex.hypot(ey);
        let n = if turn > 0.0 {
            [ey / len, -ex / len]
        } else {
            [-ey / len, ex / len]
        };
        (n, n[0] * a[0] + n[1] * a[1] + d * (n[0].abs() + n[1].abs()))
    };
    let lines = [line(0), line(1), line(2)];
    let meet = |(n, c): ([f64; 2], f64), (m, e): ([f64; 2], f64)| {
        let det = n[0] * m[1] - n[1] * m[0];
        [(c * m[1] - n[1] * e) / det, (n[0] * e - c * m[0]) / det]
    };
    Some([
        meet(lines[2], lines[0]),
        meet(lines[0], lines[1]),
        meet(lines[1], lines[2]),
    ])
}

/// Whether `p` lies in `t` with `margin` pixels to spare from every edge (a negative margin
/// lets it lie that far outside).
pub fn holds(t: &Screen, p: [f64; 2], margin: f64) -> bool {
    let turn = area2(t);
    !flat(t)
        && (0..3).all(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            cross * turn.signum() / (b[0] - a[0]).hypot(b[1] - a[1]) >= margin
        })
}

/// How wide convex polygon `p` is across its longest side: twice its area over that side's
/// length (0 for none).
pub fn width(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    let area2: f64 = (0..n)
        .map(|k| p[k][0] * p[(k + 1) % n][1] - p[(k + 1) % n][0] * p[k][1])
        .sum();
    let longest = (0..n)
        .map(|k| (p[(k + 1) % n][0] - p[k][0]).hypot(p[(k + 1) % n][1] - p[k][1]))
        .fold(0.0, f64::max);
    if longest > 0.0 { area2.abs() / longest } else { 0.0 }
}

/// The pixel `(x, y)`'s square grown by `g` pixels on every side (shrunk where negative).
pub fn square(x: u32, y: u32, g: f64) -> [f64; 4] {
    let (x, y) = (f64::from(x), f64::from(y));
    [x - g, y - g, x + 1.0 + g, y + 1.0 + g]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The right triangle (0, 0), (4, 0), (0, 4): it meets pixel (1, 1) and touches pixel
    /// (4, 0) at a corner; pixel (3, 3) is √2 away along the diagonal; grown by 1.1 at each edge
    /// ("in X and Y equally": the hypotenuse moves √2 times as far) it reaches (3, 3), not
    /// (5, 5).
    #[test]
    fn squares_meet_touch_and_grown_triangles_reach() {
        let t: Screen = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        assert_eq!(distance(&t, square(1, 1, 0.0)), 0.0);
        assert_eq!(distance(&t, square(4, 0, 0.0)), 0.0);
        assert!((distance(&t, square(3, 3, 0.0)) - std::f64::consts::SQRT_2).abs() < 1e-12);
        let grown = mitered(&t, 1.1).expect("an area");
        assert!(!clip_to_box(&grown, square(3, 3, 0.0)).is_empty());
        assert!(clip_to_box(&grown, square(5, 5, 0.0)).is_empty());
        assert!(holds(&t, [1.0, 1.0], 0.5) && !holds(&t, [1.0, 1.0], 1.5));
        assert!(flat(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]) && !flat(&t));
        assert!((width(&t) - 2.0 * std::f64::consts::SQRT_2).abs() < 1e-12);
    }
}
