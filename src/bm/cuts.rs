//! Handles that no section witnesses, cut inside the complex (issue 19): the dual of `tunnels`.
//! A handle of K that no membrane of step-1 survivors can close is often a bridge: tetrahedra
//! joining two parts of the solid across a gap the sections leave open (a web between two
//! fingers, under a belly). It is cut where no section is, so every section stays exact.
//!
//! 1. *Growth.* K is seen through its dual complex (a tetrahedron a vertex, an inner face an edge,
//!    an inner edge of K the 2-cell of its ring, an inner vertex the 3-cell of its star; with ∂K
//!    a manifold, K retracts onto it). Start from K' = the *section layer*: the tetrahedra with a
//!    face in a section or an edge inside one (the fans around such an edge join the section's
//!    triangles: a cut there could not separate anything). Add the others one at a time, deepest
//!    in K first (face steps from ∂K), while an addition closes no loop: with f faces on K' whose
//!    tetrahedra lie in c components of K', and e rings of inner edges that it completes, H₁
//!    grows by f − c − e (Mayer–Vietoris on the dual cells). So K' gains no handle that its
//!    section layer does not have; a loop through a section stays.
//! 2. *Cuts.* What growth leaves of K are layers across K's other handles, where growth fronts
//!    met. Each layer (joined through shared vertices), smallest first, leaves K for `external`;
//!    its sides still touch at vertices and edges of the sections' contours (every vertex lies
//!    on a plane), so they are separated (`separate`): at each singular simplex the cones not
//!    standing on a section lose their tips. A cut stays when ∂K is then a manifold with no more
//!    components and at least one handle fewer (`tunnels::Batches`), else it is undone.
use super::complex::{outward_face, TET_EDGES};
use super::edges::EdgeTable;
use super::faces::{FaceTable, NO_NEIGHBOUR};
use super::refine::{edge, key3, Triangulation};
use super::tunnels::{
    face_steps, vertex_groups, Batches, Found, Move, Settle, Surface, TunnelStats, TESTS_BASE,
};
use crate::eval::topology::UnionFind;
use crate::fxhash::FxHashMap;
use crate::mesh::Stars;
use std::collections::BinaryHeap;

/// Cut K's unwitnessed handles (the module's steps); counted in a [`TunnelStats`] (membranes are
/// cuts, tunnels closed are handles cut). Nothing is tried when ∂K is not a manifold.
/// `found`: ∂K if known (as `tunnels::close` left K).
pub(super) fn cut(k: &mut Triangulation, settle: Settle, found: Option<Found>) -> TunnelStats {
    let mut stats = TunnelStats::default();
    let now = match found {
        Some(Found::Manifold(now)) => Some(now),
        Some(Found::Singular) => None,
        None => Surface::of_manifold(k.kept),
    };
    let Some(now) = now else {
        stats.skipped_singular = true;
        return stats;
    };
    if now.topology.genus == 0 {
        return stats;
    }
    let mut cuts = grow(k, &mut stats);
    if cuts.is_empty() {
        return stats;
    }
    stats.genus_before = now.topology.genus;
    let mut batches = Batches {
        how: Move::Cut,
        settle,
        now,
        budget: TESTS_BASE + cuts.len() / 8,
        stats: &mut stats,
    };
    // one at a time, smallest first: a batch of them rarely all cut, and each try costs a few
    // passes over K
    cuts.sort_by_key(|c| c.len());
    for c in &cuts {
        batches.take(k, std::slice::from_ref(c));
    }
    stats.genus_after = batches.now.topology.genus;
    stats
}

