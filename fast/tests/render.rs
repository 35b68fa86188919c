//! `refrast render --impl fast` draws what `--impl reference` draws: every built-in scene in
//! every mode, through `refrast_render::render`, with colour and depth identical byte for byte.

use refrast::pipeline::Framebuffer;
use refrast::{Rasterizer, Reference, ReferenceConfig};
use refrast_fast::Fast;
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
fn every_scene_in_every_mode_is_the_references_picture() {
    let scenes = scene::scenes();
    assert!(scenes.len() >= 10, "{} scenes", scenes.len());
    let mut fast = [Fast::with_threads(1), Fast::with_threads(2)];
    for info in scenes {
        let setup = scene::scene(info.name).unwrap();
        // As the CLI builds it: the reference walks pixels as the scene's lab step does.
        let mut reference = Reference::new(ReferenceConfig {
            traversal: setup.traversal,
            ..ReferenceConfig::default()
        });
        for mode in Mode::ALL {
            let want = picture(&setup, mode, &mut reference);
            for fast in &mut fast {
                let got = picture(&setup, mode, fast);
                let what = format!("{} in {} mode, {}", info.name, mode.name(), fast.about());
                assert!(got.color() == want.color(), "colour differs: {what}");
                let bits = |f: &Framebuffer| f.depth().iter().map(|d| d.to_bits()).collect::<Vec<_>>();
                assert!(bits(&got) == bits(&want), "depth differs: {what}");
            }
        }
    }
}
