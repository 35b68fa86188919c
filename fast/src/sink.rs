//! Covered lanes and what a band does with them: keep fragments, resolve, or shade.
//!
//! Depth comes from [`Planes::depth`] for all eight lanes at once, so a fragment, a resolved
//! buffer and a shaded picture see the same bits; barycentrics only for what is kept or shaded.

use refrast::{CompareOp, DepthState, Fragment};

use crate::back::{Block, LANES, Lanes, for_each_lane};
use crate::hiz::HiZ;
use crate::plane::Planes;
use crate::tiles::BandRows;

/// What one band does with its covered samples, which come in primitive order per pixel.
pub(crate) trait Sink: Send {
    /// Takes the covered lanes of `row`, a row of triangle `t`.
    fn take(&mut self, t: &Planes, row: &Lanes);

    /// Reads in the band's buffers under `rect` (a tile) before its triangles are drawn there.
    #[inline(always)]
    fn warm(&mut self, _rect: [u32; 4]) {}

    /// The band's depth buffer and its block bounds, where it tests depth.
    #[inline(always)]
    fn depth_bounds(&mut self) -> Option<Bounded<'_>> {
        None
    }

    /// Takes the covered rows of `block`, a block of triangle `t`: where the band has
    /// [`depth_bounds`](Self::depth_bounds), skipped when every sample would fail the depth
    /// test, and the block's bound tightened after a triangle covers it.
    #[inline(always)]
    fn take_block(&mut self, t: &Planes, block: &Block<'_>) {
        if let Some(b) = self.depth_bounds()
            && b.hiz.occludes(b.rows, t, block, b.depth)
        {
            return;
        }
        block.rows(
            #[inline(always)]
            |row| self.take(t, row),
        );
        if let Some(b) = self.depth_bounds() {
            b.hiz.drawn(b.rows, block, b.depth, b.write);
        }
    }
}

/// A band's depth buffer with the bounds of its blocks: what [`Sink::take_block`] skips
/// hidden blocks with.
pub(crate) struct Bounded<'a> {
    /// Per block, a bound of `depth`.
    pub hiz: &'a mut HiZ,
    /// Where the band lies.
    pub rows: BandRows,
    /// Depth, the band's rows.
    pub depth: &'a [f32],
    /// Whether passing fragments store their depth.
    pub write: bool,
}

/// The bytes of a cache line on the machines `fast` is built for (x86-64, AArch64).
const LINE: usize = 64;

/// Reads one value per cache line of `rect`'s rows of `band` (a band's rows of a row-major
/// buffer), independent reads, so that their misses overlap: drawn into first, a tile's rows
/// miss one sample at a time, each waiting (the small scene's depth reads were a fifth of its
/// time).
#[inline(always)]
fn warm_lines<T: Copy>(rows: BandRows, band: &[T], rect: [u32; 4], bits: impl Fn(T) -> u32) {
    let step = (LINE / size_of::<T>()).max(1);
    let [x0, x1, y0, y1] = rect;
    let mut seen = 0;
    for y in y0..y1 {
        for x in (x0..x1).step_by(step) {
            seen ^= bits(band[rows.index(x, y)]);
        }
    }
    std::hint::black_box(seen);
}

/// Keeps every fragment.
impl Sink for Vec<Fragment> {
    #[inline(always)]
    fn take(&mut self, t: &Planes, row: &Lanes) {
        let depth = t.depth(&row.e);
        t.fragments(row, row.mask, &depth, |_, fragment| self.push(fragment));
    }
}

/// Calls `f` with `compare` as a constant: each arm inlines `f` with its own comparison, so
/// that a loop over lanes inside `f` compiles without a match (an indirect jump) per lane.
#[inline(always)]
fn with_constant(compare: CompareOp, f: impl Fn(CompareOp) -> u32) -> u32 {
    match compare {
        CompareOp::Never => f(CompareOp::Never),
        CompareOp::Less => f(CompareOp::Less),
        CompareOp::Equal => f(CompareOp::Equal),
        CompareOp::LessOrEqual => f(CompareOp::LessOrEqual),
        CompareOp::Greater => f(CompareOp::Greater),
        CompareOp::NotEqual => f(CompareOp::NotEqual),
        CompareOp::GreaterOrEqual => f(CompareOp::GreaterOrEqual),
        CompareOp::Always => f(CompareOp::Always),
    }
}

/// Which of the lanes in `mask` pass `compare`, `new` against `stored` (as many as `stored`
/// has, and `mask` none past them), as bits: only the lanes asked, the comparison a constant
/// ([`with_constant`]).
#[inline(always)]
fn passes(compare: CompareOp, new: &[f32; LANES], stored: &[f32], mask: u32) -> u32 {
    with_constant(
        compare,
        #[inline(always)]
        |op| {
            let mut pass = 0;
            for_each_lane(
                mask,
                #[inline(always)]
                |i| pass |= u32::from(op.passes(new[i], stored[i])) << i,
            );
            pass
        },
    )
}

