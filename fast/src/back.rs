//! The back end's coverage: exact integer edge functions, 8×8 blocks rejected whole against
//! the three edges (Abrash, *Rasterization on Larrabee*), each row of a block tested eight
//! samples at a time in lanes the compiler vectorises at the dispatched SIMD level.
//!
//! Every value is the exact `orient2d` of its sample, as the reference's `traverse` computes
//! it, reached by other sums of the same integers; so are the coverage decisions. The lanes
//! hold them in the narrowest type that holds them exactly ([`Width`]): `i32` when the
//! triangle's box is small (llvmpipe's 32-bit path), `f64` (integers below 2^53 are exact)
//! otherwise, and `i128` one lane at a time beyond that. What interpolation reads is the same
//! exact values in `f64` lanes, whatever the width.

use refrast::stage::TriangleSetup;
use refrast::{FixedPoint, SubpixelBits};

/// The side of a block, in pixels: one row of a block is one vector of eight lanes.
pub(crate) const BLOCK: u32 = 8;

/// Lanes in a row of a block.
pub(crate) const LANES: usize = BLOCK as usize;

/// Lanes as a float array, lane `i` being `i`.
const IOTA: [f64; LANES] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];

/// The type a triangle's edge values are held in, lane by lane: the narrowest that is exact
/// over every sample its traversal evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Width {
    /// Below 2^30: eight `i32` lanes (a lane's offset from lane 0, up to twice that, fits too).
    Narrow,
    /// Below 2^53: eight `f64` lanes, exact on integers.
    Wide,
    /// Larger (only far outside the guard band): `i128`, lane by lane.
    Exact,
}

impl Width {
    /// The narrowest width holding every value of magnitude up to `max`.
    fn holding(max: i64) -> Self {
        if max < 1 << 30 {
            Self::Narrow
        } else if max < 1 << 53 {
            Self::Wide
        } else {
            Self::Exact
        }
    }
}

// Every edge value `EdgeSteps::new` reckons with, and each term of it, fits `i64` with room to
// spare: coordinates are within `FixedPoint::LIMIT` (2^23 at the finest grid), so an edge's step
// is below 2^24 subpixels, a value below 2^49, and a step times a column or row of the largest
// viewport (plus two blocks) below 2^48.
const _: () = {
    let (limit, one) = (FixedPoint::LIMIT, 1 << SubpixelBits::MAX);
    let step = 2 * limit;
    let value = 2 * step * step;
    let span = (refrast::MAX_VIEWPORT as i64 + 2 * BLOCK as i64) * one * step;
    assert!(value + 4 * span < i64::MAX / 2);
};

/// A triangle's three edge functions as values at pixel (0, 0) and steps per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct EdgeSteps {
    /// The exact edge values at the sample of pixel (0, 0).
    origin: [i64; 3],
    /// The change per pixel to the right.
    dx: [i64; 3],
    /// The change per pixel downwards.
    dy: [i64; 3],
    /// 0 where the edge owns the samples on it, −1 otherwise: inside is `value + bias ≥ 0`.
    bias: [i64; 3],
    /// What its lanes hold values in.
    pub width: Width,
}

impl EdgeSteps {
    /// Reads the steps and fill-rule biases off the reference's own setup, by evaluating it,
    /// for traversals inside `rect` (`[x0, x1, y0, y1]`, half-open).
    ///
    /// Edge functions are linear, so the step is the difference of two exact values; the bias
    /// of edge k is whether `setup.is_inside` keeps a sample lying exactly on k alone.
    pub fn new(setup: &TriangleSetup, bits: SubpixelBits, rect: [u32; 4]) -> Self {
        let sample = |x, y| FixedPoint::sample(x, y, bits).expect("pixels 0 and 1 have samples");
        let origin = setup.edge_values(sample(0, 0));
        let (right, down) = (setup.edge_values(sample(1, 0)), setup.edge_values(sample(0, 1)));
        let far = 1 << 60;
        // Written out, not `[0, 1, 2].map`: this runs once per triangle, and the closures were
        // not inlined (a tenth of a frame of a million small triangles).
        let mut steps = Self {
            origin,
            dx: [right[0] - origin[0], right[1] - origin[1], right[2] - origin[2]],
            dy: [down[0] - origin[0], down[1] - origin[1], down[2] - origin[2]],
            bias: [0; 3],
            width: Width::Exact,
        };
        for k in 0..3 {
            let mut on_edge = [far; 3];
            on_edge[k] = 0;
            steps.bias[k] = if setup.is_inside(on_edge) { 0 } else { -1 };
        }
        steps.width = Width::holding(steps.reach(rect) + 1);
        steps
    }

