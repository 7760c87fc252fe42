//! The whole job of the paper on one mesh: accept the input (7.1), build the envelopes and
//! border tubes (3, 4, 6.2) from a possibly varying epsilon (6.3), run the local algorithm
//! (5.1, 5.2) between them, and report, optionally with an independent certificate of the
//! output (`envelope-verify`).
//!
//! ```text
//! simplify
//!   accept_input        envelope-check: no error-class degeneracy (else DriverError::Unacceptable)
//!   build_envelopes     envelope-offset: outer, inner, tubes, exact non-intersection proof
//!                       (run beside accept_input, whose verdict is taken first)
//!   border_walls        walls joining outer and inner envelope along each input border loop
//!   Barriers            outer + inner as envelopes, tubes as tubes, walls as full barriers
//!   simplify_local      section 5.2 with the 5.1 validity test
//!   certify             (optional) two-sided Hausdorff <= max epsilon, no self-intersection,
//!                       same genus / components / border loops
//!
//! a self-intersecting input (only CROSSINGS classes), or envelopes not proved: the same
//! steps on the rest, around
//!   KeptRegion          module kept: the faces of intersecting pairs (or none), kept as
//!                       they are
//!   build_envelopes     for the rest; named contact faces kept too until proved (<= 8 rounds)
//!   Barriers            + the kept faces as walls (touched only at shared vertices), the
//!                       shared vertices kept
//!   join, certify       rest + kept faces; only the input's own intersections allowed
//! ```
//!
//! Sharp features need no special case (6.1): where the envelopes leave no room across a
//! crease, no candidate triangle spanning it is valid.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use envelope_check::{
    CheckOptions, CheckReport, DegeneracyClass, check_with_shared, check_with_topology,
};
use envelope_mesh::{BuildError, FaceId, HalfEdgeMesh, Topology, TriangleSoup, VertexId, analyze};
use envelope_offset::{
    AnalyticalMemo, EnvelopeError, EnvelopeMethod, EnvelopeOptions, Envelopes, EpsilonField,
    Surface, build_envelopes, build_envelopes_with, face_tree,
};
use envelope_predicates::bvh::Bvh;
use envelope_verify::{Certificate, Verdict};
use glam::DVec3;
use serde_json::{Value, json};
use thiserror::Error;

use crate::barriers::{BarrierError, Barriers};
use crate::border_cover::BorderCover;
use crate::fiber::{FiberTest, VertexFibers};
use crate::kept::{KeptRegion, MAX_ROUNDS};
use crate::local::{
    HoleFilling, Options as LocalOptions, Order, Placement, SimplifyError, Stats,
    simplify_local_from,
};
use crate::rules::{Rejection, StopRule, TargetFaces, Visitor};
use crate::tolerance::simplify_past_envelopes;
use crate::walls::border_walls;

/// What [`simplify`] does.
#[derive(Debug)]
pub struct SimplifyOptions {
    /// The requested epsilon (absolute lengths; resolve percentages with the input's diagonal
    /// first, `envelope_offset::EpsilonSpec::resolve`).
    pub epsilon: EpsilonField,
    /// How the envelopes find their per-vertex offsets. Default [`EnvelopeMethod::Auto`]: the
    /// analytical method (fast), and the numerical one too where the analytical one falls
    /// short of epsilon (large epsilons; see the crate README).
    pub method: EnvelopeMethod,
    /// Hole filling (default: greedy with look-ahead).
    pub hole_filling: HoleFilling,
    /// Queue order (default: the paper's first in, first out).
    pub order: Order,
    /// Where output vertices may lie (default: the input vertices, as in the paper's 5.2;
    /// [`Placement::Slide`]: the local step then slides stuck neighbourhoods along the
    /// fibers, section 8; [`Placement::Collapse`]: and then collapses edges of what is still
    /// stuck; [`Placement::Auto`], the command line's default: collapse only when the subset
    /// run left few vertices). Only steps that run the local algorithm's phase use it (the
    /// local and hybrid methods, not the global one: the CLI refuses slide and collapse with
    /// it, and auto there reports `"auto: subset"`, as nothing moves).
    pub placement: Placement,
    /// Vertices per border-tube ring (`None`: no tubes, border vertices are then kept).
    pub tube_segments: Option<u32>,
    /// Stop once at most this many faces remain.
    pub target_faces: Option<usize>,
    /// Certify the output against the input with `envelope-verify` (two-sided Hausdorff at
    /// the largest requested epsilon, self-intersections, topology).
    pub verify: bool,
    /// Input vertices no step may remove or move, by vertex id (empty: none; ids beyond the
    /// end are free): attribute seams, say. Kept vertices stay in the output at their input
    /// positions, so an edge between two kept vertices is never removed.
    pub keep: Vec<bool>,
    /// After the step, the tolerance phase (module `tolerance`): operations proved against
    /// the contract itself where the envelopes stopped the step (thin parts at large
    /// epsilons). Only for a constant epsilon on an input that does not meet itself.
    pub tolerance_phase: bool,
}

impl SimplifyOptions {
    /// The engine's defaults for a field: auto envelopes, greedy filling, FIFO, input
    /// vertices only, 8-gon tubes, no certificate. The front door (`envelope::Simplifier`)
    /// has the command line's defaults instead (moving placement when it pays, certified).
    #[must_use]
    pub fn new(epsilon: EpsilonField) -> Self {
        SimplifyOptions {
            epsilon,
            method: EnvelopeMethod::Auto,
            hole_filling: HoleFilling::default(),
            order: Order::default(),
            placement: Placement::default(),
            tube_segments: Some(8),
            target_faces: None,
            verify: false,
            keep: Vec::new(),
            tolerance_phase: false,
        }
    }
}

