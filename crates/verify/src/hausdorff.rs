//! One-sided certified Hausdorff distance: every point of `from` within `eps` of `to`?
//!
//! Branch and bound over the triangles of `from` in the spirit of bounded-error Hausdorff
//! algorithms (Tang, Lee, Kim, "Interactive Hausdorff distance computation for general
//! polygonal models", SIGGRAPH 2009; CGAL's `bounded_error_Hausdorff_distance`), with every
//! decision taken by an exact predicate:
//!
//! * **Proof.** `p -> dist(p, t)` is convex for one triangle `t`, so its maximum over a
//!   triangle `S` is reached at a corner of `S`. If some `t` of `to` has all three corners of
//!   `S` within `eps - delta` (exact `cmp_point_triangle`), every point of `S` is.
//! * **Exact cover.** Sub-triangles are the 4-way midpoint subdivision of `T`, done on exact
//!   points `(i a + j b + k c) / 2^L`. We evaluate the predicates on the corners rounded to f64
//!   and carry, per corner, a proved bound `delta` on the distance between the f64 corner and
//!   the exact one (0 whenever the midpoints were exact in f64). A point `p*` of an exact
//!   sub-triangle has an f64 partner `p'` (same barycentric weights on the f64 corners) with
//!   `|p* - p'| <= max delta` and `p'` in the f64 sub-triangle, so `dist(p*, to) <=
//!   dist(p', t) + delta <= eps`. The exact sub-triangles partition `T`, hence the proof covers
//!   `T` exactly.
//! * **Cuts.** A sub-triangle no single triangle covers may still be proved in two pieces:
//!   cut by a plane through the shared edge of two triangles (exact sides, f64 crossing
//!   points with proved error bounds), each piece against the triangle on its side, by its
//!   vertices (`Search::split_within_f64`); ties at exactly `eps` use the same cut in
//!   rationals (`Search::split_within_exactly`). Over a vertex of `to`, the corners are
//!   nearest to faces of its fan that share only that vertex: up to `cuts::PIECE_CUTS` rounds
//!   of cuts, through shared edges and through shared corners, each piece an f64 polygon
//!   taken exactly and proved against one triangle, the crossing points' error bounds added
//!   up over the rounds (`Search::pieces_within`). Their vertices are lower-bound
//!   candidates too, less their error bounds.
//! * **Cells.** Where `to`'s triangles are several times larger than `eps`, a sub-triangle
//!   is proved only where it is within `eps` of one of them, and a thin face crosses many:
//!   subdividing takes many sub-triangles along every edge it crosses. Instead, the same
//!   chord cuts go on through the planes through the edges of the triangles near a piece
//!   and their neighbours (near a surface they bound the regions nearest to each
//!   triangle), the most even cut first, until every piece is proved against one triangle
//!   by its vertices (`Search::cells_within`): a few pieces per triangle under the face. A
//!   piece it cannot settle within its budget sends the sub-triangle back to subdividing.
//! * **Witness.** A violation is reported only for a point exactly on `T`: a corner whose f64
//!   value is exact (`delta == 0`, checked with the f64 predicates) or, otherwise, the exact
//!   rational corner, checked with rational arithmetic. It must exceed `eps` against every
//!   triangle of `to` whose outward-rounded box is within `eps (+ delta)` of it.
//! * **Tolerance.** `eps` is the user's double; `dist <= eps` is decided against the exact
//!   rational `eps^2`: proofs compare with the largest double `<= (eps - delta)^2`, witnesses
//!   with the smallest double `>= eps^2` and, in the gap between the two, with rationals.
//! * **Shared triangles.** A triangle of `from` whose three corners are, as a multiset,
//!   bitwise equal to the corners of a triangle of `to` is the same closed point set: its
//!   distance is 0, proved without any predicate (simplifiers keep many input triangles).
//!   Only bit equality is used, so `-0.0` against `0.0` merely misses the shortcut.
//!
//! * **Per-face bounds** (the error map, only when asked). A face's upper bound is the
//!   largest bound of the pieces that settled it: each proved piece's certified value (the
//!   exact close calls and cuts give `eps` itself), `0` for a shared triangle, and, for the
//!   pieces left when the face has a witness or runs out of budget, a certified bound without
//!   further subdivision. Its lower bound is the certified distance of the face's farthest
//!   exact corner candidate (or its witness). Refinement stops as soon as a piece is proved
//!   within `eps`, so the upper bound is just below `eps` wherever some piece needed
//!   subdividing; `Search::tighten` then decides the face again at tolerances between its
//!   bounds (bisection, a few rounds): a proof lowers the upper bound, a witness raises the
//!   lower one, each by the same exact machinery. All of it is spent only when asked.
//!
//! Speed without changing what is proved: faces are processed in fixed chunks, each chunk
//! sequentially, so the nearest-triangle search of a face starts from the triangle found for
//! the previous face (spatial coherence prunes the BVH descent; the search result is only an
//! estimate that the exact predicates then check), and scratch buffers are reused. A
//! sub-triangle's candidates drop the triangles whose estimated distance to one of its
//! corners exceeds eps plus its diameter (widely rounded: a triangle dropped in error costs
//! a proof, never a wrong one, as witnesses ask the tree), and exact tests are skipped
//! where the estimates already promise a bound above eps.

use envelope_mesh::FaceId;
use envelope_predicates::bvh::{Aabb, Bvh, NodeId, NodeKind};
use envelope_predicates::exact_num::Rational;
use envelope_predicates::{Sign, cmp_point_triangle, next_up};
use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use crate::numeric::{
    RPoint, TriNormal, add_up, approx_sq_dist, approx_sq_dist_with, barycentric_point, rational,
    rpoint, sq_dist_exact, sqrt_down, sqrt_up, square_down, square_up,
};
use crate::{FaceBound, OneSided, Verdict, Witness};

mod cuts;
mod slab;

use slab::Slab;

/// Subdivision depth limit (barycentric numerators stay in `u64`).
const MAX_LEVEL: u32 = 60;
/// Tiny sub-triangles (diameter below `eps * 2^-10`) examined per face at most. A region at
/// exactly epsilon along a curve that the exact cut cannot prove (the nearest triangles
/// share no edge) would otherwise be subdivided down to the resolution all along the curve:
/// millions of exact tests. Larger sub-triangles count only against the looser
/// [`MAX_FACE_SUBDIVISIONS`]: a big face over many small ones at a small epsilon
/// legitimately needs many of them.
/// What is left when the budget runs out is undecided, never proved.
const MAX_FACE_TINY: u64 = 1 << 16;
/// All sub-triangles of a face, tiny or not, are bounded too: by the pass's tiny budget, at
/// most this, plus 64 per triangle the face is compared with (legitimate work grows with
/// those triangles).
const MAX_FACE_SUBDIVISIONS: u64 = 1 << 14;
/// The first pass's budget (see [`one_sided`]): faces it leaves undecided are examined again
/// with [`MAX_FACE_TINY`] only when no face has a witness.
const FIRST_PASS_TINY: u64 = 1 << 10;
/// From this depth on, a sub-triangle that no single triangle covers is also tried with an
/// exact cut between two (see `Search::split_within_exactly`).
const SPLIT_LEVEL: u32 = 16;

