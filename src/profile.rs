//! What an implementation declares about itself: its conventions, the specification it claims,
//! its tolerance and the draw states it supports ([`Features`]). The suite judges it by these,
//! and sends it only states it supports.

use std::fmt;

use crate::edge::FillConvention;
use crate::features::{Features, StateSupport};
use crate::primitive::{LineRule, PointClipping, SAMPLE_COUNTS, SamplePattern, Topology};
use crate::setup::CullMode;
use crate::state::{DrawState, Interpolation, ProvokingVertex};

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

/// The specification an implementation claims to follow: a rule checking something that
/// specification leaves undefined or does not require reports a failure as beyond it, not as a
/// failure of conformance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Spec {
    /// refrast's own conventions (lib.rs): every rule is required.
    #[default]
    Refrast,
    /// Vulkan 1.4.
    Vulkan,
    /// OpenGL 4.6 core.
    OpenGl,
    /// Direct3D 11.3's functional specification.
    D3d11,
    /// OpenGL ES 3.2, which differs from OpenGL 4.6 where it matters here: points are clipped
    /// by the near and far planes only, the clip volume's z is always `−w ≤ z ≤ w`, there is
    /// no depth clamp. What a driver driven through OpenGL ES (wgpu's GL backend) is held to.
    OpenGlEs,
}

impl Spec {
    /// Every specification, refrast's first.
    pub const ALL: [Spec; 5] = [
        Self::Refrast,
        Self::Vulkan,
        Self::OpenGl,
        Self::D3d11,
        Self::OpenGlEs,
    ];

    /// The name reports, `--spec` and the pipe protocol use.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Refrast => "refrast",
            Self::Vulkan => "vulkan",
            Self::OpenGl => "opengl",
            Self::D3d11 => "d3d11",
            Self::OpenGlEs => "opengles",
        }
    }

    /// The specification called `name` ([`Spec::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// As a sentence names it: "Vulkan 1.4".
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::Refrast => "refrast's conventions",
            Self::Vulkan => "Vulkan 1.4",
            Self::OpenGl => "OpenGL 4.6",
            Self::D3d11 => "D3D11.3",
            Self::OpenGlEs => "OpenGL ES 3.2",
        }
    }
}

/// What an implementation declares about itself; the suite checks it against this.
///
/// A rasterizer that decides coverage in floating point declares [`Snapping::Float`] and, if it
/// breaks ties on edges by no rule (`w ≥ 0` on every edge, say), `fill: None`: the exact rules
/// are then not applicable, and the invariant rules still judge it, samples within
/// `tolerance_subpixels` (in 1/256 px) of an edge aside.
///
/// The last six fields declare lines, points and multisampling. Left at their defaults
/// (`..Profile::default()`) they declare a triangle rasterizer at one sample per pixel, at the
/// pixel's centre; the rules of the `line.`, `point.` and `msaa.` families are then not
/// applicable, and the suite sends it nothing but triangle lists at one sample.
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
    /// The specification it claims to follow.
    pub spec: Spec,
    /// How it draws lines of width one, if it draws lines (list and strip).
    pub lines: Option<LineRule>,
    /// Whether it draws points of size one: a square one pixel wide centred on the point,
    /// covered as a polygon.
    pub points: bool,
    /// Where line and point end points are snapped; `None` for the grid of triangles
    /// ([`snapping`](Self::snapping)).
    pub endpoint_snapping: Option<Snapping>,
    /// Where points alone are snapped, when on another grid than line ends (softpipe snaps
    /// points to a quarter pixel, its lines and triangles to none); `None` for
    /// [`endpoint_snapping`](Self::endpoint_snapping)'s.
    pub point_snapping: Option<Snapping>,
    /// The sample counts above one it supports, each with its positions.
    pub multisample: Vec<SamplePattern>,
    /// What clipping does to a point whose centre lies outside the viewport in x or y.
    pub point_clipping: PointClipping,
    /// The draw state it honours beyond [`features`](Self::features): the scissor, culling of
    /// both faces, triangle strips and fans, flat values, so far.
    pub state: StateSupport,
}

