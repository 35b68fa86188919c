//! The words of lines, points and multisampling: a draw's [`Topology`], the [`LineRule`] and
//! [`PointClipping`] a profile declares, and where a pixel's samples lie ([`SamplePattern`]).

use std::fmt;

/// How a draw's indices make primitives (Vulkan's `VkPrimitiveTopology`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Topology {
    /// Three indices per triangle.
    #[default]
    TriangleList,
    /// Two indices per segment.
    LineList,
    /// Each index after the first ends a segment that starts at the one before.
    LineStrip,
    /// One index per point.
    PointList,
    /// Each index after the second ends a triangle with the two before it, every other one
    /// reversed so that the winding stays the strip's ([`Draw::triangle`](crate::Draw::triangle)).
    TriangleStrip,
    /// Each index after the second ends a triangle with the one before it and the first.
    TriangleFan,
}

impl Topology {
    /// Every topology: the first contract's triangle list, then lines and points, then the
    /// strips and fans that came with the later draw state.
    pub const ALL: [Topology; 6] = [
        Self::TriangleList,
        Self::LineList,
        Self::LineStrip,
        Self::PointList,
        Self::TriangleStrip,
        Self::TriangleFan,
    ];

    /// The name the pipe protocol and reports use: `triangle-list`, `line-strip`, ….
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::TriangleList => "triangle-list",
            Self::LineList => "line-list",
            Self::LineStrip => "line-strip",
            Self::PointList => "point-list",
            Self::TriangleStrip => "triangle-strip",
            Self::TriangleFan => "triangle-fan",
        }
    }

    /// The topology called `name` ([`Topology::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Whether its primitives are line segments.
    #[must_use]
    pub fn is_lines(self) -> bool {
        matches!(self, Self::LineList | Self::LineStrip)
    }

    /// Whether its primitives are triangles (a list, a strip or a fan).
    #[must_use]
    pub fn is_triangles(self) -> bool {
        matches!(self, Self::TriangleList | Self::TriangleStrip | Self::TriangleFan)
    }

    /// The number of primitives `indices` indices make; `Err` with what is wrong when a list's
    /// count is not a multiple of its primitive's vertices.
    pub fn primitive_count(self, indices: usize) -> Result<usize, String> {
        let per = match self {
            Self::TriangleList => 3,
            Self::LineList => 2,
            Self::LineStrip => return Ok(indices.saturating_sub(1)),
            Self::TriangleStrip | Self::TriangleFan => return Ok(indices.saturating_sub(2)),
            Self::PointList => 1,
        };
        if indices.is_multiple_of(per) {
            Ok(indices / per)
        } else {
            Err(format!(
                "a {} needs a multiple of {per} indices, got {indices}",
                self.name()
            ))
        }
    }
}

impl fmt::Display for Topology {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Which pixels a line segment of width one covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum LineRule {
    /// The diamond-exit rule: a pixel is drawn when the segment, its end points nudged by
    /// `−(ε, ε²)`, meets the pixel's diamond `|x − xc| + |y − yc| < ½` and does not end in it
    /// (Vulkan's `VK_LINE_RASTERIZATION_MODE_BRESENHAM`, OpenGL 4.6 §14.5.1, D3D11.3 §3.4.3
    /// aliased lines).
    #[default]
    DiamondExit,
    /// A rectangle one pixel wide centred on the segment, from end point to end point; its samples
    /// are covered as a polygon's (Vulkan with `strictLines`).
    Rectangle,
    /// A parallelogram whose two short sides, one pixel long, lie along the minor axis through
    /// the end points (x is the major axis on a tie); covered as a polygon (Vulkan without
    /// `strictLines`).
    Parallelogram,
}

impl LineRule {
    /// Every rule.
    pub const ALL: [LineRule; 3] = [Self::DiamondExit, Self::Rectangle, Self::Parallelogram];

    /// The name the pipe protocol and reports use.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::DiamondExit => "diamond-exit",
            Self::Rectangle => "rectangle",
            Self::Parallelogram => "parallelogram",
        }
    }

    /// The rule called `name` ([`LineRule::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|r| r.name() == name)
    }
}

/// The sample counts a draw may ask for (Vulkan's `VkSampleCountFlagBits` up to 16).
pub const SAMPLE_COUNTS: [u8; 5] = [1, 2, 4, 8, 16];

/// Where a pixel's samples lie, in sixteenths of a pixel from its top-left corner.
///
/// Sixteenths hold Vulkan's standard locations for 1 to 16 samples exactly, and
/// `sampleLocationSubPixelBits` is at least 4 for custom ones.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct SamplePattern {
    count: u8,
    positions: [[u8; 2]; 16],
}

/// Vulkan's standard sample locations (Multisampling, "Standard sample locations"), in 1/16 px.
const STANDARD: [&[[u8; 2]]; 5] = [
    &[[8, 8]],
    &[[12, 12], [4, 4]],
    &[[6, 2], [14, 6], [2, 10], [10, 14]],
    &[
        [9, 5],
        [7, 11],
        [13, 9],
        [5, 3],
        [3, 13],
        [1, 7],
        [11, 15],
        [15, 1],
    ],
    &[
        [9, 9],
        [7, 5],
        [5, 10],
        [12, 7],
        [3, 6],
        [10, 13],
        [13, 11],
        [11, 3],
        [6, 14],
        [8, 1],
        [4, 2],
        [2, 12],
        [0, 8],
        [15, 4],
        [14, 15],
        [1, 0],
    ],
];

