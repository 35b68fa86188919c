//! The front end: each triangle through the reference's own stages, then binned into tiles.
//!
//! Everything that decides bits (assembly, snapping, clipping, the fan, facing, culling, the
//! bounding box) is a call into [`refrast::stage`], in the order `Reference::draw_samples` makes
//! them; this module only keeps what the back end needs and says which tiles it touches.
//!
//! What depends on a vertex alone (finiteness, its clip outcode, its projection and snapping)
//! is computed once per mesh vertex ([`VertexSetup`]), not once per triangle that uses it: the
//! same reference calls, made fewer times.

use std::ops::Range;

use refrast::stage::{
    ClipOutcome, ClipPlane, ClipVertex, FanTriangle, PixelRect, ProjectedPoint, RasterVertex, TriangleSetup,
    ViewportTransform, assemble, build_fan, classify, clip_triangle, drawn_winding, input_w, outcode,
};
use refrast::{Draw, FillConvention, Winding};

use crate::back::EdgeSteps;
use crate::plane::Planes;
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
    /// Every position of the draw, set up once ([`VertexSetup::new`]).
    pub vertices: &'d [VertexSetup],
}

/// What a position of the draw gives every triangle that uses it: what `assemble`,
/// `clip_triangle` and `snap_before_clipping` compute of a corner alone.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct VertexSetup {
    /// Whether every coordinate is finite; `assemble` discards a triangle with one that is not.
    pub finite: bool,
    /// The clip planes it lies outside of ([`outcode`]).
    pub outcode: u32,
    /// Its projection and snapping, when it has one.
    pub point: Option<ProjectedPoint>,
}

impl VertexSetup {
    /// Classifies, projects and snaps `position` as a corner of an input triangle.
    #[inline]
    pub fn new(position: [f32; 4], planes: &[ClipPlane], transform: &ViewportTransform) -> Self {
        // The clip-space position `assemble` makes of it (any corner: the position is the same).
        let clip = ClipVertex::corner(position, 0).position;
        Self {
            finite: position.iter().all(|c| c.is_finite()),
            outcode: outcode(planes, clip),
            point: transform.project_point(clip),
        }
    }
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
        let indices = setup.draw.triangles[primitive];
        let [a, b, c] = indices.map(|i| &setup.vertices[i as usize]);
        if !(a.finite && b.finite && c.finite) {
            return None;
        }
        // Snap before clipping: zero area draws nothing; `None` when a corner has no raster
        // position (then only a clipped polygon can be drawn).
        let snapped = match (a.point, b.point, c.point) {
            (Some(pa), Some(pb), Some(pc)) => {
                let points = [pa, pb, pc];
                Some((
                    TriangleSetup::new(points.map(|p| p.position), setup.fill)?,
                    points,
                ))
            }
            _ => None,
        };
        match classify([a.outcode, b.outcode, c.outcode]) {
            ClipOutcome::Outside => None,
            ClipOutcome::Inside => {
                let (t, points) = snapped?;
                // `drawn_winding` of an unclipped triangle: its snapped winding, so it is its
                // own fan and always drawn alone.
                let winding = t.winding();
                let (front_facing, rect) = kept(setup, winding, points.iter().map(|p| p.position))?;
                let (fans, raster) = (self.fans.len(), self.raster.len());
                self.push(primitive, front_facing, winding, rect, fans, raster);
                // The corners in the setup's clockwise order, the order of its edge values.
                let varyings = t.order().map(|k| points[k].corner(k).varyings);
                let last = self.triangles.last_mut().expect("pushed above");
                last.single = Some(Single {
                    steps: EdgeSteps::new(&t, setup.transform.bits, rect),
                    planes: Planes::new(primitive as u32, front_facing, varyings.each_ref(), t.area2()),
                });
                Some(rect)
            }
            ClipOutcome::Clipped => {
                let input = assemble(&setup.draw.positions, indices)?;
                // The outcodes said cut; what is cut can still leave less than a triangle.
                let outcome = clip_triangle(&input, &setup.planes, &mut self.polygon, &mut self.clip);
                if outcome != ClipOutcome::Clipped {
                    return None;
                }
                let (transform, projected) = (&setup.transform, &mut self.projected);
                if !transform.project_polygon(&self.polygon, input_w(&input), projected) {
                    return None;
                }
                build_fan(projected, setup.fill, &mut self.fan);
                let winding = drawn_winding(&input, true, self.fan.iter().map(|t| &t.setup));
                let (front_facing, rect) = kept(setup, winding, self.projected.iter().map(|v| v.position))?;
                let (fans, raster) = (self.fans.len(), self.raster.len());
                self.fans.extend_from_slice(&self.fan);
                self.raster.extend_from_slice(&self.projected);
                self.push(primitive, front_facing, winding, rect, fans, raster);
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

/// Facing, culling and the bounding box of `polygon`, in the reference's order: whether the
/// triangle faces the viewer and its box, or `None` when it is culled or off screen.
#[inline]
fn kept(
    setup: &DrawSetup<'_>,
    winding: Winding,
    polygon: impl Iterator<Item = refrast::FixedPoint>,
) -> Option<(bool, [u32; 4])> {
    let state = &setup.draw.state;
    let front_facing = state.front_face.is_front(winding)?;
    if state.cull.culls(front_facing) {
        return None;
    }
    let (x0, x1, y0, y1) =
        PixelRect::bounding(polygon, setup.transform.bits, setup.transform.viewport)?.bounds();
    Some((front_facing, [x0, x1, y0, y1]))
}
