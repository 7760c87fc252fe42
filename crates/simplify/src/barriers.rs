//! [`Barriers`]: the surfaces a candidate triangle must not touch (section 5.1) and the border
//! tubes a new border edge must not touch (section 6.2), as plain triangle data with one
//! static BVH over all of them.

use envelope_mesh::{CoordError, FaceId, TriangleSoup, VertexId, check_coordinate};
use envelope_predicates::bvh::{Aabb, Bvh, NodeKind};
use envelope_predicates::{
    SegmentTriangle, indexed_triangles_intersect, polyline_crossings, segment_triangle,
    triangles_intersect,
};
use glam::DVec3;
use rayon::prelude::*;
use std::cell::{Cell, RefCell};
use std::sync::atomic::{AtomicU64, Ordering};
use thiserror::Error;

use crate::border_cover::BorderCover;

/// How many recent blockers each thread tries before anything else (see [`Barriers::blocks`]).
const RECENT: usize = 8;

thread_local! {
    /// See [`Barriers::blocks`]: indices of the barrier triangles that blocked this thread's
    /// latest queries, most recent first, into whichever `Barriers` the thread queried (a
    /// stale or foreign index is checked against the length and only costs one test).
    static RECENT_BLOCKERS: Cell<[u32; RECENT]> = const { Cell::new([u32::MAX; RECENT]) };
    /// See [`Barriers::scoped`]: this thread's current scope, if any.
    static SCOPE: RefCell<Scope> = RefCell::new(Scope::default());
}

/// Distinct ids for [`Barriers`] values (a clone keeps its id: it holds the same triangles).
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// A thread's scope: `active` is the id of the `Barriers` it is for and the region (`None`:
/// no scope); `items` the triangles whose boxes overlap the region, gathered at the first
/// query that needs them (`gathered`); `passed` the queries in the region that nothing
/// blocked, to answer them again without a scan.
#[derive(Debug, Default)]
struct Scope {
    active: Option<(u64, Aabb)>,
    gathered: bool,
    items: Vec<Gathered>,
    passed: Vec<Query>,
    /// Triangles to test before gathering ([`Barriers::scoped_near`]): likely blockers.
    hints: Vec<u32>,
}

impl Scope {
    /// The region, when the scope is for barriers `id` and the closed box `query` lies in it.
    fn region_for(&self, id: u64, query: &Aabb) -> Option<Aabb> {
        let (owner, region) = self.active?;
        (owner == id && region.contains(query.min) && region.contains(query.max)).then_some(region)
    }
}

/// A question asked of [`Barriers::blocks`]: the candidate's corners and which of its edges
/// are border edges.
#[derive(Clone, Copy, Debug)]
struct Query {
    corners: [DVec3; 3],
    border_edges: [bool; 3],
}

impl Query {
    /// The same question, up to a rotation of the corners (which carries the border edges
    /// along): the answer is a function of the closed triangle and of its border segments.
    fn is(&self, t: [DVec3; 3], border_edges: [bool; 3]) -> bool {
        same_up_to_rotation((&self.corners, &self.border_edges), (&t, &border_edges))
    }
}

/// A barrier triangle gathered by a scope: its box, corners and kind copied next to each
/// other, so a scan reads one short contiguous list instead of four long arrays at random.
#[derive(Clone, Copy, Debug)]
struct Gathered {
    bounds: Aabb,
    corners: [DVec3; 3],
    index: u32,
    kind: BarrierKind,
}

/// What a barrier triangle constrains.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BarrierKind {
    /// An envelope surface (outer or inner, section 4): no candidate triangle may touch it.
    Envelope,
    /// A border tube (section 6.2): no new *border edge* may touch it. Tubes are not tested
    /// against whole triangles: the surface near a border leaves the tube through its wall.
    Tube,
    /// A border wall (`border_walls`, module `walls`): joins the outer and inner envelopes along a
    /// border, and like them no candidate triangle may touch it.
    Wall,
}

/// Why [`Barriers::new`] refused its input. Names the surface (index in the argument order:
/// envelopes first, then tubes) and the element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
pub enum BarrierError {
    /// A face names a vertex the soup does not have.
    #[error("barrier surface {surface}: face {face} names a vertex out of range")]
    IndexOutOfRange {
        /// The surface.
        surface: usize,
        /// The face.
        face: usize,
    },
    /// The tree given for the envelopes ([`Barriers::with_tree`]) is not one over their
    /// faces.
    #[error("the tree given is not one over the envelopes' faces")]
    TreeMismatch,
    /// A coordinate the exact predicates cannot take.
    #[error("barrier surface {surface}: vertex {vertex}: {error}")]
    Coordinate {
        /// The surface.
        surface: usize,
        /// The vertex.
        vertex: usize,
        /// What is wrong with it.
        error: CoordError,
    },
}

/// The envelopes and border tubes, flattened into one triangle list with one BVH.
///
/// The triangles are the f64 points the envelope builder constructed; every test against
/// them is exact (closed triangles: touching counts as intersecting).
///
/// ```
/// use envelope_mesh::generate;
/// use envelope_simplify::policy::Barriers;
/// let b = Barriers::new(vec![generate::icosphere(1, 1.1), generate::icosphere(1, 0.9)], vec![]).unwrap();
/// assert_eq!(b.num_triangles(), 160);
/// assert!(!b.has_tubes());
/// ```
#[derive(Clone, Debug, Default)]
pub struct Barriers {
    /// The triangles' corners in `points`, in the leaf order of `bvh` (whose leaf boxes,
    /// [`Bvh::leaf_boxes`], are their boxes, checked before any plane test).
    corners: Vec<[u32; 3]>,
    /// The surfaces' points, numbered in order of first use along `corners` (near each
    /// other in memory where the triangles are): 12 bytes a triangle and 24 a point instead
    /// of 72 bytes a triangle.
    points: Vec<DVec3>,
    kinds: Vec<BarrierKind>,
    /// The largest coordinate magnitude of any barrier triangle (the bound a barrier
    /// triangle's own [`PointSlab`] is widened for; see [`SlabFilter::new`]).
    magnitude: f64,
    /// Per envelope triangle, a bit per corner that is a pin ([`Barriers::with_pins`]).
    pinned: Vec<u8>,
    bvh: Option<Bvh>,
    /// Storage index of each triangle by its number in the order given (envelopes, tubes,
    /// walls, each face by face).
    position: Vec<u32>,
    /// Per envelope surface, the number (in the order given) of its first face, and its
    /// face count.
    envelope_faces: Vec<(u32, u32)>,
    has_tubes: bool,
    /// Input vertices no step may remove or move ([`Barriers::with_kept`]), by vertex id.
    kept: Vec<bool>,
    /// The tubes' rings ([`Barriers::with_border_cover`]).
    cover: Option<BorderCover>,
    /// Per connected component of every surface: its box and one of its vertices
    /// ([`Barriers::sweeps_across`]).
    components: Vec<(Aabb, DVec3)>,
    /// A tree over the boxes of `components`.
    component_tree: Option<Bvh>,
    /// This value's id for [`Barriers::scoped`] (0 for [`Barriers::none`], which has nothing
    /// to gather).
    id: u64,
}

