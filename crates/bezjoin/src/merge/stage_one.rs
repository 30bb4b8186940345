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
//! (docs/mathematics.md#merge-the-problem, eq. (3), with `h_0 = mu`, `h_1 = 1 - mu`). With a kept
//! piece there is nothing to minimise (see [`solve_stage_one`]).

use nalgebra::DMatrix;

use crate::basis::binomial;
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};

use super::columns::ZeroBuffer;
use super::kept::kept_solution;
use super::kkt::kkt_solution;
use super::orthogonal::orthogonal_solution;
use super::rows::Problem;
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
    /// The caller's curve, or its elevation to the working degree.
    pub curve: std::borrow::Cow<'a, BezierCurve>,
    /// "P", "Q", `"curves[2]"` ...
    pub name: &'a str,
    /// Name of its keep-point list ("p_points", "keep_points" ...).
    pub points_name: &'a str,
    pub keep: bool,
    /// (index in the caller's list, keep point)
    pub points: Vec<(usize, &'a KeepPoint)>,
}

/// The result of stage 1.
pub(crate) struct StageOne {
    /// New control points of every piece, stacked: piece `j` is rows `j
    /// (m + 1) .. (j + 1) (m + 1)` ([`StageOne::pieces`] copies them out).
    pub x: DMatrix<f64>,
    /// `m + 1`.
    pub points_per_piece: usize,
    /// The minimised metric.
    pub metric_value: f64,
    /// Relative error estimate of the stage-1 solve.
    pub error_estimate: f64,
    /// `R` itself when stage 1 found it (the orthogonal path); stage 2 then
    /// only checks it.
    pub merged: Option<DMatrix<f64>>,
    /// `d metric / d mu` for two pieces without keep points (orthogonal
    /// path), for the search of the optimal `mu`.
    pub slope: Option<f64>,
    /// The pieces are `merged` split at the breakpoint by
    /// [`BezierCurve::split_unchecked`]'s operations (two pieces, the
    /// orthogonal path's double solve): stage 2's split gives them back bit
    /// for bit ([`super::stage_two::stage_two`]).
    pub split_of_merged: bool,
}

impl StageOne {
    /// New control points of every piece, `(m + 1) x dim` each.
    pub fn pieces(&self) -> Vec<DMatrix<f64>> {
        let (x, points) = (&self.x, self.points_per_piece);
        (0..x.nrows() / points)
            .map(|j| {
                // x's rows of piece j, column by column (contiguous slices).
                let mut piece = DMatrix::zeros(points, x.ncols());
                for (to, from) in piece
                    .as_mut_slice()
                    .chunks_exact_mut(points)
                    .zip(x.as_slice().chunks_exact(x.nrows()))
                {
                    to.copy_from_slice(&from[j * points..(j + 1) * points]);
                }
                piece
            })
            .collect()
    }

    /// Piece `j` as a curve: `BezierCurve::from_matrix(&self.pieces()[j])`
    /// (the same points, the same errors) without the matrices (the debug
    /// check of [`StageOne::into_split_curves`], the tests).
    #[cfg(any(debug_assertions, test))]
    pub fn piece_curve(&self, j: usize) -> Result<BezierCurve> {
        let points = self.points_per_piece;
        BezierCurve::new(
            self.x.ncols(),
            points - 1,
            rows_of(&self.x, j * points, points),
        )
    }

