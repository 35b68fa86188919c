//! The pass that unpacks a multisampled resolve: each pixel's samples of the id and depth
//! targets written out as the channels of two single-sample targets (`unpack.wgsl`), since a
//! multisampled texture cannot be copied to a buffer.

/// The two targets a multisampled resolve is unpacked into: four samples' ids, then their
/// depths' bits.
pub const UNPACKED: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
/// The most samples per pixel [`UNPACKED`] holds.
pub const MOST_SAMPLES: u8 = 4;

/// The pipeline of `unpack.wgsl`: a multisampled id and depth target in, two
/// [`UNPACKED`] targets out.
pub fn build(device: &wgpu::Device) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("unpack"),
        source: wgpu::ShaderSource::Wgsl(include_str!("unpack.wgsl").into()),
    });
    let texture = |binding, sample_type| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: true,
        },
        count: None,
    };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("unpack"),
        entries: &[
            texture(0, wgpu::TextureSampleType::Uint),
            texture(1, wgpu::TextureSampleType::Depth),
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("unpack"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let target = Some(wgpu::ColorTargetState::from(UNPACKED));
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("unpack"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("cover"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("unpack"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &[target.clone(), target],
        }),
        multiview_mask: None,
        cache: None,
    });
    (pipeline, layout)
}
