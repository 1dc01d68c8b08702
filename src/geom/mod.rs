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
/// that lie within `tol` of each other and in one group (`same`), closest first, ties in index
/// order. The snapping of two sections' crossings on their common line pairs them in this order
/// (`arrangement::reconcile`), and the common-line trims predict that snapping with it
/// (`validate::common_lines`): one rule, so the two cannot drift apart.
pub fn close_pairs(
    a: &[f64],
    b: &[f64],
    tol: f64,
    same: impl Fn(f64, f64) -> bool,
) -> Vec<(f64, usize, usize)> {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (x, &s) in a.iter().enumerate() {
        let lo = b.partition_point(|&t| t < s - tol);
        for (y, &t) in b.iter().enumerate().skip(lo) {
            if t > s + tol {
                break;
            }
            if same(s, t) {
                pairs.push(((s - t).abs(), x, y));
            }
        }
    }
    // stable: equal gaps stay in index order
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    pairs
}
