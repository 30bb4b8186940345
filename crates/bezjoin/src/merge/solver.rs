//! Stage 1 (the constrained least-change problem, solved by Lagrange
//! multipliers) and stage 2 (the single curve `R`) for `N >= 2` consecutive
//! pieces; two pieces are the paper's case.
//!
//! Unknowns: the perturbations `e_j` of the control points of every piece
//! `j` (degree `m`, all coordinates at once: the constraint matrix is the
//! same for every coordinate, so the KKT system has `dim` right-hand sides).
//! Piece `j` is to be `R` on `[t_j, t_{j+1}]`, of length `h_j`; the pieces
//! are one polynomial exactly when, at every join,
//!
//! ```text
//! h_{j+1}^r C^_j^(r)(1) = h_j^r C^_{j+1}^(r)(0),   r = 0..m
//! ```
//!
//! (mathematics.md, eq. (3), with `h_0 = mu`, `h_1 = 1 - mu`). With a kept
//! piece there is nothing to minimise (see [`solve_stage_one`]).

use nalgebra::{DMatrix, DVector};

use crate::basis::{bezier_basis_derivatives, binomial};
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};
use crate::linalg::solve_checked;

use super::{KeepPoint, MergeMetric};

/// A constraint row whose remainder, after projecting out the rows kept
/// before it (rows scaled to unit 2-norm), is at most `RANK_TOLERANCE *
/// sqrt(N)` (`N` the number of unknowns) is treated as linearly
/// dependent on them. This is the rounding-noise level of the projection
/// itself (a few units in the last place per unknown), not a guess at
/// "nearly dependent": a row above it is kept however small its remainder,
/// and the ill-conditioning it brings is measured by the error estimate
/// (an untrustworthy answer is `IllConditioned`, never `Inconsistent`).
pub const RANK_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// A dependent row is consistent when the solution of the kept rows
/// satisfies it to this tolerance relative to the coordinate scale (the
/// larger of the input's and the result's; or to the requested accuracy, if
/// that is looser).
pub const CONSISTENCY_TOLERANCE: f64 = 1e-8;

/// A dependent row that the solution misses by more than
/// [`CONSISTENCY_TOLERANCE`] contradicts the others only if it misses by
/// more than this factor times what the rounding can explain: `sqrt(N)`
/// times (the stage-1 error estimate plus `N` units in the last place),
/// times the coordinate scale; with a kept piece, the rounding bound of its
/// extension plus the data's half-ulp rounding magnified by it. In between,
/// a consistent dependent row is not ruled out and the answer is
/// `IllConditioned`.
pub const CONTRADICTION_MARGIN: f64 = 16.0;

/// Evenly spaced samples per piece for the reported deviation.
pub const DEVIATION_SAMPLES: usize = 256;

/// Safety margin of the data-rounding term of the stage-1 KKT error estimate
/// (measured against an exact rational reference, test `merge_exact`).
pub const DATA_ROUNDING_MARGIN: f64 = 4.0;

/// One input piece with its constraints, already at the working degree.
pub(crate) struct PieceInput<'a> {
    pub curve: BezierCurve,
    /// "P", "Q", "curves[2]" ...
    pub name: String,
    /// Name of its keep-point list ("p_points", "keep_points" ...).
    pub points_name: String,
    pub keep: bool,
    /// (index in the caller's list, keep point)
    pub points: Vec<(usize, &'a KeepPoint)>,
}

/// The result of stage 1.
pub(crate) struct StageOne {
    /// New control points of every piece, `(m + 1) x dim` each.
    pub pieces: Vec<DMatrix<f64>>,
    /// The minimised metric.
    pub metric_value: f64,
    /// Relative error estimate of the KKT solve (condition x backward error).
    pub error_estimate: f64,
}

/// The exact Bernstein Gram matrix `G_ij = int_0^1 B_i^n B_j^n =
/// C(n,i) C(n,j) / ((2n+1) C(2n,i+j))`.
pub fn bernstein_gram_matrix(degree: usize) -> DMatrix<f64> {
    let n = degree;
    DMatrix::from_fn(n + 1, n + 1, |i, j| {
        binomial(n, i) * binomial(n, j) / ((2 * n + 1) as f64 * binomial(2 * n, i + j))
    })
}

