//! Every shared CSL file reconstructs with the Delaunay pruning engine (no error); the files in
//! `CLEAN` into closed, oriented, manifold surfaces without self-intersections whose sections agree
//! with the input. Prints per file: time, triangles, checks, worst section disagreement, flat zones.
//! The surfaces are written to `$BM_OUT_DIR` (if set) for the outside judge.
mod bm_common;
mod common;
use slice2solid::eval::check::check_mesh;
use slice2solid::{Error, Options};

/// Files whose surface is closed, oriented and manifold, free of self-intersections (exact crossings
/// and overlapping near-coplanar pairs), has no two vertices at one position, and whose every section agrees with the
/// input within 2% (the criterion). Flat zones attached from neither side are thickened
/// (bm::thicken), so hand and Armadillo keep their sections (Armadillo lost 20% of one before), and
/// untangle lets a pinch's kept fan retreat (Elephant and Armadillo had 5 and 6 crossings), and
/// the arrangement merges the vertices that rounding kept apart where four planes nearly meet in
/// one point (Horsers had two overlapping near-coplanar pairs of 1e-15-wide triangles there;
/// arrangement::merge, tests/bm_horsers.rs). All twelve shared files.
const CLEAN: &[&str] = &[
    "Armadillo-23-better",
    "Elephant",
    "Heart-simplified",
    "ParallelEight",
    "ParallelEightMore",
    "Horsers",
    "SideBishop",
    "balloondog",
    "balloondog_box",
    "eight_15",
    "eight_20",
    "hand",
];

/// Files whose solid is one connected piece (the reference meshes are) and that come out as one
/// component today. eight_20 came out as 23 (one-tet voids left by pruning, prune::fill_cavities).
/// Elephant (12) and eight_20 (3) are no longer one piece: their islands attached from neither
/// side are now thickened into thin slabs of their own (bm::thicken) instead of missing from the
/// sections.
const ONE_PIECE: &[&str] = &[
    "Heart-simplified",
    "ParallelEight",
    "ParallelEightMore",
    "SideBishop",
    "balloondog",
    "eight_15",
    "hand",
];

#[test]
fn every_shared_csl_file_reconstructs() {
    let out_dir = std::env::var_os("BM_OUT_DIR").map(std::path::PathBuf::from);
    let mut failures = Vec::new();
    let mut seen = Vec::new();
    for path in common::shared_csl_files() {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        seen.push(name.clone());
        let sections = slice2solid::io::read_sections(&path).expect("read");
        let t = std::time::Instant::now();
        let solid = match slice2solid::reconstruct(&sections, &Options::default()) {
            Err(Error::Unavailable(m)) => {
                eprintln!("{name}: skipped ({m})");
                return;
            }
            Err(e) => {
                failures.push(format!("{name}: error {e}"));
                continue;
            }
            Ok(s) => s,
        };
        let secs = t.elapsed().as_secs_f64();
        if let Some(d) = &out_dir {
            let _ = std::fs::create_dir_all(d);
            slice2solid::io::mesh::write_trimesh(&d.join(format!("{name}.obj")), &solid.surface)
                .expect("write");
        }
        let c = check_mesh(&solid.surface, None);
        let worst = bm_common::worst_section(&solid.surface, &sections);
        eprintln!(
            "{name}: {:.3}s {} tris closed {} manifold {} oriented {} comps {} genus {} self-int {} worst-section {:.4} flat-zone-faces {} nonconf {} steiner {} branching {} cutting {} sample pairs {} diagram steiner {}",
            secs, c.triangles, c.closed, c.manifold, c.oriented, c.components, c.genus,
            c.self_intersections_vertex_disjoint, worst,
            solid.report.counts.get("flat_zone_faces").unwrap_or(&0),
            solid.report.counts.get("nonconforming_faces").unwrap_or(&0),
            solid.report.counts.get("steiner_points").unwrap_or(&0),
            solid.report.counts.get("branching_samples").unwrap_or(&0),
            solid.report.counts.get("cutting_samples").unwrap_or(&0),
            solid.report.counts.get("sample_pairs").unwrap_or(&0),
            solid.report.counts.get("sample_steiner_points").unwrap_or(&0),
        );
        if CLEAN.contains(&name.as_str()) && !(c.closed && c.manifold && c.oriented) {
            failures.push(format!(
                "{name}: closed {} manifold {} oriented {} (boundary edges {}, non-manifold edges {}, vertices {})",
                c.closed, c.manifold, c.oriented, c.boundary_edges, c.nonmanifold_edges, c.nonmanifold_vertices
            ));
        }
        if CLEAN.contains(&name.as_str())
            && !(c.self_intersection_free && c.coincident_vertices == 0 && worst < 0.02)
        {
            failures.push(format!(
                "{name}: self-intersections {} overlapping coplanar pairs {} coincident vertices {} worst section {worst:.4}",
                c.self_intersections, c.overlapping_coplanar_pairs, c.coincident_vertices
            ));
        }
        // paper §3, Delaunay conformity: consecutive branching/cutting samples are edges
        let not_edges = solid
            .report
            .counts
            .get("sample_pairs_not_edges")
            .copied()
            .unwrap_or(0);
        if not_edges != 0 || !solid.report.counts.contains_key("sample_pairs") {
            failures.push(format!(
                "{name}: {not_edges} consecutive diagram sample pairs are not Delaunay edges (sample_pairs {:?})",
                solid.report.counts.get("sample_pairs")
            ));
        }
        if ONE_PIECE.contains(&name.as_str()) && c.components != 1 {
            failures.push(format!("{name}: {} components, expected 1", c.components));
        }
    }
    for name in CLEAN.iter().chain(ONE_PIECE) {
        if !seen.iter().any(|s| s == name) {
            failures.push(format!("{name}: not among the shared CSL files"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
