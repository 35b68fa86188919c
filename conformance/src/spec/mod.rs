//! The spec map: each normative statement of the specifications refrast holds rasterizers to,
//! the seed labs' expected results and refrast's own conventions, with the rules that check it.
//!
//! The map is data, `conformance/spec/*.toml`, one file per specification, compiled into the
//! crate so that `refrast rules --spec` and reports need no files at run time. A statement is
//! *checked* by the rules it names (or, for the course, by its golden tests), *partly* checked
//! when it also says what they leave unchecked, or says why not: *out of scope* (outside what
//! the [`Rasterizer`](refrast::Rasterizer) contract can express) or *not yet* (within it, but no
//! rule checks it). Each specification with a pinned source also has a list of that source's
//! sections (`conformance/spec/sections/*.txt`, read by the `sections` module), every one of
//! which must have a statement. [`SpecMap::problems`] is the consistency check `cargo test`
//! runs: every rule maps to a statement, every named rule exists, every reason is given, every
//! section is traced.

mod sections;

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use crate::rules::Rule;
pub use sections::Section;

/// The map's files, in the order they are shown: the specifications, then the course, then
/// refrast's conventions; each with the list of its pinned source's sections, where it has one.
const FILES: [(&str, &str, Option<&str>); 6] = [
    (
        "vulkan.toml",
        include_str!("../../spec/vulkan.toml"),
        Some(include_str!("../../spec/sections/vulkan.txt")),
    ),
    (
        "d3d11.toml",
        include_str!("../../spec/d3d11.toml"),
        Some(include_str!("../../spec/sections/d3d11.txt")),
    ),
    (
        "opengl.toml",
        include_str!("../../spec/opengl.toml"),
        Some(include_str!("../../spec/sections/opengl.txt")),
    ),
    (
        "opengles.toml",
        include_str!("../../spec/opengles.toml"),
        Some(include_str!("../../spec/sections/opengles.txt")),
    ),
    ("course.toml", include_str!("../../spec/course.toml"), None),
    ("refrast.toml", include_str!("../../spec/refrast.toml"), None),
];

/// How far the suite checks a statement.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Coverage {
    /// Named rules (or golden tests) check it.
    Checked,
    /// Named rules check part of it; the statement says which part they leave unchecked.
    Partly,
    /// Outside what the `Rasterizer` contract can express or observe.
    OutOfScope,
    /// Within the contract, but nothing checks it yet.
    #[default]
    NotYet,
}

impl Coverage {
    /// How the listing and the docs say it.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Checked => "checked",
            Self::Partly => "partly",
            Self::OutOfScope => "out of scope",
            Self::NotYet => "not yet",
        }
    }
}

/// One normative statement, in refrast's words, and what checks it.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Statement {
    /// Stable ID, unique across the map: `vk.…`, `d3d.…`, `gl.…`, `es.…`, `course.…`, `refrast.…`.
    pub id: String,
    /// The section it comes from, as the specification titles it; numbered specifications start
    /// it with the section's number (`§14.6.1 …`), which must be in their section list.
    pub section: String,
    /// The fragment in the specification's HTML it links to; for Vulkan, an anchor of its
    /// section list.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anchor: Option<String>,
    /// The statement in refrast's own words.
    pub says: String,
    /// The rules that check it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rules: Vec<String>,
    /// The golden tests that reproduce it (`path::function`, course entries).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub golden: Vec<String>,
    /// What its rules leave unchecked, when they check only part of it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub partly: Option<String>,
    /// Why it is outside the contract.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub out_of_scope: Option<String>,
    /// Why nothing checks it yet.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub not_yet: Option<String>,
    /// What part the rules check, or how refrast reads the statement.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// How far it is checked, from the fields above.
    #[serde(skip_deserializing)]
    pub coverage: Coverage,
}

