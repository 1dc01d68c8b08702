//! Zero-set extraction: marching tetrahedra on the Freudenthal split of every finest cube.
//!
//! Every cube is cut into the six tetrahedra around its main diagonal (corner 0 → corner 7). The split
//! is the same for every cube, so the triangulations of shared cube faces match and the piecewise
//! linear interpolant is continuous; with a strict sign rule (inside ⇔ f > 0) its zero set is a
//! 2-manifold without ambiguous cases. Surface vertices sit on grid edges and are welded by edge key,
//! so a surface edge is shared by exactly two triangles as long as every tetrahedron with a sign change
//! on a face is processed — which the octree's closure step guarantees — and the box boundary is
//! outside (f = −1 there). Triangles are oriented so their normal points from inside to outside.
use super::octree::{corner, is_inside, Field, Grid, IntMap};
use crate::mesh::TriMesh;

/// The six tetrahedra of the Freudenthal split (corner bits x=1, y=2, z=4), all around 0–7.
pub const TETS: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 1, 5, 7],
    [0, 2, 3, 7],
    [0, 2, 6, 7],
    [0, 4, 5, 7],
    [0, 4, 6, 7],
];

/// Keep surface vertices off the grid nodes so no triangle degenerates to a point or a segment.
const T_MIN: f64 = 1e-3;

struct Builder<'a> {
    field: &'a Field,
    mesh: TriMesh,
    edge_vertex: IntMap<(u64, u64), u32>,
}

impl Builder<'_> {
    fn vertex(&mut self, a: [u32; 3], fa: f64, b: [u32; 3], fb: f64) -> u32 {
        let (ka, kb) = (Grid::key(a), Grid::key(b));
        let key = if ka < kb { (ka, kb) } else { (kb, ka) };
        if let Some(&v) = self.edge_vertex.get(&key) {
            return v;
        }
        let pa = self.field.grid.node_position(a);
        let pb = self.field.grid.node_position(b);
        let t = (fa / (fa - fb)).clamp(T_MIN, 1.0 - T_MIN);
        let t = if t.is_finite() { t } else { 0.5 };
        let p = [
            pa[0] + t * (pb[0] - pa[0]),
            pa[1] + t * (pb[1] - pa[1]),
            pa[2] + t * (pb[2] - pa[2]),
        ];
        let id = self.mesh.vertices.len() as u32;
        self.mesh.vertices.push(p);
        self.edge_vertex.insert(key, id);
        id
    }

    /// Add triangle (a,b,c), flipped if needed so its normal points along `out`.
    fn triangle(&mut self, t: [u32; 3], out: [f64; 3]) {
        let p = |i: u32| self.mesh.vertices[i as usize];
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let d = n[0] * out[0] + n[1] * out[1] + n[2] * out[2];
        if d >= 0.0 {
            self.mesh.triangles.push(t);
        } else {
            self.mesh.triangles.push([t[0], t[2], t[1]]);
        }
    }

    fn tet(&mut self, nodes: [[u32; 3]; 4], f: [f64; 4]) {
        let inside: Vec<usize> = (0..4).filter(|&i| is_inside(f[i])).collect();
        let outside: Vec<usize> = (0..4).filter(|&i| !is_inside(f[i])).collect();
        if inside.is_empty() || outside.is_empty() {
            return;
        }
        let centroid = |s: &[usize]| {
            let mut c = [0.0; 3];
            for &i in s {
                let p = self.field.grid.node_position(nodes[i]);
                for k in 0..3 {
                    c[k] += p[k] / s.len() as f64;
                }
            }
            c
        };
        let ci = centroid(&inside);
        let co = centroid(&outside);
        let out = [co[0] - ci[0], co[1] - ci[1], co[2] - ci[2]];
        let mut v = |i: usize, o: usize| self.vertex(nodes[i], f[i], nodes[o], f[o]);
        match inside.len() {
            1 | 3 => {
                let (lone, others) = if inside.len() == 1 {
                    (inside[0], outside.clone())
                } else {
                    (outside[0], inside.clone())
                };
                let t = [v(lone, others[0]), v(lone, others[1]), v(lone, others[2])];
                self.triangle(t, out);
            }
            _ => {
                let (a, b, c, d) = (inside[0], inside[1], outside[0], outside[1]);
                // The quad ac, ad, bd, bc is a cycle around the tetrahedron.
                let q = [v(a, c), v(a, d), v(b, d), v(b, c)];
                self.triangle([q[0], q[1], q[2]], out);
                self.triangle([q[0], q[2], q[3]], out);
            }
        }
    }
}

/// Extract the zero set of the field on its surface cubes as a closed, outward-oriented triangle mesh.
pub fn extract(field: &Field) -> TriMesh {
    let mut b = Builder {
        field,
        mesh: TriMesh::default(),
        edge_vertex: IntMap::default(),
    };
    let mut cubes = field.surface_cubes.clone();
    cubes.sort_unstable_by_key(|&c| (c[2], c[1], c[0]));
    for &i in &cubes {
        let mut nodes = [[0u32; 3]; 8];
        let mut vals = [0.0; 8];
        for c in 0..8 {
            nodes[c] = corner(i, 1, c);
            vals[c] = field.values[&Grid::key(nodes[c])];
        }
        for t in TETS {
            b.tet(
                [nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]],
                [vals[t[0]], vals[t[1]], vals[t[2]], vals[t[3]]],
            );
        }
    }
    b.mesh
}
