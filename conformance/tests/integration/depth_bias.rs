//! Depth bias judged on implementations unlike the reference: one computing the bias its own
//! correct way (the max slope measure from unsnapped vertices, added to each fragment in f32)
//! must pass under every specification; one clamping the biased depth to `[0, 1]` rather than
//! to the viewport's range (as OpenGL requires and lavapipe does) is beyond Vulkan and OpenGL
//! but fails refrast's conventions and D3D11.3; one taking r one binade low (SwiftShader's class)
//! fails them all.

use refrast::DepthBias;
use refrast::{
    BiasSupport, DepthFormat, DepthSlope, Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Spec,
    StateSupport,
};
use refrast_conformance::rules::bias;
use refrast_conformance::{Options, RuleReport, Scene, Status, certify};

/// How the wrapper biases depth.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Way {
    /// `m = max(|∂z/∂x|, |∂z/∂y|)` (declared), `r = 2^(e − 23)`, clamped to the range.
    Max,
    /// The same, clamped to `[0, 1]` instead of the viewport's range unless depth clamping is
    /// on (as lavapipe does).
    ClampsToUnit,
    /// `r = 2^(e − 24)`: half the resolvable difference.
    HalfR,
    /// [`Way::Max`] from window depths computed in f32 as wgpu's OpenGL ES backend and an
    /// OpenGL driver compute them: `z` rewritten to `2z − w` (under `0 ≤ z ≤ w`), divided by `w`, then
    /// `(f − n)/2·z_ndc + (f + n)/2`. On a triangle at depth 2^-12 that rounds at the size of
    /// 1, not of its depths (llvmpipe's case).
    GlF32,
}

/// The reference drawing unbiased, then biasing each fragment itself.
struct Biased {
    spec: Spec,
    way: Way,
    inner: Reference,
}

impl Biased {
    /// Its own offset for triangle `t` of `draw`, from the unsnapped projected corners.
    fn offset(&self, draw: &Draw, t: [u32; 3]) -> f64 {
        let Some(bias) = draw.state.depth_bias else {
            return 0.0;
        };
        let s = &draw.state;
        let corner = |i: u32| {
            let v = draw.positions[i as usize];
            let p = v.map(f64::from);
            let (x, y) = draw.viewport.to_raster(p[0] / p[3], p[1] / p[3]);
            let z = if self.way == Way::GlF32 {
                let (n, f) = (s.viewport_depth.min, s.viewport_depth.max);
                // wgpu rewrites Vulkan's `0 ≤ z ≤ w` to OpenGL's `−w ≤ z ≤ w`.
                let z = match s.depth_range {
                    refrast::DepthRange::ZeroToOne => 2.0 * v[2] - v[3],
                    refrast::DepthRange::NegativeOneToOne => v[2],
                };
                let ndc = z / v[3];
                f64::from((f - n) / 2.0 * ndc + (f + n) / 2.0)
            } else {
                s.viewport_depth.window(s.depth_range.window_depth(p[2], p[3]))
            };
            [x, y, z]
        };
        let [a, b, c] = t.map(corner);
        let (x1, y1, z1) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
        let (x2, y2, z2) = (c[0] - a[0], c[1] - a[1], c[2] - a[2]);
        let det = x1 * y2 - y1 * x2;
        let (gx, gy) = ((z1 * y2 - z2 * y1) / det, (z2 * x1 - z1 * x2) / det);
        let m = gx.abs().max(gy.abs());
        let largest = [a[2], b[2], c[2]]
            .map(|z| (z as f32).abs())
            .into_iter()
            .fold(0.0f32, f32::max);
        // Depth 0 takes the smallest normal exponent, as subnormals do.
        let e = if largest < f32::MIN_POSITIVE {
            -126
        } else {
            f64::from(largest).log2().floor() as i32
        };
        let n = if self.way == Way::HalfR { 24 } else { 23 };
        let o = m * f64::from(bias.slope) + 2f64.powi(e - n) * f64::from(bias.constant);
        let k = f64::from(bias.clamp);
        if k > 0.0 {
            o.min(k)
        } else if k < 0.0 {
            o.max(k)
        } else {
            o
        }
    }
}

