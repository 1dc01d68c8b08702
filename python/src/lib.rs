//! The Python module `slice2solid._slice2solid` (re-exported by the package `slice2solid`): a thin
//! layer over the library's API. Sections come from files or numpy arrays and go through the
//! library's own validation; the engine runs with the GIL released; library errors become
//! `slice2solid.Error` subclasses whose text is the library's, location first.
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

mod arrays;
mod measure;
mod partition;
mod sections;
mod solid;

create_exception!(
    slice2solid,
    Error,
    PyException,
    "Any error of slice2solid; the text is the library's (`location: reason` for input errors)."
);
create_exception!(
    slice2solid,
    InputError,
    Error,
    "Malformed or invalid input. Attributes: `location` (file and line, JSON path or array path, plane, contour) and `reason`."
);
create_exception!(
    slice2solid,
    GeometryError,
    Error,
    "A geometric computation failed (never for valid input: a bug to report)."
);
create_exception!(
    slice2solid,
    UnavailableError,
    Error,
    "A capability this build or this method does not have (e.g. tetrahedra of the implicit method)."
);

/// The Python exception for a library error, with its text unchanged.
pub(crate) fn py_err(py: Python<'_>, e: slice2solid::Error) -> PyErr {
    let text = e.to_string();
    match e {
        slice2solid::Error::Input { location, reason } => {
            let err = InputError::new_err(text);
            let value = err.value(py);
            // Attributes are plain strings on a fresh exception object: setting them cannot fail.
            let _ = value.setattr("location", location);
            let _ = value.setattr("reason", reason);
            err
        }
        slice2solid::Error::Io { .. } => Error::new_err(text),
        slice2solid::Error::Geometry(_) => GeometryError::new_err(text),
        slice2solid::Error::Unavailable(_) => UnavailableError::new_err(text),
    }
}

/// An input error at `location` (arguments that are not what the library takes).
pub(crate) fn input_err(py: Python<'_>, location: &str, reason: impl Into<String>) -> PyErr {
    py_err(py, slice2solid::Error::input(location, reason))
}

#[pymodule]
fn _slice2solid(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<Error>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("GeometryError", py.get_type::<GeometryError>())?;
    m.add("UnavailableError", py.get_type::<UnavailableError>())?;
    m.add_class::<sections::Sections>()?;
    m.add_class::<solid::Solid>()?;
    m.add_function(wrap_pyfunction!(sections::read, m)?)?;
    m.add_function(wrap_pyfunction!(sections::sections_from_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(solid::reconstruct, m)?)?;
    m.add_function(wrap_pyfunction!(partition::reconstruct_all_labels, m)?)?;
    m.add_function(wrap_pyfunction!(measure::check, m)?)?;
    m.add_function(wrap_pyfunction!(measure::compare, m)?)?;
    Ok(())
}
