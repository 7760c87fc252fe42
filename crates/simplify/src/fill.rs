//! Hole filling (section 5.2, figure 7): a [`HoleFiller`] chooses triangles on the vertices
//! of a [`Hole`], each tested by the validity [`Filter`] through a [`FillContext`].
//!
//! * [`Greedy`] (the paper's single pass): all triangles on the hole's vertices, best aspect
//!   ratio first; the first valid one is placed and the up to three sub-holes it leaves are
//!   filled recursively the same way; no backtracking, so a failure anywhere fails the hole.
//! * [`Exhaustive`] (the paper's comparison): every triangulation of holes up to a bound,
//!   keeping the valid one whose worst triangle has the best aspect ratio; larger holes fall
//!   back to [`Greedy`].
//!
//! Orientation: hole vertices come in the order of the removed fan, so a triangle on hole
//! positions `a < b < c` is oriented as the fan was; sub-holes keep that cyclic order.
//!
//! Topology guards (combinatorial, before the filter): an edge of a candidate that is not an
//! edge of the hole's boundary must not already be an edge of the mesh (it would be
//! non-manifold, or change the genus: the link condition), and a candidate must not repeat
//! an existing face's three vertices. For an open hole (a border vertex was removed) the
//! closing edge `last -> first` is new and becomes a border edge; the filter is told so in
//! [`CandidateProfile::border_edges`] and tests it against the border tubes.

use crate::fiber::FiberPath;
use crate::filter::{Approximation, CandidateProfile, Filter, Nearby, position_in};
use crate::grid::FaceGrid;
use crate::rules::aspect_ratio;
use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use glam::DVec3;
use std::collections::HashMap;

/// The boundary of a hole left by removing a vertex's fan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Hole {
    /// Boundary vertices in the order of the removed fan (see
    /// [`HalfEdgeMesh::remove_vertex_fan`]).
    pub vertices: Vec<VertexId>,
    /// An open chain (a border vertex was removed): the edge from the last vertex to the
    /// first does not exist yet and will lie on the border.
    pub open: bool,
}

impl Hole {
    /// Number of boundary vertices.
    #[must_use]
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// True when there is no vertex.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// Whether hole positions `i` and `j` are joined by an existing hole-boundary edge.
    fn boundary_edge(&self, i: usize, j: usize) -> bool {
        let n = self.len();
        let (lo, hi) = (i.min(j), i.max(j));
        hi - lo == 1 || (!self.open && lo == 0 && hi == n - 1)
    }

    /// Whether hole positions `i` and `j` form the new border edge of an open hole.
    fn closing_edge(&self, i: usize, j: usize) -> bool {
        self.open && i.min(j) == 0 && i.max(j) == self.len() - 1
    }
}

/// What a hole filler may do: test a candidate (topology guards, then the [`Filter`] against
/// the current approximation including the triangles placed so far), place it, read back
/// what it placed.
pub struct FillContext<'a> {
    mesh: &'a HalfEdgeMesh,
    grid: &'a FaceGrid,
    filter: &'a dyn Filter,
    hole: &'a Hole,
    /// Faces of `grid` the filter must ignore ([`Self::excluding`]).
    excluded: &'a [FaceId],
    /// Planned positions and the faces around them ([`Self::moving`]).
    moved: &'a [(VertexId, DVec3)],
    extra: &'a [[VertexId; 3]],
    /// The grid's faces near the hole ([`Self::near`]).
    nearby: Option<&'a Nearby>,
    placed: Vec<[VertexId; 3]>,
    /// Candidates already rejected during this fill, by [`Self::slot`]. A rejection is final
    /// for the whole fill: the mesh and grid do not change while a hole is filled, the placed
    /// triangles only grow, and a [`Filter`] must not accept what it rejected with fewer
    /// triangles placed. Greedy re-offers a rejected triangle to every sub-hole that contains
    /// its corners; this makes the second offer free.
    rejected: Vec<bool>,
    /// Number of filter calls (for statistics).
    pub tests: u64,
}