/// Candidates of a sub-triangle at most for a proof by cells (`Search::cells_within`):
/// each cut computes its new points' distances to those near the piece.
const CELL_CANDIDATES: usize = 128;
/// The candidates' mean box extent, in eps, from which a proof by cells is tried (at 2 to 2.5,
/// bunny00 and armadillo at 1/4 %, subdividing was faster; at 3.4, the 10M torus at 1/64 %,
/// the cells were).
const CELL_EXTENT: f64 = 3.0;

/// Faces per sequential chunk of the parallel loop (the nearest-triangle hint is carried
/// within a chunk).
const CHUNK: usize = 256;

/// The corners of a triangle as bit patterns, sorted: equal keys mean equal corner multisets,
/// hence the same closed triangle.
type TriKey = [[u64; 3]; 3];

fn tri_key(t: &[DVec3; 3]) -> TriKey {
    let [mut a, mut b, mut c] = t.map(|p| p.to_array().map(f64::to_bits));
    // A three-element sorting network.
    if b < a {
        std::mem::swap(&mut a, &mut b);
    }
    if c < b {
        std::mem::swap(&mut b, &mut c);
    }
    if b < a {
        std::mem::swap(&mut a, &mut b);
    }
    [a, b, c]
}

/// A multiply-rotate mix of a key (not adversarial input: a collision only costs a probe).
fn key_hash(k: &TriKey) -> u64 {
    let mut h = 0u64;
    for x in k.as_flattened() {
        h = (h.rotate_left(23) ^ x).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
    h ^ (h >> 29)
}

/// The target's triangles by corner key: open addressing with linear probing over face
/// indices (plus one; 0 is empty). A hit is confirmed by comparing the full keys.
struct KeyTable {
    slots: Vec<u32>,
    mask: usize,
}

impl KeyTable {
    /// The table of `tris` and the triangles kept: each closed triangle once, in first
    /// occurrence order (a repeated one would make every probe for its key walk the others:
    /// quadratic for a stack of copies).
    fn dedup(tris: Vec<[DVec3; 3]>) -> (KeyTable, Vec<[DVec3; 3]>) {
        let size = (2 * tris.len()).next_power_of_two().max(2);
        let mut table = KeyTable {
            slots: vec![0u32; size],
            mask: size - 1,
        };
        let mut kept: Vec<[DVec3; 3]> = Vec::with_capacity(tris.len());
        for t in tris {
            let k = tri_key(&t);
            let mut h = key_hash(&k) as usize & table.mask;
            let fresh = loop {
                match table.slots[h] {
                    0 => break true,
                    i if tri_key(&kept[i as usize - 1]) == k => break false,
                    _ => h = (h + 1) & table.mask,
                }
            };
            if fresh {
                kept.push(t);
                table.slots[h] = kept.len() as u32;
            }
        }
        (table, kept)
    }

    fn contains(&self, tris: &[[DVec3; 3]], t: &[DVec3; 3]) -> bool {
        let k = tri_key(t);
        let mut h = key_hash(&k) as usize & self.mask;
        loop {
            match self.slots[h] {
                0 => return false,
                i if tri_key(&tris[i as usize - 1]) == k => return true,
                _ => h = (h + 1) & self.mask,
            }
        }
    }
}

/// The mesh distances are measured to: its triangles, their boxes, a BVH and the set of its
/// triangles' corner keys.
pub(crate) struct Target {
    /// The distinct triangles (a repeated one changes no distance).
    tris: Vec<[DVec3; 3]>,
    /// Per triangle of `tris`, what the distance estimate needs of it alone.
    normals: Vec<TriNormal>,
    boxes: Vec<Aabb>,
    bvh: Bvh,
    keys: KeyTable,
    /// Every face is in `tris`, in face order.
    all_faces: bool,
}

impl Target {
    pub(crate) fn new(positions: &[DVec3], faces: &[[u32; 3]]) -> Target {
        Target::from_triangles(
            faces
                .iter()
                .map(|f| f.map(|i| positions[i as usize]))
                .collect(),
        )
    }

    /// The target made of `tris` (repeated ones are kept once).
    pub(crate) fn from_triangles(tris: Vec<[DVec3; 3]>) -> Target {
        let faces = tris.len();
        let (keys, tris) = KeyTable::dedup(tris);
        let boxes: Vec<Aabb> = tris.iter().map(|&t| Aabb::from_triangle(t)).collect();
        let normals = tris.iter().map(TriNormal::new).collect();
        let bvh = Bvh::new(&boxes);
        Target {
            all_faces: tris.len() == faces,
            normals,
            tris,
            boxes,
            bvh,
            keys,
        }
    }

    /// The BVH over the target's triangle boxes (item = face index), when every face is a
    /// distinct triangle (else the distance search's tree holds each triangle once).
    pub(crate) fn bvh(&self) -> Option<&Bvh> {
        self.all_faces.then_some(&self.bvh)
    }

    /// Whether the target has no triangle.
    pub(crate) fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Calls `f` with the number of each of the target's (distinct) triangles whose box
    /// overlaps `query` ([`Target::triangle`] gives it).
    pub(crate) fn for_each_overlapping(&self, query: &Aabb, f: impl FnMut(u32)) {
        self.bvh.for_each_overlapping(query, f);
    }

    /// The largest side of any triangle's box (0 when empty).
    pub(crate) fn largest_extent(&self) -> f64 {
        self.boxes
            .iter()
            .map(|b| (b.max - b.min).max_element())
            .fold(0.0, f64::max)
    }

    /// [`approx_sq_dist`] from `p` to the triangle numbered `t`.
    pub(super) fn sq_dist(&self, p: DVec3, t: u32) -> f64 {
        approx_sq_dist_with(p, &self.tris[t as usize], &self.normals[t as usize])
    }

    /// The triangle numbered `t`.
    pub(crate) fn triangle(&self, t: u32) -> [DVec3; 3] {
        self.tris[t as usize]
    }

    /// Whether `t` is (bitwise) one of the target's triangles: then its distance is 0.
    fn has_triangle(&self, t: &[DVec3; 3]) -> bool {
        self.keys.contains(&self.tris, t)
    }

    /// Whether some point of `points` is estimated (f64, nearest-triangle search) farther
    /// than `eps` from the target: an estimate, for shortcuts that may only refuse.
    pub(crate) fn some_point_beyond(&self, points: &[DVec3], eps: f64) -> bool {
        let mut stack = Vec::new();
        let mut hint = None;
        let e2 = eps * eps;
        points
            .iter()
            .any(|&p| match self.some_within(p, hint, e2, &mut stack) {
                Some(t) => {
                    hint = Some(t);
                    false
                }
                None => true,
            })
    }

    /// Some triangle whose estimated squared distance to `p` is at most `e2`, trying `hint`
    /// first; `None` when there is none. The question of [`Target::nearest_approx_from`]
    /// with `d2 <= e2`, answered at the first triangle within reach instead of the nearest.
    fn some_within(
        &self,
        p: DVec3,
        hint: Option<u32>,
        e2: f64,
        stack: &mut Vec<NodeId>,
    ) -> Option<u32> {
        if let Some(t) = hint
            && self.sq_dist(p, t) <= e2
        {
            return Some(t);
        }
        stack.clear();
        stack.push(self.bvh.root()?);
        while let Some(n) = stack.pop() {
            if self.bvh.bounds(n).sq_distance_lower_bound(p) > e2 {
                continue;
            }
            match self.bvh.kind(n) {
                NodeKind::Leaf(items) => {
                    if let Some(&i) = items.iter().find(|&&i| self.sq_dist(p, i) <= e2) {
                        return Some(i);
                    }
                }
                NodeKind::Interior(a, b) => self.push_nearer_last(stack, p, a, b),
            }
        }
        None
    }

    /// Pushes the children `a` and `b` of a tree node, the one nearer to `p` last (so that
    /// it is searched first).
    fn push_nearer_last(&self, stack: &mut Vec<NodeId>, p: DVec3, a: NodeId, b: NodeId) {
        let (da, db) = (
            self.bvh.bounds(a).sq_distance_lower_bound(p),
            self.bvh.bounds(b).sq_distance_lower_bound(p),
        );
        if da < db {
            stack.extend([b, a]);
        } else {
            stack.extend([a, b]);
        }
    }

    /// Approximate nearest triangle to `p` (f64 branch and bound); `None` when empty.
    fn nearest_approx(&self, p: DVec3) -> Option<(u32, f64)> {
        self.nearest_approx_from(p, None, &mut Vec::new())
    }

    /// [`Target::nearest_approx`] starting from the candidate `hint` (it only prunes the
    /// descent), with a reusable stack.
    fn nearest_approx_from(
        &self,
        p: DVec3,
        hint: Option<u32>,
        stack: &mut Vec<NodeId>,
    ) -> Option<(u32, f64)> {
        let mut best: Option<(u32, f64)> = hint.map(|t| (t, self.sq_dist(p, t)));
        if best.is_some_and(|(_, d)| d.is_nan()) {
            best = None;
        }
        stack.clear();
        stack.push(self.bvh.root()?);
        while let Some(n) = stack.pop() {
            let lb = self.bvh.bounds(n).sq_distance_lower_bound(p);
            if best.is_some_and(|(_, d)| lb > d) {
                continue;
            }
            match self.bvh.kind(n) {
                NodeKind::Leaf(items) => {
                    for &i in items {
                        let d = self.sq_dist(p, i);
                        if best.is_none_or(|(_, b)| d < b) {
                            best = Some((i, d));
                        }
                    }
                }
                NodeKind::Interior(a, b) => self.push_nearer_last(stack, p, a, b),
            }
        }
        best
    }

    /// A proved lower bound of `dist(p, to)` (`f64::INFINITY` when `to` is empty).
    fn certified_lower(&self, p: DVec3) -> f64 {
        let Some((_, d2)) = self.nearest_approx(p) else {
            return f64::INFINITY;
        };
        // Tight first (a witness just beyond epsilon needs it), then looser: the approximate
        // nearest distance may be off by its rounding, or the nearest triangle missed.
        let shrink = [1.0 - 2f64.powi(-50), 1.0 - 2f64.powi(-20), 0.5, 0.25, 0.125];
        for factor in shrink {
            let l2 = d2 * factor;
            if l2.is_nan() || l2 <= 0.0 {
                return 0.0;
            }
            let r = next_up(sqrt_up(l2) * (1.0 + 2f64.powi(-40)));
            let query = Aabb::from_points(&[p]).inflated(r);
            let mut ok = true;
            self.bvh.for_each_overlapping(&query, |t| {
                if ok && cmp_point_triangle(p, self.tris[t as usize], l2) == Sign::Negative {
                    ok = false;
                }
            });
            // Triangles outside the query box are farther than r >= sqrt(l2).
            if ok {
                return sqrt_down(l2);
            }
        }
        0.0
    }
}

/// `eps` and its squares, exact and rounded both ways.
pub(crate) struct Tolerance {
    eps: f64,
    /// Largest double `<= eps^2`.
    e2lo: f64,
    /// Smallest double `>= eps^2`.
    e2hi: f64,
    /// `eps^2`, exactly.
    e2: Rational,
    resolution: f64,
}

impl Tolerance {
    pub(crate) fn new(eps: f64, resolution: f64) -> Tolerance {
        let e = rational(eps);
        Tolerance {
            eps,
            e2lo: square_down(eps),
            e2hi: square_up(eps),
            e2: (&e * &e),
            resolution,
        }
    }

    /// The tolerance.
    pub(crate) fn eps(&self) -> f64 {
        self.eps
    }

    /// Largest double `<= (eps - delta)^2`, or `None` when `eps - delta` may be <= 0.
    fn proof_threshold(&self, delta: f64) -> Option<f64> {
        let theta = if delta == 0.0 {
            self.eps
        } else {
            envelope_predicates::next_down(self.eps - delta)
        };
        (theta > 0.0).then(|| square_down(theta))
    }

    /// The value an estimated squared distance `m` is certified against: a little above `m`
    /// (so the filtered predicates decide it), and not below `eps^2 * 2^-40` (so that points
    /// lying exactly on a triangle are not compared with a near-zero bound, which only the
    /// rational fallback could decide).
    fn certification_value(&self, m: f64) -> f64 {
        (m * (1.0 + 2f64.powi(-20)))
            .max(self.e2lo * 2f64.powi(-40))
            .max(f64::MIN_POSITIVE)
    }

    /// [`Self::certification_value`] for a cut piece's point, not below `eps^2 * 2^-20`:
    /// crossing points often lie exactly on a triangle (coplanar faces), and the higher
    /// floor keeps the filtered predicate decisive there.
    fn piece_value(&self, m: f64) -> f64 {
        self.certification_value(m).max(self.e2lo * 2f64.powi(-20))
    }

    /// `dist(p, t) > eps`, exactly, for an f64 point.
    fn exceeds(&self, p: DVec3, t: [DVec3; 3]) -> bool {
        if cmp_point_triangle(p, t, self.e2hi) == Sign::Positive {
            return true;
        }
        if self.e2lo == self.e2hi || cmp_point_triangle(p, t, self.e2lo) != Sign::Positive {
            return false;
        }
        sq_dist_exact(&rpoint(p), &t) > self.e2
    }
}

/// `dist(p, t)^2 <= e2`, exactly: the f64 shortcuts [`near_vertex`], [`near_face`] and
/// [`near_edge`] (each only ever says yes when it is so), then the exact predicate.
fn within(p: DVec3, t: &[DVec3; 3], e2: f64) -> bool {
    near_face(p, t, e2)
        || near_vertex(p, t, e2)
        || near_edge(p, t, e2)
        || cmp_point_triangle(p, *t, e2) != Sign::Positive
}

/// A sufficient test for `dist(p, t)^2 <= e2` in f64 with a rigorous error bound: the
/// squared distance to a vertex of `t`, rounded up. It spares the exact predicate its worst
/// case, a point exactly on a vertex of `t` (zero signs defeat floating-point filters).
fn near_vertex(p: DVec3, t: &[DVec3; 3], e2: f64) -> bool {
    t.iter().any(|&v| {
        // Each difference, square and sum is rounded to nearest: relative error below 6u;
        // `1 + 16 eps` covers it, and `MIN_POSITIVE` covers underflow of the squares.
        let s = (p - v).length_squared();
        s * (1.0 + 16.0 * f64::EPSILON) + 4.0 * f64::MIN_POSITIVE <= e2
    })
}

/// A sufficient test for `dist(p, t)^2 <= e2` in f64 with a rigorous error bound, like
/// [`near_edge`] for the inside of `t`: the distance from `p` to an f64 point `q` within a
/// proved bound of the exact point `a + v (b - a) + w (c - a)`, for the f64 barycentrics
/// `v, w >= 0`, `v + w < 1` of `p`'s projection. Most points a proof asks about lie over
/// the inside of a triangle; the exact predicate decides their region with several filtered
/// determinants first.
fn near_face(p: DVec3, t: &[DVec3; 3], e2: f64) -> bool {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (ab.dot(ab), ab.dot(ac), ac.dot(ac));
    let (d20, d21) = (ap.dot(ab), ap.dot(ac));
    let den = d00 * d11 - d01 * d01;
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    // fl(v + w) <= 1 - 4 EPSILON gives v + w < 1 exactly; NaN fails every comparison.
    if !(v >= 0.0 && w >= 0.0 && v + w <= 1.0 - 4.0 * f64::EPSILON) {
        return false;
    }
    let q = a + ab * v + ac * w;
    let s = (p - q).length_squared();
    if s.is_nan() || s > e2 {
        return false;
    }
    // q against the exact point: per coordinate at most about 16u max(|a|, |b|, |c|) (two
    // differences, two products and two sums, v and w in [0, 1]), times sqrt 3 over the
    // coordinates, 3.1e-15 max; 4e-15 (|a| + |b| + |c|) covers it, MIN_POSITIVE the
    // underflows.
    let size = a.abs().max_element() + b.abs().max_element() + c.abs().max_element();
    let off = add_up(4e-15 * size, f64::MIN_POSITIVE);
    let s = s * (1.0 + 16.0 * f64::EPSILON) + 4.0 * f64::MIN_POSITIVE;
    let r = add_up(sqrt_up(s), off);
    square_up(r) <= e2
}

/// A sufficient test for `dist(p, t)^2 <= e2` in f64 with a rigorous error bound, like
/// [`near_vertex`] for the edges of `t`: the distance from `p` to an f64 point `q` that lies
/// within a proved bound of the exact point `a + tau (b - a)` of an edge (`tau` in `[0, 1]`).
/// Points on an edge's line (midpoints of an approximation's edge that runs along an edge of
/// `t`, cut points on a shared edge) are the exact predicate's slow case.
fn near_edge(p: DVec3, t: &[DVec3; 3], e2: f64) -> bool {
    (0..3).any(|k| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let ab = b - a;
        let l2 = ab.length_squared();
        if l2.is_nan() || l2 <= 0.0 || l2.is_infinite() {
            return false;
        }
        let tau = ((p - a).dot(ab) / l2).clamp(0.0, 1.0);
        let q = a + ab * tau;
        let s = (p - q).length_squared();
        if s.is_nan() || s > e2 {
            // Cannot pass the test below (and NaN): the common case, kept cheap.
            return false;
        }
        // q against the exact a + tau (b - a): three roundings per coordinate, each below
        // u (|a| + |b|); 1e-15 (|a| + |b|) covers their Euclidean norm.
        let off = 1e-15 * (a.abs().max_element() + b.abs().max_element());
        let s = s * (1.0 + 16.0 * f64::EPSILON) + 4.0 * f64::MIN_POSITIVE;
        let r = add_up(sqrt_up(s), off);
        square_up(r) <= e2
    })
}

