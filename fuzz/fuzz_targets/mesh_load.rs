//! Any bytes as a PLY and as an OBJ file: no panic, and an accepted mesh is one refrast can draw.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    if let Err(failure) = refrast_render::load::check_any_bytes(bytes) {
        panic!("{failure}");
    }
});
