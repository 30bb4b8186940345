//! `bezjoin connect`: the connecting curve of mathematics.md section 1.
//!
//! P and Q may be Bezier or NURBS curves (mathematics.md section 6): `u0`
//! and `v0` lie in each curve's domain, P's derivatives at `u0` are taken
//! from the left of a knot and Q's at `v0` from the right; the connecting
//! curve R is a Bezier curve.

use bezjoin_core::{
    BezierCurve, BezjoinError, ConnectOptions, Connection, Curve, GeometricOptions, KnotSide,
    PointConstraint, ShapeScale, connect, connect_geometric, relative_jump,
};
use serde_json::json;

use crate::check::{
    JoinCheck, Side, curve_json, derivatives, distance, reference_sizes, row, worst,
};
use crate::job::{JobError, Located};
use crate::ops::{OperationKind, Scenario, connect_geometric, draw_part};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// Which continuity the joins have.
#[derive(Debug, Clone, PartialEq)]
pub enum Continuity {
    /// C^k with the scales of `options` (mathematics.md section 1).
    Parametric,
    /// G^k by beta-constraints ([`bezjoin_core::connect_geometric`]): the
    /// shape values `beta_1..beta_k` per end, `None` to choose them fair.
    Geometric {
        /// At P (`p_order` values).
        p_shape: Option<Vec<f64>>,
        /// At Q (`q_order` values).
        q_shape: Option<Vec<f64>>,
    },
}

/// A parsed connect job.
pub struct ConnectJob {
    /// Curve P, left of the connection (Bezier or NURBS).
    pub p: Curve,
    /// Parameter on P where R starts (in P's domain).
    pub u0: f64,
    /// Curve Q, right of the connection (Bezier or NURBS).
    pub q: Curve,
    /// Parameter on Q where R ends (in Q's domain).
    pub v0: f64,
    /// Orders, scales and interior constraints (the scales are not used
    /// with geometric continuity, which leaves them given). The library
    /// chooses the scale (`ShapeScale::Auto` or `ShapeScale::Balanced`) when
    /// the job asks for it or gives no scale.
    pub options: ConnectOptions,
    /// Parametric or geometric continuity, with the shape values.
    pub continuity: Continuity,
    /// Indices of the constraints whose `"derivatives"` list is empty: the
    /// library needs at least the position, and the tool names the job's
    /// field when it refuses them ([`run`]).
    pub empty_constraints: Vec<usize>,
}

/// Default continuity order at each end with `"continuity": "geometric"`.
pub const DEFAULT_GEOMETRIC_ORDER: usize = 2;

/// How the scales of a job are chosen: `auto_scale` (`true`: automatic, one
/// `s` at both ends, [`ShapeScale::Auto`]; `"balanced"`, where `balanced`
/// allows it: both ends of the blend at one speed, [`ShapeScale::Balanced`];
/// `false`: the given scales, 1 where missing) or, without it, the given
/// scales, the missing one equal to the given one, and automatic when
/// neither is given: balanced where `balanced` allows it, else one `s`
/// (scale 1 makes a blend between long or fast curves loop, and one `s`
/// leaves a near-kink at the slower end of a fast and a slow curve: a
/// corner of lines 1000 and 10 long got curvature 12,944 where 10 and 10
/// get 1.33, user testing, session 44; shared with `bezjoin fillet` and
/// `bezjoin fillet-chain`).
pub(crate) fn read_scale_choice(
    p_scale: Option<Located>,
    q_scale: Option<Located>,
    auto_scale: Option<Located>,
    balanced: bool,
) -> Result<ShapeScale, JobError> {
    let mut auto = None;
    let mut chosen = ShapeScale::Auto;
    if let Some(f) = &auto_scale {
        if balanced && f.value.as_str() == Some("balanced") {
            auto = Some(true);
            chosen = ShapeScale::Balanced;
        } else if f.value.is_boolean() || !balanced {
            auto = Some(f.boolean()?);
        } else {
            return Err(f.error(format!(
                "expected true, false or \"balanced\", found {}",
                crate::job::describe(f.value)
            )));
        }
    }
    if auto == Some(true) {
        if let Some(f) = p_scale.as_ref().or(q_scale.as_ref()) {
            return Err(JobError::new(
                f.path.clone(),
                "cannot be given together with an automatic \"auto_scale\"",
            ));
        }
        return Ok(chosen);
    }
    let p = p_scale.map(|f| f.positive()).transpose()?;
    let q = q_scale.map(|f| f.positive()).transpose()?;
    let given = |p, q| ShapeScale::Given { p, q };
    Ok(match (p, q, auto) {
        (Some(a), Some(b), _) => given(a, b),
        (None, None, Some(false)) => given(1.0, 1.0),
        (Some(a), None, Some(false)) => given(a, 1.0),
        (None, Some(b), Some(false)) => given(1.0, b),
        (Some(a), None, _) => given(a, a),
        (None, Some(b), _) => given(b, b),
        (None, None, _) if balanced => ShapeScale::Balanced,
        (None, None, _) => ShapeScale::Auto,
    })
}

