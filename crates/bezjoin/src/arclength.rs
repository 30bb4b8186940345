//! Arc length of a Bezier curve and its inverse.
//!
//! `len(a, b) = int_a^b |P'(t)| dt` by adaptive Gauss-Legendre quadrature:
//! a 16-point rule on an interval is accepted when it agrees with the sum of
//! the same rule on both halves to within the interval's share of the
//! requested `accuracy`; otherwise both halves are refined. Straight lines
//! (constant speed polynomials of degree <= 31 in the integrand's square)
//! are exact at the first level.
//!
//! The inverse, [`BezierCurve::param_at_length`], solves
//! `len(start, t) = length` by Newton's method on `t` (derivative `|P'(t)|`)
//! safeguarded by bisection, so it converges even where the speed vanishes.

use crate::bezier::{BezierCurve, norm};
use crate::error::{BezjoinError, Result, check_finite_scalar};

/// Default absolute accuracy factor: lengths are computed to
/// `DEFAULT_ARC_LENGTH_ACCURACY * max(1, polygon length)`.
pub const DEFAULT_ARC_LENGTH_ACCURACY: f64 = 1e-13;

/// Maximum bisection depth of the adaptive quadrature.
const MAX_DEPTH: u32 = 40;

// 16-point Gauss-Legendre nodes (positive half) and weights on [-1, 1].
const GL_NODES: [f64; 8] = [
    0.095_012_509_837_637_44,
    0.281_603_550_779_258_9,
    0.458_016_777_657_227_4,
    0.617_876_244_402_643_8,
    0.755_404_408_355_003,
    0.865_631_202_387_831_7,
    0.944_575_023_073_232_6,
    0.989_400_934_991_649_9,
];
const GL_WEIGHTS: [f64; 8] = [
    0.189_450_610_455_068_5,
    0.182_603_415_044_923_6,
    0.169_156_519_395_002_5,
    0.149_595_988_816_576_7,
    0.124_628_971_255_533_9,
    0.095_158_511_682_492_78,
    0.062_253_523_938_647_89,
    0.027_152_459_411_754_095,
];

struct Speed<'a> {
    hodograph: &'a BezierCurve,
    buf: Vec<f64>,
}

impl Speed<'_> {
    fn at(&mut self, t: f64) -> f64 {
        self.hodograph.eval_into(t, &mut self.buf);
        norm(&self.buf)
    }

    fn gauss(&mut self, a: f64, b: f64) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        let mut sum = 0.0;
        for k in 0..8 {
            let dx = half * GL_NODES[k];
            sum += GL_WEIGHTS[k] * (self.at(mid - dx) + self.at(mid + dx));
        }
        sum * half
    }

    fn adaptive(&mut self, a: f64, b: f64, whole: f64, accuracy: f64, depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let left = self.gauss(a, m);
        let right = self.gauss(m, b);
        let refined = left + right;
        if (refined - whole).abs() <= accuracy || depth >= MAX_DEPTH {
            return refined;
        }
        self.adaptive(a, m, left, 0.5 * accuracy, depth + 1)
            + self.adaptive(m, b, right, 0.5 * accuracy, depth + 1)
    }
}

impl BezierCurve {
    /// Arc length between parameters `a` and `b` (signed: negative when
    /// `b < a`), to an absolute `accuracy > 0`. Any finite `a`, `b`.
    pub fn arc_length(&self, a: f64, b: f64, accuracy: f64) -> Result<f64> {
        check_finite_scalar("a", a)?;
        check_finite_scalar("b", b)?;
        check_finite_scalar("accuracy", accuracy)?;
        if accuracy <= 0.0 {
            return Err(BezjoinError::out_of_range("accuracy", accuracy, "> 0"));
        }
        if a == b || self.degree() == 0 {
            return Ok(0.0);
        }
        let hodograph = self.hodograph();
        Ok(arc_length_with(&hodograph, a, b, accuracy))
    }

    /// Arc length with the default accuracy
    /// ([`DEFAULT_ARC_LENGTH_ACCURACY`] times the larger of 1 and the control
    /// polygon's length).
    pub fn arc_length_default(&self, a: f64, b: f64) -> Result<f64> {
        self.arc_length(a, b, self.default_length_accuracy())
    }

