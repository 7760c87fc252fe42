//! Exact distance comparisons (point–triangle, segment–triangle, triangle–triangle against a
//! squared tolerance) on the filtered kernel against the exact kernel, with the laws
//! `dist(T1, T2) <= dist(segment, T1) <= dist(vertex, T1)` and invariance under vertex rotation.
//! Inputs are decoded as in `orient3d_vs_exact`; out-of-range coordinates are skipped.
#![no_main]

use envelope_fuzz::input::{Input, ok};
use envelope_predicates::generic as g;
use envelope_predicates::{Checked, Exact, Filtered, in_exact_range};

type C = Checked<Filtered, Exact>;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mut input = Input(data);
    let mut p = Vec::new();
    for _ in 0..6 {
        let q = input.point(&p);
        p.push(q);
    }
    let e = input.scalar();
    // Either a given eps2 or the exact square of a grid value (a tie is likely).
    let eps2 = if input.u8() % 2 == 0 { e.abs() } else { e * e };
    if !ok(&p) || !in_exact_range(eps2) {
        return;
    }
    let t = [p[0], p[1], p[2]];
    let q = p[3];
    let repro = format!(
        "t = {t:?}; q = {q:?}; p4 = {:?}; p5 = {:?}; eps2 = {eps2:?}",
        p[4], p[5]
    );
    let s = g::cmp_point_triangle::<Filtered>(q, t, eps2);
    assert_eq!(
        s,
        g::cmp_point_triangle::<Exact>(q, t, eps2),
        "point_triangle: {repro}"
    );
    assert_eq!(
        s,
        g::cmp_point_triangle::<C>(q, [t[1], t[2], t[0]], eps2),
        "rotation: {repro}"
    );
    let st = g::cmp_segment_triangle::<Filtered>(q, p[4], t, eps2);
    assert_eq!(
        st,
        g::cmp_segment_triangle::<Exact>(q, p[4], t, eps2),
        "segment_triangle: {repro}"
    );
    let t2 = [q, p[4], p[5]];
    let tt = g::cmp_triangle_triangle::<Filtered>(t, t2, eps2);
    assert_eq!(
        tt,
        g::cmp_triangle_triangle::<Exact>(t, t2, eps2),
        "triangle_triangle: {repro}"
    );
    assert!(tt <= st && st <= s, "monotonicity: {repro}");
});
