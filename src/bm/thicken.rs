//! Thickening the flat zones attached from neither side (paper §5, Figs. 12c and 13).
//!
//! A region Z of a face's section that neither adjacent cell attaches to is not in the union of the
//! cells' solids, so the solid's section on that plane would miss it. The paper's remedy is to give
//! the cutting plane a thickness there: Z becomes a thin slab on the side of one cell C, which merges
//! with C's solid wherever C attaches next to Z.
//!
//! Construction, per connected component of Z (all as chains, so the surface stays a 2-cycle):
//! * every vertex v of Z gets a copy v' = v + δ_v·n_C (n_C: unit normal into C);
//! * bottom sheet: Z's triangles in the plane, facing away from C; top sheet: their lifted copies,
//!   facing into C; a wall (two triangles) on every boundary edge a→b of Z: the quad [a', b', b, a];
//! * every non-planar triangle of C at a vertex of Z has that vertex replaced by its copy (C's
//!   surface rising from ∂Z now rises from the top sheet's rim), and each of its edges x→y gets the
//!   filler quad [x, y, y*, x*] (x* the copy of x, or x) that keeps the chain closed; fillers of C's
//!   interior edges cancel in pairs, and on a boundary edge of Z that C's surface rises from, the
//!   filler is exactly the reversed wall: both cancel, and the slab merges into C's solid there;
//! * opposite coincident triangles among the new ones cancel.
//!
//! Where C's surface does not rise from ∂Z (the section's contour, a region only the other cell
//! attaches to) the wall stays: the slab ends there with a vertical rim of height δ. Edges where the
//! slab touches the other cell's solid are left to `unpinch`.
//!
//! δ_v is twice the outside judge's section offset (1e-5 of the model's diagonal) where the
//! surroundings allow, at most a quarter of the height above the plane of C's vertices adjacent to
//! v (so lifted triangles of C do not dip below the top sheet). Every new or changed triangle is
//! tested exactly against the triangles near it (crossings, and near-coplanar overlaps as
//! `eval::check` counts them); if one crosses, the component is rebuilt with a tenth of δ, and after
//! three tries it is left flat (not in the solid, as before), with the reason.
use super::glue::{parity, sorted, tri_area, Kind};
use crate::arrangement::{Arrangement, VertexPool};
use crate::eval::near_coplanar::{overlapping_near_coplanar, NEAR_COPLANAR_RELATIVE_TOLERANCE};
use crate::eval::tri_tri::mesh_triangles_intersect;
use crate::fxhash::FxHashSet;
use crate::geom::bvh::{Aabb, Bvh};
use crate::sections::{dot, sub};
use rayon::prelude::*;
use std::collections::HashMap;

/// Edge (min, max) → the triangles using it.
type EdgeMap = crate::fxhash::FxHashMap<(u32, u32), Vec<usize>>;

/// Slab thickness wanted, relative to the model's bounding-box diagonal: twice the offset at which
/// the outside judge takes sections above and below each plane.
const TARGET_RELATIVE_THICKNESS: f64 = 2e-5;
/// Largest fraction of the height of C's neighbouring vertices a lifted vertex may rise.
const HEIGHT_FRACTION: f64 = 0.25;
/// A vertex on another plane too is lifted towards its cell's centre; below this height per unit
/// step (the direction nearly in the face's plane) it stays where it is (the slab is pinched there).
const MIN_RISE: f64 = 1e-2;
/// A vertex whose room above (a quarter of its lowest neighbour's height in C) is below this fraction
/// of the wanted thickness stays pinned.
const MIN_FRACTION_OF_TARGET: f64 = 0.1;
/// Components below this area (relative to the squared diagonal) are slivers left as they are.
const MIN_RELATIVE_AREA: f64 = 1e-12;
/// Thickness factors tried in turn.
const ATTEMPTS: [f64; 3] = [1.0, 0.1, 0.01];

