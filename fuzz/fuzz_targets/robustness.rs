//! Any f32 bit patterns and indices: no panic, well-formed fragments, resolve works.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::fuzz::{self, RawDraw};

fuzz_target!(|input: RawDraw| {
    if let Err(failure) = fuzz::robustness(&mut Reference::default(), &input) {
        panic!("{failure}");
    }
});
