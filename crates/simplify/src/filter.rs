//! The validity test of section 5.1 as a [`Filter`]: a yes/no answer about one candidate
//! triangle, given the current approximation.
//!
//! [`EnvelopeFilter`] is *the* test of the paper, shared by the local simplifier here and the
//! global one: a candidate triangle is valid when
//!
//! 1. its corners are not exactly collinear ([`collinear`](envelope_predicates::collinear)),
//! 2. it does not touch any envelope triangle, and each of its edges that will lie on the
//!    border does not touch any border-tube triangle ([`Barriers::blocks`]; 1 and 2 together
//!    are [`Barriers::refuses`], the part that does not depend on the approximation),
//! 3. it does not meet any triangle of the current approximation (the live faces of the mesh
//!    plus the triangles already placed in the same hole) anywhere other than at the vertices
//!    and edges it shares with it *by vertex id* ([`adjacent_triangles_intersect`]); sharing
//!    all three ids (a duplicate face) counts as meeting.
//!
//! Every decision is an exact predicate on the f64 input and envelope points.
//!
//! *Vertices with epsilon 0.* Candidates are built from input vertices, which lie strictly
//! between the envelopes when every epsilon is positive, so touching an envelope means
//! crossing it. A vertex with epsilon 0 lies *on* both envelopes: every candidate using it
//! touches a barrier and is rejected. That is conservative (such a vertex and the fans
//! around it are frozen) and never unsafe. Barrier contact is never excused by position.

use crate::barriers::Barriers;
use crate::grid::FaceGrid;
use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use envelope_predicates::bvh::Aabb;
use envelope_predicates::indexed_triangles_intersect;
use glam::DVec3;
use std::cell::{OnceCell, RefCell};

/// The current approximation a candidate is tested against: the live faces of the mesh
/// (indexed by a [`FaceGrid`]) plus triangles placed earlier in the same hole filling.
#[derive(Clone, Copy, Debug)]
pub struct Approximation<'a> {
    /// The mesh (positions of every vertex id; its faces are those in `grid`).
    pub mesh: &'a HalfEdgeMesh,
    /// Index of the mesh's live faces.
    pub grid: &'a FaceGrid,
    /// Triangles chosen earlier in the current filling, not yet in the mesh.
    pub placed: &'a [[VertexId; 3]],
    /// Faces of `grid` that are not part of the approximation (the fan of the vertex being
    /// removed, while its removal is only planned).
    pub excluded: &'a [FaceId],
    /// Vertices planned at other positions than the mesh's (a planned slide or collapse),
    /// each at most once. Every face of `grid` around one of them must be in `excluded` (its
    /// indexed box is stale); those that stay in the approximation are in `extra`.
    pub moved: &'a [(VertexId, DVec3)],
    /// Triangles of the approximation outside `grid` (the faces around `moved` vertices, at
    /// their planned positions), tested one by one.
    pub extra: &'a [[VertexId; 3]],
    /// The grid's faces near the candidates, gathered once (see [`Nearby`]); `None`: every
    /// query asks the grid.
    pub nearby: Option<&'a Nearby>,
}

