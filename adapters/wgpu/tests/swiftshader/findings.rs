//! SwiftShader's failures under `refrast certify`, each reduced to a minimal draw and checked
//! against the reference on SwiftShader's own 4-bit grid and against exact arithmetic
//! (docs/certified.md, "Findings"). The numbers are SwiftShader's as Chromium 148 ships it; every
//! one was also reproduced bit for bit by an f32 trace of SwiftShader's source (`VertexRoutine`,
//! `Clipper`, `SetupRoutine`, `QuadRasterizer`, `PixelRoutine`).

use refrast::{ClipMode, CompareOp, DepthBias, Draw, Fragment, PolygonMode, Rasterizer, Resolved};
use refrast_wgpu::Gpu;

use super::{apart, at, draw, exact_barycentrics, reference};

/// The reference on SwiftShader's grid, clipping x/y at the viewport as SwiftShader does.
fn expected(d: &refrast::Draw) -> Vec<refrast::Fragment> {
    reference(4, ClipMode::Full, d)
}

/// SwiftShader's fragments for a draw.
pub type Run<'a> = dyn FnMut(&Draw) -> Vec<Fragment> + 'a;

/// A finding: what it is, and its check, which panics with what moved.
type Finding = (&'static str, fn(&mut Run<'_>));

/// Each finding, in docs/certified.md's order.
const FINDINGS: [Finding; 16] = [
    (
        "a vertex at w = 0 whose winding comes out backwards draws nothing",
        w_zero_winding_backwards,
    ),
    (
        "a vertex at w = 0: the depth plane through its projection",
        w_zero_depth_plane,
    ),
    ("a snap near a tie", snap_near_a_tie),
    ("the same on depth", depth_near_snap_ties),
    ("plane equations anchored far away", planes_anchored_far_away),
    ("beyond a snapped near cut", beyond_a_snapped_near_cut),
    ("a vertex at w = NaN", w_nan),
    ("finite coordinates to 1.4e35", huge_coordinates),
    ("a vertex at w = -FLT_MIN", w_minus_flt_min),
    (
        "a vertex behind the eye: screen weights",
        behind_the_eye_screen_weights,
    ),
    (
        "polygon modes: every fragment front-facing",
        polygon_modes_front_facing,
    ),
    ("point mode: culled triangles' points drawn", point_mode_unculled),
    (
        "line mode: flat values from each edge's first vertex",
        line_mode_flat_per_edge,
    ),
    (
        "clip distances tested once per pixel",
        crate::distances::clip_distance_per_pixel,
    ),
    (
        "a line to an end behind the eye drawn as nothing",
        crate::lines::line_behind_the_eye,
    ),
    (
        "a sample's perspective divide at the pixel centre",
        crate::lines::sample_divide_at_centre,
    ),
];

/// The pixels of `f`, sorted.
fn pixels(f: &[Fragment]) -> Vec<(u32, u32)> {
    let mut p: Vec<(u32, u32)> = f.iter().map(|f| (f.x, f.y)).collect();
    p.sort_unstable();
    p
}

/// Every finding, each checked whatever the others do; those that moved are named together.
pub fn swiftshader(gpu: &mut Gpu) {
    let mut run = |d: &Draw| gpu.rasterize(d).expect("SwiftShader draws");
    let mut moved = crate::common::moved_findings(&FINDINGS, |check| check(&mut run));
    let mut resolve = |d: &Draw| gpu.resolve(d).expect("SwiftShader resolves");
    let resolved: [ResolvedFinding; 1] = [(
        "depth bias's r from other depths than the largest",
        bias_exponent_not_the_largest,
    )];
    moved.extend(crate::common::moved_findings(&resolved, |check| {
        check(&mut resolve)
    }));
    let all = FINDINGS.len() + resolved.len();
    assert!(
        moved.is_empty(),
        "swiftshader: {} of {all} hand-checked findings moved:\n{}",
        moved.len(),
        moved.join("\n")
    );
    println!("swiftshader: every hand-checked finding holds ({all})");
}

