//! Lines, points and multisampling in the contract: what a draw of another topology or sample
//! count says, what an implementation declares about them, and what it returns.
//!
//! Kept apart from [`Draw`], [`Fragment`] and [`Profile`](crate::Profile) so that code building
//! those by literal compiles unchanged: an implementation that declares nothing here is a
//! triangle rasterizer at one sample, as before ([`Rasterizer::primitive_profile`]).

use std::fmt;

use crate::draw::{Draw, Fragment};
use crate::error::DrawError;
use crate::profile::Snapping;
use crate::state::DrawState;
use crate::viewport::Viewport;

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
}

impl Topology {
    /// Every topology, triangles first.
    pub const ALL: [Topology; 4] = [
        Self::TriangleList,
        Self::LineList,
        Self::LineStrip,
        Self::PointList,
    ];

    /// The name the pipe protocol and reports use: `triangle-list`, `line-strip`, ….
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::TriangleList => "triangle-list",
            Self::LineList => "line-list",
            Self::LineStrip => "line-strip",
            Self::PointList => "point-list",
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

    /// The number of primitives `indices` indices make; `Err` with what is wrong when a list's
    /// count is not a multiple of its primitive's vertices.
    pub fn primitive_count(self, indices: usize) -> Result<usize, String> {
        let per = match self {
            Self::TriangleList => 3,
            Self::LineList => 2,
            Self::LineStrip => return Ok(indices.saturating_sub(1)),
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

/// What an implementation declares about lines, points and multisampling.
///
/// The default is a triangle rasterizer at one sample per pixel, at the pixel's centre; the
/// rules of the `line.`, `point.` and `msaa.` families are then not applicable.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct PrimitiveProfile {
    /// How it draws lines of width one, if it draws lines (list and strip).
    pub lines: Option<LineRule>,
    /// Whether it draws points of size one: a square one pixel wide centred on the point,
    /// covered as a polygon.
    pub points: bool,
    /// Where line and point end points are snapped; `None` for the grid of triangles
    /// ([`Profile::snapping`](crate::Profile::snapping)).
    pub endpoint_snapping: Option<Snapping>,
    /// Where points alone are snapped, when on another grid than line ends (softpipe snaps
    /// points to a quarter pixel, its lines and triangles to none); `None` for
    /// [`endpoint_snapping`](Self::endpoint_snapping)'s.
    pub point_snapping: Option<Snapping>,
    /// The sample counts above one it supports, each with its positions.
    pub multisample: Vec<SamplePattern>,
    /// What clipping does to a point whose centre lies outside the viewport in x or y.
    pub point_clipping: PointClipping,
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

impl PrimitiveProfile {
    /// Triangles at one sample: what an implementation that declares nothing supports.
    #[must_use]
    pub fn triangles_only() -> Self {
        Self::default()
    }

    /// The pattern of `samples` samples per pixel: the centre for one, else the declared one.
    #[must_use]
    pub fn pattern(&self, samples: u8) -> Option<SamplePattern> {
        if samples == 1 {
            return SamplePattern::standard(1);
        }
        self.multisample.iter().find(|p| p.count() == samples).copied()
    }

    /// Whether it supports drawing `topology` at `samples` samples per pixel.
    #[must_use]
    pub fn supports(&self, topology: Topology, samples: u8) -> bool {
        let drawn = match topology {
            Topology::TriangleList => true,
            Topology::LineList | Topology::LineStrip => self.lines.is_some(),
            Topology::PointList => self.points,
        };
        drawn && self.pattern(samples).is_some()
    }

    /// The topologies it draws, triangles first.
    #[must_use]
    pub fn topologies(&self) -> Vec<Topology> {
        Topology::ALL
            .into_iter()
            .filter(|&t| self.supports(t, 1))
            .collect()
    }

    /// The sample counts it supports, 1 first.
    #[must_use]
    pub fn sample_counts(&self) -> Vec<u8> {
        SAMPLE_COUNTS
            .into_iter()
            .filter(|&n| self.pattern(n).is_some())
            .collect()
    }
}

/// One draw call of any topology at any sample count: clip-space vertices, indices, state.
///
/// Primitive `i` (triangle, segment or point, in index order; segment `i` of a strip joins
/// indices `i` and `i + 1`) is [`Fragment::primitive`] `i` in every output.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveDraw {
    /// The render target's size.
    pub viewport: Viewport,
    /// Clip-space positions `[x, y, z, w]`.
    pub positions: Vec<[f32; 4]>,
    /// How the indices make primitives.
    pub topology: Topology,
    /// Vertex indices.
    pub indices: Vec<u32>,
    /// Samples per pixel (1, 2, 4, 8 or 16).
    pub samples: u8,
    /// Culling (triangles only), depth and clipping state.
    pub state: DrawState,
}

impl PrimitiveDraw {
    /// A draw of `topology` at one sample with default state.
    #[must_use]
    pub fn new(viewport: Viewport, positions: Vec<[f32; 4]>, topology: Topology, indices: Vec<u32>) -> Self {
        Self {
            viewport,
            positions,
            topology,
            indices,
            samples: 1,
            state: DrawState::default(),
        }
    }

    /// The same triangles as `draw`, at `samples` samples per pixel.
    #[must_use]
    pub fn of_triangles(draw: &Draw, samples: u8) -> Self {
        Self {
            viewport: draw.viewport,
            positions: draw.positions.clone(),
            topology: Topology::TriangleList,
            indices: draw.triangles.iter().flatten().copied().collect(),
            samples,
            state: draw.state,
        }
    }

    /// The triangle draw it is, when it is a triangle list at one sample.
    #[must_use]
    pub fn as_triangle_draw(&self) -> Option<Draw> {
        (self.topology == Topology::TriangleList && self.samples == 1 && self.indices.len().is_multiple_of(3))
            .then(|| Draw {
                viewport: self.viewport,
                positions: self.positions.clone(),
                triangles: self.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
                state: self.state,
            })
    }

    /// The vertex indices of primitive `i` (one, two or three of them); `None` past the last.
    #[must_use]
    pub fn primitive(&self, i: usize) -> Option<&[u32]> {
        match self.topology {
            Topology::TriangleList => self.indices.get(3 * i..3 * i + 3),
            Topology::LineList => self.indices.get(2 * i..2 * i + 2),
            Topology::LineStrip => self.indices.get(i..i + 2),
            Topology::PointList => self.indices.get(i..=i),
        }
    }

    /// How many primitives it draws (0 when [`validate`](Self::validate) refuses it).
    #[must_use]
    pub fn primitive_count(&self) -> usize {
        self.topology.primitive_count(self.indices.len()).unwrap_or(0)
    }

    /// Checks the sample count, the index count and every index, so that rasterizers can index
    /// `positions` freely afterwards.
    pub fn validate(&self) -> Result<(), DrawError> {
        if !SAMPLE_COUNTS.contains(&self.samples) {
            return Err(DrawError::Unsupported(format!(
                "{} samples per pixel: a draw asks for 1, 2, 4, 8 or 16",
                self.samples
            )));
        }
        self.topology
            .primitive_count(self.indices.len())
            .map_err(DrawError::Unsupported)?;
        let vertices = self.positions.len();
        for i in 0..self.primitive_count() {
            if let Some(&index) = self
                .primitive(i)
                .and_then(|p| p.iter().find(|&&v| v as usize >= vertices))
            {
                return Err(DrawError::IndexOutOfRange {
                    triangle: i,
                    index,
                    vertices,
                });
            }
        }
        Ok(())
    }

    /// What it asks for in a few words: "line-strip at 4 samples".
    #[must_use]
    pub fn describe(&self) -> String {
        let samples = if self.samples == 1 {
            "1 sample".to_owned()
        } else {
            format!("{} samples", self.samples)
        };
        format!("{} at {samples} per pixel", self.topology)
    }
}

/// A covered sample before the depth test: the fragment and which of its pixel's samples.
///
/// A line's fragment has barycentrics `[1 − t, t, 0]` along its segment (perspective-correct
/// and in screen space), a point's `[1, 0, 0]`; both face front (Vulkan: lines and points are
/// always front-facing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleFragment {
    /// The fragment. Its depth is the primitive's at this sample's position under refrast's
    /// conventions and D3D11.3 (`msaa.depth.per-sample` checks it); Vulkan and OpenGL tie the
    /// depth a shader reads (`FragCoord.z`) to no sample, so a GPU's may be the pixel centre's,
    /// judged beyond those specifications. Whatever it reports, the depth test uses each
    /// sample's own depth: [`Rasterizer::resolve_primitives`](crate::Rasterizer::resolve_primitives)
    /// is judged against a replay at each sample's depth (`msaa.resolve.per-sample`).
    pub fragment: Fragment,
    /// The sample's index in the pixel's [`SamplePattern`].
    pub sample: u8,
}

/// Depth and primitive-id buffers after the depth test, one value per sample: sample `s` of
/// pixel `(x, y)` at index `(y · width + x) · samples + s`.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleResolved {
    /// The target's size.
    pub viewport: Viewport,
    /// Samples per pixel.
    pub samples: u8,
    /// Depth per sample.
    pub depth: Vec<f32>,
    /// The primitive whose fragment last passed the depth test at each sample, if any.
    pub primitive: Vec<Option<u32>>,
}

