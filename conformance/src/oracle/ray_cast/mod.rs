//! The ray-casting oracle: rasterization and ray casting answer the same question.
//!
//! The ray through a sample centre meets the triangle's plane where the homogeneous
//! barycentrics `b` satisfy `Σ bᵢ (xᵢ − x_ndc·wᵢ) = 0`, `Σ bᵢ (yᵢ − y_ndc·wᵢ) = 0`, `Σ bᵢ = 1`.
//! Those `b` are the true perspective-correct barycentrics; the hit is visible when every
//! `bᵢ ≥ 0`, `w > 0` and it lies inside the near and far planes the draw clips at. No clipping
//! is involved, so this works for triangles crossing `w = 0` as it does for any other.

mod cut_rounding;
mod exact;
mod hit_test;
mod spread;

pub use cut_rounding::CutRounding;
#[cfg(test)]
pub(crate) use cut_rounding::reference::cut_rounding_px as reference_cut_rounding_px;
pub use hit_test::HitTest;
pub use spread::spread;

use refrast::DrawState;

use super::raster::{near_distance, window_depth};

/// Where the ray through a sample meets a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Perspective-correct barycentrics of the hit point.
    pub barycentric: [f64; 3],
    /// Window depth of the hit point, unclamped.
    pub depth: f64,
    /// Whether the triangle's visible part turns clockwise on screen: `det[x y w] < 0`. At a
    /// visible hit `w = det[x y w] / d > 0`, so the solve's denominator `d` has that
    /// determinant's sign, and the hit decides it exactly.
    pub clockwise: bool,
}

