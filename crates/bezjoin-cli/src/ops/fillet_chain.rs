//! `bezjoin fillet-chain`: rounding every corner of a chain (a wire) of
//! curves ([`bezjoin_core::fillet_chain`]; mathematics.md sections 2 and 6).
//!
//! The job gives the curves (Bezier or NURBS, in path order), whether the
//! chain is closed, and the corner options of `bezjoin fillet` (setbacks,
//! orders, scales), used at every corner; `P` is the curve before a corner,
//! `Q` the one after it. Corner `i` is the crossing of `curves[i]` and
//! `curves[i + 1]` nearest their shared end (for a wire: the vertex).
//!
//! The report is re-measured by the tool at every join from the returned
//! pieces: derivatives of the piece before the join from the left of its
//! last parameter, of the piece after it from the right of its first, each
//! read in the chain's parameter (knot intervals: a trimmed curve spans the
//! length of its parameter range, times the product of `alpha / beta` of
//! the corners before it; blend `i` spans `alpha_i` times the rate of the
//! curve before it).
//!
//! With `"radius"` (and `"order"`, default 2) instead of setbacks, every
//! corner is rounded as `bezjoin fillet` with `"radius"` rounds one
//! ([`bezjoin_core::fillet_radius_chain`], [`super::fillet_radius`]): cut
//! where the arc of radius `r` touches, joined by a fair G^k blend. The
//! report lists per corner the touching points, the arc's centre, the
//! blend's distance from the arc's circle and its fairness report, and the
//! tool's measurements of [`super::fillet_radius`]: G^k at every join from
//! the derivatives with respect to arc length (unit tangent, curvature
//! vector, `dK/ds`) of the returned pieces on both sides.

use bezjoin_core::{
    BezjoinError, ChainFillet, ChainFilletOptions, Curve, CurveRef, FilletOptions, NurbsCurve,
    RadiusChainFillet, ShapeScale, fillet_chain, fillet_radius_chain,
};
use serde_json::{Value, json};

use crate::check::{JoinCheck, curve_json, worst};
use crate::curvature::{CurvatureProfile, PathPiece};
use crate::job::{JobError, Located};
use crate::ops::fillet::read_scales;
use crate::ops::fillet_radius::{
    CornerMeasure, RoundedCorner, arc_series, corner_fields, crossing_json, draw_arc,
    measure_joins as measure_radius_joins, read_radius_fields, refuse_without_radius, with_fields,
};
use crate::ops::{OperationKind, Scenario, describe_curve};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role, Shape};
use crate::{CliError, Outcome, Summary};

/// How the corners of a chain are rounded.
pub enum ChainMode {
    /// Given setbacks, orders and scales at every corner
    /// ([`bezjoin_core::fillet_chain`]); the options say whether the chain
    /// is closed.
    Setbacks(ChainFilletOptions),
    /// Every corner sized like the arc of `radius` and rounded by a fair
    /// G^`order` blend ([`bezjoin_core::fillet_radius_chain`]).
    Radius {
        /// `r > 0`.
        radius: f64,
        /// `k`: G^k at every join.
        order: usize,
    },
}

/// A parsed fillet-chain job.
pub struct ChainJob {
    /// The curves in path order (Bezier or NURBS).
    pub curves: Vec<Curve>,
    /// The last curve's end and the first's start are one more corner.
    pub closed: bool,
    /// Setbacks or radius.
    pub mode: ChainMode,
}

