//! What the CLI's tests that write files share: the binary, and a fresh folder per test.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The `refrast` binary cargo built for these tests.
pub const REFRAST: &str = env!("CARGO_BIN_EXE_refrast");

/// A fresh folder for one test's outputs, under cargo's folder for test scratch.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// Whether `program --version` runs; if not, says why the test cannot run here.
pub fn have(program: &str) -> bool {
    let found = Command::new(program)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var("REFRAST_REQUIRE_CLIENTS").as_deref() != Ok("1"),
            "{program} is missing, and REFRAST_REQUIRE_CLIENTS=1 requires it"
        );
        eprintln!("SKIPPED: {program} is not installed (apt-get install {program})");
    }
    found
}
