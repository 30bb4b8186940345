//! The lean trial of the optimal-`mu` search: the metric and its slope at
//! one `mu`, for two pieces without kept curves or keep points (fix ends
//! allowed), with everything that does not depend on `mu` prepared once.
//!
//! The mathematics is the orthogonal stage 1's (module `orthogonal`):
//! `R`'s control points `r` are the unknowns, the metric is
//! `f(mu) = min_r ||M(mu) r - b||^2` with
//!
//! * discrete: `M = S(mu) = [S_L; S_R]`, `S_L[i][k] = B_k^i(mu)`,
//!   `S_R[i][k] = B_(k-i)^(m-i)(mu)` (the exact restrictions of `R` to
//!   `[0, mu]` and `[mu, 1]`), `b` the input control points;
//! * integral: rows `sqrt(w_k) B^m(mu u_k)` and `sqrt(w_k) B^m(mu + (1 -
//!   mu) u_k)` at the `m + 1` Gauss-Legendre nodes `u_k` of `[0, 1]`, `b`
//!   the rows `sqrt(w_k) P(u_k)`, `sqrt(w_k) Q(u_k)`: `b`, the nodes, the
//!   weights and the binomials do not depend on `mu` and are computed once.
//!
//! Fix ends are `r_0 = P_0`, `r_m = Q_m` (the first row of `S_L` and the
//! last of `S_R` are unit rows), so they remove two columns. The slope is
//! the envelope theorem's `f'(mu) = -2 <b - M r, M'(mu) r>` at the optimal
//! `r` (the constraints do not depend on `mu`), with `M'(mu) r` the control
//! points of `u R'(mu u)` and `(1 - v) R'(mu + (1 - mu) v)` (discrete) or
//! `sqrt(w_k)` times those functions at the nodes (integral).
//!
//! What a trial does: fill `M(mu)` (`O(m^2)`), one Householder QR of the
//! `2(m + 1) x (m + 1)` matrix applied to all coordinates at once, one
//! back substitution, the residual and the slope (`O(m^2)`); flat buffers
//! allocated once per search, no error estimate, no refinement, no
//! stage 2, no deviation. A trial is never an answer: the search's winner
//! is solved again by stage 1 with every check (`merge`), and a trial
//! whose factor is singular or whose values are not finite returns `None`
//! (the caller then uses the full stage-1 path for that `mu`).

use super::MergeMetric;
use super::orthogonal::gauss_legendre_unit;
use super::stage_one::PieceInput;
use crate::basis::binomial;

/// Value and slope of the metric at any `mu` (see the module).
pub(super) struct TrialSolver {
    m: usize,
    dim: usize,
    metric: MergeMetric,
    fix_ends: bool,
    /// `C(m, i)`, `i = 0..m`.
    binomials: Vec<f64>,
    /// `C(m - 1, i)`, `i = 0..m - 1`.
    binomials_1: Vec<f64>,
    /// Gauss-Legendre nodes and square roots of the weights (integral).
    nodes: Vec<f64>,
    roots: Vec<f64>,
    /// `b`, `rows x dim`, column-major (coordinate after coordinate).
    target: Vec<f64>,
    /// `P_0` and `Q_m` (fix ends).
    first: Vec<f64>,
    last: Vec<f64>,
    // Scratch, reused by every trial.
    samples: Vec<f64>,
    factor: Vec<f64>,
    rhs: Vec<f64>,
    diagonal: Vec<f64>,
    r: Vec<f64>,
    residual: Vec<f64>,
    row: Vec<f64>,
    hodograph: Vec<f64>,
}

