//! Snapping raster-space coordinates to the subpixel grid.
//!
//! Every coverage decision in refrast is made on these integers; floats never decide coverage.

use crate::error::ConfigError;

/// The largest magnitude, in pixels, that a snapped raster coordinate may have.
///
/// At 8 subpixel bits a coordinate is at most 2^23 units, an edge difference 2^24 and an edge
/// product 2^48, so [`orient2d`](crate::orient2d) is exact in `i64` with 14 bits to spare.
/// It matches D3D11's 16.8 fixed-point range (§3.2.4.1).
pub const COORD_LIMIT: f64 = 32768.0;

/// The number of fractional bits of the subpixel grid (1..=8; 8 is D3D11 and Vulkan Roadmap 2026).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SubpixelBits(u8);

impl SubpixelBits {
    /// The fewest bits accepted: one bit is needed to place the sample at the pixel centre.
    pub const MIN: u8 = 1;
    /// The most bits accepted: 8, as D3D11 and Vulkan Roadmap 2026 use; [`FixedPoint::LIMIT`] is sized for it.
    pub const MAX: u8 = 8;
    /// Eight bits, as D3D11 mandates and Vulkan Roadmap 2026 requires.
    pub const DEFAULT: SubpixelBits = SubpixelBits(8);

    /// Checks that `bits` lies in `MIN..=MAX`.
    pub fn new(bits: u8) -> Result<Self, ConfigError> {
        if (Self::MIN..=Self::MAX).contains(&bits) {
            Ok(Self(bits))
        } else {
            Err(ConfigError::SubpixelBits(bits))
        }
    }

    /// The number of fractional bits.
    #[must_use]
    pub fn get(self) -> u8 {
        self.0
    }

    /// Subpixel units per pixel, `2^bits`.
    #[must_use]
    #[inline]
    pub fn one(self) -> i64 {
        1 << self.0
    }

    /// The pixel holding subpixel coordinate `v`: `⌊v / 2^bits⌋`, as an arithmetic shift,
    /// which floors exactly as `div_euclid` by [`one`](Self::one) does, without a division.
    #[must_use]
    #[inline]
    pub fn pixel_of(self, v: i64) -> i64 {
        v >> self.0
    }
}

impl Default for SubpixelBits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A raster-space point on the subpixel grid, in units of `2^-bits` pixel.
///
/// Its coordinates never exceed [`FixedPoint::LIMIT`] in magnitude (the constructors check),
/// which is what makes every edge function on it exact in `i64`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct FixedPoint {
    pub(crate) x: i64,
    pub(crate) y: i64,
}

impl FixedPoint {
    /// The largest coordinate magnitude in subpixel units: [`COORD_LIMIT`] at the finest grid.
    pub const LIMIT: i64 = (COORD_LIMIT as i64) << SubpixelBits::MAX;

    /// A point from subpixel units, or `None` beyond [`LIMIT`](Self::LIMIT).
    #[must_use]
    pub fn new(x: i64, y: i64) -> Option<Self> {
        (x.abs() <= Self::LIMIT && y.abs() <= Self::LIMIT).then_some(Self { x, y })
    }

    /// x in subpixel units, growing to the right.
    #[must_use]
    pub fn x(self) -> i64 {
        self.x
    }

    /// y in subpixel units, growing downwards.
    #[must_use]
    pub fn y(self) -> i64 {
        self.y
    }

    /// Snaps a raster-space point, or `None` when a coordinate is not finite or exceeds [`COORD_LIMIT`].
    #[must_use]
    pub fn snap(x: f64, y: f64, bits: SubpixelBits) -> Option<Self> {
        Self::snap_rounding(x, y, bits, SnapRounding::NearestEven)
    }

    /// [`snap`](Self::snap) with another rounding.
    #[must_use]
    pub fn snap_rounding(x: f64, y: f64, bits: SubpixelBits, rounding: SnapRounding) -> Option<Self> {
        // Snapping stays within COORD_LIMIT pixels, hence within LIMIT units at any grid.
        Some(Self {
            x: rounding.snap(x, bits)?,
            y: rounding.snap(y, bits)?,
        })
    }

    /// The sample position of pixel `(px, py)`, its centre `(px + ½, py + ½)`; `None` for a
    /// pixel beyond [`COORD_LIMIT`].
    #[must_use]
    pub fn sample(px: i64, py: i64, bits: SubpixelBits) -> Option<Self> {
        let limit = COORD_LIMIT as i64;
        (px.abs() < limit && py.abs() < limit).then(|| Self::pixel_sample(px, py, bits))
    }

    /// The sample of a pixel of a viewport (sides at most [`MAX_VIEWPORT`](crate::MAX_VIEWPORT)).
    #[must_use]
    #[inline]
    pub(crate) fn pixel_sample(px: i64, py: i64, bits: SubpixelBits) -> Self {
        let half = bits.one() / 2;
        Self {
            x: px * bits.one() + half,
            y: py * bits.one() + half,
        }
    }

