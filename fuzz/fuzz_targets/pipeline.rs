//! Any bit patterns, matrix included, through the reference's renderer: mesh, lines and points.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast_conformance::fuzz::{self, RawPipeline};

fuzz_target!(|input: RawPipeline| {
    if let Err(failure) = fuzz::pipeline(&input) {
        panic!("{failure}");
    }
});
