//! The oracles: `verify` (the certificate of any simplifier's output) and `check` (is a mesh
//! acceptable input), each run with the GIL released.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

use crate::arrays::{self, json};
use crate::certificate::Certificate;
use crate::errors::from_error;
use crate::options;

/// Certifies `(v1, f1)` against `(v0, f0)`; a relative epsilon is a part of the original's
/// diagonal. With `map`, the certificate carries the error map (`envelope verify --map`).
#[pyfunction]
#[pyo3(signature = (v0, f0, v1, f1, epsilon, *, map=false))]
pub(crate) fn verify(
    py: Python<'_>,
    v0: &Bound<'_, PyAny>,
    f0: &Bound<'_, PyAny>,
    v1: &Bound<'_, PyAny>,
    f1: &Bound<'_, PyAny>,
    epsilon: &Bound<'_, PyAny>,
    map: bool,
) -> PyResult<Certificate> {
    let epsilon = options::epsilon(epsilon)?;
    let orig = arrays::mesh(v0, f0, Some("v0, f0"))?;
    let approx = arrays::mesh(v1, f1, Some("v1, f1"))?;
    let certificate = py
        .detach(|| {
            if map {
                envelope::verify_with_map(&orig, &approx, epsilon)
            } else {
                envelope::verify(&orig, &approx, epsilon)
            }
        })
        .map_err(from_error)?;
    Certificate::new(py, &certificate)
}

/// Every degeneracy class of section 7.1 with its elements, and the topology counts.
#[pyclass(frozen, module = "envelope")]
pub(crate) struct CheckReport {
    /// The mesh is acceptable input for the simplifier (no class of error severity).
    #[pyo3(get)]
    acceptable: bool,
    /// Vertex slots, referenced or not.
    #[pyo3(get)]
    vertices: usize,
    /// Triangles.
    #[pyo3(get)]
    faces: usize,
    /// Undirected edges.
    #[pyo3(get)]
    edges: usize,
    /// Border loops (closed cycles and open chains).
    #[pyo3(get)]
    border_loops: usize,
    /// Edge-connected components.
    #[pyo3(get)]
    components: usize,
    /// Euler characteristic summed over components.
    #[pyo3(get)]
    euler: i64,
    /// Genus summed over components (`None` when non-manifold or non-orientable).
    #[pyo3(get)]
    genus: Option<u32>,
    /// No non-manifold edge or vertex.
    #[pyo3(get)]
    manifold: bool,
    /// Every component orientable.
    #[pyo3(get)]
    orientable: bool,
    json: Value,
}

#[pymethods]
impl CheckReport {
    /// Every class by its key: `{"count", "severity", "examples", "undecided"}`.
    #[getter]
    fn degeneracies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json(py, &self.json["degeneracies"])
    }

    /// The classes with elements (count above 0), by key, with their counts.
    #[getter]
    fn problems<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        if let Value::Object(classes) = &self.json["degeneracies"] {
            for (key, finding) in classes {
                if let Some(n) = finding["count"].as_u64().filter(|&n| n > 0) {
                    d.set_item(key, n)?;
                }
            }
        }
        Ok(d)
    }

    /// The report as the command line's `check --json` (without the file fields).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        arrays::json_dict(py, &self.json)
    }

    fn __repr__(&self) -> String {
        format!(
            "CheckReport(acceptable={}, vertices={}, faces={}, genus={:?})",
            if self.acceptable { "True" } else { "False" },
            self.vertices,
            self.faces,
            self.genus
        )
    }
}

/// Whether a mesh is acceptable input, with every degeneracy class.
#[pyfunction]
pub(crate) fn check(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
) -> PyResult<CheckReport> {
    let mesh = arrays::mesh(vertices, faces, None)?;
    let r = py.detach(|| envelope::check(&mesh));
    Ok(CheckReport {
        acceptable: r.acceptable(),
        vertices: r.vertices,
        faces: r.faces,
        edges: r.edges,
        border_loops: r.border_loops,
        components: r.components,
        euler: r.euler,
        genus: r.genus,
        manifold: r.manifold,
        orientable: r.orientable,
        json: r.to_json(),
    })
}
