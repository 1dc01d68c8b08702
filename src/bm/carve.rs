//! Singular edges and pinched vertices that growth and toggles leave where two or more *cones*
//! of K (kept tetrahedra containing the edge or vertex, connected through faces that contain it)
//! meet there only: every cone but the largest loses its part near the edge or vertex, by
//! refinement, never by moving a vertex.
//!
//! The edges from the core (the singular edge's ends, or the vertex) to the other vertices of a
//! carved cone are split at a point near the core (`refine::grow` with no growth: every
//! tetrahedron around a split edge is split with it, so the triangulation stays conforming); the
//! children of the cone's tetrahedra with no vertex but the core and split points (the tips)
//! leave K (they become fillable). The cone then ends in a small cap instead of at the core.
//! The sections stay R ∩ P = A: a tip face on a plane is a section triangle, and the cone is
//! carved only when the tetrahedron on the other side of each such face is kept (the face stays
//! in R). A vertex is carved only when that strictly lowers the number of singular simplices of
//! ∂K, counted after a few rounds of growth (`singular::resolve`) where the carving alone only
//! moved the singularity to the cap's edge; otherwise the triangulation is restored.
use super::assembly::{boundary_of, Sets};
use super::fill::singular_simplices;
use super::refine::{edge, grow, key3, key4, on_a_plane, split, Triangulation};
use super::singular::Snapshot;
use crate::fxhash::{FxHashMap, FxHashSet};
use petgraph::unionfind::UnionFind;
use smallvec::SmallVec;

/// What the carving did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CarveStats {
    /// Singular edges and pinched vertices whose smaller cones were carved.
    pub vertices: u64,
    /// Tip tetrahedra taken out of K.
    pub tips: u64,
    /// Singular simplices left (no tip without a section face exposed, no gain, or a pinched
    /// vertex whose kept star is one cone: nothing to carve).
    pub refused: u64,
}

/// Carve the smaller cones at every singular edge and pinched vertex of ∂K, `singular` (as
/// `fill::singular_simplices` gives them), not at `nonconforming` vertices, the split points
/// `distance` from the edge or vertex (at most a quarter of each edge).
pub fn carve_pinches(
    t: &mut Triangulation,
    singular: Sets,
    nonconforming: &FxHashSet<u32>,
    distance: f64,
) -> CarveStats {
    let count = singular.0.len() + singular.1.len();
    carve_some(t, singular, count, nonconforming, distance)
}

/// `carve_pinches` at `cores`, some of ∂K's `count` singular simplices: a carving stays only
/// where it lowers that count.
fn carve_some(
    t: &mut Triangulation,
    cores: Sets,
    mut count: usize,
    nonconforming: &FxHashSet<u32>,
    distance: f64,
) -> CarveStats {
    let mut stats = CarveStats::default();
    let (edges, vertices) = cores;
    let cores = edges
        .iter()
        .map(|&(a, b)| vec![a, b])
        .chain(vertices.iter().map(|&v| vec![v]));
    for core in cores {
        if core.iter().any(|v| nonconforming.contains(v)) {
            continue;
        }
        // keep the largest cone and carve the others; where that is refused (a section face
        // of theirs would be exposed), keep the next one instead; a vertex whose kept star is
        // one cone with several holes gets a strip across it carved instead
        let mut done = false;
        'tries: for cut in cuts_at(t.kept, &core) {
            for d in [distance, 0.1 * distance] {
                let start = Snapshot::of(t);
                let mut tips = carve_core(t, &core, cut, d);
                let (mut e, mut w) = singular_simplices(&boundary_of(t.kept));
                // an edge carved away can leave one of its ends pinched: carve that too
                if tips > 0 && core.len() == 2 && e.len() + w.len() >= count {
                    for &v in core.iter().filter(|v| w.contains(v)) {
                        tips += cuts_at(t.kept, &[v])
                            .into_iter()
                            .map(|cut| carve_core(t, &[v], cut, d))
                            .find(|&n| n > 0)
                            .unwrap_or(0);
                    }
                    (e, w) = singular_simplices(&boundary_of(t.kept));
                }
                // a carved cone can leave the singularity at its cap's edge (where a kept
                // tetrahedron that was not in the cones shares the split edge): grow there
                if tips > 0 && e.len() + w.len() >= count {
                    let (_, now) = super::singular::resolve(
                        t,
                        LOOKAHEAD_ROUNDS,
                        super::singular::Reach::near(d),
                        super::singular::EdgeGaps::NearEdge,
                        Some((e, w)),
                    );
                    (e, w) = now.unwrap_or_else(|| singular_simplices(&boundary_of(t.kept)));
                }
                if tips > 0 && e.len() + w.len() < count {
                    count = e.len() + w.len();
                    stats.vertices += 1;
                    stats.tips += tips;
                    done = true;
                    break 'tries;
                }
                start.restore(t);
            }
        }
        // nothing to carve, or no carving lowered the count: refused, so the report says so
        stats.refused += u64::from(!done);
    }
    stats
}

