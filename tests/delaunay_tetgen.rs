//! Oracle tests: our kernel against TetGen (feature `tetgen`). In general position the two
//! triangulations are unique and must be equal; on degenerate input (cospherical, cocircular,
//! coplanar points) each breaks ties its own way, so both outputs go through the same exact
//! validator (`delaunay_check::check_tets`) and must span the same hull volume.
#![cfg(feature = "tetgen")]
mod common;
mod delaunay_check;
use common::shared_dir;
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use slice2solid::bm::{cell_input::CellInput, conform};
use slice2solid::delaunay::{gen, tetgen::tetgen_delaunay, Delaunay};
use slice2solid::io::read_sections;

fn sorted(mut tets: Vec<[u32; 4]>) -> Vec<[u32; 4]> {
    for t in tets.iter_mut() {
        t.sort_unstable();
    }
    tets.sort_unstable();
    tets
}

#[test]
fn tetgen_equals_ours_in_general_position() {
    for (n, seed) in [(10, 1), (100, 2), (5000, 3)] {
        let pts = gen::uniform(n, seed);
        let dt = Delaunay::new(&pts);
        let ours = sorted(dt.tets().map(|t| dt.tet_vertices(t)).collect());
        let raw = tetgen_delaunay(&pts).unwrap();
        delaunay_check::check_tets(&pts, &raw, true);
        let theirs = sorted(raw);
        assert_eq!(ours.len(), theirs.len(), "n = {n}");
        assert!(ours == theirs, "tetrahedra differ for n = {n}");
    }
}

/// Ours and TetGen's tetrahedra of `pts` through the same validator; both must pass and span the
/// same volume (the hull's, up to rounding). Returns the two tet counts (tie-breaking may differ).
fn both_valid(what: &str, pts: &[[f64; 3]]) -> (usize, usize) {
    let dt = Delaunay::try_new(pts).unwrap_or_else(|e| panic!("{what}: ours failed: {e}"));
    let ours: Vec<[u32; 4]> = dt.tets().map(|t| dt.tet_vertices(t)).collect();
    let full = dt.dimension() == 3;
    let theirs = tetgen_delaunay(pts).unwrap_or_else(|e| panic!("{what}: TetGen failed: {e}"));
    let a = delaunay_check::check_tets(pts, &ours, full);
    let b = delaunay_check::check_tets(pts, &theirs, full);
    assert!(
        (a.volume - b.volume).abs() <= 1e-12 * a.volume.abs().max(b.volume.abs()),
        "{what}: our volume {} != TetGen's {}",
        a.volume,
        b.volume
    );
    (a.tets, b.tets)
}

/// Every integer point on the sphere x² + y² + z² = n: exactly cospherical, massively cocircular
/// (n = 1454 has 720 such points, the most below 1500).
fn integer_sphere(n: i64) -> Vec<[f64; 3]> {
    let r = (n as f64).sqrt() as i64 + 1;
    let mut pts = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            for z in -r..=r {
                if x * x + y * y + z * z == n {
                    pts.push([x as f64, y as f64, z as f64]);
                }
            }
        }
    }
    pts
}

/// The integer points of the circle x² + y² = n (n = 19825 has 48) on `layers` planes z = 0, 7, 14, ...:
/// a cylinder whose rings are exactly cocircular and any two rings exactly cospherical.
fn integer_cylinder(n: i64, layers: usize) -> Vec<[f64; 3]> {
    let ring: Vec<[f64; 3]> = integer_sphere(n)
        .into_iter()
        .filter(|p| p[2] == 0.0)
        .collect();
    (0..layers)
        .flat_map(|z| ring.iter().map(move |p| [p[0], p[1], z as f64 * 7.0]))
        .collect()
}

/// Coplanar subsets among random points: a 12×12 lattice on each of three planes, plus 200 uniform
/// points in between.
fn lattice_planes_and_noise() -> Vec<[f64; 3]> {
    let mut pts = gen::uniform(200, 17);
    for z in [0.0, 0.5, 1.0] {
        for i in 0..12 {
            for j in 0..12 {
                pts.push([i as f64 / 11.0, j as f64 / 11.0, z]);
            }
        }
    }
    pts
}

