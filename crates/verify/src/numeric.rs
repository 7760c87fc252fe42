//! Number helpers: directed rounding of squares and roots, the f64 closest-point distance used
//! only to *choose* what to certify, and the exact rational distance used for witnesses.
//!
//! Nothing in this module decides a verdict on its own: f64 distances are estimates; the
//! rational distance is exact; the directed-rounding helpers are proved bounds.

use envelope_predicates::exact_num::Rational;
use envelope_predicates::{next_down, next_up};
use glam::DVec3;

/// The largest double `<= x * x` (x >= 0).
pub(crate) fn square_down(x: f64) -> f64 {
    let s = x * x;
    // `fma` gives the exact residual x*x - s; negative means s rounded up.
    if x.mul_add(x, -s) < 0.0 {
        next_down(s)
    } else {
        s
    }
}

/// The smallest double `>= x * x` (x >= 0).
pub(crate) fn square_up(x: f64) -> f64 {
    let s = x * x;
    if x.mul_add(x, -s) > 0.0 {
        next_up(s)
    } else {
        s
    }
}

/// A double `>= sqrt(s)` (s >= 0).
pub(crate) fn sqrt_up(s: f64) -> f64 {
    let r = s.sqrt();
    if r.mul_add(r, -s) < 0.0 {
        next_up(r)
    } else {
        r
    }
}

/// A double `<= sqrt(s)` (s >= 0).
pub(crate) fn sqrt_down(s: f64) -> f64 {
    let r = s.sqrt();
    if r.mul_add(r, -s) > 0.0 {
        next_down(r).max(0.0)
    } else {
        r
    }
}

/// `a + b` rounded up (a, b >= 0).
pub(crate) fn add_up(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        a
    } else if a == 0.0 {
        b
    } else {
        next_up(a + b)
    }
}

/// Approximate squared distance from `p` to the closed triangle `t` in f64 (Ericson's
/// region test; degenerate triangles fall back to their edges). An *estimate*: it is only
/// used to pick which triangle and which bound to certify with the exact predicates.
#[must_use]
pub(crate) fn approx_sq_dist(p: DVec3, t: &[DVec3; 3]) -> f64 {
    approx_sq_dist_with(p, t, &TriNormal::new(t))
}

/// What [`approx_sq_dist`] computes of the triangle alone, once per triangle of a target:
/// the cross product of its edges from the first corner, and that vector's squared length,
/// negative for a flat (or NaN) triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriNormal {
    n: DVec3,
    n2: f64,
}

impl TriNormal {
    pub(crate) fn new(t: &[DVec3; 3]) -> TriNormal {
        let [a, b, c] = *t;
        let ab = b - a;
        let ac = c - a;
        let n = ab.cross(ac);
        let n2 = n.length_squared();
        let flat = n2.partial_cmp(&(1e-30 * ab.length_squared() * ac.length_squared()));
        TriNormal {
            n,
            n2: if flat == Some(std::cmp::Ordering::Greater) {
                n2
            } else {
                -1.0
            },
        }
    }
}

/// [`approx_sq_dist`] with the triangle's [`TriNormal`] given (the same value, bit for bit).
#[must_use]
pub(crate) fn approx_sq_dist_with(p: DVec3, t: &[DVec3; 3], tn: &TriNormal) -> f64 {
    let [a, b, c] = *t;
    let ab = b - a;
    let ac = c - a;
    if tn.n2 < 0.0 {
        return approx_sq_dist_segment(p, a, b)
            .min(approx_sq_dist_segment(p, b, c))
            .min(approx_sq_dist_segment(p, c, a));
    }
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length_squared();
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length_squared();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return approx_sq_dist_segment(p, a, b);
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length_squared();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return approx_sq_dist_segment(p, a, c);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return approx_sq_dist_segment(p, b, c);
    }
    // Interior: distance to the plane.
    let h = tn.n.dot(ap);
    h * h / tn.n2
}

fn approx_sq_dist_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    let s = if l2 > 0.0 {
        (ab.dot(p - a) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * s)).length_squared()
}

/// An exact rational point.
pub(crate) type RPoint = [Rational; 3];

/// The exact rational value of a double point.
pub(crate) fn rpoint(p: DVec3) -> RPoint {
    [p.x, p.y, p.z].map(rational)
}

/// The exact rational value of a finite double.
pub(crate) fn rational(x: f64) -> Rational {
    Rational::from_f64(x).expect("finite coordinate")
}

pub(crate) fn sub(a: &RPoint, b: &RPoint) -> RPoint {
    [(&a[0] - &b[0]), (&a[1] - &b[1]), (&a[2] - &b[2])]
}

pub(crate) fn dot(a: &RPoint, b: &RPoint) -> Rational {
    (&a[0] * &b[0]) + (&a[1] * &b[1]) + (&a[2] * &b[2])
}

pub(crate) fn cross(a: &RPoint, b: &RPoint) -> RPoint {
    [
        (&a[1] * &b[2]) - (&a[2] * &b[1]),
        (&a[2] * &b[0]) - (&a[0] * &b[2]),
        (&a[0] * &b[1]) - (&a[1] * &b[0]),
    ]
}

