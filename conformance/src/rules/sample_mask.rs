//! The sample mask test: a draw with a sample mask makes exactly the fragments it makes without
//! one whose sample's bit is set, and its depth test leaves every other sample as the clear
//! left it.
//!
//! Both rules compare the implementation with itself (the same draw with and without the
//! mask), so they hold whatever its conventions: no oracle, no tolerance band.

use proptest::prelude::*;
use proptest::strategy::Union;
use refrast::{DrawState, Fragment, Profile, Rasterizer, Spec, Topology};

use super::level::Level;
use super::samples::{
    cell_counts, difference_counts, difference_picture, keys, resolved_split, sample_fragments,
};
use super::{DEPTH_TEST, Family, Need, Rule, needs};
use crate::runner::property_for;
use crate::scene::PrimitiveScene;
use crate::strategy::{self, primitive};
use crate::violation::{Violation, plural};

/// What every specification says of the sample mask.
const SOURCE: &str = "Vulkan 1.4, Sample Mask Test (fragops-samplemask); OpenGL 4.6 §14.9.3 and OpenGL ES 3.2 §13.8.3 (SAMPLE_MASK_VALUE); D3D11.3 §17.17 (SampleMask); WebGPU's multisample.mask; dEQP-VK.pipeline.*.multisample.sample_mask.*";

/// D3D11.3 maps the mask's bits to samples as the implementation chooses.
const ANY_MAPPING: &str = "D3D11.3 §17.17: \"The mapping of bits in SampleMask to samples in a multisample RenderTarget is up to the individual implmentation to decide (as long as it is some 1:1 mapping)\": only that as many samples are kept as the sample count's low bits of the mask set, each with the fragments the draw without a mask makes there, and that the complementary mask keeps the others, is required";

/// D3D11.3 names render targets, not the depth buffer, as what the mask keeps from update.
const DEPTH_NOT_NAMED: &str = "D3D11.3 §17.17 says the mask determines \"which samples get updated in all the active Rendertargets\", and no sentence names the depth-stencil buffer (nor which sample a bit is)";

/// The implementation honours a sample mask at some sample count its specification applies
/// one at.
const SAMPLE_MASK: Need = needs(
    |p| p.state.sample_mask && !masked_counts(p, Topology::TriangleList).is_empty(),
    "no sample mask at a sample count its specification applies one at",
);

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Msaa, "msaa.sample-mask.drops")
            .sentence("With a sample mask, a draw of any topology at any declared sample count makes exactly the fragments the same draw makes without one whose sample's bit of the mask is set (bit i for sample i; bit 0 at one sample, except under OpenGL and OpenGL ES, whose mask applies to multisampled targets only): none at a cleared bit's sample, none lost or added at a set bit's.")
            .source(SOURCE)
            .cases(600)
            .needs(SAMPLE_MASK)
            .d3d11(Level::Partly {
                part: |r, cfg| property_for(r, cfg, masked_draws, check_drops_any_mapping),
                note: ANY_MAPPING,
            })
            .run(|r, cfg| property_for(r, cfg, masked_draws, check_drops)),
        Rule::invariant(Family::Depth, "depth.sample-mask.untouched")
            .sentence("With a sample mask, the depth and primitive buffers the depth test leaves equal, at each sample whose bit is set, those of the same draw without one, and at each other sample those of a draw of nothing: a masked sample is neither tested nor written.")
            .source(SOURCE)
            .cases(300)
            .needs(SAMPLE_MASK)
            .needs(DEPTH_TEST)
            .d3d11(Level::NotCovered(DEPTH_NOT_NAMED))
            .run(|r, cfg| property_for(r, cfg, masked_triangles, check_resolve_drops)),
    ]
}

/// Whether `spec` applies the sample mask at `samples` samples: every one at every count but
/// OpenGL's and OpenGL ES's, whose multisample fragment operations (the mask among them) run
/// only where the framebuffer has sample buffers (`SAMPLE_BUFFERS` one: more than one sample).
#[must_use]
pub fn masks_at(spec: Spec, samples: u8) -> bool {
    samples > 1 || !matches!(spec, Spec::OpenGl | Spec::OpenGlEs)
}

