//! The reference's benchmark scenes (`benches/workload`) through three rasterizers in one run:
//! the reference, the euc crate and Mesa's lavapipe, each resolving the draw with its own depth
//! test (`Rasterizer::resolve`). lavapipe's device is set up once; its drawing and its reading
//! back are timed apart (`Gpu::resolve_timed`). `scripts/side_by_side.py` prints medians and the
//! ratios to the reference.
//!
//! Each gets the draw state it supports closest to `LessOrEqual`, no culling, far clipping on:
//! euc clips nothing, which these scenes (every vertex inside the view volume) do not need.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use refrast::{CompareOp, CullMode, Draw, Rasterizer, Reference, Viewport};
use refrast_euc::Euc;
use refrast_wgpu::{Driver, Gpu};

#[path = "../../../benches/workload/mod.rs"]
mod workload;

use workload::{HEIGHT, WIDTH, scene};

/// The workload as a draw in clip space (w = 1, so NDC).
fn draw(count: usize, area: f32) -> Draw {
    let triangles = scene(count, area);
    let positions = triangles
        .iter()
        .flat_map(|(t, _)| {
            t.map(|p| {
                [
                    p.x / WIDTH as f32 * 2.0 - 1.0,
                    1.0 - p.y / HEIGHT as f32 * 2.0,
                    p.z,
                    1.0,
                ]
            })
        })
        .collect();
    let indices = (0..triangles.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    let mut draw = Draw::new(
        Viewport::new(WIDTH, HEIGHT).expect("1920×1080"),
        positions,
        indices,
    );
    draw.state.cull = CullMode::None;
    draw.state.depth.compare = CompareOp::LessOrEqual;
    draw.state.clip_far = true;
    draw
}

/// `draw` with the state `r` supports closest to it.
fn fitted(r: &dyn Rasterizer, draw: &Draw) -> Draw {
    let mut d = draw.clone();
    d.state = r.profile().fit(d.state);
    d
}

fn side_by_side(c: &mut Criterion) {
    let mut lavapipe = match Gpu::new(Driver::Lavapipe) {
        Ok(gpu) => Some(gpu),
        Err(why) => {
            eprintln!("lavapipe: SKIPPED: {why}");
            None
        }
    };
    for (name, count, area) in [
        ("side-by-side-small", 100_000, 10.0),
        ("side-by-side-large", 1_000, 50_000.0),
    ] {
        let draw = draw(count, area);
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        let mut reference = Reference::default();
        let d = fitted(&reference, &draw);
        group.bench_function("reference", |b| {
            b.iter(|| black_box(reference.resolve(&d).expect("draws")))
        });
        let d = fitted(&Euc, &draw);
        group.bench_function("euc", |b| b.iter(|| black_box(Euc.resolve(&d).expect("draws"))));
        if let Some(gpu) = lavapipe.as_mut() {
            let d = fitted(gpu, &draw);
            // Each iteration draws and reads back; each measurement keeps one of the two.
            group.bench_function("lavapipe-draw", |b| {
                b.iter_custom(|n| {
                    (0..n)
                        .map(|_| gpu.resolve_timed(&d).expect("draws").1.drawing)
                        .sum()
                })
            });
            group.bench_function("lavapipe-read-back", |b| {
                b.iter_custom(|n| {
                    (0..n)
                        .map(|_| gpu.resolve_timed(&d).expect("draws").1.reading)
                        .sum()
                })
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(5));
    targets = side_by_side
}
criterion_main!(benches);