    /// The absolute accuracy used by [`Self::arc_length_default`].
    pub fn default_length_accuracy(&self) -> f64 {
        DEFAULT_ARC_LENGTH_ACCURACY * self.polygon_length().max(1.0)
    }

    /// The parameter `t in [0, 1]` whose signed arc length from `start` is
    /// `length` (negative: backwards). `accuracy` bounds the error of the
    /// length at the returned parameter.
    ///
    /// Errors: `start` outside `[0, 1]`; `length` longer than the part of the
    /// curve between `start` and the end it runs towards (InvalidArgument,
    /// naming both lengths).
    pub fn param_at_length(&self, start: f64, length: f64, accuracy: f64) -> Result<f64> {
        crate::error::check_closed_range("start", start, 0.0, 1.0)?;
        check_finite_scalar("length", length)?;
        if accuracy.is_nan() || accuracy <= 0.0 || !accuracy.is_finite() {
            return Err(BezjoinError::out_of_range("accuracy", accuracy, "> 0"));
        }
        if length == 0.0 {
            return Ok(start);
        }
        let hodograph = self.hodograph();
        let end = if length > 0.0 { 1.0 } else { 0.0 };
        let available = arc_length_with(&hodograph, start, end, accuracy * 0.1);
        if length.abs() > available.abs() + accuracy {
            return Err(BezjoinError::invalid(
                "length",
                format!(
                    "{} is longer than the arc length {} from t = {start} to the {} end",
                    length.abs(),
                    available.abs(),
                    if length > 0.0 { "t = 1" } else { "t = 0" }
                ),
            ));
        }
        if length.abs() >= available.abs() {
            return Ok(end);
        }
        let mut speed = Speed {
            hodograph: &hodograph,
            buf: vec![0.0; self.dim()],
        };
        // Bracket [lo, hi] in the direction of travel; f(t) = len(start, t) - length.
        let (mut lo, mut hi) = if length > 0.0 {
            (start, 1.0)
        } else {
            (0.0, start)
        };
        // Initial guess: proportional.
        let mut t = start + (end - start) * (length / available);
        for _ in 0..100 {
            let len = arc_length_with(&hodograph, start, t, accuracy * 0.1);
            let f = len - length;
            if f.abs() <= accuracy {
                return Ok(t);
            }
            // len(start, t) increases with t.
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let v = speed.at(t);
            let newton = t - f / v;
            t = if v > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= f64::EPSILON * 4.0 {
                return Ok(t);
            }
        }
        Ok(t)
    }
}

pub(crate) fn arc_length_with(hodograph: &BezierCurve, a: f64, b: f64, accuracy: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    let mut speed = Speed {
        hodograph,
        buf: vec![0.0; hodograph.dim()],
    };
    let whole = speed.gauss(a, b);
    speed.adaptive(a, b, whole, accuracy, 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_line_is_exact() {
        let line =
            BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 1.0], [3.0, 3.0], [3.0, 4.0]]).unwrap();
        let _ = line;
        let l = BezierCurve::from_rows(&[[1.0, 2.0], [4.0, 6.0]]).unwrap();
        let len = l.arc_length(0.0, 1.0, 1e-14).unwrap();
        assert!((len - 5.0).abs() < 1e-14);
        assert!((l.arc_length(1.0, 0.25, 1e-14).unwrap() + 3.75).abs() < 1e-14);
    }

    #[test]
    fn quarter_circle_approximation_and_parabola() {
        // Parabola y = x^2 on [0, 1]: (t, t^2) as a quadratic Bezier.
        let p = BezierCurve::from_rows(&[[0.0, 0.0], [0.5, 0.0], [1.0, 1.0]]).unwrap();
        let exact = (2.0f64 * 5.0f64.sqrt() + (2.0 + 5.0f64.sqrt()).ln()) / 4.0;
        let len = p.arc_length(0.0, 1.0, 1e-13).unwrap();
        assert!((len - exact).abs() < 1e-12, "{len} vs {exact}");
    }

    #[test]
    fn inverse_round_trip() {
        let c = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap();
        for &t in &[0.1, 0.4, 0.77, 1.0] {
            let s = c.arc_length(0.2, t, 1e-13).unwrap();
            let back = c.param_at_length(0.2, s, 1e-12).unwrap();
            assert!((back - t).abs() < 1e-9, "{t} -> {s} -> {back}");
        }
        assert!(c.param_at_length(0.5, 100.0, 1e-12).is_err());
    }
}