/// `carve_pinches` at the singular simplices of `singular` whose vertices all lie on no plane,
/// after the collar: a tip there has no face on a plane (its other vertices are split points of
/// edges from the core), so no section changes, and the prisms near the planes stay as they are.
/// The tips are dropped, not left fillable: nothing grows after the collar.
pub fn carve_off_planes(
    t: &mut Triangulation,
    singular: Sets,
    nonconforming: &FxHashSet<u32>,
    distance: f64,
) -> CarveStats {
    let off = |x: &u32| t.planes[*x as usize].is_empty();
    let count = singular.0.len() + singular.1.len();
    let (edges, vertices) = singular;
    let edges: Vec<(u32, u32)> = (edges.into_iter())
        .filter(|(a, b)| off(a) && off(b))
        .collect();
    let vertices: Vec<u32> = vertices.into_iter().filter(off).collect();
    if edges.is_empty() && vertices.is_empty() {
        return CarveStats::default();
    }
    let stats = carve_some(t, (edges, vertices), count, nonconforming, distance);
    t.fillable.clear();
    stats
}

/// Growth rounds after a carving that left as many singular simplices as before.
const LOOKAHEAD_ROUNDS: usize = 2;

/// Most cones tried as the one kept at a singular simplex.
const MAX_CONES: usize = 4;

/// The kept tetrahedra containing `core` (a vertex or an edge), grouped into cones (connected
/// through faces containing the core), largest first.
fn cones_at(kept: &[[u32; 4]], core: &[u32]) -> Vec<Vec<[u32; 4]>> {
    let star: Vec<[u32; 4]> = kept
        .iter()
        .copied()
        .filter(|t| core.iter().all(|v| t.contains(v)))
        .collect();
    cones_of(&star, core)
}

/// The tetrahedra of `star` (all containing `core`) in cones, connected through faces containing
/// the core; largest first, ties by the smallest tetrahedron (deterministic).
pub(super) fn cones_of(star: &[[u32; 4]], core: &[u32]) -> Vec<Vec<[u32; 4]>> {
    let mut parent: Vec<usize> = (0..star.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut by_face: FxHashMap<[u32; 3], usize> = FxHashMap::default();
    for (i, t) in star.iter().enumerate() {
        for w in t.iter().filter(|w| !core.contains(w)) {
            let others: Vec<u32> = t.iter().copied().filter(|&x| x != *w).collect();
            let f = key3([others[0], others[1], others[2]]);
            if let Some(&j) = by_face.get(&f) {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                parent[a] = b;
            } else {
                by_face.insert(f, i);
            }
        }
    }
    let mut groups: FxHashMap<usize, Vec<[u32; 4]>> = FxHashMap::default();
    for (i, t) in star.iter().enumerate() {
        let r = find(&mut parent, i);
        groups.entry(r).or_default().push(*t);
    }
    let mut cones: Vec<Vec<[u32; 4]>> = groups.into_values().collect();
    // largest first; ties by the smallest tetrahedron, so the order is deterministic
    for c in &mut cones {
        c.sort_unstable_by_key(|t| key4(*t));
    }
    cones.sort_by(|a, b| {
        b.len()
            .cmp(&a.len())
            .then_with(|| key4(a[0]).cmp(&key4(b[0])))
    });
    cones
}

/// What to carve at a singular simplex.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cut {
    /// Every cone but this one (by size, largest first).
    ConesBut(usize),
    /// At a pinched vertex whose kept star is one cone with several holes (its surface link
    /// several cycles): the shortest strip of the cone from this cycle (by size, smallest first)
    /// to another. The kept link, an annulus or worse, becomes one with a hole fewer.
    StripFrom(usize),
}

