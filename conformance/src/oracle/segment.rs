//! The line, point and per-sample oracles: every pixel and sample of the viewport, exact in
//! i128, written apart from the reference's `segment.rs`.
//!
//! - **Diamond exit** by the separating-axis test: the segment, its ends nudged by `−(ε, ε²)`,
//!   misses the open diamond exactly when its projection and the diamond's are disjoint on one
//!   of the diamond's two edge normals or on the segment's own normal.
//! - **Parallelograms and point squares** have their corners on the grid, so each is two
//!   triangles covered by [`brute_force::covers`] under the fill convention.
//! - **Rectangles** have irrational corners: a sample, nudged as the fill convention says,
//!   is inside when `4·cross² < width²·length²` and `0 < dot < length²`.
//! - **Samples** lie at the declared positions, in sixteenths of a pixel: every coordinate is
//!   scaled by 16 so that they are grid points.
//!
//! Every nudged quantity is a polynomial in ε (`Poly`) compared by its first non-zero term.

use refrast::{FillConvention, LineRule};

use super::brute_force;
use super::raster::Point;

/// `p[0] + p[1]·ε + … + p[4]·ε⁴` for an infinitesimal `ε > 0`.
type Poly = [i128; 5];

fn poly(c: i128) -> Poly {
    [c, 0, 0, 0, 0]
}

fn minus(a: Poly, b: Poly) -> Poly {
    std::array::from_fn(|k| a[k] - b[k])
}

fn times(a: Poly, b: Poly) -> Poly {
    std::array::from_fn(|k| (0..=k).map(|i| a[i] * b[k - i]).sum())
}

fn scaled(a: Poly, c: i128) -> Poly {
    a.map(|v| v * c)
}

/// Whether `a < b` for every small enough ε.
fn lt(a: Poly, b: Poly) -> bool {
    minus(a, b).into_iter().find(|&c| c != 0).is_some_and(|c| c < 0)
}

/// A point's coordinates as polynomials, moved by `(mx·ε, my·ε²)`.
fn moved(p: Point, mx: i128, my: i128) -> (Poly, Poly) {
    ([p.0, mx, 0, 0, 0], [p.1, 0, my, 0, 0])
}

/// How a fill convention nudges a sample, `(±ε, ±ε²)`, as D3D11 words it: top-left owns top
/// edges (a sample on one moves down, into the shape) and left edges (it moves right).
fn sample_nudge(fill: FillConvention) -> (i128, i128) {
    match fill {
        FillConvention::TopLeft => (1, 1),
        FillConvention::TopRight => (-1, 1),
        FillConvention::BottomLeft => (1, -1),
        FillConvention::BottomRight => (-1, -1),
    }
}

/// Whether the diamond-exit rule draws the pixel whose centre is `c` (diamond radius `h`).
#[must_use]
pub fn diamond_exit(a: Point, b: Point, c: Point, h: i128) -> bool {
    let (ax, ay) = moved(a, -1, -1);
    let (bx, by) = moved(b, -1, -1);
    let (cx, cy) = (poly(c.0), poly(c.1));
    // The end b' in the open diamond: all four |±x ± y| half-planes strictly.
    let inside = |x: Poly, y: Poly| {
        [(1, 1), (1, -1), (-1, 1), (-1, -1)].into_iter().all(|(nx, ny)| {
            lt(
                minus(scaled(x, nx), scaled(cx, nx)),
                minus(poly(h), scaled(minus(y, cy), ny)),
            )
        })
    };
    if inside(bx, by) {
        return false;
    }
    // Separating axes: the diamond's edge normals (its projection is n·c ± h) ...
    for (nx, ny) in [(1, 1), (1, -1)] {
        let pa = times(ax, poly(nx));
        let pa = [0, 1, 2, 3, 4].map(|k| pa[k] + ny * ay[k]);
        let pb = times(bx, poly(nx));
        let pb = [0, 1, 2, 3, 4].map(|k| pb[k] + ny * by[k]);
        let centre = nx * c.0 + ny * c.1;
        let (lo, hi) = if lt(pa, pb) { (pa, pb) } else { (pb, pa) };
        if !lt(poly(centre - h), hi) || !lt(lo, poly(centre + h)) {
            return false;
        }
    }
    // ... and the segment's normal m = (−dy, dx), where the segment is one value and the
    // diamond spans m·c ± h·max(|mx|, |my|).
    let (mx, my) = (-(b.1 - a.1), b.0 - a.0);
    if mx != 0 || my != 0 {
        let along = minus(
            [0, 1, 2, 3, 4].map(|k| mx * ax[k] + my * ay[k]),
            poly(mx * c.0 + my * c.1),
        );
        let reach = poly(h * mx.abs().max(my.abs()));
        if !(lt(along, reach) && lt(scaled(reach, -1), along)) {
            return false;
        }
    }
    true
}

