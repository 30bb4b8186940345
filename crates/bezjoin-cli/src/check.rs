//! Independent continuity checks of the tool's results.
//!
//! The library reports its own residuals; the tool re-measures continuity
//! from the returned control points, by evaluating the derivatives on both
//! sides of every join in the chain's global parameter
//! ([`bezjoin_core::join_jumps`]), and prints both.

use bezjoin_core::BezierCurve;
pub use bezjoin_core::distance;
use bezjoin_core::{join_jumps, relative_jump};
use serde_json::{Value, json};

/// Relative derivative jump up to which a join counts as continuous of that
/// order when the tool states a *measured* continuity order.
pub const CONTINUITY_TOLERANCE: f64 = 1e-9;

/// The measured continuity at one join of a chain.
#[derive(Debug, Clone)]
pub struct JoinCheck {
    /// Which join, e.g. `"P|R"`.
    pub name: String,
    /// The order the operation promises (derivatives `0..=promised_order`).
    pub promised_order: usize,
    /// Relative jumps of derivatives `0..=min(degrees)` across the join.
    pub relative_jumps: Vec<f64>,
}

impl JoinCheck {
    /// Measure the join of `left` (global parameter interval `left_interval`)
    /// and `right` (interval `right_interval`).
    pub fn measure(
        name: impl Into<String>,
        left: &BezierCurve,
        left_interval: f64,
        right: &BezierCurve,
        right_interval: f64,
        promised_order: usize,
    ) -> Self {
        let max_order = left.degree().min(right.degree());
        JoinCheck {
            name: name.into(),
            promised_order,
            relative_jumps: join_jumps(left, left_interval, right, right_interval, max_order),
        }
    }

    /// Measure a join from the derivative rows of both sides (flat
    /// row-major, `dim` values per row as [`BezierCurve::eval_derivatives`]
    /// returns them; row `k` = `k`-th derivative in each side's own
    /// parameter), each side read in a global parameter where it spans
    /// `*_interval`.
    pub fn from_derivatives(
        name: impl Into<String>,
        dim: usize,
        left: &[f64],
        left_interval: f64,
        right: &[f64],
        right_interval: f64,
        promised_order: usize,
    ) -> Self {
        let orders = (left.len() / dim).min(right.len() / dim);
        let relative_jumps = (0..orders)
            .map(|k| {
                let sl = left_interval.powi(k as i32);
                let sr = right_interval.powi(k as i32);
                let a: Vec<f64> = row(left, dim, k).iter().map(|v| v / sl).collect();
                let b: Vec<f64> = row(right, dim, k).iter().map(|v| v / sr).collect();
                relative_jump(&a, &b)
            })
            .collect();
        JoinCheck {
            name: name.into(),
            promised_order,
            relative_jumps,
        }
    }

    /// Largest relative jump among the promised orders.
    pub fn worst_promised(&self) -> f64 {
        self.relative_jumps
            .iter()
            .take(self.promised_order + 1)
            .copied()
            .fold(0.0, f64::max)
    }

    /// Largest `k` with jumps of orders `0..=k` all within
    /// [`CONTINUITY_TOLERANCE`]; `None` if even the points differ.
    pub fn measured_order(&self) -> Option<usize> {
        self.relative_jumps
            .iter()
            .take_while(|j| **j <= CONTINUITY_TOLERANCE)
            .count()
            .checked_sub(1)
    }

    /// Short text: `P|R: C3 promised, C3 measured (worst jump 2.1e-16)`.
    pub fn describe(&self) -> String {
        let measured = match self.measured_order() {
            Some(k) => format!("C{k}"),
            None => "not even C0".into(),
        };
        format!(
            "{}: C{} promised, {} measured (worst relative jump {:.1e})",
            self.name,
            self.promised_order,
            measured,
            self.worst_promised()
        )
    }

    /// JSON form for results.
    pub fn to_json(&self) -> Value {
        json!({
            "join": self.name,
            "promised_order": self.promised_order,
            "measured_order": self.measured_order(),
            "relative_jumps": self.relative_jumps,
            "worst_promised_jump": self.worst_promised(),
        })
    }
}

/// Worst promised jump over several joins.
pub fn worst(checks: &[JoinCheck]) -> f64 {
    checks
        .iter()
        .map(JoinCheck::worst_promised)
        .fold(0.0, f64::max)
}

/// Row `k` (`dim` values) of flat row-major derivatives.
pub fn row(values: &[f64], dim: usize, k: usize) -> &[f64] {
    &values[k * dim..(k + 1) * dim]
}

/// A curve as JSON: `{"degree", "dim", "points": [[...], ...]}`.
pub fn curve_json(curve: &BezierCurve) -> Value {
    json!({
        "degree": curve.degree(),
        "dim": curve.dim(),
        "points": (0..curve.point_count()).map(|i| curve.point(i).to_vec()).collect::<Vec<_>>(),
    })
}

#[cfg(test)]
mod join_check_tests {
    use super::*;

    #[test]
    fn split_halves_measure_full_continuity_and_a_kink_does_not() {
        let c = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap();
        let (a, b) = c.split_at(0.25).unwrap();
        let check = JoinCheck::measure("a|b", &a, 0.25, &b, 0.75, 3);
        assert_eq!(check.measured_order(), Some(3));
        assert!(check.worst_promised() < 1e-13);
        // Same pieces read with equal intervals: C0 only (speeds differ).
        let check = JoinCheck::measure("a|b", &a, 0.5, &b, 0.5, 3);
        assert_eq!(check.measured_order(), Some(0));
        assert!(check.worst_promised() > 0.1);
    }
}
