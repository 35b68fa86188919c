//! A failure of something the claimed specification does not require is `beyond-spec`, with
//! the sentence it rests on; the same failure under refrast's conventions (or a specification
//! that requires it) is a failure.

use refrast::{
    Draw, DrawError, FillConvention, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, Spec,
};
use refrast_conformance::{Options, RuleReport, Status, certify};

/// The reference claiming `spec`, drawing with `fill` (declaring top-left), and drawing a
/// vertex with a non-finite `w` as if its `w` were 1 (lavapipe draws from `w = +∞`).
struct Claiming {
    spec: Spec,
    inner: Reference,
}

impl Claiming {
    fn new(spec: Spec, fill: FillConvention) -> Self {
        Self {
            spec,
            inner: Reference::new(ReferenceConfig {
                fill,
                ..ReferenceConfig::default()
            }),
        }
    }
}

impl Rasterizer for Claiming {
    fn profile(&self) -> Profile {
        Profile {
            name: format!("claims-{}", self.spec.name()),
            fill: Some(FillConvention::TopLeft),
            spec: self.spec,
            ..self.inner.profile()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut draw = draw.clone();
        for p in &mut draw.positions {
            if !p[3].is_finite() && p[..3].iter().all(|c| c.is_finite()) {
                p[3] = 1.0;
            }
        }
        self.inner.rasterize(&draw)
    }
}

fn run(r: &mut Claiming, rule: &str) -> RuleReport {
    let options = Options {
        cases: Some(300),
        rule: Some(rule.to_owned()),
        ..Options::default()
    };
    let report = certify(r, &options, |_| {});
    let rule = report.rules.into_iter().next().expect("the rule ran");
    assert_eq!(report.refused, None, "a judgeable profile is not refused");
    rule
}

/// Drawing a non-finite w: undefined in Vulkan, so beyond it; a NaN is discarded in D3D11.3,
/// so there it fails (the D3D part draws NaN alone); refrast's conventions fail it too.
#[test]
fn a_non_finite_vertex_drawn_is_beyond_vulkan_but_fails_d3d11_and_refrast() {
    let rule = "robust.non-finite.discarded";
    let vulkan = run(&mut Claiming::new(Spec::Vulkan, FillConvention::TopLeft), rule);
    assert_eq!(vulkan.status, Status::BeyondSpec, "{vulkan:#?}");
    let note = vulkan.spec_note.unwrap_or_default();
    assert!(
        note.contains("Vulkan 1.4") && note.contains("unspecified results"),
        "{note}"
    );
    for spec in [Spec::D3d11, Spec::Refrast] {
        let other = run(&mut Claiming::new(spec, FillConvention::TopLeft), rule);
        assert_eq!(other.status, Status::Fail, "{spec:?}: {other:#?}");
        assert_eq!(other.spec_note, None);
    }
}

/// A bottom-right tie rule declared top-left: the exact rules fail it, but away from edges it
/// is right, which is all Vulkan asks (beyond Vulkan); D3D11.3 fixes top-left (a failure).
#[test]
fn a_misdeclared_tie_rule_is_beyond_vulkan_and_fails_d3d11() {
    for rule in ["fill.top-left.exact", "fill.brute-force.exact"] {
        let vulkan = run(
            &mut Claiming::new(Spec::Vulkan, FillConvention::BottomRight),
            rule,
        );
        assert_eq!(vulkan.status, Status::BeyondSpec, "{rule}: {vulkan:#?}");
        assert!(vulkan.spec_note.unwrap_or_default().contains("fixes no tie rule"));
        let d3d = run(&mut Claiming::new(Spec::D3d11, FillConvention::BottomRight), rule);
        assert_eq!(d3d.status, Status::Fail, "{rule}: {d3d:#?}");
    }
}

/// A report whose only failures are beyond the claimed specification has passed.
#[test]
fn beyond_spec_does_not_fail_a_report() {
    let options = Options {
        cases: Some(100),
        rule: Some("robust.non-finite.*".to_owned()),
        ..Options::default()
    };
    let report = certify(
        &mut Claiming::new(Spec::Vulkan, FillConvention::TopLeft),
        &options,
        |_| {},
    );
    assert_eq!(report.beyond_spec(), 1);
    assert!(report.passed());
}
