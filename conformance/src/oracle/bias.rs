//! Depth bias: the interval a triangle's offset `o = dbclamp(m·slope + r·constant)` may take
//! under a specification, from the exact plane of its unsnapped vertices, with a bound on how
//! far snapping and f32 move `m`, written apart from the reference's `bias.rs`.
//!
//! The specifications leave three things open, and the interval holds each within its bound:
//! - **m**: Vulkan and OpenGL define `√((∂z/∂x)² + (∂z/∂y)²)` and allow `max(|∂z/∂x|, |∂z/∂y|)`
//!   (D3D11.3 defines the max): the profile declares which ([`DepthSlope`]). An implementation
//!   measures it on its snapped vertices, a grid step from the exact ones, with depths rounded
//!   to f32: the interval widens by the most that moves it ([`slope_error`]).
//! - **r**: for f32 depth `2^(e − 23)`, `e` the exponent of the triangle's largest depth (which
//!   f32 rounding of a depth just under a power of two may raise); for `n`-bit fixed point
//!   `2^-n` under refrast, `1/(2^n − 1)` under D3D11.3, up to `2 × 2^-n` under Vulkan, and
//!   anything resolvable (`≥ 2^-n`) under OpenGL, which bounds it no further.
//! - **rounding**: the implementation computes `o` in f32 and adds it to a depth it evaluates
//!   in f32, per fragment or per vertex: [`OffsetBounds::slack`].

use refrast::{BiasSupport, DepthFormat, DepthSlope, DrawState, Spec};

use super::raster::{depth_bounds, project, window_depth};

/// Relative error of a few f32 operations: four ulps (`2^-21`), for a value an implementation
/// computes in f32 through a handful of roundings (a product and a sum, or a plane's three
/// terms).
const F32_FEW_ULPS: f64 = 1.0 / (1u64 << 21) as f64;

/// How far an implementation's f32 window depth of a vertex may be from exact: a few ulps of
/// the largest value its viewport transform meets, at least 1 (`p_z·z_d + o_z` with `|o_z|`,
/// `|p_z|` up to 1; OpenGL's `(z_d + 1)/2`, and wgpu's rewrite of `z` to `2z − w`, round at
/// that size whatever the depth): on a triangle at depth 2^-12 that is far more than an ulp of
/// its depths.
fn depth_rounding(max_z: f64) -> f64 {
    F32_FEW_ULPS * max_z.max(1.0)
}

/// The worst relative change of the slope a triangle may be judged with: past it, snapping
/// could move `m` by more than a sixteenth, too ill-conditioned (a sliver) to tell a wrong
/// measure from rounding.
const MAX_SLOPE_ERROR: f64 = 1.0 / 16.0;

/// What the oracle allows a triangle's depth bias.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffsetBounds {
    /// The least offset `o`.
    pub lo: f64,
    /// The greatest offset `o`.
    pub hi: f64,
    /// How far a biased depth may stray from the unbiased depth plus `o` by f32 rounding: the
    /// bias and the depth each computed in f32, added per fragment or per vertex (a plane whose
    /// terms reach `m·(W + H)` rounds at that size), and subnormal results flushed to zero.
    pub slack: f64,
    /// The depth slope `m` allowed, least and greatest.
    pub slope: [f64; 2],
    /// The resolvable difference `r` allowed, least and greatest.
    pub resolvable: [f64; 2],
}

