//! Arc length of a Bezier curve and its inverse.
//!
//! `len(a, b) = int_a^b |P'(t)| dt` by adaptive Gauss-Legendre quadrature,
//! after cutting `[a, b]` at the local minima of the speed (cusps, where
//! `|P'|` has a kink; hodograph degree <= 200), with a geometric mesh
//! towards each minimum where the speed is small but not zero (a
//! near-cusp, [`grade_at_near_cusps`]): on each piece a 16-point rule on an
//! interval is accepted when it agrees with the sum of
//! the same rule on both halves to within the interval's share of the
//! requested `accuracy`; otherwise both halves are refined. Straight lines
//! (constant speed polynomials of degree <= 31 in the integrand's square)
//! are exact at the first level. Where the requested absolute accuracy is
//! below the rounding level of the length itself (`16 eps` times the
//! length; for ranges of subnormal width, a few steps of `5e-324` in `t`
//! at the speed; e.g. long extrapolated ranges or `accuracy = 1e-300`) the
//! result is accurate to that rounding level instead, and the work stays
//! bounded.
//!
//! The inverse, [`BezierCurve::param_at_length`], solves
//! `len(start, t) = length` by Newton's method on `t` (derivative `|P'(t)|`)
//! safeguarded by bisection, so it converges even where the speed vanishes.
//! It integrates the available range once, keeping the adaptive rule's
//! accepted panels as a cumulative table; the table locates the panel that
//! holds the answer, and Newton runs inside that panel on the fixed 16-point
//! rule (whose result is checked against its halves at the end). Only when
//! that check fails does it fall back to Newton on adaptive lengths, from
//! the start of that panel (from `start` only when the range's length
//! overflows and there is no table).
//!
//! Before all that, curves whose hodograph polygon keeps the speed away
//! from zero (no cusp; degree and dimension small enough for a stack
//! buffer) are inverted by [`ChebyshevSampled::param_at_length`]: 25 speed
//! samples (49 when those do not certify) on a bracket of the answer, the interpolant integrated in closed
//! form, Newton on that polynomial, and a check of the interpolant against
//! the one through every other sample (the analogue of the rule against its
//! halves) and of the residual at the returned parameter; whatever it
//! cannot certify goes the adaptive way above.
//!
//! Repeated inversions from one start (the fillet's deviation search, one
//! per trial setback) go through a kept [`ArcLengthInverse`]: it keeps the
//! adaptive rule's bisection tree with its values ([`QuadratureTree`]) and
//! the panel inversion's rule values ([`Partials`]), so each later call
//! costs a walk of the tree and a few new evaluations, and returns what a
//! fresh call returns, bit for bit.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, DefaultHasher};

use crate::basis::binomial;
use crate::bezier::{BezierCurve, bernstein_horner, norm};
use crate::error::{BezjoinError, Compact, Result, check_finite_scalar};

/// Default absolute accuracy factor: lengths are computed to
/// `DEFAULT_ARC_LENGTH_ACCURACY * max(1, polygon length)`.
pub const DEFAULT_ARC_LENGTH_ACCURACY: f64 = 1e-13;

/// Relative rounding level below which the adaptive rule stops refining.
const ROUNDING_FLOOR: f64 = 16.0 * f64::EPSILON;

/// Units of the smallest subnormal parameter step (`5e-324`) that the
/// rule's value on an interval of subnormal width can be off by, in length:
/// its half-width `(b - a) / 2` is rounded to a whole unit there (exact for
/// normal numbers), which moves the value by up to half a unit of `t` times
/// the speed, in the whole and in each half.
const SUBNORMAL_STEPS: f64 = 4.0;

/// The level below which two of the rule's estimates of `value`, the length
/// over an interval of `width`, differ by rounding: `16 eps |value|`, and
/// for a subnormal width (`t` near 0 with a setback or accuracy near
/// `5e-324`) [`SUBNORMAL_STEPS`] steps of `5e-324` at the mean speed, at
/// least that many units of `5e-324` in length (without it such intervals
/// bisected until the evaluation budget ran out). The second term is the
/// larger only for a width or a value below about `5.5e-309`.
pub(crate) fn rounding_level(value: f64, width: f64) -> f64 {
    let step = f64::from_bits(1);
    let mean_speed = if width > 0.0 {
        value.abs() / width
    } else {
        0.0
    };
    (ROUNDING_FLOOR * value.abs()).max(SUBNORMAL_STEPS * step * mean_speed.max(1.0))
}

/// Maximum bisection depth of the adaptive quadrature.
const MAX_DEPTH: u32 = 40;

/// Speed evaluations one length computation may spend (about 0.1 s at
/// degree 20). Past it, panels are accepted as they are and the shortfall is
/// reported: `arc_length` and `param_at_length` then return
/// `IllConditioned` with the estimate instead of running on (fuzz finding
/// F2: without a budget a degree-22 curve on an extrapolated range bisected
/// towards 2^40 panels).
const MAX_EVALUATIONS: usize = 1 << 20;

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
    /// Bound on the rounding noise of the speed integrated over a unit of
    /// `t`: no refinement can resolve differences below `noise_per_unit *
    /// width` (see [`speed_noise_per_unit`]).
    noise_per_unit: f64,
}

impl<'a> Speed<'a> {
    fn new(hodograph: &'a BezierCurve, noise_per_unit: f64) -> Self {
        Speed {
            hodograph,
            buf: vec![0.0; hodograph.dim()],
            noise_per_unit,
        }
    }

    // Inlined into `gauss`, the hot loop of every length (measured: 8 %
    // of `param_at_length` when a code-layout change left it a call).
    #[inline(always)]
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
}

/// Entries a [`Partials`] keeps before it starts over.
const MAX_KEPT_PARTIALS: usize = 1 << 16;

/// The 16-point rules and speeds the panel inversion has computed, kept by
/// an [`ArcLengthInverse`] across calls. Inversions in the same panel
/// retrace the same iterates while their targets are below the parameter
/// resolution (the deviation search's doubling steps from a tiny
/// `max_deviation`: about 50 bisection steps per call, the same each time),
/// and then cost lookups; the values, hence the results, are the ones
/// computed afresh.
#[derive(Default)]
struct Partials {
    rules: FixedKeyMap<(u64, u64), f64>,
    speeds: FixedKeyMap<u64, f64>,
}

/// A map hashed with fixed keys rather than the per-process random ones of
/// `RandomState`: the same input takes the same path through the library in
/// every run (reproducible fuzzing, scripts/fuzz-short.sh). The keys are
/// the library's own parameter bits, not an attacker's.
type FixedKeyMap<K, V> = HashMap<K, V, BuildHasherDefault<DefaultHasher>>;

impl Partials {
    /// `speed.gauss(a, b)`.
    fn gauss(&mut self, speed: &mut Speed<'_>, a: f64, b: f64) -> f64 {
        if self.rules.len() >= MAX_KEPT_PARTIALS {
            self.rules.clear();
        }
        *self
            .rules
            .entry((a.to_bits(), b.to_bits()))
            .or_insert_with(|| speed.gauss(a, b))
    }

    /// `speed.at(t)`.
    fn at(&mut self, speed: &mut Speed<'_>, t: f64) -> f64 {
        if self.speeds.len() >= MAX_KEPT_PARTIALS {
            self.speeds.clear();
        }
        *self
            .speeds
            .entry(t.to_bits())
            .or_insert_with(|| speed.at(t))
    }

    /// `int_a^x |H|` on a sub-interval `[a, x]` (or `[x, a]`) of an accepted
    /// panel, with its own error check: the 16-point rule on the interval
    /// against the sum over its halves, accepted within `tolerance` or the
    /// rounding level of the value. `None` when the check fails.
    /// `whole`: the 16-point rule on the interval when already known.
    fn checked(
        &mut self,
        speed: &mut Speed<'_>,
        a: f64,
        x: f64,
        whole: Option<f64>,
        tolerance: f64,
    ) -> Option<f64> {
        if a == x {
            return Some(0.0);
        }
        let whole = whole.unwrap_or_else(|| self.gauss(speed, a, x));
        let m = 0.5 * (a + x);
        let refined = self.gauss(speed, a, m) + self.gauss(speed, m, x);
        let floor = rounding_level(refined, (x - a).abs());
        ((refined - whole).abs() <= tolerance.max(floor)).then_some(refined)
    }
}

/// Nodes a [`QuadratureTree`] keeps between passes before it starts over
/// (four times what one pass within the evaluation budget can create).
const MAX_KEPT_NODES: usize = 4 * (MAX_EVALUATIONS / 32);

/// Marks a [`Node`] the rule has not refined yet.
const NO_CHILDREN: usize = usize::MAX;

/// The adaptive rule's bisection tree on one range, kept between passes.
///
/// Which intervals the rule refines depends on the accuracy, but the
/// intervals it can visit (the cuts at the speed minima, then halving) and
/// the 16-point values on them do not. The tree keeps every value computed
/// so far, so a later pass on the same range (another accuracy, as in the
/// fillet's deviation search, which inverts the same two ranges once per
/// trial setback) walks the known part for the cost of the walk. A pass
/// gives what a fresh one gives, bit for bit: the same intervals, values,
/// order of the sums, and evaluation budget (counted as if every value were
/// computed anew).
struct QuadratureTree {
    lo: f64,
    hi: f64,
    /// `lo`, the speed minima inside (when searched), `hi`.
    cuts: Vec<f64>,
    noise_per_unit: f64,
    /// Per piece `cuts[k]..cuts[k + 1]`: the 16-point rule on it and its
    /// root node, once a pass has visited it.
    roots: Vec<Option<(f64, usize)>>,
    nodes: Vec<Node>,
}

/// An interval `[a, b]` of a [`QuadratureTree`] (the bounds are passed down
/// the walk, computed as the first pass computed them).
#[derive(Clone, Copy)]
struct Node {
    /// The 16-point rule on `[a, m]` and on `[m, b]`, `m = (a + b) / 2`.
    left: f64,
    right: f64,
    /// Index of the child on `[a, m]` (the one on `[m, b]` follows it), or
    /// [`NO_CHILDREN`].
    children: usize,
}

/// The counters of one pass.
struct Walk {
    /// Speed evaluations a fresh pass would have spent so far (the budget).
    evaluations: usize,
    /// Sum of `|refined - whole|` over panels accepted only because the
    /// depth or evaluation budget ran out: the part of the error the rule
    /// could not bring under the requested accuracy.
    unresolved: f64,
}

impl QuadratureTree {
    /// The tree on `[lo, hi]`, `lo <= hi`, cut at the local minima of the
    /// speed inside (see [`arc_length_panels`]); no values yet.
    fn new(hodograph: &BezierCurve, lo: f64, hi: f64) -> Self {
        let mut cuts = vec![lo];
        if !speed_bounded_away_from_zero(hodograph, lo, hi) {
            cuts.extend(speed_minima(hodograph, lo, hi));
        }
        cuts.push(hi);
        grade_at_near_cusps(hodograph, &mut cuts);
        Self::with_cuts(cuts, speed_noise_per_unit(hodograph, lo, hi))
    }

    fn with_cuts(cuts: Vec<f64>, noise_per_unit: f64) -> Self {
        QuadratureTree {
            lo: cuts[0],
            hi: cuts[cuts.len() - 1],
            roots: vec![None; cuts.len() - 1],
            cuts,
            noise_per_unit,
            nodes: Vec::new(),
        }
    }

    /// One pass of the adaptive rule over the range to `accuracy`: the
    /// (unsigned) length, the evaluations a fresh pass spends and the error
    /// left unresolved. Each piece gets the share of `accuracy` of its
    /// width. With `panels`, the accepted intervals are appended to it in
    /// increasing order of `t`.
    fn pass(
        &mut self,
        speed: &mut Speed<'_>,
        accuracy: f64,
        mut panels: Option<&mut Vec<Panel>>,
    ) -> LengthResult {
        if self.nodes.len() > MAX_KEPT_NODES {
            self.nodes.clear();
            self.roots.fill(None);
        }
        let mut walk = Walk {
            evaluations: 0,
            unresolved: 0.0,
        };
        let width = self.hi - self.lo;
        let mut length = 0.0;
        for k in 0..self.roots.len() {
            let (a, b) = (self.cuts[k], self.cuts[k + 1]);
            if b <= a {
                continue;
            }
            let share = accuracy * ((b - a) / width).max(f64::EPSILON);
            walk.evaluations += 16;
            let (whole, root) = match self.roots[k] {
                Some(known) => known,
                None => {
                    let whole = speed.gauss(a, b);
                    let root = self.new_node(speed, a, b);
                    self.roots[k] = Some((whole, root));
                    (whole, root)
                }
            };
            length += self.adaptive(speed, &mut walk, root, a, b, whole, share, 0, &mut panels);
        }
        LengthResult {
            length,
            evaluations: walk.evaluations,
            unresolved: walk.unresolved,
        }
    }

    /// A node on `[a, b]` with its halves' values.
    fn new_node(&mut self, speed: &mut Speed<'_>, a: f64, b: f64) -> usize {
        let m = 0.5 * (a + b);
        let left = speed.gauss(a, m);
        let right = speed.gauss(m, b);
        self.nodes.push(Node {
            left,
            right,
            children: NO_CHILDREN,
        });
        self.nodes.len() - 1
    }

