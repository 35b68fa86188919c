//! False verdicts the drivers' lines and points showed in refrast's own rules, each now a named
//! regression test: the driver's fragments as they came back, and the rule passing them, beside
//! a nearby wrong answer the rule still fails.

use refrast::{
    Draw, DrawError, Fragment, LineRule, Profile, Rasterizer, Reference, Resolved, SamplePattern, Snapping,
    Spec, Topology,
};
use refrast_conformance::rules::{line, msaa, point};
use refrast_conformance::{PrimitiveScene, Scene};

/// Answers every draw with the fragments a driver returned, declaring the reference's profile
/// (8 bits, top-left) with llvmpipe's measured 7 bits of precision under `spec`, diamond-exit lines and points, and `points_on` for points.
struct Returned {
    spec: Spec,
    points_on: Option<Snapping>,
    fragments: Vec<Fragment>,
    /// The depth buffer per sample its resolve returns; `None` replays the fragments.
    depth_buffer: Option<Vec<f32>>,
}

impl Returned {
    /// `(x, y, depth, barycentric)` of primitive 0 at sample 0.
    fn new(spec: Spec, fragments: &[(u32, u32, f32, [f32; 3])]) -> Self {
        let fragments = fragments
            .iter()
            .map(|&(x, y, depth, barycentric)| Fragment {
                x,
                y,
                sample: 0,
                primitive: 0,
                depth,
                barycentric,
                screen_barycentric: None,
                front_facing: true,
                flat: None,
            })
            .collect();
        Self {
            spec,
            points_on: None,
            fragments,
            depth_buffer: None,
        }
    }
}

