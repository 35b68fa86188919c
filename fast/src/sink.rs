//! Covered samples and what a band does with them: keep fragments, resolve, or shade.
//!
//! A covered sample's depth and barycentrics are the reference's calls on the same exact edge
//! values (`Reference`'s `Sample::new` and `Sample::fragment`), so their bits are the same.

use refrast::stage::{
    FanTriangle, RasterVertex, Varyings, fragment_depth, interpolate, interpolate_depth, screen_weights,
};
use refrast::{CompareOp, DepthState, Fragment};

use crate::front::Single;

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

    /// The corners of a triangle drawn as one fan triangle, kept in its [`Single`].
    #[inline]
    pub fn single(primitive: u32, front_facing: bool, single: &'a Single) -> Self {
        Self {
            primitive,
            front_facing,
            area2: single.area2,
            corners: single.corners.each_ref(),
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

/// What one band does with its covered samples, which come in primitive order per pixel.
pub(crate) trait Sink: Send {
    /// Takes one covered sample.
    fn covered(&mut self, sample: &Covered<'_>);
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
}
