//! Arc length of a NURBS curve and its inverse, span by span
//! (docs/mathematics.md#nurbs-curves).
//!
//! A polynomial span is a Bezier curve on `[u_i, u_(i+1)]`; arc length does
//! not depend on the (affine) parametrization, so its length is the Bezier
//! curve's ([`BezierCurve::arc_length`], adaptive Gauss-Legendre with cusp
//! cuts, docs/mathematics.md#arc-length) and so is its inverse. A rational
//! span's speed `|C'(u)|` (A4.2, [`RationalSpan::speed`] on the span's
//! homogeneous Bezier poles) is integrated by adaptive Gauss-Kronrod (7/15
//! points) on the pieces between the span's cuts (where the speed has a
//! kink or a sharp minimum, [`RationalSpan::cuts_of`]): an interval is
//! accepted when the two rules agree within its share of the accuracy,
//! otherwise both halves are refined, within a budget of
//! [`MAX_RATIONAL_EVALUATIONS`] speed evaluations; past it the call is
//! `IllConditioned` with the estimate. The inverse on a rational span is
//! first, when the span has no cuts (its speed `|N| / w^2` provably
//! bounded away from zero, [`RationalChebyshev`]), the Chebyshev inversion
//! of the polynomial spans ([`ChebyshevSampled::param_at_length`]: 25
//! samples of the speed on a bracket, the interpolant integrated and
//! inverted, certified against the interpolant through every other
//! sample); otherwise, or where that does not certify, Newton's method on
//! `u` (derivative: the speed) safeguarded by bisection, each step
//! measuring the length from the last iterate only.

use std::borrow::Cow;

use super::NurbsCurve;
use crate::arclength::{
    ArcLengthInverse, CHEBYSHEV_MAX_N, ChebyshevSampled, DEFAULT_ARC_LENGTH_ACCURACY,
    finite_default_accuracy, grade_at_near_cusps, sample_nodes, speed_bounds_away_from_zero,
    speed_minima,
};
use crate::basis::binomial;
use crate::bezier::{BezierCurve, distance, norm};
use crate::bezier::{point_and_tangent_fixed, point_and_tangent_rows};
use crate::error::{BezjoinError, Compact, Result, check_finite_scalar};

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
enum SpanForm<'a> {
    /// Polynomial: the Bezier curve on local `t = (u - lo) / (hi - lo)`.
    Polynomial(Cow<'a, BezierCurve>),
    /// Rational: the span's homogeneous Bezier poles.
    Rational(RationalSpan<'a>),
}

/// A rational span as its homogeneous Bezier poles `(w P, w)` (`dim + 1`
/// values each, the rows of the curve's kept decomposition,
/// [`NurbsCurve::span_poles`]) on `[lo, hi]`: the curve there is `A(t) /
/// w(t)` in `t = (u - lo) / (hi - lo)`, `A` and `w` Bernstein polynomials
/// of the degree `p`.
struct RationalSpan<'a> {
    rows: &'a [f64],
    dim: usize,
    degree: usize,
    lo: f64,
    hi: f64,
    /// Parameters strictly inside `(lo, hi)`, increasing, where the
    /// quadrature cuts the span ([`RationalSpan::cuts_of`]; computed once
    /// per curve, kept with its span decomposition).
    cuts: &'a [f64],
    /// Bounds of the speed when it is provably away from zero on the whole
    /// span (then `cuts` is empty), from the same computation.
    bounds: Option<SpeedBounds>,
    /// [`RationalSpanSpeed::horner`] (with `bounds`).
    horner: &'a [f64],
}

/// What the arc length keeps of one rational span, computed once per curve
/// with its span decomposition ([`RationalSpan::cuts_of`]).
#[derive(Debug, Clone)]
pub(crate) struct RationalSpanSpeed {
    /// The quadrature's cuts, strictly inside the span, increasing.
    cuts: Vec<f64>,
    /// Present when the speed is provably bounded away from zero on the
    /// span (no cuts): the Chebyshev inversion's bounds.
    bounds: Option<SpeedBounds>,
    /// With `bounds`: the speed's polynomials for [`horner_speed`], `C(q,
    /// k) N_k` (`q + 1` rows of `dim`, `q = 2p - 1`) then `C(p, k) w_k`
    /// (`p + 1` values); empty without.
    horner: Vec<f64>,
}

/// Bounds of a rational span's speed per unit of its local `t`, on the
/// whole span: `low <= |C'(t)| <= high`, and `noise` the rounding-noise
/// bound of its evaluation per unit of `t`.
#[derive(Debug, Clone, Copy)]
struct SpeedBounds {
    low: f64,
    high: f64,
    noise: f64,
}

