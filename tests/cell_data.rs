//! The per-triangle input plane and label of `cell_data` (the `.vtp` cell data) on real runs: a
//! triangle marked with a plane lies in that plane's section, and the marked triangles of a plane
//! cover exactly the flat part of the surface there. The pytest suite reads the files themselves
//! with VTK's and meshio's readers.
use slice2solid::cell_data::{surface_cell_data, tet_labels, NONE};
use slice2solid::io::read_sections;
use slice2solid::{reconstruct, Options};
use std::collections::BTreeMap;
use std::path::Path;

fn area(p: &[[f64; 3]], t: [u32; 3]) -> f64 {
    let [a, b, c] = t.map(|i| p[i as usize]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    0.5 * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
}

/// Parallel planes: the surface lies on the first and last plane (the caps), whose area is those
/// sections' area, and nowhere else: on the middle plane 7, the part of the section between the
/// figure eight's hole ends that only one side keeps (5.4e-4 without the collar) is under the
/// collar's prism on the other side.
#[test]
fn the_caps_of_the_figure_eight_are_its_end_sections() {
    let sections = read_sections(Path::new("data/eight_15.csl")).unwrap();
    let solid = reconstruct(&sections, &Options::default()).unwrap();
    let data = surface_cell_data(&solid.surface, &sections, None).unwrap();
    assert_eq!(data.plane.len(), solid.surface.triangles.len());
    let mut per_plane: BTreeMap<i32, f64> = BTreeMap::new();
    for (t, &p) in solid.surface.triangles.iter().zip(&data.plane) {
        if p != NONE {
            *per_plane.entry(p).or_default() += area(&solid.surface.vertices, *t);
        }
    }
    let first = sections.sections.first().unwrap();
    let last = sections.sections.last().unwrap();
    let planes: Vec<i32> = per_plane.keys().copied().collect();
    assert_eq!(
        planes,
        vec![first.source_index as i32, last.source_index as i32]
    );
    for s in [first, last] {
        let got = per_plane[&(s.source_index as i32)];
        assert!(
            (got - s.area()).abs() <= 1e-9 * s.area(),
            "plane {}: {got} vs {}",
            s.source_index,
            s.area()
        );
    }
    // One label in the input: every triangle and tetrahedron has it.
    assert!(data.label.iter().all(|&l| l == 1));
    let tets = solid.tets.as_ref().unwrap();
    assert!(tet_labels(tets, &sections, None)
        .unwrap()
        .iter()
        .all(|&l| l == 1));
}
