//! Clamped polynomial B-spline curves, and chains of Bezier pieces as one
//! B-spline.
//!
//! The papers state their continuity promises for the chain
//! `P|[0,u0], R, Q|[v0,1]` read as ONE B-spline whose knot intervals are the
//! lengths of the pieces' parameter ranges (docs/mathematics.md#b-spline-chains).
//! [`BSplineCurve::from_bezier_chain`] builds exactly that curve (every
//! interior knot of full multiplicity, so it is the chain itself), and
//! [`BSplineCurve::eval_derivatives_side`] evaluates it from either side of a
//! knot with the same A2.3 basis routine as everything else: continuity is
//! judged by the derivatives of one curve, not by a formula of ours.

use crate::basis::{KnotSide, basis_derivatives, find_span};
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result, check_finite};

/// A clamped, non-rational B-spline curve.
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineCurve {
    degree: usize,
    dim: usize,
    knots: Vec<f64>,
    points: Vec<f64>,
}

impl BSplineCurve {
    /// A B-spline from its full knot vector and row-major control points.
    ///
    /// Requirements: `knots.len() == point_count + degree + 1`, knots
    /// non-decreasing and finite, first and last knots of multiplicity
    /// `degree + 1` (clamped), interior multiplicities at most `degree`.
    pub fn new(dim: usize, degree: usize, knots: Vec<f64>, points: Vec<f64>) -> Result<Self> {
        if dim == 0 {
            return Err(BezjoinError::invalid("dim", "must be at least 1"));
        }
        check_finite("knots", &knots)?;
        check_finite("points", &points)?;
        let Some(order) = degree.checked_add(1) else {
            return Err(BezjoinError::invalid(
                "degree",
                format!("{degree} is too large"),
            ));
        };
        if points.len() % dim != 0 || points.len() / dim < order {
            return Err(BezjoinError::invalid(
                "points",
                format!(
                    "{} values do not make at least {} points of dimension {dim}",
                    points.len(),
                    degree + 1
                ),
            ));
        }
        let count = points.len() / dim;
        if knots.len() != count + degree + 1 {
            return Err(BezjoinError::LengthMismatch {
                name: "knots".into(),
                expected: count + degree + 1,
                actual: knots.len(),
            });
        }
        if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(BezjoinError::invalid(
                "knots",
                format!("decrease at index {}", i + 1),
            ));
        }
        // The basis (A2.2/A2.3) divides by knot differences: a non-zero one
        // whose reciprocal overflows (a subnormal interval, e.g. a chain
        // piece of length 5e-324) makes `0 * inf = NaN` of the values.
        if let Some(i) = knots
            .windows(2)
            .position(|w| w[1] > w[0] && !(1.0 / (w[1] - w[0])).is_finite())
        {
            return Err(BezjoinError::invalid(
                "knots",
                format!(
                    "the interval [{}, {}] at index {} is too short: its length {:e} has no \
                     finite reciprocal",
                    knots[i],
                    knots[i + 1],
                    i + 1,
                    knots[i + 1] - knots[i]
                ),
            ));
        }
        let (distinct, mults) = distinct_with_multiplicities(&knots);
        if distinct.len() < 2 || mults[0] != degree + 1 || *mults.last().unwrap() != degree + 1 {
            return Err(BezjoinError::invalid(
                "knots",
                "must be clamped (end multiplicities degree + 1)",
            ));
        }
        if let Some(i) = mults[1..mults.len() - 1].iter().position(|&m| m > degree) {
            return Err(BezjoinError::invalid(
                "knots",
                format!(
                    "interior knot {} has multiplicity {} > degree {degree}",
                    distinct[i + 1],
                    mults[i + 1]
                ),
            ));
        }
        Ok(Self {
            degree,
            dim,
            knots,
            points,
        })
    }

    /// The chain of Bezier `pieces` as one B-spline; piece `i` occupies a
    /// parameter interval of length `intervals[i] > 0`, starting at 0.
    ///
    /// Pieces of lower degree are elevated to the highest degree (exact);
    /// every interior knot gets multiplicity equal to the degree, so the
    /// result equals the chain with no approximation. Consecutive pieces
    /// must share their end points to within `1e-12` of the coordinate
    /// scale (otherwise InvalidArgument, naming the join).
    pub fn from_bezier_chain(pieces: &[BezierCurve], intervals: &[f64]) -> Result<Self> {
        if pieces.is_empty() {
            return Err(BezjoinError::invalid(
                "pieces",
                "at least one piece is needed",
            ));
        }
        if intervals.len() != pieces.len() {
            return Err(BezjoinError::LengthMismatch {
                name: "intervals".into(),
                expected: pieces.len(),
                actual: intervals.len(),
            });
        }
        check_finite("intervals", intervals)?;
        if let Some(i) = intervals.iter().position(|&h| h <= 0.0) {
            return Err(BezjoinError::out_of_range(
                format!("intervals[{i}]"),
                intervals[i],
                "> 0",
            ));
        }
        let dim = pieces[0].dim();
        if let Some(i) = pieces.iter().position(|p| p.dim() != dim) {
            return Err(BezjoinError::DimensionMismatch {
                name: format!("pieces[{i}]"),
                expected: dim,
                actual: pieces[i].dim(),
            });
        }
        let degree = pieces.iter().map(BezierCurve::degree).max().unwrap().max(1);
        let elevated: Vec<BezierCurve> = pieces
            .iter()
            .map(|p| p.elevate_degree(degree))
            .collect::<Result<_>>()?;
        let scale = elevated
            .iter()
            .map(BezierCurve::coordinate_scale)
            .fold(1.0, f64::max);
        let mut points: Vec<f64> = Vec::new();
        let mut knots = vec![0.0; degree + 1];
        let mut x = 0.0;
        for (i, piece) in elevated.iter().enumerate() {
            if i == 0 {
                points.extend_from_slice(piece.points());
            } else {
                let prev_end = &points[points.len() - dim..];
                let gap = crate::bezier::distance(prev_end, piece.point(0));
                if gap > 1e-12 * scale {
                    return Err(BezjoinError::invalid(
                        format!("pieces[{i}]"),
                        format!("starts {gap:e} away from the end of piece {}", i - 1),
                    ));
                }
                points.extend_from_slice(&piece.points()[dim..]);
            }
            x += intervals[i];
            let mult = if i + 1 == elevated.len() {
                degree + 1
            } else {
                degree
            };
            knots.extend(std::iter::repeat_n(x, mult));
        }
        Self::new(dim, degree, knots, points)
    }

    /// Degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The full knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Row-major control points.
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// Number of control points.
    pub fn point_count(&self) -> usize {
        self.points.len() / self.dim
    }

    /// Distinct knots and their multiplicities (the form OpenCASCADE's
    /// `Geom_BSplineCurve` takes).
    pub fn knots_with_multiplicities(&self) -> (Vec<f64>, Vec<usize>) {
        distinct_with_multiplicities(&self.knots)
    }

    /// Value and derivatives `0..=max_order` at `t`, taken from the span on
    /// `side` of `t` when `t` is a knot; row-major, `(max_order + 1) * dim`
    /// values (row `k` is the `k`-th derivative).
    pub fn eval_derivatives_side(&self, t: f64, max_order: usize, side: KnotSide) -> Vec<f64> {
        let p = self.degree;
        let span = find_span(&self.knots, p, t, side);
        let basis = basis_derivatives(&self.knots, p, span, t, max_order);
        let d = self.dim;
        let mut out = vec![0.0; (max_order + 1) * d];
        for k in 0..=max_order {
            for j in 0..=p {
                let b = basis[(k, j)];
                let row = span - p + j;
                for c in 0..d {
                    out[k * d + c] += b * self.points[row * d + c];
                }
            }
        }
        out
    }

    /// Value and derivatives at `t` (from the right at a knot).
    pub fn eval_derivatives(&self, t: f64, max_order: usize) -> Vec<f64> {
        self.eval_derivatives_side(t, max_order, KnotSide::Right)
    }

    /// Largest `k` such that derivatives `0..=k` from both sides of the knot
    /// at `t` agree to `relative_tolerance` (relative to the larger of the
    /// two derivative norms and 1e-300), up to the degree; `None` if even the
    /// values differ.
    pub fn continuity_at(&self, t: f64, relative_tolerance: f64) -> Option<usize> {
        let left = self.eval_derivatives_side(t, self.degree, KnotSide::Left);
        let right = self.eval_derivatives_side(t, self.degree, KnotSide::Right);
        let mut order = None;
        for k in 0..=self.degree {
            if relative_jump(
                &left[k * self.dim..(k + 1) * self.dim],
                &right[k * self.dim..(k + 1) * self.dim],
            ) > relative_tolerance
            {
                break;
            }
            order = Some(k);
        }
        order
    }
}

