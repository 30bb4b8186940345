//! **\[beyond\]** Rounding within a deviation bound (docs/mathematics.md#fillet-deviation-bound:
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
//! `dp`, `dq = rho dp` are chosen so that the blend stays within `eps` of
//! the corner and uses nearly all of it.
//!
//! # Guarantee
//! With `a = relative_deviation_accuracy` (default `1e-9`), the returned
//! blend satisfies
//!
//! ```text
//! eps (1 - a) <= deviation <= eps (1 - a/4) < eps
//! ```
//!
//! with `deviation` as computed by [`distance_to_curve`] (the reported
//! [`DeviationFillet::deviation`]). The bound is one-sided: a blend whose
//! deviation is above `eps` is never returned, however close. The margin
//! `a/4 eps` below `eps` covers the rounding of the computed distance (about
//! `n` units in the last place of the coordinates, far below `a/4 eps` unless
//! `eps` is below about `1e-5` times the coordinate size with the default
//! `a`). When no setback on
//! the search's path gives a deviation in the window, the answer is an
//! IllConditioned error, not a blend outside it.
//!
//! # Search
//! `h(dp) = deviation(dp) - eps (1 - a/2)` (the middle of the window, the
//! search's target) tends to `-eps` as `dp -> 0` (the blend shrinks onto
//! `X`). The search starts at `dp = eps / 2` and doubles `dp` (halves it, if
//! the first deviation is already above the target) until `h` changes sign,
//! never beyond the longest setbacks the curves allow, `dp_max =
//! min(len(P before X) - 2e-9 len(P), (len(Q after X) - 2e-9 len(Q)) / rho)`
//! (twice the sliver a setback may not leave); if the deviation is still
//! below the window there, that is an error. The root in the bracket is then
//! found by the Illinois variant of false position (bisection when a step
//! would leave the bracket), at most 100 steps; the end of the bracket on
//! the short side always has a deviation below the window, and every trial
//! is returned only if its deviation lies in the window. The trials share
//! the two arc-length inversions from the crossing (the quadrature of each
//! curve is kept between trials; each trial's cut parameters are bit for
//! bit those of a fresh [`BezierCurve::param_at_length`]), and only the
//! returned trial has its trimmed pieces built.
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
use crate::curve::CurveRef;
use crate::error::{BezjoinError, Compact, Result, check_positive};
use crate::intersect::{intersect, project};

use super::{
    Blend, Fillet, FilletOptions, SetbackInverses, assemble, available_lengths, blend_at,
    fillet_at_validated, first_crossing, validate_shape,
};
use crate::connect::ShapeScale;

/// Default of [`DeviationFilletOptions::relative_deviation_accuracy`].
pub const DEFAULT_RELATIVE_DEVIATION_ACCURACY: f64 = 1e-9;

/// Options of [`fillet_within_deviation`].
#[derive(Debug, Clone, PartialEq)]
pub struct DeviationFilletOptions {
    /// `eps > 0`: the largest distance allowed from the corner point to the
    /// blend (module documentation: the result is in `[eps (1 - a), eps
    /// (1 - a/4)]`, `a` = [`Self::relative_deviation_accuracy`]).
    pub max_deviation: f64,
    /// `dq / dp > 0`; 1 (the default) is symmetric rounding.
    pub setback_ratio: f64,
    /// Orders, scales, accuracies and intersection options as in
    /// [`FilletOptions`] (its setbacks are ignored).
    pub shape: FilletOptions,
    /// `a > 0`: the deviation is at least `eps (1 - a)` (and never above
    /// `eps (1 - a/4)`); default [`DEFAULT_RELATIVE_DEVIATION_ACCURACY`]
    /// (`1e-9`).
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
    /// The achieved deviation `min_t |R(t) - X|`, in `[eps (1 - a), eps
    /// (1 - a/4)]`.
    pub deviation: f64,
    /// The `t` on the blend where it is attained.
    pub deviation_parameter: f64,
}

