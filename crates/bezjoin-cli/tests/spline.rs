//! `bezjoin spline` run as a process: the example's result is re-checked
//! from the returned control points (given on-curve points at `u = j/n`,
//! derivative continuity at every node in the global parameter, the
//! B-spline knot vector), the SVG is well-formed, bad jobs exit 2 naming
//! the field.

mod common;
use common::assert_well_formed_xml;

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::{Value, json};

fn example_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/spline.json")
}

fn run_stdin(job: &Value, extra: &[&str]) -> Output {
    let args: Vec<&str> = ["spline"].iter().chain(extra).copied().collect();
    common::run_bezjoin(&args, job.to_string().as_bytes())
}

fn points(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| {
            p.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

/// De Casteljau evaluation of control points `b` at `t`.
fn eval(b: &[Vec<f64>], t: f64) -> Vec<f64> {
    let mut w = b.to_vec();
    while w.len() > 1 {
        w = w
            .windows(2)
            .map(|p| {
                p[0].iter()
                    .zip(&p[1])
                    .map(|(a, c)| (1.0 - t) * a + t * c)
                    .collect()
            })
            .collect();
    }
    w.remove(0)
}

/// Control points of the `m`-th derivative (repeated hodograph).
fn hodograph(b: &[Vec<f64>], m: usize) -> Vec<Vec<f64>> {
    let mut w = b.to_vec();
    for _ in 0..m {
        let n = (w.len() - 1) as f64;
        w = w
            .windows(2)
            .map(|p| p[0].iter().zip(&p[1]).map(|(a, c)| n * (c - a)).collect())
            .collect();
    }
    w
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn norm(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn segments_of(result: &Value) -> Vec<Vec<Vec<f64>>> {
    result["segments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| points(&s["points"]))
        .collect()
}

/// Relative jump of the `m`-th derivative at node `i` in the global parameter.
fn derivative_jump(segments: &[Vec<Vec<f64>>], params: &[f64], i: usize, m: usize) -> f64 {
    let (hl, hr) = (params[i] - params[i - 1], params[i + 1] - params[i]);
    let left: Vec<f64> = eval(&hodograph(&segments[i - 1], m), 1.0)
        .iter()
        .map(|v| v / hl.powi(m as i32))
        .collect();
    let right: Vec<f64> = eval(&hodograph(&segments[i], m), 0.0)
        .iter()
        .map(|v| v / hr.powi(m as i32))
        .collect();
    let size = norm(&left).max(norm(&right)).max(1e-300);
    dist(&left, &right) / size
}

/// Check a forward, non-mirrored result against its job by recomputation
/// from the returned control points.
fn check_result(job: &Value, result: &Value) {
    let n = result["degree"].as_u64().unwrap() as usize;
    let k = result["continuity"].as_u64().unwrap() as usize;
    assert_eq!(n as u64, job["degree"].as_u64().unwrap_or(3));
    assert_eq!(k as u64, job["continuity"].as_u64().unwrap_or(1));
    let segments = segments_of(result);
    let nodes = points(&job["nodes"]);
    assert_eq!(segments.len(), nodes.len() - 1);
    let params: Vec<f64> = result["params"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(params.windows(2).all(|w| w[0] < w[1]));
    let scale = nodes.iter().map(|p| norm(p)).fold(1.0, f64::max);
    // nodes on both neighbouring segments
    for (i, node) in nodes.iter().enumerate() {
        if i < segments.len() {
            assert!(dist(&eval(&segments[i], 0.0), node) < 1e-12 * scale);
        }
        if i > 0 {
            assert!(dist(&eval(&segments[i - 1], 1.0), node) < 1e-12 * scale);
        }
    }
    // given inner points at u = j / n (forward, NextToJoin: free are k+1..n-1)
    let start = points(&job["start_inner"]);
    for (j, p) in start.iter().enumerate() {
        let at = eval(&segments[0], (j + 1) as f64 / n as f64);
        assert!(
            dist(&at, p) < 1e-12 * scale,
            "start inner {j}: {at:?} vs {p:?}"
        );
    }
    let free_indices: Vec<usize> = (k + 1..n).collect();
    for (s, group) in job["free_inner"].as_array().unwrap().iter().enumerate() {
        let group = points(group);
        assert_eq!(group.len(), free_indices.len());
        for (p, &j) in group.iter().zip(&free_indices) {
            let at = eval(&segments[s + 1], j as f64 / n as f64);
            assert!(
                dist(&at, p) < 1e-10 * scale,
                "segment {} u = {j}/{n}",
                s + 1
            );
        }
    }
    // C^k in the global parameter: m-th derivative divided by h^m
    for i in 1..segments.len() {
        for m in 1..=k {
            let jump = derivative_jump(&segments, &params, i, m);
            assert!(jump < 1e-9, "node {i} order {m}: relative jump {jump}");
        }
    }
    // B-spline form: distinct knots = params, interior multiplicity n - k
    let knots: Vec<f64> = result["bspline"]["knots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let mult: Vec<u64> = result["bspline"]["multiplicities"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect();
    assert_eq!(knots.len(), params.len());
    for (a, b) in knots.iter().zip(&params) {
        assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0));
    }
    assert_eq!(mult[0] as usize, n + 1);
    assert_eq!(*mult.last().unwrap() as usize, n + 1);
    assert!(mult[1..mult.len() - 1].iter().all(|&m| m as usize == n - k));
    // ... with its poles: the B-spline built from them is the spline, each
    // segment on its knot interval (local u = (t - t_i) / (t_(i+1) - t_i)).
    let poles = points(&result["bspline"]["poles"]);
    let dim = poles[0].len();
    let flat_knots: Vec<f64> = knots
        .iter()
        .zip(&mult)
        .flat_map(|(&t, &m)| std::iter::repeat_n(t, m as usize))
        .collect();
    let whole = bezjoin_core::NurbsCurve::new(dim, n, poles.concat(), None, flat_knots)
        .expect("the bspline of the result is a valid B-spline");
    for (i, segment) in segments.iter().enumerate() {
        for j in 0..=8 {
            let u = j as f64 / 8.0;
            let t = knots[i] + u * (knots[i + 1] - knots[i]);
            let (a, b) = (whole.eval(t), eval(segment, u));
            assert!(
                dist(&a, &b) < 1e-12 * scale,
                "segment {i}, u = {u}: {a:?} vs {b:?}"
            );
        }
    }
    // the tool's own report agrees with what we measured
    assert!(
        result["report"]["max_given_point_distance"]
            .as_f64()
            .unwrap()
            < 1e-10 * scale
    );
}

#[test]
fn example_runs_and_its_result_holds() {
    let svg = std::env::temp_dir().join(format!("bezjoin-spline-{}.svg", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_bezjoin"))
        .arg("spline")
        .arg(example_path())
        .arg("--svg")
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    let job: Value =
        serde_json::from_str(&std::fs::read_to_string(example_path()).unwrap()).unwrap();
    check_result(&job, &result);
    // C1 only: the curvature (second derivative) really jumps somewhere,
    // so the continuity check above is not vacuous
    let segments = segments_of(&result);
    let params: Vec<f64> = result["params"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((1..segments.len()).any(|i| derivative_jump(&segments, &params, i, 2) > 1e-3));
    let text = std::fs::read_to_string(&svg).unwrap();
    std::fs::remove_file(&svg).ok();
    assert!(text.contains("<svg"));
    assert!(text.contains("degree 3") && text.contains("C1"));
    assert_well_formed_xml(&text);
}

#[test]
fn quintic_c2_in_3d_from_stdin_holds() {
    let f = |x: f64| vec![x, x.sin(), 0.1 * x];
    let n = 5;
    let nodes: Vec<Vec<f64>> = (0..5).map(|i| f(i as f64)).collect();
    let start: Vec<Vec<f64>> = (1..n).map(|j| f(j as f64 / n as f64)).collect();
    let free: Vec<Vec<Vec<f64>>> = (1..4)
        .map(|s| (3..n).map(|j| f(s as f64 + j as f64 / n as f64)).collect())
        .collect();
    let job = json!({"nodes": nodes, "degree": 5, "continuity": 2,
                     "start_inner": start, "free_inner": free});
    let svg = std::env::temp_dir().join(format!("bezjoin-spline5-{}.svg", std::process::id()));
    let out = run_stdin(&job, &["--svg", svg.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    check_result(&job, &result);
    let text = std::fs::read_to_string(&svg).unwrap();
    std::fs::remove_file(&svg).ok();
    assert!(text.contains("x-y projection"));
    assert_well_formed_xml(&text);
}

#[test]
fn mirrored_backward_puts_given_points_on_the_curve() {
    let job = json!({
        "nodes": [[0, 0], [1, 1], [2, 0], [3, 1]],
        "direction": "backward", "mirrored": true,
        "start_inner": [[2.3, 0.3], [2.7, 0.7]],
        "free_inner": [[[0.3, 0.6]], [[1.3, 0.6]]]
    });
    let out = run_stdin(&job, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    let segments = segments_of(&result);
    let params: Vec<f64> = result["params"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    // backward + mirrored: the derived points are u = 1/3 (near each
    // segment's start), the user gives u = 2/3 of segments 0 and 1;
    // segment 2 is the starting one
    assert!(dist(&eval(&segments[2], 1.0 / 3.0), &[2.3, 0.3]) < 1e-12);
    assert!(dist(&eval(&segments[2], 2.0 / 3.0), &[2.7, 0.7]) < 1e-12);
    assert!(dist(&eval(&segments[0], 2.0 / 3.0), &[0.3, 0.6]) < 1e-12);
    assert!(dist(&eval(&segments[1], 2.0 / 3.0), &[1.3, 0.6]) < 1e-12);
    for i in 1..segments.len() {
        assert!(dist(&eval(&segments[i - 1], 1.0), &eval(&segments[i], 0.0)) < 1e-12);
        assert!(derivative_jump(&segments, &params, i, 1) < 1e-9);
    }
}

fn assert_fails_naming(job: &Value, field: &str) {
    let out = run_stdin(job, &[]);
    assert_eq!(out.status.code(), Some(2), "job {job}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(field), "message {err:?} does not name {field}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bad_jobs_exit_2_naming_the_field() {
    let base = json!({
        "nodes": [[0, 0], [1, 1], [2, 0]],
        "start_inner": [[0.3, 0.4], [0.7, 0.8]],
        "free_inner": [[[1.7, 0.4]]]
    });
    let with = |key: &str, v: Value| {
        let mut j = base.clone();
        j[key] = v;
        j
    };
    // the base job itself is fine
    assert!(run_stdin(&base, &[]).status.success());
    assert_fails_naming(&with("degree", json!(6)), "degree");
    assert_fails_naming(&with("continuity", json!(2)), "continuity");
    assert_fails_naming(&with("direction", json!("sideways")), "direction");
    assert_fails_naming(&with("start_inner", json!([[0.3, 0.4]])), "start_inner");
    assert_fails_naming(&with("free_inner", json!([])), "free_inner");
    assert_fails_naming(
        &with("free_inner", json!([[[1.7, 0.4], [1.8, 0.2]]])),
        "free_inner",
    );
    assert_fails_naming(&with("params", json!([0, 1])), "params");
    assert_fails_naming(&with("params", json!([0, 2, 1])), "params");
    assert_fails_naming(&with("unknown_key", json!(1)), "unknown_key");
    let mut missing = base.clone();
    missing.as_object_mut().unwrap().remove("free_inner");
    assert_fails_naming(&missing, "free_inner");
    assert_fails_naming(&with("nodes", json!([[0, 0], [0, 0], [2, 0]])), "nodes");
}