    /// `R` and the two pieces as curves where the pieces are `R`'s split
    /// (`split_of_merged`): the points of `BezierCurve::from_matrix(R)`,
    /// `piece_curve(0)` and `piece_curve(1)`, built without their
    /// validation (`None` for any other stage-1 result), which cannot fail
    /// on such a result:
    ///
    /// * `split_of_merged` is set only by `orthogonal_solution` for two
    ///   pieces, whose `R` passed its check before the split (every entry
    ///   finite and the degree `m` at most `MAX_DEGREE`, else the error of
    ///   `from_matrix`) and is not changed after it;
    /// * [`solve_stage_one_slope`] returns a stage-1 result only when every
    ///   entry of `x` (the pieces) is finite, else `NonFiniteScalar`;
    /// * the dimension is the input curves' (at least 1) and every curve
    ///   has `m + 1 >= 1` points: the sizes match.
    ///
    /// So `new`'s checks (dimension, degree cap, size, finite) all pass and
    /// are not repeated (test `split_curves_are_the_checked_ones_to_the_bit`;
    /// a debug build checks every call against the validated constructors).
    ///
    /// The result is consumed: `R`'s points and `P^`'s are rearranged in
    /// the storage of `merged` and `x` (`Err(self)` for any other result:
    /// the result itself handed back, moved once, not an error to box).
    #[allow(clippy::result_large_err)]
    pub(crate) fn into_split_curves(
        self,
    ) -> std::result::Result<(BezierCurve, [BezierCurve; 2]), Self> {
        if !self.split_of_merged || self.merged.is_none() {
            return Err(self);
        }
        #[cfg(debug_assertions)]
        let checked = (
            BezierCurve::from_matrix(self.merged.as_ref().expect("R found")),
            [self.piece_curve(0), self.piece_curve(1)],
        );
        let Self {
            x,
            points_per_piece: points,
            merged,
            ..
        } = self;
        let dim = x.ncols();
        let q_hat = BezierCurve::from_parts(dim, points - 1, rows_of(&x, points, points));
        let merged = merged.expect("R found");
        let merged_curve = BezierCurve::from_parts(dim, points - 1, leading_rows(merged, points));
        let p_hat = BezierCurve::from_parts(dim, points - 1, leading_rows(x, points));
        #[cfg(debug_assertions)]
        {
            let (merged, [p, q]) = checked;
            debug_assert!(
                merged.is_ok_and(|c| c == merged_curve)
                    && p.is_ok_and(|c| c == p_hat)
                    && q.is_ok_and(|c| c == q_hat)
            );
        }
        Ok((merged_curve, [p_hat, q_hat]))
    }
}

/// Rows `0 .. count` of `m` as row-major points, as [`rows_of`]`(m, 0,
/// count)`, in `m`'s own storage (the points gathered on the stack first
/// for small pieces).
fn leading_rows(m: DMatrix<f64>, count: usize) -> Vec<f64> {
    let (rows, dim) = (m.nrows(), m.ncols());
    let mut buffer = ZeroBuffer::<LEADING_ROWS_ON_STACK>::new();
    let gathered = buffer.zeros(count * dim);
    let data = m.as_slice();
    gather_leading_rows(data, rows, dim, gathered);
    let mut points = Vec::from(m.data);
    points.truncate(count * dim);
    points.copy_from_slice(gathered);
    points
}

/// Points' entries gathered on the stack by [`leading_rows`] (a piece of
/// degree 7 in space).
const LEADING_ROWS_ON_STACK: usize = 24;

/// [`gather_rows`] with the dimension dispatched once: constant sizes for
/// 2 and 3 columns, the general body otherwise.
#[inline(always)]
fn gather_leading_rows(data: &[f64], rows: usize, dim: usize, gathered: &mut [f64]) {
    match dim {
        2 => gather_rows::<2>(data, rows, dim, gathered),
        3 => gather_rows::<3>(data, rows, dim, gathered),
        _ => gather_rows::<0>(data, rows, dim, gathered),
    }
}

/// The leading rows of the column-major `data` (`rows` rows, `dim`
/// columns) into the row-major `gathered` (a multiple of `dim` entries),
/// `dim = D` known at compile time when not `0`: every entry copied as it
/// is.
#[inline(always)]
fn gather_rows<const D: usize>(data: &[f64], rows: usize, dim: usize, gathered: &mut [f64]) {
    let dim = if D == 0 { dim } else { D };
    for (i, point) in gathered.chunks_exact_mut(dim.max(1)).enumerate() {
        for (c, v) in point[..dim].iter_mut().enumerate() {
            *v = data[c * rows + i];
        }
    }
}

