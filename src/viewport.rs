//! The viewport: its size limits and the one transform from NDC to raster space.

use crate::error::ConfigError;

/// The largest viewport side in pixels (D3D11's 16384; Vulkan guarantees at least 4096).
pub const MAX_VIEWPORT: u32 = 16384;

/// Half the side of the guard band in pixels, centred on the viewport.
///
/// Twice [`MAX_VIEWPORT`] wide, so it always contains the viewport, and within
/// [`COORD_LIMIT`](crate::COORD_LIMIT) with a margin that absorbs the clipper's rounding.
pub const GUARD_BAND: f64 = 16384.0;

/// How far beyond every side of every viewport the guard band reaches, in pixels: its half-side
/// less half the largest viewport, what the reference declares ([`Features::guard_band`]).
///
/// [`Features::guard_band`]: crate::Features::guard_band
pub const GUARD_BAND_REACH: u32 = GUARD_BAND as u32 - MAX_VIEWPORT / 2;

/// A render target's size in pixels; pixel (x, y) has its sample at (x + ½, y + ½).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Viewport {
    width: u32,
    height: u32,
}

impl Viewport {
    /// A viewport of `width × height` pixels, each side in `1..=MAX_VIEWPORT`.
    pub fn new(width: u32, height: u32) -> Result<Self, ConfigError> {
        let ok = |side| (1..=MAX_VIEWPORT).contains(&side);
        if ok(width) && ok(height) {
            Ok(Self { width, height })
        } else {
            Err(ConfigError::Viewport { width, height })
        }
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(self) -> u32 {
        self.height
    }

    /// Number of pixels, the length of a buffer covering the viewport.
    #[must_use]
    pub fn pixel_count(self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Index of pixel `(x, y)` in a row-major buffer.
    #[must_use]
    #[inline]
    pub fn index(self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// NDC to raster space: `x = (x_ndc + 1)/2 · W`, `y = (1 − y_ndc)/2 · H` (y flips to point down).
    #[must_use]
    pub fn to_raster(self, x_ndc: f64, y_ndc: f64) -> (f64, f64) {
        (
            (x_ndc + 1.0) * 0.5 * f64::from(self.width),
            (1.0 - y_ndc) * 0.5 * f64::from(self.height),
        )
    }

    /// Raster space to NDC, the inverse of [`to_raster`](Self::to_raster).
    #[must_use]
    pub fn to_ndc(self, x: f64, y: f64) -> (f64, f64) {
        (
            x / f64::from(self.width) * 2.0 - 1.0,
            1.0 - y / f64::from(self.height) * 2.0,
        )
    }

    /// The half extent in NDC units of a band reaching `px` pixels beyond each side: `|x| ≤ kx·w`
    /// keeps x inside it.
    #[must_use]
    pub fn reach_ndc(self, px: u32) -> (f64, f64) {
        let k = |side: u32| 1.0 + 2.0 * f64::from(px) / f64::from(side);
        (k(self.width), k(self.height))
    }

    /// The guard band's half extent in NDC units for x and y: `|x| ≤ gx·w` keeps x inside it.
    #[must_use]
    pub fn guard_band_ndc(self) -> (f64, f64) {
        (
            2.0 * GUARD_BAND / f64::from(self.width),
            2.0 * GUARD_BAND / f64::from(self.height),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A band of reach `px` ends `px` pixels beyond each side of the viewport.
    #[test]
    fn a_reach_ends_its_pixels_beyond_each_side() {
        for (w, h) in [(64, 32), (7, 1)] {
            let vp = Viewport::new(w, h).expect("a valid viewport");
            let (kx, ky) = vp.reach_ndc(64);
            let (x, y) = vp.to_raster(kx, ky);
            assert_eq!((x, y), (f64::from(w) + 64.0, -64.0), "{w}×{h}");
        }
    }

    /// The guard band's edge lies `GUARD_BAND` pixels from the viewport's centre on each axis,
    /// whatever the viewport's shape.
    #[test]
    fn the_guard_band_reaches_its_pixels_from_the_centre() {
        for (w, h) in [(64, 32), (7, 1), (MAX_VIEWPORT, 3)] {
            let vp = Viewport::new(w, h).expect("a valid viewport");
            let (gx, gy) = vp.guard_band_ndc();
            let (x, y) = vp.to_raster(gx, gy);
            assert_eq!(x - f64::from(w) / 2.0, GUARD_BAND, "{w}×{h}");
            assert_eq!(f64::from(h) / 2.0 - y, GUARD_BAND, "{w}×{h}");
        }
    }
}