/// [`passes`] on a full row, every lane: with the comparison a constant, one vector comparison.
#[inline(always)]
fn passes_full(compare: CompareOp, new: &[f32; LANES], stored: &[f32; LANES]) -> u32 {
    with_constant(
        compare,
        #[inline(always)]
        |op| {
            let mut pass = 0;
            for i in 0..LANES {
                pass |= u32::from(op.passes(new[i], stored[i])) << i;
            }
            pass
        },
    )
}

/// The depth test into a band of `Resolved`'s buffers, as `Resolved::from_fragments` does it.
pub(crate) struct ResolveBand<'b> {
    /// Where the band lies.
    pub rows: BandRows,
    /// The draw's depth test.
    pub state: DepthState,
    /// Depth, the band's rows.
    pub depth: &'b mut [f32],
    /// The last primitive that passed, the band's rows.
    pub primitive: &'b mut [Option<u32>],
    /// Bounds of `depth` per block.
    pub hiz: HiZ,
}

impl Sink for ResolveBand<'_> {
    /// All lanes tested at once; each lane is its own pixel, so the order among them is free.
    #[inline(always)]
    fn take(&mut self, t: &Planes, row: &Lanes) {
        let new = t.depth(&row.e);
        let span = self.rows.lanes(row);
        let depth = &mut self.depth[span.clone()];
        let primitive = &mut self.primitive[span];
        // A full row: the test and both writes as eight-lane selects.
        if let (Ok(depth), Ok(primitive)) = (
            <&mut [f32; LANES]>::try_from(&mut *depth),
            <&mut [Option<u32>; LANES]>::try_from(&mut *primitive),
        ) {
            let pass = passes_full(self.state.compare, &new, depth) & row.mask;
            for i in 0..LANES {
                let kept = pass >> i & 1 != 0;
                if self.state.write {
                    depth[i] = if kept { new[i] } else { depth[i] };
                }
                primitive[i] = if kept { Some(t.primitive) } else { primitive[i] };
            }
            return;
        }
        let pass = passes(self.state.compare, &new, depth, row.mask);
        for_each_lane(
            pass,
            #[inline(always)]
            |lane| {
                if self.state.write {
                    depth[lane] = new[lane];
                }
                primitive[lane] = Some(t.primitive);
            },
        );
    }

    #[inline(always)]
    fn warm(&mut self, rect: [u32; 4]) {
        warm_lines(self.rows, self.depth, rect, f32::to_bits);
        warm_lines(self.rows, self.primitive, rect, |p| p.unwrap_or(0));
    }

    #[inline(always)]
    fn depth_bounds(&mut self) -> Option<Bounded<'_>> {
        Some(Bounded {
            hiz: &mut self.hiz,
            rows: self.rows,
            depth: self.depth,
            write: self.state.write,
        })
    }
}

/// Early depth test, shading of what passes, depth and colour writes: `Renderer::draw_mesh`'s
/// order of work, into a band of a framebuffer.
pub(crate) struct ShadeBand<'b, C, F> {
    /// Where the band lies.
    pub rows: BandRows,
    /// The comparison.
    pub compare: CompareOp,
    /// Whether passing fragments store their depth.
    pub write: bool,
    /// Depth, the band's rows.
    pub depth: &'b mut [f32],
    /// Colour, the band's rows.
    pub color: &'b mut [C],
    /// The shader: a colour, or `None` to discard.
    pub shade: &'b F,
    /// Bounds of `depth` per block.
    pub hiz: HiZ,
}

impl<C: Send, F: Fn(&Fragment) -> Option<C> + Sync> Sink for ShadeBand<'_, C, F> {
    /// The depth test of all lanes first, each against its own pixel, then shading and writes
    /// of those that pass, in lane order: the lanes are different pixels, so this is the
    /// per-sample order of work.
    #[inline(always)]
    fn take(&mut self, t: &Planes, row: &Lanes) {
        let new = t.depth(&row.e);
        let span = self.rows.lanes(row);
        let depth = &mut self.depth[span.clone()];
        let pass = passes(self.compare, &new, depth, row.mask);
        let color = &mut self.color[span];
        t.fragments(
            row,
            pass,
            &new,
            #[inline(always)]
            |lane, fragment| {
                if let Some(c) = (self.shade)(&fragment) {
                    if self.write {
                        depth[lane] = new[lane];
                    }
                    color[lane] = c;
                }
            },
        );
    }

    /// Depth only: the colour type is the caller's, and its writes do not wait.
    #[inline(always)]
    fn warm(&mut self, rect: [u32; 4]) {
        warm_lines(self.rows, self.depth, rect, f32::to_bits);
    }

    #[inline(always)]
    fn depth_bounds(&mut self) -> Option<Bounded<'_>> {
        Some(Bounded {
            hiz: &mut self.hiz,
            rows: self.rows,
            depth: self.depth,
            write: self.write,
        })
    }
}
