//! Batch runs for `envelope.batch` (`python/envelope/batch.py`): the command line's
//! `envelope::batch`, item for item. The Python engines only decide where items run; every
//! file is written here, so the local and Ray engines make the same files.

use std::ops::ControlFlow;

use envelope::Epsilon;
use envelope::batch::{Batch, Item, Outcome, Schedule, Shard};
use pyo3::prelude::*;

use crate::{errors, options, progress};

/// An outcome as Python receives it: its summary line, whether it is final, whether this
/// run did the work.
type Line = (String, bool, bool);

fn line(o: &Outcome) -> Line {
    (o.to_json_line(), o.is_final(), o.ran)
}

fn open(
    py: Python<'_>,
    manifest: &str,
    outdir: &str,
    epsilon: Option<&Bound<'_, PyAny>>,
) -> PyResult<Batch> {
    let epsilon: Option<Epsilon> = epsilon
        .filter(|e| !e.is_none())
        .map(options::epsilon)
        .transpose()?;
    py.detach(|| Batch::open_with(manifest, outdir, epsilon))
        .map_err(errors::from_error)
}

/// The item `id` of `batch`, or an `InvalidArgumentError` naming the manifest.
fn named<'b>(batch: &'b Batch, id: &str) -> PyResult<&'b Item> {
    batch.item(id).ok_or_else(|| {
        errors::Kind::InvalidArgument.err(format!(
            "{}: no item has the id {id:?}",
            batch.manifest().display()
        ))
    })
}

fn shard(given: Option<&str>) -> PyResult<Option<Shard>> {
    given
        .map(|s| s.parse().map_err(errors::from_error))
        .transpose()
}

/// The ids of the items of `shard`, after checking every manifest line and making the
/// output folder.
#[pyfunction]
#[pyo3(signature = (manifest, outdir, epsilon=None, shard=None))]
pub(crate) fn batch_items(
    py: Python<'_>,
    manifest: &str,
    outdir: &str,
    epsilon: Option<&Bound<'_, PyAny>>,
    shard: Option<&str>,
) -> PyResult<Vec<String>> {
    let batch = open(py, manifest, outdir, epsilon)?;
    let shard = self::shard(shard)?;
    Ok(batch.shard(shard).map(|i| i.id.clone()).collect())
}

/// Runs the item `item` on a pool of `threads` (or reuses its final result).
#[pyfunction]
#[pyo3(signature = (manifest, outdir, epsilon, item, threads=None))]
pub(crate) fn batch_run_item(
    py: Python<'_>,
    manifest: &str,
    outdir: &str,
    epsilon: Option<&Bound<'_, PyAny>>,
    item: &str,
    threads: Option<i64>,
) -> PyResult<Line> {
    let batch = open(py, manifest, outdir, epsilon)?;
    let item = named(&batch, item)?;
    let threads = options::threads(threads);
    let outcome = progress::run(py, None, |_| {
        envelope::advanced::in_pool(threads, || batch.run_item(item))
    })?
    .map_err(errors::from_error)?;
    Ok(line(&outcome))
}

/// Runs the items of `shard`, `threads / threads_per_item` at a time; `on_item(line, final,
/// ran)` hears each, and returning False cancels, as does Ctrl-C.
#[pyfunction]
#[pyo3(signature = (manifest, outdir, epsilon=None, shard=None, threads=None, threads_per_item=None, on_item=None))]
pub(crate) fn batch_run(
    py: Python<'_>,
    manifest: &str,
    outdir: &str,
    epsilon: Option<&Bound<'_, PyAny>>,
    shard: Option<&str>,
    threads: Option<i64>,
    threads_per_item: Option<i64>,
    on_item: Option<Py<PyAny>>,
) -> PyResult<Vec<Line>> {
    let batch = open(py, manifest, outdir, epsilon)?;
    let schedule = Schedule {
        shard: self::shard(shard)?,
        threads: options::threads(threads),
        threads_per_item: options::threads(threads_per_item),
    };
    let outcomes = progress::run(py, None, |watch| {
        let tell = |o: &Outcome| {
            if let Some(callback) = on_item.as_ref().filter(|_| !watch.stopped()) {
                let (text, final_, ran) = line(o);
                let answer = Python::attach(|py| {
                    callback
                        .bind(py)
                        .call1((text, final_, ran))
                        .and_then(|a| a.is_truthy())
                });
                match answer {
                    Ok(true) => {}
                    Ok(false) => watch.stop(),
                    Err(e) => watch.fail(e),
                }
            }
            if watch.stopped() {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        batch.run(schedule, &tell)
    })?
    .map_err(errors::from_error)?;
    Ok(outcomes.iter().map(line).collect())
}

/// Rewrites `summary.jsonl` from the final results on disk, with `transient` (this run's
/// unrecorded failures, as summary lines) in their places; returns its lines.
#[pyfunction]
#[pyo3(signature = (manifest, outdir, epsilon, transient))]
pub(crate) fn batch_summary(
    py: Python<'_>,
    manifest: &str,
    outdir: &str,
    epsilon: Option<&Bound<'_, PyAny>>,
    transient: Vec<String>,
) -> PyResult<Vec<String>> {
    let batch = open(py, manifest, outdir, epsilon)?;
    let transient = transient
        .iter()
        .map(|l| serde_json::from_str::<Outcome>(l))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| errors::Kind::InvalidArgument.err(format!("a summary line: {e}")))?;
    let lines = py
        .detach(|| batch.write_summary(&transient))
        .map_err(errors::from_error)?;
    Ok(lines.iter().map(Outcome::to_json_line).collect())
}

/// The summary line of an item whose task was lost for good (`failed`, retried next time).
#[pyfunction]
pub(crate) fn batch_lost(
    py: Python<'_>,
    manifest: &str,
    outdir: &str,
    epsilon: Option<&Bound<'_, PyAny>>,
    item: &str,
    message: String,
) -> PyResult<String> {
    let batch = open(py, manifest, outdir, epsilon)?;
    let item = named(&batch, item)?;
    Ok(Outcome::lost(item, message).to_json_line())
}

/// Registers the functions on the compiled module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(batch_items, m)?)?;
    m.add_function(wrap_pyfunction!(batch_run_item, m)?)?;
    m.add_function(wrap_pyfunction!(batch_run, m)?)?;
    m.add_function(wrap_pyfunction!(batch_summary, m)?)?;
    m.add_function(wrap_pyfunction!(batch_lost, m)?)?;
    Ok(())
}
