//! The thread scheduler of the batched runs: who plans what, and what the other threads do
//! between the rounds. It knows nothing of geometry and decides nothing of the outcome.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering as Mem};

/// Keeps the other threads of the pool busy between the short parallel rounds of a batched
/// run: while the calling thread selects and commits, each of them works aside (the run's
/// fiber verdicts ahead of the queue), then spins until the next round begins or
/// [`Awake::MAX_SPIN`] passes, so that the next round's work is taken at once rather than
/// after a wake-up. It decides nothing: the work aside is the same whichever thread does it
/// and whenever, so the outcome never depends on it.
pub(super) struct Awake {
    round: AtomicU64,
    caller: Option<usize>,
}

impl Awake {
    const MAX_SPIN: std::time::Duration = std::time::Duration::from_millis(1);

    pub(super) fn new() -> Self {
        Self {
            round: AtomicU64::new(0),
            caller: rayon::current_thread_index(),
        }
    }

    /// One job for each other thread, until [`Awake::release`]: `aside` until it returns false
    /// (work that decides nothing: the run's fiber verdicts ahead), then spinning.
    pub(super) fn hold<'s, A: Fn() -> bool + Sync>(
        &'s self,
        scope: &rayon::Scope<'s>,
        aside: &'s A,
    ) {
        let round = self.round.load(Mem::Acquire);
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(move |_| {
                // The caller never waits here (it is the one that ends the wait).
                if rayon::current_thread_index() == self.caller {
                    return;
                }
                let current = || self.round.load(Mem::Acquire) == round;
                while current() && aside() {}
                let start = std::time::Instant::now();
                while current() && start.elapsed() < Self::MAX_SPIN {
                    std::hint::spin_loop();
                }
            });
        }
    }

    /// Ends the jobs of [`Awake::hold`] (each after the verdict it is computing).
    pub(super) fn release(&self) {
        self.round.fetch_add(1, Mem::Release);
    }
}

/// The plans of one batch, in its order (the read-only plans of a batch do not see each
/// other, so the order of planning is free). The items `inline` names (answered without a
/// plan: the doomed ones) are planned on the calling thread; the others in parallel, the
/// threads taking them one at a time, the costliest first by `cost` (ties in batch order),
/// or inline for a single one. Plans take from microseconds to a millisecond: a long one
/// begun last leaves the other threads idle until it ends, hence costliest first (less
/// waiting than rayon's adaptive split or one job per plan in queue order). A thread that
/// finds no plan left calls `aside` (work that decides nothing of the batch: the run's
/// verdicts ahead) until the last plan ends, spinning when it has none.
pub(super) fn plan_each<T: Sync, R: Send>(
    batch: &[T],
    inline: impl Fn(&T) -> bool,
    cost: impl Fn(&T) -> usize,
    plan: impl Fn(&T) -> R + Sync,
    aside: impl Fn() -> bool + Sync,
) -> Vec<R> {
    let mut heavy: Vec<usize> = (0..batch.len()).filter(|&i| !inline(&batch[i])).collect();
    heavy.sort_by_key(|&i| std::cmp::Reverse(cost(&batch[i])));
    let mut planned: Vec<Option<R>> = batch.iter().map(|_| None).collect();
    if let [one] = heavy[..] {
        planned[one] = Some(plan(&batch[one]));
    } else if !heavy.is_empty() {
        let (next, done) = (AtomicUsize::new(0), AtomicUsize::new(0));
        let take = || {
            let mut out = Vec::new();
            loop {
                let k = next.fetch_add(1, Mem::Relaxed);
                let Some(&i) = heavy.get(k) else {
                    // Work aside while the other threads finish their last plans.
                    while done.load(Mem::Acquire) < heavy.len() {
                        if !aside() {
                            std::hint::spin_loop();
                        }
                    }
                    return out;
                };
                // Counted even when the plan panics: no thread waits for it forever (the
                // panic then reaches the caller through the broadcast).
                let _done = Finally(|| {
                    done.fetch_add(1, Mem::Release);
                });
                out.push((i, plan(&batch[i])));
            }
        };
        let parts: Vec<Vec<(usize, R)>> = rayon::broadcast(|_| take());
        for (i, r) in parts.into_iter().flatten() {
            planned[i] = Some(r);
        }
    }
    batch
        .iter()
        .zip(planned)
        .filter_map(|(t, p)| if inline(t) { Some(plan(t)) } else { p })
        .collect()
}

/// Runs its closure when dropped, also while a panic unwinds (a wait on a shared counter or
/// state must not outlive the work it waits for).
pub(super) struct Finally<F: FnMut()>(pub(super) F);

impl<F: FnMut()> Drop for Finally<F> {
    fn drop(&mut self) {
        (self.0)();
    }
}
