//! The scissor test: a draw with a scissor rectangle makes exactly the fragments it makes
//! without one whose pixel lies inside, and its depth test leaves every sample outside as the
//! clear left it.
//!
//! Both rules compare the implementation with itself (the same draw with and without the
//! rectangle), so they hold whatever its conventions: no oracle, no tolerance band.

use proptest::prelude::*;
use proptest::strategy::Union;
use refrast::{Fragment, Profile, Rasterizer, Scissor};

use super::samples::{
    cell_counts, difference_counts, difference_picture, keys, resolved_split, sample_fragments,
};
use super::{DEPTH_TEST, Family, Need, Rule, needs};
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::strategy::{self, primitive};
use crate::violation::{Violation, plural};

/// What every specification says of the scissor test.
const SOURCE: &str = "Vulkan 1.4, Scissor Test (fragops-scissor); D3D11.3 §15.7; OpenGL 4.6 §14.9.2 and OpenGL ES 3.2 §13.8.2 (left ≤ x < left + width); dEQP-VK.fragment_operations.scissor.*";

/// The implementation honours a scissor rectangle.
const SCISSOR: Need = needs(|p| p.state.scissor, "no scissor");

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Clip, "clip.scissor.crops")
            .sentence("With a scissor rectangle, a draw of any topology at any declared sample count makes exactly the fragments the same draw makes without one whose pixel lies inside the rectangle (left ≤ x < left + width, top ≤ y < top + height): none outside, none lost or added inside.")
            .source(SOURCE)
            .cases(600)
            .needs(SCISSOR)
            .run(|r, cfg| property_for(r, cfg, scissored_draws, check_crops)),
        Rule::invariant(Family::Depth, "depth.scissor.outside-untouched")
            .sentence("With a scissor rectangle, the depth and primitive buffers the depth test leaves equal, inside the rectangle, those of the same draw without one, and outside it those of a draw of nothing.")
            .source(SOURCE)
            .cases(300)
            .needs(SCISSOR)
            .needs(DEPTH_TEST)
            .run(|r, cfg| property_for(r, cfg, scissored_triangles, check_resolve_crops)),
    ]
}

/// The triangles the rules draw: a mesh over the viewport, or overlapping triangles that
/// cross the near plane, at each sample count `p` declares.
fn triangles(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let scenes = prop_oneof![strategy::mesh_scene(), strategy::overlapping_scene()];
    primitive::multisampled(scenes, p.sample_counts()).boxed()
}

/// Triangles, with a scissor.
fn scissored_triangles(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    primitive::scissored(triangles(p)).boxed()
}

/// Every topology `p` draws, at each sample count it draws it at, with a scissor.
fn scissored_draws(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let mut kinds = vec![triangles(p)];
    let counts = |topology| -> Vec<u8> {
        p.sample_counts()
            .into_iter()
            .filter(|&n| p.draws(topology, n))
            .collect()
    };
    if p.lines.is_some() {
        kinds.push(
            primitive::multisampled_primitives(primitive::lines(), counts(refrast::Topology::LineList))
                .boxed(),
        );
    }
    if p.points {
        kinds.push(
            primitive::multisampled_primitives(primitive::points(), counts(refrast::Topology::PointList))
                .boxed(),
        );
    }
    primitive::scissored(Union::new(kinds)).boxed()
}

/// `case` without its scissor.
fn unscissored(case: &PrimitiveScene) -> PrimitiveScene {
    let mut whole = case.clone();
    whole.scene.state.scissor = None;
    whole
}

/// The rectangle as a sentence names it.
fn describe(s: Scissor) -> String {
    if s.width == 0 || s.height == 0 {
        return format!("the empty scissor at ({}, {})", s.x, s.y);
    }
    format!(
        "the scissor x {}..{}, y {}..{}",
        s.x,
        u64::from(s.x) + u64::from(s.width),
        s.y,
        u64::from(s.y) + u64::from(s.height)
    )
}

/// A draw with a scissor makes the fragments it makes without one, those inside the rectangle.
pub fn check_crops(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some(scissor) = case.scene.state.scissor else {
        return Ok(());
    };
    let cut = sample_fragments(r, case)?;
    let whole = sample_fragments(r, &unscissored(case))?;
    let inside: Vec<&Fragment> = whole.iter().filter(|f| scissor.contains(f.x, f.y)).collect();
    if keys(&cut) == keys(inside.iter().copied()) {
        return Ok(());
    }
    let (got, want) = (cell_counts(case, &cut), cell_counts(case, inside.iter().copied()));
    let outside = cut.iter().filter(|f| !scissor.contains(f.x, f.y)).count();
    let message = if let Some(f) = cut.iter().find(|f| !scissor.contains(f.x, f.y)) {
        format!(
            "{} outside {}: the first at ({}, {}) sample {}, of primitive {}",
            plural(outside, "fragment"),
            describe(scissor),
            f.x,
            f.y,
            f.sample,
            f.primitive
        )
    } else if got == want {
        format!(
            "inside {} the draw covers the samples it covers without a scissor, but names other primitives for them",
            describe(scissor)
        )
    } else {
        let (lost, added) = got.iter().zip(&want).fold((0, 0), |(l, a), (&g, &w)| {
            (l + w.saturating_sub(g), a + g.saturating_sub(w))
        });
        format!(
            "inside {} the draw makes other fragments than without a scissor: {} lost, {} added",
            describe(scissor),
            lost,
            added
        )
    };
    let mut violation = Violation::new(message);
    violation.counts = Some(Box::new(difference_counts(&got, &want)));
    violation.picture = Some(Box::new(difference_picture(case, &got, &want, rectangle(case))));
    Err(violation)
}

/// The scissor rectangle cut to the viewport, as an outline in pixels.
fn rectangle(case: &PrimitiveScene) -> Vec<Vec<[f64; 2]>> {
    let Some(r) = case.scene.state.scissor else {
        return Vec::new();
    };
    let (w, h) = (f64::from(case.scene.width), f64::from(case.scene.height));
    let (x0, y0) = (f64::from(r.x).min(w), f64::from(r.y).min(h));
    let (x1, y1) = (
        (x0 + f64::from(r.width)).min(w),
        (y0 + f64::from(r.height)).min(h),
    );
    vec![vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]]
}

/// The depth test with a scissor leaves the samples inside as without one, those outside as
/// a draw of nothing leaves them (the implementation's own clear value, in its own format).
pub fn check_resolve_crops(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some(scissor) = case.scene.state.scissor else {
        return Ok(());
    };
    let findings = resolved_split(
        r,
        case,
        &unscissored(case),
        |x, y, _| scissor.contains(x, y),
        [
            "inside the rectangle",
            "outside the rectangle",
            "the draw without a scissor",
        ],
    )?;
    findings.verdict(|n| {
        format!(
            "with {} the depth test leaves {} other than it should",
            describe(scissor),
            plural(n, "sample")
        )
    })
}
