//! What one arrangement cell sees: its section vertices (local ids ↔ global pool ids), per face with a
//! section a "slot" (plane, boundary loops, (u,v) coordinates, exact point-in-section locator), and for
//! every local vertex the bit mask of the slots whose plane it carries as a tag.
//!
//! Plane membership is combinatorial: a vertex is on slot `s` iff its global tag set holds the slot's
//! plane. Tags of planes on which the cell has no face with a section are ignored inside this cell.
use crate::arrangement::{Arrangement, FaceId, PlaneId, VertexPool};
use crate::delaunay::{PlaneApexes, PointTags};
use crate::geom::predicates::orient2d;
use smallvec::SmallVec;
use std::collections::{HashMap, HashSet};

pub type Mask = u128;

/// The slots of `mask` (its set bits), ascending: one step per set bit, not per slot.
pub fn slots_of(mask: Mask) -> impl Iterator<Item = usize> {
    let mut rest = mask;
    std::iter::from_fn(move || {
        (rest != 0).then(|| {
            let s = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            s
        })
    })
}

/// The cells' id-keyed maps use the crate's Fx hasher.
pub type IdHash = crate::fxhash::FxBuild;
pub type IdMap<K, V> = HashMap<K, V, IdHash>;
pub type IdSet<K> = HashSet<K, IdHash>;
pub const MAX_SLOTS: usize = 128;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Where {
    Inside,
    Outside,
    Boundary,
}

/// Exact point-in-polygon-set (even-odd over all boundary loops) with horizontal bins.
#[derive(Clone, Debug, Default)]
pub struct SectionLocator {
    edges: Vec<([f64; 2], [f64; 2])>,
    y0: f64,
    y1: f64,
    inv_dy: f64,
    bins: Vec<Vec<u32>>,
}

impl SectionLocator {
    pub fn new(loops: &[Vec<[f64; 2]>]) -> SectionLocator {
        let mut edges = Vec::new();
        for l in loops {
            for i in 0..l.len() {
                edges.push((l[i], l[(i + 1) % l.len()]));
            }
        }
        if edges.is_empty() {
            return SectionLocator::default();
        }
        let y0 = edges
            .iter()
            .map(|e| e.0[1].min(e.1[1]))
            .fold(f64::INFINITY, f64::min);
        let y1 = edges
            .iter()
            .map(|e| e.0[1].max(e.1[1]))
            .fold(f64::NEG_INFINITY, f64::max);
        let nb = (edges.len() / 2).clamp(1, 4096);
        let inv_dy = if y1 > y0 { nb as f64 / (y1 - y0) } else { 0.0 };
        let mut bins = vec![Vec::new(); nb];
        let bin = |y: f64| (((y - y0) * inv_dy) as usize).min(nb - 1);
        for (i, e) in edges.iter().enumerate() {
            let (lo, hi) = (bin(e.0[1].min(e.1[1])), bin(e.0[1].max(e.1[1])));
            for b in &mut bins[lo..=hi] {
                b.push(i as u32);
            }
        }
        SectionLocator {
            edges,
            y0,
            y1,
            inv_dy,
            bins,
        }
    }

    /// [`SectionLocator::locate`], with a point closer than `margin` to the boundary on it. A
    /// diagram sample is a point strictly inside a section; one a rounding error off an edge (a grid
    /// line along a face side that lies on another plane: a fan's axis, the lines of axis-aligned
    /// planes) would be a point on two planes tagged with one, which no kernel can place
    /// consistently.
    pub fn locate_clear(&self, q: [f64; 2], margin: f64) -> Where {
        match self.locate(q) {
            Where::Inside if self.near_boundary(q, margin) => Where::Boundary,
            w => w,
        }
    }

