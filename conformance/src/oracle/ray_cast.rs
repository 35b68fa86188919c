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
/// plane, or the triangle is seen edge-on. Every decision is exact: f64 first, with a forward
/// error bound on each sign; when a sign is within its bound of zero (a sample on an edge, a
/// triangle nearly edge-on), the same solve runs again in exact integers ([`super::exact`]).
#[must_use]
pub fn ray_cast(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Option<Hit> {
    match ray_cast_f64(tri, nx, ny, state) {
        Filtered::Sure(hit) => hit,
        Filtered::Unsure => super::exact::ray_cast_exact(tri, nx, ny, state),
    }
}

enum Filtered {
    Sure(Option<Hit>),
    Unsure,
}

/// A value with a bound on its rounding error.
#[derive(Clone, Copy)]
struct Bounded {
    v: f64,
    err: f64,
}

impl Bounded {
    fn exact(v: f64) -> Self {
        Self { v, err: 0.0 }
    }

    fn sure(self) -> bool {
        self.v.abs() > self.err && self.v.is_finite()
    }
}

// ε = 2^-53 per operation, doubled for safety: bounds that are loose cost an exact recompute,
// never a wrong answer.
const EPS: f64 = 2.0 * f64::EPSILON;

fn sub(a: Bounded, b: Bounded) -> Bounded {
    let v = a.v - b.v;
    Bounded {
        v,
        err: a.err + b.err + EPS * v.abs(),
    }
}

fn add(a: Bounded, b: Bounded) -> Bounded {
    let v = a.v + b.v;
    Bounded {
        v,
        err: a.err + b.err + EPS * v.abs(),
    }
}

fn mul(a: Bounded, b: Bounded) -> Bounded {
    let v = a.v * b.v;
    Bounded {
        v,
        err: a.err * b.v.abs() + b.err * a.v.abs() + a.err * b.err + EPS * v.abs(),
    }
}

fn ray_cast_f64(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Filtered {
    let e = Bounded::exact;
    let u = tri.map(|p| sub(e(p[0]), mul(e(nx), e(p[3]))));
    let v = tri.map(|p| sub(e(p[1]), mul(e(ny), e(p[3]))));
    let n = [
        sub(mul(u[1], v[2]), mul(u[2], v[1])),
        sub(mul(u[2], v[0]), mul(u[0], v[2])),
        sub(mul(u[0], v[1]), mul(u[1], v[0])),
    ];
    let d = add(add(n[0], n[1]), n[2]);
    let weighted = |k: usize| {
        add(
            add(mul(n[0], e(tri[0][k])), mul(n[1], e(tri[1][k]))),
            mul(n[2], e(tri[2][k])),
        )
    };
    let (nz, nw) = (weighted(2), weighted(3));
    let near = match state.depth_range {
        DepthRange::ZeroToOne => nz,
        DepthRange::NegativeOneToOne => add(nz, nw),
    };
    let far = sub(nw, nz);
    let mut signs = vec![d, n[0], n[1], n[2], nw, near];
    if state.clip_far {
        signs.push(far);
    }
    // A value exactly zero may be decisive (a sample on an edge): let the exact path say.
    if !signs.iter().all(|s| s.sure()) {
        return Filtered::Unsure;
    }
    let s = d.v.signum();
    let hit = n.iter().all(|ni| ni.v * s > 0.0)
        && nw.v * s > 0.0
        && near.v * s > 0.0
        && (!state.clip_far || far.v * s > 0.0);
    if !hit {
        return Filtered::Sure(None);
    }
    let (z, w) = (nz.v / d.v, nw.v / d.v);
    let depth = match state.depth_range {
        DepthRange::ZeroToOne => z / w,
        DepthRange::NegativeOneToOne => (z / w + 1.0) * 0.5,
    };
    Filtered::Sure(Some(Hit {
        barycentric: n.map(|ni| ni.v / d.v),
        depth,
    }))
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

impl OutlinePoint {
    /// Whether clipping made this point (an input vertex lies on two input edges, a cut on fewer).
    #[must_use]
    pub fn is_cut(&self) -> bool {
        self.edges.count_ones() < 2
    }
}

/// Distance in pixels from `s` to the outline segments `a → b` for which `keep(a, b)` holds;
/// `a.edges & b.edges` is the set of input edges a segment lies on (0 for a cut by a plane).
#[must_use]
pub fn distance_to_outline(
    outline: &[OutlinePoint],
    s: [f64; 2],
    keep: impl Fn(&OutlinePoint, &OutlinePoint) -> bool,
) -> f64 {
    let n = outline.len();
    let mut best = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        if !keep(&a, &b) {
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

/// Distance from `s` to the segment `a b`, in the points' units.
#[must_use]
pub fn segment_distance(a: [f64; 2], b: [f64; 2], s: [f64; 2]) -> f64 {
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

    fn hits(tri: [[f32; 4]; 3], w: u32, h: u32) -> usize {
        let tri = tri.map(|p| p.map(f64::from));
        let mut n = 0;
        for y in 0..h {
            for x in 0..w {
                let nx = (f64::from(x) + 0.5) / f64::from(w) * 2.0 - 1.0;
                let ny = 1.0 - (f64::from(y) + 0.5) / f64::from(h) * 2.0;
                n += usize::from(ray_cast(&tri, nx, ny, &DrawState::default()).is_some());
            }
        }
        n
    }

    /// Found by `clip.interior.matches-raycast`: x = −y at every vertex puts the eye in the
    /// triangle's plane; f64 Cramer divided by rounding noise and "hit" 23 samples.
    #[test]
    fn a_triangle_seen_edge_on_covers_nothing() {
        let tri = [
            [-57337.19, 57337.19, 2.2714622, -1.9112397],
            [65148.11, -65148.11, 0.0, 2.1716037],
            [0.0, 0.0, 0.0, 0.2],
        ];
        assert_eq!(hits(tri, 32, 16), 0);
    }

    /// Found by `clip.interior.matches-raycast`: nearly edge-on, vertices at ±30000·w and w
    /// crossing 0. The exact solve gives 120 hits; plain f64 gave none.
    #[test]
    fn a_nearly_edge_on_triangle_gets_its_exact_hits() {
        let tri = [
            [-6000.0, 6000.0, 0.0, 0.2],
            [0.0, 0.01119828, 0.0, 0.2],
            [20974.33, -20974.33, 0.0, -0.69914436],
        ];
        assert_eq!(hits(tri, 16, 16), 120);
    }

    /// Found while fixing the above: the hits lie at w ≈ 1.3e-9, close to the horizon but
    /// genuinely visible; a cutoff on small w wrongly dropped all 256.
    #[test]
    fn hits_near_the_horizon_count() {
        let tri = [
            [0.2795305, 6000.0, 0.0, 0.2],
            [-2.0273936, 56659.32, 0.7119076, 1.888644],
            [0.120680064, -4555.2896, 0.0, -0.15184298],
        ];
        assert_eq!(hits(tri, 16, 16), 256);
    }
}
