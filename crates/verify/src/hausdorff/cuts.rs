//! Proofs by cuts: a sub-triangle that no single triangle of the other mesh covers, cut
//! by planes through the shared edges and corners of the triangles nearest to its corners,
//! each piece proved against one triangle (the module docs of `hausdorff`, "Cuts").

use envelope_predicates::bvh::Aabb;
use envelope_predicates::exact_num::Rational;
use envelope_predicates::{Orientation, collinear, orient3d};
use glam::DVec3;
use smallvec::SmallVec;

use super::{Estimate, Low, Search, Sub, farther, within};
use crate::numeric::{
    RPoint, add_up, barycentric_point, cross, crossing_with_bound, dot, orient3d_with_bound,
    rpoint, sq_dist_exact, sqrt_up, sub,
};

/// Rounds of cuts [`Search::pieces_within`] makes at most (up to `2^PIECE_CUTS` pieces).
pub(super) const PIECE_CUTS: u32 = 3;
/// Pieces [`Search::cells_within`] makes at most for one polygon.
const CELL_PIECES: u64 = 512;
/// Rounds of cuts [`Search::cells_within`] makes at most on the way to one piece.
const CELL_DEPTH: u32 = 32;

impl Search<'_> {
    /// Like [`Self::split_within_f64`], with cuts in several rounds (at most
    /// [`PIECE_CUTS`] deep) and also between triangles that share only a corner (a plane
    /// through it, [`vertex_bisector_points`]): where a sub-triangle lies over a vertex of
    /// `to` its corners are nearest to triangles of that vertex's fan that share no edge,
    /// and one cut between two of them does not settle it. Each cut is a chord of the
    /// exact polygon ([`is_chord`]): its ends stand for the points at the same parameters
    /// on the exact edges, within their crossing bounds plus the polygon's, so the exact
    /// pieces partition the exact sub-triangle and stay planar and convex; a piece whose
    /// f64 vertices are proved within `u` of a triangle (the proof's convexity) proves its
    /// exact piece within `u` plus those bounds, added up over the rounds, plus `delta`.
    /// The pieces choose among the candidates that share a corner with a triangle nearest
    /// to a corner of `s` (the fan around a vertex, the two sides of an edge): a choice
    /// that only bounds the work. Also returns the pieces' farthest vertex, a lower-bound
    /// candidate.
    pub(super) fn pieces_within(&self, s: &Sub, est: &Estimate, delta: f64) -> Option<(f64, Low)> {
        let nearest: SmallVec<[[DVec3; 3]; 3]> = est
            .nearest()
            .iter()
            .map(|&t| self.target.tris[t as usize])
            .collect();
        // Cuts are through shared corners and edges only.
        let shares = |a: &[DVec3; 3], b: &[DVec3; 3]| a.iter().any(|p| b.contains(p));
        if (0..nearest.len())
            .any(|i| (i + 1..nearest.len()).any(|j| !shares(&nearest[i], &nearest[j])))
        {
            return None;
        }
        // Around a corner all of them share, its fan; else whatever touches one of them.
        let common: SmallVec<[DVec3; 3]> = nearest[0]
            .iter()
            .copied()
            .filter(|p| nearest.iter().all(|n| n.contains(p)))
            .collect();
        let keep: SmallVec<[usize; 16]> = (0..s.cands.len())
            .filter(|&i| {
                let t = &self.target.tris[s.cands[i] as usize];
                if common.is_empty() {
                    nearest.iter().any(|n| t.iter().any(|p| n.contains(p)))
                } else {
                    common.iter().any(|p| t.contains(p))
                }
            })
            .collect();
        let cands: SmallVec<[u32; 16]> = keep.iter().map(|&i| s.cands[i]).collect();
        let d: SmallVec<[f64; 64]> = (0..3)
            .flat_map(|j| keep.iter().map(move |&i| s.dist(j, i)))
            .collect();
        let poly = s.c.map(|c| c.p);
        let (u, far) = self.piece_within(&cands, &poly, &d[..], delta, PIECE_CUTS)?;
        (u <= self.tol.eps).then_some((u, far))
    }

    /// A proved bound of the distance of the polygon `poly` (f64 points, taken exactly,
    /// convex) to `to`, plus `err`, when at most `eps` (see [`Self::pieces_within`]), and
    /// the farthest vertex of its pieces (each within its piece's `err` of a point of the
    /// exact polygon). `d[k n + i]`: the estimated squared distance of `poly[k]` to
    /// `cands[i]`, `n` candidates (one allocation per piece: this runs millions of times).
    fn piece_within(
        &self,
        cands: &[u32],
        poly: &[DVec3],
        d: &[f64],
        err: f64,
        cuts: u32,
    ) -> Option<(f64, Low)> {
        let n = cands.len();
        if n == 0 {
            return None;
        }
        // Each vertex's nearest candidate, by the estimate; all must be within eps.
        let mut nearest: SmallVec<[u32; 8]> = SmallVec::new();
        let mut far: Option<Low> = None;
        for (k, dk) in d.chunks_exact(n).enumerate() {
            let (i, &m) = dk.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1))?;
            if m >= self.tol.e2lo {
                return None;
            }
            if !nearest.contains(&cands[i]) {
                nearest.push(cands[i]);
            }
            farther(&mut far, Some((m, poly[k], err)));
        }
        let far = far?;
        // One triangle for the whole piece, by its vertices: the estimates first, the exact
        // tests only where they promise a proof.
        for &t in &nearest {
            let Some(i) = cands.iter().position(|&c| c == t) else {
                continue;
            };
            if let Some(total) = self.piece_proved(poly, t, |k| d[k * n + i], err) {
                return Some((total, far));
            }
        }
        if cuts == 0 {
            return None;
        }
        // A cut between the first two nearest triangles that have a plane between them.
        for (i, &t1) in nearest.iter().enumerate() {
            for &t2 in &nearest[i + 1..] {
                let (a, b) = (
                    &self.target.tris[t1 as usize],
                    &self.target.tris[t2 as usize],
                );
                let Some([p, q, r]) =
                    bisector_points(a, b).or_else(|| vertex_bisector_points(a, b))
                else {
                    continue;
                };
                let side: SmallVec<[Orientation; 8]> =
                    poly.iter().map(|&x| orient3d(p, q, r, x)).collect();
                if !side.contains(&Orientation::Positive)
                    || !side.contains(&Orientation::Negative)
                    || !is_chord(&side)
                {
                    continue;
                }
                let (lo, hi) = clip_f64(poly, &side, [p, q, r]);
                let piece = |part: &Piece| -> Option<(f64, Low)> {
                    let points: SmallVec<[DVec3; 8]> = part.iter().map(|x| x.0).collect();
                    let e = part.iter().map(|x| x.1).fold(err, add_up);
                    // Distances of the old vertices are known; the cut points' are new.
                    let mut dist: SmallVec<[f64; 64]> = SmallVec::new();
                    for &x in &points {
                        match poly.iter().position(|&y| y == x) {
                            Some(k) => dist.extend_from_slice(&d[k * n..(k + 1) * n]),
                            None => dist.extend(cands.iter().map(|&t| self.sq_dist_or_inf(x, t))),
                        }
                    }
                    self.piece_within(cands, &points, &dist, e, cuts - 1)
                };
                let (u, mut far) = piece(&lo)?;
                let (w, other) = piece(&hi)?;
                if other.0 > far.0 {
                    far = other;
                }
                return Some((u.max(w), far));
            }
        }
        None
    }

    /// A proved bound of the distance of the polygon `poly` (f64 points, taken exactly,
    /// convex; its exact polygon within `err`) to the triangle `t` of `to`, plus `err`, when
    /// at most `eps`: every vertex within it (convexity). `sq(k)` is the estimated squared
    /// distance of `poly[k]` to `t`: the estimates first, the exact tests only where they
    /// promise a proof.
    fn piece_proved(
        &self,
        poly: &[DVec3],
        t: u32,
        sq: impl Fn(usize) -> f64,
        err: f64,
    ) -> Option<f64> {
        let value = |k: usize| self.tol.piece_value(sq(k));
        let promised = (0..poly.len()).map(value).fold(0.0, f64::max);
        if promised > self.tol.e2hi || add_up(sqrt_up(promised), err) > self.tol.eps {
            return None;
        }
        let tri = &self.target.tris[t as usize];
        let u = (0..poly.len()).try_fold(0.0f64, |u, k| {
            let c = value(k);
            within(poly[k], tri, c).then(|| u.max(sqrt_up(c)))
        })?;
        let total = add_up(u, err);
        (total <= self.tol.eps).then_some(total)
    }

    /// A proof of the whole polygon `poly` (f64 points, taken exactly, convex; its exact
    /// polygon within `err`) by the cells of `to`'s triangles: where no single triangle
    /// covers a piece, it is cut by the plane through an edge of a triangle near it and that
    /// edge's neighbour ([`bisector_points`]), and each part goes on, until every piece is
    /// proved against one triangle by its vertices (the proof of [`Self::pieces_within`],
    /// with the same chords and error bounds added up over the rounds). Near a surface the
    /// planes through its edges bound the regions nearest to each triangle, so a face over
    /// many small triangles within `eps` of them takes a few pieces per triangle it lies
    /// over, where subdividing takes many sub-triangles along every edge it crosses.
    /// `cands` are the candidates, `d[i v + k]` the estimated squared distance of
    /// `poly[k]` to `cands[i]` (`v` vertices). Returns the proved bound (at most `eps`), the
    /// farthest piece vertex (a lower-bound candidate) and the number of pieces; `None` when
    /// a piece has a vertex not within `eps` of any candidate by the estimates or finds no
    /// cut, or past [`CELL_PIECES`] pieces or [`CELL_DEPTH`] rounds: the caller subdivides.
    pub(super) fn cells_within(
        &self,
        poly: &[DVec3],
        cands: &[u32],
        d: &[f64],
        err: f64,
    ) -> Option<(f64, Low, u64)> {
        struct Part {
            points: SmallVec<[DVec3; 8]>,
            err: f64,
            /// Positions in `cands` of the triangles that may prove something here.
            idx: Vec<u32>,
            /// `d[i v + k]`: vertex `k` to `cands[idx[i]]`, `v` vertices.
            d: Vec<f64>,
            /// The edges already cut along on the way here ([`edge_key`]), `depth` of them.
            used: [u64; CELL_DEPTH as usize],
            depth: u32,
        }
        // Per candidate and edge, the plane through that edge and its neighbour's among
        // `cands` (if any), made when first asked.
        let mut planes: Vec<[Option<Option<[DVec3; 3]>>; 3]> = vec![[None; 3]; cands.len()];
        let mut stack = vec![Part {
            points: poly.iter().copied().collect(),
            err,
            idx: (0..cands.len() as u32).collect(),
            d: d.to_vec(),
            used: [0; CELL_DEPTH as usize],
            depth: 0,
        }];
        let (mut upper, mut far, mut pieces) = (0.0f64, None::<Low>, 0u64);
        while let Some(part) = stack.pop() {
            pieces += 1;
            let (n, v) = (part.idx.len(), part.points.len());
            if pieces > CELL_PIECES || n == 0 {
                return None;
            }
            let dist = |i: usize, k: usize| part.d[i * v + k];
            // Each vertex's nearest candidate by the estimate, all within eps; and the few
            // candidates with the smallest largest vertex estimate (a vertex on a corner of
            // `to` is as near to its whole fan).
            let mut order: SmallVec<[(f64, usize); 8]> = SmallVec::new();
            let mut nearest = [(f64::INFINITY, 0usize); 8];
            for i in 0..n {
                let mut w = 0.0f64;
                for k in 0..v {
                    let x = dist(i, k);
                    w = w.max(x);
                    if k < 8 && x < nearest[k].0 {
                        nearest[k] = (x, i);
                    }
                }
                if order.len() < 3 || w < order[order.len() - 1].0 {
                    let at = order.partition_point(|x| x.0 <= w);
                    order.insert(at, (w, i));
                    order.truncate(3);
                }
            }
            for k in 0..v {
                let (m, i) = if k < 8 {
                    nearest[k]
                } else {
                    (0..n)
                        .map(|i| (dist(i, k), i))
                        .min_by(|a, b| a.0.total_cmp(&b.0))?
                };
                if m >= self.tol.e2lo {
                    return None;
                }
                if !order.iter().any(|x| x.1 == i) {
                    order.push((f64::INFINITY, i));
                }
                farther(&mut far, Some((m, part.points[k], part.err)));
            }
            let proved = order.iter().find_map(|&(_, i)| {
                let t = cands[part.idx[i] as usize];
                self.piece_proved(&part.points, t, |k| dist(i, k), part.err)
            });
            if let Some(u) = proved {
                upper = upper.max(u);
                continue;
            }
            if part.depth >= CELL_DEPTH {
                return None;
            }
            // A cut along an edge of one of those triangles that splits the piece.
            let used = &part.used[..part.depth as usize];
            // Among the edges of the first of those triangles that has a cut at all, the
            // cut that splits the piece most evenly (the larger of the smaller reaches of
            // the piece beyond the plane, in f64: only a choice among sound cuts; fewer
            // pieces than the first cut found, where a long plane slices a thin piece).
            let mut cut: Option<Cut> = None;
            for &(_, i) in &order {
                let pos = part.idx[i] as usize;
                let a = &self.target.tris[cands[pos] as usize];
                for e in 0..3 {
                    let (p, q) = (a[e], a[(e + 1) % 3]);
                    let key = edge_key(p, q);
                    if used.contains(&key) {
                        continue;
                    }
                    let plane = planes[pos][e].get_or_insert_with(|| {
                        let b = cands.iter().find(|&&j| {
                            let b = &self.target.tris[j as usize];
                            j != cands[pos] && b.contains(&p) && b.contains(&q)
                        });
                        b.and_then(|&b| bisector_points(a, &self.target.tris[b as usize]))
                    });
                    let Some(plane) = *plane else {
                        continue;
                    };
                    let side: SmallVec<[Orientation; 8]> = part
                        .points
                        .iter()
                        .map(|&x| orient3d(plane[0], plane[1], plane[2], x))
                        .collect();
                    if !side.contains(&Orientation::Positive)
                        || !side.contains(&Orientation::Negative)
                        || !is_chord(&side)
                    {
                        continue;
                    }
                    let normal = (plane[1] - plane[0]).cross(plane[2] - plane[0]);
                    let (mut below, mut above) = (0.0f64, 0.0f64);
                    for &x in &part.points {
                        let h = normal.dot(x - plane[0]);
                        below = below.min(h);
                        above = above.max(h);
                    }
                    let score = (-below).min(above) / normal.length();
                    if cut.as_ref().is_none_or(|c| score > c.score) {
                        cut = Some(Cut {
                            score,
                            key,
                            plane,
                            side,
                        });
                    }
                }
                if cut.is_some() {
                    break;
                }
            }
            let Cut {
                key, plane, side, ..
            } = cut?;
            let (lo, hi) = clip_f64(&part.points, &side, plane);
            let mut used = part.used;
            used[part.depth as usize] = key;
            // The cut's crossing points are vertices of both halves: each one's distances
            // are computed once, when a half first asks (NaN: not yet; the estimates are
            // never NaN).
            let crossing: SmallVec<[DVec3; 2]> = lo
                .iter()
                .map(|x| x.0)
                .filter(|x| !part.points.contains(x))
                .collect();
            let mut crossing_d: SmallVec<[f64; 64]> =
                SmallVec::from_elem(f64::NAN, crossing.len() * n);
            for half in [lo, hi] {
                let points: SmallVec<[DVec3; 8]> = half.iter().map(|x| x.0).collect();
                let e = half.iter().map(|x| x.1).fold(part.err, add_up);
                let diam = points
                    .iter()
                    .flat_map(|x| points.iter().map(move |y| (*x - *y).length_squared()))
                    .fold(0.0, f64::max)
                    .sqrt();
                // A triangle farther than eps + diam from a vertex proves nothing here.
                let reach = (self.tol.eps + diam + 2.0 * e) * (1.0 + 1e-6);
                let reach2 = reach * reach;
                // Each vertex: a vertex of the part (its row), or a crossing point.
                let rows: SmallVec<[Result<usize, Option<usize>>; 8]> = points
                    .iter()
                    .map(|x| {
                        part.points
                            .iter()
                            .position(|y| y == x)
                            .ok_or_else(|| crossing.iter().position(|y| y == x))
                    })
                    .collect();
                let w = points.len();
                // Nor does one whose box is farther than eps from the piece's.
                let query = Aabb::from_points(&points).inflated(add_up(self.tol.eps, e));
                let mut idx = Vec::with_capacity(n);
                let mut d = Vec::with_capacity(n * w);
                for (i, &c) in part.idx.iter().enumerate() {
                    if !self.target.boxes[cands[c as usize] as usize].overlaps(&query) {
                        continue;
                    }
                    let start = d.len();
                    for (x, row) in points.iter().zip(&rows) {
                        d.push(match *row {
                            Ok(k) => dist(i, k),
                            Err(Some(j)) => {
                                let known = &mut crossing_d[j * n + i];
                                if known.is_nan() {
                                    *known = self.sq_dist_or_inf(*x, cands[c as usize]);
                                }
                                *known
                            }
                            Err(None) => self.sq_dist_or_inf(*x, cands[c as usize]),
                        });
                    }
                    if d[start..].iter().all(|&x| x <= reach2) {
                        idx.push(c);
                    } else {
                        d.truncate(start);
                    }
                }
                stack.push(Part {
                    points,
                    err: e,
                    idx,
                    d,
                    used,
                    depth: part.depth + 1,
                });
            }
        }
        Some((upper, far?, pieces))
    }

    /// [`Self::split_within_exactly`] in f64 with proved error bounds, for the f64
    /// sub-triangle `s` (its exact one is within `delta`): for each pair of the corners'
    /// nearest triangles that share an edge, cut `s` by the plane through that edge (exact
    /// signs of the corners; crossing points with [`crossing_with_bound`]) and certify
    /// each piece against the triangle on its side by its vertices, each vertex's bound plus
    /// its crossing error. Returns the proved upper bound when it is at most `eps`; `None`
    /// otherwise (ties at exactly `eps` are left to the rational cut).
    pub(super) fn split_within_f64(&self, s: &Sub, est: &Estimate, delta: f64) -> Option<f64> {
        let ts = est.nearest();
        let corners = s.c.map(|c| c.p);
        for (i, &t1) in ts.iter().enumerate() {
            for &t2 in &ts[i + 1..] {
                let (a, b) = (
                    &self.target.tris[t1 as usize],
                    &self.target.tris[t2 as usize],
                );
                let Some([p, q, r]) = bisector_points(a, b) else {
                    continue;
                };
                let side = corners.map(|x| orient3d(p, q, r, x));
                // Side <= 0 goes with one triangle, >= 0 with the other.
                let (lo, hi) = clip_f64(&corners, &side, [p, q, r]);
                let bound = |piece: &Piece, id: u32| -> Option<f64> {
                    let t = &self.target.tris[id as usize];
                    let values: SmallVec<[f64; 8]> = piece
                        .iter()
                        .map(|&(v, _)| self.tol.piece_value(self.target.sq_dist(v, id)))
                        .collect();
                    // The bound the exact tests would prove, from the estimates: no exact
                    // test where it already exceeds eps (the same answer, sooner).
                    let promised = piece
                        .iter()
                        .zip(&values)
                        .map(|(&(_, e), &c)| add_up(sqrt_up(c), e))
                        .fold(0.0, f64::max);
                    if add_up(promised, delta) > self.tol.eps {
                        return None;
                    }
                    piece
                        .iter()
                        .zip(&values)
                        .try_fold(0.0f64, |u, (&(v, e), &c)| {
                            within(v, t, c).then(|| u.max(add_up(sqrt_up(c), e)))
                        })
                };
                for (x, y) in [(t1, t2), (t2, t1)] {
                    if let (Some(u), Some(w)) = (bound(&lo, x), bound(&hi, y)) {
                        let total = add_up(u.max(w), delta);
                        if total <= self.tol.eps {
                            return Some(total);
                        }
                    }
                }
            }
        }
        None
    }

    /// A sub-triangle that straddles the shared edge of two close triangles `t1`, `t2`
    /// (a tie along a curve: each point within `eps` of one of them, no single one covering
    /// all): cut it exactly by a plane through that edge and prove each piece within `eps`
    /// of the triangle on its side, by its exact vertices (convexity again). The plane holds
    /// the edge and the sum of the two unit normals, rounded to f64: any plane through the
    /// edge is sound, this one makes the proof succeed where the nearest-triangle regions
    /// meet.
    pub(super) fn split_within_exactly(&self, face: &[DVec3; 3], s: &Sub, close: &[u32]) -> bool {
        let corners: Vec<RPoint> =
            s.c.iter()
                .map(|c| {
                    if c.delta == 0.0 {
                        rpoint(c.p)
                    } else {
                        barycentric_point(face, c.bary, s.level)
                    }
                })
                .collect();
        for (i, &t1) in close.iter().enumerate() {
            for &t2 in &close[i + 1..] {
                let (a, b) = (
                    &self.target.tris[t1 as usize],
                    &self.target.tris[t2 as usize],
                );
                let Some(plane) = bisector(a, b) else {
                    continue;
                };
                let side: Vec<Rational> = corners.iter().map(|q| plane.side(q)).collect();
                let (lo, hi) = clip_by_sign(&corners, &side);
                let within = |piece: &[RPoint], t: &[DVec3; 3]| {
                    piece.iter().all(|q| sq_dist_exact(q, t) <= self.tol.e2)
                };
                if (within(&lo, a) && within(&hi, b)) || (within(&lo, b) && within(&hi, a)) {
                    return true;
                }
            }
        }
        false
    }
}

