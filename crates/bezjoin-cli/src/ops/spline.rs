//! `bezjoin spline`: the spline whose defining points lie on the curve
//! (mathematics.md section 4, Kovtun, seed 004), built by
//! [`bezjoin_core::lagrange_spline`].
//!
//! The tool re-measures the result from the returned Bezier segments: the
//! distance of every given on-curve point from its segment at `u = j / n`,
//! and the derivative jumps at every node in the global parameter (the
//! `m`-th derivative of segment `i` divided by `h_i^m`).

use bezjoin_core::{
    BezierCurve, BuildDirection, DEFAULT_LAGRANGE_ACCURACY, DerivedPoints, LagrangeOptions,
    LagrangeSpline, lagrange_spline,
};
use serde_json::{Value, json};

use crate::check::{JoinCheck, curve_json, distance, worst};
use crate::job::{JobError, Located};
use crate::ops::{OperationKind, Scenario};
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Role};
use crate::{CliError, Outcome, Summary};

/// A parsed spline job.
pub struct SplineJob {
    /// Dimension of every point.
    pub dim: usize,
    /// The nodes, `node_count` points.
    pub nodes: Vec<Vec<f64>>,
    /// Global parameters of the nodes; `None` = chord length.
    pub params: Option<Vec<f64>>,
    /// The `degree - 1` inner points of the starting segment (segment 0
    /// forwards, the last segment backwards), increasing `u`.
    pub start_inner: Vec<Vec<f64>>,
    /// For every other segment, in increasing segment order, its
    /// `degree - 1 - continuity` free inner points, increasing `u`.
    pub free_inner: Vec<Vec<Vec<f64>>>,
    /// Degree, continuity, direction, derived points, accuracy.
    pub options: LagrangeOptions,
}

/// One given on-curve point and where it must lie.
#[derive(Debug, Clone)]
pub struct GivenPoint {
    /// Segment index.
    pub segment: usize,
    /// `j` of `u = j / n`.
    pub index: usize,
    /// The point.
    pub point: Vec<f64>,
    /// What it is: "node", "start inner" or "free inner".
    pub kind: &'static str,
}

/// Read a spline job.
pub fn parse(job: &Located) -> Result<SplineJob, JobError> {
    let obj = job.object()?;
    let nodes_field = obj.required("nodes")?;
    let nodes = nodes_field.points(None)?;
    if nodes.len() < 2 {
        return Err(JobError::new(
            nodes_field.path.clone(),
            format!("at least 2 nodes are needed, got {}", nodes.len()),
        ));
    }
    let dim = nodes[0].len();
    let params = match obj.optional("params") {
        Some(f) => {
            let values: Vec<f64> = f
                .array()?
                .iter()
                .map(|v| v.number())
                .collect::<Result<_, _>>()?;
            if values.len() != nodes.len() {
                return Err(JobError::new(
                    f.path.clone(),
                    format!(
                        "has {} entries but there are {} nodes",
                        values.len(),
                        nodes.len()
                    ),
                ));
            }
            Some(values)
        }
        None => None,
    };
    let degree = match obj.optional("degree") {
        Some(f) => {
            let d = f.count()?;
            if !(3..=5).contains(&d) {
                return Err(JobError::new(
                    f.path.clone(),
                    format!("{d} is not one of 3, 4, 5"),
                ));
            }
            d
        }
        None => 3,
    };
    let continuity = match obj.optional("continuity") {
        Some(f) => {
            let k = f.count()?;
            if k == 0 || k + 2 > degree {
                return Err(JobError::new(
                    f.path.clone(),
                    format!("{k} is not in 1..={} for degree {degree}", degree - 2),
                ));
            }
            k
        }
        None => 1,
    };
    let direction = match obj.optional("direction") {
        Some(f) => match f.choice(&["forward", "backward"])? {
            "backward" => BuildDirection::Backward,
            _ => BuildDirection::Forward,
        },
        None => BuildDirection::Forward,
    };
    let derived = match obj.optional("mirrored") {
        Some(f) if f.boolean()? => DerivedPoints::FarFromJoin,
        _ => DerivedPoints::NextToJoin,
    };
    let accuracy = match obj.optional("accuracy") {
        Some(f) => f.positive()?,
        None => DEFAULT_LAGRANGE_ACCURACY,
    };
    let options = LagrangeOptions::default()
        .with_degree(degree)
        .with_continuity(continuity)
        .with_direction(direction)
        .with_derived(derived)
        .with_accuracy(accuracy);

    let start_field = obj.required("start_inner")?;
    let start_inner = start_field.points(Some(dim))?;
    if start_inner.len() != degree - 1 {
        return Err(JobError::new(
            start_field.path.clone(),
            format!(
                "needs the {} inner points of the starting segment (degree {degree}), got {}",
                degree - 1,
                start_inner.len()
            ),
        ));
    }
    let later_segments = nodes.len() - 2;
    let per_segment = options.free_points_per_segment();
    let free_inner = match obj.optional("free_inner") {
        Some(f) => {
            let groups = f.array()?;
            if groups.len() != later_segments {
                return Err(JobError::new(
                    f.path.clone(),
                    format!(
                        "needs one entry per segment other than the starting one ({later_segments}), got {}",
                        groups.len()
                    ),
                ));
            }
            let mut out = Vec::with_capacity(groups.len());
            for g in &groups {
                let pts = g.points(Some(dim))?;
                if pts.len() != per_segment {
                    return Err(JobError::new(
                        g.path.clone(),
                        format!(
                            "needs {per_segment} free inner point(s) (degree {degree} - 1 - continuity {continuity}), got {}",
                            pts.len()
                        ),
                    ));
                }
                out.push(pts);
            }
            out
        }
        None if later_segments == 0 => Vec::new(),
        None => {
            return Err(JobError::new(
                "free_inner",
                format!(
                    "is required: {later_segments} segment(s) besides the starting one need their free inner points"
                ),
            ));
        }
    };
    obj.finish()?;
    Ok(SplineJob {
        dim,
        nodes,
        params,
        start_inner,
        free_inner,
        options,
    })
}