impl RationalSpan<'_> {
    /// Where `|C'|` has a kink or a sharp minimum: `C' = N / w^2` with the
    /// polynomial `N = A' w - A w'` (degree `2p - 1` in this product form,
    /// Bernstein coefficients from the products of Bernstein polynomials),
    /// so `|C'|` has a kink exactly where `N` vanishes (a cusp; in one
    /// dimension, wherever the curve turns back), and the strip where `|C'|`
    /// is analytic is `N . N`'s, as for a polynomial curve's hodograph. The
    /// cuts are those of the Bezier arc length for the hodograph `N`: the
    /// local minima of `|N|` ([`crate::arclength::speed_minima`]) and the
    /// geometric mesh towards a small nonzero minimum
    /// ([`crate::arclength::grade_at_near_cusps`]); none when `N`'s
    /// polygon keeps it away from zero, and then the speed's bounds
    /// ([`speed_bounds`]) and `N` and `w` for [`horner_speed`] are kept
    /// instead (the Chebyshev inversion's, [`RationalChebyshev`]). Without them the 7/15-point check
    /// is fooled at a kink (both rules off by about the same amount):
    /// measured on a one-dimensional degree-5 span, a length accepted
    /// `2.6e-11` off at a tolerance of `6e-14`.
    fn cuts_of(rows: &[f64], dim: usize, degree: usize, lo: f64, hi: f64) -> RationalSpanSpeed {
        let (p, d) = (degree, dim);
        let hd = d + 1;
        let none = || RationalSpanSpeed {
            cuts: Vec::new(),
            bounds: None,
            horner: Vec::new(),
        };
        if p == 0 {
            return none();
        }
        let q = 2 * p - 1;
        let mut numerator = vec![0.0; (q + 1) * d];
        // A' w and A w' as products of a degree p - 1 and a degree p
        // Bernstein polynomial: coefficient i + j of degree q gets
        // C(p-1, i) C(p, j) / C(q, i + j) times the product.
        for i in 0..p {
            for j in 0..=p {
                let weight = binomial(p - 1, i) * binomial(p, j) / binomial(q, i + j);
                let (r0, r1, rj) = (
                    &rows[i * hd..(i + 1) * hd],
                    &rows[(i + 1) * hd..(i + 2) * hd],
                    &rows[j * hd..(j + 1) * hd],
                );
                let dw = p as f64 * (r1[d] - r0[d]);
                for c in 0..d {
                    let da = p as f64 * (r1[c] - r0[c]);
                    numerator[(i + j) * d + c] += weight * (da * rj[d] - rj[c] * dw);
                }
            }
        }
        if numerator.iter().any(|v| !v.is_finite()) {
            return none();
        }
        let Ok(n) = BezierCurve::new(d, q, numerator) else {
            return none();
        };
        if let Some((low, high)) = speed_bounds_away_from_zero(&n) {
            let bounds = speed_bounds(rows, d, p, low, high);
            let mut horner = Vec::new();
            if bounds.is_some() {
                let points = n.points();
                horner.extend((0..=q).flat_map(|k| {
                    let b = binomial(q, k);
                    points[k * d..(k + 1) * d].iter().map(move |x| b * x)
                }));
                horner.extend((0..=p).map(|k| binomial(p, k) * rows[k * hd + d]));
            }
            let finite = horner.iter().all(|x| x.is_finite());
            return RationalSpanSpeed {
                cuts: Vec::new(),
                bounds: bounds.filter(|_| finite),
                horner,
            };
        }
        let mut cuts = vec![0.0];
        cuts.extend(speed_minima(&n, 0.0, 1.0));
        cuts.push(1.0);
        grade_at_near_cusps(&n, &mut cuts);
        let h = hi - lo;
        let mut inside: Vec<f64> = cuts
            .iter()
            .map(|&t| lo + t * h)
            .filter(|&u| u > lo && u < hi)
            .collect();
        inside.dedup();
        RationalSpanSpeed {
            cuts: inside,
            bounds: None,
            horner: Vec::new(),
        }
    }

    /// The speed `|dC/du|` at `u` in `[lo, hi]`: de Casteljau at `t` on the
    /// homogeneous poles to level `p - 1`, whose two points give `A'(t) = p
    /// (d_1 - d_0)` (the same step as de Boor's last level but one,
    /// [`NurbsCurve::point_and_tangent`]), the last level `A(t)`;
    /// `C' = (A' - w' C) / w` and `dC/du = C'(t) / (hi - lo)`
    /// ([`point_and_tangent_rows`]: no heap allocation up to
    /// `(p + 1) (dim + 1) <= 64`); plane and space quadratics and cubics
    /// with the sizes as constants. On a span with [`SpeedBounds`] (no
    /// cuts) the plane and space quadratics and cubics take
    /// [`horner_speed`] instead, about half the work.
    fn speed(&self, u: f64) -> f64 {
        let mut out = [0.0];
        self.speeds(&[u], &mut out);
        out[0]
    }

    /// [`Self::speed`] at every `u` of `us` into `out` (the size dispatch
    /// once for all of them: a Gauss-Kronrod panel's 15 nodes).
    fn speeds(&self, us: &[f64], out: &mut [f64]) {
        if self.bounds.is_some() {
            let job = FillSpeeds {
                us,
                out: &mut *out,
                lo: self.lo,
                h: self.hi - self.lo,
            };
            if self.with_horner(job).is_some() {
                return;
            }
        }
        match (self.dim, self.degree) {
            (2, 3) => self.speeds_with(us, out, speed_fixed::<3, 3>),
            (3, 3) => self.speeds_with(us, out, speed_fixed::<4, 3>),
            (2, 2) => self.speeds_with(us, out, speed_fixed::<3, 2>),
            (3, 2) => self.speeds_with(us, out, speed_fixed::<4, 2>),
            _ => self.speeds_with(us, out, |_, t| self.speed_any(t)),
        }
    }

    /// `job` run on the speed per unit `t` by [`horner_speed`] (the
    /// polynomials read in place as an array of their exact length, the
    /// sizes dispatched once, the speed inlined into the job): `None`
    /// (nothing run) without [`SpeedBounds`] or for a size other than plane
    /// and space quadratics and cubics.
    #[inline(always)]
    fn with_horner<J: HornerJob>(&self, job: J) -> Option<J::Output> {
        // Nothing run without bounds.
        self.bounds?;
        // Table lengths `(2p) dim + p + 1`.
        match (self.dim, self.degree) {
            (2, 3) => run_horner::<J, 2, 3, 16>(self.horner, job),
            (3, 3) => run_horner::<J, 3, 3, 22>(self.horner, job),
            (2, 2) => run_horner::<J, 2, 2, 11>(self.horner, job),
            (3, 2) => run_horner::<J, 3, 2, 15>(self.horner, job),
            _ => None,
        }
    }

    /// [`Self::speeds`] by `per_unit_t` (the speed in `t` from the rows).
    #[inline(always)]
    fn speeds_with(&self, us: &[f64], out: &mut [f64], per_unit_t: impl Fn(&[f64], f64) -> f64) {
        let scale = 1.0 / (self.hi - self.lo);
        for (o, &u) in out.iter_mut().zip(us) {
            let t = (u - self.lo) / (self.hi - self.lo);
            *o = per_unit_t(self.rows, t) * scale;
        }
    }

    /// The parameter in `[lo, hi]` (which holds `start`) whose signed arc
    /// length from `start` is `target`, and whether the length there met
    /// `accuracy`: first, on a span with [`SpeedBounds`], the Chebyshev
    /// inversion ([`RationalChebyshev`], its answer certified to `0.75
    /// accuracy`, `true`); otherwise, or when it does not certify,
    /// Newton's method on `f(u) = len(start, u) - target`
    /// (increasing in `u`; `f(start) = -target` exactly), safeguarded by
    /// bisection. Each step measures only the length between the last
    /// iterate and the next (not from `start` again), the `k`-th to
    /// `accuracy / 2^(k + 3)`, so the lengths summed along the way are
    /// within `accuracy / 4` of the length from `start`; the answer is taken
    /// when the sum is within `accuracy / 2` of `target` (`true`), or when
    /// the bracket has shrunk to rounding (`false`, its middle).
    fn invert(
        &self,
        start: f64,
        target: f64,
        mut lo: f64,
        mut hi: f64,
        accuracy: f64,
    ) -> Result<(f64, bool)> {
        // First the Chebyshev inversion when the span qualifies (its answer
        // certified to `0.75 accuracy`, as this one's).
        if target != 0.0 {
            if let Some(u) = RationalChebyshev::new(self)
                .and_then(|speed| speed.param_at_length(start, target, accuracy))
            {
                return Ok((u, true));
            }
        }
        let mut u = start;
        let mut value = -target;
        let mut tolerance = 0.125 * accuracy;
        for _ in 0..200 {
            let speed = self.speed(u);
            let newton = u - value / speed;
            let next = if speed > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            value += if next >= u {
                rational_length(self, u, next, tolerance)?
            } else {
                -rational_length(self, next, u, tolerance)?
            };
            tolerance *= 0.5;
            u = next;
            if value.abs() <= 0.5 * accuracy {
                return Ok((u, true));
            }
            if value > 0.0 {
                hi = u;
            } else {
                lo = u;
            }
            if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs()).max(f64::MIN_POSITIVE) {
                return Ok((0.5 * (lo + hi), false));
            }
        }
        Ok((u, false))
    }

    /// Length of the Cartesian control polygon of the span's part on `[t0,
    /// 1]` (`forward`) or `[0, t0]`: one de Casteljau pass on the
    /// homogeneous poles (on the stack up to 128 values; the whole polygon,
    /// a larger bound, above that or at the ends).
    fn part_polygon_length(&self, t0: f64, forward: bool) -> f64 {
        // Plane and space cubics with the sizes as constants and a buffer
        // of their 12 or 16 values: the same operations.
        match (self.degree, self.dim) {
            (3, 2) => self.part_polygon_sized::<16>(3, 2, t0, forward),
            (3, 3) => self.part_polygon_sized::<16>(3, 3, t0, forward),
            (p, d) => self.part_polygon_sized::<128>(p, d, t0, forward),
        }
    }

    /// [`Self::part_polygon_length`] for degree `p == self.degree` and
    /// dimension `d == self.dim`, on a buffer of `W` values.
    #[inline(always)]
    fn part_polygon_sized<const W: usize>(
        &self,
        p: usize,
        d: usize,
        t0: f64,
        forward: bool,
    ) -> f64 {
        let hd = d + 1;
        let mut work = [0.0f64; W];
        // The span's `p + 1` rows (of constant length for constant `p`, `d`:
        // the copy below inlined).
        let rows = self.rows.get(..(p + 1) * hd).unwrap_or(self.rows);
        let part: &[f64] = if rows.len() > work.len() || !(t0 > 0.0 && t0 < 1.0) {
            rows
        } else {
            let work = &mut work[..rows.len()];
            work.copy_from_slice(rows);
            part_in_place(work, p, hd, t0, forward);
            work
        };
        projected_polygon_length(part, p, d)
    }

    /// [`Self::speed`] in `t` (per unit `t`) for any dimension and degree:
    /// `A(t)` and `A'(t)` by [`point_and_tangent_rows`] on the homogeneous
    /// poles, then [`rational_speed`].
    fn speed_any(&self, t: f64) -> f64 {
        let hd = self.dim + 1;
        if self.degree == 0 {
            return 0.0;
        }
        let (mut a, mut da) = ([0.0f64; 17], [0.0f64; 17]);
        let (mut a_heap, mut da_heap) = (Vec::new(), Vec::new());
        let (a, da): (&mut [f64], &mut [f64]) = if hd <= a.len() {
            (&mut a[..hd], &mut da[..hd])
        } else {
            a_heap.resize(hd, 0.0);
            da_heap.resize(hd, 0.0);
            (&mut a_heap, &mut da_heap)
        };
        point_and_tangent_rows(self.rows, hd, self.degree, t, a, da);
        rational_speed(a, da)
    }
}

