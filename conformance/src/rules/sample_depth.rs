//! Depth per sample: each sample's fragment and depth-buffer value lie on the triangle's depth
//! plane at that sample's declared position (`msaa.depth.per-sample`).

use refrast::Rasterizer;

use super::common::precision;
use super::samples::{positions, sample_fragments};
use crate::oracle::facing::snapped_variants;
use crate::oracle::raster::{project, window_depth};
use crate::primitives::PrimitiveScene;
use crate::violation::{Findings, Violation, plural};

/// Each sample's depth is the snapped triangle's depth plane at the sample's position.
pub fn check_depth(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let frags = sample_fragments(r, case)?;
    let depths: Vec<_> = frags
        .iter()
        .map(|f| (f.fragment.x, f.fragment.y, f.sample, f.fragment.depth))
        .collect();
    on_plane(r, case, &depths, "sample fragments")?;
    check_depth_resolved(r, case)
}

/// The depth buffer's samples the triangle wrote hold its depth at their positions (with
/// depth writes on; else the buffer keeps its clear value and says nothing).
pub fn check_depth_resolved(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    if !case.scene.state.depth.write {
        return Ok(());
    }
    let draw = case.draw();
    let resolved = r
        .resolve_primitives(&draw)
        .map_err(|e| Violation::of_draw_error("resolve_primitives", &e))?;
    let n = usize::from(resolved.samples.max(1));
    let w = case.scene.width as usize;
    let written: Vec<_> = (0..resolved.depth.len().min(resolved.primitive.len()))
        .filter(|&i| resolved.primitive[i] == Some(0))
        .map(|i| {
            let pixel = i / n;
            (
                (pixel % w) as u32,
                (pixel / w) as u32,
                (i % n) as u8,
                resolved.depth[i],
            )
        })
        .collect();
    on_plane(r, case, &written, "depth buffer")
}

/// Each `(x, y, sample, depth)` of triangle 0 lies on its depth plane at the sample's declared
/// position, within the precision and what snapping may move the plane.
fn on_plane(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    depths: &[(u32, u32, u8, f32)],
    what: &str,
) -> Result<(), Violation> {
    let profile = r.profile();
    let positions = positions(r, case);
    let (w, h) = (case.scene.width, case.scene.height);
    let corners = case.scene.corners(0);
    // On a grid, the plane through the snapped corners; without one, through the exact ones.
    let v = match profile.snapping.grid_bits() {
        Some(bits) => {
            let Some(variants) = snapped_variants(&corners, w, h, &profile) else {
                return Ok(());
            };
            let one = f64::from(1u32 << bits.min(16));
            variants[0].map(|p| [p.0 as f64 / one, p.1 as f64 / one])
        }
        None => case.scene.positions_of(0).map(|p| project(w, h, p)),
    };
    let z = corners.map(|p| window_depth(case.scene.state.depth_range, f64::from(p[2]) / f64::from(p[3])));
    let area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
    if area == 0.0 {
        return Ok(());
    }
    let plane = |s: [f64; 2]| {
        let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]);
        (e(v[1], v[2]) * z[0] + e(v[2], v[0]) * z[1] + e(v[0], v[1]) * z[2]) / area
    };
    // How far a snapping variant may move the plane: its slope times the band, both ways.
    let slope = (plane([1.0, 0.0]) - plane([0.0, 0.0])).abs() + (plane([0.0, 1.0]) - plane([0.0, 0.0])).abs();
    let tolerance = 2.0 * precision(&profile) + slope * 2.0 * profile.band_px();
    let mut found = Findings::new();
    for &(x, y, sample, depth) in depths {
        let [u, vv] = positions.get(usize::from(sample)).copied().unwrap_or([8, 8]);
        let s = [
            f64::from(x) + f64::from(u) / 16.0,
            f64::from(y) + f64::from(vv) / 16.0,
        ];
        let want = plane(s).clamp(0.0, 1.0);
        let got = f64::from(depth);
        if (got - want).abs() > tolerance {
            found.add((x, y), || {
                let centre = plane([f64::from(x) + 0.5, f64::from(y) + 0.5]);
                format!(
                    "({x}, {y}) sample {sample}: depth {got}, expected {want} at the sample (the pixel centre's is {centre})"
                )
            });
        }
    }
    found.verdict(|n| {
        format!(
            "{} of the {what} carry another depth than at their sample's position",
            plural(n, "sample")
        )
    })
}
