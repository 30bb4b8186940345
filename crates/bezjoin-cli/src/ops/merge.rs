//! `bezjoin merge`: approximate merging of two consecutive curves into one
//! (mathematics.md section 3; Ganchuk et al. 2024 after Hu, Tong, Ju, Sun
//! 2001; for B-splines section 6, "Merge of B-splines"), through
//! [`bezjoin_core::merge_curves`].
//!
//! The curves may be given in any form a job accepts (Bezier, NURBS, arc).
//! Two Bezier curves give a Bezier `R`; anything else is merged as
//! polynomial B-splines into a B-spline `R` on `[0, 1]` whose interior knots
//! are `P`'s mapped into `(0, mu)` and `Q`'s into `(mu, 1)`, none at `mu`.
//! A rational curve (an arc, a NURBS curve whose weights differ) is refused
//! by the library naming the field (`q: the curve is rational ...`). Keep
//! points take `param` in their curve's own domain (`[0, 1]` for a Bezier
//! curve).
//!
//! Everything in the result's `"checks"` is measured by the tool from the
//! returned curves, not copied from the library's report: `R` on `[0, mu]`
//! and `[mu, 1]` against `P^` and `Q^`, `R` against "P then Q", and every
//! constraint of the job. A curve's parameter `u` in its domain `[a, b]`
//! corresponds to `R`'s `t0 + (t1 - t0) (u - a) / (b - a)` (`[t0, t1]` =
//! `[0, mu]` for `P`, `[mu, 1]` for `Q`).

use bezjoin_core::{
    Breakpoints, Curve, CurveMerge, KeepPoint, KnotSide, MIN_SPLIT, MergeMetric, MergeOptions,
    merge_curves, relative_jump,
};
use serde_json::{Value, json};

use crate::check::{JoinCheck, curve_json, distance, row};
use crate::job::{JobError, Located};
use crate::ops::{OperationKind, Scenario, describe_curve};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// Samples per piece of the tool's own distance measurements.
pub const CHECK_SAMPLES: usize = 400;

/// A parsed merge job.
pub struct MergeJob {
    /// The first curve, `P`, ending where `Q` starts (or nearly): Bezier,
    /// NURBS or arc.
    pub p: Curve,
    /// The second curve, `Q`.
    pub q: Curve,
    /// Metric, split, constraints, degree, accuracy.
    pub options: MergeOptions,
}

/// Keep points of `curve`: `param` in the curve's own domain.
fn keep_points(field: &Located, curve: &Curve) -> Result<Vec<KeepPoint>, JobError> {
    let (a, b) = curve.domain();
    let mut out = Vec::new();
    for item in field.array()? {
        let obj = item.object()?;
        let param = obj.required("param")?.number_in(a, b)?;
        let max_order = obj
            .optional("max_order")
            .map(|f| f.count())
            .transpose()?
            .unwrap_or(0);
        obj.finish()?;
        out.push(KeepPoint { param, max_order });
    }
    Ok(out)
}

/// Read a merge job.
pub fn parse(job: &Located) -> Result<MergeJob, JobError> {
    let obj = job.object()?;
    let p = obj.required("p")?.curve()?;
    let q = obj.required("q")?.curve()?;
    let mut options = MergeOptions::default();
    if let Some(f) = obj.optional("metric") {
        options.metric = match f.choice(&["discrete", "l2", "integral"])? {
            "discrete" => MergeMetric::Discrete,
            _ => MergeMetric::Integral,
        };
    }
    let mu = obj.optional("mu");
    let split = match obj.optional("split") {
        Some(f) => f.choice(&["given", "half", "polygon", "optimal"])?,
        None if mu.is_some() => "given",
        None => "half",
    };
    options.split = match split {
        "given" => {
            let f = obj.required("mu")?;
            // The library's rule for a given split (it said "[0, 1]" before:
            // user testing, session 40).
            Breakpoints::Given(vec![f.number_in(MIN_SPLIT, 1.0 - MIN_SPLIT)?])
        }
        other => {
            if let Some(f) = mu {
                return Err(JobError::new(
                    f.path.clone(),
                    format!("is only used with \"split\": \"given\", not {other:?}"),
                ));
            }
            match other {
                "half" => Breakpoints::Uniform,
                "polygon" => Breakpoints::PolygonLength,
                _ => Breakpoints::Optimal,
            }
        }
    };
    for (key, flag) in [
        ("keep_p", &mut options.keep_p),
        ("keep_q", &mut options.keep_q),
        ("fix_ends", &mut options.fix_ends),
    ] {
        if let Some(f) = obj.optional(key) {
            *flag = f.boolean()?;
        }
    }
    if let Some(f) = obj.optional("p_points") {
        options.p_points = keep_points(&f, &p)?;
    }
    if let Some(f) = obj.optional("q_points") {
        options.q_points = keep_points(&f, &q)?;
    }
    if let Some(f) = obj.optional("degree") {
        options.degree = Some(f.count()?);
    }
    if let Some(f) = obj.optional("accuracy") {
        options.accuracy = f.positive()?;
    }
    obj.finish()?;
    Ok(MergeJob { p, q, options })
}

