//! Why a coverage check failed, sample by sample: the mechanism each wrong sample has evidence for.
//!
//! A count of missing or double-covered samples says where, not why. For each wrong sample this
//! names what the oracles know there: the triangles that cover it, the edge two of them share
//! and how far the sample lies from it, the clip plane that cut that edge and where, and for a
//! sample the ray cast sees, the `w` of the visible point it hits, so that a student can tell a
//! missing tie rule from an edge function that is not antisymmetric, a cut taken from the wrong
//! end or a visible part discarded for its small `w`.

use std::collections::HashMap;

use refrast::{DepthRange, Fragment};

use super::ties;
use crate::oracle::outline::{OutlinePoint, segment_distance, visible_outline};
use crate::oracle::raster::{near_distance, project, sample_centre, sample_ndc};
use crate::oracle::ray_cast::ray_cast;
use crate::scene::Scene;
use crate::violation::{Class, Findings};

/// Below this many pixels from a shared edge, a sample is closer to it than an f32 edge
/// function resolves (2^-24 of a 64-px product is about 4·10^-6 px), though not exactly on it.
const HAIR_PX: f64 = 1e-4;

/// Below this many pixels from an edge whose ends do not project exactly, a sample may lie on it:
/// a distance computed in doubles from a projection in doubles is off by about 10^-15 px.
const ON_EDGE_PX: f64 = 1e-12;

/// A hit whose `w` is below this fraction of the triangle's largest `|w|` is "tiny": a visible
/// point so near the eye that a client's w-epsilon (often 10^-5 to 10^-3) may discard it.
const TINY_W: f64 = 1e-4;

/// Each wrong sample of a coverage comparison (`classes`, row-major) with what the oracles know
/// about it, for a rasterizer snapping to a grid of `grid` bits (or none): the first few
/// described ([`Findings::DESCRIBED`]).
#[must_use]
pub fn describe(scene: &Scene, frags: &[Fragment], classes: &[Class], grid: Option<u8>) -> Findings {
    let scene_view = View::of(scene, grid);
    let mut by_sample: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    for f in frags {
        by_sample.entry((f.x, f.y)).or_default().push(f.primitive);
    }
    let mut findings = Findings::new();
    for (i, class) in classes.iter().enumerate() {
        let (x, y) = (i as u32 % scene.width, i as u32 / scene.width);
        if !matches!(class, Class::Missing | Class::Unexpected | Class::Double) {
            continue;
        }
        let covering = by_sample.get(&(x, y)).cloned().unwrap_or_default();
        findings.add((x, y), || scene_view.sample(x, y, *class, &covering));
    }
    findings
}

/// What the explanation needs of the scene, computed once.
struct View<'a> {
    scene: &'a Scene,
    tris: Vec<[[f64; 4]; 3]>,
    outlines: Vec<Vec<OutlinePoint>>,
    /// Per triangle and edge k, the other triangle sharing that edge (identical end points).
    partners: Vec<[Option<usize>; 3]>,
    /// The bits of the rasterizer's grid, or none.
    grid: Option<u8>,
}

impl<'a> View<'a> {
    fn of(scene: &'a Scene, grid: Option<u8>) -> Self {
        let valid = |t: &[u32; 3]| t.iter().all(|&i| (i as usize) < scene.positions.len());
        let tris: Vec<[[f64; 4]; 3]> = (0..scene.triangles.len())
            .map(|t| {
                if valid(&scene.triangles[t]) {
                    scene.positions_of(t)
                } else {
                    [[0.0; 4]; 3]
                }
            })
            .collect();
        let outlines = tris
            .iter()
            .map(|t| visible_outline(t, scene.width, scene.height, &scene.state))
            .collect();
        let key = |i: u32| scene.positions.get(i as usize).map(|p| p.map(f32::to_bits));
        let edge = |t: &[u32; 3], k: usize| {
            let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
            if a <= b { (a, b) } else { (b, a) }
        };
        let mut users: HashMap<_, Vec<usize>> = HashMap::new();
        for (t, tri) in scene.triangles.iter().enumerate() {
            for k in 0..3 {
                users.entry(edge(tri, k)).or_default().push(t);
            }
        }
        let partners = scene
            .triangles
            .iter()
            .enumerate()
            .map(|(t, tri)| std::array::from_fn(|k| users[&edge(tri, k)].iter().copied().find(|&u| u != t)))
            .collect();
        Self {
            scene,
            tris,
            outlines,
            partners,
            grid,
        }
    }

