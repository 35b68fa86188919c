//! `fast` against the reference, bit for bit: fragments as sorted sets and resolved buffers, on
//! random scenes (clip-space triangles behind the eye, across the near plane, huge, tiny and
//! degenerate; meshes with shared edges) under every cull mode, front face and depth state.

use proptest::prelude::*;
use refrast::{
    CompareOp, CullMode, DepthRange, DepthState, Draw, DrawState, Fragment, FrontFace, Rasterizer, Reference,
    Resolved, Viewport,
};
use refrast_fast::Fast;

/// A fragment as the bits that must agree, in an order that sorts by primitive then pixel.
type Bits = (u32, u32, u32, u32, [u32; 3], Option<[u32; 3]>, bool);

fn bits(f: &Fragment) -> Bits {
    (
        f.primitive,
        f.y,
        f.x,
        f.depth.to_bits(),
        f.barycentric.map(f32::to_bits),
        f.screen_barycentric.map(|b| b.map(f32::to_bits)),
        f.front_facing,
    )
}

fn sorted(fragments: &[Fragment]) -> Vec<Bits> {
    let mut all: Vec<Bits> = fragments.iter().map(bits).collect();
    all.sort_unstable();
    all
}

/// Depth and primitive buffers as bits.
fn resolved_bits(r: &Resolved) -> (Vec<u32>, &[Option<u32>]) {
    (r.depth.iter().map(|d| d.to_bits()).collect(), &r.primitive)
}

/// Asserts that `fast` with `threads` matches the reference on `draw`.
fn agree(draw: &Draw, threads: usize) -> Result<(), TestCaseError> {
    let mut reference = Reference::default();
    let mut fast = Fast::with_threads(threads);
    let want = sorted(&reference.rasterize(draw).expect("reference draws"));
    let got = sorted(&fast.rasterize(draw).expect("fast draws"));
    prop_assert_eq!(got.len(), want.len(), "fragment count");
    prop_assert!(got == want, "fragments differ");
    let (want, got) = (reference.resolve(draw).unwrap(), fast.resolve(draw).unwrap());
    prop_assert!(
        resolved_bits(&got) == resolved_bits(&want),
        "resolved buffers differ"
    );
    Ok(())
}

/// A coordinate: mostly on screen, sometimes far off it or huge.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => -1.5f32..1.5,
        2 => -40.0f32..40.0,
        1 => -1.0e6f32..1.0e6,
        1 => Just(0.0f32),
    ]
}

/// A clip-space vertex; w is mostly positive, sometimes negative or zero.
fn vertex() -> impl Strategy<Value = [f32; 4]> {
    let w = prop_oneof![8 => 0.2f32..4.0, 2 => -2.0f32..0.0, 1 => Just(0.0f32), 1 => 1.0e-4f32..1.0e-2];
    (coordinate(), coordinate(), -0.5f32..1.5, w)
        .prop_map(|(x, y, z, w)| [x * w.abs().max(0.1), y * w.abs().max(0.1), z * w, w])
}

/// A triangle: three vertices, or a tiny one near a vertex, or one with a repeated vertex.
fn triangle() -> impl Strategy<Value = [[f32; 4]; 3]> {
    prop_oneof![
        6 => [vertex(), vertex(), vertex()],
        2 => (vertex(), [-0.02f32..0.02, -0.02f32..0.02, -0.02f32..0.02, -0.02f32..0.02])
            .prop_map(|(v, d)| {
                let near = |k: usize| [v[0] + d[k], v[1] - d[(k + 1) % 4], v[2], v[3]];
                [v, near(0), near(2)]
            }),
        1 => (vertex(), vertex()).prop_map(|(a, b)| [a, b, a]),
        1 => (vertex(), vertex()).prop_map(|(a, b)| {
            let mid = [0, 1, 2, 3].map(|k| (a[k] + b[k]) / 2.0);
            [a, mid, b]
        }),
    ]
}

