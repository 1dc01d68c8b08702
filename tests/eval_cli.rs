//! The `check` and `compare` subcommands: JSON keys, exit status.
mod common;
use common::{bin, json_of_success, shared_dir};
use slice2solid::eval::shapes::{icosphere, translated, unit_cube};
use slice2solid::io::mesh::write_trimesh;

#[test]
fn check_json_and_exit_status() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("cube.obj");
    write_trimesh(&good, &unit_cube()).unwrap();
    let out = bin().args(["check", "--json"]).arg(&good).output().unwrap();
    let j = json_of_success(&out);
    for key in [
        "closed",
        "manifold",
        "oriented",
        "self_intersections",
        "overlapping_coplanar_pairs",
        "near_coplanar_tolerance",
        "self_intersection_free",
        "components",
        "euler",
        "genus",
        "volume",
        "area",
    ] {
        assert!(j.get(key).is_some(), "missing {key}");
    }
    assert_eq!(j["closed"], true);
    assert_eq!(j["self_intersection_free"], true);
    assert!(j.get("sections").is_none() && j.get("worst_section").is_none());
    assert_eq!(j["genus"], 0);
    assert!((j["volume"].as_f64().unwrap() - 1.0).abs() < 1e-9);

    // a hole: not closed, exit status 1 (table output)
    let mut holed = icosphere([0.0; 3], 1.0, 2);
    holed.triangles.pop();
    let bad = dir.path().join("holed.obj");
    write_trimesh(&bad, &holed).unwrap();
    let out = bin().arg("check").arg(&bad).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("NOT a closed manifold"));

    // a missing file: an error, exit status 2
    let out = bin()
        .arg("check")
        .arg(dir.path().join("none.obj"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn compare_json() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.obj");
    let b = dir.path().join("b.stl");
    write_trimesh(&a, &unit_cube()).unwrap();
    write_trimesh(&b, &translated(&unit_cube(), [0.1, 0.0, 0.0])).unwrap();
    let out = bin()
        .args(["compare", "--json", "--samples", "2000", "--seed", "5"])
        .arg(&a)
        .arg(&b)
        .output()
        .unwrap();
    let j = json_of_success(&out);
    for key in ["iou", "chamfer_l1", "chamfer_l2", "hausdorff", "samples"] {
        assert!(j.get(key).is_some(), "missing {key}");
    }
    assert_eq!(j["samples"], 2000);
    // STL stores f32: the shift 0.1 is rounded, hence the tolerance
    assert!((j["iou"].as_f64().unwrap() - 0.9 / 1.1).abs() < 1e-6);
}

#[test]
fn check_with_sections_json() {
    let data = shared_dir().join("data");
    let out = bin()
        .args(["check", "--json", "--sections"])
        .arg(data.join("csl/eight_15.csl"))
        .arg(data.join("reference/eight_15.stl"))
        .output()
        .unwrap();
    let j = json_of_success(&out);
    let planes = j["sections"].as_array().unwrap();
    assert_eq!(planes.len(), 15);
    for p in planes {
        for key in [
            "plane",
            "source_index",
            "area_input",
            "area_mesh",
            "sym_diff",
            "relative",
        ] {
            assert!(p.get(key).is_some(), "missing {key}");
        }
        assert!(p["relative"].as_f64().unwrap() < 0.01);
    }
    assert!(j["worst_section"]["source_index"].is_u64());
    assert_eq!(j["genus"], 2);
}
