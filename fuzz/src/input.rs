//! The byte decoder shared by the predicate fuzz targets: small integer grids divided by powers
//! of ten, ulp neighbourhoods of them, raw doubles, and points snapped onto lines and planes
//! through earlier points (near-degenerate inputs).

use envelope_predicates::{in_exact_range, next_down, next_up};
use glam::DVec3;

/// Decodes geometric inputs from fuzz bytes (missing bytes read as zero).
pub struct Input<'a>(pub &'a [u8]);

impl Input<'_> {
    /// The next byte.
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    /// Any double, from 8 raw bytes.
    pub fn raw(&mut self) -> f64 {
        let mut b = [0u8; 8];
        for x in &mut b {
            *x = self.u8();
        }
        f64::from_le_bytes(b)
    }
    /// A small integer over a power of ten, an ulp neighbourhood of one, or a raw double.
    pub fn scalar(&mut self) -> f64 {
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
    /// A grid point, or a point snapped onto a line or plane through earlier points.
    pub fn point(&mut self, prev: &[DVec3]) -> DVec3 {
        let pick = |i: u8| {
            if prev.is_empty() {
                DVec3::ZERO
            } else {
                prev[i as usize % prev.len()]
            }
        };
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

/// Every coordinate within the exact range (targets skip inputs that are not).
pub fn ok(p: &[DVec3]) -> bool {
    p.iter()
        .all(|q| q.to_array().iter().all(|&x| in_exact_range(x)))
}
