//! The local algorithm of section 5.2: vertex removal with hole filling, every candidate
//! triangle checked by the validity test of section 5.1.
//!
//! ```text
//! simplify_local
//!   queue_vertices                 all vertices, in the queue order
//!   loop: pop v                    until the queue is empty (or the stop rule says so)
//!     try_remove_vertex(v)
//!       remove_vertex_fan          the hole (closed cycle, or open chain at a border)
//!       fill_hole                  greedy (5.2) or exhaustive, each candidate filtered (5.1)
//!       commit                     and queue the hole's vertices again
//!       or rollback                the fan comes back exactly; v leaves the queue
//! ```
//!
//! Choices the paper leaves open, and what this crate does:
//!
//! | question | answer |
//! |---|---|
//! | queue order | first in, first out ([`Fifo`]): vertex ids increasing, then the neighbours of each removed vertex appended in their counter-clockwise order; a neighbour already queued keeps its place. [`FlatFirst`] is an option. Priorities are computed when a vertex is queued and not updated while it waits. |
//! | a vertex that failed | leaves the queue; it comes back only when a neighbour is removed (the paper's "neighbors are placed back") |
//! | aspect-ratio measure | `4 sqrt(3) A / (a² + b² + c²)` (1 equilateral, 0 degenerate); f64, a priority only |
//! | look-ahead | greedy skips a valid triangle that leaves a sub-hole that certainly cannot be filled (three vertices whose triangle is rejected, or all vertices on one line) (still one pass; [`Greedy::PAPER`] without) |
//! | tie breaks | equal aspect ratios: the triangle with the lexicographically smallest hole positions (the hole starts at the vertex `remove_vertex_fan` names first) |
//! | candidate triangles | all triples of hole vertices, generated once per hole; a sub-hole considers those whose three vertices are on it |
//! | degenerate candidates | exactly collinear corners: rejected |
//! | attempts that cannot succeed | not in the paper: before the filling, the fiber test ([`FiberTest`], module `fiber`) ends an interior vertex's attempt when every triangle on its hole's vertices that meets a path from its inner to its outer envelope point is refused by the barriers (every valid filling meets that path; the module proves it); it decides nothing else, so the outcome is the same without it (`tests/fiber.rs`) |
//! | fiber verdicts ahead | with a first-in-first-out queue, the fiber test's verdict on each vertex queued at the start, computed on a copy of the starting mesh, in vertex order, by the threads that would otherwise wait while the calling thread selects and commits, or by the calling thread when the queue reaches it first ([`Doomed`]; a vertex whose fan changed before needs none); it stands in for the attempt while the vertex's fan is as it was (proved there; a debug build re-plans and asserts), so only the other attempts are planned in the batches |
//! | valence-3 interior vertex | its hole is one triangle; placed if valid and not already a face (a tetrahedron cannot lose a vertex) |
//! | border vertex | its open chain is filled as a polygon closed by the new border edge, which must not already be an edge and must not touch a border tube (6.2); with no tube in the barriers, border vertices are kept; a border vertex with one face (an ear) is kept |
//! | topology | a new edge that already exists elsewhere is refused before the filter is asked (link condition); the mesh's `add_faces` is the last guard |
//! | very large holes | vertices of valence above [`MAX_HOLE`] are kept (the candidate list is cubic in the valence) |
//! | spatial index | a hashed uniform grid over the live faces, rebuilt coarser as faces grow ([`FaceGrid`]); barriers in a static BVH |
//! | vertex positions | input positions ([`Placement::Subset`], the paper's 5.2); [`Placement::Slide`] adds the sliding the paper's section 8 proposes as future work, as a phase after the subset run (see [`LocalSimplifier::try_slide_remove`] for its choices); [`Placement::Collapse`] adds, in the same phase, edge collapses into a moved neighbour ([`LocalSimplifier::try_collapse`]; positions: memoryless quadrics, the midpoint, the neighbour's own, cheapest first, at most 8, none farther than 1.25 times the local offset from the planes around the edge) |
//! | when to move vertices | [`Placement::Auto`] (the command line's default): the subset run, then the moving phase of [`Placement::Collapse`] only when the subset run left at most one vertex in [`AUTO_MOVING_DIVISOR`] of those it started with: the moving phase tries every vertex that is left, each at several positions, so it is cheap next to the subset run only when few are left; where many are left (small epsilons), the subset run's output already has fewer faces than CGAL's envelope collapse in the benchmark, and the collapse placement took 1.1-2.8 times the subset run's seconds there (full `peers` run at af1f640) |
//! | moving phase | planned read-only with the planned positions (the faces around a moved vertex tested where they would be), batched like the subset run with two-ring-and-fiber boxes |
//!
//! The output is deterministic and the same for any number of threads. With the
//! first-in-first-out order the queue is taken in batches (`independent_batch`: the front
//! vertex and the next ones whose one-ring boxes are apart from everything before them);
//! the removals of a batch are *planned* in parallel (checks, hole, filling: read-only) and
//! *carried out* one by one in queue order. A plan only reads the mesh inside its box, so
//! this is the paper's FIFO except that re-queued neighbours of a batch are appended after
//! the whole batch, and that vertices whose fiber verdict is known ([`Doomed`]) are
//! attempted as they come, also beside a removal in the same batch that changes their fan
//! (they are then queued again). Other orders take one vertex at a time.

use crate::fiber::FiberTest;
use crate::fill::{FillContext, Hole, HoleFiller};
use crate::filter::{Approximation, CandidateProfile, Filter, Nearby, position_in};
use crate::grid::FaceGrid;
use crate::policy::{
    Exhaust, Fifo, FlatFirst, QueueOrder, Rejection, StopRule, TargetFaces, Visitor,
};
use crate::{Barriers, EnvelopeFilter, Exhaustive, Greedy};
use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use envelope_predicates::bvh::Aabb;
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, VecDeque};
use std::sync::atomic::{AtomicU8, AtomicU64, AtomicUsize, Ordering as Mem};
use thiserror::Error;

/// Vertices of larger valence are not tried (their candidate lists grow cubically).
pub const MAX_HOLE: usize = 40;

/// [`Placement::Auto`] runs the moving phase when the subset run left at most one vertex in
/// this many of those it started with.
pub const AUTO_MOVING_DIVISOR: usize = 10;

/// Why [`simplify_local`] stopped with an error.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum SimplifyError {
    /// The input has a vertex whose faces form several fans.
    #[error("vertex {0} is not manifold")]
    NonManifoldVertex(VertexId),
    /// A structure failed its sanity check (only with [`Options::check_each_step`]).
    #[error("sanity check failed after trying vertex {after}: {message}")]
    SanityCheck {
        /// The vertex tried last.
        after: VertexId,
        /// What was wrong.
        message: String,
    },
}

/// Counts of one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Live vertices before.
    pub vertices_before: usize,
    /// Live faces before.
    pub faces_before: usize,
    /// Live vertices after.
    pub vertices_after: usize,
    /// Live faces after.
    pub faces_after: usize,
    /// Removal attempts (queue pops).
    pub attempts: usize,
    /// Vertices removed.
    pub removed: usize,
    /// Attempts that failed because no valid filling was found.
    pub no_valid_fill: usize,
    /// Of those, the ones the fiber test turned away ([`Rejection::NoFillAcrossFiber`]).
    pub no_fill_across_fiber: usize,
    /// Of those, the ones answered by a verdict on the starting mesh, without a plan (see
    /// `Doomed` in the module docs' table, "fiber verdicts ahead").
    pub answered_ahead: usize,
    /// Attempts refused before filling (border without tubes, ears, non-manifold, too large).
    pub refused: usize,
    /// Candidate triangles given to the filter.
    pub candidate_tests: u64,
    /// Removals that slid neighbours along their fibers ([`Placement::Slide`]).
    pub slid: usize,
    /// Removals by an edge collapse to a moved neighbour ([`Placement::Collapse`]).
    pub collapsed: usize,
    /// Whether the moving phase ran (with [`Placement::Slide`] and [`Placement::Collapse`]
    /// always; with [`Placement::Auto`] when few vertices were left).
    pub moving_phase: bool,
}

/// The hole-filling strategy of [`Options`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoleFilling {
    /// The paper's single pass ([`Greedy`]), by default with the forced-triangle look-ahead.
    Greedy {
        /// See [`Greedy::forced_lookahead`].
        forced_lookahead: bool,
    },
    /// Every triangulation up to a hole size ([`Exhaustive`]).
    Exhaustive {
        /// Largest hole tried exhaustively; greedy above.
        max_vertices: usize,
    },
}

impl Default for HoleFilling {
    fn default() -> Self {
        Self::Greedy {
            forced_lookahead: true,
        }
    }
}

/// The queue order of [`Options`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Order {
    /// The paper's first in, first out ([`Fifo`]).
    #[default]
    Fifo,
    /// Flattest fan first ([`FlatFirst`]).
    FlatFirst,
}

/// Options of [`simplify_local`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Queue order.
    pub order: Order,
    /// Hole filling.
    pub hole_filling: HoleFilling,
    /// Stop once at most this many faces remain.
    pub target_faces: Option<usize>,
    /// Run the mesh's, the grid's and the queue's sanity checks after every attempt (slow).
    pub check_each_step: bool,
    /// Where output vertices may lie (default: the input positions).
    pub placement: Placement,
}