/// Exact squared distance from the rational point `p` to the closed segment `ab`.
fn sq_dist_segment_exact(p: &RPoint, a: &RPoint, b: &RPoint) -> Rational {
    let ab = sub(b, a);
    let ap = sub(p, a);
    let l2 = dot(&ab, &ab);
    let ap2 = dot(&ap, &ap);
    if l2 == 0 {
        return ap2;
    }
    let s = dot(&ab, &ap);
    if s <= 0 {
        return ap2;
    }
    if s >= l2 {
        let bp = sub(p, b);
        return dot(&bp, &bp);
    }
    // |ap|^2 - s^2 / |ab|^2 (Pythagoras, exact in rationals).
    ap2 - (&s * &s) / l2
}

/// Exact squared distance from the rational point `p` to the closed triangle `t`.
pub(crate) fn sq_dist_exact(p: &RPoint, t: &[DVec3; 3]) -> Rational {
    let [a, b, c] = t.map(rpoint);
    let ab = sub(&b, &a);
    let ac = sub(&c, &a);
    let n = cross(&ab, &ac);
    let n2 = dot(&n, &n);
    let edges = || {
        let d = sq_dist_segment_exact(p, &a, &b);
        let d = d.min(sq_dist_segment_exact(p, &b, &c));
        d.min(sq_dist_segment_exact(p, &c, &a))
    };
    if n2 == 0 {
        return edges();
    }
    // The projection of p is inside the closed triangle iff it is on the inner side of the
    // three edges: sign of ((e x n) . (p - v)) <= 0 for each directed edge e = v -> w.
    let inside = [(&a, &b), (&b, &c), (&c, &a)].iter().all(|(v, w)| {
        let e = sub(w, v);
        let side = dot(&cross(&e, &n), &sub(p, v));
        side <= 0
    });
    if inside {
        let h = dot(&n, &sub(p, &a));
        (&h * &h) / n2
    } else {
        edges()
    }
}

