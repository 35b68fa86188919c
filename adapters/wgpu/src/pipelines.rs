//! The shaders and render pipelines of the passes, built once per draw state, topology and
//! sample count, and how this driver captures: into a storage buffer, or one primitive at a
//! time into float targets.

use std::collections::HashMap;

use refrast::{CompareOp, CullMode, DrawError, DrawState, FrontFace, PolygonMode, Topology};

/// Which pass a pipeline is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pass {
    /// Every covered sample appended to a storage buffer.
    Capture,
    /// The same at several samples per pixel, the fragment shader run once per sample.
    CaptureSamples,
    /// The same under centroid interpolation: run once a pixel, its inputs at the centroid,
    /// one fragment appended per covered sample.
    CaptureCentroid,
    /// One primitive's covered samples written to two float targets.
    CaptureTargets,
    /// The driver's depth test, primitive ids into an id target.
    Resolve,
}

/// How this driver's covered samples are read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// One draw, a fragment shader appending to a storage buffer.
    StorageBuffer,
    /// One pass per primitive into two `Rgba32Float` targets, for a driver whose fragment
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
    topology: Topology,
    samples: u8,
    unclipped: bool,
    /// The depth bias as wgpu takes it: the constant (an `i32`), the slope factor's and the
    /// clamp's bits; `None` unbiased.
    bias: Option<(i32, u32, u32)>,
    /// How triangles are drawn: filled, or as their edges or vertices (`PolygonMode`).
    polygon: PolygonMode,
    /// Whether the vertices carry clip distances (`clip_vertex.wgsl`).
    clip: bool,
    /// The sample mask, bit `i` for sample `i` (`DrawState::sample_mask`), as the draw gives it:
    /// its bits at and above the sample count mean nothing, but a driver that reads them is
    /// what the mask rules are there to see (lavapipe does at one sample), so they are not
    /// cleared here to share pipelines.
    mask: u32,
    /// Whether filled triangles are drawn conservatively (overestimation, no extra size).
    conservative: bool,
}

impl Key {
    /// The draw's state as a pipeline key for `pass`, drawing triangles at one sample; the
    /// captures run no depth test, so their keys leave the depth state out.
    pub fn new(pass: Pass, state: &DrawState) -> Self {
        let (compare, write) = match pass {
            Pass::Resolve => (state.depth.compare, state.depth.write),
            Pass::Capture | Pass::CaptureSamples | Pass::CaptureCentroid | Pass::CaptureTargets => {
                (CompareOp::Always, false)
            }
        };
        Self {
            pass,
            cull: state.cull,
            front_face: state.front_face,
            compare,
            write,
            topology: Topology::TriangleList,
            samples: 1,
            // Depth clipping off is both planes off (`Profile::fit` sends no other).
            unclipped: !state.clip_near,
            // `Gpu::check` refuses a constant that is not a whole i32.
            bias: state
                .depth_bias
                .map(|b| (b.constant as i32, b.slope.to_bits(), b.clamp.to_bits())),
            polygon: state.polygon_mode,
            clip: false,
            mask: state.sample_mask,
            conservative: state.conservative.is_some(),
        }
    }

    /// The same key with clip distances written by the vertex stage, or not.
    #[must_use]
    pub fn clipping(self, clip: bool) -> Self {
        Self { clip, ..self }
    }

