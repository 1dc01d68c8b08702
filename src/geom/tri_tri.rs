//! Exact triangle–triangle intersection (every decision is a sign of `orient3d`/`orient2d`).
//!
//! Two closed triangles intersect iff an edge of one meets the other (closed segment–triangle test):
//! their intersection is a convex set whose extreme points lie on the boundary of one of them.
//! Triangles of one mesh that share vertices (by index) intersect only where they overlap *beyond*
//! the shared part:
//! * one shared vertex v, A = (v,a1,a2), B = (v,b1,b2): beyond v iff the opposite edge a1a2 meets B
//!   or b1b2 meets A (an extreme point ≠ v of A∩B is where A or B ends along their common line, which
//!   is on the opposite edge);
//! * a shared edge uw with apexes a, b: beyond uw iff the four points are coplanar and a, b lie
//!   strictly on the same side of uw (the triangles fold onto each other); touching along uw is fine;
//! * all three shared: the same triangle twice, which overlaps.
//!
//! Degenerate (collinear) triangles are not tested here; `check` counts them separately.
#![allow(clippy::needless_range_loop)] // small fixed-size coordinate loops read better indexed
use crate::geom::predicates::{orient2d, orient3d};

type P3 = [f64; 3];

/// True when the triangle's three points are collinear (exactly).
pub fn is_degenerate(a: P3, b: P3, c: P3) -> bool {
    (0..3).all(|k| orient2d(drop(a, k), drop(b, k), drop(c, k)) == 0.0)
}

/// Do triangles `ta` and `tb` (indices into `v`) intersect beyond their shared vertices/edge?
pub fn mesh_triangles_intersect(ta: [u32; 3], tb: [u32; 3], v: &[P3]) -> bool {
    let p = |i: u32| v[i as usize];
    let mut shared = [(0usize, 0usize); 3];
    let mut n_shared = 0;
    for i in 0..3 {
        for j in 0..3 {
            if ta[i] == tb[j] {
                shared[n_shared.min(2)] = (i, j);
                n_shared += 1;
            }
        }
    }
    match n_shared {
        0 => triangles_intersect(
            [p(ta[0]), p(ta[1]), p(ta[2])],
            [p(tb[0]), p(tb[1]), p(tb[2])],
        ),
        1 => {
            let (i, j) = shared[0];
            let (a1, a2) = (p(ta[(i + 1) % 3]), p(ta[(i + 2) % 3]));
            let (b1, b2) = (p(tb[(j + 1) % 3]), p(tb[(j + 2) % 3]));
            let va = p(ta[i]);
            // A touches B's plane only at v when a1, a2 are strictly on one side (and vice versa).
            let (s1, s2) = (orient3d(va, b1, b2, a1), orient3d(va, b1, b2, a2));
            if same_strict_sign(s1, s2) {
                return false;
            }
            let (s1, s2) = (orient3d(va, a1, a2, b1), orient3d(va, a1, a2, b2));
            if same_strict_sign(s1, s2) {
                return false;
            }
            segment_meets_triangle(a1, a2, [va, b1, b2])
                || segment_meets_triangle(b1, b2, [va, a1, a2])
        }
        2 => {
            let u = p(ta[shared[0].0]);
            let w = p(ta[shared[1].0]);
            let ia = 3 - shared[0].0 - shared[1].0;
            let ib = 3 - shared[0].1 - shared[1].1;
            folded_over_shared_edge(u, w, p(ta[ia]), p(tb[ib]))
        }
        _ => true,
    }
}

/// Triangles sharing the edge uw, with apexes a and b: do they overlap beyond uw?
pub fn folded_over_shared_edge(u: P3, w: P3, a: P3, b: P3) -> bool {
    if orient3d(u, w, a, b) != 0.0 {
        return false;
    }
    // Coplanar: project on a coordinate plane where (u,w,a) stays non-degenerate; the projection of
    // exactly coplanar points multiplies every orientation by the same sign.
    for k in 0..3 {
        let sa = orient2d(drop(u, k), drop(w, k), drop(a, k));
        if sa != 0.0 {
            let sb = orient2d(drop(u, k), drop(w, k), drop(b, k));
            return same_strict_sign(sa, sb);
        }
    }
    false
}

