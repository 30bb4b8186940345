//! `bezjoin merge` on B-splines (issue 17), run as a process: NURBS curves
//! in the job, the merged B-spline and the pieces re-read from the printed
//! JSON and checked with the library's own evaluation, never against
//! numbers copied from an earlier run.
//!
//! The defining properties: one B-spline split off a knot and merged back
//! at the split's `mu` is itself; `R`'s interior knots are `P`'s mapped
//! affinely into `(0, mu)` and `Q`'s into `(mu, 1)` with none at `mu`; `P^`,
//! `Q^` are `R`'s pieces on `P`'s and `Q`'s own knots and parameters; the
//! constraints hold in each curve's own parameter; a rational curve is
//! refused naming its field.

mod common;

use std::f64::consts::PI;

use bezjoin_core::{BezierCurve, Curve, KnotSide, NurbsCurve};
use serde_json::{Value, json};

/// Run `bezjoin merge` with `job` on stdin: (exit code, stdout, stderr).
fn run(job: &Value) -> (i32, String, String) {
    let out = common::run_bezjoin(&["merge", "-"], job.to_string().as_bytes());
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn run_ok(job: &Value) -> Value {
    let (code, stdout, stderr) = run(job);
    assert_eq!(code, 0, "bezjoin merge: {stderr}");
    serde_json::from_str(&stdout).expect("a JSON result")
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn rows(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().flat_map(numbers).collect()
}

/// A printed NURBS curve, rebuilt with the library; it must be polynomial
/// (every printed weight 1).
fn nurbs(v: &Value) -> NurbsCurve {
    let weights = numbers(&v["weights"]);
    assert!(
        weights.iter().all(|&w| w == 1.0),
        "a polynomial B-spline: {weights:?}"
    );
    assert!(v.get("points").is_none(), "NURBS form, not Bezier: {v}");
    NurbsCurve::new(
        v["dim"].as_u64().unwrap() as usize,
        v["degree"].as_u64().unwrap() as usize,
        rows(&v["poles"]),
        None,
        numbers(&v["knots"]),
    )
    .unwrap()
}

/// A curve as a job gives it: `{"degree", "poles", "knots"}`.
fn job_curve(c: &NurbsCurve) -> Value {
    json!({
        "degree": c.degree(),
        "poles": (0..c.point_count()).map(|i| c.point(i).to_vec()).collect::<Vec<_>>(),
        "knots": c.knots(),
    })
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Largest distance between `a(u)` and `b(map(u))` over 301 evenly spaced
/// `u` in `a`'s domain.
fn max_distance(a: &Curve, b: &Curve, map: impl Fn(f64) -> f64) -> f64 {
    let (lo, hi) = a.domain();
    (0..=300)
        .map(|i| {
            let u = lo + (hi - lo) * i as f64 / 300.0;
            dist(&a.eval(u), &b.eval(map(u)))
        })
        .fold(0.0, f64::max)
}

/// `R`'s parameter for `u` of a curve with domain `(a, b)` placed on
/// `[t0, t1]`.
fn affine((a, b): (f64, f64), (t0, t1): (f64, f64)) -> impl Fn(f64) -> f64 {
    move |u| t0 + (t1 - t0) * ((u - a) / (b - a))
}

/// The knots of `c` strictly inside its domain, in order, with repeats.
fn interior(c: &NurbsCurve) -> Vec<f64> {
    let (a, b) = c.domain();
    c.knots()
        .iter()
        .copied()
        .filter(|&k| k > a && k < b)
        .collect()
}

/// A cubic B-spline on `[0, 4]` with interior knots 1, 2, 3.
fn cubic_on_0_4() -> NurbsCurve {
    NurbsCurve::new(
        2,
        3,
        vec![
            0.0, 0.0, 1.0, 2.0, 2.5, 2.5, 3.5, 0.5, 5.0, 1.5, 6.0, -1.0, 7.5, 0.5,
        ],
        None,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0],
    )
    .unwrap()
}

/// Checks every merge result: `R` is a polynomial B-spline on `[0, 1]`
/// whose interior knots are exactly `P`'s mapped into `(0, mu)` then `Q`'s
/// into `(mu, 1)` (multiplicities kept), none at `mu`, with `nP + nQ - p -
/// 1` poles; `P^`, `Q^` carry `P`'s and `Q`'s own knots and are `R` on
/// `[0, mu]` and `[mu, 1]` in those parameters. Returns `R` and `mu`.
fn check_merged(p: &NurbsCurve, q: &NurbsCurve, out: &Value) -> (Curve, f64) {
    let r = nurbs(&out["curve"]);
    let mu = out["report"]["mu"].as_f64().unwrap();
    assert!(mu > 0.0 && mu < 1.0, "mu = {mu}");
    assert_eq!(out["report"]["kind"], "nurbs");
    assert_eq!(r.domain(), (0.0, 1.0));
    let degree = r.degree();
    assert_eq!(degree, p.degree().max(q.degree()));
    assert_eq!(
        r.point_count(),
        p.point_count() + q.point_count() - degree - 1
    );
    let expected: Vec<f64> = interior(p)
        .into_iter()
        .map(affine(p.domain(), (0.0, mu)))
        .chain(interior(q).into_iter().map(affine(q.domain(), (mu, 1.0))))
        .collect();
    let got = interior(&r);
    assert_eq!(got.len(), expected.len(), "{got:?} vs {expected:?}");
    for (g, e) in got.iter().zip(&expected) {
        assert!(
            (g - e).abs() <= 1e-15,
            "knots {got:?}, expected {expected:?}"
        );
    }
    assert!(
        r.knots().iter().all(|k| (k - mu).abs() > 1e-9),
        "a knot at mu = {mu}: {:?}",
        r.knots()
    );
    assert_eq!(r.multiplicity(0.0), degree + 1);
    assert_eq!(r.multiplicity(1.0), degree + 1);
    let r = Curve::Nurbs(r);
    let scale = 10.0;
    for (hat, given, place) in [
        (nurbs(&out["p_hat"]), p, (0.0, mu)),
        (nurbs(&out["q_hat"]), q, (mu, 1.0)),
    ] {
        assert_eq!(hat.domain(), given.domain());
        let (a, b) = given.domain();
        let (hk, _) = hat.knots_with_multiplicities();
        let (gk, _) = given.knots_with_multiplicities();
        assert_eq!(hk, gk, "the piece keeps its curve's knot values");
        assert!(hat.knots().iter().all(|k| (a..=b).contains(k)));
        let d = max_distance(&Curve::Nurbs(hat), &r, affine((a, b), place));
        assert!(d < 1e-12 * scale, "piece vs R: {d}");
    }
    (r, mu)
}

/// One cubic B-spline split at 2.5 (not a knot) and merged back with
/// `mu = 2.5 / 4`: the pieces' knots map onto the original's knots over 4,
/// and the original itself, `C(4 t)`, is feasible with zero change, so it
/// is the merge, for either metric. `P^`, `Q^` are `P`, `Q` unchanged.
#[test]
fn a_bspline_split_off_a_knot_merges_back_to_itself() {
    let c = cubic_on_0_4();
    let (p, q) = c.split_at(2.5).unwrap();
    assert_eq!((p.domain(), q.domain()), ((0.0, 2.5), (2.5, 4.0)));
    let whole = Curve::Nurbs(c.clone());
    for metric in ["discrete", "integral"] {
        let job = json!({"p": job_curve(&p), "q": job_curve(&q), "metric": metric, "mu": 0.625});
        let out = run_ok(&job);
        let (r, mu) = check_merged(&p, &q, &out);
        assert_eq!(mu, 0.625);
        let d = max_distance(&whole, &r, |u| u / 4.0);
        assert!(d < 1e-12, "{metric}: |R(u / 4) - C(u)| up to {d}");
        let rn = r.as_nurbs().unwrap();
        let scaled: Vec<f64> = c.knots().iter().map(|k| k / 4.0).collect();
        for (g, e) in rn.knots().iter().zip(&scaled) {
            assert!((g - e).abs() < 1e-15, "{:?} vs {scaled:?}", rn.knots());
        }
        for (hat, given) in [(&out["p_hat"], &p), (&out["q_hat"], &q)] {
            let hat = Curve::Nurbs(nurbs(hat));
            let given = Curve::Nurbs(given.clone());
            assert!(max_distance(&given, &hat, |u| u) < 1e-12, "{metric}");
        }
        let report = &out["report"];
        assert!(report["metric_value"].as_f64().unwrap() < 1e-20, "{report}");
        assert!(
            report["max_deviation"].as_f64().unwrap() < 1e-12,
            "{report}"
        );
        assert!(
            out["checks"]["max_distance_R_to_P_then_Q"]
                .as_f64()
                .unwrap()
                < 1e-12
        );
    }
}

/// Two B-splines that do not join (a gap at `P`'s end, a double knot in
/// `P`, `Q` on `[5, 8]`): for every way of choosing `mu`, `R`'s interior
/// knots are the mapped ones and none sits at `mu` (`check_merged`); `R`
/// really changes the curves, and is `C^p` at `R(mu)`: the pieces' last and
/// first derivatives agree up to the degree in `R`'s parameter.
#[test]
fn unrelated_bsplines_give_mapped_knots_and_none_at_mu() {
    let p = NurbsCurve::new(
        2,
        3,
        vec![
            0.0, 0.0, 0.5, 1.2, 1.5, 1.6, 2.2, 0.4, 3.0, 0.9, 3.6, 1.8, 4.0, 1.0,
        ],
        None,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 1.1, 1.1, 2.0, 2.0, 2.0, 2.0],
    )
    .unwrap();
    let q = NurbsCurve::new(
        2,
        3,
        vec![4.1, 1.2, 4.9, 0.3, 6.0, 0.8, 7.0, 2.0, 8.0, 1.0, 9.0, 0.0],
        None,
        vec![5.0, 5.0, 5.0, 5.0, 6.0, 7.5, 8.0, 8.0, 8.0, 8.0],
    )
    .unwrap();
    let polygon_mu = p.polygon_length() / (p.polygon_length() + q.polygon_length());
    for split in [
        json!({"mu": 0.4}),
        json!({"split": "half"}),
        json!({"split": "polygon"}),
        json!({"split": "optimal", "metric": "integral"}),
    ] {
        let mut job = json!({"p": job_curve(&p), "q": job_curve(&q)});
        job.as_object_mut()
            .unwrap()
            .extend(split.as_object().unwrap().clone());
        let out = run_ok(&job);
        let (r, mu) = check_merged(&p, &q, &out);
        match split.get("split").and_then(Value::as_str) {
            None => assert_eq!(mu, 0.4),
            Some("half") => assert_eq!(mu, 0.5),
            Some("polygon") => assert!((mu - polygon_mu).abs() < 1e-12, "{mu} vs {polygon_mu}"),
            Some(_) => {}
        }
        let deviation =
            max_distance(&Curve::Nurbs(p.clone()), &r, affine(p.domain(), (0.0, mu))).max(
                max_distance(&Curve::Nurbs(q.clone()), &r, affine(q.domain(), (mu, 1.0))),
            );
        assert!(deviation > 1e-3, "{split}: the gap forces a change");
        let hp = nurbs(&out["p_hat"]);
        let hq = nurbs(&out["q_hat"]);
        let left = hp.eval_derivatives_side(hp.domain().1, 3, KnotSide::Left);
        let right = hq.eval_derivatives_side(hq.domain().0, 3, KnotSide::Right);
        let (lp, lq) = (2.0 / mu, 3.0 / (1.0 - mu));
        for k in 0..=3 {
            let a: Vec<f64> = left[2 * k..2 * k + 2]
                .iter()
                .map(|x| x * lp.powi(k as i32))
                .collect();
            let b: Vec<f64> = right[2 * k..2 * k + 2]
                .iter()
                .map(|x| x * lq.powi(k as i32))
                .collect();
            let size = a.iter().chain(&b).fold(1.0f64, |m, x| m.max(x.abs()));
            assert!(
                dist(&a, &b) < 1e-9 * size,
                "{split}: order {k}: {a:?} vs {b:?}"
            );
        }
    }
}

/// A Bezier curve and a B-spline: merged as B-splines, so `R` is a
/// B-spline whose only interior knots are `Q`'s (the Bezier curve has
/// none), and keep_p holds: `R` on `[0, mu]` is `P`.
#[test]
fn a_bezier_curve_and_a_bspline_give_a_bspline_keeping_p() {
    let bezier = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [2.5, 2.0], [3.0, 0.5]]).unwrap();
    let p = NurbsCurve::from_bezier(&bezier);
    let q = NurbsCurve::new(
        2,
        2,
        vec![3.1, 0.4, 3.8, -0.8, 5.0, 0.0, 6.0, 1.0],
        None,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
    )
    .unwrap();
    let job = json!({
        "p": [[0.0, 0.0], [1.0, 2.0], [2.5, 2.0], [3.0, 0.5]],
        "q": job_curve(&q),
        "keep_p": true,
        "mu": 0.5,
    });
    let out = run_ok(&job);
    // Q is elevated to degree 3 first (exactly): its interior knot then
    // has multiplicity 2.
    let q3 = q.elevate_degree(3).unwrap();
    let (r, mu) = check_merged(&p, &q3, &out);
    assert_eq!(interior(r.as_nurbs().unwrap()), vec![0.75, 0.75]);
    let d = max_distance(&Curve::Bezier(bezier), &r, |u| mu * u);
    assert!(d < 1e-12, "keep_p: R on [0, mu] is P ({d})");
}

