//! Handles that no section witnesses, closed inside the complex (issue 19): K's extra handles
//! are loops of tetrahedra standing on sections whose other side is empty, so K cannot lose them
//! (R ∩ P = A); a handle is closed the other way, by a disk of unkept tetrahedra spanning its
//! tunnel. Such a disk cannot be grown one tetrahedron at a time (every tetrahedron of it but the
//! last leaves the topology as it is), so it is found by carving instead.
//!
//! 1. *Thinning.* Start from S = K ∪ the step-1 survivors (`Triangulation::fillable`: no grounded
//!    simplex outside its section, so S ∩ P ⊆ A on every plane) and remove survivors one at a time,
//!    farthest from K first (face steps within S), while a removal cannot create a tunnel or a
//!    cavity: t goes when X = t ∩ (S − t), a subcomplex of t's boundary sphere, is not the whole
//!    sphere and each of its components is contractible (Euler characteristic 1). By
//!    Mayer–Vietoris H₁ and H₂ of S − t then inject into those of S: a removal never adds a handle
//!    or a cavity; it may cut a handle or split a component. What is left beside K are the
//!    *membranes*: disks closing tunnels of K that S does not have, where the tunnels are narrowest.
//! 2. *Witnesses.* A tunnel through a hole of a section is witnessed: the section says the solid
//!    has a hole there. Survivors with all four vertices on holes of sections (the tube of
//!    tetrahedra joining a hole to the next plane's hole) are left out of S, so no membrane spans a
//!    hole.
//! 3. *Plugs.* A membrane is thin (tetrahedra meeting at edges and vertices): with it, ∂K is not a
//!    manifold. Membranes are taken into K in batches, each followed by the resolution's fill of
//!    gaps and growth at singular simplices (which only add); a batch stays when ∂K is then a
//!    manifold, has no more components (no new cavity) and its genus fell by at least one per
//!    membrane; otherwise it is undone, and the rest is tried without the membranes next to what
//!    stayed singular or bounds the new component (they are tried alone after), or else in halves;
//!    a single membrane that fails is refused (counted). Membranes that add no Euler characteristic
//!    close nothing of K and are refused unseen; a budget of batches bounds the cost (each is a
//!    few passes over K), what it leaves untried is counted and warned.
//!
//! Over 800 lines only with its unit tests (the test modules at the end); the code is shorter.
use super::complex::{outward_face, TET_EDGES};
use super::edges::EdgeTable;
use super::faces::FaceTable;
use super::refine::{edge, key3, key4, Triangulation};
use super::singular::{EdgeGaps, Snapshot};
use crate::eval::topology::UnionFind;
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::mesh::Stars;
use std::collections::{BinaryHeap, VecDeque};

/// What closing tunnels did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TunnelStats {
    /// Step-1 survivors in S (those not spanning holes).
    pub candidates: u64,
    /// Membranes thinning left, those taken (each closed a handle or more), and those refused.
    pub membranes: u64,
    pub tunnels_closed: u64,
    pub membranes_refused: u64,
    /// Batches of membranes undone (a refused membrane costs a few).
    pub batches_undone: u64,
    /// Membranes not tried: the budget of batches (`TESTS_BASE`) was spent.
    pub membranes_untested: u64,
    /// How many tetrahedra K grew by: membranes and what settling added around them.
    pub tets_added: u64,
    /// ∂K had singular simplices: nothing was tried.
    pub skipped_singular: bool,
    /// Total genus of ∂K before and after (0 when there was nothing to close).
    pub genus_before: i64,
    pub genus_after: i64,
}

/// S during thinning: which tetrahedra are in it and how many of them hold each vertex and edge.
struct Thinning<'a> {
    tets: &'a [[u32; 4]],
    faces: &'a FaceTable,
    stars: &'a Stars<u32>,
    /// [`FaceTable::neighbours`] of `tets`.
    adj: Vec<[u32; 4]>,
    in_s: Vec<bool>,
    vertex_count: Vec<u32>,
    /// Per edge number (`edges`), how many tetrahedra of S hold it.
    edges: EdgeTable,
    edge_count: Vec<u32>,
}