struct Row {
    /// Over all unknowns, unit 2-norm.
    coefficients: DVector<f64>,
    /// Right-hand side for the perturbation (one value per coordinate).
    rhs: DVector<f64>,
    label: String,
}

fn normalised(mut row: Row) -> Row {
    let norm = row.coefficients.norm();
    if norm > 0.0 {
        row.coefficients /= norm;
        row.rhs /= norm;
    }
    row
}

/// How much of the a-posteriori check a stage-1 solve runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StageOneCheck {
    /// Every check: the KKT solve's own condition and backward error, the
    /// rounding carried by the constraint rows (their SVD) magnified by the
    /// reduced problem (an eigen-decomposition), the residuals of (3) and
    /// the consistency of dependent rows. Every answer a caller receives.
    Full,
    /// All of `Full` except the rounding carried by the constraint rows: for
    /// the trial values of the optimal-`mu` search only. The winner is solved
    /// again with `Full`; if that fails, the search is repeated with `Full`
    /// at every trial ([`super::merge`]), so the answer is never less checked.
    Trial,
}

/// The rows of a stage-1 problem: the continuity conditions (3) and the
/// fix-ends and keep-point constraints, all on the perturbations `e` of all
/// control points (`(count (m + 1)) x dim`, piece after piece).
struct Problem<'p, 'a> {
    pieces: &'p [PieceInput<'a>],
    points_per_piece: usize,
    unknowns: usize,
    dim: usize,
    x0: DMatrix<f64>,
    /// Coordinate scale of the input.
    scale: f64,
    continuity: Vec<Row>,
    constraints: Vec<Row>,
}

impl<'p, 'a> Problem<'p, 'a> {
    fn new(pieces: &'p [PieceInput<'a>], lengths: &[f64], fix_ends: bool) -> Self {
        let count = pieces.len();
        let m = pieces[0].curve.degree();
        let dim = pieces[0].curve.dim();
        let points_per_piece = m + 1;
        let unknowns = count * points_per_piece;
        let mut x0 = DMatrix::zeros(unknowns, dim);
        for (j, p) in pieces.iter().enumerate() {
            x0.rows_mut(j * points_per_piece, points_per_piece)
                .copy_from(&p.curve.control_matrix());
        }
        let scale = x0.amax().max(f64::MIN_POSITIVE);

        // Continuity rows (3): independent by construction (row r of join j
        // brings in control point r of piece j + 1 for the first time).
        let at_one = bezier_basis_derivatives(m, 1.0, m);
        let at_zero = bezier_basis_derivatives(m, 0.0, m);
        let mut continuity = Vec::new();
        for j in 0..count - 1 {
            let (left, right) = (lengths[j], lengths[j + 1]);
            let longer = left.max(right);
            for r in 0..=m {
                let mut a = DVector::zeros(unknowns);
                let wl = (right / longer).powi(r as i32);
                let wr = (left / longer).powi(r as i32);
                for i in 0..=m {
                    a[j * points_per_piece + i] = wl * at_one[(r, i)];
                    a[(j + 1) * points_per_piece + i] = -wr * at_zero[(r, i)];
                }
                continuity.push(normalised(Row {
                    coefficients: a,
                    rhs: DVector::zeros(dim),
                    label: format!(
                        "continuity of order {r} between {} and {}",
                        pieces[j].name,
                        pieces[j + 1].name
                    ),
                }));
            }
        }

        // Constraint rows, in a fixed order; right-hand sides are exactly
        // zero (the constrained quantities keep their values). "Keep piece j
        // unchanged" is not among them: see `solve_stage_one`.
        let mut constraints = Vec::new();
        let unit = |index: usize| {
            let mut a = DVector::zeros(unknowns);
            a[index] = 1.0;
            a
        };
        if fix_ends {
            constraints.push(Row {
                coefficients: unit(0),
                rhs: DVector::zeros(dim),
                label: format!("fix ends (first point of {})", pieces[0].name),
            });
            constraints.push(Row {
                coefficients: unit(unknowns - 1),
                rhs: DVector::zeros(dim),
                label: format!("fix ends (last point of {})", pieces[count - 1].name),
            });
        }
        for (j, p) in pieces.iter().enumerate() {
            for &(k, kp) in &p.points {
                let d = bezier_basis_derivatives(m, kp.param, kp.max_order);
                for s in 0..=kp.max_order {
                    let mut a = DVector::zeros(unknowns);
                    for i in 0..=m {
                        a[j * points_per_piece + i] = d[(s, i)];
                    }
                    constraints.push(normalised(Row {
                        coefficients: a,
                        rhs: DVector::zeros(dim),
                        label: format!(
                            "{}[{k}] (derivative {s} of {} at {})",
                            p.points_name, p.name, kp.param
                        ),
                    }));
                }
            }
        }
        Self {
            pieces,
            points_per_piece,
            unknowns,
            dim,
            x0,
            scale,
            continuity,
            constraints,
        }
    }

    /// Conditions given beyond continuity (a kept piece counts `m + 1`).
    fn given(&self) -> usize {
        self.pieces.iter().filter(|p| p.keep).count() * self.points_per_piece
            + self.constraints.len()
    }

    /// The `Inconsistent` error for the dependent constraint `row`, missed
    /// by `residual`; `before` names the conditions it depends on.
    fn contradiction(
        &self,
        row: &Row,
        residual: f64,
        scale: f64,
        before: &[String],
        independent: usize,
    ) -> BezjoinError {
        BezjoinError::Inconsistent {
            reason: format!(
                "{} contradicts the continuity conditions and the constraints before it{} \
                 (it depends linearly on them but would need a change of {residual:e}, \
                 coordinate scale {scale:e}); {}",
                row.label,
                if before.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", summarise(before))
                },
                self.counts(independent)
            ),
        }
    }

    fn counts(&self, independent: usize) -> String {
        format!(
            "beyond continuity at most {} independent conditions fit per coordinate, {} were \
             given, {independent} independent",
            self.points_per_piece,
            self.given()
        )
    }
}

