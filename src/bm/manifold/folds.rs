//! Folds of ∂K at flat tetrahedra (cracks and fins, where rounded coplanar points meet) closed by
//! toggling the flat wedges behind them, under the same rules as the singular simplices' toggles.
use super::{Labelled, ToggleStats, MANY, NONE};
use crate::bm::complex;
use crate::bm::refine::{self, flat_height, key3, Triangulation};
use crate::fxhash::FxHashSet;
use crate::sections::{dot, sub};

/// Close the cracks and cut the fins of ∂K at flat tetrahedra. Where the tetrahedra around an edge
/// of ∂K between its two surface triangles, on one side, are all flat (their four vertices within
/// `tol` of one plane: rounded coplanar points that no plane tag makes flat), the two triangles
/// fold flat onto each other (a double sheet; a crack when that side is outside K, a fin when it
/// is inside). Toggling that wedge removes the fold; it is done when the sections allow it and,
/// with the singular simplices' toggles run where it adds one, no singular simplex is added, in
/// passes until none is left or a pass changes nothing. Returns the toggles done.
pub fn close_flat_folds(
    k: &mut Triangulation,
    nonconforming: &FxHashSet<u32>,
    tol: f64,
) -> ToggleStats {
    let lists: [&[[u32; 4]]; 3] = [k.kept, k.fillable, k.external];
    let positions = &*k.positions;
    let flat = Flat {
        flat: lists
            .iter()
            .flat_map(|l| l.iter())
            .map(|t| flat_height(t.map(|v| positions[v as usize])) <= tol)
            .collect(),
        positions,
    };
    let mut stats = ToggleStats::default();
    if !flat.flat.contains(&true)
        || !has_flat_wedge(lists, &flat, k.planes, k.internal, nonconforming)
    {
        return stats;
    }
    let mut l = Labelled::new(lists, k.planes, k.internal, nonconforming);
    // the sets whose repair failed once are not repaired again (a repair can cost a lot around
    // a vertex with a large star, and passes find the same wedges again)
    let mut refused: FxHashSet<(bool, Vec<u32>)> = FxHashSet::default();
    for _ in 0..FOLD_PASSES {
        let before = stats;
        for w in l.flat_wedges(&flat) {
            // an earlier toggle of this pass may have changed the wedge's side
            let side = l.kept[w[0] as usize];
            if w.iter().all(|&t| l.kept[t as usize] == side)
                && !l.try_unfold(&w, &flat, &mut refused, &mut stats)
            {
                // the fold may move to the flat tetrahedra behind the wedge: all of them at once
                let blob = l.flat_component(&w, &flat);
                if blob.len() > w.len() {
                    l.try_unfold(&blob, &flat, &mut refused, &mut stats);
                }
            }
        }
        if stats == before {
            break;
        }
    }
    let (kept, fillable, external) = l.into_lists();
    (*k.kept, *k.fillable, *k.external) = (kept, fillable, external);
    stats
}

/// Whether ∂K has a wedge of flat tetrahedra (`Labelled::flat_wedges`), looked for among the
/// tetrahedra that share a vertex with a flat one only: a wedge is flat tetrahedra around an edge
/// of a kept tetrahedron that is flat or beside a flat one, so every tetrahedron the search reads,
/// and every other one on a face it reads, has a vertex of a flat tetrahedron. The labelling of
/// the whole complex is then built only where there is a wedge (rarely; it was most of the
/// resolution's time on the shared files).
fn has_flat_wedge(
    lists: [&[[u32; 4]]; 3],
    flat: &Flat,
    planes: &[refine::Planes],
    internal: &FxHashSet<[u32; 3]>,
    nonconforming: &FxHashSet<u32>,
) -> bool {
    let mut near = vec![false; flat.positions.len()];
    let all = || lists.iter().flat_map(|l| l.iter());
    for (t, _) in all().zip(&flat.flat).filter(|(_, &f)| f) {
        for &v in t {
            near[v as usize] = true;
        }
    }
    // the lists' order is kept: the search's choices among a face's owners go by index
    let mut sub_flat = Vec::new();
    let mut flags = flat.flat.iter().copied();
    let sub = lists.map(|l| {
        (l.iter().zip(flags.by_ref()))
            .filter(|(t, _)| t.iter().any(|&v| near[v as usize]))
            .map(|(t, f)| {
                sub_flat.push(f);
                *t
            })
            .collect::<Vec<_>>()
    });
    let sub_lists: [&[[u32; 4]]; 3] = [&sub[0], &sub[1], &sub[2]];
    let l = Labelled::new(sub_lists, planes, internal, nonconforming);
    let sub_flat = Flat {
        flat: sub_flat,
        positions: flat.positions,
    };
    !l.flat_wedges(&sub_flat).is_empty()
}

