//! Covered samples and what a band does with them: keep fragments, resolve, or shade.
//!
//! A covered sample's depth and barycentrics are the reference's calls on the same exact edge
//! values (`Reference`'s `Sample::new` and `Sample::fragment`), so their bits are the same.

use refrast::stage::{
    FanTriangle, RasterVertex, Varyings, fragment_depth, interpolate, interpolate_depth, screen_weights,
};
use refrast::{CompareOp, DepthState, Fragment};

use crate::back::{BLOCK, Row};

/// A covered sample with its depth; [`fragment`](Covered::fragment) adds the barycentrics.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Covered<'a> {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// The triangle's index in the draw.
    pub primitive: u32,
    /// Window depth, as the reference computes it.
    pub depth: f32,
    front_facing: bool,
    values: [i64; 3],
    area2: i64,
    corners: [&'a Varyings; 3],
}

/// What the samples of one fan triangle share.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Corners<'a> {
    /// The triangle's index in the draw.
    pub primitive: u32,
    /// Whether it faces the viewer.
    pub front_facing: bool,
    area2: i64,
    corners: [&'a Varyings; 3],
}

impl<'a> Corners<'a> {
    /// The corners of fan triangle `t` of the polygon `raster`, in its setup's clockwise order
    /// (the order of the edge values), as the reference takes them.
    #[inline]
    pub fn new(primitive: u32, front_facing: bool, t: &FanTriangle, raster: &'a [RasterVertex]) -> Self {
        Self {
            primitive,
            front_facing,
            area2: t.setup.area2(),
            corners: t.setup.order().map(|k| &raster[t.corners[k]].varyings),
        }
    }

    /// The corners of a triangle drawn whole, `corners` in its setup's order.
    #[inline]
    pub fn whole(primitive: u32, front_facing: bool, area2: i64, corners: &'a [Varyings; 3]) -> Self {
        Self {
            primitive,
            front_facing,
            area2,
            corners: corners.each_ref(),
        }
    }

    /// The sample at `(x, y)` with exact edge values `values`, its depth interpolated.
    #[inline]
    pub fn sample(&self, x: u32, y: u32, values: [i64; 3]) -> Covered<'a> {
        Covered {
            x,
            y,
            primitive: self.primitive,
            depth: fragment_depth(interpolate_depth(self.corners, values, self.area2)),
            front_facing: self.front_facing,
            values,
            area2: self.area2,
            corners: self.corners,
        }
    }

    /// Lane `lane` of `row`, its depth already interpolated (one of [`row_depths`](Self::row_depths)).
    #[inline]
    fn lane(&self, row: &Row, lane: u32, depth: f32) -> Covered<'a> {
        Covered {
            x: row.x0 + lane,
            y: row.y,
            primitive: self.primitive,
            depth,
            front_facing: self.front_facing,
            values: row.values_at(lane),
            area2: self.area2,
            corners: self.corners,
        }
    }

    /// The depths of all eight lanes of `row`, covered or not: the reference's calls on each
    /// lane's exact edge values, made lane by lane in one loop the compiler can vectorise.
    #[inline]
    fn row_depths(&self, row: &Row) -> [f32; BLOCK as usize] {
        std::array::from_fn(|lane| {
            fragment_depth(interpolate_depth(
                self.corners,
                row.values_at(lane as u32),
                self.area2,
            ))
        })
    }
}

impl Covered<'_> {
    /// The full fragment: perspective-correct and screen-space barycentrics added.
    #[inline]
    pub fn fragment(&self) -> Fragment {
        let b = interpolate(self.corners, screen_weights(self.values, self.area2));
        Fragment {
            x: self.x,
            y: self.y,
            primitive: self.primitive,
            depth: self.depth,
            barycentric: b.perspective.as_vec3().to_array(),
            screen_barycentric: b.screen.map(|s| s.as_vec3().to_array()),
            front_facing: self.front_facing,
        }
    }
}

/// Rows with fewer covered lanes than this interpolate depth lane by lane: eight lanes at once
/// would do more work than they save (tiny triangles cover a few samples a row).
const FEW: u32 = 5;

