//! Properties of `connect` (mathematics.md, section 1): the continuity
//! conditions (1') and the interior constraints (2) hold, the chain
//! `P|[0,u0]`, `R`, `Q|[v0,1]` is a C^k B-spline, the structured and the
//! dense solves agree, a split curve is reproduced, and the automatic scale
//! minimises its energy.
//!
//! Residuals are always recomputed here, from evaluations of the returned
//! curve, never taken from the solver. The bounds every answer is held to
//! ([`assert_conditions`], docs/accuracy.md, Connect):
//! * the published promise `CONNECT_RESIDUAL_LIMIT` (1e-8), always;
//! * 1e-10 for result degrees up to [`STRICT_DEGREE`] and, at any degree,
//!   whenever the amplification `A = max |R_i| / S` (the connecting curve's
//!   control-point size over the data scale) is at most
//!   [`STRICT_AMPLIFICATION`];
//! * the rounding floor of a backward-stable solve, `8 (n + 1) u A`
//!   (`u` = unit roundoff), or 1e-10 if larger, always.

mod common;
use bezjoin_core::{
    AUTO_SCALE_SEARCH_DECADES, CONNECT_RESIDUAL_LIMIT, ConnectOptions, Connection,
    MAX_CONNECT_DEGREE, PointConstraint, ShapeScale, UNKINKED_POLYGON_CHORDS, connect,
    connect_dense_reference, connect_unchecked, fairness_energy,
};
use bezjoin_core::{BSplineCurve, BezierCurve, BezjoinError, KnotSide};
use common::{Random, bezier_basis_derivatives, speed_and_floor};
use proptest::prelude::*;

/// The residual the issue asks for (issue 3, item 5).
const STRICT: f64 = 1e-10;

/// Result degrees up to which [`STRICT`] holds for every answer, whatever
/// the data: measured over [`exhaustive_cases`] (worst 1.9e-13 up to degree
/// 8, and at most 7.5e-12 over earlier seeds of the same generator; answers
/// above 1e-10 appear from degree 9 or 10, from ill-posed constraint data
/// with `A` of 1e5 to 1e7, confirmed by the exact-rational reference;
/// docs/accuracy.md, Connect).
const STRICT_DEGREE: usize = 8;

/// Amplification `A = max |R_i| / S` up to which [`STRICT`] holds at every
/// degree (measured worst 3.2e-11 for `A` in [1e3, 1e4)).
const STRICT_AMPLIFICATION: f64 = 1e4;

/// Unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

