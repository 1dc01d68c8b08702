//! Point sets for tests and benchmarks (deterministic from a seed). The degenerate ones mimic what the
//! engine feeds the kernel: points on a few planes, many cocircular, coordinates rounded as they come.
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type P = [f64; 3];

/// `n` points uniform in the unit cube.
pub fn uniform(n: usize, seed: u64) -> Vec<P> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| [r.gen(), r.gen(), r.gen()]).collect()
}

/// `n` points on `planes` random planes through the unit cube (uniform on each plane's slice of the
/// cube, computed in floating point, so points of one plane are only nearly coplanar).
pub fn on_planes(n: usize, planes: usize, seed: u64) -> Vec<P> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let pl: Vec<(P, P)> = (0..planes.max(1))
        .map(|_| {
            let nrm = loop {
                let v: P = [
                    r.gen_range(-1.0..1.0),
                    r.gen_range(-1.0..1.0),
                    r.gen_range(-1.0..1.0),
                ];
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                if l > 0.1 && l <= 1.0 {
                    break [v[0] / l, v[1] / l, v[2] / l];
                }
            };
            let o: P = [
                r.gen_range(0.3..0.7),
                r.gen_range(0.3..0.7),
                r.gen_range(0.3..0.7),
            ];
            (nrm, o)
        })
        .collect();
    let mut pts = Vec::with_capacity(n);
    while pts.len() < n {
        let (nrm, o) = pl[r.gen_range(0..pl.len())];
        let x: P = [r.gen(), r.gen(), r.gen()];
        let d = (0..3).map(|k| (x[k] - o[k]) * nrm[k]).sum::<f64>();
        let p = [x[0] - d * nrm[0], x[1] - d * nrm[1], x[2] - d * nrm[2]];
        if p.iter().all(|&c| (0.0..=1.0).contains(&c)) {
            pts.push(p);
        }
    }
    pts
}

/// `n` points on the six faces of the unit cube (exactly coplanar per face) plus its corners.
pub fn cube_faces(n: usize, seed: u64) -> Vec<P> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut pts: Vec<P> = (0..8)
        .map(|k| [(k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64])
        .collect();
    for _ in 0..n {
        let f = r.gen_range(0..6);
        let (a, b): (f64, f64) = (r.gen(), r.gen());
        let c = (f % 2) as f64;
        pts.push(match f / 2 {
            0 => [c, a, b],
            1 => [a, c, b],
            _ => [a, b, c],
        });
    }
    pts
}

/// `per` points on each of `rings` circles of radius 1 around the z axis, at z = 0, 1, 2, ...
/// (cocircular within a ring up to rounding, exactly coplanar).
pub fn circles(rings: usize, per: usize) -> Vec<P> {
    let mut pts = Vec::with_capacity(rings * per);
    for z in 0..rings {
        for i in 0..per {
            let a = i as f64 * std::f64::consts::TAU / per as f64;
            pts.push([a.cos(), a.sin(), z as f64]);
        }
    }
    pts
}

/// The k×k×k integer lattice.
pub fn lattice(k: usize) -> Vec<P> {
    let mut pts = Vec::with_capacity(k * k * k);
    for x in 0..k {
        for y in 0..k {
            for z in 0..k {
                pts.push([x as f64, y as f64, z as f64]);
            }
        }
    }
    pts
}

/// `n` points on the faces of a random convex polytope (the hull of `m` random points on the unit
/// sphere): each point is a random convex combination of a random facet's corners, rounded.
/// Returns the points and the polytope's corners (included in the points).
pub fn polytope_faces(n: usize, m: usize, seed: u64) -> Vec<P> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let corners: Vec<P> = (0..m.max(4))
        .map(|_| loop {
            let v: P = [
                r.gen_range(-1.0..1.0),
                r.gen_range(-1.0..1.0),
                r.gen_range(-1.0..1.0),
            ];
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if l > 0.1 && l <= 1.0 {
                break [v[0] / l, v[1] / l, v[2] / l];
            }
        })
        .collect();
    // hull facets by brute force (m is small): triples with all other corners on one side
    let mut facets = Vec::new();
    let m = corners.len();
    for a in 0..m {
        for b in a + 1..m {
            for c in b + 1..m {
                let (mut pos, mut neg) = (false, false);
                for d in 0..m {
                    if d == a || d == b || d == c {
                        continue;
                    }
                    let o = super::pred::orient(corners[a], corners[b], corners[c], corners[d]);
                    pos |= o > 0.0;
                    neg |= o < 0.0;
                }
                if !(pos && neg) {
                    facets.push([a, b, c]);
                }
            }
        }
    }
    let mut pts = corners.clone();
    for _ in 0..n {
        let f = facets[r.gen_range(0..facets.len())];
        let (mut u, mut v): (f64, f64) = (r.gen(), r.gen());
        if u + v > 1.0 {
            u = 1.0 - u;
            v = 1.0 - v;
        }
        let w = 1.0 - u - v;
        let p = |k: usize| w * corners[f[0]][k] + u * corners[f[1]][k] + v * corners[f[2]][k];
        pts.push([p(0), p(1), p(2)]);
    }
    pts
}

