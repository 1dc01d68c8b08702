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
    let mut in_kept: FxHashSet<[u32; 4]> = kept.iter().map(|&t| key4(t)).collect();
    let mut added = 0u64;
    for _ in 0..max_rounds {
        let boundary = super::assembly::boundary_of(kept);
        let (edges, vertices) = singular_simplices(&boundary);
        if edges.is_empty() && vertices.is_empty() {
            break;
        }
        let candidates: Vec<[u32; 4]> = fillable
            .iter()
            .copied()
            .filter(|t| !in_kept.contains(&key4(*t)))
            .collect();
        let mut to_add: FxHashSet<[u32; 4]> = FxHashSet::default();
        for gap in edge_gaps(kept, &candidates, &edges)
            .into_iter()
            .chain(vertex_gaps(kept, &candidates, &vertices))
        {
            to_add.extend(gap.iter().map(|&t| key4(t)));
        }
        if to_add.is_empty() {
            break;
        }
        for t in candidates {
            if to_add.contains(&key4(t)) && in_kept.insert(key4(t)) {
                kept.push(t);
                added += 1;
            }
        }
    }
    added
}

/// The boundary's singular edges (more than two triangles) and pinched vertices (several fans).
pub(super) fn singular_simplices(tris: &[[u32; 3]]) -> (Vec<(u32, u32)>, Vec<u32>) {
    let mut edge_count: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for t in tris {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *edge_count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut edges: Vec<(u32, u32)> = edge_count
        .into_iter()
        .filter(|&(_, n)| n > 2)
        .map(|(e, _)| e)
        .collect();
    edges.sort_unstable();
    let mut around: FxHashMap<u32, Vec<[u32; 3]>> = FxHashMap::default();
    for t in tris {
        for &v in t {
            around.entry(v).or_default().push(*t);
        }
    }
    let mut vertices: Vec<u32> = around
        .into_iter()
        .filter(|(v, ts)| fans(ts, *v) > 1)
        .map(|(v, _)| v)
        .collect();
    vertices.sort_unstable();
    (edges, vertices)
}

/// Number of fans of the triangles through `v` (connected through shared edges at `v`).
pub(super) fn fans(tris: &[[u32; 3]], v: u32) -> usize {
    let n = tris.len();
    let mut parent: SmallVec<[usize; 16]> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    // the first triangle seen at each other vertex w (the edge vw)
    let mut first: FxHashMap<u32, usize> = FxHashMap::default();
    for (i, t) in tris.iter().enumerate() {
        for &w in t.iter().filter(|&&w| w != v) {
            match first.entry(w) {
                std::collections::hash_map::Entry::Occupied(e) => {
                    let (a, b) = (find(&mut parent, i), find(&mut parent, *e.get()));
                    parent[a] = b;
                }
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i);
                }
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
    // adjacency by shared sub-lists of length `share` (1: a vertex, 2: an edge)
    let mut by_key: FxHashMap<Vec<u32>, usize> = FxHashMap::default();
    for (i, it) in items.iter().enumerate() {
        let mut s = it.clone();
        s.sort_unstable();
        let keys: Vec<Vec<u32>> = match share {
            1 => s.iter().map(|&x| vec![x]).collect(),
            _ => (0..s.len())
                .flat_map(|a| (a + 1..s.len()).map(move |b| (a, b)))
                .map(|(a, b)| vec![s[a], s[b]])
                .collect(),
        };
        for k in keys {
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
fn edge_gaps(
    kept: &[[u32; 4]],
    candidates: &[[u32; 4]],
    edges: &[(u32, u32)],
) -> Vec<Vec<[u32; 4]>> {
    let wanted: FxHashSet<(u32, u32)> = edges.iter().copied().collect();
    let mut kept_around: FxHashMap<(u32, u32), Vec<[u32; 4]>> = FxHashMap::default();
    let mut cand_around: FxHashMap<(u32, u32), Vec<[u32; 4]>> = FxHashMap::default();
    for (list, map) in [(kept, &mut kept_around), (candidates, &mut cand_around)] {
        for t in list {
            for (i, j) in super::complex::TET_EDGES {
                let e = (t[i].min(t[j]), t[i].max(t[j]));
                if wanted.contains(&e) {
                    map.entry(e).or_default().push(*t);
                }
            }
        }
    }
    let mut gaps = Vec::new();
    for e in edges {
        let Some(cands) = cand_around.get(e) else {
            continue;
        };
        let kept_faces: FxHashSet<u32> = kept_around
            .get(e)
            .map(|ts| ts.iter().flat_map(|t| others(t, &[e.0, e.1])).collect())
            .unwrap_or_default();
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
fn vertex_gaps(kept: &[[u32; 4]], candidates: &[[u32; 4]], vertices: &[u32]) -> Vec<Vec<[u32; 4]>> {
    let wanted: FxHashSet<u32> = vertices.iter().copied().collect();
    let mut kept_around: FxHashMap<u32, Vec<[u32; 4]>> = FxHashMap::default();
    let mut cand_around: FxHashMap<u32, Vec<[u32; 4]>> = FxHashMap::default();
    for (list, map) in [(kept, &mut kept_around), (candidates, &mut cand_around)] {
        for t in list {
            for &v in t {
                if wanted.contains(&v) {
                    map.entry(v).or_default().push(*t);
                }
            }
        }
    }
    let mut gaps = Vec::new();
    for v in vertices {
        let (Some(ks), Some(cs)) = (kept_around.get(v), cand_around.get(v)) else {
            continue;
        };
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
}
