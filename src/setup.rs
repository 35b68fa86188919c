//! Triangle setup: facing (winding, front face, culling), edge functions, the pixels worth visiting.
//!
//! Facing is decided here and nowhere else: an unclipped triangle turns as its snapped signed
//! area says ([`Winding::from_area2`]), a clipped one as the determinant of its clip-space
//! vertices says ([`clipped_winding`]); [`FrontFace::is_front`] and [`CullMode::culls`] do the rest.

use glam::DVec4;

use crate::clip::ClipVertex;
use crate::edge::{EdgeFunction, FillConvention, orient2d};
use crate::fixed::FixedPoint;
use crate::project::{ProjectedPoint, RasterVertex, ViewportTransform};

/// Which way a triangle turns as seen on screen: the sign of its snapped [`orient2d`], or of
/// `det[x y w]` when it is clipped ([`clipped_winding`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Winding {
    /// Clockwise on screen (positive `orient2d` with y down).
    Clockwise,
    /// Counter-clockwise on screen.
    CounterClockwise,
    /// Zero area after snapping: covers nothing and counts as back-facing (Vulkan, D3D11).
    Degenerate,
}

impl Winding {
    /// The winding of a triangle with doubled signed area `area2`: the one place where "zero
    /// area" is decided.
    #[must_use]
    pub fn from_area2(area2: i64) -> Self {
        match area2.signum() {
            1 => Self::Clockwise,
            -1 => Self::CounterClockwise,
            _ => Self::Degenerate,
        }
    }
}

/// Which on-screen winding is front-facing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum FrontFace {
    /// Counter-clockwise as seen on screen (Vulkan's and OpenGL's default).
    #[default]
    CounterClockwise,
    /// Clockwise as seen on screen (D3D's default).
    Clockwise,
}

impl FrontFace {
    /// Whether a triangle of this winding faces the viewer; `None` for zero area, which
    /// draws nothing (it counts as back-facing in Vulkan and D3D).
    #[must_use]
    pub fn is_front(self, winding: Winding) -> Option<bool> {
        match (winding, self) {
            (Winding::Degenerate, _) => None,
            (w, Self::Clockwise) => Some(w == Winding::Clockwise),
            (w, Self::CounterClockwise) => Some(w == Winding::CounterClockwise),
        }
    }
}

/// Which facing a draw discards.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum CullMode {
    /// Draw both facings.
    #[default]
    None,
    /// Discard front-facing triangles.
    Front,
    /// Discard back-facing triangles (zero-area ones are back-facing and never drawn anyway).
    Back,
    /// Discard every triangle, front- and back-facing (Vulkan's `FRONT_AND_BACK`, OpenGL's
    /// `CullFace(FRONT_AND_BACK)`); lines and points are never culled. Declared apart
    /// ([`StateSupport::cull_both`](crate::StateSupport::cull_both)): it came after the others.
    FrontAndBack,
}

impl CullMode {
    /// Whether a triangle of the given facing is discarded.
    #[must_use]
    pub fn culls(self, front_facing: bool) -> bool {
        match self {
            Self::None => false,
            Self::Front => front_facing,
            Self::Back => !front_facing,
            Self::FrontAndBack => true,
        }
    }
}

/// The winding a triangle is drawn with, given the setups of the fan it is drawn as: the one
/// facing rule. Unclipped, the fan is the triangle itself, turning as its snapped area says;
/// clipped, [`clipped_winding`] decides.
pub fn drawn_winding<'a>(
    input: &[ClipVertex; 3],
    clipped: bool,
    fan: impl Iterator<Item = &'a TriangleSetup>,
) -> Winding {
    if clipped {
        clipped_winding(input, || fan.map(TriangleSetup::signed_area2).sum())
    } else {
        fan.map(TriangleSetup::winding)
            .next()
            .unwrap_or(Winding::Degenerate)
    }
}