/// Why [`simplify`] produced no output.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum DriverError {
    /// The input has degeneracies of an error class (`envelope check` lists them).
    #[error("the input is not acceptable: {}", describe_classes(.0))]
    Unacceptable(Vec<(DegeneracyClass, usize)>),
    /// The envelopes could not be built.
    #[error("envelopes: {0}")]
    Envelope(#[from] EnvelopeError),
    /// The envelope triangles are out of the exact predicates' range.
    #[error("barriers: {0}")]
    Barrier(#[from] BarrierError),
    /// The half-edge structure refused the input.
    #[error("mesh: {0}")]
    Build(#[from] BuildError),
    /// The simplifier stopped (for a cancellation: [`DriverError::Cancelled`]).
    #[error("simplify: {0}")]
    Simplify(SimplifyError),
    /// The envelopes (or tubes) could not be proved free of intersections, even after the
    /// repair rounds: simplifying between them could give a wrong answer, so nothing is.
    #[error(
        "the envelopes could not be proved free of intersections ({contacts} contacts \
         remain after repair; parts of the input, or stretches of one border, may be closer \
         together than offsets can resolve): no output is made from unproved envelopes"
    )]
    UnprovedEnvelopes {
        /// Contacts (envelope and tube) the last proof found.
        contacts: usize,
        /// Repair rounds run.
        repair_rounds: u32,
    },
    /// A list of epsilons that makes no chain (`lod_chain`).
    #[error("epsilons: {0}")]
    Epsilons(&'static str),
    /// [`Progress::cancelled`] said so.
    #[error("cancelled")]
    Cancelled,
}

impl From<SimplifyError> for DriverError {
    fn from(e: SimplifyError) -> Self {
        match e {
            SimplifyError::Cancelled => Self::Cancelled,
            e => Self::Simplify(e),
        }
    }
}

/// `Err(DriverError::Cancelled)` when `progress` asks for it (between stages).
fn go_on(progress: &mut dyn Progress) -> Result<(), DriverError> {
    if progress.cancelled() {
        Err(DriverError::Cancelled)
    } else {
        Ok(())
    }
}

fn describe_classes(c: &[(DegeneracyClass, usize)]) -> String {
    c.iter()
        // A count of zero is an undecided class (`envelope_check::Finding::undecided`).
        .map(|(k, n)| match n {
            0 => format!("{k} undecided (faces stacked too densely to test every pair)"),
            n => format!("{n} {k}"),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A stage of [`simplify`], for progress display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Checking the input.
    Check,
    /// Building envelopes and tubes.
    Envelopes,
    /// Removing vertices (`vertices` live vertices at the start).
    Simplify {
        /// Live vertices at the start.
        vertices: usize,
    },
    /// Certifying the output.
    Verify,
}

/// Told what [`simplify`] is doing; everything defaults to nothing. `()` is silent.
pub trait Progress {
    /// A stage begins.
    fn stage(&mut self, _stage: Stage) {}
    /// During [`Stage::Simplify`]: removal attempts so far and vertices removed so far.
    fn step(&mut self, _attempts: usize, _removed: usize) {}
    /// Whether to stop with [`DriverError::Cancelled`]; asked between stages and once per
    /// round of the local algorithm.
    fn cancelled(&mut self) -> bool {
        false
    }
}

impl Progress for () {}

/// Envelope statistics of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvelopeReport {
    /// `"analytical"` or `"numerical"`.
    pub method: &'static str,
    /// Median of the achieved offsets as fractions of the requested (outer and inner).
    pub achieved_median: f64,
    /// 5th percentile of the same.
    pub achieved_p5: f64,
    /// Smallest of the same.
    pub achieved_min: f64,
    /// The exact non-intersection proof of envelopes and tubes held.
    pub proved: bool,
    /// Repair rounds the proof took.
    pub repair_rounds: u32,
    /// Border tubes.
    pub tubes: usize,
    /// Vertices pinned for want of a valid normal (`envelope-offset`'s `Envelopes::pinned`:
    /// zero offsets there, and the simplifier keeps them).
    pub pinned: usize,
    /// Seconds to build and prove.
    pub seconds: f64,
}

/// The certificate of the output, in short.
#[derive(Clone, Debug, PartialEq)]
pub struct VerifyReport {
    /// Overall verdict (`Violated` if any property is violated).
    pub verdict: Verdict,
    /// The tolerance certified (the largest requested epsilon).
    pub epsilon: f64,
    /// Certified upper bound of the distance from the output to the input.
    pub approx_to_orig_upper: f64,
    /// Certified upper bound of the distance from the input to the output.
    pub orig_to_approx_upper: f64,
    /// Verdicts of the two directions.
    pub directions: [Verdict; 2],
    /// Intersecting face pairs of the output.
    pub self_intersections: usize,
    /// Genus, components and border loops unchanged.
    pub topology_matches: bool,
    /// Names of the violated properties.
    pub violations: Vec<&'static str>,
    /// Seconds to certify.
    pub seconds: f64,
    /// The whole certificate (witnesses, every self-intersecting pair, topology).
    pub certificate: Certificate,
}

impl VerifyReport {
    /// The short form of a certificate, which keeps the certificate.
    #[must_use]
    pub fn from_certificate(c: Certificate, seconds: f64) -> Self {
        VerifyReport {
            verdict: c.verdict,
            epsilon: c.epsilon,
            approx_to_orig_upper: c.approx_to_orig.upper,
            orig_to_approx_upper: c.orig_to_approx.upper,
            directions: [c.approx_to_orig.verdict, c.orig_to_approx.verdict],
            self_intersections: c.self_intersections.as_ref().map_or(0, Vec::len),
            topology_matches: c.topology.is_none_or(|t| t.matches()),
            violations: c.violations(),
            seconds,
            certificate: c,
        }
    }

    /// Stable JSON keys.
    #[must_use]
    pub fn to_json(&self) -> Value {
        json!({
            "verdict": self.verdict.as_str(),
            "epsilon": self.epsilon,
            "approx_to_orig": { "verdict": self.directions[0].as_str(), "upper": finite(self.approx_to_orig_upper) },
            "orig_to_approx": { "verdict": self.directions[1].as_str(), "upper": finite(self.orig_to_approx_upper) },
            "self_intersections": self.self_intersections,
            "topology_matches": self.topology_matches,
            "violations": self.violations,
            "seconds": self.seconds,
        })
    }
}

fn finite(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// What [`simplify`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct SimplifyReport {
    /// Input faces.
    pub input_faces: usize,
    /// Output faces.
    pub output_faces: usize,
    /// Input (referenced) vertices.
    pub input_vertices: usize,
    /// Output vertices.
    pub output_vertices: usize,
    /// The largest requested epsilon (absolute): the bound the output is held to.
    pub epsilon_abs: f64,
    /// The smallest requested epsilon (equal to `epsilon_abs` for a constant field).
    pub epsilon_min_abs: f64,
    /// `epsilon_abs` over the input's bounding-box diagonal.
    pub epsilon_fraction: f64,
    /// Bounding-box diagonal of the input.
    pub diagonal: f64,
    /// Wall-clock seconds of the whole run (verification included).
    pub seconds: f64,
    /// Seconds in the local algorithm alone.
    pub simplify_seconds: f64,
    /// The process's peak resident memory (`VmHWM`), where the platform tells it.
    pub peak_memory_bytes: Option<u64>,
    /// Vertices removed.
    pub removed_vertices: usize,
    /// `"subset"`, `"slide"`, `"collapse"`, or with [`Placement::Auto`] what it ran:
    /// `"auto: subset"` (the global method: nothing moves), `"auto: collapse"`,
    /// `"auto: light collapse"` or `"auto: light collapse, given up"` (its removals too
    /// rare, it stopped early) ([`SimplifyOptions::placement`]).
    pub placement: &'static str,
    /// Removals that slid neighbours along their fibers (0 with `"subset"`).
    pub slid_removals: usize,
    /// Removals by an edge collapse (with `"collapse"` and the `auto` collapses, and the
    /// tolerance phase's).
    pub collapsed_removals: usize,
    /// Removal attempts.
    pub attempts: usize,
    /// Attempts the fiber test turned away ([`FiberTest`]; part of the failed ones).
    pub no_fill_across_fiber: usize,
    /// Genus of the input (`None`: undefined).
    pub genus_in: Option<u32>,
    /// Genus of the output.
    pub genus_out: Option<u32>,
    /// Border loops of the input.
    pub border_loops_in: usize,
    /// Border loops of the output.
    pub border_loops_out: usize,
    /// Envelope statistics.
    pub envelope: EnvelopeReport,
    /// The certificate of the output, when asked for.
    pub verify: Option<VerifyReport>,
    /// What was kept as it was, around a self-intersecting input's intersecting pairs and
    /// where its envelopes could not be proved (`None`: nothing).
    pub kept: Option<KeptReport>,
    /// The simplification method that ran ([`SimplifyStep`]): `"local"` by default.
    pub method: &'static str,
    /// What the method adds to the report (candidate counts for the global one).
    pub method_details: Value,
    /// The tolerance phase after the step (`SimplifyOptions::tolerance_phase`), when it ran.
    pub tolerance_phase: Option<TolerancePhaseReport>,
}

/// What the tolerance phase did ([`SimplifyReport::tolerance_phase`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TolerancePhaseReport {
    /// Vertices it removed (also counted in [`SimplifyReport::removed_vertices`]).
    pub removed_vertices: usize,
    /// Seconds it took (part of [`SimplifyReport::simplify_seconds`]).
    pub seconds: f64,
    /// The epsilon the envelopes were built at: [`SimplifyReport::epsilon_abs`], or less
    /// when it exceeded [`TOLERANCE_ENVELOPE_CAP`] of the diagonal.
    pub envelope_epsilon_abs: f64,
}

impl TolerancePhaseReport {
    /// Stable JSON keys (the field names).
    #[must_use]
    pub fn to_json(&self) -> Value {
        json!({
            "removed_vertices": self.removed_vertices,
            "seconds": self.seconds,
            "envelope_epsilon_abs": self.envelope_epsilon_abs,
        })
    }
}

impl SimplifyReport {
    /// Stable JSON keys (the field names).
    #[must_use]
    pub fn to_json(&self) -> Value {
        let e = &self.envelope;
        json!({
            "input_faces": self.input_faces,
            "output_faces": self.output_faces,
            "input_vertices": self.input_vertices,
            "output_vertices": self.output_vertices,
            "epsilon_abs": self.epsilon_abs,
            "epsilon_min_abs": self.epsilon_min_abs,
            "epsilon_fraction": self.epsilon_fraction,
            "diagonal": self.diagonal,
            "seconds": self.seconds,
            "simplify_seconds": self.simplify_seconds,
            "peak_memory_bytes": self.peak_memory_bytes,
            "removed_vertices": self.removed_vertices,
            "placement": self.placement,
            "slid_removals": self.slid_removals,
            "collapsed_removals": self.collapsed_removals,
            "attempts": self.attempts,
            "no_fill_across_fiber": self.no_fill_across_fiber,
            "genus_in": self.genus_in,
            "genus_out": self.genus_out,
            "border_loops_in": self.border_loops_in,
            "border_loops_out": self.border_loops_out,
            "envelope": {
                "method": e.method,
                "achieved_median": e.achieved_median,
                "achieved_p5": e.achieved_p5,
                "achieved_min": e.achieved_min,
                "proved": e.proved,
                "repair_rounds": e.repair_rounds,
                "tubes": e.tubes,
                "pinned": e.pinned,
                "seconds": e.seconds,
            },
            "verify": self.verify.as_ref().map(VerifyReport::to_json),
            "tolerance_phase": self.tolerance_phase.as_ref().map(TolerancePhaseReport::to_json),
            "kept": self.kept.as_ref().map(|k| json!({
                "intersecting_pairs": k.intersecting_pairs,
                "kept_faces": k.kept_faces,
                "rounds": k.rounds,
                "shared_vertices": k.shared_vertices,
            })),
            "method": self.method,
            "method_details": self.method_details,
        })
    }
}

/// The process's peak resident set size (`VmHWM` in `/proc/self/status`), in bytes.
#[must_use]
pub fn peak_memory_bytes() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The error-class degeneracies of a soup (empty: acceptable input, section 7.1).
#[must_use]
pub fn input_problems(soup: &TriangleSoup) -> Vec<(DegeneracyClass, usize)> {
    input_problems_and_topology(soup).0
}

/// [`input_problems`] and the soup's topology, which the check computes anyway.
fn input_problems_and_topology(soup: &TriangleSoup) -> (Vec<(DegeneracyClass, usize)>, Topology) {
    let (report, topology) = check_with_topology(soup, &problems_only());
    (problems_of(&report), topology)
}

/// [`input_problems`] with the soup's topology and face tree given (see
/// [`check_with_shared`]).
fn input_problems_with(
    soup: &TriangleSoup,
    topology: &Topology,
    face_tree: Option<&Bvh>,
) -> Vec<(DegeneracyClass, usize)> {
    problems_of(&check_with_shared(
        soup,
        &problems_only(),
        topology,
        face_tree,
    ))
}

/// The check of [`input_problems`]: counts, no examples.
fn problems_only() -> CheckOptions {
    CheckOptions {
        max_examples: 0,
        ..CheckOptions::default()
    }
}

/// The error classes a check found, with their counts.
fn problems_of(report: &CheckReport) -> Vec<(DegeneracyClass, usize)> {
    report
        .errors()
        .map(|c| (c, report.finding(c).count))
        .collect()
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// Forwards attempts to a [`Progress`] every 256 attempts.
struct ProgressVisitor<'a> {
    progress: &'a mut dyn Progress,
    attempts: usize,
    removed: usize,
}

impl Visitor for ProgressVisitor<'_> {
    fn on_attempt(&mut self, _: envelope_mesh::VertexId) {
        self.attempts += 1;
        if self.attempts % 256 == 0 {
            self.progress.step(self.attempts, self.removed);
        }
    }
    fn on_removed(&mut self, _: envelope_mesh::VertexId, _: &[envelope_mesh::FaceId]) {
        self.removed += 1;
    }
    fn on_rejected(&mut self, _: envelope_mesh::VertexId, _: Rejection) {}
    fn cancelled(&mut self) -> bool {
        self.progress.cancelled()
    }
}

