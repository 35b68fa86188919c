//! The pipeline on top of the reference: vertices with attributes, model-view-projection,
//! a fragment-shading hook, a framebuffer with RGBA8 colour and f32 depth, PNG output.

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::draw::{Draw, Fragment};
use crate::error::{ConfigError, DrawError};
use crate::primitive::Topology;
use crate::reference::{DrawStats, Reference};
use crate::state::DrawState;
use crate::viewport::Viewport;

/// A vertex with the attributes the labs use.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Vertex {
    /// Model-space position.
    pub position: Vec3,
    /// Linear RGBA colour in `[0, 1]`.
    pub color: Vec4,
    /// Model-space normal.
    pub normal: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
}

impl Vertex {
    /// A vertex with a position and an opaque RGB colour.
    #[must_use]
    pub fn colored(position: Vec3, rgb: Vec3) -> Self {
        Self {
            position,
            color: rgb.extend(1.0),
            ..Self::default()
        }
    }
}

/// An indexed triangle mesh.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Mesh {
    /// The vertices.
    pub vertices: Vec<Vertex>,
    /// Three vertex indices per triangle.
    pub triangles: Vec<[u32; 3]>,
}

/// What the shading hook sees at a fragment: attributes interpolated perspective-correctly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadeInput {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Window depth.
    pub depth: f32,
    /// Triangle index in the mesh.
    pub primitive: u32,
    /// Whether the triangle faces the viewer.
    pub front_facing: bool,
    /// World-space position.
    pub position: Vec3,
    /// Interpolated colour.
    pub color: Vec4,
    /// Interpolated world-space normal (not renormalised).
    pub normal: Vec3,
    /// Interpolated texture coordinates.
    pub uv: Vec2,
}

/// A colour buffer (RGBA8) and a depth buffer (f32) of one size.
///
/// The buffers are reachable as slices only, so they always hold `width × height` pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    viewport: Viewport,
    color: Vec<[u8; 4]>,
    depth: Vec<f32>,
}

impl Framebuffer {
    /// A framebuffer cleared to opaque black and depth 1.0.
    pub fn new(width: u32, height: u32) -> Result<Self, ConfigError> {
        let viewport = Viewport::new(width, height)?;
        Ok(Self {
            viewport,
            color: vec![[0, 0, 0, 255]; viewport.pixel_count()],
            depth: vec![1.0; viewport.pixel_count()],
        })
    }

    /// Its size as a viewport.
    #[must_use]
    pub fn viewport(&self) -> Viewport {
        self.viewport
    }

    /// Fills colour and depth.
    pub fn clear(&mut self, color: [u8; 4], depth: f32) {
        self.color.fill(color);
        self.depth.fill(depth);
    }

    /// The colour at `(x, y)`, or `None` outside the buffer.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        (x < self.viewport.width() && y < self.viewport.height())
            .then(|| self.color[self.viewport.index(x, y)])
    }

    /// Row-major RGBA8 pixels.
    #[must_use]
    pub fn color(&self) -> &[[u8; 4]] {
        &self.color
    }

    /// Row-major RGBA8 pixels, to write.
    pub fn color_mut(&mut self) -> &mut [[u8; 4]] {
        &mut self.color
    }

    /// Row-major depth values.
    #[must_use]
    pub fn depth(&self) -> &[f32] {
        &self.depth
    }

    /// Row-major depth values, to write.
    pub fn depth_mut(&mut self) -> &mut [f32] {
        &mut self.depth
    }

    /// Colour and depth at once, to write both: for a rasterizer that depth-tests and shades as
    /// it goes, straight into the buffers.
    pub fn color_and_depth_mut(&mut self) -> (&mut [[u8; 4]], &mut [f32]) {
        (&mut self.color, &mut self.depth)
    }

    /// The colour buffer as an image (feature `png`, on by default).
    #[cfg(feature = "png")]
    #[must_use]
    pub fn to_image(&self) -> image::RgbaImage {
        let raw = self.color.iter().flatten().copied().collect();
        image::RgbaImage::from_raw(self.viewport.width(), self.viewport.height(), raw)
            .expect("the buffer holds width × height RGBA pixels by construction")
    }

    /// Writes the colour buffer as a PNG (feature `png`, on by default).
    #[cfg(feature = "png")]
    pub fn save_png(&self, path: impl AsRef<std::path::Path>) -> Result<(), image::ImageError> {
        self.to_image().save_with_format(path, image::ImageFormat::Png)
    }
}

/// Linear `[0, 1]` colour to RGBA8, clamped and rounded to nearest.
#[must_use]
#[inline]
pub fn to_rgba8(c: Vec4) -> [u8; 4] {
    let c = (c.clamp(Vec4::ZERO, Vec4::ONE) * 255.0).round();
    [c.x as u8, c.y as u8, c.z as u8, c.w as u8]
}

/// Draws meshes and lines with the reference: transform, rasterize, depth-test, shade, write.
#[derive(Clone, Debug, Default)]
pub struct Renderer {
    /// The rasterizer.
    pub reference: Reference,
    /// Culling, depth and clipping state of every draw.
    pub state: DrawState,
}

