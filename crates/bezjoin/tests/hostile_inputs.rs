//! Hostile inputs at every public entry point of the core (issue 14, item 2).
//!
//! Families: coordinates spanning `1e-300 ..= 1e300` within one curve
//! (random signs and exponents), all control points equal, repeated
//! consecutive points, collinear points, degree 40..=60; parameters,
//! setbacks, scales and accuracies include denormals (`5e-324`, `1e-310`).
//!
//! The oracle, for every call: no panic (caught with `catch_unwind` and
//! reported with the entry point and the input), an `Ok` whose every number
//! is finite or an `Err` with a non-empty message, and no call longer than
//! [`HANG_LIMIT`]. The time bound is a hang detector, not a speed goal: it is
//! generous (2 s, for a debug build on a loaded 2-core machine) where the
//! slowest call measured takes a small fraction of it.
//!
//! Functions that return plain numbers (evaluation, derivatives) cannot
//! report an error; they are held to finiteness where the exact answer is
//! within the `f64` range by an a-priori bound (evaluation at `t` in `[0, 1]`
//! is a convex combination of the control points; the `k`-th derivative is
//! at most `(2n)^k max|P_i|`).
//!
//! Every test runs a fixed number of cases from a fixed seed (ChaCha,
//! [`TestRng::deterministic_rng`], no failure persistence), so one commit
//! gives one verdict.

use std::fmt::Debug;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use bezjoin_core::{
    BSplineCurve, BezierCurve, BezjoinError, Breakpoints, ChainFillet, ChainFilletOptions,
    ChainMerge, ChainMergeOptions, ConnectOptions, Connection, Curve, DeviationFillet,
    DeviationFilletOptions, Fillet, FilletOptions, GeometricConnection, GeometricOptions,
    IntersectOptions, Intersection, IntersectionKind, KeepPoint, LagrangeOptions, LagrangeSpline,
    Merge, MergeMetric, MergeOptions, NurbsCurve, PointConstraint, RadiusChainFillet, RadiusFillet,
    bezier_from_lagrange_points, chord_length_params, connect, connect_dense_reference,
    connect_geometric, connect_unchecked, distance_to_curve, ellipse_arc, fairness_energy, fillet,
    fillet_at, fillet_chain, fillet_radius, fillet_radius_chain, fillet_vertex,
    fillet_within_deviation, intersect, lagrange_points_of_bezier, lagrange_spline, merge,
    merge_chain, merge_metric_at,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

/// One call taking longer than this is a hang (see the module documentation):
/// 2 s in an optimized build (`cargo test --release`, where the slowest call
/// takes well under 0.1 s), 40 s in an unoptimized one, whose nalgebra
/// solves run 20 to 50 times slower (the slowest debug call, a degree-55
/// merge, takes a few seconds on a loaded 2-core machine).
const HANG_LIMIT: Duration = if cfg!(debug_assertions) {
    Duration::from_secs(40)
} else {
    Duration::from_secs(2)
};

thread_local! {
    /// The slowest call of the running test (each test runs on its own
    /// thread): duration and entry point, printed at the end of the test.
    static SLOWEST: std::cell::RefCell<(Duration, String)> =
        const { std::cell::RefCell::new((Duration::ZERO, String::new())) };
}

/// Cases per test (`HOSTILE_CASES` overrides it for a longer exploratory
/// run; the seed stays fixed, so a given count gives one verdict).
const CASES: u32 = 64;

fn cases() -> u32 {
    std::env::var("HOSTILE_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(CASES)
}

// ---------------------------------------------------------------------------
// The oracle.

/// Every number a result carries, for the finiteness check.
trait Numbers {
    fn numbers(&self, out: &mut Vec<f64>);
}

impl Numbers for f64 {
    fn numbers(&self, out: &mut Vec<f64>) {
        out.push(*self);
    }
}

impl Numbers for usize {
    fn numbers(&self, _: &mut Vec<f64>) {}
}

impl<T: Numbers> Numbers for Vec<T> {
    fn numbers(&self, out: &mut Vec<f64>) {
        for v in self {
            v.numbers(out);
        }
    }
}

impl<A: Numbers, B: Numbers> Numbers for (A, B) {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.0.numbers(out);
        self.1.numbers(out);
    }
}

impl Numbers for BezierCurve {
    fn numbers(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self.points());
    }
}

impl Numbers for BSplineCurve {
    fn numbers(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self.knots());
        out.extend_from_slice(self.points());
    }
}

impl Numbers for Connection {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.curve.numbers(out);
        out.extend([
            self.p_scale,
            self.q_scale,
            self.max_residual,
            self.error_estimate,
            self.constraint_condition,
        ]);
    }
}

impl Numbers for Intersection {
    fn numbers(&self, out: &mut Vec<f64>) {
        out.extend([self.u, self.v, self.distance]);
        out.extend_from_slice(&self.point);
        if let IntersectionKind::Overlap { u_range, v_range } = self.kind {
            out.extend([u_range.0, u_range.1, v_range.0, v_range.1]);
        }
    }
}

impl Numbers for Curve {
    fn numbers(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self.points());
    }
}

impl Numbers for Fillet {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.p_trimmed.numbers(out);
        self.blend.numbers(out);
        self.q_trimmed.numbers(out);
        self.crossing.numbers(out);
        out.extend([
            self.u0,
            self.v0,
            self.p_scale,
            self.q_scale,
            self.max_residual,
        ]);
    }
}

/// The curve and shape values (the report's energy is infinite for a
/// blend with a cusp, which given shape values may ask for).
impl Numbers for GeometricConnection {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.curve.numbers(out);
        out.extend_from_slice(&self.p_shape);
        out.extend_from_slice(&self.q_shape);
        out.extend([self.max_residual, self.error_estimate]);
    }
}

