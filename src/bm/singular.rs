//! Singular edges and pinched vertices of ∂K resolved inside the complex by growing K into the
//! gaps beside them (`refine`), never by moving a vertex (design note §3; paper Fig. 12a, where
//! the branching diagrams of the two cells of a face cross).
//!
//! Around a singular edge e the tetrahedra alternate between kept sectors and gaps; the part near
//! e of every gap but the largest is kept (a thin wedge along e), so one kept sector is left.
//! Around a pinched vertex v, on the sphere of directions from v, either the kept tetrahedra
//! form several components (two cones touching at v: the shortest strip of gap tetrahedra
//! between two of them is kept near v) or one component with several holes (the two void wedges
//! of crossing diagrams: the part near v of every gap but the largest is kept). The rounds repeat
//! on the new boundary up to a bound; what stays singular is counted by the caller.
//!
//! Over 800 lines only with its unit tests (the test modules at the end); the code is shorter.
use super::refine::{edge, grow, key3, on_a_plane, Growth, Planes, Triangulation};
use super::spacing::{Rule, Spaced, MIN_GAP};
use crate::fxhash::{FxHashMap, FxHashSet};
use smallvec::SmallVec;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct SingularStats {
    /// Gaps grown into at edges and at vertices, and the tetrahedra and points that added.
    pub edge_gaps: u64,
    pub vertex_gaps: u64,
    pub tets: u64,
    pub points: u64,
    /// Singular edges and pinched vertices at the start of each round.
    pub per_round: Vec<(u64, u64)>,
    /// The vertices whose stars in K some round changed (sorted; the state kept may be an
    /// earlier one: a superset).
    pub touched: Vec<u32>,
}

/// How a gap at a singular edge is grown into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeGaps {
    /// Whole tetrahedra where every tetrahedron of the gap may be kept (no new points; but a
    /// whole tetrahedron reaches vertices far from the edge and can pinch K there).
    Whole,
    /// Only the part near the edge (split points at `distance`): nothing far from it changes.
    NearEdge,
    /// As `NearEdge`, but an edge of a gap's face on a plane outside its section is not split
    /// (`OnPlaneEdges`), so the part kept touches such a face only at the core's vertices on it:
    /// the bridge of a saddle, where a section's regions touch at a vertex and the gap between
    /// them on the plane must stay open.
    OffPlane,
}

/// Where a growth splits the edges from its core: at `distance` from the core vertex, or at
/// `fraction` of the edge where that is farther, at most halfway. A growth near its simplex only
/// has `fraction` 0; a fraction keeps the points on edges to near-coincident far vertices (a
/// cluster, an earlier round's split points) apart in proportion to those vertices, where a fixed
/// distance along long edges puts them a fraction `distance / length` of that apart: needle
/// triangles whose faces lie on each other (double sheets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    pub distance: f64,
    pub fraction: f64,
}

impl Reach {
    /// At `distance` from the core only.
    pub fn near(distance: f64) -> Reach {
        Reach {
            distance,
            fraction: 0.0,
        }
    }

    /// The fraction of an edge of length `len` at which it is split.
    fn along(&self, len: f64) -> f64 {
        (self.distance / len).max(self.fraction)
    }
}

impl SingularStats {
    /// The counts of a later pass added in; its rounds follow this one's.
    pub fn add(&mut self, later: &SingularStats) {
        self.edge_gaps += later.edge_gaps;
        self.vertex_gaps += later.vertex_gaps;
        self.tets += later.tets;
        self.points += later.points;
        self.per_round.extend_from_slice(&later.per_round);
    }
}

/// Grow K at its singular edges and vertices, up to `rounds` rounds, with split points at
/// `reach` from the singular simplex (or halfway along shorter edges). A round can expose more
/// singularities than it resolves (at the split points, where a growth was refused); the state
/// with the fewest is kept, so growing never leaves ∂K worse than it found it.
///
/// `known`: the singular simplices of ∂K now, if known; returns those at the end, if known.
pub fn resolve(
    t: &mut Triangulation,
    rounds: usize,
    reach: Reach,
    edge_gaps: EdgeGaps,
    mut known: Option<super::assembly::Sets>,
) -> (SingularStats, Option<super::assembly::Sets>) {
    let mut stats = SingularStats::default();
    // (count, the state then — unless it is the last one —, the stats then)
    let mut best: Option<(u64, Option<Snapshot>, SingularStats)> = None;
    let mut best_is_current = false;
    // the sets before the last round's growth and the vertices it touched
    let mut previous: Option<(super::assembly::Sets, Vec<u32>)> = None;
    for round in 0..=rounds {
        let (edges, vertices) = match (known.take(), previous.take()) {
            (Some(sets), _) => sets,
            (None, Some((before, touched))) => {
                let sets = super::assembly::singular_sets_after(t.kept, before, &touched);
                debug_assert_eq!(sets, super::assembly::singular_sets(t.kept));
                sets
            }
            (None, None) => super::assembly::singular_sets(t.kept),
        };
        stats
            .per_round
            .push((edges.len() as u64, vertices.len() as u64));
        let count = (edges.len() + vertices.len()) as u64;
        let last = count == 0 || round == rounds;
        best_is_current = best.as_ref().is_none_or(|b| count < b.0);
        if best_is_current {
            let snapshot = (!last).then(|| Snapshot::of(t));
            best = Some((count, snapshot, stats.clone()));
        }
        if last {
            // the state is the one just counted
            known = Some((edges, vertices));
            break;
        }
        match grow_round(t, &edges, &vertices, reach, edge_gaps, &mut stats) {
            Some(touched) => {
                stats.touched.extend(&touched);
                previous = Some(((edges, vertices), touched))
            }
            None => {
                best_is_current = false;
                break;
            }
        }
    }
    if !best_is_current {
        known = None;
        if let Some((_, Some(snapshot), at_best)) = best {
            snapshot.restore(t);
            stats = SingularStats {
                per_round: stats.per_round,
                touched: stats.touched,
                ..at_best
            };
        }
    }
    stats.touched.sort_unstable();
    stats.touched.dedup();
    (stats, known)
}

