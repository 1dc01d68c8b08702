//! Mesh file I/O: exact round trips, every reference STL, and malformed files rejected without panics.
mod common;
use common::shared_dir;
use slice2solid::io::mesh::{
    parse_obj, parse_off, parse_ply, parse_stl, read_tetmesh, read_trimesh, to_ply_bytes,
    to_stl_bytes, weld_exact, write_tetmesh, write_trimesh,
};
use slice2solid::slice::check_closed_manifold;
use slice2solid::{Error, TetMesh, TriMesh};
use std::collections::HashMap;
use std::path::PathBuf;

fn reference_stls() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(shared_dir().join("data/reference"))
        .expect("reference meshes")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "stl"))
        .collect();
    v.sort();
    assert!(!v.is_empty());
    v
}

/// Awkward floats: not representable in decimal, tiny, huge, negative zero.
fn awkward_mesh() -> TriMesh {
    TriMesh {
        vertices: vec![
            [0.1, 1.0 / 3.0, -2.0 / 7.0],
            [1e-300, 123456789.12345679, -0.0],
            [std::f64::consts::PI, 1e300, 5e-324],
            [0.0, -1.0, 2.5],
        ],
        triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
    }
}

fn assert_input_error(r: Result<TriMesh, Error>, what: &str) -> String {
    match r {
        Err(e @ Error::Input { .. }) => e.to_string(),
        Err(e) => panic!("{what}: expected an input error, got {e}"),
        Ok(_) => panic!("{what}: accepted"),
    }
}

#[test]
fn text_and_ply_round_trips_are_exact() {
    let dir = tempfile::tempdir().unwrap();
    let real = read_trimesh(&shared_dir().join("data/reference/eight_15.stl")).unwrap();
    for mesh in [awkward_mesh(), real] {
        for ext in ["obj", "off", "ply"] {
            let p = dir.path().join(format!("m.{ext}"));
            write_trimesh(&p, &mesh).unwrap();
            let back = read_trimesh(&p).unwrap();
            assert_eq!(back.triangles, mesh.triangles, "{ext}");
            // Bitwise equality (0.0 == -0.0 numerically; check bits explicitly).
            for (a, b) in back.vertices.iter().zip(&mesh.vertices) {
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "{ext}");
            }
            assert_eq!(back.vertices.len(), mesh.vertices.len());
        }
    }
}

#[test]
fn stl_round_trip_is_exact_for_f32_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.stl");
    for src in reference_stls().into_iter().take(2) {
        let mesh = read_trimesh(&src).unwrap();
        write_trimesh(&p, &mesh).unwrap();
        assert_eq!(read_trimesh(&p).unwrap(), mesh, "{}", src.display());
    }
    // Beyond the f32 range STL cannot store: an error, not a silent infinity.
    let m = awkward_mesh();
    assert!(matches!(write_trimesh(&p, &m), Err(Error::Input { .. })));
    // f64 coordinates come back rounded to f32.
    let mut m = m;
    m.vertices[2][1] = 1e30;
    let back = parse_stl(&to_stl_bytes(&m), "a.stl").unwrap();
    assert_eq!(back.triangles.len(), 4);
    assert_eq!(
        back.vertices[0],
        [
            0.1f32 as f64,
            (1.0f64 / 3.0) as f32 as f64,
            (-2.0f64 / 7.0) as f32 as f64
        ]
    );
}

