//! Where user clip distances keep a primitive, in raster space, written apart from the reference.
//!
//! A clip distance is interpolated perspective-correctly (linearly in clip space), so at a
//! point of a triangle whose screen-space barycentrics are `λ` it is `Σ λₖ dₖ/wₖ / Σ λₖ/wₖ`.
//! With every `w > 0` the denominator is positive inside the triangle, so the distance's sign
//! is that of `Σ λₖ dₖ/wₖ`, an affine function of the raster position: the part kept is the
//! triangle cut by one straight line (the *cut*), whatever the perspective. Along a segment
//! the same holds with `λ = (1 − t, t)`.

use super::raster::project;

/// An affine function `a·x + b·y + c` of the raster position whose sign is a clip distance's
/// over one triangle: positive where the distance is, zero on the cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cut {
    a: f64,
    b: f64,
    c: f64,
}

impl Cut {
    /// The cut of the triangle at clip-space `positions` (every `w > 0`) by the distance whose
    /// values at its corners are `d`, in a `width × height` viewport; `None` when some `w ≤ 0`
    /// or the projected triangle has no area (its inside is then no region to cut).
    #[must_use]
    pub fn of_triangle(width: u32, height: u32, positions: [[f64; 4]; 3], d: [f64; 3]) -> Option<Self> {
        if !positions.iter().all(|p| p[3] > 0.0) {
            return None;
        }
        let p = positions.map(|q| project(width, height, q));
        // The values dₖ/wₖ at the projected corners fix the affine function.
        let e = [0, 1, 2].map(|k| d[k] / positions[k][3]);
        let (x1, y1) = (p[1][0] - p[0][0], p[1][1] - p[0][1]);
        let (x2, y2) = (p[2][0] - p[0][0], p[2][1] - p[0][1]);
        let det = x1 * y2 - x2 * y1;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let (f1, f2) = (e[1] - e[0], e[2] - e[0]);
        let a = (f1 * y2 - f2 * y1) / det;
        let b = (x1 * f2 - x2 * f1) / det;
        let c = e[0] - a * p[0][0] - b * p[0][1];
        Some(Self { a, b, c })
    }

    /// The signed distance in pixels from raster point `(x, y)` to the cut, positive on the
    /// side kept; `±∞` where the distance has one sign all over (it is then the same at every
    /// corner), and 0 on the cut or where it is 0 all over.
    #[must_use]
    pub fn signed_px(&self, x: f64, y: f64) -> f64 {
        let value = self.a * x + self.b * y + self.c;
        let norm = self.a.hypot(self.b);
        if norm == 0.0 {
            return if value == 0.0 {
                0.0
            } else {
                value.signum() * f64::INFINITY
            };
        }
        value / norm
    }
}

/// Along a segment with clip-space ends `ends` (both `w > 0`) whose distance values are `d`:
/// where the distance is 0, as the fraction `t*` of the projected segment from its first end,
/// and whether it is kept before it (`t < t*`); `Err` when the distance has one sign (or is
/// 0) all along: then `Err(kept)` says which.
pub fn segment_cut(ends: [[f64; 4]; 2], d: [f64; 2]) -> Result<(f64, bool), bool> {
    let e = [d[0] / ends[0][3], d[1] / ends[1][3]];
    if (e[0] >= 0.0) == (e[1] >= 0.0) {
        return Err(e[0] >= 0.0);
    }
    // (1 − t)·e₀ + t·e₁ = 0.
    Ok((e[0] / (e[0] - e[1]), e[0] >= 0.0))
}

/// A triangle's edges in raster space, to tell how far a sample lies from its outline.
#[derive(Clone, Copy, Debug)]
pub struct Outline {
    corners: [[f64; 2]; 3],
    /// +1 when the corners turn one way in raster space, −1 the other.
    turn: f64,
}

impl Outline {
    /// The projected triangle at clip-space `positions` (every `w > 0`); `None` otherwise, or
    /// when it has no area.
    #[must_use]
    pub fn of_triangle(width: u32, height: u32, positions: [[f64; 4]; 3]) -> Option<Self> {
        if !positions.iter().all(|p| p[3] > 0.0) {
            return None;
        }
        let corners = positions.map(|q| project(width, height, q));
        let area = cross(corners[0], corners[1], corners[2]);
        (area != 0.0 && area.is_finite()).then(|| Self {
            corners,
            turn: area.signum(),
        })
    }

    /// The signed distance in pixels from `(x, y)` to the outline: positive inside, by the
    /// nearest edge's line (a lower bound of the true distance outside, exact inside).
    #[must_use]
    pub fn signed_px(&self, x: f64, y: f64) -> f64 {
        (0..3)
            .map(|k| {
                let (a, b) = (self.corners[k], self.corners[(k + 1) % 3]);
                let length = (b[0] - a[0]).hypot(b[1] - a[1]);
                self.turn * cross(a, b, [x, y]) / length
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// `(b − a) × (c − a)`.
fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At w = 1 the cut of a distance running from −1 on the left to +1 on the right of an
    /// 8-pixel viewport is its middle column; doubling w on the right moves it right, as
    /// perspective-correct interpolation does (screen-linear would leave it in the middle).
    #[test]
    fn the_cut_follows_perspective() {
        let corners = [
            [-1.0, -1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, 1.0, 0.5, 1.0],
        ];
        let flat = Cut::of_triangle(8, 8, corners, [-1.0, 1.0, -1.0]).expect("a triangle");
        assert!(flat.signed_px(4.0, 7.0).abs() < 1e-12);
        assert!((flat.signed_px(6.0, 7.0) - 2.0).abs() < 1e-12);
        let mut far = corners;
        far[1] = [2.0, -2.0, 1.0, 2.0];
        let leaning = Cut::of_triangle(8, 8, far, [-1.0, 1.0, -1.0]).expect("a triangle");
        assert!(
            leaning.signed_px(4.0, 8.0) < 0.0,
            "the cut moves toward the far corner"
        );
        let uncut = Cut::of_triangle(8, 8, corners, [1.0, 2.0, 3.0]).expect("a triangle");
        assert!(uncut.signed_px(100.0, -100.0) > 0.0);
        let same = Cut::of_triangle(8, 8, corners, [1.0; 3]).expect("a triangle");
        assert_eq!(same.signed_px(0.0, 0.0), f64::INFINITY);
        assert!(Cut::of_triangle(8, 8, [corners[0], corners[0], corners[1]], [1.0, -1.0, 0.0]).is_none());
    }

    #[test]
    fn a_segment_is_cut_where_its_distance_is_zero() {
        let ends = [[0.0, 0.0, 0.5, 1.0], [1.0, 0.0, 0.5, 3.0]];
        assert_eq!(segment_cut(ends, [1.0, -3.0]), Ok((0.5, true)));
        assert_eq!(segment_cut(ends, [1.0, 0.0]), Err(true));
        assert_eq!(segment_cut(ends, [-1.0, -2.0]), Err(false));
    }

    #[test]
    fn the_outline_distance_is_positive_inside() {
        let o = Outline::of_triangle(
            8,
            8,
            [
                [-1.0, -1.0, 0.5, 1.0],
                [1.0, -1.0, 0.5, 1.0],
                [-1.0, 1.0, 0.5, 1.0],
            ],
        )
        .expect("a triangle");
        assert!((o.signed_px(1.0, 6.0) - 1.0).abs() < 1e-12);
        assert!(o.signed_px(7.5, 4.0) < 0.0);
    }
}
