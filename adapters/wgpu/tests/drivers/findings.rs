//! The hand-checked findings of docs/certified.md (lavapipe, llvmpipe, softpipe), each as the
//! driver does it today.

use refrast::{Draw, Fragment, FrontFace, Rasterizer, Reference, Scissor, Viewport};
use refrast_wgpu::{Driver, Gpu};

use crate::{resolved, softpipe};

/// A draw on a `width`×`height` target with far clipping on (WebGPU cannot turn it off).
pub fn draw(width: u32, height: u32, positions: Vec<[f32; 4]>, triangles: Vec<[u32; 3]>) -> Draw {
    let mut draw = Draw::new(
        Viewport::new(width, height).expect("a viewport"),
        positions,
        triangles,
    );
    draw.state.clip_far = true;
    draw
}

/// The reference's fragments for `draw`: what each finding's input should give, exactly (i128
/// edge functions on the same 8-bit grid, the top-left rule).
pub fn expected(draw: &Draw) -> Vec<Fragment> {
    Reference::default().rasterize(draw).expect("the reference draws")
}

/// The lower-left half of a 16×16 target (y > x): 120 pixels at one sample.
pub fn lower_left_half() -> Draw {
    draw(
        16,
        16,
        vec![
            [-1.0, 1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, -1.0, 0.5, 1.0],
        ],
        vec![[2, 0, 1]],
    )
}

/// The fragments at pixel `(x, y)`.
pub fn at(frags: &[Fragment], x: u32, y: u32) -> Vec<Fragment> {
    frags.iter().filter(|f| (f.x, f.y) == (x, y)).copied().collect()
}

/// A driver's fragments for a draw.
pub(crate) type Run<'a> = dyn FnMut(&Draw) -> Vec<Fragment> + 'a;

/// One hand-checked finding: what it is, and its check, which panics with what moved.
type Finding = (&'static str, fn(Driver, &mut Run<'_>));

/// The findings every driver is checked for.
const EVERY_DRIVER: [Finding; 5] = [
    ("facing follows the front face", facing),
    ("fragments of extreme inputs", extreme_inputs),
    (
        "screen weights of a clipped triangle of equal w",
        equal_w_screen_weights,
    ),
    ("NaN screen weights beside the near cut", nan_beside_the_near_cut),
    (
        "NaN screen weights at a corner of the view volume",
        nan_at_a_view_volume_corner,
    ),
];

/// The findings of lavapipe and llvmpipe, which snap to a grid.
const ON_A_GRID: [Finding; 5] = [
    ("a tie on an edge leaving the viewport", tie_leaving_the_viewport),
    ("a sliver's weight on its vertex", sliver_weight_on_its_vertex),
    ("the wedge's extrapolated depth", wedge_depth),
    ("a vertex at w = +∞", infinite_w),
    ("a snap tie rounded to even", snap_tie_to_even),
];

/// softpipe's own findings: float edges on no grid.
const SOFTPIPE: [Finding; 4] = [
    (
        "a shared edge's sample covered twice",
        softpipe::softpipe_shared_edge_twice,
    ),
    (
        "a vertex sample as top-right keeps it",
        softpipe::softpipe_vertex_sample,
    ),
    (
        "a flat triangle weighted nothing",
        softpipe::softpipe_flat_triangle,
    ),
    (
        "non-finite weights across w = 0",
        softpipe::softpipe_across_w_zero,
    ),
];

/// lavapipe's own findings: at 4 samples, which only it draws through wgpu of Mesa's three, and
/// of the sample mask, which only it is sent of the three.
const LAVAPIPE: [Finding; 5] = [
    (
        "the scissor tested half a pixel up and left at 4 samples",
        lavapipe_multisample_scissor,
    ),
    (
        "very short lines drawn as nothing at 4 samples",
        crate::lines::lavapipe_short_lines,
    ),
    (
        "the sample mask at one sample read as any of its low 16 bits",
        crate::masks::lavapipe_single_sample_mask,
    ),
    (
        "a sample's perspective divide at the pixel centre",
        crate::masks::lavapipe_sample_divide_at_centre,
    ),
    (
        "a centroid's perspective divide at the pixel centre",
        crate::masks::lavapipe_centroid_divide_at_centre,
    ),
];

