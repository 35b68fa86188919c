//! A missing tie rule: coverage that is exactly what `e ≥ 0` on every edge gives (samples on
//! an edge belong to both triangles sharing it) or `e > 0` (to neither), not the declared fill
//! convention's. Decided only where every vertex projects exactly onto the 2^-16 grid, so that
//! "exactly on an edge" is exact arithmetic, not a guess.

use refrast::{CullMode, Draw, FillConvention, Fragment};

use crate::oracle::brute_force::{orient2d, owns};
use crate::oracle::raster::{Point, project, snap};

/// The grid on which a vertex must lie exactly for ties to be decided here.
const BITS: u8 = 16;

/// How a rasterizer without a tie rule treats a sample exactly on an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ties {
    /// Every edge owns it (`e >= 0`): a sample on a shared edge is covered twice.
    Inclusive,
    /// No edge owns it (`e > 0`): a sample on a shared edge is covered by neither.
    Exclusive,
}

impl Ties {
    /// The test a student wrote, as code.
    #[must_use]
    pub fn code(self) -> &'static str {
        match self {
            Ties::Inclusive => "e >= 0",
            Ties::Exclusive => "e > 0",
        }
    }
}

/// Triangle `tri`'s vertices in 2^-16 px, when each projects exactly onto that grid (and lies
/// in front of the eye); `None` otherwise.
#[must_use]
pub fn exact_points(positions: &[[f32; 4]], tri: [u32; 3], width: u32, height: u32) -> Option<[Point; 3]> {
    let point = |i: u32| exact_point(*positions.get(i as usize)?, width, height);
    Some([point(tri[0])?, point(tri[1])?, point(tri[2])?])
}

/// Clip-space position `p` in 2^-16 px, when it projects exactly onto that grid (and lies in
/// front of the eye); `None` otherwise.
#[must_use]
pub fn exact_point(p: [f32; 4], width: u32, height: u32) -> Option<Point> {
    let one = f64::from(1u32 << BITS);
    let snapped = snap(p, width, height, BITS)?;
    let exact = project(width, height, p.map(f64::from));
    (exact[0] * one == snapped.0 as f64 && exact[1] * one == snapped.1 as f64).then_some(snapped)
}

/// Whether the sample of pixel `(x, y)` lies exactly on the line through `a` and `b` as a
/// rasterizer places them, decided in integers: snapped to its grid of `grid` bits, or without
/// one, exactly projected; `None` when they do not project exactly onto the 2^-16 grid, where
/// exactly on cannot be told from a hair off.
#[must_use]
pub fn exactly_on_line(
    a: [f32; 4],
    b: [f32; 4],
    (width, height): (u32, u32),
    grid: Option<u8>,
    (x, y): (u32, u32),
) -> Option<bool> {
    let (ends, s) = match grid {
        Some(bits) => {
            let one = 1i128 << bits.min(16);
            let s = (i128::from(x) * one + one / 2, i128::from(y) * one + one / 2);
            ((snap(a, width, height, bits)?, snap(b, width, height, bits)?), s)
        }
        None => (
            (exact_point(a, width, height)?, exact_point(b, width, height)?),
            sample(x, y),
        ),
    };
    Some(orient2d(ends.0, ends.1, s) == 0)
}

/// Whether sample `s` is covered by `t` with samples on edges decided by `ties`, or by `fill`
/// when `ties` is `None`; `t` must not be degenerate.
#[must_use]
pub fn covers(t: [Point; 3], s: Point, ties: Option<Ties>, fill: FillConvention) -> bool {
    (0..3).all(|i| {
        let (p, q, r) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
        let e = orient2d(p, q, s) * orient2d(p, q, r).signum();
        e > 0
            || (e == 0
                && match ties {
                    Some(Ties::Inclusive) => true,
                    Some(Ties::Exclusive) => false,
                    None => owns(p, q, r, fill),
                })
    })
}

/// Whether sample `s` lies exactly on an edge of `t`.
fn on_edge(t: [Point; 3], s: Point) -> bool {
    (0..3).any(|i| orient2d(t[i], t[(i + 1) % 3], s) == 0)
}

/// The sample of pixel `(x, y)` in 2^-16 px.
fn sample(x: u32, y: u32) -> Point {
    let one = 1i128 << BITS;
    (i128::from(x) * one + one / 2, i128::from(y) * one + one / 2)
}