    /// Whether some boundary edge is closer than `d` to `q` (floats: a sampling policy, not a
    /// topological decision).
    fn near_boundary(&self, q: [f64; 2], d: f64) -> bool {
        if self.edges.is_empty() {
            return false;
        }
        (self.bin(q[1] - d)..=self.bin(q[1] + d)).any(|b| {
            self.bins[b].iter().any(|&i| {
                let (a, c) = self.edges[i as usize];
                crate::geom::segment_distance_2d(q, a, c) < d
            })
        })
    }

    /// [`SectionLocator::locate`] for the points of the row `y = y`, answered from where the
    /// boundary crosses the row; a point that rounding could put on the other side of a crossing
    /// (or on the boundary) is located exactly. For a grid of points, one pass over a bin per row
    /// instead of one per point.
    pub fn row(&self, y: f64) -> RowLocator<'_> {
        let mut row = RowLocator {
            locator: self,
            y,
            crossings: Vec::new(),
            critical: Vec::new(),
            outside: self.edges.is_empty() || y < self.y0 || y > self.y1,
            exact: false,
        };
        if row.outside {
            return row;
        }
        for &i in &self.bins[self.bin(y)] {
            let (a, c) = self.edges[i as usize];
            if y < a[1].min(c[1]) || y > a[1].max(c[1]) {
                continue;
            }
            let (lo, hi) = (a[0].min(c[0]), a[0].max(c[0]));
            let slack = 1e-10 * (a[0].abs() + c[0].abs()) + f64::MIN_POSITIVE;
            if (a[1] > y) != (c[1] > y) {
                // toggles the parity of every point left of the crossing; the crossing's rounding
                // error is far below `eps` (ulps of the coordinates, scaled by the slope)
                let x = a[0] + (y - a[1]) * (c[0] - a[0]) / (c[1] - a[1]);
                let steep = (y.abs() + a[1].abs() + c[1].abs()) / (c[1] - a[1]).abs();
                let eps = slack + 1e-10 * (c[0] - a[0]).abs() * (1.0 + steep);
                if !(x.is_finite() && eps.is_finite()) {
                    row.exact = true;
                    return row;
                }
                row.crossings.push(x);
                row.critical
                    .push(((x - eps).max(lo - slack), (x + eps).min(hi + slack)));
            } else {
                // touches the row (an end on it, or along it): on it means on the boundary
                row.critical.push((lo - slack, hi + slack));
            }
        }
        row.crossings.sort_by(f64::total_cmp);
        row.critical.sort_by(|p, q| p.0.total_cmp(&q.0));
        // merged, so that a point is in one of them iff it is in the one starting before it
        let mut merged: Vec<(f64, f64)> = Vec::with_capacity(row.critical.len());
        for (lo, hi) in row.critical.drain(..) {
            match merged.last_mut() {
                Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
                _ => merged.push((lo, hi)),
            }
        }
        row.critical = merged;
        row
    }

    /// The bin of a height (below the section's: the first, above: the last; the float-to-index
    /// cast saturates).
    fn bin(&self, y: f64) -> usize {
        (((y - self.y0) * self.inv_dy) as usize).min(self.bins.len() - 1)
    }

    pub fn locate(&self, q: [f64; 2]) -> Where {
        if self.edges.is_empty() || q[1] < self.y0 || q[1] > self.y1 {
            return Where::Outside;
        }
        let mut inside = false;
        for &i in &self.bins[self.bin(q[1])] {
            let (a, c) = self.edges[i as usize];
            let straddles = (a[1] > q[1]) != (c[1] > q[1]);
            let in_box = q[0] >= a[0].min(c[0])
                && q[0] <= a[0].max(c[0])
                && q[1] >= a[1].min(c[1])
                && q[1] <= a[1].max(c[1]);
            if !straddles && !in_box {
                continue;
            }
            let o = orient2d(a, c, q);
            if o == 0.0 && in_box {
                return Where::Boundary;
            }
            if straddles && (o > 0.0) == (c[1] > a[1]) {
                inside = !inside;
            }
        }
        if inside {
            Where::Inside
        } else {
            Where::Outside
        }
    }
}

