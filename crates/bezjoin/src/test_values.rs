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

    /// An entry for the bit-for-bit tests of maxima: from one `signed`
    /// value `v`, in about one case in eight each a zero of `v`'s sign, a
    /// NaN, an infinity of `v`'s sign, a subnormal; otherwise `1e3 v`.
    /// Every fifth `round` is all NaN.
    pub(crate) fn hostile(&mut self, round: usize) -> f64 {
        let v = self.signed();
        match (round % 5, (v * 16.0) as i64) {
            (4, _) => f64::NAN,
            (_, 0) => 0.0 * v.signum(),
            (_, 1) => f64::NAN,
            (_, -1) => f64::INFINITY * v.signum(),
            (_, 2) => v * 1e-310,
            _ => v * 1e3,
        }
    }
}

/// The bits of every value, for asserting that two routes agree bit for
/// bit (`-0` against `+0` and NaN payloads included).
pub(crate) fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// [`Values::unit`] as a closure from the state `seed` (the same sequence).
pub(crate) fn unit_generator(seed: u64) -> impl FnMut() -> f64 {
    let mut values = Values(seed);
    move || values.unit()
}

/// A planar Bezier curve of `degree` whose coordinates are the generator's
/// next `signed` values (the state carried in `state`), for the merge tests.
pub(crate) fn planar_curve(state: &mut u64, degree: usize) -> crate::bezier::BezierCurve {
    let mut values = Values(*state);
    let points = (0..(degree + 1) * 2).map(|_| values.signed()).collect();
    *state = values.0;
    crate::bezier::BezierCurve::new(2, degree, points).unwrap()
}

/// The exact jet `C^(k)(u)`, `k = 0..=order`, of the polynomial whose
/// Bezier control points on `[a, b]` are `poles` (degree `p`, a Bezier
/// curve on `[0, 1]`, a one-span NURBS elsewhere), from the f64 data in
/// rational arithmetic: `t = (u - a) / (b - a)`, the de Casteljau
/// triangle, `p!/(p-k)! Delta^k` and `(b - a)^-k`.
#[allow(clippy::needless_range_loop)]
pub(crate) fn exact_bezier_jet(
    poles: &[f64],
    dim: usize,
    p: usize,
    (a, b, u): (f64, f64, f64),
    order: usize,
) -> Vec<Vec<num_rational::BigRational>> {
    use num_rational::BigRational;
    let exact = |x: f64| BigRational::from_float(x).expect("finite");
    let level: Vec<Vec<BigRational>> = (0..=p)
        .map(|i| {
            poles[i * dim..(i + 1) * dim]
                .iter()
                .map(|&v| exact(v))
                .collect()
        })
        .collect();
    exact_bezier_jet_of(level, dim, p, (exact(a), exact(b), exact(u)), order)
}

/// [`exact_bezier_jet`] of exact poles (`p + 1` rows of `dim`) on the
/// exact domain `(a, b)` at the exact `u`.
#[allow(clippy::needless_range_loop)]
pub(crate) fn exact_bezier_jet_of(
    mut level: Vec<Vec<num_rational::BigRational>>,
    dim: usize,
    p: usize,
    (a, b, u): (
        num_rational::BigRational,
        num_rational::BigRational,
        num_rational::BigRational,
    ),
    order: usize,
) -> Vec<Vec<num_rational::BigRational>> {
    use num_rational::BigRational;
    use num_traits::{One, Zero};
    let h = &b - &a;
    let t = (u - &a) / &h;
    let s = BigRational::one() - &t;
    let mut jet = vec![vec![BigRational::zero(); dim]; order + 1];
    for l in 0..=p {
        if l > 0 {
            for i in 0..=p - l {
                for c in 0..dim {
                    level[i][c] = &s * &level[i][c] + &t * &level[i + 1][c];
                }
            }
        }
        let k = p - l;
        if k > order {
            continue;
        }
        let mut work = level[..=k].to_vec();
        for pass in 0..k {
            for i in 0..k - pass {
                for c in 0..dim {
                    work[i][c] = &work[i + 1][c] - &work[i][c];
                }
            }
        }
        let falling: i64 = (0..k).map(|j| (p - j) as i64).product();
        let mut factor = BigRational::from_integer(falling.into());
        for _ in 0..k {
            factor /= &h;
        }
        for c in 0..dim {
            jet[k][c] = &work[0][c] * &factor;
        }
    }
    jet
}
