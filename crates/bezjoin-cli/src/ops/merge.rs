//! `bezjoin merge`: approximate merging of two consecutive Bezier curves
//! into one (mathematics.md section 3; Ganchuk et al. 2024 after Hu, Tong,
//! Ju, Sun 2001), through [`bezjoin_core::merge`].
//!
//! Everything in the result's `"checks"` is measured by the tool from the
//! returned control points, not copied from the library's report: `R` split
//! at `mu` against `P^` and `Q^`, `R` against "P then Q", and every
//! constraint of the job.

use bezjoin_core::{
    BezierCurve, Breakpoints, KeepPoint, Merge, MergeMetric, MergeOptions, merge, relative_jump,
};
use serde_json::{Value, json};

use crate::check::{JoinCheck, curve_json, distance, row};
use crate::job::{JobError, Located};
use crate::ops::{OperationKind, Scenario};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// Samples per piece of the tool's own distance measurements.
pub const CHECK_SAMPLES: usize = 400;

/// A parsed merge job.
pub struct MergeJob {
    /// The first curve, `P`, ending where `Q` starts (or nearly).
    pub p: BezierCurve,
    /// The second curve, `Q`.
    pub q: BezierCurve,
    /// Metric, split, constraints, degree, accuracy.
    pub options: MergeOptions,
}

fn keep_points(field: &Located) -> Result<Vec<KeepPoint>, JobError> {
    let mut out = Vec::new();
    for item in field.array()? {
        let obj = item.object()?;
        let param = obj.required("param")?.number_in(0.0, 1.0)?;
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
    let why = "merge works on two Bezier curves (section 3)";
    let p = obj.required("p")?.bezier_curve(why)?;
    let q = obj.required("q")?.bezier_curve(why)?;
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
            Breakpoints::Given(vec![f.number_in(0.0, 1.0)?])
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
        options.p_points = keep_points(&f)?;
    }
    if let Some(f) = obj.optional("q_points") {
        options.q_points = keep_points(&f)?;
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
    let merged = merge(&job.p, &job.q, &job.options)?;
    Ok(outcome(&job, &merged))
}

/// Largest distance between `a(t)` and `b(map(t))` over `samples + 1`
/// evenly spaced `t` in `[0, 1]`.
fn sampled_distance(a: &BezierCurve, b: &BezierCurve, map: impl Fn(f64) -> f64) -> f64 {
    (0..=CHECK_SAMPLES)
        .map(|i| {
            let t = i as f64 / CHECK_SAMPLES as f64;
            distance(&a.eval(t), &b.eval(map(t)))
        })
        .fold(0.0, f64::max)
}

/// The kept point of `curve` at `param` against `R` at `a + (b - a) param`:
/// `R^(k) (b - a)^k` against `curve^(k)`, orders `0..=max_order`.
fn keep_point_check(
    name: &str,
    curve: &BezierCurve,
    r: &BezierCurve,
    (a, b): (f64, f64),
    point: &KeepPoint,
) -> (Value, f64) {
    let orders = point.max_order.min(r.degree());
    let want = curve.eval_derivatives(point.param, orders.min(curve.degree()));
    let got = r.eval_derivatives(a + (b - a) * point.param, orders);
    let dim = curve.dim();
    let mut worst: f64 = 0.0;
    let residuals: Vec<f64> = (0..=orders)
        .map(|k| {
            let scale = (b - a).powi(k as i32);
            let g: Vec<f64> = row(&got, dim, k).iter().map(|x| x * scale).collect();
            let w: Vec<f64> = if k < want.len() / dim {
                row(&want, dim, k).to_vec()
            } else {
                vec![0.0; dim]
            };
            let jump = relative_jump(&g, &w);
            worst = worst.max(jump);
            jump
        })
        .collect();
    let point_distance = distance(&r.eval(a + (b - a) * point.param), &curve.eval(point.param));
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

fn measure(job: &MergeJob, m: &Merge) -> Checks {
    let r = &m.merged;
    let mu = m.report.mu;
    let left = |t: f64| mu * t;
    let right = |t: f64| mu + (1.0 - mu) * t;
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
        let start = distance(&r.eval(0.0), &job.p.eval(0.0));
        let end = distance(&r.eval(1.0), &job.q.eval(1.0));
        note(start.max(end));
        constraints.push(json!({
            "constraint": "fix_ends",
            "distance_R(0)_to_P(0)": start,
            "distance_R(1)_to_Q(1)": end,
        }));
    }
    for point in &job.options.p_points {
        let (j, w) = keep_point_check("P", &job.p, r, (0.0, mu), point);
        note(w);
        constraints.push(j);
    }
    for point in &job.options.q_points {
        let (j, w) = keep_point_check("Q", &job.q, r, (mu, 1.0), point);
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

fn outcome(job: &MergeJob, m: &Merge) -> Outcome {
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

    let mut figure = Figure::new("Merging two curves into one");
    for (curve, name) in [(&job.p, "P"), (&job.q, "Q")] {
        figure.curve(CurveItem::bezier(
            curve,
            Role::Input,
            format!("{name}, degree {}", curve.degree()),
        ));
    }
    figure.curve(CurveItem::bezier(
        r,
        Role::Result,
        format!("R, degree {}", r.degree()),
    ));
    figure.marker(Marker::new(
        MarkerKind::Join,
        &r.eval(report.mu),
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
            &job.p.eval(0.0),
            "P(0) fixed",
        ));
        figure.marker(Marker::new(
            MarkerKind::Constraint,
            &job.q.eval(1.0),
            "Q(1) fixed",
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
    figure.line(format!(
        "Measured by the tool: max |R - (P then Q)| = {:.3e}; R split at mu vs P^, Q^: {:.1e}",
        checks.r_vs_p_then_q, checks.split_vs_hats
    ));
    if let Some(w) = checks.worst_constraint {
        figure.line(format!(
            "Worst measured constraint residual (distance or relative derivative jump): {w:.1e}"
        ));
    }
    // P^ and Q^ are the pieces of one polynomial R: they join at R(mu) with
    // every derivative (C^n, n = degree), measured from their control points.
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

/// The demo's merge scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
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
    ]
}
