//! A driver's profile as measured on this machine: the grid Vulkan reports (`vulkaninfo`) or the
//! probe measures (OpenGL, which reports nothing through wgpu), and each probe's choice among the
//! declarations the specification permits, with why.

use refrast::{
    DepthSlope, FillConvention, LineRule, PointClipping, SamplePattern, SnapAccuracy, Snapping, Spec,
};

use crate::probe::{Probes, fill_name};
use crate::reported::Reported;

/// The bits of precision a profile claims below what the probe measured: the suite draws
/// triangles the probe did not, and a claim with no room would fail on the first one a little
/// worse.
pub const MARGIN: f64 = 2.0;

/// The most precision any profile claims, the reference's own.
const MOST_PRECISION: u8 = 18;

/// The measured declarations, each with why.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// The grid.
    pub snapping: Snapping,
    /// The tie rule, if the driver keeps one.
    pub fill: Option<FillConvention>,
    /// Exact snap ties go to the even grid point.
    pub ties_to_even: bool,
    /// How close to `x/w` vertices land.
    pub snap: SnapAccuracy,
    /// How far outside the viewport a triangle may reach unclipped, in pixels.
    pub guard_band: u32,
    /// The interpolation precision claimed.
    pub precision_bits: u8,
    /// The tolerance band, in grid steps (1/256 px without a grid).
    pub tolerance_subpixels: u32,
    /// The line rule the probe saw, if the driver draws lines.
    pub lines: Option<LineRule>,
    /// Whether it draws points.
    pub points: bool,
    /// The grid points are snapped to, when coarser than the triangles'.
    pub point_snapping: Option<Snapping>,
    /// The grid line ends are snapped to, where coarser than the triangles'.
    pub endpoint_snapping: Option<Snapping>,
    /// The sample positions the probe found (4 samples), if any.
    pub multisample: Vec<SamplePattern>,
    /// What clipping does to a point outside the viewport in x or y.
    pub point_clipping: PointClipping,
    /// How its depth bias measures the depth slope.
    pub bias_slope: DepthSlope,
    /// What the driver reported through `vulkaninfo`, if anything.
    pub reported: String,
    /// Why each declaration, one clause each.
    pub why: String,
}

/// Chooses every declaration from what the driver reported (`reported`, Vulkan only) and what
/// the probes saw, under the specification the driver claims.
#[must_use]
pub fn choose(spec: Spec, reported: Option<&Reported>, probes: &Probes) -> Measured {
    let (snapping, grid_why) = grid(spec, reported, probes);
    let on_grid = snapping != Snapping::Float;
    let fill = probes.tie_rule.chosen;
    let mut why = vec![grid_why, probes.tie_rule.describe()];
    let (snap, ties_to_even) = if on_grid {
        why.push(probes.snap.describe());
        why.push(probes.rounding.describe());
        let snap = if probes.snap.far > 0 {
            SnapAccuracy::WithinOneStep
        } else {
            SnapAccuracy::Nearest
        };
        (snap, probes.rounding.to_even())
    } else {
        (SnapAccuracy::Nearest, false)
    };
    let guard_band = probes.band.reach();
    why.push(probes.band.describe());
    let measured = probes.precision.bits();
    let precision_bits = if measured.is_finite() {
        (measured - MARGIN).floor().clamp(0.0, f64::from(MOST_PRECISION)) as u8
    } else {
        MOST_PRECISION
    };
    why.push(format!(
        "{precision_bits} bits of precision ({}, less {MARGIN})",
        probes.precision.describe()
    ));
    // On a grid the band is one step (snapping's own reach); with none, twice the farthest a
    // sample was decided against exact arithmetic, in 1/256 px.
    let tolerance_subpixels = if on_grid {
        1
    } else {
        let band = (2.0 * probes.coverage.farthest * 256.0).ceil().max(1.0) as u32;
        why.push(format!(
            "a band of {band}/256 px ({}, twice that)",
            probes.coverage.describe()
        ));
        band
    };
    let p = &probes.primitives;
    why.push(p.describe());
    let (point_clipping, clipping_why) = point_clipping(spec, reported);
    why.push(clipping_why);
    why.push(probes.slope.describe());
    Measured {
        snapping,
        fill,
        // Lines by the rule the probe saw (the nearest when none fits every probe segment: the
        // `line.` rules then show where), points when the driver draws them, and the 4 samples
        // where the probe found them.
        lines: p.line_rule().or(p.nearest_rule()),
        points: p.points.is_ok(),
        point_snapping: point_grid(probes, snapping),
        endpoint_snapping: end_grid(probes, snapping),
        multisample: p.pattern().into_iter().collect(),
        point_clipping,
        bias_slope: probes.slope.measure(),
        ties_to_even,
        snap,
        guard_band,
        precision_bits,
        tolerance_subpixels,
        reported: reported.map(Reported::describe).unwrap_or_default(),
        why: why.join(", "),
    }
}