/// Where the output vertices of the local algorithm may lie.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Placement {
    /// The paper's 5.2: the output vertices are a subset of the input vertices, at their
    /// input positions (nested vertex sets, as level-of-detail chains need).
    #[default]
    Subset,
    /// The paper's section 8 ("allow the vertices to slide along their normal vectors"),
    /// after the subset run is stuck: a vertex whose removal fails is tried again with its
    /// interior neighbours slid along their fibers ([`VertexFibers`]) half-way towards its
    /// tangent plane; see [`LocalSimplifier::try_slide_remove`]. Output vertices then lie
    /// on their fibers, between the envelopes, not on the input.
    Slide,
    /// [`Placement::Slide`], and a vertex that still cannot go is removed by an edge
    /// collapse into a neighbour moved to a point chosen by memoryless quadrics (or the
    /// edge's midpoint, or the neighbour's own position), every moved face through the same
    /// filter ([`LocalSimplifier::try_collapse`]). Output vertices lie anywhere between the
    /// envelopes; the guarantee is the same (the filter, then the certificate).
    Collapse,
    /// The subset run, then the moving phase of [`Placement::Collapse`] only when the subset
    /// run left at most one vertex in [`AUTO_MOVING_DIVISOR`] of those it started with (see
    /// the module docs for why); otherwise the output is [`Placement::Subset`]'s.
    Auto,
}

/// The fiber of every vertex (by vertex id): the segment from its inner envelope point to its
/// outer one (f64 constructions of `envelope-offset`), along which [`Placement::Slide`]
/// moves it.
#[derive(Clone, Copy, Debug)]
pub struct VertexFibers<'a> {
    /// `v - eps_minus n_v`.
    pub inner: &'a [DVec3],
    /// `v + eps_plus n_v`.
    pub outer: &'a [DVec3],
}

/// Slid positions stay within this part of a fiber, `[SLIDE_RANGE, 1 - SLIDE_RANGE]` of the
/// way from the inner to the outer point (a choice: a vertex slid onto an envelope could not
/// keep a single triangle).
const SLIDE_RANGE: f64 = 0.05;

impl VertexFibers<'_> {
    /// `(inner point, outer - inner)` of `v`; `None` without a fiber of positive length.
    fn segment(&self, v: VertexId) -> Option<(DVec3, DVec3)> {
        let (a, b) = (*self.inner.get(v.index())?, *self.outer.get(v.index())?);
        let d = b - a;
        (d.length_squared() > 0.0 && d.is_finite()).then_some((a, d))
    }
}

/// The policies of [`simplify_local_with`].
pub struct Policies<'p> {
    /// The validity test (usually an [`EnvelopeFilter`]).
    pub filter: &'p dyn Filter,
    /// Queue order.
    pub order: &'p dyn QueueOrder,
    /// Hole filling.
    pub filler: &'p dyn HoleFiller,
    /// Stop rule.
    pub stop: &'p dyn StopRule,
    /// Keep every border vertex (set when there is no border tube).
    pub keep_border: bool,
    /// Run sanity checks after every attempt.
    pub check_each_step: bool,
    /// With fibers, the slide phase ([`Placement::Slide`]) runs after the subset run.
    pub fibers: Option<VertexFibers<'p>>,
    /// Edge collapses after the subset run ([`Placement::Collapse`]; with `fibers`, after
    /// sliding).
    pub collapse: bool,
    /// Run the moving phase (`fibers`, `collapse`) only when the subset run left at most one
    /// vertex in [`AUTO_MOVING_DIVISOR`] of those it started with ([`Placement::Auto`]).
    pub moving_if_few_left: bool,
    /// The fiber test ([`FiberTest`]) before each plain removal's filling: its envelopes
    /// must be barriers of `filter` and apart from every face of the mesh (see its module).
    pub fiber_test: Option<&'p FiberTest<'p>>,
}

/// Simplifies `mesh` in place by the local algorithm of section 5.2, with the validity test
/// of section 5.1 against `barriers` ([`EnvelopeFilter`]). See the module docs.
///
/// ```
/// use envelope_mesh::{generate, HalfEdgeMesh};
/// use envelope_simplify::{simplify_local, Barriers, Options};
/// let mut m = HalfEdgeMesh::from_soup(&generate::tetrahedron()).unwrap();
/// let stats = simplify_local(&mut m, &Barriers::none(), &Options::default()).unwrap();
/// assert_eq!((stats.removed, m.num_faces()), (0, 4)); // nothing can go
/// ```
pub fn simplify_local(
    mesh: &mut HalfEdgeMesh,
    barriers: &Barriers,
    options: &Options,
) -> Result<Stats, SimplifyError> {
    simplify_local_visited(mesh, barriers, options, &mut ())
}

/// [`simplify_local`] reporting every attempt to `visitor` (progress bars, tracing).
pub fn simplify_local_visited(
    mesh: &mut HalfEdgeMesh,
    barriers: &Barriers,
    options: &Options,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    simplify_local_from(mesh, barriers, options, None, visitor)
}

/// [`simplify_local_visited`] with the queue started from `seeds` (in their order; `None`:
/// every vertex, in id order) instead of every vertex: after another step changed the mesh
/// in a few places, the vertices around the changes, as the local algorithm re-queues the
/// hole's vertices after a removal. Seeds that are no longer in the mesh are skipped.
pub fn simplify_local_from(
    mesh: &mut HalfEdgeMesh,
    barriers: &Barriers,
    options: &Options,
    seeds: Option<&[VertexId]>,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    simplify_local_sliding(mesh, barriers, options, seeds, None, None, visitor)
}

/// [`simplify_local_from`] with the vertices' fibers, which [`Placement::Slide`] needs
/// (without them, or with [`Placement::Subset`], no vertex moves), and the fiber test
/// ([`Policies::fiber_test`]: `fiber_test`'s envelopes must be among `barriers`).
pub fn simplify_local_sliding(
    mesh: &mut HalfEdgeMesh,
    barriers: &Barriers,
    options: &Options,
    seeds: Option<&[VertexId]>,
    fibers: Option<VertexFibers<'_>>,
    fiber_test: Option<&FiberTest<'_>>,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    let filter = EnvelopeFilter::new(barriers);
    let order: &dyn QueueOrder = match options.order {
        Order::Fifo => &Fifo,
        Order::FlatFirst => &FlatFirst,
    };
    let (exhaustive, greedy);
    let filler: &dyn HoleFiller = match options.hole_filling {
        HoleFilling::Greedy { forced_lookahead } => {
            greedy = Greedy { forced_lookahead };
            &greedy
        }
        HoleFilling::Exhaustive { max_vertices } => {
            exhaustive = Exhaustive { max_vertices };
            &exhaustive
        }
    };
    let target;
    let stop: &dyn StopRule = match options.target_faces {
        None => &Exhaust,
        Some(n) => {
            target = TargetFaces(n);
            &target
        }
    };
    let policies = Policies {
        filter: &filter,
        order,
        filler,
        stop,
        keep_border: !barriers.has_tubes(),
        check_each_step: options.check_each_step,
        fibers: fibers.filter(|_| options.placement != Placement::Subset),
        collapse: matches!(options.placement, Placement::Collapse | Placement::Auto),
        moving_if_few_left: options.placement == Placement::Auto,
        fiber_test,
    };
    run(mesh, &policies, seeds, visitor)
}

/// [`simplify_local`] with any policies and a visitor.
pub fn simplify_local_with(
    mesh: &mut HalfEdgeMesh,
    policies: &Policies<'_>,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    run(mesh, policies, None, visitor)
}

