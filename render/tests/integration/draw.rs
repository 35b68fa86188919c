//! Pictures through `refrast_render::render`: what each mode and shading must show, and that a
//! picture sees the faults the catalogue finds.

use glam::{Vec3, Vec4};
use refrast::pipeline::Framebuffer;
use refrast::{
    CompareOp, CullMode, Draw, DrawError, DrawState, Fragment, Profile, Rasterizer, Reference,
    ReferenceConfig,
};
use refrast_fast::contract::{Recording, check_pictures, ties, tolerance};
use refrast_render::scene::{self, Setup};
use refrast_render::{Job, Mode, Overrides, Sampling, Shading, Texture, mode::overdraw_color};
use refrast_zoo::mutant::{Bug, Mutant};

/// Renders a built-in scene at its size with `rasterizer`, with the scene's defaults.
fn picture(name: &str, mode: Mode, rasterizer: &mut dyn Rasterizer) -> Framebuffer {
    let setup = scene::scene(name).unwrap_or_else(|| panic!("no scene {name}"));
    picture_of(&setup, mode, setup.shading, None, rasterizer)
}

fn picture_of(
    setup: &Setup,
    mode: Mode,
    shading: Shading,
    texture: Option<&Texture>,
    rasterizer: &mut dyn Rasterizer,
) -> Framebuffer {
    let (w, h) = setup.size;
    let camera = setup.camera(w as f32 / h as f32, &Overrides::default()).unwrap();
    let job = Job {
        mesh: &setup.mesh,
        view_projection: camera.view_projection,
        eye: camera.eye,
        state: setup.state,
        mode,
        shading,
        light: setup.light(&camera),
        texture,
        sampling: Sampling::Nearest,
        clear: setup.clear,
    };
    let mut target = Framebuffer::new(w, h).unwrap();
    refrast_render::render(rasterizer, &job, &mut target).unwrap();
    target
}

#[test]
fn render_shaded_through_fast_is_render_through_the_reference_within_fasts_precision() {
    let mut fast = refrast_fast::Fast::with_threads(1);
    // Its rasterizing and the visibility buffer's shading spread over two threads.
    let mut two = refrast_fast::Fast::with_threads(2);
    let checker = Texture::checker(8, 8, Vec4::ONE, Vec4::new(0.2, 0.2, 0.25, 1.0));
    for name in [
        "room",
        "torus",
        "sphere",
        "aligned-plane",
        "clipped-torus",
        "floor",
        "lab000-depth",
    ] {
        let setup = scene::scene(name).unwrap();
        let (w, h) = setup.size;
        let camera = setup.camera(w as f32 / h as f32, &Overrides::default()).unwrap();
        // Without culling too: the torus's back faces then fail the depth test behind its front.
        // And GREATER, which no fragment passes against the clear value 1: overdraw counts all
        // the same.
        let mut greater = setup.state;
        greater.depth.compare = CompareOp::Greater;
        let states = [
            setup.state,
            DrawState {
                cull: CullMode::None,
                ..setup.state
            },
            greater,
        ];
        for (mode, state) in Mode::ALL.into_iter().flat_map(|m| states.map(|s| (m, s))) {
            let job = Job {
                mesh: &setup.mesh,
                view_projection: camera.view_projection,
                eye: camera.eye,
                state,
                mode,
                shading: setup.shading,
                light: setup.light(&camera),
                texture: (name == "floor").then_some(&checker),
                sampling: Sampling::Bilinear,
                clear: setup.clear,
            };
            let mut expected = Framebuffer::new(w, h).unwrap();
            let mut reference = Reference::default();
            let mut recording = Recording {
                inner: &mut reference,
                fragments: Vec::new(),
            };
            refrast_render::render(&mut recording, &job, &mut expected).unwrap();
            let mut shaded = Framebuffer::new(w, h).unwrap();
            refrast_render::render_shaded(&mut fast, &job, &mut shaded).unwrap();
            // `fast` covers the same samples with its own interpolation: within its precision,
            // except where two depths tie within it.
            let tied = ties(&recording.fragments, w, h, tolerance());
            check_pictures(
                (expected.color(), expected.depth()),
                (shaded.color(), shaded.depth()),
                &tied,
                tolerance(),
            )
            .unwrap_or_else(|e| panic!("{name}, {mode}, {:?}: {e}", state.cull));
            // Each pixel rasterized and shaded on its own: the same bits at any thread count.
            let mut threaded = Framebuffer::new(w, h).unwrap();
            refrast_render::render_shaded(&mut two, &job, &mut threaded).unwrap();
            let bits = |f: &Framebuffer| {
                (
                    f.color().to_vec(),
                    f.depth().iter().map(|d| d.to_bits()).collect::<Vec<_>>(),
                )
            };
            assert!(
                bits(&threaded) == bits(&shaded),
                "{name}, {mode}, {:?}: two threads differ from one",
                state.cull
            );
        }
    }
}

