//! The reference rasterizer: clip, project, snap, set up, traverse, interpolate — nothing clever.

use crate::bias::FragmentDepth;
use crate::config::ReferenceConfig;
use crate::draw::{Draw, Fragment};
use crate::error::DrawError;
use crate::features::{Features, SnapAccuracy, StateSupport};
use crate::fixed::SnapRounding;
use crate::front::{Discard, FrontScratch, FrontSetup, Kept, front_end};
use crate::interp::{Varyings, interpolate, interpolate_depth, screen_weights};
use crate::primitive::{SAMPLE_COUNTS, SamplePattern};
use crate::profile::{DepthConvention, Profile, Snapping, Spec};
use crate::project::RasterVertex;
use crate::rasterizer::Rasterizer;
use crate::traverse::{FanTriangle, Hit, traverse};

/// What happened to the triangles of a draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DrawStats {
    /// Triangles submitted.
    pub triangles: usize,
    /// Discarded for a NaN or infinite coordinate.
    pub non_finite: usize,
    /// Wholly outside the clip volume (behind the eye included) or a user clip distance, or
    /// culled by a cull distance.
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

impl DrawStats {
    /// Triangle `primitive` through [`front_end`], counted: traversed where kept, else by why
    /// it draws nothing. The one front-end loop of every per-triangle drawing path.
    pub(crate) fn admit(
        &mut self,
        setup: &FrontSetup<'_>,
        primitive: usize,
        scratch: &mut FrontScratch,
    ) -> Option<Kept> {
        match front_end(setup, primitive, setup.corners(primitive).each_ref(), scratch) {
            Ok(kept) => {
                self.traversed += 1;
                Some(kept)
            }
            Err(discard) => {
                self.count(discard);
                None
            }
        }
    }

    pub(crate) fn count(&mut self, discard: Discard) {
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

/// Buffers reused across the triangles of one draw.
#[derive(Default)]
pub(crate) struct Scratch {
    pub(crate) front: FrontScratch,
    pub(crate) row: Vec<[i64; 3]>,
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

    /// Rasterizes `draw` of any topology, with Vulkan's standard sample locations, handing each
    /// fragment to `emit` in primitive order.
    pub fn draw(&self, draw: &Draw, mut emit: impl FnMut(Fragment)) -> Result<DrawStats, DrawError> {
        if draw.is_triangles_at_one_sample() {
            return self.draw_samples(draw, |sample| emit(sample.fragment()));
        }
        let pattern = SamplePattern::standard(draw.samples).ok_or_else(|| {
            DrawError::Unsupported(format!(
                "{} samples per pixel: a draw asks for 1, 2, 4, 8 or 16",
                draw.samples
            ))
        })?;
        self.draw_with_pattern(draw, &pattern, emit)
    }

    /// Rasterizes `draw`, handing each covered [`Sample`] to `visit` in primitive order.
    ///
    /// A sample carries its depth; its barycentrics are computed only when asked for, so a
    /// depth test can reject it first. `Err` unless `draw` is filled triangles (a list, strip or
    /// fan) at one sample: in line or point mode a triangle's samples are fragments of its
    /// edges or vertices ([`Reference::draw`]).
    pub fn draw_samples(
        &self,
        draw: &Draw,
        mut visit: impl FnMut(&Sample<'_>),
    ) -> Result<DrawStats, DrawError> {
        draw.validate()?;
        if !draw.is_triangles_at_one_sample() {
            return Err(DrawError::Unsupported(format!(
                "{}: samples are visited for triangles at one sample",
                draw.describe()
            )));
        }
        let setup = FrontSetup::new(draw, self.config);
        let mut scratch = Scratch::default();
        let mut stats = DrawStats {
            triangles: setup.triangles.len(),
            ..DrawStats::default()
        };
        for primitive in 0..setup.triangles.len() {
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
        setup: &FrontSetup<'_>,
        primitive: usize,
        scratch: &mut Scratch,
        visit: &mut impl FnMut(&Sample<'_>),
    ) -> Result<usize, Discard> {
        let kept = front_end(
            setup,
            primitive,
            setup.corners(primitive).each_ref(),
            &mut scratch.front,
        )?;
        // Drawn whole, a triangle is its own fan; clipped, its polygon's fan is in the scratch.
        let whole = kept.whole.map(|t| (t.vertices(), [FanTriangle::whole(t.setup)]));
        let (raster, fan): (&[RasterVertex], &[FanTriangle]) = match &whole {
            Some((vertices, fan)) => (vertices, fan),
            None => (&scratch.front.raster, &scratch.front.fan),
        };
        let mut covered = 0;
        let flat = setup.draw.provoking(primitive);
        traverse(
            fan,
            kept.winding,
            kept.rect,
            self.config.subpixel_bits,
            &mut scratch.row,
            |hit| {
                // The scissor and sample mask tests, on each sample the triangle covers (the
                // one sample is sample 0).
                if !setup.draw.state.passes_scissor(hit.x, hit.y) || !setup.draw.state.passes_sample_mask(0) {
                    return;
                }
                covered += 1;
                visit(&Sample::new(
                    FragmentDepth::new(setup.draw.state.viewport_depth, kept.depth_offset),
                    primitive as u32,
                    kept.front_facing,
                    flat,
                    hit,
                    fan,
                    raster,
                ));
            },
        );
        Ok(covered)
    }
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
    /// The vertex whose flat values it carries, as [`Fragment::flat`].
    pub flat: Option<u32>,
    values: [i64; 3],
    area2: i64,
    corners: [&'a Varyings; 3],
}

impl<'a> Sample<'a> {
    /// The sample at `hit` of triangle `primitive`, its depth interpolated (screen-linear),
    /// biased and clamped as `depth` says.
    pub(crate) fn new(
        depth: FragmentDepth,
        primitive: u32,
        front_facing: bool,
        flat: Option<u32>,
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
            depth: depth.of(interpolate_depth(corners, hit.values, t.setup.area2())),
            front_facing,
            flat,
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
            sample: 0,
            primitive: self.primitive,
            depth: self.depth,
            barycentric: b.perspective.as_vec3().to_array(),
            flat: self.flat,
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
                    SnapRounding::Floor => SnapAccuracy::Floor,
                    SnapRounding::TowardZero => SnapAccuracy::TowardZero,
                },
                ..Features::ALL
            },
            spec: Spec::Refrast,
            // Lines by the configured rule, points, and Vulkan's standard sample locations where
            // the grid holds sixteenths of a pixel (4 subpixel bits or more).
            lines: Some(self.config.line),
            points: true,
            endpoint_snapping: None,
            point_snapping: None,
            multisample: SAMPLE_COUNTS[1..]
                .iter()
                .filter(|_| self.config.subpixel_bits.get() >= 4)
                .filter_map(|&n| SamplePattern::standard(n))
                .collect(),
            point_clipping: self.config.point_clipping,
            state: StateSupport::ALL,
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = Vec::new();
        self.draw(draw, |f| fragments.push(f))?;
        Ok(fragments)
    }
}