/// Casts the ray through NDC point `(nx, ny)` at the clip-space triangle `tri`.
///
/// `None` when it misses, the hit is behind the eye or outside an enabled near or far plane, or
/// the triangle is seen edge-on. Every decision is exact: f64 first, with a forward error bound
/// on each sign; when a sign is within its bound of zero (a sample on an edge, a
/// triangle nearly edge-on), the same solve runs again in exact integers.
#[must_use]
pub fn ray_cast(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Option<Hit> {
    match ray_cast_f64(tri, nx, ny, state) {
        Filtered::Sure(hit) => hit,
        Filtered::Unsure => exact::ray_cast_exact(tri, nx, ny, state),
    }
}

/// Whether the ray through NDC point `(nx, ny)` hits `tri`: [`ray_cast`]`.is_some()`, with
/// no ratio computed where the exact solve decides.
#[must_use]
pub fn ray_hits(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> bool {
    match ray_cast_f64(tri, nx, ny, state) {
        Filtered::Sure(hit) => hit.is_some(),
        Filtered::Unsure => exact::ray_hits_exact(tri, nx, ny, state),
    }
}

enum Filtered {
    Sure(Option<Hit>),
    Unsure,
}

/// A value with a bound on its rounding error.
#[derive(Clone, Copy, Debug)]
struct Bounded {
    v: f64,
    err: f64,
}

impl Bounded {
    fn exact(v: f64) -> Self {
        Self { v, err: 0.0 }
    }

    fn sure(self) -> bool {
        self.v.abs() > self.err && self.v.is_finite()
    }
}

// ε = 2^-53 per operation, doubled for safety: bounds that are loose cost an exact recompute,
// never a wrong answer.
const EPS: f64 = 2.0 * f64::EPSILON;

/// The rounding of a result below the normal range, which no multiple of its magnitude
/// bounds: one unit of the smallest subnormal, twice the most it can be off. Found by
/// `set_up_numerators_decide_as_ray_hits` with coordinates near 1e-310.
const UNDERFLOW: f64 = f64::from_bits(1);

/// The error bound of a rounded result `v`: relative above the normal range, absolute below.
fn rounding(v: f64) -> f64 {
    EPS * v.abs() + UNDERFLOW
}

fn sub(a: Bounded, b: Bounded) -> Bounded {
    let v = a.v - b.v;
    Bounded {
        v,
        err: a.err + b.err + rounding(v),
    }
}

fn add(a: Bounded, b: Bounded) -> Bounded {
    let v = a.v + b.v;
    Bounded {
        v,
        err: a.err + b.err + rounding(v),
    }
}

impl std::ops::Add for Bounded {
    type Output = Self;

    fn add(self, other: Self) -> Self {
        add(self, other)
    }
}

fn mul(a: Bounded, b: Bounded) -> Bounded {
    let v = a.v * b.v;
    Bounded {
        v,
        err: a.err * b.v.abs() + b.err * a.v.abs() + a.err * b.err + rounding(v),
    }
}

/// What a hit is decided and computed from, beside the numerators `n`: their sum `d` and their
/// weightings of the corners' z and w.
#[derive(Clone, Copy)]
struct Sums {
    d: Bounded,
    nz: Bounded,
    nw: Bounded,
}

impl Sums {
    /// The sums of numerators `n` of `tri`.
    fn of(tri: &[[f64; 4]; 3], n: &[Bounded; 3]) -> Self {
        let e = Bounded::exact;
        let weighted = |k: usize| {
            add(
                add(mul(n[0], e(tri[0][k])), mul(n[1], e(tri[1][k]))),
                mul(n[2], e(tri[2][k])),
            )
        };
        Sums {
            d: add(add(n[0], n[1]), n[2]),
            nz: weighted(2),
            nw: weighted(3),
        }
    }

    /// Whether the ray hits, where the bounds settle it: every numerator, w and the enabled
    /// plane distances of the denominator's sign. `None` where the exact solve must say: a
    /// value exactly zero may be decisive (a sample on an edge), unless a sure denominator and
    /// one sure failing sign already make it a miss (a sample on one edge of a triangle and
    /// outside another, in a mesh: most fallbacks, issue 47).
    #[inline]
    fn decide(&self, n: &[Bounded; 3], state: &DrawState) -> Option<bool> {
        let Sums { d, nz, nw } = *self;
        let near = near_distance(state.depth_range, nz, nw);
        let far = sub(nw, nz);
        let s = d.v.signum();
        let signs_sure = [d, n[0], n[1], n[2], nw].iter().all(|b| b.sure())
            && (!state.clip_near || near.sure())
            && (!state.clip_far || far.sure());
        if signs_sure {
            return Some(
                n.iter().all(|ni| ni.v * s > 0.0)
                    && nw.v * s > 0.0
                    && (!state.clip_near || near.v * s > 0.0)
                    && (!state.clip_far || far.v * s > 0.0),
            );
        }
        let misses = |x: &Bounded| x.sure() && x.v * s < 0.0;
        let missed = n.iter().any(misses)
            || misses(&nw)
            || (state.clip_near && misses(&near))
            || (state.clip_far && misses(&far));
        (d.sure() && missed).then_some(false)
    }
}

fn ray_cast_f64(tri: &[[f64; 4]; 3], nx: f64, ny: f64, state: &DrawState) -> Filtered {
    let e = Bounded::exact;
    let u = tri.map(|p| sub(e(p[0]), mul(e(nx), e(p[3]))));
    let v = tri.map(|p| sub(e(p[1]), mul(e(ny), e(p[3]))));
    let n = [
        sub(mul(u[1], v[2]), mul(u[2], v[1])),
        sub(mul(u[2], v[0]), mul(u[0], v[2])),
        sub(mul(u[0], v[1]), mul(u[1], v[0])),
    ];
    let sums = Sums::of(tri, &n);
    match sums.decide(&n, state) {
        None => return Filtered::Unsure,
        Some(false) => return Filtered::Sure(None),
        Some(true) => {}
    }
    let Sums { d, nz, nw } = sums;
    let (z, w) = (nz.v / d.v, nw.v / d.v);
    let depth = window_depth(state, z / w);
    Filtered::Sure(Some(Hit {
        barycentric: n.map(|ni| ni.v / d.v),
        depth,
        clockwise: d.v < 0.0,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::oracle::raster::sample_ndc;
    use proptest::prelude::*;

    /// Coordinates where the filter's bounds matter: integers and halves (rays through edges
    /// and vertices), small ranges, and extremes.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            4 => (-4i32..=4).prop_map(|k| f64::from(k) * 0.5),
            4 => -2.0f64..2.0,
            1 => -30000.0f64..30000.0,
            1 => prop_oneof![Just(1e-300), Just(-3e-310), Just(1e300), Just(0.0), Just(-0.0)],
        ]
    }

    /// A triangle, a ray's NDC point and a clipping state where the filter's bounds matter:
    /// rays on an edge, triangles nearly edge-on (a corner on the line through the others) and
    /// planes through the eye (two corners on one line through it), where signs are unsure,
    /// at every clipping state.
    pub(super) fn ray_case() -> impl Strategy<Value = ([[f64; 4]; 3], f64, f64, DrawState)> {
        let ndc_coordinate = || prop_oneof![(-4i32..=4).prop_map(|k| f64::from(k) * 0.5), -2.0f64..2.0];
        (
            prop::array::uniform3(prop::array::uniform4(coordinate())),
            (ndc_coordinate(), ndc_coordinate()),
            (any::<bool>(), any::<bool>(), any::<bool>()),
            (any::<bool>(), any::<bool>(), 0.0f64..1.0, -0.5f64..1.5),
            (
                any::<bool>(),
                prop_oneof![(-4i32..=4).prop_map(|k| f64::from(k) * 0.5), -3.0f64..3.0],
            ),
        )
            .prop_map(
                |(mut tri, (nx, ny), clip, (on_edge, edge_on, t, u), (through_eye, scale))| {
                    if through_eye {
                        // Corner 1 on the line through the eye and corner 0 (x, y and w scaled
                        // alike, z free): the triangle's plane holds the eye.
                        for k in [0, 1, 3] {
                            tri[1][k] = scale * tri[0][k];
                        }
                    }
                    if edge_on {
                        tri[2] = std::array::from_fn(|k| tri[0][k] + u * (tri[1][k] - tri[0][k]));
                    }
                    let ndc = |p: [f64; 4]| [p[0] / p[3], p[1] / p[3]];
                    let (a, b) = (ndc(tri[0]), ndc(tri[1]));
                    let (nx, ny) = if on_edge {
                        (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
                    } else {
                        (nx, ny)
                    };
                    let state = DrawState {
                        depth_range: if clip.0 {
                            refrast::DepthRange::NegativeOneToOne
                        } else {
                            refrast::DepthRange::ZeroToOne
                        },
                        clip_near: clip.1,
                        clip_far: clip.2,
                        ..DrawState::default()
                    };
                    (tri, nx, ny, state)
                },
            )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The f64 filter, its sure misses included, decides hit or miss and facing as the
        /// exact solve does.
        #[test]
        fn the_filter_decides_as_the_exact_solve((tri, nx, ny, state) in ray_case()) {
            let decision = |h: Option<Hit>| h.map(|h| h.clockwise);
            prop_assert_eq!(ray_hits(&tri, nx, ny, &state), decision(ray_cast(&tri, nx, ny, &state)).is_some());
            prop_assert_eq!(
                decision(ray_cast(&tri, nx, ny, &state)),
                decision(exact::ray_cast_exact(&tri, nx, ny, &state))
            );
        }
    }

    #[test]
    fn a_ray_through_the_centroid_has_equal_barycentrics_when_w_is_equal() {
        let tri = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 1.0, 0.5, 1.0],
        ];
        let hit = ray_cast(&tri, 0.0, 0.0, &DrawState::default()).unwrap();
        for b in hit.barycentric {
            assert!((b - 1.0 / 3.0).abs() < 1e-12);
        }
        assert!((hit.depth - 0.5).abs() < 1e-12);
        assert!(ray_cast(&tri, 0.9, 0.0, &DrawState::default()).is_none());
    }

    #[test]
    fn perspective_barycentrics_favour_the_near_vertex() {
        // Screen midpoint between a vertex at w = 1 and two at w = 3: b = 0.75 for the near one.
        let tri = [[-1.0, 0.0, 0.0, 1.0], [3.0, -3.0, 0.0, 3.0], [3.0, 3.0, 0.0, 3.0]];
        let hit = ray_cast(&tri, 0.0, 0.0, &DrawState::default()).unwrap();
        assert!((hit.barycentric[0] - 0.75).abs() < 1e-12, "{hit:?}");
    }

    #[test]
    fn the_hit_knows_which_way_the_triangle_turns_for_any_signs_of_w() {
        // Left, right, top in NDC: counter-clockwise on screen. Reversed: clockwise.
        let ccw = [
            [-0.5, -0.5, 0.5, 1.0],
            [0.5, -0.5, 0.5, 1.0],
            [0.0, 0.5, 0.5, 1.0],
        ];
        let cw = [ccw[0], ccw[2], ccw[1]];
        let state = DrawState::default();
        assert!(!ray_cast(&ccw, 0.0, 0.0, &state).unwrap().clockwise);
        assert!(ray_cast(&cw, 0.0, 0.0, &state).unwrap().clockwise);
        // With the top vertex behind the eye (w < 0), the visible part is the wedge from a → b
        // down to infinity: a, b, then down, which turns clockwise on screen.
        let mut behind = ccw;
        behind[2] = [0.0, -0.5, 0.5, -1.0];
        let hit = ray_cast(&behind, 0.0, -0.9, &state).expect("the wedge holds this sample");
        assert!(hit.clockwise);
        assert!(ray_cast(&behind, 0.0, 0.0, &state).is_none());
    }

    #[test]
    fn triangles_behind_the_eye_are_missed() {
        let tri = [
            [0.5, 0.5, 0.5, -1.0],
            [-0.5, 0.5, 0.5, -1.0],
            [0.0, -0.5, 0.5, -1.0],
        ];
        for (nx, ny) in [(0.0, 0.0), (-0.5, -0.2), (0.3, 0.1)] {
            assert!(ray_cast(&tri, nx, ny, &DrawState::default()).is_none());
        }
    }

    fn hits(tri: [[f32; 4]; 3], w: u32, h: u32) -> usize {
        let tri = tri.map(|p| p.map(f64::from));
        let mut n = 0;
        for y in 0..h {
            for x in 0..w {
                let [nx, ny] = sample_ndc(w, h, x, y);
                n += usize::from(ray_cast(&tri, nx, ny, &DrawState::default()).is_some());
            }
        }
        n
    }

    /// Found by `clip.interior.matches-raycast`: x = −y at every vertex puts the eye in the
    /// triangle's plane; f64 Cramer divided by rounding noise and "hit" 23 samples.
    #[test]
    fn a_triangle_seen_edge_on_covers_nothing() {
        let tri = [
            [-57337.19, 57337.19, 2.2714622, -1.9112397],
            [65148.11, -65148.11, 0.0, 2.1716037],
            [0.0, 0.0, 0.0, 0.2],
        ];
        assert_eq!(hits(tri, 32, 16), 0);
    }

    /// Found by `clip.interior.matches-raycast`: nearly edge-on, vertices at ±30000·w and w
    /// crossing 0. The exact solve gives 120 hits; plain f64 gave none.
    #[test]
    fn a_nearly_edge_on_triangle_gets_its_exact_hits() {
        let tri = [
            [-6000.0, 6000.0, 0.0, 0.2],
            [0.0, 0.01119828, 0.0, 0.2],
            [20974.33, -20974.33, 0.0, -0.69914436],
        ];
        assert_eq!(hits(tri, 16, 16), 120);
    }

    /// Found while fixing the above: the hits lie at w ≈ 1.3e-9, close to the horizon but
    /// genuinely visible; a cutoff on small w wrongly dropped all 256.
    #[test]
    fn hits_near_the_horizon_count() {
        let tri = [
            [0.2795305, 6000.0, 0.0, 0.2],
            [-2.0273936, 56659.32, 0.7119076, 1.888644],
            [0.120680064, -4555.2896, 0.0, -0.15184298],
        ];
        assert_eq!(hits(tri, 16, 16), 256);
    }
}
