//! Triangles across every clip plane and w = 0 against the ray cast, outside the tolerance band.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::rules::fill::check_exactly_once;
use refrast_fuzz::Crossing;

fuzz_target!(|input: Crossing| {
    let scene = input.scene();
    if let Err(v) = check_exactly_once(&mut Reference::default(), &scene) {
        panic!("{v}\n{scene:?}");
    }
});
