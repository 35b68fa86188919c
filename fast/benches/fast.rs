//! `fast` at 1920×1080 with depth and colour, against the reference and the scalar baseline in
//! the same run, at each thread count of `REFRAST_BENCH_THREADS` (a comma-separated list;
//! by default 1, 2 and the machine's parallelism): rows `fast_Nt` and `fast_resolve_Nt`.
//!
//! Scenes (docs/performance.md gives their timings, against `fast`'s targets): 100 000
//! triangles of about 10 px, 10 000 of about 500 px, 1 000 of about 50 000 px (the shared
//! workload of `benches/reference.rs`), and a torus of 1 M triangles seen in perspective.
//! Every implementation clears, depth-tests LESS and writes one colour per pixel; the reference
//! and `fast` interpolate the vertex colour perspective-correctly.
//! `scripts/bench_fast.py` prints medians, Mtri/s, Mpix/s and ratios.
//!
//! Where Mesa's lavapipe opens (`mesa-vulkan-drivers`), the same draws go through it in the
//! same run: `lavapipe` is its drawing time (`Gpu::resolve_timed`, reading back excluded) of a
//! depth test and a primitive-id target, which `fast_resolve_Nt` also times for `fast`
//! (`Rasterizer::resolve`). lavapipe runs as many threads as the machine has cores, or
//! `LP_NUM_THREADS`, which Mesa reads once a process: with it set, the row is `lavapipe_Nt`
//! (`scripts/bench_fast.py --threads` runs one process per count).
//! `REFRAST_BENCH_DRIVER=swiftshader` (with `VK_ICD_FILENAMES` on Chromium's ICD) times
//! SwiftShader instead, as `swiftshader`.

use std::f32::consts::TAU;
use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{Mat4, Vec3, Vec4};
use refrast::camera::{Camera, Projection};
use refrast::pipeline::{Framebuffer, Mesh, Renderer, Vertex, to_rgba8};
use refrast::{Draw, Fragment, Rasterizer, Reference};
use refrast_fast::Fast;
use refrast_fast::contract::{check_pictures, ties, tolerance};
use refrast_wgpu::{Driver, Gpu};

#[path = "../../benches/workload/baseline.rs"]
mod baseline;
#[path = "../../benches/workload/mesh.rs"]
mod mesh;
#[path = "../../benches/workload/mod.rs"]
mod workload;

use baseline::baseline;
use mesh::ndc_mesh;
use workload::{HEIGHT, WIDTH, scene};

/// A scene: the mesh and matrix the renderers draw, and the same triangles in raster space
/// with a colour each for the baseline.
struct Scene {
    mesh: Mesh,
    mvp: Mat4,
    raster: Vec<([Vec3; 3], Vec4)>,
}

/// A workload scene as a mesh in NDC, drawn with the identity.
fn flat(triangles: Vec<([Vec3; 3], Vec4)>) -> Scene {
    Scene {
        mesh: ndc_mesh(&triangles),
        mvp: Mat4::IDENTITY,
        raster: triangles,
    }
}

/// A torus of `2 · segments · rings` triangles, coloured by normal, seen from above its rim.
fn torus(segments: u32, rings: u32) -> Scene {
    let mut vertices = Vec::new();
    for i in 0..segments {
        let theta = TAU * i as f32 / segments as f32;
        let radial = Vec3::new(theta.cos(), 0.0, theta.sin());
        for j in 0..rings {
            let phi = TAU * j as f32 / rings as f32;
            let normal = radial * phi.cos() + Vec3::Y * phi.sin();
            vertices.push(Vertex::colored(
                radial + normal * 0.4,
                normal * 0.5 + Vec3::splat(0.5),
            ));
        }
    }
    let at = |i: u32, j: u32| (i % segments) * rings + j % rings;
    let triangles = (0..segments)
        .flat_map(|i| (0..rings).map(move |j| (i, j)))
        .flat_map(|(i, j)| {
            let [a, b, c, d] = [at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)];
            [[a, b, c], [a, c, d]]
        })
        .collect();
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let view = Camera::look_at(Vec3::new(0.0, 1.6, -2.4), Vec3::ZERO).view();
    let projection = Projection::Perspective {
        fov_y: 0.9,
        aspect,
        near: 0.5,
        far: 10.0,
    };
    let mvp = projection.matrix() * view;
    let mesh = Mesh { vertices, triangles };
    let raster = mesh
        .triangles
        .iter()
        .map(|t| {
            let corner = |k: u32| {
                let v = &mesh.vertices[k as usize];
                let p = mvp * v.position.extend(1.0);
                let (x, y, z) = (p.x / p.w, p.y / p.w, p.z / p.w);
                Vec3::new((x + 1.0) / 2.0 * WIDTH as f32, (1.0 - y) / 2.0 * HEIGHT as f32, z)
            };
            (
                [corner(t[0]), corner(t[1]), corner(t[2])],
                mesh.vertices[t[0] as usize].color,
            )
        })
        .collect();
    Scene { mesh, mvp, raster }
}

