//! Multi-label slicing (`slice_partition`) of synthetic partitions with a known answer, at parallel,
//! random and fan planes: the CSL written and read back has, per label and plane, the area of the
//! truth's section (by Stokes over the truth's domain mesh, no contours built), labels never overlap
//! (the reader repairs no overlap), and where the truth's interface crosses a plane the two labels'
//! contours share vertices and edges whose total length is the interface's cut length.
mod common;
use common::shared_reference;
use slice2solid::eval::partition::section_contacts;
use slice2solid::io::csl::{parse_csl, to_csl_string};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::sections::{cross, dot, sub};
use slice2solid::slice::synthetic::{
    carved, nested_spheres, stacked_cylinder, touching_boxes, SyntheticPartition,
};
use slice2solid::slice::{make_planes, slice_partition, union_mesh, SliceMode};
use slice2solid::{Plane, Sections, TriMesh};
use std::collections::{HashMap, HashSet};

/// Area agreement per label and plane, relative to the squared diagonal of all meshes.
const AREA_TOL: f64 = 2e-15; // measured at most 4.2e-16
/// Interface length agreement per pair and plane, relative to the diagonal.
const LENGTH_TOL: f64 = 2e-15; // measured at most 6.2e-16

/// Section area by Stokes (as `tests/slice_reference.rs`): per triangle crossing the plane, the cut
/// segment oriented along n × N contributes ½ n·((p0 − o) × (p1 − o)).
fn stokes_area(mesh: &TriMesh, plane: &Plane) -> f64 {
    let (n, o) = (plane.normal, plane.origin);
    let mut area = 0.0;
    for t in &mesh.triangles {
        let Some((mut p0, mut p1)) = cut(mesh, *t, plane) else {
            continue;
        };
        let p = t.map(|i| mesh.vertices[i as usize]);
        let along = cross(n, cross(sub(p[1], p[0]), sub(p[2], p[0])));
        if dot(sub(p1, p0), along) < 0.0 {
            std::mem::swap(&mut p0, &mut p1);
        }
        area += 0.5 * dot(n, cross(sub(p0, o), sub(p1, o)));
    }
    area
}

/// Where the plane cuts triangle `t` (direct interpolation in 3D), if it does.
fn cut(mesh: &TriMesh, t: [u32; 3], plane: &Plane) -> Option<([f64; 3], [f64; 3])> {
    let p = t.map(|i| mesh.vertices[i as usize]);
    let d = p.map(|x| plane.signed_distance(x));
    let mut pts = Vec::with_capacity(2);
    for k in 0..3 {
        let (a, b) = (k, (k + 1) % 3);
        if (d[a] >= 0.0) != (d[b] >= 0.0) {
            let s = d[a] / (d[a] - d[b]);
            pts.push(std::array::from_fn(|c| p[a][c] + s * (p[b][c] - p[a][c])));
        }
    }
    (pts.len() == 2).then(|| (pts[0], pts[1]))
}

