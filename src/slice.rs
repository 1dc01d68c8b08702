//! Cutting a closed triangle mesh by planes into cross-sections: how users and tests make inputs with a
//! known answer.
//!
//! Per plane:
//! * **Classification is exact.** The plane is represented by its frame points `origin`, `origin + u`,
//!   `origin + v` (evaluated once in floating point); each mesh vertex gets the exact sign of `orient3d`
//!   against them. A vertex exactly on the plane is treated as lying on the `+normal` side (symbolic
//!   perturbation: the plane is moved infinitesimally towards `-normal`), consistently for every
//!   triangle, so each crossing triangle yields exactly one segment and the segments close into loops.
//! * **Crossing points are constructed once per edge** (floating point, keyed by the undirected edge, so
//!   the two triangles of an edge share the point); a vertex exactly on the plane is its own crossing point.
//! * Segments are chained into loops through the edges; loops that collapse to zero length or zero area
//!   (the plane touching a vertex or a ridge) are dropped, back-and-forth spikes are removed.
//! * **Nesting** is decided by exact point-in-polygon tests (`orient2d`) of a loop vertex against the
//!   other loops: even depth = outer contour (made CCW), odd depth = hole of the loop around it (made CW).
//!   Every region gets label 1. Planes whose section is empty are skipped.
//!
//! The mesh must be a closed, consistently oriented 2-manifold (every directed edge once, its twin once);
//! anything else is an `Error::Input`. Its global orientation does not matter (depth decides).
//! The result passes through the shared validator (`crate::validate`). A plane exactly through a
//! saddle vertex makes contours that touch there, which the validator may reject; [`make_planes`] keeps
//! its planes clear of vertices so this only happens with planes the caller chooses.
//!
//! Several meshes with a label each: [`slice_partition`] (module `partition`: priority by order,
//! touching outlines of different labels share their vertices). Where the planes go: [`make_planes`]
//! (module `planes`).
use crate::error::{Error, Result};
use crate::geom::predicates::{orient2d, orient3d};
use crate::mesh::TriMesh;
use crate::sections::{Contour, Plane, Region, Section, Sections};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};

pub mod odd;
mod partition;
mod planes;
pub mod synthetic;
pub use partition::{slice_partition, union_mesh, LabelledMesh, SHARED_VERTEX_RELATIVE_TOLERANCE};
pub use planes::{make_planes, SliceMode, PLANE_CLEARANCE, SWEEP_MAX_TILT_DEG};

/// Cut `mesh` by every plane; planes whose section is empty are skipped. `source_index` of each
/// section is its position in the result. The result goes through [`crate::validate::validate`]
/// (errors are located as `mesh: section i`).
pub fn slice_mesh(mesh: &TriMesh, planes: &[Plane]) -> Result<Sections> {
    check_closed_manifold(mesh)?;
    let per_plane: Vec<Option<Vec<Region>>> = planes
        .par_iter()
        .map(|p| section_regions(mesh, p))
        .collect::<Result<_>>()?;
    let mut sections = Vec::new();
    for (plane, regions) in planes.iter().zip(per_plane) {
        if let Some(regions) = regions {
            sections.push(Section {
                plane: *plane,
                regions,
                source_index: sections.len(),
                max_off_plane: 0.0,
            });
        }
    }
    // The shared validator checks what every reader's output satisfies (simple, non-crossing
    // contours, holes inside their parents, orientation); a repair here would be a slicer bug.
    crate::validate::validate(
        Sections {
            sections,
            n_labels: 1,
            warnings: Vec::new(),
            label_names: Default::default(),
        },
        "mesh",
    )
}

