//! Overlay of the two cells' attached regions on one shared face (2D, in the plane's (u,v) frame).
//!
//! The two cells A and B of a face triangulate its section independently (different point sets:
//! each has its own branching samples; different triangulations of nearly coplanar points). The
//! surface on the face is the oriented symmetric difference of the attached regions X_A and X_B:
//! where only A attaches, the region oriented outward from A; only B: outward from B; both: interior;
//! neither: a flat zone (nothing). To get it, a constrained Delaunay triangulation (spade) of all
//! vertices of X_A and X_B with every edge of their triangles as a constraint gives a common
//! refinement. Each original edge's chain (the CDT vertices along it) is tracked exactly through the
//! insertions (`insert_constraints`), so it is unique and direction-independent. Its triangles are
//! labelled by winding numbers: each side's triangles, as given, are a 2-chain; crossing a CDT edge
//! changes a side's winding by the net number of its directed triangle edges running along it, so
//! from the outer face (0) every face gets an integer winding per side, checked for consistency
//! (exact: integers on the CDT's combinatorics). The output is where A + B does not cancel.
//! Where two constraints cross, spade inserts a new vertex; every original edge that got vertices on
//! it (crossings, or existing vertices lying exactly on it) is returned with its chain so that the
//! caller can split the 3D triangles that use it (no T-junctions).
//!
//! Decisions: spade's robust orient2d/incircle on the (u,v) it is given (constructed coordinates:
//! the caller's frame coordinates, plus spade's rounded crossing points); our own orient2d only to
//! choose the vertex nearest a split sub-edge when repairing a chain.
//!
//! Every inconsistency (two ids at one (u,v), a side whose windings are not 0/1 — overlapping or
//! folded triangles —, inconsistent windings, a chain that cannot be tracked, a panic inside spade)
//! is an `Err` with the reason: the caller then keeps its per-side output for that face.
use crate::fxhash::FxHashMap;
use crate::geom::predicates::orient2d;
use smallvec::SmallVec;
use spade::handles::{FixedFaceHandle, FixedVertexHandle, InnerTag};
use spade::{
    ConstrainedDelaunayTriangulation, HasPosition, Intersection, LineIntersectionIterator, Point2,
    Triangulation,
};
use std::collections::HashMap;

/// Id of a vertex created by the overlay (before the caller numbers it).
const NEW: u32 = u32::MAX;

#[derive(Clone, Copy, Debug)]
struct Vx {
    p: Point2<f64>,
    id: u32,
}