/// K' during growth, seen through its dual complex (a tetrahedron a vertex, an inner face an
/// edge, an inner edge of K the 2-cell of its ring, an inner vertex the 3-cell of its star; ∂K a
/// manifold makes it a deformation retract of K): which tetrahedra are in K', how many of each
/// inner edge's ring are, and K''s components (over tetrahedra, through faces).
struct Growing<'a> {
    tets: &'a [[u32; 4]],
    faces: &'a FaceTable,
    stars: &'a Stars<u32>,
    /// [`FaceTable::neighbours`] of `tets`.
    adj: Vec<[u32; 4]>,
    in_k: Vec<bool>,
    /// The numbers of `tets`' edges.
    edges: EdgeTable,
    /// Per inner edge of K (by number): its ring's tetrahedra, and how many of them are in K'
    /// ((0, 0) for the others).
    ring: Vec<(u32, u32)>,
    parts: UnionFind,
}

impl Growing<'_> {
    /// The tetrahedron across face `i` of `t` (in K), if any.
    fn across(&self, t: usize, i: usize) -> Option<usize> {
        (self.faces).across(self.tets, &self.adj, t, i, |_| true)
    }

    /// Whether adding `t` to K' closes no loop (the module's rule): with f faces on K', whose
    /// tetrahedra lie in c components of K', and e rings of inner edges that `t` completes,
    /// H₁ grows by f − c − e (each completed ring fills the loop it closes; an inner vertex's
    /// completed star fills the cavity its rings close). False when no face touches K'.
    fn addable(&mut self, t: usize) -> bool {
        let mut roots: smallvec::SmallVec<[usize; 4]> = smallvec::SmallVec::new();
        for i in 0..4 {
            if let Some(o) = self.across(t, i).filter(|&o| self.in_k[o]) {
                roots.push(self.parts.find(o));
            }
        }
        let f = roots.len() as i64;
        if f == 0 {
            return false;
        }
        roots.sort_unstable();
        roots.dedup();
        let e = (self.edges.of_tet[t].iter())
            .filter(|&&id| {
                let (total, inside) = self.ring[id as usize];
                total > 0 && inside + 1 == total
            })
            .count() as i64;
        f - roots.len() as i64 - e <= 0
    }

    /// Put `t` in K'; the tetrahedra whose rule may have changed go to `push`.
    fn add(&mut self, t: usize, mut push: impl FnMut(usize)) {
        self.in_k[t] = true;
        let tet = self.tets[t];
        for i in 0..4 {
            if let Some(o) = self.across(t, i) {
                if self.in_k[o] {
                    self.parts.union(t, o);
                }
                push(o);
            }
        }
        for (e, (a, b)) in TET_EDGES.into_iter().enumerate() {
            let key = edge(tet[a], tet[b]);
            let r = &mut self.ring[self.edges.of_tet[t][e] as usize];
            if r.0 > 0 {
                r.1 += 1;
                if r.1 + 1 == r.0 {
                    for &o in &self.stars[key.0 as usize] {
                        if self.tets[o as usize].contains(&key.1) {
                            push(o as usize);
                        }
                    }
                }
            }
        }
    }
}

/// Per edge number (`edges`): for an inner edge of a tetrahedron that is not `grounded` (on no
/// face of ∂K: `open` has a bit per face on it), how many tetrahedra hold it (and 0 in K' so
/// far); (0, 0) for the others.
fn inner_edges(edges: &EdgeTable, grounded: &[bool], open: &[u8]) -> Vec<(u32, u32)> {
    let mut tracked = vec![false; edges.count];
    let mut total = vec![0u32; edges.count];
    for (t, ids) in edges.of_tet.iter().enumerate() {
        for &e in ids {
            tracked[e as usize] |= !grounded[t];
            total[e as usize] += 1;
        }
    }
    for (t, ids) in edges.of_tet.iter().enumerate() {
        for i in (0..4).filter(|i| open[t] >> i & 1 == 1) {
            // the face opposite vertex i: the edges not through it
            for (e, &(a, b)) in TET_EDGES.iter().enumerate() {
                if a != i && b != i {
                    tracked[ids[e] as usize] = false;
                }
            }
        }
    }
    (0..edges.count)
        .map(|e| if tracked[e] { (total[e], 0) } else { (0, 0) })
        .collect()
}

