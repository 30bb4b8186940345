//! Independent continuity checks of the tool's results.
//!
//! The library reports its own residuals; the tool re-measures continuity
//! from the returned curves, by evaluating the derivatives on both sides of
//! every join (the left piece's from the left of its last parameter, the
//! right piece's from the right of its first, so a knot of a NURBS piece is
//! read from the side that meets the join) in the chain's global parameter,
//! and prints both.

pub use bezjoin_core::distance;
use bezjoin_core::{CurveRef, KnotSide};
use serde_json::{Value, json};

use crate::series::arc_length_derivatives;

/// Relative derivative jump up to which a join counts as continuous of that
/// order when the tool states a *measured* continuity order.
pub const CONTINUITY_TOLERANCE: f64 = 1e-9;

/// Samples per piece for [`reference_sizes`].
const REFERENCE_SAMPLES: usize = 16;

/// The measured continuity at one join of a chain.
#[derive(Debug, Clone)]
pub struct JoinCheck {
    /// Which join, e.g. `"P|R"`.
    pub name: String,
    /// The order the operation promises (derivatives `0..=promised_order`).
    pub promised_order: usize,
    /// Relative jumps of derivatives `0..` across the join: `|L^(k) -
    /// R^(k)|` over the largest of `|L^(k)|`, `|R^(k)|` and the reference
    /// size of order `k` ([`reference_sizes`]), in the global parameter
    /// (for a geometric check: derivatives with respect to arc length).
    pub relative_jumps: Vec<f64>,
    /// Geometric continuity (G^k: derivatives with respect to arc length,
    /// [`JoinCheck::geometric`]) instead of parametric (C^k).
    pub geometric: bool,
}

/// One side of a join: derivative rows `0..` (flat row-major, `dim` values
/// per row, in the piece's own parameter) and `rate`, the piece's knot
/// interval per unit of its own parameter (row `k` is divided by
/// `rate^k` to read it in the chain's global parameter).
#[derive(Debug, Clone, Copy)]
pub struct Side<'a> {
    /// Derivative rows at the join.
    pub derivatives: &'a [f64],
    /// Knot interval per unit of the piece's parameter.
    pub rate: f64,
}

impl JoinCheck {
    /// Measure the join of `left` (its last parameter, derivatives from the
    /// left) and `right` (its first, from the right), Bezier or NURBS
    /// pieces, read in a global parameter where `left` spans an interval of
    /// length `left_interval` and `right` one of `right_interval`: the
    /// `k`-th derivative of a piece with domain length `L` spanning `h` is
    /// divided by `(h / L)^k`. Orders `0..=max(promised, min(degrees))` are
    /// measured, relative to the sizes of both pieces' derivatives.
    pub fn measure<'a, 'b>(
        name: impl Into<String>,
        left: impl Into<CurveRef<'a>>,
        left_interval: f64,
        right: impl Into<CurveRef<'b>>,
        right_interval: f64,
        promised_order: usize,
    ) -> Self {
        let (left, right) = (left.into(), right.into());
        let orders = promised_order.max(left.degree().min(right.degree()));
        let (l0, l1) = left.domain();
        let (r0, r1) = right.domain();
        let (left_rate, right_rate) = (left_interval / (l1 - l0), right_interval / (r1 - r0));
        JoinCheck::from_derivatives(
            name,
            left.dim(),
            Side {
                derivatives: &derivatives(left, l1, orders, KnotSide::Left),
                rate: left_rate,
            },
            Side {
                derivatives: &derivatives(right, r0, orders, KnotSide::Right),
                rate: right_rate,
            },
            &reference_sizes(&[(left, left_rate), (right, right_rate)], orders),
            promised_order,
        )
    }

    /// Measure a join from the derivative rows of both sides; `reference[k]`
    /// (in the global parameter; missing entries count as 0) is the size
    /// below which a `k`-th derivative counts as small: a derivative that
    /// vanishes on both sides (a line's second) then measures its rounding
    /// error relative to the pieces, not a relative jump of 1.
    pub fn from_derivatives(
        name: impl Into<String>,
        dim: usize,
        left: Side,
        right: Side,
        reference: &[f64],
        promised_order: usize,
    ) -> Self {
        let orders = (left.derivatives.len() / dim).min(right.derivatives.len() / dim);
        let relative_jumps = (0..orders)
            .map(|k| {
                let sl = left.rate.powi(k as i32);
                let sr = right.rate.powi(k as i32);
                let a: Vec<f64> = row(left.derivatives, dim, k)
                    .iter()
                    .map(|v| v / sl)
                    .collect();
                let b: Vec<f64> = row(right.derivatives, dim, k)
                    .iter()
                    .map(|v| v / sr)
                    .collect();
                let size = norm(&a)
                    .max(norm(&b))
                    .max(reference.get(k).copied().unwrap_or(0.0));
                if size == 0.0 {
                    0.0
                } else {
                    distance(&a, &b) / size
                }
            })
            .collect();
        JoinCheck {
            name: name.into(),
            promised_order,
            relative_jumps,
            geometric: false,
        }
    }