/// Read a fillet-chain job.
pub fn parse(job: &Located) -> Result<ChainJob, JobError> {
    let obj = job.object()?;
    let curves_field = obj.required("curves")?;
    let curves = curves_field
        .array()?
        .iter()
        .map(Located::curve)
        .collect::<Result<Vec<_>, _>>()?;
    if curves.len() < 2 {
        return Err(JobError::new(
            curves_field.path.clone(),
            format!("a chain needs at least 2 curves, {} given", curves.len()),
        ));
    }
    let closed = obj
        .optional("closed")
        .map(|f| f.boolean())
        .transpose()?
        .unwrap_or(false);
    if let Some(radius) = obj.optional("radius") {
        let radius = radius.positive()?;
        let order = read_radius_fields(
            &obj,
            &[
                "p_setback",
                "q_setback",
                "p_order",
                "q_order",
                "p_scale",
                "q_scale",
                "auto_scale",
            ],
            "every corner is the shared vertex when the curves meet end to end, else their \
             crossing nearest the shared end",
        )?;
        obj.finish()?;
        return Ok(ChainJob {
            curves,
            closed,
            mode: ChainMode::Radius { radius, order },
        });
    }
    refuse_without_radius(&obj, &["order"])?;
    let dp = obj
        .required("p_setback")
        .map_err(|e| JobError::new(e.path, "is required unless \"radius\" is given"))?
        .positive()?;
    let dq = obj
        .optional("q_setback")
        .map(|f| f.positive())
        .transpose()?
        .unwrap_or(dp);
    let p_order = obj
        .optional("p_order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(2);
    let q_order = obj
        .optional("q_order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(p_order);
    let fillet = read_scales(&obj, FilletOptions::new(dp, dq, p_order, q_order), true)?;
    obj.finish()?;
    let options = if closed {
        ChainFilletOptions::closed(fillet)
    } else {
        ChainFilletOptions::open(fillet)
    };
    Ok(ChainJob {
        curves,
        closed,
        mode: ChainMode::Setbacks(options),
    })
}

/// Run a fillet-chain job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    match &job.mode {
        ChainMode::Setbacks(options) => {
            let chain = fillet_chain(&job.curves, options)?;
            Ok(outcome(&job.curves, options, &chain))
        }
        &ChainMode::Radius { radius, order } => {
            let chain = fillet_radius_chain(&job.curves, radius, order, job.closed)
                .map_err(|e| radius_error(e, radius))?;
            Ok(radius_outcome(
                &job.curves,
                job.closed,
                radius,
                order,
                &chain,
            ))
        }
    }
}

/// The library's refusals of a radius that does not fit, as errors of the
/// job's `radius` naming the corner or the curve: `corner i radius: ...`
/// (the arc does not fit on the corner's curves) and `curves[i]: ...` (the
/// touching points of its two corners pass each other: the edge is too
/// short for the radius).
fn radius_error(e: BezjoinError, radius: f64) -> CliError {
    match e {
        BezjoinError::InvalidArgument { name, reason } if name.ends_with(" radius") => {
            let corner = name.trim_end_matches(" radius");
            JobError::new("radius", format!("{corner}: {reason}")).into()
        }
        BezjoinError::InvalidArgument { name, reason } if name.starts_with("curves[") => {
            JobError::new(
                "radius",
                format!(
                    "{radius} is too large for {name} (the arcs of its two corners overlap on \
                     it): {reason}"
                ),
            )
            .into()
        }
        other => other.into(),
    }
}

/// Where each trimmed curve starts and ends, in its own original
/// parameter: `(start, end)` per curve, from the corners' cuts `(u0, v0)`.
fn trimmed_ranges(curves: &[Curve], closed: bool, cuts: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let n = curves.len();
    (0..n)
        .map(|i| {
            let (first, last) = curves[i].domain();
            let start = if i > 0 {
                cuts[i - 1].1
            } else if closed {
                cuts[cuts.len() - 1].1
            } else {
                first
            };
            let end = if i < cuts.len() { cuts[i].0 } else { last };
            (start, end)
        })
        .collect()
}

/// The cuts `(u0, v0)` of a chain's corners.
fn setback_cuts(chain: &ChainFillet) -> Vec<(f64, f64)> {
    chain.corners.iter().map(|c| (c.u0, c.v0)).collect()
}

/// The joins of the rounded chain measured by the tool, two per corner
/// (`curve i|blend i`, `blend i|curve i+1`), and the knot intervals of the
/// whole chain as one B-spline (piece by piece, in `chain.pieces` order).
pub fn measure_joins(
    curves: &[Curve],
    options: &ChainFilletOptions,
    chain: &ChainFillet,
) -> (Vec<JoinCheck>, Vec<f64>) {
    let n = curves.len();
    let ranges = trimmed_ranges(curves, options.closed, &setback_cuts(chain));
    let (kp, kq) = (options.fillet.p_order, options.fillet.q_order);
    let mut checks = Vec::new();
    let mut intervals = Vec::new();
    // Rate of the current curve: global parameter per unit of its own
    // (original) parameter; 1 for the first curve.
    let mut rate = 1.0;
    for (i, corner) in chain.corners.iter().enumerate() {
        let j = (i + 1) % n;
        let (alpha, beta) = corner.scales;
        let left = &chain.pieces[2 * i];
        let blend = &chain.pieces[2 * i + 1];
        let right = &chain.pieces[(2 * i + 2) % chain.pieces.len()];
        let (ls, le) = ranges[i];
        let (rs, re) = ranges[j];
        // Each join is read locally (the curve before it at rate 1); the
        // relative jumps do not depend on a common factor.
        checks.push(JoinCheck::measure(
            format!("curve {i}|blend {i}"),
            left,
            le - ls,
            blend,
            alpha,
            kp,
        ));
        checks.push(JoinCheck::measure(
            format!("blend {i}|curve {j}"),
            blend,
            alpha,
            right,
            (re - rs) * alpha / beta,
            kq,
        ));
        intervals.push(rate * (le - ls));
        intervals.push(rate * alpha);
        rate *= alpha / beta;
    }
    if !options.closed {
        let (s, e) = ranges[n - 1];
        intervals.push(rate * (e - s));
    }
    (checks, intervals)
}

