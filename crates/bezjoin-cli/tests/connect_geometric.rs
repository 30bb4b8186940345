//! `bezjoin connect` with `"continuity": "geometric"` run as a process: with
//! given shape values the printed curve satisfies the beta-constraints
//! R'(0) = b1 P'(u0), R''(0) = b1^2 P''(u0) + b2 P'(u0) (and R''' for G3;
//! the same at Q), re-evaluated here from the printed control points; the
//! default (fair) shape values and the default scale of a C^k connection
//! do not loop on a corner of long edges; bad jobs exit 2 naming the field.

mod common;
use common::assert_well_formed_xml;

use bezjoin_core::BezierCurve;
use serde_json::{Value, json};

fn run(job: &Value, svg: Option<&std::path::Path>) -> (i32, String, String) {
    common::run_job("connect", job, svg)
}

fn success(job: &Value) -> Value {
    common::job_result("connect", job)
}

fn bezier(value: &Value) -> BezierCurve {
    common::bezier_of(value)
}

fn numbers(value: &Value) -> Vec<f64> {
    serde_json::from_value(value.clone()).unwrap()
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn norm(a: &[f64]) -> f64 {
    dist(a, &vec![0.0; a.len()])
}

/// `|a - b| <= 1e-9 max(1, |a|, |b|)`.
fn assert_close(a: &[f64], b: &[f64], what: &str) {
    let scale = 1.0f64.max(norm(a)).max(norm(b));
    assert!(dist(a, b) <= 1e-9 * scale, "{what}: {a:?} != {b:?}");
}

/// `sum_i c_i x_i` of rows.
fn combine(terms: &[(f64, &[f64])]) -> Vec<f64> {
    let n = terms[0].1.len();
    (0..n)
        .map(|c| terms.iter().map(|(w, x)| w * x[c]).sum())
        .collect()
}

/// The beta-constraints up to order 3 at one end: `r` the derivatives of
/// R there, `c` those of P (or Q) at the join, `b` the shape values.
fn assert_beta_constraints(r: &[f64], c: &[f64], b: &[f64], dim: usize, end: &str) {
    let row = |m: &[f64], k: usize| m[k * dim..(k + 1) * dim].to_vec();
    assert_close(&row(r, 0), &row(c, 0), &format!("{end}: R = C"));
    let (c1, c2, c3) = (row(c, 1), row(c, 2), row(c, 3));
    if !b.is_empty() {
        let want = combine(&[(b[0], &c1)]);
        assert_close(&row(r, 1), &want, &format!("{end}: R' = b1 C'"));
    }
    if b.len() >= 2 {
        let want = combine(&[(b[0] * b[0], &c2), (b[1], &c1)]);
        assert_close(&row(r, 2), &want, &format!("{end}: R'' = b1^2 C'' + b2 C'"));
    }
    if b.len() >= 3 {
        let want = combine(&[(b[0].powi(3), &c3), (3.0 * b[0] * b[1], &c2), (b[2], &c1)]);
        assert_close(
            &row(r, 3),
            &want,
            &format!("{end}: R''' = b1^3 C''' + 3 b1 b2 C'' + b3 C'"),
        );
    }
}

fn length(c: &BezierCurve) -> f64 {
    (0..2000)
        .map(|i| dist(&c.eval(i as f64 / 2000.0), &c.eval((i + 1) as f64 / 2000.0)))
        .sum()
}

#[test]
fn given_shapes_satisfy_the_beta_constraints() {
    let p = json!([[0.0, 3.0], [2.0, 6.5], [4.0, 9.0], [6.0, 10.0]]);
    let q = json!([[18.0, 10.0], [20.0, 9.0], [22.0, 6.5], [24.0, 3.0]]);
    for (u0, v0, p_shape, q_shape) in [
        (1.0, 0.0, vec![2.0, 1.5], vec![1.2, -0.7]),
        (0.8, 0.3, vec![0.7, -2.0, 4.0], vec![1.9, 3.0, -1.0]),
    ] {
        let job = json!({
            "p": p, "q": q, "u0": u0, "v0": v0,
            "continuity": "geometric",
            "p_order": p_shape.len(), "q_order": q_shape.len(),
            "p_shape": p_shape, "q_shape": q_shape,
        });
        let out = success(&job);
        let report = &out["report"];
        assert_eq!(report["continuity"], "geometric");
        assert_eq!(
            numbers(&report["p_shape"]),
            p_shape,
            "given shapes are used"
        );
        assert_eq!(numbers(&report["q_shape"]), q_shape);
        assert_eq!(report["p_shape_chosen"], "given");
        let r = bezier(&out["curve"]);
        assert_eq!(r.degree(), p_shape.len() + q_shape.len() + 1);
        let (pc, qc) = (bezier(&p), bezier(&q));
        assert_beta_constraints(
            &r.eval_derivatives(0.0, 3),
            &pc.eval_derivatives(u0, 3),
            &p_shape,
            2,
            "P",
        );
        assert_beta_constraints(
            &r.eval_derivatives(1.0, 3),
            &qc.eval_derivatives(v0, 3),
            &q_shape,
            2,
            "Q",
        );
        for join in report["measured_continuity"].as_array().unwrap() {
            assert_eq!(join["continuity"], "geometric");
            assert!(
                join["worst_promised_jump"].as_f64().unwrap() < 1e-9,
                "{join}"
            );
        }
        for end in report["measured_beta_constraints"].as_array().unwrap() {
            assert!(end["worst"].as_f64().unwrap() < 1e-9, "{end}");
        }
    }
}

/// The corner of a 40 and a 20 long edge, joined 2 from the vertex on
/// both: with scale 1 the C2 connection loops (about 18.6 long); the
/// default of a C^k connection (automatic scale) and the fair G2 shape
/// values (the default of the geometric one) give a blend shorter than 4
/// that stays in the corner's quadrant.
#[test]
fn defaults_do_not_loop_on_a_corner_of_long_edges() {
    let corner = json!({
        "p": [[-40.0, 0.0], [0.0, 0.0]],
        "q": [[0.0, 0.0], [0.0, 20.0]],
        "u0": 0.95, "v0": 0.1,
        "p_order": 2, "q_order": 2,
    });
    let with = |extra: Value| {
        let mut job = corner.clone();
        for (k, v) in extra.as_object().unwrap() {
            job[k] = v.clone();
        }
        job
    };
    let paper = success(&with(json!({"auto_scale": false})));
    let looping = length(&bezier(&paper["curve"]));
    assert!((looping - 18.6).abs() < 0.1, "scale 1: length {looping}");
    let inside = |c: &BezierCurve| {
        (0..=100).all(|i| {
            let x = c.eval(i as f64 / 100.0);
            x[0] <= 1e-12 && x[1] >= -1e-12
        })
    };
    for job in [with(json!({})), with(json!({"continuity": "geometric"}))] {
        let out = success(&job);
        let r = bezier(&out["curve"]);
        let l = length(&r);
        assert!(l < 4.0, "{job}: length {l}");
        assert!(inside(&r), "{job}: leaves the corner");
    }
    let geometric = success(&with(json!({"continuity": "geometric"})));
    let report = &geometric["report"];
    assert_eq!(report["p_shape_chosen"], "fair");
    assert_eq!(report["q_shape_chosen"], "fair");
    let p_shape = numbers(&report["p_shape"]);
    assert_eq!(p_shape.len(), 2);
    assert!(
        p_shape[0] > 0.0 && p_shape[0] != 1.0,
        "not the raw scale 1: {p_shape:?}"
    );
    for key in [
        "energy",
        "curvature_min",
        "curvature_max",
        "curvature_extrema",
    ] {
        assert!(report["fairness"][key].is_number(), "fairness.{key}");
    }
    // G2 to lines: the curvature vanishes at both ends of the blend.
    let r = bezier(&geometric["curve"]);
    for t in [0.0, 1.0] {
        let d = r.eval_derivatives(t, 2);
        let cross = d[2] * d[5] - d[3] * d[4];
        let speed = (d[2] * d[2] + d[3] * d[3]).sqrt();
        let kappa = cross / speed.powi(3);
        assert!(kappa.abs() < 1e-9, "curvature {kappa} at t = {t}");
    }
    let default_c2 = success(&with(json!({})));
    assert_eq!(default_c2["report"]["auto_scale"], true);
    assert!(default_c2["report"]["p_scale"].as_f64().unwrap() < 1.0);
}

#[test]
fn one_end_given_the_other_fair_and_the_example() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/connect-geometric.json"),
    )
    .unwrap();
    let job: Value = serde_json::from_str(&text).unwrap();
    let svg = std::env::temp_dir().join(format!("bezjoin-geometric-{}.svg", std::process::id()));
    let (code, stdout, stderr) = run(&job, Some(&svg));
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    let report = &out["report"];
    assert_eq!(numbers(&report["p_shape"]), numbers(&job["p_shape"]));
    assert_eq!(report["p_shape_chosen"], "given");
    assert_eq!(report["q_shape_chosen"], "fair");
    let q_shape = numbers(&report["q_shape"]);
    assert_eq!(q_shape.len(), 3);
    let r = bezier(&out["curve"]);
    assert_beta_constraints(
        &r.eval_derivatives(0.0, 3),
        &bezier(&job["p"]).eval_derivatives(1.0, 3),
        &numbers(&job["p_shape"]),
        2,
        "P",
    );
    assert_beta_constraints(
        &r.eval_derivatives(1.0, 3),
        &bezier(&job["q"]).eval_derivatives(0.0, 3),
        &q_shape,
        2,
        "Q",
    );
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_well_formed_xml(&picture);
    for text in [
        "(G2 | G3)",
        "G3 promised, G3 measured",
        "Curvature along arc length",
    ] {
        assert!(picture.contains(text), "picture lacks {text:?}");
    }
    let _ = std::fs::remove_file(&svg);
}

