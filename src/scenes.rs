//! Built-in scenes: the five steps of the software rasterization lab (seed 000).
//!
//! The lab gives vertex data, a camera at (0, 0, −10) with a 60° vertical field of view, and a
//! clear colour of (100, 100, 100); it does not fix the window, so scenes default to 640 × 480.

use std::fmt;

use glam::{Mat4, Vec3};

use crate::camera::{Camera, Projection};
use crate::config::{ReferenceConfig, Traversal};
use crate::depth::{CompareOp, DepthState};
use crate::draw::Draw;
use crate::error::{ConfigError, DrawError};
use crate::pipeline::{Framebuffer, Mesh, Renderer, Vertex};
use crate::reference::Reference;
use crate::viewport::Viewport;

/// A built-in scene's name (as `refrast render` takes it) and what it shows: the one type for
/// it, which `refrast-render` lists its own scenes with too.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneInfo {
    /// The name.
    pub name: &'static str,
    /// One line on what it draws.
    pub description: &'static str,
}

/// Every built-in scene.
pub const SCENES: [SceneInfo; 5] = [
    SceneInfo {
        name: "lab000-ndc",
        description: "lab 000 step 1: a white triangle given in NDC, every pixel tested",
    },
    SceneInfo {
        name: "lab000-world",
        description: "lab 000 step 2: a white world-space triangle seen from (0, 0, -10) with a 60° FOV",
    },
    SceneInfo {
        name: "lab000-rgb",
        description: "lab 000 step 3: a red-green-blue triangle, colours interpolated by barycentrics",
    },
    SceneInfo {
        name: "lab000-depth",
        description: "lab 000 step 4: a red triangle in front of the RGB one, depth-tested, every pixel tested",
    },
    SceneInfo {
        name: "lab000-bbox",
        description: "lab 000 step 5: step 4 with bounding-box traversal (identical image)",
    },
];

/// The default window of the lab scenes.
pub const DEFAULT_SIZE: (u32, u32) = (640, 480);

/// The lab's clear colour.
pub const CLEAR: [u8; 4] = [100, 100, 100, 255];

/// Why a scene could not be rendered.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneError {
    /// No scene has that name.
    Unknown(String),
    /// The size is out of range.
    Config(ConfigError),
    /// The draw was refused.
    Draw(DrawError),
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Unknown(name) => {
                let names: Vec<_> = SCENES.iter().map(|s| s.name).collect();
                write!(f, "no scene named '{name}'; the scenes are: {}", names.join(", "))
            }
            Self::Config(e) => e.fmt(f),
            Self::Draw(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for SceneError {}

fn white(positions: [[f32; 3]; 3]) -> Mesh {
    Mesh {
        vertices: positions
            .map(|p| Vertex::colored(Vec3::from(p), Vec3::ONE))
            .to_vec(),
        triangles: vec![[0, 1, 2]],
    }
}

/// Triangle 1 of steps 3–5: red top, green right, blue left, at z = 2.
fn rgb_vertices() -> [Vertex; 3] {
    [
        Vertex::colored(Vec3::new(0.0, 4.0, 2.0), Vec3::X),
        Vertex::colored(Vec3::new(3.0, -2.0, 2.0), Vec3::Y),
        Vertex::colored(Vec3::new(-3.0, -2.0, 2.0), Vec3::Z),
    ]
}

/// A scene ready to draw: its mesh, camera and projection, and the renderer set up as the lab step does.
///
/// Fixed as the lab fixes it; `refrast-render`'s `Setup` builds on it with what a command line
/// may change (camera framing, shading, light, background, size).
#[derive(Clone, Debug)]
pub struct SceneSetup {
    /// The triangles with their colours.
    pub mesh: Mesh,
    /// World to clip space.
    pub view_projection: Mat4,
    /// The reference configured for the step (traversal) and its draw state (depth test).
    pub renderer: Renderer,
}

impl SceneSetup {
    /// The scene as a clip-space draw for `viewport`.
    #[must_use]
    pub fn draw(&self, viewport: Viewport) -> Draw {
        self.renderer
            .mesh_draw(viewport, &self.mesh, self.view_projection)
    }
}

/// Sets up the scene `name` for a target of the given aspect ratio (width / height).
pub fn build(name: &str, aspect: f32) -> Result<SceneSetup, SceneError> {
    let camera = Camera::new(Vec3::new(0.0, 0.0, -10.0), Vec3::Z);
    let projection = Projection::Perspective {
        fov_y: 60f32.to_radians(),
        aspect,
        near: 0.1,
        far: 100.0,
    };
    let view_projection = projection.matrix() * camera.view();
    // Steps 1–3 have no depth buffer yet: every fragment is written.
    let no_depth = DepthState {
        compare: CompareOp::Always,
        write: false,
        clear: 1.0,
    };
    let (mesh, view_projection, depth, traversal) = match name {
        "lab000-ndc" => (
            white([[0.0, 0.5, 1.0], [0.5, -0.5, 1.0], [-0.5, -0.5, 1.0]]),
            Mat4::IDENTITY,
            no_depth,
            Traversal::Viewport,
        ),
        "lab000-world" => (
            white([[0.0, 2.0, 0.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]),
            view_projection,
            no_depth,
            Traversal::Viewport,
        ),
        "lab000-rgb" => (
            Mesh {
                vertices: rgb_vertices().to_vec(),
                triangles: vec![[0, 1, 2]],
            },
            view_projection,
            no_depth,
            Traversal::Viewport,
        ),
        "lab000-depth" | "lab000-bbox" => {
            let red = Vec3::X;
            let mut vertices = vec![
                Vertex::colored(Vec3::new(0.0, 2.0, 0.0), red),
                Vertex::colored(Vec3::new(1.5, -1.0, 0.0), red),
                Vertex::colored(Vec3::new(-1.5, -1.0, 0.0), red),
            ];
            vertices.extend(rgb_vertices());
            let traversal = if name == "lab000-bbox" {
                Traversal::BoundingBox
            } else {
                Traversal::Viewport
            };
            (
                Mesh {
                    vertices,
                    triangles: vec![[0, 1, 2], [3, 4, 5]],
                },
                view_projection,
                DepthState::default(),
                traversal,
            )
        }
        _ => return Err(SceneError::Unknown(name.to_owned())),
    };
    let mut renderer = Renderer {
        reference: Reference::new(ReferenceConfig {
            traversal,
            ..ReferenceConfig::default()
        }),
        ..Renderer::default()
    };
    renderer.state.depth = depth;
    Ok(SceneSetup {
        mesh,
        view_projection,
        renderer,
    })
}

/// Renders the scene `name` at `width × height` onto the lab's clear colour.
pub fn render(name: &str, width: u32, height: u32) -> Result<Framebuffer, SceneError> {
    let mut target = Framebuffer::new(width, height).map_err(SceneError::Config)?;
    let scene = build(name, width as f32 / height as f32)?;
    target.clear(CLEAR, scene.renderer.state.depth.clear);
    scene
        .renderer
        .draw_mesh(
            &mut target,
            &scene.mesh,
            Mat4::IDENTITY,
            scene.view_projection,
            |f| Some(f.color),
        )
        .map_err(SceneError::Draw)?;
    Ok(target)
}
