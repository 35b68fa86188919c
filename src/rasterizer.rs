//! The `Rasterizer` trait: the contract the conformance suite certifies (its data types are
//! in `draw.rs`, its declarations in `profile.rs`).

use crate::draw::{Draw, Fragment, Resolved};
use crate::error::DrawError;
use crate::profile::Profile;

/// A rasterizer that the conformance suite can certify.
///
/// Batch-oriented so that a GPU behind an API can implement it as well as a CPU loop: a
/// [`Draw`] goes in, fragments (before the depth test) and resolved buffers (after) come out.
/// It is sent only what its [`Profile`] declares: a triangle list at one sample per pixel
/// unless it declares lines, points, sample counts, strips or fans ([`Profile::draws`]), and
/// only the draw state it supports ([`Profile::supports`]).
///
/// # Implementing it
///
/// Only [`profile`](Rasterizer::profile) and [`rasterize`](Rasterizer::rasterize) are required.
/// Here an outside crate wraps the reference and declares itself:
///
/// ```
/// use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Viewport};
///
/// /// A rasterizer of our own (here it forwards to the reference).
/// struct Mine(Reference);
///
/// impl Rasterizer for Mine {
///     fn profile(&self) -> Profile {
///         Profile { name: "mine".into(), ..self.0.profile() }
///     }
///     fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
///         self.0.rasterize(draw)
///     }
/// }
///
/// let viewport = Viewport::new(8, 8).unwrap();
/// let draw = Draw::new(
///     viewport,
///     vec![[-1.0, 1.0, 0.5, 1.0], [1.0, 1.0, 0.5, 1.0], [-1.0, -1.0, 0.5, 1.0]],
///     vec![[0, 1, 2]],
/// );
/// let mut mine = Mine(Reference::default());
/// let fragments = mine.rasterize(&draw).unwrap();
/// // The upper-left half of an 8×8 target; the 8 samples on the diagonal lie on a right edge,
/// // which does not own them under the top-left rule: 36 − 8 = 28.
/// assert_eq!(fragments.len(), 28);
/// let resolved = mine.resolve(&draw).unwrap();
/// assert_eq!(resolved.primitive[0], Some(0));
/// ```
pub trait Rasterizer {
    /// The conventions and abilities this implementation declares.
    fn profile(&self) -> Profile;

    /// What it is, as it reports itself: a driver's name and version, a library's release.
    /// Shown beside the profile in reports; empty by default.
    fn about(&self) -> String {
        String::new()
    }

    /// Every covered sample of the draw, before the depth test, in any order: at one sample per
    /// pixel, a fragment per covered pixel, with [`Fragment::sample`] 0.
    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError>;

    /// Depth and primitive-id buffers after the depth test, one value per sample.
    ///
    /// The default replays [`rasterize`](Rasterizer::rasterize) in primitive order; an
    /// implementation with its own depth test overrides it so that test is what gets certified.
    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let fragments = self.rasterize(draw)?;
        Ok(Resolved::from_fragments(draw, fragments))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Viewport;

    /// A rasterizer that answers with fixed fragments and declares only what it must.
    struct Fixed(Vec<Fragment>);

    impl Rasterizer for Fixed {
        fn profile(&self) -> Profile {
            crate::Reference::default().profile()
        }

        fn rasterize(&mut self, _: &Draw) -> Result<Vec<Fragment>, DrawError> {
            Ok(self.0.clone())
        }
    }

    fn at(x: u32, y: u32) -> Fragment {
        Fragment {
            x,
            y,
            sample: 0,
            primitive: 0,
            depth: 0.25,
            barycentric: [1.0, 0.0, 0.0],
            screen_barycentric: None,
            front_facing: true,
            flat: None,
        }
    }

    /// A fragment outside the target (a driver may send one) is dropped by the default
    /// `resolve`, not wrapped into the next row or the one above.
    #[test]
    fn resolving_drops_fragments_outside_the_target() {
        let draw = Draw::new(Viewport::new(4, 4).expect("4×4"), Vec::new(), Vec::new());
        let mut r = Fixed(vec![at(4, 0), at(0, 4), at(1, 1)]);
        let resolved = r.resolve(&draw).expect("resolves");
        let drawn: Vec<usize> = (0..16).filter(|&i| resolved.primitive[i].is_some()).collect();
        assert_eq!(drawn, [5]);
        assert_eq!(resolved.depth[5], 0.25);
    }

    /// Implementations that say nothing about themselves report nothing.
    #[test]
    fn about_is_empty_unless_said() {
        assert_eq!(Fixed(Vec::new()).about(), "");
    }
}
