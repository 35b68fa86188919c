//! Polygon modes ([`PolygonMode`]): a triangle drawn as its edges or its vertices, after the
//! front end has clipped, faced and culled it as it would a filled one (Vulkan,
//! `VkPolygonMode`: "the polygon is clipped and possibly culled before these modes are applied").

use glam::DVec3;

use crate::bias::FragmentDepth;
use crate::config::{ReferenceConfig, Traversal};
use crate::distance::CornerDistances;
use crate::draw::{Draw, Fragment};
use crate::front::{FrontScratch, FrontSetup};
use crate::lines_points_samples::{Offsets, Owner};
use crate::reference::{DrawStats, Reference};
use crate::state::PolygonMode;

impl Reference {
    /// Triangles in line or point mode, at the samples `offsets` gives.
    ///
    /// Each triangle goes through the front end as a filled one does (a non-finite corner,
    /// zero area, wholly clipped away, facing and culling decide whether it is drawn; nothing is
    /// left out for holding no sample, since its edges may cover pixels its inside does not).
    /// A kept one then draws its edges `0 → 1`, `1 → 2`, `2 → 0` exactly as a line list of
    /// them would, or its vertices as a point list of them would, each fragment carrying the
    /// triangle's index, facing, flat vertex and depth bias. So what clipping made is not drawn
    /// (refrast's convention, D3D11's; Vulkan and OpenGL core leave edges made by clipping open).
    pub(crate) fn draw_polygon_mode(
        &self,
        draw: &Draw,
        offsets: &Offsets,
        mut emit: impl FnMut(Fragment),
    ) -> DrawStats {
        let config = ReferenceConfig {
            traversal: Traversal::Viewport,
            ..self.config()
        };
        let setup = FrontSetup::new(draw, config);
        let mut scratch = FrontScratch::default();
        let mut stats = DrawStats {
            triangles: setup.triangles.len(),
            ..DrawStats::default()
        };
        for primitive in 0..setup.triangles.len() {
            let Some(kept) = stats.admit(&setup, primitive, &mut scratch) else {
                continue;
            };
            let owner = Owner {
                primitive: primitive as u32,
                front_facing: kept.front_facing,
                flat: draw.provoking(primitive),
                depth: FragmentDepth::new(draw.state.viewport_depth, kept.depth_offset),
                // The front end kept it, so its distances are finite and cull nothing.
                user: CornerDistances::of(&draw.distances, &setup.triangles[primitive]).unwrap_or_default(),
            };
            let corners = setup.triangles[primitive].map(|i| draw.positions[i as usize]);
            for k in 0..3 {
                stats.fragments += match draw.state.polygon_mode {
                    PolygonMode::Point => self
                        .point(draw, corners[k], DVec3::AXES[k], &owner, offsets, &mut emit)
                        .unwrap_or(0),
                    _ => {
                        let next = (k + 1) % 3;
                        let ends = ([corners[k], corners[next]], [DVec3::AXES[k], DVec3::AXES[next]]);
                        let w = DVec3::from(corners.map(|p| f64::from(p[3])));
                        self.segment(draw, ends, w, &owner, offsets, &mut emit)
                            .unwrap_or(0)
                    }
                };
            }
        }
        stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CullMode, DrawState, Rasterizer, Topology, Viewport};

    fn draw(mode: PolygonMode, topology: Topology, positions: Vec<[f32; 4]>, indices: Vec<u32>) -> Draw {
        Draw {
            viewport: Viewport::new(16, 16).unwrap(),
            positions,
            topology,
            indices,
            samples: 1,
            state: DrawState {
                polygon_mode: mode,
                ..DrawState::default()
            },
            distances: crate::Distances::default(),
        }
    }

    /// Pixel-space corners (y down) at w = 1, as clip-space positions on a 16 × 16 viewport.
    fn at(points: &[[f32; 2]]) -> Vec<[f32; 4]> {
        points
            .iter()
            .map(|&[x, y]| [x / 8.0 - 1.0, 1.0 - y / 8.0, 0.5, 1.0])
            .collect()
    }

    fn pixels(frags: &[Fragment]) -> Vec<(u32, u32, u32)> {
        let mut p: Vec<_> = frags.iter().map(|f| (f.primitive, f.x, f.y)).collect();
        p.sort_unstable();
        p
    }

    /// In line mode a triangle draws what a line list of its edges draws, each fragment naming
    /// the triangle; in point mode what a point list of its vertices draws.
    #[test]
    fn a_triangle_draws_its_edges_or_its_vertices() {
        let corners = at(&[[2.5, 2.5], [12.5, 3.5], [6.5, 11.5]]);
        let mut r = Reference::default();
        let as_lines = draw(
            PolygonMode::Fill,
            Topology::LineList,
            corners.clone(),
            vec![0, 1, 1, 2, 2, 0],
        );
        let want: Vec<_> = pixels(&r.rasterize(&as_lines).unwrap())
            .into_iter()
            .map(|(_, x, y)| (0, x, y))
            .collect();
        let lines = draw(
            PolygonMode::Line,
            Topology::TriangleList,
            corners.clone(),
            vec![0, 1, 2],
        );
        let got = r.rasterize(&lines).unwrap();
        assert_eq!(pixels(&got), {
            let mut w = want;
            w.sort_unstable();
            w
        });
        assert!(got.iter().all(|f| f.primitive == 0 && !f.front_facing));
        // Each point carries its vertex's unit weights.
        let points = draw(PolygonMode::Point, Topology::TriangleList, corners, vec![0, 1, 2]);
        let got = r.rasterize(&points).unwrap();
        assert_eq!(pixels(&got), [(0, 2, 2), (0, 6, 11), (0, 12, 3)]);
        assert!(got.iter().any(|f| f.barycentric == [0.0, 1.0, 0.0]));
    }

    /// Culling is decided on the triangle: a back-facing one draws no edge and no vertex,
    /// though lines and points are never culled.
    #[test]
    fn culling_is_the_triangles() {
        let corners = at(&[[2.5, 2.5], [12.5, 3.5], [6.5, 11.5]]);
        let mut r = Reference::default();
        for mode in [PolygonMode::Line, PolygonMode::Point] {
            let mut d = draw(mode, Topology::TriangleList, corners.clone(), vec![0, 1, 2]);
            d.state.cull = CullMode::Back;
            assert!(r.rasterize(&d).unwrap().is_empty(), "{mode:?}");
            d.state.cull = CullMode::Front;
            assert!(!r.rasterize(&d).unwrap().is_empty(), "{mode:?}");
        }
    }

    /// A triangle whose inside holds no sample still draws its edges; one of zero area draws
    /// nothing in any mode.
    #[test]
    fn a_thin_triangle_draws_its_edges_and_a_flat_one_nothing() {
        let mut r = Reference::default();
        let thin = at(&[[2.1, 2.1], [12.9, 2.2], [2.1, 2.3]]);
        let fill = draw(
            PolygonMode::Fill,
            Topology::TriangleList,
            thin.clone(),
            vec![0, 1, 2],
        );
        assert!(r.rasterize(&fill).unwrap().is_empty());
        let line = draw(PolygonMode::Line, Topology::TriangleList, thin, vec![0, 1, 2]);
        assert!(!r.rasterize(&line).unwrap().is_empty());
        let flat = at(&[[2.5, 2.5], [12.5, 2.5], [7.5, 2.5]]);
        for mode in [PolygonMode::Line, PolygonMode::Point] {
            let d = draw(mode, Topology::TriangleList, flat.clone(), vec![0, 1, 2]);
            assert!(r.rasterize(&d).unwrap().is_empty(), "{mode:?}");
        }
    }
}