impl<'a> Thinning<'a> {
    fn new(
        tets: &'a [[u32; 4]],
        faces: &'a FaceTable,
        stars: &'a Stars<u32>,
        edges: EdgeTable,
        n_vertices: usize,
    ) -> Self {
        let mut vertex_count = vec![0u32; n_vertices];
        let mut edge_count = vec![0u32; edges.count];
        for (tet, ids) in tets.iter().zip(&edges.of_tet) {
            for &v in tet {
                vertex_count[v as usize] += 1;
            }
            for &e in ids {
                edge_count[e as usize] += 1;
            }
        }
        Thinning {
            tets,
            faces,
            stars,
            adj: faces.neighbours(tets.len()),
            in_s: vec![true; tets.len()],
            vertex_count,
            edges,
            edge_count,
        }
    }

    /// The tetrahedron across face `i` of `t` that is in S.
    fn across(&self, t: usize, i: usize) -> Option<usize> {
        (self.faces).across(self.tets, &self.adj, t, i, |o| self.in_s[o])
    }

    /// Whether removing `t` leaves no new tunnel and no new cavity (the module's rule).
    fn removable(&self, t: usize) -> bool {
        let tet = &self.tets[t];
        let face_in: [bool; 4] = std::array::from_fn(|i| self.across(t, i).is_some());
        if face_in.iter().all(|&b| b) {
            return false;
        }
        let vert_in: [bool; 4] = std::array::from_fn(|i| self.vertex_count[tet[i] as usize] > 1);
        let ids = &self.edges.of_tet[t];
        let edge_in: [bool; 6] = std::array::from_fn(|e| self.edge_count[ids[e] as usize] > 1);
        // components of X over its vertices, joined by its edges
        let mut comp = [0usize, 1, 2, 3];
        fn find(c: &mut [usize; 4], mut x: usize) -> usize {
            while c[x] != x {
                x = c[x];
            }
            x
        }
        for (e, &(a, b)) in TET_EDGES.iter().enumerate() {
            if edge_in[e] {
                let (ra, rb) = (find(&mut comp, a), find(&mut comp, b));
                if ra != rb {
                    comp[ra.max(rb)] = ra.min(rb);
                }
            }
        }
        // Euler characteristic per component (indexed by its root)
        let mut chi = [0i32; 4];
        for v in 0..4 {
            if vert_in[v] {
                chi[find(&mut comp, v)] += 1;
            }
        }
        for (e, &(a, _)) in TET_EDGES.iter().enumerate() {
            if edge_in[e] {
                chi[find(&mut comp, a)] -= 1;
            }
        }
        for (i, &on) in face_in.iter().enumerate() {
            if on {
                // any vertex of the face opposite i
                chi[find(&mut comp, (i + 1) % 4)] += 1;
            }
        }
        (0..4).all(|v| !vert_in[v] || find(&mut comp, v) != v || chi[v] == 1)
    }

    /// Take `t` out of S; the survivors whose X changed go to `push`.
    fn remove(&mut self, t: usize, mut push: impl FnMut(usize)) {
        self.in_s[t] = false;
        let tet = self.tets[t];
        for i in 0..4 {
            if let Some(o) = self.across(t, i) {
                push(o);
            }
        }
        let last_holder = |this: &Self, need: &[u32]| {
            this.stars[need[0] as usize]
                .iter()
                .map(|&o| o as usize)
                .find(|&o| this.in_s[o] && need.iter().all(|v| this.tets[o].contains(v)))
        };
        for (e, (a, b)) in TET_EDGES.into_iter().enumerate() {
            let key = edge(tet[a], tet[b]);
            let c = &mut self.edge_count[self.edges.of_tet[t][e] as usize];
            *c -= 1;
            if *c == 1 {
                if let Some(o) = last_holder(self, &[key.0, key.1]) {
                    push(o);
                }
            }
        }
        for v in tet {
            self.vertex_count[v as usize] -= 1;
            if self.vertex_count[v as usize] == 1 {
                if let Some(o) = last_holder(self, &[v]) {
                    push(o);
                }
            }
        }
    }
}

/// What it takes to settle ∂K after membranes are added (the resolution's growth).
#[derive(Clone, Copy, Debug)]
pub struct Settle {
    pub growth_rounds: usize,
    pub growth_distance: f64,
    /// A point growth adds closer than this to another vertex of its tetrahedra fails the batch
    /// (growth halves short edges: repeated, it would crowd points below what viewers weld).
    pub min_gap: f64,
    /// Two triangles of ∂K near a cut closer than this to each other's planes and overlapping
    /// there (a double sheet: the walls of a slit through slivers) fail the cut.
    pub near_coplanar: f64,
}

