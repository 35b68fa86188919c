//! Capturing without storage buffers: one pass per primitive into two float targets, for a
//! driver whose fragment shaders cannot write storage buffers (softpipe's OpenGL ES). A
//! primitive covers a sample at most once, so one pass per primitive loses nothing.

use refrast::{Draw, DrawError, Fragment, Topology};

use crate::device::Context;
use crate::pipelines::{DEPTH, FLOATS, Key, Pass, Pipelines};
use crate::resources::{Readback, VertexBuffers, along, depth_attachment, set_scissor, target};

/// Every covered sample of every primitive of `draw` (at one sample per pixel), one primitive
/// per pass.
pub fn capture(ctx: &Context, pipelines: &mut Pipelines, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let device = &ctx.device;
    if !ctx.renders_floats {
        return Err(DrawError::Unsupported(format!(
            "{} can neither write storage buffers from fragment shaders nor render to {FLOATS:?}, \
             so its covered samples cannot be read back",
            ctx.info.name
        )));
    }
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let vertices = VertexBuffers::new(ctx, draw);
    let (perspective, screen, depth) = (
        target(ctx, draw.viewport, FLOATS, 1),
        target(ctx, draw.viewport, FLOATS, 1),
        target(ctx, draw.viewport, DEPTH, 1),
    );
    let views =
        [&perspective, &screen, &depth].map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()));
    // One pipeline and one pair of read-back buffers serve every primitive.
    let key = Key::new(Pass::CaptureTargets, &draw.state)
        .drawing(draw.topology, 1)
        .clipping(draw.distances.clip > 0);
    let pipeline = pipelines.get(device, key)?;
    // The vertices of primitive `i`: a list's own, a strip's from vertex `i`.
    let (per, step) = match draw.topology {
        Topology::TriangleList => (3, 3),
        Topology::TriangleStrip => (3, 1),
        Topology::LineList => (2, 2),
        Topology::LineStrip => (2, 1),
        Topology::PointList => (1, 1),
        Topology::TriangleFan => return Err(DrawError::Unsupported("WebGPU has no triangle-fan".into())),
    };
    let (first, second) = (Readback::new(ctx, w, h, 16), Readback::new(ctx, w, h, 16));
    let mut fragments = Vec::new();
    for primitive in 0..draw.primitive_count() as u32 {
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("capture one primitive"),
        });
        {
            let colour = |view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("capture one primitive"),
                color_attachments: &[colour(&views[0]), colour(&views[1])],
                depth_stencil_attachment: Some(depth_attachment(&views[2], 1.0, false)),
                ..wgpu::RenderPassDescriptor::default()
            });
            pass.set_pipeline(pipeline);
            vertices.bind(&mut pass);
            set_scissor(&mut pass, draw);
            // The shader numbers corners by the global vertex index, as in one draw of all. An
            // odd triangle of a strip is drawn second in a strip of two, from the vertex before
            // its own, so that it turns as in the whole strip (reversed).
            let (first, count) = strip_pair(draw.topology, step * primitive, per);
            pass.draw(first..first + count, 0..1);
        }
        first.copy(&mut encoder, &perspective, wgpu::TextureAspect::All);
        second.copy(&mut encoder, &screen, wgpu::TextureAspect::All);
        ctx.queue.submit([encoder.finish()]);
        let (weights, facing) = (first.read::<[f32; 4]>(ctx)?, second.read::<[f32; 4]>(ctx)?);
        for (i, (p, s)) in weights.iter().zip(&facing).enumerate() {
            // The marker is 0 (the clear) on an uncovered sample, else 1 for a front face and 2
            // for a back face, plus 4 times the provoking vertex's place in the stream
            // (`targets.wgsl`).
            if s[3] == 0.0 {
                continue;
            }
            let (front_facing, vertex) = (s[3] % 4.0 == 1.0, (s[3] / 4.0).floor() as u32);
            if !is_drawn_primitive(draw.topology, primitive, vertex) {
                continue;
            }
            fragments.push(along(
                draw.topology,
                Fragment {
                    x: i as u32 % w,
                    y: i as u32 / w,
                    sample: 0,
                    primitive,
                    depth: p[3],
                    barycentric: [p[0], p[1], p[2]],
                    flat: draw.indices.get(vertex as usize).copied(),
                    screen_barycentric: Some([s[0], s[1], s[2]]),
                    front_facing,
                },
            ));
        }
    }
    Ok(fragments)
}

/// The vertices drawn for the primitive whose own start at `first`: its `per`, but for an odd
/// triangle of a strip, which is drawn with the one before it.
fn strip_pair(topology: Topology, first: u32, per: u32) -> (u32, u32) {
    if topology == Topology::TriangleStrip && first % 2 == 1 {
        (first - 1, per + 1)
    } else {
        (first, per)
    }
}

/// Whether a sample whose provoking vertex is `vertex` in the stream belongs to `primitive`
/// rather than to the triangle drawn with it ([`strip_pair`]): in a strip, triangle `i`'s is
/// its first or last vertex, `i` or `i + 2`, of `i`'s parity either way, and its partner's is
/// of the other.
fn is_drawn_primitive(topology: Topology, primitive: u32, vertex: u32) -> bool {
    topology != Topology::TriangleStrip || vertex % 2 == primitive % 2
}
