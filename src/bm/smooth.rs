//! `--smooth` (issue 19): ∂K refined between the planes and faired there, every section kept
//! exactly as the input gives it.
//!
//! *Refinement.* Every edge of ∂K whose two ends share no plane (it runs from one plane to another,
//! or off the planes) and is longer than `min_edge` is split at its midpoint, with every
//! tetrahedron of the cells' triangulation T around it (`refine::grow` with no growth, so T stays
//! conforming), for `rounds` rounds. The midpoint of such an edge lies strictly inside its
//! arrangement cell (the cell is convex and the ends are not on one plane of it): on no plane.
//! Each new point then moves towards the middle of the cubic Hermite curve of its edge (PN
//! triangles' edge curve: tangent at each end to ∂K's sides there, so a contour vertex's two
//! sides meet with one slope).
//!
//! *Fairing.* Then `sweeps` Gauss–Seidel sweeps of the bi-Laplacian (the umbrella of umbrellas of
//! Kobbelt et al. 1998, uniform weights, the step along ∂K's normal) move the new points, or of the
//! Laplacian with `order` 1. Points on the planes are fixed. Why the bi-Laplacian: with positions
//! fixed on curves only, the Laplacian's minimiser is a membrane, flat between the curves (it pulls
//! ∂K back to the straight ruling the pruning made: measured, no gain); the bi-Laplacian's is the
//! thin plate, continuous in slope across each plane, which bulges between the planes as a smooth
//! object does. Measurements: `docs/design/accuracy.md`.
//!
//! *Why the solid stays valid.* A move is taken, halved (up to `HALVINGS` times) or refused so that
//! every tetrahedron of T around the point keeps its orientation (exact `orient3d`, never flat),
//! the point stays strictly on its side of every plane within its reach (so in its cell, off the
//! planes) and within its reach of where refinement put it (its star in T's farthest vertex). A
//! point inside T (closed star) then stays in the kernel of its star: T stays a triangulation, K a
//! conforming complex, R ∩ P = A on every plane. A point on the outer boundary of T (an open star)
//! could still fold ∂K over a neighbour outside T: ∂K's triangles at moved points are tested
//! exactly for crossings, and the points of a crossing pair (with whatever that makes flip) go back
//! where refinement put them, counted and warned.
//!
//! *Limits.* The pruning keeps flat tetrahedra under ∂K where two contours' edges nearly line up;
//! such a one lets ∂K bend one way only, so many moves are halved and the faired surface is
//! crumpled at that scale. Most of the distance to the truth on oblique planes is elsewhere (webs
//! between separate parts), which no fairing between the planes reaches.
use super::refine::{edge, Triangulation};
use crate::arrangement::ArrPlane;
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::geom::bvh::{triangle_boxes, Bvh};
use crate::geom::predicates::orient3d;
use crate::mesh::Stars;
use crate::sections::{dot, sub};
use rayon::prelude::*;

/// What `--smooth` does (library: `DelaunayOptions::smooth`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smoothing {
    /// Rounds of refinement of ∂K's edges between the planes (each splits every such edge once:
    /// 2 rounds put three points on an edge from one plane to the next).
    pub rounds: u32,
    /// Gauss–Seidel sweeps of the fairing.
    pub sweeps: u32,
    /// 2: bi-Laplacian (thin plate, the default); 1: Laplacian (membrane).
    pub order: u32,
    /// Edges shorter than this (relative to the bounding-box diagonal) are not split.
    pub min_edge: f64,
}

impl Default for Smoothing {
    fn default() -> Self {
        Smoothing {
            rounds: 1,
            sweeps: 10,
            order: 2,
            min_edge: 2e-3,
        }
    }
}

/// What smoothing did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothStats {
    /// Midpoints refinement added, and the edges it asked for but did not split (a child would
    /// have flipped).
    pub points: u64,
    pub edges_not_split: u64,
    /// Sweeps made (fewer than asked when the points stopped moving).
    pub sweeps: u64,
    /// Steps halved to keep T valid, and steps refused after every halving.
    pub steps_shortened: u64,
    pub steps_refused: u64,
    /// Points put back where their fairing found them (∂K crossed itself at them).
    pub put_back: u64,
    /// Farthest a point ended from where refinement put it, and how many points moved.
    pub max_shift: f64,
    pub moved: u64,
}

