//! Every kernel primitive (orient2d/3d, insphere, and the filtered dot/distance/side tests) on
//! the filtered kernel against the exact GMP kernel, through `Checked<Filtered, Exact>`, which
//! panics with a pasteable reproduction on any disagreement. Inputs are decoded from the bytes
//! as small integer grids divided by powers of ten, ulp-neighbourhoods of them, raw doubles,
//! and points snapped onto lines and planes through earlier points (near-degenerate);
//! out-of-range coordinates (see `in_exact_range`) are skipped.
#![no_main]

use envelope_fuzz::input::{Input, ok};
use envelope_predicates::{Checked, Exact, Filtered, Kernel, in_exact_range};

type K = Checked<Filtered, Exact>;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mut input = Input(data);
    let mut p = Vec::new();
    for _ in 0..5 {
        let q = input.point(&p);
        p.push(q);
    }
    let eps2 = input.scalar().abs();
    if !ok(&p) || !in_exact_range(eps2) {
        return;
    }
    let [a, b, c, d, e] = [p[0], p[1], p[2], p[3], p[4]];
    let o = K::orient3d(a, b, c, d);
    assert_eq!(K::orient3d(b, a, c, d), o.reverse(), "swap law");
    let _ = K::orient2d(a.truncate(), b.truncate(), c.truncate());
    let _ = K::insphere(a, b, c, d, e);
    let _ = K::dot(a, b, c, d);
    let _ = K::cmp_sq_dist(a, b, eps2);
    let _ = K::cmp_sq_dist_point_line(a, b, c, eps2);
    let _ = K::cmp_sq_dist_point_plane(a, b, c, d, eps2);
    let _ = K::cmp_sq_dist_line_line(a, b, c, d, eps2);
    let _ = K::edge_side(a, b, c, d);
    let _ = K::closest_points_interior(a, b, c, d);
});
