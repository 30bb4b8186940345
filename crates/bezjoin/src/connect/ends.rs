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
//! fixed arrays of `[f64; dim]` rows (dimensions 1 to 4, a const
//! parameter; degree up to [`super::MAX_CONNECT_DEGREE`]), the band entries
//! from the tables, and one allocation, the result's control points.
//!
//! The G^k connect with given shape values ([`connect_ends_shaped`], for
//! [`crate::connect_geometric_curve`]) is the same path with other targets:
//! the jets combined by the partial Bell polynomials of the shapes, scales 1.

use super::{
    CONNECT_RESIDUAL_LIMIT, Connection, END_BAND_NORMS, FALLING_FACTORIALS, SIGNED_BINOMIALS,
    finite_or_infinite, power, residual_and_bound_unguarded, unit_roundoff,
};
use crate::basis::KnotSide;
use crate::bezier::BezierCurve;
use crate::curve::CurveJet;
use crate::error::{BezjoinError, Result};

/// Result degrees below which [`connect_ends`] works in fixed arrays
/// (the table range of [`END_BAND_NORMS`], [`FALLING_FACTORIALS`]);
/// larger problems take the general path.
const MAX_POINTS: usize = super::MAX_CONNECT_DEGREE + 1;

/// [`super::connect`] for `kp`, `kq`, given scales `alpha`, `beta` and no
/// interior constraints, on inputs already validated (dimensions, `u0`,
/// `v0`, the degree). Dimensions 1 to 4 run [`connect_fixed`] (rows of
/// exactly `dim` coordinates); above, the general path
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
    if let Some(connection) = connect_small(p, q, (u0, v0, kp, kq, alpha, beta), None) {
        return connection;
    }
    let problem = super::prepare(p, u0, q, v0, &super::ConnectOptions::new(kp, kq))?;
    super::solve_structured(&problem, alpha, beta)
}

/// The beta-constraints of G^kp, G^kq with the given shape values
/// (`p_shape`: `kp` values, `q_shape`: `kq`, checked by the caller, orders
/// at most [`crate::MAX_GEOMETRIC_ORDER`]) as the end path: the targets are
/// the Bell-polynomial combinations of the jets of [`crate::geometric`]'s
/// `geometric_targets` (the same operations in the same order,
/// [`bell_targets_in_place`]), the scales 1, then the solve and residual
/// check of [`connect_fixed`]. `None` when the problem is outside the
/// fixed arrays (dimension above 4, degree `kp + kq + 1 >= MAX_POINTS`):
/// the caller takes the general path.
#[allow(clippy::too_many_arguments)]
pub(crate) fn connect_ends_shaped<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    kp: usize,
    kq: usize,
    p_shape: &[f64],
    q_shape: &[f64],
) -> Option<Result<Connection>> {
    connect_small(p, q, (u0, v0, kp, kq, 1.0, 1.0), Some((p_shape, q_shape)))
}

/// [`connect_fixed`] in the dimension of `p` when it is 1 to 4 and the
/// degree fits the fixed arrays; `None` otherwise.
fn connect_small<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    q: &Q,
    args: (f64, f64, usize, usize, f64, f64),
    shapes: Option<(&[f64], &[f64])>,
) -> Option<Result<Connection>> {
    let (_, _, kp, kq, _, _) = args;
    if kp + kq + 1 >= MAX_POINTS {
        return None;
    }
    // Arrays of 8, 12 or 16 rows when they suffice: zeroing the full 32 rows
    // of every array costs more than a small problem's substitution.
    let count = kp + kq + 2;
    Some(match (p.dim(), count) {
        (1, _) => connect_fixed::<1, MAX_POINTS, P, Q>(p, q, args, shapes),
        (2, ..=8) => connect_fixed::<2, 8, P, Q>(p, q, args, shapes),
        (2, ..=12) => connect_fixed::<2, 12, P, Q>(p, q, args, shapes),
        (2, ..=16) => connect_fixed::<2, 16, P, Q>(p, q, args, shapes),
        (2, _) => connect_fixed::<2, MAX_POINTS, P, Q>(p, q, args, shapes),
        (3, ..=8) => connect_fixed::<3, 8, P, Q>(p, q, args, shapes),
        (3, ..=12) => connect_fixed::<3, 12, P, Q>(p, q, args, shapes),
        (3, ..=16) => connect_fixed::<3, 16, P, Q>(p, q, args, shapes),
        (3, _) => connect_fixed::<3, MAX_POINTS, P, Q>(p, q, args, shapes),
        (4, _) => connect_fixed::<4, MAX_POINTS, P, Q>(p, q, args, shapes),
        _ => return None,
    })
}