impl Statement {
    /// How far it is checked, from its fields: checked when it names rules or golden tests
    /// (partly when it says what they leave), else out of scope when it says why, else not yet.
    #[must_use]
    pub fn answer(&self) -> Coverage {
        if !self.rules.is_empty() || !self.golden.is_empty() {
            if self.partly.is_some() {
                Coverage::Partly
            } else {
                Coverage::Checked
            }
        } else if self.out_of_scope.is_some() {
            Coverage::OutOfScope
        } else {
            Coverage::NotYet
        }
    }
}

/// One specification's statements.
#[derive(Clone, Debug, Serialize)]
pub struct SpecDocument {
    /// Short key: `vulkan`, `d3d11`, `opengl`, `opengles`, `course`, `refrast`.
    pub key: String,
    /// Its title.
    pub title: String,
    /// The version read.
    pub version: String,
    /// Where it is published; empty for documents without one.
    pub url: String,
    /// Its statements, in the order of the specification.
    pub statements: Vec<Statement>,
    /// The sections of its pinned source, each of which needs a statement; empty for the course
    /// and refrast's conventions.
    #[serde(skip)]
    pub sections: Vec<Section>,
}

impl SpecDocument {
    /// A link to `statement`'s section, when the specification is published with anchors.
    #[must_use]
    pub fn link(&self, statement: &Statement) -> Option<String> {
        if self.url.is_empty() {
            return None;
        }
        Some(match &statement.anchor {
            Some(anchor) => format!("{}#{anchor}", self.url),
            None => self.url.clone(),
        })
    }

    /// Statements checked, partly checked, out of scope and not yet.
    #[must_use]
    pub fn tally(&self) -> [usize; 4] {
        let count = |c: Coverage| self.statements.iter().filter(|s| s.coverage == c).count();
        [
            count(Coverage::Checked),
            count(Coverage::Partly),
            count(Coverage::OutOfScope),
            count(Coverage::NotYet),
        ]
    }

    /// One line: `Vulkan 1.4: 84 of 131 statements checked, 20 partly, 24 out of scope, 3 not
    /// yet` (the four counts add up to the statements).
    #[must_use]
    pub fn coverage_line(&self) -> String {
        let [checked, partly, out, not_yet] = self.tally();
        format!(
            "{}: {checked} of {} statements checked, {partly} partly, {out} out of scope, {not_yet} not yet",
            self.title,
            self.statements.len()
        )
    }
}

/// The file's layout: `[spec]`, then `[[statement]]` entries.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    spec: Header,
    #[serde(default)]
    statement: Vec<Statement>,
}

/// The `[spec]` table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    key: String,
    title: String,
    version: String,
    url: String,
}

/// Every specification's statements.
#[derive(Clone, Debug, Serialize)]
pub struct SpecMap {
    /// In this order: Vulkan, D3D11.3, OpenGL, OpenGL ES, the course, refrast's conventions.
    pub specs: Vec<SpecDocument>,
}

/// The map compiled into the crate; `Err` names the file and what in it does not parse.
pub fn spec_map() -> Result<SpecMap, String> {
    let specs = FILES
        .iter()
        .map(|(name, text, list)| {
            let mut spec = parse(text).map_err(|e| format!("conformance/spec/{name}: {e}"))?;
            if let Some(list) = list {
                spec.sections =
                    sections::parse(list).map_err(|e| format!("{}: {e}", sections::path(&spec.key)))?;
            }
            if format!("{}.toml", spec.key) == *name {
                Ok(spec)
            } else {
                Err(format!(
                    "conformance/spec/{name}: its key is {:?}; name the file after it",
                    spec.key
                ))
            }
        })
        .collect::<Result<_, _>>()?;
    Ok(SpecMap { specs })
}

/// One file of the map, each statement's coverage filled in.
fn parse(text: &str) -> Result<SpecDocument, String> {
    let file: File = toml::from_str(text).map_err(|e| e.to_string())?;
    let mut statements = file.statement;
    for s in &mut statements {
        s.coverage = s.answer();
    }
    let Header {
        key,
        title,
        version,
        url,
    } = file.spec;
    Ok(SpecDocument {
        key,
        title,
        version,
        url,
        statements,
        sections: Vec::new(),
    })
}