/// The faces of a [`FaceGrid`] whose boxes overlap a region, gathered at the first query
/// that needs them and scanned by every later query whose box lies in the region, instead
/// of walking the grid's cells (the local simplifier has one per hole: all of the hole's
/// candidates have their corners there). A face that meets such a query has a box
/// overlapping the query's, hence the region's, so the answers are those of the grid. It
/// belongs to one grid in one state: the grid must not change while it is in use, and it
/// must be used with one grid (and its mesh) only.
///
/// It also remembers the candidates that met none of the gathered faces, with the
/// excluded faces and moved vertices they were asked with: the same candidate asked again
/// with the same ones skips the scan (the placed and extra triangles are still tested). The
/// local simplifier's ear test and greedy fill ask about many of the same triangles.
///
/// ```
/// use envelope_mesh::{HalfEdgeMesh, VertexId, generate};
/// use envelope_predicates::bvh::Aabb;
/// use envelope_simplify::policy::{Approximation, FaceGrid, Nearby};
/// use glam::DVec3;
/// let mesh = HalfEdgeMesh::from_soup(&generate::icosphere(1, 1.0)).unwrap();
/// let grid = FaceGrid::from_mesh(&mesh);
/// let plain = Approximation::of_mesh(&mesh, &grid);
/// let nearby = Nearby::new(Aabb::from_points(&[DVec3::splat(-2.0), DVec3::splat(2.0)]));
/// let hinted = Approximation { nearby: Some(&nearby), ..plain };
/// // A new triangle through the sphere's surface, and one inside it.
/// let ids = [VertexId(100), VertexId(101), VertexId(102)];
/// let across = [DVec3::ZERO, DVec3::new(1.5, 0.0, 0.0), DVec3::new(0.0, 1.5, 0.0)];
/// let inside = across.map(|p| p * 0.2);
/// assert!(hinted.intersects(ids, across) && plain.intersects(ids, across));
/// assert!(!hinted.intersects(ids, inside) && !plain.intersects(ids, inside));
/// ```
#[derive(Debug)]
pub struct Nearby {
    region: Aabb,
    faces: OnceCell<Vec<(Aabb, FaceId, [VertexId; 3])>>,
    clear: RefCell<Clear>,
}

/// [`Nearby`]'s memory of the candidates that met none of its faces, for the excluded faces
/// and moved vertices of the first such query (`None` until then).
#[derive(Debug, Default)]
struct Clear {
    asked_with: Option<AskedWith>,
    candidates: Vec<([VertexId; 3], [DVec3; 3])>,
}

/// The parts of an [`Approximation`] besides the grid that the scan's answer depends on.
#[derive(Debug)]
struct AskedWith {
    excluded: Vec<FaceId>,
    moved: Vec<(VertexId, DVec3)>,
}

impl Clear {
    /// Whether `a` asked of an approximation excluding `excluded` with `moved` may use and
    /// add to the memory.
    fn applies(&self, a: &Approximation<'_>) -> bool {
        self.asked_with
            .as_ref()
            .is_none_or(|w| w.excluded == a.excluded && w.moved == a.moved)
    }

    /// Whether candidate `t` (corners `p`), up to a rotation, is remembered as clear.
    fn knows(&self, t: [VertexId; 3], p: [DVec3; 3]) -> bool {
        self.candidates
            .iter()
            .any(|(u, q)| crate::barriers::same_up_to_rotation((u, q), (&t, &p)))
    }
}

impl Nearby {
    /// Nothing gathered yet, for queries in the closed box `region`.
    #[must_use]
    pub fn new(region: Aabb) -> Self {
        Self {
            region,
            faces: OnceCell::new(),
            clear: RefCell::new(Clear::default()),
        }
    }

    /// The gathered faces when `query` lies in the region (gathering them from `grid` the
    /// first time), else `None`.
    fn faces(&self, grid: &FaceGrid, query: &Aabb) -> Option<&[(Aabb, FaceId, [VertexId; 3])]> {
        if !(self.region.contains(query.min) && self.region.contains(query.max)) {
            return None;
        }
        Some(self.faces.get_or_init(|| {
            // Room for the usual few dozen: no regrowth (a hole's region holds its fan's
            // neighbourhood).
            let mut faces = Vec::with_capacity(64);
            grid.any_overlapping(&self.region, |f, g| {
                faces.push((grid.bounds(f), f, g));
                false
            });
            faces
        }))
    }
}

/// Exact: closed triangles `f` and `g` (vertex ids, positions `pf`, `pg`) meet away from
/// the corners they share by id.
pub(crate) fn meet(f: [VertexId; 3], pf: [DVec3; 3], g: [VertexId; 3], pg: [DVec3; 3]) -> bool {
    indexed_triangles_intersect(pf, f.map(|v| v.0), pg, g.map(|v| v.0))
}

impl<'a> Approximation<'a> {
    /// The live faces of `mesh` indexed by `grid`, nothing placed, excluded or moved.
    #[must_use]
    pub fn of_mesh(mesh: &'a HalfEdgeMesh, grid: &'a FaceGrid) -> Self {
        Self {
            mesh,
            grid,
            placed: &[],
            excluded: &[],
            moved: &[],
            extra: &[],
            nearby: None,
        }
    }

