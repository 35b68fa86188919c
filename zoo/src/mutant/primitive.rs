//! The bugs of lines, points and multisampling: the reference's own drawing with one thing
//! wrong, so that every failure is that thing's doing.

use refrast::{Draw, DrawError, Fragment, Rasterizer, Reference, SamplePattern, Topology};

use super::Bug;

/// Draws `draw` as the reference does, with `bug`.
pub fn rasterize(bug: Bug, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    draw.validate()?;
    let reference = Reference::default();
    let standard =
        || SamplePattern::standard(draw.samples).ok_or_else(|| DrawError::Unsupported(draw.describe()));
    let drawn = |pattern: &SamplePattern| {
        let mut out = Vec::new();
        reference.draw_with_pattern(draw, pattern, |f| out.push(f))?;
        Ok::<_, DrawError>(out)
    };
    match bug {
        Bug::BothEndsDrawn => Ok(with_last_pixels(draw, drawn(&standard()?)?, |_| true)),
        Bug::DoubledJoints => {
            let strip = draw.topology == Topology::LineStrip;
            let last = draw.primitive_count().saturating_sub(1);
            // Every segment of a strip but the last also draws its end: the next one's start.
            Ok(with_last_pixels(draw, drawn(&standard()?)?, |i| {
                strip && i < last
            }))
        }
        Bug::MirroredSamples => {
            let mirrored: Vec<[u8; 2]> = standard()?
                .positions()
                .iter()
                .map(|&[u, v]| [16 - u.max(1), v])
                .collect();
            drawn(&SamplePattern::new(&mirrored).map_err(DrawError::Unsupported)?)
        }
        Bug::OrderedGridSamples => {
            // The ordered grid many first multisampling chips used: n × n evenly spaced.
            let n = match draw.samples {
                1 => return drawn(&standard()?),
                2 | 4 => 2,
                _ => 4,
            };
            let step = 16 / n;
            let grid: Vec<[u8; 2]> = (0..n * n)
                .map(|i| [(i % n) * step + step / 2, (i / n) * step + step / 2])
                .take(usize::from(draw.samples))
                .collect();
            drawn(&SamplePattern::new(&grid).map_err(DrawError::Unsupported)?)
        }
        Bug::CentreOnlyCoverage => {
            // The centre's coverage, unmasked, copied to each sample the mask keeps.
            let mut centre = draw.clone().at_samples(1);
            centre.state.sample_mask = refrast::DrawState::ALL_SAMPLES;
            let mut out = Vec::new();
            reference.draw_with_pattern(&centre, &SamplePattern::standard(1).expect("one sample"), |f| {
                out.extend(
                    (0..draw.samples)
                        .filter(|&sample| draw.state.passes_sample_mask(sample))
                        .map(|sample| Fragment { sample, ..f }),
                );
            })?;
            Ok(out)
        }
        Bug::PixelBarycentrics => {
            let mut out = drawn(&standard()?)?;
            if !draw.topology.is_triangles() {
                return Ok(out);
            }
            // One set of weights per pixel and triangle: its first covered sample's.
            let mut first = std::collections::HashMap::new();
            for f in &out {
                first
                    .entry((f.x, f.y, f.primitive))
                    .or_insert((f.barycentric, f.screen_barycentric));
            }
            for f in &mut out {
                (f.barycentric, f.screen_barycentric) = first[&(f.x, f.y, f.primitive)];
            }
            Ok(out)
        }
        Bug::PixelDepth => {
            let mut out = drawn(&standard()?)?;
            // One depth per pixel and primitive: its first covered sample's, for every sample.
            let mut first: std::collections::HashMap<(u32, u32, u32), f32> = std::collections::HashMap::new();
            for f in &out {
                first.entry((f.x, f.y, f.primitive)).or_insert(f.depth);
            }
            for f in &mut out {
                f.depth = first[&(f.x, f.y, f.primitive)];
            }
            Ok(out)
        }
        Bug::RoundedPoints => {
            // Each point drawn in the pixel whose top-left corner is nearest, as `round(x)`
            // does, not in the pixel that holds it, as `floor(x)` does.
            let mut moved = draw.clone();
            if draw.topology == Topology::PointList {
                let (w, h) = (
                    f64::from(draw.viewport.width()),
                    f64::from(draw.viewport.height()),
                );
                for p in &mut moved.positions {
                    let pw = f64::from(p[3]);
                    let x = (f64::from(p[0]) / pw + 1.0) * 0.5 * w;
                    let y = (1.0 - f64::from(p[1]) / pw) * 0.5 * h;
                    let (rx, ry) = (x.round() + 0.5, y.round() + 0.5);
                    p[0] = ((rx / w * 2.0 - 1.0) * pw) as f32;
                    p[1] = ((1.0 - ry / h * 2.0) * pw) as f32;
                }
            }
            let mut out = Vec::new();
            reference.draw_with_pattern(&moved, &standard()?, |f| out.push(f))?;
            Ok(out)
        }
        _ => reference.clone().rasterize(draw),
    }
}

/// The reference's fragments plus, for each segment `i` with `also(i)`, the pixel holding its
/// last end when not drawn already.
fn with_last_pixels(draw: &Draw, mut out: Vec<Fragment>, also: impl Fn(usize) -> bool) -> Vec<Fragment> {
    if !draw.topology.is_lines() {
        return out;
    }
    let (w, h) = (
        f64::from(draw.viewport.width()),
        f64::from(draw.viewport.height()),
    );
    for i in (0..draw.primitive_count()).filter(|&i| also(i)) {
        let Some(&[_, b]) = draw.primitive(i).as_deref() else {
            continue;
        };
        let end = draw.positions[b as usize];
        if end[3] <= 0.0 {
            continue;
        }
        let x = (f64::from(end[0]) / f64::from(end[3]) + 1.0) * 0.5 * w;
        let y = (1.0 - f64::from(end[1]) / f64::from(end[3])) * 0.5 * h;
        if !(0.0..w).contains(&x) || !(0.0..h).contains(&y) {
            continue;
        }
        let (px, py) = (x as u32, y as u32);
        if out
            .iter()
            .any(|f| f.primitive == i as u32 && (f.x, f.y) == (px, py))
        {
            continue;
        }
        let state = &draw.state;
        let u = state
            .depth_range
            .window_depth(f64::from(end[2]), f64::from(end[3]));
        let depth = state
            .viewport_depth
            .fragment_depth(state.viewport_depth.window(u));
        // The end pixel as the line's own would be: inside the scissor, at the samples the mask
        // keeps.
        if !state.passes_scissor(px, py) {
            continue;
        }
        out.extend(
            (0..draw.samples)
                .filter(|&s| state.passes_sample_mask(s))
                .map(|sample| Fragment {
                    x: px,
                    y: py,
                    sample,
                    primitive: i as u32,
                    depth,
                    barycentric: [0.0, 1.0, 0.0],
                    flat: draw.provoking(i),
                    screen_barycentric: Some([0.0, 1.0, 0.0]),
                    front_facing: true,
                }),
        );
    }
    out
}
