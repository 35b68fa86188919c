//! The rule catalogue: one entry per rule, grouped by family.

pub mod bary;
pub mod bias;
pub mod cast;
pub mod centroid;
pub mod clip;
pub mod common;
pub mod conservative;
pub mod depth;
pub mod distance;
pub mod fill;
pub mod flat;
pub mod hint;
pub mod level;
pub mod line;
pub mod mesh;
pub mod meta;
pub mod msaa;
mod needs;
pub mod point;
pub mod polygon;
mod reading;
pub mod robust;
pub mod sample_bary;
pub mod sample_depth;
pub mod sample_mask;
pub mod samples;
pub mod scissor;
pub mod ties;
pub mod vertices;
pub mod viewport_depth;
mod weights;
pub mod why;

use std::fmt;

use refrast::{Profile, Rasterizer};

use crate::runner::{RunConfig, Verdict};
pub use level::{Level, Levels};
pub use needs::{
    ANY_BARYCENTRICS, CLIPS_IN_3D, CULLING, DEPTH_TEST, EXACT_COVERAGE, EXTREME_OPS, EXTREME_WINS,
    FAR_CLIPPING, GL_DEPTH_RANGE, GUARD_BAND, Need, PERSPECTIVE_BARYCENTRICS, REFERENCE_PROFILE,
    SCREEN_BARYCENTRICS, VERTEX_ON_SAMPLE, Z_OVER_W_DEPTH, needs,
};

/// A rule family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
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
    /// Lines of width one.
    Line,
    /// Points of size one.
    Point,
    /// Several samples per pixel.
    Msaa,
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
            Self::Line => "line",
            Self::Point => "point",
            Self::Msaa => "msaa",
        }
    }
}

/// Whether a rule holds for any correct rasterizer or pins one exact answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
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

/// The property a rule runs against a rasterizer.
pub type Run = fn(&mut dyn Rasterizer, &RunConfig) -> Verdict;

/// One rule of the catalogue; built with [`Rule::invariant`] or [`Rule::exact`].
#[derive(Clone)]
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
    /// What a profile must declare for the rule to apply; none for every profile.
    pub needs: Vec<Need>,
    /// Whether its inputs are drawn as generated, whatever the cull mode: for the rules about
    /// facing and culling themselves. Otherwise a triangle a restricted cull mode would discard
    /// is turned to face front first.
    pub keeps_winding: bool,
    /// What Vulkan, OpenGL and D3D11.3 each require of what it checks.
    pub levels: Levels,
    /// Runs the rule's property against a rasterizer.
    pub run: Run,
}

impl Rule {
    /// An invariant rule of `family` called `id`; finish it with the draft's `run`.
    #[must_use]
    pub fn invariant(family: Family, id: &'static str) -> RuleDraft {
        RuleDraft::new(family, Kind::Invariant, id)
    }

    /// An exact rule of `family` called `id`; finish it with the draft's `run`.
    #[must_use]
    pub fn exact(family: Family, id: &'static str) -> RuleDraft {
        RuleDraft::new(family, Kind::Exact, id)
    }

    /// `Err(reason)` when the rule does not apply to an implementation declaring `profile`:
    /// the first need it lacks.
    pub fn applies(&self, profile: &Profile) -> Result<(), &'static str> {
        self.needs.iter().try_for_each(|need| need.check(profile))
    }
}

impl fmt::Debug for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Rule")
            .field("id", &self.id)
            .field("kind", &self.kind)
            .finish_non_exhaustive()
    }
}

/// A rule being built: everything but its property, which [`RuleDraft::run`] adds.
#[derive(Clone, Debug)]
pub struct RuleDraft {
    id: &'static str,
    family: Family,
    kind: Kind,
    sentence: &'static str,
    source: &'static str,
    default_cases: u32,
    needs: Vec<Need>,
    keeps_winding: bool,
    levels: Levels,
}

impl RuleDraft {
    fn new(family: Family, kind: Kind, id: &'static str) -> Self {
        Self {
            id,
            family,
            kind,
            sentence: "",
            source: "",
            default_cases: 1000,
            needs: Vec::new(),
            keeps_winding: false,
            levels: Levels::REQUIRED,
        }
    }

    /// The rule in one sentence.
    #[must_use]
    pub fn sentence(self, sentence: &'static str) -> Self {
        Self { sentence, ..self }
    }

    /// Where it comes from.
    #[must_use]
    pub fn source(self, source: &'static str) -> Self {
        Self { source, ..self }
    }

    /// Cases tried by default (1 000 unless set).
    #[must_use]
    pub fn cases(self, default_cases: u32) -> Self {
        Self {
            default_cases,
            ..self
        }
    }

    /// Adds something the profile must declare; the rule is n/a without it.
    #[must_use]
    pub fn needs(mut self, need: Need) -> Self {
        self.needs.push(need);
        self
    }

