//! `bezjoin connect` with `"continuity": "geometric"`: the connecting curve
//! meets P and Q with geometric continuity G^k
//! ([`bezjoin_core::connect_geometric`]; docs/mathematics.md, geometric
//! continuity): `R^(j)(0) = sum_i P^(i)(u0) B_(j,i)(beta_1, ...)` at P and
//! the same with Q's shape values at Q (the beta-constraints), the shape
//! values given by the job or chosen fair (minimum of
//! `L^3 int (dkappa/ds)^2 ds`).
//!
//! The tool re-measures what it prints: G^k at both joins from the
//! derivatives with respect to arc length (unit tangent, curvature vector,
//! ...; [`JoinCheck::geometric`]), and the beta-constraints themselves by
//! composing P's Taylor series with the reparametrisation
//! `phi(t) = u0 + sum beta_j t^j / j!` ([`reparametrised_derivatives`],
//! independent of the library's Bell polynomials).

use bezjoin_core::{BezierCurve, Curve, CurveRef, GeometricConnection, KnotSide};
use serde_json::{Value, json};

use crate::check::{JoinCheck, Side, curve_json, derivatives, reference_sizes, worst};
use crate::curvature::{CurvatureProfile, PathPiece};
use crate::ops::connect::{ConnectJob, Continuity, draw_inputs_and_result, measure_constraints};
use crate::series::reparametrised_derivatives;
use crate::svg::{Figure, Role, Shape};
use crate::{Outcome, Summary};

/// G^kp at `P(u0)|R(0)` and G^kq at `R(1)|Q(v0)`, measured from the
/// arc-length derivatives of the curves (P from the left of `u0`, Q from
/// the right of `v0`).
pub fn measure_joins(
    p: &Curve,
    u0: f64,
    r: &BezierCurve,
    q: &Curve,
    v0: f64,
    (kp, kq): (usize, usize),
) -> [JoinCheck; 2] {
    let (p, q, r) = (CurveRef::from(p), CurveRef::from(q), CurveRef::from(r));
    [
        JoinCheck::geometric("P|R", (p, u0), (r, 0.0), &[p, r], kp),
        JoinCheck::geometric("R|Q", (r, 1.0), (q, v0), &[r, q], kq),
    ]
}

/// The beta-constraints re-measured: the relative residuals of
/// `R^(j)(0)` against the derivatives of `P(phi_p(t))` and of `R^(j)(1)`
/// against those of `Q(phi_q(t))`, `j = 0..=k`, each relative to the
/// larger side and the largest sampled `|R^(j)|`.
pub fn measure_beta_constraints(
    p: &Curve,
    u0: f64,
    r: &BezierCurve,
    q: &Curve,
    v0: f64,
    (p_shape, q_shape): (&[f64], &[f64]),
) -> [JoinCheck; 2] {
    let dim = r.dim();
    let check = |name: &str, curve: &Curve, at: f64, side: KnotSide, t: f64, shape: &[f64]| {
        let k = shape.len();
        let target =
            reparametrised_derivatives(&derivatives(curve.into(), at, k, side), dim, shape);
        let own = r.eval_derivatives(t, k);
        let (first, second) = if t == 0.0 {
            (&target, &own)
        } else {
            (&own, &target)
        };
        JoinCheck::from_derivatives(
            name,
            dim,
            Side {
                derivatives: first,
                rate: 1.0,
            },
            Side {
                derivatives: second,
                rate: 1.0,
            },
            &reference_sizes(&[(r.into(), 1.0)], k),
            k,
        )
    };
    [
        check("P(phi_p)|R(0)", p, u0, KnotSide::Left, 0.0, p_shape),
        check("R(1)|Q(phi_q)", q, v0, KnotSide::Right, 1.0, q_shape),
    ]
}

/// Polygon length of `r` at 2001 points (for the report: the blend's
/// size at a glance).
pub fn sampled_length(r: &BezierCurve) -> f64 {
    let n = 2000;
    let points: Vec<Vec<f64>> = (0..=n).map(|i| r.eval(i as f64 / n as f64)).collect();
    points
        .windows(2)
        .map(|w| crate::check::distance(&w[0], &w[1]))
        .sum()
}

/// The part of `curve` of arc length `length` ending at `at` (`backwards`)
/// or starting there, shortened to the curve's end; `None` when empty.
pub fn local_part(curve: &Curve, at: f64, length: f64, backwards: bool) -> Option<Curve> {
    let c = CurveRef::from(curve);
    let (first, last) = c.domain();
    let accuracy = c.default_length_accuracy();
    let signed = if backwards { -length } else { length };
    let other = c
        .param_at_length(at, signed, accuracy)
        .unwrap_or(if backwards { first } else { last });
    let (a, b) = if backwards { (other, at) } else { (at, other) };
    if b > a { c.segment(a, b).ok() } else { None }
}

