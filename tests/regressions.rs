//! Failures found by the conformance suite, kept as named tests.

use refrast::{ClipMode, Draw, Rasterizer, Reference, ReferenceConfig, Viewport};

/// Found by `meta.degenerate.empty` against `reference-full-clip`: a zero-area triangle crossing
/// the viewport's left edge was clipped, its new vertices snapped off its line, and the sliver
/// covered a sample. Degeneracy is now decided on the snapped input, before clipping.
#[test]
fn full_clip_of_a_zero_area_triangle_draws_nothing() {
    let draw = Draw::new(
        Viewport::new(16, 16).unwrap(),
        vec![
            [-0.9375, 0.8125, 0.5, 1.0],
            [-0.8125, 1.1030273, 0.5, 1.0],
            [-1.0625, 0.52197266, 0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    for clip in [ClipMode::Full, ClipMode::GuardBand] {
        let mut r = Reference::new(ReferenceConfig {
            clip,
            ..ReferenceConfig::default()
        });
        assert_eq!(r.rasterize(&draw).unwrap(), vec![], "{clip:?}");
    }
}