/// One round of growth at the given singular edges and vertices: the vertices whose stars in K
/// it changed (`Grown::touched`), or `None` when nothing grew. Where every growth of a simplex
/// was refused (a sliver child, a split that would flip a neighbour), the simplex is tried again
/// with another of its gaps left open (`all_but_one`'s `stay`), up to `ALTERNATIVES` times.
fn grow_round(
    t: &mut Triangulation,
    edges: &[(u32, u32)],
    vertices: &[u32],
    reach: Reach,
    how: EdgeGaps,
    stats: &mut SingularStats,
) -> Option<Vec<u32>> {
    let (mut edges, mut vertices) = (edges.to_vec(), vertices.to_vec());
    let (mut touched, mut grown_any) = (Vec::new(), false);
    for stay in 0..ALTERNATIVES {
        let edge_groups = edge_gaps(t, &edges, how, stay);
        let vertex_groups = vertex_gaps(t, &vertices, stay);
        let n_edge = edges.len();
        // per simplex (edges first) whether it has gaps to grow into; per group its simplex
        let tried: Vec<bool> = (edge_groups.iter().chain(&vertex_groups))
            .map(|gs| !gs.is_empty())
            .collect();
        let owners: Vec<usize> = (edge_groups.iter().chain(&vertex_groups))
            .enumerate()
            .flat_map(|(i, gs)| std::iter::repeat_n(i, gs.len()))
            .collect();
        let groups: Vec<Vec<Growth>> = edge_groups
            .into_iter()
            .chain(vertex_groups)
            .flatten()
            .collect();
        if groups.is_empty() {
            break;
        }
        let near = points_near_cores(t, &groups);
        let on_plane = OnPlaneEdges {
            split: how != EdgeGaps::OffPlane,
            planes: t.planes,
            internal: t.internal,
        };
        let points = split_points(t.positions, &groups, reach, on_plane, &near);
        let g = grow(t, &groups, points);
        let mut grew = vec![false; tried.len()];
        for (&owner, &n) in owners.iter().zip(&g.tets_per_group) {
            if n > 0 {
                if owner < n_edge {
                    stats.edge_gaps += 1;
                } else {
                    stats.vertex_gaps += 1;
                }
                grew[owner] = true;
            }
        }
        let added: u64 = g.tets_per_group.iter().sum();
        grown_any |= added > 0;
        stats.tets += added;
        stats.points += g.points;
        touched.extend(g.touched);
        // the simplices that had gaps to grow into and grew into none: another gap stays open
        let refused = |i: usize| tried[i] && !grew[i];
        edges = (0..n_edge)
            .filter(|&i| refused(i))
            .map(|i| edges[i])
            .collect();
        vertices = (0..vertices.len())
            .filter(|&i| refused(n_edge + i))
            .map(|i| vertices[i])
            .collect();
        if edges.is_empty() && vertices.is_empty() {
            break;
        }
    }
    touched.sort_unstable();
    touched.dedup();
    grown_any.then_some(touched)
}

/// Choices of the gap left open tried per singular simplex in a round (`grow_round`).
const ALTERNATIVES: usize = 3;

/// What growth changes in a triangulation, to put it back. Points and their planes are only ever
/// appended while a snapshot is held (growth adds split points; nothing moves one), so a snapshot
/// keeps their count, and of the points appended since an earlier snapshot (`of_since`) a copy:
/// copying every position on each try was a pass over all of them.
#[derive(Clone, Default)]
pub(crate) struct Snapshot {
    /// Points kept as they are; those after them are `positions`'s (and likewise the planes).
    base: (usize, usize),
    positions: Vec<[f64; 3]>,
    planes: Vec<Planes>,
    kept: Vec<[u32; 4]>,
    fillable: Vec<[u32; 4]>,
    external: Vec<[u32; 4]>,
    internal: FxHashSet<[u32; 3]>,
}

impl Snapshot {
    /// The state of `t`, to be restored while its points are still there (restoring an earlier
    /// snapshot first takes them away: use [`Snapshot::of_since`] then).
    pub(crate) fn of(t: &Triangulation) -> Snapshot {
        Self::with_base(t, (t.positions.len(), t.planes.len()))
    }

    /// The state of `t`, restorable after `earlier` was restored and other points appended.
    pub(crate) fn of_since(t: &Triangulation, earlier: &Snapshot) -> Snapshot {
        let (p, q) = earlier.base;
        Self::with_base(t, (p + earlier.positions.len(), q + earlier.planes.len()))
    }

    fn with_base(t: &Triangulation, base: (usize, usize)) -> Snapshot {
        Snapshot {
            base,
            positions: t.positions[base.0..].to_vec(),
            planes: t.planes[base.1..].to_vec(),
            kept: t.kept.clone(),
            fillable: t.fillable.clone(),
            external: t.external.clone(),
            internal: t.internal.clone(),
        }
    }

