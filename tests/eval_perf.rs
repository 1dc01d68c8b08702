//! Timing of `check` and `compare` on a 1.3 M-triangle mesh (icosphere, 8 subdivisions).
//! Ignored by default: `cargo test --release --test eval_perf -- --ignored --nocapture`.
use slice2solid::eval::check::check_mesh;
use slice2solid::eval::compare::compare_meshes;
use slice2solid::eval::shapes::{icosphere, translated};
use std::time::Instant;

#[test]
#[ignore]
fn million_triangles() {
    let t = Instant::now();
    let a = icosphere([0.0; 3], 1.0, 8);
    let b = translated(&icosphere([0.0; 3], 1.0, 8), [0.05, 0.02, 0.0]);
    println!(
        "build: {} triangles each, {:.2?}",
        a.triangles.len(),
        t.elapsed()
    );
    let t = Instant::now();
    let r = check_mesh(&a, None);
    println!("check: {:.2?}", t.elapsed());
    assert!(r.is_closed_manifold() && r.oriented);
    assert_eq!(r.self_intersections, 0);
    let t = Instant::now();
    let c = compare_meshes(&a, &b, 25_000, 0);
    println!(
        "compare (25k samples, {} lines): {:.2?}",
        c.iou_lines,
        t.elapsed()
    );
    println!(
        "iou {} chamfer_l1 {} hausdorff {}",
        c.iou, c.chamfer_l1, c.hausdorff
    );
    assert!(c.iou > 0.9 && c.iou < 1.0);
}

#[test]
#[ignore]
fn million_triangles_phases() {
    use slice2solid::eval::check::self_intersections;
    use slice2solid::eval::compare::{compare_meshes_with_lines, surface_samples};
    use slice2solid::eval::topology::analyze;
    let a = icosphere([0.0; 3], 1.0, 8);
    let t = Instant::now();
    let _ = analyze(&a);
    println!("topology: {:.2?}", t.elapsed());
    let t = Instant::now();
    let _ = self_intersections(&a);
    println!("self-intersections: {:.2?}", t.elapsed());
    let t = Instant::now();
    let _ = surface_samples(&a, 25_000, 0);
    println!("samples: {:.2?}", t.elapsed());
    let t = Instant::now();
    let _ = compare_meshes_with_lines(&a, &a, 100, 0, 1);
    println!("compare without lines: {:.2?}", t.elapsed());
}
