//! Oracle tests: our kernel against TetGen (feature `tetgen`).
#![cfg(feature = "tetgen")]
mod delaunay_check;
use slice2solid::delaunay::{gen, tetgen::tetgen_delaunay, Delaunay};

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

#[test]
fn tetgen_volume_equals_ours_on_degenerate_sets() {
    for pts in [
        gen::lattice(8),
        gen::circles(6, 30),
        gen::on_planes(3000, 40, 4),
        gen::cube_faces(2000, 5),
        gen::polytope_faces(1000, 20, 6),
    ] {
        let dt = Delaunay::new(&pts);
        let ours = delaunay_check::check_all(&pts, &dt);
        let theirs = tetgen_delaunay(&pts).unwrap();
        let vol: f64 = theirs
            .iter()
            .map(|t| {
                let p = |i: usize| pts[t[i] as usize];
                slice2solid::delaunay::pred::orient(p(0), p(1), p(2), p(3)) / 6.0
            })
            .sum();
        assert!(
            (vol - ours.volume).abs() <= 1e-9 * vol.abs(),
            "TetGen volume {vol} != ours {}",
            ours.volume
        );
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
