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
//! (mathematics.md, eq. (3), with `h_0 = mu`, `h_1 = 1 - mu`).

use nalgebra::{DMatrix, DVector};

use crate::basis::{bezier_basis_derivatives, binomial};
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};
use crate::linalg::solve_checked;

use super::{KeepPoint, MergeMetric};

/// A constraint row whose remainder, after projecting out the rows kept
/// before it (rows scaled to unit 2-norm), is shorter than this is treated
/// as linearly dependent on them ("redundant").
pub const RANK_TOLERANCE: f64 = 1e-9;

/// A redundant row is consistent when the solution of the kept rows
/// satisfies it to this tolerance relative to the curves' coordinate scale
/// (or to the requested accuracy, if that is looser); otherwise it
/// contradicts them.
pub const CONSISTENCY_TOLERANCE: f64 = 1e-8;

/// Evenly spaced samples per piece for the reported deviation.
pub const DEVIATION_SAMPLES: usize = 256;

/// Safety margin of the data-rounding term of the stage-1 error estimate
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
    coefficients: DVector<f64>,
    /// Right-hand side for the perturbation (one value per coordinate).
    rhs: DVector<f64>,
    label: String,
    /// False for the exact unit rows of "keep P/Q unchanged": they carry no
    /// rounding, so they do not enter the data-rounding term of the estimate.
    rounded: bool,
}

fn normalised(mut row: Row) -> Row {
    let norm = row.coefficients.norm();
    if norm > 0.0 {
        row.coefficients /= norm;
        row.rhs /= norm;
    }
    row
}

/// Solve stage 1 for pieces of equal degree and dimension with parameter
/// lengths `lengths` (positive, summing to 1).
/// How much of the a-posteriori check a stage-1 solve runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StageOneCheck {
    /// Every check: the KKT solve's own condition and backward error, the
    /// rounding carried by the constraint rows (their SVD) magnified by the
    /// reduced problem (an eigen-decomposition), the residuals of (3) and
    /// the consistency of redundant rows. Every answer a caller receives.
    Full,
    /// All of `Full` except the rounding carried by the constraint rows: for
    /// the trial values of the optimal-`mu` search only. The winner is solved
    /// again with `Full`; if that fails, the search is repeated with `Full`
    /// at every trial ([`super::merge`]), so the answer is never less checked.
    Trial,
}

