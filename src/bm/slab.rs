//! Flat zones (paper Fig. 13) given thickness inside the complex K, by refining K, never by moving
//! a vertex.
//!
//! A flat zone is a section triangle Z that no kept tetrahedron stands on, from either side. Its
//! *parent* is the tetrahedron (Z, a) of one side's Delaunay triangulation (the side whose kept
//! tetrahedra border the zone most). Each edge (v, a) from a vertex of Z to the apex is split at
//! the point p = v + s·(a − v) at height `thickness` above Z's plane (or half the apex's height
//! where that is less), and every tetrahedron of K around a split edge is split with it. Splitting
//! edges in one global order (the smallest split edge of a simplex first) refines every simplex
//! alike from all its sides, so K stays a conforming complex; the parts of the parent between Z
//! and its split points (the slab, a prism of three tetrahedra) are then kept. They lie inside the
//! parent, an empty Delaunay tetrahedron, so nothing they add can cross the rest of the solid, and
//! where a neighbour of Z is kept on the same side the slab shares faces with it and is joined to
//! the solid.
//!
//! An edge whose two ends share a plane lies on that plane (on the cell's boundary, in a section
//! or outside it) and is not split: then no split point lies on a plane, every slab face other
//! than Z has a split point, and no slab face lies on a plane: every section keeps R ∩ P = A.
//! Where Z borders a line of the arrangement, its slab tapers to that line.
use crate::fxhash::{FxHashMap, FxHashSet};
use smallvec::SmallVec;

/// The planes a global vertex lies on (sorted plane ids).
pub type Planes = SmallVec<[u32; 3]>;

/// A section triangle as one cell has it: global ids, outward from the cell, whether a kept
/// tetrahedron of the cell stands on it, and that cell's tetrahedron's fourth vertex (`u32::MAX`
/// in a cell without volume).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceTri {
    pub tri: [u32; 3],
    pub attached: bool,
    pub apex: u32,
}

/// One cell's section triangles on a face; a cell without volume gives its triangles a virtual
/// apex inside the cell (the cone over its section is then its triangulation).
#[derive(Clone, Debug, Default)]
pub struct Side {
    pub tris: Vec<FaceTri>,
    pub has_volume: bool,
}

/// The complex being refined: positions and planes per global vertex, the kept tetrahedra and
/// those that may be added later without leaving a section (`CellResult::fillable`).
pub struct Refinable<'a> {
    pub positions: &'a mut Vec<[f64; 3]>,
    pub planes: &'a mut Vec<Planes>,
    pub kept: &'a mut Vec<[u32; 4]>,
    pub fillable: &'a mut Vec<[u32; 4]>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlabStats {
    /// Flat-zone triangles that got a slab, and those left flat.
    pub thickened: u64,
    pub left: u64,
    /// Tetrahedra of the slabs, and the split points they added.
    pub tets: u64,
    pub points: u64,
    /// Thinnest slab (height of a split point above its zone's plane).
    pub min_thickness: f64,
}

