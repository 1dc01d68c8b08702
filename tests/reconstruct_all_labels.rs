//! `reconstruct --all-labels` with the implicit method (`implicit::labels`) on synthetic partitions
//! with a known answer (nested spheres, two boxes touching on a face, a cylinder of three stacked
//! materials, the figure eight with a ball carved out), cut by parallel, random and fan planes and read back from CSL: the domains are a
//! partition (each closed, manifold, oriented and free of self-intersections; pairwise disjoint by
//! the exact checker; no gap where the sections say two labels touch), every label's sections agree
//! with the input, and volume, IoU and interface area are close to the truth's. Numbers pinned near
//! today's (depth 7, the grid step 1/128 of the longest box side).
use slice2solid::eval::compare::compare_meshes_with_lines;
use slice2solid::eval::partition::check_partition;
use slice2solid::io::csl::{parse_csl, to_csl_string};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::slice::synthetic::{
    box_grid, carved, nested_spheres, stacked_cylinder, touching_boxes, SyntheticPartition,
};
use slice2solid::slice::{make_planes, slice_partition, union_mesh, SliceMode};
use slice2solid::solid::EXTERIOR;
use slice2solid::{reconstruct_partition, Partition};
use slice2solid::{Method, Options, Sections, TriMesh};

mod common;

const DEPTH: u32 = 7;

fn area(m: &TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| slice2solid::geom::triangle_area(t.map(|v| m.vertices[v as usize])))
        .sum()
}

/// What one case measured; the worst over its labels and pairs.
#[derive(Debug, Default)]
struct Measured {
    worst_section: f64,
    worst_iou: f64,
    worst_volume: f64,
    worst_interface: f64,
    /// Defects of the domains (Delaunay; the implicit method has none): non-manifold edges and
    /// vertices, crossing and overlapping triangle pairs within a domain and between two, vertices
    /// of one domain inside another, as the float checker sees them.
    singular: u64,
}

fn sliced(case: &SyntheticPartition, mode: SliceMode, n: usize, seed: u64) -> Sections {
    let planes = make_planes(&union_mesh(&case.meshes), n, seed, mode);
    let sections = slice_partition(&case.meshes, &planes).unwrap();
    parse_csl(&to_csl_string(&sections), "partition.csl").unwrap()
}

fn reconstruct(sections: &Sections, method: Method) -> Partition {
    let options = Options {
        method,
        depth: DEPTH,
        ..Default::default()
    };
    reconstruct_partition(sections, &options).unwrap()
}

