//! The reference at 1920×1080 with depth and colour, against a plain scalar rasterizer.
//!
//! Two workloads: 100 000 triangles of about 10 px and 1 000 of about 50 000 px (≈24× overdraw),
//! equilateral, randomly rotated and placed, random depth. `baseline` is the plain scalar loop of
//! a textbook CPU rasterizer (16.8 fixed point, incremental i64 edges, top-left bias, f32
//! depth LESS, one colour per triangle), run in the same process so the ratio survives a noisy
//! machine. `scripts/bench_ratio.py` prints medians, Mtri/s, Mpix/s and the ratio.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Mat4;
use refrast::pipeline::{Framebuffer, Mesh, Renderer};

#[path = "workload/baseline.rs"]
mod baseline;
#[path = "workload/mesh.rs"]
mod mesh;
mod workload;

use baseline::baseline;
use mesh::ndc_mesh;
use workload::{HEIGHT, WIDTH, scene};

/// The reference pipeline: clip, snap, set up, traverse, interpolate, shade, depth-test, write.
fn reference(target: &mut Framebuffer, mesh: &Mesh) -> usize {
    target.clear([0, 0, 0, 255], 1.0);
    let stats = Renderer::default()
        .draw_mesh(target, mesh, Mat4::IDENTITY, Mat4::IDENTITY, |f| Some(f.color))
        .expect("valid mesh");
    stats.fragments
}

fn bench(c: &mut Criterion) {
    for (name, count, area) in [("small_10px", 100_000, 10.0), ("large_50kpx", 1_000, 50_000.0)] {
        let triangles = scene(count, area);
        let mesh = ndc_mesh(&triangles);
        let mut target = Framebuffer::new(WIDTH, HEIGHT).expect("1080p is a valid size");
        let (mut color, mut depth) = (target.color().to_vec(), target.depth().to_vec());
        let fragments = reference(&mut target, &mesh);
        let base_fragments = baseline(&mut color, &mut depth, &triangles);
        // Read by scripts/bench_ratio.py to turn medians into Mpix/s.
        println!("fragments {name} reference {fragments} baseline {base_fragments} triangles {count}");
        let mut group = c.benchmark_group(name);
        group
            .sample_size(10)
            .throughput(Throughput::Elements(count as u64));
        group.bench_function("reference", |b| {
            b.iter(|| black_box(reference(&mut target, &mesh)))
        });
        group.bench_function("baseline", |b| {
            b.iter(|| black_box(baseline(&mut color, &mut depth, &triangles)))
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
