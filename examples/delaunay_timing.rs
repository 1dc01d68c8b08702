//! Kernel timing on S2S_N (default 10^5) uniform points and points on 40 planes, and on degenerate
//! sets (circles, polytope faces) with validation: `cargo run --release --example delaunay_timing`.
//! With S2S_WRITE_DIR the point sets are written as .xyz files instead (for other tools to time).
use slice2solid::delaunay::{gen, xyz, Delaunay};

fn main() {
    timing();
    timing_degenerate();
}

fn timing() {
    let n: usize = std::env::var("S2S_N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000);
    for (name, pts) in [
        ("uniform", gen::uniform(n, 1)),
        ("planes40", gen::on_planes(n, 40, 1)),
    ] {
        if let Ok(dir) = std::env::var("S2S_WRITE_DIR") {
            let path = std::path::Path::new(&dir).join(format!("{name}_{n}.xyz"));
            xyz::write_xyz(&path, &pts).unwrap();
            continue;
        }
        let t = std::time::Instant::now();
        let dt = Delaunay::new(&pts);
        eprintln!(
            "{name} {n}: {:.3} s, {} tets",
            t.elapsed().as_secs_f64(),
            dt.num_finite_tets()
        );
    }
}

fn timing_degenerate() {
    for (name, pts) in [
        ("circles", gen::circles(10, 200)),
        ("circles6", gen::circles(6, 100)),
        ("polytope", gen::polytope_faces(5000, 30, 5)),
    ] {
        let t = std::time::Instant::now();
        let dt = Delaunay::new(&pts);
        eprintln!(
            "{name}: {:.3} s, {} tets",
            t.elapsed().as_secs_f64(),
            dt.num_finite_tets()
        );
        let t = std::time::Instant::now();
        dt.is_valid().unwrap();
        eprintln!("valid {name}: {:.3} s", t.elapsed().as_secs_f64());
    }
}
