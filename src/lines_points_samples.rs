//! The reference beyond triangles at one sample: line lists and strips, point lists, and
//! triangles at several samples per pixel, each decided exactly on snapped coordinates.
//!
//! - **Lines** are clipped in clip space ([`clip_segment`], the same planes as triangles),
//!   their ends projected and snapped, then covered by the configured [`LineRule`]
//!   ([`segment::covers`]). Under the diamond-exit rule every sample of a drawn pixel is
//!   covered (Vulkan: "sample locations may all be treated as being at the pixel center").
//!   A fragment's `t` is the sample's projection on the snapped segment, clamped to `[0, 1]`.
//! - **User clip distances** cut lines as they cut triangles (linearly in clip space, after the
//!   clip volume's planes); a point with a negative one is discarded. A line or point whose
//!   every vertex is negative in one cull distance is not drawn.
//! - **Points** outside the view volume are discarded (Vulkan, Primitive Clipping: a point is
//!   passed "unchanged if it lies within the clip volume"), or, configured pop-free
//!   ([`PointClipping::UserClipPlanesOnly`]), only those outside the near or far plane; a kept
//!   point covers the samples of the one-pixel square centred on it ([`segment::in_point_square`]).
//! - **Triangles at several samples**: sample `k` of pixel `p` lies at `p + oₖ`, so it is covered
//!   exactly when the pixel's centre is covered by the snapped polygon moved by `½ − oₖ`. The
//!   move is a whole number of grid steps (sixteenths of a pixel need at least 4 subpixel bits),
//!   so coverage, ties and interpolation stay exact. Under centroid interpolation a
//!   triangle's fragments are held until all its samples are known (`centroid.rs`).

use glam::{DVec3, DVec4};

use crate::bias::FragmentDepth;
use crate::centroid::{CentroidPixels, Unmoved};
use crate::clip::{ClipMode, ClipPlane, ClipVertex, clip_planes, clip_segment, outcode};
use crate::config::Traversal;
use crate::distance::CornerDistances;
use crate::draw::{Draw, Fragment};
use crate::error::DrawError;
use crate::fixed::FixedPoint;
use crate::front::{Discard, FrontSetup};
use crate::interp::interpolate;
use crate::primitive::{PointClipping, SamplePattern, Topology};
use crate::project::{RasterVertex, ViewportTransform};
use crate::reference::{DrawStats, Reference, Sample, Scratch};
use crate::segment;
use crate::state::{Interpolation, PolygonMode};
use crate::traverse::{PixelRect, build_fan, traverse};

/// A pattern's sample offsets in grid units from the pixel's top-left corner.
pub(crate) type Offsets = Vec<(i64, i64)>;

/// What a line's or point's fragments carry of the primitive that made them: its own, or, in a
/// polygon mode, the triangle's.
pub(crate) struct Owner {
    /// The primitive's index in the draw.
    pub(crate) primitive: u32,
    /// Its facing: always front for a line or a point.
    pub(crate) front_facing: bool,
    /// The vertex whose flat values it carries.
    pub(crate) flat: Option<u32>,
    /// Its depth bias and the viewport's depth range.
    pub(crate) depth: FragmentDepth,
    /// Its user clip distances at its corners.
    pub(crate) user: CornerDistances,
}

impl Owner {
    /// Primitive `i` of `draw`, a line or a point with clip distances `user`: front-facing,
    /// unbiased.
    fn of(draw: &Draw, i: usize, user: CornerDistances) -> Self {
        Self {
            primitive: i as u32,
            front_facing: true,
            flat: draw.provoking(i),
            depth: FragmentDepth::new(draw.state.viewport_depth, 0.0),
            user,
        }
    }
}

impl Reference {
    /// Rasterizes a draw of any topology with samples at `pattern`, handing each covered sample
    /// to `emit` in primitive order; stats count primitives for `triangles`.
    ///
    /// A triangle list at one sample draws exactly as [`Reference::draw`]. `Err` for a draw that
    /// [`Draw::validate`] refuses, a pattern of another count than the draw's, or
    /// sample positions off this reference's grid (fewer than 4 subpixel bits).
    pub fn draw_with_pattern(
        &self,
        draw: &Draw,
        pattern: &SamplePattern,
        mut emit: impl FnMut(Fragment),
    ) -> Result<DrawStats, DrawError> {
        draw.validate()?;
        if pattern.count() != draw.samples {
            return Err(DrawError::Unsupported(format!(
                "a pattern of {} samples for a draw at {}",
                pattern.count(),
                draw.samples
            )));
        }
        let offsets = self.offsets(pattern)?;
        if draw.topology.is_triangles()
            && draw.state.polygon_mode == PolygonMode::Fill
            && let Some(mode) = draw.state.conservative
        {
            return self.draw_conservative(draw, mode, &offsets, emit);
        }
        match draw.topology {
            t if t.is_triangles() && draw.state.polygon_mode != PolygonMode::Fill => {
                Ok(self.draw_polygon_mode(draw, &offsets, emit))
            }
            t if t.is_triangles() && draw.samples == 1 => self.draw_samples(draw, |s| emit(s.fragment())),
            Topology::TriangleList | Topology::TriangleStrip | Topology::TriangleFan => {
                self.draw_triangles_at(draw, &offsets, emit)
            }
            Topology::LineList | Topology::LineStrip => Ok(self.draw_lines(draw, &offsets, emit)),
            Topology::PointList => Ok(self.draw_points(draw, &offsets, emit)),
        }
    }

