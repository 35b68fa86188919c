//! Projection: clip space to snapped raster space, with what each vertex carries to its fragments.
//!
//! One function projects and snaps a vertex ([`ViewportTransform::project`]); the zero-area test
//! before clipping and the projection of clipped polygons both go through it.

use glam::DVec3;

use crate::clip::ClipVertex;
use crate::depth::DepthRange;
use crate::fixed::{FixedPoint, SubpixelBits};
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

/// The viewport transform of a draw: NDC to raster space, snapped to its grid, with window depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ViewportTransform {
    /// The render target.
    pub viewport: Viewport,
    /// The snapping grid.
    pub bits: SubpixelBits,
    /// How z/w maps to window depth.
    pub depth_range: DepthRange,
}

impl ViewportTransform {
    /// Projects and snaps one clip-space vertex of an input triangle whose `w`s are `input_w`
    /// ([`input_w`]); `None` when it has no raster position in range.
    ///
    /// A vertex with `w ≤ 0` (after clipping, `w = 0` with `x = y = 0` is a point at infinity)
    /// has none, and neither has one that lands beyond [`COORD_LIMIT`](crate::COORD_LIMIT).
    #[must_use]
    pub fn project(&self, v: &ClipVertex, input_w: Option<DVec3>) -> Option<RasterVertex> {
        let p = v.position;
        if p.w <= 0.0 {
            return None;
        }
        let (x, y) = self.viewport.to_raster(p.x / p.w, p.y / p.w);
        let position = FixedPoint::snap(x, y, self.bits)?;
        // Screen-space barycentrics of a point with clip barycentrics b are bᵢwᵢ / Σ bⱼwⱼ; at an
        // input vertex they are exactly its unit vector.
        let screen = input_w.map(|w| {
            let scaled = v.barycentric * w;
            scaled / scaled.element_sum()
        });
        Some(RasterVertex {
            position,
            varyings: Varyings {
                depth: self.depth_range.window_depth(p.z, p.w),
                inv_w: 1.0 / p.w,
                barycentric: v.barycentric,
                screen,
            },
        })
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
            depth_range: DepthRange::ZeroToOne,
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
