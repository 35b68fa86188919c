//! Correct rasterizers shaped like the ones that exposed false verdicts (`refrast_conformance::
//! shaped`) pass, are `n/a` or are beyond their claimed specification on every rule; and the
//! counterexamples that exposed each class, from a GPU (NVIDIA H100 through wgpu), a Skia-style
//! scan converter and a student's float rasterizer through the pipe, are named regression tests.

use refrast::{
    Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Resolved, Snapping, Spec, Topology,
};
use refrast_conformance::rules::{bary, fill, msaa};
use refrast_conformance::{Options, PrimitiveScene, Scene, Status, certify};
use refrast_zoo::shaped::{Shape, Shaped, shapes};

/// Cases per rule: few, as in the restricted matrix (`REFRAST_MATRIX_CASES`).
fn cases() -> u32 {
    std::env::var("REFRAST_MATRIX_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(24)
}

#[test]
fn every_shaped_rasterizer_passes_or_is_beyond_its_specification() {
    let options = Options {
        cases: Some(cases()),
        ..Options::default()
    };
    let mut failures = Vec::new();
    for mut r in shapes() {
        let report = certify(&mut r, &options, |_| {});
        let name = r.profile().name;
        assert_eq!(report.refused, None, "{name} was refused");
        for rule in &report.rules {
            if !matches!(
                rule.status,
                Status::Pass | Status::NotApplicable | Status::BeyondSpec
            ) {
                failures.push(format!(
                    "{name}: {} {:?}: {}\n{}",
                    rule.id,
                    rule.status,
                    rule.message.as_deref().unwrap_or(""),
                    rule.counterexample.as_deref().unwrap_or("")
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The scan converter clips nothing, so the clip rules are n/a for it, with the reason; the
/// scissor's and the distances', in the same family, for what it does not declare either.
#[test]
fn a_scan_converter_is_not_asked_about_clipping() {
    let options = Options {
        cases: Some(4),
        rules: vec!["clip.*".into()],
        ..Options::default()
    };
    let report = certify(&mut Shaped::new(Shape::ScanConverter), &options, |_| {});
    assert!(!report.rules.is_empty());
    for rule in &report.rules {
        assert_eq!(rule.status, Status::NotApplicable, "{}", rule.id);
        let why = rule.message.as_deref().unwrap_or("");
        let reason = if rule.id.starts_with("clip.scissor.") {
            "no scissor"
        } else if rule.id.starts_with("clip.distance.") {
            "no clip distances"
        } else if rule.id.starts_with("clip.cull-distance.") {
            "no cull distances"
        } else {
            "clipping in 3D"
        };
        assert!(why.contains(reason), "{}: {why}", rule.id);
    }
}

/// A triangle of `positions` on a `side`×`side` target with default state.
fn triangle(side: u32, positions: [[f32; 4]; 3]) -> Scene {
    Scene::new(side, side, positions.to_vec(), vec![[0, 1, 2]])
}

/// NVIDIA H100 (and SwiftShader, and a Skia-based client): screen-space weights −0.57 to −1.09
/// on a triangle with a vertex behind the eye, which has no shape on screen. Only finite values
/// are required there; NaN ones still fail.
#[test]
fn screen_weights_across_the_eye_are_judged_only_for_finiteness() {
    let scene = triangle(
        16,
        [
            [0.0, 0.0, 0.084_573_12, -0.1],
            [0.0, -0.095_399_104, 0.0, 0.2],
            [-0.289_028_4, 0.0, 0.0, 0.2],
        ],
    );
    let mut gpu = Shaped::new(Shape::ScreenPlaneAcrossEye);
    let drawn = gpu.rasterize(&scene.draw()).expect("draws");
    assert!(
        drawn
            .iter()
            .filter_map(|f| f.screen_barycentric)
            .any(|b| b.iter().any(|&c| c < -0.5)),
        "the shape gives the GPU's out-of-range weights"
    );
    bary::check_in_range(&mut gpu, &scene).expect("finite weights across w = 0 pass");
    bary::check_sum_one(&mut gpu, &scene).expect("and sum to 1");
    let mut nan = Altered(Reference::default(), |f| {
        f.screen_barycentric = Some([f32::NAN, 0.5, 0.5])
    });
    assert!(
        bary::check_in_range(&mut nan, &scene).is_err(),
        "NaN weights still fail"
    );
}

/// Screen-space weights missing (three NaN words through the pipe) are an answer only for a
/// triangle with a vertex at w ≤ 0.
#[test]
fn missing_screen_weights_fail_only_where_they_are_defined() {
    let mut none = Altered(Reference::default(), |f| f.screen_barycentric = None);
    let behind = triangle(
        16,
        [
            [0.0, 0.0, 0.084_573_12, -0.1],
            [0.0, -0.095_399_104, 0.0, 0.2],
            [-0.289_028_4, 0.0, 0.0, 0.2],
        ],
    );
    bary::check_sum_one(&mut none, &behind).expect("none across w = 0");
    let front = triangle(
        16,
        [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, 1.0],
        ],
    );
    let why = bary::check_sum_one(&mut none, &front).expect_err("none in front of the eye");
    assert!(why.to_string().contains("barycentrics"), "{why}");
}

/// NVIDIA H100: at 4 samples, the depth buffer holds each sample's own depth (0.399 at sample 1
/// of row 1) while the sample fragments carry FragCoord.z at the pixel centre (3e-8). The
/// replay judges the buffer at each sample's own depth, not the fragments' reported one.
#[test]
fn a_resolve_is_replayed_at_each_samples_own_depth() {
    let scene = triangle(
        16,
        [
            [-0.9375, 0.8125, 0.0, 1.0],
            [23.816_406, 0.8125, 0.0, 1.0],
            [-0.9375, 0.828_613_3, 0.411_712_97, 1.0],
        ],
    );
    let case = PrimitiveScene::triangles(scene, 4);
    let mut gpu = Shaped::new(Shape::FragCoordAtCentre);
    msaa::check_resolve(&mut gpu, &case).expect("the per-sample depth test's buffer passes");
    // Away from edges, on a steep triangle covering the target: the fragments carry the
    // centre's depth, which msaa.depth.per-sample's whole rule sees and its Vulkan part (the
    // depth buffer alone) does not; a resolve that tested the centre's depth is still caught.
    let steep = PrimitiveScene::triangles(
        triangle(
            16,
            [
                [-1.0, 1.0, 0.0, 1.0],
                [3.0, 1.0, 0.0, 1.0],
                [-1.0, -3.0, 1.0, 1.0],
            ],
        ),
        4,
    );
    msaa::check_resolve(&mut gpu, &steep).expect("each sample tested at its own depth");
    assert!(msaa::check_depth(&mut gpu, &steep).is_err());
    msaa::check_depth_resolved(&mut gpu, &steep).expect("the buffer holds each sample's depth");
    let mut centre = CentreTested(Shaped::new(Shape::FragCoordAtCentre));
    assert!(msaa::check_resolve(&mut centre, &steep).is_err());
}

/// NVIDIA H100, lavapipe, SwiftShader: a point 0.0117 px below a 16×32 target draws sample 2 of
/// pixel (0, 31) at 4 samples. Vulkan's text discards it (ALL_CLIP_PLANES); its CTS accepts it:
/// beyond Vulkan, never a failure.
#[test]
fn a_point_drawn_pop_free_is_beyond_vulkan_not_a_failure() {
    let scene = Scene::new(16, 32, vec![[-1.0, -1.000_732_4, 0.0, 1.0]], Vec::new());
    let case = PrimitiveScene {
        scene,
        topology: Topology::PointList,
        indices: vec![0],
        samples: 4,
    };
    let mut gpu = Shaped::new(Shape::PopFreePoints);
    let drawn = gpu.rasterize(&case.draw()).expect("draws");
    assert!(
        drawn.iter().any(|f| (f.x, f.y, f.sample) == (0, 31, 2)),
        "{drawn:?}"
    );
    msaa::check_lines_points_as_cts(&mut gpu, &case).expect("what Vulkan's CTS checks");
    assert!(
        msaa::check_lines_points(&mut gpu, &case).is_err(),
        "the text's discard"
    );
}

/// A student's float rasterizer through the pipe: vertices 0 and 1 project 3e-7 px on either side
/// of the sample (3.5, 14.5), on neither; the rule demanded weight 1 for both at once, where the
/// exact weights are (0.809, 0.191, 0). Without a grid, a vertex that near is judged against the
/// exact weights at the sample.
#[test]
fn a_vertex_a_hair_from_a_sample_is_not_on_it() {
    let scene = triangle(
        16,
        [
            [-0.056_250_002, -0.081_250_004, 0.0, 0.1],
            [-0.323_868_22, -0.467_809_65, 0.0, 0.575_765_7],
            [-0.1, 0.1, 0.0, 0.1],
        ],
    );
    let exact = exact_weights(&scene.draw(), 0, 3, 14);
    assert!(
        (exact[0] - 0.809).abs() < 1e-3 && (exact[1] - 0.191).abs() < 1e-3,
        "{exact:?}"
    );
    let mut student = AtSample((3, 14), exact);
    bary::check_vertex_one(&mut student, &scene).expect("the exact weights at the sample");
    let mut one = AtSample((3, 14), [1.0, 0.0, 0.0]);
    assert!(
        bary::check_vertex_one(&mut one, &scene).is_err(),
        "weight 1 is not exact there"
    );
    // Exactly on a sample, a vertex still has weight 1.
    let on = triangle(
        16,
        [
            [-0.5625, 0.1875, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.5, 0.5, 0.5, 1.0],
        ],
    );
    bary::check_vertex_one(&mut AtSample((3, 6), [1.0, 0.0, 0.0]), &on).expect("exact");
    assert!(bary::check_vertex_one(&mut AtSample((3, 6), [0.9, 0.05, 0.05]), &on).is_err());
}

/// The exact perspective-correct weights of `draw`'s triangle `t`, unsnapped, at the sample of
/// pixel `(x, y)`: what a float rasterizer with exact arithmetic gives.
fn exact_weights(draw: &Draw, t: usize, x: u32, y: u32) -> [f32; 3] {
    let (w, h) = (
        f64::from(draw.viewport.width()),
        f64::from(draw.viewport.height()),
    );
    let v = draw.triangles()[t].map(|i| draw.positions[i as usize].map(f64::from));
    let p = v.map(|c| [(c[0] / c[3] + 1.0) / 2.0 * w, (1.0 - c[1] / c[3]) / 2.0 * h]);
    let s = [f64::from(x) + 0.5, f64::from(y) + 0.5];
    let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]);
    let q = [
        e(p[1], p[2]) / v[0][3],
        e(p[2], p[0]) / v[1][3],
        e(p[0], p[1]) / v[2][3],
    ];
    let sum = q[0] + q[1] + q[2];
    q.map(|c| (c / sum) as f32)
}

/// A float rasterizer (no grid, no tie rule, perspective weights only) that covers one sample,
/// with the given weights: the student's, through the pipe.
struct AtSample((u32, u32), [f32; 3]);

impl Rasterizer for AtSample {
    fn profile(&self) -> Profile {
        let mut p = Reference::default().profile();
        p.snapping = Snapping::Float;
        p.fill = None;
        p.features.screen_barycentrics = false;
        p
    }

    fn rasterize(&mut self, _: &Draw) -> Result<Vec<Fragment>, DrawError> {
        Ok(vec![Fragment {
            x: self.0.0,
            y: self.0.1,
            sample: 0,
            primitive: 0,
            depth: 0.0,
            barycentric: self.1,
            screen_barycentric: None,
            front_facing: true,
            flat: None,
        }])
    }
}

/// A Skia-style scan converter (truncating to 26.6): a vertex shared by four triangles at
/// (8.51, 8.51) px snaps onto the sample (8.5, 8.5), which the old check, testing the
/// unsnapped position, required to be covered exactly once under Vulkan. Vulkan requires
/// nothing of a sample on a vertex shared by three or more: where the profile puts it counts.
#[test]
fn a_sample_on_a_snapped_vertex_of_three_is_free_under_vulkan() {
    let at = |x: f64, y: f64| [(x / 8.0 - 1.0) as f32, (1.0 - y / 8.0) as f32, 0.5, 1.0];
    let positions = vec![
        at(8.51, 8.51),
        at(0.0, 0.0),
        at(16.0, 0.0),
        at(16.0, 16.0),
        at(0.0, 16.0),
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]];
    let scene = Scene::new(16, 16, positions, triangles);
    let mut doubled = Doubling(Shaped::new(Shape::ScanConverter), (8, 8));
    fill::check_exactly_once_between_two(&mut doubled, &scene).expect("free on the snapped vertex");
    assert!(
        fill::check_exactly_once(&mut doubled, &scene).is_err(),
        "refrast's convention"
    );
    fill::check_exactly_once(&mut Shaped::new(Shape::ScanConverter), &scene)
        .expect("the shape covers it once");
}

/// The inner rasterizer, each fragment changed by `.1`.
struct Altered<R>(R, fn(&mut Fragment));

impl<R: Rasterizer> Rasterizer for Altered<R> {
    fn profile(&self) -> Profile {
        self.0.profile()
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = self.0.rasterize(draw)?;
        fragments.iter_mut().for_each(self.1);
        Ok(fragments)
    }
}

/// The inner rasterizer covering the sample of pixel `.1` once more than it does.
struct Doubling<R>(R, (u32, u32));

impl<R: Rasterizer> Rasterizer for Doubling<R> {
    fn profile(&self) -> Profile {
        self.0.profile()
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = self.0.rasterize(draw)?;
        if let Some(&f) = fragments.iter().find(|f| (f.x, f.y) == self.1) {
            fragments.push(Fragment {
                primitive: (f.primitive + 1) % draw.triangles().len() as u32,
                ..f
            });
        }
        Ok(fragments)
    }
}

/// A FragCoord shape whose depth test used the fragments' (centre) depth at every sample: wrong.
struct CentreTested(Shaped);

impl Rasterizer for CentreTested {
    fn profile(&self) -> Profile {
        self.0.profile()
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        self.0.rasterize(draw)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        Ok(Resolved::from_fragments(draw, self.0.rasterize(draw)?))
    }
}

/// The profile claimed by the shapes that stand for GPUs is Vulkan's; the scan converter claims
/// refrast's, with the new words.
#[test]
fn the_shapes_declare_what_they_do() {
    for r in shapes() {
        let p = r.profile();
        assert!(p.name.starts_with("shaped:"));
        if p.name == "shaped:scan-converter" {
            assert_eq!(p.spec, Spec::Refrast);
            assert!(!p.features.clips_in_3d);
            assert_eq!(p.features.snap, refrast::SnapAccuracy::TowardZero);
            assert_eq!(p.snapping, Snapping::Grid(6));
        } else {
            assert_eq!(p.spec, Spec::Vulkan);
        }
    }
}
