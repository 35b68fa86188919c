//! `refrast rules` and `refrast impls`: the catalogue and the built-ins, as text for people
//! and as JSON for scripts.

use std::process::ExitCode;

use refrast_conformance::{ProfileReport, catalogue};
use refrast_registry::{BuiltIn, Origin};
use serde_json::json;

use crate::certify::this_program;
use crate::say;

/// `refrast rules --spec`: the spec map as text, JSON or docs/spec.md, or the statements one rule
/// checks; exit 1 when the map does not parse, 2 for an unknown rule.
pub fn spec(markdown: bool, as_json: bool, rule: Option<&str>) -> ExitCode {
    let map = match refrast_conformance::spec_map() {
        Ok(map) => map,
        Err(e) => {
            eprintln!("error: the spec map does not parse: {e}");
            return ExitCode::FAILURE;
        }
    };
    let Some(rule) = rule else {
        if as_json {
            say(&serde_json::to_string_pretty(&map).unwrap_or_default());
        } else if markdown {
            say(map.markdown().trim_end());
        } else {
            say(map.text().trim_end());
        }
        return ExitCode::SUCCESS;
    };
    if !catalogue().iter().any(|r| r.id == rule) {
        eprintln!("error: no rule {rule}; `refrast rules` lists them");
        return ExitCode::from(2);
    }
    let found: Vec<_> = map.statements_for(rule).collect();
    if as_json {
        let list: Vec<_> = found
            .iter()
            .map(|(spec, s)| json!({"spec": spec.key, "link": spec.link(s), "statement": s}))
            .collect();
        say(&serde_json::to_string_pretty(&list).unwrap_or_default());
        return ExitCode::SUCCESS;
    }
    say(&format!("{rule} checks {} statement(s):", found.len()));
    for (spec, s) in found {
        say(&format!(
            "  {}  {}, {}\n      {}",
            s.id, spec.title, s.section, s.says
        ));
        if let Some(partly) = &s.partly {
            say(&format!("      partly; unchecked: {partly}"));
        }
        if let Some(note) = &s.note {
            say(&format!("      note: {note}"));
        }
    }
    ExitCode::SUCCESS
}

/// Lists the rules: a line each, or a JSON array.
pub fn rules(as_json: bool) -> ExitCode {
    if as_json {
        let rules: Vec<_> = catalogue()
            .iter()
            .map(|r| {
                json!({
                    "id": r.id,
                    "kind": r.kind.to_string(),
                    "family": r.family.name(),
                    "source": r.source,
                    "sentence": r.sentence,
                    "default_cases": r.default_cases,
                })
            })
            .collect();
        say(&serde_json::to_string_pretty(&rules).unwrap_or_default());
        return ExitCode::SUCCESS;
    }
    for rule in catalogue() {
        say(&format!(
            "{:<38} {:<9} {:<6} [{}] {}",
            rule.id,
            rule.kind,
            rule.family.name(),
            rule.source,
            rule.sentence
        ));
    }
    ExitCode::SUCCESS
}

/// Lists the built-ins with their profiles: a line each, or a JSON array; one that cannot be
/// built here says why. `only` lists one, built in this process (what the listing's children
/// run).
pub fn impls(as_json: bool, only: Option<&str>) -> ExitCode {
    let all: Vec<BuiltIn> = refrast_registry::all()
        .into_iter()
        .filter(|b| only.is_none_or(|name| b.name == name))
        .collect();
    let width = all.iter().map(|b| b.name.chars().count()).max().unwrap_or(0);
    let mut listed = Vec::new();
    for b in all {
        let (profile, why) = if only.is_some() || !in_child(&b) {
            match b.build() {
                Ok(r) => (Some(ProfileReport::of(r.as_ref())), None),
                Err(why) => (None, Some(why.to_string())),
            }
        } else {
            described(&b)
        };
        if as_json {
            listed.push(json!({
                "name": b.name,
                "origin": b.origin.label(),
                "description": b.description,
                "available": profile.is_some(),
                "unavailable": why,
                "profile": profile,
            }));
            continue;
        }
        match profile {
            Some(p) => say(&format!(
                "{:<width$} {}, {}, band {} px, {}: {}",
                b.name,
                p.snapping,
                p.fill,
                p.band_px,
                b.origin.label(),
                b.description
            )),
            None => say(&format!(
                "{:<width$} unavailable here: {}",
                b.name,
                why.unwrap_or_default()
            )),
        }
    }
    if as_json {
        say(&serde_json::to_string_pretty(&listed).unwrap_or_default());
    }
    ExitCode::SUCCESS
}

/// Whether a built-in is described by a child: a third party's needs its environment (a
/// driver chosen before it loads) and prints to stderr as it loads, which the child keeps out
/// of the listing.
fn in_child(b: &BuiltIn) -> bool {
    b.origin == Origin::ThirdParty
}

/// The profile a child process (`refrast impls --json --only NAME`, the built-in's
/// environment set) reports, or why there is none.
fn described(b: &BuiltIn) -> (Option<ProfileReport>, Option<String>) {
    let out = this_program()
        .args(["impls", "--json", "--only", &b.name])
        .envs(b.env.iter().map(|(k, v)| (k, v)))
        .stdin(std::process::Stdio::null())
        .output();
    let out = match out {
        Ok(out) => out,
        Err(e) => return (None, Some(format!("could not start a child to describe it: {e}"))),
    };
    let listed: Option<serde_json::Value> = serde_json::from_slice(&out.stdout).ok();
    let Some(entry) = listed.as_ref().and_then(|l| l.get(0)) else {
        let stderr = String::from_utf8_lossy(&out.stderr);
        let end: Vec<&str> = stderr.lines().rev().take(3).collect();
        return (
            None,
            Some(format!(
                "the child describing it ended without a profile ({}): {}",
                out.status,
                end.into_iter().rev().collect::<Vec<_>>().join(" / ")
            )),
        );
    };
    let profile = serde_json::from_value(entry["profile"].clone()).ok();
    let why = entry["unavailable"].as_str().map(str::to_owned);
    (profile, why)
}