    /// The same key drawing `topology` at `samples` samples per pixel.
    #[must_use]
    pub fn drawing(self, topology: Topology, samples: u8) -> Self {
        Self {
            topology,
            samples,
            // WebGPU biases triangles only, and refuses a bias on other topologies; refrast
            // biases none but triangles either.
            bias: self.bias.filter(|_| topology.is_triangles()),
            // Only a polygon has a polygon mode.
            polygon: if topology.is_triangles() {
                self.polygon
            } else {
                PolygonMode::Fill
            },
            // Only filled triangles are drawn conservatively (Vulkan, without
            // conservativePointAndLineRasterization).
            conservative: self.conservative && topology.is_triangles() && self.polygon == PolygonMode::Fill,
            ..self
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
/// The two targets of a per-primitive capture: barycentrics and depth, then facing.
pub const FLOATS: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The shaders, the capture bind group layout, and the pipelines built so far.
pub struct Pipelines {
    /// How covered samples are read back on this driver.
    pub method: Method,
    resolve_module: wgpu::ShaderModule,
    capture_module: wgpu::ShaderModule,
    targets_module: wgpu::ShaderModule,
    /// The per-sample capture's shaders, when built (on the first draw at several samples).
    samples_module: Option<wgpu::ShaderModule>,
    /// The centroid capture's shaders, when built (on the first centroid draw).
    centroid_module: Option<wgpu::ShaderModule>,
    /// The resolve's shaders run per sample, when built (on the first resolve at several
    /// samples): the same vertex stage and interpolation as the per-sample capture, so that
    /// the two passes differ only in what their fragment shaders write.
    samples_resolve_module: Option<wgpu::ShaderModule>,
    /// The vertex stages writing clip distances, interpolated at the pixel's centre, per
    /// sample and at the centroid ([`Sampling`]), when built (on the first draw with clip
    /// distances, which only a device with the feature gets).
    clip_modules: [Option<wgpu::ShaderModule>; 3],
    /// The unpacking of a multisampled resolve: its pipeline and bind group layout, when built.
    unpacking: Option<(wgpu::RenderPipeline, wgpu::BindGroupLayout)>,
    /// How far a strip's flat values are from its primitive's index, per strip topology: 0
    /// where a primitive's flat values come from its first vertex (Vulkan), its vertices less
    /// one from its last (OpenGL ES, which cannot choose); measured on the first strip drawn.
    pub strip_offsets: HashMap<Topology, u32>,
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
        let module = |label, extra: &str| shader(device, label, include_str!("varyings.wgsl"), extra);
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
            capture_module: module(
                "capture",
                &format!(
                    "{}\n{}",
                    include_str!("record.wgsl"),
                    include_str!("capture.wgsl")
                ),
            ),
            targets_module: module("capture targets", include_str!("targets.wgsl")),
            samples_module: None,
            centroid_module: None,
            samples_resolve_module: None,
            clip_modules: [None, None, None],
            unpacking: None,
            strip_offsets: HashMap::new(),
            layout,
            capture_layout,
            plain_layout,
            built: HashMap::new(),
        };
        // A driver that cannot compile the storage capture says so as an internal (shader
        // translation) or a validation error.
        if pipelines
            .get(device, Key::new(Pass::Capture, &DrawState::default()))
            .is_err()
        {
            pipelines.method = Method::FloatTargets;
        }
        pipelines
    }

    /// The pipeline for `key`, built on first use; `Err` with the device's message when it
    /// cannot be built (a driver lacking what a topology or sample count needs).
    pub fn get(&mut self, device: &wgpu::Device, key: Key) -> Result<&wgpu::RenderPipeline, DrawError> {
        if !self.built.contains_key(&key) {
            if primitive_topology(key.topology).is_none() {
                return Err(DrawError::Unsupported(format!("WebGPU has no {}", key.topology)));
            }
            let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
            let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
            if key.pass == Pass::CaptureSamples && self.samples_module.is_none() {
                self.samples_module = Some(shader(
                    device,
                    "capture samples",
                    include_str!("varyings_sample.wgsl"),
                    &format!(
                        "{}\n{}",
                        include_str!("record.wgsl"),
                        include_str!("multisample.wgsl")
                    ),
                ));
            }
            if key.pass == Pass::CaptureCentroid && self.centroid_module.is_none() {
                self.centroid_module = Some(shader(
                    device,
                    "capture centroid",
                    include_str!("varyings_centroid.wgsl"),
                    &format!(
                        "{}\n{}",
                        include_str!("record.wgsl"),
                        include_str!("centroid.wgsl")
                    ),
                ));
            }
            if key.pass == Pass::Resolve && key.samples > 1 && self.samples_resolve_module.is_none() {
                self.samples_resolve_module = Some(shader(
                    device,
                    "resolve samples",
                    include_str!("varyings_sample.wgsl"),
                    "",
                ));
            }
            let sampling = Sampling::of(key);
            if key.clip && self.clip_modules[sampling as usize].is_none() {
                let (perspective, linear) = match sampling {
                    Sampling::Centre => ("perspective, center", "linear"),
                    Sampling::Sample => ("perspective, sample", "linear, sample"),
                    Sampling::Centroid => ("perspective, centroid", "linear, centroid"),
                };
                self.clip_modules[sampling as usize] = Some(
                    device.create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some("clip distances"),
                        source: wgpu::ShaderSource::Wgsl(
                            include_str!("clip_vertex.wgsl")
                                .replace("PERSPECTIVE", perspective)
                                .replace("LINEAR", linear)
                                .into(),
                        ),
                    }),
                );
            }
            let pipeline = self.build(device, key);
            let failed = [
                pollster::block_on(internal.pop()),
                pollster::block_on(validation.pop()),
            ];
            if let Some(e) = failed.into_iter().flatten().next() {
                return Err(DrawError::Backend(format!(
                    "the driver could not build the pipeline for {} at {} samples: {e:?}",
                    key.topology, key.samples
                )));
            }
            self.built.insert(key, pipeline);
        }
        Ok(&self.built[&key])
    }

    /// The pipeline unpacking a multisampled resolve, and its bind group layout (the ids, then
    /// the depths), built on first use.
    pub fn unpack(&mut self, device: &wgpu::Device) -> &(wgpu::RenderPipeline, wgpu::BindGroupLayout) {
        self.unpacking.get_or_insert_with(|| crate::unpack::build(device))
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
            Pass::CaptureSamples => (
                self.samples_module.as_ref().unwrap_or(&self.capture_module),
                &self.capture_layout,
                "capture_samples",
                vec![],
                always,
            ),
            Pass::CaptureCentroid => (
                self.centroid_module.as_ref().unwrap_or(&self.capture_module),
                &self.capture_layout,
                "capture_centroid",
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
                match (key.samples, &self.samples_resolve_module) {
                    (2.., Some(module)) => module,
                    _ => &self.resolve_module,
                },
                &self.plain_layout,
                "resolve",
                vec![
                    Some(wgpu::ColorTargetState::from(IDS)),
                    Some(wgpu::ColorTargetState::from(DEPTHS)),
                ],
                (compare_function(key.compare), key.write),
            ),
        };
        let (corners, strip) = match key.topology {
            Topology::TriangleList | Topology::TriangleFan => (3.0, 0.0),
            Topology::TriangleStrip => (3.0, 1.0),
            Topology::LineList => (2.0, 0.0),
            Topology::LineStrip => (2.0, 1.0),
            Topology::PointList => (1.0, 0.0),
        };
        let constants = [("corners", corners), ("strip", strip)];
        // Lines and points have no face to cull.
        let cull = if key.topology.is_triangles() {
            cull_mode(key.cull)
        } else {
            None
        };
        let positions = Some(wgpu::VertexBufferLayout {
            array_stride: 16,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![0 => Float32x4],
        });
        let distances = Some(wgpu::VertexBufferLayout {
            array_stride: 32,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![1 => Float32x4, 2 => Float32x4],
        });
        // `get` built the clip module before a key with clip distances gets here.
        let clip_module = self.clip_modules[Sampling::of(key) as usize]
            .as_ref()
            .filter(|_| key.clip);
        let (vertex_module, buffers) = match clip_module {
            Some(clip) => (clip, vec![positions, distances]),
            None => (module, vec![positions]),
        };
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(entry),
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module: vertex_module,
                entry_point: Some("vertex"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..wgpu::PipelineCompilationOptions::default()
                },
                buffers: &buffers,
            },
            primitive: wgpu::PrimitiveState {
                // `get` refuses a topology WebGPU lacks before building.
                topology: primitive_topology(key.topology).unwrap_or_default(),
                front_face: front_face(key.front_face),
                cull_mode: cull,
                unclipped_depth: key.unclipped,
                // The device has the feature where the profile declares the mode.
                polygon_mode: match key.polygon {
                    PolygonMode::Fill => wgpu::PolygonMode::Fill,
                    PolygonMode::Line => wgpu::PolygonMode::Line,
                    PolygonMode::Point => wgpu::PolygonMode::Point,
                },
                conservative: key.conservative,
                ..wgpu::PrimitiveState::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(depth.1),
                depth_compare: Some(depth.0),
                stencil: wgpu::StencilState::default(),
                bias: key
                    .bias
                    .map_or_else(wgpu::DepthBiasState::default, |(constant, slope, clamp)| {
                        wgpu::DepthBiasState {
                            constant,
                            slope_scale: f32::from_bits(slope),
                            clamp: f32::from_bits(clamp),
                        }
                    }),
            }),
            multisample: wgpu::MultisampleState {
                count: u32::from(key.samples),
                // Every pass masks, the captures too: a masked sample makes no fragment. No
                // mask is wgpu's default, all 64 bits set.
                mask: if key.mask == DrawState::ALL_SAMPLES {
                    u64::MAX
                } else {
                    u64::from(key.mask)
                },
                ..wgpu::MultisampleState::default()
            },
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..wgpu::PipelineCompilationOptions::default()
                },
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}