fn curve_from(dim: usize, degree: usize, raw: &[f64]) -> BezierCurve {
    BezierCurve::new(dim, degree, raw[..(degree + 1) * dim].to_vec()).unwrap()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Row `k` (the k-th derivative) of row-major derivatives with `dim` values per row.
fn row(m: &[f64], dim: usize, k: usize) -> Vec<f64> {
    m[k * dim..(k + 1) * dim].to_vec()
}

/// The relative residual of the module documentation, computed here from
/// curve evaluations: `|got - want| / max(|want|, S * ||D_k(t)||_1)`.
fn relative_residual(
    got: &[f64],
    want: &[f64],
    data_scale: f64,
    degree: usize,
    t: f64,
    k: usize,
) -> f64 {
    let basis = bezier_basis_derivatives(degree, t, k);
    let row_norm: f64 = basis.row(k).iter().map(|v| v.abs()).sum();
    let diff: Vec<f64> = got.iter().zip(want).map(|(a, b)| a - b).collect();
    norm(&diff) / norm(want).max(data_scale * row_norm)
}

#[derive(Debug, Clone)]
struct Case {
    p: BezierCurve,
    q: BezierCurve,
    u0: f64,
    v0: f64,
    options: ConnectOptions,
}

/// Random P, Q (2D/3D, degrees 1..=8), orders `kp`, `kq` uniform in
/// `0..=np`, `0..=nq`, scales, 0..=max constraints with K <= 3 whose data are
/// the derivatives of a random cubic (unrelated to P and Q: often ill-posed).
fn case_strategy(max_constraints: usize) -> impl Strategy<Value = Case> {
    (
        2usize..=3,
        1usize..=8,
        1usize..=8,
        prop::collection::vec(-10.0f64..10.0, 27),
        prop::collection::vec(-10.0f64..10.0, 27),
        prop::collection::vec(-10.0f64..10.0, 12),
        (0.0f64..=1.0, 0.0f64..=1.0, 0.3f64..3.0, 0.3f64..3.0),
        (0.0f64..1.0, 0.0f64..1.0),
        prop::collection::vec((0usize..=3, 0.0f64..1.0), 0..=max_constraints),
        prop::bool::ANY,
    )
        .prop_map(
            |(dim, np, nq, rp, rq, rc, (u0, v0, alpha, beta), (fp, fq), cons, endpoints)| {
                // kp uniform in 0..=np, kq uniform in 0..=nq.
                let kp = ((fp * (np + 1) as f64) as usize).min(np);
                let kq = ((fq * (nq + 1) as f64) as usize).min(nq);
                let p = curve_from(dim, np, &rp);
                let q = curve_from(dim, nq, &rq);
                let (u0, v0) = if endpoints { (1.0, 0.0) } else { (u0, v0) };
                let shape = curve_from(dim, 3, &rc);
                let m = cons.len();
                let constraints = cons
                    .iter()
                    .enumerate()
                    .map(|(j, &(order, jitter))| {
                        let t = (j as f64 + 0.2 + 0.6 * jitter) / m as f64;
                        PointConstraint::new(t, order, shape.eval_derivatives(t, order))
                    })
                    .collect();
                Case {
                    p,
                    q,
                    u0,
                    v0,
                    options: ConnectOptions {
                        p_order: kp,
                        q_order: kq,
                        scale: ShapeScale::Given { p: alpha, q: beta },
                        constraints,
                    },
                }
            },
        )
}

/// The data scale `S` of the residual definition: the control-point scale of
/// P and Q, and `|T_k| / ||D_k||_1` over all conditions.
fn data_scale(case: &Case, p_scale: f64, q_scale: f64) -> f64 {
    let o = &case.options;
    let n = o.result_degree();
    let dim = case.p.dim();
    let mut s = case.p.coordinate_scale().max(case.q.coordinate_scale());
    let mut take = |want: &[f64], t: f64, k: usize| {
        let basis = bezier_basis_derivatives(n, t, k);
        let row_norm: f64 = basis.row(k).iter().map(|v| v.abs()).sum();
        s = s.max(norm(want) / row_norm);
    };
    let pp = case.p.eval_derivatives(case.u0, o.p_order);
    for k in 0..=o.p_order {
        let want: Vec<f64> = row(&pp, dim, k)
            .iter()
            .map(|v| v * p_scale.powi(k as i32))
            .collect();
        take(&want, 0.0, k);
    }
    let qq = case.q.eval_derivatives(case.v0, o.q_order);
    for k in 0..=o.q_order {
        let want: Vec<f64> = row(&qq, dim, k)
            .iter()
            .map(|v| v * q_scale.powi(k as i32))
            .collect();
        take(&want, 1.0, k);
    }
    for c in &o.constraints {
        for (k, d) in c.values.chunks(dim).enumerate() {
            take(d, c.t, k);
        }
    }
    s
}

/// `A = max |R_i| / S`: how much larger the connecting curve's control
/// points are than the data scale (at least 1). Computed from the answer.
fn amplification(case: &Case, c: &Connection) -> f64 {
    (c.curve.coordinate_scale() / data_scale(case, c.p_scale, c.q_scale)).max(1.0)
}

/// Check (1') and (2) by evaluating the curves, independently of the solver
/// (its `error_estimate` plays no part): the worst relative residual `w`
/// meets the promise (1e-8); `w <= 1e-10` for result degrees up to
/// [`STRICT_DEGREE`] or amplification up to [`STRICT_AMPLIFICATION`]; and
/// `w <= max(1e-10, 8 (n + 1) u A)`, the rounding floor of a backward-stable
/// solve (representing `R` in f64 alone costs up to `u A`; measured worst
/// `2.4 (n + 1) u A`).
fn assert_conditions(case: &Case, c: &Connection) {
    let worst = worst_residual(case, c);
    let n = c.curve.degree();
    let a = amplification(case, c);
    let floor = 8.0 * (n + 1) as f64 * U * a;
    assert!(
        worst <= CONNECT_RESIDUAL_LIMIT,
        "degree {n}: worst relative residual {worst:e} above the promise"
    );
    assert!(
        worst <= STRICT.max(floor),
        "degree {n}: worst relative residual {worst:e} above the rounding floor {floor:e} (A = {a:e})"
    );
    if n <= STRICT_DEGREE || a <= STRICT_AMPLIFICATION {
        assert!(
            worst <= STRICT,
            "degree {n}, A = {a:e}: worst relative residual {worst:e} above {STRICT:e}"
        );
    }
}

/// The worst relative residual of (1') and (2), from curve evaluations.
fn worst_residual(case: &Case, c: &Connection) -> f64 {
    let mut worst = 0.0f64;
    let o = &case.options;
    let r = &c.curve;
    let n = r.degree();
    let dim = r.dim();
    assert_eq!(n, o.result_degree());
    let s = data_scale(case, c.p_scale, c.q_scale);
    let rp = r.eval_derivatives(0.0, o.p_order);
    let pp = case.p.eval_derivatives(case.u0, o.p_order);
    for k in 0..=o.p_order {
        let want: Vec<f64> = row(&pp, dim, k)
            .iter()
            .map(|v| v * c.p_scale.powi(k as i32))
            .collect();
        worst = worst.max(relative_residual(&row(&rp, dim, k), &want, s, n, 0.0, k));
    }
    let rq = r.eval_derivatives(1.0, o.q_order);
    let qq = case.q.eval_derivatives(case.v0, o.q_order);
    for k in 0..=o.q_order {
        let want: Vec<f64> = row(&qq, dim, k)
            .iter()
            .map(|v| v * c.q_scale.powi(k as i32))
            .collect();
        worst = worst.max(relative_residual(&row(&rq, dim, k), &want, s, n, 1.0, k));
    }
    for pc in &o.constraints {
        let rt = r.eval_derivatives(pc.t, pc.max_order);
        for (k, want) in pc.values.chunks(dim).enumerate() {
            worst = worst.max(relative_residual(&row(&rt, dim, k), want, s, n, pc.t, k));
        }
    }
    worst
}

/// `connect`'s answer, or `None` when it refuses. A refusal is accepted only
/// when it is honest: the estimate exceeds the limit and bounds the residual
/// of the unchecked answer, measured here independently. (That realistic
/// inputs are answered is asserted in tests/connect_accuracy.rs.)
fn solve_or_refuse(case: &Case) -> Option<Connection> {
    match connect(&case.p, case.u0, &case.q, case.v0, &case.options) {
        Ok(c) => {
            assert!(c.error_estimate <= CONNECT_RESIDUAL_LIMIT);
            assert!(c.max_residual <= c.error_estimate);
            Some(c)
        }
        Err(BezjoinError::IllConditioned { estimate, .. }) => {
            assert!(estimate > CONNECT_RESIDUAL_LIMIT);
            if case.options.result_degree() > MAX_CONNECT_DEGREE {
                return None;
            }
            let unchecked =
                connect_unchecked(&case.p, case.u0, &case.q, case.v0, &case.options).unwrap();
            assert_eq!(unchecked.error_estimate, estimate);
            let measured = worst_residual(case, &unchecked);
            assert!(
                measured <= estimate,
                "estimate {estimate:e} below the measured {measured:e}"
            );
            None
        }
        Err(e) => panic!("unexpected error {e}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn continuity_and_constraints_hold(case in case_strategy(3)) {
        if let Some(c) = solve_or_refuse(&case) {
            assert_conditions(&case, &c);
        }
    }

    #[test]
    fn structured_and_dense_solves_agree(case in case_strategy(3)) {
        let Some(s) = solve_or_refuse(&case) else { return Ok(()) };
        let d = match connect_dense_reference(&case.p, case.u0, &case.q, case.v0, &case.options) {
            Ok(d) => d,
            Err(BezjoinError::IllConditioned { .. }) => return Ok(()),
            Err(e) => panic!("dense reference failed: {e}"),
        };
        assert_conditions(&case, &d);
        // Both are backward stable, so their control points differ by about
        // u times the condition number of the system (the dense reference
        // reports the 1-norm condition estimate of the whole row-scaled
        // system): allowed 16 u cond. Measured: at most 0.76 u cond, and
        // never above 2.9e-12 of the coordinate scale over the cases of
        // `exhaustive_cases` nor above 3e-11 over 20 000 cases of this
        // strategy, hence the cap at 1e-10.
        let scale = s.curve.coordinate_scale().max(d.curve.coordinate_scale());
        let tolerance = (16.0 * U * d.constraint_condition.max(1.0)).min(1e-10);
        for (a, b) in s.curve.points().iter().zip(d.curve.points()) {
            prop_assert!(
                (a - b).abs() <= tolerance * scale,
                "{a} vs {b} (tolerance {tolerance:e}, condition {:e})",
                d.constraint_condition
            );
        }
    }

    #[test]
    fn chain_is_a_ck_bspline(case in case_strategy(3)) {
        let Some(c) = solve_or_refuse(&case) else { return Ok(()) };
        let (alpha, beta) = (c.p_scale, c.q_scale);
        let mut pieces = Vec::new();
        let mut intervals = Vec::new();
        if case.u0 > 0.0 {
            pieces.push(case.p.split_at(case.u0).unwrap().0);
            intervals.push(case.u0);
        }
        pieces.push(c.curve.clone());
        intervals.push(alpha);
        if case.v0 < 1.0 {
            pieces.push(case.q.split_at(case.v0).unwrap().1);
            intervals.push((1.0 - case.v0) * alpha / beta);
        }
        let chain = BSplineCurve::from_bezier_chain(&pieces, &intervals).unwrap();
        let degree = chain.degree();
        let s = data_scale(&case, alpha, beta);
        let n = c.curve.degree();
        let mut joins = Vec::new();
        // (knot, order, shorter of the two adjacent intervals)
        if case.u0 > 0.0 {
            joins.push((case.u0, case.options.p_order, case.u0.min(alpha)));
        }
        if case.v0 < 1.0 {
            let x = if case.u0 > 0.0 { case.u0 + alpha } else { alpha };
            let h = alpha.min((1.0 - case.v0) * alpha / beta);
            joins.push((x, case.options.q_order, h));
        }
        for (x, order, h) in joins {
            let left = chain.eval_derivatives_side(x, degree, KnotSide::Left);
            let right = chain.eval_derivatives_side(x, degree, KnotSide::Right);
            for k in 0..=order {
                let (l, r) = (row(&left, chain.dim(), k), row(&right, chain.dim(), k));
                // Natural size of a k-th derivative of a piece of degree
                // `degree`, control points of size S, interval h.
                let falling: f64 = (0..k).map(|i| (degree.max(n) - i) as f64).product();
                let floor = s * falling * 2f64.powi(k as i32) / h.powi(k as i32);
                let diff: Vec<f64> = l.iter().zip(&r).map(|(a, b)| a - b).collect();
                let jump = norm(&diff) / norm(&l).max(norm(&r)).max(floor);
                prop_assert!(jump <= 1e-9, "join at {x}, order {k}: jump {jump:e}");
            }
        }
    }

    #[test]
    fn a_split_curve_is_reproduced(
        dim in 2usize..=3,
        n in 1usize..=8,
        raw in prop::collection::vec(-10.0f64..10.0, 27),
        s in 0.3f64..0.7,
        u0 in 0.5f64..1.0,
        v0 in 0.0f64..0.5,
    ) {
        // u0 in [0.5, 1), v0 in [0, 0.5) keep alpha = l/s and beta = l/(1-s)
        // below 5/3: larger scales extrapolate P or Q far outside [0, 1] and
        // amplify rounding like (1 + alpha)^n, beyond what 1e-12 allows.
        let c = curve_from(dim, n, &raw);
        let (p, q) = c.split_at(s).unwrap();
        let l = s * (1.0 - u0) + (1.0 - s) * v0;
        let options = ConnectOptions::new(n, n).with_scales(l / s, l / (1.0 - s));
        let r = connect(&p, u0, &q, v0, &options).unwrap();
        prop_assert_eq!(r.curve.degree(), 2 * n + 1);
        let a = s * u0;
        let expected = c.segment(a, a + l).unwrap().elevate_degree(2 * n + 1).unwrap();
        let scale = expected.coordinate_scale();
        for (x, y) in r.curve.points().iter().zip(expected.points()) {
            prop_assert!((x - y).abs() <= 1e-12 * scale, "{x} vs {y}");
        }
    }

    #[test]
    fn a_split_curve_is_reproduced_over_the_full_range(
        dim in 2usize..=3,
        n in 1usize..=8,
        raw in prop::collection::vec(-10.0f64..10.0, 27),
        s in 0.02f64..0.98,
        u0 in 0.0f64..=1.0,
        v0 in 0.0f64..=1.0,
    ) {
        // Any u0, v0 (l > 0), s in [0.02, 0.98]: alpha = l/s and beta =
        // l/(1-s) reach 50. R is then C's segment over [s u0, s u0 + l],
        // i.e. P (or Q) extrapolated to u0 + alpha (v0 - beta), and rounding
        // grows like (1 + max(alpha, beta))^n (docs/accuracy.md: measured
        // at most 1.6e2 u |C| (1 + max(alpha, beta))^n).
        let c = curve_from(dim, n, &raw);
        let (p, q) = c.split_at(s).unwrap();
        let l = s * (1.0 - u0) + (1.0 - s) * v0;
        prop_assume!(l > 1e-9);
        let (alpha, beta) = (l / s, l / (1.0 - s));
        let case = Case {
            p,
            q,
            u0,
            v0,
            options: ConnectOptions::new(n, n).with_scales(alpha, beta),
        };
        // Strong extrapolation may be refused; the refusal must be honest.
        let Some(r) = solve_or_refuse(&case) else { return Ok(()) };
        prop_assert_eq!(r.curve.degree(), 2 * n + 1);
        let a = s * u0;
        let expected = c.segment(a, a + l).unwrap().elevate_degree(2 * n + 1).unwrap();
        let amplification = (1.0 + alpha.max(beta)).powi(n as i32);
        let tolerance = 1e3 * U * c.coordinate_scale() * amplification;
        for (x, y) in r.curve.points().iter().zip(expected.points()) {
            prop_assert!(
                (x - y).abs() <= tolerance,
                "{x} vs {y}: tolerance {tolerance:e}, alpha {alpha}, beta {beta}"
            );
        }
    }

    #[test]
    fn auto_scale_minimises_the_energy(case in case_strategy(1), factor in 0.5f64..2.0) {
        let auto = case.options.clone().with_auto_scale();
        let c = match connect(&case.p, case.u0, &case.q, case.v0, &auto) {
            Ok(c) => c,
            Err(BezjoinError::IllConditioned { estimate, .. }) => {
                prop_assert!(estimate > CONNECT_RESIDUAL_LIMIT);
                return Ok(());
            }
            // Coincident ends (the all-zero curves of the regression file):
            // refused by name (session 44).
            Err(BezjoinError::InvalidArgument { name, .. }) if name == "v0" => {
                let gap = common::distance(&case.p.eval(case.u0), &case.q.eval(case.v0));
                let scale = case.p.coordinate_scale().max(case.q.coordinate_scale());
                prop_assert!(gap <= 1e-9 * scale);
                return Ok(());
            }
            Err(e) => panic!("{e}"),
        };
        prop_assert_eq!(c.p_scale, c.q_scale);
        let o = ConnectOptions {
            scale: ShapeScale::Given { p: c.p_scale, q: c.q_scale },
            ..case.options.clone()
        };
        let checked = Case { options: o.clone(), ..case.clone() };
        assert_conditions(&checked, &c);
        let best = fairness_energy(&c.curve);
        // The documented search range: AUTO_SCALE_SEARCH_DECADES either side
        // of s0 = |Q(v0) - P(u0)| / mean(v_P, v_Q) (1 if undefined), v the
        // end's speed |X'| raised to its floor terms
        // ((BALANCED_SPEED_FLOOR c)^(j-1) |X^(j)|)^(1/j) when larger.
        let gap = norm(&case.q.eval(case.v0).iter().zip(case.p.eval(case.u0)).map(|(a, b)| a - b).collect::<Vec<_>>());
        let mut speeds = Vec::new();
        let mut floored = false;
        for (x, at, order) in [(&case.p, case.u0, case.options.p_order), (&case.q, case.v0, case.options.q_order)] {
            if order > 0 {
                let (speed, floor) = speed_and_floor(x, at, order, gap);
                speeds.push(speed.max(floor));
                floored |= floor > speed;
            }
        }
        let s0 = gap / (speeds.iter().sum::<f64>() / speeds.len().max(1) as f64);
        let s0 = if s0.is_finite() && s0 > 0.0 { s0 } else { 1.0 };
        let width = 10f64.powf(AUTO_SCALE_SEARCH_DECADES);
        let (lo, hi) = (s0 / width * (1.0 - 1e-9), s0 * width * (1.0 + 1e-9));
        if speeds.is_empty() {
            prop_assert_eq!(c.p_scale, 1.0);
            return Ok(());
        }
        prop_assert!(c.p_scale >= lo && c.p_scale <= hi);
        // Where the energy is least at the range's lower end (ends facing
        // away, whose blend there turns in kinks) and no floor applies, the
        // answer is not the energy's minimum but s0, or the largest smaller
        // scale whose control polygon is at most UNKINKED_POLYGON_CHORDS
        // chords (session 44; unit test
        // a_kinked_minimum_takes_the_natural_speed_or_the_fastest_short_blend).
        let bottom = connect(&case.p, case.u0, &case.q, case.v0, &o.clone().with_scales(s0 / width, s0 / width))
            .map(|r| fairness_energy(&r.curve))
            .unwrap_or(f64::INFINITY);
        if bottom < best * (1.0 - 1e-9) {
            prop_assert!(!floored, "s = {} above the lower end's {bottom} with a floor", c.p_scale);
            prop_assert!(c.p_scale <= s0 * (1.0 + 1e-9), "s = {} above s0 = {s0}", c.p_scale);
            prop_assert!(c.curve.polygon_length() <= UNKINKED_POLYGON_CHORDS * gap * (1.0 + 1e-9));
            return Ok(());
        }
        // Feasible perturbations of s inside the range do no better.
        for f in [factor, 1.0 / factor, 1.001, 0.999] {
            if !(lo..=hi).contains(&(c.p_scale * f)) {
                continue;
            }
            let other = o.clone().with_scales(c.p_scale * f, c.q_scale * f);
            if let Ok(r) = connect(&case.p, case.u0, &case.q, case.v0, &other) {
                let e = fairness_energy(&r.curve);
                prop_assert!(
                    best <= e * (1.0 + 1e-9) + 1e-12,
                    "s = {} gives {best}, s * {f} gives {e}", c.p_scale
                );
            }
        }
    }
}

#[test]
fn paper_example_shape_and_degree() {
    // Cubic to cubic, C3 at both ends: degree 7 (Theorem 1); with one K = 2
    // constraint, degree 10 (Theorem 2).
    let p = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [2.0, 2.0], [3.0, 0.0]]).unwrap();
    let q = BezierCurve::from_rows(&[[6.0, 0.0], [7.0, -2.0], [8.0, -2.0], [9.0, 0.0]]).unwrap();
    let plain = connect(&p, 1.0, &q, 0.0, &ConnectOptions::new(3, 3)).unwrap();
    assert_eq!(plain.curve.degree(), 7);
    let mid = plain.curve.eval_derivatives(0.5, 2);
    let o = ConnectOptions::new(3, 3).with_constraint(PointConstraint::new(0.5, 2, mid));
    let constrained = connect(&p, 1.0, &q, 0.0, &o).unwrap();
    assert_eq!(constrained.curve.degree(), 10);
    // Prescribing what the degree-7 curve already does reproduces it.
    let elevated = plain.curve.elevate_degree(10).unwrap();
    for (a, b) in constrained.curve.points().iter().zip(elevated.points()) {
        assert!((a - b).abs() < 1e-12 * elevated.coordinate_scale());
    }
}

