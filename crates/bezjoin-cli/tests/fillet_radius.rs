//! `bezjoin fillet` with `"radius"` run as a process: the cuts lie where
//! the arc of radius r touches (at r tan(theta/2) from the corner of two
//! lines), the returned pieces meet with G2 (G3 with `"order": 3`) judged
//! from the unit tangent, the curvature vector and its arc-length
//! derivative computed here from the printed control points with
//! bezjoin_core's evaluation, the comparison and the picture are there,
//! and bad jobs exit 2 naming the field.

mod common;
use common::{assert_geometric_join, assert_well_formed_xml, dist, dot, frenet, norm};

use std::path::PathBuf;

use bezjoin_core::BezierCurve;
use serde_json::{Value, json};

fn run(job: &Value, svg: Option<&std::path::Path>) -> (i32, String, String) {
    common::run_job("fillet", job, svg)
}

fn success(job: &Value) -> Value {
    common::job_result("fillet", job)
}

fn bezier(value: &Value) -> BezierCurve {
    common::bezier_of(value)
}

fn repo_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(name)
}

/// The joins of a printed radius fillet are G^order: the same `T`, `K`
/// (and `K_s` for order 3) on both sides of both joins, relative to the
/// blend's largest curvature (and its derivative).
fn assert_geometric_joins(out: &Value, order: usize) {
    let (p, r, q) = (
        bezier(&out["p_trimmed"]),
        bezier(&out["blend"]),
        bezier(&out["q_trimmed"]),
    );
    assert_eq!(r.degree(), 2 * order + 1);
    for (name, a, b) in [("P|R", &p, &r), ("R|Q", &r, &q)] {
        assert_geometric_join(name, a, b, &r, order);
    }
    for join in out["report"]["measured_continuity"].as_array().unwrap() {
        assert_eq!(join["continuity"], "geometric");
        assert_eq!(join["promised_order"].as_u64(), Some(order as u64));
        assert!(
            join["measured_order"].as_u64().unwrap() >= order as u64,
            "{join}"
        );
    }
}

/// Two lines meeting at `corner` with the turning angle `theta` (P along
/// +x with length `a`, Q turned by `theta` with length `b`), and a radius
/// `r`: the cuts are at `r tan(theta/2)` from the corner, the arc's centre
/// at `r` from both cuts, and the blend is G^order.
fn check_lines(a: f64, b: f64, theta: f64, r: f64, order: usize) -> Value {
    let (c, s) = (theta.cos(), theta.sin());
    let job = json!({
        "p": [[-a, 0.0], [0.0, 0.0]],
        "q": [[0.0, 0.0], [b * c, b * s]],
        "radius": r,
        "order": order
    });
    let out = success(&job);
    let setback = r * (theta / 2.0).tan();
    let pt = bezier(&out["p_trimmed"]);
    let qt = bezier(&out["q_trimmed"]);
    let cut_p = pt.eval(1.0);
    let cut_q = qt.eval(0.0);
    assert!(
        (dist(&cut_p, &[0.0, 0.0]) - setback).abs() < 1e-9 * setback,
        "P cut at {cut_p:?}, expected {setback} from the corner"
    );
    assert!(
        (dist(&cut_q, &[0.0, 0.0]) - setback).abs() < 1e-9 * setback,
        "Q cut at {cut_q:?}, expected {setback} from the corner"
    );
    // The cuts are on the lines, on the right sides of the corner.
    assert!(cut_p[1].abs() < 1e-12 && cut_p[0] < 0.0);
    assert!((cut_q[0] * s - cut_q[1] * c).abs() < 1e-12 && dot(&cut_q, &[c, s]) > 0.0);
    let report = &out["report"];
    assert_eq!(report["mode"], "radius");
    assert_eq!(report["corner"], "vertex");
    assert!((report["tangent_length"].as_f64().unwrap() - setback).abs() < 1e-9 * setback);
    assert!((report["turning_angle"].as_f64().unwrap() - theta).abs() < 1e-12);
    let centre: Vec<f64> = serde_json::from_value(report["arc_centre"].clone()).unwrap();
    assert!((dist(&centre, &cut_p) - r).abs() < 1e-9 * r);
    assert!((dist(&centre, &cut_q) - r).abs() < 1e-9 * r);
    assert_geometric_joins(&out, order);
    out
}

