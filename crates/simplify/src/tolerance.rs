//! The tolerance phase: simplification past the envelopes, where they bind.
//!
//! Where the input is thinner than twice epsilon (ears, fingers, plates), the envelopes of
//! its two sides would cross, so their offsets are cut back (section 4) and the envelopes,
//! not epsilon, stop the simplification: the face count stops falling as epsilon grows.
//! The paper names the way out in 8.2 (vertices that move, the original surface itself as a
//! constraint). This phase takes the contract itself as the constraint, as tolerance-volume
//! simplifiers do, and proves it per operation instead of through the envelopes.
//!
//! It runs after the simplification step, on its output, with the moving phase's
//! operations (the plain removal of a vertex, then edge collapses into a neighbour at the
//! positions of the collapse placement), one vertex at a time, each through the
//! [`ToleranceFilter`]:
//!
//! 1. every new triangle (of the filling, and every face around a moved vertex) is proved
//!    within epsilon of the input: the certificate's exact branch and bound
//!    ([`envelope_verify::Within`]); its corners are not exactly collinear. The hole filler
//!    chooses triangles by an estimate (sampled points within epsilon, f64); the proofs run
//!    once the whole operation is known, with 3;
//! 2. every new triangle meets the rest of the approximation only at the corners and edges
//!    it shares with it (the 5.1 test, exact);
//! 3. the operation as a whole: every input triangle whose box comes within epsilon of a
//!    removed face's box is proved within epsilon of the new triangles and the unchanged
//!    faces near it (the same branch and bound, the other way).
//!
//! **Why the output keeps the contract.** Invariant: every point of the approximation is
//! within epsilon of the input (A), every point of the input within epsilon of the
//! approximation (B), the approximation does not meet itself, and it is a closed-up copy of
//! the input's surface (same genus, components, borders). The step's output has them (the
//! envelopes' guarantee, which the certificate checks at the end in any case). An
//! operation replaces the faces `old` (a vertex's fan, and the faces around a moved vertex)
//! by `new` with the same boundary:
//!
//! - (A) the faces that stay did not move; each new one is proved by 1;
//! - (B) an input point `p` farther than epsilon from every face of `old` had its nearest
//!   point within epsilon on a face that stays; a point within epsilon of a face `t` of
//!   `old` lies in `t`'s box grown by epsilon, so its input triangle is among those 3
//!   proves against a subset of the new approximation (distance to a subset bounds the
//!   distance to the whole);
//! - intersections: by 2, as in 5.1; topology: a closed hole refilled by a disc, an open
//!   one (a border vertex's half disc) by a disc closed by the new border edge between its
//!   two border neighbours (which must not already be an edge, so a loop keeps at least
//!   three vertices), or an edge collapse under the link condition, changes no genus,
//!   component or border loop, and without intersections the surface stays embedded.
//!   Nothing here needs the border tubes of 6.2: the border's points are input points like
//!   any other, covered by 3, and the new border edges are edges of triangles proved by 1.
//!
//! Every decision is exact; a search left undecided by its budget refuses. The certificate
//! still judges the output.
//!
//! Choices the paper leaves open:
//!
//! | question | answer |
//! |---|---|
//! | when | after the step, on its output; only for a constant epsilon, an input without crossings kept as they are, and when asked (`SimplifyOptions::tolerance_phase`) |
//! | operations | the moving phase's: the plain removal (greedy filling), then collapses into a neighbour at the collapse placement's positions (no fibers here, so no reach limit: 1 refuses the far ones) |
//! | order | every vertex in id order, first in first out, neighbours of a change queued again |
//! | parallelism | the moving phase's batches of operations planned side by side, with each operation's box grown by epsilon plus half the largest input triangle (3 reads the approximation up to twice epsilon plus an input triangle beyond what the operation changes), so that no plan of a batch reads what another changes; the output does not depend on the thread count |
//! | borders | border vertices are removed like the others (their open holes filled, the new border edge proved with its triangle), not moved: the collapses keep them, as the moving phase does |

