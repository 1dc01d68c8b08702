//! Helpers shared by the integration tests.
#![allow(dead_code)]
use std::path::PathBuf;
use std::process::{Command, Output};

/// The command-line binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slice2solid"))
}

/// The JSON a successful run printed (the test fails with the run's stderr otherwise).
pub fn json_of_success(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

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
