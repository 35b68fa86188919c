//! Each hint both ways: on a correct rasterizer whose profile says the wrong thing, and on the
//! mutant whose bug has the same shape. Both fail the rule, and both get the hint.

use refrast::{
    CullMode, DepthRange, Draw, DrawError, DrawState, FillConvention, Fragment, FrontFace, Profile,
    Rasterizer, Reference, ReferenceConfig, Resolved, SubpixelBits, Supported,
};
use refrast_conformance::{Options, Status, certify};
use refrast_zoo::mutant::{Bug, Mutant};

/// A correct rasterizer (the reference, configured) that declares `profile` and draws with its
/// state changed by `force` whatever it is told: its profile is wrong, its drawing is not.
struct Misdeclared {
    inner: Reference,
    profile: Profile,
    force: fn(&mut DrawState),
    /// Weights numbered from the last vertex, as a rasterizer numbering from its provoking vertex.
    rotate: bool,
}

impl Misdeclared {
    fn new(config: ReferenceConfig, declare: impl FnOnce(&mut Profile), force: fn(&mut DrawState)) -> Self {
        let mut profile = Reference::default().profile();
        profile.name = "misdeclared".into();
        declare(&mut profile);
        Self {
            inner: Reference::new(config),
            profile,
            force,
            rotate: false,
        }
    }

    fn forced(&self, draw: &Draw) -> Draw {
        let mut draw = draw.clone();
        (self.force)(&mut draw.state);
        draw
    }
}

impl Rasterizer for Misdeclared {
    fn profile(&self) -> Profile {
        self.profile.clone()
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut frags = self.inner.rasterize(&self.forced(draw))?;
        if self.rotate {
            for f in &mut frags {
                f.barycentric.rotate_right(1);
            }
        }
        Ok(frags)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        self.inner.resolve(&self.forced(draw))
    }
}

/// The hint of `rule`'s failure on `r`, which must fail it.
fn hint(r: &mut dyn Rasterizer, rule: &str) -> String {
    let options = Options {
        cases: Some(500),
        rules: vec![rule.to_owned()],
        ..Options::default()
    };
    let report = certify(r, &options, |_| {});
    let name = report.implementation.clone();
    let failed = report
        .rules
        .into_iter()
        .find(|x| x.id == rule)
        .filter(|x| x.status == Status::Fail)
        .unwrap_or_else(|| panic!("{name} passes {rule}"));
    failed
        .hint
        .unwrap_or_else(|| panic!("{name} fails {rule} without a hint: {:?}", failed.message))
}

/// Both subjects fail `rule` with a hint containing `words`.
fn both(declared: &mut dyn Rasterizer, bug: Bug, rule: &str, words: &str) {
    for (who, r) in [
        ("misdeclared", declared),
        ("mutant", &mut Mutant::new(bug) as &mut dyn Rasterizer),
    ] {
        let hint = hint(r, rule);
        assert!(hint.contains(words), "{who} on {rule}: {hint}");
    }
}

/// Told counter-clockwise and back-face culling, it takes clockwise front faces: every
/// oriented triangle is culled, as `one-winding` drops its clockwise ones.
#[test]
fn a_missing_winding_is_hinted() {
    let mut declared = Misdeclared::new(
        ReferenceConfig::default(),
        |p| {
            p.features.cull_modes = Supported::only(&[CullMode::Back]);
            p.features.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
        },
        |s| {
            s.cull = CullMode::Back;
            s.front_face = FrontFace::Clockwise;
        },
    );
    both(
        &mut declared,
        Bug::OneWinding,
        "fill.mesh.exactly-once",
        "is missing, and one drawn reversed is not",
    );
}

/// Told counter-clockwise, it takes clockwise front faces: every facing comes out inverted.
#[test]
fn inverted_facing_is_hinted() {
    let mut declared = Misdeclared::new(
        ReferenceConfig::default(),
        |p| {
            p.features.cull_modes = Supported::only(&[CullMode::None]);
            p.features.front_faces = Supported::only(&[FrontFace::CounterClockwise]);
        },
        |s| s.front_face = FrontFace::Clockwise,
    );
    both(
        &mut declared,
        Bug::InvertedFacing,
        "meta.facing.from-winding",
        "front_facing the opposite",
    );
}

/// A bottom-right rasterizer declared top-left.
#[test]
fn a_mirrored_fill_convention_is_hinted() {
    let config = ReferenceConfig {
        fill: FillConvention::BottomRight,
        ..ReferenceConfig::default()
    };
    let mut declared = Misdeclared::new(config, |_| {}, |_| {});
    both(
        &mut declared,
        Bug::BottomRightAsTopLeft,
        "fill.brute-force.exact",
        "exactly what the bottom-right fill convention gives",
    );
}

