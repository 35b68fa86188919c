//! `refrast certify --exec` on the example clients in `clients/`: the correct Python rasterizer
//! passes every rule, and the two course labs, ported to Python and C++, get exactly the verdicts
//! (and counterexamples) of their Rust ports in the zoo.
//!
//! Needs `python3` and `g++`; without them each test says so and passes, unless
//! `REFRAST_REQUIRE_CLIENTS=1` (set by `.ci/run`, which installs both) makes that a failure.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::support::have;

const REFRAST: &str = env!("CARGO_BIN_EXE_refrast");

/// The repository root (clients/ lives there).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Runs `refrast certify` with `args`, returning its exit code and its JSON report's rules.
fn certify(name: &str, args: &[&str]) -> (i32, Vec<Value>) {
    let json = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.json"));
    let out = Command::new(REFRAST)
        .current_dir(root())
        .arg("certify")
        .args(args)
        // Verdicts must not depend on this machine's speed: no budget stops a rule early.
        .args(["--budget", "3600"])
        .arg("--json")
        .arg(&json)
        .arg("--report")
        .arg(Path::new(env!("CARGO_TARGET_TMPDIR")).join("report"))
        .output()
        .expect("refrast runs");
    let text = std::fs::read_to_string(&json).unwrap_or_else(|e| {
        panic!(
            "no report from certify {args:?} ({e}):\n{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    let report: Value = serde_json::from_str(&text).expect("the report is JSON");
    let rules = report["implementations"][0]["rules"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    (out.status.code().unwrap_or(-1), rules)
}

/// Rule IDs with `status`, space-separated.
fn with_status(rules: &[Value], status: &str) -> String {
    // The clients declare triangles at one sample: the rules of lines, points and samples (their
    // families, and the facing of lines and points) are n/a for them.
    let declared = |r: &&Value| {
        !["line", "point", "msaa"].contains(&r["family"].as_str().unwrap_or(""))
            && r["id"] != "meta.facing.lines-points-front"
    };
    let ids: Vec<&str> = rules
        .iter()
        .filter(declared)
        .filter(|r| r["status"] == status)
        .filter_map(|r| r["id"].as_str())
        .collect();
    ids.join(" ")
}

/// The client's statuses and counterexamples equal those of the built-in `port`.
fn same_as_port(client: &[Value], port: &str, cases: &str) {
    let (_, expected) = certify(port, &["--impl", port, "--cases", cases]);
    assert_eq!(client.len(), expected.len());
    for (c, e) in client.iter().zip(&expected) {
        assert_eq!(
            (&c["id"], &c["status"], &c["counterexample"]),
            (&e["id"], &e["status"], &e["counterexample"]),
            "the client and its Rust port `{port}` differ"
        );
    }
}

/// Every failure's counterexample, replayed alone through `reach` (`--exec CMD`, `--impl NAME`)
/// from the `.case.json` certify wrote, fails again with the same message; the reference
/// passes each.
fn replays_alike(failures: &[Value], reach: &[&str]) {
    let failed: Vec<&Value> = failures.iter().filter(|r| r["status"] == "fail").collect();
    assert!(!failed.is_empty());
    for r in failed {
        let id = r["id"].as_str().unwrap_or("?");
        assert_eq!(
            r["case"]["rule"], r["id"],
            "{id}: the report carries its case as data"
        );
        let path = r["case_path"]
            .as_str()
            .unwrap_or_else(|| panic!("{id}: no case file"));
        let replay = |reach: &[&str]| {
            let out = Command::new(REFRAST)
                .current_dir(root())
                .arg("replay")
                .args(reach)
                .arg(path)
                .arg("--json")
                .arg("--report")
                .arg(Path::new(env!("CARGO_TARGET_TMPDIR")).join("replay"))
                .output()
                .expect("refrast runs");
            let report: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
                panic!(
                    "{id}: replay printed no JSON ({e}): {}",
                    String::from_utf8_lossy(&out.stderr)
                )
            });
            (out.status.code(), report)
        };
        let (code, again) = replay(reach);
        assert_eq!(
            (code, &again["status"], &again["message"]),
            (Some(1), &r["status"], &r["message"]),
            "{id} replayed through {reach:?}"
        );
        assert!(again["picture"].is_string(), "{id}: the replay draws its picture");
        let (code, reference) = replay(&["--impl", "reference"]);
        assert_eq!(
            (code, &reference["status"]),
            (Some(0), &"pass".into()),
            "{id} on the reference"
        );
    }
}

#[test]
fn python_topleft_passes_every_rule() {
    if !have("python3") {
        return;
    }
    let (code, rules) = certify(
        "topleft",
        &["--exec", "python3 clients/python/topleft.py", "--cases", "60"],
    );
    assert_eq!(code, 0, "{rules:#?}");
    assert_eq!(rules.len(), refrast_conformance::catalogue().len());
    assert_eq!(with_status(&rules, "fail"), "");
    // It draws no lines or points, so no polygon mode either, nor their clip distances; and it
    // has no conservative rasterization.
    assert_eq!(
        with_status(&rules, "n/a"),
        "fill.conservative.over fill.conservative.under meta.polygon-mode.facing clip.distance.lines-points",
        "n/a beyond the families it does not declare"
    );
}

/// With two children the rules finish in any order, but print in catalogue order; the summary
/// names the rules a short budget cut, and proptest prints nothing of its own.
#[test]
fn rules_print_in_catalogue_order_and_the_summary_names_budget_cuts() {
    if !have("python3") {
        return;
    }
    let out = Command::new(REFRAST)
        .current_dir(root())
        .args([
            "certify",
            "--exec",
            "python3 clients/python/topleft.py",
            "--rule",
            "fill.",
            "--rule",
            "meta.",
        ])
        .args(["--jobs", "2", "--budget", "0.3", "--report"])
        .arg(Path::new(env!("CARGO_TARGET_TMPDIR")).join("order"))
        .output()
        .expect("refrast runs");
    let text = String::from_utf8_lossy(&out.stdout);
    let printed: Vec<&str> = text
        .lines()
        .filter(|l| {
            ["pass ", "FAIL ", "n/a ", "BEYOND", "CRASH", "TIMEOUT", "FLAKE"]
                .iter()
                .any(|s| l.starts_with(s))
        })
        .filter_map(|l| l.split_whitespace().nth(1))
        .collect();
    let catalogue: Vec<&str> = refrast_conformance::catalogue()
        .iter()
        .map(|r| r.id)
        .filter(|id| id.starts_with("fill.") || id.starts_with("meta."))
        .collect();
    assert_eq!(printed, catalogue, "{text}");
    let summary = text
        .lines()
        .find(|l| l.contains("the time budget cut"))
        .unwrap_or_else(|| panic!("no budget line in the summary:\n{text}"));
    assert!(summary.contains("fill.mesh.exactly-once"), "{summary}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("proptest:"), "{stderr}");
}

/// The Python client as a fixed-function rasterizer: one cull mode declared and used whatever a
/// draw asks. It must still pass every rule, none of them n/a but the one that needs culling of
/// both faces, which one mode is not (and those it never declared: conservative rasterization,
/// lines and points) (it failed a dozen when the rules expected the coverage of
/// no culling, before every rule asked its question under what the profile supports:
/// docs/profiles.md).
#[test]
fn python_topleft_with_one_cull_mode_passes_every_rule() {
    if !have("python3") {
        return;
    }
    for mode in ["back", "front"] {
        let command = format!("python3 clients/python/topleft.py --cull {mode}");
        let (code, rules) = certify(
            &format!("topleft-cull-{mode}"),
            &["--exec", &command, "--cases", "40"],
        );
        assert_eq!(code, 0, "--cull {mode}: {rules:#?}");
        assert_eq!(with_status(&rules, "fail"), "", "--cull {mode}");
        assert_eq!(
            with_status(&rules, "n/a"),
            "meta.cull.both-faces fill.conservative.over fill.conservative.under meta.polygon-mode.facing clip.distance.lines-points",
            "--cull {mode}"
        );
    }
}

/// A child declaring no cull mode at all cannot be judged: it fails to start with the line to
/// fix, and the next implementation of the same run is still certified.
#[test]
fn a_child_declaring_no_cull_mode_is_refused_and_the_run_goes_on() {
    if !have("python3") {
        return;
    }
    let json = Path::new(env!("CARGO_TARGET_TMPDIR")).join("refused.json");
    let out = Command::new(REFRAST)
        .current_dir(root())
        .args([
            "certify",
            "--impl",
            "reference",
            "--rule",
            "fill.fan.*",
            "--cases",
            "10",
        ])
        .args([
            "--exec",
            "python3 -c \"print('refrast-protocol 1'); print('cull'); print('ready')\"",
        ])
        .arg("--json")
        .arg(&json)
        .arg("--report")
        .arg(Path::new(env!("CARGO_TARGET_TMPDIR")).join("refused"))
        .output()
        .expect("refrast runs");
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("a report")).expect("JSON");
    assert_eq!(
        report["implementations"][0]["rules"][0]["status"], "pass",
        "the reference, before it, is certified"
    );
    let why = report["implementations"][1]["failed_to_start"]
        .as_str()
        .unwrap_or_default();
    assert!(why.contains("cull") && why.contains("one or more of"), "{why}");
}

#[test]
fn python_lab004_gets_the_verdicts_of_seed_004() {
    if !have("python3") {
        return;
    }
    let (code, rules) = certify(
        "lab004",
        &["--exec", "python3 clients/python/lab004.py", "--cases", "200"],
    );
    assert_eq!(code, 1);
    // Counter-clockwise only, `O_i ≤ 0` owns every edge, pixel corners, far always clipped,
    // cuts nudged by 10⁻⁶ (zoo/src/course/lab004.rs says why each fails).
    assert_eq!(
        with_status(&rules, "fail"),
        "fill.mesh.exactly-once fill.fan.exactly-once fill.rotated-quad.exactly-once \
         fill.projected-mesh.exactly-once fill.interior.matches-raycast bary.vertex.one \
         bary.screen.reconstructs-sample depth.screen-linear.matches-raycast clip.interior.matches-raycast clip.mesh.watertight \
         clip.crossing-quad.watertight clip.far.respected clip.gl-range.matches-raycast \
         meta.reversal.flips-facing meta.translate.whole-pixels meta.translate.one-subpixel \
         meta.degenerate.empty"
    );
    same_as_port(&rules, "lab004-lineeq", "200");
    replays_alike(&rules, &["--exec", "python3 clients/python/lab004.py"]);
}

#[test]
fn cpp_lab000_gets_the_verdicts_of_seed_000() {
    if !(have("g++")) {
        return;
    }
    let binary = Path::new(env!("CARGO_TARGET_TMPDIR")).join("lab000");
    let status = Command::new("g++")
        .args(["-O2", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(&binary)
        .arg(root().join("clients/cpp/lab000.cpp"))
        .status()
        .expect("g++ runs");
    assert!(status.success(), "clients/cpp/lab000.cpp does not compile");
    let command = binary.display().to_string();
    let (code, rules) = certify("lab000", &["--exec", &command, "--cases", "200"]);
    // meta.facing.from-winding since the crossing scenes were widened (docs/reach.md): dividing
    // by a negative w mirrors a vertex, as in the Rust port.
    assert_eq!(code, 1);
    // `≥ 0` on every edge, samples at pixel corners, clockwise only, no clipping
    // (zoo/src/course/lab000.rs says why each fails; the barycentric rules judge its
    // screen-space weights, the kind it declares, as zoo/tests/integration/course.rs says: those of a
    // triangle with a vertex behind the eye for finiteness only, so bary.range.unit passes).
    assert_eq!(
        with_status(&rules, "fail"),
        "fill.mesh.exactly-once fill.fan.exactly-once fill.rotated-quad.exactly-once \
         fill.projected-mesh.exactly-once fill.interior.matches-raycast bary.vertex.one \
         bary.screen.reconstructs-sample clip.behind-eye.empty clip.interior.matches-raycast clip.mesh.watertight \
         clip.crossing-quad.watertight meta.reversal.flips-facing meta.translate.one-subpixel \
         meta.facing.from-winding"
    );
    same_as_port(&rules, "lab000", "200");
    replays_alike(&rules, &["--exec", &command]);
}

#[test]
fn a_child_that_cannot_start_fails_and_a_bad_command_is_a_usage_error() {
    let report = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-start");
    let out = Command::new(REFRAST)
        .args([
            "certify",
            "--exec",
            "./no-such-rasterizer",
            "--cases",
            "1",
            "--report",
        ])
        .arg(&report)
        .output()
        .expect("refrast runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("FAILED TO START") && text.contains("no-such-rasterizer"),
        "{text}"
    );
    let page = std::fs::read_to_string(report.join("index.html")).expect("the page, even so");
    assert!(page.contains("failed to start") && page.contains("./no-such-rasterizer"));
    let out = Command::new(REFRAST)
        .args(["certify", "--exec", "python3 'unbalanced"])
        .output()
        .expect("refrast runs");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--exec: bad command line"));
}

/// Whether some process's command line contains `marker` (from `/proc/*/cmdline`), not
/// counting zombies.
fn running(marker: &str) -> bool {
    std::fs::read_dir("/proc")
        .into_iter()
        .flatten()
        .flatten()
        .any(|entry| {
            let dir = entry.path();
            let cmdline = std::fs::read(dir.join("cmdline")).unwrap_or_default();
            let zombie = std::fs::read_to_string(dir.join("stat"))
                .ok()
                .and_then(|s| s.rsplit(')').next().map(|r| r.trim_start().starts_with('Z')))
                .unwrap_or(true);
            !zombie
                && String::from_utf8_lossy(&cmdline)
                    .replace('\0', " ")
                    .contains(marker)
        })
}

/// Interrupting `refrast certify --exec` (SIGINT, as Ctrl-C sends it, or SIGTERM) ends the
/// child, which leads a process group of its own that the terminal's signal would not reach:
/// here a child that answers its handshake and then sleeps, and would outlive refrast.
#[test]
fn an_interrupted_certify_leaves_no_child_behind() {
    for signal in ["INT", "TERM"] {
        // The child's command line holds the marker; refrast's (`36$((0))0.…`, which the
        // shell expands) does not.
        let tail = format!("{}{}", std::process::id(), signal.len());
        let marker = format!("3600.{tail}");
        let child = format!(
            "sh -c 'printf \"refrast-protocol 1\\nname sleeper\\nready\\n\"; exec sleep 36$((0))0.{tail}'"
        );
        let mut refrast = Command::new(REFRAST)
            .args(["certify", "--exec", &child, "--case-timeout", "60"])
            .args(["--report", env!("CARGO_TARGET_TMPDIR")])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("refrast starts");
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(20);
        while !running(&marker) {
            assert!(std::time::Instant::now() < deadline, "the child never started");
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &refrast.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(killed.success());
        let status = refrast.wait().expect("refrast exits");
        assert_eq!(status.code(), Some(130), "SIG{signal}: {status}");
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(5);
        while running(&marker) && std::time::Instant::now() < deadline {
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        assert!(!running(&marker), "SIG{signal}: the child outlived refrast");
    }
}