/// Keep points take `param` in their curve's own domain: `Q` on `[5, 8]`
/// keeps `Q(6.5)` with its first derivative, `P` on `[0, 2]` its end with
/// ends fixed; a `param` outside the curve's domain is refused naming the
/// field.
#[test]
fn keep_points_are_in_each_curves_own_parameter() {
    let p = NurbsCurve::new(
        2,
        2,
        vec![0.0, 0.0, 1.0, 1.5, 2.0, 1.0, 3.0, 1.5],
        None,
        vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0],
    )
    .unwrap();
    let q = NurbsCurve::new(
        2,
        2,
        vec![3.1, 1.4, 4.0, 0.0, 5.5, 0.5, 6.0, 1.5],
        None,
        vec![5.0, 5.0, 5.0, 6.0, 8.0, 8.0, 8.0],
    )
    .unwrap();
    let job = json!({
        "p": job_curve(&p),
        "q": job_curve(&q),
        "degree": 4,
        "metric": "integral",
        "fix_ends": true,
        "mu": 0.45,
        "p_points": [{"param": 2.0, "max_order": 1}],
        "q_points": [{"param": 6.5, "max_order": 1}],
    });
    let out = run_ok(&job);
    let (p4, q4) = (p.elevate_degree(4).unwrap(), q.elevate_degree(4).unwrap());
    let (r, mu) = check_merged(&p4, &q4, &out);
    let r = r.as_nurbs().unwrap();
    assert!(dist(&r.eval(0.0), &p.eval(0.0)) < 1e-12);
    assert!(dist(&r.eval(1.0), &q.eval(8.0)) < 1e-12);
    for (curve, u, place) in [(&p, 2.0, (0.0, mu)), (&q, 6.5, (mu, 1.0))] {
        let (a, b) = curve.domain();
        let rate = (place.1 - place.0) / (b - a);
        let want = curve.eval_derivatives(u, 1);
        let got = r.eval_derivatives(affine((a, b), place)(u), 1);
        assert!(dist(&got[..2], &want[..2]) < 1e-12, "point at {u}");
        let scaled: Vec<f64> = got[2..].iter().map(|x| x * rate).collect();
        assert!(
            dist(&scaled, &want[2..]) < 1e-9 * (1.0 + dist(&want[2..], &[0.0, 0.0])),
            "derivative at {u}"
        );
    }
    let mut bad = job.clone();
    bad["q_points"] = json!([{"param": 0.5}]);
    let (code, _, stderr) = run(&bad);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("q_points[0].param: 0.5 is outside [5, 8]"),
        "{stderr}"
    );
}

