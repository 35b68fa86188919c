//! `refrast certify --expect FILE`: exit 0 when every verdict is as expected, 1 on an unexpected
//! failure or an unexpected pass, 2 on a file that cannot be read; `--update-expectations`
//! writes what was seen; the checked-in files (`expectations/*.txt`) all read, and a flipped
//! line of a driver's file makes the run fail.

use std::path::Path;
use std::process::{Command, Output};

use refrast_conformance::expect::Expectations;

use crate::support;

use support::{REFRAST, scratch};

/// Fails the fill rules (`fill.mesh.exactly-once`, `fill.top-left.exact`), passes the rest.
const MUTANT: &str = "mutant:inclusive-edges";

/// `refrast certify` of the mutant and the reference on two rules, with `extra` arguments.
fn certify(dir: &Path, extra: &[&str]) -> Output {
    Command::new(REFRAST)
        .args(["certify", "--impl", MUTANT, "--impl", "reference"])
        .args([
            "--rule",
            "fill.mesh.exactly-once",
            "--rule",
            "fill.top-left.exact",
        ])
        .args(["--cases", "30"])
        .arg("--report")
        .arg(dir.join("report"))
        .args(extra)
        .output()
        .expect("refrast runs")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// What the two rules do: the mutant fails both, the reference passes both.
const EXPECTED: &str = "taken cases=30 seed=104372539621377 scale=1 budget=none
[mutant:inclusive-edges]
fill.*  fail  # shared edges drawn twice
[reference]
";

#[test]
fn verdicts_as_expected_exit_zero_and_surprises_exit_one() {
    let dir = scratch("expect-flip");
    let file = dir.join("e.txt");
    let run = |text: &str| {
        std::fs::write(&file, text).expect("write the file");
        certify(&dir, &["--expect", file.to_str().unwrap()])
    };

    let out = run(EXPECTED);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    assert!(stdout(&out).contains("every verdict as expected (4 rules judged, 2 expected failures)"));

    // A failure nobody expected: the last matching line decides, and it says pass.
    let out = run(&EXPECTED.replace(
        "fill.*  fail  # shared edges drawn twice\n",
        "fill.*  fail  # shared edges drawn twice\nfill.top-left.exact  pass\n",
    ));
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(
        stdout(&out).contains(
            "UNEXPECTED FAILURE: mutant:inclusive-edges fill.top-left.exact: expected pass, got fail"
        ),
        "{}",
        stdout(&out)
    );

    // A pass nobody expected: a fix is noticed.
    let out = run(&format!("{EXPECTED}fill.mesh.exactly-once  fail  # wrongly\n"));
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(
        stdout(&out).contains("UNEXPECTED PASS: reference fill.mesh.exactly-once: expected fail, got pass")
    );

    // may-fail accepts either; a status list accepts each of its statuses.
    let out = run(&format!(
        "{EXPECTED}fill.mesh.exactly-once  may-fail\nfill.top-left.exact  pass|n/a\n"
    ));
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));

    // Another status than expected (n/a where fail is written) is a change too.
    let out = run(&EXPECTED.replace("fill.*  fail", "fill.*  n/a|crash"));
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(stdout(&out).contains(
        "UNEXPECTED FAILURE: mutant:inclusive-edges fill.mesh.exactly-once: expected n/a|crash, got fail"
    ));

    // Taken at other options: a warning, not an error.
    let out = run(&EXPECTED.replace("cases=30", "cases=300"));
    assert_eq!(out.status.code(), Some(0));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning:") && stderr.contains("cases=300"),
        "{stderr}"
    );
}

