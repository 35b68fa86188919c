//! `refrast impls` lists the restricted references under an origin of their own, plain
//! `certify` leaves them out, and `--impl` takes a glob of names.

use std::process::Command;

const REFRAST: &str = env!("CARGO_BIN_EXE_refrast");

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(REFRAST).args(args).output().expect("refrast runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn restricted_references_are_listed_apart() {
    let (code, out, _) = run(&["impls"]);
    assert_eq!(code, 0);
    let restricted: Vec<&str> = out.lines().filter(|l| l.starts_with("restricted:")).collect();
    assert!(restricted.len() >= 30, "{out}");
    assert!(
        restricted.iter().all(|l| l.contains("reference, restricted")),
        "{out}"
    );
    assert!(out.contains("restricted:fixed-function"));
}

#[test]
fn a_glob_names_several_implementations_and_a_glob_naming_none_is_a_usage_error() {
    let report = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("glob-report");
    let report = report.to_str().expect("a UTF-8 path");
    let (code, out, err) = run(&[
        "certify",
        "--impl",
        "restricted:cull=*",
        "--rule",
        "fill.fan.*",
        "--cases",
        "20",
        "--report",
        report,
    ]);
    assert_eq!(code, 0, "{out}{err}");
    for name in [
        "restricted:cull=none",
        "restricted:cull=back",
        "restricted:cull=front",
    ] {
        assert!(
            out.contains(&format!("{name}: 1 passed, 0 failed")),
            "{name}:\n{out}"
        );
    }
    let (code, _, err) = run(&["certify", "--impl", "nothing-here:*", "--report", report]);
    assert_eq!(code, 2);
    assert!(
        err.contains("no implementation's name matches 'nothing-here:*'"),
        "{err}"
    );
}