/// Rows `1..=k` of `rows` (the jet `X^(0..=k)`, bounds `errors`) replaced
/// by the targets of the beta-constraints, `T_j = sum_(i=1..j) B_(j,i)(beta)
/// X^(i)` with bound `sum_i |B_(j,i)| (err_i + 4 eps |X^(i)|)`; row 0 stays.
/// Rows are rewritten from `k` down, so every row read is still the jet's.
/// The operations and their order are those of `geometric_targets` (sums
/// from `+0.0`, `i` ascending), so the targets are the same bit for bit.
fn bell_targets_in_place<const D: usize>(rows: &mut [[f64; D]], errors: &mut [f64], shape: &[f64]) {
    let k = rows.len() - 1;
    if k == 0 {
        return;
    }
    let bell = crate::geometric::partial_bell_small(shape, k);
    let mut norms = [0.0f64; crate::geometric::MAX_GEOMETRIC_ORDER + 1];
    for (norm, row) in norms.iter_mut().zip(rows.iter()) {
        *norm = row.iter().map(|v| v * v).sum::<f64>().sqrt();
    }
    for j in (1..=k).rev() {
        let mut target = [0.0f64; D];
        let mut bound = 0.0;
        for i in 1..=j {
            let coefficient = bell[j][i];
            for c in 0..D {
                target[c] += coefficient * rows[i][c];
            }
            bound += coefficient.abs() * (errors[i] + 4.0 * f64::EPSILON * norms[i]);
        }
        rows[j] = target;
        errors[j] = bound;
    }
}