/// Per tetrahedron of K (`tets`, with their `faces` and `edges`), whether it is in the section
/// layer: a face in a section, or an edge inside one (two of its triangles on it: the fans around
/// such an edge join the section's triangles, a cut through them cannot separate anything).
/// Read from the sections' triangles into K's tables, not from K's faces into a hash of them.
fn section_layer(
    k: &Triangulation,
    tets: &[[u32; 4]],
    faces: &FaceTable,
    edges: &EdgeTable,
) -> Vec<bool> {
    let mut grounded = vec![false; tets.len()];
    let mut on_section = vec![0u8; edges.count];
    for f in k.internal.iter() {
        for c in faces.codes(&key3(*f)) {
            grounded[(c >> 2) as usize] = true;
        }
        for i in 0..3 {
            if let Some(e) = edges.id(f[i], f[(i + 1) % 3]) {
                on_section[e as usize] = on_section[e as usize].saturating_add(1);
            }
        }
    }
    for (g, ids) in grounded.iter_mut().zip(&edges.of_tet) {
        *g |= ids.iter().any(|&e| on_section[e as usize] >= 2);
    }
    grounded
}

/// Step 1: the cuts (groups of K's tetrahedra joined through shared vertices) that growth from
/// the grounded core leaves out.
fn grow(k: &Triangulation, stats: &mut TunnelStats) -> Vec<Vec<[u32; 4]>> {
    let tets: &[[u32; 4]] = k.kept;
    // three tables of K, built side by side
    let n = k.positions.len();
    let (faces, (stars, edges)) = rayon::join(
        || FaceTable::new(tets),
        || rayon::join(|| Stars::<u32>::new(n, tets), || EdgeTable::new(tets)),
    );
    let adj = faces.neighbours(tets.len());
    let grounded = section_layer(k, tets, &faces, &edges);
    // per tetrahedron, a bit per face on ∂K
    let open: Vec<u8> = (adj.iter())
        .map(|a| (0..4).fold(0u8, |m, i| m | (u8::from(a[i] == NO_NEIGHBOUR) << i)))
        .collect();
    let mut g = Growing {
        tets,
        faces: &faces,
        stars: &stars,
        adj,
        in_k: vec![false; tets.len()],
        ring: inner_edges(&edges, &grounded, &open),
        edges,
        parts: UnionFind::new(tets.len()),
    };
    for t in (0..tets.len()).filter(|&t| grounded[t]) {
        g.add(t, |_| {});
    }
    stats.candidates = grounded.iter().filter(|&&b| !b).count() as u64;
    let depth = face_steps(tets.len(), |t| open[t] != 0, |t, i| g.across(t, i));
    let mut heap: BinaryHeap<(u32, usize)> = (0..tets.len())
        .filter(|&t| !grounded[t])
        .map(|t| (depth[t], t))
        .collect();
    while let Some((_, t)) = heap.pop() {
        if g.in_k[t] || !g.addable(t) {
            continue;
        }
        let mut pushed = Vec::new();
        g.add(t, |o| pushed.push(o));
        for o in pushed {
            if !g.in_k[o] {
                heap.push((depth[o], o));
            }
        }
    }
    // what growth left out, in groups joined through shared vertices
    let groups = vertex_groups(tets, &stars, |t| !g.in_k[t]);
    stats.membranes = groups.len() as u64;
    groups
        .into_iter()
        .map(|m| m.into_iter().map(|t| tets[t]).collect())
        .collect()
}

/// Most rounds of separating (each takes every independent singular simplex at once).
const SEPARATE_ROUNDS: usize = 6;

