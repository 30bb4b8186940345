//! Arc length of a NURBS curve and its inverse, span by span
//! (docs/mathematics.md#nurbs-curves).
//!
//! A polynomial span is a Bezier curve on `[u_i, u_(i+1)]`; arc length does
//! not depend on the (affine) parametrization, so its length is the Bezier
//! curve's ([`BezierCurve::arc_length`], adaptive Gauss-Legendre with cusp
//! cuts, docs/mathematics.md#arc-length) and so is its inverse. A rational
//! span's speed `|C'(u)|` (A4.2) is integrated by adaptive Gauss-Kronrod
//! (7/15 points): an interval is accepted when the two rules agree within
//! its share of the accuracy, otherwise both halves are refined, within a
//! budget of [`MAX_RATIONAL_EVALUATIONS`] speed evaluations; past it the
//! call is `IllConditioned` with the estimate. The inverse on a rational
//! span is Newton's method on `u` (derivative: the speed) safeguarded by
//! bisection.

use super::NurbsCurve;
use crate::arclength::DEFAULT_ARC_LENGTH_ACCURACY;
use crate::bezier::{BezierCurve, distance, norm};
use crate::error::{BezjoinError, Result, check_finite_scalar};

/// Speed evaluations one rational-span length may spend (about 1,000
/// Gauss-Kronrod panels: a smooth span needs a few dozen).
pub const MAX_RATIONAL_EVALUATIONS: usize = 1 << 14;

/// Bisection depth limit of the Gauss-Kronrod rule.
const MAX_DEPTH: u32 = 50;

// Gauss-Kronrod 15-point nodes (non-negative half, the last is 0) and
// weights, and the weights of the embedded 7-point Gauss rule on the odd
// nodes (QUADPACK's qk15).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// One span in the form its length is computed in.
enum SpanForm {
    /// Polynomial: the Bezier curve on local `t = (u - lo) / (hi - lo)`.
    Polynomial(BezierCurve),
    /// Rational: the one-span NURBS itself.
    Rational(NurbsCurve),
}

struct Span {
    lo: f64,
    hi: f64,
    form: SpanForm,
}

impl Span {
    fn local(&self, u: f64) -> f64 {
        ((u - self.lo) / (self.hi - self.lo)).clamp(0.0, 1.0)
    }

    fn global(&self, t: f64) -> f64 {
        (self.lo + t * (self.hi - self.lo)).clamp(self.lo, self.hi)
    }

    /// `int_a^b |C'|` for `lo <= a <= b <= hi`.
    fn length(&self, a: f64, b: f64, accuracy: f64) -> Result<f64> {
        if a == b {
            return Ok(0.0);
        }
        match &self.form {
            SpanForm::Polynomial(bez) => bez.arc_length(self.local(a), self.local(b), accuracy),
            SpanForm::Rational(span) => rational_length(span, a, b, accuracy),
        }
    }

    /// The parameter at arc length `length >= 0` from `start`, forwards or
    /// backwards, within the span (the caller knows it is there).
    fn param_at(&self, start: f64, length: f64, forward: bool, accuracy: f64) -> Result<f64> {
        match &self.form {
            SpanForm::Polynomial(bez) => {
                let signed = if forward { length } else { -length };
                let t = bez.param_at_length(self.local(start), signed, accuracy)?;
                Ok(self.global(t))
            }
            SpanForm::Rational(span) => {
                let (mut lo, mut hi) = if forward {
                    (start, self.hi)
                } else {
                    (self.lo, start)
                };
                // f(u) = signed length from start to u minus the target,
                // increasing in u.
                let target = if forward { length } else { -length };
                let f = |u: f64| -> Result<f64> {
                    let l = if u >= start {
                        rational_length(span, start, u, 0.25 * accuracy)?
                    } else {
                        -rational_length(span, u, start, 0.25 * accuracy)?
                    };
                    Ok(l - target)
                };
                let mut u = if forward {
                    start + 0.5 * (hi - start)
                } else {
                    start - 0.5 * (start - lo)
                };
                for _ in 0..200 {
                    let value = f(u)?;
                    if value.abs() <= 0.5 * accuracy {
                        return Ok(u);
                    }
                    if value > 0.0 {
                        hi = u;
                    } else {
                        lo = u;
                    }
                    let speed = rational_speed(span, u);
                    let newton = u - value / speed;
                    u = if speed > 0.0 && newton > lo && newton < hi {
                        newton
                    } else {
                        0.5 * (lo + hi)
                    };
                    if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs()).max(f64::MIN_POSITIVE)
                    {
                        return Ok(0.5 * (lo + hi));
                    }
                }
                Ok(u)
            }
        }
    }
}

