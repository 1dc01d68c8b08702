//! `--assembly complex` with shared samples (`bm::assembly`, `docs/design/conforming-complex.md`
//! steps 5–6): the cells' kept tetrahedra form one complex, the surface is its boundary. On every
//! shared file, exactly: the tetrahedral mesh is conforming (no face in three tets, none inverted or
//! flat) and its boundary is the surface written; the surface has no crossing or overlapping
//! triangles. Pinned at today's values (upper bounds): faces the two
//! cells triangulate differently, flat-zone triangles that got no slab (`bm::slab`), and the singular
//! edges and pinched vertices that filling (`bm::fill`) and growing (`bm::singular`) could not
//! resolve. Where all of those are zero the solid is a
//! closed manifold with exact sections.
mod common;
use slice2solid::eval::check::check_mesh;
use slice2solid::{DelaunayOptions, Options};

/// (file, faces triangulated differently, flat-zone triangles, singular edges, pinched vertices,
/// components of the surface once unwitnessed voids are filled: `bm::voids`)
const PINS: [(&str, u64, u64, u64, u64, usize); 12] = [
    ("Armadillo-23-better", 0, 0, 0, 0, 3),
    ("Elephant", 0, 0, 0, 0, 1),
    ("Heart-simplified", 0, 0, 0, 0, 1),
    ("Horsers", 0, 3, 0, 0, 1),
    ("ParallelEight", 0, 0, 0, 0, 1),
    ("ParallelEightMore", 0, 0, 0, 0, 1),
    ("SideBishop", 0, 0, 0, 0, 1),
    ("balloondog", 0, 0, 0, 0, 1),
    ("balloondog_box", 0, 0, 0, 0, 2),
    ("eight_15", 0, 0, 0, 0, 1),
    ("eight_20", 0, 0, 0, 0, 1),
    ("hand", 0, 0, 0, 0, 1),
];

// Horsers kept 1 overlapping coplanar pair (two surface triangles folded flat over a wedge of
// rounded-flat tetrahedra) and was listed here until `manifold::close_flat_folds`.

fn options() -> Options {
    Options {
        delaunay: DelaunayOptions {
            shared_samples: true,
            ..Default::default()
        },
        ..Default::default()
    }
}