    pub(crate) fn restore(self, t: &mut Triangulation) {
        t.positions.truncate(self.base.0);
        t.positions.extend(self.positions);
        t.planes.truncate(self.base.1);
        t.planes.extend(self.planes);
        *t.kept = self.kept;
        *t.fillable = self.fillable;
        *t.external = self.external;
        *t.internal = self.internal;
    }
}

/// Per core vertex of `groups`, the positions of the other vertices of its tetrahedra (with it).
fn points_near_cores(t: &Triangulation, groups: &[Vec<Growth>]) -> Vec<([f64; 3], u32)> {
    let n = t.positions.len();
    let mut core = vec![false; n];
    for g in groups.iter().flatten() {
        for &c in &g.core {
            core[c as usize] = true;
        }
    }
    let mut out: Vec<(u32, u32)> = Vec::new();
    let all = t
        .kept
        .iter()
        .chain(t.fillable.iter())
        .chain(t.external.iter());
    for x in all.filter(|x| x.iter().any(|&v| core[v as usize])) {
        for &c in x.iter().filter(|&&c| core[c as usize]) {
            out.extend(x.iter().filter(|&&v| v != c).map(|&v| (v, c)));
        }
    }
    out.sort_unstable();
    out.dedup();
    out.into_iter()
        .map(|(v, c)| (t.positions[v as usize], c))
        .collect()
}

/// Per growth, the edges from its core to its other vertices, split at `reach` from the core
/// vertex (at most halfway), but those `on_plane` keeps whole; an edge asked for twice keeps its
/// first point. A point that would lie within `MIN_GAP` of the distance (or `SHORT_EDGE` of its
/// edge) of another split point of its core or of a vertex around its core (`near`) moves along
/// its edge where that clears it (`spacing`).
fn split_points(
    positions: &[[f64; 3]],
    groups: &[Vec<Growth>],
    reach: Reach,
    on_plane: OnPlaneEdges,
    near: &[([f64; 3], u32)],
) -> FxHashMap<(u32, u32), [f64; 3]> {
    let mut out = FxHashMap::default();
    let mut spaced = Spaced::new(MIN_GAP * reach.distance, near);
    let kept_off = on_plane.kept_off(groups);
    for g in groups.iter().flatten() {
        for &c in &g.core {
            for &x in g.tet.iter().filter(|x| !g.core.contains(x)) {
                if kept_off.contains(&edge(c, x)) {
                    continue;
                }
                let (p, q) = (positions[c as usize], positions[x as usize]);
                if p != q && !out.contains_key(&edge(c, x)) {
                    let d = crate::sections::sub(q, p);
                    let len = crate::sections::dot(d, d).sqrt();
                    let fraction = |k: f64| k * reach.along(len);
                    let (point, _) = spaced.place([p, q], fraction, Rule::Growth, c);
                    out.insert(edge(c, x), point);
                }
            }
        }
    }
    out
}

/// Which edges on a plane a growth splits (`EdgeGaps`): all, or (off the planes) only those whose
/// faces on a plane in the growths' tetrahedra are all inside their sections. A face outside its
/// section is the gap on the plane that must stay open (a saddle); a point on such a face's edge
/// would put a kept face there. A face inside its section may be kept, and an edge of it left
/// whole can leave a gap tetrahedron with no part near the core (its near part would reach the
/// edge's far end): Elephant under a 300-frame sweep (seed 1) kept a singular edge on a plane,
/// at a vertex on two frames' line, that way.
#[derive(Clone, Copy)]
struct OnPlaneEdges<'a> {
    split: bool,
    planes: &'a [Planes],
    internal: &'a FxHashSet<[u32; 3]>,
}

impl OnPlaneEdges<'_> {
    /// The edges of `groups`' tetrahedra not to split: none when all are split, else those on a
    /// face on a plane outside its section.
    fn kept_off(&self, groups: &[Vec<Growth>]) -> FxHashSet<(u32, u32)> {
        let mut out = FxHashSet::default();
        if self.split {
            return out;
        }
        for g in groups.iter().flatten() {
            for i in 0..4 {
                let f = super::complex::outward_face(&g.tet, i);
                if on_a_plane(self.planes, &f) && !self.internal.contains(&key3(f)) {
                    out.extend([edge(f[0], f[1]), edge(f[1], f[2]), edge(f[0], f[2])]);
                }
            }
        }
        out
    }
}

/// The tetrahedra of the triangulation around each wanted simplex (`key` gives the simplices of
/// a tetrahedron to look up), each with whether K keeps it.
fn around<K: std::hash::Hash + Eq + Copy>(
    t: &Triangulation,
    wanted: &FxHashSet<K>,
    keys: impl Fn(&[u32; 4]) -> SmallVec<[K; 6]>,
    vertices: impl Fn(&K) -> SmallVec<[u32; 2]>,
) -> FxHashMap<K, Vec<([u32; 4], bool)>> {
    let mut map: FxHashMap<K, Vec<([u32; 4], bool)>> = FxHashMap::default();
    // a wanted simplex has one of the wanted vertices: skip tetrahedra without any
    let mut marked = vec![false; t.positions.len()];
    for v in wanted.iter().flat_map(vertices) {
        marked[v as usize] = true;
    }
    let lists = [
        (&*t.kept, true),
        (&*t.fillable, false),
        (&*t.external, false),
    ];
    for (list, kept) in lists {
        for tet in list
            .iter()
            .filter(|x| x.iter().any(|&v| marked[v as usize]))
        {
            for k in keys(tet) {
                if wanted.contains(&k) {
                    map.entry(k).or_default().push((*tet, kept));
                }
            }
        }
    }
    map
}

