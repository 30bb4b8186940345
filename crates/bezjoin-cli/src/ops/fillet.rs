//! `bezjoin fillet`: rounding the corner between two crossing curves
//! (mathematics.md section 2; Krivosheev, Mavrin, Starkova, Omsk Scientific
//! Bulletin, 2025, Fig. 2).
//!
//! The job gives `P`, `Q` (Bezier or NURBS curves, mathematics.md section 6)
//! and either the setbacks `p_setback`, `q_setback` (arc lengths from the
//! crossing; with `"vertex": true` from the vertex where P ends and Q
//! starts, [`bezjoin_core::fillet_vertex`]) or `max_deviation` (the distance
//! from the corner point to the blend, with an optional `setback_ratio = dq
//! / dp`; any curves). The report is re-measured by the tool:
//! continuity at both joins in the B-spline sense (knot intervals `u0 -
//! first`, `alpha`, `(last - v0) alpha / beta`; the `k`-th derivative of
//! each piece is divided by (its interval / its domain length)^k, P's taken
//! from the left of `u0`, Q's from the right of `v0`) and the setbacks as
//! arc lengths of the original curves from the corner.

use bezjoin_core::{
    BezierCurve, Curve, DeviationFilletOptions, Fillet, FilletOptions, KnotSide, ShapeScale,
    fillet, fillet_vertex, fillet_within_deviation,
};
use serde_json::{Value, json};

use crate::arc::circular_fillet;
use crate::check::{JoinCheck, Side, curve_json, derivatives, distance, reference_sizes, worst};
use crate::job::{JobError, Located, ObjectReader};
use crate::ops::connect::read_scale_choice;
use crate::ops::fillet_radius;
use crate::ops::{OperationKind, Scenario, draw_part};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// Default of the job's `gap` (`"vertex": true`): how far apart P's end and
/// Q's start may be, absolute; OpenCASCADE's `Precision::Confusion()`.
pub const DEFAULT_VERTEX_GAP: f64 = 1e-7;

/// Where the corner is and how the setbacks are chosen.
pub enum FilletMode {
    /// Given setbacks `dp`, `dq` from the first crossing of P and Q.
    Setbacks,
    /// Given setbacks from the vertex where P ends and Q starts (within `gap`).
    Vertex {
        /// Largest distance between P's last point and Q's first point.
        gap: f64,
    },
    /// Setbacks found so that the blend passes at `max_deviation` from the
    /// corner point (`setback_ratio = dq / dp`).
    Deviation {
        /// `eps`.
        max_deviation: f64,
        /// `dq / dp`.
        setback_ratio: f64,
    },
    /// The corner sized like the circular arc of `radius`, rounded by a
    /// fair G^`order` blend ([`super::fillet_radius`]).
    Radius {
        /// `r > 0`.
        radius: f64,
        /// `k`: G^k at both cuts.
        order: usize,
        /// Also compute and draw the arc, the C^k fillet of the same
        /// setbacks and the G2 and G3 blends.
        compare: bool,
    },
}

impl FilletMode {
    /// Name in the report.
    fn name(&self) -> &'static str {
        match self {
            FilletMode::Setbacks => "setbacks",
            FilletMode::Vertex { .. } => "vertex",
            FilletMode::Deviation { .. } => "deviation",
            FilletMode::Radius { .. } => "radius",
        }
    }
}

/// A parsed fillet job.
pub struct FilletJob {
    /// Curve P (its part before the corner is kept); Bezier or NURBS.
    pub p: Curve,
    /// Curve Q (its part after the corner is kept); Bezier or NURBS.
    pub q: Curve,
    /// Setbacks (ignored in deviation and radius mode), orders and scales
    /// (ignored in radius mode).
    pub options: FilletOptions,
    /// Setback, vertex or deviation mode.
    pub mode: FilletMode,
}