impl Numbers for RadiusFillet {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.p_trimmed.numbers(out);
        self.blend.numbers(out);
        self.q_trimmed.numbers(out);
        out.extend_from_slice(&self.arc_centre);
        out.extend_from_slice(&self.p_shape);
        out.extend_from_slice(&self.q_shape);
        out.extend([self.u0, self.v0, self.arc_deviation]);
    }
}

impl Numbers for RadiusChainFillet {
    fn numbers(&self, out: &mut Vec<f64>) {
        for piece in &self.pieces {
            piece.numbers(out);
        }
        for c in &self.corners {
            out.extend_from_slice(&c.arc_centre);
            out.extend_from_slice(&c.p_shape);
            out.extend_from_slice(&c.q_shape);
            out.extend([c.u0, c.v0, c.arc_deviation]);
        }
    }
}

impl Numbers for DeviationFillet {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.fillet.numbers(out);
        out.extend([
            self.p_setback,
            self.q_setback,
            self.deviation,
            self.deviation_parameter,
        ]);
    }
}

impl Numbers for ChainFillet {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.pieces.numbers(out);
        for c in &self.corners {
            c.crossing.numbers(out);
            out.extend([c.u0, c.v0, c.scales.0, c.scales.1, c.max_residual]);
        }
    }
}

impl Numbers for Merge {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.merged.numbers(out);
        self.p_hat.numbers(out);
        self.q_hat.numbers(out);
        let r = &self.report;
        out.extend([
            r.mu,
            r.metric_value,
            r.max_deviation,
            r.solve_error_estimate,
            r.split_check_error,
        ]);
    }
}

impl Numbers for ChainMerge {
    fn numbers(&self, out: &mut Vec<f64>) {
        self.merged.numbers(out);
        self.pieces.numbers(out);
        let r = &self.report;
        out.extend_from_slice(&r.breakpoints);
        out.extend([
            r.metric_value,
            r.max_deviation,
            r.solve_error_estimate,
            r.split_check_error,
        ]);
    }
}

impl Numbers for LagrangeSpline {
    fn numbers(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self.params());
        for i in 0..self.segment_count() {
            out.extend_from_slice(self.on_curve_points(i));
        }
        self.segments().to_vec().numbers(out);
        out.extend([
            self.error_growth(),
            self.relative_error_estimate(),
            self.max_continuity_residual(),
        ]);
    }
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(non-string panic payload)".to_string()
    }
}

/// Run `f` under the oracle: no panic, no hang. `Ok(Ok(v))` or `Ok(Err(e))`
/// with a non-empty message; a violation is a test failure naming `name`
/// and `input`.
fn guarded<T>(
    name: &str,
    input: &dyn Debug,
    f: impl FnOnce() -> T,
) -> std::result::Result<T, TestCaseError> {
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(f));
    let elapsed = start.elapsed();
    SLOWEST.with(|slowest| {
        let mut slowest = slowest.borrow_mut();
        if elapsed > slowest.0 {
            *slowest = (elapsed, name.to_string());
        }
    });
    let value = result.map_err(|payload| {
        TestCaseError::fail(format!(
            "{name} panicked ({}) on {input:?}",
            panic_message(payload.as_ref())
        ))
    })?;
    if elapsed > HANG_LIMIT {
        return Err(TestCaseError::fail(format!(
            "{name} took {elapsed:?} (> {HANG_LIMIT:?}: a hang) on {input:?}"
        )));
    }
    Ok(value)
}

/// [`guarded`] for a fallible call: an `Ok` must carry only finite numbers,
/// an `Err` a non-empty message. Returns the value when `Ok`.
fn checked<T: Numbers>(
    name: &str,
    input: &dyn Debug,
    f: impl FnOnce() -> Result<T, BezjoinError>,
) -> std::result::Result<Option<T>, TestCaseError> {
    match guarded(name, input, f)? {
        Ok(v) => {
            require_finite(name, input, &v)?;
            Ok(Some(v))
        }
        Err(e) => {
            if e.to_string().trim().is_empty() {
                return Err(TestCaseError::fail(format!(
                    "{name} returned an error with an empty message ({e:?}) on {input:?}"
                )));
            }
            Ok(None)
        }
    }
}

fn require_finite<T: Numbers>(
    name: &str,
    input: &dyn Debug,
    v: &T,
) -> std::result::Result<(), TestCaseError> {
    let mut numbers = Vec::new();
    v.numbers(&mut numbers);
    if let Some(i) = numbers.iter().position(|x| !x.is_finite()) {
        return Err(TestCaseError::fail(format!(
            "{name} returned Ok with a non-finite number ({} at position {i}) on {input:?}",
            numbers[i]
        )));
    }
    Ok(())
}

/// Run `test` on `CASES` inputs of `strategy` from a fixed seed.
fn run<S: Strategy>(
    name: &str,
    strategy: S,
    test: impl Fn(S::Value) -> std::result::Result<(), TestCaseError>,
) where
    S::Value: Debug,
{
    let config = Config {
        cases: cases(),
        failure_persistence: None,
        // Shrinking re-runs failing cases; keep it short so a failure
        // report arrives quickly.
        max_shrink_iters: 16,
        ..Config::default()
    };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let verdict = runner.run(&strategy, test);
    SLOWEST.with(|slowest| {
        let slowest = slowest.borrow();
        eprintln!(
            "{name}: {} cases, slowest call {:?} ({})",
            cases(),
            slowest.0,
            slowest.1
        );
    });
    if let Err(e) = verdict {
        panic!("{name}: {e}");
    }
}

