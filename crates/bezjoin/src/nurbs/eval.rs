//! Values and derivatives of a NURBS curve through its Bezier spans (issue
//! 20: NURBS inputs within 2x their Bezier counterparts), the route of
//! [`NurbsCurve::eval_derivatives_checked_into`] (`bzj_curve_eval`,
//! `bzj_curve_eval_many`) for dimensions 2 and 3 up to degree
//! [`SPAN_FAST_MAX_DEGREE`] and orders up to [`TABLE_MAX_ORDER`].
//!
//! * A clamped one-span polynomial curve (a Bezier curve as a NURBS handle)
//!   is evaluated from its own poles by the Bezier curve's kernel
//!   (`bernstein_horner_any`, the operations of
//!   [`BezierCurve::eval_into`](crate::BezierCurve::eval_into) and
//!   [`BezierCurve::eval_derivatives_into`](crate::BezierCurve::eval_derivatives_into)
//!   in their order, the falling factorials divided by the span length):
//!   on the domain `[0, 1]` the very bits of the Bezier curve (tested). No
//!   table is built.
//! * Any other curve (rational, several spans, free end knots) reads its
//!   span's rows from a [`SpanTable`] built once, on the first evaluation
//!   of a derivative. For each order `k <= min(p, 3)` the table holds the
//!   Bezier poles, on every span, of the derivative curve `A^(k)`
//!   (homogeneous `(w P, w)` for a rational curve): the derivative control
//!   points of The NURBS Book A3.3 (`Q_i = q (R_(i+1) - R_i) /
//!   (u_(i+q+1) - u_(i+1))`, degree `q` to `q - 1`, applied `k` times),
//!   then on every span knot insertion (A5.1, convex combinations)
//!   confined to the span's window, its ends raised to multiplicity
//!   `p - k` (free end knots need no clamping first; no allocation per
//!   insertion), each pole times its binomial
//!   `C(p - k, j)`. So `A^(k)(u) = sum_j C(p-k, j) Q^(k)_j t^j (1-t)^(p-k-j)`,
//!   `t = (u - a) / (b - a)` on the span `[a, b]`, one Bernstein-Horner
//!   sum per order (the ratio `(1 - t) / t` or `t / (1 - t)`, whichever is
//!   at most 1, shared by all orders), with no differences taken at
//!   evaluation: the derivative rows carry the rounding of the derivative
//!   control points (like the basis route, A2.3), not `2^k / (b - a)^k`
//!   times the rounding of the span's poles (which a difference table of
//!   the span's Bezier poles would give: on a short span beside long ones
//!   that loses digits, tested). A rational curve then takes the quotient
//!   rule (A4.2) `C^(k) = (A^(k) - sum_(i=1..k) C(k, i) w^(i) C^(k-i)) / w`
//!   with one division by `w`. Everything on the stack at evaluation.
//!
//! Building a table costs about 8 evaluations by the basis route (48,000
//! instructions for the rational quintic below, against 6,500 for one
//! basis-route evaluation of orders 0 to 3, 970 for one from the table).
//!
//! Memory of a table: `S sum_(k=0..K) (p - k + 1) h + S + 1` doubles for
//! `S` spans, `K = min(p, 3)`, `h = d + 1` (rational) or `d` coordinates: a
//! rational quintic of 6 spans in 3D keeps `6 * 18 * 4 + 7 = 439` doubles
//! (3.5 KB) beside its 11 poles, 11 weights and 17 knots; a polynomial
//! cubic of `S` spans in 3D `30 S + S + 1`.
//!
//! The jets with rounding bounds that connect, the fillets and the G^k
//! blends take ([`CurveJet::jet_into`](crate::curve::CurveJet::jet_into))
//! come from the spans' Bezier rows as well: a one-span polynomial curve
//! by de Casteljau on its poles (`bezier_span_jet_into`), a polynomial
//! curve of several spans on its span's poles in the kept decomposition
//! (`spans_jet_into`), a rational curve on its span's homogeneous rows then
//! the quotient rule, the bounds carried through
//! (`rational_spans_jet_into`, issue 20: NURBS inputs within 2x their Bezier
//! counterparts); each with the decomposition's rounding in its bound.
//!
//! The values (order 0) of a curve of several spans stay on A2.2
//! (`value_fast_into`, the bits of the basis route). A sum that is not
//! finite is caught by the caller, which then takes the basis route.

use std::sync::OnceLock;

use super::NurbsCurve;
use crate::basis::{KnotSide, find_span};
use crate::bezier::bernstein_horner_any;

/// Highest degree evaluated here (stack arrays of this size plus one
/// rows); above it the basis route.
pub(super) const SPAN_FAST_MAX_DEGREE: usize = 15;

/// Highest derivative order whose rows a [`SpanTable`] holds (the orders
/// of a host's `D0` to `D3`); a request for more takes the basis route.
pub(super) const TABLE_MAX_ORDER: usize = 3;

/// Largest bound, relative to the row's 1-norm, that
/// [`NurbsCurve::rational_spans_jet_into`] returns; a row above it (a short
/// span beside long ones, orders far above the degree: the span route's
/// differences lose digits there, the basis route's wider knot intervals do
/// not) sends the jet to the basis route (A2.3).
pub(super) const RATIONAL_SPAN_RELATIVE_BOUND: f64 = 1e-10;

/// Highest order of [`NurbsCurve::rational_spans_jet_into`] (the rows of
/// Pascal's triangle in [`BINOMIALS`]); above it the basis route.
pub(super) const RATIONAL_SPAN_MAX_ORDER: usize = SPAN_FAST_MAX_DEGREE;

/// Rows `0..=SPAN_FAST_MAX_DEGREE` of Pascal's triangle (row `n` starts at
/// `n (n + 1) / 2`), exact in `f64`.
pub(super) const BINOMIALS: [f64; 136] = binomial_rows();

const fn binomial_rows() -> [f64; 136] {
    let mut table = [0.0; 136];
    let mut n = 0;
    while n <= SPAN_FAST_MAX_DEGREE {
        let row = n * (n + 1) / 2;
        table[row] = 1.0;
        let mut i = 1;
        while i <= n {
            // C(n, i) = C(n - 1, i - 1) + C(n - 1, i), the last term 0 at i = n.
            let above = (n - 1) * n / 2;
            let right = if i < n { table[above + i] } else { 0.0 };
            table[row + i] = table[above + i - 1] + right;
            i += 1;
        }
        n += 1;
    }
    table
}

/// `C(n, i)` by the recurrence `C(n, j) = C(n, j - 1) (n + 1 - j) / j`,
/// each step exact in `f64` while the values are integers below `2^53`.
fn binomial(n: usize, i: usize) -> f64 {
    let mut c = 1.0;
    for j in 1..=i {
        c = c * (n + 1 - j) as f64 / j as f64;
    }
    c
}

/// The Bezier rows of the derivative curves of every span (see the module
/// documentation).
#[derive(Debug)]
pub(super) struct SpanTable {
    /// The distinct knots of the domain, `S + 1` values.
    breaks: Vec<f64>,
    /// `S` blocks of `block` values: in each, for `k = 0..=K`, the
    /// `p - k + 1` rows `C(p - k, j) Q^(k)_j` of `h` values.
    rows: Vec<f64>,
    /// Values per span.
    block: usize,
}

/// The lazily built [`SpanTable`] of a curve. It is derived from the
/// curve's data and invisible from outside: equal for any two curves
/// (`PartialEq` compares the data only), empty in a clone (built again on
/// demand), shown as `SpanCache` by `Debug`. Sound because a curve's
/// fields are written only while it is being constructed (the few writes
/// in `knots.rs` and `spans.rs` touch a curve just built, before anything
/// evaluates it): the table always describes the data it sits beside.
#[derive(Default)]
pub(super) struct SpanCache(
    OnceLock<SpanTable>,
    /// The span decomposition ([`NurbsCurve::span_poles`]), boxed: a
    /// curve without it stays small.
    pub(super) OnceLock<Box<super::spans::SpanPoles>>,
);

impl Clone for SpanCache {
    fn clone(&self) -> Self {
        SpanCache::default()
    }
}

impl PartialEq for SpanCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for SpanCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SpanCache")
    }
}

impl NurbsCurve {
    /// The jet `C^(k)(u)`, `k = 0..=order`, of a clamped one-span
    /// polynomial curve (a Bezier curve as a NURBS handle) with a
    /// first-order rounding bound per row, into `values`
    /// (`(order + 1) * dim`, row-major) and `errors` (`order + 1`), as
    /// [`CurveJet::jet_into`](crate::curve::CurveJet::jet_into) wants them;
    /// `false` (nothing written) for any other curve, a dimension above 4
    /// or a degree above 15, which keep the A2.3 route. The parameter must
    /// already be checked (finite, in the domain).
    ///
    /// The poles are the Bezier control points of the domain `[a, b]`, so
    /// with `h = b - a` and `t = (u - a) / h`, `C^(k)(u) = h^-k B^(k)(t)`
    /// where `B` is that Bezier curve and `B^(k)` its derivatives in `t`,
    /// taken from the de Casteljau triangle with its bound `e_k`
    /// ([`de_casteljau_jet_into`](crate::connect::de_casteljau_jet_into),
    /// the jet of a Bezier input to connect).
    ///
    /// * On `[0, 1]`, `t = u` and `h^-k = 1` exactly: the values and bounds
    ///   of the Bezier curve's de Casteljau jet, to the bit.
    /// * Elsewhere the computed `fl(t) = fl(fl(u - a) / fl(h))` is within
    ///   `|dt| <= 3 u_r |t|` of `t` (three roundings, `u_r` the unit
    ///   roundoff), which moves row `k` by at most
    ///   `|B^(k+1)(t)| |dt| <= (|fl(B^(k+1))| + e_(k+1)) 3 u_r |t|` to first
    ///   order (0 above the degree); `fl(1 / fl(h))^k` and its product
    ///   with the row carry at most `3k u_r` relative error (one rounding
    ///   for `h`, one for the inverse, `k - 1` products, one product with
    ///   the row). Row `k`'s bound is
    ///   `fl(h^-k) (e_k + (|fl(B^(k+1))| + e_(k+1)) 3 u_r |t|) + 2 (3k + 2)
    ///   u_r |fl(C^(k))|`, the last term twice the scaling's rounding, which
    ///   also covers the rounding of the bound's own sums.
    pub(crate) fn bezier_span_jet_into(
        &self,
        u: f64,
        order: usize,
        values: &mut [f64],
        errors: &mut [f64],
    ) -> bool {
        let (p, dim) = (self.degree, self.dim);
        if self.weights.is_some() || !self.is_bezier_span() || dim > 4 || p > 15 {
            return false;
        }
        debug_assert_eq!(values.len(), (order + 1) * dim);
        debug_assert_eq!(errors.len(), order + 1);
        let poles = &self.points[..(p + 1) * dim];
        let (a, b) = (self.knots[p], self.knots[p + 1]);
        if a == 0.0 && b == 1.0 {
            crate::connect::de_casteljau_jet_into(poles, dim, p, u, order, values, errors);
            return true;
        }
        scaled_span_jet_into(poles, dim, p, ((a, b), 0.0), u, order, None, values, errors);
        true
    }

