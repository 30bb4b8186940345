//! Stage 2: the single curve `R` from the stage-1 pieces, checked by
//! restricting it back to every piece, and the measured deviation.

use nalgebra::DMatrix;

use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};

use super::stage_one::DEVIATION_SAMPLES;

/// Stage 2: the single curve `R` from the pieces, extrapolated from the
/// piece that reaches `[0, 1]` with the shortest extrapolation (for two
/// pieces the longer one: the error factor `(2/mu - 1)^m` is smallest
/// there), then checked: `R` restricted to every `[t_j, t_{j+1}]` must
/// give back that piece. Returns `R`, the largest control-point
/// difference of that check relative to the coordinate scale, and the
/// restrictions of `R` to the pieces' intervals (for [`max_deviation`]).
///
/// When stage 1 found `R` itself (`found`, the orthogonal path), `R` is
/// taken as it is and only checked.
pub(crate) fn stage_two(
    pieces: &[DMatrix<f64>],
    breakpoints: &[f64],
    accuracy: f64,
    found: Option<&DMatrix<f64>>,
) -> Result<(BezierCurve, f64, Vec<BezierCurve>)> {
    let merged = match found {
        Some(r) => BezierCurve::from_matrix(r)?,
        None => extrapolate(pieces, breakpoints)?,
    };
    check_restrictions(merged, pieces, breakpoints, accuracy)
}

/// `R` extrapolated from the piece with the shortest extrapolation, refined.
fn extrapolate(pieces: &[DMatrix<f64>], breakpoints: &[f64]) -> Result<BezierCurve> {
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
    Ok(merged)
}

/// `R` restricted to every piece's interval against the piece.
fn check_restrictions(
    merged: BezierCurve,
    pieces: &[DMatrix<f64>],
    breakpoints: &[f64],
    accuracy: f64,
) -> Result<(BezierCurve, f64, Vec<BezierCurve>)> {
    let scale = pieces
        .iter()
        .map(|p| p.amax())
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut worst = 0.0f64;
    let mut restrictions = Vec::with_capacity(pieces.len());
    for (j, p) in pieces.iter().enumerate() {
        // segment (blossoms) is a second computation of what stage 1's
        // de Casteljau split gave.
        let back = merged.segment(breakpoints[j], breakpoints[j + 1])?;
        let diff = (back.control_matrix() - p).amax();
        worst = worst.max(diff / scale);
        restrictions.push(back);
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
    Ok((merged, worst, restrictions))
}

/// Restriction matrices: row block `j` maps `R`'s control points to those of
/// `R` on `[t_j, t_{j+1}]` (exact segments of the unit coefficient vectors).
pub(super) fn restriction_matrix(degree: usize, breakpoints: &[f64]) -> DMatrix<f64> {
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

pub(super) fn refine(merged: &mut BezierCurve, pieces: &[DMatrix<f64>], breakpoints: &[f64]) {
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
///
/// `restrictions[j]` is `R` on `[t_j, t_{j+1}]` (from [`stage_two`], by
/// blossoming: `restrictions[j](u) = R(t_j + h_j u)` exactly in exact
/// arithmetic). The difference `R(t_j + h_j u) - C_j(u)` is then one Bezier
/// curve of the working degree, `restrictions[j]` minus `C_j` elevated to
/// it (convex combinations, exact in exact arithmetic), evaluated once per
/// sample instead of evaluating `R` and `C_j` separately (by the
/// Bernstein-Horner scheme of [`BezierCurve::eval_into`]): the same sampled
/// quantity, changed by rounding only (a few `n eps` of the coordinate
/// scale; tests/merge_accuracy.rs compares it with the two-evaluation form).
///
/// The differences are taken of the halved points (exact, a power of two)
/// and the distance doubled at the end, so that points near the top of the
/// `f64` range do not overflow a difference whose value is in range.
///
/// Errors: none in practice (the working degree is at least every input's,
/// so the elevation cannot fail); its error is passed on.
pub(crate) fn max_deviation(
    restrictions: &[BezierCurve],
    originals: &[&BezierCurve],
) -> Result<f64> {
    let Some(first) = restrictions.first() else {
        return Ok(0.0);
    };
    let (n, d) = (first.degree(), first.dim());
    let len = (n + 1) * d;
    // Half the difference curves, piece after piece.
    let mut halves = Vec::with_capacity(restrictions.len() * len);
    for (back, c) in restrictions.iter().zip(originals) {
        // C_j at the working degree (n >= its degree: working_degree checks
        // it).
        let elevated;
        let c_points = if c.degree() == n {
            c.points()
        } else {
            elevated = c.elevate_degree(n)?;
            elevated.points()
        };
        halves.extend(
            back.points()
                .iter()
                .zip(c_points)
                .map(|(r, c)| 0.5 * r - 0.5 * c),
        );
    }
    let mut value = vec![0.0; d];
    let mut worst = 0.0f64;
    // One Horner evaluation per sample: a table of the basis values at the
    // samples, shared by the pieces, measured slower (the unrolled Horner
    // of dimensions 2 and 3 beats a general dot product).
    for half in halves.chunks_exact(len) {
        for s in 0..=DEVIATION_SAMPLES {
            let u = s as f64 / DEVIATION_SAMPLES as f64;
            crate::bezier::bernstein_horner_any(half, n, d, u, 1.0, &mut value);
            worst = worst.max(crate::bezier::norm(&value));
        }
    }
    Ok(2.0 * worst)
}
