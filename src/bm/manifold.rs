//! Singular edges and pinched vertices of ∂K removed by toggling whole tetrahedra of the
//! triangulation, each toggle only when it strictly lowers the number of singular simplices
//! (manifold-preserving region growing, as in surface reconstruction from a Delaunay labelling).
//!
//! Toggling a tetrahedron T changes ∂K only at T's four faces, so only the vertices and edges of T
//! can change status: the count over them is the change of the global count, which every accepted
//! toggle lowers, so the search ends, and it never makes ∂K worse. A toggle must keep every
//! section R ∩ P = A: adding T is allowed when each face of T on a plane is inside its section
//! (a section triangle), removing T when each face of T on a plane has a kept tetrahedron on its
//! other side (the face stays in R). Tetrahedra lie between the planes, so nothing else of a
//! section changes. Combinatorial throughout (plane tags, section triangles); no point is added
//! or moved. What the search cannot lower (a local minimum) is left to growth (`singular`).
//!
//! The folds of ∂K at flat tetrahedra are closed with the same toggles in `folds`
//! ([`close_flat_folds`]).
use super::faces::FaceTable;
use super::refine::{key3, on_a_plane, Planes, Triangulation};
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::mesh::Stars;
use smallvec::SmallVec;

mod folds;
pub use folds::close_flat_folds;

/// What the search did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToggleStats {
    pub added: u64,
    pub removed: u64,
}

impl ToggleStats {
    /// The toggles of a later pass added in.
    pub fn add(&mut self, later: &ToggleStats) {
        self.added += later.added;
        self.removed += later.removed;
    }
}

/// The whole triangulation with a kept flag per tetrahedron, its faces and vertex stars.
struct Labelled<'a> {
    tets: Vec<[u32; 4]>,
    kept: Vec<bool>,
    /// Per tetrahedron: 0 kept at the start, 1 fillable, 2 external (where it goes back to).
    origin: Vec<u8>,
    faces: FaceTable,
    /// Per tetrahedron and local face: the other tetrahedron on it, `NONE` or `MANY` (see `twins`).
    twin: Vec<[u32; 4]>,
    star: Stars,
    planes: &'a [Planes],
    internal: &'a FxHashSet<[u32; 3]>,
    nonconforming: &'a FxHashSet<u32>,
    /// The vertices of every tetrahedron toggled for good (repeats allowed).
    touched: Vec<u32>,
    /// Every tetrahedron toggled for good, in order (toggling them again restores `kept`).
    log: Vec<u32>,
}

/// Toggle tetrahedra around the singular simplices of ∂K while that lowers their number, at most
/// `max_toggles` times; never at the vertices of faces that two cells triangulate differently
/// (`nonconforming`). Also returns the singular simplices left. `known`: the singular simplices
/// of ∂K now, if known.
pub fn resolve(
    k: &mut Triangulation,
    nonconforming: &FxHashSet<u32>,
    max_toggles: usize,
    known: Option<super::assembly::Sets>,
) -> (ToggleStats, super::assembly::Sets) {
    if let Some(none @ (edges, vertices)) = &known {
        if edges.is_empty() && vertices.is_empty() {
            return (ToggleStats::default(), none.clone());
        }
    }
    let lists: [&[[u32; 4]]; 3] = [k.kept, k.fillable, k.external];
    let mut l = Labelled::new(lists, k.planes, k.internal, nonconforming);
    let mut stats = ToggleStats::default();
    let start = known.unwrap_or_else(|| super::fill::singular_simplices(&l.boundary()));
    let mut work: Vec<u32> = start.1.clone();
    work.extend(start.0.iter().flat_map(|&(a, b)| [a, b]));
    l.toggle_rounds(work, SET_PASSES, max_toggles, &mut stats);
    let mut touched = std::mem::take(&mut l.touched);
    touched.sort_unstable();
    touched.dedup();
    let (kept, fillable, external) = l.into_lists();
    (*k.kept, *k.fillable, *k.external) = (kept, fillable, external);
    let left = super::assembly::singular_sets_after(k.kept, start, &touched);
    debug_assert_eq!(left, super::assembly::singular_sets(k.kept));
    (stats, left)
}

