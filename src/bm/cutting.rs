//! Samples of the cutting diagram (paper §2.2, Fig. 4e/4f): the boundary of the flat zones.
//!
//! For a site a (a contour vertex of another face of the cell) its Moebius cell M(a) on face f is the
//! set of section points whose maximal empty tangent sphere touches a first. The Delaunay
//! triangulation carries it (see `branching`): M(a) is approximated by the internal grounded
//! triangles of f whose `Vf` apex is a. If a and a' are neighbours along their contour, M(a) is
//! connected and M(a') is not, then M(a) ∩ M(a') lies on the cutting diagram: pruning keeps only
//! one piece of φ⁻¹(a') attached, the others become flat, and their border with M(a) is where the
//! flat zone ends. We place a sample on every grounded edge separating an apex-a triangle from an
//! apex-a' triangle, where r_a = r_a' (a quadratic in the edge parameter), thin the samples to the
//! face's contour density like the branching samples, and the caller inserts them and
//! re-triangulates with the branching samples, so the flat zone's border follows the diagram.
//!
//! Decisions are combinatorial: triangles are internal by the exact point-in-section test
//! (`Classifier`), connectivity of M(a) is through shared grounded edges that are neither contour
//! edges nor external, neighbours along a contour are the cell's contour edges (Steiner splits
//! applied). Only the position of a sample is a floating-point construction.
//!
//! Not done: consecutive cutting samples are not forced to be Delaunay edges (the branching samples
//! are not either); the samples only refine the triangulation along the diagram.
use super::branching::{apex_triangles, contour_spacing, into_cell_normal};
use super::cell_input::{edge_key, CellInput, IdMap, IdSet, Where};
use super::classify::{Classifier, TetType};
use super::complex::Complex;
use crate::sections::{dot, sub};

/// A diagram sample: (slot, (u,v) in the slot's plane, 3D position).
pub type Sample = (usize, [f64; 2], [f64; 3]);

/// Cutting-diagram samples of every slot of the cell. `taken` are samples already placed this round
/// (the branching samples): new samples keep half the contour spacing away from them too.
pub fn samples(input: &CellInput, cx: &Complex, ty: &[TetType], taken: &[Sample]) -> Vec<Sample> {
    let mut cl = Classifier::new(input);
    // neighbours along a contour: the contour edges of every slot (an apex on slot g is a contour
    // vertex of g; its neighbours are the ends of its contour edges)
    let mut contour_pairs: Vec<(u32, u32)> = input
        .slots
        .iter()
        .flat_map(|sl| sl.contour_edges.iter().copied())
        .collect();
    contour_pairs.sort_unstable();
    contour_pairs.dedup();
    let mut out = Vec::new();
    for s in 0..input.slots.len() {
        let tri_apex = apex_triangles(input, cx, ty, &cl, s);
        if tri_apex.is_empty() {
            continue;
        }
        let edges = cutting_edges(input, &mut cl, s, &tri_apex, &contour_pairs);
        if edges.is_empty() {
            continue;
        }
        let h = contour_spacing(input, s);
        if h <= 0.0 {
            continue;
        }
        let mut thin = Thinning::new(0.5 * h);
        let slot = &input.slots[s];
        for v in 0..input.points.len() {
            if input.mask[v] >> s & 1 == 1 {
                thin.occupy(slot.uv[v]);
            }
        }
        for &(ts, q, _) in taken {
            if ts == s {
                thin.occupy(q);
            }
        }
        let n = into_cell_normal(input, s);
        for ((p, q), (a, b)) in edges {
            let Some(uv) = equal_radius_point(input, s, n, (p, q), (a, b)) else {
                continue;
            };
            if slot.locator.locate(uv) != Where::Inside || thin.near(uv) {
                continue;
            }
            thin.occupy(uv);
            out.push((s, uv, slot.geom.to_3d(uv)));
        }
    }
    out
}

/// The grounded edges of slot `s` that separate a triangle with apex a from one with apex a', a and
/// a' neighbours along a contour with M(a) connected and M(a') not: ((p, q), (a, a')), sorted.
fn cutting_edges(
    input: &CellInput,
    cl: &mut Classifier,
    s: usize,
    tri_apex: &[([u32; 3], u32)],
    contour_pairs: &[(u32, u32)],
) -> Vec<((u32, u32), (u32, u32))> {
    let slot = &input.slots[s];
    // grounded edge → the triangles on it
    let mut by_edge: IdMap<(u32, u32), Vec<u32>> = IdMap::default();
    for (i, (f, _)) in tri_apex.iter().enumerate() {
        for k in 0..3 {
            by_edge
                .entry(edge_key(f[k], f[(k + 1) % 3]))
                .or_default()
                .push(i as u32);
        }
    }
    let mut inner: Vec<((u32, u32), u32, u32)> = by_edge
        .iter()
        .filter(|(_, ts)| ts.len() == 2)
        .map(|(&e, ts)| (e, ts[0], ts[1]))
        .filter(|&(e, _, _)| !slot.contour_edges.contains(&e))
        .collect();
    inner.sort_unstable();
    inner.retain(|&((p, q), _, _)| !cl.edge_external(p, q));
    // connected components of each apex's triangles, through shared inner edges
    let mut uf = UnionFind::new(tri_apex.len());
    for &(_, t1, t2) in &inner {
        if tri_apex[t1 as usize].1 == tri_apex[t2 as usize].1 {
            uf.union(t1, t2);
        }
    }
    let mut roots: IdMap<u32, IdSet<u32>> = IdMap::default();
    for (i, &(_, apex)) in tri_apex.iter().enumerate() {
        let r = uf.find(i as u32);
        roots.entry(apex).or_default().insert(r);
    }
    let components = |v: u32| roots.get(&v).map_or(0, IdSet::len);
    // contour neighbours (a connected, a' not), as ordered pairs
    let mut cut: IdSet<(u32, u32)> = IdSet::default();
    for &(x, y) in contour_pairs {
        for (a, b) in [(x, y), (y, x)] {
            if components(a) == 1 && components(b) >= 2 {
                cut.insert((a, b));
            }
        }
    }
    if cut.is_empty() {
        return Vec::new();
    }
    inner
        .iter()
        .filter_map(|&(e, t1, t2)| {
            let (b1, b2) = (tri_apex[t1 as usize].1, tri_apex[t2 as usize].1);
            if cut.contains(&(b1, b2)) {
                Some((e, (b1, b2)))
            } else if cut.contains(&(b2, b1)) {
                Some((e, (b2, b1)))
            } else {
                None
            }
        })
        .collect()
}