/// A rational curve (a circular arc, or a NURBS curve whose weights
/// differ) cannot be merged as a polynomial B-spline: exit 2, nothing on
/// standard output, and the message names the field that holds it and says
/// why. The same poles with every weight 1 are polynomial and accepted.
#[test]
fn a_rational_curve_is_refused_naming_it() {
    let line = json!([[-1.0, 0.0], [0.0, 1.0]]);
    let arc = json!({"arc": {"centre": [1.0, 1.0], "radius": 1.0, "start_angle": PI, "end_angle": 1.5 * PI}});
    let (code, stdout, stderr) = run(&json!({"p": line, "q": arc}));
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(
        stderr.contains("invalid job: q: the curve is rational"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let weighted = |weights: Value| {
        json!({
            "degree": 2,
            "poles": [[-3.0, 0.0], [-2.0, 1.5], [-1.0, 0.2], [-1.0, 0.0]],
            "knots": [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
            "weights": weights,
        })
    };
    let (code, _, stderr) = run(&json!({"p": weighted(json!([1.0, 2.0, 1.0, 1.0])), "q": line}));
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("invalid job: p: the curve is rational"),
        "{stderr}"
    );
    let out = run_ok(&json!({"p": weighted(json!([1.0, 1.0, 1.0, 1.0])), "q": line}));
    nurbs(&out["curve"]);
}

/// The printed result is accepted back as a job's curve, as the other
/// operations' are: merging `R` with a continuation of itself works.
#[test]
fn the_printed_result_is_accepted_back() {
    let c = cubic_on_0_4();
    let (p, q) = c.split_at(1.5).unwrap();
    let out = run_ok(&json!({"p": job_curve(&p), "q": job_curve(&q)}));
    let r = nurbs(&out["curve"]);
    let tail = NurbsCurve::from_bezier(
        &BezierCurve::from_rows(&[
            r.eval(1.0),
            vec![9.0, 1.0],
            vec![10.0, 0.0],
            vec![11.0, 1.0],
        ])
        .unwrap(),
    );
    let again = run_ok(&json!({"p": out["curve"], "q": job_curve(&tail), "split": "polygon"}));
    check_merged(&r, &tail, &again);
}