/// Simplifies `soup` within the requested epsilon (see the module docs). The output has
/// compacted vertex ids; its vertices are a subset of the input's, in input order.
///
/// ```
/// use envelope_mesh::generate;
/// use envelope_offset::EpsilonField;
/// use envelope_simplify::{simplify, SimplifyOptions};
/// let sphere = generate::icosphere(3, 1.0);
/// let mut options = SimplifyOptions::new(EpsilonField::Constant(0.05));
/// options.verify = true;
/// let (out, report) = simplify(&sphere, &options, &mut ()).unwrap();
/// assert!(out.num_faces() < sphere.num_faces() / 4);
/// assert_eq!(report.genus_out, Some(0));
/// assert!(report.verify.unwrap().violations.is_empty());
/// ```
pub fn simplify(
    soup: &TriangleSoup,
    options: &SimplifyOptions,
    progress: &mut dyn Progress,
) -> Result<(TriangleSoup, SimplifyReport), DriverError> {
    simplify_with(soup, options, &LocalStep, progress)
}

/// What a [`SimplifyStep`] is given besides the mesh.
#[derive(Clone, Copy, Debug)]
pub struct StepInput<'a> {
    /// Envelopes, tubes and walls as barriers.
    pub barriers: &'a Barriers,
    /// Outer envelope point of every input vertex (`v + eps_plus n_v`, f64 construction).
    pub outer: &'a [DVec3],
    /// Inner envelope point of every input vertex (`v - eps_minus n_v`, f64 construction).
    pub inner: &'a [DVec3],
    /// The job's options.
    pub options: &'a SimplifyOptions,
    /// The fiber test over `inner` and `outer` ([`FiberTest`]), when its conditions hold:
    /// proved envelopes, no pins.
    pub fiber_test: Option<&'a FiberTest<'a>>,
}

