//! Raster-space geometry for the oracles and the rules, written apart from the reference.
//!
//! The viewport transform and its inverse, pixel centres, snapping, the near plane and window
//! depth, each once. They restate refrast's conventions (`src/lib.rs`) without calling its code,
//! so that a slip in the reference cannot hide in its own oracle.

use std::ops::Add;

use refrast::{CompareOp, DepthRange, DepthState, DrawState, Fragment};

/// A point in subpixel units.
pub type Point = (i128, i128);

/// NDC to raster space: `x = (x_ndc + 1)/2 · W`, `y = (1 − y_ndc)/2 · H` (y points down).
#[must_use]
pub fn to_raster(width: u32, height: u32, nx: f64, ny: f64) -> [f64; 2] {
    [
        (nx + 1.0) * 0.5 * f64::from(width),
        (1.0 - ny) * 0.5 * f64::from(height),
    ]
}

/// Raster space to NDC, the inverse of [`to_raster`].
#[must_use]
pub fn to_ndc(width: u32, height: u32, x: f64, y: f64) -> [f64; 2] {
    [
        x / f64::from(width) * 2.0 - 1.0,
        1.0 - y / f64::from(height) * 2.0,
    ]
}

/// The NDC displacement of a raster displacement `(dx, dy)` in pixels (y flips).
#[must_use]
pub fn ndc_offset(width: u32, height: u32, dx: f64, dy: f64) -> [f64; 2] {
    [2.0 * dx / f64::from(width), -2.0 * dy / f64::from(height)]
}

/// A clip-space point projected to raster space (divided by its `w`, which must not be 0).
#[must_use]
pub fn project(width: u32, height: u32, p: [f64; 4]) -> [f64; 2] {
    to_raster(width, height, p[0] / p[3], p[1] / p[3])
}

/// The sample of pixel `(x, y)`: its centre, `(x + ½, y + ½)`.
#[must_use]
pub fn sample_centre(x: u32, y: u32) -> [f64; 2] {
    [f64::from(x) + 0.5, f64::from(y) + 0.5]
}

/// NDC of pixel `(x, y)`'s sample.
#[must_use]
pub fn sample_ndc(width: u32, height: u32, x: u32, y: u32) -> [f64; 2] {
    let [sx, sy] = sample_centre(x, y);
    to_ndc(width, height, sx, sy)
}

/// Snaps a clip-space position (`w > 0`) to the grid of `2^-bits` pixel (bits up to 16),
/// rounding half to even; `None` when it does not project to a point [`on_grid`].
#[must_use]
pub fn snap(p: [f32; 4], width: u32, height: u32, bits: u8) -> Option<Point> {
    let [x, y, _, w] = p.map(f64::from);
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let scale = f64::from(1u32 << bits.min(16));
    let [rx, ry] = to_raster(width, height, x / w, y / w).map(|c| c * scale);
    (on_grid(rx) && on_grid(ry)).then(|| (rx.round_ties_even() as i128, ry.round_ties_even() as i128))
}

/// The largest grid coordinate the oracles hold, 2^60 steps: `orient2d` of points within it
/// (differences to 2^61, products to 2^122) cannot overflow i128.
const GRID_LIMIT: f64 = 1_152_921_504_606_846_976.0;

/// Whether raster coordinate `v`, in grid steps, is finite and within `GRID_LIMIT`; beyond
/// it (huge coordinates, tiny w) the oracles fall back to floats or call the case unsure.
#[must_use]
pub fn on_grid(v: f64) -> bool {
    v.is_finite() && v.abs() <= GRID_LIMIT
}

/// The signed distance to the near plane, inside when `≥ 0`: `z`, or `z + w` for the
/// OpenGL `−w ≤ z` volume. Generic, so the f64, error-bounded and exact oracles share it.
#[must_use]
pub fn near_distance<T: Add<Output = T>>(range: DepthRange, z: T, w: T) -> T {
    match range {
        DepthRange::ZeroToOne => z,
        DepthRange::NegativeOneToOne => z + w,
    }
}

