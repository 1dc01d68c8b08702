//! `Sections`: cross-sections read from a file (`read`) or built from numpy arrays
//! (`sections_from_arrays`), both validated and repaired by the library (`io::plain` for arrays,
//! the path the JSON reader takes).
use crate::arrays::{rows_f64, vector_f64};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use slice2solid::io::plain::{
    build_sections, ContourPoints, ContourSpec, Naming, PlaneSpec, SectionSpec,
};
use slice2solid::io::ReadOptions;
use std::path::PathBuf;

/// Validated cross-sections: planes with regions (outer contour, holes, label).
#[pyclass(module = "slice2solid", frozen)]
pub struct Sections {
    pub inner: slice2solid::Sections,
}

#[pymethods]
impl Sections {
    fn __len__(&self) -> usize {
        self.inner.sections.len()
    }

    /// Number of labels (declared, or the largest label used).
    #[getter]
    fn n_labels(&self) -> usize {
        self.inner.n_labels
    }

    /// Repairs made while reading, each starting with where it happened.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }

    /// Number of regions per label.
    #[getter]
    fn labels(&self) -> std::collections::BTreeMap<i32, usize> {
        self.inner.regions_per_label()
    }

    /// Area inside each section's contours (holes subtracted), in section order.
    #[getter]
    fn areas(&self) -> Vec<f64> {
        self.inner.sections.iter().map(|s| s.area()).collect()
    }

    /// Per section: `normal` (unit), `offset` (normal·x + offset = 0), `index` (the plane's index in
    /// the input) and `regions`, each `{"label", "outer": (k, 3) array, "holes": [(k, 3) arrays]}`
    /// with outer contours counter-clockwise and holes clockwise seen from the normal.
    #[getter]
    fn planes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        for s in &self.inner.sections {
            let regions = PyList::empty(py);
            for r in &s.regions {
                let d = PyDict::new(py);
                d.set_item("label", r.label)?;
                d.set_item("outer", crate::arrays::points_array(py, &r.outer.points3))?;
                let holes = PyList::empty(py);
                for h in &r.holes {
                    holes.append(crate::arrays::points_array(py, &h.points3))?;
                }
                d.set_item("holes", holes)?;
                regions.append(d)?;
            }
            let d = PyDict::new(py);
            d.set_item("normal", s.plane.normal.to_vec())?;
            d.set_item("offset", s.plane.offset)?;
            d.set_item("index", s.source_index)?;
            d.set_item("regions", regions)?;
            out.append(d)?;
        }
        Ok(out)
    }

    /// Write the sections as CSL or JSON, by extension.
    fn write(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        slice2solid::io::write_sections(&path, &self.inner).map_err(|e| crate::py_err(py, e))
    }

    fn __repr__(&self) -> String {
        format!(
            "<slice2solid.Sections: {} planes, {} regions, {} warnings>",
            self.inner.sections.len(),
            self.inner
                .sections
                .iter()
                .map(|s| s.regions.len())
                .sum::<usize>(),
            self.inner.warnings.len()
        )
    }
}

/// Read cross-sections from a `.csl` or `.json` file, validated and repaired (`strict`: refuse
/// instead of repairing).
#[pyfunction]
#[pyo3(signature = (path, strict = false))]
pub fn read(py: Python<'_>, path: PathBuf, strict: bool) -> PyResult<Sections> {
    py.detach(|| slice2solid::io::read_sections_with(&path, &ReadOptions { strict }))
        .map(|inner| Sections { inner })
        .map_err(|e| crate::py_err(py, e))
}

/// Cross-sections from arrays, in the JSON file's schema (README, "Input formats"): `planes` is a
/// list of dicts with `point` and `normal` (or `normal` and `offset`) and `contours`, a list of
/// dicts with `points` ((k, 3) array) or `points2d` ((k, 2), plane frame), `label` (default 1) and
/// `hole_of` (index of the outer contour, or None). Validated and repaired as files are; errors are
/// located as `SOURCE: planes[i].contours[j]...`.
#[pyfunction]
#[pyo3(signature = (planes, n_labels = 0, strict = false, source = "arrays"))]
pub fn sections_from_arrays(
    py: Python<'_>,
    planes: &Bound<'_, PyAny>,
    n_labels: usize,
    strict: bool,
    source: &str,
) -> PyResult<Sections> {
    let list: Vec<Bound<'_, PyAny>> = planes.extract().map_err(|_| {
        crate::input_err(
            py,
            &format!("{source}: planes"),
            "expected a list of plane dicts",
        )
    })?;
    let specs = list
        .iter()
        .enumerate()
        .map(|(pi, p)| section_spec(p, &format!("{source}: planes[{pi}]")))
        .collect::<PyResult<Vec<_>>>()?;
    let naming = Naming {
        source,
        root: "planes",
    };
    py.detach(|| build_sections(&specs, n_labels, &naming, &ReadOptions { strict }))
        .map(|inner| Sections { inner })
        .map_err(|e| crate::py_err(py, e))
}

