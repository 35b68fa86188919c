//! The suite's modules form layers: each uses only modules of lower layers (and itself).
//!
//! The layers are listed in `src/lib.rs`. Every path to an item of the crate (`use` trees,
//! `crate::…`, `super::…` and `self::…` in code) is resolved from the module it is written in;
//! one that reaches a module of the same or a higher layer is a circle in the making and fails
//! here. Test modules (from `#[cfg(test)]` to the end of a file) and comments are left out.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Top-level modules, lowest layer first; `process`, `restricted` and `impls` (which lists the
/// restricted ones) stand apart: they use only refrast (and `status`, which uses nothing).
const LAYERS: &[&[&str]] = &[
    &["status"],
    &["oracle", "process", "restricted"],
    &["scene", "impls"],
    &["violation"],
    &["picture"],
    &["strategy"],
    &["runner"],
    &["rules"],
    &["report"],
    &["certify"],
    &["isolate", "expect"],
    &["harness", "fuzz"],
];

/// Inside a top-level module, the layers of its child modules; a child may also use its
/// parent's own items, and the parent its children.
const INNER_LAYERS: &[(&str, &[&[&str]])] = &[
    (
        "oracle",
        &[&["raster"], &["brute_force", "outline", "ray_cast"], &["facing"]],
    ),
    (
        "rules",
        &[
            &["common", "level"],
            &["cast", "mesh"],
            &["fill"],
            &["bary", "clip", "depth", "meta", "robust"],
            &["hint"],
        ],
    ),
];

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

/// The module a file defines: `a/b.rs` and `a/b/mod.rs` are `[a, b]`, `lib.rs` is `[]`.
fn module_of(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap_or_default();
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_owned());
    }
    parts
}

