//! The certificate as Python objects: the verdict, the certified bounds of the one-sided
//! Hausdorff distances both ways with their witnesses, the self-intersections and the
//! topology, named as `envelope::Certificate` names them.

use envelope::{Verdict, Witness as RustWitness};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

use crate::arrays::{json, json_dict};

/// A point exactly on a face of one mesh, proved farther than epsilon from the other.
#[pyclass(frozen, get_all, module = "envelope")]
pub(crate) struct Witness {
    /// The face the point lies on (from 0).
    face: usize,
    /// The point, rounded to float64 unless `point_is_exact`.
    point: (f64, f64, f64),
    /// Whether `point` is the witness exactly.
    point_is_exact: bool,
    /// The point is `(b0 a + b1 b + b2 c) / 2**denominator_log2` for the face's corners.
    barycentric: (u64, u64, u64),
    /// See `barycentric`.
    denominator_log2: u32,
    /// A proved lower bound of its distance to the other mesh (at least epsilon).
    distance_at_least: f64,
}

#[pymethods]
impl Witness {
    fn __repr__(&self) -> String {
        format!(
            "Witness(face={}, point={:?}, distance_at_least={})",
            self.face, self.point, self.distance_at_least
        )
    }
}

impl Witness {
    fn new(w: &RustWitness) -> Self {
        let [b0, b1, b2] = w.barycentric;
        Witness {
            face: w.face.index(),
            point: (w.point.x, w.point.y, w.point.z),
            point_is_exact: w.exact_f64,
            barycentric: (b0, b1, b2),
            denominator_log2: w.level,
            distance_at_least: w.distance,
        }
    }
}

/// One direction: is every point of the first mesh within epsilon of the second?
#[pyclass(frozen, get_all, module = "envelope")]
pub(crate) struct OneSided {
    /// `"holds"`, `"violated"` or `"undecided"`.
    verdict: &'static str,
    /// Proved lower bound of the one-sided Hausdorff distance.
    lower: f64,
    /// Proved upper bound (refined only as far as the decision needed: at most epsilon
    /// when it holds; infinite when unchecked).
    upper: f64,
    /// The farthest witness found, when violated.
    witness: Option<Py<Witness>>,
    /// Sub-triangles left undecided at the resolution.
    undecided_regions: usize,
    /// Sub-triangles examined.
    subdivisions: u64,
}

#[pymethods]
impl OneSided {
    fn __repr__(&self) -> String {
        format!(
            "OneSided(verdict='{}', lower={}, upper={})",
            self.verdict, self.lower, self.upper
        )
    }
}

impl OneSided {
    fn new(py: Python<'_>, s: &envelope::OneSided) -> PyResult<Self> {
        Ok(OneSided {
            verdict: s.verdict.as_str(),
            lower: s.lower,
            upper: s.upper,
            witness: s
                .witness
                .as_ref()
                .map(|w| Py::new(py, Witness::new(w)))
                .transpose()?,
            undecided_regions: s.undecided_regions,
            subdivisions: s.subdivisions,
        })
    }
}