fn state() -> impl Strategy<Value = DrawState> {
    let cull = prop_oneof![Just(CullMode::None), Just(CullMode::Front), Just(CullMode::Back)];
    let front = prop_oneof![Just(FrontFace::CounterClockwise), Just(FrontFace::Clockwise)];
    let compare = prop_oneof![
        Just(CompareOp::Less),
        Just(CompareOp::LessOrEqual),
        Just(CompareOp::Greater),
        Just(CompareOp::Equal),
        Just(CompareOp::Always),
        Just(CompareOp::Never),
        Just(CompareOp::NotEqual),
        Just(CompareOp::GreaterOrEqual),
    ];
    let range = prop_oneof![Just(DepthRange::ZeroToOne), Just(DepthRange::NegativeOneToOne)];
    let clear = prop_oneof![Just(1.0f32), Just(0.0f32), 0.0f32..1.0];
    (cull, front, compare, any::<bool>(), clear, range, any::<bool>()).prop_map(
        |(cull, front_face, compare, write, clear, depth_range, clip_far)| DrawState {
            cull,
            front_face,
            depth: DepthState {
                compare,
                write,
                clear,
            },
            depth_range,
            clip_far,
        },
    )
}

/// A viewport from one pixel to several tiles a side.
fn viewport() -> impl Strategy<Value = Viewport> {
    (1u32..200, 1u32..200).prop_map(|(w, h)| Viewport::new(w, h).expect("a valid size"))
}

/// A grid mesh of `n × m` cells with jittered shared vertices (every inner edge shared by two
/// triangles), in a random plane of clip space that may cross the near plane.
fn mesh() -> impl Strategy<Value = (Vec<[f32; 4]>, Vec<[u32; 3]>)> {
    (
        2usize..9,
        2usize..9,
        -1.5f32..1.5,
        0.3f32..3.0,
        -1.0f32..1.0,
        any::<u64>(),
    )
        .prop_map(|(n, m, z0, w0, tilt, seed)| {
            let mut state = seed | 1;
            let mut jitter = || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 40) as f32 / (1u64 << 24) as f32 - 0.5
            };
            let mut positions = Vec::new();
            for j in 0..=m {
                for i in 0..=n {
                    let x = -1.2 + 2.4 * (i as f32 + 0.4 * jitter()) / n as f32;
                    let y = -1.2 + 2.4 * (j as f32 + 0.4 * jitter()) / m as f32;
                    let w = w0 + tilt * x;
                    positions.push([x * w, y * w, (z0 + 0.3 * y) * w, w]);
                }
            }
            let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
            let mut triangles = Vec::new();
            for j in 0..m {
                for i in 0..n {
                    triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                    triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
            (positions, triangles)
        })
}

/// The vertices moved to `w = 1` and onto the nearest pixel sample of `viewport`.
fn onto_samples(positions: &[[f32; 4]], viewport: Viewport) -> Vec<[f32; 4]> {
    let (w, h) = (viewport.width() as f32, viewport.height() as f32);
    positions
        .iter()
        .map(|p| {
            let (x, y) = (p[0] / p[3], p[1] / p[3]);
            let px = ((x + 1.0) / 2.0 * w - 0.5).round() + 0.5;
            let py = ((1.0 - y) / 2.0 * h - 0.5).round() + 0.5;
            [px / w * 2.0 - 1.0, 1.0 - py / h * 2.0, p[2] / p[3], 1.0]
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// Soups of random clip-space triangles.
    #[test]
    fn random_triangles_match_the_reference(
        viewport in viewport(),
        triangles in prop::collection::vec(triangle(), 1..24),
        state in state(),
        threads in 1usize..3,
    ) {
        let positions: Vec<[f32; 4]> = triangles.iter().flatten().copied().collect();
        let indices = (0..triangles.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let draw = Draw { viewport, positions, triangles: indices, state };
        agree(&draw, threads)?;
    }

    /// Meshes with shared edges, some reaching through the near plane; some with every vertex
    /// on a pixel's sample, so that edges pass through samples and the fill rule decides.
    #[test]
    fn meshes_match_the_reference(
        viewport in viewport(),
        (positions, triangles) in mesh(),
        state in state(),
        on_samples in any::<bool>(),
        threads in 1usize..3,
    ) {
        let positions = if on_samples { onto_samples(&positions, viewport) } else { positions };
        let draw = Draw { viewport, positions, triangles, state };
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
    use refrast_conformance::fuzz::{Outcome, Target};
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
            Outcome::Failed(failure) => panic!("{}: {failure}", seed.display()),
            Outcome::Passed => passed += 1,
            Outcome::Skipped => {}
        }
    }
    assert!(passed > 0, "no seed decoded");
}

/// Found by `meshes_match_the_reference`: a triangle whose corners' outcodes say "cut" can be
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
    };
    for threads in [1, 2] {
        agree(&draw, threads).unwrap();
    }
}
