//! Arrangement vertices that only rounding keeps apart.
//!
//! Every arrangement vertex is constructed (in floats) from its own three planes, and its sides are
//! decided exactly on the rounded plane equations. Where four or more input planes meet in one point
//! up to the rounding of their equations (integer equations normalised to unit normals, e.g. four
//! planes of Horsers.csl), the exact predicates see several distinct vertices ~1e-17 of the diagonal
//! apart, with sliver faces and a sliver cell between them; every engine then meshes that dust and
//! produces overlapping near-coplanar triangles. Such vertices are merged here, before the sections
//! are split into pieces, so that every later step sees one consistent subdivision:
//! * vertices closer than `merge_tolerance × diagonal` (single linkage) become one pool vertex at
//!   their mean position, tagged with the union of their planes (so the triples of all of them
//!   name it, and the contours through that point find it);
//! * face polygons lose repeated vertices; a face left with fewer than three is dropped (it had no
//!   area), and so is a cell left with no face (it had no volume); the other cells keep their
//!   remaining faces, which still close them (the merge is an edge collapse of their boundary);
//! * faces and cells are renumbered, volumes of the touched cells recomputed;
//! * a cluster is left apart when its merge would leave a cell with one to three faces or two faces
//!   on one vertex set (a thin wedge between two nearly parallel planes: its two big faces would
//!   become one polygon on two planes).
//!
//! After the pieces are built, a section point on two or more planes (contour crossing) closer than
//! the same tolerance to an arrangement vertex on all its planes becomes that vertex
//! (`merge_line_points`), so no contour leaves a micro edge next to a face corner; and a contour
//! vertex on its own plane only closer than the tolerance to a section point on a line of that
//! plane becomes that point, whether next to it along a piece (a micro edge) or not (two sections
//! touching their common line at one point).
use super::{Arrangement, CellId, FaceId, PlaneTags, VertexId};
use crate::fxhash::FxHashMap as HashMap;

/// What a merge changed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct MergeStats {
    /// Vertices that disappeared into another one.
    pub vertices: usize,
    pub faces: usize,
    pub cells: usize,
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

/// Clusters of pool vertices closer than `tol` (single linkage): the cluster root of every vertex.
pub(crate) fn close_clusters(positions: &[[f64; 3]], tol: f64) -> Vec<u32> {
    let n = positions.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    if tol.is_nan() || tol <= 0.0 {
        return parent;
    }
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_by(|&a, &b| positions[a as usize][0].total_cmp(&positions[b as usize][0]));
    for i in 0..n {
        let p = positions[order[i] as usize];
        for &b in &order[i + 1..] {
            let q = positions[b as usize];
            if q[0] - p[0] >= tol {
                break;
            }
            let d2 = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>();
            if d2 < tol * tol {
                let (ra, rb) = (find(&mut parent, order[i]), find(&mut parent, b));
                if ra != rb {
                    // The smaller id survives.
                    let (lo, hi) = (ra.min(rb), ra.max(rb));
                    parent[hi as usize] = lo;
                }
            }
        }
    }
    (0..n as u32).map(|v| find(&mut parent, v)).collect()
}

/// A face polygon with every vertex replaced by `map` and repeats removed (cyclically).
fn merged_polygon(polygon: &[VertexId], map: impl Fn(VertexId) -> VertexId) -> Vec<VertexId> {
    let mut poly: Vec<VertexId> = Vec::with_capacity(polygon.len());
    for &v in polygon {
        let w = map(v);
        if poly.last() != Some(&w) {
            poly.push(w);
        }
    }
    while poly.len() > 1 && poly.first() == poly.last() {
        poly.pop();
    }
    poly
}

