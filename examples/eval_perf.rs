//! Timing of `check` and `compare` on a 1.3 M-triangle mesh (icosphere, 8 subdivisions), whole and
//! by phase: `cargo run --release --example eval_perf`.
use slice2solid::eval::check::check_mesh;
use slice2solid::eval::compare::compare_meshes;
use slice2solid::eval::shapes::{icosphere, translated};
use std::time::Instant;

/// CPU seconds (user + system, all threads) of this process so far, from /proc (Linux; 0 elsewhere).
/// On a shared machine wall time mostly measures the other users.
fn cpu() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = s.rsplit(')').next().unwrap_or("");
    let f: Vec<f64> = after
        .split_whitespace()
        .map(|x| x.parse().unwrap_or(0.0))
        .collect();
    // fields 14 and 15 of stat (utime, stime) are at 11 and 12 after the command name
    (f.get(11).unwrap_or(&0.0) + f.get(12).unwrap_or(&0.0)) / 100.0
}

fn million_triangles() {
    let (t, c) = (Instant::now(), cpu());
    let a = icosphere([0.0; 3], 1.0, 8);
    let b = translated(&icosphere([0.0; 3], 1.0, 8), [0.05, 0.02, 0.0]);
    println!(
        "build: {} triangles each, {:.2?} wall, {:.2} s CPU",
        a.triangles.len(),
        t.elapsed(),
        cpu() - c
    );
    let (t, c) = (Instant::now(), cpu());
    let r = check_mesh(&a, None);
    println!("check: {:.2?} wall, {:.2} s CPU", t.elapsed(), cpu() - c);
    assert!(r.is_closed_manifold() && r.oriented);
    assert_eq!(r.self_intersections, 0);
    let (t, c) = (Instant::now(), cpu());
    let r2 = compare_meshes(&a, &b, 25_000, 0);
    println!(
        "compare (25k samples, {} lines): {:.2?} wall, {:.2} s CPU",
        r2.iou_lines,
        t.elapsed(),
        cpu() - c
    );
    println!(
        "iou {} chamfer_l1 {} hausdorff {}",
        r2.iou, r2.chamfer_l1, r2.hausdorff
    );
    assert!(r2.iou > 0.9 && r2.iou < 1.0);
}

fn million_triangles_phases() {
    use slice2solid::eval::check::self_intersections;
    use slice2solid::eval::compare::{compare_meshes_with_lines, surface_samples};
    use slice2solid::eval::topology::analyze;
    let a = icosphere([0.0; 3], 1.0, 8);
    let (t, c) = (Instant::now(), cpu());
    let _ = analyze(&a);
    println!("topology: {:.2?} wall, {:.2} s CPU", t.elapsed(), cpu() - c);
    let (t, c) = (Instant::now(), cpu());
    let _ = self_intersections(&a);
    println!(
        "self-intersections: {:.2?} wall, {:.2} s CPU",
        t.elapsed(),
        cpu() - c
    );
    let (t, c) = (Instant::now(), cpu());
    let _ = surface_samples(&a, 25_000, 0);
    println!("samples: {:.2?} wall, {:.2} s CPU", t.elapsed(), cpu() - c);
    let (t, c) = (Instant::now(), cpu());
    let _ = compare_meshes_with_lines(&a, &a, 100, 0, 1);
    println!(
        "compare without lines: {:.2?} wall, {:.2} s CPU",
        t.elapsed(),
        cpu() - c
    );
}

fn main() {
    million_triangles();
    million_triangles_phases();
}
