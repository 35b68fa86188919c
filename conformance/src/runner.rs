//! Runs one rule's property with proptest: seeded, shrunk, panics caught.

use std::cell::RefCell;
use std::fmt::Debug;
use std::panic::{AssertUnwindSafe, catch_unwind};

use proptest::strategy::Strategy;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use refrast::Rasterizer;

use crate::picture;
use crate::scene::{Case, Scene};
use crate::violation::{Picture, Violation};

/// The seed used when none is given, so that every run tries the same cases.
pub const DEFAULT_SEED: u64 = 0x5eed_2026_0001;

/// Told each input before the rasterizer sees it, so that a process watching from outside can
/// name the case a rasterizer hung or crashed on.
pub type Announce = fn(&dyn Debug);

/// How many cases to try and from which seed.
#[derive(Clone, Copy, Debug)]
pub struct RunConfig {
    /// Random cases to generate (shrinking comes on top).
    pub cases: u32,
    /// The seed of the case generator.
    pub seed: u64,
    /// Called with every input, shrinking included, before it is checked.
    pub announce: Option<Announce>,
}

/// How a property run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Every case held.
    Pass,
    /// A case failed: the shrunk input as Rust and why it failed.
    Fail {
        /// The minimal failing input, printed as Rust.
        counterexample: String,
        /// Why it fails.
        violation: Violation,
    },
}

/// A check: the rasterizer under test against one input.
pub type Check<T> = fn(&mut dyn Rasterizer, &T) -> Result<(), Violation>;

/// Runs `check` on `cfg.cases` inputs drawn from `strategy`, shrinking the first failure.
pub fn property<T, S>(
    rasterizer: &mut dyn Rasterizer,
    cfg: &RunConfig,
    strategy: S,
    check: Check<T>,
) -> Verdict
where
    T: Debug + Clone + Case,
    S: Strategy<Value = T>,
{
    let config = Config {
        cases: cfg.cases,
        failure_persistence: None,
        max_shrink_iters: 2048,
        ..Config::default()
    };
    // Every case asks only for draw states the rasterizer declares it supports.
    let profile = rasterizer.profile();
    let strategy = strategy.prop_map(move |mut input| {
        let scene = input.scene_mut();
        scene.state = profile.fit(scene.state);
        input
    });
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes(cfg.seed));
    let mut runner = TestRunner::new_with_rng(config, rng);
    let cell = RefCell::new(rasterizer);
    let announce = cfg.announce;
    let result = runner.run(&strategy, |input| {
        let mut r = cell.borrow_mut();
        run_announced(&mut **r, check, &input, announce).map_err(|v| TestCaseError::fail(v.message))
    });
    match result {
        Ok(()) => Verdict::Pass,
        Err(TestError::Fail(reason, input)) => {
            let mut r = cell.borrow_mut();
            let input = reduce(&mut **r, check, input, announce);
            let mut violation = run_announced(&mut **r, check, &input, announce)
                .err()
                .unwrap_or_else(|| {
                    Violation::new(format!(
                        "{reason} (the shrunk case passed on a second run: is the rasterizer deterministic?)"
                    ))
                });
            if violation.picture.is_none() {
                violation.picture = Some(Box::new(coverage_picture(
                    &mut **r,
                    input.scene(),
                    &violation.samples,
                )));
            }
            Verdict::Fail {
                counterexample: format!("{input:?}"),
                violation,
            }
        }
        Err(TestError::Abort(reason)) => Verdict::Fail {
            counterexample: String::new(),
            violation: Violation::new(format!("the case generator gave up: {reason}")),
        },
    }
}

/// Takes the first smaller input that still fails, until none does.
fn reduce<T: Case + Debug>(
    r: &mut dyn Rasterizer,
    check: Check<T>,
    mut input: T,
    announce: Option<Announce>,
) -> T {
    'outer: loop {
        for candidate in input.reductions() {
            if run_announced(r, check, &candidate, announce).is_err() {
                input = candidate;
                continue 'outer;
            }
        }
        return input;
    }
}

/// The rasterizer's coverage of `scene` with the outlines, `samples` marked as wrong (red).
fn coverage_picture(r: &mut dyn Rasterizer, scene: &Scene, samples: &[(u32, u32)]) -> Picture {
    let fragments = catch_unwind(AssertUnwindSafe(|| r.rasterize(&scene.draw())))
        .ok()
        .and_then(Result::ok)
        .unwrap_or_default();
    picture::of_fragments(scene, &fragments, samples)
}

/// [`run_check`], announcing the input first.
fn run_announced<T: Debug>(
    r: &mut dyn Rasterizer,
    check: Check<T>,
    input: &T,
    announce: Option<Announce>,
) -> Result<(), Violation> {
    if let Some(announce) = announce {
        announce(input);
    }
    run_check(r, check, input)
}

/// Runs one check, turning a panic of the rasterizer into a violation.
fn run_check<T>(r: &mut dyn Rasterizer, check: Check<T>, input: &T) -> Result<(), Violation> {
    match catch_unwind(AssertUnwindSafe(|| check(r, input))) {
        Ok(result) => result,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a non-string payload".into());
            Err(Violation::new(format!("the rasterizer panicked: {what}")))
        }
    }
}

/// Spreads a u64 seed over ChaCha's 32 seed bytes.
fn seed_bytes(seed: u64) -> [u8; 32] {
    let mut bytes = [0u8; 32];
    for (i, chunk) in bytes.chunks_mut(8).enumerate() {
        let word = seed.wrapping_add(i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        chunk.copy_from_slice(&word.to_le_bytes());
    }
    bytes
}
