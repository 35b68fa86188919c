//! What the ray cast expects of each fragment: the triangle as the rasterizer may have snapped
//! it, and for a clipped one the spread of the ray cast over a grid step.

use refrast::{Fragment, Profile, Rasterizer};

use super::common::fragments;
use crate::oracle::facing::snapped_variants;
use crate::oracle::raster::{ndc_offset, sample_ndc, to_ndc, unclipped};
use crate::oracle::ray_cast::{Hit, ray_cast, spread};
use crate::scene::Scene;
use crate::violation::Violation;

/// Triangle `t` as the rasterizer may draw it: each vertex at a grid point the profile lets it
/// snap to ([`snapped_variants`]), refrast's own choice first, put back into clip space at its
/// own `w` and `z` (unsnapped without a grid). Empty unless every `w > 0`.
///
/// The oracles compare against these, not the f32 input, so that rounding the input on a sliver
/// triangle does not count against the rasterizer.
#[must_use]
pub fn snapped_triangles(scene: &Scene, t: usize, profile: &Profile) -> Vec<[[f64; 4]; 3]> {
    let corners = scene.corners(t);
    let Some(bits) = profile.snapping.grid_bits() else {
        let tri = scene.positions_of(t);
        return if tri.iter().all(|v| v[3] > 0.0) {
            vec![tri]
        } else {
            Vec::new()
        };
    };
    let one = f64::from(1u32 << bits.min(16));
    let Some(variants) = snapped_variants(&corners, scene.width, scene.height, profile) else {
        return Vec::new();
    };
    variants
        .into_iter()
        .map(|v| {
            std::array::from_fn(|k| {
                let [nx, ny] = to_ndc(
                    scene.width,
                    scene.height,
                    v[k].0 as f64 / one,
                    v[k].1 as f64 / one,
                );
                let [_, _, z, w] = corners[k].map(f64::from);
                [nx * w, ny * w, z, w]
            })
        })
        .collect()
}

/// What the ray cast expects of one fragment: its barycentrics and window depth (unclamped),
/// each within a slack on top of the profile's precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Expected {
    /// Perspective-correct barycentrics.
    pub barycentric: [f64; 3],
    /// Window depth, unclamped.
    pub depth: f64,
    /// How far the barycentrics may be off besides the precision: 0 when nothing is clipped.
    pub barycentric_slack: f64,
    /// How far the depth may be off besides the precision: 0 when nothing is clipped.
    pub depth_slack: f64,
}

/// Fragments of triangle 0, each with what the ray cast expects at its sample, and where the
/// profile lets a vertex snap to more than one grid point, what it expects of the others.
pub struct RayCast {
    /// Each fragment with refrast's own expectation (the vertices snapped to nearest, even).
    pub pairs: Vec<(Fragment, Expected)>,
    /// The other snapped triangles the profile allows (none for an exact snap or a clipped
    /// triangle, whose slack already covers a grid step).
    others: Vec<[[f64; 4]; 3]>,
    width: u32,
    height: u32,
    state: refrast::DrawState,
}

impl RayCast {
    /// Whether `accepts` holds for the expectation at `f` of any other snapped triangle.
    pub fn another_snap_accepts(&self, f: &Fragment, accepts: impl Fn(&Expected) -> bool) -> bool {
        let [nx, ny] = sample_ndc(self.width, self.height, f.x, f.y);
        self.others
            .iter()
            .filter_map(|tri| ray_cast(tri, nx, ny, &self.state))
            .any(|hit| accepts(&Expected::exact(hit)))
    }
}

/// Each fragment of triangle 0 paired with what the ray cast expects at its sample.
///
/// A triangle inside the clip volume is cast exactly as drawn (snapped, [`snapped_triangles`]);
/// fragments whose ray misses (a covered sample on an edge, a hair outside in f64) are left
/// out. A triangle that may be clipped is cast unsnapped, and the slack is the ray cast's
/// [`spread`] over one grid step around the sample: the cut vertices are snapped, and every
/// vertex of the polygon may move by that much (one step whichever way the grid rounds, or the
/// band's unit without a grid). Fragments are left out where no bound exists (the box reaches
/// the plane's horizon) or where the ray cast sees the triangle neither at the sample nor at a
/// corner of the box (a covered sample there is for the coverage rules to judge).
pub fn raycast_fragments(r: &mut dyn Rasterizer, scene: &Scene) -> Result<RayCast, Violation> {
    let profile = r.profile();
    let frags = fragments(r, scene)?;
    Ok(raycast_expectations(&profile, scene, frags))
}