    /// [`bezier_span_jet_into`](Self::bezier_span_jet_into) for a
    /// polynomial curve of several spans, dimension at most 4 and degree at
    /// most 15: the jet of the span that holds `u` (at a knot the span
    /// ending there for [`KnotSide::Left`], the one starting there for
    /// [`KnotSide::Right`]), from that span's Bezier poles in the kept
    /// decomposition ([`NurbsCurve::span_poles`]). Those poles come from
    /// knot insertions, convex combinations that each round by at most
    /// `2 u_r S` per coordinate (`S` the largest pole coordinate); a pole
    /// goes through at most `p` insertions at each of the `p + 1` knots
    /// that reach it, so it lies within `delta = 2 (p + 1)^2 u_r S sqrt(d)`
    /// of the exact span pole (the bound used is twice that), and the
    /// `k`-th derivative in `t`, `p!/(p-k)! sum Delta^k P_i B_i^(p-k)(t)`,
    /// moves by at most `p!/(p-k)! 2^k delta`: that, times `h^-k`, is added
    /// to row `k`'s bound of [`Self::bezier_span_jet_into`]'s analysis. `false`
    /// (nothing written) for other curves.
    pub(crate) fn spans_jet_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) -> bool {
        let (p, dim) = (self.degree, self.dim);
        if self.weights.is_some() || dim > 4 || p > 15 {
            return false;
        }
        debug_assert_eq!(values.len(), (order + 1) * dim);
        debug_assert_eq!(errors.len(), order + 1);
        let (poles, span) = self.decomposed_span(u, side);
        scaled_span_jet_into(poles, dim, p, span, u, order, None, values, errors);
        true
    }

    /// The Bezier poles of the span of the kept decomposition that holds
    /// `u` (from `side` at a knot), its domain, and `delta`: the bound
    /// `4 (p + 1)^2 u S sqrt(dim)` on each pole's distance from the exact
    /// one ([`spans_jet_into`](Self::spans_jet_into)'s analysis).
    #[inline]
    fn decomposed_span(&self, u: f64, side: KnotSide) -> (&[f64], ((f64, f64), f64)) {
        let spans = self.span_poles();
        let i = spans.span_at(u, side);
        let unit = f64::EPSILON / 2.0;
        let q = (self.degree + 1) as f64;
        let delta = 4.0 * q * q * unit * spans.scale * (self.dim as f64).sqrt();
        (spans.beziers[i].points(), (spans.domain(i), delta))
    }

    /// The jet of a polynomial curve (dimension 2 to 4, degree 1 to 15)
    /// as [`CurveJet::jet_into`](crate::curve::CurveJet::jet_into) takes it
    /// ([`bezier_span_jet_into`](Self::bezier_span_jet_into) for one
    /// clamped span, [`spans_jet_into`](Self::spans_jet_into) otherwise):
    /// the same values bit for bit (the de Casteljau values of the same
    /// poles, [`de_casteljau_values_into`](crate::connect::de_casteljau_values_into),
    /// scaled by the same products), with bounds never below that route's
    /// (to first order) that need no sizes' triangle and no square root:
    /// the connect's screen ([`CurveJet::jet_screen_into`](crate::curve::CurveJet::jet_screen_into)).
    ///
    /// That route bounds row `k` in `t` by
    /// `p!/(p-k)! 2 u (3 (p - k) + k + 1) S_k(a)`, where
    /// `S_k(a) = sum_j C(k, j) a^(p-k)_j` over level `p - k` of the
    /// triangle run on the poles' Euclidean sizes `a` (weights `|1 - t|`
    /// and `|t|`, which sum to 1 on `[0, 1]`). Every size in that triangle
    /// is at most `A = sqrt(dim) scale`, where `scale` is at least the
    /// largest absolute pole coordinate (the curve's
    /// [`coordinate_scale`](NurbsCurve::coordinate_scale): a span's poles
    /// are convex combinations of the curve's, to rounding), so
    /// `S_k(a) <= 2^k A`: that replaces the triangle. The rest of the
    /// bound (the parameter's rounding, `(b - a)^-k`, the decomposition's
    /// `delta`) is the route's own, with 1-norms for its Euclidean norms.
    /// `false` (nothing written) for other curves.
    pub(crate) fn span_jet_screen_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        scale: f64,
        values: &mut [f64],
        errors: &mut [f64],
    ) -> bool {
        let (p, dim) = (self.degree, self.dim);
        if self.weights.is_some() || !(2..=4).contains(&dim) || !(1..=15).contains(&p) {
            return false;
        }
        debug_assert_eq!(values.len(), (order + 1) * dim);
        debug_assert_eq!(errors.len(), order + 1);
        let size = (dim as f64).sqrt() * scale;
        if self.is_bezier_span() {
            let poles = &self.points[..(p + 1) * dim];
            let (a, b) = (self.knots[p], self.knots[p + 1]);
            if a == 0.0 && b == 1.0 {
                // `de_casteljau_jet_into` at `u` itself: its rows and
                // bounds, the bounds a priori.
                let m = order.min(p);
                values[(m + 1) * dim..].fill(0.0);
                errors[m + 1..].fill(0.0);
                crate::connect::de_casteljau_values_into(poles, dim, p, u, m, values);
                triangle_bounds(p, (size, 0.0), &mut errors[..=m]);
                return true;
            }
            let screen = Some(size);
            scaled_span_jet_into(
                poles,
                dim,
                p,
                ((a, b), 0.0),
                u,
                order,
                screen,
                values,
                errors,
            );
            return true;
        }
        let (poles, span) = self.decomposed_span(u, side);
        scaled_span_jet_into(poles, dim, p, span, u, order, Some(size), values, errors);
        true
    }

    /// [`spans_jet_into`](Self::spans_jet_into) for a curve with weights,
    /// dimension at most 3, degree 1 to 15 and orders up to
    /// [`RATIONAL_SPAN_MAX_ORDER`]: the jet of the homogeneous curve
    /// `A = (w C, w)` (`h = dim + 1` coordinates) from its span's
    /// homogeneous Bezier rows in the kept decomposition, then the quotient
    /// rule (The NURBS Book A4.2)
    /// `C^(k) = (A^(k) - sum_(i=1..k) C(k, i) w^(i) C^(k-i)) / w`. No square
    /// root: the norms in the bounds are 1-norms (never below the Euclidean
    /// norms they stand for).
    ///
    /// The homogeneous rows in `t = (u - a) / (b - a)` are the de Casteljau
    /// jet's values ([`de_casteljau_values_into`](crate::connect::de_casteljau_values_into)).
    /// Their bounds: the triangle's rounding (the bound of
    /// `de_casteljau_jet_into`, whose analysis holds in any absolute norm,
    /// here the 1-norm) is at most `p!/(p-k)! 2 u (3 (p - k) + k + 1) S_k(a)`
    /// with `S_k(x) = sum_j C(k, j) x^(p-k)_j` over level `p - k` of the
    /// triangle run on the scalars `x` (weights `|1 - t|`, `|t|`), `a` the
    /// rows' 1-norms; the rows' own rounding `e` (the products `w_i x_i`
    /// and every insertion, tracked when the decomposition is built) moves row `k` by at most `p!/(p-k)! S_k(e)`
    /// (the triangle and the differences are linear and their absolute
    /// versions dominate them). With every size at its largest,
    /// `S_k(x) <= 2^k max_j x_j`, so row `k` in `t` is within
    /// `p!/(p-k)! 2^k (2 u (3 (p - k) + k + 1) A + E)`, `A` and `E` the
    /// span's largest row 1-norm and row error, kept per span
    /// ([`SpanPoles::span_sizes`](super::spans::SpanPoles)). The parameter's
    /// rounding and the factor `(b - a)^-k` are then bounded as in
    /// `spans_jet_into`, giving `E_k` for the homogeneous row `k` in `u` (it
    /// bounds `|dA^(k)|` and `|dw^(k)|`).
    ///
    /// The quotient rule's bound, to first order, with `e_k` the bound of
    /// `C^(k)` (from `C^(k) w = N_k`, the numerator `N_k` moved by the
    /// errors of `A^(k)`, of the `w^(i)` and of the earlier rows, the
    /// quotient by the error of `w`):
    ///
    /// ```text
    /// e_k = ( E_k + sum_(i=1..k) C(k, i) (E_i |C^(k-i)| + |w^(i)| e_(k-i))
    ///         + E_0 |C^(k)|
    ///         + gamma_k (|A^(k)| + sum_(i=1..k) C(k, i) |w^(i)| |C^(k-i)|) ) / |w|
    /// ```
    ///
    /// with `gamma_k = 2 (k + 3) u_r`, twice the rounding of the row's `k`
    /// products, `k` subtractions and one division (the factor 2 also
    /// covers the rounding of the bound's own sums).
    ///
    /// `false` for other curves; when `(b - a)^-k` leaves the normal range
    /// or a row's 1-norm is zero, subnormal, infinite or NaN (rounding there
    /// is not relative: an underflowed row could come back 0 with bound 0);
    /// and
    /// when a row's bound exceeds
    /// [`RATIONAL_SPAN_RELATIVE_BOUND`] times its 1-norm (a short span beside
    /// long ones, orders far above the degree; 20 of the 354 jets of the
    /// test `rational_spans_jet_is_within_its_bound_of_the_exact_jet`): the
    /// caller then takes the basis route, which writes every value and
    /// bound again.
    pub(crate) fn rational_spans_jet_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) -> bool {
        self.rational_spans_jet_within(u, order, side, values, errors, RATIONAL_SPAN_RELATIVE_BOUND)
    }

    /// [`rational_spans_jet_into`](Self::rational_spans_jet_into) with the
    /// relative bound `limit` in place of [`RATIONAL_SPAN_RELATIVE_BOUND`];
    /// with `f64::INFINITY` (the tests) nothing is declined, not even the
    /// range checks: every bound, however loose, for data in the normal
    /// range.
    pub(crate) fn rational_spans_jet_within(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
        limit: f64,
    ) -> bool {
        let (p, dim) = (self.degree, self.dim);
        if self.weights.is_none()
            || dim > 3
            || !(1..crate::connect::SMALL_JET_POINTS).contains(&p)
            || order > RATIONAL_SPAN_MAX_ORDER
        {
            return false;
        }
        debug_assert_eq!(values.len(), (order + 1) * dim);
        debug_assert_eq!(errors.len(), order + 1);
        // The dimension, and degrees 1 to 5, as constants (the triangle's
        // arrays sized exactly); other degrees in arrays of 16 rows.
        macro_rules! by_degree {
            ($d:literal, $h:literal) => {
                match p {
                    1 => self.rational_span_jet::<$d, $h, 2>(u, order, side, values, errors, limit),
                    2 => self.rational_span_jet::<$d, $h, 3>(u, order, side, values, errors, limit),
                    3 => self.rational_span_jet::<$d, $h, 4>(u, order, side, values, errors, limit),
                    4 => self.rational_span_jet::<$d, $h, 5>(u, order, side, values, errors, limit),
                    5 => self.rational_span_jet::<$d, $h, 6>(u, order, side, values, errors, limit),
                    _ => {
                        self.rational_span_jet::<$d, $h, 16>(u, order, side, values, errors, limit)
                    }
                }
            };
        }
        match dim {
            1 => by_degree!(1, 2),
            2 => by_degree!(2, 3),
            _ => by_degree!(3, 4),
        }
    }

    /// [`rational_spans_jet_into`](Self::rational_spans_jet_into) in
    /// dimension `D`, `H = D + 1` homogeneous coordinates, the degree below
    /// `CAP` (the rows of the span and of its homogeneous jet).
    ///
    /// With the degree sized exactly (`CAP <= 6`, `p = CAP - 1`), the
    /// order equal to the degree (connect's usual case `k >= deg`) takes a
    /// copy of [`Self::rational_span_jet_body`] whose degree and order are
    /// constants: every loop of the triangle's bounds, the scaling to `u`
    /// and the quotient rule then has constant bounds and is unrolled. The
    /// same operations in the same order, so the same bits (issue 20,
    /// session 49: 1,510 -> 1,193 instructions per jet of the demo's
    /// rational cubic and quartic).
    #[allow(clippy::too_many_arguments)]
    fn rational_span_jet<const D: usize, const H: usize, const CAP: usize>(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
        limit: f64,
    ) -> bool {
        if CAP <= 6 && order == CAP - 1 {
            debug_assert_eq!(self.degree, CAP - 1);
            self.rational_span_jet_body::<D, H, CAP>(
                CAP - 1,
                u,
                CAP - 1,
                side,
                values,
                errors,
                limit,
            )
        } else {
            self.rational_span_jet_body::<D, H, CAP>(
                self.degree,
                u,
                order,
                side,
                values,
                errors,
                limit,
            )
        }
    }

    /// [`Self::rational_span_jet`] for the degree `p` (the curve's).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn rational_span_jet_body<const D: usize, const H: usize, const CAP: usize>(
        &self,
        p: usize,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
        limit: f64,
    ) -> bool {
        debug_assert!(p < CAP && p == self.degree);
        let spans = self.span_poles();
        let i = spans.span_at(u, side);
        let (a, b) = spans.domain(i);
        // Homogeneous rows 0..=top in t, one more than asked for the
        // parameter's rounding term (none above the degree).
        let top = (order + 1).min(p);
        let mut jet = [[0.0f64; H]; CAP];
        let width = b - a;
        let t = (u - a) / width;
        crate::connect::de_casteljau_values_into(
            spans.rows(i),
            H,
            p,
            t,
            top,
            jet.as_flattened_mut(),
        );
        let unit = f64::EPSILON / 2.0;
        let one_norm = super::spans::abs_sum;
        // The bounds in t of the homogeneous rows 0..=top: row k within
        // p!/(p-k)! 2^k (2 u (3 (p - k) + k + 1) A + E) of the exact jet of
        // the exact rows, A and E the span's largest row 1-norm and row
        // error (the triangle on the rows' sizes and on their errors, every
        // size at its largest: `S_k(x) = sum_j C(k, j) x_j <= 2^k max x`).
        let [size, row_error] = spans.span_sizes[i];
        let mut in_t = [0.0f64; CAP];
        triangle_bounds(p, (size, row_error), &mut in_t[..=top]);
        let rows = order.min(p);
        // (b - a)^-k out of the normal range (span widths far from 1 at high
        // orders): its rounding is no longer relative, the basis route takes
        // the jet. The powers are monotone and the normal range holds 1, so
        // the highest one decides.
        let inverse = 1.0 / width;
        let highest = (0..rows).fold(1.0f64, |scale, _| scale * inverse);
        let checked = limit.is_finite();
        if checked && !highest.is_normal() {
            return false;
        }
        // The homogeneous rows in u and their bounds E_k.
        let mut homogeneous = [[0.0f64; H]; CAP];
        let mut homogeneous_errors = [0.0f64; CAP];
        let in_t = RowsInT {
            jet: jet.as_flattened(),
            bounds: &in_t[..=top],
            t,
            width,
        };
        scale_rows_to_u(
            &in_t,
            (H, p),
            rows,
            0.0,
            one_norm,
            &mut homogeneous.as_flattened_mut()[..(rows + 1) * H],
            &mut homogeneous_errors[..=rows],
        );
        let jet = homogeneous;
        // The quotient rule (rows above the degree are zero in `jet`), the
        // 1-norms of the rows of C kept.
        let mut curve = [[0.0f64; D]; RATIONAL_SPAN_MAX_ORDER + 1];
        let mut sizes = [0.0f64; RATIONAL_SPAN_MAX_ORDER + 1];
        let (w0, e0) = (jet[0][D], homogeneous_errors[0]);
        // The bounds' sums are taken in the order that keeps the previous
        // row's bound (`i = 1`) to the end and multiply by the rounded
        // `1 / |w|` instead of dividing: each row's bound then waits for
        // the previous one by two products and two sums, not a division
        // and the whole sum (the chain that held the jet's time; issue 20,
        // session 49). Sums of nonnegative terms in any order and one more
        // rounded factor: within the factor 2 of `gamma_k` that covers the
        // bound's own rounding.
        let inverse_weight = 1.0 / w0.abs();
        for k in 0..=order {
            // Rows above the degree (k > rows) are zero.
            let mut row = [0.0f64; D];
            let mut moved = 0.0;
            if k <= rows {
                row.copy_from_slice(&jet[k][..D]);
                moved = homogeneous_errors[k];
            }
            let mut terms = one_norm(&row);
            // w^(i) vanishes above the degree: those terms are skipped.
            for i in 1..=k.min(rows) {
                let choose = BINOMIALS[k * (k + 1) / 2 + i];
                let wi = jet[i][D];
                let coef = choose * wi;
                let prev = &curve[k - i];
                for c in 0..D {
                    row[c] -= coef * prev[c];
                }
                terms += coef.abs() * sizes[k - i];
                if i > 1 {
                    moved +=
                        choose * (homogeneous_errors[i] * sizes[k - i] + wi.abs() * errors[k - i]);
                }
            }
            // The term `i = 1` (`C(k, 1) = k`), the previous row's bound in it.
            let latest = if k >= 1 && rows >= 1 {
                k as f64 * (homogeneous_errors[1] * sizes[k - 1] + jet[1][D].abs() * errors[k - 1])
            } else {
                0.0
            };
            for x in row.iter_mut() {
                *x /= w0;
            }
            sizes[k] = one_norm(&row);
            curve[k] = row;
            let gamma = 2.0 * (k + 3) as f64 * unit;
            let sum = moved + (e0 * sizes[k] + gamma * terms) + latest;
            // (A subnormal `w` has no finite reciprocal: divided then.)
            errors[k] = if inverse_weight.is_finite() {
                sum * inverse_weight
            } else {
                sum / w0.abs()
            };
            // A bound or size that is NaN or infinite, and a size below the
            // normal range or zero (where rounding is not relative: a row
            // that underflowed comes back 0 with bound 0), decline too (the
            // basis route then).
            let accepted = !checked || (sizes[k].is_normal() && errors[k] <= limit * sizes[k]);
            if !accepted {
                return false;
            }
        }
        values.copy_from_slice(curve[..=order].as_flattened());
        true
    }

    /// Whether the curve is one clamped span: its poles are the Bezier
    /// control points of the domain.
    #[inline(always)]
    pub(crate) fn is_bezier_span(&self) -> bool {
        let p = self.degree;
        let k = &self.knots;
        k.len() == 2 * p + 2 && k[0] == k[p] && k[p + 1] == k[2 * p + 1]
    }

    /// The span table, built on first use.
    fn span_table(&self) -> &SpanTable {
        self.span_cache.0.get_or_init(|| self.build_span_table())
    }

    /// The rows of [`SpanTable`]: derivative control points (A3.3) on the
    /// curve's own knots, then each span's Bezier poles ([`span_bezier`]).
    fn build_span_table(&self) -> SpanTable {
        let p = self.degree;
        let top = p.min(TABLE_MAX_ORDER);
        // On the curve's own knots (not the clamped curve's: clamping free
        // end knots shortens the windows of A3.3 there, and their
        // differences would lose digits).
        let (inner, _) = self.interior_knots();
        let (h, mut poles) = if self.weights.is_some() {
            (self.dim + 1, self.homogeneous_points())
        } else {
            (self.dim, self.points.clone())
        };
        let mut knots = self.knots.clone();
        let (first, last) = self.domain();
        let mut breaks = Vec::with_capacity(inner.len() + 2);
        breaks.push(first);
        breaks.extend_from_slice(&inner);
        breaks.push(last);
        let spans = breaks.len() - 1;
        let block: usize = (0..=top).map(|k| (p - k + 1) * h).sum();
        let mut rows = vec![0.0; spans * block];
        let mut offset = 0;
        for k in 0..=top {
            let q = p - k;
            if k > 0 {
                // A3.3 on the curve of degree q + 1; a window of length 0
                // belongs to a basis function that vanishes (its pole is 0).
                let n = poles.len() / h;
                let mut derived = Vec::with_capacity((n - 1) * h);
                for i in 0..n - 1 {
                    let window = knots[i + q + 2] - knots[i + 1];
                    let f = if window > 0.0 {
                        (q + 1) as f64 / window
                    } else {
                        0.0
                    };
                    for c in 0..h {
                        derived.push(f * (poles[(i + 1) * h + c] - poles[i * h + c]));
                    }
                }
                poles = derived;
                knots = knots[1..knots.len() - 1].to_vec();
            }
            for s in 0..spans {
                let (a, b) = (breaks[s], breaks[s + 1]);
                let j = find_span(&knots, q, a, KnotSide::Right);
                let window = &poles[(j - q) * h..(j + 1) * h];
                let local = &knots[j + 1 - q..j + 1 + q];
                let target = &mut rows[s * block + offset..][..(q + 1) * h];
                match h {
                    2 => span_bezier::<2>(window, local, a, b, q, target),
                    3 => span_bezier::<3>(window, local, a, b, q, target),
                    _ => span_bezier::<4>(window, local, a, b, q, target),
                }
            }
            offset += (q + 1) * h;
        }
        SpanTable {
            breaks,
            rows,
            block,
        }
    }

    /// The point at `u` of a curve of dimension `D`: the value and the
    /// errors of [`NurbsCurve::eval_derivatives_checked_into`] at order 0,
    /// bit for bit, returned as an array. A polynomial one-span curve (a
    /// Bezier curve as a NURBS handle) takes the Bezier kernel here with its
    /// domain test and no scratch, so that such a handle costs little more
    /// than the Bezier handle (issue 20); every other curve, a parameter
    /// outside the domain and a value that is not finite go through
    /// `eval_derivatives_checked_into`.
    ///
    /// Inlined into its caller: returned through memory instead, the point
    /// cost the C ABI's NURBS value 40 of its 300 instructions and a fifth
    /// of its time (issue 20).
    ///
    /// # Panics
    /// If the curve's dimension is not `D`.
    #[inline(always)]
    pub fn point_checked<const D: usize>(
        &self,
        name: impl Fn() -> String,
        u: f64,
    ) -> crate::error::Result<[f64; D]> {
        assert_eq!(self.dim, D);
        let mut out = [0.0f64; D];
        let (p, knots) = (self.degree, &self.knots[..]);
        if self.weights.is_none() && p <= SPAN_FAST_MAX_DEGREE && knots.len() == 2 * p + 2 {
            let (a, b) = (knots[p], knots[p + 1]);
            if knots[0] == a && knots[2 * p + 1] == b && a <= u && u <= b {
                bezier_jet::<D>(&self.points, p, u, a, b, 0, &mut out);
                if out.iter().all(|x| x.is_finite()) {
                    return Ok(out);
                }
            }
        }
        self.eval_derivatives_checked_into(name, u, 0, &mut out)?;
        Ok(out)
    }

    /// Value and derivatives `0..=max_order` at `u` in the domain (from the
    /// right at an interior knot, the last span at the end) into `out`
    /// (`(max_order + 1) * dim` values) for dimensions 2 and 3 up to degree
    /// [`SPAN_FAST_MAX_DEGREE`] and `min(max_order, degree) <=`
    /// [`TABLE_MAX_ORDER`], returning `false` (nothing written) otherwise.
    /// The caller checks that the values are finite and takes the basis
    /// route when they are not. The route: a polynomial one-span curve by
    /// the Bezier kernel on its poles, the value of any other curve by A2.2
    /// (`value_fast_into`, the bits of the basis route), the derivatives of
    /// any other curve from its span table.
    #[inline(always)]
    pub(super) fn eval_fast_into(&self, u: f64, max_order: usize, out: &mut [f64]) -> bool {
        if self.degree > SPAN_FAST_MAX_DEGREE {
            return false;
        }
        match self.dim {
            3 => self.eval_fast_dim::<3>(u, max_order, out),
            2 => self.eval_fast_dim::<2>(u, max_order, out),
            _ => false,
        }
    }

    #[inline(always)]
    fn eval_fast_dim<const D: usize>(&self, u: f64, max_order: usize, out: &mut [f64]) -> bool {
        let p = self.degree;
        let polynomial = self.weights.is_none();
        if polynomial && self.is_bezier_span() {
            let (a, b) = (self.knots[p], self.knots[p + 1]);
            bezier_jet::<D>(&self.points, p, u, a, b, max_order, out);
            return true;
        }
        if max_order == 0 {
            return self.value_fast_into(u, out);
        }
        let top = max_order.min(p);
        if top > TABLE_MAX_ORDER {
            return false;
        }
        let table = self.span_table();
        let breaks = &table.breaks;
        let spans = breaks.len() - 1;
        // Span s: breaks[s] <= u < breaks[s + 1] (the last span at the end).
        let s = breaks[1..spans].partition_point(|&x| x <= u);
        let (a, b) = (breaks[s], breaks[s + 1]);
        let t = (u - a) / (b - a);
        let block = &table.rows[s * table.block..(s + 1) * table.block];
        if polynomial {
            let jet = table_jet::<D>(block, p, top, t);
            for (row, j) in out.chunks_exact_mut(D).zip(&jet[..=top]) {
                row.copy_from_slice(j);
            }
            out[(top + 1) * D..].fill(0.0);
        } else if D == 3 {
            let jet = table_jet::<4>(block, p, top, t);
            quotient_rule::<3, 4>(&jet, top, out);
        } else {
            let jet = table_jet::<3>(block, p, top, t);
            quotient_rule::<2, 3>(&jet, top, out);
        }
        true
    }
}