fn run(
    case: &SyntheticPartition,
    method: Method,
    mode: SliceMode,
    n: usize,
    seed: u64,
) -> Measured {
    let what = format!("{} {method:?} {mode:?} {n}", case.name);
    let sections = sliced(case, mode, n, seed);
    let p = reconstruct(&sections, method);
    let want: Vec<i32> = case.domains.iter().map(|(l, _)| *l).collect();
    assert_eq!(p.labels, want, "{what}");
    let domains: Vec<(i32, String, TriMesh)> = (p.labels.iter().zip(&p.surfaces))
        .map(|(l, s)| (*l, format!("label {l}"), s.clone()))
        .collect();
    let report = check_partition(&domains, Some(&sections)).unwrap();
    let mut m = Measured::default();
    for d in &report.domains {
        // every domain is the boundary of a set of tetrahedra or cubes (a 2-cycle); a Delaunay
        // domain may keep singular simplices and flat folds there (counted, pinned per case)
        assert_eq!(d.check.boundary_edges, 0, "{what}: label {}", d.label);
        if method == Method::Implicit {
            assert!(d.valid, "{what}: label {} {:?}", d.label, d.check);
        }
        m.singular += (d.check.nonmanifold_edges
            + d.check.nonmanifold_vertices
            + d.check.self_intersections
            + d.check.overlapping_coplanar_pairs) as u64;
    }
    for pair in &report.pairs {
        if method == Method::Implicit {
            assert!(pair.disjoint, "{what}: {pair:?}");
        }
        m.singular += (pair.crossings + pair.vertices_inside[0] + pair.vertices_inside[1]) as u64;
        assert!(!pair.gap, "{what}: a gap {pair:?}");
    }
    if m.singular == 0 {
        assert!(report.valid, "{what}");
    }
    for d in &report.domains {
        let w = d.check.worst_section.as_ref().map_or(0.0, |w| w.relative);
        m.worst_section = m.worst_section.max(w);
    }
    for ((label, truth), surface) in case.domains.iter().zip(&p.surfaces) {
        let c = compare_meshes_with_lines(surface, truth, 2000, 1, 128 * 128);
        m.worst_iou = m.worst_iou.max(1.0 - c.iou);
        let v = (c.volume_mesh / c.volume_reference - 1.0).abs();
        m.worst_volume = m.worst_volume.max(v);
        eprintln!(
            "{what}: label {label} IoU {:.4} volume {:.4}",
            c.iou,
            c.volume_mesh / c.volume_reference
        );
    }
    // every interface triangle of the network separates two labels; per touching pair of the truth,
    // the network's area against the truth's interface area
    for (a, b, truth) in &case.interfaces {
        let tris: Vec<[u32; 3]> = (p.interfaces.triangles.iter().zip(&p.interface_labels))
            .filter(|(_, l)| **l == [*a, *b])
            .map(|(t, _)| *t)
            .collect();
        let got = area(&TriMesh {
            vertices: p.interfaces.vertices.clone(),
            triangles: tris,
        });
        let rel = (got / area(truth) - 1.0).abs();
        eprintln!(
            "{what}: interface {a}-{b} area {got:.4} truth {:.4}",
            area(truth)
        );
        m.worst_interface = m.worst_interface.max(rel);
    }
    for l in &p.interface_labels {
        assert!(
            l[0] < l[1] && (l[0] == EXTERIOR || want.contains(&l[0])),
            "{what}: {l:?}"
        );
    }
    eprintln!("{what}: {m:?}");
    m
}

const MODES: [(SliceMode, usize, u64); 3] = [
    (SliceMode::Parallel, 9, 0),
    (SliceMode::Random, 12, 3),
    (SliceMode::Fan, 8, 5),
];

/// Pins per mode (parallel, random, fan): worst section disagreement, 1 − IoU, volume error and
/// interface area error over the labels and pairs, each a little above what was measured (in the
/// comments). A section of the random planes that only grazes a box corner is smaller than the grid
/// step and missed (relative disagreement 1).
fn run_all(case: &SyntheticPartition, method: Method, pins: [[f64; 4]; 3]) {
    for ((mode, n, seed), pin) in MODES.into_iter().zip(pins) {
        let m = run(case, method, mode, n, seed);
        let what = format!("{} {mode:?}: {m:?}", case.name);
        assert!(m.worst_section <= pin[0], "{what}");
        assert!(m.worst_iou <= pin[1], "{what}");
        assert!(m.worst_volume <= pin[2], "{what}");
        assert!(m.worst_interface <= pin[3], "{what}");
    }
}

#[test]
fn nested_spheres_core_and_shell() {
    // measured: parallel 0.082 0.159 0.130 0.037, random 0.023 0.136 0.076 0.052,
    // fan 0.017 0.017 0.014 0.055
    run_all(
        &nested_spheres(),
        Method::Implicit,
        [
            [0.09, 0.17, 0.14, 0.045],
            [0.03, 0.15, 0.085, 0.06],
            [0.02, 0.02, 0.02, 0.065],
        ],
    );
}

#[test]
fn boxes_touching_on_a_face() {
    // measured: parallel 0.0064 0.131 0.130 0.145, random 1.0 0.108 0.053 0.021,
    // fan 0.038 0.100 0.047 0.032
    run_all(
        &touching_boxes(true),
        Method::Implicit,
        [
            [0.008, 0.14, 0.14, 0.16],
            [1.0, 0.12, 0.06, 0.03],
            [0.045, 0.11, 0.055, 0.04],
        ],
    );
}

