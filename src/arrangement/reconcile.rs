//! Agreement of two sections along their planes' common line (DESIGN invariant 5).
//!
//! Section i crosses the line L = P_i ∩ P_j at points (its pool vertices tagged {i, j}), and so does
//! section j. The rule:
//! * The disagreement on L is the Hausdorff distance between the two point sets measured along L
//!   (or the longest inside interval of one section when the other does not reach L at all); the
//!   largest is `max_disagreement`, and every line beyond `snap_tolerance × diagonal` gets a warning.
//! * Points of i and j on the same arrangement edge of L and closer than the tolerance are snapped
//!   into ONE pool vertex tagged {i, j} (closest pairs first, one to one): its position is the
//!   midpoint, its (u,v) in each plane's frame stays that section's own coordinate.
//! * Unmatched points are kept by their own section (no section is altered beyond the tolerance),
//!   and every section point lying on an edge of another plane's piece along L is inserted into that
//!   piece's boundary, so the pieces of both planes share all their vertices along L (no T-junctions).
use super::{Arrangement, ArrangementOptions, VertexId};
use crate::fxhash::FxHashMap as HashMap;
use crate::sections::{cross, dot};
use smallvec::SmallVec;

struct LinePoints {
    dir: [f64; 3],
    /// Arrangement vertices on the line, as sorted positions along it.
    breaks: Vec<f64>,
    /// (position along L, pool id) of the points of the lower / higher plane's section.
    a: Vec<(f64, VertexId)>,
    b: Vec<(f64, VertexId)>,
}

/// `line_points`: (section plane that made the point, pool id) for every section point on another plane.
/// `n_arr`: number of arrangement vertices at the start of the pool.
pub(super) fn reconcile(
    arr: &mut Arrangement,
    line_points: &[(u32, VertexId)],
    n_arr: usize,
    diag: f64,
    options: &ArrangementOptions,
) {
    let mut lines = points_on_common_lines(arr, line_points, n_arr);
    let tol = options.snap_tolerance * diag;
    let mut keys: Vec<(u32, u32)> = lines.keys().copied().collect();
    keys.sort_unstable();
    let mut worst = 0.0f64;
    let mut snaps = Snaps::default();
    for key in &keys {
        let lp = lines.get_mut(key).unwrap();
        let d = snap_line(arr, *key, lp, tol, &mut snaps);
        worst = worst.max(d);
    }
    arr.max_disagreement = worst;
    let Snaps {
        merged_into,
        snapped,
        max_snap,
    } = snaps;
    if snapped > 0 {
        arr.warnings.push(format!(
            "sections: {snapped} crossing pairs of two sections snapped to shared vertices (largest gap {max_snap:.3e})"
        ));
    }
    if !merged_into.is_empty() {
        use_survivors(arr, &mut lines, &merged_into);
    }
    insert_line_points(arr, &lines);
    if !merged_into.is_empty() {
        compact(arr, &merged_into);
    }
}

/// Per pair of section planes (lower first), the section points on their common line and the
/// arrangement vertices on it (`breaks`, unsorted).
fn points_on_common_lines(
    arr: &Arrangement,
    line_points: &[(u32, VertexId)],
    n_arr: usize,
) -> HashMap<(u32, u32), LinePoints> {
    let n = arr.n_input as u32;
    let mut lines: HashMap<(u32, u32), LinePoints> = HashMap::default();
    for &(owner, v) in line_points {
        if (v as usize) < n_arr {
            continue;
        }
        for &t in &arr.pool.tags[v as usize] {
            if t == owner || t >= n || arr.planes[t as usize].section.is_none() {
                continue;
            }
            let key = (owner.min(t), owner.max(t));
            let e = lines.entry(key).or_insert_with(|| {
                let d = cross(
                    arr.planes[key.0 as usize].plane.normal,
                    arr.planes[key.1 as usize].plane.normal,
                );
                let l = dot(d, d).sqrt();
                LinePoints {
                    dir: [d[0] / l, d[1] / l, d[2] / l],
                    breaks: Vec::new(),
                    a: Vec::new(),
                    b: Vec::new(),
                }
            });
            let s = dot(e.dir, arr.pool.positions[v as usize]);
            if owner == key.0 {
                e.a.push((s, v));
            } else {
                e.b.push((s, v));
            }
        }
    }
    for v in 0..n_arr {
        let tags = &arr.pool.tags[v];
        for (x, &ti) in tags.iter().enumerate() {
            for &tj in &tags[x + 1..] {
                if let Some(e) = lines.get_mut(&(ti, tj)) {
                    e.breaks.push(dot(e.dir, arr.pool.positions[v]));
                }
            }
        }
    }
    lines
}

/// What the snapping did so far, over all lines.
#[derive(Default)]
struct Snaps {
    /// Vertex merged away → the vertex it was merged into.
    merged_into: HashMap<VertexId, VertexId>,
    snapped: usize,
    max_snap: f64,
}