/// Check that `mesh` bounds a solid: finite coordinates, indices in range, no degenerate triangle, and
/// every directed edge used once with its reverse used once (closed, manifold along edges, oriented).
pub fn check_closed_manifold(mesh: &TriMesh) -> Result<()> {
    let n = mesh.vertices.len();
    if let Some(i) = mesh
        .vertices
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(Error::input(
            format!("mesh: vertex {i}"),
            "coordinate is not finite",
        ));
    }
    let mut directed: Vec<(u32, u32)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (ti, t) in mesh.triangles.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= n) {
            return Err(Error::input(
                format!("mesh: triangle {ti}"),
                format!("vertex index out of range ({n} vertices)"),
            ));
        }
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Err(Error::input(
                format!("mesh: triangle {ti}"),
                "repeated vertex index",
            ));
        }
        for k in 0..3 {
            directed.push((t[k], t[(k + 1) % 3]));
        }
    }
    directed.sort_unstable();
    for w in directed.windows(2) {
        if w[0] == w[1] {
            let (a, b) = w[0];
            return Err(Error::input(
                "mesh",
                format!(
                    "edge ({a},{b}) is used twice in the same direction: the mesh is non-manifold \
                     or inconsistently oriented, slicing needs a closed oriented surface"
                ),
            ));
        }
    }
    for &(a, b) in &directed {
        if directed.binary_search(&(b, a)).is_err() {
            return Err(Error::input(
                "mesh",
                format!(
                    "the mesh is not closed: edge ({a},{b}) has no neighbouring triangle across it \
                     (slicing needs a closed surface)"
                ),
            ));
        }
    }
    Ok(())
}

/// The regions of one plane's section, `None` when it is empty.
fn section_regions(mesh: &TriMesh, plane: &Plane) -> Result<Option<Vec<Region>>> {
    let (fa, fb, fc) = (
        plane.to_3d([0.0, 0.0]),
        plane.to_3d([1.0, 0.0]),
        plane.to_3d([0.0, 1.0]),
    );
    // orient3d > 0: below the CCW-from-above frame triangle, i.e. on the -normal side.
    let orient: Vec<f64> = mesh
        .vertices
        .iter()
        .map(|&p| orient3d(fa, fb, fc, p))
        .collect();
    let plus = |v: u32| orient[v as usize] <= 0.0;

    // Crossing points by undirected edge, and segments start edge -> end edge.
    let mut point_of_edge: HashMap<(u32, u32), [f64; 2]> = HashMap::new();
    let mut next: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    let key = |a: u32, b: u32| if a < b { (a, b) } else { (b, a) };
    for t in &mesh.triangles {
        let s = [plus(t[0]), plus(t[1]), plus(t[2])];
        if s[0] == s[1] && s[1] == s[2] {
            continue;
        }
        let k = (0..3)
            .find(|&k| s[k] != s[(k + 1) % 3] && s[k] != s[(k + 2) % 3])
            .expect("two sides among three vertices leave one alone");
        let (lone, after, before) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        let (e_out, e_in) = (key(lone, after), key(before, lone));
        // The section boundary runs along n × N (interior on its left seen from +n): from the edge
        // after a lone `+` vertex to the edge before it, reversed for a lone `-` vertex.
        let (from, to) = if s[k] { (e_out, e_in) } else { (e_in, e_out) };
        for e in [e_out, e_in] {
            point_of_edge.entry(e).or_insert_with(|| {
                let (p, q) = if plus(e.0) { (e.0, e.1) } else { (e.1, e.0) };
                crossing_point(plane, mesh, p, q, orient[p as usize] == 0.0)
            });
        }
        if next.insert(from, to).is_some() {
            return Err(Error::input(
                "mesh",
                "edge used by more than two triangles (non-manifold), cannot slice",
            ));
        }
    }
    if next.is_empty() {
        return Ok(None);
    }

    // Chain segments into loops.
    let mut loops: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut starts: Vec<(u32, u32)> = next.keys().copied().collect();
    starts.sort_unstable(); // deterministic loop order
    let mut visited: HashSet<(u32, u32)> = HashSet::with_capacity(next.len());
    for s in starts {
        if visited.contains(&s) {
            continue;
        }
        let mut pts = Vec::new();
        let mut e = s;
        loop {
            visited.insert(e);
            pts.push(point_of_edge[&e]);
            e = *next.get(&e).ok_or_else(|| {
                Error::input(
                    "mesh",
                    "the mesh is not closed: a section contour does not close",
                )
            })?;
            if e == s {
                break;
            }
            if visited.contains(&e) {
                return Err(Error::input(
                    "mesh",
                    "non-manifold mesh: section contours branch",
                ));
            }
        }
        let pts = clean_loop(pts);
        if pts.len() >= 3 && has_area(&pts) {
            loops.push(pts);
        }
    }
    if loops.is_empty() {
        return Ok(None);
    }
    Ok(Some(nest(plane, loops)))
}