/// The offsets a triangle with clip-space corners `p` may be biased by under `spec` (refrast's
/// own: the declared measure and format exactly), in a `width`×`height` viewport with `state`,
/// for an implementation declaring `support` that snaps within `grid_step` pixels. `None` when
/// the triangle has a corner at `w ≤ 0`, or is too thin to judge ([`MAX_SLOPE_ERROR`]).
#[must_use]
pub fn offset_bounds(
    p: &[[f32; 4]; 3],
    (width, height): (u32, u32),
    state: &DrawState,
    support: BiasSupport,
    grid_step: f64,
    spec: Spec,
) -> Option<OffsetBounds> {
    let bias = state.depth_bias?;
    if p.iter().any(|v| v[3] <= 0.0) {
        return None;
    }
    let corner = |v: &[f32; 4]| {
        let c = v.map(f64::from);
        let [x, y] = project(width, height, c);
        (x, y, window_depth(state, c[2] / c[3]))
    };
    let [a, b, c] = [corner(&p[0]), corner(&p[1]), corner(&p[2])];
    let (d1, d2) = ((b.0 - a.0, b.1 - a.1), (c.0 - a.0, c.1 - a.1));
    let (dz1, dz2) = (b.2 - a.2, c.2 - a.2);
    let det = d1.0 * d2.1 - d1.1 * d2.0;
    let gx = (dz1 * d2.1 - dz2 * d1.1) / det;
    let gy = (dz2 * d1.0 - dz1 * d2.0) / det;
    let max_z = a.2.abs().max(b.2.abs()).max(c.2.abs());
    let frobenius = (d1.0 * d1.0 + d1.1 * d1.1 + d2.0 * d2.0 + d2.1 * d2.1).sqrt();
    // A fixed-point buffer stores each depth to its own step: an implementation measuring the
    // slope on stored depths, or reporting them, is off by up to one step a value.
    let stored = support.format.unorm_bits().map_or(0.0, |n| 2f64.powi(-n));
    let error = slope_error(det.abs(), frobenius, grid_step, gx.hypot(gy), max_z, stored)?;
    let slope = slope_interval(support.slope, gx, gy, error);
    let resolvable = resolvable_interval(support.format, spec, max_z);
    let (s, k) = (f64::from(bias.slope), f64::from(bias.constant));
    let corners = [
        slope[0] * s + resolvable[0] * k,
        slope[0] * s + resolvable[1] * k,
        slope[1] * s + resolvable[0] * k,
        slope[1] * s + resolvable[1] * k,
    ];
    let finite = |v: &f64| v.is_finite();
    let (lo, hi) = (
        corners
            .iter()
            .copied()
            .filter(finite)
            .fold(f64::INFINITY, f64::min),
        corners
            .iter()
            .copied()
            .filter(finite)
            .fold(f64::NEG_INFINITY, f64::max),
    );
    // An unbounded r (OpenGL's fixed point) leaves the constant's side open.
    let (lo, hi) = match (resolvable[1].is_finite(), k.total_cmp(&0.0)) {
        (false, std::cmp::Ordering::Greater) => (lo, f64::INFINITY),
        (false, std::cmp::Ordering::Less) => (f64::NEG_INFINITY, hi),
        _ => (lo, hi),
    };
    // The implementation's f32 products and sum.
    let rounding = F32_FEW_ULPS * (s.abs() * slope[1] + k.abs() * resolvable[1].min(1.0));
    let clamp = |o: f64| dbclamp(f64::from(bias.clamp), o);
    let (lo, hi) = (clamp(lo - rounding), clamp(hi + rounding));
    let reach = f64::from(width) + f64::from(height);
    let largest = max_z + lo.abs().min(1.0).max(hi.abs().min(1.0));
    Some(OffsetBounds {
        lo,
        hi,
        // Results below f32's smallest normal may be flushed to zero, as above; a fixed-point
        // buffer's two stored depths each round to its step.
        slack: F32_FEW_ULPS * (largest + slope[1] * reach) + f64::from(f32::MIN_POSITIVE) + stored,
        slope,
        resolvable,
    })
}

/// The most the measured slope's gradient may differ from the exact one's, or `None` past
/// [`MAX_SLOPE_ERROR`] of it: vertices moved up to `step` px per axis change the two edges
/// `M` (rows `v₁ − v₀`, `v₂ − v₀`) by `E` with `‖E‖ ≤ 4·step`, and depths rounded to f32
/// ([`depth_rounding`]), or stored to a fixed-point step (`stored`), change the depth differences; the gradient solves `M'g' = Mg + Δz`,
/// so `‖g' − g‖ ≤ ‖M'⁻¹‖·(‖E‖·‖g‖ + ‖Δz‖)` with `‖M'⁻¹‖ ≤ ‖M'‖_F / |det M'|`, and
/// `|det M'| ≥ |det M| − ‖M‖_F·‖E‖ − ‖E‖²/2`.
fn slope_error(det: f64, frobenius: f64, step: f64, gradient: f64, max_z: f64, stored: f64) -> Option<f64> {
    let e = 4.0 * step;
    let det_least = det - frobenius * e - e * e / 2.0;
    if det_least <= 0.0 || !det_least.is_finite() {
        return None;
    }
    let inverse = (frobenius + e) / det_least;
    if inverse * e > MAX_SLOPE_ERROR {
        return None;
    }
    let depth_error = 2.0 * std::f64::consts::SQRT_2 * (depth_rounding(max_z) + stored);
    Some(inverse * (e * gradient + depth_error))
}

