//! Connect two curves with C^k continuity and interior constraints
//! (docs/mathematics.md#connect).
//!
//! After Krivosheev, Mavrin, Starkova, *Bezier curve conjugation for smooth
//! curve joining and corner rounding*, Omsk Scientific Bulletin, 2025
//! (Theorems 1 and 2), extended with several interior constraint points and
//! the shape scales `alpha`, `beta`:
//!
//! ```text
//! R^(k)(0)   = alpha^k P^(k)(u0),  k = 0..kp
//! R^(k)(1)   = beta^k  Q^(k)(v0),  k = 0..kq                    (1')
//! R^(k)(t_j) = D_jk,               k = 0..K_j, j = 1..m          (2)
//! ```
//!
//! The connecting curve `R` has degree `nr = kp + kq + 1 + sum_j (K_j + 1)`
//! and is the unique solution. The chain `P|[0,u0]`, `R`, `Q|[v0,1]` is a C^k
//! B-spline with knot intervals `(u0, alpha, (1 - v0) alpha / beta)`.
//!
//! # Solver
//! The structured path of the paper's eq. 19 ([`connect`]): forward
//! substitution with the lower-triangular rows of `D(0)` for `R_0..R_kp`,
//! back substitution with the anti-triangular rows of `D(1)` for
//! `R_(nr-kq)..R_nr`, one `M x M` dense solve (`M = sum (K_j + 1)`, rows
//! scaled to unit 1-norm) for the middle points with the known ones moved to
//! the right-hand side; all coordinates at once. Cost `O(nr^2 d + M^3)`.
//! [`connect_dense_reference`] solves the full `(nr+1) x (nr+1)` system by
//! LU instead; it is the reference for tests and benchmarks.
//!
//! # Where the basis rows come from
//! * Rows of `D(0)` and `D(1)` (the end conditions (1'), and `P^(k)(u0)`,
//!   `Q^(k)(v0)` when `u0`, `v0` is exactly 0 or 1): the closed form
//!   `B_i^(k)(0) = n!/(n-k)! (-1)^(k-i) C(k, i)` for `i <= k` (0 otherwise),
//!   and `B_i^(k)(1) = (-1)^k B_(n-i)^(k)(0)` from `B_i(t) = B_(n-i)(1 - t)`.
//!   It is the k-th forward difference in `R^(k)(0) = n!/(n-k)! Delta^k R_0`,
//!   i.e. exactly what A2.3 evaluates on the knots `0^(n+1) 1^(n+1)` at an
//!   end; the
//!   entries are integers formed exactly (up to rounding of `n!/(n-k)!`
//!   above 2^53). The unit test `closed_form_end_rows_equal_a23` holds them
//!   to [`bezier_basis_derivatives`] for every degree up to
//!   [`MAX_CONNECT_DEGREE`], with the exact zero pattern.
//! * Rows of `D(t_j)` for interior constraints: A2.3
//!   ([`bezier_basis_derivatives`]), as the specification requires for the
//!   solvers.
//! * The targets `P^(k)(u0)`, `Q^(k)(v0)` at interior parameters are values
//!   of the input curves, not solver rows: the de Casteljau triangle
//!   ([`de_casteljau_jet_into`]), `O(n^2 d)` with a first-order rounding
//!   bound, instead of the `O(n^3)` A2.3 matrix and its product (issue 20).
//!
//! The end rows are the hot path of [`connect`] (and of every trial scale of
//! [`ShapeScale::Auto`]); the closed form avoids A2.3's allocations there.
//! The residual check works on the stored rows without temporary matrices.
//!
//! # Relative residual
//! For each condition row with basis row `D_k` (a row of `D(0)`, `D(1)` or
//! `D(t_j)`) and target `T_k`:
//!
//! ```text
//! residual_k = |D_k R - T_k| / max(|T_k|, S * ||D_k||_1)
//! ```
//!
//! where `|.|` is the Euclidean norm over the coordinates and `S`, the *data
//! scale*, is the largest of: the absolute coordinates of the control points
//! of `P` and `Q`, and `|T_k| / ||D_k||_1` over all conditions (the smallest
//! control-point size any curve meeting condition `k` must have, since
//! `|D_k R| <= ||D_k||_1 max_i |R_i|`). `S * ||D_k||_1` is the size a k-th
//! derivative of a curve with control points of size `S` can have, so a zero
//! target derivative never divides by zero.
//!
//! # What we guarantee
//! Every returned [`Connection`] satisfies (1') and (2) with a worst relative
//! residual, *in exact arithmetic on the returned control points*, of at most
//! [`CONNECT_RESIDUAL_LIMIT`] (`1e-8`). The solver checks this itself: it
//! recomputes every residual after solving and adds a first-order rounding
//! bound for the evaluation of `D_k R` and of the targets
//! ([`Connection::error_estimate`]); when that bound exceeds the limit the
//! answer is refused with [`BezjoinError::IllConditioned`] carrying the
//! estimate. Result degrees above [`MAX_CONNECT_DEGREE`] (31, the range of
//! the measured table in `docs/accuracy.md`) are refused up front; no answer
//! is computed then, so there is no residual to bound and the reported
//! estimate is infinite.
//!
//! The measured residuals and estimates versus degree, against an exact
//! rational reference, are in `docs/accuracy.md` (Connect).

mod dense;
mod ends;
mod screen;
pub(crate) use ends::connect_ends_shaped;
mod energy;

use nalgebra::DMatrix;

use crate::basis::{KnotSide, bezier_basis_derivatives};
use crate::bezier::BezierCurve;
use crate::curve::CurveJet;
use crate::error::{BezjoinError, Result, check_finite, check_open_range, check_positive};
use crate::linalg::solve_checked;

pub use dense::connect_dense_reference;
pub use energy::{
    AUTO_SCALE_SEARCH_DECADES, BALANCED_SPEED_FLOOR, UNKINKED_POLYGON_CHORDS, fairness_energy,
};
pub(crate) use energy::{end_speed, natural_scale};

/// The promised worst relative residual of (1') and (2) (see the module
/// documentation for the definition). Answers whose error estimate exceeds
/// it are refused with `IllConditioned`.
pub const CONNECT_RESIDUAL_LIMIT: f64 = 1e-8;

/// Largest result degree `kp + kq + 1 + sum (K_j + 1)` accepted at all.
///
/// Above it the request is refused with `IllConditioned` before any work.
/// The accuracy table (docs/accuracy.md, Connect) is measured up to 31; with
/// interior constraints the worst residual there grows about tenfold per
/// three to four degrees (3e-10 at degree 30), so the 1e-8 margin is gone
/// a few degrees above it. The bound also caps the work a C caller can ask for.
/// The refusal's estimate is `f64::INFINITY`: nothing is solved, so no
/// residual exists to bound (a finite number would be a guess).
pub const MAX_CONNECT_DEGREE: usize = 31;

/// The degree `kp + kq + 1 + sum (K_j + 1)` of a connecting curve with
/// orders `p_order`, `q_order` and interior constraints of orders
/// `constraint_orders` (`K_j`), or `IllConditioned` (estimate infinite:
/// nothing is solved) when it is above [`MAX_CONNECT_DEGREE`] or
/// overflows. [`connect`] checks it first; the C ABI calls it before it
/// reads the constraints' value arrays, whose lengths depend on the orders.
#[inline]
pub fn check_connect_degree(
    p_order: usize,
    q_order: usize,
    constraint_orders: impl IntoIterator<Item = usize>,
) -> Result<usize> {
    let mut degree = p_order.checked_add(q_order).and_then(|d| d.checked_add(1));
    for k in constraint_orders {
        degree = degree
            .and_then(|d| d.checked_add(k))
            .and_then(|d| d.checked_add(1));
    }
    match degree {
        Some(d) if d <= MAX_CONNECT_DEGREE => Ok(d),
        _ => Err(degree_above_maximum(p_order, q_order, degree)),
    }
}

/// The error of [`check_connect_degree`], out of the callers' hot paths.
#[cold]
#[inline(never)]
fn degree_above_maximum(p_order: usize, q_order: usize, degree: Option<usize>) -> BezjoinError {
    BezjoinError::IllConditioned {
        what: format!(
            "connect: result degree {} is above the supported maximum {MAX_CONNECT_DEGREE} \
             (p_order {p_order} + q_order {q_order} + 1, plus one more than each \
             constraint's order)",
            degree.map_or_else(|| "(overflow)".to_string(), |d| d.to_string())
        ),
        estimate: f64::INFINITY,
        limit: CONNECT_RESIDUAL_LIMIT,
    }
}

/// An interior constraint (2): `R^(k)(t)` prescribed for `k = 0..=K`
/// (the C ABI's `BzjPointConstraint`).
#[derive(Debug, Clone, PartialEq)]
pub struct PointConstraint {
    /// Parameter on the connecting curve, in `(0, 1)`.
    pub t: f64,
    /// `K`: derivatives `0..=K` are prescribed (`K = 0`: the position only).
    pub max_order: usize,
    /// `(K + 1) * dim` values, row-major: row `k` is `R^(k)(t)`.
    pub values: Vec<f64>,
}

impl PointConstraint {
    /// A constraint at `t` on derivatives `0..=max_order`, `values` row-major.
    pub fn new(t: f64, max_order: usize, values: Vec<f64>) -> Self {
        Self {
            t,
            max_order,
            values,
        }
    }
}

/// What to connect and how (docs/mathematics.md#connect).
#[derive(Debug, Clone, PartialEq)]
pub struct ConnectOptions {
    /// `kp`: derivatives `0..=kp` of `P` at `u0` are matched (any order: above
    /// a polynomial's degree they are 0).
    pub p_order: usize,
    /// `kq`: derivatives `0..=kq` of `Q` at `v0` are matched (any order).
    pub q_order: usize,
    /// How the shape scales `alpha`, `beta` are chosen; default
    /// `ShapeScale::Given { p: 1.0, q: 1.0 }`, the paper.
    pub scale: ShapeScale,
    /// Interior constraints at distinct parameters in `(0, 1)`, any order.
    pub constraints: Vec<PointConstraint>,
}

impl ConnectOptions {
    /// Orders `kp`, `kq`, scales 1 (the paper), no constraints.
    pub fn new(p_order: usize, q_order: usize) -> Self {
        Self {
            p_order,
            q_order,
            scale: ShapeScale::default(),
            constraints: Vec::new(),
        }
    }

    /// The same options with scales `alpha`, `beta` ([`ShapeScale::Given`]).
    pub fn with_scales(mut self, p_scale: f64, q_scale: f64) -> Self {
        self.scale = ShapeScale::Given {
            p: p_scale,
            q: q_scale,
        };
        self
    }

    /// The same options with the scale chosen for fairness ([`ShapeScale::Auto`]).
    pub fn with_auto_scale(mut self) -> Self {
        self.scale = ShapeScale::Auto;
        self
    }

    /// The same options with both ends left at one fair speed
    /// ([`ShapeScale::Balanced`]).
    pub fn with_balanced_scale(mut self) -> Self {
        self.scale = ShapeScale::Balanced;
        self
    }

    /// The same options with one more interior constraint.
    pub fn with_constraint(mut self, constraint: PointConstraint) -> Self {
        self.constraints.push(constraint);
        self
    }

    /// The degree of the connecting curve: `kp + kq + 1 + sum (K_j + 1)`.
    pub fn result_degree(&self) -> usize {
        self.p_order
            + self.q_order
            + 1
            + self
                .constraints
                .iter()
                .map(|c| c.max_order + 1)
                .sum::<usize>()
    }
}

