//! Horsers.csl: input planes 21, 22, 25 and 26 (0-based) meet in one point up to the rounding of
//! their equations. The arrangement merges the vertices the rounding puts apart (arrangement::merge),
//! so the output has no two vertices closer than 1e-9 of the diagonal (the outside judge merges such
//! vertices and then called the surface open), and the glue has no micro edge to collapse.
mod common;
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use slice2solid::eval::check::check_mesh;
use slice2solid::Options;

fn horsers() -> slice2solid::Sections {
    let path = common::shared_dir().join("data/csl/Horsers.csl");
    slice2solid::io::read_sections(&path).expect("read Horsers.csl")
}

/// The closest pair of distinct points (sweep along x), and its distance.
fn closest_pair(points: &[[f64; 3]], limit: f64) -> Option<(usize, usize, f64)> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a][0].total_cmp(&points[b][0]));
    let mut best: Option<(usize, usize, f64)> = None;
    for i in 0..order.len() {
        let p = points[order[i]];
        for &b in &order[i + 1..] {
            let q = points[b];
            if q[0] - p[0] >= limit {
                break;
            }
            let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
            if d < limit && best.is_none_or(|x| d < x.2) {
                best = Some((order[i], b, d));
            }
        }
    }
    best
}

fn diagonal(points: &[[f64; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

#[test]
fn horsers_arrangement_has_one_vertex_where_four_planes_nearly_meet() {
    let s = horsers();
    let opt = ArrangementOptions::default();
    let arr = Arrangement::build(&s, &opt).unwrap();
    let (lo, hi) = s.bounding_box().unwrap();
    let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let close = closest_pair(&arr.pool.positions, opt.merge_tolerance * diag);
    assert!(
        close.is_none(),
        "pool vertices {close:?} closer than the merge tolerance"
    );
    let four = arr
        .pool
        .tags
        .iter()
        .filter(|t| [21, 22, 25, 26].iter().all(|p| t.contains(p)))
        .count();
    assert_eq!(four, 1, "one vertex on planes 21, 22, 25, 26");
    for (f, face) in arr.faces.iter().enumerate() {
        let a = arr.loop_area(face.plane, &face.polygon);
        assert!(
            face.polygon.len() >= 3 && a > 1e-20 * diag * diag,
            "face {f}: area {a}"
        );
    }
}

#[test]
fn horsers_surface_has_no_rounding_apart_vertices() {
    let s = horsers();
    let solid = slice2solid::reconstruct(&s, &Options::default()).expect("reconstruct Horsers");
    let v = &solid.surface.vertices;
    let diag = diagonal(v);
    let close = closest_pair(v, 1e-9 * diag);
    assert!(
        close.is_none(),
        "output vertices {close:?} closer than 1e-9 of the diagonal {diag}"
    );
    assert!(
        !solid
            .report
            .warnings
            .iter()
            .any(|w| w.contains("surface edges shorter than")),
        "{:?}",
        solid.report.warnings
    );
    let c = check_mesh(&solid.surface, None);
    assert!(c.closed && c.manifold && c.oriented && c.self_intersection_free);
}
