//! The structured solve without interior constraints, the hot path of
//! [`super::connect`]: the two jets ([`CurveJet::jet_into`]), the targets
//! `alpha^k P^(k)(u0)`, `beta^k Q^(k)(v0)` with their rounding bounds, the
//! forward substitution with the bands of `D(0)` and the back substitution
//! with those of `D(1)` ([`super::end_band`]), and the residual check of
//! [`super::check_residuals`], every residual with its rounding bound, on
//! the bands alone (the other entries of the rows are exact zeros).
//!
//! The same operations in the same order as the general path
//! ([`super::prepare`], [`super::condition_rows`],
//! [`super::structured_points`], [`super::check_residuals`]), so the same
//! control points, residual and estimate bit for bit (unit test
//! `end_path_equals_the_general_path`), in `O(n^2 d)` with no matrices:
//! fixed arrays of four coordinate lanes per point (dimensions 1 to 4,
//! degree up to [`super::MAX_CONNECT_DEGREE`]; the unused lanes stay exact
//! zeros) and one allocation, the result's control points.

use super::{
    CONNECT_RESIDUAL_LIMIT, Connection, end_band, end_band_norm, residual_and_bound, unit_roundoff,
};
use crate::basis::KnotSide;
use crate::bezier::BezierCurve;
use crate::curve::CurveJet;
use crate::error::{BezjoinError, Result};

/// Result degrees up to which [`connect_ends`] works in fixed arrays
/// (lanes of [`LANES`] coordinates); larger problems take the general path.
const MAX_POINTS: usize = super::MAX_CONNECT_DEGREE + 1;

/// Coordinates per point in the fixed arrays: dimensions 1 to 4.
const LANES: usize = 4;

