//! The tagged kernel (`Delaunay::try_new_tagged`) on cells of an arrangement of oblique planes,
//! whose face points are ~1 ulp off their planes in floats.
//!
//! The arrangement: a shared plane π3 through the triangle ABC, three side planes through D and the
//! edges AB, BC, CA, and a bottom plane π4 parallel to π3 through A' = 2A - D, …. Cell 1 is the
//! tetrahedron ABCD, cell 2 the frustum ABC A'B'C' on the other side of π3. Every plane has an
//! orthonormal frame (uv is a similarity of the plane, as the plane rule requires: circles in uv are
//! the plane's circles). Face points are dyadic square grids in uv (every grid square exactly
//! cocircular in uv) strictly inside the face, computed in 3D as `origin + s·u + t·v` in floats, as
//! the engine computes `plane.to_3d(uv)`; the shared face also holds a 12-gon of exactly cocircular
//! points ((±5,0), (±3,±4), … around a grid point). Corners carry three tags, edge points two (uv by
//! projection onto each plane's frame, in floats, as pool vertices would), interior points none.
//! A point generated once has one gid and identical coordinates and tags in both cells.
//!
//! `shared_oblique_face_is_identical_tagged_and_differs_untagged` is the point of the exercise: the
//! two cells triangulate the shared face identically (as gid triangles) with tags, while the untagged
//! kernel on the same points gives different face triangulations (grounded faces of non-flat tets,
//! the engine's notion today) and flat tetrahedra (four vertices on one plane); the test asserts both.
//!
//! Known limitation: ideal points that are exactly cospherical across *different* planes (e.g.
//! grids on orthogonal faces of a box: the corners of a lattice cell are on one sphere) can make
//! the float decision of a mixed 5-tuple (rounding noise) disagree with the plane rule's symbolic
//! one; the cavity is then not star-shaped and the build is refused
//! (`exact_cosphericity_across_planes_is_valid_or_an_error`). The refusals once seen on the
//! engine's axis grids were not this but a star test against a point outside the hull
//! (`hull_face_of_points_from_several_planes_on_one_oblique_plane_is_tagged`). See
//! `src/delaunay/tags.rs`.
mod delaunay_check;
use rand::{Rng, SeedableRng};
use slice2solid::delaunay::{pred, Delaunay, PointTags};
use std::collections::{BTreeMap, BTreeSet};

type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: P) -> P {
    let l = dot(a, a).sqrt();
    a.map(|c| c / l)
}

/// A plane with an orthonormal frame.
#[derive(Clone, Copy)]
struct Plane {
    o: P,
    u: P,
    v: P,
}

impl Plane {
    /// The plane through the three points, its frame turned by `angle` about `p0` (so that grids on
    /// two planes through one line are not mirror images, which would make them cospherical: see
    /// the limitation above).
    fn through(p0: P, p1: P, p2: P, angle: f64) -> Plane {
        let u = unit(sub(p1, p0));
        let n = unit(cross(sub(p1, p0), sub(p2, p0)));
        let v = cross(n, u);
        let (c, s) = (angle.cos(), angle.sin());
        // origin off p0 too (grid rays from a common corner would be concyclic across planes)
        let (du, dv) = (0.0371 * angle, 0.0213 / angle);
        Plane {
            o: std::array::from_fn(|k| p0[k] + du * u[k] + dv * v[k]),
            u: std::array::from_fn(|k| c * u[k] + s * v[k]),
            v: std::array::from_fn(|k| c * v[k] - s * u[k]),
        }
    }
    fn to_3d(self, uv: [f64; 2]) -> P {
        std::array::from_fn(|k| self.o[k] + uv[0] * self.u[k] + uv[1] * self.v[k])
    }
    fn uv(self, p: P) -> [f64; 2] {
        let d = sub(p, self.o);
        [dot(d, self.u), dot(d, self.v)]
    }
}

/// The arrangement's planes (ids 0..5), corners and faces, and the points generated on them.
struct World {
    planes: Vec<Plane>,
    /// A, B, C, D, A', B', C' with the planes through each.
    corners: Vec<(P, Vec<u32>)>,
    /// Points by position bits: (point, tags); gids in generation order.
    points: BTreeMap<[u64; 3], (P, PointTags)>,
    next_gid: u64,
}

