//! A picture through a rasterizer that depth-tests and shades as it rasterizes (refrast-fast):
//! the fragment that wins each pixel's depth test kept in a visibility buffer, each pixel then
//! shaded once, band by band over the rasterizer's threads.

use std::sync::atomic::{AtomicU32, Ordering};

use refrast::pipeline::{Framebuffer, to_rgba8};
use refrast::{CompareOp, Draw, DrawError, Fragment, Profile};

use crate::draw::{Job, Shader, draw_lines, triangle_draw};
use crate::mode::{Mode, depth_greys, overdraw_color};

/// A rasterizer that depth-tests and shades as it rasterizes, writing straight into buffers
/// (refrast-fast's `Fast::render` is one): what [`render_shaded`] draws through.
pub trait ShadingRasterizer {
    /// Draws `draw` into row-major `depth` and `color` of its viewport's size: each pixel's
    /// fragments in primitive order, tested against `draw`'s depth state; `shade` gives those
    /// that pass the value to write, or `None` to discard them (no depth or colour write).
    fn rasterize_shaded<C, F>(
        &mut self,
        draw: &Draw,
        depth: &mut [f32],
        color: &mut [C],
        shade: F,
    ) -> Result<(), DrawError>
    where
        C: Send,
        F: Fn(&Fragment) -> Option<C> + Sync;

    /// Calls `f` on every item of `items`, spread over the rasterizer's own threads where it
    /// has them: [`render_shaded`] shades its visibility buffer so, a band of rows an item,
    /// at the thread count the rasterizing had. One after another by default.
    fn for_each<T: Send>(&self, items: &mut [T], f: impl Fn(&mut T) + Sync) {
        items.iter_mut().for_each(f);
    }
}

/// refrast-fast depth-tests and shades as it rasterizes, into the buffers given.
impl ShadingRasterizer for refrast_fast::Fast {
    fn rasterize_shaded<C, F>(
        &mut self,
        draw: &Draw,
        depth: &mut [f32],
        color: &mut [C],
        shade: F,
    ) -> Result<(), DrawError>
    where
        C: Send,
        F: Fn(&Fragment) -> Option<C> + Sync,
    {
        self.render(draw, depth, color, shade)
    }

    fn for_each<T: Send>(&self, items: &mut [T], f: impl Fn(&mut T) + Sync) {
        refrast_fast::Fast::for_each(self, items, f);
    }
}

/// Rows of a picture shaded as one item of [`ShadingRasterizer::for_each`]: enough that
/// handing items to threads costs little against shading them, few enough that 1080p has
/// dozens to share.
const SHADED_ROWS: usize = 16;

/// What a pixel shows after the depth test: the last fragment that passed, as much of it as
/// the shader reads; `primitive == u32::MAX` where none did.
#[derive(Clone, Copy)]
struct Visible {
    primitive: u32,
    barycentric: [f32; 3],
}

/// Clears `target` and draws `job` into it as [`render`](crate::render) does, pixel for
/// pixel, through a [`ShadingRasterizer`]: no list of fragments is built or sorted, and each
/// pixel is shaded once, from the fragment that won its depth test (a visibility buffer; the
/// shader reads nothing else of a fragment, so the colour is the one `render` leaves there),
/// band by band over the rasterizer's threads ([`ShadingRasterizer::for_each`]).
pub fn render_shaded<R: ShadingRasterizer + ?Sized>(
    rasterizer: &mut R,
    job: &Job<'_>,
    target: &mut Framebuffer,
) -> Result<(), DrawError> {
    target.clear(job.clear, job.state.depth.clear);
    if draw_lines(job, target).is_some() {
        return Ok(());
    }
    // A shading rasterizer declares no profile, so none of the state declared apart.
    let mut draw = triangle_draw(&Profile::default(), job, target)?;
    let viewport = target.viewport();
    let triangles = job.mesh.triangles.len();
    let inside = |f: &Fragment| {
        f.x < viewport.width() && f.y < viewport.height() && (f.primitive as usize) < triangles
    };
    let (color, depth) = target.color_and_depth_mut();
    if job.mode == Mode::Overdraw {
        // Every fragment is counted, none written: the depth test is off for the count.
        draw.state.depth.compare = CompareOp::Always;
        draw.state.depth.write = false;
        let counts: Vec<AtomicU32> = (0..viewport.pixel_count()).map(|_| AtomicU32::new(0)).collect();
        let count = |f: &Fragment| -> Option<()> {
            if inside(f) {
                counts[viewport.index(f.x, f.y)].fetch_add(1, Ordering::Relaxed);
            }
            None
        };
        rasterizer.rasterize_shaded(&draw, depth, &mut vec![(); viewport.pixel_count()], count)?;
        for (pixel, count) in color.iter_mut().zip(counts) {
            if let Some(c) = overdraw_color(count.into_inner()) {
                *pixel = c;
            }
        }
        return Ok(());
    }
    let none = Visible {
        primitive: u32::MAX,
        barycentric: [0.0; 3],
    };
    let mut visible = vec![none; viewport.pixel_count()];
    let record = |f: &Fragment| {
        inside(f).then_some(Visible {
            primitive: f.primitive,
            barycentric: f.barycentric,
        })
    };
    rasterizer.rasterize_shaded(&draw, depth, &mut visible, record)?;
    let shader = Shader::new(job);
    let band = viewport.width() as usize * SHADED_ROWS;
    let mut bands: Vec<_> = color.chunks_mut(band).zip(visible.chunks(band)).collect();
    rasterizer.for_each(&mut bands, |(color, visible)| {
        for (pixel, v) in color.iter_mut().zip(visible.iter()) {
            if v.primitive != u32::MAX {
                *pixel = to_rgba8(shader.color(v.primitive, v.barycentric));
            }
        }
    });
    if job.mode == Mode::Depth {
        let greys = depth_greys(target.depth(), job.state.depth.clear);
        for (pixel, grey) in target.color_mut().iter_mut().zip(greys) {
            if let Some(g) = grey {
                *pixel = [g, g, g, 255];
            }
        }
    }
    Ok(())
}
