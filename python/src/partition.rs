//! `reconstruct_all_labels`: every label at once as a partition of space (either method,
//! `slice2solid::reconstruct_partition`), as numpy arrays in a dict.
use crate::arrays::{cells_array, points_array};
use crate::sections::Sections;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slice2solid::Options;

/// Reconstruct every label of `sections` at once (`slice2solid reconstruct --all-labels`; `method`
/// "implicit" or "delaunay", `depth`: the implicit method's octree depth). Returns a dict: `labels`
/// (increasing), `surfaces` (label -> (vertices (n, 3) float64, faces (m, 3) int64), each closed with
/// outward normals), `interface` (vertices, faces: every interface triangle once) with
/// `interface_labels` ((m, 2) int32, the labels behind and in front of each triangle, the exterior
/// 0), `report`, and with the Delaunay method `tets` (vertices, tetrahedra (k, 4) int64, positive
/// volume) and `tet_labels` ((k,) int32). Runs without the GIL.
#[pyfunction]
#[pyo3(signature = (sections, depth = 9, method = "implicit"))]
pub fn reconstruct_all_labels<'py>(
    py: Python<'py>,
    sections: &Sections,
    depth: u32,
    method: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let method = crate::solid::parse_method(py, method)?;
    let options = Options {
        method,
        depth,
        progress: false,
        ..Default::default()
    };
    let input = &sections.inner;
    let p = py
        .detach(|| slice2solid::reconstruct_partition(input, &options))
        .map_err(|e| crate::py_err(py, e))?;
    let out = PyDict::new(py);
    out.set_item("labels", p.labels.clone())?;
    let surfaces = PyDict::new(py);
    for (l, s) in p.labels.iter().zip(&p.surfaces) {
        surfaces.set_item(
            *l,
            (points_array(py, &s.vertices), cells_array(py, &s.triangles)),
        )?;
    }
    out.set_item("surfaces", surfaces)?;
    out.set_item(
        "interface",
        (
            points_array(py, &p.interfaces.vertices),
            cells_array(py, &p.interfaces.triangles),
        ),
    )?;
    let pairs: Vec<Vec<i32>> = p.interface_labels.iter().map(|l| l.to_vec()).collect();
    out.set_item("interface_labels", PyArray2::from_vec2(py, &pairs)?)?;
    if let Some(t) = &p.tets {
        out.set_item(
            "tets",
            (points_array(py, &t.vertices), cells_array(py, &t.tets)),
        )?;
        out.set_item("tet_labels", numpy::PyArray1::from_slice(py, &p.tet_labels))?;
    }
    out.set_item("report", pythonize::pythonize(py, &p.report)?)?;
    Ok(out)
}
