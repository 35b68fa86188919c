//! The suite's modules form layers: each uses only modules of lower layers (and itself).
//!
//! The layers are listed in `src/lib.rs`. A `crate::…` path (in a `use` or in code) to a module
//! of the same or a higher layer is a circle in the making and fails here.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Top-level modules, lowest layer first; `impls` stands apart (it uses only refrast).
const LAYERS: &[&[&str]] = &[
    &["oracle", "impls"],
    &["scene"],
    &["violation"],
    &["picture"],
    &["strategy"],
    &["runner"],
    &["rules"],
    &["certify"],
    &["harness", "fuzz"],
];

/// Inside `oracle`: the geometry first, then the oracles that use it.
const ORACLE_LAYERS: &[&[&str]] = &[&["raster"], &["brute_force", "outline", "ray_cast"]];

fn layer(layers: &[&[&str]], module: &str) -> Option<usize> {
    layers.iter().position(|l| l.contains(&module))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src is readable").flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every `crate::a::b` path in `text` (comments included: a doc link is a dependency too),
/// as `(a, b)`; `use crate::{a, b::c}` groups count once per module.
fn crate_paths(text: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let word = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for (i, _) in text.match_indices("crate::") {
        let rest = &text[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let inner = &group[..group.find('}').unwrap_or(group.len())];
            for part in inner.split(',') {
                let part = part.trim();
                let first = word(part);
                let second = part
                    .strip_prefix(first.as_str())
                    .and_then(|r| r.strip_prefix("::"))
                    .map(word)
                    .unwrap_or_default();
                out.push((first, second));
            }
        } else {
            let first = word(rest);
            let second = rest[first.len()..]
                .strip_prefix("::")
                .map(word)
                .unwrap_or_default();
            out.push((first, second));
        }
    }
    out
}

#[test]
fn modules_use_only_lower_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut edges = BTreeSet::new();
    let mut problems = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(&src).expect("under src");
        let parts: Vec<String> = rel
            .iter()
            .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_owned())
            .collect();
        if parts[0] == "lib" {
            continue;
        }
        let module = parts[0].clone();
        let Some(from) = layer(LAYERS, &module) else {
            problems.push(format!(
                "{}: module `{module}` has no layer in LAYERS",
                rel.display()
            ));
            continue;
        };
        let text = std::fs::read_to_string(file).expect("source is readable");
        let inner = (module == "oracle" && parts.len() > 1).then(|| parts[1].clone());
        let mut paths = crate_paths(&text);
        if inner.is_some() && parts.len() == 2 {
            // `super::x` in `oracle/y.rs` is `crate::oracle::x`.
            let siblings = crate_paths(&text.replace("super::", "crate::oracle::"));
            paths.extend(siblings.into_iter().filter(|(t, _)| t == "oracle"));
        }
        for (target, sub) in paths {
            if target == module {
                // Inside `oracle`, the geometry sits below the oracles.
                if let (Some(inner), false) = (&inner, sub.is_empty()) {
                    let (a, b) = (layer(ORACLE_LAYERS, inner), layer(ORACLE_LAYERS, &sub));
                    if sub != *inner && !matches!((a, b), (Some(a), Some(b)) if b < a) {
                        problems.push(format!("{}: oracle::{inner} uses oracle::{sub}", rel.display()));
                    }
                }
                continue;
            }
            edges.insert((module.clone(), target.clone()));
            match layer(LAYERS, &target) {
                Some(to) if to < from => {}
                _ => problems.push(format!(
                    "{}: `{module}` (layer {from}) uses `crate::{target}`, which is not in a lower layer",
                    rel.display()
                )),
            }
        }
    }
    for (a, b) in &edges {
        println!("{a} -> {b}");
    }
    assert!(problems.is_empty(), "layering broken:\n{}", problems.join("\n"));
    // The check sees the suite: these edges exist today.
    assert!(edges.contains(&("rules".into(), "oracle".into())));
    assert!(edges.contains(&("runner".into(), "picture".into())));
}
