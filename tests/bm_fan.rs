//! Rotational fans (`slice --mode fan`: planes through one axis, a rotational probe or radial MRI),
//! from the arrangement to the solid.
//!
//! The planes' equations are rounded, so no three of them pass exactly through one line; the
//! arrangement merges their pairwise meeting points into the two ends of the axis, and a pencil is
//! then known combinatorially. Regression (before: every wedge cell fell back to the untagged
//! kernel, hand cut by 40 such planes segfaulted in the tagged kernel, 16 planes took over ten
//! minutes in glue): a contour crossing the axis made one pool vertex per pair of planes, ulps
//! apart, each tagged with two planes only, and diagram samples landed on the axis (a grid line
//! along the face side) tagged with their own plane only.
mod common;
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use slice2solid::bm::{cell_input::CellInput, conform};
use slice2solid::delaunay::Delaunay;
use slice2solid::eval::check::check_mesh;
use slice2solid::slice::SliceMode;
use slice2solid::{Options, Sections};

/// The mesh cut by `planes` fan planes (seed 5), written as CSL and read back like a user's file.
fn fan(mesh: &str, planes: usize) -> Sections {
    common::sliced(mesh, planes, 5, SliceMode::Fan)
}

/// Every point where a contour crosses the axis is ONE pool vertex on every plane of the fan, and
/// no two pool vertices are closer than the arrangement's merge tolerance.
#[test]
fn a_contour_crosses_the_axis_at_one_vertex_on_every_plane() {
    let s = fan("hand", 16);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    let n = s.sections.len() as u32;
    let on_all = |v: usize| (0..n).all(|i| arr.pool.tags[v].contains(&i));
    let axis: Vec<usize> = (0..arr.pool.positions.len())
        .filter(|&v| on_all(v))
        .collect();
    // the two ends of the axis in the box, and the two points where the hand's surface crosses it
    assert_eq!(axis.len(), 4, "{axis:?}");
    let (close, tol) = close_pool_pairs(&arr);
    assert_eq!(close, 0, "pool vertices closer than {tol:e}");
}

/// How many pairs of pool vertices lie closer than the arrangement's merge tolerance, and that
/// tolerance.
fn close_pool_pairs(arr: &Arrangement) -> (usize, f64) {
    let diag = {
        let (lo, hi) = arr.pool.positions.iter().fold(
            ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                (
                    std::array::from_fn(|k| lo[k].min(p[k])),
                    std::array::from_fn(|k| hi[k].max(p[k])),
                )
            },
        );
        (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
    };
    let tol = ArrangementOptions::default().merge_tolerance * diag;
    let mut sorted: Vec<(usize, [f64; 3])> =
        arr.pool.positions.iter().copied().enumerate().collect();
    sorted.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]));
    let mut close = 0;
    for (k, &(_, p)) in sorted.iter().enumerate() {
        for &(_, q) in sorted[k + 1..]
            .iter()
            .take_while(|(_, q)| q[0] - p[0] < tol)
        {
            let d2: f64 = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum();
            close += (d2 < tol * tol) as usize;
        }
    }
    (close, tol)
}

/// The tagged kernel triangulates every wedge cell's section points (none falls back), validly.
#[test]
fn the_tagged_kernel_takes_every_wedge_cell() {
    let s = fan("eight_15", 16);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    let loops = conform::face_loops(&arr, &conform::Splits::default());
    let cells: Vec<CellInput> = (0..arr.cells.len() as u32)
        .filter_map(|c| CellInput::build(&arr, &arr.pool, &loops, c))
        .filter(|c| c.mask.iter().fold(!0u128, |a, &m| a & m) == 0 && c.points.len() >= 4)
        .collect();
    assert_eq!(cells.len(), 32);
    for (k, c) in cells.iter().enumerate() {
        let dt = Delaunay::try_new_tagged_with(&c.points, &c.tags, &c.apexes)
            .unwrap_or_else(|e| panic!("cell {k} ({} points): {e}", c.points.len()));
        // the validator re-derives every face's 2D Delaunay triangulation: a few cells suffice
        if k % 8 == 0 {
            dt.is_valid().unwrap();
        }
    }
}

