//! `lab004-lineeq`: clipping and fill rasterization of seed 004 (TU Wien EVC, "Beispiel 5 –
//! Rasterisierung"), built as its sections 5 and 6 describe them.
//!
//! What the seed does, and what this module therefore does (in `f64`: the lab is Python with
//! 8-byte floats):
//!
//! - **Clipping** (Sutherland–Hodgman in clip space): six planes in Hesse normal form, each a
//!   4-vector `p`; a vertex `v` is inside when `v · p ≤ 0` (on the plane counts). The polygon's
//!   edges, last to first included, are cut at `t = l_a/(l_a − l_b)` with `l = v · p`, and `t` is
//!   nudged by `10⁻⁶` toward the inside end: decreased when `a` is inside, increased when `b` is.
//!   Position and attributes are mixed with that `t`. The cut is computed from the edge's start,
//!   so it depends on the direction the edge is walked in.
//! - **Volume**: the lab's cube `−w ≤ x, y, z ≤ w`. That is the draw's volume under
//!   [`DepthRange::NegativeOneToOne`]; under [`DepthRange::ZeroToOne`] the near plane becomes
//!   `z ≥ 0` (the draw says so), the other five planes stay. All six always apply: the lab clips
//!   the far plane whatever [`refrast::DrawState::clip_far`] says.
//! - **Fill**: the clipped polygon is drawn as a fan from its first vertex (the seed does not say
//!   how its polygons become triangles). For `V1, V2, V3`: edges `e1 = V3 − V2`, `e2 = V1 − V3`,
//!   `e3 = V2 − V1`, `A = −e_y`, `B = e_x`, `C` from a vertex on the line, and a point is inside
//!   when `O_i(x, y) = A_i x + B_i y + C_i ≤ 0` for all three. With y down that holds inside
//!   counter-clockwise triangles only: clockwise ones draw nothing, and every edge owns its samples.
//! - **Where it samples**: the point `(x, y)` of each pixel in the bounding box of the vertices;
//!   the seed never adds ½, so the sample is the pixel's top-left corner.
//! - **Barycentrics**: `α = O_1(P)/O_1(V_1)` and likewise `β`, `γ` (screen space); they mix the
//!   vertices' attributes (`barycentricMix`). The attributes here are the weights in the input
//!   triangle (mixed at cut vertices like colour) and the window depth `z/w` of each vertex.
//!
//! Zero-area triangles (`O_1(V_1) = 0`) are skipped, as `1/O_1(V_1)` is undefined. A pixel that
//! two fan triangles both own is emitted once, by the first.

use std::collections::HashSet;

use refrast::{
    CullMode, DepthConvention, DepthRange, Draw, DrawError, Features, Fragment, Profile, Rasterizer,
    SnapAccuracy, Snapping, Spec, Supported, Winding,
};

/// Seed 004's rasterizer: six-plane Sutherland–Hodgman with a 10⁻⁶ nudge, then line equations `O_i ≤ 0`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Lab004;

/// The lab's inward nudge of the intersection parameter `t`.
pub const NUDGE: f64 = 1e-6;

/// A plane `(n_x, n_y, n_z, −d)`: a point `v` is inside when `v · p ≤ 0`.
pub type Plane = [f64; 4];

/// A clip-space vertex with the attribute mixed along with it: its weights in the input triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVertex {
    /// Homogeneous clip-space position.
    pub position: [f64; 4],
    /// Barycentrics in the input triangle.
    pub weights: [f64; 3],
}

/// The six planes of the clip volume: x, y against `±w`, far `z ≤ w`, near by the depth range.
#[must_use]
pub fn clipping_planes(range: DepthRange) -> [Plane; 6] {
    let near = match range {
        DepthRange::NegativeOneToOne => [0.0, 0.0, -1.0, -1.0],
        DepthRange::ZeroToOne => [0.0, 0.0, -1.0, 0.0],
    };
    [
        [1.0, 0.0, 0.0, -1.0],
        [-1.0, 0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0, -1.0],
        [0.0, -1.0, 0.0, -1.0],
        [0.0, 0.0, 1.0, -1.0],
        near,
    ]
}

/// The 4D dot product of a vertex with a plane: its signed distance in the plane's units.
fn distance(v: &ClipVertex, p: &Plane) -> f64 {
    (0..4).map(|k| v.position[k] * p[k]).sum()
}