impl TrialSolver {
    /// The solver for `pieces` (two, same degree and dimension, no kept
    /// curve, no keep points); `None` when the case is not one it covers
    /// (degree 0 with fix ends: the two end conditions are one unknown).
    pub(super) fn new(
        pieces: &[PieceInput<'_>],
        metric: MergeMetric,
        fix_ends: bool,
    ) -> Option<Self> {
        if pieces.len() != 2 || pieces.iter().any(|p| p.keep || !p.points.is_empty()) {
            return None;
        }
        let m = pieces[0].curve.degree();
        let dim = pieces[0].curve.dim();
        if (fix_ends && m < 1) || pieces[1].curve.degree() != m || pieces[1].curve.dim() != dim {
            return None;
        }
        let points = m + 1;
        let rows = 2 * points;
        let binomials = (0..=m).map(|i| binomial(m, i)).collect();
        let binomials_1 = (0..m).map(|i| binomial(m - 1, i)).collect();
        let mut target = vec![0.0; rows * dim];
        let (mut nodes, mut roots) = (Vec::new(), Vec::new());
        match metric {
            MergeMetric::Discrete => {
                for (j, piece) in pieces.iter().enumerate() {
                    for i in 0..points {
                        for c in 0..dim {
                            target[c * rows + j * points + i] = piece.curve.point(i)[c];
                        }
                    }
                }
            }
            MergeMetric::Integral => {
                let (u, w) = gauss_legendre_unit(points);
                roots = w.iter().map(|w| w.sqrt()).collect();
                let mut value = vec![0.0; dim];
                for (j, piece) in pieces.iter().enumerate() {
                    for k in 0..points {
                        piece.curve.eval_into(u[k], &mut value);
                        for c in 0..dim {
                            target[c * rows + j * points + k] = roots[k] * value[c];
                        }
                    }
                }
                nodes = u;
            }
        }
        Some(Self {
            m,
            dim,
            metric,
            fix_ends,
            binomials,
            binomials_1,
            nodes,
            roots,
            target,
            first: pieces[0].curve.point(0).to_vec(),
            last: pieces[1].curve.point(m).to_vec(),
            samples: vec![0.0; rows * points],
            factor: vec![0.0; rows * points],
            rhs: vec![0.0; rows * dim],
            diagonal: vec![0.0; points],
            r: vec![0.0; points * dim],
            residual: vec![0.0; rows * dim],
            row: vec![0.0; points],
            hodograph: vec![0.0; m.max(1) * dim],
        })
    }

    /// `(f(mu), f'(mu))`, or `None` when the least-squares factor is
    /// singular or a value is not finite.
    pub(super) fn evaluate(&mut self, mu: f64) -> Option<(f64, f64)> {
        let m = self.m;
        let dim = self.dim;
        let points = m + 1;
        let rows = 2 * points;
        self.fill_samples(mu);
        // The fixed columns (fix ends) move to the right-hand side.
        self.rhs.copy_from_slice(&self.target);
        let (c0, c1) = if self.fix_ends { (1, m) } else { (0, points) };
        if self.fix_ends {
            for c in 0..dim {
                let (p0, qm) = (self.first[c], self.last[c]);
                let rhs = &mut self.rhs[c * rows..(c + 1) * rows];
                let (col0, colm) = (
                    &self.samples[..rows],
                    &self.samples[m * rows..points * rows],
                );
                for i in 0..rows {
                    rhs[i] -= col0[i] * p0 + colm[i] * qm;
                }
            }
        }
        let free = c1 - c0;
        self.factor[..free * rows].copy_from_slice(&self.samples[c0 * rows..c1 * rows]);
        if !householder_solve(
            &mut self.factor[..free * rows],
            &mut self.rhs,
            &mut self.diagonal[..free],
            rows,
            free,
            dim,
        ) {
            return None;
        }
        // r: the fixed ends and the solution.
        for c in 0..dim {
            let r = &mut self.r[c * points..(c + 1) * points];
            r[c0..c1].copy_from_slice(&self.rhs[c * rows..c * rows + free]);
            if self.fix_ends {
                r[0] = self.first[c];
                r[m] = self.last[c];
            }
        }
        // Residual b - M r and the value.
        let mut value = 0.0;
        for c in 0..dim {
            let res = &mut self.residual[c * rows..(c + 1) * rows];
            res.copy_from_slice(&self.target[c * rows..(c + 1) * rows]);
            for k in 0..points {
                let rk = self.r[c * points + k];
                let column = &self.samples[k * rows..(k + 1) * rows];
                for i in 0..rows {
                    res[i] -= column[i] * rk;
                }
            }
            value += res.iter().map(|v| v * v).sum::<f64>();
        }
        let slope = -2.0 * self.derivative_dot_residual(mu);
        (value.is_finite() && slope.is_finite()).then_some((value, slope))
    }

    /// `M(mu)` into `samples` (column-major, `rows x (m + 1)`).
    fn fill_samples(&mut self, mu: f64) {
        let m = self.m;
        let points = m + 1;
        let rows = 2 * points;
        let a = &mut self.samples;
        match self.metric {
            MergeMetric::Discrete => {
                // Row i of the Bernstein triangle, B_k^i(mu), k = 0..i, in
                // `row`, raised one degree at a time; S_L row i is it, S_R
                // row m - i is it shifted by m - i.
                let s = 1.0 - mu;
                a.fill(0.0);
                let row = &mut self.row;
                row[0] = 1.0;
                for i in 0..points {
                    if i > 0 {
                        row[i] = mu * row[i - 1];
                        for k in (1..i).rev() {
                            row[k] = s * row[k] + mu * row[k - 1];
                        }
                        row[0] *= s;
                    }
                    for k in 0..=i {
                        a[k * rows + i] = row[k];
                        // S_R[m - i][k + m - i] = B_k^i(mu).
                        a[(k + m - i) * rows + points + m - i] = row[k];
                    }
                }
            }
            MergeMetric::Integral => {
                for (k, (&u, &root)) in self.nodes.iter().zip(&self.roots).enumerate() {
                    for (j, t) in [mu * u, mu + (1.0 - mu) * u].into_iter().enumerate() {
                        bernstein_values(&self.binomials, t, &mut self.row);
                        for (i, &b) in self.row.iter().enumerate() {
                            a[i * rows + j * points + k] = root * b;
                        }
                    }
                }
            }
        }
    }

    /// `<b - M r, M'(mu) r>` (see the module).
    fn derivative_dot_residual(&mut self, mu: f64) -> f64 {
        let m = self.m;
        if m == 0 {
            return 0.0;
        }
        let dim = self.dim;
        let points = m + 1;
        let rows = 2 * points;
        let scale = 1.0 / m as f64;
        let mut total = 0.0;
        for c in 0..dim {
            let r = &self.r[c * points..(c + 1) * points];
            let res = &self.residual[c * rows..(c + 1) * rows];
            // The hodograph R' (degree m - 1): m (r_(i+1) - r_i).
            let h = &mut self.hodograph[c * m..(c + 1) * m];
            for i in 0..m {
                h[i] = m as f64 * (r[i + 1] - r[i]);
            }
            match self.metric {
                MergeMetric::Discrete => {
                    // R' split at mu by de Casteljau: the left piece's
                    // point i - 1 weighs (i / m) into row i of the left
                    // half, the right piece's point i (m - i) / m into
                    // row i of the right half.
                    let s = 1.0 - mu;
                    let n = m - 1;
                    total += scale * (res[1] * h[0] + res[points + n] * h[n] * (m - n) as f64);
                    for level in 1..m {
                        for k in 0..m - level {
                            h[k] = s * h[k] + mu * h[k + 1];
                        }
                        // left[level] = h[0], right[n - level] = h[n - level].
                        total += scale
                            * ((level + 1) as f64 * res[level + 1] * h[0]
                                + (m - (n - level)) as f64
                                    * res[points + n - level]
                                    * h[n - level]);
                    }
                }
                MergeMetric::Integral => {
                    for (k, (&u, &root)) in self.nodes.iter().zip(&self.roots).enumerate() {
                        for (j, (t, weight)) in [(mu * u, u), (mu + (1.0 - mu) * u, 1.0 - u)]
                            .into_iter()
                            .enumerate()
                        {
                            bernstein_values(&self.binomials_1, t, &mut self.row[..m]);
                            let value: f64 =
                                self.row[..m].iter().zip(h.iter()).map(|(b, h)| b * h).sum();
                            total += res[j * points + k] * root * weight * value;
                        }
                    }
                }
            }
        }
        total
    }
}

/// `B_i^n(t)`, `i = 0..n` (`binomials` = `C(n, i)`), into `out` (product
/// form, as the orthogonal path's sample rows).
fn bernstein_values(binomials: &[f64], t: f64, out: &mut [f64]) {
    let s = 1.0 - t;
    let mut tp = 1.0;
    for (o, &b) in out.iter_mut().zip(binomials) {
        *o = b * tp;
        tp *= t;
    }
    let mut sp = 1.0;
    for o in out.iter_mut().rev() {
        *o *= sp;
        sp *= s;
    }
}

/// Householder QR of `a` (`rows x cols`, column-major, overwritten)
/// applied to `rhs` (`rows x dim`, column-major), then the back
/// substitution: the least-squares solution in the first `cols` entries of
/// every column of `rhs`. `false` when a pivot vanishes or is not finite.
fn householder_solve(
    a: &mut [f64],
    rhs: &mut [f64],
    diagonal: &mut [f64],
    rows: usize,
    cols: usize,
    dim: usize,
) -> bool {
    for k in 0..cols {
        let column = &a[k * rows..(k + 1) * rows];
        let norm = column[k..].iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return false;
        }
        let akk = column[k];
        let alpha = if akk > 0.0 { -norm } else { norm };
        // v = column[k..] - alpha e_1, stored in place; v^T v = 2 norm (norm + |akk|).
        a[k * rows + k] = akk - alpha;
        let beta = 1.0 / (norm * (norm + akk.abs()));
        diagonal[k] = alpha;
        let (before, after) = a.split_at_mut((k + 1) * rows);
        let v = &before[k * rows + k..(k + 1) * rows];
        for j in 0..cols - k - 1 {
            let target = &mut after[j * rows + k..(j + 1) * rows];
            reflect(v, target, beta);
        }
        for c in 0..dim {
            reflect(v, &mut rhs[c * rows + k..(c + 1) * rows], beta);
        }
    }
    for c in 0..dim {
        let y = &mut rhs[c * rows..c * rows + cols];
        for i in (0..cols).rev() {
            let mut sum = y[i];
            for j in i + 1..cols {
                sum -= a[j * rows + i] * y[j];
            }
            y[i] = sum / diagonal[i];
        }
        if y.iter().any(|v| !v.is_finite()) {
            return false;
        }
    }
    true
}

