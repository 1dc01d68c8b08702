//! The parallel bulk build (`Delaunay::try_new_with_threads`) gives the sequential build's
//! triangulation (the Delaunay triangulation under the perturbation is unique): the same oriented
//! tetrahedra and the same merged duplicates, on random and degenerate sets large enough for
//! parallel rounds (a round of at least 8192 points). 4 threads on 2 cores makes more contention.
use rand::{Rng, SeedableRng};
use slice2solid::delaunay::{gen, Delaunay};

/// A tetrahedron by its even permutation with the smallest vertex first (orientation kept).
fn canonical(t: [u32; 4]) -> [u32; 4] {
    const EVEN: [[usize; 4]; 12] = [
        [0, 1, 2, 3],
        [0, 2, 3, 1],
        [0, 3, 1, 2],
        [1, 0, 3, 2],
        [1, 2, 0, 3],
        [1, 3, 2, 0],
        [2, 0, 1, 3],
        [2, 1, 3, 0],
        [2, 3, 0, 1],
        [3, 0, 2, 1],
        [3, 1, 0, 2],
        [3, 2, 1, 0],
    ];
    EVEN.iter().map(|p| p.map(|i| t[i])).min().unwrap()
}

fn tets(dt: &Delaunay) -> Vec<[u32; 4]> {
    let mut v: Vec<[u32; 4]> = dt.tets().map(|t| canonical(dt.tet_vertices(t))).collect();
    v.sort_unstable();
    v
}

fn same_for_all_thread_counts(pts: &[[f64; 3]]) {
    let seq = Delaunay::try_new_with_threads(pts, 1).unwrap();
    seq.is_valid().unwrap();
    let want = tets(&seq);
    for threads in [2, 4] {
        let par = Delaunay::try_new_with_threads(pts, threads).unwrap();
        par.is_valid().unwrap();
        assert_eq!(
            par.num_finite_tets(),
            seq.num_finite_tets(),
            "{threads} threads"
        );
        assert_eq!(tets(&par), want, "{threads} threads");
        assert_eq!(par.duplicates(), seq.duplicates(), "{threads} threads");
    }
}

#[test]
fn uniform() {
    same_for_all_thread_counts(&gen::uniform(40_000, 3));
}

#[test]
fn lattice_cospherical_everywhere() {
    same_for_all_thread_counts(&gen::lattice(24));
}

#[test]
fn one_sphere() {
    // all points (up to rounding) on the unit sphere, the hull is every point
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let pts: Vec<[f64; 3]> = (0..20_000)
        .map(|_| {
            let z: f64 = rng.gen_range(-1.0..1.0);
            let a: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
            let r = (1.0 - z * z).sqrt();
            [r * a.cos(), r * a.sin(), z]
        })
        .collect();
    same_for_all_thread_counts(&pts);
}

#[test]
fn coplanar_contour_stack() {
    // 120 parallel planes, a circle of 200 points on each: exactly coplanar and cocircular
    same_for_all_thread_counts(&gen::circles(120, 200));
}

#[test]
fn random_planes_and_duplicates() {
    let mut pts = gen::on_planes(30_000, 40, 2);
    let copies: Vec<[f64; 3]> = pts.iter().step_by(7).copied().collect();
    pts.extend(copies);
    same_for_all_thread_counts(&pts);
}

#[test]
fn cube_faces() {
    same_for_all_thread_counts(&gen::cube_faces(30_000, 4));
}