/// Read `p_scale`, `q_scale` or `auto_scale` into `options` (shared with
/// `bezjoin fillet-chain`): without any of them the scale is chosen
/// automatically (scale 1 makes the blend loop on long or fast curves);
/// one scale given stands for both; `"auto_scale": false` keeps the
/// paper's scale 1 for a missing one; `"auto_scale": "balanced"` where
/// `balanced` allows it ([`read_scale_choice`]).
pub(crate) fn read_scales(
    obj: &ObjectReader,
    mut options: FilletOptions,
    balanced: bool,
) -> Result<FilletOptions, JobError> {
    options.scale = read_scale_choice(
        obj.optional("p_scale"),
        obj.optional("q_scale"),
        obj.optional("auto_scale"),
        balanced,
    )?;
    Ok(options)
}

/// Read a fillet job.
pub fn parse(job: &Located) -> Result<FilletJob, JobError> {
    let obj = job.object()?;
    let p_field = obj.required("p")?;
    let q_field = obj.required("q")?;
    let p = p_field.curve()?;
    let q = q_field.curve()?;
    if let Some(radius) = obj.optional("radius") {
        return parse_radius(&obj, p, q, radius.positive()?);
    }
    fillet_radius::refuse_without_radius(&obj, &["order", "compare"])?;
    let p_order = obj
        .optional("p_order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(p.degree().min(2));
    let q_order = obj
        .optional("q_order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(q.degree().min(2));
    let p_setback = obj.optional("p_setback");
    let q_setback = obj.optional("q_setback");
    let max_deviation = obj.optional("max_deviation");
    let setback_ratio = obj.optional("setback_ratio");
    let vertex_field = obj.optional("vertex");
    let vertex = vertex_field
        .as_ref()
        .map(|f| f.boolean())
        .transpose()?
        .unwrap_or(false);
    let gap = obj.optional("gap");
    if let (Some(f), false) = (&gap, vertex) {
        return Err(JobError::new(
            f.path.clone(),
            "is only used together with \"vertex\": true",
        ));
    }
    let mode = match max_deviation {
        Some(eps) => {
            if let Some(f) = p_setback.as_ref().or(q_setback.as_ref()) {
                return Err(JobError::new(
                    f.path.clone(),
                    "cannot be given together with \"max_deviation\"",
                ));
            }
            if let (Some(f), true) = (&vertex_field, vertex) {
                return Err(JobError::new(
                    f.path.clone(),
                    "cannot be true together with \"max_deviation\" (the deviation mode rounds \
                     the first crossing of the two curves)",
                ));
            }
            FilletMode::Deviation {
                max_deviation: eps.positive()?,
                setback_ratio: setback_ratio
                    .map(|f| f.positive())
                    .transpose()?
                    .unwrap_or(1.0),
            }
        }
        None => {
            if let Some(f) = setback_ratio {
                return Err(JobError::new(
                    f.path.clone(),
                    "is only used together with \"max_deviation\"",
                ));
            }
            if vertex {
                let gap = match gap {
                    Some(f) => {
                        let g = f.number()?;
                        if g < 0.0 {
                            return Err(JobError::new(f.path.clone(), format!("{g} must be >= 0")));
                        }
                        g
                    }
                    None => DEFAULT_VERTEX_GAP,
                };
                FilletMode::Vertex { gap }
            } else {
                FilletMode::Setbacks
            }
        }
    };
    let (dp, dq) = match mode {
        FilletMode::Setbacks | FilletMode::Vertex { .. } => {
            let dp = obj.required("p_setback")?.positive()?;
            let dq = match q_setback {
                Some(f) => f.positive()?,
                None => dp,
            };
            (dp, dq)
        }
        FilletMode::Deviation { .. } | FilletMode::Radius { .. } => (1.0, 1.0),
    };
    // The balanced scale for one corner by setbacks; the deviation mode's
    // automatic scale is one s (a fixed point of its setback search).
    let balanced = matches!(mode, FilletMode::Setbacks | FilletMode::Vertex { .. });
    let options = read_scales(&obj, FilletOptions::new(dp, dq, p_order, q_order), balanced)?;
    obj.finish()?;
    Ok(FilletJob {
        p,
        q,
        options,
        mode,
    })
}

/// The fields of a fillet job by radius (`radius` already read):
/// `order`, `compare`; the fields of the other modes are refused, named.
fn parse_radius(
    obj: &ObjectReader,
    p: Curve,
    q: Curve,
    radius: f64,
) -> Result<FilletJob, JobError> {
    let order = fillet_radius::read_radius_fields(
        obj,
        &[
            "p_setback",
            "q_setback",
            "max_deviation",
            "setback_ratio",
            "vertex",
            "gap",
            "p_order",
            "q_order",
            "p_scale",
            "q_scale",
            "auto_scale",
        ],
        "the corner is the vertex when P ends where Q starts, else the first crossing",
    )?;
    let compare = obj
        .optional("compare")
        .map(|f| f.boolean())
        .transpose()?
        .unwrap_or(false);
    obj.finish()?;
    Ok(FilletJob {
        p,
        q,
        options: FilletOptions::new(1.0, 1.0, order, order),
        mode: FilletMode::Radius {
            radius,
            order,
            compare,
        },
    })
}

/// Run a fillet job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    match job.mode {
        FilletMode::Setbacks => {
            let f = fillet(&job.p, &job.q, &job.options)?;
            Ok(outcome(&job, &f, None))
        }
        FilletMode::Vertex { gap } => {
            let f = fillet_vertex(&job.p, &job.q, &job.options, gap)?;
            Ok(outcome(&job, &f, None))
        }
        FilletMode::Deviation {
            max_deviation,
            setback_ratio,
        } => {
            let (p, q) = (&job.p, &job.q);
            let mut options = DeviationFilletOptions::new(max_deviation, job.options.p_order)
                .with_setback_ratio(setback_ratio);
            options.shape = job.options.clone();
            let d = fillet_within_deviation(p, q, &options)?;
            Ok(outcome(&job, &d.fillet, Some(max_deviation)))
        }
        FilletMode::Radius {
            radius,
            order,
            compare,
        } => fillet_radius::run(&job.p, &job.q, radius, order, compare),
    }
}

