//! Random scenes for `fast`'s tests: clip-space triangles behind the eye, across the near plane,
//! huge, tiny and degenerate; meshes with shared edges; every cull mode, front face and depth
//! state.

use proptest::prelude::*;
use refrast::{
    CompareOp, CullMode, DepthBias, DepthRange, DepthState, Draw, DrawState, FrontFace, Viewport,
    ViewportDepth,
};

/// A coordinate: mostly on screen, sometimes far off it or huge.
pub fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => -1.5f32..1.5,
        2 => -40.0f32..40.0,
        1 => -1.0e6f32..1.0e6,
        1 => Just(0.0f32),
    ]
}

/// A clip-space vertex; w is mostly positive, sometimes negative or zero.
pub fn vertex() -> impl Strategy<Value = [f32; 4]> {
    let w = prop_oneof![8 => 0.2f32..4.0, 2 => -2.0f32..0.0, 1 => Just(0.0f32), 1 => 1.0e-4f32..1.0e-2];
    (coordinate(), coordinate(), -0.5f32..1.5, w)
        .prop_map(|(x, y, z, w)| [x * w.abs().max(0.1), y * w.abs().max(0.1), z * w, w])
}

/// A triangle: three vertices, or a tiny one near a vertex, or one with a repeated vertex.
pub fn triangle() -> impl Strategy<Value = [[f32; 4]; 3]> {
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

pub fn state() -> impl Strategy<Value = DrawState> {
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
            // fast declares no scissor and no flat values.
            ..DrawState::default()
        },
    )
}

/// A viewport from one pixel to several tiles a side.
pub fn viewport() -> impl Strategy<Value = Viewport> {
    (1u32..200, 1u32..200).prop_map(|(w, h)| Viewport::new(w, h).expect("a valid size"))
}

/// A grid mesh of `n × m` cells with jittered shared vertices (every inner edge shared by two
/// triangles), in a random plane of clip space that may cross the near plane.
pub fn mesh() -> impl Strategy<Value = (Vec<[f32; 4]>, Vec<[u32; 3]>)> {
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
pub fn onto_samples(positions: &[[f32; 4]], viewport: Viewport) -> Vec<[f32; 4]> {
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

/// A draw of up to 23 random clip-space triangles (a soup: no shared vertices).
pub fn soup() -> impl Strategy<Value = Draw> {
    (viewport(), prop::collection::vec(triangle(), 1..24), state()).prop_map(
        |(viewport, triangles, state)| {
            let positions: Vec<[f32; 4]> = triangles.iter().flatten().copied().collect();
            let indices = (0..triangles.len() as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            Draw {
                state,
                ..Draw::new(viewport, positions, indices)
            }
        },
    )
}

/// A draw of a [`mesh`], half the time with every vertex moved onto a sample
/// ([`onto_samples`]), so that edges pass through samples and the fill rule decides.
pub fn mesh_draw() -> impl Strategy<Value = Draw> {
    (viewport(), mesh(), state(), any::<bool>()).prop_map(
        |(viewport, (positions, triangles), state, on_samples)| {
            let positions = if on_samples {
                onto_samples(&positions, viewport)
            } else {
                positions
            };
            Draw {
                state,
                ..Draw::new(viewport, positions, triangles)
            }
        },
    )
}

/// Layers drawn over each other, where most blocks are hidden: whole-viewport quads at depths
/// from a few values (so that depths tie exactly) and large sloped triangles, under a depth
/// test that is mostly one of the four that skip hidden blocks, a viewport depth range either way round and,
/// some of the time, a depth bias.
pub fn layers() -> impl Strategy<Value = Draw> {
    let quad = prop_oneof![Just(0.1f32), Just(0.3), Just(0.5), Just(0.9), -0.2f32..1.2].prop_map(|z| {
        let c = |x: f32, y: f32| [x, y, z, 1.0];
        vec![
            [c(-1.0, -1.0), c(1.0, -1.0), c(1.0, 1.0)],
            [c(-1.0, -1.0), c(1.0, 1.0), c(-1.0, 1.0)],
        ]
    });
    let sloped = prop::array::uniform3((-1.5f32..1.5, -1.5f32..1.5, -0.2f32..1.2))
        .prop_map(|v| vec![v.map(|(x, y, z)| [x, y, z, 1.0])]);
    let layer = prop_oneof![quad, sloped];
    let compare = prop_oneof![
        3 => Just(CompareOp::Less),
        3 => Just(CompareOp::LessOrEqual),
        2 => Just(CompareOp::Greater),
        2 => Just(CompareOp::GreaterOrEqual),
        1 => Just(CompareOp::Always),
    ];
    let viewport_depth = prop_oneof![
        2 => Just(ViewportDepth::FULL),
        1 => (0.0f32..1.0, 0.0f32..1.0).prop_map(|(min, max)| ViewportDepth { min, max }),
    ];
    let bias = prop_oneof![
        2 => Just(None),
        1 => (-4.0f32..4.0, -2.0f32..2.0).prop_map(|(constant, slope)| Some(DepthBias {
            constant,
            slope,
            clamp: 0.0,
        })),
    ];
    let size = (8u32..200, 8u32..200).prop_map(|(w, h)| Viewport::new(w, h).expect("a valid size"));
    (
        size,
        prop::collection::vec(layer, 2..12),
        state(),
        compare,
        viewport_depth,
        bias,
    )
        .prop_map(|(viewport, layers, state, compare, viewport_depth, depth_bias)| {
            let triangles: Vec<[[f32; 4]; 3]> = layers.concat();
            let positions: Vec<[f32; 4]> = triangles.iter().flatten().copied().collect();
            let indices = (0..triangles.len() as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            Draw {
                state: DrawState {
                    cull: CullMode::None,
                    depth: DepthState {
                        compare,
                        ..state.depth
                    },
                    depth_range: DepthRange::ZeroToOne,
                    viewport_depth,
                    depth_bias,
                    ..state
                },
                ..Draw::new(viewport, positions, indices)
            }
        })
}
