//! One-dimensional minimisation over a bounded interval, shared by the
//! searches of the library: the optimal split `mu` of [`crate::merge()`] and
//! the automatic scale ([`crate::connect::ShapeScale::Auto`]).
//!
//! Method: the function is sampled on an even grid (the global part: the
//! best sample is the global minimum's neighbourhood whenever the function
//! has at most one local minimum per grid interval), then Brent's method
//! (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973,
//! ch. 5, procedure `localmin`: parabolic interpolation safeguarded by golden
//! section) refines inside the two grid intervals around the best sample.
//! Brent's method never evaluates outside that bracket, needs at most about
//! twice the evaluations of a golden-section search on any function, and
//! converges superlinearly on smooth minima (where golden section gains a
//! fixed factor 0.618 per evaluation).
//!
//! Guarantee: the returned point is the best point evaluated (grid samples
//! included), so it is never worse than the best grid sample. Non-finite
//! values (failed evaluations) count as `+infinity`.

/// The result of [`minimize_on_grid_then_brent`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Minimum {
    /// The best point evaluated.
    pub x: f64,
    /// The function's value there (finite).
    pub value: f64,
    /// Number of function evaluations made (grid included).
    #[allow(dead_code)] // read by the tests that measure the method
    pub evaluations: usize,
}

/// Brent's relative tolerance term: twice the machine epsilon, so that the
/// absolute tolerance given by the caller decides the stopping point.
const RELATIVE_TOLERANCE: f64 = 2.0 * f64::EPSILON;

/// `(3 - sqrt 5) / 2`, the golden-section fraction.
const GOLDEN: f64 = 0.381_966_011_250_105_1;

/// Minimise `f` over `[lo, hi]`: `grid_points >= 2` evenly spaced samples,
/// then Brent's method around the best one until the bracket around the
/// best point is about `tolerance` (absolute, in `x`) wide or `max_steps`
/// refinement evaluations were made. `None` when every grid sample is
/// non-finite (the caller reports why).
pub(crate) fn minimize_on_grid_then_brent(
    mut f: impl FnMut(f64) -> f64,
    lo: f64,
    hi: f64,
    grid_points: usize,
    tolerance: f64,
    max_steps: usize,
) -> Option<Minimum> {
    debug_assert!(grid_points >= 2 && lo < hi && tolerance > 0.0);
    let mut evaluate = |x: f64| {
        let v = f(x);
        if v.is_nan() { f64::INFINITY } else { v }
    };
    let step = (hi - lo) / (grid_points - 1) as f64;
    let grid: Vec<(f64, f64)> = (0..grid_points)
        .map(|i| {
            // The last sample is `hi` exactly, not `lo + step * (n - 1)`.
            let x = if i + 1 == grid_points {
                hi
            } else {
                lo + step * i as f64
            };
            (x, evaluate(x))
        })
        .collect();
    let best = (0..grid.len())
        .min_by(|&a, &b| grid[a].1.total_cmp(&grid[b].1))
        .expect("at least two samples");
    let (x0, f0) = grid[best];
    if !f0.is_finite() {
        return None;
    }
    let a = grid[best.saturating_sub(1)].0;
    let b = grid[(best + 1).min(grid.len() - 1)].0;
    let (x, value, steps) = brent(&mut evaluate, a, b, x0, f0, tolerance, max_steps);
    Some(Minimum {
        x,
        value,
        evaluations: grid.len() + steps,
    })
}