#[test]
fn radius_fillet_of_lines_cuts_at_r_tan_half_theta_and_is_g2() {
    // The long-edge corner: edges 40 and 20 at 90 degrees, radius 2.
    let out = check_lines(40.0, 20.0, std::f64::consts::FRAC_PI_2, 2.0, 2);
    // The blend stays in the corner, near the arc (no loop).
    let r = bezier(&out["blend"]);
    let length: f64 = (0..1000)
        .map(|i| dist(&r.eval(i as f64 / 1000.0), &r.eval((i + 1) as f64 / 1000.0)))
        .sum();
    assert!(length < 4.0, "blend length {length}");
    assert!(out["report"]["arc_deviation"].as_f64().unwrap() < 0.5);
    // Other angles and lengths, and G3.
    check_lines(5.0, 7.0, 60f64.to_radians(), 1.0, 2);
    check_lines(5.0, 7.0, 120f64.to_radians(), 0.5, 3);
    check_lines(40.0, 20.0, std::f64::consts::FRAC_PI_2, 2.0, 3);
}

#[test]
fn radius_fillet_of_two_cubics_is_g2_and_g3() {
    let text = std::fs::read_to_string(repo_file("examples/fillet-radius.json")).unwrap();
    let job: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(job["radius"], 0.5, "the example is the curved corner");
    let out = success(&job);
    assert_eq!(out["report"]["corner"], "crossing");
    assert_geometric_joins(&out, 2);
    // The cuts are where the arc touches: the centre is r from both cuts
    // along their normals (the radius vector is normal to the tangent).
    let r = 0.5;
    let centre: Vec<f64> = serde_json::from_value(out["report"]["arc_centre"].clone()).unwrap();
    for (piece, t) in [("p_trimmed", 1.0), ("q_trimmed", 0.0)] {
        let c = bezier(&out[piece]);
        let at = c.eval(t);
        let [tangent, _, _] = frenet(&c, t);
        let radial: Vec<f64> = centre.iter().zip(&at).map(|(a, b)| a - b).collect();
        assert!((norm(&radial) - r).abs() < 1e-9, "{piece}: {radial:?}");
        assert!(dot(&radial, &tangent).abs() < 1e-9, "{piece}: not touching");
    }
    let mut g3 = job.clone();
    g3["order"] = json!(3);
    let out3 = success(&g3);
    assert_geometric_joins(&out3, 3);
    // Same cuts for every order: the arc decides them.
    for key in ["u0", "v0"] {
        assert_eq!(out[key], out3[key], "{key}");
    }
}