/// Crossing of edge p (on the + side) → q (on the − side) with the plane; exactly p when p is on it.
fn crossing_point(plane: &Plane, mesh: &TriMesh, p: u32, q: u32, p_on_plane: bool) -> [f64; 2] {
    let (pp, qq) = (mesh.vertices[p as usize], mesh.vertices[q as usize]);
    if p_on_plane {
        return plane.to_2d(pp);
    }
    let (dp, dq) = (plane.signed_distance(pp), plane.signed_distance(qq));
    let t = dp / (dp - dq);
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let x = [
        pp[0] + t * (qq[0] - pp[0]),
        pp[1] + t * (qq[1] - pp[1]),
        pp[2] + t * (qq[2] - pp[2]),
    ];
    plane.to_2d(x)
}

/// Remove consecutive duplicates and back-and-forth spikes (a, b, a), cyclically.
fn clean_loop(pts: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    let mut st: Vec<[f64; 2]> = Vec::with_capacity(pts.len());
    for p in pts {
        if st.last() == Some(&p) {
            continue;
        }
        if st.len() >= 2 && st[st.len() - 2] == p {
            st.pop();
            continue;
        }
        st.push(p);
    }
    loop {
        let n = st.len();
        if n >= 2 && st[0] == st[n - 1] {
            st.pop();
        } else if n >= 3 && st[n - 2] == st[0] {
            st.pop(); // spike at the last vertex
        } else if n >= 3 && st[n - 1] == st[1] {
            st.remove(0); // spike at the first vertex
        } else {
            return st;
        }
    }
}

fn has_area(pts: &[[f64; 2]]) -> bool {
    (1..pts.len() - 1).any(|i| orient2d(pts[0], pts[i], pts[i + 1]) != 0.0)
}

#[derive(PartialEq)]
enum Inside {
    In,
    Out,
    Boundary,
}

/// Exact winding test of `p` against the closed polygon `poly` (non-zero winding = inside).
fn point_in_polygon(p: [f64; 2], poly: &[[f64; 2]]) -> Inside {
    let n = poly.len();
    let mut winding = 0i64;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] <= p[1]) != (b[1] <= p[1]) || (a[1] == p[1] && b[1] == p[1]) {
            let o = orient2d(a, b, p);
            if o == 0.0
                && p[0] >= a[0].min(b[0])
                && p[0] <= a[0].max(b[0])
                && p[1] >= a[1].min(b[1])
                && p[1] <= a[1].max(b[1])
            {
                return Inside::Boundary;
            }
            if a[1] <= p[1] && b[1] > p[1] && o > 0.0 {
                winding += 1;
            } else if a[1] > p[1] && b[1] <= p[1] && o < 0.0 {
                winding -= 1;
            }
        }
    }
    if winding != 0 {
        Inside::In
    } else {
        Inside::Out
    }
}