/// Finding 1 (docs/certified.md): a vertex at w = 0 whose winding comes out backwards draws nothing.
fn w_zero_winding_backwards(run: &mut Run<'_>) {
    // 1. A vertex at w = 0 (a point at infinity, outside the view volume: y > w), the others
    // inside: the clipped polygon covers (2..=5, 0..=1). SwiftShader projects the w = 0 vertex
    // as if w were 1 (`VertexRoutine`), takes the winding from that projection
    // (`SetupRoutine`: area of the input vertices' projections), gets it backwards, and so
    // assigns the clipped polygon's edges to the wrong sides: nothing is drawn.
    let lost = draw(
        8,
        8,
        vec![[-0.5, 0.5, 0.5, 1.0], [0.5, 0.5, 0.5, 1.0], [0.0, 0.25, 0.0, 0.0]],
    );
    assert_eq!(expected(&lost).len(), 8, "the reference covers 8 samples");
    assert!(
        run(&lost).is_empty(),
        "swiftshader: the w = 0 triangle draws nothing"
    );
    println!("swiftshader: a triangle with a vertex at w = 0 draws 0 of its 8 samples");
}

/// Finding 2 (docs/certified.md): a vertex at w = 0: the depth plane through its projection.
fn w_zero_depth_plane(run: &mut Run<'_>) {
    // 2. The same kind of vertex where the winding comes out right: coverage is right, but every
    // vertex of the clipped polygon has depth 0.5, so every fragment must (a convex
    // combination). SwiftShader's depth plane runs through the input vertices' projections, the
    // w = 0 one projected as if w were 1 (to NDC (0, 1) at depth 0): 0.04 to 0.46. Its
    // perspective weights are (1, 0, 0) everywhere: the setup scales each vertex by its w, 0 at
    // infinity, so the plane equations degenerate (`a = 0` in `SetupRoutine`).
    let flat = draw(
        8,
        8,
        vec![
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 1.0, 0.0, 0.0],
        ],
    );
    let (got, want) = (run(&flat), expected(&flat));
    assert_eq!(
        pixels(&got),
        pixels(&want),
        "swiftshader: the w = 0 strip's coverage"
    );
    assert!(want.iter().all(|f| f.depth == 0.5));
    let corner = at(&got, 2, 0)[0];
    assert!(
        (corner.depth - 0.041_666_657).abs() < 1e-6,
        "depth at (2, 0): {}",
        corner.depth
    );
    assert!(got.iter().all(|f| f.barycentric == [1.0, 0.0, 0.0]));
    assert!(
        apart(
            at(&want, 2, 2)[0].barycentric,
            [7.0 / 15.0, 1.0 / 15.0, 7.0 / 15.0]
        ) < 1e-6
    );
    println!(
        "swiftshader: the w = 0 strip: depth {} at (2, 0) (must be 0.5), weights (1, 0, 0) everywhere",
        corner.depth
    );
}

/// Finding 3 (docs/certified.md): a snap near a tie.
fn snap_near_a_tie(run: &mut Run<'_>) {
    // 3. A snap near a tie (x/w computed as x·(1/w), scaled and offset in f32), which the
    // measured profile now declares (`SnapAccuracy::WithinOneStep`): vertex 0 is at
    // x = 2.84374982 px, 1.8·10⁻⁷ px below the tie between 2.8125 and 2.875; SwiftShader snaps it
    // to 2.875. Its weights at (2, 0) are exactly those of that snapped triangle; the
    // reference's, of the correctly rounded one, differ by 0.46 (a 2.8-px triangle, w 0.1 to 3.3).
    let near_tie = draw(
        16,
        16,
        vec![
            [-2.123_448_6, 3.294_562_6, 0.0, 3.294_562_6],
            [-0.1, 0.059_765_626, 0.0, 0.1],
            [-2.072_205_8, 2.423_055_4, 0.0, 2.806_797_3],
        ],
    );
    let w = [3.294_562_6, 0.1, 2.806_797_3].map(|w: f32| f64::from(w));
    let theirs = exact_barycentrics([[2.875, 0.0], [0.0, 3.25], [2.125, 1.125]], w, [2.5, 0.5]).0;
    let ours = exact_barycentrics([[2.8125, 0.0], [0.0, 3.25], [2.125, 1.125]], w, [2.5, 0.5]).0;
    let got = at(&run(&near_tie), 2, 0)[0].barycentric;
    let want = at(&expected(&near_tie), 2, 0)[0].barycentric;
    assert!(apart(got, theirs) < 1e-5 && apart(want, ours) < 1e-5 && apart(got, ours) > 0.45);
    println!("swiftshader: a vertex 1.8e-7 px below a snap tie: weights {got:?}, the reference {want:?}");
}