/// The Bezier poles of the span `[a, b]` of a degree-`q` curve, times
/// their binomials `C(q, i)`, into `target`, from the span's `q + 1` poles
/// `window` and its `2 q` knots `local` (`local[q - 1] = a`,
/// `local[q] = b`): knot insertion (A5.1) confined to the window, `a`
/// until the `q` knots on the left are `a`, then `b` until the `q` on the
/// right are `b`, keeping after each insertion the `q + 1` poles of
/// `[a, b]`. Each step is a convex combination (every window of `q + 1`
/// knots contains `[a, b]`).
fn span_bezier<const H: usize>(
    window: &[f64],
    local: &[f64],
    a: f64,
    b: f64,
    q: usize,
    target: &mut [f64],
) {
    let mut d = [[0.0f64; H]; SPAN_FAST_MAX_DEGREE + 1];
    for (row, pole) in d.iter_mut().zip(window.chunks_exact(H)) {
        row.copy_from_slice(pole);
    }
    let mut knots = [0.0f64; 2 * SPAN_FAST_MAX_DEGREE];
    knots[..2 * q].copy_from_slice(local);
    if q > 0 {
        // Insert a: new poles d'_1..d'_q, d_q; knots lose their first.
        while knots[0] != a {
            for i in 1..=q {
                let lo = knots[i - 1];
                let alpha = (a - lo) / (knots[i - 1 + q] - lo);
                let (left, right) = d.split_at_mut(i);
                for (x, y) in left[i - 1].iter_mut().zip(&right[0]) {
                    *x = (1.0 - alpha) * *x + alpha * y;
                }
            }
            knots.copy_within(1..q, 0);
            knots[q - 1] = a;
        }
        // Insert b: new poles d_0, d'_1..d'_q; knots lose their last.
        while knots[2 * q - 1] != b {
            for i in (1..=q).rev() {
                let lo = knots[i - 1];
                let alpha = (b - lo) / (knots[i - 1 + q] - lo);
                let (left, right) = d.split_at_mut(i);
                for (y, x) in right[0].iter_mut().zip(&left[i - 1]) {
                    *y = (1.0 - alpha) * x + alpha * *y;
                }
            }
            knots.copy_within(q..2 * q - 1, q + 1);
            knots[q] = b;
        }
    }
    for (i, (to, from)) in target.chunks_exact_mut(H).zip(&d).enumerate() {
        let coef = BINOMIALS[q * (q + 1) / 2 + i];
        for (t, f) in to.iter_mut().zip(from) {
            *t = coef * f;
        }
    }
}

