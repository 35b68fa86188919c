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

/// Found by `clip.mesh.watertight` against `reference-4bit`: a triangle cut by the near plane
/// close to its shared edge left, once snapped to 1/16 px, a fan of one sliver turned the other
/// way. The one-triangle traversal drew it as if it agreed, covering a sample its neighbour
/// also covers. Clipped polygons now take their winding from the unclipped triangle, and a lone
/// disagreeing sliver draws nothing.
#[test]
fn a_clipped_sliver_turned_over_by_snapping_draws_nothing() {
    let draw = Draw::new(
        Viewport::new(64, 16).unwrap(),
        vec![
            [-0.29996338, 0.3, 0.0, 0.3],
            [-1.0780681, -2.5881248, 0.19778672, 2.5982742],
            [-1.0149509, -2.5982742, -2.434117, 2.5982742],
            [0.10458627, 0.81657743, 0.12542191, 1.647636],
        ],
        vec![[1, 3, 2], [0, 3, 1]],
    );
    let subpixel_bits = refrast::SubpixelBits::new(4).unwrap();
    let mut r = Reference::new(ReferenceConfig {
        subpixel_bits,
        ..ReferenceConfig::default()
    });
    let fragments = r.rasterize(&draw).unwrap();
    let mut seen = std::collections::HashSet::new();
    for f in &fragments {
        assert!(seen.insert((f.x, f.y)), "sample {:?} covered twice", (f.x, f.y));
    }
}