/// Length of the Cartesian polygon of `p + 1` homogeneous rows `(w x, w)`
/// of `d + 1` values in `w` (infinite above 16 dimensions): each pole
/// projected once, the previous one kept. Inlined into its one caller so
/// that constant sizes unroll it.
#[inline(always)]
fn projected_polygon_length(w: &[f64], p: usize, d: usize) -> f64 {
    let hd = d + 1;
    let mut total = 0.0;
    let mut a = [0.0f64; 16];
    let mut b = [0.0f64; 16];
    if d > a.len() {
        return f64::INFINITY;
    }
    for c in 0..d {
        a[c] = w[c] / w[d];
    }
    for i in 1..=p {
        for c in 0..d {
            b[c] = w[i * hd + c] / w[i * hd + d];
        }
        total += distance(&a[..d], &b[..d]);
        a[..d].copy_from_slice(&b[..d]);
    }
    total
}

/// [`SpeedBounds`] of a rational span (`p + 1` homogeneous rows of `dim +
/// 1`) from `low <= |N(t)| <= high` on `[0, 1]` (`N = A' w - A w'` of
/// degree `q = 2p - 1`, the bounds of [`speed_bounds_away_from_zero`] on
/// its Bernstein polygon): `|C'| = |N| / w^2` and `min w_i <= w(t) <= max
/// w_i` (convex hull), so `low / max w_i^2 <= |C'(t)| <= high / min w_i^2`.
/// The noise of [`horner_speed`]: the Bernstein-Horner evaluation of `N`
/// errs by about `(q + 1) eps` times its coefficients' size (as for a
/// hodograph, `speed_noise_per_unit` in [`crate::arclength`]), and those
/// coefficients carry the rounding of their products, `p (max |A_i -
/// A_(i-1)| max w_i + max |A_i| max |w_i - w_(i-1)|)` in size, whatever
/// `N`'s own size (`A = w P` far from the origin cancels there); divided
/// by `min w_i^2`, a factor 4 and `sqrt(dim)` for the norm and the
/// division. `None` when a bound is not a positive finite number.
fn speed_bounds(
    rows: &[f64],
    dim: usize,
    degree: usize,
    low: f64,
    high: f64,
) -> Option<SpeedBounds> {
    let hd = dim + 1;
    let (mut w_min, mut w_max, mut a_max) = (f64::INFINITY, 0.0f64, 0.0f64);
    let (mut da_max, mut dw_max) = (0.0f64, 0.0f64);
    for (i, row) in rows.chunks_exact(hd).enumerate() {
        w_min = w_min.min(row[dim]);
        w_max = w_max.max(row[dim]);
        a_max = row[..dim].iter().fold(a_max, |m, x| m.max(x.abs()));
        if i > 0 {
            let previous = &rows[(i - 1) * hd..i * hd];
            dw_max = dw_max.max((row[dim] - previous[dim]).abs());
            for c in 0..dim {
                da_max = da_max.max((row[c] - previous[c]).abs());
            }
        }
    }
    let p = degree as f64;
    let q = (2 * degree - 1) as f64;
    let products = p * (da_max * w_max + a_max * dw_max);
    let bounds = SpeedBounds {
        low: low / (w_max * w_max),
        high: high / (w_min * w_min),
        noise: 4.0 * (q + 1.0) * f64::EPSILON * (dim as f64).sqrt() * (high + products)
            / (w_min * w_min),
    };
    let good = |x: f64| x > 0.0 && x.is_finite();
    (good(bounds.low) && good(bounds.high) && good(bounds.noise) && bounds.low <= bounds.high)
        .then_some(bounds)
}

/// The speed `|C'(t)|` per unit `t` of a rational span from its
/// [`RationalSpanSpeed::horner`] polynomials (`D` coordinates, `N` of degree
/// `Q = 2P - 1`, `w` of degree `P`): `|N(t)| / w(t)^2` with both in
/// Bernstein-Horner form in `r = t / (1 - t)` or `(1 - t) / t`, whichever
/// is at most 1 (the scheme of [`BezierCurve::eval`]): `N(t) = N_r
/// f^Q`, `w(t) = w_r f^P` (`f` = `1 - t` or `t`), so `|C'| = |N_r| / (w_r^2
/// f)`. `L = 2 P D + P + 1` is the polynomials' length ([`run_horner`]).
#[inline(always)]
fn horner_speed<const D: usize, const P: usize, const L: usize>(horner: &[f64; L], t: f64) -> f64 {
    let q = 2 * P - 1;
    let (numerator, weight) = horner.split_at((q + 1) * D);
    let s = 1.0 - t;
    let (r, factor) = if t <= 0.5 { (t / s, s) } else { (s / t, t) };
    let mut n = [0.0f64; D];
    let mut w;
    if t <= 0.5 {
        n.copy_from_slice(&numerator[q * D..(q + 1) * D]);
        for k in (0..q).rev() {
            for c in 0..D {
                n[c] = n[c] * r + numerator[k * D + c];
            }
        }
        w = weight[P];
        for k in (0..P).rev() {
            w = w * r + weight[k];
        }
    } else {
        n.copy_from_slice(&numerator[..D]);
        for k in 1..=q {
            for c in 0..D {
                n[c] = n[c] * r + numerator[k * D + c];
            }
        }
        w = weight[0];
        for &x in &weight[1..=P] {
            w = w * r + x;
        }
    }
    let mut square = 0.0;
    for x in n {
        square += x * x;
    }
    let size = if square.is_normal() {
        square.sqrt()
    } else {
        norm(&n)
    };
    size / (w * w * factor)
}

/// Work done on a rational span's speed per unit `t`
/// ([`RationalSpan::with_horner`]), generic in the speed so that it is
/// inlined.
trait HornerJob {
    type Output;
    fn run(self, speed: impl Fn(f64) -> f64) -> Self::Output;
}

/// [`RationalSpan::speeds`]: the speed per unit `u` at `us` into `out`.
struct FillSpeeds<'j> {
    us: &'j [f64],
    out: &'j mut [f64],
    lo: f64,
    h: f64,
}

impl HornerJob for FillSpeeds<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self, speed: impl Fn(f64) -> f64) {
        for (o, &u) in self.out.iter_mut().zip(self.us) {
            *o = speed(((u - self.lo) / self.h).clamp(0.0, 1.0)) / self.h;
        }
    }
}

/// [`ChebyshevSampled::sample_speeds`] of [`RationalChebyshev`]: the
/// speed per unit `u` at the grid's nodes ([`sample_nodes`]).
struct SampleNodes<'j> {
    grid: (&'j [f64; CHEBYSHEV_MAX_N + 1], f64, f64, usize, usize),
    samples: &'j mut [f64; CHEBYSHEV_MAX_N + 1],
    lo: f64,
    h: f64,
}

impl HornerJob for SampleNodes<'_> {
    type Output = bool;
    #[inline(always)]
    fn run(self, speed: impl Fn(f64) -> f64) -> bool {
        let (lo, h) = (self.lo, self.h);
        sample_nodes(self.grid, self.samples, |u| {
            speed(((u - lo) / h).clamp(0.0, 1.0)) / h
        })
    }
}

/// `job` on [`horner_speed`] for `D` coordinates and degree `P` when
/// `horner` has the length `L = 2 P D + P + 1` of their table (else `None`,
/// nothing run).
#[inline(always)]
fn run_horner<J: HornerJob, const D: usize, const P: usize, const L: usize>(
    horner: &[f64],
    job: J,
) -> Option<J::Output> {
    let table: &[f64; L] = horner.try_into().ok()?;
    Some(job.run(|t| horner_speed::<D, P, L>(table, t)))
}

/// [`horner_speed`] for any dimension (up to 16) and degree.
fn horner_speed_any(horner: &[f64], dim: usize, degree: usize, t: f64) -> f64 {
    let (p, d) = (degree, dim);
    let q = 2 * p - 1;
    let (numerator, weight) = horner.split_at((q + 1) * d);
    let s = 1.0 - t;
    let (r, factor) = if t <= 0.5 { (t / s, s) } else { (s / t, t) };
    let mut n = [0.0f64; 16];
    let n = &mut n[..d];
    let w = if t <= 0.5 {
        n.copy_from_slice(&numerator[q * d..(q + 1) * d]);
        for k in (0..q).rev() {
            for c in 0..d {
                n[c] = n[c] * r + numerator[k * d + c];
            }
        }
        weight[..p].iter().rev().fold(weight[p], |w, &x| w * r + x)
    } else {
        n.copy_from_slice(&numerator[..d]);
        for k in 1..=q {
            for c in 0..d {
                n[c] = n[c] * r + numerator[k * d + c];
            }
        }
        weight[1..=p].iter().fold(weight[0], |w, &x| w * r + x)
    };
    norm(n) / (w * w * factor)
}