    /// The largest magnitude of an edge value that traversals inside `rect` evaluate: lanes
    /// reach up to a block's width past its last column.
    ///
    /// A linear function takes its extremes over a rectangle at its corners: the value at the
    /// first plus each step's positive (or negative) part across it. Plain `i64`, which holds
    /// every term (asserted at the top of this file): checked `i64` through `Option`s was 7 %
    /// of the instructions of a frame of a million small triangles.
    fn reach(&self, rect: [u32; 4]) -> i64 {
        let [x0, x1, y0, y1] = rect.map(i64::from);
        let mut max = 0;
        for k in 0..3 {
            let first = self.origin[k] + x0 * self.dx[k] + y0 * self.dy[k];
            let past = x1 + i64::from(BLOCK);
            let (across, down) = ((past - x0) * self.dx[k], (y1 - y0) * self.dy[k]);
            let highest = first + across.max(0) + down.max(0);
            let lowest = first + across.min(0) + down.min(0);
            max = max.max(highest.abs()).max(lowest.abs());
        }
        max
    }

    /// A value read from its start, middle and end, for bringing it into the cache.
    #[inline(always)]
    pub fn warm(&self) -> u32 {
        (self.origin[0] ^ self.dy[0] ^ self.bias[2]) as u32
    }

    /// The exact edge values at the sample of pixel `(x, y)`.
    #[inline]
    pub fn at(&self, x: u32, y: u32) -> [i64; 3] {
        let (x, y) = (i64::from(x), i64::from(y));
        let at = |k: usize| self.origin[k] + x * self.dx[k] + y * self.dy[k];
        [at(0), at(1), at(2)]
    }

    /// The box of the samples of `rect` (`[x0, x1, y0, y1]`, half-open, non-empty) that the
    /// triangle covers, `None` when it covers none; `rect` itself where its values need more
    /// than `i64` ([`Width::Exact`]).
    ///
    /// Sample by sample, so meant for boxes of a few pixels: a triangle smaller than a pixel
    /// often covers no sample of its box, and is then neither set up further nor binned.
    pub fn covered_box(&self, rect: [u32; 4]) -> Option<[u32; 4]> {
        if self.width == Width::Exact {
            return Some(rect);
        }
        let [x0, x1, y0, y1] = rect;
        let mut covered: Option<[u32; 4]> = None;
        for y in y0..y1 {
            for x in x0..x1 {
                if self.is_inside(self.at(x, y)) {
                    let b = covered.get_or_insert([x, x + 1, y, y + 1]);
                    *b = [b[0].min(x), b[1].max(x + 1), b[2], y + 1];
                }
            }
        }
        covered
    }

    /// Whether a sample with exact edge values `values` is covered: `value + bias ≥ 0` for
    /// every edge, the reference's fill rule as [`EdgeSteps::new`] reads it off.
    #[inline(always)]
    fn is_inside(&self, values: [i64; 3]) -> bool {
        (0..3).all(|k| values[k] + self.bias[k] >= 0)
    }