    /// Where `v` is in this approximation: its planned position when it is `moved`, else
    /// the mesh's.
    #[must_use]
    pub fn position(&self, v: VertexId) -> DVec3 {
        position_in(self.mesh, self.moved, v)
    }

    /// True when the candidate `t` (corners `p`) meets a live face, an extra or a placed
    /// triangle away from shared corners. Exact; conservative boxes.
    #[must_use]
    pub fn intersects(&self, t: [VertexId; 3], p: [DVec3; 3]) -> bool {
        let pos = |g: [VertexId; 3]| g.map(|v| self.position(v));
        let bounds = Aabb::from_triangle(p);
        // Boxes of exact corners: closed triangles that meet have overlapping boxes.
        let near = |q: [DVec3; 3]| Aabb::from_triangle(q).overlaps(&bounds);
        if self.placed.iter().chain(self.extra).any(|&g| {
            let q = pos(g);
            near(q) && meet(t, p, g, q)
        }) {
            return true;
        }
        let hit =
            |f: FaceId, g: [VertexId; 3]| !self.excluded.contains(&f) && meet(t, p, g, pos(g));
        let Some(nearby) = self.nearby else {
            return self.grid.any_overlapping(&bounds, hit);
        };
        let Some(faces) = nearby.faces(self.grid, &bounds) else {
            return self.grid.any_overlapping(&bounds, hit);
        };
        let remember = nearby.clear.borrow().applies(self);
        if remember && nearby.clear.borrow().knows(t, p) {
            return false;
        }
        let met = faces
            .iter()
            .any(|&(b, f, g)| b.overlaps(&bounds) && hit(f, g));
        if !met && remember {
            let mut clear = nearby.clear.borrow_mut();
            clear.asked_with.get_or_insert_with(|| AskedWith {
                excluded: self.excluded.to_vec(),
                moved: self.moved.to_vec(),
            });
            clear.candidates.push((t, p));
        }
        met
    }
}

/// `v`'s planned position in `moved`, else its position in `mesh`.
pub(crate) fn position_in(mesh: &HalfEdgeMesh, moved: &[(VertexId, DVec3)], v: VertexId) -> DVec3 {
    moved
        .iter()
        .find(|m| m.0 == v)
        .map_or_else(|| mesh.position(v), |m| m.1)
}

/// Everything a [`Filter`] may look at about one candidate triangle.
#[derive(Clone, Copy, Debug)]
pub struct CandidateProfile<'a> {
    /// The corners, oriented as the triangle would be placed.
    pub triangle: [VertexId; 3],
    /// Their positions.
    pub corners: [DVec3; 3],
    /// `border_edges[i]`: edge `triangle[i] -> triangle[i + 1]` would be a border edge.
    pub border_edges: [bool; 3],
    /// The current approximation.
    pub approximation: Approximation<'a>,
}

