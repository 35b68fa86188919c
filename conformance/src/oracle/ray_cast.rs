//! The ray-casting oracle: rasterization and ray casting answer the same question.
//!
//! The ray through a sample centre meets the triangle's plane where the homogeneous
//! barycentrics `b` satisfy `Σ bᵢ (xᵢ − x_ndc·wᵢ) = 0`, `Σ bᵢ (yᵢ − y_ndc·wᵢ) = 0`, `Σ bᵢ = 1`.
//! Those `b` are the true perspective-correct barycentrics; the hit is visible when every
//! `bᵢ ≥ 0`, `w > 0` and it lies inside the near (and far) plane. No clipping is involved, so
//! this works for triangles crossing `w = 0` as it does for any other.

use refrast::{DepthRange, DrawState};

/// Where the ray through a sample meets a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Perspective-correct barycentrics of the hit point.
    pub barycentric: [f64; 3],
    /// Window depth of the hit point, unclamped.
    pub depth: f64,
}

/// Casts the ray through NDC point `(nx, ny)` at the clip-space triangle `tri`.
///
/// `None` when it misses, the hit is behind the eye or outside the near (or enabled far)
/// plane, or the triangle is seen edge-on.
#[must_use]
pub fn ray_cast(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Option<Hit> {
    let u = tri.map(|p| p[0] - nx * p[3]);
    let v = tri.map(|p| p[1] - ny * p[3]);
    // Solve [1 1 1; u; v] b = (1, 0, 0) by Cramer's rule.
    let det = (u[1] * v[2] - u[2] * v[1]) - (u[0] * v[2] - u[2] * v[0]) + (u[0] * v[1] - u[1] * v[0]);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let b = [
        (u[1] * v[2] - u[2] * v[1]) / det,
        (u[2] * v[0] - u[0] * v[2]) / det,
        (u[0] * v[1] - u[1] * v[0]) / det,
    ];
    if b.iter().any(|&bi| bi < 0.0 || !bi.is_finite()) {
        return None;
    }
    let at = |k: usize| b[0] * tri[0][k] + b[1] * tri[1][k] + b[2] * tri[2][k];
    let (z, w) = (at(2), at(3));
    let near = match state.depth_range {
        DepthRange::ZeroToOne => z >= 0.0,
        DepthRange::NegativeOneToOne => z >= -w,
    };
    if w.is_nan() || w <= 0.0 || !near || (state.clip_far && z > w) {
        return None;
    }
    let depth = match state.depth_range {
        DepthRange::ZeroToOne => z / w,
        DepthRange::NegativeOneToOne => (z / w + 1.0) * 0.5,
    };
    Some(Hit {
        barycentric: b,
        depth,
    })
}

/// A clip plane as a signed distance: a point is kept when it is `≥ 0`.
type PlaneDistance<'a> = Box<dyn Fn(&[f64; 4]) -> f64 + 'a>;

/// A vertex of a triangle's visible outline in raster space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutlinePoint {
    /// Raster position, or a raster direction when the point lies at infinity (`w` ≈ 0).
    pub position: [f64; 2],
    /// Whether `position` is a point (true) or a direction (false).
    pub finite: bool,
    /// Bit k set when the point lies on the triangle's edge k (from vertex k to vertex k+1).
    pub edges: u8,
}

