//! Singularities of the boundary of the kept complex K resolved inside the complex, by adding
//! tetrahedra (design note §3, rule "fill"): never by moving a vertex.
//!
//! At a singular edge e (more than two surface triangles), the tetrahedra around e alternate
//! between kept sectors and gaps. A gap made only of *fillable* tetrahedra (step-1 survivors that
//! pruning did not keep: none has a face on a plane outside its section, so adding them changes no
//! section outside its region) whose two ends are kept tetrahedra is filled: its two kept sectors
//! become one, and e has two surface triangles fewer. At a pinched vertex v (its surface
//! triangles form several fans), a component of fillable tetrahedra around v that touches two
//! different kept components around v is filled the same way. The smallest such gap is taken
//! first; a round fills every singularity that has one, and the rounds repeat on the new boundary
//! (a fill can pinch elsewhere) up to a bound. What remains is counted by the caller.
use crate::fxhash::{FxHashMap, FxHashSet};
use rayon::prelude::*;
use smallvec::SmallVec;

fn key4(mut t: [u32; 4]) -> [u32; 4] {
    t.sort_unstable();
    t
}

/// Add fillable tetrahedra to `kept` until its boundary has no singular edge or vertex that a gap
/// of fillable tetrahedra can close, or `max_rounds` ran out. Returns how many were added.
pub fn fill_singularities(
    kept: &mut Vec<[u32; 4]>,
    fillable: &[[u32; 4]],
    max_rounds: usize,
) -> u64 {
    fill_and_drop(kept, &mut fillable.to_vec(), max_rounds).added
}

/// What [`fill_and_drop`] did and found.
pub struct Filled {
    /// Tetrahedra added to K.
    pub added: u64,
    /// The boundary's singular simplices before filling.
    pub found: super::assembly::Sets,
    /// Those after filling.
    pub left: super::assembly::Sets,
    /// The vertices of the tetrahedra added (sorted).
    pub touched: Vec<u32>,
}

/// [`fill_singularities`], then drop from `fillable` the tetrahedra K has (by vertex set).
pub fn fill_and_drop(
    kept: &mut Vec<[u32; 4]>,
    fillable: &mut Vec<[u32; 4]>,
    max_rounds: usize,
) -> Filled {
    // one index over kept ++ fillable: filling only moves fillable tetrahedra into K
    let mut ix = Index::new(kept, fillable);
    for j in 0..fillable.len() {
        ix.candidate[j] = !ix.in_k(j);
    }
    let (mut added, mut all_touched) = (0u64, Vec::new());
    let mut now = singular_simplices(&ix.boundary());
    let found = now.clone();
    for _ in 0..max_rounds {
        if now.0.is_empty() && now.1.is_empty() {
            break;
        }
        let to_add = gaps_to_fill(&ix, &now);
        if to_add.is_empty() {
            break;
        }
        let chosen: Vec<usize> = (0..fillable.len())
            .filter(|&j| ix.candidate[j] && to_add.contains(&key4(fillable[j])))
            .collect();
        let mut touched = Vec::new();
        for j in chosen {
            // an equal tetrahedron may have been added just before
            if !ix.in_k(j) {
                kept.push(fillable[j]);
                touched.extend(fillable[j]);
                ix.add(j);
                added += 1;
            }
        }
        touched.sort_unstable();
        touched.dedup();
        now = super::assembly::singular_sets_after(kept, now, &touched);
        all_touched.extend(touched);
    }
    let keep: Vec<bool> = ix.candidate;
    finish(fillable, &keep, added, found, now, all_touched)
}