/// A sub-triangle corner: the f64 point, a bound on its distance to the exact corner, and the
/// exact corner's barycentric numerators (denominator `2^level`).
#[derive(Clone, Copy, Debug)]
struct Corner {
    p: DVec3,
    delta: f64,
    bary: [u64; 3],
}

struct Sub {
    c: [Corner; 3],
    level: u32,
    cands: Vec<u32>,
    /// `d[3 i + j]`: approximate squared distance of corner `j` to `cands[i]` (infinite for
    /// NaN). Computed once per point: a midpoint is a corner of three children. One
    /// allocation per sub-triangle (millions of them).
    d: Vec<f64>,
}

impl Sub {
    /// The estimated squared distance of corner `j` to `cands[i]`.
    fn dist(&self, j: usize, i: usize) -> f64 {
        self.d[3 * i + j]
    }
}

/// The rounded midpoint of two corners, with its error bound.
fn midpoint(u: &Corner, v: &Corner) -> Corner {
    let mut rho = 0.0f64;
    let mut m = [0.0; 3];
    for k in 0..3 {
        let (x, y) = (u.p[k], v.p[k]);
        let s = x + y;
        // TwoSum: x + y = s + e exactly.
        let bb = s - x;
        let e = (x - (s - bb)) + (y - bb);
        let h = s * 0.5;
        // |(x+y)/2 - h| <= |e|/2 + |s/2 - h|; both terms are bounded by |e| + |s - 2h|.
        let halving = (s - (h + h)).abs();
        rho = add_up(rho, add_up(e.abs(), halving));
        m[k] = h;
    }
    Corner {
        p: DVec3::from_array(m),
        delta: add_up(rho, add_up(u.delta * 0.5, v.delta * 0.5)),
        bary: [
            u.bary[0] + v.bary[0],
            u.bary[1] + v.bary[1],
            u.bary[2] + v.bary[2],
        ],
    }
}

