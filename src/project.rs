//! Projection: clip space to snapped raster space, with what each vertex carries to its fragments.
//!
//! One function projects and snaps a position ([`ViewportTransform::project_point`]); the
//! zero-area test before clipping, the projection of clipped polygons and a fast rasterizer's
//! once-per-vertex projection all go through it.

use glam::{DVec3, DVec4};

use crate::clip::ClipVertex;
use crate::depth::{DepthRange, ViewportDepth};
use crate::fixed::{FixedPoint, SnapRounding, SubpixelBits};
use crate::interp::Varyings;
use crate::viewport::Viewport;

/// A vertex of the polygon being drawn, after projection and snapping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterVertex {
    /// Snapped raster position.
    pub position: FixedPoint,
    /// What interpolation needs of it.
    pub varyings: Varyings,
}

/// A clip-space position projected and snapped: what every vertex at it carries but its
/// barycentrics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedPoint {
    /// Snapped raster position.
    pub position: FixedPoint,
    /// Window depth (linear in screen space).
    pub depth: f64,
    /// `1/w`.
    pub inv_w: f64,
}

impl ProjectedPoint {
    /// The raster vertex at this point with barycentrics `barycentric` and screen-space ones `screen`.
    #[must_use]
    #[inline]
    pub fn vertex(self, barycentric: DVec3, screen: Option<DVec3>) -> RasterVertex {
        RasterVertex {
            position: self.position,
            varyings: Varyings {
                depth: self.depth,
                inv_w: self.inv_w,
                barycentric,
                screen,
            },
        }
    }

    /// The raster vertex of corner `k` of an input triangle whose corners all project: both
    /// its barycentrics are unit vector `k`, as [`ViewportTransform::project`] computes them
    /// (`eₖwₖ / wₖ`, exact for `w > 0`).
    #[must_use]
    #[inline]
    pub fn corner(self, k: usize) -> RasterVertex {
        RasterVertex {
            position: self.position,
            varyings: self.corner_varyings(k),
        }
    }

    /// What [`corner`](Self::corner) interpolates, without the position: for a caller that
    /// sets up interpolation alone.
    #[must_use]
    #[inline]
    pub fn corner_varyings(self, k: usize) -> Varyings {
        self.vertex(DVec3::AXES[k], Some(DVec3::AXES[k])).varyings
    }
}

/// The viewport transform of a draw: NDC to raster space, snapped to its grid, with window depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewportTransform {
    /// The render target.
    pub viewport: Viewport,
    /// The snapping grid.
    pub bits: SubpixelBits,
    /// How a coordinate becomes a grid point.
    pub rounding: SnapRounding,
    /// How z/w maps to normalised depth.
    pub depth_range: DepthRange,
    /// Where normalised depth lands in window depth.
    pub viewport_depth: ViewportDepth,
}

impl ViewportTransform {
    /// Projects and snaps a clip-space position, the part of [`project`](Self::project) that
    /// depends on the position alone; `None` when it has no raster position in range.
    ///
    /// A position with `w ≤ 0` (after clipping, `w = 0` with `x = y = 0` is a point at infinity)
    /// has none, and neither has one that lands beyond [`COORD_LIMIT`](crate::COORD_LIMIT). A
    /// mesh vertex shared by several triangles can be projected once this way.
    #[must_use]
    #[inline]
    pub fn project_point(&self, p: DVec4) -> Option<ProjectedPoint> {
        if p.w <= 0.0 {
            return None;
        }
        let (x, y) = self.viewport.to_raster(p.x / p.w, p.y / p.w);
        Some(ProjectedPoint {
            position: FixedPoint::snap_rounding(x, y, self.bits, self.rounding)?,
            depth: self
                .viewport_depth
                .window(self.depth_range.window_depth(p.z, p.w)),
            inv_w: 1.0 / p.w,
        })
    }

    /// Projects and snaps one clip-space vertex of an input triangle whose `w`s are `input_w`
    /// ([`input_w`]); `None` when it has no raster position in range ([`project_point`](Self::project_point)).
    #[must_use]
    pub fn project(&self, v: &ClipVertex, input_w: Option<DVec3>) -> Option<RasterVertex> {
        let point = self.project_point(v.position)?;
        // Screen-space barycentrics of a point with clip barycentrics b are bᵢwᵢ / Σ bⱼwⱼ; at an
        // input vertex they are exactly its unit vector.
        let screen = input_w.map(|w| {
            let scaled = v.barycentric * w;
            scaled / scaled.element_sum()
        });
        Some(point.vertex(v.barycentric, screen))
    }

