//! Bad numbers and bad input: NaN and infinities discard a triangle, huge and tiny values are
//! clipped or snapped, bad indices and viewports are errors, and nothing panics.

use proptest::prelude::*;
use refrast::{ConfigError, Draw, DrawError, Rasterizer, Reference, Viewport};

fn viewport() -> Viewport {
    Viewport::new(32, 32).unwrap()
}

/// A triangle that covers part of the viewport.
const GOOD: [[f32; 4]; 3] = [[-0.5, 0.5, 0.5, 1.0], [0.5, 0.5, 0.5, 1.0], [0.0, -0.5, 0.5, 1.0]];

#[test]
fn non_finite_coordinates_discard_only_their_triangle() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for component in 0..4 {
            let mut broken = GOOD;
            broken[1][component] = bad;
            let positions: Vec<_> = broken.iter().chain(GOOD.iter()).copied().collect();
            let draw = Draw::new(viewport(), positions, vec![[0, 1, 2], [3, 4, 5]]);
            let mut primitives = Vec::new();
            let stats = Reference::default()
                .draw(&draw, |f| primitives.push(f.primitive))
                .unwrap();
            assert_eq!(stats.non_finite, 1, "{bad} in component {component}");
            assert!(!primitives.is_empty() && primitives.iter().all(|&p| p == 1));
        }
    }
}

#[test]
fn extreme_finite_values_neither_panic_nor_leak_bad_numbers() {
    let extremes = [
        f32::MAX,
        -f32::MAX,
        1e30,
        -1e30,
        f32::MIN_POSITIVE,
        1e-45,
        0.0,
        -0.0,
        30000.0,
        -30000.0,
    ];
    for &big in &extremes {
        for &w in &[1.0, 1e-30, 1e-45, 0.0, -1.0, f32::MAX] {
            let positions = vec![[big, 0.5, 0.5, w], [0.5, -big, 0.5, 1.0], [-0.5, -0.5, big, w]];
            let draw = Draw::new(viewport(), positions, vec![[0, 1, 2]]);
            for f in Reference::default().rasterize(&draw).unwrap() {
                assert!((0.0..=1.0).contains(&f.depth), "{big} {w}: {f:?}");
                assert!(f.barycentric.iter().all(|b| b.is_finite()), "{big} {w}: {f:?}");
            }
        }
    }
}

#[test]
fn w_zero_everywhere_draws_nothing() {
    let positions = vec![[0.0, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0], [0.0, 0.5, 0.0, 0.0]];
    let draw = Draw::new(viewport(), positions, vec![[0, 1, 2]]);
    assert!(Reference::default().rasterize(&draw).unwrap().is_empty());
}

#[test]
fn bad_indices_are_an_error_naming_the_triangle() {
    let draw = Draw::new(viewport(), GOOD.to_vec(), vec![[0, 1, 2], [0, 1, 3]]);
    let err = Reference::default().rasterize(&draw).unwrap_err();
    assert_eq!(
        err,
        DrawError::IndexOutOfRange {
            triangle: 1,
            index: 3,
            vertices: 3
        }
    );
    assert!(err.to_string().contains("triangle 1 uses vertex 3"), "{err}");
}

#[test]
fn absurd_viewports_are_refused() {
    for (w, h) in [(0, 10), (10, 0), (16385, 10), (10, u32::MAX)] {
        assert_eq!(
            Viewport::new(w, h),
            Err(ConfigError::Viewport { width: w, height: h })
        );
    }
    assert!(Viewport::new(16384, 16384).is_ok());
    let message = Viewport::new(0, 5).unwrap_err().to_string();
    assert!(message.contains("1..=16384"), "{message}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(4096)
    ))]

    /// Arbitrary bit patterns (NaN payloads, infinities, subnormals, huge, w = 0) in every coordinate.
    #[test]
    fn arbitrary_bit_patterns_never_panic(bits in prop::array::uniform12(any::<u32>()), size in 1..40u32) {
        let c: Vec<f32> = bits.iter().map(|&b| f32::from_bits(b)).collect();
        let positions = c.chunks(4).map(|p| [p[0], p[1], p[2], p[3]]).collect();
        let viewport = Viewport::new(size, size).unwrap();
        let draw = Draw::new(viewport, positions, vec![[0, 1, 2]]);
        for f in Reference::default().rasterize(&draw).unwrap() {
            prop_assert!(f.x < size && f.y < size);
            prop_assert!((0.0..=1.0).contains(&f.depth));
            prop_assert!(f.barycentric.iter().all(|b| b.is_finite()));
        }
    }

    /// Mostly sensible clip coordinates with sometimes tiny or negative w.
    #[test]
    fn near_degenerate_clip_coordinates_never_panic(
        coords in prop::array::uniform3((-4.0f32..4.0, -4.0f32..4.0, -2.0f32..2.0, prop_oneof![-1.0f32..2.0, Just(0.0), Just(1e-30)])),
    ) {
        let positions = coords.iter().map(|&(x, y, z, w)| [x, y, z, w]).collect();
        let draw = Draw::new(viewport(), positions, vec![[0, 1, 2]]);
        for f in Reference::default().rasterize(&draw).unwrap() {
            prop_assert!((0.0..=1.0).contains(&f.depth));
            let sum: f32 = f.barycentric.iter().sum();
            // The f64 weights sum to 1 within 1e-15; rounding each to f32 costs ½ ulp (≤ 2^-25
            // for values ≤ 1) and the f32 sum two more roundings: well within 4 ulps of 1.
            prop_assert!((sum - 1.0).abs() <= 4.0 * f32::EPSILON, "{:?}", f);
        }
    }
}