    /// The pattern's offsets on this reference's grid, or why they are not on it.
    fn offsets(&self, pattern: &SamplePattern) -> Result<Offsets, DrawError> {
        let one = self.config().subpixel_bits.one();
        pattern
            .positions()
            .iter()
            .map(|&[u, v]| {
                let (x, y) = (i64::from(u) * one, i64::from(v) * one);
                if x % 16 == 0 && y % 16 == 0 {
                    Ok((x / 16, y / 16))
                } else {
                    Err(DrawError::Unsupported(format!(
                        "sample position {:?} sixteenths is off the {}-bit subpixel grid (4 bits hold every sixteenth)",
                        [u, v],
                        self.config().subpixel_bits.get()
                    )))
                }
            })
            .collect()
    }

    fn transform(&self, draw: &Draw) -> ViewportTransform {
        ViewportTransform {
            viewport: draw.viewport,
            bits: self.config().subpixel_bits,
            rounding: self.config().snap_rounding,
            depth_range: draw.state.depth_range,
            viewport_depth: draw.state.viewport_depth,
        }
    }

    /// Triangles at several samples: each sample is the centre of the polygon moved by `½ − oₖ`.
    fn draw_triangles_at(
        &self,
        draw: &Draw,
        offsets: &Offsets,
        mut emit: impl FnMut(Fragment),
    ) -> Result<DrawStats, DrawError> {
        // Every sample is tested: a triangle holding no pixel centre may still hold other samples.
        let config = crate::ReferenceConfig {
            traversal: Traversal::Viewport,
            ..self.config()
        };
        let setup = FrontSetup::new(draw, config);
        let (bits, half) = (config.subpixel_bits, config.subpixel_bits.one() / 2);
        let mut scratch = Scratch::default();
        let (mut moved, mut fan) = (Vec::new(), Vec::new());
        // Under centroid interpolation a triangle's fragments wait for its every sample.
        let centroid = draw.state.interpolation == Interpolation::Centroid;
        let mut pixels = CentroidPixels::default();
        let mut stats = DrawStats {
            triangles: setup.triangles.len(),
            ..DrawStats::default()
        };
        for primitive in 0..setup.triangles.len() {
            let Some(kept) = stats.admit(&setup, primitive, &mut scratch.front) else {
                continue;
            };
            let polygon = kept.polygon(&scratch.front);
            let depth = FragmentDepth::new(draw.state.viewport_depth, kept.depth_offset);
            pixels.clear();
            for (k, &(ox, oy)) in offsets.iter().enumerate() {
                // A masked sample makes no fragment, but the centroid counts it covered.
                let masked = !draw.state.passes_sample_mask(k as u8);
                if masked && !centroid {
                    continue;
                }
                let (dx, dy) = (half - ox, half - oy);
                moved.clear();
                moved.extend(polygon.iter().map(|v| RasterVertex {
                    position: FixedPoint {
                        x: v.position.x + dx,
                        y: v.position.y + dy,
                    },
                    ..*v
                }));
                build_fan(&moved, config.fill, &mut fan);
                let Some(rect) = PixelRect::bounding(moved.iter().map(|v| v.position), bits, draw.viewport)
                else {
                    continue;
                };
                let flat = draw.provoking(primitive);
                traverse(&fan, kept.winding, rect, bits, &mut scratch.row, |hit| {
                    if !draw.state.passes_scissor(hit.x, hit.y) {
                        return;
                    }
                    let (x, y) = (hit.x, hit.y);
                    let fragment = (!masked).then(|| Fragment {
                        sample: k as u8,
                        ..Sample::new(
                            depth,
                            primitive as u32,
                            kept.front_facing,
                            flat,
                            hit,
                            &fan,
                            &moved,
                        )
                        .fragment()
                    });
                    match fragment {
                        _ if centroid => pixels.cover(x, y, k as u8, fragment),
                        Some(f) => {
                            stats.fragments += 1;
                            emit(f);
                        }
                        None => {}
                    }
                });
            }
            if centroid {
                let unmoved = Unmoved {
                    polygon: &polygon,
                    fill: config.fill,
                    bits,
                    winding: kept.winding,
                    depth,
                };
                stats.fragments += pixels.emit(&draw.state, draw.samples, &unmoved, &mut emit);
            }
        }
        Ok(stats)
    }