/// Exact orientation of a simple polygon: the sign of the turn at its lowest-leftmost vertex.
fn is_ccw(pts: &[[f64; 2]]) -> bool {
    let n = pts.len();
    let i = (0..n)
        .min_by(|&a, &b| {
            pts[a][1]
                .total_cmp(&pts[b][1])
                .then(pts[a][0].total_cmp(&pts[b][0]))
        })
        .unwrap_or(0);
    let o = orient2d(pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
    if o != 0.0 {
        o > 0.0
    } else {
        signed_area(pts) > 0.0
    }
}

fn signed_area(pts: &[[f64; 2]]) -> f64 {
    let n = pts.len();
    (0..n)
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        * 0.5
}

/// Containment tree of the loops → regions with holes, oriented by depth.
fn nest(plane: &Plane, loops: Vec<Vec<[f64; 2]>>) -> Vec<Region> {
    let boxes: Vec<([f64; 2], [f64; 2])> = loops
        .iter()
        .map(|l| {
            l.iter().fold(
                ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                |(lo, hi), p| {
                    (
                        [lo[0].min(p[0]), lo[1].min(p[1])],
                        [hi[0].max(p[0]), hi[1].max(p[1])],
                    )
                },
            )
        })
        .collect();
    let n = loops.len();
    // containers[i]: loops that contain loop i.
    let mut containers: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        for j in 0..n {
            if i == j {
                continue;
            }
            let (bi, bj) = (boxes[i], boxes[j]);
            if bi.0[0] < bj.0[0] || bi.0[1] < bj.0[1] || bi.1[0] > bj.1[0] || bi.1[1] > bj.1[1] {
                continue;
            }
            // Loops of a closed surface do not cross, so one vertex off loop j decides.
            let verdict = loops[i]
                .iter()
                .map(|&p| point_in_polygon(p, &loops[j]))
                .find(|v| *v != Inside::Boundary);
            if verdict == Some(Inside::In) {
                containers[i].push(j);
            }
        }
    }
    let depth: Vec<usize> = containers.iter().map(Vec::len).collect();
    let mut loops: Vec<Option<Vec<[f64; 2]>>> = loops.into_iter().map(Some).collect();
    let mut region_of: HashMap<usize, usize> = HashMap::new();
    let mut regions: Vec<Region> = Vec::new();
    for i in 0..n {
        if depth[i].is_multiple_of(2) {
            let mut pts = loops[i].take().expect("each loop used once");
            if !is_ccw(&pts) {
                pts.reverse();
            }
            region_of.insert(i, regions.len());
            regions.push(Region {
                label: 1,
                outer: Contour::from_2d(plane, pts),
                holes: Vec::new(),
            });
        }
    }
    for i in 0..n {
        if depth[i] % 2 == 1 {
            let parent = containers[i]
                .iter()
                .copied()
                .find(|&j| depth[j] + 1 == depth[i])
                .expect("an odd-depth loop lies inside an even-depth one");
            let mut pts = loops[i].take().expect("each loop used once");
            if is_ccw(&pts) {
                pts.reverse();
            }
            regions[region_of[&parent]]
                .holes
                .push(Contour::from_2d(plane, pts));
        }
    }
    regions
}