/// Run a merge job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    let merged = merge_curves(&job.p, &job.q, &job.options)?;
    Ok(outcome(&job, &merged))
}

/// Where a curve went in `R`: the interval `[t0, t1]` of `R`'s parameter
/// (within `R`'s domain `[0, 1]`).
#[derive(Debug, Clone, Copy)]
struct Placement {
    t0: f64,
    t1: f64,
}

impl Placement {
    /// `R`'s parameter for `curve`'s parameter `u`.
    fn map(self, curve: &Curve, u: f64) -> f64 {
        let (a, b) = curve.domain();
        self.t0 + (self.t1 - self.t0) * ((u - a) / (b - a))
    }

    /// `R`'s parameter interval per unit of `curve`'s parameter (the
    /// factor of each derivative order).
    fn rate(self, curve: &Curve) -> f64 {
        let (a, b) = curve.domain();
        (self.t1 - self.t0) / (b - a)
    }
}

/// Largest distance between `curve(u)` and `R` at the mapped parameter,
/// over `CHECK_SAMPLES + 1` evenly spaced `u` in `curve`'s domain.
fn sampled_distance(curve: &Curve, r: &Curve, place: Placement) -> f64 {
    let (a, b) = curve.domain();
    (0..=CHECK_SAMPLES)
        .map(|i| {
            let s = i as f64 / CHECK_SAMPLES as f64;
            let u = if i == CHECK_SAMPLES {
                b
            } else {
                a + (b - a) * s
            };
            distance(&curve.eval(u), &r.eval(place.map(curve, u)))
        })
        .fold(0.0, f64::max)
}

/// The kept point of `curve` at `param` (its own parameter) against `R` at
/// the mapped parameter: `R^(k) rate^k` against `curve^(k)`, orders
/// `0..=max_order`, both from the right at a knot (from the left at the
/// end of the domain), as the library imposes them.
fn keep_point_check(
    name: &str,
    curve: &Curve,
    r: &Curve,
    place: Placement,
    point: &KeepPoint,
) -> (Value, f64) {
    let orders = point.max_order;
    let want = curve.eval_derivatives_side(point.param, orders, KnotSide::Right);
    let at = place.map(curve, point.param);
    let got = r.eval_derivatives_side(at, orders, KnotSide::Right);
    let rate = place.rate(curve);
    let dim = curve.dim();
    let mut worst: f64 = 0.0;
    let residuals: Vec<f64> = (0..=orders)
        .map(|k| {
            let scale = rate.powi(k as i32);
            let g: Vec<f64> = row(&got, dim, k).iter().map(|x| x * scale).collect();
            let jump = relative_jump(&g, row(&want, dim, k));
            worst = worst.max(jump);
            jump
        })
        .collect();
    let point_distance = distance(&r.eval(at), &curve.eval(point.param));
    (
        json!({
            "curve": name,
            "param": point.param,
            "max_order": point.max_order,
            "relative_residuals": residuals,
            "point_distance": point_distance,
        }),
        worst,
    )
}

/// The tool's own measurements of a merge.
struct Checks {
    json: Value,
    split_vs_hats: f64,
    r_vs_p_then_q: f64,
    worst_constraint: Option<f64>,
}

