//! Seed 003's front end, shared by its scanline z-buffer and its area averaging: each triangle
//! clipped to the view volume, projected to unsnapped pixel coordinates, faced and culled, with
//! the plane equations its depth and barycentrics are read from.
//!
//! The clipping is the reference's Sutherland–Hodgman against all six planes
//! (`refrast::stage::clip_triangle`), so that these labs' verdicts are about what seed 003 adds.

use refrast::stage::{ClipOutcome, ClipVertex, assemble, clip_planes, clip_triangle};
use refrast::{ClipMode, CullMode, Draw, Features, SnapAccuracy, Supported, Winding};

/// What this front end supports, for a lab with or without a depth test of its own: every cull
/// mode, front face, depth state and clip setting; perspective-correct weights only; clipped at
/// the viewport's sides (no guard band); no grid, so no snap ties.
#[must_use]
pub fn features(depth_test: bool) -> Features {
    Features {
        perspective_barycentrics: true,
        screen_barycentrics: false,
        cull_modes: Supported::<CullMode>::ALL,
        front_faces: Supported::ALL,
        depth_test,
        compare_ops: Supported::ALL,
        depth_writes: Supported::ALL,
        far_clipping: Supported::ALL,
        depth_ranges: Supported::ALL,
        guard_band: 0,
        ties_to_even: false,
        snap: SnapAccuracy::Nearest,
        zero_area_before_clipping: false,
        clips_in_3d: true,
        z_rewritten_in_f32: false,
    }
}

/// A screen-space plane `value = a·x + b·y + c`, the seed's `Ax + By + Cz + D = 0` solved for z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// `∂value/∂x`: the step from one pixel to the next along a scanline (`−A/C`).
    pub a: f64,
    /// `∂value/∂y`.
    pub b: f64,
    /// The value at the origin.
    pub c: f64,
}

impl Plane {
    /// The plane through three points `(x, y, value)`; `None` when they lie on one line or its
    /// coefficients overflow.
    #[must_use]
    pub fn through(p: [[f64; 3]; 3]) -> Option<Self> {
        let [[x0, y0, v0], [x1, y1, v1], [x2, y2, v2]] = p;
        let det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let a = ((v1 - v0) * (y2 - y0) - (v2 - v0) * (y1 - y0)) / det;
        let b = ((x1 - x0) * (v2 - v0) - (x2 - x0) * (v1 - v0)) / det;
        let plane = Self {
            a,
            b,
            c: v0 - a * x0 - b * y0,
        };
        // A sliver's tiny determinant can overflow the slopes; such a plane has no values.
        [plane.a, plane.b, plane.c]
            .iter()
            .all(|v| v.is_finite())
            .then_some(plane)
    }

    /// The value at `(x, y)`.
    #[must_use]
    pub fn at(&self, x: f64, y: f64) -> f64 {
        self.a * x + self.b * y + self.c
    }
}

/// One triangle after clipping and projection: a convex polygon in pixels (y down).
#[derive(Clone, Debug)]
pub struct ScreenPolygon {
    /// The input triangle's index.
    pub primitive: u32,
    /// Its corners in pixels, in the input's order around the polygon.
    pub corners: Vec<[f64; 2]>,
    /// Whether it faces front under the draw's front face.
    pub front_facing: bool,
    /// Window depth `z/w`, linear in screen space.
    pub depth: Plane,
    /// `1/w`, linear in screen space (seed 002's `zinv`).
    pub w_inverse: Plane,
    /// Each input vertex's barycentric weight divided by `w`, linear in screen space.
    pub weights_over_w: [Plane; 3],
}

impl ScreenPolygon {
    /// The smallest and largest y of its corners: the seed's `y_min, y_max` per face.
    #[must_use]
    pub fn y_range(&self) -> (f64, f64) {
        self.corners
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c[1]), hi.max(c[1]))
            })
    }

    /// Perspective-correct barycentrics at `(x, y)`: the weights over `w` divided by `1/w`.
    #[must_use]
    pub fn barycentric_at(&self, x: f64, y: f64) -> [f64; 3] {
        let q = self.w_inverse.at(x, y);
        self.weights_over_w.map(|p| p.at(x, y) / q)
    }
}

/// Doubled signed area of a polygon in pixels (y down): positive when clockwise on screen.
#[must_use]
pub fn area2(corners: &[[f64; 2]]) -> f64 {
    (0..corners.len())
        .map(|i| {
            let (p, q) = (corners[i], corners[(i + 1) % corners.len()]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum()
}

/// The draw's triangles as the seed's labs see them: clipped, projected, culled by the draw's
/// cull mode and front face; zero-area and non-finite ones dropped (they draw nothing).
#[must_use]
pub fn polygons(draw: &Draw) -> Vec<ScreenPolygon> {
    let vp = draw.viewport;
    let state = &draw.state;
    let planes = clip_planes(ClipMode::Full, vp, state.depth_clip());
    let (mut polygon, mut scratch) = (Vec::new(), Vec::new());
    let mut out = Vec::new();
    for (t, &indices) in draw.triangles().iter().enumerate() {
        let Some(triangle) = assemble(&draw.positions, indices) else {
            continue;
        };
        let kept: &[ClipVertex] = match clip_triangle(&triangle, &planes, &[], &mut polygon, &mut scratch) {
            ClipOutcome::Inside => &triangle,
            ClipOutcome::Outside => continue,
            ClipOutcome::Clipped => &polygon,
        };
        let projected: Vec<([f64; 2], f64, f64, [f64; 3])> = kept
            .iter()
            .map(|v| {
                let p = v.position;
                let (x, y) = vp.to_raster(p.x / p.w, p.y / p.w);
                let depth = state.depth_range.window_depth(p.z, p.w);
                (
                    [x, y],
                    depth,
                    1.0 / p.w,
                    v.barycentric.to_array().map(|b| b / p.w),
                )
            })
            .collect();
        let corners: Vec<[f64; 2]> = projected.iter().map(|p| p.0).collect();
        let winding = match area2(&corners) {
            a if a > 0.0 => Winding::Clockwise,
            a if a < 0.0 => Winding::CounterClockwise,
            _ => continue,
        };
        let Some(front_facing) = state.front_face.is_front(winding) else {
            continue;
        };
        if state.cull.culls(front_facing) {
            continue;
        }
        // The plane through the corner fan's widest triangle, the steadiest of the choices.
        let widest = (1..corners.len() - 1)
            .max_by(|&i, &j| {
                let area = |k: usize| area2(&[corners[0], corners[k], corners[k + 1]]).abs();
                area(i).total_cmp(&area(j))
            })
            .unwrap_or(1);
        let pick = [0, widest, widest + 1];
        let plane = |value: &dyn Fn(usize) -> f64| {
            Plane::through(pick.map(|k| [corners[k][0], corners[k][1], value(k)]))
        };
        let (Some(depth), Some(w_inverse)) = (plane(&|k| projected[k].1), plane(&|k| projected[k].2)) else {
            continue;
        };
        let weights: Vec<Plane> = (0..3).filter_map(|j| plane(&|k| projected[k].3[j])).collect();
        let Ok(weights_over_w) = <[Plane; 3]>::try_from(weights) else {
            continue;
        };
        out.push(ScreenPolygon {
            primitive: t as u32,
            corners,
            front_facing,
            depth,
            w_inverse,
            weights_over_w,
        });
    }
    out
}
