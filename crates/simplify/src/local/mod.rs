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
//! | when to move vertices | [`Placement::Auto`] (the command line's default): the subset run, then the moving phase of [`Placement::Collapse`] when the subset run left at most one vertex in [`AUTO_MOVING_DIVISOR`] of those it started with; otherwise a light moving phase (no slide, only each vertex's cheapest collapse position; it gives up when its removals are rare, [`LIGHT_GIVE_UP_BELOW`]): the full phase tries every vertex that is left, each at several positions, so it is cheap next to the subset run only when few are left, and costs a multiple of it where many are left (small epsilons); the light one keeps most of its removals there (measured in the changelog) |
//! | moving phase | planned read-only with the planned positions (the faces around a moved vertex tested where they would be), batched like the subset run with two-ring-and-fiber boxes |
//!
//! The output is deterministic and the same for any number of threads. With the
//! first-in-first-out order the queue is taken in batches (`independent_batch`: the front
//! vertex and the next ones whose one-ring boxes are apart from those taken before them);
//! the removals of a batch are *planned* in parallel (checks, hole, filling: read-only) and
//! *carried out* one by one in queue order. A plan only reads the mesh inside its box, so
//! this is the paper's FIFO except that where the queue is a chain of neighbours (a grid
//! numbered row after row) a vertex next to one taken waits at the front of the queue for
//! the next batch while those after it in the window go on, that re-queued
//! neighbours of a batch are appended after the whole batch, and that vertices whose fiber
//! verdict is known ([`Doomed`]) are attempted as they come, also beside a removal in the
//! same batch that changes their fan (they are then queued again). Other orders take one
//! vertex at a time.

mod collapse;
mod moving;
mod plan;
mod queue;
mod run;
mod scheduler;
mod slide;
#[cfg(test)]
mod tests;
mod verdicts;

use crate::barriers::Barriers;
use crate::fiber::{FiberTest, VertexFibers};
use crate::fill::HoleFiller;
use crate::fill::{Exhaustive, Greedy};
use crate::filter::{EnvelopeFilter, Filter};
use crate::rules::{
    Exhaust, Fifo, FlatFirst, QueueOrder, Rejection, StopRule, TargetFaces, Visitor,
};
use envelope_mesh::{HalfEdgeMesh, VertexId};
pub use plan::{LocalSimplifier, Removal};
use run::run;
pub(crate) use run::tolerance_phase;
use thiserror::Error;

/// Vertices of larger valence are not tried (their candidate lists grow cubically).
pub(crate) const MAX_HOLE: usize = 40;

/// [`Placement::Auto`] runs the moving phase in full when the subset run left at most one
/// vertex in this many of those it started with, light otherwise.
pub const AUTO_MOVING_DIVISOR: usize = 10;

/// Attempts of the light moving phase before it may give up (see [`LIGHT_GIVE_UP_BELOW`]).
pub const LIGHT_PROBE: usize = 2048;

/// The light moving phase gives up, once it made [`LIGHT_PROBE`] attempts, when fewer than
/// one attempt in this many removed a vertex (checked between batches, so the output does
/// not depend on the thread count). Each removal there costs the attempts of this many
/// vertices plus the certificate's proofs of the moved faces: where the subset run left a
/// surface that is coarse against epsilon, the phase doubled the run's time for a few
/// percent of its faces (measured in the changelog).
pub const LIGHT_GIVE_UP_BELOW: usize = 25;

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
    /// The visitor asked the run to stop ([`Visitor::cancelled`]).
    #[error("cancelled")]
    Cancelled,
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
    /// Whether the moving phase ran (with [`Placement::Slide`], [`Placement::Collapse`] and
    /// [`Placement::Auto`]).
    pub moving_phase: bool,
    /// Whether it ran light ([`Placement::Auto`] when many vertices were left).
    pub moving_phase_light: bool,
    /// Whether the light phase gave up early, its removals too rare (`LIGHT_GIVE_UP_BELOW`).
    pub light_gave_up: bool,
    /// Vertices removed by the tolerance phase after the step (crate module `tolerance`;
    /// counted in `removed` and `collapsed` too).
    pub tolerance_removed: usize,
}

