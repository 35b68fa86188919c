//! What an implementation supports: the draw states it can be sent, its optional outputs, and
//! the conventions it claims beyond the profile's core ([`crate::Profile`]).

use std::fmt;
use std::marker::PhantomData;

use crate::bias::{BiasSupport, DepthBias};
use crate::conservative::ConservativeSupport;
use crate::depth::{CompareOp, DepthRange, ViewportDepth};
use crate::distance::{Distances, MAX_DISTANCES};
use crate::setup::{CullMode, FrontFace};
use crate::state::{PolygonMode, ProvokingVertex};
use crate::viewport::GUARD_BAND_REACH;

/// A draw-state setting with a few values, each of which an implementation may support.
pub trait Setting: Copy + PartialEq + fmt::Debug + 'static {
    /// Every value, the one to fall back on first.
    const VALUES: &'static [Self];
}

/// Both faces are not among the values: [`StateSupport::cull_both`] declares them, so a
/// profile written before they existed (`Supported::ALL`) does not claim them.
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

impl Setting for ProvokingVertex {
    const VALUES: &'static [Self] = &[Self::First, Self::Last];
}

/// Fill is not among the values: every rasterizer fills, so [`StateSupport::polygon_modes`]
/// declares only the line and point modes it has besides.
impl Setting for PolygonMode {
    const VALUES: &'static [Self] = &[Self::Line, Self::Point];
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

    /// No value: for a setting of [`StateSupport`], which a rasterizer may lack altogether.
    pub const NONE: Self = Self {
        mask: 0,
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

    /// Whether no value at all is supported: a profile the suite cannot judge.
    #[must_use]
    pub fn is_empty(self) -> bool {
        self.mask == 0
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

/// No value, as [`StateSupport`]'s default declares none of its state.
impl<T: Setting> Default for Supported<T> {
    fn default() -> Self {
        Self::NONE
    }
}

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

/// How close to the exact projected position snapping puts a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SnapAccuracy {
    /// On the grid point nearest the exact `x/w` (refrast; D3D11.3 §3.2.4.1 allows 0.6 ulp);
    /// at an exact tie, on the even one if `ties_to_even` says so, else on either.
    #[default]
    Nearest,
    /// On either grid point next to the exact `x/w`, per axis: within one grid step of it.
    /// Vulkan computes the viewport transform in floating point, so a vertex a hair from a
    /// snap tie may land on its far side (SwiftShader's `(x·(1/w))·scale + offset` in f32).
    WithinOneStep,
    /// On the grid point at or below the exact raster coordinate, per axis (floor): one grid
    /// point, so judged as exactly as [`SnapAccuracy::Nearest`], with an edge up to √2 steps
    /// from the exact one.
    Floor,
    /// On the grid point between the exact raster coordinate and 0, per axis: the truncation
    /// of a float-to-fixed conversion (Skia's 26.6 fixed point; a scan converter's
    /// `(int)(x * 64)`). One grid point, like [`SnapAccuracy::Floor`].
    TowardZero,
}

impl SnapAccuracy {
    /// Every accuracy, refrast's first.
    pub const ALL: [SnapAccuracy; 4] = [Self::Nearest, Self::WithinOneStep, Self::Floor, Self::TowardZero];

    /// The word the pipe protocol, the profile cache and reports use: `nearest`,
    /// `within-one-step`, `floor`, `toward-zero`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Nearest => "nearest",
            Self::WithinOneStep => "within-one-step",
            Self::Floor => "floor",
            Self::TowardZero => "toward-zero",
        }
    }

