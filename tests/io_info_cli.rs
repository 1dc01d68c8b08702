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

/// A reader that stops early (`slice2solid check ... | head -1`) must not make us panic: the process
/// ends on SIGPIPE like other tools (it used to panic inside println!, exit code 101). The mesh has
/// 3000 separate tetrahedra, so the component table is far larger than a pipe's buffer.
#[cfg(unix)]
#[test]
fn closed_stdout_is_not_a_panic() {
    use std::io::{Read, Write};
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tets.obj");
    let mut obj = std::fs::File::create(&path).unwrap();
    for k in 0..3000 {
        let x = 3.0 * k as f64;
        for p in [
            [x, 0.0, 0.0],
            [x + 1.0, 0.0, 0.0],
            [x, 1.0, 0.0],
            [x, 0.0, 1.0],
        ] {
            writeln!(obj, "v {} {} {}", p[0], p[1], p[2]).unwrap();
        }
        let b = 4 * k + 1;
        for t in [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]] {
            writeln!(obj, "f {} {} {}", b + t[0], b + t[1], b + t[2]).unwrap();
        }
    }
    drop(obj);
    let mut child = bin()
        .arg("check")
        .arg(&path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // read one byte, then close the pipe long before the output is complete
    let mut out = child.stdout.take().unwrap();
    let mut one = [0u8; 1];
    out.read_exact(&mut one).unwrap();
    drop(out);
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let status = child.wait().unwrap();
    assert!(!err.contains("panicked"), "{err}");
    assert_ne!(status.code(), Some(101), "{err}");
}
