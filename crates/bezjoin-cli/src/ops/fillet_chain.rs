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

use bezjoin_core::{
    ChainFillet, ChainFilletOptions, Curve, CurveRef, FilletOptions, NurbsCurve, fillet_chain,
};
use serde_json::{Value, json};

use crate::check::{JoinCheck, curve_json, worst};
use crate::job::{JobError, Located};
use crate::ops::fillet::read_scales;
use crate::ops::{OperationKind, Scenario, describe_curve};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// A parsed fillet-chain job.
pub struct ChainJob {
    /// The curves in path order (Bezier or NURBS).
    pub curves: Vec<Curve>,
    /// Corner options and whether the chain is closed.
    pub options: ChainFilletOptions,
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
    let dp = obj.required("p_setback")?.positive()?;
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
    let fillet = read_scales(&obj, FilletOptions::new(dp, dq, p_order, q_order))?;
    obj.finish()?;
    let options = if closed {
        ChainFilletOptions::closed(fillet)
    } else {
        ChainFilletOptions::open(fillet)
    };
    Ok(ChainJob { curves, options })
}

/// Run a fillet-chain job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    let chain = fillet_chain(&job.curves, &job.options)?;
    Ok(outcome(&job, &chain))
}

/// Where each trimmed curve starts and ends, in its own original
/// parameter: `(start, end)` per curve.
fn trimmed_ranges(job: &ChainJob, chain: &ChainFillet) -> Vec<(f64, f64)> {
    let n = job.curves.len();
    let corners = &chain.corners;
    (0..n)
        .map(|i| {
            let (first, last) = job.curves[i].domain();
            let start = if i > 0 {
                corners[i - 1].v0
            } else if job.options.closed {
                corners[corners.len() - 1].v0
            } else {
                first
            };
            let end = if i < corners.len() {
                corners[i].u0
            } else {
                last
            };
            (start, end)
        })
        .collect()
}

/// The joins of the rounded chain measured by the tool, two per corner
/// (`curve i|blend i`, `blend i|curve i+1`), and the knot intervals of the
/// whole chain as one B-spline (piece by piece, in `chain.pieces` order).
pub fn measure_joins(job: &ChainJob, chain: &ChainFillet) -> (Vec<JoinCheck>, Vec<f64>) {
    let n = job.curves.len();
    let ranges = trimmed_ranges(job, chain);
    let (kp, kq) = (job.options.fillet.p_order, job.options.fillet.q_order);
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
    if !job.options.closed {
        let (s, e) = ranges[n - 1];
        intervals.push(rate * (e - s));
    }
    (checks, intervals)
}

fn outcome(job: &ChainJob, chain: &ChainFillet) -> Outcome {
    let (kp, kq) = (job.options.fillet.p_order, job.options.fillet.q_order);
    let (checks, intervals) = measure_joins(job, chain);
    let ranges = trimmed_ranges(job, chain);
    let refs: Vec<CurveRef> = chain.pieces.iter().map(CurveRef::from).collect();
    let bspline = NurbsCurve::from_curve_chain(&refs, &intervals)
        .ok()
        .map(|s| curve_json(&s));
    let blends: Vec<&Curve> = chain.pieces.iter().skip(1).step_by(2).collect();
    let degree = blends.iter().map(|b| b.degree()).max().unwrap_or(0);
    let n = job.curves.len();
    let corners: Vec<Value> = chain
        .corners
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let (p, q) = (&job.curves[i], &job.curves[(i + 1) % n]);
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
            "closed": job.options.closed,
            "degree": degree,
            "p_order": kp,
            "q_order": kq,
            "requested_p_setback": job.options.fillet.p_setback,
            "requested_q_setback": job.options.fillet.q_setback,
            "chain_knot_intervals": intervals,
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
        }
    });

    let mut figure = Figure::new("Rounded chain");
    for (i, curve) in job.curves.iter().enumerate() {
        let mut given = CurveItem::new(
            curve,
            Role::Discarded,
            format!("curve {i}, {}, as given", describe_curve(curve)),
        );
        given.polygon = true;
        figure.curve(given);
    }
    for (i, piece) in chain.pieces.iter().enumerate() {
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
                format!("blend {}, degree {} (C{kp} | C{kq})", i / 2, piece.degree()),
            )
        };
        figure.curve(item);
    }
    for (i, c) in chain.corners.iter().enumerate() {
        figure.marker(Marker::new(
            MarkerKind::Crossing,
            &c.crossing.point,
            format!("corner {i}"),
        ));
        let blend = &chain.pieces[2 * i + 1];
        let (a, b) = blend.domain();
        figure.marker(Marker::new(MarkerKind::Join, &blend.eval(a), ""));
        figure.marker(Marker::new(MarkerKind::Join, &blend.eval(b), ""));
    }
    figure.line(format!(
        "{} curves, {} chain, {} corner{} rounded with setbacks {} / {}; blends of degree kp + kq + 1 = {kp} + {kq} + 1 = {}",
        n,
        if job.options.closed { "closed" } else { "open" },
        chain.corners.len(),
        if chain.corners.len() == 1 { "" } else { "s" },
        job.options.fillet.p_setback,
        job.options.fillet.q_setback,
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
    for check in &checks {
        figure.line(check.describe());
    }
    if job.curves[0].dim() > 2 {
        figure.line(format!(
            "{}D curves drawn projected to the x-y plane",
            job.curves[0].dim()
        ));
    }
    Outcome {
        json,
        figure,
        summary: Summary {
            degree,
            worst_continuity_jump: Some(worst(&checks)),
            max_deviation: None,
            deviation_meaning: "-",
        },
    }
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

/// The demo's fillet-chain scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    vec![Scenario {
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
    }]
}
