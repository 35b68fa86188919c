//! How snapping rounds: exact ties, and vertices a few f32 ulps from a tie.
//!
//! Each case is one vertex `v0` whose x (or, transposed, y) is at or near a tie between the grid
//! points `g` and `g + step`, and an edge from it to `v1`, three rows below the sample where
//! `v0` is one row above, chosen so that the edge passes the sample half a step to its left when
//! `v0` lands on `g` and a quarter step to its right when it lands on `g + step`. The sample is
//! covered exactly when `v0` landed on `g`, and never lies on the edge, so the tie rule does not
//! matter. Exact ties (w = 1) with `g` even and with `g` odd tell rounding to even, half up, half
//! down and to odd apart. Near ties: `x_c` the f32 nearest the tie and up to 8 ulps either side,
//! at ten values of w; the exact `x_c/w` says which grid point is nearest.

use refrast::DrawError;

use super::{Raster, batch, clip, covers};

/// How the exact ties went, one word per case.
#[derive(Clone, Debug, PartialEq)]
pub struct Rounding {
    /// "to even", "half up", "half down" or "to odd", per axis and position.
    pub cases: Vec<&'static str>,
}

impl Rounding {
    /// Whether every exact tie went to the even grid point.
    #[must_use]
    pub fn to_even(&self) -> bool {
        self.cases.iter().all(|c| *c == "to even")
    }

    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        let even = self.cases.iter().filter(|c| **c == "to even").count();
        if self.to_even() {
            format!("ties to even ({even}/{} exact ties)", self.cases.len())
        } else {
            let mut words: Vec<&str> = self.cases.clone();
            words.sort_unstable();
            words.dedup();
            let counts: Vec<String> = words
                .iter()
                .map(|w| format!("{} {w}", self.cases.iter().filter(|c| *c == w).count()))
                .collect();
            format!("no ties-to-even claim (exact ties: {})", counts.join(", "))
        }
    }
}

/// Where the vertices near a tie landed.
#[derive(Clone, Debug, PartialEq)]
pub struct Snap {
    /// Vertices tried within 8 f32 ulps of a tie (exact ties left out).
    pub tried: usize,
    /// Those that landed on the grid point farther from their exact position.
    pub far: usize,
    /// The largest distance from the tie, in grid steps, at which one did.
    pub farthest: f64,
}

impl Snap {
    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        if self.far > 0 {
            format!(
                "snapping within one step ({} of {} vertices near a tie land on the far side, up to \
                 {:.1e} steps from it)",
                self.far, self.tried, self.farthest
            )
        } else {
            format!(
                "snapping to nearest (all {} vertices near a tie land on the nearer side)",
                self.tried
            )
        }
    }
}

/// The target's size: wide enough for f32 ulps to be a small fraction of a 16-bit step.
const SIDE: u32 = 64;

/// One case's triangle, in framebuffer pixels: `v0` at `x0` one row above the sample
/// `(xs, ys)`, the edge to `v1` landing half a step left of the sample from `g` or a quarter step
/// right of it from `g + step`.
fn triangle(x0: f64, xs: f64, ys: f64, g: f64, step: f64) -> [[f64; 2]; 3] {
    let x1 = 4.0 * xs - 2.0 * step - 3.0 * g;
    [[x0, ys - 1.0], [x1, ys + 3.0], [xs + 6.0, ys + 1.0]]
}

/// Draws the exact ties and the near ties on a grid of `bits`, in one draw each.
pub fn probe(draw: &mut Raster<'_>, bits: u8) -> Result<(Rounding, Snap), DrawError> {
    let step = 0.5f64.powi(i32::from(bits));
    let place = |transpose: bool, p: [f64; 2], w: f64| {
        let p = if transpose { [p[1], p[0]] } else { p };
        clip(SIDE, SIDE, p, 0.5, w)
    };
    // Exact ties: per axis and position, g = the sample's x (even in grid units for two bits or
    // more) and g + step (odd).
    let mut positions = Vec::new();
    let mut samples = Vec::new();
    for transpose in [false, true] {
        for px in [20u32, 41] {
            let (xs, ys) = (f64::from(px) + 0.5, 30.5);
            for g in [xs, xs + step] {
                let t = triangle(g + step / 2.0, xs, ys, g, step);
                positions.extend(t.map(|p| place(transpose, p, 1.0)));
                samples.push(if transpose { (30, px) } else { (px, 30) });
            }
        }
    }
    let n = samples.len();
    let frags = draw(&batch(SIDE, SIDE, positions))?;
    let on = |i: usize| covers(&frags, n, samples[i])[i];
    let cases = (0..n / 2)
        .map(|c| match (on(2 * c), on(2 * c + 1)) {
            (true, false) => "to even",
            (false, false) => "half up",
            (true, true) => "half down",
            (false, true) => "to odd",
        })
        .collect();
    // Near ties: the vertex's clip x is the f32 nearest the tie's, then 1 to 8 ulps either side.
    let (mut positions, mut expect) = (Vec::new(), Vec::new());
    for transpose in [false, true] {
        for px in [21u32, 40] {
            let (xs, ys) = (f64::from(px) + 0.5, 30.5);
            let g = xs;
            let tie = g + step / 2.0;
            let tie_ndc = 2.0 * tie / f64::from(SIDE) - 1.0;
            for w in [0.3f32, 0.7, 1.3, 1.7, 2.9, 3.3, 5.1, 7.7, 0.55, 11.3] {
                let w64 = f64::from(w);
                let nearest = place(false, [tie, 0.0], w64)[0];
                let t = triangle(tie, xs, ys, g, step);
                for k in -8i32..=8 {
                    let mut x = nearest;
                    for _ in 0..k.abs() {
                        x = if k > 0 { x.next_up() } else { x.next_down() };
                    }
                    // Exact: the product of two f32 fits an f64, and so does the difference.
                    let off = f64::from(x) - tie_ndc * w64;
                    let mut v0 = place(transpose, t[0], w64);
                    v0[usize::from(transpose)] = if transpose { -x } else { x };
                    positions.extend([v0, place(transpose, t[1], 1.0), place(transpose, t[2], 1.0)]);
                    let sample = if transpose { (30, px) } else { (px, 30) };
                    let steps = off / w64 * f64::from(SIDE) / 2.0 / step;
                    expect.push((sample, off < 0.0, off == 0.0, steps.abs()));
                }
            }
        }
    }
    let n = expect.len();
    let frags = draw(&batch(SIDE, SIDE, positions))?;
    let mut snap = Snap {
        tried: 0,
        far: 0,
        farthest: 0.0,
    };
    let mut by_sample = std::collections::HashMap::new();
    for (i, &(sample, lower, exact, steps)) in expect.iter().enumerate() {
        if exact {
            continue;
        }
        let covered = by_sample
            .entry(sample)
            .or_insert_with(|| covers(&frags, n, sample))[i];
        snap.tried += 1;
        if covered != lower {
            snap.far += 1;
            snap.farthest = snap.farthest.max(steps);
        }
    }
    Ok((Rounding { cases }, snap))
}
