//! The arrangement builds on every shared CSL file, with exact volume and area bookkeeping.
mod arrangement_support;
mod common;
use slice2solid::arrangement::{Arrangement, ArrangementOptions, CellScope};
use std::time::Instant;

#[test]
fn every_shared_csl_file() {
    for path in common::shared_csl_files() {
        let s = slice2solid::io::read_sections(&path).unwrap();
        let t = Instant::now();
        let all = ArrangementOptions {
            scope: CellScope::All,
            ..Default::default()
        };
        let arr = Arrangement::build(&s, &all).unwrap();
        let dt = t.elapsed();
        let (n_all, n_sparse) = arrangement_support::check_scopes_agree(&s, &Default::default());
        assert_eq!(n_all, arr.cells.len());
        assert_eq!(n_sparse, arr.cells_with_sections());
        let (lo, hi) = arr.bbox;
        let box_vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
        let sum: f64 = arr.cells.iter().map(|c| c.volume).sum();
        assert!(
            ((sum - box_vol) / box_vol).abs() < 1e-12,
            "{path:?}: volumes"
        );
        arrangement_support::check_arrangement(&arr, &s);
        let mut worst_area = 0.0f64;
        for (i, sec) in s.sections.iter().enumerate() {
            let total: f64 = arr
                .faces
                .iter()
                .filter(|f| f.plane as usize == i)
                .flat_map(|f| f.pieces.iter())
                .map(|p| arr.piece_area(i as u32, p))
                .sum();
            let a = sec.area();
            worst_area = worst_area.max((total - a).abs() / a.max(1e-300));
            assert!(
                (total - a).abs() <= 1e-9 * a.max(1e-12),
                "{path:?} plane {i}: pieces {total} vs section {a}"
            );
        }
        let other: Vec<_> = arr
            .warnings
            .iter()
            .filter(|w| !w.starts_with("sections"))
            .collect();
        eprintln!(
            "{}: {} planes, {} cells ({} with sections), {} faces, {} pool vertices, max disagreement {:.3e}, area rel err {:.1e}, {} warnings, build {:.1} ms",
            path.file_name().unwrap().to_string_lossy(),
            arr.n_input,
            arr.cells.len(),
            arr.cells_with_sections(),
            arr.faces.len(),
            arr.pool.positions.len(),
            arr.max_disagreement,
            worst_area,
            arr.warnings.len(),
            dt.as_secs_f64() * 1e3
        );
        assert!(other.is_empty(), "{path:?}: {other:?}");
    }
}

/// On files whose sections agree along every line, every point of a section on another input
/// plane is ONE pool vertex used by the pieces of both planes.
#[test]
fn agreeing_files_share_every_crossing() {
    for name in ["Elephant.csl", "eight_20.csl", "Armadillo-23-better.csl"] {
        let path = common::shared_dir().join("data/csl").join(name);
        let s = slice2solid::io::csl::read_csl(&path).unwrap();
        let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
        let n = arr.n_input as u32;
        let mut used: Vec<Vec<u32>> = vec![Vec::new(); arr.pool.positions.len()];
        for f in &arr.faces {
            for p in &f.pieces {
                for &v in p.outer.iter().chain(p.holes.iter().flatten()) {
                    if !used[v as usize].contains(&f.plane) {
                        used[v as usize].push(f.plane);
                    }
                }
            }
        }
        let (mut shared, mut lonely) = (0, 0);
        for (v, tags) in arr.pool.tags.iter().enumerate() {
            let input: Vec<u32> = tags.iter().copied().filter(|&t| t < n).collect();
            if input.len() != 2 || used[v].is_empty() {
                continue;
            }
            if input.iter().all(|t| used[v].contains(t)) {
                shared += 1;
            } else {
                lonely += 1;
            }
        }
        eprintln!("{name}: {shared} shared crossings, {lonely} used by one plane only, max disagreement {:.2e}", arr.max_disagreement);
        assert!(arr.max_disagreement < 1e-6 * 3.0);
        assert_eq!(lonely, 0);
        assert!(shared > 0);
    }
}

/// Refined face boundaries hold every piece vertex lying on a face edge, in order (same area).
#[test]
fn face_boundaries_hold_the_crossings() {
    let path = common::shared_dir().join("data/csl/Elephant.csl");
    let s = slice2solid::io::read_sections(&path).unwrap();
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    let fb = arr.face_boundaries();
    assert_eq!(fb.len(), arr.faces.len());
    let mut refined = 0;
    for (f, face) in arr.faces.iter().enumerate() {
        let b = &fb[f];
        refined += b.len() - face.polygon.len();
        let a0 = arr.loop_area(face.plane, &face.polygon);
        let a1 = arr.loop_area(face.plane, b);
        assert!((a0 - a1).abs() <= 1e-9 * a0, "face {f}: {a0} vs {a1}");
        // Every piece vertex on the face's boundary (tagged with another plane of an edge) is in it.
        for p in &face.pieces {
            for &v in p.outer.iter().chain(p.holes.iter().flatten()) {
                if arr.pool.tags[v as usize].len() >= 2 {
                    assert!(
                        b.contains(&v),
                        "face {f}: piece vertex {v} not on the refined boundary"
                    );
                }
            }
        }
    }
    assert!(refined > 0);
}