/// Finding 4 (docs/certified.md): the same on depth.
fn depth_near_snap_ties(run: &mut Run<'_>) {
    // 4. The same on depth: vertex 0's y is 4.21874994 px (tie 4.21875), vertex 2's x 0.84374991
    // px (tie 0.84375); SwiftShader snaps both up, and (0, 4) gets the depth of that triangle.
    let depth_tie = draw(
        16,
        16,
        vec![
            [-0.099_560_55, 0.047_265_626, 0.0, 0.1],
            [-0.1, 0.046_435_546, 0.0, 0.1],
            [-1.870_128_4, 0.872_794_6, 0.622_909_9, 2.090_623_9],
        ],
    );
    let (got, want) = (
        at(&run(&depth_tie), 0, 4)[0].depth,
        at(&expected(&depth_tie), 0, 4)[0].depth,
    );
    assert!((got - 0.163_874_75).abs() < 1e-6 && (want - 0.176_910_24).abs() < 1e-6);
    println!("swiftshader: two vertices just below snap ties: depth {got} at (0, 4), the reference {want}");
}

/// Finding 5 (docs/certified.md): plane equations anchored far away.
fn planes_anchored_far_away(run: &mut Run<'_>) {
    // 5. f32 plane equations anchored at the vertex of largest w, here 158 000 px away (the
    // triangle is clipped; vertex 0 is behind the eye): at (0, 7) the weight of the far vertex
    // is -0.0041 (exact arithmetic on the same snapped vertices: +4.3e-5, as the reference).
    let far = draw(
        16,
        16,
        vec![
            [2.467_343_3, -2.080_675_6, 0.0, -1.893_268],
            [0.0, -3.226_922_3, 0.0, 2.425_679],
            [-50_646.65, 76_644.29, 0.0, 2.554_809_6],
        ],
    );
    let (got, want) = (run(&far), expected(&far));
    assert_eq!(
        pixels(&got),
        pixels(&want),
        "swiftshader: the far triangle's coverage"
    );
    let (g, r) = (at(&got, 0, 7)[0].barycentric, at(&want, 0, 7)[0].barycentric);
    assert!(
        g[2] < -0.004 && r[2] > 0.0,
        "the far vertex's weight at (0, 7): {g:?}"
    );
    println!("swiftshader: planes anchored 158 000 px away: weights {g:?} at (0, 7), the reference {r:?}");
    // The same with every w = 1 and every near vertex on the grid: a strip from (2.5, 2.5)-(13.5,
    // 13.5) towards a vertex 160 000 px away. At (11, 12) the far vertex weighs 0.0054 (exact:
    // 5·10⁻⁵, lavapipe 5.000003·10⁻⁵).
    let strip = draw(
        16,
        16,
        vec![
            [-0.6875, 0.6875, 0.5, 1.0],
            [0.6875, -0.6875, 0.5, 1.0],
            [20_000.0, -22_500.0, 0.5, 1.0],
        ],
    );
    let g = at(&run(&strip), 11, 12)[0].barycentric;
    // The ray cast's (`oracle::ray_cast`).
    let exact = [0.909_065_909_090_909_1, 0.090_884_090_909_090_91, 5e-5];
    assert!(apart(g, exact) > 0.003, "{g:?}");
    assert!(
        (g[2] - 0.005_396_133).abs() < 1e-6,
        "the far vertex's weight at (11, 12): {g:?}"
    );
    println!(
        "swiftshader: a strip to 160 000 px, all w = 1: weights {g:?} at (11, 12), exact [0.909066, 0.090884, 0.00005]"
    );

    // And worse, equal w, a vertex 166 000 px away: at (0, 12) a weight of 0.084 where exact
    // arithmetic on the same snapped vertices gives 5·10⁻⁶ (found by bary.equal-w.affine once
    // the profile claimed only 5 bits).
    let worse = draw(
        16,
        64,
        vec![
            [-0.120_826_77, 0.206_112_82, 0.0, 0.2],
            [-4_152.041, -5_038.468, 0.0, 0.2],
            [-0.210_416_7, 0.090_537_33, 0.0, 0.2],
        ],
    );
    let g = at(&run(&worse), 0, 12)[0].barycentric;
    assert!((g[1] - 0.083_804_32).abs() < 1e-6, "{g:?}");
    println!(
        "swiftshader: equal w, a vertex 166 000 px away: weights {g:?} at (0, 12), exact [0.497247, 0.000005, 0.502748]"
    );
}

