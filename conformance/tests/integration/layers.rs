//! The suite's modules form layers: each uses only modules of lower layers (and itself).
//!
//! The layers are listed in `src/lib.rs`. Every path to an item of the crate (`use` trees,
//! `crate::…`, `super::…` and `self::…` in code) is resolved from the module it is written in;
//! one that reaches a module of the same or a higher layer is a circle in the making and fails
//! here. Test modules (from `#[cfg(test)]` to the end of a file) and comments are left out.

use std::collections::BTreeSet;
use std::path::Path;

#[path = "../../../tests/support/modules.rs"]
mod modules;

use modules::{code, module_of, resolve, rust_files, segments, use_paths, written_paths};

/// Top-level modules, lowest layer first.
const LAYERS: &[&[&str]] = &[
    &["status"],
    &["oracle"],
    &["scene"],
    &["violation"],
    &["picture"],
    &["strategy"],
    &["runner"],
    &["rules"],
    &["spec", "report"],
    &["judge"],
    &["certify"],
    &["isolate", "expect"],
    &["harness", "fuzz"],
];

/// Inside a top-level module, the layers of its child modules; a child may also use its
/// parent's own items, and the parent its children.
const INNER_LAYERS: &[(&str, &[&[&str]])] = &[
    (
        "oracle",
        &[
            &["raster"],
            &["brute_force", "outline", "ray_cast"],
            &["facing", "segment"],
        ],
    ),
    (
        "rules",
        &[
            &["common", "level", "samples", "ties"],
            &["reading", "why", "vertices"],
            &["cast", "mesh", "weights"],
            &["fill"],
            &[
                "bary",
                "clip",
                "depth",
                "meta",
                "robust",
                "line",
                "point",
                "sample_depth",
                "scissor",
            ],
            &["msaa"],
            &["hint"],
        ],
    ),
];

fn layer(layers: &[&[&str]], module: &str) -> Option<usize> {
    layers.iter().position(|l| l.contains(&module))
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
