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

/// Euclidean distance between two points of equal dimension.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "points of different dimensions");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Euclidean norm.
pub fn norm(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Binomial coefficient `C(n, k)` as `f64` by the multiplicative formula
/// (exact while the intermediate products stay below 2^53).
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut c = 1.0;
    for i in 0..k {
        c = c * (n - i) as f64 / (i + 1) as f64;
    }
    c
}

/// Independent reference for the derivatives of the Bernstein basis: the
/// `(max_order + 1) x (degree + 1)` matrix whose entry `(r, i)` is
/// `d^r/dt^r B_i^n(t)`, from the recursion
/// `d/dt B_i^n = n (B_{i-1}^{n-1} - B_i^{n-1})` (with `B_{-1} = B_n^{n-1} = 0`)
/// applied `r` times, down to the Bernstein polynomials of degree `n - r`
/// evaluated by their triangular recurrence
/// `B_i^m = (1 - t) B_i^{m-1} + t B_{i-1}^{m-1}`. Orders above `n` are zero.
/// Any finite `t` is accepted.
pub fn bezier_basis_derivatives(degree: usize, t: f64, max_order: usize) -> nalgebra::DMatrix<f64> {
    let n = degree;
    // bernstein[m][i] = B_i^m(t), m = 0..=n.
    let mut bernstein: Vec<Vec<f64>> = vec![vec![1.0]];
    for m in 1..=n {
        let prev = &bernstein[m - 1];
        let row: Vec<f64> = (0..=m)
            .map(|i| {
                let keep = if i < m { (1.0 - t) * prev[i] } else { 0.0 };
                let shift = if i > 0 { t * prev[i - 1] } else { 0.0 };
                keep + shift
            })
            .collect();
        bernstein.push(row);
    }
    let mut d = nalgebra::DMatrix::zeros(max_order + 1, n + 1);
    for r in 0..=max_order.min(n) {
        // The r-th derivative of B_i^n is n!/(n-r)! times the r-th backward
        // difference of the degree-(n - r) basis:
        // sum_j (-1)^(r-j) C(r, j) B_{i-j}^{n-r}.
        let falling: f64 = (0..r).map(|j| (n - j) as f64).product();
        let low = &bernstein[n - r];
        for i in 0..=n {
            let mut sum = 0.0;
            for j in 0..=r {
                if j <= i && i - j <= n - r {
                    let sign = if (r - j) % 2 == 0 { 1.0 } else { -1.0 };
                    sum += sign * binomial(r, j) * low[i - j];
                }
            }
            d[(r, i)] = falling * sum;
        }
    }
    d
}

/// Row-major values, `dim` per row, as a matrix (one row per point or per
/// derivative), for tests that check with matrix algebra.
pub fn rows_matrix(values: &[f64], dim: usize) -> nalgebra::DMatrix<f64> {
    assert_eq!(values.len() % dim, 0, "not a whole number of rows");
    nalgebra::DMatrix::from_row_slice(values.len() / dim, dim, values)
}

/// The control points of `c` as an `(n + 1) x dim` matrix (one per row).
pub fn control_matrix(c: &BezierCurve) -> nalgebra::DMatrix<f64> {
    rows_matrix(c.points(), c.dim())
}

/// The curve whose control points are the rows of `m`.
pub fn curve_from_matrix(m: &nalgebra::DMatrix<f64>) -> BezierCurve {
    let points = (0..m.nrows())
        .flat_map(|i| m.row(i).iter().copied().collect::<Vec<_>>())
        .collect();
    BezierCurve::new(m.ncols(), m.nrows() - 1, points).unwrap()
}

/// `max_i |a_i - b_i|` over two arrays of equal length.
pub fn max_abs_gap(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "arrays of different lengths");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The smallest value of `metric` over the merge's `mu` range by a dense
/// scan: 333 evenly spaced points in `(0, 1)`, then 61 points 20 times finer
/// around the best one, kept within the search range `[1e-3, 1 - 1e-3]`.
/// Returns `(best mu of the coarse scan, smallest value)`.
pub fn dense_scan_minimum(metric: impl Fn(f64) -> f64) -> (f64, f64) {
    let (mut scan_mu, mut scan_best) = (0.0, f64::INFINITY);
    const STEPS: usize = 334;
    let step = 1.0 / STEPS as f64;
    for k in 1..STEPS {
        let mu = k as f64 * step;
        let v = metric(mu);
        if v < scan_best {
            (scan_mu, scan_best) = (mu, v);
        }
    }
    for k in -30..=30 {
        let mu = scan_mu + k as f64 * step / 20.0;
        if (1e-3..=1.0 - 1e-3).contains(&mu) {
            scan_best = scan_best.min(metric(mu));
        }
    }
    (scan_mu, scan_best)
}