    /// The accuracy called `name` ([`SnapAccuracy::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.name() == name)
    }

    /// The grid points a raster coordinate `v` (in grid units) may snap to, refrast's choice
    /// (nearest, half to even) first where it is among them: one point but for
    /// [`SnapAccuracy::WithinOneStep`] off the grid, and an exact tie without `ties_to_even`.
    #[must_use]
    pub fn candidates(self, v: f64, ties_to_even: bool) -> Vec<f64> {
        let nearest = v.round_ties_even();
        let other = if nearest > v { v.floor() } else { v.ceil() };
        match self {
            Self::Floor => vec![v.floor()],
            Self::TowardZero => vec![v.trunc()],
            Self::WithinOneStep if other != nearest => vec![nearest, other],
            Self::Nearest if !ties_to_even && v - v.floor() == 0.5 => vec![nearest, other],
            Self::Nearest | Self::WithinOneStep => vec![nearest],
        }
    }

    /// The least tolerance band, in grid steps, that covers how far this snapping moves an
    /// edge from the exact one: √2/2 of a step to the nearest point, up to √2 otherwise.
    #[must_use]
    pub fn least_band(self) -> u32 {
        match self {
            Self::Nearest => 1,
            Self::WithinOneStep | Self::Floor | Self::TowardZero => 2,
        }
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
    /// The cull modes it implements (at least one; the suite orients what it draws to face
    /// front when `None` is not among them).
    pub cull_modes: Supported<CullMode>,
    /// The front faces it can be told (at least one).
    pub front_faces: Supported<FrontFace>,
    /// `resolve` runs its own depth test, so the depth-test rules judge it.
    pub depth_test: bool,
    /// The depth compare ops of its depth test (at least one).
    pub compare_ops: Supported<CompareOp>,
    /// Depth writes on (`true`) and off (`false`) (at least one).
    pub depth_writes: Supported<bool>,
    /// Far-plane clipping off (`false`: depth clamped instead) and on (`true`) (at least one).
    pub far_clipping: Supported<bool>,
    /// The clip volumes' z ranges (at least one).
    pub depth_ranges: Supported<DepthRange>,
    /// How far beyond each side of the viewport, in pixels, a triangle may reach while x/y
    /// clipping still moves no edge inside it (a guard band, so its coverage can be exact); 0 when
    /// any reach outside may move one.
    pub guard_band: u32,
    /// Snapping rounds a coordinate exactly halfway between two grid points to the even one
    /// (D3D11 §3.2.4.1); Vulkan leaves ties to the implementation, so without this claim the
    /// suite moves every vertex off such a tie before drawing.
    pub ties_to_even: bool,
    /// How close to the exact `x/w` snapping lands; the exact rules and the interpolation
    /// rules accept either neighbouring grid point under [`SnapAccuracy::WithinOneStep`].
    pub snap: SnapAccuracy,
    /// Zero area is decided on the snapped input triangle before clipping, as the reference
    /// does: a triangle whose vertices all project onto one line draws nothing even where the
    /// near plane cuts it. Without this claim, clipping first may leave a sliver along the line
    /// (Vulkan allows it), which the suite then judges only outside the tolerance band.
    pub zero_area_before_clipping: bool,
    /// It clips in homogeneous space (near always, far when enabled), so a triangle with a
    /// vertex behind the eye draws its visible part. `false` for a 2D scan converter that
    /// projects `x/w`, `y/w` and fills the triangle between: the suite then sends it only
    /// vertices in front of the near plane (behind-the-eye vertices moved in front, beyond
    /// the far plane moved onto it where far clipping is on), and the clip rules are n/a.
    pub clips_in_3d: bool,
    /// Its `z` arrives rewritten to `2z − w` in f32 under the `−w ≤ z ≤ w` volume before it
    /// clips, as wgpu's OpenGL ES backend does to every vertex shader: a vertex within that
    /// rounding of the near plane may land on either side, and a triangle the exact volume
    /// leaves empty may keep a sliver. Values of such draws are required only where the
    /// rewritten geometry, too, stays within the specification's floating-point range.
    pub z_rewritten_in_f32: bool,
}

