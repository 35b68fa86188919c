//! `refrast render`: a built-in scene or a mesh file to a PNG, in any mode, through any
//! built-in rasterizer.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use glam::Vec3;
use refrast::pipeline::Framebuffer;
use refrast::{CullMode, FrontFace, MAX_VIEWPORT, Rasterizer, Reference, ReferenceConfig};
use refrast_render::scene::{self, Setup};
use refrast_render::{Job, Mode, Overrides, Sampling, Shading, Texture, load};

use crate::{find_builtin, say};

/// Arguments of `refrast render`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A built-in scene (see `refrast scenes`) or a mesh file (.ply or .obj).
    scene: String,
    /// Where to write the PNG [default: SCENE.png, or SCENE-MODE.png for a mode other than fill;
    /// with `--mode all`, the folder to write one picture per mode into].
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Picture size, WIDTHxHEIGHT, each 1..=16384 [default: the scene's, 640x480 for most].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// What to draw: points, wire, fill, depth, normals, barycentric, overdraw, or all of them.
    #[arg(long, value_name = "MODE", default_value = "fill", value_parser = parse_modes)]
    mode: Modes,
    /// Lighting: none (vertex colours), flat, gouraud or phong [default: the scene's].
    #[arg(long, value_name = "SHADING", value_parser = |s: &str| s.parse::<Shading>())]
    shading: Option<Shading>,
    /// The rasterizer that draws the triangles (see `refrast impls`): mutants and course labs
    /// show their faults; points and lines are always drawn by refrast's line rasterizer.
    #[arg(long = "impl", value_name = "NAME", default_value = "reference")]
    implementation: String,
    /// Camera position, X,Y,Z [default: the scene's, or framed to show the whole mesh].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    eye: Option<Vec3>,
    /// The point the camera looks at, X,Y,Z [default: the scene's, or the mesh's centre].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    target: Option<Vec3>,
    /// Which way is up, X,Y,Z [default: 0,1,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    up: Option<Vec3>,
    /// Vertical field of view in degrees.
    #[arg(long, value_name = "DEGREES", value_parser = parse_finite)]
    fov: Option<f32>,
    /// Near plane distance.
    #[arg(long, value_name = "D", value_parser = parse_finite)]
    near: Option<f32>,
    /// Far plane distance.
    #[arg(long, value_name = "D", value_parser = parse_finite)]
    far: Option<f32>,
    /// Orthographic projection, HEIGHT world units tall [default height: what the perspective
    /// view shows at the target].
    #[arg(long, value_name = "HEIGHT", num_args = 0..=1, value_parser = parse_finite)]
    ortho: Option<Option<f32>>,
    /// Discard none, back or front faces [default: the scene's].
    #[arg(long, value_name = "FACES", value_parser = parse_cull)]
    cull: Option<CullMode>,
    /// Which winding faces the viewer: ccw or cw.
    #[arg(long, value_name = "WINDING", default_value = "ccw", value_parser = parse_front_face)]
    front_face: FrontFace,
    /// Light position, X,Y,Z [default: the scene's light, or a headlight above the eye].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    light: Option<Vec3>,
    /// Ambient light, 0..=1 and beyond.
    #[arg(long, value_name = "A", value_parser = parse_non_negative)]
    ambient: Option<f32>,
    /// Specular reflectance k_s (0 for no highlight).
    #[arg(long, value_name = "KS", value_parser = parse_non_negative)]
    specular: Option<f32>,
    /// Specular exponent.
    #[arg(long, value_name = "N", value_parser = parse_non_negative)]
    shininess: Option<f32>,
    /// Attenuation: the light is divided by C + L·d + Q·d², given as C,L,Q.
    #[arg(long, value_name = "C,L,Q", value_parser = parse_attenuation)]
    attenuation: Option<[f32; 3]>,
    /// Blinn-Phong highlights (the half vector) instead of Phong's reflected vector.
    #[arg(long)]
    blinn: bool,
    /// A texture multiplied into the colour at perspective-correct uv: a PNG or JPEG file, or
    /// `checker` for a built-in checkerboard.
    #[arg(long, value_name = "FILE|checker")]
    texture: Option<String>,
    /// Texture sampling: nearest or bilinear.
    #[arg(long, value_name = "SAMPLING", default_value = "bilinear", value_parser = |s: &str| s.parse::<Sampling>())]
    sampling: Sampling,
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

/// `WIDTHxHEIGHT`, each side within what a viewport may be.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{s}' is not a size; give WIDTHxHEIGHT, e.g. 640x480, each 1..={MAX_VIEWPORT}");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h) = (
        w.trim().parse::<u32>().map_err(|_| bad())?,
        h.trim().parse::<u32>().map_err(|_| bad())?,
    );
    if !(1..=MAX_VIEWPORT).contains(&w) || !(1..=MAX_VIEWPORT).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

/// A finite number.
fn parse_finite(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{s}' is not a finite number")),
    }
}

/// A finite number ≥ 0.
fn parse_non_negative(s: &str) -> Result<f32, String> {
    parse_finite(s).and_then(|v| {
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(format!("'{s}' is negative; give a number ≥ 0"))
        }
    })
}

/// Three finite numbers separated by commas.
fn parse_three(s: &str) -> Result<[f32; 3], String> {
    let parts: Vec<_> = s.split(',').map(parse_finite).collect();
    match parts.as_slice() {
        [Ok(x), Ok(y), Ok(z)] => Ok([*x, *y, *z]),
        _ => Err(format!(
            "'{s}' is not three finite numbers separated by commas, e.g. 0,1.5,-3"
        )),
    }
}