/// The joins of the fillet measured by the tool: from the returned pieces
/// (`P|R`, `R|Q`), and from the ORIGINAL curves at `u0` and `v0` (so a
/// wrongly trimmed piece would show).
pub fn measure_joins(
    p: &Curve,
    q: &Curve,
    f: &Fillet,
    (kp, kq): (usize, usize),
) -> ([JoinCheck; 2], [JoinCheck; 2]) {
    let [a, b, c] = f.knot_intervals();
    let checks = [
        JoinCheck::measure("P|R", &f.p_trimmed, a, &f.blend, b, kp),
        JoinCheck::measure("R|Q", &f.blend, b, &f.q_trimmed, c, kq),
    ];
    // P spans its own parameter (rate 1), Q spans alpha/beta per unit.
    let p_orders = kp.max(p.degree().min(f.blend.degree()));
    let q_orders = kq.max(q.degree().min(f.blend.degree()));
    let ratio = f.p_scale / f.q_scale;
    let original = [
        JoinCheck::from_derivatives(
            "P(u0)|R(0)",
            p.dim(),
            Side {
                derivatives: &derivatives(p.into(), f.u0, p_orders, KnotSide::Left),
                rate: 1.0,
            },
            Side {
                derivatives: &f.blend.eval_derivatives(0.0, p_orders),
                rate: b,
            },
            &reference_sizes(&[(p.into(), 1.0), ((&f.blend).into(), b)], p_orders),
            kp,
        ),
        JoinCheck::from_derivatives(
            "R(1)|Q(v0)",
            q.dim(),
            Side {
                derivatives: &f.blend.eval_derivatives(1.0, q_orders),
                rate: b,
            },
            Side {
                derivatives: &derivatives(q.into(), f.v0, q_orders, KnotSide::Right),
                rate: ratio,
            },
            &reference_sizes(&[((&f.blend).into(), b), (q.into(), ratio)], q_orders),
            kq,
        ),
    ];
    (checks, original)
}