/// The sample counts at which `p` draws `topology` and its specification applies a mask.
fn masked_counts(p: &Profile, topology: Topology) -> Vec<u8> {
    p.sample_counts()
        .into_iter()
        .filter(|&n| p.draws(topology, n) && masks_at(p.spec, n))
        .collect()
}

/// The triangles the rules draw: a mesh over the viewport, or overlapping triangles, at each
/// sample count `p` masks at.
fn triangles(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let scenes = prop_oneof![strategy::mesh_scene(), strategy::overlapping_scene()];
    primitive::multisampled(scenes, masked_counts(p, Topology::TriangleList)).boxed()
}

/// Triangles, with a sample mask.
fn masked_triangles(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    primitive::sample_masked(triangles(p)).boxed()
}

/// Every topology `p` draws, at each sample count it masks it at, with a sample mask.
fn masked_draws(p: &Profile) -> BoxedStrategy<PrimitiveScene> {
    let mut kinds = vec![triangles(p)];
    let lines = masked_counts(p, Topology::LineList);
    if p.lines.is_some() && !lines.is_empty() {
        kinds.push(primitive::multisampled_primitives(strategy::reach::any_lines(p), lines).boxed());
    }
    let points = masked_counts(p, Topology::PointList);
    if p.points && !points.is_empty() {
        kinds.push(primitive::multisampled_primitives(primitive::points(), points).boxed());
    }
    primitive::sample_masked(Union::new(kinds)).boxed()
}

/// `case` without its sample mask.
fn unmasked(case: &PrimitiveScene) -> PrimitiveScene {
    let mut whole = case.clone();
    whole.scene.state.sample_mask = DrawState::ALL_SAMPLES;
    whole
}

/// The mask's bits at `samples` samples, as a sentence names them: `0b0101` (samples 0 and 2).
fn describe(mask: u32, samples: u8) -> String {
    let kept: Vec<String> = (0..samples)
        .filter(|&s| mask >> s & 1 == 1)
        .map(|s| s.to_string())
        .collect();
    let bits = format!(
        "{:0width$b}",
        mask & low_bits(samples),
        width = usize::from(samples)
    );
    match kept.len() {
        0 => format!("the sample mask {mask:#x} (no sample of {samples} kept)"),
        1 => format!("the sample mask {mask:#x} (0b{bits}: sample {} kept)", kept[0]),
        _ => format!(
            "the sample mask {mask:#x} (0b{bits}: samples {} kept)",
            kept.join(", ")
        ),
    }
}

/// The mask of the low `samples` bits.
fn low_bits(samples: u8) -> u32 {
    u32::MAX >> (u32::BITS - u32::from(samples.clamp(1, 32)))
}

/// A draw with a mask makes the fragments it makes without one, those at samples it keeps.
pub fn check_drops(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let mask = case.scene.state.sample_mask;
    if mask == DrawState::ALL_SAMPLES {
        return Ok(());
    }
    let kept = |f: &Fragment| mask >> f.sample & 1 == 1;
    let cut = sample_fragments(r, case)?;
    let whole = sample_fragments(r, &unmasked(case))?;
    let inside: Vec<&Fragment> = whole.iter().filter(|f| kept(f)).collect();
    if keys(&cut) == keys(inside.iter().copied()) {
        return Ok(());
    }
    let (got, want) = (cell_counts(case, &cut), cell_counts(case, inside.iter().copied()));
    let dropped = cut.iter().filter(|f| !kept(f)).count();
    let named = describe(mask, case.samples);
    let message = if let Some(f) = cut.iter().find(|f| !kept(f)) {
        format!(
            "{} at a sample {named} drops: the first at ({}, {}) sample {}, of primitive {}",
            plural(dropped, "fragment"),
            f.x,
            f.y,
            f.sample,
            f.primitive
        )
    } else if got == want {
        format!(
            "with {named} the draw covers the kept samples it covers without a mask, but names other primitives for them"
        )
    } else {
        let (lost, added) = got.iter().zip(&want).fold((0, 0), |(l, a), (&g, &w)| {
            (l + w.saturating_sub(g), a + g.saturating_sub(w))
        });
        format!(
            "with {named} the draw makes other fragments at the kept samples than without a mask: {lost} lost, {added} added"
        )
    };
    let mut violation = Violation::new(message);
    violation.counts = Some(Box::new(difference_counts(&got, &want)));
    violation.picture = Some(Box::new(difference_picture(case, &got, &want, Vec::new())));
    Err(violation)
}

