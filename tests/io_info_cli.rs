//! `slice2solid info` on a shipped example and on a broken file.
mod common;
use common::bin;

fn info(args: &[&str]) -> (bool, String, String) {
    let out = bin().arg("info").args(args).output().unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn info_json_counts_the_example() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/two_squares.json");
    let (ok, out, err) = info(&[path, "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["planes"], 2);
    assert_eq!(v["vertices"], 12);
    assert_eq!(v["contours"], 3);
    assert_eq!(v["holes"], 1);
    assert_eq!(v["bounding_box"]["max"], serde_json::json!([4.0, 4.0, 2.0]));
    // Two parallel planes cut the padded box into 3 cells, all touching a section.
    let (ok, out, err) = info(&[path, "--json", "--cells"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["arrangement"]["cells"], 3);
    assert_eq!(v["arrangement"]["cells_with_sections"], 3);
    let (ok, out, _) = info(&[path]);
    assert!(
        ok && out.contains("contours:       3 (2 outer, 1 holes)"),
        "{out}"
    );
}

#[test]
fn info_reports_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.csl");
    std::fs::write(&p, "CSLC\n1 1\n1 3 1 0 0 1 0\n0 0 0\n1 0 0\n").unwrap();
    let (ok, _, err) = info(&[p.to_str().unwrap()]);
    assert!(!ok);
    assert!(
        err.contains("bad.csl:5: plane 1") && err.contains("end of file"),
        "{err}"
    );
}