impl SplineJob {
    /// Index of the starting segment.
    pub fn start_segment(&self) -> usize {
        match self.options.direction {
            BuildDirection::Forward => 0,
            BuildDirection::Backward => self.nodes.len() - 2,
        }
    }

    /// Every point the job prescribes on the curve, with its segment and `j`.
    pub fn given_points(&self) -> Vec<GivenPoint> {
        let n = self.options.degree;
        let segments = self.nodes.len() - 1;
        let mut out = Vec::new();
        for (i, node) in self.nodes.iter().enumerate() {
            let (segment, index) = if i < segments { (i, 0) } else { (i - 1, n) };
            out.push(GivenPoint {
                segment,
                index,
                point: node.clone(),
                kind: "node",
            });
        }
        let start = self.start_segment();
        for (j, p) in self.start_inner.iter().enumerate() {
            out.push(GivenPoint {
                segment: start,
                index: j + 1,
                point: p.clone(),
                kind: "start inner",
            });
        }
        let free = self.options.free_indices();
        let others = (0..segments).filter(|&s| s != start);
        for (segment, group) in others.zip(&self.free_inner) {
            for (&j, p) in free.iter().zip(group) {
                out.push(GivenPoint {
                    segment,
                    index: j,
                    point: p.clone(),
                    kind: "free inner",
                });
            }
        }
        out
    }
}

/// Build the spline of a parsed job.
pub fn build(job: &SplineJob) -> Result<LagrangeSpline, CliError> {
    let nodes: Vec<f64> = job.nodes.concat();
    let start: Vec<f64> = job.start_inner.concat();
    let free: Vec<f64> = job.free_inner.iter().flat_map(|g| g.concat()).collect();
    Ok(lagrange_spline(
        job.dim,
        &nodes,
        job.params.as_deref(),
        &start,
        &free,
        &job.options,
    )?)
}

/// Run a spline job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let job = parse(job)?;
    let spline = build(&job)?;
    outcome(&job, &spline)
}

/// The joins of consecutive segments measured by the tool in the global
/// parameter (segment `i` spans `h_i`).
pub fn measure_joins(segments: &[BezierCurve], intervals: &[f64], order: usize) -> Vec<JoinCheck> {
    (1..segments.len())
        .map(|i| {
            JoinCheck::measure(
                format!("node {i}"),
                &segments[i - 1],
                intervals[i - 1],
                &segments[i],
                intervals[i],
                order,
            )
        })
        .collect()
}