fn parse_vec3(s: &str) -> Result<Vec3, String> {
    parse_three(s).map(Vec3::from)
}

fn parse_attenuation(s: &str) -> Result<[f32; 3], String> {
    let a = parse_three(s)?;
    if a.iter().any(|&v| v < 0.0) || a == [0.0; 3] {
        return Err(format!(
            "'{s}': give C,L,Q ≥ 0, not all zero (1,0,0 is no fall-off)"
        ));
    }
    Ok(a)
}

fn parse_cull(s: &str) -> Result<CullMode, String> {
    match s {
        "none" => Ok(CullMode::None),
        "back" => Ok(CullMode::Back),
        "front" => Ok(CullMode::Front),
        _ => Err(format!("no culling named '{s}'; give none, back or front")),
    }
}

fn parse_front_face(s: &str) -> Result<FrontFace, String> {
    match s {
        "ccw" => Ok(FrontFace::CounterClockwise),
        "cw" => Ok(FrontFace::Clockwise),
        _ => Err(format!("no winding named '{s}'; give ccw or cw")),
    }
}

/// A message for the user and the exit code that goes with it.
struct Failure(String, u8);

/// Runs `refrast render`: 0 when every picture is written, 2 on bad input (an argument, a
/// file, a mesh, a texture), 1 when the rasterizer refuses the draw.
pub fn run(args: &Args) -> ExitCode {
    match render(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message, code)) => {
            eprintln!("error: {message}");
            ExitCode::from(code)
        }
    }
}

/// The scene named, or the mesh file at that path.
fn setup(name: &str) -> Result<(Setup, String), Failure> {
    if let Some(setup) = scene::scene(name) {
        return Ok((setup, name.to_owned()));
    }
    let path = Path::new(name);
    let is_mesh = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ply") || e.eq_ignore_ascii_case("obj"));
    if !is_mesh && !path.exists() {
        let names: Vec<_> = scene::scenes().iter().map(|s| s.name).collect();
        return Err(Failure(
            format!(
                "no scene or mesh file named '{name}'; the scenes are: {}; files end in .ply or .obj",
                names.join(", ")
            ),
            2,
        ));
    }
    let loaded = load::load(path).map_err(|e| Failure(e.to_string(), 2))?;
    let stem = path
        .file_stem()
        .map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
    Ok((Setup::from_loaded(loaded), stem))
}

/// The rasterizer called `name`; the reference walks pixels as the scene's lab step does.
fn rasterizer(name: &str, setup: &Setup) -> Result<Box<dyn Rasterizer>, Failure> {
    if name == "reference" {
        return Ok(Box::new(Reference::new(ReferenceConfig {
            traversal: setup.traversal,
            ..ReferenceConfig::default()
        })));
    }
    let b = find_builtin(name).map_err(|e| Failure(e, 2))?;
    b.build()
        .map_err(|why| Failure(format!("{name} is not available here: {why}"), 2))
}

fn render(args: &Args) -> Result<(), Failure> {
    let (setup, stem) = setup(&args.scene)?;
    let (width, height) = args.size.unwrap_or(setup.size);
    let overrides = Overrides {
        eye: args.eye,
        target: args.target,
        up: args.up,
        fov_y_degrees: args.fov,
        near: args.near,
        far: args.far,
        ortho: args.ortho,
    };
    let camera = setup
        .camera(width as f32 / height as f32, &overrides)
        .map_err(|e| Failure(e.to_string(), 2))?;
    let texture = match args.texture.as_deref() {
        None => None,
        Some("checker") => Some(Texture::checker(
            8,
            8,
            glam::Vec4::ONE,
            glam::Vec4::new(0.2, 0.2, 0.25, 1.0),
        )),
        Some(file) => Some(Texture::open(Path::new(file)).map_err(|e| Failure(e.to_string(), 2))?),
    };
    let mut light = setup.light(&camera);
    light.position = args.light.unwrap_or(light.position);
    light.ambient = args.ambient.map_or(light.ambient, Vec3::splat);
    light.specular = args.specular.unwrap_or(light.specular);
    light.shininess = args.shininess.unwrap_or(light.shininess);
    light.attenuation = args.attenuation.unwrap_or(light.attenuation);
    light.blinn |= args.blinn;
    let mut state = setup.state;
    state.cull = args.cull.unwrap_or(state.cull);
    state.front_face = args.front_face;
    let mut rasterizer = rasterizer(&args.implementation, &setup)?;
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
        let job = Job {
            mesh: &setup.mesh,
            view_projection: camera.view_projection,
            eye: camera.eye,
            state,
            mode,
            shading: args.shading.unwrap_or(setup.shading),
            light,
            texture: texture.as_ref(),
            sampling: args.sampling,
            clear: setup.clear,
        };
        let start = Instant::now();
        let stats = refrast_render::render(rasterizer.as_mut(), &job, &mut target)
            .map_err(|e| Failure(format!("{} refused the draw: {e}", args.implementation), 1))?;
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
            "wrote {} ({width}x{height}, {stem}, {mode}{}, {}: {} primitives, {} fragments, {} pixels, {:.3} s)",
            path.display(),
            if mode == Mode::Fill {
                format!(", shading {}", job.shading)
            } else {
                String::new()
            },
            args.implementation,
            stats.primitives,
            stats.fragments,
            stats.written,
            seconds
        ));
    }
    Ok(())
}
