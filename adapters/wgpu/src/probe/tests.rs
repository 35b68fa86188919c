//! The probes read back what the reference declares, configured every way a driver might be.

use refrast::{ClipMode, FillConvention, Rasterizer, Reference, ReferenceConfig, SnapRounding, SubpixelBits};

use super::{Probes, REACHES};

fn reference(config: ReferenceConfig) -> Reference {
    Reference::new(config)
}

/// Every probe, through `r`.
fn measure(r: &mut Reference, reported_bits: Option<u8>) -> Result<Probes, refrast::DrawError> {
    super::measure(&mut |d| r.rasterize(d), reported_bits, Ok(()))
}

/// The default reference: 8 bits, top-left, ties to even, nearest, the 8192-px guard band, and
/// far more precision than the 18 bits it claims.
#[test]
fn the_default_reference_reads_as_it_declares() {
    let mut r = reference(ReferenceConfig::default());
    let p = measure(&mut r, None).expect("the reference draws");
    assert_eq!(p.grid.bits(), Some(8), "{}", p.grid.describe());
    assert_eq!(
        p.tie_rule.chosen,
        Some(FillConvention::TopLeft),
        "{}",
        p.tie_rule.describe()
    );
    assert_eq!((p.tie_rule.once, p.tie_rule.twice), (p.tie_rule.groups, 0));
    assert!(p.rounding.to_even(), "{}", p.rounding.describe());
    assert_eq!(p.snap.far, 0, "{}", p.snap.describe());
    assert!(p.snap.tried > 600);
    assert_eq!(p.band.reach(), refrast::GUARD_BAND_REACH, "{}", p.band.describe());
    assert!(p.precision.bits() > 18.0, "{}", p.precision.describe());
    assert!(p.precision.fragments > 1000);
}

/// Every grid from 1 to 8 bits, every tie rule.
#[test]
fn grids_and_tie_rules_read_back() {
    for bits in [4, 6, 8] {
        let mut r = reference(ReferenceConfig {
            subpixel_bits: SubpixelBits::new(bits).expect("bits"),
            ..ReferenceConfig::default()
        });
        assert_eq!(measure(&mut r, None).expect("draws").grid.bits(), Some(bits));
    }
    for fill in FillConvention::ALL {
        let mut r = reference(ReferenceConfig {
            fill,
            subpixel_bits: SubpixelBits::new(4).expect("bits"),
            ..ReferenceConfig::default()
        });
        let p = measure(&mut r, Some(4)).expect("draws");
        assert_eq!(p.tie_rule.chosen, Some(fill), "{}", p.tie_rule.describe());
        assert_eq!(
            p.band.reach(),
            refrast::GUARD_BAND_REACH,
            "{fill:?}: {}",
            p.band.describe()
        );
    }
}

/// Halves away from zero (half up on screen) and floor: no ties to even; floor also lands
/// vertices near a tie on its far side.
#[test]
fn rounding_reads_back() {
    for (rounding, word, far) in [
        (SnapRounding::NearestAwayFromZero, "half up", false),
        (SnapRounding::Floor, "half down", true),
    ] {
        let mut r = reference(ReferenceConfig {
            snap_rounding: rounding,
            ..ReferenceConfig::default()
        });
        let p = measure(&mut r, None).expect("draws");
        assert!(
            p.rounding.cases.iter().all(|c| *c == word),
            "{}",
            p.rounding.describe()
        );
        assert_eq!(p.snap.far > 0, far, "{}", p.snap.describe());
        let profile = r.profile();
        assert_eq!(p.rounding.to_even(), profile.features.ties_to_even);
    }
}

/// Clipping at the viewport is no guard band; a 32-px band is read as the largest reach tried
/// within it.
#[test]
fn guard_bands_read_back() {
    for (clip, want) in [
        (ClipMode::Full, 0),
        (ClipMode::Reach(40), 32),
        (ClipMode::Reach(8), 8),
    ] {
        let mut r = reference(ReferenceConfig {
            clip,
            ..ReferenceConfig::default()
        });
        let band = measure(&mut r, None).expect("draws").band;
        assert_eq!(band.reach(), want, "{clip:?}: {}", band.describe());
        assert!(REACHES.contains(&want) || want == 0);
    }
}

/// The line, point and sample probes read back the reference's line rule (each of them, at 8
/// and at 4 bits), its points, and Vulkan's standard 4 sample locations.
#[test]
fn the_primitive_probes_read_the_references_rule_points_and_samples() {
    for bits in [8, 4] {
        for line in refrast::LineRule::ALL {
            let mut r = reference(ReferenceConfig {
                subpixel_bits: SubpixelBits::new(bits).expect("a grid"),
                line,
                ..ReferenceConfig::default()
            });
            let p = measure(&mut r, None).expect("the reference draws").primitives;
            assert_eq!(p.line_rule(), Some(line), "{bits} bits: {}", p.describe());
            assert_eq!(p.points, Ok(0), "{bits} bits: {}", p.describe());
            assert_eq!(
                p.pattern(),
                refrast::SamplePattern::standard(4),
                "{}",
                p.describe()
            );
        }
    }
}

/// Each rule disagrees with the others somewhere on the probe's segments, so the probe can tell
/// them apart.
#[test]
fn the_line_probe_tells_every_rule_apart() {
    let mut r = reference(ReferenceConfig::default());
    let p = measure(&mut r, None).expect("the reference draws").primitives;
    let counts = p.lines.expect("the reference draws lines");
    let off: Vec<usize> = counts.iter().map(|(_, n)| *n).collect();
    assert_eq!(off.iter().filter(|&&n| n == 0).count(), 1, "{counts:?}");
}

/// The slope probe reads the reference's measure, the gradient's length, off its depth buffer.
#[test]
fn the_slope_probe_reads_the_references_exact_measure() {
    let mut r = Reference::default();
    let slope = super::bias::probe(&mut |d| r.resolve(d)).expect("the reference resolves");
    assert_eq!(
        slope.measure(),
        refrast::DepthSlope::Exact,
        "{}",
        slope.describe()
    );
    assert!(super::Slope::unmeasured().describe().contains("nothing drawn"));
}
