//! refrast's programs for people: what the labs draw, drawn through any [`refrast::Rasterizer`].
//!
//! The map, one module per stage:
//! - [`load`]: mesh files, PLY (ASCII and binary) and OBJ, validated into a [`refrast::pipeline::Mesh`];
//! - [`shapes`]: procedural meshes like the labs' (plane, star, text, torus, sphere, box);
//! - [`scene`]: the built-in scenes and the defaults of a mesh file;
//! - [`room`]: seed 002's room, a Cornell box with two blocks;
//! - [`geometry`]: bounds, edges and normals of a mesh;
//! - [`view`]: the camera, perspective or orthographic, and automatic framing;
//! - [`shade`]: flat, Gouraud and Phong shading of a point light;
//! - [`texture`]: textures sampled nearest or bilinear;
//! - [`mode`]: what a picture shows (points, wire, fill, depth, normals, barycentric, overdraw);
//! - [`draw`]: a picture through any rasterizer;
//! - [`shaded`]: a picture through a rasterizer that shades as it rasterizes, each pixel shaded
//!   once from a visibility buffer;
//! - [`multisample`]: a picture at several samples per pixel, resolved with a box filter;
//! - [`output`]: PNG files written whole or not at all.

pub mod draw;
pub mod geometry;
pub mod load;
pub mod mode;
pub mod multisample;
pub mod output;
pub mod room;
pub mod scene;
pub mod shade;
pub mod shaded;
pub mod shapes;
pub mod texture;
pub mod view;

pub use draw::{Job, Stats, render};
pub use mode::Mode;
pub use multisample::render_multisampled;
pub use shade::{Light, Shading};
pub use shaded::{ShadingRasterizer, render_shaded};
pub use texture::{Sampling, Texture};
pub use view::{Lens, Overrides, View};