/// The cuts to try at `core`, in order.
fn cuts_at(kept: &[[u32; 4]], core: &[u32]) -> Vec<Cut> {
    let cones = cones_at(kept, core).len();
    if cones >= 2 {
        return (0..cones.min(MAX_CONES)).map(Cut::ConesBut).collect();
    }
    match core {
        [v] if cones == 1 => {
            let cycles = Link::of(kept, *v).cycles;
            (0..cycles.min(MAX_CONES)).map(Cut::StripFrom).collect()
        }
        _ => Vec::new(),
    }
}

/// The surface around a vertex v: its kept star, and the cycles of ∂K's link there.
struct Link {
    star: Vec<[u32; 4]>,
    /// Per star tetrahedron, the cycles its faces through v on ∂K belong to.
    touches: Vec<SmallVec<[usize; 2]>>,
    /// Per face through v shared by two star tetrahedra, those two.
    inner: Vec<[usize; 2]>,
    cycles: usize,
}

impl Link {
    fn of(kept: &[[u32; 4]], v: u32) -> Link {
        let mut star: Vec<[u32; 4]> = kept.iter().copied().filter(|t| t.contains(&v)).collect();
        star.sort_unstable_by_key(|t| key4(*t));
        let mut by_face: FxHashMap<[u32; 3], SmallVec<[usize; 2]>> = FxHashMap::default();
        for (i, t) in star.iter().enumerate() {
            for w in t.iter().filter(|&&w| w != v) {
                let f: SmallVec<[u32; 3]> = t.iter().copied().filter(|x| x != w).collect();
                by_face.entry(key3([f[0], f[1], f[2]])).or_default().push(i);
            }
        }
        let mut faces: Vec<([u32; 3], SmallVec<[usize; 2]>)> = by_face.into_iter().collect();
        faces.sort_unstable_by_key(|f| f.0);
        let inner = faces
            .iter()
            .filter(|f| f.1.len() == 2)
            .map(|f| [f.1[0], f.1[1]])
            .collect();
        // surface faces through v joined at their edges through v: the link's cycles
        let surface: Vec<([u32; 3], usize)> = faces
            .iter()
            .filter(|f| f.1.len() == 1)
            .map(|f| (f.0, f.1[0]))
            .collect();
        let mut uf = UnionFind::<usize>::new(surface.len());
        let mut at_edge: FxHashMap<u32, usize> = FxHashMap::default();
        for (i, (f, _)) in surface.iter().enumerate() {
            for &x in f.iter().filter(|&&x| x != v) {
                if let Some(&j) = at_edge.get(&x) {
                    uf.union(i, j);
                } else {
                    at_edge.insert(x, i);
                }
            }
        }
        // cycles numbered smallest first (ties: the first face), so tries are deterministic
        let mut size: FxHashMap<usize, (usize, usize)> = FxHashMap::default();
        for i in 0..surface.len() {
            let e = size.entry(uf.find(i)).or_insert((0, i));
            e.0 += 1;
        }
        let mut roots: Vec<(usize, usize, usize)> = size
            .into_iter()
            .map(|(r, (n, first))| (n, first, r))
            .collect();
        roots.sort_unstable();
        let number: FxHashMap<usize, usize> =
            roots.iter().enumerate().map(|(k, r)| (r.2, k)).collect();
        let mut touches = vec![SmallVec::new(); star.len()];
        for (i, (_, t)) in surface.iter().enumerate() {
            let c = number[&uf.find(i)];
            if !touches[*t].contains(&c) {
                touches[*t].push(c);
            }
        }
        Link {
            star,
            touches,
            inner,
            cycles: roots.len(),
        }
    }

