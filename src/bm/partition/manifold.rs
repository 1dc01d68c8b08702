//! Domains whose boundaries are manifolds: where a label's boundary has a singular edge (more
//! than one sector of the label around it) or a pinched vertex (more than one component of the
//! label in its star), one sector or component of free tetrahedra changes label.
//!
//! The repair is a work list of vertices whose star is not a disk for some label. Every change it
//! makes lowers the sum over all vertices of their non-disk label boundaries (it only changes the
//! stars of the vertices of the tetrahedra it relabels, and it is made only where that sum there
//! drops), so it terminates; after a change, the bad vertices whose evaluation read a changed
//! label (those of the tetrahedra around the changed tetrahedra's vertices) are queued again.
use super::{Complex, NONE};
use crate::bm::complex::outward_face;
use crate::bm::fill::singular_simplices;
use crate::fxhash::FxHashSet;
use std::cmp::Reverse;

#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Fixed {
    pub relabelled: u64,
    pub edges_left: u64,
    pub vertices_left: u64,
}

/// A label's singular edges and pinched vertices.
type Singular = (Vec<(u32, u32)>, Vec<u32>);

/// Per label, its singular edges and pinched vertices.
fn singular(complex: &Complex, label: &[u32], n_labels: usize) -> Vec<Singular> {
    let mut faces: Vec<Vec<[u32; 3]>> = vec![Vec::new(); n_labels];
    for (t, tet) in complex.tets.iter().enumerate() {
        for i in 0..4 {
            let n = complex.nbr[t][i];
            if n == NONE || label[n as usize] != label[t] {
                faces[label[t] as usize].push(outward_face(tet, i));
            }
        }
    }
    faces.iter().map(|f| singular_simplices(f)).collect()
}

fn count(s: &[Singular]) -> (u64, u64) {
    let e = s.iter().map(|x| x.0.len() as u64).sum();
    let v = s.iter().map(|x| x.1.len() as u64).sum();
    (e, v)
}

/// The tetrahedra around simplex `sigma` (an edge or a vertex).
fn star(complex: &Complex, sigma: &[u32]) -> Vec<usize> {
    let mut out: Vec<usize> = complex.star[sigma[0] as usize]
        .iter()
        .map(|&t| t as usize)
        .collect();
    out.retain(|&t| sigma.iter().all(|v| complex.tets[t].contains(v)));
    out
}

/// The components of `members` (tetrahedra around `sigma`) joined through faces holding `sigma`.
fn components(complex: &Complex, sigma: &[u32], members: &[usize]) -> Vec<Vec<usize>> {
    let set: FxHashSet<usize> = members.iter().copied().collect();
    let mut seen: FxHashSet<usize> = FxHashSet::default();
    let mut out = Vec::new();
    for &s in members {
        if !seen.insert(s) {
            continue;
        }
        let mut comp = vec![s];
        let mut i = 0;
        while i < comp.len() {
            let t = comp[i];
            i += 1;
            for (k, &n) in complex.nbr[t].iter().enumerate() {
                let through_sigma = !sigma.contains(&complex.tets[t][k]);
                if n != NONE
                    && through_sigma
                    && set.contains(&(n as usize))
                    && seen.insert(n as usize)
                {
                    comp.push(n as usize);
                }
            }
        }
        out.push(comp);
    }
    out
}

/// The labels of the face neighbours of `comp` outside it, other than `not`.
fn neighbour_labels(complex: &Complex, label: &[u32], comp: &[usize], not: u32) -> Vec<u32> {
    let mut out = Vec::new();
    for &t in comp {
        for &n in &complex.nbr[t] {
            if n != NONE && label[n as usize] != not && !out.contains(&label[n as usize]) {
                out.push(label[n as usize]);
            }
        }
    }
    out
}

/// A change of labels: these tetrahedra take this label.
type Change = (Vec<usize>, u32);

/// The changes of labels around `sigma`: every piece of one label there (its tetrahedra around
/// `sigma`, face-connected through faces holding it) going to the label of one of its neighbours.
/// Pinned tetrahedra never change.
fn candidates_at(complex: &Complex, label: &[u32], pinned: &[bool], sigma: &[u32]) -> Vec<Change> {
    let around = star(complex, sigma);
    let mut labels: Vec<u32> = around.iter().map(|&t| label[t]).collect();
    labels.sort_unstable();
    labels.dedup();
    let mut out = Vec::new();
    for l in labels {
        let mine: Vec<usize> = around.iter().copied().filter(|&t| label[t] == l).collect();
        for c in components(complex, sigma, &mine) {
            if c.iter().any(|&t| pinned[t]) {
                continue;
            }
            for to in neighbour_labels(complex, label, &c, l) {
                out.push((c.clone(), to));
            }
        }
    }
    out
}