/// A rational span's speed in `u` on `[lo, hi]` for the Chebyshev
/// inversion ([`ChebyshevSampled`]), when its [`SpeedBounds`] exist: the
/// speed is then `|N| / w^2` with `|N|` bounded away from zero and `w > 0`,
/// analytic on the span (no kink, no cut), the condition under which the
/// polynomial spans use the same inversion. Evaluated by [`horner_speed`].
struct RationalChebyshev<'s, 'a> {
    span: &'s RationalSpan<'a>,
    /// The bounds per unit of `u`.
    low: f64,
    high: f64,
    noise: f64,
}

impl<'s, 'a> RationalChebyshev<'s, 'a> {
    /// `None` without bounds, or for a dimension above 16.
    fn new(span: &'s RationalSpan<'a>) -> Option<Self> {
        let bounds = span.bounds?;
        if span.dim > 16 || span.degree == 0 {
            return None;
        }
        let h = span.hi - span.lo;
        let chebyshev = RationalChebyshev {
            span,
            low: bounds.low / h,
            high: bounds.high / h,
            noise: bounds.noise / h,
        };
        (chebyshev.low > 0.0 && chebyshev.high.is_finite() && chebyshev.noise.is_finite())
            .then_some(chebyshev)
    }
}

impl ChebyshevSampled for RationalChebyshev<'_, '_> {
    fn domain(&self) -> (f64, f64) {
        (self.span.lo, self.span.hi)
    }

    fn speed_at(&self, u: f64) -> f64 {
        self.span.speed(u)
    }

    fn speed_bounds(&self) -> (f64, f64) {
        (self.low, self.high)
    }

    fn noise_per_unit(&self) -> f64 {
        self.noise
    }

    fn sample_speeds(
        &self,
        nodes: &[f64; CHEBYSHEV_MAX_N + 1],
        start: f64,
        span: f64,
        first: usize,
        step: usize,
        samples: &mut [f64; CHEBYSHEV_MAX_N + 1],
    ) -> bool {
        let s = self.span;
        let (lo, h) = (s.lo, s.hi - s.lo);
        let grid = (nodes, start, span, first, step);
        let t = |u: f64| ((u - lo) / h).clamp(0.0, 1.0);
        // The values of `speed_at` (`RationalSpan::speeds`), the table
        // read and the sizes dispatched once for all the nodes.
        let job = SampleNodes {
            grid,
            samples: &mut *samples,
            lo,
            h,
        };
        if let Some(finite) = s.with_horner(job) {
            return finite;
        }
        sample_nodes(grid, samples, |u| {
            horner_speed_any(s.horner, s.dim, s.degree, t(u)) / h
        })
    }
}

/// `|C'|` from the homogeneous `A` and `A'` (`dim + 1` values each, the
/// weight last): `C' = (A' - w' C) / w` with `C = A / w`; the plain sum of
/// squares while it is a normal number, the overflow-safe norm otherwise.
#[inline(always)]
fn rational_speed(a: &[f64], da: &[f64]) -> f64 {
    let d = a.len() - 1;
    let (w, dw) = (a[d], da[d]);
    let mut tangent = [0.0f64; 16];
    let mut heap = Vec::new();
    let tangent: &mut [f64] = if d <= tangent.len() {
        &mut tangent[..d]
    } else {
        heap.resize(d, 0.0);
        &mut heap
    };
    let mut square = 0.0;
    for c in 0..d {
        tangent[c] = (da[c] - dw * (a[c] / w)) / w;
        square += tangent[c] * tangent[c];
    }
    if square.is_normal() {
        square.sqrt()
    } else {
        norm(tangent)
    }
}

/// [`RationalSpan::speed`] in `t` for `HD = dim + 1` homogeneous
/// coordinates and the degree `P` (1 to 3) known at compile time (loops
/// unrolled): the operations of [`RationalSpan::speed_any`].
#[inline(always)]
fn speed_fixed<const HD: usize, const P: usize>(rows: &[f64], t: f64) -> f64 {
    let (mut a, mut da) = ([0.0f64; HD], [0.0f64; HD]);
    point_and_tangent_fixed::<HD, 4>(rows, P, t, &mut a, &mut da);
    rational_speed(&a, &da)
}

struct Span<'a> {
    lo: f64,
    hi: f64,
    form: SpanForm<'a>,
}

impl Span<'_> {
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

    /// `int |C'|` from `from` to the span's end `to` it runs towards
    /// (forwards: `to = hi`), to `accuracy`: on a polynomial span first by
    /// the Chebyshev interpolant of the speed (the Bezier kernel's
    /// `length_to_end`, certified to `accuracy`), else (a cusp, a curve
    /// the interpolant does not certify, a rational span) by
    /// [`Self::length`]. (On a rational span one Gauss-Kronrod panel, 15
    /// speeds, usually meets the share of a span walked past; the
    /// Chebyshev interpolant takes 25.)
    fn length_from(&self, from: f64, to: f64, forward: bool, accuracy: f64) -> Result<f64> {
        if let SpanForm::Polynomial(bez) = &self.form {
            if from == to {
                return Ok(0.0);
            }
            let mut inverse = ArcLengthInverse::new(bez, self.local(from));
            if let Some(length) = inverse.length_to_end(forward, accuracy) {
                return Ok(length);
            }
        }
        self.length(from.min(to), from.max(to), accuracy)
    }

    /// [`Self::param_at`] on a polynomial span when the answer lies strictly
    /// inside the span, without the span's length first: the Bezier
    /// inversion from `start` refuses a length beyond the span's end (an
    /// error) and returns the end for a length at least the span's (within
    /// its accuracy), so an answer strictly between `start` and the end
    /// has its length from `start` within `accuracy` of `length` (the
    /// inversion's guarantee). `None` (the caller measures the span and
    /// goes on) for a rational span, a `length` above the length of the
    /// control polygon of the span's part from `start` on (which bounds
    /// that part's arc length), any error, or the end. Where the caller's old order
    /// (span length `L` to its share of the accuracy, then this inversion
    /// when `length <= L`) would invert here, this is that inversion,
    /// bit for bit; the two differ only when `length` is within the
    /// accuracies of the span's length from `start`, and then both answers
    /// meet the accuracy.
    fn param_inside(&self, start: f64, length: f64, forward: bool, accuracy: f64) -> Option<f64> {
        let bez = match &self.form {
            SpanForm::Polynomial(bez) => bez,
            SpanForm::Rational(span) => {
                // The same on a rational span: its part's control polygon
                // bounds that part's length too (each de Casteljau level's
                // projected points lie on the previous level's polygon), and
                // the inversion's answer is taken when it met its accuracy
                // strictly inside the span.
                let bound = span.part_polygon_length(self.local(start), forward);
                if length.is_nan() || bound.is_nan() || length > bound {
                    return None;
                }
                let (lo, hi) = if forward {
                    (start, self.hi)
                } else {
                    (self.lo, start)
                };
                let target = if forward { length } else { -length };
                let (u, met) = span.invert(start, target, lo, hi, accuracy).ok()?;
                let end = if forward { self.hi } else { self.lo };
                return (met && u != end && u != start).then_some(u);
            }
        };
        let t0 = self.local(start);
        // The control polygon of the part from `t0` to the end it runs
        // towards bounds that part's length (a heuristic here: whichever
        // way it decides, the answer is the old order's or a checked one).
        let bound = part_polygon_length(bez, t0, forward);
        if length.is_nan() || bound.is_nan() || length > bound {
            return None;
        }
        let signed = if forward { length } else { -length };
        let t = bez.param_at_length(t0, signed, accuracy).ok()?;
        let end = if forward { 1.0 } else { 0.0 };
        (t != end && t != t0).then(|| self.global(t))
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
                let (lo, hi) = if forward {
                    (start, self.hi)
                } else {
                    (self.lo, start)
                };
                let target = if forward { length } else { -length };
                Ok(span.invert(start, target, lo, hi, accuracy)?.0)
            }
        }
    }
}

