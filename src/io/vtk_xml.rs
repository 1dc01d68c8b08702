//! VTK XML files, for ParaView and 3D Slicer: a surface as PolyData (`.vtp`) and tetrahedra as an
//! UnstructuredGrid (`.vtu`, cell type 10), ASCII, coordinates as shortest round-trip doubles (so
//! they read back exactly), with named Int32 cell data arrays (see `cell_data`).
//! Format: <https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html> (XML file formats).
use super::mesh::write_file;
use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
use std::fmt::Write as _;
use std::path::Path;

/// One value per cell, shown under `name` in the viewer.
#[derive(Clone, Copy, Debug)]
pub struct CellArray<'a> {
    pub name: &'a str,
    pub values: &'a [i32],
}

/// Write `mesh` as VTK XML PolyData with `cell_data` (each array one value per triangle).
pub fn write_vtp(path: &Path, mesh: &TriMesh, cell_data: &[CellArray]) -> Result<()> {
    let name = path.display().to_string();
    check_cells(&mesh.triangles, mesh.vertices.len(), cell_data, &name)?;
    write_file(path, to_vtp_string(mesh, cell_data).as_bytes())
}

/// Write `mesh` as a VTK XML UnstructuredGrid of tetrahedra with `cell_data` (one value per tetrahedron).
pub fn write_vtu(path: &Path, mesh: &TetMesh, cell_data: &[CellArray]) -> Result<()> {
    let name = path.display().to_string();
    check_cells(&mesh.tets, mesh.vertices.len(), cell_data, &name)?;
    write_file(path, to_vtu_string(mesh, cell_data).as_bytes())
}

/// PolyData text: points, cell data, triangles as `Polys` (connectivity and offsets).
pub fn to_vtp_string(mesh: &TriMesh, cell_data: &[CellArray]) -> String {
    let mut s = header("PolyData");
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"{}\">",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    push_cell_data(&mut s, cell_data);
    push_points(&mut s, &mesh.vertices);
    s.push_str("      <Polys>\n");
    push_cells(&mut s, &mesh.triangles);
    s.push_str("      </Polys>\n");
    s.push_str("    </Piece>\n  </PolyData>\n</VTKFile>\n");
    s
}

/// UnstructuredGrid text: points, cell data, tetrahedra (connectivity, offsets, types = 10).
pub fn to_vtu_string(mesh: &TetMesh, cell_data: &[CellArray]) -> String {
    let mut s = header("UnstructuredGrid");
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.vertices.len(),
        mesh.tets.len()
    );
    push_cell_data(&mut s, cell_data);
    push_points(&mut s, &mesh.vertices);
    s.push_str("      <Cells>\n");
    push_cells(&mut s, &mesh.tets);
    s.push_str("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    push_values(&mut s, mesh.tets.iter().map(|_| 10));
    s.push_str("        </DataArray>\n      </Cells>\n");
    s.push_str("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    s
}

fn header(kind: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<!-- slice2solid -->\n<VTKFile type=\"{kind}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <{kind}>\n"
    )
}

fn push_points(s: &mut String, vertices: &[[f64; 3]]) {
    s.push_str("      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for p in vertices {
        let _ = writeln!(s, "          {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    s.push_str("        </DataArray>\n      </Points>\n");
}

fn push_cell_data(s: &mut String, cell_data: &[CellArray]) {
    if cell_data.is_empty() {
        return;
    }
    let _ = writeln!(s, "      <CellData Scalars=\"{}\">", cell_data[0].name);
    for a in cell_data {
        let _ = writeln!(
            s,
            "        <DataArray type=\"Int32\" Name=\"{}\" format=\"ascii\">",
            a.name
        );
        push_values(s, a.values.iter().copied());
        s.push_str("        </DataArray>\n");
    }
    s.push_str("      </CellData>\n");
}

/// `connectivity` and `offsets` of cells with `K` corners each.
fn push_cells<const K: usize>(s: &mut String, cells: &[[u32; K]]) {
    s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for c in cells {
        s.push_str("         ");
        for v in c {
            let _ = write!(s, " {v}");
        }
        s.push('\n');
    }
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    push_values(s, (1..=cells.len()).map(|i| K * i));
    s.push_str("        </DataArray>\n");
}

/// Values, 16 to a line.
fn push_values<T: std::fmt::Display>(s: &mut String, values: impl Iterator<Item = T>) {
    for (i, v) in values.enumerate() {
        s.push_str(if i % 16 == 0 { "          " } else { " " });
        let _ = write!(s, "{v}");
        if i % 16 == 15 {
            s.push('\n');
        }
    }
    if !s.ends_with('\n') {
        s.push('\n');
    }
}

/// Writers refuse what could not be read back: indices past the vertices, arrays of the wrong length,
/// names that are not plain words.
fn check_cells<const K: usize>(
    cells: &[[u32; K]],
    n: usize,
    cell_data: &[CellArray],
    name: &str,
) -> Result<()> {
    if let Some(i) = cells
        .iter()
        .position(|c| c.iter().any(|&v| v as usize >= n))
    {
        return Err(Error::input(
            name,
            format!("cell {i} has a vertex index out of range ({n} vertices)"),
        ));
    }
    for a in cell_data {
        if a.values.len() != cells.len() {
            return Err(Error::input(
                name,
                format!(
                    "cell data `{}` has {} values for {} cells",
                    a.name,
                    a.values.len(),
                    cells.len()
                ),
            ));
        }
        if a.name.is_empty()
            || !a
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_')
        {
            return Err(Error::input(
                name,
                format!("cell data name `{}` is not a plain word", a.name),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vtp_lists_points_cells_and_data_in_order() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.1, 0.0]],
            triangles: vec![[0, 1, 2]],
        };
        let s = to_vtp_string(
            &mesh,
            &[CellArray {
                name: "plane",
                values: &[-1],
            }],
        );
        assert!(
            s.contains("NumberOfPoints=\"3\"") && s.contains("NumberOfPolys=\"1\""),
            "{s}"
        );
        assert!(s.contains("          0.0 0.1 0.0\n"), "{s}");
        assert!(
            s.contains("          0 1 2\n")
                && s.contains("Name=\"offsets\" format=\"ascii\">\n          3\n"),
            "{s}"
        );
        assert!(
            s.contains("Name=\"plane\" format=\"ascii\">\n          -1\n"),
            "{s}"
        );
        let tets = TetMesh {
            vertices: mesh.vertices.clone(),
            tets: vec![[0, 1, 2, 3]],
        };
        let dir = std::env::temp_dir().join(format!("s2s_vtk_xml_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = write_vtu(&dir.join("t.vtu"), &tets, &[])
            .unwrap_err()
            .to_string();
        assert!(e.contains("cell 0 has a vertex index out of range"), "{e}");
        let e = write_vtp(
            &dir.join("t.vtp"),
            &mesh,
            &[CellArray {
                name: "label",
                values: &[],
            }],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("`label` has 0 values for 1 cells"), "{e}");
    }
}