/// [`fill_and_drop`] when ∂K's singular simplices `known` are known and few: each round indexes
/// only the tetrahedra through a vertex of its singular simplices (every gap around one lies in
/// that star, and so does every tetrahedron with the same vertices as one of them), not all of
/// K and the fillable ones. The same tetrahedra are added, in the same order; `fillable` loses
/// those and their copies.
pub fn fill_near(
    kept: &mut Vec<[u32; 4]>,
    fillable: &mut Vec<[u32; 4]>,
    known: super::assembly::Sets,
    max_rounds: usize,
) -> Filled {
    let mut gone = vec![false; fillable.len()];
    let (mut added, mut all_touched) = (0u64, Vec::new());
    let found = known.clone();
    let mut now = known;
    for _ in 0..max_rounds {
        if now.0.is_empty() && now.1.is_empty() {
            break;
        }
        let at = || now.1.iter().chain(now.0.iter().flat_map(|e| [&e.0, &e.1]));
        // sized by the singular simplices' vertices (no pass over K for it)
        let mut near = vec![false; at().max().map_or(0, |&v| v as usize + 1)];
        for &v in at() {
            near[v as usize] = true;
        }
        let touches = |t: &[u32; 4]| t.iter().any(|&v| near.get(v as usize) == Some(&true));
        let local_kept: Vec<[u32; 4]> = kept.iter().filter(|t| touches(t)).copied().collect();
        let global: Vec<usize> = (0..fillable.len())
            .filter(|&j| !gone[j] && touches(&fillable[j]))
            .collect();
        let local_fillable: Vec<[u32; 4]> = global.iter().map(|&j| fillable[j]).collect();
        let mut ix = Index::new(&local_kept, &local_fillable);
        for j in 0..local_fillable.len() {
            ix.candidate[j] = !ix.in_k(j);
            gone[global[j]] |= !ix.candidate[j];
        }
        let to_add = gaps_to_fill(&ix, &now);
        if to_add.is_empty() {
            break;
        }
        let mut touched = Vec::new();
        for (j, &t) in local_fillable.iter().enumerate() {
            if ix.candidate[j] && to_add.contains(&key4(t)) && !ix.in_k(j) {
                kept.push(t);
                touched.extend(t);
                ix.add(j);
                added += 1;
            }
        }
        for (j, &g) in global.iter().enumerate() {
            gone[g] |= !ix.candidate[j];
        }
        touched.sort_unstable();
        touched.dedup();
        now = super::assembly::singular_sets_after(kept, now, &touched);
        all_touched.extend(touched);
    }
    let keep: Vec<bool> = gone.iter().map(|&g| !g).collect();
    finish(fillable, &keep, added, found, now, all_touched)
}

/// The fillable tetrahedra (keys) of the smallest gap at each of the singular simplices `now`.
fn gaps_to_fill(ix: &Index, now: &super::assembly::Sets) -> FxHashSet<[u32; 4]> {
    let mut to_add: FxHashSet<[u32; 4]> = FxHashSet::default();
    for gap in edge_gaps(ix, &now.0)
        .into_iter()
        .chain(vertex_gaps(ix, &now.1))
    {
        to_add.extend(gap.iter().map(|&t| key4(t)));
    }
    to_add
}

/// A fill's result, `fillable` reduced to the tetrahedra `keep` marks.
fn finish(
    fillable: &mut Vec<[u32; 4]>,
    keep: &[bool],
    added: u64,
    found: super::assembly::Sets,
    left: super::assembly::Sets,
    mut touched: Vec<u32>,
) -> Filled {
    let mut j = 0;
    fillable.retain(|_| {
        j += 1;
        keep[j - 1]
    });
    touched.sort_unstable();
    touched.dedup();
    Filled {
        added,
        found,
        left,
        touched,
    }
}

/// K's tetrahedra and the fillable ones, with their faces and vertex stars, which of them K
/// keeps and which fillable ones are candidates this round (not already in K by key).
struct Index {
    all: Vec<[u32; 4]>,
    n_kept: usize,
    faces: super::faces::FaceTable,
    star: crate::mesh::Stars,
    kept: Vec<bool>,
    candidate: Vec<bool>,
}

impl Index {
    fn new(kept: &[[u32; 4]], fillable: &[[u32; 4]]) -> Index {
        let all = [kept, fillable].concat();
        let n = all.iter().flatten().max().map_or(0, |&v| v as usize + 1);
        let mut is_kept = vec![true; kept.len()];
        is_kept.resize(all.len(), false);
        Index {
            faces: super::faces::FaceTable::new(&all),
            star: crate::mesh::Stars::new(n, &all),
            n_kept: kept.len(),
            kept: is_kept,
            candidate: vec![false; fillable.len()],
            all,
        }
    }

    /// Whether K has fillable tetrahedron `j` (it, or one with the same vertices, is kept).
    fn in_k(&self, j: usize) -> bool {
        let t = self.all[self.n_kept + j];
        let key = key4(t);
        let f = key4([t[0], t[1], t[2], u32::MAX]);
        self.faces
            .owners(&[f[0], f[1], f[2]])
            .any(|o| self.kept[o as usize] && key4(self.all[o as usize]) == key)
    }

