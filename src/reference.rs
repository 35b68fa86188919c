//! The reference rasterizer: clip, project, snap, set up, traverse, interpolate — nothing clever.

use glam::{DVec3, DVec4};

use crate::clip::{ClipMode, ClipOutcome, ClipVertex, clip_planes, clip_triangle};
use crate::depth::fragment_depth;
use crate::edge::{FillConvention, orient2d};
use crate::error::DrawError;
use crate::fixed::{FixedPoint, SubpixelBits};
use crate::interp::{RasterVertex, interpolate, interpolate_depth, screen_weights};
use crate::rasterizer::{DepthConvention, Draw, Features, Fragment, Profile, Rasterizer};
use crate::setup::{PixelRect, TriangleSetup, Winding};
use crate::traverse::{FanTriangle, traverse};

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
    /// Which edges own the samples on them.
    pub fill: FillConvention,
    /// Guard band (default) or full six-plane clipping for x and y.
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

/// The reference rasterizer: exact coverage on snapped coordinates, the definition of correct.
#[derive(Clone, Debug, Default)]
pub struct Reference {
    config: ReferenceConfig,
}

/// Buffers reused across the triangles of one draw.
#[derive(Default)]
struct Scratch {
    polygon: Vec<ClipVertex>,
    clip: Vec<ClipVertex>,
    raster: Vec<RasterVertex>,
    fan: Vec<FanTriangle>,
    row: Vec<[i64; 3]>,
    points: Vec<FixedPoint>,
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
        let state = &draw.state;
        let planes = clip_planes(self.config.clip, draw.viewport, state.clip_far, state.depth_range);
        let mut scratch = Scratch::default();
        let mut stats = DrawStats::default();
        for (primitive, indices) in draw.triangles.iter().enumerate() {
            stats.triangles += 1;
            let positions = indices.map(|i| draw.positions[i as usize]);
            if positions.iter().flatten().any(|c| !c.is_finite()) {
                stats.non_finite += 1;
                continue;
            }
            let input: [ClipVertex; 3] = [0, 1, 2].map(|k| ClipVertex {
                position: DVec4::from(positions[k].map(f64::from)),
                barycentric: DVec3::AXES[k],
            });
            if self.is_degenerate_before_clipping(draw, &input) {
                stats.degenerate += 1;
                continue;
            }
            let outcome = clip_triangle(&input, &planes, &mut scratch.polygon, &mut scratch.clip);
            let polygon: &[ClipVertex] = match outcome {
                ClipOutcome::Outside => {
                    stats.clipped_away += 1;
                    continue;
                }
                ClipOutcome::Inside => &input,
                ClipOutcome::Clipped => &scratch.polygon,
            };
            if !self.project(draw, polygon, &mut scratch.raster) {
                stats.degenerate += 1;
                continue;
            }
            let raster = &scratch.raster;
            let winding = match outcome {
                ClipOutcome::Clipped => clipped_winding(&input, raster),
                _ => Winding::from_area2(fan_area2(raster)),
            };
            let Some(front_facing) = state.front_face.is_front(winding) else {
                stats.degenerate += 1;
                continue;
            };
            if state.cull.culls(front_facing) {
                stats.culled += 1;
                continue;
            }
            self.build_fan(raster, winding, &mut scratch.fan);
            let bits = self.config.subpixel_bits;
            scratch.points.clear();
            scratch.points.extend(raster.iter().map(|v| v.position));
            let rect = match self.config.traversal {
                Traversal::BoundingBox => PixelRect::bounding(&scratch.points, bits, draw.viewport),
                Traversal::Viewport => Some(PixelRect::of_viewport(draw.viewport)),
            };
            let Some(rect) = rect else {
                stats.off_screen += 1;
                continue;
            };
            stats.traversed += 1;
            let input_w = positions_w(&input);
            let clipped = outcome == ClipOutcome::Clipped;
            let fan = &scratch.fan;
            traverse(fan, rect, bits, &mut scratch.row, |hit| {
                let t = &fan[hit.triangle];
                let corners = t.setup.order.map(|k| &raster[t.corners[k]]);
                stats.fragments += 1;
                visit(&Sample {
                    x: hit.x,
                    y: hit.y,
                    primitive: primitive as u32,
                    depth: fragment_depth(interpolate_depth(corners, hit.values, t.setup.area2)),
                    front_facing,
                    values: hit.values,
                    area2: t.setup.area2,
                    corners,
                    input_w,
                    clipped,
                });
            });
        }
        Ok(stats)
    }

    /// Whether the input triangle, snapped as it is, has zero area.
    ///
    /// Clipping a zero-area triangle makes new vertices on its line that snap off it, which
    /// would leave a sliver able to cover a sample; deciding on the input first draws nothing,
    /// as a zero-area triangle must. Only decidable when every vertex projects into the valid
    /// range (`w > 0`); other triangles are judged by their clipped, snapped polygon.
    fn is_degenerate_before_clipping(&self, draw: &Draw, input: &[ClipVertex; 3]) -> bool {
        let snapped = input.map(|v| {
            let p = v.position;
            if p.w <= 0.0 {
                return None;
            }
            let (x, y) = draw.viewport.to_raster(p.x / p.w, p.y / p.w);
            FixedPoint::snap(x, y, self.config.subpixel_bits)
        });
        match snapped {
            [Some(a), Some(b), Some(c)] => orient2d(a, b, c) == 0,
            _ => false,
        }
    }

    /// Projects and snaps a clipped polygon; `false` when a vertex has no finite raster position.
    fn project(&self, draw: &Draw, polygon: &[ClipVertex], out: &mut Vec<RasterVertex>) -> bool {
        out.clear();
        for v in polygon {
            let p = v.position;
            // After clipping w ≥ 0; a vertex with w = 0 (x = y = 0, any z ≥ 0) is a point at
            // infinity with no raster position: such a triangle projects to a segment at most.
            if p.w <= 0.0 {
                return false;
            }
            let (x, y) = draw.viewport.to_raster(p.x / p.w, p.y / p.w);
            let Some(position) = FixedPoint::snap(x, y, self.config.subpixel_bits) else {
                return false;
            };
            out.push(RasterVertex {
                position,
                depth: draw.state.depth_range.window_depth(p.z, p.w),
                inv_w: 1.0 / p.w,
                barycentric: v.barycentric,
            });
        }
        true
    }

    /// Fans the snapped polygon from its first vertex, marking slivers that snapping turned over.
    fn build_fan(&self, raster: &[RasterVertex], winding: Winding, fan: &mut Vec<FanTriangle>) {
        fan.clear();
        for i in 1..raster.len() - 1 {
            let corners = [0, i, i + 1];
            let v = corners.map(|c| raster[c].position);
            if let Some(setup) = TriangleSetup::new(v, self.config.fill) {
                let agrees = Winding::from_area2(orient2d(v[0], v[1], v[2])) == winding;
                fan.push(FanTriangle {
                    setup,
                    agrees,
                    corners,
                });
            }
        }
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
    values: [i64; 3],
    area2: i64,
    corners: [&'a RasterVertex; 3],
    input_w: Option<[f64; 3]>,
    clipped: bool,
}

impl Sample<'_> {
    /// The full fragment: the sample plus its perspective-correct and screen-space barycentrics.
    #[must_use]
    #[inline]
    pub fn fragment(&self) -> Fragment {
        let weights = screen_weights(self.values, self.area2);
        let b = interpolate(self.corners, weights, self.input_w, self.clipped);
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

/// Twice the signed area of a snapped polygon, summed over its fan (exact).
fn fan_area2(raster: &[RasterVertex]) -> i64 {
    (1..raster.len() - 1)
        .map(|i| orient2d(raster[0].position, raster[i].position, raster[i + 1].position))
        .sum()
}

/// The on-screen winding of a clipped triangle, from its unclipped vertices.
///
/// The visible (`w > 0`) part of a triangle turns on screen as `−sign(det[x y w])` says, for
/// any signs of `w` (Olano–Greer 1997; raster y points down, hence the minus). Taking it from
/// the input rather than the snapped, clipped polygon keeps a sliver that snapping folds across
/// a shared edge from counting as a polygon of its own: its winding cancels instead of drawing
/// twice. When the determinant is too close to zero for its sign to be sure in f64, the
/// snapped polygon's area decides.
fn clipped_winding(input: &[ClipVertex; 3], raster: &[RasterVertex]) -> Winding {
    let [a, b, c] = input.map(|v| v.position);
    let terms = [
        a.x * (b.y * c.w - c.y * b.w),
        -a.y * (b.x * c.w - c.x * b.w),
        a.w * (b.x * c.y - c.x * b.y),
    ];
    let det: f64 = terms.iter().sum();
    let scale = a.x.abs() * (b.y * c.w).abs().max((c.y * b.w).abs())
        + a.y.abs() * (b.x * c.w).abs().max((c.x * b.w).abs())
        + a.w.abs() * (b.x * c.y).abs().max((c.x * b.y).abs());
    // f64 rounding in a 3×3 determinant stays far below 1e-10 of the terms' size.
    if det.abs() > 1e-10 * scale {
        if det < 0.0 {
            Winding::Clockwise
        } else {
            Winding::CounterClockwise
        }
    } else {
        Winding::from_area2(fan_area2(raster))
    }
}

/// The input triangle's `w`s when all are positive: only then does it have a screen-space shape.
fn positions_w(input: &[ClipVertex; 3]) -> Option<[f64; 3]> {
    let w = input.map(|v| v.position.w);
    w.iter().all(|&w| w > 0.0).then_some(w)
}

impl Rasterizer for Reference {
    fn profile(&self) -> Profile {
        Profile {
            name: "reference".into(),
            subpixel_bits: self.config.subpixel_bits.get(),
            fill: self.config.fill,
            depth: DepthConvention::ScreenLinearZOverW,
            // Snapping moves an edge by up to √2/2 subpixel from where the float input puts it.
            tolerance_subpixels: 1,
            features: Features {
                guard_band: self.config.clip == ClipMode::GuardBand,
                ..Features::ALL
            },
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = Vec::new();
        self.draw(draw, |f| fragments.push(f))?;
        Ok(fragments)
    }
}
