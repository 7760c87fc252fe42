//! For those who write their own policies or simplification steps (as `envelope-global`
//! does): the pieces the driver assembles, after CGAL's Surface_mesh_simplification concepts.
//!
//! * [`Barriers`]: the envelopes, border tubes and walls as plain triangles;
//!   [`border_walls`] builds the walls; [`BorderCover`] the tubes' rings, which a new
//!   border edge must pass through.
//! * [`Filter`]: the validity test of 5.1 on a [`CandidateProfile`]; [`EnvelopeFilter`] is
//!   the paper's, shared by the local and the global simplifier; [`FaceGrid`] indexes the
//!   current approximation for it.
//! * [`HoleFiller`]: how a hole is filled ([`Greedy`], the paper's; [`Exhaustive`]), through
//!   a [`FillContext`].
//! * [`QueueOrder`] ([`Fifo`], [`FlatFirst`]), [`StopRule`] ([`Exhaust`], [`TargetFaces`]),
//!   [`Visitor`] (told every attempt and its [`Rejection`]).
//! * [`FiberTest`]: a necessary condition for removing an interior vertex, over the
//!   [`VertexFibers`].
//! * The local algorithm of 5.2 below the driver: [`simplify_local`] with [`Options`],
//!   [`simplify_local_from`] (seeds, fibers, fiber test, visitor), [`simplify_local_with`]
//!   (any [`Policies`]), and [`LocalSimplifier`] for one removal at a time.

pub use crate::barriers::{BarrierError, BarrierKind, Barriers};
pub use crate::border_cover::BorderCover;
pub use crate::fiber::{FiberTest, VertexFibers};
pub use crate::fill::{Exhaustive, FillContext, Greedy, Hole, HoleFiller};
pub use crate::filter::{
    Approximation, CandidateProfile, EnvelopeFilter, Filter, Nearby, NoFilter,
};
pub use crate::grid::FaceGrid;
pub use crate::local::{
    AUTO_MOVING_DIVISOR, LIGHT_GIVE_UP_BELOW, LIGHT_PROBE, LocalSimplifier, Options, Policies,
    Removal, SimplifyError, Stats, simplify_local, simplify_local_from, simplify_local_with,
};
pub use crate::rules::{
    Exhaust, Fifo, FlatFirst, QueueOrder, Rejection, StopRule, TargetFaces, Visitor, aspect_ratio,
};
pub use crate::walls::{WALL_SEGMENTS, Wall, border_walls};
