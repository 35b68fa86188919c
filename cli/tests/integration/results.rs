//! Results kept across runs: the JSON document's metadata, JUnit XML valid against the Jenkins
//! schema, `--shard` and `merge` (the parts joined equal the whole but for times), `compare`
//! (exit 1 on a regression), `rules --json` and `impls --json`.

use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;

use crate::support;

use support::{REFRAST, scratch};

/// Fails the fill rules that look at shared edges; passes the rest.
const MUTANT: &str = "mutant:inclusive-edges";

/// The published JUnit schema (Jenkins xunit-plugin's junit-10.xsd; tests/data/README.md).
const XSD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/junit-10.xsd");

fn refrast(args: &[&str]) -> Output {
    Command::new(REFRAST).args(args).output().expect("refrast runs")
}

fn text(out: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

fn read(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("a JSON file")).expect("JSON")
}

/// The certification every test here starts from: the mutant and the reference on the fill
/// family at a few cases, with `extra` arguments; the report pictures in `dir/report`.
fn certify(dir: &Path, json: &str, extra: &[&str]) -> (Output, Value) {
    let path = dir.join(json);
    let report = dir.join("report");
    let mut args = vec![
        "certify",
        "--impl",
        MUTANT,
        "--impl",
        "reference",
        "--rule",
        "fill.*",
    ];
    args.extend([
        "--cases",
        "25",
        "--seed",
        "7",
        "--report",
        report.to_str().unwrap(),
    ]);
    args.extend(["--json", path.to_str().unwrap()]);
    args.extend(extra);
    let out = refrast(&args);
    assert!(path.exists(), "no JSON: {}", text(&out));
    (out, read(&path))
}

/// A document with what varies from run to run taken out: times, the command, the shard,
/// picture folders.
fn verdicts(doc: &Value) -> Value {
    let mut doc = doc.clone();
    let run = doc["run"].as_object_mut().expect("run metadata");
    for key in ["started", "seconds", "command"] {
        run.remove(key);
    }
    run["options"].as_object_mut().expect("options").remove("shard");
    for entry in doc["implementations"].as_array_mut().expect("implementations") {
        for rule in entry["rules"].as_array_mut().into_iter().flatten() {
            let rule = rule.as_object_mut().expect("a rule");
            rule.remove("seconds");
            rule.remove("picture");
        }
    }
    doc
}

#[test]
fn the_json_says_how_the_run_was_made() {
    let dir = scratch("results-metadata");
    let (out, doc) = certify(&dir, "r.json", &["--budget", "30", "--memory-limit", "2048"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(doc["schema_version"], 1);
    let run = &doc["run"];
    assert_eq!(run["refrast_version"], env!("CARGO_PKG_VERSION"));
    assert!(run["git_revision"].as_str().is_some_and(|r| !r.is_empty()));
    let started = run["started"].as_str().expect("a start time");
    assert!(
        started.len() == 20 && started.ends_with('Z') && started.contains('T'),
        "{started}"
    );
    assert!(run["seconds"].as_f64().is_some_and(|s| s > 0.0));
    assert!(run["host"]["cpus"].as_u64().is_some_and(|n| n >= 1));
    assert_eq!(run["host"]["os"], std::env::consts::OS);
    let o = &run["options"];
    assert_eq!(
        (o["cases"].as_u64(), o["seed"].as_u64(), o["budget"].as_f64()),
        (Some(25), Some(7), Some(30.0))
    );
    assert_eq!(o["rules"], serde_json::json!(["fill.*"]));
    assert_eq!(o["memory_limit_mib"].as_u64(), Some(2048));
    let entry = &doc["implementations"][0];
    assert_eq!(entry["subject"]["impl"], MUTANT);
    assert!(entry["rules"].as_array().is_some_and(|r| !r.is_empty()));

    // A document of another schema, or none, is refused with what to do.
    let old = dir.join("old.json");
    std::fs::write(&old, "[]").expect("write");
    let out = refrast(&[
        "compare",
        old.to_str().unwrap(),
        dir.join("r.json").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out).contains("no schema_version"), "{}", text(&out));
}

/// Validates `xml` against the committed schema with xmllint; skips without xmllint unless
/// `REFRAST_REQUIRE_XMLLINT=1` (set by `.ci/run`, which installs libxml2-utils).
fn validate(xml: &Path) -> bool {
    let out = match Command::new("xmllint")
        .args(["--noout", "--schema", XSD])
        .arg(xml)
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            assert!(
                std::env::var("REFRAST_REQUIRE_XMLLINT").as_deref() != Ok("1"),
                "REFRAST_REQUIRE_XMLLINT is set, but xmllint cannot run: {e}"
            );
            println!("xmllint: SKIPPED ({e}; apt-get install libxml2-utils)");
            return false;
        }
    };
    assert!(
        out.status.success(),
        "{} is not valid JUnit: {}",
        xml.display(),
        text(&out)
    );
    true
}

