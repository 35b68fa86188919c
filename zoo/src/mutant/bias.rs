//! The bugs of depth bias: the reference drawing the bias with one term or step wrong.

use refrast::{DepthBias, Draw, DrawError, Fragment, Rasterizer, Reference, Resolved, Topology};

use super::Bug;

/// `draw` with its bias drawn wrong by `bug`: `None` when `bug` is no bias bug, or the draw
/// has no bias.
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    let bias = draw.state.depth_bias?;
    let mut reference = Reference::default();
    let with = |b: DepthBias| {
        let mut moved = draw.clone();
        moved.state.depth_bias = Some(b);
        moved
    };
    Some(match bug {
        // The slope factor's sign lost: the slope term pulls the wrong way.
        Bug::FlippedBiasSlope => reference.rasterize(&with(DepthBias {
            slope: -bias.slope,
            ..bias
        })),
        // The clamp never applied.
        Bug::IgnoredBiasClamp => reference.rasterize(&with(DepthBias { clamp: 0.0, ..bias })),
        // The depth test's copy of the depth unbiased: the fragments are right (`resolve` is not).
        Bug::FragmentOnlyBias => reference.rasterize(draw),
        Bug::MaxSlopeDeclaredExact | Bug::FixedBiasExponent => per_triangle(bug, draw, bias),
        _ => return None,
    })
}

/// Resolves `draw` with `bug`: under [`Bug::FragmentOnlyBias`] the depth test stores the
/// fragments' depths without their bias.
pub fn resolve(bug: Bug, draw: &Draw) -> Option<Result<Resolved, DrawError>> {
    if bug != Bug::FragmentOnlyBias {
        return None;
    }
    let mut plain = draw.clone();
    plain.state.depth_bias = None;
    Some(
        Reference::default()
            .rasterize(&plain)
            .map(|f| Resolved::from_fragments(draw, f)),
    )
}

/// Each triangle drawn alone with its bias's factors scaled as `bug` computes its terms: the
/// slope as `max(|∂z/∂x|, |∂z/∂y|)` where the profile says the exact length, or `r` as `2^-24`
/// whatever the triangle's depths (a 24-bit fixed-point r on an f32 buffer).
fn per_triangle(bug: Bug, draw: &Draw, bias: DepthBias) -> Result<Vec<Fragment>, DrawError> {
    let mut reference = Reference::default();
    let mut out = Vec::new();
    for i in 0..draw.primitive_count() {
        let Some(t) = draw.triangle(i) else { continue };
        let Some(corners) = window_corners(draw, t) else {
            continue;
        };
        let scaled = match bug {
            Bug::MaxSlopeDeclaredExact => {
                let (gx, gy) = gradient(corners);
                let length = gx.hypot(gy);
                let ratio = if length > 0.0 {
                    gx.abs().max(gy.abs()) / length
                } else {
                    1.0
                };
                DepthBias {
                    slope: (f64::from(bias.slope) * ratio) as f32,
                    ..bias
                }
            }
            _ => {
                let max_z = corners.iter().map(|c| (c[2] as f32).abs()).fold(0.0f32, f32::max);
                let right = 2f64.powi(refrast::bias::f32_exponent(max_z) - 23);
                DepthBias {
                    constant: (f64::from(bias.constant) * 2f64.powi(-24) / right) as f32,
                    ..bias
                }
            }
        };
        let mut alone = draw.clone();
        alone.topology = Topology::TriangleList;
        alone.indices = t.to_vec();
        alone.state.depth_bias = Some(scaled);
        out.extend(reference.rasterize(&alone)?.into_iter().map(|f| Fragment {
            primitive: i as u32,
            flat: draw.provoking(i),
            ..f
        }));
    }
    Ok(out)
}

/// The raster position and window depth of each corner of triangle `t`, unsnapped; `None`
/// when one is behind the eye.
fn window_corners(draw: &Draw, t: [u32; 3]) -> Option<[[f64; 3]; 3]> {
    let s = &draw.state;
    let mut out = [[0.0; 3]; 3];
    for (k, &i) in t.iter().enumerate() {
        let p = draw.positions.get(i as usize)?.map(f64::from);
        if p[3] <= 0.0 {
            return None;
        }
        let (x, y) = draw.viewport.to_raster(p[0] / p[3], p[1] / p[3]);
        out[k] = [
            x,
            y,
            s.viewport_depth.window(s.depth_range.window_depth(p[2], p[3])),
        ];
    }
    Some(out)
}

/// The depth gradient, per pixel, of the plane through three corners.
fn gradient([a, b, c]: [[f64; 3]; 3]) -> (f64, f64) {
    let (x1, y1, z1) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    let (x2, y2, z2) = (c[0] - a[0], c[1] - a[1], c[2] - a[2]);
    let det = x1 * y2 - y1 * x2;
    ((z1 * y2 - z2 * y1) / det, (z2 * x1 - z1 * x2) / det)
}
