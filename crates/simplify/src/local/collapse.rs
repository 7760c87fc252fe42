//! Edge collapses into a moved neighbour ([`Placement::Collapse`]): the positions tried,
//! and the removal seen as a hole filled by the fan from the kept vertex.
//!
//! [`Placement::Collapse`]: super::Placement::Collapse

use super::plan::{LocalSimplifier, Plan, in_range};
use super::{Removal, VertexFibers};
use crate::fill::{FillContext, HoleFiller};
use crate::filter::Filter;
use crate::rules::Rejection;
use envelope_mesh::{HalfEdgeMesh, VertexId};
use glam::DVec3;

/// At most this many (neighbour, position) pairs are tried per vertex by the collapse step.
pub(super) const COLLAPSE_TRIES: usize = 8;

/// A collapse position whose root-mean-square distance to the planes of the faces around
/// `v` and `w` exceeds this many times the local offset (half the longer fiber of `v` and
/// `w`) is not tried. A choice, measured: such positions are most of the tries and almost
/// none of the successes; the test is f64 and only skips, so it can cost faces, never the
/// guarantee.
pub(super) const COLLAPSE_REACH: f64 = 1.25;

/// The positions an edge collapse of `v` may try, at most [`COLLAPSE_TRIES`], cheapest first
/// by the quadric cost below: for each interior neighbour `w`, the point minimising the
/// area-weighted squared distances to the planes of the current faces around `v` and `w`
/// (memoryless quadrics, regularised towards the edge's midpoint so that flat and crease
/// neighbourhoods have one answer), `w`'s own position (a half-edge collapse) and the
/// midpoint. The cost is that mean squared distance (the quadric over the faces' total
/// area); with fibers, positions beyond [`COLLAPSE_REACH`] are dropped. f64, a priority
/// only: every position is tested exactly.
pub(super) fn collapse_candidates(
    m: &HalfEdgeMesh,
    v: VertexId,
    fibers: Option<&VertexFibers<'_>>,
) -> Vec<(f64, VertexId, DVec3)> {
    use glam::DMat3;
    if m.is_border_vertex(v) {
        return Vec::new();
    }
    let planes = |x: VertexId| {
        m.vertex_faces(x).map(|f| {
            let [a, b, c] = m.face_vertices(f).map(|y| m.position(y));
            let n2 = (b - a).cross(c - a);
            let area = 0.5 * n2.length();
            let n = if area > 0.0 {
                n2 / (2.0 * area)
            } else {
                DVec3::ZERO
            };
            (f, area, n, -n.dot(a))
        })
    };
    let half_fiber = |x: VertexId| {
        fibers
            .and_then(|f| f.segment(x))
            .map(|(_, d)| 0.5 * d.length())
    };
    let around_v: Vec<_> = planes(v).collect();
    let mut out = Vec::new();
    for w in m.vertex_neighbors(v) {
        if m.is_border_vertex(w) {
            continue;
        }
        let mut faces: Vec<_> = around_v.iter().copied().chain(planes(w)).collect();
        faces.sort_unstable_by_key(|x| x.0);
        faces.dedup_by_key(|x| x.0);
        let total: f64 = faces.iter().map(|x| x.1).sum();
        if !total.is_finite() || total <= 0.0 {
            continue;
        }
        let cost = |x: DVec3| -> f64 {
            faces
                .iter()
                .map(|&(_, a, n, d)| a * (n.dot(x) + d).powi(2))
                .sum::<f64>()
                / total
        };
        // Without a fiber at either end there is no local offset to compare with.
        let reach = match (half_fiber(v), half_fiber(w)) {
            (None, None) => f64::INFINITY,
            (a, b) => COLLAPSE_REACH * a.unwrap_or(0.0).max(b.unwrap_or(0.0)),
        };
        let mut push = |x: DVec3| {
            let c = cost(x);
            if c <= reach * reach {
                out.push((c, w, x));
            }
        };
        let mid = 0.5 * (m.position(v) + m.position(w));
        let lambda = 1e-3 * total;
        let mut q = DMat3::from_diagonal(DVec3::splat(lambda));
        let mut r = lambda * mid;
        for &(_, a, n, d) in &faces {
            q += DMat3::from_cols(n * n.x, n * n.y, n * n.z) * a;
            r -= n * (a * d);
        }
        if q.determinant().abs() > 0.0 {
            let x = q.inverse() * r;
            if x.is_finite() {
                push(x);
            }
        }
        push(m.position(w));
        push(mid);
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.truncate(COLLAPSE_TRIES);
    out
}

impl LocalSimplifier<'_> {
    /// Tries to remove `v` by collapsing its edge into the neighbour `w`, moved to `p`: the
    /// hole `v` leaves is filled by the fan from `w` (a half-edge collapse when `p` is `w`'s
    /// position), every triangle of the fan and every other face around the moved `w` through
    /// `filter`. All or nothing, like [`Self::try_slide_remove`]. Border vertices, a `p` with
    /// a coordinate outside the exact predicates' range, and edges that break the link
    /// condition (an edge of the fan that exists elsewhere) are refused.
    pub fn try_collapse(
        &mut self,
        v: VertexId,
        w: VertexId,
        p: DVec3,
        filter: &dyn Filter,
    ) -> Result<Removal, Rejection> {
        let (plan, tests) = self.plan_collapse(v, w, p, filter);
        self.candidate_tests += tests;
        self.apply(v, plan?)
    }

    /// The plan of [`Self::try_collapse`] (read only), and the filter calls it made.
    pub(super) fn plan_collapse(
        &self,
        v: VertexId,
        w: VertexId,
        p: DVec3,
        filter: &dyn Filter,
    ) -> (Result<Plan, Rejection>, u64) {
        let m = &*self.mesh;
        if !m.contains_vertex(v) || !m.contains_vertex(w) || m.find_halfedge(v, w).is_none() {
            return (Err(Rejection::NotAVertex), 0);
        }
        if self.keeps(v) || self.keeps(w) {
            return (Err(Rejection::Kept), 0);
        }
        if m.is_border_vertex(v) || m.is_border_vertex(w) || !in_range(p) {
            return (Err(Rejection::NoValidFill), 0);
        }
        let moves = if p == m.position(w) {
            Vec::new()
        } else {
            vec![(w, p)]
        };
        self.plan_moved(v, moves, filter, &FanFrom(w))
    }
}

/// Fills a closed hole with the fan from one of its vertices (an edge collapse seen as a
/// vertex removal): the triangles `(apex, a, b)` for every hole edge `a b` not at the apex,
/// in hole order, each through the context's filter.
struct FanFrom(VertexId);

impl HoleFiller for FanFrom {
    fn fill(&self, ctx: &mut FillContext<'_>) -> bool {
        let hole = ctx.hole();
        let n = hole.len();
        let Some(k) = hole.vertices.iter().position(|&x| x == self.0) else {
            return false;
        };
        if hole.open || n < 3 {
            return false;
        }
        for i in 0..n {
            let j = (i + 1) % n;
            if i == k || j == k {
                continue;
            }
            // Increasing positions: a rotation of (k, i, j), so the hole's orientation.
            let mut t = [k, i, j];
            t.sort_unstable();
            if !ctx.accepts(t) {
                return false;
            }
            ctx.place(t);
        }
        true
    }
}