impl HasPosition for Vx {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

#[derive(Clone, Debug, Default)]
pub struct Overlay {
    /// (u,v) of the vertices the overlay created, numbered `first_new + k`.
    pub new_vertices: Vec<[f64; 2]>,
    /// Output triangles (only-A outward from A, only-B outward from B), global ids.
    pub triangles: Vec<[u32; 3]>,
    /// Original edges (key `(min, max)`) with the vertices now inside them, ordered from min to max.
    pub splits: Vec<((u32, u32), Vec<u32>)>,
    /// Area of X_A ∪ X_B (in (u,v)).
    pub attached_area: f64,
    /// Area of the output (only-A plus only-B).
    pub output_area: f64,
    /// With a section layer ([`overlay_with_section`]): the triangles of the section attached from
    /// neither side (flat zones), oriented like A's (outward from A).
    pub flat: Vec<[u32; 3]>,
}

impl Overlay {
    /// The same overlay with its new vertices numbered from `first_new` instead of `base` (ids
    /// below `base` are global ids and stay).
    pub fn renumbered(mut self, base: u32, first_new: u32) -> Overlay {
        let f = |v: u32| if v >= base { v - base + first_new } else { v };
        for t in self.triangles.iter_mut().chain(self.flat.iter_mut()) {
            *t = t.map(f);
        }
        for (_, inner) in self.splits.iter_mut() {
            for v in inner.iter_mut() {
                *v = f(*v);
            }
        }
        self
    }
}

fn area2(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> f64 {
    (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
}

/// Overlay X_A (`a`) and X_B (`b`), both oriented outward from their own cell, vertices in global ids
/// with their (u,v) in `uv`. `ccw_a`: a triangle oriented outward from A is counter-clockwise in
/// (u,v). New vertices get ids from `first_new` on.
pub fn overlay<S: UvHasher>(
    uv: &HashMap<u32, [f64; 2], S>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    overlay_layers(uv, a, b, None, ccw_a, first_new)
}

/// [`overlay`] with a third layer `s`: A's triangulation of the whole section (attached or not,
/// oriented like A's). Its edges are constraints too, and the triangles inside `s` but in neither
/// X_A nor X_B are returned in [`Overlay::flat`] (the flat zones, for `thicken`).
pub fn overlay_with_section<S: UvHasher>(
    uv: &HashMap<u32, [f64; 2], S>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    s: &[[u32; 3]],
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    overlay_layers(uv, a, b, Some(s), ccw_a, first_new)
}

fn overlay_layers<S: UvHasher>(
    uv: &HashMap<u32, [f64; 2], S>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    s: Option<&[[u32; 3]]>,
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    // spade asserts on some inconsistent inputs: keep them from unwinding through the caller
    std::panic::catch_unwind(|| overlay_inner(uv, a, b, s, ccw_a, first_new))
        .unwrap_or_else(|_| Err("constrained triangulation panicked".into()))
}

type Cdt = ConstrainedDelaunayTriangulation<Vx>;

/// The hasher of a (u,v) map (any: lookups only).
pub trait UvHasher: std::hash::BuildHasher + std::panic::RefUnwindSafe {}
impl<S: std::hash::BuildHasher + std::panic::RefUnwindSafe> UvHasher for S {}

fn overlay_inner<S: UvHasher>(
    uv: &HashMap<u32, [f64; 2], S>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    s: Option<&[[u32; 3]]>,
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    // layers: A, B and optionally the whole section (A's triangulation, oriented like A's)
    let mut layers: Vec<&[[u32; 3]]> = vec![a, b];
    if let Some(s) = s {
        layers.push(s);
    }
    let q = |v: u32| -> Result<[f64; 2], String> {
        uv.get(&v)
            .copied()
            .ok_or_else(|| format!("vertex {v} has no (u,v)"))
    };
    let mut cdt = Cdt::new();
    let mut handle: FxHashMap<u32, FixedVertexHandle> = FxHashMap::default();
    let mut ids: Vec<u32> = layers
        .iter()
        .flat_map(|l| l.iter())
        .flat_map(|t| t.iter().copied())
        .collect();
    ids.sort_unstable();
    ids.dedup();
    for &v in &ids {
        let p = q(v)?;
        let n = cdt.num_vertices();
        let h = cdt
            .insert(Vx {
                p: Point2::new(p[0], p[1]),
                id: v,
            })
            .map_err(|e| format!("vertex {v}: {e:?}"))?;
        if cdt.num_vertices() == n {
            return Err(format!("vertex {v} coincides with another in (u,v)"));
        }
        handle.insert(v, h);
    }
    // every original edge once (key (min, max)), a constraint from min to max
    let mut edge_list: Vec<(u32, u32)> = layers
        .iter()
        .flat_map(|l| l.iter())
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    edge_list.sort_unstable();
    edge_list.dedup();
    let chains = insert_constraints(&mut cdt, &handle, &edge_list)?;
    // number the new vertices
    let mut out = Overlay::default();
    let mut vid: Vec<u32> = vec![NEW; cdt.num_vertices()];
    for v in cdt.vertices() {
        let id = if v.data().id == NEW {
            out.new_vertices.push([v.position().x, v.position().y]);
            first_new + out.new_vertices.len() as u32 - 1
        } else {
            v.data().id
        };
        vid[v.fix().index()] = id;
    }
    let mut chain_of: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (i, (&key, chain)) in edge_list.iter().zip(&chains).enumerate() {
        chain_of.insert(key, i);
        if chain.len() > 2 {
            let inner = chain[1..chain.len() - 1]
                .iter()
                .map(|h| vid[h.index()])
                .collect();
            out.splits.push((key, inner));
        }
    }
    // Winding numbers. Each side's triangles as given form a 2-chain; a CDT edge carries the net
    // number of the side's directed triangle edges running along it (forward minus backward), and
    // crossing it from its right to its left adds that number to the winding. From the outer face
    // (winding 0) every CDT face gets its winding per side; reaching a face twice with different
    // values means the chains are wrong (an exact, integer consistency check).
    let mut delta = vec![[0i32; 3]; cdt.num_undirected_edges()];
    for (side, &tris) in layers.iter().enumerate() {
        for t in tris {
            for k in 0..3 {
                let (x, y) = (t[k], t[(k + 1) % 3]);
                let chain = &chains[chain_of[&(x.min(y), x.max(y))]];
                let sign = if x < y { 1 } else { -1 };
                for w in chain.windows(2) {
                    let e = cdt
                        .get_edge_from_neighbors(w[0], w[1])
                        .ok_or("chain edge missing")?;
                    let d = e.fix();
                    // the undirected edge's own direction is its even half
                    let s = if d.index() & 1 == 0 { sign } else { -sign };
                    delta[d.as_undirected().index()][side] += s;
                }
            }
        }
    }
    let along = |e: spade::handles::FixedDirectedEdgeHandle| -> [i32; 3] {
        let d = delta[e.as_undirected().index()];
        if e.index() & 1 == 0 {
            d
        } else {
            d.map(|x| -x)
        }
    };
    let nf = cdt.num_all_faces();
    let mut wind: Vec<Option<[i32; 3]>> = vec![None; nf];
    let mut stack: Vec<FixedFaceHandle<InnerTag>> = Vec::new();
    wind[cdt.outer_face().fix().index()] = Some([0; 3]);
    for e in cdt.directed_edges() {
        if !e.face().is_outer() {
            continue;
        }
        // e has the outer face on its left: its right side is w(outer) − δ(e)
        let Some(g) = e.rev().face().as_inner() else {
            continue;
        };
        let w = along(e.fix()).map(|x| -x);
        match wind[g.fix().index()] {
            None => {
                wind[g.fix().index()] = Some(w);
                stack.push(g.fix());
            }
            Some(o) if o != w => return Err("winding numbers inconsistent".into()),
            Some(_) => {}
        }
    }
    while let Some(f) = stack.pop() {
        let wf = wind[f.index()].unwrap();
        for e in cdt.face(f).adjacent_edges() {
            // f is on e's left; the face on its right has w(f) − δ(e)
            let d = along(e.fix());
            let w = [wf[0] - d[0], wf[1] - d[1], wf[2] - d[2]];
            let g = e.rev().face();
            match wind[g.fix().index()] {
                None => {
                    wind[g.fix().index()] = Some(w);
                    if let Some(g) = g.as_inner() {
                        stack.push(g.fix());
                    }
                }
                Some(o) if o != w => return Err("winding numbers inconsistent".into()),
                Some(_) => {}
            }
        }
    }
    // Output: the faces where the two sides' chains do not cancel. A's triangles are CCW when
    // `ccw_a` and B's the other way, so the sum is ±1 on only-A and only-B, 0 where both attach.
    let pos = |v: spade::handles::VertexHandle<Vx, (), spade::CdtEdge<()>, ()>| {
        [v.position().x, v.position().y]
    };
    let side_sign = if ccw_a { [1, -1] } else { [-1, 1] };
    let mut covered = [0.0f64; 3];
    let mut scale = 0.0f64;
    for f in cdt.inner_faces() {
        let [v0, v1, v2] = f.vertices();
        let ar = 0.5 * area2(pos(v0), pos(v1), pos(v2));
        scale += ar.abs();
        let w = wind[f.fix().index()].ok_or("face not reached from the outer face")?;
        for (c, &wi) in covered.iter_mut().zip(&w) {
            *c += wi as f64 * ar;
        }
        if w[0] != 0 || w[1] != 0 {
            out.attached_area += ar.abs();
        }
        if w[0] != 0 && w[0] != side_sign[0] || w[1] != 0 && w[1] != side_sign[1] {
            return Err(format!("side windings {w:?}: a side's triangles overlap"));
        }
        if w[2] != 0 && w[2] != side_sign[0] {
            return Err(format!(
                "section windings {w:?}: the section's triangles overlap"
            ));
        }
        let total = w[0] + w[1];
        if total == 0 {
            if w[2] != 0 && w[0] == 0 && w[1] == 0 {
                // inside the section, attached from neither side: a flat zone, oriented like A's
                let (i0, i1, i2) = (
                    vid[v0.fix().index()],
                    vid[v1.fix().index()],
                    vid[v2.fix().index()],
                );
                out.flat
                    .push(if ccw_a { [i0, i1, i2] } else { [i0, i2, i1] });
            }
            continue;
        }
        if total.abs() > 1 {
            return Err(format!("region covered {total} times"));
        }
        out.output_area += ar.abs();
        let (i0, i1, i2) = (
            vid[v0.fix().index()],
            vid[v1.fix().index()],
            vid[v2.fix().index()],
        );
        // spade's faces are counter-clockwise
        out.triangles.push(if total > 0 {
            [i0, i1, i2]
        } else {
            [i0, i2, i1]
        });
    }
    // sanity: each side's signed covered area is its triangles' signed area (the chains are
    // exact combinatorially; only the rounding of crossing points moves area)
    for (side, &tris) in layers.iter().enumerate() {
        let mut want = 0.0;
        for t in tris {
            want += 0.5 * area2(q(t[0])?, q(t[1])?, q(t[2])?);
        }
        if (covered[side] - want).abs() > 1e-7 * scale.max(f64::MIN_POSITIVE) {
            return Err(format!(
                "side {side}: winding covers {:.6e}, triangles {want:.6e}",
                covered[side]
            ));
        }
    }
    Ok(out)
}

fn ukey(p: FixedVertexHandle, q: FixedVertexHandle) -> (usize, usize) {
    (p.index().min(q.index()), p.index().max(q.index()))
}

/// Adds every original edge (`edges`, (min, max) ids) as a constraint and returns, per edge, its
/// chain: the CDT vertices along it from min to max. The chain is what spade built for the edge
/// (its returned sub-edges), kept up to date when a later constraint splits one of its sub-edges
/// (a crossing vertex on it, or spade rerouting it through a nearby vertex): a sub-edge p–q that is
/// no longer a constraint edge is replaced by p–w–q, w the common constraint neighbour of p and q
/// created by that insertion, else the one nearest the line pq. The chain of an edge is therefore
/// unique and the same whichever direction it is walked.
fn insert_constraints(
    cdt: &mut Cdt,
    handle: &FxHashMap<u32, FixedVertexHandle>,
    edges: &[(u32, u32)],
) -> Result<Vec<Vec<FixedVertexHandle>>, String> {
    let mut chains: Vec<Vec<FixedVertexHandle>> = Vec::with_capacity(edges.len());
    // every sub-edge of every chain → the chains running along it (collinear input edges share
    // sub-edges); its number of keys is checked against spade's number of constraint edges
    let mut owner: FxHashMap<(usize, usize), SmallVec<[usize; 2]>> = FxHashMap::default();
    // Input vertices lying exactly on an edge (spade's exact line walk, before any constraint):
    // the edge is inserted as its pieces between them. Inserted whole, a constraint that is split
    // at a crossing goes on from the rounded crossing point and can miss such a vertex by an ulp,
    // making a new vertex next to it.
    let pieces: Vec<Vec<FixedVertexHandle>> = edges
        .iter()
        .map(|&(x, y)| vertices_on_segment(cdt, handle[&x], handle[&y]))
        .collect();
    for (&(x, y), through) in edges.iter().zip(&pieces) {
        let nv = cdt.num_vertices();
        let mut chain = vec![through[0]];
        for w in through.windows(2) {
            let route = cdt.add_constraint_and_split(w[0], w[1], |p| Vx { p, id: NEW });
            for e in &route {
                let e = cdt.directed_edge(*e);
                if e.from().fix() != *chain.last().unwrap() {
                    return Err(format!("constraint {x}–{y}: spade's route is not a path"));
                }
                chain.push(e.to().fix());
            }
            if *chain.last().unwrap() != w[1] {
                return Err(format!(
                    "constraint {x}–{y}: spade's route does not reach its end"
                ));
            }
        }
        let me = chains.len();
        for w in chain.windows(2) {
            owner.entry(ukey(w[0], w[1])).or_default().push(me);
        }
        let new_vertices = cdt.num_vertices() > nv;
        chains.push(chain);
        if !new_vertices && cdt.num_constraints() == owner.len() {
            continue;
        }
        // Some sub-edges were split. They can only be split at a vertex of the new chain (a
        // crossing it created, or a vertex it was routed through): repair the chains owning a
        // sub-edge between two constraint neighbours of such a vertex, then check the count.
        let mut hit: Vec<usize> = Vec::new();
        for &w in &chains[me][1..chains[me].len() - 1] {
            let nbrs: Vec<FixedVertexHandle> = cdt
                .vertex(w)
                .out_edges()
                .filter(|e| e.is_constraint_edge())
                .map(|e| e.to().fix())
                .collect();
            for (i, &p) in nbrs.iter().enumerate() {
                for &q in &nbrs[i + 1..] {
                    if let Some(cs) = owner.get(&ukey(p, q)) {
                        hit.extend(cs.iter().filter(|&&c| c != me));
                    }
                }
            }
        }
        hit.sort_unstable();
        hit.dedup();
        for &c in &hit {
            let repaired = repair_chain(cdt, &chains[c], nv)?;
            for w in chains[c].windows(2) {
                let k = ukey(w[0], w[1]);
                if let Some(cs) = owner.get_mut(&k) {
                    cs.retain(|d| *d != c);
                    if cs.is_empty() {
                        owner.remove(&k);
                    }
                }
            }
            for w in repaired.windows(2) {
                owner.entry(ukey(w[0], w[1])).or_default().push(c);
            }
            chains[c] = repaired;
        }
        if cdt.num_constraints() == owner.len() {
            continue;
        }
        // not local after all: repair every chain
        for chain in chains.iter_mut() {
            *chain = repair_chain(cdt, chain, nv)?;
        }
        owner.clear();
        for (c, chain) in chains.iter().enumerate() {
            for w in chain.windows(2) {
                owner.entry(ukey(w[0], w[1])).or_default().push(c);
            }
        }
        if cdt.num_constraints() != owner.len() {
            return Err(format!(
                "constraint {x}–{y}: {} constraint edges, {} on the chains",
                cdt.num_constraints(),
                owner.len()
            ));
        }
    }
    Ok(chains)
}

/// The vertices of `cdt` on the segment from `x` to `y` (both included), in order: exact, from
/// spade's line walk (robust orientation tests on the stored coordinates).
fn vertices_on_segment(
    cdt: &Cdt,
    x: FixedVertexHandle,
    y: FixedVertexHandle,
) -> Vec<FixedVertexHandle> {
    let mut out = vec![x];
    let mut push = |v: FixedVertexHandle| {
        if *out.last().unwrap() != v {
            out.push(v);
        }
    };
    for i in LineIntersectionIterator::new_from_handles(cdt, x, y) {
        match i {
            Intersection::VertexIntersection(v) => push(v.fix()),
            Intersection::EdgeOverlap(e) => {
                push(e.from().fix());
                push(e.to().fix());
            }
            Intersection::EdgeIntersection(_) => {}
        }
    }
    push(y);
    out
}

/// `chain` with every sub-edge that is no longer a constraint edge replaced by the constraint path
/// through a common constraint neighbour (see `insert_constraints`); `nv`: vertices before the last
/// insertion (a vertex it created is preferred).
fn repair_chain(
    cdt: &Cdt,
    chain: &[FixedVertexHandle],
    nv: usize,
) -> Result<Vec<FixedVertexHandle>, String> {
    let is_constraint = |p: FixedVertexHandle, q: FixedVertexHandle| {
        cdt.get_edge_from_neighbors(p, q)
            .is_some_and(|e| e.is_constraint_edge())
    };
    if chain.windows(2).all(|w| is_constraint(w[0], w[1])) {
        return Ok(chain.to_vec());
    }
    let pos = |h: FixedVertexHandle| {
        let p = cdt.vertex(h).position();
        [p.x, p.y]
    };
    let mut out = vec![chain[0]];
    // pending sub-edges, last one first
    let mut todo: Vec<FixedVertexHandle> = chain[1..].iter().rev().copied().collect();
    let mut budget = 4 * cdt.num_vertices() + 16;
    while let Some(qh) = todo.pop() {
        let ph = *out.last().unwrap();
        if is_constraint(ph, qh) {
            out.push(qh);
            continue;
        }
        budget = budget.checked_sub(1).ok_or("chain repair does not end")?;
        let (p, q) = (pos(ph), pos(qh));
        let mut best: Option<(bool, f64, FixedVertexHandle)> = None;
        for e in cdt.vertex(ph).out_edges() {
            if !e.is_constraint_edge() {
                continue;
            }
            let w = e.to().fix();
            if w == qh || !is_constraint(w, qh) {
                continue;
            }
            let c = pos(w);
            // w must lie between p and q along pq
            let t = (c[0] - p[0]) * (q[0] - p[0]) + (c[1] - p[1]) * (q[1] - p[1]);
            let l2 = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
            if t <= 0.0 || t >= l2 {
                continue;
            }
            let key = (w.index() < nv, orient2d(p, c, q).abs(), w);
            if best.is_none_or(|b| (key.0, key.1) < (b.0, b.1)) {
                best = Some(key);
            }
        }
        let Some((_, _, w)) = best else {
            return Err("a split sub-edge has no constraint path around it".into());
        };
        todo.push(qh);
        todo.push(w);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uvmap(pts: &[(u32, [f64; 2])]) -> HashMap<u32, [f64; 2]> {
        pts.iter().copied().collect()
    }

    fn area(uv: &HashMap<u32, [f64; 2]>, o: &Overlay, t: [u32; 3]) -> f64 {
        let q = |v: u32| {
            if v >= 1000 {
                o.new_vertices[(v - 1000) as usize]
            } else {
                uv[&v]
            }
        };
        0.5 * area2(q(t[0]), q(t[1]), q(t[2]))
    }

    #[test]
    fn same_region_different_triangulations_cancel() {
        // unit square, A splits along one diagonal, B along the other
        let uv = uvmap(&[
            (0, [0.0, 0.0]),
            (1, [1.0, 0.0]),
            (2, [1.0, 1.0]),
            (3, [0.0, 1.0]),
        ]);
        let a = [[0, 1, 2], [0, 2, 3]];
        let b = [[0, 3, 1], [1, 3, 2]]; // clockwise in (u,v): outward from B
        let o = overlay(&uv, &a, &b, true, 1000).unwrap();
        assert!(o.triangles.is_empty(), "{:?}", o.triangles);
        assert!((o.attached_area - 1.0).abs() < 1e-12);
        // the diagonals cross at the centre: both get split there
        assert_eq!(o.new_vertices, vec![[0.5, 0.5]]);
        let mut s = o.splits.clone();
        s.sort();
        assert_eq!(s, vec![((0, 2), vec![1000]), ((1, 3), vec![1000])]);
    }

    #[test]
    fn overlapping_but_different_regions() {
        // A attaches the rectangle [0,2]x[0,1] (CCW = outward from A), B the triangle (1,0),(3,0),(1,1);
        // they overlap in the quadrilateral (1,0),(2,0),(2,.5),(1,1)
        let uv = uvmap(&[
            (0, [0.0, 0.0]),
            (1, [2.0, 0.0]),
            (2, [2.0, 1.0]),
            (3, [0.0, 1.0]),
            (4, [1.0, 0.0]),
            (5, [3.0, 0.0]),
            (6, [1.0, 1.0]),
        ]);
        let a = [[0, 4, 6], [0, 6, 3], [4, 1, 2], [4, 2, 6]];
        let b = [[4, 6, 5]]; // clockwise in (u,v): outward from B
        let o = overlay(&uv, &a, &b, true, 1000).unwrap();
        // only-A: square minus the part of B inside it; only-B: B outside x ≤ 2
        // B ∩ square = triangle (1,0),(2,0),(2,.5),(1,1) region: area 1 - 0.25 = 0.75
        let (mut pos, mut neg) = (0.0, 0.0);
        for &t in &o.triangles {
            let ar = area(&uv, &o, t);
            if ar > 0.0 {
                pos += ar
            } else {
                neg -= ar
            }
        }
        assert!((pos - (2.0 - 0.75)).abs() < 1e-12, "only-A area {pos}");
        assert!((neg - (1.0 - 0.75)).abs() < 1e-12, "only-B area {neg}");
        assert!((o.attached_area - 2.25).abs() < 1e-12);
        // B's hypotenuse (5,6) crosses A's edges (1,2) at (2,.5) and (2,4) at (5/3,2/3)
        assert_eq!(o.new_vertices.len(), 2);
        let id_of = |p: [f64; 2]| {
            1000 + o
                .new_vertices
                .iter()
                .position(|q| (q[0] - p[0]).abs() + (q[1] - p[1]).abs() < 1e-12)
                .unwrap() as u32
        };
        let (m, n) = (id_of([2.0, 0.5]), id_of([5.0 / 3.0, 2.0 / 3.0]));
        let mut s = o.splits.clone();
        s.sort();
        assert_eq!(
            s,
            vec![
                ((1, 2), vec![m]),
                ((2, 4), vec![n]),
                ((4, 5), vec![1]), // vertex 1 lies on B's edge (4,5)
                ((5, 6), vec![m, n]),
            ]
        );
        // the output is a closed chain: every edge used once in each direction, except its boundary
        let mut count: HashMap<(u32, u32), i32> = HashMap::new();
        for t in &o.triangles {
            for k in 0..3 {
                let (x, y) = (t[k], t[(k + 1) % 3]);
                *count.entry((x.min(y), x.max(y))).or_default() += if x < y { 1 } else { -1 };
            }
        }
        count.retain(|_, c| *c != 0);
        // boundary of only-A ∪ only-B (as a chain): square boundary + B outside + the overlap edges
        assert!(count.values().all(|c| c.abs() == 1));
    }

    #[test]
    fn duplicate_uv_is_an_error() {
        let uv = uvmap(&[
            (0, [0.0, 0.0]),
            (1, [1.0, 0.0]),
            (2, [0.0, 1.0]),
            (3, [1.0, 0.0]),
        ]);
        assert!(overlay(&uv, &[[0, 1, 2]], &[[0, 2, 3]], true, 1000).is_err());
    }

    #[test]
    fn folded_triangle_is_an_error() {
        let uv = uvmap(&[(0, [0.0, 0.0]), (1, [1.0, 0.0]), (2, [0.0, 1.0])]);
        assert!(overlay(&uv, &[[0, 2, 1]], &[], true, 1000).is_err());
    }

    #[test]
    fn flat_zone_left_by_both_sides_vanishes() {
        // square [0,2]x[0,1]; both sides attach the left half [0,1]x[0,1], triangulated differently,
        // and leave the right half (a flat zone, triangulated differently too): nothing is output
        let uv = uvmap(&[
            (0, [0.0, 0.0]),
            (1, [1.0, 0.0]),
            (2, [2.0, 0.0]),
            (3, [2.0, 1.0]),
            (4, [1.0, 1.0]),
            (5, [0.0, 1.0]),
            (6, [0.5, 0.5]), // a sample of B only
        ]);
        let a = [[0, 1, 4], [0, 4, 5]];
        let b = [[0, 6, 1], [1, 6, 4], [4, 6, 5], [5, 6, 0]];
        let o = overlay(&uv, &a, &b, true, 1000).unwrap();
        assert!(o.triangles.is_empty(), "{:?}", o.triangles);
        assert!((o.attached_area - 1.0).abs() < 1e-12);
        // B's sample 6 lies on A's diagonal 0–4, which now passes through it
        assert!(o.splits.contains(&((0, 4), vec![6])));
    }

    /// An input recorded from a real face: (u,v), A, B, ccw_a.
    type Recorded = (HashMap<u32, [f64; 2]>, Vec<[u32; 3]>, Vec<[u32; 3]>, bool);

    fn recorded(json: &str) -> Recorded {
        let j: serde_json::Value = serde_json::from_str(json).unwrap();
        let uv = serde_json::from_value::<Vec<(u32, [f64; 2])>>(j["uv"].clone())
            .unwrap()
            .into_iter()
            .collect();
        (
            uv,
            serde_json::from_value(j["a"].clone()).unwrap(),
            serde_json::from_value(j["b"].clone()).unwrap(),
            j["ccw_a"].as_bool().unwrap(),
        )
    }

    /// Signed area of triangles (new vertices numbered from `first_new`).
    fn signed_area(
        uv: &HashMap<u32, [f64; 2]>,
        o: &Overlay,
        first_new: u32,
        tris: &[[u32; 3]],
    ) -> f64 {
        let q = |v: u32| {
            if v >= first_new {
                o.new_vertices[(v - first_new) as usize]
            } else {
                uv[&v]
            }
        };
        tris.iter()
            .map(|t| 0.5 * area2(q(t[0]), q(t[1]), q(t[2])))
            .sum()
    }

    /// The output as a 2-chain is A + B (both as given): same signed area, same boundary.
    fn assert_output_is_a_plus_b(
        uv: &HashMap<u32, [f64; 2]>,
        a: &[[u32; 3]],
        b: &[[u32; 3]],
        o: &Overlay,
        first_new: u32,
    ) {
        let want = signed_area(uv, o, first_new, a) + signed_area(uv, o, first_new, b);
        let got = signed_area(uv, o, first_new, &o.triangles);
        let scale = signed_area(uv, o, first_new, a).abs() + signed_area(uv, o, first_new, b).abs();
        assert!(
            (got - want).abs() <= 1e-9 * scale,
            "output {got}, A + B {want}"
        );
        // boundary: every input edge split along its chain, then the directed edges summed
        let chain = |x: u32, y: u32| -> Vec<u32> {
            let key = (x.min(y), x.max(y));
            let mut c = vec![key.0];
            if let Some((_, inner)) = o.splits.iter().find(|s| s.0 == key) {
                c.extend(inner);
            }
            c.push(key.1);
            if x > y {
                c.reverse();
            }
            c
        };
        let mut net: HashMap<(u32, u32), i32> = HashMap::new();
        let mut add = |x: u32, y: u32, s: i32| {
            *net.entry((x.min(y), x.max(y))).or_default() += if x < y { s } else { -s };
        };
        for t in a.iter().chain(b) {
            for k in 0..3 {
                for w in chain(t[k], t[(k + 1) % 3]).windows(2) {
                    add(w[0], w[1], 1);
                }
            }
        }
        for t in &o.triangles {
            for k in 0..3 {
                add(t[k], t[(k + 1) % 3], -1);
            }
        }
        net.retain(|_, c| *c != 0);
        assert!(
            net.is_empty(),
            "boundaries differ on {:?}",
            net.iter().take(5).collect::<Vec<_>>()
        );
    }

    #[test]
    fn elephant_face_175_labels_by_winding() {
        // The greedy chain walk of the flood fill lost part of side A here ("fill covers
        // 2.779545e-2, triangles 2.781411e-2") and the face fell back to two sheets.
        let (uv, a, b, ccw_a) = recorded(include_str!("testdata/overlay_elephant_face175.json"));
        let o = overlay(&uv, &a, &b, ccw_a, 1_000_000).unwrap();
        assert_output_is_a_plus_b(&uv, &a, &b, &o, 1_000_000);
    }

    #[test]
    fn vertex_exactly_on_an_edge_gets_no_twin() {
        // balloondog_box: an edge of B passes exactly through a vertex of A (orient2d == 0), but
        // only after crossing other constraints; spade continued from a rounded crossing point and
        // made a new vertex 4e-17 away from it (the surface then had two coplanar triangles
        // overlapping along an ulp-wide sliver).
        let (uv, a, b, ccw_a) = recorded(include_str!(
            "testdata/overlay_balloondog_box_vertex_on_edge.json"
        ));
        let (p, q) = (uv[&4801], uv[&4819]);
        assert_eq!(orient2d(p, q, uv[&4529]), 0.0);
        let o = overlay(&uv, &a, &b, ccw_a, 1_000_000).unwrap();
        assert_output_is_a_plus_b(&uv, &a, &b, &o, 1_000_000);
        for n in &o.new_vertices {
            for (v, p) in &uv {
                let d = (n[0] - p[0]).abs() + (n[1] - p[1]).abs();
                assert!(d > 1e-12, "new vertex {n:?} is {d:e} from vertex {v}");
            }
        }
        let split = o.splits.iter().find(|s| s.0 == (4801, 4819)).unwrap();
        assert!(split.1.contains(&4529), "{split:?}");
    }

    #[test]
    fn horsers_face_608_snapped_crossing() {
        // Vertex 3641 is a crossing snapped between two sections: its 3D point is the midpoint,
        // while the pool keeps this plane's own (u,v), 0.018 lower; 5162 likewise. In the pool's
        // (u,v) B's triangle [3641, 5317, 5316] is folded (the old overlay refused the face); in
        // the (u,v) of the 3D points (what glue passes for a vertex on several planes) the
        // triangulation is consistent and the overlay outputs B's region minus A's.
        let mut uv: HashMap<u32, [f64; 2]> = uvmap(&[
            (986, [-41.83683185902107, 44.86600000000001]),
            (3641, [-41.83683185902105, 51.263048128342284]),
            (5162, [-42.61811597849294, 45.63468193638729]),
            (5316, [-41.89049749048106, 51.05]),
            (5317, [-41.970995937671056, 50.71]),
            (5318, [-42.530012932046006, 47.0]),
            (5319, [-42.561317883731, 46.76]),
        ]);
        let a = [[986, 5318, 5317]];
        let b = [
            [3641, 5316, 986],
            [3641, 5317, 5316],
            [986, 5316, 5317],
            [986, 5317, 5318],
            [986, 5318, 5319],
            [986, 5319, 5162],
        ];
        // B's triangles are counter-clockwise (ccw_a = false); [3641, 5317, 5316] is not
        let folded = |uv: &HashMap<u32, [f64; 2]>| orient2d(uv[&3641], uv[&5317], uv[&5316]) < 0.0;
        assert!(folded(&uv));
        uv.insert(3641, [-41.83683185902105, 51.281201483525976]);
        uv.insert(5162, [-42.61811597849294, 45.63581294717788]);
        assert!(!folded(&uv));
        let o = overlay(&uv, &a, &b, false, 1_000_000).unwrap();
        assert_output_is_a_plus_b(&uv, &a, &b, &o, 1_000_000);
        // A's triangle is inside B's region: only B's remainder is output
        let area_a = signed_area(&uv, &o, 1_000_000, &a).abs();
        let area_b = signed_area(&uv, &o, 1_000_000, &b).abs();
        assert!((o.output_area - (area_b - area_a)).abs() < 1e-12 * area_b);
    }

    #[test]
    fn flat_zone_is_returned_with_the_section_layer() {
        // as above, with A's whole triangulation of the square [0,2]x[0,1] as the section layer
        let uv = uvmap(&[
            (0, [0.0, 0.0]),
            (1, [1.0, 0.0]),
            (2, [2.0, 0.0]),
            (3, [2.0, 1.0]),
            (4, [1.0, 1.0]),
            (5, [0.0, 1.0]),
            (6, [0.5, 0.5]),
        ]);
        let a = [[0, 1, 4], [0, 4, 5]];
        let b = [[0, 6, 1], [1, 6, 4], [4, 6, 5], [5, 6, 0]];
        let s = [[0, 1, 4], [0, 4, 5], [1, 2, 4], [2, 3, 4]];
        let o = overlay_with_section(&uv, &a, &b, &s, true, 1000).unwrap();
        assert!(o.triangles.is_empty(), "{:?}", o.triangles);
        let flat: f64 = o.flat.iter().map(|&t| area(&uv, &o, t)).sum();
        // the right half, counter-clockwise like A's triangles
        assert!((flat - 1.0).abs() < 1e-12, "{flat} {:?}", o.flat);
        assert!(o.flat.iter().all(|&t| area(&uv, &o, t) > 0.0));
        // without the layer nothing is returned as flat
        assert!(overlay(&uv, &a, &b, true, 1000).unwrap().flat.is_empty());
    }
}
