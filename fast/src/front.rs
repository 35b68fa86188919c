//! The front end: each triangle through the reference's own stages, then binned into tiles.
//!
//! Everything that decides bits (assembly, snapping, clipping, the fan, facing, culling, the
//! bounding box) is a call into [`refrast::stage`], in the order `Reference::draw_samples` makes
//! them; this module only keeps what the back end needs and says which tiles it touches.

use std::ops::Range;

use refrast::stage::{
    ClipOutcome, ClipPlane, ClipVertex, FanTriangle, PixelRect, RasterVertex, TriangleSetup, Varyings,
    ViewportTransform, assemble, build_fan, clip_triangle, drawn_winding, input_w, snap_before_clipping,
};
use refrast::{Draw, FillConvention, Winding};

use crate::back::EdgeSteps;
use crate::tiles::TileGrid;

/// What every triangle of one draw shares: its clip planes, viewport transform and fill rule.
pub(crate) struct DrawSetup<'d> {
    /// The draw.
    pub draw: &'d Draw,
    /// Its clip planes, as `clip_planes` gives them for the configuration.
    pub planes: Vec<ClipPlane>,
    /// Its viewport transform.
    pub transform: ViewportTransform,
    /// The fill convention.
    pub fill: FillConvention,
}

/// A triangle that reached traversal: what the back end needs to draw it in any tile.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    /// Its index in the draw.
    pub primitive: u32,
    /// Whether it faces the viewer.
    pub front_facing: bool,
    /// The winding it is drawn with.
    pub winding: Winding,
    /// Its bounding box of samples, clamped to the viewport: columns then rows, half-open.
    pub rect: [u32; 4],
    /// Its fan triangles in [`Chunk::fans`].
    pub fans: Range<u32>,
    /// Its snapped polygon's vertices in [`Chunk::raster`].
    pub raster: Range<u32>,
    /// The single agreeing fan triangle, when that is all it is (the fast path).
    pub single: Option<Single>,
}

/// A triangle drawn as one fan triangle that agrees with its winding, with everything the
/// back end reads kept together: stepping, area and the corners' varyings in setup order.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Single {
    /// Its edge functions, stepped per pixel.
    pub steps: EdgeSteps,
    /// Twice its area, the sum of its edge values.
    pub area2: i64,
    /// What its corners carry, in the setup's clockwise order (the order of the edge values).
    pub corners: [Varyings; 3],
}

/// The triangles of one run of primitives, set up and binned by one thread; its buffers are
/// kept from draw to draw.
#[derive(Clone, Debug, Default)]
pub(crate) struct Chunk {
    /// The triangles that reached traversal, in primitive order.
    pub triangles: Vec<Prepared>,
    /// Their fan triangles.
    pub fans: Vec<FanTriangle>,
    /// Their polygons' vertices.
    pub raster: Vec<RasterVertex>,
    /// Per tile, the indices into `triangles` of those whose box touches it, in order.
    pub bins: Vec<Vec<u32>>,
    polygon: Vec<ClipVertex>,
    clip: Vec<ClipVertex>,
    projected: Vec<RasterVertex>,
    fan: Vec<FanTriangle>,
}

impl Chunk {
    /// Sets up and bins `primitives`, replacing what the chunk held.
    pub fn prepare(&mut self, setup: &DrawSetup<'_>, grid: &TileGrid, primitives: Range<usize>) {
        self.triangles.clear();
        self.fans.clear();
        self.raster.clear();
        self.bins.resize_with(grid.tiles(), Vec::new);
        self.bins.iter_mut().for_each(Vec::clear);
        for primitive in primitives {
            let index = self.triangles.len() as u32;
            if let Some(rect) = self.prepare_one(setup, primitive) {
                grid.for_each_tile(rect, |tile| self.bins[tile].push(index));
            }
        }
    }