    /// Keep fillable tetrahedron `j`: no tetrahedron with its vertices is a candidate any more.
    fn add(&mut self, j: usize) {
        let t = self.all[self.n_kept + j];
        self.kept[self.n_kept + j] = true;
        let key = key4(t);
        let f = key4([t[0], t[1], t[2], u32::MAX]);
        for o in self.faces.owners(&[f[0], f[1], f[2]]) {
            let o = o as usize;
            if o >= self.n_kept && key4(self.all[o]) == key {
                self.candidate[o - self.n_kept] = false;
            }
        }
    }

    /// `assembly::boundary_of` of the kept tetrahedra (in another order).
    fn boundary(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        self.faces.for_each_face(|codes| {
            let mut kept = codes.iter().filter(|&&c| self.kept[(c >> 2) as usize]);
            if let (Some(&c), None) = (kept.next(), kept.next()) {
                let t = &self.all[(c >> 2) as usize];
                out.push(super::complex::outward_face(t, (c & 3) as usize));
            }
        });
        out
    }

    /// The kept tetrahedra and the candidates (in fillable order) with all of `verts`.
    fn around(&self, verts: &[u32]) -> (Vec<[u32; 4]>, Vec<[u32; 4]>) {
        let (mut kept, mut cands) = (Vec::new(), Vec::new());
        let v = verts[0] as usize;
        let star: &[u32] = if v < self.star.len() {
            &self.star[v]
        } else {
            &[]
        };
        for &i in star {
            let t = self.all[i as usize];
            if !verts[1..].iter().all(|v| t.contains(v)) {
                continue;
            }
            if self.kept[i as usize] {
                kept.push(t);
            } else if i as usize >= self.n_kept && self.candidate[i as usize - self.n_kept] {
                cands.push(t);
            }
        }
        (kept, cands)
    }
}

/// The boundary's singular edges (more than two triangles) and pinched vertices (several fans).
pub(crate) fn singular_simplices(tris: &[[u32; 3]]) -> (Vec<(u32, u32)>, Vec<u32>) {
    // Per vertex v, the other vertices of its triangles sorted: the triangles of an edge vw are a
    // run there (more than two: singular), and the fans are joined along the runs. One pass per
    // vertex, no sort of the whole surface; chunks of vertices in parallel, in vertex order.
    const CHUNK: usize = 4096;
    let n = tris.iter().flatten().max().map_or(0, |&v| v as usize + 1);
    let around = crate::mesh::Stars::<u32>::new(n, tris);
    let parts: Vec<super::assembly::Sets> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let (mut edges, mut vertices, mut ts) = (Vec::new(), Vec::new(), Vec::new());
            for v in (c * CHUNK) as u32..((c + 1) * CHUNK).min(n) as u32 {
                ts.clear();
                ts.extend(around[v as usize].iter().map(|&i| tris[i as usize]));
                if !ts.is_empty() && fans_and_edges(&ts, v, Some(&mut edges)) > 1 {
                    vertices.push(v);
                }
            }
            (edges, vertices)
        })
        .collect();
    let mut out = (Vec::new(), Vec::new());
    for (e, v) in parts {
        out.0.extend(e);
        out.1.extend(v);
    }
    out
}

/// Number of fans of the triangles through `v` (connected through shared edges at `v`).
pub(super) fn fans(tris: &[[u32; 3]], v: u32) -> usize {
    fans_and_edges(tris, v, None)
}

/// [`fans`]; with `singular`, the edges vw (w > v) of more than two of the triangles are pushed
/// there, in increasing w.
fn fans_and_edges(tris: &[[u32; 3]], v: u32, singular: Option<&mut Vec<(u32, u32)>>) -> usize {
    let n = tris.len();
    let mut parent: SmallVec<[usize; 16]> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    // triangles sharing an edge vw (the same other vertex w) are joined
    let mut at: SmallVec<[(u32, usize); 32]> = SmallVec::new();
    for (i, t) in tris.iter().enumerate() {
        at.extend(t.iter().filter(|&&w| w != v).map(|&w| (w, i)));
    }
    at.sort_unstable();
    let mut singular = singular;
    for run in at.chunk_by(|a, b| a.0 == b.0) {
        for x in &run[1..] {
            let (a, b) = (find(&mut parent, x.1), find(&mut parent, run[0].1));
            parent[a] = b;
        }
        if let Some(out) = singular.as_deref_mut() {
            if run.len() > 2 && run[0].0 > v {
                out.push((v, run[0].0));
            }
        }
    }
    (0..n).filter(|&i| find(&mut parent, i) == i).count()
}