// ---------------------------------------------------------------------------
// The input families.

/// Which family a curve comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Family {
    /// Coordinates `±m 10^e`, `e` in `-300..=300`.
    Span,
    /// Every control point the same.
    AllEqual,
    /// Consecutive control points repeated.
    Repeated,
    /// Control points on one line.
    Collinear,
    /// Degree 40..=60.
    HighDegree,
}

/// A curve of one family: its degree and row-major points (built inside the
/// test, so the constructor is under the oracle too).
#[derive(Debug, Clone)]
struct Hostile {
    // Read through `Debug` only: failure reports name the family.
    #[allow(dead_code)]
    family: Family,
    dim: usize,
    degree: usize,
    points: Vec<f64>,
}

impl Hostile {
    fn curve(&self) -> std::result::Result<BezierCurve, TestCaseError> {
        let c = checked("BezierCurve::new", self, || {
            BezierCurve::new(self.dim, self.degree, self.points.clone())
        })?;
        c.ok_or_else(|| TestCaseError::fail(format!("BezierCurve::new refused {self:?}")))
    }
}

/// `±m 10^e`, `m` in `[1, 10)`, `e` in `-300..=300`.
fn span_coordinate() -> impl Strategy<Value = f64> {
    (any::<bool>(), 1.0f64..10.0, -300i32..=300).prop_map(|(negative, m, e)| {
        let v = m * 10f64.powi(e);
        if negative { -v } else { v }
    })
}

fn ordinary_coordinate() -> impl Strategy<Value = f64> {
    -10.0f64..10.0
}

fn any_coordinate() -> BoxedStrategy<f64> {
    prop_oneof![span_coordinate(), ordinary_coordinate()].boxed()
}

/// A curve of any family in dimension `dim`.
fn hostile(dim: usize) -> BoxedStrategy<Hostile> {
    let span = (1usize..=8)
        .prop_flat_map(move |n| {
            (
                Just(n),
                prop::collection::vec(span_coordinate(), (n + 1) * dim),
            )
        })
        .prop_map(move |(degree, points)| Hostile {
            family: Family::Span,
            dim,
            degree,
            points,
        });
    let all_equal =
        (0usize..=8, prop::collection::vec(any_coordinate(), dim)).prop_map(move |(degree, p)| {
            Hostile {
                family: Family::AllEqual,
                dim,
                degree,
                points: p.repeat(degree + 1),
            }
        });
    let repeated = prop::collection::vec(
        (prop::collection::vec(any_coordinate(), dim), 1usize..=3),
        2..=5,
    )
    .prop_map(move |runs| {
        let mut points = Vec::new();
        for (p, times) in &runs {
            for _ in 0..*times {
                points.extend_from_slice(p);
            }
        }
        Hostile {
            family: Family::Repeated,
            dim,
            degree: points.len() / dim - 1,
            points,
        }
    });
    let collinear = (
        prop::collection::vec(any_coordinate(), dim),
        prop::collection::vec(any_coordinate(), dim),
        prop::collection::vec(-2.0f64..2.0, 2..=9),
    )
        .prop_map(move |(a, dir, s)| {
            let mut points = Vec::new();
            for si in &s {
                for c in 0..dim {
                    points.push(a[c] + si * dir[c]);
                }
            }
            Hostile {
                family: Family::Collinear,
                dim,
                degree: s.len() - 1,
                points,
            }
        });
    let high_degree = (40usize..=60, any::<bool>())
        .prop_flat_map(move |(n, wide)| {
            let coordinate = if wide {
                span_coordinate().boxed()
            } else {
                ordinary_coordinate().boxed()
            };
            (Just(n), prop::collection::vec(coordinate, (n + 1) * dim))
        })
        .prop_map(move |(degree, points)| Hostile {
            family: Family::HighDegree,
            dim,
            degree,
            points,
        });
    prop_oneof![span, all_equal, repeated, collinear, high_degree].boxed()
}

/// A parameter in `[0, 1]`, often a denormal or an end.
fn unit_param() -> BoxedStrategy<f64> {
    prop_oneof![
        Just(0.0),
        Just(5e-324),
        Just(1e-310),
        Just(f64::MIN_POSITIVE),
        Just(1.0 - f64::EPSILON / 2.0),
        Just(1.0),
        Just(0.5),
        0.0f64..=1.0,
    ]
    .boxed()
}

/// A parameter in the open interval `(0, 1)`, often a denormal.
fn open_param() -> BoxedStrategy<f64> {
    prop_oneof![
        Just(5e-324),
        Just(1e-310),
        Just(f64::MIN_POSITIVE),
        Just(1.0 - f64::EPSILON / 2.0),
        Just(0.5),
        0.001f64..0.999,
    ]
    .boxed()
}

/// A positive scalar (setback, scale, accuracy): denormal, tiny, huge or ordinary.
fn positive() -> BoxedStrategy<f64> {
    prop_oneof![
        Just(5e-324),
        Just(1e-310),
        Just(1e-300),
        Just(1e300),
        Just(1.0),
        1e-3f64..10.0,
    ]
    .boxed()
}

/// `(2n)^k max|P_i|`: a bound on `|P^(k)(t)|` for `t` in `[0, 1]`.
fn derivative_bound(c: &BezierCurve, k: usize) -> f64 {
    let scale = c.points().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    scale * (2.0 * c.degree().max(1) as f64).powi(k as i32)
}

/// Bounds below this are "clearly inside the f64 range" (room for rounding
/// and the Euclidean sums of the checks).
const SAFE: f64 = 1e300;

