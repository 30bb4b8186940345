//! Connect two curves with geometric continuity G^k and fair shape
//! parameters (docs/mathematics.md#geometric-continuity; the specification's
//! section 7).
//!
//! Two curves meet with G^k when, after a regular reparametrisation `phi`
//! (`phi' > 0`), they meet with C^k. With `R(t) = P(phi_p(t))` to order
//! `kp` at `t = 0` (`phi_p(0) = u0`) and `R(t) = Q(phi_q(t))` to order `kq`
//! at `t = 1` (`phi_q(1) = v0`), Faa di Bruno's formula gives the
//! beta-constraints (Barsky and DeRose 1989):
//!
//! ```text
//! R^(j)(0) = sum_(i=1..j) P^(i)(u0) B_(j,i)(beta_p1, ..., beta_p(j-i+1)),   j = 1..kp
//! R^(j)(1) = sum_(i=1..j) Q^(i)(v0) B_(j,i)(beta_q1, ..., beta_q(j-i+1)),   j = 1..kq
//! ```
//!
//! with `B_(j,i)` the partial Bell polynomials and the shape parameters
//! `beta_p = phi_p^(j)(0)`, `beta_q = phi_q^(j)(1)` (`beta_1 > 0`). For
//! `beta_j = 0` (`j >= 2`) this is connect's `C^k` with scales `alpha =
//! beta_p1`, `beta = beta_q1`. Only the targets change: the structured solve
//! of [`connect`](fn@crate::connect) is used unchanged, with its residual
//! guarantee on the new targets, interior constraints included.
//!
//! # Fair shape parameters
//!
//! When the caller gives no shape values, they are chosen by minimising the
//! curvature variation of the blend made scale-free by its length `L`,
//! `E = L^3 int (d kappa / ds)^2 ds` ([`fair::curvature_variation`]: the
//! plain integral tends to zero on ever larger loops, whose curvature
//! vanishes, so its minimisation runs away), over
//! `ln beta_1` and `gamma_j = beta_j / beta_1` (`j >= 2`) of both ends: a
//! grid over a common end speed (`beta_1` of each end `sigma |Q(v0) -
//! P(u0)|` over that end's tangent length, `sigma` over four decades around
//! 1, the `gamma_j` zero) and then Nelder-Mead in all of them
//! ([`fair::nelder_mead`], deterministic). A linear reparametrisation of
//! an input changes its `beta_1` by a factor and no `gamma_j`, so the search
//! takes the same steps, and finds the same blend up to rounding, however
//! fast the inputs run (a degree-1 line runs at its length). Where an
//! input's tangent at the join is zero there is no G^k to meet: the call
//! is IllConditioned. Shapes whose solve fails, and
//! blends with a cusp (`E` infinite), count as infinitely bad. The trial
//! solves reuse everything that does not depend on the shape values and
//! skip connect's residual check; the winner is solved again and checked
//! in full, and should it be refused the search is repeated with every
//! trial checked (a refused trial counting as infinitely bad). The report
//! gives the energy, the curvature range and the number of interior local
//! extrema of the curvature (sampled).

mod fair;
mod symmetry;
mod trial;

use nalgebra::DMatrix;

use crate::bezier::{BezierCurve, distance};
use crate::connect::{
    COINCIDENT_ENDS, ConnectOptions, Connection, PointConstraint, Problem, check_connect_degree,
    check_pair, connect_ends_shaped, prepare, solve_structured,
};
use crate::curve::CurveJet;
use crate::error::{BezjoinError, Compact, Result, check_finite};

pub(crate) use fair::curvature_at;
pub use fair::{
    CURVATURE_SAMPLES, ENERGY_PANELS, FairnessReport, MAX_LENGTH_RATIO, curvature_variation,
    fairness_report,
};

/// Largest order of geometric continuity per end (the spec asks for 4).
pub const MAX_GEOMETRIC_ORDER: usize = 6;

/// Options of [`connect_geometric`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GeometricOptions {
    /// `kp`: G^kp at `P(u0)`.
    pub p_order: usize,
    /// `kq`: G^kq at `Q(v0)`.
    pub q_order: usize,
    /// `beta_1..beta_kp` at `P` (`beta_1 > 0`); `None`: chosen for fairness.
    pub p_shape: Option<Vec<f64>>,
    /// `beta_1..beta_kq` at `Q`; `None`: chosen for fairness.
    pub q_shape: Option<Vec<f64>>,
    /// Interior constraints, as in [`ConnectOptions`].
    pub constraints: Vec<PointConstraint>,
}

impl GeometricOptions {
    /// G^kp and G^kq with fair shape parameters.
    pub fn new(p_order: usize, q_order: usize) -> Self {
        Self {
            p_order,
            q_order,
            ..Self::default()
        }
    }

    /// These options with the caller's shape values at both ends.
    pub fn with_shapes(mut self, p_shape: Vec<f64>, q_shape: Vec<f64>) -> Self {
        self.p_shape = Some(p_shape);
        self.q_shape = Some(q_shape);
        self
    }
}

