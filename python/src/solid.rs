//! `reconstruct` (the CLI's `reconstruct` options, engine run without the GIL) and the `Solid` it
//! returns: surface and tetrahedra as numpy arrays, the report as a dict, the VTK cell data.
use crate::arrays::{cells_array, points_array};
use crate::sections::Sections;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use slice2solid::cell_data::{surface_cell_data, tet_labels};
use slice2solid::{DelaunayOptions, Method, Options};
use std::path::PathBuf;

/// A reconstructed solid. `vertices` (n, 3) float64 and `faces` (m, 3) int64: its closed surface,
/// triangles counter-clockwise seen from outside; `tet_vertices`/`tets` (None for the implicit
/// method); `report`: the `--report` JSON as a dict.
#[pyclass(module = "slice2solid", frozen)]
pub struct Solid {
    solid: slice2solid::Solid,
    /// The run's input and label, for the cell data (the input plane and label of each element).
    sections: slice2solid::Sections,
    label: Option<i32>,
}

#[pymethods]
impl Solid {
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, &self.solid.surface.vertices)
    }

    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        cells_array(py, &self.solid.surface.triangles)
    }

    #[getter]
    fn tet_vertices<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.solid
            .tets
            .as_ref()
            .map(|t| points_array(py, &t.vertices))
    }

    #[getter]
    fn tets<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<i64>>> {
        self.solid.tets.as_ref().map(|t| cells_array(py, &t.tets))
    }

    /// Per face: the index of the input plane it lies on, or -1 (the `.vtp` cell data `plane`).
    #[getter]
    fn face_planes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i32>>> {
        let d = surface_cell_data(&self.solid.surface, &self.sections, self.label)
            .map_err(|e| crate::py_err(py, e))?;
        Ok(PyArray1::from_vec(py, d.plane))
    }

    /// Per face: its material's label, or -1 (the `.vtp` cell data `label`).
    #[getter]
    fn face_labels<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i32>>> {
        let d = surface_cell_data(&self.solid.surface, &self.sections, self.label)
            .map_err(|e| crate::py_err(py, e))?;
        Ok(PyArray1::from_vec(py, d.label))
    }

    /// Per tetrahedron: its label, or -1 (the `.vtu` cell data `label`); None without tetrahedra.
    #[getter]
    fn tet_labels<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray1<i32>>>> {
        let Some(t) = self.solid.tets.as_ref() else {
            return Ok(None);
        };
        let labels = tet_labels(t, &self.sections, self.label).map_err(|e| crate::py_err(py, e))?;
        Ok(Some(PyArray1::from_vec(py, labels)))
    }

    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(pythonize::pythonize(py, &self.solid.report)?)
    }

    /// Write the surface by extension (.obj, .ply, .stl, .off, or .vtp with cell data), as
    /// `reconstruct -o` does.
    fn write(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| {
            slice2solid::io::write_surface(&path, &self.solid.surface, &self.sections, self.label)
        })
        .map_err(|e| crate::py_err(py, e))
    }

    /// Write the tetrahedra by extension (.vtk, .mesh, or .vtu with labels), as `reconstruct --tets`.
    fn write_tets(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let Some(tets) = &self.solid.tets else {
            return Err(crate::py_err(
                py,
                slice2solid::Error::Unavailable(format!(
                    "{}: this method produces no tetrahedra",
                    path.display()
                )),
            ));
        };
        py.detach(|| slice2solid::io::write_tets(&path, tets, &self.sections, self.label))
            .map_err(|e| crate::py_err(py, e))
    }

    fn __repr__(&self) -> String {
        format!(
            "<slice2solid.Solid ({}): {} vertices, {} faces, {}>",
            self.solid.report.method,
            self.solid.surface.vertices.len(),
            self.solid.surface.triangles.len(),
            match &self.solid.tets {
                Some(t) => format!("{} tetrahedra", t.tets.len()),
                None => "no tetrahedra".into(),
            }
        )
    }
}

/// The method named `name` ("delaunay" or "implicit"); an input error otherwise.
pub(crate) fn parse_method(py: Python<'_>, name: &str) -> PyResult<Method> {
    match name {
        "delaunay" => Ok(Method::Delaunay),
        "implicit" => Ok(Method::Implicit),
        other => Err(crate::input_err(
            py,
            "method",
            format!("unknown method \"{other}\" (expected \"delaunay\" or \"implicit\")"),
        )),
    }
}

/// Reconstruct a solid from `sections` with the options of `slice2solid reconstruct`:
/// `method` ("delaunay" or "implicit"), `label` (only this label), `depth` (octree depth of the
/// implicit method), `no_branching`, `no_cutting`, `no_thicken`, `no_shared_samples`,
/// `keep_topology`, `collar` (height of the prisms over the sections near every plane, relative
/// to the bounding-box diagonal; 0: none), `smooth` (refine and fair the surface between the
/// planes, every section kept: `slice2solid reconstruct --smooth` with its default parameters).
/// Runs without the GIL.
#[pyfunction]
#[pyo3(signature = (sections, method = "delaunay", label = None, depth = 9, no_branching = false,
    no_cutting = false, no_thicken = false, no_shared_samples = false, keep_topology = false,
    collar = slice2solid::COLLAR_HEIGHT, smooth = false))]
#[allow(clippy::too_many_arguments)]
pub fn reconstruct(
    py: Python<'_>,
    sections: &Sections,
    method: &str,
    label: Option<i32>,
    depth: u32,
    no_branching: bool,
    no_cutting: bool,
    no_thicken: bool,
    no_shared_samples: bool,
    keep_topology: bool,
    collar: f64,
    smooth: bool,
) -> PyResult<Solid> {
    let method = parse_method(py, method)?;
    let options = Options {
        method,
        label,
        depth,
        progress: false,
        delaunay: DelaunayOptions {
            branching: !no_branching,
            cutting: !no_cutting,
            thicken_flat_zones: !no_thicken,
            shared_samples: !no_shared_samples,
            keep_topology,
            collar,
            smooth: smooth.then(slice2solid::Smoothing::default),
        },
        ..Default::default()
    };
    let input = &sections.inner;
    let solid = py
        .detach(|| slice2solid::reconstruct(input, &options))
        .map_err(|e| crate::py_err(py, e))?;
    Ok(Solid {
        solid,
        sections: input.clone(),
        label,
    })
}
