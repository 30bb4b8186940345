//! The Lagrange-form segment: its end-derivative rows and the exact change
//! between on-curve (Lagrange) points and Bezier control points.

use nalgebra::DMatrix;

use crate::basis::binomial;
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result, check_finite};

/// The Lagrange basis of degree `n` on `u = j / n`: derivatives at `u = 0`
/// and `u = 1`, and the exact map to Bezier control points.
pub(super) struct LagrangeBasis {
    pub(super) degree: usize,
    /// `at_start[m][j] = L_j^(m)(0)`.
    pub(super) at_start: Vec<Vec<f64>>,
    /// `at_end[m][j] = L_j^(m)(1)`.
    pub(super) at_end: Vec<Vec<f64>>,
    /// `to_bezier[(i, j)]`: weight of `y_j` in Bezier point `b_i`.
    pub(super) to_bezier: DMatrix<f64>,
}

impl LagrangeBasis {
    pub(super) fn new(n: usize) -> Self {
        // power coefficients in u of every L_j: power[j][k]
        let mut power = vec![vec![0.0; n + 1]; n + 1];
        for (j, row) in power.iter_mut().enumerate() {
            // integer polynomial prod_(l != j) (s - l), lowest power first
            let mut poly = vec![1.0f64];
            let mut denominator = 1.0f64;
            for l in 0..=n {
                if l == j {
                    continue;
                }
                let mut next = vec![0.0; poly.len() + 1];
                for (p, &c) in poly.iter().enumerate() {
                    next[p + 1] += c;
                    next[p] -= c * l as f64;
                }
                poly = next;
                denominator *= j as f64 - l as f64;
            }
            for (k, value) in row.iter_mut().enumerate() {
                *value = poly[k] * (n as f64).powi(k as i32) / denominator;
            }
        }
        let factorial = |m: usize| (1..=m).map(|v| v as f64).product::<f64>();
        let at_start: Vec<Vec<f64>> = (0..=n)
            .map(|m| (0..=n).map(|j| factorial(m) * power[j][m]).collect())
            .collect();
        let at_end: Vec<Vec<f64>> = (0..=n)
            .map(|m| {
                let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
                (0..=n).map(|j| sign * at_start[m][n - j]).collect()
            })
            .collect();
        let mut to_bezier = DMatrix::zeros(n + 1, n + 1);
        for i in 0..=n {
            for j in 0..=n {
                to_bezier[(i, j)] = (0..=i)
                    .map(|k| binomial(i, k) / binomial(n, k) * power[j][k])
                    .sum();
            }
        }
        Self {
            degree: n,
            at_start,
            at_end,
            to_bezier,
        }
    }

    pub(super) fn bezier_points(&self, dim: usize, on_curve: &[f64]) -> Vec<f64> {
        let n = self.degree;
        let mut out = vec![0.0; (n + 1) * dim];
        for i in 0..=n {
            for j in 0..=n {
                let w = self.to_bezier[(i, j)];
                for c in 0..dim {
                    out[i * dim + c] += w * on_curve[j * dim + c];
                }
            }
        }
        // the end points are the nodes themselves: keep them bit-exact so
        // consecutive segments share their join exactly
        out[..dim].copy_from_slice(&on_curve[..dim]);
        out[n * dim..].copy_from_slice(&on_curve[n * dim..]);
        out
    }
}

/// The exact Bezier form of the degree-`n` polynomial through the `n + 1`
/// points `on_curve` (row-major, `dim` each) at `u = j / n`, `n >= 1`.
///
/// Errors: `dim == 0`, fewer than 2 points or a length that is not a
/// multiple of `dim` (InvalidArgument), NaN/infinity (NonFinite).
pub fn bezier_from_lagrange_points(dim: usize, on_curve: &[f64]) -> Result<BezierCurve> {
    if dim == 0 {
        return Err(BezjoinError::invalid("dim", "must be at least 1"));
    }
    if on_curve.len() % dim != 0 || on_curve.len() < 2 * dim {
        return Err(BezjoinError::invalid(
            "on_curve",
            format!(
                "{} values do not make at least 2 points of dimension {dim}",
                on_curve.len()
            ),
        ));
    }
    check_finite("on_curve", on_curve)?;
    let n = on_curve.len() / dim - 1;
    let basis = LagrangeBasis::new(n);
    BezierCurve::new(dim, n, basis.bezier_points(dim, on_curve))
}

/// The `n + 1` points of `curve` at `u = j / n` (row-major): its Lagrange
/// form, the inverse of [`bezier_from_lagrange_points`].
pub fn lagrange_points_of_bezier(curve: &BezierCurve) -> Vec<f64> {
    let n = curve.degree();
    let dim = curve.dim();
    let mut out = vec![0.0; (n + 1) * dim];
    for j in 0..=n {
        let u = if n == 0 { 0.0 } else { j as f64 / n as f64 };
        curve.eval_into(u, &mut out[j * dim..(j + 1) * dim]);
    }
    out
}

#[cfg(test)]
mod segment_basis_tests {
    use super::*;

    #[test]
    fn cubic_end_derivatives_are_the_papers() {
        let b = LagrangeBasis::new(3);
        assert_eq!(b.at_start[1], vec![-5.5, 9.0, -4.5, 1.0]);
        assert_eq!(b.at_end[1], vec![-1.0, 4.5, -9.0, 5.5]);
    }

    #[test]
    fn lagrange_basis_reproduces_polynomials() {
        // y = u^n sampled at j/n: Bezier of u^n is (0, ..., 0, 1)
        for n in 1..=5 {
            let pts: Vec<f64> = (0..=n)
                .map(|j| (j as f64 / n as f64).powi(n as i32))
                .collect();
            let c = bezier_from_lagrange_points(1, &pts).unwrap();
            for i in 0..n {
                assert!(c.point(i)[0].abs() < 1e-14, "n={n} b{i}={}", c.point(i)[0]);
            }
            assert_eq!(c.point(n)[0], 1.0);
        }
    }
}