#[test]
fn the_solid_is_the_boundary_of_one_conforming_complex() {
    let mut failures = Vec::new();
    for (name, differ, flat, edges, vertices, components) in PINS {
        let sections = slice2solid::io::read_sections(&common::shared_csl(name)).unwrap();
        let solid = slice2solid::reconstruct(&sections, &options())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let count = |k: &str| {
            *solid
                .report
                .counts
                .get(k)
                .unwrap_or_else(|| panic!("{name}: no count {k}"))
        };
        let got = (
            count("nonconforming_faces"),
            count("flat_zone_triangles_left"),
            count("singular_edges"),
            count("singular_vertices"),
        );
        eprintln!("{name}: (differ, flat, singular edges, pinched vertices) {got:?}");
        if got.0 > differ || got.1 > flat || got.2 > edges || got.3 > vertices {
            failures.push(format!(
                "{name}: {got:?} above {:?}",
                (differ, flat, edges, vertices)
            ));
        }
        let (t, equal) = common::check_solid_tets(&solid);
        // conforming as a complex (TetCheck::conforming also wants a manifold boundary, which
        // the pinned singularities are not)
        let complex = t.coincident_vertices == 0
            && t.faces_used_more_than_twice == 0
            && t.interior_faces_same_side == 0
            && t.inverted == 0
            && t.flat == 0
            && t.volume_matches;
        if !complex || !equal {
            failures.push(format!(
                "{name}: tets: coincident {} faces in 3+ tets {} same-side faces {} inverted {} flat {} volume matches {} boundary = surface {equal}",
                t.coincident_vertices, t.faces_used_more_than_twice, t.interior_faces_same_side,
                t.inverted, t.flat, t.volume_matches
            ));
        }
        if (differ, flat, edges, vertices) == (0, 0, 0, 0) && !t.valid {
            failures.push(format!("{name}: tets not valid"));
        }
        let c = check_mesh(&solid.surface, Some(&sections));
        if c.components != components {
            failures.push(format!(
                "{name}: {} components, not {components}",
                c.components
            ));
        }
        let crossing = c.self_intersections + c.overlapping_coplanar_pairs > 0;
        if crossing || c.boundary_edges != 0 {
            failures.push(format!(
                "{name}: {} crossing, {} overlapping pairs, {} boundary edges",
                c.self_intersections, c.overlapping_coplanar_pairs, c.boundary_edges
            ));
        }
        if (differ, flat, edges, vertices) == (0, 0, 0, 0) {
            let worst = c.worst_section.as_ref().map_or(1.0, |w| w.relative);
            // listed: Armadillo misses a 0.59 unit² sliver of plane 22's 1.0e8 unit² section
            // (5.8e-9), not yet explained
            let bound = if name == "Armadillo-23-better" {
                6e-9
            } else {
                1e-9
            };
            if !(c.closed && c.manifold && c.oriented && worst < bound) {
                failures.push(format!(
                    "{name}: closed {} manifold {} oriented {} worst section {worst}",
                    c.closed, c.manifold, c.oriented
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Voids between the planes that no section witnesses are filled by default; `keep_topology`
/// keeps the raw result, where hand's boundary has 2 such bubbles (negative volume) besides the
/// solid, and the solid is otherwise the same but for the membranes that close the handles no
/// section witnesses (same sections, a lower genus of the main component by default).
/// (12 while gaps at singular edges were only grown into by whole tetrahedra, which enclosed
/// bubbles far from the edges.)
#[test]
fn unwitnessed_voids_are_filled_unless_the_raw_topology_is_kept() {
    let sections = slice2solid::io::read_sections(&common::shared_csl("hand")).unwrap();
    let mut raw = options();
    raw.delaunay.keep_topology = true;
    let filled = slice2solid::reconstruct(&sections, &options()).unwrap();
    let raw = slice2solid::reconstruct(&sections, &raw).unwrap();
    let (f, r) = (
        check_mesh(&filled.surface, Some(&sections)),
        check_mesh(&raw.surface, Some(&sections)),
    );
    assert_eq!((f.components, r.components), (1, 3));
    assert_eq!(filled.report.counts["voids_filled"], 2);
    assert_eq!(raw.report.counts["voids_filled"], 0);
    let voids: Vec<f64> = r
        .component_details
        .iter()
        .map(|c| c.volume)
        .filter(|&v| v < 0.0)
        .collect();
    assert_eq!(voids.len(), 2);
    // what the default adds beyond the voids: the membranes closing unwitnessed handles
    // (`bm::tunnels`), a sliver of the volume (today 2.4e-3 of it)
    let gap = f.volume - (r.volume - voids.iter().sum::<f64>());
    assert!(gap > 0.0 && gap < 3e-3 * f.volume, "{gap} of {}", f.volume);
    assert!(filled.report.counts["tunnels_closed"] > 0);
    let main = |c: &slice2solid::eval::check::CheckReport| {
        c.component_details
            .iter()
            .max_by_key(|d| d.triangles)
            .unwrap()
            .genus
    };
    assert!(main(&f) < main(&r), "{:?} {:?}", main(&f), main(&r));
    for c in [&f, &r] {
        assert!(c.closed && c.manifold && c.self_intersections == 0);
        assert!(c.worst_section.as_ref().unwrap().relative < 1e-9);
    }
}

/// A fan of planes through one line (a rotational probe). Regression: the tagged kernel once
/// panicked or segfaulted here and then refused every wedge cell (22 fell back to the untagged
/// kernel), because the arrangement left one near-duplicate vertex per pair of planes where a
/// contour crosses the axis (`tests/bm_fan.rs`). Now every cell is tagged, every face conforms, and
/// the complex's boundary is a clean surface with its sections.
#[test]
fn a_fan_of_planes_runs_through_the_tagged_kernel() {
    use slice2solid::io::mesh::read_trimesh;
    use slice2solid::slice::{make_planes, slice_mesh, SliceMode};
    let m = read_trimesh(&common::shared_reference("eight_15")).unwrap();
    let sections = slice_mesh(&m, &make_planes(&m, 11, 0, SliceMode::Fan)).unwrap();
    let solid = slice2solid::reconstruct(&sections, &options()).unwrap();
    let count = |k: &str| solid.report.counts[k];
    eprintln!(
        "fan: untagged {} nonconforming {} singular edges {}",
        count("cells_untagged"),
        count("nonconforming_faces"),
        count("singular_edges")
    );
    assert_eq!(count("cells_untagged"), 0);
    assert_eq!(count("nonconforming_faces"), 0);
    assert_eq!(count("singular_edges"), 0);
    let (t, equal) = common::check_solid_tets(&solid);
    assert_eq!((t.inverted, t.flat), (0, 0));
    assert!(t.valid && t.conforming, "{t:?}");
    assert!(equal, "{t:?}");
    let c = slice2solid::eval::check::check_mesh(&solid.surface, Some(&sections));
    let worst = c.worst_section.as_ref().unwrap().relative;
    eprintln!(
        "fan surface: closed {} manifold {} crossings {} worst {worst:e}",
        c.closed, c.manifold, c.self_intersections
    );
    assert!(c.closed && c.manifold && c.oriented && c.self_intersection_free);
    assert!(worst < 1e-9, "{worst:e}");
}

/// Generated acquisitions (seed 5, written as CSL and read back like a user's file), where gaps at
/// singular edges once refused growth or, grown into by whole tetrahedra, pinched K far from the
/// edge: hand cut by 30 random planes kept 16 singular edges and 7 pinched vertices, by a fan of
/// 40 planes 20 and 6. Growth near the edges and by whole tetrahedra, in the better of both
/// orders, leaves no singular edge; with the untagged cells' flat tetrahedra out of the
/// triangulation (they made faces of 3 and 4 tetrahedra, so stars looked pinched) no pinched
/// vertex is left either, and the surface is still embedded (0 crossing pairs) with exact sections.
#[test]
fn generated_planes_leave_no_singular_edge() {
    use slice2solid::slice::SliceMode;
    // (mesh, mode, planes, pinched vertices at most, worst section at most). Elephant random 50
    // kept 2 overlapping pairs (flat folds) until `manifold::close_flat_folds`, and 37 flat-zone
    // triangles without a slab (0.30% of a section) until a refused slab tried the other side;
    // 7 are left (6.3e-5). Elephant sweep 300: 24 overlapping pairs, 67 triangles without slab
    // (6.3%) then; 24 left (8.9e-4).
    let cases = [
        ("hand", SliceMode::Random, 30, 0, 1e-5),
        ("hand", SliceMode::Fan, 40, 0, 1e-5),
        ("Elephant", SliceMode::Random, 50, 0, 7e-5),
        ("Elephant", SliceMode::Sweep, 300, 0, 1e-3),
    ];
    let mut failures = Vec::new();
    for (mesh, mode, planes, pinched, bound) in cases {
        let sections = common::sliced(mesh, planes, 5, mode);
        let solid = slice2solid::reconstruct(&sections, &options()).unwrap();
        let count = |k: &str| solid.report.counts[k];
        let got = (count("singular_edges"), count("singular_vertices"));
        let c = check_mesh(&solid.surface, Some(&sections));
        let worst = c.worst_section.as_ref().map_or(1.0, |w| w.relative);
        eprintln!("{mesh} {mode:?} {planes}: (singular edges, pinched) {got:?}, worst {worst:e}");
        if got.0 != 0 || got.1 > pinched {
            failures.push(format!("{mesh} {mode:?} {planes}: {got:?}"));
        }
        if c.self_intersections + c.overlapping_coplanar_pairs > 0 || worst > bound {
            failures.push(format!(
                "{mesh} {mode:?} {planes}: {} crossing, {} overlapping, worst section {worst:e}",
                c.self_intersections, c.overlapping_coplanar_pairs
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