#[test]
fn a_bad_file_is_a_usage_error_naming_its_line() {
    let dir = scratch("expect-bad");
    let file = dir.join("bad.txt");
    for (text, says) in [
        ("fill.* fail\n", "before any [section]"),
        ("[x]\nfill.* failed\n", "`failed` is not a status"),
        ("[x]\nfill.nothing fail\n", "matches no rule"),
        ("[x]\nfill.* fail extra\n", "is not `RULE STATUS`"),
        ("[x]\n[x]\n", "given twice"),
        ("taken cases=many\n", "`cases=many`"),
        ("[x\n", "does not end in `]`"),
    ] {
        std::fs::write(&file, text).expect("write");
        let out = certify(&dir, &["--expect", file.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text:?}: {stderr}");
        assert!(stderr.contains(says), "{text:?}: {stderr}");
        assert!(stderr.contains("bad.txt"), "names the file: {stderr}");
    }
    let out = certify(&dir, &["--expect", "/nonexistent/e.txt"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn update_writes_what_was_seen_and_keeps_what_still_holds() {
    let dir = scratch("expect-update");
    let file = dir.join("e.txt");
    std::fs::write(
        &file,
        "[mutant:inclusive-edges]\nfill.mesh.exactly-once  may-fail  # kept\n[elsewhere]\nrobust.* crash  # other section, kept\n",
    )
    .expect("write");
    let out = certify(
        &dir,
        &[
            "--expect",
            file.to_str().unwrap(),
            "--update-expectations",
            file.to_str().unwrap(),
        ],
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "the old file expected a pass: {}",
        stdout(&out)
    );
    let written = std::fs::read_to_string(&file).expect("written");
    assert!(
        written.contains("taken cases=30 seed=104372539621377 scale=1 budget=none"),
        "{written}"
    );
    assert!(written.contains("may-fail     # kept"), "{written}");
    assert!(written.contains("fill.top-left.exact     fail "), "{written}");
    assert!(
        written.contains("[reference]") && written.contains("[elsewhere]"),
        "{written}"
    );
    let out = certify(&dir, &["--expect", file.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "the written file holds: {}",
        stdout(&out)
    );
}

/// Every checked-in expectation file reads, and names built-ins that exist.
#[test]
fn the_checked_in_files_read() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../expectations");
    let impls = Command::new(REFRAST)
        .args(["impls", "--json"])
        .output()
        .expect("refrast runs");
    let impls: serde_json::Value = serde_json::from_slice(&impls.stdout).expect("JSON");
    let names: Vec<&str> = impls
        .as_array()
        .expect("an array")
        .iter()
        .filter_map(|i| i["name"].as_str())
        .collect();
    let mut files = 0;
    for entry in std::fs::read_dir(&folder).expect("expectations/") {
        let path = entry.expect("an entry").path();
        let expect = Expectations::load(std::slice::from_ref(&path)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(expect.taken.len(), 1, "{}: one taken line", path.display());
        for section in &expect.sections {
            assert!(
                names.contains(&section.name.as_str()),
                "{}: [{}]",
                path.display(),
                section.name
            );
            for line in &section.lines {
                let failing = line.accepts.iter().any(|s| s.is_failure());
                assert!(
                    !failing || line.why.is_some(),
                    "{}: {} {} says no why",
                    path.display(),
                    line.pattern,
                    line.written
                );
            }
        }
        files += 1;
    }
    assert!(files >= 6, "the drivers', euc's and ours: {files}");
}

/// `.ci/run`'s driver run with one line of lavapipe's file flipped: exit 1. Runs on one rule
/// whose verdict does not depend on the cases (`n/a` under lavapipe's measured profile);
/// skipped without lavapipe, unless `REFRAST_REQUIRE_DRIVERS=1`.
#[test]
fn a_flipped_driver_expectation_fails_the_run() {
    let dir = scratch("expect-driver");
    let real = Path::new(env!("CARGO_MANIFEST_DIR")).join("../expectations/lavapipe.txt");
    let text = std::fs::read_to_string(&real).expect("expectations/lavapipe.txt");
    let rule = "fill.guard-band.exact";
    let run = |file: &Path| {
        Command::new(REFRAST)
            .args(["certify", "--impl", "lavapipe", "--rule", rule, "--cases", "5"])
            .arg("--expect")
            .arg(file)
            .arg("--report")
            .arg(dir.join("report"))
            .arg("--json")
            .arg(dir.join("r.json"))
            .output()
            .expect("refrast runs")
    };
    let out = run(&real);
    let json = std::fs::read_to_string(dir.join("r.json")).expect("a JSON report");
    if json.contains("\"skipped\"") {
        assert!(
            std::env::var("REFRAST_REQUIRE_DRIVERS").as_deref() != Ok("1"),
            "REFRAST_REQUIRE_DRIVERS is set, but lavapipe was skipped: {json}"
        );
        println!("lavapipe: SKIPPED (not installed)");
        return;
    }
    assert_eq!(out.status.code(), Some(0), "as checked in: {}", stdout(&out));
    let flipped = dir.join("flipped.txt");
    let line = text
        .lines()
        .find(|l| l.starts_with(rule))
        .expect("lavapipe's file has the rule's line");
    std::fs::write(&flipped, text.replace(line, &format!("{rule}  pass"))).expect("write");
    let out = run(&flipped);
    assert_eq!(out.status.code(), Some(1), "flipped: {}", stdout(&out));
    assert!(stdout(&out).contains(&format!("lavapipe {rule}: expected pass, got n/a")));
}

/// A driver asked for by name that cannot run here (no `vulkaninfo` on `PATH`, so lavapipe's
/// subpixel grid cannot be read) is SKIPPED with what is missing, and the run exits 1: it
/// certified nothing of what it was asked. Under `--expect` the same.
#[test]
fn an_unavailable_implementation_fails_the_run() {
    let dir = scratch("expect-unavailable");
    let real = Path::new(env!("CARGO_MANIFEST_DIR")).join("../expectations/lavapipe.txt");
    for expect in [None, Some(&real)] {
        let mut command = Command::new(REFRAST);
        command
            .args(["certify", "--impl", "lavapipe", "--rule", "fill.guard-band.exact"])
            .args(["--cases", "5", "--in-process"])
            .arg("--report")
            .arg(dir.join("report"))
            .env("PATH", dir.join("no-such-folder"));
        if let Some(file) = expect {
            command.arg("--expect").arg(file);
        }
        let out = command.output().expect("refrast runs");
        let said = stdout(&out);
        assert_eq!(out.status.code(), Some(1), "{said}");
        assert!(
            said.contains("lavapipe: SKIPPED") && said.contains("vulkaninfo"),
            "{said}"
        );
        assert!(
            said.contains("unavailable") || said.contains("NOT AVAILABLE"),
            "{said}"
        );
    }
}