#[test]
fn junit_is_valid_and_says_each_verdict() {
    let dir = scratch("results-junit");
    let xml = dir.join("junit.xml");
    let (out, doc) = certify(&dir, "r.json", &["--junit", xml.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let junit = std::fs::read_to_string(&xml).expect("junit.xml");
    let rules = doc["implementations"][0]["rules"].as_array().expect("rules");
    let failed = rules.iter().filter(|r| r["status"] == "fail").count();
    assert!(failed > 0);
    assert!(junit.contains(&format!(
        "<testsuite name=\"{MUTANT}\" tests=\"{}\" failures=\"{failed}\" errors=\"0\"",
        rules.len()
    )));
    assert_eq!(
        junit.matches("<testcase ").count(),
        2 * rules.len(),
        "one per (implementation, rule)"
    );
    assert!(junit.contains("type=\"fail\""));
    assert!(junit.contains("reproduce: refrast certify --impl mutant:inclusive-edges --rule "));
    validate(&xml);

    // Under expectations, what they accept is skipped and only a surprise is a failure.
    let expect = dir.join("e.txt");
    std::fs::write(&expect, "[mutant:inclusive-edges]\nfill.*  may-fail  # the mutant's bug\n[reference]\nfill.interior.matches-raycast fail # wrong on purpose\n").expect("write");
    let xml2 = dir.join("junit2.xml");
    let (out, _) = certify(
        &dir,
        "r2.json",
        &[
            "--junit",
            xml2.to_str().unwrap(),
            "--expect",
            expect.to_str().unwrap(),
        ],
    );
    assert_eq!(out.status.code(), Some(1), "the reference's pass is unexpected");
    let junit = std::fs::read_to_string(&xml2).expect("junit2.xml");
    assert!(
        junit.contains("<skipped message=\"expected may-fail, got fail"),
        "{junit}"
    );
    assert!(junit.contains("type=\"unexpected-pass\""), "{junit}");
    assert_eq!(junit.matches("type=\"fail\"").count(), 0, "{junit}");
    validate(&xml2);
}

#[test]
fn shards_merge_into_the_whole_run() {
    let dir = scratch("results-shards");
    let (whole_out, whole) = certify(&dir, "whole.json", &[]);
    let mut parts = Vec::new();
    for i in 1..=3 {
        let shard = format!("{i}/3");
        let (_, part) = certify(&dir, &format!("part{i}.json"), &["--shard", &shard]);
        assert_eq!(part["run"]["options"]["shard"]["index"], i);
        parts.push(dir.join(format!("part{i}.json")));
    }
    let sizes: Vec<usize> = parts
        .iter()
        .map(|p| {
            read(p)["implementations"][0]["rules"]
                .as_array()
                .map_or(0, Vec::len)
        })
        .collect();
    let total = whole["implementations"][0]["rules"]
        .as_array()
        .map_or(0, Vec::len);
    assert_eq!(
        sizes.iter().sum::<usize>(),
        total,
        "the parts cover the rules once: {sizes:?}"
    );
    assert!(sizes.iter().all(|&n| n > 0), "{sizes:?}");

    let merged = dir.join("merged.json");
    let junit = dir.join("merged.xml");
    let mut args = vec!["merge"];
    let names: Vec<String> = parts.iter().map(|p| p.display().to_string()).collect();
    args.extend(names.iter().map(String::as_str));
    let report = dir.join("merged-report");
    args.extend([
        "--json",
        merged.to_str().unwrap(),
        "--junit",
        junit.to_str().unwrap(),
    ]);
    args.extend(["--report", report.to_str().unwrap()]);
    let out = refrast(&args);
    assert_eq!(
        out.status.code(),
        whole_out.status.code(),
        "the whole run's exit: {}",
        text(&out)
    );
    assert_eq!(
        verdicts(&read(&merged)),
        verdicts(&whole),
        "merged differs from the whole run"
    );
    assert!(report.join("index.html").exists());
    validate(&junit);

    // Parts of different runs are refused.
    let (_, _) = certify(&dir, "other.json", &["--shard", "1/3", "--scale", "2"]);
    let other = dir.join("other.json");
    let out = refrast(&[
        "merge",
        &names[1],
        other.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out).contains("differ in their scale"), "{}", text(&out));
    let out = refrast(&["certify", "--shard", "4/3"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
}

#[test]
fn compare_says_what_moved_and_fails_on_a_regression() {
    let dir = scratch("results-compare");
    let (_, doc) = certify(&dir, "old.json", &[]);
    let old = dir.join("old.json");
    let same = refrast(&["compare", old.to_str().unwrap(), old.to_str().unwrap()]);
    assert_eq!(same.status.code(), Some(0));
    assert!(text(&same).contains("reference: no change"), "{}", text(&same));

    // The reference's first rule fails, and the mutant's first failure passes.
    let mut new = doc.clone();
    let reference = &mut new["implementations"][1]["rules"][0];
    let regressed = reference["id"].as_str().expect("an id").to_owned();
    reference["status"] = "crash".into();
    let mutant = new["implementations"][0]["rules"]
        .as_array_mut()
        .expect("rules")
        .iter_mut()
        .find(|r| r["status"] == "fail")
        .expect("a failure");
    let fixed = mutant["id"].as_str().expect("an id").to_owned();
    mutant["status"] = "pass".into();
    let path = dir.join("new.json");
    std::fs::write(&path, new.to_string()).expect("write");
    let out = refrast(&["compare", old.to_str().unwrap(), path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    let said = text(&out);
    assert!(
        said.contains(&format!("REGRESSED  {regressed}")) && said.contains("pass -> crash"),
        "{said}"
    );
    assert!(
        said.contains(&format!("fixed      {fixed}")) && said.contains("fail -> pass"),
        "{said}"
    );

    // The other way round: a fix is no regression.
    let out = refrast(&["compare", path.to_str().unwrap(), old.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "the mutant's rule fails again: {}",
        text(&out)
    );
}

#[test]
fn rules_and_impls_as_json() {
    let out = refrast(&["rules", "--json"]);
    assert!(out.status.success());
    let rules: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let rules = rules.as_array().expect("an array");
    assert_eq!(rules.len(), refrast_conformance::catalogue().len());
    for r in rules {
        for key in ["id", "kind", "family", "source", "sentence"] {
            assert!(r[key].as_str().is_some_and(|s| !s.is_empty()), "{key} of {r}");
        }
        assert!(r["default_cases"].as_u64().is_some_and(|n| n > 0));
    }

    let out = refrast(&["impls", "--json"]);
    assert!(out.status.success());
    let impls: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let impls = impls.as_array().expect("an array");
    let reference = impls
        .iter()
        .find(|i| i["name"] == "reference")
        .expect("the reference");
    assert_eq!(
        (&reference["origin"], &reference["available"]),
        (&"ours".into(), &true.into())
    );
    assert_eq!(reference["profile"]["snapping"], "8 subpixel bits");
    let mutant = impls.iter().find(|i| i["name"] == MUTANT).expect("the mutant");
    assert_eq!(mutant["origin"], "broken on purpose");
    assert_eq!(mutant["description"], "the fill rules must catch it");
    for i in impls.iter().filter(|i| i["available"] == false) {
        assert!(i["unavailable"].as_str().is_some_and(|s| !s.is_empty()), "{i}");
    }
}

#[test]
fn impls_says_each_origin_once() {
    let out = refrast(&["impls"]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(!said.contains("broken on purpose: broken on purpose"), "{said}");
    assert!(
        said.contains("broken on purpose: the fill rules must catch it"),
        "{said}"
    );
}
