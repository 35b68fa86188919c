//! A line crossing the near plane: the visible part drawn, exactly under refrast's conventions
//! or within Vulkan's allowance for other line algorithms.

use refrast::{Fragment, Rasterizer};

use super::*;

/// The segment from its front end to where it crosses the near plane, against the oracle of
/// that visible part; samples the cut's rounding could change are not judged.
pub fn check_clip(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some((frags, expected, _)) = clip_expectations(r, case)? else {
        return Ok(());
    };
    compare_samples(
        case,
        &counts(case, &frags, Some(0)),
        &expected,
        "the visible part's oracle",
    )
}

/// [`check_clip`] under Vulkan's allowance for other line algorithms (diamond-exit lines only;
/// the area rules are judged whole): every fragment within a pixel of the visible part's, and
/// every pixel of the visible part 2 px from the cut within a pixel of a fragment.
pub fn check_clip_allowance(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    if r.profile().lines != Some(LineRule::DiamondExit) {
        return check_clip(r, case);
    }
    let Some((frags, expected, cut)) = clip_expectations(r, case)? else {
        return Ok(());
    };
    let w = case.scene.width;
    let at = |i: usize| (i as u32 % w, i as u32 / w);
    let near = |(x, y): (u32, u32), set: &[(u32, u32)]| {
        set.iter().any(|&(u, v)| x.abs_diff(u) <= 1 && y.abs_diff(v) <= 1)
    };
    let got: Vec<(u32, u32)> = frags.iter().map(|f| (f.x, f.y)).collect();
    let may: Vec<(u32, u32)> = (0..expected.len())
        .filter(|&i| expected[i] != Expect::Zero)
        .map(at)
        .collect();
    let mut found = Findings::new();
    for &p in got.iter().filter(|&&p| !near(p, &may)) {
        found.add(p, || {
            format!(
                "({}, {}) is more than a pixel from the visible part's pixels",
                p.0, p.1
            )
        });
    }
    for i in (0..expected.len()).filter(|&i| expected[i] == Expect::One) {
        let p = at(i);
        let c = [f64::from(p.0) + 0.5, f64::from(p.1) + 0.5];
        if (c[0] - cut[0]).abs().max((c[1] - cut[1]).abs()) >= 2.0 && !near(p, &got) {
            found.add(p, || {
                format!(
                    "({}, {}) of the visible part has no fragment within a pixel",
                    p.0, p.1
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "the clipped segment breaks Vulkan's allowance for other line algorithms at {}",
            plural(n, "pixel")
        )
    })
}

/// What [`check_clip`] judges: the rasterizer's fragments, the expectations per sample, and
/// where the segment meets the near plane (pixels).
type ClipJudged = (Vec<Fragment>, Vec<Expect>, [f64; 2]);

/// [`ClipJudged`] of a case, `None` for a case the rule does not judge.
fn clip_expectations(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<Option<ClipJudged>, Violation> {
    let Some(d) = declared(r) else { return Ok(None) };
    let Some([pa, pb]) = case.segment(0) else {
        return Ok(None);
    };
    // Without near clipping there is no cut to judge.
    if !case.scene.state.clip_near {
        return Ok(None);
    }
    let (w, h) = (case.scene.width, case.scene.height);
    let range = case.scene.state.depth_range;
    let near = |p: [f32; 4]| near_distance(range, f64::from(p[2]), f64::from(p[3]));
    let (da, db) = (near(pa), near(pb));
    // The front end within the depth planes, so that only the near plane cuts the segment.
    if da < 0.0 || (case.scene.state.clip_far && pa[2] > pa[3]) {
        return Ok(None);
    }
    // Where the segment meets the near plane, found in clip space (where clipping happens: an
    // end behind the eye has no raster position to interpolate from), then projected.
    let s = if db < 0.0 { da / (da - db) } else { 1.0 };
    let [a4, b4] = [pa, pb].map(|p| p.map(f64::from));
    let c4: [f64; 4] = std::array::from_fn(|k| a4[k] + s * (b4[k] - a4[k]));
    let reach = f64::from(d.profile.features.guard_band);
    let shown = |[x, y]: [f64; 2]| {
        (-reach..=f64::from(w) + reach).contains(&x) && (-reach..=f64::from(h) + reach).contains(&y)
    };
    // The visible part must lie where no x/y plane cuts it (between two points that do, on a
    // segment whose w stays positive): a cut beyond where w reaches 0 is the x/y planes' to make.
    let cut = project(w, h, c4);
    if c4[3] <= 0.0 || !shown(project(w, h, a4)) || !shown(cut) {
        return Ok(None);
    }
    let Some(starts) = end_candidates(case, pa, &d) else {
        return Ok(None);
    };
    let frags = sample_fragments(r, case)?;
    let one = f64::from(1u32 << d.bits);
    let cut_grid = (cut[0] * one, cut[1] * one);
    let positions = positions(r, case);
    let g = grid(case, d.bits, &positions);
    let band = d.profile.band_px();
    // The cut rounded each way on each axis: where they disagree, rounding decides.
    // So does the front end, where the profile may snap it either way.
    let variants: Vec<Vec<Expect>> = [(0.0, 0.0), (1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0)]
        .iter()
        .flat_map(|&(ox, oy)| {
            let end = (
                (cut_grid.0 + ox).round() as i128,
                (cut_grid.1 + oy).round() as i128,
            );
            starts.iter().map(move |&start| [start, end])
        })
        .map(|ends| segment_expectations(case, &g, &d, ends, band))
        .collect();
    let mut expected = variants[0].clone();
    for (i, e) in expected.iter_mut().enumerate() {
        if variants.iter().any(|v| v[i] != variants[0][i]) {
            *e = Expect::ZeroOrOne;
        }
    }
    // Within 1.5 px of the cut, the end's own rule (its diamond left out) may go either way.
    if db < 0.0 {
        for y in 0..h {
            for x in 0..w {
                let c = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                if (c[0] - cut[0]).abs().max((c[1] - cut[1]).abs()) < 1.5 {
                    for k in 0..positions.len() {
                        expected[super::super::samples::cell(case, x, y, k as u8)] = Expect::ZeroOrOne;
                    }
                }
            }
        }
    }
    Ok(Some((frags, expected, cut)))
}
