//! The whole pipeline and the kernel on the pipeline's own point sets.
//!
//! * `reconstruct/<file>`: `slice2solid::reconstruct` (Delaunay method) on the shipped example and,
//!   when the shared data is beside the checkout (`../shared`, or `$SLICE2SOLID_SHARED`), on the
//!   heaviest shared files.
//! * `cell_kernel/*`: the Delaunay kernel on the contour vertices of every cell of Elephant (what
//!   each cell triangulates first: points on the cell's faces, massively coplanar and cocircular), and
//!   on uniform random sets of the same sizes, so the cost of the sections' degeneracy is one ratio.
//!
//! * `acquisitions/<case>`: the shared Elephant reference cut as users' probes cut it (a freehand
//!   sweep of 100 frames, a rotational fan of 40 planes; seed 1): the handle stages and the fans'
//!   cells, which the shipped files barely exercise (issues 14, 18).
//! * `read_sections/<file>`: reading and validating the same files.
//! * `partition_20_boxes/*`: every label at once against all labels as one material (issue 16).
//!
//! `cargo bench --bench reconstruct` (criterion; compare runs on the same machine in the same session).
use criterion::{criterion_group, BenchmarkId, Criterion};
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use slice2solid::bm::{cell_input::CellInput, conform};
use slice2solid::delaunay::{gen, Delaunay};
use slice2solid::{io::read_sections, Options};
use std::path::{Path, PathBuf};

fn shared_csl() -> Option<PathBuf> {
    let dir = std::env::var_os("SLICE2SOLID_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"))
        .join("data/csl");
    dir.is_dir().then_some(dir)
}

fn inputs() -> Vec<(String, PathBuf)> {
    let mut v = vec![(
        "eight_15".to_string(),
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/eight_15.csl"),
    )];
    if let Some(dir) = shared_csl() {
        for name in ["hand", "Armadillo-23-better", "Elephant"] {
            let p = dir.join(format!("{name}.csl"));
            if p.is_file() {
                v.push((name.to_string(), p));
            }
        }
    }
    v
}

/// `slice2solid::reconstruct` of `sections` with the default options, as benchmark `name` of `g`.
fn bench_reconstruct(
    g: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    sections: &slice2solid::Sections,
) {
    g.bench_with_input(BenchmarkId::from_parameter(name), sections, |b, s| {
        b.iter(|| {
            slice2solid::reconstruct(s, &Options::default())
                .expect("reconstruct")
                .surface
                .triangles
                .len()
        })
    });
}

fn reconstruct(c: &mut Criterion) {
    let mut g = c.benchmark_group("reconstruct");
    g.sample_size(10);
    for (name, path) in inputs() {
        bench_reconstruct(&mut g, &name, &read_sections(&path).expect("read sections"));
    }
    g.finish();
}

/// Reading and validating a CSL file (was a 100 ms wall-clock bound in a test, which fails on a slow
/// machine; Elephant reads in ~5 ms).
fn read(c: &mut Criterion) {
    let mut g = c.benchmark_group("read_sections");
    for (name, path) in inputs() {
        g.bench_with_input(BenchmarkId::from_parameter(&name), &path, |b, p| {
            b.iter(|| read_sections(p).expect("read sections").vertex_count())
        });
    }
    g.finish();
}

/// The contour vertices of every cell with sections (before any Steiner split).
fn cell_point_sets(path: &Path) -> Vec<Vec<[f64; 3]>> {
    let sections = read_sections(path).expect("read sections");
    let arr = Arrangement::build(&sections, &ArrangementOptions::default()).expect("arrangement");
    let loops = conform::face_loops(&arr, &conform::Splits::default());
    (0..arr.cells.len() as u32)
        .filter_map(|c| CellInput::build(&arr, &arr.pool, &loops, c))
        .map(|i| i.points)
        .filter(|p| p.len() >= 4)
        .collect()
}

fn cell_kernel(c: &mut Criterion) {
    let Some(dir) = shared_csl() else {
        eprintln!("cell_kernel: no shared data beside the checkout, skipped");
        return;
    };
    let cells = cell_point_sets(&dir.join("Elephant.csl"));
    let uniform: Vec<Vec<[f64; 3]>> = cells
        .iter()
        .enumerate()
        .map(|(i, p)| gen::uniform(p.len(), i as u64 + 1))
        .collect();
    let mut g = c.benchmark_group("cell_kernel");
    g.sample_size(20);
    for (name, sets) in [("Elephant_cells", &cells), ("uniform_same_sizes", &uniform)] {
        g.bench_with_input(BenchmarkId::from_parameter(name), sets, |b, sets| {
            b.iter(|| {
                sets.iter()
                    .map(|p| Delaunay::new(p).num_finite_tets())
                    .sum::<usize>()
            })
        });
    }
    g.finish();
}

/// The shared Elephant reference cut by a sweep of 100 frames and a fan of 40 planes (seed 1).
fn acquisitions(c: &mut Criterion) {
    use slice2solid::slice::{make_planes, slice_mesh, SliceMode};
    let Some(dir) = shared_csl() else {
        eprintln!("acquisitions: no shared data beside the checkout, skipped");
        return;
    };
    let reference = dir.join("../reference/Elephant.stl");
    let mesh =
        slice2solid::io::mesh::read_trimesh(&reference).expect("read the Elephant reference");
    let mut g = c.benchmark_group("acquisitions");
    g.sample_size(10);
    for (name, mode, n) in [
        ("Elephant_sweep_100", SliceMode::Sweep, 100),
        ("Elephant_fan_40", SliceMode::Fan, 40),
    ] {
        let sections = slice_mesh(&mesh, &make_planes(&mesh, n, 1, mode)).expect("slice");
        bench_reconstruct(&mut g, name, &sections);
    }
    g.finish();
}

/// Every label at once against all labels as one material, on the same planes: twenty touching
/// boxes (`box_grid(5, 4)`, 16 random planes, seed 3). Issue 16 asks the partition to cost at most
/// 3× the one-material run.
fn partition(c: &mut Criterion) {
    use slice2solid::slice::{
        make_planes, slice_partition, synthetic::box_grid, union_mesh, SliceMode,
    };
    let case = box_grid(5, 4);
    let planes = make_planes(&union_mesh(&case.meshes), 16, 3, SliceMode::Random);
    let sections = slice_partition(&case.meshes, &planes).expect("slice the boxes");
    let mut g = c.benchmark_group("partition_20_boxes");
    g.sample_size(20);
    g.bench_function("one_material", |b| {
        b.iter(|| slice2solid::reconstruct(&sections, &Options::default()).expect("reconstruct"))
    });
    g.bench_function("all_labels", |b| {
        b.iter(|| {
            slice2solid::reconstruct_partition(&sections, &Options::default()).expect("partition")
        })
    });
    g.finish();
}

criterion_group!(
    benches,
    read,
    reconstruct,
    acquisitions,
    cell_kernel,
    partition
);
criterion::criterion_main!(benches);