/// How a dependent condition stands, given its residual at the solution,
/// the tolerance, and what rounding explains.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Dependent {
    Consistent,
    Contradictory,
    /// Missed by more than the tolerance but within what rounding explains.
    Undecided,
}

fn classify(residual: f64, tolerance: f64, explained: f64) -> Dependent {
    if residual.is_nan() || residual > tolerance.max(CONTRADICTION_MARGIN * explained) {
        Dependent::Contradictory
    } else if residual > tolerance {
        Dependent::Undecided
    } else {
        Dependent::Consistent
    }
}

/// The dependent condition with the largest residual among those that are
/// undecided (missed by more than the tolerance, within what rounding
/// explains): reported as `IllConditioned` once every condition was checked
/// and none contradicted.
#[derive(Default)]
struct WorstUndecided(Option<(f64, String)>);

impl WorstUndecided {
    fn note(&mut self, residual: f64, label: &str) {
        if self.0.as_ref().is_none_or(|(r, _)| residual > *r) {
            self.0 = Some((residual, label.to_owned()));
        }
    }

    fn into_result(self, scale: f64, accuracy: f64) -> Result<()> {
        match self.0 {
            None => Ok(()),
            Some((residual, label)) => Err(BezjoinError::IllConditioned {
                what: format!(
                    "merge stage 1 ({label} depends linearly on the conditions before it and \
                     is missed by {residual:e}, within what the rounding explains: consistent \
                     or contradictory cannot be told)"
                ),
                estimate: residual / scale,
                limit: accuracy,
            }),
        }
    }
}

