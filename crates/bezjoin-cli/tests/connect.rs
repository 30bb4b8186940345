//! `bezjoin connect` run as a process: the examples' results are re-checked
//! from the returned control points (continuity evaluated on both sides of
//! each join, interior constraints evaluated on R), the SVG is well-formed
//! XML, and bad jobs exit with code 2 naming the field.

mod common;
use common::assert_well_formed_xml;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use bezjoin_core::BezierCurve;
use serde_json::{Value, json};

/// Relative tolerance of the re-checked conditions.
const TOLERANCE: f64 = 1e-9;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn example(name: &str) -> PathBuf {
    repo_root().join("examples").join(name)
}

fn run_with_file(job: &Path, svg: Option<&Path>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_bezjoin"));
    cmd.arg("connect").arg(job);
    if let Some(svg) = svg {
        cmd.arg("--svg").arg(svg);
    }
    cmd.output().expect("the bezjoin binary runs")
}

fn run_with_stdin(job: &str) -> Output {
    common::run_bezjoin(&["connect", "-"], job.as_bytes())
}

fn success_json(out: &Output) -> Value {
    assert!(
        out.status.success(),
        "exit {:?}, stderr: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is JSON")
}

/// A curve as the job or result writes it: an array of points or `{"points": [...]}`.
fn curve_from_rows(value: &Value) -> BezierCurve {
    let value = value.get("points").unwrap_or(value);
    let rows: Vec<Vec<f64>> = value
        .as_array()
        .expect("an array of points")
        .iter()
        .map(|p| {
            p.as_array()
                .expect("a point")
                .iter()
                .map(|x| x.as_f64().expect("a coordinate"))
                .collect()
        })
        .collect();
    BezierCurve::from_rows(&rows).expect("a valid curve")
}

fn number(job: &Value, key: &str, default: f64) -> f64 {
    job.get(key).and_then(Value::as_f64).unwrap_or(default)
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// `|a - b| <= TOLERANCE * max(1, |a|, |b|)`.
fn assert_close(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: dimensions");
    let diff: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    let scale = 1.0f64.max(norm(a)).max(norm(b));
    assert!(
        norm(&diff) <= TOLERANCE * scale,
        "{what}: {a:?} != {b:?} (difference {:.3e})",
        norm(&diff)
    );
}

/// Row `k` of flat row-major derivatives, `dim` values per row.
fn row(m: &[f64], dim: usize, k: usize) -> Vec<f64> {
    m[k * dim..(k + 1) * dim].to_vec()
}

/// Re-check a connect result against its job, from the control points alone:
/// R^(k)(0) = alpha^k P^(k)(u0) for k <= kp, R^(k)(1) = beta^k Q^(k)(v0) for
/// k <= kq (mathematics.md (1')), every interior constraint, and the degree
/// kp + kq + 1 + sum(K + 1). Returns R.
fn check_connection(job: &Value, result: &Value) -> BezierCurve {
    let p = curve_from_rows(&job["p"]);
    let q = curve_from_rows(&job["q"]);
    let u0 = number(job, "u0", 1.0);
    let v0 = number(job, "v0", 0.0);
    let kp = job["p_order"].as_u64().map_or(p.degree(), |k| k as usize);
    let kq = job["q_order"].as_u64().map_or(q.degree(), |k| k as usize);
    let r = curve_from_rows(&result["curve"]["points"]);
    assert_eq!(result["operation"], "connect");
    assert_eq!(result["curve"]["degree"].as_u64(), Some(r.degree() as u64));
    assert_eq!(r.dim(), p.dim());
    let dim = r.dim();

    let given = (job["p_scale"].as_f64(), job["q_scale"].as_f64());
    let (alpha, beta) = if job["auto_scale"] == json!(false) {
        // The paper's scale 1 where none is given.
        (number(job, "p_scale", 1.0), number(job, "q_scale", 1.0))
    } else if let (None, None) = given {
        // Chosen by the tool (asked for, or the default without scales).
        let alpha = result["report"]["p_scale"].as_f64().unwrap();
        let beta = result["report"]["q_scale"].as_f64().unwrap();
        assert!(alpha > 0.0 && beta > 0.0, "chosen scales {alpha}, {beta}");
        assert_eq!(result["report"]["auto_scale"], json!(true));
        (alpha, beta)
    } else {
        // One given scale stands for both.
        (given.0.or(given.1).unwrap(), given.1.or(given.0).unwrap())
    };

    let constraints = job["constraints"].as_array().cloned().unwrap_or_default();
    let sum_orders: usize = constraints
        .iter()
        .map(|c| c["derivatives"].as_array().unwrap().len())
        .sum();
    assert_eq!(r.degree(), kp + kq + 1 + sum_orders, "degree of R");

    let left = p.eval_derivatives(u0, kp);
    let start = r.eval_derivatives(0.0, kp);
    for k in 0..=kp {
        let want: Vec<f64> = row(&left, dim, k)
            .iter()
            .map(|x| x * alpha.powi(k as i32))
            .collect();
        assert_close(
            &row(&start, dim, k),
            &want,
            &format!("R^({k})(0) vs alpha^k P^({k})(u0)"),
        );
    }
    let right = q.eval_derivatives(v0, kq);
    let end = r.eval_derivatives(1.0, kq);
    for k in 0..=kq {
        let want: Vec<f64> = row(&right, dim, k)
            .iter()
            .map(|x| x * beta.powi(k as i32))
            .collect();
        assert_close(
            &row(&end, dim, k),
            &want,
            &format!("R^({k})(1) vs beta^k Q^({k})(v0)"),
        );
    }

    for (j, c) in constraints.iter().enumerate() {
        let t = c["t"].as_f64().unwrap();
        let wanted = c["derivatives"].as_array().unwrap();
        let got = r.eval_derivatives(t, wanted.len() - 1);
        for (k, w) in wanted.iter().enumerate() {
            let w: Vec<f64> = w
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            assert_close(
                &row(&got, dim, k),
                &w,
                &format!("constraint {j}: R^({k})({t})"),
            );
        }
    }
    r
}

fn temp_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("connect-{}-{name}", std::process::id()))
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn example_runs_and_its_joins_hold() {
    let job_path = example("connect.json");
    let svg = temp_file("plain.svg");
    let result = success_json(&run_with_file(&job_path, Some(&svg)));
    let job = read_json(&job_path);
    check_connection(&job, &result);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_well_formed_xml(&text);
    assert!(text.contains("<svg"), "an SVG document");
    std::fs::remove_file(&svg).ok();
}

