//! The reference's conventions as knobs: snapping, fill rule, clipping and traversal.

use crate::clip::ClipMode;
use crate::edge::FillConvention;
use crate::fixed::{SnapRounding, SubpixelBits};
use crate::primitive::{LineRule, PointClipping};

/// Which pixels are tested against a triangle; both give identical output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Traversal {
    /// Only the pixels of the triangle's bounding box, clamped to the viewport.
    #[default]
    BoundingBox,
    /// Every pixel of the viewport, as the first lab step does.
    Viewport,
}

/// The reference's knobs; the defaults are the conventions stated in the crate docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct ReferenceConfig {
    /// Subpixel precision of snapping.
    pub subpixel_bits: SubpixelBits,
    /// How a coordinate becomes a grid point (half to even, refrast's convention, by default).
    pub snap_rounding: SnapRounding,
    /// Which edges own the samples on them.
    pub fill: FillConvention,
    /// Guard band (default), a band of another reach, or full six-plane clipping for x and y.
    pub clip: ClipMode,
    /// Bounding-box (default) or whole-viewport traversal.
    pub traversal: Traversal,
    /// How lines are covered (the diamond-exit rule by default).
    pub line: LineRule,
    /// What clipping does to a point outside the viewport in x or y (discarded by default;
    /// kept, pop-free, as OpenGL ES and `USER_CLIP_PLANES_ONLY` devices do).
    pub point_clipping: PointClipping,
}
