//! The reference rasterizer: clip, project, snap, set up, traverse, interpolate — nothing clever.

use crate::clip::{ClipMode, ClipOutcome, ClipPlane, ClipVertex, assemble, clip_planes, clip_triangle};
use crate::depth::fragment_depth;
use crate::edge::FillConvention;
use crate::error::DrawError;
use crate::features::{Features, SnapAccuracy};
use crate::fixed::{SnapRounding, SubpixelBits};
use crate::interp::{Varyings, interpolate, interpolate_depth, screen_weights};
use crate::profile::{DepthConvention, Profile, Snapping, Spec};
use crate::project::{RasterVertex, ViewportTransform, input_w};
use crate::rasterizer::{Draw, Fragment, Rasterizer};
use crate::setup::{SnappedTriangle, ZeroArea, drawn_winding, snap_before_clipping};
use crate::traverse::{FanTriangle, Hit, PixelRect, build_fan, traverse};

/// Which pixels are tested against a triangle; both give identical output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Traversal {
    /// Only the pixels of the triangle's bounding box, clamped to the viewport.
    #[default]
    BoundingBox,
    /// Every pixel of the viewport, as the first lab step does.
    Viewport,
}

/// The reference's knobs; the defaults are the conventions stated in the crate docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct ReferenceConfig {
    /// Subpixel precision of snapping.
    pub subpixel_bits: SubpixelBits,
    /// How a coordinate becomes a grid point (half to even, refrast's convention, by default).
    pub snap_rounding: SnapRounding,
    /// Which edges own the samples on them.
    pub fill: FillConvention,
    /// Guard band (default), a band of another reach, or full six-plane clipping for x and y.
    pub clip: ClipMode,
    /// Bounding-box (default) or whole-viewport traversal.
    pub traversal: Traversal,
}

/// What happened to the triangles of a draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DrawStats {
    /// Triangles submitted.
    pub triangles: usize,
    /// Discarded for a NaN or infinite coordinate.
    pub non_finite: usize,
    /// Wholly outside the clip volume, behind the eye included.
    pub clipped_away: usize,
    /// Zero area after snapping, or a vertex with no raster position (drawn never).
    pub degenerate: usize,
    /// Discarded by the cull mode.
    pub culled: usize,
    /// Inside the clip volume, but with a bounding box that holds no sample of the viewport.
    pub off_screen: usize,
    /// Triangles that reached traversal.
    pub traversed: usize,
    /// Fragments emitted.
    pub fragments: usize,
}

/// Why a triangle drew nothing; each reason has its counter in [`DrawStats`].
enum Discard {
    NonFinite,
    ClippedAway,
    Degenerate,
    Culled,
    OffScreen,
}

impl From<ZeroArea> for Discard {
    fn from(_: ZeroArea) -> Self {
        Self::Degenerate
    }
}

impl DrawStats {
    fn count(&mut self, discard: Discard) {
        *match discard {
            Discard::NonFinite => &mut self.non_finite,
            Discard::ClippedAway => &mut self.clipped_away,
            Discard::Degenerate => &mut self.degenerate,
            Discard::Culled => &mut self.culled,
            Discard::OffScreen => &mut self.off_screen,
        } += 1;
    }
}

/// The reference rasterizer: exact coverage on snapped coordinates, the definition of correct.
#[derive(Clone, Debug, Default)]
pub struct Reference {
    config: ReferenceConfig,
}

/// What every triangle of one draw shares: its clip planes and its viewport transform.
struct DrawSetup<'d> {
    draw: &'d Draw,
    planes: Vec<ClipPlane>,
    transform: ViewportTransform,
}

/// Buffers reused across the triangles of one draw.
#[derive(Default)]
struct Scratch {
    polygon: Vec<ClipVertex>,
    clip: Vec<ClipVertex>,
    raster: Vec<RasterVertex>,
    fan: Vec<FanTriangle>,
    row: Vec<[i64; 3]>,
}