/// `x -= beta (v^T x) v`.
fn reflect(v: &[f64], x: &mut [f64], beta: f64) {
    let s = beta * v.iter().zip(x.iter()).map(|(a, b)| a * b).sum::<f64>();
    for (xi, vi) in x.iter_mut().zip(v) {
        *xi -= s * vi;
    }
}

#[cfg(test)]
mod tests {
    use super::super::stage_one::StageOneCheck;
    use super::super::{MergeOptions, PairProblem};
    use super::*;

    use crate::test_values::planar_curve as curve;

    /// The lean trial against stage 1's orthogonal path (nalgebra QR, two
    /// refinement steps, the slope from `orthogonal::sample_slopes`): the
    /// same value and slope at every degree 1..24, both metrics, with and
    /// without fix ends, over the search range.
    #[test]
    fn lean_trial_is_the_stage_one_value_and_slope() {
        let mut state = 11;
        for degree in (1..=24).step_by(1) {
            let (p, q) = (curve(&mut state, degree), curve(&mut state, degree));
            for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
                for fix_ends in [false, true] {
                    let options = MergeOptions {
                        metric,
                        fix_ends,
                        ..MergeOptions::default()
                    };
                    let problem = PairProblem::new(&p, &q, &options).unwrap();
                    let mut lean = TrialSolver::new(&problem.pieces, metric, fix_ends).unwrap();
                    for mu in [1e-3, 0.07, 0.3, 0.5, 0.61, 0.93, 1.0 - 1e-3] {
                        let Ok(reference) = problem.solve(mu, StageOneCheck::Trial) else {
                            continue;
                        };
                        let (value, slope) = lean.evaluate(mu).unwrap();
                        let context =
                            format!("degree {degree} {metric:?} fix ends {fix_ends} mu {mu}");
                        let v = reference.metric_value;
                        assert!(
                            (value - v).abs() <= 1e-10 * v + 1e-14,
                            "{context}: value {value} vs {v}"
                        );
                        let s = reference.slope.unwrap();
                        assert!(
                            (slope - s).abs() <= 1e-8 * (s.abs() + v) + 1e-12,
                            "{context}: slope {slope} vs {s}"
                        );
                    }
                }
            }
        }
    }
}
