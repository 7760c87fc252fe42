//! Meshes in and out of files (OBJ, OFF, PLY, STL, by extension), and the built-in model.

use std::path::PathBuf;

use envelope::Mesh;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays;
use crate::errors::from_error;

/// The arrays of a mesh: `(n, 3)` float64 positions and `(m, 3)` int64 triangles.
type Arrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

fn to_arrays<'py>(py: Python<'py>, mesh: &Mesh) -> Arrays<'py> {
    (
        arrays::vertices_array(py, mesh),
        arrays::faces_array(py, mesh),
    )
}

/// Reads a mesh file.
#[pyfunction]
pub(crate) fn load(py: Python<'_>, path: PathBuf) -> PyResult<Arrays<'_>> {
    let mesh = py.detach(|| envelope::load(&path)).map_err(from_error)?;
    Ok(to_arrays(py, &mesh))
}

/// Writes a mesh file in the format its extension names, atomically.
#[pyfunction]
pub(crate) fn save(
    py: Python<'_>,
    path: PathBuf,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let mesh = arrays::mesh(vertices, faces, None)?;
    py.detach(|| envelope::save(&mesh, &path))
        .map_err(from_error)
}

/// The built-in model of `envelope demo`: a cup with a fluted wall, a sharp bottom crease and
/// an open rim.
#[pyfunction]
pub(crate) fn demo(py: Python<'_>) -> Arrays<'_> {
    to_arrays(py, &Mesh::demo())
}
