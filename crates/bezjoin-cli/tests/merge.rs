//! `bezjoin merge` run as a process: the example and variants of it; every
//! property is re-measured here from the returned control points.

mod common;
use common::assert_well_formed_xml;

use std::process::{Command, Output};

use bezjoin_core::BezierCurve;
use serde_json::{Value, json};

fn example_path() -> String {
    format!("{}/../../examples/merge.json", env!("CARGO_MANIFEST_DIR"))
}

fn example() -> Value {
    serde_json::from_str(&std::fs::read_to_string(example_path()).unwrap()).unwrap()
}

fn run_stdin(job: &Value, extra: &[&str]) -> Output {
    let args: Vec<&str> = ["merge"].iter().chain(extra).copied().collect();
    common::run_bezjoin(&args, job.to_string().as_bytes())
}

fn run_ok(job: &Value) -> Value {
    let out = run_stdin(job, &[]);
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn curve_from(value: &Value) -> BezierCurve {
    let rows: Vec<Vec<f64>> = value
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            p.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    let dim = rows[0].len();
    BezierCurve::new(dim, rows.len() - 1, rows.concat()).unwrap()
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Largest distance between `a(t)` and `b(map(t))`, 201 samples.
fn max_distance(a: &BezierCurve, b: &BezierCurve, map: impl Fn(f64) -> f64) -> f64 {
    (0..=200)
        .map(|i| {
            let t = i as f64 / 200.0;
            dist(&a.eval(t), &b.eval(map(t)))
        })
        .fold(0.0, f64::max)
}

/// Checks that must hold for every merge: `R` split at `mu` gives `P^`,
/// `Q^`; the reported deviation is the tool's distance between `R` and
/// "P then Q"; and that distance is what it claims.
fn check_common(job: &Value, out: &Value) -> (BezierCurve, f64) {
    let p = curve_from(&job["p"]);
    let q = curve_from(&job["q"]);
    let r = curve_from(&out["curve"]["points"]);
    let p_hat = curve_from(&out["p_hat"]["points"]);
    let q_hat = curve_from(&out["q_hat"]["points"]);
    let mu = out["report"]["mu"].as_f64().unwrap();
    assert!(mu > 0.0 && mu < 1.0);
    let scale = 10.0;
    assert!(max_distance(&p_hat, &r, |t| mu * t) < 1e-9 * scale);
    assert!(max_distance(&q_hat, &r, |t| mu + (1.0 - mu) * t) < 1e-9 * scale);
    let deviation =
        max_distance(&p, &r, |t| mu * t).max(max_distance(&q, &r, |t| mu + (1.0 - mu) * t));
    let reported = out["checks"]["max_distance_R_to_P_then_Q"]
        .as_f64()
        .unwrap();
    // 401 samples in the tool against 201 here: the denser is at least as large.
    assert!(reported >= deviation - 1e-12 && reported <= deviation * 1.05 + 1e-12);
    // The two curves do not join exactly, so R cannot reproduce both: the
    // deviation is not zero, and stays bounded (keep_q extrapolates Q backwards).
    assert!(
        deviation > 1e-4 && deviation < 10.0,
        "deviation {deviation}"
    );
    (r, mu)
}

#[test]
fn example_runs_and_its_constraints_hold() {
    let job = example();
    let svg = std::env::temp_dir().join(format!("bezjoin-merge-test-{}.svg", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_bezjoin"))
        .args(["merge", &example_path(), "--svg"])
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    let (r, mu) = check_common(&job, &result);
    let p = curve_from(&job["p"]);
    let q = curve_from(&job["q"]);
    assert_eq!(r.degree(), job["degree"].as_u64().unwrap() as usize);
    // fix_ends
    assert!(dist(&r.eval(0.0), &p.eval(0.0)) < 1e-9);
    assert!(dist(&r.eval(1.0), &q.eval(1.0)) < 1e-9);
    // p_points: P(0.5) and P'(0.5) kept: R(mu/2) = P(0.5), mu R'(mu/2) = P'(0.5).
    let want = p.eval_derivatives(0.5, 1);
    let got = r.eval_derivatives(0.5 * mu, 1);
    let dim = r.dim();
    for k in 0..2 {
        let g: Vec<f64> = got[k * dim..(k + 1) * dim]
            .iter()
            .map(|x| x * mu.powi(k as i32))
            .collect();
        let w: Vec<f64> = want[k * dim..(k + 1) * dim].to_vec();
        assert!(dist(&g, &w) < 1e-9, "order {k}: {g:?} vs {w:?}");
    }
    let text = std::fs::read_to_string(&svg).unwrap();
    let _ = std::fs::remove_file(&svg);
    assert_well_formed_xml(&text);
    assert!(text.contains("mu = "), "caption names mu");
}

fn variant(changes: Value) -> Value {
    let mut job = example();
    let obj = job.as_object_mut().unwrap();
    for key in ["fix_ends", "p_points", "q_points", "degree", "split", "mu"] {
        obj.remove(key);
    }
    obj.extend(changes.as_object().unwrap().clone());
    job
}

#[test]
fn optimal_mu_beats_nearby_given_values() {
    for metric in ["discrete", "integral"] {
        let job = variant(json!({"metric": metric, "split": "optimal"}));
        let out = run_ok(&job);
        check_common(&job, &out);
        let mu = out["report"]["mu"].as_f64().unwrap();
        let best = out["report"]["metric_value"].as_f64().unwrap();
        for delta in [-0.05, -0.01, 0.01, 0.05] {
            let other = run_ok(&variant(json!({"metric": metric, "mu": mu + delta})));
            let value = other["report"]["metric_value"].as_f64().unwrap();
            assert!(
                value >= best * (1.0 - 1e-9),
                "{metric}: mu {} gives {value} < {best}",
                mu + delta
            );
        }
    }
}

#[test]
fn keep_p_and_keep_q_leave_the_curve_unchanged() {
    let job = variant(json!({"keep_p": true, "split": "polygon"}));
    let out = run_ok(&job);
    let (r, mu) = check_common(&job, &out);
    assert!(max_distance(&curve_from(&job["p"]), &r, |t| mu * t) < 1e-9);
    let job = variant(json!({"keep_q": true, "metric": "l2"}));
    let out = run_ok(&job);
    let (r, mu) = check_common(&job, &out);
    assert!(max_distance(&curve_from(&job["q"]), &r, |t| mu + (1.0 - mu) * t) < 1e-9);
}

#[test]
fn discrete_merge_is_no_worse_than_perturbed_feasible_curves() {
    // The discrete metric is the sum of squared control-point changes of P
    // and Q; any R of the same degree split at the same mu is feasible.
    let job = variant(json!({"metric": "discrete", "mu": 0.45}));
    let out = run_ok(&job);
    let (r, mu) = check_common(&job, &out);
    let p = curve_from(&job["p"]);
    let q = curve_from(&job["q"]);
    let cost = |r: &BezierCurve| {
        let (a, b) = r.split_at(mu).unwrap();
        let mut s = 0.0;
        for (x, y) in [(&a, &p), (&b, &q)] {
            for i in 0..=x.degree() {
                s += dist(x.point(i), y.point(i)).powi(2);
            }
        }
        s
    };
    let best = cost(&r);
    let reported = out["report"]["metric_value"].as_f64().unwrap();
    assert!((best - reported).abs() <= 1e-9 * (1.0 + best));
    let mut seed = 12345u64;
    for _ in 0..40 {
        let mut points: Vec<f64> = (0..=r.degree()).flat_map(|i| r.point(i).to_vec()).collect();
        for x in &mut points {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *x += ((seed >> 33) as f64 / (1u64 << 31) as f64 - 0.5) * 0.02;
        }
        let other = BezierCurve::new(r.dim(), r.degree(), points).unwrap();
        assert!(cost(&other) >= best * (1.0 - 1e-12));
    }
}

fn assert_job_error(job: &Value, field: &str) {
    let out = run_stdin(job, &[]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains(field), "{field} not named in: {stderr}");
    assert!(!stderr.contains("panicked"));
}

#[test]
fn bad_jobs_exit_2_naming_the_field() {
    assert_job_error(&variant(json!({"metric": "l3"})), "metric: \"l3\"");
    assert_job_error(
        &variant(json!({"split": "half", "mu": 0.3})),
        "mu: is only used with",
    );
    assert_job_error(&variant(json!({"split": "given"})), "mu: is required");
    assert_job_error(
        &variant(json!({"split": "given", "mu": 1.5})),
        "mu: 1.5 is outside [0.000001, 0.999999]",
    );
    assert_job_error(
        &variant(json!({"split": "given", "mu": 1e-7})),
        "mu: 0.0000001 is outside [0.000001, 0.999999]",
    );
    assert_job_error(
        &variant(json!({"p_points": [{"param": 1.5, "max_order": 1}]})),
        "p_points[0].param:",
    );
    assert_job_error(&variant(json!({"keep_p": "yes"})), "keep_p:");
    assert_job_error(&variant(json!({"colour": 1})), "colour");
    // Contradictory: keep P and keep Q, but they do not join.
    assert_job_error(&variant(json!({"keep_p": true, "keep_q": true})), "keep Q");
    assert_job_error(
        &variant(json!({"p_points": [{"param": 0.5, "max_order": 9}]})),
        "p_points[0].max_order",
    );
    let mut job = example();
    job["q"] = json!([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
    assert_job_error(&job, "invalid job: q has dimension 3, expected 2");
}

#[test]
fn polygon_split_is_the_control_polygon_length_ratio() {
    let job = variant(json!({"split": "polygon"}));
    let out = run_ok(&job);
    check_common(&job, &out);
    let length = |c: &BezierCurve| {
        (1..=c.degree())
            .map(|i| dist(c.point(i - 1), c.point(i)))
            .sum::<f64>()
    };
    let (lp, lq) = (
        length(&curve_from(&job["p"])),
        length(&curve_from(&job["q"])),
    );
    let mu = out["report"]["mu"].as_f64().unwrap();
    assert!((mu - lp / (lp + lq)).abs() < 1e-12);
}

#[test]
fn three_dimensional_merge_with_fixed_ends_draws_a_projection() {
    let job = json!({
        "p": [[0.0, 0.0, 0.0], [1.0, 1.0, 0.5], [2.0, 0.0, 1.0]],
        "q": {"points": [[2.05, 0.0, 1.0], [3.0, -1.0, 1.2], [4.0, 0.0, 1.0]]},
        "metric": "integral",
        "split": "optimal",
        "fix_ends": true
    });
    let svg = std::env::temp_dir().join(format!("bezjoin-merge-3d-{}.svg", std::process::id()));
    let out = run_stdin(&job, &["--svg", svg.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(result["curve"]["dim"], 3);
    let mut flat = job.clone();
    flat["q"] = job["q"]["points"].clone();
    let (r, _) = check_common(&flat, &result);
    assert!(dist(&r.eval(0.0), &[0.0, 0.0, 0.0]) < 1e-9);
    assert!(dist(&r.eval(1.0), &[4.0, 0.0, 1.0]) < 1e-9);
    let text = std::fs::read_to_string(&svg).unwrap();
    let _ = std::fs::remove_file(&svg);
    assert_well_formed_xml(&text);
    assert!(text.contains("x-y projection"));
}
