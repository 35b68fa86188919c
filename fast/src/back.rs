//! The back end's coverage: exact integer edge functions stepped per pixel, 8×8 blocks
//! accepted or rejected whole against the three edges (Abrash, *Rasterization on Larrabee*),
//! partial blocks tested eight samples a row at a time.
//!
//! Every value is the exact `orient2d` of its sample, as the reference's `traverse` computes
//! it, only reached by other sums of the same integers; so are the coverage decisions.

use refrast::stage::TriangleSetup;
use refrast::{FixedPoint, SubpixelBits};

/// The side of a block, in pixels: one row of a block is one vector of eight lanes.
pub(crate) const BLOCK: u32 = 8;

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
}

impl EdgeSteps {
    /// Reads the steps and fill-rule biases off the reference's own setup, by evaluating it.
    ///
    /// Edge functions are linear, so the step is the difference of two exact values; the bias
    /// of edge k is whether `setup.is_inside` keeps a sample lying exactly on k alone.
    pub fn new(setup: &TriangleSetup, bits: SubpixelBits) -> Self {
        let sample = |x, y| FixedPoint::sample(x, y, bits).expect("pixels 0 and 1 have samples");
        let origin = setup.edge_values(sample(0, 0));
        let (right, down) = (setup.edge_values(sample(1, 0)), setup.edge_values(sample(0, 1)));
        let far = 1 << 60;
        Self {
            origin,
            dx: [0, 1, 2].map(|k| right[k] - origin[k]),
            dy: [0, 1, 2].map(|k| down[k] - origin[k]),
            bias: [0, 1, 2].map(|k| {
                let mut on_edge = [far; 3];
                on_edge[k] = 0;
                if setup.is_inside(on_edge) { 0 } else { -1 }
            }),
        }
    }

    /// The exact edge values at the sample of pixel `(x, y)`.
    #[inline]
    pub fn at(&self, x: u32, y: u32) -> [i64; 3] {
        let (x, y) = (i64::from(x), i64::from(y));
        [0, 1, 2].map(|k| self.origin[k] + x * self.dx[k] + y * self.dy[k])
    }

    /// Visits every row of up to eight samples of `rect` (`[x0, x1, y0, y1]`, half-open,
    /// non-empty) that has a covered one: blocks row by row, rows top to bottom within a block.
    pub fn traverse(&self, rect: [u32; 4], mut visit: impl FnMut(&Row)) {
        let [x0, x1, y0, y1] = rect;
        let mut by = y0 - y0 % BLOCK;
        while by < y1 {
            let (cy0, cy1) = (by.max(y0), (by + BLOCK).min(y1));
            let mut bx = x0 - x0 % BLOCK;
            while bx < x1 {
                let (cx0, cx1) = (bx.max(x0), (bx + BLOCK).min(x1));
                self.block([cx0, cx1, cy0, cy1], &mut visit);
                bx += BLOCK;
            }
            by += BLOCK;
        }
    }

    /// One block (at most 8×8): rejected or accepted whole from its corners, else row by row.
    #[inline]
    fn block(&self, rect: [u32; 4], visit: &mut impl FnMut(&Row)) {
        let [x0, x1, y0, y1] = rect;
        let start = self.at(x0, y0);
        let (w, h) = (i64::from(x1 - x0 - 1), i64::from(y1 - y0 - 1));
        let mut accept = true;
        for (k, value) in start.iter().enumerate() {
            // A linear function takes its extremes over a rectangle at its corners.
            let (ex, ey) = (self.dx[k] * w, self.dy[k] * h);
            let lowest = value + ex.min(0) + ey.min(0) + self.bias[k];
            let highest = value + ex.max(0) + ey.max(0) + self.bias[k];
            if highest < 0 {
                return;
            }
            accept &= lowest >= 0;
        }
        let mut values = start;
        for y in y0..y1 {
            let mask = if accept {
                (1u32 << (x1 - x0)) - 1
            } else {
                self.row_mask(values, x1 - x0)
            };
            if mask != 0 {
                visit(&Row {
                    x0,
                    y,
                    mask,
                    values,
                    dx: self.dx,
                });
            }
            for (value, dy) in values.iter_mut().zip(self.dy) {
                *value += dy;
            }
        }
    }

    /// Bit i set when sample i of a row of `n` starting with edge values `row` is inside.
    #[inline]
    fn row_mask(&self, row: [i64; 3], n: u32) -> u32 {
        let biased = [0, 1, 2].map(|k| row[k] + self.bias[k]);
        let mut mask = 0;
        for lane in 0..BLOCK as usize {
            let i = lane as i64;
            let any_negative =
                (biased[0] + i * self.dx[0]) | (biased[1] + i * self.dx[1]) | (biased[2] + i * self.dx[2]);
            mask |= u32::from(any_negative >= 0) << lane;
        }
        mask & ((1u32 << n) - 1)
    }
}

/// Up to eight samples of one pixel row of a block, and which of them a triangle covers.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Row {
    /// The column of lane 0.
    pub x0: u32,
    /// The pixel row.
    pub y: u32,
    /// Bit `i` set when lane `i` (column `x0 + i`) is covered.
    pub mask: u32,
    /// The exact edge values at lane 0.
    pub values: [i64; 3],
    /// Their change per lane.
    pub dx: [i64; 3],
}

impl Row {
    /// The exact edge values at lane `lane`.
    #[inline]
    pub fn values_at(&self, lane: u32) -> [i64; 3] {
        let i = i64::from(lane);
        [0, 1, 2].map(|k| self.values[k] + i * self.dx[k])
    }

    /// Visits the lanes whose bits are set in `mask`, in order.
    #[inline]
    pub fn for_each_lane(mut mask: u32, mut visit: impl FnMut(u32)) {
        while mask != 0 {
            visit(mask.trailing_zeros());
            mask &= mask - 1;
        }
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

    /// Block traversal visits exactly the samples the reference's setup calls inside, with the
    /// same exact edge values, on triangles with edges through samples (ties), slivers and a
    /// counter-clockwise input, over rectangles that start and end off the block grid.
    #[test]
    fn blocks_cover_what_the_setup_calls_inside() {
        let bits = SubpixelBits::DEFAULT;
        let triangles = [
            [(128, 128), (5000, 128), (128, 4000)],
            [(0, 0), (6000, 256 * 3 + 128), (300, 5000)],
            [(7000, 200), (100, 150), (3000, 6000)],
            [(-900, 4000), (9000, 4100), (9100, 4300)],
        ];
        for v in triangles {
            let s = setup(v);
            let steps = EdgeSteps::new(&s, bits);
            for rect in [[0, 30, 0, 30], [3, 21, 5, 19], [7, 9, 15, 16]] {
                let mut got = Vec::new();
                steps.traverse(rect, |row| {
                    Row::for_each_lane(row.mask, |lane| {
                        got.push((row.y, row.x0 + lane, row.values_at(lane)))
                    });
                });
                got.sort_unstable();
                let mut want = Vec::new();
                for y in rect[2]..rect[3] {
                    for x in rect[0]..rect[1] {
                        let p = FixedPoint::sample(i64::from(x), i64::from(y), bits).unwrap();
                        let values = s.edge_values(p);
                        if s.is_inside(values) {
                            want.push((y, x, values));
                        }
                    }
                }
                assert_eq!(got, want, "{v:?} in {rect:?}");
            }
        }
    }
}
