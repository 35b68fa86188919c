//! The front end of one triangle, in the one order refrast draws it: finiteness, snap before
//! clipping, clip, fan, face, cull, bound.
//!
//! The reference calls [`front_end`] once per triangle; a batched front end (`fast`) calls it
//! with [`Corner`]s it set up once per mesh vertex. Either way the order of the stages, and so
//! which triangles are drawn, how they turn and which discard they count as, is written here
//! alone.

use std::borrow::Cow;

use crate::bias::polygon_offset;
use crate::clip::{
    ClipOutcome, ClipPlane, ClipVertex, assemble, classify, clip_planes, clip_triangle, outcode,
};
use crate::config::{ReferenceConfig, Traversal};
use crate::distance::{CornerDistances, Unkept};
use crate::draw::Draw;
use crate::edge::FillConvention;
use crate::fixed::FixedPoint;
use crate::project::{ProjectedPoint, RasterVertex, ViewportTransform, input_w};
use crate::setup::{SnappedTriangle, Winding, drawn_winding};
use crate::traverse::{FanTriangle, PixelRect, build_fan};

/// What one corner of an input triangle gives the front end on its own: computable once per
/// mesh vertex and shared by every triangle that uses it.
#[derive(Clone, Copy, Debug, Default)]
pub struct Corner {
    /// Whether every coordinate is finite; a triangle with a corner that is not draws nothing.
    pub finite: bool,
    /// The clip planes it lies outside of ([`outcode`]).
    pub outcode: u32,
    /// Its projection and snapping, when it has one (`w > 0`, in range).
    pub point: Option<ProjectedPoint>,
}

impl Corner {
    /// Classifies, projects and snaps `position` as a corner of an input triangle.
    #[must_use]
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

/// What every triangle of one draw shares.
#[derive(Clone, Debug)]
pub struct FrontSetup<'d> {
    /// The draw.
    pub draw: &'d Draw,
    /// Its triangles, gathered once ([`Draw::triangles`]).
    pub triangles: Cow<'d, [[u32; 3]]>,
    /// Its clip planes.
    pub planes: Vec<ClipPlane>,
    /// Its viewport transform.
    pub transform: ViewportTransform,
    /// The fill convention.
    pub fill: FillConvention,
    /// Which pixels a kept triangle is tested on.
    pub traversal: Traversal,
}

impl<'d> FrontSetup<'d> {
    /// The setup of `draw` under the reference configuration `config`.
    #[must_use]
    pub fn new(draw: &'d Draw, config: ReferenceConfig) -> Self {
        Self {
            draw,
            triangles: draw.triangles(),
            planes: clip_planes(config.clip, draw.viewport, draw.state.depth_clip()),
            transform: ViewportTransform {
                viewport: draw.viewport,
                bits: config.subpixel_bits,
                rounding: config.snap_rounding,
                depth_range: draw.state.depth_range,
                viewport_depth: draw.state.viewport_depth,
            },
            fill: config.fill,
            traversal: config.traversal,
        }
    }

    /// The corners of triangle `primitive`, each set up alone.
    #[must_use]
    #[inline]
    pub fn corners(&self, primitive: usize) -> [Corner; 3] {
        self.triangles[primitive]
            .map(|i| Corner::new(self.draw.positions[i as usize], &self.planes, &self.transform))
    }
}

/// Buffers a front end reuses from triangle to triangle; after a clipped triangle is kept,
/// `raster` and `fan` hold its snapped polygon and fan.
#[derive(Clone, Debug, Default)]
pub struct FrontScratch {
    polygon: Vec<ClipVertex>,
    clip: Vec<ClipVertex>,
    /// The kept clipped triangle's snapped polygon.
    pub raster: Vec<RasterVertex>,
    /// Its fan.
    pub fan: Vec<FanTriangle>,
}

/// Why a triangle draws nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Discard {
    /// A NaN or infinite coordinate.
    NonFinite,
    /// Wholly outside the clip volume (behind the eye included) or a user clip distance, or
    /// culled by a cull distance.
    ClippedAway,
    /// Zero area after snapping, or no raster position (drawn never).
    Degenerate,
    /// Culled by facing.
    Culled,
    /// Inside the clip volume, with a bounding box that holds no sample of the viewport.
    OffScreen,
}

/// A primitive its distances leave out is counted as one the clip volume does.
impl From<Unkept> for Discard {
    fn from(unkept: Unkept) -> Self {
        match unkept {
            Unkept::NonFinite => Self::NonFinite,
            Unkept::Culled => Self::ClippedAway,
        }
    }
}

/// A triangle the front end keeps, ready for traversal.
#[derive(Clone, Copy, Debug)]
pub struct Kept {
    /// Whether it faces the viewer.
    pub front_facing: bool,
    /// The winding it is drawn with.
    pub winding: Winding,
    /// The pixels to test.
    pub rect: PixelRect,
    /// The triangle itself when it needed no clipping (then it is its own fan); `None` when
    /// clipped, its polygon and fan then in the scratch's `raster` and `fan`.
    pub whole: Option<SnappedTriangle>,
    /// Its depth bias `o`, added to every fragment's depth before the clamp; 0 unbiased
    /// ([`polygon_offset`]).
    pub depth_offset: f64,
}

