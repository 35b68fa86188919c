//! Probes for lines, points and samples: which line rule a driver's lines follow, whether its
//! points land as the reference's, and where its 4 samples lie. WebGPU names none of them, and
//! Vulkan reports only `strictLines` and `standardSampleLocations` (`reported.rs`), which these
//! check.
//!
//! Lines and points are compared, pixel by pixel, with the reference drawing the same ones under
//! each candidate rule on the driver's grid and tie rule; the rule no probe line disagrees with
//! is the one declared. Sample positions are read off coverage: a rectangle from a pixel's left
//! edge to `t/16` px covers exactly the samples left of `t/16` under a top-left tie rule.

use refrast::{
    Draw, DrawError, FillConvention, Fragment, LineRule, Rasterizer, Reference, ReferenceConfig,
    SamplePattern, SubpixelBits, Topology, Viewport,
};

use super::clip;

/// The probe target's side, in pixels.
const SIDE: u32 = 32;

/// How many probe lines and points.
const SHAPES: u32 = 160;

/// A driver's draw of any topology, as these probes call it.
pub type PrimitiveRaster<'a> = dyn FnMut(&Draw) -> Result<Vec<Fragment>, DrawError> + 'a;

/// What the line, point and sample probes counted on one driver.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveProbes {
    /// Per line rule, the (segment, pixel) pairs where the driver and the reference under that
    /// rule disagree, over the probe's 160 segments; `Err` when the driver drew no lines.
    pub lines: Result<Vec<(LineRule, usize)>, String>,
    /// The points whose pixel differs from the reference's, over its 160 points; `Err` when
    /// the driver drew no points.
    pub points: Result<usize, String>,
    /// The positions of the 4 samples, in 1/16 px, by sample index; `Err` with why not.
    pub samples: Result<[[u8; 2]; 4], String>,
    /// The finest step, `2^-k` px, by which a point moved off a pixel edge changes the pixel it
    /// covers, in x and in y: the grid points are snapped to; `None` when every step down to
    /// `2^-FINEST_POINT_STEP` does (no grid), `Some(0)` when none does.
    pub point_steps: Option<[u8; 2]>,
    /// The same for a line's end moved off the place where its last pixel changes, in x and in
    /// y: the grid line ends are snapped to (`None` also when no lines were drawn).
    pub end_steps: Option<[u8; 2]>,
}

impl PrimitiveProbes {
    /// The line rule no probe segment disagrees with, if one.
    #[must_use]
    pub fn line_rule(&self) -> Option<LineRule> {
        let counts = self.lines.as_ref().ok()?;
        counts.iter().find(|(_, n)| *n == 0).map(|(rule, _)| *rule)
    }

    /// The grid points are snapped to, in bits: one fewer than the finest step seen, as a step
    /// of half a grid unit lands on a grid point or not by how the driver rounds ties; `None`
    /// for no grid.
    #[must_use]
    pub fn point_bits(&self) -> Option<u8> {
        self.point_steps.map(|[x, y]| x.min(y).saturating_sub(1))
    }

    /// The grid line ends are snapped to, in bits, read as [`PrimitiveProbes::point_bits`] is.
    #[must_use]
    pub fn end_bits(&self) -> Option<u8> {
        self.end_steps.map(|[x, y]| x.min(y).saturating_sub(1))
    }

    /// The line rule fewest probe pixels disagree with, if lines were drawn.
    #[must_use]
    pub fn nearest_rule(&self) -> Option<LineRule> {
        let counts = self.lines.as_ref().ok()?;
        counts.iter().min_by_key(|(_, n)| *n).map(|(rule, _)| *rule)
    }

    /// The measured 4-sample pattern, if it was measured.
    #[must_use]
    pub fn pattern(&self) -> Option<SamplePattern> {
        SamplePattern::new(self.samples.as_ref().ok()?).ok()
    }