/// Where `P` and `Q` went in `R`: `[0, mu]` and `[mu, 1]` of `R`'s domain.
fn placements(r: &Curve, mu: f64) -> (Placement, Placement) {
    let (r0, r1) = r.domain();
    let at = |t: f64| r0 + (r1 - r0) * t;
    (
        Placement {
            t0: at(0.0),
            t1: at(mu),
        },
        Placement {
            t0: at(mu),
            t1: at(1.0),
        },
    )
}

fn measure(job: &MergeJob, m: &CurveMerge) -> Checks {
    let r = &m.merged;
    let (left, right) = placements(r, m.report.mu);
    let split_vs_hats =
        sampled_distance(&m.p_hat, r, left).max(sampled_distance(&m.q_hat, r, right));
    let r_vs_p_then_q = sampled_distance(&job.p, r, left).max(sampled_distance(&job.q, r, right));
    let mut constraints = Vec::new();
    let mut worst: Option<f64> = None;
    let mut note = |w: f64| worst = Some(worst.unwrap_or(0.0).max(w));
    if job.options.keep_p {
        let d = sampled_distance(&job.p, r, left);
        note(d);
        constraints.push(json!({"constraint": "keep_p", "max_distance_R_on_[0,mu]_to_P": d}));
    }
    if job.options.keep_q {
        let d = sampled_distance(&job.q, r, right);
        note(d);
        constraints.push(json!({"constraint": "keep_q", "max_distance_R_on_[mu,1]_to_Q": d}));
    }
    if job.options.fix_ends {
        let (r0, r1) = r.domain();
        let start = distance(&r.eval(r0), &job.p.eval(job.p.domain().0));
        let end = distance(&r.eval(r1), &job.q.eval(job.q.domain().1));
        note(start.max(end));
        constraints.push(json!({
            "constraint": "fix_ends",
            "distance_R(0)_to_P(start)": start,
            "distance_R(1)_to_Q(end)": end,
        }));
    }
    for point in &job.options.p_points {
        let (j, w) = keep_point_check("P", &job.p, r, left, point);
        note(w);
        constraints.push(j);
    }
    for point in &job.options.q_points {
        let (j, w) = keep_point_check("Q", &job.q, r, right, point);
        note(w);
        constraints.push(j);
    }
    Checks {
        json: json!({
            "samples_per_piece": CHECK_SAMPLES + 1,
            "max_distance_R_split_at_mu_to_p_hat_q_hat": split_vs_hats,
            "max_distance_R_to_P_then_Q": r_vs_p_then_q,
            "constraints": constraints,
        }),
        split_vs_hats,
        r_vs_p_then_q,
        worst_constraint: worst,
    }
}

fn metric_name(metric: MergeMetric) -> &'static str {
    match metric {
        MergeMetric::Discrete => "discrete",
        MergeMetric::Integral => "integral",
    }
}

fn split_name(split: &Breakpoints) -> &'static str {
    match split {
        Breakpoints::Given(_) => "given",
        Breakpoints::Uniform => "half",
        Breakpoints::PolygonLength => "polygon",
        Breakpoints::Optimal => "optimal",
    }
}

/// `"bezier"` or `"nurbs"`: the kind of a result curve.
fn kind_name(curve: &Curve) -> &'static str {
    match curve {
        Curve::Bezier(_) => "bezier",
        Curve::Nurbs(_) => "nurbs",
    }
}