/// A 7-bit rasterizer declared 8.
#[test]
fn a_coarser_grid_is_hinted() {
    let config = ReferenceConfig {
        subpixel_bits: SubpixelBits::new(7).expect("7 bits"),
        ..ReferenceConfig::default()
    };
    let mut declared = Misdeclared::new(config, |_| {}, |_| {});
    both(
        &mut declared,
        Bug::DroppedSubpixelBit,
        "fill.brute-force.exact",
        "exactly what 7 subpixel bits give",
    );
}

/// A Vulkan-style rasterizer (0 ≤ z ≤ w) declared OpenGL's volume only.
#[test]
fn the_other_depth_map_is_hinted() {
    let mut declared = Misdeclared::new(
        ReferenceConfig::default(),
        |p| p.features.depth_ranges = Supported::only(&[DepthRange::NegativeOneToOne]),
        |s| s.depth_range = DepthRange::ZeroToOne,
    );
    both(
        &mut declared,
        Bug::UnmappedGlDepth,
        "depth.screen-linear.matches-raycast",
        "volume's window depth z/w, where the draw asked for",
    );
}

/// A rasterizer numbering vertices from its provoking (last) vertex.
#[test]
fn permuted_barycentrics_are_hinted() {
    let mut declared = Misdeclared::new(ReferenceConfig::default(), |_| {}, |_| {});
    declared.rotate = true;
    both(
        &mut declared,
        Bug::PermutedBarycentrics,
        "bary.perspective.matches-raycast",
        "the ray cast's weights of vertices 2, 0, 1 in that order",
    );
}

/// A correct rasterizer, correctly declared, fails nothing, so gets no hint: and the reference
/// restricted to one cull mode and front face, which these hints would misread if they fired on
/// culling the rules asked for, passes the rules above.
#[test]
fn correct_profiles_pass_the_hinted_rules() {
    let rules = [
        "fill.mesh.exactly-once",
        "meta.facing.from-winding",
        "fill.brute-force.exact",
        "depth.screen-linear.matches-raycast",
        "bary.perspective.matches-raycast",
    ];
    let mut fixed = Misdeclared::new(
        ReferenceConfig::default(),
        |p| {
            p.features.cull_modes = Supported::only(&[CullMode::Back]);
            p.features.front_faces = Supported::only(&[FrontFace::Clockwise]);
        },
        |s| {
            s.cull = CullMode::Back;
            s.front_face = FrontFace::Clockwise;
        },
    );
    for rule in rules {
        let options = Options {
            cases: Some(300),
            rules: vec![rule.to_owned()],
            ..Options::default()
        };
        let report = certify(&mut fixed, &options, |_| {});
        assert!(report.passed(), "{rule}: {:?}", report.rules[0].message);
    }
}

/// A Skia-style scan converter (26.6 fixed point by truncation toward zero, bottom-right ties)
/// declared as rounding to the nearest grid point: every hint it gets is verified on the failing
/// case, so none blames the tie rule or the grid (as hints did before they were verified), and
/// the exact rule's hint names the rounding it does.
#[test]
fn a_truncating_rasterizer_gets_no_wrong_hint() {
    let config = ReferenceConfig {
        subpixel_bits: SubpixelBits::new(6).expect("6 bits"),
        snap_rounding: refrast::SnapRounding::TowardZero,
        fill: FillConvention::BottomRight,
        ..ReferenceConfig::default()
    };
    let declare = |p: &mut Profile| {
        p.snapping = refrast::Snapping::Grid(6);
        p.fill = Some(FillConvention::BottomRight);
        p.features.snap = refrast::SnapAccuracy::Nearest;
        p.features.ties_to_even = false;
    };
    let mut truncating = Misdeclared::new(config, declare, |_| {});
    let right = hint(&mut truncating, "fill.brute-force.exact");
    assert!(right.contains("toward zero (truncation)"), "{right}");
    let options = Options {
        cases: Some(500),
        rules: vec!["fill.*".into(), "meta.*".into(), "clip.*".into()],
        ..Options::default()
    };
    let report = certify(&mut truncating, &options, |_| {});
    for rule in &report.rules {
        if let Some(hint) = &rule.hint {
            assert!(
                hint.contains("toward zero"),
                "{}: a hint other than the rounding: {hint}",
                rule.id
            );
        }
    }
}

/// No tie rule, either way: `e >= 0` on every edge covers a sample on a shared edge twice,
/// `e > 0` by neither; each is named with its edge test, and the correct reference gets none
/// (`correct_profiles_pass_the_hinted_rules`).
#[test]
fn a_missing_tie_rule_is_hinted() {
    for (bug, test) in [
        (Bug::InclusiveEdges, "`e >= 0`"),
        (Bug::ExclusiveEdges, "`e > 0`"),
    ] {
        let hint = hint(&mut Mutant::new(bug), "fill.mesh.exactly-once");
        assert!(
            hint.contains("no tie rule") && hint.contains(test),
            "{bug:?}: {hint}"
        );
    }
}
