//! The two render passes: capture (every covered sample into a storage buffer) and resolve
//! (the driver's own depth test into a depth and an id target), and reading them back.

use std::collections::HashMap;

use bytemuck::{Pod, Zeroable};
use refrast::{CompareOp, CullMode, Draw, DrawError, DrawState, Fragment, FrontFace};
use wgpu::util::DeviceExt;

use crate::device::Context;

/// One covered sample as the capture shader writes it (`Sample` in `shaders.wgsl`).
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

/// Which of the two passes a pipeline is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Pass {
    Capture,
    Resolve,
}

/// The state a pipeline is built for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Key {
    pass: Pass,
    cull: CullMode,
    front_face: FrontFace,
    compare: CompareOp,
    write: bool,
}

/// The shaders, the capture pass's bind group layout and the pipelines built so far.
pub struct Pipelines {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    capture_layout: wgpu::PipelineLayout,
    resolve_layout: wgpu::PipelineLayout,
    built: HashMap<Key, wgpu::RenderPipeline>,
}

/// The depth format of both passes.
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The id target of the resolve pass.
const IDS: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

impl Pipelines {
    /// Compiles the shaders on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("refrast shaders"),
            source: wgpu::ShaderSource::Wgsl(include_str!("shaders.wgsl").into()),
        });
        let storage = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: false },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("capture"),
            entries: &[storage(0), storage(1)],
        });
        let capture_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("capture"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let resolve_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("resolve"),
            bind_group_layouts: &[],
            immediate_size: 0,
        });
        Self {
            module,
            layout,
            capture_layout,
            resolve_layout,
            built: HashMap::new(),
        }
    }

    /// The pipeline for `key`, built on first use.
    fn get(&mut self, device: &wgpu::Device, key: Key) -> &wgpu::RenderPipeline {
        let Self {
            module,
            capture_layout,
            resolve_layout,
            built,
            ..
        } = self;
        built.entry(key).or_insert_with(|| {
            let (layout, entry, targets, depth) = match key.pass {
                // No depth test and no colour: every covered sample reaches the shader.
                Pass::Capture => (
                    &*capture_layout,
                    "capture",
                    vec![],
                    (wgpu::CompareFunction::Always, false),
                ),
                Pass::Resolve => (
                    &*resolve_layout,
                    "resolve",
                    vec![Some(wgpu::ColorTargetState::from(IDS))],
                    (compare_function(key.compare), key.write),
                ),
            };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(entry),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some("vertex"),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: 16,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &wgpu::vertex_attr_array![0 => Float32x4],
                    })],
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    front_face: front_face(key.front_face),
                    cull_mode: cull_mode(key.cull),
                    ..wgpu::PrimitiveState::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH,
                    depth_write_enabled: Some(depth.1),
                    depth_compare: Some(depth.0),
                    stencil: wgpu::StencilState::default(),
                    bias: wgpu::DepthBiasState::default(),
                }),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(entry),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })
    }
}

/// The draw's triangles as a plain vertex list (three per triangle, in order): vertex `i` of
/// the list is corner `i % 3` of primitive `i / 3`.
fn vertex_list(draw: &Draw) -> Vec<[f32; 4]> {
    draw.triangles
        .iter()
        .flat_map(|t| t.map(|i| draw.positions[i as usize]))
        .collect()
}

/// The draw's state as a pipeline key for `pass`.
fn key(pass: Pass, state: &DrawState) -> Key {
    Key {
        pass,
        cull: state.cull,
        front_face: state.front_face,
        compare: state.depth.compare,
        write: state.depth.write,
    }
}

/// The API's front face for refrast's. Both name the turn as seen on screen (framebuffer
/// coordinates, y down); `tests/gpu.rs` checks it on a triangle of each turn.
fn front_face(face: FrontFace) -> wgpu::FrontFace {
    match face {
        FrontFace::CounterClockwise => wgpu::FrontFace::Ccw,
        FrontFace::Clockwise => wgpu::FrontFace::Cw,
    }
}

fn cull_mode(cull: CullMode) -> Option<wgpu::Face> {
    match cull {
        CullMode::None => None,
        CullMode::Front => Some(wgpu::Face::Front),
        CullMode::Back => Some(wgpu::Face::Back),
    }
}