/// Rows `first .. first + count` of `m` as row-major points (the order
/// `BezierCurve::from_matrix` reads them in).
fn rows_of(m: &DMatrix<f64>, first: usize, count: usize) -> Vec<f64> {
    let (rows, dim) = (m.nrows(), m.ncols());
    // The rows from `first` on, gathered as the leading rows of the data
    // from `first` (column `c`'s row `i` at `c rows + i` either way): a
    // zeroed `Vec` (`malloc` and a fill, no `calloc`) written in place.
    let data = &m.as_slice()[first.min(rows)..];
    let mut out: Vec<f64> = std::iter::repeat_n(0.0, count * dim).collect();
    gather_leading_rows(data, rows, dim, &mut out);
    out
}

/// The exact Bernstein Gram matrix `G_ij = int_0^1 B_i^n B_j^n =
/// C(n,i) C(n,j) / ((2n+1) C(2n,i+j))`.
pub(crate) fn bernstein_gram_matrix(degree: usize) -> DMatrix<f64> {
    let n = degree;
    DMatrix::from_fn(n + 1, n + 1, |i, j| {
        binomial(n, i) * binomial(n, j) / ((2 * n + 1) as f64 * binomial(2 * n, i + j))
    })
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
    solve_stage_one_slope(pieces, breakpoints, metric, fix_ends, accuracy, check, true)
}

