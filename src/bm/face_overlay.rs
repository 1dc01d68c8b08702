//! Overlay of the two cells' attached regions on one shared face (2D, in the plane's (u,v) frame).
//!
//! The two cells A and B of a face triangulate its section independently (different point sets:
//! each has its own branching samples; different triangulations of nearly coplanar points). The
//! surface on the face is the oriented symmetric difference of the attached regions X_A and X_B:
//! where only A attaches, the region oriented outward from A; only B: outward from B; both: interior;
//! neither: a flat zone (nothing). To get it, a constrained Delaunay triangulation (spade) of all
//! vertices of X_A and X_B with every edge of their triangles as a constraint gives a common
//! refinement. Its triangles are labelled by flood fill: from each triangle of X_A, across every edge
//! that is not on an edge of X_A (and likewise for B). Where two constraints cross, spade inserts a
//! new vertex; every original edge that got vertices on it (crossings, or existing vertices lying
//! exactly on it) is returned with its chain so that the caller can split the 3D triangles that use
//! it (no T-junctions).
//!
//! Every inconsistency (two ids at one (u,v), a folded triangle, a flood fill that leaks, a chain that
//! cannot be followed, a panic inside spade) is an `Err` with the reason: the caller then keeps its
//! per-side output for that face.
use crate::geom::predicates::orient2d;
use spade::handles::{FixedFaceHandle, FixedVertexHandle, InnerTag};
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};
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