impl Barriers {
    /// No barrier at all: only the self-intersection part of the validity test remains.
    #[must_use]
    pub fn none() -> Self {
        Self::default()
    }

    /// Envelope surfaces (outer, inner; any number) and border tubes. Validates indices and
    /// coordinates (the exact-predicate range).
    pub fn new(
        envelopes: Vec<TriangleSoup>,
        tubes: Vec<TriangleSoup>,
    ) -> Result<Self, BarrierError> {
        Self::with_walls(envelopes, tubes, Vec::new())
    }

    /// Like [`Barriers::new`], plus border walls ([`BarrierKind::Wall`], full barriers).
    /// Surfaces are numbered envelopes first, then tubes, then walls.
    pub fn with_walls(
        envelopes: Vec<TriangleSoup>,
        tubes: Vec<TriangleSoup>,
        walls: Vec<TriangleSoup>,
    ) -> Result<Self, BarrierError> {
        Self::build(envelopes, None, tubes, walls)
    }

    /// Like [`Barriers::with_walls`], with a tree over the envelopes' faces (item = face
    /// number counted over the envelopes in the order given; `envelope-offset`'s
    /// `Envelopes::tree`, the one its proof searched), so that only the tubes and walls need
    /// one of their own. The same barriers, answering every question the same (the tree only
    /// decides where to look, and the storage order: the tree's leaf order).
    ///
    /// # Errors
    /// Those of [`Barriers::new`], and [`BarrierError::TreeMismatch`] when the tree is not
    /// one over the envelopes' faces (another number of items, or other boxes).
    ///
    /// ```
    /// use envelope_mesh::generate;
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use envelope_simplify::policy::Barriers;
    /// use glam::DVec3;
    /// let (outer, inner) = (generate::icosphere(1, 1.1), generate::icosphere(1, 0.9));
    /// let boxes: Vec<Aabb> = [&outer, &inner]
    ///     .iter()
    ///     .flat_map(|s| s.face_ids().map(|f| Aabb::from_triangle(s.triangle(f))))
    ///     .collect();
    /// let b = Barriers::with_tree(vec![outer, inner], Bvh::new(&boxes), vec![], vec![]).unwrap();
    /// assert!(b.blocks([DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0)], [false; 3]));
    /// ```
    pub fn with_tree(
        envelopes: Vec<TriangleSoup>,
        tree: Bvh,
        tubes: Vec<TriangleSoup>,
        walls: Vec<TriangleSoup>,
    ) -> Result<Self, BarrierError> {
        Self::build(envelopes, Some(tree), tubes, walls)
    }

    fn build(
        envelopes: Vec<TriangleSoup>,
        tree: Option<Bvh>,
        tubes: Vec<TriangleSoup>,
        walls: Vec<TriangleSoup>,
    ) -> Result<Self, BarrierError> {
        let has_tubes = tubes.iter().any(|t| t.num_faces() > 0);
        let surfaces: Vec<(&TriangleSoup, BarrierKind)> = envelopes
            .iter()
            .map(|s| (s, BarrierKind::Envelope))
            .chain(tubes.iter().map(|s| (s, BarrierKind::Tube)))
            .chain(walls.iter().map(|s| (s, BarrierKind::Wall)))
            .collect();
        for (surface, &(soup, _)) in surfaces.iter().enumerate() {
            for (vertex, p) in soup.positions.iter().enumerate() {
                for x in p.to_array() {
                    check_coordinate(x).map_err(|error| BarrierError::Coordinate {
                        surface,
                        vertex,
                        error,
                    })?;
                }
            }
            if !soup.indices_in_range() {
                let face = soup
                    .faces
                    .iter()
                    .position(|f| f.iter().any(|v| v.index() >= soup.num_vertices()))
                    .unwrap_or(0);
                return Err(BarrierError::IndexOutOfRange { surface, face });
            }
        }
        // Triangle `g` (numbered over the surfaces in the order given, face by face) is face
        // `g - firsts[s]` of the last surface `s` with `firsts[s] <= g`.
        let firsts: Vec<u32> = surfaces
            .iter()
            .scan(0u32, |next, (soup, _)| {
                let first = *next;
                *next += soup.num_faces() as u32;
                Some(first)
            })
            .collect();
        let count = surfaces
            .iter()
            .map(|(soup, _)| soup.num_faces())
            .sum::<usize>() as u32;
        let triangle = |g: u32| {
            let s = firsts.partition_point(|&f| f <= g) - 1;
            let (soup, kind) = surfaces[s];
            (
                soup.triangle(FaceId::from_index((g - firsts[s]) as usize)),
                kind,
            )
        };
        let box_of = |g: u32| Aabb::from_triangle(triangle(g).0);
        let envelope_faces: Vec<(u32, u32)> = envelopes
            .iter()
            .zip(&firsts)
            .map(|(e, &first)| (first, e.num_faces() as u32))
            .collect();
        let tree = match tree {
            _ if count == 0 => None,
            None => {
                let boxes: Vec<Aabb> = (0..count).into_par_iter().map(box_of).collect();
                Some(Bvh::new(&boxes))
            }
            Some(tree) => Some(joined_tree(&envelopes, tree, count, box_of)?),
        };
        // Stored in the leaf order of the tree, so that the triangles a query visits lie
        // near each other in memory (ids are this order's); each triangle's box is the
        // tree's own copy of it.
        let (bvh, corners, points, kinds, position) = match tree {
            None => (None, Vec::new(), Vec::new(), Vec::new(), Vec::new()),
            Some(tree) => {
                let (bvh, old) = tree.into_leaf_order();
                let mut position = vec![0u32; old.len()];
                for (new, &o) in (0u32..).zip(&old) {
                    position[o as usize] = new;
                }
                // Point `v` of surface `s` is `vfirsts[s] + v` before renumbering.
                let vfirsts: Vec<usize> = surfaces
                    .iter()
                    .scan(0, |next, (soup, _)| {
                        let first = *next;
                        *next += soup.num_vertices();
                        Some(first)
                    })
                    .collect();
                let total = surfaces.iter().map(|(soup, _)| soup.num_vertices()).sum();
                let mut number = vec![u32::MAX; total];
                let mut points = Vec::new();
                let mut corners = Vec::with_capacity(old.len());
                let mut kinds = Vec::with_capacity(old.len());
                for &g in &old {
                    let s = firsts.partition_point(|&f| f <= g) - 1;
                    let (soup, kind) = surfaces[s];
                    let face = soup.faces[(g - firsts[s]) as usize];
                    corners.push(face.map(|v| {
                        let k = vfirsts[s] + v.index();
                        if number[k] == u32::MAX {
                            number[k] = points.len() as u32;
                            points.push(soup.positions[v.index()]);
                        }
                        number[k]
                    }));
                    kinds.push(kind);
                }
                (Some(bvh), corners, points, kinds, position)
            }
        };
        let magnitude = points
            .par_iter()
            .map(|p| p.abs().max_element())
            .reduce(|| 0.0, f64::max);
        let pinned = vec![0; corners.len()];
        let components: Vec<(Aabb, DVec3)> = surfaces
            .iter()
            .flat_map(|(soup, _)| surface_components(soup))
            .collect();
        let component_tree = (!components.is_empty()).then(|| {
            let boxes: Vec<Aabb> = components.iter().map(|c| c.0).collect();
            Bvh::new(&boxes)
        });
        Ok(Self {
            corners,
            points,
            kinds,
            magnitude,
            pinned,
            bvh,
            position,
            envelope_faces,
            has_tubes,
            kept: Vec::new(),
            cover: None,
            components,
            component_tree,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        })
    }

