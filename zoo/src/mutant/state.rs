//! The bugs of the draw state the contract gained after its first rasterizers (the scissor,
//! the sample mask, culling of both faces, strips and fans, flat values, the depth range and clamp, depth bias, polygon modes, clip and cull distances, so far): the reference's own drawing with that state
//! applied wrong in one way, so that every failure is that bug's doing.

use refrast::{
    CullMode, Draw, DrawError, DrawState, Fragment, ProvokingVertex, Rasterizer, Reference, Resolved,
    Scissor, Topology, ViewportDepth,
};

use super::Bug;

/// Draws `draw` as the reference does, with `bug`.
pub fn rasterize(bug: Bug, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    if let Some(biased) = super::bias::rasterize(bug, draw) {
        return biased;
    }
    if let Some(moded) = super::polygon::rasterize(bug, draw) {
        return moded;
    }
    if let Some(distanced) = super::distance::rasterize(bug, draw) {
        return distanced;
    }
    if let Some(masked) = super::sample_mask::rasterize(bug, draw) {
        return masked;
    }
    if let Some(misplaced) = super::centroid::rasterize(bug, draw) {
        return misplaced;
    }
    if let Some(wrong) = super::conservative::rasterize(bug, draw) {
        return wrong;
    }
    let mut reference = Reference::default();
    if let Some(assembled) = misassembled(bug, draw) {
        // The list's flat values are its own; the strip's are what its bug leaves alone.
        let mut fragments = reference.rasterize(&assembled)?;
        for f in &mut fragments {
            f.flat = draw.provoking(f.primitive as usize);
        }
        return Ok(fragments);
    }
    if matches!(bug, Bug::LastCornerFlat | Bug::ClippedFlat | Bug::FirstOnlyFlat) {
        let mut fragments = reference.rasterize(draw)?;
        for f in &mut fragments {
            f.flat = misprovoked(bug, draw, f.primitive as usize);
        }
        return Ok(fragments);
    }
    if let Some(moved) = misranged(bug, draw) {
        return reference.rasterize(&moved);
    }
    // The culling bugs first: no rule draws both faces culled with a scissor, so neither kind
    // of bug hides the other.
    if draw.state.cull == CullMode::FrontAndBack {
        return match bug {
            // Both faces taken as the front one: back faces drawn.
            Bug::FrontOnlyForBoth => {
                let mut front = draw.clone();
                front.state.cull = CullMode::Front;
                reference.rasterize(&front)
            }
            // Every primitive culled, lines and points too.
            Bug::BothCullsLines => Ok(Vec::new()),
            _ => reference.rasterize(draw),
        };
    }
    let Some(scissor) = draw.state.scissor else {
        return reference.rasterize(draw);
    };
    let with = |scissor: Option<Scissor>| {
        let mut moved = draw.clone();
        moved.state.scissor = scissor;
        moved
    };
    match bug {
        // `x ≤ column ≤ x + width`: one column and one row too many.
        Bug::InclusiveScissor => reference.rasterize(&with(Some(Scissor {
            width: scissor.width.saturating_add(1),
            height: scissor.height.saturating_add(1),
            ..scissor
        }))),
        // The scissor as a clamp of the triangles' traversal only: lines and points ignore it.
        Bug::TrianglesOnlyScissor if !draw.topology.is_triangles() => reference.rasterize(&with(None)),
        // Rows counted from the bottom, as OpenGL's window coordinates count them, not flipped.
        Bug::BottomUpScissor => {
            let height = i64::from(draw.viewport.height());
            let top = height - i64::from(scissor.y) - i64::from(scissor.height);
            let rows = i64::from(scissor.height) + top.min(0);
            reference.rasterize(&with(Some(Scissor {
                y: u32::try_from(top.max(0)).unwrap_or(u32::MAX),
                height: u32::try_from(rows.max(0)).unwrap_or(0),
                ..scissor
            })))
        }
        _ => reference.rasterize(draw),
    }
}