/// After a cut, ∂K is singular where its two sides still touch (at vertices and edges of the
/// sections' contours, which both sides hold). At each singular vertex and edge, every cone but
/// the one standing on a section there (else the largest) loses its tip: the edges from the
/// simplex into those cones are split `SIDE_FRACTION` along (`APEX_FRACTION` at an apex; moved
/// where that would crowd a neighbour, `split_point`) and the
/// children at the simplex leave K for `external`. Simplices whose cones share an edge with
/// another's wait for the next round, so one refinement serves a whole round. Returns the
/// singular simplices left and the vertices whose stars changed.
pub fn separate(
    k: &mut Triangulation,
    sets: super::assembly::Sets,
    min_gap: f64,
) -> (super::assembly::Sets, Vec<u32>) {
    let mut sets = sets;
    let mut all_touched = Vec::new();
    for _ in 0..SEPARATE_ROUNDS {
        let (edges, vertices) = &sets;
        if edges.is_empty() && vertices.is_empty() {
            break;
        }
        let cores: Vec<Vec<u32>> = vertices
            .iter()
            .map(|&v| vec![v])
            .chain(edges.iter().map(|&(a, b)| vec![a, b]))
            .collect();
        let plans = plan_round(k, &cores, min_gap);
        if plans.is_empty() {
            break;
        }
        let touched = apply_round(k, plans);
        // only the stars of the split tetrahedra's vertices changed
        sets = super::assembly::singular_sets_after(k.kept, sets, &touched);
        all_touched.extend(touched);
    }
    (sets, all_touched)
}

/// One simplex's carving: its core, the tetrahedra of the cones that lose their tips, and the
/// split point of every edge from the core into them.
struct Plan {
    core: Vec<u32>,
    carved: Vec<[u32; 4]>,
    points: Vec<((u32, u32), [f64; 3])>,
}

/// The carvings of a round: per core, its cones (from K's stars), the one kept, the others'
/// split points; a core whose tetrahedra share an edge with an earlier core's waits.
fn plan_round(k: &Triangulation, cores: &[Vec<u32>], min_gap: f64) -> Vec<Plan> {
    // the kept tetrahedra through a core's first vertex (one pass over K)
    let mut first: crate::fxhash::FxHashMap<u32, Vec<u32>> =
        cores.iter().flatten().map(|&v| (v, Vec::new())).collect();
    // a flag per vertex spares the map a lookup for every vertex of K
    let in_core = super::refine::marks(k.positions.len(), cores.iter().flatten().copied());
    for (i, t) in k.kept.iter().enumerate() {
        for v in t.iter().filter(|&&v| in_core[v as usize]) {
            if let Some(star) = first.get_mut(v) {
                star.push(i as u32);
            }
        }
    }
    let mut claimed: crate::fxhash::FxHashSet<(u32, u32)> = Default::default();
    let mut plans = Vec::new();
    for core in cores {
        let star: Vec<[u32; 4]> = first[&core[0]]
            .iter()
            .map(|&t| k.kept[t as usize])
            .filter(|t| core.iter().all(|v| t.contains(v)))
            .collect();
        let cones = super::carve::cones_of(&star, core);
        if cones.len() < 2 {
            continue;
        }
        let grounded: Vec<usize> = (0..cones.len())
            .filter(|&i| cones[i].iter().any(|t| stands_on_section(k, t, core)))
            .collect();
        // the cones that lose their tips, at which core, how far along their edges
        let (at, carved, far): (Vec<u32>, Vec<[u32; 4]>, bool) = match grounded.len() {
            0 | 1 => {
                let keep = grounded.first().copied().unwrap_or(0);
                let carved = (cones.into_iter().enumerate())
                    .filter(|&(i, _)| i != keep)
                    .flat_map(|(_, c)| c)
                    .collect();
                (core.clone(), carved, false)
            }
            _ => match apex_cut(k, core, &cones, &grounded) {
                Some((apex, i)) => (vec![apex], cones[i].clone(), true),
                None => {
                    continue;
                }
            },
        };
        let tet_edges = || {
            carved
                .iter()
                .flat_map(|t| TET_EDGES.iter().map(move |&(a, b)| edge(t[a], t[b])))
        };
        if tet_edges().any(|e| claimed.contains(&e)) {
            continue;
        }
        claimed.extend(tet_edges());
        let mut points = Vec::new();
        for tet in &carved {
            for &v in &at {
                let pv = k.positions[v as usize];
                for &w in tet.iter().filter(|w| !at.contains(w)) {
                    let d = crate::sections::sub(k.positions[w as usize], pv);
                    // the point's neighbours: the tetrahedra around its edge, the points placed
                    let near: Vec<[f64; 3]> = (first[&v].iter())
                        .map(|&t| k.kept[t as usize])
                        .filter(|t| t.contains(&w))
                        .flatten()
                        .map(|x| k.positions[x as usize])
                        .chain(points.iter().map(|&(_, q)| q))
                        .collect();
                    let p = split_point(pv, d, far, &near, min_gap);
                    points.push((edge(v, w), p));
                }
            }
        }
        points.sort_unstable_by_key(|p| p.0);
        points.dedup_by_key(|p| p.0);
        plans.push(Plan {
            core: at,
            carved,
            points,
        });
    }
    plans
}

