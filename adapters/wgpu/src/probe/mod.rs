//! Probes: what a driver should declare where nothing reports it, measured by drawing. Vulkan
//! reports the grid (`subPixelPrecisionBits`) but names no tie rule, no rounding of snapping, no
//! guard band and no interpolation precision; OpenGL through wgpu reports nothing at all.
//!
//! Each probe is one or two draws of many small triangles, read back by primitive id, so that all
//! of them take a fraction of a second. A probe draws through any rasterizer's `rasterize`: the
//! unit tests run them on the reference configured every way and check that they read back what
//! it declares. Every position is exact in f32 and on the coarsest grid Vulkan allows (1/16 px)
//! unless the probe is about rounding; each probe returns what it counted, and
//! [`crate::measured`] chooses the declarations from that.

mod band;
pub mod bias;
mod coverage;
mod fill;
mod grid;
mod precision;
pub mod primitives;
mod snap;

use refrast::{Draw, DrawError, Fragment, Viewport};

pub use band::{Band, REACHES};
pub use bias::Slope;
pub use coverage::Coverage;
pub use fill::{TieRule, name as fill_name};
pub use grid::{FINEST, Grid};
pub use precision::Precision;
pub use primitives::{PrimitiveProbes, PrimitiveRaster};
pub use snap::{Rounding, Snap};

/// Everything the probes counted on one driver.
#[derive(Clone, Debug, PartialEq)]
pub struct Probes {
    /// The finest vertex move that changes coverage, in x and in y.
    pub grid: Grid,
    /// Samples decided against exact arithmetic on the unsnapped vertices, and how far out.
    pub coverage: Coverage,
    /// Which edges own a sample exactly on them, and shared edges covered once.
    pub tie_rule: TieRule,
    /// How exact snap ties round.
    pub rounding: Rounding,
    /// Where vertices a few ulps from a tie land.
    pub snap: Snap,
    /// Whether ties on edges leaving the viewport flip, by reach.
    pub band: Band,
    /// How far interpolated values are from exact on unclipped triangles.
    pub precision: Precision,
    /// The line rule, points, and where the 4 samples lie.
    pub primitives: PrimitiveProbes,
    /// The depth slope its bias takes ([`bias::probe`], through the depth buffer: the driver
    /// runs it apart, after the others).
    pub slope: Slope,
}

/// Runs every probe through `draw`. `reported_bits` is the grid the driver reports, if it
/// reports one (Vulkan); the probes needing a grid use it, else the measured one.
/// `multisampling` is why the driver cannot draw at 4 samples, if it cannot.
pub fn measure(
    prims: &mut PrimitiveRaster<'_>,
    reported_bits: Option<u8>,
    multisampling: Result<(), String>,
) -> Result<Probes, DrawError> {
    let draw = &mut |d: &Draw| prims(d);
    let grid = grid::probe(draw)?;
    let coverage = coverage::probe(draw)?;
    // The grid the other probes place ties on; 16 bits stands for "finer than 16" (no grid).
    let bits = reported_bits.or(grid.bits()).unwrap_or(16);
    let tie_rule = fill::probe(draw)?;
    let (rounding, snap) = snap::probe(draw, bits)?;
    let band = band::probe(draw, tie_rule.chosen)?;
    let precision = precision::probe(draw, bits)?;
    // A driver without a grid is compared with the reference's finest.
    let primitives = primitives::measure(prims, bits.min(8), tie_rule.chosen, multisampling);
    Ok(Probes {
        grid,
        coverage,
        tie_rule,
        rounding,
        snap,
        band,
        precision,
        primitives,
        slope: Slope::unmeasured(),
    })
}

/// A rasterizer's draw, as the probes call it.
pub type Raster<'a> = dyn FnMut(&Draw) -> Result<Vec<Fragment>, DrawError> + 'a;

/// Clip-space position of framebuffer point `(x, y)` (pixels, y down) at window depth `d` and
/// `w`: exact when `w` is a power of two and the point lies on a grid of at most 16 bits.
fn clip(width: u32, height: u32, [x, y]: [f64; 2], d: f64, w: f64) -> [f32; 4] {
    let nx = 2.0 * x / f64::from(width) - 1.0;
    let ny = 1.0 - 2.0 * y / f64::from(height);
    [(nx * w) as f32, (ny * w) as f32, (d * w) as f32, w as f32]
}

/// One draw of `positions` three at a time on a `width`×`height` target, far clipping on
/// (WebGPU cannot turn it off) and no culling: triangle `i` is primitive `i`.
fn batch(width: u32, height: u32, positions: Vec<[f32; 4]>) -> Draw {
    let n = u32::try_from(positions.len() / 3).expect("a few thousand triangles");
    let triangles = (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut draw = Draw::new(
        Viewport::new(width, height).expect("a probe's target"),
        positions,
        triangles,
    );
    draw.state.clip_far = true;
    draw
}

/// Per primitive, whether it covers pixel `(x, y)`.
fn covers(frags: &[Fragment], triangles: usize, (x, y): (u32, u32)) -> Vec<bool> {
    let mut covered = vec![false; triangles];
    for f in frags.iter().filter(|f| (f.x, f.y) == (x, y)) {
        if let Some(c) = covered.get_mut(f.primitive as usize) {
            *c = true;
        }
    }
    covered
}

#[cfg(test)]
mod tests;
