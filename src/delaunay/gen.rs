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