/// A lower-bound candidate: (approximate squared distance, f64 point, a proved bound on its
/// distance to a point of `from`, 0 for a point on it).
type Low = (f64, DVec3, f64);

/// The certified lower bound a candidate gives: its point's certified distance to `to`, less
/// its error.
fn low_bound(target: &Target, &(_, p, err): &Low) -> f64 {
    let d = target.certified_lower(p);
    if err == 0.0 {
        d
    } else {
        envelope_predicates::next_down(d - err).max(0.0)
    }
}

/// Keeps the farther of two lower-bound candidates (`best` on ties).
fn farther(best: &mut Option<Low>, other: Option<Low>) {
    if let Some(o) = other
        && best.is_none_or(|b| o.0 > b.0)
    {
        *best = Some(o);
    }
}

/// Everything learnt about one triangle of `from`.
#[derive(Default)]
struct FaceResult {
    upper: f64,
    /// Best lower-bound candidate ([`Low`]).
    lower_candidate: Option<Low>,
    witness: Option<Witness>,
    undecided: bool,
    subdivisions: u64,
}

struct Search<'a> {
    target: &'a Target,
    tol: &'a Tolerance,
    /// Tiny sub-triangles examined per face at most.
    tiny_budget: u64,
}

/// Per sub-triangle estimates: the triangle minimising the largest corner distance.
struct Estimate {
    best: Option<(u32, f64)>,
    corner_min: [f64; 3],
    /// The triangle nearest to each corner (`u32::MAX`: none).
    corner_best: [u32; 3],
}

impl Estimate {
    /// The triangles nearest to the corners, each once, in corner order (no allocation: it
    /// is asked for on every sub-triangle a cut is tried on).
    fn nearest(&self) -> SmallVec<[u32; 3]> {
        let mut ts = SmallVec::new();
        for t in self.corner_best {
            if t != u32::MAX && !ts.contains(&t) {
                ts.push(t);
            }
        }
        ts
    }
}

