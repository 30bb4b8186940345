//! NURBS curves in jobs (issue 16, item 7), run as processes: the NURBS and
//! arc forms are read (bad values exit 2 naming their JSON path), a merge
//! refuses rational curves naming the field, and the pieces a fillet
//! or a fillet chain returns are re-read from the printed JSON and checked
//! by evaluating derivatives on both sides of every join — not by reading
//! the tool's own report.

mod common;

use std::f64::consts::PI;
use std::ffi::OsString;

use bezjoin_core::{BezierCurve, Curve, KnotSide, NurbsCurve};
use serde_json::{Value, json};

/// Run `bezjoin <op> -` with `job` on stdin: (exit code, stdout, stderr).
fn run(op: &str, job: &Value) -> (i32, String, String) {
    let args = [OsString::from(op), OsString::from("-")];
    let out = common::run_bezjoin(&args, job.to_string().as_bytes());
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn run_ok(op: &str, job: &Value) -> Value {
    let (code, stdout, stderr) = run(op, job);
    assert_eq!(code, 0, "bezjoin {op}: {stderr}");
    serde_json::from_str(&stdout).expect("a JSON result")
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn rows(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().flat_map(numbers).collect()
}

/// A curve of the result, rebuilt with the library from its printed form.
fn curve(v: &Value) -> Curve {
    let degree = v["degree"].as_u64().unwrap() as usize;
    let dim = v["dim"].as_u64().unwrap() as usize;
    if v.get("knots").is_some() {
        let weights = numbers(&v["weights"]);
        Curve::Nurbs(
            NurbsCurve::new(
                dim,
                degree,
                rows(&v["poles"]),
                Some(weights),
                numbers(&v["knots"]),
            )
            .unwrap(),
        )
    } else {
        Curve::Bezier(BezierCurve::new(dim, degree, rows(&v["points"])).unwrap())
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// One side of a join: a curve, where it meets the join (from which side),
/// and its knot interval per unit of its own parameter (row `k` of its
/// derivatives is divided by `rate^k`).
struct At<'a> {
    curve: &'a Curve,
    u: f64,
    side: KnotSide,
    rate: f64,
}

/// The end of `curve` (from the left), read at `rate`.
fn end_of(curve: &Curve, rate: f64) -> At<'_> {
    At {
        curve,
        u: curve.domain().1,
        side: KnotSide::Left,
        rate,
    }
}

/// The start of `curve` (from the right), read at `rate`.
fn start_of(curve: &Curve, rate: f64) -> At<'_> {
    At {
        curve,
        u: curve.domain().0,
        side: KnotSide::Right,
        rate,
    }
}

/// Derivatives `0..=order` of both sides of a join in the chain's
/// parameter; returns the difference of each order relative to the larger
/// side, and at least to `speed^k` (the curves here are a few units in
/// size, so a unit length scale: a second derivative that vanishes on both
/// sides, like a line's, is then no jump).
fn join_jumps(left: At, right: At, order: usize) -> Vec<f64> {
    let dim = left.curve.dim();
    let read = |s: &At| -> Vec<Vec<f64>> {
        let d = s.curve.eval_derivatives_side(s.u, order, s.side);
        (0..=order)
            .map(|k| {
                d[k * dim..(k + 1) * dim]
                    .iter()
                    .map(|x| x / s.rate.powi(k as i32))
                    .collect()
            })
            .collect()
    };
    let (a, b) = (read(&left), read(&right));
    let speed = norm(&a[1]);
    (0..=order)
        .map(|k| {
            let d: Vec<f64> = a[k].iter().zip(&b[k]).map(|(x, y)| x - y).collect();
            norm(&d) / norm(&a[k]).max(norm(&b[k])).max(speed.powi(k as i32))
        })
        .collect()
}

/// Signed curvature of a plane curve at `u`, from the given side.
fn curvature(c: &Curve, u: f64, side: KnotSide) -> f64 {
    let d = c.eval_derivatives_side(u, 2, side);
    (d[2] * d[5] - d[3] * d[4]) / d[2].hypot(d[3]).powi(3)
}

/// An arc of radius 3 around (3, 0) running clockwise from the origin to
/// angle 120 degrees, then a line from its end: a corner of about 31 degrees.
fn arc_and_line() -> (Value, Value) {
    let end = [4.5, 1.5 * 3f64.sqrt()];
    (
        json!({"arc": {
            "centre": [3.0, 0.0], "radius": 3.0,
            "x_axis": [-1.0, 0.0], "y_axis": [0.0, 1.0],
            "start_angle": 0.0, "end_angle": 2.0 * PI / 3.0
        }}),
        json!([end, [6.5, -1.5]]),
    )
}

#[test]
fn nurbs_and_arc_forms_are_read_and_printed_back() {
    let (arc, _) = arc_and_line();
    let spline = json!({
        "degree": 3,
        "poles": [[0, 0], [1, 2], [2, -1], [3, 1], [4, 0]],
        "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1],
        "weights": [1, 2, 0.5, 1, 1]
    });
    let result = run_ok("intersect", &json!({"p": arc, "q": spline}));
    // The printed curves are accepted back as they are, and are the same.
    let again = run_ok("intersect", &json!({"p": result["p"], "q": result["q"]}));
    assert_eq!(again["p"], result["p"]);
    assert_eq!(again["q"], result["q"]);
    let p = curve(&result["p"]);
    assert_eq!(p.domain(), (0.0, 2.0 * PI / 3.0));
    assert!(p.is_rational());
    for i in 0..=20 {
        let x = p.eval(p.domain().1 * i as f64 / 20.0);
        assert!(
            ((x[0] - 3.0).hypot(x[1]) - 3.0).abs() < 1e-12,
            "on the circle"
        );
    }
    let q = curve(&result["q"]);
    assert_eq!(
        q.as_nurbs().unwrap().weights().unwrap(),
        [1.0, 2.0, 0.5, 1.0, 1.0]
    );
}

#[test]
fn bad_nurbs_values_exit_2_naming_the_json_path() {
    let line = json!([[0, 0], [1, 1]]);
    let cases = [
        (
            json!({"degree": 2, "poles": [[0, 0], [1, 1], [2, 0]], "knots": [0, 0, 0, 1, 1, 0.5]}),
            "q.knots[5]",
        ),
        (
            json!({"degree": 2, "poles": [[0, 0], [1, 1], [2, 0]], "knots": [0, 0, 0, 1, 1]}),
            "q.knots:",
        ),
        (
            json!({"degree": 1, "poles": [[0, 0], [1, 1]], "knots": [0, 0, 1, 1], "weights": [1, -2]}),
            "q.weights[1]",
        ),
        (
            json!({"degree": 1, "poles": [[0, 0], [1, 1]], "knots": [0, 0, 1, 1], "weights": [1]}),
            "q.weights:",
        ),
        (
            json!({"degree": 1, "poles": [[0, 0], [1, null]], "knots": [0, 0, 1, 1]}),
            "q.poles[1][1]",
        ),
        (
            json!({"arc": {"centre": [0, 0], "radius": 0, "start_angle": 0, "end_angle": 1}}),
            "q.arc.radius",
        ),
        (
            json!({"arc": {"centre": [0, 0], "radius": 1, "start_angle": 0, "end_angle": 7}}),
            "q.arc.end_angle",
        ),
        (
            json!({"arc": {"centre": [0, 0], "radius": 1, "start_angle": 0, "end_angle": 1, "sweep": 2}}),
            "q.arc.sweep",
        ),
    ];
    for (q, path) in cases {
        let (code, stdout, stderr) = run("intersect", &json!({"p": line, "q": q}));
        assert_eq!(code, 2, "{q}: {stderr}");
        assert!(stdout.is_empty());
        assert!(
            stderr.contains(&format!("invalid job: {path}")),
            "{q}: {stderr:?} should name {path}"
        );
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
}

#[test]
fn the_deviation_mode_takes_an_arc_crossing_a_line() {
    let arc = json!({"arc": {"centre": [0.0, 0.0], "radius": 1.0, "start_angle": 0.0,
                             "end_angle": 3.0}});
    let line = json!([[-2.0, 0.5], [2.0, 0.5]]);
    let (code, stdout, stderr) = run(
        "fillet",
        &json!({"p": arc, "q": line, "max_deviation": 0.002, "p_order": 2, "q_order": 2}),
    );
    assert_eq!(code, 0, "{stderr}");
    let out: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let deviation = out["report"]["measured_deviation"].as_f64().unwrap();
    assert!(
        (0.002 * (1.0 - 1e-9)..=0.002).contains(&deviation),
        "{deviation}"
    );
}

#[test]
fn rational_merges_and_misplaced_vertex_fields_are_refused_naming_the_field() {
    let (arc, line) = arc_and_line();
    // Merge takes NURBS curves, but only polynomial ones: an arc is rational.
    let (code, _, stderr) = run("merge", &json!({"p": line, "q": arc}));
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("invalid job: q: the curve is rational"),
        "{stderr}"
    );
    // The vertex mode's own fields.
    let (code, _, stderr) = run(
        "fillet",
        &json!({"p": arc, "q": line, "p_setback": 0.5, "gap": 0.1}),
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("invalid job: gap:"), "{stderr}");
    let (code, _, stderr) = run(
        "fillet",
        &json!({"p": arc, "q": line, "p_setback": 0.5, "vertex": true, "gap": -1}),
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("invalid job: gap:"), "{stderr}");
}

/// A C2 fillet at the vertex of an arc and a line: the trimmed arc is still
/// the exact circle with its own parameters; the setback along it is the
/// radius times the angle it lost; and at both joins the derivatives of
/// orders 0..=2 agree in the chain's parameter (the arc's from the left of
/// its new end, the line's from the right of its new start), so the
/// curvature runs from 1/3 down to 0 without a jump.
#[test]
fn fillet_of_an_arc_and_a_line_is_c2_at_both_joins() {
    let (arc, line) = arc_and_line();
    let (alpha, beta) = (0.4, 0.4);
    let job = json!({
        "p": arc, "q": line, "vertex": true, "p_setback": 0.8,
        "p_order": 2, "q_order": 2, "p_scale": alpha, "q_scale": beta
    });
    let out = run_ok("fillet", &job);
    let p = curve(&out["p_trimmed"]);
    let r = curve(&out["blend"]);
    let q = curve(&out["q_trimmed"]);
    assert!(p.as_nurbs().is_some_and(|n| n.is_rational()));
    assert!(r.as_bezier().is_some() && q.as_bezier().is_some());
    // The arc keeps its parameters: it starts at 0, on the circle.
    let (first, u0) = p.domain();
    assert_eq!(first, 0.0);
    let end = p.eval(u0);
    assert!(((end[0] - 3.0).hypot(end[1]) - 3.0).abs() < 1e-12);
    // Angle lost, seen from the centre, times the radius: the setback.
    let vertex = [4.5, 1.5 * 3f64.sqrt()];
    let angle = |x: &[f64]| (x[1]).atan2(3.0 - x[0]);
    assert!((3.0 * (angle(&vertex) - angle(&end)) - 0.8).abs() < 1e-9);
    // The line keeps [v0, 1], reparametrised to [0, 1] (a Bezier piece).
    let line_length = (2.0f64).hypot(1.5 + 1.5 * 3f64.sqrt());
    let q_start = q.eval(0.0);
    assert!((norm(&[q_start[0] - vertex[0], q_start[1] - vertex[1]]) - 0.8).abs() < 1e-9);
    let v0 = 0.8 / line_length;
    // Rates: the arc piece spans its own parameter; the blend alpha per
    // unit; the line piece (1 - v0) alpha / beta over its [0, 1].
    let jumps_p = join_jumps(end_of(&p, 1.0), start_of(&r, alpha), 2);
    let jumps_q = join_jumps(
        end_of(&r, alpha),
        start_of(&q, (1.0 - v0) * alpha / beta),
        2,
    );
    for (k, j) in jumps_p.iter().chain(&jumps_q).enumerate() {
        assert!(*j < 1e-9, "order {}: relative jump {j}", k % 3);
    }
    // Curvature: the circle's on one side, the line's (0) on the other.
    let k_arc = curvature(&p, u0, KnotSide::Left);
    assert!((k_arc.abs() - 1.0 / 3.0).abs() < 1e-12);
    assert!((curvature(&r, 0.0, KnotSide::Right) - k_arc).abs() < 1e-9);
    assert!(curvature(&r, 1.0, KnotSide::Left).abs() < 1e-9);
    // The whole chain as one B-spline runs from the arc's start to the
    // line's end.
    let spline = curve(&out["bspline"]);
    let (a, b) = spline.domain();
    let s0 = spline.eval(a);
    let s1 = spline.eval(b);
    assert!(norm(&[s0[0], s0[1]]) < 1e-12, "starts at the arc's start");
    let q_end = q.eval(1.0);
    assert!(norm(&[s1[0] - q_end[0], s1[1] - q_end[1]]) < 1e-12);
}

/// `bezjoin fillet-chain` on the demo's wire: the five pieces are re-read
/// and every join is checked to order 3 by derivatives on both sides, the
/// NURBS pieces read from the side of the join at their knots.
#[test]
fn fillet_chain_of_arc_line_and_rational_spline_is_c3_at_every_join() {
    let scenario = bezjoin_cli::ops::scenarios()
        .into_iter()
        .find(|s| s.name == "fillet-chain-arc-line-nurbs")
        .expect("the demo's wire scenario");
    let out = run_ok("fillet-chain", &scenario.job);
    let pieces: Vec<Curve> = out["pieces"]
        .as_array()
        .unwrap()
        .iter()
        .map(curve)
        .collect();
    assert_eq!(pieces.len(), 5);
    assert!(pieces[0].is_rational() && pieces[4].is_rational());
    let corners = out["corners"].as_array().unwrap();
    assert_eq!(corners.len(), 2);
    // Global parameter per unit of each piece's own parameter. The trimmed
    // curves keep or map their parameters: the arc and the B-spline (NURBS)
    // keep theirs, the line (Bezier) spans [v0, u0] of the original over
    // [0, 1]. The rates here restart at 1 for the curve before each corner.
    let line_u0 = corners[1]["u0"].as_f64().unwrap();
    let line_v0 = corners[0]["v0"].as_f64().unwrap();
    for (i, c) in corners.iter().enumerate() {
        let (alpha, beta) = (
            c["p_scale"].as_f64().unwrap(),
            c["q_scale"].as_f64().unwrap(),
        );
        let line_rate = line_u0 - line_v0;
        let (left_rate, right_rate) = if i == 0 {
            (1.0, line_rate * alpha / beta)
        } else {
            (line_rate, alpha / beta)
        };
        let (left, blend, right) = (&pieces[2 * i], &pieces[2 * i + 1], &pieces[2 * i + 2]);
        for (name, jumps) in [
            (
                "before",
                join_jumps(end_of(left, left_rate), start_of(blend, alpha), 3),
            ),
            (
                "after",
                join_jumps(end_of(blend, alpha), start_of(right, right_rate), 3),
            ),
        ] {
            for (k, j) in jumps.iter().enumerate() {
                assert!(*j < 1e-9, "corner {i}, join {name}, order {k}: {j}");
            }
        }
        // No loop or kink: the blend turns one way only (same sign of the
        // curvature along it as at the joins, within rounding).
        let signs: Vec<f64> = (0..=50)
            .map(|s| curvature(blend, s as f64 / 50.0, KnotSide::Right))
            .filter(|k| k.abs() > 1e-9)
            .collect();
        assert!(
            signs.iter().all(|k| k.signum() == signs[0].signum()),
            "corner {i}: the blend has an inflection"
        );
    }
}

fn example(name: &str) -> Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `examples/connect-nurbs.json`: R joins a circular arc (built here with
/// the library's `ellipse_arc`, not read by the tool) at `u0 = 4` to a
/// rational cubic B-spline (built here from the job's poles, weights and
/// knots) at `v0 = 2`, which is the B-spline's interior knot: its third
/// derivative jumps there, and R is C3 with the side Q leaves to (the
/// right), not with the other.
#[test]
fn connect_joins_an_arc_to_a_rational_spline_at_its_knot_from_the_right() {
    let job = example("connect-nurbs.json");
    let out = run_ok("connect", &job);
    let arc = &job["p"]["arc"];
    let p = Curve::Nurbs(
        bezjoin_core::ellipse_arc(
            2,
            &numbers(&arc["centre"]),
            &[1.0, 0.0],
            &[0.0, 1.0],
            arc["radius"].as_f64().unwrap(),
            arc["radius"].as_f64().unwrap(),
            arc["start_angle"].as_f64().unwrap(),
            arc["end_angle"].as_f64().unwrap(),
        )
        .unwrap(),
    );
    let q = Curve::Nurbs(
        NurbsCurve::new(
            2,
            3,
            rows(&job["q"]["poles"]),
            Some(numbers(&job["q"]["weights"])),
            numbers(&job["q"]["knots"]),
        )
        .unwrap(),
    );
    let r = curve(&out["curve"]);
    let (u0, v0) = (job["u0"].as_f64().unwrap(), job["v0"].as_f64().unwrap());
    assert!(job["q"]["knots"][4].as_f64() == Some(v0), "v0 is a knot");
    // The scales the library chose (auto_scale) define R's parameter.
    let alpha = out["report"]["p_scale"].as_f64().unwrap();
    let beta = out["report"]["q_scale"].as_f64().unwrap();
    let at = |curve, u, side, rate| At {
        curve,
        u,
        side,
        rate,
    };
    let first = join_jumps(at(&p, u0, KnotSide::Left, 1.0), start_of(&r, alpha), 3);
    let second = join_jumps(
        end_of(&r, alpha),
        at(&q, v0, KnotSide::Right, alpha / beta),
        3,
    );
    for (k, j) in first.iter().chain(&second).enumerate() {
        assert!(*j < 1e-9, "order {}: relative jump {j}", k % 4);
    }
    // From the left of the knot, Q's third derivative is another one.
    let wrong_side = join_jumps(
        end_of(&r, alpha),
        at(&q, v0, KnotSide::Left, alpha / beta),
        3,
    );
    assert!(wrong_side[3] > 1e-3, "{wrong_side:?}");
}

/// The example chain job is the demo's wire scenario.
#[test]
fn fillet_chain_example_is_the_demo_scenario() {
    let scenario = bezjoin_cli::ops::scenarios()
        .into_iter()
        .find(|s| s.name == "fillet-chain-arc-line-nurbs")
        .unwrap();
    assert_eq!(example("fillet-chain.json"), scenario.job);
}