fn bounding_box(pts: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let first = *pts.first()?;
    Some(pts.iter().fold((first, first), |(mut lo, mut hi), p| {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
        (lo, hi)
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sections::{cross, dot, normalize};

    /// Axis-aligned box [0,1]^3 split into a 2×2×2 grid of vertices per face (vertex layers at 0, ½, 1).
    fn cube() -> TriMesh {
        grid_box([0.0; 3], [1.0; 3], 2)
    }

    /// Closed box surface with `m` subdivisions per side, outward-oriented.
    pub(crate) fn grid_box(lo: [f64; 3], hi: [f64; 3], m: usize) -> TriMesh {
        let mut mesh = TriMesh::default();
        let mut ids: HashMap<[usize; 3], u32> = HashMap::new();
        let mut vid = |g: [usize; 3], mesh: &mut TriMesh| -> u32 {
            *ids.entry(g).or_insert_with(|| {
                mesh.vertices.push(std::array::from_fn(|k| {
                    lo[k] + (hi[k] - lo[k]) * g[k] as f64 / m as f64
                }));
                (mesh.vertices.len() - 1) as u32
            })
        };
        for axis in 0..3 {
            let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
            for side in [0, m] {
                for i in 0..m {
                    for j in 0..m {
                        let g = |di: usize, dj: usize| {
                            let mut g = [0; 3];
                            g[axis] = side;
                            g[a1] = i + di;
                            g[a2] = j + dj;
                            g
                        };
                        let q = [g(0, 0), g(1, 0), g(1, 1), g(0, 1)].map(|g| vid(g, &mut mesh));
                        // (a1, a2, axis) is right-handed: CCW in (a1,a2) faces +axis.
                        if side == m {
                            mesh.triangles.push([q[0], q[1], q[2]]);
                            mesh.triangles.push([q[0], q[2], q[3]]);
                        } else {
                            mesh.triangles.push([q[0], q[2], q[1]]);
                            mesh.triangles.push([q[0], q[3], q[2]]);
                        }
                    }
                }
            }
        }
        mesh
    }

    #[test]
    fn cube_cut_through_a_vertex_layer_has_area_one() {
        let m = cube();
        check_closed_manifold(&m).unwrap();
        for k in 0..3 {
            let mut n = [0.0; 3];
            n[k] = 1.0;
            let p = Plane::from_point_normal([0.5; 3], n).unwrap();
            let s = slice_mesh(&m, &[p]).unwrap();
            assert_eq!(s.sections.len(), 1);
            let sec = &s.sections[0];
            assert_eq!(sec.regions.len(), 1);
            assert!(sec.regions[0].holes.is_empty());
            assert_eq!(sec.area(), 1.0);
            assert!(sec.regions[0].outer.signed_area() > 0.0);
        }
    }

    #[test]
    fn plane_touching_the_bottom_face_gives_nothing_and_missing_planes_are_skipped() {
        let m = cube();
        let planes = [
            Plane::from_point_normal([0.0; 3], [0.0, 0.0, 1.0]).unwrap(),
            Plane::from_point_normal([0.0, 0.0, 3.0], [0.0, 0.0, 1.0]).unwrap(),
        ];
        assert!(slice_mesh(&m, &planes).unwrap().sections.is_empty());
    }

    #[test]
    fn inside_out_mesh_gives_the_same_oriented_sections() {
        let m = cube();
        let mut flipped = m.clone();
        flipped.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        let planes = [Plane::from_point_normal([0.3; 3], [0.2, 0.5, 1.0]).unwrap()];
        let (a, b) = (
            slice_mesh(&m, &planes).unwrap(),
            slice_mesh(&flipped, &planes).unwrap(),
        );
        assert!(a.sections[0].regions[0].outer.signed_area() > 0.0);
        let (x, y) = (
            a.sections[0].regions[0].outer.signed_area(),
            b.sections[0].regions[0].outer.signed_area(),
        );
        assert!((x - y).abs() < 1e-14, "{x} vs {y}"); // same polygon, other start vertex
    }

    #[test]
    fn open_mesh_is_rejected() {
        let mut m = cube();
        m.triangles.pop();
        let e = slice_mesh(&m, &make_planes(&m, 3, 1, SliceMode::Axes)).unwrap_err();
        assert!(e.to_string().contains("not closed"), "{e}");
    }

    #[test]
    fn nested_boxes_give_a_hole_and_an_island() {
        // A hollow box (outer shell outward, inner shell inward) plus a solid box inside the cavity.
        let mut m = grid_box([0.0; 3], [10.0; 3], 1);
        let mut add = |b: TriMesh, flip: bool| {
            let off = m.vertices.len() as u32;
            m.vertices.extend(b.vertices);
            for t in b.triangles {
                let t = t.map(|v| v + off);
                m.triangles.push(if flip { [t[0], t[2], t[1]] } else { t });
            }
        };
        add(grid_box([2.0; 3], [8.0; 3], 1), true);
        add(grid_box([4.0; 3], [6.0; 3], 1), false);
        let p = Plane::from_point_normal([5.0, 5.0, 5.2], [0.0, 0.0, 1.0]).unwrap();
        let s = slice_mesh(&m, &[p]).unwrap();
        let sec = &s.sections[0];
        assert_eq!(sec.regions.len(), 2);
        let with_hole = sec.regions.iter().find(|r| r.holes.len() == 1).unwrap();
        assert!((with_hole.area() - (100.0 - 36.0)).abs() < 1e-12);
        assert!(with_hole.holes[0].signed_area() < 0.0);
        assert!((sec.area() - (100.0 - 36.0 + 4.0)).abs() < 1e-12);
    }

    /// Polygonal torus around z: `m` segments around the axis, `k` (even) around the tube; the rings at
    /// tube angles 0 and π lie exactly on z = 0.
    fn torus(big_r: f64, r: f64, m: usize, k: usize) -> TriMesh {
        let mut mesh = TriMesh::default();
        for i in 0..m {
            let a = std::f64::consts::TAU * i as f64 / m as f64;
            for j in 0..k {
                let b = std::f64::consts::TAU * j as f64 / k as f64;
                let (cb, sb) = match j {
                    0 => (1.0, 0.0),
                    j if 2 * j == k => (-1.0, 0.0),
                    _ => (b.cos(), b.sin()),
                };
                let rho = big_r + r * cb;
                mesh.vertices.push([rho * a.cos(), rho * a.sin(), r * sb]);
            }
        }
        let id = |i: usize, j: usize| ((i % m) * k + j % k) as u32;
        for i in 0..m {
            for j in 0..k {
                let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                mesh.triangles.push([q[0], q[1], q[2]]);
                mesh.triangles.push([q[0], q[2], q[3]]);
            }
        }
        mesh
    }

    #[test]
    fn torus_cut_through_its_vertex_rings_is_an_annulus() {
        let (big_r, r, m) = (3.0, 1.0, 24);
        let t = torus(big_r, r, m, 8);
        check_closed_manifold(&t).unwrap();
        let p = Plane::from_point_normal([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let s = slice_mesh(&t, &[p]).unwrap();
        let sec = &s.sections[0];
        assert_eq!(sec.regions.len(), 1);
        assert_eq!(sec.regions[0].holes.len(), 1);
        assert_eq!(sec.regions[0].outer.points2.len(), m);
        let ngon = |rad: f64| 0.5 * m as f64 * (std::f64::consts::TAU / m as f64).sin() * rad * rad;
        let expect = ngon(big_r + r) - ngon(big_r - r);
        assert!(
            (sec.area() - expect).abs() < 1e-12 * expect,
            "{} vs {expect}",
            sec.area()
        );
        // Cut along the axis: two discs, no hole.
        let p = Plane::from_point_normal([0.0; 3], [1.0, 0.0, 0.0]).unwrap();
        let s = slice_mesh(&t, &[p]).unwrap();
        assert_eq!(s.sections[0].regions.len(), 2);
        assert!(s.sections[0].regions.iter().all(|r| r.holes.is_empty()));
    }

    const ALL_MODES: [SliceMode; 6] = [
        SliceMode::Random,
        SliceMode::Parallel,
        SliceMode::Axes,
        SliceMode::Fan,
        SliceMode::Sweep,
        SliceMode::Tilt,
    ];

    /// A box [10,13]×[20,22]×[30,31] away from the origin: three distinct extents (x longest, then
    /// y, then z) make every mode's choice of axes unambiguous.
    fn slab() -> TriMesh {
        grid_box([10.0, 20.0, 30.0], [13.0, 22.0, 31.0], 3)
    }

    fn diagonal(m: &TriMesh) -> f64 {
        let (lo, hi) = bounding_box(&m.vertices).unwrap();
        (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
    }

    /// The line where planes `a` and `b` meet: a point of it and its unit direction.
    fn meeting_line(a: &Plane, b: &Plane) -> ([f64; 3], [f64; 3]) {
        let d = cross(a.normal, b.normal);
        let dd = dot(d, d);
        assert!(dd > 1e-6, "planes almost parallel");
        let (p, q) = (cross(b.normal, d), cross(d, a.normal));
        let x = std::array::from_fn(|k| (-a.offset * p[k] - b.offset * q[k]) / dd);
        (x, normalize(d))
    }

    /// Every plane contains the line (two points of it `diag` apart, within 10⁻¹² of the diagonal).
    fn assert_all_contain(planes: &[Plane], (x, d): ([f64; 3], [f64; 3]), diag: f64) {
        for (i, p) in planes.iter().enumerate() {
            for t in [-0.5 * diag, 0.5 * diag] {
                let y = std::array::from_fn(|k| x[k] + t * d[k]);
                let s = p.signed_distance(y).abs();
                assert!(s <= 1e-12 * diag, "plane {i}: {s:e} off the common line");
            }
        }
    }

    #[test]
    fn fan_planes_share_the_line_along_the_longest_axis_through_the_centre() {
        // The cube's tie picks z; its face-centre vertices lie on that line, which moves off them.
        for (m, longest, n) in [(slab(), 0, 16), (cube(), 2, 16), (slab(), 0, 5)] {
            let diag = diagonal(&m);
            for seed in [0, 5] {
                let planes = make_planes(&m, n, seed, SliceMode::Fan);
                assert_eq!(planes.len(), n);
                let line = meeting_line(&planes[0], &planes[n / 2]);
                assert_all_contain(&planes, line, diag);
                assert!(line.1[longest].abs() > 1.0 - 1e-12, "{:?}", line.1);
                let (lo, hi) = bounding_box(&m.vertices).unwrap();
                let off: f64 = (0..3)
                    .filter(|&k| k != longest)
                    .map(|k| (line.0[k] - 0.5 * (lo[k] + hi[k])).powi(2))
                    .sum();
                assert!(
                    off.sqrt() <= 1e-3 * diag,
                    "line {:e} from the centre",
                    off.sqrt()
                );
                // Distinct: consecutive normals π/n apart (up to the clearance turns).
                let cos_min_gap = (0.9 * std::f64::consts::PI / n as f64).cos();
                for (i, a) in planes.iter().enumerate() {
                    for b in &planes[i + 1..] {
                        assert!(dot(a.normal, b.normal).abs() < cos_min_gap);
                    }
                }
            }
        }
    }

    #[test]
    fn sweep_planes_tilt_at_most_15_degrees_and_advance_inside_the_box() {
        let m = slab();
        let (lo, hi) = bounding_box(&m.vertices).unwrap();
        let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
        let planes = make_planes(&m, 12, 5, SliceMode::Sweep);
        assert_eq!(planes.len(), 12);
        let cos_max = (SWEEP_MAX_TILT_DEG.to_radians() + 1e-12).cos();
        let mut last = lo[0];
        let mut most_tilted: f64 = 0.0;
        for p in &planes {
            assert!(p.normal[0].abs() >= cos_max, "tilt {:?}", p.normal);
            most_tilted = most_tilted.max(p.normal[0].abs().acos().to_degrees());
            // Where the plane meets the central axis (centre + t·x).
            let at = centre[0] - p.signed_distance(centre) / p.normal[0];
            assert!(
                last < at && at < hi[0],
                "{at} after {last}, box ends at {}",
                hi[0]
            );
            last = at;
        }
        assert!(most_tilted > 5.0, "planes barely tilted: {most_tilted}°");
        assert_ne!(planes, make_planes(&m, 12, 6, SliceMode::Sweep));
    }

    #[test]
    fn tilt_planes_share_a_line_outside_the_box_and_cross_it() {
        let m = slab();
        let diag = diagonal(&m);
        let (lo, hi) = bounding_box(&m.vertices).unwrap();
        let planes = make_planes(&m, 16, 5, SliceMode::Tilt);
        assert_eq!(planes.len(), 16);
        let line = meeting_line(&planes[0], &planes[15]);
        assert_all_contain(&planes, line, diag);
        // Along y (second-longest), beyond the +z face (shortest axis): it misses the box.
        assert!(line.1[1].abs() > 1.0 - 1e-12, "{:?}", line.1);
        assert!(
            line.0[2] > hi[2],
            "line at z = {} inside the box",
            line.0[2]
        );
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|c| std::array::from_fn(|k| if c >> k & 1 == 1 { hi[k] } else { lo[k] }))
            .collect();
        for (i, p) in planes.iter().enumerate() {
            let d: Vec<f64> = corners.iter().map(|&c| p.signed_distance(c)).collect();
            assert!(
                d.iter().any(|&x| x > 0.0) && d.iter().any(|&x| x < 0.0),
                "plane {i} misses the box"
            );
        }
    }

    #[test]
    fn generated_planes_keep_clear_of_vertices() {
        // The cube's vertex layer at ½ is hit by parallel planes 1/2 and axis planes 1/2: moved off it;
        // its face-centre vertices lie on the fan's line and on the tilt line's middle plane.
        // Every plane still passes near the surface: within `far` (over half a grid cell's diagonal).
        for (m, far) in [(cube(), 0.5), (slab(), 1.0)] {
            let eps = PLANE_CLEARANCE * diagonal(&m);
            for mode in ALL_MODES {
                for n in [3, 4, 16] {
                    for p in make_planes(&m, n, 5, mode) {
                        let near = m
                            .vertices
                            .iter()
                            .map(|&v| p.signed_distance(v).abs())
                            .fold(f64::INFINITY, f64::min);
                        assert!(near > eps, "{mode:?} {n}: {near}");
                        assert!(near < far, "{mode:?} {n}: {near}");
                    }
                }
            }
        }
    }

    #[test]
    fn planes_are_deterministic_and_inside() {
        for m in [cube(), slab()] {
            for mode in ALL_MODES {
                let a = make_planes(&m, 7, 42, mode);
                assert_eq!(a, make_planes(&m, 7, 42, mode));
                assert_eq!(a.len(), 7);
                for p in &a {
                    // Every plane separates some vertices of the box.
                    let d: Vec<f64> = m.vertices.iter().map(|&v| p.signed_distance(v)).collect();
                    assert!(
                        d.iter().any(|&x| x > 0.0) && d.iter().any(|&x| x < 0.0),
                        "{mode:?}"
                    );
                }
            }
        }
        for mode in [SliceMode::Random, SliceMode::Fan, SliceMode::Sweep] {
            assert_ne!(
                make_planes(&cube(), 3, 1, mode),
                make_planes(&cube(), 3, 2, mode),
                "{mode:?} ignores the seed"
            );
        }
    }
}