/// The draw state a rasterizer honours beyond [`Features`]: state the contract gained after
/// its first rasterizers were written, so it defaults to none (a profile ending in
/// `..Profile::default()` keeps its meaning, and the suite sends it none of this state).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct StateSupport {
    /// It honours [`DrawState::scissor`](crate::DrawState::scissor): no fragment outside the
    /// rectangle, for every topology and sample count it draws.
    pub scissor: bool,
    /// It honours [`DrawState::sample_mask`](crate::DrawState::sample_mask): sample `i` of a
    /// fragment kept only where bit `i` is set, for every topology and sample count it draws
    /// (one sample included: bit 0, but under OpenGL and OpenGL ES, whose multisample
    /// operations skip a single-sample target), and nothing written of a sample the mask drops.
    pub sample_mask: bool,
    /// It honours [`DrawState::interpolation`](crate::DrawState::interpolation) at every sample
    /// count above one it declares: [`Interpolation::Centroid`](crate::Interpolation::Centroid)
    /// gives a triangle's fragments in a pixel one set of barycentrics, at a location inside
    /// the pixel and the triangle (the pixel centre where it covers every sample, else its
    /// first covered sample the mask keeps, under a refrast claim).
    pub centroid: bool,
    /// The conservative rasterization of filled triangles it offers
    /// ([`DrawState::conservative`](crate::DrawState::conservative)), at every sample count it
    /// declares; `None` when it has none.
    pub conservative: Option<ConservativeSupport>,
    /// It culls both faces ([`CullMode::FrontAndBack`](crate::CullMode::FrontAndBack)): no
    /// triangle drawn, lines and points drawn as with culling off.
    pub cull_both: bool,
    /// It draws triangle strips ([`Topology::TriangleStrip`](crate::Topology::TriangleStrip)),
    /// at every sample count it declares.
    pub triangle_strips: bool,
    /// It draws triangle fans ([`Topology::TriangleFan`](crate::Topology::TriangleFan)), at
    /// every sample count it declares.
    pub triangle_fans: bool,
    /// The provoking-vertex modes under which it reports [`Fragment::flat`](crate::Fragment::flat),
    /// the vertex whose flat values a fragment carries; none when it reports none. A draw in
    /// another mode is drawn all the same, its `flat` unjudged (`None` is the honest answer).
    pub flat: Supported<ProvokingVertex>,
    /// It honours [`DrawState::viewport_depth`](crate::DrawState::viewport_depth) with
    /// `min ≤ max`: window depth `n + (f − n)·u`, clamped to `[n, f]`.
    pub viewport_depth: bool,
    /// It also honours `min > max` (Vulkan allows it; D3D11 and wgpu do not).
    pub inverted_depth: bool,
    /// It draws with depth clipping off ([`DrawState::clip_near`](crate::DrawState::clip_near)
    /// and `clip_far` both `false`): nothing cut at the near or far plane, depth clamped to the
    /// viewport's depth range (Vulkan's `depthClampEnable`, wgpu's `unclipped_depth`).
    pub unclipped_depth: bool,
    /// The depth bias it honours on triangles ([`DrawState::depth_bias`](crate::DrawState::depth_bias)),
    /// declared with the format and slope measure it computes it for; `None` when it has none.
    pub depth_bias: Option<BiasSupport>,
    /// The polygon modes besides fill it draws triangles in
    /// ([`DrawState::polygon_mode`](crate::DrawState::polygon_mode)): line (edges drawn by its
    /// line rule, so with [`Profile::lines`](crate::Profile::lines) declared) and point (its
    /// points, with [`Profile::points`](crate::Profile::points)), at every sample count at
    /// which it draws both triangles and those.
    pub polygon_modes: Supported<PolygonMode>,
    /// How many user clip distances per vertex it honours ([`Draw::distances`](crate::Draw::distances)):
    /// a primitive drawn only where each, interpolated linearly in clip space, is `≥ 0`; 0 when
    /// it has none. At most [`MAX_DISTANCES`](crate::MAX_DISTANCES) with the cull distances.
    pub clip_distances: usize,
    /// How many cull distances per vertex it honours: a primitive with every vertex negative in
    /// one of them is not drawn; 0 when it has none.
    pub cull_distances: usize,
}

impl StateSupport {
    /// Whether it honours viewport depth ranges at all: declared ordered, or reversed (which
    /// implies ordered).
    #[must_use]
    pub fn honours_viewport_depth(&self) -> bool {
        self.viewport_depth || self.inverted_depth
    }

    /// `range` when declared; an inverted one in order where only ordered ones are, and the
    /// whole range where none is.
    #[must_use]
    pub fn fit_viewport_depth(&self, range: ViewportDepth) -> ViewportDepth {
        match (
            self.honours_viewport_depth(),
            self.inverted_depth || !range.is_inverted(),
        ) {
            (false, _) => ViewportDepth::FULL,
            (true, true) => range,
            (true, false) => ViewportDepth {
                min: range.max,
                max: range.min,
            },
        }
    }