/// The certificate of an approximation against its original: within epsilon both ways
/// (exact branch and bound), no self-intersection, the same genus, components and border
/// loops. `verdict` is `"violated"` if any property is, else `"undecided"` if any is, else
/// `"holds"`.
#[pyclass(frozen, module = "envelope")]
pub(crate) struct Certificate {
    /// `"holds"`, `"violated"` or `"undecided"`.
    #[pyo3(get)]
    verdict: &'static str,
    /// Every checked property is proved.
    #[pyo3(get)]
    holds: bool,
    /// The tolerance (absolute).
    #[pyo3(get)]
    epsilon: f64,
    /// Refinement stops where the bounds are closer than this (absolute).
    #[pyo3(get)]
    resolution: f64,
    /// The original's bounding-box diagonal.
    #[pyo3(get)]
    diagonal: f64,
    /// Every point of the approximation within epsilon of the original?
    #[pyo3(get)]
    approx_to_orig: Py<OneSided>,
    /// Every point of the original within epsilon of the approximation? (`None` when only
    /// the one direction was checked.)
    #[pyo3(get)]
    orig_to_approx: Option<Py<OneSided>>,
    /// Intersecting face pairs `(i, j)` of the approximation (`None`: not checked).
    #[pyo3(get)]
    self_intersections: Option<Vec<(usize, usize)>>,
    /// Whether `self_intersections` lists every pair.
    #[pyo3(get)]
    self_intersections_complete: bool,
    /// Too many overlapping face pairs to decide whether any intersects.
    #[pyo3(get)]
    self_intersections_undecided: bool,
    /// Intersecting face pairs of the approximation made of two unchanged faces of the
    /// original that met there already (allowed: what simplifying a self-intersecting input
    /// keeps; not in `self_intersections`).
    #[pyo3(get)]
    kept_intersections: Vec<(usize, usize)>,
    /// The names of the violated properties (`approx_to_orig`, `orig_to_approx`,
    /// `self_intersections`, `topology`).
    #[pyo3(get)]
    violations: Vec<&'static str>,
    /// The certificate as JSON, for `to_dict`, `topology` and `hausdorff`.
    json: Value,
}

#[pymethods]
impl Certificate {
    /// The two-sided Hausdorff distance's certified bounds `(lower, upper)` (`None` when only
    /// one direction was checked; `upper` is `None` when unbounded).
    #[getter]
    fn hausdorff<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match &self.json["hausdorff"] {
            Value::Null => Ok(py.None().into_bound(py)),
            h => Ok((json(py, &h["lower"])?, json(py, &h["upper"])?)
                .into_pyobject(py)?
                .into_any()),
        }
    }

    /// The error map (`verify(..., map=True)`, else `None`): a dict with, per face of the
    /// approximation, the certified `upper` and `lower` bounds of its distance to the
    /// original, the same per face of the original, and per vertex of the approximation the
    /// largest upper bound of its faces (`None` for an unbounded value), as the command
    /// line's JSON `map`.
    #[getter]
    fn error_map<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json(py, &self.json["map"])
    }

    /// Genus, components and border loops of both meshes and whether they match (a dict
    /// with `orig`, `approx`, `matches`; `None` when not checked).
    #[getter]
    fn topology<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json(py, &self.json["topology"])
    }

    /// Everything, as the command line's JSON (stable keys; relative values over the
    /// original's diagonal; at most 100 intersecting pairs).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        json_dict(py, &self.json)
    }

    fn __repr__(&self) -> String {
        format!(
            "Certificate(verdict='{}', epsilon={}, violations=[{}])",
            self.verdict,
            self.epsilon,
            self.violations
                .iter()
                .map(|v| format!("'{v}'"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

impl Certificate {
    pub(crate) fn new(py: Python<'_>, c: &envelope::Certificate) -> PyResult<Self> {
        Ok(Certificate {
            verdict: c.verdict.as_str(),
            holds: c.verdict == Verdict::Holds,
            epsilon: c.epsilon,
            resolution: c.resolution,
            diagonal: c.diagonal,
            approx_to_orig: Py::new(py, OneSided::new(py, &c.approx_to_orig)?)?,
            orig_to_approx: if c.two_sided {
                Some(Py::new(py, OneSided::new(py, &c.orig_to_approx)?)?)
            } else {
                None
            },
            self_intersections: c
                .self_intersections
                .as_ref()
                .map(|pairs| pairs.iter().map(|(a, b)| (a.index(), b.index())).collect()),
            self_intersections_complete: c.self_intersections_complete,
            self_intersections_undecided: c.self_intersections_undecided,
            kept_intersections: c
                .kept_intersections
                .iter()
                .map(|(a, b)| (a.index(), b.index()))
                .collect(),
            violations: c.violations(),
            json: c.to_json(),
        })
    }

    /// As a Python object (`None` stays `None`).
    pub(crate) fn py_option(
        py: Python<'_>,
        c: Option<&envelope::Certificate>,
    ) -> PyResult<Option<Py<Certificate>>> {
        c.map(|c| Py::new(py, Certificate::new(py, c)?)).transpose()
    }
}