const A: P = [0.113, 0.071, 0.029];
const B: P = [1.237, 0.193, 0.311];
const C: P = [0.389, 1.163, 0.147];
const D: P = [0.571, 0.487, 1.219];

impl World {
    /// Planes: 0 = ABD, 1 = BCD, 2 = CAD, 3 = ABC (shared), 4 = A'B'C'.
    fn new() -> World {
        let far = |x: P| std::array::from_fn(|k| 2.0 * x[k] - D[k]);
        let (a2, b2, c2) = (far(A), far(B), far(C));
        let planes = vec![
            Plane::through(A, B, D, 0.31),
            Plane::through(B, C, D, 0.77),
            Plane::through(C, A, D, 1.13),
            Plane::through(A, B, C, 0.53),
            Plane::through(a2, b2, c2, 0.97),
        ];
        let corners = vec![
            (A, vec![0, 2, 3]),
            (B, vec![0, 1, 3]),
            (C, vec![1, 2, 3]),
            (D, vec![0, 1, 2]),
            (a2, vec![0, 2, 4]),
            (b2, vec![0, 1, 4]),
            (c2, vec![1, 2, 4]),
        ];
        World {
            planes,
            corners,
            points: BTreeMap::new(),
            next_gid: 1000,
        }
    }

    /// The point at `p` on `planes` (uv by projection, or `uv` given for its first plane).
    fn add(&mut self, p: P, planes: &[u32], uv0: Option<[f64; 2]>) -> usize {
        let key = p.map(f64::to_bits);
        if !self.points.contains_key(&key) {
            let tags: Vec<(u32, [f64; 2])> = planes
                .iter()
                .enumerate()
                .map(|(k, &pl)| match (k, uv0) {
                    (0, Some(uv)) => (pl, uv),
                    _ => (pl, self.planes[pl as usize].uv(p)),
                })
                .collect();
            let t = PointTags::new(self.next_gid, &tags);
            self.next_gid += 1;
            self.points.insert(key, (p, t));
        }
        self.points.keys().position(|k| *k == key).unwrap()
    }

    /// The points of face `plane` with corners `cs`: corners, `k/4` points on its edges, a grid of
    /// step `h` in uv strictly inside, and a 12-gon around the grid point nearest the centre when
    /// `gon`. Returns their position keys.
    fn face(&mut self, plane: u32, cs: &[usize], h: f64, gon: bool) -> Vec<[u64; 3]> {
        let mut keys = Vec::new();
        let n = cs.len();
        for i in 0..n {
            // interpolated from the corner of smaller index: one float point per edge point
            let (i0, i1) = (cs[i].min(cs[(i + 1) % n]), cs[i].max(cs[(i + 1) % n]));
            let (p, q) = (self.corners[i0].clone(), self.corners[i1].clone());
            let c = self.corners[cs[i]].clone();
            self.add(c.0, &c.1, None);
            keys.push(c.0.map(f64::to_bits));
            let both: Vec<u32> = p.1.iter().copied().filter(|x| q.1.contains(x)).collect();
            for k in 1..4 {
                let t = k as f64 / 4.0;
                let x: P = std::array::from_fn(|c| p.0[c] + t * (q.0[c] - p.0[c]));
                self.add(x, &both, None);
                keys.push(x.map(f64::to_bits));
            }
        }
        let pl = self.planes[plane as usize];
        let poly: Vec<[f64; 2]> = cs.iter().map(|&c| pl.uv(self.corners[c].0)).collect();
        // strictly inside: at least h/4 from every edge (by the float edge equations)
        let inside = |q: [f64; 2]| {
            (0..n).all(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
                let l = (ex * ex + ey * ey).sqrt();
                let s = (ex * (q[1] - a[1]) - ey * (q[0] - a[0])) / l;
                let ccw = {
                    let c = poly[(i + 2) % n];
                    ex * (c[1] - a[1]) - ey * (c[0] - a[0]) > 0.0
                };
                if ccw {
                    s > h / 4.0
                } else {
                    -s > h / 4.0
                }
            })
        };
        let (lo, hi) = poly
            .iter()
            .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            });
        let g = |x: f64| (x / h).floor() as i64;
        let mut grid = Vec::new();
        for i in g(lo[0])..=g(hi[0]) + 1 {
            for j in g(lo[1])..=g(hi[1]) + 1 {
                grid.push([i as f64 * h, j as f64 * h]);
            }
        }
        if gon {
            let m: [f64; 2] = {
                let c = poly
                    .iter()
                    .fold([0.0; 2], |s, p| [s[0] + p[0], s[1] + p[1]]);
                [
                    (c[0] / n as f64 / h).round() * h,
                    (c[1] / n as f64 / h).round() * h,
                ]
            };
            for (x, y) in [(5.0, 0.0), (3.0, 4.0), (4.0, 3.0), (0.0, 5.0)] {
                for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                    grid.push([m[0] + sx * x * h / 4.0, m[1] + sy * y * h / 4.0]);
                }
            }
        }
        for uv in grid {
            if inside(uv) {
                let x = pl.to_3d(uv);
                self.add(x, &[plane], Some(uv));
                keys.push(x.map(f64::to_bits));
            }
        }
        keys
    }
}