/// A G^k connecting curve with the shape values used and its fairness.
#[derive(Debug, Clone, PartialEq)]
pub struct GeometricConnection {
    /// The Bezier curve `R` (degree `kp + kq + 1 + sum (K_j + 1)`).
    pub curve: BezierCurve,
    /// `beta_1..beta_kp` used at `P`.
    pub p_shape: Vec<f64>,
    /// `beta_1..beta_kq` used at `Q`.
    pub q_shape: Vec<f64>,
    /// Energy, curvature range and extrema of `R`.
    pub report: FairnessReport,
    /// The residual check of the structured solve (scales are 1: the shape
    /// values are in the targets).
    pub max_residual: f64,
    /// Bound on the worst relative residual of the beta-constraints and the
    /// interior constraints (at most [`crate::CONNECT_RESIDUAL_LIMIT`]).
    pub error_estimate: f64,
}

/// A G^k connecting curve with the shape values used, without the
/// fairness report ([`connect_geometric_curve`]).
#[derive(Debug, Clone, PartialEq)]
pub struct GeometricCurve {
    /// The Bezier curve `R` (degree `kp + kq + 1 + sum (K_j + 1)`).
    pub curve: BezierCurve,
    /// `beta_1..beta_kp` used at `P`.
    pub p_shape: Vec<f64>,
    /// `beta_1..beta_kq` used at `Q`.
    pub q_shape: Vec<f64>,
    /// The residual check of the structured solve (scales are 1: the shape
    /// values are in the targets).
    pub max_residual: f64,
    /// Bound on the worst relative residual of the beta-constraints and the
    /// interior constraints (at most [`crate::CONNECT_RESIDUAL_LIMIT`]).
    pub error_estimate: f64,
}

impl GeometricCurve {
    fn new(p_shape: Vec<f64>, q_shape: Vec<f64>, connection: Connection) -> Self {
        Self {
            curve: connection.curve,
            p_shape,
            q_shape,
            max_residual: connection.max_residual,
            error_estimate: connection.error_estimate,
        }
    }
}

/// The partial Bell polynomials `B_(j,i)(x_1, ..., x_(j-i+1))` for
/// `0 <= i <= j <= order` (`x[0]` is `x_1`), by the recurrence
/// `B_(j,i) = sum_(m=1..j-i+1) C(j-1, m-1) x_m B_(j-m,i-1)`,
/// `B_(0,0) = 1`. Row `j`, column `i`.
pub fn partial_bell(x: &[f64], order: usize) -> DMatrix<f64> {
    let mut b = vec![0.0; (order + 1) * (order + 1)];
    partial_bell_into(x, order, &mut b, order + 1);
    DMatrix::from_row_slice(order + 1, order + 1, &b)
}

/// [`partial_bell`] for `order <= MAX_GEOMETRIC_ORDER` in a fixed array
/// (row `j`, column `i`; the entries outside `i <= j <= order` zero): the
/// same recurrence with the binomials from [`BELL_BINOMIALS`], the same
/// numbers bit for bit (`order` at most [`MAX_GEOMETRIC_ORDER`], as the
/// callers check). Inlined, so that where
/// the caller's `order` is a constant (the end path's targets) every loop
/// has constant bounds and unrolls.
#[inline(always)]
pub(crate) fn partial_bell_small(
    x: &[f64],
    order: usize,
) -> [[f64; MAX_GEOMETRIC_ORDER + 1]; MAX_GEOMETRIC_ORDER + 1] {
    const N: usize = MAX_GEOMETRIC_ORDER + 1;
    let mut b = [[0.0; N]; N];
    debug_assert!(order <= MAX_GEOMETRIC_ORDER);
    let mut xs = [0.0; MAX_GEOMETRIC_ORDER];
    xs[..order].copy_from_slice(&x[..order]);
    b[0][0] = 1.0;
    // Exclusive ranges: they unroll where `order` is a constant (inclusive
    // ones keep a flag that stops it).
    for j in 1..order + 1 {
        for i in 1..j + 1 {
            let mut sum = 0.0;
            for m in 1..j - i + 2 {
                sum += BELL_BINOMIALS[j - 1][m - 1] * xs[m - 1] * b[j - m][i - 1];
            }
            b[j][i] = sum;
        }
    }
    b
}

/// `BELL_BINOMIALS[j][m] = C(j, m)` for `j, m < MAX_GEOMETRIC_ORDER` (zero
/// for `m > j`): the coefficients `C(j-1, m-1)` of the Bell recurrence for
/// the geometric orders. Exact integers, so the same doubles as the
/// recurrence's running product `C(j-1, m-2) (j-m+1) / (m-1)` (whose
/// product is the exact integer `C(j-1, m-1) (m-1)`).
const BELL_BINOMIALS: [[f64; MAX_GEOMETRIC_ORDER]; MAX_GEOMETRIC_ORDER] =
    crate::basis::pascal_square();

/// The recurrence of [`partial_bell`] into the row-major `b` (row stride
/// `stride`), whose entries must be zero on entry.
fn partial_bell_into(x: &[f64], order: usize, b: &mut [f64], stride: usize) {
    b[0] = 1.0;
    for j in 1..=order {
        for i in 1..=j {
            let mut sum = 0.0;
            let mut binomial = 1.0; // C(j-1, m-1)
            for m in 1..=(j - i + 1) {
                if m > 1 {
                    binomial = binomial * (j - m + 1) as f64 / (m - 1) as f64;
                }
                sum += binomial * x[m - 1] * b[(j - m) * stride + i - 1];
            }
            b[j * stride + i] = sum;
        }
    }
}

