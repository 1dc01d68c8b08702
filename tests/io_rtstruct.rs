//! DICOM RT Structure Set input. The files in tests/dicom/ are written by
//! `tests/dicom/make_rtstruct.py` (pydicom), each beside the same sections as JSON with explicit
//! planes and holes: reading the .dcm (planes fitted, holes found by nesting, keyholes repaired) must
//! give the JSON's sections, and the same solid.
mod common;
use common::{bin, json_of_success};
use slice2solid::eval::check::check_mesh;
use slice2solid::io::rtstruct::{read_rtstruct_with, Roi, RtStruct};
use slice2solid::io::{read_sections, read_sections_of_roi, ReadOptions};
use slice2solid::{reconstruct, Error, Options, Sections};
use std::path::PathBuf;

fn file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/dicom")
        .join(name)
}

fn read(name: &str) -> Sections {
    read_sections(&file(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn error_text(r: slice2solid::Result<Sections>) -> String {
    match r {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

/// Each section of `a` has a section of `b` on the same plane with the same labels, region and hole
/// counts, and area (relative `tol`).
fn assert_same_sections(a: &Sections, b: &Sections, tol: f64) {
    assert_eq!(a.sections.len(), b.sections.len());
    for (i, s) in a.sections.iter().enumerate() {
        let t = b
            .sections
            .iter()
            .find(|t| {
                let c: f64 = (0..3).map(|k| s.plane.normal[k] * t.plane.normal[k]).sum();
                c > 1.0 - 1e-9 && (s.plane.offset - t.plane.offset).abs() < 1e-6
            })
            .unwrap_or_else(|| panic!("section {i}: no section on plane {:?}", s.plane));
        let summary = |x: &slice2solid::Section| {
            let mut r: Vec<(i32, usize)> =
                x.regions.iter().map(|r| (r.label, r.holes.len())).collect();
            r.sort();
            r
        };
        assert_eq!(summary(s), summary(t), "section {i}");
        assert!(
            (s.area() - t.area()).abs() <= tol * t.area(),
            "section {i}: area {} vs {}",
            s.area(),
            t.area()
        );
    }
}

/// (components, volume) of the Delaunay reconstruction.
fn solid(sections: &Sections, label: Option<i32>) -> (usize, f64) {
    let options = Options {
        label,
        ..Default::default()
    };
    let s = reconstruct(sections, &options).unwrap();
    let c = check_mesh(&s.surface, None);
    assert!(c.closed && c.manifold && c.oriented);
    (c.components, c.volume)
}

#[test]
fn axial_planes_two_rois_and_nesting_match_the_json() {
    let dcm = read("axial_two_rois.dcm");
    let json = read("axial_two_rois.json");
    // DS decimals are the same in both files; only the fitted planes could differ, and axial
    // contours get exactly axial planes.
    assert_same_sections(&dcm, &json, 1e-12);
    let names: Vec<(i32, &str)> = dcm
        .label_names
        .iter()
        .map(|(l, n)| (*l, n.as_str()))
        .collect();
    assert_eq!(names, [(1, "Body"), (2, "Lesion"), (3, "Marker")]);
    // z = 8: Body's ring (outer + hole) and the island in its hole, and Lesion; normal +z although
    // the hole is listed first and some contours are clockwise.
    let z8 = dcm
        .sections
        .iter()
        .find(|s| (s.plane.offset + 8.0).abs() < 1e-12)
        .unwrap();
    assert_eq!(z8.plane.normal, [0.0, 0.0, 1.0]);
    let mut regions: Vec<(i32, usize)> = z8
        .regions
        .iter()
        .map(|r| (r.label, r.holes.len()))
        .collect();
    regions.sort();
    assert_eq!(regions, [(1, 0), (1, 1), (2, 0)]);
    assert!(
        dcm.warnings.iter().any(|w| w.contains(
            "skipped 1 contour(s) of type POINT (only CLOSED_PLANAR contours bound a section)"
        ) && w.contains("ROI \"Marker\" (number 3), contour 0")),
        "{:?}",
        dcm.warnings
    );
    let (n, v) = solid(&dcm, None);
    let (nj, vj) = solid(&json, None);
    assert_eq!(n, nj);
    assert!((v - vj).abs() <= 1e-9 * vj, "{v} vs {vj}");
}

#[test]
fn oblique_planes_are_fitted_from_the_points() {
    let dcm = read("oblique.dcm");
    let json = read("oblique.json");
    // The contours are 32-gons rounded to 6 decimals: a fitted plane is within ~1e-7 of the exact one.
    assert_same_sections(&dcm, &json, 1e-6);
    for s in &dcm.sections {
        assert!(
            s.max_off_plane > 0.0 && s.max_off_plane < 2e-6,
            "{}",
            s.max_off_plane
        );
        let n = s.plane.normal;
        assert!(
            n[0].abs() > 0.2 && n[1].abs() > 0.2 && n[2].abs() > 0.2,
            "{n:?}"
        );
    }
    let (n, v) = solid(&dcm, None);
    let (nj, vj) = solid(&json, None);
    assert_eq!((n, nj), (1, 1));
    assert!((v - vj).abs() <= 1e-5 * vj, "{v} vs {vj}");
}

#[test]
fn keyhole_contour_becomes_an_outer_contour_and_a_hole() {
    let dcm = read("keyhole.dcm");
    let json = read("keyhole.json");
    assert_same_sections(&dcm, &json, 1e-12);
    assert!(
        dcm.warnings.iter().any(|w| w.starts_with(&format!(
            "{}: ROI \"Ring\" (number 1), contour 2: repaired self-intersecting",
            file("keyhole.dcm").display()
        )) && w.contains("keyhole: 1 outer + 1 hole(s)")),
        "{:?}",
        dcm.warnings
    );
    // The repair drops the channel's vertices (collinear on the outer and hole edges), and the
    // solid's vertices differ from the JSON's by that: the volumes agree to 1.4e-8.
    let (n, v) = solid(&dcm, None);
    let (nj, vj) = solid(&json, None);
    assert_eq!(n, nj);
    assert!((v - vj).abs() <= 1e-7 * vj, "{v} vs {vj}");
    let e = error_text(read_rtstruct_with(
        &file("keyhole.dcm"),
        &ReadOptions { strict: true },
        None,
    ));
    assert!(
        e.contains("ROI \"Ring\" (number 1), contour 2: self-intersecting contour"),
        "{e}"
    );
}

#[test]
fn roi_picks_one_roi_by_name() {
    let lesion = read_sections_of_roi(
        &file("axial_two_rois.dcm"),
        &ReadOptions::default(),
        Some("Lesion"),
    )
    .unwrap();
    assert_eq!(lesion.sections.len(), 3);
    assert_eq!(
        lesion.regions_per_label().into_iter().collect::<Vec<_>>(),
        [(2, 3)]
    );
    assert_eq!(lesion.label_names.len(), 1);
    let (n, v) = solid(&lesion, None);
    let (nj, vj) = solid(&read("axial_two_rois.json"), Some(2));
    assert_eq!((n, nj), (1, 1));
    assert!((v - vj).abs() <= 1e-9 * vj, "{v} vs {vj}");

    let e = error_text(read_sections_of_roi(
        &file("axial_two_rois.dcm"),
        &ReadOptions::default(),
        Some("lesion"),
    ));
    assert!(
        e.contains("--roi \"lesion\": no ROI of this name (ROIs: \"Body\" (number 1), \"Lesion\" (number 2), \"Marker\" (number 3))"),
        "{e}"
    );
    let e = error_text(read_sections_of_roi(
        &PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/eight_15.csl"),
        &ReadOptions::default(),
        Some("Body"),
    ));
    assert!(e.contains("only DICOM RT Structure Sets have ROIs"), "{e}");
}

/// Two ROIs of one structure set overlapping on a plane (an organ inside the body outline).
fn overlapping_rois() -> RtStruct {
    let square = |h: f64| vec![[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]];
    RtStruct {
        file: "mem.dcm".into(),
        rois: vec![
            Roi {
                number: 1,
                name: "Body".into(),
                contours: vec![(0, square(10.0))],
            },
            Roi {
                number: 2,
                name: "Organ".into(),
                contours: vec![(0, square(2.0))],
            },
        ],
        warnings: Vec::new(),
    }
}

#[test]
fn overlapping_rois_are_repaired_together_and_read_one_at_a_time() {
    // all ROIs at once: labels that overlap in area follow the documented rule (the lower label
    // keeps the overlap: the organ inside the body is cut from the organ, with a warning);
    // --strict refuses; one ROI at a time reads each as it is
    let rt = overlapping_rois();
    let all = rt.sections(None, &ReadOptions::default()).unwrap();
    assert!(
        all.warnings.iter().any(|w| w
            .contains("repaired overlapping components of different labels")
            && w.contains("the lower label 1 keeps it")),
        "{:?}",
        all.warnings
    );
    assert!((all.sections[0].area() - 400.0).abs() < 1e-9);
    let e = error_text(rt.sections(None, &ReadOptions { strict: true }));
    assert!(
        e.starts_with("mem.dcm: ROI \"Organ\" (number 2), contour 0: region lies inside the material of mem.dcm: ROI \"Body\" (number 1), contour 0")
            && e.contains("reconstruct one ROI with --roi NAME"),
        "{e}"
    );
    let organ = rt.sections(Some("Organ"), &ReadOptions::default()).unwrap();
    assert!((organ.sections[0].area() - 16.0).abs() < 1e-12);
}

#[test]
fn malformed_files_give_located_errors() {
    let e = error_text(read_sections(&file("missing.dcm")));
    assert!(
        e.contains("missing.dcm") && e.contains("No such file"),
        "{e}"
    );
    let e = error_text(read_sections(&file("no_roi_contours.dcm")));
    assert!(
        e.ends_with("no_roi_contours.dcm: no ROI Contour Sequence (3006,0039): not an RT Structure Set with contours (Modality RTSTRUCT)"),
        "{e}"
    );
    let e = error_text(read_sections(&file("nonplanar.dcm")));
    assert!(
        e.contains(
            "nonplanar.dcm: ROI \"Bent\" (number 3), contour 1: contour is not planar: point 2 is"
        ),
        "{e}"
    );
    let e = match RtStruct::parse(b"CSLC\n1 1\n", "text.dcm") {
        Err(e) => e.to_string(),
        Ok(_) => panic!("text read as DICOM"),
    };
    assert!(e.starts_with("text.dcm: not a readable DICOM file"), "{e}");
}

#[test]
fn truncated_or_corrupted_files_never_panic() {
    let bytes = std::fs::read(file("axial_two_rois.dcm")).unwrap();
    let mut refused = 0;
    for n in 0..bytes.len() {
        if let Err(e) = RtStruct::parse(&bytes[..n], "cut.dcm") {
            assert!(matches!(e, Error::Input { .. }), "{e}");
            refused += 1;
        }
    }
    // Cut inside the data set, reading fails (a cut between elements may still parse).
    assert!(refused > bytes.len() / 2, "{refused} of {}", bytes.len());
    // Bytes of the data set flipped: an error or sections, never a panic. A sample: where a flip
    // makes a length huge, dicom-rs reserves that much before it fails, which takes seconds.
    for i in (132..bytes.len()).step_by(97) {
        let mut b = bytes.clone();
        b[i] ^= 0x01;
        if let Ok(rt) = RtStruct::parse(&b, "flip.dcm") {
            let _ = rt.sections(None, &ReadOptions::default());
        }
    }
}

#[test]
fn cli_reconstructs_and_describes_rtstruct() {
    let dir = tempfile::tempdir().unwrap();
    let (out, report) = (dir.path().join("a.obj"), dir.path().join("r.json"));
    let o = bin()
        .args(["reconstruct", file("axial_two_rois.dcm").to_str().unwrap()])
        .args(["-q", "-o", out.to_str().unwrap(), "--report"])
        .arg(&report)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    // Marker has no section, so it is not among the reconstructed labels.
    assert_eq!(
        r["label_names"],
        serde_json::json!({"1": "Body", "2": "Lesion"})
    );

    let o = bin()
        .args(["reconstruct", file("axial_two_rois.dcm").to_str().unwrap()])
        .args([
            "-q",
            "-o",
            out.to_str().unwrap(),
            "--roi",
            "Lesion",
            "--report",
        ])
        .arg(&report)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    assert_eq!(r["label_names"], serde_json::json!({"2": "Lesion"}));
    assert_eq!(r["surface"]["components"], 1);

    let o = bin()
        .args(["info", file("axial_two_rois.dcm").to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("label names:    1: \"Body\", 2: \"Lesion\", 3: \"Marker\""),
        "{text}"
    );
    let doc = json_of_success(
        &bin()
            .args(["info", file("oblique.dcm").to_str().unwrap(), "--json"])
            .output()
            .unwrap(),
    );
    assert_eq!(doc["label_names"], serde_json::json!({"7": "Prostate"}));
    assert_eq!(doc["planes"], 4);

    for (args, expect) in [
        (vec!["--roi", "Nope"], "no ROI of this name"),
        (vec!["--roi", "Body", "--label", "1"], "cannot be used with"),
    ] {
        let o = bin()
            .args(["reconstruct", file("axial_two_rois.dcm").to_str().unwrap()])
            .args(["-q", "-o", out.to_str().unwrap()])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains(expect),
            "{args:?}: {err}"
        );
    }
}
