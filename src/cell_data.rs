//! What each element of a solid is, for viewers that colour by cell data (the VTK XML files): the
//! input plane a surface triangle lies on, and the label of the material a triangle bounds or a
//! tetrahedron fills. [`NONE`] (-1) where there is no such plane or label.
//!
//! A triangle lies on an input plane when its three vertices are within `SECTION_OFFSETS[0]` (1e-12)
//! × the surface's bounding-box diagonal of it: the band in which `check --sections` takes a
//! triangle as part of the plane's section (`eval::section`). Vertices the engines put on a plane
//! are constructed there (rounding ~1e-16 relative); vertices moved off it on purpose (lifted
//! pinches, thickened slabs, 1e-6 of an edge) are not on it, and neither are their triangles.
//!
//! Labels: a triangle on a plane has the label of the input region its centroid is inside
//! (exact winding numbers in the plane's frame). Every other triangle, and every tetrahedron, has
//! the run's label when the reconstructed material is of one label (`--label L`, or an input whose
//! regions all have one label); when the solid is the union of several labels it has none.
use crate::error::Result;
use crate::eval::section::{bbox_diagonal, SECTION_OFFSETS};
use crate::mesh::{TetMesh, TriMesh};
use crate::sections::Sections;
use crate::validate::winding_number;

/// Written where a triangle lies on no input plane, or an element has no single label.
pub const NONE: i32 = -1;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceCellData {
    /// Per triangle: the input plane it lies on (`Section::source_index`), or [`NONE`].
    pub plane: Vec<i32>,
    /// Per triangle: its material's label, or [`NONE`].
    pub label: Vec<i32>,
}

/// The cell data of a surface reconstructed from `sections` with `label` selected (`Options::label`).
pub fn surface_cell_data(
    surface: &TriMesh,
    sections: &Sections,
    label: Option<i32>,
) -> Result<SurfaceCellData> {
    let selected = sections.select_label(label)?;
    let run_label = single_label(&selected, label);
    let planes = triangle_planes(surface, &selected);
    Ok(SurfaceCellData {
        plane: planes
            .iter()
            .map(|p| p.map_or(NONE, |s| selected.sections[s].source_index as i32))
            .collect(),
        label: surface
            .triangles
            .iter()
            .zip(&planes)
            .map(|(t, p)| {
                p.and_then(|s| region_label(surface, *t, &selected, s))
                    .or(run_label)
                    .unwrap_or(NONE)
            })
            .collect(),
    })
}

/// Per tetrahedron of a solid reconstructed from `sections` with `label` selected: its label.
pub fn tet_labels(tets: &TetMesh, sections: &Sections, label: Option<i32>) -> Result<Vec<i32>> {
    let run_label = single_label(&sections.select_label(label)?, label);
    Ok(vec![run_label.unwrap_or(NONE); tets.tets.len()])
}

/// Per triangle, the index (into `sections.sections`) of the plane it lies on, if any.
pub fn triangle_planes(mesh: &TriMesh, sections: &Sections) -> Vec<Option<usize>> {
    let tol = SECTION_OFFSETS[0] * bbox_diagonal(mesh);
    // Per vertex, the planes it lies on (a vertex on an arrangement edge lies on two or more).
    let on: Vec<Vec<usize>> = mesh
        .vertices
        .iter()
        .map(|&p| {
            (0..sections.sections.len())
                .filter(|&s| sections.sections[s].plane.signed_distance(p).abs() <= tol)
                .collect()
        })
        .collect();
    mesh.triangles
        .iter()
        .map(|t| {
            on[t[0] as usize]
                .iter()
                .copied()
                .find(|s| on[t[1] as usize].contains(s) && on[t[2] as usize].contains(s))
        })
        .collect()
}

/// The label of the region of section `s` that triangle `t`'s centroid is inside.
fn region_label(mesh: &TriMesh, t: [u32; 3], sections: &Sections, s: usize) -> Option<i32> {
    let sec = &sections.sections[s];
    let c = t.iter().fold([0.0; 3], |acc, &v| {
        let p = mesh.vertices[v as usize];
        [
            acc[0] + p[0] / 3.0,
            acc[1] + p[1] / 3.0,
            acc[2] + p[2] / 3.0,
        ]
    });
    let q = sec.plane.to_2d(c);
    sec.regions
        .iter()
        .find(|r| {
            winding_number(q, &r.outer.points2) != 0
                && r.holes.iter().all(|h| winding_number(q, &h.points2) == 0)
        })
        .map(|r| r.label)
}

/// The one label the reconstructed material has, if it has one.
fn single_label(selected: &Sections, label: Option<i32>) -> Option<i32> {
    if label.is_some() {
        return label;
    }
    let labels = selected.regions_per_label();
    (labels.len() == 1).then(|| *labels.keys().next().expect("one label"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::plain::{
        build_sections, ContourPoints, ContourSpec, Naming, PlaneSpec, SectionSpec,
    };

    /// Two unit squares at z = 0 (label 2) and z = 1 (label 2, with a second region of label 3).
    fn sections() -> Sections {
        let square = |z: f64, x0: f64, label: i32| ContourSpec {
            points: ContourPoints::Xyz(vec![
                [x0, 0., z],
                [x0 + 1., 0., z],
                [x0 + 1., 1., z],
                [x0, 1., z],
            ]),
            label,
            hole_of: None,
        };
        let plane = |z: f64| PlaneSpec::PointNormal {
            point: [0., 0., z],
            normal: [0., 0., 1.],
        };
        let specs = [
            SectionSpec {
                plane: plane(0.0),
                contours: vec![square(0.0, 0.0, 2)],
            },
            SectionSpec {
                plane: plane(1.0),
                contours: vec![square(1.0, 0.0, 2), square(1.0, 5.0, 3)],
            },
        ];
        let naming = Naming {
            source: "t",
            root: "planes",
        };
        build_sections(&specs, 0, &naming, &Default::default()).unwrap()
    }

    #[test]
    fn triangles_on_planes_get_the_plane_and_the_region_label() {
        let mesh = TriMesh {
            vertices: vec![
                [0.2, 0.2, 0.0],
                [0.8, 0.2, 0.0],
                [0.5, 0.8, 0.0],
                [5.5, 0.5, 1.0],
                [5.6, 0.5, 1.0],
                [5.5, 0.6, 1.0],
                [0.5, 0.5, 0.5],
                [0.5, 0.5, 1.0 + 1e-6],
            ],
            triangles: vec![[0, 1, 2], [3, 4, 5], [0, 1, 6], [3, 4, 7]],
        };
        let s = sections();
        assert_eq!(
            triangle_planes(&mesh, &s),
            vec![Some(0), Some(1), None, None]
        );
        let all = surface_cell_data(&mesh, &s, None).unwrap();
        assert_eq!(all.plane, vec![0, 1, NONE, NONE]);
        assert_eq!(all.label, vec![2, 3, NONE, NONE]);
        // label 2 selected: plane 1's label-3 region is not part of the input any more
        let only2 = surface_cell_data(&mesh, &s, Some(2)).unwrap();
        assert_eq!(only2.label, vec![2, 2, 2, 2]);
        let tets = TetMesh {
            vertices: mesh.vertices.clone(),
            tets: vec![[0, 1, 2, 6]],
        };
        assert_eq!(tet_labels(&tets, &s, None).unwrap(), vec![NONE]);
        assert_eq!(tet_labels(&tets, &s, Some(3)).unwrap(), vec![3]);
        assert_eq!(
            tet_labels(&tets, &s.select_label(Some(2)).unwrap(), None).unwrap(),
            vec![2]
        );
    }
}