/// A flat zone of one face: its triangles (global ids) and the cells it may be thickened into.
#[derive(Clone, Debug)]
pub struct Zone {
    pub face: u32,
    pub plane: u32,
    /// Area of the zone (for the report).
    pub area: f64,
    /// Candidate cells: (cell, unit normal of the face pointing into it).
    pub cells: Vec<(u32, [f64; 3])>,
    /// The zone's triangles, facing away from the cell of the same index. A single list with two
    /// cells is one triangulation for both (facing away from `cells[0]`; reversed for `cells[1]`).
    pub tris: Vec<Vec<[u32; 3]>>,
}

/// What became of one zone.
#[derive(Clone, Debug)]
pub struct ZoneOutcome {
    pub face: u32,
    pub plane: u32,
    pub area: f64,
    /// Components thickened: (cell, area, smallest and largest δ).
    pub thickened: Vec<(u32, f64, f64, f64)>,
    /// Components left flat: (area, reason).
    pub left: Vec<(f64, String)>,
}

/// Thicken every zone (see the module doc). `diag`: the model's bounding-box diagonal.
pub(super) fn thicken(
    arr: &Arrangement,
    pool: &VertexPool,
    positions: &mut Vec<[f64; 3]>,
    tris: &mut Vec<[u32; 3]>,
    kind: &mut Vec<Kind>,
    zones: &[Zone],
    diag: f64,
) -> Vec<ZoneOutcome> {
    let mut centres: HashMap<u32, [f64; 3]> = HashMap::new();
    let mut out = Vec::new();
    let mut index = TriIndex::new(positions, tris);
    for z in zones {
        let mut o = ZoneOutcome {
            face: z.face,
            plane: z.plane,
            area: z.area,
            thickened: Vec::new(),
            left: Vec::new(),
        };
        // (cell index, component triangles facing away from that cell)
        let mut pieces: Vec<(usize, Vec<[u32; 3]>)> = Vec::new();
        let edges = edge_map_near(
            positions,
            tris,
            &index.view(positions, tris),
            z.tris.iter().flatten().flatten().copied(),
        );
        if z.tris.len() == 1 {
            for comp in components(&z.tris[0]) {
                let best = (0..z.cells.len())
                    .map(|k| {
                        let c = oriented(&comp, k);
                        (merge_length(positions, kind, &edges, &c, z.cells[k].0), k)
                    })
                    .fold((f64::NEG_INFINITY, 0), |a, b| if b.0 > a.0 { b } else { a });
                pieces.push((best.1, oriented(&comp, best.1)));
            }
        } else {
            let best = (0..z.cells.len().min(z.tris.len()))
                .map(|k| {
                    let l = merge_length(positions, kind, &edges, &z.tris[k], z.cells[k].0);
                    (l, k)
                })
                .fold((f64::NEG_INFINITY, 0), |a, b| if b.0 > a.0 { b } else { a });
            for comp in components(&z.tris[best.1]) {
                pieces.push((best.1, comp));
            }
        }
        for (k, comp) in pieces {
            let (cell, into) = z.cells[k];
            let area: f64 = comp.iter().map(|&t| tri_area(positions, t)).sum();
            // lift directions: along the normal, except for vertices on other planes too (on the
            // face's rim), which move towards the cell's centre so as to stay inside the cell
            let mut dirs: HashMap<u32, Option<[f64; 3]>> = HashMap::new();
            for &v in comp.iter().flatten() {
                dirs.entry(v).or_insert_with(|| {
                    let on_other = pool
                        .tags
                        .get(v as usize)
                        .is_some_and(|t| t.iter().any(|&p| p != z.plane));
                    if !on_other {
                        return Some(into);
                    }
                    let centre = *centres
                        .entry(cell)
                        .or_insert_with(|| cell_centre(arr, pool, cell));
                    let d = sub(centre, positions[v as usize]);
                    let l = dot(d, d).sqrt();
                    let d = d.map(|x| x / l);
                    (l > 0.0 && dot(d, into) >= MIN_RISE).then_some(d)
                });
            }
            if area <= MIN_RELATIVE_AREA * diag * diag {
                // a sliver (rounding along an arrangement edge): nothing to give a thickness to
                o.left.push((area, "degenerate".into()));
                continue;
            }
            let mut why = String::new();
            let mut done = None;
            for &scale in &ATTEMPTS {
                match apply(
                    positions, tris, kind, &mut index, &comp, z.face, cell, into, &dirs, scale,
                    diag,
                ) {
                    Ok(d) => {
                        done = Some(d);
                        break;
                    }
                    Err(e) => why = e,
                }
            }
            match done {
                Some((lo, hi)) => o.thickened.push((cell, area, lo, hi)),
                None => o.left.push((area, why)),
            }
        }
        out.push(o);
    }
    out
}

