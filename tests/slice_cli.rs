//! The `slice` command end to end: errors name the file; written sections load back with the same areas;
//! the acquisition modes (fan, sweep, tilt) write files that `info` accepts.
mod common;
use common::{bin, json_of_success, shared_dir};
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

/// Fan, sweep and tilt at 16 planes (seed 5, as `../shared/eval/stress.sh` uses) through the CLI: the
/// CSL loads back with as many non-empty sections as the library makes (pinned: hand's first and
/// last tilt planes only graze its box), and `info` reads it without a repair.
#[test]
fn acquisition_modes_write_csl_that_info_accepts() {
    let dir = tempfile::tempdir().unwrap();
    for (name, mode, mode_arg, non_empty) in [
        ("hand", SliceMode::Fan, "fan", 16),
        ("eight_15", SliceMode::Fan, "fan", 16),
        ("hand", SliceMode::Sweep, "sweep", 16),
        ("eight_15", SliceMode::Sweep, "sweep", 16),
        ("hand", SliceMode::Tilt, "tilt", 14),
        ("eight_15", SliceMode::Tilt, "tilt", 16),
    ] {
        let case = format!("{name} {mode_arg}");
        let input = shared_dir().join(format!("data/reference/{name}.stl"));
        let mesh = read_trimesh(&input).unwrap_or_else(|e| panic!("{case}: {e}"));
        let output = dir.path().join(format!("{name}_{mode_arg}.csl"));
        let out = bin()
            .arg("slice")
            .arg(&input)
            .arg("-o")
            .arg(&output)
            .args(["--planes", "16", "--seed", "5", "--mode", mode_arg])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{case}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let planes = make_planes(&mesh, 16, 5, mode);
        assert_eq!(planes.len(), 16, "{case}");
        let expect = slice_mesh(&mesh, &planes).unwrap();
        let back = slice2solid::io::read_sections(&output)
            .unwrap_or_else(|e| panic!("{case}: the CSL does not load back: {e}"));
        assert_eq!(back.sections.len(), non_empty, "{case}: non-empty sections");
        assert_eq!(expect.sections.len(), non_empty, "{case}: library sections");
        assert!(back.warnings.is_empty(), "{case}: {:?}", back.warnings);
        assert!(
            back.sections.iter().all(|s| !s.regions.is_empty()),
            "{case}"
        );
        let info = json_of_success(
            &bin()
                .arg("info")
                .arg(&output)
                .arg("--json")
                .output()
                .unwrap(),
        );
        assert_eq!(info["planes"], non_empty, "{case}: {info}");
        assert_eq!(info["empty_planes"], 0, "{case}: {info}");
        assert_eq!(info["warnings"], serde_json::json!([]), "{case}: {info}");
    }
}