#[test]
fn too_high_a_degree_is_refused_with_an_estimate() {
    let p = BezierCurve::new(1, 30, (0..31).map(|i| ((i * 37) % 11) as f64).collect()).unwrap();
    let q = BezierCurve::new(1, 30, (0..31).map(|i| ((i * 53) % 13) as f64).collect()).unwrap();
    // Degree 31 exactly is solved; every degree above it is refused before
    // any work, whether reached by the orders or by constraints. No answer
    // is computed, so there is no residual to bound: the estimate is
    // infinite (docs/accuracy.md).
    let at_cap = ConnectOptions::new(15, 15);
    assert_eq!(at_cap.result_degree(), MAX_CONNECT_DEGREE);
    assert!(connect(&p, 0.3, &q, 0.6, &at_cap).is_ok());
    let constraint = |t: f64, rows: usize| PointConstraint::new(t, rows - 1, vec![1.0; rows]);
    for options in [
        ConnectOptions::new(30, 30),
        ConnectOptions::new(16, 15),
        ConnectOptions::new(15, 15).with_constraint(constraint(0.5, 1)),
        ConnectOptions::new(8, 8)
            .with_constraint(constraint(0.25, 4))
            .with_constraint(constraint(0.5, 4))
            .with_constraint(constraint(0.75, 4))
            .with_constraint(constraint(0.9, 4)),
    ] {
        let degree = options.result_degree();
        assert!(degree > MAX_CONNECT_DEGREE);
        match connect(&p, 0.3, &q, 0.6, &options).unwrap_err() {
            BezjoinError::IllConditioned {
                what,
                estimate,
                limit,
            } => {
                assert!(estimate > limit && limit == CONNECT_RESIDUAL_LIMIT);
                assert!(
                    what.contains(&format!("result degree {degree} is above")),
                    "{what}"
                );
            }
            e => panic!("expected IllConditioned, got {e}"),
        }
    }
    // An order so large that the degree overflows names the orders given
    // (user testing, session 40: it said only "result degree (overflow)").
    let huge = ConnectOptions::new(usize::MAX, 3);
    let e = connect(&p, 0.3, &q, 0.6, &huge).unwrap_err().to_string();
    assert!(
        e.contains("(overflow)") && e.contains(&format!("p_order {}", usize::MAX)),
        "{e}"
    );
}