    /// What the probes saw, in one clause each.
    #[must_use]
    pub fn describe(&self) -> String {
        let lines = match &self.lines {
            Ok(counts) => {
                let each: Vec<String> = counts
                    .iter()
                    .map(|(rule, n)| format!("{} {n}", rule.name()))
                    .collect();
                match self.line_rule() {
                    Some(rule) => format!(
                        "lines by the {} rule (of {SHAPES} probe segments, pixels off each rule: {})",
                        rule.name(),
                        each.join(", ")
                    ),
                    None => format!(
                        "lines by no rule exactly, nearest the {} rule (of {SHAPES} probe segments, pixels off each rule: {})",
                        self.nearest_rule().map_or("none", LineRule::name),
                        each.join(", ")
                    ),
                }
            }
            Err(why) => format!("no lines ({why})"),
        };
        let points = match &self.points {
            Ok(0) => format!("points as the reference's ({SHAPES} probe points)"),
            Ok(n) => format!("points: {n} of {SHAPES} probe points off the reference's pixel"),
            Err(why) => format!("no points ({why})"),
        };
        let samples = match (&self.samples, self.pattern()) {
            (Ok(_), Some(p)) if p.is_standard() => {
                "4 samples at Vulkan's standard locations (measured)".to_owned()
            }
            (Ok(positions), _) => format!("4 samples at {positions:?} sixteenths (measured)"),
            (Err(why), _) => format!("no multisampling ({why})"),
        };
        let snapped = match (self.point_steps, self.point_bits()) {
            (Some(steps), Some(bits)) => format!(
                "points snapped to {bits} bits (the finest step moving one off a pixel edge: 2^-{} px in x, 2^-{} in y)",
                steps[0], steps[1]
            ),
            _ => format!("points not snapped (steps down to 2^-{FINEST_POINT_STEP} px move them)"),
        };
        let ends = match (self.end_steps, self.end_bits()) {
            (Some(_), Some(_)) if self.line_rule().is_none() => {
                ", line ends' grid not read (the lines follow no rule exactly)".to_owned()
            }
            (Some(steps), Some(bits)) => format!(
                ", line ends snapped to {bits} bits (the finest step moving one changes its last pixel: 2^-{} px in x, 2^-{} in y)",
                steps[0], steps[1]
            ),
            _ if self.lines.is_ok() => {
                format!(", line ends not snapped (steps down to 2^-{FINEST_POINT_STEP} px move them)")
            }
            _ => String::new(),
        };
        format!("{lines}{ends}, {points}, {snapped}, {samples}")
    }
}

/// Runs the three probes through `draw`, comparing with the reference on a grid of `bits`
/// (8 for a driver without one) under `fill` (top-left for a driver without one).
pub fn measure(
    draw: &mut PrimitiveRaster<'_>,
    bits: u8,
    fill: Option<FillConvention>,
    multisampling: Result<(), String>,
) -> PrimitiveProbes {
    let reference = |line| {
        Reference::new(ReferenceConfig {
            subpixel_bits: SubpixelBits::new(bits.clamp(SubpixelBits::MIN, SubpixelBits::MAX))
                .unwrap_or(SubpixelBits::DEFAULT),
            fill: fill.unwrap_or_default(),
            line,
            ..ReferenceConfig::default()
        })
    };
    let segments = shapes(Topology::LineList);
    let lines = draw(&segments).map_err(|e| e.to_string()).map(|got| {
        let got = pixels(&got);
        LineRule::ALL
            .into_iter()
            .map(|rule| {
                let want = reference(rule).rasterize(&segments).map(|f| pixels(&f));
                (rule, want.map_or(usize::MAX, |want| differing(&got, &want)))
            })
            .collect()
    });
    let dots = shapes(Topology::PointList);
    let points = draw(&dots).map_err(|e| e.to_string()).and_then(|got| {
        let want = reference(LineRule::default())
            .rasterize(&dots)
            .map_err(|e| e.to_string())?;
        // A pair off on either side is one point off.
        Ok(differing(&pixels(&got), &pixels(&want)).div_ceil(2))
    });
    let samples = multisampling.and_then(|()| sample_positions(draw));
    let point_steps = point_steps(draw).unwrap_or(Some([0, 0]));
    let end_steps = if lines.is_ok() {
        end_steps(draw).unwrap_or(Some([0, 0]))
    } else {
        None
    };
    PrimitiveProbes {
        lines,
        points,
        samples,
        point_steps,
        end_steps,
    }
}

