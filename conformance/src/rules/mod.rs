//! The rule catalogue: one entry per rule, grouped by family.

pub mod bary;
pub mod clip;
pub mod common;
pub mod depth;
pub mod fill;
pub mod meta;
pub mod robust;

use std::fmt;

use refrast::{Profile, Rasterizer};

use crate::runner::{RunConfig, Verdict};

/// A rule family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Family {
    /// Coverage and the fill rule: watertight meshes, ownership of shared edges.
    Fill,
    /// Barycentric coordinates.
    Bary,
    /// Depth values and the depth test.
    Depth,
    /// Clipping.
    Clip,
    /// Metamorphic relations: transformations that must not change the answer (or change it predictably).
    Meta,
    /// Bad and extreme input.
    Robust,
}

impl Family {
    /// The family's name, the first part of its rules' IDs.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Fill => "fill",
            Self::Bary => "bary",
            Self::Depth => "depth",
            Self::Clip => "clip",
            Self::Meta => "meta",
            Self::Robust => "robust",
        }
    }
}

/// Whether a rule holds for any correct rasterizer or pins one exact answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// Holds for every correct rasterizer, within the profile's tolerance band.
    Invariant,
    /// Bit-identical to the reference (or the brute-force oracle) under the same profile.
    Exact,
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(match self {
            Self::Invariant => "invariant",
            Self::Exact => "exact",
        })
    }
}

/// One rule of the catalogue.
#[derive(Clone, Copy)]
pub struct Rule {
    /// Stable ID, `family.subject.property`.
    pub id: &'static str,
    /// Its family.
    pub family: Family,
    /// Invariant or exact.
    pub kind: Kind,
    /// The rule in one sentence.
    pub sentence: &'static str,
    /// Where it comes from: a seed document, a spec section.
    pub source: &'static str,
    /// Cases tried by default (the cost of one case varies by rule).
    pub default_cases: u32,
    /// `Err(reason)` when the rule does not apply to a profile.
    pub applies: fn(&Profile) -> Result<(), &'static str>,
    /// Runs the rule's property against a rasterizer.
    pub run: fn(&mut dyn Rasterizer, &RunConfig) -> Verdict,
}

impl fmt::Debug for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Rule")
            .field("id", &self.id)
            .field("kind", &self.kind)
            .finish_non_exhaustive()
    }
}

/// Applies to every profile.
pub(crate) fn always(_: &Profile) -> Result<(), &'static str> {
    Ok(())
}

/// Every rule, in catalogue order.
#[must_use]
pub fn catalogue() -> Vec<Rule> {
    let mut rules = Vec::new();
    rules.extend(fill::rules());
    rules.extend(bary::rules());
    rules.extend(depth::rules());
    rules.extend(clip::rules());
    rules.extend(meta::rules());
    rules.extend(robust::rules());
    rules
}