fn outcome(job: &MergeJob, m: &CurveMerge) -> Outcome {
    let r = &m.merged;
    let report = &m.report;
    let checks = measure(job, m);
    let o = &job.options;
    let json = json!({
        "operation": "merge",
        "curve": curve_json(r),
        "p_hat": curve_json(&m.p_hat),
        "q_hat": curve_json(&m.q_hat),
        "report": {
            "kind": kind_name(r),
            "degree": r.degree(),
            "metric": metric_name(o.metric),
            "split": split_name(&o.split),
            "mu": report.mu,
            "metric_value": report.metric_value,
            "max_deviation": report.max_deviation,
            "solve_error_estimate": report.solve_error_estimate,
            "split_check_error": report.split_check_error,
        },
        "checks": checks.json,
    });

    let (left, _) = placements(r, report.mu);
    let mut figure = Figure::new("Merging two curves into one");
    for (curve, name) in [(&job.p, "P"), (&job.q, "Q")] {
        figure.curve(CurveItem::new(
            curve,
            Role::Input,
            format!("{name}, {}", describe_curve(curve)),
        ));
    }
    figure.curve(CurveItem::new(
        r,
        Role::Result,
        format!("R, {}", describe_curve(r)),
    ));
    figure.marker(Marker::new(
        MarkerKind::Join,
        &r.eval(left.t1),
        format!("R(mu), mu = {:.4}", report.mu),
    ));
    let mut kept = Vec::new();
    if o.keep_p {
        kept.push("P kept".to_string());
    }
    if o.keep_q {
        kept.push("Q kept".to_string());
    }
    if o.fix_ends {
        kept.push("ends fixed".to_string());
        figure.marker(Marker::new(
            MarkerKind::Constraint,
            &job.p.eval(job.p.domain().0),
            "P(start) fixed",
        ));
        figure.marker(Marker::new(
            MarkerKind::Constraint,
            &job.q.eval(job.q.domain().1),
            "Q(end) fixed",
        ));
    }
    for (curve, name, points) in [(&job.p, "P", &o.p_points), (&job.q, "Q", &o.q_points)] {
        for point in points {
            kept.push(format!(
                "{name}({}) orders 0..{}",
                point.param, point.max_order
            ));
            figure.marker(Marker::new(
                MarkerKind::Constraint,
                &curve.eval(point.param),
                format!(
                    "{name}({}) kept, orders 0..{}",
                    point.param, point.max_order
                ),
            ));
        }
    }
    figure.line(format!(
        "R: degree {}; metric {} = {:.3e}; mu = {:.6} ({}); constraints: {}",
        r.degree(),
        metric_name(o.metric),
        report.metric_value,
        report.mu,
        split_name(&o.split),
        if kept.is_empty() {
            "none".to_string()
        } else {
            kept.join(", ")
        }
    ));
    if let Curve::Nurbs(n) = r {
        let (knots, _) = n.interior_knots();
        figure.line(format!(
            "R is a polynomial B-spline on [0, 1] with {} interior knot{}: P's mapped into (0, mu), Q's into (mu, 1), none at mu",
            knots.len(),
            if knots.len() == 1 { "" } else { "s" }
        ));
    }
    figure.line(format!(
        "Measured by the tool: max |R - (P then Q)| = {:.3e}; R split at mu vs P^, Q^: {:.1e}",
        checks.r_vs_p_then_q, checks.split_vs_hats
    ));
    if let Some(w) = checks.worst_constraint {
        figure.line(format!(
            "Worst measured constraint residual (distance or relative derivative jump): {w:.1e}"
        ));
    }
    // P^ and Q^ are the pieces of R around mu, one polynomial piece of R
    // spanning the join (no knot there): they join with every derivative
    // (C^n, n = degree), measured from the returned curves.
    let split_join = (report.mu > 0.0 && report.mu < 1.0).then(|| {
        JoinCheck::measure(
            "P^|Q^ at R(mu)",
            &m.p_hat,
            report.mu,
            &m.q_hat,
            1.0 - report.mu,
            r.degree(),
        )
    });
    if let Some(check) = &split_join {
        figure.line(check.describe());
    }
    Outcome {
        json,
        figure,
        summary: Summary {
            degree: r.degree(),
            worst_continuity_jump: split_join.as_ref().map(JoinCheck::worst_promised),
            max_deviation: Some(checks.r_vs_p_then_q),
            deviation_meaning: "R against P then Q (sampled)",
        },
    }
}

/// The two demo cubics: one cubic split at 0.45, then Q moved by up to
/// 0.18, so they meet with a small gap and a slight kink.
fn demo_curves() -> (Value, Value) {
    (
        json!([[0.0, 0.0], [1.125, 1.8], [2.351, 1.676], [3.588, 1.269]]),
        json!([[3.648, 1.219], [5.219, 0.921], [6.475, -0.05], [8.0, 1.5]]),
    )
}