    /// One wrong sample in words.
    fn sample(&self, x: u32, y: u32, class: Class, covering: &[u32]) -> String {
        let at = format!("sample ({x}, {y})");
        let mut distinct: Vec<usize> = covering.iter().map(|&p| p as usize).collect();
        distinct.sort_unstable();
        distinct.dedup();
        match class {
            Class::Double if distinct.len() >= 2 => self.both(&at, x, y, distinct[0], distinct[1]),
            Class::Double => {
                let t = distinct.first().copied().unwrap_or(0);
                format!(
                    "{at} is covered {} times by triangle {t} alone{}",
                    covering.len(),
                    if self.is_clipped(t) {
                        ", whose clipped polygon's fan triangles overlap there or both own their shared diagonal"
                    } else {
                        ": a triangle covers each sample at most once"
                    }
                )
            }
            Class::Missing => self.missing(&at, x, y),
            _ => self.unexpected(&at, x, y, &distinct),
        }
    }

    /// A sample covered by triangles `t` and `u`.
    fn both(&self, at: &str, x: u32, y: u32, t: usize, u: usize) -> String {
        let s = sample_centre(x, y);
        let Some(k) = (0..3).find(|&k| self.partners.get(t).and_then(|p| p[k]) == Some(u)) else {
            return format!(
                "{at} is covered by both triangles {t} and {u}, which share no edge: {}",
                self.nearest_words(t, s)
            );
        };
        let edge = self.edge_name(t, k);
        let d = self.edge_distance(t, k, s);
        if let Some(cut) = self.cut_on_edge(t, k) {
            return format!(
                "{at} is covered by both triangles {t} and {u}, which share the {edge}; {} crosses it at ({:.4}, {:.4}) px and \
                 the sample lies {} from the edge: both triangles must cut the shared edge at the same point, so compute the \
                 intersection from the same end of the edge in both (the inside one), not from whichever vertex comes first",
                self.planes_of(t),
                cut[0],
                cut[1],
                px(d)
            );
        }
        self.on_shared(at, (x, y), "covered by both", (t, k, u), d)
    }

    /// The words for sample `(x, y)` on (or a hair from) edge `k` of triangle `t`, which
    /// triangle `u` shares, `d` px from it. Exactly on it is decided in integers where its ends
    /// project exactly onto a fine grid (a distance in doubles is off by 10^-16 there); else a
    /// sample closer than doubles resolve may be on it, and both mechanisms are named.
    fn on_shared(
        &self,
        at: &str,
        (x, y): (u32, u32),
        how: &str,
        (t, k, u): (usize, usize, usize),
        d: f64,
    ) -> String {
        let edge = self.edge_name(t, k);
        let ends = [k, (k + 1) % 3].map(|j| self.scene.positions[self.scene.triangles[t][j] as usize]);
        let (w, h) = (self.scene.width, self.scene.height);
        let tie = "a sample on a shared edge belongs to exactly one of the two, as the tie rule decides (top-left: the \
                   triangle for which it is a top or a left edge), so an edge test of `e >= 0` or `e > 0` alone is not enough";
        let antisymmetric = "the edge function must be antisymmetric, E_ab(p) = −E_ba(p) exactly, as it is when both \
                             evaluate it from the same end of the edge";
        match ties::exactly_on_line(ends[0], ends[1], (w, h), self.grid, (x, y)) {
            Some(true) => format!(
                "{at} lies exactly on the {edge}, shared by triangles {t} and {u}, and is {how}: {tie}"
            ),
            Some(false) if d < HAIR_PX => format!(
                "{at} lies {} from the {edge} (not on it, as integers tell), shared by triangles {t} and {u}, and is {how}: \
                 closer than rounding resolves, so the two triangles' edge functions disagree about it; {antisymmetric}",
                px(d)
            ),
            None if d < ON_EDGE_PX => format!(
                "{at} lies on the {edge} as far as doubles tell ({} from it), shared by triangles {t} and {u}, and is \
                 {how}: {tie}; and for the tie rule to see the same zero from both triangles, {antisymmetric}",
                px(d)
            ),
            None if d < HAIR_PX => format!(
                "{at} lies {} from the {edge}, shared by triangles {t} and {u}, and is {how}: closer than rounding \
                 resolves, so the two triangles' edge functions disagree about it; {antisymmetric}",
                px(d)
            ),
            _ => format!(
                "{at} lies {} from the {edge}, shared by triangles {t} and {u}, and is {how}",
                px(d)
            ),
        }
    }