/// How the shape scales `alpha` (at `P`) and `beta` (at `Q`) of a
/// connecting curve are chosen (section 1, eq. (1'): the end derivatives of
/// `R` are those of `P` and `Q` times `alpha^r`, `beta^r`). One choice for
/// [`connect`] and for [`crate::fillet()`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ShapeScale {
    /// The caller's `alpha = p > 0` and `beta = q > 0`; `p = q = 1` is the paper.
    Given {
        /// `alpha > 0`.
        p: f64,
        /// `beta > 0`.
        q: f64,
    },
    /// `alpha = beta = s` minimising the fairness energy
    /// `E(s) = integral_0^1 |R_s''(t)|^2 dt` (computed exactly,
    /// [`fairness_energy`]) by a bounded 1-D search on `log s` over
    /// [`AUTO_SCALE_SEARCH_DECADES`] decades either side of the natural scale
    /// `s0 = |Q(v0) - P(u0)| / mean(v_P, v_Q)` (1 when the gap or the speeds
    /// vanish; `v_P = |P'(u0)|` raised to the floor of the balanced scale,
    /// [`BALANCED_SPEED_FLOOR`], where the end turns or accelerates within
    /// 1 % of the chord). `R_s` is linear in the scaled jets, so `E` is a
    /// polynomial of degree `2 max(kp, kq)` in `s`, formed from
    /// `max(kp, kq) + 1` triangular solves: its global minimum on the range
    /// (every sign change of its slope on a log-spaced grid, refined by
    /// bisection to about 1e-9 relative in `s`, and the range's ends), then
    /// one fully checked solve there. Should that solve be refused, a grid of
    /// 33 full solves, then Brent's method, skips the refused scales. Where
    /// that minimum lies at the range's lower end (ends facing away: the
    /// blend would be the chord with a kink at each end) and no end's speed
    /// is raised to its floor, `s = s0`, or the largest smaller scale whose
    /// control polygon is at most [`UNKINKED_POLYGON_CHORDS`] chords
    /// (docs/mathematics.md, "Where the energy has no minimum inside the
    /// range"). Ends within 1e-9 of their largest coordinate are
    /// InvalidArgument naming `v0` (between coincident points every blend
    /// is a loop). When
    /// `kp = kq = 0` the result does not depend on `s` and `s = 1`. Keeps
    /// blends whose ends move fast (`|P'(u0)|` large against the gap) from
    /// looping, which scale 1 does not. The chosen `s` is reported in
    /// [`Connection::p_scale`] and [`Connection::q_scale`].
    Auto,
    /// `alpha = sigma / |P'(u0)|`, `beta = sigma / |Q'(v0)|`: the blend
    /// leaves both curves at one speed `sigma`, chosen as [`ShapeScale::Auto`]
    /// chooses `s` (the same energy, search, rule at the lower end and
    /// fallback, with the natural
    /// value `sigma0 = |Q(v0) - P(u0)|`). `alpha^k P^(k)(u0)` is then the jet of
    /// `P` reparametrised to unit speed at `u0`, so the blend does not depend
    /// on how fast either curve runs in its own parameter: reparametrising `P`
    /// or `Q` linearly (a line of length 1000 given on `[0, 1]` or on
    /// `[0, 1000]`) gives the same blend, which [`ShapeScale::Auto`] does not
    /// (its one `s` leaves a curve that runs 100 times faster at 100 times the
    /// other's speed, a near-kink at the slow end). An end that turns or
    /// accelerates on a scale below 1 % of the chord is balanced at a higher
    /// speed than `|P'(u0)|` ([`BALANCED_SPEED_FLOOR`]; that end then leaves
    /// slower than `sigma`), which keeps the blend in size at near-stationary
    /// ends and keeps the reparametrisation guarantee where `P'(u0) = 0`.
    /// Where the two speeds agree to 1e-9, or an end has none (order 0, a jet
    /// that vanishes or overflows), this is [`ShapeScale::Auto`], the same
    /// bits. Not offered by
    /// [`crate::fillet_within_deviation`] (its automatic scale is a fixed point
    /// of one `s`).
    Balanced,
}

impl Default for ShapeScale {
    /// `Given { p: 1.0, q: 1.0 }`, the paper.
    fn default() -> Self {
        ShapeScale::Given { p: 1.0, q: 1.0 }
    }
}

impl ShapeScale {
    /// The given scales, checked `> 0` (named `p_scale`, `q_scale`); `None`
    /// for [`ShapeScale::Auto`].
    #[inline]
    pub(crate) fn checked(&self) -> Result<Option<(f64, f64)>> {
        match *self {
            ShapeScale::Given { p, q } => {
                check_positive("p_scale", p)?;
                check_positive("q_scale", q)?;
                Ok(Some((p, q)))
            }
            ShapeScale::Auto | ShapeScale::Balanced => Ok(None),
        }
    }
}

/// A connecting curve and the accuracy it was checked to.
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// `R`, of degree `kp + kq + 1 + sum (K_j + 1)`.
    pub curve: BezierCurve,
    /// `alpha` used.
    pub p_scale: f64,
    /// `beta` used.
    pub q_scale: f64,
    /// Worst relative residual of (1') and (2) as computed in floating point.
    pub max_residual: f64,
    /// Bound on the worst relative residual in exact arithmetic on the
    /// returned control points: `max_residual` plus first-order rounding
    /// bounds of the evaluation; never above [`CONNECT_RESIDUAL_LIMIT`].
    pub error_estimate: f64,
    /// 1-norm condition estimate of the row-scaled `M x M` interior block
    /// (1 when there are no constraints).
    pub constraint_condition: f64,
}

/// Ends closer than this part of the coordinate scale cannot be told apart
/// (the rule of a radius too small to tell from its corner): the automatic
/// scales and the fair G^k search refuse them.
pub(crate) const COINCIDENT_ENDS: f64 = 1e-9;

/// The validated problem, independent of the scales.
#[derive(Debug, Clone)]
pub(crate) struct Problem {
    pub(crate) dim: usize,
    pub(crate) degree: usize,
    pub(crate) p_order: usize,
    pub(crate) q_order: usize,
    /// `P^(k)(u0)`, `(kp+1) x dim`, unscaled.
    pub(crate) p_derivatives: DMatrix<f64>,
    /// Rounding bound of each row of `p_derivatives` (absolute, Euclidean).
    pub(crate) p_derivative_error: Vec<f64>,
    /// `Q^(k)(v0)`, `(kq+1) x dim`, unscaled.
    pub(crate) q_derivatives: DMatrix<f64>,
    pub(crate) q_derivative_error: Vec<f64>,
    /// Constraints sorted by parameter: `(t_j, (K_j+1) x dim)`.
    pub(crate) constraints: Vec<(f64, DMatrix<f64>)>,
    /// The control-point scale of `P` and `Q` (part of the data scale `S`).
    pub(crate) data_scale: f64,
}

impl Problem {
    /// The chord `|Q(v0) - P(u0)|` between the blend's ends.
    pub(crate) fn chord(&self) -> f64 {
        (self.q_derivatives.row(0) - self.p_derivatives.row(0)).norm()
    }

    /// The largest coordinate of the blend's ends `P(u0)`, `Q(v0)` (in
    /// absolute value): what tells coincident ends apart
    /// ([`COINCIDENT_ENDS`]).
    pub(crate) fn ends_coordinate(&self) -> f64 {
        crate::geometric::largest_coordinate(
            self.p_derivatives.row(0).iter(),
            self.q_derivatives.row(0).iter(),
        )
    }

    /// `Some((gap, largest coordinate of the ends))` where the ends lie
    /// within [`COINCIDENT_ENDS`] of their largest coordinate (the
    /// automatic scales and the fair G^k search refuse them).
    pub(crate) fn coincident_ends(&self) -> Option<(f64, f64)> {
        let (gap, ends) = (self.chord(), self.ends_coordinate());
        (gap <= COINCIDENT_ENDS * ends).then_some((gap, ends))
    }

    /// `M = sum (K_j + 1)`.
    pub(crate) fn middle_count(&self) -> usize {
        self.constraints.iter().map(|(_, d)| d.nrows()).sum()
    }
}

fn unit_roundoff() -> f64 {
    f64::EPSILON / 2.0
}

/// `x^k` by binary powering, the operations of `f64::powi` (compiler-rt's
/// `__powidf2`: multiply by the running square for each set bit, from the
/// lowest), inlined: the same value bit for bit (unit test
/// `power_equals_powi`) without the library call on the hot path.
#[inline]
pub(crate) fn power(x: f64, k: usize) -> f64 {
    let mut base = x;
    let mut bits = k;
    let mut result = 1.0f64;
    loop {
        if bits & 1 != 0 {
            result *= base;
        }
        bits >>= 1;
        if bits == 0 {
            return result;
        }
        base *= base;
    }
}

/// The non-zero band of row `k <= degree` of `D(0)` (`at_one = false`:
/// columns `0..=k`) or `D(1)` (`at_one = true`: columns `n-k..=n`) for
/// degree `n = degree`, by the closed form (module documentation, "Where
/// the basis rows come from"), in ascending column order into `band[..=k]`.
#[allow(clippy::needless_range_loop)] // j indexes the table and the band
pub(crate) fn end_band(degree: usize, k: usize, at_one: bool, band: &mut [f64]) {
    // n!/(n-k)! (exact while below 2^53, else within k units of roundoff) and
    // C(k, j) by the exact integer recurrence C(k, j+1) = C(k, j) (k-j)/(j+1),
    // from the tables below the table size (the same operations, done once).
    let small = degree < END_TABLE_SIZE;
    let falling = if small {
        FALLING_FACTORIALS[degree][k]
    } else {
        falling_factorial(degree, k)
    };
    if small {
        // Both ends have the same band: slot s of D(1)'s row is
        // n!/(n-k)! (-1)^(k-s) C(k, k-s), and C(k, k-s) = C(k, s) exactly
        // (integers below 2^53); f (-c) = -(f c) in IEEE arithmetic.
        let signed = &SIGNED_BINOMIALS[k];
        for (slot, &c) in band[..=k].iter_mut().zip(signed) {
            *slot = falling * c;
        }
        return;
    }
    let mut coefficient = 1.0f64; // C(k, j)
    for j in 0..=k {
        // D(0)[k][j] = n!/(n-k)! (-1)^(k-j) C(k, j);
        // D(1)[k][n-j] = n!/(n-k)! (-1)^j C(k, j)  (B_i(t) = B_(n-i)(1-t)),
        // at band position (n - j) - (n - k) = k - j.
        let (slot, negative) = if at_one {
            (k - j, j % 2 == 1)
        } else {
            (j, (k - j) % 2 == 1)
        };
        let value = falling * coefficient;
        band[slot] = if negative { -value } else { value };
        coefficient = coefficient * (k - j) as f64 / (j + 1) as f64;
    }
}

/// `sum_j |band_j|` of [`end_band`]`(degree, k, ..)` (either end: the same
/// entries in reverse order, and `C(k, j) = C(k, k - j)` exactly), summed in
/// band order from `0.0` as the general path sums a row (from the table
/// below the table size).
#[cfg(test)]
pub(crate) fn end_band_norm(degree: usize, k: usize) -> f64 {
    if degree < END_TABLE_SIZE {
        return END_BAND_NORMS[degree][k];
    }
    let mut band = vec![0.0; k + 1];
    end_band(degree, k, false, &mut band);
    band.iter().map(|v| v.abs()).sum()
}

/// `END_BAND_NORMS[n][k]`: `end_band_norm` (test-only) by the operations of
/// [`end_band`] and the sum.
pub(crate) static END_BAND_NORMS: [[f64; END_TABLE_SIZE]; END_TABLE_SIZE] = {
    let mut table = [[0.0f64; END_TABLE_SIZE]; END_TABLE_SIZE];
    let mut n = 0;
    while n < END_TABLE_SIZE {
        let mut k = 0;
        while k <= n {
            let falling = FALLING_FACTORIALS[n][k];
            let mut sum = 0.0f64;
            let mut j = 0;
            while j <= k {
                sum += (falling * BINOMIALS[k][j]).abs();
                j += 1;
            }
            table[n][k] = sum;
            k += 1;
        }
        n += 1;
    }
    table
};

/// `END_BAND_NORM_RECIPROCALS[n][k] = 1 / END_BAND_NORMS[n][k]` (rounded):
/// the data scale of the connect's screen without a division
/// (`ends::scale_targets`; the screen's slack covers the rounding).
pub(crate) static END_BAND_NORM_RECIPROCALS: [[f64; END_TABLE_SIZE]; END_TABLE_SIZE] = {
    let mut table = [[0.0f64; END_TABLE_SIZE]; END_TABLE_SIZE];
    let mut n = 0;
    while n < END_TABLE_SIZE {
        let mut k = 0;
        while k <= n {
            table[n][k] = 1.0 / END_BAND_NORMS[n][k];
            k += 1;
        }
        n += 1;
    }
    table
};

/// Degrees below which [`end_band`] reads its factors from tables.
pub(crate) const END_TABLE_SIZE: usize = MAX_CONNECT_DEGREE + 1;

/// `FALLING_FACTORIALS[n][k] = n (n-1) ... (n-k+1)` (as [`falling_factorial`]).
pub(crate) static FALLING_FACTORIALS: [[f64; END_TABLE_SIZE]; END_TABLE_SIZE] = {
    let mut table = [[0.0f64; END_TABLE_SIZE]; END_TABLE_SIZE];
    let mut n = 0;
    while n < END_TABLE_SIZE {
        let mut falling = 1.0f64;
        let mut k = 0;
        while k <= n {
            table[n][k] = falling;
            falling *= (n - k) as f64;
            k += 1;
        }
        n += 1;
    }
    table
};

