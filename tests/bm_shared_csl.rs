//! Every shared CSL file, one test each, reconstructed with the Delaunay pruning engine and held to
//! what it gives today (README's claims): a closed, oriented 2-manifold without self-intersections
//! (exact crossings and overlapping near-coplanar pairs), no degenerate triangle, no two vertices at
//! one position or nearly (`MIN_VERTEX_GAP`), exactly today's components and genus, and every section within a per-file bound
//! pinned just above today's worst value. When a change improves a number, tighten it here in the
//! same commit. Surfaces are written to `$BM_OUT_DIR` (if set) for the outside judge.
//!
//! Sections are measured two ways: `exact`, the exact `check --sections` (the limit of sections by
//! planes just off the input plane, the better side); `shifted`, planes moved ±1e-7 of the diagonal
//! (`bm_common::worst_section`), which sees past faces lying in the plane up to rounding.
mod bm_common;
mod common;
use slice2solid::eval::check::check_mesh;
use slice2solid::Options;

/// What a shared file gives today.
struct Expected {
    /// Bound on the worst relative section disagreement, exact check at the plane.
    exact: f64,
    /// Bound on the same, planes shifted ±1e-7 of the diagonal.
    shifted: f64,
    components: usize,
    genus: i64,
    /// Bound on the sum over planes of the exact disagreement (so that a plane gone bad does not
    /// hide below the worst plane's bound).
    sum: f64,
    /// Flat-zone triangles (the paper's Fig. 13: section triangles neither side keeps) thickened
    /// into slabs of tetrahedra (`bm::slab`).
    flat_zones_thickened: u64,
}

/// No two vertices of a surface closer than this, relative to the diagonal.
const MIN_VERTEX_GAP: f64 = 5e-8;

fn run(name: &str, e: Expected) {
    let path = common::shared_csl(name);
    let sections = slice2solid::io::read_sections(&path)
        .unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let solid = slice2solid::reconstruct(&sections, &Options::default())
        .unwrap_or_else(|err| panic!("{name}: {err}"));
    if let Some(d) = std::env::var_os("BM_OUT_DIR").map(std::path::PathBuf::from) {
        std::fs::create_dir_all(&d).unwrap();
        slice2solid::io::mesh::write_trimesh(&d.join(format!("{name}.obj")), &solid.surface)
            .unwrap();
    }
    let c = check_mesh(&solid.surface, Some(&sections));
    let exact = c.worst_section.as_ref().expect("sections checked").relative;
    let shifted = bm_common::worst_section(&solid.surface, &sections);
    let sum: f64 = c.sections.iter().map(|a| a.relative).sum();
    let thickened = solid.report.counts["flat_zone_triangles_thickened"];
    eprintln!(
        "{name}: {} tris, comps {} genus {} exact {exact:.6e} shifted {shifted:.6e} sum {sum:.6e} thickened {thickened} degenerate {} coincident {}",
        c.triangles, c.components, c.genus, c.degenerate_triangles, c.coincident_vertices
    );
    assert!(
        c.closed && c.manifold && c.oriented,
        "{name}: closed {} manifold {} oriented {} (boundary edges {}, non-manifold edges {}, vertices {})",
        c.closed, c.manifold, c.oriented, c.boundary_edges, c.nonmanifold_edges, c.nonmanifold_vertices
    );
    assert!(
        c.self_intersection_free,
        "{name}: {} crossing pairs, {} overlapping near-coplanar pairs",
        c.self_intersections, c.overlapping_coplanar_pairs
    );
    assert_eq!(c.degenerate_triangles, 0, "{name}: degenerate triangles");
    assert_eq!(c.coincident_vertices, 0, "{name}: coincident vertices");
    // the closest input contour vertices (balloondog) are 7.6e-8 of the diagonal apart: no
    // constructed point may come closer to another (trimesh welds below ~1e-8)
    let gap = bm_common::closest_vertex_gap(&solid.surface);
    assert!(
        gap >= MIN_VERTEX_GAP,
        "{name}: two vertices {gap:.3e} of the diagonal apart"
    );
    assert!(
        exact <= e.exact,
        "{name}: worst section (exact) {exact:.6e} > {:.6e}",
        e.exact
    );
    assert!(
        shifted <= e.shifted,
        "{name}: worst section (shifted) {shifted:.6e} > {:.6e}",
        e.shifted
    );
    assert!(
        sum <= e.sum,
        "{name}: summed section disagreement {sum:.6e} > {:.6e}",
        e.sum
    );
    assert_eq!(
        (c.components, c.genus),
        (e.components, e.genus),
        "{name}: (components, genus)"
    );
    assert_eq!(
        thickened, e.flat_zones_thickened,
        "{name}: flat zones thickened"
    );
}