impl Default for Profile {
    /// refrast's conventions with no name: an 8-bit grid, the top-left rule, screen-linear
    /// depth, the reference's tolerance and precision, every state of [`Features`] and none of
    /// [`StateSupport`], triangles at one sample.
    fn default() -> Self {
        Self {
            name: String::new(),
            snapping: Snapping::Grid(8),
            fill: Some(FillConvention::TopLeft),
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: 1,
            precision_bits: 18,
            features: Features::ALL,
            spec: Spec::Refrast,
            lines: None,
            points: false,
            endpoint_snapping: None,
            point_snapping: None,
            multisample: Vec::new(),
            point_clipping: PointClipping::AllClipPlanes,
            state: StateSupport::NONE,
        }
    }
}

impl Profile {
    /// The tolerance band in pixels: never under one unit, because snapping to the nearest grid
    /// point alone moves an edge by up to √2/2 of a grid step; never under two where a vertex
    /// may land on either neighbour ([`SnapAccuracy::WithinOneStep`](crate::SnapAccuracy::WithinOneStep): up to √2 of a step).
    #[must_use]
    pub fn band_px(&self) -> f64 {
        let least = self.features.snap.least_band();
        f64::from(self.tolerance_subpixels.max(least)) * self.snapping.unit_px()
    }

    /// `Err` with what to declare when the suite cannot judge this profile at all: a setting
    /// with no supported value (no draw could be sent), or a grid finer than the 16 bits the
    /// oracles snap to. Certification refuses such a profile before any rule runs.
    pub fn judgeable(&self) -> Result<(), String> {
        let mut problems: Vec<String> = self
            .features
            .empty_settings()
            .into_iter()
            .map(|what| format!("no value of {what}"))
            .collect();
        if let Snapping::Grid(bits) = self.snapping
            && bits > 16
        {
            problems.push(format!(
                "a grid of {bits} subpixel bits, finer than the 16 the oracles snap to (declare Snapping::Float)"
            ));
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(format!("the profile declares {}", problems.join("; ")))
        }
    }

    /// These declarations for the first contract alone, triangle lists at one sample: lines,
    /// points, sample counts above one and the later state ([`StateSupport`]) left out. For a
    /// rasterizer that borrows another's profile (`..Reference::default().profile()`, which
    /// declares all of them) but draws only triangles as the first contract has them.
    #[must_use]
    pub fn triangles_only(self) -> Self {
        let none = Self::default();
        Self {
            state: none.state,
            lines: none.lines,
            points: none.points,
            endpoint_snapping: none.endpoint_snapping,
            point_snapping: none.point_snapping,
            multisample: none.multisample,
            point_clipping: none.point_clipping,
            ..self
        }
    }

    /// The pattern of `samples` samples per pixel: the centre for one, else the declared one.
    #[must_use]
    pub fn pattern(&self, samples: u8) -> Option<SamplePattern> {
        if samples == 1 {
            return SamplePattern::standard(1);
        }
        self.multisample.iter().find(|p| p.count() == samples).copied()
    }

    /// Whether it draws `topology` at `samples` samples per pixel.
    #[must_use]
    pub fn draws(&self, topology: Topology, samples: u8) -> bool {
        let drawn = match topology {
            Topology::TriangleList => true,
            Topology::LineList | Topology::LineStrip => self.lines.is_some(),
            Topology::PointList => self.points,
            Topology::TriangleStrip => self.state.triangle_strips,
            Topology::TriangleFan => self.state.triangle_fans,
        };
        drawn && self.pattern(samples).is_some()
    }

    /// The topologies it draws, in [`Topology::ALL`]'s order (triangle lists first).
    #[must_use]
    pub fn topologies(&self) -> Vec<Topology> {
        Topology::ALL.into_iter().filter(|&t| self.draws(t, 1)).collect()
    }

    /// The sample counts it supports, 1 first.
    #[must_use]
    pub fn sample_counts(&self) -> Vec<u8> {
        SAMPLE_COUNTS
            .into_iter()
            .filter(|&n| self.pattern(n).is_some())
            .collect()
    }

    /// Whether every setting of `state` is supported. The provoking vertex is no such setting:
    /// it changes only [`Fragment::flat`](crate::Fragment::flat), which is required only under
    /// the modes a profile declares ([`StateSupport::flat`]), so any draw may ask any mode.
    #[must_use]
    pub fn supports(&self, state: &DrawState) -> bool {
        let fitted = self.fit(*state);
        DrawState {
            provoking_vertex: fitted.provoking_vertex,
            ..*state
        } == fitted
    }