/// `BINOMIALS[k][j] = C(k, j)` by the recurrence of [`end_band`].
static BINOMIALS: [[f64; END_TABLE_SIZE]; END_TABLE_SIZE] = {
    let mut table = [[0.0f64; END_TABLE_SIZE]; END_TABLE_SIZE];
    let mut k = 0;
    while k < END_TABLE_SIZE {
        let mut coefficient = 1.0f64;
        let mut j = 0;
        while j <= k {
            table[k][j] = coefficient;
            coefficient = coefficient * (k - j) as f64 / (j + 1) as f64;
            j += 1;
        }
        k += 1;
    }
    table
};

/// `SIGNED_BINOMIALS[k][j] = (-1)^(k-j) C(k, j)`, from [`BINOMIALS`] (exact).
pub(crate) static SIGNED_BINOMIALS: [[f64; END_TABLE_SIZE]; END_TABLE_SIZE] = {
    let mut table = [[0.0f64; END_TABLE_SIZE]; END_TABLE_SIZE];
    let mut k = 0;
    while k < END_TABLE_SIZE {
        let mut j = 0;
        while j <= k {
            let c = BINOMIALS[k][j];
            table[k][j] = if (k - j) % 2 == 1 { -c } else { c };
            j += 1;
        }
        k += 1;
    }
    table
};

/// Run `f` on `len` zeroed doubles: on the stack up to 96 or 512 of them
/// (the small degrees and dimensions of the hot paths), on the heap above.
pub(crate) fn with_scratch<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    if len <= 96 {
        f(&mut [0.0f64; 96][..len])
    } else if len <= 512 {
        f(&mut [0.0f64; 512][..len])
    } else {
        f(&mut vec![0.0f64; len])
    }
}

/// Row `k` (`k <= order`, `k <= degree`) of `D(0)` (`at_one = false`) or
/// `D(1)` (`at_one = true`) for degree `degree` ([`end_band`]), written
/// into `out[(row, ..)]` of a `rows x (degree + 1)` column-major buffer;
/// the other entries are left alone.
fn end_basis_row(degree: usize, k: usize, at_one: bool, out: &mut DMatrix<f64>, row: usize) {
    with_scratch(k + 1, |band| {
        end_band(degree, k, at_one, band);
        let first = if at_one { degree - k } else { 0 };
        for (i, &value) in band.iter().enumerate() {
            out[(row, first + i)] = value;
        }
    });
}

/// `D(t)` for derivatives `0..=order` of degree `degree`: the closed form at
/// `t = 0` and `t = 1`, A2.3 ([`bezier_basis_derivatives`]) elsewhere.
#[cfg(test)]
fn basis_rows(degree: usize, t: f64, order: usize) -> DMatrix<f64> {
    if degree > 0 && (t == 0.0 || t == 1.0) {
        let mut d = DMatrix::zeros(order + 1, degree + 1);
        for k in 0..=order.min(degree) {
            end_basis_row(degree, k, t == 1.0, &mut d, k);
        }
        d
    } else {
        bezier_basis_derivatives(degree, t, order)
    }
}

/// `P^(k)(t)` for `k = 0..=order` with a first-order rounding bound per row
/// (`gamma * |D| |P|`, `gamma = 2 (n + k + 2) u`), as a matrix
/// ([`derivatives_with_error_into`]).
pub(crate) fn derivatives_with_error(
    curve: &BezierCurve,
    t: f64,
    order: usize,
) -> (DMatrix<f64>, Vec<f64>) {
    let dim = curve.dim();
    let mut values = vec![0.0; (order + 1) * dim];
    let mut errors = vec![0.0; order + 1];
    derivatives_with_error_into(curve, t, order, &mut values, &mut errors);
    (DMatrix::from_row_slice(order + 1, dim, &values), errors)
}

/// `P^(k)(t)` for `k = 0..=order`, row-major into `values`
/// (`(order + 1) * dim`), and a first-order rounding bound of each row into
/// `errors` (`order + 1`); rows above the degree are exact zeros (bound 0).
///
/// * At `t = 0` and `t = 1`: `D(t)_k P` with the closed-form band of the row
///   ([`end_band`]), summed in ascending column order, bound
///   `gamma |D(t)_k| |P|` with `gamma = 2 (n + k + 2) u`.
/// * Elsewhere: the de Casteljau triangle ([`de_casteljau_jet_into`]).
///
/// These are the *targets* `P^(k)(u0)`, `Q^(k)(v0)` of the connect system,
/// values of the input curves; the solver's own rows (`D(0)`, `D(1)` and
/// `D(t_j)` of interior constraints) stay the closed form and A2.3.
/// Allocation-free while the scratch fits [`with_scratch`]'s stack buffers.
pub(crate) fn derivatives_with_error_into(
    curve: &BezierCurve,
    t: f64,
    order: usize,
    values: &mut [f64],
    errors: &mut [f64],
) {
    let n = curve.degree();
    let dim = curve.dim();
    let points = curve.points();
    assert_eq!(values.len(), (order + 1) * dim);
    assert_eq!(errors.len(), order + 1);
    if !(n > 0 && (t == 0.0 || t == 1.0)) {
        de_casteljau_jet_into(points, dim, n, t, order, values, errors);
        return;
    }
    if n < END_TABLE_SIZE {
        match dim {
            1 => return end_jet_small::<1>(points, n, t == 1.0, values, errors),
            2 => return end_jet_small::<2>(points, n, t == 1.0, values, errors),
            3 => return end_jet_small::<3>(points, n, t == 1.0, values, errors),
            4 => return end_jet_small::<4>(points, n, t == 1.0, values, errors),
            _ => {}
        }
    }
    end_jet_slices(points, dim, n, t == 1.0, order, values, errors);
}

/// [`derivatives_with_error_into`]'s values, bit for bit, with bounds that
/// are never below its bounds and cost no square root: the screen of
/// [`ends::connect_ends_curve`]. Where the jet comes from the de Casteljau
/// triangle in the plane or in space (`0 < t < 1`, degree below
/// [`SMALL_JET_POINTS`]) the sizes' triangle is skipped and row `k <=
/// min(order, n)` gets `2 u (3 n + k + 2) n!/(n-k)! 2^k sqrt(dim) scale`,
/// `scale >=` the largest absolute coordinate of a control point (its
/// [`BezierCurve::coordinate_scale`]): the sizes `a_i <= sqrt(dim) scale`,
/// the triangle's weights `|1 - t| + |t| = 1`, so `S_k = sum_j C(k, j)
/// a^(n-k)_j <= 2^k sqrt(dim) scale`, and `3 n + k + 2` is at least the
/// triangle's `3 (n - k) + k + 1` and the end bands' `n + k + 2`. Both
/// hold to first order; the screen's slack covers the rest. Elsewhere the
/// bounds of [`derivatives_with_error_into`] themselves.
pub(crate) fn derivatives_with_screen_into(
    curve: &BezierCurve,
    t: f64,
    order: usize,
    scale: f64,
    values: &mut [f64],
    errors: &mut [f64],
) {
    let n = curve.degree();
    let dim = curve.dim();
    if !(n > 0 && t > 0.0 && t < 1.0 && n < SMALL_JET_POINTS && (dim == 2 || dim == 3)) {
        derivatives_with_error_into(curve, t, order, values, errors);
        return;
    }
    assert_eq!(values.len(), (order + 1) * dim);
    assert_eq!(errors.len(), order + 1);
    let points = curve.points();
    let m = order.min(n);
    values[(m + 1) * dim..].fill(0.0);
    errors[m + 1..].fill(0.0);
    if dim == 2 {
        de_casteljau_jet_by_degree::<2, false>(points, n, t, m, values, errors);
    } else {
        de_casteljau_jet_by_degree::<3, false>(points, n, t, m, values, errors);
    }
    let size = (dim as f64).sqrt() * scale;
    let falling_row = &FALLING_FACTORIALS[n];
    let mut spread = 1.0f64;
    for (k, error) in errors[..=m].iter_mut().enumerate() {
        *error = 2.0 * unit_roundoff() * (3 * n + k + 2) as f64 * falling_row[k] * spread * size;
        spread *= 2.0;
    }
}

/// The end branch of [`derivatives_with_error_into`] (`n > 0`, `t = 0` or,
/// with `at_one`, `t = 1`) in dimension `D <= 4` and degree
/// `n <` [`END_TABLE_SIZE`]: row `k` is `sum_s b_s P_(first + s)` with the
/// band `b_s = n!/(n-k)! (-1)^(k-s) C(k, s)` of [`end_band`] (the same table
/// products), the accumulators in `[f64; D]` rows. The same operations in
/// the same order as [`end_jet_slices`], so the same values and bounds bit
/// for bit (unit test `small_end_jets_equal_the_slice_end_jets`), without
/// the scratch buffer and its zeroing. The orders are `0..errors.len()`.
fn end_jet_small<const D: usize>(
    points: &[f64],
    n: usize,
    at_one: bool,
    values: &mut [f64],
    errors: &mut [f64],
) {
    let falling_row = &FALLING_FACTORIALS[n];
    for (k, (value_row, error)) in values
        .chunks_exact_mut(D)
        .zip(errors.iter_mut())
        .enumerate()
    {
        let mut value = [0.0f64; D];
        let mut abs_row = [0.0f64; D];
        if k <= n {
            let falling = falling_row[k];
            let first = if at_one { n - k } else { 0 };
            let band_points = points[first * D..(first + k + 1) * D].chunks_exact(D);
            for (&c, point) in SIGNED_BINOMIALS[k][..=k].iter().zip(band_points) {
                let b = falling * c;
                for c in 0..D {
                    value[c] += b * point[c];
                    abs_row[c] += b.abs() * point[c].abs();
                }
            }
        }
        value_row.copy_from_slice(&value);
        let gamma = 2.0 * (n + k + 2) as f64 * unit_roundoff();
        let norm = abs_row.iter().map(|v| v * v).sum::<f64>().sqrt();
        *error = gamma * norm;
    }
}

/// The end branch of [`derivatives_with_error_into`] in any dimension and
/// degree, on scratch slices.
fn end_jet_slices(
    points: &[f64],
    dim: usize,
    n: usize,
    at_one: bool,
    order: usize,
    values: &mut [f64],
    errors: &mut [f64],
) {
    let t = if at_one { 1.0 } else { 0.0 };
    values.fill(0.0);
    with_scratch(n + 1 + dim, |buffer| {
        let (basis, abs_row) = buffer.split_at_mut(n + 1);
        for k in 0..=order {
            abs_row.fill(0.0);
            // The row's non-zero columns `first..first + len` and entries.
            let (first, row): (usize, &[f64]) = if k <= n {
                end_band(n, k, t == 1.0, &mut basis[..=k]);
                (if t == 1.0 { n - k } else { 0 }, &basis[..=k])
            } else {
                (0, &[])
            };
            let value = &mut values[k * dim..(k + 1) * dim];
            for (i, &b) in row.iter().enumerate() {
                let point = &points[(first + i) * dim..(first + i + 1) * dim];
                for c in 0..dim {
                    value[c] += b * point[c];
                    abs_row[c] += b.abs() * point[c].abs();
                }
            }
            let gamma = 2.0 * (n + k + 2) as f64 * unit_roundoff();
            let norm = abs_row.iter().map(|v| v * v).sum::<f64>().sqrt();
            errors[k] = gamma * norm;
        }
    });
}