    /// Adaptive rule on the node `[a, b]` (`whole` = the 16-point rule on
    /// it); when `panels` is given, every accepted interval is appended to
    /// it in increasing order of `t`.
    #[allow(clippy::too_many_arguments)]
    fn adaptive(
        &mut self,
        speed: &mut Speed<'_>,
        walk: &mut Walk,
        node: usize,
        a: f64,
        b: f64,
        whole: f64,
        accuracy: f64,
        depth: u32,
        panels: &mut Option<&mut Vec<Panel>>,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let Node { left, right, .. } = self.nodes[node];
        walk.evaluations += 32;
        let refined = left + right;
        // Below the rounding level of the sum no refinement can help: accept
        // there too (otherwise an absolute accuracy below `eps * length`
        // would bisect down to MAX_DEPTH everywhere, 2^40 intervals).
        if !refined.is_finite() {
            // Overflow: no refinement can help (and NaN would never pass
            // the test below, bisecting 2^MAX_DEPTH times).
            return refined;
        }
        let floor = rounding_level(refined, b - a).max(self.noise_per_unit * (b - a).abs());
        let difference = (refined - whole).abs();
        let resolved = difference <= accuracy.max(floor);
        let budget_spent = depth >= MAX_DEPTH || walk.evaluations >= MAX_EVALUATIONS;
        if resolved || budget_spent {
            if !resolved {
                walk.unresolved += difference;
            }
            if let Some(panels) = panels {
                panels.push(Panel {
                    a,
                    b,
                    length: refined,
                    tolerance: accuracy,
                });
            }
            return refined;
        }
        if self.nodes[node].children == NO_CHILDREN {
            let first = self.new_node(speed, a, m);
            self.new_node(speed, m, b);
            self.nodes[node].children = first;
        }
        let children = self.nodes[node].children;
        self.adaptive(
            speed,
            walk,
            children,
            a,
            m,
            left,
            0.5 * accuracy,
            depth + 1,
            panels,
        ) + self.adaptive(
            speed,
            walk,
            children + 1,
            m,
            b,
            right,
            0.5 * accuracy,
            depth + 1,
            panels,
        )
    }
}

/// Range of [`grade_at_near_cusps`]: its cuts reach down to
/// `2^-GRADING_LEVELS` times the distance from the minimum to its
/// neighbouring cut.
const GRADING_LEVELS: i32 = 30;

/// Ratio of consecutive cuts of [`grade_at_near_cusps`].
const GRADING_RATIO: f64 = 4.0;

/// Adds to `cuts` (sorted: `lo`, the speed minima, `hi`) a geometric mesh
/// on both sides of each minimum `m` where the speed is small but not zero
/// (a near-cusp): the cuts `m +- delta 4^k`, `k = 0, 1, ...`, below half
/// the distance to the neighbouring cut, with `delta = |H(m)| / |H'(m)|`.
///
/// Near the minimum `|H(m + s)|^2 = a^2 + b^2 s^2 + O(s^3)` (`a = |H(m)|`,
/// `b = |H'(m)|`; `H(m) . H'(m) = 0` there), whose zeros `s = +-i delta`
/// make `|H|` analytic only in a strip of half-width `delta` about `m`. On
/// a piece `[m, m + w]` with `w >> delta` the 16-point rule converges
/// slowly, and the rule on the piece and on its halves carry nearly the
/// same error, of order `a^2 / b` whatever `w` (the interval-versus-halves
/// test is fooled as at an exact kink). Measured on a degree-9 curve with
/// speed `1e-6` at its minimum: the right-hand piece accepted with rule
/// and halves `5.1e-14` apart (under its rounding-noise floor, `7e-14`)
/// while its length was `4.5e-13` off, so `param_at_length` missed its
/// accuracy by 7 %. On the graded mesh a piece `[m + delta 4^k, m + delta
/// 4^(k+1)]` keeps the singularities at `-5/3` in its own coordinate
/// `[-1, 1]` (Bernstein ellipse parameter 3: the 16-point rule's error
/// about `3^-32`, 5e-16 relative), the last one at worst at `-9/7`
/// (parameter 2.1, refined as usual); the rule converges geometrically on
/// each and its check is reliable again. An exact cusp (`a = 0`: `|H| =
/// |s| |G(s)|`, smooth on each side) and a minimum with `delta` below
/// `2^-GRADING_LEVELS` times its piece (the error's relative size, about
/// `(delta / w)^2`, is below the rounding level there) need no grading. At
/// most 15 cuts per side of a minimum (ratio 2 gave the same accuracy in
/// the near-cusp tests at 1.7 times the evaluations).
pub(crate) fn grade_at_near_cusps(hodograph: &BezierCurve, cuts: &mut Vec<f64>) {
    let n = cuts.len();
    if n <= 2 {
        return;
    }
    let d = hodograph.dim();
    let mut graded = Vec::new();
    let mut values = vec![0.0; 2 * d];
    for k in 1..n - 1 {
        let m = cuts[k];
        hodograph.eval_derivatives_into(m, 1, &mut values);
        let delta = norm(&values[..d]) / norm(&values[d..]);
        if !(delta.is_finite() && delta > 0.0) {
            continue;
        }
        for (neighbour, direction) in [(cuts[k - 1], -1.0), (cuts[k + 1], 1.0)] {
            let room = (neighbour - m).abs();
            if delta < room * 2f64.powi(-GRADING_LEVELS) {
                continue;
            }
            let mut step = delta;
            while 2.0 * step < room {
                graded.push(m + direction * step);
                step *= GRADING_RATIO;
            }
        }
    }
    if graded.is_empty() {
        return;
    }
    cuts.extend(graded);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
}

/// One interval accepted by the adaptive rule: `length = int_a^b |H|`
/// (a < b) to within `tolerance` (or the rounding level of `length`).
#[derive(Clone, Copy, Debug)]
struct Panel {
    a: f64,
    b: f64,
    length: f64,
    tolerance: f64,
}

impl BezierCurve {
    /// Arc length between parameters `a` and `b` (signed: negative when
    /// `b < a`), to an absolute `accuracy > 0`, or to `16 eps` relative where
    /// that is larger (the rounding level; for a range of subnormal width,
    /// four steps of `5e-324` in `t` at the speed). Any finite `a`, `b`.
    ///
    /// Errors: non-finite arguments, `accuracy <= 0`, a length that
    /// overflows the `f64` range (InvalidArgument).
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
        let length = arc_length_checked(&hodograph, a, b, accuracy)?;
        if !length.is_finite() {
            return Err(BezjoinError::invalid(
                "a, b",
                format!(
                    "the arc length from a = {} to b = {} overflows the double range",
                    Compact(a),
                    Compact(b)
                ),
            ));
        }
        Ok(length)
    }

    /// Arc length with the default accuracy
    /// ([`DEFAULT_ARC_LENGTH_ACCURACY`] times the larger of 1 and the control
    /// polygon's length).
    ///
    /// Errors: those of [`Self::arc_length`] for `a` and `b`, and
    /// `NonFiniteScalar` naming the control polygon's length when that
    /// overflows `f64` (finite control points more than `f64::MAX` apart):
    /// the default accuracy is relative to it.
    pub fn arc_length_default(&self, a: f64, b: f64) -> Result<f64> {
        // The caller's arguments are judged before the default they did
        // not pass, in `arc_length`'s order.
        check_finite_scalar("a", a)?;
        check_finite_scalar("b", b)?;
        self.arc_length(a, b, self.checked_default_length_accuracy("the curve")?)
    }

    /// The absolute accuracy used by [`Self::arc_length_default`].
    pub fn default_length_accuracy(&self) -> f64 {
        DEFAULT_ARC_LENGTH_ACCURACY * self.polygon_length().max(1.0)
    }

    /// [`Self::default_length_accuracy`], or the error of
    /// [`finite_default_accuracy`] naming `curve`.
    pub(crate) fn checked_default_length_accuracy(&self, curve: &str) -> Result<f64> {
        finite_default_accuracy(curve, self.default_length_accuracy(), || {
            self.polygon_length()
        })
    }

    /// The parameter `t in [0, 1]` whose signed arc length from `start` is
    /// `length` (negative: backwards). `accuracy` bounds the error of the
    /// length at the returned parameter.
    ///
    /// Errors: `start` outside `[0, 1]`; `length` longer than the part of the
    /// curve between `start` and the end it runs towards (InvalidArgument,
    /// naming both lengths).
    pub fn param_at_length(&self, start: f64, length: f64, accuracy: f64) -> Result<f64> {
        ArcLengthInverse::new(self, start).param_at_length(length, accuracy)
    }
}

/// `accuracy`, a curve's default arc-length accuracy (relative to its
/// control polygon's length), when it is finite; otherwise
/// `NonFiniteScalar` naming the control polygon length of `curve`, whose
/// overflow made it infinite. The caller passed no accuracy, so the error
/// names what the default was made of, not an argument called `accuracy`.
pub(crate) fn finite_default_accuracy(
    curve: &str,
    accuracy: f64,
    polygon_length: impl FnOnce() -> f64,
) -> Result<f64> {
    if accuracy.is_finite() {
        Ok(accuracy)
    } else {
        Err(BezjoinError::NonFiniteScalar {
            name: format!("the control polygon length of {curve}"),
            value: polygon_length(),
        })
    }
}

/// [`BezierCurve::param_at_length`] from one `start` for many lengths and
/// accuracies: each direction's [`QuadratureTree`] is built on first use
/// (the cut search at the speed minima) and kept, so later calls replay the
/// adaptive rule on the values already computed. Every call returns what
/// `curve.param_at_length(start, length, accuracy)` returns, bit for bit
/// (that function is a fresh `ArcLengthInverse`); the fillet's deviation
/// search keeps one per curve across its trial setbacks.
pub(crate) struct ArcLengthInverse<'a> {
    curve: &'a BezierCurve,
    /// Built on the first call that needs the adaptive path.
    hodograph: Option<BezierCurve>,
    /// The Chebyshev inversion's speed ([`ChebyshevSpeed`]), `None` when the
    /// curve does not qualify; built on first use.
    chebyshev: Option<Option<ChebyshevSpeed>>,
    start: f64,
    /// The trees on `[0, start]` (index 0, backwards) and `[start, 1]`
    /// (index 1, forwards).
    trees: [Option<QuadratureTree>; 2],
    partials: Partials,
}

impl<'a> ArcLengthInverse<'a> {
    /// Inversion from `start` along `curve` (`start` is checked by each call).
    pub(crate) fn new(curve: &'a BezierCurve, start: f64) -> Self {
        ArcLengthInverse {
            curve,
            hodograph: None,
            chebyshev: None,
            start,
            trees: [None, None],
            partials: Partials::default(),
        }
    }

    /// The arc length from `start` to the end `t = 1` (`forward`) or `t = 0`
    /// it runs towards, to `accuracy`, by the Chebyshev interpolant of the
    /// speed ([`ChebyshevSpeed`]'s `length_between`), without the adaptive
    /// rule; `None` when the curve does not qualify for the Chebyshev
    /// inversion or the length is not certified.
    pub(crate) fn length_to_end(&mut self, forward: bool, accuracy: f64) -> Option<f64> {
        let curve = self.curve;
        if self.chebyshev.is_none() {
            let slot = self.chebyshev.insert(Some(ChebyshevSpeed::zeroed()));
            if !slot.as_mut().is_some_and(|speed| speed.fill(curve)) {
                *slot = None;
            }
        }
        let speed = self.chebyshev.as_ref()?.as_ref()?;
        let start = self.start;
        if !(0.0..=1.0).contains(&start) {
            return None;
        }
        if forward {
            speed.length_between(start, 1.0, accuracy)
        } else {
            speed.length_between(0.0, start, accuracy)
        }
    }

    /// [`BezierCurve::param_at_length`] from this inverse's `start`.
    ///
    /// One adaptive pass over the whole available range records its
    /// accepted panels (the same value as `arc_length_with(start, end)` up to
    /// sign); the panel holding the answer is inverted by Newton on the
    /// fixed 16-point rule ([`invert_on_panels`]). When that answer fails
    /// its check, Newton runs on adaptive lengths inside that panel
    /// ([`invert_in_panel_adaptively`]); only without a finite table (a
    /// length that overflows) on adaptive lengths from `start`.
    pub(crate) fn param_at_length(&mut self, length: f64, accuracy: f64) -> Result<f64> {
        let start = self.start;
        crate::error::check_closed_range("start", start, 0.0, 1.0)?;
        check_finite_scalar("length", length)?;
        if accuracy.is_nan() || accuracy <= 0.0 || !accuracy.is_finite() {
            return Err(BezjoinError::out_of_range("accuracy", accuracy, "> 0"));
        }
        if length == 0.0 {
            return Ok(start);
        }
        let curve = self.curve;
        if self.chebyshev.is_none() {
            // Built in place in its slot (no copy of the buffer).
            let slot = self.chebyshev.insert(Some(ChebyshevSpeed::zeroed()));
            if !slot.as_mut().is_some_and(|speed| speed.fill(curve)) {
                *slot = None;
            }
        }
        if let Some(Some(speed)) = &self.chebyshev {
            if let Some(t) = speed.param_at_length(start, length, accuracy) {
                return Ok(t);
            }
        }
        self.param_at_length_adaptive(length, accuracy)
    }