/// Brent's `localmin` on `[a, b]` started from `x0` (with `f(x0) = f0`)
/// instead of the golden-section point, so the grid's best sample is reused.
/// Returns the best point, its value and the number of evaluations made.
fn brent(
    f: &mut impl FnMut(f64) -> f64,
    mut a: f64,
    mut b: f64,
    x0: f64,
    f0: f64,
    tolerance: f64,
    max_steps: usize,
) -> (f64, f64, usize) {
    let t = tolerance / 3.0;
    let (mut x, mut w, mut v) = (x0, x0, x0);
    let (mut fx, mut fw, mut fv) = (f0, f0, f0);
    // d: the last step; e: the step before it (the parabolic step must be
    // shorter than half of it, else golden section takes over).
    let (mut d, mut e) = (0.0f64, 0.0f64);
    let mut steps = 0;
    while steps < max_steps {
        let m = 0.5 * (a + b);
        let tol = RELATIVE_TOLERANCE * x.abs() + t;
        let tol2 = 2.0 * tol;
        if (x - m).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut parabolic = false;
        if e.abs() > tol {
            // Parabola through (x, fx), (w, fw), (v, fv); its vertex is x + p/q.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let previous = e;
            e = d;
            // NaN (from infinite values) fails every comparison: golden step.
            if p.abs() < (0.5 * q * previous).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                // Do not evaluate too close to the bracket's ends.
                if u - a < tol2 || b - u < tol2 {
                    d = if x < m { tol } else { -tol };
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < m { b - x } else { a - x };
            d = GOLDEN * e;
        }
        // Never step by less than tol: values closer than that are noise.
        let u = if d.abs() >= tol {
            x + d
        } else if d > 0.0 {
            x + tol
        } else {
            x - tol
        };
        let fu = f(u);
        steps += 1;
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv) = (w, fw);
            (w, fw) = (x, fx);
            (x, fx) = (u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv) = (w, fw);
                (w, fw) = (u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx, steps)
}

/// A sample of a function with its derivative.
#[derive(Debug, Clone, Copy)]
struct Sample {
    x: f64,
    value: f64,
    slope: f64,
}

/// The local minimiser in `(0, 1)` of the cubic Hermite interpolant of
/// `a`, `b` (in the interval's own parameter `s`), with its model value;
/// `None` when the cubic has no interior local minimum.
fn hermite_minimum(a: &Sample, b: &Sample) -> Option<(f64, f64)> {
    let h = b.x - a.x;
    let (fa, fb, da, db) = (a.value, b.value, a.slope * h, b.slope * h);
    let c1 = da;
    let c2 = 3.0 * (fb - fa) - 2.0 * da - db;
    let c3 = 2.0 * (fa - fb) + da + db;
    let model = |s: f64| fa + s * (c1 + s * (c2 + s * c3));
    // p'(s) = c1 + 2 c2 s + 3 c3 s^2; a minimum has p''(s) = 2 c2 + 6 c3 s > 0.
    let mut roots = [f64::NAN; 2];
    if c3.abs() <= 1e-14 * (c2.abs() + c1.abs()) {
        if c2 > 0.0 {
            roots[0] = -c1 / (2.0 * c2);
        }
    } else {
        let discriminant = c2 * c2 - 3.0 * c3 * c1;
        if discriminant >= 0.0 {
            let root = discriminant.sqrt();
            // Numerically stable pair of roots of 3 c3 s^2 + 2 c2 s + c1.
            let q = -(c2 + c2.signum() * root);
            if q != 0.0 {
                roots[0] = q / (3.0 * c3);
                roots[1] = c1 / q;
            } else {
                roots[0] = 0.0;
            }
        }
    }
    roots
        .into_iter()
        .filter(|&s| s > 0.0 && s < 1.0 && 2.0 * c2 + 6.0 * c3 * s > 0.0)
        .map(|s| (s, model(s)))
        .min_by(|p, q| p.1.total_cmp(&q.1))
}

/// Minimise `f` over `[lo, hi]` when `f` returns its value and derivative
/// (`None`: no value there): `grid_points >= 2` evenly spaced samples,
/// then, in every grid interval whose cubic Hermite interpolant has a local
/// minimum or whose values contradict its slopes of one sign (best model
/// first), a safeguarded search on the derivative ([`bracket_search`]: the
/// bracket always holds a sign change of the slope from - to +) until the
/// bracket or the step is about `tolerance` wide, or until the interval's
/// model, corrected by its measured error, cannot reach the best value
/// found ([`PRUNE_MARGIN`]). An interval with a failed end is searched by
/// [`brent`] on the values instead (never skipped). Returns the best point
/// evaluated; `None` when every grid sample failed.
pub(crate) fn minimize_with_slope(
    mut f: impl FnMut(f64) -> Option<(f64, f64)>,
    lo: f64,
    hi: f64,
    grid_points: usize,
    tolerance: f64,
    max_steps: usize,
) -> Option<Minimum> {
    debug_assert!(grid_points >= 2 && lo < hi && tolerance > 0.0);
    let mut evaluations = 0usize;
    let mut evaluate = |x: f64| {
        evaluations += 1;
        match f(x) {
            Some((value, slope)) if value.is_finite() && slope.is_finite() => {
                Sample { x, value, slope }
            }
            _ => Sample {
                x,
                value: f64::INFINITY,
                slope: f64::NAN,
            },
        }
    };
    let step = (hi - lo) / (grid_points - 1) as f64;
    let grid: Vec<Sample> = (0..grid_points)
        .map(|i| {
            evaluate(if i + 1 == grid_points {
                hi
            } else {
                lo + step * i as f64
            })
        })
        .collect();
    let mut best = *grid
        .iter()
        .min_by(|a, b| a.value.total_cmp(&b.value))
        .expect("at least two samples");
    if !best.value.is_finite() {
        return None;
    }
    // Candidate intervals: (model value, index); failed ends: value search.
    let mut candidates: Vec<(f64, usize)> = Vec::new();
    let mut failed = Vec::new();
    for i in 0..grid.len() - 1 {
        let (a, b) = (&grid[i], &grid[i + 1]);
        match (a.value.is_finite(), b.value.is_finite()) {
            (true, true) => {
                if let Some((_, model)) = hermite_minimum(a, b) {
                    candidates.push((model, i));
                } else if may_hide_minimum(a, b) {
                    candidates.push((a.value.min(b.value), i));
                }
            }
            (false, false) => {}
            _ => failed.push(i),
        }
    }
    candidates.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut budget = max_steps;
    // Every candidate is searched: a cubic model of a grid interval is too
    // rough to rule one out (two minima of nearly equal value are common);
    // only after a step inside it, with the model's error measured there,
    // can it be left (bracket_search).
    for (_, i) in candidates {
        if budget == 0 {
            break;
        }
        let found = slope_search(
            &mut evaluate,
            grid[i],
            grid[i + 1],
            tolerance,
            &mut budget,
            best.value,
        );
        if found.value < best.value {
            best = found;
        }
    }
    for i in failed {
        if budget == 0 {
            break;
        }
        let (a, b) = (grid[i], grid[i + 1]);
        let start = if a.value.is_finite() { a } else { b };
        let mut values = |x: f64| evaluate(x).value;
        let (x, value, steps) = brent(
            &mut values,
            a.x,
            b.x,
            start.x,
            start.value,
            tolerance,
            budget,
        );
        budget = budget.saturating_sub(steps);
        if value < best.value {
            best = Sample {
                x,
                value,
                slope: f64::NAN,
            };
        }
    }
    Some(Minimum {
        x: best.x,
        value: best.value,
        evaluations,
    })
}

/// The search of [`minimize_with_slope`] inside one grid interval: returns
/// the best sample evaluated (the ends included). `incumbent`: the best
/// value found elsewhere.
fn slope_search(
    evaluate: &mut impl FnMut(f64) -> Sample,
    a: Sample,
    b: Sample,
    tolerance: f64,
    budget: &mut usize,
    incumbent: f64,
) -> Sample {
    let mut best = if a.value <= b.value { a } else { b };
    // Without a sign change of the slope, the model's minimum splits the
    // interval and both halves are looked at again (a few levels deep):
    // the slope may rise, fall and rise again inside one grid interval.
    let mut work = vec![(a, b, 0usize)];
    while let Some((a, b, depth)) = work.pop() {
        if *budget == 0 {
            break;
        }
        if a.slope < 0.0 && b.slope > 0.0 {
            let found =
                bracket_search(evaluate, a, b, tolerance, budget, incumbent.min(best.value));
            if found.value < best.value {
                best = found;
            }
            continue;
        }
        if depth >= SPLIT_DEPTH || b.x - a.x <= tolerance {
            continue;
        }
        // Split at the model's minimum, kept away from the ends (the model
        // can be poor where the slope changes fast), or in the middle when
        // the values contradict the slopes without a model minimum.
        let s = match hermite_minimum(&a, &b) {
            Some((s, _)) => s.clamp(0.1, 0.9),
            None if may_hide_minimum(&a, &b) => 0.5,
            None => continue,
        };
        *budget -= 1;
        let c = evaluate(a.x + s * (b.x - a.x));
        if !c.value.is_finite() {
            continue;
        }
        if c.value < best.value {
            best = c;
        }
        work.push((c, b, depth + 1));
        work.push((a, c, depth + 1));
    }
    best
}

/// A sign change of the slope from - to +, or slopes of ONE sign with
/// values that contradict them (rising at both ends yet lower at `b`, or
/// falling at both ends yet lower at `a`): the function turns inside, a
/// minimum may hide there. (Rising at `a` and falling at `b` is one
/// maximum whatever the values; the cubic model decides there.)
fn may_hide_minimum(a: &Sample, b: &Sample) -> bool {
    (a.slope < 0.0 && b.slope > 0.0)
        || (a.slope >= 0.0 && b.slope >= 0.0 && b.value < a.value)
        || (a.slope <= 0.0 && b.slope <= 0.0 && a.value < b.value)
}

/// How often an interval without a sign change of the slope is split at
/// its model's minimum.
const SPLIT_DEPTH: usize = 6;

/// An interval's search is left when the minimum of the cubic Hermite
/// model of its current bracket, less this many times the error of the
/// previous bracket's model measured at the point just evaluated (a wider
/// interval: the new model's error is smaller, `~ width^4`), is still
/// above the best value found, by more than
/// [`PRUNE_RELATIVE`] of it.
pub(crate) const PRUNE_MARGIN: f64 = 4.0;

/// Relative part of the pruning gap (values within it are never pruned).
pub(crate) const PRUNE_RELATIVE: f64 = 1e-9;

/// The local minimiser of the cubic Hermite interpolant of `a`, `b` on the
/// whole line (not only between them), as a point: the superlinear step
/// of [`bracket_search`] from its two latest samples; `None` when the
/// cubic has no local minimum.
fn hermite_minimum_anywhere(a: &Sample, b: &Sample) -> Option<f64> {
    let h = b.x - a.x;
    if h == 0.0 {
        return None;
    }
    let (fa, fb, da, db) = (a.value, b.value, a.slope * h, b.slope * h);
    let c1 = da;
    let c2 = 3.0 * (fb - fa) - 2.0 * da - db;
    let c3 = 2.0 * (fa - fb) + da + db;
    let s = if c3.abs() <= 1e-14 * (c2.abs() + c1.abs()) {
        (c2 > 0.0).then(|| -c1 / (2.0 * c2))?
    } else {
        let discriminant = c2 * c2 - 3.0 * c3 * c1;
        if discriminant < 0.0 {
            return None;
        }
        // The root of p'(s) = c1 + 2 c2 s + 3 c3 s^2 with p''(s) > 0:
        // s = (-c2 + sqrt(d)) / (3 c3), written without cancellation.
        let root = discriminant.sqrt();
        if c2 > 0.0 {
            -c1 / (c2 + root)
        } else {
            (root - c2) / (3.0 * c3)
        }
    };
    let x = a.x + s * h;
    x.is_finite().then_some(x)
}

/// The cubic Hermite model of the bracket `a`, `b` at `x`.
fn hermite_value(a: &Sample, b: &Sample, x: f64) -> f64 {
    let h = b.x - a.x;
    let (fa, fb, da, db) = (a.value, b.value, a.slope * h, b.slope * h);
    let c2 = 3.0 * (fb - fa) - 2.0 * da - db;
    let c3 = 2.0 * (fa - fb) + da + db;
    let s = (x - a.x) / h;
    fa + s * (da + s * (c2 + s * c3))
}

/// Safeguarded search for the minimum in `[a, b]`, `a.slope < 0 <
/// b.slope`: the next point minimises the cubic Hermite model of the two
/// latest samples (order about 2 on a smooth minimum; the first step uses
/// the bracket's ends), accepted when it lies inside the bracket and moves
/// less than half the step before last (Brent's rule), otherwise the
/// bracket is bisected; a step shorter than `tolerance` is lengthened to
/// it (so a converged point closes the bracket from the other side). Stops
/// when the bracket is `tolerance` wide or a step was that short, or when
/// the bracket's model cannot reach `incumbent` ([`PRUNE_MARGIN`]).
fn bracket_search(
    evaluate: &mut impl FnMut(f64) -> Sample,
    mut a: Sample,
    mut b: Sample,
    tolerance: f64,
    budget: &mut usize,
    incumbent: f64,
) -> Sample {
    let mut best = if a.value <= b.value { a } else { b };
    let mut latest: Option<(Sample, Sample)> = None;
    // Step lengths: the last one and the one before it.
    let (mut last_step, mut step_before) = (b.x - a.x, b.x - a.x);
    while *budget > 0 && b.x - a.x > tolerance {
        let (x, proposal) = match &latest {
            Some((w, x)) => (x.x, hermite_minimum_anywhere(w, x)),
            None => (
                f64::NAN,
                hermite_minimum(&a, &b).map(|(s, _)| a.x + s * (b.x - a.x)),
            ),
        };
        let inside = |c: f64| c > a.x && c < b.x;
        let mut next = match proposal {
            Some(c) if inside(c) && (x.is_nan() || (c - x).abs() < 0.5 * step_before) => c,
            _ => 0.5 * (a.x + b.x),
        };
        if !x.is_nan() && (next - x).abs() < tolerance {
            next = x + tolerance.copysign(next - x);
        }
        if !inside(next) {
            break;
        }
        let step = if x.is_nan() {
            b.x - a.x
        } else {
            (next - x).abs()
        };
        (step_before, last_step) = (last_step, step);
        let predicted = hermite_value(&a, &b, next);
        *budget -= 1;
        let c = evaluate(next);
        if c.value < best.value {
            best = c;
        }
        if !c.value.is_finite() || c.slope == 0.0 {
            break;
        }
        if c.slope < 0.0 {
            a = c;
        } else {
            b = c;
        }
        latest = Some(match latest {
            Some((_, x)) => (x, c),
            // After the first step: the bracket end on the far side of the
            // point just evaluated is the other latest sample.
            None => (if c.slope < 0.0 { b } else { a }, c),
        });
        if step <= tolerance {
            break;
        }
        // Leave the interval when even its model, less the error just
        // measured, stays above the best value found.
        let error = (predicted - c.value).abs();
        let reach = hermite_minimum(&a, &b).map_or(a.value.min(b.value), |(_, v)| v);
        let bar = incumbent.min(best.value);
        if reach - PRUNE_MARGIN * error > bar + PRUNE_RELATIVE * bar.abs() {
            break;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Golden-section evaluations needed to shrink `width` to `tolerance`.
    fn golden_evaluations(width: f64, tolerance: f64) -> usize {
        ((width / tolerance).ln() / (1.0 / (1.0 - GOLDEN)).ln()).ceil() as usize + 1
    }

    #[test]
    fn smooth_minima_are_found_to_the_tolerance_and_faster_than_golden_section() {
        // (function, true minimiser) on [0, 1].
        type Case = (Box<dyn Fn(f64) -> f64>, f64);
        let cases: Vec<Case> = vec![
            (Box::new(|x: f64| (x - 0.3141).powi(2)), 0.3141),
            (Box::new(|x: f64| (x - 0.777).powi(2) * (1.0 + x)), 0.777),
            (
                Box::new(|x: f64| (x - 0.52).powi(2) + 0.1 * (x - 0.52).powi(3) + 2.0),
                0.52,
            ),
            (Box::new(|x: f64| -(8.0 * x).sin() - x), {
                // -8 cos(8x) - 1 = 0 -> cos(8x) = -1/8; of the two minima
                // in [0, 1] the second is lower (the -x term).
                (2.0 * std::f64::consts::PI + (-1.0f64 / 8.0).acos()) / 8.0
            }),
            (Box::new(|x: f64| (x - 0.61).abs().powf(1.5)), 0.61),
        ];
        for (i, (f, at)) in cases.iter().enumerate() {
            let m = minimize_on_grid_then_brent(f, 0.0, 1.0, 33, 1e-10, 100).unwrap();
            let smooth = i < 4;
            let accuracy = if smooth { 1e-7 } else { 1e-6 };
            assert!((m.x - at).abs() < accuracy, "case {i}: {} vs {at}", m.x);
            // Never worse than any dense sample.
            for k in 0..=1000 {
                let x = k as f64 / 1000.0;
                assert!(
                    m.value <= f(x) + 1e-15,
                    "case {i}: f({x}) below the minimum"
                );
            }
            let golden = golden_evaluations(2.0 / 32.0, 1e-10);
            // Where the minimum value is not zero, values within rounding
            // of it are flat over ~sqrt(eps) in x and the last steps are
            // tol-sized; still fewer than golden section's.
            eprintln!("case {i}: {} refinement evaluations", m.evaluations - 33);
            if smooth {
                assert!(
                    m.evaluations - 33 < golden,
                    "case {i}: {} refinement evaluations, golden section needs {golden}",
                    m.evaluations - 33
                );
            }
        }
    }

    #[test]
    fn a_zero_minimum_of_a_quadratic_is_hit_exactly() {
        // The merge-back case: the metric vanishes at the split parameter.
        let t = 0.437_851_234_9;
        let m = minimize_on_grid_then_brent(
            |x| 3.0 * (x - t).powi(2),
            1e-3,
            1.0 - 1e-3,
            33,
            1e-10,
            100,
        )
        .unwrap();
        assert!((m.x - t).abs() < 1e-9, "{} vs {t}", m.x);
        assert!(m.value < 1e-17);
    }

    #[test]
    fn minima_at_the_ends_and_failed_evaluations() {
        // Increasing function: the minimum is the left end, a grid sample.
        let m = minimize_on_grid_then_brent(|x| x, 0.0, 1.0, 9, 1e-10, 100).unwrap();
        assert_eq!(m.x, 0.0);
        // Decreasing: the right end exactly.
        let m = minimize_on_grid_then_brent(|x| -x, 0.0, 1.0, 9, 1e-10, 100).unwrap();
        assert_eq!(m.x, 1.0);
        // Failures (NaN, +inf) left of 0.5 are avoided.
        let m = minimize_on_grid_then_brent(
            |x| {
                if x < 0.5 {
                    f64::NAN
                } else if x < 0.55 {
                    f64::INFINITY
                } else {
                    (x - 0.6).powi(2)
                }
            },
            0.0,
            1.0,
            33,
            1e-10,
            100,
        )
        .unwrap();
        assert!((m.x - 0.6).abs() < 1e-7 && m.value.is_finite());
        // Nothing finite: None.
        assert!(minimize_on_grid_then_brent(|_| f64::NAN, 0.0, 1.0, 5, 1e-10, 100).is_none());
    }

    #[test]
    fn the_step_budget_is_respected_on_noise() {
        // A flat function with rounding-level noise: Brent must stop by its
        // budget or tolerance, not wander.
        let mut k = 0u64;
        let m = minimize_on_grid_then_brent(
            |x| {
                k = k
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                1.0 + (x - 0.5).powi(2) * 1e-20 + (k >> 11) as f64 * 1e-16 / (1u64 << 53) as f64
            },
            0.0,
            1.0,
            33,
            1e-10,
            25,
        )
        .unwrap();
        assert!(m.evaluations <= 33 + 25);
        assert!((0.0..=1.0).contains(&m.x));
    }

    /// The slope search finds the global minimum of a function with many
    /// local minima of nearly equal depth (against a dense scan) and
    /// spends few evaluations per minimum (the grid plus at most
    /// `per_minimum` per interval holding one).
    #[test]
    fn slope_search_finds_the_global_minimum_with_few_evaluations() {
        // f = sin(k x) + c (x - x0)^2: minima every 2 pi / k, their depths
        // differ by the parabola only.
        for (k, c, x0) in [(40.0, 0.05, 0.61), (23.0, 0.01, 0.2), (71.0, 0.3, 0.93)] {
            let f = |x: f64| (k * x).sin() + c * (x - x0) * (x - x0);
            let df = |x: f64| k * (k * x).cos() + 2.0 * c * (x - x0);
            let grid = 4 * (k as usize) / 6 + 9;
            let m =
                minimize_with_slope(|x| Some((f(x), df(x))), 0.0, 1.0, grid, 1e-10, 100).unwrap();
            let scan = (0..=200_000)
                .map(|i| f(i as f64 / 200_000.0))
                .fold(f64::INFINITY, f64::min);
            assert!(m.value <= scan + 1e-12, "k {k}: {} vs scan {scan}", m.value);
            let minima = (k / std::f64::consts::TAU).ceil() as usize + 1;
            let refinement = m.evaluations - grid;
            eprintln!("k {k}: {refinement} refinement evaluations for {minima} minima");
            assert!(
                refinement <= 3 * minima + 6,
                "k {k}: {refinement} refinement evaluations for {minima} minima"
            );
        }
    }
}