/// The clusters whose merge keeps every cell a polyhedron: each cell keeps no face (it had no
/// volume) or at least four faces on distinct vertex sets. Two nearly parallel planes crossing
/// in the box bound thin wedge cells whose side faces collapse while the two big faces stay: such
/// a cell would be left with two faces on one vertex set and two sections on one face; those
/// clusters are not merged (the vertices stay apart, as the exact predicates put them).
fn consistent_clusters(arr: &Arrangement, mut root: Vec<u32>) -> Vec<u32> {
    let size = |root: &[u32]| {
        let mut c = vec![0u32; root.len()];
        for &r in root {
            c[r as usize] += 1;
        }
        c
    };
    loop {
        let count = size(&root);
        let merged = |v: VertexId| count[root[v as usize] as usize] > 1;
        let mut reject: Vec<u32> = Vec::new();
        for cell in &arr.cells {
            let polys: Vec<&Vec<VertexId>> = cell
                .faces
                .iter()
                .map(|cf| &arr.faces[cf.face as usize].polygon)
                .collect();
            if !polys.iter().any(|p| p.iter().any(|&v| merged(v))) {
                continue;
            }
            let mut sets: Vec<Vec<VertexId>> = polys
                .iter()
                .map(|p| merged_polygon(p, |v| root[v as usize]))
                .filter(|p| p.len() >= 3)
                .map(|mut p| {
                    p.sort_unstable();
                    p
                })
                .collect();
            let n = sets.len();
            sets.sort();
            sets.dedup();
            if n == 0 || (n >= 4 && sets.len() == n) {
                continue;
            }
            for p in &polys {
                reject.extend(p.iter().filter(|&&v| merged(v)).map(|&v| root[v as usize]));
            }
        }
        if reject.is_empty() {
            return root;
        }
        reject.sort_unstable();
        reject.dedup();
        for (v, r) in root.iter_mut().enumerate() {
            if reject.binary_search(r).is_ok() {
                *r = v as u32;
            }
        }
    }
}

/// Merge the arrangement vertices closer than `tol` (all pool vertices are arrangement vertices at
/// this stage) and drop the faces and cells that degenerate. `cell_sign` is re-indexed with the cells.
pub(super) fn merge_close_vertices(
    arr: &mut Arrangement,
    cell_sign: &mut Vec<super::signs::SignVec>,
    tol: f64,
) -> MergeStats {
    let root = consistent_clusters(arr, close_clusters(&arr.pool.positions, tol));
    let n = root.len();
    if root.iter().enumerate().all(|(v, &r)| r as usize == v) {
        return MergeStats::default();
    }
    // Survivors: mean position, union of tags, (u,v) recomputed in every frame.
    let mut sum = vec![[0.0f64; 3]; n];
    let mut count = vec![0u32; n];
    let mut tags: Vec<PlaneTags> = vec![PlaneTags::new(); n];
    for (v, &r) in root.iter().enumerate() {
        let (r, p) = (r as usize, arr.pool.positions[v]);
        sum[r] = [sum[r][0] + p[0], sum[r][1] + p[1], sum[r][2] + p[2]];
        count[r] += 1;
        tags[r].extend(arr.pool.tags[v].iter().copied());
    }
    let mut new_id = vec![u32::MAX; n];
    let mut next = 0u32;
    for v in 0..n {
        if root[v] as usize == v {
            new_id[v] = next;
            next += 1;
        }
    }
    let mut pool = super::VertexPool::default();
    for v in 0..n {
        if root[v] as usize != v {
            continue;
        }
        let (pos, t) = if count[v] == 1 {
            (arr.pool.positions[v], arr.pool.tags[v].clone())
        } else {
            let c = count[v] as f64;
            let mut t = std::mem::take(&mut tags[v]);
            t.sort_unstable();
            t.dedup();
            ([sum[v][0] / c, sum[v][1] / c, sum[v][2] / c], t)
        };
        let uv = if count[v] == 1 {
            arr.pool.uv[v].clone()
        } else {
            t.iter()
                .map(|&p| arr.planes[p as usize].plane.to_2d(pos))
                .collect()
        };
        pool.positions.push(pos);
        pool.tags.push(t);
        pool.uv.push(uv);
    }
    let map = |v: VertexId| new_id[root[v as usize] as usize];
    let merged = |v: VertexId| count[root[v as usize] as usize] > 1;

    // Faces: renumbered polygons without repeats; fewer than three vertices: dropped.
    let mut face_new: Vec<Option<FaceId>> = vec![None; arr.faces.len()];
    let mut faces = Vec::with_capacity(arr.faces.len());
    let mut touched_cells = vec![false; arr.cells.len()];
    for (f, mut face) in std::mem::take(&mut arr.faces).into_iter().enumerate() {
        let touched = face.polygon.iter().any(|&v| merged(v));
        let poly = merged_polygon(&face.polygon, map);
        if touched {
            for c in [face.positive_cell, face.negative_cell]
                .into_iter()
                .flatten()
            {
                touched_cells[c as usize] = true;
            }
        }
        if poly.len() < 3 {
            continue;
        }
        face.polygon = poly;
        face_new[f] = Some(faces.len() as FaceId);
        faces.push(face);
    }
    let dropped_faces = face_new.iter().filter(|f| f.is_none()).count();

    // Cells: faces renumbered; a cell with no face left: dropped.
    let mut cell_new: Vec<Option<CellId>> = vec![None; arr.cells.len()];
    let mut cells = Vec::with_capacity(arr.cells.len());
    let mut signs = Vec::with_capacity(cell_sign.len());
    let old_signs = std::mem::take(cell_sign);
    for (c, (mut cell, sign)) in std::mem::take(&mut arr.cells)
        .into_iter()
        .zip(old_signs)
        .enumerate()
    {
        cell.faces
            .retain_mut(|cf| match face_new[cf.face as usize] {
                Some(f) => {
                    cf.face = f;
                    true
                }
                None => false,
            });
        if cell.faces.is_empty() {
            continue;
        }
        cell_new[c] = Some(cells.len() as CellId);
        cells.push(cell);
        signs.push(sign);
    }
    let dropped_cells = cell_new.iter().filter(|c| c.is_none()).count();
    for face in &mut faces {
        // A surviving face keeps both its cells (a cell is dropped only with all its faces).
        face.positive_cell = face.positive_cell.and_then(|c| cell_new[c as usize]);
        face.negative_cell = face.negative_cell.and_then(|c| cell_new[c as usize]);
    }
    arr.pool = pool;
    arr.faces = faces;
    arr.cells = cells;
    *cell_sign = signs;
    for (c, &t) in touched_cells.iter().enumerate() {
        if let (true, Some(nc)) = (t, cell_new[c]) {
            arr.cells[nc as usize].volume = cell_volume(arr, nc);
        }
    }
    MergeStats {
        vertices: n - next as usize,
        faces: dropped_faces,
        cells: dropped_cells,
    }
}

