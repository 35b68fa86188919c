//! Overlapping, intersecting grid triangles: the depth buffer is the same in any draw order.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::fuzz::{self, Overlapping};

fuzz_target!(|input: Overlapping| {
    if let Err(failure) = fuzz::depth_order(&mut Reference::default(), &input) {
        panic!("{failure}");
    }
});