/// `|a - b| / max(|a|, |b|)`, 0 when both vanish.
pub fn relative_jump(a: &[f64], b: &[f64]) -> f64 {
    let diff = crate::bezier::distance(a, b);
    let size = crate::bezier::norm(a).max(crate::bezier::norm(b));
    if size == 0.0 { 0.0 } else { diff / size }
}

/// Distinct values of a sorted knot vector and how often each occurs.
pub(crate) fn distinct_with_multiplicities(knots: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut distinct = Vec::new();
    let mut mults: Vec<usize> = Vec::new();
    for &k in knots {
        if distinct.last() == Some(&k) {
            *mults.last_mut().unwrap() += 1;
        } else {
            distinct.push(k);
            mults.push(1);
        }
    }
    (distinct, mults)
}

/// Relative jumps of the derivatives `0..=max_order` across the join of two
/// Bezier pieces, each read in a global parameter where `left` spans an
/// interval of length `left_interval` and `right` one of `right_interval`:
/// entry `k` is `|L^(k)(1)/hl^k - R^(k)(0)/hr^k|` relative to the larger norm.
pub fn join_jumps(
    left: &BezierCurve,
    left_interval: f64,
    right: &BezierCurve,
    right_interval: f64,
    max_order: usize,
) -> Vec<f64> {
    let d = left.dim();
    let l = left.eval_derivatives(1.0, max_order);
    let r = right.eval_derivatives(0.0, max_order);
    (0..=max_order)
        .map(|k| {
            let sl = left_interval.powi(k as i32);
            let sr = right_interval.powi(k as i32);
            let a: Vec<f64> = l[k * d..(k + 1) * d].iter().map(|v| v / sl).collect();
            let b: Vec<f64> = r[k * d..(k + 1) * d].iter().map(|v| v / sr).collect();
            relative_jump(&a, &b)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_curve_is_c_infinity_as_a_chain() {
        let c =
            BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [5.0, 1.0]])
                .unwrap();
        let (a, b) = c.split_at(0.3).unwrap();
        let s = BSplineCurve::from_bezier_chain(&[a, b], &[0.3, 0.7]).unwrap();
        assert_eq!(s.continuity_at(0.3, 1e-12), Some(4));
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let v = s.eval_derivatives(t, 0);
            let w = c.eval(t);
            assert!((v[0] - w[0]).abs() < 1e-13 && (v[1] - w[1]).abs() < 1e-13);
        }
    }

    #[test]
    fn a_kink_is_c0_only() {
        let a = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 0.0]]).unwrap();
        let b = BezierCurve::from_rows(&[[1.0, 0.0], [1.0, 1.0]]).unwrap();
        let s = BSplineCurve::from_bezier_chain(&[a, b], &[1.0, 1.0]).unwrap();
        assert_eq!(s.continuity_at(1.0, 1e-12), Some(0));
        let (k, m) = s.knots_with_multiplicities();
        assert_eq!(k, vec![0.0, 1.0, 2.0]);
        assert_eq!(m, vec![2, 1, 2]);
    }
}

#[cfg(test)]
mod degenerate_input_tests {
    use super::*;

    #[test]
    fn new_rejects_an_impossible_degree_without_panicking() {
        for degree in [usize::MAX, usize::MAX - 1] {
            let r = BSplineCurve::new(1, degree, vec![0.0, 1.0], vec![0.0, 1.0]);
            assert!(
                matches!(&r, Err(BezjoinError::InvalidArgument { name, .. }) if name == "degree" || name == "points"),
                "{r:?}"
            );
        }
    }

    #[test]
    fn continuity_at_a_smooth_join_of_curves_with_vanishing_derivatives() {
        // A straight line split at 0.5: all derivatives above the first
        // vanish on both sides, so the chain is C^degree at the join.
        let c = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]]).unwrap();
        let (a, b) = c.split_at(0.5).unwrap();
        let s = BSplineCurve::from_bezier_chain(&[a, b], &[0.5, 0.5]).unwrap();
        assert_eq!(s.continuity_at(0.5, 1e-12), Some(3));
        // A point that is not a knot is inside one polynomial piece.
        assert_eq!(s.continuity_at(0.25, 1e-12), Some(3));
    }
}
