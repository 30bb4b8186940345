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

/// [`connect_ends`]'s curve alone, the same control points bit for bit and
/// the same errors (the hot path of `bzj_connect`, which returns no
/// estimate). In the plane and in space a screen runs first
/// ([`super::screen`]): the same jets' values, targets and substitution,
/// and instead of the residual check's Euclidean norms, square roots and
/// divisions, bounds that are never below the check's. When every
/// condition row passes the screen, every row's bound in the full check is
/// below [`CONNECT_RESIDUAL_LIMIT`], so the full check would accept the
/// same points; when any row does not pass (or a value is not finite), the
/// full [`connect_ends`] runs and answers, estimate and refusal included.
#[allow(clippy::too_many_arguments)]
pub(super) fn connect_ends_curve<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    kp: usize,
    kq: usize,
    alpha: f64,
    beta: f64,
) -> Result<BezierCurve> {
    match super::screen::connect_ends_screened(p, q, (u0, v0, kp, kq, alpha, beta)) {
        Some(curve) => Ok(curve),
        None => connect_ends(p, u0, q, v0, kp, kq, alpha, beta).map(|c| c.curve),
    }
}

/// The jets at both ends in condition rows (`kp + 1` of P, then `kq + 1`
/// of Q), their rounding bounds, and the data scale's start (the curves'
/// coordinate scale).
struct ScaledTargets<const D: usize, const CAP: usize> {
    rows: [[f64; D]; CAP],
    errors: [f64; CAP],
    data_scale: f64,
}

impl<const D: usize, const CAP: usize> ScaledTargets<D, CAP> {
    /// The targets in place ([`scale_targets`]: `alpha^k`, `beta^k`, their
    /// bounds and norms, the data scale raised), then the two ends'
    /// substitutions and checks ([`solve_end_by_rows`]): `R` in the first
    /// `n + 1` rows, and each end's worst residual and bound.
    ///
    /// P end: row k of D(0) touches R_0..R_k only (lower triangular); Q
    /// end: row k of D(1) touches R_(n-k)..R_n only (anti-triangular). The
    /// two sets of unknowns are disjoint (n - kq = kp + 1), so each end is
    /// solved and checked on its own.
    #[inline(always)]
    fn solve(
        &mut self,
        n: usize,
        (kp, kq): (usize, usize),
        (alpha, beta): (f64, f64),
    ) -> ([[f64; D]; CAP], [(f64, f64); 2]) {
        let mut norms = [0.0f64; CAP];
        for (first, rows, scale) in [(0, kp + 1, alpha), (kp + 1, kq + 1, beta)] {
            let range = first..first + rows;
            scale_targets::<D>(
                n,
                scale,
                &mut self.rows[range.clone()],
                &mut self.errors[range.clone()],
                &mut norms[range],
                &mut self.data_scale,
            );
        }
        let end = |first: usize, rows: usize| EndRows {
            n,
            targets: &self.rows[first..first + rows],
            target_norms: &norms[first..first + rows],
            target_errors: &self.errors[first..first + rows],
            data_scale: self.data_scale,
            gamma: row_rounding(n),
        };
        let mut points = [[0.0f64; D]; CAP];
        let (p_points, q_points) = points[..n + 1].split_at_mut(kp + 1);
        let p_end = solve_end_by_rows::<D, false>(&end(0, kp + 1), p_points);
        let q_end = solve_end_by_rows::<D, true>(&end(kp + 1, kq + 1), q_points);
        (points, [p_end, q_end])
    }
}

/// The rounding factor of a row product `D_k R` in the residual check,
/// `2 (2 n + 4) u`.
fn row_rounding(n: usize) -> f64 {
    2.0 * (2 * n + 4) as f64 * unit_roundoff()
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
    // The order a constant for each geometric order (1 to 6), so that the
    // loops of [`bell_targets_order`] have constant bounds and unroll.
    match rows.len() - 1 {
        0 => {}
        1 => bell_targets_order::<D>(1, rows, errors, shape),
        2 => bell_targets_order::<D>(2, rows, errors, shape),
        3 => bell_targets_order::<D>(3, rows, errors, shape),
        4 => bell_targets_order::<D>(4, rows, errors, shape),
        5 => bell_targets_order::<D>(5, rows, errors, shape),
        6 => bell_targets_order::<D>(6, rows, errors, shape),
        k => bell_targets_order::<D>(k, rows, errors, shape),
    }
}