/// Section points on two or more planes (contour crossings, contour vertices on a plane) closer
/// than `tol` to an arrangement vertex on all their planes are that vertex: a contour passing a
/// rounding error away from a corner would otherwise leave a micro edge on the face boundary.
/// Likewise a contour vertex on its own plane only, next along a piece to a point on a line of
/// that plane closer than `tol`, is that point: a vertex meant to lie on the line (a fan's axis
/// through a vertex of every section, the slicer's rounding putting it 1e-16 to one side) is
/// crossed by its edge at a new point beside it, a micro edge whose two ends every Delaunay
/// predicate sees as one (13 of 16 cells of a cylinder under a fan fell back to the untagged
/// kernel). `n_arr`: number of arrangement vertices at the start of the pool. Returns the merged
/// count.
pub(super) fn merge_line_points(arr: &mut Arrangement, n_arr: usize, tol: f64) -> usize {
    if tol.is_nan() || tol <= 0.0 {
        return 0;
    }
    let pos = &arr.pool.positions;
    let corners = ByX::of(pos, 0..n_arr as VertexId);
    let mut merged_into: HashMap<VertexId, VertexId> = HashMap::default();
    for v in n_arr..pos.len() {
        let tags = &arr.pool.tags[v];
        if tags.len() < 2 {
            continue;
        }
        let on_all = |a: VertexId| tags.iter().all(|t| arr.pool.tags[a as usize].contains(t));
        if let Some(a) = corners.nearest(pos, pos[v], tol, on_all) {
            merged_into.insert(v as VertexId, a);
        }
    }
    micro_edges_to_lines(arr, n_arr, tol, &mut merged_into);
    if merged_into.is_empty() {
        return 0;
    }
    let map = |v: VertexId| merged_into.get(&v).copied().unwrap_or(v);
    for face in &mut arr.faces {
        for piece in &mut face.pieces {
            piece.outer = merged_polygon(&piece.outer, map);
            for h in &mut piece.holes {
                *h = merged_polygon(h, map);
            }
            piece.holes.retain(|h| h.len() >= 3);
        }
        face.pieces.retain(|p| p.outer.len() >= 3);
    }
    super::reconcile::compact(arr, &merged_into);
    merged_into.len()
}

