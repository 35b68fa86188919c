//! Arbitrary point sets, snapped and triangulated by spade: every sample covered exactly once.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::rules::fill::check_exactly_once;
use refrast_fuzz::Points;

fuzz_target!(|input: Points| {
    let scene = input.scene();
    if let Err(v) = check_exactly_once(&mut Reference::default(), &scene) {
        panic!("{v}\n{scene:?}");
    }
});
