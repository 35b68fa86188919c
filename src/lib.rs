//! refrast: a reference triangle rasterizer whose output is the definition of correct.
//!
//! It is deliberately simple and exact: coverage is decided by integer edge functions on
//! snapped coordinates, never by floats. The conformance suite (`refrast-conformance`)
//! certifies any implementation of [`Rasterizer`] against it.
//!
//! # Pipeline
//!
//! ```text
//! clip space ─ clip (near, far, guard band) ─ project ─ viewport ─ snap ─ setup (facing, cull)
//!            ─ traverse (bounding box × edge functions) ─ interpolate ─ fragments ─ depth test
//! ```
//!
//! | stage | module | key items |
//! |---|---|---|
//! | fixed point | `fixed` | [`SubpixelBits`], [`FixedPoint`], [`snap`], [`COORD_LIMIT`] |
//! | viewport | `viewport` | [`Viewport`], [`MAX_VIEWPORT`], [`GUARD_BAND`] |
//! | edge functions | `edge` | [`orient2d`], [`is_top_left`], [`FillConvention`] |
//! | clipping | `clip` | [`clip_triangle`], [`ClipMode`], [`ClipPlane`] |
//! | setup | `setup` | [`TriangleSetup`], [`Winding`], [`PixelRect`] |
//! | traversal | `traverse` | [`traverse`], [`FanTriangle`] |
//! | interpolation | `interp` | [`screen_weights`], [`interpolate_depth`], [`interpolate`] |
//! | depth | `depth` | [`DepthRange`], [`CompareOp`], [`DepthState`], [`fragment_depth`] |
//! | the contract | `rasterizer` | [`Rasterizer`], [`Draw`], [`Fragment`], [`Profile`], [`Resolved`] |
//! | the reference | `reference` | [`Reference`], [`ReferenceConfig`], [`Sample`] |
//! | lines, points | `line` | [`rasterize_line`], [`rasterize_point`] |
//! | camera, projection | `camera` | [`Camera`], [`Projection`] |
//! | pipeline | `pipeline` | [`Renderer`], [`Mesh`], [`Vertex`], [`Framebuffer`] |
//! | lab scenes | `scenes` | [`scenes::SCENES`], [`scenes::render`] |
//!
//! # Conventions
//!
//! Each is stated here once and implemented in exactly one function.
//!
//! - **Raster space**: origin top-left, x right, y down; pixel `(x, y)` has its sample at
//!   `(x + ½, y + ½)` ([`FixedPoint::sample`]).
//! - **Viewport transform**: `x = (x_ndc + 1)/2 · W`, `y = (1 − y_ndc)/2 · H` ([`Viewport::to_raster`]).
//! - **Snapping**: to `2^-bits` pixel, 8 bits by default (1..=8 accepted), round half to even ([`snap`]).
//! - **Valid range**: snapped coordinates within ±[`COORD_LIMIT`] = ±32768 px, so edge functions
//!   are exact in `i64`; viewports up to [`MAX_VIEWPORT`] = 16384 px a side.
//! - **Edge functions**: [`orient2d`] in exact integers, positive for clockwise on screen.
//! - **Fill rule**: top-left (D3D11 §3.4): a sample exactly on an edge is covered only if the
//!   edge is a top edge (horizontal, above the triangle) or a left edge; on a vertex, only if
//!   both edges are ([`FillConvention::owns_edge`], [`is_top_left`]). Other conventions are options.
//! - **Facing**: from the sign of the snapped polygon's area; front face CCW by default, CW
//!   optional; zero-area triangles are back-facing and draw nothing ([`Winding::from_area2`]).
//! - **Clip volume**: `−w ≤ x, y ≤ w`, `0 ≤ z ≤ w` (or `−w ≤ z`, [`DepthRange`]). Near is always
//!   clipped, far when enabled, x/y at the guard band ([`GUARD_BAND`]) and clamped by traversal,
//!   or at the viewport with [`ClipMode::Full`]. Intersections are canonical ([`clip::intersect`]).
//! - **Depth**: window depth `z/w` interpolated linearly in screen space ([`interpolate_depth`]),
//!   then clamped to `[0, 1]` ([`fragment_depth`]; depth clamping when far clipping is off).
//! - **Attributes**: perspective-correct, `Σ sᵢ fᵢ/wᵢ / Σ sᵢ/wᵢ`; screen-space weights also given.
//! - **Bad numbers**: a triangle with a NaN or infinite coordinate is discarded and counted
//!   ([`DrawStats::non_finite`]); an out-of-range viewport or subpixel count is a
//!   [`ConfigError`]; a bad index is a [`DrawError`]. Nothing panics.
#![forbid(unsafe_code)]

pub mod camera;
pub mod clip;
mod depth;
mod edge;
mod error;
mod fixed;
mod interp;
mod line;
pub mod pipeline;
mod rasterizer;
mod reference;
pub mod scenes;
mod setup;
mod traverse;
mod viewport;

pub use camera::{Camera, Projection};
pub use clip::{ClipMode, ClipOutcome, ClipPlane, ClipVertex, clip_triangle};
pub use depth::{CompareOp, DepthRange, DepthState, fragment_depth};
pub use edge::{EdgeFunction, FillConvention, is_top_left, orient2d};
pub use error::{ConfigError, DrawError};
pub use fixed::{COORD_LIMIT, FixedPoint, SubpixelBits, snap};
pub use interp::{Barycentrics, RasterVertex, interpolate, interpolate_depth, screen_weights};
pub use line::{LineFragment, LineVertex, rasterize_line, rasterize_point};
pub use pipeline::{Framebuffer, Mesh, Renderer, ShadeInput, Vertex};
pub use rasterizer::{
    CullMode, DepthConvention, Draw, DrawState, Features, Fragment, FrontFace, Profile, Rasterizer, Resolved,
};
pub use reference::{DrawStats, Reference, ReferenceConfig, Sample, Traversal};
pub use setup::{PixelRect, TriangleSetup, Winding};
pub use traverse::{FanTriangle, Hit, traverse};
pub use viewport::{GUARD_BAND, MAX_VIEWPORT, Viewport};