/// Finding 6 (docs/certified.md): beyond a snapped near cut.
fn beyond_a_snapped_near_cut(run: &mut Run<'_>) {
    // 6. Near a near-plane cut the clipped polygon is snapped on its own, while attributes and
    // depth come from the input triangle's plane: at (13, 6), inside the snapped polygon but
    // 0.02 px beyond the exact cut, SwiftShader extrapolates depth -0.0188 and weights
    // (1.023, -0.047, 0.023) (the same in exact arithmetic); the reference clamps to the cut's
    // values, depth 0.
    let cut = draw(
        16,
        16,
        vec![
            [0.070_751_96, 0.018_75, -0.001_414_671_5, 0.1],
            [0.035_546_876, 0.0125, 0.035_246_246, 0.1],
            [-0.1, 0.00625, 0.051_944_89, 0.1],
        ],
    );
    let (got, want) = (run(&cut), expected(&cut));
    assert_eq!(pixels(&got), vec![(13, 6)]);
    assert_eq!(pixels(&want), vec![(13, 6)]);
    assert!((got[0].depth + 0.018_789_083).abs() < 1e-6 && want[0].depth == 0.0);
    println!(
        "swiftshader: beyond a snapped near cut: depth {}, weights {:?} at (13, 6)",
        got[0].depth, got[0].barycentric
    );
}

/// Finding 7 (docs/certified.md): a vertex at w = NaN.
fn w_nan(run: &mut Run<'_>) {
    // 7. w = NaN at one vertex (the other two span a segment): 10 fragments. Vulkan leaves NaN
    // input unspecified; SwiftShader tests x, y and z for finiteness, not w (`VertexRoutine`).
    let nan = draw(
        8,
        8,
        vec![
            [0.5, 0.5, 0.5, f32::NAN],
            [0.5, 0.5, 0.5, 1.0],
            [-0.5, 0.5, 0.5, 1.0],
        ],
    );
    assert_eq!(
        run(&nan).len(),
        10,
        "swiftshader: fragments of a w = NaN triangle"
    );
}

/// Finding 8 (docs/certified.md): finite coordinates to 1.4e35.
fn huge_coordinates(run: &mut Run<'_>) {
    // 8. Finite coordinates to 1.4·10³⁵: the clipper's products overflow to ∞ and NaN, and 5
    // fragments with NaN depth come out of a triangle whose visible part has no area (x = 0).
    let huge = draw(
        2,
        9,
        vec![
            [0.0, -1.088_515_6e17, 3_296_528_000_000.0, -0.0],
            [0.0, 0.0, 1.415_189e35, 0.0],
            [0.0, -0.0, -0.0, 2_404.501_2],
        ],
    );
    let got = run(&huge);
    assert!(got.len() == 5 && got.iter().all(|f| f.depth.is_nan()) && expected(&huge).is_empty());
}

/// Finding 9 (docs/certified.md): a vertex at w = -FLT_MIN.
fn w_minus_flt_min(run: &mut Run<'_>) {
    // 9. Finding 1's mechanism with w = −1.2·10⁻³⁸ (−FLT_MIN, a normal float) instead of 0
    // (`robust.bit-patterns.sane-output` at case 41 under the measured profile): the vertex is
    // projected with 1/w = −8.5·10³⁷, and the depth plane through the input vertices'
    // projections gives −3.56·10²⁹ at (0, 0), where the clipped polygon's vertices have depths
    // 0 to 0.79 (an f32 trace of SwiftShader's source gives the same −3.5574267·10²⁹).
    let tiny_w = draw(
        1,
        2,
        vec![
            [-0.452_509_43, 0.240_404_3, -0.368_272_66, -0.698_964_54],
            [3.160_516_5, 1.175_494_4e-38, 2.484_375, 3.040_919_3],
            [-1.430_746_9, -6.426_126e-8, -1.122_525_9, -1.175_494_4e-38],
        ],
    );
    let got = run(&tiny_w);
    assert!(
        got.len() == 1 && (got[0].depth + 3.557_426_7e29).abs() < 1e23,
        "swiftshader: a vertex at w = −FLT_MIN: {got:?}"
    );
    println!(
        "swiftshader: a vertex at w = -1.2e-38: depth {} at (0, 0)",
        got[0].depth
    );
}

