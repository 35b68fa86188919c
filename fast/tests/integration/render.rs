//! `refrast render --impl fast` draws what `--impl reference` draws, under `fast`'s contract:
//! every built-in scene in every mode through `refrast_render::render`, each draw covering the
//! reference's samples exactly with interpolation within the declared precision, and the
//! pictures' colours within a level and depths within the precision except where depths tie.

use proptest::prelude::*;
use refrast::pipeline::Framebuffer;
use refrast::{Draw, Fragment, Rasterizer, Reference, ReferenceConfig};
use refrast_fast::Fast;
use refrast_fast::contract::{Recording, check_fragments, check_pictures, ties, tolerance};
use refrast_render::scene::{self, Setup};
use refrast_render::{Job, Mode, Overrides, Sampling};

use crate::support::{layers, mesh_draw, soup};

/// `setup` at its size in `mode` with its default shading, as `refrast render` draws it.
fn picture(setup: &Setup, mode: Mode, rasterizer: &mut dyn Rasterizer) -> Framebuffer {
    let (w, h) = setup.size;
    let camera = setup.camera(w as f32 / h as f32, &Overrides::default()).unwrap();
    let job = Job {
        mesh: &setup.mesh,
        view_projection: camera.view_projection,
        eye: camera.eye,
        state: setup.state,
        mode,
        shading: setup.shading,
        light: setup.light(&camera),
        texture: None,
        sampling: Sampling::Nearest,
        clear: setup.clear,
    };
    let mut target = Framebuffer::new(w, h).unwrap();
    refrast_render::render(rasterizer, &job, &mut target).unwrap();
    target
}

#[test]
fn every_scene_in_every_mode_is_the_references_picture_within_the_precision() {
    let scenes = scene::scenes();
    assert!(scenes.len() >= 10, "{} scenes", scenes.len());
    let mut fast = [Fast::with_threads(1), Fast::with_threads(2)];
    let tolerance = tolerance();
    for info in scenes {
        let setup = scene::scene(info.name).unwrap();
        // As the CLI builds it: the reference walks pixels as the scene's lab step does.
        let mut inner = Reference::new(ReferenceConfig {
            traversal: setup.traversal,
            ..ReferenceConfig::default()
        });
        let mut reference = Recording {
            inner: &mut inner,
            fragments: Vec::new(),
        };
        for mode in Mode::ALL {
            reference.fragments.clear();
            let want = picture(&setup, mode, &mut reference);
            let (w, h) = setup.size;
            let tied = ties(&reference.fragments, w, h, tolerance);
            for fast in &mut fast {
                let what = format!("{} in {} mode, {}", info.name, mode.name(), fast.about());
                let mut recording = Recording {
                    inner: fast,
                    fragments: Vec::new(),
                };
                let got = picture(&setup, mode, &mut recording);
                check_fragments(&reference.fragments, &recording.fragments, tolerance)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                check_pictures(
                    (want.color(), want.depth()),
                    (got.color(), got.depth()),
                    &tied,
                    tolerance,
                )
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            }
        }
    }
}

/// A depth buffer of `n` pixels, each from a few values (NaN and both zeros among them) picked
/// by `seed`: what a render may find before it draws.
fn stored_depths(n: usize, seed: u64) -> Vec<f32> {
    const VALUES: [f32; 8] = [1.0, 0.0, -0.0, 0.3, 0.5, 0.9, f32::NAN, 0.70001];
    let mut state = seed | 1;
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            VALUES[(state >> 61) as usize]
        })
        .collect()
}

/// A shader that discards some fragments and colours the rest by primitive and position.
fn shade(f: &Fragment) -> Option<u32> {
    (f.primitive % 5 != 3).then_some(f.primitive.wrapping_mul(2_654_435_761) ^ f.x ^ (f.y << 16))
}

/// Asserts that `render` into buffers holding `stored` gives, bit for bit, `fast`'s own
/// fragments depth-tested, shaded and written one by one in their order, which for each pixel
/// is primitive order: so every block the render skipped as hidden was one whose samples all
/// fail the test.
fn renders_its_own_fragments(draw: &Draw, seed: u64, threads: usize) -> Result<(), TestCaseError> {
    let mut fast = Fast::with_threads(threads);
    let (w, n) = (draw.viewport.width() as usize, draw.viewport.pixel_count());
    let stored = stored_depths(n, seed);
    let (mut want_depth, mut want_color) = (stored.clone(), vec![0u32; n]);
    let state = draw.state.depth;
    for f in fast.rasterize(draw).expect("fast draws") {
        let i = f.y as usize * w + f.x as usize;
        if state.compare.passes(f.depth, want_depth[i])
            && let Some(c) = shade(&f)
        {
            if state.write {
                want_depth[i] = f.depth;
            }
            want_color[i] = c;
        }
    }
    let (mut depth, mut color) = (stored, vec![0u32; n]);
    fast.render(draw, &mut depth, &mut color, shade)
        .expect("fast renders");
    let bits = |d: &[f32]| d.iter().map(|d| d.to_bits()).collect::<Vec<_>>();
    prop_assert!(
        bits(&depth) == bits(&want_depth),
        "depth differs from its fragments'"
    );
    prop_assert!(color == want_color, "colour differs from its fragments'");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// `render` is its own fragments drawn in order, on layers where most blocks are hidden
    /// (ties, NaN and signed zeros in the buffer), soups and meshes.
    #[test]
    fn render_is_its_own_fragments_in_order(
        draw in prop_oneof![2 => layers(), 1 => soup(), 1 => mesh_draw()],
        seed in any::<u64>(),
        threads in 1usize..3,
    ) {
        renders_its_own_fragments(&draw, seed, threads)?;
    }
}