    /// `bias` where declared, its clamp 0 where the clamp is not; none where bias is not.
    #[must_use]
    pub fn fit_depth_bias(&self, bias: Option<DepthBias>) -> Option<DepthBias> {
        let support = self.depth_bias?;
        bias.map(|b| DepthBias {
            clamp: if support.clamp { b.clamp } else { 0.0 },
            ..b
        })
    }

    /// `mode` where declared, else fill.
    #[must_use]
    pub fn fit_polygon_mode(&self, mode: PolygonMode) -> PolygonMode {
        if self.polygon_modes.contains(mode) {
            mode
        } else {
            PolygonMode::Fill
        }
    }

    /// `distances` with only as many clip and cull distances as are declared.
    #[must_use]
    pub fn fit_distances(&self, distances: &Distances) -> Distances {
        distances.truncated(self.clip_distances, self.cull_distances)
    }

    /// None of it: what a rasterizer written before it existed declares.
    pub const NONE: StateSupport = StateSupport {
        scissor: false,
        sample_mask: false,
        centroid: false,
        conservative: None,
        cull_both: false,
        triangle_strips: false,
        triangle_fans: false,
        flat: Supported::NONE,
        viewport_depth: false,
        inverted_depth: false,
        unclipped_depth: false,
        depth_bias: None,
        polygon_modes: Supported::NONE,
        clip_distances: 0,
        cull_distances: 0,
    };
    /// All of it, as the reference honours it.
    pub const ALL: StateSupport = StateSupport {
        scissor: true,
        sample_mask: true,
        centroid: true,
        conservative: Some(ConservativeSupport::REFERENCE),
        cull_both: true,
        triangle_strips: true,
        triangle_fans: true,
        flat: Supported::ALL,
        viewport_depth: true,
        inverted_depth: true,
        unclipped_depth: true,
        depth_bias: Some(BiasSupport::REFERENCE),
        polygon_modes: Supported::ALL,
        clip_distances: MAX_DISTANCES,
        cull_distances: MAX_DISTANCES,
    };
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
        snap: SnapAccuracy::Nearest,
        zero_area_before_clipping: true,
        clips_in_3d: true,
        z_rewritten_in_f32: false,
    };

    /// The settings of which it supports no value, each as what to declare instead: a profile
    /// with any is one the suite cannot judge (no draw could be sent to it).
    #[must_use]
    pub fn empty_settings(&self) -> Vec<&'static str> {
        [
            (
                self.cull_modes.is_empty(),
                "cull_modes (at least one of None, Back, Front)",
            ),
            (
                self.front_faces.is_empty(),
                "front_faces (CounterClockwise, Clockwise or both)",
            ),
            (
                self.compare_ops.is_empty(),
                "compare_ops (at least one compare op, such as Less)",
            ),
            (self.depth_writes.is_empty(), "depth_writes (true, false or both)"),
            (
                self.far_clipping.is_empty(),
                "far_clipping (false for depth clamping, true, or both)",
            ),
            (
                self.depth_ranges.is_empty(),
                "depth_ranges (ZeroToOne, NegativeOneToOne or both)",
            ),
        ]
        .into_iter()
        .filter_map(|(empty, what)| empty.then_some(what))
        .collect()
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
        assert!(none.is_empty() && !ops.is_empty());
        assert!(Supported::<CompareOp>::ALL.contains(CompareOp::Never));
    }

    /// Every setting left without a value is named, with what to declare; none for the
    /// reference's features.
    #[test]
    fn empty_settings_are_named_with_what_to_declare() {
        assert!(Features::ALL.empty_settings().is_empty());
        let features = Features {
            cull_modes: Supported::only(&[]),
            depth_ranges: Supported::only(&[]),
            ..Features::ALL
        };
        let named = features.empty_settings();
        assert_eq!(named.len(), 2);
        assert!(named[0].starts_with("cull_modes") && named[1].starts_with("depth_ranges"));
    }
}