/// Closed triangles (no shared-index logic): do they have a common point?
pub fn triangles_intersect(a: [P3; 3], b: [P3; 3]) -> bool {
    // Separating planes first: all of one triangle strictly on one side of the other's plane.
    if strictly_one_side(b, a) || strictly_one_side(a, b) {
        return false;
    }
    (0..3).any(|i| segment_meets_triangle(a[i], a[(i + 1) % 3], b))
        || (0..3).any(|i| segment_meets_triangle(b[i], b[(i + 1) % 3], a))
}

fn strictly_one_side(t: [P3; 3], q: [P3; 3]) -> bool {
    let s0 = orient3d(t[0], t[1], t[2], q[0]);
    if s0 == 0.0 {
        return false;
    }
    let s1 = orient3d(t[0], t[1], t[2], q[1]);
    if !same_strict_sign(s0, s1) {
        return false;
    }
    same_strict_sign(s0, orient3d(t[0], t[1], t[2], q[2]))
}

/// Closed segment pq against closed triangle t.
pub fn segment_meets_triangle(p: P3, q: P3, t: [P3; 3]) -> bool {
    let [a, b, c] = t;
    let sp = orient3d(a, b, c, p);
    let sq = orient3d(a, b, c, q);
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        return coplanar_segment_meets_triangle(p, q, t);
    }
    // The line pq crosses the plane inside the segment; is the crossing point in the closed triangle?
    let o1 = orient3d(p, q, a, b);
    let o2 = orient3d(p, q, b, c);
    let o3 = orient3d(p, q, c, a);
    let pos = o1 > 0.0 || o2 > 0.0 || o3 > 0.0;
    let neg = o1 < 0.0 || o2 < 0.0 || o3 < 0.0;
    !(pos && neg)
}

/// Both strictly positive or both strictly negative (no product: it could underflow).
#[inline]
fn same_strict_sign(a: f64, b: f64) -> bool {
    (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0)
}