    /// The shortest chain of star tetrahedra, adjacent through faces through v, from one on
    /// cycle `from` to one on another cycle.
    fn strip_from(&self, from: usize) -> Option<Vec<[u32; 4]>> {
        let mut next: Vec<SmallVec<[usize; 4]>> = vec![SmallVec::new(); self.star.len()];
        for &[a, b] in &self.inner {
            next[a].push(b);
            next[b].push(a);
        }
        let mut came: Vec<Option<usize>> = vec![None; self.star.len()];
        let mut queue = std::collections::VecDeque::new();
        for (i, c) in self.touches.iter().enumerate() {
            if c.contains(&from) {
                came[i] = Some(i);
                queue.push_back(i);
            }
        }
        while let Some(i) = queue.pop_front() {
            if self.touches[i].iter().any(|&c| c != from) {
                let mut chain = vec![self.star[i]];
                let mut j = i;
                while came[j] != Some(j) {
                    j = came[j].unwrap();
                    chain.push(self.star[j]);
                }
                return Some(chain);
            }
            for &n in &next[i] {
                if came[n].is_none() {
                    came[n] = Some(i);
                    queue.push_back(n);
                }
            }
        }
        None
    }
}

/// Split the edges from `core` into the kept tetrahedra `cut` names and take their parts near
/// the core out of K; the number of tetrahedra taken (0: nothing to carve, a split was refused,
/// or a section face would be exposed; the caller restores).
fn carve_core(t: &mut Triangulation, core: &[u32], cut: Cut, distance: f64) -> u64 {
    let carved: Vec<[u32; 4]> = match cut {
        Cut::ConesBut(keep) => {
            let cones = cones_at(t.kept, core);
            if cones.len() < 2 {
                return 0;
            }
            (cones.into_iter().enumerate())
                .filter(|&(i, _)| i != keep)
                .flat_map(|(_, c)| c)
                .collect()
        }
        Cut::StripFrom(from) => match Link::of(t.kept, core[0]).strip_from(from) {
            Some(strip) => strip,
            None => return 0,
        },
    };
    let mut points: FxHashMap<(u32, u32), [f64; 3]> = FxHashMap::default();
    for tet in &carved {
        for &v in core {
            let pv = t.positions[v as usize];
            for &w in tet.iter().filter(|w| !core.contains(w)) {
                let pw = t.positions[w as usize];
                let d = [pw[0] - pv[0], pw[1] - pv[1], pw[2] - pv[2]];
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let s = (distance / len).min(0.25);
                points.insert(
                    edge(v, w),
                    [pv[0] + s * d[0], pv[1] + s * d[1], pv[2] + s * d[2]],
                );
            }
        }
    }
    let first_new = t.positions.len();
    grow(t, &[], points.clone());
    let id_of: FxHashMap<[u64; 3], u32> = t.positions[first_new..]
        .iter()
        .enumerate()
        .map(|(i, p)| (p.map(f64::to_bits), (first_new + i) as u32))
        .collect();
    let mut ids: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for (e, p) in &points {
        match id_of.get(&p.map(f64::to_bits)) {
            Some(&id) => ids.insert(*e, id),
            None => return 0, // a split refused (it would flip a neighbour)
        };
    }
    let tips: Vec<[u32; 4]> = carved
        .iter()
        .flat_map(|&tet| split(tet, &ids))
        .filter(|c| {
            c.iter()
                .all(|v| core.contains(v) || *v as usize >= first_new)
        })
        .collect();
    take_tips(t, core, &tips)
}

