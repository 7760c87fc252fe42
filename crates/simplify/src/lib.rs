//! The local simplifier of Simplification Envelopes (Cohen et al. 1996, sections 5.1, 5.2,
//! and the border handling of 6.2).
//!
//! * [`Barriers`]: the envelopes and border tubes as plain triangles (built elsewhere).
//! * [`EnvelopeFilter`]: the validity test of 5.1, one [`Filter`] shared with the global
//!   simplifier; [`FaceGrid`] indexes the current approximation for it.
//! * [`simplify_local`]: the local algorithm of 5.2 (see [`local`] for every
//!   choice the paper leaves open); [`simplify_local_with`] takes any [`Policies`]:
//!   [`QueueOrder`], [`HoleFiller`] ([`Greedy`], [`Exhaustive`]), [`StopRule`], [`Visitor`].
//!
//! * [`border_walls`]: half-tubes closing the space between the envelopes along borders.
//! * [`simplify`]: the whole job (input check, envelopes, local algorithm, optional
//!   certificate) with a [`SimplifyReport`]; [`lod_chain`]: nested levels of detail (7.2).
//!
//! Decisions are exact predicates (`envelope-predicates`); aspect ratios and queue
//! priorities are f64 numbers that only order the work.
#![forbid(unsafe_code)]

mod barriers;
mod driver;
mod fiber;
mod fill;
mod filter;
mod grid;
pub mod local;
pub mod lod;
mod rules;
mod walls;

pub use barriers::{BarrierError, BarrierKind, Barriers};
pub use driver::{
    DriverError, EnvelopeReport, LocalStep, Progress, SimplifyOptions, SimplifyReport,
    SimplifyStep, Stage, StepInput, StepOutcome, VerifyReport, input_problems, peak_memory_bytes,
    simplify, simplify_with,
};
pub use fiber::{FiberTest, VertexFibers};
pub use fill::{Exhaustive, FillContext, Greedy, Hole, HoleFiller};
pub use filter::{Approximation, CandidateProfile, EnvelopeFilter, Filter, Nearby, NoFilter};
pub use grid::FaceGrid;
pub use local::{
    AUTO_MOVING_DIVISOR, HoleFilling, LocalSimplifier, MAX_HOLE, Options, Order, Placement,
    Policies, Removal, RemovalQueue, SimplifyError, Stats, queue_vertices, simplify_local,
    simplify_local_from, simplify_local_sliding, simplify_local_visited, simplify_local_with,
};
pub use lod::{Level, LodOptions, LodRule, Screen, lod_chain};
pub use rules::{
    Exhaust, Fifo, FlatFirst, QueueOrder, Rejection, StopRule, TargetFaces, Visitor, aspect_ratio,
};
pub use walls::{WALL_SEGMENTS, Wall, border_walls};
