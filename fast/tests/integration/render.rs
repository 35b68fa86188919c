//! `refrast render --impl fast` draws what `--impl reference` draws, under `fast`'s contract:
//! every built-in scene in every mode through `refrast_render::render`, each draw covering the
//! reference's samples exactly with interpolation within the declared precision, and the
//! pictures' colours within a level and depths within the precision except where depths tie.

use refrast::pipeline::Framebuffer;
use refrast::{Rasterizer, Reference, ReferenceConfig};
use refrast_fast::Fast;
use refrast_fast::contract::{Recording, check_fragments, check_pictures, ties, tolerance};
use refrast_render::scene::{self, Setup};
use refrast_render::{Job, Mode, Overrides, Sampling};

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
