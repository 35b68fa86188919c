//! Seed 003's visibility algorithms, each on the cases the notes teach: the painter's algorithm,
//! the scanline z-buffer and area averaging (`zoo/src/course/`), and what certification says of
//! each where it differs from a z-buffer.

use refrast::{CompareOp, Draw, Rasterizer, Reference, Resolved, Viewport};
use refrast_conformance::{Options, Status, certify};
use refrast_zoo::course::area_average::{covered_count, covered_part};
use refrast_zoo::course::painter::painting_order;
use refrast_zoo::course::scanline::intercepts;
use refrast_zoo::course::{AreaAverage, Painter, ScanlineZBuffer};

/// Triangles given in NDC at `w = 1`, each vertex `[x, y, z]`, on a square target.
fn ndc_draw(side: u32, triangles: &[[[f32; 3]; 3]]) -> Draw {
    let viewport = Viewport::new(side, side).expect("a valid size");
    let positions = triangles
        .iter()
        .flatten()
        .map(|p| [p[0], p[1], p[2], 1.0])
        .collect();
    let indices = (0..triangles.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Draw::new(viewport, positions, indices)
}

/// The status one rule gets on `r` at its default cases.
fn verdict(r: &mut dyn Rasterizer, rule: &str) -> Status {
    let options = Options {
        rules: vec![rule.to_owned()],
        ..Options::default()
    };
    let report = certify(r, &options, |_| {});
    report.rules.first().map(|r| r.status).expect("the rule ran")
}

/// Pixels where each primitive is kept.
fn kept(resolved: &Resolved, primitive: u32) -> usize {
    resolved
        .primitive
        .iter()
        .filter(|&&p| p == Some(primitive))
        .count()
}

/// A big far triangle, then a small near one inside it, submitted near first.
fn nested() -> Draw {
    ndc_draw(
        16,
        &[
            [[-0.4, 0.4, 0.2], [-0.4, -0.4, 0.2], [0.4, 0.4, 0.2]],
            [[-1.0, 1.0, 0.8], [-1.0, -1.0, 0.8], [1.0, 1.0, 0.8]],
        ],
    )
}

/// A level triangle and one tilted in depth along x, passing through it at x = 0.
fn intersecting() -> Draw {
    ndc_draw(
        32,
        &[
            [[-0.8, 0.8, 0.5], [-0.8, -0.8, 0.5], [0.8, 0.0, 0.5]],
            [[-0.8, 0.0, 0.1], [0.8, 0.8, 0.9], [0.8, -0.8, 0.9]],
        ],
    )
}

#[test]
fn painter_paints_back_to_front() {
    let draw = nested();
    // Farthest vertex first: the big triangle (0.8), then the small one (0.2).
    assert_eq!(painting_order(&draw), [1, 0]);
    let painted = Painter.resolve(&draw).expect("a valid draw");
    let z_buffer = Reference::default().resolve(&draw).expect("a valid draw");
    // Without intersections or cycles the painter's picture is the z-buffer's.
    assert_eq!(painted, z_buffer);
    assert!(kept(&painted, 0) > 0 && kept(&painted, 1) > 0);
}

#[test]
fn painter_cannot_draw_intersecting_triangles() {
    let draw = intersecting();
    let painted = Painter.resolve(&draw).expect("a valid draw");
    let z_buffer = Reference::default().resolve(&draw).expect("a valid draw");
    // The tilted triangle (1) is nearer left of x = 0 (columns 0–15), the level one (0) right of
    // it. The painter paints the tilted one first (its farthest vertex, 0.9, is the farther) and
    // the level one over all of it.
    let count = |left: bool, z: u32, painter: u32| {
        (0..z_buffer.primitive.len())
            .filter(|&i| (i % 32 < 16) == left)
            .filter(|&i| z_buffer.primitive[i] == Some(z) && painted.primitive[i] == Some(painter))
            .count()
    };
    assert!(
        count(true, 1, 0) > 20,
        "the level triangle painted over the nearer tilted one"
    );
    assert_eq!(
        count(false, 1, 0),
        0,
        "right of x = 0 the level one is nearer and kept by both"
    );
    assert!(kept(&painted, 1) < kept(&z_buffer, 1));
    assert_eq!(
        verdict(&mut Painter, "depth.intersecting.nearest-wins"),
        Status::Fail
    );
    assert_eq!(
        verdict(&mut Reference::default(), "depth.intersecting.nearest-wins"),
        Status::Pass
    );
}

#[test]
fn scanline_spans_are_half_open() {
    // A row centre on a vertex: the edge starting there counts, the edge ending there does not.
    let triangle = [[2.0, 1.5], [6.0, 5.5], [0.0, 5.5]];
    assert_eq!(intercepts(&triangle, 1.5), None);
    assert_eq!(intercepts(&triangle, 3.5), Some((1.0, 4.0)));
    // The bottom edge (y = 5.5) owns no row.
    assert_eq!(intercepts(&triangle, 5.5), None);
}

#[test]
fn scanline_zbuffer_matches_the_full_zbuffer_on_its_own_fragments() {
    for draw in [nested(), intersecting()] {
        let mut lab = ScanlineZBuffer;
        let one_row = lab.resolve(&draw).expect("a valid draw");
        let full = Resolved::from_fragments(&draw, lab.rasterize(&draw).expect("a valid draw"));
        assert_eq!(one_row, full);
    }
}

#[test]
fn scanline_zbuffer_tests_rows_in_active_list_order() {
    // Under Always the last primitive in API order should win; the active list orders faces by
    // their top row, so the face starting higher is tested first and the lower one wins.
    let mut draw = ndc_draw(
        16,
        &[
            [[-1.0, 0.0, 0.5], [-1.0, -1.0, 0.5], [1.0, 0.0, 0.5]],
            [[-1.0, 1.0, 0.5], [-1.0, -1.0, 0.5], [1.0, 1.0, 0.5]],
        ],
    );
    draw.state.depth.compare = CompareOp::Always;
    let got = ScanlineZBuffer.resolve(&draw).expect("a valid draw");
    let want = Resolved::from_fragments(&draw, ScanlineZBuffer.rasterize(&draw).expect("a valid draw"));
    let differ = (0..got.primitive.len())
        .filter(|&i| got.primitive[i] != want.primitive[i])
        .count();
    assert!(differ > 0, "the overlap goes to the API's last primitive");
    assert_eq!(
        verdict(&mut ScanlineZBuffer, "depth.resolve.matches-fragments"),
        Status::Fail
    );
}

#[test]
fn area_average_measures_the_covered_part() {
    let whole = [[-1.0, -1.0], [5.0, -1.0], [-1.0, 5.0]];
    assert_eq!(covered_part(&whole, 0, 0), Some((1.0, [0.5, 0.5])));
    // The left half of pixel (0, 0): the rectangle x in [0, 0.5].
    let left = [[-1.0, -1.0], [0.5, -1.0], [0.5, 3.0], [-1.0, 3.0]];
    let (area, centroid) = covered_part(&left, 0, 0).expect("half covered");
    assert!((area - 0.5).abs() < 1e-12 && (centroid[0] - 0.25).abs() < 1e-12);
    // A corner triangle of area 1/8.
    let corner = [[0.0, 0.0], [0.5, 0.0], [0.0, 0.5]];
    assert!((covered_part(&corner, 0, 0).expect("covered").0 - 0.125).abs() < 1e-12);
    assert_eq!(covered_part(&corner, 1, 0), None);
    assert_eq!([0.1, 0.49, 0.5, 1.0].map(|f| covered_count(f, 4)), [0, 2, 2, 4]);
    assert_eq!(covered_count(0.49, 1), 0);
}

#[test]
fn area_average_tells_half_covered_pixels_as_half_their_samples() {
    // A rectangle over a 2×2 target's left quarter: its right edge at x = −0.5 in NDC, 0.5 px.
    let mut quad = ndc_draw(2, &[]);
    quad.positions = [[-3.0, 3.0], [-3.0, -3.0], [-0.5, -3.0], [-0.5, 3.0]]
        .map(|[x, y]| [x, y, 0.5, 1.0])
        .to_vec();
    quad.indices = vec![0, 1, 2, 0, 2, 3];
    let samples = AreaAverage
        .rasterize(&quad.clone().at_samples(4))
        .expect("4 samples are declared");
    let mut pixel: Vec<u8> = samples
        .iter()
        .filter(|s| (s.x, s.y) == (0, 0))
        .map(|s| s.sample)
        .collect();
    pixel.sort_unstable();
    // Pixel 0 is half covered, pixel 1 not at all. Vulkan's
    // standard 4 positions lie at x = 6, 14, 2, 10 sixteenths: samples 0 and 2 are the left ones.
    assert_eq!(pixel, [0, 2]);
    assert!(samples.iter().all(|s| s.x == 0));
}

#[test]
fn area_average_depth_is_judged_without_a_grid() {
    // msaa.depth.per-sample once passed any rasterizer without a snapping grid unjudged; area
    // averaging gives every sample the covered part's depth, so it must fail.
    assert_eq!(verdict(&mut AreaAverage, "msaa.depth.per-sample"), Status::Fail);
}
