//! `check --sections` and `compare` on the shared reference meshes and CSL files.
mod common;
use common::shared_dir;
use slice2solid::eval::check::check_mesh;
use slice2solid::eval::compare::compare_meshes;
use slice2solid::io::mesh::read_trimesh;
use slice2solid::io::read_sections;

const NAMES: [&str; 6] = [
    "Elephant",
    "balloondog",
    "balloondog_box",
    "eight_15",
    "eight_20",
    "hand",
];

#[test]
fn reference_meshes_agree_with_their_sections() {
    let dir = shared_dir().join("data");
    for name in NAMES {
        let mesh = read_trimesh(&dir.join(format!("reference/{name}.stl"))).unwrap();
        let secs = read_sections(&dir.join(format!("csl/{name}.csl"))).unwrap();
        let r = check_mesh(&mesh, Some(&secs));
        assert!(r.is_closed_manifold() && r.oriented, "{name}: {r:?}");
        assert_eq!(r.components, 1, "{name}");
        let planes = &r.sections;
        assert_eq!(planes.len(), secs.sections.len());
        for p in planes {
            assert!(
                p.relative < 0.01,
                "{name}: plane {} (input {}) differs by {}",
                p.plane,
                p.source_index,
                p.relative
            );
            assert!(p.area_input > 0.0);
        }
        let w = r.worst_section.as_ref().unwrap();
        println!(
            "{name}: {} planes, worst plane {} relative {:.2e}; genus {}, self-intersections {} ({} vertex-disjoint)",
            planes.len(),
            w.source_index,
            w.relative,
            r.genus,
            r.self_intersections,
            r.self_intersections_vertex_disjoint
        );
    }
}

#[test]
fn wrong_sections_are_detected() {
    let dir = shared_dir().join("data");
    let mesh = read_trimesh(&dir.join("reference/eight_15.stl")).unwrap();
    let secs = read_sections(&dir.join("csl/balloondog.csl")).unwrap();
    let r = check_mesh(&mesh, Some(&secs));
    assert!(r.worst_section.unwrap().relative > 0.5);
}

#[test]
fn topology_matches_the_outside_judge() {
    // Values from shared/eval/evaluate.py (trimesh + manifold3d) on the same files.
    let dir = shared_dir().join("data/reference");
    for (name, genus, euler, si_disjoint) in [("hand", 5, -8, 0), ("eight_15", 2, -2, 0)] {
        let r = check_mesh(
            &read_trimesh(&dir.join(format!("{name}.stl"))).unwrap(),
            None,
        );
        assert_eq!(
            (r.genus, r.euler, r.self_intersections_vertex_disjoint),
            (genus, euler, si_disjoint),
            "{name}"
        );
    }
}

#[test]
fn compare_matches_the_outside_judge() {
    // evaluate.py accuracy balloondog.stl balloondog_box.stl (exact booleans, 200k samples):
    // iou 0.631157, chamfer_l1 0.014468, chamfer_l2 3.1825e-4, hausdorff 0.064491.
    let dir = shared_dir().join("data/reference");
    let a = read_trimesh(&dir.join("balloondog.stl")).unwrap();
    let b = read_trimesh(&dir.join("balloondog_box.stl")).unwrap();
    let r = compare_meshes(&a, &b, 25_000, 0);
    assert!((r.iou - 0.631157).abs() < 1e-3, "{r:?}");
    assert!((r.chamfer_l1 - 0.014468).abs() / 0.014468 < 0.05, "{r:?}");
    assert!((r.chamfer_l2 - 3.1825e-4).abs() / 3.1825e-4 < 0.1, "{r:?}");
    assert!((r.hausdorff - 0.064491).abs() < 0.01, "{r:?}");
}
