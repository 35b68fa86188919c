//! What an implementation declares about itself: its conventions, its tolerance and the draw
//! states it supports. The suite judges it by these, and sends it only states it supports.

use std::fmt;
use std::marker::PhantomData;

use crate::depth::{CompareOp, DepthRange};
use crate::edge::FillConvention;
use crate::rasterizer::DrawState;
use crate::setup::{CullMode, FrontFace};
use crate::viewport::GUARD_BAND_REACH;

/// How an implementation places vertices before it decides coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Snapping {
    /// Snapped to a grid of `2^-bits` pixel: 8 in D3D11 and Vulkan Roadmap 2026, Vulkan's
    /// `subPixelPrecisionBits` (at least 4) elsewhere.
    Grid(u8),
    /// No grid: coverage is decided on the unsnapped coordinates, in floating point. Rules that
    /// compare coverage bit for bit do not apply.
    Float,
}

impl Snapping {
    /// The grid's fractional bits, if there is a grid.
    #[must_use]
    pub fn grid_bits(self) -> Option<u8> {
        match self {
            Self::Grid(bits) => Some(bits),
            Self::Float => None,
        }
    }

    /// The unit of the tolerance band in pixels: one grid step, or 1/256 px without a grid.
    #[must_use]
    pub fn unit_px(self) -> f64 {
        let bits = self.grid_bits().unwrap_or(8).min(16);
        1.0 / f64::from(1u32 << bits)
    }
}

impl fmt::Display for Snapping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Grid(bits) => write!(f, "{bits} subpixel bits"),
            Self::Float => f.write_str("no grid (float)"),
        }
    }
}

/// How depth values are produced, as declared by an implementation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum DepthConvention {
    /// z/w interpolated linearly in screen space (Vulkan, D3D, the reference).
    #[default]
    ScreenLinearZOverW,
    /// Anything else (view-space z, 1/z, …): depth rules that need z/w do not apply.
    Other,
}

/// A draw-state setting with a few values, each of which an implementation may support.
pub trait Setting: Copy + PartialEq + fmt::Debug + 'static {
    /// Every value, the one to fall back on first.
    const VALUES: &'static [Self];
}

impl Setting for CullMode {
    const VALUES: &'static [Self] = &[Self::None, Self::Back, Self::Front];
}

impl Setting for FrontFace {
    const VALUES: &'static [Self] = &[Self::CounterClockwise, Self::Clockwise];
}

impl Setting for CompareOp {
    const VALUES: &'static [Self] = &[
        Self::Less,
        Self::LessOrEqual,
        Self::Greater,
        Self::GreaterOrEqual,
        Self::Equal,
        Self::NotEqual,
        Self::Always,
        Self::Never,
    ];
}

impl Setting for DepthRange {
    const VALUES: &'static [Self] = &[Self::ZeroToOne, Self::NegativeOneToOne];
}

/// On and off, for switches such as far clipping and depth writes.
impl Setting for bool {
    const VALUES: &'static [Self] = &[false, true];
}

/// The values of one setting an implementation supports.
pub struct Supported<T: Setting> {
    mask: u16,
    setting: PhantomData<fn() -> T>,
}

impl<T: Setting> Supported<T> {
    /// Every value.
    pub const ALL: Self = Self {
        mask: (1 << T::VALUES.len()) - 1,
        setting: PhantomData,
    };

    /// Exactly `values`.
    #[must_use]
    pub fn only(values: &[T]) -> Self {
        let mask = T::VALUES
            .iter()
            .enumerate()
            .filter(|(_, v)| values.contains(v))
            .fold(0, |mask, (i, _)| mask | 1 << i);
        Self {
            mask,
            setting: PhantomData,
        }
    }

    /// Whether `value` is supported.
    #[must_use]
    pub fn contains(self, value: T) -> bool {
        T::VALUES
            .iter()
            .position(|v| *v == value)
            .is_some_and(|i| self.mask & (1 << i) != 0)
    }

    /// The supported values, in [`Setting::VALUES`] order.
    pub fn values(self) -> impl Iterator<Item = T> {
        T::VALUES.iter().copied().filter(move |&v| self.contains(v))
    }

