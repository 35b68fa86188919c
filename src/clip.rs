//! Homogeneous clipping (Sutherland–Hodgman) with canonical edge intersections, for triangles
//! and line segments.

use glam::{DVec3, DVec4};

use crate::depth::{DepthClip, DepthRange};
use crate::viewport::Viewport;

/// A polygon vertex in clip space with its barycentric coordinates in the original triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVertex {
    /// Clip-space position `(x, y, z, w)`.
    pub position: DVec4,
    /// Barycentrics in the input triangle; linear in clip space, so perspective-correct.
    pub barycentric: DVec3,
}

impl ClipVertex {
    /// Vertex `k` of an input triangle at clip-space `position`: its barycentrics are unit vector `k`.
    #[must_use]
    pub fn corner(position: [f32; 4], k: usize) -> Self {
        Self {
            position: DVec4::from(position.map(f64::from)),
            barycentric: DVec3::AXES[k],
        }
    }
}

/// Primitive assembly: triangle `indices` of `positions` as clip vertices; `None` when a
/// coordinate is NaN or infinite (such a triangle is discarded) or an index is out of range
/// (a validated [`Draw`](crate::Draw) has none).
#[must_use]
pub fn assemble(positions: &[[f32; 4]], indices: [u32; 3]) -> Option<[ClipVertex; 3]> {
    let [a, b, c] = indices.map(|i| positions.get(i as usize).copied());
    let p = [a?, b?, c?];
    if p.iter().flatten().any(|c| !c.is_finite()) {
        return None;
    }
    Some([0, 1, 2].map(|k| ClipVertex::corner(p[k], k)))
}

/// How x and y are clipped; z is clipped at the near and far planes a draw enables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ClipMode {
    /// Clip x/y only at the guard band and let traversal clamp to the viewport (what GPUs do).
    #[default]
    GuardBand,
    /// Clip against all six planes of the view volume, as the Sutherland–Hodgman lab does.
    Full,
    /// Clip x/y this many pixels beyond each side of the viewport: a guard band of that reach
    /// (at most [`GUARD_BAND_REACH`](crate::GUARD_BAND_REACH); `Reach(0)` clips as `Full` does).
    Reach(u32),
}

impl ClipMode {
    /// How far beyond each side of any viewport a triangle may reach unclipped in x/y, in
    /// pixels: what a profile declares as its guard band.
    #[must_use]
    pub fn reach(self) -> u32 {
        match self {
            Self::GuardBand => crate::GUARD_BAND_REACH,
            Self::Full => 0,
            Self::Reach(px) => px.min(crate::GUARD_BAND_REACH),
        }
    }
}

/// One plane of the clip volume; a point is inside when its distance is `≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClipPlane {
    /// `z ≥ 0` (or `z ≥ −w`): also keeps points behind the eye out.
    Near(DepthRange),
    /// `z ≤ w`.
    Far,
    /// `x ≥ −k·w`.
    Left(f64),
    /// `x ≤ k·w`.
    Right(f64),
    /// `y ≥ −k·w`.
    Bottom(f64),
    /// `y ≤ k·w`.
    Top(f64),
}

impl ClipPlane {
    /// Signed distance of `p` (scaled by the plane's normal length), `≥ 0` inside.
    #[must_use]
    pub fn distance(self, p: DVec4) -> f64 {
        match self {
            Self::Near(range) => range.near_distance(p.z, p.w),
            Self::Far => p.w - p.z,
            Self::Left(k) => p.x + k * p.w,
            Self::Right(k) => k * p.w - p.x,
            Self::Bottom(k) => p.y + k * p.w,
            Self::Top(k) => k * p.w - p.y,
        }
    }
}

