//! Conservative rasterization (Vulkan's `VK_EXT_conservative_rasterization`): a filled
//! triangle covers whole pixels, those its closed area touches (overestimation, grown by an
//! extra size) or those wholly inside it (underestimation), every sample of each, instead of
//! the samples the fill rule keeps.
//!
//! The reference decides both exactly on the snapped polygon in subpixel integers: a pixel's
//! closed square touches a fan triangle when no edge of either separates them, or, grown by
//! `e` subpixels, when a corner of one lies within `e` of the other (squared distances in
//! `i128`: the polygon grown by a disc of radius `e`, the least "increase at each edge" can
//! mean); it lies inside when its four corners do. Degenerate triangles (zero area once
//! snapped) are culled, as `degenerateTrianglesRasterized = VK_FALSE` allows. The polygon grown
//! is the one clipped to the guard band, so a part beyond the viewport grows into it too.

use crate::bias::FragmentDepth;
use crate::config::Traversal;
use crate::conservative::Conservative;
use crate::draw::{Draw, Fragment};
use crate::error::DrawError;
use crate::fixed::FixedPoint;
use crate::front::FrontSetup;
use crate::lines_points_samples::Offsets;
use crate::project::RasterVertex;
use crate::reference::{DrawStats, Reference, Sample, Scratch};
use crate::setup::Winding;
use crate::traverse::{FanTriangle, Hit, build_fan};

/// A pixel's closed square in subpixels: its left, top, right and bottom.
#[derive(Clone, Copy)]
struct Square {
    x0: i64,
    y0: i64,
    x1: i64,
    y1: i64,
}

impl Square {
    fn corners(self) -> [FixedPoint; 4] {
        [
            (self.x0, self.y0),
            (self.x1, self.y0),
            (self.x0, self.y1),
            (self.x1, self.y1),
        ]
        .map(|(x, y)| FixedPoint { x, y })
    }

    /// The squared distance from `p` to the square (0 inside it).
    fn distance2(self, p: FixedPoint) -> i128 {
        let away = |v: i64, lo: i64, hi: i64| i128::from((lo - v).max(v - hi).max(0));
        let (dx, dy) = (away(p.x, self.x0, self.x1), away(p.y, self.y0, self.y1));
        dx * dx + dy * dy
    }
}

/// Whether `p` lies within `e` of segment `a → b` (`e2` its square), exactly.
fn near_segment(p: FixedPoint, a: FixedPoint, b: FixedPoint, e2: i128) -> bool {
    let d = (i128::from(b.x - a.x), i128::from(b.y - a.y));
    let v = (i128::from(p.x - a.x), i128::from(p.y - a.y));
    let along = d.0 * v.0 + d.1 * v.1;
    let length2 = d.0 * d.0 + d.1 * d.1;
    if along <= 0 || length2 == 0 {
        v.0 * v.0 + v.1 * v.1 <= e2
    } else if along >= length2 {
        let w = (i128::from(p.x - b.x), i128::from(p.y - b.y));
        w.0 * w.0 + w.1 * w.1 <= e2
    } else {
        let cross = d.0 * v.1 - d.1 * v.0;
        cross * cross <= e2 * length2
    }
}

/// Whether fan triangle `t`, grown by a disc of radius `e` subpixels, touches `square`.
fn touches(t: &FanTriangle, square: Square, e: i64) -> bool {
    let v = t.setup.vertices();
    let (lo_x, hi_x) = (v.iter().map(|p| p.x).min(), v.iter().map(|p| p.x).max());
    let (lo_y, hi_y) = (v.iter().map(|p| p.y).min(), v.iter().map(|p| p.y).max());
    let corners = square.corners();
    // No separating axis among the square's sides and the triangle's edges: they intersect.
    let boxes = lo_x <= Some(square.x1)
        && hi_x >= Some(square.x0)
        && lo_y <= Some(square.y1)
        && hi_y >= Some(square.y0);
    if boxes
        && t.setup
            .edges
            .iter()
            .all(|edge| corners.iter().any(|&c| edge.value(c) >= 0))
    {
        return true;
    }
    // Apart, their distance is a corner's of one to the other.
    let e2 = i128::from(e) * i128::from(e);
    e > 0
        && (v.iter().any(|&p| square.distance2(p) <= e2)
            || corners
                .iter()
                .any(|&c| (0..3).any(|k| near_segment(c, v[k], v[(k + 1) % 3], e2))))
}

