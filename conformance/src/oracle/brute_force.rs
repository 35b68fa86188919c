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
///
/// Only the samples within the triangle's bounding box are tested: one outside it lies outside
/// the triangle and off its edges, so [`covers`] could only say no.
#[must_use]
pub fn coverage(t: [Point; 3], width: u32, height: u32, bits: u8, fill: FillConvention) -> Vec<(u32, u32)> {
    let one = 1i128 << bits;
    // Pixel `i`'s sample lies at `i·one + one/2`: the pixels whose samples lie in [lo, hi].
    let pixels = |lo: i128, hi: i128, side: u32| {
        let first = (lo - one / 2 + one - 1).div_euclid(one).max(0);
        let last = (hi - one / 2).div_euclid(one).min(i128::from(side) - 1);
        // Both are within [0, side) or the range is empty; `side` fits u32.
        (first as u32)..(last + 1).max(first) as u32
    };
    let (xs, ys) = (t.map(|p| p.0), t.map(|p| p.1));
    let min = |v: [i128; 3]| v[0].min(v[1]).min(v[2]);
    let max = |v: [i128; 3]| v[0].max(v[1]).max(v[2]);
    let mut out = Vec::new();
    for y in pixels(min(ys), max(ys), height) {
        for x in pixels(min(xs), max(xs), width) {
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

    /// Testing only the bounding box finds what testing every sample of the viewport finds,
    /// for triangles inside, across and outside the viewport, on and off the sample grid.
    #[test]
    fn the_box_finds_what_the_whole_viewport_finds() {
        let (w, h, bits) = (9u32, 7u32, 4u8);
        let one = 1i128 << bits;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |range: i128| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % (2 * range as u64 + 1)) as i128 - range
        };
        for _ in 0..2000 {
            // Half the triangles with corners on half pixels, so that corners and edges often
            // pass through samples, where the box's bounds matter.
            let step = if next(1) == 0 { one / 2 } else { 1 };
            let t = [0; 3].map(|_| {
                (
                    next(24 * one / (2 * step)) * step + 4 * one,
                    next(20 * one / (2 * step)) * step + 3 * one,
                )
            });
            for fill in FillConvention::ALL {
                let mut all = Vec::new();
                for y in 0..h {
                    for x in 0..w {
                        let s = (i128::from(x) * one + one / 2, i128::from(y) * one + one / 2);
                        if covers(t, s, fill) {
                            all.push((x, y));
                        }
                    }
                }
                assert_eq!(coverage(t, w, h, bits, fill), all, "{t:?} {fill:?}");
            }
        }
    }

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
