//! Arbitrary point sets, snapped and triangulated by spade: every sample covered exactly once.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::fuzz::{self, Points};

fuzz_target!(|input: Points| {
    if let Err(failure) = fuzz::watertight(&mut Reference::default(), &input) {
        panic!("{failure}");
    }
});
