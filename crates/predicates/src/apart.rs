//! Conservative f64 pre-tests for the exact triangle/triangle test: each answers "certainly
//! apart" (the closed triangles meet nowhere beyond the vertices they share) or "don't know",
//! never a wrong "apart", for coordinates whose f64 products do not overflow (those in
//! [`crate::MAX_ALLOWED_MAGNITUDE`]). They run in plain f64 with a rigorous bound on the rounding error,
//! so a caller may skip the exact test when one says apart and must run it otherwise; this is
//! the "conservative shortcut that can only reject" of the house style. Used by the envelope
//! growth engine and the envelope proof (`envelope-offset`).
//!
//! ```
//! use envelope_predicates::apart::{surely_apart, Planar};
//! use glam::DVec3;
//! let t1 = [DVec3::ZERO, DVec3::X, DVec3::Y];
//! let t2 = t1.map(|p| p + DVec3::Z); // the same triangle one unit higher
//! let none = [false; 3];
//! assert!(surely_apart(&Planar::new(t1), none, &Planar::new(t2), none));
//! let t3 = [DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.4, 0.4, 0.0)];
//! assert!(!surely_apart(&Planar::new(t1), none, &Planar::new(t3), none)); // pierces t1
//! ```
use glam::DVec3;

/// A triangle with its f64 plane normal and the scale of its error bound.
#[derive(Clone, Copy, Debug)]
pub struct Planar {
    /// The corners.
    pub t: [DVec3; 3],
    n: DVec3,
    m12: f64,
}

impl Planar {
    /// The plane of `t` in f64 (a construction; only [`Planar::separates`] reads it).
    #[inline]
    #[must_use]
    pub fn new(t: [DVec3; 3]) -> Self {
        let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
        Planar {
            t,
            n: e1.cross(e2),
            m12: e1.abs().max_element() * e2.abs().max_element(),
        }
    }

    /// The unshared points of `q` lie strictly on one side of this plane, beyond a bound on
    /// the rounding error of the f64 orientation (a generous multiple of Shewchuk's
    /// `o3derrboundA`).
    #[inline]
    #[must_use]
    pub fn separates(&self, q: [DVec3; 3], shared: [bool; 3]) -> bool {
        let (mut pos, mut neg, mut any) = (true, true, false);
        for k in 0..3 {
            if shared[k] {
                continue;
            }
            any = true;
            let (v, tol) = self.value(q[k]);
            pos &= v > tol;
            neg &= v < -tol;
            if !(pos || neg) {
                return false;
            }
        }
        any
    }

    /// The exact side of `p` of this plane when the f64 orientation tells it beyond its
    /// error bound ([`Planar::value`]): `Some(true)` positive, `Some(false)` negative, `None`
    /// too close to the plane to tell (or not a number).
    #[inline]
    pub(crate) fn side(&self, p: DVec3) -> Option<bool> {
        let (v, tol) = self.value(p);
        if v > tol {
            Some(true)
        } else if v < -tol {
            Some(false)
        } else {
            None
        }
    }

    /// The f64 orientation of `p` against the plane, and a bound on its error: the exact
    /// `orient3d(t0, t1, t2, p)` lies within `tol` of `v` (for coordinates whose products
    /// neither overflow nor underflow below the absolute 1e-300, as in [`projection`]).
    #[inline]
    fn value(&self, p: DVec3) -> (f64, f64) {
        let d = p - self.t[0];
        (
            self.n.dot(d),
            6e-14 * self.m12 * d.abs().max_element() + 1e-300,
        )
    }
}

/// True when the closed triangles certainly meet nowhere except at the vertices they share
/// (`fs`/`gs` mark, per triangle, the vertices the other one has too). Tried in turn: the
/// unshared vertices of one strictly on one side of the other's plane (the intersection is
/// then at most the shared vertices); the nine edge-cross-edge separating axes
/// ([`edge_axes_apart`]); and, for (nearly) coplanar pairs, which neither decides, the
/// in-plane separating axes and a plane through a shared edge ([`in_plane_apart`]). A
/// `false` decides nothing.
#[inline]
#[must_use]
pub fn surely_apart(p1: &Planar, fs: [bool; 3], p2: &Planar, gs: [bool; 3]) -> bool {
    p1.separates(p2.t, gs) || apart_beyond_first_plane(p1, fs, p2, gs)
}

