//! The contract's data: one draw of any topology at any sample count, the fragments it covers,
//! the buffers after the depth test.
//!
//! A triangle rasterizer at one sample needs none of the rest: [`Draw::new`] builds a triangle
//! list at one sample, [`Draw::triangles`] reads it back as triangles, a [`Fragment`] built with
//! `sample: 0` (or `..Fragment::default()`) is at the pixel's one sample, and the suite sends
//! other topologies and sample counts only to a profile that declares them
//! ([`Profile::draws`](crate::Profile::draws)).

use std::borrow::Cow;

use crate::distance::Distances;
use crate::error::DrawError;
use crate::primitive::{SAMPLE_COUNTS, Topology};
use crate::state::DrawState;
use crate::state::PolygonMode;
use crate::viewport::Viewport;

/// One draw call: clip-space vertices, indices making primitives of one topology, the samples
/// per pixel, and state.
///
/// Primitive `i` (triangle, segment or point, in index order; segment `i` of a strip joins
/// indices `i` and `i + 1`; triangle `i` of a strip or fan is [`Draw::triangle`]`(i)`) is
/// [`Fragment::primitive`] `i` in every output.
#[derive(Clone, Debug, PartialEq)]
pub struct Draw {
    /// The render target's size.
    pub viewport: Viewport,
    /// Clip-space positions `[x, y, z, w]`.
    pub positions: Vec<[f32; 4]>,
    /// How the indices make primitives.
    pub topology: Topology,
    /// Vertex indices: three per triangle of a list ([`Draw::triangles`] reads them, and a
    /// strip's or fan's, as triangles).
    pub indices: Vec<u32>,
    /// Samples per pixel (1, 2, 4, 8 or 16).
    pub samples: u8,
    /// Culling (triangles only), depth and clipping state.
    pub state: DrawState,
    /// Each vertex's user clip and cull distances; none by default. Sent only to a rasterizer
    /// that declares them ([`StateSupport::clip_distances`](crate::StateSupport::clip_distances),
    /// [`StateSupport::cull_distances`](crate::StateSupport::cull_distances)).
    pub distances: Distances,
}

impl Draw {
    /// A triangle list at one sample with default state (no culling, CCW front, LESS depth, far
    /// clipping off).
    #[must_use]
    pub fn new(viewport: Viewport, positions: Vec<[f32; 4]>, triangles: Vec<[u32; 3]>) -> Self {
        Self::of(
            viewport,
            positions,
            Topology::TriangleList,
            triangles.into_flattened(),
        )
    }

    /// A draw of `topology` at one sample with default state.
    #[must_use]
    pub fn of(viewport: Viewport, positions: Vec<[f32; 4]>, topology: Topology, indices: Vec<u32>) -> Self {
        Self {
            viewport,
            positions,
            topology,
            indices,
            samples: 1,
            state: DrawState::default(),
            distances: Distances::default(),
        }
    }

    /// The same draw at `samples` samples per pixel.
    #[must_use]
    pub fn at_samples(self, samples: u8) -> Self {
        Self { samples, ..self }
    }

    /// Triangle `i`'s vertex indices, in the order Vulkan gives them (Triangle Lists, Strips
    /// and Fans): a list's `3i, 3i + 1, 3i + 2`; a strip's `i, i + 1 + i % 2, i + 2 − i % 2`,
    /// every other triangle reversed so that the winding is the strip's; a fan's
    /// `i + 1, i + 2, 0`. [`Fragment::barycentric`]`[k]` is the weight of its vertex `k`.
    /// `None` past the last triangle, and for lines and points.
    #[must_use]
    pub fn triangle(&self, i: usize) -> Option<[u32; 3]> {
        let at = |k: usize| self.indices.get(k).copied();
        let odd = i % 2;
        let corners = match self.topology {
            Topology::TriangleList => [3 * i, 3 * i + 1, 3 * i + 2],
            Topology::TriangleStrip => [i, i + 1 + odd, i + 2 - odd],
            Topology::TriangleFan => [i + 1, i + 2, 0],
            Topology::LineList | Topology::LineStrip | Topology::PointList => return None,
        };
        Some([at(corners[0])?, at(corners[1])?, at(corners[2])?])
    }