    /// [`Self::param_at_length`] without the Chebyshev inversion: the
    /// adaptive rule's panels and Newton inside the panel holding the answer
    /// (the path of every curve the Chebyshev inversion does not certify).
    /// `start`, `length != 0` and `accuracy` already checked.
    fn param_at_length_adaptive(&mut self, length: f64, accuracy: f64) -> Result<f64> {
        let start = self.start;
        let curve = self.curve;
        let hodograph = &*self.hodograph.get_or_insert_with(|| curve.hodograph());
        let end = if length > 0.0 { 1.0 } else { 0.0 };
        let forward = length > 0.0;
        let (range_lo, range_hi) = if forward { (start, 1.0) } else { (0.0, start) };
        let tree = self.trees[usize::from(forward)]
            .get_or_insert_with(|| QuadratureTree::new(hodograph, range_lo, range_hi));
        let mut speed = Speed::new(hodograph, tree.noise_per_unit);
        let mut panels = Vec::new();
        let pass = tree.pass(&mut speed, accuracy * 0.1, Some(&mut panels));
        check_resolved(&pass, range_lo, range_hi, accuracy * 0.1)?;
        let available = pass.length;
        if available.is_nan() {
            // Speeds that overflow to infinity on both sides of a panel
            // (`inf - inf`): no length to invert.
            return Err(BezjoinError::NonFiniteScalar {
                name: format!(
                    "arc length from t = {} to t = {} (the curve's speed overflows f64)",
                    Compact(start),
                    if forward { 1 } else { 0 }
                ),
                value: available,
            });
        }
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
        // A non-finite range length leaves no usable table.
        if available.is_finite() {
            if let Some((panel, remaining)) = locate(&panels, forward, length.abs()) {
                if let Some(t) = invert_on_panels(
                    &mut speed,
                    &mut self.partials,
                    &panel,
                    forward,
                    remaining,
                    0.5 * accuracy,
                ) {
                    return Ok(t);
                }
                // The partial integral failed its check: Newton on adaptive
                // lengths, inside this panel only.
                return Ok(invert_in_panel_adaptively(
                    &mut speed, &panel, forward, remaining, accuracy,
                ));
            }
        }
        // Fallback without a table: Newton on adaptive lengths from `start`.
        // Bracket [lo, hi] in the direction of travel; f(t) = len(start, t) - length.
        let (mut lo, mut hi) = if length > 0.0 {
            (start, 1.0)
        } else {
            (0.0, start)
        };
        // Initial guess: proportional.
        let mut t = start + (end - start) * (length.abs() / available);
        for _ in 0..100 {
            let len = arc_length_with(hodograph, start, t, accuracy * 0.1);
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

/// Maximum Newton steps of [`invert_on_panels`].
const PANEL_NEWTON_STEPS: usize = 60;

/// Maximum Newton steps of [`invert_in_panel_adaptively`].
const ADAPTIVE_NEWTON_STEPS: usize = 100;

/// The panel holding arc length `target >= 0` from the start of the range
/// covered by `panels` (from its low end when `forward`, else from its high
/// end), and the length remaining inside it (in `[0, panel.length]`).
/// `None` without panels or at a non-finite panel length on the way.
///
/// The panels are the accepted intervals of one adaptive pass over the
/// range, so their cumulative lengths locate the answer; the lengths before
/// the panel are accurate to the pass's accuracy.
fn locate(panels: &[Panel], forward: bool, target: f64) -> Option<(Panel, f64)> {
    let n = panels.len();
    let mut cumulative = 0.0;
    for k in 0..n {
        let panel = if forward {
            panels[k]
        } else {
            panels[n - 1 - k]
        };
        if !panel.length.is_finite() {
            return None;
        }
        if cumulative + panel.length >= target || k + 1 == n {
            return Some((panel, (target - cumulative).clamp(0.0, panel.length)));
        }
        cumulative += panel.length;
    }
    None
}

/// The parameter at arc length `remaining` inside `panel`, measured from its
/// low end when `forward`, else from its high end (`remaining` from
/// [`locate`]), or `None` when it cannot be certified (then the caller falls
/// back).
///
/// Safeguarded Newton (derivative: the speed) solves
/// `int_near^t |H| = remaining` with the fixed 16-point rule on
/// `[near, t]`, which costs 17 speed evaluations per step instead of an
/// adaptive length from the start. The final partial integral is checked
/// like an adaptive interval (rule against its halves, within the panel's
/// accuracy share), and the residual recomputed from the refined value must
/// be within `residual_tolerance`. Error budget of the returned `t`: the
/// panel table's accuracy plus the panel's share plus `residual_tolerance`.
fn invert_on_panels(
    speed: &mut Speed<'_>,
    partials: &mut Partials,
    panel: &Panel,
    forward: bool,
    remaining: f64,
    residual_tolerance: f64,
) -> Option<f64> {
    let (near, far) = if forward {
        (panel.a, panel.b)
    } else {
        (panel.b, panel.a)
    };
    // Sign of gauss(near, t) for t between near and far.
    let sign = if forward { 1.0 } else { -1.0 };
    if remaining == 0.0 {
        return Some(near);
    }
    // phi(t) = sign * int_near^t |H| - remaining: negative at `inside`,
    // positive at `beyond`.
    let (mut inside, mut beyond) = (near, far);
    let mut t = near + (far - near) * (remaining / panel.length);
    let mut at_rounding_limit = false;
    // The rule on [near, t] at the converged t (reused by the check).
    let mut converged = None;
    for _ in 0..PANEL_NEWTON_STEPS {
        let partial = partials.gauss(speed, near, t);
        let phi = sign * partial - remaining;
        if !phi.is_finite() {
            return None;
        }
        if phi.abs() <= residual_tolerance {
            converged = Some(partial);
            break;
        }
        if phi > 0.0 {
            beyond = t;
        } else {
            inside = t;
        }
        let v = partials.at(speed, t);
        let newton = t - phi / (sign * v);
        let (lo, hi) = if inside < beyond {
            (inside, beyond)
        } else {
            (beyond, inside)
        };
        let next = if v > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == t || hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(f64::MIN_POSITIVE) {
            // No representable parameter is closer: the length is resolved
            // to the rounding level of `t`.
            t = next;
            at_rounding_limit = true;
            break;
        }
        t = next;
    }
    if !(converged.is_some() || at_rounding_limit) {
        return None;
    }
    let partial = partials.checked(speed, near, t, converged, panel.tolerance)?;
    if at_rounding_limit || (sign * partial - remaining).abs() <= residual_tolerance {
        Some(t)
    } else {
        None
    }
}

/// The parameter at arc length `remaining` inside `panel` (from its low end
/// when `forward`, else from its high end) by safeguarded Newton on adaptive
/// lengths `int_near^t |H|` to `0.1 accuracy`, until the residual is within
/// `0.8 accuracy` (with the table's `0.1 accuracy` before the panel, the
/// length at the returned `t` errs by at most `accuracy`) or the bracket is
/// down to the rounding level of parameters in `[0, 1]` (`4 eps` wide, as
/// in the fallback from `start`); at most [`ADAPTIVE_NEWTON_STEPS`] steps.
///
/// The fallback of [`invert_on_panels`]. Each length covers part of one panel
/// only, and it is not cut again: the panel lies between two consecutive
/// cuts of the pass that produced it (or in a range where the speed is
/// bounded away from zero), so it holds no speed minimum the cut search
/// found.
fn invert_in_panel_adaptively(
    speed: &mut Speed<'_>,
    panel: &Panel,
    forward: bool,
    remaining: f64,
    accuracy: f64,
) -> f64 {
    let (near, far) = if forward {
        (panel.a, panel.b)
    } else {
        (panel.b, panel.a)
    };
    if remaining == 0.0 {
        return near;
    }
    let sign = if forward { 1.0 } else { -1.0 };
    // f(t) = int_near^t |H| (unsigned) - remaining: negative at `inside`,
    // positive at `beyond`.
    let (mut inside, mut beyond) = (near, far);
    let mut t = near + (far - near) * (remaining / panel.length);
    for _ in 0..ADAPTIVE_NEWTON_STEPS {
        let (lo, hi) = if near < t { (near, t) } else { (t, near) };
        let mut tree = QuadratureTree::with_cuts(vec![lo, hi], speed.noise_per_unit);
        let f = tree.pass(speed, 0.1 * accuracy, None).length - remaining;
        if f.abs() <= 0.8 * accuracy {
            return t;
        }
        if f > 0.0 {
            beyond = t;
        } else {
            inside = t;
        }
        let v = speed.at(t);
        let newton = t - f / (sign * v);
        let (lo, hi) = if inside < beyond {
            (inside, beyond)
        } else {
            (beyond, inside)
        };
        let next = if v > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        // The parameters' rounding level on [0, 1], as the fallback from
        // `start` has it (a relative width would bisect on towards the
        // denormals near t = 0, each step a full adaptive length).
        if next == t || hi - lo <= 4.0 * f64::EPSILON {
            return next;
        }
        t = next;
    }
    t
}

pub(crate) fn arc_length_with(hodograph: &BezierCurve, a: f64, b: f64, accuracy: f64) -> f64 {
    arc_length_counted(hodograph, a, b, accuracy).0
}

fn arc_length_counted(hodograph: &BezierCurve, a: f64, b: f64, accuracy: f64) -> (f64, usize) {
    let result = arc_length_panels(hodograph, a, b, accuracy, None);
    (result.length, result.evaluations)
}

/// The length and the number of speed evaluations it took.
///
/// The range is first cut at the local minima of the speed inside it
/// ([`speed_minima`]): at a cusp `|P'|` has a kink, and an adaptive rule
/// that compares one interval with its two halves can be fooled there (the
/// kink sits at nearly the same relative place in both, so both estimates
/// carry the same error; measured 1.5e-5 wrong with the halves agreeing to
/// 1e-13). Near-cusps (small nonzero speed at a minimum) fool it the same
/// way; there the pieces are graded towards the minimum
/// ([`grade_at_near_cusps`]). Each piece gets the share of `accuracy` of
/// its width.
///
/// The cut search is skipped when the speed is provably bounded away from
/// zero on the range ([`speed_bounded_away_from_zero`]): then `|H|` is
/// smooth (no kink), and the adaptive rule alone is reliable.
///
/// With `panels`, the accepted intervals are appended to it in increasing
/// order of `t` (each with its value and its share of the accuracy): the
/// cumulative table that [`BezierCurve::param_at_length`] inverts. (A
/// fresh [`QuadratureTree`]'s pass.)
fn arc_length_panels(
    hodograph: &BezierCurve,
    a: f64,
    b: f64,
    accuracy: f64,
    panels: Option<&mut Vec<Panel>>,
) -> LengthResult {
    if a == b {
        return LengthResult {
            length: 0.0,
            evaluations: 0,
            unresolved: 0.0,
        };
    }
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    let mut tree = QuadratureTree::new(hodograph, lo, hi);
    let mut speed = Speed::new(hodograph, tree.noise_per_unit);
    let result = tree.pass(&mut speed, accuracy, panels);
    LengthResult {
        length: if a < b { result.length } else { -result.length },
        ..result
    }
}

/// What one adaptive length computation produced.
struct LengthResult {
    /// The signed length.
    length: f64,
    /// Speed evaluations spent.
    evaluations: usize,
    /// Error the rule could not resolve within its budget (0 when it met
    /// the accuracy everywhere).
    unresolved: f64,
}

/// Rounding-noise bound of `|H(t)|` per unit of `t` on `[lo, hi]`: the
/// Bernstein-Horner evaluation of a degree-`n` hodograph errs by at most
/// about `(n + 1) eps max|H_i| sum_i |B_i(t)|`, and `sum_i |B_i(t)| =
/// (|1 - t| + |t|)^n` (1 inside `[0, 1]`, growing outside). A factor 4 covers
/// the norm and the quadrature weights.
fn speed_noise_per_unit(hodograph: &BezierCurve, lo: f64, hi: f64) -> f64 {
    let n = hodograph.degree();
    let growth = |t: f64| ((1.0 - t).abs() + t.abs()).powi(n as i32);
    let size = hodograph.coordinate_scale() * (hodograph.dim() as f64).sqrt();
    4.0 * (n + 1) as f64 * f64::EPSILON * size * growth(lo).max(growth(hi))
}

/// The length, or `IllConditioned` when the adaptive rule could not reach
/// `accuracy` within its budget.
fn arc_length_checked(hodograph: &BezierCurve, a: f64, b: f64, accuracy: f64) -> Result<f64> {
    let result = arc_length_panels(hodograph, a, b, accuracy, None);
    check_resolved(&result, a, b, accuracy)?;
    Ok(result.length)
}

fn check_resolved(result: &LengthResult, a: f64, b: f64, accuracy: f64) -> Result<()> {
    if result.unresolved > accuracy {
        let size = result.length.abs().max(f64::MIN_POSITIVE);
        return Err(BezjoinError::IllConditioned {
            what: format!("arc length from t = {a} to t = {b}"),
            estimate: (result.unresolved + accuracy) / size,
            limit: accuracy / size,
        });
    }
    Ok(())
}

/// Fraction of the largest hodograph control point that the speed must
/// provably exceed for [`speed_bounded_away_from_zero`] to skip the cut
/// search.
const SPEED_MARGIN: f64 = 0.1;

/// True when `lo..hi` lies in `[0, 1]` and the hodograph's control polygon
/// stays on one side of a plane through the origin with margin: with `u`
/// the unit mean of the control points `H_i`, `u . H_i >= SPEED_MARGIN *
/// max |H_j|` for all `i`. Then `|H(t)| >= u . H(t) >= SPEED_MARGIN * max
/// |H_j|` on `[0, 1]` (convex hull property), so the speed has no zero and
/// no sharp minimum there. Costs one pass over the control points.
pub(crate) fn speed_bounded_away_from_zero(hodograph: &BezierCurve, lo: f64, hi: f64) -> bool {
    if lo < 0.0 || hi > 1.0 {
        return false;
    }
    speed_bounds_away_from_zero(hodograph).is_some()
}

/// The bounds behind [`speed_bounded_away_from_zero`] on `[0, 1]`: `(low,
/// high)` with `low <= |H(t)| <= high` there (`low = min_i u . H_i`, `high =
/// max_i |H_i|`), when `low >= SPEED_MARGIN * high`; `None` otherwise.
pub(crate) fn speed_bounds_away_from_zero(hodograph: &BezierCurve) -> Option<(f64, f64)> {
    let d = hodograph.dim();
    let n = hodograph.degree() + 1;
    let mut mean = vec![0.0; d];
    for i in 0..n {
        for (m, x) in mean.iter_mut().zip(hodograph.point(i)) {
            *m += x;
        }
    }
    let mean_norm = norm(&mean);
    if !(mean_norm > 0.0 && mean_norm.is_finite()) {
        return None;
    }
    let mut min_along = f64::INFINITY;
    let mut max_norm = 0.0f64;
    for i in 0..n {
        let p = hodograph.point(i);
        let along: f64 = p.iter().zip(&mean).map(|(x, m)| x * m).sum::<f64>() / mean_norm;
        min_along = min_along.min(along);
        max_norm = max_norm.max(norm(p));
    }
    (max_norm.is_finite() && min_along >= SPEED_MARGIN * max_norm).then_some((min_along, max_norm))
}

/// Highest hodograph degree for which [`speed_minima`] splits the range
/// (its Bernstein product coefficients use binomials, exact far beyond).
const MINIMA_MAX_DEGREE: usize = 200;

/// Parameters in `(lo, hi)` where the speed `|H(t)|` has a local minimum
/// (`H . H'` changes sign from - to +), located by Bernstein subdivision
/// (variation diminishing: no sign change of the coefficients, no root)
/// to a relative width of `2^-44`. Empty above [`MINIMA_MAX_DEGREE`].
pub(crate) fn speed_minima(hodograph: &BezierCurve, lo: f64, hi: f64) -> Vec<f64> {
    let p = hodograph.degree();
    if p == 0 || p > MINIMA_MAX_DEGREE || hi <= lo {
        return Vec::new();
    }
    let d = hodograph.dim();
    // H on [lo, hi] as a Bezier curve in s in [0, 1], and its derivative in s.
    let h = hodograph.segment_unchecked(lo, hi);
    let g = h.hodograph();
    let q = p - 1;
    // f(s) = H(s) . H'(s), degree p + q, Bernstein coefficients.
    let deg = p + q;
    // The binomials once each (O(n^2) instead of O(n^3) for the double loop).
    let binomials = |n: usize| (0..=n).map(|k| binomial(n, k)).collect::<Vec<f64>>();
    let (cp, cq, cdeg) = (binomials(p), binomials(q), binomials(deg));
    let mut coefficients = vec![0.0; deg + 1];
    for i in 0..=p {
        for j in 0..=q {
            let w = cp[i] * cq[j] / cdeg[i + j];
            let dot: f64 = (0..d).map(|c| h.point(i)[c] * g.point(j)[c]).sum();
            coefficients[i + j] += w * dot;
        }
    }
    if coefficients.iter().any(|c| !c.is_finite()) {
        return Vec::new();
    }
    let mut roots = Vec::new();
    let mut budget = 4096usize;
    isolate(&coefficients, 0.0, 1.0, &mut roots, &mut budget);
    roots
        .into_iter()
        .map(|s| lo + s * (hi - lo))
        .filter(|&t| t > lo && t < hi)
        .collect()
}

/// Append to `roots` the points in `(s0, s1)` where the Bernstein polynomial
/// with `coefficients` on `[s0, s1]` goes from negative to positive.
fn isolate(coefficients: &[f64], s0: f64, s1: f64, roots: &mut Vec<f64>, budget: &mut usize) {
    if *budget == 0 {
        return;
    }
    *budget -= 1;
    let first = coefficients[0];
    let last = coefficients[coefficients.len() - 1];
    let mut changes = 0;
    let mut sign = 0.0f64;
    for &c in coefficients {
        if c != 0.0 {
            if sign != 0.0 && c.signum() != sign {
                changes += 1;
            }
            sign = c.signum();
        }
    }
    if changes == 0 {
        return;
    }
    // One sign change: exactly one root in (s0, s1) (the Bernstein
    // coefficients' variation bounds the roots' count, and the end values
    // have opposite signs). Bisection on values to the same width as the
    // subdivision below, O(n) per step instead of O(n^2).
    if changes == 1 && first != 0.0 && last != 0.0 {
        if first < 0.0 && last > 0.0 {
            let n = coefficients.len() - 1;
            let (mut a, mut b) = (0.0f64, 1.0f64);
            let mut value = [0.0];
            while (b - a) * (s1 - s0) > 2f64.powi(-44) {
                let m = 0.5 * (a + b);
                bernstein_horner(coefficients, n, 1, m, 1.0, &mut value);
                if value[0] < 0.0 {
                    a = m;
                } else if value[0] > 0.0 {
                    b = m;
                } else {
                    (a, b) = (m, m);
                }
            }
            roots.push(s0 + 0.5 * (a + b) * (s1 - s0));
        }
        return;
    }
    if s1 - s0 <= 2f64.powi(-44) {
        if last > 0.0 && (first < 0.0 || changes % 2 == 1) {
            roots.push(0.5 * (s0 + s1));
        }
        return;
    }
    // de Casteljau at 1/2.
    let n = coefficients.len() - 1;
    let mut w = coefficients.to_vec();
    let mut left = Vec::with_capacity(n + 1);
    let mut right = vec![0.0; n + 1];
    left.push(w[0]);
    right[n] = w[n];
    for level in 1..=n {
        for i in 0..=(n - level) {
            w[i] = 0.5 * (w[i] + w[i + 1]);
        }
        left.push(w[0]);
        right[n - level] = w[n - level];
    }
    let mid = 0.5 * (s0 + s1);
    isolate(&left, s0, mid, roots, budget);
    isolate(&right, mid, s1, roots, budget);
}

/// Chebyshev-Lobatto intervals of the Chebyshev inversion's two levels: the
/// speed is first sampled at `CHEBYSHEV_LEVELS[0] + 1` points, and only
/// when that interpolant cannot be certified at the `CHEBYSHEV_LEVELS[1] +
/// 1` points of the finer level, which contain the first level's (every
/// other one), so the first samples are kept.
const CHEBYSHEV_LEVELS: [usize; 2] = [24, 48];

/// The finer level's intervals: the sample buffer's size and the node grid.
pub(crate) const CHEBYSHEV_MAX_N: usize = CHEBYSHEV_LEVELS[1];

/// Largest `(degree + 1) * dim` of a hodograph the Chebyshev inversion
/// keeps on the stack (degree 15 in 4D, degree 31 in 2D).
const CHEBYSHEV_MAX_POINTS: usize = 64;

/// Largest dimension of the Chebyshev inversion.
const CHEBYSHEV_MAX_DIM: usize = 8;

/// Share of the inversion's `accuracy` given to the interpolant's error
/// estimate; the residual gets [`CHEBYSHEV_RESIDUAL_SHARE`], so the length
/// at the returned parameter errs by at most `0.75 accuracy` (or by the
/// rounding level where that is larger).
const CHEBYSHEV_ESTIMATE_SHARE: f64 = 0.25;
const CHEBYSHEV_RESIDUAL_SHARE: f64 = 0.5;

/// Share of the residual tolerance that the terms left out of the Newton
/// iteration's series may take ([`newton_terms`]).
const CHEBYSHEV_NEWTON_TAIL_SHARE: f64 = 0.125;

/// First try of the bracket: this factor times `length / |P'(start)|`.
const CHEBYSHEV_FIRST_WIDTH: f64 = 1.25;

/// Columns of the two levels' matrices (`n/2 + 1`).
const CHEBYSHEV_COLUMNS_0: usize = CHEBYSHEV_LEVELS[0] / 2 + 1;
const CHEBYSHEV_COLUMNS_1: usize = CHEBYSHEV_LEVELS[1] / 2 + 1;

/// The interpolation matrices of the Chebyshev inversion, one per level of
/// `n` intervals, folded twice. By `cos(pi (n - j) k / n) = (-1)^k cos(pi j
/// k / n)`, row `k` maps the folded samples `F_j = f_j + (-1)^k f_(n-j)`,
/// `j = 0..=n/2`, to the coefficient `a_k` of the interpolant through all
/// `n + 1` samples; by `cos(pi j (n - k) / n) = (-1)^j cos(pi j k / n)`
/// (and `n - k` of the parity of `k`, `n` even), row `n - k` is row `k`
/// with the odd columns negated, so only rows `0..=n/2` are kept and
/// `a_k = E + O`, `a_(n-k) = E - O` from the even- and odd-column parts of
/// one row's product ([`fold_apply`]).
struct ChebyshevTables {
    coarse: FoldedMatrix<CHEBYSHEV_COLUMNS_0, CHEBYSHEV_PAIRS_0>,
    fine: FoldedMatrix<CHEBYSHEV_COLUMNS_1, CHEBYSHEV_PAIRS_1>,
    /// `cos(pi j / N)`, `j = 0..=N`, `N` = [`CHEBYSHEV_MAX_N`]: the finer
    /// level's nodes on `[-1, 1]`; the coarser level's node `j` is node
    /// `2 j` (the same number, so its samples are the finer level's).
    nodes: [f64; CHEBYSHEV_MAX_N + 1],
    /// `2 k` as a float, `k = 0..=N + 1` (the antiderivative's divisors).
    doubled: [f64; CHEBYSHEV_MAX_N + 2],
}

/// Row pairs of the two levels' folded matrices (`(C + 1) / 2`, the last
/// pair padded with a zero row when `C` is odd).
const CHEBYSHEV_PAIRS_0: usize = CHEBYSHEV_COLUMNS_0.div_ceil(2);
const CHEBYSHEV_PAIRS_1: usize = CHEBYSHEV_COLUMNS_1.div_ceil(2);

/// A folded matrix of [`ChebyshevTables`] stored by columns, rows in
/// pairs: `columns[j][i] = [M[2 i][j], M[2 i + 1][j]]` (an even row, which
/// multiplies the even folding, beside an odd row, which multiplies the
/// odd one), so [`fold_apply`] runs down a column on two rows at once.
struct FoldedMatrix<const C: usize, const P: usize> {
    columns: [[[f64; 2]; P]; C],
}

impl<const C: usize, const P: usize> FoldedMatrix<C, P> {
    fn from_rows(rows: &[[f64; C]; C]) -> Self {
        let mut columns = [[[0.0; 2]; P]; C];
        for (k, row) in rows.iter().enumerate() {
            for (j, &entry) in row.iter().enumerate() {
                columns[j][k / 2][k % 2] = entry;
            }
        }
        FoldedMatrix { columns }
    }
}

/// Rows `0..=n/2` of the matrix of [`ChebyshevTables`] for `n = 2 (C -
/// 1)` intervals: `(2 / n) w_j cos(pi j k / n)` with `w_0 = 1/2` (the end
/// samples' half weight), `w_(n/2) = 1/2` (the middle sample, counted twice
/// by the folding), row `0` halved (the interpolant's end coefficients `a_0`
/// and, by the second folding, `a_n`).
fn folded_matrix<const C: usize>() -> [[f64; C]; C] {
    let n = 2 * (C - 1);
    let mut matrix = [[0.0; C]; C];
    for (k, row) in matrix.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            let mut w = 2.0 / n as f64;
            if j == 0 || 2 * j == n {
                w *= 0.5;
            }
            if k == 0 {
                w *= 0.5;
            }
            *entry = w * (std::f64::consts::PI * ((j * k) % (2 * n)) as f64 / n as f64).cos();
        }
    }
    matrix
}

fn chebyshev_tables() -> &'static ChebyshevTables {
    static TABLES: std::sync::OnceLock<ChebyshevTables> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let mut nodes = [0.0; CHEBYSHEV_MAX_N + 1];
        for (j, x) in nodes.iter_mut().enumerate() {
            *x = (std::f64::consts::PI * j as f64 / CHEBYSHEV_MAX_N as f64).cos();
        }
        nodes[CHEBYSHEV_MAX_N / 2] = 0.0;
        ChebyshevTables {
            coarse: FoldedMatrix::from_rows(&folded_matrix()),
            fine: FoldedMatrix::from_rows(&folded_matrix()),
            nodes,
            doubled: std::array::from_fn(|k| (2 * k) as f64),
        }
    })
}