    /// Visits every 8×8 block of `rect` (`[x0, x1, y0, y1]`, half-open, non-empty) that no
    /// edge rejects whole, row of blocks by row of blocks, each cut to `rect`; with `ACCEPT`,
    /// each block says whether it is covered whole ([`Block::full`]), which a small
    /// triangle's traversal does not ask: it seldom covers a block whole.
    #[inline(always)]
    pub fn traverse<const ACCEPT: bool>(&self, rect: [u32; 4], mut visit: impl FnMut(&Block<'_>)) {
        let lanes = LaneSteps::new(self);
        let [x0, x1, y0, y1] = rect;
        let mut by = y0 - y0 % BLOCK;
        while by < y1 {
            let (cy0, cy1) = (by.max(y0), (by + BLOCK).min(y1));
            let mut bx = x0 - x0 % BLOCK;
            while bx < x1 {
                let rect = [bx.max(x0), (bx + BLOCK).min(x1), cy0, cy1];
                if let Some(block) = self.classify::<ACCEPT>(&lanes, rect) {
                    visit(&block);
                }
                bx += BLOCK;
            }
            by += BLOCK;
        }
    }

    /// Visits every row of `rect` (`[x0, x1, y0, y1]`, half-open, non-empty, at most
    /// [`LANES`] wide) with a covered sample, top to bottom, lane 0 on its first column: a
    /// narrow box's traversal, without blocks, which would classify each block and, where the
    /// box straddles a block's edge, visit each of its rows twice.
    #[inline(always)]
    pub fn rows(&self, rect: [u32; 4], mut visit: impl FnMut(&Lanes)) {
        debug_assert!(rect[1] - rect[0] <= BLOCK);
        let lanes = LaneSteps::new(self);
        let [x0, x1, y0, y1] = rect;
        let mut values = self.at(x0, y0);
        for y in y0..y1 {
            lanes.row(values, x0, y, x1 - x0, false, &mut visit);
            for (value, dy) in values.iter_mut().zip(self.dy) {
                *value += dy;
            }
        }
    }

    /// The block `rect`, or `None` when one edge leaves every sample of it outside; with
    /// `ACCEPT`, the block is `full` when no edge leaves any sample outside (Abrash's trivial
    /// accept).
    #[inline(always)]
    fn classify<'a, const ACCEPT: bool>(
        &'a self,
        lanes: &'a LaneSteps<'a>,
        rect: [u32; 4],
    ) -> Option<Block<'a>> {
        let [x0, x1, y0, y1] = rect;
        let start = self.at(x0, y0);
        let (w, h) = (i64::from(x1 - x0 - 1), i64::from(y1 - y0 - 1));
        let mut full = ACCEPT;
        for (k, &value) in start.iter().enumerate() {
            // A linear function takes its extremes over a rectangle at its corners.
            let (ex, ey) = (self.dx[k] * w, self.dy[k] * h);
            if value + ex.max(0) + ey.max(0) + self.bias[k] < 0 {
                return None;
            }
            full = full && value + ex.min(0) + ey.min(0) + self.bias[k] >= 0;
        }
        Some(Block {
            lanes,
            rect,
            start,
            full,
        })
    }
}

/// One 8×8 block of a triangle's traversal, cut to the part of its box being drawn.
pub(crate) struct Block<'a> {
    lanes: &'a LaneSteps<'a>,
    /// Its samples: `[x0, x1, y0, y1]`, half-open.
    pub rect: [u32; 4],
    /// The exact edge values at its first sample.
    start: [i64; 3],
    /// Whether the triangle covers every sample of it.
    pub full: bool,
}

impl Block<'_> {
    /// The exact edge values at its four corner samples as `f64`, or `None` where `f64` does
    /// not hold them exactly ([`Width::Exact`]). Every sample's values lie between them.
    #[inline(always)]
    pub fn corners(&self) -> Option<[[f64; 3]; 4]> {
        let steps = self.lanes.steps;
        if steps.width == Width::Exact {
            return None;
        }
        let [x0, x1, y0, y1] = self.rect;
        let (w, h) = (i64::from(x1 - x0 - 1), i64::from(y1 - y0 - 1));
        let mut corners = [[0.0; 3]; 4];
        for (corner, (i, j)) in corners.iter_mut().zip([(0, 0), (w, 0), (0, h), (w, h)]) {
            for (k, v) in corner.iter_mut().enumerate() {
                *v = (self.start[k] + i * steps.dx[k] + j * steps.dy[k]) as f64;
            }
        }
        Some(corners)
    }

    /// Visits every row of up to eight samples with a covered one, top to bottom.
    #[inline(always)]
    pub fn rows(&self, mut visit: impl FnMut(&Lanes)) {
        let [x0, x1, y0, y1] = self.rect;
        let dy = self.lanes.steps.dy;
        let mut values = self.start;
        for y in y0..y1 {
            self.lanes.row(values, x0, y, x1 - x0, self.full, &mut visit);
            for (value, dy) in values.iter_mut().zip(dy) {
                *value += dy;
            }
        }
    }
}

