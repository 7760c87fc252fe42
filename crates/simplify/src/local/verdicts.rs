//! The fiber test's verdicts on the starting mesh, taken ahead of the queue by the threads
//! that would otherwise wait ([`Doomed`]): an atomic cache of one answer per vertex.

use super::plan::LocalSimplifier;
use super::queue::RemovalQueue;
use super::scheduler::Finally;
use crate::fill::{FillContext, HoleFiller};
use crate::filter::Filter;
use crate::rules::Rejection;
use envelope_mesh::VertexId;
use std::sync::atomic::{AtomicU8, AtomicU64, AtomicUsize, Ordering as Mem};

/// The vertices whose removal the fiber test turned away on the starting mesh, as long as their
/// fan stays as it was (the subset run of a first-in-first-out queue; not in the paper). At
/// small epsilons that is almost every attempt. Each
/// verdict is the plan's own answer (`LocalSimplifier::plan` with a filler that fills nothing)
/// on a copy of the starting mesh, taken in vertex order (the queue's when it starts with every
/// vertex): by the other threads while the calling thread selects and commits ([`Awake`]), and
/// by the calling thread when the queue reaches a vertex whose verdict nobody has taken yet (it
/// takes others ahead while it waits for one being computed). A verdict is the same whoever
/// computes it and whenever, and the queue only asks for the verdicts of vertices whose fan
/// never changed: the outcome is the same as with every verdict computed before the run, and
/// the same for any number of threads. A vertex whose fan changes before the queue reaches it
/// needs no verdict (most such are never computed; the others were taken ahead before their
/// fan changed).
///
/// **Why a verdict holds while the fan stays.** The plan's answer
/// [`Rejection::NoFillAcrossFiber`] depends on the vertex's fan (its checks, its hole, the
/// fiber path through it, the crossing count), on fixed positions (the subset run moves
/// nothing) and on the refusals of the candidate triangles across the path: by the
/// filter's [`Filter::refuses_anyway`] (independent of the approximation, by its contract)
/// or by the topology guards (an edge between two hole vertices, or the face on three,
/// already in the mesh). A removal deletes only faces and edges at the removed vertex;
/// while the fan stays, its hole vertices are alive, so an edge or face of theirs that
/// refused a candidate stays too. Every refusal holds, and so does the answer. A vertex's
/// fan changes only when it is on the hole of a removal ([`Doomed::forget`] it then).
///
/// In [`independent_batch`], such a vertex needs no plan and is taken as it comes: its
/// attempt changes nothing.
///
/// A vertex the test let pass on the starting mesh is planned without the test while its fan
/// stays as it was: the test decides nothing but the reason of a rejection (module `fiber`),
/// and it would run twice otherwise (once ahead, once in the plan).
pub(super) struct Doomed<'s> {
    /// The starting mesh's simplifier (on a copy, without a face index) and the filter;
    /// `None`: no verdicts (no fiber test, or not a batched run).
    start: Option<(LocalSimplifier<'s>, &'s dyn Filter)>,
    /// Per vertex, its [`Verdict`] (as `u8`).
    state: Vec<AtomicU8>,
    /// Per vertex, the candidates its verdict gave the filter, until counted.
    tests: Vec<AtomicU64>,
    /// The candidates of the verdicts the run used.
    used: AtomicU64,
    /// The vertices queued at the start, in vertex order.
    order: Vec<VertexId>,
    /// Per vertex, its place in `order` (`u32::MAX`: none).
    place: Vec<u32>,
    /// The next place of `order` a thread takes ahead.
    next: AtomicUsize,
}

/// A vertex's fiber verdict on the starting mesh, while its fan is as it was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Verdict {
    /// Not computed yet.
    Open,
    /// Being computed by a thread.
    Taken,
    /// [`Rejection::NoFillAcrossFiber`].
    Doomed,
    /// Anything else: the test turned nothing away (or did not apply).
    Passed,
    /// None: the fan changed, or the vertex was not queued at the start.
    Unknown,
}

impl Verdict {
    /// The verdict a state of [`Doomed`] holds (`Unknown` for any other byte).
    fn of_state(x: u8) -> Self {
        [Self::Open, Self::Taken, Self::Doomed, Self::Passed]
            .into_iter()
            .find(|d| *d as u8 == x)
            .unwrap_or(Self::Unknown)
    }
}

