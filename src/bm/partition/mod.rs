//! Every label at once with the Delaunay method (issue 16): the solid of all labels as one material
//! is one conforming complex K (`assembly`); its tetrahedra are split between the labels, so the
//! domains are a partition of K by construction (no overlap, no gap: two labels that touch share
//! the triangles between their tetrahedra) and every domain's boundary is a closed 2-cycle.
//!
//! 1. *Interfaces on the planes* (`interfaces`). Where two labels touch in a section, the shared
//!    part of their outlines is inside the one-material section, so K's section triangulation does
//!    not have it. Each such segment is put into K: its ends are located among the section
//!    triangles of its plane and split in (a triangle split or an edge split of every tetrahedron
//!    around it, so K stays conforming), and where the segment crosses an edge, that edge is split
//!    at the crossing. Then every section triangle lies in one label's region.
//! 2. *Labels* (`labels`). The rule, in order:
//!    * a tetrahedron with a face on a section takes the label of the region the face lies in
//!      (R_ℓ ∩ P = A_ℓ on every plane: the face's two sides are in ℓ);
//!    * otherwise its *compatible* labels are those whose closed region, on every plane its
//!      vertices lie on, contains its simplex there (a vertex, or an edge: the labels of the
//!      section triangles around it). One compatible label: it takes it.
//!    * the rest (several compatible labels: the tetrahedra along an interface between the planes;
//!      or none: a tetrahedron joining two labels' sections, where an interface runs between two
//!      planes) take, among their compatible labels (all where none fits), the one whose value
//!      `prefer` gives largest at their centroid: the pipeline passes each label's mean-value
//!      indicator (the implicit method's interpolant of that label's sections), so the interfaces
//!      between the planes follow the interpolation of the sections; without `prefer` they grow
//!      from the labelled ones in layers of face neighbours (majority, ties: the smaller label).
//!      Then a few rounds of majority vote among face neighbours smooth the interfaces.
//! 3. *Manifold domains* (`manifold`). Where a domain's boundary has a singular edge or a pinched
//!    vertex, a piece of free tetrahedra around it (not standing on a section) changes to a
//!    neighbouring label when that lowers the number of non-disk label boundaries at the vertices
//!    it touches (or two such changes in a row, where one alone does not), then single tetrahedra;
//!    what is left is counted and warned.
//!
//! The exterior is the complement of K ([`EXTERIOR`]); K's own boundary is unchanged.
use super::assembly::Assembled;
use super::complex::{outward_face, Complex, NONE};
use crate::arrangement::Arrangement;
use crate::mesh::{TetMesh, TriMesh};
use crate::sections::Sections;
use crate::solid::{Partition, Report, EXTERIOR};

mod interfaces;
pub use interfaces::{shared_segments, SharedSegments};
pub mod labels;
mod manifold;

/// The points of the outlines labels share in a section, each with its arrangement plane: seeds
/// of the cells' triangulations (`run_cells_seeded`), so that the one-material complex has them as
/// vertices and its tetrahedra between the planes join them (an interface between two planes runs
/// along those tetrahedra's faces).
pub fn seeds(shared: &SharedSegments, arrangement: &Arrangement) -> Vec<(u32, [f64; 3])> {
    let plane_of = labels::plane_of_section(arrangement, shared.len());
    let mut out = Vec::new();
    for (segs, plane) in shared.iter().zip(plane_of) {
        let Some(p) = plane else { continue };
        let mut seen = crate::fxhash::FxHashSet::default();
        for x in segs.iter().flatten() {
            if seen.insert(x.map(f64::to_bits)) {
                out.push((p, *x));
            }
        }
    }
    out
}