/// `kappa(s)` through the end of P, R and the start of Q (each kept part
/// as long as R, at most).
pub fn curvature_profile(job: &ConnectJob, r: &BezierCurve) -> CurvatureProfile {
    let length = sampled_length(r);
    let mut pieces = Vec::new();
    if let Some(part) = local_part(&job.p, job.u0, length, true) {
        pieces.push(PathPiece::new(Shape::curve(&part), Role::Input, "P"));
    }
    pieces.push(PathPiece::new(Shape::Bezier(r.clone()), Role::Result, "R"));
    if let Some(part) = local_part(&job.q, job.v0, length, false) {
        pieces.push(PathPiece::new(Shape::curve(&part), Role::Input, "Q"));
    }
    CurvatureProfile::new(&pieces)
}

/// The result of a geometric connect job.
pub fn outcome(job: &ConnectJob, g: &GeometricConnection) -> Outcome {
    let r = &g.curve;
    let (kp, kq) = (job.options.p_order, job.options.q_order);
    let (p_given, q_given) = match &job.continuity {
        Continuity::Geometric { p_shape, q_shape } => (p_shape.is_some(), q_shape.is_some()),
        Continuity::Parametric => (true, true),
    };
    let chosen = |given: bool| if given { "given" } else { "fair" };
    let checks = measure_joins(&job.p, job.u0, r, &job.q, job.v0, (kp, kq));
    let betas =
        measure_beta_constraints(&job.p, job.u0, r, &job.q, job.v0, (&g.p_shape, &g.q_shape));
    let (constraint_reports, max_point_distance) = measure_constraints(job, r);
    let length = sampled_length(r);
    let fairness = &g.report;
    let beta_json = |c: &JoinCheck| -> Value {
        json!({
            "end": c.name,
            "relative_residuals": c.relative_jumps,
            "worst": c.worst_promised(),
        })
    };
    let json = json!({
        "operation": "connect",
        "curve": curve_json(r),
        "report": {
            "continuity": "geometric",
            "degree": r.degree(),
            "p_order": kp,
            "q_order": kq,
            "p_shape": g.p_shape,
            "q_shape": g.q_shape,
            "p_shape_chosen": chosen(p_given),
            "q_shape_chosen": chosen(q_given),
            "fairness": {
                "energy": fairness.energy,
                "curvature_min": fairness.curvature_min,
                "curvature_max": fairness.curvature_max,
                "curvature_extrema": fairness.curvature_extrema,
            },
            "measured_length": length,
            "max_residual": g.max_residual,
            "error_estimate": g.error_estimate,
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
            "measured_beta_constraints": betas.iter().map(beta_json).collect::<Vec<_>>(),
            "constraints": constraint_reports,
        }
    });

    let mut figure = Figure::new("Connecting curve, geometric continuity");
    draw_inputs_and_result(
        &mut figure,
        job,
        r,
        format!("R, degree {} (G{kp} | G{kq})", r.degree()),
    );
    let sum_k: usize = job
        .options
        .constraints
        .iter()
        .map(|c| c.max_order + 1)
        .sum();
    figure.line(format!(
        "R: degree {} = kp + kq + 1 + sum(K+1) = {kp} + {kq} + 1 + {sum_k}; G{kp} at P(u0), G{kq} at Q(v0) by beta-constraints",
        r.degree(),
    ));
    figure.line(format!(
        "Shape values: at P beta = {} ({}), at Q beta = {} ({})",
        list(&g.p_shape),
        chosen(p_given),
        list(&g.q_shape),
        chosen(q_given)
    ));
    figure.line(format!(
        "Fairness: L^3 int (dkappa/ds)^2 ds = {:.4}; curvature {:.4} .. {:.4}, {} interior extrema; length {:.4}",
        fairness.energy,
        fairness.curvature_min,
        fairness.curvature_max,
        fairness.curvature_extrema,
        length
    ));
    for check in &checks {
        figure.line(check.describe());
    }
    figure.line(format!(
        "Beta-constraints re-measured (P(phi(t)) composed by the tool): worst relative residual {:.1e}; library's estimate {:.1e}",
        worst(&betas),
        g.error_estimate
    ));
    if let Some(d) = max_point_distance {
        figure.line(format!(
            "Largest distance of R(t_j) from a prescribed point: {d:.1e}"
        ));
    }
    if r.dim() == 2 {
        figure.plot(
            curvature_profile(job, r).plot("Curvature along arc length: end of P, R, start of Q"),
        );
    }
    Outcome {
        json,
        figure,
        summary: Summary {
            degree: r.degree(),
            worst_continuity_jump: Some(worst(&checks)),
            max_deviation: max_point_distance,
            deviation_meaning: "prescribed interior points R(t_j)",
        },
    }
}

/// `[a, b, c]` with four decimals.
pub fn list(values: &[f64]) -> String {
    format!(
        "[{}]",
        values
            .iter()
            .map(|v| format!("{v:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    )
}