/// Resolves `draw` as the reference does, with `bug`.
pub fn resolve(bug: Bug, draw: &Draw) -> Result<Resolved, DrawError> {
    if let Some(biased) = super::bias::resolve(bug, draw) {
        return biased;
    }
    let cut = Resolved::from_fragments(draw, rasterize(bug, draw)?);
    let mut whole = draw.clone();
    match bug {
        Bug::DepthPastScissor if draw.state.scissor.is_some() => whole.state.scissor = None,
        Bug::DepthPastSampleMask if draw.state.sample_mask != DrawState::ALL_SAMPLES => {
            whole.state.sample_mask = DrawState::ALL_SAMPLES;
        }
        _ => return Ok(cut),
    }
    // The scissor or mask keeps colour (here, the primitive buffer) but the depth test writes
    // depth everywhere the draw without it covers.
    let written = Resolved::from_fragments(&whole, rasterize(bug, &whole)?);
    Ok(Resolved {
        depth: written.depth,
        ..cut
    })
}

/// `draw` with its depth range or depth clipping applied wrong by `bug`; `None` for other bugs.
fn misranged(bug: Bug, draw: &Draw) -> Option<Draw> {
    let mut moved = draw.clone();
    let range = draw.state.viewport_depth;
    match bug {
        Bug::IgnoredViewportDepth => moved.state.viewport_depth = ViewportDepth::FULL,
        Bug::SortedDepthRange => {
            moved.state.viewport_depth = ViewportDepth {
                min: range.min.min(range.max),
                max: range.min.max(range.max),
            };
        }
        Bug::NearClippedAnyway => moved.state.clip_near = true,
        _ => return None,
    }
    Some(moved)
}

/// A strip or fan assembled into triangles wrong by `bug`, as the triangle list it then draws
/// (primitive `i` is still the draw's triangle `i`); `None` for other bugs and topologies.
fn misassembled(bug: Bug, draw: &Draw) -> Option<Draw> {
    let strip_or_fan = matches!(draw.topology, Topology::TriangleStrip | Topology::TriangleFan);
    let list = match bug {
        Bug::UnalternatedStrip if draw.topology == Topology::TriangleStrip => {
            draw.indices.windows(3).flatten().copied().collect()
        }
        Bug::ShortStrip if strip_or_fan => {
            let mut triangles = draw.triangles().into_owned();
            triangles.pop();
            triangles.into_flattened()
        }
        Bug::FanAsStrip if draw.topology == Topology::TriangleFan => {
            Draw {
                topology: Topology::TriangleStrip,
                ..draw.clone()
            }
            .as_triangle_list()
            .indices
        }
        _ => return None,
    };
    Some(Draw {
        topology: Topology::TriangleList,
        indices: list,
        ..draw.clone()
    })
}

/// The vertex whose flat values primitive `i` takes under `bug`.
fn misprovoked(bug: Bug, draw: &Draw, i: usize) -> Option<u32> {
    let right = draw.provoking(i);
    if bug == Bug::FirstOnlyFlat {
        let mut first = draw.clone();
        first.state.provoking_vertex = ProvokingVertex::First;
        return first.provoking(i);
    }
    let Some(corners) = draw.triangle(i) else {
        return right;
    };
    match bug {
        Bug::LastCornerFlat if draw.state.provoking_vertex == ProvokingVertex::Last => Some(corners[2]),
        Bug::ClippedFlat => {
            // Before the near plane: w ≤ 0, or z below the clip volume's near bound.
            let cut = |v: u32| {
                draw.positions.get(v as usize).is_none_or(|&[_, _, z, w]| {
                    let near = match draw.state.depth_range {
                        refrast::DepthRange::ZeroToOne => z,
                        refrast::DepthRange::NegativeOneToOne => z + w,
                    };
                    w <= 0.0 || near < 0.0
                })
            };
            match right {
                Some(v) if cut(v) => corners.into_iter().find(|&c| !cut(c)).or(right),
                _ => right,
            }
        }
        _ => right,
    }
}