fn key3(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

fn key4(mut t: [u32; 4]) -> [u32; 4] {
    t.sort_unstable();
    t
}

fn edge(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Give every flat zone of `faces` (per face, per side: its section triangles) a slab of
/// `thickness` inside K.
pub fn thicken(k: Refinable, faces: &[Vec<Side>], thickness: f64) -> SlabStats {
    let mut stats = SlabStats {
        min_thickness: f64::INFINITY,
        ..Default::default()
    };
    let (parents, unsided) = parents_of_zones(faces);
    stats.left += unsided;
    let fillable_set: FxHashSet<[u32; 4]> = k.fillable.iter().map(|&t| key4(t)).collect();
    let mut splits = split_points(k.positions, k.planes, &parents, thickness);
    // a split point off the line of its edge by rounding could invert a thin neighbour: such
    // edges are not split (each round drops at least one edge)
    loop {
        let all = k.kept.iter().chain(k.fillable.iter());
        let bad = inverted_edges(
            k.positions,
            &splits,
            all.chain(parents.iter().map(|p| &p.tet)),
        );
        if bad.is_empty() {
            break;
        }
        splits.retain(|e, _| !bad.contains(e));
    }
    let mut new_ids: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for (&(a, b), &(p, h)) in &splits {
        let id = k.positions.len() as u32;
        k.positions.push(p);
        k.planes.push(Planes::new());
        new_ids.insert((a, b), id);
        stats.min_thickness = stats.min_thickness.min(h);
    }
    stats.points = new_ids.len() as u64;
    let parent_keys: FxHashSet<[u32; 4]> = parents.iter().map(|p| key4(p.tet)).collect();
    let mut kept_out: Vec<[u32; 4]> = Vec::with_capacity(k.kept.len());
    for t in k.kept.iter() {
        kept_out.extend(split(*t, &new_ids));
    }
    let mut fillable_out: Vec<[u32; 4]> = Vec::new();
    for t in k
        .fillable
        .iter()
        .filter(|t| !parent_keys.contains(&key4(**t)))
    {
        fillable_out.extend(split(*t, &new_ids));
    }
    for p in &parents {
        let children = split(p.tet, &new_ids);
        let slab = slab_of(p, &children);
        stats.tets += slab.len() as u64;
        if slab.is_empty() {
            stats.left += 1;
        } else {
            stats.thickened += 1;
        }
        let slab_keys: FxHashSet<[u32; 4]> = slab.iter().map(|&t| key4(t)).collect();
        if fillable_set.contains(&key4(p.tet)) {
            fillable_out.extend(children.iter().filter(|t| !slab_keys.contains(&key4(**t))));
        }
        kept_out.extend(slab);
    }
    if stats.points == 0 {
        stats.min_thickness = 0.0;
    }
    *k.kept = kept_out;
    *k.fillable = fillable_out;
    stats
}

/// A flat-zone triangle and the tetrahedron (positive: the triangle is outward from the cell)
/// of the side chosen for its slab.
struct Parent {
    zone: [u32; 3],
    tet: [u32; 4],
}

/// Per flat zone (a component of flat triangles of one face, adjacent by edges), the side whose
/// attached triangles share most edges with the zone's border; its tetrahedra on the zone are the
/// parents. Returns them and how many flat triangles had no side with volume.
fn parents_of_zones(faces: &[Vec<Side>]) -> (Vec<Parent>, u64) {
    let mut parents = Vec::new();
    let mut claimed: FxHashSet<[u32; 4]> = FxHashSet::default();
    let mut unsided = 0;
    for sides in faces {
        let sides = &considered(sides)[..];
        let attached: FxHashSet<[u32; 3]> = sides
            .iter()
            .flat_map(|s| &s.tris)
            .filter(|t| t.attached)
            .map(|t| key3(t.tri))
            .collect();
        let mut flat: Vec<[u32; 3]> = sides
            .iter()
            .flat_map(|s| &s.tris)
            .map(|t| key3(t.tri))
            .filter(|k| !attached.contains(k))
            .collect();
        flat.sort_unstable();
        flat.dedup();
        for zone in edge_components(&flat) {
            let border = border_edges(&zone);
            let side = (0..sides.len())
                .filter(|&s| sides[s].tris.iter().any(|t| t.apex != u32::MAX))
                .max_by_key(|&s| {
                    let edges: FxHashSet<(u32, u32)> = sides[s]
                        .tris
                        .iter()
                        .filter(|t| t.attached)
                        .flat_map(|t| (0..3).map(move |i| edge(t.tri[i], t.tri[(i + 1) % 3])))
                        .collect();
                    // then a side with volume, then the first side
                    (
                        border.iter().filter(|e| edges.contains(e)).count(),
                        sides[s].has_volume,
                        std::cmp::Reverse(s),
                    )
                });
            let Some(side) = side else {
                unsided += zone.len() as u64;
                continue;
            };
            let by_key: FxHashMap<[u32; 3], &FaceTri> =
                sides[side].tris.iter().map(|t| (key3(t.tri), t)).collect();
            for z in &zone {
                match by_key.get(z).filter(|t| t.apex != u32::MAX) {
                    Some(t) => {
                        let tet = [t.tri[0], t.tri[1], t.tri[2], t.apex];
                        if claimed.insert(key4(tet)) {
                            parents.push(Parent { zone: t.tri, tet });
                        } else {
                            unsided += 1;
                        }
                    }
                    None => unsided += 1,
                }
            }
        }
    }
    (parents, unsided)
}

/// The sides of a face that decide its flat zones: those with volume where there are any (a cell
/// without volume triangulates its section in 2D, not necessarily as the other side does, and
/// the other side's triangles cover the same section).
pub fn considered(sides: &[Side]) -> Vec<&Side> {
    let any_volume = sides.iter().any(|s| s.has_volume);
    sides
        .iter()
        .filter(|s| s.has_volume || !any_volume)
        .collect()
}

/// Components of triangles adjacent through an edge.
fn edge_components(tris: &[[u32; 3]]) -> Vec<Vec<[u32; 3]>> {
    let mut by_edge: FxHashMap<(u32, u32), Vec<usize>> = FxHashMap::default();
    for (i, t) in tris.iter().enumerate() {
        for j in 0..3 {
            by_edge
                .entry(edge(t[j], t[(j + 1) % 3]))
                .or_default()
                .push(i);
        }
    }
    let mut seen = vec![false; tris.len()];
    let mut out = Vec::new();
    for start in 0..tris.len() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut stack = vec![start];
        let mut comp = Vec::new();
        while let Some(i) = stack.pop() {
            comp.push(tris[i]);
            let t = tris[i];
            for j in 0..3 {
                for &n in &by_edge[&edge(t[j], t[(j + 1) % 3])] {
                    if !seen[n] {
                        seen[n] = true;
                        stack.push(n);
                    }
                }
            }
        }
        out.push(comp);
    }
    out
}

/// Edges used by exactly one triangle of `tris`.
fn border_edges(tris: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut count: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for t in tris {
        for j in 0..3 {
            *count.entry(edge(t[j], t[(j + 1) % 3])).or_default() += 1;
        }
    }
    count
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Per edge (zone vertex, apex) of the parents whose ends share no plane: the split point and its
/// height above the zone. An edge shared by several parents is split once, where its first parent
/// puts it.
fn split_points(
    positions: &[[f64; 3]],
    planes: &[Planes],
    parents: &[Parent],
    thickness: f64,
) -> FxHashMap<(u32, u32), ([f64; 3], f64)> {
    use crate::sections::{cross, dot};
    let on_a_plane = |a: u32, b: u32| {
        planes[a as usize]
            .iter()
            .any(|g| planes[b as usize].contains(g))
    };
    let mut out: FxHashMap<(u32, u32), ([f64; 3], f64)> = FxHashMap::default();
    for p in parents {
        let z = p.zone.map(|v| positions[v as usize]);
        let n = cross(sub(z[1], z[0]), sub(z[2], z[0]));
        let len = dot(n, n).sqrt();
        let apex = positions[p.tet[3] as usize];
        let h = dot(n, sub(apex, z[0])).abs() / len;
        if !(h > 0.0 && len > 0.0) {
            continue;
        }
        let s = (thickness / h).min(0.5);
        for (&v, &pv) in p.zone.iter().zip(&z) {
            if on_a_plane(v, p.tet[3]) {
                continue;
            }
            let d = sub(apex, pv);
            out.entry(edge(v, p.tet[3])).or_insert((
                [pv[0] + s * d[0], pv[1] + s * d[1], pv[2] + s * d[2]],
                s * h,
            ));
        }
    }
    out
}

/// Split edges of tetrahedra that some child of their refinement would make flat or inverted (a
/// split point is off the line of its edge by rounding; a thin neighbour can flip): every split
/// edge of such a tetrahedron.
fn inverted_edges<'a>(
    positions: &[[f64; 3]],
    splits: &FxHashMap<(u32, u32), ([f64; 3], f64)>,
    tets: impl Iterator<Item = &'a [u32; 4]>,
) -> FxHashSet<(u32, u32)> {
    let base = positions.len() as u32;
    let list: Vec<((u32, u32), [f64; 3])> = splits.iter().map(|(&e, &(p, _))| (e, p)).collect();
    let ids: FxHashMap<(u32, u32), u32> = list
        .iter()
        .enumerate()
        .map(|(i, &(e, _))| (e, base + i as u32))
        .collect();
    let pos = |v: u32| {
        if v < base {
            positions[v as usize]
        } else {
            list[(v - base) as usize].1
        }
    };
    let orient = |t: [u32; 4]| {
        let c = |v: u32| {
            let q = pos(v);
            robust::Coord3D {
                x: q[0],
                y: q[1],
                z: q[2],
            }
        };
        robust::orient3d(c(t[0]), c(t[1]), c(t[2]), c(t[3]))
    };
    let mut bad = FxHashSet::default();
    for t in tets {
        let split_edges: Vec<(u32, u32)> = super::complex::TET_EDGES
            .iter()
            .map(|&(i, j)| edge(t[i], t[j]))
            .filter(|e| ids.contains_key(e))
            .collect();
        if split_edges.is_empty() {
            continue;
        }
        let whole = orient(*t);
        let flips = |c: &[u32; 4]| {
            let o = orient(*c);
            o == 0.0 || (o > 0.0) != (whole > 0.0)
        };
        if whole == 0.0 || split(*t, &ids).iter().any(flips) {
            bad.extend(split_edges);
        }
    }
    bad
}

/// `s` refined by the split edges: split at its smallest split edge (each child takes the point
/// for one end of it), then the children likewise. The same simplex is refined alike wherever it
/// appears, so shared faces of split tetrahedra still match.
pub fn split<const N: usize>(s: [u32; N], points: &FxHashMap<(u32, u32), u32>) -> Vec<[u32; N]> {
    let mut out = Vec::new();
    let mut stack = vec![s];
    while let Some(s) = stack.pop() {
        let mut smallest: Option<((u32, u32), usize, usize)> = None;
        for i in 0..N {
            for j in i + 1..N {
                let e = edge(s[i], s[j]);
                if points.contains_key(&e) && smallest.is_none_or(|(m, _, _)| e < m) {
                    smallest = Some((e, i, j));
                }
            }
        }
        match smallest {
            None => out.push(s),
            Some((e, i, j)) => {
                let p = points[&e];
                let (mut a, mut b) = (s, s);
                a[j] = p;
                b[i] = p;
                stack.push(b);
                stack.push(a);
            }
        }
    }
    out
}

/// The children of parent `p` that form its slab: those without the apex, if one of them stands
/// on the zone.
fn slab_of(p: &Parent, children: &[[u32; 4]]) -> Vec<[u32; 4]> {
    let below: Vec<[u32; 4]> = children
        .iter()
        .copied()
        .filter(|c| !c.contains(&p.tet[3]))
        .collect();
    if below.iter().any(|c| p.zone.iter().all(|v| c.contains(v))) {
        below
    } else {
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::assembly::{boundary_of, singularities};

    fn ids(pairs: &[((u32, u32), u32)]) -> FxHashMap<(u32, u32), u32> {
        pairs.iter().copied().collect()
    }

    #[test]
    fn a_tet_split_along_its_three_apex_edges_is_a_prism_and_a_top() {
        let t = [0, 1, 2, 3];
        let c = split(t, &ids(&[((0, 3), 4), ((1, 3), 5), ((2, 3), 6)]));
        assert_eq!(c.len(), 4);
        assert_eq!(c.iter().filter(|c| c.contains(&3)).count(), 1);
        // the children tile the tet: their boundary is the tet's, split on its three side faces
        let b = boundary_of(&c);
        assert_eq!(b.len(), 1 + 3 * 3);
        assert_eq!(singularities(&b), (0, 0));
    }

    #[test]
    fn two_tets_sharing_a_split_edge_stay_conforming() {
        // (0,1,2,3) and (0,2,1,4) share (0,1,2); split (0,1) and (1,2)
        let pts = ids(&[((0, 1), 5), ((1, 2), 6)]);
        let mut all = split([0, 1, 2, 3], &pts);
        all.extend(split([0, 2, 1, 4], &pts));
        assert_eq!(all.len(), 6);
        // the shared triangle is split alike from both sides: only the outer surface is open
        let b = boundary_of(&all);
        assert!(b.iter().all(|t| t.contains(&3) || t.contains(&4)));
        assert_eq!(singularities(&b), (0, 0));
        assert_eq!(b.len(), 10);
    }

    fn planes_share(f: &[u32; 3], g: u32, planes: &[Planes]) -> bool {
        f.iter().all(|&v| planes[v as usize].contains(&g))
    }

    fn planes(list: &[&[u32]]) -> Vec<Planes> {
        list.iter().map(|p| p.iter().copied().collect()).collect()
    }

    /// A unit tetrahedron standing on the flat triangle (0,1,2) of plane 0 (z = 0, outward -z),
    /// apex 3 at height 1.
    fn standing() -> (Vec<[f64; 3]>, Vec<Vec<Side>>) {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.2, 0.2, 1.0],
        ];
        let side = Side {
            tris: vec![FaceTri {
                tri: [0, 1, 2],
                attached: false,
                apex: 3,
            }],
            has_volume: true,
        };
        (positions, vec![vec![side]])
    }

    #[test]
    fn a_flat_triangle_gets_a_slab_of_the_asked_thickness() {
        let (mut positions, faces) = standing();
        let mut pl = planes(&[&[0], &[0], &[0], &[]]);
        let (mut kept, mut fillable) = (Vec::new(), vec![[0, 1, 2, 3]]);
        let s = thicken(
            Refinable {
                positions: &mut positions,
                planes: &mut pl,
                kept: &mut kept,
                fillable: &mut fillable,
            },
            &faces,
            0.01,
        );
        assert_eq!((s.thickened, s.left, s.tets, s.points), (1, 0, 3, 3));
        assert!((s.min_thickness - 0.01).abs() < 1e-12);
        // the slab is closed and the zone is its bottom; the top stays fillable
        let b = boundary_of(&kept);
        assert_eq!(b.len(), 8);
        assert!(b.iter().any(|t| key3(*t) == [0, 1, 2]));
        assert_eq!(singularities(&b), (0, 0));
        assert_eq!(fillable.len(), 1);
        assert!(fillable[0].contains(&3));
        assert!(positions[4..].iter().all(|p| (p[2] - 0.01).abs() < 1e-12));
    }

    #[test]
    fn a_zone_on_a_line_of_the_arrangement_tapers_to_it() {
        // the side face (0,1,3) lies on plane 1 (x = 0): its edges are not split, the slab is the
        // one tetrahedron through the split of (2,3), and no slab face lies on plane 1
        let (mut positions, faces) = standing();
        positions[3] = [0.0, 0.2, 1.0];
        let mut pl = planes(&[&[0, 1], &[0, 1], &[0], &[1]]);
        let (mut kept, mut fillable) = (Vec::new(), Vec::new());
        let k = Refinable {
            positions: &mut positions,
            planes: &mut pl,
            kept: &mut kept,
            fillable: &mut fillable,
        };
        let s = thicken(k, &faces, 0.01);
        assert_eq!((s.thickened, s.left, s.tets, s.points), (1, 0, 1, 1));
        assert_eq!(key4(kept[0]), [0, 1, 2, 4]);
        for i in 0..4 {
            let f = crate::bm::complex::outward_face(&kept[0], i);
            assert!(!planes_share(&f, 1, &pl) || key3(f) == [0, 1, 2]);
        }
    }

    #[test]
    fn a_zone_whose_apex_edges_all_lie_on_planes_is_left_flat() {
        let (mut positions, faces) = standing();
        positions[3] = [0.0, 0.0, 1.0];
        // 3 on plane 1 with 0 and 1, and on plane 2 with 2 and 0
        let mut pl = planes(&[&[0, 1, 2], &[0, 1], &[0, 2], &[1, 2]]);
        let (mut kept, mut fillable) = (Vec::new(), Vec::new());
        let k = Refinable {
            positions: &mut positions,
            planes: &mut pl,
            kept: &mut kept,
            fillable: &mut fillable,
        };
        let s = thicken(k, &faces, 0.01);
        assert_eq!((s.thickened, s.left, s.tets), (0, 1, 0));
        assert!(kept.is_empty());
    }
}
