//! Runs one rule's property with proptest: seeded, shrunk, panics caught.

use std::cell::{Cell, RefCell};
use std::fmt::Debug;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Arc, Once};
use std::time::{Duration, Instant};

use proptest::strategy::Strategy;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use refrast::{Profile, Rasterizer};

use crate::picture;
use crate::scene::{Case, CaseData, Scene};
use crate::status::Status;
use crate::violation::{Picture, Violation};

/// The seed used when none is given, so that every run tries the same cases.
pub const DEFAULT_SEED: u64 = 0x5eed_2026_0001;

/// Told each input before the rasterizer sees it, so that a process watching from outside can
/// name the case a rasterizer hung or crashed on.
pub type Announce = fn(&dyn Debug);

/// Shrinking steps after the first failure: each one runs a smaller case, so a slow rasterizer
/// behind a pipe would otherwise shrink for minutes; past it the counterexample is said to be
/// possibly not minimal.
const SHRINK_STEPS: u32 = 2048;

/// Why shrinking stopped when the time budget ran out.
const BUDGET_CUT: &str = "the time budget ran out while shrinking (a larger --budget shrinks further)";

/// How many cases to try and from which seed.
#[derive(Clone, Debug)]
pub struct RunConfig {
    /// Random cases to generate (shrinking comes on top).
    pub cases: u32,
    /// The seed of the case generator.
    pub seed: u64,
    /// Called with every input, shrinking included, before it is checked.
    pub announce: Option<Announce>,
    /// Wall time after which no new case starts and shrinking stops, for slow implementations
    /// (a rasterizer in another language behind a pipe); `None` runs every case.
    pub budget: Option<Duration>,
    /// Turn the triangles a restricted cull mode would discard to face front before drawing
    /// ([`Scene::orient_to_face_front`]); off for the rules about facing and culling themselves.
    pub orient: bool,
    /// Check this one case instead of generating any (`refrast replay`): the data of a case a
    /// failure reported, fitted to the rasterizer as generated cases are.
    pub replay: Option<Arc<CaseData>>,
}

/// How a property run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Every case tried held.
    Pass {
        /// Cases tried: all of them, unless the budget ran out first.
        cases: u32,
        /// Whether the budget ran out before every case was tried.
        budget_spent: bool,
    },
    /// A case failed: the shrunk input as Rust and as data, and why it failed.
    Fail {
        /// Cases tried, the failing one included.
        cases: u32,
        /// The minimal failing input, printed as Rust.
        counterexample: String,
        /// The minimal failing input as data, to replay in any language (none when no case ran).
        case: Option<Box<CaseData>>,
        /// Why shrinking stopped before the input was as small as it could be (the time
        /// budget, or 2048 smaller cases); `None` when it is minimal.
        shrinking_cut: Option<String>,
        /// Why it fails.
        violation: Violation,
        /// The scene the minimal input draws (none when no case ran).
        scene: Option<Box<Scene>>,
        /// The check on the minimal input, to run again on another rasterizer (none when no
        /// case ran): a hint is printed only if the case passes under what it suggests.
        replay: Option<Replay>,
    },
    /// The case to replay ([`RunConfig::replay`]) is not an input of this property: why.
    Unreadable(String),
}

/// A failing case's check, bound to its input: run on a rasterizer, it says whether that
/// rasterizer passes the case.
#[derive(Clone)]
pub struct Replay(Arc<ReplayFn>);

/// What a [`Replay`] runs.
type ReplayFn = dyn Fn(&mut dyn Rasterizer) -> Result<(), Violation> + Send + Sync;

impl Replay {
    /// `check` on `input`, fitted to the profile of the rasterizer it runs on (as the rule's
    /// cases are, `orient` saying whether triangles are turned to face front).
    fn of<T: Case + Clone + Send + Sync + 'static>(check: Check<T>, input: T, orient: bool) -> Self {
        Self(Arc::new(move |r| {
            let mut input = input.clone();
            let profile = guarded(|| r.profile()).map_err(|what| Violation::panicked(&what))?;
            fit(input.scene_mut(), &profile, orient);
            run_check(r, check, &input)
        }))
    }

    /// Runs the case on `r`, fitted to its profile (a panic is a violation).
    pub fn run(&self, r: &mut dyn Rasterizer) -> Result<(), Violation> {
        (self.0)(r)
    }
}

impl std::fmt::Debug for Replay {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Replay(..)")
    }
}