    /// One triangle through the stages, as `Reference::draw_triangle` takes it, appended to
    /// `triangles`; its box, or `None` when it draws nothing (non-finite, clipped away,
    /// degenerate, culled or off screen).
    fn prepare_one(&mut self, setup: &DrawSetup<'_>, primitive: usize) -> Option<[u32; 4]> {
        // Borrowed where they are returned: moving them out copies ~170 and ~470 bytes.
        let input = assemble(&setup.draw.positions, setup.draw.triangles[primitive]);
        let input = input.as_ref()?;
        let snapped = snap_before_clipping(input, &setup.transform, setup.fill);
        let Ok(snapped) = &snapped else {
            return None;
        };
        match clip_triangle(input, &setup.planes, &mut self.polygon, &mut self.clip) {
            ClipOutcome::Outside => None,
            ClipOutcome::Inside => {
                // Read in place: the snapped triangle is not copied into a fan of one.
                let triangle = snapped.as_ref()?;
                let winding = drawn_winding(input, false, std::iter::once(&triangle.setup));
                let (front_facing, rect) = kept(setup, winding, &triangle.vertices)?;
                let t = &triangle.setup;
                let alone = t.winding() == winding;
                let (fans, raster) = (self.fans.len(), self.raster.len());
                if !alone {
                    self.fans.push(FanTriangle::whole(*t));
                    self.raster.extend_from_slice(&triangle.vertices);
                }
                self.push(primitive, front_facing, winding, rect, fans, raster);
                if alone {
                    let ([a, b, c], v) = (t.order(), &triangle.vertices);
                    let last = self.triangles.last_mut().expect("pushed above");
                    set_single(&mut last.single, setup, t, [a, b, c].map(|k| &v[k].varyings));
                }
                Some(rect)
            }
            ClipOutcome::Clipped => {
                let (transform, projected) = (&setup.transform, &mut self.projected);
                if !transform.project_polygon(&self.polygon, input_w(input), projected) {
                    return None;
                }
                build_fan(projected, setup.fill, &mut self.fan);
                let winding = drawn_winding(input, true, self.fan.iter().map(|t| &t.setup));
                let (front_facing, rect) = kept(setup, winding, &self.projected)?;
                let alone = matches!(self.fan.as_slice(), [t] if t.setup.winding() == winding);
                let (fans, raster) = (self.fans.len(), self.raster.len());
                if !alone {
                    self.fans.extend_from_slice(&self.fan);
                    self.raster.extend_from_slice(&self.projected);
                }
                self.push(primitive, front_facing, winding, rect, fans, raster);
                if alone {
                    let t = &self.fan[0];
                    let corners = t.setup.order().map(|k| &self.projected[t.corners[k]].varyings);
                    let last = self.triangles.last_mut().expect("pushed above");
                    set_single(&mut last.single, setup, &t.setup, corners);
                }
                Some(rect)
            }
        }
    }

    /// Appends a triangle whose fan (when it has one) starts at `fans` and polygon at `raster`;
    /// a lone fan triangle is written into it afterwards, in place ([`set_single`]).
    #[inline]
    fn push(
        &mut self,
        primitive: usize,
        front_facing: bool,
        winding: Winding,
        rect: [u32; 4],
        fans: usize,
        raster: usize,
    ) {
        self.triangles.push(Prepared {
            primitive: primitive as u32,
            front_facing,
            winding,
            rect,
            fans: fans as u32..self.fans.len() as u32,
            raster: raster as u32..self.raster.len() as u32,
            single: None,
        });
    }
}

/// Makes `slot` the lone fan triangle `t` with `corners` in its setup's order, written where it
/// lies: built elsewhere and moved, the ~340 bytes would be copied.
#[inline]
fn set_single(slot: &mut Option<Single>, setup: &DrawSetup<'_>, t: &TriangleSetup, corners: [&Varyings; 3]) {
    *slot = Some(Single {
        steps: EdgeSteps::new(t, setup.transform.bits),
        area2: t.area2(),
        corners: corners.map(|c| *c),
    });
}

/// Facing, culling and the bounding box of `polygon`, in the reference's order: whether the
/// triangle faces the viewer and its box, or `None` when it is culled or off screen.
#[inline]
fn kept(setup: &DrawSetup<'_>, winding: Winding, polygon: &[RasterVertex]) -> Option<(bool, [u32; 4])> {
    let state = &setup.draw.state;
    let front_facing = state.front_face.is_front(winding)?;
    if state.cull.culls(front_facing) {
        return None;
    }
    let (x0, x1, y0, y1) = PixelRect::bounding(
        polygon.iter().map(|v| v.position),
        setup.transform.bits,
        setup.transform.viewport,
    )?
    .bounds();
    Some((front_facing, [x0, x1, y0, y1]))
}
