//! How far a clipper computing in f32 may move a cut that a clip plane makes.
//!
//! Clip coordinates are f32, and Vulkan bounds no clipping precision: a clipper may compute
//! each cut vertex `A + t(B − A)`, `t = d_A / (d_A − d_B)`, in f32. Each such step rounds
//! the vertex within a few ulps of the coordinates it comes from, and a polygon clipped by up
//! to six planes gathers up to six steps: at most about 28 ulps of the largest coordinate, so
//! `2^-19` of it ([`CLIP_ROUNDING`]) bounds the error `E` of every clip-space component.
//! Cut vertices are convex combinations of the input vertices, so near a sample whose ray hits
//! the triangle's plane at `X = Σ bᵢ Vᵢ`, `E ≤ 2^-19 · Σ |bᵢ| |Vᵢ|∞`. That moves the cut two
//! ways: the plane distance `d` (a sum of two coordinates, so off by `2E`) of the computed cut
//! is zero where the exact one is within `2E`, which lies `2E / |∇d|` pixels away; and the cut
//! vertices' x, y and w move their projection by `E · (1 + |x/w| + |y/w|) / w` in NDC.
//!
//! For an f32 clipper these are real: lavapipe's clipper covers a sample 0.005 px beyond a far-plane
//! cut that runs from a vertex at x = −30000, w = 0 (`clip_rounding_covers_lavapipes_far_cut`).

use refrast::DrawState;

use super::spread::{CANCELLATION, plane_at};
use crate::oracle::raster::{near_distance, to_ndc};

/// Bound on the rounding of a cut vertex's clip coordinates, relative to the largest
/// coordinate it comes from: 32 units in the last place of f32 (`2^-24`), above the 28 of six
/// clipping steps.
pub const CLIP_ROUNDING: f64 = 1.0 / 524_288.0;

#[cfg(test)]
pub(crate) mod reference;
mod row;

/// How much wider [`CutRounding`]'s own cancellation checks take each magnitude than
/// [`plane_at`] does: 2^-16, far above the 2^-28 by which their sums may differ (some 20
/// roundings each, times the 2^20 of `CANCELLATION`), so a point they pass `plane_at` passes.
const CHECK_MARGIN: f64 = 1.0 + 1.0 / 65_536.0;

/// `c[0] + c[1]·nx + c[2]·ny`: the form of every sum [`plane_at`] divides by or into.
fn affine(c: [f64; 3], [nx, ny]: [f64; 2]) -> f64 {
    c[0] + c[1] * nx + c[2] * ny
}

/// `c[0] + c[1]·|nx| + c[2]·|ny| + c[3]·|nx||ny|`: the form of [`plane_at`]'s magnitudes.
fn bilinear(c: [f64; 4], [nx, ny]: [f64; 2]) -> f64 {
    let (ax, ay) = (nx.abs(), ny.abs());
    c[0] + c[1] * ax + c[2] * ay + c[3] * ax * ay
}

/// `|(x, y)|` by a square root, within 2 ulps, where the squares neither overflow nor
/// underflow (hypot takes several times as long); by hypot elsewhere.
fn length(x: f64, y: f64) -> f64 {
    let squared = x * x + y * y;
    if squared.is_normal() {
        squared.sqrt()
    } else {
        x.hypot(y)
    }
}

/// Whether `sum` is settled for terms of total `magnitude` with [`CHECK_MARGIN`] to spare.
fn clear(sum: f64, magnitude: f64) -> bool {
    let wide = magnitude * CHECK_MARGIN;
    sum.is_finite() && wide.is_finite() && wide <= CANCELLATION * sum.abs()
}

/// The plane of a triangle as [`plane_at`] evaluates it, set up once for every NDC point.
///
/// With `u = x − nx·w`, `v = y − ny·w`, each `nᵢ = uⱼvₖ − uₖvⱼ` is exactly affine in
/// `(nx, ny)` (the `nx·ny` terms cancel), so every sum of them is too, and the magnitudes
/// `plane_at` checks them against are bilinear in `(|nx|, |ny|)`.
#[derive(Clone, Debug)]
struct Plane {
    /// `nᵢ`, the barycentrics' numerators.
    n: [[f64; 3]; 3],
    /// `Σ nᵢ`, `Σ nᵢwᵢ` and `Σ nᵢzᵢ`: the barycentrics' denominator, then depth's.
    sums: [[f64; 3]; 3],
    /// The magnitudes of the three sums' terms.
    magnitudes: [[f64; 4]; 3],
}