/// A [`SectionLocator`] along one row (`SectionLocator::row`).
pub struct RowLocator<'a> {
    locator: &'a SectionLocator,
    y: f64,
    /// Where the boundary crosses the row, ascending.
    crossings: Vec<f64>,
    /// Disjoint x-intervals, ascending, where a point is located exactly.
    critical: Vec<(f64, f64)>,
    /// The row misses the section's bins: every point is outside.
    outside: bool,
    /// Every point is located exactly (a crossing that cannot be bounded).
    exact: bool,
}

impl RowLocator<'_> {
    /// Where the point (x, the row's y) is: the same answer as `SectionLocator::locate`.
    pub fn locate(&self, x: f64) -> Where {
        if self.outside {
            return Where::Outside;
        }
        let k = self.critical.partition_point(|c| c.0 <= x);
        if self.exact || !x.is_finite() || (k > 0 && x <= self.critical[k - 1].1) {
            return self.locator.locate([x, self.y]);
        }
        // even-odd: the crossings right of the point
        let right = self.crossings.len() - self.crossings.partition_point(|&c| c <= x);
        if right % 2 == 1 {
            Where::Inside
        } else {
            Where::Outside
        }
    }
}

/// One face of the cell that carries a section.
#[derive(Clone, Debug)]
pub struct Slot {
    pub face: FaceId,
    pub plane: PlaneId,
    /// The cell's outward normal on this face is the plane normal.
    pub outward_is_plane_normal: bool,
    /// Boundary loops (outer and holes) in local ids, with Steiner splits applied.
    pub loops: Vec<Vec<u32>>,
    /// (u,v) in this plane per local vertex (meaningful for vertices carrying the slot's bit);
    /// empty once the input is slimmed ([`CellInput::slim`]).
    pub uv: Vec<[f64; 2]>,
    /// Once slimmed: the signed area of each loop in (u,v), and the (u,v) of the cell-local
    /// vertices on this slot (what the assembly and the sharing of samples read of `uv`).
    pub loop_areas: Vec<f64>,
    pub local_uv: Vec<(u32, [f64; 2])>,
    /// What only the cell's run reads ([`SlotRun`]); `None` once the input is slimmed.
    pub run: Option<Box<SlotRun>>,
    /// The cell on the other side of this face has sections on at least two faces, so it may
    /// attach here; false when the other side is empty (the section is a cap of the solid).
    pub beyond_may_attach: bool,
}

/// The part of a slot only its cell's run reads: the plane's geometry, the contour edges and a
/// point locator of the section (a slot of a stored result keeps none of it: on a dense sweep
/// they were 200 of a slot's 272 bytes, over a million slots).
#[derive(Clone, Debug)]
pub struct SlotRun {
    pub geom: crate::sections::Plane,
    pub contour_edges: IdSet<(u32, u32)>,
    pub locator: SectionLocator,
}

impl Slot {
    /// The run's data; a slimmed slot has none (reading it is a bug of the caller).
    fn run(&self) -> &SlotRun {
        self.run
            .as_deref()
            .expect("a slot's run data read after its input was slimmed")
    }

    fn run_mut(&mut self) -> &mut SlotRun {
        self.run
            .as_deref_mut()
            .expect("a slot's run data written after its input was slimmed")
    }

    pub fn geom(&self) -> &crate::sections::Plane {
        &self.run().geom
    }

    pub fn contour_edges(&self) -> &IdSet<(u32, u32)> {
        &self.run().contour_edges
    }

    pub fn locator(&self) -> &SectionLocator {
        &self.run().locator
    }
}

