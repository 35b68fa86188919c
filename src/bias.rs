//! Depth bias (polygon offset): one value per polygon, from its depth slope and its depth
//! format's resolvable difference, added to the depth of every fragment it covers, so that
//! decals and shadow maps can be drawn a little in front of (or behind) what they lie on.

use std::fmt;

use crate::depth::ViewportDepth;
use crate::fixed::SubpixelBits;
use crate::project::RasterVertex;

/// A draw's depth bias: Vulkan's `depthBiasConstantFactor`, `depthBiasSlopeFactor` and
/// `depthBiasClamp`; OpenGL's `PolygonOffsetClamp(factor, units, clamp)`; D3D11's `DepthBias`,
/// `SlopeScaledDepthBias` and `DepthBiasClamp`. Applied to triangles only (lines and points
/// are drawn unbiased: Vulkan "may" bias them, OpenGL offsets only polygons).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct DepthBias {
    /// What multiplies the depth format's resolvable difference `r` (OpenGL's `units`).
    pub constant: f32,
    /// What multiplies the polygon's depth slope `m` (OpenGL's `factor`).
    pub slope: f32,
    /// The largest offset when positive, the smallest when negative; 0 clamps nothing.
    pub clamp: f32,
}

impl DepthBias {
    /// The offset `o = dbclamp(m·slope + r·constant)` of a polygon with depth slope `m` drawn
    /// to a format whose resolvable difference there is `r` (Vulkan, Depth Bias Computation).
    #[must_use]
    pub fn offset(self, m: f64, r: f64) -> f64 {
        self.clamped(m * f64::from(self.slope) + r * f64::from(self.constant))
    }

    /// Vulkan's `dbclamp`: `o` at most `clamp` when it is positive, at least `clamp` when it is
    /// negative, unchanged when it is 0.
    #[must_use]
    pub fn clamped(self, o: f64) -> f64 {
        let k = f64::from(self.clamp);
        if k > 0.0 {
            o.min(k)
        } else if k < 0.0 {
            o.max(k)
        } else {
            o
        }
    }

    /// `Err` naming what to fix unless all three are finite (Vulkan reads a NaN clamp as 0;
    /// refrast asks for the 0).
    pub fn validate(self) -> Result<(), String> {
        if [self.constant, self.slope, self.clamp]
            .iter()
            .all(|v| v.is_finite())
        {
            return Ok(());
        }
        Err(format!(
            "depth bias constant {} slope {} clamp {}: each must be finite (clamp 0 clamps nothing)",
            self.constant, self.slope, self.clamp
        ))
    }
}

/// The depth attachment's representation, which fixes `r`, the smallest depth difference it
/// keeps distinct.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum DepthFormat {
    /// 16-bit fixed point (`D16_UNORM`): `r = 2^-16`.
    Unorm16,
    /// 24-bit fixed point (`X8_D24_UNORM_PACK32`, `D24_UNORM_S8_UINT`): `r = 2^-24`.
    Unorm24,
    /// 32-bit float (`D32_SFLOAT`): `r = 2^(e − 23)`, `e` the exponent of the polygon's largest
    /// depth. refrast's own, and what the wgpu adapter draws to.
    #[default]
    Float32,
}

impl DepthFormat {
    /// Every format.
    pub const ALL: [DepthFormat; 3] = [Self::Unorm16, Self::Unorm24, Self::Float32];

    /// The word the pipe protocol and reports use: `unorm16`, `unorm24`, `float32`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Unorm16 => "unorm16",
            Self::Unorm24 => "unorm24",
            Self::Float32 => "float32",
        }
    }

    /// The format called `name` ([`DepthFormat::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The bits of a fixed-point format; `None` for a float one.
    #[must_use]
    pub fn unorm_bits(self) -> Option<i32> {
        match self {
            Self::Unorm16 => Some(16),
            Self::Unorm24 => Some(24),
            Self::Float32 => None,
        }
    }

    /// `r` for a polygon whose largest depth magnitude, in f32, is `max_z`: `2^-n` for `n`-bit
    /// fixed point, `2^(e − 23)` for f32 with `max_z` in `[2^e, 2^(e+1))` (Vulkan, Depth Bias
    /// Computation: "the maximum exponent, e, in the range of z values spanned by the
    /// primitive"; D3D11.3 §15.10 the same). A polygon at depth 0 takes the smallest normal
    /// exponent, −126, which f32's subnormals share.
    #[must_use]
    pub fn resolvable_difference(self, max_z: f32) -> f64 {
        match self.unorm_bits() {
            Some(n) => 2f64.powi(-n),
            None => 2f64.powi(f32_exponent(max_z) - 23),
        }
    }
}

impl fmt::Display for DepthFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The exponent `e` of `|v|` as f32 stores it, `|v|` in `[2^e, 2^(e+1))`; −126 for subnormals
/// and zero (their stored exponent's), 127 for infinities and NaN (the largest).
#[must_use]
pub fn f32_exponent(v: f32) -> i32 {
    let biased = ((v.to_bits() >> 23) & 0xff) as i32;
    biased.clamp(1, 254) - 127
}