fn rational_speed(span: &NurbsCurve, u: f64) -> f64 {
    let mut point = [0.0f64; 16];
    let mut tangent = [0.0f64; 16];
    let d = span.dim();
    if d <= point.len() {
        span.point_and_tangent(u, &mut point[..d], Some(&mut tangent[..d]));
        norm(&tangent[..d])
    } else {
        let (mut point, mut tangent) = (vec![0.0; d], vec![0.0; d]);
        span.point_and_tangent(u, &mut point, Some(&mut tangent));
        norm(&tangent)
    }
}

/// One Gauss-Kronrod panel: (Kronrod value, |Kronrod - Gauss|).
fn kronrod(span: &NurbsCurve, a: f64, b: f64, evaluations: &mut usize) -> (f64, f64) {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    let centre = rational_speed(span, mid);
    let mut k = WGK[7] * centre;
    let mut g = WG[3] * centre;
    for j in 0..7 {
        let dx = half * XGK[j];
        let pair = rational_speed(span, mid - dx) + rational_speed(span, mid + dx);
        k += WGK[j] * pair;
        if j % 2 == 1 {
            g += WG[j / 2] * pair;
        }
    }
    *evaluations += 15;
    (k * half, ((k - g) * half).abs())
}

/// `int_a^b |C'|` on a rational span, adaptive Gauss-Kronrod.
fn rational_length(span: &NurbsCurve, a: f64, b: f64, accuracy: f64) -> Result<f64> {
    let mut evaluations = 0usize;
    let mut total = 0.0;
    let mut unresolved = 0.0;
    let mut stack = vec![(a, b, accuracy, 0u32)];
    while let Some((lo, hi, tol, depth)) = stack.pop() {
        let (value, error) = kronrod(span, lo, hi, &mut evaluations);
        let floor = 16.0 * f64::EPSILON * value.abs();
        if error <= tol.max(floor) || depth >= MAX_DEPTH || evaluations >= MAX_RATIONAL_EVALUATIONS
        {
            if error > tol.max(floor) {
                unresolved += error;
            }
            total += value;
            continue;
        }
        let mid = 0.5 * (lo + hi);
        stack.push((mid, hi, 0.5 * tol, depth + 1));
        stack.push((lo, mid, 0.5 * tol, depth + 1));
    }
    if !total.is_finite() {
        return Err(BezjoinError::NonFiniteScalar {
            name: format!("arc length from u = {a} to u = {b} (the speed overflows f64)"),
            value: total,
        });
    }
    if unresolved > accuracy {
        let size = total.abs().max(f64::MIN_POSITIVE);
        return Err(BezjoinError::IllConditioned {
            what: format!("arc length of a rational span from u = {a} to u = {b}"),
            estimate: (unresolved + accuracy) / size,
            limit: accuracy / size,
        });
    }
    Ok(total)
}

impl NurbsCurve {
    /// [`param_at_length`](Self::param_at_length) of a clamped one-span
    /// polynomial curve on `[a, b]` by the Bezier kernel on its poles
    /// ([`BezierCurve::param_at_length`] in `t = (u - a) / (b - a)`): on
    /// `[0, 1]` exactly the Bezier computation. Elsewhere the maps
    /// `t0 = (start - a) / h` and `u = a + h t` (`h = b - a`) each move a
    /// parameter by at most `4 eps max(|a|, |b|)` (a few roundings of
    /// values below `2 max(|a|, |b|)`), so the length at the answer moves by
    /// at most `margin = 16 eps max(|a|, |b|) S / h`, `S = n max |P_i -
    /// P_(i-1)|` the hodograph hull's bound on `|dC/dt|`; the Bezier
    /// inversion then runs to `accuracy - margin`. `None` (the span-by-span
    /// path) for other curves, when the margin exceeds half the accuracy,
    /// and on any error (the span-by-span path then reports it in `u`).
    fn one_span_param_at_length(
        &self,
        start: f64,
        length: f64,
        accuracy: f64,
    ) -> Option<Result<f64>> {
        let bezier = self.one_span_bezier()?;
        let (a, b) = self.domain();
        // An error (a length longer than the curve, an inversion that
        // cannot reach its accuracy) is left to the span-by-span path, so
        // that its message names `u` on the curve's own domain.
        if a == 0.0 && b == 1.0 {
            return bezier.param_at_length(start, length, accuracy).ok().map(Ok);
        }
        let h = b - a;
        let n = self.degree as f64;
        let hull_speed = n
            * (1..self.point_count())
                .map(|i| distance(self.point(i - 1), self.point(i)))
                .fold(0.0f64, f64::max);
        let margin = 16.0 * f64::EPSILON * a.abs().max(b.abs()) * hull_speed / h;
        if margin.is_nan() || margin > 0.5 * accuracy {
            return None;
        }
        let t0 = ((start - a) / h).clamp(0.0, 1.0);
        let t = bezier.param_at_length(t0, length, accuracy - margin).ok()?;
        Some(Ok(self.domain_parameter(t)))
    }