fn run(
    mesh: &mut HalfEdgeMesh,
    policies: &Policies<'_>,
    seeds: Option<&[VertexId]>,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    if let Some(v) = mesh.vertices().find(|&v| !mesh.is_manifold_vertex(v)) {
        return Err(SimplifyError::NonManifoldVertex(v));
    }
    let mut stats = Stats {
        vertices_before: mesh.num_vertices(),
        faces_before: mesh.num_faces(),
        ..Stats::default()
    };
    let mut queue = match seeds {
        None => queue_vertices(mesh, policies.order),
        Some(seeds) => {
            let mut q = RemovalQueue::default();
            for &v in seeds.iter().filter(|&&v| mesh.contains_vertex(v)) {
                q.push(mesh, policies.order, v);
            }
            q
        }
    };
    let batched = policies.order.is_fifo() && !policies.check_each_step;
    // The verdicts are computed on a copy of the starting mesh (see `Doomed`).
    let mut start = (batched && policies.fiber_test.is_some()).then(|| mesh.clone());
    let verdicts = Doomed::new(
        start.as_mut().map(|m| {
            let s = LocalSimplifier::without_grid(m, policies.keep_border)
                .with_fiber_test(policies.fiber_test);
            (s, policies.filter)
        }),
        &queue,
    );
    let mut local = LocalSimplifier::without_grid(mesh, policies.keep_border)
        .with_fiber_test(policies.fiber_test);
    let mut rings = RingBoxes::default();
    let awake = Awake::new();
    rayon::in_place_scope(|scope| -> Result<(), SimplifyError> {
        // The other threads take verdicts ahead while this one builds the face index (the
        // verdicts read none), selects and commits.
        if batched {
            awake.hold(scope, &verdicts);
        }
        local.grid = FaceGrid::from_mesh(local.mesh());
        'run: loop {
            let batch: Vec<(VertexId, bool)> = if batched {
                independent_batch(
                    &mut queue,
                    local.mesh(),
                    |m, v| rings.get(m, v),
                    |v| verdicts.holds(v),
                )
            } else {
                queue.pop().into_iter().map(|v| (v, false)).collect()
            };
            if batch.is_empty() {
                break;
            }
            awake.release();
            let plans = {
                let local = &local;
                plan_each(
                    &batch,
                    |&(_, doomed)| doomed,
                    |&(v, _)| {
                        let known = usize::from(verdicts.passed(v));
                        2 * local.mesh().valence(v) + known
                    },
                    |&(v, doomed)| {
                        if doomed {
                            debug_assert_eq!(
                                local.plan(v, policies.filter, &FillNothing).0.err(),
                                Some(Rejection::NoFillAcrossFiber),
                                "the verdict on {v} no longer holds"
                            );
                            (Err(Rejection::NoFillAcrossFiber), 0)
                        } else if verdicts.passed(v) {
                            local.plan_without_fiber_test(v, policies.filter, policies.filler)
                        } else {
                            local.plan(v, policies.filter, policies.filler)
                        }
                    },
                    || verdicts.take_one(),
                )
            };
            if batched {
                awake.hold(scope, &verdicts);
            }
            // Commit in queue order: the same calls, in the same order, as one at a time.
            for (&(v, ahead), (plan, tests)) in batch.iter().zip(plans) {
                if policies.stop.should_stop(local.mesh().num_faces()) {
                    break 'run;
                }
                stats.attempts += 1;
                stats.answered_ahead += usize::from(ahead);
                visitor.on_attempt(v);
                local.candidate_tests += tests;
                match plan.and_then(|p| local.apply(v, p)) {
                    Ok(removal) => {
                        stats.removed += 1;
                        visitor.on_removed(v, &removal.faces);
                        rings.forget(v);
                        for &w in &removal.hole.vertices {
                            rings.forget(w);
                            verdicts.forget(w);
                            queue.push(local.mesh(), policies.order, w);
                        }
                    }
                    Err(reason) => rejected(&mut stats, visitor, v, reason),
                }
                if policies.check_each_step {
                    let check = local
                        .sanity_check()
                        .and_then(|()| queue.sanity_check(local.mesh()));
                    check.map_err(|message| SimplifyError::SanityCheck { after: v, message })?;
                }
            }
        }
        awake.release();
        Ok(())
    })?;
    local.candidate_tests += verdicts.used_tests();
    let few_left = local.mesh().num_vertices() * AUTO_MOVING_DIVISOR <= stats.vertices_before;
    if (policies.fibers.is_some() || policies.collapse)
        && (few_left || !policies.moving_if_few_left)
    {
        stats.moving_phase = true;
        moving_phase(&mut local, policies, &mut stats, visitor)?;
    }
    stats.candidate_tests = local.candidate_tests;
    stats.vertices_after = local.mesh().num_vertices();
    stats.faces_after = local.mesh().num_faces();
    Ok(stats)
}

/// Keeps the other threads of the pool busy between the short parallel rounds of a batched
/// run: while the calling thread selects and commits (tens of microseconds a batch), each
/// of them takes fiber verdicts ahead of the queue ([`Doomed::take_one`]), then spins until
/// the next round begins or [`Awake::MAX_SPIN`] passes, so that the next round's work is
/// taken at once rather than after a wake-up. It decides nothing: a verdict is the same
/// whichever thread computes it and whenever, so the outcome never depends on it.
/// mech-holes-shark at 1/64 % (117 rounds): the spinning alone took the rounds' wall time
/// from 0.032 to 0.030 s for 0.047 s of planning.
struct Awake {
    round: AtomicU64,
    caller: Option<usize>,
}

impl Awake {
    const MAX_SPIN: std::time::Duration = std::time::Duration::from_millis(1);

    fn new() -> Self {
        Self {
            round: AtomicU64::new(0),
            caller: rayon::current_thread_index(),
        }
    }

    /// One job for each other thread, until [`Awake::release`]: verdicts, then spinning.
    fn hold<'s>(&'s self, scope: &rayon::Scope<'s>, verdicts: &'s Doomed<'_>) {
        let round = self.round.load(Mem::Acquire);
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(move |_| {
                // The caller never waits here (it is the one that ends the wait).
                if rayon::current_thread_index() == self.caller {
                    return;
                }
                let current = || self.round.load(Mem::Acquire) == round;
                while current() && verdicts.take_one() {}
                let start = std::time::Instant::now();
                while current() && start.elapsed() < Self::MAX_SPIN {
                    std::hint::spin_loop();
                }
            });
        }
    }

    /// Ends the jobs of [`Awake::hold`] (each after the verdict it is computing).
    fn release(&self) {
        self.round.fetch_add(1, Mem::Release);
    }
}

