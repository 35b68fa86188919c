//! Values along a line: depth linear in screen space and perspective-correct barycentrics, at
//! each sample's projection on the segment's line.

use refrast::{Fragment, Rasterizer};

use super::super::common::precision;
use super::super::samples::{positions, sample_fragments};
use super::{Declared, declared, snapped_ends};
use crate::oracle::raster::{clamp_depth, window_depth};
use crate::scene::PrimitiveScene;
use crate::violation::{Findings, Violation, plural};

/// For each fragment of segment 0: where on the snapped segment's line its sample projects
/// (`t`, below 0 or above 1 for a sample beyond an end), and the span of `t` a pixel makes (so a
/// rule evaluating at another point of the pixel, such as the labs' DDA, is not failed).
fn along(case: &PrimitiveScene, d: &Declared, positions: &[[u8; 2]], f: &Fragment) -> Option<(f64, f64)> {
    let [a, b] = snapped_ends(case, 0, d)?;
    let one = f64::from(1u32 << d.bits);
    let (ax, ay, dx, dy) = (
        a.0 as f64 / one,
        a.1 as f64 / one,
        (b.0 - a.0) as f64 / one,
        (b.1 - a.1) as f64 / one,
    );
    let length2 = dx * dx + dy * dy;
    if length2 == 0.0 {
        return None;
    }
    let [u, v] = positions.get(usize::from(f.sample)).copied().unwrap_or([8, 8]);
    let s = [
        f64::from(f.x) + f64::from(u) / 16.0,
        f64::from(f.y) + f64::from(v) / 16.0,
    ];
    let t = ((s[0] - ax) * dx + (s[1] - ay) * dy) / length2;
    // A pixel spans 1/length of t, however short the segment: extrapolated, t can be anything.
    Some((t, 1.0 / length2.sqrt()))
}

/// The range `value` takes over `t ± span`, `t` taken as it is and clamped to `[0, 1]`: Vulkan's
/// and OpenGL's formula, `t = (p_r − p_a)·(p_b − p_a) / ‖p_b − p_a‖²`, does not clamp, so a
/// fragment whose sample lies beyond an end may extrapolate (llvmpipe and SwiftShader do) or
/// hold the end's value (the reference does).
fn either_side(t: f64, span: f64, value: impl Fn(f64) -> f64) -> (f64, f64) {
    let all = [t - span, t + span]
        .into_iter()
        .flat_map(|t| [value(t), value(t.clamp(0.0, 1.0))]);
    all.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Depth is the ends' window depths linear in `t`, within a pixel's span of `t` and the precision.
pub fn check_depth_linear(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some(d) = declared(r) else { return Ok(()) };
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let Some(ends) = case.segment(0) else {
        return Ok(());
    };
    let [za, zb] = ends.map(|p| window_depth(&case.scene.state, f64::from(p[2]) / f64::from(p[3])));
    let p = precision(&d.profile);
    let mut found = Findings::new();
    for f in &frags {
        let Some((t, span)) = along(case, &d, &positions, f) else {
            continue;
        };
        // Clamping is monotone: the clamped values lie between the clamped bounds. With depth
        // clipping off the clamp is required; with it on, a value outside the range is
        // undefined (Depth Clamping and Range Adjustment), so the extrapolated one stands too.
        let (lo, hi) = either_side(t, span, |t| za + (zb - za) * t);
        let state = &case.scene.state;
        let (lo, hi) = if state.clip_near {
            (lo.min(clamp_depth(state, lo)), hi.max(clamp_depth(state, hi)))
        } else {
            (clamp_depth(state, lo), clamp_depth(state, hi))
        };
        let z = f64::from(f.depth);
        if z < lo - 2.0 * p || z > hi + 2.0 * p {
            found.add((f.x, f.y), || {
                format!(
                    "({}, {}) sample {}: depth {z}, expected {lo}..={hi} (t = {t:.4} between depths {za} and {zb})",
                    f.x, f.y, f.sample
                )
            });
        }
    }
    found.verdict(|n| format!("depth is not linear along the line at {}", plural(n, "fragment")))
}

/// Barycentrics are `(1 − t′, t′, 0)`, `t′` perspective-correct, within a pixel's span and the precision.
pub fn check_bary_perspective(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some(d) = declared(r) else { return Ok(()) };
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let Some([pa, pb]) = case.segment(0) else {
        return Ok(());
    };
    let (wa, wb) = (f64::from(pa[3]), f64::from(pb[3]));
    let denominator = |t: f64| (1.0 - t) / wa + t / wb;
    let correct = |t: f64| (t / wb) / denominator(t);
    let p = precision(&d.profile);
    let mut found = Findings::new();
    for f in &frags {
        let Some((t, span)) = along(case, &d, &positions, f) else {
            continue;
        };
        let [b0, b1, b2] = f.barycentric.map(f64::from);
        // Extrapolated far enough beyond an end, t′ passes a pole (1/w reaches 0 on the line):
        // no value is then out of range.
        let (lo, hi) = if denominator(t - span) * denominator(t + span) <= 0.0 {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            either_side(t, span, correct)
        };
        if b1 < lo - p || b1 > hi + p || b2.abs() > p || (b0 + b1 - 1.0).abs() > 3.0 * p {
            found.add((f.x, f.y), || {
                format!(
                    "({}, {}) sample {}: barycentrics {:?}, expected (1 − t′, t′, 0) with t′ in {lo}..={hi}",
                    f.x, f.y, f.sample, f.barycentric
                )
            });
        }
    }
    found.verdict(|n| format!("barycentrics along the line are off at {}", plural(n, "fragment")))
}