/// The reference pipeline, as `benches/reference.rs` runs it.
fn reference(target: &mut Framebuffer, scene: &Scene) -> usize {
    target.clear([0, 0, 0, 255], 1.0);
    let stats = Renderer::default()
        .draw_mesh(target, &scene.mesh, Mat4::IDENTITY, scene.mvp, |f| Some(f.color))
        .expect("valid mesh");
    stats.fragments
}

/// `fast` with the same work per fragment: early depth test, colour interpolated with the
/// fragment's perspective-correct barycentrics, rounded to RGBA8.
fn fast(fast: &mut Fast, depth: &mut [f32], color: &mut [[u8; 4]], scene: &Scene) {
    depth.fill(1.0);
    color.fill([0, 0, 0, 255]);
    let draw = Renderer::default().mesh_draw(
        refrast::Viewport::new(WIDTH, HEIGHT).unwrap(),
        &scene.mesh,
        scene.mvp,
    );
    let (vertices, triangles) = (&scene.mesh.vertices, &scene.mesh.triangles);
    let shade = |f: &Fragment| {
        let [a, b, c] = triangles[f.primitive as usize].map(|k| vertices[k as usize].color);
        let [ba, bb, bc] = f.barycentric;
        Some(to_rgba8(a * ba + b * bb + c * bc))
    };
    fast.render(&draw, depth, color, shade).expect("valid draw");
}

/// The scene as a draw, with the state `r` supports closest to the renderer's.
fn fitted_draw(r: &dyn Rasterizer, scene: &Scene) -> Draw {
    let mut draw = Renderer::default().mesh_draw(
        refrast::Viewport::new(WIDTH, HEIGHT).unwrap(),
        &scene.mesh,
        scene.mvp,
    );
    draw.state = r.profile().fit(draw.state);
    draw
}

/// The driver drawing beside `fast`: `REFRAST_BENCH_DRIVER` (lavapipe unless it names another;
/// SwiftShader also needs `VK_ICD_FILENAMES`, which `scripts/bench_fast.py` sets in a second
/// process, since the Vulkan loader reads it once).
fn gpu_driver() -> Driver {
    let name = std::env::var("REFRAST_BENCH_DRIVER").unwrap_or_else(|_| "lavapipe".into());
    Driver::ALL
        .into_iter()
        .find(|d| d.name() == name)
        .unwrap_or_else(|| {
            let names: Vec<_> = Driver::ALL.iter().map(|d| d.name()).collect();
            eprintln!(
                "REFRAST_BENCH_DRIVER={name} is not a driver; choose one of {}",
                names.join(", ")
            );
            std::process::exit(2)
        })
}

/// The thread counts `fast` runs at: `REFRAST_BENCH_THREADS`, or 1, 2 and the machine's
/// parallelism, in order, without repeats.
fn thread_counts() -> Vec<usize> {
    let mut counts = match std::env::var("REFRAST_BENCH_THREADS") {
        Ok(list) => list
            .split(',')
            .map(|n| match n.trim().parse::<usize>() {
                Ok(n) if n > 0 => n,
                _ => {
                    eprintln!(
                        "REFRAST_BENCH_THREADS={list}: each entry must be a thread count of at least 1"
                    );
                    std::process::exit(2)
                }
            })
            .collect(),
        Err(_) => vec![1, 2, std::thread::available_parallelism().map_or(1, usize::from)],
    };
    counts.sort_unstable();
    counts.dedup();
    counts
}

