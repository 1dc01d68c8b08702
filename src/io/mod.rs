//! Readers and writers: cross-sections (CSL, JSON) and meshes.
pub mod csl;
pub mod json;
pub mod mesh;
pub mod plain;

use crate::error::{Error, Result};
use crate::sections::Sections;
use std::path::Path;

pub use crate::validate::ReadOptions;

/// The section formats, chosen by file extension (case-insensitive).
fn section_format(path: &Path) -> Result<&'static str> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("csl") => Ok("csl"),
        Some("json") => Ok("json"),
        _ => Err(Error::input(
            path.display().to_string(),
            "unknown cross-section format: expected a .csl or .json file",
        )),
    }
}

/// Read cross-sections, CSL or JSON by extension (`.csl`, `.json`), validated and repaired.
pub fn read_sections(path: &Path) -> Result<Sections> {
    read_sections_with(path, &ReadOptions::default())
}

/// Read cross-sections with `options` (`strict`: refuse instead of repairing, see `ReadOptions`).
pub fn read_sections_with(path: &Path, options: &ReadOptions) -> Result<Sections> {
    match section_format(path)? {
        "csl" => csl::read_csl_with(path, options),
        _ => json::read_json_with(path, options),
    }
}

/// Write cross-sections, CSL or JSON by extension.
pub fn write_sections(path: &Path, sections: &Sections) -> Result<()> {
    match section_format(path)? {
        "csl" => csl::write_csl(path, sections),
        _ => json::write_json(path, sections),
    }
}