fn count(target: &Framebuffer, color: Option<[u8; 4]>) -> usize {
    target.color().iter().filter(|&&c| Some(c) == color).count()
}

#[test]
fn lab_scenes_are_the_reference_pipelines_pictures() {
    // The same five pictures as `refrast::scenes::render`, byte for byte, through the trait.
    for lab in refrast::scenes::SCENES {
        let setup = scene::scene(lab.name).unwrap();
        let mut reference = Reference::new(ReferenceConfig {
            traversal: setup.traversal,
            ..ReferenceConfig::default()
        });
        let ours = picture(lab.name, Mode::Fill, &mut reference);
        let theirs = refrast::scenes::render(lab.name, 640, 480).unwrap();
        assert!(ours.color() == theirs.color(), "{}", lab.name);
    }
}

#[test]
fn overdraw_shows_the_fill_rules_faults_on_shared_edges() {
    let mut reference = Reference::default();
    let once = overdraw_color(1);
    let twice = overdraw_color(2);
    let good = picture("aligned-plane", Mode::Overdraw, &mut reference);
    // Every pixel of the 512 × 512 picture is covered exactly once.
    assert_eq!(count(&good, once), 512 * 512);
    // 64 diagonals of 64 pixel centres each lie on two triangles' shared edge: inclusive edges
    // draw them twice, exclusive edges not at all.
    let mut inclusive: Box<dyn Rasterizer> = Box::new(Mutant::new(Bug::InclusiveEdges));
    let bad = picture("aligned-plane", Mode::Overdraw, inclusive.as_mut());
    assert_eq!(count(&bad, twice), 64 * 64);
    let mut exclusive: Box<dyn Rasterizer> = Box::new(Mutant::new(Bug::ExclusiveEdges));
    let cracked = picture("aligned-plane", Mode::Overdraw, exclusive.as_mut());
    assert_eq!(count(&cracked, once), 512 * 512 - 64 * 64);
    assert_eq!(count(&cracked, twice), 0);
}

#[test]
fn shadings_differ_where_they_should() {
    let setup = scene::scene("room").unwrap();
    let mut reference = Reference::default();
    let mut draw = |shading| picture_of(&setup, Mode::Fill, shading, None, &mut reference);
    let (none, flat, gouraud, phong) = (
        draw(Shading::None),
        draw(Shading::Flat),
        draw(Shading::Gouraud),
        draw(Shading::Phong),
    );
    // Unlit: the lab's colours as they are; the green floor is 0.15, 0.75, 0.15.
    let floor = none.pixel(250, 480).unwrap();
    assert_eq!(floor, [38, 191, 38, 255]);
    // Flat: one colour per triangle, so the ceiling's two triangles show at most two colours.
    let row: std::collections::BTreeSet<_> = (150..350).map(|x| flat.pixel(x, 10).unwrap()).collect();
    assert!(row.len() <= 2, "{row:?}");
    // Phong: the light, half a unit below the ceiling, falls off across it pixel by pixel.
    let row: std::collections::BTreeSet<_> = (150..350).map(|x| phong.pixel(x, 10).unwrap()).collect();
    assert!(row.len() > 5, "{row:?}");
    // Gouraud interpolates the corners' light, which differs from the light at the pixel.
    assert_ne!(gouraud.color(), phong.color());
    assert_ne!(flat.color(), gouraud.color());
}

