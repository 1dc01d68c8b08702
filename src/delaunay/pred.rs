//! Geometric decisions of the kernel, all exact, with symbolic perturbation for ties.
//!
//! Sign convention inside the kernel: a tetrahedron (a,b,c,d) is *positive* when its volume
//! (b-a)·((c-a)×(d-a)) is positive, which is `robust::orient3d(a,b,c,d) < 0`.
//! The perturbation follows Devillers & Teillaud (2011), as in CGAL's `Delaunay_triangulation_3`:
//! points are ordered lexicographically; an exactly cospherical 5-tuple is decided by the
//! orientation of the tetrahedron in which the largest point is replaced by the query (twice at most);
//! an exactly coplanar point on a hull facet is decided by the perturbed in-circle test of that facet.
use crate::geom::predicates as gp;

pub type P = [f64; 3];

/// > 0 when (a,b,c,d) has positive volume, < 0 negative, 0 coplanar. Exact.
#[inline]
pub fn orient(a: P, b: P, c: P, d: P) -> f64 {
    -gp::orient3d(a, b, c, d)
}

/// > 0 when e is strictly inside the circumsphere of the positive tetrahedron (a,b,c,d). Exact.
#[inline]
pub fn insphere(a: P, b: P, c: P, d: P, e: P) -> f64 {
    -gp::insphere(a, b, c, d, e)
}

/// Lexicographic order on coordinates (the perturbation order).
#[inline]
pub fn lex_less(a: &P, b: &P) -> bool {
    a[0] < b[0] || (a[0] == b[0] && (a[1] < b[1] || (a[1] == b[1] && a[2] < b[2])))
}

/// Orientation of three exactly coplanar points inside their plane, read in the first of the
/// xy, yz, zx projections that is not degenerate. The same projection is chosen for every
/// non-collinear triple of one plane, so signs are consistent within a plane. 0 iff collinear.
#[inline]
pub fn coplanar_orient(a: P, b: P, c: P) -> f64 {
    let o = gp::orient2d([a[0], a[1]], [b[0], b[1]], [c[0], c[1]]);
    if o != 0.0 {
        return o;
    }
    let o = gp::orient2d([a[1], a[2]], [b[1], b[2]], [c[1], c[2]]);
    if o != 0.0 {
        return o;
    }
    gp::orient2d([a[2], a[0]], [b[2], b[0]], [c[2], c[0]])
}

/// True when the three points are collinear (or not distinct). Exact.
#[inline]
pub fn collinear(a: P, b: P, c: P) -> bool {
    coplanar_orient(a, b, c) == 0.0
}

/// Perturbed conflict test of a positive finite tetrahedron `t` with `q`: true when `q` is inside the
/// perturbed circumsphere. Never ties.
#[inline]
pub fn conflict_finite(t: [P; 4], q: P) -> bool {
    let s = insphere(t[0], t[1], t[2], t[3], q);
    if s != 0.0 {
        return s > 0.0;
    }
    perturbed_insphere_tie(t, q)
}

#[cold]
fn perturbed_insphere_tie(t: [P; 4], q: P) -> bool {
    let pts = [t[0], t[1], t[2], t[3], q];
    let mut idx = [0usize, 1, 2, 3, 4];
    idx.sort_by(|&i, &j| cmp_lex(&pts[i], &pts[j]));
    for k in (0..5).rev() {
        let j = idx[k];
        if j == 4 {
            return false;
        }
        let mut r = t;
        r[j] = q;
        let o = orient(r[0], r[1], r[2], r[3]);
        if o != 0.0 {
            return o > 0.0;
        }
    }
    debug_assert!(false, "perturbed insphere undecided");
    false
}

fn cmp_lex(a: &P, b: &P) -> std::cmp::Ordering {
    a[0].partial_cmp(&b[0])
        .unwrap()
        .then(a[1].partial_cmp(&b[1]).unwrap())
        .then(a[2].partial_cmp(&b[2]).unwrap())
}

/// Perturbed conflict test of an infinite tetrahedron: `t` has the infinite vertex at position `k`
/// (its coordinates in `t[k]` are ignored), `d` is the apex of the finite tetrahedron on the other side
/// of the hull facet. True when `q` lies strictly outside the hull facet, or on its plane and inside its
/// perturbed circumcircle.
#[inline]
pub fn conflict_infinite(t: [P; 4], k: usize, d: P, q: P) -> bool {
    let mut r = t;
    r[k] = q;
    let o = orient(r[0], r[1], r[2], r[3]);
    if o != 0.0 {
        return o > 0.0;
    }
    coplanar_conflict(t, k, d, q)
}

#[cold]
fn coplanar_conflict(t: [P; 4], k: usize, d: P, q: P) -> bool {
    // Every sphere through the facet's three vertices cuts the facet's plane in their circumcircle, so
    // the sphere through the facet and `d` decides the circle. (t with ∞→d) is negative: flip the sign.
    let mut r = t;
    r[k] = d;
    let s = -insphere(r[0], r[1], r[2], r[3], q);
    if s != 0.0 {
        return s > 0.0;
    }
    let f: Vec<P> = (0..4).filter(|&i| i != k).map(|i| t[i]).collect();
    let f = [f[0], f[1], f[2]];
    let local = coplanar_orient(f[0], f[1], f[2]);
    let pts = [f[0], f[1], f[2], q];
    let mut idx = [0usize, 1, 2, 3];
    idx.sort_by(|&i, &j| cmp_lex(&pts[i], &pts[j]));
    for m in (0..4).rev() {
        let j = idx[m];
        if j == 3 {
            return false;
        }
        let mut g = f;
        g[j] = q;
        let o = coplanar_orient(g[0], g[1], g[2]);
        if o != 0.0 {
            return (o > 0.0) == (local > 0.0);
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn signs() {
        let a = [0.0, 0.0, 0.0];
        let b = [1.0, 0.0, 0.0];
        let c = [0.0, 1.0, 0.0];
        let d = [0.0, 0.0, 1.0];
        assert!(orient(a, b, c, d) > 0.0);
        assert!(insphere(a, b, c, d, [0.2, 0.2, 0.2]) > 0.0);
        assert!(insphere(a, b, c, d, [2.0, 2.0, 2.0]) < 0.0);
        assert!(coplanar_orient(a, b, c) > 0.0);
        assert!(collinear(a, b, [3.0, 0.0, 0.0]));
        // Cospherical: the perturbed answers of the two tetrahedra sharing a facet must disagree
        // about each other's apex in a consistent way (exactly one of them is Delaunay).
        let e = [1.0, 1.0, 1.0];
        assert_eq!(insphere(a, b, c, d, e), 0.0);
        let _ = conflict_finite([a, b, c, d], e);
    }
}
