//! Readers and writers: cross-sections (CSL, JSON) and meshes.
pub mod csl;
pub mod json;
pub mod mesh;
pub mod plain;
pub mod vtk_xml;

use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
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

/// Write a reconstructed surface by extension: `.vtp` (VTK XML PolyData) with the input plane each
/// triangle lies on and its label as cell data (`cell_data`; `sections` and `label` are the run's
/// input and `Options::label`), or any format of `mesh::write_trimesh`.
pub fn write_surface(
    path: &Path,
    surface: &TriMesh,
    sections: &Sections,
    label: Option<i32>,
) -> Result<()> {
    if !has_extension(path, "vtp") {
        return mesh::write_trimesh(path, surface);
    }
    let data = crate::cell_data::surface_cell_data(surface, sections, label)?;
    let arrays = [
        vtk_xml::CellArray {
            name: "plane",
            values: &data.plane,
        },
        vtk_xml::CellArray {
            name: "label",
            values: &data.label,
        },
    ];
    vtk_xml::write_vtp(path, surface, &arrays)
}

/// Write reconstructed tetrahedra by extension: `.vtu` (VTK XML UnstructuredGrid) with each
/// tetrahedron's label as cell data, or any format of `mesh::write_tetmesh`.
pub fn write_tets(
    path: &Path,
    tets: &TetMesh,
    sections: &Sections,
    label: Option<i32>,
) -> Result<()> {
    if !has_extension(path, "vtu") {
        return mesh::write_tetmesh(path, tets);
    }
    let labels = crate::cell_data::tet_labels(tets, sections, label)?;
    let arrays = [vtk_xml::CellArray {
        name: "label",
        values: &labels,
    }];
    vtk_xml::write_vtu(path, tets, &arrays)
}

fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}