fn compare_function(op: CompareOp) -> wgpu::CompareFunction {
    match op {
        CompareOp::Never => wgpu::CompareFunction::Never,
        CompareOp::Less => wgpu::CompareFunction::Less,
        CompareOp::Equal => wgpu::CompareFunction::Equal,
        CompareOp::LessOrEqual => wgpu::CompareFunction::LessEqual,
        CompareOp::Greater => wgpu::CompareFunction::Greater,
        CompareOp::NotEqual => wgpu::CompareFunction::NotEqual,
        CompareOp::GreaterOrEqual => wgpu::CompareFunction::GreaterEqual,
        CompareOp::Always => wgpu::CompareFunction::Always,
    }
}

/// A texture of the viewport's size.
fn target(ctx: &Context, draw: &Draw, format: wgpu::TextureFormat) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("target"),
        size: wgpu::Extent3d {
            width: draw.viewport.width(),
            height: draw.viewport.height(),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// A depth attachment cleared to `clear`, kept when `store`.
fn depth_attachment(
    view: &wgpu::TextureView,
    clear: f32,
    store: bool,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(clear),
            store: if store {
                wgpu::StoreOp::Store
            } else {
                wgpu::StoreOp::Discard
            },
        }),
        stencil_ops: None,
    }
}

/// Every covered sample of every triangle of `draw`, as the driver rasterized them.
pub fn capture(ctx: &Context, pipelines: &mut Pipelines, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    if draw.triangles.is_empty() {
        return Ok(Vec::new());
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

fn fragment(s: &RawSample) -> Fragment {
    Fragment {
        x: s.x,
        y: s.y,
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
    let pipeline = pipelines.get(device, key(Pass::Capture, &draw.state));
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

/// Maps a staging buffer after the queue has finished, and copies it out.
fn map(ctx: &Context, staging: &wgpu::Buffer) -> Result<Vec<u8>, DrawError> {
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| DrawError::Backend(format!("the device did not finish: {e}")))?;
    rx.recv()
        .map_err(|_| DrawError::Backend("the buffer was never mapped".into()))?
        .map_err(|e| DrawError::Backend(format!("the buffer could not be mapped: {e}")))?;
    let bytes = slice
        .get_mapped_range()
        .map_err(|e| DrawError::Backend(format!("the mapped buffer could not be read: {e}")))?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}

/// The driver's depth test: the depth buffer and the id of the last fragment that passed.
pub fn resolve(
    ctx: &Context,
    pipelines: &mut Pipelines,
    draw: &Draw,
) -> Result<(Vec<f32>, Vec<Option<u32>>), DrawError> {
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let clear = draw.state.depth.clear;
    if draw.triangles.is_empty() {
        return Ok((
            vec![clear; draw.viewport.pixel_count()],
            vec![None; draw.viewport.pixel_count()],
        ));
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
    let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
    let ids_view = ids.create_view(&wgpu::TextureViewDescriptor::default());
    let pipeline = pipelines.get(device, key(Pass::Resolve, &draw.state));
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("resolve"),
    });
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("resolve"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &ids_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(depth_attachment(&depth_view, clear, true)),
            ..wgpu::RenderPassDescriptor::default()
        });
        pass.set_pipeline(pipeline);
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
    // Rows are padded to 256 bytes in a copy; both formats take 4 bytes a pixel.
    let row = (4 * w).div_ceil(256) * 256;
    let staging = |label| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: u64::from(row) * u64::from(h),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    };
    let (depth_out, ids_out) = (staging("depth"), staging("ids"));
    let copy = |encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture, aspect, out: &wgpu::Buffer| {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: out,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
    };
    copy(&mut encoder, &depth, wgpu::TextureAspect::DepthOnly, &depth_out);
    copy(&mut encoder, &ids, wgpu::TextureAspect::All, &ids_out);
    ctx.queue.submit([encoder.finish()]);
    let (depth_bytes, id_bytes) = (map(ctx, &depth_out)?, map(ctx, &ids_out)?);
    let rows = |bytes: &[u8]| -> Vec<u32> {
        (0..h as usize)
            .flat_map(|y| {
                let start = y * row as usize;
                bytemuck::pod_collect_to_vec::<u8, u32>(&bytes[start..start + 4 * w as usize])
            })
            .collect()
    };
    let depths = rows(&depth_bytes).into_iter().map(f32::from_bits).collect();
    let primitives = rows(&id_bytes).into_iter().map(|id| id.checked_sub(1)).collect();
    Ok((depths, primitives))
}