#[test]
fn cylinder_of_three_stacked_materials() {
    // measured: parallel 0.035 0.072 0.055 0.076, random 0.033 0.139 0.070 0.012,
    // fan 0.029 0.157 0.087 0.027
    run_all(
        &stacked_cylinder(),
        Method::Implicit,
        [
            [0.04, 0.08, 0.065, 0.085],
            [0.04, 0.15, 0.08, 0.02],
            [0.035, 0.17, 0.095, 0.035],
        ],
    );
}

#[test]
fn reference_mesh_with_a_ball_carved_out() {
    let mesh = read_trimesh(&common::shared_reference("eight_15")).unwrap();
    let (c, r) = common::ball_inside(&mesh);
    // measured: parallel 0.064 0.694 0.690 0.357 (one of the nine planes crosses the ball: its
    // domain is what one section supports), random 0.097 0.257 0.222 0.033, fan 0.057 0.124 0.057 0.097
    run_all(
        &carved("eight_15", &mesh, c, r),
        Method::Implicit,
        [
            [0.07, 0.72, 0.72, 0.39],
            [0.11, 0.27, 0.24, 0.04],
            [0.065, 0.135, 0.065, 0.11],
        ],
    );
}

/// The command line: multi-label slicing, `reconstruct --all-labels` writing one surface per label
/// and the interface network, `check --partition` accepting them; the Delaunay method writing the
/// labelled tetrahedra too.
#[test]
fn all_labels_on_the_command_line() {
    use slice2solid::io::mesh::write_trimesh;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let case = nested_spheres();
    let mut args = Vec::new();
    for m in &case.meshes {
        let p = d.join(format!("m{}.stl", m.label));
        write_trimesh(&p, &m.mesh).unwrap();
        args.push(format!("{}:{}", p.display(), m.label));
    }
    let csl = d.join("nested.csl");
    let out = common::bin()
        .arg("slice")
        .args(&args)
        .arg("-o")
        .arg(&csl)
        .args(["--planes", "8", "--mode", "fan"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let net = d.join("net.ply");
    let out = common::bin()
        .arg("reconstruct")
        .arg(&csl)
        .args(["--all-labels", "--method", "implicit", "--depth", "6", "-o"])
        .arg(d.join("out.obj"))
        .arg("--interfaces")
        .arg(&net)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("label 1,") && stderr.contains("label 2,"),
        "{stderr}"
    );
    assert!(!stderr.contains("NOT a closed manifold"), "{stderr}");
    let header = std::fs::read(&net).unwrap();
    let header = String::from_utf8_lossy(&header[..300]);
    assert!(
        header.contains("property int label0\nproperty int label1"),
        "{header}"
    );
    let out = common::bin()
        .args(["check", "--partition"])
        .arg(d.join("out.label1.obj"))
        .arg(d.join("out.label2.obj"))
        .arg("--sections")
        .arg(&csl)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["valid"], true);
    assert_eq!(r["gaps"], 0);
    // the Delaunay method: one surface per label and the labelled tetrahedra
    let tets = d.join("t.vtk");
    let out = common::bin()
        .arg("reconstruct")
        .arg(&csl)
        .args(["--all-labels", "-o"])
        .arg(d.join("x.obj"))
        .arg("--tets")
        .arg(&tets)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(d.join("x.label1.obj").exists() && d.join("x.label2.obj").exists());
    let vtk = std::fs::read_to_string(&tets).unwrap();
    let cells: usize = (vtk.lines().find_map(|l| l.strip_prefix("CELLS ")))
        .and_then(|l| l.split(' ').next()?.parse().ok())
        .unwrap();
    let labels: Vec<i32> = (vtk.lines())
        .skip_while(|l| !l.starts_with("LOOKUP_TABLE"))
        .skip(1)
        .map(|l| l.parse().unwrap())
        .collect();
    assert_eq!(labels.len(), cells);
    assert!(
        labels.contains(&1) && labels.contains(&2) && labels.iter().all(|l| [1, 2].contains(l))
    );
    // the method implicit writes no tetrahedra
    let out = common::bin()
        .arg("reconstruct")
        .arg(&csl)
        .args(["--all-labels", "--method", "implicit", "--depth", "5", "-o"])
        .arg(d.join("y.obj"))
        .arg("--tets")
        .arg(d.join("y.vtk"))
        .output()
        .unwrap();
    assert!(!out.status.success());
}