    /// Line lists and strips: clip, project and snap each segment, cover it by the line rule.
    fn draw_lines(&self, draw: &Draw, offsets: &Offsets, mut emit: impl FnMut(Fragment)) -> DrawStats {
        let mut stats = DrawStats {
            triangles: draw.primitive_count(),
            ..DrawStats::default()
        };
        for i in 0..draw.primitive_count() {
            let Some(&[ia, ib]) = draw.primitive(i).as_deref() else {
                continue;
            };
            let (pa, pb) = (draw.positions[ia as usize], draw.positions[ib as usize]);
            let w = DVec3::new(f64::from(pa[3]), f64::from(pb[3]), 1.0);
            let ends = ([pa, pb], [DVec3::X, DVec3::Y]);
            let drawn = CornerDistances::of(&draw.distances, &[ia, ib])
                .map_err(Discard::from)
                .and_then(|user| self.segment(draw, ends, w, &Owner::of(draw, i, user), offsets, &mut emit));
            match drawn {
                Ok(covered) => {
                    stats.traversed += 1;
                    stats.fragments += covered;
                }
                Err(discard) => stats.count(discard),
            }
        }
        stats
    }

    /// One segment from `positions[0]` to `positions[1]`, whose ends have barycentrics
    /// `barycentrics` over corners whose `w`s are `corner_w` (and whose clip distances the
    /// owner carries): clipped, projected and snapped, then covered by the line rule; the number of
    /// samples covered, or why it drew nothing.
    pub(crate) fn segment(
        &self,
        draw: &Draw,
        (positions, barycentrics): ([[f32; 4]; 2], [DVec3; 2]),
        corner_w: DVec3,
        owner: &Owner,
        offsets: &Offsets,
        emit: &mut impl FnMut(Fragment),
    ) -> Result<usize, Discard> {
        let [pa, pb] = positions;
        if pa.iter().chain(&pb).any(|c| !c.is_finite()) {
            return Err(Discard::NonFinite);
        }
        let end = |p: [f32; 4], barycentric| ClipVertex {
            position: DVec4::from(p.map(f64::from)),
            barycentric,
        };
        let planes = clip_planes(self.config().clip, draw.viewport, draw.state.depth_clip());
        let (ca, cb) = clip_segment(
            end(pa, barycentrics[0]),
            end(pb, barycentrics[1]),
            &planes,
            owner.user.planes(),
        )
        .ok_or(Discard::ClippedAway)?;
        // Screen-space barycentrics along the input segment exist when its corners project.
        let input_w = (pa[3] > 0.0 && pb[3] > 0.0 && corner_w.min_element() > 0.0).then_some(corner_w);
        let transform = self.transform(draw);
        let (Some(va), Some(vb)) = (transform.project(&ca, input_w), transform.project(&cb, input_w)) else {
            return Err(Discard::Degenerate);
        };
        Ok(self.cover_segment(draw, owner, [va, vb], offsets, emit))
    }

    /// The samples of one snapped segment under the line rule; the number covered.
    fn cover_segment(
        &self,
        draw: &Draw,
        owner: &Owner,
        [va, vb]: [RasterVertex; 2],
        offsets: &Offsets,
        emit: &mut impl FnMut(Fragment),
    ) -> usize {
        let config = self.config();
        let one = config.subpixel_bits.one();
        let half = one / 2;
        let (a, b) = (va.position, vb.position);
        let (dx, dy) = ((b.x - a.x) as f64, (b.y - a.y) as f64);
        let length2 = dx * dx + dy * dy;
        let (width, height) = (
            i64::from(draw.viewport.width()),
            i64::from(draw.viewport.height()),
        );
        let mut covered = 0;
        let mut fragment_at = |x: i64, y: i64, s: FixedPoint, sample: usize| {
            if !draw.state.passes_sample_mask(sample as u8) {
                return;
            }
            // The sample's projection on the segment, the Vulkan line `t`.
            let t = (((s.x - a.x) as f64 * dx + (s.y - a.y) as f64 * dy) / length2).clamp(0.0, 1.0);
            let b = interpolate([&va.varyings, &vb.varyings], [1.0 - t, t]);
            covered += 1;
            emit(Fragment {
                x: x as u32,
                y: y as u32,
                sample: sample as u8,
                primitive: owner.primitive,
                depth: owner
                    .depth
                    .of(va.varyings.depth + (vb.varyings.depth - va.varyings.depth) * t),
                barycentric: b.perspective.as_vec3().to_array(),
                flat: owner.flat,
                screen_barycentric: b.screen.map(|s| s.as_vec3().to_array()),
                front_facing: owner.front_facing,
            });
        };
        segment::candidates(a, b, one, [width, height], |x, y| {
            if !(0..width).contains(&x)
                || !(0..height).contains(&y)
                || !draw.state.passes_scissor(x as u32, y as u32)
            {
                return;
            }
            let centre = FixedPoint {
                x: x * one + half,
                y: y * one + half,
            };
            if config.line == crate::LineRule::DiamondExit {
                if segment::diamond_exit(a, b, centre, half) {
                    (0..offsets.len()).for_each(|k| fragment_at(x, y, centre, k));
                }
                return;
            }
            for (k, &(ox, oy)) in offsets.iter().enumerate() {
                let s = FixedPoint {
                    x: x * one + ox,
                    y: y * one + oy,
                };
                if segment::covers(config.line, a, b, s, half, config.fill) {
                    fragment_at(x, y, s, k);
                }
            }
        });
        covered
    }

