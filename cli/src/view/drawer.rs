//! Which rasterizer draws a frame, and how: the list `I` steps through, and fast drawn through
//! refrast-render's visibility buffer, any other through its list of fragments.

use refrast::pipeline::Framebuffer;
use refrast::{DrawError, Rasterizer, ReferenceConfig};
use refrast_fast::{Fast, FastConfig};
use refrast_render::Job;

use crate::options::{Failure, Prepared, rasterizer};

/// The implementations `I` steps through, in order: the reference, the fast one, the course
/// labs (seed 003's painter shows its order on overlapping surfaces), then two mutants whose
/// fill-rule faults `overdraw` shows on shared edges.
pub const CYCLE: [&str; 10] = [
    "reference",
    "fast",
    "lab000",
    "lab002-scanline",
    "lab003-painter",
    "lab003-scanline-zbuffer",
    "lab003-area-average",
    "lab004-lineeq",
    "mutant:inclusive-edges",
    "mutant:exclusive-edges",
];

/// How a frame gets its triangles drawn.
pub enum Drawer {
    /// refrast-fast, which depth-tests and shades as it rasterizes.
    Fast(Fast),
    /// Any rasterizer, through its list of fragments.
    Fragments(Box<dyn Rasterizer>),
}

/// The rasterizer `name`: `fast` with `threads` threads, any other through `refrast render`'s lookup.
pub fn build(name: &str, scene: &Prepared, threads: usize) -> Result<Drawer, Failure> {
    if name == "fast" {
        return Ok(Drawer::Fast(Fast::new(FastConfig {
            reference: ReferenceConfig::default(),
            threads,
            ..FastConfig::default()
        })));
    }
    rasterizer(name, &scene.setup).map(Drawer::Fragments)
}

impl Drawer {
    /// Clears `target` and draws `job` into it at `samples` samples per pixel.
    pub fn draw(&mut self, job: &Job<'_>, samples: u8, target: &mut Framebuffer) -> Result<(), DrawError> {
        if samples > 1 {
            // Through the fragments at each sample; one that does not declare the count says so.
            let r: &mut dyn Rasterizer = match self {
                Self::Fast(fast) => fast,
                Self::Fragments(r) => r.as_mut(),
            };
            return refrast_render::render_multisampled(r, job, samples, target).map(|_| ());
        }
        match self {
            // The same pixels as `render` (refrast-render's tests compare them), with no list
            // of fragments to build and sort, and each pixel shaded once.
            Self::Fast(fast) => refrast_render::render_shaded(fast, job, target),
            Self::Fragments(r) => refrast_render::render(r.as_mut(), job, target).map(|_| ()),
        }
    }
}