    /// Every triangle ([`Draw::triangle`]): a list's indices as they are, a strip's or fan's
    /// gathered; empty for lines and points, whose primitives [`Draw::primitive`] gives.
    #[must_use]
    pub fn triangles(&self) -> Cow<'_, [[u32; 3]]> {
        match self.topology {
            Topology::TriangleList => Cow::Borrowed(self.indices.as_chunks::<3>().0),
            _ => Cow::Owned(
                (0..self.primitive_count())
                    .map_while(|i| self.triangle(i))
                    .collect(),
            ),
        }
    }

    /// The triangles of a triangle list, to change in place (reversing one, say); empty for
    /// every other topology, whose triangles share indices.
    pub fn triangles_mut(&mut self) -> &mut [[u32; 3]] {
        match self.topology {
            Topology::TriangleList => self.indices.as_chunks_mut::<3>().0,
            _ => &mut [],
        }
    }

    /// The same triangles as a triangle list, in the same order and each in
    /// [`Draw::triangle`]'s vertex order: what a strip or fan draws, drawn the first
    /// contract's way. Lines and points are returned as they are.
    #[must_use]
    pub fn as_triangle_list(&self) -> Self {
        if !self.topology.is_triangles() {
            return self.clone();
        }
        Self {
            topology: Topology::TriangleList,
            indices: self.triangles().iter().flatten().copied().collect(),
            ..self.clone()
        }
    }

    /// Whether it is filled triangles (a list, a strip or a fan) at one sample, not
    /// conservative: what a triangle rasterizer reading [`Draw::triangles`] draws.
    #[must_use]
    pub fn is_triangles_at_one_sample(&self) -> bool {
        self.topology.is_triangles()
            && self.samples == 1
            && self.state.polygon_mode == PolygonMode::Fill
            && self.state.conservative.is_none()
    }

    /// The vertex indices of primitive `i` (one, two or three of them; a triangle's in
    /// [`Draw::triangle`]'s order); `None` past the last.
    #[must_use]
    pub fn primitive(&self, i: usize) -> Option<Cow<'_, [u32]>> {
        let slice = match self.topology {
            Topology::TriangleList => self.indices.get(3 * i..3 * i + 3),
            Topology::LineList => self.indices.get(2 * i..2 * i + 2),
            Topology::LineStrip => self.indices.get(i..i + 2),
            Topology::PointList => self.indices.get(i..=i),
            Topology::TriangleStrip | Topology::TriangleFan => {
                return self.triangle(i).map(|t| Cow::Owned(t.to_vec()));
            }
        };
        slice.map(Cow::Borrowed)
    }

    /// The provoking vertex of primitive `i` under the draw's mode (Vulkan's
    /// `VkProvokingVertexModeEXT`, as its topology sections give it): first, a list's `3i`, a
    /// strip's `i`, a fan's `i + 1`, a line list's `2i`, a line strip's `i`; last, `3i + 2`,
    /// `i + 2`, `i + 2`, `2i + 1`, `i + 1`; a point's either way. As a vertex index (into
    /// `positions`); `None` past the last primitive.
    #[must_use]
    pub fn provoking(&self, i: usize) -> Option<u32> {
        use crate::state::ProvokingVertex::{First, Last};
        let k = match (self.topology, self.state.provoking_vertex) {
            (Topology::TriangleList, First) => 3 * i,
            (Topology::TriangleList, Last) => 3 * i + 2,
            (Topology::TriangleStrip, First) | (Topology::LineStrip, First) | (Topology::PointList, _) => i,
            (Topology::TriangleFan, First) | (Topology::LineStrip, Last) => i + 1,
            (Topology::TriangleStrip | Topology::TriangleFan, Last) => i + 2,
            (Topology::LineList, First) => 2 * i,
            (Topology::LineList, Last) => 2 * i + 1,
        };
        (i < self.primitive_count())
            .then(|| self.indices.get(k).copied())
            .flatten()
    }

    /// How many primitives it draws (0 when [`validate`](Self::validate) refuses its count).
    #[must_use]
    pub fn primitive_count(&self) -> usize {
        self.topology.primitive_count(self.indices.len()).unwrap_or(0)
    }

    /// Checks the sample count, the index count, the viewport depth range and every index, so
    /// that rasterizers can index `positions` freely afterwards.
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
        self.state
            .viewport_depth
            .validate()
            .map_err(DrawError::Unsupported)?;
        if let Some(bias) = self.state.depth_bias {
            bias.validate().map_err(DrawError::Unsupported)?;
        }
        let vertices = self.positions.len();
        self.distances
            .validate(vertices)
            .map_err(DrawError::Unsupported)?;
        // Every primitive's vertices are entries of `indices`: when none is out of range, no
        // primitive has one, and the search for the first that does (which names it), four
        // times the instructions on a list of a million triangles, is skipped.
        if self
            .indices
            .iter()
            .copied()
            .max()
            .is_none_or(|v| (v as usize) < vertices)
        {
            return Ok(());
        }
        for i in 0..self.primitive_count() {
            let out_of_range = |p: &[u32]| p.iter().copied().find(|&v| v as usize >= vertices);
            let found = match self.triangle(i) {
                Some(t) => out_of_range(&t),
                None => self.primitive(i).and_then(|p| out_of_range(&p)),
            };
            if let Some(index) = found {
                return Err(DrawError::IndexOutOfRange {
                    triangle: i,
                    index,
                    vertices,
                });
            }
        }
        Ok(())
    }

    /// What it asks for in a few words: "line-strip at 4 samples per pixel".
    #[must_use]
    pub fn describe(&self) -> String {
        let samples = if self.samples == 1 {
            "1 sample".to_owned()
        } else {
            format!("{} samples", self.samples)
        };
        let mode = if self.topology.is_triangles() && self.state.polygon_mode != PolygonMode::Fill {
            format!(" in {} mode", self.state.polygon_mode.name())
        } else {
            String::new()
        };
        let distances = match (self.distances.clip, self.distances.cull) {
            (0, 0) => String::new(),
            (clip, 0) => format!(" with {clip} clip distances"),
            (0, cull) => format!(" with {cull} cull distances"),
            (clip, cull) => format!(" with {clip} clip and {cull} cull distances"),
        };
        format!("{}{mode}{distances} at {samples} per pixel", self.topology)
    }
}