impl SamplePattern {
    /// Vulkan's standard locations for `count` samples (1, 2, 4, 8 or 16).
    #[must_use]
    pub fn standard(count: u8) -> Option<Self> {
        let i = SAMPLE_COUNTS.iter().position(|&c| c == count)?;
        Self::new(STANDARD[i]).ok()
    }

    /// Samples at `positions`, in 1/16 px from the pixel's top-left corner; `Err` with what is
    /// wrong unless there are 1, 2, 4, 8 or 16 of them, each coordinate below 16.
    pub fn new(positions: &[[u8; 2]]) -> Result<Self, String> {
        let count = u8::try_from(positions.len()).unwrap_or(u8::MAX);
        if !SAMPLE_COUNTS.contains(&count) {
            return Err(format!(
                "{} sample positions given: a pattern has 1, 2, 4, 8 or 16",
                positions.len()
            ));
        }
        if let Some(p) = positions.iter().find(|p| p[0] > 15 || p[1] > 15) {
            return Err(format!(
                "sample position {p:?} lies outside the pixel: each coordinate is 0..=15 sixteenths"
            ));
        }
        let mut all = [[0; 2]; 16];
        all[..positions.len()].copy_from_slice(positions);
        Ok(Self {
            count,
            positions: all,
        })
    }

    /// How many samples a pixel has.
    #[must_use]
    pub fn count(&self) -> u8 {
        self.count
    }

    /// Each sample's position in 1/16 px from the pixel's top-left corner, by sample index.
    #[must_use]
    pub fn positions(&self) -> &[[u8; 2]] {
        &self.positions[..usize::from(self.count)]
    }

    /// Whether these are Vulkan's standard locations for their count.
    #[must_use]
    pub fn is_standard(&self) -> bool {
        Self::standard(self.count).as_ref() == Some(self)
    }
}

impl fmt::Debug for SamplePattern {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_standard() {
            write!(f, "SamplePattern::standard({})", self.count)
        } else {
            write!(f, "SamplePattern::new(&{:?})", self.positions())
        }
    }
}

/// What clipping does to a point whose centre lies outside the view volume in x or y
/// (Vulkan's `VkPointClippingBehavior`, which `vulkaninfo` reports as `pointClippingBehavior`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum PointClipping {
    /// Discarded, with its whole square (`VK_POINT_CLIPPING_BEHAVIOR_ALL_CLIP_PLANES`, refrast's).
    #[default]
    AllClipPlanes,
    /// Kept: only user clip planes discard a point, so the samples its square reaches inside
    /// the viewport are drawn, a point sliding off the edge leaving gradually ("pop-free",
    /// `VK_POINT_CLIPPING_BEHAVIOR_USER_CLIP_PLANES_ONLY`; OpenGL ES clips points by the near and
    /// far planes only).
    UserClipPlanesOnly,
}

impl PointClipping {
    /// Both behaviours, refrast's first.
    pub const ALL: [PointClipping; 2] = [Self::AllClipPlanes, Self::UserClipPlanesOnly];

    /// The name the pipe protocol and reports use: `all-clip-planes`, `user-clip-planes-only`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::AllClipPlanes => "all-clip-planes",
            Self::UserClipPlanesOnly => "user-clip-planes-only",
        }
    }

    /// The behaviour called `name` ([`PointClipping::name`]), or as `vulkaninfo` prints it
    /// (`POINT_CLIPPING_BEHAVIOR_ALL_CLIP_PLANES`, with or without `VK_`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        let vulkan = name
            .trim_start_matches("VK_")
            .trim_start_matches("POINT_CLIPPING_BEHAVIOR_");
        Self::ALL
            .into_iter()
            .find(|c| c.name() == name || c.name().replace('-', "_").eq_ignore_ascii_case(vulkan))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Vulkan's standard locations: the 4-sample pattern of its table, one sample per quadrant,
    /// and every pattern's positions distinct.
    #[test]
    fn standard_patterns_are_vulkans() {
        let four = SamplePattern::standard(4).expect("4 samples");
        assert_eq!(four.positions(), [[6, 2], [14, 6], [2, 10], [10, 14]]);
        for n in SAMPLE_COUNTS {
            let p = SamplePattern::standard(n).expect("a standard count");
            assert_eq!(usize::from(p.count()), p.positions().len());
            let mut seen = p.positions().to_vec();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), p.positions().len(), "{n} samples are distinct");
            assert!(p.is_standard());
        }
        assert!(SamplePattern::standard(3).is_none());
        assert!(SamplePattern::new(&[[1, 2], [3, 16]]).is_err());
        assert!(SamplePattern::new(&[[1, 2], [3, 4], [5, 6]]).is_err());
        let mirrored = SamplePattern::new(&[[10, 2], [2, 6], [14, 10], [6, 14]]).expect("valid");
        assert!(!mirrored.is_standard());
        assert_eq!(
            format!("{mirrored:?}"),
            "SamplePattern::new(&[[10, 2], [2, 6], [14, 10], [6, 14]])"
        );
    }

    /// Each topology reads back from its name.
    #[test]
    fn topologies_are_named_both_ways() {
        for t in Topology::ALL {
            assert_eq!(Topology::from_name(t.name()), Some(t));
        }
        assert_eq!(Topology::from_name("triangle-strips"), None);
    }
}