fn area2(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> f64 {
    (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
}

/// Overlay X_A (`a`) and X_B (`b`), both oriented outward from their own cell, vertices in global ids
/// with their (u,v) in `uv`. `ccw_a`: a triangle oriented outward from A is counter-clockwise in
/// (u,v). New vertices get ids from `first_new` on.
pub fn overlay(
    uv: &HashMap<u32, [f64; 2]>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    // spade asserts on some inconsistent inputs: keep them from unwinding through the caller
    std::panic::catch_unwind(|| overlay_inner(uv, a, b, None, ccw_a, first_new))
        .unwrap_or_else(|_| Err("constrained triangulation panicked".into()))
}

/// [`overlay`] with a third layer `s`: A's triangulation of the whole section (attached or not,
/// oriented like A's). Its edges are constraints too, and the triangles inside `s` but in neither
/// X_A nor X_B are returned in [`Overlay::flat`] (the flat zones, for `thicken`).
pub fn overlay_with_section(
    uv: &HashMap<u32, [f64; 2]>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    s: &[[u32; 3]],
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    std::panic::catch_unwind(|| overlay_inner(uv, a, b, Some(s), ccw_a, first_new))
        .unwrap_or_else(|_| Err("constrained triangulation panicked".into()))
}

type Cdt = ConstrainedDelaunayTriangulation<Vx>;

fn overlay_inner(
    uv: &HashMap<u32, [f64; 2]>,
    a: &[[u32; 3]],
    b: &[[u32; 3]],
    s: Option<&[[u32; 3]]>,
    ccw_a: bool,
    first_new: u32,
) -> Result<Overlay, String> {
    let q = |v: u32| -> Result<[f64; 2], String> {
        uv.get(&v)
            .copied()
            .ok_or_else(|| format!("vertex {v} has no (u,v)"))
    };
    // layers: A, B and optionally the whole section (A's triangulation)
    let mut layers: Vec<(&[[u32; 3]], bool)> = vec![(a, ccw_a), (b, !ccw_a)];
    if let Some(s) = s {
        layers.push((s, ccw_a));
    }
    // sides' triangles, checked for orientation (a fold would make the flood fill meaningless)
    for &(tris, ccw) in &layers {
        for t in tris {
            let o = orient2d(q(t[0])?, q(t[1])?, q(t[2])?);
            if o != 0.0 && (o > 0.0) != ccw {
                return Err(format!("triangle {t:?} is folded in (u,v)"));
            }
        }
    }
    let mut cdt = Cdt::new();
    let mut handle: HashMap<u32, FixedVertexHandle> = HashMap::new();
    let mut ids: Vec<u32> = layers
        .iter()
        .flat_map(|l| l.0.iter())
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
    // constraints: every edge of both sides, with the sides it bounds
    let mut edges: HashMap<(u32, u32), u8> = HashMap::new();
    for (side, &(tris, _)) in layers.iter().enumerate() {
        let bit = 1u8 << side;
        for t in tris {
            for k in 0..3 {
                let (x, y) = (t[k], t[(k + 1) % 3]);
                *edges.entry((x.min(y), x.max(y))).or_default() |= bit;
            }
        }
    }
    let mut edge_list: Vec<((u32, u32), u8)> = edges.into_iter().collect();
    edge_list.sort_unstable();
    for &((x, y), _) in &edge_list {
        cdt.add_constraint_and_split(handle[&x], handle[&y], |p| Vx { p, id: NEW });
    }
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
    // chains of the original edges; bits on the CDT edges
    let mut bits = vec![0u8; cdt.num_undirected_edges()];
    let mut chains: HashMap<(u32, u32), Vec<FixedVertexHandle>> = HashMap::new();
    for &((x, y), bit) in &edge_list {
        let chain = follow(&cdt, handle[&x], handle[&y])?;
        for w in chain.windows(2) {
            let e = cdt
                .get_edge_from_neighbors(w[0], w[1])
                .ok_or("chain edge missing")?;
            bits[e.fix().as_undirected().index()] |= bit;
        }
        if chain.len() > 2 {
            let inner = chain[1..chain.len() - 1]
                .iter()
                .map(|h| vid[h.index()])
                .collect();
            out.splits.push(((x, y), inner));
        }
        chains.insert((x, y), chain);
    }
    // flood fill from each side's triangles across the edges not on that side's edges
    let nf = cdt.num_all_faces();
    let mut inside = vec![vec![false; nf]; layers.len()];
    for (side, &(tris, ccw)) in layers.iter().enumerate() {
        let bit = 1u8 << side;
        let mut stack: Vec<FixedFaceHandle<InnerTag>> = Vec::new();
        for t in tris {
            let (p0, p1, p2) = (q(t[0])?, q(t[1])?, q(t[2])?);
            if orient2d(p0, p1, p2) == 0.0 {
                continue;
            }
            // walk the first edge counter-clockwise: the triangle is on its left
            let (x, y) = if ccw { (t[0], t[1]) } else { (t[1], t[0]) };
            // the first CDT edge from x along the original edge; chains were followed from the
            // smaller id, and the walk is greedy, so the other direction is followed anew
            let reverse;
            let chain = if x < y {
                &chains[&(x, y)]
            } else {
                reverse = follow(&cdt, handle[&x], handle[&y])?;
                &reverse
            };
            let (c0, c1) = (chain[0], chain[1]);
            let e = cdt
                .get_edge_from_neighbors(c0, c1)
                .ok_or("chain edge missing")?;
            let f = e
                .face()
                .as_inner()
                .ok_or("triangle side faces the outer face")?;
            if !inside[side][f.fix().index()] {
                inside[side][f.fix().index()] = true;
                stack.push(f.fix());
            }
        }
        while let Some(f) = stack.pop() {
            for e in cdt.face(f).adjacent_edges() {
                if bits[e.as_undirected().fix().index()] & bit != 0 {
                    continue;
                }
                let g = e
                    .rev()
                    .face()
                    .as_inner()
                    .ok_or("flood fill leaked to the outer face")?;
                if !inside[side][g.fix().index()] {
                    inside[side][g.fix().index()] = true;
                    stack.push(g.fix());
                }
            }
        }
    }
    // areas: the fill must cover exactly each side's triangles
    let pos = |v: spade::handles::VertexHandle<Vx, (), spade::CdtEdge<()>, ()>| {
        [v.position().x, v.position().y]
    };
    let mut filled = vec![0.0f64; layers.len()];
    let mut scale = 0.0f64;
    for f in cdt.inner_faces() {
        let [v0, v1, v2] = f.vertices();
        let ar = 0.5 * area2(pos(v0), pos(v1), pos(v2)).abs();
        scale += ar;
        let (ia, ib) = (inside[0][f.fix().index()], inside[1][f.fix().index()]);
        if ia {
            filled[0] += ar;
        }
        if ib {
            filled[1] += ar;
        }
        if ia || ib {
            out.attached_area += ar;
        }
        if layers.len() > 2 && inside[2][f.fix().index()] {
            filled[2] += ar;
            if !ia && !ib {
                let (i0, i1, i2) = (
                    vid[v0.fix().index()],
                    vid[v1.fix().index()],
                    vid[v2.fix().index()],
                );
                out.flat
                    .push(if ccw_a { [i0, i1, i2] } else { [i0, i2, i1] });
            }
        }
        if ia != ib {
            out.output_area += ar;
            let (i0, i1, i2) = (
                vid[v0.fix().index()],
                vid[v1.fix().index()],
                vid[v2.fix().index()],
            );
            // spade's faces are counter-clockwise
            let ccw = if ia { ccw_a } else { !ccw_a };
            out.triangles
                .push(if ccw { [i0, i1, i2] } else { [i0, i2, i1] });
        }
    }
    for (side, &(tris, _)) in layers.iter().enumerate() {
        let mut want = 0.0;
        for t in tris {
            want += 0.5 * area2(q(t[0])?, q(t[1])?, q(t[2])?).abs();
        }
        if (filled[side] - want).abs() > 1e-9 * scale.max(f64::MIN_POSITIVE) {
            return Err(format!(
                "side {side}: fill covers {:.6e}, triangles {want:.6e}",
                filled[side]
            ));
        }
    }
    Ok(out)
}

/// The CDT vertices along the original segment from `x` to `y` (both included): from `x`, follow the
/// constraint edge heading most nearly towards `y`, each step getting closer.
fn follow(
    cdt: &Cdt,
    x: FixedVertexHandle,
    y: FixedVertexHandle,
) -> Result<Vec<FixedVertexHandle>, String> {
    let p = |h: FixedVertexHandle| {
        let q = cdt.vertex(h).position();
        [q.x, q.y]
    };
    let target = p(y);
    let mut chain = vec![x];
    let mut cur = x;
    let mut dist = f64::INFINITY;
    for _ in 0..cdt.num_vertices() {
        if cur == y {
            return Ok(chain);
        }
        let c = p(cur);
        let d = [target[0] - c[0], target[1] - c[1]];
        let dd = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let mut best: Option<(f64, FixedVertexHandle)> = None;
        for e in cdt.vertex(cur).out_edges() {
            if !e.is_constraint_edge() {
                continue;
            }
            let t = e.to().fix();
            if t == y {
                best = Some((2.0, t));
                break;
            }
            let w = p(t);
            let s = [w[0] - c[0], w[1] - c[1]];
            let ss = (s[0] * s[0] + s[1] * s[1]).sqrt();
            let cos = (s[0] * d[0] + s[1] * d[1]) / (ss * dd);
            if best.is_none_or(|b| cos > b.0) {
                best = Some((cos, t));
            }
        }
        let Some((cos, next)) = best else {
            return Err("chain: no constraint edge out of a vertex".into());
        };
        if cos < 0.5 {
            return Err("chain: no constraint edge towards the end".into());
        }
        let n = p(next);
        let nd = ((target[0] - n[0]).powi(2) + (target[1] - n[1]).powi(2)).sqrt();
        if next != y && nd >= dist.min(dd) {
            return Err("chain: no progress".into());
        }
        dist = nd;
        chain.push(next);
        cur = next;
    }
    Err("chain: too long".into())
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
