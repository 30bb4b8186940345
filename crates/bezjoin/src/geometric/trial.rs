//! The fair search's trial solves: the structured solve of
//! [`solve_with_shapes`](super::solve_with_shapes) with everything that does
//! not depend on the shape values prepared once (the condition rows, the
//! norms behind the targets' rounding bounds, the buffers), so a trial
//! costs the Bell polynomials, the targets and two triangular
//! substitutions, without allocating. The arithmetic is that of
//! `geometric_targets` and of connect's structured solve, operation for
//! operation, so a trial's control points are bit for bit those of
//! `solve_with_shapes` (unit test `trial_solves_equal_the_checked_solve`).

use nalgebra::DMatrix;

use crate::connect::{
    CONNECT_RESIDUAL_LIMIT, ConditionRows, Problem, SIGNED_BINOMIALS, check_residuals,
    condition_rows, solve_interior,
};

use super::MAX_GEOMETRIC_ORDER;

/// Reusable state of the trial solves of one problem.
pub(super) struct TrialSolver<'a> {
    problem: &'a Problem,
    /// Condition rows at unit scales (the shape values live in the
    /// targets), for the residual check and the interior block.
    conditions: ConditionRows,
    /// The same rows, row-major (`n + 1` entries each).
    rows: Vec<f64>,
    /// `P^(i)(u0)` and `Q^(i)(v0)`, row-major.
    p_jet: Vec<f64>,
    q_jet: Vec<f64>,
    /// Per end and derivative order `i`: `e_i + 4 eps |P^(i)|`, the
    /// rounding term of the targets' bound.
    p_terms: Vec<f64>,
    q_terms: Vec<f64>,
    bell: [[f64; MAX_GEOMETRIC_ORDER + 1]; MAX_GEOMETRIC_ORDER + 1],
    /// The end rows' targets, row-major.
    targets: Vec<f64>,
    /// Column-major copy of the points for the residual check.
    points: DMatrix<f64>,
    /// The solved control points, row-major (as [`crate::BezierCurve`]).
    row_major: Vec<f64>,
}