    /// A sample the ray cast sees that nothing covers.
    fn missing(&self, at: &str, x: u32, y: u32) -> String {
        let [nx, ny] = sample_ndc(self.scene.width, self.scene.height, x, y);
        let s = sample_centre(x, y);
        let hit =
            (0..self.tris.len()).find_map(|t| Some((t, ray_cast(&self.tris[t], nx, ny, &self.scene.state)?)));
        let Some((t, hit)) = hit else {
            return format!("{at} is missing: {}", self.nearest_words(0, s));
        };
        let tri = &self.tris[t];
        let w: f64 = (0..3).map(|k| hit.barycentric[k] * tri[k][3]).sum();
        let largest = tri.iter().fold(0.0f64, |m, v| m.max(v[3].abs()));
        let polygon = clipped_w(tri, &self.scene.state);
        let least = polygon.iter().copied().fold(f64::INFINITY, f64::min);
        if w < TINY_W * largest || least < TINY_W * largest {
            return format!(
                "{at}: the ray through it hits triangle {t} at w = {w:.3e}, a visible point (in front of the eye and of the \
                 near plane), but nothing covers it; the triangle's vertices have w = {}; its visible polygon{} has vertices at w = {}: the \
                 expected coverage comes from a visible part with tiny w (down to {least:.3e}), so a w-epsilon that discards \
                 (or culls) a triangle or its clipped polygon for a small w loses it; clip against the planes instead and \
                 keep every w > 0",
                list(tri.iter().map(|v| v[3])),
                if self.is_clipped(t) {
                    format!(" (cut by {})", self.planes_of(t))
                } else {
                    String::new()
                },
                list(polygon.iter().copied())
            );
        }
        // The nearest edge of the triangle hit: on a shared one, neither of two owned it.
        if let Some((k, d)) = self.nearest_edge(t, s)
            && let Some(u) = self.partners[t][k]
            && d < HAIR_PX
        {
            return self.on_shared(at, (x, y), "covered by neither", (t, k, u), d);
        }
        format!(
            "{at} is inside triangle {t} (the ray hits it at w = {w:.4}), but nothing covers it; {}{}",
            self.nearest_words(t, s),
            self.clipped_words(t)
        )
    }

    /// A sample covered by some of `covering` where the ray cast sees nothing.
    fn unexpected(&self, at: &str, x: u32, y: u32, covering: &[usize]) -> String {
        let s = sample_centre(x, y);
        let Some(&t) = covering.first() else {
            return format!("{at} is wrong");
        };
        let tri = &self.tris[t];
        if self.is_clipped(t) && inside_projection(tri, self.scene.width, self.scene.height, s) {
            return format!(
                "{at} is covered by triangle {t} and lies inside the projection of its vertices, but the ray through it \
                 meets the triangle where it is not visible ({}): its vertices have w = {} and z = {}, so that part must \
                 be clipped away (a near plane missing draws it as if w were positive everywhere)",
                self.planes_of(t),
                list(tri.iter().map(|v| v[3])),
                list(tri.iter().map(|v| v[2]))
            );
        }
        format!(
            "{at} is covered by triangle {t}, but {}",
            self.nearest_words(t, s)
        )
    }

    /// "it lies … px outside/inside the edge …" for the nearest outline segment of `t`.
    fn nearest_words(&self, t: usize, s: [f64; 2]) -> String {
        let o = &self.outlines[t];
        let mut best: Option<(f64, String)> = None;
        for i in 0..o.len() {
            let (a, b) = (o[i], o[(i + 1) % o.len()]);
            if !(a.finite && b.finite) {
                continue;
            }
            let d = segment_distance(a.position, b.position, s);
            let common = a.edges & b.edges;
            let name = match (0..3).find(|&k| common & (1 << k) != 0) {
                Some(k) => self.edge_name(t, k),
                None => format!("cut {} made", self.planes_of(t)),
            };
            if best.as_ref().is_none_or(|(bd, _)| d < *bd) {
                best = Some((d, name));
            }
        }
        match best {
            Some((d, name)) => format!("it lies {} from triangle {t}'s {name}", px(d)),
            None => format!("triangle {t} has no visible part"),
        }
    }