/// How an implementation measures `m`, a polygon's depth slope in depth per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum DepthSlope {
    /// `√((∂z/∂x)² + (∂z/∂y)²)`, Vulkan's and OpenGL's definition (refrast's).
    #[default]
    Exact,
    /// `max(|∂z/∂x|, |∂z/∂y|)`, the approximation Vulkan and OpenGL allow and D3D11.3 defines.
    Max,
    /// Either of them, or anything between: what a profile that cannot say declares.
    Either,
}

impl DepthSlope {
    /// Every measure.
    pub const ALL: [DepthSlope; 3] = [Self::Exact, Self::Max, Self::Either];

    /// The word the pipe protocol and reports use: `exact`, `max`, `either`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::Max => "max",
            Self::Either => "either",
        }
    }

    /// The measure called `name` ([`DepthSlope::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// `m` of a plane whose depth changes by `dzdx` and `dzdy` a pixel, as this measure takes
    /// it (`Either` as `Exact`, the definition).
    #[must_use]
    pub fn measure(self, dzdx: f64, dzdy: f64) -> f64 {
        match self {
            Self::Exact | Self::Either => dzdx.hypot(dzdy),
            Self::Max => dzdx.abs().max(dzdy.abs()),
        }
    }
}

/// The depth bias an implementation honours ([`StateSupport::depth_bias`](crate::StateSupport::depth_bias)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BiasSupport {
    /// The depth format its bias is computed for, which fixes `r`.
    pub format: DepthFormat,
    /// How it measures the depth slope `m`.
    pub slope: DepthSlope,
    /// Whether it honours [`DepthBias::clamp`] (wgpu's OpenGL backend may not); without it the
    /// suite sends a clamp of 0.
    pub clamp: bool,
}

impl BiasSupport {
    /// The reference's: f32 depth, the exact slope, the clamp.
    pub const REFERENCE: BiasSupport = BiasSupport {
        format: DepthFormat::Float32,
        slope: DepthSlope::Exact,
        clamp: true,
    };
}

/// The reference's depth offset for a polygon drawn through `polygon` (snapped on a grid of
/// `bits`, carrying window depth): `m` from the plane through its widest fan triangle
/// `(0, i, i + 1)`, `r` from its largest depth in f32, under [`BiasSupport::REFERENCE`]. 0
/// when `bias` is `None` or the polygon has no area.
#[must_use]
pub fn polygon_offset(bias: Option<DepthBias>, polygon: &[RasterVertex], bits: SubpixelBits) -> f64 {
    let (Some(bias), Some(first)) = (bias, polygon.first()) else {
        return 0.0;
    };
    let (a, za) = (first.position, first.varyings.depth);
    let widest = polygon
        .windows(2)
        .skip(1)
        .map(|pair| {
            let (b, c) = (pair[0].position, pair[1].position);
            let det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            (det, pair)
        })
        .max_by_key(|(det, _)| det.unsigned_abs());
    let Some((det, [b, c])) = widest else {
        return 0.0;
    };
    if det == 0 {
        return 0.0;
    }
    let one = bits.one() as f64;
    let edge = |v: &RasterVertex| ((v.position.x - a.x) as f64, (v.position.y - a.y) as f64);
    let ((x1, y1), (x2, y2)) = (edge(b), edge(c));
    let (dz1, dz2) = (b.varyings.depth - za, c.varyings.depth - za);
    let det = det as f64;
    // Cramer's rule on the two edges, in grid units, then scaled to depth per pixel.
    let dzdx = (dz1 * y2 - dz2 * y1) / det * one;
    let dzdy = (dz2 * x1 - dz1 * x2) / det * one;
    let max_z = polygon
        .iter()
        .map(|v| (v.varyings.depth as f32).abs())
        .fold(0.0f32, f32::max);
    let support = BiasSupport::REFERENCE;
    bias.offset(
        support.slope.measure(dzdx, dzdy),
        support.format.resolvable_difference(max_z),
    )
}

/// What makes a triangle's interpolated depth a fragment's: its polygon's offset added, then
/// the viewport's range clamping the sum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FragmentDepth {
    /// The viewport's depth range, which clamps.
    pub range: ViewportDepth,
    /// The polygon's depth bias `o` ([`polygon_offset`]).
    pub offset: f64,
}

impl FragmentDepth {
    /// Offsets by `offset`, then clamps to `range`.
    #[must_use]
    pub fn new(range: ViewportDepth, offset: f64) -> Self {
        Self { range, offset }
    }