#[test]
fn textures_are_perspective_correct() {
    // The plane tilted away, with a 2 × 2 checker: each cell's centre, projected, shows its
    // cell's colour; an affine interpolation bends the cells and the picture differs.
    let setup = scene::scene("clipped-plane").unwrap();
    let (a, b) = (Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 1.0, 1.0));
    let checker = Texture::checker(2, 1, a, b);
    let mut reference = Reference::default();
    let good = picture_of(&setup, Mode::Fill, Shading::None, Some(&checker), &mut reference);
    let mut affine: Box<dyn Rasterizer> = Box::new(Mutant::new(Bug::AffineAttributes));
    let bent = picture_of(&setup, Mode::Fill, Shading::None, Some(&checker), affine.as_mut());
    assert_ne!(good.color(), bent.color());
    let (w, h) = setup.size;
    let camera = setup.camera(w as f32 / h as f32, &Overrides::default()).unwrap();
    for v in setup.mesh.vertices.iter().filter(|v| {
        let f = (v.uv * 2.0).fract();
        (f - glam::Vec2::splat(0.5)).length() < 0.2
    }) {
        let clip = camera.view_projection * v.position.extend(1.0);
        if clip.w <= 0.5 {
            continue;
        }
        let ndc = clip.truncate() / clip.w;
        let (x, y) = ((ndc.x + 1.0) / 2.0 * w as f32, (1.0 - ndc.y) / 2.0 * h as f32);
        if !(1.0..w as f32 - 1.0).contains(&x) || !(1.0..h as f32 - 1.0).contains(&y) {
            continue;
        }
        let cell = (v.uv * 2.0).floor();
        let expected = if ((cell.x + cell.y) as u32).is_multiple_of(2) {
            a
        } else {
            b
        };
        let colour = good.pixel(x as u32, y as u32).unwrap();
        let vertex = refrast::pipeline::to_rgba8(v.color * expected);
        assert_eq!(colour, vertex, "uv {} at ({x}, {y})", v.uv);
    }
}

#[test]
fn depth_mode_is_brighter_nearer() {
    let mut reference = Reference::default();
    let depth = picture("room", Mode::Depth, &mut reference);
    // The near edge of the floor against the back wall: near is brighter.
    let near = depth.pixel(250, 495).unwrap()[0];
    let far = depth.pixel(250, 250).unwrap()[0];
    assert!(near > far, "{near} vs {far}");
    assert_eq!(depth.pixel(250, 495).unwrap(), [near, near, near, 255]);
}

#[test]
fn normals_and_barycentrics_are_colours() {
    let mut reference = Reference::default();
    let normals = picture("room", Mode::Normals, &mut reference);
    let bary = picture("room", Mode::Barycentric, &mut reference);
    // The floor's normal is ±y: green 255 or 0 with red and blue at 128.
    let floor = normals.pixel(250, 480).unwrap();
    assert!(
        floor[0].abs_diff(128) <= 1 && floor[2].abs_diff(128) <= 1 && floor[1].is_multiple_of(255),
        "{floor:?}"
    );
    // Barycentrics sum to one: the channels sum to 255 within rounding.
    for (x, y) in [(100, 100), (250, 480), (400, 300)] {
        let [r, g, b, _] = bary.pixel(x, y).unwrap();
        let sum = u32::from(r) + u32::from(g) + u32::from(b);
        assert!(sum.abs_diff(255) <= 2, "({x}, {y}): {r} {g} {b}");
    }
}

#[test]
fn points_and_wire_draw_vertices_and_edges() {
    let mut reference = Reference::default();
    let clear = Some(scene::scene("room").unwrap().clear);
    let points = picture("room", Mode::Points, &mut reference);
    let wire = picture("room", Mode::Wire, &mut reference);
    let fill = picture("room", Mode::Fill, &mut reference);
    let drawn = |t: &Framebuffer| t.color().len() - count(t, clear);
    // The room's 8 corners and the blocks' 16, some hidden behind others or coinciding.
    assert!((16..=24).contains(&drawn(&points)), "{}", drawn(&points));
    assert!(drawn(&wire) > 20 * drawn(&points) && drawn(&wire) < drawn(&fill) / 10);
}

/// A rasterizer that answers every draw with fragments outside the target and of primitives
/// the draw does not have.
struct Misbehaving;

impl Rasterizer for Misbehaving {
    fn profile(&self) -> Profile {
        Reference::default().profile()
    }

    fn rasterize(&mut self, _draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let f = |x, y, primitive| Fragment {
            x,
            y,
            sample: 0,
            primitive,
            depth: 0.5,
            barycentric: [f32::NAN, 1.0, 0.0],
            flat: None,
            screen_barycentric: None,
            front_facing: true,
        };
        Ok(vec![
            f(10_000, 0, 0),
            f(0, 10_000, 0),
            f(0, 0, 1_000_000),
            f(1, 1, 0),
        ])
    }
}

#[test]
fn a_misbehaving_rasterizer_cannot_crash_a_picture() {
    let target = picture("lab000-rgb", Mode::Fill, &mut Misbehaving);
    let clear = Some(refrast::scenes::CLEAR);
    assert_eq!(count(&target, clear), 640 * 480 - 1);
    let overdraw = picture("lab000-rgb", Mode::Overdraw, &mut Misbehaving);
    assert_eq!(count(&overdraw, overdraw_color(1)), 1);
    let _ = Vec3::ZERO;
}
