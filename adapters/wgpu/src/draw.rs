//! The passes that read back what the driver did: capture (every covered sample) and resolve
//! (the driver's own depth test into a depth and an id target), for any topology and sample
//! count.

use bytemuck::{Pod, Zeroable};
use refrast::{Draw, DrawError, Fragment, Topology};
use wgpu::util::DeviceExt;

use std::time::{Duration, Instant};

use crate::Timings;
use crate::device::Context;
use crate::pipelines::{DEPTH, DEPTHS, IDS, Key, Method, Pass, Pipelines};
use crate::resources::{Readback, VertexBuffers, along, depth_attachment, map, set_scissor, target};

/// One covered sample as the capture shader writes it (`Sample` in `capture.wgsl`); the
/// position as the bits of its f32 coordinates.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct RawSample {
    x: u32,
    y: u32,
    primitive: u32,
    front_facing: u32,
    depth: f32,
    perspective: [f32; 3],
    screen: [f32; 3],
    sample: u32,
    vertex: u32,
}

/// Every covered sample of every primitive of `draw`, as the driver rasterized them.
pub fn capture(ctx: &Context, pipelines: &mut Pipelines, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let primitives = draw.primitive_count();
    if primitives == 0 {
        return Ok(Vec::new());
    }
    if pipelines.method == Method::FloatTargets {
        if draw.samples > 1 {
            return Err(DrawError::Unsupported(format!(
                "{} captures one primitive at a time into float targets, at one sample only",
                ctx.info.name
            )));
        }
        return crate::targets::capture(ctx, pipelines, draw);
    }
    let offset = strip_offset(ctx, pipelines, draw.topology)?;
    let vertices = VertexBuffers::new(ctx, draw);
    // Room for every sample covered by four primitives; a draw covering more is drawn again with
    // room for exactly what the first pass counted.
    let mut capacity = (draw.viewport.pixel_count() * usize::from(draw.samples) * primitives.min(4)).max(1);
    loop {
        let (count, samples) = capture_pass(ctx, pipelines, draw, &vertices, capacity)?;
        if count <= capacity {
            return Ok(samples[..count]
                .iter()
                .map(|s| {
                    let mut f = fragment(s);
                    // The provoking vertex's place in the stream names the draw's vertex.
                    f.flat = draw.indices.get(s.vertex as usize).copied();
                    f.primitive = f.primitive.wrapping_sub(offset);
                    along(draw.topology, f)
                })
                .collect());
        }
        capacity = count;
    }
}

/// How far `topology`'s flat primitive ids are from its primitives' indices: 0 but for a strip
/// on a driver whose flat values come from a primitive's last vertex (1 for a line strip, 2
/// for a triangle strip). A strip of one primitive over a 4×1 target, drawn once per process
/// and topology, says which.
fn strip_offset(ctx: &Context, pipelines: &mut Pipelines, topology: Topology) -> Result<u32, DrawError> {
    let (corners, probe): (u32, Vec<[f32; 4]>) = match topology {
        Topology::LineStrip => (2, vec![[-0.75, 0.0, 0.5, 1.0], [0.75, 0.0, 0.5, 1.0]]),
        Topology::TriangleStrip => (
            3,
            vec![
                [-3.0, -3.0, 0.5, 1.0],
                [3.0, -3.0, 0.5, 1.0],
                [0.0, 3.0, 0.5, 1.0],
            ],
        ),
        _ => return Ok(0),
    };
    if let Some(&offset) = pipelines.strip_offsets.get(&topology) {
        return Ok(offset);
    }
    let viewport = refrast::Viewport::new(4, 1).map_err(|e| DrawError::Backend(e.to_string()))?;
    let indices = (0..corners).collect();
    let one = Draw::of(viewport, probe, topology, indices);
    // The resolve pass reads flat ids back with either capture method.
    let ids: Vec<u32> = resolve_with(ctx, pipelines, &one, 0)?
        .primitive
        .into_iter()
        .flatten()
        .collect();
    let offset = match ids.first() {
        Some(&first) if ids.iter().all(|&id| id == first) && (first == 0 || first == corners - 1) => first,
        _ => {
            return Err(DrawError::Backend(format!(
                "a {topology} of one primitive came back as {ids:?}: its flat values name neither its first nor its last vertex"
            )));
        }
    };
    pipelines.strip_offsets.insert(topology, offset);
    Ok(offset)
}

