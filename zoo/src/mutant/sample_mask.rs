//! The sample mask's bugs: the reference's drawing with the mask read wrong in one way.

use refrast::{Draw, DrawError, DrawState, Fragment, Rasterizer, Reference};

use super::Bug;

/// `draw` as the reference draws it with the mask `bug` reads from it, `None` for a bug
/// elsewhere or a draw with no mask (the depth bug draws its fragments right).
pub fn rasterize(bug: Bug, draw: &Draw) -> Option<Result<Vec<Fragment>, DrawError>> {
    let mask = draw.state.sample_mask;
    if mask == DrawState::ALL_SAMPLES {
        return None;
    }
    let read = match bug {
        Bug::IgnoredSampleMask => DrawState::ALL_SAMPLES,
        Bug::ReversedSampleMask => reversed(mask, draw.samples),
        Bug::TrianglesOnlySampleMask if !draw.topology.is_triangles() => DrawState::ALL_SAMPLES,
        Bug::MultisampleOnlySampleMask if draw.samples == 1 => DrawState::ALL_SAMPLES,
        _ => return None,
    };
    let mut misread = draw.clone();
    misread.state.sample_mask = read;
    Some(Reference::default().rasterize(&misread))
}

/// The low `samples` bits of `mask` in reverse order (bit `i` moved to `samples − 1 − i`).
fn reversed(mask: u32, samples: u8) -> u32 {
    (0..u32::from(samples))
        .filter(|&i| mask >> i & 1 == 1)
        .fold(0, |out, i| out | 1 << (u32::from(samples) - 1 - i))
}

#[cfg(test)]
mod tests {
    use super::reversed;

    #[test]
    fn reversing_moves_each_bit_to_its_mirror() {
        assert_eq!(reversed(0b0001, 4), 0b1000);
        assert_eq!(reversed(0b0110, 4), 0b0110);
        assert_eq!(reversed(0xffff_fff1, 4), 0b1000);
        assert_eq!(reversed(1, 1), 1);
    }
}