impl<'a> FillContext<'a> {
    /// A context for filling `hole` in `mesh` (whose live faces `grid` indexes).
    #[must_use]
    pub fn new(
        mesh: &'a HalfEdgeMesh,
        grid: &'a FaceGrid,
        filter: &'a dyn Filter,
        hole: &'a Hole,
    ) -> Self {
        Self {
            mesh,
            grid,
            filter,
            hole,
            excluded: &[],
            moved: &[],
            extra: &[],
            nearby: None,
            placed: Vec::new(),
            rejected: Vec::new(),
            tests: 0,
        }
    }

    /// The same context with `faces` (still in `mesh` and `grid`) treated as gone: the fan
    /// of a vertex whose removal is planned without editing the mesh.
    #[must_use]
    pub fn excluding(mut self, faces: &'a [FaceId]) -> Self {
        self.excluded = faces;
        self
    }

    /// The same context with vertices at planned positions (see [`Approximation::moved`]):
    /// `extra` are the faces around them that stay, and every grid face around them must be
    /// excluded too.
    #[must_use]
    pub fn moving(mut self, moved: &'a [(VertexId, DVec3)], extra: &'a [[VertexId; 3]]) -> Self {
        self.moved = moved;
        self.extra = extra;
        self
    }

    /// The same context with the grid's faces near the hole gathered into `nearby` (see
    /// [`Nearby`]; its region should hold every hole vertex at its planned position).
    #[must_use]
    pub fn near(mut self, nearby: &'a Nearby) -> Self {
        self.nearby = Some(nearby);
        self
    }

    /// Where `v` is: its planned position, else the mesh's.
    fn position(&self, v: VertexId) -> DVec3 {
        position_in(self.mesh, self.moved, v)
    }

    /// Index of the triangle `t` (hole positions) in `rejected`.
    fn slot(&self, t: [usize; 3]) -> usize {
        let n = self.hole.len();
        (t[0] * n + t[1]) * n + t[2]
    }