/// P rotated by 90 degrees about `P(1/2)` in its first two coordinates: a
/// partner that crosses `P` there whenever `P` is not degenerate.
fn rotated(p: &BezierCurve) -> BezierCurve {
    let c = p.eval(0.5);
    let d = p.dim();
    let mut pts = p.points().to_vec();
    for i in 0..=p.degree() {
        let (x, y) = (pts[i * d] - c[0], pts[i * d + 1] - c[1]);
        pts[i * d] = c[0] - y;
        pts[i * d + 1] = c[1] + x;
    }
    // Rotation can only overflow when P's coordinates are near f64::MAX,
    // which the families do not reach.
    BezierCurve::new(d, p.degree(), pts).expect("finite rotated curve")
}

// ---------------------------------------------------------------------------
// The properties, one test per group of entry points.

#[test]
fn curve_operations_survive_hostile_inputs() {
    let strategy = (
        (1usize..=3).prop_flat_map(hostile),
        unit_param(),
        unit_param(),
        0usize..=6,
        0usize..=20,
        positive(),
    );
    run(
        "curve operations",
        strategy,
        |(h, t, s, order, raise, accuracy)| {
            let c = h.curve()?;
            let input = (&h, t, s, order, raise, accuracy);
            let rows: Vec<Vec<f64>> = (0..=c.degree()).map(|i| c.point(i).to_vec()).collect();
            checked("BezierCurve::from_rows", &input, || {
                BezierCurve::from_rows(&rows)
            })?;
            // Convex combinations of the control points: always finite.
            let v = guarded("BezierCurve::eval", &input, || c.eval(t))?;
            require_finite("BezierCurve::eval", &input, &v)?;
            let v = guarded("BezierCurve::eval_de_casteljau", &input, || {
                c.eval_de_casteljau(t)
            })?;
            require_finite("BezierCurve::eval_de_casteljau", &input, &v)?;
            let v = guarded("lagrange_points_of_bezier", &input, || {
                lagrange_points_of_bezier(&c)
            })?;
            require_finite("lagrange_points_of_bezier", &input, &v)?;
            let v = guarded("BezierCurve::reverse", &input, || c.reverse())?;
            require_finite("BezierCurve::reverse", &input, &v)?;
            checked("BezierCurve::split_at", &input, || c.split_at(t))?;
            checked("BezierCurve::segment", &input, || c.segment(t, s))?;
            checked("BezierCurve::segment (extrapolated)", &input, || {
                c.segment(-t, 1.0 + s)
            })?;
            checked("BezierCurve::elevate_degree", &input, || {
                c.elevate_degree(c.degree() + raise)
            })?;
            let v = guarded("BezierCurve::coordinate_scale", &input, || {
                c.coordinate_scale()
            })?;
            require_finite("BezierCurve::coordinate_scale", &input, &v)?;
            // Derivatives: finite wherever the exact values are well inside
            // the f64 range.
            let m = guarded("BezierCurve::eval_derivatives", &input, || {
                c.eval_derivatives(t, order)
            })?;
            let mut basis_form = vec![0.0; (order + 1) * c.dim()];
            guarded("BezierCurve::eval_derivatives_basis", &input, || {
                c.eval_derivatives_basis(t, order, &mut basis_form)
            })?;
            let hodograph = guarded("BezierCurve::hodograph", &input, || c.hodograph())?;
            let d = guarded("BezierCurve::derivative_at", &input, || {
                c.derivative_at(t, order)
            })?;
            for k in 0..=order {
                if derivative_bound(&c, k) < SAFE {
                    let row = m[k * c.dim()..(k + 1) * c.dim()].to_vec();
                    require_finite("BezierCurve::eval_derivatives", &input, &row)?;
                    let row = basis_form[k * c.dim()..(k + 1) * c.dim()].to_vec();
                    require_finite("BezierCurve::eval_derivatives_basis", &input, &row)?;
                }
            }
            if derivative_bound(&c, order) < SAFE {
                require_finite("BezierCurve::derivative_at", &input, &d)?;
            }
            if derivative_bound(&c, 1) < SAFE {
                require_finite("BezierCurve::hodograph", &input, &hodograph)?;
            }
            // Lengths.
            checked("BezierCurve::arc_length", &input, || {
                c.arc_length(t, s, accuracy)
            })?;
            let total = checked("BezierCurve::arc_length_default", &input, || {
                c.arc_length_default(0.0, 1.0)
            })?;
            for length in [0.5 * total.unwrap_or(1.0), -5e-324, 1e-310, s] {
                checked("BezierCurve::param_at_length", &input, || {
                    c.param_at_length(t, length, accuracy)
                })?;
            }
            let v = guarded("BezierCurve::max_distance_sampled", &input, || {
                c.max_distance_sampled(&c.reverse(), 8)
            })?;
            // The distance between two points inside the curve's hull.
            if derivative_bound(&c, 0) < 1e150 {
                require_finite("BezierCurve::max_distance_sampled", &input, &v)?;
            }
            Ok(())
        },
    );
}