macro_rules! shared_file {
    ($test:ident, $name:literal, $exact:expr, $shifted:expr, $sum:expr, $comps:expr, $genus:expr, $thick:expr) => {
        #[test]
        fn $test() {
            run(
                $name,
                Expected {
                    exact: $exact,
                    shifted: $shifted,
                    sum: $sum,
                    components: $comps,
                    genus: $genus,
                    flat_zones_thickened: $thick,
                },
            );
        }
    };
}

// name, file, exact, shifted, summed exact, components, genus, flat-zone triangles thickened
// (genus since unwitnessed handles are closed, `bm::tunnels`, and cut, `bm::cuts`: Armadillo
// 3 -> 2 -> 0, Elephant 28 -> 14 -> 11, Horsers 4 -> 0, hand 22 -> 11 -> 6 (its reference: 5), 7 since split contour edges are
// guarded, `bm::guard`, which refuses samples near them (its flat zones 94 -> 115 triangles); the raw values are pinned in
// tests/bm_topology.rs)
// (one conforming complex; the sections are exact up to rounding, so the
// exact bounds are 1e-9 where today's value is below it; with the collar, sections just off
// the planes ("shifted") are exact too wherever the planes are parallel)
shared_file!(
    armadillo,
    "Armadillo-23-better",
    1e-9,
    2.3e-5,
    1.2e-9,
    3,
    0,
    71
);
shared_file!(elephant, "Elephant", 1e-9, 3.3e-5, 1.3e-9, 1, 11, 191);
shared_file!(heart, "Heart-simplified", 1e-9, 1e-9, 1e-9, 1, 0, 0);
shared_file!(horsers, "Horsers", 8.9e-5, 1.4e-4, 6.1e-4, 1, 0, 109);
shared_file!(parallel_eight, "ParallelEight", 1e-9, 1e-9, 1e-9, 1, 2, 0);
shared_file!(
    parallel_eight_more,
    "ParallelEightMore",
    1e-9,
    1e-9,
    1e-9,
    1,
    2,
    0
);
shared_file!(side_bishop, "SideBishop", 1e-9, 1e-9, 1e-9, 1, 0, 0);
shared_file!(balloondog, "balloondog", 1e-9, 1e-9, 1e-9, 1, 0, 0);
shared_file!(balloondog_box, "balloondog_box", 1e-9, 1e-9, 1e-9, 2, 0, 0);
shared_file!(eight_15, "eight_15", 1e-9, 1e-9, 1e-9, 1, 2, 0);
shared_file!(eight_20, "eight_20", 1e-9, 5.4e-6, 1e-9, 1, 2, 11);
shared_file!(hand, "hand", 1e-9, 1.6e-5, 1e-9, 1, 7, 115);

/// The test list above names every shared file.
#[test]
fn every_shared_file_has_a_test() {
    let names = common::shared_csl_files();
    assert_eq!(names.len(), 12);
}

/// Paper §3: consecutive samples along a branching or cutting diagram are Delaunay edges. Checked
/// here from the cells' own section triangles, not from the engine's counter: every pair of every
/// cell's list is an edge of a triangle of its face, the pairs number what the report counts, and
/// every file that has diagram samples has pairs (all but Heart-simplified, whose sections need no
/// branching).
#[test]
fn consecutive_diagram_samples_are_delaunay_edges() {
    use slice2solid::arrangement::Arrangement;
    let mut failures = Vec::new();
    for name in common::SHARED_CSL {
        let sections = slice2solid::io::read_sections(&common::shared_csl(name)).unwrap();
        let options = Options::default();
        let arr = Arrangement::build(&sections.select_label(None).unwrap(), &options.arrangement)
            .unwrap();
        let runs = slice2solid::bm::run_cells(&arr, &options).unwrap();
        let (mut pairs, mut samples, mut off) = (0u64, 0u64, Vec::new());
        for (c, r) in runs.results.iter().enumerate() {
            let Some(r) = r else { continue };
            samples += r.branching_samples + r.cutting_samples;
            pairs += r.sample_pair_list.len() as u64;
            // pairs split by Steiner points, or joined through the other side's diagram points
            assert!(
                r.sample_pair_list.len() as u64 >= r.sample_pairs,
                "{name} cell {c}: pair list against counters"
            );
            for &(slot, u, v) in &r.sample_pair_list {
                let on_face = r.faces[slot]
                    .triangles
                    .iter()
                    .any(|(t, _)| t.contains(&u) && t.contains(&v));
                if !on_face {
                    off.push((c, slot, u, v));
                }
            }
        }
        eprintln!("{name}: {samples} diagram samples, {pairs} consecutive pairs");
        if !off.is_empty() {
            failures.push(format!("{name}: pairs not edges {off:?}"));
        }
        if (name == "Heart-simplified") != (samples == 0) || (samples > 0 && pairs == 0) {
            failures.push(format!("{name}: {samples} samples, {pairs} pairs"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
