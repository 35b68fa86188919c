//! The reference's stages, for code that must reproduce it bit for bit.
//!
//! A fast implementation, a mutant in the zoo or a test of an oracle needs the same pieces the
//! reference uses, in the order it uses them ([`Reference::draw_samples`](crate::Reference::draw_samples)).
//! Steps 1–5 and the bounding box are one call, [`front_end`], which the reference and `fast`
//! both make (`fast` with [`Corner`]s set up once per mesh vertex), so the order is written once:
//!
//! 1. **assemble** the triangle's clip vertices, discarding non-finite ones ([`assemble`]);
//! 2. **snap before clipping**: project and snap the input as it is and set it up; zero area
//!    draws nothing ([`snap_before_clipping`]: [`ViewportTransform::project_point`] for each
//!    corner, then [`SnappedTriangle::new`]);
//! 3. **clip** against the near (and far) plane and the guard band or viewport ([`clip_planes`],
//!    [`clip_triangle`]: [`outcode`] for each corner, [`classify`], then Sutherland–Hodgman),
//!    then project and snap the polygon left ([`ViewportTransform::project_polygon`]);
//! 4. **fan** a clipped polygon ([`build_fan`]); an unclipped triangle is its own fan
//!    ([`FanTriangle::whole`]); the winding it is drawn with comes from one rule
//!    ([`drawn_winding`]: the snapped area, or [`clipped_winding`] when clipped);
//! 5. **face and cull** ([`FrontFace::is_front`](crate::FrontFace::is_front),
//!    [`CullMode::culls`](crate::CullMode::culls));
//! 6. **traverse** the bounding box ([`PixelRect::bounding`], [`traverse`]), edge values stepped
//!    exactly ([`EdgeFunction`], [`TriangleSetup`]);
//! 7. **interpolate** depth ([`interpolate_depth`], [`ViewportDepth::fragment_depth`](crate::ViewportDepth::fragment_depth)) and barycentrics
//!    ([`screen_weights`], [`interpolate`]) from what the corners carry ([`Varyings`]).
//!
//! Lines and points have stages of their own: [`clip_segment`], then the exact coverage of
//! [`diamond_exit`], [`in_rectangle`], [`in_parallelogram`] and [`in_point_square`] on snapped
//! ends ([`Reference::draw_with_pattern`](crate::Reference::draw_with_pattern)); the labs' DDA,
//! [`rasterize_line`] and [`rasterize_point`], stays for the course implementations.

pub use crate::bias::{FragmentDepth, polygon_offset};
pub use crate::clip::{
    ClipOutcome, ClipPlane, ClipVertex, Cut, assemble, canonical_order, classify, clip_planes, clip_polygon,
    clip_polygon_at, clip_segment, clip_triangle, intersect, intersect_nearer, outcode, user_distance,
};
pub use crate::dda::{LineFragment, LineVertex, rasterize_line, rasterize_point};
pub use crate::distance::{CornerDistances, Unkept};
pub use crate::edge::EdgeFunction;
pub use crate::front::{Corner, Discard, FrontScratch, FrontSetup, Kept, front_end};
pub use crate::interp::{Barycentrics, Varyings, interpolate, interpolate_depth, screen_weights};
pub use crate::project::{ProjectedPoint, RasterVertex, ViewportTransform, input_w};
pub use crate::segment::{
    diamond_exit, in_diamond, in_parallelogram, in_point_square, in_rectangle, meets_diamond,
};
pub use crate::setup::{
    SnappedTriangle, TriangleSetup, ZeroArea, clipped_winding, drawn_winding, snap_before_clipping,
};
pub use crate::traverse::{FanTriangle, Hit, PixelRect, build_fan, traverse};
pub use crate::viewport::GUARD_BAND;