#[test]
fn connect_survives_hostile_inputs() {
    let strategy = (
        (2usize..=3).prop_flat_map(|d| (hostile(d), hostile(d))),
        unit_param(),
        unit_param(),
        0usize..=3,
        0usize..=3,
        positive(),
        open_param(),
    );
    run(
        "connect",
        strategy,
        |((hp, hq), u0, v0, kp, kq, scale, t)| {
            let p = hp.curve()?;
            let q = hq.curve()?;
            let input = (&hp, &hq, u0, v0, kp, kq, scale, t);
            let options = ConnectOptions::new(kp, kq).with_scales(scale, 1.0);
            checked("connect", &input, || connect(&p, u0, &q, v0, &options))?;
            checked("connect_unchecked", &input, || {
                connect_unchecked(&p, u0, &q, v0, &options)
            })?;
            checked("connect_dense_reference", &input, || {
                connect_dense_reference(&p, u0, &q, v0, &options)
            })?;
            let auto = checked("connect (ShapeScale::Auto)", &input, || {
                connect(&p, u0, &q, v0, &options.clone().with_auto_scale())
            })?;
            if let Some(auto) = auto {
                let e = guarded("fairness_energy", &input, || fairness_energy(&auto.curve))?;
                // The energy of a curve with coordinates near 1e300 is
                // outside the f64 range; below 1e100 it is not.
                if derivative_bound(&auto.curve, 2) < 1e100 {
                    require_finite("fairness_energy", &input, &e)?;
                }
            }
            // An interior constraint at a (possibly denormal) parameter,
            // through the midpoint of the two ends.
            let mid: Vec<f64> = p
                .eval(u0)
                .iter()
                .zip(q.eval(v0))
                .map(|(a, b)| 0.5 * a + 0.5 * b)
                .collect();
            let constrained = options
                .clone()
                .with_constraint(PointConstraint::new(t, 0, mid));
            checked("connect (constraint)", &input, || {
                connect(&p, u0, &q, v0, &constrained)
            })?;
            checked("connect (ShapeScale::Auto, constraint)", &input, || {
                connect(&p, u0, &q, v0, &constrained.clone().with_auto_scale())
            })?;
            Ok(())
        },
    );
}

/// G^k connect (fair and given shapes) and the fillet by radius on the
/// hostile curves: no panic, no hang, finite curves or a named error.
#[test]
fn geometric_connect_and_radius_fillet_survive_hostile_inputs() {
    let strategy = (
        (2usize..=3).prop_flat_map(|d| (hostile(d), hostile(d))),
        unit_param(),
        unit_param(),
        0usize..=3,
        positive(),
        prop_oneof![Just(5e-324), Just(1e300), 0.001f64..0.5],
    );
    run(
        "geometric",
        strategy,
        |((hp, hq), u0, v0, k, beta, radius_fraction)| {
            let p = hp.curve()?;
            let q = hq.curve()?;
            let input = (&hp, &hq, u0, v0, k, beta, radius_fraction);
            checked("connect_geometric (fair)", &input, || {
                connect_geometric(&p, u0, &q, v0, &GeometricOptions::new(k, k))
            })?;
            let shape: Vec<f64> = (0..k).map(|j| if j == 0 { beta } else { -beta }).collect();
            checked("connect_geometric (given)", &input, || {
                connect_geometric(
                    &p,
                    u0,
                    &q,
                    v0,
                    &GeometricOptions::new(k, k).with_shapes(shape.clone(), shape.clone()),
                )
            })?;
            if p.dim() == 2 {
                let q = rotated(&p);
                let radius = (radius_fraction * p.coordinate_scale()).max(5e-324);
                checked("fillet_radius", &input, || {
                    fillet_radius(&p, &q, radius, k.max(1))
                })?;
                // A closed wire of the curve, its rotation and back: three
                // corners rounded by the same radius.
                let wire = [p.clone(), q.clone(), rotated(&q)];
                checked("fillet_radius_chain", &input, || {
                    fillet_radius_chain(&wire, radius, k.max(1), true)
                })?;
            }
            Ok(())
        },
    );
}

#[test]
fn intersect_survives_hostile_inputs() {
    let strategy = (
        (2usize..=3).prop_flat_map(|d| (hostile(d), hostile(d))),
        any::<bool>(),
        prop_oneof![Just(5e-324), Just(1e-310), Just(1e-9), Just(0.5)],
        prop_oneof![Just(0.0), Just(5e-324), Just(1e-6)],
    );
    run(
        "intersect",
        strategy,
        |((hp, hq), partner_is_rotation, distance_tolerance, tangent_tolerance)| {
            let p = hp.curve()?;
            let q = if partner_is_rotation {
                rotated(&p)
            } else {
                hq.curve()?
            };
            let input = (&hp, &hq, partner_is_rotation, distance_tolerance);
            checked("intersect", &input, || {
                intersect(&p, &q, &IntersectOptions::default())
            })?;
            let detailed = IntersectOptions {
                relative_distance_tolerance: distance_tolerance,
                tangent_tolerance,
                ..IntersectOptions::default()
            };
            checked("intersect (detailed options)", &input, || {
                intersect(&p, &q, &detailed)
            })?;
            checked("intersect (self)", &input, || {
                intersect(&p, &p, &IntersectOptions::default())
            })?;
            let (t, d) = guarded("distance_to_curve", &input, || {
                distance_to_curve(&p, &q.eval(0.5))
            })?;
            require_finite("distance_to_curve (parameter)", &input, &t)?;
            if derivative_bound(&p, 0) < 1e150 && derivative_bound(&q, 0) < 1e150 {
                require_finite("distance_to_curve (distance)", &input, &d)?;
            }
            Ok(())
        },
    );
}

