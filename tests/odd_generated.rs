//! Inputs of the odd-sections generator (`slice::odd`, seeds `0..SEEDS`): random planes in
//! parallel families, axis planes, planes through the origin and random directions, with
//! star-shaped contours at scales 1e-5 to 0.5 that disagree along most common lines. The shared
//! `data/odd` files came from such a generator; this one found three classes of failure in the
//! engine (rows of collinear trim vertices across regions and stretches, near-duplicate shared
//! samples, overhangs the snapping could not pair). Every valid one must come out a closed,
//! oriented manifold without crossings or double sheets, every section within 2% of the input's
//! (exact `check`); the ones that do not yet are listed with their defects at most, and a listed
//! seed that becomes clean, or a clean one that regresses, fails here (move it between the lists).
mod bm_common;
use slice2solid::eval::check::check_mesh;
use slice2solid::io::json::parse_json;
use slice2solid::slice::odd::odd_sections_json;
use slice2solid::Options;

const SEEDS: u64 = 40;

/// Seeds refused with an input error: the reader's (two planes of a family at one offset) or the
/// engine's (every plane empty).
const REFUSED: [u64; 5] = [15, 20, 27, 29, 30];

/// Not clean today: (seed, non-manifold edges, non-manifold vertices, overlapping near-coplanar
/// pairs, vertex pairs closer than `CLOSE` of the diagonal) at most. What is left: singular
/// simplices the resolution inside the complex cannot remove beside slabs of flat zones, and
/// double sheets of slab tops (docs/design/conforming-complex.md, sessions 30-32). Of seeds
/// 0..120, 92 of 111 valid inputs are clean, none with an exact crossing (80 at 2342426, which
/// also segfaulted on seed 3). Seed 32's double sheets went 85 -> 89 when split points were
/// spaced (`bm::spacing`), its near-duplicate vertices 215 -> 3. Since the pieces of split contour
/// edges are guarded (`bm::guard`, session 35), which changes the samples next to them, 93 of the
/// 111 are clean: seed 16 (37 double sheets) is; 17 went (2, 4, 72, 1) -> (2, 5, 19, 0), 32
/// (3, 6, 89, 3) -> (2, 3, 24, 5). Since the gaps between a flat zone's prisms are closed
/// (`bm::slab::gaps`, session 36), 95 of the 111 are: seed 17 is clean, 1 (1, 2, 1, 4) and 32
/// are closed manifolds with double sheets ((0, 0, 287, 1), (0, 0, 7, 0)), and seed 28 went
/// from clean to 63 double sheets that the singular resolution's growth folds beside its slab.
/// Since growth that leaves double sheets is tried again with the edges split at a fraction of
/// their length (`bm::singular::Reach`, session 38), seeds 28 and 32 are clean.
const KNOWN: [(u64, usize, usize, usize, usize); 2] = [(1, 0, 0, 287, 1), (37, 0, 1, 0, 0)];

/// Vertices closer than this fraction of the diagonal count as near-duplicates: a clean output
/// has none. Split points are kept 1e-8 of the diagonal apart (`bm::spacing`); before they were,
/// seeds 0..40 had 290 such pairs (seed 16: 70, seed 32: 215), 1e-11 apart at worst.
const CLOSE: f64 = 5e-9;

const SECTION_BOUND: f64 = 0.02;

/// Seeds beyond `SEEDS` that each showed a cause of failure, now fixed: each must be free of it
/// (closed, oriented manifold, no crossing, sections within the bound), with at most the listed
/// double sheets of slab tops and near-duplicate vertex pairs (the causes of `KNOWN`).
/// 117: plane 7 overhung plane 6's material on their line by 1.1e-3 (within the snap
/// tolerance), but plane 0 crosses the line between the two ends, so the arrangement could not
/// snap them and the trim had deferred the overhang to it: a singular edge on the line.
/// 45: two cells of a face inserted different points on it (one lost a contour edge to the other
/// side's samples and kept its run without them): a non-conforming face, 37 exact crossings.
/// Clean from session 30 to 34; since split contour edges are guarded (session 35) 27 double
/// sheets of slab tops and one near-duplicate vertex pair (the classes of `KNOWN`); 13 and none
/// since the gaps between a zone's prisms are closed (session 36); 15 since a singular simplex
/// whose growth was refused is grown into with another gap left open (session 37); none since
/// growth that leaves double sheets is tried again at a fraction of each edge (session 38).
/// 93: the collar's prisms left a pinched vertex at a lifted point (on no plane), where two cones
/// touched; clean since such simplices are carved after the collar (session 40).
/// 110: a singular edge on a plane, from a vertex on its line with another plane, with a kept
/// cone on each side (a checkerboard) and both gaps on the other plane outside its section; clean
/// since growth off the planes splits the gap's edges on a plane inside its section (session 41).
const FIXED: [(u64, usize, usize); 4] = [(45, 0, 0), (93, 0, 0), (110, 0, 0), (117, 0, 0)];

