//! Fuzz inputs: raw bytes decoded by `arbitrary` into [`Scene`]s, each printing as Rust.
//!
//! Every input maps bytes onto a bounded, valid-by-construction scene, so the fuzzer spends its
//! time on geometry rather than on rejected inputs. `Debug` prints the scene it stands for.

use std::fmt;

use arbitrary::Arbitrary;
use refrast::{
    CompareOp, CullMode, DepthBias, DepthRange, DepthState, DrawState, FrontFace, PolygonMode,
    ProvokingVertex, Scissor, ViewportDepth,
};

use crate::scene::{Scene, clip_of, rust_f32};
use crate::strategy::{self, GRID, triangulate};

/// Square viewport sides 16, 32 or 64 from a byte: small enough for exact oracles per sample.
fn square_side(b: u8) -> u32 {
    16 << (b % 3)
}

/// Any draw: raw f32 bit patterns (NaN, Inf, subnormals, huge, w = 0), any indices, any state.
#[derive(Arbitrary)]
pub struct RawDraw {
    /// The draw state's bits ([`draw_state`]).
    state: u16,
    width: u8,
    height: u8,
    vertices: Vec<[u32; 4]>,
    triangles: Vec<[u8; 3]>,
}

impl RawDraw {
    /// The scene: sides 1..=64, at most 16 vertices and 16 triangles, indices wrapped onto the
    /// vertices; `None` without vertices.
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
        let side = |b: u8| u32::from(b % 64) + 1;
        let mut scene = Scene::new(side(self.width), side(self.height), positions, triangles);
        scene.state = draw_state(self.state);
        Some(scene)
    }

    /// The draw state these bytes ask for (`draw_state`).
    #[must_use]
    pub fn state(&self) -> DrawState {
        draw_state(self.state)
    }
}

/// Every draw state from 16 bits: cull mode (both faces included), front face, compare op,
/// depth writes, depth range, far clipping, a clear value of 1, 0 or ½ (1 twice, once with the
/// last provoking vertex), and one of 16 scissor rectangles (empty ones, thin ones, and ones
/// past a 64-px viewport's right and bottom sides) or, without one, a viewport depth range of
/// four (whole, inside, inverted, a single depth) and one time in four depth clipping off, one
/// in four a depth bias of four (each sign of each factor, clamped above, below or not).
#[must_use]
pub fn draw_state(bits: u16) -> DrawState {
    const OPS: [CompareOp; 8] = [
        CompareOp::Less,
        CompareOp::Never,
        CompareOp::Equal,
        CompareOp::LessOrEqual,
        CompareOp::Greater,
        CompareOp::NotEqual,
        CompareOp::GreaterOrEqual,
        CompareOp::Always,
    ];
    let field = |shift: u16, n: u16| usize::from((bits >> shift) % n);
    let scissored = field(11, 2) == 1;
    // Without a scissor its bits choose the depth range and whether depth is clipped.
    let viewport_depth = [(0.0, 1.0), (0.25, 0.75), (1.0, 0.0), (0.5, 0.5)][field(12, 4)];
    DrawState {
        cull: [
            CullMode::None,
            CullMode::Back,
            CullMode::Front,
            CullMode::FrontAndBack,
        ][field(0, 4)],
        front_face: [FrontFace::CounterClockwise, FrontFace::Clockwise][field(2, 2)],
        depth: DepthState {
            compare: OPS[field(3, 8)],
            write: field(6, 2) == 0,
            clear: [1.0, 0.0, 0.5][field(7, 4) % 3],
        },
        depth_range: [DepthRange::ZeroToOne, DepthRange::NegativeOneToOne][field(9, 2)],
        clip_far: field(10, 2) == 1,
        clip_near: scissored || field(14, 4) != 3,
        depth_bias: (!scissored && field(14, 4) == 2).then(|| {
            let [constant, slope, clamp] = [
                [4096.0, 1.5, 0.0],
                [-4096.0, -2.0, 0.0],
                [100_000.0, 4.0, 0.01],
                [-64.0, 0.5, -0.001],
            ][field(12, 4)];
            DepthBias {
                constant,
                slope,
                clamp,
            }
        }),
        viewport_depth: if scissored {
            ViewportDepth::FULL
        } else {
            ViewportDepth {
                min: viewport_depth.0,
                max: viewport_depth.1,
            }
        },
        scissor: scissored.then(|| {
            let (a, b) = (field(12, 4), field(14, 4));
            Scissor {
                x: 3 * a as u32,
                y: 5 * b as u32,
                width: [70, 0, 30, 1][a],
                height: [1, 70, 0, 33][b],
            }
        }),
        // Every sample: the sample mask's rules compare a draw with itself unmasked, where the
        // fuzz targets' bytes would find nothing a generated mask does not.
        sample_mask: DrawState::ALL_SAMPLES,
        // At the sample: the fuzz targets draw one sample, where centroid is the same.
        interpolation: refrast::Interpolation::Sample,
        // Point-sampled: the fuzz targets judge the fill rule's coverage.
        conservative: None,
        // The clear's fourth value is its first again (1), with the last provoking vertex.
        provoking_vertex: if field(7, 4) == 3 {
            ProvokingVertex::Last
        } else {
            ProvokingVertex::First
        },
        // The robustness target draws each scene in the other modes too.
        polygon_mode: PolygonMode::Fill,
    }
}