/// `m` as `measure` takes it of the gradient `(gx, gy)`, widened by `error` each way (a change
/// of the gradient by `error` moves its length and its largest component by no more).
fn slope_interval(measure: DepthSlope, gx: f64, gy: f64, error: f64) -> [f64; 2] {
    let (length, largest) = ((gx * gx + gy * gy).sqrt(), gx.abs().max(gy.abs()));
    let [lo, hi] = match measure {
        DepthSlope::Exact => [length, length],
        DepthSlope::Max => [largest, largest],
        DepthSlope::Either => [largest, length],
    };
    [(lo - error).max(0.0), hi + error]
}

/// The `r` allowed for `format` under `spec` with the triangle's largest depth magnitude
/// `max_z` (exact, before the implementation rounds it: [`depth_rounding`]).
fn resolvable_interval(format: DepthFormat, spec: Spec, max_z: f64) -> [f64; 2] {
    let Some(n) = format.unorm_bits() else {
        // The implementation's rounding of the largest depth may carry it across 2^e; r from
        // either exponent.
        let exponent = |z: f64| {
            let z = z as f32;
            if z < f32::MIN_POSITIVE {
                -126
            } else {
                f64::from(z).log2().floor() as i32
            }
        };
        let (low, high) = (
            exponent(max_z - depth_rounding(max_z)),
            exponent(max_z + depth_rounding(max_z)),
        );
        // An r below f32's normal range may be flushed to zero (Vulkan, Floating-Point
        // Computation: denormalized values "may be flushed to zero"; Mesa takes r = 0 there).
        let r = |e: i32| 2f64.powi(e - 23);
        let least = if low - 23 < -126 { 0.0 } else { r(low) };
        return [least, r(high)];
    };
    let step = 2f64.powi(-n);
    match spec {
        Spec::Refrast => [step, step],
        // "the minimum representable value > 0 in the depth buffer format" (§15.10).
        Spec::D3d11 => {
            let unit = 1.0 / (2f64.powi(n) - 1.0);
            [unit, unit]
        }
        // "at most r = 2 × 2^-n", and at least what keeps two depths r apart distinct.
        Spec::Vulkan => [step, 2.0 * step / (1.0 - step)],
        Spec::OpenGl | Spec::OpenGlEs => [step, f64::INFINITY],
    }
}

/// Vulkan's `dbclamp` with clamp `k`: at most `k` when positive, at least when negative.
fn dbclamp(k: f64, o: f64) -> f64 {
    if k > 0.0 {
        o.min(k)
    } else if k < 0.0 {
        o.max(k)
    } else {
        o
    }
}

/// Where `spec` requires a biased depth clamped to, as refrast clamps it: to `[z_min, z_max]`
/// of the viewport under refrast and D3D11.3 (§15.6: "the z value is always clamped"), and
/// everywhere with depth clamping on. `None` where the specification requires no such clamp,
/// so that only depths inside the range are judged: Vulkan without depth clamping leaves a depth
/// outside it undefined; OpenGL and OpenGL ES clamp to `[0, 1]` ("clamped even when the depth
/// buffer uses a floating-point representation", §14.6.5), which is the range's clamp only
/// when the range is `[0, 1]` (outside a narrower range OpenGL keeps what refrast clamps).
#[must_use]
pub fn biased_depth_clamp(spec: Spec, state: &DrawState) -> Option<[f64; 2]> {
    let range = depth_bounds(state);
    if !state.clip_near {
        return Some(range);
    }
    match spec {
        Spec::Refrast | Spec::D3d11 => Some(range),
        Spec::OpenGl | Spec::OpenGlEs => (range == [0.0, 1.0]).then_some(range),
        Spec::Vulkan => None,
    }
}

#[cfg(test)]
mod tests {
    use refrast::{DepthBias, DrawState};

    use super::*;

