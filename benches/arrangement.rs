//! The arrangement on freehand-ultrasound-like sweeps (`slice --mode sweep` of the Elephant
//! reference, generated here), as the engines build it:
//!
//! * `arrangement_sections/<frames>`: `CellScope::Sections` (the default: only the cells with a
//!   section on a face), 100 and 300 frames;
//! * `arrangement_all/<frames>`: `CellScope::All` (every cell of the box, what the implicit method
//!   needs and what the Delaunay method built before), 100 and 300 frames, for the ratio.
//!
//! `cargo bench --bench arrangement` (needs the shared data beside the checkout, `../shared`, or
//! `$SLICE2SOLID_SHARED`; criterion; compare runs on the same machine in the same session).
//! Not part of `cargo test`.
use criterion::{criterion_group, BenchmarkId, Criterion};
use slice2solid::arrangement::{Arrangement, ArrangementOptions, CellScope};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::slice::{make_planes, slice_mesh, SliceMode};
use std::path::{Path, PathBuf};

fn elephant() -> slice2solid::TriMesh {
    let path = std::env::var_os("SLICE2SOLID_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"))
        .join("data/reference/Elephant.stl");
    read_trimesh(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn bench(c: &mut Criterion) {
    let mesh = elephant();
    for (group, scope, frames) in [
        (
            "arrangement_sections",
            CellScope::Sections,
            &[100usize, 300][..],
        ),
        ("arrangement_all", CellScope::All, &[100, 300][..]),
    ] {
        let mut g = c.benchmark_group(group);
        g.sample_size(10);
        let options = ArrangementOptions {
            scope,
            ..Default::default()
        };
        for &n in frames {
            let planes = make_planes(&mesh, n, 0, SliceMode::Sweep);
            let sections = slice_mesh(&mesh, &planes).expect("slicing");
            g.bench_with_input(BenchmarkId::from_parameter(n), &sections, |b, s| {
                b.iter(|| {
                    Arrangement::build(s, &options)
                        .expect("arrangement")
                        .cells
                        .len()
                })
            });
        }
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion::criterion_main!(benches);
