//! `fast` (refrast-fast, on two threads) under the `differential` target's check: grid triangles
//! anywhere in the guard band against the brute-force oracle, bit for bit. The input decodes as
//! `differential`'s does, so `fuzz/nightly.sh` starts it from `differential`'s seeds.
#![no_main]

use std::sync::{Mutex, OnceLock};

use libfuzzer_sys::fuzz_target;
use refrast_conformance::fuzz::{self, GridTriangles};
use refrast_fast::Fast;

/// One rasterizer for the whole run: its thread pool and buffers are made once.
fn fast() -> &'static Mutex<Fast> {
    static FAST: OnceLock<Mutex<Fast>> = OnceLock::new();
    FAST.get_or_init(|| Mutex::new(Fast::with_threads(2)))
}

fuzz_target!(|input: GridTriangles| {
    let mut fast = fast().lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Err(failure) = fuzz::differential(&mut *fast, &input) {
        panic!("fast: {failure}");
    }
});