/// `obj` as a dict with only `allowed` keys.
fn dict<'a, 'py>(
    obj: &'a Bound<'py, PyAny>,
    at: &str,
    allowed: &[&str],
) -> PyResult<&'a Bound<'py, PyDict>> {
    let py = obj.py();
    let d = obj
        .cast::<PyDict>()
        .map_err(|_| crate::input_err(py, at, "expected a dict"))?;
    for k in d.keys() {
        let k: String = k.str()?.to_string();
        if !allowed.contains(&k.as_str()) {
            return Err(crate::input_err(
                py,
                at,
                format!("unknown key \"{k}\" (allowed: {})", allowed.join(", ")),
            ));
        }
    }
    Ok(d)
}

fn section_spec(obj: &Bound<'_, PyAny>, at: &str) -> PyResult<SectionSpec> {
    let py = obj.py();
    let d = dict(obj, at, &["point", "normal", "offset", "contours"])?;
    let normal = match d.get_item("normal")? {
        Some(n) => vector_f64::<3>(&n, &format!("{at}.normal"))?,
        None => return Err(crate::input_err(py, at, "missing key \"normal\"")),
    };
    let plane = match (d.get_item("point")?, d.get_item("offset")?) {
        (Some(p), None) => PlaneSpec::PointNormal {
            point: vector_f64::<3>(&p, &format!("{at}.point"))?,
            normal,
        },
        (None, Some(o)) => PlaneSpec::Equation {
            normal,
            offset: o
                .extract()
                .map_err(|_| crate::input_err(py, &format!("{at}.offset"), "expected a number"))?,
        },
        _ => {
            return Err(crate::input_err(
                py,
                at,
                "give exactly one of \"point\" and \"offset\"",
            ))
        }
    };
    let contours = match d.get_item("contours")? {
        None => Vec::new(),
        Some(c) => {
            let list: Vec<Bound<'_, PyAny>> = c.extract().map_err(|_| {
                crate::input_err(
                    py,
                    &format!("{at}.contours"),
                    "expected a list of contour dicts",
                )
            })?;
            list.iter()
                .enumerate()
                .map(|(ci, c)| contour_spec(c, &format!("{at}.contours[{ci}]")))
                .collect::<PyResult<Vec<_>>>()?
        }
    };
    Ok(SectionSpec { plane, contours })
}

fn contour_spec(obj: &Bound<'_, PyAny>, at: &str) -> PyResult<ContourSpec> {
    let py = obj.py();
    let d = dict(obj, at, &["points", "points2d", "label", "hole_of"])?;
    let points = match (d.get_item("points")?, d.get_item("points2d")?) {
        (Some(p), None) => ContourPoints::Xyz(rows_f64::<3>(&p, &format!("{at}.points"))?),
        (None, Some(q)) => ContourPoints::Uv(rows_f64::<2>(&q, &format!("{at}.points2d"))?),
        _ => {
            return Err(crate::input_err(
                py,
                at,
                "give exactly one of \"points\" and \"points2d\"",
            ))
        }
    };
    let label = match d.get_item("label")? {
        None => 1,
        Some(l) => l
            .extract()
            .map_err(|_| crate::input_err(py, &format!("{at}.label"), "expected an integer"))?,
    };
    let hole_of = match d.get_item("hole_of")? {
        None => None,
        Some(h) if h.is_none() => None,
        Some(h) => Some(h.extract().map_err(|_| {
            crate::input_err(
                py,
                &format!("{at}.hole_of"),
                "expected a contour index or None",
            )
        })?),
    };
    Ok(ContourSpec {
        points,
        label,
        hole_of,
    })
}