/// Points (3D, tags) of cell 1 (`upper`: the tetrahedron ABCD) or cell 2 (the frustum), grid step
/// `h`, with `interior` random untagged points.
fn cells(h: f64, interior: usize, seed: u64) -> [(Vec<P>, Vec<PointTags>); 2] {
    let mut w = World::new();
    let shared = w.face(3, &[0, 1, 2], h, true);
    let mut up = shared.clone();
    up.extend(w.face(0, &[0, 1, 3], h, false));
    up.extend(w.face(1, &[1, 2, 3], h, false));
    up.extend(w.face(2, &[2, 0, 3], h, false));
    let mut down = shared;
    down.extend(w.face(0, &[0, 1, 5, 4], h, false));
    down.extend(w.face(1, &[1, 2, 6, 5], h, false));
    down.extend(w.face(2, &[2, 0, 4, 6], h, false));
    down.extend(w.face(4, &[4, 5, 6], h, false));
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut out = [up, down].map(|keys| {
        let keys: BTreeSet<[u64; 3]> = keys.into_iter().collect();
        let (p, t): (Vec<P>, Vec<PointTags>) = keys.iter().map(|k| w.points[k].clone()).unzip();
        (p, t)
    });
    for (c, (p, t)) in out.iter_mut().enumerate() {
        let cs: &[usize] = if c == 0 {
            &[0, 1, 2, 3]
        } else {
            &[0, 1, 2, 4, 5, 6]
        };
        for _ in 0..interior {
            let wts: Vec<f64> = cs.iter().map(|_| 0.05 + r.gen::<f64>()).collect();
            let sum: f64 = wts.iter().sum();
            let x: P = std::array::from_fn(|k| {
                cs.iter()
                    .zip(&wts)
                    .map(|(&i, wt)| w.corners[i].0[k] * wt)
                    .sum::<f64>()
                    / sum
            });
            p.push(x);
            t.push(PointTags::none());
        }
    }
    out
}

/// The tagged triangulation's triangles on `plane` as sorted gid triples.
fn tagged_face(dt: &Delaunay, tags: &[PointTags], plane: u32) -> BTreeSet<[u64; 3]> {
    dt.plane_hull_triangles(plane)
        .into_iter()
        .map(|f| {
            let mut g = f.map(|v| tags[v as usize].gid);
            g.sort_unstable();
            g
        })
        .collect()
}

/// The untagged triangulation's grounded faces of non-flat tets on `plane` (sorted gid triples),
/// and the number of flat tets (four vertices on `plane`).
fn untagged_face(dt: &Delaunay, tags: &[PointTags], plane: u32) -> (BTreeSet<[u64; 3]>, usize) {
    let mut out = BTreeSet::new();
    let mut flat = 0;
    for t in dt.tets() {
        let v = dt.tet_vertices(t);
        let on: Vec<u32> = v
            .into_iter()
            .filter(|&w| tags[w as usize].on(plane))
            .collect();
        match on.len() {
            4 => flat += 1,
            3 => {
                let mut g = [0, 1, 2].map(|i| tags[on[i] as usize].gid);
                g.sort_unstable();
                out.insert(g);
            }
            _ => {}
        }
    }
    (out, flat)
}

