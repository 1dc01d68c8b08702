//! Small synthetic closed meshes with known answers (boxes, tori, icospheres), outward oriented.
//! Used by the evaluation tests and benchmarks; handy for anyone who needs a known solid.
use crate::mesh::TriMesh;
use std::collections::HashMap;

/// Axis-aligned box `[lo, hi]`, 8 vertices, 12 triangles.
pub fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> TriMesh {
    let vertices = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { lo[0] } else { hi[0] },
                if i & 2 == 0 { lo[1] } else { hi[1] },
                if i & 4 == 0 { lo[2] } else { hi[2] },
            ]
        })
        .collect();
    // Quads counter-clockwise seen from outside.
    let quads = [
        [0, 2, 3, 1], // z = lo
        [4, 5, 7, 6], // z = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    TriMesh {
        vertices,
        triangles,
    }
}

/// Unit cube `[0,1]³`.
pub fn unit_cube() -> TriMesh {
    cuboid([0.0; 3], [1.0; 3])
}

/// Torus around the z axis: major radius `big`, minor radius `small`, `n` × `m` quads.
pub fn torus(big: f64, small: f64, n: usize, m: usize) -> TriMesh {
    let mut vertices = Vec::with_capacity(n * m);
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        for j in 0..m {
            let b = std::f64::consts::TAU * j as f64 / m as f64;
            let r = big + small * b.cos();
            vertices.push([r * a.cos(), r * a.sin(), small * b.sin()]);
        }
    }
    let id = |i: usize, j: usize| ((i % n) * m + (j % m)) as u32;
    let mut triangles = Vec::with_capacity(2 * n * m);
    for i in 0..n {
        for j in 0..m {
            let (p, q, r, s) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([p, q, r]);
            triangles.push([p, r, s]);
        }
    }
    TriMesh {
        vertices,
        triangles,
    }
}

/// Icosphere: an icosahedron subdivided `levels` times, projected on the sphere (20·4^levels triangles).
pub fn icosphere(center: [f64; 3], radius: f64, levels: u32) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let unit = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / l, p[1] / l, p[2] / l]
    };
    for p in v.iter_mut() {
        *p = unit(*p);
    }
    for _ in 0..levels {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut nf = Vec::with_capacity(f.len() * 4);
        for t in &f {
            let mut m = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                m[k] = *mid.entry(key).or_insert_with(|| {
                    let (pa, pb) = (v[a as usize], v[b as usize]);
                    v.push(unit([pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]]));
                    (v.len() - 1) as u32
                });
            }
            nf.push([t[0], m[0], m[2]]);
            nf.push([t[1], m[1], m[0]]);
            nf.push([t[2], m[2], m[1]]);
            nf.push([m[0], m[1], m[2]]);
        }
        f = nf;
    }
    let vertices = v
        .into_iter()
        .map(|p| {
            [
                center[0] + radius * p[0],
                center[1] + radius * p[1],
                center[2] + radius * p[2],
            ]
        })
        .collect();
    TriMesh {
        vertices,
        triangles: f,
    }
}

/// Translate every vertex by `d`.
pub fn translated(mesh: &TriMesh, d: [f64; 3]) -> TriMesh {
    TriMesh {
        vertices: mesh
            .vertices
            .iter()
            .map(|p| [p[0] + d[0], p[1] + d[1], p[2] + d[2]])
            .collect(),
        triangles: mesh.triangles.clone(),
    }
}

/// Both meshes in one (vertex indices of `b` shifted).
pub fn merged(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let off = a.vertices.len() as u32;
    let mut m = a.clone();
    m.vertices.extend_from_slice(&b.vertices);
    m.triangles.extend(
        b.triangles
            .iter()
            .map(|t| [t[0] + off, t[1] + off, t[2] + off]),
    );
    m
}