/// A covered sample before the depth test.
///
/// A line's fragment has barycentrics `[1 − t, t, 0]` along its segment (perspective-correct
/// and in screen space), a point's `[1, 0, 0]`; both face front (Vulkan: lines and points are
/// always front-facing). A triangle's in line or point mode carries the triangle's facing and
/// its weights over the triangle's three corners (the two ends of its edge, or its vertex).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Fragment {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Which sample of the pixel it covers: its index in the draw's
    /// [`SamplePattern`](crate::SamplePattern); always 0 at one sample per pixel.
    pub sample: u8,
    /// The primitive's index in the draw ([`Draw::primitive`]).
    pub primitive: u32,
    /// Window depth in `[0, 1]`, linear in screen space. At several samples, the primitive's
    /// depth at this sample's position under refrast's conventions and D3D11.3
    /// (`msaa.depth.per-sample` checks it); Vulkan and OpenGL tie the depth a shader reads
    /// (`FragCoord.z`) to no sample, so a GPU's may be the pixel centre's, judged beyond those
    /// specifications. Whatever it reports, the depth test uses each sample's own depth:
    /// [`Rasterizer::resolve`](crate::Rasterizer::resolve) is judged against a replay at each
    /// sample's depth (`msaa.resolve.per-sample`).
    pub depth: f32,
    /// Perspective-correct barycentrics of the sample in the input primitive.
    pub barycentric: [f32; 3],
    /// The draw's vertex (an index into its positions) whose flat values the fragment carries:
    /// its primitive's provoking vertex under the draw's
    /// [`ProvokingVertex`](crate::ProvokingVertex) ([`Draw::provoking`]), also when clipping
    /// cut that vertex away. `None` from an implementation that reports no flat values
    /// ([`StateSupport::flat`](crate::StateSupport::flat) empty).
    pub flat: Option<u32>,
    /// Screen-space (affine) barycentrics, where the implementation can give them. A profile
    /// declaring them gives them for every triangle in front of the eye; for one with a vertex
    /// at `w ≤ 0`, which has no shape on screen, `None` is an answer too, and values given are
    /// judged for finiteness only (the reference gives none there).
    pub screen_barycentric: Option<[f32; 3]>,
    /// Whether the primitive faces the viewer under the draw's [`FrontFace`](crate::FrontFace).
    pub front_facing: bool,
}