/// Times a step is halved before it is refused.
const HALVINGS: usize = 6;

/// A point keeps at least this distance (relative to the diagonal) from a plane it starts off
/// (or half its distance at the start, where that is less): the collar's default height, far
/// below any feature. Closer, a faired point changed the sections a hair off the plane (Horsers
/// at 1e-7 off: 1.4e-4 → 3.9e-4 with 1e-9 here).
const PLANE_CLEARANCE: f64 = 1e-4;

/// Sweeps stop once no point moved farther than this (relative to the diagonal).
const STILL: f64 = 1e-7;

/// Refine ∂K between the planes and fair it (module doc). `planes`: the arrangement's planes
/// (plane ids in `k.planes` index them); `diag`: the bounding-box diagonal.
pub fn smooth(
    k: &mut Triangulation,
    planes: &[ArrPlane],
    how: Smoothing,
    diag: f64,
) -> SmoothStats {
    let mut stats = SmoothStats::default();
    let first = k.positions.len();
    // where refinement put each new point
    let mut origins: Vec<[f64; 3]> = Vec::new();
    for _ in 0..how.rounds {
        let tris = super::faces::boundary(k.kept);
        let normals = side_normals(k, &tris);
        let (points, targets) = split_points(k, &tris, &normals, how.min_edge * diag);
        if points.is_empty() {
            break;
        }
        let asked = points.len() as u64;
        let n0 = k.positions.len();
        let grown = super::refine::grow(k, &[], points);
        stats.points += grown.points;
        stats.edges_not_split += asked - grown.points;
        let new: Vec<u32> = (n0 as u32..k.positions.len() as u32).collect();
        origins.extend(new.iter().map(|&v| k.positions[v as usize]));
        if new.is_empty() {
            continue;
        }
        let fair = Fairing::new(k, &new, planes, diag);
        for &v in &new {
            if let Some(&target) = targets.get(&bits(k.positions[v as usize])) {
                fair.move_towards(k.positions, v, target, &mut stats);
            }
        }
        stats.put_back += fair.put_back_crossings(k);
    }
    let free: Vec<u32> = (first as u32..k.positions.len() as u32).collect();
    if !free.is_empty() && how.sweeps > 0 {
        let fair = Fairing::new(k, &free, planes, diag);
        for _ in 0..how.sweeps {
            stats.sweeps += 1;
            let moved = fair.sweep(k.positions, how.order, &mut stats);
            if moved < STILL * diag {
                break;
            }
        }
        stats.put_back += fair.put_back_crossings(k);
    }
    for (p, o) in k.positions[first..].iter().zip(&origins) {
        let d = sub(*p, *o);
        let d = dot(d, d).sqrt();
        if d > 0.0 {
            stats.moved += 1;
            stats.max_shift = stats.max_shift.max(d);
        }
    }
    stats
}

/// A position's bits, to find a split point's target by where refinement put it.
fn bits(p: [f64; 3]) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// Per vertex, ∂K's unit normal there from its triangles off the planes (area-weighted; zero at
/// a vertex with none, or where they cancel): the sides of the solid between the planes, whose
/// slope the curve through a contour vertex follows, not the section it bounds.
fn side_normals(k: &Triangulation, tris: &[[u32; 3]]) -> Vec<[f64; 3]> {
    let mut out = vec![[0.0; 3]; k.positions.len()];
    for t in tris {
        if super::refine::on_a_plane(k.planes, t) {
            continue;
        }
        let [a, b, c] = t.map(|v| k.positions[v as usize]);
        let n = crate::sections::cross(sub(b, a), sub(c, a));
        for &v in t {
            for i in 0..3 {
                out[v as usize][i] += n[i];
            }
        }
    }
    for n in &mut out {
        let len = dot(*n, *n).sqrt();
        *n = if len > 0.0 {
            n.map(|x| x / len)
        } else {
            [0.0; 3]
        };
    }
    out
}

