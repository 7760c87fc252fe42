//! Triangle–triangle, segment–triangle, adjacent-face and coplanar-overlap predicates on the
//! filtered kernel against the same predicates on the exact kernel (every primitive also
//! cross-checked through `Checked`), plus symmetry/rotation laws. Triangles are decoded as in
//! `orient3d_vs_exact` (integer grids, ulp-neighbourhoods, raw doubles, points snapped onto
//! lines/planes through the other triangle's vertices); out-of-range coordinates are skipped.
#![no_main]

use envelope_predicates::generic as g;
use envelope_predicates::{Checked, Exact, Filtered, Shared, in_exact_range, next_down, next_up};
use glam::DVec3;

type C = Checked<Filtered, Exact>;

struct Input<'a>(&'a [u8]);

impl Input<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn raw(&mut self) -> f64 {
        let mut b = [0u8; 8];
        for x in &mut b {
            *x = self.u8();
        }
        f64::from_le_bytes(b)
    }
    fn scalar(&mut self) -> f64 {
        match self.u8() % 4 {
            0 | 1 => (self.u8() as i8) as f64 / 10f64.powi((self.u8() % 8) as i32),
            2 => {
                let mut x = (self.u8() as i8) as f64 / 10f64.powi((self.u8() % 4) as i32);
                let k = self.u8() as i8;
                for _ in 0..k.unsigned_abs() % 8 {
                    x = if k > 0 { next_up(x) } else { next_down(x) };
                }
                x
            }
            _ => self.raw(),
        }
    }
    fn point(&mut self, prev: &[DVec3]) -> DVec3 {
        let pick = |i: u8| if prev.is_empty() { DVec3::ZERO } else { prev[i as usize % prev.len()] };
        match self.u8() % 4 {
            0 | 1 => DVec3::new(self.scalar(), self.scalar(), self.scalar()),
            2 => {
                let (a, b) = (pick(self.u8()), pick(self.u8()));
                a + (b - a) * self.scalar()
            }
            _ => {
                let (a, b, c) = (pick(self.u8()), pick(self.u8()), pick(self.u8()));
                a + (b - a) * self.scalar() + (c - a) * self.scalar()
            }
        }
    }
}

fn ok(p: &[DVec3]) -> bool {
    p.iter().all(|q| q.to_array().iter().all(|&x| in_exact_range(x)))
}

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
    assert_eq!(f, g::triangles_intersect::<Exact>(t1, t2), "triangles_intersect: {repro}");
    assert_eq!(f, g::triangles_intersect::<C>(t2, t1), "symmetry: {repro}");
    assert_eq!(f, g::triangles_intersect::<Filtered>([t1[1], t1[2], t1[0]], [t2[2], t2[0], t2[1]]), "rotation: {repro}");
    let st = g::segment_triangle::<Filtered>(t2[0], t2[1], t1);
    assert_eq!(st, g::segment_triangle::<Exact>(t2[0], t2[1], t1), "segment_triangle: {repro}");
    let ov = g::triangles_overlap_with_area::<Filtered>(t1, t2);
    assert_eq!(ov, g::triangles_overlap_with_area::<Exact>(t1, t2), "overlap: {repro}");
    assert!(!ov || f, "overlap without intersection: {repro}");
    if let Some(s) = shared {
        let a = g::adjacent_triangles_intersect::<Filtered>(t1, t2, s);
        assert_eq!(a, g::adjacent_triangles_intersect::<Exact>(t1, t2, s), "adjacent: {repro}");
        assert!(!a || f, "adjacent intersection without intersection: {repro}");
    }
});
