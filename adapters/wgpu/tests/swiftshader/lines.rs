//! SwiftShader's lines to an end behind the eye and its per-sample perspective divide,
//! hand-checked (docs/certified.md, "SwiftShader drops a line whose end is behind the eye", "a
//! sample's perspective divide at the pixel centre").

use refrast::{Draw, Topology, Viewport};

use crate::findings::Run;

/// A segment on 32×16 from an end in front (w = 0.25, z/w = 0.64) to one before the near plane
/// at `w`: it crosses z = 0 where w = 0.218, and its visible part, (12.65, 1.50) to (9.33,
/// 0.55) px for `w` = 0, lies inside the viewport.
fn to_w(w: f32) -> Draw {
    let positions = vec![
        [-0.052368164, 0.203125, 0.15977967, 0.25],
        [-0.35839844, 0.20507813, -1.103786, w],
    ];
    let mut draw = Draw::of(
        Viewport::new(32, 16).expect("a viewport"),
        positions,
        Topology::LineList,
        vec![0, 1],
    );
    draw.state.clip_far = true;
    draw
}

/// With the far end at w = 0 or −0.01 nothing is drawn; at w = +0.01, the four pixels of the
/// visible part (the reference's and lavapipe's at w = 0).
pub fn line_behind_the_eye(run: &mut Run<'_>) {
    for w in [0.0, -0.01] {
        let got = run(&to_w(w));
        assert!(
            got.is_empty(),
            "swiftshader: the line to w = {w} now draws {got:?}"
        );
    }
    let mut pixels: Vec<(u32, u32)> = run(&to_w(0.01)).iter().map(|f| (f.x, f.y)).collect();
    pixels.sort_unstable();
    assert_eq!(
        pixels,
        vec![(9, 0), (10, 0), (11, 1), (12, 1)],
        "swiftshader: the line to w = 0.01"
    );
    println!("swiftshader: a line to an end at w <= 0 draws nothing of its visible part");
}

/// At 4 samples, a `sample`-qualified perspective input is divided by `1/w` interpolated at
/// the pixel centre, not at the sample: on a triangle with `w` from 0.25 to 4 the barycentrics
/// sum to 0.8–1.34, and fit numerators at the sample over the centre's denominator within
/// 10⁻⁶ on its 4-bit grid (the formula at the sample is off by 0.2).
pub fn sample_divide_at_centre(run: &mut Run<'_>) {
    let tri = crate::interpolation::perspective_triangle();
    let frags = run(&tri);
    let sum = crate::interpolation::largest_sum_error(&frags);
    let at_sample = crate::interpolation::largest_misfit(&tri, &frags, 4, false);
    let over_centre = crate::interpolation::largest_misfit(&tri, &frags, 4, true);
    assert!(
        !frags.is_empty() && sum > 0.3 && at_sample > 0.1 && over_centre < 1e-6,
        "{} fragments: sums off 1 by {sum:.3e}; off the formula at the sample by {at_sample:.3e}, over the centre's 1/w by {over_centre:.3e}",
        frags.len()
    );
}