/// The middle of the cubic Hermite (PN) curve from `a` to `b` tangent to the planes normal to
/// `na` at `a` and `nb` at `b` (Vlachos et al. 2001: the control points are the thirds of the
/// chord projected on those planes); the chord's midpoint where a normal is zero.
fn curved_midpoint(a: [f64; 3], na: [f64; 3], b: [f64; 3], nb: [f64; 3]) -> [f64; 3] {
    let wa = dot(sub(b, a), na);
    let wb = dot(sub(a, b), nb);
    let ca: [f64; 3] = std::array::from_fn(|i| (2.0 * a[i] + b[i] - wa * na[i]) / 3.0);
    let cb: [f64; 3] = std::array::from_fn(|i| (2.0 * b[i] + a[i] - wb * nb[i]) / 3.0);
    std::array::from_fn(|i| (a[i] + 3.0 * ca[i] + 3.0 * cb[i] + b[i]) / 8.0)
}

/// Per edge to split, where refinement puts its point.
type SplitPoints = FxHashMap<(u32, u32), [f64; 3]>;
/// Per split point (by its bits), where it moves to.
type Targets = FxHashMap<[u64; 3], [f64; 3]>;

/// The edges of ∂K to split (ends sharing no plane, at least `min_len` long) at their midpoints,
/// and per midpoint (by its bits) where the curve through the edge's ends puts it.
fn split_points(
    k: &Triangulation,
    tris: &[[u32; 3]],
    normals: &[[f64; 3]],
    min_len: f64,
) -> (SplitPoints, Targets) {
    let mut points = FxHashMap::default();
    let mut targets = FxHashMap::default();
    for f in tris {
        for (a, b) in [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])] {
            let e = edge(a, b);
            if points.contains_key(&e) || super::refine::edge_on_a_plane(k.planes, a, b) {
                continue;
            }
            let (pa, pb) = (k.positions[e.0 as usize], k.positions[e.1 as usize]);
            let d = sub(pa, pb);
            if dot(d, d) < min_len * min_len {
                continue;
            }
            let mid: [f64; 3] = std::array::from_fn(|i| 0.5 * (pa[i] + pb[i]));
            let curved = curved_midpoint(pa, normals[e.0 as usize], pb, normals[e.1 as usize]);
            points.insert(e, mid);
            // two edges with one midpoint: neither moves
            if targets.insert(bits(mid), curved).is_some() {
                targets.insert(bits(mid), mid);
            }
        }
    }
    (points, targets)
}

/// The fairing's fixed data: ∂K's graph, T's stars at the free points, where each started, how
/// far it may go and the planes within that reach.
struct Fairing {
    free: Vec<u32>,
    /// Position of a free vertex in `free`.
    slot: FxHashMap<u32, usize>,
    start: Vec<[f64; 3]>,
    reach: Vec<f64>,
    /// Per free point: (plane, its side there, least distance kept).
    near_planes: Vec<Vec<(usize, bool, f64)>>,
    planes: Vec<([f64; 3], f64)>,
    /// Every tetrahedron of T with a free vertex, with its orientation at the start (> 0 or < 0).
    tets: Vec<[u32; 4]>,
    signs: Vec<bool>,
    stars: Stars<u32>,
    /// ∂K's vertex neighbours (CSR over all vertices).
    nb_start: Vec<usize>,
    nb: Vec<u32>,
    /// ∂K's triangles at the start, and those at each vertex.
    tris: Vec<[u32; 3]>,
    tri_stars: Stars<u32>,
    diag: f64,
}