/// Close K's unwitnessed tunnels (the module's steps): membranes move from `fillable` into
/// `kept` where they leave ∂K a manifold with fewer handles. `on_hole`: per vertex, whether it
/// lies on a hole of a section. Nothing is tried when ∂K is not a manifold (`skipped_singular`):
/// settling membranes beside what the resolution left singular made double sheets (odd033); nor
/// when ∂K has genus 0 (no batch could lower it; the candidates are then not counted).
/// With the stats, ∂K as it leaves K.
pub(super) fn close(
    k: &mut Triangulation,
    on_hole: &[bool],
    settle: Settle,
) -> (TunnelStats, Option<Found>) {
    let mut stats = TunnelStats::default();
    let tris = super::faces::boundary(k.kept);
    let (edges, vertices) = super::fill::singular_simplices(&tris);
    if !edges.is_empty() || !vertices.is_empty() {
        stats.skipped_singular = true;
        return (stats, Some(Found::Singular));
    }
    let now = Surface::from_tris(tris);
    // a batch stays only when the genus falls: with none, thinning would find nothing to take
    if now.topology.genus == 0 {
        return (stats, Some(Found::Manifold(now)));
    }
    let membranes = thin(k, on_hole, &mut stats);
    if membranes.is_empty() {
        return (stats, Some(Found::Manifold(now)));
    }
    stats.genus_before = now.topology.genus;
    let mut batches = Batches {
        how: Move::Close,
        settle,
        now,
        budget: TESTS_BASE + membranes.len() / 8,
        stats: &mut stats,
    };
    batches.take(k, &membranes);
    let now = batches.now;
    stats.genus_after = now.topology.genus;
    // ∂K as each batch taken left it (a manifold: a batch stays only then)
    (stats, Some(Found::Manifold(now)))
}

/// ∂K as `close` left K.
pub(super) enum Found {
    Singular,
    Manifold(Surface),
}

/// Step 1: the membranes (groups of survivors joined through shared vertices) that thinning S
/// leaves beside K.
fn thin(k: &Triangulation, on_hole: &[bool], stats: &mut TunnelStats) -> Vec<Vec<[u32; 4]>> {
    let n_kept = k.kept.len();
    // step 2: a survivor with every vertex on holes could close a tunnel they witness
    let candidates = k
        .fillable
        .iter()
        .filter(|t| !t.iter().all(|&v| on_hole[v as usize]));
    let tets: Vec<[u32; 4]> = k.kept.iter().chain(candidates).copied().collect();
    stats.candidates = (tets.len() - n_kept) as u64;
    if tets.len() == n_kept {
        return Vec::new();
    }
    // three tables of S, built side by side
    let n = k.positions.len();
    let (faces, (stars, edges)) = rayon::join(
        || FaceTable::new(&tets),
        || rayon::join(|| Stars::<u32>::new(n, &tets), || EdgeTable::new(&tets)),
    );
    let mut s = Thinning::new(&tets, &faces, &stars, edges, n);
    let depth = depths(&s, n_kept);
    let mut heap: BinaryHeap<(u32, usize)> = (n_kept..tets.len()).map(|t| (depth[t], t)).collect();
    while let Some((_, t)) = heap.pop() {
        if !s.in_s[t] || !s.removable(t) {
            continue;
        }
        s.remove(t, |o| {
            if o >= n_kept {
                heap.push((depth[o], o));
            }
        });
    }
    let mut groups = membranes(&s, n_kept);
    stats.membranes = groups.len() as u64;
    // one that adds no Euler characteristic closes no handle of K (it is left for S's sake)
    groups.retain(|m| euler_gain(&s, n_kept, m) >= 1);
    stats.membranes_refused = stats.membranes - groups.len() as u64;
    groups
        .into_iter()
        .map(|m| m.into_iter().map(|t| tets[t]).collect())
        .collect()
}

/// What a batch does to K: membranes of unkept tetrahedra close tunnels (taken into K), cuts of
/// kept ones cut handles (`cuts`: they leave K for `external`, so that settling cannot take them
/// back).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Move {
    Close,
    Cut,
}

