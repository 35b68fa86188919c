//! Hints: when a failure has the shape of a misdeclared profile, one line that says so.
//!
//! Each detector redraws the shrunk counterexample and asks whether one alternative explains
//! every difference: the other winding (a front face or cull mode declared the wrong way round,
//! or y pointing up), the facing inverted, another fill convention, another subpixel
//! precision, another rounding of vertices to the grid, the other clip volume's window depth,
//! the barycentrics of a vertex order other than the draw's, no tie rule at all (samples on
//! edges covered by both triangles or by neither). A hint names both readings, a
//! misdeclared profile or the bug that looks the same (the zoo's mutants have these shapes
//! too). A hint is printed only once verified: the failing case, and more cases of the rule,
//! are run again on the rasterizer as the hint reads it (declaring what it suggests, or with
//! the difference it names undone), and must then pass. A guess that does not is worse than none.

use refrast::{
    DepthConvention, DepthRange, FillConvention, Fragment, Profile, Rasterizer, SnapAccuracy, Snapping,
    Supported,
};

use super::cast::{Expected, raycast_expectations, raycast_fragments};
use super::common::{deep_sample, fragments, precision};
use super::reading::{Read, Reading, other_range};
use super::ties::{self, Ties};
use super::{Family, Rule};
use crate::oracle::brute_force;
use crate::oracle::facing::{Turn, snapped_variants};
use crate::oracle::raster::{self, Point};
use crate::scene::Scene;

/// A hint's text and the reading that must make the failing case pass.
struct Suggestion {
    text: String,
    reading: Reading,
}

/// A detector: a suggestion when the failure on `scene` has its shape.
type Detector = fn(&mut dyn Rasterizer, &Profile, &Scene, &[Fragment]) -> Option<Suggestion>;

/// The hint for `rule`'s failure on `scene` (the shrunk counterexample), if its shape matches a
/// misdeclaration and `verify` passes on the rasterizer as the hint reads it (the failing case
/// run again, and more of the rule's cases: one case can agree with a wrong reading by
/// chance); `None` when no detector's suggestion does, or the rasterizer cannot draw it again.
///
/// Only the detectors that speak of what the rule judges run: coverage for the fill, clip and
/// metamorphic rules, facing for the rules about facing, depth for the depth rules,
/// barycentrics for theirs.
#[must_use]
pub fn diagnose(
    r: &mut dyn Rasterizer,
    rule: &Rule,
    scene: &Scene,
    verify: &mut dyn FnMut(&mut dyn Rasterizer) -> bool,
) -> Option<String> {
    let profile = r.profile();
    let frags = fragments(r, scene).ok()?;
    let facing = matches!(
        rule.id,
        "meta.facing.from-winding" | "meta.reversal.flips-facing" | "meta.cull.by-facing"
    );
    let detectors: Vec<Detector> = match rule.family {
        Family::Fill | Family::Clip => vec![
            one_winding,
            other_rounding,
            mirrored_fill,
            other_bits,
            no_tie_rule,
        ],
        Family::Meta if facing => vec![one_winding, inverted_facing],
        Family::Meta => vec![
            one_winding,
            other_rounding,
            mirrored_fill,
            other_bits,
            permuted_barycentrics,
        ],
        Family::Depth => vec![other_depth_range],
        Family::Bary => vec![permuted_barycentrics],
        Family::Robust | Family::Line | Family::Point | Family::Msaa => Vec::new(),
    };
    detectors.iter().find_map(|detect| {
        let suggestion = detect(r, &profile, scene, &frags)?;
        let mut read = Read {
            inner: &mut *r,
            reading: suggestion.reading,
        };
        verify(&mut read).then_some(suggestion.text)
    })
}

