//! Depth per sample: each sample's fragment and depth-buffer value lie on the triangle's depth
//! plane at that sample's declared position (`msaa.depth.per-sample`), and the depth test runs
//! per sample on those depths (`msaa.resolve.per-sample`).

use refrast::{CompareOp, DepthState, Profile, Rasterizer};

use super::common::precision;
use super::samples::{positions, sample_fragments};
use crate::oracle::facing::snapped_variants;
use crate::oracle::outline::segment_distance;
use crate::oracle::raster::{depth_bounds, project, window_depth};
use crate::scene::PrimitiveScene;
use crate::scene::Scene;
use crate::violation::{Findings, Violation, plural};

/// Each sample's depth is the snapped triangle's depth plane at the sample's position.
pub fn check_depth(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let frags = sample_fragments(r, case)?;
    let depths: Vec<_> = frags.iter().map(|f| (f.x, f.y, f.sample, f.depth)).collect();
    on_plane(r, case, &depths, "sample fragments")?;
    check_depth_resolved(r, case)
}

/// The depth buffer's samples the triangle wrote hold its depth at their positions (with
/// depth writes on; else the buffer keeps its clear value and says nothing).
pub fn check_depth_resolved(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    if !case.scene.state.depth.write {
        return Ok(());
    }
    let draw = case.draw();
    let resolved = r
        .resolve(&draw)
        .map_err(|e| Violation::of_draw_error("resolve", &e))?;
    let n = usize::from(resolved.samples.max(1));
    let w = case.scene.width as usize;
    let written: Vec<_> = (0..resolved.depth.len().min(resolved.primitive.len()))
        .filter(|&i| resolved.primitive[i] == Some(0))
        .map(|i| {
            let pixel = i / n;
            (
                (pixel % w) as u32,
                (pixel / w) as u32,
                (i % n) as u8,
                resolved.depth[i],
            )
        })
        .collect();
    on_plane(r, case, &written, "depth buffer")
}

/// A triangle's window depth as a plane in screen space, through its vertices as the profile
/// snaps them (without a grid, through the exact ones), with how far from it an answer may be.
pub(super) struct DepthPlane {
    /// The vertices in pixels.
    v: [[f64; 2]; 3],
    /// Their window depths.
    z: [f64; 3],
    /// Twice the signed area, never zero.
    area: f64,
    /// The viewport's depth range, which depth is clamped to.
    bounds: [f64; 2],
    /// How far from the plane a depth may be: twice the claimed precision, plus how far a
    /// snapping variant may move the plane (its slope times the band, both ways).
    pub tolerance: f64,
}

impl DepthPlane {
    /// Triangle `t` of `scene` for an implementation with `profile`; `None` when a vertex does
    /// not project onto the grid or the snapped triangle has no area.
    pub fn of(profile: &Profile, scene: &Scene, t: usize) -> Option<Self> {
        let (w, h) = (scene.width, scene.height);
        let corners = scene.corners(t);
        let v = match profile.snapping.grid_bits() {
            Some(bits) => {
                let variants = snapped_variants(&corners, w, h, profile)?;
                let one = f64::from(1u32 << bits.min(16));
                variants[0].map(|p| [p.0 as f64 / one, p.1 as f64 / one])
            }
            None => scene.positions_of(t).map(|p| project(w, h, p)),
        };
        let z = corners.map(|p| window_depth(&scene.state, f64::from(p[2]) / f64::from(p[3])));
        let area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
        if area == 0.0 || !area.is_finite() {
            return None;
        }
        let mut plane = Self {
            v,
            z,
            area,
            bounds: depth_bounds(&scene.state),
            tolerance: 0.0,
        };
        let slope = (plane.unclamped([1.0, 0.0]) - plane.unclamped([0.0, 0.0])).abs()
            + (plane.unclamped([0.0, 1.0]) - plane.unclamped([0.0, 0.0])).abs();
        plane.tolerance = 2.0 * precision(profile) + slope * 2.0 * profile.band_px();
        Some(plane)
    }

    /// The plane's value at `s`, before clamping.
    fn unclamped(&self, s: [f64; 2]) -> f64 {
        let v = &self.v;
        let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]);
        (e(v[1], v[2]) * self.z[0] + e(v[2], v[0]) * self.z[1] + e(v[0], v[1]) * self.z[2]) / self.area
    }

    /// The window depth at `s` in pixels, clamped to the viewport's depth range.
    pub fn at(&self, s: [f64; 2]) -> f64 {
        self.unclamped(s).clamp(self.bounds[0], self.bounds[1])
    }
}

/// Where sample `k` of pixel `(x, y)` lies, in pixels.
pub(super) fn sample_at(positions: &[[u8; 2]], x: u32, y: u32, k: u8) -> [f64; 2] {
    let [u, v] = positions.get(usize::from(k)).copied().unwrap_or([8, 8]);
    [
        f64::from(x) + f64::from(u) / 16.0,
        f64::from(y) + f64::from(v) / 16.0,
    ]
}

