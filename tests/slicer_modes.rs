//! Every acquisition the slicer makes (`slice --mode`: fan, sweep, tilt, parallel, axes, random),
//! sparse and denser, on shared reference meshes (seed 5, written as CSL and read back like a
//! user's file). The solid must be a closed oriented manifold with no crossing and no overlapping
//! triangle pair (exact `check`), every section within `SECTION_BOUND` of the input (or its pin in
//! `SECTION_PINS`), and the
//! tetrahedral mesh valid (conforming, nothing inverted or flat) with the surface as its boundary.
//! Cases that are not clean yet are listed in `KNOWN_UNCLEAN` and asserted still unclean, so the
//! list cannot go stale.
mod common;
use slice2solid::eval::check::check_mesh;
use slice2solid::slice::SliceMode;

/// Worst relative section difference allowed (today: at most 6.3e-10 over these cases but the
/// listed ones).
const SECTION_BOUND: f64 = 2e-9;

/// Cases whose sections are not exact yet, with the bound pinned near today's value: the hand cut
/// by 200 axis-aligned planes misses 2.72e-3 of a section (42 flat-zone triangles left without a
/// slab). Before the collar also the figure eight cut by 40
/// axis-aligned planes (6.8e-4) and by 30 random planes (1.8e-5).
const SECTION_PINS: [(&str, SliceMode, usize, f64); 1] = [("hand", SliceMode::Axes, 200, 2.8e-3)];

/// (mesh, mode, planes) not clean today, and why: none. balloondog by 30 random planes left the
/// list when its singular edge, over a vertex where two regions of a section touch, got a saddle
/// bridge (`singular`'s `OffPlane` growth).
const KNOWN_UNCLEAN: [(&str, SliceMode, usize); 0] = [];

/// What is wrong with the reconstruction of `mesh` cut by `planes` planes of `mode` (empty: clean).
fn problems(mesh: &str, mode: SliceMode, planes: usize) -> Vec<String> {
    problems_and_solid(mesh, mode, planes).0
}

/// [`problems`], and the solid.
fn problems_and_solid(
    mesh: &str,
    mode: SliceMode,
    planes: usize,
) -> (Vec<String>, slice2solid::Solid) {
    problems_and_solid_seeded(mesh, mode, planes, 5)
}

/// [`problems_and_solid`] with the slicer's `seed`.
fn problems_and_solid_seeded(
    mesh: &str,
    mode: SliceMode,
    planes: usize,
    seed: u64,
) -> (Vec<String>, slice2solid::Solid) {
    let sections = common::sliced(mesh, planes, seed, mode);
    let solid = slice2solid::reconstruct(&sections, &Default::default())
        .unwrap_or_else(|e| panic!("{mesh} {mode:?} {planes}: {e}"));
    let c = check_mesh(&solid.surface, Some(&sections));
    let worst = c.worst_section.as_ref().map_or(1.0, |w| w.relative);
    let (t, equal) = common::check_solid_tets(&solid);
    eprintln!(
        "{mesh} {mode:?} {planes}: closed {} manifold {} crossings {} overlaps {} worst {worst:e} tets valid {} boundary = surface {equal}",
        c.closed, c.manifold, c.self_intersections, c.overlapping_coplanar_pairs, t.valid
    );
    let mut out = Vec::new();
    if !(c.closed && c.manifold && c.oriented) {
        out.push(format!(
            "closed {} manifold {} oriented {}",
            c.closed, c.manifold, c.oriented
        ));
    }
    if c.self_intersections + c.overlapping_coplanar_pairs > 0 {
        out.push(format!(
            "{} crossing, {} overlapping pairs",
            c.self_intersections, c.overlapping_coplanar_pairs
        ));
    }
    let bound = SECTION_PINS
        .iter()
        .find(|p| (p.0, p.1, p.2) == (mesh, mode, planes))
        .map_or(SECTION_BOUND, |p| p.3);
    if worst > bound {
        out.push(format!("worst section {worst:e}"));
    }
    if !t.valid || !equal {
        out.push(format!("tets valid {} boundary = surface {equal}", t.valid));
    }
    (out, solid)
}

