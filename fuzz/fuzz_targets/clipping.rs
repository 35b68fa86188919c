//! Triangles and meshes across every clip plane and w = 0 against the ray cast, outside the band.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::fuzz::{self, Clipping};

fuzz_target!(|input: Clipping| {
    if let Err(failure) = fuzz::clipping(&mut Reference::default(), &input) {
        panic!("{failure}");
    }
});