/// The vertices of `tets`, each once.
fn vertices_of(complex: &Complex, tets: &[usize]) -> Vec<u32> {
    let mut vs: Vec<u32> = tets.iter().flat_map(|&t| complex.tets[t]).collect();
    vs.sort_unstable();
    vs.dedup();
    vs
}

/// Give `tets` label `to`; their labels before.
fn relabel(label: &mut [u32], tets: &[usize], to: u32) -> Vec<u32> {
    let old = tets.iter().map(|&t| label[t]).collect();
    for &t in tets {
        label[t] = to;
    }
    old
}

/// Give `tets` back their labels `old`.
fn restore(label: &mut [u32], tets: &[usize], old: &[u32]) {
    for (&t, &o) in tets.iter().zip(old) {
        label[t] = o;
    }
}

/// A candidate's key: non-disk boundaries removed, then fewer tetrahedra given a label their
/// sections exclude, then fewer tetrahedra changed.
type Gain = (u32, Reverse<(usize, usize)>);

/// What a repair step may change: a piece of one label around a singular simplex, or one
/// tetrahedron.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Moves {
    Pieces,
    Single,
}

/// Marks a vertex whose badness is not known (not yet computed, or its star changed).
const UNKNOWN: u32 = u32::MAX;

/// The labels being repaired, with every vertex's number of non-disk label boundaries as the
/// current labels have it (computed when first asked, forgotten when its star changes).
struct Repair<'a> {
    complex: &'a Complex,
    label: &'a mut [u32],
    pinned: &'a [bool],
    /// Per tetrahedron, the labels compatible with the sections (a bit per label below 64).
    compatible: &'a [u64],
    bad: Vec<u32>,
}