#[test]
fn tetgen_and_ours_pass_the_validator_on_degenerate_sets() {
    let sets: [(&str, Vec<[f64; 3]>); 9] = [
        ("lattice 8", gen::lattice(8)),
        ("circles 6x30", gen::circles(6, 30)),
        ("integer sphere 1454", integer_sphere(1454)),
        ("integer cylinder 19825 x 10", integer_cylinder(19825, 10)),
        ("lattice planes and noise", lattice_planes_and_noise()),
        ("40 planes", gen::on_planes(3000, 40, 4)),
        ("cube faces", gen::cube_faces(2000, 5)),
        ("polytope faces", gen::polytope_faces(1000, 20, 6)),
        ("uniform 2000", gen::uniform(2000, 7)),
    ];
    for (what, pts) in &sets {
        let (ours, theirs) = both_valid(what, pts);
        println!(
            "{what}: {} points, ours {ours} tets, TetGen {theirs}",
            pts.len()
        );
    }
}

/// The contour vertices of the cells of a shared CSL file, as the pipeline first triangulates them
/// (cf. `benches/reconstruct.rs`); any error fails with the path.
fn cell_point_sets(name: &str) -> Vec<Vec<[f64; 3]>> {
    let path = shared_dir().join(format!("data/csl/{name}.csl"));
    let sections = read_sections(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let arr = Arrangement::build(&sections, &ArrangementOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let loops = conform::face_loops(&arr, &conform::Splits::default());
    (0..arr.cells.len() as u32)
        .filter_map(|c| CellInput::build(&arr, &arr.pool, &loops, c))
        .map(|i| i.points)
        .filter(|p| p.len() >= 4)
        .collect()
}

/// Cells of real sections: points on a few planes each, cocircular and collinear by construction.
/// The three largest and three more spread over the sizes, from Elephant and hand.
#[test]
fn tetgen_and_ours_pass_the_validator_on_cells_of_shared_files() {
    for name in ["Elephant", "hand"] {
        let mut cells = cell_point_sets(name);
        assert!(cells.len() >= 6, "{name}: only {} cells", cells.len());
        cells.sort_by_key(|c| std::cmp::Reverse(c.len()));
        let n = cells.len();
        for k in [0, 1, 2, n / 4, n / 2, 3 * n / 4] {
            let what = format!("{name} cell #{k} by size");
            let (ours, theirs) = both_valid(&what, &cells[k]);
            println!(
                "{what}: {} points, ours {ours} tets, TetGen {theirs}",
                cells[k].len()
            );
        }
    }
}

#[test]
fn tetgen_handles_duplicates_and_small_inputs() {
    let mut pts = gen::uniform(50, 8);
    pts.extend_from_slice(&pts.clone()[..10]);
    let theirs = sorted(tetgen_delaunay(&pts).unwrap());
    assert!(theirs.iter().flatten().all(|&v| v < 50));
    let dt = Delaunay::new(&pts);
    assert_eq!(
        sorted(dt.tets().map(|t| dt.tet_vertices(t)).collect()),
        theirs
    );
    assert!(tetgen_delaunay(&pts[..3]).unwrap().is_empty());
}

/// `check_tets` panics on `tets` of `pts` (the validator can fail).
fn rejected(pts: &[[f64; 3]], tets: &[[u32; 4]]) -> bool {
    std::panic::catch_unwind(|| delaunay_check::check_tets(pts, tets, true)).is_err()
}

/// Each tetrahedron with its last two vertices swapped when negative.
fn oriented(pts: &[[f64; 3]], tets: &[[u32; 4]]) -> Vec<[u32; 4]> {
    let p = |v: u32| pts[v as usize];
    tets.iter()
        .map(|&[a, b, c, d]| {
            if slice2solid::delaunay::pred::orient(p(a), p(b), p(c), p(d)) < 0.0 {
                [a, b, d, c]
            } else {
                [a, b, c, d]
            }
        })
        .collect()
}

/// The oracle must be able to fail: on five points whose hull has two triangulations (two tets
/// on triangle 012, or three around edge 34), the one that is not Delaunay fails only the
/// empty-sphere check; an inverted or a missing tetrahedron fails too.
#[test]
fn validator_rejects_broken_triangulations() {
    let pts = [
        [1.0, 0.0, 0.0],
        [-0.5, 0.8, 0.0],
        [-0.5, -0.8, 0.0],
        [0.0, 0.0, 1.0],
        [0.1, 0.0, -0.3],
    ];
    let two = oriented(&pts, &[[0, 1, 2, 3], [0, 1, 2, 4]]);
    let three = oriented(&pts, &[[0, 1, 3, 4], [1, 2, 3, 4], [2, 0, 3, 4]]);
    let dt = Delaunay::new(&pts);
    let ours = sorted(dt.tets().map(|t| dt.tet_vertices(t)).collect());
    let (good, bad) = if ours.len() == 2 {
        (two, three)
    } else {
        (three, two)
    };
    assert_eq!(sorted(good.clone()), ours);
    assert!(!rejected(&pts, &good));
    assert!(rejected(&pts, &bad), "a non-Delaunay triangulation passed");
    let mut inverted = good.clone();
    inverted[0].swap(0, 1);
    assert!(rejected(&pts, &inverted), "an inverted tet passed");
    assert!(rejected(&pts, &good[1..]), "a missing tet passed");
}

/// TetGen sets process-wide predicate filters from each input's bounding box (`exactinit`), so
/// runs on other threads at the same time (the test harness runs tests in parallel) must not
/// change a result: the largest cells of hand and Elephant (points on planes, where rounded
/// orientations are wrong and only the exact fallback decides), run while another thread keeps
/// starting runs on a random set 2^-20 wide, give the tetrahedra of a run alone (CI once failed
/// with a facet in four tetrahedra when the oracle ran beside other tests). Without the lock in
/// `tetgen_delaunay` this test hangs in TetGen (killed after 15 minutes; with the lock it takes
/// seconds), so a watchdog fails it after 180 s.
#[test]
fn tetgen_runs_at_once_on_different_scales_match_runs_alone() {
    let scaled = |pts: Vec<[f64; 3]>, e: i32| -> Vec<[f64; 3]> {
        pts.iter()
            .map(|p| p.map(|c| c * f64::powi(2.0, e)))
            .collect()
    };
    let tiny = scaled(gen::uniform(40, 11), -20);
    let alone = |pts: &[[f64; 3]]| sorted(tetgen_delaunay(pts).unwrap());
    let tiny_alone = alone(&tiny);
    let bigs: Vec<Vec<[f64; 3]>> = ["hand", "Elephant"]
        .iter()
        .flat_map(|name| {
            let mut cells = cell_point_sets(name);
            cells.sort_by_key(|c| std::cmp::Reverse(c.len()));
            cells.truncate(3);
            cells
        })
        .collect();
    let bigs_alone: Vec<_> = bigs.iter().map(|b| alone(b)).collect();
    let done = std::sync::atomic::AtomicBool::new(false);
    // Without the lock TetGen can loop forever on its corrupted mesh: a hang fails the run too.
    let finished = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let watched = finished.clone();
    std::thread::spawn(move || {
        let start = std::time::Instant::now();
        while !watched.load(std::sync::atomic::Ordering::Relaxed) {
            if start.elapsed() > std::time::Duration::from_secs(180) {
                eprintln!("TetGen runs at once did not finish in 180 s (alone: a few seconds)");
                std::process::exit(1);
            }
            std::thread::sleep(std::time::Duration::from_millis(200));
        }
    });
    std::thread::scope(|s| {
        let tiny_runs = s.spawn(|| {
            let mut runs = 0;
            while !done.load(std::sync::atomic::Ordering::Relaxed) {
                assert!(alone(&tiny) == tiny_alone, "the small set's result changed");
                runs += 1;
            }
            runs
        });
        for round in 0..3 {
            for (k, (big, big_alone)) in bigs.iter().zip(&bigs_alone).enumerate() {
                let got = tetgen_delaunay(big).unwrap();
                delaunay_check::check_tets(big, &got, true);
                assert!(
                    &sorted(got) == big_alone,
                    "round {round}, cell {k}: result changed"
                );
            }
        }
        done.store(true, std::sync::atomic::Ordering::Relaxed);
        assert!(tiny_runs.join().unwrap() > 20, "the runs did not overlap");
    });
    finished.store(true, std::sync::atomic::Ordering::Relaxed);
}
