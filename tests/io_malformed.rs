//! Every kind of malformed input is rejected with a message naming the line (CSL) or JSON path and
//! the reason; random mutations of a real file never panic.
mod common;
use proptest::prelude::*;
use slice2solid::io::csl::{parse_csl, parse_csl_with};
use slice2solid::io::json::{parse_json, parse_json_with};
use slice2solid::io::ReadOptions;

/// Two 4x4 squares on z = 0 (lines 4-10) and z = 1 (lines 11-16).
const BASE: &str = "CSLC
2 1

1 4 1 0 0 1 0

0 0 0
4 0 0
4 4 0
0 4 0
4 1 0 1 2 3
2 4 1 0 0 1 -1
0 0 1
4 0 1
4 4 1
0 4 1
4 1 0 1 2 3
";

/// Plane 2 (line 11) with eight vertices (lines 12-19) and two components (lines 20, 21).
fn with_plane2(vertices: &str, components: &str) -> String {
    let head: Vec<&str> = BASE.lines().take(10).collect();
    let n = vertices.lines().count();
    let c = components.lines().count();
    format!(
        "{}\n2 {n} {c} 0 0 1 -1\n{vertices}\n{components}\n",
        head.join("\n")
    )
}

fn csl_error(text: &str) -> String {
    match parse_csl(text, "t.csl") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn expect(msg: &str, location: &str, reason: &str) {
    assert!(
        msg.starts_with(location),
        "location: expected `{location}` in `{msg}`"
    );
    assert!(
        msg.contains(reason),
        "reason: expected `{reason}` in `{msg}`"
    );
}

#[test]
fn base_is_valid() {
    let s = parse_csl(BASE, "t.csl").unwrap();
    assert_eq!(s.sections.len(), 2);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}

#[test]
fn csl_truncated() {
    let text: String = BASE.lines().take(13).map(|l| format!("{l}\n")).collect();
    expect(&csl_error(&text), "t.csl:13: plane 2", "end of file");
    expect(
        &csl_error("CSLC\n3 1\n"),
        "t.csl:2",
        "end of file: 3 plane(s) declared, 0 found",
    );
    expect(&csl_error(""), "t.csl:1", "empty file");
    expect(&csl_error("CSL\n"), "t.csl:1", "expected header `CSLC`");
}

#[test]
fn csl_index_out_of_range() {
    let text = BASE.replacen("4 1 0 1 2 3", "4 1 0 1 2 7", 1);
    expect(
        &csl_error(&text),
        "t.csl:10: plane 1, component 0",
        "vertex index 7 out of range",
    );
    let text = BASE.replacen("4 1 0 1 2 3", "4h3 1 0 1 2 3", 1);
    expect(
        &csl_error(&text),
        "t.csl:10: plane 1, component 0",
        "hole parent 3 is not another component",
    );
}

#[test]
fn csl_not_finite() {
    for bad in ["nan", "inf", "-inf", "1e400"] {
        let text = BASE.replacen("4 0 0", &format!("4 {bad} 0"), 1);
        expect(&csl_error(&text), "t.csl:7: plane 1", "not a finite number");
    }
    let text = BASE.replacen("4 0 0", "4 zero 0", 1);
    expect(
        &csl_error(&text),
        "t.csl:7: plane 1",
        "expected a number for y, found `zero`",
    );
}

#[test]
fn csl_zero_normal() {
    let text = BASE.replacen("2 4 1 0 0 1 -1", "2 4 1 0 0 0 -1", 1);
    expect(
        &csl_error(&text),
        "t.csl:11: plane 2",
        "normal (a, b, c) is zero",
    );
}

#[test]
fn csl_fewer_than_three_vertices() {
    let text = format!("{}2 1 0 1\n", BASE.strip_suffix("4 1 0 1 2 3\n").unwrap());
    expect(
        &csl_error(&text),
        "t.csl:16: plane 2, component 0",
        "2 distinct vertices, at least 3",
    );
    // Repeated vertices do not count.
    let text = format!(
        "{}4 1 0 1 1 0\n",
        BASE.strip_suffix("4 1 0 1 2 3\n").unwrap()
    );
    expect(
        &csl_error(&text),
        "t.csl:16: plane 2, component 0",
        "at least 3",
    );
}

#[test]
fn csl_self_intersecting() {
    // Refused in strict mode; repaired by default (tests/io_repair.rs).
    let text = BASE.replacen("4 1 0 1 2 3", "4 1 0 2 1 3", 1);
    let e = parse_csl_with(&text, "t.csl", &ReadOptions { strict: true })
        .unwrap_err()
        .to_string();
    expect(
        &e,
        "t.csl:10: plane 1, component 0",
        "self-intersecting contour",
    );
    let s = parse_csl(&text, "t.csl").unwrap();
    assert_eq!(s.sections[0].regions.len(), 2);
}

#[test]
fn csl_hole_outside_parent() {
    let text = with_plane2(
        "0 0 1\n4 0 1\n4 4 1\n0 4 1\n5 5 1\n5 6 1\n6 6 1\n6 5 1",
        "4 1 0 1 2 3\n4h0 1 4 5 6 7",
    );
    expect(
        &csl_error(&text),
        "t.csl:21: plane 2, component 1",
        "hole is not inside its parent t.csl:20: plane 2, component 0",
    );
    // The same hole inside its parent is fine.
    let ok = with_plane2(
        "0 0 1\n4 0 1\n4 4 1\n0 4 1\n1 1 1\n1 2 1\n2 2 1\n2 1 1",
        "4 1 0 1 2 3\n4h0 1 4 5 6 7",
    );
    let s = parse_csl(&ok, "t.csl").unwrap();
    assert_eq!(s.sections[1].regions[0].holes.len(), 1);
}

#[test]
fn csl_crossing_contours() {
    let text = with_plane2(
        "0 0 1\n4 0 1\n4 4 1\n0 4 1\n2 2 1\n6 2 1\n6 6 1\n2 6 1",
        "4 1 0 1 2 3\n4 1 4 5 6 7",
    );
    // Same label: refused in strict mode, merged by default (tests/io_repair.rs).
    let e = parse_csl_with(&text, "t.csl", &ReadOptions { strict: true })
        .unwrap_err()
        .to_string();
    expect(
        &e,
        "t.csl:20: plane 2, component 0",
        "contours of one plane cross",
    );
    assert!(e.contains("t.csl:21: plane 2, component 1"));
    assert_eq!(
        parse_csl(&text, "t.csl").unwrap().sections[1].regions.len(),
        1
    );
    // Different labels: refused in strict mode; by default the lower label keeps the overlap
    // (tests/io_repair.rs).
    let text = text.replace("4 1 4 5 6 7", "4 2 4 5 6 7");
    expect(
        &parse_csl_with(&text, "t.csl", &ReadOptions { strict: true })
            .unwrap_err()
            .to_string(),
        "t.csl:20: plane 2, component 0",
        "contours of one plane cross",
    );
    let s = parse_csl(&text, "t.csl").unwrap();
    let areas: Vec<(i32, f64)> = s.sections[1]
        .regions
        .iter()
        .map(|r| (r.label, r.area()))
        .collect();
    assert_eq!(areas, vec![(1, 16.0), (2, 12.0)]);
}

#[test]
fn csl_duplicate_planes() {
    let text = BASE
        .replacen("2 4 1 0 0 1 -1", "2 4 1 0 0 -2 0", 1)
        .replace(" 1\n", " 0\n");
    expect(
        &csl_error(&text),
        "t.csl:11: plane 2",
        "duplicate plane: same plane as t.csl:4: plane 1",
    );
}

#[test]
fn csl_vertex_off_plane() {
    let text = BASE.replacen("4 0 1", "4 0 1.5", 1);
    expect(
        &csl_error(&text),
        "t.csl:13: plane 2",
        "vertex 1 is 5.000e-1 off its plane",
    );
}

#[test]
fn csl_accepts_real_file_quirks() {
    // Leading spaces, blank lines, an empty plane, labels above 1, a hole with another label.
    let text = "CSLC\n  3 5\n\n\n  1 0 0 0 0 1 2\n\n 2 8 2 0 0 1 -1\n 0 0 1\n 4 0 1\n 4 4 1\n 0 4 1\n 1 1 1\n 1 2 1\n 2 2 1\n 2 1 1\n\n 4 3 0 1 2 3\n 4h0 2 4 7 6 5\n3 3 1 0 0 1 -2\n0 0 2\n1 0 2\n0 1 2\n3 4 0 1 2\n";
    let s = parse_csl(text, "q.csl").unwrap();
    assert_eq!(s.sections.len(), 3);
    assert!(s.sections[0].regions.is_empty());
    assert_eq!(s.sections[1].regions[0].label, 3);
    assert_eq!(s.n_labels, 5);
    assert_eq!(s.sections[2].regions[0].label, 4);
}

fn json_error(text: &str) -> String {
    match parse_json(text, "t.json") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn json_doc(planes: &str) -> String {
    format!("{{\"planes\": [{planes}]}}")
}
const SQ0: &str = r#"{"point": [0,0,0], "normal": [0,0,1], "contours": [{"points": [[0,0,0],[4,0,0],[4,4,0],[0,4,0]]}]}"#;

#[test]
fn json_malformed() {
    expect(
        &json_error(&json_doc(SQ0)[..30]),
        "t.json:1:30",
        "invalid JSON",
    );
    let p = |c: &str| {
        json_doc(&format!(
            r#"{SQ0}, {{"point": [0,0,1], "normal": [0,0,1], "contours": [{c}]}}"#
        ))
    };
    expect(
        &json_error(&p(r#"{"points": [[0,0,1],[4,0,1],[4,4,1]], "hole_of": 3}"#)),
        "t.json: $.planes[1].contours[0].hole_of",
        "3 is not another contour",
    );
    expect(
        &json_error(&json_doc(r#"{"point": [0,0,0], "normal": [0,0,0]}"#)),
        "t.json: $.planes[0].normal",
        "normal is zero",
    );
    expect(
        &json_error(&p(r#"{"points": [[0,0,1],[4,0,1]]}"#)),
        "t.json: $.planes[1].contours[0]",
        "at least 3",
    );
    // Refused in strict mode; repaired by default (tests/io_repair.rs).
    let bow_tie = p(r#"{"points": [[0,0,1],[4,4,1],[4,0,1],[0,4,1]]}"#);
    expect(
        &parse_json_with(&bow_tie, "t.json", &ReadOptions { strict: true })
            .unwrap_err()
            .to_string(),
        "t.json: $.planes[1].contours[0]",
        "self-intersecting",
    );
    let s = parse_json(&bow_tie, "t.json").unwrap();
    assert_eq!(s.sections[1].regions.len(), 2);
    assert!(s.warnings[0].starts_with("t.json: $.planes[1].contours[0]: repaired"));
    expect(
        &json_error(&p(
            r#"{"points": [[0,0,1],[4,0,1],[4,4,1],[0,4,1]]}, {"points": [[5,5,1],[5,6,1],[6,6,1]], "hole_of": 0}"#,
        )),
        "t.json: $.planes[1].contours[1]",
        "hole is not inside its parent t.json: $.planes[1].contours[0]",
    );
    // Different labels overlapping: refused in strict mode, resolved by default.
    let overlap = p(
        r#"{"points": [[0,0,1],[4,0,1],[4,4,1],[0,4,1]]}, {"points": [[2,2,1],[6,2,1],[6,6,1]], "label": 2}"#,
    );
    expect(
        &parse_json_with(&overlap, "t.json", &ReadOptions { strict: true })
            .unwrap_err()
            .to_string(),
        "t.json: $.planes[1].contours[0]",
        "contours of one plane cross",
    );
    let s = parse_json(&overlap, "t.json").unwrap();
    assert!(
        s.warnings[0].starts_with("t.json: $.planes[1].contours[0] (label 1) and t.json: $.planes[1].contours[1] (label 2): repaired overlapping"),
        "{:?}",
        s.warnings
    );
    expect(
        &json_error(&json_doc(&format!("{SQ0}, {SQ0}"))),
        "t.json: $.planes[1]",
        "duplicate plane: same plane as t.json: $.planes[0]",
    );
    expect(
        &json_error(&p(r#"{"points": [[0,0,1],[4,0,1.5],[4,4,1]]}"#)),
        "t.json: $.planes[1].contours[0].points[1]",
        "off its plane",
    );
    expect(
        &json_error(&p(r#"{"points": [[0,0,1],[4,0,"x"],[4,4,1]]}"#)),
        "t.json: $.planes[1].contours[0].points[1][2]",
        "expected a number",
    );
    expect(
        &json_error(&p(r#"{"points": [[0,0,1],[4,0,1],[4,4,1]], "lable": 2}"#)),
        "t.json: $.planes[1].contours[0]",
        "unknown key \"lable\"",
    );
    // JSON has no NaN; numbers too large to be finite are syntax errors of serde_json.
    expect(
        &json_error(&p(r#"{"points": [[0,0,1],[4,0,1e400],[4,4,1]]}"#)),
        "t.json:1:",
        "invalid JSON",
    );
}

#[test]
fn shipped_json_example_loads() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/two_squares.json");
    let s = slice2solid::io::read_sections(std::path::Path::new(path)).unwrap();
    assert_eq!(s.sections.len(), 2);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    // Bottom: 4x4 square with a 2x2 hole; top: a 3x3 square given in plane coordinates.
    assert!((s.sections[0].area() - 12.0).abs() < 1e-12);
    assert!((s.sections[1].area() - 9.0).abs() < 1e-12);
}

/// A real file with random byte mutations: the reader returns Ok or an error, never panics.
fn heart() -> Vec<u8> {
    std::fs::read(common::shared_dir().join("data/csl/Heart-simplified.csl")).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]
    #[test]
    fn mutated_csl_never_panics(edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 1..8)) {
        let mut bytes = heart();
        for (at, byte, kind) in edits {
            let i = at.index(bytes.len());
            match kind {
                0 => bytes[i] = byte,
                1 => { bytes.remove(i); }
                _ => bytes.insert(i, b"0123456789 .-h\nen"[byte as usize % 17]),
            }
        }
        let text = String::from_utf8_lossy(&bytes);
        if let Ok(s) = parse_csl(&text, "m.csl") {
            slice2solid::validate::validate(s, "m").unwrap();
        }
    }

    #[test]
    fn mutated_json_never_panics(edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6)) {
        let s = parse_csl(&String::from_utf8_lossy(&heart()), "h.csl").unwrap();
        let mut bytes = slice2solid::io::json::to_json_string(&s).into_bytes();
        for (at, byte) in edits {
            let i = at.index(bytes.len());
            bytes[i] = b"0123456789 .-e,[]{}\"n"[byte as usize % 21];
        }
        let _ = parse_json(&String::from_utf8_lossy(&bytes), "m.json");
    }
}
