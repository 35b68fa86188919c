//! What a picture shows: the modes of `refrast render` (seeds 002 and 004) and the false
//! colours of the diagnostic ones.

use std::fmt;
use std::str::FromStr;

use glam::{Vec3, Vec4};

/// What is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Mode {
    /// Each vertex as one pixel (seed 002's first step).
    Points,
    /// Each edge as a line, colour and depth interpolated (seed 004's line mode).
    Wire,
    /// Filled triangles, depth-tested and shaded.
    #[default]
    Fill,
    /// The depth buffer, near bright and far dark.
    Depth,
    /// The interpolated world-space normal as a colour, `n · ½ + ½`.
    Normals,
    /// The perspective-correct barycentrics as red, green and blue.
    Barycentric,
    /// Fragments per pixel before the depth test: double coverage and cracks at a glance.
    Overdraw,
}

impl Mode {
    /// Every mode, in the order `--help` lists them (and the viewer's number keys).
    pub const ALL: [Mode; 7] = [
        Self::Points,
        Self::Wire,
        Self::Fill,
        Self::Depth,
        Self::Normals,
        Self::Barycentric,
        Self::Overdraw,
    ];

    /// The name `--mode` takes.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Points => "points",
            Self::Wire => "wire",
            Self::Fill => "fill",
            Self::Depth => "depth",
            Self::Normals => "normals",
            Self::Barycentric => "barycentric",
            Self::Overdraw => "overdraw",
        }
    }

    /// Whether the mode draws triangles through the rasterizer being shown (points and lines
    /// are drawn by refrast's own line rasterizer: the `Rasterizer` trait draws triangles only).
    #[must_use]
    pub fn uses_triangles(self) -> bool {
        !matches!(self, Self::Points | Self::Wire)
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_name(s, &Self::ALL, Self::name, "mode")
    }
}

/// The one of `all` whose `name` is `s`, or a message listing the names: how `--mode`,
/// `--shading` and `--sampling` read their values.
pub(crate) fn parse_name<T: Copy>(
    s: &str,
    all: &[T],
    name: fn(T) -> &'static str,
    kind: &str,
) -> Result<T, String> {
    all.iter().copied().find(|&t| name(t) == s).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|&t| name(t)).collect();
        format!("no {kind} named '{s}'; the {kind}s are: {}", names.join(", "))
    })
}

/// The overdraw palette: 1 fragment dark blue-grey, 2 orange, 3 red, 4 or more white, so that
/// one pixel covered twice along a shared edge stands out from a surface covered once.
#[must_use]
pub fn overdraw_color(count: u32) -> Option<[u8; 4]> {
    match count {
        0 => None,
        1 => Some([52, 72, 110, 255]),
        2 => Some([255, 150, 30, 255]),
        3 => Some([230, 40, 40, 255]),
        _ => Some([255, 255, 255, 255]),
    }
}

/// The colour of a normal: each component from `[−1, 1]` to `[0, 1]`; a zero normal is grey.
#[must_use]
pub fn normal_color(normal: Vec3) -> Vec4 {
    let n = normal.try_normalize().unwrap_or(Vec3::ZERO);
    (n * 0.5 + 0.5).extend(1.0)
}

/// A grey level for each depth in `depths` that is not the clear value: the nearest written
/// depth white, the farthest dark grey, linear in window depth between them.
///
/// Window depth under perspective crowds towards 1; stretching the written range shows the
/// ordering whatever the near and far planes are.
#[must_use]
pub fn depth_greys(depths: &[f32], clear: f32) -> Vec<Option<u8>> {
    let written = || depths.iter().copied().filter(|&d| d != clear && d.is_finite());
    let (lo, hi) = written().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), d| {
        (lo.min(d), hi.max(d))
    });
    let span = hi - lo;
    depths
        .iter()
        .map(|&d| {
            (d != clear && d.is_finite()).then(|| {
                let t = if span > 0.0 { (d - lo) / span } else { 0.0 };
                (255.0 - t * 200.0).round() as u8
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mode_names_round_trip() {
        for m in Mode::ALL {
            assert_eq!(m.name().parse::<Mode>(), Ok(m));
        }
        let err = "lines".parse::<Mode>().unwrap_err();
        assert!(
            err.contains("points, wire, fill, depth, normals, barycentric, overdraw"),
            "{err}"
        );
        assert!(!Mode::Wire.uses_triangles() && Mode::Overdraw.uses_triangles());
    }

    #[test]
    fn overdraw_palette_separates_one_from_two() {
        assert_eq!(overdraw_color(0), None);
        let colours: Vec<_> = (1..=5).map(overdraw_color).collect();
        assert_ne!(colours[0], colours[1]);
        assert_ne!(colours[1], colours[2]);
        assert_eq!(colours[3], colours[4]);
    }

    #[test]
    fn depth_greys_stretch_the_written_range() {
        let greys = depth_greys(&[1.0, 0.5, 0.75, 0.6, f32::NAN], 1.0);
        assert_eq!(greys, vec![None, Some(255), Some(55), Some(175), None]);
        assert_eq!(depth_greys(&[0.3, 1.0], 1.0), vec![Some(255), None]);
    }

    #[test]
    fn normals_map_to_colours() {
        assert_eq!(normal_color(Vec3::X), Vec4::new(1.0, 0.5, 0.5, 1.0));
        assert_eq!(normal_color(Vec3::ZERO), Vec4::new(0.5, 0.5, 0.5, 1.0));
    }
}
