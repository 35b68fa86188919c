//! The plain scalar rasterizer the benchmarks measure against (a textbook
//! baseline), shared by `benches/reference.rs` and `fast/benches/fast.rs`.

use glam::{Vec3, Vec4};

use super::workload::{HEIGHT, WIDTH};

/// A plain scalar rasterizer: what the reference is measured against.
pub fn baseline(color: &mut [[u8; 4]], depth: &mut [f32], triangles: &[([Vec3; 3], Vec4)]) -> usize {
    color.fill([0, 0, 0, 255]);
    depth.fill(1.0);
    let mut fragments = 0;
    for (t, c) in triangles {
        let fx = |v: f32| (v * 256.0).round() as i64;
        let (mut a, mut b, c3) = (
            (fx(t[0].x), fx(t[0].y)),
            (fx(t[1].x), fx(t[1].y)),
            (fx(t[2].x), fx(t[2].y)),
        );
        let (mut za, mut zb) = (t[0].z, t[1].z);
        let mut area = (b.0 - a.0) * (c3.1 - a.1) - (b.1 - a.1) * (c3.0 - a.0);
        if area < 0 {
            std::mem::swap(&mut a, &mut b);
            std::mem::swap(&mut za, &mut zb);
            area = -area;
        } else if area == 0 {
            continue;
        }
        let (x0, x1) = (a.0.min(b.0).min(c3.0), a.0.max(b.0).max(c3.0));
        let (y0, y1) = (a.1.min(b.1).min(c3.1), a.1.max(b.1).max(c3.1));
        let px0 = ((x0 - 128 + 255) >> 8).max(0);
        let px1 = ((x1 - 128) >> 8).min(i64::from(WIDTH) - 1);
        let py0 = ((y0 - 128 + 255) >> 8).max(0);
        let py1 = ((y1 - 128) >> 8).min(i64::from(HEIGHT) - 1);
        let edge = |p: (i64, i64), q: (i64, i64)| {
            let top_left = (p.1 == q.1 && q.0 > p.0) || q.1 < p.1;
            (p.1 - q.1, q.0 - p.0, p, if top_left { 0 } else { -1 })
        };
        let edges = [edge(b, c3), edge(c3, a), edge(a, b)];
        let inv_area = 1.0 / area as f32;
        let (dz1, dz2) = ((zb - za) * inv_area, (t[2].z - za) * inv_area);
        let rgba = [c.x, c.y, c.z, c.w].map(|v| (v * 255.0) as u8);
        for py in py0..=py1 {
            let sy = py * 256 + 128;
            let sx = px0 * 256 + 128;
            let mut w = edges.map(|(ex, ey, o, _)| ex * (sx - o.0) + ey * (sy - o.1));
            for px in px0..=px1 {
                if (w[0] + edges[0].3) | (w[1] + edges[1].3) | (w[2] + edges[2].3) >= 0 {
                    let z = za + w[1] as f32 * dz1 + w[2] as f32 * dz2;
                    let i = py as usize * WIDTH as usize + px as usize;
                    if z < depth[i] {
                        depth[i] = z;
                        color[i] = rgba;
                    }
                    fragments += 1;
                }
                for k in 0..3 {
                    w[k] += edges[k].0 * 256;
                }
            }
        }
    }
    fragments
}
