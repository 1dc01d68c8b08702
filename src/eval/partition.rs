//! `check --partition`: are labelled domains (one closed surface per label) a partition of their
//! union, disjoint except for shared interfaces, and (optionally) does every label's section agree
//! with the input sections of that label?
//!
//! Per domain, [`check_mesh`] (closed, manifold, oriented, exact self-intersections; with sections, the
//! per-plane agreement with the label's own regions, `Sections::select_label`). Per pair of domains
//! whose boxes meet, all exact:
//! * vertices at the same position are one vertex of the pair (so triangles of the two labels that
//!   share vertices are tested as triangles of one mesh are);
//! * **interface**: a triangle of one label with the same three vertices as a triangle of the other,
//!   in opposite orientation, is interface (the domains lie on its two sides); the same triangle in
//!   the same orientation is an overlap (both domains on one side);
//! * **crossings**: any other pair of triangles, one per label, that intersects beyond its shared
//!   vertices or edge ([`mesh_triangles_intersect`], as the single-mesh self-intersection test);
//! * **inside**: a vertex of one domain that is no vertex of the other and lies strictly inside it
//!   ([`point_in_mesh`]: exact parity of a ray's crossings, `orient3d` signs, the ray drawn again
//!   when it meets an edge or vertex).
//!
//! A pair is disjoint when it has no same-orientation coincident triangle, no crossing and no vertex
//! inside the other. With sections, a pair whose regions share a contour edge in some plane but
//! whose domains share no interface triangle is reported as a gap.
use super::bvh::{triangle_boxes, Aabb, Bvh};
use super::check::{check_mesh, CheckReport};
use super::tri_tri::{is_degenerate, mesh_triangles_intersect, segment_meets_triangle};
use crate::geom::predicates::orient3d;
use crate::mesh::TriMesh;
use crate::sections::Sections;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::{HashMap, HashSet};

/// One label's domain.
#[derive(Clone, Debug, Serialize)]
pub struct DomainReport {
    pub label: i32,
    pub name: String,
    /// Closed, manifold, oriented and self-intersection free.
    pub valid: bool,
    pub check: CheckReport,
}

/// Two domains.
#[derive(Clone, Debug, Default, Serialize)]
pub struct PairReport {
    pub labels: [i32; 2],
    /// Coincident triangles in opposite orientation (each pair counted once) and their area.
    pub interface_triangles: usize,
    pub interface_area: f64,
    /// Coincident triangles in the same orientation: both domains on one side.
    pub coincident_same_orientation: usize,
    /// Intersecting triangle pairs beyond shared vertices and edges (exact).
    pub crossings: usize,
    /// The smallest crossing pair: (triangle of the first label, triangle of the second).
    pub crossing_example: Option<[usize; 2]>,
    /// A point of the first crossing pair's first triangle (its centroid), to say where.
    pub crossing_at: Option<[f64; 3]>,
    /// Vertices of the first label strictly inside the second, and of the second inside the first.
    pub vertices_inside: [usize; 2],
    /// One such vertex (its position).
    pub inside_example: Option<[f64; 3]>,
    /// Planes where the sections' regions of the two labels share a contour edge (with sections).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub section_contact_planes: Option<usize>,
    /// The sections say the labels touch, but the domains share no interface triangle.
    pub gap: bool,
    pub disjoint: bool,
}

#[derive(Clone, Debug, Serialize)]
pub struct PartitionReport {
    pub domains: Vec<DomainReport>,
    pub pairs: Vec<PairReport>,
    /// Every domain valid and every pair disjoint (gaps are reported, they do not invalidate).
    pub valid: bool,
    /// Gaps found (with sections).
    pub gaps: usize,
}

/// Check the domains `(label, name, mesh)` (module docs). With `sections`, each label's sections are
/// compared with its domain, and pairs touching in the sections but not in the domains are gaps.
pub fn check_partition(
    domains: &[(i32, String, TriMesh)],
    sections: Option<&Sections>,
) -> crate::error::Result<PartitionReport> {
    let mut reports = Vec::with_capacity(domains.len());
    for (label, name, mesh) in domains {
        let own = match sections {
            Some(s) => Some(s.select_label(Some(*label))?),
            None => None,
        };
        let check = check_mesh(mesh, own.as_ref());
        reports.push(DomainReport {
            label: *label,
            name: name.clone(),
            valid: check.is_closed_manifold() && check.oriented && check.self_intersection_free,
            check,
        });
    }
    let contacts = sections.map(section_contacts);
    let mut pairs = Vec::new();
    for i in 0..domains.len() {
        for j in i + 1..domains.len() {
            let mut p = check_pair(&domains[i].2, &domains[j].2);
            p.labels = [domains[i].0, domains[j].0];
            if let Some(c) = &contacts {
                let key = (p.labels[0].min(p.labels[1]), p.labels[0].max(p.labels[1]));
                let n = c.get(&key).copied().unwrap_or(0);
                p.section_contact_planes = Some(n);
                p.gap = n > 0 && p.interface_triangles == 0;
            }
            pairs.push(p);
        }
    }
    let valid = reports.iter().all(|d| d.valid) && pairs.iter().all(|p| p.disjoint);
    let gaps = pairs.iter().filter(|p| p.gap).count();
    Ok(PartitionReport {
        domains: reports,
        pairs,
        valid,
        gaps,
    })
}