impl Fairing {
    fn new(k: &Triangulation, free: &[u32], planes: &[ArrPlane], diag: f64) -> Fairing {
        let n = k.positions.len();
        let is_free = super::refine::marks(n, free.iter().copied());
        // every tetrahedron of T keeps its orientation: T stays a triangulation of the cells
        let tets: Vec<[u32; 4]> = (k.kept.iter())
            .chain(k.fillable.iter())
            .chain(k.external.iter())
            .filter(|t| t.iter().any(|&v| is_free[v as usize]))
            .copied()
            .collect();
        let pos = |v: u32| k.positions[v as usize];
        let signs = tets
            .iter()
            .map(|t| orient3d(pos(t[0]), pos(t[1]), pos(t[2]), pos(t[3])) > 0.0)
            .collect();
        let stars = Stars::new(n, &tets);
        let tris = super::faces::boundary(k.kept);
        let (nb_start, nb) = surface_neighbours(n, &tris);
        let tri_stars = Stars::new(n, &tris);
        let planes: Vec<([f64; 3], f64)> = planes
            .iter()
            .map(|p| (p.plane.normal, p.plane.offset))
            .collect();
        let slot = free.iter().enumerate().map(|(i, &v)| (v, i)).collect();
        let start: Vec<[f64; 3]> = free.iter().map(|&v| pos(v)).collect();
        // how far a point may go: the farthest vertex of its star in T (a closed star's kernel
        // lies within that anyway; an open one is held near where it was)
        let reach: Vec<f64> = free
            .iter()
            .map(|&v| {
                (stars[v as usize].iter())
                    .flat_map(|&t| tets[t as usize])
                    .map(|w| {
                        let d = sub(pos(w), pos(v));
                        dot(d, d)
                    })
                    .fold(0.0, f64::max)
                    .sqrt()
            })
            .collect();
        let clearance = PLANE_CLEARANCE * diag;
        let near_planes = free
            .iter()
            .zip(&reach)
            .map(|(&v, &r)| {
                let p = pos(v);
                (planes.iter().enumerate())
                    .filter_map(|(i, &(nrm, off))| {
                        let d = dot(nrm, p) + off;
                        (d.abs() <= 2.0 * r + clearance).then_some((
                            i,
                            d > 0.0,
                            clearance.min(0.5 * d.abs()),
                        ))
                    })
                    .collect()
            })
            .collect();
        Fairing {
            free: free.to_vec(),
            slot,
            start,
            reach,
            near_planes,
            planes,
            tets,
            signs,
            stars,
            nb_start,
            nb,
            tris,
            tri_stars,
            diag,
        }
    }

    fn neighbours(&self, v: u32) -> &[u32] {
        &self.nb[self.nb_start[v as usize]..self.nb_start[v as usize + 1]]
    }

    /// The umbrella of `v`: the mean of its neighbours on ∂K, less `v`.
    fn umbrella(&self, p: &[[f64; 3]], v: u32) -> [f64; 3] {
        let nb = self.neighbours(v);
        if nb.is_empty() {
            return [0.0; 3];
        }
        let mut s = [0.0; 3];
        for &w in nb {
            for i in 0..3 {
                s[i] += p[w as usize][i];
            }
        }
        let m = nb.len() as f64;
        std::array::from_fn(|i| s[i] / m - p[v as usize][i])
    }

    /// ∂K's unit normal at `v`: the area-weighted mean of its triangles' (zero if they cancel).
    fn normal(&self, p: &[[f64; 3]], v: u32) -> [f64; 3] {
        let mut s = [0.0; 3];
        for &t in &self.tri_stars[v as usize] {
            let [a, b, c] = self.tris[t as usize].map(|w| p[w as usize]);
            let n = crate::sections::cross(sub(b, a), sub(c, a));
            for i in 0..3 {
                s[i] += n[i];
            }
        }
        let len = dot(s, s).sqrt();
        if len > 0.0 {
            s.map(|x| x / len)
        } else {
            [0.0; 3]
        }
    }

    /// The Gauss–Seidel step of `v` for the (bi-)Laplacian, along ∂K's normal there (the
    /// tangential part only slides points along ∂K, and flips thin tetrahedra doing so).
    fn normal_step(&self, p: &[[f64; 3]], v: u32, order: u32) -> [f64; 3] {
        let d = self.step(p, v, order);
        let n = self.normal(p, v);
        let h = dot(d, n);
        n.map(|x| x * h)
    }

    /// The Gauss–Seidel step of `v` for the (bi-)Laplacian.
    fn step(&self, p: &[[f64; 3]], v: u32, order: u32) -> [f64; 3] {
        let u = self.umbrella(p, v);
        if order < 2 {
            return u;
        }
        let nb = self.neighbours(v);
        if nb.is_empty() {
            return [0.0; 3];
        }
        let m = nb.len() as f64;
        let (mut uu, mut nu) = ([0.0; 3], 0.0);
        for &w in nb {
            let uw = self.umbrella(p, w);
            for i in 0..3 {
                uu[i] += uw[i] / m;
            }
            nu += 1.0 / (self.neighbours(w).len().max(1) as f64 * m);
        }
        let nu = 1.0 + nu;
        std::array::from_fn(|i| -(uu[i] - u[i]) / nu)
    }

