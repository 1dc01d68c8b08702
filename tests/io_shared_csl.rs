//! Every shared CSL file loads without errors and round-trips CSL → CSL and CSL → JSON → CSL.
mod common;
use slice2solid::io::{csl, json, read_sections};
use slice2solid::Sections;
use std::time::Instant;

/// Same planes, labels and 2D points, within `rel` of the model's size.
fn assert_same(a: &Sections, b: &Sections, rel: f64, what: &str) {
    let (lo, hi) = a.bounding_box().unwrap();
    let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let tol = rel * diag;
    assert_eq!(a.sections.len(), b.sections.len(), "{what}: plane count");
    assert_eq!(a.n_labels, b.n_labels, "{what}: labels");
    for (i, (s, t)) in a.sections.iter().zip(&b.sections).enumerate() {
        for k in 0..3 {
            assert!(
                (s.plane.normal[k] - t.plane.normal[k]).abs() <= 1e-15,
                "{what}: plane {i} normal"
            );
            assert!(
                (s.plane.origin[k] - t.plane.origin[k]).abs() <= tol,
                "{what}: plane {i} origin"
            );
        }
        assert_eq!(
            s.regions.len(),
            t.regions.len(),
            "{what}: plane {i} regions"
        );
        for (r, (x, y)) in s.regions.iter().zip(&t.regions).enumerate() {
            assert_eq!(x.label, y.label, "{what}: plane {i} region {r} label");
            assert_eq!(
                x.holes.len(),
                y.holes.len(),
                "{what}: plane {i} region {r} holes"
            );
            for (c, d) in std::iter::once(&x.outer)
                .chain(&x.holes)
                .zip(std::iter::once(&y.outer).chain(&y.holes))
            {
                assert_eq!(
                    c.points2.len(),
                    d.points2.len(),
                    "{what}: plane {i} region {r} vertex count"
                );
                for (p, q) in c.points2.iter().zip(&d.points2) {
                    assert!(
                        (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol,
                        "{what}: plane {i} region {r}: {p:?} vs {q:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn every_shared_csl_file_loads_and_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    for path in common::shared_csl_files() {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let t0 = Instant::now();
        let s = read_sections(&path).unwrap_or_else(|e| panic!("{e}"));
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let (lo, hi) = s.bounding_box().unwrap();
        let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        let off = s
            .sections
            .iter()
            .map(|x| x.max_off_plane)
            .fold(0.0_f64, |m, r| {
                if r.is_nan() || m.is_nan() {
                    f64::NAN
                } else {
                    m.max(r)
                }
            });
        assert!(off.is_finite(), "{name}: off-plane distance {off}");
        eprintln!(
            "{name}: {} planes, {} vertices, {:.1} ms, max off-plane {:.2e} ({:.2e} of diagonal), warnings {:?}",
            s.sections.len(),
            s.vertex_count(),
            ms,
            off,
            off / diag,
            s.warnings
        );
        assert!(s.vertex_count() > 0);
        for sec in &s.sections {
            for r in &sec.regions {
                assert!(
                    r.outer.signed_area() > 0.0 && r.holes.iter().all(|h| h.signed_area() < 0.0)
                );
            }
        }

        // CSL -> CSL: the writer prints shortest round-trip decimals of the snapped 3D points,
        // so only the re-projection to 2D differs (a few ulps).
        let text = csl::to_csl_string(&s);
        let back = csl::parse_csl(&text, "back.csl").unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_same(&s, &back, 1e-12, &format!("{name} csl->csl"));
        assert!(
            back.warnings.is_empty(),
            "{name}: written file needs repairs: {:?}",
            back.warnings
        );

        // CSL -> JSON -> CSL through files.
        let jpath = dir.path().join(format!("{name}.json"));
        slice2solid::io::write_sections(&jpath, &s).unwrap();
        let from_json = read_sections(&jpath).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_same(&s, &from_json, 1e-12, &format!("{name} csl->json"));
        // 2D points are stored exactly in JSON.
        for (a, b) in s.sections.iter().zip(&from_json.sections) {
            for (x, y) in a.regions.iter().zip(&b.regions) {
                assert_eq!(
                    x.outer.points2, y.outer.points2,
                    "{name}: JSON 2D points exact"
                );
            }
        }
        let cpath = dir.path().join(format!("{name}.csl"));
        slice2solid::io::write_sections(&cpath, &from_json).unwrap();
        let again = read_sections(&cpath).unwrap();
        assert_same(&s, &again, 1e-12, &format!("{name} csl->json->csl"));
        let j2 = json::parse_json(&json::to_json_string(&again), "again.json").unwrap();
        assert_same(&s, &j2, 1e-12, &format!("{name} json again"));
    }
}

#[test]
fn unknown_extension_is_an_error() {
    let e = read_sections(std::path::Path::new("x.txt"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("x.txt") && e.contains(".csl, .json or .dcm"),
        "{e}"
    );
}