/// The contour vertices on their own plane only (section points, from `n_arr` on) that are next
/// along a piece to a section point on a line of that plane closer than `tol`, into
/// `merged_into` (that point, or what it is merged into already).
fn micro_edges_to_lines(
    arr: &Arrangement,
    n_arr: usize,
    tol: f64,
    merged_into: &mut HashMap<VertexId, VertexId>,
) {
    let (pos, tags) = (&arr.pool.positions, &arr.pool.tags);
    let own_only = |v: VertexId| v as usize >= n_arr && tags[v as usize].len() == 1;
    let on_line = |v: VertexId, plane: u32| {
        v as usize >= n_arr && tags[v as usize].len() >= 2 && tags[v as usize].contains(&plane)
    };
    let mut found: Vec<(VertexId, VertexId)> = Vec::new();
    for face in &arr.faces {
        for piece in &face.pieces {
            for l in std::iter::once(&piece.outer).chain(&piece.holes) {
                for k in 0..l.len() {
                    let (a, b) = (l[k], l[(k + 1) % l.len()]);
                    for (v, w) in [(a, b), (b, a)] {
                        let (p, q) = (pos[v as usize], pos[w as usize]);
                        let d2: f64 = (0..3).map(|i| (p[i] - q[i]).powi(2)).sum();
                        if own_only(v) && on_line(w, face.plane) && d2 < tol * tol {
                            found.push((v, w));
                        }
                    }
                }
            }
        }
    }
    found.extend(touching_lines(arr, n_arr, tol));
    found.sort_unstable();
    for (v, w) in found {
        if !merged_into.contains_key(&v) {
            let w = merged_into.get(&w).copied().unwrap_or(w);
            merged_into.insert(v, w);
        }
    }
}

/// The contour vertices on their own plane only (from `n_arr` on) closer than `tol` to a section
/// point on a line of that plane that is not next to them along a piece, with that point: where
/// two sections touch their common line at one point (a cone cut by a plane along its axis and a
/// plane across it, each section tangent to the line there), one section's vertex can round to
/// just off the line while the other's crossing is on it, two vertices 1e-17 apart that the
/// cells of the face triangulate differently.
fn touching_lines(arr: &Arrangement, n_arr: usize, tol: f64) -> Vec<(VertexId, VertexId)> {
    let (pos, tags) = (&arr.pool.positions, &arr.pool.tags);
    let on_lines = ByX::of(
        pos,
        (n_arr..pos.len())
            .filter(|&v| tags[v].len() >= 2)
            .map(|v| v as VertexId),
    );
    let mut found = Vec::new();
    for v in n_arr..pos.len() {
        if tags[v].len() != 1 {
            continue;
        }
        let plane = tags[v][0];
        let on_plane = |w: VertexId| tags[w as usize].contains(&plane);
        if let Some(w) = on_lines.nearest(pos, pos[v], tol, on_plane) {
            found.push((v as VertexId, w));
        }
    }
    found
}

/// Pool vertices sorted by x, for the nearest one to a point within a tolerance.
struct ByX {
    ids: Vec<VertexId>,
    xs: Vec<f64>,
}

impl ByX {
    fn of(pos: &[[f64; 3]], ids: impl Iterator<Item = VertexId>) -> ByX {
        let mut ids: Vec<VertexId> = ids.collect();
        ids.sort_by(|&a, &b| pos[a as usize][0].total_cmp(&pos[b as usize][0]));
        let xs = ids.iter().map(|&a| pos[a as usize][0]).collect();
        ByX { ids, xs }
    }

    /// The vertex nearest to `p` closer than `tol` that `accept` takes (the first in x order on
    /// a tie).
    fn nearest(
        &self,
        pos: &[[f64; 3]],
        p: [f64; 3],
        tol: f64,
        accept: impl Fn(VertexId) -> bool,
    ) -> Option<VertexId> {
        let start = self.xs.partition_point(|&x| x <= p[0] - tol);
        let mut best: Option<(f64, VertexId)> = None;
        for &a in &self.ids[start..] {
            let q = pos[a as usize];
            if q[0] >= p[0] + tol {
                break;
            }
            let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
            if d < tol && accept(a) && best.is_none_or(|b| d < b.0) {
                best = Some((d, a));
            }
        }
        best.map(|(_, a)| a)
    }
}