    /// Draws its inputs with the winding they were generated with, under any cull mode: the
    /// rule judges facing or culling itself.
    #[must_use]
    pub fn keeps_winding(self) -> Self {
        Self {
            keeps_winding: true,
            ..self
        }
    }

    /// Its level under Vulkan, OpenGL and OpenGL ES alike (required unless said).
    #[must_use]
    pub fn vulkan_and_opengl(mut self, level: Level) -> Self {
        self.levels.vulkan = level;
        self.levels.opengl = level;
        self.levels.opengles = level;
        self
    }

    /// Its level under Vulkan alone, where it differs from OpenGL's (set after
    /// [`RuleDraft::vulkan_and_opengl`] or [`RuleDraft::every_spec`]).
    #[must_use]
    pub fn vulkan(mut self, level: Level) -> Self {
        self.levels.vulkan = level;
        self
    }

    /// Its level under OpenGL ES 3.2 where it differs from OpenGL 4.6's (set after
    /// [`RuleDraft::vulkan_and_opengl`]).
    #[must_use]
    pub fn opengles(mut self, level: Level) -> Self {
        self.levels.opengles = level;
        self
    }

    /// Its level under D3D11.3 (required unless said).
    #[must_use]
    pub fn d3d11(mut self, level: Level) -> Self {
        self.levels.d3d11 = level;
        self
    }

    /// Its level under every specification but refrast's.
    #[must_use]
    pub fn every_spec(self, level: Level) -> Self {
        self.vulkan_and_opengl(level).d3d11(level)
    }

    /// The rule, with the property it runs.
    #[must_use]
    pub fn run(self, run: Run) -> Rule {
        Rule {
            id: self.id,
            family: self.family,
            kind: self.kind,
            sentence: self.sentence,
            source: self.source,
            default_cases: self.default_cases,
            needs: self.needs,
            keeps_winding: self.keeps_winding,
            levels: self.levels,
            run,
        }
    }
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
    rules.extend(line::rules());
    rules.extend(point::rules());
    rules.extend(msaa::rules());
    rules.extend(scissor::rules());
    rules.extend(sample_mask::rules());
    rules.extend(centroid::rules());
    rules.extend(conservative::rules());
    rules.extend(flat::rules());
    rules.extend(viewport_depth::rules());
    rules.extend(bias::rules());
    rules.extend(polygon::rules());
    rules.extend(distance::rules());
    rules
}

/// The catalogue as the Markdown table of docs/rules.md: `| rule | kind | sentence |`, one row per rule.
#[must_use]
pub fn markdown_table() -> String {
    let mut table = String::from("| rule | kind | sentence |\n|---|---|---|");
    for rule in catalogue() {
        table.push_str(&format!(
            "\n| `{}` | {} | {} |",
            rule.id, rule.kind, rule.sentence
        ));
    }
    table
}

/// Every rule's requirement level under Vulkan, OpenGL and D3D11.3, as Markdown: a table of
/// levels, then for each rule not required everywhere what each specification leaves out
/// (`refrast rules --levels`; `docs/levels.md` holds it).
#[must_use]
pub fn levels_markdown() -> String {
    let mut table =
        String::from("| rule | Vulkan 1.4 | OpenGL 4.6 | OpenGL ES 3.2 | D3D11.3 |\n|---|---|---|---|---|");
    let mut notes = String::new();
    for rule in catalogue() {
        let l = rule.levels;
        table.push_str(&format!(
            "\n| `{}` | {} | {} | {} | {} |",
            rule.id,
            l.vulkan.word(),
            l.opengl.word(),
            l.opengles.word(),
            l.d3d11.word()
        ));
        let mut said: Vec<(Vec<&str>, Level)> = Vec::new();
        for (spec, level) in l.each() {
            let spec = spec.title();
            let Some(note) = level.note() else { continue };
            match said
                .iter_mut()
                .find(|(_, l)| l.word() == level.word() && l.note() == Some(note))
            {
                Some((specs, _)) => specs.push(spec),
                None => said.push((vec![spec], level)),
            }
        }
        for (specs, level) in said {
            notes.push_str(&format!(
                "\n- `{}`, {}: {}: {}.",
                rule.id,
                specs.join(" and "),
                level.word(),
                level.note().unwrap_or("")
            ));
        }
    }
    format!("{table}\n{notes}\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_rule_is_complete_and_named_after_its_family() {
        let rules = catalogue();
        let mut ids: Vec<&str> = rules.iter().map(|r| r.id).collect();
        for rule in &rules {
            assert!(
                rule.id.starts_with(&format!("{}.", rule.family.name())),
                "{} is not in family {}",
                rule.id,
                rule.family.name()
            );
            assert!(!rule.sentence.is_empty(), "{} has no sentence", rule.id);
            assert!(!rule.source.is_empty(), "{} has no source", rule.id);
            assert!(rule.default_cases > 0, "{} runs no case", rule.id);
        }
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), rules.len(), "rule IDs are unique");
    }
}
