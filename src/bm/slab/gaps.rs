//! The gaps between the prisms of one flat zone (see the parent module): where neighbouring zone
//! triangles stand on different apexes, the tetrahedra between their parents around an inner
//! edge or above an inner vertex of the zone keep their parts below the split points too.
use super::{edge_counts, key4, Growth, Height, Lift, Parent, Triangulation};
use crate::bm::refine::{common_plane, edge};
use crate::fxhash::{FxHashMap, FxHashSet};
use smallvec::SmallVec;

/// The gaps between the slabs of a zone whose triangles stand on different apexes: every unkept
/// tetrahedron on the parents' side whose vertices on the zone's plane are one inner vertex or one
/// inner edge of the zone (a vertex or edge all of whose section triangles are in the zone and have
/// their first parent on that side), with that vertex or edge as its core; and the edges from its
/// core to its other vertices, to be split at the slab's thickness.
pub(super) fn gaps(t: &Triangulation, parents: &[&Parent]) -> (Vec<Growth>, Vec<Lift>) {
    let inner = Inner::of(t, parents);
    if inner.groups.is_empty() {
        return Default::default();
    }
    let parent_tets: FxHashSet<[u32; 4]> = parents.iter().map(|p| key4(p.tet)).collect();
    let mut growths = Vec::new();
    let mut lifts = Vec::new();
    for x in t.fillable.iter().chain(t.external.iter()) {
        if !x.iter().any(|&v| inner.marked[v as usize]) || parent_tets.contains(&key4(*x)) {
            continue;
        }
        if let Some((core, far)) = inner.gap(t, x) {
            for &c in &core {
                lifts.extend(far.iter().map(|&(v, h)| Lift {
                    zone_vertex: c,
                    far: v,
                    height: h,
                }));
            }
            growths.push(Growth {
                tet: *x,
                core,
                keep_slivers: true,
            });
        }
    }
    (growths, lifts)
}

/// A gap's vertices on the zone's plane, and its other vertices with their heights over it.
type Core = SmallVec<[u32; 3]>;
type Far = SmallVec<[(u32, f64); 3]>;

/// The inner vertices and edges of the zones, per group of zone triangles (one zone, one side).
struct Inner {
    /// Per group: its plane, and the height over it (positive on the parents' side).
    groups: Vec<(u32, Height)>,
    vertex: FxHashMap<u32, u32>,
    edge: FxHashMap<(u32, u32), u32>,
    /// Per vertex: whether it ends an inner edge or is an inner vertex.
    marked: Vec<bool>,
}

impl Inner {
    fn of(t: &Triangulation, parents: &[&Parent]) -> Inner {
        let mut by_group: FxHashMap<(u32, u32), Vec<&Parent>> = FxHashMap::default();
        for p in parents {
            by_group.entry((p.zone_id, p.side)).or_default().push(p);
        }
        let mut keys: Vec<&(u32, u32)> = by_group.keys().collect();
        keys.sort_unstable();
        let mut inner = Inner {
            groups: Vec::new(),
            vertex: FxHashMap::default(),
            edge: FxHashMap::default(),
            marked: vec![false; t.positions.len()],
        };
        for key in keys {
            inner.add(t, &by_group[key]);
        }
        inner
    }

    /// A group's inner edges (in two of its triangles) and inner vertices (on none of its border
    /// edges).
    fn add(&mut self, t: &Triangulation, group: &[&Parent]) {
        let z = group[0].zone;
        let (Some(plane), Some(height)) = (common_plane(t.planes, z), Height::of(t.positions, z))
        else {
            return;
        };
        let apex = t.positions[group[0].tet[3] as usize];
        let height = if height.above(apex) < 0.0 {
            height.flipped()
        } else {
            height
        };
        let g = self.groups.len() as u32;
        self.groups.push((plane, height));
        let zone: Vec<[u32; 3]> = group.iter().map(|p| p.zone).collect();
        let mut border: FxHashSet<u32> = FxHashSet::default();
        for (e, n) in edge_counts(&zone) {
            if n == 2 {
                self.edge.insert(e, g);
                self.marked[e.0 as usize] = true;
                self.marked[e.1 as usize] = true;
            } else {
                border.extend([e.0, e.1]);
            }
        }
        for v in group.iter().flat_map(|p| p.zone) {
            if !border.contains(&v) {
                self.vertex.insert(v, g);
            }
        }
    }