/// What a [`SimplifyStep`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct StepOutcome {
    /// Counts (attempts, removals, candidate tests).
    pub stats: Stats,
    /// The method's name for the report.
    pub method: &'static str,
    /// Extra report fields (`Value::Null` when none).
    pub details: Value,
}

/// The simplification step of [`simplify_with`]: the local algorithm ([`LocalStep`]) or
/// another one (the global simplifier of `envelope-global`), run on the input mesh between
/// the barriers.
pub trait SimplifyStep {
    /// Simplifies `mesh` in place.
    fn run(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
        progress: &mut dyn Progress,
    ) -> Result<StepOutcome, SimplifyError>;
}

/// The local algorithm of section 5.2 as a [`SimplifyStep`] (what [`simplify`] runs).
#[derive(Clone, Copy, Debug, Default)]
pub struct LocalStep;

impl SimplifyStep for LocalStep {
    fn run(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
        progress: &mut dyn Progress,
    ) -> Result<StepOutcome, SimplifyError> {
        self.run_from(mesh, input, None, progress)
    }
}

impl LocalStep {
    /// [`SimplifyStep::run`] with the queue started from `seeds` (`None`: every vertex), see
    /// [`simplify_local_from`](crate::policy::simplify_local_from): for a local pass after
    /// another step changed the mesh in a few places.
    pub fn run_from(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
        seeds: Option<&[VertexId]>,
        progress: &mut dyn Progress,
    ) -> Result<StepOutcome, SimplifyError> {
        let stats = run_local(mesh, input, seeds, progress)?;
        Ok(StepOutcome {
            stats,
            method: "local",
            details: Value::Null,
        })
    }
}

