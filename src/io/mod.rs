//! Readers and writers: cross-sections (CSL, JSON) and meshes.
pub mod csl;
pub mod json;
pub mod mesh;

use crate::error::{Error, Result};
use crate::sections::Sections;
use std::path::Path;

/// Read cross-sections, CSL or JSON by extension (`.csl`, `.json`).
pub fn read_sections(_path: &Path) -> Result<Sections> {
    Err(Error::Unavailable(
        "section reading is not implemented yet".into(),
    ))
}

/// Write cross-sections, CSL or JSON by extension.
pub fn write_sections(_path: &Path, _sections: &Sections) -> Result<()> {
    Err(Error::Unavailable(
        "section writing is not implemented yet".into(),
    ))
}
