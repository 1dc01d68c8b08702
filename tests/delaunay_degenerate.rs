//! Degenerate inputs: every result is checked independently (orientation, facet pairing, convex
//! hull, volume, exact empty spheres), see `delaunay_check`.
mod delaunay_check;
use delaunay_check::check_all;
use rand::{Rng, SeedableRng};
use slice2solid::delaunay::{gen, Delaunay};

fn run(pts: &[[f64; 3]]) -> delaunay_check::Summary {
    let dt = Delaunay::new(pts);
    check_all(pts, &dt)
}

#[test]
fn lattice_16() {
    let pts = gen::lattice(16);
    let s = run(&pts);
    assert!((s.volume - 15f64.powi(3)).abs() < 1e-6, "{}", s.volume);
}

#[test]
fn circles_on_parallel_planes() {
    let pts = gen::circles(8, 40);
    let s = run(&pts);
    assert!(s.tets > 0);
}

#[test]
fn points_on_40_random_planes() {
    let pts = gen::on_planes(6000, 40, 9);
    run(&pts);
}

#[test]
fn cube_faces() {
    let pts = gen::cube_faces(5000, 4);
    let s = run(&pts);
    assert!((s.volume - 1.0).abs() < 1e-9, "{}", s.volume);
}

#[test]
fn random_convex_polytope_faces() {
    let pts = gen::polytope_faces(1000, 30, 5);
    run(&pts);
}

#[test]
fn many_duplicates() {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let base = gen::uniform(300, 2);
    let pts: Vec<[f64; 3]> = (0..3000)
        .map(|_| base[r.gen_range(0..base.len())])
        .collect();
    let dt = Delaunay::new(&pts);
    let mut distinct = pts.clone();
    distinct.sort_by(|a, b| a.partial_cmp(b).unwrap());
    distinct.dedup();
    assert_eq!(dt.num_vertices() - dt.duplicates().len(), distinct.len());
    for &(a, b) in dt.duplicates() {
        assert_eq!(pts[a as usize], pts[b as usize]);
        assert!(b < a, "the kept vertex is the first occurrence");
    }
    check_all(&pts, &dt);
    // -0.0 and 0.0 are the same position
    let dt = Delaunay::new(&[
        [0.0, 0.0, 0.0],
        [-0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]);
    assert_eq!(dt.duplicates(), &[(1, 0)]);
    assert_eq!(dt.num_finite_tets(), 1);
}

#[test]
fn all_coplanar_and_collinear() {
    let plane: Vec<[f64; 3]> = (0..500)
        .map(|i| {
            let (a, b) = ((i % 23) as f64, (i / 23) as f64);
            [a, b, 2.0 * a - 3.0 * b + 1.0]
        })
        .collect();
    let dt = Delaunay::new(&plane);
    assert_eq!(dt.dimension(), 2);
    assert_eq!(dt.tets().count(), 0);
    dt.is_valid().unwrap();
    let line: Vec<[f64; 3]> = (0..100)
        .map(|i| [i as f64, 2.0 * i as f64, -(i as f64)])
        .collect();
    assert_eq!(Delaunay::new(&line).dimension(), 1);
    assert_eq!(Delaunay::new(&[[1.0, 2.0, 3.0]; 7]).dimension(), 0);
    assert_eq!(Delaunay::new(&[]).dimension(), -1);
    assert_eq!(
        Delaunay::new(&[plane[0], plane[1], plane[23]]).dimension(),
        2
    );
}

#[test]
fn five_cospherical_points() {
    // octahedron minus one corner plus a cospherical point: many exact ties
    let pts = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let s = run(&pts);
    assert_eq!(s.tets, 2);
    let pts = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [0.6, 0.8, 0.0],
        [0.0, 0.6, -0.8],
    ];
    run(&pts);
}

#[test]
fn incremental_insertion_after_build() {
    // the engine inserts Steiner points later: on the hull, on facets, outside, duplicates
    let pts = gen::cube_faces(500, 12);
    let mut dt = Delaunay::new(&pts);
    let mut all = pts.clone();
    let extra = [
        [0.5, 0.5, 0.0],
        [0.5, 0.0, 0.0],
        [0.25, 0.25, 0.25],
        [2.0, 0.5, 0.5],
        [0.5, 0.5, 0.0],
        [1.0, 1.0, 1.0],
        [-1.0, -1.0, 3.0],
    ];
    for q in extra {
        let v = dt.insert(q);
        all.push(q);
        assert_eq!(dt.point(v), q);
        assert!(!dt.vertex_tets(v).is_empty());
    }
    check_all(&all, &dt);
}
