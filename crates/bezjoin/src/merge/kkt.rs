//! The KKT path of stage 1 (no piece kept): the metric minimised subject to
//! the independent rows, with the a-posteriori error estimate.

use nalgebra::{DMatrix, DVector};

use crate::error::{BezjoinError, Result};
use crate::linalg::solve_checked;

use super::MergeMetric;
use super::rows::{Problem, Row, check_dependent_rows, extend_orthonormal};
use super::stage_one::{
    CONSISTENCY_TOLERANCE, DATA_ROUNDING_MARGIN, RANK_TOLERANCE, StageOneCheck,
    bernstein_gram_matrix,
};

/// The KKT path (no piece kept): the new control points `x0 + e` and the
/// error estimate, after the dependent rows are checked.
pub(super) fn kkt_solution(
    problem: &Problem<'_, '_>,
    metric: MergeMetric,
    accuracy: f64,
    check: StageOneCheck,
) -> Result<(DMatrix<f64>, f64)> {
    let (unknowns, points_per_piece, dim) =
        (problem.unknowns, problem.points_per_piece, problem.dim);
    let count = problem.pieces.len();
    let m = points_per_piece - 1;
    let x0 = problem.x0().view();

    // The rows are replaced by an orthonormal basis of their span (same
    // feasible set, a well-conditioned KKT matrix): the continuity rows by
    // Householder QR, `A_c^T = Q T`, so `A_c e = -A_c x0` becomes
    // `Q^T e = -Q^T x0` exactly; then the constraint rows in order by
    // Gram-Schmidt (two passes), a row whose remainder is at the rounding
    // level `RANK_TOLERANCE sqrt(N)` being linearly dependent on those
    // before it. Any larger remainder, however small, keeps the row: the
    // ill-conditioning is then the estimate's business.
    let mut basis: Vec<(DVector<f64>, DVector<f64>)> = {
        let mut at = DMatrix::zeros(unknowns, problem.continuity().len());
        for (c, row) in problem.continuity().iter().enumerate() {
            at.set_column(c, &row.coefficients);
        }
        let q = at.qr().q();
        (0..q.ncols())
            .map(|c| {
                let column = q.column(c).into_owned();
                let rhs = -(x0.transpose() * &column);
                (column, rhs)
            })
            .collect()
    };
    let rank_tolerance = RANK_TOLERANCE * (unknowns as f64).sqrt();
    let (kept, dependent) =
        extend_orthonormal(&mut basis, problem.constraints(), rank_tolerance, unknowns);

    // KKT system [W B^T; B 0] [e; lambda] = [0; c] with the orthonormal rows B.
    let weight = match metric {
        MergeMetric::Discrete => DMatrix::identity(points_per_piece, points_per_piece),
        // Scaled by 2m + 1 so its entries are of order one (e is unchanged).
        MergeMetric::Integral => bernstein_gram_matrix(m) * (2 * m + 1) as f64,
    };
    let size = unknowns + basis.len();
    let mut kkt = DMatrix::zeros(size, size);
    let mut rhs = DMatrix::zeros(size, dim);
    for j in 0..count {
        kkt.view_mut(
            (j * points_per_piece, j * points_per_piece),
            (points_per_piece, points_per_piece),
        )
        .copy_from(&weight);
    }
    for (k, (coefficients, row_rhs)) in basis.iter().enumerate() {
        for i in 0..unknowns {
            kkt[(unknowns + k, i)] = coefficients[i];
            kkt[(i, unknowns + k)] = coefficients[i];
        }
        rhs.row_mut(unknowns + k).copy_from(&row_rhs.transpose());
    }
    let solution = solve_checked(&kkt, &rhs, "the merge KKT system")?;
    // A posteriori: condition x backward error of the solve itself, but at
    // least the first-order effect of the rounding that the constraint rows
    // carry (their entries, the orthonormalisation): a relative perturbation
    // of size eps of the rows moves the feasible set by up to
    // cond(rows) eps (relative to the data), and the W-orthogonal projection
    // onto it magnifies that by at most sqrt(cond(Z^T W Z)), the reduced
    // (null-space) problem's condition. The factor 4 is a measured margin
    // (test merge_exact: the estimate bounds the true error against an exact
    // rational solution in every case, degrees 1..30).
    let estimate = match check {
        StageOneCheck::Full => solution.error_estimate().max(
            DATA_ROUNDING_MARGIN
                * f64::EPSILON
                * row_matrix_condition(problem.continuity(), &kept, unknowns)
                * match metric {
                    // W = I: Z^T W Z = Z^T Z = I for the orthonormal Z.
                    MergeMetric::Discrete => 1.0,
                    MergeMetric::Integral => {
                        reduced_condition(&basis, &weight, count, points_per_piece).sqrt()
                    }
                },
        ),
        StageOneCheck::Trial => solution.error_estimate(),
    };
    let e = solution.x.rows(0, unknowns).into_owned();

    // Dependent rows: the exact solution of the kept rows satisfies a
    // consistent one exactly, so the computed one misses it by at most its
    // own error (`sqrt(N)` estimate x scale for a unit row) plus the
    // rounding of the row (`N` eps x scale). Missed by more than
    // CONTRADICTION_MARGIN times that (and the tolerance): contradictory.
    let result_scale = (x0 + &e).amax().max(problem.scale);
    let tolerance = CONSISTENCY_TOLERANCE.max(accuracy) * problem.extent;
    let root = (unknowns as f64).sqrt();
    let explained = root * (estimate + unknowns as f64 * f64::EPSILON) * result_scale;
    let undecided = check_dependent_rows(
        problem,
        dependent.iter().copied(),
        &kept,
        &e,
        (tolerance, explained, result_scale),
    )?;
    if estimate > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "merge stage 1 (KKT system of size {size}, condition estimate {:e})",
                solution.condition
            ),
            estimate,
            limit: accuracy,
        });
    }
    undecided.into_result(result_scale, accuracy)?;
    Ok((x0 + e, estimate))
}

