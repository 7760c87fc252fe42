//! `simplify`: the library's `Simplifier` on numpy arrays, with the GIL released, progress
//! and cancellation (see [`crate::progress`]).

use envelope::{Error, Simplifier};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{self, json_dict};
use crate::certificate::Certificate;
use crate::errors::{from_error, violated};
use crate::{options, progress};

/// What `simplify` made: the output arrays, the report and the certificate.
#[pyclass(frozen, module = "envelope")]
pub(crate) struct Simplified {
    /// Output vertex positions, `(n, 3)` float64.
    #[pyo3(get)]
    vertices: Py<PyArray2<f64>>,
    /// Output triangles, `(m, 3)` int64.
    #[pyo3(get)]
    faces: Py<PyArray2<i64>>,
    /// The command line's JSON report as a dict (counts, epsilons, envelopes, times).
    #[pyo3(get)]
    report: Py<PyDict>,
    /// The certificate against the input (`None` when `certify=False`).
    #[pyo3(get)]
    certificate: Option<Py<Certificate>>,
    /// Within epsilon both ways, no self-intersection, same topology: all proved.
    #[pyo3(get)]
    is_certified: bool,
    /// The names of the violated properties (empty unless certified and violated).
    #[pyo3(get)]
    violations: Vec<&'static str>,
}

#[pymethods]
impl Simplified {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "Simplified(vertices={}, faces={}, is_certified={})",
            self.vertices.bind(py).len().unwrap_or(0),
            self.faces.bind(py).len().unwrap_or(0),
            if self.is_certified { "True" } else { "False" }
        )
    }
}

impl Simplified {
    fn new(py: Python<'_>, done: &envelope::Simplified) -> PyResult<Self> {
        Ok(Simplified {
            vertices: arrays::vertices_array(py, done.mesh()).unbind(),
            faces: arrays::faces_array(py, done.mesh()).unbind(),
            report: json_dict(py, &done.report().to_json())?.unbind(),
            certificate: Certificate::py_option(py, done.certificate())?,
            is_certified: done.is_certified(),
            violations: done.violations(),
        })
    }
}

/// Simplifies `(vertices, faces)` within `epsilon`; `None` arguments take the library's
/// defaults (the Python layer passes them all).
#[pyfunction]
#[pyo3(signature = (
    vertices, faces, epsilon, *, placement=None, method=None, envelope=None,
    hole_filling=None, tube_segments, target_faces=None, certify=None,
    tolerance_phase=None, threads=None, progress=None,
))]
pub(crate) fn simplify(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    epsilon: &Bound<'_, PyAny>,
    placement: Option<&str>,
    method: Option<&str>,
    envelope: Option<&str>,
    hole_filling: Option<&str>,
    tube_segments: Option<i64>,
    target_faces: Option<i64>,
    certify: Option<bool>,
    tolerance_phase: Option<bool>,
    threads: Option<i64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Simplified> {
    let epsilon = options::epsilon(epsilon)?;
    let mut simplifier = Simplifier::new(epsilon)
        .placement(options::placement(placement)?)
        .method(options::method(method)?)
        .envelope_method(options::envelope_method(envelope)?)
        .hole_filling(options::hole_filling(hole_filling)?)
        .tube_segments(options::tube_segments(tube_segments)?);
    if let Some(n) = target_faces {
        simplifier = simplifier.target_faces(options::count("target_faces", n)?);
    }
    if let Some(certify) = certify {
        simplifier = simplifier.certify(certify);
    }
    if let Some(on) = tolerance_phase {
        simplifier = simplifier.tolerance_phase(on);
    }
    if let Some(n) = options::threads(threads) {
        simplifier = simplifier.threads(n);
    }
    let mesh = arrays::mesh(vertices, faces, None)?;
    let result = progress::run(py, progress, |watch| {
        simplifier.progress(|e| watch.tell(e)).run(&mesh)
    })?;
    match result {
        Ok(done) => Simplified::new(py, &done),
        Err(e) => {
            let message = e.to_string();
            match e {
                Error::CertificateViolated(done) => {
                    let result = Py::new(py, Simplified::new(py, &done)?)?;
                    Err(violated(py, message, result.into_bound(py).into_any())?)
                }
                e => Err(from_error(e)),
            }
        }
    }
}
