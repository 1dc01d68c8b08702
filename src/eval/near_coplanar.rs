//! Double sheets: two triangles lying (almost) in one plane and overlapping there with positive area.
//!
//! The exact test of [`super::tri_tri`] calls two such triangles disjoint when rounding left one of
//! them 1e-13 above the other: they never meet, yet the surface runs twice through the same place
//! (a zero-thickness slab, or a flat fold). Float-based checkers (the outside judge) see them cross.
//! A pair counts as *overlapping near-coplanar* when
//! * every vertex of each triangle lies within `tol` of the other's plane (float distance along the
//!   float normal: its rounding, ~1e-16 of the triangle's size, is far below any sensible `tol`), and
//! * their projections on the coordinate plane most orthogonal to the first triangle's normal have
//!   interiors that meet (decided exactly with `orient2d` on the dropped-coordinate points, which are
//!   the input floats themselves).
//!
//! Interiors, not closed triangles: neighbours sharing an edge or a vertex in a flat (or slightly
//! bent) patch touch only along what they share, and are not reported; two triangles folded flat
//! onto each other over a shared edge, or two sheets stacked within `tol`, are.
use crate::geom::predicates::orient2d;

type P3 = [f64; 3];
type P2 = [f64; 2];

/// Default tolerance, relative to the mesh's bounding-box diagonal: far above the rounding of
/// constructed points (~1e-16 relative) and far below any feature a reconstruction means to make.
pub const NEAR_COPLANAR_RELATIVE_TOLERANCE: f64 = 1e-9;

/// Relative distance below which an edge counts as lying in another triangle's plane for
/// [`edge_in_other_plane`]: there a float determinant of the edge against the plane is ~1e-16 of its
/// magnitude, i.e. rounding noise (at 1e-12 barycentrics still carry ~1e-4 relative error).
pub const EDGE_IN_PLANE_RELATIVE_TOLERANCE: f64 = 1e-12;

/// Do triangles `a` and `b` lie within `tol` (absolute) of each other's planes and overlap in area?
/// Degenerate (collinear) triangles never overlap in area.
pub fn overlapping_near_coplanar(a: [P3; 3], b: [P3; 3], tol: f64) -> bool {
    overlapping_near_coplanar_with_normals(a, normal(a), b, normal(b), tol)
}

/// [`overlapping_near_coplanar`] with the triangles' [`normal`]s already computed.
pub fn overlapping_near_coplanar_with_normals(
    a: [P3; 3],
    na: Option<(P3, f64)>,
    b: [P3; 3],
    nb: Option<(P3, f64)>,
    tol: f64,
) -> bool {
    let (Some(na), Some(nb)) = (na, nb) else {
        return false;
    };
    if !within_plane(a, na, b, tol) || !within_plane(b, nb, a, tol) {
        return false;
    }
    let k = dominant_axis(na.0);
    interiors_overlap_2d(a.map(|p| drop(p, k)), b.map(|p| drop(p, k)))
}

/// Does an edge of either triangle lie within `tol` of the other's plane (both endpoints)? For such
/// pairs a float segment–triangle test (Möller–Trumbore, as in `shared/eval/evaluate.py`) divides by
/// a determinant that is pure rounding noise and returns arbitrary barycentrics: it may report a
/// crossing between triangles that are far apart. Informational only.
pub fn edge_in_other_plane(
    a: [P3; 3],
    na: Option<(P3, f64)>,
    b: [P3; 3],
    nb: Option<(P3, f64)>,
    tol: f64,
) -> bool {
    let near = |t: [P3; 3], n: Option<(P3, f64)>, q: [P3; 3]| {
        let Some(n) = n else { return false };
        let close = q.map(|p| close_to_plane(t, n, p, tol));
        (0..3).any(|i| close[i] && close[(i + 1) % 3])
    };
    near(a, na, b) || near(b, nb, a)
}

/// Every point of `q` is within `tol` of the plane of `t` (float normal `n` of length `len`).
fn within_plane(t: [P3; 3], n: (P3, f64), q: [P3; 3], tol: f64) -> bool {
    q.iter().all(|&p| close_to_plane(t, n, p, tol))
}

/// Is `p` within `tol` of the plane of `t` (with its unnormalised normal `n` of length `len`)?
fn close_to_plane(t: [P3; 3], (n, len): (P3, f64), p: P3, tol: f64) -> bool {
    let o = t[0];
    let d = n[0] * (p[0] - o[0]) + n[1] * (p[1] - o[1]) + n[2] * (p[2] - o[2]);
    d.abs() <= tol * len
}