/// Finding 10 (docs/certified.md): a vertex behind the eye: screen weights.
fn behind_the_eye_screen_weights(run: &mut Run<'_>) {
    // 10. A vertex behind the eye (w = −0.1): the screen-space (`@interpolate(linear)`) planes
    // run through the input vertices' projections, as in finding 2, and at (8, 2) the weights are
    // (−1.72, 0.053, 2.67) (the f32 trace gives the same numbers). Not a violation: a triangle
    // with a vertex at w ≤ 0 has no shape on screen, "linearly in framebuffer space" (Clipping
    // Shader Outputs) has no meaning across w = 0, and GPUs that rasterize homogeneously give
    // exactly these values (NVIDIA's H100: −1.09 on bary.range.unit's shrunk case); only finite
    // weights are required there. The perspective ones are in [0, 1].
    let behind = draw(
        16,
        16,
        vec![
            [0.0, 0.0, 0.0, -0.1],
            [0.233_922_76, 0.0, 0.0, 0.2],
            [0.0, 0.052_034_557, 0.0, 0.2],
        ],
    );
    let f = at(&run(&behind), 8, 2)[0];
    let screen = f.screen_barycentric.expect("screen weights");
    assert!(
        apart(screen, [-1.72, 0.053_333_33, 2.666_666_7]) < 1e-5
            && f.barycentric.iter().all(|b| (0.0..=1.0).contains(b)),
        "swiftshader: screen weights with a vertex behind the eye: {f:?}"
    );
    println!("swiftshader: a vertex behind the eye: screen weights {screen:?} at (8, 2)");
}

/// SwiftShader's depth and id buffers for a draw.
type Resolve<'a> = dyn FnMut(&Draw) -> Resolved + 'a;

/// A finding read off the depth buffer: what it is, and its check.
type ResolvedFinding = (&'static str, fn(&mut Resolve<'_>));

/// Depth bias: r on a `D32_SFLOAT` attachment taken from other depths than the triangle's
/// largest (`SetupRoutine` takes the exponent from one vertex's depth and the others'
/// differences from it), where Vulkan defines `r = 2^(e − n)` with `e` "the maximum exponent …
/// in the range of z values spanned by the primitive" (Depth Bias Computation).
fn bias_exponent_not_the_largest(resolve: &mut Resolve<'_>) {
    // Depths 0.75, 0.3, 0.3: e = −1, r = 2^-24, so a constant factor of 321027 offsets every
    // depth by 0.019135. SwiftShader offsets by 2^-25 × 321027 = 0.009567; with the 0.75 on
    // the last vertex instead, by 0.019135.
    let corners = |z: [f32; 3]| {
        let xyw = [
            (-0.118_379_354, 0.0, 0.25),
            (0.060_459_49, 0.0, 0.25),
            (0.0, 1.545_491_7, 3.137_995_7),
        ];
        (0..3)
            .map(|k| [xyw[k].0, xyw[k].1, z[k] * xyw[k].2, xyw[k].2])
            .collect::<Vec<_>>()
    };
    let offset = |z: [f32; 3], resolve: &mut Resolve<'_>| {
        let mut plain = draw(64, 32, corners(z));
        (plain.state.clip_near, plain.state.clip_far) = (false, false);
        plain.state.depth.compare = CompareOp::Always;
        let mut biased = plain.clone();
        biased.state.depth_bias = Some(DepthBias {
            constant: 321_027.0,
            slope: 0.0,
            clamp: 0.0,
        });
        let (a, b) = (resolve(&plain), resolve(&biased));
        let i = (0..a.depth.len())
            .find(|&i| a.primitive[i].is_some() && b.primitive[i].is_some())
            .expect("a covered pixel");
        f64::from(b.depth[i]) - f64::from(a.depth[i])
    };
    let required = 321_027.0 * 2f64.powi(-24);
    let first = offset([0.75, 0.3, 0.3], resolve);
    assert!(
        (first - required / 2.0).abs() < 1e-6,
        "swiftshader: the largest depth first offsets by {first} (half of Vulkan's {required} was seen)"
    );
    let last = offset([0.3, 0.3, 0.75], resolve);
    assert!(
        (last - required).abs() < 1e-6,
        "swiftshader: the largest depth last offsets by {last} (Vulkan's {required} was seen)"
    );
}