/// Whether the part of `tet` near `core` may be kept: every face of `tet` through a core vertex
/// that lies on a plane is inside that plane's section.
fn may_grow(
    tet: &[u32; 4],
    core: &[u32],
    planes: &[Planes],
    internal: &FxHashSet<[u32; 3]>,
) -> bool {
    (0..4).all(|i| {
        let f = super::complex::outward_face(tet, i);
        let through_core = f.iter().any(|v| core.contains(v));
        !through_core || !on_a_plane(planes, &f) || internal.contains(&key3(f))
    })
}

/// Components of `items` (tetrahedra around one vertex or edge) adjacent through a shared face
/// (which then contains that vertex or edge).
fn components_through(items: &[[u32; 4]]) -> Vec<Vec<usize>> {
    let mut by_face: FxHashMap<[u32; 3], Vec<usize>> = FxHashMap::default();
    for (i, t) in items.iter().enumerate() {
        for j in 0..4 {
            let f = super::complex::outward_face(t, j);
            by_face.entry(key3(f)).or_default().push(i);
        }
    }
    let mut seen = vec![false; items.len()];
    let mut out = Vec::new();
    for s in 0..items.len() {
        if seen[s] {
            continue;
        }
        seen[s] = true;
        let (mut stack, mut comp) = (vec![s], Vec::new());
        while let Some(i) = stack.pop() {
            comp.push(i);
            for j in 0..4 {
                let f = key3(super::complex::outward_face(&items[i], j));
                for &n in &by_face[&f] {
                    if !seen[n] {
                        seen[n] = true;
                        stack.push(n);
                    }
                }
            }
        }
        comp.sort_unstable();
        out.push(comp);
    }
    out
}

/// The gaps to grow into, per singular edge (one list per edge): all but one of those that may
/// grow (all of them if one may not), the one left open the `stay`-th largest.
fn edge_gaps(
    t: &Triangulation,
    edges: &[(u32, u32)],
    how: EdgeGaps,
    stay: usize,
) -> Vec<Vec<Vec<Growth>>> {
    let wanted: FxHashSet<(u32, u32)> = edges.iter().copied().collect();
    let ring = around(
        t,
        &wanted,
        |tet| {
            super::complex::TET_EDGES
                .iter()
                .map(|&(i, j)| edge(tet[i], tet[j]))
                .collect()
        },
        |e| [e.0].into_iter().collect(),
    );
    let mut out = Vec::new();
    for e in edges {
        let Some(ring) = ring.get(e) else {
            out.push(Vec::new());
            continue;
        };
        let core: SmallVec<[u32; 3]> = [e.0, e.1].into_iter().collect();
        let gaps: Vec<[u32; 4]> = ring.iter().filter(|r| !r.1).map(|r| r.0).collect();
        let open = is_open(ring, &core);
        out.push(all_but_one(t, &gaps, &core, open, how, stay));
    }
    out
}

/// Whether the tetrahedra around `core` leave a face through it with one tetrahedron: the
/// triangulation ends there (a plane with no cell with volume beyond it), and the space beyond is
/// one more gap, which cannot be grown into.
fn is_open(around: &[([u32; 4], bool)], core: &[u32]) -> bool {
    let mut count: FxHashMap<[u32; 3], u32> = FxHashMap::default();
    for (tet, _) in around {
        for i in 0..4 {
            let f = key3(super::complex::outward_face(tet, i));
            if core.iter().all(|v| f.contains(v)) {
                *count.entry(f).or_default() += 1;
            }
        }
    }
    count.values().any(|&n| n == 1)
}

/// Every gap component but one, of those whose tetrahedra may all grow at `core`. The one left
/// open is a gap that may not grow, else the `stay`-th largest (none if the space around is
/// `open`: the space beyond stays). Empty where there is no `stay`-th choice.
fn all_but_one(
    t: &Triangulation,
    gaps: &[[u32; 4]],
    core: &SmallVec<[u32; 3]>,
    open: bool,
    how: EdgeGaps,
    stay: usize,
) -> Vec<Vec<Growth>> {
    let mut comps: Vec<(bool, Vec<[u32; 4]>)> = components_through(gaps)
        .into_iter()
        .map(|c| {
            let tets: Vec<[u32; 4]> = c.iter().map(|&i| gaps[i]).collect();
            let ok = how == EdgeGaps::OffPlane
                || tets.iter().all(|x| may_grow(x, core, t.planes, t.internal));
            (ok, tets)
        })
        .collect();
    if comps.len() + usize::from(open) < 2 {
        return Vec::new();
    }
    // the largest gap that may not grow stays, or the space beyond if open (no other choice);
    // else the `stay`-th largest
    comps.sort_by_key(|(ok, c)| (!*ok, std::cmp::Reverse(c.len())));
    let forced = match comps.iter().position(|(ok, _)| !ok) {
        Some(i) => Some(i),
        None => open.then_some(usize::MAX),
    };
    let stay = match forced {
        Some(i) if stay == 0 => i,
        None if stay < comps.len() => stay,
        _ => return Vec::new(),
    };
    comps
        .into_iter()
        .enumerate()
        .filter(|&(i, (ok, _))| i != stay && ok)
        .map(|(_, (_, c))| {
            // a gap of whole tetrahedra that may all be kept is kept whole (no new points)
            let whole = how == EdgeGaps::Whole
                && core.len() == 2
                && c.iter().all(|x| may_grow(x, x, t.planes, t.internal));
            c.into_iter()
                .map(|tet| Growth {
                    tet,
                    core: if whole {
                        tet.into_iter().collect()
                    } else {
                        core.clone()
                    },
                    keep_slivers: false,
                })
                .collect()
        })
        .collect()
}

