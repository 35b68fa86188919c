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
        rules: vec![rule.to_owned()],
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
        note.contains("Vulkan 1.4")
            && note.contains("unspecified results")
            && !note.contains("required part"),
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
        let note = vulkan.spec_note.unwrap_or_default();
        assert!(note.contains("fixes no tie rule"), "{note}");
        // The required part's own cases are said: the rule's count is the whole rule's.
        assert!(note.ends_with("the required part passed all 300 cases"), "{note}");
        let d3d = run(&mut Claiming::new(Spec::D3d11, FillConvention::BottomRight), rule);
        assert_eq!(d3d.status, Status::Fail, "{rule}: {d3d:#?}");
    }
}

/// A report whose only failures are beyond the claimed specification has passed.
#[test]
fn beyond_spec_does_not_fail_a_report() {
    let options = Options {
        cases: Some(100),
        rules: vec!["robust.non-finite.*".to_owned()],
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

/// SwiftShader's NaN weights at default cases (robust.bit-patterns, case 1285): every input
/// finite and small, but vertex 1 lies inside the view volume at w = 1.9·10⁻¹⁹, so the clipped
/// polygon needs 1/w far beyond the 2^32 Vulkan asks floats to represent: not required. A
/// vertex at w = −FLT_MIN clipped away is nothing to divide by (SwiftShader's finding 9 stays
/// required), and a coordinate beyond 2^32 is out of range.
#[test]
fn arithmetic_beyond_two_to_the_32_is_not_required_of_vulkan() {
    use refrast_conformance::Scene;
    use refrast_conformance::rules::robust::within_float_range;
    let tiny_w_inside = Scene::new(
        1,
        1,
        vec![
            [0.0, -1.383_254_8e-5, 0.0, 1.855_197e-19],
            [0.0, -0.0, 0.0, 1.855_197e-19],
            [6.336_223_5e-20, -0.0, 0.0, 3.517_311_3e-36],
        ],
        vec![[0, 1, 2]],
    );
    assert!(!within_float_range(&tiny_w_inside));
    let min_w_clipped_away = Scene::new(
        1,
        2,
        vec![
            [-0.452_509_43, 0.240_404_3, -0.368_272_66, -0.698_964_54],
            [3.160_516_5, 1.175_494_4e-38, 2.484_375, 3.040_919_3],
            [-1.430_746_9, -6.426_126e-8, -1.122_525_9, -1.175_494_4e-38],
        ],
        vec![[0, 1, 2]],
    );
    assert!(within_float_range(&min_w_clipped_away));
    let mut huge = min_w_clipped_away.clone();
    huge.positions[0][0] = 5.0e9;
    assert!(!within_float_range(&huge));
}
