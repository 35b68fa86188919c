//! Mutants: the reference pipeline with one classic bug each, and the rule family that must catch it.
//!
//! One small pipeline (clip, project, snap, set up, walk the bounding box, interpolate) written
//! plainly; each [`Bug`] changes it in one place. With no bug it follows the reference's
//! conventions, so every failure the suite reports is that bug's doing.

use glam::{DVec3, DVec4};
use refrast::stage::{ClipOutcome, ClipPlane, ClipVertex, CornerDistances, clip_planes, clip_triangle};
use refrast::{
    ClipMode, CompareOp, Draw, DrawError, FillConvention, FixedPoint, Fragment, FrontFace, Profile,
    Rasterizer, Reference, Resolved, Viewport, is_top_left,
};

mod bias;
mod bug;
mod centroid;
mod conservative;
mod distance;
mod polygon;
mod primitive;
mod reach;
mod sample_mask;
mod state;

pub use bug::Bug;

/// The mutant pipeline with one bug.
#[derive(Clone, Copy, Debug)]
pub struct Mutant {
    bug: Bug,
}

impl Mutant {
    /// The pipeline with `bug`.
    #[must_use]
    pub fn new(bug: Bug) -> Self {
        Self { bug }
    }
}

/// A polygon vertex after projection: raster position, snapped position, depth, 1/w, barycentrics.
#[derive(Clone, Copy)]
struct Vert {
    raster: [f64; 2],
    fixed: [i64; 2],
    depth: f64,
    inv_w: f64,
    bary: DVec3,
    /// Screen-space weights of the corners, `None` when a corner has `w ≤ 0` (no screen shape).
    screen: Option<DVec3>,
}