/// Float normal (cross product of two edges) and its length; `None` for a zero or non-finite one.
pub fn normal(t: [P3; 3]) -> Option<(P3, f64)> {
    let e1 = [t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]];
    let e2 = [t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]];
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (len > 0.0 && len.is_finite()).then_some((n, len))
}

fn dominant_axis(n: P3) -> usize {
    let a = n.map(f64::abs);
    if a[0] >= a[1] && a[0] >= a[2] {
        0
    } else if a[1] >= a[2] {
        1
    } else {
        2
    }
}

#[inline]
fn drop(p: P3, k: usize) -> P2 {
    match k {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// Do the open interiors of two planar triangles meet? Exact. Two convex polygons have disjoint
/// interiors iff the line through some edge of one has the other in its closed outer half-plane
/// (an edge of their Minkowski difference supports it away from the origin).
pub fn interiors_overlap_2d(a: [P2; 3], b: [P2; 3]) -> bool {
    let Some(a) = counter_clockwise(a) else {
        return false;
    };
    let Some(b) = counter_clockwise(b) else {
        return false;
    };
    !(separated_by_an_edge_of(a, b) || separated_by_an_edge_of(b, a))
}

fn counter_clockwise(t: [P2; 3]) -> Option<[P2; 3]> {
    let s = orient2d(t[0], t[1], t[2]);
    if s > 0.0 {
        Some(t)
    } else if s < 0.0 {
        Some([t[0], t[2], t[1]])
    } else {
        None
    }
}

/// Some edge of counter-clockwise `t` has all of `q` on its right or on its line.
fn separated_by_an_edge_of(t: [P2; 3], q: [P2; 3]) -> bool {
    (0..3).any(|i| {
        let (p, r) = (t[i], t[(i + 1) % 3]);
        q.iter().all(|&x| orient2d(p, r, x) <= 0.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [P3; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn stacked_sheets_within_tolerance_overlap() {
        let b = [[0.1, 0.1, 1e-13], [0.9, 0.05, -1e-13], [0.1, 0.8, 0.0]];
        assert!(overlapping_near_coplanar(A, b, 1e-9));
        assert!(overlapping_near_coplanar(b, A, 1e-9));
        // the same sheet 1e-6 away is a thin slab, not a double sheet
        let far = b.map(|p| [p[0], p[1], p[2] + 1e-6]);
        assert!(!overlapping_near_coplanar(A, far, 1e-9));
    }

    #[test]
    fn touching_neighbours_do_not_overlap() {
        // flat neighbour across the hypotenuse, slightly bent: touches along the shared edge only
        let n = [[1.0, 0.0, 0.0], [1.0, 1.0, 1e-12], [0.0, 1.0, 0.0]];
        assert!(!overlapping_near_coplanar(A, n, 1e-9));
        // fan neighbour sharing only the origin
        let f = [[0.0, 0.0, 0.0], [0.0, -1.0, 0.0], [-1.0, -1.0, 1e-13]];
        assert!(!overlapping_near_coplanar(A, f, 1e-9));
        // folded back over the hypotenuse: overlaps
        let fold = [[1.0, 0.0, 0.0], [0.2, 0.2, 1e-12], [0.0, 1.0, 0.0]];
        assert!(overlapping_near_coplanar(A, fold, 1e-9));
        // degenerate triangles have no area
        let line = [[0.1, 0.1, 0.0], [0.2, 0.2, 0.0], [0.3, 0.3, 0.0]];
        assert!(!overlapping_near_coplanar(A, line, 1e-9));
    }

    #[test]
    fn interior_overlap_2d_cases() {
        let a = [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]];
        // contained, crossing, touching by a vertex, touching along an edge, disjoint
        assert!(interiors_overlap_2d(
            a,
            [[0.1, 0.1], [0.5, 0.1], [0.1, 0.5]]
        ));
        assert!(interiors_overlap_2d(
            a,
            [[1.0, -1.0], [1.0, 3.0], [-1.0, 1.0]]
        ));
        assert!(!interiors_overlap_2d(
            a,
            [[2.0, 0.0], [3.0, 0.0], [3.0, 1.0]]
        ));
        assert!(!interiors_overlap_2d(
            a,
            [[2.0, 0.0], [0.0, 2.0], [2.0, 2.0]]
        ));
        assert!(!interiors_overlap_2d(
            a,
            [[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]]
        ));
        // a star of David: no vertex inside the other, interiors still meet
        let up = [[0.0, 0.0], [2.0, 0.0], [1.0, 1.8]];
        let down = [[0.0, 1.2], [1.0, -0.6], [2.0, 1.2]];
        assert!(interiors_overlap_2d(up, down));
        // order of vertices does not matter
        assert!(interiors_overlap_2d(
            [a[2], a[1], a[0]],
            [down[1], down[0], down[2]]
        ));
    }
}
