//! A bound on a cut's rounding along a whole row of samples, so that a rule asks
//! [`CutRounding::at`] only of the samples it can matter for.

use super::{CLIP_ROUNDING, CutRounding, affine};
use crate::oracle::raster::to_ndc;

impl CutRounding {
    /// An upper bound on [`CutRounding::at`] at every sample centre of row `y`, infinity where
    /// none is sure (the plane not settled in view, a cut's gradient that may vanish): what
    /// lets a rule skip the samples of a row farther than the band and this from every cut.
    ///
    /// Over the row the NDC x of every point `at` evaluates lies in `[-1, 1]` and its y is the
    /// row's, or half a pixel up or down. The sums are affine, so their magnitudes peak at the
    /// ends, and keep one sign over the view (`settled_in_view`), so their least magnitude is
    /// at an end too; each quotient is bounded by its numerator's peak over its denominator's
    /// least, then widened by `2^-20` for the roundings of both computations.
    #[must_use]
    pub fn bound_in_row(&self, y: u32) -> f64 {
        if self.cuts == 0 {
            return 0.0;
        }
        if !self.settled_in_view {
            return f64::INFINITY;
        }
        let h = 0.5;
        let sy = f64::from(y) + 0.5;
        let [ny, up, down] = [sy, sy - h, sy + h].map(|v| to_ndc(self.width, self.height, 0.0, v)[1]);
        let ends = |c: [f64; 3], row: f64| [-1.0, 1.0].map(|nx| affine(c, [nx, row]));
        let least = |v: [f64; 2]| {
            if v[0] * v[1] > 0.0 {
                v[0].abs().min(v[1].abs())
            } else {
                0.0
            }
        };
        let most = |v: [f64; 2]| v[0].abs().max(v[1].abs());
        let rows = [ny, up, down];
        let d_least = rows
            .iter()
            .map(|&r| least(ends(self.plane.sums[0], r)))
            .fold(f64::INFINITY, f64::min);
        let d_most = rows
            .iter()
            .map(|&r| most(ends(self.plane.sums[0], r)))
            .fold(0.0, f64::max);
        let ws_least = least(ends(self.plane.sums[1], ny));
        let sizes: f64 = (0..3)
            .map(|i| most(ends(self.plane.n[i], ny)) * self.size[i])
            .sum();
        let e = CLIP_ROUNDING * sizes / d_least;
        let half = f64::from(self.width.max(self.height)) * 0.5;
        let moved = CLIP_ROUNDING * sizes / ws_least * (2.0 + ny.abs()) * half;
        // |along_x| and |along_y| of `at`: the NDC steps over the largest product of two sums.
        let step_x = 2.0 * h / f64::from(self.width) * 2.0;
        let step_y = (down - up).abs();
        let along = |step: f64| step / (d_most * d_most * (2.0 * h));
        let across = self.differences[..self.cuts]
            .iter()
            .map(|[x, y]| {
                let gx = (x[0] + x[1] * ny).abs() * along(step_x);
                let gy = least([-1.0, 1.0].map(|nx| y[0] + y[1] * nx)) * along(step_y);
                2.0 * e / gx.max(gy)
            })
            .fold(0.0, f64::max);
        let bound = (moved + across) * (1.0 + 1.0 / 1_048_576.0);
        if bound.is_nan() { f64::INFINITY } else { bound }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::oracle::raster::sample_centre;
    use crate::strategy::{clipped_mesh_scene, crossing_scene};

    /// A far-clipped triangle near the view volume: its rows are bounded, and tightly.
    #[test]
    fn an_ordinary_cut_bounds_every_row() {
        let tri = [
            [-0.5, -0.5, -0.5, 1.0],
            [0.9, -0.2, 0.7, 1.5],
            [0.1, 0.8, 1.4, 1.2],
        ];
        let state = refrast::DrawState {
            clip_far: true,
            ..refrast::DrawState::default()
        };
        let rounding = CutRounding::new(&tri, 64, 64, &state);
        for y in 0..64 {
            let bound = rounding.bound_in_row(y);
            assert!(bound < 1.0 / 256.0, "row {y}: {bound}");
            for x in 0..64 {
                assert!(rounding.at(sample_centre(x, y)) <= bound);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// No sample of a row has more rounding than the row's bound.
        #[test]
        fn the_row_bound_holds_at_every_sample(
            scene in prop_oneof![clipped_mesh_scene(), crossing_scene()],
        ) {
            for t in 0..scene.triangles.len() {
                let tri = scene.positions_of(t);
                let rounding = CutRounding::new(&tri, scene.width, scene.height, &scene.state);
                for y in 0..scene.height {
                    let bound = rounding.bound_in_row(y);
                    for x in 0..scene.width {
                        let at = rounding.at(sample_centre(x, y));
                        prop_assert!(at <= bound, "triangle {t}, pixel ({x}, {y}): {at} > {bound}");
                    }
                }
            }
        }
    }
}