fn outcome(job: &SplineJob, spline: &LagrangeSpline) -> Result<Outcome, CliError> {
    let n = spline.degree();
    let k = spline.continuity();
    let segments = spline.segments();
    let intervals = spline.intervals();
    let checks = measure_joins(segments, &intervals, k);
    let given = job.given_points();
    let mut max_distance = 0.0f64;
    let point_reports: Vec<Value> = given
        .iter()
        .map(|g| {
            let u = g.index as f64 / n as f64;
            let d = distance(&segments[g.segment].eval(u), &g.point);
            max_distance = max_distance.max(d);
            json!({"kind": g.kind, "segment": g.segment, "u": u, "point": g.point, "distance": d})
        })
        .collect();
    let bspline = spline.to_bspline()?;
    let (knots, multiplicities) = bspline.knots_with_multiplicities();
    let direction = match job.options.direction {
        BuildDirection::Forward => "forward",
        BuildDirection::Backward => "backward",
    };
    let mirrored = job.options.derived == DerivedPoints::FarFromJoin;
    let json = json!({
        "operation": "spline",
        "degree": n,
        "continuity": k,
        "direction": direction,
        "mirrored": mirrored,
        "params": spline.params(),
        "segments": segments.iter().map(curve_json).collect::<Vec<_>>(),
        "on_curve_points": (0..spline.segment_count())
            .map(|i| spline.on_curve_points(i).chunks(spline.dim()).map(|c| c.to_vec()).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "bspline": {
            "degree": n,
            "knots": knots,
            "multiplicities": multiplicities,
            "poles": bspline.points().chunks(bspline.dim()).map(|c| c.to_vec()).collect::<Vec<_>>(),
        },
        "report": {
            "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
            "given_points": point_reports,
            "max_given_point_distance": max_distance,
            "library_continuity_residual": spline.max_continuity_residual(),
            "library_error_growth": spline.error_growth(),
            "library_relative_error_estimate": spline.relative_error_estimate(),
        }
    });

    let mut figure = Figure::new("Spline with control points on the curve");
    for (i, seg) in segments.iter().enumerate() {
        figure.curve(CurveItem::bezier(seg, Role::Result, format!("segment {i}")));
    }
    for g in given.iter().filter(|g| g.kind != "node") {
        figure.marker(Marker::new(
            MarkerKind::Constraint,
            &g.point,
            format!("u = {}/{n}", g.index),
        ));
    }
    for (i, node) in job.nodes.iter().enumerate() {
        figure.marker(Marker::new(MarkerKind::Join, node, format!("node {i}")));
    }
    figure.line(format!(
        "{} segments of degree {n}, C{k} promised at every node; built {direction}{}; {}",
        spline.segment_count(),
        if mirrored {
            ", mirrored (derived points far from the join)"
        } else {
            ""
        },
        if job.params.is_some() {
            "given parameters"
        } else {
            "chord-length parameters"
        },
    ));
    let worst_jump = worst(&checks);
    if !checks.is_empty() {
        let measured = checks.iter().filter_map(JoinCheck::measured_order).min();
        figure.line(format!(
            "Measured at all {} nodes: {} (worst promised relative jump {:.1e})",
            checks.len(),
            match measured {
                Some(m) if checks.iter().all(|c| c.measured_order().is_some()) => format!("C{m}"),
                _ => "not even C0".into(),
            },
            worst_jump
        ));
    }
    figure.line(format!(
        "Largest distance of a given on-curve point from its segment: {max_distance:.1e}"
    ));
    figure.line(format!(
        "B-spline form: interior knot multiplicity {}, library error estimate {:.1e}",
        n - k,
        spline.relative_error_estimate()
    ));
    Ok(Outcome {
        json,
        figure,
        summary: Summary {
            degree: n,
            worst_continuity_jump: Some(worst_jump),
            max_deviation: Some(max_distance),
            deviation_meaning: "given on-curve points at u = j/n",
        },
    })
}

/// A wave-like cubic C^1 job: nodes and inner points sampled from
/// `y = sin(x)` with x as the parameter.
fn wave_job(degree: usize, continuity: usize, node_count: usize) -> Value {
    let f = |x: f64| [x, x.sin()];
    let step = 1.2;
    let nodes: Vec<[f64; 2]> = (0..node_count).map(|i| f(i as f64 * step)).collect();
    let params: Vec<f64> = (0..node_count).map(|i| i as f64 * step).collect();
    let start: Vec<[f64; 2]> = (1..degree)
        .map(|j| f(step * j as f64 / degree as f64))
        .collect();
    let options = LagrangeOptions::default()
        .with_degree(degree)
        .with_continuity(continuity);
    let free = options.free_indices();
    let groups: Vec<Vec<[f64; 2]>> = (1..node_count - 1)
        .map(|s| {
            free.iter()
                .map(|&j| f(step * (s as f64 + j as f64 / degree as f64)))
                .collect()
        })
        .collect();
    json!({
        "nodes": nodes,
        "params": params,
        "degree": degree,
        "continuity": continuity,
        "direction": "forward",
        "mirrored": false,
        "start_inner": start,
        "free_inner": groups,
    })
}

/// The demo's spline scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    vec![
        Scenario {
            name: "spline-cubic-c1",
            operation: OperationKind::Spline,
            title: "Cubic C1 spline through points of a sine wave",
            description: "Six nodes and the inner points of y = sin(x): the paper's construction \
                          (cubic, C1, forwards, the u = 1/3 point of every later segment derived).",
            job: wave_job(3, 1, 6),
        },
        Scenario {
            name: "spline-quintic-c2",
            operation: OperationKind::Spline,
            title: "Degree-5 C2 spline through points of a sine wave",
            description: "Five nodes of y = sin(x); every later segment gets two free inner points, \
                          the two next to the join follow from C2.",
            job: wave_job(5, 2, 5),
        },
    ]
}