/// The jet `P^(k)(t)`, `k = 0..=order`, of the Bezier curve with control
/// points `points` (degree `n`, dimension `dim`, row-major) from the de
/// Casteljau triangle: with `b^L_i` the points of level `L`
/// (`b^L_i = (1 - t) b^(L-1)_i + t b^(L-1)_(i+1)`),
/// `P^(k)(t) = n!/(n-k)! Delta^k b^(n-k)_0` (Farin, *Curves and Surfaces
/// for CAGD*, 5.5): `O(n^2 d)`, no basis matrix.
///
/// Bound of row `k` (first order, `u` the unit roundoff): with `a_i = |P_i|`
/// (Euclidean) and `a^L_i` the same triangle on the `a_i` with weights
/// `|1 - t|`, `|t|`, each level adds at most `3u` relative to `a^L` (the
/// rounding of `1 - t`, two products, one sum), each of the `k` difference
/// levels `u` relative to `S_k = sum_j C(k, j) a^(n-k)_j`, and the factor
/// `n!/(n-k)!` one more `u`, so
/// `|fl(P^(k)) - P^(k)| <= (3 (n - k) + k + 1) u n!/(n-k)! S_k`; the
/// Euclidean norm over the coordinates is at most that with the Euclidean
/// `a_i` (Minkowski). `errors[k]` is twice it, which also covers the
/// rounding of `S_k` itself (sums of non-negative terms). It is never below
/// the A2.3 bound's `|D(t)_k| |P|` term: `|B_i^(k)(t)| <= n!/(n-k)!
/// sum_j C(k, j) |B_(i-j)^(n-k)(t)|`.
pub(crate) fn de_casteljau_jet_into(
    points: &[f64],
    dim: usize,
    n: usize,
    t: f64,
    order: usize,
    values: &mut [f64],
    errors: &mut [f64],
) {
    if n >= SMALL_JET_POINTS || dim > 4 {
        de_casteljau_jet_slices(points, dim, n, t, order, values, errors);
        return;
    }
    let m = order.min(n);
    values[(m + 1) * dim..].fill(0.0);
    errors[m + 1..].fill(0.0);
    match dim {
        1 => de_casteljau_jet_small::<1, SMALL_JET_POINTS, false, true>(
            points, n, t, m, values, errors,
        ),
        2 => de_casteljau_jet_by_degree::<2, true>(points, n, t, m, values, errors),
        3 => de_casteljau_jet_by_degree::<3, true>(points, n, t, m, values, errors),
        _ => de_casteljau_jet_small::<4, SMALL_JET_POINTS, false, true>(
            points, n, t, m, values, errors,
        ),
    }
}

/// The values of [`de_casteljau_jet_into`] alone (orders `0..=m`, `m <=
/// n`, into `values[..(m + 1) * dim]`), the same operations on the
/// coordinates so the same bits, for dimensions 2 to 4 and degrees `1 <= n
/// <` [`SMALL_JET_POINTS`]: the homogeneous jets of rational spans
/// (`NurbsCurve::rational_spans_jet_into`), whose bounds are a priori.
pub(crate) fn de_casteljau_values_into(
    points: &[f64],
    dim: usize,
    n: usize,
    t: f64,
    m: usize,
    values: &mut [f64],
) {
    assert!((2..=4).contains(&dim) && (1..SMALL_JET_POINTS).contains(&n) && m <= n);
    let values = &mut values[..(m + 1) * dim];
    let mut unused = [0.0f64; SMALL_JET_POINTS];
    match dim {
        2 => de_casteljau_jet_by_degree::<2, false>(points, n, t, m, values, &mut unused),
        3 => de_casteljau_jet_by_degree::<3, false>(points, n, t, m, values, &mut unused),
        _ => de_casteljau_jet_by_degree::<4, false>(points, n, t, m, values, &mut unused),
    }
}

/// [`de_casteljau_jet_small`] with the degree a compile-time constant for
/// degrees 1 to 7 in dimension `D` (2 and 3, the plane and space): the
/// triangle's loops unrolled and sized exactly, the same operations. The
/// full jet (`m = n`, every order up to the degree: the connect's usual
/// case `kp >= deg P`) has the order a constant too, so that every loop of
/// the triangle and of the differences has constant bounds.
fn de_casteljau_jet_by_degree<const D: usize, const SIZES: bool>(
    points: &[f64],
    n: usize,
    t: f64,
    m: usize,
    values: &mut [f64],
    errors: &mut [f64],
) {
    macro_rules! by_order {
        ($n:literal) => {
            if m == $n {
                de_casteljau_jet_small::<D, { $n + 1 }, true, SIZES>(
                    points, $n, t, $n, values, errors,
                )
            } else {
                de_casteljau_jet_small::<D, { $n + 1 }, true, SIZES>(
                    points, $n, t, m, values, errors,
                )
            }
        };
    }
    match n {
        1 => by_order!(1),
        2 => by_order!(2),
        3 => by_order!(3),
        4 => by_order!(4),
        5 => by_order!(5),
        6 => by_order!(6),
        7 => by_order!(7),
        _ => de_casteljau_jet_small::<D, SMALL_JET_POINTS, false, SIZES>(
            points, n, t, m, values, errors,
        ),
    }
}

/// Control points up to which [`de_casteljau_jet_small`] works on the stack.
pub(crate) const SMALL_JET_POINTS: usize = 16;

/// [`de_casteljau_jet_into`] for dimension `D <= 4`, at most `CAP <=`
/// [`SMALL_JET_POINTS`] control points, in fixed arrays, orders `0..=m`:
/// the coordinates in `[f64; D]` rows, the sizes `a^L_i` beside them. The
/// same operations on every coordinate and size as
/// [`de_casteljau_jet_slices`] (the factor `n!/(n-k)!` from the table of
/// the same products), so the same values and bounds bit for bit (unit
/// test `small_jets_equal_the_slice_jets`). Without `SIZES` the values
/// alone (the same operations on the coordinates) and `errors` untouched:
/// [`derivatives_with_screen_into`] bounds them a priori.
#[inline(always)]
fn de_casteljau_jet_small<
    const D: usize,
    const CAP: usize,
    const UNROLL: bool,
    const SIZES: bool,
>(
    points: &[f64],
    n: usize,
    t: f64,
    m: usize,
    values: &mut [f64],
    errors: &mut [f64],
) {
    // With `UNROLL` (the degree `n` a constant, `CAP = n + 1`) every inner
    // loop runs over `0..n` with a test instead of a bound that depends on
    // the outer index, so that all bounds are constants and the loops
    // unroll; the slots that pass the test get the operations of the tight
    // loops (the bound `upto(x)` is `x` without `UNROLL`, where the tests
    // always pass).
    let upto = |x: usize| if UNROLL { n } else { x };
    // Level 0: the control points and their sizes (unused slots zero).
    let mut level = [[0.0f64; D]; CAP];
    let mut size = [0.0f64; CAP];
    for ((slot, a), point) in level
        .iter_mut()
        .zip(size.iter_mut())
        .zip(points.chunks_exact(D))
        .take(n + 1)
    {
        slot.copy_from_slice(point);
        if SIZES {
            *a = point.iter().map(|v| v * v).sum::<f64>().sqrt();
        }
    }
    let s = 1.0 - t;
    let (s_abs, t_abs) = (s.abs(), t.abs());
    let gamma_unit = 2.0 * unit_roundoff();
    let falling_row = &FALLING_FACTORIALS[n];
    // Delta^k of b^l_0..b^l_k: the first pass reads the level (x_(i+1) -
    // x_i, sizes a_i + a_(i+1)), the others work in place, as the slice
    // code's passes on its copy of the level.
    let mut work = [[0.0f64; D]; CAP];
    let mut work_size = [0.0f64; CAP];
    for l in 0..=n {
        if l > 0 {
            for i in 0..upto(n - l + 1) {
                if i + l <= n {
                    let next = level[i + 1];
                    let here = &mut level[i];
                    for c in 0..D {
                        here[c] = s * here[c] + t * next[c];
                    }
                    if SIZES {
                        size[i] = s_abs * size[i] + t_abs * size[i + 1];
                    }
                }
            }
        }
        let k = n - l;
        if k > m {
            continue;
        }
        let (difference, difference_size) = if k == 0 {
            (level[0], size[0])
        } else {
            for i in 0..upto(k) {
                if i < k {
                    let (here, next) = (level[i], level[i + 1]);
                    for c in 0..D {
                        work[i][c] = next[c] - here[c];
                    }
                    if SIZES {
                        work_size[i] = size[i] + size[i + 1];
                    }
                }
            }
            for pass in 1..upto(k) {
                if pass < k {
                    for i in 0..upto(k - pass) {
                        if i + pass < k {
                            let next = work[i + 1];
                            let here = &mut work[i];
                            for c in 0..D {
                                here[c] = next[c] - here[c];
                            }
                            if SIZES {
                                work_size[i] += work_size[i + 1];
                            }
                        }
                    }
                }
            }
            (work[0], work_size[0])
        };
        let falling = falling_row[k];
        for (v, w) in values[k * D..(k + 1) * D].iter_mut().zip(difference) {
            *v = falling * w;
        }
        if SIZES {
            errors[k] = gamma_unit * (3 * (n - k) + k + 1) as f64 * falling * difference_size;
        }
    }
}

/// `n!/(n-k)!` as the product `n (n-1) ... (n-k+1)` in that order.
fn falling_factorial(n: usize, k: usize) -> f64 {
    let mut falling = 1.0f64;
    for j in 0..k {
        falling *= (n - j) as f64;
    }
    falling
}

/// [`de_casteljau_jet_into`] in slices of any length.
fn de_casteljau_jet_slices(
    points: &[f64],
    dim: usize,
    n: usize,
    t: f64,
    order: usize,
    values: &mut [f64],
    errors: &mut [f64],
) {
    let m = order.min(n);
    values[(m + 1) * dim..].fill(0.0);
    errors[m + 1..].fill(0.0);
    let width = dim + 1;
    with_scratch(2 * (n + 1) * width, |buffer| {
        // Level L of the triangle, point i at level[i * width..], its
        // coordinates then its size a^L_i; `work` for the differences.
        let (level, work) = buffer.split_at_mut((n + 1) * width);
        for i in 0..=n {
            let point = &points[i * dim..(i + 1) * dim];
            let slot = &mut level[i * width..(i + 1) * width];
            slot[..dim].copy_from_slice(point);
            slot[dim] = point.iter().map(|v| v * v).sum::<f64>().sqrt();
        }
        let s = 1.0 - t;
        let (s_abs, t_abs) = (s.abs(), t.abs());
        let gamma_unit = 2.0 * unit_roundoff();
        for l in 0..=n {
            if l > 0 {
                for i in 0..=n - l {
                    let (here, next) = level[i * width..(i + 2) * width].split_at_mut(width);
                    for c in 0..dim {
                        here[c] = s * here[c] + t * next[c];
                    }
                    here[dim] = s_abs * here[dim] + t_abs * next[dim];
                }
            }
            let k = n - l;
            if k > m {
                continue;
            }
            // Delta^k of b^l_0..b^l_k (and the binomial sums of the sizes).
            let work = &mut work[..(k + 1) * width];
            work.copy_from_slice(&level[..(k + 1) * width]);
            for pass in 0..k {
                for i in 0..k - pass {
                    for c in 0..dim {
                        work[i * width + c] = work[(i + 1) * width + c] - work[i * width + c];
                    }
                    work[i * width + dim] += work[(i + 1) * width + dim];
                }
            }
            let falling = falling_factorial(n, k);
            for c in 0..dim {
                values[k * dim + c] = falling * work[c];
            }
            errors[k] = gamma_unit * (3 * (n - k) + k + 1) as f64 * falling * work[dim];
        }
    });
}

/// The checks of the curves and parameters, first in [`prepare`]: equal
/// dimensions, `u0` in P's domain, `v0` in Q's. Returns the dimension.
pub(crate) fn check_pair<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
) -> Result<usize> {
    let dim = p.dim();
    if q.dim() != dim {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: dim,
            actual: q.dim(),
        });
    }
    p.check_parameter("u0", u0)?;
    q.check_parameter("v0", v0)?;
    Ok(dim)
}

/// Validate the inputs (everything except the scales) and evaluate the end data.
pub(crate) fn prepare<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &ConnectOptions,
) -> Result<Problem> {
    let dim = check_pair(p, u0, q, v0)?;
    let mut constraints: Vec<(f64, DMatrix<f64>)> = Vec::with_capacity(options.constraints.len());
    let data_scale = p.coordinate_scale().max(q.coordinate_scale());
    for (j, c) in options.constraints.iter().enumerate() {
        check_open_range(&format!("constraints[{j}].t"), c.t, 0.0, 1.0)?;
        let name = format!("constraints[{j}].values");
        let rows = c.max_order.checked_add(1).ok_or_else(|| {
            BezjoinError::invalid(format!("constraints[{j}].max_order"), "is too large")
        })?;
        let expected = rows.checked_mul(dim).ok_or_else(|| {
            BezjoinError::invalid(format!("constraints[{j}].max_order"), "is too large")
        })?;
        if c.values.len() != expected {
            return Err(BezjoinError::LengthMismatch {
                name,
                expected,
                actual: c.values.len(),
            });
        }
        check_finite(&name, &c.values)?;
        let values = DMatrix::from_row_slice(rows, dim, &c.values);
        if let Some(i) = options.constraints[..j].iter().position(|o| o.t == c.t) {
            return Err(BezjoinError::invalid(
                format!("constraints[{j}].t"),
                format!(
                    "{} repeats constraints[{i}].t; constraint parameters must be distinct",
                    c.t
                ),
            ));
        }
        constraints.push((c.t, values));
    }
    let degree = check_connect_degree(
        options.p_order,
        options.q_order,
        options.constraints.iter().map(|c| c.max_order),
    )?;
    constraints.sort_by(|a, b| a.0.total_cmp(&b.0));
    // P arrives at u0 (its derivatives from the left of a knot), Q leaves
    // v0 (from the right): docs/mathematics.md#nurbs-curves.
    let (p_derivatives, p_derivative_error) = p.jet(u0, options.p_order, KnotSide::Left);
    let (q_derivatives, q_derivative_error) = q.jet(v0, options.q_order, KnotSide::Right);
    Ok(Problem {
        dim,
        degree,
        p_order: options.p_order,
        q_order: options.q_order,
        p_derivatives,
        p_derivative_error,
        q_derivatives,
        q_derivative_error,
        constraints,
        data_scale,
    })
}