/// Every triangle of one winding that should draw is missing, each draws once reversed, and
/// every one of the other winding draws.
fn one_winding(
    r: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    let band = profile.band_px();
    let turns = scene.turns(profile);
    let judged: Vec<(usize, Turn, bool)> = (0..scene.triangles.len())
        .filter(|&t| matches!(turns[t], Turn::Clockwise | Turn::CounterClockwise))
        .filter(|&t| turns[t].drawn(&scene.state) == Some(true))
        .filter(|&t| deep_sample(scene, t, 2.0 * band).is_some())
        .map(|t| (t, turns[t], frags.iter().any(|f| f.primitive as usize == t)))
        .collect();
    let &(first, lost, _) = judged.iter().find(|(_, _, drawn)| !drawn)?;
    if judged.iter().any(|&(_, turn, drawn)| drawn == (turn == lost)) {
        return None;
    }
    let mut reversed = scene.clone();
    reversed.triangles = vec![scene.triangles[first]];
    reversed.triangles[0].swap(1, 2);
    let reversed = reversed.compact();
    if fragments(r, &reversed).ok()?.is_empty() {
        return None;
    }
    let missing = judged.iter().filter(|(_, _, drawn)| !drawn).count();
    let text = format!(
        "every triangle here that turns {} on screen ({missing} of {}) is missing, and one drawn reversed is not: \
         the profile may declare its front faces or cull modes the wrong way round (or the rasterizer's y axis points \
         up), or a bug drops one winding (as mutant:one-winding does)",
        turn_word(lost),
        judged.len()
    );
    Some(Suggestion {
        text,
        reading: Reading::Drops(lost),
    })
}

/// Every fragment whose facing is sure says the opposite.
fn inverted_facing(
    _: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    let turns = scene.turns(profile);
    let judged: Vec<bool> = frags
        .iter()
        .filter_map(|f| {
            let want = turns.get(f.primitive as usize)?.front_facing(&scene.state)?;
            (turns[f.primitive as usize] != Turn::Degenerate).then_some(f.front_facing == want)
        })
        .collect();
    (!judged.is_empty() && judged.iter().all(|right| !right)).then(|| Suggestion {
        text: format!(
            "every fragment says front_facing the opposite of what its triangle's winding gives under {:?} front \
             faces: the profile may declare its front faces the wrong way round, or a bug inverts facing (as \
             mutant:inverted-facing does)",
            scene.state.front_face
        ),
        reading: Reading::InvertedFacing,
    })
}

/// Coverage is exactly another fill convention's, not the declared one's.
fn mirrored_fill(
    _: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    let (bits, declared) = (profile.snapping.grid_bits()?.min(16), profile.fill?);
    let explains = |fill| explains_coverage(scene, frags, bits, fill, None);
    if explains_coverage(scene, frags, bits, declared, Some(profile))? {
        return None;
    }
    let other = FillConvention::ALL
        .into_iter()
        .find(|&fill| fill != declared && explains(fill) == Some(true))?;
    let text = format!(
        "the coverage is exactly what the {} fill convention gives, not the declared {}: the profile may declare the \
         wrong fill convention, or a bug breaks ties on edges the wrong way (as mutant:bottom-right-as-top-left does)",
        other.name(),
        declared.name()
    );
    Some(Suggestion {
        text,
        reading: Reading::Declares(Profile {
            fill: Some(other),
            ..profile.clone()
        }),
    })
}

/// Samples exactly on edges are covered as `e >= 0` (by both triangles sharing an edge) or
/// `e > 0` (by neither) gives, not as the declared tie rule does.
fn no_tie_rule(
    _: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    let fill = profile.fill?;
    let found = ties::explaining(&scene.draw(), frags, fill)?;
    let what = match found {
        Ties::Inclusive => {
            "by every triangle whose edge passes through them, so a sample on an edge two triangles share is covered twice"
        }
        Ties::Exclusive => "by no triangle, so a sample on an edge two triangles share is covered by neither",
    };
    Some(Suggestion {
        text: format!(
            "samples exactly on an edge are covered {what}: the rasterizer has no tie rule (its edge test is `{}` on \
             every edge). Give each such sample to exactly one triangle, as the declared {} convention does: count it \
             only when the edge is a {} edge (`e > 0 || (e == 0 && owned)`)",
            found.code(),
            fill.name(),
            owned_words(fill)
        ),
        reading: Reading::TieRule(found, fill),
    })
}