/// Mean of the corners of cell `c`'s faces (strictly inside the convex cell).
fn cell_centre(arr: &Arrangement, pool: &VertexPool, c: u32) -> [f64; 3] {
    let mut sum = [0.0; 3];
    let mut n = 0.0f64;
    for cf in arr.cells.get(c as usize).map_or(&[][..], |c| &c.faces[..]) {
        for &v in &arr.faces[cf.face as usize].polygon {
            let p = pool.positions[v as usize];
            for k in 0..3 {
                sum[k] += p[k];
            }
            n += 1.0;
        }
    }
    sum.map(|x| x / n.max(1.0))
}

/// `comp` facing away from cell `k` of a shared triangulation (given facing away from cell 0).
fn oriented(comp: &[[u32; 3]], k: usize) -> Vec<[u32; 3]> {
    if k == 0 {
        comp.to_vec()
    } else {
        comp.iter().map(|t| [t[0], t[2], t[1]]).collect()
    }
}

/// Length of the boundary of `z` along which the surface of `cell` rises (where the slab would merge
/// into that cell's solid).
fn merge_length(
    positions: &[[f64; 3]],
    kind: &[Kind],
    edges: &EdgeMap,
    z: &[[u32; 3]],
    cell: u32,
) -> f64 {
    let mut len = 0.0;
    for (a, b) in boundary(z) {
        if let Some(l) = edges.get(&(a.min(b), a.max(b))) {
            if l.iter().any(|&i| kind[i] == Kind::Cell(cell)) {
                let d = sub(positions[a as usize], positions[b as usize]);
                len += dot(d, d).sqrt();
            }
        }
    }
    len
}

/// Directed boundary edges of a set of triangles: edges a→b whose reverse is not used.
fn boundary(z: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut directed: HashMap<(u32, u32), i32> = HashMap::new();
    for t in z {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *directed.entry((a, b)).or_default() += 1;
        }
    }
    let mut out: Vec<(u32, u32)> = directed
        .iter()
        .filter(|(&(a, b), &n)| n > directed.get(&(b, a)).copied().unwrap_or(0))
        .map(|(&e, _)| e)
        .collect();
    out.sort_unstable();
    out
}

/// Connected components of a set of triangles (joined across shared edges), each sorted.
fn components(z: &[[u32; 3]]) -> Vec<Vec<[u32; 3]>> {
    let mut parent: Vec<usize> = (0..z.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut by_edge: HashMap<(u32, u32), usize> = HashMap::new();
    for (i, t) in z.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if let Some(&j) = by_edge.get(&(a.min(b), a.max(b))) {
                let (x, y) = (find(&mut parent, i), find(&mut parent, j));
                parent[x] = y;
            } else {
                by_edge.insert((a.min(b), a.max(b)), i);
            }
        }
    }
    let mut comps: HashMap<usize, Vec<[u32; 3]>> = HashMap::new();
    for (i, &t) in z.iter().enumerate() {
        let r = find(&mut parent, i);
        comps.entry(r).or_default().push(t);
    }
    let mut out: Vec<Vec<[u32; 3]>> = comps.into_values().collect();
    for c in &mut out {
        c.sort_unstable();
    }
    out.sort();
    out
}

/// [`edge_map_at`] from the triangles `near` finds around `at` (those with a vertex in `at` are
/// among them: their boxes hold that vertex), without a scan of the whole surface.
fn edge_map_near(
    positions: &[[f64; 3]],
    tris: &[[u32; 3]],
    near: &Near,
    at: impl Iterator<Item = u32>,
) -> EdgeMap {
    let at: FxHashSet<u32> = at.collect();
    let mut bb = Aabb::EMPTY;
    for &v in &at {
        bb.add_point(positions[v as usize]);
    }
    let mut edges = EdgeMap::default();
    for i in near.overlapping(&bb) {
        let t = tris[i];
        if !t.iter().any(|v| at.contains(v)) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push(i);
        }
    }
    edges
}