/// `jet` (rows `P^(0..=k)`) turned into the targets `R^(j)` of the
/// beta-constraints, with the rounding bound of each row carried along.
fn geometric_targets(
    jet: &DMatrix<f64>,
    errors: &[f64],
    shape: &[f64],
) -> (DMatrix<f64>, Vec<f64>) {
    let k = jet.nrows() - 1;
    let bell = partial_bell(shape, k);
    let mut out = DMatrix::zeros(k + 1, jet.ncols());
    out.row_mut(0).copy_from(&jet.row(0));
    let mut out_errors = vec![errors[0]; k + 1];
    for j in 1..=k {
        let mut bound = 0.0;
        for i in 1..=j {
            let coefficient = bell[(j, i)];
            for c in 0..jet.ncols() {
                out[(j, c)] += coefficient * jet[(i, c)];
            }
            bound += coefficient.abs() * (errors[i] + 4.0 * f64::EPSILON * jet.row(i).norm());
        }
        out_errors[j] = bound;
    }
    (out, out_errors)
}

/// G^k at an end (`k >= 1`) is defined only where the input is regular:
/// with `P'(u0) = 0` (or `Q'(v0) = 0`) there is no unit tangent to meet, and
/// every shape value gives `R'(0) = beta_1 P'(u0) = 0`, a blend without
/// defined curvature at that end: IllConditioned, as when the search finds
/// no shape values. `(u0, P'(u0) = 0)` and `(v0, Q'(v0) = 0)`, each only
/// for an order of at least 1; an exact zero (a tiny tangent still has a
/// direction). Called after the arguments are validated, with the jets the
/// solve computes anyway (the end path's fixed rows, the general path's
/// `Problem`): no evaluation of its own.
#[inline]
pub(crate) fn check_regular_ends(
    (u0, p_zero): (f64, bool),
    (v0, q_zero): (f64, bool),
    (p_order, q_order): (usize, usize),
) -> Result<()> {
    match (p_zero, q_zero) {
        (true, _) => Err(zero_tangent_error("p", "u0", u0, p_order)),
        (false, true) => Err(zero_tangent_error("q", "v0", v0, q_order)),
        (false, false) => Ok(()),
    }
}

/// The largest error estimate of an end's invariants
/// (`geometric_end_condition`) a G^k blend is answered with: its unit
/// tangent and curvature vector at each end known to this part of
/// themselves, or IllConditioned. The
/// estimate is a first-order bound from the jets' rounding bounds, which
/// ran 6 to 420 times above the errors measured independently (user
/// testing, session 42): at `1e-6` an end whose last two poles are `1e-6`
/// apart (a relative estimate of 3e-8) is answered with its invariants
/// matched to 4e-10, and one `1e-9` apart (3e-5) is refused, where a
/// `1e-12` gap used to be answered with the curvature off by 1.7e-5 (and
/// `3e-15` by 92 %).
pub const GEOMETRIC_CONDITION_LIMIT: f64 = 1e-6;

/// The rounding of the stored blend's own `R^(j)` at an end: a `j`-th
/// difference of control points of size `coordinates`, times `n!/(n-j)!`
/// (`n` the blend's degree): `2^j n!/(n-j)! u S`.
fn stored_rounding(j: usize, (degree, coordinates): (usize, f64)) -> f64 {
    let stored: f64 = (0..j).map(|i| 2.0 * (degree - i) as f64).product();
    stored * 0.5 * f64::EPSILON * coordinates
}

/// How well the geometric invariants of one end are known, relative to
/// themselves: the unit tangent and (in two dimensions and more) the
/// curvature vector `K`, from the targets `T_j = R^(j)(end)` of the
/// beta-constraints (`rows[j]`, `j = 0..=order`) and the chord `c`. The
/// error `e_j` of `T_j` is its rounding bound (`errors[j]`) plus that of the
/// stored blend's own `R^(j)`, `2^j n!/(n-j)! u S` (`(n, S)` =
/// `(degree, coordinates)`: the blend's degree and the ends' largest
/// coordinate; far from the origin, or where the blend's first control-point
/// steps are tiny against its coordinates, the stored poles cannot hold the
/// curvature better). To first order:
/// - the tangent: `2 e_1 / |T_1|`;
/// - `K = T_2^perp / |T_1|^2`: `(e_2 + 2 |T_2| e_1 / |T_1|) / |T_1|^2`
///   against `max(|K|, 1 / c)`.
///
/// Returns the larger of the two and `|T_1|`; the curvature's derivative
/// (G^3) is not estimated. With `T_1 = 0` the tangent is undefined: infinite. At an end
/// that is nearly stationary the tangent's term dominates; next to a cusp
/// (`P'` and `P''` nearly parallel) the curvature's: it is then a small
/// difference of large numbers.
pub(crate) fn geometric_end_condition<R: AsRef<[f64]>>(
    rows: &[R],
    errors: &[f64],
    order: usize,
    chord: f64,
    (degree, coordinates): (usize, f64),
) -> (f64, f64) {
    let order = order.min(rows.len().saturating_sub(1));
    if order == 0 {
        return (0.0, 0.0);
    }
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let first = rows[1].as_ref();
    // The tangent and the curvature vector (the curvature's derivative is
    // not estimated: a first-order bound of it refused G3 fillets whose
    // blends were exact to 1e-14, session 42); a line (dimension 1) has no
    // curvature to lose.
    let order = if first.len() == 1 { 1 } else { order.min(2) };
    let speed = dot(first, first).sqrt();
    if speed == 0.0 {
        return (f64::INFINITY, speed);
    }
    // The target's bound plus the rounding of the stored blend's own
    // R^(j)(end): a j-th difference of control points of size
    // `coordinates`, times n!/(n-j)!.
    let bound = |j: usize| errors[j] + stored_rounding(j, (degree, coordinates));
    let tangent = bound(1) / speed;
    let mut worst = 2.0 * tangent;
    if order >= 2 {
        // The curvature vector K = T_2^perp / |T_1|^2: error (e_2 + 2 |T_2|
        // e_1 / |T_1|) / |T_1|^2, against max(|K|, 1 / c).
        let second = rows[2].as_ref();
        let size = dot(second, second).sqrt();
        let along = dot(second, first) / speed;
        let across = (size * size - along * along).max(0.0).sqrt();
        let scale = (speed * speed / chord).max(across);
        worst = worst.max((bound(2) + 2.0 * size * tangent) / scale);
    }
    // NaN (a zero chord, 0/0) counts as unknown.
    (if worst.is_nan() { f64::INFINITY } else { worst }, speed)
}