/// The coefficients `out[k] = a_k`, `k = 0..=n`, of the interpolant through
/// the samples `f_0..=f_n` (`samples(j)`, `n = 2 (C - 1)`), by the twice
/// folded `matrix` of [`ChebyshevTables`]: `(n/2 + 1)^2` products instead
/// of `(n + 1)^2`.
///
/// Row `k`'s product `sum_j M[k][j] F_j` is summed in four partial sums,
/// by `j mod 4` (`j = 0, 4, ..`, `1, 5, ..`, `2, 6, ..`, `3, 7, ..`, each
/// in increasing `j`); `E` is the first plus the third, `O` the second plus
/// the fourth. The partial sums of all rows are carried together, one
/// column at a time and two rows per step (an even and an odd row, whose
/// foldings are the two lanes of `[F_even_j, F_odd_j]`), so the loop has
/// no branch and the compiler pairs the lanes.
/// Coefficients of the level's interpolant `p_n = sum_k a_k T_k` (two
/// zeros past the end for the antiderivative's recurrence) from the speed
/// samples on the grid (the level's node `j` at index `j * step`), into
/// `a` (zeros on entry).
fn level_coefficients(
    tables: &ChebyshevTables,
    level: usize,
    samples: &[f64; CHEBYSHEV_MAX_N + 1],
    step: usize,
    a: &mut [f64; CHEBYSHEV_MAX_N + 3],
) {
    let sample = |j: usize| samples[j * step];
    if level == 0 {
        fold_apply(&tables.coarse, sample, a);
    } else {
        fold_apply(&tables.fine, sample, a);
    }
}

