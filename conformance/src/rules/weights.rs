//! A fragment's barycentrics as the barycentric rules judge them: of each kind the profile
//! declares, defined or not (screen-space weights across `w = 0`), and exact ones to compare.

use refrast::{Fragment, Profile, Rasterizer};

use super::common::{fragments, screen_defined};
use crate::scene::Scene;
use crate::violation::{Findings, Violation};

/// One kind of barycentrics a fragment carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// Perspective-correct.
    Perspective,
    /// Screen-space.
    Screen,
}

impl Kind {
    pub(super) fn name(self) -> &'static str {
        match self {
            Self::Perspective => "perspective",
            Self::Screen => "screen-space",
        }
    }
}

/// A fragment's barycentrics of one kind, as a rule may judge them.
pub(super) enum Weights {
    /// Defined: judged by the rule.
    Judged([f32; 3]),
    /// Screen-space weights of a triangle with a vertex at `w ≤ 0`, which has no shape on
    /// screen: neither the reference nor any specification defines them ("varies linearly in
    /// framebuffer space", Vulkan's Clipping Shader Outputs, has no meaning across `w = 0`; a
    /// GPU that rasterizes homogeneously gives the unclipped triangle's screen plane), so only
    /// finiteness is judged, and none at all is an answer.
    Undefined(Option<[f32; 3]>),
    /// None, though the profile declares them and the triangle lies in front of the eye.
    Missing,
}

/// The kinds of barycentrics a profile declares.
pub(super) fn declared(profile: &Profile) -> Vec<Kind> {
    let mut kinds = Vec::new();
    if profile.features.perspective_barycentrics {
        kinds.push(Kind::Perspective);
    }
    if profile.features.screen_barycentrics {
        kinds.push(Kind::Screen);
    }
    kinds
}

/// Fragment `f`'s barycentrics of `kind` in `scene`.
pub(super) fn weights(scene: &Scene, f: &Fragment, kind: Kind) -> Weights {
    match (kind, f.screen_barycentric) {
        (Kind::Perspective, _) => Weights::Judged(f.barycentric),
        (Kind::Screen, b) if !screen_defined(scene, f.primitive) => Weights::Undefined(b),
        (Kind::Screen, Some(b)) => Weights::Judged(b),
        (Kind::Screen, None) => Weights::Missing,
    }
}

/// Checks each declared kind of each fragment's barycentrics with `judge` (a problem in words,
/// or `None`) where they are defined, for finiteness where they are not, and that none is
/// missing; `what` says the failure for `n` fragments.
pub(super) fn judge_weights(
    r: &mut dyn Rasterizer,
    scene: &Scene,
    judge: impl Fn(&Fragment, Kind, [f32; 3]) -> Option<String>,
    what: impl FnOnce(usize) -> String,
) -> Result<(), Violation> {
    let profile = r.profile();
    let mut found = Findings::new();
    let frags = fragments(r, scene)?;
    for kind in declared(&profile) {
        for f in &frags {
            let problem = match weights(scene, f, kind) {
                Weights::Judged(b) => judge(f, kind, b),
                Weights::Undefined(b) => b.filter(|b| b.iter().any(|c| !c.is_finite())).map(|b| {
                    format!(
                        "{} {b:?} of a triangle with a vertex at w ≤ 0 (only finite values are required there)",
                        kind.name()
                    )
                }),
                Weights::Missing => Some(
                    "no screen-space barycentrics, though the profile declares them and the triangle lies in front of \
                     the eye (none, or all three NaN through the pipe, is an answer only for a triangle with a vertex \
                     at w ≤ 0)"
                        .to_owned(),
                ),
            };
            if let Some(problem) = problem {
                found.add((f.x, f.y), || format!("{:?} has {problem}", (f.x, f.y)));
            }
        }
    }
    found.verdict(what)
}

/// The exact barycentrics of kind `kind` at `s` in the triangle of projected vertices `p` with
/// clip-space `w`s (all positive): screen-space ones from the projected triangle, perspective
/// ones from those over `w`. `None` for a triangle with no area.
pub(super) fn exact_weights(p: [[f64; 2]; 3], w: [f64; 3], s: [f64; 2], kind: Kind) -> Option<[f64; 3]> {
    let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]);
    let area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if area == 0.0 || w.iter().any(|&w| w <= 0.0) {
        return None;
    }
    let screen = [e(p[1], p[2]) / area, e(p[2], p[0]) / area, e(p[0], p[1]) / area];
    Some(match kind {
        Kind::Screen => screen,
        Kind::Perspective => {
            let q = [screen[0] / w[0], screen[1] / w[1], screen[2] / w[2]];
            let sum = q[0] + q[1] + q[2];
            q.map(|c| c / sum)
        }
    })
}
