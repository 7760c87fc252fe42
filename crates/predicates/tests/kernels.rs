//! Kernel conventions, the range guard, and the known hard inputs.

use envelope_predicates::{
    Checked, Exact, Filtered, Kernel, MAX_ALLOWED_MAGNITUDE, MIN_ALLOWED_MAGNITUDE, Orientation,
    Sign, in_exact_range, next_down, next_up,
};
use glam::{DVec2, DVec3};

#[cfg(not(feature = "gmp"))]
type K = Checked<Filtered, Exact>;
/// With the feature `gmp` the two exact kernels are checked against each other too.
#[cfg(feature = "gmp")]
type K = Checked<Filtered, Checked<Exact, envelope_predicates::ExactGmp>>;

fn d3(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

#[test]
fn orient3d_convention_is_cgal_and_opposite_to_shewchuk() {
    let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
    // (b-a)×(c-a) = +z, so d = +z is on the normal's side: Positive.
    assert_eq!(K::orient3d(a, b, c, DVec3::Z), Orientation::Positive);
    assert_eq!(K::orient3d(a, b, c, -DVec3::Z), Orientation::Negative);
    assert_eq!(
        K::orient3d(a, b, c, d3(5.0, -7.0, 0.0)),
        Orientation::Degenerate
    );
    // Swapping two points flips the sign.
    assert_eq!(K::orient3d(b, a, c, DVec3::Z), Orientation::Negative);
    // robust (Shewchuk) says the opposite for the same call.
    let r = |p: DVec3| robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    };
    assert!(robust::orient3d(r(a), r(b), r(c), r(DVec3::Z)) < 0.0);
}

#[test]
fn orient2d_counter_clockwise_is_positive() {
    assert_eq!(
        K::orient2d(DVec2::ZERO, DVec2::X, DVec2::Y),
        Orientation::Positive
    );
    assert_eq!(
        K::orient2d(DVec2::ZERO, DVec2::Y, DVec2::X),
        Orientation::Negative
    );
    assert_eq!(
        K::orient2d(DVec2::ZERO, DVec2::ONE, DVec2::splat(3.0)),
        Orientation::Degenerate
    );
}

#[test]
fn insphere_convention() {
    let (a, b, c, d) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
    assert_eq!(K::orient3d(a, b, c, d), Orientation::Positive);
    assert_eq!(K::insphere(a, b, c, d, DVec3::splat(0.3)), Sign::Positive);
    assert_eq!(K::insphere(a, b, c, d, DVec3::splat(3.0)), Sign::Negative);
    assert_eq!(K::insphere(a, b, c, d, DVec3::ONE), Sign::Zero);
    // Negatively oriented tetrahedron: the sign flips.
    assert_eq!(K::insphere(b, a, c, d, DVec3::splat(0.3)), Sign::Negative);
}

#[test]
fn range_constants_and_guard() {
    assert_eq!(MAX_ALLOWED_MAGNITUDE, 2f64.powi(120));
    assert_eq!(MIN_ALLOWED_MAGNITUDE, 2f64.powi(-120));
    assert!(
        in_exact_range(MAX_ALLOWED_MAGNITUDE) && !in_exact_range(next_up(MAX_ALLOWED_MAGNITUDE))
    );
    assert!(
        in_exact_range(MIN_ALLOWED_MAGNITUDE) && !in_exact_range(next_down(MIN_ALLOWED_MAGNITUDE))
    );
    assert!(in_exact_range(-0.0) && !in_exact_range(f64::INFINITY) && !in_exact_range(f64::NAN));
}

/// robust's orient2d underflows on subnormal input: the product 5e-324 * 5e-324 is 0.
/// The filtered kernel sees the input is out of range and answers exactly.
#[test]
fn subnormal_5e_324_is_answered_exactly() {
    let t = 5e-324;
    let (a, b, c) = (DVec2::ZERO, DVec2::new(t, 0.0), DVec2::new(0.0, t));
    let raw = robust::orient2d(
        robust::Coord { x: a.x, y: a.y },
        robust::Coord { x: b.x, y: b.y },
        robust::Coord { x: c.x, y: c.y },
    );
    assert_eq!(
        raw, 0.0,
        "robust underflows here (that is why the range guard exists)"
    );
    assert_eq!(K::orient2d(a, b, c), Orientation::Positive);
    let (a3, b3, c3, d) = (
        DVec3::ZERO,
        d3(t, 0.0, 0.0),
        d3(0.0, t, 0.0),
        d3(0.0, 0.0, t),
    );
    assert_eq!(K::orient3d(a3, b3, c3, d), Orientation::Positive);
    assert_eq!(K::orient3d(a3, b3, c3, -d), Orientation::Negative);
    assert_eq!(K::insphere(a3, b3, c3, d, d3(t, t, t)), Sign::Zero);
    assert_eq!(
        K::cmp_sq_dist(d3(t, 0.0, 0.0), DVec3::ZERO, 0.0),
        Sign::Positive
    );
}