/// The lab's `inside`: on the plane counts as inside.
fn inside(v: &ClipVertex, p: &Plane) -> bool {
    distance(v, p) <= 0.0
}

/// `(1 − t)·a + t·b` for position and weights, the lab's `mix`.
fn mix(a: &ClipVertex, b: &ClipVertex, t: f64) -> ClipVertex {
    ClipVertex {
        position: std::array::from_fn(|k| (1.0 - t) * a.position[k] + t * b.position[k]),
        weights: std::array::from_fn(|k| (1.0 - t) * a.weights[k] + t * b.weights[k]),
    }
}

/// The lab's `intersect`: the crossing of edge `a → b` with `p`, nudged by [`NUDGE`] toward the inside end.
#[must_use]
pub fn intersect(a: &ClipVertex, b: &ClipVertex, p: &Plane) -> ClipVertex {
    let (la, lb) = (distance(a, p), distance(b, p));
    let mut t = la / (la - lb);
    if inside(a, p) {
        t -= NUDGE;
    } else if inside(b, p) {
        t += NUDGE;
    }
    mix(a, b, t)
}

/// The lab's `clip_plane`: one Sutherland–Hodgman pass of a polygon against one plane.
#[must_use]
pub fn clip_plane(polygon: &[ClipVertex], p: &Plane) -> Vec<ClipVertex> {
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for (i, a) in polygon.iter().enumerate() {
        let b = &polygon[(i + 1) % polygon.len()];
        if inside(a, p) {
            out.push(*a);
        }
        if inside(a, p) != inside(b, p) {
            out.push(intersect(a, b, p));
        }
    }
    out
}

/// A vertex after homogenization and the viewport transform, with what `barycentricMix` mixes.
#[derive(Clone, Copy, Debug)]
struct ScreenVertex {
    x: f64,
    y: f64,
    depth: f64,
    weights: [f64; 3],
}

/// Divide by `w`, map to pixels (y down) and to window depth; `None` if that is not a number.
fn to_screen(v: &ClipVertex, width: f64, height: f64, range: DepthRange) -> Option<ScreenVertex> {
    let [x, y, z, w] = v.position;
    let s = ScreenVertex {
        x: (x / w + 1.0) * 0.5 * width,
        y: (1.0 - y / w) * 0.5 * height,
        depth: range.window_depth(z, w),
        weights: v.weights,
    };
    (w > 0.0 && s.x.is_finite() && s.y.is_finite() && s.depth.is_finite()).then_some(s)
}

/// A line equation `O(x, y) = A x + B y + C` through `on`, normal to `edge` as `(−e_y, e_x)`.
fn line_eq(edge: [f64; 2], on: &ScreenVertex) -> [f64; 3] {
    let (a, b) = (-edge[1], edge[0]);
    [a, b, -(a * on.x + b * on.y)]
}

/// `O(x, y)`.
fn eval(o: &[f64; 3], x: f64, y: f64) -> f64 {
    o[0] * x + o[1] * y + o[2]
}

/// The lab's `drawTriangle`: every pixel of the bounding box with `O_i ≤ 0`, with its weights
/// and window depth mixed by `α, β, γ`.
fn draw_triangle(
    v: [&ScreenVertex; 3],
    width: u32,
    height: u32,
    mut emit: impl FnMut(u32, u32, [f64; 3], f64),
) {
    let [v1, v2, v3] = v;
    let e = [
        [v3.x - v2.x, v3.y - v2.y],
        [v1.x - v3.x, v1.y - v3.y],
        [v2.x - v1.x, v2.y - v1.y],
    ];
    let o = [line_eq(e[0], v2), line_eq(e[1], v3), line_eq(e[2], v1)];
    let f = [
        1.0 / eval(&o[0], v1.x, v1.y),
        1.0 / eval(&o[1], v2.x, v2.y),
        1.0 / eval(&o[2], v3.x, v3.y),
    ];
    // Zero area has no weights; positive O_i(V_i) (clockwise) leaves no point with all O_i ≤ 0.
    if !f.iter().all(|f| f.is_finite() && *f < 0.0) {
        return;
    }
    let span = |a: f64, b: f64, c: f64, max: u32| {
        let lo = a.min(b).min(c).ceil().max(0.0);
        let hi = a.max(b).max(c).floor().min(f64::from(max) - 1.0);
        (lo as u32, hi as u32, lo <= hi)
    };
    let (x0, x1, has_x) = span(v1.x, v2.x, v3.x, width);
    let (y0, y1, has_y) = span(v1.y, v2.y, v3.y, height);
    if !(has_x && has_y) {
        return;
    }
    for py in y0..=y1 {
        for px in x0..=x1 {
            let (x, y) = (f64::from(px), f64::from(py));
            let values = o.map(|o| eval(&o, x, y));
            if !values.iter().all(|&value| value <= 0.0) {
                continue;
            }
            let [alpha, beta, gamma] = [values[0] * f[0], values[1] * f[1], values[2] * f[2]];
            let weights =
                std::array::from_fn(|k| alpha * v1.weights[k] + beta * v2.weights[k] + gamma * v3.weights[k]);
            emit(
                px,
                py,
                weights,
                alpha * v1.depth + beta * v2.depth + gamma * v3.depth,
            );
        }
    }
}