impl PartialEq for Replay {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
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
    T: Debug + Clone + Case + Send + Sync + 'static,
    S: Strategy<Value = T>,
{
    property_for(rasterizer, cfg, |_| strategy, check)
}

/// [`property`] with the strategy built from the rasterizer's profile, for inputs that depend on
/// a claim: snap ties only for a declared tie rule, reach only as far as the declared guard band,
/// the sample counts it supports.
pub fn property_for<T, S>(
    rasterizer: &mut dyn Rasterizer,
    cfg: &RunConfig,
    strategy_for: impl FnOnce(&Profile) -> S,
    check: Check<T>,
) -> Verdict
where
    T: Debug + Clone + Case + Send + Sync + 'static,
    S: Strategy<Value = T>,
{
    // Every case asks only for draw states the rasterizer declares it supports, needs no 3D
    // clipping of one that does none, and under a cull mode it cannot switch off, draws its
    // triangles facing front.
    let profile = match guarded(|| rasterizer.profile()) {
        Ok(declared) => declared,
        Err(what) => {
            let violation = Violation::new(format!("profile() panicked: {what}"));
            return failed_without_case(0, violation);
        }
    };
    if let Some(data) = &cfg.replay {
        return replayed(rasterizer, cfg, &profile, data, check);
    }
    let deadline = cfg.budget.map(|b| Instant::now() + b);
    let spent = || deadline.is_some_and(|d| Instant::now() >= d);
    let orient = cfg.orient;
    let strategy = strategy_for(&profile).prop_map(move |mut input| {
        fit(input.scene_mut(), &profile, orient);
        input
    });
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes(cfg.seed));
    let mut runner = TestRunner::new_with_rng(proptest_config(cfg.cases), rng);
    let cell = RefCell::new(rasterizer);
    let announce = cfg.announce;
    // Cases tried before the first failure; shrinking comes after and is not counted.
    let tried = Cell::new(0u32);
    let failed = Cell::new(false);
    let shrink_steps = Cell::new(0u32);
    // Why shrinking stopped early, if it did.
    let cut: RefCell<Option<String>> = RefCell::new(None);
    let result = runner.run(&strategy, |input| {
        if failed.get() {
            // While shrinking: past the limits, keep what failed last.
            if let Some(why) = shrink_limit(spent(), shrink_steps.get()) {
                cut.borrow_mut().get_or_insert(why);
                return Ok(());
            }
            shrink_steps.set(shrink_steps.get() + 1);
        } else if spent() {
            // Before a failure: stop generating cases.
            return Err(TestCaseError::reject("the time budget is spent"));
        } else {
            tried.set(tried.get() + 1);
        }
        let mut r = cell.borrow_mut();
        let result =
            run_announced(&mut **r, check, &input, announce).map_err(|v| TestCaseError::fail(v.message));
        failed.set(failed.get() || result.is_err());
        result
    });
    match result {
        Ok(()) => Verdict::Pass {
            cases: tried.get(),
            budget_spent: false,
        },
        Err(TestError::Abort(_)) if !failed.get() && spent() => Verdict::Pass {
            cases: tried.get(),
            budget_spent: true,
        },
        Err(TestError::Fail(reason, input)) => {
            let mut r = cell.borrow_mut();
            let input = reduce(&mut **r, check, input, announce, &spent, &cut);
            // The shrunk case is replayed once more: one that passes now was a flake.
            let violation = run_announced(&mut **r, check, &input, announce)
                .err()
                .unwrap_or_else(|| Violation {
                    status: Status::Flake,
                    ..Violation::new(format!(
                        "{reason} (the shrunk case passed when replayed: the same draw gave \
                         another answer; is the rasterizer deterministic?)"
                    ))
                });
            failure(&mut **r, check, input, violation, tried.get(), cut.take(), orient)
        }
        Err(TestError::Abort(reason)) => failed_without_case(
            tried.get(),
            Violation::new(format!("the case generator gave up: {reason}")),
        ),
    }
}

/// The verdict on the one case of a replay: `data` read as the rule's input, fitted to
/// `profile` as generated cases are, and checked.
fn replayed<T: Debug + Clone + Case + Send + Sync + 'static>(
    rasterizer: &mut dyn Rasterizer,
    cfg: &RunConfig,
    profile: &Profile,
    data: &CaseData,
    check: Check<T>,
) -> Verdict {
    match T::from_data(data) {
        Ok(mut input) => {
            fit(input.scene_mut(), profile, cfg.orient);
            match run_announced(rasterizer, check, &input, cfg.announce) {
                Ok(()) => Verdict::Pass {
                    cases: 1,
                    budget_spent: false,
                },
                Err(violation) => failure(rasterizer, check, input, violation, 1, None, cfg.orient),
            }
        }
        Err(why) => Verdict::Unreadable(why),
    }
}