impl Search<'_> {
    /// Approximate squared distance of `p` to the target's triangle `t` (NaN as infinity).
    fn sq_dist_or_inf(&self, p: DVec3, t: u32) -> f64 {
        let d = self.target.sq_dist(p, t);
        if d.is_nan() { f64::INFINITY } else { d }
    }

    fn estimate(&self, s: &Sub) -> Estimate {
        let mut best: Option<(u32, f64)> = None;
        let mut corner_min = [f64::INFINITY; 3];
        let mut corner_best = [u32::MAX; 3];
        for (i, &t) in s.cands.iter().enumerate() {
            let mut worst = 0.0f64;
            for j in 0..3 {
                let d = s.dist(j, i);
                if d < corner_min[j] {
                    corner_min[j] = d;
                    corner_best[j] = t;
                }
                worst = worst.max(d);
            }
            if best.is_none_or(|(_, b)| worst < b) {
                best = Some((t, worst));
            }
        }
        Estimate {
            best,
            corner_min,
            corner_best,
        }
    }

    /// Whether the candidates are large enough against eps for [`Self::cells_within`] to
    /// beat subdividing: their mean box extent at least [`CELL_EXTENT`] eps. Only a choice
    /// of method; both prove the same.
    fn cells_pay(&self, cands: &[u32]) -> bool {
        let extent: f64 = cands
            .iter()
            .map(|&t| {
                let b = &self.target.boxes[t as usize];
                (b.max - b.min).max_element()
            })
            .sum();
        extent >= CELL_EXTENT * self.tol.eps * cands.len() as f64
    }

    fn corners_within(&self, s: &Sub, t: u32, e2: f64) -> bool {
        let tri = self.target.tris[t as usize];
        s.c.iter().all(|c| within(c.p, &tri, e2))
    }

    /// A proved upper bound of `max dist(p, t)` over the f64 sub-triangle, from the
    /// approximate value `m` (`None` if the estimate was too far off to certify).
    fn certify_with(&self, s: &Sub, t: u32, m: f64) -> Option<f64> {
        let c = self.tol.certification_value(m);
        self.corners_within(s, t, c).then(|| sqrt_up(c))
    }

    /// A proved upper bound of `dist(p, to)` over the exact sub-triangle (no subdivision).
    fn upper_bound(&self, s: &Sub, est: &Estimate, delta: f64) -> f64 {
        if let Some((t, m)) = est.best
            && let Some(u) = self.certify_with(s, t, m)
        {
            return add_up(u, delta);
        }
        let Some((t, _)) = self.target.nearest_approx(s.c[0].p) else {
            return f64::INFINITY;
        };
        let tri = &self.target.tris[t as usize];
        let mut m =
            s.c.iter()
                .map(|c| approx_sq_dist(c.p, tri))
                .fold(0.0, f64::max);
        for _ in 0..64 {
            if let Some(u) = self.certify_with(s, t, m) {
                return add_up(u, delta);
            }
            m = m * 2.0 + f64::MIN_POSITIVE;
        }
        f64::INFINITY
    }

    /// Proves the sub-triangle within `eps`, returning a proved upper bound. `face` is the
    /// whole triangle the sub-triangle's barycentric corners refer to.
    /// A proof by cut pieces (`pieces_within`) leaves in `low` its farthest piece vertex.
    fn prove(
        &self,
        face: &[DVec3; 3],
        s: &Sub,
        est: &Estimate,
        delta: f64,
        low: &mut Option<Low>,
    ) -> Option<f64> {
        let (t, m) = est.best?;
        // Largest double below (eps - delta)^2; 0 when eps - delta may be <= 0, so that only
        // the exact corners below can prove anything.
        let e2 = self.tol.proof_threshold(delta).unwrap_or(0.0);
        let c = self.tol.certification_value(m);
        if c <= e2 && self.corners_within(s, t, c) {
            return Some(add_up(sqrt_up(c), delta));
        }
        // No single triangle: each corner within epsilon of its nearest one, to the
        // estimate's precision, and they differ: cut by a plane between two of them.
        if est.corner_min.iter().all(|&d| d < self.tol.e2lo) {
            if let Some(u) = self.split_within_f64(s, est, delta) {
                return Some(u);
            }
            if let Some((u, far)) = self.pieces_within(s, est, delta) {
                farther(low, Some(far));
                return Some(u);
            }
        }
        let near = self.tol.e2hi * (1.0 + 2f64.powi(-20));
        // The split below is for ties (a corner at epsilon, to the estimate's precision) and
        // for deep sub-triangles; elsewhere subdividing settles a sub-triangle sooner than
        // exact cuts would.
        let tie = est
            .corner_min
            .iter()
            .any(|&d| d >= self.tol.e2lo * (1.0 - 2f64.powi(-20)));
        let split = (tie || s.level >= SPLIT_LEVEL) && est.corner_min.iter().all(|&d| d <= near);
        if m > near && !split {
            return None;
        }
        // Close call: try the few triangles whose estimate is near the threshold exactly,
        // then pairs of the triangles nearest to each corner.
        let mut close: Vec<(f64, u32)> = Vec::new();
        for (i, &t) in s.cands.iter().enumerate() {
            let w = s.dist(0, i).max(s.dist(1, i)).max(s.dist(2, i));
            if w <= near {
                close.push((w, t));
            }
        }
        close.sort_by(|a, b| a.0.total_cmp(&b.0));
        close.truncate(4);
        if close
            .iter()
            .any(|&(_, t)| self.corners_within_exactly(face, s, t, e2))
        {
            return Some(self.tol.eps);
        }
        (split && self.split_within_exactly(face, s, &est.nearest())).then_some(self.tol.eps)
    }

    /// Every exact corner of the sub-triangle within `eps` of `t` (then all of it is, by
    /// convexity of the distance to a triangle). A corner's f64 point within `eps - delta`
    /// (`e2`, rounded down) settles it; otherwise the exact corner goes to rationals, so a
    /// tie at exactly `eps` (parallel faces `eps` apart) is proved rather than subdivided.
    fn corners_within_exactly(&self, face: &[DVec3; 3], s: &Sub, t: u32, e2: f64) -> bool {
        let tri = self.target.tris[t as usize];
        s.c.iter().all(|c| {
            if e2 > 0.0 && cmp_point_triangle(c.p, tri, e2) != Sign::Positive {
                return true;
            }
            let exact = if c.delta == 0.0 {
                rpoint(c.p)
            } else {
                barycentric_point(face, c.bary, s.level)
            };
            sq_dist_exact(&exact, &tri) <= self.tol.e2
        })
    }

    /// Checks whether a corner is an exact witness of `dist > eps`.
    fn witness(&self, face: FaceId, tri: &[DVec3; 3], c: &Corner, level: u32) -> Option<Witness> {
        let target = self.target;
        if c.delta == 0.0 {
            let query = Aabb::from_points(&[c.p]).inflated(self.tol.eps);
            let mut ok = true;
            target.bvh.for_each_overlapping(&query, |t| {
                ok = ok && self.tol.exceeds(c.p, target.tris[t as usize]);
            });
            return ok.then(|| Witness {
                face,
                barycentric: c.bary,
                level,
                point: c.p,
                exact_f64: true,
                distance: target.certified_lower(c.p).max(self.tol.eps),
            });
        }
        let exact: RPoint = barycentric_point(tri, c.bary, level);
        // Boxes farther than eps + delta from the f64 corner are farther than eps from it.
        let reach = add_up(self.tol.eps, c.delta);
        let query = Aabb::from_points(&[c.p]).inflated(reach);
        let mut ok = true;
        target.bvh.for_each_overlapping(&query, |t| {
            ok = ok && sq_dist_exact(&exact, &target.tris[t as usize]) > self.tol.e2;
        });
        ok.then(|| {
            // dist(exact) >= dist(f64 corner) - delta, and > eps as just proved.
            let from_f64 = envelope_predicates::next_down(target.certified_lower(c.p) - c.delta);
            Witness {
                face,
                barycentric: c.bary,
                level,
                point: DVec3::from_array(exact.map(|x| x.to_f64())),
                exact_f64: false,
                distance: from_f64.max(self.tol.eps),
            }
        })
    }

    fn face(&self, face: FaceId, tri: [DVec3; 3], scratch: &mut Scratch) -> FaceResult {
        let mut out = FaceResult {
            subdivisions: 1,
            ..FaceResult::default()
        };
        if self.target.has_triangle(&tri) {
            // The same closed triangle: distance 0 everywhere, no lower-bound candidate.
            return out;
        }
        out.subdivisions = 0;
        let corner = |k: usize| {
            let mut bary = [0; 3];
            bary[k] = 1;
            Corner {
                p: tri[k],
                delta: 0.0,
                bary,
            }
        };
        // Fast path: the triangle nearest the centroid usually covers the whole face (the
        // same proof as below, with one candidate and no candidate list).
        let centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
        if let Some((t0, _)) =
            self.target
                .nearest_approx_from(centroid, scratch.hint, &mut scratch.stack)
        {
            scratch.hint = Some(t0);
            let s0 = Sub {
                c: [corner(0), corner(1), corner(2)],
                level: 0,
                cands: Vec::new(),
                d: Vec::new(),
            };
            let d = tri.map(|p| self.target.sq_dist(p, t0));
            let m = d[0].max(d[1]).max(d[2]);
            let est = Estimate {
                best: Some((t0, m)),
                corner_min: d,
                corner_best: [t0; 3],
            };
            let mut low = None;
            if let Some(u) = self.prove(&tri, &s0, &est, 0.0, &mut low) {
                // `d` over-estimates each corner's distance: only a ranking for the lower
                // bound, which is certified separately.
                let j = (0..3).max_by(|&a, &b| d[a].total_cmp(&d[b])).unwrap_or(0);
                out.lower_candidate = Some((d[j], tri[j], 0.0));
                farther(&mut out.lower_candidate, low);
                out.upper = u;
                out.subdivisions = 1;
                return out;
            }
        }
        let query = Aabb::from_triangle(tri).inflated(self.tol.eps);
        let mut cands = Vec::new();
        let slab = Slab::new(tri, self.tol.eps);
        self.target.bvh.for_each_overlapping(&query, |t| {
            if !slab.apart(&self.target.tris[t as usize]) {
                cands.push(t);
            }
        });
        let mut d = Vec::with_capacity(3 * cands.len());
        for &t in &cands {
            d.extend(tri.map(|p| self.sq_dist_or_inf(p, t)));
        }
        let mut stack = vec![Sub {
            c: [corner(0), corner(1), corner(2)],
            level: 0,
            cands,
            d,
        }];
        let mut tiny = 0u64;
        // All sub-triangles, tiny or not: a region at exactly epsilon along a curve on a face
        // far larger than epsilon otherwise takes about (face size / (eps 2^-10)) of them
        // before any is tiny.
        let budget = self.tiny_budget.min(MAX_FACE_SUBDIVISIONS) + 64 * stack[0].cands.len() as u64;
        while let Some(s) = stack.pop() {
            out.subdivisions += 1;
            let est = self.estimate(&s);
            let delta = s.c.iter().map(|c| c.delta).fold(0.0, f64::max);
            for j in 0..3 {
                if s.c[j].delta == 0.0
                    && out
                        .lower_candidate
                        .is_none_or(|(d, _, _)| est.corner_min[j] > d)
                {
                    out.lower_candidate = Some((est.corner_min[j], s.c[j].p, 0.0));
                }
            }
            if out.witness.is_some() {
                out.upper = out.upper.max(self.upper_bound(&s, &est, delta));
                continue;
            }
            let mut low = None;
            if let Some(u) = self.prove(&tri, &s, &est, delta, &mut low) {
                out.upper = out.upper.max(u);
                farther(&mut out.lower_candidate, low);
                continue;
            }
            // Over triangles several times larger than eps, their cells settle it in a few
            // pieces each; over smaller ones, one triangle proves a sub-triangle larger than
            // itself, and subdividing is cheaper.
            if s.cands.len() <= CELL_CANDIDATES
                && est.corner_min.iter().all(|&d| d < self.tol.e2lo)
                && self.cells_pay(&s.cands)
                && let Some((u, far, pieces)) =
                    self.cells_within(&s.c.map(|c| c.p), &s.cands, &s.d, delta)
            {
                out.upper = out.upper.max(u);
                farther(&mut out.lower_candidate, Some(far));
                out.subdivisions += pieces - 1;
                continue;
            }
            for j in 0..3 {
                if est.corner_min[j] > self.tol.e2lo * (1.0 - 2f64.powi(-20))
                    && let Some(w) = self.witness(face, &tri, &s.c[j], s.level)
                {
                    out.witness = Some(w);
                    break;
                }
            }
            let diam = (0..3)
                .map(|j| (s.c[j].p - s.c[(j + 1) % 3].p).length())
                .fold(0.0, f64::max);
            if diam < self.tol.eps * 2f64.powi(-10) {
                tiny += 1;
            }
            if out.witness.is_some()
                || s.level >= MAX_LEVEL
                || tiny >= self.tiny_budget
                || out.subdivisions >= budget
                || diam * (1.0 + 1e-9) + 2.0 * delta <= self.tol.resolution
            {
                out.undecided |= out.witness.is_none();
                out.upper = out.upper.max(self.upper_bound(&s, &est, delta));
                continue;
            }
            self.subdivide(s, &mut stack);
        }
        out
    }

    fn subdivide(&self, s: Sub, stack: &mut Vec<Sub>) {
        let [a, b, c] = s.c;
        // Midpoints sum the numerators over 2^(L+1); the old corners double theirs.
        let (ab, bc, ca) = (midpoint(&a, &b), midpoint(&b, &c), midpoint(&c, &a));
        // `mid[3 i + k]`: midpoint k (ab, bc, ca) to `cands[i]`.
        let mut mid: Vec<f64> = Vec::with_capacity(3 * s.cands.len());
        for &t in &s.cands {
            mid.extend([ab.p, bc.p, ca.p].map(|p| self.sq_dist_or_inf(p, t)));
        }
        let double = |x: Corner| Corner {
            bary: x.bary.map(|v| v * 2),
            ..x
        };
        let (a2, b2, c2) = (double(a), double(b), double(c));
        // Each child's corners, and where their distances are: (parent corner, midpoint).
        #[derive(Clone, Copy)]
        enum Src {
            Corner(usize),
            Mid(usize),
        }
        use Src::{Corner as P, Mid as M};
        let children = [
            ([a2, ab, ca], [P(0), M(0), M(2)]),
            ([ab, b2, bc], [M(0), P(1), M(1)]),
            ([ca, bc, c2], [M(2), M(1), P(2)]),
            ([bc, ca, ab], [M(1), M(2), M(0)]),
        ];
        for (corners, from) in children {
            let points = corners.map(|c| c.p);
            let query = Aabb::from_triangle(points).inflated(self.tol.eps);
            // A triangle farther than eps + diam from a corner is farther than eps from
            // every point of the child (each within diam of that corner): it can prove
            // nothing there. Estimated distances, with a wide margin; a triangle kept in
            // error only costs time, one dropped in error only a proof (witnesses and
            // bounds ask the tree, not this list).
            let diam = (0..3)
                .map(|j| (points[j] - points[(j + 1) % 3]).length())
                .fold(0.0, f64::max);
            let slack = corners.iter().map(|c| c.delta).fold(0.0, f64::max);
            let reach = (self.tol.eps + diam + 2.0 * slack) * (1.0 + 1e-6);
            let reach2 = reach * reach;
            let dist = |i: usize, f: Src| match f {
                P(j) => s.dist(j, i),
                M(k) => mid[3 * i + k],
            };
            let mut cands = Vec::with_capacity(s.cands.len());
            let mut d = Vec::with_capacity(3 * s.cands.len());
            let slab = Slab::new(points, add_up(self.tol.eps, 2.0 * slack));
            for (i, &t) in s.cands.iter().enumerate() {
                let di = from.map(|f| dist(i, f));
                if self.target.boxes[t as usize].overlaps(&query)
                    && di.iter().all(|&x| x <= reach2)
                    && !slab.apart(&self.target.tris[t as usize])
                {
                    cands.push(t);
                    d.extend_from_slice(&di);
                }
            }
            stack.push(Sub {
                c: corners,
                level: s.level + 1,
                cands,
                d,
            });
        }
    }
}