    /// The hole being filled.
    #[must_use]
    pub fn hole(&self) -> &'a Hole {
        self.hole
    }

    /// The triangle on hole positions `t` (increasing), as vertex ids.
    #[must_use]
    pub fn triangle(&self, t: [usize; 3]) -> [VertexId; 3] {
        t.map(|i| self.hole.vertices[i])
    }

    /// Aspect ratio of the triangle on hole positions `t` (a priority).
    #[must_use]
    pub fn aspect(&self, t: [usize; 3]) -> f64 {
        aspect_ratio(self.triangle(t).map(|v| self.position(v)))
    }

    /// Topology guards only (see the module docs).
    #[must_use]
    pub fn topologically_allowed(&self, t: [usize; 3]) -> bool {
        let m = self.mesh;
        let ids = self.triangle(t);
        for k in 0..3 {
            let (i, j) = (t[k], t[(k + 1) % 3]);
            if !self.hole.boundary_edge(i, j) && m.find_halfedge(ids[k], ids[(k + 1) % 3]).is_some()
            {
                return false;
            }
        }
        !face_exists(m, ids)
    }

    /// Topology guards, then the filter with the triangles placed so far.
    pub fn accepts(&mut self, t: [usize; 3]) -> bool {
        self.accepts_with(t, true)
    }

    /// [`Self::accepts`], with `placed` hidden from the filter when `with_placed` is false.
    fn accepts_with(&mut self, t: [usize; 3], with_placed: bool) -> bool {
        let slot = self.slot(t);
        if self.rejected.get(slot).copied().unwrap_or(false) {
            return false;
        }
        let ok = self.test(t, with_placed);
        if !ok {
            self.remember_rejection(slot);
        }
        ok
    }

    /// Caches the rejection of the triangle at `slot` (see [`Self::slot`]) for this fill.
    fn remember_rejection(&mut self, slot: usize) {
        if self.rejected.is_empty() {
            let n = self.hole.len();
            self.rejected = vec![false; n * n * n];
        }
        self.rejected[slot] = true;
    }

    /// The fiber test's question (see [`crate::fiber`]): whether some triangle on the hole's
    /// vertices that meets `path` is not refused anyway ([`Self::refused_anyway`], whose
    /// refusals are cached for the rest of the fill). False means no valid filling exists
    /// when the path crosses the fan once. `corners` are the hole's vertices at their positions, in hole order.
    pub(crate) fn a_triangle_across_may_pass(
        &mut self,
        path: &FiberPath,
        corners: &[DVec3],
    ) -> bool {
        path.any_triangle_that_may_meet(corners, |t| !self.refused_anyway(t))
    }

    /// Whether the triangle on hole positions `t` is refused whatever the approximation: a
    /// rejection cached already, the topology guards, or [`Filter::refuses_anyway`] (cached
    /// as a rejection: [`Self::accepts`] would refuse it too). No approximation test runs,
    /// so nothing of the mesh around the hole is gathered.
    fn refused_anyway(&mut self, t: [usize; 3]) -> bool {
        let slot = self.slot(t);
        if self.rejected.get(slot).copied().unwrap_or(false) {
            return true;
        }
        let refused = !self.topologically_allowed(t) || {
            self.tests += 1;
            let profile = self.profile(t, false);
            self.filter.refuses_anyway(&profile)
        };
        if refused {
            self.remember_rejection(slot);
        }
        refused
    }

    /// What the filter is told about the triangle on hole positions `t`.
    fn profile(&self, t: [usize; 3], with_placed: bool) -> CandidateProfile<'_> {
        let triangle = self.triangle(t);
        CandidateProfile {
            triangle,
            corners: triangle.map(|v| self.position(v)),
            border_edges: [0, 1, 2].map(|k| self.hole.closing_edge(t[k], t[(k + 1) % 3])),
            approximation: Approximation {
                mesh: self.mesh,
                grid: self.grid,
                placed: if with_placed { &self.placed } else { &[] },
                excluded: self.excluded,
                moved: self.moved,
                extra: self.extra,
                nearby: self.nearby,
            },
        }
    }

    /// Topology guards and the filter, uncached.
    fn test(&mut self, t: [usize; 3], with_placed: bool) -> bool {
        if !self.topologically_allowed(t) {
            return false;
        }
        self.tests += 1;
        let profile = self.profile(t, with_placed);
        self.filter.accepts(&profile)
    }

    /// Places the triangle on hole positions `t`.
    pub fn place(&mut self, t: [usize; 3]) {
        let tri = self.triangle(t);
        self.placed.push(tri);
    }

    /// The triangles placed so far, in order.
    #[must_use]
    pub fn placed(&self) -> &[[VertexId; 3]] {
        &self.placed
    }

    /// Forgets every placed triangle.
    pub fn clear(&mut self) {
        self.placed.clear();
        // Rejections may have come from triangles that are gone now.
        self.rejected.clear();
    }

    /// Tests `t` with one more triangle `extra` placed for the moment, without recording a
    /// rejection (it may be due to `extra`).
    fn accepts_with_extra(&mut self, t: [usize; 3], extra: [usize; 3]) -> bool {
        if self.rejected.get(self.slot(t)).copied().unwrap_or(false) {
            return false;
        }
        self.place(extra);
        let ok = self.test(t, true);
        self.placed.pop();
        ok
    }
}

/// Whether the three vertices already form a face (either orientation).
fn face_exists(m: &HalfEdgeMesh, [a, b, c]: [VertexId; 3]) -> bool {
    [(a, b), (b, a)].into_iter().any(|(u, w)| {
        m.find_halfedge(u, w)
            .and_then(|h| m.face(h))
            .is_some_and(|f| m.face_vertices(f).contains(&c))
    })
}

/// A hole-filling strategy.
pub trait HoleFiller: Sync {
    /// Fills `ctx.hole()` with `hole.len() - 2` triangles, each accepted by the context, or
    /// returns false. On success the triangles are `ctx.placed()`.
    fn fill(&self, ctx: &mut FillContext<'_>) -> bool;
}

/// The paper's single-pass greedy filling (see the module docs). Candidates are ordered by
/// aspect ratio, larger first; ties by their hole positions, lexicographically.
///
/// With `forced_lookahead` (the default, not in the paper) a valid candidate is skipped when
/// a sub-hole it leaves certainly cannot be filled: it has exactly three vertices whose one
/// possible triangle would then be rejected, or more vertices all on one line (exact). The classic case is a hole with three
/// collinear boundary vertices (a straight border): the best-shaped triangle often cuts them
/// off into a degenerate sub-hole. It is still a single pass: nothing placed is ever undone.
/// [`Greedy::PAPER`] turns it off.
#[derive(Clone, Copy, Debug)]
pub struct Greedy {
    /// Skip candidates that leave an unfillable three-vertex sub-hole.
    pub forced_lookahead: bool,
}

impl Default for Greedy {
    fn default() -> Self {
        Self {
            forced_lookahead: true,
        }
    }
}

impl Greedy {
    /// Exactly the paper's single pass, without look-ahead.
    pub const PAPER: Greedy = Greedy {
        forced_lookahead: false,
    };
}

/// All triangles on hole positions, best aspect ratio first (ties: lexicographic).
fn ranked_triangles(ctx: &FillContext<'_>) -> Vec<[usize; 3]> {
    let n = ctx.hole().len();
    let mut all = Vec::with_capacity(n * (n - 1) * (n - 2) / 6);
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                all.push((ctx.aspect([a, b, c]), [a, b, c]));
            }
        }
    }
    // Stable: equal aspect ratios keep the lexicographic order.
    all.sort_by(|x, y| y.0.total_cmp(&x.0));
    all.into_iter().map(|x| x.1).collect()
}