/// One setback tried by the deviation search: a [`DeviationFillet`] before
/// its trimmed pieces are built (only the accepted trial needs them).
struct Trial {
    blend: Blend,
    p_setback: f64,
    q_setback: f64,
    deviation: f64,
    deviation_parameter: f64,
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
/// passes within `max_deviation` of the corner point, and no closer than
/// `max_deviation (1 - relative_deviation_accuracy)` (module documentation
/// for the definition, the guarantee and the search).
///
/// `p`, `q`: Bezier or NURBS curves, as for [`super::fillet`] (NURBS pieces
/// keep their kind and parameters).
///
/// Errors: as [`super::fillet`] for the curves, orders and scales;
/// `max_deviation` or `setback_ratio` non-finite or not positive; a bound that
/// even the longest possible setbacks do not reach (InvalidArgument naming
/// `max_deviation`, with the largest deviation possible); a deviation that
/// jumps over the acceptance window (IllConditioned, with the relative gap
/// left below `max_deviation`).
///
/// ```
/// use bezjoin_core::BezierCurve;
/// use bezjoin_core::{DeviationFilletOptions, fillet_within_deviation};
/// let p = BezierCurve::from_rows(&[[-2.0, 0.0], [0.0, 0.0], [2.0, 0.0]]).unwrap();
/// let q = BezierCurve::from_rows(&[[0.0, -2.0], [0.0, 0.0], [0.0, 2.0]]).unwrap();
/// let r = fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(0.1, 2)).unwrap();
/// assert!(r.deviation <= 0.1 && r.deviation >= 0.1 * (1.0 - 1e-9));
/// ```
pub fn fillet_within_deviation<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    options: &DeviationFilletOptions,
) -> Result<DeviationFillet> {
    let (p, q): (CurveRef, CurveRef) = (p.into(), q.into());
    match options.shape.scale {
        ShapeScale::Auto => within_deviation_auto_scale(p, q, options),
        ShapeScale::Given { .. } => within_deviation(p, q, options),
        ShapeScale::Balanced => Err(BezjoinError::invalid(
            "scale",
            "the balanced scale is not offered within a deviation (its automatic scale is \
             one s, a fixed point of the setback search): use Auto or given scales",
        )),
    }
}

/// The automatic scale of a fillet within a deviation: `s` is the scale
/// [`ShapeScale::Auto`] chooses for the very setbacks that the search with
/// `alpha = beta = s` finds (`s = A(D(s))`), to a relative
/// [`DEVIATION_SCALE_TOLERANCE`]. The automatic scale cannot be chosen per
/// trial setback: its own search moves it in steps, and the deviation
/// then jumps over the acceptance window.
pub const DEVIATION_SCALE_TOLERANCE: f64 = 1e-6;

/// Most searches of the fixed point `s = A(D(s))`.
pub const DEVIATION_SCALE_STEPS: usize = 60;

/// [`fillet_within_deviation`] with [`ShapeScale::Auto`]: the fixed point
/// `s = A(D(s))` solved in `x = ln s` by secant steps on `g(x) = ln A(D(e^x))
/// - x` (a plain fixed-point step when the secant step is not usable or
/// longer than `4 |g| + 1`), from the paper's `s = 1`. The result is the
/// deviation search's at that `s`: the deviation guarantee is unchanged.
fn within_deviation_auto_scale(
    p: CurveRef,
    q: CurveRef,
    options: &DeviationFilletOptions,
) -> Result<DeviationFillet> {
    let evaluate = |x: f64| -> Result<(DeviationFillet, f64)> {
        let s = x.exp();
        let mut given = options.clone();
        given.shape.scale = ShapeScale::Given { p: s, q: s };
        let found = within_deviation(p, q, &given)?;
        let mut shape = options.shape.clone();
        shape.p_setback = found.p_setback;
        shape.q_setback = found.q_setback;
        let automatic = fillet_at_validated(p, q, found.fillet.crossing.clone(), &shape)?;
        Ok((found, automatic.p_scale.ln() - x))
    };
    let mut x = 0.0f64;
    let mut current = evaluate(x)?;
    let mut previous: Option<(f64, f64)> = None;
    for _ in 0..DEVIATION_SCALE_STEPS {
        let g = current.1;
        if g.abs() <= DEVIATION_SCALE_TOLERANCE {
            return Ok(current.0);
        }
        let mut step = g;
        if let Some((x0, g0)) = previous {
            let secant = -g * (x - x0) / (g - g0);
            if g != g0 && secant.is_finite() && secant.abs() <= 4.0 * g.abs() + 1.0 {
                step = secant;
            }
        }
        previous = Some((x, g));
        x += step;
        current = evaluate(x)?;
    }
    Err(BezjoinError::IllConditioned {
        what: format!(
            "fillet within a deviation with the automatic scale: s = A(D(s)) did not settle \
             in {DEVIATION_SCALE_STEPS} steps (last change {:e} in ln s); give the scales",
            current.1.abs()
        ),
        estimate: current.1.abs(),
        limit: DEVIATION_SCALE_TOLERANCE,
    })
}