/// Whether sample `s`, nudged as `fill` says, is inside the rectangle of half-width `h` along `a → b`.
#[must_use]
pub fn in_rectangle(a: Point, b: Point, s: Point, h: i128, fill: FillConvention) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let length2 = dx * dx + dy * dy;
    if length2 == 0 {
        return false;
    }
    let (nx, ny) = sample_nudge(fill);
    let (sx, sy) = moved(s, nx, ny);
    let (rx, ry) = (minus(sx, poly(a.0)), minus(sy, poly(a.1)));
    let cross = minus(scaled(ry, dx), scaled(rx, dy));
    let dot = [0, 1, 2, 3, 4].map(|k| rx[k] * dx + ry[k] * dy);
    lt(times(cross, cross), poly(h * h * length2)) && lt(poly(0), dot) && lt(dot, poly(length2))
}

/// Whether sample `s` is covered by the polygon `corners` (convex, four corners on the grid),
/// split into two triangles, under `fill`.
fn in_quad(corners: [Point; 4], s: Point, fill: FillConvention) -> bool {
    let [p, q, r, t] = corners;
    brute_force::covers([p, q, r], s, fill) || brute_force::covers([p, r, t], s, fill)
}

/// Whether `rule` covers sample `s` of segment `a → b` (for the diamond-exit rule, `s` is the
/// pixel's centre: it is decided per pixel). `h` is half a pixel.
#[must_use]
pub fn line_covers(rule: LineRule, a: Point, b: Point, s: Point, h: i128, fill: FillConvention) -> bool {
    match rule {
        LineRule::DiamondExit => diamond_exit(a, b, s, h),
        LineRule::Rectangle => in_rectangle(a, b, s, h, fill),
        LineRule::Parallelogram => {
            if a == b {
                return false;
            }
            // The short sides along the minor axis: x is the major axis on a tie.
            let (ox, oy) = if (b.0 - a.0).abs() >= (b.1 - a.1).abs() {
                (0, h)
            } else {
                (h, 0)
            };
            let side = |p: Point, k: i128| (p.0 + k * ox, p.1 + k * oy);
            in_quad([side(a, -1), side(b, -1), side(b, 1), side(a, 1)], s, fill)
        }
    }
}

/// Whether the point square of half-side `h` at `p` covers sample `s` under `fill`.
#[must_use]
pub fn point_covers(p: Point, s: Point, h: i128, fill: FillConvention) -> bool {
    in_quad(
        [
            (p.0 - h, p.1 - h),
            (p.0 + h, p.1 - h),
            (p.0 + h, p.1 + h),
            (p.0 - h, p.1 + h),
        ],
        s,
        fill,
    )
}

/// A viewport's samples in sixteenth-scaled units: `bits` grid bits, sample positions in 1/16 px.
#[derive(Clone, Copy, Debug)]
pub struct SampleGrid<'a> {
    /// Viewport width in pixels.
    pub width: u32,
    /// Viewport height in pixels.
    pub height: u32,
    /// Grid bits of the snapped points given.
    pub bits: u8,
    /// Sample positions in sixteenths of a pixel.
    pub positions: &'a [[u8; 2]],
}

