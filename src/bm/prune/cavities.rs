//! After step 3: voids of the complex enclosed by it and the section filled (`fill_cavities`), and
//! pinches of its surface at vertices repaired by filling notches (`fill_pinches`).
use crate::bm::classify::{Classified, TetType};
use crate::bm::complex::{Complex, NONE};
use smallvec::SmallVec;

/// Fills the voids of the complex `alive`: face-connected groups of tets of `r1` (step 1's result)
/// that are not kept, not flat, and whose every face is shared with a kept tet, with the group, or is
/// a grounded triangle. Returns (groups filled, tets added).
pub fn fill_cavities(cx: &Complex, cl: &Classified, r1: &[bool], alive: &mut [bool]) -> (u64, u64) {
    let voids = enclosed_groups(cx, cl, alive, |t| r1[t] && cl.ty[t] != TetType::Flat);
    let tets = voids.iter().map(|g| g.len() as u64).sum();
    for &t in voids.iter().flatten() {
        alive[t as usize] = true;
    }
    (voids.len() as u64, tets)
}

/// Face-connected groups of tets that are not `alive` but `member`, closed off from everything
/// else by kept tets and grounded triangles (no face to a non-member removed tet or the hull).
fn enclosed_groups(
    cx: &Complex,
    cl: &Classified,
    alive: &[bool],
    member: impl Fn(usize) -> bool,
) -> Vec<Vec<u32>> {
    let n = cx.len();
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    for s in 0..n {
        if seen[s] || alive[s] || !member(s) {
            continue;
        }
        let mut group = vec![s as u32];
        seen[s] = true;
        let mut enclosed = true;
        let mut k = 0;
        while k < group.len() {
            let t = group[k] as usize;
            k += 1;
            for (i, &nb) in cx.nbr[t].iter().enumerate() {
                if nb != NONE && alive[nb as usize] {
                    continue;
                }
                if nb != NONE && member(nb as usize) {
                    if !seen[nb as usize] {
                        seen[nb as usize] = true;
                        group.push(nb);
                    }
                } else if cl.grounded_faces[t] >> i & 1 == 0 {
                    enclosed = false;
                }
            }
        }
        if enclosed {
            out.push(group);
        }
    }
    out
}