/// `frags` of `draw` as if the rasterizer, whose samples on edges `ties` decides, broke them by
/// `fill` instead: on every exact triangle, a fragment on an edge it does not own is dropped,
/// one on an edge it owns added (a copy of another of its fragments, at that sample).
#[must_use]
pub fn with_tie_rule(
    draw: &Draw,
    mut frags: Vec<Fragment>,
    ties: Ties,
    fill: FillConvention,
) -> Vec<Fragment> {
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    for (t, &tri) in draw.triangles().iter().enumerate() {
        let Some(pts) = exact_points(&draw.positions, tri, w, h) else {
            continue;
        };
        if orient2d(pts[0], pts[1], pts[2]) == 0 {
            continue;
        }
        let mine = |f: &Fragment| f.primitive as usize == t;
        let model = match frags.iter().find(|f| mine(f)).copied() {
            Some(model) => model,
            // Culled: nothing to fix.
            None if draw.state.cull != CullMode::None => continue,
            // A sliver whose every sample lies on an edge draws nothing without a tie rule: its
            // owned samples get a fragment of plain values (the rules these hints verify
            // judge coverage).
            None => Fragment {
                x: 0,
                y: 0,
                sample: 0,
                primitive: t as u32,
                depth: 0.5,
                barycentric: [1.0 / 3.0; 3],
                flat: None,
                screen_barycentric: Some([1.0 / 3.0; 3]),
                front_facing: true,
            },
        };
        let decided = |x: u32, y: u32| covers(pts, sample(x, y), None, fill);
        match ties {
            Ties::Inclusive => {
                frags.retain(|f| !mine(f) || !on_edge(pts, sample(f.x, f.y)) || decided(f.x, f.y))
            }
            Ties::Exclusive => {
                for y in 0..h {
                    for x in 0..w {
                        let s = sample(x, y);
                        if on_edge(pts, s)
                            && decided(x, y)
                            && !frags.iter().any(|f| mine(f) && (f.x, f.y) == (x, y))
                        {
                            frags.push(Fragment { x, y, ..model });
                        }
                    }
                }
            }
        }
    }
    frags
}

/// Which of the two, if either, explains every triangle's coverage in `frags` where the
/// declared `fill` does not: `None` unless every triangle of the draw is exact, some sample
/// lies on an edge, and the declared convention does not already explain it.
#[must_use]
pub fn explaining(draw: &Draw, frags: &[Fragment], fill: FillConvention) -> Option<Ties> {
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let tris: Vec<[Point; 3]> = draw
        .triangles()
        .iter()
        .map(|&tri| exact_points(&draw.positions, tri, w, h))
        .collect::<Option<_>>()?;
    let mut got: Vec<Vec<(u32, u32)>> = vec![Vec::new(); tris.len()];
    for f in frags {
        got.get_mut(f.primitive as usize)?.push((f.x, f.y));
    }
    got.iter_mut().for_each(|g| g.sort_unstable());
    let explains = |ties: Option<Ties>| {
        tris.iter().zip(&got).all(|(&t, got)| {
            if orient2d(t[0], t[1], t[2]) == 0 {
                return got.is_empty();
            }
            // A triangle culled (drawing nothing) says nothing of ties.
            // In the order of `got`: sorted by x, then y.
            let want: Vec<(u32, u32)> = (0..w)
                .flat_map(|x| (0..h).map(move |y| (x, y)))
                .filter(|&(x, y)| covers(t, sample(x, y), ties, fill))
                .collect();
            got.is_empty() || *got == want
        })
    };
    if explains(None) {
        return None;
    }
    [Ties::Inclusive, Ties::Exclusive]
        .into_iter()
        .find(|&ties| explains(Some(ties)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// Coverage of `scene`'s triangles with samples on edges decided by `ties`.
    fn drawn(scene: &Scene, ties: Option<Ties>) -> Vec<Fragment> {
        let draw = scene.draw();
        let mut frags = Vec::new();
        for (t, &tri) in draw.triangles().iter().enumerate() {
            let pts = exact_points(&draw.positions, tri, scene.width, scene.height).expect("on the grid");
            for y in 0..scene.height {
                for x in 0..scene.width {
                    if covers(pts, sample(x, y), ties, FillConvention::TopLeft) {
                        frags.push(Fragment {
                            x,
                            y,
                            sample: 0,
                            primitive: t as u32,
                            depth: 0.5,
                            barycentric: [1.0, 0.0, 0.0],
                            flat: None,
                            screen_barycentric: None,
                            front_facing: true,
                        });
                    }
                }
            }
        }
        frags
    }

    /// The student's case of issue 43: two triangles sharing a diagonal through samples. Each
    /// missing tie rule is recognised, and the declared one is not taken for one (the first
    /// version compared coverage sorted two ways and recognised nothing).
    #[test]
    fn a_missing_tie_rule_is_recognised_on_a_shared_diagonal() {
        let scene = Scene::new(
            16,
            16,
            vec![
                [-1.0, 1.0, 0.5, 1.0],
                [1.0, -1.0, 0.5, 1.0],
                [-1.0, -1.0, 0.5, 1.0],
                [0.75, -0.25, 0.5, 1.0],
            ],
            vec![[1, 2, 3], [0, 3, 2]],
        );
        let draw = scene.draw();
        for ties in [Ties::Inclusive, Ties::Exclusive] {
            assert_eq!(
                explaining(&draw, &drawn(&scene, Some(ties)), FillConvention::TopLeft),
                Some(ties)
            );
        }
        assert_eq!(
            explaining(&draw, &drawn(&scene, None), FillConvention::TopLeft),
            None
        );
    }
}