/// proptest's configuration for `cases` cases: shrinking bounded here, by [`SHRINK_STEPS`] and
/// the budget, not by proptest, which would print its own notice on stderr (both its limits
/// are effectively off); no rule rejects a case, so a reject means the budget is spent: stop
/// at the first.
fn proptest_config(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        max_shrink_iters: u32::MAX - 1,
        max_shrink_time: 0,
        max_global_rejects: 0,
        ..Config::default()
    }
}

/// Why shrinking must stop now, if it must: the budget is `spent`, or `steps` reached
/// [`SHRINK_STEPS`].
fn shrink_limit(spent: bool, steps: u32) -> Option<String> {
    if spent {
        Some(BUDGET_CUT.to_owned())
    } else if steps >= SHRINK_STEPS {
        Some(format!("shrinking stopped after {SHRINK_STEPS} smaller cases"))
    } else {
        None
    }
}

/// The verdict on `input`, which failed with `violation` after `cases` cases: the input as
/// Rust and as data, a picture of the coverage when the check drew none, and the check bound
/// to the input for hints.
fn failure<T: Debug + Clone + Case + Send + Sync + 'static>(
    r: &mut dyn Rasterizer,
    check: Check<T>,
    input: T,
    mut violation: Violation,
    cases: u32,
    shrinking_cut: Option<String>,
    orient: bool,
) -> Verdict {
    if violation.picture.is_none() {
        violation.picture = Some(Box::new(coverage_picture(r, input.scene(), &violation.samples)));
    }
    Verdict::Fail {
        cases,
        counterexample: format!("{input:?}"),
        case: Some(Box::new(input.data())),
        shrinking_cut,
        violation,
        scene: Some(Box::new(input.scene().clone())),
        replay: Some(Replay::of(check, input, orient)),
    }
}

/// A failure with no case to show: the profile panicked, or the generator gave up.
fn failed_without_case(cases: u32, violation: Violation) -> Verdict {
    Verdict::Fail {
        cases,
        counterexample: String::new(),
        case: None,
        shrinking_cut: None,
        violation,
        scene: None,
        replay: None,
    }
}

/// `scene` as a case asks it of a rasterizer with `profile`: only draw states it supports,
/// nothing that needs 3D clipping of one that does none, and (with `orient`) its triangles
/// facing front under a cull mode it cannot switch off.
fn fit(scene: &mut Scene, profile: &Profile, orient: bool) {
    scene.state = profile.fit(scene.state);
    scene.keep_unclipped(profile);
    if orient {
        scene.orient_to_face_front(profile);
    }
}

/// Takes the first smaller input that still fails, until none does or the budget is spent
/// (then saying so in `cut`).
fn reduce<T: Case + Debug>(
    r: &mut dyn Rasterizer,
    check: Check<T>,
    mut input: T,
    announce: Option<Announce>,
    spent: &dyn Fn() -> bool,
    cut: &RefCell<Option<String>>,
) -> T {
    'outer: loop {
        for candidate in input.reductions() {
            if spent() {
                cut.borrow_mut().get_or_insert_with(|| BUDGET_CUT.to_owned());
                return input;
            }
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
    let fragments = guarded(|| r.rasterize(&scene.draw()))
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
    guarded(|| check(r, input)).unwrap_or_else(|what| Err(Violation::panicked(&what)))
}

thread_local! {
    /// How many [`guarded`] calls this thread is inside: their panics are not printed.
    static GUARD_DEPTH: Cell<u32> = const { Cell::new(0) };
    /// Where the last guarded panic on this thread happened, kept by the quiet hook.
    static PANIC_AT: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Runs `f`, turning a panic into its message and place (`Err("boom at src/x.rs:3:5")`).
///
/// A panic the suite catches is a finding it reports, so it is not also printed by the default
/// panic hook: the first call installs a hook that stays quiet inside `guarded` on this thread
/// and passes every other panic to the hook that was there before.
pub fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    static QUIET_HOOK: Once = Once::new();
    QUIET_HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if GUARD_DEPTH.with(Cell::get) > 0 {
                let at = info
                    .location()
                    .map(|l| format!("{}:{}:{}", l.file(), l.line(), l.column()));
                PANIC_AT.with(|p| *p.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
    });
    GUARD_DEPTH.with(|d| d.set(d.get() + 1));
    let result = catch_unwind(AssertUnwindSafe(f));
    GUARD_DEPTH.with(|d| d.set(d.get() - 1));
    result.map_err(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a non-string payload".into());
        match PANIC_AT.with(|p| p.borrow_mut().take()) {
            Some(at) => format!("{what} at {at}"),
            None => what,
        }
    })
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