/// Each `(x, y, sample, depth)` of triangle 0 lies on its depth plane at the sample's declared
/// position, within the precision and what snapping may move the plane.
fn on_plane(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    depths: &[(u32, u32, u8, f32)],
    what: &str,
) -> Result<(), Violation> {
    let profile = r.profile();
    let positions = positions(r, case);
    let Some(plane) = DepthPlane::of(&profile, &case.scene, 0) else {
        return Ok(());
    };
    let mut found = Findings::new();
    for &(x, y, sample, depth) in depths {
        let want = plane.at(sample_at(&positions, x, y, sample));
        let got = f64::from(depth);
        if (got - want).abs() > plane.tolerance {
            found.add((x, y), || {
                let centre = plane.at([f64::from(x) + 0.5, f64::from(y) + 0.5]);
                format!(
                    "({x}, {y}) sample {sample}: depth {got}, expected {want} at the sample (the pixel centre's is {centre})"
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "{} of the {what} carry another depth than at their sample's position",
            plural(n, "sample")
        )
    })
}

/// `resolve` equals the draw's sample fragments replayed through its depth test in
/// primitive order, each with the depth the test must use: the triangle's own at that sample's
/// position (its depth plane), not the depth a fragment reports (Vulkan's FragCoord.z is free to
/// be the pixel centre's). Samples within the band of an edge are not judged (coverage there is
/// the coverage rules' question), nor those where two depths the test compares are within
/// their tolerance of each other (either may win).
pub fn check_resolve(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let draw = case.draw();
    let got = r
        .resolve(&draw)
        .map_err(|e| Violation::of_draw_error("resolve", &e))?;
    let frags = sample_fragments(r, case)?;
    let n = usize::from(case.samples);
    let (w, h) = (case.scene.width, case.scene.height);
    let cells = (w * h) as usize * n;
    if got.depth.len() != cells || got.primitive.len() != cells {
        return Err(Violation::new(format!(
            "resolve gave {} depths and {} primitives for {cells} samples",
            got.depth.len(),
            got.primitive.len(),
        )));
    }
    let profile = r.profile();
    let positions = positions(r, case);
    let band = profile.band_px();
    let scene = &case.scene;
    let planes: Vec<Option<DepthPlane>> = (0..scene.triangles.len())
        .map(|t| DepthPlane::of(&profile, scene, t))
        .collect();
    let mut covering: Vec<Vec<u32>> = vec![Vec::new(); cells];
    for f in &frags {
        covering[(f.y * w + f.x) as usize * n + usize::from(f.sample)].push(f.primitive);
    }
    let depth = scene.state.depth;
    let mut found = Findings::new();
    let edges = Edges::of(scene, band);
    for (i, primitives) in covering.iter_mut().enumerate() {
        let (pixel, k) = (i / n, (i % n) as u8);
        let (x, y) = (pixel as u32 % w, pixel as u32 / w);
        let s = sample_at(&positions, x, y, k);
        if edges.near(s) {
            continue;
        }
        primitives.sort_unstable();
        let Some((want, id)) = replay(primitives, &planes, depth, s) else {
            continue;
        };
        let depth_ok = match want {
            Some((d, tolerance)) => (f64::from(got.depth[i]) - d).abs() <= tolerance,
            None => got.depth[i].to_bits() == depth.clear.to_bits(),
        };
        if !depth_ok || got.primitive[i] != id {
            found.add((x, y), || {
                let expected = want.map_or(format!("{} (the clear value)", depth.clear), |(d, t)| format!("{d} ± {t:.1e}"));
                format!(
                    "({x}, {y}) sample {k}: resolved ({}, {:?}), its fragments replayed at each sample's own depth ({expected}, {id:?})",
                    got.depth[i], got.primitive[i]
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "{} resolved otherwise than the draw's fragments replayed through its depth test at each sample's own depth",
            plural(n, "sample")
        )
    })
}

/// The triangles of a scene whose vertices all project (one that does not is drawn nowhere
/// near by these rules), projected once, each with its box grown by the band: a sample outside
/// a box is farther than the band from that triangle's edges, so only triangles whose box
/// holds it are measured (issue 47: every sample measured every edge).
struct Edges {
    band: f64,
    triangles: Vec<([[f64; 2]; 3], [f64; 4])>,
}

impl Edges {
    /// The projected triangles of `scene`, boxes grown by `band` and a margin of `2^-30` of the
    /// largest coordinate: [`segment_distance`]'s nearest point lies within a few ulps of it.
    fn of(scene: &Scene, band: f64) -> Self {
        let triangles = (0..scene.triangles.len())
            .map(|t| scene.positions_of(t))
            .filter(|p| p.iter().all(|v| v[3] > 0.0))
            .map(|p| {
                let c = p.map(|v| project(scene.width, scene.height, v));
                let size = c.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
                let grow = band + size / 1_073_741_824.0;
                let (xs, ys) = (c.map(|v| v[0]), c.map(|v| v[1]));
                let low = |v: [f64; 3]| v.iter().fold(f64::INFINITY, |m, &x| m.min(x)) - grow;
                let high = |v: [f64; 3]| v.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x)) + grow;
                (c, [low(xs), high(xs), low(ys), high(ys)])
            })
            .collect();
        Edges { band, triangles }
    }

    /// Whether `s` lies within the band of an edge of a projected triangle (a box with a NaN
    /// holds nothing, as the distance to a NaN corner is never within the band).
    fn near(&self, s: [f64; 2]) -> bool {
        self.triangles.iter().any(|(c, [x0, x1, y0, y1])| {
            (*x0..=*x1).contains(&s[0])
                && (*y0..=*y1).contains(&s[1])
                && (0..3).any(|e| segment_distance(c[e], c[(e + 1) % 3], s) < self.band)
        })
    }
}

/// What a replay leaves at a sample: the depth written with its tolerance (`None`: the clear
/// value), and the last primitive to pass.
type Replayed = (Option<(f64, f64)>, Option<u32>);

/// The depth test replayed at sample `s` over `covering` (in primitive order) with each
/// triangle's depth there: the depth left written (with its tolerance; `None` when nothing was
/// written) and the last primitive to pass. `None` when the outcome is not sure: a depth the
/// test compares is within the tolerance of the stored one, or a triangle has no plane.
fn replay(
    covering: &[u32],
    planes: &[Option<DepthPlane>],
    test: DepthState,
    s: [f64; 2],
) -> Option<Replayed> {
    let mut stored: Option<(f64, f64)> = None;
    let mut id = None;
    for &p in covering {
        let plane = planes.get(p as usize)?.as_ref()?;
        let d = plane.at(s);
        let (against, slack) = stored.unwrap_or((f64::from(test.clear), 0.0));
        let decided = matches!(test.compare, CompareOp::Never | CompareOp::Always);
        if !decided && (d - against).abs() <= plane.tolerance + slack {
            return None;
        }
        if test.compare.passes(d as f32, against as f32) {
            id = Some(p);
            if test.write {
                stored = Some((d, plane.tolerance));
            }
        }
    }
    Some((stored, id))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Whether `s` is within `band` of an edge of a projecting triangle, every edge measured.
    fn near_directly(scene: &Scene, s: [f64; 2], band: f64) -> bool {
        (0..scene.triangles.len()).any(|t| {
            let p = scene.positions_of(t);
            p.iter().all(|v| v[3] > 0.0) && {
                let c = p.map(|v| project(scene.width, scene.height, v));
                (0..3).any(|e| segment_distance(c[e], c[(e + 1) % 3], s) < band)
            }
        })
    }

    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![
            12 => -2.0f32..2.0,
            1 => -1e30f32..1e30,
            1 => Just(f32::NAN),
            1 => Just(f32::INFINITY)
        ]
    }

    proptest! {
        /// Boxes skip only samples no edge is within the band of, whatever the coordinates.
        #[test]
        fn boxes_skip_only_far_samples(
            corners in prop::collection::vec(
                (coordinate(), coordinate(), -1.0f32..1.0, prop_oneof![6 => 0.1f32..4.0, 1 => -1.0f32..0.0])
                    .prop_map(|(x, y, z, w)| [x, y, z, w]),
                3..7,
            ),
            band in prop_oneof![Just(0.0), Just(1.0 / 256.0), Just(0.5), Just(3.0)],
            s in [0.0f64..16.0, 0.0f64..16.0],
            along in (0usize..6, prop_oneof![Just(0.0), 0.0f64..1.0], -1.5f64..1.5),
        ) {
            let triangles = (0..corners.len() / 3).map(|t| {
                let i = u32::try_from(3 * t).unwrap_or(0);
                [i, i + 1, i + 2]
            }).collect();
            let scene = Scene::new(16, 16, corners, triangles);
            // Half the samples lie across the first triangle's edge or beside a corner, across
            // or along an axis, where a box too small shows.
            let c = scene.positions_of(0).map(|v| project(16, 16, v));
            let (e, t, off) = along;
            let (a, b) = (c[e % 3], c[(e + 1) % 3]);
            let step = if e < 3 { [off * band, 0.0] } else { [0.0, off * band] };
            let across = [a[0] + t * (b[0] - a[0]) + step[0], a[1] + t * (b[1] - a[1]) + step[1]];
            let s = if off > 0.0 && across.iter().all(|v| v.is_finite()) { across } else { s };
            prop_assert_eq!(Edges::of(&scene, band).near(s), near_directly(&scene, s, band));
        }
    }
}