/// Whether the exact sides of a polygon's vertices (in cycle order) change sign at most
/// twice around it, the zeros aside: then the parts [`clip_f64`] makes hold the two sides
/// of a chord of the exact polygon the f64 one stands for (a crossing point stands for the
/// point at the same parameter on the exact edge, within its bound plus the polygon's), so
/// they cover it. The f64 points of a cut piece are off its plane by roundings, and a plane
/// may meet such a polygon four times; no cut is made there.
fn is_chord(side: &[Orientation]) -> bool {
    // On the cut search's path: counted without collecting the signs.
    let mut signs = side.iter().filter(|&&s| s != Orientation::Degenerate);
    let Some(first) = signs.next() else {
        return true;
    };
    let (mut changes, mut last) = (0, first);
    for s in signs {
        changes += usize::from(s != last);
        last = s;
    }
    changes + usize::from(last != first) <= 2
}

/// A cut of [`Search::cells_within`]: how evenly it splits the piece, its edge
/// ([`edge_key`]), its plane and the exact sides of the piece's points.
struct Cut {
    score: f64,
    key: u64,
    plane: [DVec3; 3],
    side: SmallVec<[Orientation; 8]>,
}

/// The edge `p q` (either way round) as a hash of its ends' bits: which edges a piece was
/// already cut along (a collision only skips a cut).
fn edge_key(p: DVec3, q: DVec3) -> u64 {
    let h = |x: DVec3| {
        x.to_array().iter().fold(0u64, |h, v| {
            (h.rotate_left(23) ^ v.to_bits()).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        })
    };
    h(p) ^ h(q)
}