/// Up to eight samples of one pixel row of a block, which of them a triangle covers, and their
/// exact edge values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lanes {
    /// The column of lane 0.
    pub x0: u32,
    /// The pixel row.
    pub y: u32,
    /// How many lanes lie in the row (the rest are past its end).
    pub n: u32,
    /// Bit `i` set when lane `i` (column `x0 + i`) is covered.
    pub mask: u32,
    /// Each edge's value per lane, exact (integers below 2^53; beyond, rounded once).
    pub e: [[f64; LANES]; 3],
}

impl Lanes {
    /// One covered sample at `(x, y)` with exact edge values `values`, in lane 0.
    #[inline(always)]
    pub fn one(x: u32, y: u32, values: [i64; 3]) -> Self {
        Self {
            x0: x,
            y,
            n: 1,
            mask: 1,
            e: values.map(|v| [v as f64; LANES]),
        }
    }

    /// Lane `lane`'s three edge values.
    #[cfg(test)]
    pub fn values(&self, lane: usize) -> [f64; 3] {
        [self.e[0][lane], self.e[1][lane], self.e[2][lane]]
    }
}

/// Visits the lanes whose bits are set in `mask`, in order.
#[inline(always)]
pub(crate) fn for_each_lane(mut mask: u32, mut visit: impl FnMut(usize)) {
    while mask != 0 {
        visit(mask.trailing_zeros() as usize);
        mask &= mask - 1;
    }
}

/// A triangle's edge steps as the lanes of a row use them: the change per lane and the least
/// value inside (`−bias`), for its [`Width`].
///
/// Plain arrays and loops: inside [`Simd::vectorize`](fearless_simd::Simd::vectorize) the
/// compiler turns each loop over the eight lanes into vector instructions of that level, with
/// the same IEEE results as scalar code (no fast-math, no contraction into fused multiply-adds).
struct LaneSteps<'a> {
    steps: &'a EdgeSteps,
    dx: [f64; 3],
    least: [f64; 3],
    /// For [`Width::Narrow`]: each lane's offset from lane 0 (`i·dx`), per edge, in `i32`.
    offsets: [[i32; LANES]; 3],
}

impl<'a> LaneSteps<'a> {
    #[inline(always)]
    fn new(steps: &'a EdgeSteps) -> Self {
        let mut offsets = [[0; LANES]; 3];
        if steps.width == Width::Narrow {
            for (offsets, &dx) in offsets.iter_mut().zip(&steps.dx) {
                for (i, offset) in offsets.iter_mut().enumerate() {
                    *offset = i as i32 * dx as i32;
                }
            }
        }
        Self {
            steps,
            dx: [steps.dx[0] as f64, steps.dx[1] as f64, steps.dx[2] as f64],
            least: [
                -steps.bias[0] as f64,
                -steps.bias[1] as f64,
                -steps.bias[2] as f64,
            ],
            offsets,
        }
    }