/// What one band does with its covered samples, which come in primitive order per pixel.
pub(crate) trait Sink: Send {
    /// Takes one covered sample.
    fn covered(&mut self, sample: &Covered<'_>);

    /// Takes the covered lanes of `row` of a triangle with `corners`, in order: one by one
    /// when there are few, else as a row.
    #[inline]
    fn take_row(&mut self, corners: &Corners<'_>, row: &Row) {
        if row.mask.count_ones() < FEW {
            self.covered_lanes(corners, row);
        } else {
            self.covered_row(corners, row);
        }
    }

    /// Takes the covered lanes of `row`, one sample at a time.
    #[inline]
    fn covered_lanes(&mut self, corners: &Corners<'_>, row: &Row) {
        Row::for_each_lane(row.mask, |lane| {
            self.covered(&corners.sample(row.x0 + lane, row.y, row.values_at(lane)));
        });
    }

    /// Takes a row of at least [`FEW`] covered lanes; one at a time unless the sink does better.
    #[inline]
    fn covered_row(&mut self, corners: &Corners<'_>, row: &Row) {
        self.covered_lanes(corners, row);
    }
}

/// Keeps every fragment.
impl Sink for Vec<Fragment> {
    #[inline]
    fn covered(&mut self, sample: &Covered<'_>) {
        self.push(sample.fragment());
    }
}

/// The rows of a band in a row-major buffer: where pixel `(x, y)` lies.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BandRows {
    /// The band's first row.
    pub y0: u32,
    /// The buffer's width.
    pub width: u32,
}

impl BandRows {
    /// Index of pixel `(x, y)` in the band's slice.
    #[inline]
    fn index(self, x: u32, y: u32) -> usize {
        (y - self.y0) as usize * self.width as usize + x as usize
    }

    /// The range of the band's slice that `row`'s lanes up to its last covered one occupy.
    #[inline]
    fn lanes(self, row: &Row) -> std::ops::Range<usize> {
        let start = self.index(row.x0, row.y);
        start..start + (u32::BITS - row.mask.leading_zeros()) as usize
    }
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
}

impl Sink for ResolveBand<'_> {
    #[inline]
    fn covered(&mut self, sample: &Covered<'_>) {
        let i = self.rows.index(sample.x, sample.y);
        if self.state.test_and_write(sample.depth, &mut self.depth[i]) {
            self.primitive[i] = Some(sample.primitive);
        }
    }

    #[inline]
    fn covered_row(&mut self, corners: &Corners<'_>, row: &Row) {
        let depths = corners.row_depths(row);
        let lanes = self.rows.lanes(row);
        let (depth, primitive) = (&mut self.depth[lanes.clone()], &mut self.primitive[lanes]);
        Row::for_each_lane(row.mask, |lane| {
            let i = lane as usize;
            if self.state.test_and_write(depths[i], &mut depth[i]) {
                primitive[i] = Some(corners.primitive);
            }
        });
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
}

impl<C: Send, F: Fn(&Fragment) -> Option<C> + Sync> Sink for ShadeBand<'_, C, F> {
    #[inline]
    fn covered(&mut self, sample: &Covered<'_>) {
        let i = self.rows.index(sample.x, sample.y);
        if !self.compare.passes(sample.depth, self.depth[i]) {
            return;
        }
        if let Some(color) = (self.shade)(&sample.fragment()) {
            if self.write {
                self.depth[i] = sample.depth;
            }
            self.color[i] = color;
        }
    }

    /// The depth test of all lanes first, each against its own pixel, then shading and writes
    /// of those that pass, in lane order: the lanes are different pixels, so this is the
    /// per-sample order of work.
    #[inline]
    fn covered_row(&mut self, corners: &Corners<'_>, row: &Row) {
        let depths = corners.row_depths(row);
        let lanes = self.rows.lanes(row);
        let (depth, color) = (&mut self.depth[lanes.clone()], &mut self.color[lanes]);
        let mut pass = 0;
        for (i, (new, stored)) in depths.iter().zip(depth.iter()).enumerate() {
            pass |= u32::from(self.compare.passes(*new, *stored)) << i;
        }
        Row::for_each_lane(row.mask & pass, |lane| {
            let i = lane as usize;
            if let Some(c) = (self.shade)(&corners.lane(row, lane, depths[i]).fragment()) {
                if self.write {
                    depth[i] = depths[i];
                }
                color[i] = c;
            }
        });
    }
}