    /// Projects and snaps every vertex of `polygon` (cut from an input triangle whose `w`s are
    /// `input_w`) into `out`; `false` when one has no raster position.
    pub fn project_polygon(
        &self,
        polygon: &[ClipVertex],
        input_w: Option<DVec3>,
        out: &mut Vec<RasterVertex>,
    ) -> bool {
        out.clear();
        for v in polygon {
            match self.project(v, input_w) {
                Some(r) => out.push(r),
                None => return false,
            }
        }
        true
    }
}

/// The input triangle's `w`s when all are positive: only then does it have a shape on screen,
/// and its fragments screen-space barycentrics.
#[must_use]
pub fn input_w(input: &[ClipVertex; 3]) -> Option<DVec3> {
    let w = input.map(|v| v.position.w);
    w.iter().all(|&w| w > 0.0).then(|| DVec3::from(w))
}

#[cfg(test)]
pub(crate) mod tests {
    use glam::DVec4;

    use super::*;

    /// An 8×8 viewport, 8 subpixel bits, Vulkan depth: the stages' unit tests share it.
    pub(crate) fn transform() -> ViewportTransform {
        ViewportTransform {
            viewport: Viewport::new(8, 8).expect("8×8 is a valid viewport"),
            bits: SubpixelBits::DEFAULT,
            rounding: SnapRounding::NearestEven,
            depth_range: DepthRange::ZeroToOne,
            viewport_depth: ViewportDepth::FULL,
        }
    }

    #[test]
    fn an_input_vertex_carries_its_unit_vector_exactly() {
        let v = ClipVertex::corner([0.25, -0.5, 0.3, 3.0], 1);
        let r = transform().project(&v, Some(DVec3::new(1.0, 3.0, 0.7))).unwrap();
        assert_eq!(r.varyings.screen, Some(DVec3::Y));
        assert_eq!(r.varyings.barycentric, DVec3::Y);
        assert_eq!(r.varyings.inv_w, 1.0 / 3.0);
    }

    /// A corner projected once as a point is what `project` gives it inside any triangle
    /// whose corners all project: the same bits, down to the screen barycentrics.
    #[test]
    fn a_projected_point_is_the_corner_project_gives() {
        let t = transform();
        let corners = [
            [0.25, -0.5, 0.3, 3.0],
            [-7.0, 2.5, 0.9, 1e-3],
            [1e-30, 3e-7, 0.0, 7.25],
        ];
        let w = DVec3::new(3.0, 1e-3, 7.25);
        for (k, p) in corners.into_iter().enumerate() {
            let v = ClipVertex::corner(p, k);
            let point = t.project_point(v.position).unwrap();
            assert_eq!(point.corner(k), t.project(&v, Some(w)).unwrap(), "corner {k}");
        }
    }

    #[test]
    fn a_vertex_made_by_clipping_carries_its_own_screen_barycentrics() {
        // Halfway in clip space from input vertex 0 (w = 1) to vertex 1 (w = 3): on screen it
        // lies a quarter of the way, bᵢwᵢ normalised = (0.5·1, 0.5·3, 0) / 2.
        let v = ClipVertex {
            position: DVec4::new(0.0, 0.0, 0.5, 2.0),
            barycentric: DVec3::new(0.5, 0.5, 0.0),
        };
        let r = transform().project(&v, Some(DVec3::new(1.0, 3.0, 2.0))).unwrap();
        assert_eq!(r.varyings.screen, Some(DVec3::new(0.25, 0.75, 0.0)));
        // Behind the eye the input has no shape on screen, so no screen barycentrics either.
        let r = transform().project(&v, None).unwrap();
        assert_eq!(r.varyings.screen, None);
    }

    #[test]
    fn no_raster_position_without_positive_w_or_in_range() {
        let t = transform();
        assert!(
            t.project(&ClipVertex::corner([0.0, 0.0, 0.0, 0.0], 0), None)
                .is_none()
        );
        assert!(
            t.project(&ClipVertex::corner([1.0, 1.0, 0.5, -1.0], 0), None)
                .is_none()
        );
        assert!(
            t.project(&ClipVertex::corner([1e9, 0.0, 0.5, 1.0], 0), None)
                .is_none()
        );
    }
}
