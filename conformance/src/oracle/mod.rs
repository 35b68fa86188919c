//! Oracles that decide the right answer without the reference's code path.
//!
//! - [`brute_force`]: every pixel of the viewport, exact `orient2d` in i128, explicit fill-rule
//!   bias, on snapped coordinates. Decides coverage exactly.
//! - [`ray_cast`]: the ray through each sample centre against the triangle in clip space, in
//!   f64 with an error bound on every sign, and in exact big integers (`exact`) when a sign is
//!   unsure. Decides coverage and gives the true perspective-correct barycentrics and depth,
//!   whatever the clipping.

pub mod brute_force;
mod exact;
pub mod ray_cast;