/// Box-overlap queries on the surface while zones are thickened, without a scan or a BVH of the
/// whole surface per zone: segments, each a BVH over some triangles' boxes as they were when it was
/// built (the first over the whole surface), and per triangle the segment holding its current box.
/// Triangles changed or added since are built into a new segment at the next [`Near`] view, and
/// the last segments merged when the newest is not much smaller than the one before (a binary
/// counter: every triangle is rebuilt O(log) times). A query gives exactly the triangles whose
/// current box overlaps (what a scan of the surface gives).
struct TriIndex {
    /// (triangles, BVH over their boxes at build).
    segs: Vec<(Vec<usize>, Bvh)>,
    /// Per triangle: the segment holding its current box (`NONE`: changed or added since).
    seg_of: Vec<u32>,
    /// Triangles changed since they were put into a segment.
    pending: Vec<usize>,
}

/// A [`TriIndex`] brought up to date with the surface.
struct Near<'a> {
    index: &'a TriIndex,
}

impl TriIndex {
    const NONE: u32 = u32::MAX;

    fn new(positions: &[[f64; 3]], tris: &[[u32; 3]]) -> TriIndex {
        let mut index = TriIndex {
            segs: Vec::new(),
            seg_of: Vec::new(),
            pending: Vec::new(),
        };
        index.view(positions, tris);
        index
    }
    /// Triangle `i` is about to change (or was restored).
    fn touch(&mut self, i: usize) {
        if let Some(s) = self.seg_of.get_mut(i) {
            if *s != Self::NONE {
                *s = Self::NONE;
                self.pending.push(i);
            }
        }
    }
    /// The surface was cut back to its first `n` triangles.
    fn truncate(&mut self, n: usize) {
        self.seg_of.truncate(n);
        self.pending.retain(|&i| i < n);
    }
    /// A segment over `items` (current triangles) with their current boxes.
    fn push_segment(&mut self, positions: &[[f64; 3]], tris: &[[u32; 3]], items: Vec<usize>) {
        let id = self.segs.len() as u32;
        for &i in &items {
            self.seg_of[i] = id;
        }
        let bvh = Bvh::build(
            items
                .iter()
                .map(|&i| Aabb::of_points(&tris[i].map(|v| positions[v as usize])))
                .collect(),
        );
        self.segs.push((items, bvh));
    }
    /// The triangles of segment `s` whose box there is still their current one.
    fn live(&self, s: usize) -> Vec<usize> {
        let id = s as u32;
        self.segs[s]
            .0
            .iter()
            .copied()
            .filter(|&i| self.seg_of.get(i) == Some(&id))
            .collect()
    }
    fn view(&mut self, positions: &[[f64; 3]], tris: &[[u32; 3]]) -> Near<'_> {
        assert!(self.seg_of.len() <= tris.len(), "TriIndex: truncate first");
        let n0 = self.seg_of.len();
        self.seg_of.resize(tris.len(), Self::NONE);
        self.pending.extend(n0..tris.len());
        if !self.pending.is_empty() {
            let mut items = std::mem::take(&mut self.pending);
            items.sort_unstable();
            items.dedup();
            self.push_segment(positions, tris, items);
            // merge the newest segments while the last is at least half the one before it (the
            // whole surface's segment too, once the changes outgrow it)
            while self.segs.len() >= 2 {
                let k = self.segs.len();
                let (last, prev) = (self.segs[k - 1].0.len(), self.segs[k - 2].0.len());
                if 2 * last < prev {
                    break;
                }
                let mut items = self.live(k - 2);
                items.extend(self.live(k - 1));
                items.sort_unstable();
                self.segs.truncate(k - 2);
                self.push_segment(positions, tris, items);
            }
        }
        Near { index: self }
    }
}