/// Volume of a cell from its face polygons (outward orientation from `outward_is_plane_normal`).
fn cell_volume(arr: &Arrangement, c: CellId) -> f64 {
    let cell = &arr.cells[c as usize];
    let first = &arr.faces[cell.faces[0].face as usize];
    let o = arr.pool.positions[first.polygon[0] as usize];
    let mut vol = 0.0;
    for cf in &cell.faces {
        let poly = &arr.faces[cf.face as usize].polygon;
        let p = |k: usize| {
            let x = arr.pool.positions[poly[k] as usize];
            [x[0] - o[0], x[1] - o[1], x[2] - o[2]]
        };
        let mut s = 0.0;
        for i in 1..poly.len() - 1 {
            s += det3(p(0), p(i), p(i + 1)) / 6.0;
        }
        // Face polygons are counter-clockwise seen from the plane normal.
        vol += if cf.outward_is_plane_normal { s } else { -s };
    }
    vol
}

fn det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

#[cfg(test)]
mod tests {
    use crate::arrangement::{Arrangement, ArrangementOptions};
    use crate::sections::{Contour, Plane, Region, Section, Sections};

    /// Planes 22, 23, 26, 27 of Horsers.csl (integer equations) through (15.21, -8.81, 24.87) / 7 up to the
    /// rounding of their unit normals, each with a disk of radius `r` around that point.
    fn four_planes_nearly_through_one_point(r: f64) -> Sections {
        let p = [15.21 / 7.0, -8.81 / 7.0, 24.87 / 7.0];
        let eqs: [([f64; 3], f64); 4] = [
            ([0.0, -7.0, -7.0], 16.06),
            ([2.0, -5.0, -10.0], 24.89),
            ([3.0, 4.0, -5.0], 16.28),
            ([-1.0, 4.0, -8.0], 35.63),
        ];
        let sections = eqs
            .iter()
            .enumerate()
            .map(|(k, &(n, d))| {
                let plane = Plane::from_equation(n, d).unwrap();
                let c = plane.to_2d(p);
                let pts: Vec<[f64; 2]> = (0..40)
                    .map(|a| {
                        let t = a as f64 / 40.0 * std::f64::consts::TAU + 0.3 * k as f64;
                        [c[0] + r * t.cos(), c[1] + r * t.sin()]
                    })
                    .collect();
                Section {
                    plane,
                    regions: vec![Region {
                        label: 1,
                        outer: Contour::from_2d(&plane, pts),
                        holes: Vec::new(),
                    }],
                    source_index: k,
                    max_off_plane: 0.0,
                }
            })
            .collect();
        Sections {
            sections,
            n_labels: 1,
            warnings: Vec::new(),
            label_names: Default::default(),
        }
    }

    fn closest_pair(arr: &Arrangement) -> f64 {
        let pos = &arr.pool.positions;
        let mut best = f64::INFINITY;
        for a in 0..pos.len() {
            for b in a + 1..pos.len() {
                let d = (0..3).map(|k| (pos[a][k] - pos[b][k]).powi(2)).sum::<f64>();
                best = best.min(d.sqrt());
            }
        }
        best
    }