    /// Back to raster space in pixels (exact: at most 23 significant bits).
    #[must_use]
    pub fn to_raster(self, bits: SubpixelBits) -> (f64, f64) {
        let one = bits.one() as f64;
        (self.x as f64 / one, self.y as f64 / one)
    }
}

/// Snaps one raster coordinate to the grid, rounding half to even (D3D11 §3.2.4.1).
///
/// `None` when `v` is NaN, infinite or beyond [`COORD_LIMIT`].
#[must_use]
pub fn snap(v: f64, bits: SubpixelBits) -> Option<i64> {
    SnapRounding::NearestEven.snap(v, bits)
}

/// How a raster coordinate becomes a grid point: refrast's convention and the others a profile
/// may declare, so that the reference can play any of them (`refrast impls`, the restricted
/// configurations).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SnapRounding {
    /// To the nearest grid point, halves to even (D3D11 §3.2.4.1): refrast's convention.
    #[default]
    NearestEven,
    /// To the nearest grid point, halves away from zero (dEQP's reference renderer); Vulkan
    /// leaves ties to the implementation.
    NearestAwayFromZero,
    /// Down to the grid point at or below: always within one grid step of the exact value, on
    /// the far side of it half the time.
    Floor,
    /// Toward zero, to the grid point between the exact value and the raster origin: the
    /// truncation of a float-to-fixed conversion (Skia's 26.6 fixed point).
    TowardZero,
}

impl SnapRounding {
    /// `v` pixels in grid units; `None` when `v` is NaN, infinite or beyond [`COORD_LIMIT`].
    #[must_use]
    pub fn snap(self, v: f64, bits: SubpixelBits) -> Option<i64> {
        if !v.is_finite() || v.abs() > COORD_LIMIT {
            return None;
        }
        // Exact: scaling by a power of two only changes the exponent.
        let scaled = v * bits.one() as f64;
        Some(match self {
            Self::NearestEven => scaled.round_ties_even(),
            Self::NearestAwayFromZero => scaled.round(),
            Self::Floor => scaled.floor(),
            Self::TowardZero => scaled.trunc(),
        } as i64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shift floors as `div_euclid` does, on both sides of zero, at every grid, up to the
    /// coordinate limit.
    #[test]
    fn pixel_of_floors_as_division_does() {
        for bits in SubpixelBits::MIN..=SubpixelBits::MAX {
            let bits = SubpixelBits::new(bits).expect("in range");
            let one = bits.one();
            for v in [
                0,
                1,
                -1,
                one - 1,
                one,
                one + 1,
                -one,
                -one - 1,
                -one + 1,
                37 * one + 5,
            ]
            .into_iter()
            .chain([FixedPoint::LIMIT, -FixedPoint::LIMIT, FixedPoint::LIMIT - 1])
            {
                assert_eq!(bits.pixel_of(v), v.div_euclid(one), "{v} at {bits:?}");
            }
        }
    }

    /// Each rounding at a tie, just past one, and on a grid point (4 bits: 1/16 px).
    #[test]
    fn roundings_differ_only_where_they_should() {
        let bits = SubpixelBits::new(4).expect("4 bits");
        let at = |r: SnapRounding, v: f64| r.snap(v, bits).expect("in range");
        let tie = 2.5 / 16.0;
        assert_eq!(at(SnapRounding::NearestEven, tie), 2);
        assert_eq!(at(SnapRounding::NearestAwayFromZero, tie), 3);
        assert_eq!(at(SnapRounding::NearestAwayFromZero, -tie), -3);
        assert_eq!(at(SnapRounding::Floor, 2.9 / 16.0), 2);
        assert_eq!(at(SnapRounding::Floor, -2.1 / 16.0), -3);
        for r in [
            SnapRounding::NearestEven,
            SnapRounding::NearestAwayFromZero,
            SnapRounding::Floor,
        ] {
            assert_eq!(at(r, 3.0 / 16.0), 3);
            assert_eq!(r.snap(f64::NAN, bits), None);
        }
    }

    #[test]
    fn a_snapped_point_reads_back_its_units() {
        // (2.25, −3.5) px at 8 bits: 576 and −896 units; the sample of pixel (1, 2) at its centre.
        let p = FixedPoint::snap(2.25, -3.5, SubpixelBits::DEFAULT).unwrap();
        assert_eq!((p.x(), p.y()), (576, -896));
        let s = FixedPoint::sample(1, 2, SubpixelBits::DEFAULT).unwrap();
        assert_eq!((s.x(), s.y()), (384, 640));
        assert_eq!(p.to_raster(SubpixelBits::DEFAULT), (2.25, -3.5));
    }

    /// A pixel's sample exists only while it stays within [`FixedPoint::LIMIT`]: pixel 32768
    /// would put its centre half a pixel beyond it.
    #[test]
    fn samples_end_at_the_coordinate_limit() {
        let bits = SubpixelBits::DEFAULT;
        let last = COORD_LIMIT as i64 - 1;
        assert!(FixedPoint::sample(last, -last, bits).is_some());
        assert!(FixedPoint::sample(last + 1, 0, bits).is_none());
        assert!(FixedPoint::sample(0, -(last + 1), bits).is_none());
    }
}
