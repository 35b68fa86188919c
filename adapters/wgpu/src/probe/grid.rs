//! The snapping grid: the finest vertex move that still changes coverage.
//!
//! A vertical left edge at `x_s ± ¾·2^-k` px of a sample at `x_s` (k = 1 to 16): on a grid of
//! `b` bits the two snap to different sides of the sample for every `k ≤ b` (¾ of a step or more
//! rounds to at least one step), and both onto the sample for `k > b` (⅜ of a step or less
//! rounds to none), where they cover it alike whatever the tie rule. No tie is involved, so
//! neither the tie rule nor the rounding of ties matters. The same edges turned horizontal
//! measure y.

use refrast::DrawError;

use super::{Raster, batch, clip, covers};

/// The finest step tried: a grid finer than 16 bits is no grid the suite can snap to.
pub const FINEST: u8 = 16;

/// For each axis, the moves `2^-k` (k = 1 to [`FINEST`]) that changed coverage.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Per k from 1, whether moving a vertical edge by `¾·2^-k` either way changed coverage.
    pub x: Vec<bool>,
    /// The same for a horizontal edge.
    pub y: Vec<bool>,
}

impl Grid {
    /// The bits of one axis: how many moves from the coarsest changed coverage, when every
    /// finer one did not; `None` when all did (no grid of 16 bits or fewer) or the pattern is
    /// not a grid's.
    fn axis(moved: &[bool]) -> Option<u8> {
        let bits = moved.iter().take_while(|&&m| m).count();
        let grid = moved[bits..].iter().all(|&m| !m);
        (grid && bits < moved.len()).then(|| u8::try_from(bits).expect("16 at most"))
    }

    /// The grid's bits when both axes have the same one.
    #[must_use]
    pub fn bits(&self) -> Option<u8> {
        let (x, y) = (Self::axis(&self.x), Self::axis(&self.y));
        (x == y).then_some(x).flatten()
    }

    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        let axis = |moved: &[bool]| match Self::axis(moved) {
            Some(bits) => format!("2^-{bits} px"),
            None if moved.iter().all(|&m| m) => format!("every step down to 2^-{FINEST} px"),
            None => format!(
                "no grid's pattern (moves 2^-k changing coverage for k = {:?})",
                (1..)
                    .zip(moved)
                    .filter(|(_, m)| **m)
                    .map(|(k, _)| k)
                    .collect::<Vec<u32>>()
            ),
        };
        let (x, y) = (axis(&self.x), axis(&self.y));
        if x == y {
            format!("the finest vertex move changing coverage is {x} in x and y")
        } else {
            format!("the finest vertex move changing coverage is {x} in x, {y} in y")
        }
    }
}

/// Draws the moved edges, both axes in one draw.
pub fn probe(draw: &mut Raster<'_>) -> Result<Grid, DrawError> {
    let sample = 4.5;
    let mut positions = Vec::new();
    for transpose in [false, true] {
        for k in 1..=i32::from(FINEST) {
            for sign in [-1.0, 1.0] {
                let e = sample + sign * 0.75 * 0.5f64.powi(k);
                // A left edge from (e, 1) to (e, 14), the triangle to its right.
                for [x, y] in [[e, 1.0], [e, 14.0], [sample + 8.0, 7.5]] {
                    let p = if transpose { [y, x] } else { [x, y] };
                    positions.push(clip(16, 16, p, 0.5, 1.0));
                }
            }
        }
    }
    let triangles = positions.len() / 3;
    let frags = draw(&batch(16, 16, positions))?;
    let per_axis = usize::from(FINEST) * 2;
    let moved =
        |covered: &[bool]| -> Vec<bool> { covered.chunks(2).map(|pair| pair[0] != pair[1]).collect() };
    let x = covers(&frags, triangles, (4, 7));
    let y = covers(&frags, triangles, (7, 4));
    Ok(Grid {
        x: moved(&x[..per_axis]),
        y: moved(&y[per_axis..]),
    })
}
