//! The simplifier of Simplification Envelopes (Cohen et al. 1996): the local algorithm of
//! sections 5.1 and 5.2 with the border handling of 6.2, run between envelopes by a driver.
//!
//! The front door is the driver: [`simplify`] (and [`simplify_with`], which takes another
//! [`SimplifyStep`]) does the whole job (input check, envelopes, border tubes and walls, the
//! local algorithm, an optional certificate) and reports it in a [`SimplifyReport`];
//! [`lod_chain`] makes nested levels of detail (7.2), and [`correspondence`] says which
//! faces of a finer level each face of a coarser one covers (8.1). Their options and reports
//! are at the crate root.
//!
//! [`policy`] is for those who write their own policies or simplification steps: the
//! barriers, the validity filter of 5.1 shared with the global simplifier, hole fillers,
//! queue orders, stop rules, visitors, the fiber test, border walls, and the local
//! algorithm's lower-level entry points ([`policy::simplify_local`] and its variants).
//!
//! Inside, the modules form a chain: `grid`, `border_cover`, `barriers`, `fiber`, `filter`,
//! `rules`, `walls`, `fill`, then `local` (the algorithm, one idea per file), `kept` (the faces kept
//! around a self-intersecting input's crossings), `driver`, `lod`, `correspond`.
//! Decisions are exact predicates (`envelope-predicates`); aspect ratios and queue
//! priorities are f64 numbers that only order the work.
#![forbid(unsafe_code)]

mod barriers;
mod border_cover;
mod correspond;
mod driver;
mod fiber;
mod fill;
mod filter;
mod grid;
mod kept;
mod local;
mod lod;
pub mod policy;
mod rules;
mod tolerance;
mod walls;

pub use correspond::{Correspondence, correspondence};
pub use driver::{
    CROSSINGS, DriverError, EnvelopeReport, KeptReport, LocalStep, Progress, SimplifyOptions,
    SimplifyReport, SimplifyStep, Stage, StepInput, StepOutcome, TOLERANCE_ENVELOPE_CAP,
    TOLERANCE_WHEN_CUT_BELOW, TolerancePhaseReport, VerifyReport, input_problems,
    peak_memory_bytes, simplify, simplify_with,
};
pub use local::{HoleFilling, Order, Placement};
pub use lod::{Level, LodOptions, LodRule, Screen, lod_chain};