fn outcome(curves: &[Curve], options: &ChainFilletOptions, chain: &ChainFillet) -> Outcome {
    let (kp, kq) = (options.fillet.p_order, options.fillet.q_order);
    let (checks, intervals) = measure_joins(curves, options, chain);
    let ranges = trimmed_ranges(curves, options.closed, &setback_cuts(chain));
    let refs: Vec<CurveRef> = chain.pieces.iter().map(CurveRef::from).collect();
    let bspline = NurbsCurve::from_curve_chain(&refs, &intervals)
        .ok()
        .map(|s| curve_json(&s));
    let blends: Vec<&Curve> = chain.pieces.iter().skip(1).step_by(2).collect();
    let degree = blends.iter().map(|b| b.degree()).max().unwrap_or(0);
    let n = curves.len();
    let corners: Vec<Value> = chain
        .corners
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let (p, q) = (&curves[i], &curves[(i + 1) % n]);
            json!({
                "index": i,
                "crossing": {"u": c.crossing.u, "v": c.crossing.v, "point": c.crossing.point},
                "u0": c.u0,
                "v0": c.v0,
                "p_scale": c.scales.0,
                "q_scale": c.scales.1,
                "measured_p_setback": p.arc_length_default(c.u0, c.crossing.u).unwrap_or(f64::NAN),
                "measured_q_setback": q.arc_length_default(c.crossing.v, c.v0).unwrap_or(f64::NAN),
                "library_max_residual": c.max_residual,
            })
        })
        .collect();
    let json = json!({
        "operation": "fillet-chain",
        "pieces": chain.pieces.iter().map(curve_json).collect::<Vec<_>>(),
        "bspline": bspline,
        "corners": corners,
        "report": {
            "mode": "setbacks",
            "closed": options.closed,
            "degree": degree,
            "p_order": kp,
            "q_order": kq,
            "requested_p_setback": options.fillet.p_setback,
            "requested_q_setback": options.fillet.q_setback,
            "auto_scale": !matches!(options.fillet.scale, ShapeScale::Given { .. }),
            "balanced_scale": options.fillet.scale == ShapeScale::Balanced,
            "chain_knot_intervals": intervals,
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
        }
    });

    let mut figure = Figure::new("Rounded chain");
    let corner_points: Vec<&[f64]> = chain
        .corners
        .iter()
        .map(|c| c.crossing.point.as_slice())
        .collect();
    draw_chain(
        &mut figure,
        curves,
        &chain.pieces,
        &ranges,
        &corner_points,
        &format!("C{kp} | C{kq}"),
    );
    figure.line(format!(
        "{} curves, {} chain, {} corner{} rounded with setbacks {} / {}; blends of degree kp + kq + 1 = {kp} + {kq} + 1 = {}",
        n,
        if options.closed { "closed" } else { "open" },
        chain.corners.len(),
        if chain.corners.len() == 1 { "" } else { "s" },
        options.fillet.p_setback,
        options.fillet.q_setback,
        kp + kq + 1,
    ));
    for (i, c) in chain.corners.iter().enumerate() {
        figure.line(format!(
            "corner {i}: curve {i} cut at u0 = {:.4}, curve {} at v0 = {:.4}; scales alpha = {:.4}, beta = {:.4}",
            c.u0,
            (i + 1) % n,
            c.v0,
            c.scales.0,
            c.scales.1
        ));
    }
    finish(json, figure, curves, &checks, degree, None)
}