    /// Whether replacing the triangles `old` of the approximation by `new` (the same
    /// boundary: a vertex's fan by the filling of its hole, stars before and after a move)
    /// would carry a whole barrier component across, so the approximation would no longer
    /// lie between the envelopes as the input does although no triangle meets a barrier.
    /// This happens at large epsilons, where an inner envelope shrinks to a small closed
    /// surface that one hole's filling can pass over without touching it.
    ///
    /// The test: `C = old - new` is a closed surface (a 2-cycle) inside the box `B` of its
    /// corners; both parts are apart from every barrier (the mesh's faces and each accepted
    /// triangle are), so the winding number of `C` is constant on each barrier component,
    /// and zero on one with a vertex outside `B`. For each component inside `B` it is
    /// counted exactly at one of its vertices along a segment leaving `B`
    /// ([`polyline_crossings`]); it must be zero. A count that no segment decides is taken
    /// as a sweep, and `old`/`new` whose boundaries differ (an open hole at a border) claim
    /// nothing: the test can only refuse.
    ///
    /// ```
    /// use envelope_mesh::generate;
    /// use envelope_simplify::policy::Barriers;
    /// use glam::DVec3;
    /// let inner = generate::icosphere(1, 0.1);
    /// let b = Barriers::new(vec![inner], vec![]).unwrap();
    /// let (a, c, d) = (DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0), DVec3::new(0.0, 1.0, 0.0));
    /// let (up, down) = (DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 0.0, -1.0));
    /// let above = [[a, c, up], [c, d, up], [d, a, up]];
    /// let below = [[a, c, down], [c, d, down], [d, a, down]];
    /// // The tent over the small sphere replaced by the tent under it: swept across.
    /// assert!(b.sweeps_across(&above, &below));
    /// assert!(!b.sweeps_across(&above, &above));
    /// ```
    #[must_use]
    pub fn sweeps_across(&self, old: &[[DVec3; 3]], new: &[[DVec3; 3]]) -> bool {
        let Some(tree) = &self.component_tree else {
            return false;
        };
        let corners: Vec<DVec3> = old.iter().chain(new).flatten().copied().collect();
        if corners.is_empty() {
            return false;
        }
        let region = Aabb::from_points(&corners);
        let mut inside = Vec::new();
        tree.for_each_overlapping(&region, |c| {
            let (b, _) = self.components[c as usize];
            if region.contains(b.min) && region.contains(b.max) {
                inside.push(c);
            }
        });
        if inside.is_empty() || !same_boundary(old, new) {
            return false;
        }
        // `old - new`: the new triangles reversed.
        let cycle: Vec<[DVec3; 3]> = old
            .iter()
            .copied()
            .chain(new.iter().map(|&[a, b, c]| [a, c, b]))
            .collect();
        inside
            .into_iter()
            .any(|c| winding_not_zero(self.components[c as usize].1, &region, &cycle))
    }

    /// Declares pin points: input vertices where the envelopes were pinched to the input
    /// (`envelope-offset`'s `Envelopes::pinned`, a vertex with no valid normal). An envelope
    /// triangle with a corner at a pin (the same f64 point) no longer blocks a candidate that
    /// has that point as a corner and meets it nowhere else (exact adjacency-aware test, the
    /// one used for mesh faces sharing a vertex). A candidate that passes through a pin
    /// other than at a corner is still blocked, so the pinned vertex itself is never
    /// removed. Walls and tubes are unaffected.
    ///
    /// Why this is safe: the candidate minus its pinned corner is connected and meets no
    /// barrier, and its other corners are input vertices inside the space between the
    /// envelopes, so it stays inside that space.
    ///
    /// ```
    /// use envelope_mesh::TriangleSoup;
    /// use envelope_simplify::policy::Barriers;
    /// use glam::DVec3;
    /// let roof = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]], &[[0, 1, 2]]);
    /// let candidate = [DVec3::ZERO, DVec3::new(1.0, 0.0, -1.0), DVec3::new(0.0, 1.0, -1.0)];
    /// let plain = Barriers::new(vec![roof.clone()], vec![]).unwrap();
    /// assert!(plain.blocks(candidate, [false; 3])); // touches at the origin
    /// let pinned = Barriers::new(vec![roof], vec![]).unwrap().with_pins(&[DVec3::ZERO]);
    /// assert!(!pinned.blocks(candidate, [false; 3]));
    /// ```
    #[must_use]
    pub fn with_pins(self, pins: &[DVec3]) -> Self {
        self.pinned_at(pins, BarrierKind::Envelope)
    }

    /// Marks the corners of the `kind` triangles that lie at one of `pins` (the same f64
    /// point) as pins.
    fn pinned_at(mut self, pins: &[DVec3], kind: BarrierKind) -> Self {
        let key = |p: DVec3| p.to_array().map(f64::to_bits);
        let set: std::collections::HashSet<[u64; 3]> = pins.iter().map(|&p| key(p)).collect();
        if set.is_empty() {
            return self;
        }
        for i in 0..self.corners.len() {
            let t = self.corners_of(i);
            if self.kinds[i] == kind {
                self.pinned[i] = (0..3)
                    .filter(|&k| set.contains(&key(t[k])))
                    .fold(0, |m, k| m | 1 << k);
            }
        }
        self
    }

    /// Declares kept vertices: `kept[v]` for each vertex id `v` of the mesh being simplified
    /// that no step may remove or move (the local algorithm's removals, slides and
    /// collapses, the global regions). Vertices beyond `kept` are free. A constraint on the
    /// approximation beside the barrier triangles: the vertices where kept input faces
    /// (around self-intersections) or attribute seams attach.
    ///
    /// ```
    /// use envelope_mesh::VertexId;
    /// use envelope_simplify::policy::Barriers;
    /// let b = Barriers::none().with_kept(vec![false, true]);
    /// assert!(b.keeps(VertexId(1)) && !b.keeps(VertexId(0)) && !b.keeps(VertexId(7)));
    /// ```
    #[must_use]
    pub fn with_kept(mut self, kept: Vec<bool>) -> Self {
        self.kept = kept;
        self
    }

    /// The rings of the border tubes (with their border vertex ids), which a new border
    /// edge must pass through ([`BorderCover`]): [`EnvelopeFilter`](crate::policy::EnvelopeFilter)
    /// then refuses a border vertex's removal whose new edge misses one
    /// ([`Self::refuses_border_edge`]). Without it, only the tubes' triangles bound a new
    /// border edge.
    #[must_use]
    pub fn with_border_cover(mut self, cover: BorderCover) -> Self {
        self.cover = Some(cover);
        self
    }

    /// Whether the new border edge between `ends`, which replaces the border vertex
    /// `removed`, misses the ring of an input border vertex it stands for
    /// ([`BorderCover::covers`]); false without a [`Self::with_border_cover`].
    #[must_use]
    pub fn refuses_border_edge(&self, removed: VertexId, ends: [(VertexId, DVec3); 2]) -> bool {
        self.cover
            .as_ref()
            .is_some_and(|c| !c.covers(removed, ends))
    }

