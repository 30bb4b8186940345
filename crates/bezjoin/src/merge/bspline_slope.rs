//! `d metric / d mu` of the B-spline pair merge ([`super::merge_bsplines`]
//! with [`super::Breakpoints::Optimal`]), in closed form.
//!
//! # The slope
//!
//! At a split `mu` the merged curve `R` has the poles `r` and the knots
//! `T(mu)`: `p + 1` zeros, `P`'s interior knots `mu s_i` (`s_i = (k_i -
//! a_P) / (b_P - a_P)`), `Q`'s interior knots `mu + (1 - mu) s'_i`, `p + 1`
//! ones. Stage 1 minimises
//!
//! ```text
//! F(r, mu) = sum_j (A_j(mu) r - c_j)^T W_j (A_j(mu) r - c_j)
//! ```
//!
//! over `r` under constraints that do not depend on `mu` (none, or fix
//! ends: `R`'s first and last pole; kept curves and keep points make the
//! rows depend on `mu` and are searched on values alone). By the envelope
//! theorem the metric `f(mu) = min_r F(r, mu)` has the slope
//!
//! ```text
//! f'(mu) = dF/dmu at the optimal, fixed r
//!        = 2 sum_j (A_j r - c_j)^T W_j (dA_j/dmu) r,
//! ```
//!
//! the Lagrange terms vanishing because the constraint rows are constant.
//! `A_j(mu) r` is the piece `R|[t_j, t_{j+1}]` on `C_j`'s own knots: the
//! poles of `R` after inserting `mu` `p` times (Boehm's algorithm), the
//! first `n_P` for `P^`, the last `n_Q` for `Q^`. Every inserted pole is
//! `alpha P_i + (1 - alpha) P_{i-1}` with `alpha = (mu - tau_i) / (tau_{i+p}
//! - tau_i)`, a rational function of `mu` and of knots that move with
//! `mu` at the rates `d tau / d mu` (0 for the end knots, `s_i` for `P`'s,
//! `1 - s'_i` for `Q`'s, 1 for every inserted `mu`). Carrying the
//! derivative through every insertion (forward differentiation, exact up
//! to rounding) gives `(dA_j/dmu) r` for the knot motion and the moving
//! split together, `O(p^2 dim)` work per trial.
//!
//! The slope is checked against central differences of the metric
//! (`tests::slope_is_the_derivative_of_the_metric`).

use nalgebra::DMatrix;

use crate::basis::{KnotSide, find_span};
use crate::nurbs::NurbsCurve;

/// `d tau / d mu` for every knot of `R` (the order of
/// `SplineProblem::merged_knots` for two pieces): the clamped ends are
/// fixed, `P`'s interior knot `mu s` moves at `s`, `Q`'s `mu + (1 - mu) s`
/// at `1 - s`.
pub(super) fn knot_rates(degree: usize, p: &NurbsCurve, q: &NurbsCurve) -> Vec<f64> {
    let mut rates = vec![0.0; degree + 1];
    for (curve, from_start) in [(p, true), (q, false)] {
        let (a, b) = curve.domain();
        let n = curve.point_count();
        for &k in &curve.knots()[degree + 1..n] {
            let s = (k - a) / (b - a);
            rates.push(if from_start { s } else { 1.0 - s });
        }
    }
    rates.extend(std::iter::repeat_n(0.0, degree + 1));
    rates
}

/// `(dA_P/dmu) r` and `(dA_Q/dmu) r`: the derivatives of `R`'s pieces on
/// `[0, mu]` (the first `left_count` poles) and `[mu, 1]` (the last
/// `right_count`) with respect to `mu` at fixed poles `r` (`n_R x dim`),
/// `R` on `knots` moving at `rates` (the module's method). `mu` must lie
/// strictly between two knots of `R` (no knot of `R` is at the join).
pub(super) fn piece_rates(
    degree: usize,
    knots: &[f64],
    rates: &[f64],
    poles: &DMatrix<f64>,
    mu: f64,
    left_count: usize,
    right_count: usize,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let p = degree;
    let d = poles.ncols();
    debug_assert_eq!(knots.len(), rates.len());
    debug_assert_eq!(knots.len(), poles.nrows() + p + 1);
    let mut knots = knots.to_vec();
    let mut rates = rates.to_vec();
    // Row-major poles and their rates (zero: r is fixed).
    let mut h: Vec<f64> = (0..poles.nrows())
        .flat_map(|i| (0..d).map(move |c| (i, c)))
        .map(|(i, c)| poles[(i, c)])
        .collect();
    let mut dh = vec![0.0; h.len()];
    let mut out = Vec::with_capacity(h.len() + p * d);
    let mut dout = Vec::with_capacity(h.len() + p * d);
    for _ in 0..p {
        let k = find_span(&knots, p, mu, KnotSide::Right);
        out.clear();
        dout.clear();
        out.extend_from_slice(&h[..(k + 1 - p) * d]);
        dout.extend_from_slice(&dh[..(k + 1 - p) * d]);
        for i in (k + 1 - p)..=k {
            let numerator = mu - knots[i];
            let denominator = knots[i + p] - knots[i];
            let alpha = numerator / denominator;
            let numerator_rate = 1.0 - rates[i];
            let denominator_rate = rates[i + p] - rates[i];
            let alpha_rate = (numerator_rate * denominator - numerator * denominator_rate)
                / (denominator * denominator);
            for c in 0..d {
                let (now, before) = (h[i * d + c], h[(i - 1) * d + c]);
                let (now_rate, before_rate) = (dh[i * d + c], dh[(i - 1) * d + c]);
                out.push(alpha * now + (1.0 - alpha) * before);
                dout.push(
                    alpha_rate * (now - before) + alpha * now_rate + (1.0 - alpha) * before_rate,
                );
            }
        }
        out.extend_from_slice(&h[k * d..]);
        dout.extend_from_slice(&dh[k * d..]);
        std::mem::swap(&mut h, &mut out);
        std::mem::swap(&mut dh, &mut dout);
        knots.insert(k + 1, mu);
        rates.insert(k + 1, 1.0);
    }
    let total = h.len() / d;
    debug_assert_eq!(total + 1, left_count + right_count);
    let left = DMatrix::from_row_slice(left_count, d, &dh[..left_count * d]);
    let right = DMatrix::from_row_slice(right_count, d, &dh[(total - right_count) * d..]);
    (left, right)
}