#[test]
fn comparison_and_picture() {
    let job = json!({
        "p": [[-40.0, 0.0], [0.0, 0.0]],
        "q": [[0.0, 0.0], [0.0, 20.0]],
        "radius": 2.0,
        "compare": true
    });
    let svg = std::env::temp_dir().join(format!("bezjoin-radius-{}.svg", std::process::id()));
    let (code, stdout, stderr) = run(&job, Some(&svg));
    assert_eq!(code, 0, "{stderr}");
    let out: Value = serde_json::from_str(&stdout).unwrap();
    assert_geometric_joins(&out, 2);
    let variants = out["comparison"].as_array().unwrap();
    assert_eq!(variants.len(), 4);
    // The arc of the comparison is the job's `arc` form: centre (-2, 2), r = 2.
    let arc = &variants[0]["rounding"]["arc"];
    assert_eq!(arc["radius"], 2.0);
    let centre: Vec<f64> = serde_json::from_value(arc["centre"].clone()).unwrap();
    assert!(dist(&centre, &[-2.0, 2.0]) < 1e-12);
    // The C2 fillet of the same setbacks: the same cuts, C2 in its own
    // parameter, so its curvature is continuous too.
    assert_eq!(variants[1]["continuity"], "C2");
    let c2 = bezier(&variants[1]["rounding"]);
    assert!(dist(&c2.eval(0.0), &[-2.0, 0.0]) < 1e-9 && dist(&c2.eval(1.0), &[0.0, 2.0]) < 1e-9);
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_well_formed_xml(&picture);
    for text in [
        "G1 arc",
        "C2, same setbacks",
        "G2 by radius",
        "G3 by radius",
    ] {
        assert!(picture.contains(&format!(">{text}</text>")), "{text}");
    }
    // Without "compare": one blend, the arc as reference, one graph.
    let (code, _, stderr) = run(
        &json!({"p": job["p"], "q": job["q"], "radius": 2.0}),
        Some(&svg),
    );
    assert_eq!(code, 0, "{stderr}");
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_well_formed_xml(&picture);
    assert!(picture.contains("circular arc of radius 2"));
    assert_eq!(picture.matches("<clipPath ").count(), 1);
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
fn bad_radius_jobs_exit_2_naming_the_field() {
    let with = |extra: Value| {
        let mut job = json!({"p": [[-4.0, 0.0], [0.0, 0.0]], "q": [[0.0, 0.0], [0.0, 2.0]]});
        for (k, v) in extra.as_object().unwrap() {
            job[k] = v.clone();
        }
        job
    };
    assert_exit_2_naming(&with(json!({"radius": -1})), "radius: -1 must be > 0");
    assert_exit_2_naming(&with(json!({"radius": 0})), "radius");
    assert_exit_2_naming(&with(json!({"radius": "big"})), "radius: expected a number");
    // The arc of radius 3 would touch Q beyond its end (tangent length 3 > 2).
    assert_exit_2_naming(&with(json!({"radius": 3})), "radius");
    assert_exit_2_naming(&with(json!({"radius": 1, "order": 0})), "order");
    assert_exit_2_naming(&with(json!({"radius": 1, "order": 9})), "order");
    assert_exit_2_naming(&with(json!({"radius": 1, "order": "two"})), "order");
    assert_exit_2_naming(&with(json!({"radius": 1, "compare": 1})), "compare");
    for other in [
        "p_setback",
        "max_deviation",
        "p_order",
        "auto_scale",
        "p_scale",
        "vertex",
    ] {
        assert_exit_2_naming(&with(json!({"radius": 1, other: 1})), other);
    }
    assert_exit_2_naming(&with(json!({"radius": 1, "colour": 1})), "colour");
    // "order" and "compare" belong to the radius mode.
    assert_exit_2_naming(&with(json!({"p_setback": 1, "order": 2})), "order");
    assert_exit_2_naming(&with(json!({"p_setback": 1, "compare": true})), "compare");
    // The comparison is drawn for plane curves.
    let space = json!({
        "p": [[-4.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        "q": [[0.0, 0.0, 0.0], [0.0, 2.0, 0.0]],
        "radius": 1, "compare": true
    });
    assert_exit_2_naming(&space, "compare");
}

/// The test's own Frenet formulas on the parabola `y = x^2`, where
/// `kappa = 2 / w^3` and `dkappa/ds = -24 x / w^6` with `w = sqrt(1 + 4x^2)`,
/// so `K = kappa N` and `K_s = kappa_s N - kappa^2 T`; and the G2 check
/// fails on a blend whose second control point is moved.
#[test]
fn the_checks_are_not_vacuous() {
    let parabola = BezierCurve::from_rows(&[[-1.0, 1.0], [0.0, -1.0], [1.0, 1.0]]).unwrap();
    let t: f64 = 0.75; // x = 2t - 1 = 0.5
    let x = 2.0 * t - 1.0;
    let w = (1.0 + 4.0 * x * x).sqrt();
    let tangent = [1.0 / w, 2.0 * x / w];
    let normal = [-tangent[1], tangent[0]];
    let kappa = 2.0 / w.powi(3);
    let kappa_s = -24.0 * x / w.powi(6);
    let [t1, k, ks] = frenet(&parabola, t);
    assert!(dist(&t1, &tangent) < 1e-14);
    assert!(dist(&k, &[kappa * normal[0], kappa * normal[1]]) < 1e-14);
    let want = [
        kappa_s * normal[0] - kappa * kappa * tangent[0],
        kappa_s * normal[1] - kappa * kappa * tangent[1],
    ];
    assert!(dist(&ks, &want) < 1e-13, "{ks:?} {want:?}");

    let mut out = success(&json!({
        "p": [[-40.0, 0.0], [0.0, 0.0]],
        "q": [[0.0, 0.0], [0.0, 20.0]],
        "radius": 2.0
    }));
    assert_geometric_joins(&out, 2);
    // Moving the third control point off the line bends the blend at P.
    let y = out["blend"]["points"][2][1].as_f64().unwrap();
    out["blend"]["points"][2][1] = json!(y + 1e-4);
    let broken = std::panic::catch_unwind(|| assert_geometric_joins(&out, 2));
    assert!(broken.is_err(), "a curvature jump must fail the G2 check");
}