impl Rasterizer for Lab004 {
    fn profile(&self) -> Profile {
        Profile {
            name: "lab004-lineeq".into(),
            // No snapping: f64 line equations on raw coordinates.
            snapping: Snapping::Float,
            // `O_i ≤ 0` owns every edge: no tie rule.
            fill: None,
            // z/w of each vertex, mixed with screen-space α, β, γ.
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: 1,
            // Held to the reference's precision: the labs compute in f32 or f64 from exact inputs.
            precision_bits: 18,
            features: Features {
                perspective_barycentrics: false,
                screen_barycentrics: true,
                cull_modes: Supported::only(&[CullMode::None]),
                front_faces: Supported::ALL,
                depth_test: false,
                compare_ops: Supported::ALL,
                depth_writes: Supported::ALL,
                far_clipping: Supported::ALL,
                depth_ranges: Supported::ALL,
                // x and y are clipped at the viewport, cut points nudged inward.
                guard_band: 0,
                // No grid, so no snap ties.
                ties_to_even: false,
                snap: SnapAccuracy::Nearest,
                zero_area_before_clipping: false,
                clips_in_3d: true,
                z_rewritten_in_f32: false,
            },
            spec: Spec::Refrast,
            ..Profile::default()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        draw.validate()?;
        let (width, height) = (draw.viewport.width(), draw.viewport.height());
        let range = draw.state.depth_range;
        let planes = clipping_planes(range);
        // Every drawn triangle is counter-clockwise on screen, the only winding `O_i ≤ 0` accepts.
        let front_facing = draw
            .state
            .front_face
            .is_front(Winding::CounterClockwise)
            .unwrap_or(false);
        let mut out = Vec::new();
        for (t, indices) in draw.triangles().iter().enumerate() {
            let input = indices.map(|i| draw.positions[i as usize]);
            if input.iter().flatten().any(|c| !c.is_finite()) {
                continue;
            }
            let mut polygon: Vec<ClipVertex> = (0..3)
                .map(|k| ClipVertex {
                    position: input[k].map(f64::from),
                    weights: std::array::from_fn(|j| if j == k { 1.0 } else { 0.0 }),
                })
                .collect();
            for p in &planes {
                if polygon.len() < 3 {
                    break;
                }
                polygon = clip_plane(&polygon, p);
            }
            let screen: Option<Vec<ScreenVertex>> = polygon
                .iter()
                .map(|v| to_screen(v, f64::from(width), f64::from(height), range))
                .collect();
            let Some(screen) = screen.filter(|s| s.len() >= 3) else {
                continue;
            };
            let mut seen = HashSet::new();
            for k in 1..screen.len() - 1 {
                draw_triangle(
                    [&screen[0], &screen[k], &screen[k + 1]],
                    width,
                    height,
                    |x, y, w, depth| {
                        if screen.len() > 3 && !seen.insert((x, y)) {
                            return;
                        }
                        let weights = w.map(|w| w as f32);
                        out.push(Fragment {
                            x,
                            y,
                            sample: 0,
                            primitive: t as u32,
                            depth: depth.clamp(0.0, 1.0) as f32,
                            barycentric: weights,
                            flat: None,
                            screen_barycentric: Some(weights),
                            front_facing,
                        });
                    },
                );
            }
        }
        Ok(out)
    }
}
