//! **[beyond]** Rounding within a deviation bound (mathematics.md, section 2:
//! "a bound on the deviation from the sharp corner instead of a setback, as
//! CNC corner smoothing asks").
//!
//! # Definition
//! The *deviation* of a rounded corner is the distance from the sharp corner
//! point `X` (the crossing) to the blend curve `R`:
//!
//! ```text
//! deviation = min over t in [0, 1] of |R(t) - X|
//! ```
//!
//! i.e. how far the rounded path passes from the corner it replaces (the
//! trimmed pieces lie on the original curves, so only `R` deviates). Given
//! `eps > 0` and a ratio `rho = dq / dp` (1 = symmetric), the setbacks
//! `dp`, `dq = rho dp` are chosen so that `deviation = eps` to
//! `relative_deviation_accuracy * eps`.
//!
//! # Search
//! `g(dp) = deviation(dp) - eps` tends to `-eps` as `dp -> 0` (the blend
//! shrinks onto `X`). The search starts at `dp = eps / 2` and doubles `dp`
//! (halves it, if the first deviation is already above `eps`) until `g`
//! changes sign, never beyond the longest setbacks the curves allow,
//! `dp_max = (1 - 1e-9) min(len(P before X), len(Q after X) / rho)`; if the
//! deviation is still below `eps` there, that is an error. The root in the
//! bracket is then found by the Illinois variant of false position
//! (bisection when a step would leave the bracket), at most 100 steps.
//!
//! Monotonicity: for two lines the deviation is exactly proportional to the
//! setback; for curved corners it grows monotonically while the setbacks are
//! short against the curves (`tests/fillet.rs` checks sweeps of cubic
//! corners up to setbacks of about 1/8 of the curve length), but with the
//! paper's scales (`alpha = beta = 1`) and long setbacks it can turn
//! (measured: a C1 cubic corner whose deviation decreases beyond a setback
//! of 0.6 on curves about 3 long). Walking up from short setbacks makes the
//! search return the first bracketed root, i.e. the shortest setbacks on the
//! doubling grid that reach `eps`, whether or not the deviation turns later.

use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result, check_positive};
use crate::intersect::{intersect, project};

use super::{
    Fillet, FilletOptions, available_lengths, fillet_at_validated, first_crossing, validate_shape,
};

/// Default of [`DeviationFilletOptions::relative_deviation_accuracy`].
pub const DEFAULT_RELATIVE_DEVIATION_ACCURACY: f64 = 1e-9;

/// Options of [`fillet_within_deviation`].
#[derive(Debug, Clone, PartialEq)]
pub struct DeviationFilletOptions {
    /// `eps > 0`: the distance from the corner point to the blend.
    pub max_deviation: f64,
    /// `dq / dp > 0`; 1 (the default) is symmetric rounding.
    pub setback_ratio: f64,
    /// Orders, scales, accuracies and intersection options as in
    /// [`FilletOptions`] (its setbacks are ignored).
    pub shape: FilletOptions,
    /// The deviation meets `eps` to `relative_deviation_accuracy * eps`;
    /// default [`DEFAULT_RELATIVE_DEVIATION_ACCURACY`] (`1e-9`).
    pub relative_deviation_accuracy: f64,
}

impl DeviationFilletOptions {
    /// Symmetric rounding within `max_deviation`, orders `kp = kq = order`,
    /// scales 1.
    pub fn new(max_deviation: f64, order: usize) -> Self {
        Self {
            max_deviation,
            setback_ratio: 1.0,
            shape: FilletOptions::symmetric(1.0, order),
            relative_deviation_accuracy: DEFAULT_RELATIVE_DEVIATION_ACCURACY,
        }
    }

    /// The same options with setback ratio `dq / dp`.
    pub fn with_setback_ratio(mut self, ratio: f64) -> Self {
        self.setback_ratio = ratio;
        self
    }
}

/// A corner rounded within a deviation bound.
#[derive(Debug, Clone, PartialEq)]
pub struct DeviationFillet {
    /// The rounded corner.
    pub fillet: Fillet,
    /// The setback `dp` found.
    pub p_setback: f64,
    /// `dq = ratio * dp`.
    pub q_setback: f64,
    /// The achieved deviation `min_t |R(t) - X|`.
    pub deviation: f64,
    /// The `t` on the blend where it is attained.
    pub deviation_parameter: f64,
}

/// The closest point of `curve` to `point`: `(t, distance)`, the global
/// minimum over `[0, 1]` (every local minimum of a dense sampling,
/// `16 (n + 1)` intervals, is polished by Gauss-Newton and the best kept).
pub fn distance_to_curve(curve: &BezierCurve, point: &[f64]) -> (f64, f64) {
    let hodograph = curve.hodograph();
    let samples = 16 * (curve.degree() + 1);
    let mut buf = vec![0.0; curve.dim()];
    let dist: Vec<f64> = (0..=samples)
        .map(|i| {
            curve.eval_into(i as f64 / samples as f64, &mut buf);
            crate::bezier::distance(&buf, point)
        })
        .collect();
    let mut best = (0.0, f64::INFINITY);
    for i in 0..=samples {
        let left = if i > 0 { dist[i - 1] } else { f64::INFINITY };
        let right = if i < samples {
            dist[i + 1]
        } else {
            f64::INFINITY
        };
        if dist[i] <= left && dist[i] <= right {
            let start = i as f64 / samples as f64;
            let (t, d) = project(curve, &hodograph, point, Some(start));
            if d < best.1 {
                best = (t, d);
            }
        }
    }
    best
}