/// The jet of the polynomial Bezier span `points` (`p + 1` rows of `D`) on
/// `[a, b]` at `u`, by the Bezier curve's kernel: the operations of
/// `BezierCurve::eval_into` (order 0) and `BezierCurve::eval_derivatives_into`
/// in their order, the falling factorial divided by `b - a` once per order
/// (exact when `b - a = 1`).
#[inline(always)]
fn bezier_jet<const D: usize>(
    points: &[f64],
    p: usize,
    u: f64,
    a: f64,
    b: f64,
    max_order: usize,
    out: &mut [f64],
) {
    let len = b - a;
    // On [0, 1] (a Bezier curve as a NURBS handle) t is u itself: the same
    // value as the division, without its latency. The division is out of
    // line so that the compiler branches: as a select of both values, it
    // kept the division's latency on every call (issue 20).
    let t = if a == 0.0 && len == 1.0 {
        u
    } else {
        span_parameter(u, a, len)
    };
    if max_order == 0 {
        bernstein_horner_any(points, p, D, t, 1.0, out);
    } else {
        let mut diff = [0.0f64; (SPAN_FAST_MAX_DEGREE + 1) * 3];
        let diff = &mut diff[..(p + 1) * D];
        diff.copy_from_slice(&points[..(p + 1) * D]);
        let top = max_order.min(p);
        let mut factor = 1.0;
        for k in 0..=top {
            let m = p - k;
            bernstein_horner_any(
                &diff[..(m + 1) * D],
                m,
                D,
                t,
                factor,
                &mut out[k * D..(k + 1) * D],
            );
            if k < top {
                for i in 0..m * D {
                    diff[i] = diff[i + D] - diff[i];
                }
                factor = factor * m as f64 / len;
            }
        }
        out[(top + 1) * D..].fill(0.0);
    }
}

/// `(u - a) / len`, the parameter in a span of length `len` from `a`
/// ([`bezier_jet`]; out of line on purpose).
#[inline(never)]
fn span_parameter(u: f64, a: f64, len: f64) -> f64 {
    (u - a) / len
}

/// Rows `0..=top` (`top <= TABLE_MAX_ORDER`) of the jet from one span's
/// block of the table at `t`: for each order one Horner sum over its
/// binomial-weighted rows, forwards from row 0 in `(1 - t) / t` times `t^m`
/// for `t > 1/2`, backwards from row `m` in `t / (1 - t)` times
/// `(1 - t)^m` otherwise (the scheme of `bernstein_horner`). The degree is
/// a constant up to 7 (the loops unrolled), a variable above.
#[inline(always)]
fn table_jet<const H: usize>(block: &[f64], p: usize, top: usize, t: f64) -> [[f64; H]; 4] {
    match p {
        1 => table_jet_degree::<H, 1>(block, top, t),
        2 => table_jet_degree::<H, 2>(block, top, t),
        3 => table_jet_degree::<H, 3>(block, top, t),
        4 => table_jet_degree::<H, 4>(block, top, t),
        5 => table_jet_degree::<H, 5>(block, top, t),
        6 => table_jet_degree::<H, 6>(block, top, t),
        7 => table_jet_degree::<H, 7>(block, top, t),
        _ => table_jet_any::<H>(block, p, top, t),
    }
}

/// [`table_jet_rows`] at the constant degree `P`.
#[inline(never)]
fn table_jet_degree<const H: usize, const P: usize>(
    block: &[f64],
    top: usize,
    t: f64,
) -> [[f64; H]; 4] {
    table_jet_sides::<H>(block, P, top, t)
}

/// [`table_jet_rows`] at a degree `8..=SPAN_FAST_MAX_DEGREE`.
#[inline(never)]
fn table_jet_any<const H: usize>(block: &[f64], p: usize, top: usize, t: f64) -> [[f64; H]; 4] {
    table_jet_sides::<H>(block, p, top, t)
}

/// The direction of the Horner sums chosen once per call (one branch on
/// `t`, which a caller sweeping parameters makes unpredictable, instead of
/// one per order).
#[inline(always)]
fn table_jet_sides<const H: usize>(block: &[f64], p: usize, top: usize, t: f64) -> [[f64; H]; 4] {
    if t > 0.5 {
        table_jet_rows::<H, true>(block, p, top, t)
    } else {
        table_jet_rows::<H, false>(block, p, top, 1.0 - t)
    }
}

/// The rows at `x = t` (`FORWARD`, `t > 1/2`) or `x = 1 - t`.
#[inline(always)]
fn table_jet_rows<const H: usize, const FORWARD: bool>(
    block: &[f64],
    p: usize,
    top: usize,
    x: f64,
) -> [[f64; H]; 4] {
    debug_assert!(top <= TABLE_MAX_ORDER && top <= p);
    let ratio = (1.0 - x) / x;
    // x^(p - top), then times x per order downwards.
    let mut power = 1.0;
    for _ in 0..p - top {
        power *= x;
    }
    let mut powers = [0.0f64; 4];
    for m in (0..=top).rev() {
        powers[m] = power;
        power *= x;
    }
    // powers[k] = x^(p - k).
    let mut jet = [[0.0f64; H]; 4];
    let mut offset = 0;
    for k in 0..=TABLE_MAX_ORDER {
        if k > top {
            break;
        }
        let m = p - k;
        let rows = &block[offset..offset + (m + 1) * H];
        offset += (m + 1) * H;
        let mut sum = [0.0f64; H];
        if FORWARD {
            sum.copy_from_slice(&rows[..H]);
            for q in rows[H..].chunks_exact(H) {
                for c in 0..H {
                    sum[c] = sum[c] * ratio + q[c];
                }
            }
        } else {
            sum.copy_from_slice(&rows[m * H..]);
            for q in rows[..m * H].chunks_exact(H).rev() {
                for c in 0..H {
                    sum[c] = sum[c] * ratio + q[c];
                }
            }
        }
        for c in 0..H {
            jet[k][c] = sum[c] * powers[k];
        }
    }
    jet
}

/// A4.2 on homogeneous rows `0..=top` (`H = D + 1` values, the weight
/// last) into the Cartesian rows of `out`; orders above `top` (above the
/// degree) have `A^(k) = w^(k) = 0`. The binomials from the table, above
/// it by their exact recurrence; one division by `w`.
#[inline(always)]
fn quotient_rule<const D: usize, const H: usize>(jet: &[[f64; H]; 4], top: usize, out: &mut [f64]) {
    debug_assert!(H == D + 1);
    let inverse = 1.0 / jet[0][D];
    let rows = out.len() / D;
    for k in 0..rows {
        let mut value = [0.0f64; D];
        if k <= top {
            value.copy_from_slice(&jet[k][..D]);
        }
        let (done, rest) = out.split_at_mut(k * D);
        // Rows C^(k-1), C^(k-2), ... with i = 1, 2, ..., min(k, top).
        for (i, previous) in (1..=k.min(top)).zip(done.chunks_exact(D).rev()) {
            let choose = if k <= SPAN_FAST_MAX_DEGREE {
                BINOMIALS[k * (k + 1) / 2 + i]
            } else {
                binomial(k, i)
            };
            let coef = choose * jet[i][D];
            for c in 0..D {
                value[c] -= coef * previous[c];
            }
        }
        for (o, v) in rest[..D].iter_mut().zip(value) {
            *o = v * inverse;
        }
    }
}

/// The bound of row `k` in `u = a + (b - a) t` from its bound in `t`
/// (`scaled_span_jet_into`'s analysis): `scale = fl((b - a)^-1)^k`,
/// `in_t` the row's bound in `t`, `next` the size of row `k + 1` in `t`
/// plus its bound (0 above the degree), `dt = 3 u |t|` the parameter's
/// rounding, `size` the scaled row's norm; the last term is twice the
/// scaling's rounding and covers the bound's own sums.
#[inline(always)]
fn bound_in_u(scale: f64, in_t: f64, next: f64, dt: f64, k: usize, size: f64) -> f64 {
    let unit = f64::EPSILON / 2.0;
    scale * (in_t + next * dt) + 2.0 * (3 * k + 2) as f64 * unit * size
}