/// Tetrahedra with four vertices on one plane (by tags).
fn flat_tets(dt: &Delaunay, tags: &[PointTags]) -> usize {
    dt.tets()
        .filter(|&t| {
            let v = dt.tet_vertices(t).map(|w| &tags[w as usize]);
            v[0].planes
                .iter()
                .any(|&(pl, _)| v[1..].iter().all(|x| x.on(pl)))
        })
        .count()
}

/// Every check that holds for a tagged triangulation: `is_valid` (positive tets, tagged local
/// Delaunay, every face plane = its reference 2D Delaunay), no flat tet, and the independent
/// structural checks (orientation, facet pairing, closed hull, all points used, volume = hull's).
fn check_tagged(pts: &[P], tags: &[PointTags], dt: &Delaunay) -> f64 {
    dt.is_valid().unwrap();
    assert_eq!(flat_tets(dt, tags), 0);
    let tl: Vec<[u32; 4]> = dt.tets().map(|t| dt.tet_vertices(t)).collect();
    delaunay_check::check_tets_structure(pts, &tl)
}

#[test]
fn oblique_cells_are_valid_with_planes_delaunay() {
    for (h, interior, seed) in [(0.25, 0, 1), (0.125, 30, 2), (0.09375, 40, 3)] {
        let [(p1, t1), (p2, t2)] = cells(h, interior, seed);
        for (pts, tags) in [(&p1, &t1), (&p2, &t2)] {
            let dt = Delaunay::try_new_tagged(pts, tags).unwrap();
            check_tagged(pts, tags, &dt);
        }
        let v1 = check_tagged(&p1, &t1, &Delaunay::try_new_tagged(&p1, &t1).unwrap());
        let want = pred::orient(A, B, C, D) / 6.0;
        assert!((v1 - want).abs() < 1e-12 * want, "volume {v1} != {want}");
    }
}

#[test]
fn shared_oblique_face_is_identical_tagged_and_differs_untagged() {
    let mut differ_total = 0;
    for (h, interior, seed) in [(0.125, 20, 5), (0.0625, 60, 6)] {
        let [(pa, ta), (pb, tb)] = cells(h, interior, seed);
        let da = Delaunay::try_new_tagged(&pa, &ta).unwrap();
        let db = Delaunay::try_new_tagged(&pb, &tb).unwrap();
        check_tagged(&pa, &ta, &da);
        check_tagged(&pb, &tb, &db);
        let (fa, fb) = (tagged_face(&da, &ta, 3), tagged_face(&db, &tb, 3));
        assert!(fa.len() > 20);
        assert_eq!(fa, fb, "the two cells triangulate the shared face alike");
        // untagged, same points: the two sides disagree, and there are flat tets
        let (ua, flat_a) = untagged_face(&Delaunay::new(&pa), &ta, 3);
        let (ub, flat_b) = untagged_face(&Delaunay::new(&pb), &tb, 3);
        let differ = ua.symmetric_difference(&ub).count();
        differ_total += differ;
        assert!(flat_a + flat_b > 0);
        eprintln!(
            "h = {h}: tagged face {} triangles identical; untagged {} vs {} triangles, {differ} differ, {} flat tets",
            fa.len(),
            ua.len(),
            ub.len(),
            flat_a + flat_b
        );
    }
    assert!(
        differ_total > 0,
        "the untagged cells agree on the shared face"
    );
}

#[test]
fn tagged_without_tags_is_the_untagged_triangulation() {
    let [(pts, _), _] = cells(0.125, 40, 9);
    let none = vec![PointTags::none(); pts.len()];
    let a = Delaunay::new(&pts);
    let b = Delaunay::try_new_tagged(&pts, &none).unwrap();
    b.is_valid().unwrap();
    let tets = |dt: &Delaunay| {
        let mut t: Vec<[u32; 4]> = dt
            .tets()
            .map(|t| {
                let mut v = dt.tet_vertices(t);
                v.sort_unstable();
                v
            })
            .collect();
        t.sort_unstable();
        t
    };
    assert_eq!(tets(&a), tets(&b));
}