/// A constraint on candidate triangles: yes or no, never a score.
///
/// Contract: monotone in the approximation. While one hole is filled the mesh does not
/// change and the placed triangles only grow; a candidate rejected with some triangles placed
/// must be rejected with more placed (every validity test of 5.1 is of this kind: more
/// triangles can only block more). The hole fillers cache rejections on this basis.
pub trait Filter: Sync {
    /// Whether the candidate may be placed.
    fn accepts(&self, profile: &CandidateProfile<'_>) -> bool;

    /// A refusal that needs nothing of the approximation: true only when [`Filter::accepts`]
    /// is false for this candidate (its ids, corners and border edges) whatever
    /// `profile.approximation` is (mesh, placed, excluded and moved faces). Callers may ask
    /// it first to skip work: the ear test (module `fill`) asks it of every ear before
    /// any approximation test, so that a hole whose ears the barriers alone turn away never
    /// gathers the mesh faces around it. The default claims nothing.
    fn refuses_anyway(&self, profile: &CandidateProfile<'_>) -> bool {
        let _ = profile;
        false
    }

    /// A hint: the candidates asked about until `run` returns have their corners in the
    /// closed box `region` (the local simplifier gives each hole the box of its vertices). A
    /// filter may prepare for that once; the envelope filter gathers the barrier triangles
    /// there ([`Barriers::scoped`]). The answers must be those without the hint, also for a
    /// candidate outside `region`. By default it runs `run`.
    fn within(&self, region: &Aabb, run: &mut dyn FnMut()) {
        let _ = region;
        run();
    }

    /// [`Self::within`], with a second hint: the candidates are likely refused by what lies
    /// around the input faces `faces` (the local simplifier names those around the removed
    /// vertex); the envelope filter tests their envelope triangles first
    /// ([`Barriers::scoped_near`]). The answers must be those without the hints. By default
    /// [`Self::within`].
    fn within_near(&self, region: &Aabb, faces: &[u32], run: &mut dyn FnMut()) {
        let _ = faces;
        self.within(region, run);
    }

    /// Whether replacing the approximation's triangles `old` by the accepted triangles `new`
    /// (the same boundary) is refused as a whole although each triangle passes: the envelope
    /// filter refuses one that carries a barrier component across
    /// ([`Barriers::sweeps_across`]); the tolerance filter one that leaves part of the input
    /// farther than epsilon from the approximation. `rest` is the approximation without
    /// `old` (its `excluded` faces are `old`'s; nothing placed). `open`: a border vertex's
    /// fan, whose boundary is an open chain that `new` closes by a new border edge (the
    /// envelope filter claims nothing there). By default nothing is refused.
    fn refuses_replacement(
        &self,
        old: &[[DVec3; 3]],
        new: &[[DVec3; 3]],
        rest: &Approximation<'_>,
        open: bool,
    ) -> bool {
        let _ = (old, new, rest, open);
        false
    }

    /// Whether removing the border vertex `removed` is refused whatever the filling, for its
    /// new border edge between `ends` (ids and positions): the envelope filter refuses one
    /// that misses the ring of an input border vertex it stands for
    /// ([`Barriers::refuses_border_edge`]). By default nothing is refused.
    fn refuses_border_edge(&self, removed: VertexId, ends: [(VertexId, DVec3); 2]) -> bool {
        let _ = (removed, ends);
        false
    }
}

/// Accepts everything; the default base of [`EnvelopeFilter`].
#[derive(Clone, Copy, Debug, Default)]
pub struct NoFilter;

impl Filter for NoFilter {
    fn accepts(&self, _: &CandidateProfile<'_>) -> bool {
        true
    }
}

impl<F: Fn(&CandidateProfile<'_>) -> bool + Sync> Filter for F {
    fn accepts(&self, profile: &CandidateProfile<'_>) -> bool {
        self(profile)
    }
}

/// The validity test of section 5.1 (see the module docs), after a `base` filter (run
/// first, so a cheap user constraint saves the geometric tests).
#[derive(Clone, Copy, Debug)]
pub struct EnvelopeFilter<'b, F = NoFilter> {
    barriers: &'b Barriers,
    base: F,
}

impl<'b> EnvelopeFilter<'b> {
    /// The paper's test against `barriers`.
    #[must_use]
    pub fn new(barriers: &'b Barriers) -> Self {
        Self {
            barriers,
            base: NoFilter,
        }
    }
}

impl<'b, F: Filter> EnvelopeFilter<'b, F> {
    /// The paper's test, after `base`.
    #[must_use]
    pub fn with_base(barriers: &'b Barriers, base: F) -> Self {
        Self { barriers, base }
    }

    /// The barriers this filter tests against.
    #[must_use]
    pub fn barriers(&self) -> &'b Barriers {
        self.barriers
    }
}

