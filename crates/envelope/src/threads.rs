//! Where the work runs: a pool of the requested size, or rayon's global pool.

use crate::Error;

/// Runs `work` on a thread of a pool with `threads` workers (`None`: rayon's global pool,
/// one per core unless `RAYON_NUM_THREADS` says otherwise). The work starts on a worker, not
/// on the caller's thread: each batch of parallel work then wakes the others without putting
/// the caller to sleep and waking it again.
///
/// # Errors
/// [`Error::InvalidArgument`] for 0 threads, [`Error::Threads`] when the pool cannot be built.
pub fn run<T: Send>(threads: Option<usize>, work: impl FnOnce() -> T + Send) -> Result<T, Error> {
    match threads {
        Some(0) => Err(Error::InvalidArgument("threads must be at least 1".into())),
        Some(n) => Ok(pool(n)?.install(work)),
        None if rayon::current_thread_index().is_some() => Ok(work()),
        None => Ok(rayon::scope(|_| work())),
    }
}

/// A pool of `threads` workers.
///
/// # Errors
/// As [`run`].
pub(crate) fn pool(threads: usize) -> Result<rayon::ThreadPool, Error> {
    if threads == 0 {
        return Err(Error::InvalidArgument("threads must be at least 1".into()));
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Threads(e.to_string()))
}