fn outcome(job: &FilletJob, f: &Fillet, max_deviation: Option<f64>) -> Outcome {
    let (p, q) = (&job.p, &job.q);
    let (kp, kq) = (job.options.p_order, job.options.q_order);
    let [a, b, c] = f.knot_intervals();
    let (checks, original) = measure_joins(p, q, f, (kp, kq));
    let x = &f.crossing;
    let crossing_gap = distance(&p.eval(x.u), &q.eval(x.v));
    let p_setback = p.arc_length_default(f.u0, x.u).unwrap_or(f64::NAN);
    let q_setback = q.arc_length_default(x.v, f.v0).unwrap_or(f64::NAN);
    let (want_p, want_q) = match job.mode {
        FilletMode::Setbacks | FilletMode::Vertex { .. } => {
            (Some(job.options.p_setback), Some(job.options.q_setback))
        }
        FilletMode::Deviation { .. } | FilletMode::Radius { .. } => (None, None),
    };
    // Distance from the corner point to the blend, by dense sampling
    // refined with golden-section search around the best sample.
    let (deviation, deviation_t) = distance_to(&f.blend, &x.point);
    let worst_jump = worst(&checks).max(worst(&original));
    let p_first = p.domain().0;
    let q_last = q.domain().1;
    let bspline = f.to_bspline().ok().map(|s| curve_json(&s));

    let json = json!({
        "operation": "fillet",
        "p_trimmed": curve_json(&f.p_trimmed),
        "blend": curve_json(&f.blend),
        "q_trimmed": curve_json(&f.q_trimmed),
        "bspline": bspline,
        "u0": f.u0,
        "v0": f.v0,
        "crossing": {"u": x.u, "v": x.v, "point": x.point, "distance": crossing_gap},
        "report": {
            "mode": job.mode.name(),
            "blend_degree": f.blend.degree(),
            "p_order": kp,
            "q_order": kq,
            "auto_scale": !matches!(job.options.scale, ShapeScale::Given { .. }),
            "balanced_scale": job.options.scale == ShapeScale::Balanced,
            "p_scale": f.p_scale,
            "q_scale": f.q_scale,
            "chain_knot_intervals": [a, b, c],
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
            "measured_continuity_against_original_curves":
                original.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
            "measured_p_setback": p_setback,
            "measured_q_setback": q_setback,
            "requested_p_setback": want_p,
            "requested_q_setback": want_q,
            "requested_max_deviation": max_deviation,
            "measured_deviation": deviation,
            "measured_deviation_parameter": deviation_t,
            "library_max_residual": f.max_residual,
        }
    });

    let mut figure = Figure::new("Rounded corner");
    draw_part(&mut figure, p, p_first, f.u0, Role::Input, "P");
    draw_part(&mut figure, q, f.v0, q_last, Role::Input, "Q");
    figure.curve(CurveItem::bezier(
        &f.blend,
        Role::Result,
        format!("blend R, degree {} (C{} | C{})", f.blend.degree(), kp, kq),
    ));
    let mut arc_line = None;
    if let Some(arc) = circular_fillet(p, f.u0, q, x.u, x.v, f.v0) {
        figure.curve(CurveItem {
            shape: arc.shape.clone(),
            role: Role::Reference,
            label: format!(
                "circular-arc fillet, radius {:.4} (curvature jumps at its ends)",
                arc.radius
            ),
            polygon: false,
            comb: true,
        });
        arc_line = Some(format!(
            "Reference: circular arc tangent to P at P(u0) and to Q at v = {:.4}, radius {:.4}: only G1",
            arc.v, arc.radius
        ));
    }
    let corner_label = match job.mode {
        FilletMode::Vertex { .. } => format!("vertex P({:.4}) = Q({:.4})", x.u, x.v),
        _ => format!("X = P({:.4}) = Q({:.4})", x.u, x.v),
    };
    figure.marker(Marker::new(MarkerKind::Crossing, &x.point, corner_label));
    figure.marker(Marker::new(
        MarkerKind::Join,
        &f.blend.eval(0.0),
        format!("P(u0), u0 = {:.4}", f.u0),
    ));
    figure.marker(Marker::new(
        MarkerKind::Join,
        &f.blend.eval(1.0),
        format!("Q(v0), v0 = {:.4}", f.v0),
    ));
    figure.line(format!(
        "Blend R: degree {} = kp + kq + 1 = {} + {} + 1; scales alpha = {:.4}, beta = {:.4}",
        f.blend.degree(),
        kp,
        kq,
        f.p_scale,
        f.q_scale,
    ));
    let interval_names = if p.as_bezier().is_some() && q.as_bezier().is_some() {
        "(u0, alpha, (1 - v0) alpha / beta)"
    } else {
        "(u0 - first, alpha, (last - v0) alpha / beta)"
    };
    figure.line(format!(
        "Chain knot intervals {interval_names} = ({a:.4}, {b:.4}, {c:.4})"
    ));
    let from = match job.mode {
        FilletMode::Vertex { .. } => "the vertex",
        _ => "X",
    };
    figure.line(format!(
        "Setbacks measured as arc lengths from {from}: along P {p_setback:.6}, along Q {q_setback:.6}{}",
        match (want_p, want_q) {
            (Some(dp), Some(dq)) => format!(" (asked {dp}, {dq})"),
            _ => String::new(),
        }
    ));
    figure.line(format!(
        "Distance from {from} to the blend: {deviation:.6}{}",
        match max_deviation {
            Some(eps) => format!(" (asked {eps})"),
            None => String::new(),
        }
    ));
    for check in &checks {
        figure.line(check.describe());
    }
    if let Some(line) = arc_line {
        figure.line(line);
    }
    if p.dim() > 2 {
        figure.line(format!(
            "{}D curves drawn projected to the x-y plane",
            p.dim()
        ));
    }
    Outcome {
        json,
        figure,
        summary: Summary {
            degree: f.blend.degree(),
            worst_continuity_jump: Some(worst_jump),
            max_deviation: Some(deviation),
            deviation_meaning: "distance from the corner point to the blend",
        },
    }
}