/// [`surely_apart`] without its first test (`p1`'s plane), for a caller that has made it
/// already and makes `p2` only when it fails.
#[inline]
#[must_use]
pub fn apart_beyond_first_plane(p1: &Planar, fs: [bool; 3], p2: &Planar, gs: [bool; 3]) -> bool {
    p2.separates(p1.t, fs)
        || straddling_apart(p1, fs, p2, gs)
        || edge_axes_apart(&p1.t, fs, &p2.t, gs)
        || in_plane_apart(p1, fs, p2, gs)
}

/// Two triangles that each strictly straddle the other's plane, decided in error-bounded
/// f64 from orientations alone (every orientation used surely nonzero: beyond its error
/// bound, see [`Planar`], so its sign is the exact one). A `false` decides nothing.
///
/// With no shared vertex, Guigue and Devillers' test (the exact one is
/// `generic::intersect`'s `straddling_triangles_meet`): with every vertex surely off the
/// other plane, the signs, rotations and swaps are the exact test's; the triangles meet iff
/// `orient3d(p1, q1, p2, q2) <= 0` and `orient3d(p1, r1, r2, p2) <= 0`, so either surely
/// positive means apart.
///
/// With one shared vertex `v`, `t1 = [v, a1, b1]` and `t2 = [v, a2, b2]` up to rotation
/// (which keeps each plane's orientation), `n1`, `n2` their normals: each meets the other's
/// plane in a segment from `v` along the line where the planes cross, `[v, x1]` and
/// `[v, x2]`, and the triangles meet beyond `v` iff those point the same way. With
/// `w = (a1 - v) × n1`, `w · (x1 - v) < 0`, and writing `x2` on `a2 b2` and expanding
/// (Binet-Cauchy), `w · (x2 - v)` has the sign of `γ / α`, `α = orient3d(v, a1, b1, a2)`,
/// `γ = orient3d(v, a2, b2, a1)`: the triangles are apart iff `α` and `γ` have the same
/// sign. No new orientation at all: the four of the plane tests decide.
///
/// Either case replaces the nine edge axes ([`edge_axes_apart`]: up to nine axes of six
/// projections) that decided all the envelope proof's crossed pairs at small offsets.
#[must_use]
pub fn straddling_apart(p1: &Planar, fs: [bool; 3], p2: &Planar, gs: [bool; 3]) -> bool {
    let shared = fs.iter().filter(|&&b| b).count();
    if shared != gs.iter().filter(|&&b| b).count() || shared > 1 {
        return false;
    }
    let (Some(s1), Some(s2)) = (strict_sides(p2, &p1.t, fs), strict_sides(p1, &p2.t, gs)) else {
        return false;
    };
    // Both sides among the unshared corners (all on one side is the plane test's case).
    if !straddles(s1, fs) || !straddles(s2, gs) {
        return false;
    }
    if shared == 1 {
        // `a1` and `a2`: the corners after the shared one.
        let after = |own: [bool; 3]| own.iter().position(|&b| b).map_or(0, |k| (k + 1) % 3);
        let (a1, a2) = (after(fs), after(gs));
        // `s2[a2]`: the sign of alpha; `s1[a1]`: that of gamma.
        return s2[a2] == s1[a1];
    }
    guigue_devillers(p1, s1, p2, s2) == Some(false)
}