/// Split the one-material complex `k` (built from the one-material view of `sections`, whose
/// planes are `arrangement`'s, seeded with `seeds(shared, ..)`) between `labels` (increasing,
/// positive); `shared`: the sections' `shared_segments`.
/// `prefer`: a label's value at a point (larger: more that label's), which decides the
/// tetrahedra the planes leave open (by their centroids) instead of the growth from their
/// neighbours.
pub fn split(
    sections: &Sections,
    arrangement: &Arrangement,
    k: Assembled,
    labels: &[i32],
    shared: &SharedSegments,
    prefer: Option<&labels::Prefer<'_>>,
) -> Partition {
    let mut report = Report::default();
    let Assembled {
        tets,
        planes,
        lifted_from,
        ..
    } = k;
    let mut mesh = interfaces::Mesh {
        positions: tets.vertices,
        planes,
        lifted_from,
        // back to the complex's orientation (TetMesh swaps two vertices for positive volume)
        tets: tets.tets.iter().map(|t| [t[0], t[1], t[3], t[2]]).collect(),
    };
    let regions = labels::Regions::new(sections, arrangement, labels);
    let inserted = interfaces::insert(&mut mesh, &regions, shared);
    report.count("partition_interface_segments", inserted.segments);
    report.count("partition_interface_points", inserted.points);
    report.count("partition_interface_splits", inserted.splits);
    if inserted.missed > 0 {
        report.warnings.push(format!(
            "partition: {} interface segments between touching labels could not be put into the complex (their sections' triangles there take the label of their centre)",
            inserted.missed
        ));
    }
    report.count("partition_interface_segments_missed", inserted.missed);
    let complex = Complex::new(mesh.positions.len(), std::mem::take(&mut mesh.tets));
    let mut assigned = labels::assign(&complex, &mesh, &regions, prefer);
    report.count("partition_tets_on_sections", assigned.on_sections);
    report.count("partition_tets_one_compatible", assigned.one_compatible);
    report.count("partition_tets_grown", assigned.grown);
    report.count("partition_section_faces_conflicting", assigned.conflicts);
    report.count("partition_section_faces_unlocated", assigned.unlocated);
    if assigned.conflicts > 0 {
        report.warnings.push(format!(
            "partition: {} tetrahedra stand on section triangles of two different labels (they take the smaller)",
            assigned.conflicts
        ));
    }
    let fixed = manifold::repair(
        &complex,
        &mut assigned.label,
        &assigned.pinned,
        &assigned.compatible,
        labels.len(),
    );
    report.count("partition_tets_relabelled_for_manifold", fixed.relabelled);
    report.count("partition_singular_edges_left", fixed.edges_left);
    report.count("partition_singular_vertices_left", fixed.vertices_left);
    if fixed.edges_left + fixed.vertices_left > 0 {
        report.warnings.push(format!(
            "partition: the domains' boundaries keep {} singular edges and {} pinched vertices that relabelling did not remove",
            fixed.edges_left, fixed.vertices_left
        ));
    }
    let mut partition = outputs(&mesh.positions, &complex, &assigned.label, labels);
    partition.report = report;
    partition
}

/// Per label its boundary, the interface network, and the labelled tetrahedra.
fn outputs(positions: &[[f64; 3]], complex: &Complex, label: &[u32], labels: &[i32]) -> Partition {
    let mut per_label: Vec<Vec<[u32; 3]>> = vec![Vec::new(); labels.len()];
    let mut network = Vec::new();
    let mut pairs = Vec::new();
    for (t, tet) in complex.tets.iter().enumerate() {
        let l = label[t];
        for i in 0..4 {
            let n = complex.nbr[t][i];
            let other = if n == NONE { NONE } else { label[n as usize] };
            if other == l {
                continue;
            }
            let face = outward_face(tet, i);
            per_label[l as usize].push(face);
            if other == NONE {
                // from the exterior (the smallest label) into the domain
                network.push([face[0], face[2], face[1]]);
                pairs.push([EXTERIOR, labels[l as usize]]);
            } else if l < other {
                network.push(face);
                pairs.push([labels[l as usize], labels[other as usize]]);
            }
        }
    }
    for tris in &mut per_label {
        tris.sort_unstable();
    }
    Partition {
        labels: labels.to_vec(),
        surfaces: (per_label.iter())
            .map(|tris| TriMesh::with_used_vertices(positions, tris))
            .collect(),
        interfaces: TriMesh::with_used_vertices(positions, &network),
        interface_labels: pairs,
        tets: Some(TetMesh {
            vertices: positions.to_vec(),
            tets: complex
                .tets
                .iter()
                .map(|t| [t[0], t[1], t[3], t[2]])
                .collect(),
        }),
        tet_labels: label.iter().map(|&l| labels[l as usize]).collect(),
        report: Report::default(),
    }
}