/// Move `tips` (children of kept tetrahedra near `core`) from K to the fillable ones, when each
/// tip face that lies on a plane has a kept tetrahedron on its other side; else 0.
fn take_tips(t: &mut Triangulation, core: &[u32], tips: &[[u32; 4]]) -> u64 {
    let tip_keys: FxHashSet<[u32; 4]> = tips.iter().map(|&x| key4(x)).collect();
    let through_core = |f: &[u32; 3]| f.iter().any(|v| core.contains(v));
    let is_tip = super::refine::one_of(t.positions.len(), &tip_keys);
    let in_kept = t.kept.iter().filter(|x| is_tip(x)).count();
    if tips.is_empty()
        || !sections_stay_covered(t, tips, &tip_keys, through_core)
        || in_kept < tips.len()
    {
        return 0;
    }
    t.kept.retain(|x| !is_tip(x));
    t.fillable.extend(tips.iter().copied());
    tips.len() as u64
}

/// Whether every face of a tip (of `tips`, keyed `tip_keys`) that passes `through` and lies on a
/// plane keeps a kept tetrahedron that is not a tip on it: taking the tips out leaves every
/// section covered.
pub(super) fn sections_stay_covered(
    t: &Triangulation,
    tips: &[[u32; 4]],
    tip_keys: &FxHashSet<[u32; 4]>,
    through: impl Fn(&[u32; 3]) -> bool,
) -> bool {
    let mut on_plane: FxHashSet<[u32; 3]> = FxHashSet::default();
    for tip in tips {
        for i in 0..4 {
            let f = super::complex::outward_face(tip, i);
            if through(&f) && on_a_plane(t.planes, &f) {
                on_plane.insert(key3(f));
            }
        }
    }
    if on_plane.is_empty() {
        return true;
    }
    // only a tetrahedron with three vertices on such faces can cover one (no hashing of the rest)
    let mut on = vec![false; t.positions.len()];
    for f in &on_plane {
        for &v in f {
            on[v as usize] = true;
        }
    }
    let near = |x: &[u32; 4]| x.iter().filter(|&&v| on[v as usize]).count() >= 3;
    let mut covered: FxHashSet<[u32; 3]> = FxHashSet::default();
    for tet in (t.kept.iter()).filter(|x| near(x) && !tip_keys.contains(&key4(**x))) {
        for i in 0..4 {
            let f = key3(super::complex::outward_face(tet, i));
            if on_plane.contains(&f) {
                covered.insert(f);
            }
        }
    }
    covered.len() == on_plane.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::refine::test_support::{positive, Owned};

    /// The origin and the six unit points on the axes (+x, +y, +z, -x, -y, -z).
    const AXIS_STAR: [[f64; 3]; 7] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, -1.0],
    ];

    /// Two tetrahedra meeting at the origin only (a pinched vertex): the smaller cone loses its
    /// tip, the boundary becomes two closed surfaces without a singular vertex.
    #[test]
    fn two_cones_touching_at_a_vertex_are_separated() {
        let mut positions = AXIS_STAR.to_vec();
        positions.push([-1.0, -1.0, -1.0]);
        // one cone at the origin of one tet, the other of one tet and one beyond it
        let kept = vec![
            positive(&positions, [0, 1, 2, 3]),
            positive(&positions, [0, 4, 5, 6]),
            positive(&positions, [4, 5, 6, 7]),
        ];
        let mut o = Owned {
            kept,
            ..Owned::at(positions)
        };
        let mut t = o.view();
        let singular = singular_simplices(&boundary_of(t.kept));
        assert_eq!(singular.1, vec![0]);
        let stats = carve_pinches(&mut t, singular, &FxHashSet::default(), 0.1);
        assert_eq!((stats.vertices, stats.tips, stats.refused), (1, 1, 0));
        let (e, w) = singular_simplices(&boundary_of(t.kept));
        assert!(e.is_empty() && w.is_empty(), "{e:?} {w:?}");
        // equal cones: the one with the smaller tetrahedron stays, the other no longer reaches
        // the origin
        let at_origin: Vec<_> = t.kept.iter().filter(|x| x.contains(&0)).collect();
        assert_eq!(at_origin.len(), 1);
        assert_eq!(key4(*at_origin[0]), [0, 1, 2, 3]);
    }

    /// Two pinched vertices, one on a plane and one on none: after the collar only the second
    /// is carved (a tip at the first could expose a section face).
    #[test]
    fn after_the_collar_only_pinches_on_no_plane_are_carved() {
        let mut positions = Vec::new();
        let mut kept = Vec::new();
        for shift in [0.0, 10.0] {
            let base = positions.len() as u32;
            for p in AXIS_STAR {
                positions.push([p[0] + shift, p[1], p[2]]);
            }
            kept.push(positive(&positions, [base, base + 1, base + 2, base + 3]));
            kept.push(positive(&positions, [base, base + 4, base + 5, base + 6]));
        }
        let mut o = Owned {
            kept,
            ..Owned::at(positions)
        };
        o.planes[7].push(0);
        let mut t = o.view();
        let singular = singular_simplices(&boundary_of(t.kept));
        assert_eq!(singular, (vec![], vec![0, 7]));
        let stats = carve_off_planes(&mut t, singular, &FxHashSet::default(), 0.1);
        assert_eq!((stats.vertices, stats.tips, stats.refused), (1, 1, 0));
        assert!(t.fillable.is_empty());
        let (e, w) = singular_simplices(&boundary_of(t.kept));
        assert_eq!((e, w), (vec![], vec![7]));
    }

    /// The six octants around the origin but two opposite ones: one cone whose surface link is
    /// two cycles (an annulus, as where a crossing diagram leaves two holes at a vertex). No cone
    /// can be carved; the shortest strip of the cone from one hole to the other is, and the
    /// boundary becomes a manifold.
    #[test]
    fn one_cone_with_two_holes_at_a_vertex_loses_a_strip_across_it() {
        let mut positions = vec![[0.0, 0.0, 0.0]];
        for axis in 0..3 {
            for sign in [1.0, -1.0] {
                let mut p = [0.0; 3];
                p[axis] = sign;
                positions.push(p);
            }
        }
        // vertex of axis a (0, 1, 2) with sign s (0: +, 1: -)
        let at = |a: usize, s: usize| (1 + 2 * a + s) as u32;
        let mut kept = Vec::new();
        for sx in 0..2 {
            for sy in 0..2 {
                for sz in 0..2 {
                    if sx == sy && sy == sz {
                        continue; // the octants (+,+,+) and (-,-,-) are the holes
                    }
                    kept.push(positive(&positions, [0, at(0, sx), at(1, sy), at(2, sz)]));
                }
            }
        }
        let mut o = Owned {
            kept,
            ..Owned::at(positions)
        };
        let mut t = o.view();
        assert_eq!(cones_at(t.kept, &[0]).len(), 1);
        assert_eq!(Link::of(t.kept, 0).cycles, 2);
        let singular = singular_simplices(&boundary_of(t.kept));
        assert_eq!(singular, (vec![], vec![0]));
        let stats = carve_pinches(&mut t, singular, &FxHashSet::default(), 0.1);
        assert_eq!((stats.vertices, stats.refused), (1, 0), "{stats:?}");
        // the strip: two octants, each losing its tip at the origin
        assert_eq!(stats.tips, 2);
        let (e, w) = singular_simplices(&boundary_of(t.kept));
        assert!(e.is_empty() && w.is_empty(), "{e:?} {w:?}");
        assert_eq!(Link::of(t.kept, 0).cycles, 1);
    }
}
