//! Simplification envelopes: vertex normals, analytical and numerical epsilon, per-vertex
//! epsilon fields and border tubes (Cohen et al., "Simplification Envelopes", 1996, sections
//! 3, 4, 6.2, 6.3).
//!
//! [`build_envelopes`] reads like the paper:
//!
//! 1. accept the input (manifold, consistently oriented: section 3's "well-behaved" model),
//! 2. evaluate the [`EpsilonField`] per vertex (6.3),
//! 3. compute [`vertex_normals`] within 90 degrees of every adjacent face (3); a vertex with
//!    none (a folded fan) is *pinned*: offsets zero there ([`Envelopes::pinned`]),
//! 4. compute per-vertex `eps_plus` / `eps_minus` by the [`EnvelopeMethod::Analytical`] prism
//!    clipping (4.1) or the [`EnvelopeMethod::Numerical`] iterative growth (4.2) (or the growth
//!    from the proved clipping where it fell short: [`EnvelopeMethod::Auto`]),
//! 5. place the envelope vertices `v ± eps_v n_v` (f64 constructions, same connectivity),
//! 6. **prove** exactly that input, outer and inner envelope are pairwise and individually
//!    free of intersections ([`Proof`]); when the proof fails (the analytical distances are
//!    f64 constructions and approximate the bilinear-patch prism; the numerical steps check
//!    end positions, not the swept volume) every vertex of an offending envelope face has its
//!    epsilon halved and the proof is re-run, at most [`EnvelopeOptions::max_repair_rounds`]
//!    times. A proof that still fails is reported, never hidden,
//! 7. grow border [`Tube`]s (6.2) and prove them.
//!
//! Exactness: predicates are exact (`envelope-predicates`), normals, offset vertices and
//! distances are f64 constructions. The guarantee is the exact proof on the constructed
//! vertices, nothing else.
//!
//! Choices the paper leaves open, made here: the normal combination (angle-weighted average,
//! maximin fallback; [`normals`](vertex_normals)), pinning where there is no valid normal,
//! the prism's conservative "closest point" set and the repair by halving (analytical),
//! `K = 4`, global step `min(1 % of the diagonal, eps/K)`, local step half the shortest incident edge within 90 degrees of the
//! offset direction, the step tripled after every accepted step (not in the paper: an
//! unobstructed vertex reaches its target in about 2 checks instead of `K`), at most 10
//! halvings per step (numerical; [`NumericalParams`]), the order of moves (Z-order
//! renumbering, then coloured parallel batches, deterministic; [`engine`](self) docs), outer
//! and inner grown together and checked against each other, and the tube rules in
//! [`tubes`](Tube).
#![forbid(unsafe_code)]

mod analytical;
mod build;
mod engine;
mod error;
mod field;
mod morton;
mod normals;
mod numerical;
mod options;
mod proof;
mod repair;
mod tubes;

#[cfg(test)]
mod tests;

pub use analytical::AnalyticalFaces;
pub use build::{Envelopes, build_envelopes, build_envelopes_with, face_tree};
pub use error::{EnvelopeError, TUBE_SEGMENTS};
pub use field::{
    EPSILON_SYNTAX, EpsilonField, EpsilonFileError, EpsilonParseError, EpsilonSpec, parse_epsilon,
    read_epsilon_file,
};
pub use normals::{VertexNormals, vertex_normals};
pub use options::{AnalyticalMemo, EnvelopeMethod, EnvelopeOptions, NumericalParams};
pub use proof::{Contact, Proof, Surface};
pub use tubes::Tube;
