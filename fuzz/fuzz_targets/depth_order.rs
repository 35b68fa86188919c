//! Overlapping grid triangles with their own depths: the depth buffer is order independent.
#![no_main]

use libfuzzer_sys::fuzz_target;
use refrast::Reference;
use refrast_conformance::rules::depth::check_order_independent;
use refrast_fuzz::GridTriangles;

fuzz_target!(|input: (GridTriangles, [u8; 18])| {
    let Some(mut scene) = input.0.scene() else { return };
    // Depth per vertex from the bytes, so triangles intersect.
    for (p, z) in scene.positions.iter_mut().zip(input.1.iter().cycle()) {
        p[2] = f32::from(*z) / 255.0;
    }
    if let Err(v) = check_order_independent(&mut Reference::default(), &scene) {
        panic!("{v}\n{scene:?}");
    }
});