impl Near<'_> {
    /// Calls `f` for every triangle whose box overlaps `bb` (closed), in no particular order.
    fn for_each_overlap(&self, bb: &Aabb, mut f: impl FnMut(usize)) {
        let idx = self.index;
        for (s, (items, bvh)) in idx.segs.iter().enumerate() {
            bvh.for_each_overlap(bb, |k| {
                let i = items[k as usize];
                if idx.seg_of.get(i) == Some(&(s as u32)) {
                    f(i)
                }
            });
        }
    }
    /// The triangles whose box overlaps `bb`, ascending.
    fn overlapping(&self, bb: &Aabb) -> Vec<usize> {
        let mut out = Vec::new();
        self.for_each_overlap(bb, |j| out.push(j));
        out.sort_unstable();
        out
    }
}

/// Edge → triangles, for the triangles with a vertex in `at` (the edges among `at` are complete).
#[cfg(test)]
fn edge_map_at(tris: &[[u32; 3]], at: impl Iterator<Item = u32>) -> EdgeMap {
    let mut mark: Vec<bool> = Vec::new();
    for v in at {
        if mark.len() <= v as usize {
            mark.resize(v as usize + 1, false);
        }
        mark[v as usize] = true;
    }
    let mut edges = EdgeMap::default();
    for (i, t) in tris.iter().enumerate() {
        if !t
            .iter()
            .any(|&v| mark.get(v as usize).copied().unwrap_or(false))
        {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push(i);
        }
    }
    edges
}

/// The quad [p, q, r, s] (cyclic) as triangles: degenerate sides dropped, else split along the
/// diagonal through the smallest id, so that a quad and its reverse give opposite triangles.
fn quad(p: u32, q: u32, r: u32, s: u32, out: &mut Vec<[u32; 3]>) {
    match (p == s, q == r) {
        (true, true) => {}
        (true, false) => out.push([p, q, r]),
        (false, true) => out.push([p, q, s]),
        (false, false) => {
            if p.min(r) < q.min(s) {
                out.push([p, q, r]);
                out.push([p, r, s]);
            } else {
                out.push([q, r, s]);
                out.push([q, s, p]);
            }
        }
    }
}

/// Drop pairs of opposite coincident triangles.
fn cancel_opposites(list: Vec<([u32; 3], Kind)>) -> Vec<([u32; 3], Kind)> {
    let mut by_key: HashMap<[u32; 3], (Vec<usize>, Vec<usize>)> = HashMap::new();
    for (i, (t, _)) in list.iter().enumerate() {
        let e = by_key.entry(sorted(*t)).or_default();
        if parity(*t) {
            e.0.push(i)
        } else {
            e.1.push(i)
        }
    }
    let mut drop = vec![false; list.len()];
    for (pos, neg) in by_key.values() {
        for (&i, &j) in pos.iter().zip(neg) {
            drop[i] = true;
            drop[j] = true;
        }
    }
    list.into_iter()
        .zip(drop)
        .filter(|(_, d)| !d)
        .map(|(x, _)| x)
        .collect()
}

