//! Shared helpers for the benchmarks.
#![forbid(unsafe_code)]

use glam::DVec3;

/// xorshift64*: deterministic inputs without extra dependencies.
pub struct Rng(pub u64);

impl Rng {
    /// A double in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A point in the unit cube.
    pub fn point(&mut self) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit())
    }
}