    /// Whether `v` is kept ([`Self::with_kept`]).
    #[must_use]
    pub fn keeps(&self, v: VertexId) -> bool {
        self.kept.get(v.index()).copied().unwrap_or(false)
    }

    /// The kept flags by vertex id ([`Self::with_kept`]; empty when none is kept).
    #[must_use]
    pub fn kept(&self) -> &[bool] {
        &self.kept
    }

    /// [`Self::with_pins`] for walls: a wall triangle with a corner at one of `pins` no longer
    /// blocks a candidate that has that point as a corner and meets it nowhere else. For the
    /// faces of a self-intersecting input kept as they are (given as walls): a new triangle
    /// may share a vertex (or an edge) with them, which the rest keeps (never removed nor
    /// moved), and must meet them nowhere else, so no intersection is made.
    #[must_use]
    pub fn with_wall_pins(self, pins: &[DVec3]) -> Self {
        self.pinned_at(pins, BarrierKind::Wall)
    }

    /// Number of barrier triangles (envelopes and tubes).
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.corners.len()
    }

    /// Whether there is at least one tube triangle. Without tubes nothing bounds a border's
    /// creep (section 6.2), so the local simplifier keeps every border vertex.
    #[must_use]
    pub fn has_tubes(&self) -> bool {
        self.has_tubes
    }

    /// Barrier triangle `i` and its kind (`0..num_triangles()`, in an order of this type's
    /// choosing: spatially coherent, not the order of the surfaces given).
    #[must_use]
    pub fn triangle(&self, i: usize) -> ([DVec3; 3], BarrierKind) {
        (self.corners_of(i), self.kinds[i])
    }

    /// The corners of barrier triangle `i`.
    fn corners_of(&self, i: usize) -> [DVec3; 3] {
        self.corners[i].map(|v| self.points[v as usize])
    }

    /// The part of the validity test (5.1) that does not depend on the approximation: the
    /// corners of `t` are exactly collinear, or [`Self::blocks`] says it touches a barrier.
    /// `EnvelopeFilter` asks it first; the global simplifier screens candidates
    /// with it.
    #[must_use]
    pub fn refuses(&self, t: [DVec3; 3], border_edges: [bool; 3]) -> bool {
        envelope_predicates::collinear(t[0], t[1], t[2]) || self.blocks(t, border_edges)
    }

    /// True when the closed triangle `t` touches an envelope or wall triangle, or when one of the
    /// closed segments `t[i] t[i+1]` with `border_edges[i]` touches a tube triangle. Exact.
    ///
    /// Where it looks, which changes only the order of the tests and never the answer: first
    /// the triangles that blocked this thread's latest queries (the candidates of one hole
    /// are tested in a row and are mostly blocked by the few envelope triangles around the
    /// removed vertex), then, when `t`'s box lies in the region of a [`Self::scoped`] call
    /// running on this thread, the triangles gathered there, else the BVH. In such a
    /// region a query that passed before passes again at once: the barriers never change,
    /// and the answer depends on nothing else (the local simplifier's ear test and its
    /// greedy fill ask about many of the same triangles).
    #[must_use]
    pub fn blocks(&self, t: [DVec3; 3], border_edges: [bool; 3]) -> bool {
        let Some(bvh) = &self.bvh else {
            return false;
        };
        let Some(root) = bvh.root() else {
            return false;
        };
        let query = Aabb::from_triangle(t);
        if SCOPE.with_borrow(|s| {
            s.region_for(self.id, &query).is_some()
                && s.passed.iter().any(|q| q.is(t, border_edges))
        }) {
            return false;
        }
        // Barrier corners are at most `magnitude`: `plane` covers them; the barriers' own
        // filters cover `t` when its corners are too (else they are skipped: no pruning).
        let plane = SlabFilter::new(t, self.magnitude);
        let boxes = bvh.leaf_boxes();
        let meets = |i: u32| {
            let i = i as usize;
            i < self.corners.len()
                && boxes[i].overlaps(&query)
                && self.item_meets(
                    i,
                    self.corners_of(i),
                    self.kinds[i],
                    &plane,
                    t,
                    border_edges,
                )
        };
        let mut recent = RECENT_BLOCKERS.get();
        if let Some(j) = recent.iter().position(|&i| meets(i)) {
            recent[..=j].rotate_right(1);
            RECENT_BLOCKERS.set(recent);
            return true;
        }
        let untried = |i: u32| !recent.contains(&i) && meets(i);
        let found = SCOPE
            .with_borrow_mut(|s| {
                let region = s.region_for(self.id, &query)?;
                if let Some(&i) = s.hints.iter().find(|&&i| untried(i)) {
                    return Some(Some(i));
                }
                if !s.gathered {
                    s.gathered = true;
                    let items = &mut s.items;
                    bvh.for_each_overlapping(&region, |i| {
                        let k = i as usize;
                        items.push(Gathered {
                            bounds: boxes[k],
                            corners: self.corners_of(k),
                            index: i,
                            kind: self.kinds[k],
                        });
                    });
                }
                let found = s
                    .items
                    .iter()
                    .find(|g| {
                        g.bounds.overlaps(&query)
                            && !recent.contains(&g.index)
                            && self.item_meets(
                                g.index as usize,
                                g.corners,
                                g.kind,
                                &plane,
                                t,
                                border_edges,
                            )
                    })
                    .map(|g| g.index);
                if found.is_none() {
                    s.passed.push(Query {
                        corners: t,
                        border_edges,
                    });
                }
                Some(found)
            })
            .unwrap_or_else(|| self.first_blocker(bvh, root, &query, &plane, &untried));
        match found {
            Some(i) => {
                recent.rotate_right(1);
                recent[0] = i;
                RECENT_BLOCKERS.set(recent);
                true
            }
            None => false,
        }
    }

    /// Runs `f` with a scope for [`Self::blocks`] on this thread: the triangles whose boxes
    /// overlap the closed box `region` are gathered once, and every query whose box lies in
    /// `region` (and is asked of `self`) scans them instead of walking the BVH. A triangle
    /// that meets such a query has a box overlapping the query's, hence `region`'s, so the
    /// answers are exactly those without the scope; only the work changes. The local
    /// simplifier scopes each hole to the box of its vertices, where all its candidates lie.
    /// Scopes nest (the inner one applies until it returns).
    ///
    /// ```
    /// use envelope_mesh::generate;
    /// use envelope_predicates::bvh::Aabb;
    /// use envelope_simplify::policy::Barriers;
    /// use glam::DVec3;
    /// let b = Barriers::new(vec![generate::icosphere(2, 1.0)], vec![]).unwrap();
    /// let t = [DVec3::new(0.9, 0.0, 0.0), DVec3::new(1.1, 0.1, 0.0), DVec3::new(1.0, -0.1, 0.1)];
    /// let far = [DVec3::ZERO, DVec3::new(0.1, 0.0, 0.0), DVec3::new(0.0, 0.1, 0.0)];
    /// let region = Aabb::from_points(&[DVec3::splat(-0.5), DVec3::splat(1.5)]);
    /// b.scoped(&region, || {
    ///     assert!(b.blocks(t, [false; 3])); // crosses the sphere: found among the gathered
    ///     assert!(!b.blocks(far, [false; 3])); // inside, clear of it
    /// });
    /// ```
    pub fn scoped<R>(&self, region: &Aabb, f: impl FnOnce() -> R) -> R {
        self.scoped_near(region, &[], f)
    }

    /// [`Self::scoped`], where the envelope triangles of faces `faces` (face numbers of
    /// each envelope surface, which for envelopes of one mesh are that mesh's faces) are
    /// tested before the scope gathers anything: a query they block needs no gathering.
    /// The local simplifier names the input faces around the removed vertex: the fiber
    /// test's candidates are mostly blocked by their offsets. Only the order of the tests
    /// changes, never an answer.
    ///
    /// ```
    /// use envelope_mesh::generate;
    /// use envelope_predicates::bvh::Aabb;
    /// use envelope_simplify::policy::Barriers;
    /// use glam::DVec3;
    /// let sphere = generate::icosphere(2, 1.0);
    /// let b = Barriers::new(vec![sphere.clone()], vec![]).unwrap();
    /// let t = [DVec3::new(0.9, 0.0, 0.0), DVec3::new(1.1, 0.1, 0.0), DVec3::new(1.0, -0.1, 0.1)];
    /// let region = Aabb::from_points(&[DVec3::splat(-0.5), DVec3::splat(1.5)]);
    /// let all: Vec<u32> = (0..sphere.num_faces() as u32).collect();
    /// assert!(b.scoped_near(&region, &all[..5], || b.blocks(t, [false; 3])));
    /// ```
    pub fn scoped_near<R>(&self, region: &Aabb, faces: &[u32], f: impl FnOnce() -> R) -> R {
        if self.bvh.is_none() || self.id == 0 {
            return f();
        }
        // Reuse the thread's buffers unless an enclosing scope is using them.
        let (mut items, mut passed, mut hints) = SCOPE.with_borrow_mut(|s| {
            if s.active.is_none() {
                (
                    std::mem::take(&mut s.items),
                    std::mem::take(&mut s.passed),
                    std::mem::take(&mut s.hints),
                )
            } else {
                (Vec::new(), Vec::new(), Vec::new())
            }
        });
        items.clear();
        passed.clear();
        hints.clear();
        for &(first, count) in &self.envelope_faces {
            hints.extend(
                faces
                    .iter()
                    .filter(|&&f| f < count)
                    .filter_map(|&f| self.position.get((first + f) as usize).copied()),
            );
        }
        let scope = Scope {
            active: Some((self.id, *region)),
            gathered: false,
            items,
            passed,
            hints,
        };
        /// Puts the enclosing scope back when `f` returns or unwinds.
        struct Restore(Option<Scope>);
        impl Drop for Restore {
            fn drop(&mut self) {
                if let Some(mut outer) = self.0.take() {
                    let inner = SCOPE.replace(Scope::default());
                    if outer.active.is_none() {
                        outer.items = inner.items;
                        outer.passed = inner.passed;
                        outer.hints = inner.hints;
                    }
                    SCOPE.set(outer);
                }
            }
        }
        let _restore = Restore(Some(SCOPE.replace(scope)));
        f()
    }

    /// The first triangle under `root` that blocks the query and passes `untried`.
    fn first_blocker(
        &self,
        bvh: &Bvh,
        root: envelope_predicates::bvh::NodeId,
        query: &Aabb,
        plane: &SlabFilter,
        untried: &dyn Fn(u32) -> bool,
    ) -> Option<u32> {
        // Depth-first with a fixed stack: the tree's depth is at most 64 (median splits).
        let mut stack = [root; 64];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let n = stack[len];
            let bounds = bvh.bounds(n);
            if !bounds.overlaps(query) || plane.separates(&bounds) {
                continue;
            }
            match bvh.kind(n) {
                NodeKind::Interior(a, b) if len + 2 <= stack.len() => {
                    stack[len] = b;
                    stack[len + 1] = a;
                    len += 2;
                }
                NodeKind::Interior(a, b) => {
                    // Deeper than any median-split tree gets: finish these subtrees apart.
                    if let Some(i) = [a, b]
                        .into_iter()
                        .find_map(|c| self.first_blocker(bvh, c, query, plane, untried))
                    {
                        return Some(i);
                    }
                }
                NodeKind::Leaf(items) => {
                    if let Some(&i) = items.iter().find(|&&i| untried(i)) {
                        return Some(i);
                    }
                }
            }
        }
        None
    }

    /// Whether barrier triangle `i` (corners `b`, kind `kind`), whose box overlaps the
    /// candidate `t`'s, blocks it (`plane`: `t`'s filter).
    fn item_meets(
        &self,
        i: usize,
        b: [DVec3; 3],
        kind: BarrierKind,
        plane: &SlabFilter,
        t: [DVec3; 3],
        border_edges: [bool; 3],
    ) -> bool {
        match kind {
            BarrierKind::Envelope | BarrierKind::Wall => {
                // The barrier triangle's own slab is made here, when the candidate's plane
                // does not separate, rather than kept at 168 bytes per barrier triangle (the
                // same values, the same pruning; the memory it saves is in the changelog).
                let apart = plane.separates_points(b) || {
                    let own = SlabFilter::new(b, self.magnitude).points;
                    own.covers(plane.t_mag) && own.separates_points(t)
                };
                !apart
                    && match pin_ids(t, b, self.pinned[i]) {
                        Some(g) => indexed_triangles_intersect(t, [0, 1, 2], b, g),
                        None => triangles_intersect(t, b),
                    }
            }
            BarrierKind::Tube => (0..3).any(|k| {
                border_edges[k]
                    && segment_triangle(t[k], t[(k + 1) % 3], b) != SegmentTriangle::Disjoint
            }),
        }
    }
}