    fn diag(s: &Sections) -> f64 {
        let (lo, hi) = s.bounding_box().unwrap();
        (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
    }

    /// On z = 0, a triangle whose edge y = x + δ crosses x = 0 and y = 0 at δ from the corner of
    /// the three axis planes (the other two planes carry no section).
    fn contour_passing_near_a_corner(delta: f64) -> Sections {
        let axis = |k: usize| {
            let mut n = [0.0; 3];
            n[k] = 1.0;
            Plane::from_equation(n, 0.0).unwrap()
        };
        let z = axis(2);
        let pts = vec![[-1.0, -1.0 + delta], [1.0, 1.0 + delta], [-1.0, 1.0]];
        let mut sections = vec![Section {
            plane: z,
            regions: vec![Region {
                label: 1,
                outer: Contour::from_2d(&z, pts),
                holes: Vec::new(),
            }],
            source_index: 0,
            max_off_plane: 0.0,
        }];
        for k in [0, 1] {
            sections.push(Section {
                plane: axis(k),
                regions: Vec::new(),
                source_index: k + 1,
                max_off_plane: 0.0,
            });
        }
        Sections {
            sections,
            n_labels: 1,
            warnings: Vec::new(),
            label_names: Default::default(),
        }
    }

    #[test]
    fn crossings_a_rounding_error_from_a_corner_are_the_corner() {
        let s = contour_passing_near_a_corner(1e-13);
        let off = ArrangementOptions {
            merge_tolerance: 0.0,
            ..Default::default()
        };
        let arr = Arrangement::build(&s, &off).unwrap();
        assert!(closest_pair(&arr) < 1e-12, "{}", closest_pair(&arr));
        let opt = ArrangementOptions::default();
        let arr = Arrangement::build(&s, &opt).unwrap();
        assert!(closest_pair(&arr) >= opt.merge_tolerance * diag(&s));
        // The corner of the three planes is on the contour of plane 0.
        let corner = arr
            .pool
            .tags
            .iter()
            .position(|t| t.len() == 3 && t[..] == [0, 1, 2]);
        let corner = corner.expect("corner") as u32;
        let on_contour = arr
            .faces
            .iter()
            .flat_map(|f| f.pieces.iter())
            .filter(|p| p.outer.contains(&corner))
            .count();
        assert!(on_contour >= 2, "{on_contour}");
        let total: f64 = arr
            .faces
            .iter()
            .filter(|f| f.plane == 0)
            .flat_map(|f| f.pieces.iter())
            .map(|p| arr.piece_area(0, p))
            .sum();
        assert!((total - s.sections[0].area()).abs() <= 1e-9 * total);
        for face in &arr.faces {
            for piece in &face.pieces {
                assert!(piece.outer.len() >= 3);
                let a = arr.loop_area(face.plane, &piece.outer);
                assert!(a > 1e-20, "piece area {a}");
            }
        }
        assert!(
            arr.warnings.iter().all(|w| w.starts_with("sections")),
            "{:?}",
            arr.warnings
        );
    }

    #[test]
    fn the_configuration_has_rounding_apart_vertices_without_the_merge() {
        let s = four_planes_nearly_through_one_point(1.0);
        let opt = ArrangementOptions {
            merge_tolerance: 0.0,
            ..Default::default()
        };
        let arr = Arrangement::build(&s, &opt).unwrap();
        // What the exact predicates alone give: distinct vertices a rounding error apart.
        assert!(
            closest_pair(&arr) < 1e-12 * diag(&s),
            "{}",
            closest_pair(&arr)
        );
    }

    #[test]
    fn four_planes_nearly_through_one_point_give_one_vertex() {
        let s = four_planes_nearly_through_one_point(1.0);
        let opt = ArrangementOptions::default();
        let arr = Arrangement::build(&s, &opt).unwrap();
        let tol = opt.merge_tolerance * diag(&s);
        assert!(closest_pair(&arr) >= tol, "{}", closest_pair(&arr));
        // One vertex on all four planes.
        let centre = arr
            .pool
            .tags
            .iter()
            .filter(|t| (0..4).all(|p| t.contains(&p)))
            .count();
        assert_eq!(centre, 1);
        for (f, face) in arr.faces.iter().enumerate() {
            let mut vs = face.polygon.clone();
            vs.sort_unstable();
            vs.dedup();
            assert!(vs.len() >= 3 && vs.len() == face.polygon.len(), "face {f}");
            let a = arr.loop_area(face.plane, &face.polygon);
            assert!(a > tol * tol, "face {f}: area {a}");
            for &v in &face.polygon {
                assert!(arr.pool.tags[v as usize].contains(&face.plane));
            }
            for cell in [face.positive_cell, face.negative_cell]
                .into_iter()
                .flatten()
            {
                assert!(arr.cells[cell as usize]
                    .faces
                    .iter()
                    .any(|cf| cf.face as usize == f));
            }
        }
        for (c, cell) in arr.cells.iter().enumerate() {
            assert!(cell.faces.len() >= 4, "cell {c}");
            assert!(
                cell.volume > tol * tol * tol,
                "cell {c}: volume {}",
                cell.volume
            );
        }
        // The cells still tile the box.
        let (lo, hi) = arr.bbox;
        let box_vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
        let sum: f64 = arr.cells.iter().map(|c| c.volume).sum();
        assert!(((sum - box_vol) / box_vol).abs() < 1e-12);
        // Every section keeps its area in the pieces.
        for (i, sec) in s.sections.iter().enumerate() {
            let total: f64 = arr
                .faces
                .iter()
                .filter(|f| f.plane as usize == i)
                .flat_map(|f| f.pieces.iter())
                .map(|p| arr.piece_area(i as u32, p))
                .sum();
            assert!((total - sec.area()).abs() <= 1e-9 * sec.area(), "plane {i}");
        }
    }

    /// Plane `k` of the input, `plane`, with one region bounded by `pts`.
    fn section(plane: Plane, pts: &[[f64; 3]], k: usize) -> Section {
        Section {
            plane,
            regions: vec![Region {
                label: 1,
                outer: Contour::from_2d(&plane, pts.iter().map(|&p| plane.to_2d(p)).collect()),
                holes: Vec::new(),
            }],
            source_index: k,
            max_off_plane: 0.0,
        }
    }

    /// On z = 0 a triangle with its apex `delta` beside the line x = 0 (meant on it: a fan's axis
    /// through a vertex of every section), on x = 0 a square meeting z = 0 where the triangle does.
    fn vertex_beside_a_line(delta: f64) -> Sections {
        let z = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let x = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
        let triangle = [[-1.0, 0.0, 0.0], [delta, 0.5, 0.0], [1.0, 0.0, 0.0]];
        let square = [
            [0.0, 0.0, -0.5],
            [0.0, 0.5, -0.5],
            [0.0, 0.5, 0.5],
            [0.0, 0.0, 0.5],
        ];
        Sections {
            sections: vec![section(z, &triangle, 0), section(x, &square, 1)],
            n_labels: 1,
            warnings: Vec::new(),
            label_names: Default::default(),
        }
    }

    #[test]
    fn a_vertex_a_rounding_error_beside_a_line_is_the_point_on_it() {
        let s = vertex_beside_a_line(1e-16);
        let opt = ArrangementOptions::default();
        let arr = Arrangement::build(&s, &opt).unwrap();
        assert!(closest_pair(&arr) >= opt.merge_tolerance * diag(&s));
        // the triangle's pieces on either side of x = 0 share the apex, on both planes
        let apex: Vec<usize> = (0..arr.pool.positions.len())
            .filter(|&v| {
                let p = arr.pool.positions[v];
                (p[0].abs() < 1e-9) && ((p[1] - 0.5).abs() < 1e-9) && p[2].abs() < 1e-9
            })
            .collect();
        assert_eq!(apex.len(), 1, "{apex:?}");
        assert_eq!(arr.pool.tags[apex[0]].as_slice(), &[0, 1]);
        // a vertex farther than the tolerance stays a vertex of its own plane
        let s = vertex_beside_a_line(1e-3);
        let arr = Arrangement::build(&s, &opt).unwrap();
        assert!(arr
            .pool
            .positions
            .iter()
            .any(|p| p[0] == 1e-3 && p[1] == 0.5));
    }

    /// On z = 0 a triangle whose apex touches the line x = 0 from one side, 1e-16 off it; on
    /// x = 0 a triangle whose vertex touches z = 0 there, exactly on it (a cone cut along and
    /// across its axis: both sections tangent to their common line at one point). One vertex, on
    /// both planes; before, the apex stayed 1e-16 beside the other's point, and the cells of the
    /// face triangulated the two differently (a cone under axis planes: 3 non-conforming faces,
    /// 3 overlapping pairs).
    #[test]
    fn sections_touching_their_common_line_at_one_point_share_it() {
        let z = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let x = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
        let touching_x = [[-1.0, 0.0, 0.0], [-1e-16, 0.5, 0.0], [-1.0, 1.0, 0.0]];
        let touching_z = [[0.0, 0.5, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 0.5]];
        let s = Sections {
            sections: vec![section(z, &touching_x, 0), section(x, &touching_z, 1)],
            n_labels: 1,
            warnings: Vec::new(),
            label_names: Default::default(),
        };
        let opt = ArrangementOptions::default();
        let arr = Arrangement::build(&s, &opt).unwrap();
        let near: Vec<usize> = (0..arr.pool.positions.len())
            .filter(|&v| {
                let p = arr.pool.positions[v];
                p[0].abs() < 1e-9 && (p[1] - 0.5).abs() < 1e-9 && p[2].abs() < 1e-9
            })
            .collect();
        assert_eq!(near.len(), 1, "{near:?}");
        assert_eq!(arr.pool.tags[near[0]].as_slice(), &[0, 1]);
        assert!(closest_pair(&arr) >= opt.merge_tolerance * diag(&s));
    }
}