/// Thicken one component `z` (facing away from `cell`) into `cell`; on success returns the smallest
/// and largest δ. On failure everything is restored and the reason returned.
#[allow(clippy::too_many_arguments)]
fn apply(
    positions: &mut Vec<[f64; 3]>,
    tris: &mut Vec<[u32; 3]>,
    kind: &mut Vec<Kind>,
    index: &mut TriIndex,
    z: &[[u32; 3]],
    face: u32,
    cell: u32,
    into: [f64; 3],
    dirs: &HashMap<u32, Option<[f64; 3]>>,
    scale: f64,
    diag: f64,
) -> Result<(f64, f64), String> {
    let mut vz: Vec<u32> = z.iter().flatten().copied().collect();
    vz.sort_unstable();
    vz.dedup();
    let in_z: FxHashSet<u32> = vz.iter().copied().collect();
    // C's non-planar triangles at the zone's vertices (their boxes hold a vertex of the zone)
    let z_box = Aabb::of_points(
        &vz.iter()
            .map(|&v| positions[v as usize])
            .collect::<Vec<_>>(),
    );
    let cell_tris: Vec<usize> = index
        .view(positions, tris)
        .overlapping(&z_box)
        .into_iter()
        .filter(|&i| kind[i] == Kind::Cell(cell) && tris[i].iter().any(|v| in_z.contains(v)))
        .collect();
    let tiny = 1e-9 * diag;
    let mut height: HashMap<u32, f64> = HashMap::new();
    for &i in &cell_tris {
        let t = tris[i];
        for &v in &t {
            if !in_z.contains(&v) {
                continue;
            }
            for &w in &t {
                let h = dot(sub(positions[w as usize], positions[v as usize]), into);
                if h > tiny {
                    let e = height.entry(v).or_insert(f64::INFINITY);
                    *e = e.min(h);
                }
            }
        }
    }
    let n0 = positions.len();
    let mut copy: HashMap<u32, u32> = HashMap::new();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for &v in &vz {
        let Some(dir) = dirs.get(&v).copied().flatten() else {
            continue; // pinned: the slab's top meets its bottom here
        };
        let mut d = TARGET_RELATIVE_THICKNESS * diag;
        if let Some(&h) = height.get(&v) {
            if HEIGHT_FRACTION * h < MIN_FRACTION_OF_TARGET * d {
                continue; // C's surface passes just above: pinned (no room for a slab here)
            }
            d = d.min(HEIGHT_FRACTION * h);
        }
        let d = d * scale;
        lo = lo.min(d);
        hi = hi.max(d);
        let p = positions[v as usize];
        positions.push([p[0] + d * dir[0], p[1] + d * dir[1], p[2] + d * dir[2]]);
        copy.insert(v, (positions.len() - 1) as u32);
    }
    let star = |v: u32| copy.get(&v).copied().unwrap_or(v);
    let mut added: Vec<([u32; 3], Kind)> = Vec::new();
    for &t in z {
        added.push((t, Kind::Face(face)));
        added.push(([star(t[0]), star(t[2]), star(t[1])], Kind::Face(face)));
    }
    let mut q = Vec::new();
    for (a, b) in boundary(z) {
        quad(star(a), star(b), b, a, &mut q);
    }
    added.extend(q.drain(..).map(|t| (t, Kind::Face(face))));
    let mut substituted: Vec<(usize, [u32; 3])> = Vec::new();
    for &i in &cell_tris {
        let t = tris[i];
        for k in 0..3 {
            let (x, y) = (t[k], t[(k + 1) % 3]);
            quad(x, y, star(y), star(x), &mut q);
        }
        substituted.push((i, t));
    }
    added.extend(q.drain(..).map(|t| (t, Kind::Cell(cell))));
    let added = cancel_opposites(added);
    // crossings of C's triangles before the change (not to be blamed on the slab)
    let before = crossings(
        positions,
        tris,
        &index.view(positions, tris),
        &substituted.iter().map(|s| s.0).collect::<Vec<_>>(),
        diag,
    );
    let n_tris = tris.len();
    for &(i, t) in &substituted {
        index.touch(i);
        tris[i] = t.map(star);
    }
    for &(t, k) in &added {
        tris.push(t);
        kind.push(k);
    }
    let changed: Vec<usize> = substituted
        .iter()
        .map(|s| s.0)
        .chain(n_tris..tris.len())
        .collect();
    let after = crossings(
        positions,
        tris,
        &index.view(positions, tris),
        &changed,
        diag,
    );
    if after > before {
        for &(i, t) in &substituted {
            index.touch(i);
            tris[i] = t;
        }
        index.truncate(n_tris);
        tris.truncate(n_tris);
        kind.truncate(n_tris);
        positions.truncate(n0);
        return Err(format!(
            "{after} crossings with δ up to {hi:.2e} ({before} before)"
        ));
    }
    Ok((lo, hi))
}