/// Per-chunk state of the face loop: the previous face's nearest triangle and a BVH stack.
#[derive(Default)]
struct Scratch {
    hint: Option<u32>,
    stack: Vec<NodeId>,
}

/// The face results of one chunk, folded.
#[derive(Default)]
struct Summary {
    upper: f64,
    undecided: usize,
    witness: Option<Witness>,
    /// The most distant lower-bound candidates, at most [`LOWS`], farthest first.
    lows: Vec<Low>,
    subdivisions: u64,
}

/// Exact points certified for the lower bound.
const LOWS: usize = 32;

impl Summary {
    fn add(&mut self, r: FaceResult) {
        self.upper = self.upper.max(r.upper);
        self.undecided += usize::from(r.undecided);
        self.subdivisions += r.subdivisions;
        if let Some(w) = r.witness
            && self
                .witness
                .as_ref()
                .is_none_or(|b| w.distance > b.distance)
        {
            self.witness = Some(w);
        }
        self.lows.extend(r.lower_candidate);
        if self.lows.len() >= 4 * LOWS {
            self.trim();
        }
    }

    fn trim(&mut self) {
        self.lows.sort_by(|a, b| b.0.total_cmp(&a.0));
        self.lows.truncate(LOWS);
    }

    /// `self` then `o`, in face order (ties keep the earlier face: deterministic).
    fn merge(mut self, o: Summary) -> Summary {
        self.upper = self.upper.max(o.upper);
        self.undecided += o.undecided;
        self.subdivisions += o.subdivisions;
        if let Some(w) = o.witness
            && self
                .witness
                .as_ref()
                .is_none_or(|b| w.distance > b.distance)
        {
            self.witness = Some(w);
        }
        self.lows.extend(o.lows);
        self.trim();
        self
    }
}