pub(crate) fn solve_stage_one(
    pieces: &[PieceInput<'_>],
    lengths: &[f64],
    metric: MergeMetric,
    fix_ends: bool,
    accuracy: f64,
    check: StageOneCheck,
) -> Result<StageOne> {
    let count = pieces.len();
    debug_assert!(count >= 2 && lengths.len() == count);
    let m = pieces[0].curve.degree();
    let dim = pieces[0].curve.dim();
    let points_per_piece = m + 1;
    let unknowns = count * points_per_piece;
    let x0 = {
        let mut x = DMatrix::zeros(unknowns, dim);
        for (j, p) in pieces.iter().enumerate() {
            x.rows_mut(j * points_per_piece, points_per_piece)
                .copy_from(&p.curve.control_matrix());
        }
        x
    };
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
                rounded: true,
            }));
        }
    }

    // Constraint rows, in a fixed order; right-hand sides are exactly zero
    // (the constrained quantities keep their values).
    let mut constraints = Vec::new();
    let unit = |index: usize| {
        let mut a = DVector::zeros(unknowns);
        a[index] = 1.0;
        a
    };
    for (j, p) in pieces.iter().enumerate() {
        if p.keep {
            for i in 0..=m {
                constraints.push(Row {
                    coefficients: unit(j * points_per_piece + i),
                    rhs: DVector::zeros(dim),
                    label: format!("keep {} unchanged (control point {i})", p.name),
                    rounded: false,
                });
            }
        }
    }
    if fix_ends {
        constraints.push(Row {
            coefficients: unit(0),
            rhs: DVector::zeros(dim),
            label: format!("fix ends (first point of {})", pieces[0].name),
            rounded: true,
        });
        constraints.push(Row {
            coefficients: unit(unknowns - 1),
            rhs: DVector::zeros(dim),
            label: format!("fix ends (last point of {})", pieces[count - 1].name),
            rounded: true,
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
                    rounded: true,
                }));
            }
        }
    }
    let given_constraints = constraints.len();

    // The constraint rows are replaced by an orthonormal basis of their span
    // (same feasible set, a well-conditioned KKT matrix): the continuity rows
    // by Householder QR, `A_c^T = Q T`, so `A_c e = -A_c x0` becomes
    // `Q^T e = -Q^T x0` exactly; then the constraint rows in order by
    // Gram-Schmidt (two passes), a row whose remainder is below
    // RANK_TOLERANCE being linearly dependent on those before it.
    let mut basis: Vec<(DVector<f64>, DVector<f64>)> = {
        let mut at = DMatrix::zeros(unknowns, continuity.len());
        for (c, row) in continuity.iter().enumerate() {
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
    let mut kept = Vec::new();
    let mut redundant = Vec::new();
    for row in constraints {
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
        if remainder > RANK_TOLERANCE {
            basis.push((v / remainder, rhs / remainder));
            kept.push(row);
        } else {
            redundant.push(row);
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
                * row_matrix_condition(&continuity, &kept, unknowns)
                * reduced_condition(&basis, &weight, count, points_per_piece).sqrt(),
        ),
        StageOneCheck::Trial => solution.error_estimate(),
    };
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
    let e = solution.x.rows(0, unknowns).into_owned();

    // The continuity conditions (3) themselves, on the original rows (unit
    // length), relative to the coordinate scale of the result.
    let x = &x0 + &e;
    let result_scale = x.amax().max(scale);
    let continuity_residual = continuity
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

    // Redundant rows: consistent (satisfied by the solution) or contradictory.
    let tolerance = CONSISTENCY_TOLERANCE.max(accuracy) * scale;
    for row in &redundant {
        let residual = (e.transpose() * &row.coefficients - &row.rhs).amax();
        if residual > tolerance {
            let kept_labels: Vec<&str> = kept.iter().map(|r| r.label.as_str()).collect();
            return Err(BezjoinError::Inconsistent {
                reason: format!(
                    "{} contradicts the continuity conditions and the constraints before it{} \
                     (it depends linearly on them but would need a change of {residual:e}, \
                     coordinate scale {scale:e}); beyond continuity at most {points_per_piece} \
                     independent conditions fit per coordinate, {} were given, {} independent",
                    row.label,
                    if kept_labels.is_empty() {
                        String::new()
                    } else {
                        format!(" ({})", summarise(&kept_labels))
                    },
                    given_constraints,
                    kept.len()
                ),
            });
        }
    }

    let mut metric_value = 0.0;
    let unscaled = match metric {
        MergeMetric::Discrete => weight,
        MergeMetric::Integral => bernstein_gram_matrix(m),
    };
    let mut new_pieces = Vec::with_capacity(count);
    for j in 0..count {
        let ej = e.rows(j * points_per_piece, points_per_piece);
        metric_value += (ej.transpose() * &unscaled * ej).trace();
        new_pieces.push(x0.rows(j * points_per_piece, points_per_piece) + ej);
    }
    Ok(StageOne {
        pieces: new_pieces,
        metric_value: metric_value.max(0.0),
        error_estimate: estimate,
    })
}

/// 2-norm condition number of the constraint rows that carry rounding, as
/// given (continuity rows, fix-ends and keep-point rows; each scaled to unit
/// length). The exact unit rows of "keep P/Q unchanged" are left out.
fn row_matrix_condition(continuity: &[Row], kept: &[Row], unknowns: usize) -> f64 {
    let rows: Vec<&Row> = continuity
        .iter()
        .chain(kept)
        .filter(|row| row.rounded)
        .collect();
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

fn summarise(labels: &[&str]) -> String {
    const SHOWN: usize = 4;
    if labels.len() <= SHOWN {
        labels.join("; ")
    } else {
        format!(
            "{}; and {} more",
            labels[..SHOWN].join("; "),
            labels.len() - SHOWN
        )
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
