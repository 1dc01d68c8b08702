//! Triangle and tetrahedral mesh files. Formats are chosen by file extension.
use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
use std::path::Path;

/// Read a triangle mesh: STL (ASCII or binary), OBJ, PLY (ASCII or binary).
pub fn read_trimesh(_path: &Path) -> Result<TriMesh> {
    Err(Error::Unavailable(
        "mesh reading is not implemented yet".into(),
    ))
}

/// Write a triangle mesh: .obj, .ply, .stl, .off.
pub fn write_trimesh(_path: &Path, _mesh: &TriMesh) -> Result<()> {
    Err(Error::Unavailable(
        "mesh writing is not implemented yet".into(),
    ))
}

/// Write a tetrahedral mesh: .vtk (legacy unstructured grid) or .mesh (MEDIT).
pub fn write_tetmesh(_path: &Path, _mesh: &TetMesh) -> Result<()> {
    Err(Error::Unavailable(
        "tetrahedral mesh writing is not implemented yet".into(),
    ))
}
