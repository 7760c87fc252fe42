//! Batch runs: many meshes from a manifest, as the 1996 paper simplified the 2,636 objects
//! of a submarine's machine room with epsilon a part of each object's diagonal.
//!
//! The choices:
//! * **Layout.** Item `id`'s outputs are in `OUTDIR/<id>/`: `simplified.<ext>` and
//!   `report.json`, or `level-1.<ext>`, ... and `lod.json` for a chain, and `result.json`
//!   (its [`Outcome`]), written last. The folder is built under a hidden name beside it and
//!   renamed into place, so a killed run never leaves half a folder under an id.
//! * **Keys.** An item's key is a SHA-256 of the program's version, its parameters and its
//!   input's bytes. A final result under the same key is reused, not recomputed: a second run
//!   does no work, a killed run resumes where it stopped, and a changed input or parameter is
//!   run again.
//! * **Final and transient.** Every status is final except a failure another run could
//!   avoid (an output that could not be written, a missing input, a cancellation, a crash):
//!   those are not recorded and are retried.
//! * **Shards.** Item `k` (from 0, in manifest order) belongs to shard `i` of `n` (from 1)
//!   when `k mod n = i - 1`; each shard can run on its own machine over a shared folder.
//! * **Summary.** `OUTDIR/summary.jsonl` has one line per manifest item with a final result,
//!   in manifest order, plus this run's transient failures. It is rebuilt from the result
//!   files at the end of every run, so a rerun with no work left rewrites the summary of
//!   every shard.
//! * **Parallelism.** Several items at a time, each on a pool of its own ([`Schedule`]);
//!   every output is the same for any number of threads.
//!
//! ```
//! # let dir = tempfile::tempdir()?;
//! envelope::save(&envelope::Mesh::demo(), dir.path().join("cup.obj"))?;
//! std::fs::write(
//!     dir.path().join("manifest.jsonl"),
//!     "{\"id\": \"cup\", \"input\": \"cup.obj\", \"epsilon\": \"1%\", \"placement\": \"subset\"}\n",
//! )?;
//! let batch = envelope::batch::Batch::open(dir.path().join("manifest.jsonl"), dir.path().join("out"))?;
//! let outcomes = batch.run(Default::default(), &|_| std::ops::ControlFlow::Continue(()))?;
//! assert_eq!(outcomes[0].status, envelope::batch::Status::Ok);
//! assert!(dir.path().join("out/cup/simplified.obj").exists());
//! // A second run reuses the result.
//! assert!(!batch.run(Default::default(), &|_| std::ops::ControlFlow::Continue(()))?[0].ran);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod manifest;
mod outcome;
mod run;

use std::fs;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

pub use manifest::{Item, Job, ManifestError, parse as parse_manifest};
pub use outcome::{Outcome, Status};

use crate::{Epsilon, Error, threads};

/// The summary's file name in the output folder.
pub const SUMMARY: &str = "summary.jsonl";

/// Shard `index` of `count` (from 1): every `count`-th item of the manifest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `1..=count`.
    pub index: usize,
    /// Shards in all.
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = Error;

    /// `i/n` with `1 <= i <= n`.
    fn from_str(s: &str) -> Result<Shard, Error> {
        let bad = || Error::InvalidArgument(format!("shard {s:?}: expected i/n with 1 <= i <= n"));
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

/// Which items run, and how many at a time.
///
/// `threads` (default: rayon's, one per core) are shared out as `threads / threads_per_item`
/// items at a time, each on a pool of `threads_per_item` (default 1). One thread per item
/// gave the most objects per minute over the `libcgal-demo` corpus (small items parallelize
/// poorly); a batch of a few large meshes is faster with more threads per item. The
/// outputs are the same either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Schedule {
    /// Only this shard's items.
    pub shard: Option<Shard>,
    /// Threads in all.
    pub threads: Option<usize>,
    /// Threads of each item (the Ray engine's `cpus_per_task`).
    pub threads_per_item: Option<usize>,
}

/// A manifest, checked line by line, and the folder its outputs go to.
#[derive(Clone, Debug)]
pub struct Batch {
    manifest: PathBuf,
    items: Vec<Item>,
    outdir: PathBuf,
}

impl Batch {
    /// Reads and checks the manifest (every line before any work) and creates the output
    /// folder if missing (its parent must exist).
    ///
    /// # Errors
    /// [`Error::Manifest`] naming the line and key; [`Error::Io`] when the manifest cannot
    /// be read or the folder cannot be made.
    pub fn open(manifest: impl AsRef<Path>, outdir: impl AsRef<Path>) -> Result<Batch, Error> {
        Self::open_with(manifest, outdir, None)
    }

    /// [`Batch::open`], with an epsilon for the items that give none.
    ///
    /// # Errors
    /// As [`Batch::open`].
    pub fn open_with(
        manifest: impl AsRef<Path>,
        outdir: impl AsRef<Path>,
        default_epsilon: Option<Epsilon>,
    ) -> Result<Batch, Error> {
        let manifest = manifest.as_ref().to_path_buf();
        let text = fs::read_to_string(&manifest).map_err(|e| Error::io(&manifest, &e))?;
        let items = manifest::parse(&text, &manifest, default_epsilon)?;
        let outdir = outdir.as_ref().to_path_buf();
        if !outdir.is_dir() {
            fs::create_dir(&outdir).map_err(|e| Error::io(&outdir, &e))?;
        }
        Ok(Batch {
            manifest,
            items,
            outdir,
        })
    }