/// [`geometric_end_condition`] of both ends against
/// [`GEOMETRIC_CONDITION_LIMIT`]: IllConditioned naming the worse end
/// (`(u0, |P'(u0)|, its rounding bound)` and `(v0, ...)` for the message)
/// when its invariants are not known to the limit.
#[cold]
#[inline(never)]
pub(crate) fn geometric_condition_error(
    (p_estimate, u0, p_speed, p_error): (f64, f64, f64, f64),
    (q_estimate, v0, q_speed, q_error): (f64, f64, f64, f64),
    (p_order, q_order): (usize, usize),
) -> BezjoinError {
    let p_worse = p_estimate >= q_estimate;
    let (name, at, value, speed, error, order, estimate) = if p_worse {
        ("p", "u0", u0, p_speed, p_error, p_order, p_estimate)
    } else {
        ("q", "v0", v0, q_speed, q_error, q_order, q_estimate)
    };
    let derivative = if p_worse { "P'(u0)" } else { "Q'(v0)" };
    BezjoinError::IllConditioned {
        what: format!(
            "G^k connect: the tangent and curvature of {name} at {at} = {} are known only to \
             {estimate:.1e} of themselves (|{derivative}| = {}, rounding bound {}): {name} is \
             nearly stationary there, or the blend's poles are too large against its end \
             derivatives to hold them, so no blend meets {name} with G^{order} to the promise",
            Compact(value),
            Compact(speed),
            Compact(error),
        ),
        estimate,
        limit: GEOMETRIC_CONDITION_LIMIT,
    }
}

/// [`input_condition`] plus [`stored_condition`] of both ends (`(jet, its
/// bounds, the targets, the end's parameter)`, the chord between the jets'
/// rows 0), as the end path forms them: IllConditioned
/// ([`geometric_condition_error`]) above [`GEOMETRIC_CONDITION_LIMIT`].
/// Without targets (before the fair search) the input's part alone: it is
/// the same for every shape value, while the stored blend's part depends on
/// `beta_1` (a B-spline on `[0, 1e9]` has `|P'|` 1e9 times smaller than on
/// `[0, 1]`, which the search's `beta_1` makes up for).
fn check_targets_condition(
    (p, p_errors, p_targets, u0): (&DMatrix<f64>, &[f64], Option<&DMatrix<f64>>, f64),
    (q, q_errors, q_targets, v0): (&DMatrix<f64>, &[f64], Option<&DMatrix<f64>>, f64),
    (kp, kq, degree): (usize, usize, usize),
) -> Result<()> {
    let inputs = input_conditions((p, p_errors, kp), (q, q_errors, kq), degree);
    let (chord, stored) = (inputs.chord, inputs.stored);
    let stored_part = |targets: Option<&DMatrix<f64>>, order: usize| {
        targets.map_or(0.0, |t| stored_condition(&rows_of(t), order, chord, stored))
    };
    let p_end = inputs.p.0 + stored_part(p_targets, kp);
    let q_end = inputs.q.0 + stored_part(q_targets, kq);
    if p_end.max(q_end) <= GEOMETRIC_CONDITION_LIMIT {
        return Ok(());
    }
    Err(geometric_condition_error(
        (p_end, u0, inputs.p.1, inputs.p.2),
        (q_end, v0, inputs.q.1, inputs.q.2),
        (kp, kq),
    ))
}

/// The rows of a jet or of targets, each a `Vec` (what the condition
/// functions take).
fn rows_of(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter()
        .map(|row| row.iter().copied().collect())
        .collect()
}

