//! The mesh writers: text (OBJ, OFF, VTK, MEDIT) and bytes (PLY, STL) of a mesh, without the file.
use crate::mesh::{TetMesh, TriMesh};
use std::fmt::Write as _;

/// Wavefront OBJ text: `v x y z` with shortest round-trip floats, `f a b c` 1-based.
pub fn to_obj_string(mesh: &TriMesh) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 24 * mesh.triangles.len());
    s.push_str("# slice2solid\n");
    for p in &mesh.vertices {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for t in &mesh.triangles {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

/// OFF text with shortest round-trip floats.
pub fn to_off_string(mesh: &TriMesh) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 24 * mesh.triangles.len());
    let _ = writeln!(s, "OFF\n{} {} 0", mesh.vertices.len(), mesh.triangles.len());
    for p in &mesh.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for t in &mesh.triangles {
        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
    }
    s
}

/// Binary little-endian PLY: vertex `double x y z`, face `list uchar int vertex_indices`.
pub fn to_ply_bytes(mesh: &TriMesh) -> Vec<u8> {
    ply_bytes(mesh, "slice2solid", None)
}

/// Binary PLY whose faces carry two int properties `label0 label1`: the labels on a triangle's back
/// and front (an interface network between labelled domains; the normal points from `label0` into
/// `label1`). `labels` has one pair per triangle.
pub fn to_labelled_ply_bytes(mesh: &TriMesh, labels: &[[i32; 2]]) -> Vec<u8> {
    assert_eq!(
        labels.len(),
        mesh.triangles.len(),
        "one label pair per triangle"
    );
    ply_bytes(mesh, "slice2solid interface network", Some(labels))
}

/// Binary little-endian PLY with `comment`, and with `labels`, two int face properties.
fn ply_bytes(mesh: &TriMesh, comment: &str, labels: Option<&[[i32; 2]]>) -> Vec<u8> {
    let label_properties = if labels.is_some() {
        "property int label0\nproperty int label1\n"
    } else {
        ""
    };
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment {comment}\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list uchar int vertex_indices\n{label_properties}end_header\n",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    let face_bytes = if labels.is_some() { 21 } else { 13 };
    let mut b = header.into_bytes();
    b.reserve(24 * mesh.vertices.len() + face_bytes * mesh.triangles.len());
    for p in &mesh.vertices {
        for c in p {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    for (k, t) in mesh.triangles.iter().enumerate() {
        b.push(3);
        for &i in t {
            b.extend_from_slice(&(i as i32).to_le_bytes());
        }
        for &x in labels.map_or(&[][..], |l| &l[k][..]) {
            b.extend_from_slice(&x.to_le_bytes());
        }
    }
    b
}

/// Binary STL (coordinates rounded to f32, facet normals computed from the corners).
pub fn to_stl_bytes(mesh: &TriMesh) -> Vec<u8> {
    let mut b = Vec::with_capacity(84 + 50 * mesh.triangles.len());
    let mut header = [b' '; 80];
    let tag = b"binary STL by slice2solid";
    header[..tag.len()].copy_from_slice(tag);
    b.extend_from_slice(&header);
    b.extend_from_slice(&(mesh.triangles.len() as u32).to_le_bytes());
    for t in &mesh.triangles {
        let [p, q, r] = t.map(|i| mesh.vertices[i as usize]);
        let e1 = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let e2 = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let n = if len > 0.0 {
            n.map(|c| c / len)
        } else {
            [0.0; 3]
        };
        for c in n.iter().chain(&p).chain(&q).chain(&r) {
            b.extend_from_slice(&(*c as f32).to_le_bytes());
        }
        b.extend_from_slice(&[0, 0]);
    }
    b
}

/// VTK legacy ASCII unstructured grid of tetrahedra (cell type 10), shortest round-trip floats.
pub fn to_vtk_string(mesh: &TetMesh) -> String {
    to_vtk_string_labelled(mesh, None)
}

/// Legacy VTK as [`to_vtk_string`], with a `label` per tetrahedron as cell data where given.
pub fn to_vtk_string_labelled(mesh: &TetMesh, labels: Option<&[i32]>) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 40 * mesh.tets.len());
    let _ = writeln!(
        s,
        "# vtk DataFile Version 3.0\nslice2solid tetrahedra\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double",
        mesh.vertices.len()
    );
    for p in &mesh.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "CELLS {} {}", mesh.tets.len(), 5 * mesh.tets.len());
    for t in &mesh.tets {
        let _ = writeln!(s, "4 {} {} {} {}", t[0], t[1], t[2], t[3]);
    }
    let _ = writeln!(s, "CELL_TYPES {}", mesh.tets.len());
    for _ in &mesh.tets {
        s.push_str("10\n");
    }
    if let Some(labels) = labels {
        let _ = writeln!(
            s,
            "CELL_DATA {}\nSCALARS label int 1\nLOOKUP_TABLE default",
            labels.len()
        );
        for l in labels {
            let _ = writeln!(s, "{l}");
        }
    }
    s
}

/// MEDIT `.mesh` (double precision, 1-based indices, every vertex and tetrahedron with reference 1).
pub fn to_medit_string(mesh: &TetMesh) -> String {
    to_medit_string_labelled(mesh, None)
}

/// MEDIT as [`to_medit_string`], with each tetrahedron's label as its reference where given.
pub fn to_medit_string_labelled(mesh: &TetMesh, labels: Option<&[i32]>) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 40 * mesh.tets.len());
    let _ = writeln!(
        s,
        "MeshVersionFormatted 2\nDimension 3\nVertices\n{}",
        mesh.vertices.len()
    );
    for p in &mesh.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?} 1", p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "Tetrahedra\n{}", mesh.tets.len());
    for (i, t) in mesh.tets.iter().enumerate() {
        let r = labels.map_or(1, |l| l[i]);
        let _ = writeln!(s, "{} {} {} {} {r}", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
    s.push_str("End\n");
    s
}