/// Window depth from `z_d = z/w` under `state`, unclamped: Vulkan's `z_f = p_z·z_d + o_z` with
/// `o_z = minDepth`, `p_z = maxDepth − minDepth`, or `(maxDepth + minDepth)/2` and
/// `(maxDepth − minDepth)/2` for the OpenGL range (Controlling the Viewport; OpenGL 4.6 §13.8.1).
#[must_use]
pub fn window_depth(state: &DrawState, z_over_w: f64) -> f64 {
    let (n, f) = (
        f64::from(state.viewport_depth.min),
        f64::from(state.viewport_depth.max),
    );
    let (o, p) = match state.depth_range {
        DepthRange::ZeroToOne => (n, f - n),
        DepthRange::NegativeOneToOne => ((f + n) * 0.5, (f - n) * 0.5),
    };
    p * z_over_w + o
}

/// `[z_min, z_max] = [min(n, f), max(n, f)]`, the range depth clamping keeps a fragment's
/// depth in (Vulkan, Depth Clamping and Range Adjustment).
#[must_use]
pub fn depth_bounds(state: &DrawState) -> [f64; 2] {
    let (n, f) = (
        f64::from(state.viewport_depth.min),
        f64::from(state.viewport_depth.max),
    );
    [n.min(f), n.max(f)]
}

/// `depth` clamped to [`depth_bounds`]: what refrast's contract stores.
#[must_use]
pub fn clamp_depth(state: &DrawState, depth: f64) -> f64 {
    let [lo, hi] = depth_bounds(state);
    depth.clamp(lo, hi)
}

/// Whether a point at `z`, `w` lies outside a depth plane `state` clips at: before the near
/// plane when near clipping is on, beyond the far plane when far clipping is.
#[must_use]
pub fn outside_depth_planes(state: &DrawState, z: f64, w: f64) -> bool {
    (state.clip_near && near_distance(state.depth_range, z, w) < 0.0) || (state.clip_far && z > w)
}

/// Whether every vertex lies inside the clip volume of `state` (`w > 0`, near when enabled,
/// far when enabled, and `|x|, |y| ≤ w`), so that no implementation clips the triangle.
#[must_use]
pub fn unclipped(p: &[[f32; 4]; 3], state: &DrawState) -> bool {
    p.iter().all(|&[x, y, z, w]| {
        w > 0.0 && !outside_depth_planes(state, f64::from(z), f64::from(w)) && x.abs() <= w && y.abs() <= w
    })
}

/// Whether a fragment at depth `new` passes `op` against `stored` (Vulkan 1.4, Depth Comparison).
///
/// Written apart from the reference's `CompareOp::passes`, so that a wrong compare op cannot
/// hide behind its own replay.
#[must_use]
pub fn depth_passes(op: CompareOp, new: f32, stored: f32) -> bool {
    match op {
        CompareOp::Never => false,
        CompareOp::Always => true,
        CompareOp::Less => new < stored,
        CompareOp::LessOrEqual => new <= stored,
        CompareOp::Equal => new == stored,
        CompareOp::NotEqual => new != stored,
        CompareOp::Greater => new > stored,
        CompareOp::GreaterOrEqual => new >= stored,
    }
}

/// Fragments replayed through the depth test in primitive order (API order), fragments of one
/// primitive in the order given: the depth and id buffers, row by row. Fragments outside the
/// `width × height` viewport are left out.
#[must_use]
pub fn replay_depth(
    depth: DepthState,
    width: u32,
    height: u32,
    fragments: &[Fragment],
) -> (Vec<f32>, Vec<Option<u32>>) {
    let pixels = width as usize * height as usize;
    let (mut depths, mut ids) = (vec![depth.clear; pixels], vec![None; pixels]);
    let mut ordered: Vec<&Fragment> = fragments.iter().filter(|f| f.x < width && f.y < height).collect();
    ordered.sort_by_key(|f| f.primitive);
    for f in ordered {
        let i = f.y as usize * width as usize + f.x as usize;
        if depth_passes(depth.compare, f.depth, depths[i]) {
            ids[i] = Some(f.primitive);
            if depth.write {
                depths[i] = f.depth;
            }
        }
    }
    (depths, ids)
}