#[test]
fn fillet_survives_hostile_inputs() {
    let strategy = (
        hostile(2),
        prop_oneof![
            Just(5e-324),
            Just(1e-310),
            Just(1e-300),
            Just(1e300),
            0.001f64..0.4
        ],
        0usize..=2,
        positive(),
    );
    run(
        "fillet",
        strategy,
        |(h, setback_fraction, order, deviation_fraction)| {
            let p = h.curve()?;
            let q = rotated(&p);
            let input = (&h, setback_fraction, order, deviation_fraction);
            // Setbacks relative to the curve's size (a denormal fraction
            // gives a denormal or tiny setback).
            let size = p.coordinate_scale();
            let setback = (setback_fraction * size).max(5e-324);
            let options = FilletOptions::symmetric(setback, order);
            let f = checked("fillet", &input, || fillet(&p, &q, &options))?;
            checked("fillet (auto scale)", &input, || {
                fillet(&p, &q, &options.clone().with_auto_scale())
            })?;
            checked("fillet (denormal setbacks)", &input, || {
                fillet(&p, &q, &FilletOptions::new(5e-324, 1e-310, order, order))
            })?;
            if let Some(f) = f {
                checked("Fillet::to_bspline", &input, || f.to_bspline())?;
                checked("fillet_at", &input, || {
                    fillet_at(&p, &q, &f.crossing, &options)
                })?;
            }
            let deviation = (deviation_fraction.min(1.0) * 1e-3 * size).max(5e-324);
            checked("fillet_within_deviation", &input, || {
                fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(deviation, order))
            })?;
            checked("fillet_within_deviation (denormal)", &input, || {
                fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(5e-324, order))
            })?;
            // A chain P, rot(P), P: two corners.
            checked("fillet_chain", &input, || {
                fillet_chain(
                    &[p.clone(), q.clone(), p.clone()],
                    &ChainFilletOptions::open(options.clone()),
                )
            })?;
            checked("fillet_chain (closed)", &input, || {
                fillet_chain(
                    &[p.clone(), q.clone()],
                    &ChainFilletOptions::closed(options.clone()),
                )
            })?;
            Ok(())
        },
    );
}

#[test]
fn merge_survives_hostile_inputs() {
    let strategy = (
        (1usize..=3).prop_flat_map(|d| (hostile(d), hostile(d))),
        any::<bool>(),
        open_param(),
        unit_param(),
        any::<bool>(),
    );
    run(
        "merge",
        strategy,
        |((hp, hq), split_one_curve, mu, keep_param, integral)| {
            let a = hp.curve()?;
            // Either the two pieces of one curve (mergeable exactly) or two
            // unrelated curves.
            let (p, q) = if split_one_curve {
                match checked("BezierCurve::split_at", &hp, || a.split_at(mu))? {
                    Some(pieces) => pieces,
                    None => return Ok(()),
                }
            } else {
                (a, hq.curve()?)
            };
            let input = (&hp, &hq, split_one_curve, mu, keep_param, integral);
            let metric = if integral {
                MergeMetric::Integral
            } else {
                MergeMetric::Discrete
            };
            let base = MergeOptions::default().with_metric(metric);
            for split in [
                Breakpoints::Uniform,
                Breakpoints::Given(vec![mu]),
                Breakpoints::PolygonLength,
            ] {
                checked("merge", &(&input, split.clone()), || {
                    merge(&p, &q, &base.clone().with_split(split))
                })?;
            }
            // The optimal-mu search costs up to ~130 solves: only at modest
            // degree so the case count stays affordable.
            if p.degree().max(q.degree()) <= 12 {
                checked("merge (optimal mu)", &input, || {
                    merge(&p, &q, &base.clone().with_split(Breakpoints::Optimal))
                })?;
            }
            let constrained = MergeOptions {
                fix_ends: true,
                p_points: vec![KeepPoint {
                    param: keep_param,
                    max_order: 0,
                }],
                degree: Some(p.degree().max(q.degree()) + 1),
                ..base.clone()
            };
            checked("merge (constraints)", &input, || {
                merge(&p, &q, &constrained)
            })?;
            checked("merge_metric_at", &input, || {
                merge_metric_at(&p, &q, &base, mu)
            })?;
            for breakpoints in [
                Breakpoints::Uniform,
                Breakpoints::PolygonLength,
                Breakpoints::Given(vec![mu]),
            ] {
                let options = ChainMergeOptions {
                    metric,
                    breakpoints: breakpoints.clone(),
                    ..ChainMergeOptions::default()
                };
                checked("merge_chain", &(&input, &breakpoints), || {
                    merge_chain(&[p.clone(), q.clone()], &options)
                })?;
            }
            Ok(())
        },
    );
}

#[test]
fn lagrange_and_bspline_survive_hostile_inputs() {
    let strategy = (
        (1usize..=3).prop_flat_map(hostile),
        3usize..=5,
        any::<bool>(),
        unit_param(),
        prop_oneof![Just(5e-324), Just(1e-310), Just(1e-300), 0.1f64..10.0],
    );
    run(
        "lagrange and B-spline",
        strategy,
        |(h, degree, chord, t, interval)| {
            let c = h.curve()?;
            let input = (&h, degree, chord, t, interval);
            let dim = c.dim();
            let points = c.points();
            checked("bezier_from_lagrange_points", &input, || {
                bezier_from_lagrange_points(dim, points)
            })?;
            checked("chord_length_params", &input, || {
                chord_length_params(dim, points)
            })?;
            // The control points as nodes; inner points from the family too
            // (cycled), so they are as hostile as the nodes.
            let options = LagrangeOptions::default().with_degree(degree);
            let count = c.point_count();
            if count >= 2 {
                let pick = |i: usize| points[i % points.len()];
                let start: Vec<f64> = (0..(degree - 1) * dim).map(|i| pick(i + dim)).collect();
                let free: Vec<f64> = (0..(count - 2) * options.free_points_per_segment() * dim)
                    .map(|i| pick(i + 2 * dim))
                    .collect();
                let params: Vec<f64> = (0..count).map(|i| i as f64 * interval).collect();
                let params = if chord { None } else { Some(&params[..]) };
                let spline = checked("lagrange_spline", &input, || {
                    lagrange_spline(dim, points, params, &start, &free, &options)
                })?;
                if let Some(spline) = spline {
                    checked("LagrangeSpline::to_bspline", &input, || spline.to_bspline())?;
                    checked("LagrangeSpline::construction_data", &input, || {
                        spline.construction_data(&options)
                    })?;
                }
            }
            // B-splines: the curve's halves as a chain with (possibly
            // denormal) intervals, then evaluated.
            let (left, right) = c.split_at(0.5).map_err(|e| {
                TestCaseError::fail(format!("split_at(0.5) refused {input:?}: {e}"))
            })?;
            let spline = checked("BSplineCurve::from_bezier_chain", &input, || {
                BSplineCurve::from_bezier_chain(&[left, right], &[interval, 1.0])
            })?;
            if let Some(b) = spline {
                let x = t * (interval + 1.0);
                let m = guarded("BSplineCurve::eval_derivatives", &input, || {
                    b.eval_derivatives(x, 0)
                })?;
                require_finite("BSplineCurve::eval_derivatives", &input, &m)?;
                guarded("BSplineCurve::continuity_at", &input, || {
                    b.continuity_at(interval, 1e-9)
                })?;
                checked("BSplineCurve::new", &input, || {
                    BSplineCurve::new(
                        dim,
                        b.degree(),
                        b.points().to_vec(),
                        None,
                        b.knots().to_vec(),
                    )
                })?;
            }
            Ok(())
        },
    );
}