/// 2-norm condition number of the constraint rows as given (continuity
/// rows, kept fix-ends and keep-point rows; each scaled to unit length).
pub(super) fn row_matrix_condition(continuity: &[Row], kept: &[&Row], unknowns: usize) -> f64 {
    let rows: Vec<&Row> = continuity.iter().chain(kept.iter().copied()).collect();
    if rows.is_empty() {
        return 1.0;
    }
    let mut matrix = DMatrix::zeros(rows.len(), unknowns);
    for (k, row) in rows.iter().enumerate() {
        let norm = row.coefficients.norm().max(f64::MIN_POSITIVE);
        matrix.set_row(k, &(row.coefficients.transpose() / norm));
    }
    let singular = matrix.singular_values();
    singular.max() / singular.min().max(f64::MIN_POSITIVE)
}

/// Condition number of the reduced (null-space) Hessian `Z^T W Z`, `Z` an
/// orthonormal basis of the null space of the orthonormal rows `basis`.
pub(super) fn reduced_condition(
    basis: &[(DVector<f64>, DVector<f64>)],
    weight: &DMatrix<f64>,
    count: usize,
    points_per_piece: usize,
) -> f64 {
    let unknowns = count * points_per_piece;
    if unknowns == 0 {
        return 1.0;
    }
    let mut projector = DMatrix::<f64>::identity(unknowns, unknowns);
    for (row, _) in basis {
        projector.ger(-1.0, row, row, 1.0);
    }
    let eigen = projector.symmetric_eigen();
    let columns: Vec<usize> = (0..unknowns)
        .filter(|&i| eigen.eigenvalues[i] > 0.5)
        .collect();
    if columns.is_empty() {
        return 1.0;
    }
    let z = DMatrix::from_fn(unknowns, columns.len(), |i, j| {
        eigen.eigenvectors[(i, columns[j])]
    });
    let mut weighted = DMatrix::zeros(unknowns, columns.len());
    for j in 0..count {
        let block = j * points_per_piece;
        weighted
            .rows_mut(block, points_per_piece)
            .copy_from(&(weight * z.rows(block, points_per_piece)));
    }
    let reduced = (z.transpose() * weighted).symmetric_eigen().eigenvalues;
    reduced.max() / reduced.min().max(f64::MIN_POSITIVE)
}
