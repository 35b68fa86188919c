//! Fuzz inputs: raw bytes decoded by `arbitrary` into the conformance suite's [`Scene`]s.
//!
//! Each input's `Debug` prints the scene it stands for as Rust, so a crash log pastes into a test.

use std::fmt;

use arbitrary::Arbitrary;
use refrast_conformance::Scene;
use refrast_conformance::strategy::{GRID, triangulate};

/// Viewport sides come from a byte: 1..=64.
fn side(b: u8) -> u32 {
    u32::from(b % 64) + 1
}

/// Any draw: raw f32 bit patterns (NaN, Inf, subnormals, huge, w = 0) and any indices.
#[derive(Arbitrary)]
pub struct RawDraw {
    width: u8,
    height: u8,
    vertices: Vec<[u32; 4]>,
    triangles: Vec<[u8; 3]>,
}

impl RawDraw {
    /// The scene: at most 16 vertices and 16 triangles, indices wrapped onto the vertices.
    #[must_use]
    pub fn scene(&self) -> Option<Scene> {
        let positions: Vec<[f32; 4]> = self
            .vertices
            .iter()
            .take(16)
            .map(|v| v.map(f32::from_bits))
            .collect();
        let n = positions.len() as u32;
        if n == 0 {
            return None;
        }
        let triangles = self
            .triangles
            .iter()
            .take(16)
            .map(|t| t.map(|i| u32::from(i) % n))
            .collect();
        Some(Scene::new(
            side(self.width),
            side(self.height),
            positions,
            triangles,
        ))
    }
}

/// Grid triangles: vertices on the 1/256-pixel grid anywhere within ±2048 px.
#[derive(Arbitrary)]
pub struct GridTriangles {
    side: u8,
    triangles: Vec<[(i16, i16); 3]>,
}

impl GridTriangles {
    /// The scene, at depth ½, up to 6 triangles; `None` without any.
    #[must_use]
    pub fn scene(&self) -> Option<Scene> {
        let s = 16 << (self.side % 3);
        // Each i16 step is 1/16 px: ±2048 px reach well past the viewport on every side.
        let tris: Vec<[(i64, i64); 3]> = self
            .triangles
            .iter()
            .take(6)
            .map(|t| t.map(|(x, y)| (i64::from(x) * GRID / 16, i64::from(y) * GRID / 16)))
            .collect();
        (!tris.is_empty()).then(|| Scene::from_subpixels(s, s, 8, &tris, 0.5))
    }
}

/// A point set on the grid of a square viewport, triangulated by spade with its corners.
#[derive(Arbitrary)]
pub struct Points {
    side: u8,
    points: Vec<(u16, u16)>,
    w: Vec<u8>,
}

impl Points {
    /// The spade mesh, w per vertex in [0.25, 4.2].
    #[must_use]
    pub fn scene(&self) -> Scene {
        let s = 16 << (self.side % 3);
        let max = i64::from(s) * GRID;
        let points: Vec<(i64, i64)> = self
            .points
            .iter()
            .take(32)
            .map(|&(x, y)| (i64::from(x) % (max + 1), i64::from(y) % (max + 1)))
            .collect();
        let ws: Vec<f32> = self
            .w
            .iter()
            .take(8)
            .map(|&b| 0.25 + f32::from(b) / 64.0)
            .collect();
        triangulate(s, s, &points, if ws.is_empty() { &[1.0] } else { &ws }, &[0.5])
    }
}

/// Triangles across the clip planes: coordinates up to ±30000·w, w of either sign, z across 0.
#[derive(Arbitrary)]
pub struct Crossing {
    side: u8,
    vertices: [(i16, i16, i8, i8); 3],
}

impl Crossing {
    /// The scene of one triangle.
    #[must_use]
    pub fn scene(&self) -> Scene {
        let s = 16 << (self.side % 3);
        let positions = self
            .vertices
            .iter()
            .map(|&(x, y, z, w)| {
                let w = if w == 0 { 0.01 } else { f32::from(w) / 32.0 };
                let (x, y) = (f32::from(x) / 32767.0 * 30000.0, f32::from(y) / 32767.0 * 30000.0);
                [x * w.abs(), y * w.abs(), f32::from(z) / 64.0 * w.abs(), w]
            })
            .collect();
        Scene::new(s, s, positions, vec![[0, 1, 2]])
    }
}

impl fmt::Debug for RawDraw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.scene())
    }
}

impl fmt::Debug for GridTriangles {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.scene())
    }
}

impl fmt::Debug for Points {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.scene())
    }
}

impl fmt::Debug for Crossing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.scene())
    }
}
