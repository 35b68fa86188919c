//! Facing from the snapped signed area, front-face choice, cull modes, zero-area triangles.

use crate::support;

use refrast::{CullMode, FixedPoint, FrontFace, Reference, Winding, orient2d};
use support::{fragments, raster_draw};

/// Clockwise on screen (y down): top left, top right, bottom.
const CW: [(f64, f64); 3] = [(1.0, 1.0), (7.0, 1.0), (4.0, 7.0)];
const CCW: [(f64, f64); 3] = [(1.0, 1.0), (4.0, 7.0), (7.0, 1.0)];

#[test]
fn winding_comes_from_the_sign_of_orient2d() {
    let p = |(x, y): (f64, f64)| FixedPoint::new(x as i64, y as i64).unwrap();
    assert_eq!(
        Winding::from_area2(orient2d(p(CW[0]), p(CW[1]), p(CW[2]))),
        Winding::Clockwise
    );
    assert_eq!(
        Winding::from_area2(orient2d(p(CCW[0]), p(CCW[1]), p(CCW[2]))),
        Winding::CounterClockwise
    );
    assert_eq!(Winding::from_area2(0), Winding::Degenerate);
}

#[test]
fn front_facing_follows_the_front_face_setting() {
    for (triangle, is_cw) in [(CW, true), (CCW, false)] {
        for (front_face, front_is_cw) in [(FrontFace::Clockwise, true), (FrontFace::CounterClockwise, false)]
        {
            let mut draw = raster_draw(8, &[triangle]);
            draw.state.front_face = front_face;
            let frags = fragments(&draw);
            assert!(!frags.is_empty());
            assert!(
                frags.iter().all(|f| f.front_facing == (is_cw == front_is_cw)),
                "{front_face:?}"
            );
        }
    }
}

#[test]
fn cull_modes_discard_the_named_facing() {
    for triangle in [CW, CCW] {
        for front_face in [FrontFace::Clockwise, FrontFace::CounterClockwise] {
            let mut draw = raster_draw(8, &[triangle]);
            draw.state.front_face = front_face;
            let front = fragments(&draw)[0].front_facing;
            for (cull, drawn) in [
                (CullMode::None, true),
                (CullMode::Front, !front),
                (CullMode::Back, front),
            ] {
                draw.state.cull = cull;
                let stats = Reference::default().draw(&draw, |_| {}).unwrap();
                assert_eq!(stats.fragments > 0, drawn, "{cull:?} {front_face:?}");
                assert_eq!(stats.culled, usize::from(!drawn));
            }
        }
    }
}

#[test]
fn winding_reversal_keeps_coverage() {
    let mut a: Vec<_> = fragments(&raster_draw(8, &[CW]))
        .iter()
        .map(|f| (f.x, f.y))
        .collect();
    let mut b: Vec<_> = fragments(&raster_draw(8, &[CCW]))
        .iter()
        .map(|f| (f.x, f.y))
        .collect();
    a.sort_unstable();
    b.sort_unstable();
    assert_eq!(a, b);
}

#[test]
fn zero_area_triangles_draw_nothing_under_any_cull_mode() {
    let degenerate = [
        [(1.0, 1.0), (4.0, 4.0), (7.0, 7.0)], // collinear through sample centres
        [(2.5, 2.5), (2.5, 2.5), (6.5, 3.5)], // repeated vertex
        [(3.0, 3.0), (3.0, 3.0), (3.0, 3.0)], // a point
        [(1.0, 1.0), (1.0 + 1e-4, 1.0), (5.0, 1.0)], // becomes collinear once snapped
    ];
    for triangle in degenerate {
        for cull in [CullMode::None, CullMode::Front, CullMode::Back] {
            let mut draw = raster_draw(8, &[triangle]);
            draw.state.cull = cull;
            let stats = Reference::default()
                .draw(&draw, |f| panic!("{triangle:?} drew {f:?}"))
                .unwrap();
            assert_eq!(stats.degenerate, 1, "{triangle:?}");
        }
    }
}
