//! Fundamental prisms with bilinear-patch sides (Cohen et al., *Simplification Envelopes*,
//! 1996, sections 3, 4 and 8.1): exact point, segment and triangle classification.
//!
//! *Exact predicates, inexact constructions*: the six prism corners `v_i ± ε_i n_i` are f64
//! constructions ([`Prism::from_offsets`] says so); every decision on them is exact
//! (`envelope-predicates` for orientations, and for the curved sides a quadratic side
//! function evaluated with a rigorous f64 filter and an exact-rational fallback).
//!
//! * [`Prism`]: constructors, [`Prism::check`] / [`Prism::sanity_check`],
//!   [`Prism::classify`] ([`Location`]), [`Prism::intersects_segment`],
//!   [`Prism::intersects_triangle`], [`Prism::tetrahedra`].
//! * [`Patch`]: one bilinear side, [`Patch::side`] (the exact side function, derived in the
//!   crate README) and [`Patch::intersects_segment`].
//! * [`PolyhedralPrism`] / [`Split`]: section 8.1, sides split into triangles (the
//!   correspondences between levels of `envelope-simplify` stand on them).
//! * [`details`]: kernel-generic variants (run them on `Checked<Filtered, Exact>` in tests).
//! * [`clip`]: the one inexact part, section 4.1's clipping of a triangle against the prism
//!   in f64 (the analytical epsilon of `envelope-offset`, which follows it with its exact
//!   proof).
#![forbid(unsafe_code)]

pub mod clip;
mod num;
mod patch;
mod poly;
mod prism;

pub use patch::Patch;
pub use poly::{PolyhedralPrism, Split};
pub use prism::{Location, Prism, PrismError};

/// Specialised variants: kernel-generic forms and index-level helpers.
pub mod details {
    pub use crate::patch::details::*;
    pub use crate::poly::details::*;
    pub use crate::prism::details::*;
}