/// A part of a cut polygon: f64 points, each with a proved bound on its distance to the
/// exact point it stands for.
type Piece = SmallVec<[(DVec3, f64); 8]>;

/// Cuts the convex polygon `poly` (f64 points, taken exactly) by the plane through
/// `[p, q, r]`, whose exact sides of `poly`'s points are `side`: the (point, error bound)
/// lists of its parts on the side `<= 0` and `>= 0`, in order, the crossing points of the
/// edges whose ends lie strictly apart computed in f64 with proved bounds on their distance
/// to the exact ones ([`crossing_with_bound`]); the polygon's own points have bound 0.
fn clip_f64(poly: &[DVec3], side: &[Orientation], [p, q, r]: [DVec3; 3]) -> (Piece, Piece) {
    let mut lo: Piece = SmallVec::new();
    let mut hi: Piece = SmallVec::new();
    for k in 0..poly.len() {
        let j = (k + 1) % poly.len();
        if side[k] != Orientation::Positive {
            lo.push((poly[k], 0.0));
        }
        if side[k] != Orientation::Negative {
            hi.push((poly[k], 0.0));
        }
        let opposite = matches!(
            (side[k], side[j]),
            (Orientation::Negative, Orientation::Positive)
                | (Orientation::Positive, Orientation::Negative)
        );
        if opposite {
            let x = crossing_with_bound(
                poly[k],
                poly[j],
                orient3d_with_bound(p, q, r, poly[k]),
                orient3d_with_bound(p, q, r, poly[j]),
            );
            lo.push(x);
            hi.push(x);
        }
    }
    (lo, hi)
}