/// What the ends' condition takes from the inputs alone: each end's
/// [`input_condition`] `(estimate, |X'|, its bound)`, the chord between the
/// jets' rows 0 and the stored blend's `(degree, largest coordinate)` for
/// [`stored_condition`]. The same numbers for [`check_targets_condition`]
/// and the fair search's trials.
pub(super) struct InputConditions {
    pub(super) p: (f64, f64, f64),
    pub(super) q: (f64, f64, f64),
    pub(super) chord: f64,
    pub(super) stored: (usize, f64),
}

/// [`InputConditions`] of the jets `(p, p_errors, kp)`, `(q, q_errors, kq)`
/// for a blend of `degree`.
pub(super) fn input_conditions(
    (p, p_errors, kp): (&DMatrix<f64>, &[f64], usize),
    (q, q_errors, kq): (&DMatrix<f64>, &[f64], usize),
    degree: usize,
) -> InputConditions {
    let (p_jet, q_jet) = (rows_of(p), rows_of(q));
    let chord = distance(&p_jet[0], &q_jet[0]);
    InputConditions {
        p: input_condition(&p_jet, p_errors, kp, chord, degree),
        q: input_condition(&q_jet, q_errors, kq, chord, degree),
        chord,
        stored: (degree, largest_coordinate(&p_jet[0], &q_jet[0])),
    }
}

