//! Geometry: every geometric decision goes through `predicates`. `tri_tri` (exact triangle-triangle
//! intersection) and `bvh` (bounding-volume hierarchy of boxes) serve the measuring instruments
//! (eval).
pub mod bvh;
pub mod predicates;
pub mod tri_tri;

/// Area of the triangle `p` (a construction, in floats).
pub fn triangle_area(p: [[f64; 3]; 3]) -> f64 {
    use crate::sections::{cross, dot, sub};
    let w = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    0.5 * dot(w, w).sqrt()
}

/// The point of the three planes with equations `a`, `b`, `c` (`[n, d]`, n · x + d = 0), by
/// Cramer's rule (a construction, in floats; not finite where the normals are dependent). The
/// arrangement's vertices are made with it, so whoever predicts where they lie uses it too.
pub fn three_planes_point(a: [f64; 4], b: [f64; 4], c: [f64; 4]) -> [f64; 3] {
    use crate::sections::{cross, dot};
    let (n1, n2, n3) = ([a[0], a[1], a[2]], [b[0], b[1], b[2]], [c[0], c[1], c[2]]);
    let c23 = cross(n2, n3);
    let c31 = cross(n3, n1);
    let c12 = cross(n1, n2);
    let det = dot(n1, c23);
    std::array::from_fn(|k| -(a[3] * c23[k] + b[3] * c31[k] + c[3] * c12[k]) / det)
}

/// Distance from `q` to the segment `ab` in the plane (a construction, in floats).
pub fn segment_distance_2d(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let e = [a[0] + t * d[0] - q[0], a[1] + t * d[1] - q[1]];
    (e[0] * e[0] + e[1] * e[1]).sqrt()
}

/// Candidate pairs (gap, index in `a`, index in `b`) of two sorted lists of positions along a line
/// that lie within `tol` of each other and between the same two `breaks` (sorted positions of the
/// arrangement's vertices on the line: two crossings merge only on one arrangement edge), closest
/// first, ties in index order. The snapping of two sections' crossings on their common line pairs
/// them in this order (`arrangement::reconcile`), and the common-line trims predict that snapping
/// with it (`validate::common_lines`): one rule, breaks included, so the two cannot drift apart
/// (they did while each caller passed its own grouping: seed 117 of the generated odd inputs).
pub fn close_pairs(a: &[f64], b: &[f64], tol: f64, breaks: &[f64]) -> Vec<(f64, usize, usize)> {
    let edge = |s: f64| breaks.partition_point(|&x| x < s);
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (x, &s) in a.iter().enumerate() {
        let lo = b.partition_point(|&t| t < s - tol);
        for (y, &t) in b.iter().enumerate().skip(lo) {
            if t > s + tol {
                break;
            }
            if edge(s) == edge(t) {
                pairs.push(((s - t).abs(), x, y));
            }
        }
    }
    // stable: equal gaps stay in index order
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    pairs
}
