//! Growing the kept complex K into the tetrahedra beside it by refining them, never by moving a
//! vertex: the one operation behind flat-zone slabs (`slab`) and the resolution of singular
//! edges and vertices (`singular`).
//!
//! A *growth* asks for the part of an unkept tetrahedron T near a *core* simplex σ of T (a face,
//! an edge or a vertex): every edge from a vertex of σ to a vertex of T outside σ is split at a
//! point near σ, and the children of T without a vertex outside σ are kept. Splitting an edge
//! splits every tetrahedron of the triangulation around it (kept, fillable and external alike),
//! always at the smallest split edge of a simplex first (one global order), so every simplex is
//! refined alike from all its sides and the triangulation stays conforming; the grown parts lie
//! inside T, so nothing can cross. A split point lies on the planes of both ends of its edge
//! (combinatorial plane membership), section triangles are refined with the tetrahedra, and a
//! child is kept only if each of its faces that lies on a plane is inside that plane's section:
//! the sections stay R ∩ P = A.
//!
//! Refinement cannot split an edge of a tetrahedron flat up to rounding (a child would flip);
//! those on the outer boundary of the cells' triangulations hold no volume and are taken out first
//! ([`drop_hull_slivers`]).
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::sections::{cross, dot, sub};
use rayon::prelude::*;
use smallvec::SmallVec;

/// The planes a global vertex lies on (plane ids).
pub type Planes = SmallVec<[u32; 3]>;

/// The union of the cells' triangulations in global ids, split into what K keeps, what survived
/// step 1 (`CellResult::fillable`) and the rest, with the section triangles inside their sections.
pub struct Triangulation<'a> {
    pub positions: &'a mut Vec<[f64; 3]>,
    pub planes: &'a mut Vec<Planes>,
    pub kept: &'a mut Vec<[u32; 4]>,
    pub fillable: &'a mut Vec<[u32; 4]>,
    pub external: &'a mut Vec<[u32; 4]>,
    /// Sorted keys of the section triangles inside their sections.
    pub internal: &'a mut FxHashSet<[u32; 3]>,
}

/// The part of `tet` (positively oriented, unkept) near `core` (some of its vertices).
#[derive(Clone, Debug, PartialEq)]
pub struct Growth {
    pub tet: [u32; 4],
    pub core: SmallVec<[u32; 3]>,
    /// Keep the children even where one is a sliver (the parts of a sliver near its core are
    /// slivers too; refusing them leaves a crack where the growth must close a gap).
    pub keep_slivers: bool,
}

/// What one refinement did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Grown {
    /// Per group of growths asked for: the tetrahedra it added to K (0: refused).
    pub tets_per_group: Vec<u64>,
    pub points: u64,
    /// The vertices of every tetrahedron K gained or lost (sorted, once each): only their stars
    /// in K changed, so only simplices through them can have changed on ∂K.
    pub touched: Vec<u32>,
}