/// A [`RawDraw`] through the reference's whole pipeline: a model-view-projection matrix of any
/// bit patterns (identity when absent), the triangles as a mesh, their edges as lines, the
/// vertices as points.
#[derive(Arbitrary)]
pub struct RawPipeline {
    /// The draw: positions' x, y, z are model space, their fourth component the vertex grey.
    pub draw: RawDraw,
    /// Column-major matrix bits.
    pub matrix: Option<[u32; 16]>,
}

impl RawPipeline {
    /// The matrix as floats, column-major.
    #[must_use]
    pub fn matrix(&self) -> [f32; 16] {
        match self.matrix {
            Some(bits) => bits.map(f32::from_bits),
            None => std::array::from_fn(|i| if i % 5 == 0 { 1.0 } else { 0.0 }),
        }
    }
}

/// Grid triangles: vertices on the 1/256-pixel grid anywhere within ±2048 px.
#[derive(Arbitrary)]
pub struct GridTriangles {
    side: u8,
    triangles: Vec<[(i32, i32); 3]>,
}

/// ±2048 px in 1/256 px: well past the viewport on every side, inside the guard band.
const REACH: i64 = 2048 * GRID;

impl GridTriangles {
    /// The scene at depth ½, up to 6 triangles; `None` without any.
    ///
    /// Every bit of a coordinate's 1/256 px counts (wrapped into ±2048 px, not divided), so an
    /// implementation that drops a subpixel bit differs from the oracle.
    #[must_use]
    pub fn scene(&self) -> Option<Scene> {
        self.scene_at(8)
    }

    /// [`scene`](Self::scene) with coordinates in 1/512 px, for a profile that declares
    /// `ties_to_even`: an odd coordinate lies exactly halfway between two 8-bit grid points.
    #[must_use]
    pub fn scene_with_ties(&self) -> Option<Scene> {
        self.scene_at(strategy::FINE_BITS)
    }

    fn scene_at(&self, bits: u8) -> Option<Scene> {
        let s = square_side(self.side);
        let reach = REACH << (bits - 8);
        let wrap = |c: i32| (i64::from(c) + reach).rem_euclid(2 * reach + 1) - reach;
        let tris: Vec<[(i64, i64); 3]> = self
            .triangles
            .iter()
            .take(6)
            .map(|t| t.map(|(x, y)| (wrap(x), wrap(y))))
            .collect();
        (!tris.is_empty()).then(|| Scene::from_subpixels(s, s, bits, &tris, 0.5))
    }
}

/// Grid triangles with a depth per vertex from bytes, so that they overlap and intersect.
#[derive(Arbitrary)]
pub struct Overlapping {
    triangles: GridTriangles,
    depths: [u8; 18],
}

impl Overlapping {
    /// The scene, depths in [0, 1] in steps of 1/255; `None` without triangles.
    #[must_use]
    pub fn scene(&self) -> Option<Scene> {
        let mut scene = self.triangles.scene()?;
        for (p, z) in scene.positions.iter_mut().zip(self.depths.iter().cycle()) {
            p[2] = f32::from(*z) / 255.0;
        }
        Some(scene)
    }
}

/// One triangle inside the top-left 16 × 16 pixels with its own w and depth per vertex.
#[derive(Arbitrary)]
pub struct Perspective {
    side: u8,
    /// x and y in 1/256 px (wrapped into 0..=16 px), w and z from bytes.
    vertices: [(u16, u16, u8, u8); 3],
}

impl Perspective {
    /// Whether every vertex has the same w (then perspective and screen weights agree).
    #[must_use]
    pub fn equal_w(&self) -> bool {
        let [a, b, c] = self.vertices.map(|v| v.2);
        a == b && b == c
    }

