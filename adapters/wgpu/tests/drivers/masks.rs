//! lavapipe's sample mask at one sample and its per-sample perspective divide, hand-checked
//! (docs/certified.md, "lavapipe reads the sample mask at one sample as any of its low 16 bits",
//! "a sample's perspective divide at the pixel centre").

use refrast::{Draw, Fragment};
use refrast_wgpu::Driver;

use crate::findings::{Run, lower_left_half};

/// At one sample, a sample mask with bit 0 clear draws every fragment where another of its low
/// 16 bits is set (and none where none is); at 4 samples each bit keeps its own sample.
pub fn lavapipe_single_sample_mask(d: Driver, run: &mut Run<'_>) {
    let mut half = lower_left_half();
    let mut drawn = |half: &mut Draw, mask: u32| {
        half.state.sample_mask = mask;
        run(half)
    };
    assert_eq!(
        drawn(&mut half, u32::MAX).len(),
        120,
        "{}: the unmasked half",
        d.name()
    );
    let counts: Vec<usize> = [0x2, 0x8000, 0xffff_fffe, 0, 0x1_0000, 0x8000_0000]
        .into_iter()
        .map(|mask| drawn(&mut half, mask).len())
        .collect();
    // Vulkan (Sample Mask Test) keeps none of them: bit 0 is sample 0's.
    assert_eq!(
        counts,
        [120, 120, 120, 0, 0, 0],
        "{}: fragments at one sample under masks 0x2, 0x8000, 0xfffffffe, 0, 0x10000, 0x80000000",
        d.name()
    );
    let mut four = half.clone().at_samples(4);
    let whole = drawn(&mut four, u32::MAX);
    let kept: Vec<(u32, u32, u8)> = drawn(&mut four, 0b0101)
        .iter()
        .map(|f| (f.x, f.y, f.sample))
        .collect();
    let want: Vec<(u32, u32, u8)> = whole
        .iter()
        .filter(|f| f.sample % 2 == 0)
        .map(|f| (f.x, f.y, f.sample))
        .collect();
    assert_eq!(
        sorted(kept),
        sorted(want),
        "{}: at 4 samples, mask 0b0101 keeps samples 0 and 2",
        d.name()
    );
}

/// `v` in order.
fn sorted<T: Ord>(mut v: Vec<T>) -> Vec<T> {
    v.sort_unstable();
    v
}

/// At 4 samples, a `sample`-qualified perspective input is divided by `1/w` interpolated at
/// the pixel centre, not at the sample: on a triangle with `w` from 0.25 to 4 the barycentrics
/// sum to 0.8–1.34, and fit numerators at the sample over the centre's denominator within
/// 2·10⁻³ (the formula at the sample is off by 0.19).
pub fn lavapipe_sample_divide_at_centre(d: Driver, run: &mut Run<'_>) {
    let tri = crate::interpolation::perspective_triangle();
    let frags = run(&tri);
    assert_eq!(frags.len(), 406, "{}: the triangle's sample fragments", d.name());
    let sum = crate::interpolation::largest_sum_error(&frags);
    let at_sample = crate::interpolation::largest_misfit(&tri, &frags, 8, false);
    let over_centre = crate::interpolation::largest_misfit(&tri, &frags, 8, true);
    assert!(
        sum > 0.3 && at_sample > 0.1 && over_centre < 2e-3,
        "{}: sums off 1 by {sum:.3e}; off the formula at the sample by {at_sample:.3e}, over the centre's 1/w by {over_centre:.3e}",
        d.name()
    );
}

/// Under centroid interpolation at 4 samples, the same: numerators at the centroid (the pixel
/// centre where all 4 samples are covered, else the first covered sample, which is D3D11's
/// location) over `1/w` at the pixel centre, so a partly covered pixel's barycentrics sum off 1
/// and name no location at all.
pub fn lavapipe_centroid_divide_at_centre(d: Driver, run: &mut Run<'_>) {
    let mut tri = crate::interpolation::perspective_triangle();
    tri.state.interpolation = refrast::Interpolation::Centroid;
    let frags = run(&tri);
    assert_eq!(frags.len(), 406, "{}: the triangle's sample fragments", d.name());
    let sum = crate::interpolation::largest_sum_error(&frags);
    let at_centroid = largest_centroid_misfit(&tri, &frags, false);
    let over_centre = largest_centroid_misfit(&tri, &frags, true);
    assert!(
        sum > 0.05 && at_centroid > 0.05 && over_centre < 2e-3,
        "{}: sums off 1 by {sum:.3e}; off the formula at the centroid by {at_centroid:.3e}, over the centre's 1/w by {over_centre:.3e}",
        d.name()
    );
}

/// `largest_misfit` with the numerators at a centroid: the pixel centre where the pixel has all
/// 4 samples among `frags`, else its first sample among them (D3D11.3 §3.5.5), on lavapipe's
/// 8-bit grid.
fn largest_centroid_misfit(draw: &Draw, frags: &[Fragment], centre: bool) -> f64 {
    let mut covered = std::collections::HashMap::new();
    for f in frags {
        *covered.entry((f.x, f.y)).or_insert(0u32) |= 1 << f.sample;
    }
    crate::interpolation::largest_misfit_at(draw, frags, 8, centre, |f| {
        let mask = covered[&(f.x, f.y)];
        (mask != 0b1111).then(|| mask.trailing_zeros() as usize)
    })
}