impl SampleGrid<'_> {
    /// A grid point (units of `2^-bits` px) in the scaled units.
    #[must_use]
    pub fn scale(&self, p: Point) -> Point {
        (p.0 * 16, p.1 * 16)
    }

    /// Half a pixel in the scaled units.
    #[must_use]
    pub fn half(&self) -> i128 {
        8 << self.bits
    }

    /// Sample `k` of pixel `(x, y)` in the scaled units.
    #[must_use]
    pub fn sample(&self, x: u32, y: u32, k: usize) -> Point {
        let [u, v] = self.positions[k].map(i128::from);
        (
            (16 * i128::from(x) + u) << self.bits,
            (16 * i128::from(y) + v) << self.bits,
        )
    }

    /// The centre of pixel `(x, y)` in the scaled units.
    #[must_use]
    pub fn centre(&self, x: u32, y: u32) -> Point {
        (
            (16 * i128::from(x) + 8) << self.bits,
            (16 * i128::from(y) + 8) << self.bits,
        )
    }

    /// The pixels of the viewport within one pixel of the box `lo..=hi` (scaled units): no
    /// sample farther out can lie inside a shape within the box.
    #[must_use]
    pub fn pixels_near(&self, lo: Point, hi: Point) -> (std::ops::Range<u32>, std::ops::Range<u32>) {
        let pixel = 16i128 << self.bits;
        let span = |lo: i128, hi: i128, side: u32| {
            let first = (lo.div_euclid(pixel) - 1).clamp(0, i128::from(side));
            let last = (hi.div_euclid(pixel) + 2).clamp(0, i128::from(side));
            first as u32..last as u32
        };
        (span(lo.0, hi.0, self.width), span(lo.1, hi.1, self.height))
    }

    /// Every `(x, y, sample)` within one pixel of the box `lo..=hi` for which `covered` holds,
    /// row by row.
    pub fn collect(
        &self,
        lo: Point,
        hi: Point,
        mut covered: impl FnMut(u32, u32, usize) -> bool,
    ) -> Vec<(u32, u32, u8)> {
        let (xs, ys) = self.pixels_near(lo, hi);
        let mut out = Vec::new();
        for y in ys {
            for x in xs.clone() {
                for k in 0..self.positions.len() {
                    if covered(x, y, k) {
                        out.push((x, y, k as u8));
                    }
                }
            }
        }
        out
    }

    /// The samples segment `a → b` (snapped, `2^-bits` units) covers under `rule`; under the
    /// diamond-exit rule, every sample of each drawn pixel.
    #[must_use]
    pub fn line(&self, rule: LineRule, a: Point, b: Point, fill: FillConvention) -> Vec<(u32, u32, u8)> {
        let (a, b, h) = (self.scale(a), self.scale(b), self.half());
        let (lo, hi) = ((a.0.min(b.0), a.1.min(b.1)), (a.0.max(b.0), a.1.max(b.1)));
        self.collect(lo, hi, |x, y, k| match rule {
            LineRule::DiamondExit => diamond_exit(a, b, self.centre(x, y), h),
            _ => line_covers(rule, a, b, self.sample(x, y, k), h, fill),
        })
    }

    /// The samples the point square at `p` covers.
    #[must_use]
    pub fn point(&self, p: Point, fill: FillConvention) -> Vec<(u32, u32, u8)> {
        let (p, h) = (self.scale(p), self.half());
        self.collect(p, p, |x, y, k| point_covers(p, self.sample(x, y, k), h, fill))
    }

    /// The samples triangle `t` covers.
    #[must_use]
    pub fn triangle(&self, t: [Point; 3], fill: FillConvention) -> Vec<(u32, u32, u8)> {
        let t = t.map(|p| self.scale(p));
        let lo = (t[0].0.min(t[1].0).min(t[2].0), t[0].1.min(t[1].1).min(t[2].1));
        let hi = (t[0].0.max(t[1].0).max(t[2].0), t[0].1.max(t[1].1).max(t[2].1));
        self.collect(lo, hi, |x, y, k| {
            brute_force::covers(t, self.sample(x, y, k), fill)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CENTRE: [[u8; 2]; 1] = [[8, 8]];

    fn grid(width: u32, height: u32) -> SampleGrid<'static> {
        SampleGrid {
            width,
            height,
            bits: 4,
            positions: &CENTRE,
        }
    }

    /// From centre to centre horizontally: the first pixel drawn, the last not; reversed, the
    /// other way round.
    #[test]
    fn the_diamond_rule_leaves_out_the_last_pixel() {
        let g = grid(8, 2);
        let px = |x: i128, y: i128| (16 * x + 8, 16 * y + 8);
        let drawn = |a, b| {
            g.line(LineRule::DiamondExit, a, b, FillConvention::TopLeft)
                .into_iter()
                .map(|(x, y, _)| (x, y))
                .collect::<Vec<_>>()
        };
        assert_eq!(drawn(px(1, 0), px(4, 0)), [(1, 0), (2, 0), (3, 0)]);
        assert_eq!(drawn(px(4, 0), px(1, 0)), [(2, 0), (3, 0), (4, 0)]);
        assert!(drawn(px(2, 1), px(2, 1)).is_empty());
    }

    /// A point on a pixel corner covers the pixel below and to the right of it under top-left.
    #[test]
    fn a_point_on_a_corner_takes_the_pixel_its_square_owns() {
        let g = grid(4, 4);
        let covered = g.point((32, 32), FillConvention::TopLeft);
        assert_eq!(covered, [(1, 1, 0)]);
        let covered = g.point((32, 32), FillConvention::BottomRight);
        assert_eq!(covered, [(2, 2, 0)]);
    }

    /// The four standard samples of a pixel each land on the triangle that holds them.
    #[test]
    fn samples_lie_where_the_pattern_puts_them() {
        let four = [[6, 2], [14, 6], [2, 10], [10, 14]];
        let g = SampleGrid {
            width: 1,
            height: 1,
            bits: 4,
            positions: &four,
        };
        // The upper-left half of the pixel (below the anti-diagonal x + y = 1): samples 0 and 2.
        let upper_left = g.triangle([(0, 0), (16, 0), (0, 16)], FillConvention::TopLeft);
        assert_eq!(upper_left, [(0, 0, 0), (0, 0, 2)]);
    }
}