impl Rasterizer for Mutant {
    /// The reference's lines, points, standard samples and scissor for a bug among them,
    /// triangles at one sample for the others.
    fn profile(&self) -> Profile {
        let reference = Reference::default().profile();
        let mut profile = Profile {
            name: format!("mutant:{}", self.bug.name()),
            ..if self.bug.is_primitive() || self.bug.is_state() {
                reference
            } else {
                reference.triangles_only()
            }
        };
        if self.bug.is_reach() {
            profile.state.polygon_modes = refrast::Supported::NONE;
        }
        profile
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        if self.bug.is_state() {
            return state::rasterize(self.bug, draw);
        }
        if let Some(fragments) = reach::rasterize(self.bug, draw) {
            return fragments;
        }
        if self.bug.is_primitive() {
            // Its bug is in lines, points or samples: triangles at one sample are the reference's.
            return primitive::rasterize(self.bug, draw);
        }
        draw.validate()?;
        let state = &draw.state;
        let planes = clip_planes(ClipMode::GuardBand, draw.viewport, state.depth_clip());
        let mut out = Vec::new();
        for (primitive, t) in draw.triangles().iter().enumerate() {
            let p = t.map(|i| draw.positions[i as usize]);
            if p.iter().flatten().any(|c| !c.is_finite()) {
                continue;
            }
            let input = [0, 1, 2].map(|k| ClipVertex::corner(p[k], k));
            // Clip and cull distances as the reference honours them: no bug is in them.
            let Ok(user) = CornerDistances::of(&draw.distances, t) else {
                continue;
            };
            // Zero area is decided on the snapped input before clipping, as the reference does
            // (its profile claims it), unless that is the bug.
            if !matches!(self.bug, Bug::ZeroAreaAfterClipping | Bug::DegenerateFragments)
                && input.iter().all(|c| c.position.w > 0.0)
                && let Some(v) = self.project(draw, &input, &input)
                && orient(v[0].fixed, v[1].fixed, v[2].fixed) == 0
            {
                continue;
            }
            let polygon = match self.bug {
                Bug::NoNearClip => input.to_vec(),
                Bug::DirectionalClip => clip_walking(&input, &planes),
                _ => {
                    let (mut poly, mut scratch) = (Vec::new(), Vec::new());
                    match clip_triangle(&input, &planes, user.planes(), &mut poly, &mut scratch) {
                        ClipOutcome::Outside => continue,
                        ClipOutcome::Inside => input.to_vec(),
                        ClipOutcome::Clipped => poly,
                    }
                }
            };
            let Some(verts) = self.project(draw, &input, &polygon) else {
                continue;
            };
            if verts.len() < 3 {
                continue;
            }
            let area: i64 = (1..verts.len() - 1)
                .map(|i| orient(verts[0].fixed, verts[i].fixed, verts[i + 1].fixed))
                .sum();
            if area == 0 && self.bug != Bug::DegenerateFragments {
                continue;
            }
            let unclipped = polygon.len() == 3 && polygon == input;
            let clockwise = if self.bug == Bug::UnsnappedFacing && unclipped {
                // The bug: the unsnapped positions' area, which a sliver's snapping can reverse.
                let r = verts.iter().map(|v| v.raster).collect::<Vec<_>>();
                (r[1][0] - r[0][0]) * (r[2][1] - r[0][1]) - (r[1][1] - r[0][1]) * (r[2][0] - r[0][0]) > 0.0
            } else {
                area > 0
            };
            if self.bug == Bug::OneWinding && clockwise {
                continue;
            }
            let mut front = match state.front_face {
                FrontFace::Clockwise => clockwise,
                FrontFace::CounterClockwise => !clockwise && area != 0,
            };
            if self.bug == Bug::InvertedFacing {
                front = !front;
            }
            if state.cull.culls(front) {
                continue;
            }
            for i in 1..verts.len() - 1 {
                let tri = [verts[0], verts[i], verts[i + 1]];
                self.walk(draw.viewport, tri, primitive as u32, front, unclipped, &mut out);
            }
        }
        if self.bug == Bug::PermutedBarycentrics {
            // Vertex k's weight handed to vertex k + 1.
            for f in &mut out {
                f.barycentric.rotate_right(1);
                if let Some(s) = &mut f.screen_barycentric {
                    s.rotate_right(1);
                }
            }
        }
        Ok(out)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        if self.bug.is_state() {
            return state::resolve(self.bug, draw);
        }
        let fragments = self.rasterize(draw)?;
        if self.bug == Bug::StrictCompare {
            let mut strict = draw.clone();
            let op = &mut strict.state.depth.compare;
            *op = match *op {
                CompareOp::LessOrEqual => CompareOp::Less,
                CompareOp::GreaterOrEqual => CompareOp::Greater,
                other => other,
            };
            return Ok(Resolved::from_fragments(&strict, fragments));
        }
        if self.bug != Bug::DepthWithoutTest {
            return Ok(Resolved::from_fragments(draw, fragments));
        }
        // The bug: every fragment writes, in submission order, whatever its depth.
        let vp = draw.viewport;
        let mut resolved = Resolved {
            viewport: vp,
            samples: 1,
            depth: vec![draw.state.depth.clear; vp.pixel_count()],
            primitive: vec![None; vp.pixel_count()],
        };
        for f in fragments.iter().filter(|f| f.x < vp.width() && f.y < vp.height()) {
            let i = vp.index(f.x, f.y);
            resolved.depth[i] = f.depth;
            resolved.primitive[i] = Some(f.primitive);
        }
        Ok(resolved)
    }
}

impl Mutant {
    /// Divides by w and snaps; `None` when a vertex has no finite raster position in range.
    fn project(&self, draw: &Draw, corners: &[ClipVertex; 3], polygon: &[ClipVertex]) -> Option<Vec<Vert>> {
        let range = draw.state.depth_range;
        // What the bug mixes: the corners' window depths, by a cut vertex's barycentrics.
        let lerped_depth = |b: DVec3| {
            (0..3)
                .map(|k| b[k] * range.window_depth(corners[k].position.z, corners[k].position.w))
                .sum::<f64>()
        };
        // A point with homogeneous weights b projects to screen weights bₖwₖ / Σ bⱼwⱼ (the
        // bug keeps b, the clip-space weights, as if the cut's t served both).
        let corner_w = DVec3::from(corners.map(|c| c.position.w));
        let screen = |b: DVec3| {
            (corner_w.min_element() > 0.0).then(|| {
                if self.bug == Bug::PerspectiveCutScreen {
                    b
                } else {
                    b * corner_w / b.dot(corner_w)
                }
            })
        };
        // The dropped bit: snap to 1/128 px, kept in 1/256 px units like everything else.
        let step = if self.bug == Bug::DroppedSubpixelBit {
            2.0
        } else {
            1.0
        };
        polygon
            .iter()
            .map(|c| {
                let p = c.position;
                if p.w == 0.0 || (self.bug != Bug::NoNearClip && p.w < 0.0) {
                    return None;
                }
                let (x, y) = draw.viewport.to_raster(p.x / p.w, p.y / p.w);
                let round = |u: f64| {
                    if self.bug == Bug::HalfUpSnap {
                        (u + 0.5).floor()
                    } else {
                        u.round_ties_even()
                    }
                };
                let snap = |v: f64| {
                    let s = round(v * 256.0 / step) * step;
                    (s.is_finite() && s.abs() <= FixedPoint::LIMIT as f64).then_some(s as i64)
                };
                Some(Vert {
                    raster: [x, y],
                    fixed: [snap(x)?, snap(y)?],
                    depth: match self.bug {
                        Bug::UnmappedGlDepth => p.z / p.w,
                        Bug::LerpedCutDepth => lerped_depth(c.barycentric),
                        _ => range.window_depth(p.z, p.w),
                    },
                    inv_w: 1.0 / p.w,
                    bary: c.barycentric,
                    screen: screen(c.barycentric),
                })
            })
            .collect()
    }

