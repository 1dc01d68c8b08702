//! The `slice` command end to end: errors name the file; written sections load back with the same areas.
mod common;
use common::{bin, shared_dir};
use slice2solid::io::mesh::{read_trimesh, write_trimesh};
use slice2solid::slice::{make_planes, slice_mesh, SliceMode};

#[test]
fn open_mesh_is_rejected_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = read_trimesh(&shared_dir().join("data/reference/eight_15.stl")).unwrap();
    mesh.triangles.truncate(mesh.triangles.len() - 3);
    let input = dir.path().join("open.obj");
    write_trimesh(&input, &mesh).unwrap();
    let out = bin()
        .arg("slice")
        .arg(&input)
        .arg("-o")
        .arg(dir.path().join("o.csl"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("open.obj") && err.contains("not closed"),
        "{err}"
    );
}

#[test]
fn sliced_reference_meshes_load_back_with_the_same_areas() {
    let dir = tempfile::tempdir().unwrap();
    for (name, mode, mode_arg) in [
        ("eight_15", SliceMode::Axes, "axes"),
        ("hand", SliceMode::Random, "random"),
        ("Elephant", SliceMode::Parallel, "parallel"),
        ("balloondog_box", SliceMode::Random, "random"),
    ] {
        let input = shared_dir().join(format!("data/reference/{name}.stl"));
        for ext in ["csl", "json"] {
            let output = dir.path().join(format!("{name}.{ext}"));
            let out = bin()
                .args([
                    "slice",
                    input.to_str().unwrap(),
                    "-o",
                    output.to_str().unwrap(),
                ])
                .args(["--planes", "8", "--seed", "3", "--mode", mode_arg])
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{name}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            let mesh = read_trimesh(&input).unwrap();
            let expect = slice_mesh(&mesh, &make_planes(&mesh, 8, 3, mode)).unwrap();
            let back = slice2solid::io::read_sections(&output)
                .unwrap_or_else(|e| panic!("{name}.{ext} does not load back: {e}"));
            assert_eq!(back.sections.len(), expect.sections.len(), "{name}.{ext}");
            for (a, b) in back.sections.iter().zip(&expect.sections) {
                assert_eq!(a.regions.len(), b.regions.len(), "{name}.{ext}");
                let holes = |s: &slice2solid::Section| -> usize {
                    s.regions.iter().map(|r| r.holes.len()).sum()
                };
                assert_eq!(holes(a), holes(b), "{name}.{ext}");
                let rel = (a.area() - b.area()).abs() / b.area();
                assert!(
                    rel < 1e-9,
                    "{name}.{ext}: area {} vs {}",
                    a.area(),
                    b.area()
                );
            }
            println!(
                "{name}.{ext}: {} sections, {} vertices",
                back.sections.len(),
                back.vertex_count()
            );
        }
    }
}