/// Per pair of labels (lower first), the number of planes where a region of each has a contour edge
/// of the other (the same two 3D points, either direction).
pub fn section_contacts(sections: &Sections) -> HashMap<(i32, i32), usize> {
    let key = |p: [f64; 3]| p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let mut out: HashMap<(i32, i32), usize> = HashMap::new();
    for s in &sections.sections {
        let mut owner: HashMap<([u64; 3], [u64; 3]), HashSet<i32>> = HashMap::new();
        for r in &s.regions {
            for c in std::iter::once(&r.outer).chain(&r.holes) {
                let n = c.points3.len();
                for k in 0..n {
                    let (a, b) = (key(c.points3[k]), key(c.points3[(k + 1) % n]));
                    owner
                        .entry((a.min(b), a.max(b)))
                        .or_default()
                        .insert(r.label);
                }
            }
        }
        let mut here: HashSet<(i32, i32)> = HashSet::new();
        for labels in owner.values().filter(|l| l.len() > 1) {
            let mut l: Vec<i32> = labels.iter().copied().collect();
            l.sort_unstable();
            for a in 0..l.len() {
                for b in a + 1..l.len() {
                    here.insert((l[a], l[b]));
                }
            }
        }
        for p in here {
            *out.entry(p).or_default() += 1;
        }
    }
    out
}

/// Both meshes in one vertex array, vertices of `b` at the position of a vertex of `a` replaced by it.
fn joined(a: &TriMesh, b: &TriMesh) -> (Vec<[f64; 3]>, Vec<[u32; 3]>, Vec<bool>) {
    let key = |p: [f64; 3]| p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let at: HashMap<[u64; 3], u32> = a
        .vertices
        .iter()
        .enumerate()
        .map(|(i, &p)| (key(p), i as u32))
        .collect();
    let mut vertices = a.vertices.clone();
    let mut shared_b = vec![false; b.vertices.len()];
    let map: Vec<u32> = b
        .vertices
        .iter()
        .enumerate()
        .map(|(i, &p)| match at.get(&key(p)) {
            Some(&k) => {
                shared_b[i] = true;
                k
            }
            None => {
                vertices.push(p);
                (vertices.len() - 1) as u32
            }
        })
        .collect();
    let tb = b
        .triangles
        .iter()
        .map(|t| t.map(|v| map[v as usize]))
        .collect();
    (vertices, tb, shared_b)
}

/// The exact pair tests of the module docs for domains `a` and `b` (labels left unset).
pub fn check_pair(a: &TriMesh, b: &TriMesh) -> PairReport {
    let mut r = PairReport::default();
    let (ba, bb) = (Aabb::of_points(&a.vertices), Aabb::of_points(&b.vertices));
    if !ba.overlaps(&bb) {
        r.disjoint = true;
        return r;
    }
    let (v, tb, shared_b) = joined(a, b);
    let ta = &a.triangles;
    let sorted = |t: [u32; 3]| {
        let mut s = t;
        s.sort_unstable();
        s
    };
    let by_vertices: HashMap<[u32; 3], usize> = ta
        .iter()
        .enumerate()
        .map(|(i, &t)| (sorted(t), i))
        .collect();
    // twin_of_b[j]: the coincident triangle of `a`, if any.
    let mut twin_a = vec![false; ta.len()];
    let mut twin_b = vec![false; tb.len()];
    for (j, &t) in tb.iter().enumerate() {
        let Some(&i) = by_vertices.get(&sorted(t)) else {
            continue;
        };
        let s = ta[i];
        let rot = (0..3).find(|&k| s[k] == t[0]).unwrap_or(0);
        let same = s[(rot + 1) % 3] == t[1];
        if same {
            r.coincident_same_orientation += 1;
        } else {
            r.interface_triangles += 1;
            r.interface_area += crate::geom::triangle_area(t.map(|k| v[k as usize]));
        }
        twin_a[i] = true;
        twin_b[j] = true;
    }
    crossings(&v, ta, &tb, (&twin_a, &twin_b), &mut r);
    let mut shared_a = vec![false; a.vertices.len()];
    for &k in tb.iter().flatten() {
        if let Some(x) = shared_a.get_mut(k as usize) {
            *x = true;
        }
    }
    let a_only: Vec<[f64; 3]> = (0..a.vertices.len())
        .filter(|&k| !shared_a[k])
        .map(|k| a.vertices[k])
        .collect();
    let b_only: Vec<[f64; 3]> = (0..b.vertices.len())
        .filter(|&k| !shared_b[k])
        .map(|k| b.vertices[k])
        .collect();
    let (in_b, ex_b) = count_inside(&a_only, b);
    let (in_a, ex_a) = count_inside(&b_only, a);
    r.vertices_inside = [in_b, in_a];
    r.inside_example = ex_b.or(ex_a);
    r.disjoint = r.coincident_same_orientation == 0 && r.crossings == 0 && in_a + in_b == 0;
    r
}