#[test]
fn constrained_example_passes_through_the_prescribed_derivatives() {
    let job_path = example("connect-constrained.json");
    let svg = temp_file("constrained.svg");
    let result = success_json(&run_with_file(&job_path, Some(&svg)));
    let job = read_json(&job_path);
    // The papers' constraint is really in the example.
    assert_eq!(
        job["constraints"][0],
        json!({"t": 0.5, "derivatives": [[12.0, 14.0], [8.1, 1.4], [-5.0, -39.0]]})
    );
    check_connection(&job, &result);
    assert_well_formed_xml(&std::fs::read_to_string(&svg).unwrap());
    std::fs::remove_file(&svg).ok();
}

#[test]
fn auto_scale_from_stdin_keeps_the_joins() {
    let job = json!({
        "p": {"points": [[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [3.0, 2.5, 1.0], [4.0, 1.0, 1.0]]},
        "q": [[9.0, 1.0, 0.0], [10.0, -1.0, 0.5], [12.0, 0.0, 1.0], [13.0, 2.0, 0.0]],
        "u0": 0.8,
        "v0": 0.25,
        "p_order": 2,
        "q_order": 1,
        "auto_scale": true,
    });
    let result = success_json(&run_with_stdin(&job.to_string()));
    check_connection(&job, &result);
    let alpha = result["report"]["p_scale"].as_f64().unwrap();
    let beta = result["report"]["q_scale"].as_f64().unwrap();
    assert_eq!(alpha, beta, "auto scale chooses alpha = beta");
}

#[test]
fn balanced_scale_leaves_both_curves_at_one_speed() {
    // P runs about 4 times faster than Q at the ends used; the balanced scales
    // make R leave both at one speed: alpha |P'(u0)| = beta |Q'(v0)| = |R'(0)| = |R'(1)|.
    let job = json!({
        "p": [[0.0, 0.0], [4.0, 3.0], [8.0, 0.0], [12.0, 2.0]],
        "q": [[14.0, 1.0], [14.5, 0.0], [15.0, 1.5]],
        "u0": 1.0,
        "v0": 0.0,
        "p_order": 2,
        "q_order": 2,
        "auto_scale": "balanced",
    });
    let result = success_json(&run_with_stdin(&job.to_string()));
    check_connection(&job, &result);
    assert_eq!(result["report"]["auto_scale"], json!(true));
    assert_eq!(result["report"]["balanced_scale"], json!(true));
    let alpha = result["report"]["p_scale"].as_f64().unwrap();
    let beta = result["report"]["q_scale"].as_f64().unwrap();
    let r = common::bezier_of(&result["curve"]);
    let norm = |v: Vec<f64>| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let start = norm(r.derivative_at(0.0, 1));
    let end = norm(r.derivative_at(1.0, 1));
    assert!(
        (start - end).abs() <= 1e-12 * start,
        "|R'(0)| = {start}, |R'(1)| = {end}"
    );
    // |P'(1)| = 3 |(4, 2)|, |Q'(0)| = 2 |(0.5, -1)|.
    let (p_speed, q_speed) = (3.0 * 20f64.sqrt(), 2.0 * 1.25f64.sqrt());
    assert!((alpha * p_speed - start).abs() <= 1e-12 * start);
    assert!((beta * q_speed - start).abs() <= 1e-12 * start);
    assert!((alpha / beta - q_speed / p_speed).abs() <= 1e-12 * alpha / beta);
}

#[test]
fn the_check_detects_a_broken_join() {
    // The re-check is not vacuous: a result whose R is moved away fails it.
    let job_path = example("connect.json");
    let mut result = success_json(&run_with_file(&job_path, None));
    let job = read_json(&job_path);
    result["curve"]["points"][1][0] =
        json!(result["curve"]["points"][1][0].as_f64().unwrap() + 1e-3);
    let broken = std::panic::catch_unwind(|| check_connection(&job, &result));
    assert!(
        broken.is_err(),
        "a perturbed control point must fail the continuity check"
    );
}

#[test]
fn the_xml_checker_rejects_malformed_documents() {
    assert_well_formed_xml(
        "<?xml version=\"1.0\"?><svg a=\"1 &lt; 2\"><g><path d='M0 0'/></g><!-- x --></svg>",
    );
    for bad in [
        "<svg><g></svg>",
        "<svg></g>",
        "<svg a=1></svg>",
        "<svg>a & b</svg>",
        "<svg><g>",
        "<svg/><svg/>",
        "<svg a=\"x\" a=\"y\"/>",
    ] {
        assert!(
            std::panic::catch_unwind(|| assert_well_formed_xml(bad)).is_err(),
            "accepted {bad:?}"
        );
    }
}

fn assert_rejected(job: &str, field: &str) {
    let out = run_with_stdin(job);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "exit code for {job}: {stderr}");
    assert!(
        stderr.contains(field),
        "message for {job} does not name {field}: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "a panic for {job}: {stderr}");
    assert!(out.stdout.is_empty(), "no result printed for {job}");
}

#[test]
fn bad_jobs_exit_2_naming_the_field() {
    let q = "[[2, 0], [3, 1], [4, 0]]";
    let p = "[[0, 0], [1, 1], [2, 0]]";
    assert_rejected(&format!("{{\"q\": {q}}}"), "p: is required");
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"u0\": 1.5}}"),
        "u0 = 1.5",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"p_order\": \"one\"}}"),
        "p_order",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"q_order\": 1.5}}"),
        "q_order",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"auto_scale\": true, \"q_scale\": 2}}"),
        "q_scale",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"auto_scale\": \"balanced\", \"p_scale\": 2}}"),
        "p_scale",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"auto_scale\": \"fair\"}}"),
        "auto_scale: expected true, false or \"balanced\"",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"constraints\": [{{\"t\": 0.5}}]}}"),
        "constraints[0].derivatives",
    );
    assert_rejected(
        &format!("{{\"p\": {p}, \"q\": {q}, \"colour\": 1}}"),
        "colour",
    );
    assert_rejected("{\"p\": ", "line");
}
