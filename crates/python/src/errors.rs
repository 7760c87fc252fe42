//! The exception classes and how the library's errors map onto them.
//!
//! The classes are made with Python's `type()` at first use rather than with
//! `create_exception!`: two of them also derive from `ValueError` (bad arguments are value
//! errors to Python code that catches those), and the macro takes a single base. The message
//! of every exception made from an [`envelope::Error`] is its `Display`, what the command line
//! prints after `envelope: error: `.

use envelope::Error;
use envelope::advanced::genus::GenusError;
use envelope::advanced::simplify::DriverError;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};

/// The exception classes of the package, in an order where each comes after its bases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Envelope,
    Input,
    Read,
    InvalidMesh,
    NotAcceptable,
    InvalidArgument,
    InvalidEpsilon,
    Simplify,
    Write,
    CertificateViolated,
    Cancelled,
}

/// A base of a class: another of ours, or one of Python's.
enum Base {
    Ours(Kind),
    Exception,
    ValueError,
}

impl Kind {
    const ALL: [Kind; 11] = [
        Kind::Envelope,
        Kind::Input,
        Kind::Read,
        Kind::InvalidMesh,
        Kind::NotAcceptable,
        Kind::InvalidArgument,
        Kind::InvalidEpsilon,
        Kind::Simplify,
        Kind::Write,
        Kind::CertificateViolated,
        Kind::Cancelled,
    ];

    /// The class name, its bases and its docstring.
    fn spec(self) -> (&'static str, &'static [Base], &'static str) {
        match self {
            Kind::Envelope => (
                "EnvelopeError",
                &[Base::Exception],
                "Base class of every error of the envelope package.",
            ),
            Kind::Input => (
                "InputError",
                &[Base::Ours(Kind::Envelope)],
                "The input mesh cannot be used (unreadable, invalid, or not acceptable).",
            ),
            Kind::Read => (
                "ReadError",
                &[Base::Ours(Kind::Input)],
                "A mesh file could not be read; the message names the file and the element.",
            ),
            Kind::InvalidMesh => (
                "InvalidMeshError",
                &[Base::Ours(Kind::Input), Base::ValueError],
                "Arrays that make no mesh: a wrong shape or dtype, a non-finite coordinate, or \
                 an index that is negative or out of range (the message names the row).",
            ),
            Kind::NotAcceptable => (
                "NotAcceptableError",
                &[Base::Ours(Kind::Input)],
                "The mesh has degeneracies the method refuses (see envelope.check).",
            ),
            Kind::InvalidArgument => (
                "InvalidArgumentError",
                &[Base::Ours(Kind::Envelope), Base::ValueError],
                "An argument out of its range or an unknown choice (the message names it).",
            ),
            Kind::InvalidEpsilon => (
                "InvalidEpsilonError",
                &[Base::Ours(Kind::InvalidArgument)],
                "An epsilon (or alpha) that cannot be parsed or is not a positive finite length.",
            ),
            Kind::Simplify => (
                "SimplifyError",
                &[Base::Ours(Kind::Envelope)],
                "The simplifier made no output, e.g. the envelopes could not be proved free of \
                 intersections (no output is made from unproved envelopes).",
            ),
            Kind::Write => (
                "WriteError",
                &[Base::Ours(Kind::Envelope)],
                "A mesh file could not be written (nothing was put in its place).",
            ),
            Kind::CertificateViolated => (
                "CertificateViolated",
                &[Base::Ours(Kind::Envelope)],
                "The output was made but its certificate found a violation. The output is in \
                 the attribute `result` (a Simplified) for inspection; it must not be used as a \
                 simplification within epsilon.",
            ),
            Kind::Cancelled => (
                "Cancelled",
                &[Base::Ours(Kind::Envelope)],
                "The progress callback returned False: the call stopped and made no output.",
            ),
        }
    }

    /// The class, made on first use.
    pub(crate) fn class(self, py: Python<'_>) -> PyResult<Bound<'_, PyType>> {
        static CLASSES: [PyOnceLock<Py<PyType>>; Kind::ALL.len()] =
            [const { PyOnceLock::new() }; Kind::ALL.len()];
        let cell = &CLASSES[self as usize];
        if let Some(class) = cell.get(py) {
            return Ok(class.bind(py).clone());
        }
        let (name, bases, doc) = self.spec();
        let bases = bases
            .iter()
            .map(|b| match b {
                Base::Ours(kind) => kind.class(py),
                Base::Exception => Ok(py.get_type::<PyException>()),
                Base::ValueError => Ok(py.get_type::<PyValueError>()),
            })
            .collect::<PyResult<Vec<_>>>()?;
        let namespace = PyDict::new(py);
        namespace.set_item("__module__", "envelope")?;
        namespace.set_item("__doc__", doc)?;
        let class = py
            .get_type::<PyType>()
            .call1((name, PyTuple::new(py, bases)?, namespace))?
            .cast_into::<PyType>()?;
        Ok(cell.get_or_init(py, || class.unbind()).bind(py).clone())
    }

    /// An exception of this class with `message`.
    pub(crate) fn err(self, message: impl Into<String>) -> PyErr {
        let message = message.into();
        Python::attach(|py| match self.class(py) {
            Ok(class) => PyErr::from_type(class, message),
            Err(e) => e,
        })
    }
}

/// Adds every class to the module under its name.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    for kind in Kind::ALL {
        m.add(kind.spec().0, kind.class(m.py())?)?;
    }
    Ok(())
}

/// The class of a library error.
fn kind_of(e: &Error) -> Kind {
    match e {
        Error::Read(_) => Kind::Read,
        Error::Write(_) => Kind::Write,
        Error::UnknownFormat(_) | Error::InvalidArgument(_) | Error::Manifest(_) => {
            Kind::InvalidArgument
        }
        Error::Repair(_) => Kind::NotAcceptable,
        Error::InvalidMesh(_) => Kind::InvalidMesh,
        Error::InvalidEpsilon(_)
        | Error::Simplify(DriverError::Epsilons(_))
        | Error::Genus(GenusError::InvalidAlpha(_)) => Kind::InvalidEpsilon,
        Error::Genus(GenusError::InvalidBeta(_)) => Kind::InvalidArgument,
        Error::Simplify(DriverError::Unacceptable(_)) | Error::Genus(_) => Kind::NotAcceptable,
        Error::Simplify(_) => Kind::Simplify,
        Error::Cancelled => Kind::Cancelled,
        Error::CertificateViolated(_) => Kind::CertificateViolated,
        _ => Kind::Envelope,
    }
}

/// The exception for a library error, its message the error's `Display`. A violated
/// certificate carries no `result` here: `simplify` attaches the output.
pub(crate) fn from_error(e: Error) -> PyErr {
    kind_of(&e).err(e.to_string())
}

/// [`Kind::CertificateViolated`] with the output attached as `result`.
pub(crate) fn violated(
    py: Python<'_>,
    message: String,
    result: Bound<'_, PyAny>,
) -> PyResult<PyErr> {
    let instance = Kind::CertificateViolated.class(py)?.call1((message,))?;
    instance.setattr("result", result)?;
    Ok(PyErr::from_value(instance))
}
