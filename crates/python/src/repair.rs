//! Repair that never moves the surface (`envelope::repair`), for arrays.

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays;
use crate::errors::from_error;

/// The repaired arrays and the report.
type Repaired<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyDict>,
);

/// Repairs a mesh without moving its surface; returns its arrays and the report as a dict
/// (`acceptable`, `left`, and every step's changes by input index).
#[pyfunction]
pub(crate) fn repair<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
) -> PyResult<Repaired<'py>> {
    let mesh = arrays::mesh(vertices, faces, None)?;
    let repaired = py.detach(|| envelope::repair(&mesh)).map_err(from_error)?;
    let report = arrays::json_dict(py, &repaired.to_json())?;
    Ok((
        arrays::vertices_array(py, repaired.mesh()),
        arrays::faces_array(py, repaired.mesh()),
        report,
    ))
}
