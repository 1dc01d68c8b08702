//! `slice2solid delaunay` end to end: JSON keys, the tets file, errors, and the TetGen oracle switch.
mod common;
mod delaunay_check;
use common::{bin, json_of_success};
use slice2solid::delaunay::{gen, xyz};
use std::path::Path;

/// The tetrahedra of a `--tets` file (four vertex indices a line); a malformed line fails.
fn read_tets(path: &Path) -> Vec<[u32; 4]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .map(|l| {
            let v: Vec<u32> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 4, "{}: line {l:?}", path.display());
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

/// `slice2solid delaunay POINTS --json --tets FILE [extra]`: the JSON and the tetrahedra written.
fn run_delaunay(points: &Path, tets: &Path, extra: &[&str]) -> (serde_json::Value, Vec<[u32; 4]>) {
    let out = bin()
        .arg("delaunay")
        .arg(points)
        .args(["--json", "--tets"])
        .arg(tets)
        .args(extra)
        .output()
        .unwrap();
    (json_of_success(&out), read_tets(tets))
}

#[test]
fn delaunay_cli_json_and_tets_file() {
    let dir = tempfile::tempdir().unwrap();
    let pts_path = dir.path().join("p.xyz");
    let mut pts = gen::uniform(200, 5);
    pts.push(pts[0]); // a duplicate
    xyz::write_xyz(&pts_path, &pts).unwrap();
    let (j, tets) = run_delaunay(&pts_path, &dir.path().join("t.txt"), &[]);
    assert_eq!(j["points"], 201);
    assert_eq!(j["vertices"], 200);
    let secs = j["seconds"].as_f64().unwrap();
    assert!(secs > 0.0 && secs.is_finite(), "seconds {secs}");
    assert!(j["peak_bytes"].as_u64().unwrap() > 0);
    assert_eq!(tets.len() as u64, j["tets"].as_u64().unwrap());
    delaunay_check::check_tets(&pts, &tets, true);
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
        // both files through the same exact validator; in general position they are also equal
        let (j, theirs) = run_delaunay(&p, &dir.path().join("tetgen.txt"), &["--oracle", "tetgen"]);
        let (o, ours) = run_delaunay(&p, &dir.path().join("ours.txt"), &[]);
        let pts = xyz::read_xyz(&p).unwrap();
        delaunay_check::check_tets(&pts, &theirs, true);
        delaunay_check::check_tets(&pts, &ours, true);
        assert_eq!(j["tets"], o["tets"]);
        assert_eq!(theirs.len() as u64, j["tets"].as_u64().unwrap());
        // a degenerate set: ties are broken differently, so only the validator decides
        let q = dir.path().join("lattice.xyz");
        let lattice = gen::lattice(5);
        xyz::write_xyz(&q, &lattice).unwrap();
        for (extra, file) in [(&["--oracle", "tetgen"][..], "lt.txt"), (&[][..], "lo.txt")] {
            let (_, tets) = run_delaunay(&q, &dir.path().join(file), extra);
            delaunay_check::check_tets(&lattice, &tets, true);
        }
    } else {
        assert_eq!(out.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&out.stderr).contains("not available"));
    }
}

#[test]
fn delaunay_cli_tets_file_is_the_same_for_every_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let pts_path = dir.path().join("p.xyz");
    // large enough for parallel rounds; exactly coplanar circles and a duplicate
    let mut pts = gen::circles(100, 200);
    pts.push(pts[17]);
    xyz::write_xyz(&pts_path, &pts).unwrap();
    let files: Vec<String> = ["1", "2", "3"]
        .iter()
        .map(|t| {
            let path = dir.path().join(format!("t{t}.txt"));
            let (j, tets) = run_delaunay(&pts_path, &path, &["--threads", t]);
            assert_eq!(j["tets"].as_u64().unwrap() as usize, tets.len());
            std::fs::read_to_string(&path).unwrap()
        })
        .collect();
    assert_eq!(files[0], files[1]);
    assert_eq!(files[0], files[2]);
}