impl Plane {
    fn new(tri: &[[f64; 4]; 3]) -> Self {
        let pairs = [(1, 2), (2, 0), (0, 1)];
        let n = pairs.map(|(j, k)| {
            let (a, b) = (tri[j], tri[k]);
            [
                a[0] * b[1] - b[0] * a[1],
                b[3] * a[1] - a[3] * b[1],
                b[0] * a[3] - a[0] * b[3],
            ]
        });
        let an = pairs.map(|(j, k)| {
            let (a, b) = (tri[j].map(f64::abs), tri[k].map(f64::abs));
            [
                a[0] * b[1] + b[0] * a[1],
                a[3] * b[1] + b[3] * a[1],
                a[0] * b[3] + b[0] * a[3],
                2.0 * a[3] * b[3],
            ]
        });
        let weights = [[1.0; 3], tri.map(|p| p[3]), tri.map(|p| p[2])];
        let sums = weights.map(|f| std::array::from_fn(|c| (0..3).map(|i| n[i][c] * f[i]).sum()));
        let magnitudes =
            weights.map(|f| std::array::from_fn(|c| (0..3).map(|i| an[i][c] * f[i].abs()).sum()));
        Self { n, sums, magnitudes }
    }

    /// Whether [`plane_at`] surely evaluates the plane at NDC `p`, given `Σ nᵢ` there: its
    /// three cancellation checks, each with [`CHECK_MARGIN`] to spare.
    fn surely_settled(&self, p: [f64; 2], d: f64) -> bool {
        let [ad, aw, az] = self.magnitudes.map(|c| bilinear(c, p));
        let (ws, zs) = (affine(self.sums[1], p), affine(self.sums[2], p));
        clear(d, ad) && clear(ws, aw) && clear(ws, az + (zs / ws).abs() * aw)
    }

    /// Whether [`plane_at`] surely evaluates the plane everywhere in the NDC square
    /// `[-1, 1]²`, the view: `Σ nᵢ` and `Σ nᵢwᵢ`, affine, keep one sign over it and stay
    /// twice their terms' largest magnitude (at the corners) over `CANCELLATION` from zero; a
    /// factor far above any rounding of these bounds.
    fn settled_in_view(&self) -> bool {
        let corners = [[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0], [1.0, 1.0]];
        let [ad, aw, az] = self.magnitudes.map(|c| bilinear(c, [1.0, 1.0]));
        let least = |c: [f64; 3]| {
            let at = corners.map(|p| affine(c, p));
            let same = at.iter().all(|&v| v > 0.0) || at.iter().all(|&v| v < 0.0);
            if same {
                at.iter().fold(f64::INFINITY, |m, v| m.min(v.abs()))
            } else {
                0.0
            }
        };
        let (d, ws) = (least(self.sums[0]), least(self.sums[1]));
        let zs = corners
            .iter()
            .fold(0.0f64, |m, &p| m.max(affine(self.sums[2], p).abs()));
        let sure = |least: f64, magnitude: f64| {
            let wide = 2.0 * magnitude;
            wide.is_finite() && wide <= CANCELLATION * least
        };
        sure(d, ad) && sure(ws, aw) && sure(ws, az + zs / ws * aw)
    }
}

/// How far, in pixels, an f32 clipper may move the cuts of one triangle near any sample: set
/// up once per triangle, since it runs for every sample of every clipped one.
#[derive(Clone, Debug)]
pub struct CutRounding {
    tri: [[f64; 4]; 3],
    width: u32,
    height: u32,
    state: DrawState,
    plane: Plane,
    /// Whether [`plane_at`] evaluates the plane everywhere in view, so no sample needs checks.
    settled_in_view: bool,
    /// For the signed distance to each plane that cuts (the first `cuts`), the numerators of
    /// its central differences along x and along y, affine in the other coordinate.
    differences: [[[f64; 2]; 2]; 3],
    cuts: usize,
    /// Each vertex's largest coordinate, which bounds its rounding.
    size: [f64; 3],
}

/// Whether plane `k` (w = 0, near, far) clips a draw in `state`.
fn cuts_at(state: &DrawState, k: usize) -> bool {
    [true, state.clip_near, state.clip_far][k]
}