/// Each finding of docs/certified.md for driver `d`, as the driver does it today: every one is
/// checked, and those that moved are named together.
pub fn findings(d: Driver, gpu: &mut Gpu) {
    let mut run = |draw: &Draw| gpu.rasterize(draw).expect("the driver draws");
    let own: &[Finding] = if d == Driver::Softpipe {
        &SOFTPIPE
    } else {
        &ON_A_GRID
    };
    let multisampled: &[Finding] = if d == Driver::Lavapipe { &LAVAPIPE } else { &[] };
    let all: Vec<Finding> = EVERY_DRIVER
        .iter()
        .chain(own)
        .chain(multisampled)
        .copied()
        .collect();
    let mut moved = crate::common::moved_findings(&all, |check| check(d, &mut run));
    let resolved: &[resolved::ResolvedFinding] = match d {
        Driver::Softpipe => &[(
            "depth bias saturated per vertex",
            resolved::softpipe_bias_per_vertex,
        )],
        Driver::Llvmpipe => &[(
            "a biased depth read back clamped as the buffer holds it",
            resolved::llvmpipe_biased_copy_clamped,
        )],
        _ => &[],
    };
    let mut resolve = |draw: &Draw| gpu.resolve(draw).expect("the driver resolves");
    moved.extend(crate::common::moved_findings(resolved, |check| {
        check(&mut resolve)
    }));
    let all = all.len() + resolved.len();
    assert!(
        moved.is_empty(),
        "{}: {} of {} hand-checked findings moved:\n{}",
        d.name(),
        moved.len(),
        all,
        moved.join("\n")
    );
    println!("{}: every hand-checked finding holds ({all})", d.name());
}

