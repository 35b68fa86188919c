//! `refrast view`: a window showing a scene or mesh drawn every frame by any built-in rasterizer,
//! with a camera to fly, the render modes on the number keys, and the implementation switched
//! by a key, so that a student sees what `certify` reports (a cracked edge in `overdraw`).
//!
//! One module per concern: [`camera`] (yaw, pitch, movement), [`keys`] (the bindings),
//! [`app`] (the state the keys change, and one frame), [`drawer`] (the implementations and how
//! each draws), [`overlay`] (the status lines), [`timing`] (frame times), [`window`] (the
//! display, through minifb).

mod app;
mod camera;
mod drawer;
mod keys;
mod overlay;
mod timing;
mod window;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use refrast_render::Mode;

use self::app::Viewer;
use self::drawer::CYCLE;
use self::keys::Action;
use self::timing::FrameTimes;
use self::window::Screen;
use crate::options::{Failure, SceneArgs, prepare};
use crate::say;

/// Arguments of `refrast view`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// The scene, its size, camera, light and first rasterizer (`--impl`, default fast).
    #[command(flatten)]
    scene: SceneArgs,
    /// What to show first: points, wire, fill, depth, normals, barycentric or overdraw (keys 1 to 7).
    #[arg(long, value_name = "MODE", default_value = "fill", value_parser = |s: &str| s.parse::<Mode>())]
    mode: Mode,
    /// Threads the fast rasterizer draws with (the 60 fps target is for one).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: u16,
    /// Draw N frames as fast as possible, then close and print the median and mean times of
    /// rendering and of whole frames (for measuring; the first 10 frames are not counted).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    frames: Option<u32>,
    /// The folder `P` saves pictures into.
    #[arg(short, long, value_name = "DIR", default_value = ".")]
    output: PathBuf,
}

/// Frames not counted by `--frames`: the first draws allocate and warm the caches.
const WARMUP: usize = 10;

/// The interactive frame rate: the loop sleeps out what is left of each 60th of a second.
const FRAME_BUDGET: Duration = Duration::from_nanos(1_000_000_000 / 60);

/// Runs `refrast view`: 0 when the window is closed (or `--frames` are drawn), 2 on bad input or
/// without a display, 1 when a frame cannot be shown or a measured draw is refused.
pub fn run(args: &ViewArgs) -> ExitCode {
    match view(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message, code)) => {
            eprintln!("error: {message}");
            ExitCode::from(code)
        }
    }
}

fn view(args: &ViewArgs) -> Result<(), Failure> {
    let scene = prepare(&args.scene)?;
    let implementation = args.scene.implementation.as_deref().unwrap_or("fast");
    if !args.output.is_dir() {
        return Err(Failure(
            format!("--output {} is not a folder", args.output.display()),
            2,
        ));
    }
    let mut viewer = Viewer::new(
        &scene,
        implementation,
        usize::from(args.threads),
        args.mode,
        args.output.clone(),
    )?;
    let (width, height) = scene.size;
    let title = format!("refrast view: {}", scene.stem);
    let mut screen = Screen::open(&title, width as usize, height as usize).map_err(|e| Failure(e, 2))?;
    if args.frames.is_none() {
        say(&format!(
            "{title}: {} triangles; I cycles {}",
            scene.setup.mesh.triangles.len(),
            CYCLE.join(", ")
        ));
        for (keys, what) in keys::HELP {
            say(&format!("  {keys:<11} {what}"));
        }
        say("  the status lines: implementation, mode, triangles, culling; frame and render times");
    }
    let mut times = FrameTimes::default();
    let mut last = Instant::now();
    let mut drawn = 0u32;
    while screen.is_open() {
        let start = Instant::now();
        let dt = start.duration_since(last).as_secs_f32().min(0.1);
        last = start;
        if !input(&mut screen, &mut viewer, dt) {
            break;
        }
        let (w, h) = screen.size();
        let viewport = viewer.target.viewport();
        if (w, h) != (viewport.width() as usize, viewport.height() as usize) && w > 0 && h > 0 {
            viewer.resize(w as u32, h as u32).map_err(|e| Failure(e, 1))?;
            say(&format!("size {w}x{h}"));
        }
        let (drawn_ok, render_time) = viewer.draw();
        if let Err(e) = drawn_ok {
            let why = format!("{} refused the draw: {e}", viewer.implementation());
            if args.frames.is_some() {
                return Err(Failure(why, 1));
            }
            viewer.tell(why);
        }
        let (render_ms, frame_ms) = times.recent_ms();
        screen
            .show(&viewer.target, &viewer.status(render_ms, frame_ms))
            .map_err(|e| Failure(e, 1))?;
        times.push(render_time, start.elapsed());
        drawn += 1;
        match args.frames {
            Some(n) if drawn >= n => break,
            Some(_) => {}
            None => std::thread::sleep(FRAME_BUDGET.saturating_sub(start.elapsed())),
        }
    }
    if args.frames.is_some() {
        report(&times, &viewer, args);
    }
    Ok(())
}

/// Reads this frame's keys and mouse into the viewer; `false` when the viewer should close.
fn input(screen: &mut Screen, viewer: &mut Viewer<'_>, dt: f32) -> bool {
    for key in screen.pressed() {
        match keys::action(key) {
            Some(Action::Quit) => return false,
            Some(action) => {
                if let Some(line) = viewer.act(action) {
                    say(&line);
                }
            }
            None => {}
        }
    }
    let motion = keys::motion(|k| screen.held(k));
    let drag = screen.drag();
    viewer.step(&motion, drag, dt);
    true
}

/// Prints `--frames`' measurement: render and whole-frame medians and means, and the rate.
fn report(times: &FrameTimes, viewer: &Viewer<'_>, args: &ViewArgs) {
    let warmup = if times.summary(WARMUP).is_some() {
        WARMUP
    } else {
        0
    };
    let Some((render, frame)) = times.summary(warmup) else {
        return;
    };
    let viewport = viewer.target.viewport();
    let threads = if viewer.implementation() == "fast" {
        format!(
            " ({} thread{})",
            args.threads,
            if args.threads == 1 { "" } else { "s" }
        )
    } else {
        String::new()
    };
    say(&format!(
        "{} {}x{}, {}{threads}, {}: {} frames (after {warmup} not counted): \
         render median {:.2} ms (mean {:.2}), whole frame median {:.2} ms (mean {:.2}) = {:.0} fps",
        args.scene.scene,
        viewport.width(),
        viewport.height(),
        viewer.implementation(),
        viewer.mode,
        frame.frames,
        render.median_ms,
        render.mean_ms,
        frame.median_ms,
        frame.mean_ms,
        frame.fps()
    ));
}
