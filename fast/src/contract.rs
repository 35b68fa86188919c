//! What `fast` promises against the reference, as checks its tests, its benchmark and the render
//! tests share: the same covered samples, interpolation within the declared precision, and
//! resolved buffers that differ only where depths tie within it.

use std::collections::HashMap;

use refrast::{CompareOp, DepthState, Fragment, Resolved};

/// The declared precision as a distance: `2^-PRECISION_BITS`.
#[must_use]
pub fn tolerance() -> f32 {
    0.5f32.powi(i32::from(crate::PRECISION_BITS))
}

/// The coverage key of a fragment: which sample of which primitive, and its facing.
fn key(f: &Fragment) -> (u32, u32, u32, bool) {
    (f.primitive, f.y, f.x, f.front_facing)
}

/// Checks that `got` covers exactly the samples `want` covers (same primitives, same facing),
/// and that each one's depth and barycentrics are within `tolerance` of `want`'s.
///
/// # Errors
/// The first difference, in words.
pub fn check_fragments(want: &[Fragment], got: &[Fragment], tolerance: f32) -> Result<(), String> {
    let mut want: Vec<&Fragment> = want.iter().collect();
    let mut got: Vec<&Fragment> = got.iter().collect();
    want.sort_unstable_by_key(|f| key(f));
    got.sort_unstable_by_key(|f| key(f));
    if want.len() != got.len() {
        return Err(format!(
            "{} fragments, the reference has {}",
            got.len(),
            want.len()
        ));
    }
    let close = |a: f32, b: f32| (a - b).abs() <= tolerance;
    let close3 = |a: [f32; 3], b: [f32; 3]| (0..3).all(|k| close(a[k], b[k]));
    for (w, g) in want.iter().zip(&got) {
        let at = format!("primitive {} at ({}, {})", g.primitive, g.x, g.y);
        if key(w) != key(g) {
            return Err(format!(
                "covers {at}, facing {}; the reference covers primitive {} at ({}, {}) there",
                g.front_facing, w.primitive, w.x, w.y
            ));
        }
        if !close(w.depth, g.depth) {
            return Err(format!("{at}: depth {} against {}", g.depth, w.depth));
        }
        if !close3(w.barycentric, g.barycentric) {
            return Err(format!(
                "{at}: barycentrics {:?} against {:?}",
                g.barycentric, w.barycentric
            ));
        }
        let screen = match (w.screen_barycentric, g.screen_barycentric) {
            (Some(a), Some(b)) => close3(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if !screen {
            return Err(format!(
                "{at}: screen barycentrics {:?} against {:?}",
                g.screen_barycentric, w.screen_barycentric
            ));
        }
    }
    Ok(())
}

/// Checks `got`, a resolve of a draw with depth state `state` whose reference fragments are
/// `want` (in draw order per pixel), against every outcome the depth test could have had where
/// two depths tie within `tolerance`.
///
/// Each depth `fast` compares is within `tolerance` of the reference's, so a comparison can
/// only turn out otherwise where the two reference depths are within twice that: there both
/// outcomes are followed. A pixel passes when its primitive is one some path leaves, with a
/// depth within `tolerance` of that path's.
///
/// # Errors
/// The first pixel no path explains.
pub fn check_resolved(
    want: &[Fragment],
    state: DepthState,
    got: &Resolved,
    tolerance: f32,
) -> Result<(), String> {
    let width = got.viewport.width();
    let mut per_pixel: HashMap<usize, Vec<&Fragment>> = HashMap::new();
    for f in want {
        per_pixel.entry((f.y * width + f.x) as usize).or_default().push(f);
    }
    for (i, (&depth, &primitive)) in got.depth.iter().zip(&got.primitive).enumerate() {
        let fragments = per_pixel.remove(&i).unwrap_or_default();
        let outcomes = outcomes(&fragments, state, 2.0 * tolerance);
        let explained = outcomes
            .iter()
            .any(|&(d, p)| p == primitive && (d == depth || (d - depth).abs() <= tolerance));
        if !explained {
            let (x, y) = (i as u32 % width, i as u32 / width);
            return Err(format!(
                "pixel ({x}, {y}) holds primitive {primitive:?} at depth {depth}; the depth test \
                 can leave only {outcomes:?} (depth, primitive) from {} fragments",
                fragments.len()
            ));
        }
    }
    Ok(())
}

/// Every (stored depth, primitive) the depth test can leave after `fragments`, following both
/// outcomes of each comparison between depths within `tie` of each other.
fn outcomes(fragments: &[&Fragment], state: DepthState, tie: f32) -> Vec<(f32, Option<u32>)> {
    let mut paths = vec![(state.clear, None)];
    for f in fragments {
        let mut next = Vec::with_capacity(paths.len() * 2);
        for &(stored, primitive) in &paths {
            let passes = state.compare.passes(f.depth, stored);
            let tied = !matches!(state.compare, CompareOp::Never | CompareOp::Always)
                && (f.depth - stored).abs() <= tie;
            let written = (if state.write { f.depth } else { stored }, Some(f.primitive));
            if passes || tied {
                next.push(written);
            }
            if !passes || tied {
                next.push((stored, primitive));
            }
        }
        next.sort_unstable_by_key(|a| (a.0.to_bits(), a.1));
        next.dedup_by(|a, b| a.0.to_bits() == b.0.to_bits() && a.1 == b.1);
        paths = next;
    }
    paths
}

/// Which pixels of a `width`-wide target hold fragments of two primitives whose depths are
/// within twice `tolerance` (`fragments` in any order): where a picture's depth test may pick
/// either.
#[must_use]
pub fn ties(fragments: &[Fragment], width: u32, height: u32, tolerance: f32) -> Vec<bool> {
    let mut depths: Vec<Vec<f32>> = vec![Vec::new(); (width * height) as usize];
    for f in fragments {
        depths[(f.y * width + f.x) as usize].push(f.depth);
    }
    depths
        .iter_mut()
        .map(|d| {
            d.sort_unstable_by(f32::total_cmp);
            d.windows(2).any(|w| w[1] - w[0] <= 2.0 * tolerance)
        })
        .collect()
}

/// Checks two pictures of one scene, `want` drawn through the reference and `got` through
/// `fast`: each pixel's colour within one level a channel (a value interpolated within the
/// precision can still round to the next level) and its depth within `tolerance`, except where
/// `ties` says the depth test may have picked another primitive.
///
/// # Errors
/// How many pixels differ, and the first.
pub fn check_pictures(
    want: (&[[u8; 4]], &[f32]),
    got: (&[[u8; 4]], &[f32]),
    ties: &[bool],
    tolerance: f32,
) -> Result<(), String> {
    let close = |a: [u8; 4], b: [u8; 4]| (0..4).all(|c| a[c].abs_diff(b[c]) <= 1);
    let differ: Vec<usize> = (0..want.0.len())
        .filter(|&i| {
            let depth = want.1[i] == got.1[i] || (want.1[i] - got.1[i]).abs() <= tolerance;
            !(ties[i] || close(want.0[i], got.0[i]) && depth)
        })
        .collect();
    match differ.first() {
        None => Ok(()),
        Some(&i) => Err(format!(
            "{} pixels differ beyond the precision and no tie explains them; pixel {i}: colour {:?} \
             depth {} against {:?} {}",
            differ.len(),
            got.0[i],
            got.1[i],
            want.0[i],
            want.1[i]
        )),
    }
}

/// A rasterizer that draws with an inner one and keeps every fragment it returned, so that a
/// test can find the ties ([`ties`]) of a picture drawn through it.
pub struct Recording<'r> {
    /// The rasterizer drawing.
    pub inner: &'r mut dyn refrast::Rasterizer,
    /// Every fragment of every draw so far.
    pub fragments: Vec<Fragment>,
}

impl refrast::Rasterizer for Recording<'_> {
    fn profile(&self) -> refrast::Profile {
        self.inner.profile()
    }

    fn about(&self) -> String {
        self.inner.about()
    }

    fn rasterize(&mut self, draw: &refrast::Draw) -> Result<Vec<Fragment>, refrast::DrawError> {
        let fragments = self.inner.rasterize(draw)?;
        self.fragments.extend_from_slice(&fragments);
        Ok(fragments)
    }
}