impl CutRounding {
    /// The bound for clip-space triangle `tri` in a `width` × `height` viewport.
    #[must_use]
    pub fn new(tri: &[[f64; 4]; 3], width: u32, height: u32, state: &DrawState) -> Self {
        let range = state.depth_range;
        // The signed distances to the planes that clip: w = 0, near and far when enabled.
        let distance = |plane: usize, p: &[f64; 4]| match plane {
            0 => p[3],
            1 => near_distance(range, p[2], p[3]),
            _ => p[3] - p[2],
        };
        let plane = Plane::new(tri);
        let mut differences = [[[0.0; 2]; 2]; 3];
        let mut cuts = 0;
        for k in 0..3 {
            if cuts_at(state, k) && tri.iter().any(|v| distance(k, v) < 0.0) {
                let f = tri.map(|v| distance(k, &v));
                let [n0, nx, ny]: [f64; 3] =
                    std::array::from_fn(|c| (0..3).map(|i| plane.n[i][c] * f[i]).sum());
                let [d0, dx, dy] = plane.sums[0];
                // For affine N and D along a line, N(r)/D(r) − N(l)/D(l) is
                // (r − l)(N′D − ND′)/(D(r)D(l)): no difference of nearly equal quotients.
                differences[cuts] = [
                    [nx * d0 - dx * n0, nx * dy - dx * ny],
                    [ny * d0 - dy * n0, ny * dx - dy * nx],
                ];
                cuts += 1;
            }
        }
        Self {
            tri: *tri,
            width,
            height,
            state: *state,
            settled_in_view: plane.settled_in_view(),
            plane,
            differences,
            cuts,
            size: tri.map(|v| v.iter().fold(0.0f64, |m, c| m.max(c.abs()))),
        }
    }

    /// How far, in pixels, the cuts may move near raster point `s`: 0 when no plane cuts the
    /// triangle, infinity where the triangle's plane cannot be evaluated there (seen edge-on).
    #[must_use]
    pub fn at(&self, s: [f64; 2]) -> f64 {
        if self.cuts == 0 {
            return 0.0;
        }
        // The sample, then the central differences' points: left, right, up, down.
        let h = 0.5;
        // Three columns and three rows: six divisions, not ten.
        let [[nx, ny], [left, up], [right, down]] =
            [0.0, -h, h].map(|o| to_ndc(self.width, self.height, s[0] + o, s[1] + o));
        let points = [[nx, ny], [left, ny], [right, ny], [nx, up], [nx, down]];
        let in_view = self.settled_in_view && points.iter().all(|p| p[0].abs() <= 1.0 && p[1].abs() <= 1.0);
        let d = points.map(|p| affine(self.plane.sums[0], p));
        for (&p, &dp) in points.iter().zip(&d) {
            // Only near the threshold does plane_at itself decide, exactly as before.
            if !in_view
                && !self.plane.surely_settled(p, dp)
                && plane_at(&self.tri, p[0], p[1], &self.state).is_none()
            {
                return f64::INFINITY;
            }
        }
        // w = Σ nᵢwᵢ / Σ nᵢ at the sample, both settled: their signs are sure.
        let ws = affine(self.plane.sums[1], points[0]);
        if (ws > 0.0) != (d[0] > 0.0) {
            // The plane is behind the eye along this ray: nothing visible projects here.
            return 0.0;
        }
        // Σ |bᵢ| |Vᵢ|∞ times |Σ nᵢ|, and then the error E of the module's doc.
        let sizes: f64 = (0..3)
            .map(|i| affine(self.plane.n[i], points[0]).abs() * self.size[i])
            .sum();
        let e = CLIP_ROUNDING * sizes / d[0].abs();
        let half = f64::from(self.width.max(self.height)) * 0.5;
        // E / w is CLIP_ROUNDING · sizes / |Σ nᵢwᵢ|.
        let moved = CLIP_ROUNDING * sizes / ws.abs() * (1.0 + nx.abs() + ny.abs()) * half;
        // The central differences (value(right) − value(left)) / 2h and (down − up) / 2h of
        // each distance's value Σ bᵢdᵢ, as one quotient each.
        let along_x = (points[2][0] - points[1][0]) / (d[2] * d[1] * (2.0 * h));
        let along_y = (points[4][1] - points[3][1]) / (d[4] * d[3] * (2.0 * h));
        let across = self.differences[..self.cuts]
            .iter()
            .map(|[x, y]| {
                let gradient = length((x[0] + x[1] * ny) * along_x, (y[0] + y[1] * nx) * along_y);
                2.0 * e / gradient
            })
            .fold(0.0, f64::max);
        moved + across
    }
}

/// How far, in pixels, an f32 clipper may move the cuts of `tri` near raster point `s`: 0 when
/// no plane cuts the triangle, infinity where the triangle's plane cannot be evaluated there
/// (seen edge-on). For many samples of one triangle, [`CutRounding`] sets up once (the rules
/// do; the tests ask one sample at a time).
#[cfg(test)]
fn cut_rounding_px(tri: &[[f64; 4]; 3], width: u32, height: u32, s: [f64; 2], state: &DrawState) -> f64 {
    CutRounding::new(tri, width, height, state).at(s)
}

#[cfg(test)]
mod tests {
    use refrast::{CullMode, DepthRange, DrawState};

