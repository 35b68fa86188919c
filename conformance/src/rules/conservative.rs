//! Conservative rasterization: under overestimation a triangle covers every pixel its closed
//! area touches (grown by the extra size), under underestimation only the pixels wholly inside
//! it, every sample of each; degenerate triangles as the profile declares.
//!
//! The oracle works in f64 on each snapped form of the triangle the profile allows, projected
//! to the screen: a pixel is required where every form touches its square shrunk by a hair
//! (grown by the least the extra size may be: the disc reading of "increased at each of its
//! edges", less twice the declared granularity; the square shrunk by the snapping band, as a
//! clipped polygon's cut vertices snap too), and allowed where some form, each edge pushed out
//! by the extra size, the declared overestimation and the snapping band (corners mitered: the
//! most it may mean), touches the square grown by a hair. Underestimation requires the pixels
//! every form holds with a band to spare and allows those some form holds less a band. No code
//! is shared with the reference, which decides in subpixel integers.

use std::collections::BTreeMap;

use refrast::{Conservative, ConservativeSupport, CullMode, Fragment, Profile, Rasterizer};

use super::cast::snapped_triangles;
use super::level::Level;
use super::samples::sample_fragments;
use super::{Family, Need, Rule, needs};
use crate::oracle::raster::project;
use crate::oracle::squares::{Screen, clip_to_box, collinear, distance, flat, holds, mitered, square, width};
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::strategy::primitive;
use crate::violation::{Findings, Violation, plural};

/// How far a pixel's square is shrunk or grown so that f64 rounding never decides a verdict.
const HAIR: f64 = 1e-6;

/// What the rule expects of one pixel.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Pixel {
    Required,
    Allowed,
    Forbidden,
}

/// The case's snapped forms of its first triangle on the screen, and what it expects of
/// every pixel of the viewport; `None` where it judges nothing (forms of both zero and
/// nonzero area).
fn expectations(case: &PrimitiveScene, profile: &Profile) -> Option<Vec<Pixel>> {
    let scene = &case.scene;
    let support = profile.state.conservative?;
    let mode = scene.state.conservative?;
    // The generator sends neither; a pasted case with them is not judged here.
    if scene.state.scissor.is_some() || scene.state.sample_mask != refrast::DrawState::ALL_SAMPLES {
        return None;
    }
    let forms: Vec<Screen> = snapped_triangles(scene, 0, profile)
        .iter()
        .map(|t| t.map(|p| project(scene.width, scene.height, p)))
        .collect();
    let input = scene
        .positions_of(0)
        .map(|p| project(scene.width, scene.height, p.map(f64::from)));
    let degenerate = forms.iter().filter(|t| flat(t)).count();
    if forms.is_empty() || (degenerate > 0 && degenerate < forms.len()) {
        return None;
    }
    let zero = degenerate > 0;
    let bits = profile.snapping.grid_bits().unwrap_or(8);
    let band = f64::from(profile.tolerance_subpixels) / f64::from(1u32 << bits.min(16));
    let (w, h) = (scene.width, scene.height);
    // What must be drawn grows only the part inside the viewport: Vulkan clips to the view
    // volume first, where a guard band would grow the rest too (which is allowed).
    let viewport = [0.0, 0.0, f64::from(w), f64::from(h)];
    let inside: Vec<Vec<[f64; 2]>> = forms.iter().map(|t| clip_to_box(t, viewport)).collect();
    // A sliver the viewport cuts, within the band of a line, may snap to no area where an
    // implementation clips it there (its cut vertices snap): then culling it is right too.
    let cut = forms.iter().any(|t| {
        t.iter()
            .any(|p| !(0.0..=viewport[2]).contains(&p[0]) || !(0.0..=viewport[3]).contains(&p[1]))
    });
    let may_vanish = cut && inside.iter().any(|p| width(p) <= 2.0 * band);
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            out.push(match mode {
                Conservative::Underestimate => {
                    let inside = |t: &Screen, g: f64| {
                        let [x0, y0, x1, y1] = square(x, y, g);
                        [[x0, y0], [x1, y0], [x0, y1], [x1, y1]]
                            .iter()
                            .all(|&c| holds(t, c, 0.0))
                    };
                    if forms.iter().all(|t| inside(t, band + HAIR)) {
                        Pixel::Required
                    } else if forms.iter().any(|t| inside(t, -band - HAIR)) {
                        Pixel::Allowed
                    } else {
                        Pixel::Forbidden
                    }
                }
                Conservative::Overestimate { extra } => {
                    let extra = f64::from(extra);
                    let least = (extra - 2.0 * f64::from(support.extra_granularity)).max(0.0);
                    let most = extra
                        + f64::from(support.overestimation_size)
                        + f64::from(support.extra_granularity)
                        + band;
                    // The square shrunk by the band: a cut vertex snapped where the polygon is
                    // clipped moves its edges by up to that much.
                    let touched = inside
                        .iter()
                        .all(|t| distance(t, square(x, y, -band - HAIR)) <= least);
                    let reached = forms.iter().any(|t| match mitered(t, most) {
                        Some(m) => !clip_to_box(&m, square(x, y, HAIR)).is_empty(),
                        None => distance(t, square(x, y, HAIR)) <= most * std::f64::consts::SQRT_2,
                    });
                    // Degenerate once snapped: culled, drawn as what its segment touches, or
                    // either (unknown, or zero area before snapping already); back-facing
                    // (Vulkan: "Degenerate triangles are considered backfacing"), so culled
                    // where back faces are.
                    let drawn = if may_vanish {
                        None
                    } else if !zero {
                        Some(true)
                    } else if matches!(scene.state.cull, CullMode::Back | CullMode::FrontAndBack) {
                        Some(false)
                    } else if collinear(&input) {
                        None
                    } else {
                        support.degenerate_triangles
                    };
                    match drawn {
                        Some(true) if touched => Pixel::Required,
                        Some(false) => Pixel::Forbidden,
                        _ if reached => Pixel::Allowed,
                        _ => Pixel::Forbidden,
                    }
                }
            });
        }
    }
    Some(out)
}