impl Rasterizer for Biased {
    fn profile(&self) -> Profile {
        let reference = self.inner.profile();
        Profile {
            name: "biased".into(),
            spec: self.spec,
            state: StateSupport {
                depth_bias: Some(BiasSupport {
                    format: DepthFormat::Float32,
                    slope: DepthSlope::Max,
                    clamp: true,
                }),
                ..reference.state
            },
            ..reference
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut plain = draw.clone();
        plain.state.depth_bias = None;
        let mut fragments = self.inner.rasterize(&plain)?;
        let range = draw.state.viewport_depth;
        let (lo, hi) = match self.way {
            Way::ClampsToUnit if draw.state.clip_near => (0.0, 1.0),
            _ => (range.min.min(range.max), range.min.max(range.max)),
        };
        for f in &mut fragments {
            let Some(t) = draw.triangle(f.primitive as usize) else {
                continue;
            };
            f.depth = (f.depth + self.offset(draw, t) as f32).clamp(lo, hi);
        }
        Ok(fragments)
    }
}

/// The two bias rules' reports on the wrapper biasing `way` and claiming `spec`.
fn run(spec: Spec, way: Way) -> Vec<RuleReport> {
    let mut r = Biased {
        spec,
        way,
        inner: Reference::default(),
    };
    let options = Options {
        cases: Some(300),
        rules: vec!["depth.bias.offset".to_owned(), "depth.bias.clamp".to_owned()],
        ..Options::default()
    };
    certify(&mut r, &options, |_| {}).rules
}

/// The max measure, the bias added to each fragment's f32 depth after interpolation, from
/// exact depths or from OpenGL's f32 ones: right under every specification, refrast's
/// conventions included.
#[test]
fn a_correct_bias_computed_another_way_passes_everywhere() {
    for way in [Way::Max, Way::GlF32] {
        for spec in Spec::ALL {
            for report in run(spec, way) {
                assert_eq!(report.status, Status::Pass, "{way:?}, {spec:?}: {report:#?}");
            }
        }
    }
}

/// Regression (llvmpipe through OpenGL ES, once its slope measure was probed): a triangle at
/// depth 2^-12.4 whose f32 window depths round at the size of 1, so its slope comes out 0.1 %
/// off the exact plane's; the oracle first bounded that rounding by the depths' own size.
#[test]
fn f32_depths_of_a_shallow_plane_pass() {
    let mut scene = Scene::new(
        64,
        32,
        vec![
            [0.200_499_07, 0.0, 4.864_864e-5, 0.25],
            [0.0, 0.212_513_74, 4.490_044e-5, 0.25],
            [-0.023_486_024, 0.0, 4.682_403_2e-5, 0.25],
        ],
        vec![[0, 1, 2]],
    );
    scene.state.clip_near = false;
    scene.state.depth_bias = Some(DepthBias {
        constant: 0.0,
        slope: 1.0,
        clamp: 0.0,
    });
    let mut r = Biased {
        spec: Spec::OpenGlEs,
        way: Way::GlF32,
        inner: Reference::default(),
    };
    let judged = bias::check_bias_under(&mut r, &scene, Spec::OpenGlEs);
    assert!(judged.is_ok(), "{judged:?}");
}

/// A biased depth clamped to `[0, 1]` rather than to a narrower viewport range: what OpenGL
/// requires and Vulkan leaves undefined (so beyond both, never a failure of them), what
/// refrast's conventions and D3D11.3 (which clamp to the range) fail.
#[test]
fn clamping_to_zero_one_is_beyond_vulkan_and_opengl_only() {
    for spec in [Spec::Vulkan, Spec::OpenGl, Spec::OpenGlEs] {
        let offset = &run(spec, Way::ClampsToUnit)[0];
        assert_eq!(offset.status, Status::BeyondSpec, "{spec:?}: {offset:#?}");
    }
    for spec in [Spec::Refrast, Spec::D3d11] {
        let offset = &run(spec, Way::ClampsToUnit)[0];
        assert_eq!(offset.status, Status::Fail, "{spec:?}: {offset:#?}");
    }
}

/// r one binade low fails every specification: f32's r is `2^(e − 23)` in all of them.
#[test]
fn half_the_resolvable_difference_fails_every_specification() {
    for spec in Spec::ALL {
        let offset = &run(spec, Way::HalfR)[0];
        assert_eq!(offset.status, Status::Fail, "{spec:?}: {offset:#?}");
        let message = offset.message.clone().unwrap_or_default();
        assert!(message.contains("r in ["), "{message}");
    }
}