// ---------------------------------------------------------------------------
// NURBS curves (issue 16): the families above as poles, with hostile knot
// vectors and weights.

/// How the knots of a hostile NURBS curve are laid out.
#[derive(Debug, Clone, Copy)]
enum KnotFamily {
    /// Clamped, interior knots repeated up to the degree.
    ClampedRepeated,
    /// Unclamped and uniform.
    Uniform,
    /// Knot intervals near the smallest with a finite reciprocal.
    Tiny,
    /// Knot values near 1e300.
    Huge,
}

/// A NURBS curve of a hostile family (built inside the test).
#[derive(Debug, Clone)]
struct HostileNurbs {
    poles: Hostile,
    degree: usize,
    knots: KnotFamily,
    weights: Option<Vec<f64>>,
    /// Random numbers for the knot layout.
    draws: Vec<f64>,
}

impl HostileNurbs {
    fn knot_vector(&self, count: usize) -> Vec<f64> {
        let p = self.degree;
        let len = count + p + 1;
        let (start, step) = match self.knots {
            KnotFamily::Tiny => (0.0, 1e-300),
            KnotFamily::Huge => (1e300, 1e285),
            _ => (-1.0, 0.5),
        };
        let mut knots = Vec::with_capacity(len);
        match self.knots {
            KnotFamily::Uniform => {
                for i in 0..len {
                    knots.push(start + step * i as f64);
                }
            }
            _ => {
                knots.extend(std::iter::repeat_n(start, p + 1));
                // Fewer than p + 1 poles (a point raised to degree 1): the
                // constructor refuses the curve, whatever the knots.
                let interior = len.saturating_sub(2 * (p + 1));
                let mut x = start;
                let mut i = 0;
                while i < interior {
                    x += step * (0.5 + self.draws[i % self.draws.len()]);
                    let m = (1 + (self.draws[(i + 1) % self.draws.len()] * p as f64) as usize)
                        .min(p)
                        .min(interior - i);
                    knots.extend(std::iter::repeat_n(x, m));
                    i += m;
                }
                x += step;
                knots.extend(std::iter::repeat_n(x, p + 1));
            }
        }
        knots
    }

    fn curve(&self) -> std::result::Result<Option<NurbsCurve>, TestCaseError> {
        let count = self.poles.points.len() / self.poles.dim;
        let weights = self
            .weights
            .as_ref()
            .map(|w| w.iter().cycle().take(count).copied().collect());
        checked("NurbsCurve::new", self, || {
            NurbsCurve::new(
                self.poles.dim,
                self.degree,
                self.poles.points.clone(),
                weights,
                self.knot_vector(count),
            )
        })
    }
}

fn hostile_nurbs(dim: usize) -> BoxedStrategy<HostileNurbs> {
    let weights = prop_oneof![
        Just(None),
        prop::collection::vec(0.3f64..3.0, 1..6).prop_map(Some),
        prop::collection::vec((-150i32..=150).prop_map(|e| 10f64.powi(e)), 1..6).prop_map(Some),
    ];
    let knots = prop_oneof![
        Just(KnotFamily::ClampedRepeated),
        Just(KnotFamily::Uniform),
        Just(KnotFamily::Tiny),
        Just(KnotFamily::Huge),
    ];
    (
        hostile(dim),
        1usize..=8,
        knots,
        weights,
        prop::collection::vec(0.0f64..1.0, 4),
    )
        .prop_map(|(poles, degree, knots, weights, draws)| {
            let count = poles.points.len() / poles.dim;
            HostileNurbs {
                degree: degree.min(count.saturating_sub(1)).max(1),
                poles,
                knots,
                weights,
                draws,
            }
        })
        .boxed()
}

/// A parameter of the domain `[a, b]` from a unit parameter (denormal
/// offsets included).
fn in_domain(c: &NurbsCurve, t: f64) -> f64 {
    let (a, b) = c.domain();
    (a + t * (b - a)).clamp(a, b)
}