#[derive(Clone, Debug)]
pub struct CellInput {
    pub cell: u32,
    /// Local id → global pool id.
    pub global: Vec<u32>,
    pub points: Vec<[f64; 3]>,
    pub mask: Vec<Mask>,
    /// Per local vertex, every input plane it lies on with its pool (u,v) there and its global id
    /// (cell-local vertices: [`local_gid`]), for the tagged Delaunay kernel: both cells of a face
    /// hand it the same tags for the same points, so both triangulate the face alike.
    pub tags: Vec<PointTags>,
    /// The apexes of the cell's face planes, through which the kernel's plane rule decides
    /// ([`plane_apexes`]): the same for every cell that has the plane.
    pub apexes: PlaneApexes,
    pub slots: Vec<Slot>,
    /// Once slimmed (`tags` then empty): the planes of each cell-local vertex (no pool id), which
    /// the assembly reads.
    pub local_planes: Vec<(u32, SmallVec<[u32; 3]>)>,
}

/// The kernel's global id of a cell-local vertex (a diagram sample without a pool id): above every
/// pool id, so ties against pool vertices are decided alike in every cell.
pub fn local_gid(local: u32) -> u64 {
    (1u64 << 32) | local as u64
}

/// The kernel's tags of pool vertex `g`: its planes, each with the coordinates of the vertex's
/// *position* in that plane's frame. Not `pool.uv`: a point where two sections cross their common
/// line keeps each section's own (u,v), while its position is their midpoint (`reconcile`), up to
/// the snap tolerance away; the tag rules decide for the points their (u,v) describe, the float
/// predicates for the positions, and the two must be the same points up to rounding.
///
/// Only the planes of the cell's faces (`cell_planes`): a point on the common line of a fan of
/// planes lies on all of them (the kernel refuses more than `tags::MAX_PLANES`, and the cell is
/// then triangulated untagged). The two cells of a face see the
/// same planes through it: a line of that face's plane with another plane meets the face only
/// along an edge of it, and that other plane bounds both cells there.
pub fn pool_tags(
    arr: &Arrangement,
    pool: &VertexPool,
    g: u32,
    cell_planes: &IdSet<PlaneId>,
) -> PointTags {
    let p = pool.positions[g as usize];
    let planes: SmallVec<[(u32, [f64; 2]); 3]> = pool.tags[g as usize]
        .iter()
        .filter(|t| cell_planes.contains(t))
        .map(|&t| (t, arr.planes[t as usize].plane.to_2d(p)))
        .collect();
    let mut tags = PointTags::new(g as u64, &planes);
    tags.segment = pool.on_segment.get(&g).map(|s| s.map(u64::from));
    tags
}

/// The kernel's apex of each of `planes`: above the point of the plane nearest the centre of the
/// arrangement's box, by the box's diagonal (a function of the plane and the box alone, so every
/// cell with the plane has the same apex; far enough that no triple of the plane's points is
/// nearly coplanar with it unless it is nearly collinear).
pub fn plane_apexes(arr: &Arrangement, planes: impl Iterator<Item = PlaneId>) -> PlaneApexes {
    let (lo, hi) = arr.bbox;
    let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    PlaneApexes::new(
        planes
            .map(|t| {
                let plane = &arr.planes[t as usize].plane;
                let d = plane.signed_distance(centre);
                let foot: [f64; 3] = std::array::from_fn(|k| centre[k] - d * plane.normal[k]);
                (t, PlaneApexes::above(foot, plane.normal, diag))
            })
            .collect(),
    )
}

pub fn edge_key(a: u32, b: u32) -> (u32, u32) {
    if a < b {
        (a, b)
    } else {
        (b, a)
    }
}