/// Two constraint points 1e-4 apart with positions 2 apart and equal
/// tangents: the curve must swing by about 1e4 times its size between them,
/// and its control points become 1e12 times the data. The solve is done
/// (degree 11, far below the cap) and refused by its own residual check.
fn crowded_constraints() -> Case {
    let p = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [2.0, 2.0], [3.0, 0.0]]).unwrap();
    let q = BezierCurve::from_rows(&[[6.0, 0.0], [7.0, -2.0], [8.0, -2.0], [9.0, 0.0]]).unwrap();
    let options = ConnectOptions::new(3, 3)
        .with_constraint(PointConstraint::new(0.5, 1, vec![4.5, 1.0, 1.0, 0.0]))
        .with_constraint(PointConstraint::new(0.5001, 1, vec![4.5, -1.0, 1.0, 0.0]));
    Case {
        p,
        q,
        u0: 1.0,
        v0: 0.0,
        options,
    }
}

#[test]
fn ill_posed_constraints_below_the_degree_cap_are_refused_by_the_residual_check() {
    let case = crowded_constraints();
    assert_eq!(case.options.result_degree(), 11);
    let err = connect(&case.p, case.u0, &case.q, case.v0, &case.options).unwrap_err();
    let message = err.to_string();
    let BezjoinError::IllConditioned {
        what,
        estimate,
        limit,
    } = err
    else {
        panic!("expected IllConditioned, got {message}");
    };
    assert_eq!(limit, CONNECT_RESIDUAL_LIMIT);
    assert!(
        estimate.is_finite() && estimate > CONNECT_RESIDUAL_LIMIT,
        "{estimate:e}"
    );
    assert_eq!(what, "connect (degree 11)");
    assert!(
        message.starts_with("connect (degree 11): estimated relative error ")
            && message.ends_with(" exceeds the promised 1e-8"),
        "{message}"
    );
    // The refusal is honest: the unchecked answer, measured here, really
    // misses the promise, and the estimate bounds what was measured.
    let unchecked = connect_unchecked(&case.p, case.u0, &case.q, case.v0, &case.options).unwrap();
    assert_eq!(unchecked.error_estimate, estimate);
    let measured = worst_residual(&case, &unchecked);
    assert!(
        measured > CONNECT_RESIDUAL_LIMIT && measured <= estimate,
        "measured {measured:e}, estimate {estimate:e}"
    );
    // The same points 1e-2 apart are answered and meet the bounds.
    let mut relaxed = case.clone();
    relaxed.options.constraints[1].t = 0.51;
    let c = connect(&relaxed.p, 1.0, &relaxed.q, 0.0, &relaxed.options).unwrap();
    assert_conditions(&relaxed, &c);
}

