//! Planning a removal (read-only: the checks, the hole, the fiber test, the filling) and
//! applying it ([`LocalSimplifier`]).

use super::MAX_HOLE;
use crate::fiber::FiberTest;
use crate::fill::{FillContext, Hole, HoleFiller};
use crate::filter::{Approximation, CandidateProfile, Filter, Nearby, position_in};
use crate::grid::FaceGrid;
use crate::rules::Rejection;
use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use envelope_predicates::bvh::Aabb;
use glam::DVec3;

/// A successful vertex removal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Removal {
    /// The hole the vertex left.
    pub hole: Hole,
    /// The faces that fill it.
    pub faces: Vec<FaceId>,
}

/// A mesh being simplified by vertex removal, with the spatial index of its live faces.
#[derive(Debug)]
pub struct LocalSimplifier<'m> {
    pub(super) mesh: &'m mut HalfEdgeMesh,
    pub(super) grid: FaceGrid,
    pub(super) keep_border: bool,
    /// Vertices never removed nor moved, by id (empty: none).
    pub(super) keep: &'m [bool],
    /// Asked before every plain removal's filling ([`Policies::fiber_test`]).
    pub(super) fiber_test: Option<&'m FiberTest<'m>>,
    /// Candidate triangles given to the filter so far.
    pub candidate_tests: u64,
}

impl<'m> LocalSimplifier<'m> {
    /// Indexes the faces of `mesh`. With `keep_border`, border vertices are never removed.
    pub fn new(mesh: &'m mut HalfEdgeMesh, keep_border: bool) -> Self {
        let grid = FaceGrid::from_mesh(mesh);
        Self {
            grid,
            ..Self::without_grid(mesh, keep_border)
        }
    }

    /// Vertices never to remove nor move, by id (vertices beyond the slice are free).
    #[must_use]
    pub fn with_keep(mut self, keep: &'m [bool]) -> Self {
        self.keep = keep;
        self
    }

    /// Whether `v` is never to be removed nor moved ([`Self::with_keep`]).
    pub(super) fn keeps(&self, v: VertexId) -> bool {
        self.keep.get(v.index()).copied().unwrap_or(false)
    }

    /// [`Self::new`] with an empty face index, for plans that read none (the fiber test's
    /// verdicts, see [`Doomed`]) while the index is built; the caller sets `grid` before
    /// anything else.
    pub(super) fn without_grid(mesh: &'m mut HalfEdgeMesh, keep_border: bool) -> Self {
        Self {
            mesh,
            grid: FaceGrid::empty(),
            keep_border,
            keep: &[],
            fiber_test: None,
            candidate_tests: 0,
        }
    }

