//! Sections of arbitrary orientation, the product's case: reference meshes cut by random planes
//! (`slice`, written as CSL and read back like a user's file), reconstructed and checked. Each result
//! must be a closed, oriented manifold without self-intersections whose sections agree with the input.
mod common;
use slice2solid::eval::check::check_mesh;
use slice2solid::io::{mesh::read_trimesh, read_sections, write_sections};
use slice2solid::slice::{make_planes, slice_mesh, SliceMode};
use slice2solid::Options;

/// The cases (`mesh: n planes, seed s`) whose result is not clean.
fn sweep(mesh: &str, plane_counts: &[usize], seeds: &[u64]) -> Vec<String> {
    let m = read_trimesh(&common::shared_reference(mesh)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let mut bad = Vec::new();
    for &n in plane_counts {
        for &seed in seeds {
            let planes = make_planes(&m, n, seed, SliceMode::Random);
            let path = dir.path().join(format!("{mesh}_{n}_{seed}.csl"));
            write_sections(&path, &slice_mesh(&m, &planes).unwrap()).unwrap();
            let sections = read_sections(&path).unwrap();
            let solid = slice2solid::reconstruct(&sections, &Options::default()).unwrap();
            let c = check_mesh(&solid.surface, Some(&sections));
            let worst = c.worst_section.as_ref().map_or(0.0, |w| w.relative);
            let ok =
                c.closed && c.manifold && c.oriented && c.self_intersection_free && worst < 0.02;
            eprintln!(
                "{mesh} {n} planes seed {seed}: closed {} manifold {} oriented {} crossings {} coplanar overlaps {} worst section {worst:.2e}",
                c.closed, c.manifold, c.oriented, c.self_intersections, c.overlapping_coplanar_pairs
            );
            if !ok {
                bad.push(format!("{mesh}: {n} planes, seed {seed}"));
            }
        }
    }
    bad
}

/// The hand cases that are not clean today (a listed expectation, like `KNOWN_UNCLEAN`). 12
/// planes seed 2 had 2 overlapping near-coplanar pairs (the walls of a flat crack that meets no
/// edge where they fold onto each other) until growth that leaves double sheets was tried again
/// at a fraction of each edge (`bm::singular::Reach`, session 38). 8 planes seed 1 (8 pairs: a
/// crack whose filling left a singular simplex) is clean since the fold closing repairs such a
/// filling with the toggles.
/// No case has an exact crossing and every section is within 1e-9. (5 planes, seeds 2 and 3,
/// kept a pinched vertex each until `carve`; 8 planes seed 3 is clean since growth refuses
/// sliver children.)
/// 12 planes seed 1 kept a pinched vertex from session 36 (when the gaps between a flat zone's
/// prisms were closed) to 39: the singular resolution's growth left it at a contour vertex of
/// plane 2 whose cones cannot be carved, and the collar at the vertex's lifted copy; clean since
/// pinches on no plane are carved after the collar (`bm::carve::carve_off_planes`, session 40).
const KNOWN_UNCLEAN_HAND: &[&str] = &[];

#[test]
fn hand_cut_by_random_planes() {
    let bad = sweep("hand", &[3, 5, 8, 12], &[1, 2, 3]);
    assert_eq!(
        bad, KNOWN_UNCLEAN_HAND,
        "unclean cases (update the list when one is fixed)"
    );
}

#[test]
fn figure_eight_cut_by_random_planes() {
    let bad = sweep("eight_15", &[3, 5, 8, 12], &[1, 2, 3]);
    assert!(bad.is_empty(), "{bad:?}");
}

/// The cases of `many_random_planes` that are not clean today: a listed expectation, so that both a
/// fix (a case leaves the list: remove it here) and a regression (a case joins it) fail the test.
/// None today: Elephant 20 planes, seed 5, left the list with `carve`, the four balloondog_box
/// cases when growth stopped keeping sliver children, balloondog 30 planes, seed 5 (a singular edge
/// over a section whose regions touch at a vertex) with the saddle bridges of `singular`'s
/// `OffPlane` growth. With the first pipeline (each cell glued, since removed) 8 cases kept 3–15
/// exact crossings instead.
const KNOWN_UNCLEAN: &[&str] = &[];

/// With 20 or 30 random planes, all 20 cases are clean (`KNOWN_UNCLEAN`).
#[test]
fn many_random_planes() {
    let bad: Vec<String> = [
        "hand",
        "eight_15",
        "balloondog",
        "balloondog_box",
        "Elephant",
    ]
    .iter()
    .flat_map(|m| sweep(m, &[20, 30], &[4, 5]))
    .collect();
    assert_eq!(
        bad, KNOWN_UNCLEAN,
        "unclean cases (update KNOWN_UNCLEAN when one is fixed)"
    );
}