/// The basis rows of every condition, in the order P end (k = 0..kp), Q end
/// (k = 0..kq), constraints (sorted by t, k = 0..K_j), with their targets and
/// the targets' rounding bounds.
#[derive(Clone)]
pub(crate) struct ConditionRows {
    pub(crate) rows: DMatrix<f64>,
    pub(crate) targets: DMatrix<f64>,
    pub(crate) target_errors: Vec<f64>,
}

pub(crate) fn condition_rows(problem: &Problem, alpha: f64, beta: f64) -> ConditionRows {
    let n = problem.degree;
    let count = n + 1;
    let dim = problem.dim;
    let mut rows = DMatrix::zeros(count, n + 1);
    let mut targets = DMatrix::zeros(count, dim);
    let mut target_errors = Vec::with_capacity(count);
    let mut r = 0;
    // End rows: D(0) rows 0..=kp and D(1) rows 0..=kq by the closed form.
    for (derivatives, errors, order, scale, at_one) in [
        (
            &problem.p_derivatives,
            &problem.p_derivative_error,
            problem.p_order,
            alpha,
            false,
        ),
        (
            &problem.q_derivatives,
            &problem.q_derivative_error,
            problem.q_order,
            beta,
            true,
        ),
    ] {
        let mut factor = 1.0f64;
        for k in 0..=order {
            end_basis_row(n, k, at_one, &mut rows, r);
            let mut square = 0.0;
            for c in 0..dim {
                let v = derivatives[(k, c)] * factor;
                targets[(r, c)] = v;
                square += v * v;
            }
            // alpha^k as powi forms it ([`power`]), as the bound is stated.
            let error =
                power(scale, k) * errors[k] + (k + 1) as f64 * unit_roundoff() * square.sqrt();
            target_errors.push(error);
            factor *= scale;
            r += 1;
        }
    }
    // Interior rows: D(t_j) from A2.3.
    for (t, values) in &problem.constraints {
        let dt = bezier_basis_derivatives(n, *t, values.nrows() - 1);
        for k in 0..values.nrows() {
            for i in 0..=n {
                rows[(r, i)] = dt[(k, i)];
            }
            for c in 0..dim {
                targets[(r, c)] = values[(k, c)];
            }
            target_errors.push(0.0);
            r += 1;
        }
    }
    ConditionRows {
        rows,
        targets,
        target_errors,
    }
}

/// Check every condition on the computed control points `points`
/// (`(n+1) x dim`): the worst floating-point relative residual and the bound
/// on the worst exact one.
///
/// The data scale `S` is the largest of the given positions' scale and
/// `|T_k| / ||D_k||_1` over all conditions. Allocation-free: one pass for
/// `S`, one for the residuals (`n + 1 <= 32` rows by [`MAX_CONNECT_DEGREE`]).
pub(crate) fn check_residuals(
    problem: &Problem,
    conditions: &ConditionRows,
    points: &DMatrix<f64>,
) -> (f64, f64) {
    let n = problem.degree;
    let rows = &conditions.rows;
    let targets = &conditions.targets;
    let count = rows.nrows();
    let dim = problem.dim;
    let mut row_norms = [0.0f64; MAX_CONNECT_DEGREE + 1];
    let mut data_scale = problem.data_scale;
    for (r, norm) in row_norms.iter_mut().enumerate().take(count) {
        *norm = rows.row(r).iter().map(|v| v.abs()).sum();
        let v = targets.row(r).norm() / *norm;
        if v.is_finite() {
            data_scale = data_scale.max(v);
        }
    }
    // Rounding of D_k R (dot products of length n + 1, basis entries with a
    // relative error of a few units per order) and of the target.
    let gamma = 2.0 * (2 * n + 4) as f64 * unit_roundoff();
    let mut worst = 0.0f64;
    let mut worst_bound = 0.0f64;
    for (r, row_norm) in row_norms.iter().enumerate().take(count) {
        let target = targets.row(r);
        let denominator = target.norm().max(data_scale * row_norm);
        let mut difference_square = 0.0;
        let mut abs_square = 0.0;
        for c in 0..dim {
            let mut value = 0.0;
            let mut abs_value = 0.0;
            for i in 0..=n {
                let b = rows[(r, i)];
                let x = points[(i, c)];
                value += b * x;
                abs_value += b.abs() * x.abs();
            }
            let difference = value - target[c];
            difference_square += difference * difference;
            abs_square += abs_value * abs_value;
        }
        let (residual, bound) = residual_and_bound(
            difference_square,
            abs_square,
            gamma,
            conditions.target_errors[r],
            denominator,
        );
        worst = worst.max(residual);
        worst_bound = worst_bound.max(bound);
    }
    (worst, worst_bound)
}

/// Turn solved control points into a checked [`Connection`], or refuse.
pub(crate) fn finish(
    problem: &Problem,
    conditions: &ConditionRows,
    points: DMatrix<f64>,
    alpha: f64,
    beta: f64,
    constraint_condition: f64,
    what: &str,
) -> Result<Connection> {
    let (max_residual, error_estimate) = check_residuals(problem, conditions, &points);
    let trusted = error_estimate.is_finite() && error_estimate <= CONNECT_RESIDUAL_LIMIT;
    if !trusted || points.iter().any(|v| !v.is_finite()) {
        return Err(BezjoinError::IllConditioned {
            what: format!("{what} (degree {})", problem.degree),
            estimate: error_estimate,
            limit: CONNECT_RESIDUAL_LIMIT,
        });
    }
    Ok(Connection {
        curve: BezierCurve::from_matrix(&points)?,
        p_scale: alpha,
        q_scale: beta,
        max_residual,
        error_estimate,
        constraint_condition,
    })
}

/// The structured solve for given scales on a validated problem.
pub(crate) fn solve_structured(problem: &Problem, alpha: f64, beta: f64) -> Result<Connection> {
    let (conditions, points, constraint_condition) = structured_points(problem, alpha, beta)?;
    finish(
        problem,
        &conditions,
        points,
        alpha,
        beta,
        constraint_condition,
        "connect",
    )
}

/// The structured solve without the final accuracy check.
pub(crate) fn structured_points(
    problem: &Problem,
    alpha: f64,
    beta: f64,
) -> Result<(ConditionRows, DMatrix<f64>, f64)> {
    let conditions = condition_rows(problem, alpha, beta);
    let (points, constraint_condition) = solve_condition_rows(problem, &conditions)?;
    Ok((conditions, points, constraint_condition))
}

/// The control points that meet `conditions` (end bands by the triangular
/// solves, then the interior block), and the interior block's condition
/// estimate (1 without interior constraints). Linear in the targets.
pub(crate) fn solve_condition_rows(
    problem: &Problem,
    conditions: &ConditionRows,
) -> Result<(DMatrix<f64>, f64)> {
    let n = problem.degree;
    let kp = problem.p_order;
    let kq = problem.q_order;
    let dim = problem.dim;
    let rows = &conditions.rows;
    let targets = &conditions.targets;
    let mut points = DMatrix::<f64>::zeros(n + 1, dim);
    // Each row divided by its diagonal entry first: `R_k = T_k / b_k -
    // sum_s (b_s / b_k) R_s` with `b_s / b_k = +-C(k, s)` exact integers
    // (SIGNED_BINOMIALS), so the divisions depend on no solved point and
    // the chain from row to row is products (docs/mathematics.md,
    // "Connect: the structured solve"). The end path, the screen and the
    // G^k trials do the same operations.
    // P end: row k of D(0) touches R_0..R_k only (lower triangular).
    for k in 0..=kp {
        let diagonal = rows[(k, k)];
        let signed = &SIGNED_BINOMIALS[k];
        for c in 0..dim {
            let mut x = targets[(k, c)] / diagonal;
            for i in 0..k {
                x -= signed[i] * signed[k] * points[(i, c)];
            }
            points[(k, c)] = x;
        }
    }
    // Q end: row k of D(1) touches R_(n-k)..R_n only (anti-triangular);
    // column `index + s` is band slot `s`.
    for (k, signed) in SIGNED_BINOMIALS[..=kq].iter().enumerate() {
        let r = kp + 1 + k;
        let index = n - k;
        let diagonal = rows[(r, index)];
        for c in 0..dim {
            let mut x = targets[(r, c)] / diagonal;
            for i in index + 1..=n {
                x -= signed[i - index] * signed[0] * points[(i, c)];
            }
            points[(index, c)] = x;
        }
    }
    // Interior constraints: M x M for R_(kp+1)..R_(kp+M), known points moved
    // to the right-hand side, rows scaled to unit 1-norm.
    let m = problem.middle_count();
    let constraint_condition = if m > 0 {
        solve_interior(conditions, &mut points, kp, kq, m)?
    } else {
        1.0
    };
    Ok((points, constraint_condition))
}

/// The interior constraints' `m x m` block for the points `R_(kp+1) ..
/// R_(kp+m)`, the known points (both ends) moved to the right-hand side,
/// rows scaled to unit 1-norm, solved into `points`; returns the block's
/// condition estimate.
pub(crate) fn solve_interior(
    conditions: &ConditionRows,
    points: &mut DMatrix<f64>,
    kp: usize,
    kq: usize,
    m: usize,
) -> Result<f64> {
    let (rows, targets) = (&conditions.rows, &conditions.targets);
    let n = points.nrows() - 1;
    let dim = points.ncols();
    let first = kp + 1;
    let start = kp + kq + 2;
    let mut a = DMatrix::<f64>::zeros(m, m);
    let mut b = DMatrix::<f64>::zeros(m, dim);
    for i in 0..m {
        let row = rows.row(start + i);
        let norm: f64 = row.iter().map(|v| v.abs()).sum();
        for j in 0..m {
            a[(i, j)] = row[first + j] / norm;
        }
        for c in 0..dim {
            let mut sum = targets[(start + i, c)];
            for j in (0..first).chain(first + m..=n) {
                sum -= row[j] * points[(j, c)];
            }
            b[(i, c)] = sum / norm;
        }
    }
    let solution = solve_checked(&a, &b, "connect: interior constraints")?;
    points.rows_mut(first, m).copy_from(&solution.x);
    Ok(solution.condition)
}

/// The curve `R` connecting `P` at `u0` to `Q` at `v0` with C^k continuity
/// (1') and the interior constraints (2) (docs/mathematics.md#connect;
/// Krivosheev, Mavrin, Starkova 2025, Theorems 1 and 2), by the structured
/// solve.
///
/// The degree of the result is `kp + kq + 1 + sum (K_j + 1)`.
///
/// `P` and `Q` are any curves ([`BezierCurve`], [`NurbsCurve`](crate::NurbsCurve),
/// [`Curve`](crate::Curve)): only their derivative jets are used, P's from
/// the left of `u0` and Q's from the right of `v0` (at a knot of a NURBS
/// curve; docs/mathematics.md#nurbs-curves). The orders `kp`, `kq` may exceed the
/// degrees: derivatives above a polynomial's degree are 0, a rational
/// curve (a circle) has derivatives of every order.
///
/// # Guarantee
/// The returned curve satisfies (1') and (2) with a worst relative residual
/// (module documentation) of at most [`CONNECT_RESIDUAL_LIMIT`], as bounded
/// by [`Connection::error_estimate`]; otherwise the call fails with
/// `IllConditioned` carrying the estimate.
///
/// # Errors
/// * `DimensionMismatch` (`q`) when `P` and `Q` have different dimensions;
/// * `ParameterOutOfRange` / `NonFinite` for `u0`, `v0` outside the
///   curve's domain (`[0, 1]` for a Bezier curve), given `p_scale`,
///   `q_scale` not `> 0`, `constraints[j].t` outside `(0, 1)`;
/// * `InvalidArgument` for a repeated `constraints[j].t` or an empty
///   `constraints[j].max_order` so large that `(K + 1) * dim` overflows;
/// * `LengthMismatch` / `NonFinite` for `constraints[j].values`;
/// * `Singular` if the interior block is singular (it is not in exact
///   arithmetic: Hermite interpolation at distinct points is unisolvent);
/// * `IllConditioned` when the accuracy cannot be guaranteed or the degree
///   exceeds [`MAX_CONNECT_DEGREE`].
///
/// ```
/// use bezjoin_core::BezierCurve;
/// use bezjoin_core::{ConnectOptions, connect};
/// let p = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]]).unwrap();
/// let q = BezierCurve::from_rows(&[[5.0, 0.0], [6.0, 2.0], [7.0, 0.0], [8.0, 1.0]]).unwrap();
/// let joined = connect(&p, 1.0, &q, 0.0, &ConnectOptions::new(3, 3)).unwrap();
/// assert_eq!(joined.curve.degree(), 7);
/// assert!(joined.max_residual < 1e-12);
/// ```
pub fn connect<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &ConnectOptions,
) -> Result<Connection> {
    if let Some((kp, kq, alpha, beta)) = end_path_case(p, u0, q, v0, options)? {
        return ends::connect_ends(p, u0, q, v0, kp, kq, alpha, beta);
    }
    let problem = prepare(p, u0, q, v0, options)?;
    match options.scale.checked()? {
        Some((alpha, beta)) => solve_structured(&problem, alpha, beta),
        None if options.scale == ShapeScale::Balanced => energy::balanced_scale(&problem),
        None => energy::auto_scale(&problem),
    }
}

