//! `bezjoin intersect`: all meeting points of two curves
//! ([`bezjoin_core::intersect`]).
//!
//! The job gives `P`, `Q` (Bezier or NURBS) and optional tolerances; the
//! result lists every hit with `u`, `v` (in each curve's domain), the point
//! and its kind (crossing, touching, overlap). The report re-measures
//! `|P(u) - Q(v)|` for every hit from the curves.

use bezjoin_core::{Curve, CurveRef, IntersectOptions, Intersection, IntersectionKind, intersect};
use serde_json::{Value, json};

use crate::check::{curve_json, distance};
use crate::job::{JobError, Located};
use crate::ops::{OperationKind, Scenario, describe_curve};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// A parsed intersect job.
pub struct IntersectJob {
    /// Curve P (Bezier or NURBS).
    pub p: Curve,
    /// Curve Q (Bezier or NURBS).
    pub q: Curve,
    /// Tolerances and work bounds.
    pub options: IntersectOptions,
}

/// Read an intersect job.
pub fn parse(job: &Located) -> Result<IntersectJob, JobError> {
    let obj = job.object()?;
    let p = obj.required("p")?.curve()?;
    let q = obj.required("q")?.curve()?;
    let mut options = IntersectOptions::default();
    if let Some(f) = obj.optional("relative_distance_tolerance") {
        options.relative_distance_tolerance = f.positive()?;
    }
    if let Some(f) = obj.optional("tangent_tolerance") {
        options.tangent_tolerance = f.positive()?;
    }
    if let Some(f) = obj.optional("max_depth") {
        options.max_depth = f.count()?;
    }
    if let Some(f) = obj.optional("max_box_pairs") {
        options.max_box_pairs = f.count()?;
    }
    if let Some(f) = obj.optional("max_hits") {
        options.max_hits = f.count()?;
    }
    obj.finish()?;
    Ok(IntersectJob { p, q, options })
}

/// Run an intersect job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    let hits = intersect(&job.p, &job.q, &job.options)?;
    Ok(outcome(&job, &hits))
}

fn kind_name(kind: &IntersectionKind) -> &'static str {
    match kind {
        IntersectionKind::Crossing => "crossing",
        IntersectionKind::Touching => "touching",
        IntersectionKind::Overlap { .. } => "overlap",
    }
}

fn hit_json(p: &Curve, q: &Curve, hit: &Intersection) -> (Value, f64) {
    let gap = distance(&p.eval(hit.u), &q.eval(hit.v));
    let mut value = json!({
        "u": hit.u,
        "v": hit.v,
        "point": hit.point,
        "kind": kind_name(&hit.kind),
        "measured_distance": gap,
    });
    if let IntersectionKind::Overlap { u_range, v_range } = hit.kind {
        let end_gap = distance(&p.eval(u_range.1), &q.eval(v_range.1));
        value["u_range"] = json!([u_range.0, u_range.1]);
        value["v_range"] = json!([v_range.0, v_range.1]);
        value["measured_end_distance"] = json!(end_gap);
        return (value, gap.max(end_gap));
    }
    (value, gap)
}

fn outcome(job: &IntersectJob, hits: &[Intersection]) -> Outcome {
    let (p, q) = (&job.p, &job.q);
    let mut worst_gap: f64 = 0.0;
    let list: Vec<Value> = hits
        .iter()
        .map(|h| {
            let (v, gap) = hit_json(p, q, h);
            worst_gap = worst_gap.max(gap);
            v
        })
        .collect();
    let scale = |c: &Curve| CurveRef::from(c).coordinate_scale();
    let tolerance = job.options.relative_distance_tolerance * scale(p).max(scale(q));
    let json = json!({
        "operation": "intersect",
        "p": curve_json(p),
        "q": curve_json(q),
        "hits": list,
        "report": {
            "count": hits.len(),
            "crossings": hits.iter().filter(|h| h.kind == IntersectionKind::Crossing).count(),
            "touching": hits.iter().filter(|h| h.kind == IntersectionKind::Touching).count(),
            "overlaps": hits.iter().filter(|h| matches!(h.kind, IntersectionKind::Overlap { .. })).count(),
            "max_measured_distance": worst_gap,
            "distance_tolerance": tolerance,
        }
    });
    let mut figure = Figure::new("Intersections");
    figure.curve(CurveItem::new(
        p,
        Role::Input,
        format!("P, {}", describe_curve(p)),
    ));
    figure.curve(CurveItem::new(
        q,
        Role::Result,
        format!("Q, {}", describe_curve(q)),
    ));
    for (i, h) in hits.iter().enumerate() {
        figure.marker(Marker::new(
            MarkerKind::Crossing,
            &h.point,
            format!(
                "#{} {}: u = {:.6}, v = {:.6}",
                i + 1,
                kind_name(&h.kind),
                h.u,
                h.v
            ),
        ));
    }
    figure.line(format!(
        "{} hit(s); largest |P(u) - Q(v)| re-measured: {:.1e} (tolerance {:.1e})",
        hits.len(),
        worst_gap,
        tolerance
    ));
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
            degree: p.degree().max(q.degree()),
            worst_continuity_jump: None,
            max_deviation: Some(worst_gap),
            deviation_meaning: "|P(u) - Q(v)| at the hits",
        },
    }
}

/// The demo's intersect scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    vec![Scenario {
        name: "intersect-wavy-cubics",
        operation: OperationKind::Intersect,
        title: "Intersect: two cubics crossing several times",
        description: "Two wavy cubics of opposite phase meet at several points; every hit is marked with its parameters u on P and v on Q.",
        job: json!({
            "p": [[0.0, 0.0], [1.5, 4.0], [2.5, -4.0], [4.0, 0.0]],
            "q": [[0.0, 1.5], [1.5, -2.5], [2.5, 2.5], [4.0, -1.5]]
        }),
    }]
}
