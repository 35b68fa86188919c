//! The brute-force oracle: every pixel of the viewport, `orient2d` in i128, explicit fill-rule bias.
//!
//! It shares no code with the reference: edges are classified by their geometry as D3D11 words
//! it (a top edge is horizontal with the third vertex below it; a left edge has the third vertex
//! to its right), nothing is reordered, nothing is stepped.

use refrast::FillConvention;

use super::raster::Point;

/// Twice the signed area of `a, b, c`.
#[must_use]
pub fn orient2d(a: Point, b: Point, c: Point) -> i128 {
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
}

/// Whether edge `p q` of a triangle whose third vertex is `r` owns the samples on it.
///
/// Top-left: a horizontal edge owns them when the triangle lies below it, any other edge when
/// the triangle lies to its right. The other conventions flip "below" and "right".
#[must_use]
pub fn owns(p: Point, q: Point, r: Point, fill: FillConvention) -> bool {
    let (right, below) = match fill {
        FillConvention::TopLeft => (true, true),
        FillConvention::TopRight => (false, true),
        FillConvention::BottomLeft => (true, false),
        FillConvention::BottomRight => (false, false),
    };
    if p.1 == q.1 {
        (r.1 > p.1) == below
    } else {
        // r right of the line at r's height: r.x > p.x + (r.y − p.y)(q.x − p.x)/(q.y − p.y).
        let dy = q.1 - p.1;
        let side = ((r.0 - p.0) * dy - (r.1 - p.1) * (q.0 - p.0)) * dy.signum();
        (side > 0) == right
    }
}

/// Whether sample `s` is covered by triangle `t` under `fill`.
#[must_use]
pub fn covers(t: [Point; 3], s: Point, fill: FillConvention) -> bool {
    if orient2d(t[0], t[1], t[2]) == 0 {
        return false;
    }
    (0..3).all(|i| {
        let (p, q, r) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
        let e = orient2d(p, q, s) * orient2d(p, q, r).signum();
        e > 0 || (e == 0 && owns(p, q, r, fill))
    })
}

/// Every covered pixel of a `width × height` viewport, row by row.
#[must_use]
pub fn coverage(t: [Point; 3], width: u32, height: u32, bits: u8, fill: FillConvention) -> Vec<(u32, u32)> {
    let one = 1i128 << bits;
    let mut out = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let s = (i128::from(x) * one + one / 2, i128::from(y) * one + one / 2);
            if covers(t, s, fill) {
                out.push((x, y));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_split_square_covers_each_sample_once_under_every_convention() {
        let s = 256;
        let (a, b, c, d) = ((0, 0), (2 * s, 0), (2 * s, 2 * s), (0, 2 * s));
        for fill in FillConvention::ALL {
            let first = coverage([a, b, c], 2, 2, 8, fill);
            let second = coverage([a, c, d], 2, 2, 8, fill);
            assert_eq!(first.len() + second.len(), 4, "{fill:?}");
            assert!(first.iter().all(|p| !second.contains(p)));
        }
    }
}
