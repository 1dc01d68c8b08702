//! `slice2solid delaunay` end to end: JSON keys, the tets file, errors, and the TetGen oracle switch.
mod common;
use common::{bin, json_of_success};
use slice2solid::delaunay::{gen, xyz};

#[test]
fn delaunay_cli_json_and_tets_file() {
    let dir = tempfile::tempdir().unwrap();
    let pts_path = dir.path().join("p.xyz");
    let mut pts = gen::uniform(200, 5);
    pts.push(pts[0]); // a duplicate
    xyz::write_xyz(&pts_path, &pts).unwrap();
    let tets_path = dir.path().join("t.txt");
    let out = bin()
        .args(["delaunay", pts_path.to_str().unwrap(), "--json", "--tets"])
        .arg(&tets_path)
        .output()
        .unwrap();
    let j = json_of_success(&out);
    assert_eq!(j["points"], 201);
    assert_eq!(j["vertices"], 200);
    let secs = j["seconds"].as_f64().unwrap();
    assert!(secs > 0.0 && secs.is_finite(), "seconds {secs}");
    assert!(j["peak_bytes"].as_u64().unwrap() > 0);
    let text = std::fs::read_to_string(&tets_path).unwrap();
    let tets: Vec<[usize; 4]> = text
        .lines()
        .map(|l| {
            let v: Vec<usize> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect();
    assert_eq!(tets.len() as u64, j["tets"].as_u64().unwrap());
    assert!(tets.iter().flatten().all(|&v| v < 200));
    for t in &tets {
        let p = |k: usize| pts[t[k]];
        assert!(slice2solid::delaunay::pred::orient(p(0), p(1), p(2), p(3)) > 0.0);
    }
}

#[test]
fn delaunay_cli_bad_input_is_an_error_with_a_line() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.xyz");
    std::fs::write(&p, "0 0 0\n1 2\n").unwrap();
    let out = bin()
        .args(["delaunay", p.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.xyz:2"), "{err}");
}

#[test]
fn delaunay_cli_oracle_switch() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("p.xyz");
    xyz::write_xyz(&p, &gen::uniform(100, 6)).unwrap();
    let out = bin()
        .args([
            "delaunay",
            p.to_str().unwrap(),
            "--json",
            "--oracle",
            "tetgen",
        ])
        .output()
        .unwrap();
    if cfg!(feature = "tetgen") {
        assert!(out.status.success());
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let ours = bin()
            .args(["delaunay", p.to_str().unwrap(), "--json"])
            .output()
            .unwrap();
        let o: serde_json::Value = serde_json::from_slice(&ours.stdout).unwrap();
        assert_eq!(j["tets"], o["tets"]);
    } else {
        assert_eq!(out.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&out.stderr).contains("not available"));
    }
}