    /// Length of the control polygon (poles).
    pub fn polygon_length(&self) -> f64 {
        (1..self.point_count())
            .map(|i| distance(self.point(i - 1), self.point(i)))
            .sum()
    }

    /// The absolute accuracy of [`arc_length_default`](Self::arc_length_default):
    /// [`DEFAULT_ARC_LENGTH_ACCURACY`] times the larger of 1 and the
    /// control polygon's length.
    pub fn default_length_accuracy(&self) -> f64 {
        DEFAULT_ARC_LENGTH_ACCURACY * self.polygon_length().max(1.0)
    }

    fn length_spans(&self) -> Vec<Span> {
        self.bezier_spans()
            .into_iter()
            .map(|s| {
                let (lo, hi) = s.domain();
                let form = match s.to_bezier() {
                    Some(b) => SpanForm::Polynomial(b),
                    None => SpanForm::Rational(s),
                };
                Span { lo, hi, form }
            })
            .collect()
    }

    /// Arc length from `a` to `b` (both in the domain; signed: negative
    /// when `b < a`) to the absolute `accuracy > 0` (or the rounding level
    /// of the length where that is larger), span by span (module
    /// documentation).
    pub fn arc_length(&self, a: f64, b: f64, accuracy: f64) -> Result<f64> {
        self.check_parameter("a", a)?;
        self.check_parameter("b", b)?;
        check_finite_scalar("accuracy", accuracy)?;
        if accuracy <= 0.0 {
            return Err(BezjoinError::out_of_range("accuracy", accuracy, "> 0"));
        }
        if a == b {
            return Ok(0.0);
        }
        if b < a {
            return Ok(-self.arc_length(b, a, accuracy)?);
        }
        let spans: Vec<Span> = self
            .length_spans()
            .into_iter()
            .filter(|s| s.hi > a && s.lo < b)
            .collect();
        let share = accuracy / spans.len() as f64;
        let mut total = 0.0;
        for s in &spans {
            total += s.length(a.max(s.lo), b.min(s.hi), share)?;
        }
        Ok(total)
    }

    /// [`arc_length`](Self::arc_length) to [`default_length_accuracy`](Self::default_length_accuracy).
    pub fn arc_length_default(&self, a: f64, b: f64) -> Result<f64> {
        self.arc_length(a, b, self.default_length_accuracy())
    }

    /// The parameter whose signed arc length from `start` (in the domain)
    /// is `length` (negative: backwards), the length at the answer within
    /// `accuracy`. A `length` longer than the curve from `start` to the end
    /// it runs towards is `InvalidArgument` naming both lengths.
    pub fn param_at_length(&self, start: f64, length: f64, accuracy: f64) -> Result<f64> {
        self.check_parameter("start", start)?;
        check_finite_scalar("length", length)?;
        if accuracy.is_nan() || accuracy <= 0.0 || !accuracy.is_finite() {
            return Err(BezjoinError::out_of_range("accuracy", accuracy, "> 0"));
        }
        if length == 0.0 {
            return Ok(start);
        }
        if let Some(t) = self.one_span_param_at_length(start, length, accuracy) {
            return t;
        }
        let forward = length > 0.0;
        let (first, last) = self.domain();
        let mut spans: Vec<Span> = self
            .length_spans()
            .into_iter()
            .filter(|s| if forward { s.hi > start } else { s.lo < start })
            .collect();
        if !forward {
            spans.reverse();
        }
        let share = 0.5 * accuracy / spans.len().max(1) as f64;
        let mut remaining = length.abs();
        let mut walked = 0.0;
        for s in &spans {
            let (from, to) = if forward {
                (start.max(s.lo), s.hi)
            } else {
                (start.min(s.hi), s.lo)
            };
            let piece = s.length(from.min(to), from.max(to), share)?;
            if remaining <= piece {
                return s.param_at(from, remaining, forward, 0.5 * accuracy);
            }
            remaining -= piece;
            walked += piece;
        }
        if remaining <= accuracy {
            return Ok(if forward { last } else { first });
        }
        Err(BezjoinError::invalid(
            "length",
            format!(
                "{} is longer than the arc length {walked} from u = {start} to the {} end u = {}",
                length.abs(),
                if forward { "last" } else { "first" },
                if forward { last } else { first }
            ),
        ))
    }
}