impl Repair<'_> {
    /// How many of `tets` would take a label not compatible with the sections (`labels::assign`).
    fn misfits(&self, tets: &[usize], to: u32) -> usize {
        let fits = |t: usize| to >= 64 || self.compatible[t] & (1 << to) != 0;
        tets.iter().filter(|&&t| !fits(t)).count()
    }

    /// Vertex `v`'s non-disk label boundaries under the current labels.
    fn bad(&mut self, v: u32) -> u32 {
        if self.bad[v as usize] == UNKNOWN {
            self.bad[v as usize] = vertex_bad(self.complex, self.label, v);
        }
        self.bad[v as usize]
    }

    /// Non-disk label boundaries at `vertices` under the current labels.
    fn cost(&mut self, vertices: &[u32]) -> u32 {
        vertices.iter().map(|&v| self.bad(v)).sum()
    }

    /// The same, with the labels as they are for the moment (a change being tried).
    fn cost_trying(&self, vertices: &[u32]) -> u32 {
        (vertices.iter())
            .map(|&v| vertex_bad(self.complex, self.label, v))
            .sum()
    }

    /// The change among `candidates` that lowers the non-disk boundaries around it most, if any.
    fn best_change(&mut self, candidates: &[Change]) -> Option<Change> {
        let mut best: Option<(Gain, &Change)> = None;
        for change in candidates {
            let vs = vertices_of(self.complex, &change.0);
            let before = self.cost(&vs);
            let old = relabel(self.label, &change.0, change.1);
            let after = self.cost_trying(&vs);
            restore(self.label, &change.0, &old);
            let gain = (
                before.saturating_sub(after),
                Reverse((self.misfits(&change.0, change.1), change.0.len())),
            );
            if after < before && best.is_none_or(|b| gain > b.0) {
                best = Some((gain, change));
            }
        }
        best.map(|b| b.1.clone())
    }

    /// Two changes in a row where one alone does not help: a change among `candidates` (at most
    /// two more non-disk boundaries), then a change at a vertex it made bad; the pair that lowers
    /// the non-disk boundaries at all vertices they touch most, if any (a spike of one label
    /// retracts by two pieces where each alone leaves a pinch).
    fn best_pair(&mut self, candidates: &[Change]) -> Option<Vec<Change>> {
        let mut best: Option<(Gain, Vec<Change>)> = None;
        for (comp, to) in candidates {
            let vs = vertices_of(self.complex, comp);
            let before1 = self.cost(&vs);
            let old = relabel(self.label, comp, *to);
            // after the first change: its vertices' badness (the second changes only its own)
            let after1: Vec<u32> = (vs.iter())
                .map(|&w| vertex_bad(self.complex, self.label, w))
                .collect();
            if after1.iter().sum::<u32>() > before1 + 2 {
                restore(self.label, comp, &old);
                continue;
            }
            let mut tried = Vec::new();
            for (&w, _) in vs.iter().zip(&after1).filter(|x| *x.1 > 0) {
                for (comp2, to2) in candidates_at(self.complex, self.label, self.pinned, &[w]) {
                    if comp2.iter().any(|t| comp.contains(t)) {
                        continue;
                    }
                    let vs2 = vertices_of(self.complex, &comp2);
                    let old2 = relabel(self.label, &comp2, to2);
                    let mut after = self.cost_trying(&vs2);
                    restore(self.label, &comp2, &old2);
                    after += (vs.iter().zip(&after1))
                        .filter(|x| vs2.binary_search(x.0).is_err())
                        .map(|x| x.1)
                        .sum::<u32>();
                    tried.push((vs2, after, comp2, to2));
                }
            }
            restore(self.label, comp, &old);
            for (vs2, after, comp2, to2) in tried {
                let mut both = vs2;
                both.extend(&vs);
                both.sort_unstable();
                both.dedup();
                let before = self.cost(&both);
                let gain = (
                    before.saturating_sub(after),
                    Reverse((
                        self.misfits(comp, *to) + self.misfits(&comp2, to2),
                        comp.len() + comp2.len(),
                    )),
                );
                if after < before && best.as_ref().is_none_or(|b| gain > b.0) {
                    best = Some((gain, vec![(comp.clone(), *to), (comp2, to2)]));
                }
            }
        }
        best.map(|b| b.1)
    }

    /// The single free tetrahedron around `v` whose change to a face neighbour's label lowers the
    /// non-disk boundaries at its vertices most, if any.
    fn best_single(&mut self, v: u32) -> Option<Change> {
        let mut best: Option<(u32, usize, u32)> = None;
        for &t in &self.complex.star[v as usize] {
            let t = t as usize;
            if self.pinned[t] {
                continue;
            }
            let vs = self.complex.tets[t];
            let before = self.cost(&vs);
            let current = self.label[t];
            for &n in &self.complex.nbr[t] {
                if n == NONE || self.label[n as usize] == current {
                    continue;
                }
                self.label[t] = self.label[n as usize];
                let after = self.cost_trying(&vs);
                if after < before && best.is_none_or(|b| before - after > b.0) {
                    best = Some((before - after, t, self.label[t]));
                }
                self.label[t] = current;
            }
        }
        best.map(|(_, t, l)| (vec![t], l))
    }

    /// The changes of kind `moves` that lower the non-disk boundaries around bad vertex `v`: a
    /// piece around one of its singular edges, else around `v`, one change or two; or a single
    /// tetrahedron.
    fn changes_at(&mut self, v: u32, moves: Moves) -> Vec<Change> {
        if moves == Moves::Single {
            return self.best_single(v).into_iter().collect();
        }
        let edges = singular_edges_at(self.complex, self.label, v);
        let simplices = (edges.iter().map(|&w| vec![v, w])).chain([vec![v]]);
        for sigma in simplices {
            let options = candidates_at(self.complex, self.label, self.pinned, &sigma);
            if let Some(c) = self.best_change(&options) {
                return vec![c];
            }
            if let Some(cs) = self.best_pair(&options) {
                return cs;
            }
        }
        Vec::new()
    }

    /// Work through the bad vertices `at` (and those changes make bad or change around) with
    /// changes of kind `moves` until none helps; the vertices left bad.
    fn settle(&mut self, at: Vec<u32>, moves: Moves, fixed: &mut Fixed) -> Vec<u32> {
        let mut queued = vec![false; self.complex.star.len()];
        let mut queue = std::collections::VecDeque::new();
        for v in at {
            if !std::mem::replace(&mut queued[v as usize], true) {
                queue.push_back(v);
            }
        }
        let mut left = Vec::new();
        while let Some(v) = queue.pop_front() {
            queued[v as usize] = false;
            if self.bad(v) == 0 {
                continue;
            }
            let changes = self.changes_at(v, moves);
            if changes.is_empty() {
                left.push(v);
                continue;
            }
            let (changed, again) = self.commit(changes);
            fixed.relabelled += changed;
            for u in again {
                if !queued[u as usize] && self.bad(u) > 0 {
                    queued[u as usize] = true;
                    queue.push_back(u);
                }
            }
        }
        left.sort_unstable();
        left.dedup();
        left.retain(|&v| self.bad(v) > 0);
        left
    }

    /// Make `changes`; the vertices whose evaluation may differ now: those of the tetrahedra
    /// around the changed tetrahedra's vertices.
    fn commit(&mut self, changes: Vec<Change>) -> (u64, Vec<u32>) {
        let mut changed = 0;
        let mut touched = Vec::new();
        for (comp, to) in changes {
            for &t in &comp {
                self.label[t] = to;
                touched.extend(self.complex.tets[t]);
            }
            changed += comp.len() as u64;
        }
        touched.sort_unstable();
        touched.dedup();
        let mut again = Vec::new();
        for &u in &touched {
            self.bad[u as usize] = UNKNOWN;
            again.extend(
                (self.complex.star[u as usize].iter()).flat_map(|&t| self.complex.tets[t as usize]),
            );
        }
        again.sort_unstable();
        again.dedup();
        (changed, again)
    }
}

