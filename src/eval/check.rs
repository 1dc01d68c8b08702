//! `check`: is a triangle mesh a valid solid boundary, and (optionally) do its sections agree with
//! the input cross-sections?
use super::bvh::{triangle_boxes, Bvh};
use super::near_coplanar::{
    edge_in_other_plane, normal, overlapping_near_coplanar_with_normals,
    EDGE_IN_PLANE_RELATIVE_TOLERANCE, NEAR_COPLANAR_RELATIVE_TOLERANCE,
};
use super::section::{section_agreement, SectionAgreement};
use super::topology::{analyze, ComponentReport};
use super::tri_tri::{is_degenerate, mesh_triangles_intersect};
use crate::mesh::TriMesh;
use crate::sections::Sections;
use rayon::prelude::*;
use serde::Serialize;

/// Everything `check` measures. Field names are the JSON keys scripts rely on.
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport {
    pub vertices: usize,
    pub triangles: usize,
    /// Every undirected edge is used by exactly two triangles (and no triangle repeats a vertex).
    pub closed: bool,
    /// Edge-manifold (no edge in three or more triangles) and vertex-manifold (every vertex fan is one
    /// disk, or one half-disk on the boundary), no triangle repeating a vertex index.
    pub manifold: bool,
    /// Every two-triangle edge is used once in each direction, and every closed component has
    /// positive signed volume (normals point outward).
    pub oriented: bool,
    /// Number of intersecting triangle pairs (exact; triangles sharing vertices count only when they
    /// overlap beyond what they share; degenerate triangles are not tested).
    pub self_intersections: usize,
    /// The intersecting pairs whose triangles share no vertex (what `shared/eval/evaluate.py` counts,
    /// except that it ignores contacts within rounding: it tests strict crossings with a 1e-12 margin).
    pub self_intersections_vertex_disjoint: usize,
    /// One intersecting pair (triangle indices), the smallest in lexicographic order.
    pub self_intersection_example: Option<[usize; 2]>,
    /// Pairs the exact test calls disjoint that nevertheless lie within `near_coplanar_tolerance` of
    /// each other's planes and overlap there with positive area (beyond any shared vertex or edge): a
    /// double sheet or a flat fold that only rounding keeps apart. Float checkers see them cross.
    pub overlapping_coplanar_pairs: usize,
    /// The smallest such pair.
    pub overlapping_coplanar_example: Option<[usize; 2]>,
    /// The absolute distance used for "near-coplanar": `NEAR_COPLANAR_RELATIVE_TOLERANCE` (1e-9) of
    /// the bounding-box diagonal.
    pub near_coplanar_tolerance: f64,
    /// No intersecting pair and no overlapping near-coplanar pair.
    pub self_intersection_free: bool,
    /// Informational, not a defect: disjoint pairs sharing no vertex, with overlapping bounding boxes,
    /// where an edge of one lies within 1e-12 of the diagonal of the other's plane. Float
    /// segment–triangle tests (the outside judge's) divide by a rounding-noise determinant there and
    /// may report crossings that exact arithmetic refutes; an upper bound on such false positives.
    pub edge_in_plane_pairs: usize,
    pub components: usize,
    /// V − E + F over the used vertices.
    pub euler: i64,
    /// Sum of the genera of the components where defined (closed, oriented, manifold components).
    pub genus: i64,
    /// Signed volume (divergence theorem), area.
    pub volume: f64,
    pub area: f64,
    pub boundary_edges: usize,
    pub nonmanifold_edges: usize,
    pub nonmanifold_vertices: usize,
    pub inconsistent_edges: usize,
    /// Triangles whose three points are collinear, or that repeat a vertex index.
    pub degenerate_triangles: usize,
    /// Used vertices sharing their exact position with another used vertex (counted beyond the first
    /// at each position): pinch points where the surface touches itself. The triangles around them
    /// meet there, so they also count in `self_intersections`; tools that weld vertices (trimesh's
    /// `process=True`, as in the outside judge) see a shared vertex instead and count nothing.
    pub coincident_vertices: usize,
    pub component_details: Vec<ComponentReport>,
    /// Per input plane (only with sections; empty and absent from the JSON without): the mesh's
    /// section against the input section.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sections: Vec<SectionAgreement>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_section: Option<WorstSection>,
}