/// Sort the line's points, warn if its two sections disagree beyond `tol`, and snap the close
/// pairs on one arrangement edge (closest first, one to one; `b`'s point merged into `a`'s and
/// dropped from `b`). Returns the disagreement.
fn snap_line(
    arr: &mut Arrangement,
    key: (u32, u32),
    lp: &mut LinePoints,
    tol: f64,
    snaps: &mut Snaps,
) -> f64 {
    lp.breaks.sort_by(f64::total_cmp);
    lp.a.sort_by(|x, y| x.0.total_cmp(&y.0));
    lp.b.sort_by(|x, y| x.0.total_cmp(&y.0));
    let sa: Vec<f64> = lp.a.iter().map(|x| x.0).collect();
    let sb: Vec<f64> = lp.b.iter().map(|x| x.0).collect();
    let d = set_disagreement(&sa, &sb);
    if d > tol {
        arr.warnings.push(format!(
            "sections {} and {} disagree along their common line by {:.3e} ({} vs {} points); each keeps its own points there",
            arr.planes[key.0 as usize].section.unwrap_or(usize::MAX),
            arr.planes[key.1 as usize].section.unwrap_or(usize::MAX),
            d,
            sa.len(),
            sb.len()
        ));
    }
    let pairs = crate::geom::close_pairs(&sa, &sb, tol, &lp.breaks);
    let mut used_a = vec![false; lp.a.len()];
    let mut used_b = vec![false; lp.b.len()];
    let mut keep_b = vec![true; lp.b.len()];
    for (dist, x, y) in pairs {
        if used_a[x] || used_b[y] {
            continue;
        }
        let (va, vb) = (lp.a[x].1, lp.b[y].1);
        if snaps.merged_into.contains_key(&va) || snaps.merged_into.contains_key(&vb) {
            continue;
        }
        used_a[x] = true;
        used_b[y] = true;
        keep_b[y] = false;
        merge(arr, va, vb, key.1);
        snaps.merged_into.insert(vb, va);
        snaps.snapped += 1;
        snaps.max_snap = snaps.max_snap.max(dist);
    }
    let kept: Vec<(f64, VertexId)> =
        lp.b.iter()
            .zip(&keep_b)
            .filter(|(_, &k)| k)
            .map(|(p, _)| *p)
            .collect();
    lp.b = kept;
    d
}

/// Replace merged vertices by their survivors in the pieces and on every line.
fn use_survivors(
    arr: &mut Arrangement,
    lines: &mut HashMap<(u32, u32), LinePoints>,
    merged_into: &HashMap<VertexId, VertexId>,
) {
    for face in &mut arr.faces {
        for piece in &mut face.pieces {
            for l in std::iter::once(&mut piece.outer).chain(piece.holes.iter_mut()) {
                for v in l.iter_mut() {
                    if let Some(&w) = merged_into.get(v) {
                        *v = w;
                    }
                }
            }
        }
    }
    // Points merged on one line may sit on other lines too (planes sharing a line): use the survivor.
    for lp in lines.values_mut() {
        for list in [&mut lp.a, &mut lp.b] {
            for p in list.iter_mut() {
                if let Some(&w) = merged_into.get(&p.1) {
                    p.1 = w;
                }
            }
            let mut seen = std::collections::HashSet::new();
            list.retain(|p| seen.insert(p.1));
        }
    }
}

/// Merge vertex `vb` (made by the section of plane `pb`) into `va`.
fn merge(arr: &mut Arrangement, va: VertexId, vb: VertexId, pb: u32) {
    let (a, b) = (va as usize, vb as usize);
    let pa = arr.pool.positions[a];
    let pbp = arr.pool.positions[b];
    let mid = [
        0.5 * (pa[0] + pbp[0]),
        0.5 * (pa[1] + pbp[1]),
        0.5 * (pa[2] + pbp[2]),
    ];
    let mut tags: SmallVec<[u32; 3]> = arr.pool.tags[a].clone();
    for &t in &arr.pool.tags[b] {
        if !tags.contains(&t) {
            tags.push(t);
        }
    }
    tags.sort_unstable();
    let uv = tags
        .iter()
        .map(|&t| {
            let own = |v: usize| {
                arr.pool.tags[v]
                    .iter()
                    .position(|&x| x == t)
                    .map(|k| arr.pool.uv[v][k])
            };
            if t == pb {
                own(b).unwrap()
            } else if let Some(x) = own(a) {
                x
            } else {
                arr.planes[t as usize].plane.to_2d(mid)
            }
        })
        .collect();
    arr.pool.positions[a] = mid;
    arr.pool.tags[a] = tags;
    arr.pool.uv[a] = uv;
}

