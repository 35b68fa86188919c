//! The spec map (`conformance/spec/*.toml`) is consistent with the catalogue, traces every
//! section of each pinned source (`conformance/spec/sections/*.txt`), its golden tests exist,
//! and `docs/spec.md` is what it generates.

use std::path::Path;

use refrast_conformance::{Coverage, catalogue, spec_map};

/// The workspace's root, where the golden tests' paths start.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("conformance/ has a parent")
}

#[test]
fn every_rule_maps_to_a_statement_and_every_statement_is_answered() {
    let map = spec_map().expect("the spec map parses");
    let problems = map.problems(&catalogue());
    assert!(
        problems.is_empty(),
        "the spec map is inconsistent:\n{}",
        problems.join("\n")
    );
}

/// Whether `text` defines `function` as a `#[test]`: the attribute among those just above it.
fn is_test(text: &str, function: &str) -> bool {
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    lines.iter().enumerate().any(|(i, line)| {
        line.starts_with(&format!("fn {function}("))
            && lines[..i]
                .iter()
                .rev()
                .take_while(|l| l.starts_with("#[") || l.starts_with("///"))
                .any(|l| *l == "#[test]")
    })
}

#[test]
fn every_golden_test_exists() {
    let map = spec_map().expect("the spec map parses");
    let mut missing = Vec::new();
    for spec in &map.specs {
        for s in &spec.statements {
            for test in &s.golden {
                let Some((path, function)) = test.split_once("::") else {
                    continue;
                };
                let text = std::fs::read_to_string(root().join(path)).unwrap_or_default();
                if !is_test(&text, function) {
                    missing.push(format!("{}: {test}", s.id));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "golden tests that do not exist:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_consistency_check_catches_each_kind_of_mistake() {
    let map = spec_map().expect("the spec map parses");
    let rules = catalogue();
    let mut broken = map.clone();
    let vk = &mut broken.specs[0].statements;
    vk[0].rules.push("fill.no-such.rule".into());
    // A not-yet entry whose reason is blank, and an out-of-scope one that also says not yet.
    let blank = vk
        .iter()
        .position(|s| s.coverage == Coverage::NotYet)
        .expect("Vulkan has a not-yet entry");
    vk[blank].not_yet = Some("  ".into());
    let doubled = vk
        .iter()
        .position(|s| s.coverage == Coverage::OutOfScope)
        .expect("an out-of-scope entry");
    vk[doubled].not_yet = Some("also not yet".into());
    let doubled_id = vk[doubled].id.clone();
    // A not-yet entry that also names a rule: two answers, though its stored coverage says one.
    let two = vk
        .iter()
        .rposition(|s| s.coverage == Coverage::NotYet)
        .expect("a not-yet entry");
    vk[two].rules.push("fill.mesh.exactly-once".into());
    let two_id = vk[two].id.clone();
    // A partly-checked entry that names no rules: it cannot be partly checked.
    let partly = vk
        .iter()
        .position(|s| s.coverage == Coverage::Partly)
        .expect("a partly-checked entry");
    vk[partly].rules.clear();
    vk[partly].partly = Some("the rest".into());
    let partly_id = vk[partly].id.clone();
    // A repeated ID, an empty section and a golden test without its path.
    let (first_id, course) = (vk[0].id.clone(), broken.specs.len() - 2);
    broken.specs[1].statements[0].id = first_id.clone();
    broken.specs[1].statements[1].section = " ".into();
    broken.specs[course].statements[0].golden = vec!["just_a_name".into()];
    // Every statement naming fill.top-left.exact dropped: the rule then maps to nothing.
    for spec in &mut broken.specs {
        for s in &mut spec.statements {
            s.rules.retain(|r| r != "fill.top-left.exact");
        }
    }
    let problems = broken.problems(&rules).join("\n");
    for expected in [
        "names the rule fill.no-such.rule, which does not exist".to_owned(),
        "an empty reason".to_owned(),
        format!("{doubled_id} in vulkan.toml: needs exactly one of"),
        format!("{two_id} in vulkan.toml: needs exactly one of"),
        format!("{partly_id} in vulkan.toml: says `partly` but names no rules"),
        format!("{first_id} in d3d11.toml: the ID is also used in vulkan.toml"),
        "an empty field".to_owned(),
        "golden test \"just_a_name\" is not `path::function`".to_owned(),
        "rule fill.top-left.exact maps to no statement".to_owned(),
    ] {
        assert!(
            problems.contains(&expected),
            "{expected:?} not reported in:\n{problems}"
        );
    }
    assert!(map.problems(&rules).is_empty());
}

/// The keys of the specifications whose pinned sources have section lists.
const LISTED: [&str; 4] = ["vulkan", "d3d11", "opengl", "opengles"];

#[test]
fn every_section_of_each_pinned_source_has_a_statement() {
    let map = spec_map().expect("the spec map parses");
    for key in LISTED {
        let spec = map
            .specs
            .iter()
            .find(|s| s.key == key)
            .expect("the specification is in the map");
        assert!(
            spec.sections.len() > 20,
            "conformance/spec/sections/{key}.txt lists {} sections; it should list every section of the chapters {key}.toml traces",
            spec.sections.len()
        );
    }
    let problems = map.section_problems();
    assert!(
        problems.is_empty(),
        "the spec map does not trace every section of its sources:\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_completeness_check_catches_a_missing_section_and_an_unknown_one() {
    let map = spec_map().expect("the spec map parses");
    let mut broken = map.clone();
    // Every Vulkan statement on depth bias dropped: the section is then untraced.
    let vk = &mut broken.specs[0].statements;
    vk.retain(|s| s.anchor.as_deref() != Some("primsrast-depthbias"));
    // A statement linking to an anchor its list does not have (a typo), and one with no anchor,
    // each from a section with other statements.
    for s in vk.iter_mut() {
        match s.id.as_str() {
            "vk.line.t" => s.anchor = Some("primsrast-lines-basik".into()),
            "vk.raster.inside-framebuffer" => s.anchor = None,
            _ => {}
        }
    }
    // An OpenGL statement citing a section number its list does not have.
    let gl = broken
        .specs
        .iter_mut()
        .find(|s| s.key == "opengl")
        .expect("OpenGL is in the map");
    gl.statements[0].section = "§14.66 Depth Offset".into();
    let gl_id = gl.statements[0].id.clone();
    let problems = broken.section_problems().join("\n");
    for expected in [
        "vulkan.toml has no statement for 1 section(s) of conformance/spec/sections/vulkan.txt".to_owned(),
        "  primsrast-depthbias (Depth Bias)".to_owned(),
        "vk.line.t in vulkan.toml: its anchor primsrast-lines-basik is not in conformance/spec/sections/vulkan.txt"
            .to_owned(),
        "vk.raster.inside-framebuffer in vulkan.toml: has no anchor".to_owned(),
        format!("{gl_id} in opengl.toml: its section number §14.66 is not in conformance/spec/sections/opengl.txt"),
    ] {
        assert!(
            problems.contains(&expected),
            "{expected:?} not reported in:\n{problems}"
        );
    }
    assert!(
        broken
            .problems(&catalogue())
            .join("\n")
            .contains("primsrast-depthbias (Depth Bias)")
    );
}

#[test]
fn docs_spec_md_is_generated_from_the_map() {
    let map = spec_map().expect("the spec map parses");
    let want = map.markdown();
    let got = std::fs::read_to_string(root().join("docs/spec.md")).unwrap_or_default();
    assert!(
        got.trim_end() == want.trim_end(),
        "docs/spec.md is out of date: regenerate it with `refrast rules --spec --markdown > docs/spec.md`"
    );
}

#[test]
fn the_readme_states_the_coverage_of_each_specification() {
    let map = spec_map().expect("the spec map parses");
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap_or_default();
    for spec in &map.specs {
        let line = format!("- {}", spec.coverage_line());
        assert!(
            readme.contains(&line),
            "README.md does not say `{line}`: copy the coverage lines of docs/spec.md into it"
        );
    }
}
