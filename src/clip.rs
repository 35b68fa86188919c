//! Homogeneous clipping (Sutherland–Hodgman) with canonical edge intersections, for triangles
//! and line segments.

use glam::{DVec3, DVec4};

use crate::depth::{DepthClip, DepthRange};
use crate::distance::user_outcode;
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
/// edge is walked, so two triangles sharing an edge get the same point and stay watertight;
/// and the inside end is the one whose coordinates the clip volume bounds, so a far vertex's
/// huge ones never enter the sum but through `t`.
#[must_use]
pub fn intersect(inside: &ClipVertex, outside: &ClipVertex, d_inside: f64, d_outside: f64) -> ClipVertex {
    let t = d_inside / (d_inside - d_outside);
    ClipVertex {
        position: inside.position + (outside.position - inside.position) * t,
        barycentric: inside.barycentric + (outside.barycentric - inside.barycentric) * t,
    }
}

/// Where edge `a → b` crosses a user clip distance whose values at its ends are `da` and `db`,
/// computed from the end nearer the cut (the smaller `|d|`; on a tie, the first in
/// [`canonical_order`]).
///
/// Neither the direction the edge is walked nor the sign of the distance decides that end, so
/// two triangles sharing the edge get the same point (a mesh stays watertight) and so do a
/// distance and its negation (`−a / (−a + b)` is `a / (a − b)` exactly in floating point): a
/// primitive cut by `d` and by `−d` shares the cut (complementarity).
#[must_use]
pub fn intersect_nearer(a: &ClipVertex, b: &ClipVertex, da: f64, db: f64) -> ClipVertex {
    let a_first = match da.abs().total_cmp(&db.abs()) {
        std::cmp::Ordering::Equal => canonical_order(a, b).is_le(),
        order => order.is_lt(),
    };
    if a_first {
        intersect(a, b, da, db)
    } else {
        intersect(b, a, db, da)
    }
}

/// A total order of clip vertices by position, then barycentrics: which end of an edge a user
/// clip distance's cut is computed from where both are as near it ([`intersect_nearer`]).
#[must_use]
pub fn canonical_order(a: &ClipVertex, b: &ClipVertex) -> std::cmp::Ordering {
    let key = |v: &ClipVertex| {
        let (p, b) = (v.position, v.barycentric);
        [p.x, p.y, p.z, p.w, b.x, b.y, b.z]
    };
    let (ka, kb) = (key(a), key(b));
    ka.iter()
        .zip(&kb)
        .map(|(x, y)| x.total_cmp(y))
        .find(|o| o.is_ne())
        .unwrap_or(std::cmp::Ordering::Equal)
}

/// One cut of clipping: a plane of the clip volume, or a user clip distance (its values at the
/// input primitive's corners, [`user_distance`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cut {
    /// A plane of the clip volume, cut from the inside end ([`intersect`]).
    Plane(ClipPlane),
    /// A user clip distance, cut from the end nearer it ([`intersect_nearer`]).
    User(DVec3),
}

impl Cut {
    /// The signed distance of `v`, `≥ 0` kept.
    #[must_use]
    #[inline]
    pub fn distance(self, v: &ClipVertex) -> f64 {
        match self {
            Self::Plane(plane) => plane.distance(v.position),
            Self::User(d) => user_distance(v, d),
        }
    }

    /// Where edge `inside → outside`, whose distances are `d_inside` and `d_outside`, is cut.
    #[must_use]
    #[inline]
    pub fn crossing(
        self,
        inside: &ClipVertex,
        outside: &ClipVertex,
        d_inside: f64,
        d_outside: f64,
    ) -> ClipVertex {
        match self {
            Self::Plane(_) => intersect(inside, outside, d_inside, d_outside),
            Self::User(_) => intersect_nearer(inside, outside, d_inside, d_outside),
        }
    }

    /// The cuts of `planes`, then of the user clip distances `user`, in the order clipping
    /// makes them.
    pub fn all<'a>(planes: &'a [ClipPlane], user: &'a [DVec3]) -> impl Iterator<Item = Cut> + 'a {
        planes
            .iter()
            .map(|&plane| Self::Plane(plane))
            .chain(user.iter().map(|&d| Self::User(d)))
    }
}

/// Clips a convex polygon against one plane, writing the kept part into `out`.
pub fn clip_polygon(polygon: &[ClipVertex], plane: ClipPlane, out: &mut Vec<ClipVertex>) {
    clip_polygon_at(polygon, Cut::Plane(plane), out);
}

/// Clips a convex polygon to where `cut`'s distance is `≥ 0`, writing the kept part into `out`.
pub fn clip_polygon_at(polygon: &[ClipVertex], cut: Cut, out: &mut Vec<ClipVertex>) {
    out.clear();
    for (i, current) in polygon.iter().enumerate() {
        let next = &polygon[(i + 1) % polygon.len()];
        let (dc, dn) = (cut.distance(current), cut.distance(next));
        if dc >= 0.0 {
            out.push(*current);
        }
        match (dc >= 0.0, dn >= 0.0) {
            (true, false) => out.push(cut.crossing(current, next, dc, dn)),
            (false, true) => out.push(cut.crossing(next, current, dn, dc)),
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

/// A user clip distance at clip vertex `v`: its barycentrics' dot product with the distance
/// at the input primitive's corners ([`CornerDistances`](crate::distance::CornerDistances)),
/// so linear in clip space, as Vulkan, OpenGL and D3D11 interpolate clip distances.
#[must_use]
#[inline]
pub fn user_distance(v: &ClipVertex, corners: DVec3) -> f64 {
    v.barycentric.dot(corners)
}

/// Clips triangle `tri` against `planes`, then to where each user clip distance of `user` is
/// `≥ 0`, leaving the polygon in `polygon` when it was cut.
pub fn clip_triangle(
    tri: &[ClipVertex; 3],
    planes: &[ClipPlane],
    user: &[DVec3],
    polygon: &mut Vec<ClipVertex>,
    scratch: &mut Vec<ClipVertex>,
) -> ClipOutcome {
    match classify([0, 1, 2].map(|k| outcode(planes, tri[k].position) | user_outcode(user, k))) {
        ClipOutcome::Clipped => {}
        outcome => return outcome,
    }
    polygon.clear();
    polygon.extend_from_slice(tri);
    for cut in Cut::all(planes, user) {
        clip_polygon_at(polygon, cut, scratch);
        std::mem::swap(polygon, scratch);
        if polygon.len() < 3 {
            return ClipOutcome::Outside;
        }
    }
    ClipOutcome::Clipped
}

/// Clips segment `a → b` against `planes`, then to where each user clip distance of `user` is
/// `≥ 0`, keeping `w > 0`; `None` when nothing is left.
///
/// Each cut is made from the end [`Cut::crossing`] chooses, as for triangles.
#[must_use]
pub fn clip_segment(
    mut a: ClipVertex,
    mut b: ClipVertex,
    planes: &[ClipPlane],
    user: &[DVec3],
) -> Option<(ClipVertex, ClipVertex)> {
    for cut in Cut::all(planes, user) {
        let (da, db) = (cut.distance(&a), cut.distance(&b));
        match (da >= 0.0, db >= 0.0) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => b = cut.crossing(&a, &b, da, db),
            (false, true) => a = cut.crossing(&b, &a, db, da),
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
            clip_triangle(&tri, &planes, &[], &mut polygon, &mut scratch),
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
