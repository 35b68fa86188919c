//! The front end: each triangle through the reference's own front end, then binned into tiles.
//!
//! Which triangles are drawn, how they turn and what they cover is decided by
//! [`refrast::stage::front_end`], the call the reference makes; this module keeps what the back
//! end needs and says which tiles a triangle touches. What depends on a vertex alone
//! (finiteness, its clip outcode, its projection and snapping: a [`Corner`]) is computed once per
//! mesh vertex, not once per triangle that uses it.

use std::ops::Range;

use refrast::Winding;
use refrast::stage::{Corner, FanTriangle, FrontScratch, FrontSetup, front_end};

use crate::back::EdgeSteps;
use crate::plane::Planes;
use crate::tiles::TileGrid;

/// What every triangle of one draw shares: the front end's setup and every position's corner.
pub(crate) struct DrawSetup<'d> {
    /// The draw, its clip planes, viewport transform and fill rule.
    pub front: FrontSetup<'d>,
    /// Every position of the draw as a triangle's corner, set up once ([`Corner::new`]).
    pub vertices: &'d [Corner],
}

/// The largest box, in pixels, cut to the samples its triangle covers before binning: a
/// triangle smaller than a pixel or two often covers none, or fewer tiles than its box
/// touches; beyond it, testing every sample in the front end would cost what traversal does.
const TIGHTENED: u32 = 16;

/// A triangle that reached traversal: what the back end needs to draw it in any tile.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    /// The winding it is drawn with.
    pub winding: Winding,
    /// Its bounding box of samples, clamped to the viewport: columns then rows, half-open.
    pub rect: [u32; 4],
    /// Its fan triangles in [`Chunk::fans`] and their interpolation in [`Chunk::fan_planes`].
    pub fans: Range<u32>,
    /// The single agreeing fan triangle, when that is all it is (the fast path).
    pub single: Option<Single>,
}

impl Prepared {
    /// A value read from each part of the record (its box, its edge steps, its planes), for
    /// bringing it into the cache before it is drawn (`drive::warm_tile`).
    #[inline(always)]
    pub fn warm(&self) -> u32 {
        let mut seen = self.rect[0] ^ self.fans.start;
        if let Some(single) = &self.single {
            seen ^= single.steps.warm() ^ single.planes.warm();
        }
        seen
    }
}

/// A triangle drawn as one fan triangle that agrees with its winding: its coverage and its
/// interpolation, set up once.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Single {
    /// Its edge functions, stepped per pixel.
    pub steps: EdgeSteps,
    /// Its depth and barycentrics.
    pub planes: Planes,
}

/// The triangles of one run of primitives, set up and binned by one thread; its buffers are
/// kept from draw to draw.
#[derive(Clone, Debug, Default)]
pub(crate) struct Chunk {
    /// The triangles that reached traversal, in primitive order.
    pub triangles: Vec<Prepared>,
    /// Their fan triangles.
    pub fans: Vec<FanTriangle>,
    /// Each fan triangle's interpolation, set up once (parallel to `fans`).
    pub fan_planes: Vec<Planes>,
    /// Per tile, the indices into `triangles` of those whose box touches it, in order.
    pub bins: Vec<Vec<u32>>,
    scratch: FrontScratch,
}

impl Chunk {
    /// Sets up and bins `primitives`, replacing what the chunk held.
    pub fn prepare(&mut self, setup: &DrawSetup<'_>, grid: &TileGrid, primitives: Range<usize>) {
        self.triangles.clear();
        self.fans.clear();
        self.fan_planes.clear();
        self.bins.resize_with(grid.tiles(), Vec::new);
        self.bins.iter_mut().for_each(Vec::clear);
        for primitive in primitives {
            let index = self.triangles.len() as u32;
            if let Some(rect) = self.prepare_one(setup, primitive) {
                grid.for_each_tile(rect, |tile| self.bins[tile].push(index));
            }
        }
    }

    /// One triangle through the front end the reference uses ([`front_end`]), its corners set
    /// up once per vertex, appended to `triangles`; its box, or `None` when it draws nothing.
    fn prepare_one(&mut self, setup: &DrawSetup<'_>, primitive: usize) -> Option<[u32; 4]> {
        let corners = setup.front.triangles[primitive].map(|i| &setup.vertices[i as usize]);
        // Borrowed where it lies: moved out of the `Result` (or through `.ok()?`), the
        // ~340-byte record was copied once a triangle.
        let kept = front_end(&setup.front, primitive, corners, &mut self.scratch);
        let Ok(kept) = &kept else {
            return None;
        };
        let (x0, x1, y0, y1) = kept.rect.bounds();
        let mut rect = [x0, x1, y0, y1];
        let fans = self.fans.len();
        let single = match &kept.whole {
            Some(t) => {
                let steps = EdgeSteps::new(&t.setup, setup.front.transform.bits, rect);
                if (x1 - x0) * (y1 - y0) <= TIGHTENED {
                    rect = steps.covered_box(rect)?;
                }
                // The corners in the setup's clockwise order, the order of its edge values.
                let [a, b, c] = t.setup.order();
                let corner = |k: usize| t.points[k].corner_varyings(k);
                let (a, b, c) = (corner(a), corner(b), corner(c));
                let varyings = [&a, &b, &c];
                Some(Single {
                    steps,
                    planes: Planes::new(
                        primitive as u32,
                        kept.front_facing,
                        varyings,
                        t.setup.area2(),
                        setup.front.draw.state.viewport_depth,
                        kept.depth_offset,
                    ),
                })
            }
            None => {
                let (fan, polygon) = (&self.scratch.fan, &self.scratch.raster);
                self.fan_planes.extend(fan.iter().map(|f| {
                    let corners = f.setup.order().map(|k| &polygon[f.corners[k]].varyings);
                    Planes::new(
                        primitive as u32,
                        kept.front_facing,
                        corners,
                        f.setup.area2(),
                        setup.front.draw.state.viewport_depth,
                        kept.depth_offset,
                    )
                }));
                self.fans.extend_from_slice(fan);
                None
            }
        };
        self.triangles.push(Prepared {
            winding: kept.winding,
            rect,
            fans: fans as u32..self.fans.len() as u32,
            single,
        });
        Some(rect)
    }
}