/// The jet of the degree-`p` Bezier span `poles` of the domain `(a, b)`
/// at `u` to `order`, with the bounds of
/// [`NurbsCurve::bezier_span_jet_into`]'s analysis, plus
/// `h^-k p!/(p-k)! 2^k delta` on row `k` for poles within `delta`
/// (Euclidean) of the exact ones (0: the curve's own poles).
///
/// With `screen = Some(size)` (`size` at least every pole's Euclidean
/// size; [`NurbsCurve::span_jet_screen_into`]) the same values bit for bit
/// (the de Casteljau values of the same poles, scaled by the same
/// products), with the triangle's bound replaced by [`triangle_bounds`]
/// of `size` and the Euclidean norms by 1-norms: never below the bounds
/// without it (to first order), and no square root.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn scaled_span_jet_into(
    poles: &[f64],
    dim: usize,
    p: usize,
    ((a, b), delta): ((f64, f64), f64),
    u: f64,
    order: usize,
    screen: Option<f64>,
    values: &mut [f64],
    errors: &mut [f64],
) {
    /// Rows times coordinates of the stack jet (orders `0..=16` in 4D).
    const STACK: usize = 17 * 4;
    // Orders 0..=top with top = min(order + 1, p): one more than asked
    // for the parameter's rounding term (zero above the degree).
    let top = (order + 1).min(p);
    let mut jet = [0.0f64; STACK];
    let mut jet_errors = [0.0f64; 17];
    let jet = &mut jet[..(top + 1) * dim];
    let jet_errors = &mut jet_errors[..=top];
    let h = b - a;
    let t = (u - a) / h;
    if let Some(size) = screen {
        crate::connect::de_casteljau_values_into(poles, dim, p, t, top, jet);
        triangle_bounds(p, (size, 0.0), jet_errors);
        let in_t = RowsInT {
            jet,
            bounds: jet_errors,
            t,
            width: h,
        };
        scale_rows_to_u(
            &in_t,
            (dim, p),
            order,
            delta,
            super::spans::abs_sum,
            values,
            errors,
        );
        return;
    }
    crate::connect::de_casteljau_jet_into(poles, dim, p, t, top, jet, jet_errors);
    let norm = |row: &[f64]| row.iter().map(|v| v * v).sum::<f64>().sqrt();
    let in_t = RowsInT {
        jet,
        bounds: jet_errors,
        t,
        width: h,
    };
    scale_rows_to_u(&in_t, (dim, p), order, delta, norm, values, errors);
}

/// A span's jet in `t = (u - a) / (b - a)`: rows `0..=top` (`dim` values
/// each) and their bounds in `t`.
struct RowsInT<'a> {
    jet: &'a [f64],
    bounds: &'a [f64],
    t: f64,
    /// `b - a`.
    width: f64,
}

/// The rows of `in_t` in `u`, `0..=order` (zero above the degree `p`):
/// row `k` times `(b - a)^-k` (by repeated products of the rounded
/// reciprocal), its bound [`bound_in_u`] with `norm` for the rows' norms
/// and the next row's norm and bound for the parameter's rounding, plus
/// `(b - a)^-k p!/(p-k)! 2^k delta` when `delta > 0`. The last part of
/// [`scaled_span_jet_into`] (Euclidean norms, or 1-norms for the screen).
#[inline(always)]
fn scale_rows_to_u(
    in_t: &RowsInT<'_>,
    (dim, p): (usize, usize),
    order: usize,
    delta: f64,
    norm: impl Fn(&[f64]) -> f64,
    values: &mut [f64],
    errors: &mut [f64],
) {
    let (jet, bounds) = (in_t.jet, in_t.bounds);
    let unit = f64::EPSILON / 2.0;
    let dt = 3.0 * unit * in_t.t.abs();
    let inverse = 1.0 / in_t.width;
    let mut scale = 1.0;
    // p!/(p-k)! 2^k, exact in f64 for p <= 15.
    let mut moved = 1.0;
    for k in 0..=order {
        let out = &mut values[k * dim..(k + 1) * dim];
        if k > p {
            out.fill(0.0);
            errors[k] = 0.0;
            continue;
        }
        let row = &jet[k * dim..(k + 1) * dim];
        for (o, &v) in out.iter_mut().zip(row) {
            *o = scale * v;
        }
        let next = if k < p {
            norm(&jet[(k + 1) * dim..(k + 2) * dim]) + bounds[k + 1]
        } else {
            0.0
        };
        errors[k] = bound_in_u(scale, bounds[k], next, dt, k, norm(out));
        if delta > 0.0 {
            errors[k] += scale * moved * delta;
            moved *= 2.0 * (p - k) as f64;
        }
        scale *= inverse;
    }
}