/// Mixed magnitudes (tiny and huge coordinates in one predicate) overflow or underflow inside
/// the expansions; out of range, the exact kernel decides.
#[test]
fn mixed_magnitudes() {
    let (tiny, huge) = (6.0e-300, -5.2e300);
    let a = DVec2::new(tiny, huge);
    let b = DVec2::new(8.3e-300, 5.7e-300);
    let c = DVec2::new(1.0e-310, 3.0e250);
    let _ = K::orient2d(a, b, c);
    let p = [
        d3(tiny, huge, 1.0),
        d3(1e-200, 1e-200, 1e-200),
        d3(1e200, -1e-200, 3.0),
        d3(0.5, 1e300, -1e300),
    ];
    let _ = K::orient3d(p[0], p[1], p[2], p[3]);
    let _ = K::insphere(p[0], p[1], p[2], p[3], d3(1.0, 2.0, 3.0));
    // An exactly coplanar configuration at mixed scales: the plane z = 0.
    let q = [
        d3(1e-300, 0.0, 0.0),
        d3(1e300, 1.0, 0.0),
        d3(-3.0, 1e-250, 0.0),
        d3(7e100, -2e-100, 0.0),
    ];
    assert_eq!(K::orient3d(q[0], q[1], q[2], q[3]), Orientation::Degenerate);
    // Huge coordinates whose products overflow f64 entirely.
    let h = 1e200;
    let z = 2f64.powi(-500);
    let r = [
        d3(0.0, 0.0, 0.0),
        d3(h, 0.0, 0.0),
        d3(0.0, h, 0.0),
        d3(1.0, 1.0, z),
    ];
    assert_eq!(K::orient3d(r[0], r[1], r[2], r[3]), Orientation::Positive);
    let d2 = 2f64.powi(-1000);
    assert_eq!(
        K::cmp_sq_dist_point_plane(r[3], r[0], r[1], r[2], d2),
        Sign::Zero
    );
    assert_eq!(
        K::cmp_sq_dist_point_plane(r[3], r[0], r[1], r[2], next_up(d2)),
        Sign::Negative
    );
    assert_eq!(
        K::cmp_sq_dist_point_plane(r[3], r[0], r[1], r[2], next_down(d2)),
        Sign::Positive
    );
}

#[test]
#[should_panic(expected = "non-finite coordinate")]
fn nan_panics_instead_of_answering() {
    let _ = Filtered::orient3d(DVec3::ZERO, DVec3::X, DVec3::Y, d3(f64::NAN, 0.0, 0.0));
}

#[test]
#[should_panic(expected = "non-finite coordinate")]
fn infinity_panics_in_filtered_primitives() {
    let _ = Filtered::cmp_sq_dist(DVec3::ZERO, d3(f64::INFINITY, 0.0, 0.0), 1.0);
}

/// A tiny deterministic generator (tests must not depend on rand).
struct Lcg(u64);
impl Lcg {
    fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 ^ (self.0 >> 29)
    }
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn point(&mut self, scale: f64) -> DVec3 {
        d3(
            self.range(-1.0, 1.0) * scale,
            self.range(-1.0, 1.0) * scale,
            self.range(-1.0, 1.0) * scale,
        )
    }
}

/// A point a + t (b - a), rounded to doubles: nearly (rarely exactly) collinear.
fn snapped_on_line(a: DVec3, b: DVec3, t: f64) -> DVec3 {
    a + (b - a) * t
}

