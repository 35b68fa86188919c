//! The reference's draw statistics account for every triangle once, and for every fragment.

use refrast::{CullMode, Draw, DrawStats, Fragment, Rasterizer, Reference, ReferenceConfig, Viewport};

/// One triangle for each way a draw can end, in this order: a NaN, behind the eye, zero area,
/// culled (clockwise on screen, back faces culled), off the viewport, and two drawn.
fn every_outcome() -> Draw {
    let tri = |p: [[f32; 2]; 3], w: f32| p.map(|[x, y]| [x * w, y * w, 0.5 * w, w]);
    let ccw = [[-0.5, 0.5], [0.5, 0.5], [0.0, -0.5]];
    let cw = [[-0.5, 0.5], [0.0, -0.5], [0.5, 0.5]];
    let mut positions = Vec::new();
    positions.extend(tri(ccw, 1.0).map(|mut v| {
        v[0] = f32::NAN;
        v
    }));
    positions.extend(tri(ccw, -1.0));
    positions.extend(tri([[0.0, 0.0], [0.25, 0.25], [0.5, 0.5]], 1.0));
    positions.extend(tri(cw, 1.0));
    positions.extend(tri([[3.0, 3.0], [3.5, 3.0], [3.0, 3.5]], 1.0));
    positions.extend(tri(ccw, 1.0));
    positions.extend(tri([[-0.9, -0.9], [-0.1, -0.9], [-0.5, -0.2]], 2.0));
    let triangles = (0..7).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut draw = Draw::new(Viewport::new(16, 16).expect("16×16"), positions, triangles);
    draw.state.cull = CullMode::Back;
    draw
}

#[test]
fn every_triangle_is_counted_once_and_every_fragment_too() {
    let draw = every_outcome();
    let reference = Reference::new(ReferenceConfig::default());
    let mut emitted: Vec<Fragment> = Vec::new();
    let stats = reference.draw(&draw, |f| emitted.push(f)).expect("draws");
    let DrawStats {
        triangles,
        non_finite,
        clipped_away,
        degenerate,
        culled,
        off_screen,
        traversed,
        fragments,
    } = stats;
    assert_eq!(triangles, 7);
    assert_eq!(
        [
            non_finite,
            clipped_away,
            degenerate,
            culled,
            off_screen,
            traversed
        ],
        [1, 1, 1, 1, 1, 2],
        "{stats:?}"
    );
    assert_eq!(fragments, emitted.len());
    assert!(fragments > 1, "both drawn triangles cover samples");
    assert_eq!(emitted, Reference::default().rasterize(&draw).expect("draws"));
}

/// A reference reports the configuration it was made with (public API; nothing inside reads it).
#[test]
fn a_reference_keeps_its_configuration() {
    let config = ReferenceConfig {
        clip: refrast::ClipMode::Full,
        ..ReferenceConfig::default()
    };
    assert_eq!(Reference::new(config).config(), config);
}
