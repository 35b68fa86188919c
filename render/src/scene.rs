//! The built-in scenes of `refrast render`: lab 000's five steps, seed 002's room, and meshes
//! like seed 004's, some reaching outside the view so that they must be clipped.

use glam::{Mat4, Vec3};
use refrast::pipeline::Mesh;
use refrast::scenes::SceneInfo;
use refrast::{CullMode, DrawState, Traversal};

use crate::geometry::{bounds, smooth_normals, to_left_handed};
use crate::load::Loaded;
use crate::room;
use crate::shade::{Light, Shading};
use crate::shapes;
use crate::view::{Lens, Overrides, View, ViewError};

/// How a scene is looked at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Framing {
    /// The vertices are given in clip space already (lab 000's first step).
    ClipSpace,
    /// A fixed camera.
    Fixed(View),
    /// A camera that shows the whole mesh ([`View::frame`]).
    Auto,
}

/// A scene ready to draw: the mesh and the defaults that the command line may override.
///
/// Not [`refrast::scenes::SceneSetup`], which fixes the camera and projection as lab 000 does:
/// this one keeps how the scene is framed, so that `--eye`, `--fov` and the viewer can move it.
#[derive(Clone, Debug)]
pub struct Setup {
    /// The triangles, in world space (clip space under [`Framing::ClipSpace`]).
    pub mesh: Mesh,
    /// The camera.
    pub framing: Framing,
    /// Culling, facing, depth test and clipping.
    pub state: DrawState,
    /// How the reference walks pixels (lab 000's fifth step walks bounding boxes).
    pub traversal: Traversal,
    /// The default shading.
    pub shading: Shading,
    /// The light; `None` for a headlight above the eye.
    pub light: Option<Light>,
    /// The background.
    pub clear: [u8; 4],
    /// The default picture size.
    pub size: (u32, u32),
}

/// A scene's view resolved for one picture: world to clip space, and where the eye is.
///
/// No camera of its own: the camera is [`View`]'s (built on refrast's
/// [`Camera`](refrast::camera::Camera)); this is what drawing needs once the aspect is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Framed {
    /// World to clip space.
    pub view_projection: Mat4,
    /// The eye, for lighting.
    pub eye: Vec3,
    /// The view, unless the scene is in clip space already.
    pub view: Option<View>,
}

impl Setup {
    /// The scene's camera for a target of the given aspect ratio, with the command line's
    /// choices applied (a clip-space scene gets a framed camera once any is given).
    pub fn camera(&self, aspect: f32, overrides: &Overrides) -> Result<Framed, ViewError> {
        let bounds = bounds(&self.mesh).unwrap_or((Vec3::splat(-1.0), Vec3::ONE));
        let base = match self.framing {
            Framing::ClipSpace if !overrides.any() => {
                return Ok(Framed {
                    view_projection: Mat4::IDENTITY,
                    eye: Vec3::new(0.0, 0.0, -1.0),
                    view: None,
                });
            }
            Framing::Fixed(view) => view,
            Framing::ClipSpace | Framing::Auto => View::frame(bounds, aspect),
        };
        let view = base.with(overrides, bounds);
        view.validate()?;
        Ok(Framed {
            view_projection: view.view_projection(aspect),
            eye: view.eye,
            view: Some(view),
        })
    }

    /// The light: the scene's, or a headlight a little above and to the left of the eye.
    #[must_use]
    pub fn light(&self, camera: &Framed) -> Light {
        self.light.unwrap_or_else(|| {
            let offset = camera.view.map_or(Vec3::ZERO, |v| {
                let (right, up, _) = v.camera().basis();
                ((up - right) * 0.5) * (v.target - v.eye).length()
            });
            Light::headlight(camera.eye + offset)
        })
    }

    /// A mesh read from a file: turned into our left-handed world, framed automatically from
    /// its front, Phong-shaded under a headlight, with normals computed where the file has none.
    #[must_use]
    pub fn from_loaded(loaded: Loaded) -> Self {
        let mut mesh = to_left_handed(loaded.mesh);
        if !loaded.has_normals {
            smooth_normals(&mut mesh);
        }
        Self::mesh(mesh, Framing::Auto, Shading::Phong, CullMode::None)
    }

    /// A mesh scene: depth-tested, clipped at the far plane as every graphics API clips (the GPU
    /// adapters cannot do otherwise), on a dark background.
    fn mesh(mesh: Mesh, framing: Framing, shading: Shading, cull: CullMode) -> Self {
        Self {
            mesh,
            framing,
            state: DrawState {
                cull,
                clip_far: true,
                ..DrawState::default()
            },
            traversal: Traversal::BoundingBox,
            shading,
            light: None,
            clear: [40, 40, 48, 255],
            size: refrast::scenes::DEFAULT_SIZE,
        }
    }
}