/// The largest coordinate of two points (in absolute value): the size of
/// the stored blend's poles both paths measure the condition with.
pub(crate) fn largest_coordinate<'a>(
    a: impl IntoIterator<Item = &'a f64>,
    b: impl IntoIterator<Item = &'a f64>,
) -> f64 {
    a.into_iter().chain(b).fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The input's part of an end's condition, `(estimate, |X'|, its bound)`
/// (the last two for the message): [`geometric_end_condition`] of the
/// input's own jet `X^(j)` with its rounding bounds. The invariants are the
/// same in every parametrisation, so this part does not depend on the shape
/// values; and an error of `X'` turns the shape values' terms `beta_j X'` of
/// the targets with the tangent, so it is counted here, once. `degree` is
/// the blend's. 0 at an end of order 0.
pub(crate) fn input_condition<J: AsRef<[f64]>>(
    jet: &[J],
    errors: &[f64],
    order: usize,
    chord: f64,
    degree: usize,
) -> (f64, f64, f64) {
    if order == 0 || jet.len() < 2 {
        return (0.0, 0.0, 0.0);
    }
    let (estimate, speed) = geometric_end_condition(jet, errors, order, chord, (degree, 0.0));
    (estimate, speed, errors[1])
}

/// The stored blend's part of an end's condition: [`geometric_end_condition`]
/// of the targets `T_j` with the blend's own rounding alone (independent in
/// every `R^(j)`, so the targets' full size counts). 0 at an end of order 0.
pub(crate) fn stored_condition<T: AsRef<[f64]>>(
    targets: &[T],
    order: usize,
    chord: f64,
    stored: (usize, f64),
) -> f64 {
    if order == 0 || targets.len() < 2 {
        return 0.0;
    }
    let zero = [0.0; MAX_GEOMETRIC_ORDER + 1];
    geometric_end_condition(targets, &zero[..targets.len()], order, chord, stored).0
}

/// How well the stored blend holds the curvature's derivative at an end of
/// order 3 or more, relative to itself: the third arc-length derivative
/// `r_sss = d(kappa N)/ds` from the targets `T_j` (`rows[j]`, the blend's
/// own rounding alone, as [`stored_condition`]),
///
/// ```text
/// r_sss = (T_3 - (T_3.t) t) / s^3 - |T_2^perp|^2 t / s^4 - 3 (T_2.t) T_2^perp / s^4
/// ```
///
/// (`s = |T_1|`, `t = T_1 / s`), to first order in the rows' errors `e_j`:
/// `(e_3 + 5 |T_3| e_1 / s) / s^3 + 4 (2 |T_2| e_2 + 6 |T_2|^2 e_1 / s) / s^4`
/// against `max(|r_sss|, 1 / c^2)`. 0 below order 3 and in dimension 1.
///
/// Used by the fair search only, to steer it away from blends whose end
/// steps are too short for the coordinates to hold `dK/ds` (a G3 fillet of
/// radius 1e-5 on an L 40 long missed it by 4.2e-6, session 44); the
/// refusal after the search does not use it (session 42: as a refusal it
/// turned away G3 fillets whose blends were exact to 1e-14).
pub(crate) fn stored_curvature_derivative_condition<T: AsRef<[f64]>>(
    targets: &[T],
    order: usize,
    chord: f64,
    (degree, coordinates): (usize, f64),
) -> f64 {
    if order < 3 || targets.len() < 4 || targets[1].as_ref().len() < 2 {
        return 0.0;
    }
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let (t1, t2, t3) = (
        targets[1].as_ref(),
        targets[2].as_ref(),
        targets[3].as_ref(),
    );
    let s = dot(t1, t1).sqrt();
    if s.is_nan() || s <= 0.0 {
        return f64::INFINITY;
    }
    let error = |j: usize| stored_rounding(j, (degree, coordinates));
    let (e1, e2, e3) = (error(1), error(2), error(3));
    let (size2, size3) = (dot(t2, t2).sqrt(), dot(t3, t3).sqrt());
    let (along2, along3) = (dot(t2, t1) / s, dot(t3, t1) / s);
    // r_sss, coordinate by coordinate.
    let mut value = 0.0;
    let across2_square = (size2 * size2 - along2 * along2).max(0.0);
    for c in 0..t1.len() {
        let t = t1[c] / s;
        let perp2 = t2[c] - along2 * t;
        let x = (t3[c] - along3 * t) / (s * s * s)
            - across2_square * t / (s * s * s * s)
            - 3.0 * along2 * perp2 / (s * s * s * s);
        value += x * x;
    }
    let value = value.sqrt();
    let error = (e3 + 5.0 * size3 * e1 / s) / (s * s * s)
        + 4.0 * (2.0 * size2 * e2 + 6.0 * size2 * size2 * e1 / s) / (s * s * s * s);
    let scale = value.max(1.0 / (chord * chord));
    let estimate = error / scale;
    if estimate.is_nan() {
        f64::INFINITY
    } else {
        estimate
    }
}

/// Whether a jet (rows `P, P', ...`) has a first derivative, all of whose
/// coordinates are exactly zero: the `Problem` form of the test of
/// [`check_regular_ends`].
fn zero_tangent(jet: &DMatrix<f64>) -> bool {
    jet.nrows() > 1 && jet.row(1).iter().all(|v| *v == 0.0)
}

/// The error of [`check_regular_ends`], out of line: the end path stays
/// small where the check passes.
#[cold]
#[inline(never)]
fn zero_tangent_error(name: &str, at: &str, value: f64, order: usize) -> BezjoinError {
    BezjoinError::IllConditioned {
        what: format!(
            "G^k connect: the tangent of {name} at {at} = {value} is zero, so no shape \
             values give a blend with defined curvature there (G^{order} needs a regular point)"
        ),
        estimate: f64::INFINITY,
        limit: crate::CONNECT_RESIDUAL_LIMIT,
    }
}

/// The fair search needs `P(u0) != Q(v0)`: between coincident ends a blend
/// is a loop, and a loop has no fairest size (the scale-free energy falls
/// as the loop grows: user testing, session 40, answered blends with
/// coordinates of 1e68 on a part 10 across and reported energy 0). Ends
/// within [`COINCIDENT_ENDS`] of their largest coordinate (the curves' far
/// poles do not count: review, session 44) are InvalidArgument
/// naming `v0`; with shape values given, such a blend is the caller's
/// choice and is answered.
fn check_ends_apart(problem: &Problem, u0: f64, v0: f64) -> Result<()> {
    let Some((gap, ends)) = problem.coincident_ends() else {
        return Ok(());
    };
    Err(BezjoinError::invalid(
        "v0",
        format!(
            "Q(v0 = {}) is {} from P(u0 = {}), within {COINCIDENT_ENDS:e} of their largest \
             coordinate {}: a G^k blend between coincident points is a loop, which has no \
             fairest size; give p_shape and q_shape, or ends apart",
            Compact(v0),
            Compact(gap),
            Compact(u0),
            Compact(ends)
        ),
    ))
}

/// Shape values given by the caller for one end: `order` values, `beta_1`
/// finite and positive, the rest finite.
fn check_shape(name: &str, shape: &[f64], order: usize) -> Result<()> {
    if shape.len() != order {
        return Err(BezjoinError::LengthMismatch {
            name: name.into(),
            expected: order,
            actual: shape.len(),
        });
    }
    check_finite(name, shape)?;
    if order > 0 && shape[0] <= 0.0 {
        return Err(BezjoinError::invalid(
            format!("{name}[0]"),
            format!(
                "beta_1 = {} must be positive (the reparametrisation must keep the direction)",
                shape[0]
            ),
        ));
    }
    Ok(())
}

/// The structured solve with the beta-constraints of the given shapes, after
/// the ends' condition ([`check_targets_condition`]).
fn solve_with_shapes(
    problem: &Problem,
    (u0, v0): (f64, f64),
    p_shape: &[f64],
    q_shape: &[f64],
) -> Result<Connection> {
    let mut shaped = problem.clone();
    let (p, p_errors) =
        geometric_targets(&problem.p_derivatives, &problem.p_derivative_error, p_shape);
    let (q, q_errors) =
        geometric_targets(&problem.q_derivatives, &problem.q_derivative_error, q_shape);
    check_targets_condition(
        (
            &problem.p_derivatives,
            &problem.p_derivative_error,
            Some(&p),
            u0,
        ),
        (
            &problem.q_derivatives,
            &problem.q_derivative_error,
            Some(&q),
            v0,
        ),
        (problem.p_order, problem.q_order, problem.degree),
    )?;
    shaped.p_derivatives = p;
    shaped.p_derivative_error = p_errors;
    shaped.q_derivatives = q;
    shaped.q_derivative_error = q_errors;
    solve_structured(&shaped, 1.0, 1.0)
}

/// Connect `P` at `u0` to `Q` at `v0` with G^kp and G^kq (the module
/// documentation states the beta-constraints), and the interior
/// constraints of `options`, for any curves (NURBS too: P's jet from the
/// left of `u0`, Q's from the right of `v0`).
///
/// Guarantee: the returned curve satisfies the beta-constraints of the
/// returned shape values and the interior constraints with the residual
/// guarantee of [`connect`](fn@crate::connect) (`error_estimate <=
/// CONNECT_RESIDUAL_LIMIT`); so it meets P and Q with G^kp and G^kq
/// (`P'(u0)`, `Q'(v0)` are not zero: a zero tangent at an end of order at
/// least 1 is refused, IllConditioned naming the curve and the parameter;
/// so is an end whose invariants are not known to
/// [`GEOMETRIC_CONDITION_LIMIT`] of themselves (docs/mathematics.md,
/// "Numerically stationary ends"). Without shape values the
/// returned ones minimise the curvature variation as the module says (a
/// local minimum from a deterministic start; no global guarantee).
///
/// Errors: those of [`connect`](fn@crate::connect) (parameters, dimensions,
/// degree above [`crate::MAX_CONNECT_DEGREE`], IllConditioned); an order
/// above [`MAX_GEOMETRIC_ORDER`] or shape values of the wrong count, not
/// finite, or `beta_1 <= 0` (InvalidArgument / LengthMismatch naming
/// `p_shape` or `q_shape`); no shape values with which the solve succeeds
/// and the curvature is defined (IllConditioned).
pub fn connect_geometric_curve<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &GeometricOptions,
) -> Result<GeometricCurve> {
    for (name, order) in [("p_order", options.p_order), ("q_order", options.q_order)] {
        if order > MAX_GEOMETRIC_ORDER {
            return Err(BezjoinError::invalid(
                name,
                format!("{order} is above the largest geometric order {MAX_GEOMETRIC_ORDER}"),
            ));
        }
    }
    if let Some(shape) = &options.p_shape {
        check_shape("p_shape", shape, options.p_order)?;
    }
    if let Some(shape) = &options.q_shape {
        check_shape("q_shape", shape, options.q_order)?;
    }
    if let (Some(ps), Some(qs), true) = (
        &options.p_shape,
        &options.q_shape,
        options.constraints.is_empty(),
    ) {
        // The checks of `prepare` in its order, then the end path.
        check_pair(p, u0, q, v0)?;
        check_connect_degree(options.p_order, options.q_order, [])?;
        let (kp, kq) = (options.p_order, options.q_order);
        if let Some(connection) = connect_ends_shaped(p, u0, q, v0, kp, kq, ps, qs) {
            return Ok(GeometricCurve::new(ps.clone(), qs.clone(), connection?));
        }
    }
    let mut connect_options = ConnectOptions::new(options.p_order, options.q_order);
    connect_options.constraints = options.constraints.clone();
    let problem = prepare(p, u0, q, v0, &connect_options)?;
    check_regular_ends(
        (u0, zero_tangent(&problem.p_derivatives)),
        (v0, zero_tangent(&problem.q_derivatives)),
        (options.p_order, options.q_order),
    )?;
    let (p_shape, q_shape, connection) = match (&options.p_shape, &options.q_shape) {
        (Some(ps), Some(qs)) => {
            let connection = solve_with_shapes(&problem, (u0, v0), ps, qs)?;
            (ps.clone(), qs.clone(), connection)
        }
        _ => {
            check_ends_apart(&problem, u0, v0)?;
            // The input's part before the search (no shape value changes
            // it; the winner's targets are checked in full).
            check_targets_condition(
                (
                    &problem.p_derivatives,
                    &problem.p_derivative_error,
                    None,
                    u0,
                ),
                (
                    &problem.q_derivatives,
                    &problem.q_derivative_error,
                    None,
                    v0,
                ),
                (options.p_order, options.q_order, problem.degree),
            )?;
            let search = |checked: bool| {
                fair::fair_shapes(
                    &problem,
                    options.p_shape.as_deref(),
                    options.q_shape.as_deref(),
                    checked,
                )
            };
            // Trials skip connect's residual check; the winner is solved
            // and checked in full. Should it be refused, the search is
            // repeated with every trial checked (a refused trial counting
            // as infinitely bad), and its winner solved and checked again.
            let (ps, qs) = search(false)?;
            match solve_with_shapes(&problem, (u0, v0), &ps, &qs) {
                Ok(connection) => (ps, qs, connection),
                Err(_) => {
                    let (ps, qs) = search(true)?;
                    let connection = solve_with_shapes(&problem, (u0, v0), &ps, &qs)?;
                    (ps, qs, connection)
                }
            }
        }
    };
    Ok(GeometricCurve::new(p_shape, q_shape, connection))
}