impl CellInput {
    /// Drop what only the cell's own run reads (the slots' point locators, contour-edge sets
    /// and (u,v) of every local vertex, a slot's share of which is kept: its loops' areas and
    /// its cell-local vertices' (u,v); the points' tags, of which the cell-local vertices' planes
    /// are kept), once the run is stored: the assembly and the sharing of samples read ids,
    /// points, loops and those. A rerun builds its input anew.
    pub fn slim(&mut self) {
        let locals: Vec<usize> = (0..self.global.len())
            .filter(|&l| self.global[l] == u32::MAX)
            .collect();
        if !self.tags.is_empty() {
            self.local_planes = locals
                .iter()
                .map(|&l| (l as u32, self.tags[l].planes.iter().map(|p| p.0).collect()))
                .collect();
            self.tags = Vec::new();
        }
        for (s, slot) in self.slots.iter_mut().enumerate() {
            slot.run = None;
            if slot.uv.is_empty() {
                continue; // slimmed already
            }
            slot.loop_areas = slot
                .loops
                .iter()
                .map(|l| {
                    let pts: Vec<[f64; 2]> = l.iter().map(|&v| slot.uv[v as usize]).collect();
                    crate::sections::polygon_signed_area(&pts)
                })
                .collect();
            slot.local_uv = (locals.iter())
                .filter(|&&l| self.mask[l] >> s & 1 == 1)
                .map(|&l| (l as u32, slot.uv[l]))
                .collect();
            slot.uv = Vec::new();
        }
    }

    /// Gather the cell's section vertices and faces. `face_loops[f]` are the face's boundary loops in
    /// global ids (Steiner points included). Returns `None` when no face of the cell has a section.
    pub fn build(
        arr: &Arrangement,
        pool: &VertexPool,
        face_loops: &[Vec<Vec<u32>>],
        cell: u32,
    ) -> Option<CellInput> {
        let mut slot_faces = Vec::new();
        for cf in &arr.cells[cell as usize].faces {
            if !face_loops[cf.face as usize].is_empty() {
                slot_faces.push(cf.clone());
            }
        }
        if slot_faces.is_empty() {
            return None;
        }
        slot_faces.truncate(MAX_SLOTS);
        let mut local: IdMap<u32, u32> = IdMap::default();
        let mut global = Vec::new();
        for cf in &slot_faces {
            for l in &face_loops[cf.face as usize] {
                for &g in l {
                    local.entry(g).or_insert_with(|| {
                        global.push(g);
                        (global.len() - 1) as u32
                    });
                }
            }
        }
        let plane_slot: IdMap<PlaneId, usize> = slot_faces
            .iter()
            .enumerate()
            .map(|(s, cf)| (arr.faces[cf.face as usize].plane, s))
            .collect();
        let n = global.len();
        let mut mask = vec![0 as Mask; n];
        let mut slots: Vec<Slot> = slot_faces
            .iter()
            .map(|cf| Slot {
                face: cf.face,
                plane: arr.faces[cf.face as usize].plane,
                outward_is_plane_normal: cf.outward_is_plane_normal,
                loops: Vec::new(),
                uv: vec![[f64::NAN; 2]; n],
                loop_areas: Vec::new(),
                local_uv: Vec::new(),
                run: Some(Box::new(SlotRun {
                    geom: arr.planes[arr.faces[cf.face as usize].plane as usize].plane,
                    contour_edges: IdSet::default(),
                    locator: SectionLocator::default(),
                })),
                beyond_may_attach: {
                    let face = &arr.faces[cf.face as usize];
                    [face.positive_cell, face.negative_cell]
                        .into_iter()
                        .flatten()
                        .filter(|&c| c != cell)
                        .any(|c| {
                            arr.cells[c as usize]
                                .faces
                                .iter()
                                .filter(|g| !face_loops[g.face as usize].is_empty())
                                .count()
                                >= 2
                        })
                },
            })
            .collect();
        for (l, &g) in global.iter().enumerate() {
            for (ti, &p) in pool.tags[g as usize].iter().enumerate() {
                if let Some(&s) = plane_slot.get(&p) {
                    mask[l] |= 1 << s;
                    slots[s].uv[l] = pool.uv[g as usize][ti];
                }
            }
        }
        for (s, cf) in slot_faces.iter().enumerate() {
            let loops: Vec<Vec<u32>> = face_loops[cf.face as usize]
                .iter()
                .map(|l| l.iter().map(|g| local[g]).collect())
                .collect();
            let slot = &mut slots[s];
            for l in &loops {
                for i in 0..l.len() {
                    slot.run_mut()
                        .contour_edges
                        .insert(edge_key(l[i], l[(i + 1) % l.len()]));
                }
            }
            let uv_loops: Vec<Vec<[f64; 2]>> = loops
                .iter()
                .map(|l| l.iter().map(|&v| slot.uv[v as usize]).collect())
                .collect();
            slot.run_mut().locator = SectionLocator::new(&uv_loops);
            slot.loops = loops;
        }
        let points = global.iter().map(|&g| pool.positions[g as usize]).collect();
        let cell_planes: IdSet<PlaneId> = arr.cells[cell as usize]
            .faces
            .iter()
            .map(|cf| arr.faces[cf.face as usize].plane)
            .collect();
        let tags = global
            .iter()
            .map(|&g| pool_tags(arr, pool, g, &cell_planes))
            .collect();
        let apexes = plane_apexes(arr, cell_planes.iter().copied());
        Some(CellInput {
            cell,
            global,
            points,
            mask,
            tags,
            apexes,
            slots,
            local_planes: Vec::new(),
        })
    }

