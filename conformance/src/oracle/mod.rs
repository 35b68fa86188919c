//! Oracles that decide the right answer without the reference's code path.
//!
//! - [`raster`]: the conventions' geometry (viewport transform, pixel centres, snapping, near
//!   plane, window depth), written once for the whole suite.
//! - [`brute_force`]: every pixel of the viewport, exact `orient2d` in i128, explicit fill-rule
//!   bias, on snapped coordinates. Decides coverage exactly.
//! - [`ray_cast`]: the ray through each sample centre against the triangle in clip space, in
//!   f64 with an error bound on every sign, and in exact big integers when a sign is unsure.
//!   Decides coverage and facing, and gives the true perspective-correct barycentrics and
//!   depth, whatever the clipping.
//! - [`outline`]: a triangle's visible outline in raster space and distances to it, for the
//!   tolerance band and for pictures.
//! - [`segment`]: lines (the diamond-exit rule by separating axes, rectangles, parallelograms),
//!   point squares and triangles at each declared sample position, exact in i128.
//! - [`facing`]: which way a triangle turns as an implementation with a profile may snap it,
//!   and where correct implementations may disagree; the grid points a vertex may snap to.
//! - [`bias`]: the interval a triangle's depth bias may take under each specification, from
//!   its exact plane, with bounds for snapping and f32.
//! - [`distance`]: where user clip distances cut a triangle or a segment, as a line in raster
//!   space (perspective-correct interpolation keeps the cut straight).
//! - [`provoking`]: which vertex gives a primitive its flat values, from the specifications'
//!   tables.

pub mod bias;
pub mod brute_force;
pub mod distance;
pub mod facing;
pub mod outline;
pub mod provoking;
pub mod raster;
pub mod ray_cast;
pub mod segment;
pub mod squares;