/// The scenes besides lab 000's (which [`refrast::scenes::SCENES`] lists).
const MORE: [SceneInfo; 13] = [
    SceneInfo {
        name: "room",
        description: "lab 002: a Cornell box with a short and a tall block, lit per pixel by the lab's light",
    },
    SceneInfo {
        name: "plane",
        description: "lab 004: a square of 8 × 8 quads, colours across (shared edges everywhere)",
    },
    SceneInfo {
        name: "aligned-plane",
        description: "the plane head-on and orthographic, its diagonals through pixel centres: the fill rule decides them",
    },
    SceneInfo {
        name: "star",
        description: "lab 004: a flat five-pointed star, a fan of thin triangles around its centre",
    },
    SceneInfo {
        name: "overlaps",
        description: "seed 003: three bars overlapping in a cycle and two triangles through each other: no painting order draws them",
    },
    SceneInfo {
        name: "text",
        description: "lab 004: the word 'refrast' in 8 × 8 glyph cells sharing their edges",
    },
    SceneInfo {
        name: "torus",
        description: "lab 004: a torus of 48 × 24 quads, coloured around its rings",
    },
    SceneInfo {
        name: "sphere",
        description: "a UV sphere of 48 × 24, for shading",
    },
    SceneInfo {
        name: "clipped-plane",
        description: "the plane tilted through the near plane and past the sides: clipped everywhere",
    },
    SceneInfo {
        name: "floor",
        description: "a floor of two triangles to the horizon, cut by the near plane: try --texture checker",
    },
    SceneInfo {
        name: "clipped-star",
        description: "lab 004: the star, larger than the view and tilted through the near plane",
    },
    SceneInfo {
        name: "clipped-torus",
        description: "lab 004: the torus lying around the eye, cut by the near plane and the sides",
    },
    SceneInfo {
        name: "clipped-text",
        description: "the text seen at a grazing angle, reaching behind the eye",
    },
];

/// Every built-in scene: lab 000's steps first.
#[must_use]
pub fn scenes() -> Vec<SceneInfo> {
    refrast::scenes::SCENES.into_iter().chain(MORE).collect()
}

