//! Grid triangles anywhere in the guard band against the brute-force oracle, bit for bit.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::fuzz::{self, GridTriangles};

fuzz_target!(|input: GridTriangles| {
    if let Err(failure) = fuzz::differential(&mut Reference::default(), &input) {
        panic!("{failure}");
    }
});