/// Read a connect job.
pub fn parse(job: &Located) -> Result<ConnectJob, JobError> {
    let obj = job.object()?;
    let p = obj.required("p")?.curve()?;
    let q = obj.required("q")?.curve()?;
    let u0 = obj
        .optional("u0")
        .map(|f| f.number())
        .transpose()?
        .unwrap_or(p.domain().1);
    let v0 = obj
        .optional("v0")
        .map(|f| f.number())
        .transpose()?
        .unwrap_or(q.domain().0);
    let geometric = match obj.optional("continuity") {
        Some(f) => f.choice(&["parametric", "geometric"])? == "geometric",
        None => false,
    };
    let (p_default, q_default) = if geometric {
        (DEFAULT_GEOMETRIC_ORDER, DEFAULT_GEOMETRIC_ORDER)
    } else {
        (p.degree(), q.degree())
    };
    let p_order = obj
        .optional("p_order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(p_default);
    let q_order = obj
        .optional("q_order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(q_default);
    let mut options = ConnectOptions::new(p_order, q_order);
    let p_scale = obj.optional("p_scale");
    let q_scale = obj.optional("q_scale");
    let auto_scale_field = obj.optional("auto_scale");
    let p_shape = obj.optional("p_shape");
    let q_shape = obj.optional("q_shape");
    let continuity = if geometric {
        if let Some(f) = p_scale
            .iter()
            .chain(&q_scale)
            .chain(&auto_scale_field)
            .next()
        {
            return Err(JobError::new(
                f.path.clone(),
                "is not used with \"continuity\": \"geometric\" (give the shape values \
                 \"p_shape\", \"q_shape\" instead, or leave them out to choose them fair)",
            ));
        }
        Continuity::Geometric {
            p_shape: p_shape.map(|f| f.numbers()).transpose()?,
            q_shape: q_shape.map(|f| f.numbers()).transpose()?,
        }
    } else {
        if let Some(f) = p_shape.iter().chain(&q_shape).next() {
            return Err(JobError::new(
                f.path.clone(),
                "is only used with \"continuity\": \"geometric\"",
            ));
        }
        options.scale = read_scale_choice(p_scale, q_scale, auto_scale_field, true)?;
        Continuity::Parametric
    };
    let mut empty_constraints = Vec::new();
    if let Some(list) = obj.optional("constraints") {
        for (j, item) in list.array()?.iter().enumerate() {
            let c = item.object()?;
            let t = c.required("t")?.number()?;
            let derivatives = c.required("derivatives")?.points(Some(p.dim()))?;
            c.finish()?;
            if derivatives.is_empty() {
                empty_constraints.push(j);
            }
            // The job's rows, flattened row-major; an empty list becomes a
            // position-only constraint without values, which the library
            // refuses at the same point of its checks as before ([`run`]).
            let max_order = derivatives.len().saturating_sub(1);
            options
                .constraints
                .push(PointConstraint::new(t, max_order, derivatives.concat()));
        }
    }
    obj.finish()?;
    Ok(ConnectJob {
        p,
        u0,
        q,
        v0,
        options,
        continuity,
        empty_constraints,
    })
}

/// Run a connect job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    if let Continuity::Geometric { p_shape, q_shape } = &job.continuity {
        let mut options = GeometricOptions::new(job.options.p_order, job.options.q_order);
        options.p_shape = p_shape.clone();
        options.q_shape = q_shape.clone();
        options.constraints = job.options.constraints.clone();
        let g = connect_geometric(&job.p, job.u0, &job.q, job.v0, &options)
            .map_err(|e| empty_constraint_error(&job, e))?;
        return Ok(connect_geometric::outcome(&job, &g));
    }
    let connection = connect(&job.p, job.u0, &job.q, job.v0, &job.options)
        .map_err(|e| empty_constraint_error(&job, e))?;
    Ok(outcome(&job, &connection))
}

/// The library's refusal of a constraint without values (an empty
/// `"derivatives"` list, [`ConnectJob::empty_constraints`]) as the job's
/// own field: `constraints[j].derivatives: is empty; ...`. Every other
/// error is passed on unchanged.
fn empty_constraint_error(job: &ConnectJob, e: BezjoinError) -> BezjoinError {
    if let BezjoinError::LengthMismatch { name, .. } = &e {
        let refused = job
            .empty_constraints
            .iter()
            .find(|j| *name == format!("constraints[{j}].values"));
        if let Some(j) = refused {
            return BezjoinError::invalid(
                format!("constraints[{j}].derivatives"),
                "is empty; at least the position (order 0) is needed",
            );
        }
    }
    e
}