/// The on-screen winding of a clipped triangle, from its unclipped vertices.
///
/// The visible (`w > 0`) part of a triangle turns on screen as `−sign(det[x y w])` says, for
/// any signs of `w` (Olano–Greer 1997; raster y points down, hence the minus). Taking it from
/// the input rather than the snapped, clipped polygon keeps a sliver that snapping folds across
/// a shared edge from counting as a polygon of its own: its winding cancels instead of drawing
/// twice. When the determinant is too close to zero for its sign to be sure in f64, the snapped
/// polygon's doubled signed area (`snapped_area2`, the sum over its fan) decides.
#[must_use]
pub fn clipped_winding(input: &[ClipVertex; 3], snapped_area2: impl FnOnce() -> i64) -> Winding {
    let [a, b, c]: [DVec4; 3] = input.map(|v| v.position);
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
        Winding::from_area2(snapped_area2())
    }
}

/// An input triangle projected and snapped as it was given, before clipping, with nonzero area.
#[derive(Clone, Copy, Debug)]
pub struct SnappedTriangle {
    /// The projected corners, in input order ([`SnappedTriangle::vertices`] with barycentrics).
    pub points: [ProjectedPoint; 3],
    /// Its setup, which holds its signed area, computed once.
    pub setup: TriangleSetup,
}

/// The zero-area test, made before clipping.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ZeroArea;

/// Projects, snaps and sets up the input triangle as it is, before clipping: `Ok(None)` when a
/// vertex has no raster position, `Err(ZeroArea)` when the snapped triangle has zero area.
///
/// Clipping a zero-area triangle makes new vertices on its line that snap off it, which would
/// leave a sliver able to cover a sample; deciding on the input first draws nothing, as a
/// zero-area triangle must. Only decidable when every vertex projects into the valid range
/// (`w > 0`); other triangles are judged by their clipped, snapped polygon. A triangle that
/// needs no clipping is drawn from this, so its vertices are snapped, and its area computed, once.
pub fn snap_before_clipping(
    input: &[ClipVertex; 3],
    transform: &ViewportTransform,
    fill: FillConvention,
) -> Result<Option<SnappedTriangle>, ZeroArea> {
    let [a, b, c] = input.map(|v| transform.project_point(v.position));
    let (Some(a), Some(b), Some(c)) = (a, b, c) else {
        return Ok(None);
    };
    SnappedTriangle::new([a, b, c], fill).ok_or(ZeroArea).map(Some)
}

impl SnappedTriangle {
    /// The input triangle whose corners project to `points`, set up under `fill`; `None` when
    /// the snapped triangle has zero area. [`snap_before_clipping`] once the corners project.
    #[must_use]
    #[inline]
    pub fn new(points: [ProjectedPoint; 3], fill: FillConvention) -> Option<Self> {
        let setup = TriangleSetup::new(points.map(|p| p.position), fill)?;
        Some(Self { points, setup })
    }

    /// The projected vertices, in input order, each with its own barycentrics: built when
    /// asked, since they are the same unit vectors for every triangle drawn whole.
    #[must_use]
    #[inline]
    pub fn vertices(&self) -> [RasterVertex; 3] {
        [0, 1, 2].map(|k| self.points[k].corner(k))
    }
}

/// A non-degenerate snapped triangle ready for traversal, reordered to turn clockwise.
#[derive(Clone, Copy, Debug)]
pub struct TriangleSetup {
    /// The vertices in clockwise order.
    pub(crate) vertices: [FixedPoint; 3],
    /// `order[k]` is the input position of `vertices[k]` (the input is reordered when counter-clockwise).
    pub(crate) order: [usize; 3],
    /// `edges[k]` is the edge opposite `vertices[k]`, so its value is vertex k's barycentric weight.
    pub(crate) edges: [EdgeFunction; 3],
    /// Twice the (positive) area, the sum of the three edge values at any point.
    pub(crate) area2: i64,
    /// How the input turned on screen, before reordering.
    pub(crate) winding: Winding,
}