#[test]
fn nurbs_operations_survive_hostile_inputs() {
    let strategy = (
        (1usize..=3).prop_flat_map(hostile_nurbs),
        unit_param(),
        unit_param(),
        0usize..=6,
        0usize..=4,
    );
    run("NURBS operations", strategy, |(h, t, s, order, raise)| {
        let Some(c) = h.curve()? else { return Ok(()) };
        let input = (&h, t, s, order, raise);
        let (u, w) = (in_domain(&c, t), in_domain(&c, s));
        // The value is a convex combination of the poles (positive weights).
        let value = guarded("NurbsCurve::eval", &input, || c.eval(u))?;
        require_finite("NurbsCurve::eval", &input, &value)?;
        checked("NurbsCurve::eval_derivatives_checked", &input, || {
            c.eval_derivatives_checked("u", u, order)
        })?;
        checked("NurbsCurve::insert_knot", &input, || c.insert_knot(u, 1))?;
        checked("NurbsCurve::split_at", &input, || c.split_at(u))?;
        checked("NurbsCurve::segment", &input, || {
            c.segment(u.min(w), u.max(w))
        })?;
        let r = guarded("NurbsCurve::reverse", &input, || c.reverse())?;
        require_finite("NurbsCurve::reverse", &input, &r)?;
        let k = guarded("NurbsCurve::clamped", &input, || c.clamped())?;
        require_finite("NurbsCurve::clamped", &input, &k)?;
        let spans = guarded("NurbsCurve::bezier_spans", &input, || c.bezier_spans())?;
        require_finite("NurbsCurve::bezier_spans", &input, &spans)?;
        checked("NurbsCurve::elevate_degree", &input, || {
            c.elevate_degree(c.degree() + raise)
        })?;
        checked("NurbsCurve::arc_length_default", &input, || {
            c.arc_length_default(u.min(w), u.max(w))
        })?;
        if let Some(total) = checked("NurbsCurve::arc_length_default (whole)", &input, || {
            let (a, b) = c.domain();
            c.arc_length_default(a, b)
        })? {
            checked("NurbsCurve::param_at_length", &input, || {
                let (a, _) = c.domain();
                c.param_at_length(a, 0.5 * total, c.default_length_accuracy())
            })?;
        }
        Ok(())
    });
}

#[test]
fn nurbs_joins_survive_hostile_inputs() {
    let strategy = (hostile_nurbs(2), unit_param(), 0usize..=3, positive());
    run("NURBS joins", strategy, |(h, t, order, setback)| {
        let Some(p) = h.curve()? else { return Ok(()) };
        let input = (&h, t, order, setback);
        // Q: P reversed and rotated by 90 degrees about P's middle point,
        // as a NURBS curve; it crosses P there unless P is degenerate.
        let (a, b) = p.domain();
        let c = p.eval(0.5 * (a + b));
        let mut poles = p.points().to_vec();
        for row in poles.chunks_exact_mut(2) {
            let (x, y) = (row[0] - c[0], row[1] - c[1]);
            row[0] = c[0] - y;
            row[1] = c[1] + x;
        }
        let Ok(q) = NurbsCurve::new(
            2,
            p.degree(),
            poles,
            p.weights().map(<[f64]>::to_vec),
            p.knots().to_vec(),
        ) else {
            return Ok(());
        };
        let (pc, qc) = (Curve::from(p.clone()), Curve::from(q.clone()));
        let u = in_domain(&p, t);
        checked("connect (NURBS)", &input, || {
            connect(
                &pc,
                u,
                &qc,
                in_domain(&q, 1.0 - t),
                &ConnectOptions::new(order, order),
            )
        })?;
        checked("intersect (NURBS)", &input, || {
            intersect(&p, &q, &IntersectOptions::default())
        })?;
        let options = FilletOptions::symmetric(setback, order);
        checked("fillet (NURBS)", &input, || fillet(&p, &q, &options))?;
        checked("fillet_vertex (NURBS)", &input, || {
            fillet_vertex(&p, &p.reverse(), &options, 1e-9)
        })?;
        checked("fillet_chain (NURBS)", &input, || {
            fillet_chain(
                &[pc.clone(), qc.clone()],
                &ChainFilletOptions::closed(options.clone()),
            )
        })?;
        Ok(())
    });
}

#[test]
fn ellipse_arcs_survive_hostile_inputs() {
    let strategy = (
        prop::collection::vec(any_coordinate(), 3),
        positive(),
        positive(),
        any_coordinate(),
        positive(),
    );
    run("ellipse_arc", strategy, |(centre, rx, ry, a0, sweep)| {
        let input = (&centre, rx, ry, a0, sweep);
        for dim in [2usize, 3] {
            let (x, y) = if dim == 2 {
                (vec![1.0, 0.0], vec![0.0, 1.0])
            } else {
                (vec![0.0, 1.0, 0.0], vec![0.0, 0.0, 1.0])
            };
            if let Some(e) = checked("ellipse_arc", &input, || {
                ellipse_arc(dim, &centre[..dim], &x, &y, rx, ry, a0, a0 + sweep)
            })? {
                checked("ellipse_arc length", &input, || {
                    let (a, b) = e.domain();
                    e.arc_length_default(a, b)
                })?;
            }
        }
        Ok(())
    });
}

/// A segment so far outside `[0, 1]` that its control points overflow is
/// refused naming the argument, with the number as it reads (user testing,
/// session 44: `a = -1e300` was printed as 301 digits, with the type name
/// `f64`).
#[test]
fn an_overflowing_segment_names_its_bound_in_a_short_message() {
    let c = BezierCurve::new(2, 3, vec![0.0, 0.0, 1.0, 2.0, 3.0, -1.0, 4.0, 0.0]).unwrap();
    match c.segment(-1e300, 1e300) {
        Err(BezjoinError::InvalidArgument { name, reason }) => {
            assert_eq!(name, "a = -1e300", "{reason}");
            assert!(reason.len() < 120 && !reason.contains("f64"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
}
