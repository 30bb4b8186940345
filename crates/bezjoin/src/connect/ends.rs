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
//! one allocation, the result's control points, while the jets, bands and
//! bounds fit [`super::with_scratch`]'s stack buffers.

use super::{
    CONNECT_RESIDUAL_LIMIT, Connection, end_band, residual_and_bound, triangular_number,
    unit_roundoff, with_scratch,
};
use crate::basis::KnotSide;
use crate::bezier::BezierCurve;
use crate::curve::CurveJet;
use crate::error::{BezjoinError, Result};

/// [`super::connect`] for `kp`, `kq`, given scales `alpha`, `beta` and no
/// interior constraints, on inputs already validated (dimensions, `u0`,
/// `v0`, the degree).
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
    let count = n + 1;
    let mut points = vec![0.0f64; count * dim];
    let (p_len, q_len) = ((kp + 1) * dim, (kq + 1) * dim);
    let band_len = triangular_number(kp + 1) + triangular_number(kq + 1);
    let scratch_len = p_len + q_len + 3 * count + band_len;
    let (max_residual, error_estimate) = with_scratch(scratch_len, |buffer| {
        // Rows 0..=kp are the P end (D(0) rows k), rows kp+1.. the Q end
        // (D(1) rows k), as in `condition_rows`.
        let (targets, rest) = buffer.split_at_mut(p_len + q_len);
        let (target_errors, rest) = rest.split_at_mut(count);
        let (target_norms, rest) = rest.split_at_mut(count);
        let (row_norms, bands) = rest.split_at_mut(count);
        let (p_targets, q_targets) = targets.split_at_mut(p_len);
        let (p_errors, q_errors) = target_errors.split_at_mut(kp + 1);
        // P arrives at u0 (from the left of a knot), Q leaves v0.
        p.jet_into(u0, kp, KnotSide::Left, p_targets, p_errors);
        q.jet_into(v0, kq, KnotSide::Right, q_targets, q_errors);
        // Targets and their bounds in place: T_k = s^k X^(k),
        // e_k = s^k err_k + (k + 1) u |T_k|.
        let mut r = 0;
        for (jet, errors, order, scale) in [
            (&mut *p_targets, &mut *p_errors, kp, alpha),
            (&mut *q_targets, &mut *q_errors, kq, beta),
        ] {
            let mut factor = 1.0f64;
            for k in 0..=order {
                let mut square = 0.0;
                for v in &mut jet[k * dim..(k + 1) * dim] {
                    *v *= factor;
                    square += *v * *v;
                }
                let norm = square.sqrt();
                target_norms[r] = norm;
                errors[k] =
                    scale.powi(k as i32) * errors[k] + (k + 1) as f64 * unit_roundoff() * norm;
                factor *= scale;
                r += 1;
            }
        }
        // The bands of rows r = 0..=n, row r at bands[triangular_number(k)..]
        // of its end (k its order), and their 1-norms.
        let (p_bands, q_bands) = bands.split_at_mut(triangular_number(kp + 1));
        for k in 0..=kp {
            let band = &mut p_bands[triangular_number(k)..][..=k];
            end_band(n, k, false, band);
            row_norms[k] = band.iter().map(|v| v.abs()).sum();
        }
        for k in 0..=kq {
            let band = &mut q_bands[triangular_number(k)..][..=k];
            end_band(n, k, true, band);
            row_norms[kp + 1 + k] = band.iter().map(|v| v.abs()).sum();
        }
        // P end: row k of D(0) touches R_0..R_k only (lower triangular).
        for k in 0..=kp {
            let band = &p_bands[triangular_number(k)..][..=k];
            let diagonal = band[k];
            for c in 0..dim {
                let mut sum = p_targets[k * dim + c];
                for i in 0..k {
                    sum -= band[i] * points[i * dim + c];
                }
                points[k * dim + c] = sum / diagonal;
            }
        }
        // Q end: row k of D(1) touches R_(n-k)..R_n only (anti-triangular).
        for k in 0..=kq {
            let band = &q_bands[triangular_number(k)..][..=k];
            let index = n - k;
            let diagonal = band[0];
            for c in 0..dim {
                let mut sum = q_targets[k * dim + c];
                for i in index + 1..=n {
                    sum -= band[i - index] * points[i * dim + c];
                }
                points[index * dim + c] = sum / diagonal;
            }
        }
        // The residual check of `check_residuals` on the bands.
        let mut data_scale = p.coordinate_scale().max(q.coordinate_scale());
        for r in 0..count {
            let v = target_norms[r] / row_norms[r];
            if v.is_finite() {
                data_scale = data_scale.max(v);
            }
        }
        let gamma = 2.0 * (2 * n + 4) as f64 * unit_roundoff();
        let mut worst = 0.0f64;
        let mut worst_bound = 0.0f64;
        for r in 0..count {
            let (band, first, target) = if r <= kp {
                (
                    &p_bands[triangular_number(r)..][..=r],
                    0,
                    &p_targets[r * dim..(r + 1) * dim],
                )
            } else {
                let k = r - kp - 1;
                (
                    &q_bands[triangular_number(k)..][..=k],
                    n - k,
                    &q_targets[k * dim..(k + 1) * dim],
                )
            };
            let denominator = target_norms[r].max(data_scale * row_norms[r]);
            let mut difference_square = 0.0;
            let mut abs_square = 0.0;
            for c in 0..dim {
                let mut value = 0.0;
                let mut abs_value = 0.0;
                for (i, &b) in band.iter().enumerate() {
                    let x = points[(first + i) * dim + c];
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
            worst = worst.max(residual);
            worst_bound = worst_bound.max(bound);
        }
        (worst, worst_bound)
    });
    let trusted = error_estimate.is_finite() && error_estimate <= CONNECT_RESIDUAL_LIMIT;
    if !trusted || points.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::IllConditioned {
            what: format!("connect (degree {n})"),
            estimate: error_estimate,
            limit: CONNECT_RESIDUAL_LIMIT,
        });
    }
    Ok(Connection {
        curve: BezierCurve::from_parts(dim, n, points),
        p_scale: alpha,
        q_scale: beta,
        max_residual,
        error_estimate,
        constraint_condition: 1.0,
    })
}
