//! The hand-checked findings read off a driver's depth buffer (`resolve`): depth bias.

use refrast::{CompareOp, DepthBias, Draw, Resolved};

use crate::findings::draw;

/// A driver's depth and id buffers for a draw.
pub(crate) type Resolve<'a> = dyn FnMut(&Draw) -> Resolved + 'a;

/// A finding read off the depth buffer: what it is, and its check.
pub(crate) type ResolvedFinding = (&'static str, fn(&mut Resolve<'_>));

/// softpipe: depth bias added to each vertex and clamped to [0, 1] there, before interpolation
/// (Mesa's `draw_pipe_offset.c`: "we're applying the offset and clamping per-vertex"), where
/// OpenGL ES 3.2 §13.7.2 adds `o` to each fragment's depth and then clamps ("Fragment depth
/// values are clamped even when the depth buffer uses a floating-point representation").
pub(crate) fn softpipe_bias_per_vertex(resolve: &mut Resolve<'_>) {
    let got = resolve(&biased_past_zero());
    let i = got.index(8, 7, 0);
    assert_eq!(got.primitive[i], Some(0), "softpipe: (8, 7) covered");
    assert!(
        (got.depth[i] - 0.011_589).abs() < 1e-5,
        "softpipe: (8, 7) biased to {} (the bent plane gives 0.011589; OpenGL ES requires 0)",
        got.depth[i]
    );
}

/// llvmpipe, a false verdict of refrast's: OpenGL ES copies no depth texture, so the adapter
/// reads the depth test's result back as the passing fragment's FragCoord.z, which carries the
/// bias unclamped (−0.014503 here); the buffer holds it clamped to [0, 1] (§13.7.2), and so
/// must the copy, or `depth.bias.offset` fails a driver that is right.
pub(crate) fn llvmpipe_biased_copy_clamped(resolve: &mut Resolve<'_>) {
    let got = resolve(&biased_past_zero());
    let i = got.index(8, 7, 0);
    assert_eq!(
        (got.primitive[i], got.depth[i]),
        (Some(0), 0.0),
        "llvmpipe: (8, 7) biased below 0, read back clamped"
    );
}

/// A triangle whose bias carries part of it below depth 0, written with every fragment.
fn biased_past_zero() -> Draw {
    // A triangle at (8, 8), (8, 7.205), (12.976, 8) px, depth 0, 0 and 0.1443: ∂z/∂x = 0.029006,
    // ∂z/∂y = 0, so slope factor −1 makes o = −0.029006. At (8, 7), sample (8.5, 7.5), depth
    // 0.014503; biased −0.014503, clamped to 0. softpipe clamps the vertices instead (0, 0,
    // 0.1153) and interpolates the bent plane: 0.011589.
    let mut biased = draw(
        16,
        16,
        vec![
            [0.0, 0.0, 0.0, 0.25],
            [0.0, 0.024_832_683, 0.0, 0.25],
            [0.155_489_34, 0.0, 0.036_083_46, 0.25],
        ],
        vec![[0, 1, 2]],
    );
    biased.state.depth.compare = CompareOp::Always;
    biased.state.depth_bias = Some(DepthBias {
        constant: 0.0,
        slope: -1.0,
        clamp: 0.0,
    });
    biased
}