/// The visible part of `tri` in raster space: clipped at `w > 0`, the near and (when enabled)
/// far planes, then projected. Each point records which triangle edges it lies on, so an
/// outline segment is known to be part of an input edge or a cut made by a plane.
#[must_use]
pub fn visible_outline(tri: &[[f64; 4]; 3], width: u32, height: u32, state: &DrawState) -> Vec<OutlinePoint> {
    // Vertex k lies on edges k and k−1.
    let mut poly: Vec<([f64; 4], u8)> = (0..3)
        .map(|k| (tri[k], (1 << k) | (1 << ((k + 2) % 3))))
        .collect();
    let near = |p: &[f64; 4]| match state.depth_range {
        DepthRange::ZeroToOne => p[2],
        DepthRange::NegativeOneToOne => p[2] + p[3],
    };
    let mut planes: Vec<PlaneDistance<'_>> = vec![Box::new(|p: &[f64; 4]| p[3]), Box::new(near)];
    if state.clip_far {
        planes.push(Box::new(|p: &[f64; 4]| p[3] - p[2]));
    }
    for plane in &planes {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let ((a, ea), (b, eb)) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (plane(&a), plane(&b));
            if da >= 0.0 {
                out.push((a, ea));
            }
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                // A cut point lies on whatever input edge the cut segment lies on.
                out.push(([0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * t), ea & eb));
            }
        }
        poly = out;
        if poly.is_empty() {
            return Vec::new();
        }
    }
    let (w, h) = (f64::from(width), f64::from(height));
    let scale = poly.iter().map(|(p, _)| p[3].abs()).fold(0.0, f64::max);
    poly.iter()
        .map(|&(p, edges)| {
            let finite = p[3] > 1e-12 * scale;
            let position = if finite {
                [(p[0] / p[3] + 1.0) * 0.5 * w, (1.0 - p[1] / p[3]) * 0.5 * h]
            } else {
                // A point at infinity: keep its direction in raster orientation.
                [p[0] * w, -p[1] * h]
            };
            OutlinePoint {
                position,
                finite,
                edges,
            }
        })
        .collect()
}

/// Distance in pixels from `s` to the outline segments for which `keep(edges)` holds, where
/// `edges` is the set of input edges the segment lies on (0 for a cut by a plane).
#[must_use]
pub fn distance_to_outline(outline: &[OutlinePoint], s: [f64; 2], keep: impl Fn(u8) -> bool) -> f64 {
    let n = outline.len();
    let mut best = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        if !keep(a.edges & b.edges) {
            continue;
        }
        let d = match (a.finite, b.finite) {
            (true, true) => segment_distance(a.position, b.position, s),
            // From a finite point towards infinity: the ray a + t·dir.
            (true, false) => ray_distance(a.position, b.position, s),
            (false, true) => ray_distance(b.position, a.position, s),
            (false, false) => f64::INFINITY,
        };
        best = best.min(d);
    }
    best
}

fn segment_distance(a: [f64; 2], b: [f64; 2], s: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((s[0] - a[0]) * dx + (s[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (s[0] - a[0] - t * dx).hypot(s[1] - a[1] - t * dy)
}

fn ray_distance(a: [f64; 2], dir: [f64; 2], s: [f64; 2]) -> f64 {
    let len2 = dir[0] * dir[0] + dir[1] * dir[1];
    if len2 == 0.0 {
        return (s[0] - a[0]).hypot(s[1] - a[1]);
    }
    let t = (((s[0] - a[0]) * dir[0] + (s[1] - a[1]) * dir[1]) / len2).max(0.0);
    (s[0] - a[0] - t * dir[0]).hypot(s[1] - a[1] - t * dir[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_through_the_centroid_has_equal_barycentrics_when_w_is_equal() {
        let tri = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 1.0, 0.5, 1.0],
        ];
        let hit = ray_cast(&tri, 0.0, 0.0, &DrawState::default()).unwrap();
        for b in hit.barycentric {
            assert!((b - 1.0 / 3.0).abs() < 1e-12);
        }
        assert!((hit.depth - 0.5).abs() < 1e-12);
        assert!(ray_cast(&tri, 0.9, 0.0, &DrawState::default()).is_none());
    }

    #[test]
    fn perspective_barycentrics_favour_the_near_vertex() {
        // Screen midpoint between a vertex at w = 1 and two at w = 3: b = 0.75 for the near one.
        let tri = [[-1.0, 0.0, 0.0, 1.0], [3.0, -3.0, 0.0, 3.0], [3.0, 3.0, 0.0, 3.0]];
        let hit = ray_cast(&tri, 0.0, 0.0, &DrawState::default()).unwrap();
        assert!((hit.barycentric[0] - 0.75).abs() < 1e-12, "{hit:?}");
    }

    #[test]
    fn triangles_behind_the_eye_are_missed() {
        let tri = [
            [0.5, 0.5, 0.5, -1.0],
            [-0.5, 0.5, 0.5, -1.0],
            [0.0, -0.5, 0.5, -1.0],
        ];
        for (nx, ny) in [(0.0, 0.0), (-0.5, -0.2), (0.3, 0.1)] {
            assert!(ray_cast(&tri, nx, ny, &DrawState::default()).is_none());
        }
        assert!(visible_outline(&tri, 8, 8, &DrawState::default()).is_empty());
    }
}