/// [`simplify`] with another simplification step in place of the local algorithm.
///
/// An input whose only error classes are [`CROSSINGS`] (it meets itself) is simplified
/// around its crossings: the faces of its intersecting pairs are kept as they are (module
/// `kept`), the rest is simplified between its own proved envelopes with the kept faces as
/// walls, and the certificate allows exactly the input's own intersections; the report's
/// [`SimplifyReport::kept`] says how much was kept.
pub fn simplify_with(
    soup: &TriangleSoup,
    options: &SimplifyOptions,
    step: &dyn SimplifyStep,
    progress: &mut dyn Progress,
) -> Result<(TriangleSoup, SimplifyReport), DriverError> {
    let start = Instant::now();
    progress.stage(Stage::Check);
    go_on(progress)?;
    progress.stage(Stage::Envelopes);
    go_on(progress)?;
    // The input's topology and face tree, which the check and the envelopes both need:
    // computed once, side by side (the analysis is sequential, the tree parallel). Not for
    // a face naming a missing vertex: the check alone reports that.
    let t_env = Instant::now();
    let shared = soup
        .indices_in_range()
        .then(|| rayon::join(|| analyze(soup), || face_tree(soup)));
    let mut capped = tolerance_cap(soup, options);
    // The input check and the envelopes run side by side (much of the check is sequential);
    // the check's verdict comes first, whatever the envelopes made of a refused input. An
    // input with problems never uses these envelopes (refused, or simplified around its
    // crossings with envelopes of its own), so the check abandons them when it finds any.
    let abandon = Arc::new(AtomicBool::new(false));
    let ((problems, own_topology), (env, env_seconds)) = rayon::join(
        // The check gives the topology the driver needs too (border walls, the report).
        || {
            let checked = match &shared {
                Some((topology, tree)) => (input_problems_with(soup, topology, Some(tree)), None),
                None => {
                    let (problems, topology) = input_problems_and_topology(soup);
                    (problems, Some(topology))
                }
            };
            if !checked.0.is_empty() {
                abandon.store(true, Ordering::Relaxed);
            }
            checked
        },
        || {
            let env = envelopes_up_to(
                soup,
                options,
                shared.as_ref().map(|(t, b)| (t, b)),
                capped.map(|(_, cap)| cap),
                Some(Arc::clone(&abandon)),
                None,
            );
            (env, t_env.elapsed().as_secs_f64())
        },
    );
    let crossing = !problems.is_empty() && problems.iter().all(|(c, _)| CROSSINGS.contains(c));
    if !problems.is_empty() && !crossing {
        return Err(DriverError::Unacceptable(problems));
    }
    let (topo_in, tree) = match (shared, own_topology) {
        (Some((topology, tree)), _) => (topology, Some(tree)),
        (None, Some(topology)) => (topology, None),
        (None, None) => (analyze(soup), None),
    };
    let used = referenced(soup);
    if crossing {
        drop(env);
        // Undecided (too many overlapping boxes) stays refused.
        let Some(pairs) = envelope_check::intersecting_pairs(soup, tree.as_ref()) else {
            return Err(DriverError::Unacceptable(problems));
        };
        let start_with = Start::Pairs(pairs, problems);
        return simplify_keeping(
            soup, &topo_in, &used, start_with, options, step, progress, start,
        );
    }
    let mut env = env?;
    if capped.is_some() && !env.proof.holds() {
        // The tolerance phase follows proved envelopes only: the full ones, as without it.
        capped = None;
        env = envelopes_for(soup, options, tree.as_ref().map(|b| (&topo_in, b)))?;
    }
    // An invariant of every command: no output from envelopes whose proof failed. Where
    // it fails, the faces it names are kept as they are and the rest tried again.
    if !env.proof.holds() {
        let start_with = Start::Unproved(Box::new(env));
        return simplify_keeping(
            soup, &topo_in, &used, start_with, options, step, progress, start,
        );
    }
    let between = simplify_between(
        soup,
        &topo_in,
        (env, env_seconds),
        &used,
        None,
        capped.map(|(e, _)| e),
        options,
        step,
        progress,
    )?;
    // The half-edge count: the same numbers as `analyze(&out)`, without its edge table.
    let (out, (genus_out, border_loops_out)) = rayon::join(
        || between.mesh.to_soup(),
        || between.mesh.genus_and_border_loops(),
    );
    let verify = certify(soup, &out, between.epsilon_abs, false, options, progress)?;
    let report = between.report(
        soup,
        &out,
        &topo_in,
        (genus_out, border_loops_out),
        verify,
        None,
        options,
        start,
    );
    Ok((out, report))
}

/// The error classes an input meeting itself has: the faces around them are kept (the
/// driver's crossing path, see [`simplify_with`]); an input whose only error classes are
/// these is simplified, not refused. Each makes intersecting pairs that cover it: a T-junction
/// (the faces at the vertex meet the edge's face away from what they share), two vertices at
/// one position (the faces of one meet those of the other there; what repair leaves where it
/// splits a pinch into sheets), coincident faces.
pub const CROSSINGS: [DegeneracyClass; 4] = [
    DegeneracyClass::IntersectingTriangles,
    DegeneracyClass::CoincidentTriangles,
    DegeneracyClass::TJunctions,
    DegeneracyClass::DuplicateVertices,
];

/// With the tolerance phase on and a constant epsilon above this part of the input's
/// diagonal, the envelopes are built at this part instead, and the
/// tolerance phase always runs, at the full epsilon, on what the step leaves. A choice,
/// measured (CHANGELOG.md, benches/runs): the envelopes' growth costs most of a run at
/// large epsilons, while there the envelopes, cut back where the surface is thin, stop the
/// step anyway; from a step at the cap the phase ends within a few faces of where it ends
/// from one at the full epsilon, in less time.
pub const TOLERANCE_ENVELOPE_CAP: f64 = 0.01;

/// Without the cap, the tolerance phase runs when the envelopes were cut back: at least
/// one requested vertex in 20 has an offset below this part of its epsilon (the
/// envelopes' `achieved_p5`). Elsewhere the step is rarely stuck by the envelopes and the
/// phase would cost time for a few faces.
pub const TOLERANCE_WHEN_CUT_BELOW: f64 = 0.9;

/// The constant epsilon `options` asks of `soup` when the tolerance phase is on and it
/// exceeds [`TOLERANCE_ENVELOPE_CAP`] of the diagonal: `(epsilon, cap)`.
fn tolerance_cap(soup: &TriangleSoup, options: &SimplifyOptions) -> Option<(f64, f64)> {
    let EpsilonField::Constant(e) = options.epsilon else {
        return None;
    };
    let cap = TOLERANCE_ENVELOPE_CAP * soup.diagonal();
    (options.tolerance_phase && cap > 0.0 && e > cap).then_some((e, cap))
}

/// The envelopes of `soup` for `options` (with its topology and face tree when known).
pub(crate) fn envelopes_for(
    soup: &TriangleSoup,
    options: &SimplifyOptions,
    shared: Option<(&Topology, &Bvh)>,
) -> Result<Envelopes, DriverError> {
    envelopes_up_to(soup, options, shared, None, None, None)
}

