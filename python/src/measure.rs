//! `check` and `compare` on numpy meshes: the library's `eval` instruments, run without the GIL.
use crate::arrays::{index_rows, rows_f64};
use crate::sections::Sections;
use pyo3::prelude::*;
use slice2solid::eval::{check_mesh, compare_meshes};
use slice2solid::TriMesh;

/// A triangle mesh from arrays (`location` names them in errors).
fn trimesh(
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    location: &str,
) -> PyResult<TriMesh> {
    let vertices = rows_f64::<3>(vertices, &format!("{location}vertices"))?;
    let triangles = index_rows::<3>(faces, vertices.len(), &format!("{location}faces"))?;
    let mesh = TriMesh {
        vertices,
        triangles,
    };
    match mesh.problem() {
        Some(p) => Err(crate::input_err(
            faces.py(),
            &format!("{location}vertices"),
            p,
        )),
        None => Ok(mesh),
    }
}

/// A mesh given as a `(vertices, faces)` pair or as an object with `.vertices` and `.faces`
/// (a `Solid`, a `trimesh.Trimesh`).
fn mesh_argument(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<TriMesh> {
    if let Ok((v, f)) = obj.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
        return trimesh(&v, &f, &format!("{name}."));
    }
    match (obj.getattr("vertices"), obj.getattr("faces")) {
        (Ok(v), Ok(f)) => trimesh(&v, &f, &format!("{name}.")),
        _ => Err(crate::input_err(
            obj.py(),
            name,
            "expected a (vertices, faces) pair or an object with .vertices and .faces",
        )),
    }
}

/// What `slice2solid check --json` prints for a surface: closed, manifold, oriented,
/// self-intersections, genus, volume; with `sections`, the agreement with each input plane.
#[pyfunction]
#[pyo3(signature = (vertices, faces, sections = None))]
pub fn check<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    sections: Option<&Sections>,
) -> PyResult<Bound<'py, PyAny>> {
    let mesh = trimesh(vertices, faces, "")?;
    let input = sections.map(|s| &s.inner);
    let report = py.detach(|| check_mesh(&mesh, input));
    Ok(pythonize::pythonize(py, &report)?)
}

/// What `slice2solid compare --json A B` prints: IoU, Chamfer L1/L2, Hausdorff of `a` against the
/// reference `b`, normalised by `b`'s bounding-box diagonal. Each mesh is a `(vertices, faces)` pair
/// or an object with `.vertices` and `.faces`.
#[pyfunction]
#[pyo3(signature = (a, b, samples = 25_000, seed = 0))]
pub fn compare<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    samples: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let a = mesh_argument(a, "a")?;
    let b = mesh_argument(b, "b")?;
    for (m, name) in [(&a, "a"), (&b, "b")] {
        if m.triangles.is_empty() {
            return Err(crate::input_err(py, name, "the mesh has no triangles"));
        }
    }
    if samples == 0 {
        return Err(crate::input_err(
            py,
            "samples",
            "at least one sample is needed",
        ));
    }
    let report = py.detach(|| compare_meshes(&a, &b, samples, seed));
    Ok(pythonize::pythonize(py, &report)?)
}