/// One tree over all `count` barrier triangles (`box_of(g)` the box of triangle `g`:
/// envelopes first, then tubes and walls): the envelopes' `tree`, checked against their
/// boxes, joined in place with one built over the rest.
fn joined_tree(
    envelopes: &[TriangleSoup],
    tree: Bvh,
    count: u32,
    box_of: impl Fn(u32) -> Aabb + Sync,
) -> Result<Bvh, BarrierError> {
    let n: u32 = envelopes.iter().map(|e| e.num_faces() as u32).sum();
    if !tree.has_item_boxes_of(n as usize, &box_of) {
        return Err(BarrierError::TreeMismatch);
    }
    let rest: Vec<Aabb> = (n..count).into_par_iter().map(&box_of).collect();
    Ok(tree.joined(&Bvh::new(&rest)))
}

/// Corner ids for [`indexed_triangles_intersect`], with the candidate `t` numbered
/// `[0, 1, 2]`: a pin corner `j` of `b` (bit `j` of `mask`) at the point of `t[i]` gets id
/// `i` (they share it), every other corner of `b` an id of its own. `None` when no pin
/// corner is shared, or either triangle repeats a point (then the plain test decides: it
/// can only block more).
fn pin_ids(t: [DVec3; 3], b: [DVec3; 3], mask: u8) -> Option<[u32; 3]> {
    let repeats = |x: [DVec3; 3]| x[0] == x[1] || x[1] == x[2] || x[2] == x[0];
    if mask == 0 || repeats(t) || repeats(b) {
        return None;
    }
    let mut shared = false;
    let ids = [0, 1, 2].map(|j| {
        let at = (mask & 1 << j != 0)
            .then(|| t.iter().position(|&p| p == b[j]))
            .flatten();
        shared |= at.is_some();
        at.map_or(3 + j as u32, |i| i as u32)
    });
    shared.then_some(ids)
}