/// Insert, into every piece edge lying on a line L_ij, the points of section j strictly inside it.
fn insert_line_points(arr: &mut Arrangement, lines: &HashMap<(u32, u32), LinePoints>) {
    let n = arr.n_input as u32;
    for f in 0..arr.faces.len() {
        let i = arr.faces[f].plane;
        if i >= n || arr.faces[f].pieces.is_empty() {
            continue;
        }
        let mut pieces = std::mem::take(&mut arr.faces[f].pieces);
        for piece in &mut pieces {
            for l in std::iter::once(&mut piece.outer).chain(piece.holes.iter_mut()) {
                let m = l.len();
                let mut out = Vec::with_capacity(m);
                for k in 0..m {
                    let (x, y) = (l[k], l[(k + 1) % m]);
                    out.push(x);
                    let tx = &arr.pool.tags[x as usize];
                    let ty = &arr.pool.tags[y as usize];
                    let mut extra: Vec<(f64, VertexId)> = Vec::new();
                    let mut dir_used = None;
                    for &j in tx.iter() {
                        if j == i || j >= n || !ty.contains(&j) {
                            continue;
                        }
                        let key = (i.min(j), i.max(j));
                        let Some(lp) = lines.get(&key) else { continue };
                        // Points of the other section: `a` holds the lower plane's.
                        let other = if i == key.0 { &lp.b } else { &lp.a };
                        if other.is_empty() {
                            continue;
                        }
                        let sx = dot(lp.dir, arr.pool.positions[x as usize]);
                        let sy = dot(lp.dir, arr.pool.positions[y as usize]);
                        let (lo, hi) = (sx.min(sy), sx.max(sy));
                        let start = other.partition_point(|p| p.0 <= lo);
                        for &(s, v) in &other[start..] {
                            if s >= hi {
                                break;
                            }
                            if v != x && v != y && arr.pool.tags[v as usize].contains(&i) {
                                extra.push((if sx <= sy { s - lo } else { hi - s }, v));
                            }
                        }
                        dir_used = Some(());
                    }
                    if dir_used.is_some() && !extra.is_empty() {
                        extra.sort_by(|p, q| p.0.total_cmp(&q.0));
                        extra.dedup_by_key(|p| p.1);
                        out.extend(extra.iter().map(|p| p.1));
                    }
                }
                *l = out;
            }
        }
        arr.faces[f].pieces = pieces;
    }
}

/// Remove merged-away vertices from the pool and renumber.
pub(super) fn compact(arr: &mut Arrangement, merged_into: &HashMap<VertexId, VertexId>) {
    let nv = arr.pool.positions.len();
    let mut new_id = vec![u32::MAX; nv];
    let mut next = 0u32;
    for (v, id) in new_id.iter_mut().enumerate() {
        if !merged_into.contains_key(&(v as VertexId)) {
            *id = next;
            next += 1;
        }
    }
    let keep = |v: usize| new_id[v] != u32::MAX;
    let mut k = 0;
    arr.pool.positions.retain(|_| {
        k += 1;
        keep(k - 1)
    });
    k = 0;
    arr.pool.tags.retain(|_| {
        k += 1;
        keep(k - 1)
    });
    k = 0;
    arr.pool.uv.retain(|_| {
        k += 1;
        keep(k - 1)
    });
    for face in &mut arr.faces {
        for v in face.polygon.iter_mut() {
            *v = new_id[*v as usize];
        }
        for piece in &mut face.pieces {
            for l in std::iter::once(&mut piece.outer).chain(piece.holes.iter_mut()) {
                for v in l.iter_mut() {
                    *v = new_id[*v as usize];
                }
            }
        }
    }
}

fn set_disagreement(a: &[f64], b: &[f64]) -> f64 {
    let span = |x: &[f64]| -> f64 {
        x.chunks(2)
            .map(|c| if c.len() == 2 { c[1] - c[0] } else { 0.0 })
            .fold(0.0, f64::max)
    };
    if a.is_empty() {
        return span(b);
    }
    if b.is_empty() {
        return span(a);
    }
    let near = |x: f64, set: &[f64]| {
        set.iter()
            .map(|y| (x - y).abs())
            .fold(f64::INFINITY, f64::min)
    };
    let h1 = a.iter().map(|&x| near(x, b)).fold(0.0, f64::max);
    let h2 = b.iter().map(|&x| near(x, a)).fold(0.0, f64::max);
    h1.max(h2)
}

#[cfg(test)]
mod tests {
    use super::set_disagreement;
    #[test]
    fn disagreement_of_point_sets() {
        assert_eq!(set_disagreement(&[0.0, 1.0], &[0.0, 1.0]), 0.0);
        assert!((set_disagreement(&[0.0, 1.0], &[0.1, 1.0]) - 0.1).abs() < 1e-15);
        assert!((set_disagreement(&[0.0, 1.0], &[]) - 1.0).abs() < 1e-15);
        assert!((set_disagreement(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0]) - 2.0).abs() < 1e-15);
    }
}
