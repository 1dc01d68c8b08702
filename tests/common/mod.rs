//! Helpers shared by the integration tests.
#![allow(dead_code)]
use std::path::PathBuf;

/// The shared data directory: `$SLICE2SOLID_SHARED`, else `$CARGO_MANIFEST_DIR/../shared` if it
/// exists, else `/work/shared`.
pub fn shared_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("SLICE2SOLID_SHARED") {
        return PathBuf::from(d);
    }
    let sibling = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared"));
    if sibling.exists() {
        return sibling;
    }
    PathBuf::from("/work/shared")
}

/// Every `*.csl` file of the shared data, sorted.
pub fn shared_csl_files() -> Vec<PathBuf> {
    let dir = shared_dir().join("data/csl");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "csl"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no CSL files in {}", dir.display());
    files
}
