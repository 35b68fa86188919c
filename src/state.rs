//! A draw's state besides its geometry: facing, culling, depth and clipping. Its own module
//! because both the contract (a [`Draw`](crate::Draw) carries it) and a profile (which states
//! it supports) need it.

use crate::depth::{DepthRange, DepthState};
use crate::setup::{CullMode, FrontFace};

/// Everything about a draw besides its geometry.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct DrawState {
    /// Facing to discard.
    pub cull: CullMode,
    /// Which winding is front-facing.
    pub front_face: FrontFace,
    /// Depth test and write.
    pub depth: DepthState,
    /// The clip volume's z range.
    pub depth_range: DepthRange,
    /// Whether triangles are clipped at the far plane `z = w` (near is always clipped).
    pub clip_far: bool,
}