/// What clipping does to points outside the viewport in x/y, with why: under Vulkan what the
/// device reports (`pointClippingBehavior`; Vulkan 1.1 requires it, so a device that prints
/// none is taken at the core's `ALL_CLIP_PLANES`), under OpenGL ES the specification's own
/// rule (§12.5: a point is clipped by the near and far planes only).
fn point_clipping(spec: Spec, reported: Option<&Reported>) -> (PointClipping, String) {
    match (spec, reported.and_then(|r| r.point_clipping)) {
        (Spec::OpenGlEs, _) => (
            PointClipping::UserClipPlanesOnly,
            "points clipped by the near and far planes only (OpenGL ES 3.2 §12.5)".to_owned(),
        ),
        (_, Some(c)) => (c, format!("points {} (vulkaninfo)", c.name())),
        (_, None) => (
            PointClipping::AllClipPlanes,
            "points all-clip-planes (none reported)".to_owned(),
        ),
    }
}

/// The grid points are snapped to when it is coarser than the triangles' (`None`: theirs).
fn point_grid(probes: &Probes, triangles: Snapping) -> Option<Snapping> {
    coarser_grid(probes.primitives.point_bits(), triangles)
}

/// The grid line ends are snapped to when it is coarser than the triangles' (`None`: theirs).
///
/// Read only where the driver's lines follow one rule exactly: the probe moves an end about
/// where that rule's last pixel changes, which another algorithm's need not (llvmpipe's lines
/// through OpenGL ES, off the diamond-exit rule at 10 probe pixels, read as 1 bit).
fn end_grid(probes: &Probes, triangles: Snapping) -> Option<Snapping> {
    probes.primitives.line_rule()?;
    coarser_grid(probes.primitives.end_bits(), triangles)
}

/// A probed grid of `probed` bits when coarser than the triangles' (`None`: theirs).
///
/// The point and line-end probes read one bit coarse at worst (a half step is a tie), so only
/// a grid coarser than that is a grid of its own.
fn coarser_grid(probed: Option<u8>, triangles: Snapping) -> Option<Snapping> {
    match (probed, triangles.grid_bits()) {
        (Some(probed), Some(bits)) if probed + 1 >= bits => None,
        (Some(probed), _) => Some(Snapping::Grid(probed.max(1))),
        (None, _) => None,
    }
}

/// The grid: Vulkan's is the `subPixelPrecisionBits` it reports, which the probe checks; under
/// OpenGL the probe's, or none when every step down to 2^-16 px moved coverage.
fn grid(spec: Spec, reported: Option<&Reported>, probes: &Probes) -> (Snapping, String) {
    let seen = probes.grid.describe();
    if let Some(bits) = reported.and_then(|r| r.subpixel_bits) {
        let agrees = if probes.grid.bits() == Some(bits) {
            "probe agrees".to_owned()
        } else {
            format!("the probe disagrees: {seen}")
        };
        return (
            Snapping::Grid(bits),
            format!("{bits} subpixel bits (vulkaninfo subPixelPrecisionBits; {agrees})"),
        );
    }
    let name = spec.title();
    match probes.grid.bits() {
        Some(bits) if bits > 0 => (
            Snapping::Grid(bits),
            format!("{bits} subpixel bits (measured, {name} reports none through wgpu: {seen})"),
        ),
        _ => (
            Snapping::Float,
            format!("no grid (measured, {name} reports none through wgpu: {seen})"),
        ),
    }
}

impl Measured {
    /// The declarations as reports list them: "top-left" and so on.
    #[must_use]
    pub fn summary(&self) -> String {
        let lines = self.lines.map_or("no lines", |r| r.name());
        let samples = if self.multisample.is_empty() {
            "1 sample"
        } else {
            "1 or 4 samples"
        };
        format!(
            "{}, {}, {}{}, guard band {} px, {} bits precision, {lines} lines, {samples}",
            self.snapping,
            fill_name(self.fill),
            match self.snap {
                SnapAccuracy::Nearest => "snapping to nearest".to_owned(),
                other => format!("snapping {}", other.name().replace('-', " ")),
            },
            if self.ties_to_even { ", ties to even" } else { "" },
            self.guard_band,
            self.precision_bits
        )
    }
}