    /// Measure geometric continuity G^k at a join: the derivatives with
    /// respect to arc length ([`arc_length_derivatives`]: point, unit
    /// tangent, curvature vector, its arc-length derivative, ...) of `left`
    /// at its parameter (from the left of a knot) against those of `right`
    /// at its parameter (from the right), orders `0..=promised_order + 1`
    /// (the order above the promise shows whether it happens to hold too),
    /// each relative to the larger side and to the largest norm of that
    /// order sampled on `reference` (so a curvature that vanishes on both
    /// sides, as on lines, is measured against the blend's curvature).
    pub fn geometric(
        name: impl Into<String>,
        (left, at_left): (CurveRef, f64),
        (right, at_right): (CurveRef, f64),
        reference: &[CurveRef],
        promised_order: usize,
    ) -> Self {
        let orders = promised_order + 1;
        let dim = left.dim();
        let jet = |curve: CurveRef, u: f64, side: KnotSide| {
            arc_length_derivatives(&derivatives(curve, u, orders, side), dim, orders)
                .unwrap_or_else(|| vec![f64::NAN; (orders + 1) * dim])
        };
        let a = jet(left, at_left, KnotSide::Left);
        let b = jet(right, at_right, KnotSide::Right);
        let sizes = geometric_reference_sizes(reference, orders);
        let mut check = JoinCheck::from_derivatives(
            name,
            dim,
            Side {
                derivatives: &a,
                rate: 1.0,
            },
            Side {
                derivatives: &b,
                rate: 1.0,
            },
            &sizes,
            promised_order,
        );
        // A side without a tangent (zero speed) is no G1 join.
        for j in check.relative_jumps.iter_mut() {
            if !j.is_finite() {
                *j = f64::INFINITY;
            }
        }
        check.geometric = true;
        check
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

    /// `C` for parametric, `G` for geometric continuity.
    fn letter(&self) -> char {
        if self.geometric { 'G' } else { 'C' }
    }

    /// Short text: `P|R: C3 promised, C3 measured (worst jump 2.1e-16)`
    /// (`G2 promised, G2 measured ...` for a geometric check).
    pub fn describe(&self) -> String {
        let letter = self.letter();
        let measured = match self.measured_order() {
            Some(k) => format!("{letter}{k}"),
            None => format!("not even {letter}0"),
        };
        format!(
            "{}: {letter}{} promised, {} measured (worst relative jump {:.1e})",
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
            "continuity": if self.geometric { "geometric" } else { "parametric" },
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

/// Reference sizes of the derivatives `0..=orders` at a join of `pieces`
/// (each with its knot interval per unit of its own parameter, as
/// [`Side::rate`]): entry `k` is the largest norm of a `k`-th derivative,
/// in the global parameter, sampled at `REFERENCE_SAMPLES + 1` parameters
/// of each piece.
pub fn reference_sizes(pieces: &[(CurveRef, f64)], orders: usize) -> Vec<f64> {
    let mut sizes = vec![0.0f64; orders + 1];
    for &(curve, rate) in pieces {
        for_each_sample(curve, orders, |d| {
            for (k, size) in sizes.iter_mut().enumerate() {
                let n = norm(row(d, curve.dim(), k)) / rate.powi(k as i32);
                if n.is_finite() {
                    *size = size.max(n);
                }
            }
        });
    }
    sizes
}

/// Reference sizes of the arc-length derivatives `0..=orders` of `curves`:
/// entry `k` is the largest norm of `d^k r / ds^k` sampled at
/// `REFERENCE_SAMPLES + 1` parameters of each curve (points of zero speed
/// are skipped).
pub fn geometric_reference_sizes(curves: &[CurveRef], orders: usize) -> Vec<f64> {
    let mut sizes = vec![0.0f64; orders + 1];
    for &curve in curves {
        let dim = curve.dim();
        for_each_sample(curve, orders, |d| {
            let Some(s) = arc_length_derivatives(d, dim, orders) else {
                return;
            };
            for (k, size) in sizes.iter_mut().enumerate() {
                let n = norm(row(&s, dim, k));
                if n.is_finite() {
                    *size = size.max(n);
                }
            }
        });
    }
    sizes
}

/// Call `f` with the derivatives `0..=orders` of `curve` at
/// `REFERENCE_SAMPLES + 1` evenly spaced parameters of its domain (from the
/// right, the last one from the left).
fn for_each_sample(curve: CurveRef, orders: usize, mut f: impl FnMut(&[f64])) {
    let (a, b) = curve.domain();
    for i in 0..=REFERENCE_SAMPLES {
        let u = a + (b - a) * i as f64 / REFERENCE_SAMPLES as f64;
        let side = if i == REFERENCE_SAMPLES {
            KnotSide::Left
        } else {
            KnotSide::Right
        };
        f(&derivatives(curve, u, orders, side));
    }
}

/// Euclidean norm.
fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Value and derivatives `0..=order` of `curve` at `u` (row-major, `dim`
/// values per row), from `side` at a knot of a NURBS curve.
pub fn derivatives(curve: CurveRef, u: f64, order: usize, side: KnotSide) -> Vec<f64> {
    match curve {
        CurveRef::Bezier(c) => c.eval_derivatives(u, order),
        CurveRef::Nurbs(c) => c.eval_derivatives_side(u, order, side),
    }
}

/// A curve as JSON, in the form jobs accept back: a Bezier curve as
/// `{"degree", "dim", "points": [[...], ...]}`, a NURBS curve as
/// `{"degree", "dim", "poles": [[...], ...], "knots": [flat], "weights":
/// [one per pole, 1 when polynomial], "domain": [first, last]}`.
pub fn curve_json<'a>(curve: impl Into<CurveRef<'a>>) -> Value {
    match curve.into() {
        CurveRef::Bezier(c) => json!({
            "degree": c.degree(),
            "dim": c.dim(),
            "points": (0..c.point_count()).map(|i| c.point(i).to_vec()).collect::<Vec<_>>(),
        }),
        CurveRef::Nurbs(c) => {
            let (first, last) = c.domain();
            json!({
                "degree": c.degree(),
                "dim": c.dim(),
                "poles": (0..c.point_count()).map(|i| c.point(i).to_vec()).collect::<Vec<_>>(),
                "knots": c.knots(),
                "weights": (0..c.point_count()).map(|i| c.weight(i)).collect::<Vec<_>>(),
                "domain": [first, last],
            })
        }
    }
}

#[cfg(test)]
mod join_check_tests {
    use super::*;
    use bezjoin_core::{BezierCurve, NurbsCurve, ellipse_arc};

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

    #[test]
    fn nurbs_pieces_are_measured_from_the_side_of_the_join() {
        // A circle split at a knot: both halves keep the original
        // parameters, so with intervals equal to their domain lengths the
        // join is C-infinity; a line after it is only G1 and C1 at best.
        let circle =
            ellipse_arc(2, &[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0, 2.0, 0.0, 3.0).unwrap();
        let (a, b) = circle.split_at(1.2).unwrap();
        let check = JoinCheck::measure("a|b", &a, 1.2, &b, 1.8, 4);
        assert_eq!(check.measured_order(), Some(4), "{check:?}");
        let end = circle.eval_derivatives(3.0, 1);
        let line = NurbsCurve::from_bezier(
            &BezierCurve::new(2, 1, vec![end[0], end[1], end[0] + end[2], end[1] + end[3]])
                .unwrap(),
        );
        let check = JoinCheck::measure("b|line", &b, 1.8, &line, 1.0, 2);
        assert_eq!(check.measured_order(), Some(1), "{check:?}");
    }

    #[test]
    fn geometric_check_reads_arc_length_derivatives() {
        // A circle split anywhere and read with any speeds is G-infinity; a
        // line leaving it along its tangent is G1 only (the curvature jumps).
        let circle =
            ellipse_arc(2, &[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0, 2.0, 0.0, 3.0).unwrap();
        let (a, b) = circle.split_at(1.2).unwrap();
        let (a, b) = (CurveRef::from(&a), CurveRef::from(&b));
        let check = JoinCheck::geometric("a|b", (a, 1.2), (b, 1.2), &[a, b], 3);
        assert_eq!(check.measured_order(), Some(4), "{check:?}");
        assert!(check.describe().contains("G3 promised, G4 measured"));
        let end = circle.eval_derivatives(3.0, 1);
        let line = BezierCurve::new(
            2,
            1,
            vec![end[0], end[1], end[0] + 5.0 * end[2], end[1] + 5.0 * end[3]],
        )
        .unwrap();
        let c = CurveRef::from(&circle);
        let l = CurveRef::from(&line);
        let check = JoinCheck::geometric("circle|line", (c, 3.0), (l, 0.0), &[c, l], 2);
        assert_eq!(check.measured_order(), Some(1), "{check:?}");
        assert!((check.relative_jumps[2] - 1.0).abs() < 1e-12);
        assert_eq!(check.to_json()["continuity"], "geometric");
    }

    #[test]
    fn nurbs_json_gives_poles_knots_weights_and_domain() {
        let arc =
            ellipse_arc(2, &[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, 1.0, 0.0, 1.0).unwrap();
        let v = curve_json(&arc);
        assert_eq!(v["degree"], 2);
        assert_eq!(v["poles"].as_array().unwrap().len(), 3);
        assert_eq!(v["knots"].as_array().unwrap().len(), 6);
        assert_eq!(v["weights"].as_array().unwrap().len(), 3);
        assert_eq!(v["domain"], json!([0.0, 1.0]));
    }
}
