//! Levels of detail (Cohen et al. 7.2) and genus reduction (El-Sana and Varshney 1997) on
//! numpy arrays.

use envelope::{Genus, Lod};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

use crate::arrays::{self, json_dict};
use crate::certificate::Certificate;
use crate::errors::from_error;
use crate::{options, progress};

/// One level of detail (level 0, the input, is not listed).
#[pyclass(frozen, module = "envelope")]
pub(crate) struct Level {
    /// 1, 2, ...
    #[pyo3(get)]
    index: usize,
    /// Vertex positions, `(n, 3)` float64 (a subset of the previous level's).
    #[pyo3(get)]
    vertices: Py<PyArray2<f64>>,
    /// Triangles, `(m, 3)` int64.
    #[pyo3(get)]
    faces: Py<PyArray2<i64>>,
    /// The requested epsilon (absolute).
    #[pyo3(get)]
    epsilon: f64,
    /// The epsilon of this step's envelopes, around the previous level.
    #[pyo3(get)]
    step: f64,
    /// The bound to the original, both ways.
    #[pyo3(get)]
    bound: f64,
    /// The viewing distance from which this level may be shown.
    #[pyo3(get)]
    switching_distance: f64,
    /// The step's report (its input is the previous level), as a dict.
    #[pyo3(get)]
    report: Py<PyDict>,
    /// This level against the original at `bound` (`None` when `certify=False`).
    #[pyo3(get)]
    certificate: Option<Py<Certificate>>,
    /// The certificate holds.
    #[pyo3(get)]
    is_certified: bool,
    /// Which faces of the level before each face covers (Cohen et al. 8.1), as the command
    /// line's `correspondence-K.json` (`covers`, `by_nearest`, `error`, ...); `None` unless
    /// asked for with `correspondences=True`.
    #[pyo3(get)]
    correspondence: Option<Py<PyDict>>,
    json: Value,
}

#[pymethods]
impl Level {
    /// The level as the command line's `summary.json` lists it.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        json_dict(py, &self.json)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "Level(index={}, faces={}, bound={}, switching_distance={})",
            self.index,
            self.faces.bind(py).len().unwrap_or(0),
            self.bound,
            self.switching_distance
        )
    }
}

/// A chain of levels of detail with nested vertex sets; `None` arguments take the library's
/// defaults.
#[pyfunction]
#[pyo3(signature = (
    vertices, faces, epsilons, *, rule=None, envelope=None, hole_filling=None, certify=None,
    pixels=None, resolution=None, fov_degrees=None, correspondences=None, threads=None,
    progress=None,
))]
pub(crate) fn lod(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    epsilons: &Bound<'_, PyAny>,
    rule: Option<&str>,
    envelope: Option<&str>,
    hole_filling: Option<&str>,
    certify: Option<bool>,
    pixels: Option<f64>,
    resolution: Option<f64>,
    fov_degrees: Option<f64>,
    correspondences: Option<bool>,
    threads: Option<i64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Vec<Level>> {
    let mut chain = Lod::new(options::epsilons(epsilons)?)
        .rule(options::lod_rule(rule)?)
        .envelope_method(options::envelope_method(envelope)?)
        .hole_filling(options::hole_filling(hole_filling)?)
        .screen(options::screen(pixels, resolution, fov_degrees)?);
    if let Some(certify) = certify {
        chain = chain.certify(certify);
    }
    if let Some(on) = correspondences {
        chain = chain.correspondences(on);
    }
    if let Some(n) = options::threads(threads) {
        chain = chain.threads(n);
    }
    let mesh = arrays::mesh(vertices, faces, None)?;
    let levels = progress::run(py, progress, |watch| {
        chain.progress(|e| watch.tell(e)).run(&mesh)
    })?
    .map_err(from_error)?;
    let diagonal = mesh.diagonal();
    levels
        .iter()
        .map(|l| {
            let out = envelope::Mesh::from_soup(l.mesh.clone());
            let certificate = l.certified.as_ref().map(|v| &v.certificate);
            Ok(Level {
                index: l.index,
                vertices: arrays::vertices_array(py, &out).unbind(),
                faces: arrays::faces_array(py, &out).unbind(),
                epsilon: l.requested,
                step: l.step,
                bound: l.cumulative,
                switching_distance: l.switching_distance,
                report: json_dict(py, &l.report.to_json())?.unbind(),
                certificate: Certificate::py_option(py, certificate)?,
                is_certified: certificate.is_some_and(envelope::Certificate::holds),
                correspondence: l
                    .correspondence
                    .as_ref()
                    .map(|c| json_dict(py, &c.to_json()).map(Bound::unbind))
                    .transpose()?,
                json: l.to_json(diagonal),
            })
        })
        .collect()
}

/// What `genus` made: the output arrays, the report and the added triangles.
#[pyclass(frozen, module = "envelope")]
pub(crate) struct GenusResult {
    /// Output vertex positions, `(n, 3)` float64.
    #[pyo3(get)]
    vertices: Py<PyArray2<f64>>,
    /// Output triangles, `(m, 3)` int64.
    #[pyo3(get)]
    faces: Py<PyArray2<i64>>,
    /// The command line's JSON report as a dict (genus in and out, holes filled, ...).
    #[pyo3(get)]
    report: Py<PyDict>,
    /// The triangles the caps added, as rows of `faces`.
    #[pyo3(get)]
    added_faces: Vec<usize>,
}

#[pymethods]
impl GenusResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "GenusResult(faces={}, added_faces={})",
            self.faces.bind(py).len().unwrap_or(0),
            self.added_faces.len()
        )
    }
}

/// Fills the holes and tunnels an L-infinity cube of side `2 alpha` cannot pass; `None`
/// arguments take the library's defaults.
#[pyfunction]
#[pyo3(signature = (vertices, faces, alpha, *, beta_degrees=None, source=None, threads=None))]
pub(crate) fn genus(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    alpha: &Bound<'_, PyAny>,
    beta_degrees: Option<f64>,
    source: Option<&str>,
    threads: Option<i64>,
) -> PyResult<GenusResult> {
    let mut reduction =
        Genus::new(options::epsilon(alpha)?).source(options::tessellation_source(source)?);
    if let Some(beta) = beta_degrees {
        reduction = reduction.beta_degrees(beta);
    }
    if let Some(n) = options::threads(threads) {
        reduction = reduction.threads(n);
    }
    let mesh = arrays::mesh(vertices, faces, None)?;
    let (out, report) = py.detach(|| reduction.run(&mesh)).map_err(from_error)?;
    Ok(GenusResult {
        vertices: arrays::vertices_array(py, &out).unbind(),
        faces: arrays::faces_array(py, &out).unbind(),
        report: json_dict(py, &report.to_json())?.unbind(),
        added_faces: report.added_faces.iter().map(|f| f.index()).collect(),
    })
}