/// Whether two closed triangles with no shared vertex meet, decided in error-bounded f64
/// when every vertex of each is surely off the other's plane (see [`Planar`]): apart when
/// one plane has the other triangle on one side, else (each strictly straddles the other's
/// plane) Guigue and Devillers' two orientations, each surely nonzero (the exact test is
/// `generic::intersect`'s `straddling_triangles_meet`). `None` when an orientation is too
/// close to zero for f64 to tell: the exact test decides. For coordinates of at most
/// [`crate::MAX_ALLOWED_MAGNITUDE`]. Both answers are exact, so a caller may return either.
///
/// ```
/// use envelope_predicates::apart::{straddling_decides, Planar};
/// use glam::DVec3;
/// let t1 = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(2.0, -1.0, 0.0), DVec3::new(-1.0, 2.0, 0.0)];
/// let through = [DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.3, 0.2, 1.0), DVec3::new(0.2, 0.4, 1.0)];
/// let beside = through.map(|p| p + DVec3::new(5.0, 0.0, 0.0));
/// assert_eq!(straddling_decides(&Planar::new(t1), &Planar::new(through)), Some(true));
/// assert_eq!(straddling_decides(&Planar::new(t1), &Planar::new(beside)), Some(false));
/// ```
#[must_use]
pub fn straddling_decides(p1: &Planar, p2: &Planar) -> Option<bool> {
    let none = [false; 3];
    let s2 = strict_sides(p1, &p2.t, none)?;
    if !straddles(s2, none) {
        return Some(false);
    }
    let s1 = strict_sides(p2, &p1.t, none)?;
    if !straddles(s1, none) {
        return Some(false);
    }
    guigue_devillers(p1, s1, p2, s2)
}

/// The exact sides of `of`'s corners that `own` does not mark (the shared ones stay
/// `false`) of `plane` (`true`: positive), when every one is surely off it; else `None`.
fn strict_sides(plane: &Planar, of: &[DVec3; 3], own: [bool; 3]) -> Option<[bool; 3]> {
    let mut out = [false; 3];
    for k in (0..3).filter(|&k| !own[k]) {
        out[k] = plane.side(of[k])?;
    }
    Some(out)
}

/// Whether the corners that `own` does not mark lie on both sides (see [`strict_sides`]).
fn straddles(sides: [bool; 3], own: [bool; 3]) -> bool {
    let mut unshared = (0..3).filter(|&k| !own[k]).map(|k| sides[k]);
    let first = unshared.next();
    unshared.any(|s| Some(s) != first)
}

/// Guigue and Devillers' two orientations for triangles with no shared vertex that each
/// strictly straddle the other's plane, `s1[k]` (`s2[k]`) the exact side of `t1[k]`
/// (`t2[k]`) of the other plane (`true`: positive): `Some(false)` when either is surely
/// positive (apart), `Some(true)` when both are surely negative (they meet), else `None`.
fn guigue_devillers(p1: &Planar, s1: [bool; 3], p2: &Planar, s2: [bool; 3]) -> Option<bool> {
    let alone = |s: [bool; 3]| {
        if s[0] == s[1] {
            2
        } else if s[0] == s[2] {
            1
        } else {
            0
        }
    };
    let (i, j) = (alone(s1), alone(s2));
    let (t1, t2) = (&p1.t, &p2.t);
    let (a1, mut b1, mut c1) = (t1[i], t1[(i + 1) % 3], t1[(i + 2) % 3]);
    let (a2, mut b2, mut c2) = (t2[j], t2[(j + 1) % 3], t2[(j + 2) % 3]);
    if !s1[i] {
        std::mem::swap(&mut b2, &mut c2);
    }
    if !s2[j] {
        std::mem::swap(&mut b1, &mut c1);
    }
    let o1 = Planar::new([a1, b1, a2]).side(b2);
    let o2 = Planar::new([a1, c1, c2]).side(a2);
    if o1 == Some(true) || o2 == Some(true) {
        Some(false)
    } else if o1 == Some(false) && o2 == Some(false) {
        Some(true)
    } else {
        None
    }
}

/// `L·(p - o)` as an interval that certainly holds the exact value for the f64 points `p`,
/// `o` and the f64 vector `L`: the difference and the dot product each round by at most
/// `u` per operation, so `|error| <= 5u Σ|L_i||d_i|` (`d = fl(p - o)`); `8u` plus an
/// absolute `1e-300` for underflow is a safe margin.
#[inline]
fn projection(l: DVec3, p: DVec3, o: DVec3) -> (f64, f64) {
    let d = p - o;
    let v = l.dot(d);
    let tol = 8.0 * f64::EPSILON * l.abs().dot(d.abs()) + 1e-300;
    (v - tol, v + tol)
}