fn fold_apply<const C: usize, const P: usize>(
    matrix: &FoldedMatrix<C, P>,
    samples: impl Fn(usize) -> f64,
    out: &mut [f64],
) {
    let n = 2 * (C - 1);
    let mut folded = [[0.0; 2]; C];
    for (j, pair) in folded.iter_mut().enumerate() {
        let (f, g) = (samples(j), samples(n - j));
        *pair = [f + g, f - g];
    }
    let mut partial = [[[0.0f64; 2]; P]; 4];
    for (class, sums) in partial.iter_mut().enumerate() {
        let mut j = class;
        while j < C {
            let column = &matrix.columns[j];
            let v = folded[j];
            for (sum, entry) in sums.iter_mut().zip(column) {
                sum[0] += entry[0] * v[0];
                sum[1] += entry[1] * v[1];
            }
            j += 4;
        }
    }
    let out = &mut out[..=n];
    for k in 0..C {
        let (i, lane) = (k / 2, k % 2);
        let e = partial[0][i][lane] + partial[2][i][lane];
        let o = partial[1][i][lane] + partial[3][i][lane];
        out[k] = e + o;
        if 2 * k < n {
            out[n - k] = e - o;
        }
    }
}

/// The speed `|P'(t)|` on `[0, 1]` of a curve whose hodograph's control
/// polygon keeps the speed provably away from zero
/// ([`speed_bounded_away_from_zero`]: no cusp, no kink of `|P'|`, which is
/// then analytic on `[0, 1]`), for the Chebyshev inversion
/// ([`ChebyshevSampled::param_at_length`]). The hodograph is kept once as
/// its binomial-weighted control points `C(m, i) H_i` on the stack, so an
/// evaluation is one Horner pass with no allocation.
struct ChebyshevSpeed {
    weighted: [f64; CHEBYSHEV_MAX_POINTS],
    /// Hodograph degree `m` and dimension.
    degree: usize,
    dim: usize,
    /// `|P'(t)| >= low` on `[0, 1]` (the polygon's projection bound) and
    /// `|P'(t)| <= high` (convex hull).
    low: f64,
    high: f64,
    /// [`speed_noise_per_unit`] on `[0, 1]`.
    noise_per_unit: f64,
}

impl ChebyshevSpeed {
    /// `None` when the curve does not qualify: degree 0, a hodograph larger
    /// than the stack buffer, non-finite points, or a speed not provably
    /// bounded away from zero.
    #[cfg(test)]
    fn new(curve: &BezierCurve) -> Option<Self> {
        let mut speed = Self::zeroed();
        speed.fill(curve).then_some(speed)
    }

    /// No curve yet: every field zero (the rows past the hodograph's stay
    /// zero after [`Self::fill`]).
    fn zeroed() -> Self {
        ChebyshevSpeed {
            weighted: [0.0; CHEBYSHEV_MAX_POINTS],
            degree: 0,
            dim: 0,
            low: 0.0,
            high: 0.0,
            noise_per_unit: 0.0,
        }
    }

    /// `Self::new` (test-only) written into a zeroed `self` in place (no copy of the
    /// buffer): `false` when the curve does not qualify (`self` then means
    /// nothing).
    fn fill(&mut self, curve: &BezierCurve) -> bool {
        // Cubics in the plane and in space with the sizes as constants
        // (the loops unrolled); the same operations as the general case.
        match (curve.degree(), curve.dim()) {
            (3, 2) => self.fill_sized(curve, 3, 2),
            (3, 3) => self.fill_sized(curve, 3, 3),
            (n, d) => self.fill_sized(curve, n, d),
        }
    }

    /// [`Self::fill`] for degree `n` and dimension `d` of `curve`. The
    /// hodograph `H_i` is formed in `weighted` and scaled there by `C(m,
    /// i)` once it has passed the checks.
    #[inline(always)]
    fn fill_sized(&mut self, curve: &BezierCurve, n: usize, d: usize) -> bool {
        if n == 0 || d > CHEBYSHEV_MAX_DIM || n * d > CHEBYSHEV_MAX_POINTS {
            return false;
        }
        let points = &curve.points()[..(n + 1) * d];
        let m = n - 1;
        let weighted = &mut self.weighted[..n * d];
        for i in 0..n {
            for c in 0..d {
                weighted[i * d + c] = n as f64 * (points[(i + 1) * d + c] - points[i * d + c]);
            }
        }
        let h = &*weighted;
        if h.iter().any(|x| !x.is_finite()) {
            return false;
        }
        // The bound of `speed_bounded_away_from_zero`, with its margin.
        let mut mean = [0.0; CHEBYSHEV_MAX_DIM];
        for i in 0..n {
            for c in 0..d {
                mean[c] += h[i * d + c];
            }
        }
        let mean_norm = norm(&mean[..d]);
        if !(mean_norm > 0.0 && mean_norm.is_finite()) {
            return false;
        }
        let mut low = f64::INFINITY;
        let mut high = 0.0f64;
        for i in 0..n {
            let p = &h[i * d..(i + 1) * d];
            let along: f64 = p.iter().zip(&mean).map(|(x, u)| x * u).sum::<f64>() / mean_norm;
            low = low.min(along);
            high = high.max(norm(p));
        }
        if !(high.is_finite() && low >= SPEED_MARGIN * high && low > 0.0) {
            return false;
        }
        let scale = h
            .iter()
            .fold(0.0f64, |s, x| s.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        // `C(m, i)` by `C(m, i + 1) = C(m, i) (m - i) / (i + 1)` up to
        // `m = 50`: exact integers there (every product `C(m, i + 1) (i +
        // 1)` is below `2^53`), so the values of `binomial`; above, `binomial`.
        let mut w = 1.0f64;
        for i in 0..=m {
            if m > 50 {
                w = binomial(m, i);
            }
            for c in 0..d {
                weighted[i * d + c] *= w;
            }
            w = w * (m - i) as f64 / (i + 1) as f64;
        }
        if weighted.iter().any(|x| !x.is_finite()) {
            return false;
        }
        self.degree = m;
        self.dim = d;
        self.low = low;
        self.high = high;
        self.noise_per_unit = 4.0 * n as f64 * f64::EPSILON * scale * (d as f64).sqrt();
        true
    }

    /// `|P'(t)|` for `t` in `[0, 1]`: Bernstein-Horner in `t / (1 - t)` or
    /// `(1 - t) / t`, whichever is at most 1 (the scheme of
    /// [`BezierCurve::eval`]), with the dimension fixed at compile time for
    /// the plane and space.
    #[inline(always)]
    fn at(&self, t: f64) -> f64 {
        match self.dim {
            2 => self.at_exact::<2>(t),
            3 => self.at_exact::<3>(t),
            _ => self.at_in::<CHEBYSHEV_MAX_DIM>(t),
        }
    }

    /// [`Self::at`] for `D == dim`: the rows of `weighted` are read in place
    /// in chunks of `D` (no copies into padded rows). The same operations
    /// in the same order as [`Self::at_in`], so the same value to the bit.
    #[inline(always)]
    fn at_exact<const D: usize>(&self, t: f64) -> f64 {
        let m = self.degree;
        let rows = self.weighted[..(m + 1) * D].chunks_exact(D);
        let s = 1.0 - t;
        let (r, factor) = if t <= 0.5 { (t / s, s) } else { (s / t, t) };
        let mut acc = [0.0; D];
        let step = |acc: &mut [f64; D], p: &[f64]| {
            for (a, x) in acc.iter_mut().zip(p) {
                *a = *a * r + x;
            }
        };
        if t <= 0.5 {
            acc.copy_from_slice(&self.weighted[m * D..(m + 1) * D]);
            for p in rows.take(m).rev() {
                step(&mut acc, p);
            }
        } else {
            acc.copy_from_slice(&self.weighted[..D]);
            for p in rows.skip(1) {
                step(&mut acc, p);
            }
        }
        let mut power = 1.0;
        for _ in 0..m {
            power *= factor;
        }
        norm(&acc) * power
    }

    /// The speed at the grid nodes `i = first, first + step, ..` below
    /// [`CHEBYSHEV_MAX_N`], `t = start + (nodes[i] + 1) span / 2`, into
    /// `samples[i]`; `false` at the first value that is not finite. The
    /// plane and space up to hodograph degree 4 take [`at_fixed`]
    /// (chosen once for all the nodes), the rest [`Self::at`]; the values
    /// are the same to the bit.
    fn sample(
        &self,
        nodes: &[f64; CHEBYSHEV_MAX_N + 1],
        start: f64,
        span: f64,
        first: usize,
        step: usize,
        samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    ) -> bool {
        match (self.dim, self.degree) {
            (2, 1) => self.sample_fixed::<2, 1>(nodes, start, span, first, step, samples),
            (2, 2) => self.sample_fixed::<2, 2>(nodes, start, span, first, step, samples),
            (2, 3) => self.sample_fixed::<2, 3>(nodes, start, span, first, step, samples),
            (2, 4) => self.sample_fixed::<2, 4>(nodes, start, span, first, step, samples),
            (3, 1) => self.sample_fixed::<3, 1>(nodes, start, span, first, step, samples),
            (3, 2) => self.sample_fixed::<3, 2>(nodes, start, span, first, step, samples),
            (3, 3) => self.sample_fixed::<3, 3>(nodes, start, span, first, step, samples),
            (3, 4) => self.sample_fixed::<3, 4>(nodes, start, span, first, step, samples),
            _ => sample_nodes((nodes, start, span, first, step), samples, |t| self.at(t)),
        }
    }

    /// [`Self::sample`] for dimension `D` and hodograph degree `M`: the
    /// rows copied once into a local array, the loops of
    /// [`Self::at_exact`] unrolled.
    fn sample_fixed<const D: usize, const M: usize>(
        &self,
        nodes: &[f64; CHEBYSHEV_MAX_N + 1],
        start: f64,
        span: f64,
        first: usize,
        step: usize,
        samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    ) -> bool {
        let mut rows = [[0.0f64; D]; 5];
        for (row, w) in rows
            .iter_mut()
            .zip(self.weighted.chunks_exact(D))
            .take(M + 1)
        {
            row.copy_from_slice(w);
        }
        sample_nodes((nodes, start, span, first, step), samples, |t| {
            at_fixed::<D, M>(&rows, t)
        })
    }

    /// [`Self::at`] in `D >= dim` coordinates (the unused ones stay 0).
    #[inline(always)]
    fn at_in<const D: usize>(&self, t: f64) -> f64 {
        let (m, d) = (self.degree, self.dim.min(D));
        let w = &self.weighted;
        let row = |i: usize| {
            let mut p = [0.0; D];
            p[..d].copy_from_slice(&w[i * self.dim..i * self.dim + d]);
            p
        };
        let s = 1.0 - t;
        let (r, factor, mut acc) = if t <= 0.5 {
            (t / s, s, row(m))
        } else {
            (s / t, t, row(0))
        };
        for k in 1..=m {
            let p = if t <= 0.5 { row(m - k) } else { row(k) };
            for c in 0..D {
                acc[c] = acc[c] * r + p[c];
            }
        }
        let mut power = 1.0;
        for _ in 0..m {
            power *= factor;
        }
        norm(&acc[..d]) * power
    }
}

impl ChebyshevSampled for ChebyshevSpeed {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    #[inline(always)]
    fn speed_at(&self, t: f64) -> f64 {
        self.at(t)
    }

    fn speed_bounds(&self) -> (f64, f64) {
        (self.low, self.high)
    }

    fn noise_per_unit(&self) -> f64 {
        self.noise_per_unit
    }

    #[inline(always)]
    fn sample_speeds(
        &self,
        nodes: &[f64; CHEBYSHEV_MAX_N + 1],
        start: f64,
        span: f64,
        first: usize,
        step: usize,
        samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    ) -> bool {
        self.sample(nodes, start, span, first, step, samples)
    }
}

/// A speed the Chebyshev inversion runs on: the polynomial
/// [`ChebyshevSpeed`] on `[0, 1]`, and a rational NURBS span's speed on its
/// knot interval (`nurbs::length`). Its implementor vouches that the speed
/// is analytic on [`Self::domain`] (no kink: provably bounded away from
/// zero) and lies within [`Self::speed_bounds`] there.
pub(crate) trait ChebyshevSampled {
    /// The parameter interval `[lo, hi]` of the speed.
    fn domain(&self) -> (f64, f64);

    /// The speed at `t` in the domain.
    fn speed_at(&self, t: f64) -> f64;

    /// `(low, high)` with `low <= speed <= high` on the domain, `low > 0`.
    fn speed_bounds(&self) -> (f64, f64);

    /// Rounding-noise bound of the speed's evaluation per unit of the
    /// parameter ([`speed_noise_per_unit`]).
    fn noise_per_unit(&self) -> f64;

    /// The speed at the grid nodes `i = first, first + step, ..` below
    /// [`CHEBYSHEV_MAX_N`], `t = start + (nodes[i] + 1) span / 2`, into
    /// `samples[i]`; `false` at the first value that is not finite.
    fn sample_speeds(
        &self,
        nodes: &[f64; CHEBYSHEV_MAX_N + 1],
        start: f64,
        span: f64,
        first: usize,
        step: usize,
        samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    ) -> bool;

