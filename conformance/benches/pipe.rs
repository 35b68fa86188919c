//! What the pipe protocol costs: draws per second through `Process` to a C++ child that
//! answers at once (`clients/cpp/echo.cpp`), with 1 and 100 triangles per draw, beside the
//! reference rasterizing the same draw in this process.
//!
//! `cargo bench -p refrast-conformance --bench pipe`; criterion's `thrpt` is draws per second.
//! Needs `g++`; without it the benchmark says so and measures nothing.

use std::path::Path;
use std::process::Command;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use refrast::{Draw, Rasterizer, Reference, Viewport};
use refrast_pipe::Process;

/// `n` small triangles on a 64×64 target, each a few pixels.
fn draw(n: u32) -> Draw {
    let viewport = Viewport::new(64, 64).expect("valid");
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 0..n {
        let (x, y) = ((t % 10) as f32 * 0.2 - 0.95, (t / 10) as f32 * 0.2 - 0.95);
        positions.extend([[x, y, 0.5, 1.0], [x + 0.1, y, 0.5, 1.0], [x, y + 0.1, 0.5, 1.0]]);
        triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
    }
    Draw::new(viewport, positions, triangles)
}

/// Compiles the echo client into the target folder; `None` (said) without g++.
fn echo() -> Option<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = root.join("target").join("pipe-echo");
    let built = Command::new("g++")
        .args(["-O2", "-std=c++17", "-o"])
        .arg(&out)
        .arg(root.join("clients/cpp/echo.cpp"))
        .status()
        .is_ok_and(|s| s.success());
    if !built {
        eprintln!("SKIPPED: g++ could not build clients/cpp/echo.cpp (apt-get install g++)");
        return None;
    }
    Some(out.display().to_string())
}

fn pipe(c: &mut Criterion) {
    let Some(echo) = echo() else { return };
    let mut process = Process::try_spawn(&echo).expect("the echo client starts");
    let mut reference = Reference::default();
    let mut group = c.benchmark_group("pipe");
    group.throughput(Throughput::Elements(1));
    for n in [1, 100] {
        let d = draw(n);
        group.bench_function(format!("echo/{n}-triangles"), |b| {
            b.iter(|| process.rasterize(&d).expect("echo answers"));
        });
        group.bench_function(format!("reference-in-process/{n}-triangles"), |b| {
            b.iter(|| reference.rasterize(&d).expect("valid"));
        });
    }
    group.finish();
}

criterion_group!(benches, pipe);
criterion_main!(benches);