#[test]
fn incremental_tagged_insertion_matches_the_bulk_build() {
    // half the points in bulk, then the rest one by one (as conformity splitting would), in the
    // generation order (face by face: long runs of points on one plane)
    for (pts, tags) in cells(0.125, 30, 11) {
        let split = pts.len() / 3;
        let mut dt = Delaunay::try_new_tagged(&pts[..split], &tags[..split]).unwrap();
        for k in split..pts.len() {
            assert_eq!(dt.insert_tagged(pts[k], &tags[k]), k as u32);
        }
        check_tagged(&pts, &tags, &dt);
        let bulk = Delaunay::try_new_tagged(&pts, &tags).unwrap();
        for pl in 0..5 {
            assert_eq!(
                tagged_face(&dt, &tags, pl),
                tagged_face(&bulk, &tags, pl),
                "plane {pl}"
            );
        }
    }
}

#[test]
fn bad_tags_are_errors() {
    let pts = [[0.0; 3], [1.0, 0.0, 0.0]];
    assert!(Delaunay::try_new_tagged(&pts, &[PointTags::none()]).is_err());
    // more planes than the masks of the rules have bits
    let planes: Vec<(u32, [f64; 2])> = (0..=slice2solid::delaunay::MAX_PLANES as u32)
        .map(|k| (k, [0.0; 2]))
        .collect();
    let many = PointTags::new(0, &planes);
    assert!(Delaunay::try_new_tagged(&pts, &[many, PointTags::none()]).is_err());
    let rep = PointTags::new(0, &[(1, [0.0; 2]), (1, [0.5; 2])]);
    assert!(Delaunay::try_new_tagged(&pts, &[rep, PointTags::none()]).is_err());
}

#[test]
fn generated_tetrahedron_cell_is_valid() {
    // the bench's point set, smaller (the reference 2D check is brute force)
    let (pts, tags) = slice2solid::delaunay::gen::tagged_tetrahedron(120, 300, 4);
    assert!(pts.len() > 600);
    let dt = Delaunay::try_new_tagged(&pts, &tags).unwrap();
    check_tagged(&pts, &tags, &dt);
    for pl in 0..4 {
        assert!(dt.plane_hull_triangles(pl).len() > 100, "plane {pl}");
    }
    assert!(flat_tets(&Delaunay::new(&pts), &tags) > 0);
}

/// The known limit of the tag rules (exact cosphericity across planes, e.g. lattice cells on
/// orthogonal faces of a box) never gives a silently wrong triangulation: the build is either valid
/// (tagged `is_valid`) or an error from `try_new_tagged`. Faces x = 0, y = 0, z = 0 of the unit cube,
/// each a 5 × 5 grid in its axis plane's own coordinates, and the far corner.
#[test]
fn exact_cosphericity_across_planes_is_valid_or_an_error() {
    let mut pts = Vec::new();
    let mut tags = Vec::new();
    let mut gid = 0u64;
    for axis in 0..3u32 {
        for i in 0..5 {
            for j in 0..5 {
                let (s, t) = (i as f64 / 4.0, j as f64 / 4.0);
                let mut p = [0.0; 3];
                let (a, b) = ((axis as usize + 1) % 3, (axis as usize + 2) % 3);
                p[a] = s;
                p[b] = t;
                if pts.contains(&p) {
                    continue;
                }
                // every axis plane the point lies on, with that plane's (u, v) = the next two axes
                let planes: Vec<(u32, [f64; 2])> = (0..3u32)
                    .filter(|&k| p[k as usize] == 0.0)
                    .map(|k| {
                        let (u, v) = (((k + 1) % 3) as usize, ((k + 2) % 3) as usize);
                        (k, [p[u], p[v]])
                    })
                    .collect();
                pts.push(p);
                tags.push(PointTags::new(gid, &planes));
                gid += 1;
            }
        }
    }
    pts.push([1.0, 1.0, 1.0]);
    tags.push(PointTags::new(gid, &[]));
    match Delaunay::try_new_tagged(&pts, &tags) {
        Ok(dt) => dt.is_valid().expect("an Ok tagged build is valid"),
        Err(e) => eprintln!("refused, as it may be: {e}"),
    }
}