/// A draw with a mask keeps some samples, as many as the mask's bits below the sample count,
/// each with the fragments it makes there without a mask, and the complementary mask keeps
/// the rest: D3D11.3's "some 1:1 mapping" (one draw's; the mapping may differ between draws).
pub fn check_drops_any_mapping(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let mask = case.scene.state.sample_mask;
    if mask == DrawState::ALL_SAMPLES {
        return Ok(());
    }
    let cut = sample_fragments(r, case)?;
    let whole = sample_fragments(r, &unmasked(case))?;
    let drawn: Vec<u8> = (0..case.samples)
        .filter(|&s| cut.iter().any(|f| f.sample == s))
        .collect();
    let kept = (mask & low_bits(case.samples)).count_ones() as usize;
    // The kept samples the draw leaves empty must be samples the draw without a mask leaves
    // empty too.
    let spare = (0..case.samples)
        .filter(|&s| !drawn.contains(&s) && !whole.iter().any(|f| f.sample == s))
        .count();
    let at_drawn: Vec<&Fragment> = whole.iter().filter(|f| drawn.contains(&f.sample)).collect();
    let fits = drawn.len() <= kept && kept - drawn.len() <= spare;
    let named = describe(mask, case.samples);
    if fits && keys(&cut) == keys(at_drawn.iter().copied()) {
        return check_complement(r, case, &whole, &drawn, &named);
    }
    let message = if drawn.len() > kept {
        format!(
            "with {named} the draw makes fragments at {} of {} samples, where the mask keeps {kept}",
            drawn.len(),
            case.samples
        )
    } else if !fits {
        format!(
            "with {named} the draw makes fragments at {} of {} samples, where the mask keeps {kept} and the draw without it covers more",
            drawn.len(),
            case.samples
        )
    } else {
        "at the samples it draws, the draw makes other fragments than without a mask".to_owned()
    };
    let (got, want) = (
        cell_counts(case, &cut),
        cell_counts(case, at_drawn.iter().copied()),
    );
    let mut violation = Violation::new(message);
    violation.counts = Some(Box::new(difference_counts(&got, &want)));
    violation.picture = Some(Box::new(difference_picture(case, &got, &want, Vec::new())));
    Err(violation)
}

/// A 1:1 mapping sends the bits a mask clears to the samples it does not keep: the draw under
/// the complementary mask (its low bits) makes exactly the fragments of the draw without a mask
/// at the samples `drawn` (those the mask kept) leaves out.
fn check_complement(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    whole: &[Fragment],
    drawn: &[u8],
    named: &str,
) -> Result<(), Violation> {
    let complement = !case.scene.state.sample_mask & low_bits(case.samples);
    let mut other = case.clone();
    other.scene.state.sample_mask = complement;
    let rest = sample_fragments(r, &other)?;
    let elsewhere: Vec<&Fragment> = whole.iter().filter(|f| !drawn.contains(&f.sample)).collect();
    if keys(&rest) == keys(elsewhere.iter().copied()) {
        return Ok(());
    }
    let (got, want) = (
        cell_counts(case, &rest),
        cell_counts(case, elsewhere.iter().copied()),
    );
    let mut violation = Violation::new(format!(
        "with {named} the draw keeps samples {drawn:?}, but with the complementary mask {complement:#x} it does not make the other samples' fragments of the draw without a mask (no 1:1 mapping of bits to samples gives both)"
    ));
    violation.counts = Some(Box::new(difference_counts(&got, &want)));
    violation.picture = Some(Box::new(difference_picture(case, &got, &want, Vec::new())));
    Err(violation)
}

