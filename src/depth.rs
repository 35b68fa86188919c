//! Depth: the clip-space z range, the window depth, and the depth test.

/// The clip volume's z range, which fixes the near plane and how z/w maps to window depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum DepthRange {
    /// `0 ≤ z ≤ w`, window depth `z/w` (Vulkan, D3D).
    #[default]
    ZeroToOne,
    /// `−w ≤ z ≤ w`, window depth `(z/w + 1)/2` (OpenGL).
    NegativeOneToOne,
}

impl DepthRange {
    /// The signed distance to the near plane: inside when `≥ 0`.
    #[must_use]
    pub fn near_distance(self, z: f64, w: f64) -> f64 {
        match self {
            Self::ZeroToOne => z,
            Self::NegativeOneToOne => z + w,
        }
    }

    /// Window depth of a clip-space point inside the volume (`> 1` beyond an unclipped far plane).
    #[must_use]
    pub fn window_depth(self, z: f64, w: f64) -> f64 {
        match self {
            Self::ZeroToOne => z / w,
            Self::NegativeOneToOne => (z / w + 1.0) * 0.5,
        }
    }
}

/// The depth a fragment stores: interpolated window depth clamped to `[0, 1]`.
///
/// With far clipping off this is depth clamping (D3D11 `DepthClipEnable = FALSE`): geometry
/// beyond the far plane is drawn at depth 1 instead of at an unbounded or infinite depth.
/// With it on, it only removes rounding just outside the range.
#[must_use]
#[inline]
pub fn fragment_depth(interpolated: f64) -> f32 {
    interpolated.clamp(0.0, 1.0) as f32
}

/// How an incoming depth is compared with the stored one; the fragment passes when true.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum CompareOp {
    /// Never passes.
    Never,
    /// Passes when nearer: `new < stored`.
    #[default]
    Less,
    /// `new == stored`.
    Equal,
    /// `new <= stored`.
    LessOrEqual,
    /// `new > stored`.
    Greater,
    /// `new != stored`.
    NotEqual,
    /// `new >= stored`.
    GreaterOrEqual,
    /// Always passes (depth testing off).
    Always,
}

impl CompareOp {
    /// Whether a fragment at depth `new` passes against `stored`.
    #[must_use]
    #[inline]
    pub fn passes(self, new: f32, stored: f32) -> bool {
        match self {
            Self::Never => false,
            Self::Less => new < stored,
            Self::Equal => new == stored,
            Self::LessOrEqual => new <= stored,
            Self::Greater => new > stored,
            Self::NotEqual => new != stored,
            Self::GreaterOrEqual => new >= stored,
            Self::Always => true,
        }
    }
}

/// The depth test and write state of a draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthState {
    /// The comparison; `Always` turns the test off.
    pub compare: CompareOp,
    /// Whether passing fragments store their depth.
    pub write: bool,
    /// The value the depth buffer starts from.
    pub clear: f32,
}

impl Default for DepthState {
    /// LESS with writes on, cleared to 1.0 (the far plane).
    fn default() -> Self {
        Self {
            compare: CompareOp::Less,
            write: true,
            clear: 1.0,
        }
    }
}

impl DepthState {
    /// Applies the test to one stored value: stores when asked and reports whether it passed.
    #[inline]
    pub fn test_and_write(&self, new: f32, stored: &mut f32) -> bool {
        let pass = self.compare.passes(new, *stored);
        if pass && self.write {
            *stored = new;
        }
        pass
    }
}
