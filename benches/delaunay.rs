//! Kernel throughput: uniform points and points on 40 random planes, 10^4 and 10^5 points
//! (10^6 with `S2S_BENCH_1M=1`); 1 and 2 threads on 2·10^5 uniform points and on 400 parallel
//! circles of 250 points (`benches/kernel_vs_cgal.sh` compares the CLI with CGAL side by side); and the tagged kernel against the untagged one on a cell with four
//! oblique faces (`gen::tagged_tetrahedron`: 4 × ~2500 face points + 10^4 interior points).
//!
//! Also writes point files for comparisons with other tools:
//! `S2S_WRITE_XYZ=out.xyz S2S_KIND=planes S2S_N=1000000 cargo bench --bench delaunay` writes the points
//! and exits (kinds: uniform, planes).
//!
//! `S2S_TIME_XYZ=points.xyz cargo bench --bench delaunay` triangulates that file once and prints the
//! kernel's wall and CPU seconds as JSON (CPU time of this thread, from /proc: on a shared, loaded
//! machine it varies far less than wall time, for comparisons with other programs run alike).
use criterion::{criterion_group, BenchmarkId, Criterion};
use slice2solid::delaunay::{gen, xyz, Delaunay};

fn points(kind: &str, n: usize) -> Vec<[f64; 3]> {
    match kind {
        "uniform" => gen::uniform(n, 1),
        _ => gen::on_planes(n, 40, 1),
    }
}

fn bench(c: &mut Criterion) {
    let mut sizes = vec![10_000, 100_000];
    if std::env::var_os("S2S_BENCH_1M").is_some() {
        sizes.push(1_000_000);
    }
    let mut g = c.benchmark_group("delaunay");
    g.sample_size(10);
    for kind in ["uniform", "planes40"] {
        for &n in &sizes {
            let pts = points(kind, n);
            g.bench_with_input(BenchmarkId::new(kind, n), &pts, |b, pts| {
                b.iter(|| Delaunay::new(pts).num_finite_tets())
            });
        }
    }
    // the parallel bulk build against the sequential one (same triangulation)
    for (kind, pts) in [
        ("uniform", gen::uniform(200_000, 1)),
        ("circles_stack", gen::circles(400, 250)),
    ] {
        for threads in [1, 2] {
            let id = BenchmarkId::new(format!("{kind}_threads{threads}"), pts.len());
            g.bench_with_input(id, &pts, |b, pts| {
                b.iter(|| {
                    Delaunay::try_new_with_threads(pts, threads)
                        .unwrap()
                        .num_finite_tets()
                })
            });
        }
    }
    // tagged vs untagged on one cell with four oblique faces (dyadic uv grids, ~1 ulp off-plane)
    let (pts, tags) = gen::tagged_tetrahedron(2500, 10_000, 1);
    let n = pts.len();
    g.bench_with_input(
        BenchmarkId::new("tetra_cell_untagged", n),
        &pts,
        |b, pts| b.iter(|| Delaunay::new(pts).num_finite_tets()),
    );
    g.bench_with_input(BenchmarkId::new("tetra_cell_tagged", n), &pts, |b, pts| {
        b.iter(|| {
            Delaunay::try_new_tagged(pts, &tags)
                .unwrap()
                .num_finite_tets()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);

/// CPU time of the calling thread in seconds (Linux), else None.
fn thread_cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

fn main() {
    if let Some(path) = std::env::var_os("S2S_TIME_XYZ") {
        let pts = xyz::read_xyz(std::path::Path::new(&path)).expect("read points");
        let (c0, t0) = (thread_cpu_seconds(), std::time::Instant::now());
        let dt = Delaunay::new(&pts);
        let (c1, wall) = (thread_cpu_seconds(), t0.elapsed().as_secs_f64());
        let cpu = c0.zip(c1).map(|(a, b)| b - a);
        println!(
            "{}",
            serde_json::json!({"points": pts.len(), "tets": dt.num_finite_tets(), "seconds": wall, "cpu": cpu})
        );
        return;
    }
    if let Some(path) = std::env::var_os("S2S_WRITE_XYZ") {
        let kind = std::env::var("S2S_KIND").unwrap_or_else(|_| "planes".into());
        let n = std::env::var("S2S_N")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1_000_000);
        xyz::write_xyz(std::path::Path::new(&path), &points(&kind, n)).expect("write points");
        return;
    }
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
}