/// A captured sample as a fragment; a position outside `0..2³²` (a driver shading off the
/// target) becomes `u32::MAX`, which every viewport excludes.
fn fragment(s: &RawSample) -> Fragment {
    let pixel = |bits: u32| {
        let centre = f32::from_bits(bits).floor();
        if (0.0..u32::MAX as f32).contains(&centre) {
            centre as u32
        } else {
            u32::MAX
        }
    };
    Fragment {
        x: pixel(s.x),
        y: pixel(s.y),
        sample: u8::try_from(s.sample).unwrap_or(u8::MAX),
        primitive: s.primitive,
        depth: s.depth,
        barycentric: s.perspective,
        flat: None,
        screen_barycentric: Some(s.screen),
        front_facing: s.front_facing != 0,
    }
}

/// One capture pass with room for `capacity` samples: how many there were, and those that fit.
fn capture_pass(
    ctx: &Context,
    pipelines: &mut Pipelines,
    draw: &Draw,
    vertices: &VertexBuffers,
    capacity: usize,
) -> Result<(usize, Vec<RawSample>), DrawError> {
    let device = &ctx.device;
    let sample_size = std::mem::size_of::<RawSample>() as u64;
    let bytes = capacity as u64 * sample_size;
    if bytes > device.limits().max_storage_buffer_binding_size {
        return Err(DrawError::Unsupported(format!(
            "{capacity} covered samples need {bytes} bytes, more than the device binds"
        )));
    }
    let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
    let count_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("count"),
        contents: bytemuck::bytes_of(&0u32),
        usage: storage,
    });
    let sample_buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("samples"),
        size: bytes,
        usage: storage,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("capture"),
        layout: &pipelines.layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: count_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: sample_buffer.as_entire_binding(),
            },
        ],
    });
    let depth = target(ctx, draw.viewport, DEPTH, draw.samples);
    let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
    // Centroid interpolation changes only a filled triangle's inputs, and only above one sample.
    let centroid = draw.state.interpolation == refrast::Interpolation::Centroid
        && draw.topology.is_triangles()
        && draw.state.polygon_mode == refrast::PolygonMode::Fill;
    let pass = match (draw.samples, centroid) {
        (1, _) => Pass::Capture,
        (_, true) => Pass::CaptureCentroid,
        (_, false) => Pass::CaptureSamples,
    };
    let key = Key::new(pass, &draw.state)
        .drawing(draw.topology, draw.samples)
        .clipping(draw.distances.clip > 0);
    let pipeline = pipelines.get(device, key)?;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("capture"),
    });
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("capture"),
            color_attachments: &[],
            depth_stencil_attachment: Some(depth_attachment(&depth_view, 1.0, false)),
            ..wgpu::RenderPassDescriptor::default()
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        vertices.bind(&mut pass);
        set_scissor(&mut pass, draw);
        pass.draw(0..vertices.count, 0..1);
    }
    let count = read_buffer(ctx, encoder, &count_buffer, 4)?;
    let count = bytemuck::pod_read_unaligned::<u32>(&count) as usize;
    let fit = count.min(capacity);
    let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("read") });
    let samples = if fit == 0 {
        Vec::new()
    } else {
        let raw = read_buffer(ctx, encoder, &sample_buffer, fit as u64 * sample_size)?;
        bytemuck::pod_collect_to_vec(&raw)
    };
    Ok((count, samples))
}