impl<'s> Doomed<'s> {
    /// The verdicts of the vertices `queue` holds, none computed yet (none at all without
    /// `start`).
    pub(super) fn new(
        start: Option<(LocalSimplifier<'s>, &'s dyn Filter)>,
        queue: &RemovalQueue,
    ) -> Self {
        let (order, slots) = match &start {
            Some((s, _)) => {
                let order: Vec<VertexId> = s
                    .mesh()
                    .vertices()
                    .filter(|v| queue.queued.get(v.index()).copied().unwrap_or(false))
                    .collect();
                let slots = order.last().map_or(0, |v| v.index() + 1);
                (order, slots)
            }
            None => (Vec::new(), 0),
        };
        let mut place = vec![u32::MAX; slots];
        let state = (0..slots)
            .map(|_| AtomicU8::new(Verdict::Unknown as u8))
            .collect::<Vec<_>>();
        for (k, v) in order.iter().enumerate() {
            place[v.index()] = k as u32;
            state[v.index()].store(Verdict::Open as u8, Mem::Relaxed);
        }
        Self {
            start,
            state,
            tests: (0..slots).map(|_| AtomicU64::new(0)).collect(),
            used: AtomicU64::new(0),
            order,
            place,
            next: AtomicUsize::new(0),
        }
    }

    /// Computes `v`'s verdict if no thread has taken it; returns whether this one did.
    fn take(&self, v: VertexId) -> bool {
        let Some((start, filter)) = &self.start else {
            return false;
        };
        let slot = &self.state[v.index()];
        let (open, taken) = (Verdict::Open as u8, Verdict::Taken as u8);
        if slot
            .compare_exchange(open, taken, Mem::Acquire, Mem::Relaxed)
            .is_err()
        {
            return false;
        }
        // Should the plan panic, the slot says `Unknown` rather than `Taken`, so that no
        // thread waits for it forever (the panic then ends the run, see `run`'s scope).
        let unfinished = Finally(|| {
            let unknown = Verdict::Unknown as u8;
            let _ = slot.compare_exchange(taken, unknown, Mem::Release, Mem::Relaxed);
        });
        let (verdict, tests) = match start.plan(v, *filter, &FillNothing) {
            (Err(Rejection::NoFillAcrossFiber), tests) => (Verdict::Doomed, tests),
            (_, tests) => (Verdict::Passed, tests),
        };
        self.tests[v.index()].store(tests, Mem::Relaxed);
        // A fan changed meanwhile (`forget`) keeps `Unknown`.
        let _ = slot.compare_exchange(taken, verdict as u8, Mem::Release, Mem::Relaxed);
        drop(unfinished);
        true
    }

    /// Computes the next open verdict in queue order; false when none is left.
    pub(super) fn take_one(&self) -> bool {
        loop {
            let k = self.next.fetch_add(1, Mem::Relaxed);
            let Some(&v) = self.order.get(k) else {
                return false;
            };
            if self.take(v) {
                return true;
            }
        }
    }

    /// `v`'s verdict, computed now if nobody has (the queue has reached `v`).
    fn verdict(&self, v: VertexId) -> Verdict {
        let Some(&k) = self.place.get(v.index()) else {
            return Verdict::Unknown;
        };
        if k == u32::MAX {
            return Verdict::Unknown;
        }
        // The threads ahead go on from after `v`.
        self.next.fetch_max(k as usize + 1, Mem::Relaxed);
        loop {
            match Verdict::of_state(self.state[v.index()].load(Mem::Acquire)) {
                Verdict::Open => {
                    self.take(v);
                }
                // Another thread is computing it: take one ahead meanwhile.
                Verdict::Taken => {
                    if !self.take_one() {
                        std::hint::spin_loop();
                    }
                }
                verdict => {
                    if verdict != Verdict::Unknown {
                        let tests = self.tests[v.index()].swap(0, Mem::Relaxed);
                        self.used.fetch_add(tests, Mem::Relaxed);
                    }
                    return verdict;
                }
            }
        }
    }

    /// Whether `v`'s attempt is known to end with [`Rejection::NoFillAcrossFiber`].
    pub(super) fn holds(&self, v: VertexId) -> bool {
        self.verdict(v) == Verdict::Doomed
    }

    /// Whether `v`'s plan may leave the fiber test out (see the type's docs); asked after
    /// [`Doomed::holds`].
    pub(super) fn passed(&self, v: VertexId) -> bool {
        self.state
            .get(v.index())
            .is_some_and(|x| x.load(Mem::Acquire) == Verdict::Passed as u8)
    }

    /// `v`'s fan changed: its verdict no longer holds (nor is it needed).
    pub(super) fn forget(&self, v: VertexId) {
        if let Some(x) = self.state.get(v.index()) {
            x.store(Verdict::Unknown as u8, Mem::Release);
        }
    }

    /// The candidates the verdicts the run used gave the filter.
    pub(super) fn used_tests(&self) -> u64 {
        self.used.load(Mem::Relaxed)
    }
}

/// The filler of [`Doomed`]'s plans: the fiber test runs before the filling, so a
/// filling that never succeeds leaves its answer alone.
pub(super) struct FillNothing;

impl HoleFiller for FillNothing {
    fn fill(&self, _: &mut FillContext<'_>) -> bool {
        false
    }
}