/// The certified bounds of one face from its result (see the module docs).
fn face_bound(search: &Search<'_>, face: FaceId, tri: [DVec3; 3], r: &FaceResult) -> FaceBound {
    let target = search.target;
    let mut lower = r
        .lower_candidate
        .as_ref()
        .map_or(0.0, |low| low_bound(target, low));
    if let Some(w) = &r.witness {
        lower = lower.max(w.distance);
    }
    let mut upper = r.upper;
    search.tighten(face, tri, &mut lower, &mut upper);
    FaceBound { lower, upper }
}

/// Bisection rounds of [`Search::tighten`].
const MAP_ROUNDS: u32 = 3;

impl Search<'_> {
    /// For the error map only: narrows a face's certified `[lower, upper]` (`upper` at most
    /// `eps`) by deciding the same face again at tolerances between them, with the same
    /// proofs and witnesses: a proof at `e` makes its bound (at most `e`) the new upper
    /// bound, a witness its distance (more than `e`) the new lower bound. At most
    /// [`MAP_ROUNDS`] rounds, each with the first pass's budget; stops when the bounds are
    /// within a quarter of each other (plus `eps / 256`), or at an undecided round.
    fn tighten(&self, face: FaceId, tri: [DVec3; 3], lower: &mut f64, upper: &mut f64) {
        if !(*upper > 0.0 && *upper <= self.tol.eps) {
            return;
        }
        let floor = self.tol.eps * 2f64.powi(-8);
        for _ in 0..MAP_ROUNDS {
            if *upper <= 1.25 * *lower + floor {
                return;
            }
            let e = 0.5 * (*lower + *upper);
            if !(e > 0.0 && e < *upper) {
                return;
            }
            let tol = Tolerance::new(e, self.tol.resolution);
            let search = Search {
                target: self.target,
                tol: &tol,
                tiny_budget: FIRST_PASS_TINY,
            };
            let r = search.face(face, tri, &mut Scratch::default());
            match &r.witness {
                Some(w) => *lower = lower.max(w.distance),
                None if !r.undecided => *upper = upper.min(r.upper),
                None => return,
            }
        }
    }
}

/// A face's index and its bounds.
type IndexedBound = (usize, FaceBound);

/// Whether every point of every triangle of `tris` is proved within `eps` of `target`,
/// stopping at the first that is not (a few triangles on this thread, more on all): a witness and
/// a triangle left undecided by the first pass's budget both answer `false` (never a wrong
/// `true`).
pub(crate) fn all_within(tris: &[[DVec3; 3]], target: &Target, tol: &Tolerance) -> bool {
    let search = Search {
        target,
        tol,
        tiny_budget: FIRST_PASS_TINY,
    };
    let proved = |scratch: &mut Scratch, (i, &t): (usize, &[DVec3; 3])| {
        let r = search.face(FaceId::from_index(i), t, scratch);
        r.witness.is_none() && !r.undecided
    };
    if tris.len() < PARALLEL_FROM {
        let mut scratch = Scratch::default();
        tris.iter().enumerate().all(|x| proved(&mut scratch, x))
    } else {
        tris.par_iter()
            .enumerate()
            .with_min_len(PARALLEL_FROM / 2)
            .map_init(Scratch::default, proved)
            .all(|ok| ok)
    }
}

/// [`all_within`] splits lists at least this long between threads.
const PARALLEL_FROM: usize = 4;