/// [`bell_targets_in_place`] for order `k = rows.len() - 1 >= 1`: the inner
/// loop runs over `1..=k` with a test `i <= j` (instead of the bound `j`),
/// so that with `k` a constant every bound is; the terms that pass the test
/// are those of the triangular loop, in the same order.
#[inline(always)]
fn bell_targets_order<const D: usize>(
    k: usize,
    rows: &mut [[f64; D]],
    errors: &mut [f64],
    shape: &[f64],
) {
    let bell = crate::geometric::partial_bell_small(shape, k);
    let mut norms = [0.0f64; crate::geometric::MAX_GEOMETRIC_ORDER + 1];
    for (norm, row) in norms.iter_mut().zip(rows.iter()) {
        *norm = row.iter().map(|v| v * v).sum::<f64>().sqrt();
    }
    // Exclusive ranges, which unroll with `k` a constant.
    for j in (1..k + 1).rev() {
        let mut target = [0.0f64; D];
        let mut bound = 0.0;
        for i in 1..k + 1 {
            if i <= j {
                let coefficient = bell[j][i];
                for c in 0..D {
                    target[c] += coefficient * rows[i][c];
                }
                bound += coefficient.abs() * (errors[i] + 4.0 * f64::EPSILON * norms[i]);
            }
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
            // G^k needs a regular point at each end of order >= 1.
            let zero = |rows: &[[f64; D]]| rows.len() > 1 && rows[1].iter().all(|v| *v == 0.0);
            crate::geometric::check_regular_ends((u0, zero(p_rows)), (v0, zero(q_rows)), (kp, kq))?;
            // The ends' tangents and curvatures must be known to the promise,
            // as the general path checks them (the same numbers): the input's
            // part on the jets, the stored blend's on the targets.
            use crate::geometric::{
                GEOMETRIC_CONDITION_LIMIT, geometric_condition_error, input_condition,
                largest_coordinate, stored_condition,
            };
            let chord = crate::bezier::distance(&p_rows[0], &q_rows[0]);
            let stored = (n, largest_coordinate(&p_rows[0], &q_rows[0]));
            let p_input = input_condition(p_rows, p_errors, kp, chord, n);
            let q_input = input_condition(q_rows, q_errors, kq, chord, n);
            bell_targets_in_place(p_rows, p_errors, p_shape);
            bell_targets_in_place(q_rows, q_errors, q_shape);
            let p = p_input.0 + stored_condition(p_rows, kp, chord, stored);
            let q = q_input.0 + stored_condition(q_rows, kq, chord, stored);
            if p.max(q) > GEOMETRIC_CONDITION_LIMIT {
                return Err(geometric_condition_error(
                    (p, u0, p_input.1, p_input.2),
                    (q, v0, q_input.1, q_input.2),
                    (kp, kq),
                ));
            }
        }
    }
    // Targets and their bounds in place, their norms, and the data scale
    // of `check_residuals` ([`scale_targets`]), then both ends' solves.
    let mut targets = ScaledTargets {
        rows: targets,
        errors: target_errors,
        data_scale: p.coordinate_scale().max(q.coordinate_scale()),
    };
    let (points, [(p_residual, p_bound), (q_residual, q_bound)]) =
        targets.solve(n, (kp, kq), (alpha, beta));
    // The maxima over all rows (f64::max of non-negative, non-NaN values:
    // the order of the rows does not matter).
    let max_residual = 0.0f64.max(p_residual).max(q_residual);
    let error_estimate = 0.0f64.max(p_bound).max(q_bound);
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

/// One end's targets and their bounds in place (`k = 0..rows.len()`):
/// `T_k = s^k X^(k)`, `e_k = s^k err_k + (k + 1) u |T_k|` (`s^k` as
/// [`power`] forms it, the factor of `X^(k)` by repeated products), the
/// norms `|T_k|` into `norms`, and `data_scale` raised to every finite
/// `|T_k| / ||D_k||_1` (the 1-norms of the rows from the table of
/// `end_band_norm`, the sums the general path forms; `f64::max` over
/// non-NaN values, so the order of the rows does not matter).
///
/// With `s = 1` (the paper's scale) the products by `s^k` and by the
/// factor are skipped: they are exact (`1 x = x` for every `x`, and
/// `power(1, k) = 1`), so the values are the same bit for bit.
fn scale_targets<const D: usize>(
    n: usize,
    scale: f64,
    rows: &mut [[f64; D]],
    errors: &mut [f64],
    norms: &mut [f64],
    data_scale: &mut f64,
) {
    let band_norms = &END_BAND_NORMS[n];
    let unit = scale == 1.0;
    let mut factor = 1.0f64;
    for (k, ((row, error), norm)) in rows
        .iter_mut()
        .zip(errors.iter_mut())
        .zip(norms.iter_mut())
        .enumerate()
    {
        let mut square = 0.0;
        for v in row.iter_mut() {
            if !unit {
                *v *= factor;
            }
            square += *v * *v;
        }
        let size = square.sqrt();
        let scaled_error = if unit {
            *error
        } else {
            power(scale, k) * *error
        };
        *error = scaled_error + (k + 1) as f64 * unit_roundoff() * size;
        factor *= scale;
        *norm = size;
        let v = size / band_norms[k];
        if v.is_finite() {
            *data_scale = data_scale.max(v);
        }
    }
}

/// One end's condition rows for [`solve_end`]: the targets `T_k`, their
/// norms and rounding bounds (`k = 0..rows`), and what the residual check
/// needs of the whole system.
struct EndRows<'a, const D: usize> {
    /// The degree of `R`.
    n: usize,
    targets: &'a [[f64; D]],
    target_norms: &'a [f64],
    target_errors: &'a [f64],
    /// The data scale `S` of the residual check.
    data_scale: f64,
    /// The rounding factor of `D_k R`, `2 (2 n + 4) u`.
    gamma: f64,
}

