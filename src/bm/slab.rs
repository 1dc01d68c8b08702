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
//! Neighbouring zone triangles may stand on different apexes. Their prisms then meet only at the
//! zone's edges and vertices, and the tetrahedra between the parents (around an inner edge or
//! above an inner vertex of the zone) are *gaps*: each keeps its part below the split points of
//! its edges from the zone (at the same thickness), so a zone's slab is one solid whose inner
//! edges and vertices are inside it. Without them an inner edge had four surface triangles (the
//! two zone triangles and a wall of each prism, lying nearly on each other above it). A gap that
//! is a sliver keeps its sliver part: refusing it would leave a crack between the prisms.
//!
//! An edge whose two ends share a plane lies on that plane (on the cell's boundary, in a section
//! or outside it) and is not split at first: then no split point lies on a plane, every slab face
//! other than Z has a split point, and no slab face lies on a plane: every section keeps R ∩ P = A.
//! Where Z borders a line of the arrangement, its slab tapers to that line. A zone left without a
//! slab that way (every edge to its apex on a plane: a cell corner on two planes, as between
//! axis-aligned planes) is tried once more with those edges split too; `refine::grow` then keeps
//! a slab only where its faces on a plane lie inside that plane's section.
use super::refine::{edge, grow, key3, key4, Growth, Planes, Triangulation};
use super::spacing::{Rule, Spaced, SLAB_GAP};
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::sections::{cross, dot, sub};
use gaps::gaps;

mod gaps;
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

#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlabStats {
    /// Flat-zone triangles that got a slab, and those left flat.
    pub thickened: u64,
    pub left: u64,
    /// Tetrahedra of the slabs, and the split points they added.
    pub tets: u64,
    pub points: u64,
    /// Tetrahedra between the prisms of one zone (standing on an inner vertex or edge of it) that
    /// kept their part below the split points, and those refused.
    pub gaps_closed: u64,
    pub gaps_open: u64,
    /// Thinnest slab (height of a split point above its zone's plane).
    pub min_thickness: f64,
}

/// Give every flat zone of `faces` (per face, per side: its section triangles) a slab of
/// `thickness` inside K.
pub fn thicken(t: &mut Triangulation, faces: &[Vec<Side>], thickness: f64) -> SlabStats {
    let (candidates, unsided) = parents_of_zones(faces);
    let first_new = t.positions.len();
    let mut stats = SlabStats {
        left: unsided,
        min_thickness: f64::INFINITY,
        ..Default::default()
    };
    // first every zone triangle's preferred parent; where refused (a split would flip a rounded
    // neighbour), the next side's, if that tetrahedron is still unsplit
    let mut pending: Vec<(&[Parent], &[Parent])> =
        candidates.iter().map(|c| (&c[..], &c[..])).collect();
    let mut left: Vec<&[Parent]> = Vec::new();
    while !pending.is_empty() {
        let parents: Vec<&Parent> = pending.iter().map(|c| &c.0[0]).collect();
        let refused = grow_slabs(t, &parents, thickness, false, first_new, &mut stats);
        let next = refused.iter().filter_map(|&i| pending[i].0.get(1));
        let existing = existing_among(t, next.map(|p| p.tet));
        pending = refused
            .into_iter()
            .filter_map(|i| {
                let (rest, all) = (&pending[i].0[1..], pending[i].1);
                let usable = rest
                    .first()
                    .is_some_and(|p| existing.contains(&key4(p.tet)));
                if !usable {
                    left.push(all);
                }
                usable.then_some((rest, all))
            })
            .collect();
    }
    // a zone still without a slab (mostly one whose parents' edges all lie on planes: a cell corner
    // on two planes, as cells between axis-aligned planes have) is tried once more with the edges on
    // planes split too, where those planes' sections hold the slab's faces on them
    let existing = existing_among(t, left.iter().flat_map(|all| all.iter().map(|p| p.tet)));
    let last: Vec<&Parent> = left
        .iter()
        .filter_map(|all| all.iter().find(|p| existing.contains(&key4(p.tet))))
        .collect();
    let unusable = left.len() - last.len();
    stats.left +=
        (unusable + grow_slabs(t, &last, thickness, true, first_new, &mut stats).len()) as u64;
    if stats.points == 0 {
        stats.min_thickness = 0.0;
    }
    stats
}

