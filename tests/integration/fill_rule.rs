//! The top-left rule on hand-made triangles whose edges and vertices lie on pixel centres.
//!
//! Coordinates are in pixels; samples sit at `k + ½`, so every vertex below is on a sample.

use crate::support;

use refrast::{FillConvention, FixedPoint, is_top_left};
use support::{pixels, raster_draw};

fn p(x: i64, y: i64) -> FixedPoint {
    FixedPoint::new(x, y).unwrap()
}

#[test]
fn edge_classification_follows_d3d11() {
    // Clockwise on screen (y down): top edges run right, left edges run up.
    assert!(is_top_left(p(0, 0), p(4, 0)), "flat top");
    assert!(!is_top_left(p(4, 4), p(0, 4)), "flat bottom");
    assert!(is_top_left(p(0, 4), p(0, 0)), "vertical left");
    assert!(!is_top_left(p(4, 0), p(4, 4)), "vertical right");
    assert!(is_top_left(p(0, 4), p(3, 0)), "slanted left");
    assert!(!is_top_left(p(3, 0), p(5, 4)), "slanted right");
}

#[test]
fn flat_top_owns_its_top_and_left_samples() {
    // Right angle at the top left: top edge y = ½, left edge x = ½, hypotenuse x + y = 5.
    let got = pixels(&raster_draw(8, &[[(0.5, 0.5), (4.5, 0.5), (0.5, 4.5)]]));
    // Covered: x + y < 4 (the hypotenuse is a right edge and keeps nothing).
    let want: Vec<_> = (0..8u32)
        .flat_map(|y| (0..8u32).map(move |x| (x, y)))
        .filter(|(x, y)| x + y < 4)
        .collect();
    assert_eq!(got, want);
    assert!(got.contains(&(0, 0)), "vertex on top and left edges is covered");
    assert!(!got.contains(&(4, 0)), "vertex on top and right edges is not");
    assert!(!got.contains(&(0, 4)), "vertex on left and right edges is not");
}

#[test]
fn flat_bottom_keeps_nothing_of_its_bottom_edge() {
    // Left edge x = ½ (up), bottom edge y = 4½ (not owned), hypotenuse y = x (a right edge).
    let got = pixels(&raster_draw(8, &[[(0.5, 0.5), (4.5, 4.5), (0.5, 4.5)]]));
    assert_eq!(got, vec![(0, 1), (0, 2), (1, 2), (0, 3), (1, 3), (2, 3)]);
}

#[test]
fn two_left_edges_meeting_at_a_sample_cover_it() {
    // Leftmost vertex (½, 3½) between two left edges; the right side is the vertical x = 4½.
    let got = pixels(&raster_draw(8, &[[(4.5, 0.5), (4.5, 6.5), (0.5, 3.5)]]));
    assert!(got.contains(&(0, 3)), "vertex where two left edges meet");
    assert!(
        got.iter().all(|&(x, _)| x < 4),
        "the right edge x = 4½ keeps nothing"
    );
    assert!(!got.contains(&(4, 0)) && !got.contains(&(4, 6)));
}

#[test]
fn one_left_edge_and_two_right_edges() {
    // The mirror image: left edge x = ½ owns its samples, the right vertex (4½, 3½) is lost.
    let got = pixels(&raster_draw(8, &[[(0.5, 0.5), (4.5, 3.5), (0.5, 6.5)]]));
    assert!(!got.contains(&(4, 3)), "vertex where two right edges meet");
    assert!((1..6).all(|y| got.contains(&(0, y))), "left edge samples");
    // Both ends of the left edge are also on a right edge (the upper one runs down-right).
    assert!(
        !got.contains(&(0, 0)),
        "top vertex: the left edge meets a right edge"
    );
    assert!(
        !got.contains(&(0, 6)),
        "bottom vertex: the left edge meets a right edge"
    );
}

#[test]
fn a_square_split_either_way_covers_each_sample_once() {
    for diagonal in [
        [
            [(0.5, 0.5), (6.5, 0.5), (6.5, 6.5)],
            [(0.5, 0.5), (6.5, 6.5), (0.5, 6.5)],
        ],
        [
            [(6.5, 0.5), (6.5, 6.5), (0.5, 6.5)],
            [(0.5, 0.5), (6.5, 0.5), (0.5, 6.5)],
        ],
    ] {
        let mut got = pixels(&raster_draw(8, &diagonal));
        let n = got.len();
        got.dedup();
        assert_eq!(got.len(), n, "a sample was covered twice");
        // The square [½, 6½]² owns its top and left sides: 6 × 6 samples.
        assert_eq!(n, 36);
    }
}

#[test]
fn every_convention_is_watertight_on_a_fan() {
    // Eight triangles around (4½, 4½): every edge passes through samples.
    let ring = [
        (0.5, 0.5),
        (4.5, 0.5),
        (8.5, 0.5),
        (8.5, 4.5),
        (8.5, 8.5),
        (4.5, 8.5),
        (0.5, 8.5),
        (0.5, 4.5),
    ];
    let centre = (4.5, 4.5);
    let fan: Vec<_> = (0..8).map(|i| [centre, ring[i], ring[(i + 1) % 8]]).collect();
    let draw = raster_draw(16, &fan);
    for fill in FillConvention::ALL {
        let config = refrast::ReferenceConfig {
            fill,
            ..Default::default()
        };
        let mut counts = vec![0u32; 16 * 16];
        refrast::Reference::new(config)
            .draw(&draw, |f| counts[(f.y * 16 + f.x) as usize] += 1)
            .unwrap();
        // Counted per sample: none twice, and the 8 × 8 square (which owns two of its four sides
        // under any convention) has exactly 64 covered.
        assert!(counts.iter().all(|&c| c <= 1), "{fill:?}: a sample covered twice");
        assert_eq!(counts.iter().filter(|&&c| c == 1).count(), 64, "{fill:?}");
    }
}