/// Passes of [`close_flat_folds`] (each toggle can uncover a fold behind it).
const FOLD_PASSES: usize = 8;

/// Single toggles of the singular simplices' search after one unfolding (`repair_after_unfold`),
/// per round.
const REPAIR_TOGGLES: usize = 64;

/// Rounds of that search (single toggles, then a strip or a fan at each pinched vertex left).
const REPAIR_PASSES: usize = 2;

/// Largest set of flat tetrahedra toggled at once.
const FLAT_COMPONENT: usize = 256;

/// Which tetrahedra are flat, and where the points are (to tell a fold from a flat continuation).
struct Flat<'a> {
    flat: Vec<bool>,
    positions: &'a [[f64; 3]],
}

impl Flat<'_> {
    /// Do `a` and `b` lie on the same side of the line through `e` (in the plane they nearly
    /// share with it)? Two surface triangles at `e` with such apexes folded onto each other.
    fn same_side(&self, e: (u32, u32), a: u32, b: u32) -> bool {
        let p = |v: u32| self.positions[v as usize];
        let (o, d) = (p(e.0), sub(p(e.1), p(e.0)));
        let dd = dot(d, d);
        let perp = |q: [f64; 3]| {
            let w = sub(q, o);
            let s = dot(w, d) / dd;
            [w[0] - s * d[0], w[1] - s * d[1], w[2] - s * d[2]]
        };
        dot(perp(p(a)), perp(p(b))) > 0.0
    }
}