/// Submits `encoder` with a copy of the first `size` bytes of `buffer`, waits, and returns them.
fn read_buffer(
    ctx: &Context,
    mut encoder: wgpu::CommandEncoder,
    buffer: &wgpu::Buffer,
    size: u64,
) -> Result<Vec<u8>, DrawError> {
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("staging"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    map(ctx, &staging)
}

/// The driver's depth test: the depth buffer and the id of the last fragment that passed, one
/// value per sample.
pub fn resolve(ctx: &Context, pipelines: &mut Pipelines, draw: &Draw) -> Result<Resolve, DrawError> {
    let offset = strip_offset(ctx, pipelines, draw.topology)?;
    resolve_with(ctx, pipelines, draw, offset)
}

/// [`resolve`], each flat id taken `offset` from its primitive's index.
fn resolve_with(
    ctx: &Context,
    pipelines: &mut Pipelines,
    draw: &Draw,
    offset: u32,
) -> Result<Resolve, DrawError> {
    let n = draw.viewport.pixel_count() * usize::from(draw.samples);
    let clear = draw.state.depth.clear;
    if draw.primitive_count() == 0 {
        return Ok(Resolve {
            depth: vec![clear; n],
            primitive: vec![None; n],
            timings: Timings {
                drawing: Duration::ZERO,
                reading: Duration::ZERO,
            },
        });
    }
    let device = &ctx.device;
    let vertices = VertexBuffers::new(ctx, draw);
    let samples = draw.samples;
    let depth = target(ctx, draw.viewport, DEPTH, samples);
    let ids = target(ctx, draw.viewport, IDS, samples);
    let depths = target(ctx, draw.viewport, DEPTHS, samples);
    let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
    let ids_view = ids.create_view(&wgpu::TextureViewDescriptor::default());
    let depths_view = depths.create_view(&wgpu::TextureViewDescriptor::default());
    let key = Key::new(Pass::Resolve, &draw.state)
        .drawing(draw.topology, samples)
        .clipping(draw.distances.clip > 0);
    let pipeline = pipelines.get(device, key)?;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("resolve"),
    });
    {
        // The clear depth's bits, exact in an f64.
        let cleared = wgpu::Color {
            r: f64::from(clear.to_bits()),
            ..wgpu::Color::TRANSPARENT
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("resolve"),
            color_attachments: &[
                colour(&ids_view, wgpu::Color::TRANSPARENT),
                colour(&depths_view, cleared),
            ],
            depth_stencil_attachment: Some(depth_attachment(&depth_view, clear, true)),
            ..wgpu::RenderPassDescriptor::default()
        });
        pass.set_pipeline(pipeline);
        vertices.bind(&mut pass);
        set_scissor(&mut pass, draw);
        pass.draw(0..vertices.count, 0..1);
    }
    // The draw, timed apart from reading it back.
    let started = Instant::now();
    ctx.queue.submit([encoder.finish()]);
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| DrawError::Backend(format!("the device did not finish: {e}")))?;
    let drawing = started.elapsed();
    let started = Instant::now();
    let (depths, primitives) = if samples == 1 {
        read_single(ctx, draw, &ids, &depth, &depths)?
    } else {
        read_samples(ctx, pipelines, draw, &ids_view, &depth_view)?
    };
    Ok(Resolve {
        depth: depths,
        primitive: primitives
            .into_iter()
            .map(|id| id.checked_sub(1).map(|p| p.wrapping_sub(offset)))
            .collect(),
        timings: Timings {
            drawing,
            reading: started.elapsed(),
        },
    })
}

/// A colour attachment cleared to `clear` and stored.
fn colour(view: &wgpu::TextureView, clear: wgpu::Color) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(clear),
            store: wgpu::StoreOp::Store,
        },
    })
}