/// Where the constraint data of an exhaustive case come from.
#[derive(Debug, Clone, Copy, PartialEq)]
enum ConstraintData {
    /// The derivatives of the unconstrained connection (same P, Q, orders,
    /// scales) at `t_j`, each coordinate scaled by a factor in [0.9, 1.1]:
    /// what a user nudging the natural shape asks for.
    Natural,
    /// The derivatives of an unrelated random cubic: often ill-posed.
    Unrelated,
}

/// One random case: P, Q with coordinates in [-10, 10]; `u0`, `v0` uniform
/// in [0, 1], a quarter of the cases at the ends (1, 0); scales log-uniform
/// in [0.3, 3]; one constraint per entry of `orders` (its `K_j`), at `t_j`
/// spread over (0, 1), with data as `data` says.
#[allow(clippy::too_many_arguments)]
fn random_case(
    rng: &mut Random,
    dim: usize,
    (np, nq): (usize, usize),
    (kp, kq): (usize, usize),
    orders: &[usize],
    data: ConstraintData,
) -> Case {
    let p = rng.curve(dim, np, 10.0);
    let q = rng.curve(dim, nq, 10.0);
    let (u0, v0) = if rng.next() < 0.25 {
        (1.0, 0.0)
    } else {
        (rng.next(), rng.next())
    };
    let alpha = rng.range(0.3f64.ln(), 3f64.ln()).exp();
    let beta = rng.range(0.3f64.ln(), 3f64.ln()).exp();
    let mut options = ConnectOptions::new(kp, kq).with_scales(alpha, beta);
    let shape = match data {
        ConstraintData::Natural => connect(&p, u0, &q, v0, &options).unwrap().curve,
        ConstraintData::Unrelated => rng.curve(dim, 3, 10.0),
    };
    let m = orders.len();
    for (j, &order) in orders.iter().enumerate() {
        let t = (j as f64 + 0.2 + 0.6 * rng.next()) / m as f64;
        // Row-major, derivative by derivative: the same order of draws as
        // one row per derivative.
        let values = shape
            .eval_derivatives(t, order)
            .iter()
            .map(|v| match data {
                ConstraintData::Natural => v * rng.range(0.9, 1.1),
                ConstraintData::Unrelated => *v,
            })
            .collect();
        options = options.with_constraint(PointConstraint::new(t, order, values));
    }
    Case {
        p,
        q,
        u0,
        v0,
        options,
    }
}

