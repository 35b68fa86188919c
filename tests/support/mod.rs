//! Helpers shared by the integration tests.
#![allow(dead_code)] // Each test binary uses its own subset of these helpers.

use refrast::{Draw, Fragment, Rasterizer, Reference, Viewport};

/// Clip-space position (w = 1) of a raster point given in pixels; exact for power-of-two viewports.
pub fn clip_of(viewport: Viewport, x: f64, y: f64) -> [f32; 4] {
    let (nx, ny) = viewport.to_ndc(x, y);
    [nx as f32, ny as f32, 0.5, 1.0]
}

/// A draw of triangles given in raster pixels on a `size × size` viewport.
pub fn raster_draw(size: u32, triangles: &[[(f64, f64); 3]]) -> Draw {
    let viewport = Viewport::new(size, size).unwrap();
    let positions = triangles
        .iter()
        .flatten()
        .map(|&(x, y)| clip_of(viewport, x, y))
        .collect();
    let indices = (0..triangles.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Draw::new(viewport, positions, indices)
}

/// The covered pixels of a draw with the default reference, sorted by row then column.
pub fn pixels(draw: &Draw) -> Vec<(u32, u32)> {
    let mut out: Vec<_> = fragments(draw).iter().map(|f| (f.x, f.y)).collect();
    out.sort_unstable_by_key(|&(x, y)| (y, x));
    out
}

/// The fragments of a draw with the default reference.
pub fn fragments(draw: &Draw) -> Vec<Fragment> {
    Reference::default().rasterize(draw).unwrap()
}