/// [`solve_end`] with the number of rows a constant for orders up to 7
/// (`rows` 1 to 8: every loop of the substitution with constant bounds,
/// unrolled), the same code with a run-time count above.
fn solve_end_by_rows<const D: usize, const AT_ONE: bool>(
    end: &EndRows<'_, D>,
    points: &mut [[f64; D]],
) -> (f64, f64) {
    match end.targets.len() {
        1 => solve_end::<D, AT_ONE, 1>(1, end, points),
        2 => solve_end::<D, AT_ONE, 2>(2, end, points),
        3 => solve_end::<D, AT_ONE, 3>(3, end, points),
        4 => solve_end::<D, AT_ONE, 4>(4, end, points),
        5 => solve_end::<D, AT_ONE, 5>(5, end, points),
        6 => solve_end::<D, AT_ONE, 6>(6, end, points),
        7 => solve_end::<D, AT_ONE, 7>(7, end, points),
        8 => solve_end::<D, AT_ONE, 8>(8, end, points),
        rows => solve_end::<D, AT_ONE, MAX_POINTS>(rows, end, points),
    }
}

/// The rows `k = 0..rows` (`rows <= ROWS`, the size of the scratch
/// arrays) of one end: `D(0)` (`AT_ONE = false`, unknown
/// `R_k`, known `R_0..R_(k-1)` at band slots `0..k`) or `D(1)` (unknown
/// `R_(n-k)` at slot 0, known `R_(n-k+1)..R_n` at slots `1..=k`), with the
/// band `n!/(n-k)! (-1)^(k-s) C(k, s)` ([`super::end_band`]) from the
/// tables. Row by row: the unknown by substitution on the row divided by
/// its diagonal entry (`T_k / b_k` by [`divided_target`], then the known
/// points times the integers `b_s / b_k`), then the row's residual sums
/// `sum b_s R_s` and `sum |b_s| |R_s|` (each accumulator in the general
/// path's order: columns ascending, so at the P end the known points
/// first, at the Q end the new one first); at the P end the substitution
/// and the residual sums share the pass over the known points. Then every
/// row's residual and bound ([`residual_and_bound_unguarded`], branch-free,
/// the rows side by side), the guard and the maxima. Returns the end's
/// worst residual and bound. `points` is the end's part of `R`:
/// `R_0..R_(rows-1)` (P) or `R_(n+1-rows)..R_n` (Q).
///
/// The inner loops run over all `rows` slots with a test `s < k` (P) or
/// `s <= k` (Q) instead of bounds that depend on `k`: with `rows` a
/// constant every loop has constant bounds and unrolls; the operations on
/// the slots that pass the test are those of the triangular loops.
#[inline(always)]
fn solve_end<const D: usize, const AT_ONE: bool, const ROWS: usize>(
    rows: usize,
    end: &EndRows<'_, D>,
    points: &mut [[f64; D]],
) -> (f64, f64) {
    debug_assert_eq!(points.len(), rows);
    let n = end.n;
    let falling = &FALLING_FACTORIALS[n];
    let norms = &END_BAND_NORMS[n];
    let mut difference_squares = [0.0f64; ROWS];
    let mut abs_squares = [0.0f64; ROWS];
    // The end's unknowns in the order they are solved: `R_k` (P end) or
    // `R_(n-k)` (Q end) at `local[k]`, copied out at the end (a local array
    // indexed by constants stays in registers).
    let mut local = [[0.0f64; D]; ROWS];
    for k in 0..rows {
        let f = falling[k];
        let signed = &SIGNED_BINOMIALS[k];
        let target = end.targets[k];
        let mut value = [0.0f64; D];
        let mut abs_value = [0.0f64; D];
        if AT_ONE {
            // The new point's residual terms come first; solve it first.
            let new_band = f * signed[0];
            let mut x = divided_target(target, new_band);
            for s in 1..rows {
                if s <= k {
                    // `b_s / b_0`, an exact integer (`signed[0]` is +-1).
                    let ratio = signed[s] * signed[0];
                    let point = local[k - s];
                    for c in 0..D {
                        x[c] -= ratio * point[c];
                    }
                }
            }
            for c in 0..D {
                value[c] += new_band * x[c];
                abs_value[c] += new_band.abs() * x[c].abs();
            }
            local[k] = x;
            for s in 1..rows {
                if s <= k {
                    let b = f * signed[s];
                    let point = local[k - s];
                    for c in 0..D {
                        value[c] += b * point[c];
                        abs_value[c] += b.abs() * point[c].abs();
                    }
                }
            }
        } else {
            let new_band = f * signed[k];
            let mut x = divided_target(target, new_band);
            for s in 0..rows {
                if s < k {
                    // `b_s / b_k`, an exact integer (`signed[k]` is 1).
                    let ratio = signed[s] * signed[k];
                    let b = f * signed[s];
                    let point = local[s];
                    for c in 0..D {
                        x[c] -= ratio * point[c];
                        value[c] += b * point[c];
                        abs_value[c] += b.abs() * point[c].abs();
                    }
                }
            }
            for c in 0..D {
                value[c] += new_band * x[c];
                abs_value[c] += new_band.abs() * x[c].abs();
            }
            local[k] = x;
        }
        let mut difference_square = 0.0;
        let mut abs_square = 0.0;
        for c in 0..D {
            let difference = value[c] - target[c];
            difference_square += difference * difference;
            abs_square += abs_value[c] * abs_value[c];
        }
        difference_squares[k] = difference_square;
        abs_squares[k] = abs_square;
    }
    for (k, x) in local[..rows].iter().enumerate() {
        // `points` holds `R_0..R_(rows-1)` (P) or `R_(n+1-rows)..R_n` (Q).
        points[if AT_ONE { rows - 1 - k } else { k }] = *x;
    }
    // The residuals and their bounds in a pass of their own: the square
    // roots and divisions of different rows are independent there (the
    // substitution above is a chain), the same operations per row.
    let mut residuals = [0.0f64; ROWS];
    let mut bounds = [0.0f64; ROWS];
    for k in 0..rows {
        let denominator = end.target_norms[k].max(end.data_scale * norms[k]);
        (residuals[k], bounds[k]) = residual_and_bound_unguarded(
            difference_squares[k],
            abs_squares[k],
            end.gamma,
            end.target_errors[k],
            denominator,
        );
    }
    let mut max_residual = 0.0f64;
    let mut max_bound = 0.0f64;
    for k in 0..rows {
        let (residual, bound) = finite_or_infinite((residuals[k], bounds[k]));
        max_residual = max_residual.max(residual);
        max_bound = max_bound.max(bound);
    }
    (max_residual, max_bound)
}

/// `T_k / b_k` per coordinate: the start of row `k`'s substitution divided
/// by its diagonal entry (docs/mathematics.md, "Connect: the structured
/// solve"). It depends on no solved point, so the divisions of all rows run
/// beside the chain of substitutions, whose steps are then products by the
/// exact integers `b_s / b_k = +-C(k, s)`. Shared by the end path and the
/// screen, so the two give the same points bit for bit.
#[inline(always)]
pub(super) fn divided_target<const D: usize>(target: [f64; D], diagonal: f64) -> [f64; D] {
    target.map(|v| v / diagonal)
}
