//! `slice2solid reconstruct --label`: one material of a multi-label input (`data/two_labels.json`:
//! a box of label 1 and a box of label 2 side by side, cut by the same two planes).
mod common;
use common::bin;
use slice2solid::eval::check::check_mesh;
use slice2solid::io::mesh::read_trimesh;

const INPUT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/two_labels.json");

/// (components, volume, x range) of the surface `reconstruct` writes with `args`.
fn run(args: &[&str]) -> (usize, f64, [f64; 2]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.obj");
    let o = bin()
        .args(["reconstruct", INPUT, "-o", out.to_str().unwrap(), "-q"])
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mesh = read_trimesh(&out).unwrap();
    let c = check_mesh(&mesh, None);
    assert!(c.closed && c.manifold && c.oriented, "{args:?}");
    let xs = mesh.vertices.iter().map(|p| p[0]);
    let range = [
        xs.clone().fold(f64::INFINITY, f64::min),
        xs.fold(f64::NEG_INFINITY, f64::max),
    ];
    (c.components, c.volume, range)
}

#[test]
fn every_material_by_default_one_with_label() {
    let (n, v, x) = run(&[]);
    assert_eq!(n, 2);
    assert!((v - 8.0).abs() < 1e-12, "{v}");
    assert_eq!(x, [0.0, 5.0]);
    let (n, v, x) = run(&["--label", "1"]);
    assert_eq!(n, 1);
    assert!((v - 4.0).abs() < 1e-12, "{v}");
    assert_eq!(x, [0.0, 2.0]);
    let (n, v, x) = run(&["--label", "2"]);
    assert_eq!(n, 1);
    assert!((v - 4.0).abs() < 1e-12, "{v}");
    assert_eq!(x, [3.0, 5.0]);
}

#[test]
fn a_label_absent_from_the_input_is_an_error_naming_the_labels_present() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.obj");
    let o = bin()
        .args([
            "reconstruct",
            INPUT,
            "-o",
            out.to_str().unwrap(),
            "--label",
            "3",
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--label 3"), "{err}");
    assert!(err.contains("labels present: 1, 2"), "{err}");
    assert!(!out.exists(), "no surface is written");
}