    /// The depth a fragment stores for interpolated depth `z`: `z + o`, clamped to the range
    /// ([`ViewportDepth::fragment_depth`]; Vulkan biases before Depth Clamping and Range
    /// Adjustment).
    #[must_use]
    #[inline]
    pub fn of(self, z: f64) -> f32 {
        self.range.fragment_depth(z + self.offset)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The clamp bounds the offset from above when positive, from below when negative, and
    /// not at all when 0; the offset is `m·slope + r·constant` before it.
    #[test]
    fn the_offset_is_slope_and_constant_terms_clamped_as_vulkan_says() {
        let bias = DepthBias {
            constant: 4.0,
            slope: -2.0,
            clamp: 0.0,
        };
        assert_eq!(bias.offset(0.5, 0.25), 0.0);
        assert_eq!(bias.offset(0.25, 0.25), 0.5);
        let up = DepthBias { clamp: 0.125, ..bias };
        assert_eq!(up.offset(0.25, 0.25), 0.125);
        assert_eq!(up.offset(1.0, 0.25), -1.0);
        let down = DepthBias {
            clamp: -0.125,
            ..bias
        };
        assert_eq!(down.offset(1.0, 0.25), -0.125);
        assert_eq!(down.offset(0.25, 0.25), 0.5);
        assert!(bias.validate().is_ok());
        let bad = DepthBias {
            clamp: f32::NAN,
            ..bias
        };
        assert!(bad.validate().is_err_and(|m| m.contains("finite")));
    }

    /// `r` is `2^-n` for fixed point whatever the depth, and one f32 ulp step below the
    /// polygon's largest depth's binade for float: `2^(e − 23)`.
    #[test]
    fn the_resolvable_difference_follows_the_format() {
        assert_eq!(DepthFormat::Unorm16.resolvable_difference(0.7), 2f64.powi(-16));
        assert_eq!(DepthFormat::Unorm24.resolvable_difference(0.001), 2f64.powi(-24));
        assert_eq!(DepthFormat::Float32.resolvable_difference(0.5), 2f64.powi(-24));
        assert_eq!(DepthFormat::Float32.resolvable_difference(0.99), 2f64.powi(-24));
        assert_eq!(DepthFormat::Float32.resolvable_difference(1.0), 2f64.powi(-23));
        assert_eq!(DepthFormat::Float32.resolvable_difference(0.3), 2f64.powi(-25));
        assert_eq!(DepthFormat::Float32.resolvable_difference(0.0), 2f64.powi(-149));
        assert_eq!(f32_exponent(-3.0), 1);
        assert_eq!(f32_exponent(f32::INFINITY), 127);
        for format in DepthFormat::ALL {
            assert_eq!(DepthFormat::from_name(format.name()), Some(format));
        }
        for slope in DepthSlope::ALL {
            assert_eq!(DepthSlope::from_name(slope.name()), Some(slope));
        }
    }

    /// The reference's offset of a right triangle 32 px a side, depth 0.25 at its right angle
    /// rising by 1/128 a pixel in x and 1/256 in y: `m` the gradient's length, `r = 2^-24` (its
    /// largest depth, 0.5, is in [2^-1, 1)); clipped polygons take the widest fan triangle, so a
    /// sliver appended on the same plane changes nothing; no bias, no offset.
    #[test]
    fn the_polygon_offset_is_the_plane_slope_and_the_largest_depths_r() {
        use crate::interp::Varyings;
        use glam::DVec3;
        let bits = SubpixelBits::DEFAULT;
        let one = bits.one();
        let vertex = |x: i64, y: i64, depth: f64| RasterVertex {
            position: crate::fixed::FixedPoint {
                x: x * one,
                y: y * one,
            },
            varyings: Varyings {
                depth,
                inv_w: 1.0,
                barycentric: DVec3::X,
                screen: None,
            },
        };
        let triangle = [vertex(0, 0, 0.25), vertex(32, 0, 0.5), vertex(0, 32, 0.375)];
        let bias = DepthBias {
            constant: 2.0,
            slope: 1.0,
            clamp: 0.0,
        };
        let m = (1.0f64 / 128.0).hypot(1.0 / 256.0);
        let expected = m + 2.0 * 2f64.powi(-24);
        assert!((polygon_offset(Some(bias), &triangle, bits) - expected).abs() < 1e-15);
        let mut polygon = triangle.to_vec();
        polygon.push(vertex(0, 16, 0.3125));
        assert!((polygon_offset(Some(bias), &polygon, bits) - expected).abs() < 1e-15);
        assert_eq!(polygon_offset(None, &triangle, bits), 0.0);
        let flat = [vertex(0, 0, 0.25), vertex(32, 0, 0.5), vertex(64, 0, 0.75)];
        assert_eq!(polygon_offset(Some(bias), &flat, bits), 0.0, "no area, no plane");
        let range = ViewportDepth { min: 0.25, max: 0.5 };
        assert_eq!(
            FragmentDepth::new(range, 0.5).of(0.3),
            0.5,
            "offset, then clamped"
        );
    }

    /// A slope along a diagonal is √2 times its larger component under the exact measure.
    #[test]
    fn the_exact_slope_is_the_gradients_length_and_max_its_largest_component() {
        assert_eq!(DepthSlope::Exact.measure(3.0, -4.0), 5.0);
        assert_eq!(DepthSlope::Max.measure(3.0, -4.0), 4.0);
        assert_eq!(DepthSlope::Either.measure(3.0, -4.0), 5.0);
    }
}