/// `(b0 a + b1 b + b2 c) / 2^level`, exactly.
pub(crate) fn barycentric_point(t: &[DVec3; 3], bary: [u64; 3], level: u32) -> RPoint {
    let den = Rational::from(envelope_predicates::exact_num::Integer::from(1) << level);
    let v = t.map(rpoint);
    std::array::from_fn(|k| {
        let s = (&v[0][k] * envelope_predicates::exact_num::Integer::from(bary[0]))
            + (&v[1][k] * envelope_predicates::exact_num::Integer::from(bary[1]))
            + (&v[2][k] * envelope_predicates::exact_num::Integer::from(bary[2]));
        s / &den
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directed_rounding() {
        for x in [0.1, 0.3, 1.0 / 3.0, 7.0, 1e-30] {
            assert!(rational(square_down(x)) <= rational(x) * rational(x));
            assert!(rational(square_up(x)) >= rational(x) * rational(x));
            let r = rational(sqrt_up(x));
            assert!((&r * &r) >= rational(x));
            let r = rational(sqrt_down(x));
            assert!((&r * &r) <= rational(x));
        }
    }

    #[test]
    fn exact_distance_matches_hand_values() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let d = |p: DVec3| sq_dist_exact(&rpoint(p), &t);
        assert_eq!(d(DVec3::new(0.25, 0.25, 2.0)), 4);
        assert_eq!(d(DVec3::new(-1.0, 0.0, 0.0)), 1);
        assert_eq!(d(DVec3::new(1.0, 1.0, 0.0)), Rational::from((1, 2)));
        assert_eq!(d(DVec3::new(0.5, -3.0, 4.0)), 25);
        let seg = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert_eq!(sq_dist_exact(&rpoint(DVec3::new(1.5, 2.0, 0.0)), &seg), 4);
        assert!((approx_sq_dist(DVec3::new(1.0, 1.0, 0.0), &t) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn barycentric_points_are_exact() {
        let t = [
            DVec3::ZERO,
            DVec3::new(0.1, 0.0, 0.0),
            DVec3::new(0.0, 0.3, 0.0),
        ];
        let p = barycentric_point(&t, [1, 1, 2], 2);
        assert_eq!(p[0], rational(0.1) / 4);
        assert_eq!(p[1], rational(0.3) / 2);
    }
}

/// `((b - a) x (c - a)) . (d - a)` evaluated in f64 (the sign convention of
/// `envelope_predicates::orient3d`), with a bound on its error: Shewchuk's stage-A bound
/// `(7 + 56 u) u * permanent` (u = 2^-53, "Adaptive precision floating-point arithmetic",
/// 1997), doubled, plus a term for underflow.
pub(crate) fn orient3d_with_bound(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> (f64, f64) {
    // Shewchuk's orient3d(a, b, c, d) is the negation of this convention: evaluate his
    // expression on (b, a, c, d), which swaps the sign.
    let (pa, pb, pc, pd) = (b, a, c, d);
    let (adx, bdx, cdx) = (pa.x - pd.x, pb.x - pd.x, pc.x - pd.x);
    let (ady, bdy, cdy) = (pa.y - pd.y, pb.y - pd.y, pc.y - pd.y);
    let (adz, bdz, cdz) = (pa.z - pd.z, pb.z - pd.z, pc.z - pd.z);
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    let u = f64::EPSILON / 2.0;
    let bound = 2.0 * (7.0 + 56.0 * u) * u * permanent + 64.0 * f64::MIN_POSITIVE;
    (det, bound)
}

/// Where the segment `x y` crosses a plane, given the plane's side values at its ends:
/// `sx`, `sy` approximate (errors at most `ex`, `ey`) with exactly known, strictly opposite
/// signs. Returns an f64 point and a proved bound on its distance to the exact crossing.
///
/// The exact crossing is `x + l (y - x)` with `l = |sx| / (|sx| + |sy|)` for the exact side
/// values; `l` lies in the interval the error bounds give (widened for the rounding of its
/// own computation), and the point is taken at its middle.
pub(crate) fn crossing_with_bound(
    x: DVec3,
    y: DVec3,
    (sx, ex): (f64, f64),
    (sy, ey): (f64, f64),
) -> (DVec3, f64) {
    let widen = 1e-15;
    let (ax, ay) = (sx.abs(), sy.abs());
    let lo = |v: f64, e: f64| ((v - e) * (1.0 - widen)).max(0.0);
    let hi = |v: f64, e: f64| (v + e) * (1.0 + widen);
    let l_lo = {
        let (a, b) = (lo(ax, ex), hi(ay, ey));
        if a + b > 0.0 {
            (a / (a + b) * (1.0 - widen)).max(0.0)
        } else {
            0.0
        }
    };
    let l_hi = {
        let (a, b) = (hi(ax, ex), lo(ay, ey));
        if a + b > 0.0 {
            (a / (a + b) * (1.0 + widen)).min(1.0)
        } else {
            1.0
        }
    };
    let (l_lo, l_hi) = if l_lo <= l_hi && l_hi.is_finite() {
        (l_lo, l_hi)
    } else {
        (0.0, 1.0)
    };
    let l = (0.5 * (l_lo + l_hi)).clamp(l_lo, l_hi);
    let p = x + (y - x) * l;
    // |l - l*| <= l_hi - l_lo; the rounding of `p` is below 3u per coordinate of
    // |x| + |y| (sqrt(3) for the Euclidean norm): 1e-15 covers it.
    let span = (y - x).length() * (1.0 + 1e-12);
    let round = 1e-15 * (x.abs().max_element() + y.abs().max_element()) + f64::MIN_POSITIVE;
    let err = add_up((l_hi - l_lo) * span * (1.0 + 1e-12), round);
    (p, err)
}

/// Proptest strategies shared by the crate's unit tests.
#[cfg(test)]
pub(crate) mod strategies {
    use glam::DVec3;
    use proptest::prelude::*;

    /// A coordinate: any double in [-8, 8), or a multiple of 1/8 there (exact ties).
    pub(crate) fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![-8.0f64..8.0, (-64i32..64).prop_map(|k| f64::from(k) / 8.0)]
    }

    /// A point of [`coord`]s.
    pub(crate) fn point() -> impl Strategy<Value = DVec3> {
        (coord(), coord(), coord()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }
}

#[cfg(test)]
mod crossing_tests {
    use super::strategies::point;
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        /// The f64 determinant is within its bound of the exact one, and the crossing point
        /// within its bound of the exact crossing (rational arithmetic).
        #[test]
        fn bounds_hold(a in point(), b in point(), c in point(), x in point(), y in point()) {
            let exact_side = |q: DVec3| {
                let (ra, rq) = (rpoint(a), rpoint(q));
                let n = cross(&sub(&rpoint(b), &ra), &sub(&rpoint(c), &ra));
                dot(&sub(&rq, &ra), &n)
            };
            for q in [x, y] {
                let (s, e) = orient3d_with_bound(a, b, c, q);
                let diff = (&exact_side(q) - rational(s)).abs();
                prop_assert!(diff <= rational(e), "side of {q:?}");
            }
            let (sx, sy) = (exact_side(x), exact_side(y));
            if (sx.is_positive() && sy.is_negative()) || (sx.is_negative() && sy.is_positive()) {
                let (p, err) = crossing_with_bound(
                    x, y, orient3d_with_bound(a, b, c, x), orient3d_with_bound(a, b, c, y));
                let t = &sx / (&sx - &sy);
                let (rx, ry) = (rpoint(x), rpoint(y));
                let star: RPoint = std::array::from_fn(|k| {
                    let dk = &ry[k] - &rx[k];
                    &rx[k] + (&dk * &t)
                });
                let d = sub(&rpoint(p), &star);
                let d2 = dot(&d, &d);
                let e = rational(err);
                prop_assert!(d2 <= (&e * &e), "crossing off by more than {err}");
            }
        }
    }
}
