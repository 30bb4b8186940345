//! Decomposition into Bezier spans (The NURBS Book A5.6, as repeated knot
//! insertion) and degree elevation (the spans elevated, then the knots the
//! elevated curve does not need removed, each removal checked).

use super::knots::insert_once;
use super::{NurbsCurve, unit_weights_dropped};
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};

/// Relative size (to the largest homogeneous coordinate) above which a
/// knot removal that should be exact is refused as ill-conditioned.
const REMOVAL_TOLERANCE: f64 = 1e-10;

impl NurbsCurve {
    /// The distinct knot values inside the open domain, with their
    /// multiplicities.
    pub fn interior_knots(&self) -> (Vec<f64>, Vec<usize>) {
        let (first, last) = self.domain();
        let (k, m) = self.knots_with_multiplicities();
        k.into_iter()
            .zip(m)
            .filter(|(u, _)| *u > first && *u < last)
            .unzip()
    }

    /// Number of non-empty knot spans in the domain.
    pub fn span_count(&self) -> usize {
        self.interior_knots().0.len() + 1
    }

    /// The curve as its Bezier spans, in order: one-span curves of the same
    /// degree on `[u_i, u_(i+1)]` (the distinct knots of the domain), with
    /// the original parameters; rational spans stay rational. Exact.
    pub fn bezier_spans(&self) -> Vec<NurbsCurve> {
        let p = self.degree;
        let hd = self.dim + 1;
        let clamped = self.clamped();
        let (breaks, mults) = clamped.interior_knots();
        let mut h = clamped.homogeneous_points();
        let mut knots = clamped.knots.clone();
        for (&u, &m) in breaks.iter().zip(&mults) {
            for _ in m..p {
                insert_once(hd, p, &mut knots, &mut h, u);
            }
        }
        let (first, last) = self.domain();
        let mut ends = vec![first];
        ends.extend_from_slice(&breaks);
        ends.push(last);
        let rational = self.weights.is_some();
        ends.windows(2)
            .enumerate()
            .map(|(i, ab)| {
                let rows = &h[i * p * hd..(i * p + p + 1) * hd];
                let mut span =
                    NurbsCurve::from_homogeneous(self.dim, p, rows, Vec::new(), rational);
                let mut k = vec![ab[0]; p + 1];
                k.extend(std::iter::repeat_n(ab[1], p + 1));
                span.knots = k;
                span.weights = unit_weights_dropped(span.weights.take());
                span
            })
            .collect()
    }

    /// The Bezier curve of a clamped one-span polynomial curve, read from
    /// its poles (no knot work): the curve is this Bezier curve in the
    /// local parameter `t = (u - first) / (last - first)`. `None` for
    /// several spans, unclamped ends or unequal weights.
    pub(crate) fn one_span_bezier(&self) -> Option<BezierCurve> {
        if !self.is_bezier_span() || self.is_rational() {
            return None;
        }
        Some(BezierCurve::from_parts(
            self.dim,
            self.degree,
            self.points.clone(),
        ))
    }

    /// The parameter `a + (b - a) t` of the domain `[a, b]` for the local
    /// parameter `t` of [`one_span_bezier`](Self::one_span_bezier): the
    /// ends exact (`t <= 0` gives `a`, `t >= 1` gives `b`), clamped to the
    /// domain in between.
    pub(crate) fn domain_parameter(&self, t: f64) -> f64 {
        let (a, b) = self.domain();
        if t <= 0.0 {
            a
        } else if t >= 1.0 {
            b
        } else {
            (a + (b - a) * t).clamp(a, b)
        }
    }

    /// The curve as a Bezier curve on `[0, 1]` when it is one polynomial
    /// span (clamped, weights all equal); `None` otherwise.
    pub fn to_bezier(&self) -> Option<BezierCurve> {
        if self.span_count() != 1 || self.is_rational() {
            return None;
        }
        let c = self.clamped();
        BezierCurve::new(c.dim, c.degree, c.points.clone()).ok()
    }

    /// The same curve with degree `new_degree >= degree`: every span
    /// elevated, every knot's multiplicity raised by `new_degree - degree`
    /// (so the continuity at each knot is kept), ends clamped; exact.
    ///
    /// Errors: `new_degree` below the degree or above
    /// [`MAX_DEGREE`](crate::MAX_DEGREE); `IllConditioned` if a knot
    /// removal that is exact in exact arithmetic leaves an error above
    /// `1e-10` of the largest homogeneous coordinate.
    pub fn elevate_degree(&self, new_degree: usize) -> Result<NurbsCurve> {
        let p = self.degree;
        if new_degree < p {
            return Err(BezjoinError::invalid(
                "new_degree",
                format!(
                    "{new_degree} is below the curve's degree {p}; degree reduction is not exact"
                ),
            ));
        }
        if new_degree == p {
            return Ok(self.clone());
        }
        if new_degree > crate::bezier::MAX_DEGREE {
            return Err(BezjoinError::invalid(
                "new_degree",
                format!(
                    "{new_degree} is above the supported maximum {}",
                    crate::bezier::MAX_DEGREE
                ),
            ));
        }
        let q = new_degree;
        let hd = self.dim + 1;
        let spans = self.bezier_spans();
        let (breaks, mults) = self.interior_knots();
        let mut h: Vec<f64> = Vec::new();
        let (first, last) = self.domain();
        let mut knots = vec![first; q + 1];
        for (i, span) in spans.iter().enumerate() {
            let raised = BezierCurve::new(hd, p, span.homogeneous_points())?.elevate_degree(q)?;
            let skip = if i == 0 { 0 } else { hd };
            h.extend_from_slice(&raised.points()[skip..]);
            if i + 1 < spans.len() {
                knots.extend(std::iter::repeat_n(breaks[i], q));
            }
        }
        knots.extend(std::iter::repeat_n(last, q + 1));
        let scale = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut curve =
            NurbsCurve::from_homogeneous(self.dim, q, &h, knots, self.weights.is_some());
        for (&u, &m) in breaks.iter().zip(&mults) {
            for _ in m..p {
                let (reduced, error) = curve.remove_knot_once(u);
                if error.is_nan() || error > REMOVAL_TOLERANCE * scale {
                    return Err(BezjoinError::IllConditioned {
                        what: format!("degree elevation: removing the knot {u}"),
                        estimate: error / scale,
                        limit: REMOVAL_TOLERANCE,
                    });
                }
                curve = reduced;
            }
        }
        curve.weights = unit_weights_dropped(curve.weights.take());
        Ok(curve)
    }
}