/// The first fan triangle turning as the polygon does that holds `p` (on its edges too), or
/// else the first that turns so (extrapolating): its index and its edge values at `p`.
fn holder(fan: &[FanTriangle], winding: Winding, p: FixedPoint) -> Option<(usize, [i64; 3])> {
    let agreeing = || {
        fan.iter()
            .enumerate()
            .filter(|(_, t)| t.setup.winding() == winding)
    };
    agreeing()
        .map(|(i, t)| (i, t.setup.edge_values(p)))
        .find(|(_, values)| values.iter().all(|&v| v >= 0))
        .or_else(|| agreeing().next().map(|(i, t)| (i, t.setup.edge_values(p))))
}

impl Reference {
    /// Filled triangles under conservative rasterization: each pixel the snapped polygon
    /// touches (grown by the extra size) or holds, every sample of it the scissor and the mask
    /// keep, with barycentrics and depth at the sample (extrapolated where it lies outside).
    pub(crate) fn draw_conservative(
        &self,
        draw: &Draw,
        mode: Conservative,
        offsets: &Offsets,
        mut emit: impl FnMut(Fragment),
    ) -> Result<DrawStats, DrawError> {
        let config = crate::ReferenceConfig {
            traversal: Traversal::Viewport,
            ..self.config()
        };
        let setup = FrontSetup::new(draw, config);
        let one = config.subpixel_bits.one();
        let extra = match mode {
            Conservative::Overestimate { extra } => (f64::from(extra) * one as f64).round().max(0.0) as i64,
            Conservative::Underestimate => 0,
        };
        let mut scratch = Scratch::default();
        let mut fan = Vec::new();
        let mut stats = DrawStats {
            triangles: setup.triangles.len(),
            ..DrawStats::default()
        };
        for primitive in 0..setup.triangles.len() {
            // Zero area once snapped is a degenerate triangle: culled, as declared.
            let Some(kept) = stats.admit(&setup, primitive, &mut scratch.front) else {
                continue;
            };
            let polygon = kept.polygon(&scratch.front);
            build_fan(&polygon, config.fill, &mut fan);
            let agreeing: Vec<&FanTriangle> =
                fan.iter().filter(|t| t.setup.winding() == kept.winding).collect();
            let depth = FragmentDepth::new(draw.state.viewport_depth, kept.depth_offset);
            let flat = draw.provoking(primitive);
            let (xs, ys) = pixel_range(&polygon, extra, one, draw);
            for y in ys {
                for x in xs.clone() {
                    let square = Square {
                        x0: i64::from(x) * one,
                        y0: i64::from(y) * one,
                        x1: i64::from(x + 1) * one,
                        y1: i64::from(y + 1) * one,
                    };
                    let covered = match mode {
                        Conservative::Overestimate { .. } => {
                            agreeing.iter().any(|t| touches(t, square, extra))
                        }
                        Conservative::Underestimate => square.corners().iter().all(|&c| {
                            agreeing
                                .iter()
                                .any(|t| t.setup.edge_values(c).iter().all(|&v| v >= 0))
                        }),
                    };
                    if !covered || !draw.state.passes_scissor(x, y) {
                        continue;
                    }
                    for (k, &(ox, oy)) in offsets.iter().enumerate() {
                        let p = FixedPoint {
                            x: square.x0 + ox,
                            y: square.y0 + oy,
                        };
                        let Some((triangle, values)) = holder(&fan, kept.winding, p) else {
                            continue;
                        };
                        if !draw.state.passes_sample_mask(k as u8) {
                            continue;
                        }
                        let hit = Hit {
                            x,
                            y,
                            triangle,
                            values,
                        };
                        stats.fragments += 1;
                        emit(Fragment {
                            sample: k as u8,
                            ..Sample::new(
                                depth,
                                primitive as u32,
                                kept.front_facing,
                                flat,
                                hit,
                                &fan,
                                &polygon,
                            )
                            .fragment()
                        });
                    }
                }
            }
        }
        Ok(stats)
    }
}