    /// Walks the bounding box of one triangle of the fan and emits its covered samples.
    fn walk(
        &self,
        vp: Viewport,
        t: [Vert; 3],
        primitive: u32,
        front: bool,
        unclipped: bool,
        out: &mut Vec<Fragment>,
    ) {
        let [a, b, c] = t.map(|v| v.fixed);
        let area = orient(a, b, c);
        let sign = area.signum();
        let xs = [a[0], b[0], c[0]];
        let ys = [a[1], b[1], c[1]];
        let first = |min: i64| (min - 128 + 255).div_euclid(256);
        let last = |max: i64| (max - 128).div_euclid(256);
        let (w, h) = (i64::from(vp.width()), i64::from(vp.height()));
        // The clamp: the last pixel is side − 1 (the bug clamps to the side itself).
        let top = if self.bug == Bug::UnclampedBbox { 0 } else { 1 };
        let x0 = first(*xs.iter().min().unwrap_or(&0)).max(0);
        let y0 = first(*ys.iter().min().unwrap_or(&0)).max(0);
        let mut x1 = last(*xs.iter().max().unwrap_or(&0)).min(w - top);
        let mut y1 = last(*ys.iter().max().unwrap_or(&0)).min(h - top);
        if self.bug == Bug::ExclusiveBboxMax {
            x1 -= 1;
            y1 -= 1;
        }
        for py in y0..=y1 {
            for px in x0..=x1 {
                let s = [px * 256 + 128, py * 256 + 128];
                let Some(e) = self.edges(t, s, sign) else { continue };
                let weights = if area == 0 {
                    [1.0 / 3.0; 3]
                } else {
                    let denom = if self.bug == Bug::WrongArea {
                        area.abs() as f64 / 2.0
                    } else {
                        area.abs() as f64
                    };
                    e.map(|v| v / denom)
                };
                let q = [0, 1, 2].map(|k| weights[k] * t[k].inv_w);
                let qs: f64 = q.iter().sum();
                let persp = [0, 1, 2].map(|k| q[k] / qs);
                let mix = |wt: [f64; 3]| (0..3).map(|k| t[k].bary * wt[k]).sum::<DVec3>();
                let affine_mix = mix(weights);
                let screen = (0..3)
                    .map(|k| t[k].screen.map(|s| s * weights[k]))
                    .sum::<Option<DVec3>>();
                let affine = match self.bug {
                    Bug::AffineAttributes => true,
                    Bug::AffineClipped => !unclipped,
                    _ => false,
                };
                let bary = if affine { affine_mix } else { mix(persp) };
                let dw = if self.bug == Bug::PerspectiveDepth {
                    persp
                } else {
                    weights
                };
                let depth = (0..3).map(|k| t[k].depth * dw[k]).sum::<f64>().clamp(0.0, 1.0);
                out.push(Fragment {
                    x: px as u32,
                    y: py as u32,
                    sample: 0,
                    primitive,
                    depth: depth as f32,
                    barycentric: bary.as_vec3().to_array(),
                    flat: None,
                    screen_barycentric: screen.map(|s| s.as_vec3().to_array()),
                    front_facing: front,
                });
            }
        }
    }

