//! The depth slope a driver's bias takes: Vulkan and OpenGL define `m` as the gradient's length
//! and allow its largest component, and which a driver computes is not reported.
//!
//! One right triangle on a 64×64 target whose depth rises by 1/1024 a pixel in x and in y alike,
//! drawn with every fragment written, once unbiased and once with a slope factor of 64 (constant
//! 0): the offset read off the depth buffer is `64/1024` under `max(|∂z/∂x|, |∂z/∂y|)` and √2
//! times that under the exact length. Depths stay below ½ and inside `[0, 1]`, so no clamp and
//! no resolvable difference is involved.

use refrast::{CompareOp, DepthBias, DepthSlope, Draw, DrawError, Resolved};

use super::{batch, clip};

/// The slope factor drawn.
const FACTOR: f32 = 64.0;

/// The depth's rise a pixel, in x and in y alike.
const RISE: f64 = 1.0 / 1024.0;

/// How far from 1 or √2 the measured ratio may be and still name that measure: the driver's
/// f32 depths (a few ulps of ½ against an offset of 1/16) move it by far less.
const CLOSE: f64 = 0.01;

/// What the probe saw.
#[derive(Clone, Debug, PartialEq)]
pub struct Slope {
    /// The median biased depth less the unbiased one, over the pixels both drew, divided by
    /// `FACTOR · RISE`; `None` when no pixel showed an offset (nothing drawn).
    pub ratio: Option<f64>,
}

impl Slope {
    /// Not measured: what the probes that draw fragments alone leave (tests of the other probes).
    #[must_use]
    pub fn unmeasured() -> Self {
        Self { ratio: None }
    }

    /// The measure it shows: the largest component at a ratio of 1, the length at √2, and
    /// `Either` (what the specifications allow) otherwise, for the rules to judge.
    #[must_use]
    pub fn measure(&self) -> DepthSlope {
        match self.ratio {
            Some(r) if (r - 1.0).abs() < CLOSE => DepthSlope::Max,
            Some(r) if (r - std::f64::consts::SQRT_2).abs() < CLOSE => DepthSlope::Exact,
            _ => DepthSlope::Either,
        }
    }

    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        let what = match self.measure() {
            DepthSlope::Max => "max(|dz/dx|, |dz/dy|)",
            DepthSlope::Exact => "the gradient's length",
            DepthSlope::Either => "either (neither fits)",
        };
        match self.ratio {
            Some(r) => format!(
                "depth bias slope {what} (measured: a diagonal gradient's offset {r:.4} times its largest component's)"
            ),
            None => format!("depth bias slope {what} (nothing drawn to measure)"),
        }
    }
}

/// Draws the triangle unbiased and biased through `resolve` and reads the ratio.
pub fn probe(resolve: &mut dyn FnMut(&Draw) -> Result<Resolved, DrawError>) -> Result<Slope, DrawError> {
    let depth = |[x, y]: [f64; 2]| 0.125 + RISE * (x + y);
    let corners = [[4.0, 4.0], [60.0, 4.0], [4.0, 60.0]];
    let mut plain = batch(
        64,
        64,
        corners.iter().map(|&p| clip(64, 64, p, depth(p), 1.0)).collect(),
    );
    plain.state.depth.compare = CompareOp::Always;
    let mut biased = plain.clone();
    biased.state.depth_bias = Some(DepthBias {
        constant: 0.0,
        slope: FACTOR,
        clamp: 0.0,
    });
    let (a, b) = (resolve(&plain)?, resolve(&biased)?);
    let mut offsets: Vec<f64> = (0..a.depth.len().min(b.depth.len()))
        .filter(|&i| a.primitive[i].is_some() && b.primitive[i].is_some())
        .map(|i| f64::from(b.depth[i]) - f64::from(a.depth[i]))
        .collect();
    offsets.sort_by(f64::total_cmp);
    let ratio = offsets
        .get(offsets.len() / 2)
        .map(|o| o / (f64::from(FACTOR) * RISE));
    Ok(Slope { ratio })
}