/// Pairs (changed triangle, any other) that cross exactly or overlap near-coplanar (within
/// `eval::check`'s tolerance), each counted once.
fn crossings(
    positions: &[[f64; 3]],
    tris: &[[u32; 3]],
    near: &Near,
    changed: &[usize],
    diag: f64,
) -> usize {
    if changed.is_empty() {
        return 0;
    }
    let tol = NEAR_COPLANAR_RELATIVE_TOLERANCE * diag;
    let grow = |b: Aabb| Aabb {
        lo: b.lo.map(|x| x - 2.0 * tol),
        hi: b.hi.map(|x| x + 2.0 * tol),
    };
    let tbox = |t: [u32; 3]| Aabb::of_points(&t.map(|v| positions[v as usize]));
    let is_changed: FxHashSet<usize> = changed.iter().copied().collect();
    let pts = |t: [u32; 3]| t.map(|v| positions[v as usize]);
    // the pairs of one changed triangle (independent of the others: counted in parallel)
    let count = |&i: &usize| -> usize {
        let t = tris[i];
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return 0;
        }
        let mut n = 0;
        near.for_each_overlap(&grow(tbox(t)), |j| {
            if j == i || (is_changed.contains(&j) && j < i) {
                return;
            }
            let u = tris[j];
            if u[0] == u[1] || u[1] == u[2] || u[0] == u[2] {
                return;
            }
            let cross = mesh_triangles_intersect(t, u, positions);
            if cross || overlapping_near_coplanar(pts(t), pts(u), tol) {
                n += 1;
            }
        });
        n
    };
    changed.par_iter().map(count).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge_balance_ok(tris: &[[u32; 3]]) -> bool {
        let mut m: HashMap<(u32, u32), i32> = HashMap::new();
        for t in tris {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *m.entry((a, b)).or_default() += 1;
                *m.entry((b, a)).or_default() -= 1;
            }
        }
        m.values().all(|&c| c == 0)
    }

    #[test]
    fn a_quad_and_its_reverse_cancel() {
        let mut q = Vec::new();
        quad(5, 2, 7, 9, &mut q);
        quad(9, 7, 2, 5, &mut q);
        let k: Vec<([u32; 3], Kind)> = q.into_iter().map(|t| (t, Kind::Face(0))).collect();
        assert!(cancel_opposites(k).is_empty());
    }

    /// A unit square section in z = 0 split into an attached left half (a tet of cell 0 stands on it,
    /// apex above) and a flat right half: the slab merges with the tet along the middle edge.
    #[test]
    fn a_zone_next_to_an_attached_region_merges_into_its_cell() {
        // 0 (0,0) 1 (1,0) 2 (2,0) 3 (2,1) 4 (1,1) 5 (0,1); apex 6 above the left half
        let mut pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, 1.0],
        ];
        // solid: pyramid over the left square, facing out (bottom faces -z)
        let mut tris = vec![
            [0, 4, 1],
            [0, 5, 4], // bottom (section, outward from cell 0 = -z)
            [0, 1, 6],
            [1, 4, 6],
            [4, 5, 6],
            [5, 0, 6],
        ];
        let mut kind = vec![
            Kind::Face(0),
            Kind::Face(0),
            Kind::Cell(0),
            Kind::Cell(0),
            Kind::Cell(0),
            Kind::Cell(0),
        ];
        assert!(edge_balance_ok(&tris));
        let zone = Zone {
            face: 0,
            plane: 0,
            area: 1.0,
            cells: vec![(0, [0.0, 0.0, 1.0])],
            tris: vec![vec![[1, 3, 2], [1, 4, 3]]],
        };
        let diag = 3.0;
        let arr = super::super::empty_arrangement();
        let out = thicken(
            &arr,
            &arr.pool,
            &mut pos,
            &mut tris,
            &mut kind,
            &[zone],
            diag,
        );
        assert_eq!(out[0].thickened.len(), 1, "{out:?}");
        assert!(out[0].left.is_empty());
        assert!(edge_balance_ok(&tris));
        // closed 2-manifold: every undirected edge used exactly twice
        let edges = edge_map_at(&tris, tris.iter().flatten().copied());
        assert!(edges.values().all(|l| l.len() == 2), "{edges:?}");
        // the middle edge 1–4 is now inside the flat bottom (two section triangles)
        let mid = &edges[&(1, 4)];
        assert!(mid.iter().all(|&i| kind[i] == Kind::Face(0)));
        // no crossings
        let all: Vec<usize> = (0..tris.len()).collect();
        let mut index = TriIndex::new(&pos, &tris);
        assert_eq!(
            crossings(&pos, &tris, &index.view(&pos, &tris), &all, diag),
            0
        );
        // the copies sit δ above their vertices
        let d = TARGET_RELATIVE_THICKNESS * diag;
        assert!((pos[7][2] - d).abs() < 1e-15 && pos[7][0] == pos[1][0]);
    }
}