/// Relabel free tetrahedra (not `pinned`) where that lowers the number of non-disk label
/// boundaries around them: whole pieces around each singular simplex (one change, or two in a
/// row), else single tetrahedra, until no bad vertex has such a change.
pub(super) fn repair(
    complex: &Complex,
    label: &mut [u32],
    pinned: &[bool],
    compatible: &[u64],
    n_labels: usize,
) -> Fixed {
    let mut fixed = Fixed::default();
    let mut initial = Vec::new();
    for (edges, vertices) in singular(complex, label, n_labels) {
        initial.extend((edges.iter().flat_map(|&(a, b)| [a, b])).chain(vertices));
    }
    let mut repair = Repair {
        complex,
        label,
        pinned,
        compatible,
        bad: vec![UNKNOWN; complex.star.len()],
    };
    // pieces wherever they help first, then single tetrahedra, as long as those change something
    let mut at = initial;
    loop {
        at = repair.settle(at, Moves::Pieces, &mut fixed);
        let before = fixed.relabelled;
        at = repair.settle(at, Moves::Single, &mut fixed);
        if fixed.relabelled == before || at.is_empty() {
            break;
        }
    }
    let (e, v) = count(&singular(complex, label, n_labels));
    fixed.edges_left = e;
    fixed.vertices_left = v;
    fixed
}

