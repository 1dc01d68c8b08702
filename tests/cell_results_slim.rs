//! The cells' results hold, once stored, only what the assembly and the sharing of samples read
//! (`CellInput::slim`): no point locators, contour-edge sets, per-slot (u,v) of every local
//! vertex or kernel tags of every point. On a 1000-frame sweep these were gigabytes
//! (docs/design/scale.md); this guards the structure, with and without shared samples, on a
//! shared file.
mod common;
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use slice2solid::{DelaunayOptions, Options};

fn check(name: &str, shared_samples: bool) {
    let sections = slice2solid::io::read_sections(&common::shared_csl(name)).unwrap();
    let arr = Arrangement::build(&sections, &ArrangementOptions::default()).unwrap();
    let options = Options {
        delaunay: DelaunayOptions {
            shared_samples,
            ..Default::default()
        },
        ..Default::default()
    };
    let runs = slice2solid::bm::run_cells(&arr, &options).unwrap();
    let inputs: Vec<_> = runs
        .results
        .iter()
        .flatten()
        .filter_map(|r| r.input.as_ref())
        .collect();
    assert!(!inputs.is_empty(), "{name}: no cell ran");
    for input in inputs {
        let what = format!(
            "{name} (shared samples {shared_samples}) cell {}",
            input.cell
        );
        assert!(input.tags.is_empty(), "{what}: tags kept");
        // every vertex still cell-local has its planes (some may have adopted a shared id since)
        let with_planes: Vec<u32> = input.local_planes.iter().map(|p| p.0).collect();
        for (l, &g) in input.global.iter().enumerate() {
            if g == u32::MAX {
                assert!(
                    with_planes.contains(&(l as u32)),
                    "{what}: local {l} without planes"
                );
            }
        }
        for slot in &input.slots {
            assert!(slot.uv.is_empty(), "{what}: slot (u,v) kept");
            assert!(slot.run.is_none(), "{what}: slot run data kept");
            assert_eq!(
                slot.loop_areas.len(),
                slot.loops.len(),
                "{what}: loop areas"
            );
        }
    }
    // a start is kept only while sharing runs; none is left after it
    assert!(
        runs.results.iter().flatten().all(|r| r.start.is_none()),
        "{name}: run starts kept"
    );
}

#[test]
fn stored_cell_results_are_slim() {
    for name in ["eight_15", "hand"] {
        check(name, true);
        check(name, false);
    }
}
