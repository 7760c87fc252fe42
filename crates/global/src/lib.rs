//! The global set-cover simplifier of Simplification Envelopes (Cohen et al. 1996, sections
//! 5.3 and 5.4), on the envelopes, validity filter and hole filling of `envelope-simplify`.
//!
//! * [`seed_candidates`]: candidate triangles on the boundaries of small disk
//!   [`Region`]s, each covering the vertices whose fundamental-prism edge ([`Fibers`]) it
//!   meets (the generalized projection, exact); see the `candidates` docs for what the
//!   pruning can miss.
//! * [`surface_candidates`]: candidate triangles from the whole surface (issue 37), corners
//!   within a few edges of a seed on the current approximation, cover found through a
//!   [`FiberIndex`] and decided exactly, each with its maximal hole ([`maximal_hole`]).
//! * [`simplify_global`]: the greedy selection (rank by cover, skip overlapping, cut, place,
//!   fill the sub-holes, or roll back).
//! * [`Method`] / [`HybridStep`] / [`GlobalStep`]: `local`, `global` and `hybrid` as steps of
//!   [`envelope_simplify::simplify_with`], which keeps the input checks, envelopes, tubes,
//!   walls, certificate and report of the local driver.
//!
//! The guarantee is the local algorithm's: every placed triangle passes the exact validity
//! test of 5.1 against the envelopes, the walls and the current approximation, so the output
//! is within epsilon of the input both ways, does not self-intersect, and keeps genus and
//! border loops. Cover and aspect ratios only order the work.
#![forbid(unsafe_code)]

mod candidates;
mod global;
mod region;
mod step;
mod surface;

pub use candidates::{Candidate, Fibers, Generated, Reach, covers, seed_candidates};
pub use global::{GlobalError, GlobalOptions, GlobalStats, simplify_global, simplify_global_with};
pub use region::{Region, ball, region};
pub use step::{GlobalStep, HybridOrder, HybridStep, Method};
pub use surface::{
    FiberIndex, SURFACE_RINGS, SurfaceReach, covered, maximal_hole, surface_candidates,
};
