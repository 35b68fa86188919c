//! lavapipe's sample mask at one sample, hand-checked (docs/certified.md, "lavapipe reads the
//! sample mask at one sample as any of its low 16 bits").

use refrast::Draw;
use refrast_wgpu::Driver;

use crate::findings::{Run, draw};

/// At one sample, a sample mask with bit 0 clear draws every fragment where another of its low
/// 16 bits is set (and none where none is); at 4 samples each bit keeps its own sample.
pub fn lavapipe_single_sample_mask(d: Driver, run: &mut Run<'_>) {
    // The lower-left half of a 16×16 target (y > x): 120 pixels.
    let mut half = draw(
        16,
        16,
        vec![
            [-1.0, 1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, -1.0, 0.5, 1.0],
        ],
        vec![[2, 0, 1]],
    );
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