    /// Visits the `n` samples of row `y` from column `x0`, whose lane 0 has edge values
    /// `values`, unless none is covered; with `full`, all `n` are, untested.
    ///
    /// Visited in place: returned, the ~200-byte row was copied by `memcpy` (a fifth of a
    /// frame of small triangles).
    #[inline(always)]
    fn row(&self, values: [i64; 3], x0: u32, y: u32, n: u32, full: bool, visit: &mut impl FnMut(&Lanes)) {
        let valid = (1u32 << n) - 1;
        let mut inside = [true; LANES];
        let width = if full { None } else { Some(self.steps.width) };
        match width {
            None => {}
            Some(Width::Narrow) => {
                // `value + bias` per edge and lane; all three are ≥ 0 exactly when their OR
                // is (no sign bit): one vector OR and compare, where a comparison per edge
                // combined lane by lane was not vectorised whole.
                let mut biased = [[0i32; LANES]; 3];
                for (k, biased) in biased.iter_mut().enumerate() {
                    let start = values[k] as i32 + self.steps.bias[k] as i32;
                    for (i, biased) in biased.iter_mut().enumerate() {
                        *biased = start + self.offsets[k][i];
                    }
                }
                for (i, inside) in inside.iter_mut().enumerate() {
                    *inside = biased[0][i] | biased[1][i] | biased[2][i] >= 0;
                }
            }
            Some(Width::Wide) => {
                // The three edges' lanes first, then one combination per lane (as above).
                let mut lanes = [[0.0; LANES]; 3];
                for (k, lanes) in lanes.iter_mut().enumerate() {
                    let start = values[k] as f64;
                    for (i, lane) in lanes.iter_mut().enumerate() {
                        *lane = start + IOTA[i] * self.dx[k];
                    }
                }
                let least = self.least;
                for (i, inside) in inside.iter_mut().enumerate() {
                    *inside =
                        (lanes[0][i] >= least[0]) & (lanes[1][i] >= least[1]) & (lanes[2][i] >= least[2]);
                }
            }
            Some(Width::Exact) => {
                let dx = self.steps.dx;
                for k in 0..3 {
                    let bias = i128::from(self.steps.bias[k]);
                    for (i, inside) in inside.iter_mut().enumerate() {
                        *inside &= i128::from(values[k]) + i as i128 * i128::from(dx[k]) + bias >= 0;
                    }
                }
            }
        }
        let mut mask = 0;
        for (i, &inside) in inside.iter().enumerate() {
            mask |= u32::from(inside) << i;
        }
        let mask = mask & valid;
        if mask == 0 {
            return;
        }
        let e = self.lane_values(values);
        visit(&Lanes { x0, y, n, mask, e });
    }

    /// The exact edge values of the eight lanes whose lane 0 has `values`, as `f64` (rounded
    /// once beyond 2^53, at [`Width::Exact`]).
    #[inline(always)]
    fn lane_values(&self, values: [i64; 3]) -> [[f64; LANES]; 3] {
        let mut e = [[0.0; LANES]; 3];
        for k in 0..3 {
            if self.steps.width == Width::Exact {
                let lane = |i: usize| i128::from(values[k]) + i as i128 * i128::from(self.steps.dx[k]);
                e[k] = std::array::from_fn(|i| lane(i) as f64);
            } else {
                let start = values[k] as f64;
                for i in 0..LANES {
                    e[k][i] = start + IOTA[i] * self.dx[k];
                }
            }
        }
        e
    }
}

#[cfg(test)]
mod tests {
    use refrast::FillConvention;

    use super::*;

    fn setup(v: [(i64, i64); 3]) -> TriangleSetup {
        let points = v.map(|(x, y)| FixedPoint::new(x, y).expect("in range"));
        TriangleSetup::new(points, FillConvention::TopLeft).expect("nonzero area")
    }