/// The point of grounded edge (p, q) of slot `s` where the tangent-sphere radii of sites a and b are
/// equal, in the slot's (u,v); `None` when r_a − r_b does not change sign strictly inside the edge.
/// On the plane r_x(t) = h_x / 2 + |p + t (q − p) − x'|² / (2 h_x), x' the projection of site x and
/// h_x its height along `n` (constant over the plane), so r_a − r_b is a quadratic in t.
fn equal_radius_point(
    input: &CellInput,
    s: usize,
    n: [f64; 3],
    (p, q): (u32, u32),
    (a, b): (u32, u32),
) -> Option<[f64; 2]> {
    let slot = &input.slots[s];
    let plane = slot.geom;
    let (p2, q2) = (slot.uv[p as usize], slot.uv[q as usize]);
    let site = |x: u32| {
        let x3 = input.points[x as usize];
        (plane.to_2d(x3), dot(n, sub(x3, plane.origin)))
    };
    let t = equal_radius_parameter(p2, q2, site(a), site(b))?;
    Some([p2[0] + t * (q2[0] - p2[0]), p2[1] + t * (q2[1] - p2[1])])
}

/// Parameter t in (0, 1) on segment p→q (in a plane) where r_a(t) = r_b(t), sites given by their
/// projection and height (> 0); `None` without a strict sign change of r_a − r_b over [0, 1].
fn equal_radius_parameter(
    p: [f64; 2],
    q: [f64; 2],
    (a, ha): ([f64; 2], f64),
    (b, hb): ([f64; 2], f64),
) -> Option<f64> {
    if !(ha > 0.0 && hb > 0.0) {
        return None;
    }
    let e = [q[0] - p[0], q[1] - p[1]];
    let ee = e[0] * e[0] + e[1] * e[1];
    // coefficients of r_x(t) = A t² + B t + C
    let coef = |x: [f64; 2], h: f64| {
        let d = [p[0] - x[0], p[1] - x[1]];
        (
            ee / (2.0 * h),
            (d[0] * e[0] + d[1] * e[1]) / h,
            0.5 * h + (d[0] * d[0] + d[1] * d[1]) / (2.0 * h),
        )
    };
    let (aa, ba, ca) = coef(a, ha);
    let (ab, bb, cb) = coef(b, hb);
    let (qa, qb, qc) = (aa - ab, ba - bb, ca - cb);
    let g = |t: f64| (qa * t + qb) * t + qc;
    let (g0, g1) = (g(0.0), g(1.0));
    if !(g0 < 0.0 && g1 > 0.0 || g0 > 0.0 && g1 < 0.0) {
        return None;
    }
    // exactly one root in (0, 1): bisection on the sign change (robust for any qa, also tiny)
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let up = g0 < 0.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if (g(mid) < 0.0) == up {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    (t > 0.0 && t < 1.0).then_some(t)
}

/// Points in a plane bucketed by cells of size `r`: is a new point closer than `r` to one of them?
struct Thinning {
    r: f64,
    cells: IdMap<(i64, i64), Vec<[f64; 2]>>,
}

impl Thinning {
    fn new(r: f64) -> Thinning {
        Thinning {
            r,
            cells: IdMap::default(),
        }
    }

    fn key(&self, q: [f64; 2]) -> (i64, i64) {
        (
            (q[0] / self.r).floor() as i64,
            (q[1] / self.r).floor() as i64,
        )
    }

    fn occupy(&mut self, q: [f64; 2]) {
        if q.iter().all(|c| c.is_finite()) {
            let k = self.key(q);
            self.cells.entry(k).or_default().push(q);
        }
    }

    fn near(&self, q: [f64; 2]) -> bool {
        let (kx, ky) = self.key(q);
        (kx - 1..=kx + 1).any(|x| {
            (ky - 1..=ky + 1).any(|y| {
                self.cells.get(&(x, y)).is_some_and(|l| {
                    l.iter()
                        .any(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) < self.r * self.r)
                })
            })
        })
    }
}

struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let p = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = p;
            x = p;
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}