/// Every `np, nq` in `1..=8`, every `kp <= np`, `kq <= nq`, each in 2D and
/// in 3D (one with [`ConstraintData::Natural`], the other with
/// [`ConstraintData::Unrelated`], alternating), with the number of
/// constraints cycling through 0..=3 and their orders `K_j` through 0..=3
/// ([`random_case`]); then, for every `np, nq` at the highest orders
/// `kp = np`, `kq = nq`, three constraints with `K = 3` each (result degrees
/// 15..=29, the largest this range allows). Deterministic (seeded xorshift).
fn exhaustive_cases() -> Vec<(Case, ConstraintData)> {
    let mut rng = Random(0x5EED_C0DE_2026_0003);
    let mut cases = Vec::new();
    let mut index = 0usize;
    let data_for = |dim: usize, flip: bool| {
        if (dim == 2) != flip {
            ConstraintData::Natural
        } else {
            ConstraintData::Unrelated
        }
    };
    for np in 1..=8 {
        for nq in 1..=8 {
            for kp in 0..=np {
                for kq in 0..=nq {
                    let flip = (np + nq + kp + kq) % 2 == 1;
                    for dim in [2, 3] {
                        let data = data_for(dim, flip);
                        let orders: Vec<usize> =
                            (0..index % 4).map(|j| (index / 4 + j) % 4).collect();
                        let case = random_case(&mut rng, dim, (np, nq), (kp, kq), &orders, data);
                        cases.push((case, data));
                        index += 1;
                    }
                }
            }
            for dim in [2, 3] {
                let data = data_for(dim, (np + nq) % 2 == 1);
                let case = random_case(&mut rng, dim, (np, nq), (np, nq), &[3, 3, 3], data);
                cases.push((case, data));
            }
        }
    }
    cases
}

/// Issue 3, item 5, exhaustively: every order combination, 0..=3
/// constraints with K up to 3. Every answer meets the bounds of
/// [`assert_conditions`] (residuals recomputed here); every refusal is
/// honest ([`solve_or_refuse`]); result degrees above the cap are refused
/// (none occur here: the largest is 29); and problems of result degree up to
/// [`STRICT_DEGREE`] are all answered (measured: the first refusals, of
/// ill-posed data, appear at degree 10).
#[test]
fn every_order_combination_meets_the_residual_bounds() {
    let cases = exhaustive_cases();
    assert_eq!(cases.len(), 2 * 44 * 44 + 2 * 64);
    let mut answered = 0;
    let mut orders_seen = std::collections::HashSet::new();
    for (case, _) in &cases {
        let o = &case.options;
        orders_seen.insert((case.p.degree(), case.q.degree(), o.p_order, o.q_order));
        let degree = o.result_degree();
        match solve_or_refuse(case) {
            Some(c) => {
                assert!(degree <= MAX_CONNECT_DEGREE);
                assert_conditions(case, &c);
                answered += 1;
            }
            None => assert!(degree > STRICT_DEGREE, "degree {degree} refused: {case:?}"),
        }
    }
    assert_eq!(orders_seen.len(), 44 * 44);
    // Refusals are the exception (measured: about 4 %).
    assert!(
        answered * 10 >= cases.len() * 9,
        "{answered} of {}",
        cases.len()
    );
}

/// Prints the worst measured residual per result degree and per decade of
/// amplification for the exhaustive cases (the numbers in docs/accuracy.md).
#[test]
#[ignore = "prints the exhaustive residual table for docs/accuracy.md"]
fn print_exhaustive_residuals() {
    let cases = exhaustive_cases();
    let mut by_degree = vec![(0usize, 0usize, 0.0f64, 0.0f64); MAX_CONNECT_DEGREE + 1];
    let mut by_amplification = [0.0f64; 10];
    let mut floor_ratio = 0.0f64;
    for (case, data) in &cases {
        let n = case.options.result_degree();
        by_degree[n].0 += 1;
        let Some(c) = solve_or_refuse(case) else {
            by_degree[n].1 += 1;
            continue;
        };
        let worst = worst_residual(case, &c);
        let a = amplification(case, &c);
        match data {
            ConstraintData::Natural => by_degree[n].2 = by_degree[n].2.max(worst),
            ConstraintData::Unrelated => by_degree[n].3 = by_degree[n].3.max(worst),
        }
        let decade = (a.log10().floor() as usize).min(9);
        by_amplification[decade] = by_amplification[decade].max(worst);
        floor_ratio = floor_ratio.max(worst / ((n + 1) as f64 * U * a));
    }
    println!("| result degree | cases | refused | worst, natural data | worst, unrelated data |");
    println!("|---:|---:|---:|---:|---:|");
    for (n, (count, refused, natural, unrelated)) in by_degree.iter().enumerate() {
        if *count > 0 {
            println!("| {n} | {count} | {refused} | {natural:.1e} | {unrelated:.1e} |");
        }
    }
    println!("\n| amplification A | worst residual |\n|---|---:|");
    for (decade, worst) in by_amplification.iter().enumerate() {
        println!("| [1e{decade}, 1e{}) | {worst:.1e} |", decade + 1);
    }
    println!("\nmax residual / ((n + 1) u A) = {floor_ratio:.2}");
}

