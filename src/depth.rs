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

    /// Normalised depth of a clip-space point: 0 at the near plane, 1 at the far one (beyond
    /// `[0, 1]` before or past a plane not clipped at); [`ViewportDepth::window`] maps it.
    #[must_use]
    pub fn window_depth(self, z: f64, w: f64) -> f64 {
        match self {
            Self::ZeroToOne => z / w,
            Self::NegativeOneToOne => (z / w + 1.0) * 0.5,
        }
    }
}

/// What clipping needs of a draw's state: the depth planes it clips at and its clip volume's z
/// range ([`DrawState::depth_clip`](crate::DrawState::depth_clip)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DepthClip {
    /// Whether the near plane clips.
    pub near: bool,
    /// Whether the far plane clips.
    pub far: bool,
    /// The clip volume's z range, which places the near plane.
    pub range: DepthRange,
}

/// The viewport's depth range, Vulkan's `minDepth` and `maxDepth` (OpenGL's `DepthRange(n, f)`,
/// D3D11's `MinDepth`, `MaxDepth`): where the clip volume's near and far planes land in
/// window depth. Each lies in `[0, 1]`; `min` may exceed `max`, which reverses depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewportDepth {
    /// Window depth at the near plane (`n`).
    pub min: f32,
    /// Window depth at the far plane (`f`).
    pub max: f32,
}

impl Default for ViewportDepth {
    /// `[0, 1]`: the whole depth buffer, near at 0.
    fn default() -> Self {
        Self::FULL
    }
}

impl ViewportDepth {
    /// `[0, 1]`, every API's default.
    pub const FULL: Self = Self { min: 0.0, max: 1.0 };

    /// Window depth of normalised depth `u` (0 at the near plane, 1 at the far one, as
    /// [`DepthRange::window_depth`] gives it): `n + (f − n)·u`, Vulkan's `o_z + p_z·z_d` for
    /// either clip volume.
    #[must_use]
    #[inline]
    pub fn window(self, u: f64) -> f64 {
        let (n, f) = (f64::from(self.min), f64::from(self.max));
        n + (f - n) * u
    }

    /// The depth a fragment stores: interpolated window depth clamped to `[min(n, f), max(n, f)]`.
    ///
    /// With depth clipping off this is depth clamping (Vulkan, Depth Clamping and Range
    /// Adjustment; D3D11 `DepthClipEnable = FALSE`): geometry before the near or beyond the far
    /// plane is drawn at its depth instead of an unbounded or infinite one. With clipping on it
    /// only removes rounding just outside the range (where Vulkan leaves the value undefined).
    #[must_use]
    #[inline]
    pub fn fragment_depth(self, interpolated: f64) -> f32 {
        let (lo, hi) = (self.min.min(self.max), self.min.max(self.max));
        (interpolated as f32).clamp(lo, hi)
    }

    /// Whether `min > max`: depth reversed, the near plane at the larger window depth.
    #[must_use]
    pub fn is_inverted(self) -> bool {
        self.min > self.max
    }

    /// `Err` naming what to fix unless both ends are in `[0, 1]` (Vulkan
    /// VUID-VkViewport-minDepth-01234 and maxDepth-01235; NaN included).
    pub fn validate(self) -> Result<(), String> {
        let ok = |v: f32| (0.0..=1.0).contains(&v);
        if ok(self.min) && ok(self.max) {
            return Ok(());
        }
        Err(format!(
            "viewport depth {}..{}: minDepth and maxDepth must each be in [0, 1]",
            self.min, self.max
        ))
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The range maps the near plane to `min` and the far one to `max`, reversed too, and a
    /// fragment's depth is clamped between them; each end must lie in `[0, 1]`.
    #[test]
    fn the_viewport_depth_range_maps_clamps_and_validates() {
        let reversed = ViewportDepth { min: 0.75, max: 0.25 };
        assert_eq!(reversed.window(0.0), 0.75);
        assert_eq!(reversed.window(1.0), 0.25);
        assert_eq!(reversed.window(0.5), 0.5);
        assert!(reversed.is_inverted() && !ViewportDepth::FULL.is_inverted());
        assert_eq!(reversed.fragment_depth(reversed.window(-1.0)), 0.75);
        assert_eq!(reversed.fragment_depth(reversed.window(2.0)), 0.25);
        assert_eq!(ViewportDepth::FULL.fragment_depth(1.5), 1.0);
        let single = ViewportDepth { min: 0.5, max: 0.5 };
        assert_eq!(single.fragment_depth(single.window(0.9)), 0.5);
        assert!(reversed.validate().is_ok() && single.validate().is_ok());
        for bad in [(-0.1, 0.5), (0.5, 1.5), (f32::NAN, 0.5)] {
            let range = ViewportDepth {
                min: bad.0,
                max: bad.1,
            };
            assert!(range.validate().is_err_and(|m| m.contains("[0, 1]")), "{bad:?}");
        }
        assert!(ViewportDepth::FULL.fragment_depth(f64::NAN).is_nan());
    }
}
