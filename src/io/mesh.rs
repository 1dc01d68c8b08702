//! Triangle and tetrahedral mesh files. Formats are chosen by file extension (case-insensitive).
//!
//! | read | `.stl` (ASCII or binary, detected by size), `.obj`, `.ply` (ASCII, binary LE/BE) |
//! |---|---|
//! | write | `.obj`, `.off` (ASCII, shortest round-trip floats: exact), `.ply` (binary little endian, doubles: exact), `.stl` (binary, f32) |
//! | tets | `.vtk` (legacy ASCII unstructured grid, cell type 10), `.mesh` (MEDIT, reference 1); both readable back |
//!
//! STL stores no connectivity: positions that are bit-for-bit equal are welded into one vertex (so the
//! mesh is indexed and shared vertices are shared). OBJ and PLY keep the file's vertices as they are.
//! Triangles whose corners are not three distinct vertex indices (after welding, for STL) carry no
//! area and are dropped. OBJ/PLY polygons with more than three corners are fan-triangulated.
//! Every malformed file gives `Error::Input` naming the file (and the line for text formats), never a panic.
//!
//! Layout: this module picks the format and does the file I/O; `read` parses, `write` formats.
use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
use std::collections::HashMap;
use std::io::Write as _;
use std::path::Path;

mod read;
mod write;
use read::{parse_medit, parse_vtk};
pub use read::{parse_obj, parse_off, parse_ply, parse_stl};
pub use write::{
    to_labelled_ply_bytes, to_medit_string, to_medit_string_labelled, to_obj_string, to_off_string,
    to_ply_bytes, to_stl_bytes, to_vtk_string, to_vtk_string_labelled,
};

/// Read a triangle mesh: STL (ASCII or binary), OBJ, PLY (ASCII or binary), OFF.
pub fn read_trimesh(path: &Path) -> Result<TriMesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let name = path.display().to_string();
    match extension(path).as_str() {
        "stl" => parse_stl(&bytes, &name),
        "obj" => parse_obj(&text(&bytes, &name)?, &name),
        "ply" => parse_ply(&bytes, &name),
        "off" => parse_off(&text(&bytes, &name)?, &name),
        other => Err(Error::input(
            name,
            format!(
                "unknown triangle mesh extension `{other}` (expected .stl, .obj, .ply or .off)"
            ),
        )),
    }
}

/// Write a triangle mesh: .obj, .ply, .stl, .off.
pub fn write_trimesh(path: &Path, mesh: &TriMesh) -> Result<()> {
    let name = path.display().to_string();
    check_trimesh(mesh, &name)?;
    if extension(path) == "stl" {
        if let Some(i) = mesh
            .vertices
            .iter()
            .position(|p| p.iter().any(|c| !(*c as f32).is_finite()))
        {
            return Err(Error::input(
                name,
                format!("vertex {i} is outside the f32 range binary STL can store"),
            ));
        }
    }
    let bytes = match extension(path).as_str() {
        "obj" => to_obj_string(mesh).into_bytes(),
        "off" => to_off_string(mesh).into_bytes(),
        "ply" => to_ply_bytes(mesh),
        "stl" => to_stl_bytes(mesh),
        other => {
            return Err(Error::input(
                name,
                format!(
                    "unknown output mesh extension `{other}` (expected .obj, .ply, .stl or .off)"
                ),
            ))
        }
    };
    write_file(path, &bytes)
}

/// Write an interface network (`.ply` only): every triangle with the labels on its two sides as
/// face properties `label0` (behind) and `label1` (in front), see [`to_labelled_ply_bytes`].
pub fn write_labelled_network(path: &Path, mesh: &TriMesh, labels: &[[i32; 2]]) -> Result<()> {
    let name = path.display().to_string();
    if extension(path) != "ply" {
        return Err(Error::input(
            name,
            "an interface network is written as .ply (a label pair per face)",
        ));
    }
    check_trimesh(mesh, &name)?;
    write_file(path, &to_labelled_ply_bytes(mesh, labels))
}

/// Write a tetrahedral mesh: .vtk (legacy unstructured grid) or .mesh (MEDIT).
pub fn write_tetmesh(path: &Path, mesh: &TetMesh) -> Result<()> {
    write_tetmesh_labelled(path, mesh, None)
}

/// [`write_tetmesh`] with a label per tetrahedron (VTK cell data, MEDIT references) where given.
pub fn write_tetmesh_labelled(path: &Path, mesh: &TetMesh, labels: Option<&[i32]>) -> Result<()> {
    let name = path.display().to_string();
    let n = mesh.vertices.len();
    if let Some((i, _)) = mesh
        .tets
        .iter()
        .enumerate()
        .find(|(_, t)| t.iter().any(|&v| v as usize >= n))
    {
        return Err(Error::input(
            name,
            format!("tetrahedron {i} has a vertex index out of range ({n} vertices)"),
        ));
    }
    let s = match extension(path).as_str() {
        "vtk" => to_vtk_string_labelled(mesh, labels),
        "mesh" => to_medit_string_labelled(mesh, labels),
        other => {
            return Err(Error::input(
                name,
                format!("unknown tetrahedral mesh extension `{other}` (expected .vtk or .mesh)"),
            ))
        }
    };
    write_file(path, s.as_bytes())
}