/// The cell's surface around vertex `v`, as the gluing makes it when the other side of every face
/// that is not a cap attaches: boundary faces of kept tets that are not grounded, internal section
/// triangles containing `v` that no kept tet stands on, and on caps the attached triangles instead.
/// Returns the number of fans (edge-connected groups of those triangles around `v`); more than
/// one is a pinch of the surface at `v`.
pub(super) fn surface_fans(cx: &Complex, cl: &Classified, alive: &[bool], v: u32) -> usize {
    // called for every vertex of every cell: small buffers on the stack, no hashing
    let mut tris: SmallVec<[[u32; 2]; 32]> = SmallVec::new();
    let mut planar: SmallVec<[bool; 32]> = SmallVec::new();
    for &t in &cx.star[v as usize] {
        let tu = t as usize;
        if cl.ty[tu] == TetType::Flat {
            continue;
        }
        let tv = cx.tets[tu];
        for i in 0..4 {
            if tv[i] == v {
                continue;
            }
            let nb = cx.nbr[tu][i];
            let open = nb == NONE || !alive[nb as usize];
            let on_section = nb == NONE || cl.ty[nb as usize] == TetType::Flat;
            // on a cap the attached triangles are surface, elsewhere the unattached ones
            let cap = cl.cap_faces[tu] >> i & 1 == 1;
            let surface = if alive[tu] {
                open && (cl.grounded_faces[tu] >> i & 1 == 0 || cap)
            } else {
                on_section && cl.section_faces[tu] >> i & 1 == 1 && !cap
            };
            if surface {
                let mut w = [0u32; 2];
                let mut k = 0;
                for (j, &x) in tv.iter().enumerate() {
                    if j != i && x != v {
                        w[k] = x;
                        k += 1;
                    }
                }
                tris.push(w);
                planar.push(cl.grounded_faces[tu] >> i & 1 == 1);
            }
        }
    }
    if tris.len() < 2 {
        return tris.len();
    }
    let mut parent: SmallVec<[usize; 32]> = (0..tris.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    // Triangles continue each other across an edge (v, w) they alone share; where more meet (a
    // crease of the solid touching a section along the edge), only planar with planar and
    // non-planar with non-planar, as the gluing pairs them.
    // (w, triangle) sorted: the triangles through each edge (v, w) are a run
    let mut by_w: SmallVec<[(u32, usize); 64]> = tris
        .iter()
        .enumerate()
        .flat_map(|(k, w)| w.iter().map(move |&x| (x, k)))
        .collect();
    by_w.sort_unstable();
    for run in by_w.chunk_by(|a, b| a.0 == b.0) {
        for x in 0..run.len() {
            for y in x + 1..run.len() {
                let (kx, ky) = (run[x].1, run[y].1);
                if run.len() == 2 || planar[kx] == planar[ky] {
                    let (a, b) = (find(&mut parent, kx), find(&mut parent, ky));
                    parent[a] = b;
                }
            }
        }
    }
    (0..tris.len())
        .filter(|&k| find(&mut parent, k) == k)
        .count()
}

/// Where the cell's surface is pinched at a vertex `v` (several fans: the removed regions around
/// `v` — "notches", groups of removed tets of v's star joined through faces containing v — touch
/// each other only at v), fill every notch but one when its tets all survived step 1: the paper's
/// steps leave this case open (a branching sample where two crotches of the sampled branching
/// diagram meet, or a section vertex where the attached region touches itself), and the gluing
/// could only split the vertex. The notch kept open is one that cannot be filled, else the largest.
/// With a single notch on a cap (a crotch between two branches coming down onto a section that
/// nothing attaches to from the other side, e.g. along the branching diagram: the paper's Fig. 12
/// case without a thickness), the notch is filled when possible. Vertices of filled tets are
/// re-examined. Returns (vertices repaired, tets added).
pub fn fill_pinches(cx: &Complex, cl: &Classified, r1: &[bool], alive: &mut [bool]) -> (u64, u64) {
    let nv = cx.star.len();
    let mut queue: Vec<u32> = (0..nv as u32).rev().collect();
    let mut queued = vec![true; nv];
    let mut visits = vec![0u8; nv];
    let (mut fixed, mut added) = (0, 0);
    while let Some(v) = queue.pop() {
        queued[v as usize] = false;
        if surface_fans(cx, cl, alive, v) < 2 || visits[v as usize] >= 3 {
            continue;
        }
        visits[v as usize] += 1;
        // notches around v
        let star = &cx.star[v as usize];
        let mut comp: Vec<usize> = vec![usize::MAX; star.len()];
        let mut notches: Vec<Vec<u32>> = Vec::new();
        for s in 0..star.len() {
            if alive[star[s] as usize] || comp[s] != usize::MAX {
                continue;
            }
            let id = notches.len();
            comp[s] = id;
            let mut group = vec![star[s]];
            let mut k = 0;
            while k < group.len() {
                let t = group[k] as usize;
                k += 1;
                for (i, &nb) in cx.nbr[t].iter().enumerate() {
                    if cx.tets[t][i] == v || nb == NONE || alive[nb as usize] {
                        continue;
                    }
                    if let Some(p) = star.iter().position(|&x| x == nb) {
                        if comp[p] == usize::MAX {
                            comp[p] = id;
                            group.push(nb);
                        }
                    }
                }
            }
            notches.push(group);
        }
        if notches.is_empty() {
            continue;
        }
        let fillable = |g: &Vec<u32>| {
            g.iter()
                .all(|&t| r1[t as usize] && cl.ty[t as usize] != TetType::Flat)
        };
        let keep = notches
            .iter()
            .position(|g| !fillable(g))
            .unwrap_or_else(|| {
                (0..notches.len())
                    .max_by_key(|&k| notches[k].len())
                    .unwrap_or(0)
            });
        // one notch: a crease (crotch between two branches) comes down onto the section at v,
        // e.g. along the branching diagram on a cap; fill it when possible
        let on_cap = star.iter().any(|&t| {
            let tv = cx.tets[t as usize];
            (0..4).any(|i| tv[i] != v && cl.cap_faces[t as usize] >> i & 1 == 1)
        });
        if notches.len() == 1 && !on_cap {
            continue;
        }
        let keep = if notches.len() == 1 { usize::MAX } else { keep };
        let mut any = false;
        for (k, g) in notches.iter().enumerate() {
            if k == keep || !fillable(g) {
                continue;
            }
            any = true;
            for &t in g {
                alive[t as usize] = true;
                added += 1;
                for &w in &cx.tets[t as usize] {
                    if !queued[w as usize] {
                        queued[w as usize] = true;
                        queue.push(w);
                    }
                }
            }
        }
        if any {
            fixed += 1;
        }
    }
    (fixed, added)
}