use crate::fill::Greedy;
use crate::filter::{Approximation, CandidateProfile, Filter};
use crate::local::{Policies, SimplifyError, Stats, tolerance_phase};
use crate::rules::{Exhaust, Fifo, StopRule, Visitor};
use envelope_mesh::{HalfEdgeMesh, TriangleSoup};
use envelope_predicates::bvh::Aabb;
use envelope_verify::Within;
use glam::DVec3;

/// The validity test of the tolerance phase (see the module docs): a candidate triangle is
/// valid when its corners are not collinear, it meets the approximation only where it
/// shares corners with it, and it lies within epsilon of the input; a replacement when the
/// input near the removed faces stays within epsilon of the approximation.
pub struct ToleranceFilter<'w> {
    within: &'w Within,
}

impl<'w> ToleranceFilter<'w> {
    /// The test against the input of `within`, at its epsilon.
    #[must_use]
    pub fn new(within: &'w Within) -> Self {
        Self { within }
    }
}

/// Points of a triangle sampled for the estimate of [`ToleranceFilter::accepts`]: the
/// barycentric grid of this many steps per edge.
const SAMPLE_STEPS: u32 = 4;

/// The points `(i a + j b + k c) / SAMPLE_STEPS` of `t`, `i + j + k = SAMPLE_STEPS` (f64).
fn samples(t: [DVec3; 3]) -> Vec<DVec3> {
    let n = SAMPLE_STEPS;
    let mut out = Vec::with_capacity(((n + 1) * (n + 2) / 2) as usize);
    for i in 0..=n {
        for j in 0..=n - i {
            let k = n - i - j;
            out.push(
                (f64::from(i) * t[0] + f64::from(j) * t[1] + f64::from(k) * t[2]) / f64::from(n),
            );
        }
    }
    out
}

impl Filter for ToleranceFilter<'_> {
    /// Exact: not collinear, no intersection with the approximation. Estimated: no sampled
    /// point beyond epsilon from the input (a shortcut that only refuses; the proof is in
    /// [`Filter::refuses_replacement`], once the whole operation is known).
    fn accepts(&self, p: &CandidateProfile<'_>) -> bool {
        !self.refuses_anyway(p) && !p.approximation.intersects(p.triangle, p.corners)
    }

    /// The estimate of [`Filter::accepts`], which needs nothing of the approximation.
    fn refuses_anyway(&self, p: &CandidateProfile<'_>) -> bool {
        let [a, b, c] = p.corners;
        envelope_predicates::collinear(a, b, c)
            || self.within.some_point_beyond(&samples(p.corners))
    }

    fn refuses_replacement(
        &self,
        old: &[[DVec3; 3]],
        new: &[[DVec3; 3]],
        rest: &Approximation<'_>,
        _open: bool,
    ) -> bool {
        let epsilon = self.within.epsilon();
        // The input triangles within reach of a removed face.
        let reach: Vec<Aabb> = old
            .iter()
            .map(|&t| Aabb::from_triangle(t).inflated(epsilon))
            .collect();
        let at_risk = self.within.triangles_overlapping(&reach);
        let Some(region) = at_risk
            .iter()
            .map(|&t| Aabb::from_triangle(t))
            .reduce(|a, b| a.union(&b))
        else {
            return false;
        };
        // What covers them: the new triangles and the faces that stay within epsilon of them.
        let reach = region.inflated(epsilon);
        let mut cover = new.to_vec();
        rest.grid.any_overlapping(&reach, |f, g| {
            if !rest.excluded.contains(&f) {
                cover.push(g.map(|v| rest.position(v)));
            }
            false
        });
        let cover = Within::from_triangles(cover, epsilon);
        // Cheapest first: the input's corners estimated against the cover, the new
        // triangles proved against the input, the input proved against the cover.
        cover.some_point_beyond(&corners_from(&at_risk, &region))
            || !self.within.holds(new)
            || !cover.holds(&at_risk)
    }
}

