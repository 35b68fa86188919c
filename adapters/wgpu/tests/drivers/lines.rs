//! lavapipe's lines at 4 samples, hand-checked (docs/certified.md, "lavapipe drops very short
//! lines at 4 samples").

use refrast::{Draw, Topology, Viewport};
use refrast_wgpu::Driver;

use crate::findings::Run;

/// A diagonal segment on 16×16 at 4 samples, its ends on the 8-bit grid `n` steps each way
/// about (7.365, 8.615): its rectangle holds sample 3 of pixel (7, 8), at (7.625, 8.875).
fn short_diagonal(n: i32) -> Draw {
    let (cx, cy) = (1886, 2206);
    let ndc = |x: i32, y: i32| {
        [
            x as f32 / 256.0 / 8.0 - 1.0,
            1.0 - y as f32 / 256.0 / 8.0,
            0.0,
            1.0,
        ]
    };
    let positions = vec![ndc(cx - n / 2, cy + n / 2), ndc(cx + n - n / 2, cy - (n - n / 2))];
    let mut draw = Draw::of(
        Viewport::new(16, 16).expect("a viewport"),
        positions,
        Topology::LineList,
        vec![0, 1],
    )
    .at_samples(4);
    draw.state.clip_far = true;
    draw
}

/// Lines 4 to 12 grid steps each way (0.022 to 0.066 px) draw nothing, where their rectangle
/// holds sample 3 of pixel (7, 8) up to 0.033 px inside its outline; from 16 steps it is drawn.
pub fn lavapipe_short_lines(d: Driver, run: &mut Run<'_>) {
    let covers = |f: &[refrast::Fragment]| f.iter().any(|f| (f.x, f.y, f.sample) == (7, 8, 3));
    for n in [4, 8, 12] {
        let got = run(&short_diagonal(n));
        assert!(
            got.is_empty(),
            "{}: a line {n} steps each way now draws {got:?}",
            d.name()
        );
    }
    let long = run(&short_diagonal(16));
    assert!(
        covers(&long),
        "{}: a line 16 steps each way no longer covers sample 3 of (7, 8): {long:?}",
        d.name()
    );
}
