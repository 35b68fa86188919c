//! The bugs of clip and cull distances: the reference drawing a draw's distances with one step
//! wrong.

use refrast::{Distances, Draw, DrawError, Fragment, Rasterizer, Reference};

use super::Bug;

/// What the epsilon bug compares each clip distance with: `2^-10`, a tolerance a shader writer
/// might reach for.
const EPSILON: f32 = 1.0 / 1024.0;

/// `draw` with its distances drawn wrong by `bug`: `None` when `bug` is no distance bug, or the
/// draw has none.
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    let d = &draw.distances;
    if d.is_empty() {
        return None;
    }
    let mut reference = Reference::default();
    let with = |distances: Distances| Draw {
        distances,
        ..draw.clone()
    };
    // Each clip distance replaced by `f(value, vertex)`.
    let each_clip = |f: &dyn Fn(f32, usize) -> f32| {
        let mut moved = d.clone();
        let n = d.per_vertex();
        for (i, value) in moved.values.iter_mut().enumerate() {
            if i % n < d.clip {
                *value = f(*value, i / n);
            }
        }
        moved
    };
    Some(match bug {
        // Declared, never honoured.
        Bug::IgnoredClipDistances => reference.rasterize(&with(d.truncated(0, d.cull))),
        // Interpolated linearly in screen space: the perspective-correct cut of d·w is the
        // screen-linear cut of d.
        Bug::ScreenLinearClipDistances => reference.rasterize(&with(each_clip(&|v, vertex| {
            v * draw.positions.get(vertex).map_or(1.0, |p| p[3])
        }))),
        // Kept only where a distance exceeds a small epsilon: a sliver along each cut is lost to
        // both a draw and its complement.
        Bug::EpsilonClipDistances => reference.rasterize(&with(each_clip(&|v, _| v - EPSILON))),
        // Honoured on triangles, ignored on lines and points.
        Bug::TrianglesOnlyClipDistances if !draw.topology.is_triangles() => {
            reference.rasterize(&with(d.truncated(0, d.cull)))
        }
        // A primitive culled when any vertex, not every one, is negative in a cull distance.
        Bug::AnyVertexCulls => any_vertex_culls(draw),
        _ => return None,
    })
}

/// The reference's draw without cull distances, less every primitive with some vertex negative
/// in one of them.
fn any_vertex_culls(draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    let d = &draw.distances;
    let culled: Vec<bool> = (0..draw.primitive_count())
        .map(|i| {
            draw.primitive(i)
                .is_some_and(|corners| (0..d.cull).any(|j| corners.iter().any(|&v| d.cull_of(v)[j] < 0.0)))
        })
        .collect();
    let unculled = Draw {
        distances: d.truncated(d.clip, 0),
        ..draw.clone()
    };
    let mut fragments = Reference::default().rasterize(&unculled)?;
    fragments.retain(|f| !culled.get(f.primitive as usize).copied().unwrap_or(false));
    Ok(fragments)
}