    /// The core of `x` if it is a gap (its vertices on its group's plane are an inner vertex or
    /// edge of that group, every other vertex strictly on the parents' side), and its other
    /// vertices with their heights.
    fn gap(&self, t: &Triangulation, x: &[u32; 4]) -> Option<(Core, Far)> {
        let g = *x.iter().find_map(|v| self.vertex.get(v)).or_else(|| {
            (0..4)
                .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                .find_map(|(i, j)| self.edge.get(&edge(x[i], x[j])))
        })?;
        let (plane, height) = &self.groups[g as usize];
        let core: Core = (x.iter().copied())
            .filter(|&v| t.planes[v as usize].contains(plane))
            .collect();
        let inner = match core[..] {
            [v] => self.vertex.get(&v) == Some(&g),
            [u, v] => self.edge.get(&edge(u, v)) == Some(&g),
            _ => false,
        };
        let far: Far = (x.iter())
            .filter(|v| !core.contains(v))
            .map(|&v| (v, height.above(t.positions[v as usize])))
            .collect();
        (inner && far.iter().all(|&(_, h)| h > 0.0)).then_some((core, far))
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::planes;
    use super::super::{thicken, FaceTri, Side};
    use crate::bm::assembly::{boundary_of, singularities};
    use crate::bm::refine::key3;
    use crate::bm::refine::test_support::Owned;

    /// A square zone of four triangles around an inner vertex 0, each standing on its own apex:
    /// `apex_height` of the apexes, `lean` moves apex 6 towards apex 5 (a sliver between them).
    fn pinwheel(lean: f64) -> (Owned, Vec<Vec<Side>>) {
        use crate::bm::refine::test_support::positive;
        let t = 1.0 / 3.0;
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [t, t, 1.0],
            [-t + lean, t, 1.0],
            [-t, -t, 1.0],
            [t, -t, 1.0],
        ];
        let zone = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]];
        let mut tris = Vec::new();
        let mut fillable = Vec::new();
        for (i, z) in zone.iter().enumerate() {
            let apex = 5 + i as u32;
            let x = positive(&positions, [z[0], z[1], z[2], apex]);
            tris.push(FaceTri {
                tri: if x[3] == apex {
                    [x[0], x[1], x[2]]
                } else {
                    [x[0], x[1], x[3]]
                },
                attached: false,
                apex,
            });
            fillable.push(x);
            // the tetrahedron between this triangle's parent and the next one's, around their
            // common edge (0, z[2])
            let next = 5 + (i as u32 + 1) % 4;
            fillable.push(positive(&positions, [0, z[2], apex, next]));
        }
        // above the vertex, between the four apexes
        fillable.push(positive(&positions, [0, 5, 6, 7]));
        fillable.push(positive(&positions, [0, 5, 7, 8]));
        let o = Owned {
            positions,
            planes: planes(&[&[0], &[0], &[0], &[0], &[0], &[], &[], &[], &[]]),
            fillable,
            internal: zone.iter().map(|z| key3(*z)).collect(),
            ..Default::default()
        };
        let side = Side {
            tris,
            has_volume: true,
        };
        (o, vec![vec![side]])
    }

    /// Around an inner vertex of a zone whose triangles stand on four apexes, the four wedges
    /// around its inner edges and the two tetrahedra above the vertex keep their parts below the
    /// split points: the vertex is inside the slab (its only surface triangles are the zone's),
    /// and the slab's boundary is a manifold.
    #[test]
    fn an_inner_zone_vertex_between_four_apexes_is_inside_one_slab() {
        let (mut o, faces) = pinwheel(0.0);
        let s = thicken(&mut o.view(), &faces, 0.01);
        assert_eq!(
            (s.thickened, s.left, s.gaps_closed, s.gaps_open),
            (4, 0, 6, 0)
        );
        let b = boundary_of(&o.kept);
        assert_eq!(singularities(&b), (0, 0));
        let at_vertex: Vec<[u32; 3]> = b
            .iter()
            .filter(|t| t.contains(&0))
            .map(|t| key3(*t))
            .collect();
        assert_eq!(at_vertex.len(), 4, "{at_vertex:?}");
        assert!(at_vertex.iter().all(|t| o.internal.contains(t)));
        // every split point at the thickness
        assert!(o.positions[9..].iter().all(|p| (p[2] - 0.01).abs() < 1e-12));
    }

    /// A gap that is a sliver (two apexes nearly in one plane with the zone edge between them)
    /// keeps its sliver wedge: refusing it would leave a crack between the two prisms.
    #[test]
    fn a_sliver_gap_between_two_prisms_is_closed() {
        // apex 6 on the plane through the edge (0, 2) and apex 5, up to 1e-9
        let lean = 2.0 / 3.0 - 1e-9;
        let (mut o, faces) = pinwheel(lean);
        let sliver = positive_sliver(&o.positions);
        assert!(o.fillable.contains(&sliver));
        let s = thicken(&mut o.view(), &faces, 0.01);
        assert_eq!((s.gaps_closed, s.gaps_open), (6, 0));
        assert_eq!(singularities(&boundary_of(&o.kept)), (0, 0));
    }

    fn positive_sliver(positions: &[[f64; 3]]) -> [u32; 4] {
        crate::bm::refine::test_support::positive(positions, [0, 2, 5, 6])
    }
}