/// [`connect_geometric`] with its [`FairnessReport`]: the curve of
/// [`connect_geometric_curve`] and [`fairness_report`] of it (energy,
/// curvature range and extrema on [`ENERGY_PANELS`] panels and
/// [`CURVATURE_SAMPLES`] samples, which cost far more than the solve with
/// given shape values: callers that do not need the report should call
/// [`connect_geometric_curve`]).
///
/// Errors: those of [`connect_geometric_curve`].
pub fn connect_geometric<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    u0: f64,
    q: &Q,
    v0: f64,
    options: &GeometricOptions,
) -> Result<GeometricConnection> {
    let g = connect_geometric_curve(p, u0, q, v0, options)?;
    let report = fairness_report(&g.curve);
    Ok(GeometricConnection {
        curve: g.curve,
        p_shape: g.p_shape,
        q_shape: g.q_shape,
        report,
        max_residual: g.max_residual,
        error_estimate: g.error_estimate,
    })
}

#[cfg(test)]
mod end_path_tests {
    use super::*;
    use crate::nurbs::NurbsCurve;

    /// The end path of [`connect_geometric_curve`] (given shapes, no
    /// interior constraints) equals the general path (`prepare` +
    /// `solve_with_shapes`) bit for bit: control points, residual and
    /// estimate, or the same error, on random Bezier and NURBS pairs of
    /// dimensions 1 to 6 (5 and 6 take the general path inside too), every
    /// order up to [`MAX_GEOMETRIC_ORDER`], parameters at the ends and
    /// inside, shape values of both signs after `beta_1`.
    #[test]
    fn end_path_equals_the_general_path_on_random_cases() {
        let mut values = crate::test_values::Values(2026);
        let mut agreed = 0;
        for case in 0..400 {
            let mut pick = |below: usize| ((values.unit() * below as f64) as usize).min(below - 1);
            let dim = 1 + pick(6);
            let (np, nq) = (pick(10), pick(10));
            let (kp, kq) = (pick(MAX_GEOMETRIC_ORDER + 1), pick(MAX_GEOMETRIC_ORDER + 1));
            let (u_choice, v_choice, nurbs) = (pick(4), pick(4), pick(3) == 0);
            let mut draws = crate::test_values::Values(11 + case as u64);
            let mut curve = |degree: usize, offset: f64| {
                let points: Vec<f64> = (0..(degree + 1) * dim)
                    .map(|_| offset + 4.0 * draws.signed())
                    .collect();
                BezierCurve::new(dim, degree, points).unwrap()
            };
            let (p, q) = (curve(np, 0.0), curve(nq, 3.0));
            let mut shape = |order: usize| -> Vec<f64> {
                (0..order)
                    .map(|i| {
                        if i == 0 {
                            0.2 + 2.0 * draws.unit()
                        } else {
                            2.0 * draws.signed()
                        }
                    })
                    .collect()
            };
            let (ps, qs) = (shape(kp), shape(kq));
            let parameter = |choice: usize, value: f64| match choice {
                0 => 0.0,
                1 => 1.0,
                _ => value,
            };
            let u0 = parameter(u_choice, draws.unit());
            let v0 = parameter(v_choice, draws.unit());
            let options = GeometricOptions::new(kp, kq).with_shapes(ps.clone(), qs.clone());
            let label = format!("case {case}: dim {dim} {np}/{nq} G{kp}/G{kq} {u0}/{v0}");
            let (fast, problem) = if nurbs {
                let (p, q) = (NurbsCurve::from_bezier(&p), NurbsCurve::from_bezier(&q));
                let fast = connect_geometric_curve(&p, u0, &q, v0, &options);
                (
                    fast,
                    prepare(&p, u0, &q, v0, &ConnectOptions::new(kp, kq)).unwrap(),
                )
            } else {
                let fast = connect_geometric_curve(&p, u0, &q, v0, &options);
                (
                    fast,
                    prepare(&p, u0, &q, v0, &ConnectOptions::new(kp, kq)).unwrap(),
                )
            };
            // A zero tangent at an end of order >= 1 (a degree-0 input) is
            // refused before either path solves.
            if zero_tangent(&problem.p_derivatives) || zero_tangent(&problem.q_derivatives) {
                match &fast {
                    Err(BezjoinError::IllConditioned { what, .. }) => {
                        assert!(what.contains("is zero"), "{label}: {what}")
                    }
                    other => panic!("{label}: {other:?}"),
                }
                continue;
            }
            let general = solve_with_shapes(&problem, (u0, v0), &ps, &qs);
            if let Ok(g) = &fast {
                assert_eq!((&g.p_shape, &g.q_shape), (&ps, &qs), "{label}");
            }
            agreed += usize::from(crate::connect::assert_same_answer(
                &label,
                fast.as_ref()
                    .map(|g| (g.curve.points().to_vec(), g.max_residual, g.error_estimate)),
                general
                    .as_ref()
                    .map(|c| (c.curve.points().to_vec(), c.max_residual, c.error_estimate)),
            ));
        }
        // Most cases are answered (not a test of two identical refusals).
        assert!(agreed > 250, "only {agreed} answered cases");
    }

    /// The fixed-array Bell polynomials are those of [`partial_bell`].
    #[test]
    fn small_bell_table_equals_partial_bell() {
        let mut values = crate::test_values::Values(5);
        for order in 0..=MAX_GEOMETRIC_ORDER {
            let x: Vec<f64> = (0..order.max(1)).map(|_| 3.0 * values.signed()).collect();
            let (small, big) = (partial_bell_small(&x, order), partial_bell(&x, order));
            for j in 0..=MAX_GEOMETRIC_ORDER {
                for i in 0..=MAX_GEOMETRIC_ORDER {
                    let expected = if i <= order && j <= order {
                        big[(j, i)]
                    } else {
                        0.0
                    };
                    assert_eq!(
                        small[j][i].to_bits(),
                        expected.to_bits(),
                        "order {order} ({j}, {i})"
                    );
                }
            }
        }
    }
}