/// The code of a file without its test module, its comments and the contents of its string
/// literals (a message saying "use …" is no `use`).
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut out = String::with_capacity(text.len());
    let (mut in_string, mut escaped, mut chars) = (false, false, text.chars().peekable());
    while let Some(c) = chars.next() {
        if in_string {
            match (escaped, c) {
                (false, '\\') => escaped = true,
                (false, '"') => {
                    in_string = false;
                    out.push('"');
                }
                (_, '\n') => {
                    escaped = false;
                    out.push('\n');
                }
                _ => escaped = false,
            }
            continue;
        }
        match c {
            '"' => {
                in_string = true;
                out.push('"');
            }
            // A character literal holding a quote is no string.
            '\'' if chars.peek() == Some(&'"') => {
                out.push(c);
                out.push(chars.next().unwrap_or('"'));
            }
            '/' if chars.peek() == Some(&'/') => {
                for rest in chars.by_ref() {
                    if rest == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            c => out.push(c),
        }
    }
    out
}

/// Splits `s` at commas that are not inside braces.
fn split_top(s: &str) -> Vec<&str> {
    let (mut depth, mut start, mut out) = (0, 0, Vec::new());
    for (i, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(&s[start..]);
    out
}

/// The paths a use tree names, each as its segments: `a::{b, c::{d, e}}` is `a::b`, `a::c::d`, `a::c::e`.
fn use_paths(tree: &str, prefix: &[String], out: &mut Vec<Vec<String>>) {
    let tree = tree.trim();
    if tree.is_empty() {
        return;
    }
    match tree.find('{') {
        Some(open) => {
            let close = tree.rfind('}').unwrap_or(tree.len());
            let mut path = prefix.to_vec();
            path.extend(segments(tree[..open].trim_end_matches("::")));
            for part in split_top(&tree[open + 1..close]) {
                use_paths(part, &path, out);
            }
        }
        None => {
            let mut path = prefix.to_vec();
            path.extend(segments(tree.split(" as ").next().unwrap_or(tree)));
            out.push(path);
        }
    }
}

fn segments(path: &str) -> Vec<String> {
    path.split("::")
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(str::to_owned)
        .collect()
}

/// Every path in `code` that starts at `crate`, `super` or `self`, as written.
fn written_paths(code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = code.to_owned();
    // Use trees first (they may hold braces), then cut them out.
    while let Some(start) = find_word(&rest, "use ") {
        let Some(len) = rest[start..].find(';') else { break };
        let tree = rest[start + 4..start + len]
            .trim()
            .trim_start_matches("pub ")
            .to_owned();
        use_paths(&tree, &[], &mut out);
        rest.replace_range(start..start + len + 1, "");
    }
    let bytes: Vec<char> = rest.chars().collect();
    let text: String = bytes.iter().collect();
    for root in ["crate::", "super::", "self::"] {
        for (i, _) in text.match_indices(root) {
            let before = text[..i].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let path: String = text[i..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            out.push(segments(&path));
        }
    }
    out
}

/// The byte index of `word` where it starts a word.
fn find_word(s: &str, word: &str) -> Option<usize> {
    s.match_indices(word).map(|(i, _)| i).find(|&i| {
        !s[..i]
            .chars()
            .last()
            .is_some_and(|c| c.is_alphanumeric() || c == '_')
    })
}

/// Resolves a written path against the module it is written in; `None` for other crates.
fn resolve(module: &[String], path: &[String]) -> Option<Vec<String>> {
    let mut at: Vec<String> = module.to_vec();
    let mut rest = path;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            at.clear();
            rest = &rest[1..];
        }
        Some("self") => rest = &rest[1..],
        Some("super") => {
            while rest.first().map(String::as_str) == Some("super") {
                at.pop()?;
                rest = &rest[1..];
            }
        }
        _ => return None,
    }
    at.extend(rest.iter().cloned());
    Some(at)
}

/// Checks one resolved edge; a problem when it points sideways or up.
fn check_edge(from: &[String], to: &[String]) -> Result<(), String> {
    let (Some(a), Some(b)) = (from.first(), to.first()) else {
        return Ok(());
    };
    if a != b {
        let (la, lb) = (layer(LAYERS, a), layer(LAYERS, b));
        return match (la, lb) {
            (Some(la), Some(lb)) if lb < la => Ok(()),
            _ => Err(format!(
                "`{a}` uses `{}`, which is not in a lower layer",
                to.join("::")
            )),
        };
    }
    let Some((_, inner)) = INNER_LAYERS.iter().find(|(m, _)| m == a) else {
        return Ok(());
    };
    let (Some(ca), Some(cb)) = (from.get(1), to.get(1)) else {
        return Ok(());
    };
    match (layer(inner, ca), layer(inner, cb)) {
        _ if ca == cb => Ok(()),
        // One of them is not a child module (an item of the parent): parent and child may meet.
        (None, _) | (_, None) => Ok(()),
        (Some(la), Some(lb)) if lb < la => Ok(()),
        _ => Err(format!(
            "`{a}::{ca}` uses `{}`, which is not in a lower layer",
            to.join("::")
        )),
    }
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
        let module = module_of(rel);
        if module.is_empty() {
            continue;
        }
        if layer(LAYERS, &module[0]).is_none() {
            problems.push(format!(
                "{}: module `{}` has no layer in LAYERS",
                rel.display(),
                module[0]
            ));
            continue;
        }
        let text = std::fs::read_to_string(file).expect("source is readable");
        for path in written_paths(&code(&text)) {
            let Some(to) = resolve(&module, &path) else {
                continue;
            };
            if let Err(problem) = check_edge(&module, &to) {
                problems.push(format!("{}: {problem}", rel.display()));
            }
            if let (Some(a), Some(b)) = (module.first(), to.first())
                && a != b
            {
                edges.insert((a.clone(), b.clone()));
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

#[test]
fn the_parser_sees_nested_trees_and_relative_paths() {
    let mut paths = Vec::new();
    use_paths("crate::{scene::{Case, Scene}, certify::Options}", &[], &mut paths);
    let module = vec!["runner".to_owned()];
    let resolved: Vec<_> = paths.iter().filter_map(|p| resolve(&module, p)).collect();
    assert!(resolved.contains(&vec!["certify".to_owned(), "Options".to_owned()]));
    assert!(resolved.contains(&vec!["scene".to_owned(), "Case".to_owned()]));
    // `super::` from a top-level module is the crate root.
    let to = resolve(&module, &segments("super::certify::run_rule")).unwrap();
    assert!(check_edge(&module, &to).is_err());
    // Siblings inside a layered module.
    let ray_cast = vec!["oracle".to_owned(), "ray_cast".to_owned()];
    let to = resolve(&ray_cast, &segments("super::outline::visible_outline")).unwrap();
    assert!(check_edge(&ray_cast, &to).is_err());
    let to = resolve(&ray_cast, &segments("super::raster::snap")).unwrap();
    assert!(check_edge(&ray_cast, &to).is_ok());
    let written = written_paths("use crate::{scene::Scene, certify::Options};\nfn f() { super::x::y(); }");
    assert_eq!(written.len(), 3, "{written:?}");
}