/// Hand and figure-eight cut by 16 and 40 fan planes: closed, oriented, manifold, no crossing, every
/// section within 1e-9 of the input (today at most 1.1e-10; 4.5e-5 before the conforming complex
/// became the default), few cells untagged, in seconds.
#[test]
fn fans_reconstruct_clean() {
    let mut failures = Vec::new();
    for (mesh, n, untagged, genus) in [
        ("hand", 16, 0, 18),
        ("hand", 40, 0, 10),
        ("eight_15", 16, 0, 2),
    ] {
        let s = fan(mesh, n);
        let t = std::time::Instant::now();
        let solid = slice2solid::reconstruct(&s, &Options::default()).unwrap();
        let secs = t.elapsed().as_secs_f64();
        let c = check_mesh(&solid.surface, Some(&s));
        let worst = c.worst_section.as_ref().unwrap().relative;
        eprintln!(
            "{mesh} fan {n}: {secs:.2} s, closed {} manifold {} oriented {} crossings {} overlaps {} \
             worst section {worst:.2e} components {} genus {} untagged {}",
            c.closed,
            c.manifold,
            c.oriented,
            c.self_intersections,
            c.overlapping_coplanar_pairs,
            c.components,
            c.genus,
            solid.report.counts["cells_untagged"]
        );
        assert!(c.closed && c.manifold && c.oriented, "{mesh} fan {n}");
        assert_eq!((c.self_intersections, c.overlapping_coplanar_pairs), (0, 0));
        assert!(worst < 2e-9, "{mesh} fan {n}: worst section {worst:e}");
        // topology is issue 19's (the hand's reference genus is 5): pinned so that a change shows
        let got = (solid.report.counts["cells_untagged"], c.genus);
        if got != (untagged, genus) {
            failures.push(format!(
                "{mesh} fan {n}: (untagged, genus) {got:?}, pinned {:?}",
                (untagged, genus)
            ));
        }
        // before: over 300 s; today 0.6–3.7 s on a shared 2-core machine (a loose bound: noisy)
        assert!(secs < 30.0, "{mesh} fan {n}: {secs:.1} s");
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A contour edge that a cell's diagram samples take away is split and both cells of its face run
/// again; the pieces are guarded (`bm::guard`), so the next run keeps them. Before, the halves were
/// taken away again round after round: Elephant cut by 40 fan planes ran 7 rounds of conformity
/// (160 cell runs, 84 Steiner points, 2.3 s); now 3 rounds, 124 runs, 52 points.
#[test]
fn split_contour_edges_are_kept_by_the_next_run() {
    let s = fan("Elephant", 40);
    let solid = slice2solid::reconstruct(&s, &Options::default()).unwrap();
    let n = |k: &str| solid.report.counts[k];
    assert_eq!(
        (n("conformity_rounds"), n("cell_runs"), n("steiner_points")),
        (3, 124, 52)
    );
    // its one untagged cell triangulates every face as its neighbours do: no second run in
    // generic position (it doubled the time, 1.7 -> 3.5 s, before the retry asked for a face
    // triangulated differently)
    assert_eq!((n("cells_untagged"), n("nonconforming_faces")), (1, 0));
    let retried = [
        "generic_position_retries_not_kept",
        "generic_position_vertices_moved",
    ];
    assert!(retried
        .iter()
        .all(|k| !solid.report.counts.contains_key(*k)));
    let c = check_mesh(&solid.surface, Some(&s));
    assert!(c.closed && c.manifold && c.oriented);
    assert_eq!((c.self_intersections, c.overlapping_coplanar_pairs), (0, 0));
}

/// The middle layer of `slice::synthetic::stacked_cylinder` (a 24-gon prism) cut by `planes` fan
/// planes whose axis crosses its wall on a vertical edge: every section has a vertex on the axis,
/// each rounded 1e-16 to one side of it by the slicer.
fn cylinder_fan(planes: usize, seed: u64) -> Sections {
    use slice2solid::slice::{
        make_planes, slice_partition, synthetic::stacked_cylinder, union_mesh,
    };
    let case = stacked_cylinder();
    let fan = make_planes(&union_mesh(&case.meshes), planes, seed, SliceMode::Fan);
    let s = slice_partition(&case.meshes[1..2], &fan).unwrap();
    let csl = slice2solid::io::csl::to_csl_string(&s);
    slice2solid::io::csl::parse_csl(&csl, "cylinder fan").unwrap()
}

/// A section vertex that the slicer put 1e-16 beside the axis is the axis vertex (one pool vertex
/// on every plane), not a vertex beside the point where its own edge crosses the axis: that micro
/// edge made 13 of the 16 wedge cells fall back to the untagged kernel, 12 faces non-conforming,
/// 8,344 conformity Steiner points and 111 singular edges.
#[test]
fn a_section_vertex_beside_the_axis_is_the_axis_vertex() {
    let s = cylinder_fan(8, 5);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    let (close, tol) = close_pool_pairs(&arr);
    assert_eq!(close, 0, "pool vertices closer than {tol:e}");
    let n = s.sections.len() as u32;
    let on_all = (0..arr.pool.positions.len())
        .filter(|&v| (0..n).all(|i| arr.pool.tags[v].contains(&i)))
        .count();
    // the two ends of the axis in the box, and where it crosses the cylinder's wall
    assert_eq!(on_all, 4);
}

/// Solids symmetric about a fan's axis: the cylinder above under fans through a vertex of every
/// section, and the shipped `nested_fan.csl`
/// (a core ball in a shell, as one material). Mirror-image points on two planes through one line
/// are exactly cospherical, which the tagged kernel cannot decide (`delaunay::tags`): such cells
/// were triangulated untagged, their faces differed from the neighbours' (cylinder fan 8: 1 cell,
/// 2 non-conforming faces, 6 singular edges, 2 pinched vertices; fan 16: 1, 1, 1, 2; nested_fan
/// 2 cells, 3 singular edges; a sphere STL under 24 to 40 fan planes too). The
/// pipeline now moves the contour vertices to generic position in their planes (1e-10 of the
/// diagonal, `validate::move_to_generic_position`) and runs again: (case, vertices moved, 0 when
/// no retry was needed), every one clean with every section within 1e-9.
#[test]
fn solids_symmetric_about_a_fans_axis_are_moved_to_generic_position() {
    let nested = {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/nested_fan.csl");
        slice2solid::io::read_sections(&path).unwrap()
    };
    let cases = [
        ("cylinder fan 6 seed 1", cylinder_fan(6, 1), 0),
        ("cylinder fan 8 seed 5", cylinder_fan(8, 5), 73),
        ("cylinder fan 16 seed 5", cylinder_fan(16, 5), 149),
        ("cylinder fan 40 seed 5", cylinder_fan(40, 5), 371),
        ("nested_fan.csl", nested, 908),
    ];
    let mut failures = Vec::new();
    for (name, s, moved) in cases {
        let solid = slice2solid::reconstruct(&s, &Options::default()).unwrap();
        let c = check_mesh(&solid.surface, Some(&s));
        let n = |k: &str| solid.report.counts.get(k).copied().unwrap_or(0);
        let worst = c.worst_section.as_ref().unwrap().relative;
        eprintln!(
            "{name}: moved {}, untagged {}, worst section {worst:.2e}",
            n("generic_position_vertices_moved"),
            n("cells_untagged")
        );
        let clean = c.closed && c.manifold && c.oriented;
        let crossings = (c.self_intersections, c.overlapping_coplanar_pairs);
        if !clean || crossings != (0, 0) || worst >= 1e-9 {
            failures.push(format!("{name}: {c:?}"));
        }
        let got = (
            n("cells_untagged"),
            n("nonconforming_faces"),
            n("generic_position_vertices_moved"),
        );
        if got != (0, 0, moved) {
            failures.push(format!(
                "{name}: (untagged, non-conforming faces, moved) {got:?}, pinned {:?}",
                (0, 0, moved)
            ));
        }
        let warned = (solid.report.warnings.iter()).any(|w| w.contains("generic position"));
        if warned != (moved > 0) {
            failures.push(format!("{name}: warning {warned}, moved {moved}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