/// The outcome of a rounded chain: the caption ends with the measured
/// joins (and a note for curves in space); the summary has the blends'
/// `degree`, the worst measured jump and the `deviation` with its meaning.
fn finish(
    json: Value,
    mut figure: Figure,
    curves: &[Curve],
    checks: &[JoinCheck],
    degree: usize,
    deviation: Option<(f64, &'static str)>,
) -> Outcome {
    for check in checks {
        figure.line(check.describe());
    }
    if curves[0].dim() > 2 {
        figure.line(format!(
            "{}D curves drawn projected to the x-y plane",
            curves[0].dim()
        ));
    }
    Outcome {
        json,
        figure,
        summary: Summary {
            degree,
            worst_continuity_jump: Some(worst(checks)),
            max_deviation: deviation.map(|(d, _)| d),
            deviation_meaning: deviation.map_or("-", |(_, m)| m),
        },
    }
}

/// Draw a rounded chain: the given curves dashed grey with their polygons
/// or poles, the kept parts (on `ranges` of their own parameters) and the
/// blends (`joins`: their continuity, e.g. `C2 | C2`) with curvature combs
/// on one scale, the corners (crosses) and the joins (circles).
fn draw_chain(
    figure: &mut Figure,
    curves: &[Curve],
    pieces: &[Curve],
    ranges: &[(f64, f64)],
    corners: &[&[f64]],
    joins: &str,
) {
    for (i, curve) in curves.iter().enumerate() {
        let mut given = CurveItem::new(
            curve,
            Role::Discarded,
            format!("curve {i}, {}, as given", describe_curve(curve)),
        );
        given.polygon = true;
        figure.curve(given);
    }
    for (i, piece) in pieces.iter().enumerate() {
        let item = if i % 2 == 0 {
            let c = i / 2;
            let (s, e) = ranges[c];
            CurveItem::new(
                piece,
                Role::Input,
                format!("curve {c} on [{s:.4}, {e:.4}] (kept part)"),
            )
            .without_polygon()
        } else {
            CurveItem::new(
                piece,
                Role::Result,
                format!("blend {}, degree {} ({joins})", i / 2, piece.degree()),
            )
        };
        figure.curve(item);
    }
    for (i, point) in corners.iter().enumerate() {
        figure.marker(Marker::new(
            MarkerKind::Crossing,
            point,
            format!("corner {i}"),
        ));
        let blend = &pieces[2 * i + 1];
        let (a, b) = blend.domain();
        figure.marker(Marker::new(MarkerKind::Join, &blend.eval(a), ""));
        figure.marker(Marker::new(MarkerKind::Join, &blend.eval(b), ""));
    }
}

/// Corner `i` of a chain rounded by radius, with the pieces around it.
fn rounded_corner<'a>(
    curves: &'a [Curve],
    chain: &'a RadiusChainFillet,
    i: usize,
) -> RoundedCorner<'a> {
    let (n, len) = (curves.len(), chain.pieces.len());
    let c = &chain.corners[i];
    let Curve::Bezier(blend) = &chain.pieces[2 * i + 1] else {
        unreachable!("the blends of a chain are Bezier curves")
    };
    RoundedCorner {
        p: &curves[i],
        q: &curves[(i + 1) % n],
        p_kept: &chain.pieces[2 * i],
        blend,
        q_kept: &chain.pieces[(2 * i + 2) % len],
        corner: &c.corner,
        u0: c.u0,
        v0: c.v0,
        arc_centre: &c.arc_centre,
        arc_deviation: c.arc_deviation,
        p_shape: &c.p_shape,
        q_shape: &c.q_shape,
        report: &c.report,
    }
}

