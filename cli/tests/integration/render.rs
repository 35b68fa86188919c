//! `refrast render`: every built-in scene and a PLY and an OBJ file in every mode, and a
//! one-line message with exit code 2 for each kind of bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const REFRAST: &str = env!("CARGO_BIN_EXE_refrast");

/// A scratch folder of this test's own.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("render").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render(args: &[&str]) -> Output {
    Command::new(REFRAST)
        .arg("render")
        .args(args)
        .output()
        .expect("refrast runs")
}

/// Asserts a refusal: exit code 2, and an error on stderr's first line containing `names`,
/// with no panic or backtrace anywhere.
fn refused(args: &[&str], names: &str) {
    let out = render(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    let first = stderr.lines().next().unwrap_or("");
    assert!(
        first.starts_with("error: ") && first.contains(names),
        "{args:?}: {stderr}"
    );
    assert!(
        !stderr.contains("panicked") && !stderr.contains("backtrace"),
        "{args:?}: {stderr}"
    );
}

/// The PNG at `path`, decoded.
/// The room drawn by `implementation` with `state`, which it does not declare: refused with
/// exit code 1 and a message saying so, and no file written at `path`.
fn refused_undeclared(path: &Path, implementation: &str, state: &[&str]) {
    let mut args = vec!["room", "--impl", implementation];
    args.extend_from_slice(state);
    args.extend(["-o", path.to_str().unwrap()]);
    let out = render(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("does not declare") && !path.exists(), "{stderr}");
}

fn png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// How many pixels differ from the scene's background.
fn drawn(image: &image::RgbaImage, scene: &str) -> usize {
    let background = if scene.starts_with("lab000") {
        [100, 100, 100, 255]
    } else if scene == "room" {
        [0, 0, 0, 255]
    } else {
        [40, 40, 48, 255]
    };
    image.pixels().filter(|p| p.0 != background).count()
}

const MODES: [&str; 7] = [
    "points",
    "wire",
    "fill",
    "depth",
    "normals",
    "barycentric",
    "overdraw",
];

/// Renders `scene` in every mode into a fresh folder and checks each picture was drawn.
fn every_mode(scene: &str, stem: &str, size: (u32, u32)) {
    let dir = scratch(stem);
    let out = render(&[scene, "--mode", "all", "-o", dir.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{scene}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    for mode in MODES {
        let file = if mode == "fill" {
            format!("{stem}.png")
        } else {
            format!("{stem}-{mode}.png")
        };
        let image = png(&dir.join(&file));
        assert_eq!(image.dimensions(), size, "{file}");
        assert!(drawn(&image, scene) > 0, "{file} is blank");
    }
}

#[test]
fn every_scene_renders_in_every_mode() {
    let out = Command::new(REFRAST).arg("scenes").output().unwrap();
    let listing = String::from_utf8(out.stdout).unwrap();
    let names: Vec<_> = listing
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(
        names.len() >= 16 && names.contains(&"room") && names.contains(&"clipped-torus"),
        "{names:?}"
    );
    for name in names {
        let size = match name {
            "room" => (500, 500),
            "aligned-plane" => (512, 512),
            _ => (640, 480),
        };
        every_mode(name, name, size);
    }
}

/// A cube as an ASCII PLY with per-vertex colours, one quad face per side.
const CUBE_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n\
property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 6\n\
property list uchar int vertex_indices\nend_header\n\
-1 -1 -1 255 0 0\n1 -1 -1 0 255 0\n1 1 -1 0 0 255\n-1 1 -1 255 255 0\n\
-1 -1 1 255 0 255\n1 -1 1 0 255 255\n1 1 1 255 255 255\n-1 1 1 40 40 40\n\
4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";

/// A textured, lit square as OBJ: positions, uv, normals, two triangles.
const SQUARE_OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
vn 0 0 -1\nf 1/1/1 3/3/1 2/2/1\nf 1/1/1 4/4/1 3/3/1\n";

#[test]
fn ply_and_obj_files_render_in_every_mode() {
    let dir = scratch("files");
    let ply = dir.join("cube.ply");
    let obj = dir.join("square.obj");
    std::fs::write(&ply, CUBE_PLY).unwrap();
    std::fs::write(&obj, SQUARE_OBJ).unwrap();
    every_mode(ply.to_str().unwrap(), "cube", (640, 480));
    every_mode(obj.to_str().unwrap(), "square", (640, 480));
    // The OBJ's uv carries a texture: the checkerboard shows both its colours.
    let out = render(&[
        obj.to_str().unwrap(),
        "--texture",
        "checker",
        "--shading",
        "none",
        "-o",
    ]);
    assert_eq!(out.status.code(), Some(2), "-o needs a value");
    let textured = dir.join("textured.png");
    let out = render(&[
        obj.to_str().unwrap(),
        "--texture",
        "checker",
        "--shading",
        "none",
        "--sampling",
        "nearest",
        "-o",
        textured.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let image = png(&textured);
    let colours: std::collections::BTreeSet<_> = image.pixels().map(|p| p.0).collect();
    assert!(
        colours.contains(&[255, 255, 255, 255]) && colours.contains(&[51, 51, 64, 255]),
        "{}",
        colours.len()
    );
}

/// `--scissor` draws only inside its rectangle, in every mode (wire and points too); a
/// rasterizer that does not declare a scissor refuses the draw (exit 1), and a malformed
/// rectangle is a usage error (exit 2).
#[test]
fn a_scissor_keeps_every_mode_inside_it() {
    let dir = scratch("scissor");
    for mode in ["fill", "wire", "points", "depth"] {
        let path = dir.join(format!("{mode}.png"));
        let out = render(&[
            "room",
            "--size",
            "160x120",
            "--mode",
            mode,
            "--scissor",
            "20,30,80,40",
            "-o",
            path.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{mode}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let image = png(&path);
        let outside = image
            .enumerate_pixels()
            .filter(|(x, y, p)| !((20..100).contains(x) && (30..70).contains(y)) && p.0 != [0, 0, 0, 255])
            .count();
        assert_eq!(outside, 0, "{mode}: pixels drawn outside the scissor");
        assert!(
            drawn(&image, "room") > 0,
            "{mode}: nothing drawn inside the scissor"
        );
    }
    refused_undeclared(&dir.join("fast.png"), "fast", &["--scissor", "20,30,80,40"]);
    refused(&["room", "--scissor", "1,2,3"], "is not a scissor");
}

/// `--sample-mask` keeps the samples of its set bits: at 4 samples, 0b0011 keeps two of each
/// pixel's four, so over the room's black clear every channel sums to about half the unmasked
/// picture's, and 0 draws nothing; at one sample only bit 0 counts. A rasterizer without a
/// sample mask refuses the draw (exit 1), and a malformed mask is a usage error (exit 2).
#[test]
fn a_sample_mask_keeps_the_samples_of_its_bits() {
    let dir = scratch("sample-mask");
    let light = |name: &str, extra: &[&str]| -> u64 {
        let path = dir.join(name);
        let mut args = vec!["room", "--size", "160x120"];
        args.extend_from_slice(extra);
        args.extend(["-o", path.to_str().unwrap()]);
        let out = render(&args);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        png(&path)
            .pixels()
            .map(|p| u64::from(p.0[0]) + u64::from(p.0[1]) + u64::from(p.0[2]))
            .sum()
    };
    let whole = light("whole.png", &["--samples", "4"]);
    let half = light("half.png", &["--samples", "4", "--sample-mask", "0b0011"]);
    assert!(whole > 0, "the unmasked room is black");
    let ratio = half as f64 / whole as f64;
    // Each kept sample is shaded as unmasked and each masked one is the black clear: the
    // box filter halves every pixel, up to its rounding to 8 bits.
    assert!(
        (0.48..=0.52).contains(&ratio),
        "masked to half the samples: {ratio}"
    );
    assert_eq!(light("none.png", &["--samples", "4", "--sample-mask", "0"]), 0);
    assert_eq!(
        light("one.png", &["--sample-mask", "0xfffffffe"]),
        0,
        "bit 0 clear at one sample"
    );
    assert_eq!(
        light("kept.png", &["--sample-mask", "1"]),
        light("plain.png", &[])
    );
    refused_undeclared(
        &dir.join("refused.png"),
        "restricted:sample-mask=none",
        &["--sample-mask", "0b0101"],
    );
    refused(&["room", "--sample-mask", "0b012"], "is not a sample mask");
    refused(&["room", "--sample-mask", "4294967296"], "is not a sample mask");
}

/// `--interpolation centroid` reads the checkered floor's texture once a pixel: at 4 samples
/// it draws the same pixels as at the sample but with fewer distinct colours (no pixel blends
/// two texels inside a triangle), and at one sample exactly the same picture. A rasterizer
/// without centroid refuses the draw (exit 1), and an unknown word is a usage error (exit 2).
#[test]
fn centroid_reads_the_texture_once_a_pixel() {
    let dir = scratch("centroid");
    let draw = |name: &str, extra: &[&str]| {
        let path = dir.join(name);
        let mut args = vec![
            "floor",
            "--size",
            "160x120",
            "--texture",
            "checker",
            "--sampling",
            "nearest",
        ];
        args.extend_from_slice(extra);
        args.extend(["-o", path.to_str().unwrap()]);
        let out = render(&args);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        png(&path)
    };
    let colours = |image: &image::RgbaImage| {
        image
            .pixels()
            .map(|p| p.0)
            .collect::<std::collections::BTreeSet<_>>()
            .len()
    };
    let sample = draw("sample.png", &["--samples", "4"]);
    let centroid = draw("centroid.png", &["--samples", "4", "--interpolation", "centroid"]);
    assert_ne!(sample, centroid);
    assert!(
        colours(&centroid) < colours(&sample),
        "{} against {}",
        colours(&centroid),
        colours(&sample)
    );
    assert_eq!(
        draw("one.png", &["--interpolation", "centroid"]),
        draw("plain.png", &[])
    );
    refused_undeclared(
        &dir.join("refused.png"),
        "restricted:centroid=none",
        &["--samples", "4", "--interpolation", "centroid"],
    );
    refused(&["floor", "--interpolation", "center"], "no interpolation named");
}

/// `--conservative over` draws every pixel a triangle touches, so the overdraw picture gains
/// pixels (shared edges drawn twice, as no tie rule applies) and `under` loses them; a
/// rasterizer without it refuses the draw (exit 1), an extra size beyond the declared one is
/// refused too, and a malformed mode is a usage error (exit 2).
#[test]
fn conservative_draws_the_pixels_touched_or_held() {
    let dir = scratch("conservative");
    let drawn = |name: &str, extra: &[&str]| -> usize {
        let path = dir.join(name);
        let mut args = vec!["star", "--size", "160x120", "--mode", "overdraw"];
        args.extend_from_slice(extra);
        args.extend(["-o", path.to_str().unwrap()]);
        let out = render(&args);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let clear = png(&path).get_pixel(0, 0).0;
        png(&path).pixels().filter(|p| p.0 != clear).count()
    };
    let plain = drawn("plain.png", &[]);
    let over = drawn("over.png", &["--conservative", "over"]);
    let grown = drawn("grown.png", &["--conservative", "over,1.5"]);
    let under = drawn("under.png", &["--conservative", "under"]);
    assert!(
        under < plain && plain < over && over < grown,
        "{under} {plain} {over} {grown}"
    );
    refused_undeclared(
        &dir.join("refused.png"),
        "restricted:conservative=none",
        &["--conservative", "over"],
    );
    let out = render(&[
        "room",
        "--impl",
        "restricted:conservative=over-only",
        "--conservative",
        "under",
        "-o",
        dir.join("x.png").to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    refused(&["star", "--conservative", "over,-1"], "no conservative mode");
}

/// `--depth-bias` moves the depth picture and nothing else: the same pixels drawn, each at
/// its depth plus the triangle's offset (a slope factor of −64 pulls the room's sloped walls
/// toward the eye; pushed away, a surface could reach the far plane and fail the depth test
/// against the clear, as it should); a rasterizer without depth bias refuses the draw (exit 1),
/// and a malformed bias is a usage error (exit 2).
#[test]
fn a_depth_bias_moves_depth_and_nothing_else() {
    let dir = scratch("bias");
    let draw = |name: &str, extra: &[&str]| {
        let path = dir.join(name);
        let mut args = vec![
            "room",
            "--size",
            "160x120",
            "--mode",
            "depth",
            "-o",
            path.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = render(&args);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        png(&path)
    };
    let plain = draw("plain.png", &[]);
    let biased = draw("biased.png", &["--depth-bias", "0,-64"]);
    let background = |p: &image::Rgba<u8>| p.0 == [0, 0, 0, 255];
    let moved = plain
        .pixels()
        .zip(biased.pixels())
        .filter(|(a, b)| {
            assert_eq!(
                background(a),
                background(b),
                "the bias changed which pixels are drawn"
            );
            a != b
        })
        .count();
    assert!(moved > 0, "a slope factor of −64 moved no pixel's depth");
    refused_undeclared(
        &dir.join("refused.png"),
        "restricted:depth-bias=none",
        &["--depth-bias", "0,64"],
    );
    refused(&["room", "--depth-bias", "1"], "is not a depth bias");
    refused(&["room", "--depth-bias", "1,NaN"], "is not a depth bias");
}

/// `--polygon-mode line` has the rasterizer draw each triangle's edges: fewer pixels than
/// filled; point mode its vertices, fewer still. A rasterizer without
/// polygon modes refuses the draw (exit 1), and an unknown mode is a usage error (exit 2).
#[test]
fn a_polygon_mode_draws_edges_or_vertices() {
    let dir = scratch("polygon-mode");
    let draw = |name: &str, extra: &[&str]| {
        let path = dir.join(name);
        let mut args = vec![
            "room",
            "--size",
            "160x120",
            "--mode",
            "fill",
            "-o",
            path.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = render(&args);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        png(&path)
    };
    let drawn = |image: &image::RgbaImage| image.pixels().filter(|p| p.0 != [0, 0, 0, 255]).count();
    let filled = draw("fill.png", &[]);
    let lines = draw("line.png", &["--polygon-mode", "line"]);
    let points = draw("point.png", &["--polygon-mode", "point"]);
    let (f, l, p) = (drawn(&filled), drawn(&lines), drawn(&points));
    assert!(0 < p && p < l && l < f, "points {p}, lines {l}, filled {f}");
    refused_undeclared(
        &dir.join("refused.png"),
        "restricted:polygon-mode=fill",
        &["--polygon-mode", "line"],
    );
    refused(&["room", "--polygon-mode", "wire"], "no polygon mode named");
}

#[test]
fn an_interrupted_or_failed_render_leaves_no_file() {
    let dir = scratch("atomic");
    let target = dir.join("room.png");
    // A refused draw (euc culls back faces only) writes nothing.
    let out = render(&["room", "--impl", "euc", "-o", target.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("euc refused the draw"));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    // A picture that is written leaves no temporary file beside it.
    assert!(render(&["room", "-o", target.to_str().unwrap()]).status.success());
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("room.png")]);
}

#[test]
fn bad_arguments_are_refused_with_one_line() {
    let dir = scratch("bad-arguments");
    let out = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    let o = out("x.png");
    refused(
        &["no-such-scene", "-o", &o],
        "no scene or mesh file named 'no-such-scene'",
    );
    refused(&["room", "--size", "0x10", "-o", &o], "'0x10' is not a size");
    refused(
        &["room", "--size", "99999x10", "-o", &o],
        "'99999x10' is not a size",
    );
    refused(&["room", "--size", "big", "-o", &o], "'big' is not a size");
    refused(&["room", "--mode", "lines", "-o", &o], "no mode named 'lines'");
    refused(
        &["room", "--shading", "toon", "-o", &o],
        "no shading named 'toon'",
    );
    refused(
        &["room", "--impl", "nope", "-o", &o],
        "no implementation named 'nope'",
    );
    refused(
        &["room", "--eye", "1,2", "-o", &o],
        "'1,2' is not three finite numbers",
    );
    refused(
        &["room", "--eye", "nan,0,0", "-o", &o],
        "is not three finite numbers",
    );
    refused(
        &["room", "--eye", "0,0,0", "--target", "0,0,0", "-o", &o],
        "--eye and --target are the same point",
    );
    refused(&["room", "--fov", "180", "-o", &o], "--fov 180 is out of range");
    refused(
        &["room", "--near", "5", "--far", "1", "-o", &o],
        "need 0 < near < far",
    );
    refused(&["room", "--near", "-1", "-o", &o], "need 0 < near < far");
    refused(
        &["room", "--ortho", "0", "-o", &o],
        "the window height must be positive",
    );
    refused(&["room", "--up", "0,0,0", "-o", &o], "--up must not be zero");
    refused(
        &["room", "--cull", "sideways", "-o", &o],
        "no culling named 'sideways'",
    );
    refused(&["room", "--attenuation", "0,0,0", "-o", &o], "not all zero");
    refused(&["room", "--specular", "-1", "-o", &o], "is negative");
    refused(&["room", "-o", &out("missing-folder/x.png")], "could not write");
    refused(
        &["room", "--texture", &out("no-such-texture.png"), "-o", &o],
        "could not read the texture",
    );
    let not_an_image = out("not-an-image.png");
    std::fs::write(&not_an_image, "this is text").unwrap();
    refused(
        &["room", "--texture", &not_an_image, "-o", &o],
        "could not read the texture",
    );
    assert!(!dir.join("x.png").exists());
}

#[test]
fn malformed_meshes_are_refused_with_one_line() {
    let dir = scratch("bad-meshes");
    let o = dir.join("x.png").to_str().unwrap().to_owned();
    let header = |vertices: u32, faces: u32| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\n\
             property float z\nelement face {faces}\nproperty list uchar int vertex_indices\nend_header\n"
        )
    };
    let cases = [
        ("truncated.ply", format!("{}0 0 0\n1 0 0\n", header(3, 1)), "PLY"),
        (
            "counts.ply",
            format!("{}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", header(3, 2)),
            "PLY",
        ),
        (
            "text.ply",
            format!("{}0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", header(3, 1)),
            "PLY line",
        ),
        (
            "index.ply",
            format!("{}0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", header(3, 1)),
            "refers to vertex 7",
        ),
        // ASCII PLY has no spelling of NaN; a number beyond f32 is infinite.
        (
            "nan.ply",
            format!("{}0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", header(3, 1)),
            "PLY line 11",
        ),
        (
            "inf.ply",
            format!("{}0 0 0\n1 1e39 0\n0 1 0\n3 0 1 2\n", header(3, 1)),
            "non-finite position",
        ),
        (
            "nan.obj",
            "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n".to_owned(),
            "non-finite position",
        ),
        (
            "huge.ply",
            format!("{}0 0 0\n", header(u32::MAX, 1)),
            "declares 4294967295",
        ),
        (
            "index.obj",
            "v 0 0 0\nv 1 0 0\nf 1 2 3\n".to_owned(),
            "OBJ line 3",
        ),
        (
            "text.obj",
            "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n".to_owned(),
            "OBJ line 2",
        ),
        ("empty.obj", String::new(), "no vertices"),
        (
            "mesh.stl",
            "solid".to_owned(),
            "unknown mesh format; the supported extensions are .ply and .obj",
        ),
    ];
    for (name, text, names) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        refused(&[path.to_str().unwrap(), "-o", &o], names);
    }
    refused(
        &[dir.join("missing.ply").to_str().unwrap(), "-o", &o],
        "missing.ply",
    );
    assert!(!dir.join("x.png").exists());
}

#[test]
fn the_documented_render_commands_run() {
    // The `render` commands of the README and of docs/render.md, whose paths are relative to
    // the repository root, where the pages say to run them.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let pages = ["README.md", "docs/render.md"].map(|page| std::fs::read_to_string(root.join(page)).unwrap());
    let commands: Vec<_> = pages
        .iter()
        .flat_map(|page| page.lines())
        .filter_map(|l| l.strip_prefix("cargo run --release -- render "))
        .map(|l| l.split('#').next().unwrap().trim())
        .collect();
    assert!(commands.len() >= 5, "{commands:?}");
    // Run where the pages' root-relative paths resolve (a copy of what they name, under a
    // folder of the test's own, as the repository root), writing into that folder.
    let dir = scratch("readme");
    let data = dir.join("render/tests/data");
    std::fs::create_dir_all(&data).unwrap();
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../render/tests/data/cube.ply");
    std::fs::copy(source, data.join("cube.ply")).unwrap();
    for command in commands {
        let out = Command::new(REFRAST)
            .current_dir(&dir)
            .arg("render")
            .args(command.split_whitespace())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "render {command}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    assert!(dir.join("room.png").exists() && dir.join("pictures/room-overdraw.png").exists());
}

#[test]
fn mesa_draws_the_scenes_coverage_as_the_reference_does() {
    // The GPU drivers through wgpu: the same fragments per pixel in overdraw, pixel for pixel.
    // Without Mesa this says so and passes, unless REFRAST_REQUIRE_DRIVERS=1 (set by .ci/run).
    let dir = scratch("mesa");
    for scene in ["room", "torus", "clipped-star"] {
        let path = |i: &str| dir.join(format!("{scene}-{i}.png"));
        let reference = path("reference");
        assert!(
            render(&[scene, "--mode", "overdraw", "-o", reference.to_str().unwrap()])
                .status
                .success()
        );
        for driver in ["lavapipe", "llvmpipe"] {
            let out = render(&[
                scene,
                "--mode",
                "overdraw",
                "--impl",
                driver,
                "-o",
                path(driver).to_str().unwrap(),
            ]);
            let stderr = String::from_utf8_lossy(&out.stderr);
            if stderr.contains("is not available here") {
                assert!(
                    std::env::var("REFRAST_REQUIRE_DRIVERS").as_deref() != Ok("1"),
                    "{driver} is missing, and REFRAST_REQUIRE_DRIVERS=1 requires it: {stderr}"
                );
                eprintln!("SKIPPED: {stderr}");
                continue;
            }
            assert!(out.status.success(), "{scene} through {driver}: {stderr}");
            assert!(
                png(&path(driver)) == png(&reference),
                "{scene}: {driver}'s overdraw differs"
            );
        }
    }
}

#[test]
fn the_documented_pictures_are_committed() {
    // Every picture docs/render.md shows (`pictures/…`, relative to docs/) is in docs/pictures/
    // (`*.png` is ignored by git elsewhere).
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let page = std::fs::read_to_string(root.join("docs/render.md")).unwrap();
    let pictures: Vec<_> = page
        .split("](pictures/")
        .skip(1)
        .filter_map(|rest| rest.split_once(')').map(|(name, _)| name))
        .collect();
    assert!(pictures.len() >= 10, "{pictures:?}");
    for name in pictures {
        let image = png(&root.join("docs/pictures").join(name));
        assert!(drawn(&image, "") > 0, "{name} is blank");
    }
}

#[test]
fn an_implementations_own_depth_test_draws_its_picture() {
    // Seed 003's painter draws `overlaps` in its painting order, which the reference's depth
    // buffer does not give; through refrast's replay of its fragments the two would be equal.
    let dir = scratch("own-depth-test");
    let picture = |name: &str| {
        let path = dir.join(format!("{name}.png"));
        let out = render(&[
            "overlaps",
            "--impl",
            name,
            "--size",
            "240x120",
            "-o",
            path.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        png(&path)
    };
    let (reference, painter) = (picture("reference"), picture("lab003-painter"));
    let differ = reference
        .pixels()
        .zip(painter.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(differ > 50, "{differ} pixels differ");
    assert_eq!(
        drawn(&reference, "overlaps"),
        drawn(&painter, "overlaps"),
        "the same coverage"
    );
}
