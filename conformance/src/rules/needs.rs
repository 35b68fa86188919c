//! What a rule needs a profile to declare ([`Need`]), each need once: without it the rule is
//! n/a, with the reason.

use std::fmt;

use refrast::{CompareOp, CullMode, DepthConvention, DepthRange, Profile, SubpixelBits};

/// Something a rule needs a profile to declare; without it the rule is n/a, with the reason.
#[derive(Clone, Copy)]
pub struct Need {
    has: fn(&Profile) -> bool,
    lacking: &'static str,
}

impl Need {
    /// `Err(reason)` when an implementation declaring `profile` lacks it.
    pub fn check(&self, profile: &Profile) -> Result<(), &'static str> {
        if (self.has)(profile) {
            Ok(())
        } else {
            Err(self.lacking)
        }
    }

    /// Why a rule needing it does not apply to a profile without it.
    #[must_use]
    pub fn lacking(&self) -> &'static str {
        self.lacking
    }
}

impl fmt::Debug for Need {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_tuple("Need").field(&self.lacking).finish()
    }
}

/// The one way to say what a rule needs: `has` tells whether a profile declares it, `lacking`
/// is the reason the rule is n/a when it does not.
#[must_use]
pub const fn needs(has: fn(&Profile) -> bool, lacking: &'static str) -> Need {
    Need { has, lacking }
}

/// Fragments carry perspective-correct barycentrics.
pub const PERSPECTIVE_BARYCENTRICS: Need = needs(
    |p| p.features.perspective_barycentrics,
    "no perspective-correct barycentrics",
);
/// Fragments carry screen-space barycentrics.
pub const SCREEN_BARYCENTRICS: Need =
    needs(|p| p.features.screen_barycentrics, "no screen-space barycentrics");
/// A vertex can lie on a sample centre as drawn: no grid, or one of at least one bit (a
/// whole-pixel grid puts every vertex on a pixel corner).
pub const VERTEX_ON_SAMPLE: Need = needs(
    |p| p.snapping.grid_bits() != Some(0),
    "a whole-pixel grid puts no vertex on a sample centre",
);
/// Fragments carry barycentrics of either kind.
pub const ANY_BARYCENTRICS: Need = needs(
    |p| p.features.perspective_barycentrics || p.features.screen_barycentrics,
    "no barycentrics of either kind",
);
/// Depth is z/w interpolated linearly in screen space.
pub const Z_OVER_W_DEPTH: Need = needs(
    |p| p.depth == DepthConvention::ScreenLinearZOverW,
    "depth is not z/w linear in screen space",
);
/// The depth test is implemented.
pub const DEPTH_TEST: Need = needs(|p| p.features.depth_test, "no depth test");
/// The compare ops that keep the nearest or the farthest fragment with writes on, so that the
/// depth buffer after them does not depend on the order of the draws: nearest first.
pub const EXTREME_OPS: [CompareOp; 4] = [
    CompareOp::Less,
    CompareOp::LessOrEqual,
    CompareOp::Greater,
    CompareOp::GreaterOrEqual,
];

/// A depth test that keeps the nearest (or the farthest) fragment and writes it: `Less`,
/// `LessOrEqual`, `Greater` or `GreaterOrEqual`, with writes on.
pub const EXTREME_WINS: Need = needs(
    |p| {
        let f = &p.features;
        f.depth_test
            && f.depth_writes.contains(true)
            && EXTREME_OPS.iter().any(|&op| f.compare_ops.contains(op))
    },
    "no depth test keeping the nearest or farthest fragment (Less, LessOrEqual, Greater or GreaterOrEqual, with writes)",
);
/// Culling of front or back faces is implemented.
pub const CULLING: Need = needs(
    |p| p.features.cull_modes.values().any(|c| c != CullMode::None),
    "no culling",
);
/// Far-plane clipping can be switched on.
pub const FAR_CLIPPING: Need = needs(
    |p| p.features.far_clipping.contains(true),
    "no far-plane clipping",
);
/// The OpenGL `−w ≤ z` clip volume is supported.
pub const GL_DEPTH_RANGE: Need = needs(
    |p| p.features.depth_ranges.contains(DepthRange::NegativeOneToOne),
    "no −w ≤ z clip volume",
);
/// Clipping in 3D: the clip rules ask what a triangle behind the eye or across a clip plane
/// draws, which a 2D scan converter, sent only what needs no clipping, is never asked.
pub const CLIPS_IN_3D: Need = needs(
    |p| p.features.clips_in_3d,
    "no clipping in 3D (clipping none): it is sent only what needs none",
);
/// x/y clipping moves no edge inside the viewport of a triangle reaching some way outside it.
pub const GUARD_BAND: Need = needs(
    |p| p.features.guard_band > 0,
    "x/y clipping may move edges (no guard band)",
);
/// Coverage decided exactly: a snapping grid and a tie rule, so an oracle can say bit for bit.
pub const EXACT_COVERAGE: Need = needs(
    |p| p.snapping.grid_bits().is_some() && p.fill.is_some(),
    "no snapping grid or no tie rule, so coverage has no exact answer",
);
/// A profile the reference can reproduce, for rules that compare with it.
pub const REFERENCE_PROFILE: Need = needs(
    |p| {
        p.snapping
            .grid_bits()
            .is_some_and(|b| SubpixelBits::new(b).is_ok())
            && p.fill.is_some()
    },
    "the reference reproduces only a grid of 1..=8 subpixel bits with a tie rule",
);