/// Which of the tetrahedra `wanted` the triangulation has now (sorted keys): one scan, a tetrahedron
/// looked up only when it has the smallest vertex of a wanted one (no set of the whole complex).
fn existing_among(
    t: &Triangulation,
    wanted: impl IntoIterator<Item = [u32; 4]>,
) -> FxHashSet<[u32; 4]> {
    let wanted: FxHashSet<[u32; 4]> = wanted.into_iter().map(key4).collect();
    let mut first = vec![false; t.positions.len()];
    for k in &wanted {
        first[k[0] as usize] = true;
    }
    t.kept
        .iter()
        .chain(t.fillable.iter())
        .chain(t.external.iter())
        .filter(|x| x.iter().any(|&v| first[v as usize]))
        .map(|&x| key4(x))
        .filter(|k| wanted.contains(k))
        .collect()
}

/// Grow the slabs of `parents` (with `on_planes`, splitting edges that lie on a plane too; the
/// slabs' points so far from `first_new` on); returns the indices of those refused.
fn grow_slabs(
    t: &mut Triangulation,
    parents: &[&Parent],
    thickness: f64,
    on_planes: bool,
    first_new: usize,
    stats: &mut SlabStats,
) -> Vec<usize> {
    if parents.is_empty() {
        return Vec::new();
    }
    // the rounds that leave edges on planes unsplit close the gaps between their prisms too; the
    // last try, which splits those edges as well, grows prisms only
    let (gaps, gap_lifts) = if on_planes {
        Default::default()
    } else {
        gaps(t, parents)
    };
    let mut lifts = parent_lifts(t.positions, parents);
    lifts.extend(gap_lifts);
    let points = split_points(
        t.positions,
        t.planes,
        &lifts,
        thickness,
        on_planes,
        first_new,
    );
    let min_thickness = points.values().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let groups: Vec<Vec<Growth>> = parents
        .iter()
        .map(|p| {
            vec![Growth {
                tet: p.tet,
                core: p.zone.into_iter().collect(),
                keep_slivers: false,
            }]
        })
        .chain(gaps.into_iter().map(|g| vec![g]))
        .collect();
    let g = grow(
        t,
        &groups,
        points.into_iter().map(|(e, p)| (e, p.0)).collect(),
    );
    let (of_parents, of_gaps) = g.tets_per_group.split_at(parents.len());
    stats.thickened += of_parents.iter().filter(|&&n| n > 0).count() as u64;
    stats.gaps_closed += of_gaps.iter().filter(|&&n| n > 0).count() as u64;
    stats.gaps_open += of_gaps.iter().filter(|&&n| n == 0).count() as u64;
    stats.tets += g.tets_per_group.iter().sum::<u64>();
    stats.points += g.points;
    if g.points > 0 {
        stats.min_thickness = stats.min_thickness.min(min_thickness);
    }
    (0..parents.len())
        .filter(|&i| g.tets_per_group[i] == 0)
        .collect()
}

/// A flat-zone triangle and the tetrahedron (positive: the triangle is outward from the cell)
/// of the side chosen for its slab.
struct Parent {
    zone: [u32; 3],
    tet: [u32; 4],
    /// The flat zone (numbered over all faces) and the side of its face the tetrahedron is on.
    zone_id: u32,
    side: u32,
}

