//! The fairness energy and the automatic scale ([`super::ShapeScale::Auto`]).

use super::{Connection, Problem, solve_structured};
use crate::basis::binomial;
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};
use crate::minimize::minimize_on_grid_then_brent;

/// Decades of `s` searched on either side of the natural scale `s0`.
pub const AUTO_SCALE_SEARCH_DECADES: f64 = 2.0;

/// Grid points of the coarse search (then refinement by Brent's method,
/// [`crate::minimize`]).
const GRID_POINTS: usize = 33;

/// The refinement stops when the bracket around the best `log s` is about
/// this wide (a relative change of `s` of 1e-9).
const LOG_SCALE_TOLERANCE: f64 = 1e-9;

/// At most this many refinement evaluations after the grid.
const REFINEMENT_STEPS: usize = 60;

/// `integral_0^1 |R''(t)|^2 dt`, exactly (up to rounding): the second
/// hodograph `h` (degree `m = n - 2`, `h_i = n (n-1) (R_(i+2) - 2 R_(i+1) + R_i)`)
/// against the Bernstein Gram matrix
/// `G_ij = integral B_i^m B_j^m = C(m,i) C(m,j) / ((2m+1) C(2m, i+j))`:
/// `E = sum_c h_c^T G h_c`. Zero for degrees below 2.
pub fn fairness_energy(curve: &BezierCurve) -> f64 {
    let n = curve.degree();
    if n < 2 {
        return 0.0;
    }
    let d = curve.dim();
    let m = n - 2;
    let factor = (n * (n - 1)) as f64;
    let second: Vec<f64> = (0..=m)
        .flat_map(|i| {
            let (a, b, c) = (curve.point(i), curve.point(i + 1), curve.point(i + 2));
            (0..d)
                .map(|k| factor * (c[k] - 2.0 * b[k] + a[k]))
                .collect::<Vec<_>>()
        })
        .collect();
    let mut energy = 0.0;
    for i in 0..=m {
        for j in 0..=m {
            let gram =
                binomial(m, i) * binomial(m, j) / ((2 * m + 1) as f64 * binomial(2 * m, i + j));
            let dot: f64 = (0..d).map(|k| second[i * d + k] * second[j * d + k]).sum();
            energy += gram * dot;
        }
    }
    energy
}

/// `s0 = |Q(v0) - P(u0)| / mean(|P'(u0)|, |Q'(v0)|)`, 1 when undefined.
pub(crate) fn natural_scale(problem: &Problem) -> f64 {
    let p = &problem.p_derivatives;
    let q = &problem.q_derivatives;
    let gap = (q.row(0) - p.row(0)).norm();
    let mut speeds = Vec::new();
    if p.nrows() > 1 {
        speeds.push(p.row(1).norm());
    }
    if q.nrows() > 1 {
        speeds.push(q.row(1).norm());
    }
    let speed = speeds.iter().sum::<f64>() / speeds.len().max(1) as f64;
    let s0 = gap / speed;
    if s0.is_finite() && s0 > 0.0 { s0 } else { 1.0 }
}

pub(crate) fn auto_scale(problem: &Problem) -> Result<Connection> {
    if problem.p_order == 0 && problem.q_order == 0 {
        return solve_structured(problem, 1.0, 1.0);
    }
    let center = natural_scale(problem).ln();
    let half_width = AUTO_SCALE_SEARCH_DECADES * std::f64::consts::LN_10;
    let (lo, hi) = (center - half_width, center + half_width);
    let energy_at = |log_s: f64| -> f64 {
        let s = log_s.exp();
        match solve_structured(problem, s, s) {
            Ok(c) => fairness_energy(&c.curve),
            Err(_) => f64::INFINITY,
        }
    };
    let Some(minimum) = minimize_on_grid_then_brent(
        energy_at,
        lo,
        hi,
        GRID_POINTS,
        LOG_SCALE_TOLERANCE,
        REFINEMENT_STEPS,
    ) else {
        // No scale in the range gives a trustworthy answer: report the one at s0.
        let s = center.exp();
        return solve_structured(problem, s, s);
    };
    let s = minimum.x.exp();
    let result = solve_structured(problem, s, s)?;
    if !result.curve.points().iter().all(|v| v.is_finite()) {
        return Err(BezjoinError::Singular {
            what: "connect_auto_scale".into(),
        });
    }
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_of_a_parabola_is_exact() {
        // R(t) = (t, t^2): R'' = (0, 2), energy 4; written as a cubic.
        let parabola = BezierCurve::from_rows(&[[0.0, 0.0], [0.5, 0.0], [1.0, 1.0]]).unwrap();
        assert!((fairness_energy(&parabola) - 4.0).abs() < 1e-13);
        let cubic = parabola.elevate_degree(5).unwrap();
        assert!((fairness_energy(&cubic) - 4.0).abs() < 1e-12);
    }
}
