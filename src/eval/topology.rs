//! Combinatorial checks of a triangle mesh: edges and their uses, closedness, edge and vertex
//! manifoldness, orientation consistency, components (connected through shared edges), Euler
//! characteristic and genus; plus signed volume and area (floating point).
use crate::mesh::{Stars, TriMesh};
use rayon::prelude::*;
use serde::Serialize;

/// One connected component (triangles connected through shared edges).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ComponentReport {
    pub triangles: usize,
    pub vertices: usize,
    pub edges: usize,
    /// V − E + F of this component.
    pub euler: i64,
    /// Every edge of the component is used by exactly two of its triangles.
    pub closed: bool,
    /// (2 − χ)/2 for a closed, consistently oriented manifold component; `None` otherwise.
    pub genus: Option<i64>,
    /// Signed volume (divergence theorem); positive when oriented outward. Meaningful when closed.
    pub volume: f64,
    pub area: f64,
}

#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Topology {
    pub vertices_used: usize,
    pub edges: usize,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by three or more triangles.
    pub nonmanifold_edges: usize,
    /// Vertices whose triangle fan is not a single disk (or half-disk at the boundary).
    pub nonmanifold_vertices: usize,
    /// Two-triangle edges used twice in the same direction.
    pub inconsistent_edges: usize,
    /// Triangles with a repeated vertex index.
    pub repeated_index_triangles: usize,
    pub closed: bool,
    pub manifold: bool,
    /// Consistent orientation on every edge, and every closed shell facing out of the material:
    /// positive volume, or negative for a cavity shell enclosed by an odd number of other shells.
    pub oriented: bool,
    pub euler: i64,
    pub components: Vec<ComponentReport>,
}

/// Undirected edge key (min, max) with the triangle and whether it runs min→max in that triangle.
#[derive(Clone, Copy)]
struct EdgeUse {
    a: u32,
    b: u32,
    tri: u32,
    forward: bool,
}

