//! What the viewer shows and how keys change it: the camera, the mode, the implementation, the
//! culling and the light, and one frame drawn from them; no window here, so it runs in tests.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use refrast::pipeline::Framebuffer;
use refrast::{CullMode, DrawError, DrawState};
use refrast_render::scene::{Framed, Framing};
use refrast_render::{Light, Mode, View, geometry};

use super::camera::{FlyCamera, Motion};
use super::drawer::{CYCLE, Drawer, build};
use super::keys::Action;
use crate::options::{Failure, Prepared};

/// Radians the camera turns per pixel the mouse is dragged.
const MOUSE_RADIANS_PER_PIXEL: f32 = 0.005;

/// How long a message (a saved file, a refused draw) stays on the status line.
const MESSAGE_SECONDS: u64 = 4;

/// The viewer's state between frames.
pub struct Viewer<'a> {
    scene: &'a Prepared,
    impls: Vec<String>,
    current: usize,
    rasterizer: Drawer,
    threads: usize,
    /// What is shown.
    pub mode: Mode,
    /// The camera, `None` for a scene given in clip space (lab000-ndc), which has no eye to move.
    fly: Option<FlyCamera>,
    start: Option<FlyCamera>,
    state: DrawState,
    light: Light,
    headlight: bool,
    /// Whether the movement keys move the light.
    pub moving_light: bool,
    /// The picture, without the status line.
    pub target: Framebuffer,
    output: PathBuf,
    message: Option<(String, Instant)>,
    /// Samples per pixel: 1, or 4 after `M`.
    pub samples: u8,
}

impl<'a> Viewer<'a> {
    /// A viewer of `scene` in `mode`, drawn first by `implementation` (`fast` with `threads`
    /// threads), saving pictures into `output`.
    pub fn new(
        scene: &'a Prepared,
        implementation: &str,
        threads: usize,
        mode: Mode,
        output: PathBuf,
    ) -> Result<Self, Failure> {
        let mut impls: Vec<String> = CYCLE.iter().map(|s| (*s).to_owned()).collect();
        let current = match impls.iter().position(|n| n == implementation) {
            Some(i) => i,
            None => {
                impls.insert(0, implementation.to_owned());
                0
            }
        };
        let rasterizer = build(implementation, scene, threads)?;
        let (width, height) = scene.size;
        let target = Framebuffer::new(width, height).map_err(|e| Failure(e.to_string(), 2))?;
        let speed = scene_speed(scene);
        let fly = scene
            .camera
            .view
            .map(|view| FlyCamera::new(&roomy(scene, view), speed));
        Ok(Self {
            scene,
            impls,
            current,
            rasterizer,
            threads,
            mode,
            fly,
            start: fly,
            state: scene.state,
            light: scene.light,
            headlight: scene.headlight,
            moving_light: false,
            target,
            output,
            message: None,
            samples: 1,
        })
    }

    /// The name of the implementation drawing.
    #[must_use]
    pub fn implementation(&self) -> &str {
        &self.impls[self.current]
    }

    /// Where the eye is, if the scene has one.
    #[cfg(test)]
    #[must_use]
    pub fn eye(&self) -> Option<glam::Vec3> {
        self.fly.map(|f| f.eye)
    }

    /// The light's position.
    #[cfg(test)]
    #[must_use]
    pub fn light_position(&self) -> glam::Vec3 {
        self.light.position
    }

    /// Carries out `action`, returning a line saying what changed; `Quit` is the caller's.
    pub fn act(&mut self, action: Action) -> Option<String> {
        match action {
            Action::Mode(mode) => {
                self.mode = mode;
                Some(format!("mode {mode}"))
            }
            Action::NextImpl => Some(self.next_impl()),
            Action::ToggleCull => {
                self.state.cull = match (self.state.cull, self.scene.state.cull) {
                    (CullMode::None, CullMode::None) => CullMode::Back,
                    (CullMode::None, scene) => scene,
                    _ => CullMode::None,
                };
                Some(format!("cull {}", cull_name(self.state.cull)))
            }
            Action::ToggleSamples => {
                self.samples = if self.samples == 1 { 4 } else { 1 };
                Some(if self.samples == 1 {
                    "1 sample per pixel".to_owned()
                } else {
                    format!("{} samples per pixel", self.samples)
                })
            }
            Action::ToggleLight => {
                self.moving_light = !self.moving_light;
                Some(format!(
                    "the movement keys move the {}",
                    if self.moving_light { "light" } else { "camera" }
                ))
            }
            Action::Save => Some(match self.save() {
                Ok(path) => self.tell(format!("saved {}", path.display())),
                Err(e) => self.tell(e),
            }),
            Action::Reset => {
                self.fly = self.start;
                Some("camera reset".to_owned())
            }
            Action::Quit => None,
        }
    }