/// Components of `items` (each a small list of vertex ids) where two items are adjacent when they
/// share at least `share` ids.
fn components(items: &[Vec<u32>], share: usize) -> Vec<Vec<usize>> {
    let n = items.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    // adjacency by shared sub-lists of length `share` (1: a vertex, 2: an edge), as pairs (a
    // vertex's second entry `u32::MAX`): no allocation per key
    let mut by_key: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    let mut s: SmallVec<[u32; 4]> = SmallVec::new();
    let mut keys: SmallVec<[(u32, u32); 6]> = SmallVec::new();
    for (i, it) in items.iter().enumerate() {
        s.clear();
        s.extend_from_slice(it);
        s.sort_unstable();
        keys.clear();
        match share {
            1 => keys.extend(s.iter().map(|&x| (x, u32::MAX))),
            _ => {
                for a in 0..s.len() {
                    keys.extend((a + 1..s.len()).map(|b| (s[a], s[b])));
                }
            }
        }
        for &k in &keys {
            if let Some(&j) = by_key.get(&k) {
                let (x, y) = (find(&mut parent, i), find(&mut parent, j));
                parent[x] = y;
            } else {
                by_key.insert(k, i);
            }
        }
    }
    let mut groups: FxHashMap<usize, Vec<usize>> = FxHashMap::default();
    for i in 0..n {
        let r = find(&mut parent, i);
        groups.entry(r).or_default().push(i);
    }
    let mut out: Vec<Vec<usize>> = groups.into_values().collect();
    out.sort_unstable();
    out
}

/// The other vertices of `t` than those of `of`.
fn others(t: &[u32; 4], of: &[u32]) -> Vec<u32> {
    t.iter().copied().filter(|v| !of.contains(v)).collect()
}

/// Per singular edge, the smallest gap of candidates around it whose ends are all kept
/// tetrahedra (around an edge, two tetrahedra are adjacent when they share a face through it,
/// i.e. one more vertex).
fn edge_gaps(ix: &Index, edges: &[(u32, u32)]) -> Vec<Vec<[u32; 4]>> {
    let mut gaps = Vec::new();
    for e in edges {
        let (kept_around, cands) = ix.around(&[e.0, e.1]);
        if cands.is_empty() {
            continue;
        }
        let kept_faces: FxHashSet<u32> = kept_around
            .iter()
            .flat_map(|t| others(t, &[e.0, e.1]))
            .collect();
        let links: Vec<Vec<u32>> = cands.iter().map(|t| others(t, &[e.0, e.1])).collect();
        let best = components(&links, 1)
            .into_iter()
            .filter(|comp| {
                // the ends: vertices (faces through e) used once in the component
                let mut uses: FxHashMap<u32, u32> = FxHashMap::default();
                for &i in comp {
                    for &x in &links[i] {
                        *uses.entry(x).or_default() += 1;
                    }
                }
                let ends: Vec<u32> = uses
                    .into_iter()
                    .filter(|&(_, n)| n == 1)
                    .map(|(x, _)| x)
                    .collect();
                ends.len() == 2 && ends.iter().all(|x| kept_faces.contains(x))
            })
            .min_by_key(|comp| comp.len());
        if let Some(comp) = best {
            gaps.push(comp.iter().map(|&i| cands[i]).collect());
        }
    }
    gaps
}

