//! `lab003-painter`: the painter's algorithm of seed 003 (CS174, "Hidden Surface Removal"), as a
//! student writes it from the notes: sort the triangles by depth, then paint them back to front,
//! each overwriting what lies under it. There is no depth buffer.
//!
//! What the seed says, and what this module therefore does:
//!
//! - **Sort by z-depth** (step 1): one key per triangle, its *farthest* vertex's window depth
//!   ([`sort_key`]), largest first; ties keep submission order (a stable sort).
//! - **Scan-convert back to front** (step 2): each triangle's pixels, found by the reference's
//!   scan conversion, overwrite the picture. Only the order of painting is the lab's.
//! - **No depth test** of any kind: a later-painted triangle wins every pixel it covers, whatever
//!   depth its pixel has, and whatever the depth buffer's clear value.
//!
//! So that the depth rules judge it, it declares a depth test (`Less`, writes on, the only setting
//! it offers): its [`Rasterizer::resolve`] is the painter's order, and the depth it reports at a
//! pixel is the depth of the surface painted last there, what a z-buffer would hold if the order
//! were right. The seed's warning, "cannot handle cyclic or intersecting polygons", is what the
//! suite should find: two triangles that pass through each other, or three that overlap in a cycle,
//! have no order in which painting them leaves the nearer surface everywhere
//! (`depth.intersecting.nearest-wins`). A farthest-vertex key also misorders triangles that do
//! neither, when a big one's far vertex lies behind a small one it covers.

use refrast::{
    CompareOp, Draw, DrawError, Features, Fragment, Profile, Rasterizer, Reference, Resolved, Supported,
};

/// Seed 003's painter's algorithm over the reference's scan conversion.
#[derive(Clone, Copy, Debug, Default)]
pub struct Painter;

/// A triangle's place in the painting order: the window depth of its farthest vertex in front of
/// the eye (`w > 0`), or `None` when no vertex is (such a triangle draws nothing after clipping).
#[must_use]
pub fn sort_key(draw: &Draw, triangle: usize) -> Option<f64> {
    let indices = draw.triangle(triangle)?;
    indices
        .iter()
        .filter_map(|&i| draw.positions.get(i as usize))
        .filter(|p| p[3] > 0.0 && p.iter().all(|c| c.is_finite()))
        .map(|p| {
            draw.state
                .depth_range
                .window_depth(f64::from(p[2]), f64::from(p[3]))
        })
        .reduce(f64::max)
}

/// The painting order: triangle indices from the farthest key to the nearest, stably.
#[must_use]
pub fn painting_order(draw: &Draw) -> Vec<usize> {
    let mut order: Vec<(usize, f64)> = (0..draw.triangles().len())
        .filter_map(|t| sort_key(draw, t).map(|key| (t, key)))
        .collect();
    order.sort_by(|a, b| b.1.total_cmp(&a.1));
    order.into_iter().map(|(t, _)| t).collect()
}

impl Rasterizer for Painter {
    fn profile(&self) -> Profile {
        let reference = Reference::default().profile().triangles_only();
        Profile {
            name: "lab003-painter".into(),
            features: Features {
                // The painting order stands in for a depth test; it has one setting.
                depth_test: true,
                compare_ops: Supported::only(&[CompareOp::Less]),
                depth_writes: Supported::only(&[true]),
                ..reference.features
            },
            ..reference
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        Reference::default().rasterize(draw)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let fragments = self.rasterize(draw)?;
        let viewport = draw.viewport;
        let mut by_triangle: Vec<Vec<Fragment>> = vec![Vec::new(); draw.triangles().len()];
        for f in fragments {
            if let Some(list) = by_triangle.get_mut(f.primitive as usize) {
                list.push(f);
            }
        }
        let mut resolved = Resolved {
            viewport,
            samples: 1,
            depth: vec![draw.state.depth.clear; viewport.pixel_count()],
            primitive: vec![None; viewport.pixel_count()],
        };
        for t in painting_order(draw) {
            for f in &by_triangle[t] {
                if f.x < viewport.width() && f.y < viewport.height() {
                    let i = viewport.index(f.x, f.y);
                    resolved.depth[i] = f.depth;
                    resolved.primitive[i] = Some(f.primitive);
                }
            }
        }
        Ok(resolved)
    }
}