/// [`SHAPES`] segments (or points) on a `SIDE`² target, their ends on the 1/16 px grid: a fixed
/// pseudo-random spread of lengths and slopes, with the cases rules turn on first (45°
/// diagonals through pixel corners, axis-aligned segments on pixel centres and edges, ends on
/// pixel centres).
fn shapes(topology: Topology) -> Draw {
    let mut state: u32 = 0x9e37_79b9;
    let mut next = move |range: u32| {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state % range
    };
    let sixteenths = SIDE * 16;
    let mut ends: Vec<[f64; 2]> = Vec::new();
    let special: [[f64; 4]; 8] = [
        [2.0, 2.0, 12.0, 12.0],
        [20.0, 4.0, 8.0, 16.0],
        [3.5, 20.5, 15.5, 20.5],
        [22.0, 22.0, 30.0, 22.0],
        [24.5, 2.5, 24.5, 14.5],
        [26.0, 18.0, 26.0, 30.0],
        [4.5, 26.5, 14.5, 29.5],
        [16.5, 24.5, 17.5, 31.5],
    ];
    let per = if topology == Topology::PointList { 1 } else { 2 };
    for [x0, y0, x1, y1] in special {
        ends.push([x0, y0]);
        if per == 2 {
            ends.push([x1, y1]);
        }
    }
    while ends.len() < (SHAPES * per) as usize {
        let a = [next(sixteenths), next(sixteenths)];
        ends.push(a.map(|v| f64::from(v) / 16.0));
        if per == 2 {
            // Mostly short segments, some across the target.
            let reach = if next(4) == 0 { sixteenths } else { 96 };
            let b = a.map(|v| (v + next(2 * reach)).saturating_sub(reach).min(sixteenths - 1));
            ends.push(b.map(|v| f64::from(v) / 16.0));
        }
    }
    let positions: Vec<[f32; 4]> = ends.iter().map(|&p| clip(SIDE, SIDE, p, 0.5, 1.0)).collect();
    let indices = (0..positions.len() as u32).collect();
    let viewport = Viewport::new(SIDE, SIDE).expect("the probe's target");
    let mut draw = Draw::of(viewport, positions, topology, indices);
    draw.state.clip_far = true;
    draw
}

/// The finest step tried by [`point_steps`], `2^-FINEST_POINT_STEP` px.
const FINEST_POINT_STEP: u8 = 14;

/// Points `2^-k` px either side of a pixel edge, `k` from 1 to [`FINEST_POINT_STEP`], in x (at
/// `y = 7.25`) and in y (at `x = 3.25`): unsnapped, the two of a pair cover different pixels;
/// snapped onto the edge, the same. The finest `k` telling a pair apart, per axis; `None` when
/// every pair is told apart; `Err` when the draw fails.
fn point_steps(draw: &mut PrimitiveRaster<'_>) -> Result<Option<[u8; 2]>, DrawError> {
    let mut spots: Vec<[f64; 2]> = Vec::new();
    for k in 1..=FINEST_POINT_STEP {
        let step = (-f64::from(k)).exp2();
        spots.extend([
            [10.0 + step, 7.25],
            [10.0 - step, 7.25],
            [3.25, 10.0 + step],
            [3.25, 10.0 - step],
        ]);
    }
    finest_steps(draw, &spots, Topology::PointList, &[[0, 1], [2, 3]])
}

/// Segments from `(2.25, 7.25)` along x (from `(3.25, 2.25)` along y) ending `2^-k` px either
/// side of a pixel edge (where a diamond-exit line's last pixel changes) and of a pixel centre
/// (where a rectangle's or parallelogram's does), `k` from 1 to [`FINEST_POINT_STEP`]: the
/// finest `k` telling a pair apart, per axis, as [`point_steps`] reads points.
fn end_steps(draw: &mut PrimitiveRaster<'_>) -> Result<Option<[u8; 2]>, DrawError> {
    let mut ends: Vec<[f64; 2]> = Vec::new();
    for k in 1..=FINEST_POINT_STEP {
        let step = (-f64::from(k)).exp2();
        for at in [10.0, 10.5] {
            ends.extend([
                [2.25, 7.25],
                [at + step, 7.25],
                [2.25, 7.25],
                [at - step, 7.25],
                [3.25, 2.25],
                [3.25, at + step],
                [3.25, 2.25],
                [3.25, at - step],
            ]);
        }
    }
    // Segment pairs per axis: at the edge, then at the centre.
    finest_steps(draw, &ends, Topology::LineList, &[[0, 1], [4, 5], [2, 3], [6, 7]])
}