#[inline]
fn drop(p: P3, k: usize) -> [f64; 2] {
    match k {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

fn coplanar_segment_meets_triangle(p: P3, q: P3, t: [P3; 3]) -> bool {
    for k in 0..3 {
        let (a, b, c) = (drop(t[0], k), drop(t[1], k), drop(t[2], k));
        if orient2d(a, b, c) != 0.0 {
            let (p2, q2) = (drop(p, k), drop(q, k));
            return point_in_triangle_2d(p2, a, b, c)
                || point_in_triangle_2d(q2, a, b, c)
                || segments_meet_2d(p2, q2, a, b)
                || segments_meet_2d(p2, q2, b, c)
                || segments_meet_2d(p2, q2, c, a);
        }
    }
    false // degenerate triangle
}

fn point_in_triangle_2d(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let o = [orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p)];
    let pos = o.iter().any(|&x| x > 0.0);
    let neg = o.iter().any(|&x| x < 0.0);
    !(pos && neg)
}

/// Closed segments pq and ab in the plane.
pub fn segments_meet_2d(p: [f64; 2], q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    let o1 = orient2d(p, q, a);
    let o2 = orient2d(p, q, b);
    let o3 = orient2d(a, b, p);
    let o4 = orient2d(a, b, q);
    if same_strict_sign(o1, o2) || same_strict_sign(o3, o4) {
        return false;
    }
    if o1 == 0.0 && o2 == 0.0 {
        // Collinear: overlap of the coordinate ranges on both axes.
        return (0..2)
            .all(|k| p[k].min(q[k]) <= a[k].max(b[k]) && a[k].min(b[k]) <= p[k].max(q[k]));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [P3; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn crossing_and_separate() {
        let b = [[0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [0.3, 0.3, 1.0]];
        assert!(triangles_intersect(A, b));
        let far = [[2.0, 2.0, -1.0], [2.0, 2.0, 1.0], [3.0, 3.0, 1.0]];
        assert!(!triangles_intersect(A, far));
        // touching at a point counts for unrelated triangles
        let touch = [[0.5, 0.5, 0.0], [1.0, 1.0, 1.0], [1.0, 0.5, 1.0]];
        assert!(triangles_intersect(A, touch));
        // coplanar overlap, and coplanar containment
        let inner = [[0.1, 0.1, 0.0], [0.2, 0.1, 0.0], [0.1, 0.2, 0.0]];
        assert!(triangles_intersect(A, inner));
        let beside = [[1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0]];
        assert!(!triangles_intersect(A, beside));
    }

    #[test]
    fn shared_parts_are_not_intersections() {
        let v: Vec<P3> = vec![
            [0.0, 0.0, 0.0],   // 0
            [1.0, 0.0, 0.0],   // 1
            [0.0, 1.0, 0.0],   // 2
            [1.0, 1.0, 0.0],   // 3 other side of edge 1-2, coplanar
            [0.2, 0.2, 0.0],   // 4 same side of 1-2 as 0, coplanar (fold)
            [0.3, 0.3, 1.0],   // 5 off plane
            [-1.0, -1.0, 0.0], // 6
            [-1.0, -2.0, 0.0], // 7
            [0.5, 0.1, -1.0],  // 8
            [0.1, 0.5, 1.0],   // 9
        ];
        // shared edge, flat neighbours: fine; folded: intersect; bent: fine
        assert!(!mesh_triangles_intersect([0, 1, 2], [2, 1, 3], &v));
        assert!(mesh_triangles_intersect([0, 1, 2], [2, 1, 4], &v));
        assert!(!mesh_triangles_intersect([0, 1, 2], [2, 1, 5], &v));
        // shared vertex only
        assert!(!mesh_triangles_intersect([0, 1, 2], [0, 6, 7], &v));
        // shared vertex 0, B = (0,8,9) pierces A through its interior
        assert!(mesh_triangles_intersect([0, 1, 2], [0, 8, 9], &v));
        // same triangle twice
        assert!(mesh_triangles_intersect([0, 1, 2], [1, 2, 0], &v));
    }

    use proptest::prelude::*;

    fn tri() -> impl Strategy<Value = [P3; 3]> {
        // small integer grid: many coplanar, collinear and touching configurations
        proptest::array::uniform3(proptest::array::uniform3((-2i32..=2).prop_map(f64::from)))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        /// The answer does not depend on the order of the triangles or of their vertices.
        #[test]
        fn symmetric_and_permutation_invariant(a in tri(), b in tri()) {
            prop_assume!(!is_degenerate(a[0], a[1], a[2]) && !is_degenerate(b[0], b[1], b[2]));
            let r = triangles_intersect(a, b);
            prop_assert_eq!(r, triangles_intersect(b, a));
            prop_assert_eq!(r, triangles_intersect([a[1], a[2], a[0]], b));
            prop_assert_eq!(r, triangles_intersect([a[0], a[2], a[1]], [b[2], b[1], b[0]]));
            // a shared corner point: the closed triangles always meet there
            let c = [a[0], b[1], b[2]];
            if !is_degenerate(c[0], c[1], c[2]) {
                prop_assert!(triangles_intersect(a, c));
            }
        }

        /// Index-sharing pairs: consistent with the closed test on the parts beyond the shared vertex.
        #[test]
        fn shared_vertex_consistent(a in tri(), b in tri()) {
            let v = vec![a[0], a[1], a[2], b[1], b[2]];
            let (ta, tb) = ([0u32, 1, 2], [0u32, 3, 4]);
            prop_assume!(!is_degenerate(v[0], v[1], v[2]) && !is_degenerate(v[0], v[3], v[4]));
            prop_assume!(v[3] != v[1] && v[3] != v[2] && v[4] != v[1] && v[4] != v[2]);
            let r = mesh_triangles_intersect(ta, tb, &v);
            prop_assert_eq!(r, mesh_triangles_intersect(tb, ta, &v));
            prop_assert_eq!(r, mesh_triangles_intersect([1, 2, 0], [4, 0, 3], &v));
            // beyond the shared vertex implies intersecting as closed triangles
            if r {
                prop_assert!(triangles_intersect([v[0], v[1], v[2]], [v[0], v[3], v[4]]));
            }
        }
    }
}