impl Rasterizer for Returned {
    fn profile(&self) -> Profile {
        Profile {
            name: "returned".into(),
            spec: self.spec,
            precision_bits: 7,
            lines: Some(LineRule::DiamondExit),
            points: true,
            point_snapping: self.points_on,
            multisample: SamplePattern::standard(4).into_iter().collect(),
            ..Reference::default().profile().triangles_only()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        // Triangles at one sample draw nothing here; every other draw returns the driver's.
        if draw.is_triangles_at_one_sample() {
            return Ok(Vec::new());
        }
        Ok(self.fragments.clone())
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let mut resolved = Resolved::from_fragments(draw, self.rasterize(draw)?);
        if let Some(depth) = &self.depth_buffer {
            resolved.depth.clone_from(depth);
        }
        Ok(resolved)
    }
}

/// One primitive of `topology` on a `width`×`height` target, far clipping on.
fn case(width: u32, height: u32, positions: Vec<[f32; 4]>, topology: Topology) -> PrimitiveScene {
    let indices = (0..positions.len() as u32).collect();
    let mut scene = Scene::new(width, height, positions, Vec::new());
    scene.state.clip_far = true;
    PrimitiveScene {
        scene,
        topology,
        indices,
        samples: 1,
    }
}

const BARY: [f32; 3] = [1.0, 0.0, 0.0];

/// llvmpipe: a segment 0.005 px long from a pixel corner, which the diamond-exit rule draws as
/// nothing, drawn as one fragment. OpenGL 4.6 §14.5.1 lets the count differ by one, and that
/// fragment then corresponds to none; two such fragments are still more than one apart.
#[test]
fn one_fragment_for_a_segment_the_rule_draws_as_none_is_within_the_allowance() {
    let tiny = case(
        16,
        16,
        vec![[-0.9375, 1.0, 0.0, 1.0], [-0.937_011_7, 0.999_511_7, 0.0, 1.0]],
        Topology::LineStrip,
    );
    let mut llvmpipe = Returned::new(Spec::OpenGl, &[(0, 0, 0.0, BARY)]);
    assert_eq!(line::check_diamond_allowance(&mut llvmpipe, &tiny).err(), None);
    let mut two = Returned::new(Spec::OpenGl, &[(0, 0, 0.0, BARY), (5, 5, 0.0, BARY)]);
    assert!(line::check_diamond_allowance(&mut two, &tiny).is_err());
}

/// A vertical segment exactly on the viewport's left edge: the diamond-exit rule draws column
/// −1, outside the target, and another algorithm may draw column 0 instead. A column two
/// pixels in is not within a pixel of the rule's.
#[test]
fn a_segment_on_the_viewports_edge_may_draw_the_column_inside() {
    let edge = case(
        16,
        16,
        vec![[-1.0, -0.84375, 0.0, 1.0], [-1.0, 1.0, 0.0, 1.0]],
        Topology::LineList,
    );
    let column = |x| (0..15).map(|y| (x, y, 0.0, BARY)).collect::<Vec<_>>();
    let mut inside = Returned::new(Spec::OpenGl, &column(0));
    assert_eq!(line::check_diamond_allowance(&mut inside, &edge).err(), None);
    let mut two_in = Returned::new(Spec::OpenGl, &column(2));
    assert!(line::check_diamond_allowance(&mut two_in, &edge).is_err());
}

/// llvmpipe: a pixel whose centre lies before a short segment's start gets the depth and
/// barycentrics of Vulkan's and OpenGL's formula, `t` unclamped (t ≈ −0.64 here), not the
/// start's. A depth above the segment's far end is still wrong.
#[test]
fn depth_and_barycentrics_beyond_an_end_may_extrapolate() {
    let short = case(
        16,
        16,
        vec![
            [0.122_363_284, 0.1875, 0.0, 0.2],
            [0.1375, 0.1875, 0.066_614_24, 0.2],
        ],
        Topology::LineList,
    );
    let mut llvmpipe = Returned::new(Spec::OpenGl, &[(12, 0, -0.217_033_62, [1.64, -0.64, 0.0])]);
    assert_eq!(line::check_depth_linear(&mut llvmpipe, &short).err(), None);
    assert_eq!(line::check_bary_perspective(&mut llvmpipe, &short).err(), None);
    let mut above = Returned::new(Spec::OpenGl, &[(12, 0, 0.5, [1.64, -0.64, 0.0])]);
    assert!(line::check_depth_linear(&mut above, &short).is_err());
}

/// llvmpipe: a perspective segment 0.13 px long, a pixel centre 1.9 of its lengths before its
/// start: t′ = (t/w_b) / ((1 − t)/w_a + t/w_b) is 3.65 there, past the pole a pixel's span of `t`
/// crosses, so no value is out of range.
#[test]
fn barycentrics_past_the_pole_of_an_extrapolated_segment_are_not_judged() {
    let steep = case(
        32,
        64,
        vec![
            [0.843_796_25, -1.555_820_3, 0.0, 1.861_168_3],
            [0.400_049_42, -0.741_287_05, 0.0, 0.882_392_2],
        ],
        Topology::LineList,
    );
    let mut llvmpipe = Returned::new(Spec::OpenGl, &[(23, 58, 0.0, [-2.649_228, 3.649_202, 0.0])]);
    assert_eq!(line::check_bary_perspective(&mut llvmpipe, &steep).err(), None);
}

/// softpipe snaps points to a quarter pixel (its triangles to no grid): a point 1/128 px below
/// a pixel edge lands on the edge, and covering the row above is a tie. Declared, the rule lets
/// it; undeclared, the same pixel fails.
#[test]
fn a_point_on_a_coarser_grid_than_the_triangles_may_land_on_a_pixel_edge() {
    let point = case(16, 16, vec![[-1.0, -0.250_976_56, 0.0, 1.0]], Topology::PointList);
    let mut softpipe = Returned::new(Spec::OpenGl, &[(0, 9, 0.0, BARY)]);
    softpipe.points_on = Some(Snapping::Grid(1));
    assert_eq!(point::check_pixel_holding(&mut softpipe, &point).err(), None);
    softpipe.points_on = None;
    assert!(point::check_pixel_holding(&mut softpipe, &point).is_err());
}

/// SwiftShader at 4 samples: `FragCoord.z` is one value for the pixel's four samples, which
/// Vulkan allows (it names no location for z), while its depth buffer holds each sample's depth
/// from the position mirrored in x, which it does not. A pixel under the plane 0.1 + 0.4·x: the
/// fragments alone fail only refrast's conventions; a depth buffer at the samples' own positions
/// passes, the mirrored one fails.
#[test]
fn per_sample_depth_is_required_of_the_depth_buffer_not_of_fragcoord_z() {
    let mut plane = case(
        1,
        1,
        vec![
            [-1.0, 1.0, 0.1, 1.0],
            [3.0, 1.0, 0.9, 1.0],
            [-1.0, -3.0, 0.1, 1.0],
        ],
        Topology::TriangleList,
    );
    plane.indices = Vec::new();
    plane.scene.triangles = vec![[0, 1, 2]];
    plane.samples = 4;
    let at = |x16: f32| 0.1 + 0.4 * x16 / 16.0;
    let mut swiftshader = Returned::new(Spec::Vulkan, &[]);
    swiftshader.fragments = (0..4)
        .map(|sample| Fragment {
            x: 0,
            y: 0,
            sample,
            primitive: 0,
            depth: at(10.0),
            barycentric: BARY,
            screen_barycentric: None,
            front_facing: true,
            flat: None,
        })
        .collect();
    swiftshader.depth_buffer = Some([6.0, 14.0, 2.0, 10.0].map(at).to_vec());
    assert!(msaa::check_depth(&mut swiftshader, &plane).is_err());
    assert_eq!(msaa::check_depth_resolved(&mut swiftshader, &plane).err(), None);
    swiftshader.depth_buffer = Some([10.0, 2.0, 14.0, 6.0].map(at).to_vec());
    assert!(msaa::check_depth_resolved(&mut swiftshader, &plane).is_err());
}

/// lavapipe and SwiftShader at 4 samples: a point just below the viewport covers sample 2 of
/// pixel (0, 31). Vulkan (`ALL_CLIP_PLANES`) discards such a point, so that is a failure there;
/// OpenGL 4.6 §13.7 lets the point be kept, and D3D11.3 draws it as a clipped quad, so under
/// either the sample may be covered. The same fragment two pixels away is wrong under all three.
#[test]
fn a_point_just_outside_the_viewport_may_be_drawn_under_opengl_and_d3d11() {
    let mut point = case(16, 32, vec![[-1.0, -1.000_732_4, 0.0, 1.0]], Topology::PointList);
    point.samples = 4;
    let returned = |spec: Spec, x: u32| {
        let mut r = Returned::new(spec, &[(x, 31, 0.0, BARY)]);
        r.fragments[0].sample = 2;
        r
    };
    assert!(point::check_pixel_holding(&mut returned(Spec::Vulkan, 0), &point).is_err());
    for spec in [Spec::OpenGl, Spec::D3d11] {
        assert_eq!(
            point::check_pixel_holding(&mut returned(spec, 0), &point).err(),
            None,
            "{spec:?}"
        );
        assert!(
            point::check_pixel_holding(&mut returned(spec, 2), &point).is_err(),
            "{spec:?}"
        );
    }
}

/// softpipe's "non-finite weights within 2³²" (adapters/wgpu/tests/drivers/findings.rs), re-read:
/// under 0 ≤ z ≤ w the 9×1 triangle is empty in exact arithmetic (two vertices behind the eye,
/// vertex 1 5.9·10⁻⁷ before the near plane). wgpu's OpenGL ES backend hands the driver z
/// rewritten to 2z − w in f32, which puts vertex 1 only 4.8·10⁻⁷ before it and leaves a sliver
/// whose clipped vertices have w from 10⁻⁴⁰ to 10⁻²⁷, far below 2⁻³²: nothing is required of
/// its values, so softpipe's NaN weights there are no failure.
#[test]
fn a_sliver_only_the_gl_rewrite_makes_requires_no_values() {
    use refrast_conformance::rules::robust;
    let scene = Scene::new(
        9,
        1,
        vec![
            [-1.175_494_4e-38, -3.996_676, 1.175_494_4e-38, -3.999_976_4],
            [-1.175_494_4e-38, 1.175_494_4e-38, -2.970_919e-7, 2.546_645_2],
            [-1.515_625, 22_237_420.0, 2.484_375, -0.576_177_6],
        ],
        vec![[0, 1, 2]],
    );
    let drawn = Reference::default().rasterize(&scene.draw()).expect("draws");
    assert!(drawn.is_empty(), "empty in exact arithmetic: {drawn:?}");
    assert!(
        robust::within_float_range(&scene),
        "the draw as sent stays within 2³²"
    );
    let mut received = Reference::default().profile();
    received.features.z_rewritten_in_f32 = true;
    assert!(
        !robust::within_float_range_as_received(&scene, &received),
        "as the driver receives it, a sliver at w < 2⁻³²"
    );
    let mut softpipe = Sliver(received);
    robust::check_sane_where_defined(&mut softpipe, &scene).expect("NaN weights on that sliver");
    softpipe.0.features.z_rewritten_in_f32 = false;
    assert!(
        robust::check_sane_where_defined(&mut softpipe, &scene).is_err(),
        "without the rewrite, a fragment of an empty triangle must still be well formed"
    );
}

/// Draws the sample on vertex 1 of the 9×1 sliver with softpipe's (NaN, ∞, ∞) weights.
struct Sliver(Profile);

impl Rasterizer for Sliver {
    fn profile(&self) -> Profile {
        self.0.clone()
    }