/// Per pinched vertex, the smallest component of candidates around it (adjacent through a face
/// through the vertex, i.e. two more vertices) that touches two different kept components.
fn vertex_gaps(ix: &Index, vertices: &[u32]) -> Vec<Vec<[u32; 4]>> {
    let mut gaps = Vec::new();
    for v in vertices {
        let (ks, cs) = ix.around(&[*v]);
        if ks.is_empty() || cs.is_empty() {
            continue;
        }
        let kept_links: Vec<Vec<u32>> = ks.iter().map(|t| others(t, &[*v])).collect();
        // kept component of each face (edge of the link) through v
        let mut face_comp: FxHashMap<(u32, u32), usize> = FxHashMap::default();
        for (ci, comp) in components(&kept_links, 2).into_iter().enumerate() {
            for i in comp {
                let l = &kept_links[i];
                for (a, b) in [(0, 1), (0, 2), (1, 2)] {
                    face_comp.insert((l[a].min(l[b]), l[a].max(l[b])), ci);
                }
            }
        }
        let links: Vec<Vec<u32>> = cs.iter().map(|t| others(t, &[*v])).collect();
        let best = components(&links, 2)
            .into_iter()
            .filter(|comp| {
                let touched: FxHashSet<usize> = comp
                    .iter()
                    .flat_map(|&i| {
                        let l = &links[i];
                        [(0, 1), (0, 2), (1, 2)]
                            .into_iter()
                            .filter_map(|(a, b)| face_comp.get(&(l[a].min(l[b]), l[a].max(l[b]))))
                            .copied()
                            .collect::<Vec<_>>()
                    })
                    .collect();
                touched.len() >= 2
            })
            .min_by_key(|comp| comp.len());
        if let Some(comp) = best {
            gaps.push(comp.iter().map(|&i| cs[i]).collect());
        }
    }
    gaps
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::assembly::{boundary_of, singularities};

    /// Four tetrahedra around the edge (0,1), apexes 2,3,4,5 in turn: (0,1,2,3), (0,1,3,4),
    /// (0,1,4,5), (0,1,5,2). Keeping the first and third leaves (0,1) singular.
    fn ring() -> [[u32; 4]; 4] {
        [[0, 1, 2, 3], [0, 1, 3, 4], [0, 1, 4, 5], [0, 1, 5, 2]]
    }

    #[test]
    fn a_gap_of_fillable_tets_closes_a_singular_edge() {
        let r = ring();
        let mut kept = vec![r[0], r[2]];
        assert_eq!(singularities(&boundary_of(&kept)).0, 1);
        let added = fill_singularities(&mut kept, &[r[1], r[3]], 4);
        assert_eq!(added, 1, "one gap is enough");
        assert_eq!(singularities(&boundary_of(&kept)), (0, 0));
    }

    #[test]
    fn nothing_to_fill_with_leaves_the_singularity() {
        let r = ring();
        let mut kept = vec![r[0], r[2]];
        assert_eq!(fill_singularities(&mut kept, &[], 4), 0);
        assert_eq!(kept.len(), 2);
    }

    #[test]
    fn a_pinched_vertex_is_joined_through_fillable_tets() {
        // (0,1,2,3) and (0,4,5,6) meet only at 0; (0,2,3,4) and (0,3,4,5) lead from a face of
        // the first through 0 to a face of the second
        let mut kept = vec![[0, 1, 2, 3], [0, 4, 5, 6]];
        assert_eq!(singularities(&boundary_of(&kept)), (0, 1));
        assert_eq!(
            fill_singularities(&mut kept, &[[0, 2, 3, 4], [0, 3, 4, 5], [7, 8, 9, 0]], 4),
            2
        );
        assert_eq!(singularities(&boundary_of(&kept)), (0, 0));
    }

    #[test]
    fn filling_near_the_known_singularities_equals_the_whole_pass() {
        // a singular edge (0,1) with its gap, a pinched vertex 10 with its strip, a copy of a
        // kept tetrahedron next to the edge, and fillable tetrahedra far from both
        let r = ring();
        let kept = vec![r[0], r[2], [10, 11, 12, 13], [10, 14, 15, 16]];
        let fillable = vec![
            [30, 31, 32, 33],
            r[1],
            [10, 12, 13, 14],
            [1, 0, 2, 3],
            r[3],
            [10, 13, 14, 15],
            [31, 32, 33, 34],
        ];
        let known = crate::bm::assembly::singular_sets(&kept);
        assert_eq!((known.0.len(), known.1.len()), (1, 1));
        let (mut k1, mut f1) = (kept.clone(), fillable.clone());
        let whole = fill_and_drop(&mut k1, &mut f1, 4);
        let (mut k2, mut f2) = (kept, fillable);
        let near = fill_near(&mut k2, &mut f2, known, 4);
        assert_eq!((whole.added, near.added), (3, 3));
        assert_eq!(k1, k2, "the same tetrahedra, in the same order");
        assert_eq!(f1, f2, "the same left fillable, the copy dropped");
        assert_eq!(whole.left, near.left);
        assert_eq!(whole.touched, near.touched);
        assert_eq!(singularities(&boundary_of(&k2)), (0, 0));
    }
}
