//! The reference path: the full `(nr+1) x (nr+1)` system `C R = F` of the
//! paper's eq. 19, solved by LU ([`crate::linalg::solve_checked`]).

use nalgebra::DMatrix;

use super::{ConnectOptions, Connection, condition_rows, finish, prepare};
use crate::curve::CurveJet;
use crate::error::{BezjoinError, Result};
use crate::linalg::solve_checked;

/// [`super::connect`] by a plain dense solve of the whole system (rows
/// scaled to unit 1-norm), ignoring its structure. Same inputs, errors and
/// residual check; `constraint_condition` reports the condition estimate of
/// the whole scaled system. Used as the reference in tests and benchmarks;
/// `O(nr^3 + nr^2 d)`.
pub fn connect_dense_reference<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &ConnectOptions,
) -> Result<Connection> {
    let problem = prepare(p, u0, q, v0, options)?;
    let (alpha, beta) = options.scale.checked()?.ok_or_else(|| {
        BezjoinError::invalid(
            "scale",
            "the dense reference takes given scales, not Auto or Balanced",
        )
    })?;
    let conditions = condition_rows(&problem, alpha, beta);
    let size = conditions.rows.nrows();
    let mut a = DMatrix::<f64>::zeros(size, size);
    let mut b = DMatrix::<f64>::zeros(size, problem.dim);
    for r in 0..size {
        let norm: f64 = conditions.rows.row(r).iter().map(|v| v.abs()).sum();
        a.row_mut(r).copy_from(&(conditions.rows.row(r) / norm));
        b.row_mut(r).copy_from(&(conditions.targets.row(r) / norm));
    }
    let solution = solve_checked(&a, &b, "connect: dense reference system")?;
    finish(
        &problem,
        &conditions,
        solution.x,
        alpha,
        beta,
        solution.condition,
        "connect (dense reference)",
    )
}
