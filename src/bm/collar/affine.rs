//! The least distorting affine map of a cell that lifts every section point of its faces by the
//! collar height: a linear program of twelve unknowns (a translation and a matrix).
//!
//! A homothety lifts every face alike but moves far points in proportion to the cell's width; a
//! squeeze along one normal keeps widths but fails where the faces are not parallel. Between these,
//! the map x ↦ x + h(τ + G x̃) (x̃ = (x − c)/reach) that maximises the smallest lift η ≤ 1 of the
//! points on the cell's planes, with no point of the cell moving more than `max_shift`, and,
//! nearly as high, moves points least. Affine functions take their extremes at extreme points, so the
//! constraints are written at the convex hull of each plane's points and the corners of the
//! cell's bounding box. The result is checked exactly like the other candidates.
use super::{dist, CellPart, Contraction};
use crate::arrangement::ArrPlane;
use crate::bm::refine::Triangulation;
use crate::fxhash::FxHashMap;
use microlp::{ComparisonOp, OptimizationDirection, Problem, Variable};

/// Smallest lift worth a map, as a fraction of the collar height.
const MIN_LIFT: f64 = 1e-3;

/// The corners of the convex hull of `pts` (Andrew's monotone chain; collinear points dropped).
fn hull_2d(mut pts: Vec<([f64; 2], usize)>) -> Vec<usize> {
    pts.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
    pts.dedup_by(|a, b| a.0 == b.0);
    if pts.len() < 3 {
        return pts.iter().map(|p| p.1).collect();
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<([f64; 2], usize)> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &([f64; 2], usize)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2].0, hull[hull.len() - 1].0, p.0) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull.iter().map(|p| p.1).collect()
}

/// The unknowns: τ (3), G row-major (9), and one more (η or the shift bound).
struct Unknowns {
    tau: [Variable; 3],
    g: [[Variable; 3]; 3],
}

impl Unknowns {
    fn new(lp: &mut Problem, g_bound: f64) -> Unknowns {
        let free = (f64::NEG_INFINITY, f64::INFINITY);
        Unknowns {
            tau: [0; 3].map(|_| lp.add_var(0.0, free)),
            g: [[0; 3]; 3].map(|row| row.map(|_| lp.add_var(0.0, (-g_bound, g_bound)))),
        }
    }

    /// The terms of w·(τ + G x̃).
    fn along(&self, w: [f64; 3], x: [f64; 3]) -> Vec<(Variable, f64)> {
        let mut e: Vec<(Variable, f64)> = self.tau.iter().copied().zip(w).collect();
        for (row, wi) in self.g.iter().zip(w) {
            e.extend(row.iter().zip(x).map(|(&g, xj)| (g, wi * xj)));
        }
        e
    }
}

/// Points on one plane: (u,v) in its frame, vertex id.
type PlanePoints = Vec<([f64; 2], usize)>;

/// The constraints of a cell: (inward unit normal, scaled point) per hull corner of each plane's
/// points, and the scaled corners of the bounding box.
struct CellConstraints {
    lifts: Vec<([f64; 3], [f64; 3])>,
    corners: Vec<[f64; 3]>,
}

fn constraints(
    k: &Triangulation,
    part: &CellPart,
    arr_planes: &[ArrPlane],
    c: [f64; 3],
    reach: f64,
) -> CellConstraints {
    let scaled = |x: [f64; 3]| [0, 1, 2].map(|i| (x[i] - c[i]) / reach);
    let mut vertices: Vec<u32> = part
        .kept
        .iter()
        .flat_map(|&i| k.kept[i])
        .chain(part.bases.iter().flat_map(|b| b.0))
        .collect();
    vertices.sort_unstable();
    vertices.dedup();
    let mut on_plane: FxHashMap<u32, PlanePoints> = FxHashMap::default();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &v in &vertices {
        let x = k.positions[v as usize];
        for i in 0..3 {
            lo[i] = lo[i].min(x[i]);
            hi[i] = hi[i].max(x[i]);
        }
        for &p in &k.planes[v as usize] {
            let uv = arr_planes[p as usize].plane.to_2d(x);
            on_plane.entry(p).or_default().push((uv, v as usize));
        }
    }
    let mut lifts = Vec::new();
    let mut planes: Vec<(u32, PlanePoints)> = on_plane.into_iter().collect();
    planes.sort_unstable_by_key(|p| p.0);
    for (p, pts) in planes {
        let plane = &arr_planes[p as usize].plane;
        let inward = if plane.signed_distance(c) > 0.0 {
            plane.normal
        } else {
            plane.normal.map(|x| -x)
        };
        for v in hull_2d(pts) {
            lifts.push((inward, scaled(k.positions[v])));
        }
    }
    let corners = (0..8)
        .map(|m| scaled([0, 1, 2].map(|i| if m >> i & 1 == 0 { lo[i] } else { hi[i] })))
        .collect();
    CellConstraints { lifts, corners }
}