/// Length of the control polygon of `bez` on `[t0, 1]` (`forward`) or
/// `[0, t0]` (one de Casteljau pass on the stack up to 64 coordinates;
/// the whole polygon, a larger bound, above that).
fn part_polygon_length(bez: &BezierCurve, t0: f64, forward: bool) -> f64 {
    let (n, d) = (bez.degree(), bez.dim());
    let points = bez.points();
    let mut work = [0.0f64; 64];
    if points.len() > work.len() || t0 <= 0.0 || t0 >= 1.0 {
        return bez.polygon_length();
    }
    work[..points.len()].copy_from_slice(points);
    // Plane and space cubics with the sizes as constants (unrolled).
    match (n, d) {
        (3, 2) => part_polygon_sized(&mut work, 3, 2, t0, forward),
        (3, 3) => part_polygon_sized(&mut work, 3, 3, t0, forward),
        (n, d) => part_polygon_sized(&mut work, n, d, t0, forward),
    }
}

/// [`part_polygon_length`]'s pass on `work` (`n + 1` rows of `d`).
#[inline(always)]
fn part_polygon_sized(work: &mut [f64; 64], n: usize, d: usize, t0: f64, forward: bool) -> f64 {
    let work = &mut work[..(n + 1) * d];
    part_in_place(work, n, d, t0, forward);
    (1..=n)
        .map(|i| distance(&work[(i - 1) * d..i * d], &work[i * d..(i + 1) * d]))
        .sum()
}

/// The control points (`n + 1` rows of `d` in `work`) of the part on `[t0,
/// 1]` (`forward`) or `[0, t0]`, in place: one de Casteljau pass.
#[inline(always)]
fn part_in_place(work: &mut [f64], n: usize, d: usize, t0: f64, forward: bool) {
    if forward {
        // Right part: after step r, point n - r is final.
        for r in 1..=n {
            for i in 0..=n - r {
                for c in 0..d {
                    work[i * d + c] = (1.0 - t0) * work[i * d + c] + t0 * work[(i + 1) * d + c];
                }
            }
        }
    } else {
        // Left part: after step r, point r is final.
        for r in 1..=n {
            for i in (r..=n).rev() {
                for c in 0..d {
                    work[i * d + c] = (1.0 - t0) * work[(i - 1) * d + c] + t0 * work[i * d + c];
                }
            }
        }
    }
}

/// One Gauss-Kronrod panel: (Kronrod value, |Kronrod - Gauss|).
fn kronrod(span: &RationalSpan<'_>, a: f64, b: f64, evaluations: &mut usize) -> (f64, f64) {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    // The nodes: the centre, then `mid - dx_j`, `mid + dx_j` for j = 0..7.
    let mut nodes = [mid; 15];
    for j in 0..7 {
        let dx = half * XGK[j];
        nodes[1 + 2 * j] = mid - dx;
        nodes[2 + 2 * j] = mid + dx;
    }
    let mut speeds = [0.0; 15];
    span.speeds(&nodes, &mut speeds);
    let centre = speeds[0];
    let mut k = WGK[7] * centre;
    let mut g = WG[3] * centre;
    for j in 0..7 {
        let pair = speeds[1 + 2 * j] + speeds[2 + 2 * j];
        k += WGK[j] * pair;
        if j % 2 == 1 {
            g += WG[j / 2] * pair;
        }
    }
    *evaluations += 15;
    (k * half, ((k - g) * half).abs())
}

/// `int_a^b |C'|` on a rational span (`lo <= a <= b <= hi`), adaptive
/// Gauss-Kronrod on each piece between the span's cuts
/// ([`RationalSpan::cuts_of`]) inside `(a, b)`, each to its equal share of
/// `accuracy`.
fn rational_length(span: &RationalSpan<'_>, a: f64, b: f64, accuracy: f64) -> Result<f64> {
    // Without cuts inside `(a, b)` the first panel is `[a, b]` at the whole
    // `accuracy`; when it is accepted and finite, the loop below would
    // return `0.0 + value` with nothing unresolved: the same bits, without
    // setting up the stack.
    if !span.cuts.iter().any(|&u| u > a && u < b) {
        let mut evaluations = 0usize;
        let (value, error) = kronrod(span, a, b, &mut evaluations);
        let total = 0.0 + value;
        if error <= accuracy.max(16.0 * f64::EPSILON * value.abs()) && total.is_finite() {
            return Ok(total);
        }
    }
    rational_length_adaptive(span, a, b, accuracy)
}