/// Whether axis `l` separates the two triangles (see [`edge_axes_apart`]): with no shared
/// vertex (`shared == 0`), disjoint projection intervals; with one, `origin` (the shared
/// vertex, which projects to exactly 0) strictly between the unshared vertices of one and
/// those of the other.
#[inline]
fn axis_apart(
    l: DVec3,
    (t1, fs): (&[DVec3; 3], [bool; 3]),
    (t2, gs): (&[DVec3; 3], [bool; 3]),
    origin: DVec3,
    shared: usize,
) -> bool {
    let (mut lo1, mut hi1, mut lo2, mut hi2) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for k in 0..3 {
        if !fs[k] {
            let (lo, hi) = projection(l, t1[k], origin);
            lo1 = lo1.min(lo);
            hi1 = hi1.max(hi);
        }
        if !gs[k] {
            let (lo, hi) = projection(l, t2[k], origin);
            lo2 = lo2.min(lo);
            hi2 = hi2.max(hi);
        }
    }
    if shared == 0 {
        hi1 < lo2 || hi2 < lo1
    } else {
        (hi1 < 0.0 && lo2 > 0.0) || (hi2 < 0.0 && lo1 > 0.0)
    }
}

/// The shared vertex of `t1` when there is exactly one (else `t1[0]`), and how many.
#[inline]
fn origin_of(t1: &[DVec3; 3], fs: [bool; 3]) -> (DVec3, usize) {
    let shared = fs.iter().filter(|&&b| b).count();
    let origin = match fs.iter().position(|&b| b) {
        Some(k) => t1[k],
        None => t1[0],
    };
    (origin, shared)
}

/// The separating-axis test on the nine edge-cross-edge directions (any direction is a
/// valid axis, so the f64 cross products need no error bound; the projections carry one,
/// see `projection`). With no shared vertex: the projections of the two triangles are
/// disjoint intervals. With exactly one shared vertex `s`: the unshared vertices of one
/// project strictly below `s`, of the other strictly above, so the triangles (convex
/// combinations) meet at most in `s`. A `false` decides nothing.
#[must_use]
pub fn edge_axes_apart(t1: &[DVec3; 3], fs: [bool; 3], t2: &[DVec3; 3], gs: [bool; 3]) -> bool {
    let (origin, shared) = origin_of(t1, fs);
    if shared > 1 {
        return false;
    }
    for i in 0..3 {
        let e1 = t1[(i + 1) % 3] - t1[i];
        for j in 0..3 {
            let l = e1.cross(t2[(j + 1) % 3] - t2[j]);
            if axis_apart(l, (t1, fs), (t2, gs), origin, shared) {
                return true;
            }
        }
    }
    false
}

