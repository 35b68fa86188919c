//! The bugs only lines and points beyond the 8-bit grid at `w = 1` show: line ends floored,
//! diamond-exit lines tested per sample, points kept behind the eye or past a depth plane,
//! points drawn in vertex order, and the near cut of a line found between its projected ends.
//!
//! Each mutant declares no polygon modes: `line.polygon-mode.edges` and
//! `point.polygon-mode.vertices` compare a triangle's edges and corners with the same
//! implementation's lists, which these bugs (in lists only) would show there too.

use refrast::{DepthRange, Draw, DrawError, Fragment, Rasterizer, Reference, SamplePattern, Topology};

use super::Bug;

/// Draws `draw` as the reference does, with `bug`; `None` when `bug` is none of these.
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    if let Err(e) = draw.validate() {
        return Some(Err(e));
    }
    let mut reference = Reference::default();
    let lines = draw.topology.is_lines();
    let points = draw.topology == Topology::PointList;
    Some(match bug {
        Bug::FlooredLineEnds if lines => reference.rasterize(&floored(draw)),
        Bug::PerSampleDiamonds if lines && draw.samples > 1 => per_sample(draw),
        Bug::UnclippedPoints if points => reference.rasterize(&unclipped(draw)),
        Bug::VertexOrderPoints if points => {
            let n = draw.positions.len() as u32;
            let indices = (0..draw.indices.len() as u32).map(|i| i % n.max(1)).collect();
            reference.rasterize(&Draw {
                indices,
                ..draw.clone()
            })
        }
        Bug::ScreenSpaceLineCut if lines && draw.distances.is_empty() => screen_cut(draw),
        Bug::FlooredLineEnds
        | Bug::PerSampleDiamonds
        | Bug::UnclippedPoints
        | Bug::VertexOrderPoints
        | Bug::ScreenSpaceLineCut => reference.rasterize(draw),
        _ => return None,
    })
}

/// Clip-space `p` moved to the raster position `f` makes of its own (pixels), at its `w`.
fn moved(draw: &Draw, p: [f32; 4], f: impl Fn(f64, f64) -> (f64, f64)) -> [f32; 4] {
    let (w, h) = (
        f64::from(draw.viewport.width()),
        f64::from(draw.viewport.height()),
    );
    let pw = f64::from(p[3]);
    let x = (f64::from(p[0]) / pw + 1.0) * 0.5 * w;
    let y = (1.0 - f64::from(p[1]) / pw) * 0.5 * h;
    let (x, y) = f(x, y);
    [
        ((x / w * 2.0 - 1.0) * pw) as f32,
        ((1.0 - y / h * 2.0) * pw) as f32,
        p[2],
        p[3],
    ]
}

/// Every vertex in front of the eye floored to the 8-bit grid, as `(v · 256) as i32` does on
/// positive coordinates, where the reference rounds to nearest.
fn floored(draw: &Draw) -> Draw {
    let mut out = draw.clone();
    let floor = |v: f64| (v * 256.0).floor() / 256.0;
    for p in out
        .positions
        .iter_mut()
        .filter(|p| p[3] > 0.0 && p.iter().all(|c| c.is_finite()))
    {
        *p = moved(draw, *p, |x, y| (floor(x), floor(y)));
    }
    out
}

/// Each sample's coverage from the diamond-exit rule at the sample's own position: the draw
/// moved by the pixel centre minus the sample, drawn at one sample.
fn per_sample(draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let pattern =
        SamplePattern::standard(draw.samples).ok_or_else(|| DrawError::Unsupported(draw.describe()))?;
    let mut out = Vec::new();
    for (k, &[u, v]) in pattern.positions().iter().enumerate() {
        let (dx, dy) = (
            f64::from(8 - i16::from(u)) / 16.0,
            f64::from(8 - i16::from(v)) / 16.0,
        );
        // Sample k kept or masked as its own bit says, not as bit 0 of the one-sample draw.
        if !draw.state.passes_sample_mask(k as u8) {
            continue;
        }
        let mut shifted = draw.clone().at_samples(1);
        shifted.state.sample_mask = refrast::DrawState::ALL_SAMPLES;
        for p in shifted.positions.iter_mut().filter(|p| p[3] > 0.0) {
            *p = moved(draw, *p, |x, y| (x + dx, y + dy));
        }
        let fragments = Reference::default().rasterize(&shifted)?;
        out.extend(fragments.into_iter().map(|f| Fragment { sample: k as u8, ..f }));
    }
    Ok(out)
}

/// Every point behind the eye turned to face it, and every depth beyond a plane put on it:
/// nothing is clipped.
fn unclipped(draw: &Draw) -> Draw {
    let mut out = draw.clone();
    for p in &mut out.positions {
        if p[3] < 0.0 {
            *p = p.map(|c| -c);
        }
        let near = match draw.state.depth_range {
            DepthRange::ZeroToOne => 0.0,
            DepthRange::NegativeOneToOne => -p[3],
        };
        if p[3] > 0.0 {
            p[2] = p[2].clamp(near, p[3]);
        }
    }
    out
}

/// Each segment crossing the near plane cut where it crosses, but at the point that fraction of
/// the way between its projected ends (right only when both ends share one `w`); drawn as a
/// list, each fragment's flat vertex the one the draw names.
fn screen_cut(draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let near = |p: [f32; 4]| match draw.state.depth_range {
        DepthRange::ZeroToOne => f64::from(p[2]),
        DepthRange::NegativeOneToOne => f64::from(p[2]) + f64::from(p[3]),
    };
    let mut positions = Vec::new();
    for i in 0..draw.primitive_count() {
        let Some(&[a, b]) = draw.primitive(i).as_deref() else {
            continue;
        };
        let (pa, pb) = (draw.positions[a as usize], draw.positions[b as usize]);
        let (da, db) = (near(pa), near(pb));
        let mut ends = [pa, pb];
        if draw.state.clip_near && (da < 0.0) != (db < 0.0) && pa[3] != 0.0 && pb[3] != 0.0 {
            let (front, back) = if da >= 0.0 { (0, 1) } else { (1, 0) };
            let s = [da, db][front] / ([da, db][front] - [da, db][back]);
            let raster = |p: [f32; 4]| {
                [
                    f64::from(p[0]) / f64::from(p[3]),
                    f64::from(p[1]) / f64::from(p[3]),
                ]
            };
            let (f, k) = (raster(ends[front]), raster(ends[back]));
            let wf = f64::from(ends[front][3]);
            let cut = [0, 1].map(|j| ((f[j] + s * (k[j] - f[j])) * wf) as f32);
            let z = match draw.state.depth_range {
                DepthRange::ZeroToOne => 0.0,
                DepthRange::NegativeOneToOne => -ends[front][3],
            };
            ends[back] = [cut[0], cut[1], z, ends[front][3]];
        }
        positions.extend(ends);
    }
    let list = Draw {
        indices: (0..positions.len() as u32).collect(),
        positions,
        topology: Topology::LineList,
        ..draw.clone()
    };
    let mut out = Reference::default().rasterize(&list)?;
    for f in &mut out {
        f.flat = draw.provoking(f.primitive as usize);
    }
    Ok(out)
}