/// Closest point of `curve` to `point`: `(distance, t)`, by 2001 samples
/// and golden-section refinement around the best one.
fn distance_to(curve: &BezierCurve, point: &[f64]) -> (f64, f64) {
    let d = |t: f64| distance(&curve.eval(t), point);
    let n = 2000;
    let best = (0..=n)
        .map(|i| i as f64 / n as f64)
        .fold((f64::INFINITY, 0.0), |(bd, bt), t| {
            let v = d(t);
            if v < bd { (v, t) } else { (bd, bt) }
        });
    let (mut lo, mut hi) = (
        (best.1 - 1.0 / n as f64).max(0.0),
        (best.1 + 1.0 / n as f64).min(1.0),
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let m1 = hi - g * (hi - lo);
        let m2 = lo + g * (hi - lo);
        if d(m1) < d(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let t = 0.5 * (lo + hi);
    let v = d(t);
    if v < best.0 { (v, t) } else { best }
}

fn corner_job(setbacks: (f64, f64), orders: (usize, usize)) -> Value {
    json!({
        "p": [[-4.0, -0.5], [-2.5, 0.8], [-1.0, 0.6], [1.5, -0.2]],
        "q": [[0.2, -2.0], [-0.3, -0.5], [0.6, 1.2], [-0.2, 3.0]],
        "p_setback": setbacks.0,
        "q_setback": setbacks.1,
        "p_order": orders.0,
        "q_order": orders.1,
        "p_scale": 0.15,
        "q_scale": 0.15
    })
}

/// The demo's fillet scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    vec![
        Scenario {
            name: "fillet-symmetric-c2",
            operation: OperationKind::Fillet,
            title: "Fillet: symmetric C2 rounding of a corner between two cubics",
            description: "Equal setbacks 0.6 along both cubics from their crossing; the blend of degree 5 is C2 at both ends (scales alpha = beta = 0.15 keep it from looping). The purple dashed circular arc of the same corner (tangent at P(u0)) is drawn for comparison: its comb jumps at the ends, ours does not.",
            job: corner_job((0.6, 0.6), (2, 2)),
        },
        Scenario {
            name: "fillet-asymmetric-c3",
            operation: OperationKind::Fillet,
            title: "Fillet: asymmetric C3 rounding (setbacks 0.4 and 0.9)",
            description: "Setbacks 0.4 along P and 0.9 along Q; the blend of degree 7 is C3 at both ends, next to the circular arc of the same corner.",
            job: corner_job((0.4, 0.9), (3, 3)),
        },
    ]
}
