//! Independent checks of a Delaunay triangulation, computed from the tetrahedra list only
//! (no use of the kernel's adjacency): orientation, facet pairing, convex hull, volume, empty spheres.
#![allow(dead_code)]
use slice2solid::delaunay::{pred, Delaunay};
use std::collections::HashMap;

pub type P = [f64; 3];

pub struct Summary {
    pub tets: usize,
    pub volume: f64,
    pub hull_volume: f64,
}

/// Every check of the issue; panics with a message on the first failure.
pub fn check_all(pts: &[P], dt: &Delaunay) -> Summary {
    dt.is_valid().unwrap();
    let tets: Vec<[u32; 4]> = dt.tets().map(|t| dt.tet_vertices(t)).collect();
    check_tets(pts, &tets, dt.dimension() == 3)
}

/// Every check of a tetrahedra list `tets` of `pts`, from the list alone, so that any kernel's
/// output (ours, TetGen's, the CLI's file) goes through the same oracle; panics on the first failure.
/// `full_dim`: the points span 3D (then there are tetrahedra and every distinct point is a vertex).
pub fn check_tets(pts: &[P], tets: &[[u32; 4]], full_dim: bool) -> Summary {
    assert!(
        tets.iter().flatten().all(|&v| (v as usize) < pts.len()),
        "a vertex index is out of range"
    );
    positive_orientation(pts, tets);
    let hull = matched_facets(tets);
    assert_eq!(
        full_dim,
        !tets.is_empty(),
        "tets exist iff the points span 3D"
    );
    closed_surface(&hull);
    points_inside_hull(pts, &hull);
    let used = every_point_used(pts, tets, full_dim);
    let (volume, hull_volume) = volumes(pts, tets, &hull, used.first().copied());
    let scale = volume.abs().max(hull_volume.abs()).max(1e-300);
    assert!(
        (volume - hull_volume).abs() <= 1e-12 * scale,
        "volume {volume} != hull volume {hull_volume}"
    );
    empty_spheres(pts, tets);
    Summary {
        tets: tets.len(),
        volume,
        hull_volume,
    }
}

/// The checks of [`check_tets`] that hold for a tagged triangulation too (whose face points are
/// ~1 ulp off their planes, so its hull is convex and its spheres empty only for the ideal points):
/// positive orientation, facet pairing, closed boundary, every point used, volume = hull volume.
/// Returns the volume.
pub fn check_tets_structure(pts: &[P], tets: &[[u32; 4]]) -> f64 {
    positive_orientation(pts, tets);
    let hull = matched_facets(tets);
    closed_surface(&hull);
    let used = every_point_used(pts, tets, true);
    let (volume, hull_volume) = volumes(pts, tets, &hull, used.first().copied());
    assert!(
        (volume - hull_volume).abs() <= 1e-12 * volume.abs().max(1e-300),
        "volume {volume} != hull volume {hull_volume}"
    );
    volume
}

/// Every tetrahedron positively oriented, by the exact orientation predicate.
fn positive_orientation(pts: &[P], tets: &[[u32; 4]]) {
    let p = |v: u32| pts[v as usize];
    for t in tets {
        assert!(
            pred::orient(p(t[0]), p(t[1]), p(t[2]), p(t[3])) > 0.0,
            "tet {t:?} not positively oriented"
        );
    }
}

/// `tri` rotated so that its smallest vertex comes first (same cyclic orientation).
fn rotated(tri: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| tri[k]).unwrap();
    [tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]]
}

/// Facets: each in at most two tetrahedra, which then see it with opposite orientations (they lie
/// on opposite sides). Returns the facets of one tetrahedron only (the boundary), oriented so that
/// the tetrahedron is on their positive side.
fn matched_facets(tets: &[[u32; 4]]) -> Vec<[u32; 3]> {
    let mut facets: HashMap<[u32; 3], Vec<[u32; 3]>> = HashMap::new();
    const F: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];
    for t in tets {
        for f in F {
            let tri = rotated([t[f[0]], t[f[1]], t[f[2]]]);
            let mut key = tri;
            key.sort_unstable();
            facets.entry(key).or_default().push(tri);
        }
    }
    let mut hull = Vec::new();
    for (k, v) in &facets {
        assert!(v.len() <= 2, "facet {k:?} shared by {} tets", v.len());
        if v.len() == 1 {
            hull.push(v[0]);
        } else {
            assert_ne!(v[0], v[1], "facet {k:?}: both tets on the same side");
        }
    }
    hull
}

