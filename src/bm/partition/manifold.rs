//! Domains whose boundaries are manifolds: where a label's boundary has a singular edge (more
//! than one sector of the label around it) or a pinched vertex (more than one component of the
//! label in its star), one sector or component of free tetrahedra changes label.
use super::{Complex, NONE};
use crate::bm::complex::outward_face;
use crate::bm::fill::singular_simplices;
use crate::fxhash::FxHashSet;

/// Most rounds of repair (each recounts every domain's singular simplices).
const ROUNDS: usize = 8;

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

/// Non-disk label boundaries at the vertices of `tets` (each vertex once).
fn cost_at(complex: &Complex, label: &[u32], tets: &[usize]) -> u32 {
    (vertices_of(complex, tets).iter())
        .map(|&v| vertex_bad(complex, label, v))
        .sum()
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

/// The change among `candidates` that lowers the non-disk boundaries around it most, if any.
fn best_change(complex: &Complex, label: &mut [u32], candidates: Vec<Change>) -> Option<Change> {
    let mut best: Option<(u32, Vec<usize>, u32)> = None;
    for (comp, to) in candidates {
        let before = cost_at(complex, label, &comp);
        let old = relabel(label, &comp, to);
        let after = cost_at(complex, label, &comp);
        restore(label, &comp, &old);
        if after < before && best.as_ref().is_none_or(|b| before - after > b.0) {
            best = Some((before - after, comp, to));
        }
    }
    best.map(|b| (b.1, b.2))
}

/// Two changes in a row where one alone does not help: a change among `candidates` (at most two
/// more non-disk boundaries), then the best change at a vertex it made bad; the pair that lowers
/// the non-disk boundaries at all vertices they touch most, if any (a spike of one label retracts
/// by two pieces where each alone leaves a pinch).
fn best_pair(
    complex: &Complex,
    label: &mut [u32],
    pinned: &[bool],
    candidates: Vec<Change>,
) -> Option<Vec<Change>> {
    let mut best: Option<(u32, Vec<Change>)> = None;
    for (comp, to) in candidates {
        let before1 = cost_at(complex, label, &comp);
        let old = relabel(label, &comp, to);
        if cost_at(complex, label, &comp) > before1 + 2 {
            restore(label, &comp, &old);
            continue;
        }
        let bad: Vec<u32> = (vertices_of(complex, &comp).into_iter())
            .filter(|&w| vertex_bad(complex, label, w) > 0)
            .collect();
        for w in bad {
            for (comp2, to2) in candidates_at(complex, label, pinned, &[w]) {
                if comp2.iter().any(|t| comp.contains(t)) {
                    continue;
                }
                let both: Vec<usize> = comp.iter().chain(&comp2).copied().collect();
                let old2 = relabel(label, &comp2, to2);
                let after = cost_at(complex, label, &both);
                restore(label, &comp2, &old2);
                restore(label, &comp, &old);
                let before = cost_at(complex, label, &both);
                relabel(label, &comp, to);
                if after < before && best.as_ref().is_none_or(|b| before - after > b.0) {
                    best = Some((before - after, vec![(comp.clone(), to), (comp2, to2)]));
                }
            }
        }
        restore(label, &comp, &old);
    }
    best.map(|b| b.1)
}

/// Relabel free tetrahedra (not `pinned`) where that lowers the number of non-disk label
/// boundaries around them: whole pieces around each singular simplex (one change, or two in a
/// row), then single tetrahedra; rounds until nothing improves.
pub(super) fn repair(
    complex: &Complex,
    label: &mut [u32],
    pinned: &[bool],
    n_labels: usize,
) -> Fixed {
    let mut fixed = Fixed::default();
    let mut sets = singular(complex, label, n_labels);
    for _ in 0..ROUNDS {
        let (e, v) = count(&sets);
        if e + v == 0 {
            break;
        }
        let mut changed = 0;
        for (edges, vertices) in &sets {
            let simplices =
                (edges.iter().map(|&(a, b)| vec![a, b])).chain(vertices.iter().map(|&v| vec![v]));
            for sigma in simplices {
                let options = candidates_at(complex, label, pinned, &sigma);
                let changes = match best_change(complex, label, options.clone()) {
                    Some(c) => vec![c],
                    None => best_pair(complex, label, pinned, options).unwrap_or_default(),
                };
                for (comp, to) in changes {
                    for &t in &comp {
                        label[t] = to;
                    }
                    changed += comp.len() as u64;
                }
            }
        }
        changed += local_moves(complex, label, pinned, &sets);
        fixed.relabelled += changed;
        sets = singular(complex, label, n_labels);
        if changed == 0 {
            break;
        }
    }
    let (e, v) = count(&sets);
    fixed.edges_left = e;
    fixed.vertices_left = v;
    fixed
}

/// How many labels' boundaries are not a disk around vertex `v`: the link of the label's
/// boundary faces at `v` must be one cycle (no singular edge through `v`, no pinch).
fn vertex_bad(complex: &Complex, label: &[u32], v: u32) -> u32 {
    let star = &complex.star[v as usize];
    let mut labels: smallvec::SmallVec<[u32; 4]> = smallvec::SmallVec::new();
    for &t in star {
        let l = label[t as usize];
        if !labels.contains(&l) {
            labels.push(l);
        }
    }
    let mut bad = 0;
    for l in labels {
        // the link's edges: boundary faces of l at v without v
        let mut link: smallvec::SmallVec<[(u32, u32); 32]> = smallvec::SmallVec::new();
        for &t in star {
            let t = t as usize;
            if label[t] != l {
                continue;
            }
            for i in 0..4 {
                let tet = &complex.tets[t];
                if tet[i] == v {
                    continue;
                }
                let n = complex.nbr[t][i];
                if n != NONE && label[n as usize] == l {
                    continue;
                }
                let f = outward_face(tet, i);
                let k = f.iter().position(|&w| w == v).expect("a face holding v");
                link.push((f[(k + 1) % 3], f[(k + 2) % 3]));
            }
        }
        if link.is_empty() {
            continue;
        }
        // one cycle: every link vertex twice, and following the edges visits them all
        let mut ok = true;
        let mut ends: smallvec::SmallVec<[u32; 64]> = smallvec::SmallVec::new();
        for &(a, b) in &link {
            ends.push(a);
            ends.push(b);
        }
        ends.sort_unstable();
        for pair in ends.chunks(2) {
            if pair.len() != 2 || pair[0] != pair[1] {
                ok = false;
                break;
            }
        }
        if ok && ends.windows(3).any(|w| w[0] == w[2]) {
            ok = false;
        }
        if ok {
            let start = link[0].0;
            let mut at = link[0].1;
            let mut steps = 1;
            while at != start && steps <= link.len() {
                match link.iter().find(|e| e.0 == at) {
                    Some(e) => at = e.1,
                    None => break,
                }
                steps += 1;
            }
            ok = at == start && steps == link.len();
        }
        bad += u32::from(!ok);
    }
    bad
}

/// Most passes of single-tetrahedron moves.
const LOCAL_PASSES: usize = 6;

/// Single free tetrahedra around the vertices of singular simplices change to a neighbour's label
/// where that lowers the number of non-disk label boundaries at its four vertices; the number of
/// tetrahedra changed.
fn local_moves(complex: &Complex, label: &mut [u32], pinned: &[bool], sets: &[Singular]) -> u64 {
    let mut at: Vec<u32> = (sets.iter())
        .flat_map(|(e, v)| e.iter().flat_map(|&(a, b)| [a, b]).chain(v.iter().copied()))
        .collect();
    at.sort_unstable();
    at.dedup();
    let mut moved = 0;
    let cost = |label: &[u32], t: usize| -> u32 {
        complex.tets[t]
            .iter()
            .map(|&w| vertex_bad(complex, label, w))
            .sum()
    };
    for _ in 0..LOCAL_PASSES {
        let mut improved = false;
        let mut next = Vec::new();
        for &v in &at {
            if vertex_bad(complex, label, v) == 0 {
                continue;
            }
            let mut best: Option<(u32, usize, u32)> = None;
            for &t in &complex.star[v as usize] {
                let t = t as usize;
                if pinned[t] {
                    continue;
                }
                let before = cost(label, t);
                let current = label[t];
                for &n in &complex.nbr[t] {
                    if n == NONE || label[n as usize] == current {
                        continue;
                    }
                    label[t] = label[n as usize];
                    let after = cost(label, t);
                    if after < before && best.is_none_or(|b| before - after > b.0) {
                        best = Some((before - after, t, label[t]));
                    }
                    label[t] = current;
                }
            }
            if let Some((_, t, l)) = best {
                label[t] = l;
                moved += 1;
                improved = true;
                next.extend(complex.tets[t]);
            }
        }
        if !improved {
            break;
        }
        at.extend(next);
        at.sort_unstable();
        at.dedup();
    }
    moved
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
    fn a_pinch_no_free_change_undoes_stays_and_is_counted() {
        let c = three();
        let mut label = vec![0, 0, 0];
        // pinned: the first two; the third may change, but only to a neighbour's label (it has
        // none): the pinch stays and is counted
        let fixed = repair(&c, &mut label, &[true, true, false], 2);
        assert_eq!(fixed.vertices_left, 1);
        assert_eq!(label, vec![0, 0, 0]);
    }
}