/// [`connect`]'s curve alone: the same control points bit for bit, the same
/// errors in the same order, the same guarantee (every condition to a
/// relative residual of [`CONNECT_RESIDUAL_LIMIT`] in exact arithmetic on
/// the returned points, or [`BezjoinError::IllConditioned`] with the full
/// check's estimate). For given scales and no interior constraints it
/// screens the answer with bounds that are never below the full check's
/// (norms by 1-norms above and largest coordinates below, the jets'
/// rounding a priori: no square root, no division but the substitution's;
/// magnitudes between `1e-140` and `1e140`, where the full check's squares
/// are normal numbers) and runs the full check only when the screen does
/// not pass; everything else is
/// `connect(...)?.curve`. `bzj_connect`'s path: it returns no estimate.
pub fn connect_curve<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &ConnectOptions,
) -> Result<BezierCurve> {
    if let Some((kp, kq, alpha, beta)) = end_path_case(p, u0, q, v0, options)? {
        return ends::connect_ends_curve(p, u0, q, v0, kp, kq, alpha, beta);
    }
    connect(p, u0, q, v0, options).map(|connection| connection.curve)
}

/// Whether [`connect`] takes the end path (no interior constraints, given
/// scales): then `Some((kp, kq, alpha, beta))` after the checks of
/// [`prepare`] in its order and the scales' (the same errors as the general
/// path); `None` for the general path, which checks again.
fn end_path_case<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &ConnectOptions,
) -> Result<Option<(usize, usize, f64, f64)>> {
    if !options.constraints.is_empty() {
        return Ok(None);
    }
    check_pair(p, u0, q, v0)?;
    check_connect_degree(options.p_order, options.q_order, [])?;
    let (kp, kq) = (options.p_order, options.q_order);
    Ok(options
        .scale
        .checked()?
        .map(|(alpha, beta)| (kp, kq, alpha, beta)))
}

/// [`connect`] without the accuracy refusal: the answer is returned even when
/// its [`Connection::error_estimate`] exceeds [`CONNECT_RESIDUAL_LIMIT`]
/// (input errors and a singular interior block are still errors). Given
/// scales only: [`ShapeScale::Auto`] is `InvalidArgument` (`scale`).
///
/// For measurements (the accuracy table in docs/accuracy.md) and for callers
/// that apply their own acceptance test to `error_estimate`; prefer
/// [`connect`], whose answers carry the guarantee.
pub fn connect_unchecked<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &ConnectOptions,
) -> Result<Connection> {
    let problem = prepare(p, u0, q, v0, options)?;
    let (alpha, beta) = options.scale.checked()?.ok_or_else(|| {
        BezjoinError::invalid(
            "scale",
            "connect_unchecked takes given scales, not Auto or Balanced",
        )
    })?;
    let (conditions, points, constraint_condition) = structured_points(&problem, alpha, beta)?;
    let (max_residual, error_estimate) = check_residuals(&problem, &conditions, &points);
    // Residuals that overflow (coordinates near the top of the f64 range
    // against tiny scales) leave no estimate at all: refuse rather than
    // return an infinite one.
    if !error_estimate.is_finite() || !max_residual.is_finite() {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "connect (unchecked, degree {}): the residuals overflow f64",
                problem.degree
            ),
            estimate: error_estimate,
            limit: CONNECT_RESIDUAL_LIMIT,
        });
    }
    Ok(Connection {
        curve: BezierCurve::from_matrix(&points)?,
        p_scale: alpha,
        q_scale: beta,
        max_residual,
        error_estimate,
        constraint_condition,
    })
}

/// One end condition's relative residual `sqrt(difference_square) /
/// denominator` and its bound with the rounding of the row product
/// (`gamma * sqrt(abs_square)`) and of the target (`target_error`); both
/// infinite when either is not finite. Shared by the general residual check
/// and the end-condition fast path (`ends.rs`), so both judge alike.
#[inline]
pub(super) fn residual_and_bound(
    difference_square: f64,
    abs_square: f64,
    gamma: f64,
    target_error: f64,
    denominator: f64,
) -> (f64, f64) {
    finite_or_infinite(residual_and_bound_unguarded(
        difference_square,
        abs_square,
        gamma,
        target_error,
        denominator,
    ))
}

/// The two formulas of [`residual_and_bound`] without its guard (no
/// branch: the end path runs them over all rows side by side).
#[inline(always)]
pub(super) fn residual_and_bound_unguarded(
    difference_square: f64,
    abs_square: f64,
    gamma: f64,
    target_error: f64,
    denominator: f64,
) -> (f64, f64) {
    let residual = difference_square.sqrt() / denominator;
    let bound = residual + (gamma * abs_square.sqrt() + target_error) / denominator;
    (residual, bound)
}

/// The guard of [`residual_and_bound`]: both infinite when either is not
/// finite.
#[inline(always)]
pub(super) fn finite_or_infinite((residual, bound): (f64, f64)) -> (f64, f64) {
    if residual.is_finite() && bound.is_finite() {
        (residual, bound)
    } else {
        (f64::INFINITY, f64::INFINITY)
    }
}

