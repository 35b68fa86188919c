//! refrast: a reference triangle rasterizer whose output is the definition of correct.
//!
//! It is deliberately simple and exact: coverage is decided by integer edge functions on
//! snapped coordinates, never by floats. The conformance suite (`refrast-conformance`)
//! certifies any implementation of [`Rasterizer`] against it.
//!
//! # Pipeline
//!
//! [`Reference::draw_samples`] takes each triangle through these stages, one call each:
//!
//! ```text
//! assemble ─ snap before clipping (zero area?) ─ clip (near, far, guard band) ─ project and snap
//!          ─ fan ─ facing, cull ─ traverse (bounding box × edge functions) ─ interpolate ─ depth
//! ```
//!
//! # The map
//!
//! The root holds the contract, the reference and the conventions. The stages' own types and
//! functions are in [`stage`], for code that must reproduce the reference bit for bit; the lab
//! programs built on it are in [`camera`], [`pipeline`] and [`scenes`].
//!
//! | what | where | key items |
//! |---|---|---|
//! | the contract | `rasterizer.rs`, `draw.rs` | [`Rasterizer`], [`Draw`], [`Fragment`], [`Resolved`] |
//! | lines, points, samples | `primitive.rs` | [`Topology`], [`LineRule`], [`PointClipping`], [`SamplePattern`], [`SAMPLE_COUNTS`] |
//! | what an implementation declares | `profile.rs`, `features.rs` | [`Profile`], [`Snapping`], [`Spec`], [`Features`], [`StateSupport`], [`Supported`], [`SnapAccuracy`] |
//! | state | `state.rs`, `setup.rs`, `depth.rs` | [`DrawState`], [`Scissor`], [`Interpolation`], [`Conservative`], [`ProvokingVertex`], [`CullMode`], [`FrontFace`], [`DepthState`], [`CompareOp`], [`DepthRange`], [`ViewportDepth`] |
//! | polygon modes | `state.rs`, `polygon.rs` | [`PolygonMode`] |
//! | clip and cull distances | `distance.rs` | [`Distances`], [`MAX_DISTANCES`], [`stage::CornerDistances`] |
//! | depth bias | `bias.rs` | [`DepthBias`], [`DepthFormat`], [`DepthSlope`], [`BiasSupport`], [`bias::polygon_offset`] |
//! | the reference | `reference.rs` | [`Reference`], [`ReferenceConfig`], [`Traversal`], [`ClipMode`], [`DrawStats`], [`Sample`] |
//! | fixed point | `fixed.rs` | [`SubpixelBits`], [`FixedPoint`], [`snap`], [`SnapRounding`], [`COORD_LIMIT`] |
//! | viewport | `viewport.rs` | [`Viewport`], [`MAX_VIEWPORT`] |
//! | edge functions, fill rule | `edge.rs` | [`orient2d`], [`is_top_left`], [`FillConvention`] |
//! | errors | `error.rs` | [`DrawError`], [`ConfigError`], [`Unavailable`] |
//! | clipping | `clip.rs` | [`stage::assemble`], [`stage::clip_triangle`], [`stage::clip_segment`], [`stage::clip_planes`] |
//! | projection | `project.rs` | [`stage::ViewportTransform`], [`stage::RasterVertex`] |
//! | setup, facing | `setup.rs` | [`stage::snap_before_clipping`], [`stage::drawn_winding`], [`stage::clipped_winding`], [`Winding`], [`stage::TriangleSetup`] |
//! | traversal | `traverse.rs` | [`stage::build_fan`], [`stage::traverse`], [`stage::PixelRect`] |
//! | interpolation | `interp.rs` | [`stage::Varyings`], [`stage::interpolate`], [`stage::interpolate_depth`] |
//! | lines, points (the labs' DDA) | `dda.rs` | [`stage::rasterize_line`], [`stage::rasterize_point`] |
//! | exact lines, points | `segment.rs` | [`stage::diamond_exit`], [`stage::in_rectangle`], [`stage::in_parallelogram`], [`stage::in_point_square`] |
//! | the reference's lines, points and samples | `lines_points_samples.rs` | [`Reference::draw_with_pattern`] |
//! | camera, projection | `camera.rs` | [`camera::Camera`], [`camera::Projection`] |
//! | mesh pipeline, PNG | `pipeline.rs` | [`pipeline::Renderer`], [`pipeline::Mesh`], [`pipeline::Framebuffer`] |
//! | lab scenes | `scenes.rs` | [`scenes::SCENES`], [`scenes::render`] |
//!
//! The lab programs stay in this crate: they are the reference's own users and its executable
//! spec (the golden scenes run through them), they need nothing but `glam`, and a crate of their
//! own would only move the `image` dependency, which the suite needs anyway for its pictures.
//! PNG output uses `image` behind the default feature `png`; a crate that needs only the
//! contract and the reference depends on refrast with `default-features = false`.
//!
//! # Conventions
//!
//! Each is stated here once and implemented in exactly one function.
//!
//! - **Raster space**: origin top-left, x right, y down; pixel `(x, y)` has its sample at
//!   `(x + ½, y + ½)` ([`FixedPoint::sample`]).
//! - **Viewport transform**: `x = (x_ndc + 1)/2 · W`, `y = (1 − y_ndc)/2 · H` ([`Viewport::to_raster`]).
//! - **Snapping**: to `2^-bits` pixel, 8 bits by default (1..=8 accepted), round half to even
//!   ([`snap`]; other roundings are options, [`SnapRounding`], so the reference can play any
//!   profile the suite accepts).
//! - **Valid range**: snapped coordinates within ±[`COORD_LIMIT`] = ±32768 px, so edge functions
//!   are exact in `i64`; viewports up to [`MAX_VIEWPORT`] = 16384 px a side.
//! - **Edge functions**: [`orient2d`] in exact integers, positive for clockwise on screen.
//! - **Fill rule**: top-left (D3D11 §3.4): a sample exactly on an edge is covered only if the
//!   edge is a top edge (horizontal, above the triangle) or a left edge; on a vertex, only if
//!   both edges are ([`FillConvention::owns_edge`], [`is_top_left`]). Other conventions are options.
//! - **Zero area**: a triangle whose snapped signed area is zero covers nothing, decided on the
//!   input before clipping when every vertex projects ([`Winding::from_area2`], used by
//!   [`stage::snap_before_clipping`]).
//! - **Facing**: a triangle that needs no clipping turns as its snapped signed area says; a
//!   clipped one as `−sign(det[x y w])` of its clip-space vertices says (Olano–Greer; the sign of
//!   the visible part whatever the signs of `w`), falling back to the snapped polygon's area
//!   when the determinant is too close to zero to be sure ([`stage::drawn_winding`],
//!   [`stage::clipped_winding`]). Front
//!   face CCW by default, CW optional ([`FrontFace::is_front`]); culling by facing, of
//!   triangles only: none, front, back or both ([`CullMode::culls`]).
//! - **Clip volume**: `−w ≤ x, y ≤ w`, `0 ≤ z ≤ w` (or `−w ≤ z`, [`DepthRange`]). Near is
//!   clipped unless depth clipping is off ([`DrawState::clip_near`]), far when enabled, x/y (which
//!   also keep out what lies behind the eye) at the guard band ([`stage::GUARD_BAND`]) and clamped by
//!   traversal, or at the viewport with [`ClipMode::Full`]. Intersections are canonical:
//!   computed from the inside end ([`stage::intersect`]); a user clip distance's from the end
//!   nearer the cut, whichever side it keeps ([`stage::intersect_nearer`]).
//! - **Clip and cull distances**: a primitive whose every vertex is negative in one cull
//!   distance is discarded; each clip distance, interpolated linearly in clip space, then cuts
//!   it after the clip volume's planes, keeping where it is `≥ 0` (a point with a negative one is
//!   discarded); a non-finite distance discards the primitive ([`Distances`],
//!   [`stage::CornerDistances`]).
//! - **Scissor**: a fragment is produced only where its pixel lies in the draw's scissor
//!   rectangle, half-open in raster space, for every primitive and sample
//!   ([`DrawState::passes_scissor`]).
//! - **Sample mask**: sample `i` of a fragment is kept only where bit `i` of the draw's mask
//!   is set, for every primitive and sample count, bit 0 at one sample
//!   ([`DrawState::passes_sample_mask`]).
//! - **Centroid**: at several samples, a triangle drawn with [`Interpolation::Centroid`] gives
//!   all its fragments in a pixel the barycentrics of one location: the pixel centre where it
//!   covers every sample (before the mask), else its first covered sample the mask keeps
//!   ([`DrawState::centroid_sample`]); lines and points keep each sample's.
//! - **Conservative rasterization**: a filled triangle drawn with a [`Conservative`] mode covers
//!   every sample of each pixel whose closed square its snapped polygon touches (grown by a
//!   disc of the extra size) or, underestimating, holds; a triangle of zero area once snapped
//!   is culled ([`ConservativeSupport::REFERENCE`], `conservative_cover.rs`).
//! - **Strips and fans**: triangle `i` of a strip is indices `i, i+1+i%2, i+2−i%2` (every other
//!   one reversed, so the strip keeps one winding), of a fan `i+1, i+2, 0`, as Vulkan makes them
//!   and orders their barycentrics; each draws as that triangle would in a list
//!   ([`Draw::triangle`]).
//! - **Flat values**: a fragment names the vertex whose flat values it carries, its
//!   primitive's provoking vertex: the first (Vulkan's default) or the last, as the draw's
//!   [`ProvokingVertex`] says, also where clipping cut it away ([`Draw::provoking`]).
//! - **Coverage of a clipped polygon**: its snapped fan's winding number
//!   ([`stage::traverse`]), so a sliver turned over by snapping neither doubles nor leaks.
//! - **Depth**: window depth `n + (f − n)·z/w` through the viewport's depth range
//!   ([`ViewportDepth`], reversed when `n > f`), interpolated linearly in screen space
//!   ([`stage::interpolate_depth`]), then clamped to `[min(n, f), max(n, f)]`
//!   ([`ViewportDepth::fragment_depth`]; depth clamping when a depth plane is not clipped at).
//! - **Depth bias**: a triangle's depth is offset by `o = dbclamp(m·slope + r·constant)`, one
//!   value per polygon, before the clamp: `m` the exact slope `√((∂z/∂x)² + (∂z/∂y)²)` of its
//!   snapped widest fan triangle, `r = 2^(e − 23)` for its largest depth `2^e ≤ z < 2^(e+1)`,
//!   refrast's depth being f32 ([`bias::polygon_offset`]); lines and points are not biased.
//! - **Polygon modes**: a triangle in line or point mode is clipped, faced and culled as a
//!   filled one, then draws its edges `0 → 1`, `1 → 2`, `2 → 0` as a line list of them would
//!   and its vertices as a point list would, with the triangle's index, facing, flat vertex and
//!   bias; edges and vertices made by clipping are not drawn ([`PolygonMode`]).
//! - **Attributes**: perspective-correct, `Σ sᵢ fᵢ/wᵢ / Σ sᵢ/wᵢ`, for triangles and lines alike
//!   ([`stage::interpolate`]); screen-space barycentrics also given.
//! - **Bad numbers**: a triangle with a NaN or infinite coordinate is discarded and counted
//!   ([`DrawStats::non_finite`]); an out-of-range viewport or subpixel count is a
//!   [`ConfigError`]; a bad index is a [`DrawError`]. Nothing panics.
#![forbid(unsafe_code)]