/// The smallest value of `metric` over the tails of the optimal `mu`'s
/// search range towards `1e-2`: at each end, from a decade closer to it
/// than the polygon split `polygon_mu` (at most `MIN_SPLIT` from it), 121
/// points evenly spaced in `ln mu` (`ln (1 - mu)`), then 41 points 20 times
/// finer around the best. Returns `(best mu, smallest value)`; `(NaN,
/// inf)` when the polygon split is within `1e-1` of neither end.
pub fn tail_scan_minimum(metric: impl Fn(f64) -> f64, polygon_mu: f64) -> (f64, f64) {
    const STEPS: usize = 120;
    let mut best = (f64::NAN, f64::INFINITY);
    for toward_one in [false, true] {
        let distance = if toward_one {
            1.0 - polygon_mu
        } else {
            polygon_mu
        };
        let reach = (distance / 10.0).max(bezjoin_core::MIN_SPLIT);
        if reach >= 1e-2 {
            continue;
        }
        let (lo, hi) = (reach.ln(), 1e-2f64.ln());
        let step = (hi - lo) / STEPS as f64;
        let at = |s: f64| {
            let d = s.exp().clamp(reach, 1e-2);
            if toward_one { 1.0 - d } else { d }
        };
        let mut side = (0.0, f64::INFINITY);
        for k in 0..=STEPS {
            let s = lo + k as f64 * step;
            let v = metric(at(s));
            if v < side.1 {
                side = (s, v);
            }
        }
        let centre = side.0;
        for k in -20..=20 {
            let s = centre + k as f64 * step / 20.0;
            let v = metric(at(s));
            if v < side.1 {
                side = (s, v);
            }
        }
        if side.1 < best.1 {
            best = (at(side.0), side.1);
        }
    }
    best
}

/// The optimal-split options of both metrics, with free and with fixed
/// ends.
pub fn optimal_split_variants() -> Vec<bezjoin_core::MergeOptions> {
    use bezjoin_core::{Breakpoints, MergeMetric, MergeOptions};
    let mut out = Vec::new();
    for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
        for fix_ends in [false, true] {
            let mut o = MergeOptions::default()
                .with_metric(metric)
                .with_split(Breakpoints::Optimal);
            o.fix_ends = fix_ends;
            out.push(o);
        }
    }
    out
}

/// The optimal split's metric `best` (at `mu`) is no larger than any of a
/// tail scan ([`tail_scan_minimum`] from the polygon split `polygon.0`), the
/// dense scan of the middle ([`dense_scan_minimum`]) and the polygon
/// split's own metric `polygon.1` (relative slack 1e-6); `metric_at` is the
/// merge's metric at a given `mu`, a `mu` where the solve is refused
/// (IllConditioned) being no answer, as in the search.
pub fn assert_no_split_beats(
    label: &str,
    (mu, best): (f64, f64),
    polygon: (f64, f64),
    metric_at: impl Fn(f64) -> bezjoin_core::Result<f64>,
) {
    let metric = |mu: f64| match metric_at(mu) {
        Ok(v) => v,
        Err(bezjoin_core::BezjoinError::IllConditioned { .. }) => f64::INFINITY,
        Err(e) => panic!("{label}: {e}"),
    };
    let (tail_mu, tail_best) = tail_scan_minimum(metric, polygon.0);
    let (_, middle_best) = dense_scan_minimum(metric);
    for (what, at, value) in [
        ("the tail scan", tail_mu, tail_best),
        ("the middle scan", f64::NAN, middle_best),
        ("the polygon split", polygon.0, polygon.1),
    ] {
        assert!(
            best <= value * (1.0 + 1e-6) + 1e-300,
            "{label}: optimal mu {mu} gives {best}, {what} {value} at {at}"
        );
    }
}

/// The documented speed of an end for the automatic and balanced scales:
/// `|X'(u)|` and the largest floor term `((BALANCED_SPEED_FLOOR c)^(j-1)
/// |X^(j)(u)|)^(1/j)`, `j = 2..=order` (0 when there is none), `c` the chord.
pub fn speed_and_floor(x: &BezierCurve, u: f64, order: usize, chord: f64) -> (f64, f64) {
    let floor = (2..=order)
        .map(|j| {
            ((bezjoin_core::BALANCED_SPEED_FLOOR * chord).powi(j as i32 - 1)
                * norm(&x.derivative_at(u, j)))
            .powf(1.0 / j as f64)
        })
        .fold(0.0, f64::max);
    (norm(&x.derivative_at(u, 1)), floor)
}
