//! The reference matches the brute-force oracle bit for bit on random triangles.
//!
//! Cases: `PROPTEST_CASES` when set, else 10 000 per property.

use proptest::prelude::*;
use refrast::stage::{FanTriangle, PixelRect, TriangleSetup, traverse};
use refrast::{
    COORD_LIMIT, Draw, FillConvention, FixedPoint, Rasterizer, Reference, ReferenceConfig, SubpixelBits,
    Traversal, Viewport, snap,
};
use refrast_conformance::oracle::{brute_force, raster};

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(10_000);
    ProptestConfig::with_cases(cases)
}

/// One coordinate in subpixel units for a viewport side of `side` pixels: mostly on screen,
/// often on pixel centres or pixel edges, sometimes far outside.
fn coordinate(side: u32, bits: u8) -> impl Strategy<Value = i64> {
    let one = 1i64 << bits;
    let max = i64::from(side) * one;
    prop_oneof![
        4 => -max / 2..max + max / 2,
        2 => (-2..i64::from(side) + 2).prop_map(move |p| p * one + one / 2),
        1 => (-2..i64::from(side) + 2).prop_map(move |p| p * one),
        1 => (-2..2 * i64::from(side) + 2).prop_map(move |p| p * one / 2),
        1 => -(4000 * one)..(4000 * one),
    ]
}

/// A triangle, sometimes with a horizontal or a vertical edge or a repeated vertex.
fn triangle(width: u32, height: u32, bits: u8) -> impl Strategy<Value = [(i64, i64); 3]> {
    let point = move || (coordinate(width, bits), coordinate(height, bits));
    (point(), point(), point(), 0..6u8).prop_map(|(a, b, mut c, shape)| {
        match shape {
            0 => c.1 = a.1, // a–c horizontal
            1 => c.0 = b.0, // b–c vertical
            2 => c = a,     // degenerate
            _ => {}
        }
        [a, b, c]
    })
}

/// Clip-space positions (w = 1) that the viewport transform maps back to exactly `t`.
///
/// Viewports are powers of two, so `X / 2^bits / W · 2 − 1` is exact in f32 for every coordinate used.
fn to_clip(t: [(i64, i64); 3], viewport: Viewport, bits: u8) -> Vec<[f32; 4]> {
    let one = f64::from(1u32 << bits);
    t.iter()
        .map(|&(x, y)| {
            let (nx, ny) = viewport.to_ndc(x as f64 / one, y as f64 / one);
            [nx as f32, ny as f32, 0.5, 1.0]
        })
        .collect()
}

fn reference_coverage(reference: &mut Reference, draw: &Draw) -> Vec<(u32, u32)> {
    let mut pixels: Vec<_> = reference
        .rasterize(draw)
        .unwrap()
        .iter()
        .map(|f| (f.x, f.y))
        .collect();
    pixels.sort_unstable_by_key(|&(x, y)| (y, x));
    pixels
}

fn widen(t: [(i64, i64); 3]) -> [raster::Point; 3] {
    t.map(|(x, y)| (i128::from(x), i128::from(y)))
}

proptest! {
    #![proptest_config(config())]

    /// Whole draws (viewport transform, snapping, setup, traversal) against the oracle.
    #[test]
    fn reference_matches_brute_force(
        (width, height, bits, t) in (0..7u32, 0..7u32, 1..=8u8).prop_flat_map(|(lw, lh, bits)| {
            let (w, h) = (1 << lw, 1 << lh);
            (Just(w), Just(h), Just(bits), triangle(w, h, bits))
        }),
    ) {
        check_draw(t, width, height, bits)?;
    }

    /// Every fill convention and both traversals, 8 bits, 64 × 32 viewport.
    #[test]
    fn every_convention_and_traversal_matches_brute_force(
        t in triangle(64, 32, 8),
        fill in prop::sample::select(FillConvention::ALL.to_vec()),
        traversal in prop::sample::select(vec![Traversal::BoundingBox, Traversal::Viewport]),
    ) {
        check_draw_with(t, 64, 32, 8, fill, traversal)?;
    }

    /// Triangles with vertices at the ends of the valid range, through setup and traversal directly.
    #[test]
    fn extreme_coordinates_match_brute_force(
        corner in prop::array::uniform3((any::<bool>(), any::<bool>(), 0..4096i64, 0..4096i64)),
        on_screen in (0..64i64, 0..64i64),
    ) {
        let bits = SubpixelBits::DEFAULT;
        let limit = (COORD_LIMIT as i64) << bits.get();
        // Two vertices near ±COORD_LIMIT, one on screen so the triangle crosses the viewport.
        let far = |(sx, sy, dx, dy): (bool, bool, i64, i64)| {
            let x = if sx { limit - dx } else { -limit + dx };
            let y = if sy { limit - dy } else { -limit + dy };
            (x, y)
        };
        let t = [far(corner[0]), far(corner[1]), (on_screen.0 * 256 + 128, on_screen.1 * 256 + 128)];
        let viewport = Viewport::new(64, 64).unwrap();
        let points = t.map(|(x, y)| FixedPoint::new(x, y).unwrap());
        let mut got = Vec::new();
        if let (Some(setup), Some(rect)) = (
            TriangleSetup::new(points, FillConvention::TopLeft),
            PixelRect::bounding(points, bits, viewport),
        ) {
            let fan = [FanTriangle::whole(setup)];
            traverse(&fan, setup.winding(), rect, bits, &mut Vec::new(), |hit| got.push((hit.x, hit.y)));
        }
        got.sort_unstable_by_key(|&(x, y)| (y, x));
        prop_assert_eq!(got, brute_force::coverage(widen(t), 64, 64, 8, FillConvention::TopLeft));
    }
}

fn check_draw(t: [(i64, i64); 3], width: u32, height: u32, bits: u8) -> Result<(), TestCaseError> {
    check_draw_with(
        t,
        width,
        height,
        bits,
        FillConvention::TopLeft,
        Traversal::BoundingBox,
    )
}

fn check_draw_with(
    t: [(i64, i64); 3],
    width: u32,
    height: u32,
    bits: u8,
    fill: FillConvention,
    traversal: Traversal,
) -> Result<(), TestCaseError> {
    let viewport = Viewport::new(width, height).unwrap();
    let subpixel_bits = SubpixelBits::new(bits).unwrap();
    let positions = to_clip(t, viewport, bits);
    // The round trip is exact, so the oracle sees the very coordinates the reference snaps to.
    for (p, &(x, y)) in positions.iter().zip(&t) {
        let (rx, ry) = viewport.to_raster(f64::from(p[0]), f64::from(p[1]));
        prop_assert_eq!(
            (snap(rx, subpixel_bits), snap(ry, subpixel_bits)),
            (Some(x), Some(y))
        );
    }
    let draw = Draw::new(viewport, positions, vec![[0, 1, 2]]);
    let mut reference = Reference::new(ReferenceConfig {
        subpixel_bits,
        fill,
        traversal,
        ..ReferenceConfig::default()
    });
    let got = reference_coverage(&mut reference, &draw);
    let want = brute_force::coverage(widen(t), width, height, bits, fill);
    prop_assert_eq!(
        got,
        want,
        "triangle {:?} in {}x{} at {} bits, {:?}, {:?}",
        t,
        width,
        height,
        bits,
        fill,
        traversal
    );
    Ok(())
}
