//! Displaced vertices must not make the surface cross itself.
//!
//! Gluing splits pinched vertices into copies and lifts branching samples off their plane (paper
//! Fig. 12b), each by a tiny step in a direction chosen from local combinatorics. Where that
//! direction points across a neighbouring sheet (a crease folding back onto the section, two fans
//! meeting at a narrow angle), the displaced vertex's triangles cross other triangles. Each
//! displaced vertex is therefore checked exactly (orient3d triangle tests) against the triangles
//! near it, and when its star crosses one, other candidate positions are tried in a fixed order:
//! a tenth of the step, the opposite step, a step into the solid along the star's inward normal,
//! and finally the position it came from (a coincident copy: a pinch point, but no crossing). The
//! first position whose star crosses nothing is kept; if none is free, the one with fewest crossings.
use crate::eval::bvh::{triangle_boxes, Aabb, Bvh};
use crate::eval::tri_tri::mesh_triangles_intersect;
use crate::sections::{cross, dot, sub};
use std::collections::HashMap;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Untangled {
    /// Vertices moved to another candidate than their first position.
    pub redirected: u64,
    /// Vertices whose star still crosses the surface at the best candidate.
    pub unresolved: u64,
}

/// `moved`: (vertex, position it was displaced from). `anchors`: vertices left in place whose star
/// touched a displaced one (the fan that kept a split vertex's id), each with the displacement length
/// its partner got: when the displaced side cannot be freed, moving the anchor off may be (the other
/// fan of a pinch retreats instead). Positions are updated in place.
pub fn untangle(
    positions: &mut [[f64; 3]],
    tris: &[[u32; 3]],
    moved: &[(u32, [f64; 3])],
    anchors: &[(u32, f64)],
) -> Untangled {
    let mut out = Untangled::default();
    if moved.is_empty() || tris.is_empty() {
        return out;
    }
    let step_len: HashMap<u32, f64> = moved
        .iter()
        .map(|&(v, o)| {
            let d = sub(positions[v as usize], o);
            (v, dot(d, d).sqrt())
        })
        .chain(anchors.iter().copied())
        .collect();
    let moved: Vec<(u32, [f64; 3])> = moved
        .iter()
        .copied()
        .chain(
            anchors
                .iter()
                .filter(|a| a.1 > 0.0)
                .map(|&(v, _)| (v, positions[v as usize])),
        )
        .collect();
    let moved = &moved[..];
    let mut star: HashMap<u32, Vec<u32>> = HashMap::new();
    let moved_set: std::collections::HashSet<u32> = moved.iter().map(|m| m.0).collect();
    for (i, t) in tris.iter().enumerate() {
        for &v in t {
            if moved_set.contains(&v) {
                star.entry(v).or_default().push(i as u32);
            }
        }
    }
    // Boxes padded by the largest displacement (times a margin) stay conservative while vertices move.
    let reach = moved
        .iter()
        .map(|&(v, o)| {
            let d = sub(positions[v as usize], o);
            dot(d, d).sqrt()
        })
        .fold(0.0f64, f64::max);
    let pad = 4.0 * reach;
    let boxes: Vec<Aabb> = triangle_boxes(positions, tris)
        .into_iter()
        .map(|b| Aabb {
            lo: b.lo.map(|x| x - pad),
            hi: b.hi.map(|x| x + pad),
        })
        .collect();
    let bvh = Bvh::build(boxes);
    let crossings = |positions: &[[f64; 3]], v: u32| -> usize {
        let Some(s) = star.get(&v) else { return 0 };
        let mut n = 0;
        for &i in s {
            let t = tris[i as usize];
            let bb = Aabb::of_points(&t.map(|w| positions[w as usize]));
            bvh.for_each_overlap(&bb, |j| {
                if j != i && mesh_triangles_intersect(t, tris[j as usize], positions) {
                    // a pair inside the star is seen from both sides; count it once
                    if !(s.contains(&j) && j < i) {
                        n += 1;
                    }
                }
            });
        }
        n
    };
    // Sweeps: a chain of displaced neighbours (samples along one crease) may only clear once its
    // neighbours have moved, so the vertices still crossing are revisited.
    let mut todo: Vec<(u32, [f64; 3])> = moved.to_vec();
    let first: HashMap<u32, [f64; 3]> = moved
        .iter()
        .map(|&(v, _)| (v, positions[v as usize]))
        .collect();
    let mut unresolved = 0;
    for _sweep in 0..4 {
        let mut again = Vec::new();
        for &(v, origin) in &todo {
            let start = positions[v as usize];
            let mut best = (crossings(positions, v), start);
            if best.0 == 0 {
                continue;
            }
            let step = sub(first[&v], origin);
            let len = step_len[&v];
            let inward = star
                .get(&v)
                .map(|s| inward_normal(positions, tris, s))
                .unwrap_or([0.0; 3]);
            let mut candidates = vec![
                first[&v],
                add(origin, scale(step, 0.1)),
                sub(origin, step),
                add(origin, scale(inward, len)),
                add(origin, scale(inward, 0.1 * len)),
                sub(origin, scale(inward, len)),
                sub(origin, scale(inward, 0.1 * len)),
            ];
            // Into the kernel of the star on either side (every incident triangle's plane is passed
            // on the same side), at shrinking steps: the displaced star then stays within its own
            // side of the old one, away from the sheets touching it.
            if let Some(s) = star.get(&v) {
                for side in [1.0, -1.0] {
                    if let Some(d) = kernel_direction(positions, tris, s, origin, side) {
                        for f in [1.0, 0.1, 0.01] {
                            candidates.push(add(origin, scale(d, f * len)));
                        }
                    }
                }
            }
            candidates.push(origin);
            for c in candidates {
                if c == start || !c.iter().all(|x| x.is_finite()) {
                    continue;
                }
                positions[v as usize] = c;
                let n = crossings(positions, v);
                if std::env::var_os("BM_DEBUG_UNTANGLE").is_some() {
                    eprintln!(
                        "untangle {v}: candidate {:?} (from {:?}) crosses {n}",
                        sub(c, origin),
                        origin
                    );
                }
                if n < best.0 {
                    best = (n, c);
                    if n == 0 {
                        break;
                    }
                }
            }
            positions[v as usize] = best.1;
            if best.0 > 0 {
                again.push((v, origin));
            }
        }
        unresolved = again.len();
        if again.is_empty() {
            break;
        }
        todo = again;
    }
    // A crease of several lifted samples can only go back all together: its triangles between two
    // displaced vertices cross whichever of them stays lifted.
    if unresolved > 0 {
        let origin_of: HashMap<u32, [f64; 3]> = moved.iter().copied().collect();
        let mut left = 0;
        for &(v, _) in &todo {
            if crossings(positions, v) == 0 {
                continue;
            }
            let mut group: Vec<u32> = vec![v];
            for &i in &star[&v] {
                for &w in &tris[i as usize] {
                    if w != v && origin_of.contains_key(&w) && !group.contains(&w) {
                        group.push(w);
                    }
                }
            }
            let saved: Vec<[f64; 3]> = group.iter().map(|&w| positions[w as usize]).collect();
            let before: usize = group.iter().map(|&w| crossings(positions, w)).sum();
            for &w in &group {
                positions[w as usize] = origin_of[&w];
            }
            let after: usize = group.iter().map(|&w| crossings(positions, w)).sum();
            if after >= before {
                for (&w, &p) in group.iter().zip(&saved) {
                    positions[w as usize] = p;
                }
            }
            if crossings(positions, v) > 0 {
                left += 1;
            }
        }
        unresolved = left;
    }
    out.redirected = moved
        .iter()
        .filter(|&&(v, _)| positions[v as usize] != first[&v])
        .count() as u64;
    out.unresolved = unresolved as u64;
    out
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// A unit direction `d` from `o` with `side · (n_t · d) > 0` for the unit normal `n_t` of every
/// triangle of `star` (taken with `o` in place of the star's vertex), maximising the smallest margin
/// over a few candidates (the mean normal, each triangle's normal, pairwise sums) refined by a few
/// perceptron steps; `None` when no candidate has a positive margin. `side` = 1: outward (into the
/// void the star faces), -1: into the solid.
fn kernel_direction(
    positions: &[[f64; 3]],
    tris: &[[u32; 3]],
    star: &[u32],
    o: [f64; 3],
    side: f64,
) -> Option<[f64; 3]> {
    let mut normals: Vec<[f64; 3]> = Vec::new();
    for &i in star {
        let t = tris[i as usize];
        // the star's vertex is the one displaced: evaluate the planes through its origin
        let p = t.map(|w| positions[w as usize]);
        let k = (0..3).min_by(|&a, &b| {
            let da = sub(p[a], o);
            let db = sub(p[b], o);
            dot(da, da).total_cmp(&dot(db, db))
        })?;
        let mut q = p;
        q[k] = o;
        let n = cross(sub(q[1], q[0]), sub(q[2], q[0]));
        let l = dot(n, n).sqrt();
        if l > 0.0 {
            normals.push(scale(n, side / l));
        }
    }
    if normals.is_empty() {
        return None;
    }
    let margin = |d: [f64; 3]| {
        normals
            .iter()
            .map(|&n| dot(n, d))
            .fold(f64::INFINITY, f64::min)
    };
    let unit = |d: [f64; 3]| {
        let l = dot(d, d).sqrt();
        (l > 0.0).then(|| scale(d, 1.0 / l))
    };
    let mut cands: Vec<[f64; 3]> = Vec::new();
    cands.extend(unit(normals.iter().fold([0.0; 3], |a, &n| add(a, n))));
    cands.extend(normals.iter().copied());
    for i in 0..normals.len() {
        for j in i + 1..normals.len() {
            cands.extend(unit(add(normals[i], normals[j])));
        }
    }
    let mut best = cands
        .into_iter()
        .map(|d| (margin(d), d))
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    for _ in 0..50 {
        if best.0 > 0.05 {
            break;
        }
        // push away from the worst plane
        let worst = normals
            .iter()
            .copied()
            .min_by(|&a, &b| dot(a, best.1).total_cmp(&dot(b, best.1)))?;
        let Some(d) = unit(add(best.1, scale(worst, 0.25))) else {
            break;
        };
        let m = margin(d);
        if m <= best.0 {
            break;
        }
        best = (m, d);
    }
    (best.0 > 0.0).then_some(best.1)
}

/// Unit vector into the solid at `v`: minus the area-weighted sum of its star's outward normals.
fn inward_normal(positions: &[[f64; 3]], tris: &[[u32; 3]], star: &[u32]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for &i in star {
        let t = tris[i as usize].map(|w| positions[w as usize]);
        n = add(n, cross(sub(t[1], t[0]), sub(t[2], t[0])));
    }
    let l = dot(n, n).sqrt();
    if l > 0.0 {
        scale(n, -1.0 / l)
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square (two triangles, outward +z) and a pyramid apex displaced straight through it.
    #[test]
    fn a_vertex_pushed_through_a_sheet_is_moved_back() {
        // sheet: square at z = 0; tent: a triangle fan from v (index 4) above the sheet
        let mut pos = vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [0.0, 0.0, 0.1],
            [-0.5, 0.0, 0.5],
            [0.5, 0.0, 0.5],
        ];
        let tris = vec![[0, 1, 2], [0, 2, 3], [4, 6, 5]];
        let origin = pos[4];
        // displaced through the sheet: its triangle now crosses the square
        pos[4] = [0.0, 0.0, -0.1];
        assert!(
            mesh_triangles_intersect(tris[2], tris[0], &pos)
                || mesh_triangles_intersect(tris[2], tris[1], &pos)
        );
        let u = untangle(&mut pos, &tris, &[(4, origin)], &[]);
        assert_eq!(
            u,
            Untangled {
                redirected: 1,
                unresolved: 0
            }
        );
        assert!(pos[4][2] > 0.0, "{:?}", pos[4]);
    }

    #[test]
    fn a_harmless_displacement_is_kept() {
        let mut pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.8, 0.8, 0.001],
        ];
        let tris = vec![[0, 1, 2], [1, 3, 2]];
        let before = pos.clone();
        let u = untangle(&mut pos, &tris, &[(3, [0.8, 0.8, 0.0])], &[]);
        assert_eq!(u, Untangled::default());
        assert_eq!(pos, before);
    }
}
