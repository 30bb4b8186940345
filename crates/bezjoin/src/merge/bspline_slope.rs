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

/// `R` split at `mu` (inserted `p` times by Boehm's algorithm) as a linear
/// map on `R`'s poles, with its derivative in `mu` at fixed poles. `mu`
/// lies in the span `tau_k <= mu < tau_{k+1}` (`k = n_P - 1`, no knot of
/// `R` at the join); the insertions change only the poles `k - p..=k`, so
/// the split poles are `r_i` for `i < k - p`, `block` times `r_{k-p..=k}`
/// for the `2p + 1` rows `k - p..=k + p`, and `r_{i-p}` after: `O(p^3)`
/// work however many poles `R` has. `P^` is split rows `0..=k`, `Q^` rows
/// `k..`.
pub(super) struct PairSplit {
    /// `k`: the span of `R` holding `mu`, the index of the split pole `R(mu)`.
    pub span: usize,
    /// `(2p + 1) x (p + 1)`.
    pub block: DMatrix<f64>,
    /// `d block / d mu` with the knots moving at their rates (zero when
    /// no rates were given).
    pub block_rate: DMatrix<f64>,
}

/// [`PairSplit`] of `R` (degree `p`, `knots`, each moving at `rates` if
/// given) at `mu`, which lies in the span `span`.
pub(super) fn pair_split(
    degree: usize,
    knots: &[f64],
    rates: Option<&[f64]>,
    mu: f64,
    span: usize,
) -> PairSplit {
    let p = degree;
    let k = span;
    debug_assert!(k >= p && knots[k] <= mu && mu < knots[k + 1]);
    // The local curve: poles k-p..=k (unit vectors), knots k-p..=k+p+1.
    let mut local: Vec<f64> = knots[k - p..=k + p + 1].to_vec();
    let mut local_rates: Vec<f64> = match rates {
        Some(rates) => rates[k - p..=k + p + 1].to_vec(),
        None => Vec::new(),
    };
    let width = p + 1;
    let with_rates = rates.is_some();
    // Row-major: row i of the local poles is h[i * width..(i + 1) * width].
    let mut h = vec![0.0; (2 * p + 1) * width];
    for i in 0..width {
        h[i * width + i] = 1.0;
    }
    let mut dh = vec![0.0; if with_rates { h.len() } else { 0 }];
    // Row i is zero outside the columns lo[i]..=hi[i] (a new row combines
    // two neighbours, lo[i-1] <= lo[i] and hi[i-1] <= hi[i]): about half
    // of the block, which is what the loops visit.
    let mut lo: Vec<usize> = (0..2 * p + 1).collect();
    let mut hi = lo.clone();
    // Insertion j (0-based) has j + p + 1 poles before it; mu is in local
    // span p + j. New poles i = j + 1..=p + j (old indices) from i and i - 1,
    // computed from the top down so that each reads unchanged rows; the
    // old pole p + j moves to p + j + 1.
    for j in 0..p {
        let top = p + j;
        h.copy_within(top * width..(top + 1) * width, (top + 1) * width);
        if with_rates {
            dh.copy_within(top * width..(top + 1) * width, (top + 1) * width);
        }
        (lo[top + 1], hi[top + 1]) = (lo[top], hi[top]);
        for i in (j + 1..=top).rev() {
            let columns = lo[i - 1]..hi[i] + 1;
            lo[i] = lo[i - 1];
            let numerator = mu - local[i];
            let denominator = local[i + p] - local[i];
            let alpha = numerator / denominator;
            let (before, now) = h[(i - 1) * width..(i + 1) * width].split_at_mut(width);
            if with_rates {
                let numerator_rate = 1.0 - local_rates[i];
                let denominator_rate = local_rates[i + p] - local_rates[i];
                let alpha_rate = (numerator_rate * denominator - numerator * denominator_rate)
                    / (denominator * denominator);
                let (before_rate, now_rate) =
                    dh[(i - 1) * width..(i + 1) * width].split_at_mut(width);
                for (((rate, &before_rate), &now), &before) in now_rate[columns.clone()]
                    .iter_mut()
                    .zip(&before_rate[columns.clone()])
                    .zip(&now[columns.clone()])
                    .zip(&before[columns.clone()])
                {
                    *rate =
                        alpha_rate * (now - before) + alpha * *rate + (1.0 - alpha) * before_rate;
                }
            }
            for (value, &before) in now[columns.clone()].iter_mut().zip(&before[columns]) {
                *value = alpha * *value + (1.0 - alpha) * before;
            }
        }
        local.insert(top + 1, mu);
        if with_rates {
            local_rates.insert(top + 1, 1.0);
        }
    }
    let rows = 2 * p + 1;
    PairSplit {
        span: k,
        block: DMatrix::from_row_slice(rows, width, &h),
        block_rate: if with_rates {
            DMatrix::from_row_slice(rows, width, &dh)
        } else {
            DMatrix::zeros(rows, width)
        },
    }
}

impl PairSplit {
    /// `A_P` (`(k + 1) x n_R`) and `A_Q` (`n_Q x n_R`), the restriction
    /// matrices of the two pieces, as (first column, the columns from
    /// there on that can be non-zero): `A_P` uses poles `0..=k`, `A_Q`
    /// poles `k - p..`.
    pub(super) fn restrictions(
        &self,
        degree: usize,
        unknowns: usize,
    ) -> [(usize, DMatrix<f64>); 2] {
        let (p, k) = (degree, self.span);
        let rows = unknowns + p;
        let right_count = rows - k;
        let offset = k - p;
        let mut left = DMatrix::zeros(k + 1, k + 1);
        let mut right = DMatrix::zeros(right_count, unknowns - offset);
        for i in 0..k - p {
            left[(i, i)] = 1.0;
        }
        for b in 0..=p {
            for c in 0..=p {
                left[(k - p + b, k - p + c)] = self.block[(b, c)];
                right[(b, c)] = self.block[(p + b, c)];
            }
        }
        for i in p + 1..right_count {
            right[(i, k + i - p - offset)] = 1.0;
        }
        [(0, left), (offset, right)]
    }

    /// `(dA_P/dmu) r` and `(dA_Q/dmu) r` at fixed poles `r` (`n_R x dim`).
    pub(super) fn piece_rates(
        &self,
        degree: usize,
        poles: &DMatrix<f64>,
    ) -> (DMatrix<f64>, DMatrix<f64>) {
        let (p, k) = (degree, self.span);
        let d = poles.ncols();
        let local = self.block_rate.clone() * poles.rows(k - p, p + 1);
        let right_count = poles.nrows() + p - k;
        let mut left = DMatrix::zeros(k + 1, d);
        let mut right = DMatrix::zeros(right_count, d);
        left.rows_mut(k - p, p + 1).copy_from(&local.rows(0, p + 1));
        right.rows_mut(0, p + 1).copy_from(&local.rows(p, p + 1));
        (left, right)
    }
}
