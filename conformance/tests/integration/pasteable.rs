//! Counterexamples print as Rust that compiles: these are pasted verbatim from `certify` output.

use refrast::*;
use refrast_conformance::*;

#[test]
fn a_printed_scene_compiles_and_round_trips() {
    // Pasted from `refrast certify` (fill.mesh.exactly-once against an inclusive-edges rasterizer).
    let pasted = Scene {
        width: 16,
        height: 16,
        positions: vec![
            [-1.0, 1.0, 0.5, 1.0],
            [1.0, 1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, -1.0, 0.5, 1.0],
        ],
        triangles: vec![[2, 0, 1], [3, 0, 2]],
        state: DrawState {
            cull: CullMode::None,
            front_face: FrontFace::CounterClockwise,
            depth: DepthState {
                compare: CompareOp::Less,
                write: true,
                clear: 1.0,
            },
            depth_range: DepthRange::ZeroToOne,
            clip_far: false,
            scissor: Some(Scissor {
                x: 2,
                y: 0,
                width: 9,
                height: 16,
            }),
            sample_mask: 0x5,
            interpolation: Interpolation::Centroid,
            conservative: Some(Conservative::Overestimate { extra: 0.5 }),
            provoking_vertex: ProvokingVertex::Last,
            clip_near: false,
            viewport_depth: ViewportDepth { min: 0.75, max: 0.25 },
            depth_bias: Some(DepthBias {
                constant: -4096.0,
                slope: 1.5,
                clamp: 0.0,
            }),
            polygon_mode: PolygonMode::Line,
        },
        distances: Distances {
            clip: 1,
            cull: 1,
            values: vec![0.5, -1.0, -0.25, 2.0, 1.0, 0.0, -3.0, 1.5],
        },
    };
    let printed = format!("{pasted:?}");
    assert!(
        printed.contains(
            "scissor: Some(Scissor { x: 2, y: 0, width: 9, height: 16 }),\n        sample_mask: 0x5,\n        interpolation: Interpolation::Centroid,\n        conservative: Some(Conservative::Overestimate { extra: 0.5 }),\n        provoking_vertex: ProvokingVertex::Last,\n        clip_near: false,\n        viewport_depth: ViewportDepth { min: 0.75, max: 0.25 },\n        depth_bias: Some(DepthBias { constant: -4096.0, slope: 1.5, clamp: 0.0 }),\n        polygon_mode: PolygonMode::Line,\n    },"
        ) && printed.contains(
            "    distances: Distances { clip: 1, cull: 1, values: vec![0.5, -1.0, -0.25, 2.0, 1.0, 0.0, -3.0, 1.5] },\n}"
        ) && !printed.contains(".."),
        "{printed}"
    );
    // Without a scissor or the last provoking vertex, the state prints as before there were
    // either, the rest left to the default.
    let unscissored = Scene {
        state: DrawState {
            scissor: None,
            sample_mask: DrawState::ALL_SAMPLES,
            interpolation: Interpolation::Sample,
            conservative: None,
            provoking_vertex: ProvokingVertex::First,
            clip_near: true,
            viewport_depth: ViewportDepth::FULL,
            depth_bias: None,
            polygon_mode: PolygonMode::Fill,
            ..pasted.state
        },
        distances: Distances::default(),
        ..pasted.clone()
    };
    let printed_without = format!("{unscissored:?}");
    assert!(
        !printed_without.contains("scissor")
            && !printed_without.contains("sample_mask")
            && !printed_without.contains("interpolation")
            && printed_without
                .contains("        ..DrawState::default()\n    },\n    distances: Distances::default(),\n}"),
        "{printed_without}"
    );
    assert!(
        printed.starts_with("Scene {") && printed.contains("CompareOp::Less"),
        "{printed}"
    );
    // Printing is stable: the same scene prints the same text.
    assert_eq!(printed, format!("{:?}", pasted.clone()));
}

#[test]
fn wrapped_inputs_print_as_rust_too() {
    let scene = Scene::new(16, 16, vec![[0.0, 0.0, 0.5, 1.0]; 3], vec![[0, 1, 2]]);
    let poisoned = Poisoned {
        scene: scene.clone(),
        at: (0, 3),
        value: f32::NAN,
    };
    let text = format!("{poisoned:?}");
    assert!(text.contains("value: f32::NAN"), "{text}");
    let moved = Translated { scene, dx: -2, dy: 3 };
    assert!(format!("{moved:?}").contains("dx: -2, dy: 3"));
}