impl Kept {
    /// Its snapped polygon: the triangle's corners, or the clipped polygon in `scratch`.
    #[must_use]
    pub fn polygon(&self, scratch: &FrontScratch) -> Vec<RasterVertex> {
        match &self.whole {
            Some(t) => t.vertices().to_vec(),
            None => scratch.raster.clone(),
        }
    }
}

/// Takes triangle `primitive`, whose corners are `corners` (as [`FrontSetup::corners`] gives
/// them), through the front end: kept, or why it draws nothing.
///
/// 1. a non-finite corner or user distance discards it, and so does every corner negative in
///    one cull distance;
/// 2. **snap before clipping**: when every corner projects, the snapped input is set up, and
///    zero area draws nothing (clipping it would leave slivers off its line);
/// 3. **clip** (the clip volume, then each user clip distance): wholly outside draws nothing; wholly inside is drawn as snapped; otherwise it
///    is clipped, its polygon projected, snapped and fanned;
/// 4. **face** by the winding it is drawn with ([`drawn_winding`]), then **cull**;
/// 5. **bound**: its box of samples in the viewport, or the whole viewport.
///
/// Inlined, and the corners taken by reference, so that a batched caller builds the large
/// [`Kept`] in place: copies of it were most of the 30 % `fast` spent in `memcpy` on the torus.
#[inline]
pub fn front_end(
    setup: &FrontSetup<'_>,
    primitive: usize,
    corners: [&Corner; 3],
    scratch: &mut FrontScratch,
) -> Result<Kept, Discard> {
    if !corners.iter().all(|c| c.finite) {
        return Err(Discard::NonFinite);
    }
    // User distances: non-finite ones discard, a cull distance may cull, clip distances cut.
    // Set up only where the draw has distances: otherwise the ~200-byte record was zeroed and
    // copied for every triangle.
    let user = if setup.draw.distances.is_empty() {
        None
    } else {
        Some(CornerDistances::of(
            &setup.draw.distances,
            &setup.triangles[primitive],
        )?)
    };
    let user_outcode = |k: usize| user.as_ref().map_or(0, |u| u.outcode(k));
    let snapped = match corners.map(|c| c.point) {
        [Some(a), Some(b), Some(c)] => {
            Some(SnappedTriangle::new([a, b, c], setup.fill).ok_or(Discard::Degenerate)?)
        }
        _ => None,
    };
    match classify([0, 1, 2].map(|k| corners[k].outcode | user_outcode(k))) {
        ClipOutcome::Outside => Err(Discard::ClippedAway),
        ClipOutcome::Inside => {
            let triangle = snapped.ok_or(Discard::Degenerate)?;
            let winding = triangle.setup.winding();
            let positions = triangle.points.map(|p| p.position);
            // The corners as raster vertices only where a bias needs them.
            let offset = match setup.draw.state.depth_bias {
                None => 0.0,
                bias => polygon_offset(bias, &triangle.vertices(), setup.transform.bits),
            };
            kept(setup, winding, positions, Some(triangle), offset)
        }
        ClipOutcome::Clipped => {
            let input =
                assemble(&setup.draw.positions, setup.triangles[primitive]).ok_or(Discard::NonFinite)?;
            // The outcodes said cut; what is cut can still leave less than a triangle.
            if clip_triangle(
                &input,
                &setup.planes,
                user.as_ref().map_or(&[], CornerDistances::planes),
                &mut scratch.polygon,
                &mut scratch.clip,
            ) != ClipOutcome::Clipped
            {
                return Err(Discard::ClippedAway);
            }
            if !setup
                .transform
                .project_polygon(&scratch.polygon, input_w(&input), &mut scratch.raster)
            {
                return Err(Discard::Degenerate);
            }
            build_fan(&scratch.raster, setup.fill, &mut scratch.fan);
            let winding = drawn_winding(&input, true, scratch.fan.iter().map(|t| &t.setup));
            let offset = polygon_offset(setup.draw.state.depth_bias, &scratch.raster, setup.transform.bits);
            kept(
                setup,
                winding,
                scratch.raster.iter().map(|v| v.position),
                None,
                offset,
            )
        }
    }
}

/// Facing, culling and bounding, in that order.
#[inline]
fn kept(
    setup: &FrontSetup<'_>,
    winding: Winding,
    polygon: impl IntoIterator<Item = FixedPoint>,
    whole: Option<SnappedTriangle>,
    depth_offset: f64,
) -> Result<Kept, Discard> {
    let state = &setup.draw.state;
    let front_facing = state.front_face.is_front(winding).ok_or(Discard::Degenerate)?;
    if state.cull.culls(front_facing) {
        return Err(Discard::Culled);
    }
    let (bits, viewport) = (setup.transform.bits, setup.transform.viewport);
    let rect = match setup.traversal {
        Traversal::BoundingBox => PixelRect::bounding(polygon, bits, viewport).ok_or(Discard::OffScreen)?,
        Traversal::Viewport => PixelRect::of_viewport(viewport),
    };
    Ok(Kept {
        front_facing,
        winding,
        rect,
        whole,
        depth_offset,
    })
}