/// The plans of one batch, in its order (the read-only plans of a batch do not see each
/// other, so the order of planning is free). The items `inline` names (answered without a
/// plan: the doomed ones) are planned on the calling thread; the others in parallel, the
/// threads taking them one at a time, the costliest first by `cost` (ties in batch order),
/// or inline for a single one. Plans take from microseconds to a millisecond: a long one
/// begun last leaves the other threads idle until it ends. mech-holes-shark at 1/64 %, two
/// threads, 117 rounds (instrumented runs): rayon's adaptive split, 28.7 ms of wall time
/// for the rounds' plans; one job per plan, 22.2 ms with 3.7 ms of one thread waiting for
/// the other's last plan; taken costliest first, 19.2-20.3 ms with 0.7-0.8 ms, for 33-35 ms
/// of planning. A thread that finds no plan left calls `aside` (work that decides nothing
/// of the batch: the run's verdicts ahead) until the last plan ends, spinning when it has
/// none: mech-holes-shark at 1/64 %, 1.8 ms of such waiting in 114 rounds (instrumented),
/// the batched run 29.7 -> 28.7 ms (trimmed means of 40 alternating runs).
fn plan_each<T: Sync, R: Send>(
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
struct Finally<F: FnMut()>(F);

impl<F: FnMut()> Drop for Finally<F> {
    fn drop(&mut self) {
        (self.0)();
    }
}

/// The vertices whose removal the fiber test turned away on the starting mesh, as long as their
/// fan stays as it was (the subset run of a first-in-first-out queue; not in the paper). At
/// small epsilons that is almost every attempt (armadillo at 1/64 %: 26,130 of 27,717). Each
/// verdict is the plan's own answer (`LocalSimplifier::plan` with a filler that fills nothing)
/// on a copy of the starting mesh, taken in vertex order (the queue's when it starts with every
/// vertex): by the other threads while the calling thread selects and commits ([`Awake`]), and
/// by the calling thread when the queue reaches a vertex whose verdict nobody has taken yet (it
/// takes others ahead while it waits for one being computed). A verdict is the same whoever
/// computes it and whenever, and the queue only asks for the verdicts of vertices whose fan
/// never changed: the outcome is the same as with every verdict computed before the run, and
/// the same for any number of threads. A vertex whose fan changes before the queue reaches it
/// needs no verdict (mech-holes-shark at 1/64 %: 1,455 of 5,246, of which about 1,220 are
/// never computed; the others were taken ahead before their fan changed).
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
struct Doomed<'s> {
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
enum Verdict {
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
    fn new(start: Option<(LocalSimplifier<'s>, &'s dyn Filter)>, queue: &RemovalQueue) -> Self {
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
    fn take_one(&self) -> bool {
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
    fn holds(&self, v: VertexId) -> bool {
        self.verdict(v) == Verdict::Doomed
    }

    /// Whether `v`'s plan may leave the fiber test out (see the type's docs); asked after
    /// [`Doomed::holds`].
    fn passed(&self, v: VertexId) -> bool {
        self.state
            .get(v.index())
            .is_some_and(|x| x.load(Mem::Acquire) == Verdict::Passed as u8)
    }

    /// `v`'s fan changed: its verdict no longer holds (nor is it needed).
    fn forget(&self, v: VertexId) {
        if let Some(x) = self.state.get(v.index()) {
            x.store(Verdict::Unknown as u8, Mem::Release);
        }
    }

    /// The candidates the verdicts the run used gave the filter.
    fn used_tests(&self) -> u64 {
        self.used.load(Mem::Relaxed)
    }
}

/// The filler of [`Doomed`]'s plans: the fiber test runs before the filling, so a
/// filling that never succeeds leaves its answer alone.
struct FillNothing;

impl HoleFiller for FillNothing {
    fn fill(&self, _: &mut FillContext<'_>) -> bool {
        false
    }
}

/// Counts a failed attempt at `v` and tells the visitor.
fn rejected(stats: &mut Stats, visitor: &mut dyn Visitor, v: VertexId, reason: Rejection) {
    if reason == Rejection::NoFillAcrossFiber {
        stats.no_valid_fill += 1;
        stats.no_fill_across_fiber += 1;
    } else if reason == Rejection::NoValidFill {
        stats.no_valid_fill += 1;
    } else {
        stats.refused += 1;
    }
    visitor.on_rejected(v, reason);
}

/// The phase after the subset run ([`Placement::Slide`], [`Placement::Collapse`]): every
/// live vertex in id order, first in first out: the plain removal, else the slide of
/// [`LocalSimplifier::try_slide_remove`] (with fibers), else (with `policies.collapse`) the
/// collapse of [`LocalSimplifier::try_collapse`] on the positions of `collapse_candidates`,
/// cheapest first, until one passes; after a removal the hole's vertices and the neighbours
/// of moved vertices are queued again. The first time round, the plain removal is skipped:
/// the subset run failed it last, and by the paper's rule (only neighbours are queued again)
/// nothing around it changed since; only vertices queued again after a change try it. (A
/// removal near a vertex but not next to it, across a thin part, can unblock it; the subset
/// run gives those up too.)
///
/// Batched like the subset run, with the box of [`moving_box`] (the two-ring and the
/// neighbours' fibers: every face a slide or collapse of the vertex reads or changes) in
/// place of the one-ring's; a slid or collapsed position outside that box is not tried, so
/// the box holds. With `check_each_step`, one vertex at a time (same plans, other re-queue
/// order).
fn moving_phase(
    local: &mut LocalSimplifier<'_>,
    policies: &Policies<'_>,
    stats: &mut Stats,
    visitor: &mut dyn Visitor,
) -> Result<(), SimplifyError> {
    let mut queue = queue_vertices(local.mesh(), &Fifo);
    // Whether the vertex's neighbourhood changed since the subset run failed it.
    let mut changed = vec![
        false;
        local
            .mesh()
            .vertices()
            .map(|v| v.index() + 1)
            .max()
            .unwrap_or(0)
    ];
    let fibers = policies.fibers.as_ref();
    let ways = Ways {
        filter: policies.filter,
        filler: policies.filler,
        fibers,
        collapse: policies.collapse,
    };
    loop {
        let batch: Vec<VertexId> = if policies.check_each_step {
            queue.pop().into_iter().collect()
        } else {
            independent_batch(
                &mut queue,
                local.mesh(),
                |m, v| moving_box(m, v, fibers),
                |_| false,
            )
            .into_iter()
            .map(|(v, _)| v)
            .collect()
        };
        if batch.is_empty() {
            break;
        }
        let jobs: Vec<(VertexId, bool)> = batch
            .iter()
            .map(|&v| (v, std::mem::take(&mut changed[v.index()])))
            .collect();
        let plans = {
            let local = &*local;
            plan_each(
                &jobs,
                |_| false,
                |_| 0,
                |&(v, plain)| local.plan_stuck(v, plain, &ways),
                || false,
            )
        };
        for (&v, (plan, tests)) in batch.iter().zip(plans) {
            if policies.stop.should_stop(local.mesh().num_faces()) {
                return Ok(());
            }
            stats.attempts += 1;
            visitor.on_attempt(v);
            local.candidate_tests += tests;
            let result = plan.and_then(|(plan, way)| {
                let moved: Vec<VertexId> = plan.moves.iter().map(|m| m.0).collect();
                local.apply(v, plan).map(|removal| (removal, way, moved))
            });
            match result {
                Ok((removal, way, moved)) => {
                    stats.removed += 1;
                    stats.slid += usize::from(way == Way::Slid);
                    stats.collapsed += usize::from(way == Way::Collapsed);
                    visitor.on_removed(v, &removal.faces);
                    let around = moved.iter().flat_map(|&u| local.mesh().vertex_neighbors(u));
                    let again: Vec<VertexId> = removal
                        .hole
                        .vertices
                        .iter()
                        .copied()
                        .chain(around)
                        .collect();
                    for w in again {
                        if local.mesh().contains_vertex(w) {
                            changed[w.index()] = true;
                            queue.push(local.mesh(), &Fifo, w);
                        }
                    }
                }
                Err(reason) => rejected(stats, visitor, v, reason),
            }
            if policies.check_each_step {
                local
                    .sanity_check()
                    .map_err(|message| SimplifyError::SanityCheck { after: v, message })?;
            }
        }
    }
    Ok(())
}

/// What the moving phase may try (the thread-safe part of [`Policies`]).
struct Ways<'p> {
    filter: &'p dyn Filter,
    filler: &'p dyn HoleFiller,
    fibers: Option<&'p VertexFibers<'p>>,
    collapse: bool,
}

/// How a removal of the moving phase went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Way {
    Plain,
    Slid,
    Collapsed,
}

/// The box of `v`'s two-ring and of its neighbours' fibers: every face that a slide or a
/// collapse of `v` reads or changes lies in it, when the slid and collapsed positions do.
fn moving_box(m: &HalfEdgeMesh, v: VertexId, fibers: Option<&VertexFibers<'_>>) -> Aabb {
    let mut points = vec![m.position(v)];
    for u in m.vertex_neighbors(v) {
        points.extend(m.vertex_neighbors(u).map(|x| m.position(x)));
        if let Some((a, d)) = fibers.and_then(|f| f.segment(u)) {
            points.extend([a, a + d]);
        }
    }
    Aabb::from_points(&points)
}

/// At most this many (neighbour, position) pairs are tried per vertex by the collapse step.
const COLLAPSE_TRIES: usize = 8;

/// A collapse position whose root-mean-square distance to the planes of the faces around
/// `v` and `w` exceeds this many times the local offset (half the longer fiber of `v` and
/// `w`) is not tried. A choice, measured: on armadillo at 1/64 % such positions are 88 % of
/// the tries and 0.6 % of the successes (3 of 543); the test is f64 and only skips, so it can
/// cost faces, never the guarantee.
const COLLAPSE_REACH: f64 = 1.25;

/// The positions an edge collapse of `v` may try, at most [`COLLAPSE_TRIES`], cheapest first
/// by the quadric cost below: for each interior neighbour `w`, the point minimising the
/// area-weighted squared distances to the planes of the current faces around `v` and `w`
/// (memoryless quadrics, regularised towards the edge's midpoint so that flat and crease
/// neighbourhoods have one answer), `w`'s own position (a half-edge collapse) and the
/// midpoint. The cost is that mean squared distance (the quadric over the faces' total
/// area); with fibers, positions beyond [`COLLAPSE_REACH`] are dropped. f64, a priority
/// only: every position is tested exactly.
fn collapse_candidates(
    m: &HalfEdgeMesh,
    v: VertexId,
    fibers: Option<&VertexFibers<'_>>,
) -> Vec<(f64, VertexId, DVec3)> {
    use glam::DMat3;
    if m.is_border_vertex(v) {
        return Vec::new();
    }
    let planes = |x: VertexId| {
        m.vertex_faces(x).map(|f| {
            let [a, b, c] = m.face_vertices(f).map(|y| m.position(y));
            let n2 = (b - a).cross(c - a);
            let area = 0.5 * n2.length();
            let n = if area > 0.0 {
                n2 / (2.0 * area)
            } else {
                DVec3::ZERO
            };
            (f, area, n, -n.dot(a))
        })
    };
    let half_fiber = |x: VertexId| {
        fibers
            .and_then(|f| f.segment(x))
            .map(|(_, d)| 0.5 * d.length())
    };
    let around_v: Vec<_> = planes(v).collect();
    let mut out = Vec::new();
    for w in m.vertex_neighbors(v) {
        if m.is_border_vertex(w) {
            continue;
        }
        let mut faces: Vec<_> = around_v.iter().copied().chain(planes(w)).collect();
        faces.sort_unstable_by_key(|x| x.0);
        faces.dedup_by_key(|x| x.0);
        let total: f64 = faces.iter().map(|x| x.1).sum();
        if !total.is_finite() || total <= 0.0 {
            continue;
        }
        let cost = |x: DVec3| -> f64 {
            faces
                .iter()
                .map(|&(_, a, n, d)| a * (n.dot(x) + d).powi(2))
                .sum::<f64>()
                / total
        };
        // Without a fiber at either end there is no local offset to compare with.
        let reach = match (half_fiber(v), half_fiber(w)) {
            (None, None) => f64::INFINITY,
            (a, b) => COLLAPSE_REACH * a.unwrap_or(0.0).max(b.unwrap_or(0.0)),
        };
        let mut push = |x: DVec3| {
            let c = cost(x);
            if c <= reach * reach {
                out.push((c, w, x));
            }
        };
        let mid = 0.5 * (m.position(v) + m.position(w));
        let lambda = 1e-3 * total;
        let mut q = DMat3::from_diagonal(DVec3::splat(lambda));
        let mut r = lambda * mid;
        for &(_, a, n, d) in &faces {
            q += DMat3::from_cols(n * n.x, n * n.y, n * n.z) * a;
            r -= n * (a * d);
        }
        if q.determinant().abs() > 0.0 {
            let x = q.inverse() * r;
            if x.is_finite() {
                push(x);
            }
        }
        push(m.position(w));
        push(mid);
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.truncate(COLLAPSE_TRIES);
    out
}

#[derive(Clone, Copy, Debug)]
struct Entry {
    priority: f64,
    seq: u64,
    v: VertexId,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    /// Reversed: the heap pops the smallest priority, then the earliest queued.
    fn cmp(&self, o: &Self) -> Ordering {
        o.priority
            .total_cmp(&self.priority)
            .then(o.seq.cmp(&self.seq))
    }
}

/// The removal queue: each vertex at most once, smallest priority first, then first queued.
#[derive(Clone, Debug, Default)]
pub struct RemovalQueue {
    heap: BinaryHeap<Entry>,
    /// Entries in the order the heap would pop them, at constant cost each: those queued
    /// with a first-in-first-out order ([`QueueOrder::is_fifo`]: one priority for every
    /// vertex) and those put back by a batch window. [`RemovalQueue::pop`] takes the first
    /// of both stores.
    fifo: VecDeque<Entry>,
    queued: Vec<bool>,
    seq: u64,
}

impl RemovalQueue {
    /// Queues `v` unless it is queued already or is not a live vertex.
    pub fn push(&mut self, mesh: &HalfEdgeMesh, order: &dyn QueueOrder, v: VertexId) {
        if !mesh.contains_vertex(v) {
            return;
        }
        if self.queued.len() <= v.index() {
            self.queued.resize(v.index() + 1, false);
        }
        if self.queued[v.index()] {
            return;
        }
        self.queued[v.index()] = true;
        let e = Entry {
            priority: order.priority(mesh, v),
            seq: self.seq,
            v,
        };
        // The deque stays in heap order while its priorities are one (a single order).
        if order.is_fifo() && self.fifo.back().is_none_or(|b| b.priority == e.priority) {
            self.fifo.push_back(e);
        } else {
            self.heap.push(e);
        }
        self.seq += 1;
    }

    /// Takes the next entry (the heap's order over both stores).
    fn pop_entry(&mut self) -> Option<Entry> {
        let from_heap = match (self.heap.peek(), self.fifo.front()) {
            (Some(h), Some(f)) => h > f,
            (h, _) => h.is_some(),
        };
        if from_heap {
            self.heap.pop()
        } else {
            self.fifo.pop_front()
        }
    }

    /// Puts back the entries just taken by [`RemovalQueue::pop_entry`] (in the order taken,
    /// nothing queued since, still flagged as queued). They come before every entry left,
    /// so in front of the deque, in order, they are where the heap would keep them.
    fn put_back(&mut self, entries: Vec<Entry>) {
        debug_assert!(
            entries.windows(2).all(|w| w[0] > w[1]),
            "not in the order taken"
        );
        debug_assert!(
            entries
                .last()
                .is_none_or(|e| self.fifo.front().is_none_or(|f| e > f)
                    && self.heap.peek().is_none_or(|h| e > h)),
            "queued since"
        );
        for e in entries.into_iter().rev() {
            self.fifo.push_front(e);
        }
    }

    /// Takes the next vertex.
    pub fn pop(&mut self) -> Option<VertexId> {
        let e = self.pop_entry()?;
        self.queued[e.v.index()] = false;
        Some(e.v)
    }

    /// Number of queued vertices.
    #[must_use]
    pub fn len(&self) -> usize {
        self.heap.len() + self.fifo.len()
    }

    /// True when nothing is queued.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty() && self.fifo.is_empty()
    }

    /// Each queued vertex is live, flagged, and stored once; the deque is in queue order.
    pub fn sanity_check(&self, mesh: &HalfEdgeMesh) -> Result<(), String> {
        let mut seen = vec![false; self.queued.len()];
        if self
            .fifo
            .iter()
            .zip(self.fifo.iter().skip(1))
            .any(|(a, b)| a <= b)
        {
            return Err("first-in-first-out entries out of order".into());
        }
        for e in self.heap.iter().chain(&self.fifo) {
            let i = e.v.index();
            if !self.queued[i] || seen[i] {
                return Err(format!("queue entry {} unflagged or repeated", e.v));
            }
            if !mesh.contains_vertex(e.v) {
                return Err(format!("queued vertex {} is dead", e.v));
            }
            seen[i] = true;
        }
        if seen != self.queued {
            return Err("queue flags disagree with the heap".into());
        }
        Ok(())
    }
}

/// How far [`independent_batch`] looks into the queue, and how many it takes at most.
/// Larger batches wake the other threads less often and leave less of the batch's last plan
/// alone on one thread, but the selection is serial and its box tests grow with the square
/// of the window. bunny00 at 1/64 %, 2 threads (instrumented run): 1,989 batches with 256
/// and 64, the selection 0.046 s and the planning 1.076 s of wall time for 1.728 s of work;
/// 1,130 batches with 512 and 128, 0.058 s and 0.983 s for 1.724 s; 675 with 1,024 and 256,
/// 0.088 s and 0.966 s. armadillo at 1/64 % gains nothing beyond 256 (its selection took
/// 0.021, 0.036 and 0.068 s).
const BATCH_WINDOW: usize = 512;
const BATCH_LIMIT: usize = 128;

/// Takes vertices off a first-in-first-out queue for one round of planning: the front
/// vertex, then, among the next ones, every vertex whose closed box `reach(mesh, v)` is
/// apart from the boxes of all vertices before it (taken or not), until [`BATCH_LIMIT`]
/// are taken or [`BATCH_WINDOW`] are looked at. The box must hold everything a plan of the
/// vertex reads or its removal changes (the subset run: the one-ring box, [`one_ring_box`],
/// which holds the vertex's fan and every candidate triangle of its hole): the removals of
/// a batch do not see each other, nor do they see the skipped vertices' removals, and
/// carrying them out before those changes nothing but the order in which re-queued
/// neighbours are appended. Skipped vertices keep their places.
///
/// Vertices `doomed` (their attempt is known to change nothing, see [`Doomed`]) are taken
/// as they come, marked `true`, without a box: they hold back no one and are held back by
/// no one, and do not count towards the window and the limit. One whose fan a removal
/// earlier in the batch changes is on that removal's hole, so it is queued again and
/// attempted anew; the only departure from one-at-a-time order is that its first attempt
/// came before the removal. (Holding doomed vertices back like the others made the
/// batches mostly skipped vertices: armadillo at 1/64 %, 149 batches of 2 to 29 plans
/// each; now 51 of 128.)
///
/// The batches depend on the queue and the mesh only, never on the number of threads, so
/// the output does not either.
fn independent_batch(
    queue: &mut RemovalQueue,
    mesh: &HalfEdgeMesh,
    mut reach: impl FnMut(&HalfEdgeMesh, VertexId) -> Aabb,
    doomed: impl Fn(VertexId) -> bool,
) -> Vec<(VertexId, bool)> {
    let mut batch = Vec::new();
    let mut skipped = Vec::new();
    let mut boxes: Vec<Aabb> = Vec::new();
    let mut planned = 0;
    // Only vertices to be planned are skipped: doomed ones are always taken.
    while planned < BATCH_LIMIT && planned + skipped.len() < BATCH_WINDOW {
        let Some(e) = queue.pop_entry() else {
            break;
        };
        let v = e.v;
        if doomed(v) {
            queue.queued[v.index()] = false;
            batch.push((v, true));
            continue;
        }
        let b = reach(mesh, v);
        // Latest first: a vertex's neighbours in the queue are mostly just before it.
        if boxes.iter().rev().any(|x| x.overlaps(&b)) {
            skipped.push(e);
        } else {
            queue.queued[v.index()] = false;
            batch.push((v, false));
            planned += 1;
        }
        boxes.push(b);
    }
    queue.put_back(skipped);
    batch
}

/// The [`one_ring_box`]es of the subset run, kept while the one-ring stays: a vertex's box
/// changes only when its neighbours do (no vertex moves there), that is when it is on the
/// hole of a removal ([`RingBoxes::forget`] it then). Vertices skipped by a batch are taken
/// up again by the next, with the box computed the first time.
#[derive(Default)]
struct RingBoxes(Vec<Option<Aabb>>);

impl RingBoxes {
    fn get(&mut self, mesh: &HalfEdgeMesh, v: VertexId) -> Aabb {
        let i = v.index();
        if self.0.len() <= i {
            self.0.resize(i + 1, None);
        }
        *self.0[i].get_or_insert_with(|| one_ring_box(mesh, v))
    }

    fn forget(&mut self, v: VertexId) {
        if let Some(b) = self.0.get_mut(v.index()) {
            *b = None;
        }
    }
}

/// The box of `v` and its neighbours.
fn one_ring_box(mesh: &HalfEdgeMesh, v: VertexId) -> Aabb {
    mesh.vertex_neighbors(v)
        .fold(Aabb::from_points(&[mesh.position(v)]), |b, w| {
            b.union(&Aabb::from_points(&[mesh.position(w)]))
        })
}

/// Every live vertex, in id order, prioritised by `order` (section 5.2: "placing all
/// vertices in a queue").
#[must_use]
pub fn queue_vertices(mesh: &HalfEdgeMesh, order: &dyn QueueOrder) -> RemovalQueue {
    let mut q = RemovalQueue::default();
    for v in mesh.vertices() {
        q.push(mesh, order, v);
    }
    q
}

/// A successful vertex removal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Removal {
    /// The hole the vertex left.
    pub hole: Hole,
    /// The faces that fill it.
    pub faces: Vec<FaceId>,
}