/// Solve stage 1 for pieces of equal degree and dimension, piece `j` on
/// `[breakpoints[j], breakpoints[j + 1]]` (`0 = t_0 < ... < t_N = 1`).
///
/// Without kept pieces: the KKT system of the metric and the rows.
///
/// With a kept piece there is nothing to minimise: (3) makes all pieces one
/// curve `R`, and a kept piece fixes `R` (its extension to `[0, 1]`), hence
/// every piece. They are computed directly, by blossoming the kept piece
/// (the one with the shortest extrapolation, if several are kept), with a
/// first-order bound on the rounding of every control point; every other
/// condition (another kept piece, fix ends, keep points) is then dependent
/// and only checked. (Written as unit rows among the continuity rows, as
/// before, keep P with a small `mu` left the last unit rows with remainders
/// of about `(mu / (1 - mu))^n`, which a fixed rank tolerance took for
/// exact dependence and the consistency test for a contradiction.)
pub(crate) fn solve_stage_one(
    pieces: &[PieceInput<'_>],
    breakpoints: &[f64],
    metric: MergeMetric,
    fix_ends: bool,
    accuracy: f64,
    check: StageOneCheck,
) -> Result<StageOne> {
    let count = pieces.len();
    debug_assert!(count >= 2 && breakpoints.len() == count + 1);
    let lengths: Vec<f64> = breakpoints.windows(2).map(|w| w[1] - w[0]).collect();
    let m = pieces[0].curve.degree();
    let problem = Problem::new(pieces, &lengths, fix_ends);
    let (x, estimate) = if pieces.iter().any(|p| p.keep) {
        kept_solution(&problem, breakpoints, &lengths, accuracy)?
    } else {
        kkt_solution(&problem, metric, accuracy, check)?
    };
    let e = &x - &problem.x0;

    // The continuity conditions (3) themselves, on the original rows (unit
    // length), relative to the coordinate scale of the input and result.
    let result_scale = x.amax().max(problem.scale);
    let continuity_residual = problem
        .continuity
        .iter()
        .map(|row| (x.transpose() * &row.coefficients).amax())
        .fold(0.0f64, f64::max)
        / result_scale;
    if continuity_residual.is_nan() || continuity_residual > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: "merge stage 1 (residual of the continuity conditions (3))".into(),
            estimate: continuity_residual,
            limit: accuracy,
        });
    }

    let points_per_piece = problem.points_per_piece;
    let mut metric_value = 0.0;
    let weight = match metric {
        MergeMetric::Discrete => DMatrix::identity(points_per_piece, points_per_piece),
        MergeMetric::Integral => bernstein_gram_matrix(m),
    };
    let mut new_pieces = Vec::with_capacity(count);
    for j in 0..count {
        let ej = e.rows(j * points_per_piece, points_per_piece);
        metric_value += (ej.transpose() * &weight * ej).trace();
        new_pieces.push(x.rows(j * points_per_piece, points_per_piece).into_owned());
    }
    // Coordinates near the top of the f64 range can overflow the squared
    // changes (or the solution itself) without any NaN in the input; the
    // optimal-`mu` search would then see no finite value at all.
    if !metric_value.is_finite() || x.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::NonFiniteScalar {
            name: format!(
                "merge metric at mu = {} (the control-point changes overflow f64: \
                 coordinates of about {:e} are too large for this metric; scale the curves down)",
                breakpoints[1], problem.scale
            ),
            value: metric_value,
        });
    }
    Ok(StageOne {
        pieces: new_pieces,
        metric_value: metric_value.max(0.0),
        error_estimate: estimate,
    })
}