impl Move {
    /// Make the move with `batch` and settle ∂K: the singular simplices left, and the vertices
    /// whose stars in K changed (sorted).
    fn apply(
        self,
        k: &mut Triangulation,
        batch: &[Vec<[u32; 4]>],
        settle: Settle,
    ) -> (super::assembly::Sets, Vec<u32>) {
        let keys: FxHashSet<[u32; 4]> = batch.iter().flatten().map(|&t| key4(t)).collect();
        let mut touched: Vec<u32> = batch.iter().flatten().flatten().copied().collect();
        touched.sort_unstable();
        touched.dedup();
        match self {
            Move::Close => {
                let in_batch = super::refine::one_of(k.positions.len(), &keys);
                k.fillable.retain(|t| !in_batch(t));
                k.kept.extend(batch.iter().flatten().copied());
                // ∂K was a manifold: it is one again unless singular next to the membranes
                let sets =
                    super::assembly::singular_sets_after(k.kept, Default::default(), &touched);
                if !sets.0.is_empty() || !sets.1.is_empty() {
                    let (left, more) = settled(k, settle, sets);
                    touched.extend(more);
                    touched.sort_unstable();
                    touched.dedup();
                    return (left, touched);
                }
                (sets, touched)
            }
            Move::Cut => {
                let in_batch = super::refine::one_of(k.positions.len(), &keys);
                k.kept.retain(|t| !in_batch(t));
                k.external.extend(batch.iter().flatten().copied());
                // only the stars of the cut's vertices changed; its sides are then separated
                // (the resolution's fill would only close the cut again)
                let sets =
                    super::assembly::singular_sets_after(k.kept, Default::default(), &touched);
                let (sets, split) = super::cuts::separate(k, sets, settle.min_gap);
                touched.extend(split);
                touched.sort_unstable();
                touched.dedup();
                (sets, touched)
            }
        }
    }
}

/// Step 3's state: the move, how to settle, ∂K now (a manifold), the batches left.
pub(super) struct Batches<'a> {
    pub how: Move,
    pub settle: Settle,
    pub now: Surface,
    pub budget: usize,
    pub stats: &'a mut TunnelStats,
}

impl Batches<'_> {
    /// Step 3 for `batch`: take it if [`Batches::try_batch`] keeps it; else without the membranes
    /// blamed for the failure, then each of those alone; else each half.
    pub fn take(&mut self, k: &mut Triangulation, batch: &[Vec<[u32; 4]>]) {
        if batch.is_empty() {
            return;
        }
        if self.budget == 0 {
            self.stats.membranes_untested += batch.len() as u64;
            return;
        }
        self.budget -= 1;
        let blamed = match self.try_batch(k, batch) {
            Ok(grown) => {
                self.stats.tunnels_closed += batch.len() as u64;
                self.stats.tets_added += grown;
                return;
            }
            Err(blamed) => blamed,
        };
        self.stats.batches_undone += 1;
        if batch.len() == 1 {
            self.stats.membranes_refused += 1;
            return;
        }
        if !blamed.is_empty() && blamed.len() < batch.len() {
            let (rest, suspects): (Vec<usize>, Vec<usize>) =
                (0..batch.len()).partition(|i| !blamed.contains(i));
            let rest: Vec<Vec<[u32; 4]>> = rest.into_iter().map(|i| batch[i].clone()).collect();
            self.take(k, &rest);
            for i in suspects {
                self.take(k, std::slice::from_ref(&batch[i]));
            }
            return;
        }
        let (a, b) = batch.split_at(batch.len() / 2);
        self.take(k, a);
        self.take(k, b);
    }

    /// Take the membranes of `batch` into K and settle ∂K. Kept (`Ok`: how many tetrahedra K
    /// grew by) when ∂K is then a manifold with no more components than `now` and at least one
    /// handle fewer per membrane (`now` updated); else undone, with the membranes to blame
    /// (indices: those next to what stayed singular or to a new small component; none when the
    /// genus did not fall enough).
    fn try_batch(
        &mut self,
        k: &mut Triangulation,
        batch: &[Vec<[u32; 4]>],
    ) -> Result<u64, Vec<usize>> {
        let before = Snapshot::of(k);
        let (kept_before, points_before) = (k.kept.len(), k.positions.len());
        let (mut left, touched) = self.how.apply(k, batch, self.settle);
        left.1
            .extend(crowded_points(k, points_before, self.settle.min_gap));
        if self.how == Move::Cut && left.0.is_empty() && left.1.is_empty() {
            let tol = self.settle.near_coplanar;
            left.1.extend(double_sheets(k, batch, points_before, tol));
        }
        let blamed = if !left.0.is_empty() || !left.1.is_empty() {
            blame(k, batch, &left)
        } else {
            let mut after = self.now.after(k.kept, &touched);
            if self.how == Move::Close && after.may_hide_a_void(&mut self.now, &touched) {
                // membranes can close a pocket into a cavity: filled when no section witnesses it
                if super::voids::fill(k).tets_filled > 0 {
                    after = Surface::of(k.kept);
                }
            }
            let (now, then) = (self.now.topology, after.topology);
            if then.components <= now.components && then.genus + batch.len() as i64 <= now.genus {
                self.now = after;
                return Ok(k.kept.len().abs_diff(kept_before) as u64);
            }
            if then.components > now.components {
                // a membrane closed a pocket into a cavity a section witnesses: on its boundary
                let on_small = after.minor_vertices();
                (0..batch.len())
                    .filter(|&i| batch[i].iter().flatten().any(|v| on_small.contains(v)))
                    .collect()
            } else {
                Vec::new()
            }
        };
        before.restore(k);
        Err(blamed)
    }
}