impl SpecMap {
    /// The statements that name `rule`, with their specifications.
    pub fn statements_for<'a>(
        &'a self,
        rule: &'a str,
    ) -> impl Iterator<Item = (&'a SpecDocument, &'a Statement)> {
        self.specs.iter().flat_map(move |spec| {
            spec.statements
                .iter()
                .filter(move |s| s.rules.iter().any(|r| r == rule))
                .map(move |s| (spec, s))
        })
    }

    /// What is inconsistent between the map and `rules`, one line each; empty when nothing is:
    /// a rule no statement names, a statement naming a rule that does not exist, a statement
    /// neither checked nor giving its reason (or giving two answers, or `partly` without rules),
    /// a repeated ID, an empty field, a golden test not written as `path::function`, and what
    /// [`SpecMap::section_problems`] finds. Each statement is judged by its fields
    /// ([`Statement::answer`]), not by its stored coverage.
    #[must_use]
    pub fn problems(&self, rules: &[Rule]) -> Vec<String> {
        let known: BTreeSet<&str> = rules.iter().map(|r| r.id).collect();
        let mut named = BTreeSet::new();
        let mut ids = BTreeMap::new();
        let mut problems = Vec::new();
        for spec in &self.specs {
            if [&spec.key, &spec.title, &spec.version]
                .iter()
                .any(|f| f.trim().is_empty())
            {
                problems.push(format!(
                    "{}.toml: `key`, `title` and `version` must not be empty",
                    spec.key
                ));
            }
            for s in &spec.statements {
                let at = format!("{} in {}.toml", s.id, spec.key);
                if let Some(other) = ids.insert(s.id.as_str(), spec.key.as_str()) {
                    problems.push(format!("{at}: the ID is also used in {other}.toml"));
                }
                let optional = [&s.anchor, &s.note, &s.partly].into_iter().flatten();
                let texts = [&s.id, &s.section, &s.says]
                    .into_iter()
                    .chain(optional)
                    .chain(&s.rules);
                if texts.chain(&s.golden).any(|t| t.trim().is_empty()) {
                    problems.push(format!(
                        "{at}: an empty field (`section`, `says`, an anchor, a note, `partly`, a rule or a golden test)"
                    ));
                }
                for rule in &s.rules {
                    if known.contains(rule.as_str()) {
                        named.insert(rule.as_str());
                    } else {
                        problems.push(format!("{at}: names the rule {rule}, which does not exist"));
                    }
                }
                for test in &s.golden {
                    if test
                        .split_once("::")
                        .is_none_or(|(p, f)| p.is_empty() || f.is_empty())
                    {
                        problems.push(format!("{at}: golden test {test:?} is not `path::function`"));
                    }
                }
                let reasons = [&s.out_of_scope, &s.not_yet];
                for reason in reasons.into_iter().flatten() {
                    if reason.trim().is_empty() {
                        problems.push(format!("{at}: an empty reason; say why in one sentence"));
                    }
                }
                if s.partly.is_some() && s.rules.is_empty() {
                    problems.push(format!(
                        "{at}: says `partly` but names no rules; name the rules that check the rest"
                    ));
                }
                let checked = matches!(s.answer(), Coverage::Checked | Coverage::Partly);
                let answers = usize::from(checked) + reasons.iter().filter(|r| r.is_some()).count();
                if answers != 1 {
                    problems.push(format!(
                        "{at}: needs exactly one of `rules` (or `golden`), `out_of_scope` and `not_yet` (with its reason)"
                    ));
                }
            }
        }
        for rule in rules {
            if !named.contains(rule.id) {
                problems.push(format!(
                    "rule {} maps to no statement: name it in the statement it checks, or in refrast.toml if it checks a convention",
                    rule.id
                ));
            }
        }
        problems.extend(self.section_problems());
        problems
    }

    /// The map as text: each specification's coverage line, then its statements.
    #[must_use]
    pub fn text(&self) -> String {
        let mut out = String::new();
        for spec in &self.specs {
            let _ = writeln!(out, "{} ({})", spec.coverage_line(), spec.version);
            for s in &spec.statements {
                let what = match s.coverage {
                    Coverage::Checked => format!("checked by {}", checked_by(s, "")),
                    Coverage::Partly => format!(
                        "partly checked by {}; unchecked: {}",
                        checked_by(s, ""),
                        s.partly.as_deref().unwrap_or("")
                    ),
                    Coverage::OutOfScope => {
                        format!("out of scope: {}", s.out_of_scope.as_deref().unwrap_or(""))
                    }
                    Coverage::NotYet => format!("not yet: {}", s.not_yet.as_deref().unwrap_or("")),
                };
                let _ = writeln!(out, "  {}  [{}]\n      {}\n      {what}", s.id, s.section, s.says);
            }
            out.push('\n');
        }
        out
    }

    /// `docs/spec.md`: the coverage per specification, then a table per specification.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut out = String::from(
            "# The specifications, sentence by sentence\n\n\
             Generated by `refrast rules --spec --markdown` from `conformance/spec/*.toml`; \
             `cargo test` fails when it is out of date, when a rule maps to no statement, when a \
             statement names a rule that does not exist, when one gives no reason, or when a \
             section of a pinned source (listed in `conformance/spec/sections/`) has no statement.\n\n\
             Each entry is a normative statement in refrast's own words, with the rules that check \
             it, *partly* when they leave some of it unchecked (and what), or why none does: *out \
             of scope* (outside what the `Rasterizer` contract can express or observe) or *not \
             yet* (within it, but unchecked). The course's entries are \
             the seed labs' expected results, each with the golden test that reproduces it; \
             refrast's conventions are the rules that check a choice of refrast's rather than a \
             sentence of a specification.\n\n## Coverage\n\n",
        );
        for spec in &self.specs {
            let _ = writeln!(out, "- {}", spec.coverage_line());
        }
        for spec in &self.specs {
            let _ = write!(out, "\n## {}\n\n{}", spec.title, spec.version);
            if !spec.url.is_empty() {
                let _ = write!(out, ", <{}>", spec.url);
            }
            if !spec.sections.is_empty() {
                let _ = write!(
                    out,
                    "\n\nEach of the {} sections listed in `{}` has a statement.",
                    spec.sections.len(),
                    sections::path(&spec.key)
                );
            }
            out.push_str("\n\n| statement | section | says | checked by |\n|---|---|---|---|\n");
            for s in &spec.statements {
                let section = match spec.link(s).filter(|_| s.anchor.is_some()) {
                    Some(link) => format!("[{}]({link})", s.section),
                    None => s.section.clone(),
                };
                let by = match s.coverage {
                    Coverage::Checked => checked_by(s, "`"),
                    Coverage::Partly => format!(
                        "{}; *partly, unchecked:* {}",
                        checked_by(s, "`"),
                        s.partly.as_deref().unwrap_or("")
                    ),
                    Coverage::OutOfScope => {
                        format!("*out of scope:* {}", s.out_of_scope.as_deref().unwrap_or(""))
                    }
                    Coverage::NotYet => format!("*not yet:* {}", s.not_yet.as_deref().unwrap_or("")),
                };
                let note = s.note.as_deref().map(|n| format!(" ({n})")).unwrap_or_default();
                let _ = writeln!(
                    out,
                    "| `{}` | {} | {} | {}{} |",
                    s.id,
                    cell(&section),
                    cell(&s.says),
                    cell(&by),
                    cell(&note)
                );
            }
        }
        out
    }
}

/// "rule, rule, golden test" for a checked statement, each name between `quote`s.
fn checked_by(s: &Statement, quote: &str) -> String {
    let mut parts: Vec<String> = s.rules.iter().map(|r| format!("{quote}{r}{quote}")).collect();
    parts.extend(s.golden.iter().map(|g| format!("golden {quote}{g}{quote}")));
    parts.join(", ")
}

/// Text safe in a markdown table cell: no pipes, no line breaks.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}
