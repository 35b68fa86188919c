//! Coverage against exact arithmetic on the unsnapped vertices: how far from an edge a sample
//! can be and still be decided the other way. For a driver with no grid this is its tolerance
//! band; on a grid it is snapping's reach (up to about √2/2 of a step), reported only.
//!
//! 300 triangles in one draw on a 64×64 target, vertices anywhere on it with f32 coordinates on
//! no grid (w = 1, so `x/w` is the input); every sample of each triangle's bounding box is
//! compared with the sign of its exact edge functions (f64 is exact for these), samples exactly
//! on an edge left out.

use refrast::DrawError;

use super::{Raster, batch};

/// What the coverage probe saw.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage {
    /// Samples compared.
    pub samples: usize,
    /// Those decided against exact arithmetic.
    pub wrong: usize,
    /// The largest distance from an edge of one, in pixels.
    pub farthest: f64,
}

impl Coverage {
    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "{} of {} samples decided against exact arithmetic, the farthest {:.1e} px from its edge",
            self.wrong, self.samples, self.farthest
        )
    }
}

/// Draws the triangles and compares every sample of their bounding boxes.
pub fn probe(draw: &mut Raster<'_>) -> Result<Coverage, DrawError> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        // 24 random bits, as f32 in [0, 1): exactly representable, on no grid.
        (state >> 40) as f32 / (1u32 << 24) as f32
    };
    let mut tris: Vec<[[f32; 2]; 3]> = Vec::new();
    while tris.len() < 300 {
        let t = [(); 3].map(|()| [next() * 2.0 - 1.0, next() * 2.0 - 1.0]);
        if orient(t[0].map(f64::from), t[1].map(f64::from), t[2].map(f64::from)) != 0.0 {
            tris.push(t);
        }
    }
    let positions = tris.iter().flatten().map(|&[x, y]| [x, y, 0.5, 1.0]).collect();
    let frags = draw(&batch(64, 64, positions))?;
    let mut covered = std::collections::HashSet::new();
    for f in &frags {
        covered.insert((f.primitive, f.x, f.y));
    }
    let mut coverage = Coverage {
        samples: 0,
        wrong: 0,
        farthest: 0.0,
    };
    for (i, t) in tris.iter().enumerate() {
        // Framebuffer positions, exact: x_f = (x + 1)·32, y_f = (1 − y)·32.
        let p = t.map(|[x, y]| [(f64::from(x) + 1.0) * 32.0, (1.0 - f64::from(y)) * 32.0]);
        let (lo, hi) = (
            p.iter()
                .fold([f64::MAX; 2], |m, q| [m[0].min(q[0]), m[1].min(q[1])]),
            p.iter()
                .fold([f64::MIN; 2], |m, q| [m[0].max(q[0]), m[1].max(q[1])]),
        );
        let whole = orient(p[0], p[1], p[2]);
        for y in (lo[1].floor() as u32)..(hi[1].ceil() as u32).min(64) {
            for x in (lo[0].floor() as u32)..(hi[0].ceil() as u32).min(64) {
                let s = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                let e = [
                    orient(p[1], p[2], s),
                    orient(p[2], p[0], s),
                    orient(p[0], p[1], s),
                ];
                if e.contains(&0.0) {
                    continue;
                }
                let inside = e.iter().all(|&v| v.signum() == whole.signum());
                let primitive = u32::try_from(i).expect("300 triangles");
                coverage.samples += 1;
                if covered.contains(&(primitive, x, y)) != inside {
                    coverage.wrong += 1;
                    let distance = (0..3)
                        .map(|k| {
                            let (a, b) = (p[(k + 1) % 3], p[(k + 2) % 3]);
                            e[k].abs() / (b[0] - a[0]).hypot(b[1] - a[1])
                        })
                        .fold(f64::MAX, f64::min);
                    coverage.farthest = coverage.farthest.max(distance);
                }
            }
        }
    }
    Ok(coverage)
}

/// Twice the signed area of `a, b, c`.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}