/// Decides whether every point of the triangles `faces` of `positions` lies within `eps` of
/// `target`, with a certified interval for the one-sided Hausdorff distance; with
/// `per_face`, also the certified bounds of each face (in face order).
pub(crate) fn one_sided(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    target: &Target,
    tol: &Tolerance,
    per_face: bool,
) -> (OneSided, Option<Vec<FaceBound>>) {
    // Two passes, so that a violated direction does not spend the full budget on faces
    // that stay undecided (ties along curves; fuzzed meshes of degenerate triangles took
    // seconds): the first pass gives each face a small budget and sets aside the faces it
    // leaves undecided. If some face has a witness, the verdict is `Violated` whatever
    // they are, and their first-pass results stand; otherwise they are examined again
    // with the full budget. Both passes are deterministic.
    let first = Search {
        target,
        tol,
        tiny_budget: FIRST_PASS_TINY,
    };
    let (mut sum, deferred, mut bounds) = faces
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut scratch = Scratch::default();
            let mut sum = Summary::default();
            let mut deferred = Vec::new();
            let mut bounds: Vec<IndexedBound> = Vec::new();
            for (k, f) in chunk.iter().enumerate() {
                let tri = f.map(|v| positions[v as usize]);
                let index = c * CHUNK + k;
                let r = first.face(FaceId::from_index(index), tri, &mut scratch);
                if r.undecided && r.witness.is_none() {
                    deferred.push((index, r));
                } else {
                    if per_face {
                        bounds.push((
                            index,
                            face_bound(&first, FaceId::from_index(index), tri, &r),
                        ));
                    }
                    sum.add(r);
                }
            }
            (sum, deferred, bounds)
        })
        .reduce(
            || (Summary::default(), Vec::new(), Vec::new()),
            |(a, mut da, mut ba), (b, db, bb)| {
                da.extend(db);
                ba.extend(bb);
                (a.merge(b), da, ba)
            },
        );
    if sum.witness.is_some() {
        for (index, r) in deferred {
            if per_face {
                let tri = faces[index].map(|v| positions[v as usize]);
                bounds.push((
                    index,
                    face_bound(&first, FaceId::from_index(index), tri, &r),
                ));
            }
            sum.add(r);
        }
    } else if !deferred.is_empty() {
        let full = Search {
            target,
            tol,
            tiny_budget: MAX_FACE_TINY,
        };
        let (again, again_bounds) = deferred
            .par_iter()
            .map(|(index, first_result)| {
                let f = faces[*index];
                let tri = f.map(|v| positions[v as usize]);
                let r = full.face(FaceId::from_index(*index), tri, &mut Scratch::default());
                let bound = per_face.then(|| {
                    let b = face_bound(&full, FaceId::from_index(*index), tri, &r);
                    // Both passes' upper bounds are certified: the smaller holds.
                    let upper = b.upper.min(first_result.upper);
                    vec![(*index, FaceBound { upper, ..b })]
                });
                let mut s = Summary::default();
                s.add(r);
                (s, bound.unwrap_or_default())
            })
            .reduce(
                || (Summary::default(), Vec::new()),
                |(a, mut ba), (b, bb)| {
                    ba.extend(bb);
                    (a.merge(b), ba)
                },
            );
        sum = sum.merge(again);
        bounds.extend(again_bounds);
        // Every sub-triangle examined counts, the first pass's included.
        sum.subdivisions += deferred.iter().map(|(_, r)| r.subdivisions).sum::<u64>();
    }
    let Summary {
        mut upper,
        undecided,
        witness,
        mut lows,
        subdivisions,
    } = sum;
    // Certify the few most distant exact points for the lower bound.
    lows.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut lower = lows
        .iter()
        .take(LOWS)
        .map(|low| low_bound(target, low))
        .fold(0.0, f64::max);
    if let Some(w) = &witness {
        lower = lower.max(w.distance);
    }
    if faces.is_empty() {
        upper = 0.0;
    }
    let verdict = if witness.is_some() {
        Verdict::Violated
    } else if undecided > 0 {
        Verdict::Undecided
    } else {
        Verdict::Holds
    };
    let per_face = per_face.then(|| {
        // Every face is in `bounds` exactly once: settled in the first pass, or deferred and
        // then settled by one of the two branches above.
        let mut out = vec![
            FaceBound {
                lower: 0.0,
                upper: f64::INFINITY,
            };
            faces.len()
        ];
        for (index, b) in bounds {
            out[index] = b;
        }
        out
    });
    let one = OneSided {
        verdict,
        lower,
        upper,
        witness,
        undecided_regions: undecided,
        subdivisions,
    };
    (one, per_face)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::strategies::point;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]
        /// `near_edge` and `near_vertex` only say "within" when the exact distance is.
        /// Points on an edge's line (rounded), or a few ulps or a small distance off it.
        #[test]
        fn near_tests_are_sound(
            t in [point(), point(), point()],
            k in 0usize..3,
            tau in 0.0f64..1.0,
            off in prop_oneof![Just(0.0), -1e-14f64..1e-14, -1e-3f64..1e-3],
            dir in point(),
            e2 in prop_oneof![Just(0.0), 0.0f64..1e-6, 0.0f64..1e-2],
        ) {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let p = a + (b - a) * tau + dir * off;
            let exact = sq_dist_exact(&rpoint(p), &t);
            if near_edge(p, &t, e2) || near_vertex(p, &t, e2) {
                prop_assert!(exact <= rational(e2), "{p:?} {t:?} {e2}");
            }
            // And it is not vacuous: a point rounded onto an edge is within any usable e2.
            if off == 0.0 && e2 >= 1e-6 && a != b {
                prop_assert!(near_edge(p, &t, e2), "{p:?} {t:?} {e2}");
            }
        }

        /// `near_face` only says "within" when the exact distance is: points over the
        /// inside of a triangle (rounded), a few ulps or a small distance off its plane.
        #[test]
        fn near_face_is_sound(
            t in [point(), point(), point()],
            v in 0.0f64..1.0,
            w in 0.0f64..1.0,
            off in prop_oneof![Just(0.0), -1e-14f64..1e-14, -1e-3f64..1e-3],
            dir in point(),
            e2 in prop_oneof![Just(0.0), 0.0f64..1e-30, 0.0f64..1e-6, 0.0f64..1e-2],
            shift in prop_oneof![Just(0.0), -1e6f64..1e6],
        ) {
            let (v, w) = if v + w > 1.0 { (1.0 - v, 1.0 - w) } else { (v, w) };
            // Far from the origin the roundings grow with the coordinates, not the triangle.
            let t = t.map(|x| x + DVec3::splat(shift));
            let [a, b, c] = t;
            let p = a + (b - a) * v + (c - a) * w + dir * off;
            let exact = sq_dist_exact(&rpoint(p), &t);
            if near_face(p, &t, e2) {
                prop_assert!(exact <= rational(e2), "{p:?} {t:?} {e2}");
            }
            // And it is not vacuous: a point rounded into a fat triangle, well inside, is
            // within any usable e2.
            let n = (b - a).cross(c - a).length();
            let fat = n > 0.1 * (b - a).length_squared().max((c - a).length_squared());
            if off == 0.0 && e2 >= 1e-6 && fat && v > 0.01 && w > 0.01 && v + w < 0.99 {
                prop_assert!(near_face(p, &t, e2), "{p:?} {t:?} {e2}");
            }
        }

        /// `some_point_beyond` (the first triangle within reach, from a hint) answers as the
        /// nearest-triangle search would: some point's nearest triangle beyond `eps`.
        #[test]
        fn some_point_beyond_agrees_with_the_nearest_triangle(
            tris in prop::collection::vec([point(), point(), point()], 1..40),
            points in prop::collection::vec(point(), 1..12),
            scale in 0.9f64..1.1,
        ) {
            let target = Target::from_triangles(tris);
            // Epsilon about the farthest point's distance, so that both answers come up.
            let far = points
                .iter()
                .filter_map(|&p| target.nearest_approx(p))
                .map(|(_, d2)| d2)
                .fold(0.0, f64::max);
            let eps = far.sqrt() * scale;
            let e2 = eps * eps;
            let nearest_beyond = points
                .iter()
                .any(|&p| target.nearest_approx(p).is_none_or(|(_, d2)| d2 > e2));
            prop_assert_eq!(target.some_point_beyond(&points, eps), nearest_beyond);
        }
    }
}