    /// Add a cell-local vertex (a branching sample) on slot `s` at (u,v) `q`.
    pub fn add_local_vertex(&mut self, s: usize, q: [f64; 2], p3: [f64; 3]) -> u32 {
        self.add_vertex(s, q, p3, u32::MAX)
    }

    /// Add a vertex on slot `s` at (u,v) `q` with global id `gid` (`u32::MAX`: cell-local).
    pub fn add_vertex(&mut self, s: usize, q: [f64; 2], p3: [f64; 3], gid: u32) -> u32 {
        let l = self.points.len() as u32;
        self.points.push(p3);
        self.global.push(gid);
        self.mask.push(1 << s);
        let kernel_gid = if gid == u32::MAX {
            local_gid(l)
        } else {
            gid as u64
        };
        let uv = self.slots[s].geom().to_2d(p3);
        self.tags
            .push(PointTags::new(kernel_gid, &[(self.slots[s].plane, uv)]));
        for (k, slot) in self.slots.iter_mut().enumerate() {
            slot.uv.push(if k == s { q } else { [f64::NAN; 2] });
        }
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_of_a_mask_are_its_set_bits_ascending() {
        assert_eq!(slots_of(0).count(), 0);
        let m: Mask = 1 | 1 << 5 | 1 << 64 | 1 << 127;
        assert_eq!(slots_of(m).collect::<Vec<_>>(), vec![0, 5, 64, 127]);
        let scan: Vec<usize> = (0..128).filter(|&s| m >> s & 1 == 1).collect();
        assert_eq!(slots_of(m).collect::<Vec<_>>(), scan);
    }

    #[test]
    fn a_row_locates_as_the_locator_does() {
        // a star with a hole, vertices on grid rows and columns, a horizontal edge, a near-flat one
        let outer = vec![
            [0.0, 0.0],
            [2.0, 0.5],
            [4.0, 0.0],
            [3.5, 2.0],
            [4.0, 4.0],
            [2.0, 3.0],
            [1.0, 3.0],
            [0.0, 4.0],
            [0.5, 2.0 + 1e-13],
        ];
        let hole = vec![[1.5, 1.5], [1.5, 2.5], [2.5, 2.5], [2.5, 1.5]];
        let loc = SectionLocator::new(&[outer, hole]);
        let mut seen = [0usize; 3];
        for j in -2..=82 {
            let y = 0.05 * j as f64;
            let row = loc.row(y);
            for i in -2..=82 {
                let x = 0.05 * i as f64;
                let w = loc.locate([x, y]);
                assert_eq!(row.locate(x), w, "({x}, {y})");
                seen[w as usize] += 1;
            }
            for x in [0.5, 1.0, 1.5, 2.0, 2.5, 3.5] {
                assert_eq!(row.locate(x), loc.locate([x, y]), "({x}, {y})");
            }
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
    }

    #[test]
    fn locator_inside_outside_boundary() {
        let sq = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let hole = vec![[0.5, 0.5], [0.5, 1.5], [1.5, 1.5], [1.5, 0.5]];
        let loc = SectionLocator::new(&[sq, hole]);
        assert_eq!(loc.locate([0.25, 1.0]), Where::Inside);
        assert_eq!(loc.locate([1.0, 1.0]), Where::Outside);
        assert_eq!(loc.locate([3.0, 1.0]), Where::Outside);
        assert_eq!(loc.locate([2.0, 1.0]), Where::Boundary);
        assert_eq!(loc.locate([1.0, 0.0]), Where::Boundary);
        assert_eq!(loc.locate([0.5, 1.0]), Where::Boundary);
        assert_eq!(loc.locate([1.75, 0.5]), Where::Inside);
        // a rounding error inside the outer edge x = 0 is on it for a sample
        assert_eq!(loc.locate([1e-17, 1.0]), Where::Inside);
        assert_eq!(loc.locate_clear([1e-17, 1.0], 1e-9), Where::Boundary);
        assert_eq!(loc.locate_clear([0.25, 1.0], 1e-9), Where::Inside);
        assert_eq!(loc.locate_clear([0.25, 1.0], 0.3), Where::Boundary);
        assert_eq!(loc.locate_clear([1.0, 1.0], 0.3), Where::Outside);
    }

    /// Slimming keeps of a slot's (u,v) what is read after the run: each loop's signed area
    /// (an outer square and a hole, opposite signs) and the cell-local vertices on the slot.
    #[test]
    fn slim_keeps_loop_areas_and_local_uv() {
        let uv = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [0.5, 0.5],
            [0.5, 1.5],
            [1.5, 1.5],
            [1.5, 0.5],
            [f64::NAN; 2], // a local vertex on no slot
        ];
        let n = uv.len();
        let slot = Slot {
            face: 0,
            plane: 0,
            outward_is_plane_normal: true,
            loops: vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]],
            uv,
            loop_areas: Vec::new(),
            local_uv: Vec::new(),
            run: Some(Box::new(SlotRun {
                geom: crate::sections::Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap(),
                contour_edges: IdSet::default(),
                locator: SectionLocator::default(),
            })),
            beyond_may_attach: true,
        };
        let mut global: Vec<u32> = (0..n as u32).collect();
        global[5] = u32::MAX; // a diagram sample of this cell on the slot
        global[8] = u32::MAX; // one in the cell's interior
        let mut mask = vec![1 as Mask; n];
        mask[8] = 0;
        let mut input = CellInput {
            cell: 0,
            global,
            points: vec![[0.0; 3]; n],
            mask,
            tags: vec![PointTags::none(); n],
            apexes: PlaneApexes::default(),
            slots: vec![slot],
            local_planes: Vec::new(),
        };
        input.tags[5] = PointTags::new(local_gid(5), &[(7, [0.5, 1.5])]);
        input.slim();
        let slot = &input.slots[0];
        assert!(slot.uv.is_empty() && slot.run.is_none());
        assert_eq!(slot.loop_areas, vec![4.0, -1.0]);
        assert_eq!(slot.local_uv, vec![(5, [0.5, 1.5])]);
        // the tags go; the cell-local vertices' planes stay
        assert!(input.tags.is_empty());
        let locals: Vec<(u32, Vec<u32>)> = input
            .local_planes
            .iter()
            .map(|(l, p)| (*l, p.to_vec()))
            .collect();
        assert_eq!(locals, vec![(5, vec![7]), (8, vec![])]);
        // slimming twice changes nothing
        input.slim();
        assert_eq!(input.slots[0].loop_areas, vec![4.0, -1.0]);
    }
}