/// A tetrahedral cell with four oblique faces for the tagged kernel: on each face (plane id 0..4,
/// an orthonormal frame turned and offset per plane) a dyadic square grid in uv of about
/// `per_face` points strictly inside the face (every grid square exactly cocircular in uv; in 3D
/// `origin + s·u + t·v` in floats, ~1 ulp off the plane), tagged with its plane, uv and a gid; then
/// `interior` untagged random points inside. Returns the points and their tags.
pub fn tagged_tetrahedron(
    per_face: usize,
    interior: usize,
    seed: u64,
) -> (Vec<P>, Vec<super::PointTags>) {
    let v: [P; 4] = [
        [0.113, 0.071, 0.029],
        [1.237, 0.193, 0.311],
        [0.389, 1.163, 0.147],
        [0.571, 0.487, 1.219],
    ];
    let sub = |a: P, b: P| -> P { [a[0] - b[0], a[1] - b[1], a[2] - b[2]] };
    let dot = |a: P, b: P| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: P, b: P| -> P {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: P| -> P { a.map(|c| c / dot(a, a).sqrt()) };
    let mut pts = Vec::new();
    let mut tags = Vec::new();
    for f in 0..4usize {
        let [p0, p1, p2] = [(f + 1) % 4, (f + 2) % 4, (f + 3) % 4].map(|i| v[i]);
        let angle = 0.31 + 0.47 * f as f64;
        let (u0, n) = (unit(sub(p1, p0)), unit(cross(sub(p1, p0), sub(p2, p0))));
        let v0 = cross(n, u0);
        let (c, s) = (angle.cos(), angle.sin());
        let u: P = std::array::from_fn(|k| c * u0[k] + s * v0[k]);
        let w: P = std::array::from_fn(|k| c * v0[k] - s * u0[k]);
        let o: P = std::array::from_fn(|k| p0[k] + 0.0371 * angle * u[k] + 0.0213 / angle * w[k]);
        let uv = |p: P| [dot(sub(p, o), u), dot(sub(p, o), w)];
        let tri = [uv(p0), uv(p1), uv(p2)];
        let area = ((tri[1][0] - tri[0][0]) * (tri[2][1] - tri[0][1])
            - (tri[2][0] - tri[0][0]) * (tri[1][1] - tri[0][1]))
            .abs()
            / 2.0;
        // dyadic step with about per_face grid points in the triangle
        let h = 2f64.powi((0.5 * (area / per_face.max(1) as f64).log2()).round() as i32);
        let edge = |a: [f64; 2], b: [f64; 2], q: [f64; 2]| {
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            (ex * (q[1] - a[1]) - ey * (q[0] - a[0])) / (ex * ex + ey * ey).sqrt()
        };
        let sign = edge(tri[0], tri[1], tri[2]).signum();
        let (lo, hi) = tri
            .iter()
            .fold(([f64::MAX; 2], [f64::MIN; 2]), |(l, h), p| {
                (
                    [l[0].min(p[0]), l[1].min(p[1])],
                    [h[0].max(p[0]), h[1].max(p[1])],
                )
            });
        for i in (lo[0] / h).floor() as i64..=(hi[0] / h).ceil() as i64 {
            for j in (lo[1] / h).floor() as i64..=(hi[1] / h).ceil() as i64 {
                let q = [i as f64 * h, j as f64 * h];
                if (0..3).all(|e| sign * edge(tri[e], tri[(e + 1) % 3], q) > h / 4.0) {
                    pts.push(std::array::from_fn(|k| o[k] + q[0] * u[k] + q[1] * w[k]));
                    let gid =
                        (f as u64) << 40 | ((i + (1 << 19)) as u64) << 20 | (j + (1 << 19)) as u64;
                    tags.push(super::PointTags::new(gid, &[(f as u32, q)]));
                }
            }
        }
    }
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..interior {
        let w: [f64; 4] = std::array::from_fn(|_| 0.05 + r.gen::<f64>());
        let s: f64 = w.iter().sum();
        pts.push(std::array::from_fn(|k| {
            (0..4).map(|i| v[i][k] * w[i]).sum::<f64>() / s
        }));
        tags.push(super::PointTags::none());
    }
    (pts, tags)
}
