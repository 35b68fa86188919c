//! The README's rule table is the catalogue: same rules, same order, same kinds and sentences;
//! and docs/levels.md says what each specification requires of each rule, as the catalogue does.

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
fn the_readme_rule_table_is_the_catalogue() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md sits at the repository root");
    let table = markdown_table();
    let header = table.lines().next().expect("the table has a header");
    let start = readme
        .find(header)
        .expect("the README has the catalogue table (`cargo run -- rules --markdown` prints it)");
    let in_readme: Vec<&str> = readme[start..]
        .lines()
        .take_while(|l| l.starts_with('|'))
        .collect();
    let want: Vec<&str> = table.lines().collect();
    let first_difference = in_readme
        .iter()
        .zip(&want)
        .position(|(a, b)| a != b)
        .or((in_readme.len() != want.len()).then(|| in_readme.len().min(want.len())));
    if let Some(i) = first_difference {
        panic!(
            "the README's rule table differs from catalogue() at line {} of the table:\n  README:    {}\n  catalogue: {}\n\
             Replace the table with the output of `cargo run -- rules --markdown`.",
            i + 1,
            in_readme.get(i).unwrap_or(&"(nothing)"),
            want.get(i).unwrap_or(&"(nothing)"),
        );
    }
}