/// The depths and ids (plus one) of a resolve at one sample, copied back.
fn read_single(
    ctx: &Context,
    draw: &Draw,
    ids: &wgpu::Texture,
    depth: &wgpu::Texture,
    depths: &wgpu::Texture,
) -> Result<(Vec<f32>, Vec<u32>), DrawError> {
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("read back"),
        });
    let ids_out = Readback::new(ctx, w, h, 4);
    ids_out.copy(&mut encoder, ids, wgpu::TextureAspect::All);
    let depth_out = Readback::new(ctx, w, h, 4);
    if ctx.copies_depth {
        depth_out.copy(&mut encoder, depth, wgpu::TextureAspect::DepthOnly);
    } else {
        // OpenGL ES cannot copy a depth texture: the passing fragment wrote its depth's bits to
        // an integer target. With writes on, that is what the depth buffer holds; with writes off the
        // buffer keeps its clear value (a driver writing it anyway would still show in the ids,
        // as later fragments would test against it).
        depth_out.copy(&mut encoder, depths, wgpu::TextureAspect::All);
    }
    ctx.queue.submit([encoder.finish()]);
    let read: Vec<f32> = depth_out.read::<f32>(ctx)?;
    let read = if ctx.copies_depth || draw.state.depth.write {
        read
    } else {
        vec![draw.state.depth.clear; read.len()]
    };
    Ok((read, ids_out.read::<u32>(ctx)?))
}

/// The depths and ids (plus one) of a resolve at several samples (at most
/// [`MOST_SAMPLES`](crate::unpack::MOST_SAMPLES)), sample by sample: `unpack.wgsl` loads each
/// pixel's samples into two one-sample targets, which are copied back.
fn read_samples(
    ctx: &Context,
    pipelines: &mut Pipelines,
    draw: &Draw,
    ids: &wgpu::TextureView,
    depth: &wgpu::TextureView,
) -> Result<(Vec<f32>, Vec<u32>), DrawError> {
    use crate::unpack::{MOST_SAMPLES, UNPACKED};
    if draw.samples > MOST_SAMPLES {
        return Err(DrawError::Unsupported(format!(
            "a resolve at {} samples: the adapter reads back at most {MOST_SAMPLES}",
            draw.samples
        )));
    }
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let device = &ctx.device;
    let (pipeline, layout) = pipelines.unpack(device);
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("unpack"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(ids),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(depth),
            },
        ],
    });
    let unpacked = [0, 1].map(|_| target(ctx, draw.viewport, UNPACKED, 1));
    let views = unpacked
        .each_ref()
        .map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()));
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("unpack"),
    });
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("unpack"),
            color_attachments: &[
                colour(&views[0], wgpu::Color::TRANSPARENT),
                colour(&views[1], wgpu::Color::TRANSPARENT),
            ],
            ..wgpu::RenderPassDescriptor::default()
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
    let outs = [0, 1].map(|_| Readback::new(ctx, w, h, 16));
    for (out, texture) in outs.iter().zip(&unpacked) {
        out.copy(&mut encoder, texture, wgpu::TextureAspect::All);
    }
    ctx.queue.submit([encoder.finish()]);
    let per_sample = |texels: Vec<[u32; 4]>| -> Vec<u32> {
        texels
            .into_iter()
            .flat_map(|t| t.into_iter().take(usize::from(draw.samples)))
            .collect()
    };
    let ids = per_sample(outs[0].read::<[u32; 4]>(ctx)?);
    let depths = per_sample(outs[1].read::<[u32; 4]>(ctx)?)
        .into_iter()
        .map(f32::from_bits)
        .collect();
    Ok((depths, ids))
}

/// What the driver's depth test left, and how long drawing and reading it back took.
pub struct Resolve {
    /// The depth buffer, row by row, sample by sample within a pixel.
    pub depth: Vec<f32>,
    /// The primitive that last passed the depth test at each sample.
    pub primitive: Vec<Option<u32>>,
    /// How long the device drew, and how long reading back took.
    pub timings: Timings,
}
