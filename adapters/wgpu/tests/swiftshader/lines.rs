//! SwiftShader's lines to an end behind the eye, hand-checked (docs/certified.md, "SwiftShader
//! drops a line whose end is behind the eye").

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