    fn rasterize(&mut self, _: &Draw) -> Result<Vec<Fragment>, DrawError> {
        Ok(vec![Fragment {
            x: 4,
            y: 0,
            sample: 0,
            primitive: 0,
            depth: 0.0,
            barycentric: [f32::NAN, f32::INFINITY, f32::INFINITY],
            screen_barycentric: Some([f32::NAN; 3]),
            front_facing: true,
            flat: None,
        }])
    }
}

/// softpipe's "flat triangle, weights summing to 0", re-read: on 32×32 the triangle projects
/// to y = 4.5000004…4.5000005 (1.2·10⁻⁸ px² across 2.3 px, which its 7 claimed bits cannot
/// resolve), and the sample of (24, 4), 4·10⁻⁷ px outside it, within the band where coverage is
/// not judged, is drawn weighted (0, 0, 0) in one vertex order and otherwise in another. Weights
/// computed at a precision ε may be off by ε · extent² / area, here far more than their whole
/// range, which no specification bounds: `meta.rotation.same-coverage` and
/// `meta.reversal.flips-facing` compare weights only of triangles the claimed precision resolves.
#[test]
fn weights_in_the_band_of_a_sliver_are_not_compared() {
    use refrast_conformance::rules::meta;
    let scene = Scene::new(
        32,
        32,
        vec![
            [0.053125, 0.071875, 0.0, 0.1],
            [1.355_272_4, 2.509_384_9, 0.0, 3.491_318_2],
            [0.050_903_32, 0.071875, 0.0, 0.1],
        ],
        vec![[0, 1, 2]],
    );
    let mut softpipe = Flat;
    meta::check_rotation(&mut softpipe, &scene).expect("weights in the band are not compared");
}

/// softpipe's flat triangle: the sample of (24, 4), weighted (0, 0, 0) when vertex 0 comes
/// first, (1/3, 1/3, 1/3) otherwise; softpipe's profile (no grid, no tie rule, 1/256 px band).
struct Flat;

impl Rasterizer for Flat {
    fn profile(&self) -> Profile {
        Profile {
            name: "softpipe-like".into(),
            snapping: Snapping::Float,
            fill: None,
            precision_bits: 7,
            ..Reference::default().profile()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let first = draw.triangles().first().map_or(0, |t| t[0]);
        let weight = if first == 0 { 0.0 } else { 1.0 / 3.0 };
        Ok(vec![Fragment {
            x: 24,
            y: 4,
            sample: 0,
            primitive: 0,
            depth: 0.0,
            barycentric: [weight; 3],
            screen_barycentric: Some([weight; 3]),
            front_facing: true,
            flat: None,
        }])
    }
}