/// [`fillet_within_deviation`] with given scales.
fn within_deviation(
    p: CurveRef,
    q: CurveRef,
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
    validate_shape(&options.shape)?;
    let hits = intersect(p, q, &options.shape.intersect)?;
    let crossing = first_crossing(&hits)?;
    let corner = crossing.point.clone();
    let (before, after) = available_lengths(p, q, &crossing)?;
    // Leave each curve twice the sliver a setback may not leave
    // ([`super::chain::sliver_length`], the rule of `blend_at`).
    let p_kept = 2.0 * super::chain::sliver_length(p, "p")?.1;
    let q_kept = 2.0 * super::chain::sliver_length(q, "q")?.1;
    let longest = (before - p_kept).min((after - q_kept) / ratio);

    // The two arc-length inversions are kept across the trials: each trial
    // inverts the same ranges from the crossing (to another accuracy), and
    // re-integrating them per trial made this search take seconds on
    // degree-50 curves with thousands of doubling steps.
    let mut inverses = SetbackInverses::new(p, q, &crossing);
    let mut attempt = |dp: f64| -> Result<Trial> {
        let mut shape = options.shape.clone();
        shape.p_setback = dp;
        shape.q_setback = ratio * dp;
        let blend = blend_at(p, q, &crossing, &shape, &mut inverses)?;
        let (t, deviation) = distance_to_curve(&blend.connection.curve, &corner);
        Ok(Trial {
            blend,
            p_setback: dp,
            q_setback: ratio * dp,
            deviation,
            deviation_parameter: t,
        })
    };
    // The accepted trial's trimmed pieces (a segment inside the domain cannot
    // fail: its control points are convex combinations of the curve's).
    let accept = |trial: Trial| -> Result<DeviationFillet> {
        Ok(DeviationFillet {
            fillet: assemble(p, q, crossing.clone(), trial.blend)?,
            p_setback: trial.p_setback,
            q_setback: trial.q_setback,
            deviation: trial.deviation,
            deviation_parameter: trial.deviation_parameter,
        })
    };
    // The bound is strict: only a deviation in the window [low, high]
    // below eps is accepted, and the search aims inside it, at `target`;
    // `high` keeps a margin of a/4 eps for the rounding of the computed
    // distance.
    let a = options.relative_deviation_accuracy.min(1.0);
    let low = eps * (1.0 - a);
    let high = eps * (1.0 - 0.25 * a);
    let target = eps * (1.0 - 0.5 * a);
    let accepted = |d: f64| (low..=high).contains(&d);
    // Bracket the smallest root of h(dp) = deviation(dp) - target: walk up
    // from a short setback by doubling (or down by halving when the first
    // one is already too deviant). `lo` has h < 0, `hi` has h > 0.
    let (mut lo, mut h_lo) = (0.0, -target);
    // The largest deviation found below the window (for the error message).
    let mut closest_below = 0.0f64;
    let mut dp = (0.5 * eps).min(longest);
    let mut trial = attempt(dp)?;
    if accepted(trial.deviation) {
        return accept(trial);
    }
    let mut h = trial.deviation - target;
    if h < 0.0 {
        loop {
            lo = dp;
            h_lo = h;
            if dp >= longest {
                return Err(BezjoinError::invalid(
                    "max_deviation",
                    format!(
                        "{eps} cannot be reached: the longest setbacks possible (p_setback = {}, \
                         q_setback = {}) give a deviation of only {}",
                        Compact(trial.p_setback),
                        Compact(trial.q_setback),
                        Compact(trial.deviation)
                    ),
                ));
            }
            closest_below = closest_below.max(trial.deviation);
            dp = (2.0 * dp).min(longest);
            trial = attempt(dp)?;
            if accepted(trial.deviation) {
                return accept(trial);
            }
            h = trial.deviation - target;
            if h > 0.0 {
                break;
            }
        }
    } else {
        for _ in 0..60 {
            let shorter = 0.5 * dp;
            let t = attempt(shorter)?;
            if accepted(t.deviation) {
                return accept(t);
            }
            let hs = t.deviation - target;
            if hs < 0.0 {
                lo = shorter;
                h_lo = hs;
                closest_below = closest_below.max(t.deviation);
                break;
            }
            dp = shorter;
            h = hs;
        }
    }
    let (mut hi, mut h_hi) = (dp, h);
    // Illinois false position on h over [lo, hi].
    let mut side = 0i32;
    for _ in 0..100 {
        let mut dp = (lo * h_hi - hi * h_lo) / (h_hi - h_lo);
        if !(dp > lo && dp < hi) {
            dp = 0.5 * (lo + hi);
        }
        let trial = attempt(dp)?;
        if accepted(trial.deviation) {
            return accept(trial);
        }
        let h = trial.deviation - target;
        if h < 0.0 {
            lo = dp;
            h_lo = h;
            if side == -1 {
                h_hi *= 0.5;
            }
            side = -1;
            closest_below = closest_below.max(trial.deviation);
        } else {
            hi = dp;
            h_hi = h;
            if side == 1 {
                h_lo *= 0.5;
            }
            side = 1;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
    }
    Err(BezjoinError::IllConditioned {
        what: format!(
            "deviation search: no setback gives a deviation in [{low}, {high}] for \
             max_deviation = {eps} (the deviation jumps over the window; the closest below \
             it is {closest_below})"
        ),
        estimate: (eps - closest_below) / eps,
        limit: options.relative_deviation_accuracy,
    })
}