/// The KKT path (no piece kept): the new control points `x0 + e` and the
/// error estimate, after the dependent rows are checked.
fn kkt_solution(
    problem: &Problem<'_, '_>,
    metric: MergeMetric,
    accuracy: f64,
    check: StageOneCheck,
) -> Result<(DMatrix<f64>, f64)> {
    let (unknowns, points_per_piece, dim) =
        (problem.unknowns, problem.points_per_piece, problem.dim);
    let count = problem.pieces.len();
    let m = points_per_piece - 1;
    let x0 = &problem.x0;

    // The rows are replaced by an orthonormal basis of their span (same
    // feasible set, a well-conditioned KKT matrix): the continuity rows by
    // Householder QR, `A_c^T = Q T`, so `A_c e = -A_c x0` becomes
    // `Q^T e = -Q^T x0` exactly; then the constraint rows in order by
    // Gram-Schmidt (two passes), a row whose remainder is at the rounding
    // level `RANK_TOLERANCE sqrt(N)` being linearly dependent on those
    // before it. Any larger remainder, however small, keeps the row: the
    // ill-conditioning is then the estimate's business.
    let mut basis: Vec<(DVector<f64>, DVector<f64>)> = {
        let mut at = DMatrix::zeros(unknowns, problem.continuity.len());
        for (c, row) in problem.continuity.iter().enumerate() {
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
    let mut kept = Vec::new();
    let mut dependent = Vec::new();
    for row in &problem.constraints {
        let mut v = row.coefficients.clone();
        let mut rhs = row.rhs.clone();
        for _ in 0..2 {
            for (b, b_rhs) in &basis {
                let dot = b.dot(&v);
                v.axpy(-dot, b, 1.0);
                rhs.axpy(-dot, b_rhs, 1.0);
            }
        }
        let remainder = v.norm();
        if remainder > rank_tolerance {
            basis.push((v / remainder, rhs / remainder));
            kept.push(row);
        } else {
            dependent.push(row);
        }
    }

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
                * row_matrix_condition(&problem.continuity, &kept, unknowns)
                * reduced_condition(&basis, &weight, count, points_per_piece).sqrt(),
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
    let tolerance = CONSISTENCY_TOLERANCE.max(accuracy) * result_scale;
    let root = (unknowns as f64).sqrt();
    let explained = root * (estimate + unknowns as f64 * f64::EPSILON) * result_scale;
    let mut undecided = WorstUndecided::default();
    for row in &dependent {
        let residual = (e.transpose() * &row.coefficients - &row.rhs).amax();
        match classify(residual, tolerance, explained) {
            Dependent::Contradictory => {
                let before: Vec<String> = kept.iter().map(|r| r.label.clone()).collect();
                return Err(problem.contradiction(
                    row,
                    residual,
                    result_scale,
                    &before,
                    kept.len(),
                ));
            }
            Dependent::Undecided => undecided.note(residual, &row.label),
            _ => {}
        }
    }
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

/// The path with a kept piece: every piece is the kept piece's extension
/// restricted to its interval. Returns the new control points and the error
/// estimate (largest rounding bound relative to the coordinate scale of
/// input and result), after checking every other condition.
fn kept_solution(
    problem: &Problem<'_, '_>,
    breakpoints: &[f64],
    lengths: &[f64],
    accuracy: f64,
) -> Result<(DMatrix<f64>, f64)> {
    let pieces = problem.pieces;
    let count = pieces.len();
    let (unknowns, points_per_piece, dim) =
        (problem.unknowns, problem.points_per_piece, problem.dim);
    let x0 = &problem.x0;
    // The kept piece with the shortest extrapolation (as in stage 2).
    let reach = |j: usize| breakpoints[j].max(1.0 - breakpoints[j + 1]) / lengths[j];
    let source = (0..count)
        .filter(|&j| pieces[j].keep)
        .min_by(|&a, &b| reach(a).total_cmp(&reach(b)))
        .expect("a kept piece");
    let h = lengths[source];
    let mut x = x0.clone();
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
    let tolerance = CONSISTENCY_TOLERANCE.max(accuracy) * result_scale;
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
    for row in &problem.constraints {
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

/// A double-double number `hi + lo` (`|lo| <= ulp(hi) / 2`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct DoubleDouble {
    hi: f64,
    lo: f64,
}

/// `a + b = s + e` exactly (Knuth's TwoSum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a b = p + e` exactly (fused multiply-add).
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `(t - origin) / (end - origin)` to about `eps^2` relative: the
/// differences are exact double-doubles, the quotient is corrected once.
fn relative_parameter(t: f64, origin: f64, end: f64) -> DoubleDouble {
    let (nh, nl) = two_sum(t, -origin);
    let (dh, dl) = two_sum(end, -origin);
    let q = nh / dh;
    // remainder = (nh + nl) - q (dh + dl), the first product exactly.
    let (ph, pl) = two_product(q, dh);
    let remainder = ((nh - ph) - pl) + nl - q * dl;
    let (hi, lo) = two_sum(q, remainder / dh);
    DoubleDouble { hi, lo }
}

/// The control points of the curve with control points `points` (rows) on
/// `[a, b]` of its parameter, each the blossom `(a^(n-i), b^i)`, by
/// compensated de Casteljau (Graillat, Langlois, Louvet, "Algorithms for
/// accurate, validated and fast polynomial evaluation", 2009: every step's
/// rounding is captured exactly by TwoSum / TwoProduct and carried in a
/// second recurrence, as are the low parts of `a`, `b` and `1 - t`), with a
/// bound on each result's error: `2 eps |value| + 2 (3 n eps)^2 |blossom|`,
/// where `|blossom|` is the same recurrence on `|p|` with weights
/// `|1 - t|`, `|t|` (twice the published `eps |value| + 2 gamma_3n^2
/// |blossom|` for the low parts of the parameters). Far outside `[0, 1]`
/// the weights sum to `(|1 - a| + |a|)^(n-i) (|1 - b| + |b|)^i`, the
/// `(2/mu - 1)^n` of the spec: plain de Casteljau loses that many units in
/// the last place, the compensated one only its square times `eps^2`, so
/// the answer stays accurate to a few ulps until that product reaches the
/// accuracy. Also returns `|blossom|` (`eps |blossom|` bounds how far half
/// an ulp of rounding in the data moves the result).
fn blossom_segment(
    points: &DMatrix<f64>,
    a: DoubleDouble,
    b: DoubleDouble,
) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let n = points.nrows() - 1;
    let dim = points.ncols();
    let gamma = 3.0 * n as f64 * f64::EPSILON;
    let mut out = DMatrix::zeros(n + 1, dim);
    let mut bound = DMatrix::zeros(n + 1, dim);
    let mut blossom_abs = DMatrix::zeros(n + 1, dim);
    // One de Casteljau step at t on the first `len` entries of (value,
    // error, absolute) recurrences.
    let step = |value: &mut DMatrix<f64>,
                error: &mut DMatrix<f64>,
                absolute: &mut DMatrix<f64>,
                len: usize,
                t: DoubleDouble| {
        let (sh, sl) = two_sum(1.0, -t.hi);
        let sl = sl - t.lo;
        for j in 0..len - 1 {
            for c in 0..dim {
                let (p, q) = (value[(j, c)], value[(j + 1, c)]);
                let (p1, pi1) = two_product(sh, p);
                let (p2, pi2) = two_product(t.hi, q);
                let (sum, sigma) = two_sum(p1, p2);
                value[(j, c)] = sum;
                error[(j, c)] = sh * error[(j, c)]
                    + t.hi * error[(j + 1, c)]
                    + (pi1 + pi2 + sigma + sl * p + t.lo * q);
                absolute[(j, c)] = sh.abs() * absolute[(j, c)] + t.hi.abs() * absolute[(j + 1, c)];
            }
        }
    };
    // `level` holds the blossom values (b^i, ...) after i steps at b.
    let mut level = points.clone();
    let mut level_error = DMatrix::zeros(n + 1, dim);
    let mut level_abs = points.abs();
    for i in 0..=n {
        let len = n + 1 - i;
        let mut value = level.rows(0, len).into_owned();
        let mut error = level_error.rows(0, len).into_owned();
        let mut absolute = level_abs.rows(0, len).into_owned();
        for done in 0..len - 1 {
            step(&mut value, &mut error, &mut absolute, len - done, a);
        }
        for c in 0..dim {
            let result = value[(0, c)] + error[(0, c)];
            out[(i, c)] = result;
            bound[(i, c)] =
                2.0 * f64::EPSILON * result.abs() + 2.0 * gamma * gamma * absolute[(0, c)];
            blossom_abs[(i, c)] = absolute[(0, c)];
        }
        if i < n {
            step(&mut level, &mut level_error, &mut level_abs, len, b);
        }
    }
    (out, bound, blossom_abs)
}

/// 2-norm condition number of the constraint rows as given (continuity
/// rows, kept fix-ends and keep-point rows; each scaled to unit length).
fn row_matrix_condition(continuity: &[Row], kept: &[&Row], unknowns: usize) -> f64 {
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
fn reduced_condition(
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

fn summarise<S: AsRef<str>>(labels: &[S]) -> String {
    const SHOWN: usize = 4;
    let shown: Vec<&str> = labels.iter().take(SHOWN).map(AsRef::as_ref).collect();
    if labels.len() <= SHOWN {
        shown.join("; ")
    } else {
        format!("{}; and {} more", shown.join("; "), labels.len() - SHOWN)
    }
}

/// Stage 2: the single curve `R` from the pieces, extrapolated from the
/// piece that reaches `[0, 1]` with the shortest extrapolation (for two
/// pieces the longer one: the error factor `(2/mu - 1)^m` is smallest
/// there), then checked: `R` restricted to every `[t_j, t_{j+1}]` must
/// give back that piece. Returns `R` and the largest control-point
/// difference of that check relative to the coordinate scale.
pub(crate) fn stage_two(
    pieces: &[DMatrix<f64>],
    breakpoints: &[f64],
    accuracy: f64,
) -> Result<(BezierCurve, f64)> {
    let lengths: Vec<f64> = breakpoints.windows(2).map(|w| w[1] - w[0]).collect();
    // Extrapolating piece j to [0, 1] runs de Casteljau steps at parameters
    // down to -t_j / h_j and up to 1 + (1 - t_{j+1}) / h_j; each step at a
    // distance s outside [0, 1] multiplies rounding errors by up to 1 + 2s.
    // Take the piece with the shortest reach (for two pieces: the longer).
    let reach = |j: usize| breakpoints[j].max(1.0 - breakpoints[j + 1]) / lengths[j];
    let longest = (0..lengths.len())
        .min_by(|&a, &b| reach(a).total_cmp(&reach(b)))
        .unwrap_or(0);
    let piece = BezierCurve::from_matrix(&pieces[longest])?;
    let h = lengths[longest];
    let start = -breakpoints[longest] / h;
    let end = (1.0 - breakpoints[longest]) / h;
    let mut merged = piece.segment(start, end)?;
    // Refinement: the extrapolation amplifies rounding by up to (2/h - 1)^m;
    // two steps of least-squares correction against ALL pieces (the stacked
    // restriction matrices [S_0; S_1; ...] are well conditioned together,
    // unlike any one of them) remove most of it.
    refine(&mut merged, pieces, breakpoints);
    let scale = pieces
        .iter()
        .map(|p| p.amax())
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut worst = 0.0f64;
    for (j, p) in pieces.iter().enumerate() {
        let back = merged.segment(breakpoints[j], breakpoints[j + 1])?;
        let diff = (back.control_matrix() - p).amax();
        worst = worst.max(diff / scale);
    }
    if worst.is_nan() || worst > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "merge stage 2 (R of degree {} restricted to the pieces does not give them back)",
                merged.degree()
            ),
            estimate: worst,
            limit: accuracy,
        });
    }
    Ok((merged, worst))
}

/// Restriction matrices: row block `j` maps `R`'s control points to those of
/// `R` on `[t_j, t_{j+1}]` (exact segments of the unit coefficient vectors).
fn restriction_matrix(degree: usize, breakpoints: &[f64]) -> DMatrix<f64> {
    let count = breakpoints.len() - 1;
    let points = degree + 1;
    let mut s = DMatrix::zeros(count * points, points);
    for k in 0..points {
        let mut unit = vec![0.0; points];
        unit[k] = 1.0;
        let basis_curve = BezierCurve::from_parts(1, degree, unit);
        for j in 0..count {
            let seg = basis_curve.segment_unchecked(breakpoints[j], breakpoints[j + 1]);
            for i in 0..points {
                s[(j * points + i, k)] = seg.points()[i];
            }
        }
    }
    s
}

fn refine(merged: &mut BezierCurve, pieces: &[DMatrix<f64>], breakpoints: &[f64]) {
    let degree = merged.degree();
    let points = degree + 1;
    let s = restriction_matrix(degree, breakpoints);
    let mut target = DMatrix::zeros(s.nrows(), merged.dim());
    for (j, p) in pieces.iter().enumerate() {
        target.rows_mut(j * points, points).copy_from(p);
    }
    let qr = s.clone().qr();
    let (q, r) = (qr.q(), qr.r());
    let mut current = merged.control_matrix();
    for _ in 0..2 {
        let residual = &target - &s * &current;
        let Some(correction) = r.solve_upper_triangular(&(q.transpose() * residual)) else {
            return;
        };
        if correction.iter().any(|v| !v.is_finite()) {
            return;
        }
        current += correction;
    }
    if let Ok(better) = BezierCurve::from_matrix(&current) {
        *merged = better;
    }
}

/// Largest distance between `R` and the original pieces, each compared in
/// its own parameter: `R(t_j + h_j u)` against `C_j(u)` at
/// [`DEVIATION_SAMPLES`]` + 1` evenly spaced `u`.
pub(crate) fn max_deviation(
    merged: &BezierCurve,
    originals: &[&BezierCurve],
    breakpoints: &[f64],
) -> f64 {
    let dim = merged.dim();
    let mut a = vec![0.0; dim];
    let mut b = vec![0.0; dim];
    let mut worst = 0.0f64;
    for (j, c) in originals.iter().enumerate() {
        let (t0, t1) = (breakpoints[j], breakpoints[j + 1]);
        for s in 0..=DEVIATION_SAMPLES {
            let u = s as f64 / DEVIATION_SAMPLES as f64;
            merged.eval_into(t0 + (t1 - t0) * u, &mut a);
            c.eval_into(u, &mut b);
            worst = worst.max(crate::bezier::distance(&a, &b));
        }
    }
    worst
}