/// The finest `k` at which some pair of `positions` drawn as `topology` covers different
/// pixels, per axis: each `k` in turn has `2 · pairs.len()` primitives, and `pairs` names each
/// pair's two within them, the first half of x, the second of y; `None` when every `k` down to
/// [`FINEST_POINT_STEP`] tells one apart.
fn finest_steps(
    draw: &mut PrimitiveRaster<'_>,
    positions: &[[f64; 2]],
    topology: Topology,
    pairs: &[[u32; 2]],
) -> Result<Option<[u8; 2]>, DrawError> {
    let clip_positions: Vec<[f32; 4]> = positions.iter().map(|&p| clip(SIDE, SIDE, p, 0.5, 1.0)).collect();
    let indices = (0..clip_positions.len() as u32).collect();
    let viewport = Viewport::new(SIDE, SIDE).expect("the probe's target");
    let mut probe = Draw::of(viewport, clip_positions, topology, indices);
    probe.state.clip_far = true;
    let covered = pixels(&draw(&probe)?);
    let of =
        |p: u32| -> Vec<(u32, u32)> { covered.iter().filter(|t| t.0 == p).map(|t| (t.1, t.2)).collect() };
    let (per_k, per_axis) = (2 * pairs.len() as u32, pairs.len() / 2);
    let mut finest = [0u8; 2];
    for k in 1..=FINEST_POINT_STEP {
        let first = per_k * u32::from(k - 1);
        for (axis, slot) in finest.iter_mut().enumerate() {
            let told = pairs[axis * per_axis..(axis + 1) * per_axis]
                .iter()
                .any(|&[a, b]| of(first + a) != of(first + b));
            if told {
                *slot = k;
            }
        }
    }
    Ok(if finest == [FINEST_POINT_STEP; 2] {
        None
    } else {
        Some(finest)
    })
}

/// The sorted (primitive, x, y) triples covered, samples merged.
fn pixels(fragments: &[Fragment]) -> Vec<(u32, u32, u32)> {
    let mut all: Vec<_> = fragments.iter().map(|s| (s.primitive, s.x, s.y)).collect();
    all.sort_unstable();
    all.dedup();
    all
}

/// How many triples one sorted list has and the other lacks.
fn differing(a: &[(u32, u32, u32)], b: &[(u32, u32, u32)]) -> usize {
    let only = |x: &[(u32, u32, u32)], y: &[(u32, u32, u32)]| {
        x.iter().filter(|t| y.binary_search(t).is_err()).count()
    };
    only(a, b) + only(b, a)
}

/// The 4 samples' positions: pixel `(t − 1, 0)` holds a rectangle from its left edge to
/// `t/16` px right of it, pixel `(t − 1, 1)` one from its top edge to `t/16` px below it, for
/// `t` in 1..=16; a sample at `o/16` is covered exactly when `o < t` under a top-left tie
/// rule, so it is left uncovered `o` times.
fn sample_positions(draw: &mut PrimitiveRaster<'_>) -> Result<[[u8; 2]; 4], String> {
    let mut corners: Vec<[f64; 2]> = Vec::new();
    for t in 1..=16u32 {
        let (c, reach) = (f64::from(t - 1), f64::from(t) / 16.0);
        // Across: x from c to c + reach, y over row 0. Down: x over column c, y from 1 to 1 + reach.
        for [x0, y0, x1, y1] in [[c, 0.0, c + reach, 1.0], [c, 1.0, c + 1.0, 1.0 + reach]] {
            corners.extend([[x0, y0], [x1, y0], [x0, y1], [x1, y0], [x1, y1], [x0, y1]]);
        }
    }
    let positions: Vec<[f32; 4]> = corners.iter().map(|&p| clip(16, 2, p, 0.5, 1.0)).collect();
    let indices = (0..positions.len() as u32).collect();
    let mut probe = Draw::of(
        Viewport::new(16, 2).expect("the probe's target"),
        positions,
        Topology::TriangleList,
        indices,
    );
    probe.samples = 4;
    probe.state.clip_far = true;
    let got = draw(&probe).map_err(|e| format!("a draw at 4 samples failed: {e}"))?;
    if got.is_empty() {
        return Err("32 rectangles drawn at 4 samples came back with no sample covered".into());
    }
    // covered[row][t − 1][sample]
    let mut covered = [[[false; 4]; 16]; 2];
    for s in &got {
        let f = s;
        if f.x >= 16 || f.y >= 2 || s.sample >= 4 {
            return Err(format!(
                "sample {} of pixel ({}, {}) is outside the probe's 16×2 target at 4 samples",
                s.sample, f.x, f.y
            ));
        }
        covered[f.y as usize][f.x as usize][usize::from(s.sample)] = true;
    }
    let mut positions = [[0u8; 2]; 4];
    for (k, position) in positions.iter_mut().enumerate() {
        for (axis, row) in covered.iter().enumerate() {
            let seen: Vec<bool> = row.iter().map(|pixel| pixel[k]).collect();
            let left = seen.iter().filter(|c| !**c).count();
            // Covered from some t on, and at every t after it.
            if left >= 16 || seen[left..].iter().any(|c| !c) {
                return Err(format!(
                    "sample {k}'s coverage along {} is not a step ({seen:?})",
                    ["x", "y"][axis]
                ));
            }
            position[axis] = u8::try_from(left).unwrap_or(u8::MAX);
        }
    }
    Ok(positions)
}
