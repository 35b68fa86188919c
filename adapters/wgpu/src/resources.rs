//! What every pass needs: the draw as a vertex list, render targets, the depth attachment, and
//! reading textures and buffers back to the CPU.

use bytemuck::Pod;
use refrast::{Draw, DrawError, Fragment, Topology, Viewport};
use wgpu::util::DeviceExt;

use crate::device::Context;

/// The vertex buffers of a draw: its positions ([`vertex_list`]) and, where it has clip
/// distances, eight per vertex beside them (those it lacks at 1, inside), as `clip_vertex.wgsl`
/// reads them.
pub struct VertexBuffers {
    positions: wgpu::Buffer,
    distances: Option<wgpu::Buffer>,
    /// How many vertices are drawn.
    pub count: u32,
}

impl VertexBuffers {
    /// The buffers of `draw` on `ctx`'s device.
    pub fn new(ctx: &Context, draw: &Draw) -> Self {
        let buffer = |label, contents: &[u8]| {
            ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::VERTEX,
            })
        };
        let vertices = vertex_list(draw);
        let d = &draw.distances;
        let distances = (d.clip > 0).then(|| {
            let values: Vec<[f32; 8]> = draw
                .indices
                .iter()
                .map(|&i| {
                    let mut row = [1.0; 8];
                    row[..d.clip.min(8)].copy_from_slice(&d.clip_of(i)[..d.clip.min(8)]);
                    row
                })
                .collect();
            buffer("clip distances", bytemuck::cast_slice(&values))
        });
        Self {
            positions: buffer("vertices", bytemuck::cast_slice(&vertices)),
            distances,
            count: vertices.len() as u32,
        }
    }

    /// Binds them to `pass`: the positions at slot 0, the distances at slot 1.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.positions.slice(..));
        if let Some(distances) = &self.distances {
            pass.set_vertex_buffer(1, distances.slice(..));
        }
    }
}

/// The draw's indices as a plain vertex list, in order, for the draw's topology without an
/// index buffer: vertex `i` of a list is corner `i % n` of primitive `i / n` (`n` the
/// primitive's vertices); of a strip, vertex `i` starts segment `i`. A draw the adapter has
/// validated indexes within `positions`.
pub fn vertex_list(draw: &Draw) -> Vec<[f32; 4]> {
    draw.indices.iter().map(|&i| draw.positions[i as usize]).collect()
}

/// A fragment's barycentrics as the contract orders them: vertex `i` of a strip is corner
/// `i % 2` of a line strip, `i % 3` of a triangle strip (`shaders.wgsl`), so an odd segment
/// starts at corner 1 and has its weights swapped, and a triangle's weights are gathered in
/// [`Draw::triangle`](refrast::Draw::triangle)'s order.
pub fn along(topology: Topology, mut f: Fragment) -> Fragment {
    if topology == Topology::LineStrip && f.primitive % 2 == 1 {
        f.barycentric.swap(0, 1);
        if let Some(s) = f.screen_barycentric.as_mut() {
            s.swap(0, 1);
        }
    }
    if topology == Topology::TriangleStrip {
        let i = f.primitive as usize;
        let odd = i % 2;
        // The corners of triangle i's vertices i, i + 1 + odd, i + 2 − odd.
        let corners = [i, i + 1 + odd, i + 2 - odd].map(|v| v % 3);
        f.barycentric = corners.map(|c| f.barycentric[c]);
        f.screen_barycentric = f.screen_barycentric.map(|s| corners.map(|c| s[c]));
    }
    f
}

/// A texture of the viewport's size at `samples` samples per pixel: copied back at one, read by
/// a shader (`unpack.wgsl`) at several.
pub fn target(ctx: &Context, viewport: Viewport, format: wgpu::TextureFormat, samples: u8) -> wgpu::Texture {
    let read = if samples == 1 {
        wgpu::TextureUsages::COPY_SRC
    } else {
        wgpu::TextureUsages::TEXTURE_BINDING
    };
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("target"),
        size: wgpu::Extent3d {
            width: viewport.width(),
            height: viewport.height(),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: u32::from(samples),
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | read,
        view_formats: &[],
    })
}

/// A depth attachment cleared to `clear`, kept when `store`.
pub fn depth_attachment(
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

/// Maps a staging buffer after the queue has finished, and copies it out.
pub fn map(ctx: &Context, staging: &wgpu::Buffer) -> Result<Vec<u8>, DrawError> {
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

/// A staging buffer a texture is copied into, and read back from row by row.
pub struct Readback {
    buffer: wgpu::Buffer,
    /// Bytes per row in the buffer: a copy pads rows to 256 bytes.
    row: u32,
    pixel: u32,
    width: u32,
    height: u32,
}

impl Readback {
    /// Room for a `width`×`height` texture of `pixel` bytes a texel.
    pub fn new(ctx: &Context, width: u32, height: u32, pixel: u32) -> Self {
        let row = (pixel * width).div_ceil(256) * 256;
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(row) * u64::from(height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            buffer,
            row,
            pixel,
            width,
            height,
        }
    }

    /// Records a copy of `texture` (its `aspect`) into the buffer.
    pub fn copy(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
        aspect: wgpu::TextureAspect,
    ) {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// The texels, row after row, once the copy's submission has finished.
    pub fn read<T: Pod>(&self, ctx: &Context) -> Result<Vec<T>, DrawError> {
        let bytes = map(ctx, &self.buffer)?;
        let used = (self.pixel * self.width) as usize;
        Ok((0..self.height as usize)
            .flat_map(|y| {
                let start = y * self.row as usize;
                bytemuck::pod_collect_to_vec::<u8, T>(&bytes[start..start + used])
            })
            .collect())
    }
}

/// The draw's scissor rectangle on `pass`, cut to the target, as wgpu requires of a rectangle
/// (what lies past the target passes nothing there anyway), none leaving the whole target; and
/// its viewport's depth range, over the whole target (wgpu's default viewport, with
/// `min_depth ≤ max_depth`: `Profile::fit` sends no other).
pub fn set_scissor(pass: &mut wgpu::RenderPass<'_>, draw: &Draw) {
    let depth = draw.state.viewport_depth;
    if depth != refrast::ViewportDepth::FULL {
        let (w, h) = (draw.viewport.width() as f32, draw.viewport.height() as f32);
        pass.set_viewport(0.0, 0.0, w, h, depth.min, depth.max);
    }
    if let Some(s) = draw.state.scissor {
        let (w, h) = (draw.viewport.width(), draw.viewport.height());
        let (x, y) = (s.x.min(w), s.y.min(h));
        pass.set_scissor_rect(x, y, s.width.min(w - x), s.height.min(h - y));
    }
}