fn assert_exit_2_naming(job: &Value, field: &str) {
    let (code, stdout, stderr) = run(job, None);
    assert_eq!(code, 2, "{job}: {stderr}");
    assert!(stderr.contains(field), "{stderr:?} should name {field}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stdout.is_empty());
}

#[test]
fn bad_geometric_jobs_exit_2_naming_the_field() {
    let with = |extra: Value| {
        let mut job = json!({
            "p": [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]],
            "q": [[3.0, 0.0], [4.0, 1.0], [5.0, 0.0]],
            "continuity": "geometric",
        });
        for (k, v) in extra.as_object().unwrap() {
            job[k] = v.clone();
        }
        job
    };
    assert_exit_2_naming(&with(json!({"continuity": "G2"})), "continuity");
    assert_exit_2_naming(&with(json!({"p_shape": [1.0]})), "p_shape");
    assert_exit_2_naming(&with(json!({"q_shape": [-1.0, 0.0]})), "q_shape[0]");
    assert_exit_2_naming(&with(json!({"p_shape": [1.0, "x"]})), "p_shape[1]");
    assert_exit_2_naming(&with(json!({"p_shape": 2.0})), "p_shape");
    assert_exit_2_naming(&with(json!({"p_order": 9})), "p_order");
    assert_exit_2_naming(&with(json!({"p_scale": 0.5})), "p_scale");
    assert_exit_2_naming(&with(json!({"auto_scale": true})), "auto_scale");
    // Shape values belong to geometric continuity.
    assert_exit_2_naming(
        &with(json!({"continuity": "parametric", "q_shape": [1.0, 0.0]})),
        "q_shape",
    );
    assert_exit_2_naming(
        &with(json!({"continuity": null, "p_shape": [1.0, 0.0]})),
        "p_shape",
    );
}