/// The plane whose section disagrees most (largest `relative`).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct WorstSection {
    /// Index into `sections`.
    pub plane: usize,
    /// The plane's index in the input file.
    pub source_index: usize,
    pub relative: f64,
    pub sym_diff: f64,
}

impl CheckReport {
    pub fn is_closed_manifold(&self) -> bool {
        self.closed && self.manifold
    }
}

/// Check `mesh`; with `sections`, also compare its section by every input plane with the input.
pub fn check_mesh(mesh: &TriMesh, sections: Option<&Sections>) -> CheckReport {
    let topo = analyze(mesh);
    let si = self_intersections(mesh);
    let genus = topo.components.iter().filter_map(|c| c.genus).sum();
    let agreements = sections.map_or_else(Vec::new, |s| section_agreement(mesh, s));
    let worst_section = {
        agreements
            .iter()
            .max_by(|x, y| x.relative.total_cmp(&y.relative))
            .map(|w| WorstSection {
                plane: w.plane,
                source_index: w.source_index,
                relative: w.relative,
                sym_diff: w.sym_diff,
            })
    };
    CheckReport {
        vertices: mesh.vertices.len(),
        triangles: mesh.triangles.len(),
        closed: topo.closed,
        manifold: topo.manifold,
        oriented: topo.oriented,
        self_intersections: si.count,
        self_intersections_vertex_disjoint: si.vertex_disjoint,
        self_intersection_example: si.example,
        overlapping_coplanar_pairs: si.overlapping_coplanar,
        overlapping_coplanar_example: si.overlapping_coplanar_example,
        near_coplanar_tolerance: si.tolerance,
        self_intersection_free: si.count == 0 && si.overlapping_coplanar == 0,
        edge_in_plane_pairs: si.edge_in_plane,
        components: topo.components.len(),
        euler: topo.euler,
        genus,
        volume: topo.components.iter().map(|c| c.volume).sum(),
        area: topo.components.iter().map(|c| c.area).sum(),
        boundary_edges: topo.boundary_edges,
        nonmanifold_edges: topo.nonmanifold_edges,
        nonmanifold_vertices: topo.nonmanifold_vertices,
        inconsistent_edges: topo.inconsistent_edges,
        degenerate_triangles: si.collinear + topo.repeated_index_triangles,
        coincident_vertices: coincident_vertices(mesh),
        component_details: topo.components,
        sections: agreements,
        worst_section,
    }
}

/// Intersecting triangle pairs of one mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SelfIntersections {
    pub count: usize,
    /// Pairs sharing no vertex index.
    pub vertex_disjoint: usize,
    /// The smallest intersecting pair (i < j).
    pub example: Option<[usize; 2]>,
    /// Triangles with three collinear (distinct-index) points, skipped.
    pub collinear: usize,
    /// Pairs not intersecting exactly but overlapping near-coplanar (see [`super::near_coplanar`]).
    pub overlapping_coplanar: usize,
    pub overlapping_coplanar_example: Option<[usize; 2]>,
    /// Disjoint vertex-disjoint pairs with overlapping boxes and an edge of one in the other's plane.
    pub edge_in_plane: usize,
    /// Absolute near-coplanar tolerance used.
    pub tolerance: f64,
}

