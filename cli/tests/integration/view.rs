//! `refrast view`: without a display it says so in one line and exits 2, as it does for bad
//! arguments; with Xvfb, xdotool and python3-xlib, scripts/check_viewer.py drives the window.
//!
//! Without those tools the window test says so and passes, unless `REFRAST_REQUIRE_VIEWER=1`
//! (set by `.ci/run`, which installs them) makes that a failure.

use std::path::Path;
use std::process::{Command, Output};

const REFRAST: &str = env!("CARGO_BIN_EXE_refrast");

/// `refrast view ARGS` with no display at all.
fn headless(args: &[&str]) -> Output {
    Command::new(REFRAST)
        .arg("view")
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("refrast runs")
}

/// Asserts exit code 2 and an error on stderr's first line containing `names`, no panic.
fn refused(args: &[&str], names: &str) -> String {
    let out = headless(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    let first = stderr.lines().next().unwrap_or("");
    assert!(
        first.starts_with("error: ") && first.contains(names),
        "{args:?}: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    stderr
}

#[test]
fn without_a_display_it_says_so_in_one_line_and_exits_2() {
    let stderr = refused(&["room"], "DISPLAY is not set");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("xvfb-run"), "{stderr}");
    // The same with a measurement asked for: nothing is measured without a window.
    let out = headless(&["room", "--frames", "5"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty(), "{}", String::from_utf8_lossy(&out.stdout));
}

#[test]
fn a_display_that_is_not_there_is_named() {
    let out = Command::new(REFRAST)
        .args(["view", "room"])
        .env("DISPLAY", ":4093")
        .output()
        .expect("refrast runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: could not open a window on DISPLAY=:4093"),
        "{stderr}"
    );
}

#[test]
fn bad_arguments_are_refused_before_any_window() {
    // Each in one line, as `refrast render` refuses them.
    for (args, names) in [
        (
            &["no-such-scene"][..],
            "no scene or mesh file named 'no-such-scene'",
        ),
        (
            &["room", "--impl", "no-such-impl"],
            "no implementation named 'no-such-impl'",
        ),
        (
            &["room", "--output", "no/such/folder"],
            "--output no/such/folder is not a folder",
        ),
    ] {
        let stderr = refused(args, names);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
    // Values clap checks: its message, then a hint line.
    refused(&["room", "--size", "0x480"], "--size");
    refused(&["room", "--mode", "lines"], "no mode named 'lines'");
    refused(&["room", "--threads", "0"], "--threads");
    refused(&["room", "--frames", "0"], "--frames");
}

#[test]
fn the_window_passes_scripts_check_viewer_py() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let Ok(out) = Command::new("python3")
        .arg(root.join("scripts/check_viewer.py"))
        .args(["--refrast", REFRAST])
        .output()
    else {
        assert!(
            std::env::var("REFRAST_REQUIRE_VIEWER").as_deref() != Ok("1"),
            "python3 is missing, and REFRAST_REQUIRE_VIEWER=1 requires it"
        );
        eprintln!("SKIPPED: no python3 to run scripts/check_viewer.py");
        return;
    };
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // The script skips (exit 0, saying so) without its tools, and fails itself when
    // REFRAST_REQUIRE_VIEWER=1 asks for them.
    eprintln!("{stdout}");
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("passed") || stdout.contains("SKIPPED"),
        "{stdout}"
    );
}