/// A conservative f64 separating-axis test for one triangle `t`.
///
/// `separates(box)` is true only when the exact values of `n . x` over the box and over `t`
/// do not overlap, `n` the f64 cross product of `t`'s edges; `separates_points(q)` the same
/// for the corners of a triangle `q` on `n` and on the three in-plane edge normals
/// `n x (t[k+1] - t[k])` (four of the eleven axes of the triangle/triangle separating-axis
/// theorem). The axes are whatever f64 vectors the products round to: any axis separates
/// when the projections are disjoint. Every dot product's rounding error (at most
/// `3u sum |a_i x_i|`, bounded by `1e-15 |a|_1 max|x|` plus an underflow term) is added on
/// both sides, so a pair is only declared apart when it is. It only prunes work; the
/// decisions are the exact predicates'.
#[derive(Clone, Copy, Debug, Default)]
struct SlabFilter {
    /// The axes and widened projections: what [`SlabFilter::separates_points`] reads.
    points: PointSlab,
    /// `|axis|_1`.
    norm1: [f64; 4],
    /// `t`'s projection on each axis, as computed.
    lo: [f64; 4],
    hi: [f64; 4],
    t_mag: f64,
}

/// The part of a [`SlabFilter`] that [`SlabFilter::separates_points`] reads (what a barrier
/// triangle's own test needs).
#[derive(Clone, Copy, Debug, Default)]
struct PointSlab {
    /// The normal, then the three in-plane edge normals.
    axes: [DVec3; 4],
    /// `t`'s projection on each axis widened by the slack for coordinates up to `bound` on
    /// the other side (infinite on an axis that cannot separate: zero or not finite).
    lo_wide: [f64; 4],
    hi_wide: [f64; 4],
    /// At least `t`'s coordinate magnitude: the one that `lo_wide` and `hi_wide` cover.
    bound: f64,
}

impl PointSlab {
    /// [`SlabFilter::separates_points`].
    fn separates_points(&self, q: [DVec3; 3]) -> bool {
        (0..4).any(|k| {
            let d = q.map(|p| self.axes[k].dot(p));
            d[0].min(d[1]).min(d[2]) > self.hi_wide[k] || d[0].max(d[1]).max(d[2]) < self.lo_wide[k]
        })
    }

    /// Whether [`Self::separates_points`] may be asked of triangles whose coordinates are
    /// at most `mag` in magnitude.
    fn covers(&self, mag: f64) -> bool {
        mag <= self.bound
    }
}

impl SlabFilter {
    /// The filter of `t`, widened for triangles with coordinates up to `bound` in magnitude
    /// (or up to `t`'s own, when larger) in [`SlabFilter::separates_points`].
    fn new(t: [DVec3; 3], bound: f64) -> Self {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let axes = [
            n,
            n.cross(t[1] - t[0]),
            n.cross(t[2] - t[1]),
            n.cross(t[0] - t[2]),
        ];
        let t_mag = t.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
        let mut f = Self {
            points: PointSlab {
                axes,
                lo_wide: [f64::NEG_INFINITY; 4],
                hi_wide: [f64::INFINITY; 4],
                bound: bound.max(t_mag),
            },
            norm1: axes.map(|a| a.abs().element_sum()),
            lo: [0.0; 4],
            hi: [0.0; 4],
            t_mag,
        };
        for k in 0..4 {
            let d = t.map(|p| axes[k].dot(p));
            f.lo[k] = d[0].min(d[1]).min(d[2]);
            f.hi[k] = d[0].max(d[1]).max(d[2]);
            if let Some(slack) = f.slack(k, f.points.bound) {
                f.points.lo_wide[k] = f.lo[k] - slack;
                f.points.hi_wide[k] = f.hi[k] + slack;
            }
        }
        f
    }

    /// Rounding slack for axis `k` with coordinates up to `mag` on the other side.
    fn slack(&self, k: usize, mag: f64) -> Option<f64> {
        let n1 = self.norm1[k];
        (n1.is_finite() && n1 != 0.0).then(|| 2.0 * (1e-15 * n1 * mag.max(self.t_mag) + 1e-300))
    }

    fn separates(&self, b: &Aabb) -> bool {
        let n = self.points.axes[0];
        let mag = b.min.abs().max_element().max(b.max.abs().max_element());
        let Some(slack) = self.slack(0, mag) else {
            return false;
        };
        let lo = DVec3::select(n.cmpge(DVec3::ZERO), b.min, b.max);
        let hi = DVec3::select(n.cmpge(DVec3::ZERO), b.max, b.min);
        n.dot(lo) > self.hi[0] + slack || n.dot(hi) < self.lo[0] - slack
    }

    /// The test for the three corners of a triangle `q` on all four axes. The caller knows
    /// that `q`'s coordinates are at most `self.points.bound` in magnitude (the slack is
    /// precomputed for that bound; [`PointSlab::covers`] tells).
    fn separates_points(&self, q: [DVec3; 3]) -> bool {
        self.points.separates_points(q)
    }
}

/// The largest coordinate magnitude of `t`.
#[cfg(test)]
fn magnitude(t: [DVec3; 3]) -> f64 {
    t.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max)
}

/// The box and one vertex of every connected component of `soup`'s faces.
fn surface_components(soup: &TriangleSoup) -> Vec<(Aabb, DVec3)> {
    let (comp, n) = envelope_mesh::vertex_components(soup.num_vertices(), &soup.faces);
    // Every component has a vertex: its first one is set while its box is still empty.
    let mut out = vec![(Aabb::EMPTY, DVec3::ZERO); n];
    for (&p, c) in soup.positions.iter().zip(&comp) {
        if let Some(c) = c {
            let (b, first) = &mut out[*c as usize];
            if b.is_empty() {
                *first = p;
            }
            *b = b.union(&Aabb::from_points(&[p]));
        }
    }
    out
}

/// Whether the directed edges of `old` and `new` cancel (`old - new` is closed).
fn same_boundary(old: &[[DVec3; 3]], new: &[[DVec3; 3]]) -> bool {
    let key = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut edges: Vec<([[u64; 3]; 2], i32)> = Vec::new();
    let mut add = |t: &[DVec3; 3], s: i32| {
        for i in 0..3 {
            let (a, b) = (key(t[i]), key(t[(i + 1) % 3]));
            // An edge and its reverse cancel: stored one way with a sign.
            let (e, s) = if a < b { ([a, b], s) } else { ([b, a], -s) };
            match edges.iter_mut().find(|(f, _)| *f == e) {
                Some((_, n)) => *n += s,
                None => edges.push((e, s)),
            }
        }
    };
    old.iter().for_each(|t| add(t, 1));
    new.iter().for_each(|t| add(t, -1));
    edges.iter().all(|&(_, n)| n == 0)
}