/// The sub-holes that triangle `t` (hole positions, on `poly`) leaves in `poly`.
fn sub_holes(poly: &[usize], t: [usize; 3]) -> [Vec<usize>; 3] {
    // Positions on the sub-hole, increasing (a rotation of `t` when the sub-hole wraps
    // around the hole's start, so the orientation is the same).
    let mut at = t.map(|i| {
        poly.iter()
            .position(|&p| p == i)
            .expect("triangle on the sub-hole")
    });
    at.sort_unstable();
    let (a, b, c) = (at[0], at[1], at[2]);
    [
        poly[a..=b].to_vec(),
        poly[b..=c].to_vec(),
        poly[c..].iter().chain(&poly[..=a]).copied().collect(),
    ]
}

impl Greedy {
    /// Whether placing `t` leaves a sub-hole that certainly cannot be filled: three vertices
    /// whose triangle is rejected, or more, all on one line (exact).
    fn dooms(poly: &[usize], t: [usize; 3], ctx: &mut FillContext<'_>) -> bool {
        let subs = sub_holes(poly, t);
        let pos = |i: usize| ctx.position(ctx.hole.vertices[i]);
        let on_a_line = |s: &Vec<usize>| {
            s.len() > 3
                && s[2..]
                    .iter()
                    .all(|&k| envelope_predicates::collinear(pos(s[0]), pos(s[1]), pos(k)))
        };
        if subs.iter().any(on_a_line) {
            return true;
        }
        if subs.iter().all(|s| s.len() != 3) {
            return false;
        }
        subs.iter().filter(|s| s.len() == 3).any(|s| {
            let mut f = [s[0], s[1], s[2]];
            f.sort_unstable();
            !ctx.accepts_with_extra(f, t)
        })
    }

    /// Fills the sub-hole `poly` (hole positions in cyclic order) recursively.
    fn fill_sub(
        &self,
        ranked: &[[usize; 3]],
        poly: &[usize],
        member: &mut [bool],
        ctx: &mut FillContext<'_>,
    ) -> bool {
        if poly.len() < 3 {
            return true;
        }
        for &i in poly {
            member[i] = true;
        }
        let choice = ranked
            .iter()
            .filter(|t| t.iter().all(|&i| member[i]))
            .find(|&&t| {
                ctx.accepts(t)
                    && !(self.forced_lookahead && poly.len() > 3 && Self::dooms(poly, t, ctx))
            })
            .copied();
        for &i in poly {
            member[i] = false;
        }
        let Some(t) = choice else {
            return false;
        };
        ctx.place(t);
        sub_holes(poly, t)
            .iter()
            .all(|s| self.fill_sub(ranked, s, member, ctx))
    }
}

impl Greedy {
    /// Fills `ctx.hole()` starting with the triangle on hole positions `first` (increasing),
    /// which must pass the context's test like any other, then the up to three sub-holes it
    /// leaves, greedily. The global simplifier (5.3) places its chosen triangle this way.
    pub fn fill_from(&self, ctx: &mut FillContext<'_>, first: [usize; 3]) -> bool {
        let n = ctx.hole().len();
        if n < 3 || first[0] >= first[1] || first[1] >= first[2] || first[2] >= n {
            return false;
        }
        if !ctx.accepts(first) {
            return false;
        }
        ctx.place(first);
        let ranked = ranked_triangles(ctx);
        let poly: Vec<usize> = (0..n).collect();
        let mut member = vec![false; n];
        sub_holes(&poly, first)
            .iter()
            .all(|s| self.fill_sub(&ranked, s, &mut member, ctx))
    }
}