/// [`solve_stage_one`], with the slope `d metric / d mu` computed only when
/// `slope` is set (a merge at a given `mu` needs none; the same answer and
/// checks otherwise, `StageOne::slope` is then `None`).
pub(crate) fn solve_stage_one_slope(
    pieces: &[PieceInput<'_>],
    breakpoints: &[f64],
    metric: MergeMetric,
    fix_ends: bool,
    accuracy: f64,
    check: StageOneCheck,
    slope: bool,
) -> Result<StageOne> {
    let count = pieces.len();
    debug_assert!(count >= 2 && breakpoints.len() == count + 1);
    // The piece lengths, on the stack for two pieces.
    let pair;
    let many: Vec<f64>;
    let lengths: &[f64] = if count == 2 {
        pair = [
            breakpoints[1] - breakpoints[0],
            breakpoints[2] - breakpoints[1],
        ];
        &pair
    } else {
        many = breakpoints.windows(2).map(|w| w[1] - w[0]).collect();
        &many
    };
    let m = pieces[0].curve.degree();
    let problem = Problem::new(pieces, lengths, fix_ends);
    let mut found = None;
    let mut split_of_merged = false;
    // The result scale when the orthogonal solve already measured it on
    // this very `x` (the same `lsq::amax(x).max(problem.scale)`).
    let mut measured_scale = None;
    let (x, estimate) = if pieces.iter().any(|p| p.keep) {
        kept_solution(&problem, breakpoints, lengths, accuracy)?
    } else {
        let want_slope = slope && count == 2 && pieces.iter().all(|p| p.points.is_empty());
        match orthogonal_solution(
            &problem,
            breakpoints,
            metric,
            accuracy,
            check == StageOneCheck::Full,
            want_slope,
        ) {
            Ok(solved) => {
                found = Some((solved.merged, solved.metric_value, solved.slope));
                split_of_merged = solved.split_of_merged;
                measured_scale = solved.result_scale;
                (solved.x, solved.estimate)
            }
            // The orthogonal estimate can be far more pessimistic than the
            // KKT formulation's (the integral metric at degrees above ~15):
            // the KKT solve, with its own full check, is tried before
            // refusing, so nothing answered before the orthogonal stage 1
            // is refused now. No slope then (the search falls back to
            // values, `PairProblem::optimal_mu`).
            Err(refusal @ BezjoinError::IllConditioned { .. }) => {
                match kkt_solution(&problem, metric, accuracy, check) {
                    Ok(solution) => solution,
                    Err(_) => return Err(refusal),
                }
            }
            Err(other) => return Err(other),
        }
    };
    // The continuity conditions (3) themselves, on the original rows (unit
    // length), relative to the coordinate scale of the input and result.
    // As nalgebra's `amax` but 0 for an all-NaN x: the same once the
    // input's scale (finite, positive) is the larger.
    let result_scale =
        measured_scale.unwrap_or_else(|| super::lsq::amax(x.as_slice()).max(problem.scale));
    let continuity_residual = problem.continuity_residual(&x) / result_scale;
    if continuity_residual.is_nan() || continuity_residual > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: "merge stage 1 (residual of the continuity conditions (3))".into(),
            estimate: continuity_residual,
            limit: accuracy,
        });
    }

    let points_per_piece = problem.points_per_piece;
    let mut metric_value = 0.0;
    // The kept path's metric from the changes (the orthogonal path
    // measured it on its residual).
    let weight = match (&found, metric) {
        (Some(_), _) => DMatrix::zeros(0, 0),
        (None, MergeMetric::Discrete) => DMatrix::identity(points_per_piece, points_per_piece),
        (None, MergeMetric::Integral) => bernstein_gram_matrix(m),
    };
    // The changes, for the metric of the kept and KKT paths only.
    let e = if found.is_none() {
        &x - problem.x0().view()
    } else {
        DMatrix::zeros(0, 0)
    };
    if found.is_none() {
        for j in 0..count {
            let ej = e.rows(j * points_per_piece, points_per_piece);
            metric_value += (ej.transpose() * &weight * ej).trace();
        }
    }
    let (merged, slope) = match found {
        // The orthogonal path measured the metric on its least-squares
        // residual (no Gram matrix).
        Some((merged, value, slope)) => {
            metric_value = value;
            (Some(merged), slope)
        }
        None => (None, None),
    };
    // Coordinates near the top of the f64 range can overflow the squared
    // changes (or the solution itself) without any NaN in the input; the
    // optimal-`mu` search would then see no finite value at all.
    if !metric_value.is_finite() || !super::lsq::all_finite(x.as_slice()) {
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
        x,
        points_per_piece,
        metric_value: metric_value.max(0.0),
        error_estimate: estimate,
        merged,
        slope,
        split_of_merged,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The constant-dimension gathers of leading rows are the general one
    /// bit for bit, and `rows_of` reads the rows asked for (random signed
    /// entries, 2 and 3 columns, every row count and first row).
    #[test]
    fn constant_size_gathered_rows_are_the_general_one() {
        let mut values = crate::test_values::Values(59);
        for dim in [2, 3] {
            for rows in 1..=16 {
                let data: Vec<f64> = (0..rows * dim).map(|_| values.signed()).collect();
                for count in 0..=rows {
                    let (mut general, mut sized) = (vec![0.0; count * dim], vec![0.0; count * dim]);
                    gather_rows::<0>(&data, rows, dim, &mut general);
                    match dim {
                        2 => gather_rows::<2>(&data, rows, dim, &mut sized),
                        _ => gather_rows::<3>(&data, rows, dim, &mut sized),
                    }
                    let bits = crate::test_values::bits;
                    assert_eq!(bits(&general), bits(&sized), "{rows} x {dim}, {count} rows");
                    // rows_of from every first row, against the entries
                    // read one by one.
                    let m = DMatrix::from_column_slice(rows, dim, &data);
                    for first in 0..=rows - count {
                        let mut expected = Vec::new();
                        for i in first..first + count {
                            for c in 0..dim {
                                expected.push(m[(i, c)]);
                            }
                        }
                        assert_eq!(
                            bits(&rows_of(&m, first, count)),
                            bits(&expected),
                            "{rows} x {dim}, rows {first}.."
                        );
                    }
                }
            }
        }
    }
}