impl<F: Filter> Filter for EnvelopeFilter<'_, F> {
    fn accepts(&self, p: &CandidateProfile<'_>) -> bool {
        self.base.accepts(p)
            && !self.barriers.refuses(p.corners, p.border_edges)
            && !p.approximation.intersects(p.triangle, p.corners)
    }

    /// The base's own such refusal, or the barriers' (which see only the corners and the
    /// border edges).
    fn refuses_anyway(&self, p: &CandidateProfile<'_>) -> bool {
        self.base.refuses_anyway(p) || self.barriers.refuses(p.corners, p.border_edges)
    }

    fn within(&self, region: &Aabb, run: &mut dyn FnMut()) {
        self.barriers
            .scoped(region, || self.base.within(region, run));
    }

    fn within_near(&self, region: &Aabb, faces: &[u32], run: &mut dyn FnMut()) {
        self.barriers.scoped_near(region, faces, || {
            self.base.within_near(region, faces, run);
        });
    }

    fn refuses_replacement(
        &self,
        old: &[[DVec3; 3]],
        new: &[[DVec3; 3]],
        rest: &Approximation<'_>,
        open: bool,
    ) -> bool {
        // An open chain's filling has no closed boundary to carry a component across.
        self.base.refuses_replacement(old, new, rest, open)
            || (!open && self.barriers.sweeps_across(old, new))
    }

    fn refuses_border_edge(&self, removed: VertexId, ends: [(VertexId, DVec3); 2]) -> bool {
        self.base.refuses_border_edge(removed, ends)
            || self.barriers.refuses_border_edge(removed, ends)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        (-12i32..=12).prop_map(|k| f64::from(k) / 8.0)
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (coord(), coord(), coord()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// `intersects` with a [`Nearby`] answers what the grid answers, whatever the region
        /// (holding the query, missing it, across it), for candidates with corners at mesh
        /// vertices (shared ids: the adjacency-aware test) or elsewhere, with and without
        /// excluded faces, and one `Nearby` reused by several queries.
        #[test]
        fn nearby_gives_the_grids_answers(
            region in [point(), point()],
            queries in prop::collection::vec(
                prop::array::uniform3((0u32..60, point())), 1..10),
            excluded in prop::collection::vec(0u32..80, 0..6),
        ) {
            let soup = generate::icosphere(1, 1.0);
            let mesh = HalfEdgeMesh::from_soup(&soup).unwrap();
            let grid = FaceGrid::from_mesh(&mesh);
            let excluded: Vec<FaceId> = excluded.into_iter().map(FaceId).collect();
            let plain = Approximation { excluded: &excluded, ..Approximation::of_mesh(&mesh, &grid) };
            let nearby = Nearby::new(Aabb::from_points(&region));
            let hinted = Approximation { nearby: Some(&nearby), ..plain };
            // The same `Nearby` asked with nothing excluded: what it remembers as clear with
            // `excluded` must not answer for it.
            let everything = Approximation { excluded: &[], ..Approximation::of_mesh(&mesh, &grid) };
            let hinted_everything = Approximation { nearby: Some(&nearby), ..everything };
            for q in queries {
                // Ids below the mesh's 42 vertices are corners at those vertices; the others
                // are new vertices at the drawn points.
                let ids = q.map(|(k, _)| if k < 42 { VertexId(k) } else { VertexId(1000 + k) });
                if ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2] {
                    continue;
                }
                let corners = [0, 1, 2].map(|i| {
                    if ids[i].index() < 42 { mesh.position(ids[i]) } else { q[i].1 }
                });
                // Twice each (the second may come from the memory), rotated, then with
                // nothing excluded.
                let rotated = ([ids[1], ids[2], ids[0]], [corners[1], corners[2], corners[0]]);
                for (a, b, (ids, corners)) in [
                    (hinted, plain, (ids, corners)),
                    (hinted, plain, (ids, corners)),
                    (hinted, plain, rotated),
                    (hinted_everything, everything, (ids, corners)),
                ] {
                    prop_assert_eq!(
                        a.intersects(ids, corners),
                        b.intersects(ids, corners),
                        "{:?} {:?}", ids, corners
                    );
                }
                // Clear once every face it meets is excluded; not with none excluded.
                let meets: Vec<FaceId> = mesh
                    .faces()
                    .filter(|&f| {
                        let g = mesh.face_vertices(f);
                        meet(ids, corners, g, g.map(|v| mesh.position(v)))
                    })
                    .collect();
                let fresh = Nearby::new(Aabb::from_points(&region));
                let clear = Approximation { excluded: &meets, nearby: Some(&fresh), ..everything };
                let full = Approximation { nearby: Some(&fresh), ..everything };
                prop_assert!(!clear.intersects(ids, corners));
                prop_assert_eq!(full.intersects(ids, corners), !meets.is_empty());
            }
        }
    }
}