/// Read a tetrahedral mesh written by [`write_tetmesh`] (or any VTK legacy ASCII unstructured grid whose
/// cells are all tetrahedra, or MEDIT `.mesh` with `Vertices` and `Tetrahedra`). Used by tests and tools.
pub fn read_tetmesh(path: &Path) -> Result<TetMesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let name = path.display().to_string();
    let s = text(&bytes, &name)?;
    match extension(path).as_str() {
        "vtk" => parse_vtk(&s, &name),
        "mesh" => parse_medit(&s, &name),
        other => Err(Error::input(
            name,
            format!("unknown tetrahedral mesh extension `{other}` (expected .vtk or .mesh)"),
        )),
    }
}

/// Merge vertices with bit-for-bit equal positions (`-0.0` equals `0.0`) and drop triangles that become
/// degenerate (two equal corner indices). Vertices keep the order of their first use.
pub fn weld_exact(mesh: &TriMesh) -> TriMesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::with_capacity(mesh.vertices.len());
    let mut out = TriMesh::default();
    let mut remap = vec![u32::MAX; mesh.vertices.len()];
    for t in &mesh.triangles {
        let mut nt = [0u32; 3];
        for k in 0..3 {
            let old = t[k] as usize;
            if remap[old] == u32::MAX {
                let p = mesh.vertices[old];
                let key = p.map(|c| (c + 0.0).to_bits());
                let next = out.vertices.len() as u32;
                let id = *map.entry(key).or_insert_with(|| {
                    out.vertices.push(p);
                    next
                });
                remap[old] = id;
            }
            nt[k] = remap[old];
        }
        if nt[0] != nt[1] && nt[1] != nt[2] && nt[0] != nt[2] {
            out.triangles.push(nt);
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Helpers

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

fn text(bytes: &[u8], name: &str) -> Result<String> {
    String::from_utf8(bytes.to_vec()).map_err(|e| {
        Error::input(
            name,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

pub(crate) fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut f = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
    f.write_all(bytes).map_err(|e| Error::io(path, e))
}

fn drop_degenerate(mesh: &mut TriMesh) {
    mesh.triangles
        .retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
}

fn check_trimesh(mesh: &TriMesh, name: &str) -> Result<()> {
    check_indices(&mesh.triangles, mesh.vertices.len(), name, "triangle")
}

fn check_tets(mesh: &TetMesh, name: &str) -> Result<()> {
    check_indices(&mesh.tets, mesh.vertices.len(), name, "tetrahedron")
}

/// Writers refuse a cell that refers past the vertex array instead of writing a file that cannot be read back.
fn check_indices<const K: usize>(
    cells: &[[u32; K]],
    n: usize,
    name: &str,
    what: &str,
) -> Result<()> {
    match cells
        .iter()
        .position(|c| c.iter().any(|&v| v as usize >= n))
    {
        Some(i) => Err(Error::input(
            name,
            format!("{what} {i} has a vertex index out of range ({n} vertices)"),
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> TriMesh {
        TriMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.1, 0.2, 1.0 / 3.0],
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        }
    }

    #[test]
    fn obj_and_off_text_round_trip_exactly() {
        let m = tetra();
        assert_eq!(parse_obj(&to_obj_string(&m), "t.obj").unwrap(), m);
        assert_eq!(parse_ply(&to_ply_bytes(&m), "t.ply").unwrap(), m);
        let labelled = to_labelled_ply_bytes(&m, &vec![[0, 3]; m.triangles.len()]);
        assert_eq!(parse_ply(&labelled, "t.ply").unwrap(), m);
        assert_eq!(parse_off(&to_off_string(&m), "t.off").unwrap(), m);
    }

    #[test]
    fn stl_binary_welds_shared_corners() {
        let m = tetra();
        let back = parse_stl(&to_stl_bytes(&m), "t.stl").unwrap();
        assert_eq!(back.vertices.len(), 4);
        assert_eq!(back.triangles.len(), 4);
    }

    #[test]
    fn big_endian_ply_with_float_coordinates() {
        let m = tetra();
        let mut b = String::from(
            "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
             property float z\nelement face 4\nproperty list uchar uint vertex_index\nend_header\n"
        )
        .into_bytes();
        for p in &m.vertices {
            for c in p {
                b.extend_from_slice(&(*c as f32).to_be_bytes());
            }
        }
        for t in &m.triangles {
            b.push(3);
            for i in t {
                b.extend_from_slice(&i.to_be_bytes());
            }
        }
        let back = parse_ply(&b, "be.ply").unwrap();
        assert_eq!(back.triangles, m.triangles);
        assert_eq!(back.vertices[3][2], (1.0f64 / 3.0) as f32 as f64);
    }

    #[test]
    fn binary_stl_whose_header_says_solid_is_binary() {
        let mut b = to_stl_bytes(&tetra());
        b[..12].copy_from_slice(b"solid tetra ");
        let m = parse_stl(&b, "s.stl").unwrap();
        assert_eq!(m.triangles.len(), 4);
        assert_eq!(m.vertices.len(), 4);
    }

    #[test]
    fn obj_polygons_are_fan_triangulated_and_negative_indices_work() {
        let s = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2//2 3 -1\n";
        let m = parse_obj(s, "q.obj").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn bad_obj_names_the_line() {
        let e = parse_obj("v 0 0 0\nv 1 0 nan\n", "b.obj").unwrap_err();
        assert!(e.to_string().starts_with("b.obj:2:"), "{e}");
        let e = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", "b.obj").unwrap_err();
        assert!(e.to_string().starts_with("b.obj:5:"), "{e}");
    }
}
