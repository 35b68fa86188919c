//! `fast` against the reference under its contract (`refrast_fast::contract`): the same covered
//! samples, interpolation within the declared precision, and resolved buffers that differ only
//! where depths tie within it; on random scenes (clip-space triangles behind the eye, across the
//! near plane, huge, tiny and degenerate; meshes with shared edges) under every cull mode, front
//! face and depth state.

use crate::support;

use proptest::prelude::*;
use refrast::{
    CompareOp, CullMode, DepthRange, DepthState, Draw, DrawState, FrontFace, Rasterizer, Reference, Resolved,
    Viewport,
};
use refrast_fast::Fast;
use refrast_fast::contract::{check_fragments, check_resolved, tolerance};
use support::{layers, mesh_draw, soup};

/// Depth and primitive buffers as bits.
fn resolved_bits(r: &Resolved) -> (Vec<u32>, &[Option<u32>]) {
    (r.depth.iter().map(|d| d.to_bits()).collect(), &r.primitive)
}

/// Asserts that `fast` with `threads` keeps its contract with the reference on `draw`, and that
/// its resolve is its own fragments' resolve, bit for bit.
fn agree(draw: &Draw, threads: usize) -> Result<(), TestCaseError> {
    let mut reference = Reference::default();
    let mut fast = Fast::with_threads(threads);
    let want = reference.rasterize(draw).expect("reference draws");
    let got = fast.rasterize(draw).expect("fast draws");
    let tolerance = tolerance();
    check_fragments(&want, &got, tolerance).map_err(TestCaseError::fail)?;
    let resolved = fast.resolve(draw).expect("fast resolves");
    check_resolved(&want, draw.state.depth, &resolved, tolerance).map_err(TestCaseError::fail)?;
    let own = Resolved::from_fragments(draw, got);
    prop_assert!(
        resolved_bits(&resolved) == resolved_bits(&own),
        "fast's resolve is not the resolve of its fragments"
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// Soups of random clip-space triangles.
    #[test]
    fn random_triangles_keep_the_contract(draw in soup(), threads in 1usize..3) {
        agree(&draw, threads)?;
    }

    /// Meshes with shared edges, some reaching through the near plane; some with every vertex
    /// on a pixel's sample, so that edges pass through samples and the fill rule decides.
    #[test]
    fn meshes_keep_the_contract(draw in mesh_draw(), threads in 1usize..3) {
        agree(&draw, threads)?;
    }

    /// Layers over each other, ties and hidden blocks (which the resolve skips untested,
    /// `hiz.rs`) included.
    #[test]
    fn hidden_layers_keep_the_contract(draw in layers(), threads in 1usize..3) {
        agree(&draw, threads)?;
    }
}

/// More primitives than one batch, over a target of many tiles: batches keep primitive order
/// in the depth test (each of the overlapping quads drawn twice at one depth, so the later
/// copy passes LESS_OR_EQUAL and owns the pixel).
#[test]
fn many_batches_keep_primitive_order() {
    let viewport = Viewport::new(300, 170).unwrap();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..20_000u32 {
        let t = i as f32 * 0.618;
        let (cx, cy) = ((t.sin() * 0.8), ((t * 1.3).cos() * 0.8));
        let s = 0.05 + 0.1 * (i % 7) as f32 / 7.0;
        let z = (i % 13) as f32 / 13.0;
        let base = positions.len() as u32;
        positions.extend([
            [cx - s, cy - s, z, 1.0],
            [cx + s, cy - s, z, 1.0],
            [cx, cy + s, z, 1.0],
        ]);
        triangles.push([base, base + 1, base + 2]);
        triangles.push([base, base + 1, base + 2]);
    }
    let mut draw = Draw::new(viewport, positions, triangles);
    draw.state.depth.compare = CompareOp::LessOrEqual;
    for threads in [1, 2] {
        agree(&draw, threads).unwrap();
    }
}

/// Shared vertices are set up once for all their triangles: a NaN vertex drops exactly the
/// triangles that use it, and a vertex behind the eye is clipped in one triangle while its
/// neighbours, sharing the others, are drawn whole.
#[test]
fn shared_vertices_set_up_once_drop_and_clip_only_their_triangles() {
    let viewport = Viewport::new(40, 30).unwrap();
    let positions = vec![
        [-0.9, -0.9, 0.5, 1.0],
        [0.9, -0.9, 0.5, 1.0],
        [0.9, 0.9, 0.5, 1.0],
        [-0.9, 0.9, 0.5, 1.0],
        [0.0, 0.0, f32::NAN, 1.0],
        [0.2, 0.1, -0.5, -0.5],
        [0.0, -0.2, 0.4, 1.0],
    ];
    let triangles = vec![
        [0, 1, 6],
        [1, 2, 6],
        [2, 3, 4],
        [3, 0, 4],
        [0, 6, 5],
        [6, 2, 5],
        [2, 3, 6],
    ];
    let mut draw = Draw::new(viewport, positions, triangles);
    draw.state.cull = CullMode::None;
    for threads in [1, 2] {
        agree(&draw, threads).unwrap();
    }
    let fragments = Fast::with_threads(1).rasterize(&draw).unwrap();
    let drawn = |p: u32| fragments.iter().any(|f| f.primitive == p);
    assert!(
        drawn(0) && drawn(1) && drawn(6),
        "the triangles of finite vertices are drawn"
    );
    assert!(!drawn(2) && !drawn(3), "the triangles of the NaN vertex are not");
}

/// The `differential` fuzz target's committed seeds (`fuzz/seeds/differential/`) pass under
/// `fast`, as the `fast` fuzz target runs them: on stable, without cargo-fuzz.
#[test]
fn differential_fuzz_seeds_pass() {
    use refrast_conformance::fuzz::{Checked, Target};
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/seeds/differential");
    let mut seeds: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    seeds.sort();
    assert!(seeds.len() > 10, "{} holds the seeds", dir.display());
    let mut fast = Fast::with_threads(2);
    let mut passed = 0;
    for seed in &seeds {
        let bytes = std::fs::read(seed).unwrap();
        match Target::Differential.run(&mut fast, &bytes) {
            Checked::Failed(failure) => panic!("{}: {failure}", seed.display()),
            Checked::Passed => passed += 1,
            Checked::Skipped => {}
        }
    }
    assert!(passed > 0, "no seed decoded");
}

/// Found by `meshes_match_the_reference` (now `meshes_keep_the_contract`): a triangle whose corners' outcodes say "cut" can be
/// clipped to nothing (here by the near plane, with w < 0 corners), and then draws nothing,
/// where a first version asserted it always left a polygon.
#[test]
fn a_triangle_the_outcodes_call_cut_can_be_clipped_to_nothing() {
    let positions = vec![
        [0.6083917, 0.75226825, -0.63448983, -0.60517853],
        [0.036888298, -0.3798176, 0.43475032, 0.38603845],
        [1.317501, -1.3182373, 1.3804243, 1.249443],
        [1.2958847, -0.016650936, -1.3418539, -0.94055575],
        [-0.024924818, 0.027955057, 0.23239012, 0.15759923],
        [1.7626817, -0.31033516, 1.9233767, 1.4187059],
        [1.0501438, -1.166624, -1.5352421, -0.83389395],
        [0.07506698, 0.49553493, 0.7884813, 0.45015022],
        [1.5468676, 1.4580411, 2.3415408, 1.3396623],
    ];
    let triangles = vec![
        [0, 1, 4],
        [0, 4, 3],
        [1, 2, 5],
        [1, 5, 4],
        [3, 4, 7],
        [3, 7, 6],
        [4, 5, 8],
        [4, 8, 7],
    ];
    let mut draw = Draw::new(Viewport::new(1, 1).unwrap(), positions, triangles);
    draw.state = DrawState {
        cull: CullMode::None,
        front_face: FrontFace::CounterClockwise,
        depth: DepthState {
            compare: CompareOp::Less,
            write: false,
            clear: 1.0,
        },
        depth_range: DepthRange::ZeroToOne,
        clip_far: true,
        ..DrawState::default()
    };
    for threads in [1, 2] {
        agree(&draw, threads).unwrap();
    }
}

/// Found by `random_triangles_keep_the_contract`: a triangle clipped at the near plane whose
/// polygon reaches the guard band, where window depth runs far outside `[0, 1]`. Depth
/// interpolated in f32 over the edge values erred by 2^-15.7 (its error scales with the corners'
/// depth range, not the result's); in f64 lanes it is within an f32 ulp.
#[test]
fn a_clipped_polygon_with_far_depths_keeps_depth_precise() {
    let positions = vec![
        [0.0, -0.174_657_03, -0.0, -0.312_266_05],
        [0.0, 0.0, 0.081_651_24, 0.2],
        [-0.101_962_66, 0.0, 0.0, 0.2],
    ];
    let mut draw = Draw::new(Viewport::new(3, 33).unwrap(), positions, vec![[0, 1, 2]]);
    draw.state.cull = CullMode::None;
    draw.state.clip_far = false;
    agree(&draw, 1).unwrap();
}

/// Found by `robust.bit-patterns.sane-output` in `fast`'s certification: corners' `1/w` that
/// differ by 10^45 underflowed to zero in f32 perspective weights and made NaN barycentrics;
/// the weights are now one f64 reciprocal per fragment.
#[test]
fn corners_whose_w_differ_by_many_orders_keep_finite_barycentrics() {
    let positions = vec![
        [0.0, 0.0, 0.0, -3.023_819_5e21],
        [0.0, -1_048_250_450_000_000.0, -7.978_133_3e-22, 8.082_63e24],
        [5.029_327_3e-20, 0.0, 1.651_652_2e-24, 4.604_487e-24],
    ];
    let mut draw = Draw::new(Viewport::new(3, 3).unwrap(), positions, vec![[0, 1, 2]]);
    draw.state.cull = CullMode::None;
    draw.state.clip_far = false;
    let fragments = Fast::with_threads(1).rasterize(&draw).unwrap();
    assert!(!fragments.is_empty(), "the case draws");
    for f in &fragments {
        assert!(f.barycentric.iter().all(|b| b.is_finite()), "{f:?}");
    }
    agree(&draw, 1).unwrap();
}
