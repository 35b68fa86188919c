//! The benchmark workload, shared by `benches/reference.rs` and the side-by-side benchmark of
//! `adapters/wgpu`: equilateral triangles of one area, randomly rotated and placed on a
//! 1920×1080 target, random depth and colour, the same every run.

use glam::{Vec3, Vec4};

/// The target's width.
pub const WIDTH: u32 = 1920;
/// The target's height.
pub const HEIGHT: u32 = 1080;

/// A small deterministic generator (xorshift64*), so every run draws the same scene.
struct Rng(u64);

impl Rng {
    fn next_f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `count` equilateral triangles of `area` px², as raster-space `(x, y, z)` and a colour each.
pub fn scene(count: usize, area: f32) -> Vec<([Vec3; 3], Vec4)> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let side = (4.0 * area / 3f32.sqrt()).sqrt();
    let radius = side / 3f32.sqrt();
    (0..count)
        .map(|_| {
            let centre = (rng.next_f32() * WIDTH as f32, rng.next_f32() * HEIGHT as f32);
            let (angle, z) = (rng.next_f32() * std::f32::consts::TAU, rng.next_f32());
            let corner = |k: f32| {
                let a = angle + k * std::f32::consts::TAU / 3.0;
                Vec3::new(centre.0 + radius * a.cos(), centre.1 + radius * a.sin(), z)
            };
            let colour = Vec4::new(rng.next_f32(), rng.next_f32(), rng.next_f32(), 1.0);
            ([corner(0.0), corner(1.0), corner(2.0)], colour)
        })
        .collect()
}
