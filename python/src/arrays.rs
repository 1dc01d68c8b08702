//! numpy arrays in and out: any array-like of numbers is taken (converted to float64 or int64 as
//! numpy would), with its shape checked; a wrong one is an `InputError` naming the argument.
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray2, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;

/// `obj` as rows of `K` values of type `T` (converted as numpy would); `rows_name` and `what` name
/// the expected array in the error: "an (n, 3) array of numbers".
fn rows<T, const K: usize>(
    obj: &Bound<'_, PyAny>,
    location: &str,
    rows_name: &str,
    what: &str,
) -> PyResult<Vec<[T; K]>>
where
    T: numpy::Element + Copy + for<'a, 'py> FromPyObject<'a, 'py>,
{
    let py = obj.py();
    let a: PyArrayLike2<T, AllowTypeChange> = obj.extract().map_err(|e| {
        crate::input_err(
            py,
            location,
            format!("expected an ({rows_name}, {K}) array of {what} ({e})"),
        )
    })?;
    let a = a.as_array();
    if a.ncols() != K {
        return Err(crate::input_err(
            py,
            location,
            format!(
                "expected an ({rows_name}, {K}) array of {what}, got shape {:?}",
                a.shape()
            ),
        ));
    }
    Ok(a.rows()
        .into_iter()
        .map(|r| std::array::from_fn(|k| r[k]))
        .collect())
}

/// `obj` as rows of `K` float64 numbers.
pub fn rows_f64<const K: usize>(obj: &Bound<'_, PyAny>, location: &str) -> PyResult<Vec<[f64; K]>> {
    rows(obj, location, "n", "numbers")
}

/// `obj` as `K` float64 numbers.
pub fn vector_f64<const K: usize>(obj: &Bound<'_, PyAny>, location: &str) -> PyResult<[f64; K]> {
    let py = obj.py();
    let a: PyArrayLike1<f64, AllowTypeChange> = obj
        .extract()
        .map_err(|e| crate::input_err(py, location, format!("expected {K} numbers ({e})")))?;
    let a = a.as_array();
    if a.len() != K {
        return Err(crate::input_err(
            py,
            location,
            format!("expected {K} numbers, got {}", a.len()),
        ));
    }
    Ok(std::array::from_fn(|k| a[k]))
}

/// `obj` as rows of `K` vertex indices below `n_vertices`.
pub fn index_rows<const K: usize>(
    obj: &Bound<'_, PyAny>,
    n_vertices: usize,
    location: &str,
) -> PyResult<Vec<[u32; K]>> {
    let py = obj.py();
    let a: Vec<[i64; K]> = rows(obj, location, "m", "integers")?;
    let mut out = Vec::with_capacity(a.len());
    for (i, r) in a.iter().enumerate() {
        if let Some(&bad) = r.iter().find(|&&v| v < 0 || v as u64 >= n_vertices as u64) {
            return Err(crate::input_err(
                py,
                &format!("{location}[{i}]"),
                format!("vertex index {bad} is out of range ({n_vertices} vertices)"),
            ));
        }
        out.push(std::array::from_fn(|k| r[k] as u32));
    }
    Ok(out)
}

/// Points as an (n, 3) float64 array.
pub fn points_array<'py>(py: Python<'py>, points: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    Array2::from_shape_vec((points.len(), 3), flat)
        .expect("n x 3 values")
        .into_pyarray(py)
}

/// Cells as an (m, K) int64 array.
pub fn cells_array<'py, const K: usize>(
    py: Python<'py>,
    cells: &[[u32; K]],
) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = cells.iter().flatten().map(|&v| v as i64).collect();
    Array2::from_shape_vec((cells.len(), K), flat)
        .expect("m x K values")
        .into_pyarray(py)
}