    /// The parameter at signed arc length `length != 0` from `start` in
    /// the domain (`[0, 1]` for a Bezier curve), certified to `accuracy`,
    /// or `None` (then the adaptive path answers, including every error).
    ///
    /// The speed is sampled at the `n + 1` Chebyshev-Lobatto points of a
    /// bracket `[start, far]` (first `1.25 length / |P'(start)|` wide, then
    /// `length / low`, which holds the answer by the speed bound, each at
    /// most up to the domain's end), `n = 24`, and `n = 48` (24 more samples
    /// between the first) only when the first level cannot be certified.
    /// The interpolant `p_n` is integrated in closed form (Chebyshev
    /// series), and Newton's method safeguarded by bisection solves
    /// `int_start^t p_n = |length|` on that polynomial, without further
    /// speed evaluations (Trefethen, *Approximation Theory and Approximation
    /// Practice*, ch. 3 and 19).
    ///
    /// The check, as the adaptive rule's (a rule against a refined one): the
    /// interpolant `p_(n/2)` through every other sample differs from `p_n`
    /// by at most `sum_k |a_k - b_k|` on the bracket (Chebyshev polynomials
    /// are bounded by 1), so their lengths at `t` differ by at most `|t -
    /// start|` times that; the answer is accepted when this is within a
    /// quarter of `accuracy` (or the rounding level of the length and of the
    /// speed's evaluation, [`rounding_level`], [`speed_noise_per_unit`])
    /// and the residual, recomputed at the returned `t`, within half of it.
    /// `sum_k |a_k - b_k|` is `2 sum_(k > n/2) |a_k|` ([`coarse_difference`]:
    /// at the even nodes `T_k = T_(n-k)`, so `b_k = a_k + a_(n-k)`), so
    /// `p_(n/2)` is never formed.
    fn param_at_length(&self, start: f64, length: f64, accuracy: f64) -> Option<f64> {
        let target = length.abs();
        let forward = length > 0.0;
        let (domain_lo, domain_hi) = self.domain();
        let room = if forward {
            domain_hi - start
        } else {
            start - domain_lo
        };
        if !(room > 0.0 && target.is_finite()) {
            return None;
        }
        let at_start = self.speed_at(start);
        let (low, high) = self.speed_bounds();
        let bound = target / low;
        let first = (CHEBYSHEV_FIRST_WIDTH * target / at_start).max(target / high);
        let mut samples = [0.0; CHEBYSHEV_MAX_N + 1];
        samples[CHEBYSHEV_MAX_N] = at_start;
        for width in [first.min(bound), bound] {
            let (width, far) = if width >= room || !width.is_finite() {
                (room, if forward { domain_hi } else { domain_lo })
            } else {
                (
                    width,
                    if forward {
                        start + width
                    } else {
                        start - width
                    },
                )
            };
            let answer = self.invert_on(start, far, target, accuracy, &mut samples);
            if answer.is_some() || width == room || width >= bound {
                return answer.flatten();
            }
        }
        None
    }

    /// `int_start^far |P'|` (`start <= far`) by the Chebyshev interpolant
    /// of the speed on `[start, far]` integrated in closed form, certified
    /// as [`Self::param_at_length`] certifies an answer: the interpolant
    /// through every other sample differs from it by at most
    /// `coarse_difference`, so the two lengths differ by at most `(far -
    /// start)` times that, accepted within a quarter of `accuracy` (or the
    /// rounding level of the length and of the speed's evaluation); 25
    /// samples, 49 when those do not certify; `None` when neither does.
    fn length_between(&self, start: f64, far: f64, accuracy: f64) -> Option<f64> {
        let tables = chebyshev_tables();
        let span = far - start;
        if span.is_nan() || span <= 0.0 {
            return None;
        }
        let mut samples = [0.0; CHEBYSHEV_MAX_N + 1];
        samples[CHEBYSHEV_MAX_N] = self.speed_at(start);
        for (level, &n) in CHEBYSHEV_LEVELS.iter().enumerate() {
            let step = CHEBYSHEV_MAX_N / n;
            let new = if level == 0 { step } else { 2 * step };
            let first_new = if level == 0 { 0 } else { step };
            if !self.sample_speeds(&tables.nodes, start, span, first_new, new, &mut samples) {
                return None;
            }
            let mut a = [0.0; CHEBYSHEV_MAX_N + 3];
            level_coefficients(tables, level, &samples, step, &mut a);
            // The antiderivative's value at x = 1 with G(-1) = 0: `G(1) -
            // G(-1) = sum_k c_k (1 - (-1)^k)` over k >= 1, i.e. twice the
            // odd coefficients (c_k = (a_(k-1) - a_(k+1)) / 2k, c_1 = a_0 -
            // a_2 / 2).
            let mut odd = a[0] - 0.5 * a[2];
            let mut k = 3;
            while k <= n + 1 {
                odd += (a[k - 1] - a[k + 1]) / (2 * k) as f64;
                k += 2;
            }
            let total = span * odd;
            if !total.is_finite() {
                return None;
            }
            let estimate = span * coarse_difference(&a, n);
            let floor = rounding_level(total, span) + self.noise_per_unit() * span;
            if estimate <= (CHEBYSHEV_ESTIMATE_SHARE * accuracy).max(floor) {
                return Some(total);
            }
        }
        None
    }