/// [`super::connect`] for `kp`, `kq`, given scales `alpha`, `beta` and no
/// interior constraints, on inputs already validated (dimensions, `u0`,
/// `v0`, the degree). Dimensions above [`LANES`] take the general path
/// ([`super::prepare`], [`super::solve_structured`]), which computes the
/// same numbers.
#[allow(clippy::too_many_arguments)]
pub(super) fn connect_ends<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    kp: usize,
    kq: usize,
    alpha: f64,
    beta: f64,
) -> Result<Connection> {
    let dim = p.dim();
    let n = kp + kq + 1;
    if dim > LANES || n >= MAX_POINTS {
        let problem = super::prepare(p, u0, q, v0, &super::ConnectOptions::new(kp, kq))?;
        return super::solve_structured(&problem, alpha, beta);
    }
    let count = n + 1;
    // Row r of the system: r <= kp the P end (row r of D(0)), r = kp + 1 + k
    // the Q end (row k of D(1)), as in `condition_rows`. Coordinates beyond
    // `dim` stay exact zeros, so sums over all lanes equal sums over `dim`.
    let mut points = [[0.0f64; LANES]; MAX_POINTS];
    let mut targets = [[0.0f64; LANES]; MAX_POINTS];
    let mut target_errors = [0.0f64; MAX_POINTS];
    let mut target_norms = [0.0f64; MAX_POINTS];
    let mut row_norms = [0.0f64; MAX_POINTS];
    {
        // P arrives at u0 (from the left of a knot), Q leaves v0.
        let mut jet = [0.0f64; MAX_POINTS * LANES];
        let values = &mut jet[..(kp + 1) * dim];
        p.jet_into(u0, kp, KnotSide::Left, values, &mut target_errors[..=kp]);
        spread_rows(values, dim, &mut targets[..=kp]);
        let values = &mut jet[..(kq + 1) * dim];
        q.jet_into(
            v0,
            kq,
            KnotSide::Right,
            values,
            &mut target_errors[kp + 1..=n],
        );
        spread_rows(values, dim, &mut targets[kp + 1..=n]);
    }
    // Targets and their bounds in place: T_k = s^k X^(k),
    // e_k = s^k err_k + (k + 1) u |T_k|.
    for (first, order, scale) in [(0, kp, alpha), (kp + 1, kq, beta)] {
        let mut factor = 1.0f64;
        for k in 0..=order {
            let r = first + k;
            let mut square = 0.0;
            for v in &mut targets[r][..dim] {
                *v *= factor;
                square += *v * *v;
            }
            let norm = square.sqrt();
            target_norms[r] = norm;
            target_errors[r] =
                scale.powi(k as i32) * target_errors[r] + (k + 1) as f64 * unit_roundoff() * norm;
            factor *= scale;
        }
    }
    // The 1-norms of the rows (the tables of `end_band_norm`, the sums the
    // general path forms) and the data scale of `check_residuals`.
    let mut data_scale = p.coordinate_scale().max(q.coordinate_scale());
    for r in 0..count {
        row_norms[r] = end_band_norm(n, if r <= kp { r } else { r - kp - 1 });
        let v = target_norms[r] / row_norms[r];
        if v.is_finite() {
            data_scale = data_scale.max(v);
        }
    }
    let gamma = 2.0 * (2 * n + 4) as f64 * unit_roundoff();
    let mut max_residual = 0.0f64;
    let mut error_estimate = 0.0f64;
    let mut band = [0.0f64; MAX_POINTS];
    // Row by row: the band once, the unknown it determines, its residual.
    // P end: row k of D(0) touches R_0..R_k only (lower triangular); Q end:
    // row k of D(1) touches R_(n-k)..R_n only (anti-triangular). The two
    // sets of unknowns are disjoint (n - kq = kp + 1), so a row's residual
    // is final as soon as its own unknown is solved.
    for r in 0..count {
        let target = targets[r];
        let (first, k) = if r <= kp {
            let k = r;
            end_band(n, k, false, &mut band[..=k]);
            let diagonal = band[k];
            for c in 0..LANES {
                let mut sum = target[c];
                for i in 0..k {
                    sum -= band[i] * points[i][c];
                }
                points[k][c] = sum / diagonal;
            }
            (0, k)
        } else {
            let k = r - kp - 1;
            let first = n - k;
            end_band(n, k, true, &mut band[..=k]);
            let diagonal = band[0];
            for c in 0..LANES {
                let mut sum = target[c];
                for i in first + 1..=n {
                    sum -= band[i - first] * points[i][c];
                }
                points[first][c] = sum / diagonal;
            }
            (first, k)
        };
        let denominator = target_norms[r].max(data_scale * row_norms[r]);
        let mut difference_square = 0.0;
        let mut abs_square = 0.0;
        for c in 0..dim {
            let mut value = 0.0;
            let mut abs_value = 0.0;
            for (i, &b) in band[..=k].iter().enumerate() {
                let x = points[first + i][c];
                value += b * x;
                abs_value += b.abs() * x.abs();
            }
            let difference = value - target[c];
            difference_square += difference * difference;
            abs_square += abs_value * abs_value;
        }
        let (residual, bound) = residual_and_bound(
            difference_square,
            abs_square,
            gamma,
            target_errors[r],
            denominator,
        );
        max_residual = max_residual.max(residual);
        error_estimate = error_estimate.max(bound);
    }
    let mut flat = Vec::with_capacity(count * dim);
    for point in &points[..count] {
        flat.extend_from_slice(&point[..dim]);
    }
    let trusted = error_estimate.is_finite() && error_estimate <= CONNECT_RESIDUAL_LIMIT;
    if !trusted || flat.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::IllConditioned {
            what: format!("connect (degree {n})"),
            estimate: error_estimate,
            limit: CONNECT_RESIDUAL_LIMIT,
        });
    }
    Ok(Connection {
        curve: BezierCurve::from_parts(dim, n, flat),
        p_scale: alpha,
        q_scale: beta,
        max_residual,
        error_estimate,
        constraint_condition: 1.0,
    })
}

/// Rows of `dim` values into the first `dim` lanes of `rows`.
fn spread_rows(values: &[f64], dim: usize, rows: &mut [[f64; LANES]]) {
    for (row, value) in rows.iter_mut().zip(values.chunks_exact(dim)) {
        row[..dim].copy_from_slice(value);
    }
}
