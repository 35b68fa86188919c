//! A draw's state besides its geometry: facing, culling, depth, clipping, the scissor and the
//! provoking vertex. Its own module because both the contract (a [`Draw`](crate::Draw) carries
//! it) and a profile (which states it supports) need it.

use crate::bias::DepthBias;
use crate::conservative::Conservative;
use crate::depth::{DepthClip, DepthRange, DepthState, ViewportDepth};
use crate::setup::{CullMode, FrontFace};

/// Everything about a draw besides its geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawState {
    /// Facing to discard.
    pub cull: CullMode,
    /// Which winding is front-facing.
    pub front_face: FrontFace,
    /// Depth test and write.
    pub depth: DepthState,
    /// The clip volume's z range.
    pub depth_range: DepthRange,
    /// Whether triangles are clipped at the far plane `z = w`; without it, depth is clamped.
    pub clip_far: bool,
    /// Whether primitives are clipped at the near plane (`z = 0`, or `z = −w`); without it,
    /// depth is clamped (depth clipping off: Vulkan's `depthClipEnable = VK_FALSE`, OpenGL's
    /// `DEPTH_CLAMP`, D3D11's `DepthClipEnable = FALSE`). Sent off only to a rasterizer that
    /// declares it ([`StateSupport::unclipped_depth`](crate::StateSupport::unclipped_depth)),
    /// and then with far clipping off too (the reference also draws near off with far on, as
    /// `GL_AMD_depth_clamp_separate` would). What lies behind the eye is still clipped, by x and y.
    pub clip_near: bool,
    /// Where the near and far planes land in window depth. Sent other than `[0, 1]` only to a
    /// rasterizer that declares it ([`StateSupport::viewport_depth`](crate::StateSupport::viewport_depth)).
    pub viewport_depth: ViewportDepth,
    /// The depth bias of triangles; `None` biases nothing (Vulkan's `depthBiasEnable` off).
    /// Sent only to a rasterizer that declares it
    /// ([`StateSupport::depth_bias`](crate::StateSupport::depth_bias)).
    pub depth_bias: Option<DepthBias>,
    /// The rectangle fragments must fall in; `None` tests nothing. Sent only to a rasterizer
    /// that declares it ([`StateSupport::scissor`](crate::StateSupport::scissor)).
    pub scissor: Option<Scissor>,
    /// The static sample mask, ANDed with each fragment's coverage: sample `i` is kept only
    /// where bit `i` is set, at every sample count (bit 0 alone at one sample); bits at and
    /// above the draw's sample count mean nothing. All ones (`u32::MAX`) tests nothing. Sent
    /// other than all ones only to a rasterizer that declares it
    /// ([`StateSupport::sample_mask`](crate::StateSupport::sample_mask)): Vulkan's `pSampleMask`,
    /// OpenGL's `SampleMaski`, D3D11's `SampleMask`, WebGPU's `multisample.mask`.
    pub sample_mask: u32,
    /// Where a triangle's fragments at several samples take their barycentrics: at each
    /// sample (the default), or at one centroid location per pixel
    /// ([`Interpolation::Centroid`]). Sent other than at the sample only to a rasterizer that
    /// declares it ([`StateSupport::centroid`](crate::StateSupport::centroid)).
    pub interpolation: Interpolation,
    /// Conservative rasterization of filled triangles: whole pixels touched or held, every
    /// sample of each; `None` rasterizes as the fill rule says. Lines, points and the polygon
    /// modes are drawn as without it. Sent only to a rasterizer that declares it
    /// ([`StateSupport::conservative`](crate::StateSupport::conservative)).
    pub conservative: Option<Conservative>,
    /// Which vertex of a primitive gives its flat values ([`Fragment::flat`](crate::Fragment::flat)).
    /// Sent other than first only to a rasterizer that declares it
    /// ([`StateSupport::flat`](crate::StateSupport::flat)).
    pub provoking_vertex: ProvokingVertex,
    /// How triangles are rasterized: filled, as their edges or as their vertices. Sent other
    /// than fill only to a rasterizer that declares the mode
    /// ([`StateSupport::polygon_modes`](crate::StateSupport::polygon_modes)); lines and points
    /// are drawn alike whatever it says, though a profile fits it as any other setting.
    pub polygon_mode: PolygonMode,
}

/// Which vertex of a primitive gives its flat (not interpolated) values: Vulkan's
/// `VkProvokingVertexModeEXT`, OpenGL's `ProvokingVertex`, D3D11's leading vertex (first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ProvokingVertex {
    /// The primitive's first vertex (Vulkan's default, D3D11): a list's `3i`, a strip's `i`, a
    /// fan's `i + 1`, a line's `2i` or `i`, a point's.
    #[default]
    First,
    /// Its last vertex (OpenGL's default, OpenGL ES's only one): a list's `3i + 2`, a strip's or
    /// fan's `i + 2`, a line's `2i + 1` or `i + 1`, a point's.
    Last,
}

