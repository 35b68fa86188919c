//! Centroid interpolation's bugs: the reference's fragments with each pixel's barycentrics
//! taken at another location than the centroid.

use std::collections::HashMap;

use refrast::{Draw, DrawError, DrawState, Fragment, Interpolation, PolygonMode, Rasterizer, Reference};

use super::Bug;

/// A pixel of a primitive: column, row, primitive.
type Key = (u32, u32, u32);

/// `draw` as the reference draws it with `bug`'s centroid, `None` for a bug elsewhere or a draw
/// centroid changes nothing in (one sample, lines, points, a polygon mode, at the sample).
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    let bugs = [
        Bug::CentreCentroid,
        Bug::IgnoredCentroid,
        Bug::FirstSampleCentroid,
        Bug::UnmaskedCentroid,
        Bug::PostMaskCentroid,
    ];
    // (The centre of a partly covered pixel is computed from the unsnapped corners: off the
    // snapped one by far less than it is off the centroid, and only where the bug is.)
    let applies = draw.state.interpolation == Interpolation::Centroid
        && draw.topology.is_triangles()
        && draw.samples > 1
        && draw.state.polygon_mode == PolygonMode::Fill;
    (applies && bugs.contains(&bug)).then(|| misplaced(bug, draw))
}

/// The reference's centroid fragments of `draw`, each pixel's barycentrics moved as `bug` says.
fn misplaced(bug: Bug, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let mut reference = Reference::default();
    let mut at_sample = draw.clone();
    at_sample.state.interpolation = Interpolation::Sample;
    if bug == Bug::IgnoredCentroid {
        return reference.rasterize(&at_sample);
    }
    let mut unmasked = at_sample.clone();
    unmasked.state.sample_mask = DrawState::ALL_SAMPLES;
    // Each pixel's covered samples (before the mask) and its first covered sample's weights.
    let mut covered: HashMap<Key, (u32, [f32; 3])> = HashMap::new();
    for f in reference.rasterize(&unmasked)? {
        let pixel = covered
            .entry((f.x, f.y, f.primitive))
            .or_insert((0, f.barycentric));
        pixel.0 |= 1 << f.sample;
    }
    let mut first_kept: HashMap<Key, [f32; 3]> = HashMap::new();
    for f in reference.rasterize(&at_sample)? {
        first_kept.entry((f.x, f.y, f.primitive)).or_insert(f.barycentric);
    }
    let all = (1u32 << draw.samples) - 1;
    let kept = draw.state.sample_mask & all;
    let mut out = reference.rasterize(draw)?;
    for f in &mut out {
        let key = (f.x, f.y, f.primitive);
        let (cover, first) = covered[&key];
        let centre = || centre_barycentrics(draw, key).unwrap_or(f.barycentric);
        f.barycentric = match bug {
            // Where every sample is covered the centroid is the centre already.
            Bug::CentreCentroid if cover != all => centre(),
            Bug::FirstSampleCentroid => first_kept[&key],
            Bug::UnmaskedCentroid if cover != all => first,
            Bug::PostMaskCentroid if cover != all && cover & kept == kept => centre(),
            _ => f.barycentric,
        };
    }
    Ok(out)
}

/// The perspective-correct barycentrics of triangle `key.2` at the centre of pixel
/// `(key.0, key.1)`, inside it or not, from its unsnapped projected corners: `None` for a
/// corner at `w ≤ 0` or a triangle of no area on the screen.
fn centre_barycentrics(draw: &Draw, key: Key) -> Option<[f32; 3]> {
    let corners = draw.triangle(key.2 as usize)?;
    let (width, height) = (
        f64::from(draw.viewport.width()),
        f64::from(draw.viewport.height()),
    );
    let clip = corners.map(|i| draw.positions.get(i as usize).map(|p| p.map(f64::from)));
    let mut screen = [[0.0; 2]; 3];
    let mut w = [0.0; 3];
    for k in 0..3 {
        let p = clip[k]?;
        if p[3] <= 0.0 {
            return None;
        }
        screen[k] = [
            (p[0] / p[3] + 1.0) * 0.5 * width,
            (1.0 - p[1] / p[3]) * 0.5 * height,
        ];
        w[k] = p[3];
    }
    let c = [f64::from(key.0) + 0.5, f64::from(key.1) + 0.5];
    let area =
        |a: [f64; 2], b: [f64; 2], p: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    let whole = area(screen[0], screen[1], screen[2]);
    if whole == 0.0 {
        return None;
    }
    let s = [
        area(screen[1], screen[2], c) / whole,
        area(screen[2], screen[0], c) / whole,
        area(screen[0], screen[1], c) / whole,
    ];
    let q: [f64; 3] = std::array::from_fn(|k| s[k] / w[k]);
    let sum: f64 = q.iter().sum();
    Some(q.map(|v| (v / sum) as f32))
}