/// Twin markers: no other tetrahedron on the face, or more than one.
const NONE: u32 = u32::MAX;
const MANY: u32 = u32::MAX - 1;

/// Per tetrahedron and local face, the one other tetrahedron on that face (`NONE`, `MANY`).
fn twins(faces: &FaceTable, n: usize) -> Vec<[u32; 4]> {
    let mut twin = vec![[NONE; 4]; n];
    faces.for_each_face(|codes| {
        for &c in codes {
            twin[(c >> 2) as usize][(c & 3) as usize] = match codes {
                [a, b] => (if *a == c { b } else { a }) >> 2,
                [_] => NONE,
                _ => MANY,
            };
        }
    });
    twin
}

/// Rounds of set moves (each followed by single toggles again).
const SET_PASSES: usize = 4;

impl<'a> Labelled<'a> {
    /// From the kept, fillable and external tetrahedra.
    fn new(
        lists: [&[[u32; 4]]; 3],
        planes: &'a [Planes],
        internal: &'a FxHashSet<[u32; 3]>,
        nonconforming: &'a FxHashSet<u32>,
    ) -> Labelled<'a> {
        let tets: Vec<[u32; 4]> = lists.concat();
        let n = tets.iter().flatten().max().map_or(0, |&v| v as usize + 1);
        let (mut kept, mut origin) = (Vec::new(), Vec::new());
        for (list, o) in lists.into_iter().zip(0u8..) {
            kept.resize(kept.len() + list.len(), o == 0);
            origin.resize(origin.len() + list.len(), o);
        }
        let faces = FaceTable::new(&tets);
        Labelled {
            twin: twins(&faces, tets.len()),
            faces,
            star: Stars::new(n, &tets),
            tets,
            kept,
            origin,
            planes,
            internal,
            nonconforming,
            touched: Vec::new(),
            log: Vec::new(),
        }
    }

    /// (kept, fillable, external), each unkept tetrahedron back in the list it came from.
    #[allow(clippy::type_complexity)]
    fn into_lists(self) -> (Vec<[u32; 4]>, Vec<[u32; 4]>, Vec<[u32; 4]>) {
        let (mut kept, mut fillable, mut external) = (Vec::new(), Vec::new(), Vec::new());
        for ((t, k), origin) in self.tets.into_iter().zip(self.kept).zip(self.origin) {
            match (k, origin) {
                (true, _) => kept.push(t),
                (false, 2) => external.push(t),
                (false, _) => fillable.push(t),
            }
        }
        (kept, fillable, external)
    }

    /// Up to `passes` rounds of single toggles from `work` (at most `max_toggles` in all), each
    /// followed, at every pinched vertex left, by the way out of a local minimum of single
    /// toggles: a strip of gap tetrahedra joining two fans, or the smallest fan's tetrahedra
    /// removed; the next round starts at the vertices so changed, until there are none.
    fn toggle_rounds(
        &mut self,
        mut work: Vec<u32>,
        passes: usize,
        max_toggles: usize,
        stats: &mut ToggleStats,
    ) {
        for _ in 0..passes {
            let left = self.toggle_singles(work, max_toggles, stats);
            work = Vec::new();
            for v in left {
                if self.fans_at(v) > 1 && self.join_or_carve(v, stats) {
                    work.push(v);
                }
            }
            if work.is_empty() {
                break;
            }
        }
    }

    /// Single toggles around the vertices of `work` (and those they touch) while they lower the
    /// count; returns the vertices looked at that are still singular.
    fn toggle_singles(
        &mut self,
        mut work: Vec<u32>,
        max_toggles: usize,
        stats: &mut ToggleStats,
    ) -> Vec<u32> {
        let mut queued: FxHashSet<u32> = work.iter().copied().collect();
        let mut seen: FxHashSet<u32> = queued.clone();
        while let Some(v) = work.pop() {
            queued.remove(&v);
            if (stats.added + stats.removed) as usize >= max_toggles {
                break;
            }
            if let Some(t) = self.toggle_one_at(v, stats) {
                for w in self.tets[t as usize] {
                    seen.insert(w);
                    if queued.insert(w) {
                        work.push(w);
                    }
                }
            }
        }
        let mut left: Vec<u32> = seen
            .into_iter()
            .filter(|&v| self.vertex_bad(v) > 0)
            .collect();
        left.sort_unstable();
        left
    }

    /// The first toggle of a tetrahedron on either side of the surface at `v` (toggling any other
    /// one of its star leaves the surface at v as it is) that lowers the count; additions first
    /// (they grow towards the sections' solid rather than carve it).
    fn toggle_one_at(&mut self, v: u32, stats: &mut ToggleStats) -> Option<u32> {
        let mut order: Vec<u32> = self
            .surface_at(v)
            .iter()
            .flat_map(|f| self.faces.owners(f))
            .collect();
        order.sort_unstable_by_key(|&t| (self.kept[t as usize], t));
        order.dedup();
        order.into_iter().find(|&t| self.try_set(&[t], stats))
    }

    /// Toggle every tetrahedron of `set` (each allowed in turn) and keep the change if it lowers
    /// the count over their vertices and edges; else undo it.
    fn try_set(&mut self, set: &[u32], stats: &mut ToggleStats) -> bool {
        let before: u32 = self.badness(set);
        if before == 0 {
            return false;
        }
        if !self.toggle_allowed(set) {
            return false;
        }
        if self.badness(set) < before {
            for &t in set {
                self.touched.extend(self.tets[t as usize]);
                self.log.push(t);
                if self.kept[t as usize] {
                    stats.added += 1;
                } else {
                    stats.removed += 1;
                }
            }
            return true;
        }
        self.flip(set);
        false
    }

    /// Toggle the tetrahedra of `set` in turn, each only if allowed (`may_toggle`) after those
    /// before it (two kept tetrahedra on both sides of a section triangle may not both go), and
    /// return true; else undo them and return false.
    fn toggle_allowed(&mut self, set: &[u32]) -> bool {
        for (done, &t) in set.iter().enumerate() {
            if !self.may_toggle(t) {
                self.flip(&set[..done]);
                return false;
            }
            self.kept[t as usize] ^= true;
        }
        true
    }

    /// Toggle every tetrahedron of `set` (its own inverse).
    fn flip(&mut self, set: &[u32]) {
        for &t in set {
            self.kept[t as usize] ^= true;
        }
    }

    /// Tetrahedra sharing a face with `t`.
    fn face_neighbours(&self, t: u32) -> SmallVec<[u32; 4]> {
        let tet = self.tets[t as usize];
        (0..4)
            .flat_map(|i| {
                let f = key3(super::complex::outward_face(&tet, i));
                self.faces.owners(&f).filter(move |&o| o != t)
            })
            .collect()
    }

    /// At a pinched vertex: join two fans by the shortest strip of gap tetrahedra around `v`, or
    /// carve the smallest fan's kept tetrahedra at `v`, whichever lowers the count first.
    fn join_or_carve(&mut self, v: u32, stats: &mut ToggleStats) -> bool {
        let star: Vec<u32> = self.star_of(v).to_vec();
        let kept: Vec<u32> = star
            .iter()
            .copied()
            .filter(|&t| self.kept[t as usize])
            .collect();
        let comps = self.components_at(v, &kept);
        if comps.len() >= 2 {
            if let Some(strip) = self.strip_between(v, &star, &comps) {
                if self.try_set(&strip, stats) {
                    return true;
                }
            }
        }
        let mut by_size = comps;
        by_size.sort_by_key(|c| c.len());
        by_size.pop();
        by_size.into_iter().any(|c| self.try_set(&c, stats))
    }

    /// Components of `tets` (around `v`) through shared faces containing `v`.
    fn components_at(&self, v: u32, tets: &[u32]) -> Vec<Vec<u32>> {
        let set: FxHashSet<u32> = tets.iter().copied().collect();
        let mut comp: FxHashMap<u32, usize> = FxHashMap::default();
        let mut out: Vec<Vec<u32>> = Vec::new();
        for &t0 in tets {
            if comp.contains_key(&t0) {
                continue;
            }
            let id = out.len();
            out.push(vec![t0]);
            comp.insert(t0, id);
            let mut stack = vec![t0];
            while let Some(t) = stack.pop() {
                for n in self.neighbours_at(v, t) {
                    if set.contains(&n) && !comp.contains_key(&n) {
                        comp.insert(n, id);
                        out[id].push(n);
                        stack.push(n);
                    }
                }
            }
        }
        out
    }

    /// Tetrahedra sharing with `t` a face through `v`.
    fn neighbours_at(&self, v: u32, t: u32) -> SmallVec<[u32; 3]> {
        let tet = self.tets[t as usize];
        (0..4)
            .filter(|&i| tet[i] != v)
            .flat_map(|i| {
                let f = key3(super::complex::outward_face(&tet, i));
                self.faces.owners(&f).filter(move |&o| o != t)
            })
            .collect()
    }

    /// The shortest chain of unkept tetrahedra around `v`, each allowed to be added, from one
    /// kept component to another.
    fn strip_between(&self, v: u32, star: &[u32], comps: &[Vec<u32>]) -> Option<Vec<u32>> {
        let in_first: FxHashSet<u32> = comps[0].iter().copied().collect();
        let in_other: FxHashSet<u32> = comps[1..].iter().flatten().copied().collect();
        let usable: FxHashSet<u32> = star
            .iter()
            .copied()
            .filter(|&t| !self.kept[t as usize] && self.may_toggle(t))
            .collect();
        let mut from: FxHashMap<u32, u32> = FxHashMap::default();
        let mut queue = std::collections::VecDeque::new();
        for &t in &usable {
            if self
                .neighbours_at(v, t)
                .iter()
                .any(|n| in_first.contains(n))
            {
                from.insert(t, t);
                queue.push_back(t);
            }
        }
        while let Some(t) = queue.pop_front() {
            if self
                .neighbours_at(v, t)
                .iter()
                .any(|n| in_other.contains(n))
            {
                let mut chain = vec![t];
                let mut j = t;
                while from[&j] != j {
                    j = from[&j];
                    chain.push(j);
                }
                return Some(chain);
            }
            for n in self.neighbours_at(v, t) {
                if usable.contains(&n) && !from.contains_key(&n) {
                    from.insert(n, t);
                    queue.push_back(n);
                }
            }
        }
        None
    }

    fn fans_at(&self, v: u32) -> usize {
        super::fill::fans(&self.surface_at(v), v)
    }

    /// Whether another tetrahedron than `t` on face `f` is kept.
    fn other_kept(&self, f: &[u32; 3], t: u32) -> bool {
        self.faces
            .owners(f)
            .any(|o| o != t && self.kept[o as usize])
    }

    /// `other_kept` of the face of `t` opposite its local vertex `i`.
    fn other_kept_at(&self, t: u32, i: usize) -> bool {
        match self.twin[t as usize][i] {
            NONE => false,
            MANY => {
                let f = key3(super::complex::outward_face(&self.tets[t as usize], i));
                self.other_kept(&f, t)
            }
            o => self.kept[o as usize],
        }
    }

    /// Toggling `t` keeps every section (see the module docs). Where the two cells of a face
    /// triangulate it differently (a vertex of such a face, or a face with more than two
    /// tetrahedra), the tetrahedra overlap and nothing is toggled.
    fn may_toggle(&self, t: u32) -> bool {
        let tet = self.tets[t as usize];
        if tet.iter().any(|v| self.nonconforming.contains(v)) {
            return false;
        }
        let adding = !self.kept[t as usize];
        (0..4).all(|i| {
            let f = key3(super::complex::outward_face(&tet, i));
            let owners = self.faces.owners(&f).len();
            if owners > 2 {
                return false;
            }
            if !on_a_plane(self.planes, &f) {
                return true;
            }
            if adding {
                self.internal.contains(&f)
            } else {
                self.other_kept_at(t, i)
            }
        })
    }

    /// The surface triangles of ∂K through vertex `v` (sorted keys).
    fn surface_at(&self, v: u32) -> SmallVec<[[u32; 3]; 16]> {
        let mut out = SmallVec::new();
        for &t in self.star_of(v) {
            if !self.kept[t as usize] {
                continue;
            }
            let tet = self.tets[t as usize];
            for i in 0..4 {
                if tet[i] == v {
                    continue;
                }
                if !self.other_kept_at(t, i) {
                    out.push(key3(super::complex::outward_face(&tet, i)));
                }
            }
        }
        out
    }

    /// The surface triangles (`assembly::boundary_of` of the kept tetrahedra, in another order).
    fn boundary(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        self.faces.for_each_face(|codes| {
            let mut kept = codes.iter().filter(|&&c| self.kept[(c >> 2) as usize]);
            if let (Some(&c), None) = (kept.next(), kept.next()) {
                let t = &self.tets[(c >> 2) as usize];
                out.push(super::complex::outward_face(t, (c & 3) as usize));
            }
        });
        out
    }

    /// The tetrahedra with vertex `v`.
    fn star_of(&self, v: u32) -> &[u32] {
        if (v as usize) < self.star.len() {
            &self.star[v as usize]
        } else {
            &[]
        }
    }

    /// 1 if `v` is pinched, plus its edges with more than two surface triangles.
    fn vertex_bad(&self, v: u32) -> u32 {
        self.vertex_and_edges_bad(v, None)
    }

    /// Whether `v` is pinched, plus those of its edges to `towards` (all if `None`) that have more
    /// than two surface triangles.
    fn vertex_and_edges_bad(&self, v: u32, towards: Option<&FxHashSet<u32>>) -> u32 {
        let tris = self.surface_at(v);
        let mut bad = u32::from(super::fill::fans(&tris, v) > 1);
        let mut ends: SmallVec<[u32; 32]> =
            tris.iter().flatten().copied().filter(|&w| w != v).collect();
        ends.sort_unstable();
        // each edge once: from its smaller end
        bad += ends
            .chunk_by(|a, b| a == b)
            .filter(|run| {
                run.len() > 2 && run[0] > v && towards.is_none_or(|s| s.contains(&run[0]))
            })
            .count() as u32;
        bad
    }

    /// Singular simplices among the vertices and edges of the tetrahedra of `set`.
    fn badness(&self, set: &[u32]) -> u32 {
        let verts: FxHashSet<u32> = set.iter().flat_map(|&t| self.tets[t as usize]).collect();
        verts
            .iter()
            .map(|&v| self.vertex_and_edges_bad(v, Some(&verts)))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::refine::test_support::Owned;
    use smallvec::smallvec;

    /// Octahedron around vertex 0 at the origin split into eight tets, one per octant; vertices
    /// 1..=6 are ±x, ±y, ±z.
    fn octants() -> Vec<[u32; 4]> {
        let (px, nx, py, ny, pz, nz) = (1, 2, 3, 4, 5, 6);
        let mut out = Vec::new();
        for x in [px, nx] {
            for y in [py, ny] {
                for z in [pz, nz] {
                    out.push([0, x, y, z]);
                }
            }
        }
        out
    }

    fn run(kept: &[usize], planes: Vec<Planes>, internal: &[[u32; 3]]) -> (ToggleStats, usize) {
        let all = octants();
        let mut o = Owned {
            positions: vec![[0.0; 3]; 7],
            planes,
            kept: kept.iter().map(|&i| all[i]).collect(),
            fillable: (0..8)
                .filter(|i| !kept.contains(i))
                .map(|i| all[i])
                .collect(),
            internal: internal.iter().map(|&f| key3(f)).collect(),
            ..Default::default()
        };
        let (s, _) = resolve(&mut o.view(), &FxHashSet::default(), 100, None);
        let b = super::super::assembly::boundary_of(&o.kept);
        let (e, v) = super::super::fill::singular_simplices(&b);
        (s, e.len() + v.len())
    }

    use crate::bm::refine::test_support::positive as oriented;

    /// The points a b c d top bottom of [`crack`].
    pub(super) fn crack_points(height: f64) -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.3, 0.3, height],
            [0.4, 0.2, 1.0],
            [0.3, 0.3, -1.0],
        ]
    }

    /// A triangle a b c with d `height` above a point inside it: the tetrahedron a b c d, unkept,
    /// between two kept ones, a b d p above and a b c q below. Flat (1e-13), its faces a b d and
    /// a b c are on ∂K and lie on each other (a crack; edge a b is singular too), and adding it
    /// closes the crack: returns the toggles and the singular edges left.
    fn crack(height: f64) -> (ToggleStats, u64) {
        let p = crack_points(height);
        let (a, b, c, d, top, bottom) = (0, 1, 2, 3, 4, 5);
        let mut o = Owned {
            kept: [[a, b, d, top], [a, b, c, bottom]]
                .map(|t| oriented(&p, t))
                .to_vec(),
            external: vec![oriented(&p, [a, b, c, d])],
            ..Owned::at(p)
        };
        let s = close_flat_folds(&mut o.view(), &FxHashSet::default(), 1e-8);
        let boundary = super::super::assembly::boundary_of(&o.kept);
        (s, super::super::assembly::singularities(&boundary).0)
    }

    #[test]
    fn a_flat_crack_is_closed_and_a_real_gap_kept() {
        assert_eq!(
            crack(1e-13),
            (
                ToggleStats {
                    added: 1,
                    removed: 0
                },
                0
            )
        );
        // 0.1 thick: a gap the fold search leaves alone (the singular edge is the toggles' job)
        assert_eq!(crack(0.1), (ToggleStats::default(), 1));
    }

    #[test]
    fn two_kept_tetrahedra_on_both_sides_of_a_section_triangle_may_not_both_go() {
        // triangle 0 1 2 on plane 9 (a section triangle), apex 3 above it and 4 below, both kept
        let planes: Vec<Planes> = (0..5)
            .map(|v| if v < 3 { smallvec![9] } else { smallvec![] })
            .collect();
        let internal: FxHashSet<[u32; 3]> = [[0, 1, 2]].into_iter().collect();
        let kept = [[0, 1, 2, 3], [0, 2, 1, 4]];
        let none = FxHashSet::default();
        let mut l = Labelled::new([&kept, &[], &[]], &planes, &internal, &none);
        // each alone may go (the other keeps the triangle in R), not both
        assert!(l.toggle_allowed(&[0]));
        assert_eq!(l.kept, [false, true]);
        l.flip(&[0]);
        assert!(!l.toggle_allowed(&[0, 1]));
        assert_eq!(l.kept, [true, true], "a refused set is undone");
        assert!(!l.toggle_allowed(&[1, 0]));
        assert_eq!(l.kept, [true, true]);
    }

    #[test]
    fn two_octants_touching_at_a_vertex_are_made_manifold() {
        // octants 0 (+x+y+z) and 7 (-x-y-z) touch only at vertex 0
        let (s, left) = run(&[0, 7], vec![smallvec![]; 7], &[]);
        assert_eq!(left, 0);
        assert!(s.added + s.removed > 0);
    }

    #[test]
    fn a_toggle_that_would_change_a_section_is_refused() {
        // the plane z = 0 (tag 9) through 0 and ±x, ±y, with no section: no tet with a face on it
        // may be added, and the kept ones have no kept tet across it, so none may be removed
        let mut planes: Vec<Planes> = vec![smallvec![]; 7];
        for v in [0, 1, 2, 3, 4] {
            planes[v] = smallvec![9];
        }
        let (s, left) = run(&[0, 7], planes, &[]);
        assert_eq!(s, ToggleStats::default());
        assert_eq!(left, 1);
    }
}