/// The gaps to grow into, per pinched vertex (one list per vertex): a strip joining two kept
/// components, or all holes of one kept component but the `stay`-th largest (`all_but_one`).
fn vertex_gaps(t: &Triangulation, vertices: &[u32], stay: usize) -> Vec<Vec<Vec<Growth>>> {
    let wanted: FxHashSet<u32> = vertices.iter().copied().collect();
    let star = around(
        t,
        &wanted,
        |tet| tet.iter().copied().collect(),
        |&v| [v].into_iter().collect(),
    );
    let mut out = Vec::new();
    for v in vertices {
        let Some(star) = star.get(v) else {
            out.push(Vec::new());
            continue;
        };
        let core: SmallVec<[u32; 3]> = [*v].into_iter().collect();
        let kept: Vec<[u32; 4]> = star.iter().filter(|r| r.1).map(|r| r.0).collect();
        let gaps: Vec<[u32; 4]> = star.iter().filter(|r| !r.1).map(|r| r.0).collect();
        let kept_comps = components_through(&kept);
        if kept_comps.len() >= 2 {
            // one strip, no other choice
            let strip = if stay == 0 {
                shortest_strip(t, &kept, &kept_comps, &gaps, *v)
            } else {
                None
            };
            let growths = strip.into_iter().map(|strip| {
                strip
                    .into_iter()
                    .map(|tet| Growth {
                        tet,
                        core: core.clone(),
                        keep_slivers: false,
                    })
                    .collect()
            });
            out.push(growths.collect());
        } else {
            let open = is_open(star, &core);
            out.push(all_but_one(t, &gaps, &core, open, EdgeGaps::NearEdge, stay));
        }
    }
    out
}

/// The shortest chain of gap tetrahedra around `v` (adjacent through faces through v) from one
/// kept component to another, each of which may grow at v.
fn shortest_strip(
    t: &Triangulation,
    kept: &[[u32; 4]],
    kept_comps: &[Vec<usize>],
    gaps: &[[u32; 4]],
    v: u32,
) -> Option<Vec<[u32; 4]>> {
    let faces_through = |tet: &[u32; 4]| -> SmallVec<[[u32; 3]; 3]> {
        (0..4)
            .map(|i| key3(super::complex::outward_face(tet, i)))
            .filter(|f| f.contains(&v))
            .collect()
    };
    let mut comp_of_face: FxHashMap<[u32; 3], usize> = FxHashMap::default();
    for (ci, comp) in kept_comps.iter().enumerate() {
        for &i in comp {
            for f in faces_through(&kept[i]) {
                comp_of_face.insert(f, ci);
            }
        }
    }
    let usable: Vec<usize> = (0..gaps.len())
        .filter(|&i| may_grow(&gaps[i], &[v], t.planes, t.internal))
        .collect();
    // a strip through a sliver is refused as a whole (its child near v is a sliver too): the
    // shortest strip of tetrahedra that are not, where there is one
    let solid: Vec<usize> = (usable.iter().copied())
        .filter(|&i| !super::refine::sliver(t.positions, &gaps[i]))
        .collect();
    strip_through(gaps, &solid, &comp_of_face, &faces_through)
        .or_else(|| strip_through(gaps, &usable, &comp_of_face, &faces_through))
}