/// Random inputs for the comparisons of the hot path (issue 20): degrees
/// 0..=7 in dimensions 1..=4, orders 0..=6, parameters at the ends and
/// inside, scales in `[1/4, 4]`; `nurbs` also gives P as a NURBS curve.
fn random_pair(
    rng: &mut Random,
    nurbs: bool,
) -> (bezjoin_core::Curve, f64, BezierCurve, f64, ConnectOptions) {
    let dim = 1 + rng.below(4);
    let (np, nq) = (rng.below(8), rng.below(8));
    let p = rng.curve(dim, np, 3.0);
    let q = rng.curve(dim, nq, 3.0);
    let parameter = |rng: &mut Random| match rng.below(4) {
        0 => 0.0,
        1 => 1.0,
        _ => rng.next(),
    };
    let (u0, v0) = (parameter(rng), parameter(rng));
    let (kp, kq) = (rng.below(7), rng.below(7));
    let (alpha, beta) = (rng.range(-2.0, 2.0).exp2(), rng.range(-2.0, 2.0).exp2());
    let options = ConnectOptions::new(kp, kq).with_scales(alpha, beta);
    let p = if nurbs && rng.below(2) == 0 {
        bezjoin_core::Curve::Nurbs(bezjoin_core::NurbsCurve::from_bezier(&p))
    } else {
        bezjoin_core::Curve::Bezier(p)
    };
    (p, u0, q, v0, options)
}

/// `connect` without interior constraints runs its allocation-free path
/// (the jets into stack buffers, the bands of `D(0)` and `D(1)`, the
/// substitutions and the residual check without matrices); the general
/// structured path with the condition rows as matrices stays behind
/// `connect_unchecked`. Same operations in the same order: the same control
/// points, residual and estimate bit for bit, and a refusal exactly when the
/// general path's estimate exceeds the limit (with that estimate). Bezier
/// and NURBS inputs, 600 random cases (fixed seed).
#[test]
fn connect_without_constraints_equals_the_general_structured_path() {
    let mut rng = Random(0x2020_c0ec_7001);
    let mut refused = 0;
    for case in 0..600 {
        let (p, u0, q, v0, options) = random_pair(&mut rng, true);
        let general = connect_unchecked(&p, u0, &q, v0, &options).unwrap();
        match connect(&p, u0, &q, v0, &options) {
            Ok(fast) => assert_eq!(fast, general, "case {case}: {options:?} u0 {u0} v0 {v0}"),
            Err(BezjoinError::IllConditioned { estimate, .. }) => {
                assert!(
                    general.error_estimate > CONNECT_RESIDUAL_LIMIT,
                    "case {case}"
                );
                assert_eq!(estimate, general.error_estimate, "case {case}");
                refused += 1;
            }
            Err(e) => panic!("case {case}: {e}"),
        }
    }
    eprintln!("{refused} of 600 refused by both paths");
    assert!(refused < 60, "{refused} of 600 refused");
}

/// The hot path against the dense LU reference (another algorithm, the
/// whole `(n+1) x (n+1)` system): both are checked to the residual limit by
/// the solver; their control points agree to `1e-11` of the larger control
/// point (measured at most 2.1e-14 on these 400 cases, fixed seed; result
/// degrees up to 13, backward-stable triangular solves against LU with
/// refinement).
#[test]
fn connect_without_constraints_agrees_with_the_dense_reference() {
    let mut rng = Random(0x2020_de45_e001);
    let mut worst = 0.0f64;
    for case in 0..400 {
        let (p, u0, q, v0, options) = random_pair(&mut rng, false);
        let (Ok(fast), Ok(dense)) = (
            connect(&p, u0, &q, v0, &options),
            connect_dense_reference(&p, u0, &q, v0, &options),
        ) else {
            continue;
        };
        let scale = fast.curve.coordinate_scale();
        let gap = common::max_abs_gap(fast.curve.points(), dense.curve.points()) / scale;
        worst = worst.max(gap);
        assert!(gap <= 1e-11, "case {case}: {gap:e} ({options:?})");
    }
    eprintln!("structured vs dense reference: worst relative gap {worst:e}");
}

#[test]
fn automatic_scale_of_nearly_stationary_ends_keeps_the_blend_in_size() {
    // Reliability R1: P ends at (6 + eps, 1) and Q starts at (10 - eps, -1),
    // each with its end poles eps apart (|P'| = |Q'| = 3 eps), on a shape 11
    // wide. The search was centred on s0 = chord / mean(|P'|, |Q'|), two
    // decades either side of 1e10 for eps = 1e-9, and every OK answer had
    // control points of 265 (eps = 1e-3) to 5e37 (eps = 1e-15, orders 3/3).
    // With each end's speed raised to its floor, the blend stays within the
    // shape and meets both conditions (1') to the residual promise.
    for eps in [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3] {
        let p = BezierCurve::from_rows(&[[0.0, 0.0], [3.0, 0.0], [6.0, 1.0], [6.0 + eps, 1.0]])
            .unwrap();
        let q =
            BezierCurve::from_rows(&[[10.0 - eps, -1.0], [10.0, -1.0], [10.0, 3.0], [11.0, 8.0]])
                .unwrap();
        for (kp, kq) in [(2, 2), (3, 3), (2, 3)] {
            let options = ConnectOptions::new(kp, kq).with_auto_scale();
            let c = connect(&p, 1.0, &q, 0.0, &options)
                .unwrap_or_else(|e| panic!("eps {eps:e}, orders {kp}/{kq}: {e}"));
            let size = c.curve.coordinate_scale();
            assert!(
                size < 12.0,
                "eps {eps:e}, orders {kp}/{kq}: control points up to {size}"
            );
            let given = options.with_scales(c.p_scale, c.q_scale);
            let case = Case {
                p: p.clone(),
                q: q.clone(),
                u0: 1.0,
                v0: 0.0,
                options: given,
            };
            let worst = worst_residual(&case, &c);
            assert!(
                worst <= CONNECT_RESIDUAL_LIMIT,
                "eps {eps:e}, orders {kp}/{kq}: relative residual {worst:e}"
            );
        }
    }
}