/// A mesh being simplified by vertex removal, with the spatial index of its live faces.
#[derive(Debug)]
pub struct LocalSimplifier<'m> {
    mesh: &'m mut HalfEdgeMesh,
    grid: FaceGrid,
    keep_border: bool,
    /// Asked before every plain removal's filling ([`Policies::fiber_test`]).
    fiber_test: Option<&'m FiberTest<'m>>,
    /// Candidate triangles given to the filter so far.
    pub candidate_tests: u64,
}

impl<'m> LocalSimplifier<'m> {
    /// Indexes the faces of `mesh`. With `keep_border`, border vertices are never removed.
    pub fn new(mesh: &'m mut HalfEdgeMesh, keep_border: bool) -> Self {
        let grid = FaceGrid::from_mesh(mesh);
        Self {
            grid,
            ..Self::without_grid(mesh, keep_border)
        }
    }

    /// [`Self::new`] with an empty face index, for plans that read none (the fiber test's
    /// verdicts, see [`Doomed`]) while the index is built; the caller sets `grid` before
    /// anything else.
    fn without_grid(mesh: &'m mut HalfEdgeMesh, keep_border: bool) -> Self {
        Self {
            mesh,
            grid: FaceGrid::empty(),
            keep_border,
            fiber_test: None,
            candidate_tests: 0,
        }
    }

