//! Conservative rasterization (Vulkan's `VK_EXT_conservative_rasterization`) as state: the
//! mode a draw asks for and what an implementation offers. Apart from the drawing
//! (`conservative_cover.rs`), because the draw state and the profile need these types and the
//! drawing needs the draw.

use std::hash::{Hash, Hasher};

/// How a filled triangle's pixels are chosen under conservative rasterization.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Conservative {
    /// Every pixel whose closed square the triangle's closed area touches, edges and corners
    /// included, the triangle first grown by `extra` pixels at each edge (Vulkan's
    /// `extraPrimitiveOverestimationSize`): every sample of each.
    Overestimate {
        /// Pixels the triangle grows by at each edge, `0 ≤ extra`.
        extra: f32,
    },
    /// Only the pixels whose closed square lies wholly inside the closed triangle: every
    /// sample of each.
    Underestimate,
}

impl Conservative {
    /// The word the pipe protocol and the case files use: `over,EXTRA` or `under`.
    #[must_use]
    pub fn words(self) -> String {
        match self {
            Self::Overestimate { extra } => format!("over,{extra:?}"),
            Self::Underestimate => "under".to_owned(),
        }
    }

    /// The mode [`Conservative::words`] names; `None` for anything else (a negative or
    /// non-finite extra size included).
    #[must_use]
    pub fn from_words(text: &str) -> Option<Self> {
        match text.split_once(',') {
            None if text == "under" => Some(Self::Underestimate),
            Some(("over", extra)) => {
                let extra: f32 = extra.parse().ok()?;
                (extra.is_finite() && extra >= 0.0).then_some(Self::Overestimate { extra })
            }
            _ => None,
        }
    }
}

/// The conservative rasterization an implementation offers on filled triangles, as Vulkan's
/// `VkPhysicalDeviceConservativeRasterizationPropertiesEXT` reports it
/// ([`StateSupport::conservative`](crate::StateSupport::conservative)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConservativeSupport {
    /// How far, in pixels, it may grow a triangle at each edge beyond what is asked
    /// (`primitiveOverestimationSize`): pixels that close may be covered too.
    pub overestimation_size: f32,
    /// The largest extra size it honours (`maxExtraPrimitiveOverestimationSize`); 0 for none.
    pub max_extra: f32,
    /// The steps its extra size comes in (`extraPrimitiveOverestimationSizeGranularity`): the
    /// size it grows by may fall short of the one asked by this much.
    pub extra_granularity: f32,
    /// Whether it offers underestimation (`primitiveUnderestimation`).
    pub underestimate: bool,
    /// Whether a triangle of zero area once snapped draws the pixels its segment or point
    /// touches (`degenerateTrianglesRasterized`), `Some(false)` when it is culled, `None`
    /// when unknown (either is accepted).
    pub degenerate_triangles: Option<bool>,
}

impl ConservativeSupport {
    /// The reference's: exact (no overestimation of its own), extra sizes up to 2 pixels on
    /// its 8-bit grid, underestimation, degenerate triangles culled.
    pub const REFERENCE: ConservativeSupport = ConservativeSupport {
        overestimation_size: 0.0,
        max_extra: 2.0,
        extra_granularity: 1.0 / 256.0,
        underestimate: true,
        degenerate_triangles: Some(false),
    };

    /// `mode` where offered: an extra size clamped to the largest, underestimation only
    /// where offered.
    #[must_use]
    pub fn fit(&self, mode: Conservative) -> Option<Conservative> {
        match mode {
            Conservative::Overestimate { extra } => Some(Conservative::Overestimate {
                extra: extra.clamp(0.0, self.max_extra),
            }),
            Conservative::Underestimate => self.underestimate.then_some(mode),
        }
    }
}

impl Eq for ConservativeSupport {}

impl Hash for ConservativeSupport {
    fn hash<H: Hasher>(&self, state: &mut H) {
        for size in [self.overestimation_size, self.max_extra, self.extra_granularity] {
            size.to_bits().hash(state);
        }
        (self.underestimate, self.degenerate_triangles).hash(state);
    }
}