    /// Steps to the next implementation of the cycle; one that cannot be built is said and skipped.
    fn next_impl(&mut self) -> String {
        for _ in 0..self.impls.len() {
            self.current = (self.current + 1) % self.impls.len();
            match build(&self.impls[self.current], self.scene, self.threads) {
                Ok(r) => {
                    self.rasterizer = r;
                    return format!("impl {}", self.implementation());
                }
                Err(Failure(why, _)) => {
                    self.tell(why);
                }
            }
        }
        format!("impl {}", self.implementation())
    }

    /// Moves the camera, or the light, for `dt` seconds as `motion` asks, and turns the camera
    /// by a mouse drag of `drag` pixels.
    pub fn step(&mut self, motion: &Motion, drag: (f32, f32), dt: f32) {
        let Some(fly) = &mut self.fly else {
            return;
        };
        if self.moving_light {
            let moved = fly.displacement(motion, dt);
            if moved != glam::Vec3::ZERO {
                // A headlight left behind stays where it was put.
                self.light.position += moved;
                self.headlight = false;
            }
            fly.steer(motion, dt);
        } else {
            fly.update(motion, dt);
        }
        // Dragging right turns right; dragging up looks up (window y grows downwards).
        fly.turn(
            drag.0 * MOUSE_RADIANS_PER_PIXEL,
            -drag.1 * MOUSE_RADIANS_PER_PIXEL,
        );
    }

    /// Makes the picture `width`×`height`; the projection follows the new aspect ratio.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<(), String> {
        self.target = Framebuffer::new(width, height).map_err(|e| e.to_string())?;
        Ok(())
    }

    /// The camera for the current picture size.
    fn camera(&self) -> Framed {
        let viewport = self.target.viewport();
        let aspect = viewport.width() as f32 / viewport.height() as f32;
        self.fly.map_or(self.scene.camera, |f| f.camera(aspect))
    }

    /// Draws one frame into [`target`](Self::target), returning whether the rasterizer drew it
    /// and how long that took.
    pub fn draw(&mut self) -> (Result<(), DrawError>, Duration) {
        let camera = self.camera();
        if self.headlight {
            self.light.position = self.scene.setup.light(&camera).position;
        }
        let job = self.scene.job(self.mode, &camera, self.light, self.state);
        let start = Instant::now();
        let drawn = self.rasterizer.draw(&job, self.samples, &mut self.target);
        (drawn, start.elapsed())
    }

    /// The two status lines: implementation, mode, triangles and culling; frame and render
    /// times, and the latest message while it is fresh.
    #[must_use]
    pub fn status(&self, render_ms: f64, frame_ms: f64) -> String {
        let mut line = format!(
            "{} | {} | {} triangles | cull {}\nframe {frame_ms:.1} ms, render {render_ms:.1} ms",
            self.implementation(),
            self.mode,
            self.scene.setup.mesh.triangles.len(),
            cull_name(self.state.cull),
        );
        if self.samples > 1 {
            line.push_str(&format!(" | {} samples", self.samples));
        }
        if self.moving_light {
            line.push_str(" | keys move the light");
        }
        if let Some((message, at)) = &self.message
            && at.elapsed() < Duration::from_secs(MESSAGE_SECONDS)
        {
            line.push_str(" | ");
            line.push_str(message);
        }
        line
    }

    /// Puts `message` on the status line for a while, and returns it.
    pub fn tell(&mut self, message: String) -> String {
        self.message = Some((message.clone(), Instant::now()));
        message
    }

    /// Writes the picture to the first free `STEM-IMPL-MODE-N.png` in the output folder.
    fn save(&self) -> Result<PathBuf, String> {
        let base = format!("{}-{}-{}", self.scene.stem, self.implementation(), self.mode).replace(':', "-");
        let path = (1..)
            .map(|n| self.output.join(format!("{base}-{n}.png")))
            .find(|p| !p.exists())
            .expect("an unbounded range has a free name");
        refrast_render::output::save_png(&self.target, &path)
            .map_err(|e| format!("could not write {}: {e}", path.display()))?;
        Ok(path)
    }
}