    use super::*;
    use crate::oracle::outline::{distance_to_outline, visible_outline};
    use crate::oracle::raster::sample_centre;
    use crate::rules::mesh::{Relax, mesh_expectation};
    use crate::scene::Scene;
    use crate::violation::Expect;

    fn far_clipped() -> DrawState {
        DrawState {
            cull: CullMode::None,
            clip_far: true,
            depth_range: DepthRange::ZeroToOne,
            ..DrawState::default()
        }
    }

    /// The distance from pixel `(x, y)`'s sample to the cuts of `scene`'s triangle, and how
    /// far rounding may move them there.
    fn cut_and_rounding(scene: &Scene, x: u32, y: u32) -> (f64, f64) {
        let tri = scene.positions_of(0);
        let s = sample_centre(x, y);
        let outline = visible_outline(&tri, scene.width, scene.height, &scene.state);
        let d = distance_to_outline(&outline, s, |a, b| a.edges & b.edges == 0);
        (
            d,
            cut_rounding_px(&tri, scene.width, scene.height, s, &scene.state),
        )
    }

    /// lavapipe's `clip.interior` counterexample (case 612 at the default seed): it covers
    /// (12, 29), 0.005 px beyond a far-plane cut running from a vertex at x = −30000, w = 0.
    /// Before the cuts knew about rounding, that sample had to stay uncovered.
    #[test]
    fn clip_rounding_covers_lavapipes_far_cut() {
        let mut scene = Scene::new(
            16,
            32,
            vec![
                [2.395_028_4, 0.0, 1.855_659_2, 1.855_659_2],
                [0.0, -3000.0, -0.080_122_16, -0.1],
                [-30000.0, 1.276_549_9, -0.230_131_86, 0.0],
            ],
            vec![[0, 1, 2]],
        );
        scene.state = far_clipped();
        let (d, r) = cut_and_rounding(&scene, 12, 29);
        assert!(d > 1.0 / 256.0, "outside the band: {d}");
        assert!(d < 1.0 / 256.0 + r, "within rounding: {d} vs {r}");
        let (expected, _) = mesh_expectation(&scene, 1.0 / 256.0, Relax::NONE);
        assert_eq!(expected[29 * 16 + 12], Expect::ZeroOrOne);
    }

    /// llvmpipe's and softpipe's (case 1597): vertices at x = −44078 and y = −32420.
    #[test]
    fn clip_rounding_covers_llvmpipes_near_cut() {
        let mut scene = Scene::new(
            39,
            64,
            vec![
                [0.0, 0.202_146_25, 0.0, 0.2],
                [-44_078.234, 0.0, 2.702_006, 2.274_348_3],
                [-1.688_258_2, -32_420.537, -0.415_350_94, 1.907_600_2],
            ],
            vec![[0, 1, 2]],
        );
        scene.state = far_clipped();
        let (expected, _) = mesh_expectation(&scene, 1.0 / 256.0, Relax::NONE);
        let strict = |x: u32, y: u32| {
            let (d, r) = cut_and_rounding(&scene, x, y);
            d >= 1.0 / 256.0 && d < 1.0 / 256.0 + r
        };
        let loosened: Vec<_> = (0..64)
            .flat_map(|y| (0..39).map(move |x| (x, y)))
            .filter(|&(x, y)| strict(x, y))
            .collect();
        assert!(
            !loosened.is_empty(),
            "some sample depends on the clipper's rounding"
        );
        for (x, y) in loosened {
            assert_eq!(expected[(y * 39 + x) as usize], Expect::ZeroOrOne, "({x}, {y})");
        }
    }

    /// Near the view volume (coordinates within 1.5) the rounding stays under half the 1/256-px
    /// band of an 8-bit grid (0.28 of it at worst here), so cuts are judged nearly as sharply as
    /// before.
    #[test]
    fn ordinary_cuts_move_by_little() {
        let tri = [
            [-0.5, -0.5, -0.5, 1.0],
            [0.9, -0.2, 0.7, 1.5],
            [0.1, 0.8, 1.4, 1.2],
        ];
        let state = far_clipped();
        let worst = (0..64)
            .flat_map(|y| (0..64).map(move |x| sample_centre(x, y)))
            .map(|s| cut_rounding_px(&tri, 64, 64, s, &state))
            .fold(0.0, f64::max);
        assert!(worst < 0.5 / 256.0, "{worst}");
    }

    /// Nothing cut, nothing moved.
    #[test]
    fn uncut_triangles_have_no_rounding() {
        let tri = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, 1.0],
        ];
        assert_eq!(cut_rounding_px(&tri, 16, 16, [8.0, 8.0], &far_clipped()), 0.0);
    }
}