/// Where a pipeline's fragment stage reads its inputs, which picks its `varyings*.wgsl` and
/// its clip-distance vertex stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sampling {
    /// At the pixel's centre, once a pixel (one sample per pixel).
    Centre,
    /// At each sample, once a sample (`varyings_sample.wgsl`).
    Sample,
    /// At the pixel's centroid, once a pixel (`varyings_centroid.wgsl`).
    Centroid,
}

impl Sampling {
    /// Where `key`'s fragment stage reads its inputs.
    fn of(key: Key) -> Self {
        match key.pass {
            Pass::CaptureSamples => Self::Sample,
            Pass::CaptureCentroid => Self::Centroid,
            Pass::Resolve if key.samples > 1 => Self::Sample,
            _ => Self::Centre,
        }
    }
}

/// A shader module of `varyings`, `shaders.wgsl`, then `extra`.
fn shader(device: &wgpu::Device, label: &str, varyings: &str, extra: &str) -> wgpu::ShaderModule {
    let source = format!("{varyings}\n{}\n{extra}", include_str!("shaders.wgsl"));
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    })
}

/// The API's topology for refrast's; `None` for a triangle fan, which WebGPU does not have.
fn primitive_topology(topology: Topology) -> Option<wgpu::PrimitiveTopology> {
    Some(match topology {
        Topology::TriangleList => wgpu::PrimitiveTopology::TriangleList,
        Topology::TriangleStrip => wgpu::PrimitiveTopology::TriangleStrip,
        Topology::LineList => wgpu::PrimitiveTopology::LineList,
        Topology::LineStrip => wgpu::PrimitiveTopology::LineStrip,
        Topology::PointList => wgpu::PrimitiveTopology::PointList,
        Topology::TriangleFan => return None,
    })
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
        // wgpu has no face for both: `Gpu::check_target` refuses such a draw before any
        // pipeline is built, as its profile does not declare it.
        CullMode::FrontAndBack => None,
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