/// The planes a draw clips against, in a fixed order: near and far as `depth` enables them,
/// then x and y (which also keep out what lies behind the eye).
#[must_use]
pub fn clip_planes(mode: ClipMode, viewport: Viewport, depth: DepthClip) -> Vec<ClipPlane> {
    let (kx, ky) = match mode {
        ClipMode::GuardBand => viewport.guard_band_ndc(),
        ClipMode::Full => (1.0, 1.0),
        ClipMode::Reach(_) => viewport.reach_ndc(mode.reach()),
    };
    let mut planes = Vec::with_capacity(6);
    if depth.near {
        planes.push(ClipPlane::Near(depth.range));
    }
    if depth.far {
        planes.push(ClipPlane::Far);
    }
    planes.extend([
        ClipPlane::Left(kx),
        ClipPlane::Right(kx),
        ClipPlane::Bottom(ky),
        ClipPlane::Top(ky),
    ]);
    planes
}

/// Where edge `inside → outside` crosses the plane, computed from the inside end.
///
/// Always starting from the inside vertex makes the result independent of the direction the
/// edge is walked, so two triangles sharing an edge get the same point and stay watertight.
#[must_use]
pub fn intersect(inside: &ClipVertex, outside: &ClipVertex, d_inside: f64, d_outside: f64) -> ClipVertex {
    let t = d_inside / (d_inside - d_outside);
    ClipVertex {
        position: inside.position + (outside.position - inside.position) * t,
        barycentric: inside.barycentric + (outside.barycentric - inside.barycentric) * t,
    }
}

/// Clips a convex polygon against one plane, writing the kept part into `out`.
pub fn clip_polygon(polygon: &[ClipVertex], plane: ClipPlane, out: &mut Vec<ClipVertex>) {
    out.clear();
    for (i, current) in polygon.iter().enumerate() {
        let next = &polygon[(i + 1) % polygon.len()];
        let (dc, dn) = (plane.distance(current.position), plane.distance(next.position));
        if dc >= 0.0 {
            out.push(*current);
        }
        match (dc >= 0.0, dn >= 0.0) {
            (true, false) => out.push(intersect(current, next, dc, dn)),
            (false, true) => out.push(intersect(next, current, dn, dc)),
            _ => {}
        }
    }
}

/// What clipping did to a triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClipOutcome {
    /// Wholly inside every plane: the triangle is drawn as it is.
    Inside,
    /// Wholly outside (or behind the eye): nothing is drawn.
    Outside,
    /// Cut: the polygon left in the output buffer is drawn.
    Clipped,
}

/// The planes of `planes` that `p` lies outside (bit `i` for `planes[i]`), Cohen–Sutherland's
/// outcode: a mesh vertex shared by several triangles can be classified once.
#[must_use]
#[inline]
pub fn outcode(planes: &[ClipPlane], p: DVec4) -> u32 {
    debug_assert!(planes.len() <= 32, "one bit per plane");
    planes.iter().enumerate().fold(0, |code, (i, plane)| {
        if plane.distance(p) >= 0.0 {
            code
        } else {
            code | 1 << i
        }
    })
}

/// What clipping does to a triangle whose corners have outcodes `codes`: nothing is left when
/// one plane has all three outside, the triangle is kept whole when no plane has any.
#[must_use]
#[inline]
pub fn classify(codes: [u32; 3]) -> ClipOutcome {
    if codes[0] & codes[1] & codes[2] != 0 {
        ClipOutcome::Outside
    } else if codes[0] | codes[1] | codes[2] == 0 {
        ClipOutcome::Inside
    } else {
        ClipOutcome::Clipped
    }
}

/// Clips triangle `tri` against `planes`, leaving the polygon in `polygon` when it was cut.
pub fn clip_triangle(
    tri: &[ClipVertex; 3],
    planes: &[ClipPlane],
    polygon: &mut Vec<ClipVertex>,
    scratch: &mut Vec<ClipVertex>,
) -> ClipOutcome {
    match classify(tri.map(|v| outcode(planes, v.position))) {
        ClipOutcome::Clipped => {}
        outcome => return outcome,
    }
    polygon.clear();
    polygon.extend_from_slice(tri);
    for &plane in planes {
        clip_polygon(polygon, plane, scratch);
        std::mem::swap(polygon, scratch);
        if polygon.len() < 3 {
            return ClipOutcome::Outside;
        }
    }
    ClipOutcome::Clipped
}

