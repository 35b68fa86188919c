//! Shading (seeds 002 and 003): a point light with ambient, diffuse and specular terms and
//! attenuation, evaluated per triangle (flat), per vertex (Gouraud) or per pixel (Phong).

use std::fmt;
use std::str::FromStr;

use glam::{Vec3, Vec3A};

/// Where lighting is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    /// No lighting: the interpolated vertex colour (times the texture), as lab 000 draws.
    #[default]
    None,
    /// Once per triangle, at its centroid with its face normal: facets show.
    Flat,
    /// Once per vertex, the light then interpolated across the triangle (Gouraud 1971).
    Gouraud,
    /// Once per pixel, with the interpolated normal and position (Phong 1975; seed 002's last step).
    Phong,
}

impl Shading {
    /// Every shading, in the order `--help` lists them.
    pub const ALL: [Shading; 4] = [Self::None, Self::Flat, Self::Gouraud, Self::Phong];

    /// The name `--shading` takes.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Flat => "flat",
            Self::Gouraud => "gouraud",
            Self::Phong => "phong",
        }
    }
}

impl fmt::Display for Shading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Shading {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        crate::mode::parse_name(s, &Self::ALL, Self::name, "shading")
    }
}

/// A point light and the surface's response to it (CS174's lighting model, seed 003).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// World-space position.
    pub position: Vec3,
    /// Colour times power of the light.
    pub color: Vec3,
    /// Light reaching every surface from everywhere (seed 002's indirect light per area).
    pub ambient: Vec3,
    /// Constant, linear and quadratic attenuation: the light is divided by `c + l·d + q·d²`.
    pub attenuation: [f32; 3],
    /// Specular reflectance `k_s` (white highlights; 0 for none).
    pub specular: f32,
    /// Specular exponent.
    pub shininess: f32,
    /// Blinn-Phong (the half vector) instead of Phong (the reflected vector) for the highlight.
    pub blinn: bool,
}

impl Light {
    /// Seed 002's light: at (0, 0.5, −0.7) in our y-up world, power 1.1, indirect light 0.5,
    /// falling off as `1 / (4π d²)`, no highlight.
    pub const LAB_002: Light = Light {
        position: Vec3::new(0.0, 0.5, -0.7),
        color: Vec3::splat(1.1),
        ambient: Vec3::splat(0.5),
        attenuation: [0.0, 0.0, 4.0 * std::f32::consts::PI],
        specular: 0.0,
        shininess: 32.0,
        blinn: false,
    };

    /// A white light at `position` that does not fall off, with a soft ambient and a highlight:
    /// the default for meshes, where no scene says where the light is.
    #[must_use]
    pub fn headlight(position: Vec3) -> Self {
        Self {
            position,
            color: Vec3::splat(0.9),
            ambient: Vec3::splat(0.15),
            attenuation: [1.0, 0.0, 0.0],
            specular: 0.35,
            shininess: 32.0,
            blinn: false,
        }
    }

    /// The light at a surface point: `(diffuse, specular)` such that the colour is
    /// `albedo · diffuse + specular`.
    ///
    /// Lighting is two-sided: a normal facing away from the eye is turned around, so the inside
    /// of the room and the back of a flat mesh are lit as their front. A zero normal gets only
    /// the ambient term.
    #[must_use]
    pub fn at(&self, point: Vec3, normal: Vec3, eye: Vec3) -> (Vec3, Vec3) {
        let (diffuse, specular) = self.at_simd(point.into(), normal.into(), eye.into());
        (diffuse.into(), specular.into())
    }