/// Whether the hole's *ears* (triangles on three consecutive hole vertices, the closing edge
/// of an open hole included) allow a filling: with nothing placed, one ear passes the
/// context's test for a triangle, two that are not consecutive for four vertices or more.
///
/// A necessary condition for any filling. Every triangulation of a polygon with `n >= 4`
/// vertices has two ears (Meisters), and never two consecutive ones: the ear at `i` leaves
/// `i` without a diagonal, the ear at `i + 1` gives it the diagonal `i (i + 2)`. By the
/// [`Filter`] contract a triangle rejected with nothing placed is rejected with more placed.
/// So when this fails every filler fails too, and asking it first changes no outcome, only
/// the work: at most `n` tests instead of a failing greedy pass's dozens (at small epsilon
/// most attempts fail, and the second ear turns away most of the holes whose first ear
/// passes). Rejections are cached in the context; the test stops as soon as the condition
/// holds, so when every ear passes it costs two tests (ears 0 and 2), and as soon as it
/// cannot (the ears not rejected yet are one, or two consecutive ones). It runs twice: first
/// with [`Filter::refuses_anyway`] alone (the barriers: no approximation test, nothing of
/// the mesh gathered), then, when that leaves two ears apart, with the full test.
pub(crate) fn ears_allow_a_filling(ctx: &mut FillContext<'_>) -> bool {
    let n = ctx.hole().len();
    if n < 3 {
        return false;
    }
    let ear = |i: usize| {
        let mut t = [i, (i + 1) % n, (i + 2) % n];
        t.sort_unstable();
        t
    };
    if n == 3 {
        return ctx.accepts(ear(0));
    }
    // First with what refuses an ear whatever the approximation (the barriers): when that
    // already leaves no two ears apart, no approximation test runs and nothing around the
    // hole is gathered (at small epsilon most holes end here). The refusals are cached, so
    // the second pass, the full test, asks only about the ears that are left.
    two_ears_apart(n, |i| !ctx.refused_anyway(ear(i))) && two_ears_apart(n, |i| ctx.accepts(ear(i)))
}

/// Whether two ears at cyclic distance 2 or more pass `passes` (`n >= 4` ears, each asked at
/// most once). Even positions first: when every ear passes, the first two asked (0 and 2)
/// are already apart. Stops as soon as the answer is known: two apart passed, or the ears
/// not refused yet are one, or two consecutive ones (with three or more, two are apart).
fn two_ears_apart(n: usize, mut passes: impl FnMut(usize) -> bool) -> bool {
    let apart = |i: usize, j: usize| {
        let d = i.abs_diff(j);
        d != 1 && d != n - 1
    };
    let mut accepted: Vec<usize> = Vec::with_capacity(n);
    let mut open = vec![true; n];
    let mut left = n;
    for i in (0..n).step_by(2).chain((1..n).step_by(2)) {
        if passes(i) {
            if accepted.iter().any(|&j| apart(i, j)) {
                return true;
            }
            accepted.push(i);
        } else {
            open[i] = false;
            left -= 1;
            let cannot = match left {
                0 | 1 => true,
                2 => {
                    let mut two = (0..n).filter(|&k| open[k]);
                    let (a, b) = (two.next().unwrap_or(0), two.next().unwrap_or(0));
                    !apart(a, b)
                }
                _ => false,
            };
            if cannot {
                return false;
            }
        }
    }
    false
}

impl HoleFiller for Greedy {
    fn fill(&self, ctx: &mut FillContext<'_>) -> bool {
        let n = ctx.hole().len();
        if n < 3 || !ears_allow_a_filling(ctx) {
            return false;
        }
        let ranked = ranked_triangles(ctx);
        let poly: Vec<usize> = (0..n).collect();
        let mut member = vec![false; n];
        self.fill_sub(&ranked, &poly, &mut member, ctx)
    }
}