/// `bounds[k] = p!/(p-k)! 2^k (2 u (3 (p - k) + k + 1) size + error)` for
/// the rows `k = 0..bounds.len()` (at most `p + 1`): the de Casteljau
/// triangle's bounds of the rows in `t` with every size at `size` and
/// every input row's own error at `error` (0 for a curve's poles;
/// [`NurbsCurve::span_jet_screen_into`], `rational_span_jet`);
/// `p!/(p-k)! 2^k` by running products, exact in f64 for `p <= 15`.
fn triangle_bounds(p: usize, (size, error): (f64, f64), bounds: &mut [f64]) {
    // `3 (p - k) + k + 1` and `p - k` as doubles stepped down (exact).
    let mut count = (3 * p + 1) as f64;
    let mut remaining = p as f64;
    let mut moved = 1.0f64;
    for bound in bounds.iter_mut() {
        *bound = moved * (f64::EPSILON * count * size + error);
        moved *= 2.0 * remaining;
        count -= 2.0;
        remaining -= 1.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::basis::{KnotSide, basis_scratch_len};
    use crate::bezier::BezierCurve;
    use crate::test_values::{Values, exact_bezier_jet};

    /// Agreement of the span route with the basis route: each row `k`
    /// within `AGREEMENT_FACTOR` times the basis route's own first-order
    /// rounding bound of that row (`eval_derivatives_with_bound`,
    /// `2 (p + k + 2) eps` times the sums of absolute terms), i.e. the two
    /// routes' errors together at most twice that bound each. Over the
    /// cases of `span_route_agrees_with_the_basis_route` the largest ratio
    /// is 1.5 (printed by the test). A table of differences of the spans'
    /// Bezier poles (or of the clamped curve's derivative control points)
    /// exceeds it by orders of magnitude on the short spans there.
    const AGREEMENT_FACTOR: f64 = 4.0;

    #[test]
    fn binomial_table_is_pascals_triangle() {
        for n in 0..=SPAN_FAST_MAX_DEGREE {
            let mut c = 1u64;
            for i in 0..=n {
                assert_eq!(BINOMIALS[n * (n + 1) / 2 + i], c as f64, "C({n}, {i})");
                assert_eq!(binomial(n, i), c as f64, "C({n}, {i})");
                c = c * (n - i) as u64 / (i + 1) as u64;
            }
        }
    }

    /// A curve of `spans` spans on an uneven knot vector starting at
    /// `start`: one interior knot doubled (a C^(p-2) join), clamped or
    /// (`clamped == false`, several spans) with free end knots; poles in
    /// `[-2, 2)`, weights (when `rational`) in `[0.3, 3.3)`.
    fn curve(
        values: &mut Values,
        dim: usize,
        p: usize,
        spans: usize,
        rational: bool,
        clamped: bool,
    ) -> NurbsCurve {
        let start = 4.0 * values.unit() - 2.0;
        let mut knots = Vec::new();
        let mut u = start;
        if clamped {
            knots.extend(std::iter::repeat_n(u, p + 1));
        } else {
            for _ in 0..=p {
                knots.push(u);
                u += 0.1 + values.unit();
            }
            u = *knots.last().unwrap();
        }
        for s in 1..spans {
            u += 0.05 + values.unit();
            knots.push(u);
            if s == 1 && p > 1 {
                knots.push(u);
            }
        }
        u += 0.05 + values.unit();
        if clamped {
            knots.extend(std::iter::repeat_n(u, p + 1));
        } else {
            for _ in 0..=p {
                knots.push(u);
                u += 0.1 + values.unit();
            }
        }
        let count = knots.len() - p - 1;
        let poles = (0..count * dim)
            .map(|_| 4.0 * values.unit() - 2.0)
            .collect();
        let weights = rational.then(|| (0..count).map(|_| 0.3 + 3.0 * values.unit()).collect());
        NurbsCurve::new(dim, p, poles, weights, knots).unwrap()
    }

    /// Asserts every row `k` of `jet` (`dim` values each) within `bound[k]`
    /// (Euclidean) of the exact row `exact[k]`; the largest miss / bound
    /// over the rows with a positive bound. `at` names the case.
    fn worst_miss_over_bound(
        jet: &[f64],
        bound: &[f64],
        exact: &[Vec<num_rational::BigRational>],
        dim: usize,
        at: &str,
    ) -> f64 {
        use num_rational::BigRational;
        use num_traits::ToPrimitive;
        let mut worst: f64 = 0.0;
        for (k, &limit) in bound.iter().enumerate() {
            let miss = (0..dim)
                .map(|c| {
                    let x = BigRational::from_float(jet[k * dim + c]).unwrap();
                    (x - &exact[k][c]).to_f64().unwrap().powi(2)
                })
                .sum::<f64>()
                .sqrt();
            assert!(miss <= limit, "{at} k {k}: miss {miss:e} above {limit:e}");
            if limit > 0.0 {
                worst = worst.max(miss / limit);
            }
        }
        worst
    }

    /// The exact Bezier rows of every span of a curve from its f64 data
    /// (homogeneous `(w x, w)` with the products exact for a curve with
    /// weights): every distinct knot of the domain, its ends included,
    /// inserted up to multiplicity `p` by Boehm's insertion in rationals;
    /// span `i` has rows `i p ..= i p + p`. With the span breaks (domain
    /// ends and distinct interior knots).
    fn exact_span_rows(c: &NurbsCurve) -> (Vec<Vec<num_rational::BigRational>>, Vec<f64>) {
        use num_rational::BigRational;
        use num_traits::One;
        let p = c.degree();
        let exact = |x: f64| BigRational::from_float(x).expect("finite");
        let mut knots: Vec<BigRational> = c.knots().iter().map(|&k| exact(k)).collect();
        let mut poles: Vec<Vec<BigRational>> = (0..c.point_count())
            .map(|i| {
                let row = c.point(i).iter().map(|&x| exact(x));
                match c.weights() {
                    None => row.collect(),
                    Some(w) => {
                        let w = exact(w[i]);
                        let mut row: Vec<BigRational> = row.map(|x| x * &w).collect();
                        row.push(w);
                        row
                    }
                }
            })
            .collect();
        let h = poles[0].len();
        let (interior, _) = c.interior_knots();
        let (first, last) = c.domain();
        // Every distinct knot of the domain to multiplicity p (the ends at
        // least p: free end knots are clamped by the same insertions).
        let mut targets = vec![first];
        targets.extend(&interior);
        targets.push(last);
        for &k in &targets {
            let ku = exact(k);
            while knots.iter().filter(|x| **x == ku).count() < p {
                // Boehm: span `s` with knots[s] <= k < knots[s + 1]; at the
                // domain's last knot the last span of the domain,
                // knots[s] < k <= knots[s + 1] (the span from the right
                // would be past the last pole).
                let s = if k == last {
                    knots.iter().rposition(|x| *x < ku).unwrap()
                } else {
                    knots.iter().rposition(|x| *x <= ku).unwrap()
                };
                let mut next = Vec::with_capacity(poles.len() + 1);
                for i in 0..=poles.len() {
                    if i + p <= s {
                        next.push(poles[i].clone());
                    } else if i > s {
                        next.push(poles[i - 1].clone());
                    } else {
                        let alpha = (&ku - &knots[i]) / (&knots[i + p] - &knots[i]);
                        let beta = BigRational::one() - &alpha;
                        next.push(
                            (0..h)
                                .map(|j| &alpha * &poles[i][j] + &beta * &poles[i - 1][j])
                                .collect(),
                        );
                    }
                }
                poles = next;
                knots.insert(s + 1, ku.clone());
            }
        }
        // The first span's rows start where the multiplicity of `first`
        // (at least p, first met at index j) ends p + 1 knots before the
        // span: row j + m - p - 1.
        let ku = exact(first);
        let j = knots.iter().position(|x| *x == ku).unwrap();
        let m = knots.iter().filter(|x| **x == ku).count();
        let start = j + m - p - 1;
        let poles = poles[start..start + p * (interior.len() + 1) + 1].to_vec();
        (poles, targets)
    }

    /// For every span `[b_i, b_(i+1)]` of `breaks`: its start from the
    /// right, its end from the left, and a random parameter inside, each
    /// with the span's index.
    fn span_parameters(breaks: &[f64], values: &mut Values) -> Vec<(f64, KnotSide, usize)> {
        let mut us = Vec::new();
        for (i, w) in breaks.windows(2).enumerate() {
            us.push((w[0], KnotSide::Right, i));
            us.push((w[1], KnotSide::Left, i));
            us.push((w[0] + (w[1] - w[0]) * values.unit(), KnotSide::Right, i));
        }
        us
    }

    /// The screen's jet of a polynomial curve (`span_jet_screen_into`):
    /// `jet_into`'s values bit for bit and bounds never below its bounds,
    /// for one clamped span on `[0, 1]` and on another domain, and for
    /// curves of several spans, clamped and not; dimensions 2-4, degrees
    /// 1-15, orders 0 to two above the degree, at the knots from both
    /// sides, at the ends and inside spans. Rational curves, dimension 1
    /// and degree 16 are declined.
    #[test]
    fn span_screen_jets_are_the_jets_with_larger_bounds() {
        let mut values = Values(4702);
        let (mut compared, mut larger) = (0, 0);
        for case in 0..60 {
            let dim = 2 + case % 3;
            let p = 1 + (case * 7) % 15;
            let spans = 1 + case % 3;
            let clamped = spans == 1 || case % 2 == 0;
            let mut c = curve(&mut values, dim, p, spans, false, clamped);
            if case % 5 == 0 && spans == 1 {
                // The same poles on [0, 1]: the direct route.
                let poles = c.points().to_vec();
                let mut knots = vec![0.0; p + 1];
                knots.extend(std::iter::repeat_n(1.0, p + 1));
                c = NurbsCurve::new(dim, p, poles, None, knots).unwrap();
            }
            let mut breaks = vec![c.domain().0];
            breaks.extend(c.interior_knots().0);
            breaks.push(c.domain().1);
            for (u, side, _) in span_parameters(&breaks, &mut values) {
                for order in [0, 1, p / 2, p, p + 2] {
                    let mut full = (vec![7.0; (order + 1) * dim], vec![7.0; order + 1]);
                    let mut screen = full.clone();
                    crate::curve::CurveJet::jet_into(&c, u, order, side, &mut full.0, &mut full.1);
                    let scale = c.coordinate_scale();
                    assert!(c.span_jet_screen_into(
                        u,
                        order,
                        side,
                        scale,
                        &mut screen.0,
                        &mut screen.1
                    ));
                    let label =
                        format!("case {case}: dim {dim} p {p} spans {spans} u {u} order {order}");
                    assert_eq!(full.0, screen.0, "{label}");
                    for (k, (a, b)) in full.1.iter().zip(&screen.1).enumerate() {
                        assert!(*b >= *a * (1.0 - 1e-9), "{label} row {k}: {b:e} < {a:e}");
                        larger += usize::from(b > a);
                    }
                    compared += 1;
                }
            }
        }
        let mut declined = (vec![0.0; 6], vec![0.0; 3]);
        let rational = curve(&mut values, 2, 3, 2, true, true);
        assert!(!rational.span_jet_screen_into(
            0.0,
            2,
            KnotSide::Right,
            1.0,
            &mut declined.0,
            &mut declined.1
        ));
        let line = curve(&mut values, 1, 3, 2, false, true);
        let mut one = (vec![0.0; 3], vec![0.0; 3]);
        assert!(!line.span_jet_screen_into(0.0, 2, KnotSide::Right, 1.0, &mut one.0, &mut one.1));
        let high = curve(&mut values, 2, 16, 1, false, true);
        assert!(!high.span_jet_screen_into(
            0.0,
            2,
            KnotSide::Right,
            1.0,
            &mut declined.0,
            &mut declined.1
        ));
        assert!(
            compared > 1000 && larger > compared,
            "{compared} jets, {larger} larger bounds"
        );
    }

    /// `spans_jet_into` (the jet with bounds of a polynomial curve of
    /// several spans, from the kept decomposition): every row within its
    /// bound of the exact jet of the same f64 data (the span's exact poles
    /// by exact knot insertion), from both sides at every interior knot, at
    /// the ends and inside spans; dimensions 1-4, degrees 1-5 and 7, two to
    /// four spans, a double knot in some, domains near 0 and shifted by
    /// 1000. Rational and degree-16 curves are declined.
    #[test]
    fn spans_jet_is_within_its_bound_of_the_exact_jet() {
        use num_rational::BigRational;
        let exact = |x: f64| BigRational::from_float(x).expect("finite");
        let mut values = Values(37);
        let mut worst: f64 = 0.0;
        let mut checked = 0;
        for case in 0..48 {
            let dim = 1 + case % 4;
            let p = [1, 2, 3, 4, 5, 7][case % 6];
            let spans = 2 + case % 3;
            let c = curve(&mut values, dim, p, spans, false, true);
            let c = if case % 5 == 4 {
                // Shifted far from 0: the parameter's rounding matters.
                let knots: Vec<f64> = c.knots().iter().map(|k| k + 1000.0).collect();
                NurbsCurve::new(dim, p, c.points().to_vec(), None, knots).unwrap()
            } else {
                c
            };
            let (poles, breaks) = exact_span_rows(&c);
            for (u, side, span) in span_parameters(&breaks, &mut values) {
                let order = [1, p, p + 1][checked % 3];
                let mut jet = vec![f64::NAN; (order + 1) * dim];
                let mut bound = vec![f64::NAN; order + 1];
                assert!(c.spans_jet_into(u, order, side, &mut jet, &mut bound));
                let rows = poles[span * p..=span * p + p].to_vec();
                let domain = (exact(breaks[span]), exact(breaks[span + 1]), exact(u));
                let reference =
                    crate::test_values::exact_bezier_jet_of(rows, dim, p, domain, order);
                let at = format!("case {case} dim {dim} p {p} u {u} {side:?}");
                worst = worst.max(worst_miss_over_bound(&jet, &bound, &reference, dim, &at));
                checked += 1;
            }
        }
        println!("{checked} jets; largest miss / bound: {worst:.3}");
        assert!(checked > 300, "{checked} jets");
        let decline = |nurbs: NurbsCurve| {
            let (mut v, mut e) = (vec![0.0; 2 * nurbs.dim()], vec![0.0; 2]);
            assert!(!nurbs.spans_jet_into(0.5, 1, KnotSide::Right, &mut v, &mut e));
        };
        decline(curve(&mut values, 3, 3, 2, true, true));
        let high: Vec<f64> = (0..17 * 2).map(|_| values.unit()).collect();
        decline(NurbsCurve::from_bezier(
            &BezierCurve::new(2, 16, high).unwrap(),
        ));
    }

    /// `rational_spans_jet_into` (the jet with bounds of a curve with
    /// weights, from the kept homogeneous decomposition and the quotient
    /// rule): every row within its bound of the exact jet of the same f64
    /// data (exact homogeneous span rows, exact Bezier jet, exact quotient
    /// rule), from both sides at every interior knot, at the ends and inside
    /// spans; dimensions 1-3, degrees 1-5 (one to four spans) and 7 (one or,
    /// twice, two), a double knot in some, free end knots in some (clamped here by
    /// exact insertions, there by the route's f64 ones), weights 0.3-3.3, domains near 0
    /// and shifted by 1000, orders 1, the degree, and the degree plus 2 (rows
    /// above the degree do not vanish). Curves without weights, dimension 4
    /// and orders above 15 are declined.
    #[test]
    fn rational_spans_jet_is_within_its_bound_of_the_exact_jet() {
        use num_rational::BigRational;
        use num_traits::Zero;
        let exact = |x: f64| BigRational::from_float(x).expect("finite");
        let mut values = Values(41);
        let mut worst: f64 = 0.0;
        let (mut checked, mut declined) = (0, 0);
        for case in 0..54 {
            let dim = 1 + case % 3;
            let p = [1, 2, 3, 4, 5, 7][case % 6];
            // Degree 7 on one or two clamped spans only: beyond, the
            // rationals of the reference grow to thousands of digits.
            let spans = match p {
                7 => 1 + usize::from(case % 24 == 11),
                _ => 1 + case % 4,
            };
            let clamped = case % 7 != 3 || spans == 1 || p == 7;
            let c = curve(&mut values, dim, p, spans, true, clamped);
            let weights = c.weights().map(|w| w.to_vec());
            let c = match case % 5 {
                // Shifted far from 0: the parameter's rounding matters.
                4 => {
                    let knots: Vec<f64> = c.knots().iter().map(|k| k + 1000.0).collect();
                    NurbsCurve::new(dim, p, c.points().to_vec(), weights, knots).unwrap()
                }
                // Squeezed towards the first knot (`a + (k - a)^4 / 4`):
                // short spans beside long ones, where the differences of
                // the span rows amplify the decomposition's rounding.
                2 => {
                    let a = c.knots()[0];
                    let knots: Vec<f64> = c
                        .knots()
                        .iter()
                        .map(|k| a + (k - a).powi(4) / 4.0)
                        .collect();
                    NurbsCurve::new(dim, p, c.points().to_vec(), weights, knots).unwrap()
                }
                _ => c,
            };
            let (poles, breaks) = exact_span_rows(&c);
            for (u, side, span) in span_parameters(&breaks, &mut values) {
                let order = [1, p, p + 2][checked % 3];
                let mut jet = vec![f64::NAN; (order + 1) * dim];
                let mut bound = vec![f64::NAN; order + 1];
                // Every bound, however loose (the short spans are the
                // test of the decomposition's rounding), and whether the
                // screened route would take it.
                assert!(c.rational_spans_jet_within(
                    u,
                    order,
                    side,
                    &mut jet,
                    &mut bound,
                    f64::INFINITY
                ));
                let (mut v, mut e) = (jet.clone(), bound.clone());
                if !c.rational_spans_jet_into(u, order, side, &mut v, &mut e) {
                    declined += 1;
                }
                let rows = poles[span * p..=span * p + p].to_vec();
                let domain = (exact(breaks[span]), exact(breaks[span + 1]), exact(u));
                let homogeneous =
                    crate::test_values::exact_bezier_jet_of(rows, dim + 1, p, domain, order);
                // A4.2 in rationals.
                let mut reference: Vec<Vec<BigRational>> = Vec::new();
                for k in 0..=order {
                    let mut row: Vec<BigRational> = homogeneous[k][..dim].to_vec();
                    for i in 1..=k {
                        let choose = BigRational::from_integer((binomial(k, i) as i64).into());
                        let coef = choose * &homogeneous[i][dim];
                        for (o, x) in row.iter_mut().zip(&reference[k - i]) {
                            *o -= &coef * x;
                        }
                    }
                    let w = &homogeneous[0][dim];
                    assert!(!w.is_zero());
                    reference.push(row.into_iter().map(|x| x / w).collect());
                }
                let at = format!("case {case} dim {dim} p {p} u {u} {side:?} order {order}");
                worst = worst.max(worst_miss_over_bound(&jet, &bound, &reference, dim, &at));
                checked += 1;
            }
        }
        println!("{checked} jets ({declined} declined); largest miss / bound: {worst:.3}");
        assert!(
            checked > 250 && declined < checked / 4,
            "{checked} jets, {declined} declined"
        );
        let decline = |nurbs: NurbsCurve, order: usize| {
            let (mut v, mut e) = (vec![0.0; (order + 1) * nurbs.dim()], vec![0.0; order + 1]);
            assert!(!nurbs.rational_spans_jet_into(0.5, order, KnotSide::Right, &mut v, &mut e));
        };
        decline(curve(&mut values, 3, 3, 2, false, true), 1);
        decline(curve(&mut values, 4, 3, 2, true, true), 1);
        decline(curve(&mut values, 3, 3, 2, true, true), 16);
        // A span of width 1e-6 between spans of width 1: its third
        // derivative from the span's rows has a bound far above
        // RATIONAL_SPAN_RELATIVE_BOUND (the basis route takes it).
        let poles: Vec<f64> = (0..6 * 2).map(|_| 4.0 * values.unit() - 2.0).collect();
        let weights = (0..6).map(|_| 0.5 + values.unit()).collect();
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0 + 1e-6, 2.0, 2.0, 2.0, 2.0];
        let short = NurbsCurve::new(2, 3, poles, Some(weights), knots).unwrap();
        let (mut v, mut e) = (vec![0.0; 4 * 2], vec![0.0; 4]);
        assert!(!short.rational_spans_jet_into(1.0 + 5e-7, 3, KnotSide::Right, &mut v, &mut e));
        assert!(short.rational_spans_jet_into(0.5, 3, KnotSide::Right, &mut v, &mut e));
        // Out of the normal range (the review of session 46): one span of
        // width 1e100 at order 4 (`(b - a)^-4` underflows: the fourth
        // derivative came back 0 with bound 0), width 1e30 at order 12
        // (a subnormal row), width 1e-30 at order 10 (an infinite row with an
        // infinite bound was accepted).
        for (width, order) in [(1e100, 4), (1e30, 12), (1e-30, 10), (1e-100, 4)] {
            let poles = vec![0.0, 1.0, 3.0, -1.0];
            let weights = Some(vec![1.0, 2.0, 0.5, 1.5]);
            let knots = vec![0.0, 0.0, 0.0, 0.0, width, width, width, width];
            let far = NurbsCurve::new(1, 3, poles, weights, knots).unwrap();
            let (mut v, mut e) = (vec![0.0; order + 1], vec![0.0; order + 1]);
            assert!(
                !far.rational_spans_jet_into(width / 3.0, order, KnotSide::Right, &mut v, &mut e),
                "width {width:e} order {order}"
            );
            // Orders whose rows stay in range are taken.
            assert!(far.rational_spans_jet_into(
                width / 3.0,
                1,
                KnotSide::Right,
                &mut v[..2],
                &mut e[..2]
            ));
        }
    }

    /// The rational span jet's copy with a constant degree and order
    /// (`order == p`, `p <= 5`) gives the values and bounds of the copy
    /// with both read at run time (the arrays of 16 rows), bit for bit,
    /// and so does its refusal: dimensions 1 to 3, degrees 1 to 5, one to
    /// three spans, both knot sides, with the relative bound of the
    /// library and with none.
    #[test]
    fn rational_span_jet_with_constant_order_gives_the_same_bits() {
        let mut values = Values(49);
        let mut compared = 0;
        for case in 0..240 {
            let dim = 1 + case % 3;
            let p = 1 + (case / 3) % 5;
            let c = curve(&mut values, dim, p, 1 + case % 3, true, case % 2 == 0);
            let (a, b) = c.domain();
            for (j, side) in [
                (0.0, KnotSide::Right),
                (0.37, KnotSide::Left),
                (1.0, KnotSide::Left),
            ]
            .into_iter()
            .chain(std::iter::once((values.unit(), KnotSide::Right)))
            {
                let u = a + (b - a) * j;
                for limit in [RATIONAL_SPAN_RELATIVE_BOUND, f64::INFINITY] {
                    let run = |constant: bool| {
                        let mut v = vec![f64::NAN; (p + 1) * dim];
                        let mut e = vec![f64::NAN; p + 1];
                        macro_rules! by_degree {
                            ($d:literal, $h:literal) => {
                                match (p, constant) {
                                    (_, false) => c.rational_span_jet_body::<$d, $h, 16>(
                                        p, u, p, side, &mut v, &mut e, limit,
                                    ),
                                    (1, true) => c.rational_span_jet::<$d, $h, 2>(
                                        u, p, side, &mut v, &mut e, limit,
                                    ),
                                    (2, true) => c.rational_span_jet::<$d, $h, 3>(
                                        u, p, side, &mut v, &mut e, limit,
                                    ),
                                    (3, true) => c.rational_span_jet::<$d, $h, 4>(
                                        u, p, side, &mut v, &mut e, limit,
                                    ),
                                    (4, true) => c.rational_span_jet::<$d, $h, 5>(
                                        u, p, side, &mut v, &mut e, limit,
                                    ),
                                    _ => c.rational_span_jet::<$d, $h, 6>(
                                        u, p, side, &mut v, &mut e, limit,
                                    ),
                                }
                            };
                        }
                        let taken = match dim {
                            1 => by_degree!(1, 2),
                            2 => by_degree!(2, 3),
                            _ => by_degree!(3, 4),
                        };
                        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                        (taken, bits(&v), bits(&e))
                    };
                    let (constant, runtime) = (run(true), run(false));
                    assert_eq!(
                        constant, runtime,
                        "dim {dim} degree {p} u {u} limit {limit}"
                    );
                    compared += usize::from(constant.0);
                }
            }
        }
        // Most jets are taken (the rest are refusals, compared as well).
        assert!(compared > 1500, "{compared} jets taken");
    }

    /// A NURBS curve whose jets all come from the basis route (A2.3 and
    /// its bounds), the route of rational curves before session 46.
    struct BasisRoute<'a>(&'a NurbsCurve);

    impl crate::curve::CurveJet for BasisRoute<'_> {
        fn dim(&self) -> usize {
            self.0.dim()
        }
        fn check_parameter(&self, name: &str, u: f64) -> crate::Result<()> {
            self.0.check_parameter(name, u)
        }
        fn coordinate_scale(&self) -> f64 {
            self.0.coordinate_scale()
        }
        fn jet(&self, u: f64, order: usize, side: KnotSide) -> (nalgebra::DMatrix<f64>, Vec<f64>) {
            let dim = self.0.dim();
            let mut v = vec![0.0; (order + 1) * dim];
            let mut e = vec![0.0; order + 1];
            self.0
                .eval_derivatives_into(u, order, side, &mut v, Some(&mut e));
            (nalgebra::DMatrix::from_row_slice(order + 1, dim, &v), e)
        }
    }

    /// Connect on rational inputs answers wherever it answered when every
    /// rational jet came from the basis route (`BasisRoute`, A2.3): 3,000
    /// random pairs of rational curves (dimensions 2 and 3, degrees 2-5,
    /// one to four spans with a double knot, in a third of them the knots
    /// squeezed towards the start so that short spans sit beside long ones),
    /// random parameters, orders 1 to the degree plus 1 (above the degree a
    /// rational curve's derivatives do not vanish). Prints how the error
    /// estimates compare.
    #[test]
    fn rational_span_jets_answer_where_the_basis_route_answers() {
        use crate::connect::{ConnectOptions, connect};
        let mut values = Values(47);
        let (mut both, mut old_only, mut new_only, mut neither) = (0, 0, 0, 0);
        let mut ratios = Vec::new();
        let (mut worst_new, mut worst_old) = (0.0f64, 0.0f64);
        for case in 0..3000 {
            let dim = 2 + case % 2;
            let p = [2, 3, 4, 5][case % 4];
            let spans = 1 + case % 4;
            let c = curve(&mut values, dim, p, spans, true, true);
            let d = curve(
                &mut values,
                dim,
                [2, 3, 4, 5][(case / 4) % 4],
                1 + (case / 3) % 4,
                true,
                true,
            );
            // Short spans: squeeze the knots geometrically in some cases.
            let squeeze = |c: NurbsCurve, f: f64| {
                let (a, _) = c.domain();
                let knots: Vec<f64> = c.knots().iter().map(|k| a + (k - a).powf(f)).collect();
                NurbsCurve::new(
                    c.dim(),
                    c.degree(),
                    c.points().to_vec(),
                    c.weights().map(|w| w.to_vec()),
                    knots,
                )
                .unwrap()
            };
            let (c, d) = if case % 3 == 0 {
                (squeeze(c, 3.0), squeeze(d, 3.0))
            } else {
                (c, d)
            };
            let (a, b) = c.domain();
            let (e, f) = d.domain();
            let u0 = a + (b - a) * values.unit();
            let v0 = e + (f - e) * values.unit();
            let kp = 1 + case % (c.degree() + 2);
            let kq = 1 + (case / 7) % (d.degree() + 2);
            let options = ConnectOptions::new(kp, kq);
            let new = connect(&c, u0, &d, v0, &options);
            let old = connect(&BasisRoute(&c), u0, &BasisRoute(&d), v0, &options);
            match (&old, &new) {
                (Ok(o), Ok(n)) => {
                    both += 1;
                    ratios.push(n.error_estimate / o.error_estimate);
                    worst_new = worst_new.max(n.error_estimate);
                    worst_old = worst_old.max(o.error_estimate);
                }
                (Ok(o), Err(err)) => {
                    old_only += 1;
                    if old_only < 6 {
                        println!(
                            "old only: case {case} kp {kp} kq {kq} est {:e}: {err}",
                            o.error_estimate
                        );
                    }
                }
                (Err(_), Ok(_)) => new_only += 1,
                _ => neither += 1,
            }
        }
        ratios.sort_by(f64::total_cmp);
        let n = ratios.len();
        println!(
            "answered by both {both}, by the basis route only {old_only}, by the span route only \
             {new_only}, by neither {neither}; largest estimate {worst_new:e} (basis route \
             {worst_old:e}); estimate / basis route's: median {:.2} p90 {:.2} max {:.2}",
            ratios[n / 2],
            ratios[9 * n / 10],
            ratios[n - 1]
        );
        assert_eq!(old_only, 0, "refused where the basis route answered");
        assert!(both > 2900, "{both} answered by both");
    }

    /// `bezier_span_jet_into` (the jet with bounds a one-span polynomial
    /// NURBS gives connect and the G^k blends): every row within its bound
    /// of the exact jet of the same f64 data, for domains `[0, 1]`, shifted
    /// and scaled (widths 1e-3 to 1e3, offsets up to 1e3), dimensions 1-4,
    /// degrees 1-15 (seven of them; 15 on two domains), orders up to the degree plus 2, parameters at the ends
    /// and inside; on `[0, 1]` the Bezier curve's own de Casteljau jet to
    /// the bit. Rational, multi-span and high-degree curves are declined.
    #[test]
    #[allow(clippy::needless_range_loop)]
    fn one_span_jet_is_within_its_bound_of_the_exact_jet() {
        let mut values = Values(29);
        let mut worst: f64 = 0.0;
        let domains = [
            (0.0, 1.0),
            (-2.0, 3.5),
            (1000.0, 1000.001),
            (0.25, 0.2500001),
            (-700.0, 300.0),
        ];
        for dim in 1..=4 {
            for p in [1, 2, 3, 4, 7, 11, 15] {
                // Degree 15 on the two gentlest domains only: on the others
                // the rationals of its triangle grow to thousands of digits.
                let domains = if p == 15 { &domains[..2] } else { &domains[..] };
                for &(a, b) in domains {
                    let poles: Vec<f64> = (0..(p + 1) * dim)
                        .map(|_| 4.0 * values.unit() - 2.0)
                        .collect();
                    let mut knots = vec![a; p + 1];
                    knots.extend(std::iter::repeat_n(b, p + 1));
                    let nurbs = NurbsCurve::new(dim, p, poles.clone(), None, knots).unwrap();
                    let mut us = vec![a, b];
                    us.push(a + (b - a) * values.unit());
                    for &u in &us {
                        for order in [0, 1, p + 2] {
                            let mut jet = vec![f64::NAN; (order + 1) * dim];
                            let mut bound = vec![f64::NAN; order + 1];
                            assert!(nurbs.bezier_span_jet_into(u, order, &mut jet, &mut bound));
                            if (a, b) == (0.0, 1.0) {
                                let (mut v, mut e) = (vec![0.0; jet.len()], vec![0.0; order + 1]);
                                crate::connect::de_casteljau_jet_into(
                                    &poles, dim, p, u, order, &mut v, &mut e,
                                );
                                assert!(
                                    jet.iter().zip(&v).all(|(x, y)| x.to_bits() == y.to_bits())
                                );
                                assert!(
                                    bound
                                        .iter()
                                        .zip(&e)
                                        .all(|(x, y)| x.to_bits() == y.to_bits())
                                );
                            }
                            let exact = exact_bezier_jet(&poles, dim, p, (a, b, u), order);
                            let at = format!("dim {dim} p {p} [{a}, {b}] u {u}");
                            worst =
                                worst.max(worst_miss_over_bound(&jet, &bound, &exact, dim, &at));
                        }
                    }
                }
            }
        }
        println!("largest miss / bound: {worst:.3}");
        // Declined: rational, two spans, degree 16.
        let decline = |nurbs: NurbsCurve| {
            let (mut v, mut e) = (vec![0.0; 2 * nurbs.dim()], vec![0.0; 2]);
            assert!(!nurbs.bezier_span_jet_into(0.5, 1, &mut v, &mut e));
        };
        decline(curve(&mut values, 3, 3, 1, true, true));
        decline(curve(&mut values, 3, 3, 2, false, true));
        let high: Vec<f64> = (0..17 * 2).map(|_| values.unit()).collect();
        decline(NurbsCurve::from_bezier(
            &BezierCurve::new(2, 16, high).unwrap(),
        ));
    }

    /// The jets of dimensions 2 and 3 at degrees 1 to 5
    /// (`eval_rows_fixed`, the degree and dimension constants) are the
    /// general body's (`eval_rows` on heap buffers) to the bit, values and
    /// bounds: polynomial and rational curves of 1 to 3 spans, clamped and
    /// with free end knots, every order up to 7, at random parameters and at
    /// every knot from both sides.
    #[test]
    fn fixed_degree_rows_are_the_general_rows_to_the_bit() {
        let mut values = Values(31);
        let mut cases = 0;
        for dim in 2..=3 {
            for p in 1..=5 {
                for spans in 1..=3 {
                    for rational in [false, true] {
                        for clamped in [true, false] {
                            if !clamped && spans == 1 {
                                continue;
                            }
                            let c = curve(&mut values, dim, p, spans, rational, clamped);
                            let (a, b) = c.domain();
                            let mut us: Vec<f64> =
                                (0..4).map(|_| a + (b - a) * values.unit()).collect();
                            us.extend(c.knots.iter().copied().filter(|&k| (a..=b).contains(&k)));
                            for &u in &us {
                                for side in [KnotSide::Left, KnotSide::Right] {
                                    for order in 0..=7 {
                                        let rows = order + 1;
                                        let n = order.min(p);
                                        let mut fast = vec![f64::NAN; rows * dim];
                                        let mut fast_bound = vec![f64::NAN; rows];
                                        c.eval_derivatives_into(
                                            u,
                                            order,
                                            side,
                                            &mut fast,
                                            Some(&mut fast_bound),
                                        );
                                        let mut general = vec![f64::NAN; rows * dim];
                                        let mut general_bound = vec![f64::NAN; rows];
                                        let mut basis = vec![0.0; (n + 1) * (p + 1)];
                                        let mut work = vec![0.0; basis_scratch_len(p)];
                                        let mut jets = vec![0.0; 3 * rows];
                                        c.eval_rows(
                                            u,
                                            n,
                                            side,
                                            &mut general,
                                            Some(&mut general_bound),
                                            &mut basis,
                                            &mut work,
                                            &mut jets,
                                        );
                                        let same = |x: &[f64], y: &[f64]| {
                                            x.iter().zip(y).all(|(a, b)| a.to_bits() == b.to_bits())
                                        };
                                        assert!(
                                            same(&fast, &general)
                                                && same(&fast_bound, &general_bound),
                                            "dim {dim} p {p} spans {spans} rational {rational} clamped {clamped} \
                                             u {u} {side:?} order {order}: {fast:?} {fast_bound:?} vs \
                                             {general:?} {general_bound:?}"
                                        );
                                        cases += 1;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        assert!(cases > 5000, "{cases} cases");
    }

    /// A Bezier curve as a one-span NURBS (`from_bezier`, domain `[0, 1]`)
    /// evaluates to the bits of the Bezier curve, every order up to the
    /// degree plus 2 (the rows above the degree exactly 0), at random
    /// parameters, the ends and 1/2, dimensions 2 and 3, degrees 1 to 15.
    #[test]
    fn one_span_polynomial_is_the_bezier_curve_to_the_bit() {
        let mut values = Values(26);
        for dim in 2..=3 {
            for p in 1..=SPAN_FAST_MAX_DEGREE {
                let points = (0..(p + 1) * dim)
                    .map(|_| 4.0 * values.unit() - 2.0)
                    .collect();
                let bezier = BezierCurve::new(dim, p, points).unwrap();
                let nurbs = NurbsCurve::from_bezier(&bezier);
                let mut ts = vec![0.0, 0.5, 1.0];
                ts.extend((0..20).map(|_| values.unit()));
                for t in ts {
                    for order in 0..=p + 2 {
                        let mut ours = vec![f64::NAN; (order + 1) * dim];
                        nurbs
                            .eval_derivatives_checked_into(|| "t".into(), t, order, &mut ours)
                            .unwrap();
                        let mut theirs = vec![0.0; (order + 1) * dim];
                        if order == 0 {
                            bezier.eval_into(t, &mut theirs);
                        } else {
                            bezier.eval_derivatives_into(t, order, &mut theirs);
                        }
                        assert!(
                            ours.iter()
                                .zip(&theirs)
                                .all(|(a, b)| a.to_bits() == b.to_bits()),
                            "dim {dim}, degree {p}, order {order}, t {t}: {ours:?} vs {theirs:?}"
                        );
                    }
                }
            }
        }
    }

    /// `point_checked` is `eval_derivatives_checked_into` at order 0, bit
    /// for bit, and fails where it fails with the same error: one-span
    /// polynomial curves on `[0, 1]` (its own path) and on other domains,
    /// one-span curves whose end knots are not clamped, rational and
    /// multi-span curves, parameters at and between the ends, outside the
    /// domain and not finite, degrees 1 to 9 and 12, 15 (the fast path's
    /// last), 16 and 20, and poles near the top of the `f64` range (whose
    /// Horner sums overflow and are redone by the kernel's own fallbacks:
    /// the value of a one-span curve, a convex combination, stays finite,
    /// so `point_checked`'s own finiteness test is a defence, not a path
    /// this test reaches).
    #[test]
    fn point_checked_is_the_checked_evaluation_at_order_zero() {
        fn check<const D: usize>(c: &NurbsCurve, u: f64) -> bool {
            let mut general = [f64::NAN; D];
            let expected = c.eval_derivatives_checked_into(|| "u".into(), u, 0, &mut general);
            let ours = c.point_checked::<D>(|| "u".into(), u);
            match (ours, expected) {
                (Ok(x), Ok(())) => {
                    assert!(
                        x.iter()
                            .zip(&general)
                            .all(|(a, b)| a.to_bits() == b.to_bits()),
                        "u {u}: {x:?} vs {general:?} for {c:?}"
                    );
                    true
                }
                (Err(a), Err(b)) => {
                    assert_eq!(a.to_string(), b.to_string(), "u {u}");
                    false
                }
                (a, b) => panic!("u {u}: {a:?} vs {b:?} for {c:?}"),
            }
        }
        let mut values = Values(50);
        let (mut answered, mut refused) = (0, 0);
        for case in 0..360 {
            let dim = 2 + case % 2;
            let p = [1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 15, 16, 20][(case / 2) % 13];
            let c = match case % 6 {
                // A Bezier curve as a NURBS handle: the fast path.
                0 | 1 => {
                    let magnitude = if case % 12 == 1 { 1e307 } else { 1.0 };
                    let points = (0..(p + 1) * dim)
                        .map(|_| magnitude * (4.0 * values.unit() - 2.0))
                        .collect();
                    NurbsCurve::from_bezier(&BezierCurve::new(dim, p, points).unwrap())
                }
                2 => curve(&mut values, dim, p, 1, false, true),
                3 => curve(&mut values, dim, p, 1, false, false),
                4 => curve(&mut values, dim, p, 1 + case % 3, true, case % 4 == 0),
                _ => curve(&mut values, dim, p, 2 + case % 2, false, true),
            };
            let (a, b) = c.domain();
            let mut us = vec![
                a,
                b,
                0.5 * (a + b),
                a - 1e-9,
                b + 1.0,
                f64::NAN,
                f64::INFINITY,
            ];
            us.extend((0..6).map(|_| a + (b - a) * values.unit()));
            for u in us {
                let ok = if dim == 2 {
                    check::<2>(&c, u)
                } else {
                    check::<3>(&c, u)
                };
                if ok {
                    answered += 1;
                } else {
                    refused += 1;
                }
            }
        }
        // Both outcomes were compared (not only one of them).
        assert!(answered > 2000 && refused > 1000, "{answered} / {refused}");
    }

    /// The span route (every route of `eval_derivatives_checked_into` in
    /// dimensions 2 and 3) agrees with the basis route (A2.3 and A4.2 on
    /// the knot vector, an independent formulation) within
    /// [`AGREEMENT_FACTOR`] times the basis route's rounding bound, every
    /// order up to the degree plus 2, for polynomial and rational curves of
    /// 1 to 4 spans (clamped, and with free end knots), degrees 1 to 15,
    /// at random parameters, at every knot of the domain (from the right)
    /// and at both ends. Evaluating leaves the curve equal to a fresh copy,
    /// and a clone evaluates to the same bits.
    #[test]
    fn span_route_agrees_with_the_basis_route() {
        let mut values = Values(2026);
        let mut worst = 0.0f64;
        for dim in 2..=3 {
            for p in 1..=SPAN_FAST_MAX_DEGREE {
                for spans in 1..=4 {
                    for rational in [false, true] {
                        for clamped in [true, false] {
                            let c = curve(&mut values, dim, p, spans, rational, clamped);
                            let fresh = c.clone();
                            let (first, last) = c.domain();
                            let mut us: Vec<f64> = c
                                .knots()
                                .iter()
                                .copied()
                                .filter(|u| (first..=last).contains(u))
                                .collect();
                            us.extend((0..12).map(|_| first + (last - first) * values.unit()));
                            for &u in &us {
                                for order in [0, 1, 2, 3, p, p + 2] {
                                    let mut ours = vec![f64::NAN; (order + 1) * dim];
                                    c.eval_derivatives_checked_into(
                                        || "u".into(),
                                        u,
                                        order,
                                        &mut ours,
                                    )
                                    .unwrap();
                                    let (theirs, bound) =
                                        c.eval_derivatives_with_bound(u, order, KnotSide::Right);
                                    for k in 0..=order {
                                        let a = &ours[k * dim..(k + 1) * dim];
                                        let b = &theirs[k * dim..(k + 1) * dim];
                                        let gap = crate::bezier::distance(a, b);
                                        let allowed = AGREEMENT_FACTOR * bound[k] + 1e-300;
                                        worst = worst.max(gap / allowed * AGREEMENT_FACTOR);
                                        assert!(
                                            gap <= allowed,
                                            "dim {dim}, degree {p}, spans {spans}, rational \
                                             {rational}, clamped {clamped}, u {u}, order {k}: \
                                             {a:?} vs {b:?}, gap {gap:e}, bound {:e}",
                                            bound[k]
                                        );
                                    }
                                }
                            }
                            assert_eq!(c, fresh);
                            let copy = c.clone();
                            for &u in &us {
                                let x = c.eval_derivatives_checked("u", u, 3).unwrap();
                                let y = copy.eval_derivatives_checked("u", u, 3).unwrap();
                                assert!(x.iter().zip(&y).all(|(a, b)| a.to_bits() == b.to_bits()));
                            }
                        }
                    }
                }
            }
        }
        eprintln!("largest gap / basis bound: {worst:.2}");
    }
}