/// One label through the partition is the one-label implicit reconstruction up to the extraction:
/// the edge points are the same roots (f₁ − f_exterior = 2f), the octree's interpolated nodes are
/// evaluated here. Shared eight_15, depth 7: the same genus, volume and nearly the same solid.
#[test]
fn one_label_as_a_partition_is_the_implicit_solid() {
    let sections = slice2solid::io::read_sections(&common::shared_csl("eight_15")).unwrap();
    let options = Options {
        method: Method::Implicit,
        depth: DEPTH,
        ..Default::default()
    };
    let one = slice2solid::reconstruct(&sections, &options)
        .unwrap()
        .surface;
    let p = reconstruct(&sections, Method::Implicit);
    assert_eq!(p.labels, vec![1]);
    let c = compare_meshes_with_lines(&p.surfaces[0], &one, 2000, 1, 128 * 128);
    eprintln!(
        "IoU {} volumes {} {}",
        c.iou, c.volume_mesh, c.volume_reference
    );
    // measured 0.973 and 0.36% at depth 7 (0.9955 and 0.02% at depth 9): where the octree
    // interpolates a coarse leaf, the partition evaluates every finest node
    assert!(c.iou > 0.965, "IoU {}", c.iou);
    assert!(
        (c.volume_mesh / c.volume_reference - 1.0).abs() < 0.005,
        "{c:?}"
    );
    let genus = |m: &TriMesh| {
        let t = slice2solid::eval::topology::analyze(m);
        t.components.iter().filter_map(|c| c.genus).sum::<i64>()
    };
    assert_eq!(genus(&p.surfaces[0]), genus(&one));
    assert!(p.interface_labels.iter().all(|l| *l == [EXTERIOR, 1]));
}

/// The shipped multi-label example of the README (`data/nested_fan.csl`) at depth 7: a valid
/// partition, the core one ball and the shell two spheres, no gap.
#[test]
fn shipped_example_is_a_partition() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/nested_fan.csl");
    let sections = slice2solid::io::read_sections(&path).unwrap();
    let p = reconstruct(&sections, Method::Implicit);
    assert_eq!(p.labels, vec![1, 2]);
    let domains: Vec<(i32, String, TriMesh)> = (p.labels.iter().zip(&p.surfaces))
        .map(|(l, s)| (*l, format!("label {l}"), s.clone()))
        .collect();
    let report = check_partition(&domains, Some(&sections)).unwrap();
    assert!(report.valid && report.gaps == 0, "{report:?}");
    let components: Vec<usize> = report.domains.iter().map(|d| d.check.components).collect();
    assert_eq!(components, vec![1, 2]);
    for d in &report.domains {
        // measured 1.23e-2 and 1.32e-2 (the grid step is 1/128 of the box)
        let w = d.check.worst_section.as_ref().unwrap().relative;
        assert!(w < 0.015, "label {}: {w}", d.label);
    }
}

/// The Delaunay method (`bm::partition`) on the same partitions. Pins per mode (parallel,
/// random, fan), a little above what was measured (in the comments): worst section disagreement,
/// 1 − IoU, volume error, interface area error, and the domains' defects (`Measured::singular`).
/// The defects are known failures listed here, not accepted ones: where the labels' tetrahedra
/// meet in a checkerboard the relabelling (`partition::manifold`) does not undo; on the stacked
/// cylinder cut by a fan, the solid of all labels as one material is itself not a manifold (11
/// singular edges: wedge cells fall back to the untagged kernel where mirror-image points of two
/// planes through the axis are exactly cospherical, the kernel's open case, `delaunay::tags`).
fn run_all_delaunay(case: &SyntheticPartition, pins: [[f64; 5]; 3]) {
    // every mode measured before any pin is checked, so a failure shows all three
    let measured: Vec<(SliceMode, Measured)> = (MODES.into_iter())
        .map(|(mode, n, seed)| (mode, run(case, Method::Delaunay, mode, n, seed)))
        .collect();
    for ((mode, m), pin) in measured.iter().zip(pins) {
        let what = format!("{} Delaunay {mode:?}: {m:?}", case.name);
        eprintln!("{what}");
        assert!(m.worst_section <= pin[0], "{what}");
        assert!(m.worst_iou <= pin[1], "{what}");
        assert!(m.worst_volume <= pin[2], "{what}");
        assert!(m.worst_interface <= pin[3], "{what}");
        assert!(m.singular as f64 <= pin[4], "{what}");
    }
}

