//! The bugs of polygon modes: the reference drawing a triangle's edges or vertices with one
//! step of the mode wrong.

use refrast::stage::{FrontScratch, FrontSetup, front_end};
use refrast::{
    CullMode, Draw, DrawError, Fragment, PolygonMode, Rasterizer, Reference, ReferenceConfig, Topology,
    Traversal,
};

use super::Bug;

/// `draw` with its polygon mode drawn wrong by `bug`: `None` when `bug` is no polygon-mode
/// bug, or the draw is filled.
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    if draw.state.polygon_mode == PolygonMode::Fill || !draw.topology.is_triangles() {
        return None;
    }
    let mut reference = Reference::default();
    let with = |f: &dyn Fn(&mut Draw)| {
        let mut moved = draw.clone();
        f(&mut moved);
        moved
    };
    Some(match bug {
        // The mode declared but never honoured: triangles filled.
        Bug::FilledPolygonModes => reference.rasterize(&with(&|d| d.state.polygon_mode = PolygonMode::Fill)),
        // Culled after the triangle became lines or points, which nothing culls.
        Bug::UnculledPolygonModes => reference.rasterize(&with(&|d| d.state.cull = CullMode::None)),
        // Each fragment front-facing, as a line's or a point's is.
        Bug::FrontFacingPolygonModes => reference.rasterize(draw).map(|mut fragments| {
            fragments.iter_mut().for_each(|f| f.front_facing = true);
            fragments
        }),
        // The loop left open: the third edge (third corner to first) not drawn.
        Bug::OpenPolygonLoop if draw.state.polygon_mode == PolygonMode::Line => open_loop(draw),
        _ => return None,
    })
}

/// Each triangle the front end keeps drawn as a line list of its first two edges only, each
/// fragment then given the triangle's index, facing and flat vertex.
fn open_loop(draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
    draw.validate()?;
    let config = ReferenceConfig {
        traversal: Traversal::Viewport,
        ..ReferenceConfig::default()
    };
    let setup = FrontSetup::new(draw, config);
    let mut scratch = FrontScratch::default();
    let mut kept = Vec::new();
    let mut indices = Vec::new();
    for i in 0..setup.triangles.len() {
        if let Ok(k) = front_end(&setup, i, setup.corners(i).each_ref(), &mut scratch) {
            let [a, b, c] = setup.triangles[i];
            indices.extend([a, b, b, c]);
            kept.push((i, k.front_facing));
        }
    }
    let lines = Draw {
        topology: Topology::LineList,
        indices,
        state: refrast::DrawState {
            polygon_mode: PolygonMode::Fill,
            ..draw.state
        },
        ..draw.clone()
    };
    let mut fragments = Reference::new(config).rasterize(&lines)?;
    for f in &mut fragments {
        let (triangle, front_facing) = kept[f.primitive as usize / 2];
        f.primitive = triangle as u32;
        f.front_facing = front_facing;
        f.flat = draw.provoking(triangle);
    }
    Ok(fragments)
}
