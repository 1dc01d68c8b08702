//! Combinatorial checks of a triangle mesh: edges and their uses, closedness, edge and vertex
//! manifoldness, orientation consistency, components (connected through shared edges), Euler
//! characteristic and genus; plus signed volume and area (floating point).
use crate::mesh::TriMesh;
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
    /// Consistent orientation on every edge and positive volume of every closed component.
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
    let mut all_volumes_positive = true;
    for (c, cr) in comps.iter_mut().enumerate() {
        cr.euler = cr.vertices as i64 - cr.edges as i64 + cr.triangles as i64;
        euler += cr.euler;
        if cr.closed && !comp_inconsistent[c] && !comp_nonmanifold_vertex[c] {
            cr.genus = Some((2 - cr.euler) / 2);
        }
        if cr.closed && cr.volume <= 0.0 {
            all_volumes_positive = false;
        }
    }
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
    let mut start = vec![0u32; n + 1];
    for (ti, t) in mesh.triangles.iter().enumerate() {
        if !repeated[ti] {
            for &x in t {
                start[x as usize + 1] += 1;
            }
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut inc = vec![0u32; start[n] as usize];
    for (ti, t) in mesh.triangles.iter().enumerate() {
        if !repeated[ti] {
            for &x in t {
                inc[fill[x as usize] as usize] = ti as u32;
                fill[x as usize] += 1;
            }
        }
    }
    (0..n)
        .into_par_iter()
        .map(|vi| {
            let fan = &inc[start[vi] as usize..start[vi + 1] as usize];
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
