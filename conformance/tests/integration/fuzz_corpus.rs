//! Replays the committed fuzz seeds and reproducers on stable, decoded as `fuzz_target!` does.
//!
//! `fuzz/seeds/<target>/` is a small minimised corpus; `fuzz/regressions/<target>/` holds every
//! input that once made a target fail, named after what it showed. Both run against the reference.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use refrast::Reference;
use refrast_conformance::fuzz::{Checked, Target};

/// The files of `fuzz/<kind>/<target>/`, sorted; none when the folder does not exist.
fn files(kind: &str, target: Target) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz")
        .join(kind)
        .join(target.name());
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|entries| {
            entries
                .filter_map(|e| Some(e.ok()?.path()))
                .filter(|p| p.is_file())
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// Runs every seed and reproducer of `target`; fails naming each file that fails or panics.
fn replay(target: Target) {
    let seeds = files("seeds", target);
    assert!(
        !seeds.is_empty(),
        "fuzz/seeds/{} is empty: run fuzz/nightly.sh and commit a minimised corpus",
        target.name()
    );
    let (mut passed, mut failures) = (0, Vec::new());
    for path in seeds.iter().chain(&files("regressions", target)) {
        let bytes = std::fs::read(path).expect("a corpus file is readable");
        let outcome = catch_unwind(AssertUnwindSafe(|| target.run(&mut Reference::default(), &bytes)));
        match outcome {
            Ok(Checked::Passed) => passed += 1,
            Ok(Checked::Skipped) => {}
            Ok(Checked::Failed(f)) => failures.push(format!("{}: {f}", path.display())),
            Err(_) => failures.push(format!("{}: panicked (message above)", path.display())),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // A corpus that decodes to nothing would make this test vacuous.
    assert!(passed > 0, "no seed of {} decodes to an input", target.name());
}

#[test]
fn robustness_seeds_and_regressions() {
    replay(Target::Robustness);
}

#[test]
fn differential_seeds_and_regressions() {
    replay(Target::Differential);
}

#[test]
fn watertight_seeds_and_regressions() {
    replay(Target::Watertight);
}

#[test]
fn clipping_seeds_and_regressions() {
    replay(Target::Clipping);
}

#[test]
fn depth_order_seeds_and_regressions() {
    replay(Target::DepthOrder);
}

#[test]
fn interpolation_seeds_and_regressions() {
    replay(Target::Interpolation);
}

#[test]
fn pipeline_seeds_and_regressions() {
    replay(Target::Pipeline);
}

/// A planted bug is caught through the same replay path: the decoder and checks are live.
#[test]
fn replay_catches_an_inclusive_rasterizer() {
    use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer};
    // Every triangle covers every sample: any mesh of two or more triangles double-covers.
    struct Everything;
    impl Rasterizer for Everything {
        fn profile(&self) -> Profile {
            Profile {
                name: "everything".into(),
                ..Reference::default().profile()
            }
        }
        fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
            let v = draw.viewport;
            Ok((0..v.height())
                .flat_map(|y| (0..v.width()).map(move |x| (x, y)))
                .flat_map(|(x, y)| {
                    (0..draw.triangles().len() as u32).map(move |primitive| Fragment {
                        x,
                        y,
                        sample: 0,
                        primitive,
                        depth: 0.5,
                        barycentric: [1.0 / 3.0; 3],
                        screen_barycentric: None,
                        front_facing: true,
                        flat: None,
                    })
                })
                .collect())
        }
    }
    let seeds = files("seeds", Target::Watertight);
    let failed = seeds
        .iter()
        .map(|p| Target::Watertight.run(&mut Everything, &std::fs::read(p).expect("readable")))
        .filter(|o| matches!(o, Checked::Failed(_)))
        .count();
    assert!(
        failed > 0,
        "no watertight seed caught a rasterizer that covers everything twice"
    );
}
