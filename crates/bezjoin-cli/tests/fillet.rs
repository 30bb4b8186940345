//! `bezjoin fillet` and `bezjoin intersect` run as processes: the examples
//! run, their outputs' defining properties hold when re-evaluated from the
//! returned control points, the SVG is well-formed and bad jobs exit 2
//! naming the field.

mod common;
use common::assert_well_formed_xml;

use std::ffi::OsString;
use std::path::PathBuf;

use bezjoin_core::BezierCurve;
use serde_json::Value;

fn repo_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(name)
}

/// Run `bezjoin <op> -` with `job` on stdin, optionally `--svg`.
fn run(op: &str, job: &str, svg: Option<&PathBuf>) -> (i32, String, String) {
    let mut args = vec![OsString::from(op), OsString::from("-")];
    if let Some(path) = svg {
        args.push("--svg".into());
        args.push(path.into());
    }
    let out = common::run_bezjoin(&args, job.as_bytes());
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn curve(value: &Value) -> BezierCurve {
    let rows: Vec<Vec<f64>> = serde_json::from_value(value["points"].clone()).unwrap();
    let dim = rows[0].len();
    let degree = rows.len() - 1;
    BezierCurve::new(dim, degree, rows.concat()).unwrap()
}

fn job_curve(job: &Value, key: &str) -> BezierCurve {
    let rows: Vec<Vec<f64>> = serde_json::from_value(job[key].clone()).unwrap();
    BezierCurve::new(rows[0].len(), rows.len() - 1, rows.concat()).unwrap()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Relative jump of the k-th derivatives, each divided by its interval^k.
fn jump(
    left: &BezierCurve,
    tl: f64,
    il: f64,
    right: &BezierCurve,
    tr: f64,
    ir: f64,
    k: usize,
) -> f64 {
    let a = left.eval_derivatives(tl, k);
    let b = right.eval_derivatives(tr, k);
    let a: Vec<f64> = a[k * left.dim()..]
        .iter()
        .map(|x| x / il.powi(k as i32))
        .collect();
    let b: Vec<f64> = b[k * right.dim()..]
        .iter()
        .map(|x| x / ir.powi(k as i32))
        .collect();
    let d: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(&a).max(norm(&b)).max(1e-300)
}

/// Arc length by composite Simpson on 20000 panels (independent of the
/// library's Gauss rules).
fn length(c: &BezierCurve, a: f64, b: f64) -> f64 {
    let n = 20000;
    let h = (b - a) / n as f64;
    let speed = |t: f64| norm(&c.eval_derivatives(t, 1)[c.dim()..]);
    let mut s = speed(a) + speed(b);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * speed(a + i as f64 * h);
    }
    (s * h / 3.0).abs()
}

fn min_distance(c: &BezierCurve, point: &[f64]) -> f64 {
    (0..=100_000)
        .map(|i| {
            let p = c.eval(i as f64 / 100_000.0);
            norm(&[p[0] - point[0], p[1] - point[1]])
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn well_formed_checker_rejects_broken_xml() {
    let broken = std::panic::catch_unwind(|| assert_well_formed_xml("<svg><g></svg>"));
    assert!(broken.is_err());
    assert_well_formed_xml("<?xml version=\"1.0\"?><svg a=\"x>y\"><g/><text>a</text></svg>");
}

fn check_fillet_output(job: &Value, out: &Value, setbacks: Option<(f64, f64)>) {
    let p = job_curve(job, "p");
    let q = job_curve(job, "q");
    let pt = curve(&out["p_trimmed"]);
    let r = curve(&out["blend"]);
    let qt = curve(&out["q_trimmed"]);
    let u0 = out["u0"].as_f64().unwrap();
    let v0 = out["v0"].as_f64().unwrap();
    let kp = job["p_order"].as_u64().unwrap() as usize;
    let kq = job["q_order"].as_u64().unwrap() as usize;
    let (given_p, given_q) = (job["p_scale"].as_f64(), job["q_scale"].as_f64());
    let (alpha, beta) = if job["auto_scale"].as_bool() == Some(false) {
        // The paper's scale 1 where none is given.
        (given_p.unwrap_or(1.0), given_q.unwrap_or(1.0))
    } else if job["auto_scale"].as_str() == Some("balanced")
        || (job.get("auto_scale").is_none() && given_p.is_none() && given_q.is_none())
    {
        // Chosen by the library, one speed at both ends (asked for, or the
        // default without scales since session 44): the reported scales.
        assert_eq!(out["report"]["balanced_scale"].as_bool(), Some(true));
        (
            out["report"]["p_scale"].as_f64().unwrap(),
            out["report"]["q_scale"].as_f64().unwrap(),
        )
    } else if given_p.is_some() || given_q.is_some() {
        // One given scale stands for both.
        (given_p.or(given_q).unwrap(), given_q.or(given_p).unwrap())
    } else {
        // Chosen by the library (`"auto_scale": true`): the reported
        // scales, equal.
        let s = out["report"]["p_scale"].as_f64().unwrap();
        assert_eq!(out["report"]["q_scale"].as_f64(), Some(s));
        (s, s)
    };
    assert_eq!(out["report"]["p_scale"].as_f64(), Some(alpha));
    assert_eq!(out["report"]["q_scale"].as_f64(), Some(beta));
    assert_eq!(r.degree(), kp + kq + 1);
    // Trimmed pieces are the original curves' parts.
    for i in 0..=20 {
        let s = i as f64 / 20.0;
        let (a, b) = (pt.eval(s), p.eval(s * u0));
        assert!(norm(&[a[0] - b[0], a[1] - b[1]]) < 1e-12);
        let (a, b) = (qt.eval(s), q.eval(v0 + s * (1.0 - v0)));
        assert!(norm(&[a[0] - b[0], a[1] - b[1]]) < 1e-12);
    }
    // C^k in the B-spline sense with intervals (u0, alpha, (1-v0) alpha/beta).
    let c = (1.0 - v0) * alpha / beta;
    for k in 0..=kp {
        let j = jump(&pt, 1.0, u0, &r, 0.0, alpha, k);
        assert!(j < 1e-9, "P|R order {k}: jump {j}");
    }
    for k in 0..=kq {
        let j = jump(&r, 1.0, alpha, &qt, 0.0, c, k);
        assert!(j < 1e-9, "R|Q order {k}: jump {j}");
    }
    // The order above the promise is generically NOT continuous (the test
    // can fail: the blend is not just a copy of a smooth curve).
    let above = jump(&pt, 1.0, u0, &r, 0.0, alpha, kp + 1);
    assert!(above > 1e-6, "order kp+1 unexpectedly continuous: {above}");
    // The crossing is a meeting point of P and Q.
    let x = &out["crossing"];
    let (u, v) = (x["u"].as_f64().unwrap(), x["v"].as_f64().unwrap());
    let (a, b) = (p.eval(u), q.eval(v));
    assert!(norm(&[a[0] - b[0], a[1] - b[1]]) < 1e-8);
    assert!(u0 < u && v < v0);
    if let Some((dp, dq)) = setbacks {
        let lp = length(&p, u0, u);
        let lq = length(&q, v, v0);
        assert!(
            (lp - dp).abs() < 1e-8 * dp.max(1.0),
            "P setback {lp} vs {dp}"
        );
        assert!(
            (lq - dq).abs() < 1e-8 * dq.max(1.0),
            "Q setback {lq} vs {dq}"
        );
        let reported = out["report"]["measured_p_setback"].as_f64().unwrap();
        assert!((reported - lp).abs() < 1e-8);
    }
}

#[test]
fn fillet_example_runs_and_its_properties_hold() {
    let text = std::fs::read_to_string(repo_file("examples/fillet.json")).unwrap();
    let job: Value = serde_json::from_str(&text).unwrap();
    let svg = std::env::temp_dir().join(format!("bezjoin-fillet-test-{}.svg", std::process::id()));
    let (code, stdout, stderr) = run("fillet", &text, Some(&svg));
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    let dp = job["p_setback"].as_f64().unwrap();
    let dq = job["q_setback"].as_f64().unwrap();
    check_fillet_output(&job, &out, Some((dp, dq)));
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_well_formed_xml(&picture);
    assert!(picture.contains("circular-arc fillet"));
    let _ = std::fs::remove_file(&svg);
}

#[test]
fn fillet_c3_asymmetric_and_default_scales() {
    let job: Value = serde_json::json!({
        "p": [[-4.0, -0.5], [-2.5, 0.8], [-1.0, 0.6], [1.5, -0.2]],
        "q": [[0.2, -2.0], [-0.3, -0.5], [0.6, 1.2], [-0.2, 3.0]],
        "p_setback": 0.4, "q_setback": 0.9, "p_order": 3, "q_order": 3
    });
    let (code, stdout, stderr) = run("fillet", &job.to_string(), None);
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    check_fillet_output(&job, &out, Some((0.4, 0.9)));
}

/// Fast lines (speed 8, as cubics) with a short setback: with scale 1
/// (`"auto_scale": false`, the paper's) the blend's control points pass the
/// corner; without any scale field the scale is chosen automatically (the
/// default) and they stay in the corner's quadrant, as with `"auto_scale":
/// true`; on fast curved cubics the C^k chain holds at the chosen scale.
#[test]
fn fillet_auto_scale_keeps_the_blend_in_the_corner() {
    let lines = serde_json::json!({
        "p": [[-4.0, 0.0], [-1.0, 0.0], [2.0, 0.0], [5.0, 0.0]],
        "q": [[0.0, -4.0], [0.0, -1.0], [0.0, 2.0], [0.0, 5.0]],
        "p_setback": 0.5, "p_order": 2, "q_order": 2
    });
    let inside = |out: &Value| {
        out["blend"]["points"]
            .as_array()
            .unwrap()
            .iter()
            .all(|b| b[0].as_f64().unwrap() <= 1e-15 && b[1].as_f64().unwrap() >= -1e-15)
    };
    let mut paper = lines.clone();
    paper["auto_scale"] = Value::Bool(false);
    let (code, stdout, stderr) = run("fillet", &paper.to_string(), None);
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(out["report"]["p_scale"].as_f64(), Some(1.0));
    assert!(!inside(&out));
    let mut chosen = None;
    for auto in [None, Some(true)] {
        let mut job = lines.clone();
        if let Some(a) = auto {
            job["auto_scale"] = Value::Bool(a);
        }
        let (code, stdout, stderr) = run("fillet", &job.to_string(), None);
        assert_eq!(code, 0, "{stderr}");
        let out: Value = serde_json::from_str(&stdout).unwrap();
        assert!(inside(&out), "{}", out["blend"]);
        let s = out["report"]["p_scale"].as_f64().unwrap();
        assert!(s > 0.0 && s < 1.0, "s = {s}");
        assert_eq!(
            *chosen.get_or_insert(s),
            s,
            "the default (balanced) is the automatic scale where the speeds agree"
        );
    }
    // The chain check needs nonzero higher derivatives: fast curved cubics.
    let curved = serde_json::json!({
        "p": [[-4.0, -0.6], [-1.0, 0.3], [2.0, 0.3], [5.0, -0.6]],
        "q": [[0.6, -4.0], [-0.3, -1.0], [-0.3, 2.0], [0.6, 5.0]],
        "p_setback": 0.5, "p_order": 2, "q_order": 2, "auto_scale": true
    });
    let (code, stdout, stderr) = run("fillet", &curved.to_string(), None);
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    check_fillet_output(&curved, &out, Some((0.5, 0.5)));
}

#[test]
fn balanced_fillet_gives_unequal_lines_the_blend_of_equal_ones() {
    // Lines 1000 and 10 long meeting at a right angle, setback 1: cut at the same
    // points as lines 10 and 10, so the balanced blend is the same; the checks of
    // `check_fillet_output` hold with its two scales.
    let job = |p_start: f64| {
        serde_json::json!({
            "p": [[p_start, 0.0], [0.0, 0.0]],
            "q": [[0.0, 0.0], [0.0, 10.0]],
            "p_setback": 1.0, "p_order": 2, "q_order": 2, "vertex": true,
            "auto_scale": "balanced"
        })
    };
    let mut blends = Vec::new();
    for p_start in [-10.0, -1000.0] {
        let job = job(p_start);
        let (code, stdout, stderr) = run("fillet", &job.to_string(), None);
        assert_eq!(code, 0, "{stderr}");
        let out: Value = serde_json::from_str(&stdout).unwrap();
        assert_eq!(out["report"]["balanced_scale"], Value::Bool(true));
        let (alpha, beta) = (
            out["report"]["p_scale"].as_f64().unwrap(),
            out["report"]["q_scale"].as_f64().unwrap(),
        );
        assert!((alpha * -p_start - beta * 10.0).abs() <= 1e-12 * beta * 10.0);
        blends.push(curve(&out["blend"]));
    }
    for (a, b) in blends[0].points().iter().zip(blends[1].points()) {
        assert!((a - b).abs() <= 1e-12, "{a} vs {b}");
    }
    // Curved cubics of different speeds: the chain is C^2 with the two scales.
    let curved = serde_json::json!({
        "p": [[-8.0, -0.6], [-2.0, 0.3], [4.0, 0.3], [10.0, -0.6]],
        "q": [[0.6, -1.0], [-0.3, -0.2], [-0.3, 0.5], [0.6, 1.2]],
        "p_setback": 0.3, "p_order": 2, "q_order": 2, "auto_scale": "balanced"
    });
    let (code, stdout, stderr) = run("fillet", &curved.to_string(), None);
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    check_fillet_output(&curved, &out, Some((0.3, 0.3)));
    let r = curve(&out["blend"]);
    let (start, end) = (
        norm(&r.derivative_at(0.0, 1)),
        norm(&r.derivative_at(1.0, 1)),
    );
    assert!((start - end).abs() <= 1e-12 * start, "{start} vs {end}");
    // Where it is not offered, the field is named.
    let mut deviation = job(-10.0);
    deviation["max_deviation"] = serde_json::json!(0.1);
    deviation.as_object_mut().unwrap().remove("p_setback");
    deviation.as_object_mut().unwrap().remove("vertex");
    assert_exit_2_naming("fillet", &deviation.to_string(), "auto_scale");
}

#[test]
fn fillet_within_deviation_passes_at_eps_from_the_corner() {
    let eps = 0.08;
    let job: Value = serde_json::json!({
        "p": [[-4.0, -0.5], [-2.5, 0.8], [-1.0, 0.6], [1.5, -0.2]],
        "q": [[0.2, -2.0], [-0.3, -0.5], [0.6, 1.2], [-0.2, 3.0]],
        "max_deviation": eps, "p_order": 2, "q_order": 2,
        "p_scale": 0.15, "q_scale": 0.15
    });
    let (code, stdout, stderr) = run("fillet", &job.to_string(), None);
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    check_fillet_output(&job, &out, None);
    let x: Vec<f64> = serde_json::from_value(out["crossing"]["point"].clone()).unwrap();
    let d = min_distance(&curve(&out["blend"]), &x);
    assert!((d - eps).abs() < 1e-6, "distance {d} vs eps {eps}");
}

#[test]
fn intersect_example_hits_are_meeting_points_and_crossings() {
    let text = std::fs::read_to_string(repo_file("examples/intersect.json")).unwrap();
    let job: Value = serde_json::from_str(&text).unwrap();
    let svg =
        std::env::temp_dir().join(format!("bezjoin-intersect-test-{}.svg", std::process::id()));
    let (code, stdout, stderr) = run("intersect", &text, Some(&svg));
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    let p = job_curve(&job, "p");
    let q = job_curve(&job, "q");
    let hits = out["hits"].as_array().unwrap();
    // Independent count: proper crossings of fine polylines of P and Q
    // (an odd sample count keeps the symmetric middle crossing off the
    // vertices).
    let n = 1999;
    let poly = |c: &BezierCurve| -> Vec<Vec<f64>> {
        (0..=n).map(|i| c.eval(i as f64 / n as f64)).collect()
    };
    let (pp, qq) = (poly(&p), poly(&q));
    let cross = |a: &[f64], b: &[f64], c: &[f64]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let mut polyline_crossings = 0;
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (&pp[i], &pp[i + 1], &qq[j], &qq[j + 1]);
            if cross(a, b, c) * cross(a, b, d) < 0.0 && cross(c, d, a) * cross(c, d, b) < 0.0 {
                polyline_crossings += 1;
            }
        }
    }
    assert_eq!(hits.len(), polyline_crossings);
    assert!(hits.len() >= 3);
    let mut last_u = -1.0;
    for h in hits {
        let (u, v) = (h["u"].as_f64().unwrap(), h["v"].as_f64().unwrap());
        let (a, b) = (p.eval(u), q.eval(v));
        assert!(norm(&[a[0] - b[0], a[1] - b[1]]) < 1e-8);
        let point: Vec<f64> = serde_json::from_value(h["point"].clone()).unwrap();
        assert!(norm(&[point[0] - a[0], point[1] - a[1]]) < 1e-12);
        assert_eq!(h["kind"], "crossing");
        assert!(u > last_u + 1e-6, "hits ordered by u and distinct");
        last_u = u;
    }
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_well_formed_xml(&picture);
    let _ = std::fs::remove_file(&svg);
}

fn assert_exit_2_naming(op: &str, job: &str, field: &str) {
    let (code, _, stderr) = run(op, job, None);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains(field), "{stderr:?} should name {field}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn bad_jobs_exit_2_naming_the_field() {
    let lines = r#""p": [[-1, 0], [1, 0]], "q": [[0, -1], [0, 1]]"#;
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": -0.5}}"),
        "p_setback",
    );
    assert_exit_2_naming("fillet", &format!("{{{lines}}}"), "p_setback");
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": 0.2, \"max_deviation\": 0.1}}"),
        "p_setback",
    );
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": 0.2, \"colour\": 1}}"),
        "colour",
    );
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": 0.2, \"auto_scale\": true, \"q_scale\": 2}}"),
        "q_scale",
    );
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": 0.2, \"auto_scale\": 1}}"),
        "auto_scale",
    );
    // Setback longer than the part of P before the crossing (library error).
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": 5}}"),
        "p_setback",
    );
    // Orders may exceed the degree (a line's higher derivatives are 0),
    // but must be non-negative integers.
    assert_exit_2_naming(
        "fillet",
        &format!("{{{lines}, \"p_setback\": 0.2, \"p_order\": 1.5}}"),
        "p_order",
    );
    assert_exit_2_naming(
        "fillet",
        "{\"p\": [[0, 0], [1, 0]], \"q\": [[0, 1], [1, 1]], \"p_setback\": 0.1}",
        "intersect",
    );
    assert_exit_2_naming(
        "intersect",
        &format!("{{{lines}, \"max_depth\": \"x\"}}"),
        "max_depth",
    );
    // "q" alone would be found inside "required": name the field as printed.
    assert_exit_2_naming(
        "intersect",
        "{\"p\": [[0, 0], [1, 0]]}",
        "invalid job: q: is required",
    );
    assert_exit_2_naming(
        "intersect",
        "{\"p\": [[0, 0], [1, 0]], \"q\": [[0, 0, 1], [1, 0, 1]]}",
        "invalid job: q has dimension 3, expected 2",
    );
    assert_exit_2_naming("intersect", "{\"p\": [[0, 0], [1, 0]", "line");
}
