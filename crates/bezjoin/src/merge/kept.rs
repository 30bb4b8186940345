//! The kept-piece path of stage 1: a kept piece fixes `R`, so every piece
//! is its extension (compensated blossoming) and the other conditions are
//! only checked.

use nalgebra::{DMatrix, DVector};

use crate::error::{BezjoinError, Result};

use crate::compensated::{blossom_segment, relative_parameter};

use super::rows::{Dependent, Problem, WorstUndecided, classify};
use super::stage_one::CONSISTENCY_TOLERANCE;

/// The path with a kept piece: every piece is the kept piece's extension
/// restricted to its interval. Returns the new control points and the error
/// estimate (largest rounding bound relative to the coordinate scale of
/// input and result), after checking every other condition.
pub(super) fn kept_solution(
    problem: &Problem<'_, '_>,
    breakpoints: &[f64],
    lengths: &[f64],
    accuracy: f64,
) -> Result<(DMatrix<f64>, f64)> {
    let pieces = problem.pieces;
    let count = pieces.len();
    let (unknowns, points_per_piece, dim) =
        (problem.unknowns, problem.points_per_piece, problem.dim);
    let x0 = problem.x0().view();
    // The kept piece with the shortest extrapolation (as in stage 2).
    let reach = |j: usize| breakpoints[j].max(1.0 - breakpoints[j + 1]) / lengths[j];
    let source = (0..count)
        .filter(|&j| pieces[j].keep)
        .min_by(|&a, &b| reach(a).total_cmp(&reach(b)))
        .expect("a kept piece");
    let h = lengths[source];
    let mut x = x0.clone_owned();
    let mut bound = DMatrix::zeros(unknowns, dim);
    let mut sensitivity = DMatrix::zeros(unknowns, dim);
    let source_points = pieces[source].curve.control_matrix();
    let (origin, end) = (breakpoints[source], breakpoints[source + 1]);
    for k in (0..count).filter(|&k| k != source) {
        let a = relative_parameter(breakpoints[k], origin, end);
        let b = relative_parameter(breakpoints[k + 1], origin, end);
        let (points, rounding, absolute) = blossom_segment(&source_points, a, b);
        x.rows_mut(k * points_per_piece, points_per_piece)
            .copy_from(&points);
        bound
            .rows_mut(k * points_per_piece, points_per_piece)
            .copy_from(&rounding);
        sensitivity
            .rows_mut(k * points_per_piece, points_per_piece)
            .copy_from(&(absolute * f64::EPSILON));
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "merge stage 1 (the extension of the kept {} overflows)",
                pieces[source].name
            ),
            estimate: f64::INFINITY,
            limit: accuracy,
        });
    }
    let e = &x - x0;
    let result_scale = x.amax().max(problem.scale);
    let estimate = bound.amax() / result_scale;
    // Every other condition is dependent. If the curves the data round
    // satisfy it, the computed pieces miss it by at most their rounding
    // bound, plus the data's own rounding (half an ulp of every control
    // point) magnified by the extension, `eps |blossom|`, plus the rounding
    // of e itself: what rounding explains.
    let tolerance = CONSISTENCY_TOLERANCE.max(accuracy) * problem.extent;
    let explained_point =
        |i: usize| bound.row(i).amax() + sensitivity.row(i).amax() + f64::EPSILON * result_scale;
    let explained_at = |coefficients: &DVector<f64>| {
        (0..unknowns)
            .map(|i| coefficients[i].abs() * explained_point(i))
            .sum::<f64>()
    };
    let independent = points_per_piece;
    let source_label = format!("keep {} unchanged", pieces[source].name);
    let mut undecided = WorstUndecided::default();
    for k in (0..count).filter(|&k| k != source && pieces[k].keep) {
        let block = k * points_per_piece;
        let residual = e.rows(block, points_per_piece).amax();
        let explained = (block..block + points_per_piece)
            .map(explained_point)
            .fold(0.0, f64::max);
        let label = format!("keep {} unchanged", pieces[k].name);
        match classify(residual, tolerance, explained) {
            Dependent::Contradictory => {
                return Err(BezjoinError::Inconsistent {
                    reason: format!(
                        "{label} contradicts {source_label} and the continuity conditions: \
                         with {} kept, R is its extension, which differs from {} by \
                         {residual:e} (coordinate scale {result_scale:e}); kept curves must be \
                         pieces of one curve; {}",
                        pieces[source].name,
                        pieces[k].name,
                        problem.counts(independent)
                    ),
                });
            }
            Dependent::Undecided => undecided.note(residual, &label),
            _ => {}
        }
    }
    let kept_labels: Vec<String> = (0..count)
        .filter(|&j| pieces[j].keep)
        .map(|j| format!("keep {} unchanged", pieces[j].name))
        .collect();
    for row in problem.constraints() {
        let residual = (e.transpose() * &row.coefficients - &row.rhs).amax();
        match classify(residual, tolerance, explained_at(&row.coefficients)) {
            Dependent::Contradictory => {
                return Err(problem.contradiction(
                    row,
                    residual,
                    result_scale,
                    &kept_labels,
                    independent,
                ));
            }
            Dependent::Undecided => undecided.note(residual, &row.label),
            _ => {}
        }
    }
    if estimate.is_nan() || estimate > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "merge stage 1 (extension of the kept {} over [{}, {}] of its parameter)",
                pieces[source].name,
                -breakpoints[source] / h,
                (1.0 - breakpoints[source]) / h
            ),
            estimate,
            limit: accuracy,
        });
    }
    undecided.into_result(result_scale, accuracy)?;
    // The other kept pieces agree with the extension (checked above) and are
    // returned exactly as given.
    for k in (0..count).filter(|&k| k != source && pieces[k].keep) {
        let block = k * points_per_piece;
        x.rows_mut(block, points_per_piece)
            .copy_from(&x0.rows(block, points_per_piece));
    }
    Ok((x, estimate))
}