/// A conservative draw of one triangle covers every pixel it is required to and none it may
/// not, every sample of each.
pub fn check_conservative(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let Some(expected) = expectations(case, &profile) else {
        return Ok(());
    };
    let frags = sample_fragments(r, case)?;
    let mut pixels: BTreeMap<(u32, u32), u64> = BTreeMap::new();
    for f in frags.iter().filter(|f: &&Fragment| f.primitive == 0) {
        *pixels.entry((f.x, f.y)).or_default() |= 1 << f.sample.min(63);
    }
    let all = (1u64 << case.samples.min(63)) - 1;
    let width = case.scene.width;
    let mode = case
        .scene
        .state
        .conservative
        .map(Conservative::words)
        .unwrap_or_default();
    let mut found = Findings::new();
    for y in 0..case.scene.height {
        for x in 0..width {
            let want = expected[(y * width + x) as usize];
            let got = pixels.get(&(x, y)).copied();
            let problem = match (want, got) {
                (Pixel::Required, None) => Some("not drawn, where the triangle requires it".to_owned()),
                (Pixel::Forbidden, Some(_)) => Some("drawn, beyond what the triangle may reach".to_owned()),
                (_, Some(bits)) if bits & all != all => Some(format!(
                    "drawn at samples {bits:#b} of {}, where a conservative fragment covers them all",
                    case.samples
                )),
                _ => None,
            };
            if let Some(what) = problem {
                found.add((x, y), || format!("({x}, {y}) {what} ({mode})"));
            }
        }
    }
    found.verdict(|n| {
        format!(
            "{} of a conservative triangle ({mode}) drawn wrong",
            plural(n, "pixel")
        )
    })
}

/// The implementation offers conservative rasterization.
const CONSERVATIVE: Need = needs(
    |p| p.state.conservative.is_some(),
    "no conservative rasterization",
);

/// The implementation offers underestimation.
const UNDERESTIMATE: Need = needs(
    |p| {
        p.state
            .conservative
            .is_some_and(|c: ConservativeSupport| c.underestimate)
    },
    "no conservative underestimation",
);

/// Why OpenGL and OpenGL ES do not judge it.
const NOT_CORE: &str = "OpenGL 4.6 and OpenGL ES 3.2 have no conservative rasterization in core (NV_conservative_raster and INTEL_conservative_rasterization are extensions)";

/// Why D3D11.3 does not judge it.
const EMPTY_SECTION: &str =
    "D3D11.3 §15.17 Conservative Rasterization is empty (\"TODO\"): the rules are D3D12's and Vulkan's";

/// Where the rules come from.
const SOURCE: &str = "Vulkan 1.4, Conservative Rasterization (VK_EXT_conservative_rasterization: overestimation, primitiveOverestimationSize, extraPrimitiveOverestimationSize, degenerateTrianglesRasterized, underestimation); dEQP-VK.rasterization.conservative.*";

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Fill, "fill.conservative.over")
            .sentence("Under overestimation a triangle covers every pixel whose closed square its closed snapped area touches, grown by the extra size (less its granularity), all samples of each, and no pixel beyond its edges pushed out by the extra size, the declared overestimation size and granularity; a triangle of zero area once snapped draws nothing where degenerate triangles are declared culled, and the pixels its segment touches where declared rasterized.")
            .source(SOURCE)
            .cases(600)
            .needs(CONSERVATIVE)
            .vulkan_and_opengl(Level::NotCovered(NOT_CORE))
            .vulkan(Level::Required)
            .d3d11(Level::NotCovered(EMPTY_SECTION))
            .run(|r, cfg| property_for(r, cfg, |d| primitive::conservative(d, false), check_conservative)),
        Rule::invariant(Family::Fill, "fill.conservative.under")
            .sentence("Under underestimation a triangle covers exactly the pixels whose closed square lies inside its closed snapped area, all samples of each, outside the tolerance band.")
            .source(SOURCE)
            .cases(400)
            .needs(UNDERESTIMATE)
            .vulkan_and_opengl(Level::NotCovered(NOT_CORE))
            .vulkan(Level::Required)
            .d3d11(Level::NotCovered(EMPTY_SECTION))
            .run(|r, cfg| property_for(r, cfg, |d| primitive::conservative(d, true), check_conservative)),
    ]
}