pub mod bias;
pub mod camera;
mod centroid;
mod clip;
mod config;
mod conservative;
mod conservative_cover;
mod dda;
mod depth;
mod distance;
mod draw;
mod edge;
mod error;
mod features;
mod fixed;
mod front;
mod interp;
mod lines_points_samples;
pub mod pipeline;
mod polygon;
mod primitive;
mod profile;
mod project;
mod rasterizer;
mod reference;
pub mod scenes;
mod segment;
mod setup;
pub mod stage;
mod state;
mod traverse;
mod viewport;

pub use bias::{BiasSupport, DepthBias, DepthFormat, DepthSlope};
pub use clip::ClipMode;
pub use config::{ReferenceConfig, Traversal};
pub use conservative::{Conservative, ConservativeSupport};
pub use depth::{CompareOp, DepthClip, DepthRange, DepthState, ViewportDepth};
pub use distance::{Distances, MAX_DISTANCES};
pub use draw::{Draw, Fragment, Resolved};
pub use edge::{FillConvention, is_top_left, orient2d};
pub use error::{ConfigError, DrawError, Unavailable};
pub use features::{Features, Setting, SnapAccuracy, StateSupport, Supported};
pub use fixed::{COORD_LIMIT, FixedPoint, SnapRounding, SubpixelBits, snap};
pub use primitive::{LineRule, PointClipping, SAMPLE_COUNTS, SamplePattern, Topology};
pub use profile::{DepthConvention, Profile, Snapping, Spec};
pub use rasterizer::Rasterizer;
pub use reference::{DrawStats, Reference, Sample};
pub use setup::{CullMode, FrontFace, Winding};
pub use state::{DrawState, Interpolation, PolygonMode, ProvokingVertex, Scissor};
pub use viewport::{GUARD_BAND_REACH, MAX_VIEWPORT, Viewport};
