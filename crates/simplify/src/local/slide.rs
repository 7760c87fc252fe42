//! Sliding vertices along their fibers (the paper's section 8, [`Placement::Slide`]).
//!
//! [`Placement::Slide`]: super::Placement::Slide

use super::plan::{LocalSimplifier, in_range};
use super::{Removal, VertexFibers};
use crate::fill::HoleFiller;
use crate::filter::Filter;
use crate::rules::Rejection;
use envelope_mesh::VertexId;
use glam::DVec3;

/// Slid positions stay within this part of a fiber, `[SLIDE_RANGE, 1 - SLIDE_RANGE]` of the
/// way from the inner to the outer point (a choice: a vertex slid onto an envelope could not
/// keep a single triangle).
const SLIDE_RANGE: f64 = 0.05;

impl LocalSimplifier<'_> {
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
    pub(super) fn slide_moves(
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
            if m.is_border_vertex(u) || self.keeps(u) {
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
}