/// The fixed camera of the clipped scenes: at (0, 0, −3) looking at the origin, 50°, near 0.5.
fn clipped_view() -> View {
    View {
        eye: Vec3::new(0.0, 0.0, -3.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        lens: Lens::Perspective { fov_y_degrees: 50.0 },
        near: 0.5,
        far: 50.0,
    }
}

/// A camera `distance` before the origin on −z, looking along +z with `fov_y_degrees`.
fn head_on(distance: f32, fov_y_degrees: f32) -> View {
    View {
        eye: Vec3::new(0.0, 0.0, -distance),
        target: Vec3::ZERO,
        up: Vec3::Y,
        lens: Lens::Perspective { fov_y_degrees },
        near: 0.1,
        far: 100.0,
    }
}

/// A mesh scene seen by the clipped scenes' fixed camera, unlit.
fn clipped(mesh: Mesh, cull: CullMode) -> Setup {
    Setup::mesh(mesh, Framing::Fixed(clipped_view()), Shading::None, cull)
}

/// The torus of the torus scenes: radii 1 and 0.4, 48 × 24 quads.
fn torus() -> Mesh {
    shapes::torus(1.0, 0.4, 48, 24).expect("0 < 0.4 < 1: valid radii")
}

/// `mesh` moved by `model`, normals with it.
fn transformed(mut mesh: Mesh, model: Mat4) -> Mesh {
    let normals = model.inverse().transpose();
    for v in &mut mesh.vertices {
        v.position = model.transform_point3(v.position);
        v.normal = normals.transform_vector3(v.normal).normalize_or_zero();
    }
    mesh
}

/// The scene `name`, or `None` if there is none of that name.
#[must_use]
pub fn scene(name: &str) -> Option<Setup> {
    if let Ok(lab) = refrast::scenes::build(name, 1.0) {
        let framing = if name == "lab000-ndc" {
            Framing::ClipSpace
        } else {
            // Lab 000's camera: at (0, 0, −10) looking along +z with a 60° field of view.
            Framing::Fixed(head_on(10.0, 60.0))
        };
        return Some(Setup {
            mesh: lab.mesh,
            framing,
            // Far clipping changes no lab picture (everything lies before the far plane) and
            // lets the GPU adapters, which always clip at far, draw the scene.
            state: DrawState {
                clip_far: true,
                ..lab.renderer.state
            },
            traversal: lab.renderer.reference.config().traversal,
            shading: Shading::None,
            light: None,
            clear: refrast::scenes::CLEAR,
            size: refrast::scenes::DEFAULT_SIZE,
        });
    }
    let tilt = |degrees: f32| Mat4::from_rotation_x(degrees.to_radians());
    let setup = match name {
        "room" => Setup {
            light: Some(Light::LAB_002),
            clear: [0, 0, 0, 255],
            size: (500, 500),
            ..Setup::mesh(
                room::room(),
                Framing::Fixed(View {
                    eye: room::EYE,
                    target: Vec3::ZERO,
                    up: Vec3::Y,
                    lens: Lens::Perspective {
                        fov_y_degrees: room::fov_y_degrees(),
                    },
                    near: 0.5,
                    far: 10.0,
                }),
                Shading::Phong,
                CullMode::None,
            )
        },
        "plane" => Setup::mesh(shapes::plane(8), Framing::Auto, Shading::None, CullMode::None),
        "aligned-plane" => Setup {
            size: (512, 512),
            ..Setup::mesh(
                shapes::plane(8),
                // 2 units over 512 px: vertices every 64 px on pixel corners, so each quad's
                // diagonal runs through the centres of the pixels it crosses.
                Framing::Fixed(View {
                    eye: Vec3::new(0.0, 0.0, -2.0),
                    target: Vec3::ZERO,
                    up: Vec3::Y,
                    lens: Lens::Orthographic { height: 2.0 },
                    near: 1.0,
                    far: 3.0,
                }),
                Shading::None,
                CullMode::None,
            )
        },
        "star" => Setup::mesh(shapes::star(5), Framing::Auto, Shading::None, CullMode::None),
        // Head-on, so that world z alone orders the surfaces, as the cycle is built.
        "overlaps" => Setup::mesh(
            shapes::overlaps(),
            Framing::Fixed(head_on(8.0, 30.0)),
            Shading::None,
            CullMode::None,
        ),
        "text" => Setup::mesh(
            shapes::text("refrast"),
            Framing::Auto,
            Shading::None,
            CullMode::None,
        ),
        "torus" => Setup::mesh(torus(), Framing::Auto, Shading::None, CullMode::Back),
        "sphere" => Setup::mesh(
            shapes::sphere(48, 24),
            Framing::Auto,
            Shading::Phong,
            CullMode::Back,
        ),
        "clipped-plane" => clipped(
            transformed(shapes::plane(8), Mat4::from_scale(Vec3::splat(3.0)) * tilt(-70.0)),
            CullMode::None,
        ),
        "floor" => clipped(
            transformed(
                shapes::plane(1),
                Mat4::from_translation(Vec3::new(0.0, -1.0, 2.0))
                    * tilt(90.0)
                    * Mat4::from_scale(Vec3::splat(6.0)),
            ),
            CullMode::None,
        ),
        "clipped-star" => clipped(
            transformed(shapes::star(5), Mat4::from_scale(Vec3::splat(3.6)) * tilt(-55.0)),
            CullMode::None,
        ),
        "clipped-torus" => clipped(
            transformed(
                torus(),
                // Twice as large, tilted so that its lower half comes at the eye: cut by the
                // near plane below, by the sides left and right.
                Mat4::from_translation(Vec3::new(0.0, 0.2, -1.2))
                    * tilt(-50.0)
                    * Mat4::from_scale(Vec3::splat(2.2)),
            ),
            CullMode::Back,
        ),
        "clipped-text" => clipped(
            transformed(
                shapes::text("refrast"),
                Mat4::from_translation(Vec3::new(0.0, -0.1, -2.2))
                    * tilt(-60.0)
                    * Mat4::from_scale(Vec3::splat(6.0)),
            ),
            CullMode::None,
        ),
        _ => return None,
    };
    Some(setup)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_builds_with_a_valid_camera() {
        for info in scenes() {
            let setup = scene(info.name).unwrap_or_else(|| panic!("{}", info.name));
            assert!(!setup.mesh.triangles.is_empty(), "{}", info.name);
            let (w, h) = setup.size;
            setup.camera(w as f32 / h as f32, &Overrides::default()).unwrap();
        }
        assert!(scene("no-such-scene").is_none());
    }

    #[test]
    fn clipped_scenes_reach_through_the_near_plane_and_past_the_sides() {
        for name in [
            "clipped-plane",
            "clipped-star",
            "clipped-torus",
            "clipped-text",
            "floor",
        ] {
            let setup = scene(name).unwrap();
            let camera = setup.camera(4.0 / 3.0, &Overrides::default()).unwrap();
            let clip: Vec<_> = setup
                .mesh
                .vertices
                .iter()
                .map(|v| camera.view_projection * v.position.extend(1.0))
                .collect();
            assert!(
                clip.iter().any(|c| c.z < 0.0),
                "{name}: nothing before the near plane"
            );
            assert!(
                clip.iter().any(|c| c.x.abs() > c.w || c.y.abs() > c.w),
                "{name}: nothing past a side"
            );
            assert!(
                clip.iter()
                    .any(|c| c.z > 0.0 && c.x.abs() < c.w && c.y.abs() < c.w),
                "{name}: nothing in view"
            );
        }
    }

    #[test]
    fn a_clip_space_scene_gets_a_camera_once_asked() {
        let setup = scene("lab000-ndc").unwrap();
        let plain = setup.camera(1.0, &Overrides::default()).unwrap();
        assert_eq!(plain.view_projection, Mat4::IDENTITY);
        let moved = Overrides {
            eye: Some(Vec3::new(0.0, 0.0, -4.0)),
            ..Overrides::default()
        };
        let framed = setup.camera(1.0, &moved).unwrap();
        assert_eq!(framed.eye, Vec3::new(0.0, 0.0, -4.0));
        assert_ne!(framed.view_projection, Mat4::IDENTITY);
    }
}
