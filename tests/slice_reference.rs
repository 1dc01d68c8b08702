//! Slicing the reference meshes: every section's area against an independent computation that builds no
//! contours, plus the section conventions (outer CCW, holes CW and inside their outer contour).
mod common;
use common::shared_dir;
use slice2solid::geom::predicates::orient2d;
use slice2solid::io::mesh::read_trimesh;
use slice2solid::sections::{cross, dot, sub};
use slice2solid::slice::{make_planes, slice_mesh, SliceMode};
use slice2solid::{Plane, Sections, TriMesh};
use std::path::PathBuf;

fn reference_meshes() -> Vec<(String, TriMesh)> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(shared_dir().join("data/reference"))
        .expect("reference meshes")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "stl"))
        .collect();
    v.sort();
    assert!(!v.is_empty());
    v.into_iter()
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            (name, read_trimesh(&p).unwrap())
        })
        .collect()
}

/// Section area by Stokes: over the triangles crossing the plane, the cut segment (points by direct
/// parametric interpolation in 3D, oriented along n × N of the triangle's normal N) contributes
/// ½ n·((p0 − o) × (p1 − o)). For a closed outward-oriented mesh the sum is the section's area.
fn independent_area(mesh: &TriMesh, plane: &Plane) -> f64 {
    let n = plane.normal;
    let o = plane.origin;
    let mut area = 0.0;
    for t in &mesh.triangles {
        let p = t.map(|i| mesh.vertices[i as usize]);
        let d = p.map(|x| dot(n, x) + plane.offset);
        let mut cut = Vec::with_capacity(2);
        for k in 0..3 {
            let (a, b) = (k, (k + 1) % 3);
            if (d[a] >= 0.0) != (d[b] >= 0.0) {
                let s = d[a] / (d[a] - d[b]);
                cut.push(std::array::from_fn::<f64, 3, _>(|c| {
                    p[a][c] + s * (p[b][c] - p[a][c])
                }));
            }
        }
        if cut.len() != 2 {
            continue;
        }
        let normal = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        let along = cross(n, normal);
        let (mut p0, mut p1) = (cut[0], cut[1]);
        if dot(sub(p1, p0), along) < 0.0 {
            std::mem::swap(&mut p0, &mut p1);
        }
        area += 0.5 * dot(n, cross(sub(p0, o), sub(p1, o)));
    }
    area
}

fn diag2(mesh: &TriMesh) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &mesh.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum()
}

/// Crossing-number test in floating point (enough for checking nesting away from the boundary).
fn inside(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut c = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            c = !c;
        }
    }
    c
}

/// Do closed segments ab and cd share a point? Exact.
fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    let within = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    (o1 == 0.0 && within(a, b, c))
        || (o2 == 0.0 && within(a, b, d))
        || (o3 == 0.0 && within(c, d, a))
        || (o4 == 0.0 && within(c, d, b))
}

/// No two contour edges of a section meet, except consecutive edges of one contour at their vertex.
fn check_simple(name: &str, i: usize, sec: &slice2solid::Section) {
    // (a, b, contour, edge index, contour length)
    type Seg = ([f64; 2], [f64; 2], usize, usize, usize);
    let mut segs: Vec<Seg> = Vec::new();
    let contours = sec
        .regions
        .iter()
        .flat_map(|r| std::iter::once(&r.outer).chain(&r.holes));
    for (ci, c) in contours.enumerate() {
        let n = c.points2.len();
        for k in 0..n {
            segs.push((c.points2[k], c.points2[(k + 1) % n], ci, k, n));
        }
    }
    segs.sort_by(|x, y| x.0[0].min(x.1[0]).total_cmp(&y.0[0].min(y.1[0])));
    for (si, s) in segs.iter().enumerate() {
        let xmax = s.0[0].max(s.1[0]);
        for t in &segs[si + 1..] {
            if t.0[0].min(t.1[0]) > xmax {
                break;
            }
            if s.2 == t.2 && ((s.3 + 1) % s.4 == t.3 || (t.3 + 1) % t.4 == s.3) {
                continue; // consecutive edges share their vertex
            }
            assert!(
                !segments_meet(s.0, s.1, t.0, t.1),
                "{name} section {i}: contour edges meet at {:?}-{:?} / {:?}-{:?}",
                s.0,
                s.1,
                t.0,
                t.1
            );
        }
    }
}

fn check_conventions(name: &str, s: &Sections) {
    // The validator had nothing to repair: orientation and vertices are right as sliced. (Where
    // a flat face of the mesh is cut, its crossings are on one line up to rounding, and the
    // validator drops the middle ones: exact crossings of the mesh, not a slicer error.)
    let repairs: Vec<&String> = (s.warnings.iter())
        .filter(|w| !w.contains("on the segment between their neighbours within rounding"))
        .collect();
    assert!(repairs.is_empty(), "{name}: {repairs:?}");
    for (i, sec) in s.sections.iter().enumerate() {
        assert!(!sec.regions.is_empty());
        check_simple(name, i, sec);
        for r in &sec.regions {
            assert_eq!(r.label, 1);
            assert!(
                r.outer.signed_area() > 0.0,
                "{name} section {i}: outer contour not CCW"
            );
            assert!(r.outer.points2.len() >= 3);
            for h in &r.holes {
                assert!(h.signed_area() < 0.0, "{name} section {i}: hole not CW");
                // Most hole vertices lie strictly inside the outer contour (all of them, unless touching).
                let inn = h
                    .points2
                    .iter()
                    .filter(|&&p| inside(p, &r.outer.points2))
                    .count();
                assert!(
                    2 * inn > h.points2.len(),
                    "{name} section {i}: hole outside its parent"
                );
            }
            for c in std::iter::once(&r.outer).chain(&r.holes) {
                let n = c.points2.len();
                for k in 0..n {
                    assert_ne!(
                        c.points2[k],
                        c.points2[(k + 1) % n],
                        "{name}: repeated vertex"
                    );
                }
                for (q2, q3) in c.points2.iter().zip(&c.points3) {
                    assert_eq!(sec.plane.to_3d(*q2), *q3);
                }
            }
        }
    }
}