/// The result of a chain rounded by radius: the pieces, per corner the
/// library's data and the tool's measurements ([`corner_fields`]), and the
/// picture with the arcs of radius `r` and `kappa(s)` around the chain.
fn radius_outcome(
    curves: &[Curve],
    closed: bool,
    radius: f64,
    order: usize,
    chain: &RadiusChainFillet,
) -> Outcome {
    let n = curves.len();
    let corners: Vec<RoundedCorner> = (0..chain.corners.len())
        .map(|i| rounded_corner(curves, chain, i))
        .collect();
    let measures: Vec<CornerMeasure> = corners
        .iter()
        .map(|c| CornerMeasure::new(c, radius))
        .collect();
    let joins: Vec<[[JoinCheck; 2]; 2]> = corners
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let names = [
                format!("curve {i}"),
                format!("blend {i}"),
                format!("curve {}", (i + 1) % n),
            ];
            measure_radius_joins(c, order, [&names[0], &names[1], &names[2]])
        })
        .collect();
    let checks: Vec<JoinCheck> = joins.iter().flat_map(|j| j[0].clone()).collect();
    let original: Vec<JoinCheck> = joins.iter().flat_map(|j| j[1].clone()).collect();
    let degree = corners.iter().map(|c| c.blend.degree()).max().unwrap_or(0);
    let arc_deviation = corners.iter().map(|c| c.arc_deviation).fold(0.0, f64::max);
    let corner_json: Vec<Value> = corners
        .iter()
        .zip(&measures)
        .zip(&joins)
        .enumerate()
        .map(|(i, ((c, m), j))| {
            let head = json!({
                "index": i,
                "crossing": crossing_json(c.p, c.q, c.corner),
                "u0": c.u0,
                "v0": c.v0,
                "touching_points": [c.p.eval(c.u0), c.q.eval(c.v0)],
            });
            with_fields(head, corner_fields(c, m, j))
        })
        .collect();
    let json = json!({
        "operation": "fillet-chain",
        "pieces": chain.pieces.iter().map(curve_json).collect::<Vec<_>>(),
        "corners": corner_json,
        "report": {
            "mode": "radius",
            "closed": closed,
            "radius": radius,
            "order": order,
            "degree": degree,
            "max_arc_deviation": arc_deviation,
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
            "measured_continuity_against_original_curves":
                original.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
        }
    });

    let mut figure = Figure::new("Rounded chain by radius");
    let cuts: Vec<(f64, f64)> = corners.iter().map(|c| (c.u0, c.v0)).collect();
    let corner_points: Vec<&[f64]> = corners.iter().map(|c| c.corner.point.as_slice()).collect();
    draw_chain(
        &mut figure,
        curves,
        &chain.pieces,
        &trimmed_ranges(curves, closed, &cuts),
        &corner_points,
        &format!("G{order} | G{order}, fair shape values"),
    );
    let arcs: Vec<Option<Shape>> = corners
        .iter()
        .map(|c| draw_arc(&mut figure, c, radius, false))
        .collect();
    for c in &corners {
        figure.marker(Marker::new(MarkerKind::Centre, c.arc_centre, ""));
    }
    if curves[0].dim() == 2 {
        figure.plot(chain_curvature_plot(&chain.pieces, arcs));
    }
    figure.line(format!(
        "{n} curves, {} chain, {} corner{} rounded like the arc of radius {radius}",
        if closed { "closed" } else { "open" },
        corners.len(),
        if corners.len() == 1 { "" } else { "s" },
    ));
    figure.line(format!(
        "Blends of degree 2k + 1 = {degree}, G{order} at both cuts, fair shape values; \
         arcs dashed (curvature 1/r = {:.4})",
        1.0 / radius
    ));
    for (i, (c, m)) in corners.iter().zip(&measures).enumerate() {
        figure.line(format!(
            "corner {i} ({}, turning {:.2} deg): cuts at {:.4} and {:.4} from it, r tan(theta/2) = {:.4}",
            m.corner_kind(),
            m.turning_angle.to_degrees(),
            m.p_setback,
            m.q_setback,
            m.tangent_length,
        ));
        figure.line(format!(
            "blend {i}: curvature {:.4} .. {:.4}, interior extrema {}, energy {:.4}, {:.4} from the circle",
            c.report.curvature_min,
            c.report.curvature_max,
            c.report.curvature_extrema,
            c.report.energy,
            c.arc_deviation,
        ));
    }
    finish(
        json,
        figure,
        curves,
        &checks,
        degree,
        Some((
            arc_deviation,
            "distance of the blends from the circles of radius r",
        )),
    )
}

