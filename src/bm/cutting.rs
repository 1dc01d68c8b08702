//! Samples of the cutting diagram (paper §2.2, Fig. 4e/4f): the boundary of the flat zones.
//!
//! For a site a (a contour vertex of another face of the cell) its Moebius cell M(a) on face f is the
//! set of section points whose maximal empty tangent sphere touches a first. The Delaunay
//! triangulation carries it (see `branching`): M(a) is approximated by the internal grounded
//! triangles of f whose `Vf` apex is a. If a and a' are neighbours along their contour, M(a) is
//! connected and M(a') is not, then M(a) ∩ M(a') lies on the cutting diagram: pruning keeps only
//! one piece of φ⁻¹(a') attached, the others become flat, and their border with M(a) is where the
//! flat zone ends. Every grounded edge separating an apex-a triangle from an
//! apex-a' triangle approximates a piece of that border, running roughly along it (not across it:
//! the edge and a a' are the two grounded edges of a `Tee` tet), so its sample is the point where
//! r_a = r_a' (a quadratic) on the line through the edge's midpoint perpendicular to the edge,
//! nearest to the midpoint and within the edge's length, kept only if no other site has a smaller
//! radius there (it is on M(a) ∩ M(a')). The samples are thinned to the face's contour density like
//! the branching samples; the caller inserts them with the branching samples and re-triangulates,
//! so the flat zone's border follows the diagram.
//!
//! Connectivity of M(a): triangles with apex a are connected through shared grounded edges that are
//! neither contour edges nor external, and also when their `Vf` tets are face-connected around a
//! through tets that step 1 keeps (`Vf`, `Ee`, see `join_around_apex`). Without the second rule a
//! sparse face, where each site owns a triangle or two and neighbouring labels jump, shows
//! "disconnected" cells everywhere (measured: 22 to 330 samples per shared file, mostly where no
//! flat zone follows); with it, a cell counts as disconnected when the outside of a section (on f,
//! or on a's face) separates its pieces, which is the continuous definition for parallel planes
//! (a Voronoi cell is convex, only the section can cut it) and where pruning makes a flat zone.
//!
//! Decisions are combinatorial: triangles, edges and tets are internal or external by the exact
//! point-in-section tests of `Classifier`, neighbours along a contour are the cell's contour edges
//! (Steiner splits applied). Only the position of a sample is a floating-point construction.
//!
//! Chains: each sample carries its site pair (a, a'); two samples are consecutive when their source
//! edges share an endpoint that no third source edge of the pair has (the separating edges form
//! polylines along M(a) ∩ M(a')), after thinning along these chains (`chains::thin_chains`). The
//! cell makes consecutive samples Delaunay edges with Steiner points on the diagram
//! (`chains::conform_pairs`, paper §3's Delaunay conformity condition).
use super::branching::{contour_spacing, Site, SiteIndex};
use super::cell_input::{edge_key, CellInput, IdMap, IdSet, Where};
use super::chains::{thin_chains, Chains, DiagramSample, Kind, SlotDiagram};
use super::classify::{tet_type, Classifier, TetType};
use super::complex::{Complex, NONE};
use super::guard::{bucket, ContourGuard};
use crate::sections::{dot, sub};