/// For pairs in (nearly) one plane, where neither plane separates and every edge-cross-edge
/// axis is (nearly) the common normal. With no shared vertex: the separating axes `n1 × e`
/// for the six edges `e` of both triangles (`n1` the f64 normal of `t1`; any axis is valid,
/// see [`edge_axes_apart`]: these are the in-plane edge normals of the 2-D test). With one
/// shared vertex `s`: the axes `n1 × (u + w)`, `u` and `w` the unit directions from `s` to
/// an unshared vertex of `t1` and of `t2` (lines through `s` between the two triangles).
/// With a shared edge `ab`: the unshared vertices `c` of `t1` and `d` of `t2` strictly on
/// the two sides of the plane through `a`, `b` and the f64 point `e = a + n1 / |n1|·len`
/// (the plane holds `a` and `b` exactly, whatever `e` is; the sides are decided by the
/// error-bounded f64 orientation of [`Planar`]), so that `t1` and `t2` lie in the two closed
/// half-spaces and meet in that plane only, where each is the segment `ab`. A `false`
/// decides nothing.
#[must_use]
pub fn in_plane_apart(p1: &Planar, fs: [bool; 3], p2: &Planar, gs: [bool; 3]) -> bool {
    let (t1, t2) = (&p1.t, &p2.t);
    let (origin, shared) = origin_of(t1, fs);
    if shared > 2 {
        return false;
    }
    if shared == 2 {
        let (Some(c), Some(d)) = (fs.iter().position(|&b| !b), gs.iter().position(|&b| !b)) else {
            return false;
        };
        // The shared edge as `t1` orders it (`a` then `b` around `t1`).
        let (a, b) = (t1[(c + 1) % 3], t1[(c + 2) % 3]);
        let len = p1.m12.sqrt();
        if !(len > 0.0 && len.is_finite()) {
            return false;
        }
        let e = a + p1.n * (1.0 / len);
        let side = Planar::new([a, b, e]);
        let (vc, tc) = side.value(t1[c]);
        let (vd, td) = side.value(t2[d]);
        return (vc > tc && vd < -td) || (vc < -tc && vd > td);
    }
    let n1 = p1.n;
    if shared == 1 {
        // Lines through the shared vertex between an edge of each (the sum of their unit
        // directions): an edge's own line has its far vertex on it, never strictly apart.
        let unit = |p: DVec3| (p - origin).normalize_or_zero();
        let others = |t: &[DVec3; 3], m: [bool; 3]| {
            let mut o = [DVec3::ZERO; 2];
            let mut k = 0;
            for i in 0..3 {
                if !m[i] && k < 2 {
                    o[k] = unit(t[i]);
                    k += 1;
                }
            }
            o
        };
        let (u, w) = (others(t1, fs), others(t2, gs));
        return u.iter().any(|&a| {
            w.iter()
                .any(|&b| axis_apart(n1.cross(a + b), (t1, fs), (t2, gs), origin, shared))
        });
    }
    (0..3).any(|i| {
        let e1 = t1[(i + 1) % 3] - t1[i];
        let e2 = t2[(i + 1) % 3] - t2[i];
        axis_apart(n1.cross(e1), (t1, fs), (t2, gs), origin, shared)
            || axis_apart(n1.cross(e2), (t1, fs), (t2, gs), origin, shared)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::indexed_triangles_intersect as tris_intersect;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    /// Crossed triangles whose planes do not separate them; an edge-cross-edge axis does.
    #[test]
    fn edge_axes_separate_crossed_triangles() {
        let t1 = [v(-1.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0)];
        let t2 = [v(0.0, -1.0, 2.0), v(0.0, 1.0, 2.0), v(0.0, 0.0, 1.5)];
        let none = [false; 3];
        assert!(!surely_apart_planes(t1, t2));
        assert!(edge_axes_apart(&t1, none, &t2, none));
    }

    /// The apex of one triangle on an edge of the other: touching, never "apart".
    #[test]
    fn edge_axes_never_separate_touching_triangles() {
        let t1 = [v(-1.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0)];
        let t2 = [v(0.0, -1.0, 1.0), v(0.0, 1.0, 1.0), v(0.0, 0.0, 2.0)];
        assert!(!edge_axes_apart(&t1, [false; 3], &t2, [false; 3]));
        assert!(tris_intersect(t1, [0, 1, 2], t2, [3, 4, 5]));
    }

    /// One shared vertex, each triangle straddling the other's plane: a plane through the
    /// shared vertex separates them; when one passes through the other's interior, none.
    #[test]
    fn edge_axes_with_one_shared_vertex() {
        let s = DVec3::ZERO;
        let t1 = [s, v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)];
        let fs = [true, false, false];
        let apart = [s, v(-1.0, -1.0, 1.0), v(-1.0, -1.0, -1.0)];
        assert!(!surely_apart_planes(t1, apart));
        assert!(edge_axes_apart(&t1, fs, &apart, fs));
        assert!(!tris_intersect(t1, [0, 1, 2], apart, [0, 3, 4]));
        let through = [s, v(0.3, 0.3, 1.0), v(0.3, 0.3, -1.0)];
        assert!(!edge_axes_apart(&t1, fs, &through, fs));
        assert!(tris_intersect(t1, [0, 1, 2], through, [0, 3, 4]));
    }

    /// The f64 straddling test against the exact one on random crossed pairs (each
    /// straddling the other's plane) with no shared vertex and with one (at each position
    /// in either triangle): never "apart" for a pair that meets beyond what it shares, and
    /// "apart" for nearly every pair that does not (it fails when a swap, a rotation or the
    /// shared-vertex sign rule is wrong).
    #[test]
    fn straddling_apart_is_the_exact_answer_on_crossed_pairs() {
        let mut next = crate::xorshift(0x2545_F491_4F6C_DD1D);
        for shared in [0usize, 1] {
            let (mut apart, mut claimed, mut meeting) = (0, 0, 0);
            for round in 0..60_000 {
                let mut c = || (next() >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0;
                let mut t1 = [v(c(), c(), c()), v(c(), c(), c()), v(c(), c(), c())];
                let mut t2 = [v(c(), c(), c()), v(c(), c(), c()), v(c(), c(), c())];
                let (mut f, mut g) = ([0, 1, 2], [3, 4, 5]);
                if shared == 1 {
                    let (i, j) = (round % 3, (round / 3) % 3);
                    t2[j] = t1[i];
                    g[j] = f[i];
                }
                if round % 2 == 1 {
                    // The same pair the other way round.
                    (t1, t2, f, g) = (t2, t1, g, f);
                }
                let (fs, gs) = (f.map(|x| g.contains(&x)), g.map(|x| f.contains(&x)));
                let (p1, p2) = (Planar::new(t1), Planar::new(t2));
                if p1.separates(t2, gs) || p2.separates(t1, fs) {
                    continue;
                }
                // The exact test alone (the pre-tests would ask this one first).
                let meets = crate::exact_indexed(t1, t2, crate::shared_indices(f, g));
                let says = straddling_apart(&p1, fs, &p2, gs);
                assert!(!(says && meets), "{t1:?} {f:?} {t2:?} {g:?}");
                meeting += usize::from(meets);
                apart += usize::from(!meets);
                claimed += usize::from(says);
            }
            assert!(
                meeting > 500 && apart > 500,
                "{shared}: {meeting} meeting, {apart} apart"
            );
            assert!(
                claimed * 100 >= apart * 99,
                "{shared}: {claimed} of {apart} apart pairs claimed"
            );
        }
    }

    /// `straddling_decides` against the exact test on random pairs (f64 coordinates: apart,
    /// crossed and touching ones) and on grid pairs (many exact zeros, which it must leave
    /// to the exact test): every answer it gives is the exact one, and it answers nearly
    /// every random pair.
    #[test]
    fn straddling_decides_only_the_exact_answer() {
        let mut next = crate::xorshift(0x0DDB_1A5E_5BAD_5EED);
        let (mut decided, mut meeting, mut random) = (0, 0, 0);
        for round in 0..90_000 {
            let grid = round % 3 == 0;
            let mut c = || {
                let r = next();
                if grid {
                    (r % 5) as f64 - 2.0
                } else {
                    (r >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
                }
            };
            let t1 = [v(c(), c(), c()), v(c(), c(), c()), v(c(), c(), c())];
            let t2 = [v(c(), c(), c()), v(c(), c(), c()), v(c(), c(), c())];
            let exact = crate::generic::triangles_intersect::<crate::Filtered>(t1, t2);
            let says = straddling_decides(&Planar::new(t1), &Planar::new(t2));
            assert!(says.is_none_or(|x| x == exact), "{t1:?} {t2:?}: {says:?}");
            if !grid {
                random += 1;
                decided += usize::from(says.is_some());
                meeting += usize::from(says == Some(true));
            }
        }
        assert!(
            decided * 100 >= random * 99,
            "{decided} of {random} decided"
        );
        assert!(meeting > 2000, "{meeting} meeting");
    }

    /// Soundness against the exact test: on random pairs from a coarse grid (many touching,
    /// coplanar and collinear cases) and random f64 pairs, with no or one shared vertex,
    /// "apart" is never claimed for triangles that meet beyond what they share.
    #[test]
    fn pre_tests_never_claim_apart_for_meeting_triangles() {
        let mut next = crate::xorshift(0x9E37_79B9_7F4A_7C15);
        // Claimed apart: per number of shared vertices, and among coplanar pairs.
        let mut claimed = [0; 3];
        let mut coplanar_claimed = 0;
        for round in 0..120_000 {
            // Grid points, random points, and grid points in the plane z = x + y (coplanar
            // pairs: touching, overlapping and apart ones).
            let kind = round % 3;
            let mut point = || {
                let mut c = || {
                    let r = next();
                    if kind == 1 {
                        (r >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
                    } else {
                        (r % 5) as f64 - 2.0
                    }
                };
                let (x, y, z) = (c(), c(), c());
                if kind == 2 {
                    v(x, y, x + y)
                } else {
                    v(x, y, z)
                }
            };
            let t1 = [point(), point(), point()];
            let mut t2 = [point(), point(), point()];
            let shared = (round / 3) % 3;
            let (f, g) = match shared {
                0 => ([0, 1, 2], [3, 4, 5]),
                1 => {
                    t2[0] = t1[0];
                    ([0, 1, 2], [0, 4, 5])
                }
                _ => {
                    // The edge (1, 2) of t1, the other way round in t2 (as in a mesh).
                    t2[0] = t1[2];
                    t2[1] = t1[1];
                    ([0, 1, 2], [2, 1, 5])
                }
            };
            let fs = f.map(|x| g.contains(&x));
            let gs = g.map(|x| f.contains(&x));
            let (p1, p2) = (Planar::new(t1), Planar::new(t2));
            if surely_apart(&p1, fs, &p2, gs) {
                claimed[shared] += 1;
                if kind == 2 {
                    coplanar_claimed += 1;
                }
                // The exact test alone: `tris_intersect` asks these pre-tests first, so it
                // could not contradict them.
                assert!(
                    !crate::exact_indexed(t1, t2, crate::shared_indices(f, g)),
                    "claimed apart but meeting: {t1:?} {f:?} {t2:?} {g:?}"
                );
            }
        }
        assert!(claimed.iter().all(|&c| c > 1000), "{claimed:?}");
        assert!(coplanar_claimed > 1000, "{coplanar_claimed}");
    }

    /// Coplanar pairs that only the in-plane test decides: two faces of a flat strip sharing
    /// an edge, sharing a vertex, and sharing none.
    #[test]
    fn flat_neighbours_are_apart_in_plane() {
        let p = |x: f64, y: f64| v(x, y, 0.5 * x - 0.25 * y + 1.0);
        let (a, b, c, d, e) = (
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(0.0, 1.0),
            p(1.0, 1.0),
            p(2.0, 1.0),
        );
        let none = [false; 3];
        let cases = [
            (
                [a, b, c],
                [false, true, true],
                [b, d, c],
                [true, false, true],
            ),
            (
                [a, b, c],
                [false, true, false],
                [b, e, d],
                [true, false, false],
            ),
            ([a, b, c], none, [p(1.5, 0.0), e, d], none),
        ];
        for (t1, fs, t2, gs) in cases {
            let (p1, p2) = (Planar::new(t1), Planar::new(t2));
            assert!(!p1.separates(t2, gs) && !p2.separates(t1, fs));
            assert!(surely_apart(&p1, fs, &p2, gs), "{t1:?} {t2:?}");
        }
        // Overlapping in the plane: never apart.
        let (t1, t2) = ([a, b, c], [b, p(0.25, 0.25), c]); // exactly in the plane
        let fs = [false, true, true];
        let gs = [true, false, true];
        assert!(!surely_apart(&Planar::new(t1), fs, &Planar::new(t2), gs));
        assert!(tris_intersect(t1, [0, 1, 2], t2, [1, 9, 2]));
    }

    fn surely_apart_planes(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
        let shared = |a: [DVec3; 3], b: [DVec3; 3]| a.map(|p| b.contains(&p));
        Planar::new(t1).separates(t2, shared(t2, t1))
            || Planar::new(t2).separates(t1, shared(t1, t2))
    }
}