/// Where the barycentrics of a triangle's fragment are evaluated at several samples per
/// pixel: a shader input's interpolation sampling (WGSL's `sample` and `centroid`, Vulkan's
/// `Sample` and `Centroid` decorations, D3D11's `linear_sample` and `linear_centroid`). Lines
/// and points are evaluated at each sample under both, a location inside them; at one sample
/// both are the pixel's one sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Interpolation {
    /// At each covered sample's position, as under sample shading.
    #[default]
    Sample,
    /// At one location per pixel and triangle, shared by all its fragments there, as D3D11.3
    /// §3.5.5 defines it ([`DrawState::centroid_sample`]): the pixel centre where the triangle
    /// covers every sample of the pixel (before the sample mask), else the first covered
    /// sample the mask keeps. Vulkan and OpenGL require only a location inside both the pixel
    /// and the triangle, which both choices are.
    Centroid,
}

impl Interpolation {
    /// Both, at the sample first.
    pub const ALL: [Interpolation; 2] = [Self::Sample, Self::Centroid];

    /// The word the pipe protocol, the case files and reports use: `sample`, `centroid`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Sample => "sample",
            Self::Centroid => "centroid",
        }
    }

    /// The sampling called `name` ([`Interpolation::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// How a triangle is rasterized: Vulkan's `VkPolygonMode`, OpenGL's `PolygonMode` (both faces
/// alike), D3D11's `FillMode` (which has no point mode).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum PolygonMode {
    /// Its inside is covered by the fill rule.
    #[default]
    Fill,
    /// Its edges, first to second, second to third and third to first, are drawn as the
    /// draw's line segments would be.
    Line,
    /// Its vertices are drawn as the draw's points would be.
    Point,
}

impl PolygonMode {
    /// Every mode, fill first.
    pub const ALL: [PolygonMode; 3] = [Self::Fill, Self::Line, Self::Point];

    /// The word the pipe protocol, the case files and reports use: `fill`, `line`, `point`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Fill => "fill",
            Self::Line => "line",
            Self::Point => "point",
        }
    }

    /// The mode called `name` ([`PolygonMode::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

impl Default for DrawState {
    /// No culling, counter-clockwise front faces, a LESS test, the `[0, 1]` clip volume with
    /// near clipping on and far clipping off, the whole depth range, no depth bias, no scissor,
    /// no sample mask, interpolation at the sample, no conservative rasterization, the first
    /// provoking vertex, triangles filled.
    fn default() -> Self {
        Self {
            cull: CullMode::default(),
            front_face: FrontFace::default(),
            depth: DepthState::default(),
            depth_range: DepthRange::default(),
            clip_far: false,
            clip_near: true,
            viewport_depth: ViewportDepth::FULL,
            depth_bias: None,
            scissor: None,
            sample_mask: Self::ALL_SAMPLES,
            interpolation: Interpolation::Sample,
            conservative: None,
            provoking_vertex: ProvokingVertex::default(),
            polygon_mode: PolygonMode::Fill,
        }
    }
}

impl DrawState {
    /// The depth planes it clips at and its clip volume's z range: what clipping needs of it.
    #[must_use]
    pub fn depth_clip(&self) -> DepthClip {
        DepthClip {
            near: self.clip_near,
            far: self.clip_far,
            range: self.depth_range,
        }
    }

    /// The sample mask that masks nothing.
    pub const ALL_SAMPLES: u32 = u32::MAX;

    /// Whether sample `sample` of a fragment passes the sample mask test: the one place the
    /// reference applies it, as Vulkan's Sample Mask Test does, bit `sample` of the mask.
    #[must_use]
    #[inline]
    pub fn passes_sample_mask(&self, sample: u8) -> bool {
        u32::from(sample) < u32::BITS && self.sample_mask >> sample & 1 == 1
    }

    /// Where a triangle's centroid lies in a pixel of `samples` samples of which it covers
    /// those set in `covered` (bit `k` for sample `k`, before the sample mask): `None` for the
    /// pixel centre, where it covers them all, else the first covered sample the mask keeps
    /// (`None` too where the mask keeps none, and no fragment is made). The one place the
    /// reference chooses it, as D3D11.3 §3.5.5 does; counting coverage before the mask for the
    /// centre keeps the location inside the triangle, as Vulkan and OpenGL require, since every
    /// standard pattern's samples surround the centre.
    #[must_use]
    pub fn centroid_sample(&self, samples: u8, covered: u32) -> Option<u8> {
        let all = 1u32.checked_shl(u32::from(samples)).map_or(u32::MAX, |b| b - 1);
        if covered & all == all {
            return None;
        }
        (0..samples).find(|&k| covered >> k & 1 == 1 && self.passes_sample_mask(k))
    }

