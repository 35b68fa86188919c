//! A triangle's visible outline in raster space, and distances to it.
//!
//! The outline is what the tolerance band is measured from (boundary edges and cuts made by
//! clip planes) and what pictures draw. It is clipped at `w > 0` and the near (and far) plane,
//! never at the viewport, and every point knows which input edges it lies on.

use refrast::DrawState;

use super::raster::{near_distance, project};

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
    let near = |p: &[f64; 4]| near_distance(state.depth_range, p[2], p[3]);
    let mut planes: Vec<PlaneDistance<'_>> = vec![Box::new(|p: &[f64; 4]| p[3])];
    if state.clip_near {
        planes.push(Box::new(near));
    }
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
                project(width, height, p)
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

/// The stretches of row `sy` (x intervals, ends included) holding every point within `r` of
/// an outline segment `a → b` for which `keep(a, b)` holds, as [`distance_to_outline`]
/// measures it: each segment's part inside the band `|y − sy| ≤ r`, widened by `r`, and both
/// by a margin of `2^-30` of the largest coordinate (and of the stretch's ends) for the
/// roundings of either computation.
/// A point outside them all is farther than `r` from every kept segment.
#[must_use]
pub fn row_reach(
    outline: &[OutlinePoint],
    sy: f64,
    r: f64,
    keep: impl Fn(&OutlinePoint, &OutlinePoint) -> bool,
) -> Vec<(f64, f64)> {
    let n = outline.len();
    let mut stretches = Vec::new();
    for i in 0..n {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        if !keep(&a, &b) {
            continue;
        }
        let (from, along, ray) = match (a.finite, b.finite) {
            (true, true) => (
                a.position,
                [b.position[0] - a.position[0], b.position[1] - a.position[1]],
                false,
            ),
            (true, false) => (a.position, b.position, true),
            (false, true) => (b.position, a.position, true),
            (false, false) => continue,
        };
        let size = [from[0], from[1], along[0], along[1], sy, r]
            .iter()
            .fold(1.0f64, |m, c| m.max(c.abs()));
        let margin = size / 1_073_741_824.0;
        let reach = r + margin;
        // The segment's parameters inside the band: all of it when it runs along the row.
        let last = if ray { f64::INFINITY } else { 1.0 };
        let (t0, t1) = if along[1] == 0.0 {
            if (from[1] - sy).abs() > reach {
                continue;
            }
            (0.0, last)
        } else {
            let enter = (sy - reach - from[1]) / along[1];
            let leave = (sy + reach - from[1]) / along[1];
            (enter.min(leave).max(0.0), enter.max(leave).min(last))
        };
        match t0.partial_cmp(&t1) {
            // Nothing of the segment reaches the row.
            Some(std::cmp::Ordering::Greater) => continue,
            // Bad numbers: the whole row, so nothing is skipped.
            None => {
                stretches.push((f64::NEG_INFINITY, f64::INFINITY));
                continue;
            }
            _ => {}
        }
        let x = |t: f64| {
            if t == 0.0 || along[0] == 0.0 {
                from[0]
            } else {
                from[0] + t * along[0]
            }
        };
        let (x0, x1) = (x(t0), x(t1));
        // The ends' own roundings scale with them, far along a ray.
        let wide = reach + margin + x0.abs().max(x1.abs()) / 1_073_741_824.0;
        let (lo, hi) = (x0.min(x1) - wide, x0.max(x1) + wide);
        stretches.push(if lo.is_nan() || hi.is_nan() {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (lo, hi)
        });
    }
    stretches
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
    fn a_triangle_behind_the_eye_has_no_visible_outline() {
        let tri = [
            [0.5, 0.5, 0.5, -1.0],
            [-0.5, 0.5, 0.5, -1.0],
            [0.0, -0.5, 0.5, -1.0],
        ];
        assert!(visible_outline(&tri, 8, 8, &DrawState::default()).is_empty());
    }

    #[test]
    fn a_cut_by_the_near_plane_lies_on_fewer_than_two_input_edges() {
        // Vertex 2 before the near plane (z < 0): edges 1 (1→2) and 2 (2→0) are cut.
        let tri = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, -0.5, 1.0],
        ];
        let outline = visible_outline(&tri, 8, 8, &DrawState::default());
        assert_eq!(outline.len(), 4);
        assert_eq!(outline.iter().filter(|p| p.is_cut()).count(), 2);
        // The cut runs along y = 0 in NDC, raster row 4: a sample on it is 0 px away.
        assert!(distance_to_outline(&outline, [4.0, 4.0], |a, b| a.is_cut() && b.is_cut()) < 1e-12);
    }

    /// Coordinates on a grid, near it, off it, and huge: segments along rows, through sample
    /// centres, and rays.
    fn coordinate() -> impl proptest::strategy::Strategy<Value = f64> {
        use proptest::prelude::*;
        prop_oneof![
            (-8i32..=24).prop_map(|k| f64::from(k) * 0.5),
            (-8i32..=24).prop_map(|k| f64::from(k) * 0.5 + 1e-9),
            -10.0f64..30.0,
            prop_oneof![Just(1e7), Just(-3e9), Just(1e-12)],
        ]
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]

        /// Every sample of a row within `r` of a kept segment lies in a stretch of its reach.
        #[test]
        fn a_rows_reach_holds_every_sample_within_it(
            points in proptest::collection::vec(
                (coordinate(), coordinate(), proptest::prelude::any::<u8>()), 1..7),
            row in 0u32..16,
            r in proptest::prop_oneof![
                proptest::strategy::Just(0.0),
                proptest::strategy::Just(1.0 / 256.0),
                0.0f64..3.0,
            ],
        ) {
            let outline: Vec<OutlinePoint> = points
                .iter()
                .map(|&(x, y, f)| OutlinePoint { position: [x, y], finite: f % 4 != 0, edges: f & 7 })
                .collect();
            let keep = |a: &OutlinePoint, b: &OutlinePoint| a.edges & b.edges & 1 == 0;
            let sy = f64::from(row) + 0.5;
            let reach = row_reach(&outline, sy, r, keep);
            for x in 0..16 {
                let s = [f64::from(x) + 0.5, sy];
                if distance_to_outline(&outline, s, keep) <= r {
                    proptest::prop_assert!(
                        reach.iter().any(|&(lo, hi)| lo <= s[0] && s[0] <= hi),
                        "sample {s:?} is within {r} but outside {reach:?}"
                    );
                }
            }
        }
    }
}