impl<'a> TrialSolver<'a> {
    pub(super) fn new(problem: &'a Problem) -> Self {
        let terms = |jet: &DMatrix<f64>, errors: &[f64]| -> Vec<f64> {
            (0..jet.nrows())
                .map(|i| errors[i] + 4.0 * f64::EPSILON * jet.row(i).norm())
                .collect()
        };
        let row_major = |m: &DMatrix<f64>| -> Vec<f64> {
            (0..m.nrows())
                .flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)]))
                .collect()
        };
        let conditions = condition_rows(problem, 1.0, 1.0);
        let ends = problem.p_order + problem.q_order + 2;
        Self {
            problem,
            rows: row_major(&conditions.rows.rows(0, ends).into_owned()),
            conditions,
            p_jet: row_major(&problem.p_derivatives),
            q_jet: row_major(&problem.q_derivatives),
            p_terms: terms(&problem.p_derivatives, &problem.p_derivative_error),
            q_terms: terms(&problem.q_derivatives, &problem.q_derivative_error),
            bell: [[0.0; MAX_GEOMETRIC_ORDER + 1]; MAX_GEOMETRIC_ORDER + 1],
            targets: vec![0.0; ends * problem.dim],
            points: DMatrix::zeros(problem.degree + 1, problem.dim),
            row_major: vec![0.0; (problem.degree + 1) * problem.dim],
        }
    }

    /// The stored blend's part of each end's condition
    /// ([`super::stored_condition`], and at orders 3 and more the larger
    /// [`super::stored_curvature_derivative_condition`]) on the targets of
    /// the last [`solve`](Self::solve): `(P's end, Q's end)`; `stored` is
    /// the blend's degree and its ends' largest coordinate.
    pub(super) fn stored_conditions(&self, chord: f64, stored: (usize, f64)) -> (f64, f64) {
        let dim = self.problem.dim;
        let (kp, kq) = (self.problem.p_order, self.problem.q_order);
        let rows = |first: usize, order: usize| -> Vec<&[f64]> {
            self.targets[first * dim..(first + order + 1) * dim]
                .chunks_exact(dim)
                .collect()
        };
        let end = |rows: Vec<&[f64]>, order: usize| {
            super::stored_condition(&rows, order, chord, stored).max(
                super::stored_curvature_derivative_condition(&rows, order, chord, stored),
            )
        };
        (end(rows(0, kp), kp), end(rows(kp + 1, kq), kq))
    }

    /// The targets of the beta-constraints of one end (the rows from
    /// `first`), as `geometric_targets` forms them (with scale 1,
    /// `condition_rows` takes them unchanged).
    fn set_end_targets(&mut self, at_q: bool, shape: &[f64]) {
        let dim = self.problem.dim;
        let (jet, first) = if at_q {
            (&self.q_jet, self.problem.p_order + 1)
        } else {
            (&self.p_jet, 0)
        };
        let k = jet.len() / dim - 1;
        self.bell = super::partial_bell_small(shape, k);
        let targets = &mut self.targets[first * dim..(first + k + 1) * dim];
        targets[..dim].copy_from_slice(&jet[..dim]);
        for j in 1..=k {
            let out = &mut targets[j * dim..(j + 1) * dim];
            out.fill(0.0);
            for i in 1..=j {
                let coefficient = self.bell[j][i];
                for (o, x) in out.iter_mut().zip(&jet[i * dim..(i + 1) * dim]) {
                    *o += coefficient * x;
                }
            }
        }
    }

    /// The targets' rounding bounds of one end, as `geometric_targets` and
    /// `condition_rows` at unit scale form them, into the condition rows
    /// (with the targets), for the residual check.
    fn set_end_bounds(&mut self, at_q: bool) {
        let problem = self.problem;
        let dim = problem.dim;
        let (errors, terms, first, k) = if at_q {
            (
                &problem.q_derivative_error,
                &self.q_terms,
                problem.p_order + 1,
                problem.q_order,
            )
        } else {
            (
                &problem.p_derivative_error,
                &self.p_terms,
                0,
                problem.p_order,
            )
        };
        let half_eps = f64::EPSILON / 2.0;
        for j in 0..=k {
            let r = first + j;
            let mut square = 0.0;
            for c in 0..dim {
                let v = self.targets[r * dim + c];
                self.conditions.targets[(r, c)] = v;
                square += v * v;
            }
            let mut bound = errors[0];
            if j > 0 {
                bound = 0.0;
                for (coefficient, term) in self.bell[j][1..=j].iter().zip(&terms[1..=j]) {
                    bound += coefficient.abs() * term;
                }
            }
            // condition_rows at scale 1: 1^j e_j + (j + 1) u |T_j|.
            self.conditions.target_errors[r] = bound + (j + 1) as f64 * half_eps * square.sqrt();
        }
    }

    /// The blend's control points (row-major) for the shape values, or
    /// `None` when the structured solve fails or, with `checked`, when
    /// connect's residual check would refuse them.
    pub(super) fn solve(
        &mut self,
        p_shape: &[f64],
        q_shape: &[f64],
        checked: bool,
    ) -> Option<&[f64]> {
        let problem = self.problem;
        let n = problem.degree;
        let n1 = n + 1;
        let (kp, kq, dim) = (problem.p_order, problem.q_order, problem.dim);
        if checked {
            // The bounds need each end's Bell values: form the ends one
            // after the other.
            self.set_end_targets(false, p_shape);
            self.set_end_bounds(false);
            self.set_end_targets(true, q_shape);
            self.set_end_bounds(true);
        } else {
            self.set_end_targets(false, p_shape);
            self.set_end_targets(true, q_shape);
        }
        let rows = &self.rows;
        let targets = &self.targets;
        let points = &mut self.row_major;
        // connect's structured solve, operation for operation.
        for k in 0..=kp {
            let row = &rows[k * n1..(k + 1) * n1];
            let diagonal = row[k];
            let signed = &SIGNED_BINOMIALS[k];
            for c in 0..dim {
                let mut x = targets[k * dim + c] / diagonal;
                for i in 0..k {
                    x -= signed[i] * signed[k] * points[i * dim + c];
                }
                points[k * dim + c] = x;
            }
        }
        for (k, signed) in SIGNED_BINOMIALS[..=kq].iter().enumerate() {
            let r = kp + 1 + k;
            let row = &rows[r * n1..(r + 1) * n1];
            let index = n - k;
            let diagonal = row[index];
            for c in 0..dim {
                let mut x = targets[r * dim + c] / diagonal;
                for i in index + 1..=n {
                    x -= signed[i - index] * signed[0] * points[i * dim + c];
                }
                points[index * dim + c] = x;
            }
        }
        let m = problem.middle_count();
        if m > 0 || checked {
            for i in 0..n1 {
                for c in 0..dim {
                    self.points[(i, c)] = points[i * dim + c];
                }
            }
        }
        if m > 0 {
            solve_interior(&self.conditions, &mut self.points, kp, kq, m).ok()?;
            let first = kp + 1;
            for i in first..first + m {
                for c in 0..dim {
                    self.row_major[i * dim + c] = self.points[(i, c)];
                }
            }
        }
        if self.row_major.iter().any(|v| !v.is_finite()) {
            return None;
        }
        if checked {
            let (_, estimate) = check_residuals(problem, &self.conditions, &self.points);
            if !(estimate.is_finite() && estimate <= CONNECT_RESIDUAL_LIMIT) {
                return None;
            }
        }
        Some(&self.row_major)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bezier::BezierCurve;
    use crate::connect::{ConnectOptions, PointConstraint, prepare};
    use crate::geometric::solve_with_shapes;

    #[test]
    fn trial_solves_equal_the_checked_solve() {
        let p =
            BezierCurve::from_rows(&[[-1.0, -1.0], [-0.3, 0.2], [0.4, 0.5], [1.2, 0.3]]).unwrap();
        let q =
            BezierCurve::from_rows(&[[0.5, -1.2], [0.1, -0.2], [-0.1, 0.6], [0.3, 1.4]]).unwrap();
        for (kp, kq, constrained) in [(2, 2, false), (3, 1, false), (4, 4, false), (2, 3, true)] {
            let mut options = ConnectOptions::new(kp, kq);
            if constrained {
                options = options.with_constraint(PointConstraint::new(0.4, 0, vec![0.3, 0.1]));
            }
            let problem = prepare(&p, 0.8, &q, 0.3, &options).unwrap();
            let mut trial = TrialSolver::new(&problem);
            for s in [0.05, 0.3, 1.7] {
                let ps: Vec<f64> = (0..kp).map(|j| s * (1.0 - 0.4 * j as f64)).collect();
                let qs: Vec<f64> = (0..kq).map(|j| s * (0.8 + 0.3 * j as f64)).collect();
                let reference = solve_with_shapes(&problem, (0.8, 0.3), &ps, &qs).unwrap();
                let points = trial.solve(&ps, &qs, true).unwrap();
                assert_eq!(points, reference.curve.points(), "kp {kp} kq {kq} s {s}");
            }
        }
    }

    /// The search with unchecked trials finds what the checked one finds
    /// when no trial is refused.
    #[test]
    fn unchecked_search_equals_the_checked_search() {
        let p =
            BezierCurve::from_rows(&[[-1.0, -1.0], [-0.3, 0.2], [0.4, 0.5], [1.2, 0.3]]).unwrap();
        let q =
            BezierCurve::from_rows(&[[0.5, -1.2], [0.1, -0.2], [-0.1, 0.6], [0.3, 1.4]]).unwrap();
        let problem = prepare(&p, 0.8, &q, 0.3, &ConnectOptions::new(2, 2)).unwrap();
        let search =
            |checked| crate::geometric::fair::fair_shapes(&problem, None, None, checked).unwrap();
        assert_eq!(search(false), search(true));
    }
}