    /// Whether a fragment at pixel `(x, y)` passes the scissor test: the one place the
    /// reference applies it, as Vulkan's Scissor Test does, to each fragment's pixel.
    #[must_use]
    #[inline]
    pub fn passes_scissor(&self, x: u32, y: u32) -> bool {
        self.scissor.is_none_or(|s| s.contains(x, y))
    }
}

/// A scissor rectangle in pixels, in raster space (origin top-left, y down, as fragments'
/// `x` and `y`): a fragment outside it is not produced (Vulkan, Scissor Test; D3D11.3 §15.7).
/// It may reach past the viewport, and have no width or height (then nothing passes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Scissor {
    /// The first column inside.
    pub x: u32,
    /// The first row inside.
    pub y: u32,
    /// Columns inside: `x ≤ column < x + width`.
    pub width: u32,
    /// Rows inside: `y ≤ row < y + height`.
    pub height: u32,
}

impl Scissor {
    /// Whether pixel `(px, py)` is inside: `x ≤ px < x + width` and `y ≤ py < y + height`,
    /// in 64 bits so that a rectangle reaching past `u32::MAX` does not wrap.
    #[must_use]
    #[inline]
    pub fn contains(self, px: u32, py: u32) -> bool {
        let inside = |p: u32, start: u32, extent: u32| {
            p >= start && u64::from(p) < u64::from(start) + u64::from(extent)
        };
        inside(px, self.x, self.width) && inside(py, self.y, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rectangle is half-open: its first column and row are in, `x + width` and
    /// `y + height` are out; one at the top of `u32` does not wrap to take in column 0.
    #[test]
    fn a_scissor_holds_its_first_and_not_its_end_pixels() {
        let s = Scissor {
            x: 2,
            y: 3,
            width: 4,
            height: 1,
        };
        assert!(s.contains(2, 3) && s.contains(5, 3));
        assert!(!s.contains(1, 3) && !s.contains(6, 3) && !s.contains(2, 4) && !s.contains(2, 2));
        assert!(!Scissor { width: 0, ..s }.contains(2, 3));
        let far = Scissor {
            x: u32::MAX - 1,
            y: 0,
            width: 10,
            height: 1,
        };
        assert!(far.contains(u32::MAX, 0) && !far.contains(0, 0));
        let state = DrawState {
            scissor: Some(s),
            ..DrawState::default()
        };
        assert!(state.passes_scissor(3, 3) && !state.passes_scissor(0, 0));
        assert!(DrawState::default().passes_scissor(u32::MAX, u32::MAX));
    }

    /// Bit `i` of the mask keeps sample `i`; the default keeps every sample.
    #[test]
    fn the_sample_mask_keeps_the_samples_of_its_set_bits() {
        let state = DrawState {
            sample_mask: 0b1010,
            ..DrawState::default()
        };
        assert!(!state.passes_sample_mask(0) && state.passes_sample_mask(1));
        assert!(!state.passes_sample_mask(2) && state.passes_sample_mask(3));
        assert!(!state.passes_sample_mask(15) && !state.passes_sample_mask(200));
        assert!((0..32).all(|s| DrawState::default().passes_sample_mask(s)));
    }

    /// The centroid is the centre where every sample is covered, whatever the mask; else the
    /// first covered sample the mask keeps.
    #[test]
    fn the_centroid_is_the_centre_or_the_first_covered_kept_sample() {
        let state = DrawState {
            sample_mask: 0b1011,
            ..DrawState::default()
        };
        assert_eq!(state.centroid_sample(4, 0b1111), None);
        assert_eq!(DrawState::default().centroid_sample(16, 0xffff), None);
        assert_eq!(DrawState::default().centroid_sample(4, 0b1100), Some(2));
        assert_eq!(state.centroid_sample(4, 0b1100), Some(3));
        assert_eq!(state.centroid_sample(4, 0b0100), None);
        assert_eq!(state.centroid_sample(1, 0b1), None);
    }

    #[test]
    fn modes_are_named_as_the_protocol_names_them() {
        for sampling in Interpolation::ALL {
            assert_eq!(Interpolation::from_name(sampling.name()), Some(sampling));
        }
        for mode in PolygonMode::ALL {
            assert_eq!(PolygonMode::from_name(mode.name()), Some(mode));
        }
        assert_eq!(PolygonMode::from_name("wire"), None);
    }
}