#[test]
fn delaunay_nested_spheres() {
    // measured: parallel 3e-15 0.110 0.110 0.047 0, random 1.6e-9 0.249 0.195 1.064 36,
    // fan 8.8e-10 0.027 0.023 0.432 19 (random was 0.174 0.120 0.881 42 with the manifold
    // step's rounds; the work list moves one 55-tetrahedron piece of the core to the shell)
    run_all_delaunay(
        &nested_spheres(),
        [
            [1e-8, 0.12, 0.12, 0.055, 0.0],
            [1e-8, 0.26, 0.205, 1.12, 40.0],
            [1e-8, 0.03, 0.026, 0.45, 21.0],
        ],
    );
}

#[test]
fn delaunay_boxes_touching_on_a_face() {
    // measured: parallel 0 0.200 0.200 0.200 0, random 6.0e-9 0.173 0.160 1.417 65,
    // fan 4.5e-11 0.615 0.573 0.069 11 (fan was 0.466 0.418 with the plane rule read in (u,v):
    // the boxes' corners are exactly cocircular on the fan's planes, ties the floats now decide;
    // three cells of the one-material complex were untagged then, one now)
    run_all_delaunay(
        &touching_boxes(true),
        [
            [1e-8, 0.21, 0.21, 0.21, 0.0],
            [1e-8, 0.185, 0.17, 1.49, 70.0],
            [1e-8, 0.63, 0.59, 0.075, 12.0],
        ],
    );
}

#[test]
fn delaunay_cylinder_of_three_stacked_materials() {
    // measured: parallel 0 0.108 0.108 0.108 0, random 3.0e-9 0.351 0.284 1.621 107,
    // fan 6.1e-11 0.189 0.170 0.197 46 (was 3.3e-11 0.117 0.107 0.565 6464 while every section's
    // vertex on the fan's axis, rounded 1e-16 beside it, left a micro edge and 13 of 16 wedge
    // cells of the one-material complex fell back to the untagged kernel: no longer, and the
    // labelling of the conforming complex gives the middle layer 15% too much volume)
    run_all_delaunay(
        &stacked_cylinder(),
        [
            [1e-8, 0.115, 0.115, 0.115, 0.0],
            [1e-8, 0.36, 0.295, 1.7, 115.0],
            [1e-8, 0.195, 0.175, 0.21, 50.0],
        ],
    );
}

#[test]
fn delaunay_reference_mesh_with_a_ball_carved_out() {
    let mesh = read_trimesh(&common::shared_reference("eight_15")).unwrap();
    let (c, r) = common::ball_inside(&mesh);
    // measured: parallel 7.6e-12 0.526 0.142 0.875 0, random 5.4e-10 0.276 0.246 0.913 39,
    // fan 2.6e-10 0.121 0.103 0.698 12
    run_all_delaunay(
        &carved("eight_15", &mesh, c, r),
        [
            [1e-8, 0.54, 0.155, 0.93, 0.0],
            [1e-8, 0.29, 0.26, 0.97, 42.0],
            [1e-8, 0.13, 0.11, 0.75, 13.0],
        ],
    );
}