pub fn analyze(mesh: &TriMesh) -> Topology {
    let v = &mesh.vertices;
    let tris = &mesh.triangles;
    let repeated: Vec<bool> = tris
        .iter()
        .map(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        .collect();
    let mut uses: Vec<EdgeUse> = Vec::with_capacity(3 * tris.len());
    for (ti, t) in tris.iter().enumerate() {
        if repeated[ti] {
            continue;
        }
        for k in 0..3 {
            let (x, y) = (t[k], t[(k + 1) % 3]);
            uses.push(EdgeUse {
                a: x.min(y),
                b: x.max(y),
                tri: ti as u32,
                forward: x < y,
            });
        }
    }
    uses.par_sort_unstable_by_key(|e| ((e.a as u64) << 32 | e.b as u64, e.tri));

    // Per edge group: counts, orientation, triangle adjacency (union-find over triangles).
    let mut uf = UnionFind::new(tris.len());
    let (mut edges, mut boundary, mut nonmanifold, mut inconsistent) = (0, 0, 0, 0);
    let mut edge_group_start = Vec::new(); // for per-component edge counting
    let mut i = 0;
    while i < uses.len() {
        let mut j = i + 1;
        while j < uses.len() && uses[j].a == uses[i].a && uses[j].b == uses[i].b {
            j += 1;
        }
        edges += 1;
        edge_group_start.push(i);
        match j - i {
            1 => boundary += 1,
            2 => {
                if uses[i].forward == uses[i + 1].forward {
                    inconsistent += 1;
                }
            }
            _ => nonmanifold += 1,
        }
        for k in i + 1..j {
            uf.union(uses[i].tri as usize, uses[k].tri as usize);
        }
        i = j;
    }

    let nonmanifold_vertex = vertex_fans_are_disks(mesh, &repeated);
    let nonmanifold_vertices = nonmanifold_vertex.iter().filter(|&&b| b).count();

    // Components.
    let mut comp_of_root = vec![u32::MAX; tris.len()];
    let mut comps: Vec<ComponentReport> = Vec::new();
    let mut tri_comp = vec![u32::MAX; tris.len()];
    // Volumes relative to one vertex: less cancellation than relative to the world origin.
    let o = v.first().copied().unwrap_or([0.0; 3]);
    for ti in 0..tris.len() {
        if repeated[ti] {
            continue;
        }
        let r = uf.find(ti);
        if comp_of_root[r] == u32::MAX {
            comp_of_root[r] = comps.len() as u32;
            comps.push(ComponentReport {
                triangles: 0,
                vertices: 0,
                edges: 0,
                euler: 0,
                closed: true,
                genus: None,
                volume: 0.0,
                area: 0.0,
            });
        }
        let c = comp_of_root[r];
        tri_comp[ti] = c;
        let cr = &mut comps[c as usize];
        cr.triangles += 1;
        let t = tris[ti];
        let (a, b, cc) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
        cr.volume += det3(sub(a, o), sub(b, o), sub(cc, o)) / 6.0;
        cr.area += 0.5 * norm(cross(sub(b, a), sub(cc, a)));
    }
    let mut comp_inconsistent = vec![false; comps.len()];
    for &s in &edge_group_start {
        let c = tri_comp[uses[s].tri as usize] as usize;
        comps[c].edges += 1;
        let n = uses[s..]
            .iter()
            .take_while(|e| e.a == uses[s].a && e.b == uses[s].b)
            .count();
        if n != 2 {
            comps[c].closed = false;
        } else if uses[s].forward == uses[s + 1].forward {
            comp_inconsistent[c] = true;
        }
    }
    let mut vert_comp = vec![u32::MAX; v.len()];
    let mut comp_nonmanifold_vertex = vec![false; comps.len()];
    let mut vertices_used = 0;
    for (ti, t) in tris.iter().enumerate() {
        if repeated[ti] {
            continue;
        }
        for &x in t {
            if vert_comp[x as usize] == u32::MAX {
                vert_comp[x as usize] = tri_comp[ti];
                comps[tri_comp[ti] as usize].vertices += 1;
                vertices_used += 1;
            } else if vert_comp[x as usize] != tri_comp[ti] {
                // a vertex shared by two edge-components is a non-manifold pinch
                comp_nonmanifold_vertex[tri_comp[ti] as usize] = true;
            }
            if nonmanifold_vertex[x as usize] {
                comp_nonmanifold_vertex[tri_comp[ti] as usize] = true;
            }
        }
    }
    let mut euler = 0;
    for (c, cr) in comps.iter_mut().enumerate() {
        cr.euler = cr.vertices as i64 - cr.edges as i64 + cr.triangles as i64;
        euler += cr.euler;
        if cr.closed && !comp_inconsistent[c] && !comp_nonmanifold_vertex[c] {
            cr.genus = Some((2 - cr.euler) / 2);
        }
    }
    let all_volumes_positive = shells_face_outward(mesh, &comps, &tri_comp);
    let rep = repeated.iter().filter(|&&b| b).count();
    let closed = boundary == 0 && nonmanifold == 0 && rep == 0 && !tris.is_empty();
    let manifold = nonmanifold == 0 && nonmanifold_vertices == 0 && rep == 0;
    Topology {
        vertices_used,
        edges,
        boundary_edges: boundary,
        nonmanifold_edges: nonmanifold,
        nonmanifold_vertices,
        inconsistent_edges: inconsistent,
        repeated_index_triangles: rep,
        closed,
        manifold,
        oriented: inconsistent == 0 && nonmanifold == 0 && all_volumes_positive,
        euler,
        components: comps,
    }
}

/// Outward orientation of closed shells: a shell enclosed by an even number of other shells bounds
/// material (positive volume), one enclosed by an odd number bounds a cavity (negative volume).
/// Nesting is decided by the winding number of one vertex of the shell with respect to each other shell.
fn shells_face_outward(mesh: &TriMesh, comps: &[ComponentReport], tri_comp: &[u32]) -> bool {
    let closed: Vec<usize> = (0..comps.len()).filter(|&c| comps[c].closed).collect();
    if closed.iter().all(|&c| comps[c].volume > 0.0) && closed.len() < 2 {
        return true;
    }
    let mut tris_of: Vec<Vec<[u32; 3]>> = vec![Vec::new(); comps.len()];
    for (ti, t) in mesh.triangles.iter().enumerate() {
        if tri_comp[ti] != u32::MAX {
            tris_of[tri_comp[ti] as usize].push(*t);
        }
    }
    let v = &mesh.vertices;
    let bbox = |tris: &[[u32; 3]]| {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for t in tris {
            for &i in t {
                for k in 0..3 {
                    lo[k] = lo[k].min(v[i as usize][k]);
                    hi[k] = hi[k].max(v[i as usize][k]);
                }
            }
        }
        (lo, hi)
    };
    let boxes: Vec<_> = tris_of.iter().map(|t| bbox(t)).collect();
    closed.par_iter().all(|&c| {
        let p = v[tris_of[c][0][0] as usize];
        let depth = closed
            .iter()
            .filter(|&&d| d != c)
            .filter(|&&d| (0..3).all(|k| boxes[d].0[k] <= p[k] && p[k] <= boxes[d].1[k]))
            .filter(|&&d| winding_number(v, &tris_of[d], p).abs() > 0.5)
            .count();
        (comps[c].volume > 0.0) == (depth % 2 == 0)
    })
}

/// Generalised winding number of a closed shell around `p` (sum of signed solid angles / 4π).
fn winding_number(v: &[[f64; 3]], tris: &[[u32; 3]], p: [f64; 3]) -> f64 {
    let mut total = 0.0;
    for t in tris {
        let a = sub(v[t[0] as usize], p);
        let b = sub(v[t[1] as usize], p);
        let c = sub(v[t[2] as usize], p);
        let (la, lb, lc) = (norm(a), norm(b), norm(c));
        let num = det3(a, b, c);
        let den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
        total += 2.0 * num.atan2(den);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Every undirected edge in exactly two triangles, no triangle repeating an index (cheaper than
/// [`analyze`]).
pub fn is_closed(mesh: &TriMesh) -> bool {
    if mesh.triangles.is_empty()
        || mesh
            .triangles
            .iter()
            .any(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
    {
        return false;
    }
    let mut keys: Vec<u64> = mesh
        .triangles
        .iter()
        .flat_map(|t| {
            (0..3).map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                (a.min(b) as u64) << 32 | a.max(b) as u64
            })
        })
        .collect();
    keys.par_sort_unstable();
    keys.chunks(2).all(|c| c.len() == 2 && c[0] == c[1])
        && keys.windows(3).all(|w| !(w[0] == w[1] && w[1] == w[2]))
}

/// For each vertex, true when its triangle fan is not one cycle (interior) or one path (boundary).
/// The link of v has a node per neighbour and an edge a–b per triangle (v,a,b); with every link
/// node of degree ≤ 2 it is a disjoint union of cycles and paths, and must have exactly one piece.
fn vertex_fans_are_disks(mesh: &TriMesh, repeated: &[bool]) -> Vec<bool> {
    let n = mesh.vertices.len();
    let stars: Stars = Stars::new_where(n, &mesh.triangles, |ti| !repeated[ti]);
    (0..n)
        .into_par_iter()
        .map(|vi| {
            let fan = &stars[vi];
            if fan.is_empty() {
                return false;
            }
            // link edges (a, b) of the fan
            let mut nodes: Vec<u32> = Vec::with_capacity(2 * fan.len());
            let links: Vec<(u32, u32)> = fan
                .iter()
                .map(|&ti| {
                    let t = mesh.triangles[ti as usize];
                    let k = t.iter().position(|&x| x as usize == vi).unwrap_or(0);
                    (t[(k + 1) % 3], t[(k + 2) % 3])
                })
                .collect();
            for &(a, b) in &links {
                nodes.push(a);
                nodes.push(b);
            }
            nodes.sort_unstable();
            let mut degree: Vec<(u32, u32)> = Vec::new();
            for &x in &nodes {
                match degree.last_mut() {
                    Some((y, d)) if *y == x => *d += 1,
                    _ => degree.push((x, 1)),
                }
            }
            if degree.iter().any(|&(_, d)| d > 2) {
                return true;
            }
            let idx = |x: u32| degree.binary_search_by_key(&x, |&(y, _)| y).unwrap_or(0);
            let mut uf = UnionFind::new(degree.len());
            for &(a, b) in &links {
                uf.union(idx(a), idx(b));
            }
            let r0 = uf.find(0);
            (1..degree.len()).any(|i| uf.find(i) != r0)
        })
        .collect()
}

pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }
    pub fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] as usize != x {
            let p = self.parent[x] as usize;
            self.parent[x] = self.parent[p];
            x = p;
        }
        x
    }
    pub fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb) as u32;
        }
    }
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
fn det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    dot(a, cross(b, c))
}