/// The depth and primitive-id buffers after the depth test, one value per sample: sample `s`
/// of pixel `(x, y)` at index `(y · width + x) · samples + s` ([`Resolved::index`]), so at one
/// sample per pixel they are row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolved {
    /// The target's size.
    pub viewport: Viewport,
    /// Samples per pixel.
    pub samples: u8,
    /// Depth per sample.
    pub depth: Vec<f32>,
    /// The primitive whose fragment last passed the depth test at each sample (written or
    /// not), if any.
    pub primitive: Vec<Option<u32>>,
}

impl Resolved {
    /// The index of sample `s` of pixel `(x, y)`.
    #[must_use]
    pub fn index(&self, x: u32, y: u32, s: u8) -> usize {
        self.viewport.index(x, y) * usize::from(self.samples) + usize::from(s)
    }

    /// Replays fragments through the draw's depth test, sample by sample, in primitive order
    /// (API order); fragments outside the target or past its samples are dropped.
    #[must_use]
    pub fn from_fragments(draw: &Draw, mut fragments: Vec<Fragment>) -> Self {
        let viewport = draw.viewport;
        let n = viewport.pixel_count() * usize::from(draw.samples);
        let mut resolved = Self {
            viewport,
            samples: draw.samples,
            depth: vec![draw.state.depth.clear; n],
            primitive: vec![None; n],
        };
        // Stable: fragments of one primitive keep their order.
        fragments.sort_by_key(|f| f.primitive);
        for f in fragments {
            if f.x >= viewport.width() || f.y >= viewport.height() || f.sample >= draw.samples {
                continue;
            }
            let i = resolved.index(f.x, f.y, f.sample);
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

    /// Strips share end points; lists refuse a count that leaves indices over.
    #[test]
    fn primitives_follow_the_topology() {
        let vp = Viewport::new(4, 4).expect("4×4");
        let strip = Draw::of(vp, vec![[0.0; 4]; 3], Topology::LineStrip, vec![0, 1, 2]);
        assert_eq!(strip.primitive_count(), 2);
        assert_eq!(strip.primitive(1).as_deref(), Some(&[1, 2][..]));
        assert!(strip.triangles().is_empty());
        assert!(strip.validate().is_ok());
        let list = Draw::of(vp, vec![[0.0; 4]; 3], Topology::LineList, vec![0, 1, 2]);
        assert!(matches!(list.validate(), Err(DrawError::Unsupported(m)) if m.contains("multiple of 2")));
        let bad = Draw::of(vp, vec![[0.0; 4]; 2], Topology::PointList, vec![0, 5]);
        assert!(matches!(
            bad.validate(),
            Err(DrawError::IndexOutOfRange {
                triangle: 1,
                index: 5,
                ..
            })
        ));
        let odd = Draw::of(vp, Vec::new(), Topology::PointList, Vec::new()).at_samples(3);
        assert!(odd.validate().is_err());
    }

    /// The easy path: triangles in, the same triangles read back, one sample.
    #[test]
    fn a_triangle_list_reads_back_as_triangles() {
        let vp = Viewport::new(4, 4).expect("4×4");
        let draw = Draw::new(vp, vec![[0.0; 4]; 4], vec![[0, 1, 2], [2, 1, 3]]);
        assert_eq!(draw.triangles()[..], [[0, 1, 2], [2, 1, 3]]);
        assert_eq!(draw.indices, [0, 1, 2, 2, 1, 3]);
        assert!(draw.is_triangles_at_one_sample());
        assert_eq!(draw.primitive(1).as_deref(), Some(&[2, 1, 3][..]));
        assert_eq!(draw.as_triangle_list(), draw);
        assert!(!draw.clone().at_samples(4).is_triangles_at_one_sample());
        assert_eq!(draw.describe(), "triangle-list at 1 sample per pixel");
    }

    /// Strips and fans make their triangles in Vulkan's vertex order (Triangle Strips: odd
    /// ones reversed; Triangle Fans: the hub last); fewer than three indices make none.
    #[test]
    fn strips_and_fans_make_vulkans_triangles() {
        let vp = Viewport::new(4, 4).expect("4×4");
        let strip = Draw::of(
            vp,
            vec![[0.0; 4]; 9],
            Topology::TriangleStrip,
            vec![4, 5, 6, 7, 8],
        );
        assert_eq!(strip.primitive_count(), 3);
        assert_eq!(strip.triangles()[..], [[4, 5, 6], [5, 7, 6], [6, 7, 8]]);
        assert_eq!(strip.triangle(3), None);
        assert_eq!(strip.primitive(1).as_deref(), Some(&[5, 7, 6][..]));
        let fan = Draw {
            topology: Topology::TriangleFan,
            ..strip.clone()
        };
        assert_eq!(fan.triangles()[..], [[5, 6, 4], [6, 7, 4], [7, 8, 4]]);
        let list = fan.as_triangle_list();
        assert_eq!(
            (list.topology, list.indices),
            (Topology::TriangleList, vec![5, 6, 4, 6, 7, 4, 7, 8, 4])
        );
        assert!(strip.is_triangles_at_one_sample() && strip.validate().is_ok());
        let short = Draw {
            indices: vec![0, 1],
            ..strip.clone()
        };
        assert_eq!((short.primitive_count(), short.triangles().len()), (0, 0));
        assert!(short.validate().is_ok());
        let bad = Draw {
            indices: vec![0, 1, 2, 9],
            ..strip
        };
        assert!(matches!(
            bad.validate(),
            Err(DrawError::IndexOutOfRange {
                triangle: 1,
                index: 9,
                ..
            })
        ));
    }

    /// Sample `s` of a pixel is its own depth-test slot; one sample is row-major.
    #[test]
    fn each_sample_is_tested_on_its_own() {
        let vp = Viewport::new(2, 2).expect("2×2");
        let draw = Draw::new(vp, Vec::new(), Vec::new()).at_samples(4);
        let at = |sample, primitive, depth| Fragment {
            x: 1,
            y: 0,
            sample,
            primitive,
            depth,
            ..Fragment::default()
        };
        let resolved = Resolved::from_fragments(
            &draw,
            vec![at(2, 0, 0.5), at(2, 1, 0.25), at(3, 1, 0.5), at(4, 0, 0.0)],
        );
        assert_eq!(resolved.index(1, 0, 2), 6);
        assert_eq!(resolved.primitive[4..8], [None, None, Some(1), Some(1)]);
        assert_eq!(resolved.depth[6], 0.25);
        assert_eq!(
            resolved.primitive.iter().flatten().count(),
            2,
            "sample 4 of 4 is dropped"
        );
    }
}