/// Whether the winding number of the closed `cycle` at `p` (inside `region`, which holds
/// the cycle) is not zero, counted along segments from `p` out of `region`; true when no
/// segment decides it (each passes through an edge or a vertex).
fn winding_not_zero(p: DVec3, region: &Aabb, cycle: &[[DVec3; 3]]) -> bool {
    let reach = 2.0 * (region.max - region.min).length()
        + region.max.abs().max(region.min.abs()).max_element()
        + 1e-30;
    const DIRECTIONS: [[f64; 3]; 10] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.6, 0.37, 0.71],
        [-0.53, 0.79, -0.31],
        [0.29, -0.61, 0.73],
        [-0.67, -0.23, -0.7],
    ];
    for d in DIRECTIONS {
        let q = p + DVec3::from_array(d) * reach;
        match polyline_crossings(&[p, q], cycle) {
            Some(0) => return false,
            Some(_) => return true,
            None => {}
        }
    }
    true
}

/// Whether the triangle `(a, a_data)` is `(b, b_data)` up to a rotation of its corners, the
/// per-corner data (border edges, positions) rotating along. The memories of
/// [`Barriers::scoped`] and [`Nearby`] match their questions with it.
pub(crate) fn same_up_to_rotation<A: PartialEq, B: PartialEq>(
    (a, a_data): (&[A; 3], &[B; 3]),
    (b, b_data): (&[A; 3], &[B; 3]),
) -> bool {
    (0..3).any(|r| (0..3).all(|k| a[(k + r) % 3] == b[k] && a_data[(k + r) % 3] == b_data[k]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = DVec3> {
        (-4i32..=4, -4i32..=4, -4i32..=4)
            .prop_map(|(x, y, z)| DVec3::new(x.into(), y.into(), z.into()))
    }

    /// A roof over the origin: `z = x + y` on the unit corner triangle.
    fn roof() -> TriangleSoup {
        TriangleSoup::from_raw(
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            &[[0, 1, 2]],
        )
    }

    fn roof_triangle() -> [DVec3; 3] {
        roof().triangle(envelope_mesh::FaceId(0))
    }

    fn boxes_of(surfaces: &[&TriangleSoup]) -> Vec<Aabb> {
        surfaces
            .iter()
            .flat_map(|s| s.face_ids().map(|f| Aabb::from_triangle(s.triangle(f))))
            .collect()
    }

    /// Barriers on a tree handed in (a refit of the inner envelope's tree with both faces of
    /// a position in one leaf) answer as those that built their own, with a tube and a wall
    /// beside the envelopes; a tree that is not over the envelopes' faces is refused.
    #[test]
    fn barriers_on_a_given_tree_answer_as_built_ones() {
        use envelope_mesh::generate;
        let outer = generate::icosphere(2, 1.1);
        let inner = generate::icosphere(2, 0.9);
        let tube = generate::torus(1.0, 0.05, 16, 6);
        let wall = roof();
        let built = Barriers::with_walls(
            vec![outer.clone(), inner.clone()],
            vec![tube.clone()],
            vec![wall.clone()],
        )
        .unwrap();
        let tree = Bvh::new(&boxes_of(&[&inner]))
            .interleaved(2)
            .refit(&boxes_of(&[&outer, &inner]));
        let given = Barriers::with_tree(
            vec![outer.clone(), inner.clone()],
            tree,
            vec![tube],
            vec![wall],
        )
        .unwrap();
        assert_eq!(given.num_triangles(), built.num_triangles());
        let mut state = 0x5DEE_CE66_D1CE_4E5B_u64;
        let mut coord = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.6 - 1.3
        };
        let (mut blocked, mut free) = (0, 0);
        for _ in 0..400 {
            let t = [(); 3].map(|()| DVec3::new(coord(), coord(), coord()) * 0.6);
            let edges = [true, false, true];
            let answer = built.blocks(t, edges);
            assert_eq!(given.blocks(t, edges), answer, "{t:?}");
            if answer {
                blocked += 1;
            } else {
                free += 1;
            }
        }
        assert!(blocked > 20 && free > 20, "{blocked} blocked, {free} free");
        // The surfaces the other way round: other boxes at the same items.
        let swapped = Barriers::with_tree(
            vec![outer.clone(), inner.clone()],
            Bvh::new(&boxes_of(&[&inner, &outer])),
            vec![],
            vec![],
        );
        assert_eq!(swapped.err(), Some(BarrierError::TreeMismatch));
        let short = Barriers::with_tree(
            vec![outer.clone(), inner],
            Bvh::new(&boxes_of(&[&outer])),
            vec![],
            vec![],
        );
        assert_eq!(short.err(), Some(BarrierError::TreeMismatch));
    }

    #[test]
    fn a_pin_lets_a_candidate_touch_at_its_corner_only() {
        let plain = Barriers::new(vec![roof()], vec![]).unwrap();
        let pinned = Barriers::new(vec![roof()], vec![])
            .unwrap()
            .with_pins(&[DVec3::ZERO]);
        let d = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        // Below the roof, corner at the pin: only the pinned barriers let it through.
        let below = [DVec3::ZERO, d(1.0, 0.0, 0.0), d(0.0, 1.0, 0.0)];
        assert!(plain.blocks(below, [false; 3]));
        assert!(!pinned.blocks(below, [false; 3]));
        // Corner at the pin, but it crosses the roof away from it.
        let crossing = [DVec3::ZERO, d(1.0, 0.0, 2.0), d(0.0, 1.0, 0.0)];
        assert!(pinned.blocks(crossing, [false; 3]));
        // On the roof's plane along its edge from the pin: meets it along a segment.
        let along = [DVec3::ZERO, d(0.5, 0.0, 0.5), d(0.5, -1.0, 0.0)];
        assert!(pinned.blocks(along, [false; 3]));
        // Through the pin, which is not its corner (the pinned vertex cannot be removed).
        let through = [d(-1.0, -1.0, 0.0), d(1.0, -1.0, 0.0), d(0.0, 1.0, 0.0)];
        assert!(through[0].x < 0.0 && pinned.blocks(through, [false; 3]));
        // A corner at the roof's other corner, which is no pin.
        let other = [d(1.0, 0.0, 1.0), d(2.0, 0.0, 0.0), d(1.0, -1.0, 0.0)];
        assert!(pinned.blocks(other, [false; 3]));
        // A wall with a corner at the pin is not relaxed.
        let walled = Barriers::with_walls(vec![], vec![], vec![roof()])
            .unwrap()
            .with_pins(&[DVec3::ZERO]);
        assert!(walled.blocks(below, [false; 3]));
        // Two pins: a candidate sharing the roof's edge between them, folded away from it.
        let two = Barriers::new(vec![roof()], vec![])
            .unwrap()
            .with_pins(&[DVec3::ZERO, d(1.0, 0.0, 1.0)]);
        let hinge = [DVec3::ZERO, d(1.0, 0.0, 1.0), d(0.5, -1.0, 0.0)];
        assert!(plain.blocks(hinge, [false; 3]));
        assert!(!two.blocks(hinge, [false; 3]));
        let folded = [DVec3::ZERO, d(1.0, 0.0, 1.0), d(0.25, 0.5, 0.75)];
        assert!(two.blocks(folded, [false; 3]));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]
        /// The prefilter may only say "apart" when the exact test says the closed triangles do
        /// not meet: small integer grids give many touching and coplanar pairs, and the
        /// nudge by a few ulps puts points just on either side.
        #[test]
        fn slab_filter_never_separates_meeting_triangles(
            t in [point(), point(), point()],
            q in [point(), point(), point()],
            nudge in -3i32..=3,
        ) {
            let mut q = q;
            q[0].x += f64::from(nudge) * f64::EPSILON * q[0].x.abs().max(1.0);
            let bq = Aabb::from_triangle(q);
            let bound = magnitude(t).max(magnitude(q));
            let f = SlabFilter::new(t, bound);
            if f.separates_points(q) || f.separates(&bq) || SlabFilter::new(q, bound).separates_points(t) {
                prop_assert!(!triangles_intersect(t, q), "{t:?} {q:?}");
            }
        }

        /// `blocks` answers what the brute force over every barrier triangle answers, whatever
        /// the previous queries left as the thread's recent blockers (`RECENT_BLOCKERS`), and
        /// inside a scope whatever its region (queries inside it, outside it, across it), also
        /// nested in another scope, before and after the inner one. Each query is asked with
        /// its border edges, then rotated, then with the border edges flipped (the scope's
        /// remembered passes must tell these apart), with tube triangles among the barriers.
        #[test]
        fn blocks_is_the_brute_force_answer_whatever_the_hints(
            barrier in prop::collection::vec([point(), point(), point()], 1..12),
            tube in prop::collection::vec([point(), point(), point()], 0..4),
            queries in prop::collection::vec(([point(), point(), point()], prop::array::uniform3(any::<bool>())), 1..8),
            hint in prop::array::uniform8(0u32..16),
            regions in [point(), point(), point(), point()],
            scoping in 0u8..5,
            near in prop::collection::vec(0u32..16, 0..6),
        ) {
            let soup = TriangleSoup::new(
                barrier.iter().flatten().copied().collect(),
                (0..barrier.len() as u32)
                    .map(|k| [3 * k, 3 * k + 1, 3 * k + 2].map(envelope_mesh::VertexId))
                    .collect(),
            );
            let tubes = TriangleSoup::new(
                tube.iter().flatten().copied().collect(),
                (0..tube.len() as u32)
                    .map(|k| [3 * k, 3 * k + 1, 3 * k + 2].map(envelope_mesh::VertexId))
                    .collect(),
            );
            let b = Barriers::new(vec![soup], vec![tubes]).unwrap();
            let other = Barriers::new(vec![roof()], Vec::new()).unwrap();
            RECENT_BLOCKERS.set(hint);
            let brute = |q: [DVec3; 3], e: [bool; 3]| {
                barrier.iter().any(|&t| triangles_intersect(q, t))
                    || tube.iter().any(|&t| {
                        (0..3).any(|k| {
                            e[k] && segment_triangle(q[k], q[(k + 1) % 3], t) != SegmentTriangle::Disjoint
                        })
                    })
            };
            let ask = |qs: &[([DVec3; 3], [bool; 3])]| -> Result<(), TestCaseError> {
                for &(q, e) in qs {
                    let rotated = ([q[1], q[2], q[0]], [e[1], e[2], e[0]]);
                    let flipped = e.map(|x| !x);
                    for (q, e) in [(q, e), rotated, (q, flipped)] {
                        prop_assert_eq!(b.blocks(q, e), brute(q, e), "{:?} {:?}", q, e);
                    }
                }
                Ok(())
            };
            let outer = Aabb::from_points(&regions[..2]);
            let inner = Aabb::from_points(&regions[2..]);
            let (first, rest) = queries.split_at(queries.len() / 2);
            match scoping {
                0 => ask(&queries)?,
                1 => b.scoped(&outer, || {
                    ask(&queries)?;
                    // `b`'s scope (its gathered triangles, its remembered passes) is not
                    // another value's.
                    for &(q, e) in &queries {
                        prop_assert_eq!(other.blocks(q, e), triangles_intersect(q, roof_triangle()));
                    }
                    Ok(())
                })?,
                // Hinted faces (some out of range), alone and around another value's scope.
                3 => b.scoped_near(&outer, &near, || ask(&queries))?,
                4 => b.scoped_near(&outer, &near, || {
                    ask(first)?;
                    other.scoped_near(&inner, &near, || {
                        for &(q, e) in rest {
                            prop_assert_eq!(other.blocks(q, e), triangles_intersect(q, roof_triangle()));
                        }
                        b.scoped_near(&inner, &near, || ask(rest))
                    })?;
                    ask(&queries)
                })?,
                _ => b.scoped(&outer, || {
                    ask(first)?;
                    // Another value's scope must not be used for `b`; `b`'s inner one is.
                    other.scoped(&inner, || {
                        for &(q, e) in rest {
                            // Gathers `other`'s; answers from `b`'s would be wrong.
                            prop_assert_eq!(other.blocks(q, e), triangles_intersect(q, roof_triangle()));
                        }
                        ask(rest)?;
                        b.scoped(&inner, || ask(rest))
                    })?;
                    ask(&queries)
                })?,
            }
        }

        /// Pins only relax: whatever pinned barriers block, plain ones block; a candidate
        /// with no pin among its corners gets the plain answer; and a candidate let through
        /// that meets a barrier triangle shares a pinned corner with each one it meets.
        /// Candidates start at a barrier corner half the time, so corners are shared often.
        #[test]
        fn pins_only_relax_at_shared_pinned_corners(
            barrier in prop::collection::vec([point(), point(), point()], 1..10),
            queries in prop::collection::vec(([point(), point(), point()], any::<bool>(), 0usize..30), 1..8),
            pin_picks in prop::collection::vec(0usize..30, 0..6),
        ) {
            let corners: Vec<DVec3> = barrier.iter().flatten().copied().collect();
            let pins: Vec<DVec3> = pin_picks.iter().map(|&k| corners[k % corners.len()]).collect();
            let soup = TriangleSoup::new(
                corners.clone(),
                (0..barrier.len() as u32)
                    .map(|k| [3 * k, 3 * k + 1, 3 * k + 2].map(envelope_mesh::VertexId))
                    .collect(),
            );
            let plain = Barriers::new(vec![soup.clone()], Vec::new()).unwrap();
            let pinned = Barriers::new(vec![soup], Vec::new()).unwrap().with_pins(&pins);
            for (mut q, at_corner, k) in queries {
                if at_corner {
                    q[0] = corners[k % corners.len()];
                }
                let (p, b) = (plain.blocks(q, [false; 3]), pinned.blocks(q, [false; 3]));
                prop_assert!(!b || p, "{:?}", q);
                if !q.iter().any(|c| pins.contains(c)) {
                    prop_assert_eq!(p, b, "{:?}", q);
                }
                if !b {
                    for t in barrier.iter().filter(|&&t| triangles_intersect(q, t)) {
                        prop_assert!(
                            t.iter().any(|c| pins.contains(c) && q.contains(c)),
                            "{:?} meets {:?} away from a pin", q, t
                        );
                    }
                }
            }
        }
    }
}