/// Per flat zone (a component of flat triangles of one face, adjacent by edges), the side whose
/// attached triangles share most edges with the zone's border; its tetrahedra on the zone are the
/// parents, each followed by the other sides' tetrahedra on the same triangle (tried where the
/// first is refused). Returns them and how many flat triangles had no side with volume.
fn parents_of_zones(faces: &[Vec<Side>]) -> (Vec<Vec<Parent>>, u64) {
    let mut parents = Vec::new();
    let mut claimed: FxHashSet<[u32; 4]> = FxHashSet::default();
    let mut unsided = 0;
    let mut zones = 0u32;
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
            let zone_id = zones;
            zones += 1;
            let border = border_edges(&zone);
            // sides by preference: most attached edges on the zone's border, then a side with
            // volume, then the first side
            let mut ranked: Vec<usize> = (0..sides.len())
                .filter(|&s| sides[s].tris.iter().any(|t| t.apex != u32::MAX))
                .collect();
            ranked.sort_by_key(|&s| {
                let edges: FxHashSet<(u32, u32)> = sides[s]
                    .tris
                    .iter()
                    .filter(|t| t.attached)
                    .flat_map(|t| (0..3).map(move |i| edge(t.tri[i], t.tri[(i + 1) % 3])))
                    .collect();
                std::cmp::Reverse((
                    border.iter().filter(|e| edges.contains(e)).count(),
                    sides[s].has_volume,
                    std::cmp::Reverse(s),
                ))
            });
            let by_key: Vec<FxHashMap<[u32; 3], &FaceTri>> = ranked
                .iter()
                .map(|&s| sides[s].tris.iter().map(|t| (key3(t.tri), t)).collect())
                .collect();
            for z in &zone {
                let candidates: Vec<Parent> = (by_key.iter().zip(&ranked))
                    .filter_map(|(m, &s)| m.get(z).filter(|t| t.apex != u32::MAX).map(|t| (t, s)))
                    .map(|(t, s)| Parent {
                        zone: t.tri,
                        tet: [t.tri[0], t.tri[1], t.tri[2], t.apex],
                        zone_id,
                        side: s as u32,
                    })
                    .filter(|p| !claimed.contains(&key4(p.tet)))
                    .collect();
                match candidates.first() {
                    Some(first) => {
                        claimed.insert(key4(first.tet));
                        parents.push(candidates);
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
    edge_counts(tris)
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect()
}

/// How many triangles of `tris` use each of their edges.
fn edge_counts(tris: &[[u32; 3]]) -> FxHashMap<(u32, u32), u32> {
    let mut count: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for t in tris {
        for j in 0..3 {
            *count.entry(edge(t[j], t[(j + 1) % 3])).or_default() += 1;
        }
    }
    count
}

/// An edge from a zone vertex to a vertex above the zone, and that vertex's height over the zone's
/// plane (positive; both makers leave out the others): where a slab's split point goes.
#[derive(Clone, Copy, Debug)]
struct Lift {
    zone_vertex: u32,
    far: u32,
    height: f64,
}

/// The edges (zone vertex, apex) of the parents.
fn parent_lifts(positions: &[[f64; 3]], parents: &[&Parent]) -> Vec<Lift> {
    let mut out = Vec::new();
    for p in parents {
        let Some(height) = Height::of(positions, p.zone) else {
            continue;
        };
        let h = height.above(positions[p.tet[3] as usize]).abs();
        if h > 0.0 {
            out.extend(p.zone.map(|v| Lift {
                zone_vertex: v,
                far: p.tet[3],
                height: h,
            }));
        }
    }
    out
}

/// Signed height over the plane of a zone triangle (positive on the side its normal points to).
struct Height {
    origin: [f64; 3],
    /// The triangle's normal (not unit: the height is its dot product over its length, as the
    /// slabs have always measured it) and its length.
    normal: [f64; 3],
    len: f64,
}

impl Height {
    fn of(positions: &[[f64; 3]], tri: [u32; 3]) -> Option<Height> {
        let z = tri.map(|v| positions[v as usize]);
        let n = cross(sub(z[1], z[0]), sub(z[2], z[0]));
        let len = dot(n, n).sqrt();
        (len > 0.0).then_some(Height {
            origin: z[0],
            normal: n,
            len,
        })
    }

    fn above(&self, x: [f64; 3]) -> f64 {
        dot(self.normal, sub(x, self.origin)) / self.len
    }

    /// The same height, positive on the other side.
    fn flipped(self) -> Height {
        Height {
            normal: self.normal.map(|c| -c),
            ..self
        }
    }
}

/// Per edge of `lifts` whose ends share no plane: the split point and its height above the zone.
/// An edge asked for several times is split once, where its first request puts it. A point that
/// would come near another slab point (from `first_new` on, or of this call) moves farther along
/// its edge (`spacing`): zone vertices whose parents' apexes are nearly in line, or a cluster,
/// would otherwise get near-duplicate split points and nearly coplanar walls between them.
fn split_points(
    positions: &[[f64; 3]],
    planes: &[Planes],
    lifts: &[Lift],
    thickness: f64,
    on_planes: bool,
    first_new: usize,
) -> FxHashMap<(u32, u32), ([f64; 3], f64)> {
    let on_a_plane = |a: u32, b: u32| super::refine::edge_on_a_plane(planes, a, b);
    let earlier: Vec<([f64; 3], u32)> = positions[first_new..]
        .iter()
        .map(|&p| (p, u32::MAX))
        .collect();
    let mut spaced = Spaced::new(SLAB_GAP * thickness, &earlier);
    let mut out: FxHashMap<(u32, u32), ([f64; 3], f64)> = FxHashMap::default();
    for l in lifts {
        let (v, far, h) = (l.zone_vertex, l.far, l.height);
        if !on_planes && on_a_plane(v, far) {
            continue;
        }
        if let std::collections::hash_map::Entry::Vacant(e) = out.entry(edge(v, far)) {
            let ends = [positions[v as usize], positions[far as usize]];
            let (x, at) = spaced.place(ends, |k| k * (thickness / h), Rule::Slab, v);
            e.insert((x, at * h));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::assembly::{boundary_of, singularities};
    use crate::bm::refine::test_support::Owned;
    use crate::bm::refine::Triangulation;

    fn planes_share(f: &[u32; 3], g: u32, planes: &[Planes]) -> bool {
        f.iter().all(|&v| planes[v as usize].contains(&g))
    }

    pub(super) fn planes(list: &[&[u32]]) -> Vec<Planes> {
        list.iter().map(|p| p.iter().copied().collect()).collect()
    }

    /// A unit tetrahedron standing on the flat triangle (0,1,2) of plane 0 (z = 0, outward -z),
    /// apex 3 at height 1.
    /// Thicken with `fillable` the only tets besides K (empty), the zone (0,1,2) a section triangle.
    fn run(
        positions: &mut Vec<[f64; 3]>,
        planes: &mut Vec<Planes>,
        faces: &[Vec<Side>],
        fillable: &mut Vec<[u32; 4]>,
    ) -> (SlabStats, Vec<[u32; 4]>) {
        let mut kept = Vec::new();
        let mut external = Vec::new();
        let mut internal: FxHashSet<[u32; 3]> = [[0, 1, 2]].into_iter().collect();
        let mut t = Triangulation {
            positions,
            planes,
            kept: &mut kept,
            fillable,
            external: &mut external,
            internal: &mut internal,
        };
        let s = thicken(&mut t, faces, 0.01);
        (s, kept)
    }

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
        let mut fillable = vec![[0, 1, 2, 3]];
        let (s, kept) = run(&mut positions, &mut pl, &faces, &mut fillable);
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

    /// Two zone triangles sharing an edge, standing on different apexes, get one prism each inside
    /// their own parents; the tetrahedron between the parents around the common edge is a gap of
    /// the zone and keeps its wedge below the same split points, so the slab is one solid and the
    /// common edge is inside it (before the gaps were closed it had four surface triangles: the
    /// two zone triangles and a wall of each prism, nearly on each other above the edge).
    #[test]
    fn two_zone_triangles_with_different_apexes_make_one_slab() {
        // the square (0,1,3,2) on z = 0, two zone triangles standing on apexes 4 and 5, and the
        // tetrahedron (1,2,4,5) between them around their common edge (1,2)
        use crate::bm::refine::test_support::positive;
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.3, 0.3, 1.0],
            [0.7, 0.7, 1.0],
        ];
        let tri = |tri: [u32; 3], apex: u32| FaceTri {
            tri,
            attached: false,
            apex,
        };
        let side = Side {
            tris: vec![tri([0, 2, 1], 4), tri([1, 2, 3], 5)],
            has_volume: true,
        };
        let mut o = Owned {
            fillable: [[0, 2, 1, 4], [1, 2, 3, 5], [1, 2, 4, 5]]
                .map(|t| positive(&positions, t))
                .to_vec(),
            positions,
            planes: planes(&[&[0], &[0], &[0], &[0], &[], &[]]),
            internal: [[0, 1, 2], [1, 2, 3]].into_iter().collect(),
            ..Default::default()
        };
        let s = thicken(&mut o.view(), &[vec![side]], 0.01);
        assert_eq!((s.thickened, s.left, s.tets, s.points), (2, 0, 9, 6));
        assert_eq!((s.gaps_closed, s.gaps_open), (1, 0));
        let b = boundary_of(&o.kept);
        assert_eq!(singularities(&b), (0, 0));
        // no surface triangle has the common edge but the two zone triangles
        let at_common_edge = b
            .iter()
            .filter(|t| t.contains(&1) && t.contains(&2))
            .count();
        assert_eq!(at_common_edge, 2);
        assert!(b.iter().any(|t| key3(*t) == [0, 1, 2]));
        // the wedge of (1,2,4,5) below the split points is kept, its rest stays fillable
        assert!(!o.fillable.iter().any(|t| t.contains(&1) && t.contains(&2)));
    }

    #[test]
    fn a_zone_on_a_line_of_the_arrangement_tapers_to_it() {
        // the side face (0,1,3) lies on plane 1 (x = 0): its edges are not split, the slab is the
        // one tetrahedron through the split of (2,3), and no slab face lies on plane 1
        let (mut positions, faces) = standing();
        positions[3] = [0.0, 0.2, 1.0];
        let mut pl = planes(&[&[0, 1], &[0, 1], &[0], &[1]]);
        let (s, kept) = run(&mut positions, &mut pl, &faces, &mut Vec::new());
        assert_eq!((s.thickened, s.left, s.tets, s.points), (1, 0, 1, 1));
        assert_eq!(key4(kept[0]), [0, 1, 2, 4]);
        for i in 0..4 {
            let f = crate::bm::complex::outward_face(&kept[0], i);
            assert!(!planes_share(&f, 1, &pl) || key3(f) == [0, 1, 2]);
        }
    }

    #[test]
    fn a_zone_at_a_corner_of_two_planes_gets_a_slab_where_their_sections_allow_it() {
        // as below, but the tetrahedron's faces on planes 1 and 2 are inside their sections: the
        // second try splits the edges on the planes and keeps the whole prism
        let (mut positions, faces) = standing();
        positions[3] = [0.0, 0.0, 1.0];
        let mut o = Owned {
            positions,
            planes: planes(&[&[0, 1, 2], &[0, 1], &[0, 2], &[1, 2]]),
            internal: [[0, 1, 2], [0, 1, 3], [0, 2, 3]].into_iter().collect(),
            ..Default::default()
        };
        let s = thicken(&mut o.view(), &faces, 0.01);
        assert_eq!((s.thickened, s.left, s.tets, s.points), (1, 0, 3, 3));
        assert_eq!(singularities(&boundary_of(&o.kept)), (0, 0));
        assert!(o.positions[4..].iter().all(|p| (p[2] - 0.01).abs() < 1e-12));
    }

    #[test]
    fn a_zone_whose_apex_edges_all_lie_on_planes_is_left_flat() {
        // (where the planes' sections do not hold the slab's faces on them)
        let (mut positions, faces) = standing();
        positions[3] = [0.0, 0.0, 1.0];
        // 3 on plane 1 with 0 and 1, and on plane 2 with 2 and 0
        let mut pl = planes(&[&[0, 1, 2], &[0, 1], &[0, 2], &[1, 2]]);
        let (s, kept) = run(&mut positions, &mut pl, &faces, &mut Vec::new());
        assert_eq!((s.thickened, s.left, s.tets), (0, 1, 0));
        assert!(kept.is_empty());
    }

    #[test]
    fn zone_vertices_whose_apexes_are_nearly_in_line_get_split_points_apart() {
        // two zone triangles on z = 0 sharing the edge (1, 2), their apexes 4 and 5 1e-10 apart:
        // the edges from 1 and from 2 to the two apexes are nearly parallel, and split at one
        // fraction their points would be 1e-11 apart
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.5, 0.5, 1.0],
            [0.5, 0.5 + 1e-10, 1.0],
        ];
        let pl = vec![Planes::new(); 6];
        let parents = [
            Parent {
                zone: [0, 1, 2],
                tet: [0, 1, 2, 4],
                zone_id: 0,
                side: 0,
            },
            Parent {
                zone: [1, 3, 2],
                tet: [1, 3, 2, 5],
                zone_id: 0,
                side: 0,
            },
        ];
        let thickness = 0.01;
        let points = split_points(
            &positions,
            &pl,
            &parent_lifts(&positions, &[&parents[0], &parents[1]]),
            thickness,
            false,
            6,
        );
        assert_eq!(points.len(), 6);
        let ps: Vec<([f64; 3], f64)> = points.values().copied().collect();
        for (i, a) in ps.iter().enumerate() {
            // at least the thickness above the zone
            assert!(a.1 >= thickness && (a.0[2] - a.1).abs() < 1e-15, "{a:?}");
            for b in &ps[i + 1..] {
                let d = (0..3)
                    .map(|k| (a.0[k] - b.0[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(d >= SLAB_GAP * thickness, "{a:?} {b:?}: {d:e}");
            }
        }
    }
}