    /// `value` when supported, else the first supported value (`value` when there is none).
    #[must_use]
    pub fn fit(self, value: T) -> T {
        if self.contains(value) {
            value
        } else {
            self.values().next().unwrap_or(value)
        }
    }
}

impl<T: Setting> Clone for Supported<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: Setting> Copy for Supported<T> {}

impl<T: Setting> PartialEq for Supported<T> {
    fn eq(&self, other: &Self) -> bool {
        self.mask == other.mask
    }
}

impl<T: Setting> Eq for Supported<T> {}

impl<T: Setting> std::hash::Hash for Supported<T> {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.mask.hash(state);
    }
}

impl<T: Setting> fmt::Debug for Supported<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_set().entries(self.values()).finish()
    }
}

/// Optional abilities and supported states; a rule needing one that is absent is "not
/// applicable", never "passed", and no draw asks for a state that is not supported.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Features {
    /// Fragments carry perspective-correct barycentrics.
    pub perspective_barycentrics: bool,
    /// Fragments carry screen-space barycentrics.
    pub screen_barycentrics: bool,
    /// The cull modes it implements (`None` at least).
    pub cull_modes: Supported<CullMode>,
    /// The front faces it can be told.
    pub front_faces: Supported<FrontFace>,
    /// `resolve` runs its own depth test, so the depth-test rules judge it.
    pub depth_test: bool,
    /// The depth compare ops of its depth test.
    pub compare_ops: Supported<CompareOp>,
    /// Depth writes on (`true`) and off (`false`).
    pub depth_writes: Supported<bool>,
    /// Far-plane clipping off (`false`: depth clamped instead) and on (`true`).
    pub far_clipping: Supported<bool>,
    /// The clip volumes' z ranges.
    pub depth_ranges: Supported<DepthRange>,
    /// How far beyond each side of the viewport, in pixels, a triangle may reach while x/y
    /// clipping still moves no edge inside it (a guard band, so its coverage can be exact); 0 when
    /// any reach outside may move one.
    pub guard_band: u32,
    /// Snapping rounds a coordinate exactly halfway between two grid points to the even one
    /// (D3D11 §3.2.4.1); Vulkan leaves ties to the implementation, so without this claim the
    /// suite moves every vertex off such a tie before drawing.
    pub ties_to_even: bool,
}

impl Features {
    /// Everything the reference does.
    pub const ALL: Features = Features {
        perspective_barycentrics: true,
        screen_barycentrics: true,
        cull_modes: Supported::ALL,
        front_faces: Supported::ALL,
        depth_test: true,
        compare_ops: Supported::ALL,
        depth_writes: Supported::ALL,
        far_clipping: Supported::ALL,
        depth_ranges: Supported::ALL,
        guard_band: GUARD_BAND_REACH,
        ties_to_even: true,
    };
}

/// What an implementation declares about itself; the suite checks it against this.
///
/// A rasterizer that decides coverage in floating point declares [`Snapping::Float`] and, if it
/// breaks ties on edges by no rule (`w ≥ 0` on every edge, say), `fill: None`: the exact rules
/// are then not applicable, and the invariant rules still judge it, samples within
/// `tolerance_subpixels` (in 1/256 px) of an edge aside.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Profile {
    /// A short name, as `--impl` takes it.
    pub name: String,
    /// Where vertices lie when coverage is decided.
    pub snapping: Snapping,
    /// Which edges own samples lying exactly on them; `None` for no tie rule.
    pub fill: Option<FillConvention>,
    /// How depth is interpolated.
    pub depth: DepthConvention,
    /// Half-width of the band around edges where rules that compare with an oracle don't care,
    /// in grid steps ([`Snapping::unit_px`]); at least one is used.
    pub tolerance_subpixels: u32,
    /// The precision claimed for interpolation: barycentrics and depth within
    /// `2^-precision_bits` of their exact values, barycentrics summing to 1 within a quarter of
    /// that. Neither Vulkan nor D3D bounds it; 18 is what f32 on exact edge values keeps, with
    /// room (the reference's claim), 14 what an f32 rasterizer evaluating plane equations keeps.
    pub precision_bits: u8,
    /// Optional abilities and supported states.
    pub features: Features,
}