fn check_all_primitives(p: [DVec3; 5], eps2: f64) {
    let [a, b, c, d, e] = p;
    let _ = K::orient3d(a, b, c, d);
    let _ = K::orient3d(d, a, b, c);
    let _ = K::insphere(a, b, c, d, e);
    let _ = K::orient2d(a.truncate(), b.truncate(), c.truncate());
    let _ = K::dot(a, b, c, d);
    let _ = K::cmp_sq_dist(a, b, eps2);
    let _ = K::cmp_sq_dist_point_line(a, b, c, eps2);
    let _ = K::cmp_sq_dist_point_plane(a, b, c, d, eps2);
    let _ = K::cmp_sq_dist_line_line(a, b, c, d, eps2);
    let _ = K::edge_side(a, b, c, d);
    let _ = K::closest_points_interior(a, b, c, d);
}

#[test]
fn near_degenerate_snapped_lines_and_planes() {
    let mut g = Lcg(1);
    for scale in [1.0, 1e-3, 1e7, 2f64.powi(100), 2f64.powi(-100)] {
        for _ in 0..300 {
            let (a, b, c) = (g.point(scale), g.point(scale), g.point(scale));
            let t = g.range(-2.0, 3.0);
            let on_line = snapped_on_line(a, b, t);
            let on_plane = a + (b - a) * g.unit() + (c - a) * g.unit();
            check_all_primitives([a, b, on_line, on_plane, c], scale * scale * g.unit());
            check_all_primitives([on_plane, a, b, c, on_line], 0.0);
        }
    }
}

#[test]
fn integer_grids_divided_by_powers_of_ten() {
    let mut g = Lcg(2);
    for k in [1, 3, 7, 16] {
        let s = 10f64.powi(k);
        for _ in 0..300 {
            let mut pt = || {
                d3(
                    (g.next_u64() % 7) as f64 / s,
                    (g.next_u64() % 7) as f64 / s,
                    (g.next_u64() % 7) as f64 / s,
                )
            };
            let p = [pt(), pt(), pt(), pt(), pt()];
            check_all_primitives(p, (2.0 / s) * (2.0 / s));
        }
    }
}

#[test]
fn nextafter_neighbourhoods() {
    // A degenerate configuration with each coordinate moved by a few ulps in every direction.
    let base = [
        d3(0.1, 0.2, 0.3),
        d3(0.4, 0.5, 0.6),
        d3(0.7, 0.8, 0.9),
        d3(1.0, 1.1, 1.2),
        d3(0.3, 0.3, 0.3),
    ];
    let nudge = |x: f64, k: i32| {
        let mut y = x;
        for _ in 0..k.abs() {
            y = if k > 0 { next_up(y) } else { next_down(y) };
        }
        y
    };
    for i in 0..5 {
        for axis in 0..3 {
            for k in -3..=3 {
                let mut p = base;
                p[i][axis] = nudge(p[i][axis], k);
                check_all_primitives(p, 0.01);
                check_all_primitives([p[1], p[3], p[0], p[2], p[4]], 0.0);
            }
        }
    }
}

#[test]
fn range_edges_agree_with_exact() {
    let mut g = Lcg(3);
    let top = 2f64.powi(120);
    let bottom = 2f64.powi(-120);
    for _ in 0..200 {
        // Coordinates within a few ulps of the limits, with signs, and near-degenerate.
        let mut edge = |lim: f64| {
            let m = if g.unit() < 0.5 {
                lim
            } else {
                if lim > 1.0 {
                    next_down(lim)
                } else {
                    next_up(lim)
                }
            };
            let m = m * if g.unit() < 0.5 { 1.0 } else { 0.75 };
            if g.unit() < 0.5 { -m } else { m }
        };
        let mut p = [DVec3::ZERO; 5];
        for q in &mut p {
            *q = d3(edge(top), edge(bottom), edge(top));
        }
        check_all_primitives(p, 0.0);
        let mut p2 = [DVec3::ZERO; 5];
        for q in &mut p2 {
            *q = d3(edge(bottom), edge(bottom), edge(bottom));
        }
        check_all_primitives(p2, 0.0);
        // Exactly coplanar at the top edge: z = 0 plane with huge and tiny coordinates.
        let flat = p.map(|q| d3(q.x, q.y, 0.0));
        assert_eq!(
            K::orient3d(flat[0], flat[1], flat[2], flat[3]),
            Orientation::Degenerate
        );
        // Collinear points on the bottom edge.
        let l = [
            d3(bottom, 0.0, 0.0),
            d3(2.0 * bottom, 0.0, 0.0),
            d3(-bottom, 0.0, 0.0),
        ];
        assert_eq!(K::cmp_sq_dist_point_line(l[2], l[0], l[1], 0.0), Sign::Zero);
    }
}