/// The joins of P, R and Q measured by the tool: `R^(k)(0) / alpha^k`
/// against `P^(k)(u0)` (from the left of a knot), and `R^(k)(1) / alpha^k`
/// against `(beta/alpha)^k Q^(k)(v0)` (from the right), the chain's knot
/// intervals `(u0 - first, alpha, (last - v0) alpha/beta)` in the original
/// parameters; orders `0..=max(promised, min(degrees))`.
pub fn measure_joins(
    p: &Curve,
    u0: f64,
    r: &BezierCurve,
    q: &Curve,
    v0: f64,
    (p_scale, q_scale): (f64, f64),
    (p_order, q_order): (usize, usize),
) -> [JoinCheck; 2] {
    let dim = r.dim();
    let left_orders = p_order.max(p.degree().min(r.degree()));
    let right_orders = q_order.max(q.degree().min(r.degree()));
    let left = derivatives(p.into(), u0, left_orders, KnotSide::Left);
    let start = r.eval_derivatives(0.0, left_orders);
    let end = r.eval_derivatives(1.0, right_orders);
    let right = derivatives(q.into(), v0, right_orders, KnotSide::Right);
    let ratio = p_scale / q_scale;
    [
        JoinCheck::from_derivatives(
            "P|R",
            dim,
            Side {
                derivatives: &left,
                rate: 1.0,
            },
            Side {
                derivatives: &start,
                rate: p_scale,
            },
            &reference_sizes(&[(p.into(), 1.0), (r.into(), p_scale)], left_orders),
            p_order,
        ),
        JoinCheck::from_derivatives(
            "R|Q",
            dim,
            Side {
                derivatives: &end,
                rate: p_scale,
            },
            Side {
                derivatives: &right,
                rate: ratio,
            },
            &reference_sizes(&[(r.into(), p_scale), (q.into(), ratio)], right_orders),
            q_order,
        ),
    ]
}