    /// The same simplifier with the fiber test before every plain removal's filling:
    /// `test`'s envelopes must be barriers of the filters it is given and apart from every
    /// face of the mesh (see [`FiberTest`]).
    #[must_use]
    pub fn with_fiber_test(mut self, test: Option<&'m FiberTest<'m>>) -> Self {
        self.fiber_test = test;
        self
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> &HalfEdgeMesh {
        self.mesh
    }

    /// The index of the live faces.
    #[must_use]
    pub fn grid(&self) -> &FaceGrid {
        &self.grid
    }

    /// The mesh's and the grid's sanity checks.
    pub fn sanity_check(&self) -> Result<(), String> {
        self.mesh.sanity_check()?;
        self.grid.sanity_check(self.mesh)
    }

    /// Tries to remove `v` (section 5.2): removes its fan, fills the hole with `filler`
    /// (every candidate through `filter`), and keeps the result, or restores the fan exactly.
    pub fn try_remove_vertex(
        &mut self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> Result<Removal, Rejection> {
        let (plan, tests) = self.plan(v, filter, filler);
        self.candidate_tests += tests;
        self.apply(v, plan?)
    }

    /// Tries to remove `v` with its interior neighbours slid along their fibers (the paper's
    /// section 8): each neighbour `u` whose fiber is within 60 degrees of `v`'s goes
    /// half-way from where it is towards the point of its fiber on the plane through `v`
    /// perpendicular to `v`'s fiber, kept within `[0.05, 0.95]` of the fiber. Then the hole
    /// is filled as in [`Self::try_remove_vertex`] (the filling sees the slid positions),
    /// and every other face around a slid vertex, at its new position, must pass `filter`
    /// against the approximation with the filling in it. All or nothing: the slide is only
    /// planned (the mesh is edited once it passed). Returns the removal and the slid vertices.
    ///
    /// Choices (not in the paper, which only sketches the idea): half-way (a chord over a
    /// curved patch then errs on both sides instead of one), the 60 degrees, the range, and
    /// border vertices never slide (their tubes hold them).
    pub fn try_slide_remove(
        &mut self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
        fibers: &VertexFibers<'_>,
    ) -> Result<(Removal, Vec<VertexId>), Rejection> {
        let moves = self.slide_moves(v, fibers)?;
        let (plan, tests) = self.plan_moved(v, moves, filter, filler);
        self.candidate_tests += tests;
        let plan = plan?;
        let slid = plan.moves.iter().map(|m| m.0).collect();
        self.apply(v, plan).map(|removal| (removal, slid))
    }

    /// The positions [`Self::try_slide_remove`] gives `v`'s neighbours (read only).
    fn slide_moves(
        &self,
        v: VertexId,
        fibers: &VertexFibers<'_>,
    ) -> Result<Vec<(VertexId, DVec3)>, Rejection> {
        let m = &*self.mesh;
        if !m.contains_vertex(v) || m.is_isolated(v) {
            return Err(Rejection::NotAVertex);
        }
        let Some((_, dv)) = fibers.segment(v) else {
            return Err(Rejection::NoValidFill);
        };
        let nv = dv.normalize();
        let pv = m.position(v);
        let mut moves = Vec::new();
        for u in m.vertex_neighbors(v) {
            if m.is_border_vertex(u) {
                continue;
            }
            let Some((a, d)) = fibers.segment(u) else {
                continue;
            };
            let dn = d.dot(nv);
            if dn <= 0.5 * d.length() {
                continue;
            }
            let pu = m.position(u);
            let s_now = (pu - a).dot(d) / d.length_squared();
            let s_plane = (pv - a).dot(nv) / dn;
            let s = (0.5 * (s_now + s_plane)).clamp(SLIDE_RANGE, 1.0 - SLIDE_RANGE);
            let q = a + d * s;
            if (s - s_now).abs() > 1e-3 && in_range(q) && q != pu {
                moves.push((u, q));
            }
        }
        if moves.is_empty() {
            return Err(Rejection::NoValidFill);
        }
        Ok(moves)
    }

    /// Tries to remove `v` by collapsing its edge into the neighbour `w`, moved to `p`: the
    /// hole `v` leaves is filled by the fan from `w` (a half-edge collapse when `p` is `w`'s
    /// position), every triangle of the fan and every other face around the moved `w` through
    /// `filter`. All or nothing, like [`Self::try_slide_remove`]. Border vertices, a `p` with
    /// a coordinate outside the exact predicates' range, and edges that break the link
    /// condition (an edge of the fan that exists elsewhere) are refused.
    pub fn try_collapse(
        &mut self,
        v: VertexId,
        w: VertexId,
        p: DVec3,
        filter: &dyn Filter,
    ) -> Result<Removal, Rejection> {
        let (plan, tests) = self.plan_collapse(v, w, p, filter);
        self.candidate_tests += tests;
        self.apply(v, plan?)
    }

    /// The plan of [`Self::try_collapse`] (read only), and the filter calls it made.
    fn plan_collapse(
        &self,
        v: VertexId,
        w: VertexId,
        p: DVec3,
        filter: &dyn Filter,
    ) -> (Result<Plan, Rejection>, u64) {
        let m = &*self.mesh;
        if !m.contains_vertex(v) || !m.contains_vertex(w) || m.find_halfedge(v, w).is_none() {
            return (Err(Rejection::NotAVertex), 0);
        }
        if m.is_border_vertex(v) || m.is_border_vertex(w) || !in_range(p) {
            return (Err(Rejection::NoValidFill), 0);
        }
        let moves = if p == m.position(w) {
            Vec::new()
        } else {
            vec![(w, p)]
        };
        self.plan_moved(v, moves, filter, &FanFrom(w))
    }

    /// The moving phase's plan for `v` (read only): the plain removal when `plain`, else or
    /// then the slide, then the collapses (see `moving_phase`), each position inside
    /// [`moving_box`]. Also returns the filter calls.
    fn plan_stuck(
        &self,
        v: VertexId,
        plain: bool,
        ways: &Ways<'_>,
    ) -> (Result<(Plan, Way), Rejection>, u64) {
        let (filter, filler) = (ways.filter, ways.filler);
        let mut tests = 0;
        if plain {
            let (plan, t) = self.plan(v, filter, filler);
            tests += t;
            match plan {
                Ok(plan) => return (Ok((plan, Way::Plain)), tests),
                Err(Rejection::NoValidFill | Rejection::NoFillAcrossFiber) => {}
                Err(other) => return (Err(other), tests),
            }
        }
        let m = &*self.mesh;
        if !m.contains_vertex(v) || m.is_isolated(v) {
            return (Err(Rejection::NotAVertex), tests);
        }
        let fibers = ways.fibers;
        let reach = moving_box(m, v, fibers);
        if let Some(moves) = fibers.and_then(|f| self.slide_moves(v, f).ok()) {
            if moves.iter().all(|&(_, q)| reach.contains(q)) {
                let (plan, t) = self.plan_moved(v, moves, filter, filler);
                tests += t;
                if let Ok(plan) = plan {
                    return (Ok((plan, Way::Slid)), tests);
                }
            }
        }
        if ways.collapse {
            for (_, w, p) in collapse_candidates(m, v, fibers) {
                if !reach.contains(p) {
                    continue;
                }
                let (plan, t) = self.plan_collapse(v, w, p, filter);
                tests += t;
                if let Ok(plan) = plan {
                    return (Ok((plan, Way::Collapsed)), tests);
                }
            }
        }
        (Err(Rejection::NoValidFill), tests)
    }

    /// Sets vertex positions and re-indexes the `affected` faces (every live face around a
    /// moved vertex).
    fn move_vertices(
        &mut self,
        affected: &[FaceId],
        moves: impl Iterator<Item = (VertexId, DVec3)>,
    ) {
        for &f in affected {
            self.grid.remove(f);
        }
        for (u, q) in moves {
            self.mesh.set_position(u, q);
        }
        for &f in affected {
            let t = self.mesh.face_vertices(f);
            self.grid.insert(f, t, t.map(|x| self.mesh.position(x)));
        }
    }

    /// Everything [`Self::try_remove_vertex`] decides, without editing anything: the checks,
    /// the hole (as `remove_vertex_fan` would leave it) and its filling, with the fan
    /// excluded from the approximation instead of removed. Shared access only, so plans of
    /// removals whose neighbourhoods are apart can be made in parallel. Also returns the
    /// number of candidates given to the filter.
    fn plan(
        &self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> (Result<Plan, Rejection>, u64) {
        self.plan_moved(v, Vec::new(), filter, filler)
    }

    /// [`Self::plan`] without the fiber test: the same outcome, but for the reason of a
    /// rejection ([`Rejection::NoValidFill`] where the test would have said
    /// [`Rejection::NoFillAcrossFiber`]).
    fn plan_without_fiber_test(
        &self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> (Result<Plan, Rejection>, u64) {
        let mut tests = 0;
        let plan = self.plan_counted(v, Vec::new(), filter, filler, false, &mut tests);
        (plan, tests)
    }

    /// [`Self::plan`] with vertices at planned positions (`moves`, each vertex once): the
    /// faces around them are taken out of the grid's view and tested at their planned
    /// positions (the filling against them, then each of them that stays against the
    /// approximation with the filling in it).
    fn plan_moved(
        &self,
        v: VertexId,
        moves: Vec<(VertexId, DVec3)>,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> (Result<Plan, Rejection>, u64) {
        let mut tests = 0;
        let plan = self.plan_counted(v, moves, filter, filler, true, &mut tests);
        (plan, tests)
    }

    fn plan_counted(
        &self,
        v: VertexId,
        moves: Vec<(VertexId, DVec3)>,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
        fiber: bool,
        tests: &mut u64,
    ) -> Result<Plan, Rejection> {
        let m = &*self.mesh;
        if !m.contains_vertex(v) || m.is_isolated(v) {
            return Err(Rejection::NotAVertex);
        }
        let border = m.is_border_vertex(v);
        if border && self.keep_border {
            return Err(Rejection::BorderWithoutTubes);
        }
        if !m.is_manifold_vertex(v) {
            return Err(Rejection::NonManifold);
        }
        // The outgoing half-edges once: the fan (`vertex_faces` order) and the ring.
        let mut hs = Vec::with_capacity(8);
        hs.extend(m.outgoing_halfedges(v));
        let mut fan: Vec<FaceId> = Vec::with_capacity(hs.len());
        fan.extend(hs.iter().filter_map(|&h| m.face(h)));
        if border && fan.len() < 2 {
            return Err(Rejection::Ear);
        }
        if hs.len() > MAX_HOLE {
            return Err(Rejection::HoleTooLarge);
        }
        // The ring as `remove_vertex_fan` returns it: counter-clockwise from the outgoing
        // half-edge, starting after the border gap at a border vertex.
        let mut vertices: Vec<VertexId> = hs.iter().map(|&h| m.target(h)).collect();
        if hs.first().is_some_and(|&h| m.is_border_halfedge(h)) {
            vertices.rotate_left(1);
        }
        let hole = Hole {
            vertices,
            open: border,
        };
        // At most `MAX_HOLE` vertices: pairwise, without sorting a copy.
        let ring = &hole.vertices;
        if (1..ring.len()).any(|i| ring[..i].contains(&ring[i])) {
            return Err(Rejection::RepeatedNeighbour);
        }
        // Faces around a moved vertex: stale in the grid; those outside the fan stay, at
        // their planned positions (none move in the subset run: the fan alone is excluded).
        let mut moved_around = Vec::new();
        let mut stay = Vec::new();
        if !moves.is_empty() {
            moved_around.clone_from(&fan);
            for &(u, _) in &moves {
                for f in m.vertex_faces(u) {
                    if !moved_around.contains(&f) {
                        moved_around.push(f);
                        stay.push(m.face_vertices(f));
                    }
                }
            }
        }
        let excluded: &[FaceId] = if moves.is_empty() {
            &fan
        } else {
            &moved_around
        };
        // Every candidate of the filling has its corners among the hole's vertices.
        let corners: Vec<DVec3> = hole
            .vertices
            .iter()
            .map(|&u| position_in(m, &moves, u))
            .collect();
        let region = Aabb::from_points(&corners);
        // The fiber test (module `fiber`): interior vertices at their current positions.
        let path = match self.fiber_test {
            Some(test) if fiber && moves.is_empty() && !border => {
                test.path(v, m.position(v), &corners)
            }
            _ => None,
        };
        let nearby = Nearby::new(region);
        let mut ctx = FillContext::new(m, &self.grid, filter, &hole)
            .excluding(excluded)
            .moving(&moves, &stay)
            .near(&nearby);
        let (mut filled, mut across) = (false, true);
        // The input faces around `v`: their envelope triangles refuse most of the fiber
        // test's candidates (tested first; only the order of the tests changes).
        let near = match (&path, self.fiber_test) {
            (Some(_), Some(test)) => test.faces_around(v),
            _ => &[],
        };
        filter.within_near(&region, near, &mut || {
            if let Some(path) = &path {
                if !ctx.a_triangle_across_may_pass(path, &corners) {
                    let fan: Vec<[DVec3; 3]> = fan
                        .iter()
                        .map(|&f| m.face_vertices(f).map(|x| m.position(x)))
                        .collect();
                    across = !path.crosses_once(fan);
                    if !across {
                        return;
                    }
                }
            }
            filled = filler.fill(&mut ctx);
        });
        *tests = ctx.tests;
        if !across {
            return Err(Rejection::NoFillAcrossFiber);
        }
        let placed = ctx.placed().to_vec();
        if !filled {
            return Err(Rejection::NoValidFill);
        }
        debug_assert_eq!(placed.len() + 2, hole.len());
        for (k, &t) in stay.iter().enumerate() {
            let others: Vec<[VertexId; 3]> = stay
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != k)
                .map(|(_, &g)| g)
                .collect();
            let approximation = Approximation {
                mesh: m,
                grid: &self.grid,
                placed: &placed,
                excluded,
                moved: &moves,
                extra: &others,
                nearby: None,
            };
            let profile = CandidateProfile {
                triangle: t,
                corners: t.map(|x| approximation.position(x)),
                // The edges of a moved vertex are interior; the third edge did not move.
                border_edges: [false; 3],
                approximation,
            };
            *tests += 1;
            if !filter.accepts(&profile) {
                return Err(Rejection::NoValidFill);
            }
        }
        // The filling and the moved stars must not carry a barrier component across (an
        // open hole claims nothing there: its boundary is not the fan's).
        if !border {
            let at = |t: [VertexId; 3], moved: bool| {
                t.map(|x| {
                    if moved {
                        position_in(m, &moves, x)
                    } else {
                        m.position(x)
                    }
                })
            };
            let old: Vec<[DVec3; 3]> = fan
                .iter()
                .map(|&f| at(m.face_vertices(f), false))
                .chain(stay.iter().map(|&t| at(t, false)))
                .collect();
            let new: Vec<[DVec3; 3]> = placed.iter().chain(&stay).map(|&t| at(t, true)).collect();
            *tests += 1;
            if filter.refuses_replacement(&old, &new) {
                return Err(Rejection::NoValidFill);
            }
        }
        Ok(Plan {
            hole,
            fan,
            placed,
            moves,
        })
    }

    /// Carries out a plan made by [`Self::plan`] on the mesh as it was then: moves its
    /// vertices, removes the fan, adds the filling (the mesh's `add_faces` is the last
    /// guard), updates the grid; on a refusal everything comes back exactly.
    fn apply(&mut self, v: VertexId, plan: Plan) -> Result<Removal, Rejection> {
        let mut affected: Vec<FaceId> = plan
            .moves
            .iter()
            .flat_map(|&(u, _)| self.mesh.vertex_faces(u))
            .collect();
        affected.sort_unstable();
        affected.dedup();
        let back: Vec<(VertexId, DVec3)> = plan
            .moves
            .iter()
            .map(|&(u, _)| (u, self.mesh.position(u)))
            .collect();
        self.move_vertices(&affected, plan.moves.iter().copied());
        let cp = self.mesh.begin();
        let refused = match self.mesh.remove_vertex_fan(v) {
            Ok(ring) => {
                debug_assert_eq!(ring, plan.hole.vertices);
                self.mesh
                    .add_faces(&plan.placed)
                    .map_err(Rejection::MeshRefused)
            }
            Err(_) => Err(Rejection::NonManifold),
        };
        let faces = match refused {
            Ok(faces) => faces,
            Err(reason) => {
                self.mesh.rollback(cp);
                self.move_vertices(&affected, back.into_iter());
                return Err(reason);
            }
        };
        self.mesh
            .remove_vertex(v)
            .expect("the removed vertex is isolated");
        self.mesh.commit(cp);
        for &f in &plan.fan {
            self.grid.remove(f);
        }
        for &f in &faces {
            let t = self.mesh.face_vertices(f);
            self.grid.insert(f, t, t.map(|x| self.mesh.position(x)));
        }
        self.grid.rebalance();
        Ok(Removal {
            hole: plan.hole,
            faces,
        })
    }
}

/// Every coordinate of `p` in the exact predicates' range (a cancellation can leave one
/// below it).
fn in_range(p: DVec3) -> bool {
    p.to_array()
        .into_iter()
        .all(|x| envelope_mesh::check_coordinate(x).is_ok())
}

/// Fills a closed hole with the fan from one of its vertices (an edge collapse seen as a
/// vertex removal): the triangles `(apex, a, b)` for every hole edge `a b` not at the apex,
/// in hole order, each through the context's filter.
struct FanFrom(VertexId);

impl HoleFiller for FanFrom {
    fn fill(&self, ctx: &mut FillContext<'_>) -> bool {
        let hole = ctx.hole();
        let n = hole.len();
        let Some(k) = hole.vertices.iter().position(|&x| x == self.0) else {
            return false;
        };
        if hole.open || n < 3 {
            return false;
        }
        for i in 0..n {
            let j = (i + 1) % n;
            if i == k || j == k {
                continue;
            }
            // Increasing positions: a rotation of (k, i, j), so the hole's orientation.
            let mut t = [k, i, j];
            t.sort_unstable();
            if !ctx.accepts(t) {
                return false;
            }
            ctx.place(t);
        }
        true
    }
}

/// A planned removal ([`LocalSimplifier::plan`]).
struct Plan {
    hole: Hole,
    fan: Vec<FaceId>,
    placed: Vec<[VertexId; 3]>,
    /// Vertices to move first (a slide or a collapse), each once.
    moves: Vec<(VertexId, DVec3)>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;

    /// `plan_each` gives each item's plan in the batch's order, whatever it plans inline,
    /// first or in parallel, and whatever the threads do aside while others finish: batches
    /// of 0 to 40 items, some inline, costs out of order.
    #[test]
    fn plan_each_answers_in_batch_order() {
        for n in [0usize, 1, 2, 3, 7, 40] {
            for inline_every in [1usize, 2, 3, 100] {
                let batch: Vec<usize> = (0..n).collect();
                let inline = |&i: &usize| i % inline_every == 1;
                // Work aside for the threads that run out of plans: a bounded count of it.
                let aside = AtomicUsize::new(0);
                let planned = plan_each(
                    &batch,
                    inline,
                    |&i| (i * 7919) % 13,
                    |&i| (i, i * i),
                    || aside.fetch_add(1, Mem::Relaxed) < 1000,
                );
                let expected: Vec<(usize, usize)> = batch.iter().map(|&i| (i, i * i)).collect();
                assert_eq!(
                    planned, expected,
                    "{n} items, every {inline_every}th inline"
                );
            }
        }
    }

    /// A verdict is the plan's own answer on the starting mesh whoever takes it and
    /// whenever: on a bumpy sphere, the verdicts taken by other threads ahead of the queue
    /// (all of them, in parallel) and those asked one by one on the calling thread alone
    /// are the plan's answers; a vertex forgotten before it is asked has none; only the
    /// verdicts asked count their candidates. Fails when a forgotten verdict is still given,
    /// when a verdict lands on another vertex, or when a thread's verdict is lost.
    #[test]
    fn verdicts_are_the_plans_answers_whoever_takes_them() {
        use crate::{FiberTest, VertexFibers};
        use envelope_offset::{EnvelopeOptions, EpsilonField, build_envelopes};
        let mut soup = generate::icosphere(3, 1.0);
        for p in &mut soup.positions {
            *p *= 1.0 + 0.05 * (7.0 * p.x).sin() * (5.0 * p.y).cos();
        }
        let env =
            build_envelopes(&soup, &EnvelopeOptions::new(EpsilonField::Constant(0.004))).unwrap();
        assert!(env.proof.holds() && env.pinned.is_empty());
        let fibers = VertexFibers {
            inner: &env.inner.positions,
            outer: &env.outer.positions,
        };
        let test = FiberTest::new(fibers, &soup.faces);
        let barriers = Barriers::new(vec![env.outer.clone(), env.inner.clone()], vec![]).unwrap();
        let filter = EnvelopeFilter::new(&barriers);
        let mesh = HalfEdgeMesh::from_soup(&soup).unwrap();
        let queue = queue_vertices(&mesh, &Fifo);
        // The plan's own answers, one simplifier, no verdicts.
        let mut plain = mesh.clone();
        let plain = LocalSimplifier::without_grid(&mut plain, false).with_fiber_test(Some(&test));
        let answers: Vec<(Verdict, u64)> = mesh
            .vertices()
            .map(|v| match plain.plan(v, &filter, &FillNothing) {
                (Err(Rejection::NoFillAcrossFiber), t) => (Verdict::Doomed, t),
                (_, t) => (Verdict::Passed, t),
            })
            .collect();
        let doomed = answers.iter().filter(|a| a.0 == Verdict::Doomed).count();
        assert!(doomed > 50 && doomed < answers.len(), "{doomed} doomed");
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        for ahead in [false, true] {
            let mut copy = mesh.clone();
            let start =
                LocalSimplifier::without_grid(&mut copy, false).with_fiber_test(Some(&test));
            let verdicts = Doomed::new(Some((start, &filter as &dyn Filter)), &queue);
            let forgotten = |v: VertexId| v.index() % 7 == 3;
            if ahead {
                // Every verdict taken by the pool's threads at once, before anything is asked.
                pool.broadcast(|_| while verdicts.take_one() {});
            }
            let mut expected_tests = 0;
            for (v, &(answer, tests)) in mesh.vertices().zip(&answers) {
                if forgotten(v) {
                    verdicts.forget(v);
                    assert!(!verdicts.holds(v) && !verdicts.passed(v), "{v} forgotten");
                    continue;
                }
                assert_eq!(
                    verdicts.holds(v),
                    answer == Verdict::Doomed,
                    "{v}, ahead {ahead}"
                );
                assert_eq!(
                    verdicts.passed(v),
                    answer == Verdict::Passed,
                    "{v}, ahead {ahead}"
                );
                expected_tests += tests;
            }
            assert_eq!(verdicts.used_tests(), expected_tests, "ahead {ahead}");
        }
        // No verdicts without a starting mesh.
        let none = Doomed::new(None, &queue);
        assert!(mesh.vertices().all(|v| !none.holds(v) && !none.passed(v)));
    }

    /// A plan that panics ends `plan_each` with that panic, while the other threads work
    /// aside: none of them waits forever for the plan to be counted. Fails (the call does not
    /// return within the time allowed) when a panicking plan is not counted as done.
    #[test]
    fn plan_each_passes_a_panic_on() {
        let (send, receive) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(3)
                .build()
                .unwrap();
            let batch: Vec<usize> = (0..20).collect();
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                pool.install(|| {
                    plan_each(
                        &batch,
                        |_| false,
                        |&i| i,
                        |&i| {
                            assert_ne!(i, 7, "plan 7 fails");
                            std::thread::sleep(std::time::Duration::from_millis(2));
                            i
                        },
                        || false,
                    )
                })
            }));
            let _ = send.send(outcome.is_err());
        });
        let panicked = receive.recv_timeout(std::time::Duration::from_secs(20));
        assert_eq!(panicked, Ok(true), "plan_each hung or hid the panic");
    }

    /// The queue pops in the heap's order (smallest priority, then first queued) whether
    /// entries sit in its deque or its heap: first-in-first-out and prioritised pushes
    /// mixed, pops, and entries taken and put back as a batch window does, against a plain
    /// heap.
    #[test]
    fn queue_pops_in_heap_order_with_both_stores() {
        let m = HalfEdgeMesh::from_soup(&generate::torus(1.0, 0.4, 12, 8)).unwrap();
        let n = m.vertices().count() as u64;
        let mut next = {
            let mut x = 0x2545_F491_4F6C_DD1D_u64;
            move || {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                x
            }
        };
        let mut q = RemovalQueue::default();
        let mut reference = BinaryHeap::new();
        let mut queued = std::collections::HashSet::new();
        let mut seq = 0;
        let (mut from_deque, mut from_heap, mut put_back) = (0, 0, 0);
        for step in 0..4000 {
            let r = next();
            match r % 4 {
                0 | 1 => {
                    let v = VertexId((next() % n) as u32);
                    // Mostly first-in-first-out runs, with prioritised pushes between them.
                    let order: &dyn QueueOrder = if step % 500 < 400 { &Fifo } else { &FlatFirst };
                    q.push(&m, order, v);
                    if queued.insert(v) {
                        reference.push(Entry {
                            priority: order.priority(&m, v),
                            seq,
                            v,
                        });
                        seq += 1;
                    }
                }
                2 => {
                    let got = q.pop();
                    let want = reference.pop().map(|e| e.v);
                    assert_eq!(got, want, "step {step}");
                    if let Some(v) = want {
                        queued.remove(&v);
                    }
                }
                _ => {
                    // A window: take some, put all back.
                    let k = (next() % 6) as usize;
                    let mut taken = Vec::new();
                    for _ in 0..k {
                        let deque_front = q.fifo.front().map(|e| e.seq);
                        let Some(e) = q.pop_entry() else { break };
                        if deque_front == Some(e.seq) {
                            from_deque += 1;
                        } else {
                            from_heap += 1;
                        }
                        taken.push(e);
                    }
                    put_back += taken.len();
                    q.put_back(taken);
                }
            }
            q.sanity_check(&m).unwrap();
            assert_eq!(q.len(), reference.len());
        }
        assert!(
            from_deque > 100 && from_heap > 100 && put_back > 200,
            "{from_deque} {from_heap} {put_back}"
        );
    }

    /// Collapse positions beyond [`COLLAPSE_REACH`] times the local offset are dropped; the
    /// rest come cheapest first, at most [`COLLAPSE_TRIES`].
    #[test]
    fn collapse_positions_stay_within_reach_of_the_fibers() {
        let m = HalfEdgeMesh::from_soup(&generate::icosphere(1, 1.0)).unwrap();
        let v = m.vertices().next().unwrap();
        let fibers_of = |h: f64| {
            let inner: Vec<DVec3> = m.vertices().map(|u| m.position(u) * (1.0 - h)).collect();
            let outer: Vec<DVec3> = m.vertices().map(|u| m.position(u) * (1.0 + h)).collect();
            (inner, outer)
        };
        let unbounded = collapse_candidates(&m, v, None);
        assert_eq!(unbounded.len(), COLLAPSE_TRIES);
        assert!(unbounded.windows(2).all(|w| w[0].0 <= w[1].0));
        for (h, expect_all) in [(1.0, true), (1e-9, false)] {
            let (inner, outer) = fibers_of(h);
            let fibers = VertexFibers {
                inner: &inner,
                outer: &outer,
            };
            let within = collapse_candidates(&m, v, Some(&fibers));
            let reach = COLLAPSE_REACH * h;
            assert!(within.iter().all(|c| c.0 <= reach * reach), "h = {h}");
            if expect_all {
                assert_eq!(within, unbounded);
            } else {
                // On a sphere no position lies on every plane around an edge.
                assert!(within.is_empty(), "h = {h}: {within:?}");
            }
        }
    }
}