/// The corners of `tris`, each once, nearest to the middle of `region` first: where a
/// removal uncovers the input, it does so around the removed vertex, so an estimate that
/// stops at the first point beyond gets there sooner.
fn corners_from(tris: &[[DVec3; 3]], region: &Aabb) -> Vec<DVec3> {
    let middle = 0.5 * (region.min + region.max);
    let mut corners: Vec<DVec3> = tris.iter().flatten().copied().collect();
    corners.sort_unstable_by_key(|p| p.to_array().map(f64::to_bits));
    corners.dedup();
    corners.sort_by(|a, b| {
        a.distance_squared(middle)
            .total_cmp(&b.distance_squared(middle))
    });
    corners
}

/// Runs the tolerance phase (module docs) on `mesh`, the output of a simplification of
/// `input` at the constant `epsilon`: `keep` names the vertices never removed nor moved
/// (by id), `stop` may end it early.
pub(crate) fn simplify_past_envelopes(
    mesh: &mut HalfEdgeMesh,
    input: &TriangleSoup,
    epsilon: f64,
    keep: &[bool],
    stop: Option<&dyn StopRule>,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    let within = Within::new(input, epsilon);
    let filter = ToleranceFilter::new(&within);
    let policies = Policies {
        filter: &filter,
        order: &Fifo,
        filler: &Greedy::default(),
        stop: stop.unwrap_or(&Exhaust),
        keep_border: false,
        keep,
        check_each_step: false,
        fibers: None,
        collapse: true,
        auto_moving: false,
        fiber_test: None,
    };
    // The filter reads faces within twice epsilon plus an input triangle of what an
    // operation changes (module docs): half of it, with room for the boxes' rounding.
    let reads_beyond = 1.01 * (epsilon + 0.5 * within.largest_extent());
    tolerance_phase(mesh, &policies, reads_beyond, visitor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::FaceGrid;
    use envelope_mesh::{FaceId, VertexId, generate};

    /// A sphere with one vertex pulled out into a spike, the spike's fan and the fan from
    /// its first neighbour over the hole it leaves.
    fn spike() -> (TriangleSoup, HalfEdgeMesh, Vec<FaceId>, Vec<[DVec3; 3]>) {
        let mut soup = generate::icosphere(2, 1.0);
        soup.positions[0] *= 1.5;
        let mesh = HalfEdgeMesh::from_soup(&soup).unwrap();
        let v = VertexId(0);
        let fan: Vec<FaceId> = mesh.vertex_faces(v).collect();
        let ring: Vec<VertexId> = mesh.vertex_neighbors(v).collect();
        let new = (1..ring.len() - 1)
            .map(|i| [ring[0], ring[i], ring[i + 1]].map(|x| mesh.position(x)))
            .collect();
        (soup, mesh, fan, new)
    }

    #[test]
    fn a_removal_that_uncovers_the_input_is_refused() {
        let (soup, mesh, fan, new) = spike();
        let grid = FaceGrid::from_mesh(&mesh);
        let old: Vec<[DVec3; 3]> = fan
            .iter()
            .map(|&f| mesh.face_vertices(f).map(|x| mesh.position(x)))
            .collect();
        let rest = Approximation {
            excluded: &fan,
            ..Approximation::of_mesh(&mesh, &grid)
        };
        // The spike's tip is about 0.55 above the flat filling.
        let small = Within::new(&soup, 0.1);
        assert!(ToleranceFilter::new(&small).refuses_replacement(&old, &new, &rest, false));
        // Within 0.75 of the filling; the input farther round is covered by the faces that
        // stay, which the test must count.
        let large = Within::new(&soup, 0.75);
        assert!(!ToleranceFilter::new(&large).refuses_replacement(&old, &new, &rest, false));
        // Without them, the far input is uncovered.
        let nothing_stays: Vec<FaceId> = mesh.faces().collect();
        let alone = Approximation {
            excluded: &nothing_stays,
            ..rest
        };
        assert!(ToleranceFilter::new(&large).refuses_replacement(&old, &new, &alone, false));
    }

    #[test]
    fn samples_cover_the_corners_and_the_middle() {
        let t = [DVec3::X, DVec3::Y, DVec3::Z];
        let s = samples(t);
        assert_eq!(s.len(), 15);
        assert!(t.iter().all(|c| s.contains(c)));
        assert!(
            s.iter()
                .any(|p| (*p - DVec3::new(0.25, 0.25, 0.5)).length() < 1e-15)
        );
    }
}