/// How far along its edges a cone is carved at its apex (more than half: the two cones of an
/// edge between two planes then keep disjoint parts of it).
const APEX_FRACTION: f64 = 0.6;

/// How far along its edges a cone is carved at the simplex its sides share: a fraction of each
/// edge, not a distance (fans of slivers have nearly parallel edges, whose points at one
/// distance would crowd).
const SIDE_FRACTION: f64 = 0.4;

/// At a singular edge between two planes whose two cones each stand on a section through one
/// end only (slivers standing on the two planes, the sides of a cut between them): the smaller
/// cone and its apex, the other end; its tip there (beyond the edge's middle) goes, and the next
/// round separates what is left.
fn apex_cut(
    k: &Triangulation,
    core: &[u32],
    cones: &[Vec<[u32; 4]>],
    grounded: &[usize],
) -> Option<(u32, usize)> {
    let &[a, b] = core else { return None };
    if grounded.len() != 2 {
        return None;
    }
    // per grounded cone, the core ends its section faces hold
    let ends = |i: usize| {
        let (mut on_a, mut on_b) = (false, false);
        for t in &cones[i] {
            for j in 0..4 {
                let f = key3(outward_face(t, j));
                if k.internal.contains(&f) {
                    on_a |= f.contains(&a);
                    on_b |= f.contains(&b);
                }
            }
        }
        (on_a, on_b)
    };
    let (x, y) = (grounded[0], grounded[1]);
    match (ends(x), ends(y)) {
        ((true, false), (false, true)) | ((false, true), (true, false)) => {
            let i = if cones[x].len() <= cones[y].len() {
                x
            } else {
                y
            };
            let apex = if ends(i).0 { b } else { a };
            Some((apex, i))
        }
        _ => None,
    }
}

/// The point `APEX_FRACTION` (at an apex) or `SIDE_FRACTION` along `d` from `pv`, moved along
/// the edge by tenths (an apex's point staying beyond the middle, a side's up to it) to the first
/// place at least 1.5 `min_gap` from every point of `near` (the vertices of the tetrahedra around
/// the edge and the points already placed): slivers' edges are nearly parallel, and a point
/// closer than `min_gap` to a vertex of its tetrahedra fails the cut (`tunnels::crowded_points`).
fn split_point(pv: [f64; 3], d: [f64; 3], far: bool, near: &[[f64; 3]], min_gap: f64) -> [f64; 3] {
    let s0 = if far { APEX_FRACTION } else { SIDE_FRACTION };
    let at = |s: f64| [0, 1, 2].map(|i| pv[i] + s * d[i]);
    let gap = 1.5 * min_gap;
    let clear = |s: f64| {
        let p = at(s);
        (near.iter()).all(|&q| {
            let e = crate::sections::sub(p, q);
            crate::sections::dot(e, e) >= gap * gap
        })
    };
    let fits = |s: f64| s > 0.05 && s < 0.95 && if far { s > 0.5 } else { s <= 0.5 };
    [0.0, 0.1, -0.1, 0.2, -0.2, 0.3, -0.3]
        .iter()
        .map(|ds| s0 + ds)
        .filter(|&s| fits(s))
        .find(|&s| clear(s))
        .map_or(at(s0), at)
}