#[test]
fn section_areas_match_the_independent_computation() {
    let mut worst: f64 = 0.0;
    for (name, mesh) in reference_meshes() {
        let scale = diag2(&mesh);
        for (mode, seed) in [
            (SliceMode::Random, 1),
            (SliceMode::Random, 7),
            (SliceMode::Parallel, 0),
            (SliceMode::Axes, 0),
            (SliceMode::Fan, 5),
            (SliceMode::Sweep, 5),
            (SliceMode::Tilt, 0),
        ] {
            let planes = make_planes(&mesh, 9, seed, mode);
            let s = slice_mesh(&mesh, &planes).unwrap();
            check_conventions(&name, &s);
            let mut kept = s.sections.iter().peekable();
            let (mut holes, mut regions) = (0, 0);
            for plane in &planes {
                let expect = independent_area(&mesh, plane);
                match kept.peek() {
                    Some(sec) if sec.plane == *plane => {
                        let got = sec.area();
                        let rel = (got - expect).abs() / expect.abs().max(1e-6 * scale);
                        worst = worst.max(rel);
                        assert!(
                            rel < 1e-9,
                            "{name} {mode:?} seed {seed}: area {got} vs independent {expect} (rel {rel:e})"
                        );
                        regions += sec.regions.len();
                        holes += sec.regions.iter().map(|r| r.holes.len()).sum::<usize>();
                        kept.next();
                    }
                    // A skipped plane has an empty section.
                    _ => assert!(
                        expect.abs() <= 1e-9 * scale,
                        "{name}: skipped a section of area {expect}"
                    ),
                }
            }
            assert!(kept.next().is_none());
            assert!(
                !s.sections.is_empty(),
                "{name} {mode:?}: every plane missed"
            );
            println!(
                "{name:>15} {mode:?}/{seed}: {} of {} planes, {regions} regions, {holes} holes, {} vertices",
                s.sections.len(),
                planes.len(),
                s.vertex_count()
            );
        }
    }
    println!("worst relative area difference {worst:e}");
}

/// A genus-2 figure eight cut across both holes gives a section with two holes.
#[test]
fn eight_has_sections_with_holes() {
    let mesh = read_trimesh(&shared_dir().join("data/reference/eight_15.stl")).unwrap();
    let planes = make_planes(&mesh, 9, 0, SliceMode::Axes);
    let s = slice_mesh(&mesh, &planes).unwrap();
    let max_holes = s
        .sections
        .iter()
        .map(|sec| sec.regions.iter().map(|r| r.holes.len()).sum::<usize>())
        .max()
        .unwrap();
    assert_eq!(max_holes, 2);
}

/// Axis planes exactly through mesh vertices (those vertices are on the plane: the symbolic
/// perturbation decides), and oblique planes through vertices: still closed loops, same areas.
#[test]
fn planes_through_mesh_vertices() {
    for (name, mesh) in reference_meshes() {
        let scale = diag2(&mesh);
        let step = mesh.vertices.len() / 7;
        let mut planes = Vec::new();
        for i in 1..7 {
            let v = mesh.vertices[i * step];
            let mut n = [0.0; 3];
            n[i % 3] = 1.0;
            planes.push(Plane::from_point_normal(v, n).unwrap());
            planes.push(Plane::from_point_normal(v, [0.3, -0.5, 0.8]).unwrap());
        }
        let on_plane = planes
            .iter()
            .map(|p| {
                mesh.vertices
                    .iter()
                    .filter(|&&v| p.signed_distance(v) == 0.0)
                    .count()
            })
            .sum::<usize>();
        assert!(
            on_plane >= 6,
            "{name}: expected vertices exactly on the axis planes"
        );
        let s = slice_mesh(&mesh, &planes).unwrap();
        check_conventions(&name, &s);
        assert_eq!(
            s.sections.len(),
            planes.len(),
            "{name}: a plane through a vertex of the mesh missed it"
        );
        for (sec, plane) in s.sections.iter().zip(&planes) {
            let expect = independent_area(&mesh, plane);
            let rel = (sec.area() - expect).abs() / expect.abs().max(1e-6 * scale);
            assert!(rel < 1e-9, "{name}: area {} vs {expect}", sec.area());
        }
        println!("{name}: {on_plane} vertices exactly on the cutting planes");
    }
}

/// The evaluation module's own mesh/section comparison (slab symmetric difference, written by another
/// hand) finds the sliced sections equal to the mesh's sections.
#[test]
fn eval_finds_no_difference_between_mesh_and_its_slices() {
    for (name, mesh) in reference_meshes() {
        let s = slice_mesh(&mesh, &make_planes(&mesh, 6, 11, SliceMode::Random)).unwrap();
        let agreement = slice2solid::eval::section::section_agreement(&mesh, &s);
        assert_eq!(agreement.len(), s.sections.len());
        let worst = agreement
            .iter()
            .map(|a| a.relative)
            // NaN (a broken measurement) must not vanish in the max
            .fold(0.0_f64, |m, r| {
                if r.is_nan() || m.is_nan() {
                    f64::NAN
                } else {
                    m.max(r)
                }
            });
        println!("{name}: worst relative symmetric difference {worst:e}");
        assert!(worst < 1e-9, "{name}: {worst}");
    }
}