/// A flat triangle of a sliced mesh, cut by three axis planes: the contour points of the faces
/// x = 0, y = 0 and z = 0 of the corner region {x, y, z ≥ 0, x + y + z ≤ 0.9} lie on the oblique
/// plane x + y + z = 0.9 up to rounding, so that hull face of the cell's points is tiled by tetrahedra
/// flat up to rounding. The rounded centroid of such a tetrahedron can fall outside it, and the
/// kernel's star test of a new hull facet (against a point inside the hull) then refused valid
/// insertions: the cell fell back to the untagged kernel (balloondog cut by 100 axis planes: 29
/// cells). The build must succeed and be valid.
#[test]
fn hull_face_of_points_from_several_planes_on_one_oblique_plane_is_tagged() {
    let mut pts: Vec<P> = Vec::new();
    let mut tags = Vec::new();
    let tag = |p: P, gid: u64| {
        let planes: Vec<(u32, [f64; 2])> = (0..3u32)
            .filter(|&k| p[k as usize] == 0.0)
            .map(|k| {
                let (u, v) = (((k + 1) % 3) as usize, ((k + 2) % 3) as usize);
                (k, [p[u], p[v]])
            })
            .collect();
        PointTags::new(gid, &planes)
    };
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let n = 40;
    for axis in 0..3usize {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        for i in 0..=n {
            // the contour on the oblique plane (irregular spacing, as a mesh's crossings are),
            // the face's edge on the next axis plane, and samples inside the face's triangle
            let s = (i as f64 + 0.5 * rng.gen::<f64>()) / (n as f64 + 1.0) * 0.9;
            let mut on_mesh = [0.0; 3];
            on_mesh[a] = s;
            on_mesh[b] = 0.9 - s;
            let mut on_edge = [0.0; 3];
            on_edge[a] = s;
            let mut inside = [0.0; 3];
            inside[a] = s * rng.gen::<f64>();
            inside[b] = (0.9 - s) * rng.gen::<f64>();
            for p in [on_mesh, on_edge, inside] {
                if !pts.contains(&p) {
                    tags.push(tag(p, pts.len() as u64));
                    pts.push(p);
                }
            }
        }
    }
    let dt = Delaunay::try_new_tagged(&pts, &tags).expect("a valid cavity was refused");
    dt.is_valid().unwrap();
    assert_eq!(flat_tets(&dt, &tags), 0);
}

/// A cell of a generated odd input (`slice::odd` seed 3, before common-line trims broke rows
/// across regions): four planes' points with their tags and the cells' plane apexes, dumped as the
/// engine passed them. Inserting vertex 12 made a cavity of float decisions alone (no tag rule
/// decided any of it) that was star-shaped by its finite facets but not a ball; the kernel checked
/// the ball only after a tag rule, glued it, and the next insertion read a broken neighbour: a
/// segfault. A tagged triangulation is not Delaunay by the float predicates (the rules decided
/// earlier cavities), so a float cavity need not be a ball either: it is checked on every tagged
/// insertion now. The build must not crash, and be valid or refused.
#[test]
fn a_float_cavity_that_is_no_ball_in_a_tagged_triangulation_is_refused() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/tagged_cell_cavity_not_a_ball.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let num = |v: &serde_json::Value| v.as_f64().unwrap();
    let mut pts: Vec<P> = Vec::new();
    let mut tags = Vec::new();
    for x in doc["points"].as_array().unwrap() {
        let p = x["p"].as_array().unwrap();
        pts.push([num(&p[0]), num(&p[1]), num(&p[2])]);
        let planes: Vec<(u32, [f64; 2])> = x["planes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| (t[0].as_u64().unwrap() as u32, [num(&t[1]), num(&t[2])]))
            .collect();
        let mut t = PointTags::new(x["gid"].as_u64().unwrap(), &planes);
        if let Some(s) = x["segment"].as_array() {
            t.segment = Some([s[0].as_u64().unwrap(), s[1].as_u64().unwrap()]);
        }
        tags.push(t);
    }
    let apexes = slice2solid::delaunay::PlaneApexes::new(
        doc["apexes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| {
                let p = a[1].as_array().unwrap();
                (
                    a[0].as_u64().unwrap() as u32,
                    [num(&p[0]), num(&p[1]), num(&p[2])],
                )
            })
            .collect(),
    );
    assert_eq!((pts.len(), apexes.get(8).is_some()), (131, true));
    match Delaunay::try_new_tagged_with(&pts, &tags, &apexes) {
        Ok(dt) => dt.is_valid().expect("an Ok tagged build is valid"),
        Err(e) => assert!(matches!(e, slice2solid::Error::Input { .. }), "{e}"),
    }
}
