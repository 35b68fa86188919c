//! The reference restricted to one setting (or a few), as a rasterizer that supports less would
//! be: it declares only the restricted values and *uses* them whatever a draw asks, leaves out
//! the outputs it does not declare, and rounds, snaps and clips as its claims allow. Each must
//! pass or be `n/a` on every rule: the suite's own proof that a rule asks its question under
//! whatever a profile supports (`tests/integration/restricted.rs`, and `refrast certify --impl
//! 'restricted:*'` at full cases).

mod state;

use refrast::{
    ClipMode, CompareOp, Conservative, CullMode, DepthRange, Draw, DrawError, DrawState, Features, Fragment,
    FrontFace, Interpolation, PointClipping, Profile, Rasterizer, Reference, ReferenceConfig, Resolved,
    SnapAccuracy, SnapRounding, Spec, StateSupport, Supported,
};

/// The reference under a restricted profile.
#[derive(Clone, Debug)]
pub struct Restricted {
    name: String,
    inner: Reference,
    features: Features,
    state: StateSupport,
    spec: Spec,
}

impl Restricted {
    /// The reference configured by `config`, declaring `restrict` of its features, `state` and
    /// `spec`, named `restricted:NAME`.
    #[must_use]
    pub fn new(
        name: &str,
        config: ReferenceConfig,
        restrict: impl FnOnce(&mut Features),
        state: StateSupport,
        spec: Spec,
    ) -> Self {
        let inner = Reference::new(config);
        let mut features = inner.profile().features;
        restrict(&mut features);
        Self {
            name: format!("restricted:{name}"),
            inner,
            features,
            state,
            spec,
        }
    }

    /// The draw with every setting replaced by the restricted one it would use; under OpenGL
    /// and OpenGL ES, no sample mask at one sample, as their multisample operations run on
    /// multisampled targets only; under Vulkan, OpenGL and OpenGL ES, a centroid at each
    /// covered sample, inside the pixel and the triangle as they require, but not one location
    /// per pixel; overestimation grown by the overestimation size it declares (what the suite
    /// must accept from a driver).
    fn forced(&self, draw: &Draw) -> Draw {
        let mut state = self.profile().fit(draw.state);
        if draw.samples == 1 && matches!(self.spec, Spec::OpenGl | Spec::OpenGlEs) {
            state.sample_mask = DrawState::ALL_SAMPLES;
        }
        if matches!(self.spec, Spec::Vulkan | Spec::OpenGl | Spec::OpenGlEs) {
            state.interpolation = Interpolation::Sample;
        }
        // Overestimation grown by all the overestimation it declares it may add.
        if let (Some(Conservative::Overestimate { extra }), Some(support)) =
            (state.conservative, self.state.conservative)
        {
            state.conservative = Some(Conservative::Overestimate {
                extra: extra + support.overestimation_size,
            });
        }
        Draw {
            state,
            distances: self.state.fit_distances(&draw.distances),
            ..draw.clone()
        }
    }
}