/// The other ends of the edges at `v` that are singular for some label (more than two of that
/// label's boundary faces around them).
fn singular_edges_at(complex: &Complex, label: &[u32], v: u32) -> Vec<u32> {
    let mut ends: smallvec::SmallVec<[(u32, u32); 64]> = smallvec::SmallVec::new();
    for_link_edges(complex, label, v, |l, a, b| {
        ends.push((l, a));
        ends.push((l, b));
    });
    ends.sort_unstable();
    let mut out: Vec<u32> = (ends.chunk_by(|x, y| x == y))
        .filter(|run| run.len() > 2)
        .map(|run| run[0].1)
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Call `edge(label, from, to)` for the link edges of every label's boundary faces at `v` (each
/// boundary face of a tetrahedron of that label holding `v`, outward, without `v`).
fn for_link_edges(complex: &Complex, label: &[u32], v: u32, mut edge: impl FnMut(u32, u32, u32)) {
    for &t in &complex.star[v as usize] {
        let t = t as usize;
        let (tet, l) = (&complex.tets[t], label[t]);
        for i in 0..4 {
            let n = complex.nbr[t][i];
            if tet[i] == v || (n != NONE && label[n as usize] == l) {
                continue;
            }
            let f = outward_face(tet, i);
            let k = f.iter().position(|&w| w == v).expect("a face holding v");
            edge(l, f[(k + 1) % 3], f[(k + 2) % 3]);
        }
    }
}

/// How many labels' boundaries are not a disk around vertex `v`: the link of the label's
/// boundary faces at `v` must be one cycle (no singular edge through `v`, no pinch).
fn vertex_bad(complex: &Complex, label: &[u32], v: u32) -> u32 {
    let mut link: smallvec::SmallVec<[(u32, u32, u32); 32]> = smallvec::SmallVec::new();
    for_link_edges(complex, label, v, |l, a, b| link.push((l, a, b)));
    link.sort_unstable();
    (link.chunk_by(|x, y| x.0 == y.0))
        .map(|edges| u32::from(!is_one_cycle(edges)))
        .sum()
}

/// Whether `edges` (one label's link edges, sorted by their start) form one directed cycle: every
/// vertex starts one edge and ends one, and following them from the first visits them all.
fn is_one_cycle(edges: &[(u32, u32, u32)]) -> bool {
    if edges.windows(2).any(|w| w[0].1 == w[1].1) {
        return false;
    }
    let mut ends: smallvec::SmallVec<[u32; 32]> = edges.iter().map(|e| e.2).collect();
    ends.sort_unstable();
    if !ends.iter().zip(edges).all(|(&b, e)| b == e.1) {
        return false;
    }
    let (start, mut at) = (edges[0].1, edges[0].2);
    let mut steps = 1;
    while at != start {
        let next = (edges.binary_search_by_key(&at, |e| e.1)).expect("every end starts an edge");
        at = edges[next].2;
        steps += 1;
    }
    steps == edges.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two tetrahedra on the triangle (0,1,2), apexes 3 and 4, and a third touching the first
    /// only at vertex 3.
    fn three() -> Complex {
        Complex::new(8, vec![[0, 1, 2, 3], [0, 2, 1, 4], [3, 5, 6, 7]])
    }

    #[test]
    fn a_label_meeting_itself_at_a_vertex_is_not_a_disk_there() {
        let c = three();
        assert_eq!(vertex_bad(&c, &[0, 0, 1], 3), 0);
        assert_eq!(vertex_bad(&c, &[0, 0, 0], 3), 1);
        assert_eq!(vertex_bad(&c, &[0, 1, 0], 0), 0);
    }

    #[test]
    fn a_link_is_a_disk_only_as_one_directed_cycle() {
        let cycle = |edges: &[(u32, u32)]| {
            let mut e: Vec<(u32, u32, u32)> = edges.iter().map(|&(a, b)| (0, a, b)).collect();
            e.sort_unstable();
            is_one_cycle(&e)
        };
        assert!(cycle(&[(1, 2), (2, 3), (3, 1)]));
        // two cycles (a pinch), a vertex starting two edges (a singular edge), an open fan
        assert!(!cycle(&[(1, 2), (2, 3), (3, 1), (4, 5), (5, 6), (6, 4)]));
        assert!(!cycle(&[(1, 2), (2, 1), (1, 3), (3, 1)]));
        assert!(!cycle(&[(1, 2), (2, 3)]));
    }

    #[test]
    fn a_spike_of_free_tetrahedra_is_relabelled_and_the_pinch_goes() {
        // the third tetrahedron touches the first two only at vertex 3, and it is free with a
        // face neighbour of another label: it takes that label, the pinch of label 0 goes
        let c = Complex::new(
            9,
            vec![[0, 1, 2, 3], [0, 2, 1, 4], [3, 5, 6, 7], [5, 6, 7, 8]],
        );
        let mut label = vec![0, 0, 0, 1];
        assert_eq!(vertex_bad(&c, &label, 3), 1);
        let fixed = repair(&c, &mut label, &[true, true, false, true], &[!0; 4], 2);
        assert_eq!((fixed.edges_left, fixed.vertices_left), (0, 0));
        assert_eq!(label, vec![0, 0, 1, 1]);
        assert_eq!(fixed.relabelled, 1);
    }

    #[test]
    fn a_pinch_no_free_change_undoes_stays_and_is_counted() {
        let c = three();
        let mut label = vec![0, 0, 0];
        // pinned: the first two; the third may change, but only to a neighbour's label (it has
        // none): the pinch stays and is counted
        let fixed = repair(&c, &mut label, &[true, true, false], &[!0; 3], 2);
        assert_eq!(fixed.vertices_left, 1);
        assert_eq!(label, vec![0, 0, 0]);
    }
}
