//! The suite used from another crate: panics in any method are findings (`crash`), a wrong
//! answer that does not come again on replay is a `flake`, `fail_fast` stops at the first
//! failing rule, and failure messages name the difference that happened.

use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference};
use refrast_conformance::rules::common::compare_sets;
use refrast_conformance::{Options, Scene, Status, catalogue, certify, run_rule};

/// The reference, with one thing done wrong.
struct Wrapped {
    inner: Reference,
    fault: Fault,
    /// Draws so far.
    calls: u32,
}

#[derive(Clone, Copy)]
enum Fault {
    /// `profile()` panics.
    PanickingProfile,
    /// `rasterize` panics.
    PanickingDraw,
    /// A copy of the first fragment one column right of the viewport, besides the right ones.
    ExtraOutside,
    /// Primitive ids 0 and 1 swapped.
    SwappedIds,
    /// No fragments on the third draw only: a wrong answer the same draw does not give again.
    WrongOnce,
}

impl Wrapped {
    fn new(fault: Fault) -> Self {
        Self {
            inner: Reference::default(),
            fault,
            calls: 0,
        }
    }
}

impl Rasterizer for Wrapped {
    fn profile(&self) -> Profile {
        assert!(
            !matches!(self.fault, Fault::PanickingProfile),
            "this profile cannot be read"
        );
        self.inner.profile()
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = self.inner.rasterize(draw)?;
        self.calls += 1;
        match self.fault {
            Fault::WrongOnce if self.calls == 3 => fragments.clear(),
            Fault::WrongOnce => {}
            Fault::PanickingProfile => {}
            Fault::PanickingDraw => panic!("the rasteriser fell over"),
            Fault::ExtraOutside => {
                if let Some(&f) = fragments.first() {
                    fragments.push(Fragment {
                        x: draw.viewport.width(),
                        ..f
                    });
                }
            }
            Fault::SwappedIds => fragments.iter_mut().for_each(|f| {
                f.primitive = match f.primitive {
                    0 => 1,
                    1 => 0,
                    p => p,
                }
            }),
        }
        Ok(fragments)
    }
}

#[test]
fn a_failure_that_does_not_replay_is_a_flake() {
    let mut r = Wrapped::new(Fault::WrongOnce);
    let report = run_rule(&rule("fill.top-left.exact"), &mut r, &options());
    assert_eq!(report.status, Status::Flake, "{report:#?}");
    assert!(report.status.is_failure(), "a flake is no pass");
    let message = report.message.unwrap_or_default();
    assert!(message.contains("passed when replayed"), "{message}");
}

fn rule(id: &str) -> refrast_conformance::Rule {
    catalogue()
        .into_iter()
        .find(|r| r.id == id)
        .unwrap_or_else(|| panic!("no rule {id}"))
}

fn options() -> Options {
    Options {
        cases: Some(64),
        ..Options::default()
    }
}

#[test]
fn a_panicking_profile_fails_the_rule_instead_of_escaping() {
    let mut r = Wrapped::new(Fault::PanickingProfile);
    let report = run_rule(&rule("fill.top-left.exact"), &mut r, &options());
    assert_eq!(report.status, Status::Crash);
    let message = report.message.unwrap_or_default();
    assert!(
        message.starts_with("profile() panicked: this profile cannot be read at "),
        "{message}"
    );
    // certify too: the profile's panic is the implementation's name, every rule fails.
    let all = certify(
        &mut r,
        &Options {
            rules: vec!["robust.*".into()],
            ..options()
        },
        |_| {},
    );
    assert!(all.implementation.contains("panicked"), "{}", all.implementation);
    assert!(all.rules.iter().all(|r| r.status == Status::Crash));
    assert!(!all.passed(), "a crash is no pass");
}

#[test]
fn a_panic_is_reported_with_its_place() {
    let mut r = Wrapped::new(Fault::PanickingDraw);
    let report = run_rule(&rule("fill.top-left.exact"), &mut r, &options());
    assert_eq!(report.status, Status::Crash, "{report:#?}");
    let message = report.message.unwrap_or_default();
    assert!(
        message.starts_with("the rasterizer panicked: the rasteriser fell over at ")
            && message.contains("outside.rs:"),
        "{message}"
    );
}

#[test]
fn fail_fast_stops_at_the_first_failing_rule() {
    let mut r = Wrapped::new(Fault::PanickingDraw);
    let quick = Options {
        fail_fast: true,
        ..options()
    };
    let report = certify(&mut r, &quick, |_| {});
    assert_eq!(report.rules.len(), 1, "only the first rule ran");
    assert_eq!(report.rules[0].status, Status::Crash, "a crash stops it too");
    assert_eq!(report.rules.len() + report.not_run.len(), catalogue().len());
    assert_eq!(report.not_run[0], catalogue()[1].id);
    // Without it, every rule runs and nothing is left unrun.
    let mut fine = Reference::default();
    let all = certify(
        &mut fine,
        &Options {
            rules: vec!["robust.*".into()],
            fail_fast: true,
            ..options()
        },
        |_| {},
    );
    assert!(all.passed() && all.not_run.is_empty());
}

#[test]
fn fragments_outside_the_viewport_are_named_as_such() {
    let mut r = Wrapped::new(Fault::ExtraOutside);
    let report = run_rule(&rule("fill.top-left.exact"), &mut r, &options());
    let message = report.message.unwrap_or_default();
    assert!(
        message.contains("fragments outside the") && message.contains("viewport, the first at"),
        "{message}"
    );
}

#[test]
fn swapped_primitive_ids_name_the_sample_and_both_owners() {
    // A quad of two triangles, the lower-left one first.
    let positions = vec![
        [-0.5, -0.5, 0.5, 1.0],
        [0.5, -0.5, 0.5, 1.0],
        [0.5, 0.5, 0.5, 1.0],
        [-0.5, 0.5, 0.5, 1.0],
    ];
    let scene = Scene::new(8, 8, positions, vec![[0, 1, 2], [0, 2, 3]]);
    let want = Reference::default()
        .rasterize(&scene.draw())
        .expect("the quad draws");
    let mut got = Wrapped::new(Fault::SwappedIds)
        .rasterize(&scene.draw())
        .expect("the quad draws");
    got.sort_by_key(|f| (f.y, f.x));
    let message = compare_sets(&scene, &got, &want, "the reference")
        .expect_err("swapped ids differ")
        .to_string();
    let first = got[0];
    let owner = |p: u32| 1 - p;
    assert_eq!(
        message,
        format!(
            "the reference: same samples covered, but by different primitives: ({}, {}) by [{}], expected [{}]",
            first.x,
            first.y,
            first.primitive,
            owner(first.primitive)
        )
    );
}
