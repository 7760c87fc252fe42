//! The Python package `envelope`: a thin layer over the library's front door (`envelope`).
//!
//! This is the compiled module `envelope._envelope`; the public functions, their defaults
//! (read from here: `options::defaults_dict`) and their docstrings are in
//! `python/envelope/__init__.py`. Every call validates its arrays at the boundary
//! (`arrays`), releases the GIL for the library's work, and maps the library's errors onto
//! exception classes whose messages are the library's `Display` (`errors`).
//!
//! * `arrays`: numpy arrays in and out, JSON reports as dicts.
//! * `errors`: the exception classes.
//! * `options`: epsilons, named choices, counts, defaults.
//! * `progress`: the GIL released, progress callbacks, cancellation and Ctrl-C.
//! * `simplify`, `oracle` (verify, check), `chains` (lod, genus), `files`.
//! * `repair`: repair that never moves the surface.
//! * `batch`: the natives under `envelope.batch` (manifests, items, summaries).
#![forbid(unsafe_code)]

mod arrays;
mod batch;
mod certificate;
mod chains;
mod errors;
mod files;
mod options;
mod oracle;
mod progress;
mod repair;
mod simplify;

use pyo3::prelude::*;

/// The compiled module.
#[pymodule]
fn _envelope(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULTS", options::defaults_dict(m.py())?)?;
    errors::register(m)?;

    m.add_function(wrap_pyfunction!(simplify::simplify, m)?)?;
    m.add_class::<simplify::Simplified>()?;

    m.add_function(wrap_pyfunction!(oracle::verify, m)?)?;
    m.add_function(wrap_pyfunction!(oracle::check, m)?)?;
    m.add_class::<certificate::Certificate>()?;
    m.add_class::<certificate::OneSided>()?;
    m.add_class::<certificate::Witness>()?;
    m.add_class::<oracle::CheckReport>()?;

    m.add_function(wrap_pyfunction!(chains::lod, m)?)?;
    m.add_function(wrap_pyfunction!(chains::genus, m)?)?;
    m.add_class::<chains::Level>()?;
    m.add_class::<chains::GenusResult>()?;

    m.add_function(wrap_pyfunction!(files::load, m)?)?;
    m.add_function(wrap_pyfunction!(files::save, m)?)?;
    m.add_function(wrap_pyfunction!(files::demo, m)?)?;
    m.add_function(wrap_pyfunction!(repair::repair, m)?)?;

    // The natives of `envelope.batch` (python/envelope/batch.py).
    batch::register(m)?;

    Ok(())
}