/// `kappa(s)` along the whole chain (kept parts and blends in path order;
/// a closed chain from the start of curve 0's kept part), with the arc of
/// each corner dashed from where its blend starts.
fn chain_curvature_plot(pieces: &[Curve], arcs: Vec<Option<Shape>>) -> crate::svg::Plot {
    let path: Vec<PathPiece> = pieces
        .iter()
        .enumerate()
        .map(|(i, piece)| {
            let (role, label) = if i % 2 == 0 {
                (Role::Input, format!("curve {}", i / 2))
            } else {
                (Role::Result, format!("blend {}", i / 2))
            };
            PathPiece::new(Shape::curve(piece), role, label)
        })
        .collect();
    let profile = CurvatureProfile::new(&path);
    let mut plot = profile.plot(
        "Curvature along arc length around the chain: kept parts, blends (red); the arcs (dashed)",
    );
    for (i, arc) in arcs.into_iter().enumerate() {
        if let (Some(arc), Some(start)) = (arc, profile.pieces[2 * i + 1].first()) {
            plot.series.push(arc_series(arc, start[0]));
        }
    }
    plot
}

/// The demo's wire: a circular arc, a line and a rational cubic B-spline,
/// meeting at two corners.
fn wire_job() -> Value {
    json!({
        "curves": [
            {"arc": {
                "centre": [3.0, 0.0],
                "radius": 3.0,
                "x_axis": [-1.0, 0.0],
                "y_axis": [0.0, 1.0],
                "start_angle": 0.0,
                "end_angle": 2.0943951023931953
            }},
            [[4.5, 2.598076211353316], [6.5, -1.0]],
            {
                "degree": 3,
                "poles": [[6.5, -1.0], [8.5, -1.5], [9.5, 1.5], [11.0, 0.5], [12.5, 2.5]],
                "knots": [0.0, 0.0, 0.0, 0.0, 4.0, 8.0, 8.0, 8.0, 8.0],
                "weights": [1.0, 2.5, 0.6, 1.8, 1.0]
            }
        ],
        "p_setback": 0.8,
        "p_order": 3,
        "q_order": 3,
        "auto_scale": true
    })
}

/// The demo's closed wire: the outline of an L-shaped plate of four lines,
/// a cubic step and a circular arc (exact rational quadratic), every
/// vertex rounded by radius 1 with G2.
fn plate_job() -> Value {
    json!({
        "curves": [
            [[0.0, 0.0], [12.0, 0.0]],
            [[12.0, 0.0], [12.0, 4.0]],
            [[12.0, 4.0], [6.0, 4.0]],
            [[6.0, 4.0], [5.6, 6.5], [4.0, 7.5], [4.0, 10.0]],
            {"arc": {
                "centre": [2.0, 8.5],
                "radius": 2.5,
                "start_angle": 0.6435011087932844,
                "end_angle": 2.498091544796509
            }},
            [[0.0, 10.0], [0.0, 0.0]]
        ],
        "closed": true,
        "radius": 1.0,
        "order": 2
    })
}

/// The demo's fillet-chain scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    vec![
        Scenario {
            name: "fillet-chain-arc-line-nurbs",
            operation: OperationKind::FilletChain,
            title: "Fillet chain: a wire of a circular arc, a line and a rational B-spline, every vertex rounded C3",
            description: "An open wire: a circular arc of radius 3 (an exact rational quadratic NURBS, \
                      from the job's \"arc\" form), a line, and a rational cubic B-spline of two spans \
                      (weights 1, 2.5, 0.6, 1.8, 1, knots on [0, 8]). Both vertices are rounded with \
                      setbacks 0.8 by blends of degree 7, C3 at both ends, scales chosen \
                      automatically. The curvature combs run on across all four joins: the arc's \
                      constant band continues into the first blend, both blends fall to zero where \
                      they meet the line, and the second blend's comb continues into the B-spline's.",
            job: wire_job(),
        },
        Scenario {
            name: "fillet-chain-radius-plate",
            operation: OperationKind::FilletChain,
            title: "Fillet chain by radius: closed L-shaped plate of lines, a cubic and an arc, all corners G2, r = 1",
            description: "A closed wire: the outline of an L-shaped plate of four lines, a cubic \
                      step (an S-shaped edge) and a circular arc of radius 2.5 (an exact \
                      rational quadratic NURBS). Each of the six vertices, the inner one \
                      included, is sized like the circular fillet of radius 1 (cut at r \
                      tan(theta/2) from the vertex of two lines, where the arc touches a curved \
                      edge) and rounded by a fair G2 blend of degree 5. The combs run on across \
                      every join; below, the curvature along arc length around the whole wire: \
                      each blend rises smoothly from the edge's own curvature to one maximum and \
                      back, where the arc of radius 1 (dashed) jumps to 1/r and back.",
            job: plate_job(),
        },
    ]
}