    /// Every item, in manifest order.
    #[must_use]
    pub fn items(&self) -> &[Item] {
        &self.items
    }

    /// The items of `shard` (all of them for `None`), in manifest order.
    pub fn shard(&self, shard: Option<Shard>) -> impl Iterator<Item = &Item> {
        self.items
            .iter()
            .enumerate()
            .filter(move |(k, _)| shard.is_none_or(|s| k % s.count == s.index - 1))
            .map(|(_, item)| item)
    }

    /// The item named `id`.
    #[must_use]
    pub fn item(&self, id: &str) -> Option<&Item> {
        self.items.iter().find(|i| i.id == id)
    }

    /// The output folder.
    #[must_use]
    pub fn outdir(&self) -> &Path {
        &self.outdir
    }

    /// The manifest file.
    #[must_use]
    pub fn manifest(&self) -> &Path {
        &self.manifest
    }

    /// Runs one item (or reuses its final result) and returns what became of it. Never fails:
    /// every problem is the outcome's status and message. Called by other engines (the
    /// Python package's Ray tasks) to run the items they schedule.
    #[must_use]
    pub fn run_item(&self, item: &Item) -> Outcome {
        run::run_item(&self.outdir, item, &AtomicBool::new(false))
    }

    /// Runs the items of `schedule.shard` (every item for `None`), several at a time (see
    /// [`Schedule`]), then writes the summary. `on_item` hears each outcome as it comes (from
    /// several threads); returning `Break` cancels the run (running items stop at their next
    /// check and are retried by the next run).
    ///
    /// # Errors
    /// [`Error::Io`] when the summary cannot be written; [`Error::Cancelled`] when `on_item`
    /// asked to stop (finished items are kept); [`Error::InvalidArgument`] for 0 threads.
    pub fn run(
        &self,
        schedule: Schedule,
        on_item: &(dyn Fn(&Outcome) -> ControlFlow<()> + Sync),
    ) -> Result<Vec<Outcome>, Error> {
        let threads = schedule.threads.unwrap_or_else(rayon::current_num_threads);
        let per_item = schedule.threads_per_item.unwrap_or(1);
        if threads == 0 || per_item == 0 {
            return Err(Error::InvalidArgument("threads must be at least 1".into()));
        }
        let items: Vec<&Item> = self.shard(schedule.shard).collect();
        let workers = (threads / per_item).clamp(1, items.len().max(1));
        let pools = (0..workers)
            .map(|_| threads::pool(per_item.min(threads)))
            .collect::<Result<Vec<_>, _>>()?;
        let stop = AtomicBool::new(false);
        let next = AtomicUsize::new(0);
        let slots: Vec<Mutex<Option<Outcome>>> = items.iter().map(|_| Mutex::new(None)).collect();
        // Each worker thread hands its items to a pool of its own and waits outside it, so an
        // item's time is its own (inside one shared pool, a thread waiting on an item's
        // parallel step steals another item and times both).
        std::thread::scope(|scope| {
            for pool in &pools {
                scope.spawn(|| {
                    while !stop.load(Ordering::Relaxed) {
                        let k = next.fetch_add(1, Ordering::Relaxed);
                        let Some(item) = items.get(k) else { break };
                        let outcome = pool.install(|| run::run_item(&self.outdir, item, &stop));
                        if on_item(&outcome).is_break() {
                            stop.store(true, Ordering::Relaxed);
                        }
                        *slots[k].lock().unwrap_or_else(PoisonError::into_inner) = Some(outcome);
                    }
                });
            }
        });
        let outcomes: Vec<Outcome> = slots
            .into_iter()
            .filter_map(|s| s.into_inner().unwrap_or_else(PoisonError::into_inner))
            .collect();
        let transient: Vec<Outcome> = outcomes.iter().filter(|o| !o.is_final()).cloned().collect();
        self.write_summary(&transient)?;
        if stop.load(Ordering::Relaxed) {
            return Err(Error::Cancelled);
        }
        Ok(outcomes)
    }

    /// Rewrites `summary.jsonl` from the final results on disk, in manifest order, with
    /// `transient` (this run's failures that were not recorded) in their places; returns its
    /// lines.
    ///
    /// # Errors
    /// [`Error::Io`] when it cannot be written.
    pub fn write_summary(&self, transient: &[Outcome]) -> Result<Vec<Outcome>, Error> {
        let mut lines = Vec::new();
        for item in &self.items {
            if let Some(o) = transient.iter().find(|o| o.id == item.id) {
                lines.push(o.clone());
            } else if let Some(o) = run::recorded(&self.outdir, item) {
                lines.push(o);
            }
        }
        let text: String = lines.iter().map(|o| o.to_json_line() + "\n").collect();
        let path = self.outdir.join(SUMMARY);
        let partial = self
            .outdir
            .join(format!(".{SUMMARY}.partial-{}", std::process::id()));
        fs::write(&partial, text).map_err(|e| Error::io(&partial, &e))?;
        fs::rename(&partial, &path).map_err(|e| Error::io(&path, &e))?;
        Ok(lines)
    }
}