impl TriangleSetup {
    /// Sets up `v` under `fill`, computing its signed area once; `None` for a zero-area triangle.
    ///
    /// Inlined, so that a batched front end builds it in place rather than copying it.
    #[must_use]
    #[inline]
    pub fn new(v: [FixedPoint; 3], fill: FillConvention) -> Option<Self> {
        let area2 = orient2d(v[0], v[1], v[2]);
        let winding = Winding::from_area2(area2);
        let order = match winding {
            Winding::Clockwise => [0, 1, 2],
            Winding::CounterClockwise => [0, 2, 1],
            Winding::Degenerate => return None,
        };
        let [a, b, c] = order.map(|i| v[i]);
        Some(Self {
            vertices: [a, b, c],
            order,
            edges: [
                EdgeFunction::new(b, c, fill),
                EdgeFunction::new(c, a, fill),
                EdgeFunction::new(a, b, fill),
            ],
            area2: area2.abs(),
            winding,
        })
    }

    /// The vertices in clockwise order.
    #[must_use]
    pub fn vertices(&self) -> [FixedPoint; 3] {
        self.vertices
    }

    /// `order()[k]` is the input position of `vertices()[k]`.
    #[must_use]
    pub fn order(&self) -> [usize; 3] {
        self.order
    }

    /// Twice the triangle's (positive) area in square subpixel units.
    #[must_use]
    pub fn area2(&self) -> i64 {
        self.area2
    }

    /// How the input vertices turned on screen (never [`Winding::Degenerate`]).
    #[must_use]
    pub fn winding(&self) -> Winding {
        self.winding
    }

    /// Twice the signed area of the input vertices: positive when they turn clockwise.
    #[must_use]
    pub fn signed_area2(&self) -> i64 {
        match self.winding {
            Winding::Clockwise => self.area2,
            _ => -self.area2,
        }
    }

    /// The three edge values at `p` (exact), whether or not `p` is inside.
    #[must_use]
    #[inline]
    pub fn edge_values(&self, p: FixedPoint) -> [i64; 3] {
        self.edges.map(|e| e.value(p))
    }

