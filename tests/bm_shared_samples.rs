//! `DelaunayOptions::shared_samples`: both cells of a face insert the diagram samples of both sides
//! (`bm::shared_samples`), the first step of one conforming complex
//! (`docs/design/conforming-complex.md`). Per shared file, pinned: the faces whose two cells still
//! triangulate them differently (without sharing: Elephant 544, Horsers 293, eight_20 96,
//! Armadillo 57, hand 17, …), the consecutive sample pairs that stop being Delaunay edges where the
//! two sides' diagrams cross (paper Fig. 12a; the next step inserts the crossings), and that the
//! surface stays a clean closed manifold with its sections.
mod common;
use slice2solid::eval::check::check_mesh;
use slice2solid::{DelaunayOptions, Options};

/// (file, faces triangulated differently: with sharing / without, sample pairs not edges with
/// sharing, components, genus)
const PINS: [(&str, u64, u64, u64, usize, i64); 12] = [
    ("Armadillo-23-better", 0, 57, 102, 3, 2),
    ("Elephant", 1, 544, 328, 10, 29),
    ("Heart-simplified", 0, 0, 0, 1, 0),
    ("Horsers", 3, 293, 64, 13, 5),
    ("ParallelEight", 0, 4, 0, 1, 2),
    ("ParallelEightMore", 0, 4, 0, 1, 2),
    ("SideBishop", 0, 8, 0, 1, 0),
    ("balloondog", 0, 12, 9, 1, 0),
    ("balloondog_box", 0, 13, 18, 2, 0),
    ("eight_15", 0, 8, 2, 1, 2),
    ("eight_20", 0, 96, 323, 3, 3),
    ("hand", 0, 17, 37, 1, 16),
];

fn options(shared_samples: bool) -> Options {
    Options {
        delaunay: DelaunayOptions {
            shared_samples,
            ..Default::default()
        },
        ..Default::default()
    }
}

#[test]
fn both_cells_of_a_face_triangulate_it_alike() {
    let mut failures = Vec::new();
    for (name, differ, differ_unshared, not_edges, comps, genus) in PINS {
        let sections = slice2solid::io::read_sections(&common::shared_csl(name)).unwrap();
        let solid = slice2solid::reconstruct(&sections, &options(true))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let unshared = slice2solid::reconstruct(&sections, &options(false)).unwrap();
        let count = |s: &slice2solid::Solid, k: &str| s.report.counts.get(k).copied();
        let got = (
            count(&solid, "nonconforming_faces"),
            count(&unshared, "nonconforming_faces"),
            count(&solid, "sample_pairs_not_edges"),
        );
        let c = check_mesh(&solid.surface, Some(&sections));
        let worst = c.worst_section.as_ref().map_or(f64::NAN, |w| w.relative);
        eprintln!(
            "{name}: faces differing {:?} (unshared {:?}), pairs not edges {:?}, comps {} genus {} worst {worst:.3e}",
            got.0, got.1, got.2, c.components, c.genus
        );
        if got != (Some(differ), Some(differ_unshared), Some(not_edges)) {
            failures.push(format!(
                "{name}: (differing, unshared, pairs not edges) {got:?}"
            ));
        }
        if !(c.closed && c.manifold && c.oriented && c.self_intersection_free && worst < 0.02) {
            failures.push(format!(
                "{name}: closed {} manifold {} oriented {} self-intersection free {} worst {worst}",
                c.closed, c.manifold, c.oriented, c.self_intersection_free
            ));
        }
        if (c.components, c.genus) != (comps, genus) {
            failures.push(format!(
                "{name}: (components, genus) {:?}",
                (c.components, c.genus)
            ));
        }
        if count(&solid, "cells_kept_unshared") != Some(0) {
            failures.push(format!("{name}: cells kept their unshared run"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