impl Renderer {
    /// Draws `mesh` with `model` then `view_projection`, colouring fragments with `shader`.
    ///
    /// The shader returns a linear colour, or `None` to discard the fragment (no depth write).
    pub fn draw_mesh(
        &self,
        target: &mut Framebuffer,
        mesh: &Mesh,
        model: Mat4,
        view_projection: Mat4,
        shader: impl Fn(&ShadeInput) -> Option<Vec4>,
    ) -> Result<DrawStats, DrawError> {
        let mvp = view_projection * model;
        let normal_matrix = model.inverse().transpose();
        // Per vertex, once per draw: world position and normal, with colour and uv, to mix per fragment.
        let world: Vec<(Vec3, Vec3)> = mesh
            .vertices
            .iter()
            .map(|v| {
                (
                    model.transform_point3(v.position),
                    normal_matrix.transform_vector3(v.normal),
                )
            })
            .collect();
        let draw = self.mesh_draw(target.viewport, mesh, mvp);
        let depth_state = self.state.depth;
        self.reference.draw_samples(&draw, |sample| {
            let i = target.viewport.index(sample.x, sample.y);
            // Early depth test: most fragments of a deep scene stop here, before any interpolation.
            if !depth_state.compare.passes(sample.depth, target.depth[i]) {
                return;
            }
            let f = sample.fragment();
            let [a, b, c] = mesh.triangles[f.primitive as usize].map(|k| k as usize);
            let [ba, bb, bc] = f.barycentric;
            let (va, vb, vc) = (&mesh.vertices[a], &mesh.vertices[b], &mesh.vertices[c]);
            let input = ShadeInput {
                x: f.x,
                y: f.y,
                depth: f.depth,
                primitive: f.primitive,
                front_facing: f.front_facing,
                position: world[a].0 * ba + world[b].0 * bb + world[c].0 * bc,
                color: va.color * ba + vb.color * bb + vc.color * bc,
                normal: world[a].1 * ba + world[b].1 * bb + world[c].1 * bc,
                uv: va.uv * ba + vb.uv * bb + vc.uv * bc,
            };
            if let Some(color) = shader(&input) {
                if depth_state.write {
                    target.depth[i] = f.depth;
                }
                target.color[i] = to_rgba8(color);
            }
        })
    }

    /// The clip-space draw of `mesh` under `mvp` with this renderer's state.
    #[must_use]
    pub fn mesh_draw(&self, viewport: Viewport, mesh: &Mesh, mvp: Mat4) -> Draw {
        Draw {
            state: self.state,
            ..Draw::new(
                viewport,
                mesh.vertices
                    .iter()
                    .map(|v| (mvp * v.position.extend(1.0)).to_array())
                    .collect(),
                mesh.triangles.clone(),
            )
        }
    }

    /// Draws each vertex as a point of size one through the reference's point rasterization
    /// (the path `point.*` certifies), in its colour: the pixel whose centre its one-pixel
    /// square holds (on a pixel corner, the one above and to the left under top-left).
    ///
    /// A point outside the clip volume (behind the eye, before the near plane, beyond the far
    /// plane when enabled, or not finite) is not drawn; the depth test applies. Returns the
    /// number of pixels that passed.
    pub fn draw_points(&self, target: &mut Framebuffer, vertices: &[Vertex], mvp: Mat4) -> usize {
        let indices = (0..vertices.len() as u32).collect();
        self.draw_topology(target, vertices, Topology::PointList, indices, mvp, |f| {
            vertices[f.primitive as usize].color
        })
    }

    /// Draws line segments between mesh vertices through the reference's line rasterization
    /// (the diamond-exit rule `line.*` certifies), colour interpolated perspective-correctly.
    ///
    /// Segments are clipped in clip space at the near plane, the guard band (and far when
    /// enabled); a segment naming a vertex that does not exist is skipped; the depth test
    /// applies. Returns the number of pixels that passed.
    pub fn draw_lines(
        &self,
        target: &mut Framebuffer,
        vertices: &[Vertex],
        segments: &[[u32; 2]],
        mvp: Mat4,
    ) -> usize {
        let n = vertices.len();
        let kept: Vec<[u32; 2]> = segments
            .iter()
            .copied()
            .filter(|s| s.iter().all(|&i| (i as usize) < n))
            .collect();
        let indices = kept.iter().flatten().copied().collect();
        self.draw_topology(target, vertices, Topology::LineList, indices, mvp, |f| {
            let [a, b] = kept[f.primitive as usize].map(|i| vertices[i as usize].color);
            // Perspective-correct, as for triangles: the fragment's place along the segment.
            a.lerp(b, f.barycentric[1])
        })
    }

    /// Draws `indices` of `vertices` as `topology` through the reference, depth-tested, each
    /// passing fragment coloured by `color`; the number of pixels that passed.
    fn draw_topology(
        &self,
        target: &mut Framebuffer,
        vertices: &[Vertex],
        topology: Topology,
        indices: Vec<u32>,
        mvp: Mat4,
        color: impl Fn(&Fragment) -> Vec4,
    ) -> usize {
        let viewport = target.viewport;
        let positions = vertices
            .iter()
            .map(|v| (mvp * v.position.extend(1.0)).to_array())
            .collect();
        let draw = Draw {
            state: self.state,
            ..Draw::of(viewport, positions, topology, indices)
        };
        let mut written = 0;
        // The draw is valid by construction (indices checked, one sample), so it cannot fail.
        let _ = self.reference.draw(&draw, |f| {
            let i = viewport.index(f.x, f.y);
            if self.state.depth.test_and_write(f.depth, &mut target.depth[i]) {
                target.color[i] = to_rgba8(color(&f));
                written += 1;
            }
        });
        written
    }
}