impl Stats {
    /// Adds the counts of a `later` run on this one's output (a local stage of the hybrid,
    /// the tolerance phase): its counters added, its output counts taken.
    pub fn add_later(&mut self, later: &Stats) {
        self.vertices_after = later.vertices_after;
        self.faces_after = later.faces_after;
        self.attempts += later.attempts;
        self.removed += later.removed;
        self.no_valid_fill += later.no_valid_fill;
        self.no_fill_across_fiber += later.no_fill_across_fiber;
        self.answered_ahead += later.answered_ahead;
        self.refused += later.refused;
        self.candidate_tests += later.candidate_tests;
        self.slid += later.slid;
        self.collapsed += later.collapsed;
        self.moving_phase |= later.moving_phase;
        self.moving_phase_light |= later.moving_phase_light;
        self.light_gave_up |= later.light_gave_up;
        self.tolerance_removed += later.tolerance_removed;
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
    /// The subset run, then the moving phase of [`Placement::Collapse`] when the subset run
    /// left at most one vertex in [`AUTO_MOVING_DIVISOR`] of those it started with, and
    /// otherwise a light one: no slide, each vertex's cheapest collapse position only (see
    /// the module docs for why).
    Auto,
}

impl Placement {
    /// Every placement, in the order of [`Placement::as_str`]'s names.
    pub const ALL: [Placement; 4] = [
        Placement::Subset,
        Placement::Slide,
        Placement::Collapse,
        Placement::Auto,
    ];

    /// `"subset"`, `"slide"`, `"collapse"` or `"auto"` (the command line's names).
    #[must_use]
    pub const fn as_str(self) -> &'static str {
        match self {
            Placement::Subset => "subset",
            Placement::Slide => "slide",
            Placement::Collapse => "collapse",
            Placement::Auto => "auto",
        }
    }

    /// Parses [`Placement::as_str`].
    ///
    /// ```
    /// use envelope_simplify::Placement;
    /// assert_eq!(Placement::parse("collapse"), Some(Placement::Collapse));
    /// assert_eq!(Placement::parse("move"), None);
    /// ```
    #[must_use]
    pub fn parse(s: &str) -> Option<Placement> {
        Placement::ALL.into_iter().find(|p| p.as_str() == s)
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
    /// Keep every border vertex (the envelope filter's when there is no border tube, whose
    /// test an open hole's new border edge needs; the tolerance filter proves it instead).
    pub keep_border: bool,
    /// Vertices never removed nor moved, by id ([`Barriers::with_kept`]; empty: none).
    pub keep: &'p [bool],
    /// Run sanity checks after every attempt.
    pub check_each_step: bool,
    /// With fibers, the slide phase ([`Placement::Slide`]) runs after the subset run.
    pub fibers: Option<VertexFibers<'p>>,
    /// Edge collapses after the subset run ([`Placement::Collapse`]; with `fibers`, after
    /// sliding).
    pub collapse: bool,
    /// The moving phase's extent follows the subset run ([`Placement::Auto`]): in full when
    /// it left at most one vertex in [`AUTO_MOVING_DIVISOR`] of those it started with,
    /// otherwise light (no slide, each vertex's cheapest collapse position only).
    pub auto_moving: bool,
    /// The fiber test ([`FiberTest`]) before each plain removal's filling: its envelopes
    /// must be barriers of `filter` and apart from every face of the mesh (see its module).
    pub fiber_test: Option<&'p FiberTest<'p>>,
}

/// Simplifies `mesh` in place by the local algorithm of section 5.2, with the validity test
/// of section 5.1 against `barriers` ([`EnvelopeFilter`]). See the module docs.
///
/// ```
/// use envelope_mesh::{generate, HalfEdgeMesh};
/// use envelope_simplify::policy::{simplify_local, Barriers, Options};
/// let mut m = HalfEdgeMesh::from_soup(&generate::tetrahedron()).unwrap();
/// let stats = simplify_local(&mut m, &Barriers::none(), &Options::default()).unwrap();
/// assert_eq!((stats.removed, m.num_faces()), (0, 4)); // nothing can go
/// ```
pub fn simplify_local(
    mesh: &mut HalfEdgeMesh,
    barriers: &Barriers,
    options: &Options,
) -> Result<Stats, SimplifyError> {
    simplify_local_from(mesh, barriers, options, None, None, None, &mut ())
}

/// [`simplify_local`] with the queue started from `seeds` (in their order; `None`: every
/// vertex, in id order), the vertices' fibers, the fiber test, and a visitor told of every
/// attempt (progress bars, tracing).
///
/// * `seeds`: after another step changed the mesh in a few places, the vertices around the
///   changes, as the local algorithm re-queues the hole's vertices after a removal. Seeds
///   that are no longer in the mesh are skipped.
/// * `fibers`: what [`Placement::Slide`] needs (without them, or with [`Placement::Subset`],
///   no vertex moves).
/// * `fiber_test`: see [`Policies::fiber_test`]; its envelopes must be among `barriers`.
pub fn simplify_local_from(
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
        keep: barriers.kept(),
        check_each_step: options.check_each_step,
        fibers: fibers.filter(|_| options.placement != Placement::Subset),
        collapse: matches!(options.placement, Placement::Collapse | Placement::Auto),
        auto_moving: options.placement == Placement::Auto,
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
