//! Textures (seed 003): an image sampled at perspective-correct uv, nearest or bilinear,
//! repeating outside `[0, 1]`.

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use glam::{Vec2, Vec4};

/// How a texture is read between texel centres.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Sampling {
    /// The texel under the sample.
    Nearest,
    /// The four nearest texels, weighted by distance (seed 003's bilinear interpolation).
    #[default]
    Bilinear,
}

impl Sampling {
    /// Every sampling, in the order `--help` lists them.
    pub const ALL: [Sampling; 2] = [Self::Nearest, Self::Bilinear];

    /// The name `--sampling` takes.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Nearest => "nearest",
            Self::Bilinear => "bilinear",
        }
    }
}

impl fmt::Display for Sampling {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Sampling {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("no sampling named '{s}'; the samplings are: nearest, bilinear"))
    }
}

/// Why a texture could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file could not be opened or decoded.
    #[error("could not read the texture {path}: {reason}")]
    Unreadable {
        /// The file.
        path: String,
        /// What the decoder said.
        reason: String,
    },
}

/// An RGBA texture in linear `[0, 1]` values, row 0 at `v = 0` (the top of the image).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    texels: Vec<Vec4>,
}

impl Texture {
    /// The largest side accepted from a file: 16384 texels, as the largest framebuffer.
    pub const MAX_SIDE: u32 = 16384;

    /// Reads a PNG or JPEG file.
    pub fn open(path: &Path) -> Result<Self, TextureError> {
        let unreadable = |reason: String| TextureError::Unreadable {
            path: path.display().to_string(),
            reason,
        };
        let mut reader = image::ImageReader::open(path)
            .map_err(|e| unreadable(e.to_string()))?
            .with_guessed_format()
            .map_err(|e| unreadable(e.to_string()))?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(Self::MAX_SIDE);
        limits.max_image_height = Some(Self::MAX_SIDE);
        reader.limits(limits);
        let image = reader.decode().map_err(|e| unreadable(e.to_string()))?;
        let rgba = image.to_rgba8();
        let texels = rgba
            .pixels()
            .map(|p| Vec4::from_array(p.0.map(f32::from)) / 255.0)
            .collect();
        Ok(Self {
            width: rgba.width(),
            height: rgba.height(),
            texels,
        })
    }

    /// A checkerboard of `cells × cells` squares in two colours: shows at a glance whether uv
    /// is interpolated with perspective (straight lines) or without (bent ones).
    #[must_use]
    pub fn checker(cells: u32, texels_per_cell: u32, a: Vec4, b: Vec4) -> Self {
        let cells = cells.clamp(1, 256);
        let per = texels_per_cell.clamp(1, 64);
        let side = cells * per;
        let texels = (0..side * side)
            .map(|i| {
                let (x, y) = (i % side / per, i / side / per);
                if (x + y) % 2 == 0 { a } else { b }
            })
            .collect();
        Self {
            width: side,
            height: side,
            texels,
        }
    }

    /// `(width, height)` in texels.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The texel at integer coordinates, wrapped: the texture repeats.
    fn texel(&self, x: i64, y: i64) -> Vec4 {
        let x = x.rem_euclid(i64::from(self.width)) as usize;
        let y = y.rem_euclid(i64::from(self.height)) as usize;
        self.texels[y * self.width as usize + x]
    }

    /// The colour at `uv`; a non-finite uv reads texel (0, 0).
    #[must_use]
    pub fn sample(&self, uv: Vec2, sampling: Sampling) -> Vec4 {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        // Texel space: texel centres at half-integers; wrapped to one period first, so that
        // huge coordinates keep their fraction.
        let u = uv.x.rem_euclid(1.0) * self.width as f32;
        let v = uv.y.rem_euclid(1.0) * self.height as f32;
        match sampling {
            Sampling::Nearest => self.texel(u.floor() as i64, v.floor() as i64),
            Sampling::Bilinear => {
                let (x, y) = (u - 0.5, v - 0.5);
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (x - x0, y - y0);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let top = self.texel(x0, y0).lerp(self.texel(x0 + 1, y0), fx);
                let bottom = self.texel(x0, y0 + 1).lerp(self.texel(x0 + 1, y0 + 1), fx);
                top.lerp(bottom, fy)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn two_by_one() -> Texture {
        Texture {
            width: 2,
            height: 1,
            texels: vec![Vec4::ZERO, Vec4::ONE],
        }
    }

    #[test]
    fn nearest_reads_the_texel_under_the_sample_and_repeats() {
        let t = two_by_one();
        assert_eq!(t.sample(Vec2::new(0.25, 0.5), Sampling::Nearest), Vec4::ZERO);
        assert_eq!(t.sample(Vec2::new(0.75, 0.5), Sampling::Nearest), Vec4::ONE);
        assert_eq!(t.sample(Vec2::new(1.75, 0.5), Sampling::Nearest), Vec4::ONE);
        assert_eq!(t.sample(Vec2::new(-0.25, 0.5), Sampling::Nearest), Vec4::ONE);
        assert_eq!(t.sample(Vec2::new(f32::NAN, 0.5), Sampling::Nearest), Vec4::ZERO);
    }

    #[test]
    fn bilinear_blends_between_texel_centres() {
        let t = two_by_one();
        // Texel centres at u = 0.25 and 0.75: exact there, halfway between at 0.5.
        assert_relative_eq!(t.sample(Vec2::new(0.25, 0.5), Sampling::Bilinear), Vec4::ZERO);
        assert_relative_eq!(t.sample(Vec2::new(0.75, 0.5), Sampling::Bilinear), Vec4::ONE);
        assert_relative_eq!(
            t.sample(Vec2::new(0.5, 0.5), Sampling::Bilinear),
            Vec4::splat(0.5)
        );
        // At u = 0 the neighbours are the last texel (wrapped) and the first: halfway again.
        assert_relative_eq!(
            t.sample(Vec2::new(0.0, 0.5), Sampling::Bilinear),
            Vec4::splat(0.5)
        );
        assert_relative_eq!(
            t.sample(Vec2::new(0.375, 0.5), Sampling::Bilinear),
            Vec4::splat(0.25)
        );
    }

    #[test]
    fn checker_alternates() {
        let t = Texture::checker(2, 1, Vec4::ZERO, Vec4::ONE);
        assert_eq!(t.size(), (2, 2));
        assert_eq!(t.texels, vec![Vec4::ZERO, Vec4::ONE, Vec4::ONE, Vec4::ZERO]);
    }

    #[test]
    fn a_missing_texture_names_the_file() {
        let err = Texture::open(Path::new("/no/such/texture.png")).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("could not read the texture /no/such/texture.png: "),
            "{err}"
        );
    }
}
