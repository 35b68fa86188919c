//! What `refrast render` and `refrast view` share: the options that choose a scene, its size,
//! camera, light and rasterizer, and the draw they describe, so both commands read them alike.

use std::path::Path;

use glam::Vec3;
use refrast::{
    Conservative, CullMode, DepthBias, DrawState, FrontFace, Interpolation, MAX_VIEWPORT, PolygonMode,
    Rasterizer, Reference, ReferenceConfig, Scissor,
};
use refrast_render::scene::{self, Framed, Setup};
use refrast_render::{Job, Light, Mode, Overrides, Sampling, Shading, Texture, load};

/// The options of a scene and its draw, flattened into `render`'s and `view`'s arguments.
#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    /// A built-in scene (see `refrast scenes`) or a mesh file (.ply or .obj).
    pub scene: String,
    /// Picture size, WIDTHxHEIGHT, each 1..=16384 [default: the scene's, 640x480 for most].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Lighting: none (vertex colours), flat, gouraud or phong [default: the scene's].
    #[arg(long, value_name = "SHADING", value_parser = |s: &str| s.parse::<Shading>())]
    pub shading: Option<Shading>,
    /// The rasterizer that draws the triangles (see `refrast impls`): mutants and course labs
    /// show their faults; points and lines are always drawn by refrast's line rasterizer
    /// [default: reference for render, fast for view].
    #[arg(long = "impl", value_name = "NAME")]
    pub implementation: Option<String>,
    /// Camera position, X,Y,Z [default: the scene's, or framed to show the whole mesh].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<Vec3>,
    /// The point the camera looks at, X,Y,Z [default: the scene's, or the mesh's centre].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<Vec3>,
    /// Which way is up, X,Y,Z [default: 0,1,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: Option<Vec3>,
    /// Vertical field of view in degrees.
    #[arg(long, value_name = "DEGREES", value_parser = parse_finite)]
    pub fov: Option<f32>,
    /// Near plane distance.
    #[arg(long, value_name = "D", value_parser = parse_finite)]
    pub near: Option<f32>,
    /// Far plane distance.
    #[arg(long, value_name = "D", value_parser = parse_finite)]
    pub far: Option<f32>,
    /// Orthographic projection, HEIGHT world units tall [default height: what the perspective
    /// view shows at the target].
    #[arg(long, value_name = "HEIGHT", num_args = 0..=1, value_parser = parse_finite)]
    pub ortho: Option<Option<f32>>,
    /// Discard none, back, front or front-and-back faces (the last draws no triangle; points
    /// and wire are never culled) [default: the scene's].
    #[arg(long, value_name = "FACES", value_parser = parse_cull)]
    pub cull: Option<CullMode>,
    /// Which winding faces the viewer: ccw or cw.
    #[arg(long, value_name = "WINDING", default_value = "ccw", value_parser = parse_front_face)]
    pub front_face: FrontFace,
    /// Draw only inside this rectangle of pixels, X,Y,WIDTH,HEIGHT from the top-left corner
    /// (the scissor test); the rasterizer must declare a scissor (the reference does).
    #[arg(long, value_name = "X,Y,W,H", value_parser = parse_scissor)]
    pub scissor: Option<Scissor>,
    /// Keep only the samples whose bit is set in MASK (the sample mask test: bit i keeps sample
    /// i of every pixel, bit 0 at one sample), in decimal, 0x hex or 0b binary: with --samples
    /// 4, 0b0101 keeps samples 0 and 2, so edges and the whole picture draw at half coverage;
    /// the rasterizer must declare a sample mask (the reference does).
    #[arg(long, value_name = "MASK", value_parser = parse_sample_mask)]
    pub sample_mask: Option<u32>,
    /// Where a triangle's fragments take their barycentrics at several samples: sample (each
    /// at its own sample) or centroid (one location a pixel: its centre where the triangle
    /// covers every sample, else its first covered sample the mask keeps); `--mode barycentric`
    /// shows the difference along edges. The rasterizer must declare centroid (the reference
    /// does).
    #[arg(long, value_name = "AT", default_value = "sample", value_parser = parse_interpolation)]
    pub interpolation: Interpolation,
    /// Draw triangles conservatively: `over` (every pixel a triangle touches, all its
    /// samples), `over,EXTRA` (the triangle grown by EXTRA pixels first) or `under` (only
    /// pixels wholly inside); `--mode overdraw` shows shared edges drawn twice, as no tie rule
    /// applies. The rasterizer must declare it (the reference does).
    #[arg(long, value_name = "MODE", value_parser = parse_conservative)]
    pub conservative: Option<Conservative>,
    /// Offset each triangle's depth by CONSTANT units of its depth format's resolution plus
    /// SLOPE times its depth slope, at most CLAMP from where it was (0 or absent: no clamp);
    /// the rasterizer must declare depth bias (the reference does). Lines and points are not
    /// biased.
    #[arg(long, value_name = "CONSTANT,SLOPE[,CLAMP]", value_parser = parse_depth_bias, allow_hyphen_values = true)]
    pub depth_bias: Option<DepthBias>,
    /// How the rasterizer draws triangles: fill, line (each triangle's edges, culled and faced
    /// as the triangle) or point (its vertices); the rasterizer must declare line or point
    /// mode (the reference does). Unlike `--mode wire`, which draws the mesh's edges with
    /// refrast's own line rasterizer, this asks the rasterizer itself.
    #[arg(long, value_name = "MODE", default_value = "fill", value_parser = parse_polygon_mode)]
    pub polygon_mode: PolygonMode,
    /// Light position, X,Y,Z [default: the scene's light, or a headlight above the eye].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// Ambient light, 0..=1 and beyond.
    #[arg(long, value_name = "A", value_parser = parse_non_negative)]
    pub ambient: Option<f32>,
    /// Specular reflectance k_s (0 for no highlight).
    #[arg(long, value_name = "KS", value_parser = parse_non_negative)]
    pub specular: Option<f32>,
    /// Specular exponent.
    #[arg(long, value_name = "N", value_parser = parse_non_negative)]
    pub shininess: Option<f32>,
    /// Attenuation: the light is divided by C + L·d + Q·d², given as C,L,Q.
    #[arg(long, value_name = "C,L,Q", value_parser = parse_attenuation)]
    pub attenuation: Option<[f32; 3]>,
    /// Blinn-Phong highlights (the half vector) instead of Phong's reflected vector.
    #[arg(long)]
    pub blinn: bool,
    /// A texture multiplied into the colour at perspective-correct uv: a PNG or JPEG file, or
    /// `checker` for a built-in checkerboard.
    #[arg(long, value_name = "FILE|checker")]
    pub texture: Option<String>,
    /// Texture sampling: nearest or bilinear.
    #[arg(long, value_name = "SAMPLING", default_value = "bilinear", value_parser = |s: &str| s.parse::<Sampling>())]
    pub sampling: Sampling,
}