/// Every triangulation of holes with at most `max_vertices` vertices (Catalan(n - 2) of
/// them: 1430 for 10), keeping the valid one that maximises the smallest aspect ratio (ties:
/// the first in enumeration order); [`Greedy`] above the bound.
///
/// A triangulation is valid when each triangle passes the topology guards and the filter
/// with nothing placed, and no two of its triangles meet away from shared vertex ids (exact).
/// This equals placing them one by one with [`crate::filter::EnvelopeFilter`]; a custom filter that
/// looks at `placed` sees it empty here.
#[derive(Clone, Copy, Debug)]
pub struct Exhaustive {
    /// Largest hole tried exhaustively.
    pub max_vertices: usize,
}

impl Default for Exhaustive {
    fn default() -> Self {
        Self { max_vertices: 10 }
    }
}

/// All triangulations of the polygon on positions `i..=j` (with edge `i j`), each as a list
/// of increasing triples.
fn triangulations(
    i: usize,
    j: usize,
    memo: &mut HashMap<(usize, usize), Vec<Vec<[usize; 3]>>>,
) -> Vec<Vec<[usize; 3]>> {
    if j - i < 2 {
        return vec![Vec::new()];
    }
    if let Some(r) = memo.get(&(i, j)) {
        return r.clone();
    }
    let mut out = Vec::new();
    for k in i + 1..j {
        let left = triangulations(i, k, memo);
        let right = triangulations(k, j, memo);
        for l in &left {
            for r in &right {
                let mut t = Vec::with_capacity(l.len() + r.len() + 1);
                t.push([i, k, j]);
                t.extend_from_slice(l);
                t.extend_from_slice(r);
                out.push(t);
            }
        }
    }
    memo.insert((i, j), out.clone());
    out
}

