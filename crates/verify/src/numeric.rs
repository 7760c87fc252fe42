//! Number helpers: directed rounding of squares and roots, the f64 closest-point distance used
//! only to *choose* what to certify, and the exact rational distance used for witnesses.
//!
//! Nothing in this module decides a verdict on its own: f64 distances are estimates; the
//! rational distance is exact; the directed-rounding helpers are proved bounds.

use envelope_predicates::{next_down, next_up};
use glam::DVec3;
use rug::Rational;

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
    let [a, b, c] = *t;
    let ab = b - a;
    let ac = c - a;
    let n2 = ab.cross(ac).length_squared();
    let flat = n2.partial_cmp(&(1e-30 * ab.length_squared() * ac.length_squared()));
    if flat != Some(std::cmp::Ordering::Greater) {
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
    let n = ab.cross(ac);
    let h = n.dot(ap);
    h * h / n2
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
    [
        Rational::from(&a[0] - &b[0]),
        Rational::from(&a[1] - &b[1]),
        Rational::from(&a[2] - &b[2]),
    ]
}

pub(crate) fn dot(a: &RPoint, b: &RPoint) -> Rational {
    Rational::from(&a[0] * &b[0]) + Rational::from(&a[1] * &b[1]) + Rational::from(&a[2] * &b[2])
}

pub(crate) fn cross(a: &RPoint, b: &RPoint) -> RPoint {
    [
        Rational::from(&a[1] * &b[2]) - Rational::from(&a[2] * &b[1]),
        Rational::from(&a[2] * &b[0]) - Rational::from(&a[0] * &b[2]),
        Rational::from(&a[0] * &b[1]) - Rational::from(&a[1] * &b[0]),
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
    ap2 - Rational::from(&s * &s) / l2
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
        Rational::from(&h * &h) / n2
    } else {
        edges()
    }
}

/// `(b0 a + b1 b + b2 c) / 2^level`, exactly.
pub(crate) fn barycentric_point(t: &[DVec3; 3], bary: [u64; 3], level: u32) -> RPoint {
    let den = Rational::from(rug::Integer::from(1) << level);
    let v = t.map(rpoint);
    std::array::from_fn(|k| {
        let s = Rational::from(&v[0][k] * rug::Integer::from(bary[0]))
            + Rational::from(&v[1][k] * rug::Integer::from(bary[1]))
            + Rational::from(&v[2][k] * rug::Integer::from(bary[2]));
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
            assert!(Rational::from(&r * &r) >= rational(x));
            let r = rational(sqrt_down(x));
            assert!(Rational::from(&r * &r) <= rational(x));
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