    /// Block traversal, accepting whole blocks or not, visits exactly the samples the
    /// reference's setup calls inside, with their exact edge values, on triangles with edges
    /// through samples (ties), slivers, a counter-clockwise input and one that misses a block's
    /// last sample by a subpixel, one between samples that covers none and large ones with edges
    /// through samples, over rectangles that start and end off the block grid, at every width;
    /// so does the traversal row by row of a narrow rectangle ([`EdgeSteps::rows`]); and the
    /// box of those samples is [`EdgeSteps::covered_box`]'s.
    #[test]
    fn blocks_cover_what_the_setup_calls_inside() {
        let bits = SubpixelBits::DEFAULT;
        let triangles = [
            [(128, 128), (5000, 128), (128, 4000)],
            // Right and bottom edges through samples, which the fill rule leaves out.
            [(5248, 3968), (5248, 128), (128, 3968)],
            [(0, 0), (6000, 256 * 3 + 128), (300, 5000)],
            [(7000, 200), (100, 150), (3000, 6000)],
            [(-900, 4000), (9000, 4100), (9100, 4300)],
            // Covering the first block but for its last sample, (7.5, 7.5) px, just outside.
            [(0, 0), (0, 3839), (3839, 0)],
            // Large enough for `f64` lanes.
            [(0, 0), (900_000, 1000), (2000, 800_000)],
            // Smaller than a pixel, between samples: covers none.
            [(140, 140), (200, 150), (150, 210)],
            // Large enough for `f64` lanes, with edges through samples, both ways round.
            [(128, 128), (800_128, 128), (128, 800_128)],
            [(128, 128), (128, 800_128), (800_128, 128)],
            [(800_128, 800_128), (128, 800_128), (800_128, 128)],
            [(800_128, 800_128), (800_128, 128), (128, 800_128)],
        ];
        let mut widths = Vec::new();
        for v in triangles {
            let s = setup(v);
            for rect in [
                [0, 30, 0, 30],
                [3, 21, 5, 19],
                [7, 9, 15, 16],
                [1550, 1580, 1550, 1580],
                // Narrow: drawn row by row without blocks, one across a block's edge.
                [5, 13, 2, 11],
            ] {
                let mut steps = EdgeSteps::new(&s, bits, rect);
                widths.push(steps.width);
                // The reach from the corners is the largest value the lanes reach.
                let [x0, x1, y0, y1] = rect.map(i64::from);
                let reached = (y0..=y1).flat_map(|y| (x0..=x1 + 8).map(move |x| (x, y)));
                let max = reached
                    .flat_map(|(x, y)| (0..3).map(move |k| (k, x, y)))
                    .map(|(k, x, y)| (steps.origin[k] + x * steps.dx[k] + y * steps.dy[k]).abs())
                    .max();
                assert_eq!(steps.reach(rect), max.unwrap_or(0), "{v:?} in {rect:?}");
                for width in [steps.width, Width::Exact] {
                    steps.width = width;
                    let got = covered::<false>(&steps, rect);
                    assert_eq!(got, covered::<true>(&steps, rect), "{v:?} accepting blocks");
                    if rect[1] - rect[0] <= BLOCK {
                        assert_eq!(got, covered_rows(&steps, rect), "{v:?} row by row");
                    }
                    let mut want = Vec::new();
                    for y in rect[2]..rect[3] {
                        for x in rect[0]..rect[1] {
                            let p = FixedPoint::sample(i64::from(x), i64::from(y), bits).unwrap();
                            let values = s.edge_values(p);
                            if s.is_inside(values) {
                                want.push((y, x, values.map(|v| (v as f64).to_bits())));
                            }
                        }
                    }
                    assert_eq!(got, want, "{v:?} in {rect:?} at {width:?}");
                    // The box of the same samples, or none; the whole rect beyond `i64`.
                    let bounds = want.iter().fold(None, |b: Option<[u32; 4]>, &(y, x, _)| {
                        let [x0, x1, y0, y1] = b.unwrap_or([x, x + 1, y, y + 1]);
                        Some([x0.min(x), x1.max(x + 1), y0.min(y), y1.max(y + 1)])
                    });
                    let expected = if width == Width::Exact { Some(rect) } else { bounds };
                    assert_eq!(steps.covered_box(rect), expected, "{v:?} in {rect:?}");
                }
            }
        }
        assert!(widths.contains(&Width::Narrow) && widths.contains(&Width::Wide));
    }

    /// The covered samples of `rect` visited row by row ([`EdgeSteps::rows`]), sorted, with
    /// the bits of their edge values.
    fn covered_rows(steps: &EdgeSteps, rect: [u32; 4]) -> Vec<(u32, u32, [u64; 3])> {
        let mut got = Vec::new();
        steps.rows(rect, |row| {
            for_each_lane(row.mask, |lane| {
                got.push((row.y, row.x0 + lane as u32, row.values(lane).map(f64::to_bits)))
            });
        });
        got.sort_unstable();
        got
    }

    /// The covered samples of `rect`, sorted, with the bits of their edge values.
    fn covered<const ACCEPT: bool>(steps: &EdgeSteps, rect: [u32; 4]) -> Vec<(u32, u32, [u64; 3])> {
        let mut got = Vec::new();
        steps.traverse::<ACCEPT>(rect, |block| {
            block.rows(|row| {
                for_each_lane(row.mask, |lane| {
                    got.push((row.y, row.x0 + lane as u32, row.values(lane).map(f64::to_bits)))
                });
            })
        });
        got.sort_unstable();
        got
    }
}