/// Cutting-diagram samples of every slot of the cell. `taken` are samples already placed this round
/// (the branching samples): new samples keep half the contour spacing away from them too.
/// `apex` is `branching::apex_triangles` of the triangulation `cx` (tet types `ty`).
/// Each sample carries its diagram identity; two are consecutive (linked) when their
/// source edges (same site pair) share an endpoint that no third source edge of the pair has, and
/// the diagram between them stays in the section and the two sites' cells (`chains`).
pub fn sample_chains(
    input: &CellInput,
    cx: &Complex,
    ty: &[TetType],
    cl: &mut Classifier,
    apex: &[Vec<([u32; 3], u32)>],
    taken: &[DiagramSample],
) -> Chains {
    // neighbours along a contour: the contour edges of every slot (an apex on slot g is a contour
    // vertex of g; its neighbours are the ends of its contour edges)
    let mut contour_pairs: Vec<(u32, u32)> = input
        .slots
        .iter()
        .flat_map(|sl| sl.contour_edges().iter().copied())
        .collect();
    contour_pairs.sort_unstable();
    contour_pairs.dedup();
    let mut out = Chains::default();
    // one list per slot
    for (s, tri_apex) in apex.iter().enumerate() {
        if tri_apex.is_empty() {
            continue;
        }
        let edges = cutting_edges(input, cx, ty, cl, s, tri_apex, &contour_pairs);
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
        for t in taken.iter().filter(|t| t.slot == s) {
            thin.occupy(t.uv);
        }
        let d = SlotDiagram::new(input, s);
        let n = d.n;
        let mut cands = Vec::with_capacity(edges.len());
        // (site pair, endpoint) → source edges
        let mut at_vertex: IdMap<((u32, u32), u32), Vec<u32>> = IdMap::default();
        for (i, &((p, q), (a, b))) in edges.iter().enumerate() {
            let sites = edge_key(a, b);
            for v in [p, q] {
                at_vertex.entry((sites, v)).or_default().push(i as u32);
            }
            let cand = diagram_point_near_edge(input, s, n, (p, q), (a, b))
                .filter(|&uv| {
                    slot.locator().locate_clear(uv, clearance(slot, p, q)) == Where::Inside
                        && not_dominated(input, s, n, &d.sites, &d.index, uv, a)
                })
                .map(|uv| DiagramSample {
                    slot: s,
                    uv,
                    p3: slot.geom().to_3d(uv),
                    kind: Kind::Cutting,
                    sites,
                });
            cands.push(cand);
        }
        let mut links: Vec<(u32, u32)> = at_vertex
            .values()
            .filter(|l| l.len() == 2)
            .map(|l| (l[0].min(l[1]), l[0].max(l[1])))
            .collect();
        links.sort_unstable();
        let mut cont = |a: u32, b: u32| {
            a == b
                || (input.mask[a as usize] & input.mask[b as usize] != 0 && !cl.edge_external(a, b))
        };
        out.extend(thin_chains(cands, &links, &mut thin, |x, y| {
            d.between(input, x.uv, y.uv, x.sites, y.sites, &mut cont)
                .is_some()
        }));
    }
    out
}

/// The grounded edges of slot `s` that separate a triangle with apex a from one with apex a', a and
/// a' neighbours along a contour with M(a) connected and M(a') not: ((p, q), (a, a')), sorted.
fn cutting_edges(
    input: &CellInput,
    cx: &Complex,
    ty: &[TetType],
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
        .filter(|&(e, _, _)| !slot.contour_edges().contains(&e))
        .collect();
    inner.sort_unstable();
    // connected components of each apex's triangles, through shared inner edges (the point location
    // of an edge only where it matters: same apex here, the cutting edges below)
    let mut uf = UnionFind::new(tri_apex.len());
    for &((p, q), t1, t2) in &inner {
        if tri_apex[t1 as usize].1 == tri_apex[t2 as usize].1 && !cl.edge_external(p, q) {
            uf.union(t1, t2);
        }
    }
    join_around_apex(input, cx, ty, cl, tri_apex, &mut uf);
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
        .filter(|&((p, q), _)| !cl.edge_external(p, q))
        .collect()
}