/// The shortest chain of the `usable` gap tetrahedra, adjacent through faces through the vertex
/// (`faces_through`), from one touching the first kept component (`comp_of_face`) to one
/// touching another.
fn strip_through(
    gaps: &[[u32; 4]],
    usable: &[usize],
    comp_of_face: &FxHashMap<[u32; 3], usize>,
    faces_through: &impl Fn(&[u32; 4]) -> SmallVec<[[u32; 3]; 3]>,
) -> Option<Vec<[u32; 4]>> {
    let mut gap_of_face: FxHashMap<[u32; 3], Vec<usize>> = FxHashMap::default();
    for &i in usable {
        for f in faces_through(&gaps[i]) {
            gap_of_face.entry(f).or_default().push(i);
        }
    }
    let touches = |i: usize| -> SmallVec<[usize; 3]> {
        faces_through(&gaps[i])
            .iter()
            .filter_map(|f| comp_of_face.get(f).copied())
            .collect()
    };
    // breadth-first from the gap tets touching the first kept component, to one touching another
    let mut from: FxHashMap<usize, usize> = FxHashMap::default();
    let mut queue = std::collections::VecDeque::new();
    for &i in usable {
        if touches(i).contains(&0) {
            from.insert(i, i);
            queue.push_back(i);
        }
    }
    while let Some(i) = queue.pop_front() {
        if touches(i).iter().any(|&c| c != 0) {
            let mut chain = vec![gaps[i]];
            let mut j = i;
            while from[&j] != j {
                j = from[&j];
                chain.push(gaps[j]);
            }
            return Some(chain);
        }
        for f in faces_through(&gaps[i]) {
            for &n in gap_of_face.get(&f).into_iter().flatten() {
                if let std::collections::hash_map::Entry::Vacant(e) = from.entry(n) {
                    e.insert(i);
                    queue.push_back(n);
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::assembly::{boundary_of, singularities};

    use crate::bm::refine::test_support::{orient, positive, Owned};

    /// Snapshots put back the points they saw, as the growth orders use them: a later state
    /// kept (`of_since`), the earlier one restored and other points appended, then the later
    /// state restored again over those.
    #[test]
    fn snapshots_restore_the_points_they_saw() {
        let mut o = Owned::at(vec![[0.0; 3], [1.0, 0.0, 0.0]]);
        o.kept.push([0, 1, 0, 1]);
        let mut t = o.view();
        let start = Snapshot::of(&t);
        let add = |t: &mut Triangulation, x: f64, plane: u32| {
            t.positions.push([x, x, x]);
            t.planes.push(smallvec::smallvec![plane]);
            t.kept.push([0, 1, t.positions.len() as u32 - 1, 0]);
        };
        add(&mut t, 2.0, 7);
        add(&mut t, 3.0, 8);
        let later = Snapshot::of_since(&t, &start);
        let (positions, planes, kept) = (t.positions.clone(), t.planes.clone(), t.kept.clone());
        start.clone().restore(&mut t);
        assert_eq!(t.positions.len(), 2);
        assert_eq!((t.planes.len(), t.kept.len()), (2, 1));
        add(&mut t, 9.0, 9);
        later.restore(&mut t);
        assert_eq!(*t.positions, positions);
        assert_eq!(*t.planes, planes);
        assert_eq!(*t.kept, kept);
        // a snapshot restored after growth that only appended takes the new points away
        let before = Snapshot::of(&t);
        add(&mut t, 4.0, 1);
        before.restore(&mut t);
        assert_eq!(*t.positions, positions);
        assert_eq!(*t.planes, planes);
    }

    /// Eight tetrahedra around the vertex 0 (the octants of an octahedron with apexes ±x, ±y,
    /// ±z), `kept` of them in K.
    type Split = (Vec<[f64; 3]>, Vec<[u32; 4]>, Vec<[u32; 4]>);

    fn octahedron(kept_octants: &[usize]) -> Split {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        let mut kept = Vec::new();
        let mut rest = Vec::new();
        let mut i = 0;
        for x in [1, 2] {
            for y in [3, 4] {
                for z in [5, 6] {
                    let t = positive(&positions, [0, x, y, z]);
                    if kept_octants.contains(&i) {
                        kept.push(t);
                    } else {
                        rest.push(t);
                    }
                    i += 1;
                }
            }
        }
        (positions, kept, rest)
    }

    /// The octahedron with `kept_octants` kept and the rest fillable, no planes.
    fn octants_owned(kept_octants: &[usize]) -> Owned {
        let (positions, kept, fillable) = octahedron(kept_octants);
        Owned {
            kept,
            fillable,
            ..Owned::at(positions)
        }
    }

    fn resolve_octants(kept_octants: &[usize]) -> (SingularStats, Vec<[u32; 4]>, Vec<[f64; 3]>) {
        let mut o = octants_owned(kept_octants);
        let (s, _) = resolve(&mut o.view(), 4, Reach::near(0.1), EdgeGaps::Whole, None);
        (s, o.kept, o.positions)
    }

    /// Two planes crossing in a line through a section, as two frames of a freehand sweep: z = 0
    /// (vertices 0-4, section on the +x half) and x = 0 (vertices 0, 3-6, section in the
    /// quadrants +y+z and -y-z), the origin on both. The octants +x+y+z and +x-y-z are kept, so
    /// the edge (0, 1) on z = 0, from the line out, is singular: a checkerboard across z = 0
    /// inside its section. Each gap has a face on x = 0 outside that section, so only growth off
    /// the planes may close one; it must split the gap's edge from 1 to the line (on z = 0,
    /// inside its section), or the gap has no part near the edge that avoids the line (Elephant,
    /// 300-frame sweep, seed 1, before `OnPlaneEdges`).
    #[test]
    fn a_checkerboard_at_two_crossing_planes_is_bridged_off_the_planes() {
        let mut o = octants_owned(&[0, 3]);
        for v in 0..5 {
            o.planes[v].push(0);
        }
        for v in [0, 3, 4, 5, 6] {
            o.planes[v].push(1);
        }
        let internal = [[0, 1, 3], [0, 1, 4], [0, 3, 5], [0, 4, 6]];
        o.internal = internal.into_iter().map(key3).collect();
        assert_eq!(singularities(&boundary_of(&o.kept)).0, 1);
        // the gap +x+y-z: its edges on its face on x = 0 (outside) stay whole, not the others
        let gap = Growth {
            tet: positive(&o.positions, [0, 1, 3, 6]),
            core: [0, 1].into_iter().collect(),
            keep_slivers: false,
        };
        let rule = |split| OnPlaneEdges {
            split,
            planes: &o.planes,
            internal: &o.internal,
        };
        let kept_off = rule(false).kept_off(&[vec![gap.clone()]]);
        let want: FxHashSet<(u32, u32)> = [(0, 3), (0, 6), (3, 6)].into_iter().collect();
        assert_eq!(kept_off, want);
        assert!(rule(true).kept_off(&[vec![gap]]).is_empty());
        resolve(&mut o.view(), 4, Reach::near(0.1), EdgeGaps::OffPlane, None);
        let in_sections = o
            .kept
            .iter()
            .all(|x| crate::bm::refine::faces_in_sections(x, &o.planes, &o.internal));
        assert_eq!(
            (singularities(&boundary_of(&o.kept)), in_sections),
            ((0, 0), true)
        );
    }

    /// A saddle: on the plane z = 0 (vertices 0-4) the section is the quadrants +x+y and -x-y,
    /// which touch at the origin; above them the octants 0 and 6 are kept, so the edge from the
    /// origin up (0, 5) is singular. Growing near the edge would put the quadrants +x-y or -x+y,
    /// outside the section, into K; growth off the plane bridges the octants above it instead.
    #[test]
    fn a_section_pinched_at_a_vertex_gets_a_saddle() {
        let run = |how: EdgeGaps| {
            let mut o = octants_owned(&[0, 6]);
            for p in o.planes.iter_mut().take(5) {
                p.push(0);
            }
            o.internal = [key3([0, 1, 3]), key3([0, 2, 4])].into_iter().collect();
            resolve(&mut o.view(), 4, Reach::near(0.1), how, None);
            let in_sections = o
                .kept
                .iter()
                .all(|x| crate::bm::refine::faces_in_sections(x, &o.planes, &o.internal));
            (singularities(&boundary_of(&o.kept)), in_sections)
        };
        let (near, in_sections) = run(EdgeGaps::NearEdge);
        assert!(near != (0, 0) && in_sections, "{near:?}");
        assert_eq!(run(EdgeGaps::OffPlane), ((0, 0), true));
    }

    #[test]
    fn two_octants_touching_at_the_centre_are_joined() {
        // octants 0 (+x+y+z) and 7 (-x-y-z) meet only at the vertex 0
        let (s, kept, positions) = resolve_octants(&[0, 7]);
        assert!(s.vertex_gaps >= 1, "{s:?}");
        assert_eq!(singularities(&boundary_of(&kept)), (0, 0));
        assert!(kept.iter().all(|&k| orient(&positions, k) > 0.0));
    }

    #[test]
    fn two_octants_sharing_an_edge_are_joined_along_it() {
        // octants 0 (+x+y+z) and 3 (+x-y-z) share only the edge (0, +x)
        let (s, kept, positions) = resolve_octants(&[0, 3]);
        assert!(s.edge_gaps >= 1, "{s:?}");
        assert_eq!(singularities(&boundary_of(&kept)), (0, 0));
        assert!(kept.iter().all(|&k| orient(&positions, k) > 0.0));
    }

    #[test]
    fn an_open_ring_at_a_last_plane_is_closed_by_its_one_gap() {
        // three tets above z = 0 around the edge (0,1) on it, nothing below (a last plane):
        // the outer two kept, the middle one a gap; the space below is the other gap
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.3, 0.7, 0.7],
            [0.3, -0.7, 0.7],
        ];
        let [a, b, c] = [[0, 1, 2, 4], [0, 1, 4, 5], [0, 1, 5, 3]].map(|t| positive(&positions, t));
        assert_eq!(singularities(&boundary_of(&[a, c])).0, 1);
        let mut o = Owned {
            kept: vec![a, c],
            fillable: vec![b],
            ..Owned::at(positions)
        };
        let (s, _) = resolve(&mut o.view(), 4, Reach::near(0.1), EdgeGaps::Whole, None);
        assert_eq!(s.edge_gaps, 1, "{s:?}");
        // the gap may be kept whole: no new points
        assert_eq!((s.tets, s.points), (1, 0));
        assert_eq!(singularities(&boundary_of(&o.kept)), (0, 0));
    }

    /// A singular edge (0, 1) whose ring has two gaps: a wedge of two tetrahedra and a sliver
    /// 1e-7 rad wide. The smaller one is grown into first, but its children near the edge are
    /// slivers and refused; then the larger gap is grown into instead and the edge is resolved
    /// in the same round (before, nothing grew and the edge stayed singular).
    #[test]
    fn a_refused_gap_leaves_the_other_gap_to_grow_into() {
        let angles = [
            0.0f64,
            72.0,
            144.0,
            216.0,
            288.0,
            360.0 - 1e-7f64.to_degrees(),
        ];
        let mut positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        positions.extend((angles.iter().map(|a| a.to_radians())).map(|a| [0.5, a.cos(), a.sin()]));
        let ring: Vec<[u32; 4]> = (0..6)
            .map(|i| positive(&positions, [0, 1, 2 + i, 2 + (i + 1) % 6]))
            .collect();
        let (kept, fillable) = ([ring[0], ring[3], ring[4]], [ring[1], ring[2], ring[5]]);
        assert_eq!(singularities(&boundary_of(&kept)), (1, 0));
        let mut o = Owned {
            kept: kept.to_vec(),
            fillable: fillable.to_vec(),
            ..Owned::at(positions)
        };
        let (s, _) = resolve(&mut o.view(), 1, Reach::near(0.1), EdgeGaps::NearEdge, None);
        assert_eq!(s.edge_gaps, 1, "{s:?}");
        assert_eq!(singularities(&boundary_of(&o.kept)), (0, 0));
        assert!(o.kept.iter().all(|&k| orient(&o.positions, k) > 0.0));
    }

    /// Two cones touching at the vertex 0 of a double cone over a hexagon on z = 0 (apexes ±z),
    /// one above the edge p0p1, one below p2p3, where p1 and p2 are 1e-7 rad apart: both
    /// shortest strips between the cones pass a sliver (the tetrahedra over p1p2), whose child
    /// near 0 is refused, so the strip goes the long way round (odd072: a needle cone to a tiny
    /// section touching the solid at a contour vertex).
    #[test]
    fn a_strip_between_two_cones_goes_round_a_sliver() {
        let degrees = [
            0.0f64,
            90.0,
            90.0 + 1e-7f64.to_degrees(),
            180.0,
            240.0,
            300.0,
        ];
        let mut positions = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
        positions.extend(degrees.map(|a| [a.to_radians().cos(), a.to_radians().sin(), 0.0]));
        let p = |i: usize| (3 + i % 6) as u32;
        let upper: Vec<[u32; 4]> = (0..6)
            .map(|i| positive(&positions, [0, p(i), p(i + 1), 1]))
            .collect();
        let lower: Vec<[u32; 4]> = (0..6)
            .map(|i| positive(&positions, [0, p(i), p(i + 1), 2]))
            .collect();
        assert!(crate::bm::refine::sliver(&positions, &upper[1]));
        let kept = vec![upper[0], lower[2]];
        assert_eq!(singularities(&boundary_of(&kept)), (0, 1));
        let fillable = (upper.iter().chain(&lower))
            .filter(|t| !kept.contains(t))
            .copied()
            .collect();
        let mut o = Owned {
            kept,
            fillable,
            ..Owned::at(positions)
        };
        let (s, _) = resolve(&mut o.view(), 4, Reach::near(0.1), EdgeGaps::NearEdge, None);
        assert_eq!(s.vertex_gaps, 1, "{s:?}");
        assert_eq!(singularities(&boundary_of(&o.kept)), (0, 0));
        assert!(o.kept.iter().all(|&k| orient(&o.positions, k) > 0.0));
    }

    #[test]
    fn a_clean_boundary_is_left_alone() {
        let (s, kept, _) = resolve_octants(&[0, 1]);
        let none = SingularStats {
            per_round: vec![(0, 0)],
            ..Default::default()
        };
        assert_eq!(s, none);
        assert_eq!(kept.len(), 2);
    }

    #[test]
    fn split_points_towards_near_duplicate_vertices_stay_apart() {
        // core 0; vertices 1, 2, 3 within 2e-7 of each other, 1 away (a jittering contour), and 4
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 2e-7, 0.0],
            [1.0, 1e-7, 1e-7],
            [0.0, 1.0, 0.0],
        ];
        let planes = vec![Planes::new(); 5];
        let core: SmallVec<[u32; 3]> = [0].into_iter().collect();
        let groups = vec![
            vec![Growth {
                tet: [0, 1, 2, 4],
                core: core.clone(),
                keep_slivers: false,
            }],
            vec![Growth {
                tet: [0, 1, 3, 4],
                core,
                keep_slivers: false,
            }],
        ];
        let distance = 1e-3;
        let near = [(positions[4], 0)];
        let internal = FxHashSet::default();
        let on_plane = OnPlaneEdges {
            split: true,
            planes: &planes,
            internal: &internal,
        };
        let points = split_points(&positions, &groups, Reach::near(distance), on_plane, &near);
        assert_eq!(points.len(), 4);
        let ps: Vec<[f64; 3]> = points.values().copied().collect();
        for (i, a) in ps.iter().enumerate() {
            for b in &ps[i + 1..] {
                let d = (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
                assert!(d >= MIN_GAP * distance, "{a:?} {b:?}: {d:e}");
            }
        }
        // each on its edge, between a quarter and two growth distances from the core
        for (&(a, b), p) in &points {
            let (x, y) = (positions[a as usize], positions[b as usize]);
            let len = (0..3).map(|k| (y[k] - x[k]).powi(2)).sum::<f64>().sqrt();
            let t = (0..3).map(|k| (p[k] - x[k]).powi(2)).sum::<f64>().sqrt();
            assert!((0.25 * distance..=2.0 * distance).contains(&t), "{t}");
            let cross = [
                (p[1] - x[1]) * (y[2] - x[2]) - (p[2] - x[2]) * (y[1] - x[1]),
                (p[2] - x[2]) * (y[0] - x[0]) - (p[0] - x[0]) * (y[2] - x[2]),
                (p[0] - x[0]) * (y[1] - x[1]) - (p[1] - x[1]) * (y[0] - x[0]),
            ];
            assert!(cross.iter().all(|c| c.abs() < 1e-15 * len), "{cross:?}");
        }
    }

    /// Two edges from a core to far vertices 1e-6 apart: at a growth distance of 1e-3 along edges
    /// of length 1 their split points are 1e-9 apart (needles whose faces lie on each other); at a
    /// fifth of each edge, 2e-7 apart. A short edge is split at the distance still.
    #[test]
    fn a_reach_by_fraction_keeps_the_points_of_converging_edges_apart() {
        let core = [0.0; 3];
        let far = [[1.0, 0.0, 0.0], [1.0, 1e-6, 0.0]];
        let split = |reach: Reach, q: [f64; 3]| {
            let s = reach.along(1.0).min(0.5);
            q.map(|c| s * c)
        };
        let gap = |reach: Reach| {
            let (a, b) = (split(reach, far[0]), split(reach, far[1]));
            (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
        };
        let near = Reach::near(1e-3);
        let spread = Reach {
            fraction: 0.2,
            ..near
        };
        assert!((gap(near) - 1e-9).abs() < 1e-15, "{}", gap(near));
        assert!((gap(spread) - 2e-7).abs() < 1e-15, "{}", gap(spread));
        assert_eq!(split(spread, core), core);
        // an edge of 2e-3: the distance (half of it) is farther than the fraction
        assert_eq!(spread.along(2e-3), 0.5);
    }
}
