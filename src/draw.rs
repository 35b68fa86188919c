//! The contract's data: a draw of triangles, the fragments it covers, the buffers after the
//! depth test. Apart from the trait so that the other topologies' types
//! ([`crate::PrimitiveDraw`]) can build on them without a circle of modules.

use crate::error::DrawError;
use crate::state::DrawState;
use crate::viewport::Viewport;

/// One draw call: clip-space vertices, triangles indexing them, and state.
///
/// Triangle `i` of `triangles` is primitive `i` in every output.
#[derive(Clone, Debug, PartialEq)]
pub struct Draw {
    /// The render target's size.
    pub viewport: Viewport,
    /// Clip-space positions `[x, y, z, w]`.
    pub positions: Vec<[f32; 4]>,
    /// Vertex indices, three per triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Culling, depth and clipping state.
    pub state: DrawState,
}

impl Draw {
    /// A draw with default state (no culling, CCW front, LESS depth, far clipping off).
    #[must_use]
    pub fn new(viewport: Viewport, positions: Vec<[f32; 4]>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            viewport,
            positions,
            triangles,
            state: DrawState::default(),
        }
    }

    /// Checks every index, so rasterizers can index `positions` freely afterwards.
    pub fn validate(&self) -> Result<(), DrawError> {
        let vertices = self.positions.len();
        for (triangle, indices) in self.triangles.iter().enumerate() {
            if let Some(&index) = indices.iter().find(|&&i| i as usize >= vertices) {
                return Err(DrawError::IndexOutOfRange {
                    triangle,
                    index,
                    vertices,
                });
            }
        }
        Ok(())
    }
}

/// A covered sample before the depth test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Index of the triangle in [`Draw::triangles`].
    pub primitive: u32,
    /// Window depth in `[0, 1]`, linear in screen space.
    pub depth: f32,
    /// Perspective-correct barycentrics of the sample in the input triangle.
    pub barycentric: [f32; 3],
    /// Screen-space (affine) barycentrics, where the implementation can give them. A profile
    /// declaring them gives them for every triangle in front of the eye; for one with a vertex
    /// at `w ≤ 0`, which has no shape on screen, `None` is an answer too, and values given are
    /// judged for finiteness only (the reference gives none there).
    pub screen_barycentric: Option<[f32; 3]>,
    /// Whether the triangle faces the viewer under the draw's [`FrontFace`](crate::FrontFace).
    pub front_facing: bool,
}

/// The depth and primitive-id buffers after the depth test, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolved {
    /// The target's size.
    pub viewport: Viewport,
    /// Depth per pixel.
    pub depth: Vec<f32>,
    /// The primitive whose fragment last passed the depth test at each pixel (written or not), if any.
    pub primitive: Vec<Option<u32>>,
}

impl Resolved {
    /// Replays fragments through the draw's depth test in primitive order (API order).
    #[must_use]
    pub fn from_fragments(draw: &Draw, mut fragments: Vec<Fragment>) -> Self {
        let viewport = draw.viewport;
        let mut resolved = Self {
            viewport,
            depth: vec![draw.state.depth.clear; viewport.pixel_count()],
            primitive: vec![None; viewport.pixel_count()],
        };
        // Stable: fragments of one primitive keep their order.
        fragments.sort_by_key(|f| f.primitive);
        for f in fragments {
            if f.x >= viewport.width() || f.y >= viewport.height() {
                continue;
            }
            let i = viewport.index(f.x, f.y);
            if draw.state.depth.test_and_write(f.depth, &mut resolved.depth[i]) {
                resolved.primitive[i] = Some(f.primitive);
            }
        }
        resolved
    }
}
