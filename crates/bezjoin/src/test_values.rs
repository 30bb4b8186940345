//! Deterministic test inputs for the unit tests (a 64-bit LCG, fixed seed).

/// A 64-bit linear congruential generator (Knuth's MMIX constants).
pub(crate) struct Values(pub(crate) u64);

impl Values {
    /// The next value in `[0, 1)`: the top 53 bits of the state.
    pub(crate) fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next value in `[-1, 1)`: `2 unit - 1`, exact (a power-of-two
    /// scaling and a subtraction of values of the same binade or exact).
    pub(crate) fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
}

/// A planar Bezier curve of `degree` whose coordinates are the generator's
/// next `signed` values (the state carried in `state`), for the merge tests.
pub(crate) fn planar_curve(state: &mut u64, degree: usize) -> crate::bezier::BezierCurve {
    let mut values = Values(*state);
    let points = (0..(degree + 1) * 2).map(|_| values.signed()).collect();
    *state = values.0;
    crate::bezier::BezierCurve::new(2, degree, points).unwrap()
}