/// Crossing pairs between `ta` and `tb` (indices into `v`), twins skipped.
fn crossings(
    v: &[[f64; 3]],
    ta: &[[u32; 3]],
    tb: &[[u32; 3]],
    twins: (&[bool], &[bool]),
    r: &mut PairReport,
) {
    let pts = |t: [u32; 3]| t.map(|k| v[k as usize]);
    let degenerate = |t: [u32; 3]| {
        let p = pts(t);
        t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || is_degenerate(p[0], p[1], p[2])
    };
    let bvh = Bvh::build(triangle_boxes(v, ta));
    let boxes_b = triangle_boxes(v, tb);
    let found: Vec<[usize; 2]> = (0..tb.len())
        .into_par_iter()
        .filter(|&j| !twins.1[j] && !degenerate(tb[j]))
        .flat_map_iter(|j| {
            let mut hits = Vec::new();
            bvh.for_each_overlap(&boxes_b[j], |i| {
                let i = i as usize;
                if !twins.0[i] && !degenerate(ta[i]) && mesh_triangles_intersect(ta[i], tb[j], v) {
                    hits.push([i, j]);
                }
            });
            hits
        })
        .collect();
    r.crossings = found.len();
    r.crossing_example = found.iter().min().copied();
    r.crossing_at = r.crossing_example.map(|[i, _]| {
        let p = pts(ta[i]);
        std::array::from_fn(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
    });
}

/// How many of `points` lie strictly inside `mesh`, and one of them.
fn count_inside(points: &[[f64; 3]], mesh: &TriMesh) -> (usize, Option<[f64; 3]>) {
    let locator = MeshLocator::new(mesh);
    let inside: Vec<[f64; 3]> = points
        .par_iter()
        .copied()
        .filter(|&p| locator.locate(p) == Location::Inside)
        .collect();
    (inside.len(), inside.first().copied())
}

/// Where a point is with respect to a closed mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    Inside,
    Outside,
    OnBoundary,
}

/// Exact point location in a closed, consistently oriented mesh: the parity of a ray's crossings
/// (every decision an `orient3d` sign; a ray meeting an edge, a vertex or running in a triangle's
/// plane is drawn again in another of 16 fixed directions).
pub struct MeshLocator<'a> {
    mesh: &'a TriMesh,
    bvh: Bvh,
    reach: f64,
}

/// Ray directions: nearly along ±x, ±y, ±z (so the ray's box stays thin), slightly skewed.
const RAY_DIRECTIONS: [[f64; 3]; 16] = {
    let mut d = [[0.0; 3]; 16];
    let mut i = 0;
    while i < 16 {
        let axis = i % 3;
        let sign = if (i / 3) % 2 == 0 { 1.0 } else { -1.0 };
        let mut v = [
            1.3e-3 * (i as f64 + 1.0),
            0.7e-3 * (i as f64 + 2.0),
            0.9e-3 * (i as f64 + 0.5),
        ];
        v[axis] = sign;
        d[i] = v;
        i += 1;
    }
    d
};