/// The edges a fill convention owns, in words.
fn owned_words(fill: FillConvention) -> &'static str {
    match fill {
        FillConvention::TopLeft => "top or a left",
        FillConvention::TopRight => "top or a right",
        FillConvention::BottomLeft => "bottom or a left",
        FillConvention::BottomRight => "bottom or a right",
    }
}

/// Coverage is exactly another subpixel precision's, not the declared one's.
fn other_bits(
    _: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    let (declared, fill) = (profile.snapping.grid_bits()?.min(16), profile.fill?);
    if explains_coverage(scene, frags, declared, fill, Some(profile))? {
        return None;
    }
    // The nearest precision that explains it: a small triangle agrees with many coarse grids.
    let mut nearest: Vec<u8> = (1..=16u8).filter(|&b| b != declared).collect();
    nearest.sort_by_key(|&b| (b.abs_diff(declared), b));
    let other = nearest
        .into_iter()
        .find(|&b| explains_coverage(scene, frags, b, fill, None) == Some(true))?;
    Some(Suggestion {
        text: format!(
            "the coverage is exactly what {other} subpixel bits give, not the declared {declared}: the profile may \
             declare the wrong subpixel precision, or a bug snaps to a coarser grid (as mutant:dropped-subpixel-bit does)"
        ),
        reading: Reading::Declares(Profile {
            snapping: Snapping::Grid(other),
            ..profile.clone()
        }),
    })
}

/// Coverage is exactly what another rounding of vertices to the declared grid gives (floor,
/// truncation toward zero, to the nearest), not the declared one.
fn other_rounding(
    _: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    let (bits, fill) = (profile.snapping.grid_bits()?.min(16), profile.fill?);
    if explains_coverage(scene, frags, bits, fill, Some(profile))? {
        return None;
    }
    let rounding = |snap: SnapAccuracy| {
        let mut p = profile.clone();
        p.features.snap = snap;
        p.features.ties_to_even = snap == SnapAccuracy::Nearest && profile.features.ties_to_even;
        p
    };
    let other = [
        SnapAccuracy::TowardZero,
        SnapAccuracy::Floor,
        SnapAccuracy::Nearest,
    ]
    .into_iter()
    .filter(|&snap| snap != profile.features.snap)
    .find(|&snap| explains_coverage(scene, frags, bits, fill, Some(&rounding(snap))) == Some(true))?;
    Some(Suggestion {
        text: format!(
            "the coverage is exactly what snapping vertices {} gives, not the declared {}: the profile may declare \
             the wrong rounding (`snap {}` in the pipe protocol; a float-to-fixed conversion truncates toward zero), \
             or a bug rounds vertices to the grid otherwise",
            accuracy_words(other),
            accuracy_words(profile.features.snap),
            other.name()
        ),
        reading: Reading::Declares(rounding(other)),
    })
}

/// A snap accuracy as a hint says it.
fn accuracy_words(snap: SnapAccuracy) -> &'static str {
    match snap {
        SnapAccuracy::Nearest => "to the nearest grid point",
        SnapAccuracy::WithinOneStep => "to either neighbouring grid point",
        SnapAccuracy::Floor => "down (floor)",
        SnapAccuracy::TowardZero => "toward zero (truncation)",
    }
}

/// Whether the brute-force oracle at `bits` under `fill` gives exactly `frags`, triangle by
/// triangle, culling by the snapped facing: with each vertex snapped to the nearest grid point,
/// or, given the profile that declares `bits`, to any grid point it lets a vertex snap to.
/// `None` when it cannot say (a triangle needs clipping, a vertex does not project).
fn explains_coverage(
    scene: &Scene,
    frags: &[Fragment],
    bits: u8,
    fill: FillConvention,
    declared: Option<&Profile>,
) -> Option<bool> {
    for t in 0..scene.triangles.len() {
        let corners = scene.corners(t);
        if !raster::unclipped(&corners, &scene.state) {
            return None;
        }
        let variants: Vec<[Point; 3]> = match declared {
            Some(profile) => snapped_variants(&corners, scene.width, scene.height, profile)?,
            None => {
                let snapped: Vec<Point> = corners
                    .iter()
                    .map(|&p| raster::snap(p, scene.width, scene.height, bits))
                    .collect::<Option<_>>()?;
                vec![[snapped[0], snapped[1], snapped[2]]]
            }
        };
        let mut got: Vec<(u32, u32)> = frags
            .iter()
            .filter(|f| f.primitive as usize == t)
            .map(|f| (f.x, f.y))
            .collect();
        got.sort_unstable();
        let explained = variants.iter().any(|&tri| {
            let turn = match brute_force::orient2d(tri[0], tri[1], tri[2]).signum() {
                1 => Turn::Clockwise,
                -1 => Turn::CounterClockwise,
                _ => Turn::Degenerate,
            };
            let mut want = if turn.drawn(&scene.state) == Some(false) {
                Vec::new()
            } else {
                brute_force::coverage(tri, scene.width, scene.height, bits, fill)
            };
            want.sort_unstable();
            got == want
        });
        if !explained {
            return Some(false);
        }
    }
    Some(true)
}