/// [`raycast_fragments`] for fragments already drawn: what the ray cast expects of each of
/// `frags` for a rasterizer with `profile` drawing `scene`.
#[must_use]
pub fn raycast_expectations(profile: &Profile, scene: &Scene, frags: Vec<Fragment>) -> RayCast {
    let state = scene.state;
    let (w, h) = (scene.width, scene.height);
    let mut cast = RayCast {
        pairs: Vec::new(),
        others: Vec::new(),
        width: w,
        height: h,
        state,
    };
    let Some(corners) = scene
        .triangles
        .first()
        .map(|t| t.map(|i| scene.positions[i as usize]))
    else {
        return cast;
    };
    if unclipped(&corners, &state) {
        let mut tris = snapped_triangles(scene, 0, profile).into_iter();
        let Some(tri) = tris.next() else {
            return cast;
        };
        cast.others = tris.collect();
        cast.pairs = frags
            .into_iter()
            .filter(|f| f.primitive == 0)
            .filter_map(|f| {
                let [nx, ny] = sample_ndc(w, h, f.x, f.y);
                let hit = ray_cast(&tri, nx, ny, &state)?;
                Some((f, Expected::exact(hit)))
            })
            .collect();
        return cast;
    }
    let tri = scene.positions_of(0);
    let step = profile.snapping.unit_px();
    let half = ndc_offset(w, h, step, step).map(f64::abs);
    cast.pairs = frags
        .into_iter()
        .filter(|f| f.primitive == 0)
        .filter_map(|f| {
            let [nx, ny] = sample_ndc(w, h, f.x, f.y);
            // The bound speaks of a visible point within the box; where the ray cast sees none
            // at the sample or a corner, the fragment is the coverage rules' business.
            let corners = [(0.0, 0.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)];
            corners
                .iter()
                .find_map(|(sx, sy)| ray_cast(&tri, nx + sx * half[0], ny + sy * half[1], &state))?;
            let s = spread(&tri, nx, ny, half, &state)?;
            let expected = Expected {
                barycentric: s.at.barycentric,
                depth: s.at.depth,
                barycentric_slack: s.barycentric,
                depth_slack: s.depth,
            };
            Some((f, expected))
        })
        .collect();
    cast
}

/// ", allowed …" naming the slack a triangle reaching outside the clip volume earns, if any, in
/// the words of the profile: snapped cut vertices on a grid, the float tolerance's unit without
/// one.
pub fn slack_note(slack: f64, profile: &Profile) -> String {
    if slack <= 0.0 {
        return String::new();
    }
    match profile.snapping.grid_bits() {
        Some(bits) => format!(
            ", allowed {slack:.3e} more because the triangle reaches outside the clip volume (past a side of the \
             viewport or a depth plane), where the vertices clipping may make are snapped to the {bits}-bit grid (the \
             ray cast's spread over one grid step)"
        ),
        None => format!(
            ", allowed {slack:.3e} more because the triangle reaches outside the clip volume (past a side of the \
             viewport or a depth plane), where the vertices clipping may make are only as exact as float arithmetic \
             (the ray cast's spread over the float tolerance's unit, {} px)",
            profile.snapping.unit_px()
        ),
    }
}

impl Expected {
    /// An exact ray-cast hit: no slack.
    fn exact(hit: Hit) -> Self {
        Self {
            barycentric: hit.barycentric,
            depth: hit.depth,
            barycentric_slack: 0.0,
            depth_slack: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use refrast::{Profile, Rasterizer, Reference, Snapping};

    use super::slack_note;

    /// A float profile is not told of snapping or a grid, a gridded one is; no slack, no words.
    #[test]
    fn slack_is_said_in_the_profiles_words() {
        let base = Reference::default().profile();
        let float = Profile {
            snapping: Snapping::Float,
            ..base.clone()
        };
        let grid = Profile {
            snapping: Snapping::Grid(8),
            ..base
        };
        let said = slack_note(1e-4, &float);
        assert!(
            !said.contains("snapped") && !said.contains("grid") && said.contains("float"),
            "{said}"
        );
        assert!(slack_note(1e-4, &grid).contains("snapped to the 8-bit grid"));
        assert_eq!(slack_note(0.0, &float), "");
    }
}