    /// Edge `k` of triangle `t` and the distance of `s` from its visible part, if visible.
    fn nearest_edge(&self, t: usize, s: [f64; 2]) -> Option<(usize, f64)> {
        (0..3)
            .map(|k| (k, self.edge_distance(t, k, s)))
            .filter(|(_, d)| d.is_finite())
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// Distance of `s` from the visible part of edge `k` of triangle `t` (infinite if none).
    fn edge_distance(&self, t: usize, k: usize, s: [f64; 2]) -> f64 {
        let o = &self.outlines[t];
        (0..o.len())
            .filter(|&i| {
                let (a, b) = (o[i], o[(i + 1) % o.len()]);
                a.finite && b.finite && a.edges & b.edges & (1 << k) != 0
            })
            .map(|i| segment_distance(o[i].position, o[(i + 1) % o.len()].position, s))
            .fold(f64::INFINITY, f64::min)
    }

    /// Where a clip plane cuts edge `k` of triangle `t`, in pixels, if it does.
    fn cut_on_edge(&self, t: usize, k: usize) -> Option<[f64; 2]> {
        self.outlines[t]
            .iter()
            .find(|p| p.finite && p.is_cut() && p.edges & (1 << k) != 0)
            .map(|p| p.position)
    }

    /// Whether triangle `t`'s visible outline has a point made by a clip plane.
    fn is_clipped(&self, t: usize) -> bool {
        self.outlines[t].iter().any(OutlinePoint::is_cut)
    }

    /// "the edge from vertex i (x, y) to vertex j (x, y)" for edge `k` of triangle `t`.
    fn edge_name(&self, t: usize, k: usize) -> String {
        let (i, j) = (self.scene.triangles[t][k], self.scene.triangles[t][(k + 1) % 3]);
        format!("edge from vertex {i} to vertex {j}")
    }

    /// ", clipped by … to a polygon of n vertices whose w runs from … to …", if clipped.
    fn clipped_words(&self, t: usize) -> String {
        if !self.is_clipped(t) {
            return String::new();
        }
        format!(
            "; {} cuts it to a polygon of {} vertices",
            self.planes_of(t),
            self.outlines[t].len()
        )
    }

    /// The clip planes some vertex of triangle `t` lies beyond, in words.
    fn planes_of(&self, t: usize) -> String {
        let state = &self.scene.state;
        let tri = &self.tris[t];
        let mut planes = Vec::new();
        if tri.iter().any(|v| v[3] <= 0.0) {
            planes.push("w = 0 (the eye)");
        }
        if state.clip_near
            && tri
                .iter()
                .any(|v| near_distance(state.depth_range, v[2], v[3]) < 0.0)
        {
            planes.push(match state.depth_range {
                DepthRange::ZeroToOne => "the near plane z = 0",
                DepthRange::NegativeOneToOne => "the near plane z = −w",
            });
        }
        if state.clip_far && tri.iter().any(|v| v[2] > v[3]) {
            planes.push("the far plane z = w");
        }
        if planes.is_empty() {
            "a clip plane".to_owned()
        } else {
            planes.join(" and ")
        }
    }
}

/// A clip plane as a signed distance: a point is kept when it is `≥ 0`.
type PlaneDistance<'a> = dyn Fn(&[f64; 4]) -> f64 + 'a;

/// The `w` of each vertex of `tri`'s visible polygon: clipped at `w ≥ 0` and the near (and,
/// when enabled, far) plane, as the outline is.
fn clipped_w(tri: &[[f64; 4]; 3], state: &refrast::DrawState) -> Vec<f64> {
    let mut poly: Vec<[f64; 4]> = tri.to_vec();
    let near = |p: &[f64; 4]| {
        if state.clip_near {
            near_distance(state.depth_range, p[2], p[3])
        } else {
            1.0
        }
    };
    let far = |p: &[f64; 4]| if state.clip_far { p[3] - p[2] } else { 1.0 };
    let eye = |p: &[f64; 4]| p[3];
    let planes: [&PlaneDistance<'_>; 3] = [&eye, &near, &far];
    for plane in planes {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (plane(&a), plane(&b));
            if da >= 0.0 {
                out.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                out.push([0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * t));
            }
        }
        poly = out;
    }
    poly.iter().map(|p| p[3]).collect()
}

/// Whether `s` lies inside the projection of `tri`'s three vertices, each divided by its own
/// `w` whatever its sign: what a rasterizer without clipping fills.
fn inside_projection(tri: &[[f64; 4]; 3], width: u32, height: u32, s: [f64; 2]) -> bool {
    if tri.iter().any(|v| v[3] == 0.0) {
        return false;
    }
    let p = tri.map(|v| project(width, height, v));
    let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]);
    let v = [e(p[0], p[1]), e(p[1], p[2]), e(p[2], p[0])];
    v.iter().all(|&x| x > 0.0) || v.iter().all(|&x| x < 0.0)
}

/// A distance in pixels: "exactly 0 px" or in three significant digits.
fn px(d: f64) -> String {
    if d == 0.0 {
        "0 px".to_owned()
    } else {
        format!("{d:.3e} px")
    }
}

/// Numbers as "a, b, c" in four significant digits.
fn list(values: impl Iterator<Item = f64>) -> String {
    values.map(|v| format!("{v:.4e}")).collect::<Vec<_>>().join(", ")
}
