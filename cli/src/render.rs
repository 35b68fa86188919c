//! `refrast render`: a built-in scene or a mesh file to a PNG, in any mode, through any
//! built-in rasterizer.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use refrast::pipeline::Framebuffer;
use refrast_render::Mode;

use crate::options::{Failure, SceneArgs, prepare, rasterizer};
use crate::say;

/// Arguments of `refrast render`.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// The scene, its size, camera, light and rasterizer.
    #[command(flatten)]
    scene: SceneArgs,
    /// Where to write the PNG [default: SCENE.png, or SCENE-MODE.png for a mode other than fill;
    /// with `--mode all`, the folder to write one picture per mode into].
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// What to draw: points, wire, fill, depth, normals, barycentric, overdraw, or all of them.
    #[arg(long, value_name = "MODE", default_value = "fill", value_parser = parse_modes)]
    mode: Modes,
    /// Samples per pixel (1, 2, 4, 8 or 16), each depth-tested and shaded on its own, then
    /// averaged into its pixel (a box filter); the rasterizer must declare the count (the
    /// reference declares them all). Points and wire modes draw at one sample.
    #[arg(long, value_name = "N", default_value = "1", value_parser = parse_samples)]
    samples: u8,
}

/// A sample count the contract knows: 1, 2, 4, 8 or 16.
fn parse_samples(s: &str) -> Result<u8, String> {
    s.parse::<u8>()
        .ok()
        .filter(|n| refrast::SAMPLE_COUNTS.contains(n))
        .ok_or_else(|| format!("{s} is not a sample count: use 1, 2, 4, 8 or 16"))
}

/// One mode, or every mode.
#[derive(Clone, Debug)]
pub struct Modes(Vec<Mode>);

fn parse_modes(s: &str) -> Result<Modes, String> {
    if s == "all" {
        return Ok(Modes(Mode::ALL.to_vec()));
    }
    s.parse::<Mode>()
        .map(|m| Modes(vec![m]))
        .map_err(|e| format!("{e}, all"))
}

/// Runs `refrast render`: 0 when every picture is written, 2 on bad input (an argument, a
/// file, a mesh, a texture), 1 when the rasterizer refuses the draw.
pub fn run(args: &RenderArgs) -> ExitCode {
    match render(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message, code)) => {
            eprintln!("error: {message}");
            ExitCode::from(code)
        }
    }
}

fn render(args: &RenderArgs) -> Result<(), Failure> {
    let prepared = prepare(&args.scene)?;
    let (setup, stem) = (&prepared.setup, &prepared.stem);
    let (width, height) = prepared.size;
    let name = args.scene.implementation.as_deref().unwrap_or("reference");
    let mut rasterizer = rasterizer(name, setup)?;
    let mut target = Framebuffer::new(width, height).map_err(|e| Failure(e.to_string(), 2))?;
    let modes = &args.mode.0;
    if modes.len() > 1
        && let Some(dir) = &args.output
    {
        std::fs::create_dir_all(dir)
            .map_err(|e| Failure(format!("could not create the folder {}: {e}", dir.display()), 2))?;
    }
    if setup.mesh.triangles.is_empty() && modes.iter().any(|m| m.uses_triangles()) {
        say(&format!(
            "note: {stem} has no triangles; only --mode points draws its vertices"
        ));
    }
    for &mode in modes {
        let job = prepared.job(mode, &prepared.camera, prepared.light, prepared.state);
        let start = Instant::now();
        let stats = refrast_render::render_multisampled(rasterizer.as_mut(), &job, args.samples, &mut target)
            .map_err(|e| Failure(format!("{name} refused the draw: {e}"), 1))?;
        let seconds = start.elapsed().as_secs_f64();
        let file = format!(
            "{stem}{}.png",
            if mode == Mode::Fill {
                String::new()
            } else {
                format!("-{mode}")
            }
        );
        let path = match (&args.output, modes.len()) {
            (Some(dir), n) if n > 1 => dir.join(file),
            (Some(path), _) => path.clone(),
            (None, _) => PathBuf::from(file),
        };
        refrast_render::output::save_png(&target, &path)
            .map_err(|e| Failure(format!("could not write {}: {e}", path.display()), 2))?;
        say(&format!(
            "wrote {} ({width}x{height}{}, {stem}, {mode}{}, {}: {} primitives, {} fragments, {} written, {:.3} s)",
            path.display(),
            if args.samples > 1 && mode.uses_triangles() {
                format!(" at {} samples", args.samples)
            } else {
                String::new()
            },
            if mode == Mode::Fill {
                format!(", shading {}", job.shading)
            } else {
                String::new()
            },
            name,
            stats.primitives,
            stats.fragments,
            stats.written,
            seconds
        ));
    }
    Ok(())
}
