//! The `Rasterizer` trait: the contract the conformance suite certifies (its data types are
//! in `draw.rs` and `primitive.rs`).

use crate::draw::{Draw, Fragment, Resolved};
use crate::error::DrawError;
use crate::primitive::{PrimitiveDraw, PrimitiveProfile, SampleFragment, SampleResolved};
use crate::profile::Profile;

/// A triangle rasterizer that the conformance suite can certify.
///
/// Batch-oriented so that a GPU behind an API can implement it as well as a CPU loop: a
/// [`Draw`] goes in, fragments (before the depth test) and resolved buffers (after) come out.
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

    /// Every covered sample of the draw, before the depth test, in any order.
    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError>;

    /// Depth and primitive-id buffers after the depth test.
    ///
    /// The default replays [`rasterize`](Rasterizer::rasterize) in primitive order; an
    /// implementation with its own depth test overrides it so that test is what gets certified.
    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let fragments = self.rasterize(draw)?;
        Ok(Resolved::from_fragments(draw, fragments))
    }

    /// What it declares about lines, points and multisampling; by default nothing: triangles at
    /// one sample per pixel.
    fn primitive_profile(&self) -> PrimitiveProfile {
        PrimitiveProfile::triangles_only()
    }

    /// Every covered sample of a draw of any topology and sample count, before the depth test.
    ///
    /// The default draws a triangle list at one sample through [`rasterize`](Rasterizer::rasterize)
    /// and refuses anything else as [`DrawError::Unsupported`]; an implementation declaring
    /// lines, points or samples in [`primitive_profile`](Rasterizer::primitive_profile)
    /// overrides it.
    fn rasterize_primitives(&mut self, draw: &PrimitiveDraw) -> Result<Vec<SampleFragment>, DrawError> {
        rasterize_as_triangles(self, draw)
    }

    /// Depth and primitive-id buffers per sample after the depth test.
    ///
    /// The default resolves a triangle list at one sample through [`resolve`](Rasterizer::resolve)
    /// and replays [`rasterize_primitives`](Rasterizer::rasterize_primitives) sample by sample
    /// otherwise.
    fn resolve_primitives(&mut self, draw: &PrimitiveDraw) -> Result<SampleResolved, DrawError> {
        resolve_by_replay(self, draw)
    }
}

/// [`Rasterizer::rasterize_primitives`] for an implementation that declares nothing beyond
/// triangles: a triangle list at one sample through [`Rasterizer::rasterize`], anything else
/// refused as unsupported.
pub fn rasterize_as_triangles<R: Rasterizer + ?Sized>(
    r: &mut R,
    draw: &PrimitiveDraw,
) -> Result<Vec<SampleFragment>, DrawError> {
    draw.validate()?;
    let Some(triangles) = draw.as_triangle_draw() else {
        return Err(DrawError::Unsupported(draw.describe()));
    };
    Ok(r.rasterize(&triangles)?
        .into_iter()
        .map(|fragment| SampleFragment { fragment, sample: 0 })
        .collect())
}

/// [`Rasterizer::resolve_primitives`] by default: a triangle list at one sample through the
/// implementation's own [`Rasterizer::resolve`] (so its depth test is what gets judged), anything
/// else replayed from [`Rasterizer::rasterize_primitives`].
pub fn resolve_by_replay<R: Rasterizer + ?Sized>(
    r: &mut R,
    draw: &PrimitiveDraw,
) -> Result<SampleResolved, DrawError> {
    draw.validate()?;
    if let Some(triangles) = draw.as_triangle_draw() {
        let resolved = r.resolve(&triangles)?;
        return Ok(SampleResolved {
            viewport: resolved.viewport,
            samples: 1,
            depth: resolved.depth,
            primitive: resolved.primitive,
        });
    }
    let fragments = r.rasterize_primitives(draw)?;
    Ok(SampleResolved::from_fragments(draw, fragments))
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
            primitive: 0,
            depth: 0.25,
            barycentric: [1.0, 0.0, 0.0],
            screen_barycentric: None,
            front_facing: true,
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
