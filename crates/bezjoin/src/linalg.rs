//! Small dense linear algebra with self-checks.
//!
//! Every solve here returns its solution together with a residual-based
//! accuracy estimate, so that callers can refuse an answer they cannot trust
//! (`BezjoinError::IllConditioned`) instead of returning silent garbage.

use nalgebra::DMatrix;

use crate::error::{BezjoinError, Result};

/// A solution of `A X = B` with its quality measures.
#[derive(Debug, Clone)]
pub(crate) struct CheckedSolution {
    /// The solution `X` (as many columns as `B`).
    pub(crate) x: DMatrix<f64>,
    /// `||A X - B||_inf / (||A||_inf ||X||_inf + ||B||_inf)`: the backward error.
    pub(crate) backward_error: f64,
    /// An estimate of the 1-norm condition number of `A` (from the LU factors).
    pub(crate) condition: f64,
}

impl CheckedSolution {
    /// Forward relative error estimate: condition times backward error.
    pub fn error_estimate(&self) -> f64 {
        self.condition * self.backward_error.max(f64::EPSILON)
    }
}

/// Infinity norm (largest absolute row sum).
pub(crate) fn norm_inf(m: &DMatrix<f64>) -> f64 {
    (0..m.nrows())
        .map(|i| m.row(i).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// Solve the square system `A X = B` by LU with partial pivoting, with one
/// step of iterative refinement, and report the backward error and the
/// condition estimate (`||A||_1 ||A^-1||_1`, the inverse formed from the
/// factors: these systems are small).
///
/// Errors: `Singular { what }` when a pivot vanishes; `DimensionMismatch`
/// when `A` is not square or `B` has another number of rows.
pub(crate) fn solve_checked(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    what: &str,
) -> Result<CheckedSolution> {
    if a.nrows() != a.ncols() {
        return Err(BezjoinError::DimensionMismatch {
            name: format!("{what}: columns of A"),
            expected: a.nrows(),
            actual: a.ncols(),
        });
    }
    if b.nrows() != a.nrows() {
        return Err(BezjoinError::DimensionMismatch {
            name: format!("{what}: rows of B"),
            expected: a.nrows(),
            actual: b.nrows(),
        });
    }
    let n = a.nrows();
    if n == 0 {
        return Ok(CheckedSolution {
            x: DMatrix::zeros(0, b.ncols()),
            backward_error: 0.0,
            condition: 1.0,
        });
    }
    let lu = a.clone().lu();
    let mut x = lu
        .solve(b)
        .ok_or_else(|| BezjoinError::Singular { what: what.into() })?;
    if x.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::Singular { what: what.into() });
    }
    // One step of iterative refinement.
    let r = b - a * &x;
    if let Some(dx) = lu.solve(&r) {
        if dx.iter().all(|v| v.is_finite()) {
            x += dx;
        }
    }
    let residual = b - a * &x;
    let denom = norm_inf(a) * norm_inf(&x) + norm_inf(b);
    let backward_error = if denom == 0.0 {
        0.0
    } else {
        norm_inf(&residual) / denom
    };
    let condition = match lu.try_inverse() {
        Some(inv) => norm_1(a) * norm_1(&inv),
        None => return Err(BezjoinError::Singular { what: what.into() }),
    };
    if !condition.is_finite() {
        return Err(BezjoinError::Singular { what: what.into() });
    }
    Ok(CheckedSolution {
        x,
        backward_error,
        condition,
    })
}

/// 1-norm (largest absolute column sum).
pub(crate) fn norm_1(m: &DMatrix<f64>) -> f64 {
    (0..m.ncols())
        .map(|j| m.column(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_and_reports_condition() {
        let a = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 3.0]);
        let b = DMatrix::from_row_slice(2, 1, &[3.0, 5.0]);
        let s = solve_checked(&a, &b, "test").unwrap();
        assert!((s.x[(0, 0)] - 0.8).abs() < 1e-15 && (s.x[(1, 0)] - 1.4).abs() < 1e-15);
        assert!(s.condition >= 1.0 && s.condition < 10.0);
        let sing = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(matches!(
            solve_checked(&sing, &b, "s"),
            Err(BezjoinError::Singular { .. })
        ));
    }
}
