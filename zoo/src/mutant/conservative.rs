//! Conservative rasterization's bugs: the reference's conservative drawing with one thing
//! wrong.

use std::collections::BTreeMap;

use refrast::{
    Conservative, Draw, DrawError, FixedPoint, Fragment, PolygonMode, Rasterizer, Reference, SubpixelBits,
    Topology, orient2d,
};

use super::Bug;

/// `draw` as the reference draws it with `bug`, `None` for a bug elsewhere or a draw with no
/// conservative triangles.
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    let mode = draw.state.conservative?;
    let bugs = [
        Bug::SampledConservative,
        Bug::BoxConservative,
        Bug::UnextendedConservative,
        Bug::OneSampleConservative,
        Bug::OverForUnder,
        Bug::RasterizedDegenerates,
    ];
    let applies = draw.topology.is_triangles() && draw.state.polygon_mode == PolygonMode::Fill;
    (applies && bugs.contains(&bug)).then(|| wrong(bug, mode, draw))
}

/// The reference's fragments of `draw` under `mode`, with `bug`.
fn wrong(bug: Bug, mode: Conservative, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let mut reference = Reference::default();
    let mut changed = draw.clone();
    match (bug, mode) {
        (Bug::SampledConservative, _) => changed.state.conservative = None,
        (Bug::UnextendedConservative, Conservative::Overestimate { .. })
        | (Bug::OverForUnder, Conservative::Underestimate) => {
            changed.state.conservative = Some(Conservative::Overestimate { extra: 0.0 });
        }
        _ => {}
    }
    let mut out = reference.rasterize(&changed)?;
    match bug {
        Bug::OneSampleConservative => out.retain(|f| f.sample == 0),
        Bug::BoxConservative => out = boxed(&out, draw.samples),
        Bug::RasterizedDegenerates if matches!(mode, Conservative::Overestimate { .. }) => {
            out.extend(degenerate_edges(draw, &out)?);
        }
        _ => {}
    }
    Ok(out)
}

/// Every sample of every pixel in each primitive's box of pixels, carrying the values of the
/// primitive's first fragment.
fn boxed(frags: &[Fragment], samples: u8) -> Vec<Fragment> {
    let mut boxes: BTreeMap<u32, (Fragment, [u32; 4])> = BTreeMap::new();
    for f in frags {
        let entry = boxes.entry(f.primitive).or_insert((*f, [f.x, f.y, f.x, f.y]));
        let b = &mut entry.1;
        *b = [b[0].min(f.x), b[1].min(f.y), b[2].max(f.x), b[3].max(f.y)];
    }
    let mut out = Vec::new();
    for (first, [x0, y0, x1, y1]) in boxes.into_values() {
        for y in y0..=y1 {
            for x in x0..=x1 {
                out.extend((0..samples).map(|sample| Fragment {
                    x,
                    y,
                    sample,
                    ..first
                }));
            }
        }
    }
    out
}

/// The edges of each triangle of zero area once snapped (culled), drawn as the
/// reference's lines at every sample, as if degenerate triangles were rasterized while the
/// profile says they are culled.
fn degenerate_edges(draw: &Draw, drawn: &[Fragment]) -> Result<Vec<Fragment>, DrawError> {
    let mut out = Vec::new();
    for (i, t) in draw.triangles().iter().enumerate() {
        if drawn.iter().any(|f| f.primitive == i as u32) || !zero_once_snapped(draw, *t) {
            continue;
        }
        let mut lines = Draw::of(
            draw.viewport,
            draw.positions.clone(),
            Topology::LineList,
            vec![t[0], t[1], t[1], t[2], t[2], t[0]],
        );
        lines.samples = draw.samples;
        for f in Reference::default().rasterize(&lines)? {
            out.push(Fragment {
                primitive: i as u32,
                front_facing: false,
                ..f
            });
        }
    }
    Ok(out)
}

/// Whether triangle `t` of `draw` has its corners in front of the eye and zero area once
/// snapped to the reference's grid.
fn zero_once_snapped(draw: &Draw, t: [u32; 3]) -> bool {
    let (width, height) = (
        f64::from(draw.viewport.width()),
        f64::from(draw.viewport.height()),
    );
    let snapped: Option<Vec<FixedPoint>> = t
        .iter()
        .map(|&i| {
            let p = draw.positions.get(i as usize)?.map(f64::from);
            if p[3] <= 0.0 {
                return None;
            }
            let (x, y) = (
                (p[0] / p[3] + 1.0) * 0.5 * width,
                (1.0 - p[1] / p[3]) * 0.5 * height,
            );
            FixedPoint::snap(x, y, SubpixelBits::DEFAULT)
        })
        .collect();
    snapped.is_some_and(|v| orient2d(v[0], v[1], v[2]) == 0)
}
