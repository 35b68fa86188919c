//! `refrast certify --report DIR` writes `DIR/index.html` (tables, matrix, failures with their
//! pictures and reproduce commands, every report string escaped), and `--jobs` changes nothing
//! but the times.

use std::path::Path;
use std::process::{Command, Output};

use base64::Engine;
use serde_json::Value;

use crate::support;

use support::{REFRAST, scratch};

/// The mutant that draws shared edges twice: fails fill rules with a picture.
const MUTANT: &str = "mutant:inclusive-edges";

/// Runs `refrast certify` with `args`, the report in `dir` and the JSON in `dir/r.json`: the
/// output, and the JSON's array of implementations.
fn certify(dir: &Path, args: &[&str]) -> (Output, Value) {
    let json = dir.join("r.json");
    let out = Command::new(REFRAST)
        .arg("certify")
        .args(args)
        .arg("--report")
        .arg(dir)
        .arg("--json")
        .arg(&json)
        .output()
        .expect("refrast runs");
    let text = std::fs::read_to_string(&json).unwrap_or_else(|e| {
        panic!(
            "no JSON from certify {args:?} ({e}):\n{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    let doc: Value = serde_json::from_str(&text).expect("the report is JSON");
    assert_eq!(doc["schema_version"], 1, "the schema version");
    (out, doc["implementations"].clone())
}

/// The text between `start` (excluded) and the next `end` after it, from `from` on.
fn between<'a>(text: &'a str, from: usize, start: &str, end: &str) -> Option<(&'a str, usize)> {
    let at = from + text[from..].find(start)? + start.len();
    let len = text[at..].find(end)?;
    Some((&text[at..at + len], at + len))
}

/// Undoes the page's escaping.
fn unescape(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&amp;", "&")
}

#[test]
fn the_page_holds_tables_matrix_failures_and_escaped_text() {
    let dir = scratch("report-page");
    // A command that cannot start, whose name and message carry markup to escape.
    let odd = "/nonexistent/<b>&rasterizer";
    let args = [
        "--impl",
        "reference",
        "--impl",
        MUTANT,
        "--exec",
        odd,
        "--rule",
        "fill.*",
        "--cases",
        "200",
    ];
    let (out, json) = certify(&dir, &args);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "the mutant fails:\n{stdout}");
    assert!(
        stdout.contains(&format!("wrote {}", dir.join("index.html").display())),
        "{stdout}"
    );
    let page = std::fs::read_to_string(dir.join("index.html")).expect("index.html is written");
    assert!(page.starts_with("<!doctype html>") && page.trim_end().ends_with("</html>"));
    // Self-contained: no asset from elsewhere (links to the specifications' sections are fine).
    for asset in ["src=\"http", "<link", "url(http", "@import"] {
        assert!(!page.contains(asset), "no external assets: {asset}");
    }
    assert!(
        std::fs::read_dir(&dir)
            .unwrap()
            .all(|e| !e.unwrap().file_name().to_string_lossy().ends_with(".tmp"))
    );

    // A row per rule in each certified implementation's table, and a matrix with every rule.
    let entries = json.as_array().expect("an array");
    assert_eq!(entries.len(), 3);
    for (column, entry) in entries.iter().take(2).enumerate() {
        let rules = entry["rules"].as_array().expect("rules");
        assert!(rules.len() >= 5, "the fill family: {}", rules.len());
        for (row, rule) in rules.iter().enumerate() {
            let id = rule["id"].as_str().unwrap();
            let seconds = rule["seconds"].as_f64().expect("seconds in the JSON");
            assert!(seconds >= 0.0);
            let (cells, _) = between(&page, 0, &format!("<tr id=\"r{column}-{row}\">"), "</tr>")
                .unwrap_or_else(|| panic!("no row for {id} of entry {column}"));
            assert!(cells.contains(&format!("<code>{id}</code>")), "{cells}");
            let label = match rule["status"].as_str().unwrap() {
                "fail" => "FAIL",
                "pass" => "pass",
                _ => "n/a",
            };
            assert!(cells.contains(&format!(">{label}</")), "{id}: {cells}");
        }
        let (matrix, _) = between(&page, 0, "<table class=\"matrix\">", "</table>").expect("a matrix");
        assert!(matrix.contains(&format!(
            "<th class=\"rule\">{}</th>",
            rules[0]["id"].as_str().unwrap()
        )));
    }
    assert!(
        entries[0]["rules"]
            .as_array()
            .unwrap()
            .iter()
            .all(|r| r["status"] != "fail")
    );

    // Each failure of the mutant: a FAIL cell, its detail with a picture that decodes, and a
    // reproduce command that fails the same rule on the same counterexample.
    let failures: Vec<&Value> = entries[1]["rules"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["status"] == "fail")
        .collect();
    assert!(!failures.is_empty(), "the mutant fails a fill rule");
    assert!(page.contains("<a class=\"status fail\" href=\"#f1-"));
    let mut from = 0;
    let mut pictures = 0;
    while let Some((data, end)) = between(&page, from, "src=\"data:image/png;base64,", "\"") {
        let png = base64::engine::general_purpose::STANDARD
            .decode(data)
            .expect("base64");
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
        let picture = image::load_from_memory(&png).expect("a PNG that decodes");
        assert!(picture.width() > 16 && picture.height() > 16);
        pictures += 1;
        from = end;
    }
    assert!(pictures >= 1, "an embedded picture");
    // Each failure names the statements of the specifications its rule checks.
    assert!(
        page.contains("<ul class=\"statements\">"),
        "a failure's statements"
    );
    let first = failures[0];
    let (code, _) = between(&page, 0, "<h4>Reproduce the rule</h4>\n<pre><code>", "</code>")
        .expect("a reproduce command");
    let words = shell_words::split(&unescape(code)).expect("a shell command");
    let expected = [
        "refrast",
        "certify",
        "--impl",
        MUTANT,
        "--rule",
        first["id"].as_str().unwrap(),
        "--seed",
        &first["seed"].to_string(),
        "--cases",
        &first["planned"].to_string(),
    ];
    assert_eq!(words, expected);
    let again = scratch("report-reproduce");
    let (out, rerun) = certify(&again, &words[2..].iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(out.status.code(), Some(1));
    let rule = &rerun[0]["rules"][0];
    assert_eq!((&rule["id"], &rule["status"]), (&first["id"], &first["status"]));
    assert_eq!(
        rule["counterexample"], first["counterexample"],
        "the same counterexample"
    );
    let (case, at) = between(&page, 0, "<pre><code>", "</code>").expect("the case as data");
    let case: Value = serde_json::from_str(&unescape(case)).expect("the page's case is JSON");
    assert_eq!(case, first["case"], "the page shows the report's case");
    let (counterexample, at) = between(&page, at, "<pre><code>", "</code>").expect("a counterexample");
    assert_eq!(
        unescape(counterexample),
        first["counterexample"].as_str().unwrap()
    );
    let (replay, _) = between(
        &page,
        at,
        "<h4>Replay this case alone</h4>\n<pre><code>",
        "</code>",
    )
    .expect("a replay command");
    let replay = shell_words::split(&unescape(replay)).expect("one command line");
    assert_eq!(&replay[..2], ["refrast", "replay"]);
    assert_eq!(
        replay.last(),
        first["case_path"].as_str().map(str::to_owned).as_ref()
    );

    // Strings from reports and the command line are escaped, never markup.
    assert!(
        page.contains("/nonexistent/&lt;b&gt;&amp;rasterizer"),
        "the --exec name, escaped"
    );
    assert!(!page.contains("<b>&rasterizer"));
    assert!(
        page.contains("--rule &#39;fill.*&#39;"),
        "the command line, quoted and escaped"
    );
    assert!(
        page.contains("document.body.dataset.imagesDecoded"),
        "the decode check script"
    );
}

/// The verdicts of a JSON report, times and picture paths left out.
fn verdicts(json: &Value) -> Vec<Value> {
    let mut entries = json.as_array().expect("an array").clone();
    for entry in &mut entries {
        for rule in entry["rules"].as_array_mut().into_iter().flatten() {
            let rule = rule.as_object_mut().expect("a rule");
            rule.remove("seconds");
            rule.remove("picture");
            rule.remove("case_path");
        }
    }
    entries
}

/// The rule lines of certify's output, in order.
fn rule_lines(out: &Output) -> Vec<String> {
    let text = String::from_utf8_lossy(&out.stdout);
    let starts = ["pass ", "FAIL ", "n/a ", "== ", "  --fail-fast"];
    text.lines()
        .filter(|l| starts.iter().any(|s| l.starts_with(s)))
        .map(str::to_owned)
        .collect()
}

#[test]
fn jobs_change_only_the_times() {
    for (name, extra) in [("all", &[][..]), ("fail-fast", &["--fail-fast"][..])] {
        let mut args = vec!["--impl", MUTANT, "--impl", "reference", "--rule", "fill.*"];
        args.extend(["--cases", "200", "--seed", "11"]);
        args.extend(extra);
        let one = [&args[..], &["--jobs", "1"]].concat();
        let two = [&args[..], &["--jobs", "2"]].concat();
        let (out1, json1) = certify(&scratch(&format!("jobs1-{name}")), &one);
        let (out2, json2) = certify(&scratch(&format!("jobs2-{name}")), &two);
        assert_eq!(out1.status.code(), Some(1));
        assert_eq!(out2.status.code(), Some(1));
        assert_eq!(
            verdicts(&json1),
            verdicts(&json2),
            "{name}: --jobs 1 and --jobs 2 differ"
        );
        assert_eq!(
            rule_lines(&out1),
            rule_lines(&out2),
            "{name}: the printed report differs"
        );
        if name == "fail-fast" {
            assert_eq!(
                json1.as_array().unwrap().len(),
                1,
                "the reference is not certified"
            );
            let rules = json1[0]["rules"].as_array().unwrap();
            assert_eq!(
                rules.last().unwrap()["status"],
                "fail",
                "the run stops at the failure"
            );
            assert!(String::from_utf8_lossy(&out2.stdout).contains("--fail-fast: not certified: reference"));
        } else {
            assert_eq!(json1.as_array().unwrap().len(), 2);
        }
    }
}

#[test]
fn zero_jobs_is_a_usage_error() {
    let out = Command::new(REFRAST)
        .args(["certify", "--jobs", "0"])
        .output()
        .expect("refrast runs");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("--jobs"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn rules_spec_prints_the_map_and_the_statements_of_one_rule() {
    let run = |args: &[&str]| Command::new(REFRAST).args(args).output().expect("refrast runs");
    let text = run(&["rules", "--spec"]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.starts_with("Vulkan 1.4: "),
        "{}",
        &text[..text.len().min(200)]
    );
    assert!(text.contains("statements checked") && text.contains("vk.depth.test-per-sample"));

    let json = run(&["rules", "--spec", "--json"]);
    let json: Value = serde_json::from_slice(&json.stdout).expect("JSON");
    let specs = json["specs"].as_array().expect("an array of specifications");
    assert_eq!(specs[0]["key"], "vulkan");
    assert!(
        specs
            .iter()
            .all(|s| s["statements"].as_array().is_some_and(|a| !a.is_empty()))
    );

    let one = run(&["rules", "--spec", "--rule", "depth.intersecting.nearest-wins"]);
    let one = String::from_utf8_lossy(&one.stdout);
    assert!(one.contains("course.003.painters-algorithm"), "{one}");

    let unknown = run(&["rules", "--spec", "--rule", "fill.no-such-rule"]);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("no rule fill.no-such-rule"));
}

/// `refrast replay` takes a case certify wrote and says clearly what it cannot use: no
/// rasterizer named, two named, a missing file, a file that is no case, a word the protocol
/// does not have (exit 2 each); the reference passes the mutant's case (exit 0).
#[test]
fn replay_reads_a_written_case_and_refuses_what_it_cannot_use() {
    let dir = scratch("replay-usage");
    let (out, json) = certify(&dir, &["--impl", MUTANT, "--rule", "fill.mesh.exactly-once"]);
    assert_eq!(out.status.code(), Some(1));
    let case = json[0]["rules"][0]["case_path"]
        .as_str()
        .expect("a case file")
        .to_owned();
    let replay = |args: &[&str]| {
        Command::new(REFRAST)
            .arg("replay")
            .args(args)
            .output()
            .expect("refrast runs")
    };
    let said = |o: &Output| String::from_utf8_lossy(&o.stderr).into_owned();
    let out = replay(&[
        "--impl",
        MUTANT,
        &case,
        "--report",
        &dir.join("again").to_string_lossy(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", said(&out));
    let out = replay(&["--impl", "reference", &case]);
    assert_eq!(out.status.code(), Some(0), "{}", said(&out));
    let out = replay(&[&case]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        said(&out).contains("--exec") && said(&out).contains("--impl"),
        "{}",
        said(&out)
    );
    let out = replay(&["--impl", "reference", "--exec", "true", &case]);
    assert_eq!(out.status.code(), Some(2), "{}", said(&out));
    let out = replay(&["--impl", "reference", "/nonexistent/case.json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(said(&out).contains("/nonexistent/case.json"), "{}", said(&out));
    let text = std::fs::read_to_string(&case).expect("the case");
    let sideways = dir.join("sideways.json");
    std::fs::write(
        &sideways,
        text.replace("\"cull\": \"none\"", "\"cull\": \"sideways\""),
    )
    .expect("write");
    let out = replay(&["--impl", "reference", &sideways.to_string_lossy()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        said(&out).contains("cull 'sideways' is none of"),
        "{}",
        said(&out)
    );
}

/// A driver that needs its environment set before its process starts (softpipe's
/// `GALLIUM_DRIVER`) is replayed in a child of refrast with it set, as `certify` runs it, so
/// the command a failed rule prints works as printed.
#[test]
fn replay_sets_the_environment_a_driver_needs() {
    let dir = scratch("replay-environment");
    let (_, json) = certify(&dir, &["--impl", MUTANT, "--rule", "fill.mesh.exactly-once"]);
    let case = json[0]["rules"][0]["case_path"]
        .as_str()
        .expect("a case file")
        .to_owned();
    let out = Command::new(REFRAST)
        .args(["replay", "--impl", "softpipe", &case, "--report"])
        .arg(dir.join("softpipe"))
        .env_remove("GALLIUM_DRIVER")
        .output()
        .expect("refrast runs");
    let (said, printed) = (
        String::from_utf8_lossy(&out.stderr),
        String::from_utf8_lossy(&out.stdout),
    );
    assert!(!said.contains("set before its process starts"), "{said}");
    if out.status.code() == Some(2) && said.contains("unavailable on this machine") {
        eprintln!("skipped: softpipe is not installed here ({said})");
        return;
    }
    assert!(printed.contains("on softpipe"), "{printed}{said}");
}