fn length(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// Length of the cut of the interface triangles by the plane.
fn interface_length(interface: &TriMesh, plane: &Plane) -> f64 {
    interface
        .triangles
        .iter()
        .filter_map(|&t| cut(interface, t, plane))
        .map(|(a, b)| length(a, b))
        .sum()
}

/// Per pair of labels (lower first), the total length of the contour edges the two share in `s`
/// (the same two 3D points), and how many vertices they share.
fn shared_edges(s: &slice2solid::Section) -> HashMap<(i32, i32), (f64, usize)> {
    let key = |p: [f64; 3]| p.map(f64::to_bits);
    type Edge = ([u64; 3], [u64; 3]);
    let mut owner: HashMap<Edge, (HashSet<i32>, f64)> = HashMap::new();
    let mut vertex_labels: HashMap<[u64; 3], HashSet<i32>> = HashMap::new();
    for r in &s.regions {
        for c in std::iter::once(&r.outer).chain(&r.holes) {
            let n = c.points3.len();
            for k in 0..n {
                let (p, q) = (c.points3[k], c.points3[(k + 1) % n]);
                let (a, b) = (key(p), key(q));
                let e = owner.entry((a.min(b), a.max(b))).or_default();
                e.0.insert(r.label);
                e.1 = length(p, q);
                vertex_labels.entry(a).or_default().insert(r.label);
            }
        }
    }
    let mut out: HashMap<(i32, i32), (f64, usize)> = HashMap::new();
    for (labels, len) in owner.values() {
        if labels.len() == 2 {
            let mut l: Vec<i32> = labels.iter().copied().collect();
            l.sort_unstable();
            out.entry((l[0], l[1])).or_default().0 += len;
        }
    }
    for labels in vertex_labels.values().filter(|l| l.len() == 2) {
        let mut l: Vec<i32> = labels.iter().copied().collect();
        l.sort_unstable();
        out.entry((l[0], l[1])).or_default().1 += 1;
    }
    out
}

/// What one case at one plane placement measured.
#[derive(Debug, Default)]
struct Measured {
    planes: usize,
    worst_area: f64,
    worst_length: f64,
    /// Planes where some pair touches (truth) / share edges (sliced).
    contact_planes: usize,
    touching_warnings: usize,
}

fn diagonal(m: &TriMesh) -> f64 {
    let b = slice2solid::eval::bvh::Aabb::of_points(&m.vertices);
    b.diagonal()
}

/// Slice `case` with `n` planes of `mode`, write CSL, read it back, compare with the truth.
fn run(case: &SyntheticPartition, mode: SliceMode, n: usize, seed: u64) -> Measured {
    let union = union_mesh(&case.meshes);
    let diag = diagonal(&union);
    let planes = make_planes(&union, n, seed, mode);
    let sliced = slice_partition(&case.meshes, &planes).unwrap();
    let text = to_csl_string(&sliced);
    let read: Sections = parse_csl(&text, "partition.csl").unwrap();
    let what = format!("{} {mode:?}", case.name);
    for w in &read.warnings {
        assert!(
            w.contains("touching components of different labels"),
            "{what}: the reader repaired more than touching labels: {w}"
        );
    }
    let mut m = Measured {
        planes: read.sections.len(),
        touching_warnings: read.warnings.len(),
        ..Default::default()
    };
    let crossed: Vec<&Plane> = planes
        .iter()
        .filter(|p| case.domains.iter().any(|(_, d)| stokes_area(d, p) > 0.0))
        .collect();
    assert_eq!(read.sections.len(), crossed.len(), "{what}: planes kept");
    for (s, truth_plane) in read.sections.iter().zip(crossed) {
        // (CSL stores the plane equation; reading normalises it again, within ulps)
        assert!(
            dot(s.plane.normal, truth_plane.normal) > 1.0 - 1e-14,
            "{what}"
        );
        for (label, domain) in &case.domains {
            let got: f64 = s
                .regions
                .iter()
                .filter(|r| r.label == *label)
                .map(|r| r.area())
                .sum();
            let want = stokes_area(domain, &s.plane);
            m.worst_area = m.worst_area.max((got - want).abs() / (diag * diag));
        }
        let shared = shared_edges(s);
        let mut contact = false;
        for (a, b, interface) in &case.interfaces {
            let want = interface_length(interface, &s.plane);
            let (got, vertices) = shared.get(&(*a, *b)).copied().unwrap_or_default();
            m.worst_length = m.worst_length.max((got - want).abs() / diag);
            if want > 0.0 {
                contact = true;
                assert!(
                    vertices >= 2,
                    "{what}: labels {a}, {b} share {vertices} vertices"
                );
            }
        }
        m.contact_planes += usize::from(contact);
        // Labels the truth keeps apart share nothing.
        for (a, b) in shared.keys() {
            assert!(
                case.interfaces.iter().any(|(x, y, _)| (x, y) == (a, b)),
                "{what}: labels {a} and {b} share an edge but do not touch"
            );
        }
    }
    assert_eq!(
        section_contacts(&read).values().sum::<usize>() > 0,
        m.contact_planes > 0,
        "{what}"
    );
    assert!(
        m.worst_area <= AREA_TOL,
        "{what}: area off by {:e} diag²",
        m.worst_area
    );
    assert!(
        m.worst_length <= LENGTH_TOL,
        "{what}: interface off by {:e} diag",
        m.worst_length
    );
    assert!(m.touching_warnings >= m.contact_planes, "{what}: {m:?}");
    m
}

const MODES: [(SliceMode, usize, u64); 3] = [
    (SliceMode::Parallel, 9, 0),
    (SliceMode::Random, 12, 3),
    (SliceMode::Fan, 8, 5),
];

/// Run every mode; the number of planes where labels touch (truth and sections alike), per mode,
/// must be `contacts` (parallel, random, fan).
fn run_all(case: &SyntheticPartition, contacts: [usize; 3]) {
    let measured: Vec<Measured> = MODES
        .into_iter()
        .map(|(mode, n, seed)| run(case, mode, n, seed))
        .collect();
    eprintln!("{}: {measured:?}", case.name);
    let got: Vec<usize> = measured.iter().map(|m| m.contact_planes).collect();
    assert_eq!(got, contacts, "{}: planes where labels touch", case.name);
    for (m, (_, n, _)) in measured.iter().zip(MODES) {
        assert!(m.planes <= n);
    }
}

#[test]
fn nested_spheres_core_and_shell() {
    run_all(&nested_spheres(), [5, 7, 8]);
}

#[test]
fn boxes_touching_on_a_face_conforming() {
    run_all(&touching_boxes(true), [9, 11, 7]);
}

#[test]
fn boxes_touching_on_a_face_with_different_grids() {
    run_all(&touching_boxes(false), [9, 11, 7]);
}

#[test]
fn cylinder_of_three_stacked_materials() {
    run_all(&stacked_cylinder(), [9, 12, 7]);
}

/// Box A = [0,1]³ (label 1, listed first) and box B = [0.5,2]×[0.3,1.4]×[-0.2,0.8] (label 2)
/// overlap in the box A∩B, which A keeps: label 2 is B minus A∩B (its truth for Stokes areas is B
/// with A∩B reversed, not a manifold but the right signed sections); the interface is the part of
/// A's boundary inside B, the faces x = 1, y = 1 and z = 0 of A∩B. The outlines cross: the priority
/// difference makes new vertices, which must be in both labels' contours.
fn overlapping_boxes() -> SyntheticPartition {
    use slice2solid::eval::shapes::{cuboid, grid_box, inverted, merged};
    use slice2solid::slice::LabelledMesh;
    let a = grid_box([0.0; 3], [1.0; 3], [2, 2, 2]);
    let b = grid_box([0.5, 0.3, -0.2], [2.0, 1.4, 0.8], [3, 2, 2]);
    let ab = cuboid([0.5, 0.3, 0.0], [1.0, 1.0, 0.8]);
    let on_a = |p: [f64; 3]| p[0] == 1.0 || p[1] == 1.0 || p[2] == 0.0;
    let interface = TriMesh {
        vertices: ab.vertices.clone(),
        triangles: ab
            .triangles
            .iter()
            .copied()
            .filter(|t| {
                let p = t.map(|v| ab.vertices[v as usize]);
                (0..3).any(|k| p.iter().all(|q| q[k] == [1.0, 1.0, 0.0][k]))
                    && p.iter().all(|&q| on_a(q))
            })
            .collect(),
    };
    assert_eq!(interface.triangles.len(), 6);
    let lm = |name: &str, mesh: &TriMesh, label| LabelledMesh {
        name: name.into(),
        mesh: mesh.clone(),
        label,
    };
    SyntheticPartition {
        name: "two overlapping boxes, the first keeps the overlap".into(),
        meshes: vec![lm("box A", &a, 1), lm("box B", &b, 2)],
        domains: vec![(1, a), (2, merged(&b, &inverted(&ab)))],
        interfaces: vec![(1, 2, interface)],
    }
}

#[test]
fn overlapping_boxes_the_first_listed_keeps_the_overlap() {
    run_all(&overlapping_boxes(), [2, 9, 8]);
}

#[test]
fn reference_mesh_with_a_ball_carved_out() {
    let mesh = read_trimesh(&shared_reference("eight_15")).unwrap();
    let (c, r) = common::ball_inside(&mesh);
    eprintln!("ball at {c:?}, radius {r}");
    assert!((r - 0.093860).abs() < 1e-5, "ball radius {r}");
    assert!(r > 0.02 * diagonal(&mesh), "ball radius {r}");
    run_all(&carved("eight_15", &mesh, c, r), [1, 5, 8]);
}

/// The other plane placements (axes, sweep, tilt) place their planes for the union of the meshes
/// too: areas and interfaces as exact, on the partitions whose outlines meet non-conformingly or
/// cross (the planes where labels touch pinned per mode).
#[test]
fn other_modes_on_different_grids_and_overlapping_boxes() {
    for (case, want) in [
        (touching_boxes(false), [6, 8, 8]),
        (overlapping_boxes(), [6, 3, 3]),
        (stacked_cylinder(), [6, 8, 6]),
    ] {
        let mut touching = Vec::new();
        for (mode, n) in [
            (SliceMode::Axes, 9),
            (SliceMode::Sweep, 8),
            (SliceMode::Tilt, 8),
        ] {
            touching.push(run(&case, mode, n, 7).contact_planes);
        }
        eprintln!("{}: {touching:?}", case.name);
        assert_eq!(touching, want, "{}: planes where labels touch", case.name);
    }
}

/// `check_partition` on the truth's domains of the carved figure eight: both closed, disjoint, the
/// ball's surface the interface.
#[test]
fn carved_reference_domains_are_a_partition() {
    let mesh = read_trimesh(&shared_reference("eight_15")).unwrap();
    let (c, r) = common::ball_inside(&mesh);
    let case = carved("eight_15", &mesh, c, r);
    let domains: Vec<(i32, String, TriMesh)> = case
        .domains
        .iter()
        .map(|(l, m)| (*l, format!("label {l}"), m.clone()))
        .collect();
    let report = slice2solid::eval::partition::check_partition(&domains, None).unwrap();
    assert!(report.valid, "{report:#?}");
    let p = &report.pairs[0];
    assert_eq!(p.interface_triangles, 1280);
    let ball_area = slice2solid::eval::check::check_mesh(&case.domains[1].1, None).area;
    assert!((p.interface_area - ball_area).abs() < 1e-12 * ball_area);
    assert_eq!(report.domains[0].check.components, 2);
}