    /// Whether `v` at `q` keeps every tetrahedron of T around it oriented as it was, stays on its
    /// side of the planes near it and within its reach.
    fn allowed(&self, p: &[[f64; 3]], v: u32, q: [f64; 3]) -> bool {
        let s = self.slot[&v];
        let d = sub(q, self.start[s]);
        if dot(d, d) > self.reach[s] * self.reach[s] {
            return false;
        }
        for &(i, side, keep) in &self.near_planes[s] {
            let (nrm, off) = self.planes[i];
            let d = dot(nrm, q) + off;
            if (d > 0.0) != side || d.abs() < keep {
                return false;
            }
        }
        self.tets_kept(p, v, q)
    }

    fn tets_kept(&self, p: &[[f64; 3]], v: u32, q: [f64; 3]) -> bool {
        self.stars[v as usize].iter().all(|&t| {
            let tet = self.tets[t as usize];
            let at = |w: u32| if w == v { q } else { p[w as usize] };
            let o = orient3d(at(tet[0]), at(tet[1]), at(tet[2]), at(tet[3]));
            o != 0.0 && (o > 0.0) == self.signs[t as usize]
        })
    }

    /// Move `v` towards `target`, as far as [`Fairing::allowed`] lets it.
    fn move_towards(&self, p: &mut [[f64; 3]], v: u32, target: [f64; 3], stats: &mut SmoothStats) {
        let d = sub(target, p[v as usize]);
        if dot(d, d) != 0.0 {
            self.step_by(p, v, d, stats);
        }
    }

    /// Move `v` by `d`, or half of it, ... up to `HALVINGS` times, the first that
    /// [`Fairing::allowed`] lets it (counted); the length of the move made.
    fn step_by(&self, p: &mut [[f64; 3]], v: u32, mut d: [f64; 3], stats: &mut SmoothStats) -> f64 {
        let from = p[v as usize];
        for h in 0..=HALVINGS {
            let q = std::array::from_fn(|i| from[i] + d[i]);
            if self.allowed(p, v, q) {
                p[v as usize] = q;
                if h > 0 {
                    stats.steps_shortened += 1;
                }
                return dot(d, d).sqrt();
            }
            d = d.map(|x| 0.5 * x);
        }
        stats.steps_refused += 1;
        0.0
    }

    /// One sweep over the free points; the longest move made.
    fn sweep(&self, p: &mut [[f64; 3]], order: u32, stats: &mut SmoothStats) -> f64 {
        let mut longest: f64 = 0.0;
        for &v in &self.free {
            let d = self.normal_step(p, v, order);
            if dot(d, d).sqrt() < STILL * self.diag * 1e-3 {
                continue;
            }
            longest = longest.max(self.step_by(p, v, d, stats));
        }
        longest
    }

    /// Put the points of ∂K's crossing triangle pairs at moved points back where they started,
    /// with every free point whose tetrahedra that would flip, until ∂K crosses itself nowhere
    /// there (at worst every point is back: the refined, valid, start). How many went back.
    fn put_back_crossings(&self, k: &mut Triangulation) -> u64 {
        let mut back: FxHashSet<u32> = FxHashSet::default();
        loop {
            let crossing = self.crossing_points(k);
            let fresh: Vec<u32> = crossing.into_iter().filter(|v| !back.contains(v)).collect();
            if fresh.is_empty() {
                break;
            }
            let mut todo = fresh;
            while let Some(v) = todo.pop() {
                if !back.insert(v) {
                    continue;
                }
                k.positions[v as usize] = self.start[self.slot[&v]];
                // a neighbour still moved may now flip a tetrahedron shared with v
                for &t in &self.stars[v as usize] {
                    let tet = self.tets[t as usize];
                    let pos = |w: u32| k.positions[w as usize];
                    let o = orient3d(pos(tet[0]), pos(tet[1]), pos(tet[2]), pos(tet[3]));
                    if o == 0.0 || (o > 0.0) != self.signs[t as usize] {
                        todo.extend(
                            tet.iter()
                                .filter(|w| self.slot.contains_key(w) && !back.contains(w)),
                        );
                    }
                }
            }
        }
        back.len() as u64
    }