/// The columns and rows a polygon grown by `e` subpixels may touch, inside the viewport.
fn pixel_range(
    polygon: &[RasterVertex],
    e: i64,
    one: i64,
    draw: &Draw,
) -> (std::ops::Range<u32>, std::ops::Range<u32>) {
    let span = |coords: Vec<i64>, side: u32| {
        let lo = coords.iter().min().copied().unwrap_or(0) - e;
        let hi = coords.iter().max().copied().unwrap_or(0) + e;
        // A pixel whose closed square ends at `lo` still touches it.
        let first = (lo.div_euclid(one) - 1).clamp(0, i64::from(side));
        let last = (hi.div_euclid(one) + 1).clamp(-1, i64::from(side) - 1);
        first as u32..(last + 1).max(first) as u32
    };
    (
        span(
            polygon.iter().map(|v| v.position.x).collect(),
            draw.viewport.width(),
        ),
        span(
            polygon.iter().map(|v| v.position.y).collect(),
            draw.viewport.height(),
        ),
    )
}

#[cfg(test)]
mod tests {
    use crate::{Conservative, Draw, DrawState, Fragment, Reference, Topology, Viewport};

    /// A triangle given in pixels over 8×8 at `samples`, drawn conservatively as `mode`.
    fn draw(v: [(f32, f32); 3], mode: Conservative, samples: u8) -> Vec<Fragment> {
        let clip = |(x, y): (f32, f32)| [x / 4.0 - 1.0, 1.0 - y / 4.0, 0.5, 1.0];
        let mut draw = Draw::of(
            Viewport::new(8, 8).unwrap(),
            v.map(clip).to_vec(),
            Topology::TriangleList,
            vec![0, 1, 2],
        );
        draw.samples = samples;
        draw.state = DrawState {
            conservative: Some(mode),
            ..DrawState::default()
        };
        let mut frags = Vec::new();
        Reference::default().draw(&draw, |f| frags.push(f)).unwrap();
        frags
    }

    fn pixels(frags: &[Fragment]) -> Vec<(u32, u32)> {
        let mut p: Vec<(u32, u32)> = frags.iter().map(|f| (f.x, f.y)).collect();
        p.dedup();
        p.sort_unstable();
        p.dedup();
        p
    }

    /// A triangle whose corners touch pixel (4, 4)'s and pixel (0, 1)'s corners covers those
    /// pixels (edges and corners count), not (0, 2), half a diagonal from its hypotenuse; it
    /// reaches (5, 5), whose corner is √2 px away, grown by 1.5 px and not by 1.
    #[test]
    fn overestimation_covers_what_the_closed_triangle_touches() {
        let over = |extra| Conservative::Overestimate { extra };
        let t = [(1.0, 1.0), (4.0, 1.0), (4.0, 4.0)];
        let touched = pixels(&draw(t, over(0.0), 1));
        assert!(touched.contains(&(4, 4)) && touched.contains(&(3, 3)) && touched.contains(&(0, 0)));
        assert!(touched.contains(&(0, 1)) && !touched.contains(&(5, 5)) && !touched.contains(&(0, 2)));
        assert!(!pixels(&draw(t, over(1.0), 1)).contains(&(5, 5)));
        assert!(pixels(&draw(t, over(1.5), 1)).contains(&(5, 5)));
        // Every sample of a covered pixel, at 4 samples.
        let four = draw(t, over(0.0), 4);
        assert_eq!(four.len(), 4 * touched.len());
    }

    /// Underestimation keeps the pixels wholly inside, their edges on the triangle's included.
    #[test]
    fn underestimation_keeps_the_pixels_inside() {
        let t = [(1.0, 1.0), (7.0, 1.0), (1.0, 7.0)];
        let held = pixels(&draw(t, Conservative::Underestimate, 1));
        assert!(held.contains(&(1, 1)) && held.contains(&(5, 1)) && held.contains(&(3, 3)));
        assert!(!held.contains(&(6, 1)) && !held.contains(&(0, 1)) && !held.contains(&(4, 3)));
    }

    /// A triangle of zero area once snapped draws nothing, as declared.
    #[test]
    fn degenerate_triangles_are_culled() {
        let flat = [(1.0, 1.0), (5.0, 3.0), (3.0, 2.0)];
        assert!(draw(flat, Conservative::Overestimate { extra: 1.0 }, 1).is_empty());
    }
}