    /// `state` with each unsupported setting replaced by a supported one (an undeclared scissor
    /// or sample mask dropped, centroid interpolation at the sample where undeclared, undeclared culling of both faces replaced like an unsupported cull mode, the
    /// provoking vertex one the profile reports flat values under, an undeclared polygon mode
    /// filled): what the suite sends.
    #[must_use]
    pub fn fit(&self, state: DrawState) -> DrawState {
        let f = &self.features;
        let mut fitted = state;
        fitted.cull = if state.cull == CullMode::FrontAndBack && self.state.cull_both {
            state.cull
        } else {
            f.cull_modes.fit(state.cull)
        };
        fitted.front_face = f.front_faces.fit(state.front_face);
        fitted.depth.compare = f.compare_ops.fit(state.depth.compare);
        fitted.depth.write = f.depth_writes.fit(state.depth.write);
        // Depth clipping off is both planes off; else far clipping as declared.
        fitted.clip_near = !self.state.unclipped_depth || state.clip_near;
        fitted.clip_far = fitted.clip_near && f.far_clipping.fit(state.clip_far);
        fitted.viewport_depth = self.state.fit_viewport_depth(state.viewport_depth);
        fitted.depth_bias = self.state.fit_depth_bias(state.depth_bias);
        fitted.depth_range = f.depth_ranges.fit(state.depth_range);
        fitted.scissor = state.scissor.filter(|_| self.state.scissor);
        if !self.state.sample_mask {
            fitted.sample_mask = DrawState::ALL_SAMPLES;
        }
        if !self.state.centroid {
            fitted.interpolation = Interpolation::Sample;
        }
        fitted.conservative = state
            .conservative
            .and_then(|mode| self.state.conservative.and_then(|support| support.fit(mode)));
        fitted.polygon_mode = self.state.fit_polygon_mode(state.polygon_mode);
        // Without flat values the mode changes nothing: the default is what such a draw has.
        fitted.provoking_vertex = if self.state.flat.is_empty() {
            ProvokingVertex::First
        } else {
            self.state.flat.fit(state.provoking_vertex)
        };
        fitted
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::depth::{CompareOp, ViewportDepth};
    use crate::features::{SnapAccuracy, StateSupport, Supported};
    use crate::setup::{CullMode, FrontFace};

    /// The words `certify` prints for a profile's snapping (docs/certified.md).
    #[test]
    fn snapping_reads_as_certify_prints_it() {
        assert_eq!(Snapping::Grid(8).to_string(), "8 subpixel bits");
        assert_eq!(Snapping::Float.to_string(), "no grid (float)");
    }

    fn gpu(features: Features) -> Profile {
        Profile {
            name: "gpu".into(),
            snapping: Snapping::Grid(8),
            fill: Some(FillConvention::TopLeft),
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: 1,
            precision_bits: 18,
            features,
            spec: Spec::Vulkan,
            ..Profile::default()
        }
    }

    /// Nothing declared: triangles at one sample, nothing else.
    #[test]
    fn the_default_profile_is_triangles_at_one_sample() {
        let p = Profile::default();
        assert_eq!(p.topologies(), [Topology::TriangleList]);
        assert_eq!(p.sample_counts(), [1]);
        assert!(!p.draws(Topology::LineList, 1));
        assert!(!p.draws(Topology::TriangleList, 4));
        let more = Profile {
            lines: Some(LineRule::DiamondExit),
            multisample: vec![SamplePattern::standard(4).expect("4")],
            ..p
        };
        assert!(more.draws(Topology::LineStrip, 4));
        assert!(!more.draws(Topology::TriangleStrip, 1));
        assert_eq!(more.sample_counts(), [1, 4]);
        let strips = Profile {
            state: StateSupport {
                triangle_strips: true,
                ..StateSupport::NONE
            },
            ..more.clone()
        };
        assert!(strips.draws(Topology::TriangleStrip, 4) && !strips.draws(Topology::TriangleFan, 1));
        let fewer = more.clone().triangles_only();
        assert_eq!(fewer.topologies(), [Topology::TriangleList]);
        assert_eq!(fewer.sample_counts(), [1]);
        assert_eq!(
            Profile {
                name: "x".into(),
                ..fewer
            },
            Profile {
                name: "x".into(),
                ..Profile::default()
            }
        );
    }

    #[test]
    fn fitting_a_state_changes_only_what_is_unsupported() {
        let mut features = Features::ALL;
        features.far_clipping = Supported::only(&[true]);
        features.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
        let profile = gpu(features);
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
        // The provoking vertex is fitted to a declared mode but never makes a draw unsupported.
        let last_only = Profile {
            state: StateSupport {
                flat: Supported::only(&[ProvokingVertex::Last]),
                ..StateSupport::NONE
            },
            ..profile.clone()
        };
        assert!(last_only.supports(&fitted));
        assert_eq!(last_only.fit(fitted).provoking_vertex, ProvokingVertex::Last);
        assert_eq!(profile.fit(fitted).provoking_vertex, ProvokingVertex::First);
        assert_eq!(profile.band_px(), 1.0 / 256.0);
        let float = Profile {
            snapping: Snapping::Float,
            tolerance_subpixels: 4,
            ..profile
        };
        assert_eq!(float.band_px(), 4.0 / 256.0);
        let mut either = gpu(Features::ALL);
        either.features.snap = SnapAccuracy::WithinOneStep;
        assert_eq!(
            either.band_px(),
            2.0 / 256.0,
            "either neighbour moves an edge up to √2 steps"
        );
    }

    /// Depth clipping off goes only to a profile declaring it, and then with far clipping off
    /// whatever far clipping it declares; a depth range only to one honouring ranges, a
    /// reversed one in order where only ordered ones are declared.
    #[test]
    fn depth_clipping_and_ranges_are_fitted_to_what_is_declared() {
        let reversed = ViewportDepth { min: 0.75, max: 0.25 };
        let asked = DrawState {
            clip_near: false,
            clip_far: true,
            viewport_depth: reversed,
            ..DrawState::default()
        };
        let mut profile = gpu(Features {
            far_clipping: Supported::only(&[true]),
            ..Features::ALL
        });
        let plain = profile.fit(asked);
        assert!(plain.clip_near && plain.clip_far && plain.viewport_depth == ViewportDepth::FULL);
        assert!(!profile.supports(&asked));
        profile.state = StateSupport {
            unclipped_depth: true,
            viewport_depth: true,
            ..StateSupport::NONE
        };
        let fitted = profile.fit(asked);
        assert!(!fitted.clip_near && !fitted.clip_far);
        assert_eq!(fitted.viewport_depth, ViewportDepth { min: 0.25, max: 0.75 });
        assert!(profile.supports(&fitted));
        profile.state = StateSupport {
            inverted_depth: true,
            ..StateSupport::NONE
        };
        assert!(profile.state.honours_viewport_depth());
        assert_eq!(profile.fit(asked).viewport_depth, reversed);
    }

    /// A profile with a setting left empty, or a grid the oracles cannot snap to, is refused
    /// with what to declare; one supported value of each is enough.
    #[test]
    fn a_profile_is_judgeable_with_one_value_of_each_setting() {
        let one = Features {
            cull_modes: Supported::only(&[CullMode::Back]),
            front_faces: Supported::only(&[FrontFace::Clockwise]),
            compare_ops: Supported::only(&[CompareOp::Less]),
            depth_writes: Supported::only(&[true]),
            far_clipping: Supported::only(&[false]),
            ..Features::ALL
        };
        assert_eq!(gpu(one).judgeable(), Ok(()));
        let none = Features {
            cull_modes: Supported::only(&[]),
            ..one
        };
        let why = gpu(none).judgeable().expect_err("no cull mode");
        assert!(why.contains("no value of cull_modes"), "{why}");
        let fine = Profile {
            snapping: Snapping::Grid(20),
            ..gpu(one)
        };
        assert!(fine.judgeable().expect_err("20 bits").contains("Snapping::Float"));
    }

    /// Each specification reads back from its name.
    #[test]
    fn specifications_are_named_both_ways() {
        for spec in Spec::ALL {
            assert_eq!(Spec::from_name(spec.name()), Some(spec));
        }
        assert_eq!(Spec::from_name("metal"), None);
    }
}