/// What one seed gives: refused with an input error, or checked (report, worst section).
enum Outcome {
    Refused(String),
    Checked(Box<slice2solid::eval::check::CheckReport>, f64, usize),
}

fn run(seed: u64) -> Result<Outcome, String> {
    let name = format!("odd seed {seed}");
    let sections = match parse_json(&odd_sections_json(seed), &name) {
        Ok(s) => s,
        Err(e) => return Ok(Outcome::Refused(e.to_string())),
    };
    let solid = match slice2solid::reconstruct(&sections, &Options::default()) {
        Ok(s) => s,
        // every plane empty: nothing to bound the arrangement with
        Err(e @ slice2solid::Error::Input { .. }) => return Ok(Outcome::Refused(e.to_string())),
        Err(e) => return Err(format!("{name}: reconstruct failed: {e}")),
    };
    let c = check_mesh(&solid.surface, Some(&sections));
    let worst = c.worst_section.as_ref().map_or(0.0, |w| w.relative);
    let close = bm_common::close_vertex_pairs(&solid.surface, CLOSE);
    Ok(Outcome::Checked(Box::new(c), worst, close))
}

fn is_clean(c: &slice2solid::eval::check::CheckReport, worst: f64, close: usize) -> bool {
    is_clean_but(c, worst, close, 0, 0)
}

/// [`is_clean`], allowing up to `double_sheets` overlapping near-coplanar pairs and
/// `near_duplicates` close vertex pairs.
fn is_clean_but(
    c: &slice2solid::eval::check::CheckReport,
    worst: f64,
    close: usize,
    double_sheets: usize,
    near_duplicates: usize,
) -> bool {
    close <= near_duplicates
        && c.closed
        && c.manifold
        && c.oriented
        && c.self_intersections == 0
        && c.overlapping_coplanar_pairs <= double_sheets
        && worst <= SECTION_BOUND
}

#[test]
fn generated_odd_inputs_are_clean_or_listed() {
    let mut problems = Vec::new();
    let mut refused = Vec::new();
    for seed in 0..SEEDS {
        let name = format!("odd seed {seed}");
        let (c, worst, close) = match run(seed) {
            Ok(Outcome::Checked(c, worst, close)) => (c, worst, close),
            Ok(Outcome::Refused(e)) => {
                refused.push(seed);
                if !REFUSED.contains(&seed) {
                    problems.push(format!("{name}: refused: {e}"));
                }
                continue;
            }
            Err(e) => {
                problems.push(e);
                continue;
            }
        };
        let clean = is_clean(&c, worst, close);
        let measured = format!(
            "({seed}, {}, {}, {}, {close}) crossings {} worst section {worst:.2e}",
            c.nonmanifold_edges,
            c.nonmanifold_vertices,
            c.overlapping_coplanar_pairs,
            c.self_intersections
        );
        match KNOWN.iter().find(|k| k.0 == seed) {
            None if !clean => problems.push(format!("{name}: not clean: {measured}")),
            None => {}
            Some(_) if clean => problems.push(format!("{name}: clean now, unlist it: {measured}")),
            Some(&(_, edges, vertices, overlaps, near_duplicates)) => {
                let worse = c.self_intersections > 0
                    || close > near_duplicates
                    || c.nonmanifold_edges > edges
                    || c.nonmanifold_vertices > vertices
                    || c.overlapping_coplanar_pairs > overlaps
                    || worst > SECTION_BOUND;
                if worse {
                    problems.push(format!("{name}: worse than listed: {measured}"));
                }
            }
        }
    }
    if refused != REFUSED {
        problems.push(format!("refused seeds {refused:?}, listed {REFUSED:?}"));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_fixed_seeds_stay_clean() {
    for (seed, double_sheets, near_duplicates) in FIXED {
        match run(seed) {
            Ok(Outcome::Checked(c, worst, close)) => {
                assert!(
                    is_clean_but(&c, worst, close, double_sheets, near_duplicates),
                    "odd seed {seed}: {c:?} worst {worst} close pairs {close}"
                )
            }
            Ok(Outcome::Refused(e)) => panic!("odd seed {seed}: refused: {e}"),
            Err(e) => panic!("{e}"),
        }
    }
}