    /// The same simplifier with the fiber test before every plain removal's filling:
    /// `test`'s envelopes must be barriers of the filters it is given and apart from every
    /// face of the mesh (see [`FiberTest`]).
    #[must_use]
    pub fn with_fiber_test(mut self, test: Option<&'m FiberTest<'m>>) -> Self {
        self.fiber_test = test;
        self
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> &HalfEdgeMesh {
        self.mesh
    }

    /// The index of the live faces.
    #[must_use]
    pub fn grid(&self) -> &FaceGrid {
        &self.grid
    }

    /// The mesh's and the grid's sanity checks.
    pub fn sanity_check(&self) -> Result<(), String> {
        self.mesh.sanity_check()?;
        self.grid.sanity_check(self.mesh)
    }

    /// Tries to remove `v` (section 5.2): removes its fan, fills the hole with `filler`
    /// (every candidate through `filter`), and keeps the result, or restores the fan exactly.
    pub fn try_remove_vertex(
        &mut self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> Result<Removal, Rejection> {
        let (plan, tests) = self.plan(v, filter, filler);
        self.candidate_tests += tests;
        self.apply(v, plan?)
    }

    /// Sets vertex positions and re-indexes the `affected` faces (every live face around a
    /// moved vertex).
    fn move_vertices(
        &mut self,
        affected: &[FaceId],
        moves: impl Iterator<Item = (VertexId, DVec3)>,
    ) {
        for &f in affected {
            self.grid.remove(f);
        }
        for (u, q) in moves {
            self.mesh.set_position(u, q);
        }
        for &f in affected {
            let t = self.mesh.face_vertices(f);
            self.grid.insert(f, t, t.map(|x| self.mesh.position(x)));
        }
    }

    /// Everything [`Self::try_remove_vertex`] decides, without editing anything: the checks,
    /// the hole (as `remove_vertex_fan` would leave it) and its filling, with the fan
    /// excluded from the approximation instead of removed. Shared access only, so plans of
    /// removals whose neighbourhoods are apart can be made in parallel. Also returns the
    /// number of candidates given to the filter.
    pub(super) fn plan(
        &self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> (Result<Plan, Rejection>, u64) {
        self.plan_moved(v, Vec::new(), filter, filler)
    }

    /// [`Self::plan`] without the fiber test: the same outcome, but for the reason of a
    /// rejection ([`Rejection::NoValidFill`] where the test would have said
    /// [`Rejection::NoFillAcrossFiber`]).
    pub(super) fn plan_without_fiber_test(
        &self,
        v: VertexId,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> (Result<Plan, Rejection>, u64) {
        let mut tests = 0;
        let plan = self.plan_counted(v, Vec::new(), filter, filler, false, &mut tests);
        (plan, tests)
    }

    /// [`Self::plan`] with vertices at planned positions (`moves`, each vertex once): the
    /// faces around them are taken out of the grid's view and tested at their planned
    /// positions (the filling against them, then each of them that stays against the
    /// approximation with the filling in it).
    pub(super) fn plan_moved(
        &self,
        v: VertexId,
        moves: Vec<(VertexId, DVec3)>,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
    ) -> (Result<Plan, Rejection>, u64) {
        let mut tests = 0;
        let plan = self.plan_counted(v, moves, filter, filler, true, &mut tests);
        (plan, tests)
    }

    fn plan_counted(
        &self,
        v: VertexId,
        moves: Vec<(VertexId, DVec3)>,
        filter: &dyn Filter,
        filler: &dyn HoleFiller,
        fiber: bool,
        tests: &mut u64,
    ) -> Result<Plan, Rejection> {
        let m = &*self.mesh;
        if !m.contains_vertex(v) || m.is_isolated(v) {
            return Err(Rejection::NotAVertex);
        }
        if self.keeps(v) {
            return Err(Rejection::Kept);
        }
        let border = m.is_border_vertex(v);
        if border && self.keep_border {
            return Err(Rejection::BorderWithoutTubes);
        }
        if !m.is_manifold_vertex(v) {
            return Err(Rejection::NonManifold);
        }
        // The outgoing half-edges once: the fan (`vertex_faces` order) and the ring.
        let mut hs = Vec::with_capacity(8);
        hs.extend(m.outgoing_halfedges(v));
        let mut fan: Vec<FaceId> = Vec::with_capacity(hs.len());
        fan.extend(hs.iter().filter_map(|&h| m.face(h)));
        if border && fan.len() < 2 {
            return Err(Rejection::Ear);
        }
        if hs.len() > MAX_HOLE {
            return Err(Rejection::HoleTooLarge);
        }
        // The ring as `remove_vertex_fan` returns it: counter-clockwise from the outgoing
        // half-edge, starting after the border gap at a border vertex.
        let mut vertices: Vec<VertexId> = hs.iter().map(|&h| m.target(h)).collect();
        if hs.first().is_some_and(|&h| m.is_border_halfedge(h)) {
            vertices.rotate_left(1);
        }
        let hole = Hole {
            vertices,
            open: border,
        };
        // At most `MAX_HOLE` vertices: pairwise, without sorting a copy.
        let ring = &hole.vertices;
        if (1..ring.len()).any(|i| ring[..i].contains(&ring[i])) {
            return Err(Rejection::RepeatedNeighbour);
        }
        // The new border edge joins the chain's ends, whatever the filling (border vertices
        // never move).
        if border {
            let ends = [ring[0], ring[ring.len() - 1]].map(|u| (u, m.position(u)));
            if filter.refuses_border_edge(v, ends) {
                return Err(Rejection::BorderNotCovered);
            }
        }
        // Faces around a moved vertex: stale in the grid; those outside the fan stay, at
        // their planned positions (none move in the subset run: the fan alone is excluded).
        let mut moved_around = Vec::new();
        let mut stay = Vec::new();
        if !moves.is_empty() {
            moved_around.clone_from(&fan);
            for &(u, _) in &moves {
                for f in m.vertex_faces(u) {
                    if !moved_around.contains(&f) {
                        moved_around.push(f);
                        stay.push(m.face_vertices(f));
                    }
                }
            }
        }
        let excluded: &[FaceId] = if moves.is_empty() {
            &fan
        } else {
            &moved_around
        };
        // Every candidate of the filling has its corners among the hole's vertices.
        let corners: Vec<DVec3> = hole
            .vertices
            .iter()
            .map(|&u| position_in(m, &moves, u))
            .collect();
        let region = Aabb::from_points(&corners);
        // The fiber test (module `fiber`): interior vertices at their current positions.
        let path = match self.fiber_test {
            Some(test) if fiber && moves.is_empty() && !border => {
                test.path(v, m.position(v), &corners)
            }
            _ => None,
        };
        let nearby = Nearby::new(region);
        let mut ctx = FillContext::new(m, &self.grid, filter, &hole)
            .excluding(excluded)
            .moving(&moves, &stay)
            .near(&nearby);
        let (mut filled, mut across) = (false, true);
        // The input faces around `v`: their envelope triangles refuse most of the fiber
        // test's candidates (tested first; only the order of the tests changes).
        let near = match (&path, self.fiber_test) {
            (Some(_), Some(test)) => test.faces_around(v),
            _ => &[],
        };
        filter.within_near(&region, near, &mut || {
            if let Some(path) = &path {
                if !ctx.a_triangle_across_may_pass(path, &corners) {
                    let fan: Vec<[DVec3; 3]> = fan
                        .iter()
                        .map(|&f| m.face_vertices(f).map(|x| m.position(x)))
                        .collect();
                    across = !path.crosses_once(fan);
                    if !across {
                        return;
                    }
                }
            }
            filled = filler.fill(&mut ctx);
        });
        *tests = ctx.tests;
        if !across {
            return Err(Rejection::NoFillAcrossFiber);
        }
        let placed = ctx.placed().to_vec();
        if !filled {
            return Err(Rejection::NoValidFill);
        }
        debug_assert_eq!(placed.len() + 2, hole.len());
        for (k, &t) in stay.iter().enumerate() {
            let others: Vec<[VertexId; 3]> = stay
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != k)
                .map(|(_, &g)| g)
                .collect();
            let approximation = Approximation {
                mesh: m,
                grid: &self.grid,
                placed: &placed,
                excluded,
                moved: &moves,
                extra: &others,
                nearby: None,
            };
            let profile = CandidateProfile {
                triangle: t,
                corners: t.map(|x| approximation.position(x)),
                // The edges of a moved vertex are interior; the third edge did not move.
                border_edges: [false; 3],
                approximation,
            };
            *tests += 1;
            if !filter.accepts(&profile) {
                return Err(Rejection::NoValidFill);
            }
        }
        // The replacement as a whole (the filling and the moved stars): no barrier
        // component carried across, the input still covered (the filter's to say).
        {
            let at = |t: [VertexId; 3], moved: bool| {
                t.map(|x| {
                    if moved {
                        position_in(m, &moves, x)
                    } else {
                        m.position(x)
                    }
                })
            };
            let old: Vec<[DVec3; 3]> = fan
                .iter()
                .map(|&f| at(m.face_vertices(f), false))
                .chain(stay.iter().map(|&t| at(t, false)))
                .collect();
            let new: Vec<[DVec3; 3]> = placed.iter().chain(&stay).map(|&t| at(t, true)).collect();
            let rest = Approximation {
                excluded,
                moved: &moves,
                ..Approximation::of_mesh(m, &self.grid)
            };
            *tests += 1;
            if filter.refuses_replacement(&old, &new, &rest, border) {
                return Err(Rejection::NoValidFill);
            }
        }
        Ok(Plan {
            hole,
            fan,
            placed,
            moves,
        })
    }

    /// Carries out a plan made by [`Self::plan`] on the mesh as it was then: moves its
    /// vertices, removes the fan, adds the filling (the mesh's `add_faces` is the last
    /// guard), updates the grid; on a refusal everything comes back exactly.
    pub(super) fn apply(&mut self, v: VertexId, plan: Plan) -> Result<Removal, Rejection> {
        let mut affected: Vec<FaceId> = plan
            .moves
            .iter()
            .flat_map(|&(u, _)| self.mesh.vertex_faces(u))
            .collect();
        affected.sort_unstable();
        affected.dedup();
        let back: Vec<(VertexId, DVec3)> = plan
            .moves
            .iter()
            .map(|&(u, _)| (u, self.mesh.position(u)))
            .collect();
        self.move_vertices(&affected, plan.moves.iter().copied());
        let cp = self.mesh.begin();
        let refused = match self.mesh.remove_vertex_fan(v) {
            Ok(ring) => {
                debug_assert_eq!(ring, plan.hole.vertices);
                self.mesh
                    .add_faces(&plan.placed)
                    .map_err(Rejection::MeshRefused)
            }
            Err(_) => Err(Rejection::NonManifold),
        };
        let faces = match refused {
            Ok(faces) => faces,
            Err(reason) => {
                self.mesh.rollback(cp);
                self.move_vertices(&affected, back.into_iter());
                return Err(reason);
            }
        };
        self.mesh
            .remove_vertex(v)
            .expect("the removed vertex is isolated");
        self.mesh.commit(cp);
        for &f in &plan.fan {
            self.grid.remove(f);
        }
        for &f in &faces {
            let t = self.mesh.face_vertices(f);
            self.grid.insert(f, t, t.map(|x| self.mesh.position(x)));
        }
        self.grid.rebalance();
        Ok(Removal {
            hole: plan.hole,
            faces,
        })
    }
}

/// Every coordinate of `p` in the exact predicates' range (a cancellation can leave one
/// below it).
pub(super) fn in_range(p: DVec3) -> bool {
    p.to_array()
        .into_iter()
        .all(|x| envelope_mesh::check_coordinate(x).is_ok())
}

/// A planned removal ([`LocalSimplifier::plan`]).
pub(super) struct Plan {
    pub(super) hole: Hole,
    pub(super) fan: Vec<FaceId>,
    pub(super) placed: Vec<[VertexId; 3]>,
    /// Vertices to move first (a slide or a collapse), each once.
    pub(super) moves: Vec<(VertexId, DVec3)>,
}