/// Whether `t` has a face through `core` in a section.
fn stands_on_section(k: &Triangulation, t: &[u32; 4], core: &[u32]) -> bool {
    (0..4).any(|j| {
        let f = key3(outward_face(t, j));
        f.iter().any(|v| core.contains(v)) && k.internal.contains(&f)
    })
}

/// Split at every plan's points (one refinement) and take each plan's tips out of K, where the
/// split was made and every face of a tip on a plane keeps a kept tetrahedron on its other side.
/// The vertices whose stars changed.
fn apply_round(k: &mut Triangulation, plans: Vec<Plan>) -> Vec<u32> {
    let all: FxHashMap<(u32, u32), [f64; 3]> = plans
        .iter()
        .flat_map(|p| p.points.iter().copied())
        .collect();
    let first_new = k.positions.len();
    let touched = super::refine::grow(k, &[], all).touched;
    let id_of: FxHashMap<[u64; 3], u32> = k.positions[first_new..]
        .iter()
        .enumerate()
        .map(|(i, p)| (p.map(f64::to_bits), (first_new + i) as u32))
        .collect();
    let mut tips: Vec<[u32; 4]> = Vec::new();
    for plan in &plans {
        let ids: Option<FxHashMap<(u32, u32), u32>> = (plan.points.iter())
            .map(|(e, p)| id_of.get(&p.map(f64::to_bits)).map(|&id| (*e, id)))
            .collect();
        let Some(ids) = ids else { continue }; // a split refused (it would flip a neighbour)
        let mine: crate::fxhash::FxHashSet<u32> = ids.values().copied().collect();
        tips.extend(
            (plan.carved.iter())
                .flat_map(|&tet| super::refine::split(tet, &ids))
                .filter(|c| c.iter().all(|v| plan.core.contains(v) || mine.contains(v))),
        );
    }
    take_tips(k, &tips);
    touched
}

