//! Long calls without the GIL, with progress and cancellation.
//!
//! The work runs on a thread of its own with the GIL released, while the calling thread
//! waits for it and, every [`POLL`], takes the GIL to run Python's signal handlers
//! (`Python::check_signals`). The polling is on the calling thread because Python runs
//! signal handlers only on its main thread: the library's progress callback is called on a
//! worker of the thread pool, where checking signals would see nothing, so Ctrl-C would go
//! unnoticed until the call ended.
//!
//! Either way of stopping sets one flag that the library's callback answers with
//! [`ControlFlow::Break`]; the library then ends with `Error::Cancelled` at its next check.
//! An exception raised meanwhile (the `KeyboardInterrupt` of a signal handler, or one from
//! the user's callback) is kept and re-raised in place of any result: a Ctrl-C during the
//! last stage still interrupts.

use std::ops::ControlFlow;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use envelope::{Event, Stage};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::from_error;

/// How often the waiting thread looks for signals.
const POLL: Duration = Duration::from_millis(25);

/// What a running call shares between the work, its callback and the waiting thread.
pub(crate) struct Watch {
    callback: Option<Py<PyAny>>,
    stop: AtomicBool,
    error: Mutex<Option<PyErr>>,
}

impl Watch {
    /// The library's progress callback: tells the user's callback (with the GIL), and
    /// answers `Break` once anything asked to stop.
    pub(crate) fn tell(&self, event: Event) -> ControlFlow<()> {
        if !self.stop.load(Ordering::Relaxed)
            && let Some(callback) = &self.callback
        {
            match Python::attach(|py| call(py, callback, event)) {
                Ok(true) => {}
                Ok(false) => self.stop.store(true, Ordering::Relaxed),
                Err(e) => self.fail(e),
            }
        }
        if self.stop.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    /// Asks the work to stop (as a callback returning `False` does).
    pub(crate) fn stop(&self) {
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Whether anything asked the work to stop.
    pub(crate) fn stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// Keeps the first exception and asks the work to stop.
    pub(crate) fn fail(&self, e: PyErr) {
        let mut slot = self.error.lock().unwrap_or_else(|p| p.into_inner());
        slot.get_or_insert(e);
        self.stop.store(true, Ordering::Relaxed);
    }

    fn take_error(&self) -> Option<PyErr> {
        self.error.lock().unwrap_or_else(|p| p.into_inner()).take()
    }
}

/// Calls the user's callback with the event as a dict: `False` (or anything false but
/// `None`) asks to stop.
fn call(py: Python<'_>, callback: &Py<PyAny>, event: Event) -> PyResult<bool> {
    let answer = callback.bind(py).call1((event_dict(py, event)?,))?;
    Ok(answer.is_none() || answer.is_truthy()?)
}

/// An event as the dict the Python callback receives: `kind` is `"level"`, `"stage"` or
/// `"removed"`, with the event's fields.
fn event_dict(py: Python<'_>, event: Event) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    match event {
        Event::Level { index, count } => {
            d.set_item("kind", "level")?;
            d.set_item("index", index)?;
            d.set_item("count", count)?;
        }
        Event::Stage(stage) => {
            d.set_item("kind", "stage")?;
            let name = match stage {
                Stage::Check => "check",
                Stage::Envelopes => "envelopes",
                Stage::Simplify { vertices } => {
                    d.set_item("vertices", vertices)?;
                    "simplify"
                }
                Stage::Verify => "verify",
            };
            d.set_item("stage", name)?;
        }
        Event::Removed { attempts, removed } => {
            d.set_item("kind", "removed")?;
            d.set_item("attempts", attempts)?;
            d.set_item("removed", removed)?;
        }
        other => {
            d.set_item("kind", "other")?;
            d.set_item("description", format!("{other:?}"))?;
        }
    }
    Ok(d)
}

/// Runs `work` with the GIL released, handing it the [`Watch`] whose `tell` is its progress
/// callback. The outer error is a Python exception raised while it ran (it wins over the
/// result); the inner result is the library's.
pub(crate) fn run<T: Send>(
    py: Python<'_>,
    callback: Option<Py<PyAny>>,
    work: impl FnOnce(&Watch) -> T + Send,
) -> PyResult<T> {
    if let Some(callback) = &callback
        && !callback.bind(py).is_callable()
    {
        return Err(from_error(envelope::Error::InvalidArgument(format!(
            "progress must be callable or None, got {}",
            callback.bind(py).get_type().name()?
        ))));
    }
    let watch = Watch {
        callback,
        stop: AtomicBool::new(false),
        error: Mutex::new(None),
    };
    let result = py.detach(|| {
        std::thread::scope(|scope| {
            let (sender, receiver) = mpsc::channel();
            let watch = &watch;
            scope.spawn(move || {
                // The receiver is gone only when the waiting thread has stopped waiting.
                let _ = sender.send(work(watch));
            });
            loop {
                match receiver.recv_timeout(POLL) {
                    Ok(result) => break Some(result),
                    Err(mpsc::RecvTimeoutError::Timeout) => {
                        if let Err(e) = Python::attach(|py| py.check_signals()) {
                            watch.fail(e);
                        }
                    }
                    // The work panicked: the scope re-raises the panic when it ends.
                    Err(mpsc::RecvTimeoutError::Disconnected) => break None,
                }
            }
        })
    });
    match (watch.take_error(), result) {
        (Some(e), _) => Err(e),
        (None, Some(result)) => Ok(result),
        (None, None) => Err(pyo3::exceptions::PyRuntimeError::new_err(
            "the work stopped without a result",
        )),
    }
}
