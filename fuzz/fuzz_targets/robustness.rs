//! Any bit patterns through the reference: no panic, well-formed fragments, resolve works.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::{Rasterizer, Reference};
use refrast_conformance::rules::robust::check_well_formed;
use refrast_fuzz::RawDraw;

fuzz_target!(|input: RawDraw| {
    let Some(scene) = input.scene() else { return };
    let mut r = Reference::default();
    if let Err(v) = check_well_formed(&mut r, &scene) {
        panic!("{v}\n{scene:?}");
    }
    r.resolve(&scene.draw())
        .expect("indices are in range by construction");
});