#[cfg(test)]
mod cavity_tests {
    use super::*;
    use crate::eval::shapes::{cuboid, merged};

    fn flipped(m: &TriMesh) -> TriMesh {
        let mut m = m.clone();
        for t in &mut m.triangles {
            t.swap(1, 2);
        }
        m
    }

    #[test]
    fn a_cavity_shell_facing_into_the_cavity_is_outward() {
        let outer = cuboid([0.0; 3], [4.0; 3]);
        let inner = cuboid([1.0; 3], [2.0; 3]);
        assert!(analyze(&merged(&outer, &flipped(&inner))).oriented);
        // The same inner shell facing out of the cavity is inside-out material.
        assert!(!analyze(&merged(&outer, &inner)).oriented);
        // An island inside the cavity faces out again (depth 2).
        let island = cuboid([1.25; 3], [1.75; 3]);
        let nested = merged(&merged(&outer, &flipped(&inner)), &island);
        assert!(analyze(&nested).oriented);
        assert!(
            !analyze(&merged(
                &merged(&outer, &flipped(&inner)),
                &flipped(&island)
            ))
            .oriented
        );
        // Two disjoint positive shells, and a lone inside-out one.
        let apart = cuboid([5.0; 3], [6.0; 3]);
        assert!(analyze(&merged(&outer, &apart)).oriented);
        assert!(!analyze(&flipped(&outer)).oriented);
    }
}
