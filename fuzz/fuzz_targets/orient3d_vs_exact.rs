//! Every kernel primitive (orient2d/3d, insphere, and the filtered dot/distance/side tests) on
//! the filtered kernel against the exact GMP kernel, through `Checked<Filtered, Exact>`, which
//! panics with a pasteable reproduction on any disagreement. Inputs are decoded from the bytes
//! as small integer grids divided by powers of ten, ulp-neighbourhoods of them, raw doubles,
//! and points snapped onto lines and planes through earlier points (near-degenerate);
//! out-of-range coordinates (see `in_exact_range`) are skipped.
#![no_main]

use envelope_predicates::{Checked, Exact, Filtered, Kernel, in_exact_range, next_down, next_up};
use glam::DVec3;

type K = Checked<Filtered, Exact>;

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