impl Labelled<'_> {
    /// Toggle every tetrahedron of `set` if each is allowed, the folds at their edges get fewer and
    /// the singular simplices at them no more; else leave them. Toggling changes ∂K only at the
    /// set's faces, so these local counts are the changes of the global ones. Where the toggle
    /// lowers the folds but leaves a singular simplex (a crack filled up to a vertex where the
    /// outside goes on), the singular simplices' own toggles run there, and the whole change
    /// stays only if, over every vertex it touched, it leaves no more singular simplices and
    /// fewer folds than before.
    fn try_unfold(
        &mut self,
        set: &[u32],
        flat: &Flat,
        refused: &mut FxHashSet<(bool, Vec<u32>)>,
        stats: &mut ToggleStats,
    ) -> bool {
        let Some(&first) = set.first() else {
            return false;
        };
        let edges = self.edges_of(set);
        let before = (self.badness(set), self.folds_at(&edges, flat));
        // which way: filling a crack and cutting the same tetrahedra as a fin are two moves
        let adding = !self.kept[first as usize];
        if !self.toggle_allowed(set) {
            return false;
        }
        let after = (self.badness(set), self.folds_at(&edges, flat));
        if after.1 >= before.1 {
            self.flip(set);
            return false;
        }
        if after.0 > before.0 {
            let mut key = (adding, set.to_vec());
            key.1.sort_unstable();
            if refused.contains(&key) || !self.repair_after_unfold(set, flat, stats) {
                refused.insert(key);
                self.flip(set);
                return false;
            }
        }
        for &t in set {
            self.touched.extend(self.tets[t as usize]);
            self.log.push(t);
            if self.kept[t as usize] {
                stats.added += 1;
            } else {
                stats.removed += 1;
            }
        }
        true
    }

    /// The edges of the tetrahedra of `set`.
    fn edges_of(&self, set: &[u32]) -> FxHashSet<(u32, u32)> {
        set.iter()
            .flat_map(|&t| {
                let v = self.tets[t as usize];
                [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
                    .map(|(i, j)| refine::edge(v[i], v[j]))
            })
            .collect()
    }

    /// After `set` was toggled (fewer folds, more singular simplices at it): the singular
    /// simplices' toggles at its vertices (`REPAIR_PASSES` rounds of at most `REPAIR_TOGGLES`
    /// single toggles, then a strip or a fan at each pinched vertex left). Keeps them and
    /// returns true if, over the vertices of `set` and of every tetrahedron they toggled, the
    /// singular simplices are no more and the folds fewer than before `set` was toggled; else
    /// undoes them (not `set`) and returns false. Their toggles are added to `stats`.
    fn repair_after_unfold(&mut self, set: &[u32], flat: &Flat, stats: &mut ToggleStats) -> bool {
        let (touched, logged) = (self.touched.len(), self.log.len());
        let mut scratch = ToggleStats::default();
        let work: Vec<u32> = set.iter().flat_map(|&t| self.tets[t as usize]).collect();
        self.toggle_rounds(work, REPAIR_PASSES, REPAIR_TOGGLES, &mut scratch);
        // everything toggled since before `set` was
        let mut changed: Vec<u32> = self.log[logged..].to_vec();
        changed.extend_from_slice(set);
        let edges = self.edges_of(&changed);
        let after = (self.badness(&changed), self.folds_at(&edges, flat));
        // toggles are their own inverse: the same flips undo the repair and redo it
        let repair: Vec<u32> = self.log[logged..].to_vec();
        self.flip(&repair);
        self.flip(set);
        let before = (self.badness(&changed), self.folds_at(&edges, flat));
        self.flip(set);
        if after.0 <= before.0 && after.1 < before.1 {
            self.flip(&repair);
            stats.add(&scratch);
            return true;
        }
        self.touched.truncate(touched);
        self.log.truncate(logged);
        false
    }

    /// How many of `edges` are folds of ∂K: a flat wedge on one side between two of its surface
    /// triangles there.
    fn folds_at(&self, edges: &FxHashSet<(u32, u32)>, flat: &Flat) -> usize {
        edges
            .iter()
            .filter(|&&(a, b)| {
                self.surface_at(a)
                    .iter()
                    .filter(|f| f.contains(&b))
                    .any(|f| self.fold_at((a, b), *f, flat))
            })
            .count()
    }

    /// Is surface triangle `f` (sorted key) the start of a flat wedge at its edge `e`, on either
    /// side?
    fn fold_at(&self, e: (u32, u32), f: [u32; 3], flat: &Flat) -> bool {
        self.faces
            .owners(&f)
            .any(|t| self.wedge(e, f, t, flat).is_some())
    }

    /// Every wedge of flat tetrahedra (`flat` per tetrahedron) around an edge of ∂K that fills the
    /// whole angle on one side between the edge's two surface triangles.
    fn flat_wedges(&self, flat: &Flat) -> Vec<Vec<u32>> {
        let mut out = Vec::new();
        let mut seen: FxHashSet<Vec<u32>> = FxHashSet::default();
        for (t, &kept) in self.kept.iter().enumerate() {
            // a wedge starts at t or at a tetrahedron across one of its faces, and is all flat
            if !kept || !self.near_flat(t as u32, flat) {
                continue;
            }
            let tet = self.tets[t];
            for i in 0..4 {
                let f = key3(complex::outward_face(&tet, i));
                if self.other_kept_at(t as u32, i) {
                    continue;
                }
                // f is on ∂K: walk around each of its edges on both sides
                let outside = self.faces.owners(&f).find(|&o| o != t as u32);
                for e in [(f[0], f[1]), (f[1], f[2]), (f[0], f[2])] {
                    for start in [Some(t as u32), outside].into_iter().flatten() {
                        if let Some(mut w) = self.wedge(e, f, start, flat) {
                            w.sort_unstable();
                            if seen.insert(w.clone()) {
                                out.push(w);
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Whether `t` or a tetrahedron sharing a face with it is flat.
    fn near_flat(&self, t: u32, flat: &Flat) -> bool {
        flat.flat[t as usize]
            || (0..4).any(|i| match self.twin[t as usize][i] {
                NONE => false,
                MANY => {
                    let f = key3(complex::outward_face(&self.tets[t as usize], i));
                    self.faces.owners(&f).any(|o| flat.flat[o as usize])
                }
                o => flat.flat[o as usize],
            })
    }

    /// From `start` (a tetrahedron on face `f`, which contains edge `e`), the tetrahedra around `e`
    /// on `start`'s side of ∂K up to the next surface triangle at `e`, if all are flat.
    fn wedge(&self, e: (u32, u32), f: [u32; 3], start: u32, flat: &Flat) -> Option<Vec<u32>> {
        let side = self.kept[start as usize];
        let (mut t, mut entered) = (start, f);
        let mut out = Vec::new();
        let first = *f.iter().find(|&&v| v != e.0 && v != e.1)?;
        let last = loop {
            if !flat.flat[t as usize] || out.len() > 64 {
                return None;
            }
            out.push(t);
            let tet = self.tets[t as usize];
            // the other face of t at e
            let apex = *tet
                .iter()
                .find(|&&v| v != e.0 && v != e.1 && !entered.contains(&v))?;
            let next = key3([e.0, e.1, apex]);
            let beyond = self.faces.owners(&next).find(|&o| o != t);
            match beyond {
                Some(n) if self.kept[n as usize] == side => {
                    if n == start {
                        return None; // all the way round: no surface at e on this side
                    }
                    (t, entered) = (n, next);
                }
                // the next surface triangle at e (or the hull, outside everything, for a fin):
                // a fold if it lies over the first one, not beside it
                Some(_) => break apex,
                None if side => break apex,
                None => return None,
            }
        };
        flat.same_side(e, first, last).then_some(out)
    }

    /// The flat tetrahedra on the side of `w` (kept or not) connected to `w` through faces, at
    /// most `FLAT_COMPONENT` of them.
    fn flat_component(&self, w: &[u32], flat: &Flat) -> Vec<u32> {
        let side = self.kept[w[0] as usize];
        let mut out: Vec<u32> = w.to_vec();
        let mut seen: FxHashSet<u32> = w.iter().copied().collect();
        let mut i = 0;
        while i < out.len() && out.len() < FLAT_COMPONENT {
            for n in self.face_neighbours(out[i]) {
                if flat.flat[n as usize] && self.kept[n as usize] == side && seen.insert(n) {
                    out.push(n);
                }
            }
            i += 1;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::refine::test_support::{positive as oriented, Owned};

    /// A crack (`manifold`'s test `crack`: the flat tetrahedron a b c d, `height` thick, unkept
    /// between the kept a b d top and a b c bottom) and, apart from it, kept tetrahedra sharing no
    /// vertex with it: the search among the flat one's neighbours finds a wedge exactly when the
    /// whole complex's does.
    #[test]
    fn the_wedge_search_near_flat_tetrahedra_agrees_with_the_whole_complex() {
        for (height, wedge) in [(1e-13, true), (0.1, false)] {
            let mut p = super::super::tests::crack_points(height);
            // far away, a kept pair and an unkept one beside them
            p.extend([
                [5.0, 0.0, 0.0],
                [6.0, 0.0, 0.0],
                [5.0, 1.0, 0.0],
                [5.0, 0.0, 1.0],
            ]);
            p.extend([[6.0, 1.0, 1.0], [5.0, 0.0, -1.0]]);
            let (a, b, c, d, top, bottom) = (0, 1, 2, 3, 4, 5);
            let o = Owned {
                kept: [
                    [a, b, d, top],
                    [a, b, c, bottom],
                    [6, 7, 8, 9],
                    [7, 8, 9, 10],
                ]
                .map(|t| oriented(&p, t))
                .to_vec(),
                fillable: vec![oriented(&p, [6, 7, 8, 11])],
                external: vec![oriented(&p, [a, b, c, d])],
                ..Owned::at(p)
            };
            let lists: [&[[u32; 4]]; 3] = [&o.kept, &o.fillable, &o.external];
            let flat = Flat {
                flat: (lists.iter().flat_map(|l| l.iter()))
                    .map(|t| flat_height(t.map(|v| o.positions[v as usize])) <= 1e-8)
                    .collect(),
                positions: &o.positions,
            };
            let none = FxHashSet::default();
            let whole = Labelled::new(lists, &o.planes, &o.internal, &none);
            assert_eq!(!whole.flat_wedges(&flat).is_empty(), wedge);
            let near = has_flat_wedge(lists, &flat, &o.planes, &o.internal, &none);
            assert_eq!(near, wedge);
        }
    }
}