/// An ASCII STL written here (independently of the library's writer) reads as the binary one does.
#[test]
fn ascii_stl_reads_like_binary() {
    let mesh = read_trimesh(&shared_dir().join("data/reference/eight_15.stl")).unwrap();
    let mut s = String::from("solid eight 15\n");
    for t in &mesh.triangles {
        s.push_str("  facet normal 0 0 0\n    outer loop\n");
        for &v in t {
            let p = mesh.vertices[v as usize];
            // ASCII coordinates are read as f64: print the stored values exactly.
            s.push_str(&format!("      vertex {:e} {:e} {:e}\n", p[0], p[1], p[2]));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid eight 15\n");
    let back = parse_stl(s.as_bytes(), "ascii.stl").unwrap();
    assert_eq!(back, mesh);
    // Truncated: the error names the line of the open loop.
    let cut = &s[..s.len() / 2];
    let cut = &cut[..cut.rfind("vertex").unwrap()];
    let e = assert_input_error(parse_stl(cut.as_bytes(), "ascii.stl"), "truncated ascii");
    assert!(e.contains("ascii.stl:") && e.contains("truncated"), "{e}");
    let bad = s.replacen("vertex", "vertex nan", 1);
    let e = assert_input_error(parse_stl(bad.as_bytes(), "ascii.stl"), "nan");
    assert!(e.starts_with("ascii.stl:4:"), "{e}");
}

#[test]
fn ascii_ply_with_quads_and_vertex_index() {
    let s = "ply\nformat ascii 1.0\ncomment a unit square pyramid\nelement vertex 5\nproperty float x\n\
             property float y\nproperty float z\nproperty uchar red\nelement face 5\n\
             property list uchar uint vertex_index\nend_header\n\
             0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n0.5 0.5 1 5\n\
             4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    let m = parse_ply(s.as_bytes(), "p.ply").unwrap();
    assert_eq!(m.vertices.len(), 5);
    assert_eq!(m.triangles.len(), 6);
    assert_eq!(m.triangles[0], [0, 3, 2]);
    assert_eq!(m.triangles[1], [0, 2, 1]);
    check_closed_manifold(&m).unwrap();
    let e = assert_input_error(
        parse_ply(s.replace("3 3 0 4\n", "3 3 0 9\n").as_bytes(), "p.ply"),
        "index out of range",
    );
    assert!(e.contains("face 4") && e.contains("out of range"), "{e}");
    let e = assert_input_error(
        parse_ply(s.replace("0.5 0.5 1", "0.5 nan 1").as_bytes(), "p.ply"),
        "nan",
    );
    assert!(e.contains("Line 16"), "{e}"); // ply-rs rejects it while parsing, with the line
}

#[test]
fn obj_reads_polygons_and_rejects_bad_indices() {
    let s = "# quad pyramid\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nvn 0 0 1\n\
             f 1//1 4//1 3//1 2//1\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf -2 -5 -1\n";
    let m = parse_obj(s, "p.obj").unwrap();
    assert_eq!(m.triangles.len(), 6);
    assert_eq!(m.triangles[5], [3, 0, 4]);
    check_closed_manifold(&m).unwrap();
    let e = assert_input_error(
        parse_obj(&s.replace("f 3 4 5", "f 3 4 6"), "p.obj"),
        "out of range",
    );
    assert!(e.starts_with("p.obj:12:"), "{e}");
    let e = assert_input_error(
        parse_obj(&s.replace("f 3 4 5", "f 3 4"), "p.obj"),
        "two corners",
    );
    assert!(e.starts_with("p.obj:12:"), "{e}");
    let e = assert_input_error(
        parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "t.off"),
        "off",
    );
    assert!(e.starts_with("t.off:6:"), "{e}");
}

#[test]
fn truncated_or_corrupt_binary_files_are_errors_not_panics() {
    let mesh = awkward_mesh();
    let stl = to_stl_bytes(&mesh);
    for len in 0..stl.len() {
        let r = parse_stl(&stl[..len], "t.stl");
        assert!(matches!(r, Err(Error::Input { .. })), "stl cut at {len}");
    }
    let mut nan = stl.clone();
    nan[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = assert_input_error(parse_stl(&nan, "n.stl"), "nan stl");
    assert!(e.contains("triangle 0") && e.contains("not finite"), "{e}");

    let ply = to_ply_bytes(&mesh);
    for len in 0..ply.len() {
        let r = parse_ply(&ply[..len], "t.ply");
        assert!(matches!(r, Err(Error::Input { .. })), "ply cut at {len}");
    }
    let mut bad = ply.clone();
    let n = bad.len();
    bad[n - 4..].copy_from_slice(&7i32.to_le_bytes());
    let e = assert_input_error(parse_ply(&bad, "b.ply"), "ply index");
    assert!(e.contains("face 3") && e.contains("out of range"), "{e}");
}

#[test]
fn tet_meshes_round_trip_through_vtk_and_medit() {
    let dir = tempfile::tempdir().unwrap();
    let tets = TetMesh {
        vertices: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.1, 1.0 / 3.0, -1e-300],
        ],
        tets: vec![[0, 1, 2, 3], [0, 2, 1, 4]],
    };
    for ext in ["vtk", "mesh"] {
        let p = dir.path().join(format!("t.{ext}"));
        write_tetmesh(&p, &tets).unwrap();
        assert_eq!(read_tetmesh(&p).unwrap(), tets, "{ext}");
        let text = std::fs::read_to_string(&p).unwrap();
        if ext == "vtk" {
            assert!(
                text.contains("DATASET UNSTRUCTURED_GRID")
                    && text.contains("CELL_TYPES 2\n10\n10\n")
            );
        } else {
            assert!(
                text.contains("Tetrahedra\n2\n1 2 3 4 1\n1 3 2 5 1\n") && text.ends_with("End\n")
            );
        }
        // Truncation is an error naming the file.
        std::fs::write(&p, &text[..text.len() * 2 / 3]).unwrap();
        let e = read_tetmesh(&p).unwrap_err().to_string();
        assert!(e.contains(&format!("t.{ext}")), "{e}");
    }
    let bad = TetMesh {
        vertices: vec![[0.0; 3]],
        tets: vec![[0, 0, 0, 1]],
    };
    assert!(write_tetmesh(&dir.path().join("b.vtk"), &bad).is_err());
}