    /// The free points of ∂K's triangles that cross another triangle of ∂K (exactly) or overlap
    /// one nearly in its plane (the double sheets `check` counts, at twice its tolerance), among
    /// the triangles with a free point that moved.
    fn crossing_points(&self, k: &Triangulation) -> Vec<u32> {
        use crate::eval::near_coplanar::{
            normal, overlapping_near_coplanar_with_normals, NEAR_COPLANAR_RELATIVE_TOLERANCE,
        };
        let tris = super::faces::boundary(k.kept);
        let positions: &[[f64; 3]] = k.positions;
        let moved = |v: u32| {
            self.slot
                .get(&v)
                .is_some_and(|&s| positions[v as usize] != self.start[s])
        };
        let bvh = Bvh::build(triangle_boxes(positions, &tris));
        let tol = 2.0 * NEAR_COPLANAR_RELATIVE_TOLERANCE * bvh.bounds().diagonal();
        let pts = |t: [u32; 3]| t.map(|v| positions[v as usize]);
        let normals: Vec<_> = tris.par_iter().map(|&t| normal(pts(t))).collect();
        let at_moved: Vec<bool> = (tris.par_iter())
            .map(|t| t.iter().any(|&v| moved(v)))
            .collect();
        // each pair once: from its first triangle at a moved point
        let mut out: Vec<u32> = (0..tris.len())
            .into_par_iter()
            .filter(|&i| at_moved[i])
            .flat_map_iter(|i| {
                let t = tris[i];
                let grown = bvh.item_box(i as u32).grown(2.0 * tol);
                let mut found = Vec::new();
                bvh.for_each_overlap(&grown, |j| {
                    let j = j as usize;
                    let u = tris[j];
                    if j == i || (j < i && at_moved[j]) {
                        return;
                    }
                    if crate::geom::tri_tri::mesh_triangles_intersect(t, u, positions)
                        || overlapping_near_coplanar_with_normals(
                            pts(t),
                            normals[i],
                            pts(u),
                            normals[j],
                            tol,
                        )
                    {
                        found.extend(t.iter().chain(&u).copied());
                    }
                });
                found
            })
            .collect();
        out.retain(|v| self.slot.contains_key(v));
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// ∂K's vertex neighbours as CSR arrays over `n` vertices.
fn surface_neighbours(n: usize, tris: &[[u32; 3]]) -> (Vec<usize>, Vec<u32>) {
    let mut pairs: Vec<(u32, u32)> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .flat_map(|(a, b)| [(a, b), (b, a)])
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    let mut start = vec![0usize; n + 1];
    for &(a, _) in &pairs {
        start[a as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    (start, pairs.into_iter().map(|(_, b)| b).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The curve's middle between two points of the unit circle with their radial normals lies
    /// between the chord and the arc (the cubic approximates it: 0.884 at 90°); with normals
    /// across the chord, or none, it is the chord's midpoint.
    #[test]
    fn a_curved_midpoint_follows_the_normals() {
        let (a, b) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let m = curved_midpoint(a, a, b, b);
        let r = dot(m, m).sqrt();
        assert!((m[0] - m[1]).abs() < 1e-15 && m[2] == 0.0, "{m:?}");
        assert!(r > 0.88 && r < 1.0, "radius {r}");
        let n = [0.0, 0.0, 1.0];
        assert_eq!(curved_midpoint(a, n, b, n), [0.5, 0.5, 0.0]);
        assert_eq!(curved_midpoint(a, [0.0; 3], b, [0.0; 3]), [0.5, 0.5, 0.0]);
    }

    /// ∂K's neighbours are symmetric and listed once.
    #[test]
    fn surface_neighbours_are_each_edge_once_each_way() {
        let (start, nb) = surface_neighbours(4, &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]);
        for v in 0..4usize {
            let mut got = nb[start[v]..start[v + 1]].to_vec();
            got.sort_unstable();
            let want: Vec<u32> = (0..4).filter(|&w| w != v as u32).collect();
            assert_eq!(got, want);
        }
    }
}