impl Rasterizer for Restricted {
    fn profile(&self) -> Profile {
        Profile {
            name: self.name.clone(),
            features: self.features,
            state: self.state,
            spec: self.spec,
            ..self.inner.profile()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        // The reference's lines, points and samples: the restrictions are of triangle states.
        let mut fragments = self.inner.rasterize(&self.forced(draw))?;
        // What it does not declare, it does not compute: garbage the suite must ignore.
        for f in &mut fragments {
            if !self.features.perspective_barycentrics {
                f.barycentric = [f32::NAN; 3];
            }
            if !self.features.screen_barycentrics {
                f.screen_barycentric = None;
            }
            if self.state.flat.is_empty() {
                f.flat = Some(u32::MAX - 1);
            }
        }
        Ok(fragments)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let forced = self.forced(draw);
        if self.features.depth_test {
            self.inner.resolve(&forced)
        } else {
            // No depth test of its own: the trait's replay of its fragments.
            Ok(Resolved::from_fragments(&forced, self.rasterize(draw)?))
        }
    }
}

/// A restriction: its name after `restricted:`, what it is, and how to build it.
pub struct Restriction {
    /// The name after `restricted:`.
    pub name: String,
    /// One line on what it restricts.
    pub description: String,
    /// Builds it.
    pub make: Box<dyn Fn() -> Restricted + Send + Sync>,
}

/// How a restriction changes the reference's features.
trait Restrict: Fn(&mut Features) + Clone + Send + Sync + 'static {}

impl<F: Fn(&mut Features) + Clone + Send + Sync + 'static> Restrict for F {}

/// A restriction of the default reference's features.
fn only(name: impl Into<String>, description: impl Into<String>, restrict: impl Restrict) -> Restriction {
    configured(
        name,
        description,
        ReferenceConfig::default(),
        restrict,
        Spec::Refrast,
    )
}

/// A restriction with its own reference configuration and claimed specification, declaring
/// all the state beyond [`Features`].
fn configured(
    name: impl Into<String>,
    description: impl Into<String>,
    config: ReferenceConfig,
    restrict: impl Restrict,
    spec: Spec,
) -> Restriction {
    restriction(name, description, config, restrict, StateSupport::ALL, spec)
}

/// A restriction of everything a profile declares.
fn restriction(
    name: impl Into<String>,
    description: impl Into<String>,
    config: ReferenceConfig,
    restrict: impl Restrict,
    state: StateSupport,
    spec: Spec,
) -> Restriction {
    let name = name.into();
    let inner = name.clone();
    Restriction {
        name,
        description: description.into(),
        make: Box::new(move || Restricted::new(&inner, config, restrict.clone(), state, spec)),
    }
}

/// Every restriction: each optional setting of [`Features`] at each value it may be
/// restricted to, the roundings, guard bands and specification claims a profile may declare,
/// and three combinations (a fixed-function rasterizer, the least a profile can declare, an
/// OpenGL-style one).
#[must_use]
pub fn restrictions() -> Vec<Restriction> {
    let mut all = vec![
        only("cull=none", "no culling at all", |f| {
            f.cull_modes = Supported::only(&[CullMode::None])
        }),
        only("cull=back", "always culls back faces", |f| {
            f.cull_modes = Supported::only(&[CullMode::Back])
        }),
        only("cull=front", "always culls front faces", |f| {
            f.cull_modes = Supported::only(&[CullMode::Front]);
        }),
        only(
            "cull=back+front",
            "culls back or front faces, never neither",
            |f| {
                f.cull_modes = Supported::only(&[CullMode::Back, CullMode::Front]);
            },
        ),
        only("front-face=ccw", "counter-clockwise front faces only", |f| {
            f.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
        }),
        only("front-face=cw", "clockwise front faces only", |f| {
            f.front_faces = Supported::only(&[FrontFace::Clockwise]);
        }),
        only("depth-write=on", "depth writes always on", |f| {
            f.depth_writes = Supported::only(&[true])
        }),
        only("depth-write=off", "depth writes always off", |f| {
            f.depth_writes = Supported::only(&[false])
        }),
        only("far-clipping=off", "no far clipping: depth clamped", |f| {
            f.far_clipping = Supported::only(&[false]);
        }),
        only("far-clipping=on", "far clipping always on", |f| {
            f.far_clipping = Supported::only(&[true])
        }),
        only(
            "depth-range=zero-to-one",
            "only the 0 ≤ z ≤ w clip volume",
            |f| {
                f.depth_ranges = Supported::only(&[DepthRange::ZeroToOne]);
            },
        ),
        only(
            "depth-range=negative-one-to-one",
            "only OpenGL's −w ≤ z ≤ w",
            |f| {
                f.depth_ranges = Supported::only(&[DepthRange::NegativeOneToOne]);
            },
        ),
        only("barycentrics=screen", "screen-space barycentrics only", |f| {
            f.perspective_barycentrics = false;
        }),
        only(
            "barycentrics=perspective",
            "perspective-correct barycentrics only",
            |f| {
                f.screen_barycentrics = false;
            },
        ),
        only("barycentrics=none", "no barycentrics at all", |f| {
            f.perspective_barycentrics = false;
            f.screen_barycentrics = false;
        }),
        only("depth-test=none", "no depth test of its own", |f| {
            f.depth_test = false
        }),
        only(
            "zero-area=unclaimed",
            "no claim about zero area before clipping",
            |f| {
                f.zero_area_before_clipping = false;
            },
        ),
        configured(
            "ties=away-from-zero",
            "snap ties rounded away from zero (dEQP's reference), no ties-to-even claim",
            ReferenceConfig {
                snap_rounding: SnapRounding::NearestAwayFromZero,
                ..ReferenceConfig::default()
            },
            |_: &mut Features| {},
            Spec::Refrast,
        ),
        configured(
            "snap=floor",
            "snapping down to the grid, declared loosely: within one step of x/w, not the nearest point",
            ReferenceConfig {
                snap_rounding: SnapRounding::Floor,
                ..ReferenceConfig::default()
            },
            |f: &mut Features| f.snap = SnapAccuracy::WithinOneStep,
            Spec::Refrast,
        ),
        configured(
            "snap=floor-exact",
            "snapping down to the grid, declared as exactly that (snap floor)",
            ReferenceConfig {
                snap_rounding: SnapRounding::Floor,
                ..ReferenceConfig::default()
            },
            |_: &mut Features| {},
            Spec::Refrast,
        ),
        configured(
            "snap=toward-zero",
            "snapping by truncation toward the raster origin, declared as such (snap toward-zero)",
            ReferenceConfig {
                snap_rounding: SnapRounding::TowardZero,
                ..ReferenceConfig::default()
            },
            |_: &mut Features| {},
            Spec::Refrast,
        ),
        configured(
            "guard-band=0",
            "x/y clipped at the viewport: no guard band",
            ReferenceConfig {
                clip: ClipMode::Full,
                ..ReferenceConfig::default()
            },
            |_: &mut Features| {},
            Spec::Refrast,
        ),
        configured(
            "guard-band=64",
            "x/y clipped 64 px beyond the viewport",
            ReferenceConfig {
                clip: ClipMode::Reach(64),
                ..ReferenceConfig::default()
            },
            |_: &mut Features| {},
            Spec::Refrast,
        ),
        only(
            "guard-band=8192",
            "the reference's guard band, declared as such",
            |_: &mut Features| {},
        ),
    ];
    for &op in <CompareOp as refrast::Setting>::VALUES {
        all.push(only(
            format!("compare={}", compare_word(op)),
            format!("depth compare op {op:?} only"),
            move |f: &mut Features| f.compare_ops = Supported::only(&[op]),
        ));
    }
    for spec in [Spec::Vulkan, Spec::OpenGl, Spec::OpenGlEs, Spec::D3d11] {
        // OpenGL ES clips points by the near and far planes only: the reference plays it so.
        let point_clipping = match spec {
            Spec::OpenGlEs => PointClipping::UserClipPlanesOnly,
            _ => PointClipping::AllClipPlanes,
        };
        all.push(configured(
            format!("spec={}", spec.name()),
            format!("claims {} instead of refrast's conventions", spec.title()),
            ReferenceConfig {
                point_clipping,
                ..ReferenceConfig::default()
            },
            |_: &mut Features| {},
            spec,
        ));
    }
    all.push(configured(
        "points=pop-free",
        "points outside the viewport kept by clipping (user-clip-planes-only), declared so",
        ReferenceConfig {
            point_clipping: PointClipping::UserClipPlanesOnly,
            ..ReferenceConfig::default()
        },
        |_: &mut Features| {},
        Spec::Refrast,
    ));
    all.extend(state::restrictions());
    all.extend(combinations());
    all
}

/// Restrictions of several settings at once.
fn combinations() -> Vec<Restriction> {
    vec![
        only(
            "fixed-function",
            "a fixed-function course rasterizer: culls back faces, clockwise front, Less with writes, far clamped, no screen barycentrics",
            |f| {
                f.cull_modes = Supported::only(&[CullMode::Back]);
                f.front_faces = Supported::only(&[FrontFace::Clockwise]);
                f.compare_ops = Supported::only(&[CompareOp::Less]);
                f.depth_writes = Supported::only(&[true]);
                f.far_clipping = Supported::only(&[false]);
                f.screen_barycentrics = false;
            },
        ),
        restriction(
            "least",
            "one value of every setting, no optional output or claim: culls front faces, LessOrEqual, no depth test, no barycentrics, no guard band, snapping down, no scissor, strips or fans",
            ReferenceConfig {
                clip: ClipMode::Full,
                snap_rounding: SnapRounding::Floor,
                ..ReferenceConfig::default()
            },
            |f| {
                f.cull_modes = Supported::only(&[CullMode::Front]);
                f.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
                f.compare_ops = Supported::only(&[CompareOp::LessOrEqual]);
                f.depth_writes = Supported::only(&[false]);
                f.far_clipping = Supported::only(&[true]);
                f.depth_ranges = Supported::only(&[DepthRange::ZeroToOne]);
                f.perspective_barycentrics = false;
                f.screen_barycentrics = false;
                f.depth_test = false;
                f.zero_area_before_clipping = false;
            },
            StateSupport::NONE,
            Spec::Vulkan,
        ),
        configured(
            "opengl-style",
            "OpenGL's clip volume only, far clipping on, culling off or back, a 64-px guard band, ties away from zero",
            ReferenceConfig {
                clip: ClipMode::Reach(64),
                snap_rounding: SnapRounding::NearestAwayFromZero,
                ..ReferenceConfig::default()
            },
            |f| {
                f.depth_ranges = Supported::only(&[DepthRange::NegativeOneToOne]);
                f.far_clipping = Supported::only(&[true]);
                f.cull_modes = Supported::only(&[CullMode::None, CullMode::Back]);
                f.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
            },
            Spec::OpenGl,
        ),
    ]
}

/// A compare op as the names of the restrictions spell it (the pipe protocol's words).
fn compare_word(op: CompareOp) -> &'static str {
    match op {
        CompareOp::Never => "never",
        CompareOp::Less => "less",
        CompareOp::Equal => "equal",
        CompareOp::LessOrEqual => "less-equal",
        CompareOp::Greater => "greater",
        CompareOp::NotEqual => "not-equal",
        CompareOp::GreaterOrEqual => "greater-equal",
        CompareOp::Always => "always",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every restriction declares a profile the suite can judge, under a name of its own, and
    /// declares exactly what its reference configuration does where that shows in the profile.
    #[test]
    fn every_restriction_is_judgeable_and_named_once() {
        let all = restrictions();
        let mut names: Vec<&str> = all.iter().map(|r| r.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all.len());
        for r in &all {
            let p = (r.make)().profile();
            assert_eq!(p.judgeable(), Ok(()), "{}", r.name);
            assert_eq!(p.name, format!("restricted:{}", r.name));
        }
        let floor = restrictions()
            .into_iter()
            .find(|r| r.name == "snap=floor")
            .expect("listed");
        let p = (floor.make)().profile();
        assert_eq!(p.features.snap, SnapAccuracy::WithinOneStep);
        assert!(!p.features.ties_to_even);
        let truncating = restrictions()
            .into_iter()
            .find(|r| r.name == "snap=toward-zero")
            .expect("listed");
        assert_eq!(
            (truncating.make)().profile().features.snap,
            SnapAccuracy::TowardZero
        );
    }

    /// A restricted rasterizer uses its one value whatever the draw asks: told to cull nothing,
    /// `cull=back` still culls a clockwise triangle.
    #[test]
    fn a_restricted_rasterizer_uses_its_value_whatever_is_asked() {
        let back = restrictions()
            .into_iter()
            .find(|r| r.name == "cull=back")
            .expect("listed");
        let mut r = (back.make)();
        let viewport = refrast::Viewport::new(16, 16).expect("16×16");
        let clockwise = vec![
            [-1.0, 1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, -1.0, 0.5, 1.0],
        ];
        let draw = Draw::new(viewport, clockwise, vec![[2, 0, 1]]);
        assert_eq!(draw.state.cull, CullMode::None);
        assert!(r.rasterize(&draw).expect("draws").is_empty());
        let mut reversed = draw.clone();
        reversed.indices = vec![2, 1, 0];
        assert_eq!(r.rasterize(&reversed).expect("draws").len(), 120);
    }
}
