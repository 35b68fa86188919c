//! The reference against the brute-force oracle, bit for bit, on grid triangles in the guard band.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::rules::fill::check_guard_band;
use refrast_fuzz::GridTriangles;

fuzz_target!(|input: GridTriangles| {
    let Some(scene) = input.scene() else { return };
    for t in 0..scene.triangles.len() {
        let mut one = scene.clone();
        one.triangles = vec![scene.triangles[t]];
        if let Err(v) = check_guard_band(&mut Reference::default(), &one) {
            panic!("{v}\n{one:?}");
        }
    }
});
