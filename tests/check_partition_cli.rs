//! `check --partition` on synthetic partitions with known answers (valid with the interface area of
//! the truth, overlapping refused naming the labels and the place, a gap found with sections), and
//! multi-label `slice MESH:LABEL ...` on the command line.
mod common;
use common::{bin, json_of_success};
use slice2solid::eval::shapes::{grid_box, translated};
use slice2solid::io::mesh::write_trimesh;
use slice2solid::slice::synthetic::{nested_spheres, stacked_cylinder, touching_boxes};
use slice2solid::TriMesh;
use std::path::{Path, PathBuf};

/// Write `domains` as `dir/name.labelL.obj`; the paths in order.
fn write_domains(dir: &Path, name: &str, domains: &[(i32, TriMesh)]) -> Vec<PathBuf> {
    domains
        .iter()
        .map(|(l, m)| {
            let p = dir.join(format!("{name}.label{l}.obj"));
            write_trimesh(&p, m).unwrap();
            p
        })
        .collect()
}

/// `check --partition PATHS... [--sections S] --json`: exit code and report.
fn check(paths: &[PathBuf], sections: Option<&Path>) -> (i32, serde_json::Value) {
    let mut cmd = bin();
    cmd.arg("check").arg("--partition").args(paths);
    if let Some(s) = sections {
        cmd.arg("--sections").arg(s);
    }
    let out = cmd.arg("--json").output().unwrap();
    let code = out.status.code().unwrap();
    assert!(
        code == 0 || code == 1,
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (code, serde_json::from_slice(&out.stdout).unwrap())
}

fn pair(r: &serde_json::Value, a: i64, b: i64) -> &serde_json::Value {
    r["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["labels"][0] == a && p["labels"][1] == b)
        .unwrap()
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn boxes_touching_on_a_face_are_a_partition_with_the_face_as_interface() {
    let dir = tempfile::tempdir().unwrap();
    let paths = write_domains(dir.path(), "boxes", &touching_boxes(true).domains);
    let (code, r) = check(&paths, None);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["valid"], true);
    let p = pair(&r, 1, 2);
    assert_eq!(p["interface_triangles"], 16);
    assert!((f(&p["interface_area"]) - 2.0).abs() < 1e-14, "{p}");
    assert_eq!(p["crossings"], 0);
    assert_eq!(p["vertices_inside"], serde_json::json!([0, 0]));
    for d in r["domains"].as_array().unwrap() {
        assert_eq!(d["valid"], true, "{d}");
    }
}

#[test]
fn overlapping_boxes_are_refused_naming_the_labels_and_the_place() {
    let dir = tempfile::tempdir().unwrap();
    let a = grid_box([0.0; 3], [1.0; 3], [2, 2, 2]);
    let b = grid_box([0.5, 0.3, -0.2], [2.0, 1.4, 0.8], [3, 2, 2]);
    let paths = write_domains(dir.path(), "overlap", &[(1, a), (2, b)]);
    let (code, r) = check(&paths, None);
    assert_eq!(code, 1);
    assert_eq!(r["valid"], false);
    let p = pair(&r, 1, 2);
    assert_eq!(p["disjoint"], false);
    assert_eq!(p["interface_triangles"], 0);
    // A's boundary inside B meets B's boundary inside A along the overlap's edges.
    assert!(p["crossings"].as_u64().unwrap() > 0, "{p}");
    let at: Vec<f64> = p["crossing_at"].as_array().unwrap().iter().map(f).collect();
    assert!(at.iter().all(|x| (-0.2..=2.0).contains(x)), "{at:?}");
    // A's grid vertices strictly inside B: (1, 0.5|1, 0|0.5); B's inside A: (0.5, 0.3|0.85, 0.3|0.8).
    assert_eq!(p["vertices_inside"], serde_json::json!([4, 4]), "{p}");
    // The human report says which labels and where.
    let out = bin()
        .arg("check")
        .arg("--partition")
        .args(&paths)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("labels 1-2") && text.contains("OVERLAP"),
        "{text}"
    );
    assert!(text.contains("NOT a partition"), "{text}");
}

#[test]
fn nested_core_and_shell_are_a_partition_with_the_core_surface_as_interface() {
    let dir = tempfile::tempdir().unwrap();
    let case = nested_spheres();
    let core_area: f64 = {
        let m = &case.domains[0].1;
        m.triangles
            .iter()
            .map(|t| {
                let p = t.map(|i| m.vertices[i as usize]);
                let (u, v) = (
                    slice2solid::sections::sub(p[1], p[0]),
                    slice2solid::sections::sub(p[2], p[0]),
                );
                let c = slice2solid::sections::cross(u, v);
                0.5 * slice2solid::sections::dot(c, c).sqrt()
            })
            .sum()
    };
    let paths = write_domains(dir.path(), "spheres", &case.domains);
    let (code, r) = check(&paths, None);
    assert_eq!(code, 0, "{r:#}");
    let p = pair(&r, 1, 2);
    assert_eq!(p["interface_triangles"], 320);
    assert!((f(&p["interface_area"]) - core_area).abs() < 1e-13 * core_area);
    assert!((core_area - 3.0).abs() < 0.1, "{core_area}"); // 4π 0.5² = 3.14 for the sphere
                                                           // The shell has two components (outer sphere, inner cavity) and the volume of the difference.
    let shell = &r["domains"][1]["check"];
    assert_eq!(shell["components"], 2);
}

#[test]
fn stacked_cylinder_layers_touch_only_their_neighbours() {
    let dir = tempfile::tempdir().unwrap();
    let paths = write_domains(dir.path(), "cyl", &stacked_cylinder().domains);
    let (code, r) = check(&paths, None);
    assert_eq!(code, 0, "{r:#}");
    let cap = 0.5 * 24.0 * (std::f64::consts::TAU / 24.0).sin() * 1.5 * 1.5;
    for (a, b, area) in [(1, 2, cap), (2, 3, cap), (1, 3, 0.0)] {
        let p = pair(&r, a, b);
        assert!(
            (f(&p["interface_area"]) - area).abs() < 1e-13,
            "{a}-{b}: {p}"
        );
        assert_eq!(p["disjoint"], true);
    }
}

/// Slice the touching boxes on the command line (`MESH:LABEL`), then check the truth's domains and a
/// gapped pair against the sections.
#[test]
fn sliced_boxes_agree_with_their_domains_and_a_gap_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let case = touching_boxes(true);
    let paths = write_domains(d, "boxes", &case.domains);
    let csl = d.join("boxes.csl");
    let out = bin()
        .arg("slice")
        .arg(format!("{}:1", paths[0].display()))
        .arg(format!("{}:2", paths[1].display()))
        .args(["--mode", "fan", "--planes", "6", "-o"])
        .arg(&csl)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("label 1:") && text.contains("label 2:"),
        "{text}"
    );
    // The plane of the fan nearly parallel to the face y = 1 misses it.
    assert!(text.contains("5 touching pairs"), "{text}");
    let info = json_of_success(&bin().arg("info").arg(&csl).arg("--json").output().unwrap());
    assert_eq!(info["planes"], 6, "{info}");

    let (code, r) = check(&paths, Some(&csl));
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["gaps"], 0);
    assert_eq!(pair(&r, 1, 2)["section_contact_planes"], 5);
    for dom in r["domains"].as_array().unwrap() {
        let worst = f(&dom["check"]["worst_section"]["relative"]);
        // 8.9e-12 and 2.7e-11 measured, the same as for each box sliced alone (the resolution of
        // the single-label section agreement on these planes)
        assert!(worst < 5e-11, "label {}: {worst}", dom["label"]);
    }

    // Box B moved 0.01 away: still disjoint (valid), but the sections say they touch: a gap, and B's
    // sections disagree.
    let gapped = translated(&case.domains[1].1, [0.0, 0.01, 0.0]);
    let b = d.join("gap.label2.obj");
    write_trimesh(&b, &gapped).unwrap();
    let (code, r) = check(&[paths[0].clone(), b], Some(&csl));
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["gaps"], 1);
    let p = pair(&r, 1, 2);
    assert_eq!(p["gap"], true);
    assert_eq!(p["interface_triangles"], 0);
    let worst = f(&r["domains"][1]["check"]["worst_section"]["relative"]);
    assert!(worst > 1e-3, "{worst}");
}

#[test]
fn partition_needs_two_distinct_labels() {
    let dir = tempfile::tempdir().unwrap();
    let paths = write_domains(dir.path(), "boxes", &touching_boxes(true).domains);
    let out = bin()
        .args(["check", "--partition"])
        .arg(&paths[0])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("at least two"));
    let out = bin()
        .args(["check", "--partition"])
        .arg(format!("{}:1", paths[0].display()))
        .arg(format!("{}:1", paths[1].display()))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("also the label"));
}