/// The vertices of ∂K's triangles near a cut (through a vertex of `batch` or a point from
/// `first` on) that overlap a later such triangle nearly in its plane (within `tol`).
fn double_sheets(k: &Triangulation, batch: &[Vec<[u32; 4]>], first: usize, tol: f64) -> Vec<u32> {
    let mut mark: FxHashSet<u32> = batch.iter().flatten().flatten().copied().collect();
    mark.extend(first as u32..k.positions.len() as u32);
    let tris = super::assembly::boundary_near(k.kept, |v| mark.contains(&v));
    let pairs = crate::eval::check::overlapping_near_coplanar_pairs(k.positions, &tris, tol);
    let mut out: Vec<u32> = pairs.into_iter().flat_map(|[i, _]| tris[i]).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The points from `first` on with an edge of a kept tetrahedron shorter than `min_gap`.
fn crowded_points(k: &Triangulation, first: usize, min_gap: f64) -> Vec<u32> {
    let mut out = Vec::new();
    for t in k
        .kept
        .iter()
        .filter(|t| t.iter().any(|&v| v as usize >= first))
    {
        for (a, b) in TET_EDGES {
            let (a, b) = (t[a], t[b]);
            if (a as usize) < first && (b as usize) < first {
                continue;
            }
            let d = crate::sections::sub(k.positions[a as usize], k.positions[b as usize]);
            if crate::sections::dot(d, d) < min_gap * min_gap {
                out.push(a.max(b));
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The membranes of `batch` (indices) next to the singular simplices `left`: the one with a
/// vertex of the simplex, or else the one with the nearest vertex.
fn blame(k: &Triangulation, batch: &[Vec<[u32; 4]>], left: &super::assembly::Sets) -> Vec<usize> {
    let mut owner: FxHashMap<u32, usize> = FxHashMap::default();
    for (i, m) in batch.iter().enumerate() {
        for t in m {
            for &v in t {
                owner.insert(v, i);
            }
        }
    }
    let at = left.1.iter().copied().chain(left.0.iter().map(|e| e.0));
    let mut blamed: Vec<usize> = at
        .filter_map(|v| {
            owner.get(&v).copied().or_else(|| {
                let p = k.positions[v as usize];
                owner
                    .iter()
                    .map(|(&w, &i)| {
                        (
                            {
                                let d = crate::sections::sub(p, k.positions[w as usize]);
                                crate::sections::dot(d, d)
                            },
                            i,
                        )
                    })
                    .min_by(|a, b| a.0.total_cmp(&b.0))
                    .map(|x| x.1)
            })
        })
        .collect();
    blamed.sort_unstable();
    blamed.dedup();
    blamed
}

/// The resolution's fill and growth after membranes were added next to the `singular` simplices
/// of ∂K: those left (a manifold when there are none), and the vertices whose stars in K changed
/// (sorted). A membrane can also close a pocket into a cavity: `Batches::try_batch` looks.
fn settled(
    k: &mut Triangulation,
    settle: Settle,
    singular: super::assembly::Sets,
) -> (super::assembly::Sets, Vec<u32>) {
    let filled = super::fill::fill_near(k.kept, k.fillable, singular, FILL_ROUNDS);
    let (mut left, mut touched) = (filled.left, filled.touched);
    for how in [EdgeGaps::NearEdge, EdgeGaps::Whole] {
        if left.0.is_empty() && left.1.is_empty() {
            break;
        }
        let (stats, now) = super::singular::resolve(
            k,
            settle.growth_rounds,
            super::singular::Reach::near(settle.growth_distance),
            how,
            Some(left),
        );
        touched.extend(stats.touched);
        left = now.unwrap_or_else(|| super::assembly::singular_sets(k.kept));
    }
    (left, touched)
}

/// Most batches tried (each costs a few passes over K): this many, plus one per eight membranes;
/// membranes left when they are spent are counted as untested.
pub(super) const TESTS_BASE: usize = 24;

/// Most rounds of filling gaps after membranes were added.
const FILL_ROUNDS: usize = 8;

/// Components and total genus of ∂K (a manifold surface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Topology {
    pub components: usize,
    pub genus: i64,
}

/// ∂K's triangles, its components (joined through shared vertices) and its topology, for a
/// boundary whose every edge has two triangles (a manifold, or pinched only at vertices).
pub(super) struct Surface {
    tris: Vec<[u32; 3]>,
    /// Over the vertices below the largest one of `tris`.
    parts: UnionFind,
    n_vertices: usize,
    pub topology: Topology,
}

impl Surface {
    pub fn of(tets: &[[u32; 4]]) -> Surface {
        Surface::from_tris(super::faces::boundary(tets))
    }

    /// ∂K of `tets` when it is a manifold.
    pub fn of_manifold(tets: &[[u32; 4]]) -> Option<Surface> {
        let tris = super::faces::boundary(tets);
        let (edges, vertices) = super::fill::singular_simplices(&tris);
        (edges.is_empty() && vertices.is_empty()).then(|| Surface::from_tris(tris))
    }

    fn from_tris(tris: Vec<[u32; 3]>) -> Surface {
        let n = tris.iter().flatten().max().map_or(0, |&v| v as usize + 1);
        let mut parts = UnionFind::new(n);
        for t in &tris {
            parts.union(t[0] as usize, t[1] as usize);
            parts.union(t[0] as usize, t[2] as usize);
        }
        // per component χ = V − E + F = V − F/2, every edge being on two triangles
        let mut counts: FxHashMap<usize, (i64, i64)> = FxHashMap::default();
        let mut seen = vec![false; n];
        for t in &tris {
            let c = counts.entry(parts.find(t[0] as usize)).or_default();
            c.1 += 1;
            for &v in t {
                if !std::mem::replace(&mut seen[v as usize], true) {
                    c.0 += 1;
                }
            }
        }
        let topology = Topology {
            components: counts.len(),
            genus: counts.values().map(|&(v, f)| (2 - (v - f / 2)) / 2).sum(),
        };
        Surface {
            tris,
            parts,
            n_vertices: n,
            topology,
        }
    }

    /// ∂K after a change of K inside the stars of the sorted vertices `touched` (every edge of it
    /// still on two triangles: the caller checked): triangles through no touched vertex stay,
    /// those through one are read from the tetrahedra through one.
    pub fn after(&self, tets: &[[u32; 4]], touched: &[u32]) -> Surface {
        // touched is sorted: its last vertex sizes the marks (no pass over K for it)
        let mut mark = vec![false; touched.last().map_or(0, |&v| v as usize + 1)];
        for &v in touched {
            mark[v as usize] = true;
        }
        let marked = |v: &u32| mark.get(*v as usize).copied().unwrap_or(false);
        let near: Vec<[u32; 4]> = (tets.iter())
            .filter(|t| t.iter().any(marked))
            .copied()
            .collect();
        let local = super::faces::boundary(&near)
            .into_iter()
            .filter(|f| f.iter().any(marked));
        let kept = (self.tris.iter())
            .filter(|f| !f.iter().any(marked))
            .copied();
        Surface::from_tris(kept.chain(local).collect())
    }

    /// Whether membranes through the `touched` vertices may have closed a pocket into a cavity
    /// (its wall a new component of ∂K): ∂K has more components than `before`, or the membranes
    /// joined two components of it (which could hide a new one in the count).
    fn may_hide_a_void(&self, before: &mut Surface, touched: &[u32]) -> bool {
        if self.topology.components != before.topology.components {
            return true;
        }
        let mut on_surface = vec![false; before.n_vertices];
        for t in &before.tris {
            for &v in t {
                on_surface[v as usize] = true;
            }
        }
        let mut roots = (touched.iter())
            .filter(|&&v| on_surface.get(v as usize).copied().unwrap_or(false))
            .map(|&v| before.parts.find(v as usize))
            .collect::<Vec<_>>();
        roots.sort_unstable();
        roots.dedup();
        roots.len() > 1
    }

    /// The vertices outside the component with the most triangles.
    fn minor_vertices(&mut self) -> FxHashSet<u32> {
        let mut size: FxHashMap<usize, usize> = FxHashMap::default();
        for t in &self.tris {
            *size.entry(self.parts.find(t[0] as usize)).or_default() += 1;
        }
        let major = size
            .iter()
            .max_by_key(|(&r, &c)| (c, std::cmp::Reverse(r)))
            .map(|(&r, _)| r);
        let tris = std::mem::take(&mut self.tris);
        let minor = tris
            .iter()
            .flatten()
            .copied()
            .filter(|&v| Some(self.parts.find(v as usize)) != major)
            .collect();
        self.tris = tris;
        minor
    }
}

/// The survivors that thinning left, in groups joined through shared vertices.
fn membranes(s: &Thinning, n_kept: usize) -> Vec<Vec<usize>> {
    vertex_groups(s.tets, s.stars, |t| t >= n_kept && s.in_s[t])
}

/// The tetrahedra that pass `member`, in groups joined through shared vertices (`stars`: the
/// tetrahedra around each vertex), each in the order found, groups by their first member.
pub(super) fn vertex_groups(
    tets: &[[u32; 4]],
    stars: &Stars<u32>,
    member: impl Fn(usize) -> bool,
) -> Vec<Vec<usize>> {
    let mut group = vec![false; tets.len()];
    let mut out: Vec<Vec<usize>> = Vec::new();
    for t0 in 0..tets.len() {
        if !member(t0) || group[t0] {
            continue;
        }
        group[t0] = true;
        let mut members = vec![t0];
        let mut i = 0;
        while i < members.len() {
            let t = members[i];
            i += 1;
            for &v in &tets[t] {
                for &o in &stars[v as usize] {
                    let o = o as usize;
                    if member(o) && !group[o] {
                        group[o] = true;
                        members.push(o);
                    }
                }
            }
        }
        out.push(members);
    }
    out
}

/// χ(K ∪ m) − χ(K) for a membrane `m`: the simplices of `m` that K (the first `n_kept`) does
/// not have, with their signs.
fn euler_gain(s: &Thinning, n_kept: usize, m: &[usize]) -> i64 {
    let in_k = |need: &[u32]| {
        s.stars[need[0] as usize]
            .iter()
            .any(|&o| (o as usize) < n_kept && need.iter().all(|v| s.tets[o as usize].contains(v)))
    };
    let (v, e, f) = simplices(m.iter().map(|&t| &s.tets[t]));
    let new_v = v.iter().filter(|&&x| !in_k(&[x])).count() as i64;
    let new_e = e.iter().filter(|&&(a, b)| !in_k(&[a, b])).count() as i64;
    let new_f = f.iter().filter(|k| !in_k(&k[..])).count() as i64;
    new_v - new_e + new_f - m.len() as i64
}

/// The vertices, edges and faces (sorted keys) of some tetrahedra.
type Simplices = (FxHashSet<u32>, FxHashSet<(u32, u32)>, FxHashSet<[u32; 3]>);

fn simplices<'a>(tets: impl Iterator<Item = &'a [u32; 4]>) -> Simplices {
    let (mut v, mut e, mut f) = Simplices::default();
    for t in tets {
        v.extend(t);
        for (a, b) in TET_EDGES {
            e.insert(edge(t[a], t[b]));
        }
        for i in 0..4 {
            f.insert(key3(outward_face(t, i)));
        }
    }
    (v, e, f)
}

/// Per tetrahedron of S, its distance in face steps within S from K (the first `n_kept`); those
/// that no path reaches get the largest depth (they go first).
fn depths(s: &Thinning, n_kept: usize) -> Vec<u32> {
    face_steps(s.tets.len(), |t| t < n_kept, |t, i| s.across(t, i))
}

/// Per tetrahedron (of `n`), its distance in face steps (`across`: the neighbour across face `i`
/// of `t`, if any) from the `seed` ones; `u32::MAX` where no path reaches.
pub(super) fn face_steps(
    n: usize,
    seed: impl Fn(usize) -> bool,
    across: impl Fn(usize, usize) -> Option<usize>,
) -> Vec<u32> {
    let mut depth = vec![u32::MAX; n];
    let mut queue: VecDeque<usize> = (0..n).filter(|&t| seed(t)).collect();
    for &t in &queue {
        depth[t] = 0;
    }
    while let Some(t) = queue.pop_front() {
        for i in 0..4 {
            if let Some(o) = across(t, i) {
                if depth[o] == u32::MAX {
                    depth[o] = depth[t] + 1;
                    queue.push_back(o);
                }
            }
        }
    }
    depth
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::refine::test_support::{ring, Complex, Owned};

    /// Euler characteristic of the complex of `tets` (β0 − β1 + β2).
    fn euler(tets: &[[u32; 4]]) -> i64 {
        let (v, e, f) = simplices(tets.iter());
        v.len() as i64 - e.len() as i64 + f.len() as i64 - tets.len() as i64
    }

    /// A test triangulation owning `complex`: no planes, no sections.
    fn owned((positions, kept, fillable): Complex) -> Owned {
        Owned {
            kept,
            fillable,
            ..Owned::at(positions)
        }
    }

    #[test]
    fn thinning_leaves_a_membrane_across_a_ring() {
        let mut owned = owned(ring(8));
        assert_eq!(euler(&owned.kept), 0);
        let all: Vec<[u32; 4]> = owned.kept.iter().chain(&owned.fillable).copied().collect();
        assert_eq!(euler(&all), 1);
        let k = owned.view();
        let mut stats = TunnelStats::default();
        let n = k.positions.len();
        let membranes = thin(&k, &vec![false; n], &mut stats);
        assert_eq!((stats.candidates, stats.membranes), (24, 1));
        let m = &membranes[0];
        assert!(!m.is_empty() && m.len() < 24, "{m:?}");
        // K with the membrane: one component, no handle, no cavity
        let with: Vec<[u32; 4]> = k.kept.iter().chain(m).copied().collect();
        assert_eq!(euler(&with), 1);
    }

    #[test]
    fn a_tunnel_through_holes_keeps_no_membrane() {
        let mut owned = owned(ring(8));
        let k = owned.view();
        // the inner wall (3i, 3i + 2) and the axis lie on holes: the tube is witnessed
        let n = k.positions.len();
        let on_hole: Vec<bool> = (0..n).map(|v| v >= n - 2 || v % 3 != 1).collect();
        let mut stats = TunnelStats::default();
        assert!(thin(&k, &on_hole, &mut stats).is_empty());
        assert_eq!(stats.candidates, 0);
    }

    #[test]
    fn topology_of_a_ring() {
        let (_, kept, _) = ring(8);
        assert_eq!(
            Surface::of(&kept).topology,
            Topology {
                components: 1,
                genus: 1
            }
        );
    }

    #[test]
    fn a_local_change_updates_the_surface_as_a_full_pass_would() {
        // the ring cut through one prism (a handle fewer), then a second prism away (a second
        // component): read from the touched stars only, as from all of K
        let (_, kept, _) = ring(8);
        let mut now = Surface::of(&kept);
        let mut k = kept.clone();
        for station in [0u32, 4] {
            let prism: Vec<u32> = (3 * station..3 * station + 6).map(|v| v % 24).collect();
            let cut: Vec<[u32; 4]> = (k.iter())
                .filter(|t| t.iter().all(|v| prism.contains(v)))
                .copied()
                .collect();
            assert_eq!(cut.len(), 3, "a prism of three tetrahedra");
            k.retain(|t| !cut.contains(t));
            let mut touched: Vec<u32> = cut.iter().flatten().copied().collect();
            touched.sort_unstable();
            touched.dedup();
            let after = now.after(&k, &touched);
            let full = Surface::of(&k);
            assert_eq!(after.topology, full.topology);
            let (mut a, mut b) = (after.tris.clone(), full.tris.clone());
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b);
            now = after;
        }
        assert_eq!(
            now.topology,
            Topology {
                components: 2,
                genus: 0
            }
        );
    }

    #[test]
    fn survivors_beside_a_ball_all_go() {
        // two tets of K sharing a face; survivors glued to it that close no loop
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, -1.0, -1.0],
            [2.0, 0.0, 0.0],
        ];
        let kept = vec![[0, 1, 2, 3], [1, 2, 3, 4]];
        let fill = vec![[0, 1, 2, 5], [1, 2, 4, 6], [1, 3, 4, 6]];
        let mut owned = owned((positions, kept, fill));
        let mut k = owned.view();
        let settle = Settle {
            growth_rounds: 1,
            growth_distance: 1e-3,
            min_gap: 1e-7,
            near_coplanar: 1e-9,
        };
        let mut stats = TunnelStats::default();
        assert!(thin(&k, &[false; 7], &mut stats).is_empty());
        assert_eq!((stats.candidates, stats.membranes), (3, 0));
        // ∂K is a sphere: closing does not even thin, and K stays as it is
        let (stats, found) = close(&mut k, &[false; 7], settle);
        assert_eq!(
            (stats.candidates, stats.membranes, stats.tets_added),
            (0, 0, 0)
        );
        assert!(matches!(found, Some(Found::Manifold(s)) if s.topology.genus == 0));
        assert_eq!(k.kept.len(), 2);
        assert_eq!(k.fillable.len(), 3);
    }
}