fn run(cases: &[(&str, SliceMode, usize)]) {
    let mut failures = Vec::new();
    for &(mesh, mode, planes) in cases {
        let p = problems(mesh, mode, planes);
        let known = KNOWN_UNCLEAN.contains(&(mesh, mode, planes));
        match (p.is_empty(), known) {
            (false, false) => failures.push(format!("{mesh} {mode:?} {planes}: {p:?}")),
            (true, true) => failures.push(format!(
                "{mesh} {mode:?} {planes} is clean now: take it off KNOWN_UNCLEAN"
            )),
            _ => {}
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

const MODES: [SliceMode; 5] = [
    SliceMode::Fan,
    SliceMode::Sweep,
    SliceMode::Tilt,
    SliceMode::Parallel,
    SliceMode::Axes,
];

fn every_mode(mesh: &'static str) -> Vec<(&'static str, SliceMode, usize)> {
    let mut cases: Vec<(&str, SliceMode, usize)> = MODES
        .iter()
        .flat_map(|&m| [(mesh, m, 16), (mesh, m, 40)])
        .collect();
    cases.extend([(mesh, SliceMode::Random, 10), (mesh, SliceMode::Random, 30)]);
    cases
}

#[test]
fn the_figure_eight_under_every_mode() {
    run(&every_mode("eight_15"));
}

#[test]
fn the_balloon_dog_under_every_mode() {
    run(&every_mode("balloondog"));
}

#[test]
fn the_hand_under_the_probe_modes() {
    run(&[
        ("hand", SliceMode::Fan, 40),
        ("hand", SliceMode::Sweep, 40),
        ("hand", SliceMode::Tilt, 40),
    ]);
}

/// A dense grid of axis-aligned planes (100: about 33 per axis), where contour points of one flat
/// triangle of the mesh on several planes are coplanar up to rounding: no cell may fall back to
/// the untagged kernel (the star test once refused them: 29 cells) and ∂K is clean (a kept
/// tetrahedron flat up to rounding on a cell's hull blocked the growth at a pinched vertex until
/// such tetrahedra were taken out).
#[test]
fn the_balloon_dog_on_a_dense_axis_grid() {
    let (problems, solid) = problems_and_solid("balloondog", SliceMode::Axes, 100);
    assert!(problems.is_empty(), "{problems:?}");
    let count = |k: &str| solid.report.counts.get(k).copied();
    assert_eq!(count("cells_untagged"), Some(0));
    assert_eq!(count("singular_vertices"), Some(0));
}

/// The hand cut by 200 axis-aligned planes: two singular edges were left where carving a cone only
/// moved the singularity to its cap's edge; carving is now judged after growth rounds there.
#[test]
fn the_hand_on_a_denser_axis_grid() {
    run(&[("hand", SliceMode::Axes, 200)]);
}

/// The boxed balloon dog cut by 40 axis-aligned planes: a side of the box is a straight contour
/// stretch whose slicer vertices zig-zag by ulps, so three consecutive ones made a section
/// triangle of area 1e-18 whose side of the contour was rounding noise; the flat tetrahedra kept
/// on it folded ∂K onto itself (one overlapping pair with seeds 1-4, 6, 7, 11-13; seed 5 was
/// clean). Validation now removes contour vertices on their neighbours' segment within rounding
/// (warned); the slicer's output goes through it, as does every reader's (unit tests in
/// `validate`).
#[test]
fn the_boxed_balloon_dog_on_an_axis_grid() {
    let (problems, _) = problems_and_solid_seeded("balloondog_box", SliceMode::Axes, 40, 1);
    assert!(problems.is_empty(), "{problems:?}");
}

/// The figure eight cut by a freehand sweep of 100 frames (seed 3): adjacent frames cross near
/// the object, and a contour vertex was left pinched between a wide gap below its plane and a
/// gap above it whose growth made a sliver child (near-duplicate split points of earlier
/// rounds). Growth kept the wide gap open and was refused in the other; now a simplex whose
/// every growth is refused is tried again with another gap left open (`singular::grow_round`).
#[test]
fn the_figure_eight_on_a_sweep_of_100_frames() {
    let (problems, solid) = problems_and_solid_seeded("eight_15", SliceMode::Sweep, 100, 3);
    assert!(problems.is_empty(), "{problems:?}");
    assert_eq!(
        solid.report.counts.get("singular_vertices").copied(),
        Some(0)
    );
}

/// Elephant cut by a freehand sweep of 300 frames (seed 1): one singular edge was left on a
/// frame, from a vertex on its line with the next frame out, with a kept cone on each side of the
/// frame (a checkerboard inside its section). Both gaps touch the next frame outside its section,
/// so only growth off the planes may close one, and it had left whole the gap's edge on the first
/// frame (inside its section): no part of the gap near the edge avoided the line
/// (`singular::OnPlaneEdges`).
#[test]
fn the_elephant_on_a_sweep_of_300_frames() {
    let (problems, solid) = problems_and_solid_seeded("Elephant", SliceMode::Sweep, 300, 1);
    assert!(problems.is_empty(), "{problems:?}");
    assert_eq!(solid.report.counts.get("singular_edges").copied(), Some(0));
}