impl Reference {
    /// A reference rasterizer with the given configuration.
    #[must_use]
    pub fn new(config: ReferenceConfig) -> Self {
        Self { config }
    }

    /// Its configuration.
    #[must_use]
    pub fn config(&self) -> ReferenceConfig {
        self.config
    }

    /// Rasterizes `draw`, handing each fragment to `emit` in primitive order.
    pub fn draw(&self, draw: &Draw, mut emit: impl FnMut(Fragment)) -> Result<DrawStats, DrawError> {
        self.draw_samples(draw, |sample| emit(sample.fragment()))
    }

    /// Rasterizes `draw`, handing each covered [`Sample`] to `visit` in primitive order.
    ///
    /// A sample carries its depth; its barycentrics are computed only when asked for, so a
    /// depth test can reject it first.
    pub fn draw_samples(
        &self,
        draw: &Draw,
        mut visit: impl FnMut(&Sample<'_>),
    ) -> Result<DrawStats, DrawError> {
        draw.validate()?;
        let setup = DrawSetup {
            draw,
            planes: clip_planes(
                self.config.clip,
                draw.viewport,
                draw.state.clip_far,
                draw.state.depth_range,
            ),
            transform: ViewportTransform {
                viewport: draw.viewport,
                bits: self.config.subpixel_bits,
                rounding: self.config.snap_rounding,
                depth_range: draw.state.depth_range,
            },
        };
        let mut scratch = Scratch::default();
        let mut stats = DrawStats {
            triangles: draw.triangles.len(),
            ..DrawStats::default()
        };
        for primitive in 0..draw.triangles.len() {
            match self.draw_triangle(&setup, primitive, &mut scratch, &mut visit) {
                Ok(fragments) => {
                    stats.traversed += 1;
                    stats.fragments += fragments;
                }
                Err(discard) => stats.count(discard),
            }
        }
        Ok(stats)
    }

    /// One triangle through the stages; the number of samples it covered, or why it drew nothing.
    fn draw_triangle(
        &self,
        setup: &DrawSetup<'_>,
        primitive: usize,
        scratch: &mut Scratch,
        visit: &mut impl FnMut(&Sample<'_>),
    ) -> Result<usize, Discard> {
        let state = &setup.draw.state;
        let input =
            assemble(&setup.draw.positions, setup.draw.triangles[primitive]).ok_or(Discard::NonFinite)?;
        let snapped = snap_before_clipping(&input, &setup.transform, self.config.fill)?;
        let clipped = self.clip_and_fan(&input, snapped, setup, scratch)?;
        let winding = drawn_winding(&input, clipped, scratch.fan.iter().map(|t| &t.setup));
        let front_facing = state.front_face.is_front(winding).ok_or(Discard::Degenerate)?;
        if state.cull.culls(front_facing) {
            return Err(Discard::Culled);
        }
        let rect = self
            .pixel_rect(&scratch.raster, setup.transform)
            .ok_or(Discard::OffScreen)?;
        let (raster, fan) = (&scratch.raster, &scratch.fan);
        let mut covered = 0;
        traverse(
            fan,
            winding,
            rect,
            self.config.subpixel_bits,
            &mut scratch.row,
            |hit| {
                covered += 1;
                visit(&Sample::new(primitive as u32, front_facing, hit, fan, raster));
            },
        );
        Ok(covered)
    }

    /// Clips the input and leaves what is drawn in `scratch`: the snapped polygon and its fan.
    /// Returns whether clipping cut it.
    fn clip_and_fan(
        &self,
        input: &[ClipVertex; 3],
        snapped: Option<SnappedTriangle>,
        setup: &DrawSetup<'_>,
        scratch: &mut Scratch,
    ) -> Result<bool, Discard> {
        match clip_triangle(input, &setup.planes, &mut scratch.polygon, &mut scratch.clip) {
            ClipOutcome::Outside => Err(Discard::ClippedAway),
            // Drawn as it is: snapped and set up once, before clipping.
            ClipOutcome::Inside => {
                let triangle = snapped.ok_or(Discard::Degenerate)?;
                set(&mut scratch.raster, &triangle.vertices);
                set(&mut scratch.fan, &[FanTriangle::whole(triangle.setup)]);
                Ok(false)
            }
            ClipOutcome::Clipped => {
                let (transform, raster) = (&setup.transform, &mut scratch.raster);
                if !transform.project_polygon(&scratch.polygon, input_w(input), raster) {
                    return Err(Discard::Degenerate);
                }
                build_fan(raster, self.config.fill, &mut scratch.fan);
                Ok(true)
            }
        }
    }

    /// The pixels traversal visits: the polygon's bounding box, or the whole viewport.
    fn pixel_rect(&self, raster: &[RasterVertex], transform: ViewportTransform) -> Option<PixelRect> {
        match self.config.traversal {
            Traversal::BoundingBox => PixelRect::bounding(
                raster.iter().map(|v| v.position),
                transform.bits,
                transform.viewport,
            ),
            Traversal::Viewport => Some(PixelRect::of_viewport(transform.viewport)),
        }
    }
}

/// Replaces a scratch buffer's contents.
fn set<T: Copy>(buffer: &mut Vec<T>, items: &[T]) {
    buffer.clear();
    buffer.extend_from_slice(items);
}

/// A covered sample with its depth; [`fragment`](Sample::fragment) adds the barycentrics.
#[derive(Clone, Copy, Debug)]
pub struct Sample<'a> {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// The triangle's index in the draw.
    pub primitive: u32,
    /// Window depth, as [`Fragment::depth`].
    pub depth: f32,
    /// Whether the triangle faces the viewer.
    pub front_facing: bool,
    values: [i64; 3],
    area2: i64,
    corners: [&'a Varyings; 3],
}

impl<'a> Sample<'a> {
    /// The sample at `hit` of triangle `primitive`, its depth interpolated (screen-linear).
    fn new(
        primitive: u32,
        front_facing: bool,
        hit: Hit,
        fan: &[FanTriangle],
        raster: &'a [RasterVertex],
    ) -> Self {
        let t = &fan[hit.triangle];
        // The corners in the setup's clockwise order, the order of the edge values.
        let corners = t.setup.order().map(|k| &raster[t.corners[k]].varyings);
        Self {
            x: hit.x,
            y: hit.y,
            primitive,
            depth: fragment_depth(interpolate_depth(corners, hit.values, t.setup.area2())),
            front_facing,
            values: hit.values,
            area2: t.setup.area2(),
            corners,
        }
    }

    /// The full fragment: the sample plus its perspective-correct and screen-space barycentrics.
    #[must_use]
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

impl Rasterizer for Reference {
    fn profile(&self) -> Profile {
        Profile {
            name: "reference".into(),
            snapping: Snapping::Grid(self.config.subpixel_bits.get()),
            fill: Some(self.config.fill),
            depth: DepthConvention::ScreenLinearZOverW,
            // Snapping moves an edge by up to √2/2 subpixel from where the float input puts it.
            tolerance_subpixels: 1,
            // f64 on exact edge values, rounded to f32 once: within 2^-24, claimed with room.
            precision_bits: 18,
            features: Features {
                guard_band: self.config.clip.reach(),
                ties_to_even: self.config.snap_rounding == SnapRounding::NearestEven,
                snap: match self.config.snap_rounding {
                    SnapRounding::NearestEven | SnapRounding::NearestAwayFromZero => SnapAccuracy::Nearest,
                    SnapRounding::Floor => SnapAccuracy::WithinOneStep,
                },
                ..Features::ALL
            },
            spec: Spec::Refrast,
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = Vec::new();
        self.draw(draw, |f| fragments.push(f))?;
        Ok(fragments)
    }
}