impl<'a> MeshLocator<'a> {
    pub fn new(mesh: &'a TriMesh) -> MeshLocator<'a> {
        let bvh = Bvh::build(triangle_boxes(&mesh.vertices, &mesh.triangles));
        let reach = 2.0 * bvh.bounds().diagonal() + 1.0;
        MeshLocator { mesh, bvh, reach }
    }

    /// Inside, outside or on the surface (closed triangles); `OnBoundary` too in the unlikely case
    /// that every ray direction is degenerate.
    pub fn locate(&self, p: [f64; 3]) -> Location {
        let b = self.bvh.bounds();
        if (0..3).any(|k| p[k] < b.lo[k] || p[k] > b.hi[k]) {
            return Location::Outside;
        }
        let tri = |i: u32| self.mesh.triangles[i as usize].map(|k| self.mesh.vertices[k as usize]);
        let mut on = false;
        self.bvh.for_each_overlap(&Aabb { lo: p, hi: p }, |i| {
            on = on || segment_meets_triangle(p, p, tri(i));
        });
        if on {
            return Location::OnBoundary;
        }
        'directions: for d in RAY_DIRECTIONS {
            let q: [f64; 3] = std::array::from_fn(|k| p[k] + self.reach * d[k]);
            let ray = Aabb::of_points(&[p, q]);
            let mut parity = false;
            let mut degenerate = false;
            self.bvh.for_each_overlap(&ray, |i| {
                if degenerate {
                    return;
                }
                match ray_crosses(p, q, tri(i)) {
                    Some(c) => parity ^= c,
                    None => degenerate = true,
                }
            });
            if degenerate {
                continue 'directions;
            }
            return if parity {
                Location::Inside
            } else {
                Location::Outside
            };
        }
        Location::OnBoundary
    }
}

/// Does segment pq (p on no triangle) cross triangle t through its interior? `None` when it meets
/// the triangle's boundary or lies in its plane (a degenerate ray).
fn ray_crosses(p: [f64; 3], q: [f64; 3], t: [[f64; 3]; 3]) -> Option<bool> {
    let [a, b, c] = t;
    let (sp, sq) = (orient3d(a, b, c, p), orient3d(a, b, c, q));
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return Some(false);
    }
    if sq == 0.0 || sp == 0.0 {
        // q in the plane (p is not on the triangle): degenerate if the segment meets it at all.
        return if segment_meets_triangle(p, q, t) {
            None
        } else {
            Some(false)
        };
    }
    let o = [
        orient3d(p, q, a, b),
        orient3d(p, q, b, c),
        orient3d(p, q, c, a),
    ];
    let pos = o.iter().any(|&x| x > 0.0);
    let neg = o.iter().any(|&x| x < 0.0);
    if pos && neg {
        return Some(false);
    }
    if o.contains(&0.0) {
        return None;
    }
    Some(true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::shapes::{grid_box, icosphere};

    #[test]
    fn points_in_a_box_and_a_sphere() {
        let b = grid_box([0.0; 3], [1.0; 3], [2, 2, 2]);
        let l = MeshLocator::new(&b);
        assert_eq!(l.locate([0.5, 0.5, 0.5]), Location::Inside);
        assert_eq!(l.locate([0.25, 0.5, 0.5]), Location::Inside); // ray along x meets grid edges
        assert_eq!(l.locate([1.0, 0.3, 0.7]), Location::OnBoundary);
        assert_eq!(l.locate([1.0, 0.5, 0.5]), Location::OnBoundary); // a grid vertex
        assert_eq!(l.locate([1.0 + 1e-15, 0.5, 0.5]), Location::Outside);
        assert_eq!(l.locate([1.0 - 1e-15, 0.5, 0.5]), Location::Inside);
        let s = icosphere([0.0; 3], 1.0, 3);
        let l = MeshLocator::new(&s);
        assert_eq!(l.locate([0.0; 3]), Location::Inside);
        assert_eq!(l.locate([0.9, 0.0, 0.0]), Location::Inside);
        assert_eq!(l.locate([0.0, 0.0, 1.5]), Location::Outside);
        assert_eq!(l.locate(s.vertices[7]), Location::OnBoundary);
    }
}

#[cfg(test)]
mod pair_tests {
    use super::*;
    use crate::slice::synthetic::{nested_spheres, touching_boxes};

    #[test]
    fn conforming_interfaces_are_interfaces_and_others_cross() {
        let c = touching_boxes(true);
        let p = check_pair(&c.domains[0].1, &c.domains[1].1);
        assert!(p.disjoint && p.crossings == 0, "{p:?}");
        assert_eq!(p.interface_triangles, 16);
        // Different grids on the face: coplanar overlapping triangles that are not the same.
        let c = touching_boxes(false);
        let p = check_pair(&c.domains[0].1, &c.domains[1].1);
        assert!(!p.disjoint && p.crossings > 0, "{p:?}");
        assert_eq!(p.vertices_inside, [0, 0]);
        // The core with itself: every triangle coincident in the same orientation.
        let s = nested_spheres();
        let p = check_pair(&s.domains[0].1, &s.domains[0].1);
        assert_eq!(p.coincident_same_orientation, 320);
        assert!(!p.disjoint);
        // The core against the whole ball (not the shell): core vertices strictly inside.
        let ball = &s.meshes[1].mesh;
        let p = check_pair(&s.domains[0].1, ball);
        assert_eq!(p.vertices_inside, [162, 0]);
        assert!(!p.disjoint && p.crossings == 0);
    }
}