#[test]
fn unknown_extensions_and_missing_files() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.xyz");
    std::fs::write(&p, "1 2 3").unwrap();
    assert!(matches!(read_trimesh(&p), Err(Error::Input { .. })));
    assert!(matches!(
        write_trimesh(&p, &awkward_mesh()),
        Err(Error::Input { .. })
    ));
    assert!(matches!(
        read_trimesh(&dir.path().join("none.stl")),
        Err(Error::Io { .. })
    ));
}

/// Every reference STL welds into a closed mesh: each undirected edge in exactly two triangles.
#[test]
fn reference_stls_weld_into_closed_meshes() {
    for p in reference_stls() {
        let m = read_trimesh(&p).unwrap();
        let mut count: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let bad = count.values().filter(|&&c| c != 2).count();
        let chi = m.vertices.len() as i64 - count.len() as i64 + m.triangles.len() as i64;
        println!(
            "{}: {} vertices, {} triangles, {} edges, Euler characteristic {chi}",
            p.file_name().unwrap().to_string_lossy(),
            m.vertices.len(),
            m.triangles.len(),
            count.len()
        );
        assert_eq!(
            bad,
            0,
            "{}: {bad} edges not in exactly two triangles",
            p.display()
        );
        check_closed_manifold(&m).unwrap();
        // Welding again changes nothing: the reader already shares every repeated position.
        assert_eq!(weld_exact(&m), m);
    }
}

mod fuzz {
    use super::*;
    use proptest::prelude::*;

    fn valid_files() -> Vec<(&'static str, Vec<u8>)> {
        let m = TriMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        };
        let ascii_ply =
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                         property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                         end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        vec![
            ("stl", to_stl_bytes(&m)),
            ("ply", to_ply_bytes(&m)),
            ("ply", ascii_ply.as_bytes().to_vec()),
            ("obj", slice2solid::io::mesh::to_obj_string(&m).into_bytes()),
            ("off", slice2solid::io::mesh::to_off_string(&m).into_bytes()),
        ]
    }

    fn parse(ext: &str, b: &[u8]) {
        let _ = match ext {
            "stl" => parse_stl(b, "f.stl"),
            "ply" => parse_ply(b, "f.ply"),
            "obj" => parse_obj(&String::from_utf8_lossy(b), "f.obj"),
            _ => parse_off(&String::from_utf8_lossy(b), "f.off"),
        };
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        /// Corrupting bytes of valid files never panics (errors are fine).
        #[test]
        fn corrupted_files_never_panic(which in 0usize..5, edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..6), cut in any::<usize>()) {
            let files = valid_files();
            let (ext, mut b) = files[which].clone();
            for (pos, byte) in edits {
                let n = b.len();
                b[pos % n] = byte;
            }
            let keep = if cut % 3 == 0 { cut % (b.len() + 1) } else { b.len() };
            parse(ext, &b[..keep]);
        }

        #[test]
        fn random_bytes_never_panic(which in 0usize..5, b in proptest::collection::vec(any::<u8>(), 0..400)) {
            parse(valid_files()[which].0, &b);
        }
    }
}