/// One label through the Delaunay partition is the Delaunay solid: the same complex, every
/// tetrahedron that label's, so the same surface.
#[test]
fn one_label_as_a_delaunay_partition_is_the_delaunay_solid() {
    let sections = slice2solid::io::read_sections(&common::shared_csl("eight_15")).unwrap();
    let one = slice2solid::reconstruct(&sections, &Options::default()).unwrap();
    let p = reconstruct(&sections, Method::Delaunay);
    assert_eq!(p.labels, vec![1]);
    let mut a = one.surface.triangles.clone();
    let mut b: Vec<[u32; 3]> = p.surfaces[0].triangles.clone();
    assert_eq!(a.len(), b.len());
    let key = |m: &TriMesh, t: &[u32; 3]| {
        let mut k = t.map(|v| m.vertices[v as usize].map(f64::to_bits));
        k.sort_unstable();
        k
    };
    let mut ka: Vec<_> = a.drain(..).map(|t| key(&one.surface, &t)).collect();
    let mut kb: Vec<_> = b.drain(..).map(|t| key(&p.surfaces[0], &t)).collect();
    ka.sort_unstable();
    kb.sort_unstable();
    assert!(ka == kb, "the same triangles");
    let tets = p.tets.as_ref().unwrap();
    assert_eq!(tets.tets.len(), one.tets.as_ref().unwrap().tets.len());
    assert!(p.tet_labels.iter().all(|&l| l == 1));
}

/// The multi-organ case: twenty boxes in a 5×4 grid (`box_grid`), each touching its neighbours,
/// cut by 16 random planes. No gap, every label's sections within the tolerance, and the defects
/// the manifold step leaves where many labels meet (pinned: a known failure, not an accepted one).
#[test]
fn delaunay_twenty_touching_boxes() {
    let m = run(&box_grid(5, 4), Method::Delaunay, SliceMode::Random, 16, 3);
    // measured: worst section 5.9e-5, 1 − IoU 0.472, volume 0.397, interface 3.31, defects 284
    assert!(m.worst_section <= 6.5e-5, "{m:?}");
    assert!(m.worst_iou <= 0.49, "{m:?}");
    assert!(m.worst_volume <= 0.41, "{m:?}");
    assert!(m.worst_interface <= 3.45, "{m:?}");
    assert!(m.singular <= 300, "{m:?}");
}

/// `compare-methods --all-labels` on the shipped multi-label example: both methods' partitions,
/// each domain checked against its label's sections, no gap, and per label the two methods'
/// domains agreeing (IoU near what was measured at depth 6: 0.973 and 0.983).
#[test]
fn compare_methods_with_every_label() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/nested_fan.csl");
    let out = common::bin()
        .arg("compare-methods")
        .arg(&path)
        .args(["--all-labels", "--depth", "6", "--json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let c: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let methods = c["methods"].as_array().unwrap();
    let names: Vec<&str> = methods
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["delaunay", "implicit"]);
    for m in methods {
        assert_eq!(m["status"], "ok", "{m}");
        let check = &m["check"];
        assert_eq!(check["gaps"], 0, "{}", m["method"]);
        let domains = check["domains"].as_array().unwrap();
        let labels: Vec<i64> = domains
            .iter()
            .map(|d| d["label"].as_i64().unwrap())
            .collect();
        assert_eq!(labels, [1, 2]);
        for d in domains {
            // measured: Delaunay 3.2e-5 (the core, where a fan cell is triangulated untagged,
            // issue 14) and 3.5e-10; implicit 0.025 (the grid at depth 6)
            let w = d["check"]["worst_section"]["relative"].as_f64().unwrap();
            assert!(w < 0.027, "{} label {}: {w}", m["method"], d["label"]);
        }
    }
    // the implicit partition is valid; the Delaunay one keeps defects there (issue 14, listed)
    assert_eq!(methods[1]["check"]["valid"], true);
    assert_eq!(methods[0]["check"]["valid"], false);
    let iou: Vec<f64> = (c["agreement"].as_array().unwrap().iter())
        .map(|a| a["compare"]["iou"].as_f64().unwrap())
        .collect();
    assert_eq!(iou.len(), 2);
    assert!(iou[0] > 0.965 && iou[1] > 0.975, "{iou:?}");
}
