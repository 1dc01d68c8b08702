//! Property tests on small random inputs, including integer points on a tiny grid (heavily degenerate:
//! coplanar, cospherical and duplicate points everywhere).
mod delaunay_check;
use proptest::prelude::*;
use slice2solid::delaunay::Delaunay;

fn grid_points(k: i32, max: usize) -> impl Strategy<Value = Vec<[f64; 3]>> {
    prop::collection::vec((0..k, 0..k, 0..k), 0..max).prop_map(|v| {
        v.into_iter()
            .map(|(x, y, z)| [x as f64, y as f64, z as f64])
            .collect()
    })
}

fn float_points(max: usize) -> impl Strategy<Value = Vec<[f64; 3]>> {
    prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), 0..max)
        .prop_map(|v| v.into_iter().map(|(x, y, z)| [x, y, z]).collect())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn tiny_grid_is_delaunay(pts in grid_points(3, 40)) {
        let dt = Delaunay::new(&pts);
        delaunay_check::check_all(&pts, &dt);
    }

    #[test]
    fn small_grid_incremental_is_delaunay(pts in grid_points(5, 60), split in 0usize..60) {
        let split = split.min(pts.len());
        let mut dt = Delaunay::new(&pts[..split]);
        for (k, p) in pts[split..].iter().enumerate() {
            let v = dt.insert(*p);
            prop_assert_eq!(dt.point(v), *p);
            if v as usize != split + k {
                prop_assert!(pts[..split + k].contains(p), "only a duplicate may return an old id");
            }
        }
        delaunay_check::check_all(&pts, &dt);
    }

    #[test]
    fn random_floats_are_delaunay(pts in float_points(60)) {
        let dt = Delaunay::new(&pts);
        delaunay_check::check_all(&pts, &dt);
    }

    #[test]
    fn points_on_two_planes(a in grid_points(6, 30), b in grid_points(6, 30)) {
        // z = 0 and x + y + z = 5 (exactly representable), plus an apex
        let mut pts: Vec<[f64; 3]> = a.iter().map(|p| [p[0], p[1], 0.0]).collect();
        pts.extend(b.iter().map(|p| [p[0], p[1], 5.0 - p[0] - p[1]]));
        pts.push([-1.0, -1.0, -1.0]);
        let dt = Delaunay::new(&pts);
        delaunay_check::check_all(&pts, &dt);
    }
}
