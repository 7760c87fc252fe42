//! Exact distance comparisons (point–triangle, segment–triangle, triangle–triangle against a
//! squared tolerance) on the filtered kernel against the exact kernel, with the laws
//! `dist(T1, T2) <= dist(segment, T1) <= dist(vertex, T1)` and invariance under vertex rotation.
//! Inputs are decoded as in `orient3d_vs_exact`; out-of-range coordinates are skipped.
#![no_main]

use envelope_predicates::generic as g;
use envelope_predicates::{Checked, Exact, Filtered, in_exact_range, next_down, next_up};
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
    let e = input.scalar();
    // Either a given eps2 or the exact square of a grid value (a tie is likely).
    let eps2 = if input.u8() % 2 == 0 { e.abs() } else { e * e };
    if !ok(&p) || !in_exact_range(eps2) {
        return;
    }
    let t = [p[0], p[1], p[2]];
    let q = p[3];
    let repro = format!("t = {t:?}; q = {q:?}; p4 = {:?}; p5 = {:?}; eps2 = {eps2:?}", p[4], p[5]);
    let s = g::cmp_point_triangle::<Filtered>(q, t, eps2);
    assert_eq!(s, g::cmp_point_triangle::<Exact>(q, t, eps2), "point_triangle: {repro}");
    assert_eq!(s, g::cmp_point_triangle::<C>(q, [t[1], t[2], t[0]], eps2), "rotation: {repro}");
    let st = g::cmp_segment_triangle::<Filtered>(q, p[4], t, eps2);
    assert_eq!(st, g::cmp_segment_triangle::<Exact>(q, p[4], t, eps2), "segment_triangle: {repro}");
    let t2 = [q, p[4], p[5]];
    let tt = g::cmp_triangle_triangle::<Filtered>(t, t2, eps2);
    assert_eq!(tt, g::cmp_triangle_triangle::<Exact>(t, t2, eps2), "triangle_triangle: {repro}");
    assert!(tt <= st && st <= s, "monotonicity: {repro}");
});
