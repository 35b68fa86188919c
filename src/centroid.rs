//! Centroid interpolation: a triangle's fragments in a pixel held back until every sample is
//! known, then given the barycentrics of the one location [`DrawState::centroid_sample`]
//! chooses (the pixel centre, evaluated on the unmoved polygon, or a covered sample's own).

use std::collections::HashMap;

use crate::bias::FragmentDepth;
use crate::draw::Fragment;
use crate::edge::FillConvention;
use crate::fixed::{FixedPoint, SubpixelBits};
use crate::project::RasterVertex;
use crate::reference::Sample;
use crate::setup::Winding;
use crate::state::DrawState;
use crate::traverse::{FanTriangle, Hit, build_fan};

/// A fragment's perspective-correct and screen-space barycentrics.
type Weights = ([f32; 3], Option<[f32; 3]>);

/// One triangle's covered samples per pixel and its kept fragments, in the order they came.
#[derive(Default)]
pub(crate) struct CentroidPixels {
    /// Per pixel: the samples the triangle covers (before the mask), and its first kept
    /// fragment's index in `fragments`.
    pixels: HashMap<(u32, u32), (u32, Option<usize>)>,
    fragments: Vec<Fragment>,
    fan: Vec<FanTriangle>,
}

/// What the pixel centre's barycentrics need of the triangle: its unmoved snapped polygon and
/// how it is drawn.
pub(crate) struct Unmoved<'a> {
    pub(crate) polygon: &'a [RasterVertex],
    pub(crate) fill: FillConvention,
    pub(crate) bits: SubpixelBits,
    pub(crate) winding: Winding,
    pub(crate) depth: FragmentDepth,
}

impl CentroidPixels {
    /// Forgets the last triangle's pixels.
    pub(crate) fn clear(&mut self) {
        self.pixels.clear();
        self.fragments.clear();
    }

    /// Sample `k` of pixel `(x, y)` is covered; `fragment` is its fragment where the mask
    /// keeps it.
    pub(crate) fn cover(&mut self, x: u32, y: u32, k: u8, fragment: Option<Fragment>) {
        let pixel = self.pixels.entry((x, y)).or_default();
        pixel.0 |= 1 << k;
        if let Some(f) = fragment {
            pixel.1.get_or_insert(self.fragments.len());
            self.fragments.push(f);
        }
    }

    /// Hands each kept fragment to `emit`, in the order it came, with its pixel's centroid
    /// barycentrics; how many.
    pub(crate) fn emit(
        &mut self,
        state: &DrawState,
        samples: u8,
        unmoved: &Unmoved<'_>,
        emit: &mut impl FnMut(Fragment),
    ) -> usize {
        build_fan(unmoved.polygon, unmoved.fill, &mut self.fan);
        let mut at: HashMap<(u32, u32), Weights> = HashMap::new();
        for (&(x, y), &(covered, first)) in &self.pixels {
            let Some(first) = first else { continue };
            let f = match state.centroid_sample(samples, covered) {
                // Fragments came sample by sample, so the pixel's first is its first kept one.
                Some(_) => self.fragments[first],
                None => centre(&self.fan, unmoved, &self.fragments[first]),
            };
            at.insert((x, y), (f.barycentric, f.screen_barycentric));
        }
        for f in &self.fragments {
            let (barycentric, screen_barycentric) = at[&(f.x, f.y)];
            emit(Fragment {
                barycentric,
                screen_barycentric,
                ..*f
            });
        }
        self.fragments.len()
    }
}

/// `f` with the barycentrics of its pixel's centre on the unmoved polygon: from the fan
/// triangle holding the centre (on its edges included), else extrapolated from the first
/// that turns as the polygon does (a centre a snapped sliver leaves outside every one).
fn centre(fan: &[FanTriangle], unmoved: &Unmoved<'_>, f: &Fragment) -> Fragment {
    let centre = FixedPoint::pixel_sample(i64::from(f.x), i64::from(f.y), unmoved.bits);
    let values = |t: &FanTriangle| t.setup.edge_values(centre);
    let agrees = |t: &&FanTriangle| t.setup.winding() == unmoved.winding;
    let found = fan
        .iter()
        .position(|t| agrees(&t) && values(t).iter().all(|&v| v >= 0))
        .or_else(|| fan.iter().position(|t| agrees(&t)));
    let Some(triangle) = found else { return *f };
    let hit = Hit {
        x: f.x,
        y: f.y,
        triangle,
        values: values(&fan[triangle]),
    };
    let at = Sample::new(
        unmoved.depth,
        f.primitive,
        f.front_facing,
        f.flat,
        hit,
        fan,
        unmoved.polygon,
    )
    .fragment();
    Fragment {
        barycentric: at.barycentric,
        screen_barycentric: at.screen_barycentric,
        ..*f
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use crate::{Draw, DrawState, Fragment, Interpolation, Reference, Topology, Viewport};

    /// A triangle in perspective over 12×12 at 4 samples, masked as `mask`, sampled as `at`.
    fn draw(at: Interpolation, mask: u32, samples: u8) -> Vec<Fragment> {
        let positions = vec![
            [-0.9, -0.8, 0.2, 1.0],
            [1.6, -1.2, 0.5, 2.0],
            [-0.2, 3.0, 0.9, 4.0],
        ];
        let mut draw = Draw::of(
            Viewport::new(12, 12).unwrap(),
            positions,
            Topology::TriangleList,
            vec![0, 1, 2],
        );
        draw.samples = samples;
        draw.state = DrawState {
            interpolation: at,
            sample_mask: mask,
            ..DrawState::default()
        };
        let mut frags = Vec::new();
        Reference::default().draw(&draw, |f| frags.push(f)).unwrap();
        frags
    }

    /// Under centroid a pixel's fragments are the at-sample draw's, with the barycentrics of
    /// the one-sample draw (the centre) where all four samples are covered, else of the first
    /// covered sample the mask keeps.
    #[test]
    fn centroid_is_the_centre_when_covered_else_the_first_kept_sample() {
        let centre: HashMap<_, _> = draw(Interpolation::Sample, u32::MAX, 1)
            .into_iter()
            .map(|f| ((f.x, f.y), f.barycentric))
            .collect();
        for mask in [u32::MAX, 0b1010] {
            let at_sample = draw(Interpolation::Sample, mask, 4);
            let all = draw(Interpolation::Sample, u32::MAX, 4);
            let centroid = draw(Interpolation::Centroid, mask, 4);
            assert_eq!(centroid.len(), at_sample.len());
            let (mut centres, mut samples) = (0, 0);
            for (c, s) in centroid.iter().zip(&at_sample) {
                assert_eq!((c.x, c.y, c.sample, c.depth), (s.x, s.y, s.sample, s.depth));
                let covered = all.iter().filter(|f| (f.x, f.y) == (c.x, c.y)).count();
                if covered == 4 {
                    assert_eq!(c.barycentric, centre[&(c.x, c.y)]);
                    centres += 1;
                } else {
                    let first = at_sample.iter().find(|f| (f.x, f.y) == (c.x, c.y)).unwrap();
                    assert_eq!(c.barycentric, first.barycentric);
                    samples += 1;
                }
            }
            assert!(centres > 20 && samples > 10, "{centres} {samples}");
        }
    }
}