/// The depth test with a mask leaves the kept samples as without one, the others as a draw of
/// nothing leaves them (the implementation's own clear value, in its own format).
pub fn check_resolve_drops(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let mask = case.scene.state.sample_mask;
    if mask == DrawState::ALL_SAMPLES {
        return Ok(());
    }
    let findings = resolved_split(
        r,
        case,
        &unmasked(case),
        |_, _, s| mask >> s & 1 == 1,
        ["kept", "masked", "the draw without a mask"],
    )?;
    findings.verdict(|n| {
        format!(
            "with {} the depth test leaves {} other than it should",
            describe(mask, case.samples),
            plural(n, "sample")
        )
    })
}

#[cfg(test)]
mod tests {
    use refrast::{Draw, DrawError, Reference};

    use super::*;
    use crate::scene::Scene;

    /// The reference reading the mask's low bits through another mapping: rotated by one
    /// sample (bit i keeps sample i + 1, a 1:1 mapping D3D11.3 allows), or packed onto the
    /// lowest samples (as many kept, but no mapping: two masks can keep the same sample).
    struct Remapped {
        packed: bool,
    }

    impl Rasterizer for Remapped {
        fn profile(&self) -> Profile {
            Profile {
                spec: Spec::D3d11,
                ..Reference::default().profile()
            }
        }

        fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
            let (n, low) = (u32::from(draw.samples), low_bits(draw.samples));
            let m = draw.state.sample_mask & low;
            let mut read = draw.clone();
            read.state.sample_mask = if self.packed {
                low_bits(m.count_ones() as u8) & if m == 0 { 0 } else { u32::MAX }
            } else {
                ((m << 1) | (m >> (n - 1))) & low
            };
            Reference::default().rasterize(&read)
        }
    }

    /// A square over a 4×4 target at 4 samples, masked to samples 0 and 2.
    fn square() -> PrimitiveScene {
        let scene = Scene::new(
            4,
            4,
            vec![
                [-1.0, -1.0, 0.5, 1.0],
                [1.0, -1.0, 0.5, 1.0],
                [1.0, 1.0, 0.5, 1.0],
                [-1.0, 1.0, 0.5, 1.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let mut case = PrimitiveScene::triangles(scene, 4);
        case.scene.state.sample_mask = 0b0101;
        case
    }

    /// Under D3D11.3 a rotated mapping passes the part its specification requires and fails
    /// the whole rule; a packing that is no mapping fails both.
    #[test]
    fn d3d11_accepts_any_one_to_one_mapping_and_no_other() {
        let case = square();
        let mut rotated = Remapped { packed: false };
        assert!(check_drops_any_mapping(&mut rotated, &case).is_ok());
        assert!(check_drops(&mut rotated, &case).is_err());
        let mut packed = Remapped { packed: true };
        let err = check_drops_any_mapping(&mut packed, &case).expect_err("samples 0 and 1 for either mask");
        assert!(err.message.contains("complementary mask"), "{}", err.message);
        assert!(check_drops_any_mapping(&mut Reference::default(), &case).is_ok());
    }

    /// A mask is named by the bits its sample count reads, and the samples they keep.
    #[test]
    fn a_mask_is_named_by_the_samples_it_keeps() {
        assert_eq!(
            describe(0b0101, 4),
            "the sample mask 0x5 (0b0101: samples 0, 2 kept)"
        );
        assert_eq!(
            describe(0xffff_fff0, 4),
            "the sample mask 0xfffffff0 (no sample of 4 kept)"
        );
        assert_eq!(describe(2, 1), "the sample mask 0x2 (no sample of 1 kept)");
        assert_eq!(
            describe(0x8000, 16),
            "the sample mask 0x8000 (0b1000000000000000: sample 15 kept)"
        );
    }

    /// OpenGL and OpenGL ES mask multisampled draws only; the others every draw.
    #[test]
    fn the_mask_applies_at_one_sample_outside_opengl() {
        assert!(masks_at(Spec::Vulkan, 1) && masks_at(Spec::D3d11, 1) && masks_at(Spec::Refrast, 1));
        assert!(!masks_at(Spec::OpenGl, 1) && !masks_at(Spec::OpenGlEs, 1));
        assert!(masks_at(Spec::OpenGlEs, 4));
    }
}