/// Two routes to one answer agree bit for bit: the same control points,
/// residual and estimate (`true`), or the same error message (`false`);
/// a panic naming `label` otherwise.
#[cfg(test)]
pub(crate) fn assert_same_answer(
    label: &str,
    a: std::result::Result<(Vec<f64>, f64, f64), &BezjoinError>,
    b: std::result::Result<(Vec<f64>, f64, f64), &BezjoinError>,
) -> bool {
    match (a, b) {
        (Ok((pa, ra, ea)), Ok((pb, rb, eb))) => {
            assert_eq!(pa, pb, "{label}");
            assert_eq!(ra.to_bits(), rb.to_bits(), "{label}");
            assert_eq!(ea.to_bits(), eb.to_bits(), "{label}");
            true
        }
        (Err(a), Err(b)) => {
            assert_eq!(a.to_string(), b.to_string(), "{label}");
            false
        }
        (a, b) => panic!("{label}: paths disagree: {a:?} / {b:?}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic(offset: f64) -> BezierCurve {
        BezierCurve::from_rows(&[
            [offset, 0.0],
            [offset + 1.0, 1.0],
            [offset + 2.0, -1.0],
            [offset + 3.0, 0.5],
        ])
        .unwrap()
    }

    #[test]
    fn error_messages_name_the_argument() {
        let p = cubic(0.0);
        let q = cubic(5.0);
        let err = |u0: f64, v0: f64, o: ConnectOptions| {
            connect(&p, u0, &q, v0, &o).unwrap_err().to_string()
        };
        assert_eq!(
            err(1.5, 0.0, ConnectOptions::new(1, 1)),
            "u0 = 1.5 is outside [0, 1]"
        );
        assert!(err(1.0, -0.5, ConnectOptions::new(1, 1)).starts_with("v0 = -0.5"));
        // Orders above the degree are allowed (docs/mathematics.md#nurbs-curves):
        // a cubic's 4th derivative is 0, and the result matches it.
        let above = connect(&p, 1.0, &q, 0.0, &ConnectOptions::new(4, 1)).unwrap();
        let fourth = above.curve.eval_derivatives(0.0, 4);
        assert!(fourth[8..10].iter().all(|x| x.abs() < 1e-9), "{fourth:?}");
        assert!(
            err(1.0, 0.0, ConnectOptions::new(1, 1).with_scales(0.0, 1.0))
                .starts_with("p_scale = 0")
        );
        assert!(
            err(1.0, 0.0, ConnectOptions::new(1, 1).with_scales(1.0, -1.0))
                .starts_with("q_scale = -1")
        );
        let c = |t: f64| PointConstraint::new(t, 0, vec![1.0, 2.0]);
        assert!(
            err(1.0, 0.0, ConnectOptions::new(1, 1).with_constraint(c(1.0)))
                .starts_with("constraints[0].t = 1")
        );
        // t <= 0: the end itself and outside; the second constraint is named.
        for t in [0.0, -0.25] {
            let o = ConnectOptions::new(1, 1)
                .with_constraint(c(0.5))
                .with_constraint(c(t));
            let e = connect(&p, 1.0, &q, 0.0, &o).unwrap_err();
            assert!(
                matches!(e, BezjoinError::ParameterOutOfRange { .. }),
                "t = {t}: {e:?}"
            );
            assert_eq!(
                e.to_string(),
                format!("constraints[1].t = {t} is outside (0, 1)")
            );
        }
        // An empty value list (no position) is refused, naming it.
        let o = ConnectOptions::new(1, 1).with_constraint(PointConstraint::new(0.5, 0, Vec::new()));
        let e = connect(&p, 1.0, &q, 0.0, &o).unwrap_err();
        assert!(matches!(e, BezjoinError::LengthMismatch { .. }), "{e:?}");
        assert_eq!(
            e.to_string(),
            "constraints[0].values has 0 values, expected 2"
        );
        let o = ConnectOptions::new(1, 1)
            .with_constraint(c(0.5))
            .with_constraint(c(0.5));
        assert!(err(1.0, 0.0, o).starts_with("constraints[1].t"));
        let o = ConnectOptions::new(1, 1).with_constraint(PointConstraint::new(
            0.5,
            1,
            vec![1.0, 2.0, 1.0],
        ));
        assert_eq!(
            err(1.0, 0.0, o),
            "constraints[0].values has 3 values, expected 4"
        );
        let o = ConnectOptions::new(1, 1).with_constraint(PointConstraint::new(
            0.5,
            0,
            vec![1.0, f64::NAN],
        ));
        assert!(err(1.0, 0.0, o).starts_with("constraints[0].values[1] = NaN"));
        let o = ConnectOptions::new(1, 1).with_constraint(PointConstraint::new(
            0.5,
            usize::MAX,
            vec![1.0, 2.0],
        ));
        assert_eq!(err(1.0, 0.0, o), "constraints[0].max_order: is too large");
        let q3 = BezierCurve::from_rows(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]).unwrap();
        assert!(matches!(
            connect(&p, 1.0, &q3, 0.0, &ConnectOptions::new(1, 1)),
            Err(BezjoinError::DimensionMismatch { .. })
        ));
    }

    #[test]
    fn closed_form_end_rows_equal_a23() {
        for n in 1..=MAX_CONNECT_DEGREE {
            for (t, at_one) in [(0.0, false), (1.0, true)] {
                let reference = bezier_basis_derivatives(n, t, n);
                let mut closed = DMatrix::zeros(n + 1, n + 1);
                for k in 0..=n {
                    end_basis_row(n, k, at_one, &mut closed, k);
                }
                assert_eq!(closed, basis_rows(n, t, n));
                for k in 0..=n {
                    let scale: f64 = reference.row(k).iter().map(|v| v.abs()).sum();
                    for i in 0..=n {
                        let (a, b) = (closed[(k, i)], reference[(k, i)]);
                        assert!(
                            (a - b).abs() <= 1e-14 * scale,
                            "n={n} t={t} k={k} i={i}: closed {a} vs A2.3 {b}"
                        );
                        // Exact zeros: D(0) is lower triangular, D(1) anti-triangular.
                        if (!at_one && i > k) || (at_one && i + k < n) {
                            assert_eq!(a, 0.0);
                        }
                    }
                }
            }
        }
    }

    /// `derivatives_with_error_into` at `t = 0`, `1`: the closed-form band
    /// times the control points, in ascending column order, with the bound
    /// `gamma |D| |P|`, bit for bit. Elsewhere (the de Casteljau triangle,
    /// inside and outside `[0, 1]`): within its bound of the exact jet
    /// (exact rational arithmetic on the same f64 inputs), and within the
    /// sum of both bounds of the A2.3 products. Degrees 0..=9, dimensions
    /// 1..=4, orders up to 11 (above the degree too), stack and heap buffers.
    #[test]
    #[allow(clippy::needless_range_loop)]
    fn jets_in_place_are_within_their_bounds() {
        use num_rational::BigRational;
        use num_traits::ToPrimitive;
        let exact = |x: f64| BigRational::from_float(x).expect("finite");
        for n in 0..=9 {
            for dim in 1..=4 {
                let points: Vec<f64> = (0..(n + 1) * dim)
                    .map(|i| ((i * 7919) % 97) as f64 / 9.7 - 5.0)
                    .collect();
                let curve = BezierCurve::new(dim, n, points).unwrap();
                for t in [0.0, 1.0, 0.3, 0.5, 0.77, 1e-9, -0.2, 1.4] {
                    // The exact jet: de Casteljau in rationals, then n!/(n-k)! Delta^k.
                    let exact_jet = crate::test_values::exact_bezier_jet(
                        curve.points(),
                        dim,
                        n,
                        (0.0, 1.0, t),
                        n,
                    );
                    for order in [0, 1, 2, 3, n, n + 2] {
                        let d = basis_rows(n, t, order);
                        let (values, errors) = derivatives_with_error(&curve, t, order);
                        let at_end = n > 0 && (t == 0.0 || t == 1.0);
                        for k in 0..=order {
                            let mut value = vec![0.0; dim];
                            let mut abs = vec![0.0; dim];
                            for i in 0..=n {
                                let b = d[(k, i)];
                                if b != 0.0 {
                                    for c in 0..dim {
                                        value[c] += b * curve.point(i)[c];
                                        abs[c] += b.abs() * curve.point(i)[c].abs();
                                    }
                                }
                            }
                            let gamma = 2.0 * (n + k + 2) as f64 * unit_roundoff();
                            let a23_bound = gamma * abs.iter().map(|v| v * v).sum::<f64>().sqrt();
                            if at_end {
                                for c in 0..dim {
                                    assert_eq!(values[(k, c)], value[c], "n {n} t {t} k {k}");
                                }
                                assert_eq!(errors[k], a23_bound, "n {n} dim {dim} t {t} k {k}");
                                continue;
                            }
                            if k > n {
                                assert!((0..dim).all(|c| values[(k, c)] == 0.0));
                                assert_eq!(errors[k], 0.0);
                                continue;
                            }
                            let miss = (0..dim)
                                .map(|c| {
                                    (exact(values[(k, c)]) - &exact_jet[k][c])
                                        .to_f64()
                                        .unwrap()
                                        .powi(2)
                                })
                                .sum::<f64>()
                                .sqrt();
                            assert!(
                                miss <= errors[k],
                                "n {n} dim {dim} t {t} k {k}: miss {miss:e} above bound {:e}",
                                errors[k]
                            );
                            let gap = (0..dim)
                                .map(|c| (values[(k, c)] - value[c]).powi(2))
                                .sum::<f64>()
                                .sqrt();
                            assert!(gap <= 1.01 * (errors[k] + a23_bound), "n {n} t {t} k {k}");
                        }
                    }
                }
            }
        }
    }

    /// The fixed-array jets (dimensions 1..=4, degree below 16) against the
    /// slice code they replace on the hot path: bit for bit, values and
    /// bounds, every order, inside and outside `[0, 1]`.
    #[test]
    fn small_jets_equal_the_slice_jets() {
        for n in 0..SMALL_JET_POINTS {
            for dim in 1..=4 {
                let points: Vec<f64> = (0..(n + 1) * dim)
                    .map(|i| ((i * 7919) % 97) as f64 / 9.7 - 5.0)
                    .collect();
                for t in [0.3, 0.5, 0.77, 1e-9, -0.2, 1.4] {
                    for order in [0, 1, n, n + 2] {
                        let mut fast = (vec![7.0; (order + 1) * dim], vec![7.0; order + 1]);
                        let mut slow = fast.clone();
                        de_casteljau_jet_into(&points, dim, n, t, order, &mut fast.0, &mut fast.1);
                        de_casteljau_jet_slices(
                            &points,
                            dim,
                            n,
                            t,
                            order,
                            &mut slow.0,
                            &mut slow.1,
                        );
                        assert_eq!(fast, slow, "n {n} dim {dim} t {t} order {order}");
                    }
                }
            }
        }
    }

    /// The fixed-array end jets ([`end_jet_small`], the branch of
    /// `derivatives_with_error_into` at `t = 0` and `t = 1` for dimensions
    /// 1..=4) equal the slice code ([`end_jet_slices`]) bit for bit, values
    /// and bounds, degrees 1..=31 (the table range), orders 0, 1, `n` and
    /// above the degree, both ends, with signed zeros and a huge point.
    #[test]
    fn small_end_jets_equal_the_slice_end_jets() {
        let bits = crate::test_values::bits;
        for n in 1..END_TABLE_SIZE {
            for dim in 1..=4 {
                let mut points: Vec<f64> = (0..(n + 1) * dim)
                    .map(|i| ((i * 7919) % 97) as f64 / 9.7 - 5.0)
                    .collect();
                points[0] = -0.0;
                points[n * dim + dim / 2] = 1e300;
                for at_one in [false, true] {
                    for order in [0, 1, n, n + 2] {
                        let mut fast = (vec![7.0; (order + 1) * dim], vec![7.0; order + 1]);
                        let mut slow = fast.clone();
                        let (values, errors) = (&mut fast.0, &mut fast.1);
                        match dim {
                            1 => end_jet_small::<1>(&points, n, at_one, values, errors),
                            2 => end_jet_small::<2>(&points, n, at_one, values, errors),
                            3 => end_jet_small::<3>(&points, n, at_one, values, errors),
                            _ => end_jet_small::<4>(&points, n, at_one, values, errors),
                        }
                        end_jet_slices(&points, dim, n, at_one, order, &mut slow.0, &mut slow.1);
                        let what = format!("n {n} dim {dim} at_one {at_one} order {order}");
                        assert_eq!(bits(&fast.0), bits(&slow.0), "values, {what}");
                        assert_eq!(bits(&fast.1), bits(&slow.1), "bounds, {what}");
                    }
                }
            }
        }
    }

    /// The end-condition hot path ([`ends::connect_ends`], fixed arrays)
    /// against the general structured path ([`prepare`],
    /// [`solve_structured`]): the same control points, residual and
    /// estimate bit for bit, for dimensions 1..=5 (5 takes the general path
    /// inside too), degrees of P and Q 1..=7, orders up to the degrees,
    /// parameters at the ends and inside, and several scales.
    #[test]
    fn end_path_equals_the_general_path() {
        let mut cases = 0;
        for dim in 1..=5 {
            for (np, nq) in [(1, 1), (3, 3), (3, 4), (5, 2), (7, 7)] {
                let curve = |degree: usize, offset: usize| {
                    let points: Vec<f64> = (0..(degree + 1) * dim)
                        .map(|i| (((i + offset) * 7919) % 97) as f64 / 9.7 - 5.0)
                        .collect();
                    BezierCurve::new(dim, degree, points).unwrap()
                };
                let (p, q) = (curve(np, 3), curve(nq, 41));
                for (u0, v0) in [(1.0, 0.0), (0.6, 0.3), (0.0, 1.0), (0.25, 0.0)] {
                    for (kp, kq) in [(0, 0), (1, 2), (np, nq), (np.min(2), nq)] {
                        for (alpha, beta) in [(1.0, 1.0), (0.3, 2.5)] {
                            let options = ConnectOptions::new(kp, kq).with_scales(alpha, beta);
                            let fast = connect(&p, u0, &q, v0, &options);
                            let problem = prepare(&p, u0, &q, v0, &options).unwrap();
                            let general = solve_structured(&problem, alpha, beta);
                            match (fast, general) {
                                (Ok(a), Ok(b)) => {
                                    assert_eq!(
                                        a.curve.points(),
                                        b.curve.points(),
                                        "dim {dim} {np}/{nq} {u0}/{v0} {kp}/{kq}"
                                    );
                                    assert_eq!(a.max_residual, b.max_residual);
                                    assert_eq!(a.error_estimate, b.error_estimate);
                                }
                                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                                (a, b) => panic!("paths disagree: {a:?} / {b:?}"),
                            }
                            cases += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(cases, 5 * 5 * 4 * 4 * 2);
    }

    /// The end path against the general path on random cases from the
    /// fixed-seed generator: dimensions 1..=6 (5 and 6 take the general
    /// path inside), input degrees 0..=15 (the compile-time-degree jets,
    /// the run-time ones and the slice ones), orders up to result degree
    /// 31 (the whole table range; many such cases are refused, and then
    /// both paths must refuse alike), parameters at the ends and inside,
    /// scales over four decades. Control points, residual and estimate
    /// bit for bit, or the same error.
    #[test]
    fn end_path_equals_the_general_path_on_random_cases() {
        let mut values = crate::test_values::Values(2025);
        let mut pick = |below: usize| ((values.unit() * below as f64) as usize).min(below - 1);
        let mut agreed = 0;
        for case in 0..600 {
            let dim = 1 + pick(6);
            let (np, nq) = (pick(16), pick(16));
            let kp = pick(np + 3).min(15);
            let kq = pick((nq + 3).min(MAX_CONNECT_DEGREE - kp));
            let mut coordinates = crate::test_values::Values(7 + case as u64);
            let mut curve = |degree: usize, offset: f64| {
                let points: Vec<f64> = (0..(degree + 1) * dim)
                    .map(|_| offset + 4.0 * coordinates.signed())
                    .collect();
                BezierCurve::new(dim, degree, points).unwrap()
            };
            let (p, q) = (curve(np, 0.0), curve(nq, 3.0));
            let parameter = |choice: usize, value: f64| match choice {
                0 => 0.0,
                1 => 1.0,
                _ => value,
            };
            let u0 = parameter(pick(4), values_unit(case, 1));
            let v0 = parameter(pick(4), values_unit(case, 2));
            let alpha = 10f64.powf(2.0 * values_unit(case, 3) - 1.0);
            let beta = 10f64.powf(2.0 * values_unit(case, 4) - 1.0);
            let options = ConnectOptions::new(kp, kq).with_scales(alpha, beta);
            let fast = connect(&p, u0, &q, v0, &options);
            let problem = prepare(&p, u0, &q, v0, &options).unwrap();
            let general = solve_structured(&problem, alpha, beta);
            let label = format!("case {case}: dim {dim} {np}/{nq} {kp}/{kq} {u0}/{v0}");
            let answer =
                |c: &Connection| (c.curve.points().to_vec(), c.max_residual, c.error_estimate);
            agreed += usize::from(assert_same_answer(
                &label,
                fast.as_ref().map(answer),
                general.as_ref().map(answer),
            ));
        }
        // Most cases are answered (not a test of two identical refusals).
        assert!(agreed > 300, "only {agreed} answered cases");
    }

    /// A value in [0, 1) for case `case`, slot `slot` (its own generator,
    /// so the draws of one case do not shift those of the next).
    fn values_unit(case: usize, slot: u64) -> f64 {
        crate::test_values::Values(1000 * case as u64 + slot).unit()
    }

    /// [`end_band`]'s tables give the values of its run-time recurrence bit
    /// for bit (degrees up to the table size, every order and end).
    #[test]
    fn end_band_tables_equal_the_recurrence() {
        for n in 0..END_TABLE_SIZE {
            for k in 0..=n {
                let falling = falling_factorial(n, k);
                let mut coefficient = 1.0f64;
                let mut band = vec![0.0; k + 1];
                for at_one in [false, true] {
                    end_band(n, k, at_one, &mut band);
                    coefficient = 1.0;
                    for j in 0..=k {
                        let (slot, negative) = if at_one {
                            (k - j, j % 2 == 1)
                        } else {
                            (j, (k - j) % 2 == 1)
                        };
                        let value = falling * coefficient;
                        assert_eq!(
                            band[slot],
                            if negative { -value } else { value },
                            "n {n} k {k} j {j}"
                        );
                        coefficient = coefficient * (k - j) as f64 / (j + 1) as f64;
                    }
                }
                assert!(coefficient == 0.0 || k == 0 || coefficient.is_finite());
            }
        }
    }

    /// [`power`] is `powi` bit for bit (scales of every size, inexact
    /// products, overflow and underflow; exponents up to past the degree
    /// limit).
    #[test]
    fn power_equals_powi() {
        let mut values = crate::test_values::Values(25);
        let mut scales = vec![1.0, 0.5, 2.0, 1.7, 0.6, 1e-300, 1e300, 0.0, -1.3];
        for _ in 0..200 {
            scales.push(10f64.powf(8.0 * values.signed()) * values.unit());
        }
        for x in scales {
            for k in 0..=2 * MAX_CONNECT_DEGREE {
                assert_eq!(power(x, k).to_bits(), x.powi(k as i32).to_bits(), "{x}^{k}");
            }
        }
    }

    /// [`end_band_norm`]'s table against the sum of the bands of both ends.
    #[test]
    fn end_band_norms_equal_the_band_sums() {
        for n in 0..END_TABLE_SIZE + 3 {
            for k in 0..=n {
                let mut band = vec![0.0; k + 1];
                for at_one in [false, true] {
                    end_band(n, k, at_one, &mut band);
                    let sum: f64 = band.iter().map(|v| v.abs()).sum();
                    assert_eq!(end_band_norm(n, k), sum, "n {n} k {k} at_one {at_one}");
                }
            }
        }
    }

    #[test]
    fn structured_matches_dense_on_a_small_case() {
        let p = cubic(0.0);
        let q = cubic(5.0);
        let o = ConnectOptions::new(3, 2)
            .with_scales(0.7, 1.3)
            .with_constraint(PointConstraint::new(0.4, 1, vec![4.0, 3.0, 2.0, 0.0]));
        let s = connect(&p, 0.8, &q, 0.1, &o).unwrap();
        let d = connect_dense_reference(&p, 0.8, &q, 0.1, &o).unwrap();
        assert_eq!(s.curve.degree(), 3 + 2 + 1 + 2);
        let scale = s.curve.coordinate_scale();
        for (a, b) in s.curve.points().iter().zip(d.curve.points()) {
            assert!((a - b).abs() <= 1e-12 * scale);
        }
    }

    /// A random problem of [`the_curve_path_answers_as_the_full_check`]:
    /// curves, parameters, orders and scales from `values`.
    fn random_problem(
        values: &mut crate::test_values::Values,
        case: usize,
    ) -> (BezierCurve, f64, BezierCurve, f64, ConnectOptions) {
        let mut pick = |below: usize| ((values.unit() * below as f64) as usize).min(below - 1);
        let dim = [1, 2, 2, 3, 3, 4][pick(6)];
        let (np, nq) = (pick(16), pick(16));
        let kp = pick(np + 3).min(15);
        let kq = pick((nq + 3).min(MAX_CONNECT_DEGREE - kp));
        // Near the origin, or far from it (the ends' rounding then counts).
        let offset = [0.0, 0.0, 1e4, 1e9][pick(4)];
        let mut coordinates = crate::test_values::Values(45 + case as u64);
        let mut curve = |degree: usize, shift: f64| {
            let points: Vec<f64> = (0..(degree + 1) * dim)
                .map(|_| offset + shift + 4.0 * coordinates.signed())
                .collect();
            BezierCurve::new(dim, degree, points).unwrap()
        };
        let (p, q) = (curve(np, 0.0), curve(nq, 3.0));
        let parameter = |choice: usize, value: f64| match choice {
            0 => 0.0,
            1 => 1.0,
            _ => value,
        };
        let u0 = parameter(pick(4), values_unit(case, 11));
        let v0 = parameter(pick(4), values_unit(case, 12));
        // 0.1 to 1e3: large scales of high orders are refused.
        let alpha = 10f64.powf(4.0 * values.unit() - 1.0);
        let beta = 10f64.powf(4.0 * values.unit() - 1.0);
        (
            p,
            u0,
            q,
            v0,
            ConnectOptions::new(kp, kq).with_scales(alpha, beta),
        )
    }

    /// `connect_curve` is `connect(...).curve`: the same points bit for bit
    /// or the same error, on problems answered and refused, near the origin
    /// and far from it. Where its screen passes, the full check accepts the
    /// same points (the screen's bounds are never below the check's); most
    /// problems the full check accepts pass the screen (it is not a path
    /// that always falls back).
    #[test]
    fn the_curve_path_answers_as_the_full_check() {
        let mut values = crate::test_values::Values(4545);
        let (mut screened, mut refused, mut fell_back) = (0, 0, 0);
        for case in 0..800 {
            let (p, u0, q, v0, options) = random_problem(&mut values, case);
            let label = format!(
                "case {case}: dim {} {}/{} {}/{} {u0}/{v0} {:?}",
                p.dim(),
                p.degree(),
                q.degree(),
                options.p_order,
                options.q_order,
                options.scale
            );
            let full = connect(&p, u0, &q, v0, &options);
            let curve = connect_curve(&p, u0, &q, v0, &options);
            // P as a NURBS curve: its own jets and bounds in the screen.
            let nurbs = crate::NurbsCurve::from_bezier(&p);
            let full_nurbs = connect(&nurbs, u0, &q, v0, &options);
            let curve_nurbs = connect_curve(&nurbs, u0, &q, v0, &options);
            for (full, curve) in [(&full, &curve), (&full_nurbs, &curve_nurbs)] {
                match (full, curve) {
                    (Ok(c), Ok(r)) => assert_eq!(c.curve.points(), r.points(), "{label}"),
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{label}"),
                    _ => panic!("{label}: {full:?} against {curve:?}"),
                }
            }
            refused += usize::from(full.is_err());
            let Some((alpha, beta)) = options.scale.checked().unwrap() else {
                unreachable!()
            };
            let args = (u0, v0, options.p_order, options.q_order, alpha, beta);
            match screen::connect_ends_screened(&p, &q, args) {
                Some(r) => {
                    screened += 1;
                    let c = full
                        .as_ref()
                        .unwrap_or_else(|e| panic!("{label}: screen passed, check refused: {e}"));
                    assert_eq!(c.curve.points(), r.points(), "{label}");
                    assert!(c.error_estimate <= CONNECT_RESIDUAL_LIMIT, "{label}");
                }
                None => {
                    if let (Ok(_), 2..=3) = (&full, p.dim()) {
                        fell_back += 1;
                    }
                }
            }
        }
        assert!(
            screened > 300 && refused > 20 && fell_back < screened / 10,
            "screened {screened}, refused {refused}, fell back {fell_back}"
        );
    }

    /// Across the scale at which the full check starts refusing (curves
    /// 1e9 from the origin: the jets' rounding grows with `s^k`), the
    /// curve-only path answers as `connect` at every step, and its screen
    /// never passes a problem the check refuses.
    #[test]
    fn the_curve_path_refuses_where_the_full_check_refuses() {
        let mut coordinates = crate::test_values::Values(4546);
        let mut curve = |degree: usize, shift: f64| {
            let points: Vec<f64> = (0..(degree + 1) * 3)
                .map(|_| shift + 4.0 * coordinates.signed())
                .collect();
            BezierCurve::new(3, degree, points).unwrap()
        };
        let (p, q) = (curve(7, 1e9), curve(4, 1e9 + 3.0));
        let (mut answered, mut refused, mut screened) = (0, 0, 0);
        for step in 0..=300 {
            let scale = 10f64.powf(step as f64 / 100.0);
            let options = ConnectOptions::new(7, 2).with_scales(scale, scale);
            let full = connect(&p, 0.35, &q, 0.8, &options);
            let curve = connect_curve(&p, 0.35, &q, 0.8, &options);
            match (&full, &curve) {
                (Ok(c), Ok(r)) => assert_eq!(c.curve.points(), r.points(), "scale {scale}"),
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "scale {scale}"),
                _ => panic!("scale {scale}: {full:?} against {curve:?}"),
            }
            answered += usize::from(full.is_ok());
            refused += usize::from(full.is_err());
            if screen::connect_ends_screened(&p, &q, (0.35, 0.8, 7, 2, scale, scale)).is_some() {
                screened += 1;
                assert!(full.is_ok(), "scale {scale}: screen passed, check refused");
            }
        }
        assert!(
            answered > 20 && refused > 20 && screened > 10,
            "answered {answered}, refused {refused}, screened {screened}"
        );
    }

    /// Where the full check's squares overflow (coordinates or targets
    /// near `1e155`: an infinite estimate) or lose digits (coordinates
    /// near `1e-170`: Euclidean norms below the largest coordinate), the
    /// curve-only path refuses as `connect` does and answers as it does
    /// (reproducers of the review of session 45).
    #[test]
    fn the_curve_path_answers_as_the_full_check_at_the_ends_of_the_double_range() {
        let line = |a: f64, b: f64| BezierCurve::new(2, 1, vec![a, 0.0, b, 0.0]).unwrap();
        let cubic = |points: [f64; 8]| BezierCurve::new(2, 3, points.to_vec()).unwrap();
        let p = cubic([0.0, 0.0, 1.0, 2.0, 3.0, 1.0, 4.0, 0.0]);
        let q = cubic([6.0, 0.0, 7.0, -1.0, 8.0, 1.0, 9.0, 0.0]);
        // Lines along x: P from a to b, Q from c to d; u0, v0; kp, kq; beta.
        let lines = [
            ([0.0, 1e155, 2e155, 3e155], (0.5, 0.5), (1, 1), 1.0),
            ([-1e155, 1e155, 2e155, 3e155], (0.5, 0.5), (1, 1), 1.0),
            ([0.0, 1e-169, 2e-169, 3e-169], (1.0, 0.0), (0, 15), 1e7),
            ([0.0, 1e-172, 2e-172, 3e-172], (1.0, 0.0), (0, 15), 3e8),
        ];
        let mut cases: Vec<_> = lines
            .iter()
            .map(|&([a, b, c, d], (u0, v0), (kp, kq), beta)| {
                (line(a, b), u0, line(c, d), v0, kp, kq, 1.0, beta)
            })
            .collect();
        for scale in [1e50, 1e52, 1e53] {
            cases.push((p.clone(), 0.5, q.clone(), 0.5, 3, 3, scale, scale));
        }
        let mut refused = 0;
        for (p, u0, q, v0, kp, kq, alpha, beta) in cases {
            let options = ConnectOptions::new(kp, kq).with_scales(alpha, beta);
            let full = connect(&p, u0, &q, v0, &options);
            let curve = connect_curve(&p, u0, &q, v0, &options);
            let label = format!("{p:?} {q:?} {kp}/{kq} {alpha:e}/{beta:e}");
            match (&full, &curve) {
                (Ok(c), Ok(r)) => assert_eq!(c.curve.points(), r.points(), "{label}"),
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{label}"),
                _ => panic!("{label}: {full:?} against {curve:?}"),
            }
            refused += usize::from(full.is_err());
        }
        assert!(refused >= 4, "{refused}");
    }

    /// The screen's jets: the values of [`derivatives_with_error_into`] bit
    /// for bit, bounds never below its bounds, for every dimension, degree,
    /// order and parameter (the ends and outside the plane and space take
    /// the full bounds themselves).
    #[test]
    fn screen_jets_are_the_jets_with_larger_bounds() {
        let mut values = crate::test_values::Values(4547);
        let mut larger = 0;
        for n in 0..SMALL_JET_POINTS + 2 {
            for dim in 1..=4 {
                let offset = [0.0, 1e5][n % 2];
                let points: Vec<f64> = (0..(n + 1) * dim)
                    .map(|_| offset + 10.0 * values.signed())
                    .collect();
                let curve = BezierCurve::new(dim, n, points).unwrap();
                for t in [0.0, 1.0, 0.3, 0.5, 0.77, 1e-9, 1.0 - 1e-12, values.unit()] {
                    for order in [0, 1, n / 2, n, n + 2] {
                        let mut full = (vec![7.0; (order + 1) * dim], vec![7.0; order + 1]);
                        let mut screen = full.clone();
                        derivatives_with_error_into(&curve, t, order, &mut full.0, &mut full.1);
                        let scale = curve.coordinate_scale();
                        derivatives_with_screen_into(
                            &curve,
                            t,
                            order,
                            scale,
                            &mut screen.0,
                            &mut screen.1,
                        );
                        let label = format!("n {n} dim {dim} t {t} order {order}");
                        assert_eq!(full.0, screen.0, "{label}");
                        for (k, (a, b)) in full.1.iter().zip(&screen.1).enumerate() {
                            assert!(*b >= *a * (1.0 - 1e-12), "{label} row {k}: {b:e} < {a:e}");
                            larger += usize::from(b > a);
                        }
                    }
                }
            }
        }
        // The a-priori bounds are used (not the full ones everywhere).
        assert!(larger > 1000, "{larger}");
    }
}
