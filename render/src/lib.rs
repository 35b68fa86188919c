//! refrast's programs for people: what the labs draw, drawn through any [`refrast::Rasterizer`].
//!
//! The map, one module per stage:
//! - [`load`]: mesh files, PLY (ASCII and binary) and OBJ, validated into a [`refrast::pipeline::Mesh`];
//! - [`shapes`]: procedural meshes like the labs' (plane, star, text, torus, sphere, box).

pub mod load;
pub mod shapes;
