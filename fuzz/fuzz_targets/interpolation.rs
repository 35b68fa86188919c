//! Perspective triangles inside the view: barycentrics and depth against the ray cast.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::fuzz::{self, Perspective};

fuzz_target!(|input: Perspective| {
    if let Err(failure) = fuzz::interpolation(&mut Reference::default(), &input) {
        panic!("{failure}");
    }
});