#[cfg(test)]
mod tests {
    use refrast::ViewportDepth;

    use super::*;

    #[test]
    fn the_transform_and_its_inverse_agree_on_sample_centres() {
        for (w, h) in [(16, 16), (7, 13), (64, 32)] {
            for (x, y) in [(0, 0), (3, 5), (w - 1, h - 1)] {
                let [nx, ny] = sample_ndc(w, h, x, y);
                let [rx, ry] = to_raster(w, h, nx, ny);
                let [sx, sy] = sample_centre(x, y);
                // Exact on power-of-two sides; a rounding or two otherwise.
                assert!(
                    (rx - sx).abs() < 1e-12 && (ry - sy).abs() < 1e-12,
                    "{w}×{h} ({x}, {y})"
                );
                if w.is_power_of_two() && h.is_power_of_two() {
                    assert_eq!([rx, ry], [sx, sy]);
                }
            }
        }
        // NDC (−1, 1) is the top-left corner, (1, −1) the bottom-right.
        assert_eq!(to_raster(8, 4, -1.0, 1.0), [0.0, 0.0]);
        assert_eq!(to_raster(8, 4, 1.0, -1.0), [8.0, 4.0]);
    }

    #[test]
    fn snapping_rounds_half_to_even_and_needs_positive_w() {
        // Raster x = 0.5 + 1/512 px lies halfway between 1/256 px steps 128 and 129.
        let nx = ((0.5 + 1.0 / 512.0) / 8.0 * 2.0 - 1.0) as f32;
        assert_eq!(snap([nx, 1.0, 0.0, 1.0], 8, 8, 8), Some((128, 0)));
        assert_eq!(snap([0.0, 0.0, 0.0, 0.0], 8, 8, 8), None);
        assert_eq!(snap([0.0, 0.0, 0.0, -1.0], 8, 8, 8), None);
        // Beyond 2^60 grid steps i128 products could overflow: no grid point.
        assert_eq!(snap([f32::MAX, 0.0, 0.0, 1.0], 8, 8, 8), None);
    }

    #[test]
    fn the_gl_range_moves_the_near_plane_to_minus_w() {
        assert_eq!(near_distance(DepthRange::ZeroToOne, -0.5, 1.0), -0.5);
        assert_eq!(near_distance(DepthRange::NegativeOneToOne, -0.5, 1.0), 0.5);
        let gl = DrawState {
            depth_range: DepthRange::NegativeOneToOne,
            ..DrawState::default()
        };
        assert_eq!(window_depth(&gl, -1.0), 0.0);
        assert_eq!(window_depth(&DrawState::default(), 0.25), 0.25);
    }

    /// The viewport's depth range maps the near plane to minDepth and the far one to maxDepth
    /// under either volume, reversed too; depth clamps to the range between them.
    #[test]
    fn the_viewport_depth_range_maps_and_clamps() {
        let mut state = DrawState {
            viewport_depth: ViewportDepth { min: 0.75, max: 0.25 },
            ..DrawState::default()
        };
        assert_eq!(window_depth(&state, 0.0), 0.75);
        assert_eq!(window_depth(&state, 1.0), 0.25);
        assert_eq!(window_depth(&state, 0.5), 0.5);
        assert_eq!(clamp_depth(&state, 0.9), 0.75);
        assert_eq!(clamp_depth(&state, -1.0), 0.25);
        state.depth_range = DepthRange::NegativeOneToOne;
        assert_eq!(window_depth(&state, -1.0), 0.75);
        assert_eq!(window_depth(&state, 1.0), 0.25);
        assert!(!outside_depth_planes(&state, -0.5, 1.0));
        assert!(outside_depth_planes(&state, -1.5, 1.0));
        state.clip_near = false;
        assert!(!outside_depth_planes(&state, -1.5, 1.0));
    }
}