    /// One bracket `[start, far]` of [`Self::param_at_length`]: `None` when
    /// the length there is shorter than `target` (try a wider bracket),
    /// `Some(None)` when the answer is inside but not certified at either
    /// level. `samples[CHEBYSHEV_MAX_N]` holds the speed at `start`.
    fn invert_on(
        &self,
        start: f64,
        far: f64,
        target: f64,
        accuracy: f64,
        samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    ) -> Option<Option<f64>> {
        let tables = chebyshev_tables();
        let span = far - start;
        for (level, &n) in CHEBYSHEV_LEVELS.iter().enumerate() {
            // Grid index of this level's node j: j * step; the coarser
            // level's samples are every other one of the finer level's.
            let step = CHEBYSHEV_MAX_N / n;
            let new = if level == 0 { step } else { 2 * step };
            let first_new = if level == 0 { 0 } else { step };
            // x = cos(pi j / N) in [-1, 1] is t = start + (x + 1) span / 2:
            // x = -1 at `start` (the last sample, already taken), x = 1 at
            // `far`.
            if !self.sample_speeds(&tables.nodes, start, span, first_new, new, samples) {
                return Some(None);
            }
            let mut a = [0.0; CHEBYSHEV_MAX_N + 3];
            level_coefficients(tables, level, samples, step, &mut a);
            let inverted = if level == 0 {
                invert_level::<{ CHEBYSHEV_LEVELS[0] }>(
                    &a,
                    start,
                    far,
                    target,
                    accuracy,
                    self.noise_per_unit(),
                )
            } else {
                invert_level::<{ CHEBYSHEV_LEVELS[1] }>(
                    &a,
                    start,
                    far,
                    target,
                    accuracy,
                    self.noise_per_unit(),
                )
            };
            match inverted {
                // Too short a bracket, or an answer: done with this bracket.
                None => return None,
                Some(Some(t)) => return Some(Some(t)),
                Some(None) => {}
            }
        }
        Some(None)
    }
}

/// `speed` at the nodes `first, first + step, ...` below
/// [`CHEBYSHEV_MAX_N`] (`t = start + (nodes[i] + 1) span / 2`) into
/// `samples[i]`; `false` at the first value that is not finite. The loop
/// of both sampling routes of [`ChebyshevSpeed::sample`].
#[inline(always)]
pub(crate) fn sample_nodes(
    (nodes, start, span, first, step): (&[f64; CHEBYSHEV_MAX_N + 1], f64, f64, usize, usize),
    samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    speed: impl Fn(f64) -> f64,
) -> bool {
    let mut i = first;
    while i < CHEBYSHEV_MAX_N {
        let f = speed(start + 0.5 * (nodes[i] + 1.0) * span);
        if !f.is_finite() {
            return false;
        }
        samples[i] = f;
        i += step;
    }
    true
}

/// [`ChebyshevSpeed::at_exact`] for `D` coordinates and hodograph degree
/// `M` (`rows[..=M]` its weighted rows): the same operations in the same
/// order, so the same value to the bit.
#[inline(always)]
fn at_fixed<const D: usize, const M: usize>(rows: &[[f64; D]; 5], t: f64) -> f64 {
    let s = 1.0 - t;
    let (r, factor) = if t <= 0.5 { (t / s, s) } else { (s / t, t) };
    let mut acc;
    if t <= 0.5 {
        acc = rows[M];
        for k in (0..M).rev() {
            for c in 0..D {
                acc[c] = acc[c] * r + rows[k][c];
            }
        }
    } else {
        acc = rows[0];
        for row in &rows[1..=M] {
            for c in 0..D {
                acc[c] = acc[c] * r + row[c];
            }
        }
    }
    let mut power = 1.0;
    for _ in 0..M {
        power *= factor;
    }
    norm(&acc) * power
}

/// `sum_k |a_k - b_k|` of the Chebyshev inversion's check, `b` the
/// coefficients of the interpolant through every other of the `n + 1`
/// Lobatto samples of `p_n = sum_k a_k T_k`: at the even nodes `x_(2i) =
/// cos(pi i / (n/2))` `T_k = T_(n-k)` for `k > n/2`, so `b_j = a_j +
/// a_(n-j)` for `j < n/2`, `b_(n/2) = a_(n/2)`, and the sum is `2
/// sum_(k > n/2) |a_k|`.
fn coarse_difference(a: &[f64], n: usize) -> f64 {
    2.0 * a[n / 2 + 1..=n].iter().map(|x| x.abs()).sum::<f64>()
}

/// One level of [`ChebyshevSampled::invert_on`]: `n` intervals, `a[..=n]`
/// the coefficients of the speed's interpolant `p_n` on the bracket (`x =
/// -1` at `start`), `a[n + 1] = a[n + 2] = 0`. `None` when
/// the interpolant's length on the bracket is shorter than `target`,
/// `Some(None)` when the answer is not certified.
/// `n` is fixed at compile time (`N`), so the loops over the coefficients
/// have constant bounds.
fn invert_level<const N: usize>(
    a: &[f64; CHEBYSHEV_MAX_N + 3],
    start: f64,
    far: f64,
    target: f64,
    accuracy: f64,
    noise_per_unit: f64,
) -> Option<Option<f64>> {
    let n = N;
    let span = far - start;
    let difference = coarse_difference(a, n);
    // The antiderivative G = sum_k c_k T_k with G(-1) = 0, degree n + 1.
    let mut c = [0.0; CHEBYSHEV_MAX_N + 2];
    c[1] = a[0] - 0.5 * a[2];
    // `(2 k) as f64` from a table (the same exact integers): the loop
    // has no conversions and pairs its divisions.
    let divisors = &chebyshev_tables().doubled;
    for k in 2..=n + 1 {
        c[k] = (a[k - 1] - a[k + 1]) / divisors[k];
    }
    let mut alternating = 0.0;
    for (k, ck) in c[1..=n + 1].iter().enumerate() {
        // c[k + 1]: sign (-1)^(k + 1).
        alternating += if k % 2 == 0 { -ck } else { *ck };
    }
    c[0] = -alternating;
    let a_full = a;
    let c = &c[..=n + 1];
    let half = 0.5 * span.abs();
    // `T_k(1) = 1`: the length of the whole bracket is the coefficients' sum.
    let total = half * c.iter().sum::<f64>();
    if !total.is_finite() {
        return Some(None);
    }
    if total < target {
        return None;
    }
    // Newton on x with bisection: length(x) - target, increasing.
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    let mut x = -1.0 + 2.0 * (target / total);
    let residual_tolerance = CHEBYSHEV_RESIDUAL_SHARE * accuracy;
    // The iteration runs on the series cut after `c_kept`: the terms left
    // out change the length by at most `tail` anywhere on the bracket
    // (`|T_k| <= 1`), so a truncated residual within `residual_tolerance -
    // tail` is one of the whole series within `residual_tolerance`. (The
    // answer is checked below on the whole series all the same.)
    let (kept, tail) = newton_terms(c, half, CHEBYSHEV_NEWTON_TAIL_SHARE * residual_tolerance);
    let newton_tolerance = residual_tolerance - tail;
    // `a[n + 1] = 0`: the slope's series is cut at the same index.
    let (c_kept, a_kept) = (&c[..=kept], &a_full[..=kept]);
    let mut converged = false;
    for _ in 0..PANEL_NEWTON_STEPS {
        let (length_at, speed_at) = clenshaw_pair(c_kept, a_kept, x);
        let g = half * length_at - target;
        if g.abs() <= newton_tolerance {
            converged = true;
            break;
        }
        if g > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let slope = half * speed_at;
        let newton = x - g / slope;
        let next = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == x || hi - lo <= 4.0 * f64::EPSILON {
            break;
        }
        x = next;
    }
    if !converged {
        return Some(None);
    }
    let t = (start + 0.5 * (x + 1.0) * span).clamp(start.min(far), start.max(far));
    // The residual and the estimate at the parameter returned.
    let x = if span != 0.0 {
        (2.0 * (t - start) / span - 1.0).clamp(-1.0, 1.0)
    } else {
        -1.0
    };
    let value = half * clenshaw(c, x);
    let width = (t - start).abs();
    let estimate = width * difference;
    let floor = rounding_level(value, width) + noise_per_unit * width;
    let certified = estimate <= (CHEBYSHEV_ESTIMATE_SHARE * accuracy).max(floor)
        && (value - target).abs() <= residual_tolerance;
    Some(certified.then_some(t))
}

/// The Newton iteration of [`invert_level`] runs on `c[..=kept]`:
/// `(kept, tail)`, `kept` the smallest index with `tail = half * sum_(k >
/// kept) |c_k| <= budget` (`kept = c.len() - 1`, `tail = 0` when no term can
/// be left out).
fn newton_terms(c: &[f64], half: f64, budget: f64) -> (usize, f64) {
    let mut kept = c.len() - 1;
    let mut tail = 0.0f64;
    while kept > 1 {
        let next = tail + half * c[kept].abs();
        if next > budget || next.is_nan() {
            break;
        }
        tail = next;
        kept -= 1;
    }
    (kept, tail)
}

/// `(sum_k c[k] T_k(x), sum_k a[k] T_k(x))` (`c`, `a` of the same length)
/// by two Clenshaw recurrences in one loop: each the same operations in the
/// same order as [`clenshaw`], so the same values to the bit.
fn clenshaw_pair(c: &[f64], a: &[f64], x: f64) -> (f64, f64) {
    let a = &a[..c.len()];
    let (mut b1, mut b2) = (0.0, 0.0);
    let (mut d1, mut d2) = (0.0, 0.0);
    for (&ck, &ak) in c[1..].iter().zip(&a[1..]).rev() {
        let b0 = 2.0 * x * b1 - b2 + ck;
        b2 = b1;
        b1 = b0;
        let d0 = 2.0 * x * d1 - d2 + ak;
        d2 = d1;
        d1 = d0;
    }
    (x * b1 - b2 + c[0], x * d1 - d2 + a[0])
}

/// `sum_k coefficients[k] T_k(x)` by Clenshaw's recurrence.
fn clenshaw(coefficients: &[f64], x: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &c in coefficients[1..].iter().rev() {
        let b0 = 2.0 * x * b1 - b2 + c;
        b2 = b1;
        b1 = b0;
    }
    x * b1 - b2 + coefficients[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_line_is_exact() {
        let l = BezierCurve::from_rows(&[[1.0, 2.0], [4.0, 6.0]]).unwrap();
        let len = l.arc_length(0.0, 1.0, 1e-14).unwrap();
        assert!((len - 5.0).abs() < 1e-14);
        assert!((l.arc_length(1.0, 0.25, 1e-14).unwrap() + 3.75).abs() < 1e-14);
    }

    #[test]
    fn parabola_length_matches_closed_form() {
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

#[cfg(test)]
mod rounding_floor_tests {
    use super::*;

    fn cubic() -> BezierCurve {
        BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap()
    }

    /// Length of a long extrapolated range: the default absolute accuracy is
    /// far below the rounding level of a length ~1e13. It must terminate and
    /// be accurate to rounding (reference: the same length summed over pieces
    /// split at the parameters where the integrand is smooth).
    #[test]
    fn long_range_far_below_rounding_terminates_and_is_accurate() {
        let c = cubic();
        let len = c.arc_length_default(-1e4, 1e4).unwrap();
        let mut reference = 0.0;
        let cuts = [-1e4, -1e3, -1e2, -10.0, -1.0, 0.0, 1.0, 10.0, 1e2, 1e3, 1e4];
        for w in cuts.windows(2) {
            reference += c
                .arc_length(w[0], w[1], 1e-6 * (w[1] - w[0]).abs())
                .unwrap();
        }
        assert!(
            (len - reference).abs() <= 1e-12 * reference,
            "{len} vs {reference}"
        );
    }

    #[test]
    fn work_stays_bounded_when_accuracy_is_below_rounding() {
        let c = cubic();
        let h = c.hodograph();
        let (_, evaluations) = arc_length_counted(&h, -1e4, 1e4, c.default_length_accuracy());
        assert!(evaluations < 20_000, "{evaluations} speed evaluations");
        let (_, evaluations) = arc_length_counted(&h, 0.0, 1.0, 1e-300);
        assert!(evaluations < 20_000, "{evaluations} speed evaluations");
    }

    #[test]
    fn accuracy_below_rounding_terminates() {
        let c = cubic();
        let tight = c.arc_length(0.0, 1.0, 1e-300).unwrap();
        let normal = c.arc_length(0.0, 1.0, 1e-13).unwrap();
        assert!((tight - normal).abs() <= 1e-13, "{tight} vs {normal}");
    }
}

#[cfg(test)]
mod panel_inversion_tests {
    use super::*;

    fn cubic() -> BezierCurve {
        BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap()
    }

    /// Cusp at t = 1/2 (hodograph through the origin).
    fn cusp() -> BezierCurve {
        BezierCurve::from_rows(&[[0.0, 0.0], [2.0, 1.0], [0.0, 1.0], [2.0, 0.0]]).unwrap()
    }

    /// The panel inversion itself (not the fallback) answers, and its answer
    /// has the defining property, on a smooth curve and across a cusp, both
    /// directions.
    #[test]
    fn panel_inversion_answers_and_meets_the_accuracy() {
        for c in [cubic(), cusp()] {
            let h = c.hodograph();
            for &accuracy in &[1e-6, 1e-10, 1e-13] {
                for &start in &[0.0, 0.25, 0.5, 0.8, 1.0] {
                    for forward in [true, false] {
                        let (lo, hi) = if forward { (start, 1.0) } else { (0.0, start) };
                        if lo == hi {
                            continue;
                        }
                        let mut panels = Vec::new();
                        let available =
                            arc_length_panels(&h, lo, hi, 0.1 * accuracy, Some(&mut panels)).length;
                        let sum: f64 = panels.iter().map(|p| p.length).sum();
                        assert!((sum - available).abs() <= 1e-14 * available);
                        assert!(panels.windows(2).all(|w| w[0].b <= w[1].a));
                        for &fraction in &[1e-9, 0.1, 0.37, 0.5, 0.9, 0.999_999] {
                            let target = fraction * available;
                            let mut speed = Speed::new(&h, speed_noise_per_unit(&h, lo, hi));
                            let (panel, remaining) = locate(&panels, forward, target).unwrap();
                            let t = invert_on_panels(
                                &mut speed,
                                &mut Partials::default(),
                                &panel,
                                forward,
                                remaining,
                                0.5 * accuracy,
                            )
                            .unwrap_or_else(|| {
                                panic!("no answer: start {start}, fraction {fraction}")
                            });
                            let measured = arc_length_with(&h, start, t, 1e-16).abs();
                            assert!(
                                (measured - target).abs() <= accuracy,
                                "start {start}, forward {forward}, fraction {fraction}, \
                                 accuracy {accuracy:e}: {measured} vs {target}"
                            );
                            let public = if forward { target } else { -target };
                            let adaptive = ArcLengthInverse::new(&c, start)
                                .param_at_length_adaptive(public, accuracy)
                                .unwrap();
                            assert_eq!(adaptive, t);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn speed_bound_holds_where_the_cut_search_is_skipped() {
        let gentle =
            BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 0.5], [2.0, 0.5], [3.0, 0.0]]).unwrap();
        let h = gentle.hodograph();
        assert!(speed_bounded_away_from_zero(&h, 0.0, 1.0));
        assert!(speed_bounded_away_from_zero(&h, 0.2, 0.7));
        // Outside [0, 1] the control polygon says nothing.
        assert!(!speed_bounded_away_from_zero(&h, -0.5, 1.0));
        let bound = SPEED_MARGIN
            * (0..=h.degree())
                .map(|i| norm(h.point(i)))
                .fold(0.0, f64::max);
        for k in 0..=1000 {
            let t = k as f64 / 1000.0;
            assert!(norm(&h.eval(t)) >= bound, "t = {t}");
        }
        // A cusp (speed 0 inside) and a 1D curve turning back: not skipped.
        assert!(!speed_bounded_away_from_zero(&cusp().hodograph(), 0.0, 1.0));
        let back = BezierCurve::from_rows(&[[0.0], [2.0], [-1.0], [1.0]]).unwrap();
        assert!(!speed_bounded_away_from_zero(&back.hodograph(), 0.0, 1.0));
        // Skipping the cut search leaves the length as it was: against the
        // sum over pieces (each integrated to far tighter accuracy).
        let whole = gentle.arc_length(0.0, 1.0, 1e-13).unwrap();
        let pieces: f64 = (0..8)
            .map(|k| {
                gentle
                    .arc_length(k as f64 / 8.0, (k + 1) as f64 / 8.0, 1e-16)
                    .unwrap()
            })
            .sum();
        assert!((whole - pieces).abs() <= 1e-13, "{whole} vs {pieces}");
    }
}

#[cfg(test)]
mod kept_inverse_tests {
    use super::*;

    fn cubic() -> BezierCurve {
        BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap()
    }

    /// Cusp at t = 1/2 (hodograph through the origin).
    fn cusp() -> BezierCurve {
        BezierCurve::from_rows(&[[0.0, 0.0], [2.0, 1.0], [0.0, 1.0], [2.0, 0.0]]).unwrap()
    }

    /// Degree 45 with pseudo-random coordinates in [-10, 10]: wiggly, with
    /// many speed minima (the family of the hostile-input test whose
    /// deviation search took seconds).
    fn wiggly() -> BezierCurve {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let points: Vec<f64> = (0..46 * 2)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 11) as f64 / (1u64 << 53) as f64 * 20.0 - 10.0
            })
            .collect();
        BezierCurve::new(2, 45, points).unwrap()
    }

    fn same(a: &Result<f64>, b: &Result<f64>) -> bool {
        match (a, b) {
            (Ok(x), Ok(y)) => x.to_bits() == y.to_bits(),
            (Err(x), Err(y)) => x.to_string() == y.to_string(),
            _ => false,
        }
    }

    /// One kept inverse answering many lengths and accuracies in a mixed
    /// order (tighter and looser than before, both directions, lengths
    /// below the parameter resolution, beyond the end, accuracies below
    /// the rounding level) gives exactly what a fresh `param_at_length`
    /// gives for each.
    #[test]
    fn a_kept_inverse_answers_as_fresh_calls_bit_for_bit() {
        for c in [cubic(), cusp(), wiggly()] {
            let total = c.arc_length(0.0, 1.0, 1e-13).unwrap();
            for &start in &[0.0, 0.3, 0.5, 0.77, 1.0] {
                let mut kept = ArcLengthInverse::new(&c, start);
                let mut calls = 0;
                for &fraction in &[
                    0.2, -0.2, 1e-3, -0.45, 1e-20, -1e-20, 0.6, 1.5, 5e-324, 0.05, -0.01,
                ] {
                    for &relative in &[1e-6, 1e-12, 1e-9, 1e-300, 1e-3] {
                        let length = fraction * total;
                        let accuracy = relative * length.abs().max(1e-300);
                        let fresh = c.param_at_length(start, length, accuracy);
                        let reused = kept.param_at_length(length, accuracy);
                        assert!(
                            same(&fresh, &reused),
                            "start {start}, length {length:e}, accuracy {accuracy:e}: \
                             {fresh:?} vs {reused:?}"
                        );
                        calls += 1;
                    }
                }
                assert_eq!(calls, 55);
            }
        }
    }

    /// A tree walked again at other accuracies gives the fresh pass's
    /// length, evaluation count, unresolved error and panels.
    #[test]
    fn a_kept_tree_replays_the_fresh_pass() {
        for c in [cubic(), cusp(), wiggly()] {
            let h = c.hodograph();
            let mut tree = QuadratureTree::new(&h, 0.1, 0.9);
            for &accuracy in &[1e-6, 1e-12, 1e-3, 1e-300, 1e-9, 1e-14] {
                let mut speed = Speed::new(&h, tree.noise_per_unit);
                let mut kept_panels = Vec::new();
                let kept = tree.pass(&mut speed, accuracy, Some(&mut kept_panels));
                let mut fresh_panels = Vec::new();
                let fresh = arc_length_panels(&h, 0.1, 0.9, accuracy, Some(&mut fresh_panels));
                assert_eq!(kept.length.to_bits(), fresh.length.to_bits());
                assert_eq!(kept.evaluations, fresh.evaluations);
                assert_eq!(kept.unresolved.to_bits(), fresh.unresolved.to_bits());
                assert_eq!(kept_panels.len(), fresh_panels.len());
                for (k, f) in kept_panels.iter().zip(&fresh_panels) {
                    assert_eq!(
                        (k.a, k.b, k.length, k.tolerance),
                        (f.a, f.b, f.length, f.tolerance)
                    );
                }
            }
        }
    }

    /// The fallback inside a panel meets the accuracy on its own (without
    /// the fixed rule's answer), in both directions and across a cusp.
    #[test]
    fn the_fallback_inside_a_panel_meets_the_accuracy() {
        for c in [cubic(), cusp(), wiggly()] {
            let h = c.hodograph();
            for &accuracy in &[1e-6, 1e-10] {
                for &start in &[0.0, 0.4, 1.0] {
                    for forward in [true, false] {
                        let (lo, hi) = if forward { (start, 1.0) } else { (0.0, start) };
                        if lo == hi {
                            continue;
                        }
                        let mut panels = Vec::new();
                        let available =
                            arc_length_panels(&h, lo, hi, 0.1 * accuracy, Some(&mut panels)).length;
                        for &fraction in &[1e-9, 0.1, 0.5, 0.93] {
                            let target = fraction * available;
                            let (panel, remaining) = locate(&panels, forward, target).unwrap();
                            let mut speed = Speed::new(&h, speed_noise_per_unit(&h, lo, hi));
                            let t = invert_in_panel_adaptively(
                                &mut speed, &panel, forward, remaining, accuracy,
                            );
                            let measured = arc_length_with(&h, start, t, 1e-16).abs();
                            assert!(
                                (measured - target).abs() <= accuracy,
                                "start {start}, forward {forward}, fraction {fraction}: \
                                 {measured} vs {target}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// Lengths of subnormal size to a subnormal accuracy stop at their
    /// rounding level (four units of 5e-324) instead of bisecting until the
    /// evaluation budget runs out, and agree with the same length to a
    /// reachable accuracy.
    #[test]
    fn subnormal_lengths_stop_at_their_rounding_level() {
        for c in [cubic(), wiggly()] {
            let h = c.hodograph();
            for &b in &[1.94e-313, 3e-320, 1e-310] {
                let (tight, evaluations) = arc_length_counted(&h, 0.0, b, 5e-324);
                assert!(evaluations < 20_000, "{b:e}: {evaluations} evaluations");
                let reachable = arc_length_with(&h, 0.0, b, 1e-300);
                let speed = norm(&h.eval(0.0));
                assert!(
                    (tight - reachable).abs() <= 1e-9 * speed * b + 8.0 * f64::from_bits(1),
                    "{b:e}: {tight:e} vs {reachable:e}"
                );
                assert!(c.arc_length(0.0, b, 5e-324).is_ok());
            }
        }
    }
}

#[cfg(test)]
mod chebyshev_tests {
    use super::*;

    /// The two cubics of the fillet benchmark and of the C++ demo.
    fn gentle() -> Vec<BezierCurve> {
        [
            [[-1.0, -1.0], [-0.3, 0.2], [0.4, 0.5], [1.2, 0.3]],
            [[0.5, -1.2], [0.1, -0.2], [-0.1, 0.6], [0.3, 1.4]],
            [[0.0, 0.0], [0.8, 0.3], [1.5, -0.2], [2.2, 0.4]],
            [[1.0, -1.0], [1.3, -0.2], [0.8, 0.6], [1.2, 1.4]],
        ]
        .iter()
        .map(|rows| BezierCurve::from_rows(rows).unwrap())
        .collect()
    }

    /// The Chebyshev inversion answers on gentle curves for setbacks up to a
    /// fifth of the remaining length (so the fast path is the one the
    /// fillet takes), its answer meets the accuracy against the
    /// adaptive rule at 1e-16, and it agrees with the adaptive inversion to
    /// within the sum of both accuracies.
    #[test]
    fn the_chebyshev_inversion_answers_and_meets_the_accuracy() {
        for c in gentle() {
            let speed = ChebyshevSpeed::new(&c).expect("a gentle curve qualifies");
            let h = c.hodograph();
            for &start in &[0.1, 0.45, 0.9] {
                for &relative in &[1e-12, 1e-9] {
                    for &fraction in &[0.01, 0.2, 0.6] {
                        for forward in [true, false] {
                            let end = if forward { 1.0 } else { 0.0 };
                            let available = arc_length_with(&h, start, end, 1e-16).abs();
                            let target = fraction * available;
                            let accuracy = relative * target;
                            let signed = if forward { target } else { -target };
                            // Short setbacks (the fillet's) must be answered;
                            // a long one may be declined (a wide bracket).
                            let Some(t) = speed.param_at_length(start, signed, accuracy) else {
                                assert!(fraction > 0.5, "no answer: start {start}, {fraction}");
                                continue;
                            };
                            let measured = arc_length_with(&h, start, t, 1e-16).abs();
                            assert!(
                                (measured - target).abs() <= accuracy,
                                "start {start}, fraction {fraction}, forward {forward}: \
                                 {measured} vs {target}"
                            );
                            assert_eq!(c.param_at_length(start, signed, accuracy).unwrap(), t);
                            let adaptive = ArcLengthInverse::new(&c, start)
                                .param_at_length_adaptive(signed, accuracy)
                                .unwrap();
                            let between = arc_length_with(&h, t, adaptive, 1e-16).abs();
                            assert!(between <= 2.0 * accuracy, "{between:e}");
                        }
                    }
                }
            }
        }
    }

    /// The twice-folded matrices give the coefficients of the direct
    /// interpolation sum `a_k = (2 / n) sum'' f_j cos(pi j k / n)` (end
    /// terms and end coefficients halved), and the check's `sum_k |a_k -
    /// b_k|` from the aliasing identity equals the one with `b` interpolated
    /// directly through every other sample, on a smooth function with slowly
    /// decaying coefficients, at both levels.
    #[test]
    fn folded_coefficients_and_coarse_difference_match_the_direct_sums() {
        let direct = |f: &[f64]| -> Vec<f64> {
            let n = f.len() - 1;
            (0..=n)
                .map(|k| {
                    let mut sum = 0.0;
                    for (j, fj) in f.iter().enumerate() {
                        let w = if j == 0 || j == n { 0.5 } else { 1.0 };
                        sum += w * fj * (std::f64::consts::PI * (j * k) as f64 / n as f64).cos();
                    }
                    let a = 2.0 / n as f64 * sum;
                    if k == 0 || k == n { 0.5 * a } else { a }
                })
                .collect()
        };
        let function = |x: f64| 1.0 / (1.1 - x) + (3.0 * x).sin();
        let tables = chebyshev_tables();
        for (level, &n) in CHEBYSHEV_LEVELS.iter().enumerate() {
            let step = CHEBYSHEV_MAX_N / n;
            let f: Vec<f64> = (0..=n).map(|j| function(tables.nodes[j * step])).collect();
            let mut a = [0.0; CHEBYSHEV_MAX_N + 3];
            if level == 0 {
                fold_apply(&tables.coarse, |j| f[j], &mut a);
            } else {
                fold_apply(&tables.fine, |j| f[j], &mut a);
            }
            let reference = direct(&f);
            for k in 0..=n {
                assert!((a[k] - reference[k]).abs() <= 1e-14, "n {n}, k {k}");
            }
            let even: Vec<f64> = f.iter().step_by(2).copied().collect();
            let b = direct(&even);
            let explicit: f64 = (0..=n)
                .map(|k| (reference[k] - b.get(k).copied().unwrap_or(0.0)).abs())
                .sum();
            let identity = coarse_difference(&a, n);
            assert!(
                explicit > 1e-9,
                "the function must not be resolved at n / 2"
            );
            assert!(
                (identity - explicit).abs() <= 1e-12,
                "n {n}: {identity:e} vs {explicit:e}"
            );
        }
    }

    /// The column-wise `fold_apply` gives the coefficients of the row-wise
    /// product it replaced to the bit: for each row `k` the four partial
    /// sums by `j mod 4` in increasing `j`, `E` and `O` from them, `a_k = E +
    /// O`, `a_(n-k) = E - O` (the session-26 loop, kept here as the
    /// reference), on fixed-seed samples of mixed signs and magnitudes at
    /// both levels.
    #[test]
    fn column_wise_fold_is_the_row_wise_product_to_the_bit() {
        fn row_wise<const C: usize>(rows: &[[f64; C]; C], f: &[f64], out: &mut [f64]) {
            let n = 2 * (C - 1);
            let (mut even, mut odd) = ([0.0; C], [0.0; C]);
            for j in 0..C {
                even[j] = f[j] + f[n - j];
                odd[j] = f[j] - f[n - j];
            }
            for (k, row) in rows.iter().enumerate() {
                let folded = if k % 2 == 0 { &even } else { &odd };
                let (mut e, mut o) = ([0.0; 2], [0.0; 2]);
                let mut j = 0;
                while j + 3 < C {
                    e[0] += row[j] * folded[j];
                    o[0] += row[j + 1] * folded[j + 1];
                    e[1] += row[j + 2] * folded[j + 2];
                    o[1] += row[j + 3] * folded[j + 3];
                    j += 4;
                }
                while j < C {
                    if j % 2 == 0 {
                        e[0] += row[j] * folded[j];
                    } else {
                        o[0] += row[j] * folded[j];
                    }
                    j += 1;
                }
                let (e, o) = (e[0] + e[1], o[0] + o[1]);
                out[k] = e + o;
                if 2 * k < n {
                    out[n - k] = e - o;
                }
            }
        }
        let mut values = crate::test_values::Values(27);
        let tables = chebyshev_tables();
        let coarse_rows = folded_matrix::<CHEBYSHEV_COLUMNS_0>();
        let fine_rows = folded_matrix::<CHEBYSHEV_COLUMNS_1>();
        for case in 0..200 {
            let f: Vec<f64> = (0..=CHEBYSHEV_MAX_N)
                .map(|_| (values.unit() - 0.3) * 10f64.powi(case % 7 - 3))
                .collect();
            for (level, &n) in CHEBYSHEV_LEVELS.iter().enumerate() {
                let step = CHEBYSHEV_MAX_N / n;
                let g: Vec<f64> = (0..=n).map(|j| f[j * step]).collect();
                let (mut a, mut b) = (
                    [f64::NAN; CHEBYSHEV_MAX_N + 3],
                    [f64::NAN; CHEBYSHEV_MAX_N + 3],
                );
                if level == 0 {
                    fold_apply(&tables.coarse, |j| g[j], &mut a);
                    row_wise(&coarse_rows, &g, &mut b);
                } else {
                    fold_apply(&tables.fine, |j| g[j], &mut a);
                    row_wise(&fine_rows, &g, &mut b);
                }
                for k in 0..=n {
                    assert_eq!(a[k].to_bits(), b[k].to_bits(), "case {case}, n {n}, k {k}");
                }
            }
        }
    }

    /// Curves the control-polygon bound cannot clear (a cusp, a curve
    /// turning back) and lengths past the end are left to the adaptive path.
    #[test]
    fn the_chebyshev_inversion_declines_what_it_cannot_certify() {
        let cusp =
            BezierCurve::from_rows(&[[0.0, 0.0], [2.0, 1.0], [0.0, 1.0], [2.0, 0.0]]).unwrap();
        assert!(ChebyshevSpeed::new(&cusp).is_none());
        let back = BezierCurve::from_rows(&[[0.0], [2.0], [-1.0], [1.0]]).unwrap();
        assert!(ChebyshevSpeed::new(&back).is_none());
        let c = &gentle()[0];
        let speed = ChebyshevSpeed::new(c).unwrap();
        let total = c.arc_length(0.5, 1.0, 1e-14).unwrap();
        assert!(speed.param_at_length(0.5, 1.01 * total, 1e-12).is_none());
        assert!(speed.param_at_length(1.0, 0.1, 1e-12).is_none());
        // Below the parameter resolution: no certified answer here.
        assert!(speed.param_at_length(0.5, 1e-300, 1e-310).is_none());
    }

    /// The node sampling with the dimension and degree fixed at compile
    /// time (`sample_fixed`, 2D and 3D up to hodograph degree 4) gives the
    /// speed of `at` and of the general `at_in` to the bit, at every node
    /// of both levels of brackets on either side of `t = 1/2`, on
    /// fixed-seed gentle curves of degrees 2 to 6 (the last two take the
    /// general loop, as a check of the dispatch).
    #[test]
    fn fixed_sampling_is_the_general_speed_to_the_bit() {
        let mut state = 26u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let tables = chebyshev_tables();
        let mut checked = 0;
        for case in 0..60 {
            let degree = 2 + case % 5;
            let dim = 2 + (case / 5) % 2;
            // Along x with small sideways wiggles: the speed stays away from 0.
            let points: Vec<f64> = (0..=degree)
                .flat_map(|i| {
                    let mut row = vec![i as f64 + 0.2 * next()];
                    row.extend((1..dim).map(|_| 0.3 * next() - 0.15));
                    row
                })
                .collect();
            let curve = BezierCurve::new(dim, degree, points).unwrap();
            let speed = ChebyshevSpeed::new(&curve).expect("a gentle curve qualifies");
            for (start, span) in [(0.05, 0.3), (0.6, 0.35), (0.7, -0.5), (0.2, 0.6)] {
                for (first, step) in [(0, 2), (1, 2), (0, 1)] {
                    let mut samples = [f64::NAN; CHEBYSHEV_MAX_N + 1];
                    assert!(speed.sample(&tables.nodes, start, span, first, step, &mut samples));
                    let mut i = first;
                    while i < CHEBYSHEV_MAX_N {
                        let t = start + 0.5 * (tables.nodes[i] + 1.0) * span;
                        let what = format!("case {case}, degree {degree}, dim {dim}, t {t}");
                        assert_eq!(samples[i].to_bits(), speed.at(t).to_bits(), "{what}");
                        let general = speed.at_in::<CHEBYSHEV_MAX_DIM>(t);
                        assert_eq!(samples[i].to_bits(), general.to_bits(), "{what}");
                        checked += 1;
                        i += step;
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }

    /// The Newton iteration's fused recurrences are the two plain Clenshaw
    /// sums to the bit, and the terms `newton_terms` leaves out sum to at
    /// most its budget while the next one would not fit (fixed-seed
    /// coefficients decaying like `10^-k`, with the budget at several
    /// levels).
    #[test]
    fn fused_clenshaw_and_the_newton_terms() {
        let mut values = crate::test_values::Values(7);
        let mut next = || values.unit();
        for case in 0..50 {
            let len = 3 + case % 24;
            let c: Vec<f64> = (0..len).map(|k| (next() - 0.5) * 10f64.powi(-k)).collect();
            let a: Vec<f64> = (0..len).map(|_| next() - 0.5).collect();
            let x = 2.0 * next() - 1.0;
            let (g, p) = clenshaw_pair(&c, &a, x);
            assert_eq!(g.to_bits(), clenshaw(&c, x).to_bits(), "case {case}");
            assert_eq!(p.to_bits(), clenshaw(&a, x).to_bits(), "case {case}");
            let half = 0.25 + next();
            for budget in [0.0, 1e-15, 1e-9, 1e-3, 1.0] {
                let (kept, tail) = newton_terms(&c, half, budget);
                let left_out: f64 = c[kept + 1..].iter().map(|x| half * x.abs()).sum();
                assert!((tail - left_out).abs() <= 1e-15 * left_out, "case {case}");
                assert!(tail <= budget, "case {case}, budget {budget}");
                if kept > 1 {
                    assert!(tail + half * c[kept].abs() > budget, "case {case}");
                }
            }
        }
    }
}
