//! Readers and writers: cross-sections (CSL, JSON, and DICOM RT Structure Sets to read) and meshes.
pub mod csl;
pub mod json;
pub mod loose_contours;
pub mod mesh;
pub mod plain;
pub mod rtstruct;
pub mod vtk_xml;

use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
use crate::sections::Sections;
use std::path::Path;

pub use crate::validate::ReadOptions;

/// The section formats, chosen by file extension (case-insensitive); a file with another extension
/// (clinical exports are often named by UID) is DICOM when it has the DICOM preamble and `DICM`.
fn section_format(path: &Path) -> Result<&'static str> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("csl") => Ok("csl"),
        Some("json") => Ok("json"),
        Some("dcm") => Ok("dcm"),
        _ if has_dicom_preamble(path) => Ok("dcm"),
        _ => Err(Error::input(
            path.display().to_string(),
            "unknown cross-section format: expected a .csl, .json or .dcm (DICOM RT Structure Set) file",
        )),
    }
}

fn has_dicom_preamble(path: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 132];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok()
        && &head[128..] == b"DICM"
}

/// Read cross-sections, CSL, JSON or RT Structure Set by extension (`.csl`, `.json`, `.dcm`),
/// validated and repaired.
pub fn read_sections(path: &Path) -> Result<Sections> {
    read_sections_with(path, &ReadOptions::default())
}

/// Read cross-sections with `options` (`strict`: refuse instead of repairing, see `ReadOptions`).
pub fn read_sections_with(path: &Path, options: &ReadOptions) -> Result<Sections> {
    read_sections_of_roi(path, options, None)
}

/// Read cross-sections with `options`; `roi`: only the ROI of this name, for an RT Structure Set
/// (the other formats have no ROI names: naming one is an error; select a label instead).
pub fn read_sections_of_roi(
    path: &Path,
    options: &ReadOptions,
    roi: Option<&str>,
) -> Result<Sections> {
    match (section_format(path)?, roi) {
        ("dcm", _) => rtstruct::read_rtstruct_with(path, options, roi),
        (_, Some(name)) => Err(Error::input(
            format!("{}: --roi {name:?}", path.display()),
            "only DICOM RT Structure Sets have ROIs; select a label of this file with --label",
        )),
        ("csl", None) => csl::read_csl_with(path, options),
        _ => json::read_json_with(path, options),
    }
}

/// Write cross-sections, CSL or JSON by extension.
pub fn write_sections(path: &Path, sections: &Sections) -> Result<()> {
    match section_format(path)? {
        "csl" => csl::write_csl(path, sections),
        "json" => json::write_json(path, sections),
        _ => Err(Error::Unavailable(format!(
            "{}: writing DICOM RT Structure Sets (write .csl or .json)",
            path.display()
        ))),
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

/// Write labelled tetrahedra (a partition): .vtu and .vtk with a `label` cell array, .mesh with
/// the label as each tetrahedron's reference.
pub fn write_labelled_tets(path: &Path, tets: &TetMesh, labels: &[i32]) -> Result<()> {
    if has_extension(path, "vtu") {
        let arrays = [vtk_xml::CellArray {
            name: "label",
            values: labels,
        }];
        return vtk_xml::write_vtu(path, tets, &arrays);
    }
    mesh::write_tetmesh_labelled(path, tets, Some(labels))
}

fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}