/// Round the corner at the first crossing of `p` and `q` so that the blend
/// passes at distance `max_deviation` from the corner point (module
/// documentation for the definition and the search).
///
/// Errors: as [`super::fillet`] for the curves, orders and scales;
/// `max_deviation` or `setback_ratio` non-finite or not positive; a bound that
/// even the longest possible setbacks do not reach (InvalidArgument naming
/// `max_deviation`, with the largest deviation possible).
///
/// ```
/// use bezjoin_core::BezierCurve;
/// use bezjoin_core::fillet::{DeviationFilletOptions, fillet_within_deviation};
/// let p = BezierCurve::from_rows(&[[-2.0, 0.0], [0.0, 0.0], [2.0, 0.0]]).unwrap();
/// let q = BezierCurve::from_rows(&[[0.0, -2.0], [0.0, 0.0], [0.0, 2.0]]).unwrap();
/// let r = fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(0.1, 2)).unwrap();
/// assert!((r.deviation - 0.1).abs() <= 1e-9 * 0.1);
/// ```
pub fn fillet_within_deviation(
    p: &BezierCurve,
    q: &BezierCurve,
    options: &DeviationFilletOptions,
) -> Result<DeviationFillet> {
    if q.dim() != p.dim() {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: p.dim(),
            actual: q.dim(),
        });
    }
    let eps = options.max_deviation;
    let ratio = options.setback_ratio;
    check_positive("max_deviation", eps)?;
    check_positive("setback_ratio", ratio)?;
    check_positive(
        "relative_deviation_accuracy",
        options.relative_deviation_accuracy,
    )?;
    validate_shape(p, q, &options.shape)?;
    let hits = intersect(p, q, &options.shape.intersect)?;
    let crossing = first_crossing(&hits)?;
    let corner = crossing.point.clone();
    let (before, after) = available_lengths(p, q, &crossing)?;
    let longest = (1.0 - 1e-9) * before.min(after / ratio);

    let attempt = |dp: f64| -> Result<DeviationFillet> {
        let mut shape = options.shape.clone();
        shape.p_setback = dp;
        shape.q_setback = ratio * dp;
        let fillet = fillet_at_validated(p, q, crossing.clone(), &shape)?;
        let (t, deviation) = distance_to_curve(&fillet.blend, &corner);
        Ok(DeviationFillet {
            fillet,
            p_setback: dp,
            q_setback: ratio * dp,
            deviation,
            deviation_parameter: t,
        })
    };
    let tolerance = options.relative_deviation_accuracy * eps;
    // Bracket the smallest root: walk up from a short setback by doubling
    // (or down by halving when the first one is already too deviant).
    let (mut lo, mut g_lo) = (0.0, -eps);
    let mut dp = (0.5 * eps).min(longest);
    let mut trial = attempt(dp)?;
    let mut g = trial.deviation - eps;
    if g.abs() <= tolerance {
        return Ok(trial);
    }
    if g < 0.0 {
        loop {
            lo = dp;
            g_lo = g;
            if dp >= longest {
                return Err(BezjoinError::invalid(
                    "max_deviation",
                    format!(
                        "{eps} cannot be reached: the longest setbacks possible (p_setback = {}, \
                         q_setback = {}) give a deviation of only {}",
                        trial.p_setback, trial.q_setback, trial.deviation
                    ),
                ));
            }
            dp = (2.0 * dp).min(longest);
            trial = attempt(dp)?;
            g = trial.deviation - eps;
            if g.abs() <= tolerance {
                return Ok(trial);
            }
            if g > 0.0 {
                break;
            }
        }
    } else {
        for _ in 0..60 {
            let shorter = 0.5 * dp;
            let t = attempt(shorter)?;
            let gs = t.deviation - eps;
            if gs.abs() <= tolerance {
                return Ok(t);
            }
            if gs < 0.0 {
                lo = shorter;
                g_lo = gs;
                break;
            }
            dp = shorter;
            trial = t;
            g = gs;
        }
    }
    let (mut hi, mut g_hi) = (dp, g);
    let mut best = trial;
    // Illinois false position on g(dp) = deviation - eps over [lo, hi].
    let mut side = 0i32;
    for _ in 0..100 {
        let mut dp = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        if !(dp > lo && dp < hi) {
            dp = 0.5 * (lo + hi);
        }
        let trial = attempt(dp)?;
        let g = trial.deviation - eps;
        if g.abs() < (best.deviation - eps).abs() {
            best = trial;
        }
        if g.abs() <= tolerance {
            return Ok(best);
        }
        if g < 0.0 {
            lo = dp;
            g_lo = g;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = dp;
            g_hi = g;
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
    }
    let miss = (best.deviation - eps).abs() / eps;
    if miss <= options.relative_deviation_accuracy {
        return Ok(best);
    }
    Err(BezjoinError::IllConditioned {
        what: format!(
            "deviation search: the closest deviation found is {} for max_deviation = {eps}",
            best.deviation
        ),
        estimate: miss,
        limit: options.relative_deviation_accuracy,
    })
}
