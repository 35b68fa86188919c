//! The rule table of docs/rules.md is the catalogue: same rules, same order, same kinds and
//! sentences; and docs/levels.md says what each specification requires of each rule, as the
//! catalogue does.

use refrast_conformance::{levels_markdown, markdown_table};

#[test]
fn the_levels_page_is_the_catalogues() {
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/levels.md"))
        .expect("docs/levels.md exists");
    let want = levels_markdown();
    assert!(
        page.contains(want.trim_end()),
        "docs/levels.md is out of date: put the output of `cargo run -- rules --levels` in it"
    );
}

#[test]
fn the_rules_page_table_is_the_catalogue() {
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/rules.md"))
        .expect("docs/rules.md exists");
    let table = markdown_table();
    let header = table.lines().next().expect("the table has a header");
    let start = page
        .find(header)
        .expect("docs/rules.md has the catalogue table (`cargo run -- rules --markdown` prints it)");
    let on_page: Vec<&str> = page[start..].lines().take_while(|l| l.starts_with('|')).collect();
    let want: Vec<&str> = table.lines().collect();
    let first_difference = on_page
        .iter()
        .zip(&want)
        .position(|(a, b)| a != b)
        .or((on_page.len() != want.len()).then(|| on_page.len().min(want.len())));
    if let Some(i) = first_difference {
        panic!(
            "the rule table of docs/rules.md differs from catalogue() at line {} of the table:\n  docs/rules.md: {}\n  catalogue:     {}\n\
             Replace the table with the output of `cargo run -- rules --markdown`.",
            i + 1,
            on_page.get(i).unwrap_or(&"(nothing)"),
            want.get(i).unwrap_or(&"(nothing)"),
        );
    }
}