/// Count intersecting triangle pairs: BVH of triangle boxes, candidate pairs (i < j) with overlapping
/// boxes (grown by the near-coplanar tolerance), exact test, then the near-coplanar overlap test on the
/// pairs the exact test calls disjoint (rayon over i).
pub fn self_intersections(mesh: &TriMesh) -> SelfIntersections {
    let v = &mesh.vertices;
    let t = &mesh.triangles;
    let skip: Vec<bool> = t
        .par_iter()
        .map(|tr| {
            tr[0] == tr[1]
                || tr[1] == tr[2]
                || tr[0] == tr[2]
                || is_degenerate(v[tr[0] as usize], v[tr[1] as usize], v[tr[2] as usize])
        })
        .collect();
    let collinear = skip
        .iter()
        .zip(t)
        .filter(|(&s, tr)| s && tr[0] != tr[1] && tr[1] != tr[2] && tr[0] != tr[2])
        .count();
    let bvh = Bvh::build(triangle_boxes(v, t));
    let tolerance = if bvh.is_empty() {
        0.0
    } else {
        NEAR_COPLANAR_RELATIVE_TOLERANCE * bvh.bounds().diagonal()
    };
    let in_plane =
        tolerance * (EDGE_IN_PLANE_RELATIVE_TOLERANCE / NEAR_COPLANAR_RELATIVE_TOLERANCE);
    let pts = |tr: [u32; 3]| tr.map(|k| v[k as usize]);
    let normals: Vec<_> = t.par_iter().map(|&tr| normal(pts(tr))).collect();
    let smaller = |a: Option<[usize; 2]>, b: Option<[usize; 2]>| match (a, b) {
        (Some(x), Some(y)) => Some(x.min(y)),
        (x, y) => x.or(y),
    };
    let merge = |a: SelfIntersections, b: SelfIntersections| SelfIntersections {
        count: a.count + b.count,
        vertex_disjoint: a.vertex_disjoint + b.vertex_disjoint,
        example: smaller(a.example, b.example),
        collinear: 0,
        overlapping_coplanar: a.overlapping_coplanar + b.overlapping_coplanar,
        overlapping_coplanar_example: smaller(
            a.overlapping_coplanar_example,
            b.overlapping_coplanar_example,
        ),
        edge_in_plane: a.edge_in_plane + b.edge_in_plane,
        tolerance,
    };
    let mut out = (0..t.len())
        .into_par_iter()
        .filter(|&i| !skip[i])
        .map(|i| {
            let mut r = SelfIntersections::default();
            // A point of the other triangle's projection lies within tolerance/|n_k| ≤ √3·tolerance of
            // this triangle along the dropped axis: grow the query box by twice the tolerance.
            let bb = bvh.item_box(i as u32).grown(2.0 * tolerance);
            bvh.for_each_overlap(&bb, |j| {
                let j = j as usize;
                if j <= i || skip[j] {
                    return;
                }
                if mesh_triangles_intersect(t[i], t[j], v) {
                    r.count += 1;
                    if !t[i].iter().any(|x| t[j].contains(x)) {
                        r.vertex_disjoint += 1;
                    }
                    if r.example.is_none_or(|f| j < f[1]) {
                        r.example = Some([i, j]);
                    }
                } else if overlapping_near_coplanar_with_normals(
                    pts(t[i]),
                    normals[i],
                    pts(t[j]),
                    normals[j],
                    tolerance,
                ) {
                    r.overlapping_coplanar += 1;
                    if r.overlapping_coplanar_example.is_none_or(|f| j < f[1]) {
                        r.overlapping_coplanar_example = Some([i, j]);
                    }
                } else if !t[i].iter().any(|x| t[j].contains(x))
                    && bvh.item_box(i as u32).overlaps(bvh.item_box(j as u32))
                    && edge_in_other_plane(pts(t[i]), normals[i], pts(t[j]), normals[j], in_plane)
                {
                    r.edge_in_plane += 1;
                }
            });
            r
        })
        .reduce(SelfIntersections::default, merge);
    out.collinear = collinear;
    out.tolerance = tolerance;
    out
}