/// The boundary facets form a closed, consistently oriented surface: every directed edge once, and
/// its reverse once.
fn closed_surface(hull: &[[u32; 3]]) {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for h in hull {
        for k in 0..3 {
            *edges.entry((h[k], h[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(
            n, 1,
            "boundary edge {a}-{b} directed the same way {n} times"
        );
        assert!(edges.contains_key(&(b, a)), "boundary edge {a}-{b} is open");
    }
}

/// Every input point on the inner side of (or on) every boundary facet, exactly: the boundary is
/// convex and holds all points, so it is the convex hull's boundary.
fn points_inside_hull(pts: &[P], hull: &[[u32; 3]]) {
    let p = |v: u32| pts[v as usize];
    for h in hull {
        for (i, q) in pts.iter().enumerate() {
            assert!(
                pred::orient(p(h[0]), p(h[1]), p(h[2]), *q) >= 0.0,
                "hull facet {h:?} has point {i} outside"
            );
        }
    }
}

/// The vertices used, sorted; with `full_dim`, every distinct input point must be one of them
/// (a Delaunay triangulation uses every point; duplicates may be left out).
fn every_point_used(pts: &[P], tets: &[[u32; 4]], full_dim: bool) -> Vec<u32> {
    let mut used: Vec<u32> = tets.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    if full_dim {
        let bits = |q: &P| {
            [
                (q[0] + 0.0).to_bits(),
                (q[1] + 0.0).to_bits(),
                (q[2] + 0.0).to_bits(),
            ]
        };
        let mut distinct: Vec<[u64; 3]> = pts.iter().map(bits).collect();
        distinct.sort_unstable();
        distinct.dedup();
        let mut used_pos: Vec<[u64; 3]> = used.iter().map(|&v| bits(&pts[v as usize])).collect();
        used_pos.sort_unstable();
        used_pos.dedup();
        assert_eq!(used_pos.len(), used.len(), "two vertices at one position");
        assert_eq!(
            distinct.len(),
            used.len(),
            "some distinct point is not a vertex"
        );
    }
    used
}

/// Total volume of the tetrahedra, and the volume enclosed by the boundary facets (cones from a
/// vertex `apex`, divergence theorem).
fn volumes(pts: &[P], tets: &[[u32; 4]], hull: &[[u32; 3]], apex: Option<u32>) -> (f64, f64) {
    let p = |v: u32| pts[v as usize];
    let volume: f64 = tets
        .iter()
        .map(|t| signed_vol(p(t[0]), p(t[1]), p(t[2]), p(t[3])).abs())
        .sum();
    let c = apex.map(p).unwrap_or([0.0; 3]);
    // facet normals point inwards: the cone (h, c) from a point c of the hull is positive
    let hull_volume: f64 = hull
        .iter()
        .map(|h| signed_vol(p(h[0]), p(h[1]), p(h[2]), c))
        .sum();
    (volume, hull_volume)
}

fn signed_vol(a: P, b: P, c: P, d: P) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

/// Exact empty-sphere check of every tetrahedron against every input point. Candidates come from a
/// uniform grid and a generously padded float bounding box of the circumsphere; spheres whose float
/// centre is unreliable (huge or NaN radius) are checked against all points.
pub fn empty_spheres(pts: &[P], tets: &[[u32; 4]]) {
    if tets.is_empty() {
        return;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for q in pts {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let diag = ((0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>()).sqrt();
    let g = ((pts.len() as f64).cbrt().ceil() as usize).clamp(1, 64);
    let cell = |x: f64, k: usize| -> usize {
        if hi[k] > lo[k] {
            (((x - lo[k]) / (hi[k] - lo[k]) * g as f64) as isize).clamp(0, g as isize - 1) as usize
        } else {
            0
        }
    };
    let mut grid: Vec<Vec<u32>> = vec![Vec::new(); g * g * g];
    for (i, q) in pts.iter().enumerate() {
        grid[(cell(q[0], 0) * g + cell(q[1], 1)) * g + cell(q[2], 2)].push(i as u32);
    }
    let p = |v: u32| pts[v as usize];
    for t in tets {
        let (a, b, c, d) = (p(t[0]), p(t[1]), p(t[2]), p(t[3]));
        let sphere = circumsphere(a, b, c, d);
        let test = |i: u32| {
            if t.contains(&i) {
                return;
            }
            // float filter: clearly outside (with a generous relative margin) needs no exact test
            if let Some((ctr, r)) = sphere {
                let q = pts[i as usize];
                let d2 = (0..3).map(|k| (q[k] - ctr[k]).powi(2)).sum::<f64>();
                if r.is_finite() && d2.sqrt() > r * (1.0 + 1e-6) + diag * 1e-9 {
                    return;
                }
            }
            assert!(
                pred::insphere(a, b, c, d, pts[i as usize]) <= 0.0,
                "point {i} strictly inside the circumsphere of {t:?}"
            );
        };
        match sphere {
            Some((ctr, r)) if r.is_finite() && r < diag => {
                let pad = r * 1e-6 + diag * 1e-9;
                let r0: Vec<usize> = (0..3).map(|k| cell(ctr[k] - r - pad, k)).collect();
                let r1: Vec<usize> = (0..3).map(|k| cell(ctr[k] + r + pad, k)).collect();
                for x in r0[0]..=r1[0] {
                    for y in r0[1]..=r1[1] {
                        for z in r0[2]..=r1[2] {
                            for &i in &grid[(x * g + y) * g + z] {
                                test(i);
                            }
                        }
                    }
                }
            }
            _ => (0..pts.len() as u32).for_each(test),
        }
    }
}

fn circumsphere(a: P, b: P, c: P, d: P) -> Option<(P, f64)> {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    let cross = |x: P, y: P| {
        [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ]
    };
    let dot = |x: P, y: P| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let vw = cross(v, w);
    let wu = cross(w, u);
    let uv = cross(u, v);
    let det = 2.0 * dot(u, vw);
    // flat tetrahedra: the float centre is unreliable, let the caller test every point exactly
    if det.abs() <= 1e-6 * (dot(u, u) * dot(v, v) * dot(w, w)).sqrt() {
        return None;
    }
    let (nu, nv, nw) = (dot(u, u), dot(v, v), dot(w, w));
    let o = [
        (nu * vw[0] + nv * wu[0] + nw * uv[0]) / det,
        (nu * vw[1] + nv * wu[1] + nw * uv[1]) / det,
        (nu * vw[2] + nv * wu[2] + nw * uv[2]) / det,
    ];
    let r = dot(o, o).sqrt();
    Some(([a[0] + o[0], a[1] + o[1], a[2] + o[2]], r))
}
