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

/// The same surface with every triangle reversed (a cavity, when merged into an enclosing mesh).
pub fn inverted(mesh: &TriMesh) -> TriMesh {
    TriMesh {
        vertices: mesh.vertices.clone(),
        triangles: mesh.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect(),
    }
}

/// Axis-aligned box `[lo, hi]` whose faces are `m[k]`-by-`m[k']` grids of quads (the box cut into
/// `m[0]` × `m[1]` × `m[2]` cells), each quad split along the diagonal from its lowest grid corner,
/// outward oriented. Two boxes meeting on a face with the same grid there share its triangles
/// (reversed); with different grids they meet non-conformingly.
pub fn grid_box(lo: [f64; 3], hi: [f64; 3], m: [usize; 3]) -> TriMesh {
    let mut mesh = TriMesh::default();
    let mut ids: HashMap<[usize; 3], u32> = HashMap::new();
    let mut vid = |g: [usize; 3], mesh: &mut TriMesh| -> u32 {
        *ids.entry(g).or_insert_with(|| {
            mesh.vertices.push(std::array::from_fn(|k| {
                if g[k] == m[k] {
                    hi[k]
                } else {
                    lo[k] + (hi[k] - lo[k]) * g[k] as f64 / m[k] as f64
                }
            }));
            (mesh.vertices.len() - 1) as u32
        })
    };
    for axis in 0..3 {
        let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, m[axis]] {
            for i in 0..m[a1] {
                for j in 0..m[a2] {
                    let g = |di: usize, dj: usize| {
                        let mut g = [0; 3];
                        g[axis] = side;
                        g[a1] = i + di;
                        g[a2] = j + dj;
                        g
                    };
                    let q = [g(0, 0), g(1, 0), g(1, 1), g(0, 1)].map(|g| vid(g, &mut mesh));
                    // (a1, a2, axis) is right-handed: counter-clockwise in (a1, a2) faces +axis.
                    if side == m[axis] {
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

/// A prism over the regular `n`-gon of radius `r` about the z axis through `(cx, cy)`, from `z0` to
/// `z1`, outward oriented: `n` side quads (two triangles each) and two caps fanned from their centre.
/// Two such prisms meeting at a cap (the same `n`, `r`, centre) share its triangles, reversed.
pub fn cylinder(center: [f64; 2], r: f64, z0: f64, z1: f64, n: usize) -> TriMesh {
    let ring = |z: f64| -> Vec<[f64; 3]> {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [center[0] + r * a.cos(), center[1] + r * a.sin(), z]
            })
            .collect()
    };
    let mut vertices = ring(z0);
    vertices.extend(ring(z1));
    vertices.push([center[0], center[1], z0]);
    vertices.push([center[0], center[1], z1]);
    let (c0, c1) = ((2 * n) as u32, (2 * n + 1) as u32);
    let mut triangles = Vec::with_capacity(4 * n);
    for i in 0..n {
        let (a, b) = (i as u32, ((i + 1) % n) as u32);
        let (a1, b1) = (a + n as u32, b + n as u32);
        triangles.push([a, b, b1]);
        triangles.push([a, b1, a1]);
        triangles.push([c0, b, a]);
        triangles.push([c1, a1, b1]);
    }
    TriMesh {
        vertices,
        triangles,
    }
}