/// [`connect_ends`] in dimension `D` (`p.dim() == q.dim() == D`), result
/// degree `n = kp + kq + 1 < CAP <= MAX_POINTS` (`CAP`: the rows of the
/// fixed arrays); `args` is
/// `(u0, v0, kp, kq, alpha, beta)`.
///
/// Row `r` of the system: `r <= kp` the P end (row `r` of `D(0)`),
/// `r = kp + 1 + k` the Q end (row `k` of `D(1)`), as in
/// [`super::condition_rows`]. Both ends' bands are `n!/(n-k)! (-1)^(k-j)
/// C(k, j)` ([`super::end_band`]), formed from the tables.
fn connect_fixed<const D: usize, const CAP: usize, P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    q: &Q,
    (u0, v0, kp, kq, alpha, beta): (f64, f64, usize, usize, f64, f64),
    shapes: Option<(&[f64], &[f64])>,
) -> Result<Connection> {
    let n = kp + kq + 1;
    let count = n + 1;
    // The jets straight into the target rows: P arrives at u0 (from the
    // left of a knot), Q leaves v0.
    let mut targets = [[0.0f64; D]; CAP];
    let mut target_errors = [0.0f64; CAP];
    {
        let (p_rows, q_rows) = targets[..count].split_at_mut(kp + 1);
        let (p_errors, q_errors) = target_errors[..count].split_at_mut(kp + 1);
        p.jet_into(u0, kp, KnotSide::Left, p_rows.as_flattened_mut(), p_errors);
        q.jet_into(v0, kq, KnotSide::Right, q_rows.as_flattened_mut(), q_errors);
        if let Some((p_shape, q_shape)) = shapes {
            bell_targets_in_place(p_rows, p_errors, p_shape);
            bell_targets_in_place(q_rows, q_errors, q_shape);
        }
    }
    // Targets and their bounds in place: T_k = s^k X^(k),
    // e_k = s^k err_k + (k + 1) u |T_k|.
    let mut target_norms = [0.0f64; CAP];
    for (first, order, scale) in [(0, kp, alpha), (kp + 1, kq, beta)] {
        let mut factor = 1.0f64;
        for k in 0..=order {
            let r = first + k;
            let mut square = 0.0;
            for v in &mut targets[r] {
                *v *= factor;
                square += *v * *v;
            }
            let norm = square.sqrt();
            target_norms[r] = norm;
            target_errors[r] =
                power(scale, k) * target_errors[r] + (k + 1) as f64 * unit_roundoff() * norm;
            factor *= scale;
        }
    }
    // The order of the derivative of row r.
    let order_of = |r: usize| if r <= kp { r } else { r - kp - 1 };
    // The 1-norms of the rows (the table of `end_band_norm`, the sums the
    // general path forms) and the data scale of `check_residuals`.
    let norms = &END_BAND_NORMS[n];
    let mut data_scale = p.coordinate_scale().max(q.coordinate_scale());
    for r in 0..count {
        let v = target_norms[r] / norms[order_of(r)];
        if v.is_finite() {
            data_scale = data_scale.max(v);
        }
    }
    let gamma = 2.0 * (2 * n + 4) as f64 * unit_roundoff();
    let falling = &FALLING_FACTORIALS[n];
    let mut points = [[0.0f64; D]; CAP];
    let mut max_residual = 0.0f64;
    let mut error_estimate = 0.0f64;
    let mut difference_squares = [0.0f64; CAP];
    let mut abs_squares = [0.0f64; CAP];
    let mut denominators = [0.0f64; CAP];
    // Row by row: the band once, the unknown it determines, its residual.
    // P end: row k of D(0) touches R_0..R_k only (lower triangular); Q end:
    // row k of D(1) touches R_(n-k)..R_n only (anti-triangular). The two
    // sets of unknowns are disjoint (n - kq = kp + 1), so a row's residual
    // is final as soon as its own unknown is solved. One pass over the
    // known points of the band feeds both the substitution sum
    // `T - sum b_i R_i` and the residual's `sum b_i R_i`, `sum |b_i| |R_i|`
    // (each accumulator in the general path's order), then the new point
    // adds its terms.
    for r in 0..count {
        let (k, new, known) = if r <= kp {
            // Row k of D(0): unknown R_k, known R_0..R_(k-1) at band 0..k.
            (r, r, 0)
        } else {
            // Row k of D(1): unknown R_(n-k) at band 0, known R_(n-k+1)..R_n.
            let k = r - kp - 1;
            (k, n - k, n - k + 1)
        };
        let f = falling[k];
        let signed = &SIGNED_BINOMIALS[k];
        let target = targets[r];
        // Band slots of the known points and of the new one.
        let (known_slots, new_slot) = if r <= kp { (0..k, k) } else { (1..k + 1, 0) };
        let mut sum = target;
        let mut value = [0.0f64; D];
        let mut abs_value = [0.0f64; D];
        let new_band = f * signed[new_slot];
        // D(0): the known points come before the new one in the residual's
        // order (columns ascending); D(1): after it.
        if r > kp {
            // The new point's residual terms come first; solve it first.
            for (slot, point) in known_slots.clone().zip(&points[known..=n]) {
                let b = f * signed[slot];
                for c in 0..D {
                    sum[c] -= b * point[c];
                }
            }
            for c in 0..D {
                points[new][c] = sum[c] / new_band;
            }
            let x = points[new];
            for c in 0..D {
                value[c] += new_band * x[c];
                abs_value[c] += new_band.abs() * x[c].abs();
            }
            for (slot, point) in known_slots.zip(&points[known..=n]) {
                let b = f * signed[slot];
                for c in 0..D {
                    value[c] += b * point[c];
                    abs_value[c] += b.abs() * point[c].abs();
                }
            }
        } else {
            for (slot, point) in known_slots.zip(&points[..k]) {
                let b = f * signed[slot];
                for c in 0..D {
                    sum[c] -= b * point[c];
                    value[c] += b * point[c];
                    abs_value[c] += b.abs() * point[c].abs();
                }
            }
            for c in 0..D {
                points[new][c] = sum[c] / new_band;
            }
            let x = points[new];
            for c in 0..D {
                value[c] += new_band * x[c];
                abs_value[c] += new_band.abs() * x[c].abs();
            }
        }
        let mut difference_square = 0.0;
        let mut abs_square = 0.0;
        for c in 0..D {
            let difference = value[c] - target[c];
            difference_square += difference * difference;
            abs_square += abs_value[c] * abs_value[c];
        }
        difference_squares[r] = difference_square;
        abs_squares[r] = abs_square;
        denominators[r] = target_norms[r].max(data_scale * norms[k]);
    }
    // The residuals and their bounds in a pass of their own: the square
    // roots and divisions of different rows are independent there (the
    // substitution above is a chain), the same operations per row.
    // The formulas first (branch-free, so the rows' square roots and
    // divisions go side by side), then the guard and the maxima.
    let mut residuals = [0.0f64; CAP];
    let mut bounds = [0.0f64; CAP];
    for r in 0..count {
        (residuals[r], bounds[r]) = residual_and_bound_unguarded(
            difference_squares[r],
            abs_squares[r],
            gamma,
            target_errors[r],
            denominators[r],
        );
    }
    for r in 0..count {
        let (residual, bound) = finite_or_infinite((residuals[r], bounds[r]));
        max_residual = max_residual.max(residual);
        error_estimate = error_estimate.max(bound);
    }
    let flat = points[..count].as_flattened().to_vec();
    let trusted = error_estimate.is_finite() && error_estimate <= CONNECT_RESIDUAL_LIMIT;
    if !trusted || flat.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::IllConditioned {
            what: format!("connect (degree {n})"),
            estimate: error_estimate,
            limit: CONNECT_RESIDUAL_LIMIT,
        });
    }
    Ok(Connection {
        curve: BezierCurve::from_parts(D, n, flat),
        p_scale: alpha,
        q_scale: beta,
        max_residual,
        error_estimate,
        constraint_condition: 1.0,
    })
}
