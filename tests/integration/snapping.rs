//! Snapping to the subpixel grid: round half to even, the valid range, the bit counts accepted.

use refrast::{COORD_LIMIT, ConfigError, FixedPoint, SubpixelBits, snap};

fn bits(n: u8) -> SubpixelBits {
    SubpixelBits::new(n).unwrap()
}

#[test]
fn halves_round_to_even() {
    let unit = 1.0 / 256.0;
    assert_eq!(snap(0.5 * unit, bits(8)), Some(0));
    assert_eq!(snap(1.5 * unit, bits(8)), Some(2));
    assert_eq!(snap(2.5 * unit, bits(8)), Some(2));
    assert_eq!(snap(3.5 * unit, bits(8)), Some(4));
    assert_eq!(snap(-0.5 * unit, bits(8)), Some(0));
    assert_eq!(snap(-1.5 * unit, bits(8)), Some(-2));
    assert_eq!(snap(-2.5 * unit, bits(8)), Some(-2));
}

#[test]
fn other_values_round_to_nearest() {
    let unit = 1.0 / 256.0;
    assert_eq!(snap(0.49 * unit, bits(8)), Some(0));
    assert_eq!(snap(0.51 * unit, bits(8)), Some(1));
    assert_eq!(snap(-0.51 * unit, bits(8)), Some(-1));
    assert_eq!(snap(10.0, bits(8)), Some(2560));
    assert_eq!(snap(10.0, bits(4)), Some(160));
    // 1/32 px is half a unit at 4 bits (ties to 0) but 8 whole units at 8 bits.
    assert_eq!(snap(1.0 / 32.0, bits(4)), Some(0));
    assert_eq!(snap(3.0 / 32.0, bits(4)), Some(2));
    assert_eq!(snap(1.0 / 32.0, bits(8)), Some(8));
}

#[test]
fn the_valid_range_is_inclusive_and_bad_numbers_are_refused() {
    assert_eq!(snap(COORD_LIMIT, bits(8)), Some(32768 * 256));
    assert_eq!(snap(-COORD_LIMIT, bits(8)), Some(-32768 * 256));
    assert_eq!(snap(COORD_LIMIT + 1e-3, bits(8)), None);
    assert_eq!(snap(-1e30, bits(8)), None);
    assert_eq!(snap(f64::NAN, bits(8)), None);
    assert_eq!(snap(f64::INFINITY, bits(8)), None);
    assert_eq!(snap(f64::NEG_INFINITY, bits(8)), None);
    assert_eq!(FixedPoint::snap(1.0, f64::NAN, bits(8)), None);
}

#[test]
fn subpixel_bits_outside_one_to_eight_are_errors() {
    assert_eq!(SubpixelBits::new(0), Err(ConfigError::SubpixelBits(0)));
    assert_eq!(SubpixelBits::new(9), Err(ConfigError::SubpixelBits(9)));
    for n in 1..=8 {
        assert_eq!(bits(n).get(), n);
    }
    assert_eq!(SubpixelBits::default().get(), 8);
    let message = SubpixelBits::new(12).unwrap_err().to_string();
    assert!(message.contains("1..=8"), "{message}");
}

#[test]
fn samples_sit_at_pixel_centres() {
    assert_eq!(FixedPoint::sample(0, 0, bits(8)), FixedPoint::new(128, 128));
    assert_eq!(FixedPoint::sample(3, -2, bits(4)), FixedPoint::new(56, -24));
    assert_eq!(
        FixedPoint::sample(3, -2, bits(4)).unwrap().to_raster(bits(4)),
        (3.5, -1.5)
    );
    // Beyond the valid range there is no point to return.
    assert_eq!(FixedPoint::sample(40_000, 0, bits(8)), None);
    assert_eq!(FixedPoint::new(FixedPoint::LIMIT + 1, 0), None);
    assert!(FixedPoint::new(-FixedPoint::LIMIT, FixedPoint::LIMIT).is_some());
}
