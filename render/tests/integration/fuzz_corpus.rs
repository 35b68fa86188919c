//! Replays the `mesh_load` fuzz target's committed seeds and reproducers on stable:
//! `fuzz/seeds/mesh_load/` (a few valid PLY and OBJ files) and `fuzz/regressions/mesh_load/`
//! (every input that once made the loaders panic or accept a bad mesh, named after what it showed).

use std::panic::catch_unwind;
use std::path::{Path, PathBuf};

use refrast_render::load::{check_any_bytes, parse_obj, parse_ply};

/// The files of `fuzz/<kind>/mesh_load/`, sorted; none when the folder does not exist.
fn files(kind: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz")
        .join(kind)
        .join("mesh_load");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| Some(e.ok()?.path()))
                .filter(|p| p.is_file())
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

#[test]
fn mesh_load_seeds_and_regressions() {
    let seeds = files("seeds");
    assert!(!seeds.is_empty(), "fuzz/seeds/mesh_load is empty");
    let mut failures = Vec::new();
    for path in seeds.iter().chain(&files("regressions")) {
        let bytes = std::fs::read(path).expect("a corpus file is readable");
        match catch_unwind(|| check_any_bytes(&bytes)) {
            Ok(Ok(())) => {}
            Ok(Err(f)) => failures.push(format!("{}: {f}", path.display())),
            Err(_) => failures.push(format!("{}: panicked (message above)", path.display())),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The seeds are valid meshes: the corpus starts from files that read.
    let read = seeds
        .iter()
        .filter(|p| {
            let bytes = std::fs::read(p).expect("readable");
            parse_ply(&bytes).is_ok() || parse_obj(&bytes).is_ok()
        })
        .count();
    assert_eq!(read, seeds.len(), "a seed no longer reads");
}