impl HoleFiller for Exhaustive {
    fn fill(&self, ctx: &mut FillContext<'_>) -> bool {
        let n = ctx.hole().len();
        if n > self.max_vertices {
            return Greedy::default().fill(ctx);
        }
        if n < 3 || !ears_allow_a_filling(ctx) {
            return false;
        }
        let mut alone: HashMap<[usize; 3], bool> = HashMap::new();
        let mut apart: HashMap<([usize; 3], [usize; 3]), bool> = HashMap::new();
        let mut best: Option<(f64, Vec<[usize; 3]>)> = None;
        for tri in triangulations(0, n - 1, &mut HashMap::new()) {
            let worst = tri
                .iter()
                .map(|&t| ctx.aspect(t))
                .fold(f64::INFINITY, f64::min);
            if best.as_ref().is_some_and(|b| b.0 >= worst) {
                continue;
            }
            let ok = tri
                .iter()
                .all(|&t| *alone.entry(t).or_insert_with(|| ctx.accepts_with(t, false)))
                && tri.iter().enumerate().all(|(x, &s)| {
                    tri[..x].iter().all(|&t| {
                        *apart.entry((t, s)).or_insert_with(|| {
                            let (p, q) = (ctx.triangle(s), ctx.triangle(t));
                            let pos = |g: [VertexId; 3]| g.map(|v| ctx.position(v));
                            !crate::filter::meet(p, pos(p), q, pos(q))
                        })
                    })
                });
            if ok {
                best = Some((worst, tri));
            }
        }
        let Some((_, tri)) = best else {
            return false;
        };
        ctx.clear();
        for t in tri {
            ctx.place(t);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::TriangleSoup;
    use glam::DVec3;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A flat hexagon (no faces needed: the filters below never look at the mesh).
    fn hexagon() -> (HalfEdgeMesh, Hole) {
        let ring: Vec<DVec3> = (0..6)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::FRAC_PI_3;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .chain([DVec3::ZERO])
            .collect();
        let faces = (0..6u32)
            .map(|k| [6, k, (k + 1) % 6].map(VertexId))
            .collect();
        let m = HalfEdgeMesh::from_soup(&TriangleSoup::new(ring, faces)).unwrap();
        let hole = Hole {
            vertices: (0..6).map(VertexId).collect(),
            open: false,
        };
        (m, hole)
    }

    fn is_ear(t: [VertexId; 3]) -> bool {
        let mut k = t.map(|v| v.0);
        k.sort_unstable();
        matches!(
            k,
            [0, 1, 2] | [1, 2, 3] | [2, 3, 4] | [3, 4, 5] | [0, 4, 5] | [0, 1, 5]
        )
    }

    /// A filter that rejects every ear leaves no triangulation: both fillers fail after
    /// asking for five of the six ears only (0, 2, 4, 1, 3: the last one alone cannot make
    /// a pair), where a greedy pass would try all twenty triangles.
    #[test]
    fn no_ear_no_filling_after_six_tests() {
        let (m, hole) = hexagon();
        let grid = FaceGrid::from_mesh(&m);
        let calls = AtomicUsize::new(0);
        let no_ears = |p: &CandidateProfile<'_>| {
            calls.fetch_add(1, Ordering::Relaxed);
            !is_ear(p.triangle)
        };
        let fillers: [&dyn HoleFiller; 2] = [&Greedy::default(), &Exhaustive::default()];
        for filler in fillers {
            calls.store(0, Ordering::Relaxed);
            let mut ctx = FillContext::new(&m, &grid, &no_ears, &hole);
            assert!(!filler.fill(&mut ctx));
            assert_eq!(calls.load(Ordering::Relaxed), 5);
        }
        // One ear allowed: still none (a hexagon's triangulations have two ears). Two
        // opposite ears: exhaustive finds the triangulation that uses them.
        let allowing = |ears: &'static [[u32; 3]]| {
            move |p: &CandidateProfile<'_>| {
                let mut k = p.triangle.map(|v| v.0);
                k.sort_unstable();
                !is_ear(p.triangle) || ears.contains(&k)
            }
        };
        let one = allowing(&[[2, 3, 4]]);
        let mut ctx = FillContext::new(&m, &grid, &one, &hole);
        assert!(!Exhaustive::default().fill(&mut ctx));
        let two = allowing(&[[0, 1, 2], [3, 4, 5]]);
        let mut ctx = FillContext::new(&m, &grid, &two, &hole);
        assert!(Exhaustive::default().fill(&mut ctx));
        assert_eq!(ctx.placed().len(), 4);
    }

    /// A hexagon's triangulations have two ears that are not consecutive: with only one
    /// ear, or only two consecutive ones (the pair 5, 0 wraps around), both fillers give up
    /// after the ear tests (six, or five when the ears still open after the fifth are
    /// consecutive: 5 and 0); with two apart (0 and 3, or 5 and 1 across the wrap), the
    /// ear test lets them go on and exhaustive filling succeeds.
    #[test]
    fn two_ears_apart_are_needed() {
        let (m, hole) = hexagon();
        let grid = FaceGrid::from_mesh(&m);
        // Ear `i` is the triangle on hole positions i, i + 1, i + 2.
        let ear = |i: u32| {
            let mut k = [i, (i + 1) % 6, (i + 2) % 6];
            k.sort_unstable();
            k
        };
        // Allowed ears, whether fillable, and the ear tests an unfillable one takes (order
        // 0, 2, 4, 1, 3, 5).
        let cases: [(&[u32], bool, usize); 6] = [
            (&[2], false, 6),
            (&[2, 3], false, 6),
            (&[5, 0], false, 5),
            (&[0, 3], true, 0),
            (&[5, 1], true, 0),
            (&[0, 2, 4], true, 0),
        ];
        for (ears, fillable, ear_tests) in cases {
            let allowed: Vec<[u32; 3]> = ears.iter().map(|&i| ear(i)).collect();
            let calls = AtomicUsize::new(0);
            let filter = |p: &CandidateProfile<'_>| {
                calls.fetch_add(1, Ordering::Relaxed);
                let mut k = p.triangle.map(|v| v.0);
                k.sort_unstable();
                !is_ear(p.triangle) || allowed.contains(&k)
            };
            let fillers: [&dyn HoleFiller; 2] = [&Greedy::default(), &Exhaustive::default()];
            for filler in fillers {
                calls.store(0, Ordering::Relaxed);
                let mut ctx = FillContext::new(&m, &grid, &filter, &hole);
                let filled = filler.fill(&mut ctx);
                if fillable {
                    assert!(calls.load(Ordering::Relaxed) > 6, "ears {ears:?}");
                } else {
                    assert!(!filled, "ears {ears:?}");
                    assert_eq!(calls.load(Ordering::Relaxed), ear_tests, "ears {ears:?}");
                }
            }
            let mut ctx = FillContext::new(&m, &grid, &filter, &hole);
            assert_eq!(
                Exhaustive::default().fill(&mut ctx),
                fillable,
                "ears {ears:?}"
            );
        }
    }
}
