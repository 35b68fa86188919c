//! SwiftShader's clip distances, hand-checked (docs/certified.md, finding 15).

use refrast::{Distances, Draw, Fragment, Topology, Viewport};

/// Finding 15: clip distances are tested once per pixel, at its centre, not at each sample.
///
/// A triangle at 4 samples whose clip distance is 0 along the edge `x = 41.5` (its corners
/// there) and 0.598 at the far corner; drawn by `−d`, nothing of it is inside (`−d ≤ 0`
/// everywhere, 0 only on that edge). SwiftShader's `−d` draw covers the samples of pixel column
/// 41 right of the edge, whose own barycentrics (the third, the far corner's weight, 0.006 or
/// 0.017) put `−d` at −0.003 or −0.010: outside the clip half-space, which Vulkan's
/// ClipDistance says "will be considered outside the clip volume". The pixel's centre lies on
/// the edge, where `−d` is 0, and that decides all four samples; the `+d` draw covers them too,
/// so they are drawn twice (the complementarity criterion). Single-sampled, as dEQP's
/// complementarity tests draw, nothing shows.
pub fn clip_distance_per_pixel(run: &mut crate::findings::Run<'_>) {
    let positions = vec![
        [1.0, -1.0, 0.5, 1.0],
        [0.296875, -0.34375, 0.5, 1.0],
        [0.296875, -0.21960449, 0.5, 1.0],
    ];
    let mut draw = Draw::of(
        Viewport::new(64, 64).expect("a viewport"),
        positions,
        Topology::TriangleList,
        vec![1, 2, 0],
    );
    draw.samples = 4;
    draw.state.clip_far = true;
    draw.distances = Distances::new(1, 0, &[vec![-0.5982502], vec![0.0], vec![0.0]]);
    let got: Vec<Fragment> = run(&draw);
    // Each sample's interpolated −d, from its own perspective-correct barycentrics.
    let outside: Vec<(u32, u32, u8, f32)> = got
        .iter()
        .map(|f| (f.x, f.y, f.sample, -0.598_250_2 * f.barycentric[2]))
        .filter(|&(.., d)| d < -1e-3)
        .collect();
    assert_eq!(got.len(), 7, "swiftshader: the −d draw's samples: {got:?}");
    assert_eq!(
        outside.len(),
        7,
        "swiftshader: samples with −d clearly negative: {outside:?}"
    );
    assert!(outside.iter().all(|&(x, ..)| x == 41), "{outside:?}");
    println!("swiftshader: clip distances tested at the pixel centre: 7 samples drawn where −d < 0");
}
