//! The entries, in the order `refrast impls` lists them: the reference's configurations, the
//! zoo, the third parties, `fast`.

use refrast::{ClipMode, LineRule, Rasterizer, Reference, ReferenceConfig, SubpixelBits};
use refrast_zoo::Named;
use refrast_zoo::course;
use refrast_zoo::mutant::{Bug, Mutant};
use refrast_zoo::restricted::restrictions;
use refrast_zoo::shaped::{Shape, Shaped};

use crate::{BuiltIn, Origin};

/// Every built-in (without the third parties when the `third-party` feature is off).
#[must_use]
pub fn all() -> Vec<BuiltIn> {
    let mut all = reference();
    all.extend(restricted());
    all.extend(shaped());
    all.extend(mutants());
    all.extend(course_labs());
    #[cfg(feature = "third-party")]
    all.extend(third_party());
    all.push(BuiltIn::new(
        "fast",
        "the reference's coverage with its own f32/f64 interpolation (2^-18): SIMD lanes, 64×64 tiles over threads",
        Origin::Ours,
        || Box::new(refrast_fast::Fast::default()),
    ));
    all
}

/// The reference and its other configurations.
fn reference() -> Vec<BuiltIn> {
    let named = |name: &'static str, config: ReferenceConfig| {
        move || Box::new(Named::new(name, config)) as Box<dyn Rasterizer>
    };
    let four_bits = ReferenceConfig {
        subpixel_bits: SubpixelBits::new(4).expect("4 is in range"),
        ..ReferenceConfig::default()
    };
    let full_clip = ReferenceConfig {
        clip: ClipMode::Full,
        ..ReferenceConfig::default()
    };
    let lines = |line: LineRule| ReferenceConfig {
        line,
        ..ReferenceConfig::default()
    };
    vec![
        BuiltIn::new(
            "reference",
            "the reference: 8 subpixel bits, top-left, guard-band clipping",
            Origin::Ours,
            || Box::new(Reference::default()),
        ),
        BuiltIn::new(
            "reference-full-clip",
            "the reference clipping all six planes (Sutherland–Hodgman, seed 004)",
            Origin::Ours,
            named("reference-full-clip", full_clip),
        ),
        BuiltIn::new(
            "reference-4bit",
            "the reference snapping to 4 subpixel bits (Vulkan's minimum)",
            Origin::Ours,
            named("reference-4bit", four_bits),
        ),
        BuiltIn::new(
            "reference-rectangle-lines",
            "the reference drawing lines as rectangles one pixel wide (Vulkan's strictLines)",
            Origin::Ours,
            named("reference-rectangle-lines", lines(LineRule::Rectangle)),
        ),
        BuiltIn::new(
            "reference-parallelogram-lines",
            "the reference drawing lines as parallelograms along the minor axis (Vulkan's non-strict lines)",
            Origin::Ours,
            named("reference-parallelogram-lines", lines(LineRule::Parallelogram)),
        ),
    ]
}

/// The reference restricted to each setting ([`refrast_zoo::restricted`]).
fn restricted() -> Vec<BuiltIn> {
    restrictions()
        .into_iter()
        .map(|r| {
            let make = r.make;
            BuiltIn::new(
                format!("restricted:{}", r.name),
                format!("the reference restricted: {}", r.description),
                Origin::Restricted,
                move || Box::new(make()),
            )
        })
        .collect()
}

/// The reference shaped like the rasterizers that exposed false verdicts
/// ([`refrast_zoo::shaped`]).
fn shaped() -> Vec<BuiltIn> {
    Shape::ALL
        .into_iter()
        .map(|shape| {
            BuiltIn::new(
                format!("shaped:{}", shape.name()),
                format!("the reference shaped: {}", shape.description()),
                Origin::Shaped,
                move || Box::new(Shaped::new(shape)),
            )
        })
        .collect()
}

/// Every mutant, named `mutant:NAME`.
fn mutants() -> Vec<BuiltIn> {
    Bug::ALL
        .iter()
        .map(|&bug| {
            BuiltIn::new(
                format!("mutant:{}", bug.name()),
                format!("the {} rules must catch it", bug.caught_by()),
                Origin::Mutant,
                move || Box::new(Mutant::new(bug)),
            )
        })
        .collect()
}

/// The course rasterizers, in seed order.
fn course_labs() -> Vec<BuiltIn> {
    course::labs()
        .into_iter()
        .map(|lab| BuiltIn::new(lab.name, lab.description, Origin::Course, lab.make))
        .collect()
}

/// euc, then every driver through wgpu.
#[cfg(feature = "third-party")]
fn third_party() -> Vec<BuiltIn> {
    let mut all = vec![BuiltIn::new(
        "euc",
        "the euc crate 0.5.3: f32 homogeneous rasterization, no clipping, no tie rule",
        Origin::ThirdParty,
        || Box::new(refrast_euc::Euc),
    )];
    all.extend(refrast_wgpu::Driver::ALL.iter().map(|&driver| {
        let mut b = BuiltIn::fallible(
            driver.name(),
            driver.description(),
            Origin::ThirdParty,
            move || Ok(Box::new(refrast_wgpu::Gpu::new(driver)?) as Box<dyn Rasterizer>),
        );
        for (name, value) in driver.env() {
            b = b.with_env(name, value);
        }
        b
    }));
    all
}