    /// A right triangle on a 64×64 viewport: depth 0.25 at the top left, rising by 1/128 a
    /// pixel to the right and 1/256 a pixel down.
    fn ramp() -> [[f32; 4]; 3] {
        // x_f = (x + 1)·32, y_f = (1 − y)·32: corners at (0, 0), (32, 0), (0, 32) px.
        [
            [-1.0, 1.0, 0.25, 1.0],
            [0.0, 1.0, 0.5, 1.0],
            [-1.0, 0.0, 0.375, 1.0],
        ]
    }

    fn biased(constant: f32, slope: f32, clamp: f32) -> DrawState {
        DrawState {
            depth_bias: Some(DepthBias {
                constant,
                slope,
                clamp,
            }),
            ..DrawState::default()
        }
    }

    const EXACT: BiasSupport = BiasSupport {
        format: DepthFormat::Float32,
        slope: DepthSlope::Exact,
        clamp: true,
    };

    /// The slope term is `m·slope` with the declared measure, within the snapping bound; the
    /// constant term `r·constant` with r one ulp of the largest depth (0.5: 2^-23).
    #[test]
    fn the_interval_holds_the_declared_measure_and_r() {
        let state = biased(0.0, 2.0, 0.0);
        let step = 1.0 / 256.0;
        let b = offset_bounds(&ramp(), (64, 64), &state, EXACT, step, Spec::Refrast).expect("wide");
        let exact = 2.0 * (1.0f64 / 128.0).hypot(1.0 / 256.0);
        assert!(
            b.lo <= exact && exact <= b.hi && b.hi - b.lo < 0.01 * exact,
            "{b:?}"
        );
        let max = BiasSupport {
            slope: DepthSlope::Max,
            ..EXACT
        };
        let m = offset_bounds(&ramp(), (64, 64), &state, max, step, Spec::Refrast).expect("wide");
        assert!(
            m.hi < b.lo,
            "the max measure is below the exact one here: {m:?} {b:?}"
        );
        let constant = biased(1000.0, 0.0, 0.0);
        let c = offset_bounds(&ramp(), (64, 64), &constant, EXACT, step, Spec::Vulkan).expect("wide");
        assert_eq!(
            c.resolvable,
            [2f64.powi(-25), 2f64.powi(-24)],
            "0.5 may round below its binade"
        );
        let clamped = biased(1000.0, 0.0, 1e-5);
        let k = offset_bounds(&ramp(), (64, 64), &clamped, EXACT, step, Spec::Refrast).expect("wide");
        let clamp = f64::from(1e-5f32);
        assert!(k.hi == clamp && k.lo == clamp, "{k:?}");
    }

    /// A sliver is not judged; fixed-point r follows each specification.
    #[test]
    fn slivers_are_unjudged_and_fixed_point_r_follows_the_spec() {
        let sliver = [
            [-1.0, 1.0, 0.25, 1.0],
            [1.0, 1.0, 0.5, 1.0],
            [0.0, 0.999, 0.3, 1.0],
        ];
        let state = biased(1.0, 1.0, 0.0);
        assert!(offset_bounds(&sliver, (64, 64), &state, EXACT, 1.0 / 256.0, Spec::Refrast).is_none());
        let n = 2f64.powi(-16);
        assert_eq!(
            resolvable_interval(DepthFormat::Unorm16, Spec::Refrast, 0.5),
            [n, n]
        );
        assert!(resolvable_interval(DepthFormat::Unorm16, Spec::Vulkan, 0.5)[1] > 2.0 * n);
        assert_eq!(
            resolvable_interval(DepthFormat::Unorm16, Spec::OpenGl, 0.5)[1],
            f64::INFINITY
        );
        assert_eq!(biased_depth_clamp(Spec::Vulkan, &state), None);
        assert_eq!(biased_depth_clamp(Spec::OpenGlEs, &state), Some([0.0, 1.0]));
        let narrow = DrawState {
            viewport_depth: refrast::ViewportDepth { min: 0.5, max: 1.0 },
            ..state
        };
        assert_eq!(biased_depth_clamp(Spec::OpenGl, &narrow), None);
        assert_eq!(biased_depth_clamp(Spec::D3d11, &narrow), Some([0.5, 1.0]));
    }
}