/// The pairs (i < j) of `triangles` that overlap nearly in one plane within `tolerance`
/// (absolute), whether or not they also cross: the BVH search of [`self_intersections`] with the
/// tolerance given rather than taken from the triangles' box (for callers that judge a part of a
/// model by the model's tolerance), in order.
pub fn overlapping_near_coplanar_pairs(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    tolerance: f64,
) -> Vec<[usize; 2]> {
    let pts = |tr: [u32; 3]| tr.map(|k| vertices[k as usize]);
    let normals: Vec<_> = triangles.iter().map(|&tr| normal(pts(tr))).collect();
    let bvh = Bvh::build(triangle_boxes(vertices, triangles));
    let mut out = Vec::new();
    for (i, &a) in triangles.iter().enumerate() {
        // as in `self_intersections`: a point within the tolerance of the other's plane is within
        // twice it of its box
        let bb = bvh.item_box(i as u32).grown(2.0 * tolerance);
        let mut found: Vec<usize> = Vec::new();
        bvh.for_each_overlap(&bb, |j| {
            let j = j as usize;
            let b = triangles[j];
            if j > i
                && overlapping_near_coplanar_with_normals(
                    pts(a),
                    normals[i],
                    pts(b),
                    normals[j],
                    tolerance,
                )
            {
                found.push(j);
            }
        });
        found.sort_unstable();
        out.extend(found.into_iter().map(|j| [i, j]));
    }
    out
}

/// Used vertices at exactly the position of another used vertex (beyond the first at each position).
pub fn coincident_vertices(mesh: &TriMesh) -> usize {
    let mut used = vec![false; mesh.vertices.len()];
    for t in &mesh.triangles {
        for &k in t {
            if let Some(u) = used.get_mut(k as usize) {
                *u = true;
            }
        }
    }
    // -0.0 and 0.0 are the same position: compare by value, not by bits
    let key = |p: [f64; 3]| p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let mut pts: Vec<[u64; 3]> = mesh
        .vertices
        .iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(&p, _)| key(p))
        .collect();
    pts.par_sort_unstable();
    pts.windows(2).filter(|w| w[0] == w[1]).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// The BVH search finds exactly the pairs a test of every pair finds: triangles on a small
        /// grid, each lifted off z = 0 by less or more than the tolerance (so sheets stack within
        /// it, miss it, or are far apart), some tilted by one raised corner.
        #[test]
        fn overlapping_pairs_are_those_of_every_pair(
            tris in proptest::collection::vec(
                (
                    proptest::array::uniform3((0i32..4, 0i32..4)),
                    prop_oneof![Just(0.0), Just(4e-10), Just(3e-9), Just(0.5)],
                    prop_oneof![Just(0.0), Just(0.0), Just(2e-10), Just(1.0)],
                ),
                1..16,
            ),
        ) {
            let mut vertices: Vec<[f64; 3]> = Vec::new();
            let mut triangles: Vec<[u32; 3]> = Vec::new();
            for (corners, lift, tilt) in &tris {
                let first = vertices.len() as u32;
                for (k, &(x, y)) in corners.iter().enumerate() {
                    let z = lift + if k == 0 { *tilt } else { 0.0 };
                    vertices.push([f64::from(x), f64::from(y), z]);
                }
                triangles.push([first, first + 1, first + 2]);
            }
            let tol = 1e-9;
            let pts = |tr: [u32; 3]| tr.map(|k| vertices[k as usize]);
            let mut every = Vec::new();
            for i in 0..triangles.len() {
                for j in i + 1..triangles.len() {
                    if crate::eval::near_coplanar::overlapping_near_coplanar(
                        pts(triangles[i]), pts(triangles[j]), tol,
                    ) {
                        every.push([i, j]);
                    }
                }
            }
            prop_assert_eq!(overlapping_near_coplanar_pairs(&vertices, &triangles, tol), every);
        }
    }
}
