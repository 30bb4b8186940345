//! Helpers shared by the integration tests of `bezjoin-core`.
#![allow(dead_code)] // each test binary uses its own subset

use bezjoin_core::BezierCurve;

/// Deterministic pseudo-random numbers (xorshift64*): reproducible test data
/// without an extra dependency. The seed must be non-zero.
pub struct Random(pub u64);

impl Random {
    /// Uniform in `[0, 1)`, 53 random bits.
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    /// Uniform in `0..n` (`n >= 1`).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next() * n as f64) as usize).min(n - 1)
    }

    /// A curve whose control-point coordinates are uniform in
    /// `[-half_width, half_width)`.
    pub fn curve(&mut self, dim: usize, degree: usize, half_width: f64) -> BezierCurve {
        let points = (0..(degree + 1) * dim)
            .map(|_| self.range(-half_width, half_width))
            .collect();
        BezierCurve::new(dim, degree, points).unwrap()
    }
}
