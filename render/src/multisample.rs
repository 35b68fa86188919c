//! A picture at several samples per pixel: each sample depth-tested and shaded on its own, then
//! resolved to its pixel with a box filter (the mean of its samples), as a 4× supersampled
//! target is in seed 001's memory sums.

use refrast::pipeline::{Framebuffer, to_rgba8};
use refrast::{DrawError, Rasterizer, Topology};

use crate::draw::{Job, Shader, Stats, render, triangle_draw};
use crate::mode::{Mode, depth_greys, overdraw_color};

/// Clears `target` and draws `job` into it at `samples` samples per pixel through
/// [`Rasterizer::rasterize`], each pixel the mean of its samples.
///
/// One sample draws as [`render`] does; so do the points and wire modes, whose lines are drawn
/// at one sample whatever `samples` says. `Err(Unsupported)` naming the sample counts the
/// rasterizer declares when it does not declare `samples`.
pub fn render_multisampled(
    rasterizer: &mut dyn Rasterizer,
    job: &Job<'_>,
    samples: u8,
    target: &mut Framebuffer,
) -> Result<Stats, DrawError> {
    if samples <= 1 || !job.mode.uses_triangles() {
        return render(rasterizer, job, target);
    }
    let declared = rasterizer.profile();
    if !declared.draws(Topology::TriangleList, samples) {
        return Err(DrawError::Unsupported(format!(
            "{samples} samples per pixel (it declares {:?})",
            declared.sample_counts()
        )));
    }
    target.clear(job.clear, job.state.depth.clear);
    let viewport = target.viewport();
    let draw = triangle_draw(&declared, job, target)?;
    let mut fragments = rasterizer.rasterize(&draw.at_samples(samples))?;
    // API order, as the depth test replays them: stable, so each primitive keeps its own.
    fragments.sort_by_key(|f| f.primitive);
    let n = usize::from(samples);
    let triangles = job.mesh.triangles.len();
    let mut depth = vec![job.state.depth.clear; viewport.pixel_count() * n];
    let mut color = vec![job.clear; viewport.pixel_count() * n];
    let mut counts = vec![0u32; viewport.pixel_count() * n];
    let shader = Shader::new(job);
    let mut stats = Stats {
        primitives: triangles,
        fragments: 0,
        written: 0,
    };
    for f in &fragments {
        // A misbehaving implementation's fragment outside the target, of a sample or a
        // primitive the draw does not have, is skipped.
        if f.x >= viewport.width()
            || f.y >= viewport.height()
            || f.sample >= samples
            || f.primitive as usize >= triangles
        {
            continue;
        }
        stats.fragments += 1;
        let i = viewport.index(f.x, f.y) * n + usize::from(f.sample);
        counts[i] += 1;
        if job.mode != Mode::Overdraw && job.state.depth.test_and_write(f.depth, &mut depth[i]) {
            color[i] = to_rgba8(shader.color(f.primitive, f.barycentric));
            stats.written += 1;
        }
    }
    match job.mode {
        Mode::Overdraw => {
            for (c, &count) in color.iter_mut().zip(&counts) {
                *c = overdraw_color(count).unwrap_or(job.clear);
            }
        }
        Mode::Depth => {
            for (c, grey) in color.iter_mut().zip(depth_greys(&depth, job.state.depth.clear)) {
                *c = grey.map_or(job.clear, |g| [g, g, g, 255]);
            }
        }
        _ => {}
    }
    // The box filter, channel by channel, rounded to nearest; depth keeps sample 0's (Vulkan's
    // `VK_RESOLVE_MODE_SAMPLE_ZERO_BIT`).
    let half = n as u32 / 2;
    for (pixel, samples) in target.color_mut().iter_mut().zip(color.chunks_exact(n)) {
        let mut sum = [0u32; 4];
        for c in samples {
            for (total, &channel) in sum.iter_mut().zip(c) {
                *total += u32::from(channel);
            }
        }
        *pixel = sum.map(|v| ((v + half) / n as u32) as u8);
    }
    for (d, chunk) in target.depth_mut().iter_mut().zip(depth.chunks_exact(n)) {
        *d = chunk[0];
    }
    Ok(stats)
}