#[cfg(test)]
mod tests {
    use refrast::{Conservative, Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Topology};

    use super::check_conservative;
    use crate::scene::{PrimitiveScene, Scene};

    /// The reference drawing a triangle that draws nothing (degenerate, culled) as its edges,
    /// declaring that degenerate triangles are rasterized (`Some(true)`) or not saying
    /// (`None`).
    struct DrawnDegenerates(Option<bool>);

    impl Rasterizer for DrawnDegenerates {
        fn profile(&self) -> Profile {
            let mut p = Reference::default().profile();
            if let Some(c) = &mut p.state.conservative {
                c.degenerate_triangles = self.0;
            }
            p
        }

        fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
            let mut out = Reference::default().rasterize(draw)?;
            if out.is_empty() {
                let edges = Draw::of(
                    draw.viewport,
                    draw.positions.clone(),
                    Topology::LineList,
                    vec![0, 1, 1, 2, 2, 0],
                );
                out = Reference::default().rasterize(&Draw {
                    samples: draw.samples,
                    ..edges
                })?;
                for f in &mut out {
                    f.primitive = 0;
                }
            }
            Ok(out)
        }
    }

    /// A triangle over 20×16 a sixteenth of a grid step off its line, so of zero area once
    /// snapped (vertices in 1/4096 px).
    fn degenerate() -> PrimitiveScene {
        let t = [
            (16 * 300, 16 * 200),
            (16 * 900, 16 * 600),
            (16 * 600, 16 * 400 + 1),
        ];
        let mut scene = Scene::from_subpixels(20, 16, 12, &[t], 0.5);
        scene.state.conservative = Some(Conservative::Overestimate { extra: 0.0 });
        PrimitiveScene::triangles(scene, 1)
    }

    /// A triangle over 20×16 at one sample, overestimated with no extra size.
    fn over(positions: [[f32; 4]; 3]) -> PrimitiveScene {
        let mut scene = Scene::new(20, 16, positions.to_vec(), vec![[0, 1, 2]]);
        scene.state.conservative = Some(Conservative::Overestimate { extra: 0.0 });
        PrimitiveScene::triangles(scene, 1)
    }

    /// Two false verdicts the reference clipping all six planes got: a sliver cut by the
    /// viewport's top, its cut vertices snapped, missing a pixel whose corner the exact cut
    /// touches (the required set now shrinks the square by the band); and a sliver 0.0004 px
    /// wide cut at the top and bottom, which snaps to no area once clipped and is culled (a
    /// sliver the viewport cuts within the band of a line is required nothing).
    #[test]
    fn slivers_a_full_clip_snaps_are_not_failed() {
        let full_clip = || {
            Reference::new(refrast::ReferenceConfig {
                clip: refrast::ClipMode::Full,
                ..refrast::ReferenceConfig::default()
            })
        };
        let cut_at_top = over([
            [0.2722656, 1.1723633, 0.5, 1.0],
            [-1.0, -0.6982422, 0.5, 1.0],
            [-1.0, -0.69873047, 0.5, 1.0],
        ]);
        let cut_twice = over([
            [0.5132812, -1.0327148, 0.5, 1.0],
            [0.52734375, -0.63964844, 0.5, 1.0],
            [0.5894531, 1.0927734, 0.5, 1.0],
        ]);
        for case in [cut_at_top, cut_twice] {
            assert_eq!(check_conservative(&mut full_clip(), &case), Ok(()));
            assert_eq!(check_conservative(&mut Reference::default(), &case), Ok(()));
        }
    }

    /// Culled is right for the reference, which declares it; edges drawn where culling is
    /// declared is wrong; where the profile does not say, either passes; where it declares
    /// them rasterized, edges alone miss pixels the segment touches.
    #[test]
    fn degenerate_triangles_are_judged_as_declared() {
        assert_eq!(
            check_conservative(&mut Reference::default(), &degenerate()),
            Ok(())
        );
        let err = check_conservative(&mut DrawnDegenerates(Some(false)), &degenerate())
            .expect_err("declared culled");
        assert!(
            err.message.contains("beyond what the triangle may reach"),
            "{}",
            err.message
        );
        assert_eq!(
            check_conservative(&mut DrawnDegenerates(None), &degenerate()),
            Ok(())
        );
        let err = check_conservative(&mut DrawnDegenerates(Some(true)), &degenerate())
            .expect_err("edges are not every touched pixel");
        assert!(
            err.message.contains("not drawn, where the triangle requires it"),
            "{}",
            err.message
        );
    }
}
