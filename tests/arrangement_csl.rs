//! The arrangement builds on every shared CSL file, with exact volume and area bookkeeping.
mod arrangement_support;
mod common;
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use std::time::Instant;

#[test]
fn every_shared_csl_file() {
    for path in common::shared_csl_files() {
        let s = slice2solid::io::csl::read_csl(&path).unwrap();
        let t = Instant::now();
        let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
        let dt = t.elapsed();
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

#[test]
#[ignore]
fn horsers_disagreement_details() {
    let s =
        slice2solid::io::csl::read_csl(&common::shared_dir().join("data/csl/Horsers.csl")).unwrap();
    let arr = Arrangement::build(
        &s,
        &ArrangementOptions {
            snap_tolerance: 1e-6,
            ..Default::default()
        },
    )
    .unwrap();
    for w in &arr.warnings {
        eprintln!("{w}");
    }
}