/// A back-facing triangle (clockwise on screen, counter-clockwise front faces): the pixel-space
/// corners (2, 14), (2, 2), (14, 14) of a 16 × 16 target, drawn in `mode`.
fn back_facing(mode: PolygonMode) -> Draw {
    let mut d = draw(
        16,
        16,
        vec![
            [-0.75, -0.75, 0.5, 1.0],
            [-0.75, 0.75, 0.5, 1.0],
            [0.75, -0.75, 0.5, 1.0],
        ],
    );
    d.state.polygon_mode = mode;
    d
}

/// Finding 11 (docs/certified.md): in line and point mode every fragment reports front-facing.
fn polygon_modes_front_facing(run: &mut Run<'_>) {
    // 11. Filled, the triangle's fragments report back-facing, as its clockwise turn says; as
    // its edges or its vertices, every one reports front-facing, as a line's or a point's
    // would, where Vulkan's FrontFacing is zero for "a back-facing polygon primitive" and
    // VkPolygonMode changes only "the final rasterization of polygons".
    assert!(
        run(&back_facing(PolygonMode::Fill))
            .iter()
            .all(|f| !f.front_facing),
        "swiftshader: filled, the triangle faces back"
    );
    for mode in [PolygonMode::Line, PolygonMode::Point] {
        let got = run(&back_facing(mode));
        assert!(
            !got.is_empty() && got.iter().all(|f| f.front_facing),
            "swiftshader: in {} mode every fragment front-facing: {got:?}",
            mode.name()
        );
        assert!(
            reference(4, ClipMode::Full, &back_facing(mode))
                .iter()
                .all(|f| !f.front_facing)
        );
    }
    println!("swiftshader: a back-facing triangle's edges and vertices report front-facing");
}

/// Finding 12 (docs/certified.md): in point mode a culled triangle's points are drawn.
fn point_mode_unculled(run: &mut Run<'_>) {
    // 12. Back faces culled: filled and in line mode the triangle draws nothing; in point mode
    // its three points are drawn, each covering the one pixel centre at its square's top-left
    // corner (the reference's points with culling off), where VkPolygonMode's polygon is
    // "clipped and possibly culled before these modes are applied".
    let culled = |mode| {
        let mut d = back_facing(mode);
        d.state.cull = refrast::CullMode::Back;
        d
    };
    assert!(run(&culled(PolygonMode::Fill)).is_empty() && run(&culled(PolygonMode::Line)).is_empty());
    let got = run(&culled(PolygonMode::Point));
    let points = expected(&back_facing(PolygonMode::Point));
    assert!(
        pixels(&got) == [(1, 1), (1, 13), (13, 13)]
            && pixels(&points) == pixels(&got)
            && expected(&culled(PolygonMode::Point)).is_empty(),
        "swiftshader: a culled triangle's points drawn: {got:?}"
    );
    println!("swiftshader: a back-facing triangle culled filled and as lines draws its 3 points");
}

/// Finding 13 (docs/certified.md): in line mode flat values come from each edge's first vertex.
fn line_mode_flat_per_edge(run: &mut Run<'_>) {
    // 13. One triangle of a list, the first vertex provoking (wgpu's Vulkan default): every
    // fragment must carry vertex 0's flat values, the triangle's provoking vertex; the edge
    // from vertex 1 carries vertex 1's and the edge from vertex 2 vertex 2's, as if each edge
    // were a line of its own.
    let got = run(&back_facing(PolygonMode::Line));
    let flats: std::collections::BTreeSet<Option<u32>> = got.iter().map(|f| f.flat).collect();
    assert_eq!(
        flats.into_iter().collect::<Vec<_>>(),
        [Some(0), Some(1), Some(2)],
        "swiftshader: line mode's flat vertices"
    );
    assert!(
        run(&back_facing(PolygonMode::Fill))
            .iter()
            .all(|f| f.flat == Some(0))
    );
    println!("swiftshader: a triangle's edges carry the flat values of vertices 0, 1 and 2");
}
