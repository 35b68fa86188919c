//! Depth clipping off: what every specification requires (triangles wholly in front of the eye,
//! crossing the near and far planes, drawn whole with depth clamped) and what it leaves to a
//! guard band's f32 cuts (triangles crossing w = 0), each as a named regression test of the
//! false verdicts lavapipe, llvmpipe, softpipe and SwiftShader got before the rule had levels.

use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Spec, ViewportDepth};
use refrast_conformance::{Options, RuleReport, Status, certify};

/// How the reference is broken: where it draws more than it should, with depth clipping off.
#[derive(Clone, Copy, PartialEq)]
enum Slip {
    /// A triangle with a vertex at `w ≤ 0` also covers pixel row 0 (as a guard band's cut in
    /// f32 of a triangle nearly in a plane through the eye lands it at the viewport's edge).
    EyeCrossing,
    /// Depth is not clamped to the viewport's range: depth is reported unmapped (in `[0, 1]`).
    Unclamped,
}

/// The reference claiming `spec`, slipping as `slip` says where depth clipping is off.
struct Slipping {
    spec: Spec,
    slip: Slip,
    inner: Reference,
}

impl Rasterizer for Slipping {
    fn profile(&self) -> Profile {
        Profile {
            name: "slipping".into(),
            spec: self.spec,
            ..self.inner.profile()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        if draw.state.clip_near {
            return self.inner.rasterize(draw);
        }
        if self.slip == Slip::Unclamped {
            let mut full = draw.clone();
            full.state.viewport_depth = ViewportDepth::FULL;
            return self.inner.rasterize(&full);
        }
        let mut fragments = self.inner.rasterize(draw)?;
        for (t, corners) in draw.triangles().iter().enumerate() {
            if corners.iter().any(|&i| draw.positions[i as usize][3] <= 0.0) {
                let covered: Vec<u32> = fragments
                    .iter()
                    .filter(|f| f.primitive == t as u32 && f.y == 0)
                    .map(|f| f.x)
                    .collect();
                let extra = (0..draw.viewport.width()).filter(|x| !covered.contains(x));
                let template = Fragment {
                    x: 0,
                    y: 0,
                    sample: 0,
                    primitive: t as u32,
                    depth: 0.5,
                    barycentric: [1.0, 0.0, 0.0],
                    screen_barycentric: None,
                    front_facing: true,
                    flat: draw.provoking(t),
                };
                fragments.extend(extra.map(|x| Fragment { x, ..template }).collect::<Vec<_>>());
            }
        }
        Ok(fragments)
    }
}

fn run(spec: Spec, slip: Slip) -> RuleReport {
    let mut r = Slipping {
        spec,
        slip,
        inner: Reference::default(),
    };
    let options = Options {
        cases: Some(300),
        rules: vec!["clip.unclipped-depth.clamped".to_owned()],
        ..Options::default()
    };
    let report = certify(&mut r, &options, |_| {});
    report.rules.into_iter().next().expect("the rule ran")
}

/// Extra coverage from a triangle crossing w = 0 is beyond Vulkan and OpenGL (the four drivers'
/// class: their guard bands cut such a triangle in f32), but fails refrast's conventions.
#[test]
fn eye_crossing_slips_with_depth_clipping_off_are_beyond_the_specifications() {
    for spec in [Spec::Vulkan, Spec::OpenGl, Spec::OpenGlEs, Spec::D3d11] {
        let report = run(spec, Slip::EyeCrossing);
        assert_eq!(report.status, Status::BeyondSpec, "{spec:?}: {report:#?}");
        let note = report.spec_note.unwrap_or_default();
        assert!(note.contains("only the x and y planes"), "{note}");
    }
    assert_eq!(run(Spec::Refrast, Slip::EyeCrossing).status, Status::Fail);
}

/// Depth left unclamped (and unmapped) fails every specification: it shows on triangles wholly
/// in front of the eye, which all of them require.
#[test]
fn unclamped_depth_fails_every_specification() {
    for spec in [Spec::Vulkan, Spec::OpenGl, Spec::D3d11, Spec::Refrast] {
        let report = run(spec, Slip::Unclamped);
        assert_eq!(report.status, Status::Fail, "{spec:?}: {report:#?}");
    }
}