/// [`envelopes_for`], every offset requested at most `cap` (see [`tolerance_cap`]).
fn envelopes_up_to(
    soup: &TriangleSoup,
    options: &SimplifyOptions,
    shared: Option<(&Topology, &Bvh)>,
    cap: Option<f64>,
    abandon: Option<Arc<AtomicBool>>,
    analytical_memo: Option<AnalyticalMemo>,
) -> Result<Envelopes, DriverError> {
    let mut field = options.epsilon.evaluate(&soup.positions)?;
    if let Some(cap) = cap {
        for e in &mut field {
            *e = e.min(cap);
        }
    }
    let env_options = EnvelopeOptions {
        method: options.method,
        tube_segments: options.tube_segments,
        // The driver tests every input pair exactly and refuses an intersecting input, or
        // builds these for faces that meet nowhere ([`simplify_around_crossings`]), before
        // they are used.
        input_free_of_intersections: true,
        abandon,
        analytical_memo,
        ..EnvelopeOptions::new(EpsilonField::PerVertex(field))
    };
    Ok(match shared {
        Some((topology, tree)) => build_envelopes_with(soup, &env_options, topology, tree)?,
        None => build_envelopes(soup, &env_options)?,
    })
}

/// The certificate of `out` against `soup` at `epsilon`, when asked for.
fn certify(
    soup: &TriangleSoup,
    out: &TriangleSoup,
    epsilon: f64,
    allow_input_intersections: bool,
    options: &SimplifyOptions,
    progress: &mut dyn Progress,
) -> Result<Option<VerifyReport>, DriverError> {
    if !options.verify {
        return Ok(None);
    }
    progress.stage(Stage::Verify);
    go_on(progress)?;
    let t = Instant::now();
    let certify_options = envelope_verify::Options {
        allow_input_intersections,
        ..envelope_verify::Options::new(epsilon)
    };
    let c = envelope_verify::certify(soup, out, &certify_options);
    Ok(Some(VerifyReport::from_certificate(
        c,
        t.elapsed().as_secs_f64(),
    )))
}

/// What [`simplify_between`] leaves: the simplified mesh and the numbers of the report.
struct Between {
    mesh: HalfEdgeMesh,
    stats: Stats,
    method: &'static str,
    details: Value,
    envelope: EnvelopeReport,
    epsilon_abs: f64,
    epsilon_min_abs: f64,
    simplify_seconds: f64,
    tolerance: Option<TolerancePhaseReport>,
}

impl Between {
    /// The report of a run whose output is `out`.
    fn report(
        self,
        soup: &TriangleSoup,
        out: &TriangleSoup,
        topo_in: &Topology,
        (genus_out, border_loops_out): (Option<u32>, usize),
        verify: Option<VerifyReport>,
        kept: Option<KeptReport>,
        options: &SimplifyOptions,
        start: Instant,
    ) -> SimplifyReport {
        let diagonal = soup.diagonal();
        let stats = self.stats;
        SimplifyReport {
            input_faces: soup.num_faces(),
            output_faces: out.num_faces(),
            input_vertices: topo_in.num_referenced_vertices,
            output_vertices: out.num_vertices(),
            epsilon_abs: self.epsilon_abs,
            epsilon_min_abs: self.epsilon_min_abs,
            epsilon_fraction: self.epsilon_abs / diagonal,
            diagonal,
            seconds: start.elapsed().as_secs_f64(),
            simplify_seconds: self.simplify_seconds,
            peak_memory_bytes: peak_memory_bytes(),
            removed_vertices: stats.removed,
            placement: match options.placement {
                Placement::Subset => "subset",
                Placement::Slide => "slide",
                Placement::Collapse => "collapse",
                Placement::Auto if stats.light_gave_up => "auto: light collapse, given up",
                Placement::Auto if stats.moving_phase_light => "auto: light collapse",
                Placement::Auto if stats.moving_phase => "auto: collapse",
                Placement::Auto => "auto: subset",
            },
            slid_removals: stats.slid,
            collapsed_removals: stats.collapsed,
            attempts: stats.attempts,
            no_fill_across_fiber: stats.no_fill_across_fiber,
            genus_in: topo_in.genus,
            genus_out,
            border_loops_in: topo_in.num_border_loops(),
            border_loops_out,
            envelope: self.envelope,
            verify,
            kept,
            method: self.method,
            method_details: self.details,
            tolerance_phase: self.tolerance,
        }
    }
}

/// The envelopes' statistics for the report.
fn envelope_report(env: &Envelopes, options: &SimplifyOptions, seconds: f64) -> EnvelopeReport {
    let fractions = env.achieved_fractions();
    EnvelopeReport {
        method: match options.method {
            EnvelopeMethod::Analytical => "analytical",
            EnvelopeMethod::Numerical => "numerical",
            EnvelopeMethod::Auto => match env.method {
                EnvelopeMethod::Numerical => "auto: numerical",
                _ => "auto: analytical",
            },
        },
        achieved_median: quantile(&fractions, 0.5),
        achieved_p5: quantile(&fractions, 0.05),
        achieved_min: quantile(&fractions, 0.0),
        proved: env.proof.holds(),
        repair_rounds: env.proof.repair_rounds,
        tubes: env.tubes.len(),
        pinned: env.pinned.len(),
        seconds,
    }
}

