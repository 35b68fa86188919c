//! The shaders and render pipelines of the three passes, built once per draw state, and how
//! this driver captures: into a storage buffer, or one triangle at a time into float targets.

use std::collections::HashMap;

use refrast::{CompareOp, CullMode, DrawState, FrontFace};

/// Which pass a pipeline is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pass {
    /// Every covered sample appended to a storage buffer.
    Capture,
    /// One triangle's covered samples written to two float targets.
    CaptureTargets,
    /// The driver's depth test, primitive ids into an id target.
    Resolve,
}

/// How this driver's covered samples are read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// One draw, a fragment shader appending to a storage buffer.
    StorageBuffer,
    /// One pass per triangle into two `Rgba32Float` targets, for a driver whose fragment
    /// shaders cannot write storage buffers (softpipe's OpenGL ES).
    FloatTargets,
}

/// The state a pipeline is built for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Key {
    pass: Pass,
    cull: CullMode,
    front_face: FrontFace,
    compare: CompareOp,
    write: bool,
}

impl Key {
    /// The draw's state as a pipeline key for `pass`; the captures run no depth test, so
    /// their keys leave the depth state out.
    pub fn new(pass: Pass, state: &DrawState) -> Self {
        let (compare, write) = match pass {
            Pass::Resolve => (state.depth.compare, state.depth.write),
            Pass::Capture | Pass::CaptureTargets => (CompareOp::Always, false),
        };
        Self {
            pass,
            cull: state.cull,
            front_face: state.front_face,
            compare,
            write,
        }
    }
}

/// The depth format of every pass.
pub const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The id target of the resolve pass.
pub const IDS: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// The resolve pass's copy of the passing fragment's depth (its f32 bits), for backends that
/// cannot copy a depth texture; integer because wgpu's OpenGL ES backend renders to no float
/// format without an extension.
pub const DEPTHS: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// The two targets of a per-triangle capture: barycentrics and depth, then facing.
pub const FLOATS: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The shaders, the capture bind group layout, and the pipelines built so far.
pub struct Pipelines {
    /// How covered samples are read back on this driver.
    pub method: Method,
    resolve_module: wgpu::ShaderModule,
    capture_module: wgpu::ShaderModule,
    targets_module: wgpu::ShaderModule,
    /// The capture pass's bind group layout: the count, then the samples.
    pub layout: wgpu::BindGroupLayout,
    capture_layout: wgpu::PipelineLayout,
    plain_layout: wgpu::PipelineLayout,
    built: HashMap<Key, wgpu::RenderPipeline>,
}

impl Pipelines {
    /// Compiles the shaders on `device`, and finds out whether its fragment shaders can write
    /// storage buffers by building that capture pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let module = |label, extra: &str| {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(format!("{}\n{extra}", include_str!("shaders.wgsl")).into()),
            })
        };
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
        let plain_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("resolve"),
            bind_group_layouts: &[],
            immediate_size: 0,
        });
        let mut pipelines = Self {
            method: Method::StorageBuffer,
            resolve_module: module("resolve", ""),
            capture_module: module("capture", include_str!("capture.wgsl")),
            targets_module: module("capture targets", include_str!("targets.wgsl")),
            layout,
            capture_layout,
            plain_layout,
            built: HashMap::new(),
        };
        // A driver that cannot compile the storage capture says so as an internal (shader
        // translation) or a validation error.
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
        let probe = Key::new(Pass::Capture, &DrawState::default());
        let built = pipelines.build(device, probe);
        let failed = pollster::block_on(internal.pop()).is_some();
        if !(pollster::block_on(validation.pop()).is_some() || failed) {
            pipelines.built.insert(probe, built);
        } else {
            pipelines.method = Method::FloatTargets;
        }
        pipelines
    }

    /// The pipeline for `key`, built on first use.
    pub fn get(&mut self, device: &wgpu::Device, key: Key) -> &wgpu::RenderPipeline {
        if !self.built.contains_key(&key) {
            let pipeline = self.build(device, key);
            self.built.insert(key, pipeline);
        }
        &self.built[&key]
    }

    /// Builds the pipeline for `key`.
    fn build(&self, device: &wgpu::Device, key: Key) -> wgpu::RenderPipeline {
        let floats = Some(wgpu::ColorTargetState::from(FLOATS));
        // Captures run no depth test: every covered sample reaches the shader.
        let always = (wgpu::CompareFunction::Always, false);
        let (module, layout, entry, targets, depth) = match key.pass {
            Pass::Capture => (
                &self.capture_module,
                &self.capture_layout,
                "capture",
                vec![],
                always,
            ),
            Pass::CaptureTargets => (
                &self.targets_module,
                &self.plain_layout,
                "capture_targets",
                vec![floats.clone(), floats],
                always,
            ),
            Pass::Resolve => (
                &self.resolve_module,
                &self.plain_layout,
                "resolve",
                vec![
                    Some(wgpu::ColorTargetState::from(IDS)),
                    Some(wgpu::ColorTargetState::from(DEPTHS)),
                ],
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
    }
}

/// The API's front face for refrast's. Both name the turn as seen on screen (framebuffer
/// coordinates, y down); `tests/drivers.rs` checks it on a
/// counter-clockwise triangle under each front face.
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