/// A message for the user and the exit code that goes with it.
#[derive(Debug)]
pub struct Failure(pub String, pub u8);

/// A scene with the command line's choices applied: everything a [`Job`] needs but the mode.
pub struct Prepared {
    /// The scene as built, before the options.
    pub setup: Setup,
    /// The scene's name, or the mesh file's stem: what output files are named after.
    pub stem: String,
    /// The picture size.
    pub size: (u32, u32),
    /// The camera options given.
    pub overrides: Overrides,
    /// The camera for `size`.
    pub camera: Framed,
    /// The light, with the options applied.
    pub light: Light,
    /// Whether the light is the headlight that follows the eye (no scene light, no `--light`).
    pub headlight: bool,
    /// Culling, facing, depth test and clipping.
    pub state: DrawState,
    /// The shading.
    pub shading: Shading,
    /// The texture, if any.
    pub texture: Option<Texture>,
    /// How the texture is sampled.
    pub sampling: Sampling,
}

impl Prepared {
    /// The draw of this scene in `mode` as seen by `camera` under `light`.
    #[must_use]
    pub fn job(&self, mode: Mode, camera: &Framed, light: Light, state: DrawState) -> Job<'_> {
        Job {
            mesh: &self.setup.mesh,
            view_projection: camera.view_projection,
            eye: camera.eye,
            state,
            mode,
            shading: self.shading,
            light,
            texture: self.texture.as_ref(),
            sampling: self.sampling,
            clear: self.setup.clear,
        }
    }
}