/// Joins the pieces of each apex's triangles (union-find over `tri_apex`) whose `Vf` tets are
/// face-connected around the apex a through tets that step 1 keeps and step 2 considers (`Vf`,
/// `Ee`), across faces containing a. Pieces joined so are one φ⁻¹(a) for the pruning (no
/// singularity at a, no flat zone), however the grounded triangles between them are labelled (a
/// sparse face gives each site a triangle or two, and the labels of neighbouring triangles jump);
/// pieces separated there are what pruning cuts apart.
fn join_around_apex(
    input: &CellInput,
    cx: &Complex,
    ty: &[TetType],
    cl: &mut Classifier,
    tri_apex: &[([u32; 3], u32)],
    uf: &mut UnionFind,
) {
    let mut by_apex: IdMap<u32, Vec<u32>> = IdMap::default();
    for (i, &(_, apex)) in tri_apex.iter().enumerate() {
        by_apex.entry(apex).or_default().push(i as u32);
    }
    let mut apexes: Vec<u32> = by_apex
        .iter()
        .filter(|(_, ts)| {
            let mut r: Vec<u32> = ts.iter().map(|&t| uf.find(t)).collect();
            r.sort_unstable();
            r.dedup();
            r.len() >= 2
        })
        .map(|(&a, _)| a)
        .collect();
    apexes.sort_unstable();
    for a in apexes {
        let tris = &by_apex[&a];
        // the Vf tet of each triangle: the tet of a's star holding the triangle
        let mut claimed: IdMap<u32, u32> = IdMap::default();
        let mut starts = Vec::new();
        for &i in tris {
            let f = tri_apex[i as usize].0;
            if let Some(&t) = cx.star[a as usize]
                .iter()
                .find(|&&t| f.iter().all(|v| cx.tets[t as usize].contains(v)))
            {
                starts.push((t, i));
            }
        }
        for (t0, i) in starts {
            if let Some(&j) = claimed.get(&t0) {
                uf.union(i, j);
                continue;
            }
            claimed.insert(t0, i);
            let tv0 = cx.tets[t0 as usize];
            let (_, g0, _) = tet_type(tv0.map(|v| input.mask[v as usize]));
            if cl.tet_external(&tv0, ty[t0 as usize], g0) {
                continue;
            }
            let mut stack = vec![t0];
            while let Some(t) = stack.pop() {
                let tv = cx.tets[t as usize];
                for (k, &opposite) in tv.iter().enumerate() {
                    let nb = cx.nbr[t as usize][k];
                    // faces containing a: opposite the other three vertices
                    if opposite == a || nb == NONE {
                        continue;
                    }
                    if let Some(&j) = claimed.get(&nb) {
                        uf.union(i, j);
                        continue;
                    }
                    let nv = cx.tets[nb as usize];
                    let nty = ty[nb as usize];
                    if !matches!(nty, TetType::Vf | TetType::Ee) {
                        continue;
                    }
                    let (_, g, _) = tet_type(nv.map(|v| input.mask[v as usize]));
                    if cl.tet_external(&nv, nty, g) {
                        continue;
                    }
                    claimed.insert(nb, i);
                    stack.push(nb);
                }
            }
        }
    }
}

/// How far a sample found across edge (p, q) must be from the section boundary: a millionth of
/// the edge (see [`super::cell_input::SectionLocator::locate_clear`]).
fn clearance(slot: &super::cell_input::Slot, p: u32, q: u32) -> f64 {
    let (a, b) = (slot.uv[p as usize], slot.uv[q as usize]);
    super::chains::SAMPLE_CLEARANCE * (b[0] - a[0]).hypot(b[1] - a[1])
}

/// A point of M(a) ∩ M(b) near grounded edge (p, q) of slot `s`, in the slot's (u,v): the root of
/// r_a = r_b nearest to the edge's midpoint on the line through it perpendicular to the edge, within
/// the edge's length. (The edge separating an apex-a triangle from an apex-b one approximates the
/// diagram and runs roughly along it, so the diagram is found across the edge, not on it.) `None`
/// when there is no root there.
fn diagram_point_near_edge(
    input: &CellInput,
    s: usize,
    n: [f64; 3],
    (p, q): (u32, u32),
    (a, b): (u32, u32),
) -> Option<[f64; 2]> {
    let slot = &input.slots[s];
    let plane = *slot.geom();
    let (p2, q2) = (slot.uv[p as usize], slot.uv[q as usize]);
    let site = |x: u32| {
        let x3 = input.points[x as usize];
        (plane.to_2d(x3), dot(n, sub(x3, plane.origin)))
    };
    diagram_point_across(p2, q2, site(a), site(b))
}

/// The root of r_a = r_b (sites given by projection and height) nearest to the midpoint of p2 q2
/// on the line through it perpendicular to p2 q2, within the length of p2 q2 of the midpoint.
pub(super) fn diagram_point_across(
    p2: [f64; 2],
    q2: [f64; 2],
    a: ([f64; 2], f64),
    b: ([f64; 2], f64),
) -> Option<[f64; 2]> {
    let m = [0.5 * (p2[0] + q2[0]), 0.5 * (p2[1] + q2[1])];
    // perpendicular of the edge, as long as the edge
    let d = [q2[1] - p2[1], p2[0] - q2[0]];
    let (from, to) = ([m[0] - d[0], m[1] - d[1]], [m[0] + d[0], m[1] + d[1]]);
    let t = equal_radius_parameters(from, to, a, b)
        .into_iter()
        .min_by(|x, y| (x - 0.5).abs().total_cmp(&(y - 0.5).abs()))?;
    Some([
        from[0] + t * (to[0] - from[0]),
        from[1] + t * (to[1] - from[1]),
    ])
}

