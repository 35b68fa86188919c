//! The passes that read back what the driver did: capture (every covered sample) and resolve
//! (the driver's own depth test into a depth and an id target).

use bytemuck::{Pod, Zeroable};
use refrast::{Draw, DrawError, Fragment};
use wgpu::util::DeviceExt;

use std::time::{Duration, Instant};

use crate::Timings;
use crate::device::Context;
use crate::pipelines::{DEPTH, DEPTHS, IDS, Key, Method, Pass, Pipelines};
use crate::resources::{Readback, depth_attachment, map, target, vertex_list};

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
    pad: u32,
}

/// Every covered sample of every triangle of `draw`, as the driver rasterized them.
pub fn capture(ctx: &Context, pipelines: &mut Pipelines, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    if draw.triangles.is_empty() {
        return Ok(Vec::new());
    }
    if pipelines.method == Method::FloatTargets {
        return crate::targets::capture(ctx, pipelines, draw);
    }
    let vertices = vertex_list(draw);
    // Room for every sample covered by four triangles; a draw covering more is drawn again with
    // room for exactly what the first pass counted.
    let mut capacity = (draw.viewport.pixel_count() * draw.triangles.len().min(4)).max(1);
    loop {
        let (count, samples) = capture_pass(ctx, pipelines, draw, &vertices, capacity)?;
        if count <= capacity {
            return Ok(samples[..count].iter().map(fragment).collect());
        }
        capacity = count;
    }
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
        primitive: s.primitive,
        depth: s.depth,
        barycentric: s.perspective,
        screen_barycentric: Some(s.screen),
        front_facing: s.front_facing != 0,
    }
}

/// One capture pass with room for `capacity` samples: how many there were, and those that fit.
fn capture_pass(
    ctx: &Context,
    pipelines: &mut Pipelines,
    draw: &Draw,
    vertices: &[[f32; 4]],
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
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("vertices"),
        contents: bytemuck::cast_slice(vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
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
    let depth = target(ctx, draw, DEPTH);
    let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
    let pipeline = pipelines.get(device, Key::new(Pass::Capture, &draw.state));
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
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
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

/// The driver's depth test: the depth buffer and the id of the last fragment that passed.
pub fn resolve(ctx: &Context, pipelines: &mut Pipelines, draw: &Draw) -> Result<Resolve, DrawError> {
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let clear = draw.state.depth.clear;
    if draw.triangles.is_empty() {
        return Ok(Resolve {
            depth: vec![clear; draw.viewport.pixel_count()],
            primitive: vec![None; draw.viewport.pixel_count()],
            timings: Timings {
                drawing: Duration::ZERO,
                reading: Duration::ZERO,
            },
        });
    }
    let device = &ctx.device;
    let vertices = vertex_list(draw);
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("vertices"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let depth = target(ctx, draw, DEPTH);
    let ids = target(ctx, draw, IDS);
    let depths = target(ctx, draw, DEPTHS);
    let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
    let ids_view = ids.create_view(&wgpu::TextureViewDescriptor::default());
    let depths_view = depths.create_view(&wgpu::TextureViewDescriptor::default());
    let pipeline = pipelines.get(device, Key::new(Pass::Resolve, &draw.state));
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("resolve"),
    });
    {
        let colour = |view, clear| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
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
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
    // The draw, timed apart from reading it back.
    let started = Instant::now();
    ctx.queue.submit([encoder.finish()]);
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| DrawError::Backend(format!("the device did not finish: {e}")))?;
    let drawing = started.elapsed();
    let started = Instant::now();
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("read back"),
    });
    let ids_out = Readback::new(ctx, w, h, 4);
    ids_out.copy(&mut encoder, &ids, wgpu::TextureAspect::All);
    let depth_out = if ctx.copies_depth {
        let out = Readback::new(ctx, w, h, 4);
        out.copy(&mut encoder, &depth, wgpu::TextureAspect::DepthOnly);
        out
    } else {
        // OpenGL ES cannot copy a depth texture: the passing fragment wrote its depth's bits to
        // an integer target. With writes on, that is what the depth buffer holds; with writes off the
        // buffer keeps its clear value (a driver writing it anyway would still show in the ids,
        // as later fragments would test against it).
        let out = Readback::new(ctx, w, h, 4);
        out.copy(&mut encoder, &depths, wgpu::TextureAspect::All);
        out
    };
    ctx.queue.submit([encoder.finish()]);
    let depths: Vec<f32> = depth_out.read::<f32>(ctx)?;
    let depths = if ctx.copies_depth || draw.state.depth.write {
        depths
    } else {
        vec![clear; depths.len()]
    };
    let primitives = ids_out
        .read::<u32>(ctx)?
        .into_iter()
        .map(|id| id.checked_sub(1))
        .collect();
    Ok(Resolve {
        depth: depths,
        primitive: primitives,
        timings: Timings {
            drawing,
            reading: started.elapsed(),
        },
    })
}

/// What the driver's depth test left, and how long drawing and reading it back took.
pub struct Resolve {
    /// The depth buffer, row by row.
    pub depth: Vec<f32>,
    /// The primitive that last passed the depth test at each pixel.
    pub primitive: Vec<Option<u32>>,
    /// How long the device drew, and how long reading back took.
    pub timings: Timings,
}
