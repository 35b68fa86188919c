//! softpipe's own hand-checked findings (docs/certified.md): float edges on no grid.

use refrast::Draw;
use refrast_wgpu::Driver;

use crate::findings::{Run, at, draw, expected};

/// Two triangles of softpipe's findings on 64×64, sharing the edge (32.5, 32.5)–(18.5, 50.5).
pub(crate) fn softpipe_fan() -> Draw {
    draw(
        64,
        64,
        vec![
            [0.015625, -0.015625, 0.5, 1.0],
            [0.0, -0.1875, 0.5, 1.0],
            [-0.421875, -0.578125, 0.5, 1.0],
            [-0.046875, -0.015625, 0.5, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// softpipe: a shared edge's midpoint covered by both triangles.
pub(crate) fn softpipe_shared_edge_twice(_: Driver, run: &mut Run<'_>) {
    // Two triangles sharing the edge (32.5, 32.5)–(18.5, 50.5); its midpoint is the sample of
    // pixel (25, 41), covered by both.
    let fan = softpipe_fan();
    assert_eq!(
        at(&run(&fan), 25, 41).len(),
        2,
        "softpipe: the shared-edge sample twice"
    );
}

/// softpipe: the sample on a vertex where two right edges meet.
pub(crate) fn softpipe_vertex_sample(_: Driver, run: &mut Run<'_>) {
    let fan = softpipe_fan();
    // The sample (12.5, 0.5) is vertex 1, where two right edges meet: softpipe covers it, as
    // top-right would; its float edges follow top-right on 259 of the probe's 262 tie samples,
    // not all, so it declares no tie rule (tests/measured.rs).
    let corner = draw(
        16,
        16,
        vec![
            [-1.0, 1.0, 0.5, 1.0],
            [0.5625, 0.9375, 0.5, 1.0],
            [-1.0, 0.937_011_7, 0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    assert_eq!(at(&run(&corner), 12, 0).len(), 1, "softpipe: the vertex sample");
    assert!(at(&expected(&corner), 12, 0).is_empty(), "top-left leaves it out");
    assert_eq!(
        at(&expected(&fan), 25, 41).len(),
        1,
        "exactly one triangle covers it"
    );
}

/// softpipe: a triangle flat on the reference's grid draws a pixel weighted nothing.
pub(crate) fn softpipe_flat_triangle(_: Driver, run: &mut Run<'_>) {
    // All three vertices project to y = 4.5000004 to 4.5000005 (exact area 1.2·10⁻⁸ px²; on an
    // 8-bit grid zero, but softpipe snaps to no grid), and (24, 4), whose sample lies 4·10⁻⁷ px
    // outside the triangle, is drawn weighted 0, 0, 0: the weights sum to 0, not 1.
    let flat = draw(
        32,
        32,
        vec![
            [0.053125, 0.071875, 0.0, 0.1],
            [1.355_272_4, 2.509_384_9, 0.0, 3.491_318_2],
            [0.050_903_32, 0.071875, 0.0, 0.1],
        ],
        vec![[0, 1, 2]],
    );
    assert!(
        expected(&flat).is_empty(),
        "zero area on the reference's grid: nothing drawn"
    );
    let frags = run(&flat);
    assert_eq!(frags.len(), 1, "softpipe: one fragment of the flat triangle");
    assert_eq!(
        (frags[0].x, frags[0].y),
        (24, 4),
        "softpipe: the flat triangle's pixel"
    );
    assert_eq!(frags[0].barycentric, [0.0; 3], "softpipe: weighted nothing");
    assert_eq!(
        frags[0].screen_barycentric,
        Some([2.0, 0.0, -2.0]),
        "softpipe: screen weights"
    );
}

/// softpipe: non-finite weights on triangles crossing w = 0, within 2³² too.
pub(crate) fn softpipe_across_w_zero(_: Driver, run: &mut Run<'_>) {
    // A triangle crossing w = 0 (w = 0, −2·10⁻⁶, 27.7): (2, 10) is weighted (∞, NaN, ∞).
    let crossing = draw(
        3,
        21,
        vec![
            [1.876_499_6e14, 0.0, 0.0, 0.0],
            [-0.0, 0.0, 0.0, -2.011_305e-6],
            [0.0, -1.257_901_8e-6, 0.0, 27.699_118],
        ],
        vec![[0, 1, 2]],
    );
    let weights = at(&run(&crossing), 2, 10);
    assert!(
        weights.len() == 1 && weights[0].barycentric.iter().all(|b| !b.is_finite()),
        "softpipe: non-finite weights at (2, 10): {weights:?}"
    );
    // The same within 2³², every clipped vertex at w ≥ 2⁻³² (so required of OpenGL): two
    // vertices behind the eye, vertex 1 a hair before the near plane; the sample on vertex 1.
    let within = draw(
        9,
        1,
        vec![
            [-1.175_494_4e-38, -3.996_676, 1.175_494_4e-38, -3.999_976_4],
            [-1.175_494_4e-38, 1.175_494_4e-38, -2.970_919e-7, 2.546_645_2],
            [-1.515_625, 22_237_420.0, 2.484_375, -0.576_177_6],
        ],
        vec![[0, 1, 2]],
    );
    let scene = refrast_conformance::Scene {
        width: 9,
        height: 1,
        positions: within.positions.clone(),
        triangles: within.triangles().to_vec(),
        state: within.state,
        distances: within.distances.clone(),
    };
    assert!(
        refrast_conformance::rules::robust::within_float_range(&scene),
        "the 9×1 draw stays within 2³²"
    );
    let weights = at(&run(&within), 4, 0);
    assert!(
        weights.len() == 1 && weights[0].barycentric.iter().all(|b| !b.is_finite()),
        "softpipe: non-finite weights at (4, 0) within range: {weights:?}"
    );
}