/// Parameters t in [0, 1] on segment p→q (in a plane) where r_a(t) = r_b(t), sites given by their
/// projection and height (> 0). On the plane r_x(t) = h_x / 2 + |p + t (q − p) − x'|² / (2 h_x),
/// x' the projection of site x and h_x its height (constant over the plane): r_a − r_b is a
/// quadratic in t, solved in closed form (the cancellation-free variant).
fn equal_radius_parameters(
    p: [f64; 2],
    q: [f64; 2],
    (a, ha): ([f64; 2], f64),
    (b, hb): ([f64; 2], f64),
) -> Vec<f64> {
    if !(ha > 0.0 && hb > 0.0) {
        return Vec::new();
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
    let scale = qa.abs().max(qb.abs()).max(qc.abs());
    let mut roots = Vec::new();
    if !(scale > 0.0 && scale.is_finite()) {
        return roots;
    }
    if qa.abs() <= 1e-12 * scale {
        // equal heights in effect: a line (the bisector)
        if qb != 0.0 {
            roots.push(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let k = -0.5 * (qb + qb.signum() * disc.sqrt());
            roots.push(k / qa);
            if k != 0.0 {
                roots.push(qc / k);
            }
        }
    }
    roots.retain(|t| (0.0..=1.0).contains(t));
    roots
}

/// Is `uv` (on slot `s`) on the boundary of M(a): no site has a smaller tangent-sphere radius there
/// than a (up to rounding)?
fn not_dominated(
    input: &CellInput,
    s: usize,
    n: [f64; 3],
    sites: &[Site],
    index: &SiteIndex,
    uv: [f64; 2],
    a: u32,
) -> bool {
    let plane = *input.slots[s].geom();
    let x = plane.to_3d(uv);
    let r = |p: [f64; 3]| {
        let h = dot(n, sub(p, x));
        if h > 0.0 {
            dot(sub(p, x), sub(p, x)) / (2.0 * h)
        } else {
            f64::INFINITY
        }
    };
    let ra = r(input.points[a as usize]);
    let mut best = f64::INFINITY;
    index.visit(uv, |k| {
        best = best.min(r(sites[k].1));
        best
    });
    ra <= best * (1.0 + 1e-9)
}

/// Points in a plane bucketed by cells of size `r`: is a new point closer than `r` to one of them,
/// or does it encroach a guarded contour edge ([`ContourGuard`])?
pub(super) struct Thinning {
    r: f64,
    cells: IdMap<(i64, i64), Vec<[f64; 2]>>,
    guard: Option<ContourGuard>,
}

impl Thinning {
    pub(super) fn new(r: f64) -> Thinning {
        Thinning {
            r,
            cells: IdMap::default(),
            guard: None,
        }
    }

    /// As [`Thinning::new`], and a point that encroaches a contour edge `guard` holds is near.
    pub(super) fn guarded(r: f64, guard: ContourGuard) -> Thinning {
        Thinning {
            guard: Some(guard),
            ..Thinning::new(r)
        }
    }

    pub(super) fn occupy(&mut self, q: [f64; 2]) {
        if q.iter().all(|c| c.is_finite()) {
            let k = bucket(q, self.r);
            self.cells.entry(k).or_default().push(q);
        }
    }

    pub(super) fn near(&self, q: [f64; 2]) -> bool {
        let (kx, ky) = bucket(q, self.r);
        (kx - 1..=kx + 1).any(|x| {
            (ky - 1..=ky + 1).any(|y| {
                self.cells.get(&(x, y)).is_some_and(|l| {
                    l.iter()
                        .any(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) < self.r * self.r)
                })
            })
        }) || self.guard.as_ref().is_some_and(|g| g.encroaches(q))
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

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::bm::branching::apex_triangles;
    use crate::bm::cell::delaunay_tets;
    use crate::bm::cell_input::{SectionLocator, Slot, SlotRun};
    use crate::bm::classify::tet_types;
    use crate::sections::Plane;

    /// A closed polygon of `n` vertices on the circle of centre (cx, cy) and radius `r`.
    pub(crate) fn circle(cx: f64, cy: f64, r: f64, n: usize) -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [cx + r * a.cos(), cy + r * a.sin()]
            })
            .collect()
    }

    /// The paper's configuration (Fig. 4d): one circle on z = 0 facing four circles on z = 1; the
    /// bottom face's branching diagram is the cross between the four circles' projections.
    pub(crate) fn one_facing_four() -> CellInput {
        let four: Vec<Vec<[f64; 2]>> = [(-0.6, -0.6), (0.6, -0.6), (0.6, 0.6), (-0.6, 0.6)]
            .iter()
            .map(|&(x, y)| circle(x, y, 0.4, 24))
            .collect();
        slab(&[circle(0.0, 0.0, 1.2, 48)], &four)
    }

    /// The slab cell between z = 0 (slot 0, below) and z = 1 (slot 1, above) with the given contour
    /// loops (x, y) on each plane.
    pub(crate) fn slab(bottom: &[Vec<[f64; 2]>], top: &[Vec<[f64; 2]>]) -> CellInput {
        let mut input = CellInput {
            cell: 0,
            global: Vec::new(),
            points: Vec::new(),
            mask: Vec::new(),
            tags: Vec::new(),
            apexes: crate::delaunay::PlaneApexes::default(),
            slots: Vec::new(),
            local_planes: Vec::new(),
        };
        let mut per_slot = Vec::new();
        for (s, (z, loops)) in [(0.0, bottom), (1.0, top)].into_iter().enumerate() {
            let geom = Plane::from_equation([0.0, 0.0, 1.0], -z).unwrap();
            let mut ids = Vec::new();
            for l in loops {
                let mut li = Vec::new();
                for p in l {
                    li.push(input.points.len() as u32);
                    input.global.push(input.points.len() as u32);
                    input.points.push([p[0], p[1], z]);
                    input.mask.push(1 << s);
                }
                ids.push(li);
            }
            per_slot.push((geom, ids, s == 1));
        }
        let n = input.points.len();
        for (s, (geom, loops, outward)) in per_slot.into_iter().enumerate() {
            let uv: Vec<[f64; 2]> = (0..n)
                .map(|v| {
                    if input.mask[v] >> s & 1 == 1 {
                        geom.to_2d(input.points[v])
                    } else {
                        [f64::NAN; 2]
                    }
                })
                .collect();
            let mut contour_edges = IdSet::default();
            for l in &loops {
                for i in 0..l.len() {
                    contour_edges.insert(edge_key(l[i], l[(i + 1) % l.len()]));
                }
            }
            let uv_loops: Vec<Vec<[f64; 2]>> = loops
                .iter()
                .map(|l| l.iter().map(|&v| uv[v as usize]).collect())
                .collect();
            input.slots.push(Slot {
                face: s as u32,
                plane: s as u32,
                outward_is_plane_normal: outward,
                loops,
                uv,
                loop_areas: Vec::new(),
                local_uv: Vec::new(),
                run: Some(Box::new(SlotRun {
                    geom,
                    contour_edges,
                    locator: SectionLocator::new(&uv_loops),
                })),
                beyond_may_attach: false,
            });
        }
        input.tags = (0..n)
            .map(|v| {
                let planes: Vec<(u32, [f64; 2])> = (0..2)
                    .filter(|&s| input.mask[v] >> s & 1 == 1)
                    .map(|s| (s as u32, input.slots[s].uv[v]))
                    .collect();
                crate::delaunay::PointTags::new(v as u64, &planes)
            })
            .collect();
        input
    }

    /// Counter-clockwise rectangle [x0, x1] × [y0, y1] sampled every `step` along its sides.
    fn rectangle(x0: f64, x1: f64, y0: f64, y1: f64, step: f64) -> Vec<[f64; 2]> {
        let mut out = Vec::new();
        let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            let m = (len / step).round().max(1.0) as usize;
            for i in 0..m {
                let t = i as f64 / m as f64;
                out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
            }
        }
        out
    }

    /// The top contour: a diamond of radius 0.3 around the origin, vertices on the axes.
    fn diamond() -> Vec<[f64; 2]> {
        vec![[0.3, 0.0], [0.0, 0.3], [-0.3, 0.0], [0.0, -0.3]]
    }

    fn run(input: &CellInput) -> (Complex, Vec<TetType>, Vec<DiagramSample>) {
        let cx = Complex::new(input.points.len(), delaunay_tets(&input.points).unwrap());
        let ty = tet_types(input, &cx);
        let mut cl = Classifier::new(input);
        let apex = apex_triangles(input, &cx, &ty, &cl);
        let samples = sample_chains(input, &cx, &ty, &mut cl, &apex, &[]).samples;
        (cx, ty, samples)
    }

    #[test]
    fn equal_radius_parameters_solve_the_quadratic() {
        // equal heights (parallel planes): the bisector of the projections, x = 0.25 here
        let t =
            equal_radius_parameters([0.0, 0.0], [1.0, 0.0], ([0.0, 1.0], 2.0), ([0.5, 1.0], 2.0));
        assert_eq!(t.len(), 1);
        assert!((t[0] - 0.25).abs() < 1e-12);
        // heights differ: r_a(x) = 1/2 + x²/2 (a over 0 at height 1), r_b(x) = 1 + (x − 1/2)²/4
        // (b over 1/2 at height 2): a circle of the Moebius diagram, crossed twice by the x axis
        let a = ([0.0, 0.0], 1.0);
        let b = ([0.5, 0.0], 2.0);
        let ts = equal_radius_parameters([-3.0, 0.0], [3.0, 0.0], a, b);
        assert_eq!(ts.len(), 2, "{ts:?}");
        for t in ts {
            let x = -3.0 + 6.0 * t;
            let r = |(c, h): ([f64; 2], f64)| 0.5 * h + (x - c[0]).powi(2) / (2.0 * h);
            assert!((r(a) - r(b)).abs() < 1e-12, "{} {}", r(a), r(b));
        }
        // the segment stays inside the circle: none
        assert!(equal_radius_parameters([0.0, 0.0], [0.5, 0.0], a, b).is_empty());
    }

    /// Paper Fig. 4e/4f: the bottom section is two rectangles with a gap; the top contour is a small
    /// diamond over the gap. The Moebius (here Voronoi) cells on the bottom of the diamond's vertices
    /// (0, ±0.3) reach across the gap into both rectangles (disconnected), those of (±0.3, 0) stay in
    /// one rectangle (connected): the cutting diagram is M(±0.3, 0) ∩ M(0, ±0.3), the diagonals
    /// |y| = |x| inside the rectangles.
    #[test]
    fn samples_on_the_border_of_a_disconnected_moebius_cell() {
        let bottom = vec![
            rectangle(0.2, 3.0, -1.0, 1.0, 0.2),
            rectangle(-3.0, -0.2, -1.0, 1.0, 0.2),
        ];
        let input = slab(&bottom, &[diamond()]);
        let (cx, ty, samples) = run(&input);
        // the separating edges: between the triangles of a connected cell (apex (±0.3, 0)) and of a
        // disconnected one (apex (0, ±0.3)), one per quadrant here
        let mut cl = Classifier::new(&input);
        let tri_apex = &apex_triangles(&input, &cx, &ty, &cl)[0];
        let pairs: Vec<(u32, u32)> = input.slots[1].contour_edges().iter().copied().collect();
        let edges = cutting_edges(&input, &cx, &ty, &mut cl, 0, tri_apex, &pairs);
        assert_eq!(edges.len(), 4, "{edges:?}");
        for (_, (a, b)) in &edges {
            let (pa, pb) = (input.points[*a as usize], input.points[*b as usize]);
            assert!(pa[1] == 0.0 && pb[0] == 0.0, "{pa:?} {pb:?}");
        }
        let on_bottom: Vec<&DiagramSample> = samples.iter().filter(|s| s.slot == 0).collect();
        eprintln!(
            "{} samples, {} on the bottom",
            samples.len(),
            on_bottom.len()
        );
        for s in &on_bottom {
            eprintln!("{:?}", s.p3);
        }
        // every bottom sample is on a diagonal (bisector of two diamond vertices), inside a rectangle
        for s in &on_bottom {
            let [x, y, z] = s.p3;
            assert_eq!(z, 0.0);
            assert!(
                (x.abs() - y.abs()).abs() < 1e-9,
                "{:?} is off the diagram",
                s.p3
            );
            assert!(x.abs() > 0.2 && x.abs() < 1.0, "{:?}", s.p3);
        }
        // on all four arcs (one per quadrant)
        for (sx, sy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            assert!(
                on_bottom
                    .iter()
                    .any(|s| s.p3[0] * sx > 0.0 && s.p3[1] * sy > 0.0),
                "no sample in quadrant ({sx}, {sy})"
            );
        }
    }

    /// One rectangle under the diamond: every Moebius cell on the bottom is connected, and the
    /// bottom rectangles' vertices see one convex contour above: no cutting sample anywhere.
    #[test]
    fn no_samples_when_every_moebius_cell_is_connected() {
        let bottom = vec![rectangle(-3.0, 3.0, -1.0, 1.0, 0.2)];
        let input = slab(&bottom, &[diamond()]);
        let (_, _, samples) = run(&input);
        assert!(samples.is_empty(), "{samples:?}");
    }
}