/// Lifts at least `eta` (in collar heights) at every hull corner of every plane.
fn lift_rows(
    lp: &mut Problem,
    u: &Unknowns,
    cs: &CellConstraints,
    eta: Option<Variable>,
    at_least: f64,
) {
    for &(w, x) in &cs.lifts {
        let mut e = u.along(w, x);
        if let Some(eta) = eta {
            e.push((eta, -1.0));
        }
        lp.add_constraint(e.as_slice(), ComparisonOp::Ge, at_least);
    }
}

/// Moves at most `bound` (in collar heights, per coordinate) at every corner of the bounding box.
fn shift_rows(
    lp: &mut Problem,
    u: &Unknowns,
    cs: &CellConstraints,
    bound: Option<Variable>,
    fixed: f64,
) {
    for &x in &cs.corners {
        for i in 0..3 {
            let mut w = [0.0; 3];
            w[i] = 1.0;
            for sign in [1.0, -1.0] {
                let mut e: Vec<(Variable, f64)> = u
                    .along(w, x)
                    .into_iter()
                    .map(|(v, a)| (v, sign * a))
                    .collect();
                if let Some(b) = bound {
                    e.push((b, -1.0));
                }
                lp.add_constraint(e.as_slice(), ComparisonOp::Le, fixed);
            }
        }
    }
}

/// The map, or `None` where no affine map lifts every plane's points (or the program fails).
pub(super) fn best_affine(
    k: &Triangulation,
    part: &CellPart,
    arr_planes: &[ArrPlane],
    height: f64,
    max_shift: f64,
) -> Option<Contraction> {
    let c = part.centre();
    let reach = part
        .kept
        .iter()
        .flat_map(|&i| k.kept[i])
        .chain(part.bases.iter().flat_map(|b| b.0))
        .map(|v| dist(k.positions[v as usize], c))
        .fold(0.0, f64::max);
    if !(reach > 0.0 && height > 0.0) {
        return None;
    }
    let cs = constraints(k, part, arr_planes, c, reach);
    // I + (h/reach)G keeps orientation while every entry of (h/reach)G is below 1/4
    let g_bound = 0.25 * reach / height;
    let sigma = max_shift / height;
    // the largest lift (at most one height), and among those nearly as high the smallest move:
    // one program with the move weighted far below the lift (a move of `sigma` costs 1% of it)
    let mut lp = Problem::new(OptimizationDirection::Maximize);
    let u = Unknowns::new(&mut lp, g_bound);
    let eta = lp.add_var(1.0, (0.0, 1.0));
    let bound = lp.add_var(-0.01 / sigma, (0.0, sigma));
    lift_rows(&mut lp, &u, &cs, Some(eta), 0.0);
    shift_rows(&mut lp, &u, &cs, Some(bound), 0.0);
    let sol = lp.solve().ok()?;
    if sol[eta] < MIN_LIFT {
        return None;
    }
    let t = u.tau.map(|v| height * sol[v]);
    let g = u.g.map(|row| row.map(|v| height / reach * sol[v]));
    Some(Contraction { c, t, g })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_keeps_corners_only() {
        let pts = vec![
            ([0.0, 0.0], 0),
            ([1.0, 0.0], 1),
            ([1.0, 1.0], 2),
            ([0.0, 1.0], 3),
            ([0.5, 0.5], 4),
            ([0.5, 0.0], 5),
        ];
        let mut h = hull_2d(pts);
        h.sort_unstable();
        assert_eq!(h, vec![0, 1, 2, 3]);
    }
}