    /// The three edge values at sample `s` (oriented so inside is positive), or `None` when the
    /// fill rule (as this mutant applies it) leaves the sample out.
    fn edges(&self, t: [Vert; 3], s: [i64; 2], sign: i64) -> Option<[f64; 3]> {
        let f = t.map(|v| v.fixed);
        let pairs = [(1, 2), (2, 0), (0, 1)];
        let values: [f64; 3] = match self.bug {
            Bug::Edge32Bit => pairs.map(|(i, j)| {
                let (a, b) = (f[i].map(|v| v as i32), f[j].map(|v| v as i32));
                let (sx, sy) = (s[0] as i32, s[1] as i32);
                let e = (b[0].wrapping_sub(a[0]))
                    .wrapping_mul(sy.wrapping_sub(a[1]))
                    .wrapping_sub((b[1].wrapping_sub(a[1])).wrapping_mul(sx.wrapping_sub(a[0])));
                f64::from(e) * sign as f64
            }),
            Bug::FloatEdges => {
                let r = t.map(|v| v.raster.map(|c| c as f32));
                let p = [s[0] as f32 / 256.0, s[1] as f32 / 256.0];
                pairs.map(|(i, j)| {
                    let e = (r[j][0] - r[i][0]) * (p[1] - r[i][1]) - (r[j][1] - r[i][1]) * (p[0] - r[i][0]);
                    f64::from(e) * sign as f64
                })
            }
            Bug::RotatedEdgeOrigin => {
                let r = f.map(|v| v.map(|c| c as f32 / 256.0));
                let p = [s[0] as f32 / 256.0, s[1] as f32 / 256.0];
                // Each edge's function taken from vertex 0, not from the edge's own start.
                pairs.map(|(i, j)| {
                    let d = [r[j][0] - r[i][0], r[j][1] - r[i][1]];
                    let e = d[0] * (p[1] - r[0][1])
                        - d[1] * (p[0] - r[0][0])
                        - (d[0] * (r[i][1] - r[0][1]) - d[1] * (r[i][0] - r[0][0]));
                    f64::from(e) * sign as f64
                })
            }
            _ if sign == 0 => {
                // The bug emits a zero-area triangle's samples that lie on its line.
                let on_line = pairs.iter().all(|&(i, j)| orient(f[i], f[j], s) == 0);
                return on_line.then_some([0.0; 3]);
            }
            _ => pairs.map(|(i, j)| (orient(f[i], f[j], s) * sign) as f64),
        };
        let covered = (0..3).all(|k| {
            let v = values[k];
            let (i, j) = pairs[k];
            match self.bug {
                Bug::InclusiveEdges => v >= 0.0,
                Bug::ExclusiveEdges => v > 0.0,
                _ => v > 0.0 || (v == 0.0 && self.owns(f, i, j, sign)),
            }
        });
        covered.then_some(values)
    }

    /// Whether edge `i → j` owns its samples: top-left on the clockwise-ordered triangle.
    fn owns(&self, f: [[i64; 2]; 3], i: usize, j: usize, sign: i64) -> bool {
        let p = |k: usize| FixedPoint::new(f[k][0], f[k][1]).unwrap_or_default();
        // Inside is where the oriented edge values are positive: walk the edge so it turns clockwise.
        let (a, b) = if sign >= 0 { (p(i), p(j)) } else { (p(j), p(i)) };
        match self.bug {
            Bug::BottomRightAsTopLeft => FillConvention::BottomRight.owns_edge(a, b),
            _ => is_top_left(a, b),
        }
    }
}

/// Twice the signed area of `a, b, c` on 1/256-pixel coordinates.
fn orient(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Sutherland–Hodgman with the bug: each intersection computed in f32 from the vertex met
/// first while walking, so two triangles walking a shared edge opposite ways cut it apart.
fn clip_walking(input: &[ClipVertex; 3], planes: &[ClipPlane]) -> Vec<ClipVertex> {
    let mut poly = input.to_vec();
    for &plane in planes {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (cur, next) = (poly[i], poly[(i + 1) % poly.len()]);
            let (dc, dn) = (plane.distance(cur.position), plane.distance(next.position));
            if dc >= 0.0 {
                out.push(cur);
            }
            if (dc >= 0.0) != (dn >= 0.0) {
                let t = (dc / (dc - dn)) as f32;
                let lerp = |a: f64, b: f64| f64::from(a as f32 + t * (b as f32 - a as f32));
                let p = [0, 1, 2, 3].map(|k| lerp(cur.position[k], next.position[k]));
                let q = [0, 1, 2].map(|k| lerp(cur.barycentric[k], next.barycentric[k]));
                out.push(ClipVertex {
                    position: DVec4::from(p),
                    barycentric: DVec3::from(q),
                });
            }
        }
        poly = out;
        if poly.len() < 3 {
            return Vec::new();
        }
    }
    poly
}
