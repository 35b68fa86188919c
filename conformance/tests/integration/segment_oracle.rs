//! The reference's exact line and point coverage (`refrast::stage`) against the suite's oracle
//! (`oracle::segment`), written apart: on ends a quarter pixel apart or a grid step off, where
//! nearly every pixel is a tie of the diamond or the shape's outline, under every convention.

use proptest::prelude::*;
use refrast::{FillConvention, FixedPoint, LineRule, stage};
use refrast_conformance::oracle::segment;

/// Grid units per pixel (4 bits): the oracle's scale is 16 times this, the samples' sixteenths.
const ONE: i64 = 16;

/// A coordinate on quarter pixels (ties everywhere), or one grid step off one.
fn coordinate() -> impl Strategy<Value = i64> {
    prop_oneof![
        (0i64..40).prop_map(|q| q * ONE / 4),
        (0i64..40, -1i64..=1).prop_map(|(q, d)| q * ONE / 4 + d)
    ]
}

fn point() -> impl Strategy<Value = (i64, i64)> {
    (coordinate(), coordinate())
}

/// Every sample of the 12 × 12 pixels the coordinates reach, at the 16 standard positions.
fn samples() -> Vec<(i64, i64)> {
    let sixteen = refrast::SamplePattern::standard(16).expect("16 samples");
    let mut out = Vec::new();
    for py in 0..12 {
        for px in 0..12 {
            for &[u, v] in sixteen.positions() {
                out.push((px * ONE + i64::from(u), py * ONE + i64::from(v)));
            }
            out.push((px * ONE + ONE / 2, py * ONE + ONE / 2));
        }
    }
    out
}

fn fixed((x, y): (i64, i64)) -> FixedPoint {
    FixedPoint::new(x, y).expect("small coordinates")
}

/// The oracle's scale: 16 times the grid, so that sixteenths are grid points.
fn scaled((x, y): (i64, i64)) -> (i128, i128) {
    (i128::from(x) * 16, i128::from(y) * 16)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    /// The diamond-exit rule at every pixel centre, by the reference's candidates and by the
    /// oracle's separating axes.
    #[test]
    fn diamond_exit_agrees(a in point(), b in point()) {
        for py in 0..12 {
            for px in 0..12 {
                let c = (px * ONE + ONE / 2, py * ONE + ONE / 2);
                let reference = stage::diamond_exit(fixed(a), fixed(b), fixed(c), ONE / 2);
                let oracle = segment::diamond_exit(scaled(a), scaled(b), scaled(c), i128::from(ONE / 2) * 16);
                prop_assert_eq!(reference, oracle, "pixel ({}, {}) of {:?} → {:?}", px, py, a, b);
            }
        }
    }

    /// Rectangles, parallelograms and point squares at every sample, under a convention each case
    /// (each case tests some 2 500 samples).
    #[test]
    fn shapes_agree(a in point(), b in point(), fill in prop::sample::select(FillConvention::ALL.to_vec())) {
        let h = ONE / 2;
        for &s in &samples() {
            let reference = [
                stage::in_rectangle(fixed(a), fixed(b), fixed(s), h, fill),
                stage::in_parallelogram(fixed(a), fixed(b), fixed(s), h, fill),
            ];
            for (rule, reference) in [LineRule::Rectangle, LineRule::Parallelogram].into_iter().zip(reference) {
                let oracle = segment::line_covers(rule, scaled(a), scaled(b), scaled(s), i128::from(h) * 16, fill);
                prop_assert_eq!(reference, oracle, "{:?} {:?} sample {:?} of {:?} → {:?}", rule, fill, s, a, b);
            }
            let reference = stage::in_point_square(fixed(a), fixed(s), h, fill);
            let oracle = segment::point_covers(scaled(a), scaled(s), i128::from(h) * 16, fill);
            prop_assert_eq!(reference, oracle, "point {:?} {:?} sample {:?}", a, fill, s);
        }
    }
}

/// Regression (`refrast certify`, `reference-4bit`, `point.square.exact`, case 870): a point at
/// raster y = 16.0039 on a 16-pixel target lies below the view volume, and clipping discards
/// it, but 4 subpixel bits snap it onto the viewport's bottom edge. The oracle decided "in view"
/// on the snapped point and expected a fragment; it now decides in clip space, as clipping does.
#[test]
fn a_point_outside_the_view_volume_is_discarded_though_it_snaps_onto_the_edge() {
    use refrast::{ReferenceConfig, SubpixelBits};
    use refrast_conformance::{PrimitiveScene, Scene};
    use refrast_zoo::Named;
    let config = ReferenceConfig {
        subpixel_bits: SubpixelBits::new(4).expect("4 bits"),
        ..ReferenceConfig::default()
    };
    let mut four_bits = Named::new("reference-4bit", config);
    let case = PrimitiveScene {
        scene: Scene::new(16, 16, vec![[-0.995_605_47, -1.000_488_3, 0.0, 1.0]], Vec::new()),
        topology: refrast::Topology::PointList,
        indices: vec![0],
        samples: 1,
    };
    assert_eq!(
        refrast_conformance::rules::point::check_square_exact(&mut four_bits, &case),
        Ok(())
    );
}

/// Regression (`reference-4bit`, `line.strip.shared-end-once`, seed 33): a strip whose first
/// segment runs at 45° before snapping, and straight down after 4-bit snapping, followed by a
/// horizontal one. The rule took both for x-major left-to-right by their unsnapped ends and
/// called the shared pixel a duplicate; it now classifies the snapped ends, and leaves out a
/// joint that a grid step or two could reclassify.
#[test]
fn a_strip_is_classified_by_its_snapped_ends() {
    use refrast::{ReferenceConfig, SubpixelBits};
    use refrast_conformance::{PrimitiveScene, Scene};
    use refrast_zoo::Named;
    let config = ReferenceConfig {
        subpixel_bits: SubpixelBits::new(4).expect("4 bits"),
        ..ReferenceConfig::default()
    };
    let mut four_bits = Named::new("reference-4bit", config);
    let positions = vec![
        [-0.566_406_25, 0.883_789_06, 0.0, 1.0],
        [-0.561_523_44, 0.878_906_25, 0.0, 1.0],
        [-0.542_480_47, 0.878_906_25, 0.0, 1.0],
    ];
    let case = PrimitiveScene {
        scene: Scene::new(16, 16, positions, Vec::new()),
        topology: refrast::Topology::LineStrip,
        indices: vec![0, 1, 2],
        samples: 1,
    };
    assert_eq!(
        refrast_conformance::rules::line::check_shared_end_once(&mut four_bits, &case),
        Ok(())
    );
}
