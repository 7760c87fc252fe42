//! Arrays in and out: numpy arrays (or anything numpy converts) into a [`Mesh`], checked
//! row by row, and meshes and JSON reports back into numpy arrays and Python objects.
//!
//! This is the boundary: every refusal names the row (vertex or triangle, from 0) and what
//! is wrong with it, as an `InvalidMeshError`. What [`Mesh::new`] checks itself (non-finite
//! coordinates, indices beyond the last vertex) keeps its message.

use envelope::{Error, Mesh};
use numpy::ndarray::Array2;
use numpy::{
    Element, IntoPyArray, PyArray2, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods,
    PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value;

use crate::errors::{Kind, from_error};

/// An `InvalidMeshError` with the library's prefix.
fn invalid(detail: String) -> PyErr {
    Kind::InvalidMesh.err(format!("invalid mesh: {detail}"))
}

/// A mesh from `vertices` (`(n, 3)`, anything `numpy.asarray(..., dtype=float64)` converts)
/// and `faces` (`(m, 3)`, any integer dtype). `name` prefixes the messages when a call takes
/// two meshes.
pub(crate) fn mesh(
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    name: Option<&str>,
) -> PyResult<Mesh> {
    let named = |e: PyErr| match name {
        Some(name) => {
            let py = vertices.py();
            PyErr::from_type(e.get_type(py), format!("{name}: {}", e.value(py)))
        }
        None => e,
    };
    let positions = positions(vertices).map_err(named)?;
    let triangles = triangles(faces, positions.len()).map_err(named)?;
    Mesh::new(positions, triangles)
        .map_err(|e| from_error(Error::InvalidMesh(e)))
        .map_err(named)
}

/// `numpy.asarray(obj, dtype)` (the dtype `None` keeps the array's own).
fn asarray<'py>(obj: &Bound<'py, PyAny>, dtype: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
    let numpy = obj.py().import("numpy")?;
    numpy.getattr("asarray")?.call1((obj, dtype))
}

/// Checks a `(rows, 3)` shape; `what` names the array and `rows` its row count.
fn check_shape(array: &Bound<'_, PyUntypedArray>, what: &str, rows: &str) -> PyResult<()> {
    let shape = array.shape();
    if shape.len() == 2 && shape[1] == 3 {
        return Ok(());
    }
    let shape = shape
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ");
    let comma = if array.ndim() == 1 { "," } else { "" };
    Err(invalid(format!(
        "{what} must have shape ({rows}, 3), got ({shape}{comma})"
    )))
}

fn positions(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[f64; 3]>> {
    let array = asarray(obj, Some("float64")).map_err(|e| {
        invalid(format!(
            "vertices cannot be read as float64 numbers: {}",
            e.value(obj.py())
        ))
    })?;
    let array = array.cast_into::<PyArrayDyn<f64>>()?;
    check_shape(array.as_untyped(), "vertices", "n")?;
    let view = array.readonly();
    Ok(view
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

fn triangles(obj: &Bound<'_, PyAny>, vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    let py = obj.py();
    let array = asarray(obj, None)
        .map_err(|e| invalid(format!("faces cannot be read as an array: {}", e.value(py))))?;
    let Ok(array) = array.cast_into::<PyUntypedArray>() else {
        return Err(invalid("faces cannot be read as an array".into()));
    };
    // `numpy.asarray([])` is a float array: no triangles, whatever its dtype.
    if array.len() == 0 && matches!(array.shape(), [0] | [0, 3]) {
        return Ok(Vec::new());
    }
    let rows = match array.dtype().kind() {
        b'i' => rows::<i64>(&array, "int64")?,
        b'u' => rows::<u64>(&array, "uint64")?,
        _ => {
            return Err(invalid(format!(
                "faces must be integers, got dtype {}",
                array.dtype()
            )));
        }
    };
    rows.into_iter()
        .enumerate()
        .map(|(t, row)| {
            let corners = || format!("[{}, {}, {}]", row[0], row[1], row[2]);
            if row.iter().any(|&i| i < 0) {
                return Err(invalid(format!(
                    "triangle {t} {} names a negative vertex index",
                    corners()
                )));
            }
            // Beyond u32 is beyond the last vertex too; Mesh::new reports the others.
            row.iter()
                .map(|&i| u32::try_from(i))
                .collect::<Result<Vec<u32>, _>>()
                .map(|v| [v[0], v[1], v[2]])
                .map_err(|_| {
                    invalid(format!(
                        "triangle {t} {} names a vertex beyond the last one ({vertices} vertices)",
                        corners()
                    ))
                })
        })
        .collect()
}

/// The rows of an integer `(m, 3)` array, cast to `T` (named `dtype` for numpy) and widened.
fn rows<T: Element + Copy + Into<i128>>(
    array: &Bound<'_, PyUntypedArray>,
    dtype: &str,
) -> PyResult<Vec<[i128; 3]>> {
    check_shape(array, "faces", "m")?;
    let cast = array.call_method1("astype", (dtype,))?;
    let cast = cast.cast_into::<PyArrayDyn<T>>()?;
    let view = cast.readonly();
    Ok(view
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0].into(), r[1].into(), r[2].into()])
        .collect())
}

/// The vertex positions as an `(n, 3)` float64 array.
pub(crate) fn vertices_array<'py>(py: Python<'py>, mesh: &Mesh) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = mesh.positions().flatten().collect();
    Array2::from_shape_vec((mesh.num_vertices(), 3), flat)
        .unwrap_or_else(|_| Array2::zeros((0, 3)))
        .into_pyarray(py)
}

/// The triangles as an `(m, 3)` int64 array.
pub(crate) fn faces_array<'py>(py: Python<'py>, mesh: &Mesh) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = mesh.triangles().flatten().map(i64::from).collect();
    Array2::from_shape_vec((mesh.num_faces(), 3), flat)
        .unwrap_or_else(|_| Array2::zeros((0, 3)))
        .into_pyarray(py)
}

/// A JSON value as plain Python objects (dicts, lists, numbers, strings, None).
pub(crate) fn json<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (None, Some(i)) => i.into_pyobject(py)?.into_any(),
            (None, None) => n.as_f64().into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(items) => PyList::new(
            py,
            items
                .iter()
                .map(|v| json(py, v))
                .collect::<PyResult<Vec<_>>>()?,
        )?
        .into_any(),
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, v) in map {
                dict.set_item(k, json(py, v)?)?;
            }
            dict.into_any()
        }
    })
}

/// A JSON object as a Python dict.
pub(crate) fn json_dict<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyDict>> {
    Ok(json(py, value)?.cast_into::<PyDict>()?)
}