fn scenario(
    name: &'static str,
    title: &'static str,
    description: &'static str,
    extra: Value,
) -> Scenario {
    let (p, q) = demo_curves();
    let mut job = json!({ "p": p, "q": q });
    if let (Value::Object(target), Value::Object(source)) = (&mut job, extra) {
        target.extend(source);
    }
    Scenario {
        name,
        operation: OperationKind::Merge,
        title,
        description,
        job,
    }
}

/// Two cubic B-splines: one B-spline on `[0, 5]` (knots 1, 2, 3, 4) split
/// at 1.6, not a knot, then `Q`'s first three poles moved by less than 0.09, so
/// they meet with a small gap and a slight kink. `P` keeps the parameters
/// `[0, 1.6]`, `Q` `[1.6, 5]`.
fn demo_bsplines() -> Value {
    json!({
        "p": {
            "degree": 3,
            "poles": [[0.0, 0.0], [0.8, 1.7], [1.76, 2.02], [2.464, 1.529], [2.721, 1.368]],
            "knots": [0.0, 0.0, 0.0, 0.0, 1.0, 1.6, 1.6, 1.6, 1.6]
        },
        "q": {
            "degree": 3,
            "poles": [
                [2.78, 1.31], [2.95, 1.22], [3.52, 0.97], [4.6, 1.4], [5.8, 0.2], [7.0, -0.3], [8.0, 1.2]
            ],
            "knots": [1.6, 1.6, 1.6, 1.6, 2.0, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0]
        }
    })
}

/// The demo's merge scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    let mut bsplines = demo_bsplines();
    if let Value::Object(job) = &mut bsplines {
        job.extend([
            ("metric".to_string(), json!("integral")),
            ("split".to_string(), json!("optimal")),
            ("fix_ends".to_string(), json!(true)),
        ]);
    }
    vec![
        scenario(
            "merge-discrete",
            "Merge, discrete metric, mu = 1/2",
            "Two cubics with a small gap and kink merged into one cubic, smallest sum of squared control-point changes.",
            json!({"metric": "discrete", "split": "half"}),
        ),
        scenario(
            "merge-integral-optimal",
            "Merge, integral metric, optimal mu",
            "The L2 distance of the changed curves from the given ones is minimised, over mu too.",
            json!({"metric": "integral", "split": "optimal"}),
        ),
        scenario(
            "merge-keep-p",
            "Merge keeping P",
            "P stays exactly (R on [0, mu] is P); only Q changes.",
            json!({"metric": "discrete", "split": "polygon", "keep_p": true}),
        ),
        scenario(
            "merge-keep-q",
            "Merge keeping Q",
            "Q stays exactly (R on [mu, 1] is Q); only P changes.",
            json!({"metric": "integral", "split": "polygon", "keep_q": true}),
        ),
        scenario(
            "merge-fix-ends",
            "Merge with fixed ends",
            "P(0) and Q(1) stay where they are.",
            json!({"metric": "integral", "split": "optimal", "fix_ends": true}),
        ),
        scenario(
            "merge-keep-point",
            "Merge keeping a point with derivatives",
            "Degree 5 result keeping P(0.5) with derivatives up to order 1 and Q(1) up to order 1.",
            json!({
                "metric": "discrete",
                "split": "given",
                "mu": 0.5,
                "degree": 5,
                "p_points": [{"param": 0.5, "max_order": 1}],
                "q_points": [{"param": 1.0, "max_order": 1}]
            }),
        ),
        Scenario {
            name: "merge-bsplines",
            operation: OperationKind::Merge,
            title: "Merge of two cubic B-splines, integral metric, optimal mu",
            description: "One cubic B-spline split at 1.6 (not a knot), then Q's first poles moved by less than \
                          0.09: two polynomial B-splines (P on [0, 1.6], one interior knot; Q on [1.6, 5], \
                          three) with a small gap and kink, merged into one cubic B-spline on [0, 1] \
                          (section 6): P's interior knot mapped into (0, mu), Q's into (mu, 1), no knot at mu, \
                          so one polynomial piece spans the join; ends fixed.",
            job: bsplines,
        },
    ]
}