/// Move `tips` from K to `external` when each tip face on a plane keeps a kept tetrahedron
/// that is not a tip on its other side (a section stays covered); else nothing moves. Tips are
/// children of kept tetrahedra split this round: all in K.
fn take_tips(k: &mut Triangulation, tips: &[[u32; 4]]) {
    use super::refine::key4;
    let tip_keys: crate::fxhash::FxHashSet<[u32; 4]> = tips.iter().map(|&x| key4(x)).collect();
    if tips.is_empty() || !super::carve::sections_stay_covered(k, tips, &tip_keys, |_| true) {
        return;
    }
    let is_tip = super::refine::one_of(k.positions.len(), &tip_keys);
    k.kept.retain(|x| !is_tip(x));
    k.external.extend(tips.iter().copied());
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::refine::test_support::{ring, Owned};

    /// The ring of `ring(n)` (a solid torus of prisms, no survivors) with the floor (z = 0) of
    /// the prisms `stations` in a section.
    fn ring_with_floor(n: u32, stations: impl Iterator<Item = u32>) -> Owned {
        let (positions, kept, _) = ring(n);
        let mut owned = Owned {
            kept,
            ..Owned::at(positions)
        };
        for i in stations {
            let (j, base) = ((i + 1) % n, 3 * i);
            let [a, b, d, e] = [base, base + 1, 3 * j, 3 * j + 1];
            owned.internal.insert(key3([a, b, d]));
            owned.internal.insert(key3([b, d, e]));
        }
        owned
    }

    fn settle() -> Settle {
        Settle {
            growth_rounds: 1,
            growth_distance: 1e-3,
            min_gap: 1e-7,
            near_coplanar: 1e-9,
        }
    }

    #[test]
    fn a_ring_whose_section_is_one_floor_is_cut_elsewhere() {
        let mut owned = ring_with_floor(8, 0..1);
        let floor = owned.internal.clone();
        let mut k = owned.view();
        let before = Surface::of(k.kept).topology;
        assert_eq!((before.components, before.genus), (1, 1));
        let stats = cut(&mut k, settle(), None);
        assert_eq!((stats.membranes, stats.tunnels_closed), (1, 1), "{stats:?}");
        let after = Surface::of(k.kept).topology;
        assert_eq!((after.components, after.genus), (1, 0));
        let (edges, vertices) = super::super::assembly::singular_sets(k.kept);
        assert!(edges.is_empty() && vertices.is_empty());
        // the section keeps its tetrahedra
        for f in floor {
            assert!(k
                .kept
                .iter()
                .any(|t| (0..4).any(|i| key3(outward_face(t, i)) == f)));
        }
    }

    #[test]
    fn the_cone_off_the_section_loses_its_tip_at_a_shared_edge() {
        use crate::bm::refine::test_support::positive;
        // two tetrahedra sharing only the edge (0, 1); the first stands on a section there
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, 0.5, 1.0],
            [0.5, -1.0, 0.0],
            [0.5, -0.5, -1.0],
        ];
        let on_section = positive(&positions, [0, 1, 2, 3]);
        let off = positive(&positions, [0, 1, 4, 5]);
        let mut owned = Owned {
            kept: vec![on_section, off],
            ..Owned::at(positions)
        };
        owned.internal.insert([0, 1, 2]);
        let mut k = owned.view();
        let sets = super::super::assembly::singular_sets(k.kept);
        assert_eq!(sets.0, vec![(0, 1)]);
        let (left, _) = separate(&mut k, sets, 1e-7);
        assert!(left.0.is_empty() && left.1.is_empty(), "{left:?}");
        assert_eq!(left, super::super::assembly::singular_sets(k.kept));
        // the first is whole, the second lost the part near the edge
        assert!(k.kept.contains(&on_section));
        assert!(!k
            .kept
            .iter()
            .any(|t| t != &on_section && t.contains(&0) && t.contains(&1)));
        assert!(k.kept.iter().any(|t| t.contains(&4) && t.contains(&5)));
    }

    #[test]
    fn a_split_point_moves_off_a_crowding_neighbour() {
        let (pv, d) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        // nothing near: the side fraction; a vertex beside it: the next tenth that is clear
        assert_eq!(split_point(pv, d, false, &[], 0.01), [0.4, 0.0, 0.0]);
        let near = [[0.4, 0.001, 0.0]];
        let p = split_point(pv, d, false, &near, 0.01);
        assert!((p[0] - 0.5).abs() < 1e-12, "{p:?}");
        // an apex's point stays beyond the middle
        let near = [[0.6, 0.0, 0.001], [0.7, 0.0, 0.0]];
        let p = split_point(pv, d, true, &near, 0.01);
        assert!(p[0] > 0.5 && (p[0] - 0.8).abs() < 1e-12, "{p:?}");
    }

    #[test]
    fn a_loop_through_a_section_is_not_cut() {
        // the floor of every prism is in a section: the ring's loop lies in the section layer
        let mut owned = ring_with_floor(8, 0..8);
        let mut k = owned.view();
        let n = k.kept.len();
        let stats = cut(&mut k, settle(), None);
        assert_eq!((stats.membranes, stats.tunnels_closed), (0, 0), "{stats:?}");
        assert_eq!(k.kept.len(), n);
        assert_eq!(Surface::of(k.kept).topology.genus, 1);
    }
}