/// The driver's row: its name, with lavapipe's thread count where `LP_NUM_THREADS` sets it.
fn driver_row(driver: Driver) -> String {
    match std::env::var("LP_NUM_THREADS") {
        Ok(n) if driver == Driver::Lavapipe => format!("{}_{}t", driver.name(), n.trim()),
        _ => driver.name().to_owned(),
    }
}

fn bench(c: &mut Criterion) {
    // A hundredth of each scene under REFRAST_BENCH_SMALL, so that CI runs every row once
    // (`cargo test --benches` runs criterion's test mode) and the bench cannot rot.
    // (A tenth of the torus's segments and rings is a hundredth of its triangles.)
    let (k, t) = if std::env::var_os("REFRAST_BENCH_SMALL").is_some() {
        (100, 10)
    } else {
        (1, 1)
    };
    let scenes = [
        ("small_10px", flat(scene(100_000 / k, 10.0))),
        ("medium_500px", flat(scene(10_000 / k, 500.0))),
        ("large_50kpx", flat(scene(1_000 / k, 50_000.0))),
        ("torus_1m", torus(1000 / t, 500 / t)),
    ];
    let mut fasts: Vec<(usize, Fast)> = thread_counts()
        .into_iter()
        .map(|n| (n, Fast::with_threads(n)))
        .collect();
    // Read by scripts/bench_fast.py into its metadata.
    println!("simd {}", fasts[0].1.simd().name());
    let threads: Vec<String> = fasts.iter().map(|(n, _)| n.to_string()).collect();
    println!("threads {}", threads.join(","));
    let driver = gpu_driver();
    let mut gpu = Gpu::new(driver)
        .inspect_err(|why| eprintln!("{}: SKIPPED: {why}", driver.name()))
        .ok();
    for (name, scene) in &scenes {
        let count = scene.mesh.triangles.len();
        let mut target = Framebuffer::new(WIDTH, HEIGHT).expect("1080p is a valid size");
        let (mut color, mut depth) = (target.color().to_vec(), target.depth().to_vec());
        let fragments = reference(&mut target, scene);
        let base_fragments = baseline(&mut color, &mut depth, &scene.raster);
        fast(&mut fasts[0].1, &mut depth, &mut color, scene);
        // `fast`'s contract: the reference's picture within its precision, except at ties.
        let draw = Renderer::default().mesh_draw(
            refrast::Viewport::new(WIDTH, HEIGHT).unwrap(),
            &scene.mesh,
            scene.mvp,
        );
        let all = Reference::default()
            .rasterize(&draw)
            .expect("the reference draws");
        let tied = ties(&all, WIDTH, HEIGHT, tolerance());
        if let Err(e) = check_pictures(
            (target.color(), target.depth()),
            (&color, &depth),
            &tied,
            tolerance(),
        ) {
            panic!("{name}: fast's picture is not the reference's: {e}");
        }
        // Read by scripts/bench_fast.py to turn medians into Mpix/s.
        println!("fragments {name} reference {fragments} baseline {base_fragments} triangles {count}");
        let mut group = c.benchmark_group(format!("fast/{name}"));
        group
            .sample_size(10)
            .throughput(Throughput::Elements(count as u64));
        group.bench_function("reference", |b| {
            b.iter(|| black_box(reference(&mut target, scene)))
        });
        group.bench_function("baseline", |b| {
            b.iter(|| black_box(baseline(&mut color, &mut depth, &scene.raster)))
        });
        for (threads, r) in &mut fasts {
            group.bench_function(format!("fast_{threads}t"), |b| {
                b.iter(|| fast(r, &mut depth, &mut color, scene));
            });
        }
        if let Some(gpu) = gpu.as_mut() {
            for (threads, r) in &mut fasts {
                let draw = fitted_draw(r, scene);
                group.bench_function(format!("fast_resolve_{threads}t"), |b| {
                    b.iter(|| black_box(r.resolve(&draw).expect("draws")))
                });
            }
            let draw = fitted_draw(gpu, scene);
            // Each iteration draws and reads back; only the drawing is counted.
            group.bench_function(driver_row(driver), |b| {
                b.iter_custom(|n| {
                    (0..n)
                        .map(|_| gpu.resolve_timed(&draw).expect("the driver draws").1.drawing)
                        .sum()
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