/// A plane through three points, exactly: `side(q)` is the sign-carrying determinant.
struct Plane {
    origin: RPoint,
    normal: RPoint,
}

impl Plane {
    fn side(&self, q: &RPoint) -> Rational {
        dot(&sub(q, &self.origin), &self.normal)
    }
}

/// The corners of `a` that are corners of `b`, in `a`'s order (`[..n]`).
fn shared_corners(a: &[DVec3; 3], b: &[DVec3; 3]) -> ([DVec3; 3], usize) {
    let mut out = [DVec3::ZERO; 3];
    let mut n = 0;
    for &p in a {
        if b.contains(&p) {
            out[n] = p;
            n += 1;
        }
    }
    (out, n)
}

/// Three f64 points spanning the plane through the shared edge of two triangles that also
/// holds the sum of their unit normals (any rounding is harmless: any plane through the edge
/// is sound, see `split_within_exactly`); `None` when they share no edge or the plane
/// degenerates.
fn bisector_points(a: &[DVec3; 3], b: &[DVec3; 3]) -> Option<[DVec3; 3]> {
    let (shared, n) = shared_corners(a, b);
    let [p, q] = shared[..n] else {
        return None;
    };
    let normal = |t: &[DVec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
    let (na, nb) = (normal(a), normal(b));
    // Opposite orientations: the sum is not a bisector, the difference is.
    let d = if na.dot(nb) >= 0.0 { na + nb } else { na - nb };
    let r = p + d;
    if !r.is_finite() || d == DVec3::ZERO || collinear(p, q, r) {
        return None;
    }
    Some([p, q, r])
}

/// Three f64 points spanning a plane between two triangles that share exactly one corner
/// `v`: through `v`, holding the sum of their unit normals, and turned so that it separates
/// the directions from `v` to their centroids (f64; any plane is a sound cut, this one only
/// makes the pieces likely to be near their triangles). `None` when they share no single
/// corner or the plane degenerates.
fn vertex_bisector_points(a: &[DVec3; 3], b: &[DVec3; 3]) -> Option<[DVec3; 3]> {
    let (shared, n) = shared_corners(a, b);
    let [v] = shared[..n] else {
        return None;
    };
    let normal = |t: &[DVec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
    let (na, nb) = (normal(a), normal(b));
    let n = if na.dot(nb) >= 0.0 { na + nb } else { na - nb }.normalize_or_zero();
    let towards = |t: &[DVec3; 3]| ((t[0] + t[1] + t[2]) / 3.0 - v).normalize_or_zero();
    let m = towards(a) - towards(b);
    let m = (m - n * m.dot(n)).normalize_or_zero();
    let scale = (a[0] - a[1])
        .length()
        .max((a[1] - a[2]).length())
        .max((a[2] - a[0]).length());
    let (q, r) = (v + n * scale, v + n.cross(m) * scale);
    if n == DVec3::ZERO
        || m == DVec3::ZERO
        || !q.is_finite()
        || !r.is_finite()
        || collinear(v, q, r)
    {
        return None;
    }
    Some([v, q, r])
}

/// The plane through the shared edge of two triangles that also holds the sum of their unit
/// normals (f64, any rounding is harmless: see `split_within_exactly`); `None` when they
/// share no edge or the plane degenerates.
fn bisector(a: &[DVec3; 3], b: &[DVec3; 3]) -> Option<Plane> {
    let [p, q, r] = bisector_points(a, b)?;
    let (p, q, r) = (rpoint(p), rpoint(q), rpoint(r));
    let normal = cross(&sub(&q, &p), &sub(&r, &p));
    Some(Plane { origin: p, normal })
}

/// Splits a convex polygon by the signs of its vertices: (side <= 0, side >= 0), the
/// crossing points computed exactly.
fn clip_by_sign(poly: &[RPoint], side: &[Rational]) -> (Vec<RPoint>, Vec<RPoint>) {
    let (mut lo, mut hi) = (Vec::new(), Vec::new());
    for i in 0..poly.len() {
        let j = (i + 1) % poly.len();
        let (si, sj) = (&side[i], &side[j]);
        if *si <= 0 {
            lo.push(poly[i].clone());
        }
        if *si >= 0 {
            hi.push(poly[i].clone());
        }
        if (*si < 0 && *sj > 0) || (*si > 0 && *sj < 0) {
            let t = si / (si - sj);
            let x: RPoint = std::array::from_fn(|k| {
                let dk = &poly[j][k] - &poly[i][k];
                &poly[i][k] + (&dk * &t)
            });
            lo.push(x.clone());
            hi.push(x);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use Orientation::{Degenerate as Z, Negative as N, Positive as P};

    #[test]
    fn a_chord_changes_sign_at_most_twice() {
        for side in [
            &[N, P, P][..],
            &[N, N, P, P],
            &[N, Z, P, Z],
            &[N, Z, N, P],
            &[Z, N, P, Z, P],
        ] {
            assert!(is_chord(side), "{side:?}");
        }
        for side in [&[N, P, N, P][..], &[N, P, Z, N, P], &[P, N, P, N, Z, Z]] {
            assert!(!is_chord(side), "{side:?}");
        }
    }
}
