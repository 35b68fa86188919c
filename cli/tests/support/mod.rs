//! What the CLI's tests that write files share: the binary, and a fresh folder per test.

use std::path::{Path, PathBuf};

/// The `refrast` binary cargo built for these tests.
pub const REFRAST: &str = env!("CARGO_BIN_EXE_refrast");

/// A fresh folder for one test's outputs, under cargo's folder for test scratch.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}