/// [`rational_length`]'s adaptive rule (every case; the caller's shortcut
/// is its first panel when that is accepted).
fn rational_length_adaptive(span: &RationalSpan<'_>, a: f64, b: f64, accuracy: f64) -> Result<f64> {
    let mut evaluations = 0usize;
    let mut total = 0.0;
    let mut unresolved = 0.0;
    let inside = span.cuts.iter().filter(|&&u| u > a && u < b);
    let share = accuracy / (inside.clone().count() + 1) as f64;
    let ends = std::iter::once(a)
        .chain(inside.copied())
        .chain(std::iter::once(b));
    let mut piece_lo = a;
    for piece_hi in ends.skip(1) {
        // Depth-first: at most one pending interval per level (depth <=
        // MAX_DEPTH), on the stack.
        let mut stack = [(0.0f64, 0.0f64, 0.0f64, 0u32); MAX_DEPTH as usize + 2];
        stack[0] = (piece_lo, piece_hi, share, 0);
        piece_lo = piece_hi;
        let mut pending = 1;
        while pending > 0 {
            pending -= 1;
            let (lo, hi, tol, depth) = stack[pending];
            let (value, error) = kronrod(span, lo, hi, &mut evaluations);
            let floor = 16.0 * f64::EPSILON * value.abs();
            if error <= tol.max(floor)
                || depth >= MAX_DEPTH
                || evaluations >= MAX_RATIONAL_EVALUATIONS
            {
                if error > tol.max(floor) {
                    unresolved += error;
                }
                total += value;
                continue;
            }
            let mid = 0.5 * (lo + hi);
            stack[pending] = (mid, hi, 0.5 * tol, depth + 1);
            stack[pending + 1] = (lo, mid, 0.5 * tol, depth + 1);
            pending += 2;
        }
    }
    if !total.is_finite() {
        return Err(BezjoinError::NonFiniteScalar {
            name: format!(
                "arc length from u = {} to u = {} (the speed overflows f64)",
                Compact(a),
                Compact(b)
            ),
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

    fn length_spans(&self) -> Vec<Span<'_>> {
        if self.weights.is_none() {
            // The spans' Bezier curves straight from the decomposition's
            // buffer: the curves `to_bezier` gives of the polynomial spans
            // of `bezier_spans`, bit for bit (their poles).
            let poles = self.span_poles();
            return (0..poles.count())
                .map(|i| {
                    let (lo, hi) = poles.domain(i);
                    Span {
                        lo,
                        hi,
                        form: SpanForm::Polynomial(Cow::Borrowed(&poles.beziers[i])),
                    }
                })
                .collect();
        }
        (0..self.span_poles().count())
            .map(|i| self.weighted_span(i))
            .collect()
    }

    /// Span `i` of a curve with weights, as [`Self::length_spans`] lists it:
    /// a span whose weights are all equal is polynomial, its Bezier curve
    /// with the poles `w P / w` (what `to_bezier` of the span of
    /// `bezier_spans` gives, bit for bit); the others are read as
    /// homogeneous rows in place, with their cuts (computed for all spans
    /// on first use and kept with the decomposition).
    fn weighted_span(&self, i: usize) -> Span<'_> {
        let poles = self.span_poles();
        let (dim, degree, h) = (self.dim, self.degree, poles.h);
        let cuts = poles.rational_cuts.get_or_init(|| {
            (0..poles.count())
                .map(|i| {
                    let (lo, hi) = poles.domain(i);
                    RationalSpan::cuts_of(poles.rows(i), dim, degree, lo, hi)
                })
                .collect()
        });
        let (lo, hi) = poles.domain(i);
        let rows = poles.rows(i);
        let equal = rows.chunks_exact(h).all(|r| r[dim] == rows[dim]);
        let polynomial = equal
            .then(|| {
                let points = rows
                    .chunks_exact(h)
                    .flat_map(|r| r[..dim].iter().map(move |x| x / r[dim]))
                    .collect();
                BezierCurve::new(dim, degree, points).ok()
            })
            .flatten();
        let form = match polynomial {
            Some(b) => SpanForm::Polynomial(Cow::Owned(b)),
            None => SpanForm::Rational(RationalSpan {
                rows,
                dim,
                degree,
                lo,
                hi,
                cuts: &cuts[i].cuts,
                bounds: cuts[i].bounds,
                horner: &cuts[i].horner,
            }),
        };
        Span { lo, hi, form }
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
    ///
    /// Errors: those of [`arc_length`](Self::arc_length) for `a` and `b`,
    /// and `NonFiniteScalar` naming the control polygon's length when that
    /// overflows `f64`: the default accuracy is relative to it.
    pub fn arc_length_default(&self, a: f64, b: f64) -> Result<f64> {
        // The caller's arguments are judged before the default they did
        // not pass, in `arc_length`'s order.
        self.check_parameter("a", a)?;
        self.check_parameter("b", b)?;
        self.arc_length(a, b, self.checked_default_length_accuracy("the curve")?)
    }

    /// [`default_length_accuracy`](Self::default_length_accuracy), or the
    /// error of `finite_default_accuracy` naming `curve`.
    pub(crate) fn checked_default_length_accuracy(&self, curve: &str) -> Result<f64> {
        finite_default_accuracy(curve, self.default_length_accuracy(), || {
            self.polygon_length()
        })
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
        let mut remaining = length.abs();
        let mut walked = 0.0;
        // One span of the walk: the answer if it lies there, else the
        // span's length taken off `remaining`.
        let mut step = |s: &Span, share: f64| -> Result<Option<f64>> {
            let (from, to) = if forward {
                (start.max(s.lo), s.hi)
            } else {
                (start.min(s.hi), s.lo)
            };
            if let Some(u) = s.param_inside(from, remaining, forward, 0.5 * accuracy) {
                return Ok(Some(u));
            }
            let piece = s.length_from(from, to, forward, share)?;
            if remaining <= piece {
                return s
                    .param_at(from, remaining, forward, 0.5 * accuracy)
                    .map(Some);
            }
            remaining -= piece;
            walked += piece;
            Ok(None)
        };
        // The spans ahead of `start`, visited in place one at a time (the
        // same spans, in the same order, as `length_spans` filtered to
        // those with `hi > start` forwards, `lo < start` backwards,
        // reversed): the breaks increase, so they are the indices
        // `lo_index..hi_index`.
        let poles = self.span_poles();
        let span = |i: usize| {
            if self.weights.is_some() {
                return self.weighted_span(i);
            }
            let (lo, hi) = poles.domain(i);
            Span {
                lo,
                hi,
                form: SpanForm::Polynomial(Cow::Borrowed(&poles.beziers[i])),
            }
        };
        let count = poles.count();
        let (lo_index, hi_index) = if forward {
            // Spans with hi > start.
            (
                (0..count)
                    .find(|&i| poles.breaks[i + 1] > start)
                    .unwrap_or(count),
                count,
            )
        } else {
            // Spans with lo < start.
            (
                0,
                (0..count)
                    .rev()
                    .find(|&i| poles.breaks[i] < start)
                    .map_or(0, |i| i + 1),
            )
        };
        let share = 0.5 * accuracy / (hi_index - lo_index).max(1) as f64;
        if forward {
            for i in lo_index..hi_index {
                if let Some(u) = step(&span(i), share)? {
                    return Ok(u);
                }
            }
        } else {
            for i in (lo_index..hi_index).rev() {
                if let Some(u) = step(&span(i), share)? {
                    return Ok(u);
                }
            }
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

#[cfg(test)]
mod tests {
    use super::{NurbsCurve, RationalChebyshev, SpanForm};

    use crate::arclength::ChebyshevSampled;
    use crate::test_values::unit_generator as generator;

    /// `int_a^b |C'|` (`a <= b`) independently of the module: the speed from
    /// de Boor's algorithm (`point_and_tangent`), a composite 8-point
    /// Gauss-Legendre rule on each knot span inside `[a, b]`, the panels
    /// doubled until two passes agree to `1e-16` relative (the speed is
    /// analytic on a span without kinks, which the callers ensure).
    fn reference_length(c: &NurbsCurve, a: f64, b: f64) -> f64 {
        const X: [f64; 4] = [
            0.183_434_642_495_649_8,
            0.525_532_409_916_329,
            0.796_666_477_413_626_7,
            0.960_289_856_497_536_3,
        ];
        const W: [f64; 4] = [
            0.362_683_783_378_362,
            0.313_706_645_877_887_3,
            0.222_381_034_453_374_5,
            0.101_228_536_290_376_3,
        ];
        let dim = c.dim;
        let speed = |u: f64| {
            let (mut p, mut t) = (vec![0.0; dim], vec![0.0; dim]);
            c.point_and_tangent(u, &mut p, Some(&mut t));
            t.iter().map(|x| x * x).sum::<f64>().sqrt()
        };
        let composite = |x0: f64, x1: f64, n: usize| {
            (0..n)
                .map(|k| {
                    let lo = x0 + (x1 - x0) * k as f64 / n as f64;
                    let hi = x0 + (x1 - x0) * (k + 1) as f64 / n as f64;
                    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
                    half * X
                        .iter()
                        .zip(&W)
                        .map(|(x, w)| w * (speed(mid - half * x) + speed(mid + half * x)))
                        .sum::<f64>()
                })
                .sum::<f64>()
        };
        let mut ends = vec![a];
        ends.extend(c.knots.iter().copied().filter(|&k| k > a && k < b));
        ends.push(b);
        ends.dedup();
        ends.windows(2)
            .map(|w| {
                let mut n = 4;
                let mut previous = composite(w[0], w[1], n);
                loop {
                    n *= 2;
                    let value = composite(w[0], w[1], n);
                    if (value - previous).abs() <= 1e-16 * value.abs() || n >= 1 << 12 {
                        return value;
                    }
                    previous = value;
                }
            })
            .sum()
    }

    /// A random rational curve: `dim` 2 or 3, degree 1 to 5, 1 to 3 spans
    /// on a shifted domain, weights in `[0.2, 5]`.
    fn random_rational(next: &mut impl FnMut() -> f64, case: usize) -> NurbsCurve {
        let dim = 2 + case % 2;
        let degree = 1 + (case / 2) % 5;
        let spans = 1 + (case / 10) % 3;
        let count = degree + spans;
        let (a, h) = (4.0 * next() - 2.0, 0.3 + 3.0 * next());
        let mut inner: Vec<f64> = (1..spans).map(|_| 0.05 + 0.9 * next()).collect();
        inner.sort_by(f64::total_cmp);
        let mut knots = vec![0.0; degree + 1];
        knots.extend(&inner);
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        let knots = knots.iter().map(|k| a + h * k).collect();
        let poles = (0..count * dim).map(|_| 4.0 * next() - 2.0).collect();
        let weights = (0..count)
            .map(|_| (25f64.ln() * next()).exp() * 0.2)
            .collect();
        NurbsCurve::new(dim, degree, poles, Some(weights), knots).unwrap()
    }

    /// The control polygon bound of a rational span's part with the
    /// cubics' constant sizes (`part_polygon_length`) is the general body's
    /// (run-time degree and dimension, the 128-value buffer) to the bit:
    /// random rational curves of degrees 1 to 5 in the plane and in space,
    /// at random `t0`, at the ends and outside, both directions.
    #[test]
    fn part_polygon_length_with_constant_sizes_is_the_general_one() {
        use std::hint::black_box;
        let mut next = generator(44);
        let mut cubics = 0;
        for case in 0..120 {
            let c = random_rational(&mut next, case);
            for s in c.length_spans() {
                let SpanForm::Rational(span) = &s.form else {
                    continue;
                };
                cubics += usize::from(span.degree == 3);
                for t0 in [next(), next(), 0.0, 1.0, 1.5] {
                    for forward in [true, false] {
                        let fast = span.part_polygon_length(t0, forward);
                        let general = span.part_polygon_sized::<128>(
                            black_box(span.degree),
                            black_box(span.dim),
                            t0,
                            forward,
                        );
                        assert_eq!(fast.to_bits(), general.to_bits(), "case {case} t0 {t0}");
                    }
                }
            }
        }
        assert!(cubics > 20, "{cubics}");
    }

    /// The part's polygon with every pole projected twice (the body before
    /// each pole was projected once): the reference for the test below.
    fn part_polygon_projecting_twice(span: &super::RationalSpan, t0: f64, forward: bool) -> f64 {
        let (p, d, hd) = (span.degree, span.dim, span.dim + 1);
        let mut w = span.rows.to_vec();
        if t0 > 0.0 && t0 < 1.0 {
            super::part_in_place(&mut w, p, hd, t0, forward);
        }
        let mut total = 0.0;
        for i in 1..=p {
            let a: Vec<f64> = (0..d)
                .map(|c| w[(i - 1) * hd + c] / w[(i - 1) * hd + d])
                .collect();
            let b: Vec<f64> = (0..d).map(|c| w[i * hd + c] / w[i * hd + d]).collect();
            total += super::distance(&a, &b);
        }
        total
    }

    /// `part_polygon_length` (each pole projected once, the previous one
    /// kept) is the polygon projecting every pole twice to the bit, with
    /// the constant sizes and the general body: random rational curves of
    /// degrees 1 to 5 in the plane and in space, at random `t0`, at the ends
    /// and outside, both directions.
    #[test]
    fn part_polygon_length_projecting_once_is_projecting_twice() {
        let mut next = generator(45);
        for case in 0..120 {
            let c = random_rational(&mut next, case);
            for s in c.length_spans() {
                let SpanForm::Rational(span) = &s.form else {
                    continue;
                };
                for t0 in [next(), next(), 0.0, 1.0, 1.5] {
                    for forward in [true, false] {
                        let once = span.part_polygon_length(t0, forward);
                        let twice = part_polygon_projecting_twice(span, t0, forward);
                        assert_eq!(once.to_bits(), twice.to_bits(), "case {case} t0 {t0}");
                    }
                }
            }
        }
    }

    /// `rational_length`'s shortcut (one accepted panel on `[a, b]` without
    /// cuts inside) is the adaptive rule's answer bit for bit, errors
    /// included, and meets the accuracy against the independent
    /// [`reference_length`]: every rational span of random curves (degrees
    /// 1 to 5, plane and space, weights in `[0.2, 5]`) and of the kinked
    /// curve (cuts inside), random `a < b` and whole spans, accuracies from
    /// `1e-3` to `1e-14` relative (both the shortcut and the refinement
    /// occur).
    #[test]
    fn rational_length_shortcut_is_the_adaptive_rule_to_the_bit() {
        use super::{rational_length, rational_length_adaptive};
        let mut next = generator(91);
        let (mut short, mut refined, mut cut) = (0, 0, 0);
        let mut curves: Vec<NurbsCurve> = (0..150)
            .map(|case| random_rational(&mut next, case))
            .collect();
        curves.push(kinked_curve());
        for c in &curves {
            for s in c.length_spans() {
                let SpanForm::Rational(span) = &s.form else {
                    continue;
                };
                for k in 0..6 {
                    let (x, y) = (next(), next());
                    let (a, b) = if k == 0 {
                        (s.lo, s.hi)
                    } else {
                        (s.global(x.min(y)), s.global(x.max(y)))
                    };
                    if a >= b {
                        continue;
                    }
                    let scale = c.polygon_length().max(1e-300);
                    let relative = [1e-3, 1e-6, 1e-9, 1e-12, 1e-14, 1e-8][k];
                    let accuracy = relative * scale;
                    let fast = rational_length(span, a, b, accuracy);
                    let general = rational_length_adaptive(span, a, b, accuracy);
                    match (&fast, &general) {
                        (Ok(f), Ok(g)) => {
                            assert_eq!(f.to_bits(), g.to_bits(), "{a} {b} {accuracy}")
                        }
                        (Err(f), Err(g)) => assert_eq!(format!("{f}"), format!("{g}")),
                        _ => panic!("{fast:?} {general:?}"),
                    }
                    let inside = span.cuts.iter().any(|&u| u > a && u < b);
                    cut += usize::from(inside);
                    let mut evaluations = 0;
                    let (_, error) = super::kronrod(span, a, b, &mut evaluations);
                    if !inside && error <= accuracy {
                        short += 1;
                    } else {
                        refined += 1;
                    }
                    if let Ok(f) = fast {
                        if !inside && relative >= 1e-12 {
                            let reference = reference_length(c, a, b);
                            let floor = 64.0 * f64::EPSILON * reference;
                            assert!(
                                (f - reference).abs() <= accuracy.max(floor),
                                "{f} {reference} {accuracy}"
                            );
                        }
                    }
                }
            }
        }
        assert!(
            short > 300 && refined > 100 && cut > 5,
            "{short} {refined} {cut}"
        );
    }

    /// The Chebyshev inversion on a rational span (`RationalChebyshev`,
    /// taken when the span's `N = A' w - A w'` is provably away from zero)
    /// meets its contract: the length from `start` to its answer, by the
    /// independent [`reference_length`], is within `accuracy` of the length
    /// asked for. Random rational curves of degrees 1 to 5 in the plane and
    /// in space, weights in `[0.2, 5]`, starts anywhere in a span (and at its
    /// ends), lengths over the whole span, both directions, accuracies
    /// `1e-12` and `1e-9` relative. Also its speed (`horner_speed`, from
    /// `N` and `w`) is de Casteljau's on the homogeneous poles
    /// (`RationalSpan::speed_any`) within rounding, its rounding floor far
    /// below the speed, and enough
    /// spans qualify and are answered (the path is exercised).
    #[test]
    fn rational_chebyshev_inversion_meets_its_accuracy() {
        let mut next = generator(20);
        let (mut qualified, mut spans, mut answered, mut asked) = (0, 0, 0, 0);
        for case in 0..120 {
            let c = random_rational(&mut next, case);
            for s in c.length_spans() {
                let SpanForm::Rational(span) = &s.form else {
                    continue;
                };
                spans += 1;
                let Some(speed) = RationalChebyshev::new(span) else {
                    continue;
                };
                qualified += 1;
                // The rounding floor stays far below the speed (so that the
                // accuracies asked for are met by the estimate, not
                // excused by the floor): `(q + 1) eps` relative, and the
                // products' size, near the origin within a few hundred.
                let (_, high) = speed.speed_bounds();
                assert!(
                    speed.noise_per_unit() <= 1e-11 * high,
                    "case {case}: noise {} for speeds up to {high}",
                    speed.noise_per_unit()
                );
                for k in 0..=8 {
                    let u = s.lo + (s.hi - s.lo) * k as f64 / 8.0;
                    let t = (u - s.lo) / (s.hi - s.lo);
                    let (a, b) = (speed.speed_at(u), span.speed_any(t) / (s.hi - s.lo));
                    assert!(
                        (a - b).abs() <= 1e-12 * b,
                        "case {case}: speed {a} vs {b} at {u}"
                    );
                }
                for trial in 0..6 {
                    let start = match trial {
                        0 => s.lo,
                        1 => s.hi,
                        _ => s.lo + (s.hi - s.lo) * next(),
                    };
                    let forward = trial == 0 || (trial > 1 && next() < 0.5);
                    let room = if forward {
                        reference_length(&c, start, s.hi)
                    } else {
                        reference_length(&c, s.lo, start)
                    };
                    let target = room * (0.02 + 0.96 * next());
                    if target.is_nan() || target <= 0.0 {
                        continue;
                    }
                    let accuracy = [1e-12, 1e-9][trial % 2] * target;
                    let signed = if forward { target } else { -target };
                    asked += 1;
                    let Some(u) = speed.param_at_length(start, signed, accuracy) else {
                        continue;
                    };
                    answered += 1;
                    let got = reference_length(&c, start.min(u), start.max(u));
                    assert!(
                        (got - target).abs() <= accuracy,
                        "case {case} trial {trial}: length {got} for {target} (accuracy {accuracy}, off {:.3e})",
                        (got - target).abs() / accuracy
                    );
                    // And through the public inversion (which tries it first).
                    let v = c.param_at_length(start, signed, accuracy).unwrap();
                    let got = reference_length(&c, start.min(v), start.max(v));
                    assert!(
                        (got - target).abs() <= accuracy,
                        "case {case} trial {trial}"
                    );
                }
            }
        }
        // Random poles make loops: about a third of the spans keep `N`'s
        // polygon in a half-plane with the margin.
        assert!(
            4 * qualified > spans,
            "only {qualified} of {spans} rational spans qualify"
        );
        eprintln!("{qualified} of {spans} spans qualify, {answered} of {asked} answered");
        assert!(
            4 * answered > 3 * asked,
            "only {answered} of {asked} inversions answered by the Chebyshev path"
        );
    }

    /// A span whose speed has kinks (the one-dimensional curve of
    /// [`rational_length_across_kinks_meets_its_accuracy`]) never takes the
    /// Chebyshev path: its spans with cuts have no bounds.
    #[test]
    fn spans_with_cuts_do_not_take_the_chebyshev_path() {
        let c = kinked_curve();
        let mut cut = 0;
        for s in c.length_spans() {
            if let SpanForm::Rational(span) = &s.form {
                if !span.cuts.is_empty() {
                    cut += 1;
                    assert!(RationalChebyshev::new(span).is_none());
                }
            }
        }
        assert!(cut > 0);
    }

    /// A rational span whose speed has kinks inside (a one-dimensional
    /// curve turning back: `C'` changes sign): its length at a tight
    /// accuracy meets that accuracy against an independent reference, the
    /// speed from de Boor's algorithm (`point_and_tangent`), its sign
    /// changes located by bisection, and a composite 5-point
    /// Gauss-Legendre rule on each smooth piece between them. Without the
    /// cuts at the kinks (`RationalSpan::cuts_of`) the Gauss-Kronrod check
    /// accepted a panel across a kink: measured `2.6e-11` off at `6.2e-14`
    /// on this curve (the inversion test's random case that found it).
    #[test]
    fn rational_length_across_kinks_meets_its_accuracy() {
        let c = kinked_curve();
        rational_length_across_kinks(&c);
    }

    /// The one-dimensional degree-5 rational curve that turns back (the
    /// inversion test's random case 68).
    fn kinked_curve() -> NurbsCurve {
        let poles = vec![
            2.3158259354913726,
            4.503647148417016,
            3.1019149764740988,
            -4.428100189994561,
            0.35435796215622073,
            3.3632577678205546,
            -0.06362190290908476,
            1.6426265002983254,
            -4.499992475682969,
            4.955582215009798,
        ];
        let knots = vec![
            0.4794442489523907,
            1.0738268284322547,
            1.5186117806068087,
            1.721586033985297,
            2.663142354005702,
            3.3701910197778306,
            3.3701910197778306,
            3.478010361062626,
            3.9420339567676317,
            3.9420339567676317,
            3.9420339567676317,
            3.9420339567676317,
            3.9420339567676317,
            4.254525833658945,
            4.54479656576175,
            5.038934060533719,
        ];
        let weights = vec![
            0.7739740083584901,
            2.453384181696604,
            2.663719645079522,
            0.3358887923977314,
            2.669332842909135,
            2.723990046834692,
            1.1182546283442611,
            0.8592184501846636,
            2.142553227337032,
            0.494082404683343,
        ];
        NurbsCurve::new(1, 5, poles, Some(weights), knots).unwrap()
    }

    fn rational_length_across_kinks(c: &NurbsCurve) {
        let derivative = |u: f64| {
            let (mut p, mut t) = ([0.0], [0.0]);
            c.point_and_tangent(u, &mut p, Some(&mut t));
            t[0]
        };
        // 5-point Gauss-Legendre on [-1, 1].
        let nodes = [
            0.0,
            0.538_469_310_105_683,
            -0.538_469_310_105_683,
            0.906_179_845_938_664,
            -0.906_179_845_938_664,
        ];
        let rule = [
            0.568_888_888_888_888_9,
            0.478_628_670_499_366_5,
            0.478_628_670_499_366_5,
            0.236_926_885_056_189_1,
            0.236_926_885_056_189_1,
        ];
        let composite = |a: f64, b: f64| {
            let n = 400;
            (0..n)
                .map(|k| {
                    let (x0, x1) = (
                        a + (b - a) * k as f64 / n as f64,
                        a + (b - a) * (k + 1) as f64 / n as f64,
                    );
                    let (mid, half) = (0.5 * (x0 + x1), 0.5 * (x1 - x0));
                    half * nodes
                        .iter()
                        .zip(&rule)
                        .map(|(x, w)| w * derivative(mid + half * x).abs())
                        .sum::<f64>()
                })
                .sum::<f64>()
        };
        let reference = |a: f64, b: f64| {
            // Sign changes of C' on a fine grid, refined by bisection.
            let mut ends = vec![a];
            let grid = 4000;
            let at = |k: usize| a + (b - a) * k as f64 / grid as f64;
            for k in 0..grid {
                let (mut lo, mut hi) = (at(k), at(k + 1));
                if derivative(lo) * derivative(hi) < 0.0 {
                    for _ in 0..200 {
                        let mid = 0.5 * (lo + hi);
                        if mid <= lo || mid >= hi {
                            break;
                        }
                        if derivative(lo) * derivative(mid) <= 0.0 {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    ends.push(0.5 * (lo + hi));
                }
            }
            ends.push(b);
            assert!(ends.len() >= 3, "the range holds a kink: {ends:?}");
            ends.windows(2).map(|w| composite(w[0], w[1])).sum::<f64>()
        };
        for (a, b, accuracy) in [
            (3.7100221589151285, 3.924053459701759, 6.2e-14),
            (3.478010361062626, 3.9326640992722726, 1e-13),
            (3.3701910197778306, 3.9420339567676317, 1e-12),
        ] {
            let length = c.arc_length(a, b, accuracy).unwrap();
            let exact = reference(a, b);
            assert!(
                (length - exact).abs() <= accuracy + 8.0 * f64::EPSILON * exact,
                "[{a}, {b}]: {length} vs {exact}, accuracy {accuracy}"
            );
        }
    }

    /// The multi-span inversion (the answer inside the span that holds it
    /// without that span's length first; the lengths of the spans walked
    /// past by the Chebyshev interpolant where it certifies) meets its
    /// contract: the length from `start` to the answer, by an independent
    /// quadrature (the span-by-span adaptive Gauss-Legendre / Gauss-Kronrod
    /// `arc_length` at a thousandth of the accuracy), is within `accuracy`
    /// of the length asked for. Polynomial and rational curves of degrees
    /// 2 to 4 with 2 to 6 spans on shifted domains, starts at random and at
    /// knots, lengths that cross one or more span boundaries and lengths
    /// ending near a knot, both directions, accuracies 1e-12 to 1e-6
    /// relative.
    #[test]
    fn multi_span_inversion_meets_its_accuracy() {
        let mut next = generator(3);
        let mut crossed = 0;
        for case in 0..160 {
            let degree = 2 + case % 3;
            let count = degree + 2 + (case / 3) % 5;
            let rational = case % 4 == 3;
            let (a, h) = (6.0 * next() - 3.0, 0.5 + 4.0 * next());
            let mut knots = vec![0.0; degree + 1];
            knots.extend((1..count - degree).map(|i| i as f64 / (count - degree) as f64));
            knots.extend(std::iter::repeat_n(1.0, degree + 1));
            let knots: Vec<f64> = knots.iter().map(|k| a + h * k).collect();
            let poles: Vec<f64> = (0..count)
                .flat_map(|i| [i as f64 + 0.6 * next(), 1.5 * next()])
                .collect();
            let weights = rational.then(|| (0..count).map(|_| 0.5 + 1.5 * next()).collect());
            let c = NurbsCurve::new(2, degree, poles, weights, knots.clone()).unwrap();
            let (first, last) = c.domain();
            let total = c.arc_length(first, last, 1e-14).unwrap();
            let inner: Vec<f64> = knots[degree + 1..count].to_vec();
            for trial in 0..6 {
                let start = if trial % 3 == 0 {
                    inner[trial % inner.len()]
                } else {
                    first + (last - first) * next()
                };
                let forward = trial % 2 == 0;
                let room = if forward {
                    c.arc_length(start, last, 1e-14).unwrap()
                } else {
                    c.arc_length(first, start, 1e-14).unwrap()
                };
                // A length to just past or just short of a knot, or random.
                let target = if trial == 4 {
                    let k = inner[inner.len() / 2];
                    let to_knot = c.arc_length(start.min(k), start.max(k), 1e-14).unwrap();
                    to_knot * (1.0 + 1e-9 * (next() - 0.5))
                } else {
                    room * (0.05 + 0.9 * next())
                };
                if !(target > 0.0 && target < room) {
                    continue;
                }
                let relative = [1e-12, 1e-9, 1e-6][trial % 3];
                let accuracy = relative * total;
                let signed = if forward { target } else { -target };
                let u = c.param_at_length(start, signed, accuracy).unwrap();
                assert!(u >= first && u <= last, "case {case} trial {trial}");
                if inner.iter().any(|&k| (k - start) * (k - u) < 0.0) {
                    crossed += 1;
                }
                let got = c.arc_length(start, u, 1e-3 * accuracy).unwrap();
                assert!(
                    (got - signed).abs() <= accuracy,
                    "case {case} trial {trial}: length {got} for {signed} (accuracy {accuracy})"
                );
            }
        }
        assert!(crossed > 200, "only {crossed} inversions crossed a knot");
    }
}