    /// The scene: w in [0.1, 4] and z/w in [−0.25, 1] per vertex, so that a sixth of the
    /// vertices lie before the near plane and the triangle is clipped there.
    #[must_use]
    pub fn scene(&self) -> Scene {
        let s = square_side(self.side);
        let inside = |c: u16| i64::from(c) % (16 * GRID + 1);
        let positions = self
            .vertices
            .iter()
            .map(|&(x, y, w, z)| {
                let w = 0.1 + f32::from(w) / 255.0 * 3.9;
                clip_of(
                    s,
                    s,
                    8,
                    inside(x),
                    inside(y),
                    f32::from(z) / 255.0 * 1.25 - 0.25,
                    w,
                )
            })
            .collect();
        Scene::new(s, s, positions, vec![[0, 1, 2]])
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
    /// The spade mesh covering the viewport, w per vertex in [0.25, 4.2], depth ½.
    #[must_use]
    pub fn scene(&self) -> Scene {
        self.mesh(&[0.5])
    }

    /// The spade mesh with depths `zs` cycled over its vertices.
    fn mesh(&self, zs: &[f32]) -> Scene {
        let s = square_side(self.side);
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
        triangulate(s, s, &points, if ws.is_empty() { &[1.0] } else { &ws }, zs)
    }
}

/// A triangle or a mesh across the clip planes.
#[derive(Arbitrary)]
pub enum Clipping {
    /// One triangle: coordinates up to ±30000·w, w of either sign, z across 0.
    Triangle {
        /// Viewport side selector.
        side: u8,
        /// x, y in units of 30000/32767, z in units of 1/64, w in units of 1/32 (0 → 0.01).
        vertices: [(i16, i16, i8, i8); 3],
    },
    /// A spade mesh whose vertex depths straddle the near plane, so shared edges get clipped.
    Mesh {
        /// The mesh.
        points: Points,
        /// Depths in [−1, 1] in steps of 1/64, cycled over the vertices.
        depths: Vec<i8>,
    },
}

impl Clipping {
    /// The scene.
    #[must_use]
    pub fn scene(&self) -> Scene {
        match self {
            Self::Triangle { side, vertices } => {
                let s = square_side(*side);
                let positions = vertices
                    .iter()
                    .map(|&(x, y, z, w)| {
                        let w = if w == 0 { 0.01 } else { f32::from(w) / 32.0 };
                        let (x, y) = (f32::from(x) / 32767.0 * 30000.0, f32::from(y) / 32767.0 * 30000.0);
                        [x * w.abs(), y * w.abs(), f32::from(z) / 64.0 * w.abs(), w]
                    })
                    .collect();
                Scene::new(s, s, positions, vec![[0, 1, 2]])
            }
            Self::Mesh { points, depths } => {
                let zs: Vec<f32> = depths
                    .iter()
                    .take(8)
                    .map(|&z| (f32::from(z) / 64.0).clamp(-1.0, 1.0))
                    .collect();
                points.mesh(if zs.is_empty() { &[-0.5, 0.5] } else { &zs })
            }
        }
    }
}

/// Prints `scene` or, when there is none, says so.
fn write_scene(f: &mut fmt::Formatter<'_>, scene: Option<Scene>) -> fmt::Result {
    match scene {
        Some(s) => write!(f, "{s:?}"),
        None => write!(f, "/* no scene: the input decodes to nothing to draw */"),
    }
}

impl fmt::Debug for RawDraw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_scene(f, self.scene())
    }
}

impl fmt::Debug for RawPipeline {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m: Vec<String> = self.matrix().iter().map(|&v| rust_f32(v)).collect();
        writeln!(f, "// model-view-projection, column-major:")?;
        writeln!(f, "Mat4::from_cols_array(&[{}]),", m.join(", "))?;
        write_scene(f, self.draw.scene())
    }
}

impl fmt::Debug for GridTriangles {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_scene(f, self.scene())
    }
}

impl fmt::Debug for Overlapping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_scene(f, self.scene())
    }
}

impl fmt::Debug for Perspective {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_scene(f, Some(self.scene()))
    }
}

impl fmt::Debug for Points {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_scene(f, Some(self.scene()))
    }
}

impl fmt::Debug for Clipping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_scene(f, Some(self.scene()))
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::draw_state;

    #[test]
    fn sixteen_bits_reach_every_draw_state() {
        let states: HashSet<String> = (0..=u16::MAX).map(|b| format!("{:?}", draw_state(b))).collect();
        // 4 cull modes × 2 front faces × 8 compare ops × 2 write masks × 4 (3 clears with the
        // first provoking vertex, one with the last) × 2 ranges × 2 far-clipping settings × 28
        // (16 scissor rectangles; without one, 4 viewport depth ranges × near clipping on, off,
        // or on with one of 4 depth biases, each range with its own).
        assert_eq!(states.len(), 4 * 2 * 8 * 2 * 4 * 2 * 2 * 28);
    }
}