    /// Point lists: keep the points inside the view volume, cover the square around each.
    fn draw_points(&self, draw: &Draw, offsets: &Offsets, mut emit: impl FnMut(Fragment)) -> DrawStats {
        let mut stats = DrawStats {
            triangles: draw.primitive_count(),
            ..DrawStats::default()
        };
        for (i, &index) in draw.indices.iter().enumerate() {
            let p = draw.positions[index as usize];
            let drawn = CornerDistances::of(&draw.distances, &[index])
                .map_err(Discard::from)
                .and_then(|user| {
                    self.point(draw, p, DVec3::X, &Owner::of(draw, i, user), offsets, &mut emit)
                });
            match drawn {
                Ok(covered) => {
                    stats.traversed += 1;
                    stats.fragments += covered;
                }
                Err(discard) => stats.count(discard),
            }
        }
        stats
    }

    /// One point at `p`, its barycentrics `barycentric` over corners whose clip distances the
    /// owner carries: kept inside the view volume (or only the near and far planes, pop-free) and
    /// where no clip distance is negative, then the square around it covered; the number of
    /// samples covered, or why it drew nothing.
    pub(crate) fn point(
        &self,
        draw: &Draw,
        p: [f32; 4],
        barycentric: DVec3,
        owner: &Owner,
        offsets: &Offsets,
        emit: &mut impl FnMut(Fragment),
    ) -> Result<usize, Discard> {
        let config = self.config();
        if p.iter().any(|c| !c.is_finite()) {
            return Err(Discard::NonFinite);
        }
        let mut planes = clip_planes(ClipMode::Full, draw.viewport, draw.state.depth_clip());
        // Kept pop-free, a point is clipped by the near and far planes alone.
        if config.point_clipping == PointClipping::UserClipPlanesOnly {
            planes.retain(|p| matches!(p, ClipPlane::Near(_) | ClipPlane::Far));
        }
        let clip = DVec4::from(p.map(f64::from));
        if outcode(&planes, clip) != 0 || !owner.user.keeps(barycentric) {
            return Err(Discard::ClippedAway);
        }
        let point = self
            .transform(draw)
            .project_point(clip)
            .ok_or(Discard::Degenerate)?;
        let (one, half) = (config.subpixel_bits.one(), config.subpixel_bits.one() / 2);
        let c = point.position;
        let pixels = |lo: i64, hi: i64, side: u32| {
            lo.div_euclid(one).max(0)..=hi.div_euclid(one).min(i64::from(side) - 1)
        };
        let barycentric = barycentric.as_vec3().to_array();
        let mut covered = 0;
        for y in pixels(c.y - half, c.y + half, draw.viewport.height()) {
            for x in pixels(c.x - half, c.x + half, draw.viewport.width()) {
                if !draw.state.passes_scissor(x as u32, y as u32) {
                    continue;
                }
                for (k, &(ox, oy)) in offsets.iter().enumerate() {
                    let s = FixedPoint {
                        x: x * one + ox,
                        y: y * one + oy,
                    };
                    if !segment::in_point_square(c, s, half, config.fill)
                        || !draw.state.passes_sample_mask(k as u8)
                    {
                        continue;
                    }
                    covered += 1;
                    emit(Fragment {
                        x: x as u32,
                        y: y as u32,
                        sample: k as u8,
                        primitive: owner.primitive,
                        depth: owner.depth.of(point.depth),
                        barycentric,
                        flat: owner.flat,
                        screen_barycentric: Some(barycentric),
                        front_facing: owner.front_facing,
                    });
                }
            }
        }
        Ok(covered)
    }
}
