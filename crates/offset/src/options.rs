//! What [`crate::build_envelopes`] is asked for: the method, its parameters and the limits
//! on the input.
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::analytical::AnalyticalFaces;
use crate::field::EpsilonField;

/// How the per-vertex epsilon is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum EnvelopeMethod {
    /// Prism clipping (section 4.1), then the exact proof and repair.
    Analytical,
    /// Iterative growth with exact checks (section 4.2).
    #[default]
    Numerical,
    /// The analytical clipping first, proved and repaired. When every offset reaches the
    /// requested epsilon, that is the result. When clipping or repair cut some, the numerical
    /// growth starts from the proved analytical envelopes and moves only the short vertices
    /// (the others are part of its scene, where they are); its result is proved again and
    /// kept when the proof holds (every offset is then at least the analytical one).
    /// When the analytical repair gives up, the numerical method from zero offsets, and the
    /// better of the two. Not in the paper: the analytical method is several times faster
    /// and reaches the full epsilon when it is small against the features; the growth gets
    /// closer to it where epsilon is large against them, and seeding it with the analytical
    /// offsets reaches further than growing from zero.
    Auto,
}

/// Parameters of the numerical method (section 4.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NumericalParams {
    /// `K`: a vertex that has taken fewer than `K` steps halves its step when rejected.
    pub k: u32,
    /// Global step cap as a fraction of the bounding-box diagonal (also capped by `eps/K`).
    pub global_fraction: f64,
    /// Local step as a fraction of the shortest incident edge within 90 degrees of the
    /// offset direction.
    pub local_fraction: f64,
    /// Maximum halvings of one step.
    pub max_halvings: u32,
    /// Factor applied to a mover's step after each accepted step (`1.0`: the paper's fixed
    /// step; `2.0`: doubling, so an unobstructed vertex reaches its target in about
    /// `log2(target / step)` checks instead of `target / step`).
    pub step_growth: f64,
}

impl Default for NumericalParams {
    fn default() -> Self {
        NumericalParams {
            k: 4,
            global_fraction: 0.01,
            local_fraction: 0.5,
            max_halvings: 10,
            step_growth: 3.0,
        }
    }
}

/// Options of [`build_envelopes`](crate::build_envelopes).
#[derive(Debug)]
pub struct EnvelopeOptions {
    /// Requested epsilon per vertex.
    pub epsilon: EpsilonField,
    /// Analytical or numerical.
    pub method: EnvelopeMethod,
    /// Numerical-method parameters (also used to grow tubes).
    pub numerical: NumericalParams,
    /// Vertices per tube ring; `None` builds no tubes.
    pub tube_segments: Option<u32>,
    /// Maximum rounds of "halve offending vertices, re-prove".
    pub max_repair_rounds: u32,
    /// The caller has proved the input free of self-intersections (as `envelope-check`'s
    /// exact pairwise test does, and `envelope simplify` refuses an input that fails it):
    /// the proof then skips input-input pairs. With `false` (the default) it tests them, and
    /// an intersecting input shows as input-input contacts.
    pub input_free_of_intersections: bool,
    /// Set by another thread when the envelopes are no longer wanted (the simplify driver's
    /// input check, running beside the build, found the input unusable as it is): the build
    /// then stops at its next stage, repair round or pass of the numerical growth with
    /// [`EnvelopeError::Abandoned`]. What a build returns never depends on when it was set,
    /// only whether.
    ///
    /// [`EnvelopeError::Abandoned`]: crate::EnvelopeError::Abandoned
    pub abandon: Option<Arc<AtomicBool>>,
    /// What the analytical method keeps for, or takes from, another build (`None`: neither).
    pub analytical_memo: Option<AnalyticalMemo>,
}

/// A build's analytical per-face minima kept for a later build over a subset of its faces,
/// or taken from an earlier one ([`EnvelopeOptions::analytical_memo`]). The offsets are the
/// same as without it; only the clipping of the faces whose minimum still holds is saved.
#[derive(Clone, Debug)]
pub enum AnalyticalMemo {
    /// Keep this build's minima ([`Envelopes::analytical`](crate::Envelopes::analytical)).
    Keep,
    /// Take the minima that still hold from an earlier build's (used only when this build's
    /// faces are a subset of its faces, on the same positions), and keep this build's.
    Reuse(Arc<AnalyticalFaces>),
}

/// Whether `flag` (an [`EnvelopeOptions::abandon`]) is raised: the one reading of it that
/// the build's stages, its repair rounds and the growth's passes share.
pub(crate) fn raised(flag: Option<&AtomicBool>) -> bool {
    flag.is_some_and(|f| f.load(Ordering::Relaxed))
}

impl EnvelopeOptions {
    /// Defaults (numerical, 8-gon tubes, 30 repair rounds) for a field.
    #[must_use]
    pub fn new(epsilon: EpsilonField) -> Self {
        EnvelopeOptions {
            epsilon,
            method: EnvelopeMethod::default(),
            numerical: NumericalParams::default(),
            tube_segments: Some(8),
            max_repair_rounds: 30,
            input_free_of_intersections: false,
            abandon: None,
            analytical_memo: None,
        }
    }
}