pub fn key3(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

pub fn key4(mut t: [u32; 4]) -> [u32; 4] {
    t.sort_unstable();
    t
}

pub fn edge(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Split at `points` (per edge, where) and grow K by `groups` of growths, each group all or
/// nothing: a group is refused when one of its growths would keep no child containing its core,
/// or a child with a face on a plane outside the section. Edges whose points would flatten or
/// invert a child of some tetrahedron are not split. Growth tetrahedra not in the triangulation
/// (a cell without volume: the cone over its section) are added to it as external first.
pub fn grow(
    t: &mut Triangulation,
    groups: &[Vec<Growth>],
    mut points: FxHashMap<(u32, u32), [f64; 3]>,
) -> Grown {
    // only tetrahedra with the smallest vertex of a growth can be one of them
    let wanted: FxHashSet<[u32; 4]> = groups.iter().flatten().map(|g| key4(g.tet)).collect();
    let first = marks(t.positions.len(), wanted.iter().map(|k| k[0]));
    let known: FxHashSet<[u32; 4]> = t
        .kept
        .iter()
        .chain(t.fillable.iter())
        .chain(t.external.iter())
        .filter(|x| x.iter().any(|&v| first[v as usize]))
        .map(|&x| key4(x))
        .filter(|k| wanted.contains(k))
        .collect();
    for g in groups.iter().flatten() {
        if !known.contains(&key4(g.tet)) {
            t.external.push(g.tet);
        }
    }
    // the tetrahedra an edge to split can be on (two vertices at the ends of one), found in one
    // pass over each list: refusing edges below only drops ends, so later passes read these only
    let mut ends = marks(t.positions.len(), points.keys().flat_map(|e| [e.0, e.1]));
    let near = [&*t.kept, &*t.fillable, &*t.external].map(|list| {
        (list.iter().enumerate())
            .filter(|(_, x)| touches_two(x, &ends))
            .map(|(i, _)| i)
            .collect::<Vec<usize>>()
    });
    // each round drops at least one edge
    loop {
        let lists: [&[[u32; 4]]; 3] = [t.kept, t.fillable, t.external];
        let all = (0..3)
            .flat_map(|l| near[l].iter().map(move |&i| &lists[l][i]))
            .filter(|x| touches_two(x, &ends));
        let bad = inverted_edges(t.positions, &points, all);
        if bad.is_empty() {
            break;
        }
        points.retain(|e, _| !bad.contains(e));
        ends = marks(t.positions.len(), points.keys().flat_map(|e| [e.0, e.1]));
    }
    let ids = insert_points(t, &points);
    // a simplex is split only where two of its vertices end a split edge
    let ends = marks(t.positions.len(), ids.keys().flat_map(|e| [e.0, e.1]));
    let mut touched = Vec::new();
    split_all(t.kept, &near[0], &ends, &ids, Some(&mut touched));
    split_all(t.fillable, &near[1], &ends, &ids, None);
    split_all(t.external, &near[2], &ends, &ids, None);
    let refined: Vec<[u32; 3]> = t
        .internal
        .iter()
        .copied()
        .filter(|x| touches_two(x, &ends))
        .collect();
    for x in refined {
        t.internal.remove(&x);
        t.internal.extend(split(x, &ids).into_iter().map(key3));
    }
    let mut out = Grown {
        points: ids.len() as u64,
        ..Default::default()
    };
    let mut grown: FxHashSet<[u32; 4]> = FxHashSet::default();
    for group in groups {
        let children: Option<Vec<[u32; 4]>> = group
            .iter()
            .map(|g| kept_children(g, &ids, t.planes, t.internal, t.positions))
            .collect::<Option<Vec<_>>>()
            .map(|c| c.concat());
        let added = children.map_or(0, |c| {
            c.into_iter().filter(|x| grown.insert(key4(*x))).count()
        });
        out.tets_per_group.push(added as u64);
    }
    let moved = one_of(t.positions.len(), &grown);
    let mut taken: Vec<[u32; 4]> = t.fillable.iter().copied().filter(|x| moved(x)).collect();
    taken.extend(t.external.iter().copied().filter(|x| moved(x)));
    t.fillable.retain(|x| !moved(x));
    t.external.retain(|x| !moved(x));
    touched.extend(taken.iter().flatten());
    t.kept.extend(taken);
    touched.sort_unstable();
    touched.dedup();
    out.touched = touched;
    out
}

/// Replaces each tetrahedron of `list` with two vertices at `ends` by its children at the split
/// points `ids`, in place (the children where their parent was); `near` holds the positions of
/// every such tetrahedron (and maybe others), in increasing order. With `touched`, the vertices
/// of the children are pushed there.
fn split_all(
    list: &mut Vec<[u32; 4]>,
    near: &[usize],
    ends: &[bool],
    ids: &FxHashMap<(u32, u32), u32>,
    mut touched: Option<&mut Vec<u32>>,
) {
    let mut at = near
        .iter()
        .copied()
        .filter(|&i| touches_two(&list[i], ends))
        .peekable();
    if at.peek().is_none() {
        return;
    }
    // the runs between split tetrahedra copied whole; one allocation
    let mut out = Vec::with_capacity(list.len() + 64);
    let mut from = 0;
    for i in at {
        out.extend_from_slice(&list[from..i]);
        let children = split(list[i], ids);
        if let Some(touched) = touched.as_deref_mut() {
            touched.extend(children.iter().flatten());
        }
        out.extend(children);
        from = i + 1;
    }
    out.extend_from_slice(&list[from..]);
    *list = out;
}

/// Per vertex below `n`, whether it is one of `vertices`.
pub(super) fn marks(n: usize, vertices: impl Iterator<Item = u32>) -> Vec<bool> {
    let mut out = vec![false; n];
    for v in vertices {
        out[v as usize] = true;
    }
    out
}

/// Membership in `keys` (sorted keys of tetrahedra with vertices below `n_vertices`): a flag per
/// vertex of theirs spares hashing every tetrahedron that has a vertex of none of them, which is
/// most of a whole complex scanned for a few.
pub fn one_of(n_vertices: usize, keys: &FxHashSet<[u32; 4]>) -> impl Fn(&[u32; 4]) -> bool + '_ {
    let on = marks(n_vertices, keys.iter().flatten().copied());
    move |x: &[u32; 4]| x.iter().all(|&v| on[v as usize]) && keys.contains(&key4(*x))
}

/// Whether at least two vertices of `s` are marked (it may have a split edge).
fn touches_two<const N: usize>(s: &[u32; N], marked: &[bool]) -> bool {
    s.iter().filter(|&&v| marked[v as usize]).count() >= 2
}

/// The split points as new global vertices, each on the planes of both ends of its edge.
fn insert_points(
    t: &mut Triangulation,
    points: &FxHashMap<(u32, u32), [f64; 3]>,
) -> FxHashMap<(u32, u32), u32> {
    let mut list: Vec<(&(u32, u32), &[f64; 3])> = points.iter().collect();
    list.sort_unstable_by_key(|(e, _)| **e);
    let mut ids = FxHashMap::default();
    for (&(a, b), &p) in list {
        let common: Planes = t.planes[a as usize]
            .iter()
            .copied()
            .filter(|g| t.planes[b as usize].contains(g))
            .collect();
        ids.insert((a, b), t.positions.len() as u32);
        t.positions.push(p);
        t.planes.push(common);
    }
    ids
}

/// The children of `g.tet` without a vertex outside the core, or `None` if none of them contains
/// the core, one of them has a face on a plane outside the section, or (unless the growth keeps
/// slivers) one of them is a sliver.
fn kept_children(
    g: &Growth,
    ids: &FxHashMap<(u32, u32), u32>,
    planes: &[Planes],
    internal: &FxHashSet<[u32; 3]>,
    positions: &[[f64; 3]],
) -> Option<Vec<[u32; 4]>> {
    let outer: SmallVec<[u32; 3]> = g
        .tet
        .iter()
        .copied()
        .filter(|v| !g.core.contains(v))
        .collect();
    let near: Vec<[u32; 4]> = split(g.tet, ids)
        .into_iter()
        .filter(|c| !c.iter().any(|v| outer.contains(v)))
        .collect();
    let on_core = near.iter().any(|c| g.core.iter().all(|v| c.contains(v)));
    let in_sections = near.iter().all(|c| faces_in_sections(c, planes, internal));
    let solid = g.keep_slivers || near.iter().all(|c| !sliver(positions, c));
    (on_core && in_sections && solid).then_some(near)
}

/// Take out of the triangulation its tetrahedra that are flat up to rounding (`ROUNDING_FLAT`) with a face
/// on its outer boundary (a face no other tetrahedron shares) and no face on a plane: the contour
/// points of one flat triangle of a sliced mesh, on two or more planes, lie on one oblique plane,
/// and where that plane bounds a cell's points the cell's hull is folded there by rounding into
/// such a tetrahedron. It holds no volume, but no edge of it can be split (a child would flip),
/// which blocks every refinement around it. A kept one is taken out only where that leaves ∂K as
/// it was up to the flat fold: its faces on ∂K (outer or beside an unkept tetrahedron) are exactly
/// one side of it, the faces beside kept tetrahedra the other, so ∂K trades one side's triangles
/// for the other's, with the same border. Returns how many were taken out.
pub fn drop_hull_slivers(t: &mut Triangulation) -> u64 {
    let (planes, positions) = (&*t.planes, &*t.positions);
    let flat_off_planes = |x: &[u32; 4]| {
        flat_to_rounding(positions, x)
            && !(0..4).any(|i| on_a_plane(planes, &key3(super::complex::outward_face(x, i))))
    };
    // tetrahedra numbered as the table has them: kept first, then fillable, then external
    let lists: [&[[u32; 4]]; 3] = [t.kept, t.fillable, t.external];
    // such slivers are rare: the face table of everything is built only when there are some
    let mut candidates: Vec<u32> = Vec::new();
    let mut first = 0u32;
    for list in lists {
        let found: Vec<u32> = (list.par_iter().enumerate())
            .filter(|(_, x)| flat_off_planes(x))
            .map(|(j, _)| first + j as u32)
            .collect();
        candidates.extend(found);
        first += list.len() as u32;
    }
    if candidates.is_empty() {
        return 0;
    }
    let table = super::faces::FaceTable::of_lists(&lists);
    let n_kept = t.kept.len() as u32;
    // `x` (number `j`, flat and off the planes) has a face no other tetrahedron shares
    let goes = |j: u32, x: &[u32; 4]| -> bool {
        let fs: [[u32; 3]; 4] = std::array::from_fn(|i| key3(super::complex::outward_face(x, i)));
        if j >= n_kept {
            return true;
        }
        let side = flat_sides(x.map(|v| positions[v as usize]));
        // beside a kept tetrahedron: the face's kept owners are this one and that one
        let beside_kept: [bool; 4] =
            std::array::from_fn(|i| table.owners(&fs[i]).filter(|&o| o < n_kept).count() == 2);
        (0..4).all(|i| beside_kept[i] == side[i]) || (0..4).all(|i| beside_kept[i] != side[i])
    };
    // only a tetrahedron with a face no other one shares can go: looked up from those faces
    let tet = |j: u32| {
        let (nf, j) = (t.fillable.len() as u32, j as usize);
        match j.checked_sub(n_kept as usize) {
            None => t.kept[j],
            Some(f) if f < nf as usize => t.fillable[f],
            Some(f) => t.external[f - nf as usize],
        }
    };
    let outer = |x: &[u32; 4]| {
        (0..4).any(|i| table.codes(&key3(super::complex::outward_face(x, i))).len() == 1)
    };
    let going: Vec<u32> = (candidates.into_iter())
        .filter(|&j| {
            let x = tet(j);
            outer(&x) && goes(j, &x)
        })
        .collect();
    if going.is_empty() {
        return 0;
    }
    let (mut next, mut g) = (0u32, going.iter().peekable());
    for list in [&mut *t.kept, &mut *t.fillable, &mut *t.external] {
        list.retain(|_| {
            next += 1;
            g.next_if_eq(&&(next - 1)).is_none()
        });
    }
    going.len() as u64
}

/// Height over its largest face below this fraction of its longest edge: flat up to the rounding
/// of its vertices' constructions (far below `SLIVER`: taking such a tetrahedron out moves ∂K by
/// no more than that height, which must stay below every real feature, slabs included).
const ROUNDING_FLAT: f64 = 1e-12;

fn flat_to_rounding(positions: &[[f64; 3]], t: &[u32; 4]) -> bool {
    let p = t.map(|v| positions[v as usize]);
    flat_height(p) < ROUNDING_FLAT * longest_edge(p)
}

fn longest_edge(p: [[f64; 3]; 4]) -> f64 {
    super::complex::TET_EDGES
        .iter()
        .map(|&(i, j)| {
            let e = sub(p[i], p[j]);
            dot(e, e).sqrt()
        })
        .fold(0.0, f64::max)
}

/// Per face of a flat tetrahedron (face i opposite vertex i, outward), whether it faces the same way
/// as its largest face.
fn flat_sides(p: [[f64; 3]; 4]) -> [bool; 4] {
    let normal = |i: usize| {
        // outward: away from vertex i
        let f = [(1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)][i];
        let n = cross(sub(p[f.1], p[f.0]), sub(p[f.2], p[f.0]));
        if dot(n, sub(p[i], p[f.0])) > 0.0 {
            [-n[0], -n[1], -n[2]]
        } else {
            n
        }
    };
    let ns: [[f64; 3]; 4] = std::array::from_fn(normal);
    let big = (0..4)
        .max_by(|&a, &b| dot(ns[a], ns[a]).total_cmp(&dot(ns[b], ns[b])))
        .unwrap();
    std::array::from_fn(|i| dot(ns[i], ns[big]) > 0.0)
}

/// Height over its largest face below this fraction of its longest edge: a tetrahedron flat up to
/// rounding, whose faces on ∂K would lie on each other.
const SLIVER: f64 = 1e-6;

pub(super) fn sliver(positions: &[[f64; 3]], t: &[u32; 4]) -> bool {
    let p = t.map(|v| positions[v as usize]);
    flat_height(p) < SLIVER * longest_edge(p)
}

/// Distance of the farthest vertex from the plane of the largest face (float; for a flatness
/// test far above rounding).
pub fn flat_height(p: [[f64; 3]; 4]) -> f64 {
    let (mut best, mut height) = (0.0, f64::INFINITY);
    for i in 0..4 {
        // the other three in increasing index
        let f = [(1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)][i];
        let f = [p[f.0], p[f.1], p[f.2]];
        let n = cross(sub(f[1], f[0]), sub(f[2], f[0]));
        let len = dot(n, n).sqrt();
        if len > best {
            best = len;
            height = dot(n, sub(p[i], f[0])).abs() / len;
        }
    }
    height
}

/// The face `f` lies on a plane: its three vertices share that plane's tag.
pub fn on_a_plane(planes: &[Planes], f: &[u32; 3]) -> bool {
    common_plane(planes, *f).is_some()
}

/// The edge `a b` lies on a plane: its two ends share that plane's tag.
pub fn edge_on_a_plane(planes: &[Planes], a: u32, b: u32) -> bool {
    let pb = &planes[b as usize];
    planes[a as usize].iter().any(|g| pb.contains(g))
}

/// The plane shared by the three vertices of `f`, if any.
pub fn common_plane(planes: &[Planes], f: [u32; 3]) -> Option<u32> {
    let [a, b, c] = f.map(|v| &planes[v as usize]);
    a.iter().copied().find(|p| b.contains(p) && c.contains(p))
}

/// Each face of `tet` that lies on a plane (its three vertices share it) is a section triangle.
pub fn faces_in_sections(
    tet: &[u32; 4],
    planes: &[Planes],
    internal: &FxHashSet<[u32; 3]>,
) -> bool {
    (0..4).all(|i| {
        let f = super::complex::outward_face(tet, i);
        !on_a_plane(planes, &f) || internal.contains(&key3(f))
    })
}

/// Split edges of tetrahedra that some child of their refinement would make flat or inverted (a
/// split point is off the line of its edge by rounding; a thin neighbour can flip): every split
/// edge of such a tetrahedron.
fn inverted_edges<'a>(
    positions: &[[f64; 3]],
    points: &FxHashMap<(u32, u32), [f64; 3]>,
    tets: impl Iterator<Item = &'a [u32; 4]>,
) -> FxHashSet<(u32, u32)> {
    let base = positions.len() as u32;
    let list: Vec<((u32, u32), [f64; 3])> = points.iter().map(|(&e, &p)| (e, p)).collect();
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

/// Tetrahedra for the tests of the modules that refine K.
#[cfg(test)]
pub(crate) mod test_support {
    /// robust's orient3d of `t` (K's tetrahedra are positive).
    pub fn orient(p: &[[f64; 3]], t: [u32; 4]) -> f64 {
        let c = |v: u32| robust::Coord3D {
            x: p[v as usize][0],
            y: p[v as usize][1],
            z: p[v as usize][2],
        };
        robust::orient3d(c(t[0]), c(t[1]), c(t[2]), c(t[3]))
    }

    /// `t`, its last two vertices swapped where that makes it positive.
    pub fn positive(p: &[[f64; 3]], t: [u32; 4]) -> [u32; 4] {
        if orient(p, t) > 0.0 {
            t
        } else {
            [t[0], t[1], t[3], t[2]]
        }
    }

    /// Positions, K's tetrahedra and the step-1 survivors of a test complex.
    pub type Complex = (Vec<[f64; 3]>, Vec<[u32; 4]>, Vec<[u32; 4]>);

    /// A solid torus of tetrahedra: a ring of `n` triangular prisms (3 tets each), plus the tets
    /// of the ring's hole as step-1 survivors (a disk of them spans it).
    pub fn ring(n: u32) -> Complex {
        // vertices: per station i, three around the ring tube: 3i, 3i+1, 3i+2; plus centre c
        let mut pos = Vec::new();
        for i in 0..n {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            let (c, s) = (a.cos(), a.sin());
            pos.push([2.0 * c, 2.0 * s, 0.0]);
            pos.push([3.0 * c, 3.0 * s, 0.0]);
            pos.push([2.5 * c, 2.5 * s, 1.0]);
        }
        pos.push([0.0, 0.0, 0.0]);
        pos.push([0.0, 0.0, 1.0]);
        let (c0, c1) = (3 * n, 3 * n + 1);
        let mut kept = Vec::new();
        let mut fill = Vec::new();
        for i in 0..n {
            let j = (i + 1) % n;
            let [a, b, c] = [3 * i, 3 * i + 1, 3 * i + 2];
            let [d, e, f] = [3 * j, 3 * j + 1, 3 * j + 2];
            // prism abc-def as three tets
            kept.push([a, b, c, d]);
            kept.push([b, c, d, e]);
            kept.push([c, d, e, f]);
            // the hole: a fan of tets from the axis to the inner wall (a, d, c, f)
            fill.push([c0, c1, a, d]);
            fill.push([c1, a, d, c]);
            fill.push([c1, d, c, f]);
        }
        (pos, kept, fill)
    }

    /// A triangulation that owns its lists (a test builds one and lends it with `view`).
    #[derive(Default)]
    pub struct Owned {
        pub positions: Vec<[f64; 3]>,
        pub planes: Vec<super::Planes>,
        pub kept: Vec<[u32; 4]>,
        pub fillable: Vec<[u32; 4]>,
        pub external: Vec<[u32; 4]>,
        pub internal: crate::fxhash::FxHashSet<[u32; 3]>,
    }

    impl Owned {
        /// `positions` with no plane on any point, and nothing else.
        pub fn at(positions: Vec<[f64; 3]>) -> Owned {
            Owned {
                planes: vec![super::Planes::new(); positions.len()],
                positions,
                ..Owned::default()
            }
        }

        pub fn view(&mut self) -> super::Triangulation<'_> {
            super::Triangulation {
                positions: &mut self.positions,
                planes: &mut self.planes,
                kept: &mut self.kept,
                fillable: &mut self.fillable,
                external: &mut self.external,
                internal: &mut self.internal,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::assembly::{boundary_of, singularities};

    fn ids(pairs: &[((u32, u32), u32)]) -> FxHashMap<(u32, u32), u32> {
        pairs.iter().copied().collect()
    }

    /// `one_of` answers as the keys' set does, whatever the order of a tetrahedron's vertices,
    /// for tetrahedra with every vertex on the keys' tetrahedra and for the others.
    #[test]
    fn one_of_is_membership_in_the_keys() {
        let keys: FxHashSet<[u32; 4]> = [key4([3, 1, 2, 0]), key4([4, 5, 6, 7])]
            .into_iter()
            .collect();
        let member = one_of(9, &keys);
        for (t, want) in [
            ([0, 1, 2, 3], true),
            ([2, 3, 0, 1], true),
            ([7, 6, 5, 4], true),
            ([0, 1, 2, 4], false), // every vertex on a key's tetrahedron, not a key
            ([0, 1, 2, 8], false),
            ([8, 8, 8, 8], false),
        ] {
            assert_eq!(member(&t), want, "{t:?}");
        }
    }

    /// A tetrahedron flat up to rounding on the outer boundary: the square a b c d with c lifted
    /// 1e-15 (its upper faces a b c and a c d, lower a b d and b c d) over two kept tetrahedra
    /// below (apex e). Kept, with only its lower faces beside kept tetrahedra, it goes and ∂K
    /// takes the lower faces instead; kept with a kept neighbour above too, it stays; unkept, it goes.
    #[test]
    fn a_flat_tet_on_the_hull_is_taken_out_where_that_keeps_the_boundary() {
        let positions0 = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1e-15],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, -1.0],
            [0.5, 0.2, 1.0],
        ];
        let (a, b, c, d, e, f) = (0, 1, 2, 3, 4, 5);
        let p = &positions0;
        let flat = test_support::positive(p, [a, b, c, d]);
        let below = [
            test_support::positive(p, [a, b, d, e]),
            test_support::positive(p, [b, c, d, e]),
        ];
        let above = test_support::positive(p, [a, b, c, f]);
        let run = |kept: Vec<[u32; 4]>, fillable: Vec<[u32; 4]>| {
            let mut o = test_support::Owned {
                kept,
                fillable,
                ..test_support::Owned::at(positions0.clone())
            };
            let n = drop_hull_slivers(&mut o.view());
            (n, o.kept, o.fillable)
        };
        let (n, kept, _) = run(vec![flat, below[0], below[1]], vec![]);
        assert_eq!(n, 1);
        assert_eq!(kept.len(), 2);
        let bnd = boundary_of(&kept);
        assert_eq!(singularities(&bnd), (0, 0));
        assert!(bnd.iter().any(|t| key3(*t) == key3([a, b, d])));
        let (n, kept, _) = run(vec![flat, below[0], below[1], above], vec![]);
        assert_eq!((n, kept.len()), (0, 4));
        let (n, _, fillable) = run(vec![below[0], below[1]], vec![flat]);
        assert_eq!((n, fillable.len()), (1, 0));
    }

    #[test]
    fn a_tet_split_along_its_three_apex_edges_is_a_prism_and_a_top() {
        let c = split([0, 1, 2, 3], &ids(&[((0, 3), 4), ((1, 3), 5), ((2, 3), 6)]));
        assert_eq!(c.len(), 4);
        assert_eq!(c.iter().filter(|c| c.contains(&3)).count(), 1);
        // the children tile the tet: its boundary, split on its three side faces
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

    /// Two unit-ish tets around the edge (0,1) with a third between them: (0,1,2,3) kept,
    /// (0,1,3,4) unkept, (0,1,4,5) kept; the edge (0,1) alone is on plane 0.
    fn fan() -> (Vec<[f64; 3]>, Vec<Planes>) {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.5],
            [0.5, 1.0, 0.5],
            [-0.5, 1.0, 0.5],
            [-1.0, 0.0, 0.5],
        ];
        let planes = vec![
            [0].into_iter().collect(),
            [0].into_iter().collect(),
            Planes::new(),
            Planes::new(),
            Planes::new(),
            Planes::new(),
        ];
        (positions, planes)
    }

    use super::test_support::{orient, positive};

    /// The fan's gap b between the kept a and c, grown at the edge (0,1) with its four edges to the
    /// gap's other vertices split a tenth of the way: the triangulation after, and what grew.
    fn grow_the_fans_gap(planes: Vec<Planes>) -> (test_support::Owned, Grown) {
        let (positions, _) = fan();
        let [a, b, c] = [[0, 1, 2, 3], [0, 1, 3, 4], [0, 1, 4, 5]].map(|t| positive(&positions, t));
        let mut o = test_support::Owned {
            positions,
            planes,
            kept: vec![a, c],
            fillable: vec![b],
            ..Default::default()
        };
        let mut t = o.view();
        let mut points = FxHashMap::default();
        for (v, x) in [(0, 3), (0, 4), (1, 3), (1, 4)] {
            let (p, q) = (t.positions[v as usize], t.positions[x as usize]);
            points.insert(edge(v, x), [0, 1, 2].map(|i| p[i] + 0.1 * (q[i] - p[i])));
        }
        let growth = Growth {
            tet: b,
            core: [0, 1].into_iter().collect(),
            keep_slivers: false,
        };
        let g = grow(&mut t, &[vec![growth]], points);
        (o, g)
    }

    #[test]
    fn growing_into_a_gap_at_an_edge_joins_its_two_sectors() {
        let (positions, planes) = fan();
        let [a, c] = [[0, 1, 2, 3], [0, 1, 4, 5]].map(|t| positive(&positions, t));
        let before = crate::bm::assembly::singular_sets(&[a, c]);
        assert_eq!(singularities(&boundary_of(&[a, c])).0, 1);
        let (o, g) = grow_the_fans_gap(planes);
        assert_eq!(g.points, 4);
        assert!(g.tets_per_group[0] > 0);
        let bnd = boundary_of(&o.kept);
        assert_eq!(singularities(&bnd), (0, 0));
        // the touched vertices are enough to update the singular sets
        assert_eq!(before.0, vec![(0, 1)]);
        let after = crate::bm::assembly::singular_sets_after(&o.kept, before, &g.touched);
        assert_eq!(after, (vec![], vec![]));
        assert!(o.kept.iter().all(|&k| orient(&o.positions, k) > 0.0));
        // the rest of the gap stays unkept
        assert!(!o.fillable.is_empty());
    }

    #[test]
    fn no_growth_puts_a_face_on_a_plane_outside_its_section() {
        // the same gap, but its face (0,1,3) lies on plane 0 and is not a section triangle
        let (_, mut planes) = fan();
        planes[3] = [0].into_iter().collect();
        let (o, g) = grow_the_fans_gap(planes);
        assert_eq!(g.tets_per_group, vec![0]);
        assert_eq!(
            o.kept.len(),
            6,
            "the two kept tets are split in three each, none added"
        );
    }
}
