//! The provoking vertex, as the specifications' tables give it: which vertex of the index
//! stream a primitive takes its flat values from. Written apart from the reference's
//! `Draw::provoking`, so that a wrong table cannot hide behind its own replay.

use refrast::{Draw, ProvokingVertex, Topology};

/// The positions in the index stream of primitive `i`'s first and last vertex: Vulkan's
/// topology sections (its provoking vertex under each mode of `VK_EXT_provoking_vertex`),
/// OpenGL 4.6's Table 13.2 and OpenGL ES 3.2's Table 12.3 (there counted from 1).
fn first_and_last(topology: Topology, i: usize) -> (usize, usize) {
    match topology {
        Topology::PointList => (i, i),
        Topology::LineList => (2 * i, 2 * i + 1),
        Topology::LineStrip => (i, i + 1),
        Topology::TriangleList => (3 * i, 3 * i + 2),
        Topology::TriangleStrip => (i, i + 2),
        // The hub, vertex 0, provokes under neither mode.
        Topology::TriangleFan => (i + 1, i + 2),
    }
}

/// The vertex (an index into the draw's positions) whose flat values primitive `i` carries
/// under the draw's mode; `None` past the draw's indices.
#[must_use]
pub fn provoking_vertex(draw: &Draw, i: usize) -> Option<u32> {
    let (first, last) = first_and_last(draw.topology, i);
    let at = match draw.state.provoking_vertex {
        ProvokingVertex::First => first,
        ProvokingVertex::Last => last,
    };
    draw.indices.get(at).copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use refrast::Viewport;

    /// OpenGL 4.6's Table 13.2, counted from 1 there: a strip's triangle i (from 1) is provoked
    /// by vertex i (first) or i + 2 (last), a fan's by i + 1 or i + 2.
    #[test]
    fn the_tables_rows() {
        let vp = Viewport::new(4, 4).expect("4×4");
        let mut draw = Draw::of(vp, vec![[0.0; 4]; 6], Topology::TriangleFan, vec![5, 4, 3, 2, 1]);
        assert_eq!(provoking_vertex(&draw, 0), Some(4));
        draw.state.provoking_vertex = ProvokingVertex::Last;
        assert_eq!(provoking_vertex(&draw, 2), Some(1));
        draw.topology = Topology::TriangleStrip;
        assert_eq!(provoking_vertex(&draw, 1), Some(2));
        draw.topology = Topology::LineList;
        assert_eq!(provoking_vertex(&draw, 1), Some(2));
        assert_eq!(provoking_vertex(&draw, 2), None);
    }
}
