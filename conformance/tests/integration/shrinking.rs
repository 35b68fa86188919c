//! Shrinking stops at the time budget and says so; run to its end, the counterexample is as
//! small as it gets.

use std::time::Duration;

use refrast::{Rasterizer, Reference};
use refrast_conformance::{DEFAULT_SEED, RunConfig, Scene, Verdict, Violation, property, strategy};

/// Fails every case, slowly, as a rasterizer behind a pipe might.
fn slow_failure(_: &mut dyn Rasterizer, _: &Scene) -> Result<(), Violation> {
    std::thread::sleep(Duration::from_millis(30));
    Err(Violation::new("always"))
}

/// Fails every case at once.
fn failure(_: &mut dyn Rasterizer, _: &Scene) -> Result<(), Violation> {
    Err(Violation::new("always"))
}

fn config(budget: Option<Duration>) -> RunConfig {
    RunConfig {
        cases: 10,
        seed: DEFAULT_SEED,
        announce: None,
        budget,
        orient: true,
        replay: None,
    }
}

#[test]
fn a_shrink_cut_short_by_the_budget_says_so() {
    let budget = Some(Duration::from_millis(10));
    let verdict = property(
        &mut Reference::default(),
        &config(budget),
        strategy::grid_scene(),
        slow_failure,
    );
    match verdict {
        Verdict::Fail {
            shrinking_cut: Some(why),
            case: Some(_),
            ..
        } => assert!(why.contains("budget"), "{why}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_shrink_run_to_its_end_is_minimal() {
    match property(
        &mut Reference::default(),
        &config(None),
        strategy::grid_scene(),
        failure,
    ) {
        Verdict::Fail {
            shrinking_cut: None,
            case: Some(case),
            scene: Some(scene),
            ..
        } => assert_eq!(scene.triangles.len(), 1, "{case:?}"),
        other => panic!("{other:?}"),
    }
}
