//! The same bits at every SIMD level: fragments and resolved buffers drawn at each level this
//! CPU has (and at the scalar fallback, with the default feature `force_support_fallback`), compared
//! bit for bit with the best level's, on random scenes and meshes. Levels the CPU or the build
//! lacks are skipped with a message.

use crate::support;

use proptest::prelude::*;
use refrast::{Draw, Fragment, Rasterizer, Resolved};
use refrast_fast::{Fast, FastConfig, SimdLevel};
use support::{mesh_draw, soup};

/// A fragment as bits, in the order `fast` returns them.
type Bits = (u32, u32, u32, u32, [u32; 3], Option<[u32; 3]>, bool);

fn bits(f: &Fragment) -> Bits {
    (
        f.primitive,
        f.y,
        f.x,
        f.depth.to_bits(),
        f.barycentric.map(f32::to_bits),
        f.screen_barycentric.map(|b| b.map(f32::to_bits)),
        f.front_facing,
    )
}

fn resolved_bits(r: &Resolved) -> (Vec<u32>, Vec<Option<u32>>) {
    (r.depth.iter().map(|d| d.to_bits()).collect(), r.primitive.clone())
}

/// The levels this machine can run, each as a rasterizer on `threads` threads.
fn rasterizers(threads: usize) -> Vec<Fast> {
    SimdLevel::ALL
        .into_iter()
        .filter(|level| level.level().is_some())
        .map(|simd| {
            Fast::new(FastConfig {
                threads,
                simd,
                ..FastConfig::default()
            })
        })
        .collect()
}

/// Asserts that every level draws `draw` as the best level does, bit for bit.
fn same_bits(draw: &Draw, threads: usize) -> Result<(), TestCaseError> {
    let mut best = Fast::with_threads(threads);
    let want = best.rasterize(draw).expect("draws");
    let want_resolved = resolved_bits(&best.resolve(draw).expect("resolves"));
    for mut fast in rasterizers(threads) {
        let got = fast.rasterize(draw).expect("draws");
        prop_assert!(
            got.iter().map(bits).eq(want.iter().map(bits)),
            "fragments at {} differ from {}'s",
            fast.simd().name(),
            best.simd().name()
        );
        prop_assert!(
            resolved_bits(&fast.resolve(draw).expect("resolves")) == want_resolved,
            "resolve at {} differs",
            fast.simd().name()
        );
    }
    Ok(())
}

/// Says which levels run here and which are skipped, and that more than one runs where the
/// CPU has SIMD.
#[test]
fn levels_this_machine_runs() {
    for level in SimdLevel::ALL {
        match level.level() {
            Some(_) => eprintln!("level {}: compared", level.name()),
            None if level == SimdLevel::Fallback => eprintln!(
                "level fallback: SKIPPED: this build has no scalar fallback on a SIMD baseline \
                 (built without the default feature force_support_fallback)"
            ),
            None => eprintln!("level {}: SKIPPED: this CPU does not have it", level.name()),
        }
    }
    let running = rasterizers(1);
    assert!(!running.is_empty());
    assert!(running.iter().any(|f| f.simd() == Fast::with_threads(1).simd()));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 120, ..ProptestConfig::default() })]

    /// Soups of random clip-space triangles.
    #[test]
    fn random_triangles_draw_the_same_bits_at_every_level(draw in soup(), threads in 1usize..3) {
        same_bits(&draw, threads)?;
    }

    /// Meshes with shared edges, some through the near plane, some with every vertex on a
    /// sample (edges through samples, where the fill rule decides).
    #[test]
    fn meshes_draw_the_same_bits_at_every_level(draw in mesh_draw()) {
        same_bits(&draw, 1)?;
    }
}
