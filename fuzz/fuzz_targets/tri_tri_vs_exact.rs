//! Triangle–triangle, segment–triangle, adjacent-face and coplanar-overlap predicates on the
//! filtered kernel against the same predicates on the exact kernel (every primitive also
//! cross-checked through `Checked`), plus symmetry/rotation laws. Triangles are decoded as in
//! `orient3d_vs_exact` (integer grids, ulp-neighbourhoods, raw doubles, points snapped onto
//! lines/planes through the other triangle's vertices); out-of-range coordinates are skipped.
#![no_main]

use envelope_fuzz::input::{Input, ok};
use envelope_predicates::generic as g;
use envelope_predicates::{Checked, Exact, Filtered, Shared};

type C = Checked<Filtered, Exact>;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mut input = Input(data);
    let mut p = Vec::new();
    for _ in 0..6 {
        let q = input.point(&p);
        p.push(q);
    }
    let mode = input.u8();
    if !ok(&p) {
        return;
    }
    let t1 = [p[0], p[1], p[2]];
    let mut t2 = [p[3], p[4], p[5]];
    // Sometimes make the faces adjacent.
    let shared = match mode % 3 {
        1 => {
            t2[0] = t1[0];
            Some(Shared::Vertex(0, 0))
        }
        2 => {
            t2[0] = t1[1];
            t2[1] = t1[0];
            Some(Shared::Edge([0, 1], [1, 0]))
        }
        _ => None,
    };
    let repro = format!("t1 = {t1:?}; t2 = {t2:?}");
    let f = g::triangles_intersect::<Filtered>(t1, t2);
    assert_eq!(
        f,
        g::triangles_intersect::<Exact>(t1, t2),
        "triangles_intersect: {repro}"
    );
    assert_eq!(f, g::triangles_intersect::<C>(t2, t1), "symmetry: {repro}");
    assert_eq!(
        f,
        g::triangles_intersect::<Filtered>([t1[1], t1[2], t1[0]], [t2[2], t2[0], t2[1]]),
        "rotation: {repro}"
    );
    let st = g::segment_triangle::<Filtered>(t2[0], t2[1], t1);
    assert_eq!(
        st,
        g::segment_triangle::<Exact>(t2[0], t2[1], t1),
        "segment_triangle: {repro}"
    );
    let ov = g::triangles_overlap_with_area::<Filtered>(t1, t2);
    assert_eq!(
        ov,
        g::triangles_overlap_with_area::<Exact>(t1, t2),
        "overlap: {repro}"
    );
    assert!(!ov || f, "overlap without intersection: {repro}");
    if let Some(s) = shared {
        let a = g::adjacent_triangles_intersect::<Filtered>(t1, t2, s);
        assert_eq!(
            a,
            g::adjacent_triangles_intersect::<Exact>(t1, t2, s),
            "adjacent: {repro}"
        );
        assert!(
            !a || f,
            "adjacent intersection without intersection: {repro}"
        );
    }
});
