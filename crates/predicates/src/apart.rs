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
            let d = q[k] - self.t[0];
            let v = self.n.dot(d);
            // Plus an absolute 1e-300 for underflow, as in `projection`.
            let tol = 6e-14 * self.m12 * d.abs().max_element() + 1e-300;
            pos &= v > tol;
            neg &= v < -tol;
        }
        any && (pos || neg)
    }
}

/// True when the closed triangles certainly meet nowhere except at the vertices they share
/// (`fs`/`gs` mark, per triangle, the vertices the other one has too): the unshared vertices
/// of one lie strictly on one side of the other's plane, so the intersection is at most the
/// shared vertices. A `false` decides nothing.
#[inline]
#[must_use]
pub fn surely_apart(p1: &Planar, fs: [bool; 3], p2: &Planar, gs: [bool; 3]) -> bool {
    p1.separates(p2.t, gs) || p2.separates(p1.t, fs) || edge_axes_apart(&p1.t, fs, &p2.t, gs)
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

/// The separating-axis test on the nine edge-cross-edge directions (any direction is a
/// valid axis, so the f64 cross products need no error bound; the projections carry one,
/// see [`projection`]). With no shared vertex: the projections of the two triangles are
/// disjoint intervals. With exactly one shared vertex `s`: the unshared vertices of one
/// project strictly below `s`, of the other strictly above, so the triangles (convex
/// combinations) meet at most in `s`. A `false` decides nothing.
#[must_use]
pub fn edge_axes_apart(t1: &[DVec3; 3], fs: [bool; 3], t2: &[DVec3; 3], gs: [bool; 3]) -> bool {
    let shared = fs.iter().filter(|&&b| b).count();
    if shared > 1 {
        return false;
    }
    let origin = match fs.iter().position(|&b| b) {
        Some(k) => t1[k],
        None => t1[0],
    };
    for i in 0..3 {
        let e1 = t1[(i + 1) % 3] - t1[i];
        for j in 0..3 {
            let l = e1.cross(t2[(j + 1) % 3] - t2[j]);
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
            let apart = if shared == 0 {
                hi1 < lo2 || hi2 < lo1
            } else {
                (hi1 < 0.0 && lo2 > 0.0) || (hi2 < 0.0 && lo1 > 0.0)
            };
            if apart {
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::indexed_triangles_intersect as tris_intersect;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
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

    /// Soundness against the exact test: on random pairs from a coarse grid (many touching,
    /// coplanar and collinear cases) and random f64 pairs, with no or one shared vertex,
    /// "apart" is never claimed for triangles that meet beyond what they share.
    #[test]
    fn pre_tests_never_claim_apart_for_meeting_triangles() {
        let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
        let mut claimed = 0;
        for round in 0..40_000 {
            let mut point = |grid: bool| {
                let mut c = || {
                    let r = next();
                    if grid {
                        (r % 5) as f64 - 2.0
                    } else {
                        (r >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
                    }
                };
                v(c(), c(), c())
            };
            let grid = round % 2 == 0;
            let t1 = [point(grid), point(grid), point(grid)];
            let mut t2 = [point(grid), point(grid), point(grid)];
            let (f, g) = if round % 4 < 2 {
                ([0, 1, 2], [3, 4, 5])
            } else {
                t2[0] = t1[0];
                ([0, 1, 2], [0, 4, 5])
            };
            let fs = f.map(|x| g.contains(&x));
            let gs = g.map(|x| f.contains(&x));
            let (p1, p2) = (Planar::new(t1), Planar::new(t2));
            if surely_apart(&p1, fs, &p2, gs) {
                claimed += 1;
                assert!(
                    !tris_intersect(t1, f, t2, g),
                    "claimed apart but meeting: {t1:?} {t2:?}"
                );
            }
        }
        assert!(claimed > 1000, "{claimed}");
    }

    fn surely_apart_planes(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
        let shared = |a: [DVec3; 3], b: [DVec3; 3]| a.map(|p| b.contains(&p));
        Planar::new(t1).separates(t2, shared(t2, t1))
            || Planar::new(t2).separates(t1, shared(t1, t2))
    }
}