#[test]
fn an_automatic_scale_whose_blend_cannot_hold_its_tangents_is_refused() {
    // User testing, session 43: a corner of lines 10000 and 0.05 long, cut
    // 0.015 from the vertex, orders 1/1 with the automatic scale. One s for
    // ends whose speeds differ by 2e5 put the short line's first step
    // (s |Q'| / n) below the rounding of the coordinates far from the
    // origin: at 1e4 and 1e5 the stored blend left Q with its tangent off by
    // 4.9 and 164 degrees, every residual within its bound. The automatic
    // scale now stays where both steps hold their direction to
    // GEOMETRIC_CONDITION_LIMIT, or the connect is refused by name. Every
    // answer is judged here by the stored poles' first steps against P' and
    // Q'.
    let (mut answered, mut refused) = (0, 0);
    for turn in [90.0f64, 179.0] {
        for offset in [0.0, 1e4, 1e5] {
            let (a, b) = (0.3f64, 0.3 + turn.to_radians());
            let v = [offset, -offset];
            let p =
                BezierCurve::from_rows(&[[v[0] - 1e4 * a.cos(), v[1] - 1e4 * a.sin()], v]).unwrap();
            let q = BezierCurve::from_rows(&[v, [v[0] + 0.05 * b.cos(), v[1] + 0.05 * b.sin()]])
                .unwrap();
            let (u0, v0) = (1.0 - 0.015 / 1e4, 0.015 / 0.05);
            let options = ConnectOptions::new(1, 1).with_auto_scale();
            match connect(&p, u0, &q, v0, &options) {
                Ok(c) => {
                    answered += 1;
                    let points = c.curve.points();
                    let n = c.curve.degree();
                    let angle = |step: [f64; 2], along: [f64; 2]| {
                        let cross = step[0] * along[1] - step[1] * along[0];
                        let dot = step[0] * along[0] + step[1] * along[1];
                        cross.atan2(dot).abs()
                    };
                    let first = [points[2] - points[0], points[3] - points[1]];
                    let last = [
                        points[2 * n] - points[2 * n - 2],
                        points[2 * n + 1] - points[2 * n - 1],
                    ];
                    let errors = (
                        angle(first, [a.cos(), a.sin()]),
                        angle(last, [b.cos(), b.sin()]),
                    );
                    assert!(
                        errors.0.max(errors.1) <= 1e-6,
                        "turn {turn}, offset {offset:e}: tangents off by {errors:?} rad"
                    );
                }
                Err(BezjoinError::IllConditioned { what, estimate, .. }) => {
                    refused += 1;
                    assert!(
                        what.contains("first step at q") && what.contains("balanced"),
                        "{what}"
                    );
                    assert!(estimate > 1e-6, "{what}: estimate {estimate:e}");
                }
                Err(e) => panic!("turn {turn}, offset {offset:e}: {e}"),
            }
        }
    }
    // Near the origin the corner is answered; far from it, refused.
    assert!(
        answered >= 2 && refused >= 2,
        "answered {answered}, refused {refused}"
    );
}

/// The automatic scales size the blend by the gap between its ends, so
/// coincident ends (a line's end and the start of the next line) are
/// refused by name, `v0`, by both (user testing, session 44: a loop 0.003
/// across was answered at the corner); ends 1e-6 apart are answered, and
/// with given scales the loop is the caller's choice.
#[test]
fn automatic_scales_refuse_coincident_ends() {
    let p = BezierCurve::new(2, 1, vec![0.0, 0.0, 1.0, 0.0]).unwrap();
    let q = BezierCurve::new(2, 1, vec![1.0, 0.0, 1.0, 1.0]).unwrap();
    for options in [
        ConnectOptions::new(1, 1).with_auto_scale(),
        ConnectOptions::new(2, 1).with_balanced_scale(),
    ] {
        match connect(&p, 1.0, &q, 0.0, &options) {
            Err(BezjoinError::InvalidArgument { name, reason }) => {
                assert_eq!(name, "v0", "{reason}");
                assert!(reason.contains("loop"), "{reason}");
            }
            other => panic!("{:?}: {other:?}", options.scale),
        }
        assert!(connect(&p, 1.0, &q, 1e-6, &options).is_ok());
    }
    assert!(connect(&p, 1.0, &q, 0.0, &ConnectOptions::new(1, 1)).is_ok());
    // The ends' own coordinates decide, not the curves' far poles (review,
    // session 44: ends 0.5 apart next to a pole at 1e9 were refused).
    let far = BezierCurve::new(2, 2, vec![1.0, 0.5, 1.0, 1.0, 0.0, 1e9]).unwrap();
    for options in [
        ConnectOptions::new(1, 1).with_auto_scale(),
        ConnectOptions::new(1, 1).with_balanced_scale(),
    ] {
        assert!(connect(&p, 1.0, &far, 0.0, &options).is_ok());
    }
}

/// The U-turn between the facing ends of two parallel lines 10 apart (a
/// slot's end: the default blend of the workbench and of `bezjoin
/// connect`) is a U, not the chord with a kink at each end: with the
/// automatic and the balanced scale, orders 1 to 3, its curvature (sampled
/// at 2001 parameters) stays below 1 (ten over the gap; a semicircle has
/// 0.2) and it reaches 1 to 10 past the lines' ends. Before session 44 the
/// energy's minimum lay at the search range's lower end: curvature 6,000 at
/// both ends, 0.025 past the ends (user testing, session 44).
#[test]
fn the_u_turn_between_two_lines_is_a_u_not_two_kinks() {
    let p = BezierCurve::new(2, 1, vec![0.0, 0.0, 50.0, 0.0]).unwrap();
    let q = BezierCurve::new(2, 1, vec![50.0, 10.0, 0.0, 10.0]).unwrap();
    for k in 1..=3 {
        for options in [
            ConnectOptions::new(k, k).with_auto_scale(),
            ConnectOptions::new(k, k).with_balanced_scale(),
        ] {
            let c = connect(&p, 1.0, &q, 0.0, &options).unwrap();
            let mut reach = 0.0f64;
            for i in 0..=2000 {
                let t = i as f64 / 2000.0;
                let d = c.curve.eval_derivatives(t, 2);
                let (d1, d2) = ([d[2], d[3]], [d[4], d[5]]);
                let speed = d1[0].hypot(d1[1]);
                let curvature = (d1[0] * d2[1] - d1[1] * d2[0]).abs() / speed.powi(3);
                assert!(
                    curvature < 1.0,
                    "C{k} {:?} t = {t}: curvature {curvature}",
                    options.scale
                );
                reach = reach.max(d[0] - 50.0);
            }
            assert!(
                (1.0..=10.0).contains(&reach),
                "C{k} {:?}: reach {reach}",
                options.scale
            );
        }
    }
}
