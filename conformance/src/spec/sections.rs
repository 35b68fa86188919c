//! The section lists: every section of the chapters each specification's map traces, as read
//! from its pinned source, so that a test can tell (offline) which sections have no statement.
//!
//! `conformance/spec/sections/KEY.txt` holds one section a line, its key, a tab, its title;
//! blank lines and lines starting with `#` are comments (the header says where the list comes
//! from). A key is an HTML anchor (Vulkan: `primsrast-depthbias`) or a section number starting
//! with `§` (`§14.6.1`). A statement belongs to a section by its anchor, or, in a list of
//! numbers, by the number that starts its `section` field.

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;

use super::{SpecDocument, SpecMap, Statement};

/// One section of a pinned source: the anchor or number that names it, and its title.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Section {
    /// Its anchor (`primsrast-lines-stipple`) or number (`§13.7.2`).
    pub key: String,
    /// Its title, as the source gives it.
    pub title: String,
}

/// Where `key`'s list lives, from the workspace's root.
#[must_use]
pub fn path(key: &str) -> String {
    format!("conformance/spec/sections/{key}.txt")
}

/// A list's sections, in its order; `Err` names the first line that is not `key<TAB>title`.
pub fn parse(text: &str) -> Result<Vec<Section>, String> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| !line.trim().is_empty() && !line.starts_with('#'))
        .map(|(i, line)| match line.split_once('\t') {
            Some((key, title)) if !key.trim().is_empty() && !title.trim().is_empty() => Ok(Section {
                key: key.trim().to_owned(),
                title: title.trim().to_owned(),
            }),
            _ => Err(format!("line {}: not `key<TAB>title`: {line:?}", i + 1)),
        })
        .collect()
}

impl SpecDocument {
    /// Whether its section list names sections by number (`§…`) rather than by anchor.
    fn numbered(&self) -> bool {
        self.sections.iter().all(|s| s.key.starts_with('§'))
    }

    /// The key of the section `statement` belongs to: the number starting its `section` in a
    /// numbered list, else its anchor; `None` when it has neither.
    #[must_use]
    pub fn section_key<'a>(&self, statement: &'a Statement) -> Option<&'a str> {
        if self.numbered() {
            statement
                .section
                .split_whitespace()
                .next()
                .filter(|n| n.starts_with('§'))
        } else {
            statement.anchor.as_deref()
        }
    }
}

impl SpecMap {
    /// What is incomplete between the map and the section lists, one line each: a section with
    /// no statement (all of a file's at once), a statement whose section is not in its list (a
    /// typo, or a section the list lacks), a section listed twice.
    #[must_use]
    pub fn section_problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        for spec in self.specs.iter().filter(|s| !s.sections.is_empty()) {
            let list = path(&spec.key);
            let mut traced: BTreeMap<&str, usize> =
                spec.sections.iter().map(|s| (s.key.as_str(), 0)).collect();
            let mut seen = BTreeSet::new();
            for section in &spec.sections {
                if !seen.insert(section.key.as_str()) {
                    problems.push(format!("{list}: {} is listed twice", section.key));
                }
            }
            for s in &spec.statements {
                let what = if spec.numbered() {
                    "section number"
                } else {
                    "anchor"
                };
                match spec.section_key(s) {
                    Some(key) => match traced.get_mut(key) {
                        Some(count) => *count += 1,
                        None => problems.push(format!(
                            "{} in {}.toml: its {what} {key} is not in {list}",
                            s.id, spec.key
                        )),
                    },
                    None => problems.push(format!(
                        "{} in {}.toml: has no {what}, so it belongs to no section of {list}",
                        s.id, spec.key
                    )),
                }
            }
            let missing: Vec<String> = spec
                .sections
                .iter()
                .filter(|s| traced.get(s.key.as_str()) == Some(&0))
                .map(|s| format!("  {} ({})", s.key, s.title))
                .collect();
            if !missing.is_empty() {
                problems.push(format!(
                    "{}.toml has no statement for {} section(s) of {list}; add one to each (checked, \
                     partly, out_of_scope or not_yet):\n{}",
                    spec.key,
                    missing.len(),
                    missing.join("\n")
                ));
            }
        }
        problems
    }
}