/// Sections 5.1-5.2 between proved envelopes: the barriers (envelopes, tubes, border walls,
/// and the kept faces of a self-intersecting input with the vertices they share kept), the
/// half-edge mesh of `soup`, and the step run on it. `used`: the referenced vertices of the
/// whole input (whose requested epsilons bound the output). `held_to`: the constant
/// epsilon of `options` when the envelopes were built at less ([`tolerance_cap`]).
#[allow(clippy::too_many_arguments)]
fn simplify_between(
    soup: &TriangleSoup,
    topo_in: &Topology,
    (env, env_seconds): (Envelopes, f64),
    used: &[bool],
    kept: Option<&KeptRegion>,
    held_to: Option<f64>,
    options: &SimplifyOptions,
    step: &dyn SimplifyStep,
    progress: &mut dyn Progress,
) -> Result<Between, DriverError> {
    let env_proved = env.proof.holds();
    let envelope = envelope_report(&env, options, env_seconds);
    let requested = env
        .requested
        .iter()
        .zip(used)
        .filter(|(_, u)| **u)
        .fold((0.0f64, f64::INFINITY), |(hi, lo), (&e, _)| {
            (hi.max(e), lo.min(e))
        });
    let env_epsilon_abs = requested.0;
    let (epsilon_abs, epsilon_min_abs) = held_to.map_or(requested, |e| (e, e));
    // The tubes' rings, by border vertex: a new border edge must pass through those it
    // stands for (module `border_cover`).
    let cover = BorderCover::new(
        &env.tubes
            .iter()
            .map(|t| (&t.border[..], t.closed, &t.mesh))
            .collect::<Vec<_>>(),
    );
    let tubes: Vec<TriangleSoup> = env.tubes.into_iter().map(|t| t.mesh).collect();
    // Without the walls, the space between the envelopes is open along the border and an
    // interior candidate triangle can leave it there (see `walls`).
    let mut walls: Vec<TriangleSoup> = border_walls(soup, topo_in, &env.outer, &env.inner)
        .into_iter()
        .map(|w| w.mesh)
        .collect();
    // The kept faces: no new triangle may touch them but at a shared vertex.
    walls.extend(kept.map(|k| k.kept.clone()));
    let (outer, inner) = (env.outer.positions.clone(), env.inner.positions.clone());
    let referenced = referenced(soup);
    // Pins: where an envelope passes through the input vertex (a zero offset; every pinned
    // vertex, and any vertex the numerical growth could not move at all).
    let pins: Vec<DVec3> = (0..soup.num_vertices())
        .filter(|&v| referenced[v] && (env.eps_plus[v] == 0.0 || env.eps_minus[v] == 0.0))
        .map(|v| soup.positions[v])
        .collect();
    // The barriers' tree, the mesh the simplifier edits and the fiber test are independent:
    // built side by side.
    let (barriers, (mesh, fiber_test)) = rayon::join(
        // The proof's tree over the envelopes: only the tubes and walls get a new one.
        || Barriers::with_tree(vec![env.outer, env.inner], env.tree, tubes, walls),
        || {
            rayon::join(
                || HalfEdgeMesh::from_soup(soup),
                // The fiber test's conditions: envelopes proved apart from the input,
                // nothing pinned. (It only refuses: more barriers leave its refusals true.)
                || {
                    (env_proved && pins.is_empty()).then(|| {
                        FiberTest::new(
                            VertexFibers {
                                inner: &inner,
                                outer: &outer,
                            },
                            &soup.faces,
                        )
                    })
                },
            )
        },
    );
    let mut keep = options.keep.clone();
    let mut barriers = barriers?.with_pins(&pins).with_border_cover(cover);
    if let Some(k) = kept {
        keep.resize(keep.len().max(k.shared.len()), false);
        for (slot, &s) in keep.iter_mut().zip(&k.shared) {
            *slot |= s;
        }
        let shared: Vec<DVec3> = (0..soup.num_vertices())
            .filter(|&v| k.shared[v])
            .map(|v| soup.positions[v])
            .collect();
        barriers = barriers.with_wall_pins(&shared);
    }
    let barriers = barriers.with_kept(keep);
    let mut mesh = mesh?;
    go_on(progress)?;
    progress.stage(Stage::Simplify {
        vertices: mesh.num_vertices(),
    });
    go_on(progress)?;
    let t_simp = Instant::now();
    let input = StepInput {
        barriers: &barriers,
        outer: &outer,
        inner: &inner,
        options,
        fiber_test: fiber_test.as_ref(),
    };
    let mut outcome = step.run(&mut mesh, &input, progress)?;
    go_on(progress)?;
    // What follows proves against the input, not the envelopes: their barriers and fiber
    // test go first (hundreds of megabytes on a fine scan at large epsilon).
    let kept_faces = barriers.kept().to_vec();
    drop(fiber_test);
    drop((barriers, outer, inner));
    let mut tolerance = None;
    let cut_back = envelope.achieved_p5 < TOLERANCE_WHEN_CUT_BELOW;
    if options.tolerance_phase
        && kept.is_none()
        && epsilon_abs == epsilon_min_abs
        && (held_to.is_some() || cut_back)
    {
        let target = options.target_faces.map(TargetFaces);
        let mut visitor = ProgressVisitor {
            progress,
            attempts: 0,
            removed: 0,
        };
        let t_phase = Instant::now();
        let past = simplify_past_envelopes(
            &mut mesh,
            soup,
            epsilon_abs,
            &kept_faces,
            target.as_ref().map(|t| t as &dyn StopRule),
            &mut visitor,
        )?;
        outcome.stats.add_later(&past);
        tolerance = Some(TolerancePhaseReport {
            removed_vertices: past.removed,
            seconds: t_phase.elapsed().as_secs_f64(),
            envelope_epsilon_abs: env_epsilon_abs,
        });
        go_on(progress)?;
    }
    Ok(Between {
        mesh,
        stats: outcome.stats,
        method: outcome.method,
        details: outcome.details,
        envelope,
        epsilon_abs,
        epsilon_min_abs,
        simplify_seconds: t_simp.elapsed().as_secs_f64(),
        tolerance,
    })
}

/// How much of the input was kept as it was ([`SimplifyReport::kept`]): around its
/// intersecting pairs, and where its envelopes could not be proved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KeptReport {
    /// Intersecting face pairs of the input (T-junction and coincident pairs among them).
    pub intersecting_pairs: usize,
    /// Input faces kept unchanged: the faces of those pairs, those the envelope proof named
    /// and the faces around them, and what keeps the rest a manifold.
    pub kept_faces: usize,
    /// Envelope builds after the first: each time the rest's envelopes could not be proved,
    /// the faces the proof named were kept too (or one ring around the kept ones).
    pub rounds: usize,
    /// Vertices the kept faces share with the rest (kept, never removed nor moved).
    pub shared_vertices: usize,
}

/// Where [`simplify_keeping`] starts.
enum Start {
    /// A self-intersecting input (its only error classes are [`CROSSINGS`]): its intersecting
    /// pairs, and the classes to refuse it with when nothing is left to simplify.
    Pairs(Vec<(FaceId, FaceId)>, Vec<(DegeneracyClass, usize)>),
    /// An input whose envelopes could not be proved: those envelopes.
    Unproved(Box<Envelopes>),
}