impl Profile {
    /// The tolerance band in pixels: never under one unit, because snapping alone moves an edge
    /// by up to √2/2 of a grid step.
    #[must_use]
    pub fn band_px(&self) -> f64 {
        f64::from(self.tolerance_subpixels.max(1)) * self.snapping.unit_px()
    }

    /// Whether every setting of `state` is supported.
    #[must_use]
    pub fn supports(&self, state: &DrawState) -> bool {
        *state == self.fit(*state)
    }

    /// `state` with each unsupported setting replaced by a supported one.
    #[must_use]
    pub fn fit(&self, state: DrawState) -> DrawState {
        let f = &self.features;
        let mut fitted = state;
        fitted.cull = f.cull_modes.fit(state.cull);
        fitted.front_face = f.front_faces.fit(state.front_face);
        fitted.depth.compare = f.compare_ops.fit(state.depth.compare);
        fitted.depth.write = f.depth_writes.fit(state.depth.write);
        fitted.clip_far = f.far_clipping.fit(state.clip_far);
        fitted.depth_range = f.depth_ranges.fit(state.depth_range);
        fitted
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two sets are equal when they hold the same settings, whatever order they were listed in
    /// (`Profile` and `Features` derive their equality from it).
    #[test]
    fn sets_are_equal_by_their_settings() {
        let both = Supported::only(&[CullMode::Back, CullMode::None]);
        assert_eq!(both, Supported::only(&[CullMode::None, CullMode::Back]));
        assert_ne!(both, Supported::only(&[CullMode::None]));
        assert_ne!(both, Supported::<CullMode>::ALL);
    }

    /// The words `certify` prints for a profile's snapping (README, "Certified implementations").
    #[test]
    fn snapping_reads_as_certify_prints_it() {
        assert_eq!(Snapping::Grid(8).to_string(), "8 subpixel bits");
        assert_eq!(Snapping::Float.to_string(), "no grid (float)");
    }

    #[test]
    fn a_set_keeps_what_it_supports_and_falls_back_in_order() {
        let ops = Supported::only(&[CompareOp::GreaterOrEqual, CompareOp::LessOrEqual]);
        assert!(ops.contains(CompareOp::LessOrEqual));
        assert!(!ops.contains(CompareOp::Less));
        assert_eq!(ops.fit(CompareOp::Less), CompareOp::LessOrEqual);
        assert_eq!(ops.fit(CompareOp::GreaterOrEqual), CompareOp::GreaterOrEqual);
        assert_eq!(
            ops.values().collect::<Vec<_>>(),
            [CompareOp::LessOrEqual, CompareOp::GreaterOrEqual]
        );
        assert_eq!(format!("{ops:?}"), "{LessOrEqual, GreaterOrEqual}");
        let none: Supported<bool> = Supported::only(&[]);
        assert!(!none.fit(false));
        assert!(Supported::<CompareOp>::ALL.contains(CompareOp::Never));
    }

    #[test]
    fn fitting_a_state_changes_only_what_is_unsupported() {
        let mut features = Features::ALL;
        features.far_clipping = Supported::only(&[true]);
        features.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
        let profile = Profile {
            name: "gpu".into(),
            snapping: Snapping::Grid(8),
            fill: Some(FillConvention::TopLeft),
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: 1,
            precision_bits: 18,
            features,
        };
        let state = DrawState {
            front_face: FrontFace::Clockwise,
            cull: CullMode::Front,
            ..DrawState::default()
        };
        assert!(!profile.supports(&state));
        let fitted = profile.fit(state);
        assert!(fitted.clip_far);
        assert_eq!(fitted.front_face, FrontFace::CounterClockwise);
        assert_eq!(fitted.cull, CullMode::Front);
        assert!(profile.supports(&fitted));
        assert_eq!(profile.band_px(), 1.0 / 256.0);
        let float = Profile {
            snapping: Snapping::Float,
            tolerance_subpixels: 4,
            ..profile
        };
        assert_eq!(float.band_px(), 4.0 / 256.0);
    }
}