fn outcome(job: &ConnectJob, c: &Connection) -> Outcome {
    let r = &c.curve;
    let checks = measure_joins(
        &job.p,
        job.u0,
        r,
        &job.q,
        job.v0,
        (c.p_scale, c.q_scale),
        (job.options.p_order, job.options.q_order),
    );
    let (constraint_reports, max_point_distance) = measure_constraints(job, r);
    let json = json!({
        "operation": "connect",
        "curve": curve_json(r),
        "report": {
            "continuity": "parametric",
            "degree": r.degree(),
            "auto_scale": !matches!(job.options.scale, ShapeScale::Given { .. }),
            "balanced_scale": job.options.scale == ShapeScale::Balanced,
            "p_scale": c.p_scale,
            "q_scale": c.q_scale,
            "max_residual": c.max_residual,
            "chain_knot_intervals": [
                job.u0 - job.p.domain().0,
                c.p_scale,
                (job.q.domain().1 - job.v0) * c.p_scale / c.q_scale
            ],
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
            "constraints": constraint_reports,
        }
    });

    let mut figure = Figure::new("Connecting curve");
    draw_inputs_and_result(&mut figure, job, r, format!("R, degree {}", r.degree()));
    let sum_k: usize = job
        .options
        .constraints
        .iter()
        .map(|c| c.max_order + 1)
        .sum();
    figure.line(format!(
        "R: degree {} = kp + kq + 1 + sum(K+1) = {} + {} + 1 + {}; scales alpha = {:.4}, beta = {:.4}{}",
        r.degree(),
        job.options.p_order,
        job.options.q_order,
        sum_k,
        c.p_scale,
        c.q_scale,
        match job.options.scale {
            ShapeScale::Balanced => " (automatic, balanced: one speed at both ends)",
            ShapeScale::Auto => " (automatic)",
            ShapeScale::Given { .. } => "",
        }
    ));
    for check in &checks {
        figure.line(check.describe());
    }
    figure.line(format!(
        "Library's own largest relative residual: {:.1e}",
        c.max_residual
    ));
    if let Some(d) = max_point_distance {
        figure.line(format!(
            "Largest distance of R(t_j) from a prescribed point: {d:.1e}"
        ));
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

/// The interior constraints re-measured on `r`: per constraint its index,
/// `t`, the relative residual of every prescribed order and the distance of
/// `R(t)` from the prescribed point; and the largest such distance.
pub(crate) fn measure_constraints(
    job: &ConnectJob,
    r: &BezierCurve,
) -> (Vec<serde_json::Value>, Option<f64>) {
    let dim = r.dim();
    let mut reports = Vec::new();
    let mut max_point_distance: Option<f64> = None;
    for (j, con) in job.options.constraints.iter().enumerate() {
        let d = r.eval_derivatives(con.t, con.max_order);
        let jumps: Vec<f64> = (0..=con.max_order)
            .map(|k| relative_jump(row(&d, dim, k), row(&con.values, dim, k)))
            .collect();
        let at = r.eval(con.t);
        let distance = distance(&at, row(&con.values, dim, 0));
        max_point_distance = Some(max_point_distance.unwrap_or(0.0).max(distance));
        reports.push(json!({
            "index": j,
            "t": con.t,
            "relative_residuals": jumps,
            "point_distance": distance,
        }));
    }
    (reports, max_point_distance)
}

/// P and Q (the parts used over the whole given curves), R, its end points
/// and the prescribed points of the constraints.
pub(crate) fn draw_inputs_and_result(
    figure: &mut Figure,
    job: &ConnectJob,
    r: &BezierCurve,
    r_label: String,
) {
    let dim = r.dim();
    draw_part(figure, &job.p, job.p.domain().0, job.u0, Role::Input, "P");
    draw_part(figure, &job.q, job.v0, job.q.domain().1, Role::Input, "Q");
    figure.curve(CurveItem::bezier(r, Role::Result, r_label));
    figure.marker(Marker::new(MarkerKind::Join, &r.eval(0.0), "R(0)"));
    figure.marker(Marker::new(MarkerKind::Join, &r.eval(1.0), "R(1)"));
    for con in &job.options.constraints {
        figure.marker(Marker::new(
            MarkerKind::Constraint,
            row(&con.values, dim, 0),
            format!("R({}) prescribed, orders 0..{}", con.t, con.max_order),
        ));
    }
}

/// Cubic P of the demo: ends at (6, 10) heading up and to the right.
fn demo_p() -> serde_json::Value {
    json!([[0.0, 3.0], [2.0, 6.5], [4.0, 9.0], [6.0, 10.0]])
}

/// Cubic Q of the demo: starts at (18, 10) heading down and to the right.
fn demo_q() -> serde_json::Value {
    json!([[18.0, 10.0], [20.0, 9.0], [22.0, 6.5], [24.0, 3.0]])
}

/// The demo's connect scenarios (mathematics.md section 1): the papers'
/// connection of two cubics without interior constraints, the same
/// connection through the prescribed point R(0.5) = (12, 14) with
/// R'(0.5) = (8.1, 1.4) and R''(0.5) = (-5, -39), and the unconstrained
/// connection with the scale chosen automatically.
pub fn demo_scenarios() -> Vec<Scenario> {
    vec![
        Scenario {
            name: "connect-plain",
            operation: OperationKind::Connect,
            title: "Connection of two cubics, C2 at both joins",
            description: "R joins the end of P to the start of Q with continuity of orders \
                          0..2 on both sides at scales alpha = beta = 1; no interior \
                          constraints, so R has degree kp + kq + 1 = 5.",
            job: json!({
                "p": demo_p(),
                "q": demo_q(),
                "u0": 1.0,
                "v0": 0.0,
                "p_order": 2,
                "q_order": 2,
                "p_scale": 1.0,
                "q_scale": 1.0,
            }),
        },
        Scenario {
            name: "connect-constrained",
            operation: OperationKind::Connect,
            title: "Connection through a prescribed point with derivatives",
            description: "The papers' interior constraint: R(0.5) = (12, 14), \
                          R'(0.5) = (8.1, 1.4), R''(0.5) = (-5, -39), with C2 joins to P \
                          and Q; R has degree kp + kq + 1 + (K + 1) = 2 + 2 + 1 + 3 = 8.",
            job: json!({
                "p": demo_p(),
                "q": demo_q(),
                "u0": 1.0,
                "v0": 0.0,
                "p_order": 2,
                "q_order": 2,
                "p_scale": 1.0,
                "q_scale": 1.0,
                "constraints": [
                    { "t": 0.5, "derivatives": [[12.0, 14.0], [8.1, 1.4], [-5.0, -39.0]] }
                ],
            }),
        },
        Scenario {
            name: "connect-auto-scale",
            operation: OperationKind::Connect,
            title: "Connection with the scale chosen automatically",
            description: "The same cubics, joined at interior parameters u0 = 0.9 and \
                          v0 = 0.1 with C2 joins; the scales alpha and beta are chosen \
                          by connect_auto_scale instead of being given.",
            job: json!({
                "p": demo_p(),
                "q": demo_q(),
                "u0": 0.9,
                "v0": 0.1,
                "p_order": 2,
                "q_order": 2,
                "auto_scale": true,
            }),
        },
    ]
}