/// Some faces kept as they are (module `kept`): the faces of a self-intersecting input's
/// intersecting pairs, and the faces an envelope proof names where it fails; the rest
/// simplified between its own proved envelopes, the two joined again and certified with the
/// input's own intersections allowed.
fn simplify_keeping(
    soup: &TriangleSoup,
    topo_in: &Topology,
    used: &[bool],
    start_with: Start,
    options: &SimplifyOptions,
    step: &dyn SimplifyStep,
    progress: &mut dyn Progress,
    start: Instant,
) -> Result<(TriangleSoup, SimplifyReport), DriverError> {
    let (pairs, problems, mut first) = match start_with {
        Start::Pairs(pairs, problems) => (pairs, Some(problems), None),
        Start::Unproved(env) => (Vec::new(), None, Some(env)),
    };
    let mut region = KeptRegion::around(soup, &pairs);
    let mut rounds = 0;
    let mut minima = None;
    let mut last = (0, 0);
    let (region, env, env_seconds) = loop {
        go_on(progress)?;
        let t = Instant::now();
        if region.rest.num_faces() == 0 {
            return Err(match problems {
                Some(problems) if rounds == 0 => DriverError::Unacceptable(problems),
                _ => DriverError::UnprovedEnvelopes {
                    contacts: last.0,
                    repair_rounds: last.1,
                },
            });
        }
        // The first round of an unproved input is its own envelopes (nothing kept yet). Each
        // round's rest is a subset of the one before: its clipping takes the minima that
        // still hold from the round before (the same offsets, computed near the changes only).
        let memo = match minima.take() {
            Some(before) => AnalyticalMemo::Reuse(before),
            None => AnalyticalMemo::Keep,
        };
        let mut env = match first.take() {
            Some(env) => *env,
            None => envelopes_up_to(&region.rest, options, None, None, None, Some(memo))?,
        };
        minima = env.analytical.take();
        last = (
            env.proof.contacts.len() + env.proof.tube_contacts.len(),
            env.proof.repair_rounds,
        );
        if env.proof.holds() {
            break (region, env, t.elapsed().as_secs_f64());
        }
        if rounds == MAX_ROUNDS {
            return Err(DriverError::UnprovedEnvelopes {
                contacts: env.proof.contacts.len() + env.proof.tube_contacts.len(),
                repair_rounds: env.proof.repair_rounds,
            });
        }
        // The rest faces the proof names (as input faces, or through their envelope faces,
        // which have the input's connectivity) are kept too.
        let named: Vec<FaceId> = env
            .proof
            .contacts
            .iter()
            .chain(&env.proof.tube_contacts)
            .flat_map(|c| [c.a, c.b])
            .filter(|(surface, _)| !matches!(surface, Surface::Tube(_)))
            .map(|(_, f)| region.rest_faces[f.index()])
            .collect();
        // Two tubes that meet (or one meeting itself, where the border turns back on itself:
        // its rings lie almost along the border and no radius clears them) name no face.
        // Along the cut the ring below moves the border; on the input's own border nothing
        // would, so the faces around those border vertices of their segments are kept. So
        // every round keeps more than the one before.
        let tube_face = |(surface, f): (Surface, FaceId)| match surface {
            Surface::Tube(t) => Some((&env.tubes[t as usize], f)),
            _ => None,
        };
        let at: Vec<VertexId> = env
            .proof
            .tube_contacts
            .iter()
            .filter(|c| tube_face(c.a).is_some() && tube_face(c.b).is_some())
            .flat_map(|c| [c.a, c.b])
            .filter_map(tube_face)
            .flat_map(|(tube, f)| {
                // Segment `i` (between rings `i` and `i + 1`) has two faces per ring vertex.
                let n = tube.border.len().max(1);
                let i = f.index() / (2 * tube.mesh.num_vertices() / n).max(1);
                [i, i + 1].map(|j| tube.border.get(j % n).copied())
            })
            .flatten()
            .filter(|v| !region.shared[v.index()])
            .collect();
        region = region.grown(soup, &named, &at);
        rounds += 1;
    };
    let topo_rest = analyze(&region.rest);
    let between = simplify_between(
        &region.rest,
        &topo_rest,
        (env, env_seconds),
        used,
        Some(&region),
        None,
        options,
        step,
        progress,
    )?;
    // The kept faces joined on again: their vertices are live in the mesh (shared ones are
    // kept, the others isolated there, and no step removes an isolated vertex).
    let (mut out, ids, _) = between.mesh.to_soup_with_ids();
    let mut index_of = vec![u32::MAX; ids.iter().map(|v| v.index() + 1).max().unwrap_or(0)];
    for (i, v) in ids.iter().enumerate() {
        index_of[v.index()] = i as u32;
    }
    for f in &region.kept.faces {
        let joined = f.map(|v| index_of.get(v.index()).copied().unwrap_or(u32::MAX));
        if let Some(k) = joined.iter().position(|&i| i == u32::MAX) {
            return Err(DriverError::Simplify(SimplifyError::SanityCheck {
                after: f[k],
                message: "a vertex of a kept face left the mesh".into(),
            }));
        }
        out.faces.push(joined.map(VertexId));
    }
    let topo_out = analyze(&out);
    let kept = KeptReport {
        intersecting_pairs: pairs.len(),
        kept_faces: region.num_kept(),
        rounds,
        shared_vertices: region.shared.iter().filter(|&&s| s).count(),
    };
    let verify = certify(soup, &out, between.epsilon_abs, true, options, progress)?;
    let numbers = (topo_out.genus, topo_out.num_border_loops());
    let report = between.report(
        soup,
        &out,
        topo_in,
        numbers,
        verify,
        Some(kept),
        options,
        start,
    );
    Ok((out, report))
}

fn referenced(soup: &TriangleSoup) -> Vec<bool> {
    let mut used = vec![false; soup.num_vertices()];
    for f in &soup.faces {
        for v in f {
            used[v.index()] = true;
        }
    }
    used
}

fn run_local(
    mesh: &mut HalfEdgeMesh,
    input: &StepInput<'_>,
    seeds: Option<&[VertexId]>,
    progress: &mut dyn Progress,
) -> Result<Stats, SimplifyError> {
    let options = input.options;
    let local_options = LocalOptions {
        order: options.order,
        hole_filling: options.hole_filling,
        target_faces: options.target_faces,
        check_each_step: false,
        placement: options.placement,
    };
    let fibers = VertexFibers {
        inner: input.inner,
        outer: input.outer,
    };
    let mut visitor = ProgressVisitor {
        progress,
        attempts: 0,
        removed: 0,
    };
    simplify_local_from(
        mesh,
        input.barriers,
        &local_options,
        seeds,
        Some(fibers),
        input.fiber_test,
        &mut visitor,
    )
}