/// The view with room to fly: an automatically framed mesh's planes hug it, so that stepping
/// closer would cut it at once; they are widened unless `--near` or `--far` was given. A scene
/// with a camera of its own keeps its planes (the clipped scenes are about them).
fn roomy(scene: &Prepared, mut view: View) -> View {
    let framed = scene.setup.framing == Framing::Auto;
    let given = scene.overrides.near.is_some() || scene.overrides.far.is_some();
    if let (true, false, Some((lo, hi))) = (framed, given, geometry::bounds(&scene.setup.mesh)) {
        let radius = ((hi - lo).length() / 2.0).max(1e-3);
        let distance = ((lo + hi) / 2.0 - view.eye).length();
        view.near = view.near.min(radius * 0.02);
        view.far = view.far.max(distance + 4.0 * radius);
    }
    view
}

/// Moving speed: the scene's bounding sphere's radius a second, so every scene takes a few
/// seconds to cross.
fn scene_speed(scene: &Prepared) -> f32 {
    geometry::bounds(&scene.setup.mesh).map_or(1.0, |(lo, hi)| ((hi - lo).length() / 2.0).max(1e-3))
}

fn cull_name(cull: CullMode) -> &'static str {
    match cull {
        CullMode::None => "none",
        CullMode::Back => "back",
        CullMode::Front => "front",
        CullMode::FrontAndBack => "front-and-back",
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;
    use crate::options::{SceneArgs, prepare};

    #[derive(Parser)]
    struct Line {
        #[command(flatten)]
        scene: SceneArgs,
    }

    /// The scene as the command line `refrast view ARGS` would prepare it.
    fn scene(args: &[&str]) -> Prepared {
        let line = Line::parse_from(std::iter::once("view").chain(args.iter().copied()));
        prepare(&line.scene).unwrap()
    }

    fn colors(viewer: &mut Viewer<'_>) -> Vec<[u8; 4]> {
        let (drawn, _) = viewer.draw();
        drawn.unwrap();
        viewer.target.color().to_vec()
    }

    #[test]
    fn i_cycles_the_list_from_the_first_implementation() {
        let room = scene(&["room", "--size", "64x48"]);
        let mut v = Viewer::new(&room, "fast", 1, Mode::Fill, PathBuf::from(".")).unwrap();
        let mut seen = vec![v.implementation().to_owned()];
        for _ in 0..CYCLE.len() {
            assert_eq!(
                v.act(Action::NextImpl),
                Some(format!("impl {}", v.implementation()))
            );
            seen.push(v.implementation().to_owned());
        }
        assert_eq!(seen[1..], [&CYCLE[2..], &CYCLE[..2]].concat());
        // One outside the list starts the cycle.
        let mut euc = Viewer::new(&room, "euc", 1, Mode::Fill, PathBuf::from(".")).unwrap();
        euc.act(Action::NextImpl);
        assert_eq!(euc.implementation(), "reference");
        assert!(Viewer::new(&room, "no-such", 1, Mode::Fill, PathBuf::from(".")).is_err());
    }

    #[test]
    fn a_mutant_changes_the_overdraw_picture_of_the_aligned_plane() {
        let plane = scene(&["aligned-plane", "--size", "128x128"]);
        let mut v = Viewer::new(&plane, "fast", 1, Mode::Overdraw, PathBuf::from(".")).unwrap();
        let fast = colors(&mut v);
        while !v.implementation().starts_with("mutant:") {
            v.act(Action::NextImpl);
        }
        let mutant = colors(&mut v);
        let differ = fast.iter().zip(&mutant).filter(|(a, b)| a != b).count();
        assert!(
            differ > 100,
            "{differ} pixels differ under {}",
            v.implementation()
        );
    }

    #[test]
    fn moving_changes_the_picture_and_reset_undoes_it() {
        let room = scene(&["room", "--size", "64x48"]);
        let mut v = Viewer::new(&room, "reference", 1, Mode::Fill, PathBuf::from(".")).unwrap();
        let before = colors(&mut v);
        let eye = v.eye().unwrap();
        v.step(
            &crate::view::keys::motion(|k| k == minifb::Key::W),
            (0.0, 0.0),
            0.2,
        );
        assert!(v.eye().unwrap().z > eye.z, "W walks into the room");
        assert_ne!(colors(&mut v), before);
        v.act(Action::Reset);
        assert_eq!(colors(&mut v), before);
        // A drag turns the camera without moving it.
        v.step(&Motion::default(), (40.0, 0.0), 0.016);
        assert_eq!(v.eye(), Some(eye));
        assert_ne!(colors(&mut v), before);
    }

    #[test]
    fn l_hands_the_movement_keys_to_the_light() {
        let room = scene(&["room", "--size", "32x32"]);
        let mut v = Viewer::new(&room, "fast", 1, Mode::Fill, PathBuf::from(".")).unwrap();
        let (eye, light) = (v.eye(), v.light_position());
        v.act(Action::ToggleLight);
        let up = Motion {
            up: 1.0,
            ..Motion::default()
        };
        v.step(&up, (0.0, 0.0), 0.1);
        assert_eq!(v.eye(), eye);
        assert!(v.light_position().y > light.y);
        assert!(v.status(1.0, 2.0).contains("keys move the light"));
        v.act(Action::ToggleLight);
        v.step(&up, (0.0, 0.0), 0.1);
        assert!(v.eye().unwrap().y > eye.unwrap().y);
    }

    #[test]
    fn m_toggles_four_samples_and_the_status_line_says_so() {
        let star = scene(&["star", "--size", "64x48"]);
        let mut v = Viewer::new(&star, "reference", 1, Mode::Fill, PathBuf::from(".")).unwrap();
        let one = colors(&mut v);
        assert_eq!(
            v.act(Action::ToggleSamples).as_deref(),
            Some("4 samples per pixel")
        );
        assert!(v.status(1.0, 2.0).contains("| 4 samples"));
        let four = colors(&mut v);
        // Edge pixels blend: the two pictures differ, though not everywhere.
        let differ = one.iter().zip(&four).filter(|(a, b)| a != b).count();
        assert!(differ > 10 && differ < one.len() / 2, "{differ} pixels differ");
        assert_eq!(
            v.act(Action::ToggleSamples).as_deref(),
            Some("1 sample per pixel")
        );
        assert!(!v.status(1.0, 2.0).contains("samples"));
    }

    #[test]
    fn c_toggles_culling_and_the_status_line_says_so() {
        let torus = scene(&["torus", "--size", "32x32"]);
        let mut v = Viewer::new(&torus, "fast", 1, Mode::Overdraw, PathBuf::from(".")).unwrap();
        assert_eq!(
            v.status(1.0, 2.0),
            "fast | overdraw | 2304 triangles | cull back\nframe 2.0 ms, render 1.0 ms"
        );
        let culled = colors(&mut v);
        assert_eq!(v.act(Action::ToggleCull).as_deref(), Some("cull none"));
        assert!(v.status(1.0, 2.0).contains("cull none"));
        assert_ne!(colors(&mut v), culled, "back faces add overdraw");
        assert_eq!(v.act(Action::ToggleCull).as_deref(), Some("cull back"));
    }

    #[test]
    fn p_saves_the_picture_to_a_new_file_each_time() {
        let dir = std::env::temp_dir().join(format!("refrast-view-save-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let room = scene(&["room", "--size", "32x24"]);
        let mut v = Viewer::new(&room, "mutant:inclusive-edges", 1, Mode::Depth, dir.clone()).unwrap();
        colors(&mut v);
        let first = v.act(Action::Save).unwrap();
        let second = v.act(Action::Save).unwrap();
        assert_eq!(
            first,
            format!(
                "saved {}",
                dir.join("room-mutant-inclusive-edges-depth-1.png").display()
            )
        );
        assert!(second.ends_with("depth-2.png"), "{second}");
        assert!(v.status(0.0, 0.0).ends_with(&second));
        let png = std::fs::read(dir.join("room-mutant-inclusive-edges-depth-2.png")).unwrap();
        assert!(png.starts_with(b"\x89PNG"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
