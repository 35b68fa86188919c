//! Hierarchical depth (Greene, Kass and Miller, *Hierarchical Z-buffer visibility*, 1993): per
//! 8×8 block of a band, an upper bound of the depths stored in it, so that a block of a
//! triangle that fails a `Less` or `LessOrEqual` test at every sample is skipped before any.
//!
//! Under those two tests a depth is only ever replaced by a smaller or equal one, so a bound
//! once true stays true whatever draws next; it is tightened from the buffer itself after a
//! triangle covers a whole block. Skipping changes no output: the samples skipped are exactly
//! ones whose test would have failed ([`Planes::depth_floor`] bounds them below).

use refrast::CompareOp;

use crate::back::{BLOCK, Block};
use crate::plane::Planes;
use crate::tiles::BandRows;

/// A bound not yet read off the buffer: NaN, which no bound read off it is (see
/// [`HiZ::refresh`]).
const UNKNOWN: f32 = f32::NAN;

/// The bounds of one band's blocks, and the test they decide.
pub(crate) struct HiZ {
    /// Per block, row-major, at least every depth stored in it (NaNs, which fail every
    /// test, aside), or [`UNKNOWN`] before it is first read.
    bounds: Vec<f32>,
    /// Blocks per row.
    columns: usize,
    /// Whether a depth equal to the bound fails (`Less`) or passes (`LessOrEqual`); `None`
    /// for every other test, which this does not decide.
    strict: Option<bool>,
}

impl HiZ {
    /// The bounds of a band of `width` pixels and `height` rows, for a draw testing with
    /// `compare`; each is read off the depth buffer when first asked for, so that a draw of
    /// small triangles, which never asks, does not read the buffer twice.
    pub fn new(compare: CompareOp, width: u32, height: u32) -> Self {
        let strict = match compare {
            CompareOp::Less => Some(true),
            CompareOp::LessOrEqual => Some(false),
            _ => None,
        };
        let columns = width.div_ceil(BLOCK) as usize;
        let blocks = if strict.is_some() {
            columns * height.div_ceil(BLOCK) as usize
        } else {
            0
        };
        Self {
            bounds: vec![UNKNOWN; blocks],
            columns,
            strict,
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
        let Some(strict) = self.strict else {
            return false;
        };
        let Some(corners) = block.corners() else {
            return false;
        };
        let floor = t.depth_floor(&corners);
        let mut bound = self.bounds[self.index(rows, block.rect)];
        if bound.is_nan() {
            self.refresh(rows, block.rect, depth);
            bound = self.bounds[self.index(rows, block.rect)];
        }
        if strict { floor >= bound } else { floor > bound }
    }

    /// After `block` is drawn with depth writes `write` on: its bound tightened to the largest
    /// depth now in it when the triangle covered it whole, so wrote (or tested) every sample.
    #[inline(always)]
    pub fn drawn(&mut self, rows: BandRows, block: &Block<'_>, depth: &[f32], write: bool) {
        if block.full && write {
            self.refresh(rows, block.rect, depth);
        }
    }

    /// Tightens the bound of the block holding `rect` to the largest depth now in it.
    #[inline(always)]
    fn refresh(&mut self, rows: BandRows, rect: [u32; 4], depth: &[f32]) {
        if self.strict.is_none() {
            return;
        }
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
            bound = row.iter().fold(bound, |a, &b| if b > a { b } else { a });
        }
        self.bounds[index] = bound;
    }
}