    /// Whether edge values mean inside under the fill rule: every biased value is non-negative.
    #[must_use]
    #[inline]
    pub fn is_inside(&self, values: [i64; 3]) -> bool {
        // One sign test: the OR of the three is negative exactly when one of them is.
        let [a, b, c] = [0, 1, 2].map(|k| self.edges[k].biased(values[k]));
        a | b | c >= 0
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use super::*;
    use crate::fixed::SubpixelBits;
    use crate::project::tests::transform;

    fn triangle(p: [[f32; 4]; 3]) -> [ClipVertex; 3] {
        [0, 1, 2].map(|k| ClipVertex::corner(p[k], k))
    }

    /// (0, 0), (2, 0), (0, 1) px turn clockwise with y down: twice their area, 2 px² in 1/256-px
    /// units, is positive, and negative for the reversed order, whose vertices come back
    /// clockwise with `order()` saying where each came from.
    #[test]
    fn a_setup_keeps_its_vertices_clockwise_and_its_area_signed() {
        let p = [(0.0, 0.0), (2.0, 0.0), (0.0, 1.0)]
            .map(|(x, y)| FixedPoint::snap(x, y, SubpixelBits::DEFAULT).unwrap());
        let cw = TriangleSetup::new(p, FillConvention::TopLeft).unwrap();
        assert_eq!((cw.signed_area2(), cw.vertices()), (2 * 256 * 256, p));
        let ccw = TriangleSetup::new([p[0], p[2], p[1]], FillConvention::TopLeft).unwrap();
        assert_eq!(ccw.signed_area2(), -2 * 256 * 256);
        let input = [p[0], p[2], p[1]];
        assert_eq!(ccw.order().map(|k| input[k]), ccw.vertices());
        assert_eq!(
            orient2d(ccw.vertices()[0], ccw.vertices()[1], ccw.vertices()[2]),
            2 * 256 * 256
        );
    }

    #[test]
    fn zero_area_is_decided_before_clipping_when_every_vertex_projects() {
        let fill = FillConvention::TopLeft;
        // Collinear, reaching far outside the viewport: clipping would cut it into a sliver.
        let line = triangle([[-3.0, -3.0, 0.5, 1.0], [0.0, 0.0, 0.5, 1.0], [3.0, 3.0, 0.5, 1.0]]);
        assert_eq!(
            snap_before_clipping(&line, &transform(), fill).err(),
            Some(ZeroArea)
        );
        // A vertex behind the eye has no raster position: decided after clipping instead.
        let behind = triangle([
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, -1.0],
        ]);
        assert!(matches!(
            snap_before_clipping(&behind, &transform(), fill),
            Ok(None)
        ));
        // Left, right, top in NDC: counter-clockwise on screen, its area computed once.
        let ccw = triangle([
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, 1.0],
        ]);
        let snapped = snap_before_clipping(&ccw, &transform(), fill).unwrap().unwrap();
        assert_eq!(snapped.setup.winding(), Winding::CounterClockwise);
        assert!(snapped.setup.signed_area2() < 0);
    }

    #[test]
    fn a_clipped_triangle_turns_as_its_homogeneous_determinant_says() {
        let asked = Cell::new(false);
        let fallback = || {
            asked.set(true);
            0
        };
        let ccw = triangle([
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, 1.0],
        ]);
        assert_eq!(clipped_winding(&ccw, fallback), Winding::CounterClockwise);
        // The top vertex behind the eye: the visible part is the wedge below a → b, clockwise.
        let behind = triangle([
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, -0.5, 0.5, -1.0],
        ]);
        assert_eq!(clipped_winding(&behind, fallback), Winding::Clockwise);
        assert!(!asked.get(), "a sure determinant needs no snapped polygon");
        // Seen edge-on (every vertex on the plane x = 0 through the eye): the polygon decides.
        let edge_on = triangle([[0.0, -0.5, 0.5, 1.0], [0.0, 0.5, 0.5, 1.0], [0.0, 0.0, 0.5, 2.0]]);
        assert_eq!(clipped_winding(&edge_on, fallback), Winding::Degenerate);
        assert!(asked.get());
    }

    /// Found by mutation testing (the threshold's scale was unjudged): vertex c = 2a, so the
    /// eye lies in the triangle's plane and det[x y w] is exactly 0, but f64 evaluates it to
    /// 3.6e-15 (1e-16 of the terms' size). That noise must not decide the winding; the
    /// snapped polygon does. A scale of the wrong sign or size would trust it.
    #[test]
    fn rounding_noise_in_the_determinant_defers_to_the_polygon() {
        let (a, b) = (
            [0.909_557_8, 1.732_340_1, -1.624_561_7],
            [-2.829_915, 2.014_590_7, -0.268_931_72],
        );
        let edge_on = triangle([
            [a[0], a[1], 0.5, a[2]],
            [b[0], b[1], 0.5, b[2]],
            [2.0 * a[0], 2.0 * a[1], 0.5, 2.0 * a[2]],
        ]);
        assert_eq!(clipped_winding(&edge_on, || 0), Winding::Degenerate);
    }

    /// The threshold sits at 1e-10 of the determinant's terms, from either side: at 2e-10 the
    /// determinant's sign decides (counter-clockwise) against a snapped polygon that winds the
    /// other way, at 0.5e-10 the polygon does. The vertices are chosen so that any change to
    /// how the terms' size is summed moves the threshold by more than those factors
    /// (cargo-mutants' 12 survivors of the scale, docs/mutants.md).
    #[test]
    fn the_determinant_decides_above_its_threshold_and_the_polygon_below() {
        let vertex = |x: f64, y: f64, w: f64| ClipVertex {
            position: DVec4::new(x, y, 0.5, w),
            barycentric: glam::DVec3::ZERO,
        };
        let near_edge_on = |cy: f64| {
            [
                vertex(-2.704, -2.796, -1.556),
                vertex(-0.51, -0.076, 0.093),
                vertex(0.246_478, cy, -0.033_021),
            ]
        };
        let clockwise_polygon = || 5;
        // det = 2.000003e-10 and 5.000003e-11 of the terms' size (f64, as computed there).
        let above = near_edge_on(0.050_656_827_924_317_97);
        let below = near_edge_on(0.050_656_827_907_520_01);
        assert_eq!(
            clipped_winding(&above, clockwise_polygon),
            Winding::CounterClockwise
        );
        assert_eq!(clipped_winding(&below, clockwise_polygon), Winding::Clockwise);
    }
}