    /// [`at`](Self::at) in SIMD lanes: the same operations in the same order, lane by lane
    /// (and dot products summed x, y, then z, as `Vec3`'s), so the same bits, in fewer
    /// instructions; Phong shading calls it once per pixel.
    #[must_use]
    pub(crate) fn at_simd(&self, point: Vec3A, normal: Vec3A, eye: Vec3A) -> (Vec3A, Vec3A) {
        let ambient = Vec3A::from(self.ambient);
        let Some(mut n) = normal.try_normalize() else {
            return (ambient, Vec3A::ZERO);
        };
        let to_eye = (eye - point).try_normalize().unwrap_or(Vec3A::ZERO);
        if n.dot(to_eye) < 0.0 {
            n = -n;
        }
        let to_light = Vec3A::from(self.position) - point;
        let distance = to_light.length();
        let Some(l) = to_light.try_normalize() else {
            return (ambient, Vec3A::ZERO);
        };
        let [c, lin, q] = self.attenuation;
        let falloff = c + lin * distance + q * distance * distance;
        let color = Vec3A::from(self.color);
        let incoming = if falloff > 0.0 { color / falloff } else { color };
        let lambert = n.dot(l).max(0.0);
        let diffuse = ambient + incoming * lambert;
        if self.specular <= 0.0 || lambert <= 0.0 {
            return (diffuse, Vec3A::ZERO);
        }
        let cosine = if self.blinn {
            (l + to_eye).try_normalize().map_or(0.0, |h| n.dot(h))
        } else {
            // The light reflected about the normal, against the direction to the eye.
            (2.0 * n.dot(l) * n - l).dot(to_eye)
        };
        let highlight = cosine.max(0.0).powf(self.shininess);
        (diffuse, incoming * self.specular * highlight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// `Light::at` as it was written in `Vec3` before it moved to SIMD lanes: the oracle that
    /// the lanes change no bit.
    fn at_in_vec3(light: &Light, point: Vec3, normal: Vec3, eye: Vec3) -> (Vec3, Vec3) {
        let Some(mut n) = normal.try_normalize() else {
            return (light.ambient, Vec3::ZERO);
        };
        let to_eye = (eye - point).try_normalize().unwrap_or(Vec3::ZERO);
        if n.dot(to_eye) < 0.0 {
            n = -n;
        }
        let to_light = light.position - point;
        let distance = to_light.length();
        let Some(l) = to_light.try_normalize() else {
            return (light.ambient, Vec3::ZERO);
        };
        let [c, lin, q] = light.attenuation;
        let falloff = c + lin * distance + q * distance * distance;
        let incoming = if falloff > 0.0 {
            light.color / falloff
        } else {
            light.color
        };
        let lambert = n.dot(l).max(0.0);
        let diffuse = light.ambient + incoming * lambert;
        if light.specular <= 0.0 || lambert <= 0.0 {
            return (diffuse, Vec3::ZERO);
        }
        let cosine = if light.blinn {
            (l + to_eye).try_normalize().map_or(0.0, |h| n.dot(h))
        } else {
            (2.0 * n.dot(l) * n - l).dot(to_eye)
        };
        (
            diffuse,
            incoming * light.specular * cosine.max(0.0).powf(light.shininess),
        )
    }

    #[test]
    fn simd_lanes_give_the_vec3_codes_bits() {
        // A small deterministic generator: points, normals and eyes over a few units.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 6.0 - 3.0
        };
        let lights = [
            Light::LAB_002,
            Light::headlight(Vec3::new(0.5, 2.0, -3.0)),
            Light {
                blinn: true,
                ..Light::headlight(Vec3::new(-1.0, 0.5, -2.0))
            },
        ];
        for light in lights {
            for _ in 0..20_000 {
                let mut v = || Vec3::new(next(), next(), next());
                let (point, normal, eye) = (v(), v(), v());
                let (d, s) = light.at(point, normal, eye);
                let (d0, s0) = at_in_vec3(&light, point, normal, eye);
                assert_eq!(
                    (d.to_array().map(f32::to_bits), s.to_array().map(f32::to_bits)),
                    (d0.to_array().map(f32::to_bits), s0.to_array().map(f32::to_bits)),
                    "{light:?} at {point}, {normal}, eye {eye}"
                );
            }
        }
    }

    #[test]
    fn lab_light_follows_the_lab_formula() {
        // R = ρ (P max(r̂·n̂, 0) / (4π r²) + N), straight below the light at distance 1.
        let light = Light::LAB_002;
        let point = light.position - Vec3::Y;
        let (diffuse, specular) = light.at(point, Vec3::Y, point + Vec3::Y);
        let expected = 0.5 + 1.1 / (4.0 * std::f32::consts::PI);
        assert_relative_eq!(diffuse, Vec3::splat(expected), epsilon = 1e-6);
        assert_eq!(specular, Vec3::ZERO);
        // At 45° and distance √2 the cosine and the square fall off together.
        let point = light.position - Vec3::new(1.0, 1.0, 0.0);
        let (diffuse, _) = light.at(point, Vec3::Y, point + Vec3::Y);
        let expected = 0.5 + 1.1 * std::f32::consts::FRAC_1_SQRT_2 / (4.0 * std::f32::consts::PI * 2.0);
        assert_relative_eq!(diffuse.x, expected, epsilon = 1e-6);
    }

    #[test]
    fn lighting_is_two_sided_and_zero_normals_get_ambient() {
        let light = Light::headlight(Vec3::new(0.0, 0.0, -5.0));
        let eye = Vec3::new(0.0, 0.0, -5.0);
        let front = light.at(Vec3::ZERO, -Vec3::Z, eye);
        let back = light.at(Vec3::ZERO, Vec3::Z, eye);
        assert_eq!(front, back);
        assert_relative_eq!(front.0, Vec3::splat(0.15 + 0.9), epsilon = 1e-6);
        assert_eq!(
            light.at(Vec3::ZERO, Vec3::ZERO, eye),
            (Vec3::splat(0.15), Vec3::ZERO)
        );
    }

    #[test]
    fn phong_and_blinn_highlights_peak_at_the_mirror_direction() {
        let mut light = Light::headlight(Vec3::new(-1.0, 0.0, -1.0));
        let mirror_eye = Vec3::new(1.0, 0.0, -1.0);
        let off_eye = Vec3::new(0.0, 0.0, -1.0);
        let n = -Vec3::Z;
        for blinn in [false, true] {
            light.blinn = blinn;
            let peak = light.at(Vec3::ZERO, n, mirror_eye).1;
            let off = light.at(Vec3::ZERO, n, off_eye).1;
            assert_relative_eq!(peak, Vec3::splat(0.9 * 0.35), epsilon = 1e-5);
            assert!(off.x < peak.x, "blinn {blinn}: {off} vs {peak}");
        }
        // Off the mirror direction Blinn's half-vector falls off more slowly than Phong's.
        light.blinn = false;
        let phong = light.at(Vec3::ZERO, n, off_eye).1.x;
        light.blinn = true;
        let blinn = light.at(Vec3::ZERO, n, off_eye).1.x;
        assert!(blinn > phong, "{blinn} vs {phong}");
    }

    #[test]
    fn shading_names_round_trip() {
        for s in Shading::ALL {
            assert_eq!(s.name().parse::<Shading>(), Ok(s));
        }
        let err = "gouraudd".parse::<Shading>().unwrap_err();
        assert!(err.contains("none, flat, gouraud, phong"), "{err}");
    }
}