/// Depths are what the ray cast gives under the other clip volume (its near plane and its
/// window depth), not under the draw's.
fn other_depth_range(
    r: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    frags: &[Fragment],
) -> Option<Suggestion> {
    if profile.depth != DepthConvention::ScreenLinearZOverW {
        return None;
    }
    let eps = precision(profile);
    let off = |f: &Fragment, w: &Expected| {
        (f64::from(f.depth) - raster::clamp_depth(&scene.state, w.depth)).abs() > eps + w.depth_slack
    };
    let declared = raycast_fragments(r, scene).ok()?;
    if !declared.pairs.iter().any(|(f, w)| off(f, w)) {
        return None;
    }
    let range = scene.state.depth_range;
    let mut other = scene.clone();
    other.state.depth_range = other_range(range);
    let explained = raycast_expectations(profile, &other, frags.to_vec());
    if explained.pairs.is_empty() || explained.pairs.iter().any(|(f, w)| off(f, w)) {
        return None;
    }
    let (said, other) = match range {
        DepthRange::ZeroToOne => (
            "0 ≤ z ≤ w, window depth z/w",
            "−w ≤ z ≤ w volume's window depth (z/w + 1)/2",
        ),
        DepthRange::NegativeOneToOne => (
            "−w ≤ z ≤ w, window depth (z/w + 1)/2",
            "0 ≤ z ≤ w volume's window depth z/w",
        ),
    };
    Some(Suggestion {
        text: format!(
            "every depth is the {other}, where the draw asked for {said}: the profile may declare the wrong depth \
             ranges, or a bug maps z to window depth the other way (as mutant:unmapped-gl-depth does)"
        ),
        reading: Reading::Declares(Profile {
            features: refrast::Features {
                depth_ranges: Supported::only(&[other_range(range)]),
                ..profile.features
            },
            ..profile.clone()
        }),
    })
}

/// The perspective barycentrics are the ray cast's with the vertices in another order.
fn permuted_barycentrics(
    r: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
    _: &[Fragment],
) -> Option<Suggestion> {
    if !profile.features.perspective_barycentrics {
        return None;
    }
    let eps = precision(profile);
    let cast = raycast_fragments(r, scene).ok()?;
    let fits = |order: [usize; 3]| {
        cast.pairs.iter().all(|(f, w): &(Fragment, Expected)| {
            (0..3).all(|k| {
                (f64::from(f.barycentric[k]) - w.barycentric[order[k]]).abs() <= eps + w.barycentric_slack
            })
        })
    };
    if cast.pairs.is_empty() || fits([0, 1, 2]) {
        return None;
    }
    let order = [[1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]]
        .into_iter()
        .find(|&o| fits(o))?;
    Some(Suggestion {
        text: format!(
            "every fragment's barycentrics are the ray cast's weights of vertices {}, {}, {} in that order: the weights \
             go to the wrong vertices, as in a rasterizer that numbers them otherwise than the draw (from its \
             provoking vertex, say) or one with a bug in its setup",
            order[0], order[1], order[2]
        ),
        reading: Reading::Permuted(order),
    })
}

/// A turn in words.
fn turn_word(turn: Turn) -> &'static str {
    match turn {
        Turn::Clockwise => "clockwise",
        _ => "counter-clockwise",
    }
}
