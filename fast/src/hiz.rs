//! Hierarchical depth (Greene, Kass and Miller, *Hierarchical Z-buffer visibility*, 1993): per
//! 8×8 block of a band, a bound of the depths stored in it, so that a block of a triangle that
//! fails the depth test at every sample is skipped before any. Under `Less` and `LessOrEqual`
//! the bound is an upper one; under `Greater` and `GreaterOrEqual` (reversed depth) a lower
//! one, kept as the upper bound of the negated depths so that one comparison serves both.
//!
//! Under those four tests a depth is only ever replaced by one nearer in the test's direction,
//! so a bound once true stays true whatever draws next; it is tightened from the buffer itself
//! after a triangle covers a whole block. Skipping changes no output: the samples skipped are
//! exactly ones whose test would have failed ([`Planes::depth_bounds`] holds their depths).

use refrast::CompareOp;

use crate::back::{BLOCK, Block};
use crate::plane::Planes;
use crate::tiles::BandRows;

/// A bound not yet read off the buffer: NaN, which no bound read off it is (`refresh`).
const UNKNOWN: f32 = f32::NAN;

/// The bounds of one band's blocks, and the test they decide.
pub(crate) struct HiZ {
    /// Per block, row-major, at least every depth stored in it times `−sign` (NaNs, which
    /// fail every test, aside), or [`UNKNOWN`] before it is first read.
    bounds: Vec<f32>,
    /// Blocks per row.
    columns: usize,
    /// The test's direction and strictness; `None` for every test this does not decide.
    test: Option<Toward>,
}

/// Which way a depth test passes.
#[derive(Clone, Copy, Debug)]
struct Toward {
    /// −1 where smaller depths pass (`Less`, `LessOrEqual`), 1 where greater ones do: bounds
    /// and comparisons are on depths times `−sign`, where smaller always passes.
    sign: f32,
    /// Whether a depth equal to the stored one fails (`Less`, `Greater`).
    strict: bool,
}

impl HiZ {
    /// The bounds of a band of `width` pixels and `height` rows, for a draw testing with
    /// `compare`; each is read off the depth buffer when first asked for, so that a draw of
    /// small triangles, which never asks, does not read the buffer twice.
    pub fn new(compare: CompareOp, width: u32, height: u32) -> Self {
        let toward = |sign, strict| Some(Toward { sign, strict });
        let test = match compare {
            CompareOp::Less => toward(-1.0, true),
            CompareOp::LessOrEqual => toward(-1.0, false),
            CompareOp::Greater => toward(1.0, true),
            CompareOp::GreaterOrEqual => toward(1.0, false),
            _ => None,
        };
        let columns = width.div_ceil(BLOCK) as usize;
        let blocks = if test.is_some() {
            columns * height.div_ceil(BLOCK) as usize
        } else {
            0
        };
        Self {
            bounds: vec![UNKNOWN; blocks],
            columns,
            test,
        }
    }

    /// Which bound holds block `rect` (`[x0, x1, y0, y1]`, inside one block of the band
    /// `rows`).
    #[inline(always)]
    fn index(&self, rows: BandRows, rect: [u32; 4]) -> usize {
        ((rect[2] - rows.y0) / BLOCK) as usize * self.columns + (rect[0] / BLOCK) as usize
    }

    /// Whether every sample of `block` of triangle `t` fails the depth test against what the
    /// band stores in `depth`.
    #[inline(always)]
    pub fn occludes(&mut self, rows: BandRows, t: &Planes, block: &Block<'_>, depth: &[f32]) -> bool {
        let Some(test) = self.test else {
            return false;
        };
        let Some([least, most]) = block.corners().and_then(|c| t.depth_bounds(&c)) else {
            return false;
        };
        // The triangle's nearest depth in the test's direction, as a depth where smaller passes.
        let floor = if test.sign < 0.0 { least } else { -most };
        let mut bound = self.bounds[self.index(rows, block.rect)];
        if bound.is_nan() {
            self.refresh(rows, block.rect, depth);
            bound = self.bounds[self.index(rows, block.rect)];
        }
        if test.strict {
            floor >= bound
        } else {
            floor > bound
        }
    }

    /// After `block` is drawn with depth writes `write` on: its bound tightened to the depths
    /// now in it when the triangle covered it whole, so wrote (or tested) every sample.
    #[inline(always)]
    pub fn drawn(&mut self, rows: BandRows, block: &Block<'_>, depth: &[f32], write: bool) {
        if block.full && write {
            self.refresh(rows, block.rect, depth);
        }
    }

    /// Tightens the bound of the block holding `rect` to the farthest depth now in it in the
    /// test's direction (as a depth where smaller passes).
    #[inline(always)]
    fn refresh(&mut self, rows: BandRows, rect: [u32; 4], depth: &[f32]) {
        let Some(test) = self.test else {
            return;
        };
        let sign = -test.sign;
        let index = self.index(rows, rect);
        // Bands start on a block's first row, so blocks lie on multiples of 8 from theirs.
        let (x0, y0) = (rect[0] - rect[0] % BLOCK, rect[2] - rect[2] % BLOCK);
        let width = rows.width as usize;
        let (x0, x1) = (x0 as usize, (x0 + BLOCK).min(rows.width) as usize);
        let first = (y0 - rows.y0) as usize;
        let last = (first + BLOCK as usize).min(depth.len() / width);
        // Never NaN: a NaN depth is passed over (it fails every test).
        let mut bound = f32::NEG_INFINITY;
        for y in first..last {
            let row = &depth[y * width + x0..y * width + x1];
            bound = row
                .iter()
                .fold(bound, |a, &b| if sign * b > a { sign * b } else { a });
        }
        self.bounds[index] = bound;
    }
}