/// Clips segment `a → b` against `planes`, keeping `w > 0`; `None` when nothing is left.
///
/// Each cut is made from the end inside the plane ([`intersect`]), as for triangles.
#[must_use]
pub fn clip_segment(
    mut a: ClipVertex,
    mut b: ClipVertex,
    planes: &[ClipPlane],
) -> Option<(ClipVertex, ClipVertex)> {
    for &plane in planes {
        let (da, db) = (plane.distance(a.position), plane.distance(b.position));
        match (da >= 0.0, db >= 0.0) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => b = intersect(&a, &b, da, db),
            (false, true) => a = intersect(&b, &a, db, da),
        }
    }
    (a.position.w > 0.0 && b.position.w > 0.0 && a.position.is_finite() && b.position.is_finite())
        .then_some((a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Outcodes name the planes a point is outside of, and a triangle is wholly outside only
    /// when one plane has all three corners out: two corners out of different planes are cut.
    #[test]
    fn outcodes_classify_triangles_plane_by_plane() {
        let planes = clip_planes(
            ClipMode::Full,
            Viewport::new(8, 8).expect("8×8 is a valid viewport"),
            DepthClip {
                near: true,
                far: true,
                range: DepthRange::ZeroToOne,
            },
        );
        let code = |x: f64, y: f64, z: f64| outcode(&planes, DVec4::new(x, y, z, 1.0));
        let (inside, left, right, behind) = (
            code(0.0, 0.0, 0.5),
            code(-2.0, 0.0, 0.5),
            code(2.0, 0.0, 0.5),
            code(0.0, 0.0, -1.0),
        );
        assert_eq!(inside, 0);
        assert_eq!(behind, 0b1, "the near plane comes first");
        assert_eq!(left, 0b100);
        assert_eq!(right, 0b1000);
        assert_eq!(code(-2.0, 0.0, 2.0), 0b110, "past far and left");
        assert_eq!(classify([inside; 3]), ClipOutcome::Inside);
        assert_eq!(classify([left, left, left | behind]), ClipOutcome::Outside);
        assert_eq!(classify([left, right, right]), ClipOutcome::Clipped);
        assert_eq!(classify([inside, behind, behind]), ClipOutcome::Clipped);
        let tri = [[-2.0, 0.0], [2.0, 0.0], [0.0, 0.5]].map(|[x, y]| ClipVertex {
            position: DVec4::new(x, y, 0.5, 1.0),
            barycentric: DVec3::ZERO,
        });
        let (mut polygon, mut scratch) = (Vec::new(), Vec::new());
        assert_eq!(
            clip_triangle(&tri, &planes, &mut polygon, &mut scratch),
            ClipOutcome::Clipped
        );
        assert!(polygon.len() >= 3);
    }

    /// With depth clipping off no depth plane is among the planes; what lies behind the eye
    /// is still outside, by x or y.
    #[test]
    fn depth_clipping_off_leaves_only_x_and_y() {
        let viewport = Viewport::new(8, 8).expect("8×8 is a valid viewport");
        let off = DepthClip {
            near: false,
            far: false,
            range: DepthRange::ZeroToOne,
        };
        let planes = clip_planes(ClipMode::Full, viewport, off);
        assert_eq!(planes.len(), 4);
        assert!(
            !planes
                .iter()
                .any(|p| matches!(p, ClipPlane::Near(_) | ClipPlane::Far))
        );
        let code = |x: f64, z: f64, w: f64| outcode(&planes, DVec4::new(x, 0.0, z, w));
        assert_eq!(code(0.0, -5.0, 1.0), 0, "before the near plane, kept");
        assert_eq!(code(0.0, 5.0, 1.0), 0, "beyond the far plane, kept");
        assert_ne!(code(0.5, 0.5, -1.0), 0, "behind the eye, outside");
    }
}
