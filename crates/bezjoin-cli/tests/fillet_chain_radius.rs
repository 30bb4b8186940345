//! `bezjoin fillet-chain` with `"radius"` run as a process (issue 18):
//! every corner of an open and of a closed wire is cut where the arc of
//! radius r touches both edges (for two lines at r tan(theta/2) from the
//! vertex, theta computed here from the job), the printed pieces meet with
//! G2 (G3 with `"order": 3`) judged here from the unit tangent, the
//! curvature vector and its arc-length derivative of the printed control
//! points, the per-corner report agrees with the blends' curvature sampled
//! here, and bad jobs exit 2 naming the field.

mod common;
use common::{assert_geometric_join, bezier_of as bezier, dist, dot, frenet, norm};

use bezjoin_core::BezierCurve;
use serde_json::{Value, json};

/// The subcommand under test.
const OP: &str = "fillet-chain";

fn numbers(value: &Value) -> Vec<f64> {
    serde_json::from_value(value.clone()).unwrap()
}

/// The job's curves (Bezier) and the printed result of the job.
fn rounded(job: &Value) -> (Vec<BezierCurve>, Value) {
    let curves = job["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(bezier)
        .collect();
    (curves, common::job_result(OP, job))
}

/// The pieces of a printed chain meet with G^order at every join: the
/// same point, unit tangent and curvature vector (and `dK/ds` for order
/// 3) on both sides, relative to the adjoining blend's largest curvature
/// (and its derivative); with order 2 the slope of the curvature jumps
/// (the check can tell G2 from G3). Returns the number of joins.
fn assert_geometric_chain(out: &Value, order: usize, closed: bool) -> usize {
    let pieces = printed_pieces(out);
    // A closed chain also joins its last piece to its first.
    let joins = pieces.len() - usize::from(!closed);
    for j in 0..joins {
        let (a, b) = (&pieces[j], &pieces[(j + 1) % pieces.len()]);
        // Every join has a blend on one side (pieces alternate).
        let blend = if j % 2 == 0 { b } else { a };
        assert_eq!(blend.degree(), 2 * order + 1, "join {j}: blend degree");
        assert_geometric_join(&format!("join {j}"), a, b, blend, order);
    }
    joins
}

/// The printed chain's pieces, in path order.
fn printed_pieces(out: &Value) -> Vec<BezierCurve> {
    out["pieces"]
        .as_array()
        .unwrap()
        .iter()
        .map(bezier)
        .collect()
}

/// Signed curvature of a plane curve at `t`.
fn curvature(c: &BezierCurve, t: f64) -> f64 {
    let d = c.eval_derivatives(t, 2);
    let (x1, y1, x2, y2) = (d[2], d[3], d[4], d[5]);
    (x1 * y2 - y1 * x2) / (x1 * x1 + y1 * y1).powf(1.5)
}

/// Corner `i` of a wire of Bezier curves `curves` (the job's): the cuts
/// lie on the given curves where the printed pieces end and start, the
/// arc's centre is `r` from both cuts along their normals (the arc touches
/// there), the corner is the vertex, and the fairness report's curvature
/// range and extrema are those of the printed blend, sampled here.
fn assert_corner(out: &Value, curves: &[BezierCurve], i: usize, r: f64) {
    let n = curves.len();
    let corner = &out["corners"][i];
    let pieces = out["pieces"].as_array().unwrap();
    let (p, q) = (&curves[i], &curves[(i + 1) % n]);
    let (u0, v0) = (
        corner["u0"].as_f64().unwrap(),
        corner["v0"].as_f64().unwrap(),
    );
    let kept_p = bezier(&pieces[2 * i]);
    let kept_q = bezier(&pieces[(2 * i + 2) % pieces.len()]);
    let (at_p, at_q) = (p.eval(u0), q.eval(v0));
    let touching = &corner["touching_points"];
    assert!(dist(&numbers(&touching[0]), &at_p) < 1e-12, "corner {i}");
    assert!(dist(&numbers(&touching[1]), &at_q) < 1e-12, "corner {i}");
    assert!(dist(&kept_p.eval(1.0), &at_p) < 1e-12, "corner {i}: P cut");
    assert!(dist(&kept_q.eval(0.0), &at_q) < 1e-12, "corner {i}: Q cut");
    let centre = numbers(&corner["arc_centre"]);
    for (name, c, t, at) in [("P", p, u0, &at_p), ("Q", q, v0, &at_q)] {
        let [tangent, _, _] = frenet(c, t);
        let radial: Vec<f64> = centre.iter().zip(at).map(|(a, b)| a - b).collect();
        assert!(
            (norm(&radial) - r).abs() < 1e-9 * r,
            "corner {i} {name}: {radial:?}"
        );
        assert!(
            dot(&radial, &tangent).abs() < 1e-9 * r,
            "corner {i} {name}: the arc does not touch"
        );
    }
    assert_eq!(corner["corner"], "vertex");
    let vertex = p.eval(1.0);
    assert!(dist(&numbers(&corner["crossing"]["point"]), &vertex) < 1e-12);
    // The fairness report describes the printed blend.
    let blend = bezier(&pieces[2 * i + 1]);
    let kappa: Vec<f64> = (0..=400)
        .map(|s| curvature(&blend, s as f64 / 400.0))
        .collect();
    let lo = kappa.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = kappa.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let fairness = &corner["fairness"];
    let (rlo, rhi) = (
        fairness["curvature_min"].as_f64().unwrap(),
        fairness["curvature_max"].as_f64().unwrap(),
    );
    let size = rhi.abs().max(rlo.abs());
    assert!(
        (lo - rlo).abs() < 1e-3 * size,
        "corner {i}: min {lo} vs {rlo}"
    );
    assert!(
        (hi - rhi).abs() < 1e-3 * size,
        "corner {i}: max {hi} vs {rhi}"
    );
    let energy = fairness["energy"].as_f64().unwrap();
    assert!(
        energy.is_finite() && energy > 0.0,
        "corner {i}: energy {energy}"
    );
    let extrema = kappa
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
        .count();
    assert_eq!(
        fairness["curvature_extrema"].as_u64(),
        Some(extrema as u64),
        "corner {i}: interior curvature extrema"
    );
    // No loop: the blend turns one way, as the corner does.
    assert!(
        kappa.iter().all(|k| k * (lo + hi) >= -1e-9 * size),
        "corner {i}: the blend has an inflection"
    );
}

/// `r tan(theta / 2)`, theta the turning angle from `a` to `b` (directions).
fn tangent_length(a: &[f64], b: &[f64], r: f64) -> f64 {
    let cos = dot(a, b) / (norm(a) * norm(b));
    r * (0.5 * cos.clamp(-1.0, 1.0).acos()).tan()
}

#[test]
fn open_wire_of_lines_and_a_cubic_is_g2_at_every_join() {
    let job = json!({
        "curves": [
            [[0.0, 0.0], [6.0, 0.0]],
            [[6.0, 0.0], [8.0, 5.0]],
            [[8.0, 5.0], [7.0, 8.0], [5.0, 9.0], [2.0, 9.0]]
        ],
        "radius": 1.0
    });
    let (curves, out) = rounded(&job);
    assert_eq!(out["pieces"].as_array().unwrap().len(), 5);
    assert_eq!(out["corners"].as_array().unwrap().len(), 2);
    assert_eq!(assert_geometric_chain(&out, 2, false), 4);
    for i in 0..2 {
        assert_corner(&out, &curves, i, 1.0);
    }
    // Between the two lines the cuts are r tan(theta/2) from the vertex.
    let setback = tangent_length(&[1.0, 0.0], &[2.0, 5.0], 1.0);
    let pieces = out["pieces"].as_array().unwrap();
    let vertex = [6.0, 0.0];
    assert!((dist(&bezier(&pieces[0]).eval(1.0), &vertex) - setback).abs() < 1e-9);
    assert!((dist(&bezier(&pieces[2]).eval(0.0), &vertex) - setback).abs() < 1e-9);
    // The open ends are kept.
    assert!(dist(&bezier(&pieces[0]).eval(0.0), &[0.0, 0.0]) < 1e-12);
    assert!(dist(&bezier(&pieces[4]).eval(1.0), &[2.0, 9.0]) < 1e-12);
    let report = &out["report"];
    assert_eq!(report["mode"], "radius");
    assert_eq!(report["closed"], false);
    assert_eq!(report["order"], 2, "order 2 by default");
    assert_eq!(report["measured_continuity"].as_array().unwrap().len(), 4);
}

#[test]
fn closed_triangle_is_g3_at_every_join_and_drawn() {
    let corners = [[0.0, 0.0], [8.0, 0.0], [3.0, 6.0]];
    let curves: Vec<Value> = (0..3)
        .map(|i| json!([corners[i], corners[(i + 1) % 3]]))
        .collect();
    let job = json!({"curves": curves, "closed": true, "radius": 1.0, "order": 3});
    let svg = std::env::temp_dir().join(format!("bezjoin-chain-radius-{}.svg", std::process::id()));
    let (code, stdout, stderr) = common::run_job(OP, &job, Some(&svg));
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(out["pieces"].as_array().unwrap().len(), 6);
    assert_eq!(assert_geometric_chain(&out, 3, true), 6);
    let lines: Vec<BezierCurve> = curves.iter().map(bezier).collect();
    let pieces = out["pieces"].as_array().unwrap();
    for i in 0..3 {
        assert_corner(&out, &lines, i, 1.0);
        // Corner i is the vertex at the end of edge i.
        let (a, b, c) = (corners[i], corners[(i + 1) % 3], corners[(i + 2) % 3]);
        let setback = tangent_length(
            &[b[0] - a[0], b[1] - a[1]],
            &[c[0] - b[0], c[1] - b[1]],
            1.0,
        );
        let kept_before = bezier(&pieces[2 * i]);
        let kept_after = bezier(&pieces[(2 * i + 2) % 6]);
        assert!(
            (dist(&kept_before.eval(1.0), &b) - setback).abs() < 1e-9,
            "corner {i}"
        );
        assert!(
            (dist(&kept_after.eval(0.0), &b) - setback).abs() < 1e-9,
            "corner {i}"
        );
    }
    assert_eq!(out["report"]["closed"], true);
    let picture = common::read_picture(
        &svg,
        &[
            "blend 2, degree 7 (G3 | G3, fair shape values)",
            "circular arc of radius 1",
            "blend 2|curve 0: G3 promised, G3 measured",
        ],
    );
    assert_eq!(
        picture.matches("<clipPath ").count(),
        1,
        "one curvature graph"
    );
    let _ = std::fs::remove_file(&svg);
}

fn assert_exit_2_naming(job: &Value, fields: &[&str]) {
    let (code, stdout, stderr) = common::run_job(OP, job, None);
    assert_eq!(code, 2, "{job}: {stderr}");
    for field in fields {
        assert!(stderr.contains(field), "{stderr:?} should name {field}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stdout.is_empty());
}

#[test]
fn bad_radius_jobs_exit_2_naming_the_field() {
    let rectangle = |w: f64, h: f64, extra: Value| {
        let c = [[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]];
        let curves: Vec<Value> = (0..4).map(|i| json!([c[i], c[(i + 1) % 4]])).collect();
        let mut job = json!({"curves": curves, "closed": true});
        for (k, v) in extra.as_object().unwrap() {
            job[k] = v.clone();
        }
        job
    };
    assert_eq!(
        common::run_job(OP, &rectangle(8.0, 5.0, json!({"radius": 1})), None).0,
        0
    );
    assert_exit_2_naming(
        &rectangle(8.0, 5.0, json!({"radius": -1})),
        &["radius: -1 must be > 0"],
    );
    assert_exit_2_naming(&rectangle(8.0, 5.0, json!({"radius": 0})), &["radius"]);
    for other in ["p_setback", "q_setback", "p_order", "q_scale", "auto_scale"] {
        assert_exit_2_naming(
            &rectangle(8.0, 5.0, json!({"radius": 1, other: 1})),
            &[other, "radius"],
        );
    }
    // "order" belongs to the radius mode; orders 1..=6.
    assert_exit_2_naming(
        &rectangle(8.0, 5.0, json!({"p_setback": 1, "order": 2})),
        &["order"],
    );
    assert_exit_2_naming(
        &rectangle(8.0, 5.0, json!({"radius": 1, "order": 0})),
        &["order"],
    );
    assert_exit_2_naming(
        &rectangle(8.0, 5.0, json!({"radius": 1, "order": 7})),
        &["order"],
    );
    // The short edges (1 long) would be cut 0.8 from both ends: the radius
    // is too large for them.
    assert_exit_2_naming(
        &rectangle(8.0, 1.0, json!({"radius": 0.8})),
        &["radius: 0.8 is too large for curves[1]", "overlap"],
    );
    // At an open end: the arc of radius 3 would touch the first edge (1
    // long) 3 from the vertex.
    let open = json!({
        "curves": [[[0.0, 0.0], [1.0, 0.0]], [[1.0, 0.0], [1.0, 5.0]]],
        "radius": 3
    });
    assert_exit_2_naming(&open, &["radius", "corner 0"]);
}

/// The chain check fails on a blend whose third control point is moved
/// (a curvature jump at its first join), and the fairness check on a
/// report whose curvature maximum is not the blend's.
#[test]
fn the_checks_are_not_vacuous() {
    let job = json!({
        "curves": [[[-4.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 4.0]]],
        "radius": 1.0
    });
    let (curves, out) = rounded(&job);
    assert_geometric_chain(&out, 2, false);
    assert_corner(&out, &curves, 0, 1.0);
    let mut bent = out.clone();
    let y = bent["pieces"][1]["points"][2][1].as_f64().unwrap();
    bent["pieces"][1]["points"][2][1] = json!(y + 1e-4);
    let broken = std::panic::catch_unwind(|| assert_geometric_chain(&bent, 2, false));
    assert!(broken.is_err(), "a curvature jump must fail the G2 check");
    let mut wrong = out.clone();
    let max = wrong["corners"][0]["fairness"]["curvature_max"]
        .as_f64()
        .unwrap();
    wrong["corners"][0]["fairness"]["curvature_max"] = json!(1.1 * max);
    let broken = std::panic::catch_unwind(|| assert_corner(&wrong, &curves, 0, 1.0));
    assert!(broken.is_err(), "a wrong curvature range must fail");
}

/// `"auto_scale": "balanced"` by setbacks: a closed 1000 x 10 rectangle of
/// lines gets, at every corner, the blend of a 10 x 10 square moved to that
/// corner (the cuts lie at the same places relative to the corner; only the
/// sides' speeds differ), and the reported scales are one speed over each
/// side's length.
#[test]
fn balanced_setback_chain_rounds_a_long_rectangle_as_a_square() {
    let rectangle = |w: f64, h: f64| {
        json!({
            "curves": [[[0.0, 0.0], [w, 0.0]], [[w, 0.0], [w, h]], [[w, h], [0.0, h]],
                       [[0.0, h], [0.0, 0.0]]],
            "closed": true, "p_setback": 1.0, "p_order": 2, "auto_scale": "balanced"
        })
    };
    let corners = |job: &Value| {
        let out = common::job_result(OP, job);
        let corners_at: Vec<Vec<f64>> = job["curves"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| numbers(&c[0]))
            .collect();
        let pieces = printed_pieces(&out);
        let shapes: Vec<Vec<f64>> = (0..4)
            .map(|i| {
                let corner = &corners_at[(i + 1) % 4];
                let blend = &pieces[2 * i + 1];
                (0..=blend.degree())
                    .flat_map(|k| (0..2).map(move |c| blend.point(k)[c] - corner[c]))
                    .collect()
            })
            .collect();
        (shapes, out)
    };
    let (square, _) = corners(&rectangle(10.0, 10.0));
    let (long, out) = corners(&rectangle(1000.0, 10.0));
    for (i, (a, b)) in long.iter().zip(&square).enumerate() {
        let apart = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(apart <= 1e-9, "corner {i}: {apart}");
    }
    assert_eq!(out["report"]["balanced_scale"], json!(true));
    assert_eq!(out["report"]["auto_scale"], json!(true));
    let lengths = [1000.0, 10.0, 1000.0, 10.0];
    for (i, corner) in out["corners"].as_array().unwrap().iter().enumerate() {
        let (alpha, beta) = (
            corner["p_scale"].as_f64().unwrap(),
            corner["q_scale"].as_f64().unwrap(),
        );
        let (before, after) = (alpha * lengths[i], beta * lengths[(i + 1) % 4]);
        assert!(
            (before - after).abs() <= 1e-12 * after,
            "corner {i}: speeds {before}, {after}"
        );
    }
}
