//! The input of the line, point and multisampling rules: a scene drawn as another topology or
//! at several samples per pixel, printed as pasteable Rust.

use std::fmt;

use refrast::{Draw, Topology};

use super::{Case, CaseData, DrawData, Scene};

/// A scene drawn as `topology` at `samples` samples per pixel.
///
/// A triangle list's triangles come from the scene's `triangles`; strips, fans, lines and
/// points from `indices` (the scene's triangles are then empty), so the state, viewport and positions are the scene's, fitted and
/// printed as for every rule.
#[derive(Clone, PartialEq)]
pub struct PrimitiveScene {
    /// Viewport, positions, state and (for a triangle list) triangles.
    pub scene: Scene,
    /// How the primitives are made.
    pub topology: Topology,
    /// Vertex indices of strips, fans, lines and points (empty for a triangle list).
    pub indices: Vec<u32>,
    /// Samples per pixel.
    pub samples: u8,
}

impl PrimitiveScene {
    /// `scene`'s triangles at `samples` samples per pixel.
    #[must_use]
    pub fn triangles(scene: Scene, samples: u8) -> Self {
        Self {
            scene,
            topology: Topology::TriangleList,
            indices: Vec::new(),
            samples,
        }
    }

    /// Strips, fans, lines or points of `topology` over `positions`, at one sample per pixel.
    #[must_use]
    pub fn of(
        width: u32,
        height: u32,
        positions: Vec<[f32; 4]>,
        topology: Topology,
        indices: Vec<u32>,
    ) -> Self {
        Self {
            scene: Scene::new(width, height, positions, Vec::new()),
            topology,
            indices,
            samples: 1,
        }
    }

    /// The indices drawn: the triangles' for a triangle list.
    #[must_use]
    pub fn all_indices(&self) -> Vec<u32> {
        if self.topology == Topology::TriangleList {
            self.scene.triangles.iter().flatten().copied().collect()
        } else {
            self.indices.clone()
        }
    }

    /// The draw the rasterizer under test receives.
    ///
    /// # Panics
    /// When the viewport is out of range; strategies only build valid sizes.
    #[must_use]
    pub fn draw(&self) -> Draw {
        Draw {
            viewport: self.scene.viewport().expect("strategies build valid viewports"),
            positions: self.scene.positions.clone(),
            topology: self.topology,
            indices: self.all_indices(),
            samples: self.samples,
            state: self.scene.state,
            distances: self.scene.distances.clone(),
        }
    }

    /// The end points of segment `i` (of a list or a strip), as clip-space positions.
    #[must_use]
    pub fn segment(&self, i: usize) -> Option<[[f32; 4]; 2]> {
        let ends = match self.topology {
            Topology::LineList => self.indices.get(2 * i..2 * i + 2)?,
            Topology::LineStrip => self.indices.get(i..i + 2)?,
            _ => return None,
        };
        Some([0, 1].map(|k| self.scene.positions[ends[k] as usize]))
    }

    /// How many primitives it draws.
    #[must_use]
    pub fn primitive_count(&self) -> usize {
        self.topology
            .primitive_count(self.all_indices().len())
            .unwrap_or(0)
    }

    /// The same primitives as a list, in the same order: a line strip's segments as a line
    /// list, a triangle strip's or fan's triangles as a triangle list, each in
    /// [`Draw::triangle`]'s vertex order.
    #[must_use]
    pub fn as_list(&self) -> Self {
        match self.topology {
            Topology::LineStrip => Self {
                topology: Topology::LineList,
                indices: self.indices.windows(2).flatten().copied().collect(),
                ..self.clone()
            },
            Topology::TriangleStrip | Topology::TriangleFan => {
                let mut scene = self.scene.clone();
                scene.triangles = self.draw().triangles().into_owned();
                Self::triangles(scene, self.samples)
            }
            _ => self.clone(),
        }
    }
}

impl Case for PrimitiveScene {
    /// Every way of dropping one primitive: a triangle, a list's segment or point, a strip's
    /// first or last vertex, a fan's first or last rim vertex.
    fn reductions(&self) -> Vec<Self> {
        if self.topology == Topology::TriangleList {
            return self
                .scene
                .reductions()
                .into_iter()
                .map(|scene| Self {
                    scene,
                    ..self.clone()
                })
                .collect();
        }
        let per = match self.topology {
            Topology::LineList => 2,
            _ => 1,
        };
        let count = self.primitive_count();
        if count < 2 {
            return Vec::new();
        }
        let without = |range: std::ops::Range<usize>| {
            let mut s = self.clone();
            s.indices.drain(range);
            s
        };
        let last = self.indices.len() - 1..self.indices.len();
        match self.topology {
            Topology::LineStrip => vec![without(0..1), without(last)],
            // Dropping two first vertices keeps every later triangle's parity, and so its order.
            Topology::TriangleStrip => vec![without(0..2), without(0..1), without(last)],
            Topology::TriangleFan => vec![without(1..2), without(last)],
            _ => (0..count).map(|i| without(per * i..per * i + per)).collect(),
        }
    }

    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn scene_mut(&mut self) -> &mut Scene {
        &mut self.scene
    }

    fn data(&self) -> CaseData {
        CaseData::of_draw(DrawData::new(
            &self.scene,
            self.topology,
            self.all_indices(),
            self.samples,
        ))
    }

    fn from_data(data: &CaseData) -> Result<Self, String> {
        data.only_draw()?;
        let (scene, topology, indices, samples) = data.draw.scene()?;
        Ok(Self {
            scene,
            topology,
            indices,
            samples,
        })
    }
}

impl fmt::Debug for PrimitiveScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let scene = format!("{:?}", self.scene).replace('\n', "\n    ");
        writeln!(f, "PrimitiveScene {{")?;
        writeln!(f, "    scene: {scene},")?;
        writeln!(f, "    topology: Topology::{:?},", self.topology)?;
        writeln!(f, "    indices: vec!{:?},", self.indices)?;
        writeln!(f, "    samples: {},", self.samples)?;
        write!(f, "}}")
    }
}