/// Builds the scene or mesh that `args` names and applies every option to it; a bad option,
/// file, mesh or texture is a [`Failure`] with exit code 2.
pub fn prepare(args: &SceneArgs) -> Result<Prepared, Failure> {
    let (setup, stem) = setup(&args.scene)?;
    let size = args.size.unwrap_or(setup.size);
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
        .camera(size.0 as f32 / size.1 as f32, &overrides)
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
    state.scissor = args.scissor;
    state.sample_mask = args.sample_mask.unwrap_or(DrawState::ALL_SAMPLES);
    state.interpolation = args.interpolation;
    state.conservative = args.conservative;
    state.depth_bias = args.depth_bias;
    state.polygon_mode = args.polygon_mode;
    Ok(Prepared {
        headlight: setup.light.is_none() && args.light.is_none(),
        shading: args.shading.unwrap_or(setup.shading),
        setup,
        stem,
        size,
        overrides,
        camera,
        light,
        state,
        texture,
        sampling: args.sampling,
    })
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
pub fn rasterizer(name: &str, setup: &Setup) -> Result<Box<dyn Rasterizer>, Failure> {
    if name == "reference" {
        return Ok(Box::new(Reference::new(ReferenceConfig {
            traversal: setup.traversal,
            ..ReferenceConfig::default()
        })));
    }
    let b = refrast_registry::find(name).map_err(|e| Failure(e, 2))?;
    b.build()
        .map_err(|why| Failure(format!("{name} is not available here: {why}"), 2))
}

/// A 32-bit mask in decimal, `0x` hexadecimal or `0b` binary.
fn parse_sample_mask(s: &str) -> Result<u32, String> {
    let t = s.trim();
    let parsed = if let Some(hex) = t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
        u32::from_str_radix(hex, 16)
    } else if let Some(bits) = t.strip_prefix("0b").or_else(|| t.strip_prefix("0B")) {
        u32::from_str_radix(bits, 2)
    } else {
        t.parse::<u32>()
    };
    parsed.map_err(|_| {
        format!(
            "'{s}' is not a sample mask; give 32 bits, bit i keeping sample i, in decimal, 0x hex or 0b binary, e.g. 0b0101"
        )
    })
}

/// `X,Y,WIDTH,HEIGHT`: four whole numbers of pixels.
fn parse_scissor(s: &str) -> Result<Scissor, String> {
    let bad = || {
        format!(
            "'{s}' is not a scissor; give X,Y,WIDTH,HEIGHT in pixels from the top-left corner, e.g. 10,10,100,50"
        )
    };
    let v: Vec<u32> = s
        .split(',')
        .map(|n| n.trim().parse::<u32>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x, y, width, height] => Ok(Scissor { x, y, width, height }),
        _ => Err(bad()),
    }
}

/// `CONSTANT,SLOPE` or `CONSTANT,SLOPE,CLAMP`: finite numbers.
fn parse_depth_bias(s: &str) -> Result<DepthBias, String> {
    let bad = || {
        format!(
            "'{s}' is not a depth bias; give CONSTANT,SLOPE or CONSTANT,SLOPE,CLAMP, finite numbers, e.g. 1000,1.5 or -4,-2,0.001"
        )
    };
    let v: Vec<f32> = s
        .split(',')
        .map(|n| {
            n.trim()
                .parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(bad)
        })
        .collect::<Result<_, _>>()?;
    match v[..] {
        [constant, slope] => Ok(DepthBias {
            constant,
            slope,
            clamp: 0.0,
        }),
        [constant, slope, clamp] => Ok(DepthBias {
            constant,
            slope,
            clamp,
        }),
        _ => Err(bad()),
    }
}

/// `WIDTHxHEIGHT`, each side within what a viewport may be.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
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
        "front-and-back" => Ok(CullMode::FrontAndBack),
        _ => Err(format!(
            "no culling named '{s}'; give none, back, front or front-and-back"
        )),
    }
}

fn parse_polygon_mode(s: &str) -> Result<PolygonMode, String> {
    PolygonMode::from_name(s).ok_or_else(|| format!("no polygon mode named '{s}'; give fill, line or point"))
}

fn parse_conservative(s: &str) -> Result<Conservative, String> {
    let words = if s == "over" { "over,0" } else { s };
    Conservative::from_words(words).ok_or_else(|| {
        format!("'{s}' is no conservative mode; give over, over,EXTRA (pixels, 0 or more) or under")
    })
}

fn parse_interpolation(s: &str) -> Result<Interpolation, String> {
    Interpolation::from_name(s)
        .ok_or_else(|| format!("no interpolation named '{s}'; give sample or centroid"))
}

fn parse_front_face(s: &str) -> Result<FrontFace, String> {
    match s {
        "ccw" => Ok(FrontFace::CounterClockwise),
        "cw" => Ok(FrontFace::Clockwise),
        _ => Err(format!("no winding named '{s}'; give ccw or cw")),
    }
}