/// The front face as seen on screen: counter-clockwise there is front-facing.
fn facing(d: Driver, run: &mut Run<'_>) {
    // The front face as seen on screen (y down): counter-clockwise there is front-facing.
    let mut ccw = draw(
        8,
        8,
        vec![
            [-0.5, 0.5, 0.5, 1.0],
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, 0.5, 0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    for (face, front) in [(FrontFace::CounterClockwise, true), (FrontFace::Clockwise, false)] {
        ccw.state.front_face = face;
        let frags = run(&ccw);
        assert!(
            !frags.is_empty() && frags.iter().all(|f| f.front_facing == front),
            "{}: facing under {face:?}",
            d.name()
        );
    }
}

/// Fragments outside the framebuffer, with NaN screen weights, from extreme inputs.
fn extreme_inputs(d: Driver, run: &mut Run<'_>) {
    // Outside-the-framebuffer fragments from extreme inputs (w = 0, a subnormal w, 10³³).
    let extreme = draw(
        2,
        2,
        vec![
            [0.0, 0.0, 0.0, 1.546_945_5e33],
            [0.0, 1.387_206_3e25, 0.0, 0.0],
            [-9.870_036e-26, -0.0, 1.974_007_4e-25, f32::MIN_POSITIVE],
        ],
        vec![[0, 1, 2]],
    );
    let frags = run(&extreme);
    let outside = frags.iter().filter(|f| f.x >= 2 || f.y >= 2).count();
    let non_finite = frags
        .iter()
        .filter(|f| f.barycentric.iter().any(|b| !b.is_finite()))
        .count();
    println!(
        "{}: the extreme triangle gives {} fragments, {outside} outside the 2×2 target, {non_finite} with non-finite weights",
        d.name(),
        frags.len()
    );
    if d == Driver::Softpipe {
        return;
    }
    assert_eq!(
        (frags.len(), outside),
        (12, 10),
        "{}: fragments outside the framebuffer",
        d.name()
    );
    assert!(
        frags
            .iter()
            .all(|f| f.screen_barycentric.is_some_and(|b| b.iter().all(|w| w.is_nan()))),
        "{}: NaN screen-space weights",
        d.name()
    );
}

/// Screen weights beside a near cut made after an x cut, all w equal.
fn equal_w_screen_weights(d: Driver, run: &mut Run<'_>) {
    // Screen-space weights on a triangle clipped by x = w and then the near plane, all w equal
    // (so they must equal the perspective weights): Mesa's draw clipper (`draw_pipe_clip.c`,
    // `interp()`) takes a noperspective output's t from the first axis whose clip coordinates
    // differ, here x, on which both ends of the near cut lie one ulp apart, so t = 0 there.
    let equal_w = draw(
        16,
        16,
        vec![
            [0.034_362_59, -0.156_878_2, 0.095_027_015, 0.2],
            [0.289_709_93, 0.0, 0.0, 0.2],
            [0.0, 0.0, -0.036_756_188, 0.2],
        ],
        vec![[0, 1, 2]],
    );
    let drawn = at(&run(&equal_w), 15, 9);
    let want = at(&expected(&equal_w), 15, 9);
    let (Some(got), Some(want)) = (drawn.first(), want.first()) else {
        panic!("{}: (15, 9) covered by the driver and the reference", d.name());
    };
    let screen = got.screen_barycentric.expect("screen weights");
    let apart = |a: [f32; 3], b: [f32; 3]| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f32::max);
    println!(
        "{}: clipped, equal w, at (15, 9): perspective {:?}, screen {screen:?} (reference {:?})",
        d.name(),
        got.barycentric,
        want.barycentric
    );
    assert!(
        apart(got.barycentric, want.barycentric) < 0.5f32.powi(8)
            && apart(screen, [0.18407, 0.62537, 0.19056]) < 1e-4,
        "{}: clipped screen weights",
        d.name()
    );
}

/// Both ends of a cut at x = 1 exactly, different w: NaN screen weights beside it.
fn nan_beside_the_near_cut(d: Driver, run: &mut Run<'_>) {
    // The same choice of axis, when both ends of the cut project to x = 1 exactly but differ in
    // w: t = 0/0, and every screen weight of the fragments beside that cut is NaN.
    let nan = draw(
        16,
        16,
        vec![
            [0.160_769_08, 0.0, -0.097_080_015, 0.2],
            [0.235_439_35, 0.0, 0.0, 0.2],
            [0.0, -0.362_214_3, 0.897_783_8, 0.897_783_8],
        ],
        vec![[0, 1, 2]],
    );
    let drawn = at(&run(&nan), 15, 8);
    let screen = drawn.first().and_then(|f| f.screen_barycentric);
    println!(
        "{}: clipped at x = w and z = 0, at (15, 8): screen {screen:?}",
        d.name()
    );
    assert!(
        screen.is_some_and(|b| b.iter().all(|w| w.is_nan())) && !at(&expected(&nan), 15, 8).is_empty(),
        "{}: NaN screen weights beside the near cut",
        d.name()
    );
}

/// The same 0/0 at a corner of the view volume, along a diagonal.
fn nan_at_a_view_volume_corner(d: Driver, run: &mut Run<'_>) {
    // The same 0/0 at a corner of the view volume (`bary.sum.one` at case 5): vertex 1 lies
    // beyond x = w and y = −w, both w = 0.1. Clipping at x = w leaves an edge with both ends on
    // x = w (w 0.1 and 0.1074); clipping that edge at y = −w takes t from x, where both ends
    // have x/w = 1. The fan triangle through the new vertex gets NaN screen weights: every
    // sample along the diagonal (8, 8)…(15, 15), which the reference covers with finite ones.
    let corner = draw(
        16,
        16,
        vec![
            [0.0, 0.0, 0.0, 0.1],
            [0.117_693_14, -0.112_314_224, 0.0, 0.1],
            [-3.616_577, 0.0, 0.0, 2.782_967],
        ],
        vec![[0, 1, 2]],
    );
    let (got, want) = (run(&corner), expected(&corner));
    let nan: Vec<(u32, u32)> = got
        .iter()
        .filter(|f| f.screen_barycentric.is_some_and(|b| b.iter().any(|w| w.is_nan())))
        .map(|f| (f.x, f.y))
        .collect();
    println!(
        "{}: corner of the view volume: NaN screen weights at {nan:?}",
        d.name()
    );
    assert!(
        nan.len() == 8 && nan.iter().all(|&(x, y)| x == y && !at(&want, x, y).is_empty()),
        "{}: NaN screen weights along the diagonal",
        d.name()
    );
}

/// A sample exactly on an edge leaving the viewport is covered, inside it is not.
fn tie_leaving_the_viewport(d: Driver, run: &mut Run<'_>) {
    // A sample exactly on an edge leaving the viewport is covered; the same triangle moved
    // inside (8 px right and down, on a 64×64 target; pixel x / 32 − 1 in NDC) leaves it out,
    // as the top-left rule says.
    let leaving = draw(
        32,
        32,
        vec![
            [-0.53125, 0.65625, 0.5, 1.0],
            [-0.635_253_9, 0.21875, 0.5, 1.0],
            [1.172_851_6, 1.09375, 0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    let inside = draw(
        64,
        64,
        vec![
            [-0.515625, 0.578125, 0.5, 1.0],
            [13.835_937_5 / 32.0 - 1.0, 0.359375, 0.5, 1.0],
            [42.765_625 / 32.0 - 1.0, 0.796875, 0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    assert_eq!(
        at(&run(&leaving), 26, 2).len(),
        1,
        "{}: clipped tie covered",
        d.name()
    );
    assert!(
        at(&run(&inside), 34, 10).is_empty(),
        "{}: unclipped tie left out",
        d.name()
    );
    assert!(at(&expected(&leaving), 26, 2).is_empty() && at(&expected(&inside), 34, 10).is_empty());
}

/// A 0.008-px sliver with a 30:1 w ratio: its vertex sample's weight.
fn sliver_weight_on_its_vertex(d: Driver, run: &mut Run<'_>) {
    // A 0.008-px sliver with a 30:1 w ratio: the sample on vertex 0 weighs 0.99744 there.
    let sliver = draw(
        32,
        16,
        vec![
            [1.594_691, -1.313_275, 0.0, 3.001_771_5],
            [0.053_173_83, -0.081_25, 0.0, 0.1],
            [0.053_173_83, -0.036_425_78, 0.0, 0.1],
        ],
        vec![[0, 1, 2]],
    );
    let on_vertex = at(&run(&sliver), 24, 11);
    let off = (1.0
        - on_vertex
            .first()
            .expect("the vertex sample is covered")
            .barycentric[0])
        .abs();
    assert!(
        off > 0.5f32.powi(14) && off < 0.5f32.powi(8),
        "{}: off by {off}",
        d.name()
    );
}

/// The extrapolated depth of a wedge from a vertex at w = 0.
fn wedge_depth(d: Driver, run: &mut Run<'_>) {
    // `robust.bit-patterns.sane-output` at case 289 (2×33): vertex 0 at the centre (depth 0),
    // vertex 1 at w = 0 (a point at infinity, +x), vertex 2 behind the eye. The visible part is
    // a wedge below the row y = 16.5 whose left edge passes 0.001 px (a quarter of a 1/256-px
    // step) below the sample (0.5, 16.5), and 0.50024 steps below the row at x = 0, a hair past
    // a snap tie. Mesa covers the sample and gives it the exact depth plane's value there, −0.82:
    // the plane rises 1.65 per px along the row and 843 per px across it (exact arithmetic:
    // −0.8232). The reference leaves the sample out.
    let wedge = draw(
        2,
        33,
        vec![
            [1.175_494_4e-38, 1.175_494_4e-38, 1.175_494_4e-38, 2.484_375],
            [1.508_894, -1.175_494_4e-38, 2.484_375, 0.0],
            [-12332.554, -1.460_532_1, 2.484_375, -3.986_368_7],
        ],
        vec![[0, 1, 2]],
    );
    let outside = at(&run(&wedge), 0, 16);
    assert!(
        outside.len() == 1
            && (-0.83..-0.81).contains(&outside[0].depth)
            && at(&expected(&wedge), 0, 16).is_empty(),
        "{}: the wedge's extrapolated depth: {outside:?}",
        d.name()
    );
}

/// A vertex at w = +∞: lavapipe draws a fragment, llvmpipe none.
fn infinite_w(d: Driver, run: &mut Run<'_>) {
    // w = +∞ at a vertex: lavapipe draws a fragment, llvmpipe through OpenGL ES draws none.
    let infinite = draw(
        16,
        16,
        vec![
            [-0.631_347_66, 1.0, 0.0, f32::INFINITY],
            [-0.631_347_66, 1.0, 0.0, 1.0],
            [-0.631_347_66, 0.9375, 0.0, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    let drawn: Vec<(u32, u32)> = run(&infinite).iter().map(|f| (f.x, f.y)).collect();
    let expected = if d == Driver::Lavapipe {
        vec![(4, 2)]
    } else {
        vec![]
    };
    assert_eq!(
        drawn,
        expected,
        "{}: fragments of a triangle with w = ∞",
        d.name()
    );
}

/// A snap tie, rounded to even.
fn snap_tie_to_even(d: Driver, run: &mut Run<'_>) {
    // A snap tie: vertex 0's x is (0.21508789 + 1) / 2 · 16 = 9.720703125 px = 2488.5 units,
    // exactly halfway. Rounded to even (2488) it covers what the reference covers, 55 pixels;
    // rounded up (`mutant:half-up-snap`) one more. So the profile claims `ties_to_even`.
    let tie = draw(
        16,
        16,
        vec![
            [0.215_087_89, -0.1875, 0.0, 1.0],
            [-1.0, 1.0, 0.0, 1.0],
            [0.6875, 0.875, 0.0, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    assert_eq!((f64::from(tie.positions[0][0]) + 1.0) * 8.0 * 256.0, 2488.5);
    let pixels = |f: Vec<Fragment>| {
        let mut p: Vec<(u32, u32)> = f.iter().map(|f| (f.x, f.y)).collect();
        p.sort_unstable();
        p
    };
    let want = pixels(Reference::default().rasterize(&tie).expect("the reference draws"));
    assert_eq!(want.len(), 55);
    assert_eq!(
        pixels(run(&tie)),
        want,
        "{}: a snap tie rounded to even",
        d.name()
    );
}

/// At 4 samples, the scissor keeps the samples of the column left of it and of the row above
/// it that lie within half a pixel of the rectangle; at one sample it is exact.
fn lavapipe_multisample_scissor(d: Driver, run: &mut Run<'_>) {
    // The lower-left half, scissored to the 2×2 pixels at (3, 5).
    let mut half = lower_left_half().at_samples(4);
    let scissor = Scissor {
        x: 3,
        y: 5,
        width: 2,
        height: 2,
    };
    half.state.scissor = Some(scissor);
    let mut outside: Vec<(u32, u32, u8)> = run(&half)
        .iter()
        .filter(|f| !scissor.contains(f.x, f.y))
        .map(|f| (f.x, f.y, f.sample))
        .collect();
    outside.sort_unstable();
    // Samples 1 and 3 lie in a pixel's right half, 2 and 3 in its lower half (Vulkan's
    // standard locations): column 2's right half and row 4's lower half.
    let shifted = vec![
        (2, 4, 3),
        (2, 5, 1),
        (2, 5, 3),
        (2, 6, 1),
        (2, 6, 3),
        (3, 4, 2),
        (3, 4, 3),
        (4, 4, 2),
        (4, 4, 3),
    ];
    assert_eq!(
        outside,
        shifted,
        "{}: samples outside the scissor at 4 samples",
        d.name()
    );
    half.samples = 1;
    assert!(
        run(&half).iter().all(|f| scissor.contains(f.x, f.y)),
        "{}: at one sample, fragments outside the scissor",
        d.name()
    );
}