impl SampleResolved {
    /// The index of sample `s` of pixel `(x, y)`.
    #[must_use]
    pub fn index(&self, x: u32, y: u32, s: u8) -> usize {
        self.viewport.index(x, y) * usize::from(self.samples) + usize::from(s)
    }

    /// Replays fragments through the draw's depth test, sample by sample, in primitive order.
    #[must_use]
    pub fn from_fragments(draw: &PrimitiveDraw, mut fragments: Vec<SampleFragment>) -> Self {
        let viewport = draw.viewport;
        let n = viewport.pixel_count() * usize::from(draw.samples);
        let mut resolved = Self {
            viewport,
            samples: draw.samples,
            depth: vec![draw.state.depth.clear; n],
            primitive: vec![None; n],
        };
        // Stable: fragments of one primitive keep their order.
        fragments.sort_by_key(|f| f.fragment.primitive);
        for SampleFragment { fragment: f, sample } in fragments {
            if f.x >= viewport.width() || f.y >= viewport.height() || sample >= draw.samples {
                continue;
            }
            let i = resolved.index(f.x, f.y, sample);
            if draw.state.depth.test_and_write(f.depth, &mut resolved.depth[i]) {
                resolved.primitive[i] = Some(f.primitive);
            }
        }
        resolved
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

    /// Strips share end points; lists refuse a count that leaves indices over.
    #[test]
    fn primitives_follow_the_topology() {
        let vp = Viewport::new(4, 4).expect("4×4");
        let strip = PrimitiveDraw::new(vp, vec![[0.0; 4]; 3], Topology::LineStrip, vec![0, 1, 2]);
        assert_eq!(strip.primitive_count(), 2);
        assert_eq!(strip.primitive(1), Some(&[1, 2][..]));
        assert!(strip.validate().is_ok());
        let list = PrimitiveDraw::new(vp, vec![[0.0; 4]; 3], Topology::LineList, vec![0, 1, 2]);
        assert!(matches!(list.validate(), Err(DrawError::Unsupported(m)) if m.contains("multiple of 2")));
        let bad = PrimitiveDraw::new(vp, vec![[0.0; 4]; 2], Topology::PointList, vec![0, 5]);
        assert!(matches!(
            bad.validate(),
            Err(DrawError::IndexOutOfRange {
                triangle: 1,
                index: 5,
                ..
            })
        ));
        let odd = PrimitiveDraw {
            samples: 3,
            ..PrimitiveDraw::new(vp, Vec::new(), Topology::PointList, Vec::new())
        };
        assert!(odd.validate().is_err());
        for t in Topology::ALL {
            assert_eq!(Topology::from_name(t.name()), Some(t));
        }
    }

    /// Nothing declared: triangles at one sample, nothing else.
    #[test]
    fn the_default_profile_is_triangles_at_one_sample() {
        let p = PrimitiveProfile::triangles_only();
        assert_eq!(p.topologies(), [Topology::TriangleList]);
        assert_eq!(p.sample_counts(), [1]);
        assert!(!p.supports(Topology::LineList, 1));
        assert!(!p.supports(Topology::TriangleList, 4));
        let more = PrimitiveProfile {
            lines: Some(LineRule::DiamondExit),
            multisample: vec![SamplePattern::standard(4).expect("4")],
            ..p
        };
        assert!(more.supports(Topology::LineStrip, 4));
        assert_eq!(more.sample_counts(), [1, 4]);
    }
}
