//! `bezjoin fillet` with `"radius"`: the corner sized like the circular G1
//! fillet of radius `r` and rounded by a fair G^k blend
//! ([`bezjoin_core::fillet_radius`]; docs/mathematics.md, fillet by
//! radius). P and Q are cut where the arc of radius `r` touches them; a
//! blend of degree `2k + 1` joins the cuts with G^k and shape values chosen
//! for fairness (minimum of `L^3 int (dkappa/ds)^2 ds`).
//!
//! The tool re-measures: the turning angle at the corner and the tangent
//! length `r tan(theta / 2)` (the setback of the arc between lines), the
//! setbacks as arc lengths from the corner to the cuts, the distances of
//! the arc's centre from both cuts (`r`), and G^k at both joins from the
//! derivatives with respect to arc length ([`JoinCheck::geometric`]).
//!
//! With `"compare": true` (plane curves) the picture shows the same corner
//! rounded four ways side by side, each with its curvature comb and its
//! curvature along arc length below: the G1 arc of radius `r` (the
//! curvature jumps to `1/r`), the C^k fillet of the same setbacks with the
//! automatic scale (curvature continuous in the parameter's sense), and
//! the fair G2 and G3 blends by radius (the curvature rises smoothly from
//! the curves' own); the result's `comparison` lists their curvature
//! ranges, jumps and energies.

use bezjoin_core::{
    BezierCurve, Curve, CurveRef, FairnessReport, FilletOptions, Intersection, KnotSide,
    RadiusFillet, curvature_variation, fairness_report, fillet_at, fillet_radius,
};
use serde_json::{Value, json};

use crate::check::{JoinCheck, curve_json, derivatives, distance, worst};
use crate::curvature::{CurvatureProfile, PathPiece};
use crate::job::{JobError, ObjectReader};
use crate::ops::connect_geometric::{list, local_part, sampled_length};
use crate::ops::draw_part;
use crate::svg::{CurveItem, Figure, Marker, MarkerKind, Plot, PlotSeries, Role, Shape};
use crate::{CliError, Outcome, Summary};

/// Default of the job's `order` with `"radius"`: G2.
pub const DEFAULT_RADIUS_ORDER: usize = 2;

/// A rounding smaller than this fraction of the whole curves' extent has
/// its markers' labels in the caption instead of next to them.
const SMALL_ROUNDING: f64 = 0.15;

/// One corner rounded by radius as the tool re-measures it: the given
/// curves, the returned pieces around the corner and the library's data
/// (of [`fillet_radius`], or of one corner of
/// [`bezjoin_core::fillet_radius_chain`]).
pub(crate) struct RoundedCorner<'a> {
    /// The given curve before the corner.
    pub p: &'a Curve,
    /// The given curve after the corner.
    pub q: &'a Curve,
    /// The returned part of P, ending at the cut `u0`.
    pub p_kept: &'a Curve,
    /// The blend.
    pub blend: &'a BezierCurve,
    /// The returned part of Q, starting at the cut `v0`.
    pub q_kept: &'a Curve,
    /// The corner rounded.
    pub corner: &'a Intersection,
    /// The cut on P.
    pub u0: f64,
    /// The cut on Q.
    pub v0: f64,
    /// The arc's centre.
    pub arc_centre: &'a [f64],
    /// The library's largest distance of the blend from the arc's circle.
    pub arc_deviation: f64,
    /// Shape values at P.
    pub p_shape: &'a [f64],
    /// Shape values at Q.
    pub q_shape: &'a [f64],
    /// The library's fairness report of the blend.
    pub report: &'a FairnessReport,
}

impl<'a> RoundedCorner<'a> {
    /// The corner of a single fillet by radius.
    fn of_fillet(p: &'a Curve, q: &'a Curve, f: &'a RadiusFillet) -> Self {
        RoundedCorner {
            p,
            q,
            p_kept: &f.p_trimmed,
            blend: &f.blend,
            q_kept: &f.q_trimmed,
            corner: &f.corner,
            u0: f.u0,
            v0: f.v0,
            arc_centre: &f.arc_centre,
            arc_deviation: f.arc_deviation,
            p_shape: &f.p_shape,
            q_shape: &f.q_shape,
            report: &f.report,
        }
    }
}

/// What the tool measures of the corner and the cuts.
pub(crate) struct CornerMeasure {
    /// Angle between P's arriving and Q's leaving tangent at the corner.
    pub turning_angle: f64,
    /// `r tan(theta / 2)`.
    pub tangent_length: f64,
    /// Arc length along P from the cut to the corner.
    pub p_setback: f64,
    /// Arc length along Q from the corner to the cut.
    pub q_setback: f64,
    /// `|C - P(u0)|`, `|C - Q(v0)|`.
    pub centre_distances: [f64; 2],
    /// The corner is where P ends and Q starts.
    pub vertex: bool,
}

impl CornerMeasure {
    /// Measure `c` rounded with `radius`.
    pub(crate) fn new(c: &RoundedCorner, radius: f64) -> Self {
        let (p, q, x) = (c.p, c.q, c.corner);
        let tp = derivatives(p.into(), x.u, 1, KnotSide::Left);
        let tq = derivatives(q.into(), x.v, 1, KnotSide::Right);
        let dim = p.dim();
        let (a, b) = (&tp[dim..], &tq[dim..]);
        let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
        let na = a.iter().map(|x| x * x).sum::<f64>();
        let nb = b.iter().map(|x| x * x).sum::<f64>();
        let cross = (na * nb - dot * dot).max(0.0).sqrt();
        let turning_angle = cross.atan2(dot);
        let length = |c: &Curve, a: f64, b: f64| c.arc_length_default(a, b).unwrap_or(f64::NAN);
        CornerMeasure {
            turning_angle,
            tangent_length: radius * (0.5 * turning_angle).tan(),
            p_setback: length(p, c.u0, x.u),
            q_setback: length(q, x.v, c.v0),
            centre_distances: [
                distance(c.arc_centre, &p.eval(c.u0)),
                distance(c.arc_centre, &q.eval(c.v0)),
            ],
            vertex: x.u == p.domain().1 && x.v == q.domain().0,
        }
    }

    /// `vertex` or `crossing`.
    pub(crate) fn corner_kind(&self) -> &'static str {
        if self.vertex { "vertex" } else { "crossing" }
    }
}

/// The circular arc of radius `radius` about `centre` from `start` to
/// `end`, turning the way `tangent` (the direction at `start`) points:
/// the drawable arc and the job's `arc` form of it. Plane curves only.
pub(crate) fn arc_between(
    centre: &[f64],
    radius: f64,
    start: &[f64],
    end: &[f64],
    tangent: &[f64],
) -> (Shape, Value) {
    let a0 = (start[1] - centre[1]).atan2(start[0] - centre[0]);
    let a1 = (end[1] - centre[1]).atan2(end[0] - centre[0]);
    // Counter-clockwise when the tangent at the start is (-sin a0, cos a0).
    let ccw = -a0.sin() * tangent[0] + a0.cos() * tangent[1] > 0.0;
    let full = 2.0 * std::f64::consts::PI;
    let sweep = if ccw {
        (a1 - a0).rem_euclid(full)
    } else {
        -(a0 - a1).rem_euclid(full)
    };
    let shape = Shape::Arc {
        center: [centre[0], centre[1]],
        radius,
        start_angle: a0,
        sweep,
    };
    let form = if ccw {
        json!({"arc": {"centre": centre, "radius": radius,
                       "start_angle": a0, "end_angle": a0 + sweep}})
    } else {
        json!({"arc": {"centre": centre, "radius": radius, "y_axis": [0.0, -1.0],
                       "start_angle": -a0, "end_angle": -a0 - sweep}})
    };
    (shape, form)
}

/// The arc of radius `radius` of the corner `c` (drawable, and in the
/// job's `arc` form), for plane curves; `None` in space.
pub(crate) fn corner_arc(c: &RoundedCorner, radius: f64) -> Option<(Shape, Value)> {
    (c.p.dim() == 2).then(|| {
        let tangent = derivatives(c.p.into(), c.u0, 1, KnotSide::Left)[2..].to_vec();
        arc_between(
            c.arc_centre,
            radius,
            &c.p.eval(c.u0),
            &c.q.eval(c.v0),
            &tangent,
        )
    })
}

/// The G^k joins of the corner measured by the tool with derivatives with
/// respect to arc length ([`JoinCheck::geometric`]: point, unit tangent,
/// curvature vector, `dK/ds`, ...): from the returned pieces
/// (`P|R`, `R|Q` for `names` = `[P, R, Q]`), and from the original curves
/// at `u0`, `v0` (`P(u0)|R(0)`, `R(1)|Q(v0)`; a wrongly trimmed piece
/// would show).
pub(crate) fn measure_joins(
    c: &RoundedCorner,
    order: usize,
    [pn, rn, qn]: [&str; 3],
) -> [[JoinCheck; 2]; 2] {
    let (pt, qt) = (CurveRef::from(c.p_kept), CurveRef::from(c.q_kept));
    let r = CurveRef::from(c.blend);
    let pt_end = pt.domain().1;
    let qt_start = qt.domain().0;
    let (p, q) = (CurveRef::from(c.p), CurveRef::from(c.q));
    [
        [
            JoinCheck::geometric(
                format!("{pn}|{rn}"),
                (pt, pt_end),
                (r, 0.0),
                &[pt, r],
                order,
            ),
            JoinCheck::geometric(
                format!("{rn}|{qn}"),
                (r, 1.0),
                (qt, qt_start),
                &[r, qt],
                order,
            ),
        ],
        [
            JoinCheck::geometric(
                format!("{pn}(u0)|{rn}(0)"),
                (p, c.u0),
                (r, 0.0),
                &[pt, r],
                order,
            ),
            JoinCheck::geometric(
                format!("{rn}(1)|{qn}(v0)"),
                (r, 1.0),
                (q, c.v0),
                &[r, qt],
                order,
            ),
        ],
    ]
}

/// The report's fields of one corner: the library's (`arc_centre`,
/// `arc_deviation`, shape values, `fairness`) and the tool's measurements
/// (turning angle, tangent length, setbacks, centre distances, blend
/// length, the joins `[returned pieces, original curves]`).
pub(crate) fn corner_fields(
    c: &RoundedCorner,
    m: &CornerMeasure,
    [checks, original]: &[[JoinCheck; 2]; 2],
) -> serde_json::Map<String, Value> {
    let fairness = c.report;
    let fields = json!({
        "corner": m.corner_kind(),
        "arc_centre": c.arc_centre,
        "arc_deviation": c.arc_deviation,
        "p_shape": c.p_shape,
        "q_shape": c.q_shape,
        "fairness": {
            "energy": fairness.energy,
            "curvature_min": fairness.curvature_min,
            "curvature_max": fairness.curvature_max,
            "curvature_extrema": fairness.curvature_extrema,
        },
        "turning_angle": m.turning_angle,
        "tangent_length": m.tangent_length,
        "measured_p_setback": m.p_setback,
        "measured_q_setback": m.q_setback,
        "measured_centre_distances": m.centre_distances,
        "measured_length": sampled_length(c.blend),
        "measured_continuity": checks.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
        "measured_continuity_against_original_curves":
            original.iter().map(JoinCheck::to_json).collect::<Vec<_>>(),
    });
    match fields {
        Value::Object(map) => map,
        _ => unreachable!("json! of an object"),
    }
}

/// The corner `x` of `p` and `q` in the result: `u`, `v`, `point` and the
/// re-measured `|P(u) - Q(v)|` as `distance`.
pub(crate) fn crossing_json(p: &Curve, q: &Curve, x: &Intersection) -> Value {
    json!({"u": x.u, "v": x.v, "point": x.point, "distance": distance(&p.eval(x.u), &q.eval(x.v))})
}

/// `head` (an object) with the fields of `tail` added.
pub(crate) fn with_fields(mut head: Value, tail: serde_json::Map<String, Value>) -> Value {
    if let Value::Object(map) = &mut head {
        map.extend(tail);
    }
    head
}

/// The fields of a job by radius besides `radius` (already read): refuse
/// each of `refused` when given, naming it (`why`: what decides the
/// corner instead), and read `order` (default [`DEFAULT_RADIUS_ORDER`]).
pub(crate) fn read_radius_fields(
    obj: &ObjectReader,
    refused: &[&str],
    why: &str,
) -> Result<usize, JobError> {
    for key in refused {
        if let Some(f) = obj.optional(key) {
            return Err(JobError::new(
                f.path.clone(),
                format!(
                    "cannot be given together with \"radius\" (the arc of the radius sets the \
                     cuts, \"order\" the continuity G^k at both, and the shape values are \
                     chosen fair; {why})"
                ),
            ));
        }
    }
    Ok(obj
        .optional("order")
        .map(|f| f.count())
        .transpose()?
        .unwrap_or(DEFAULT_RADIUS_ORDER))
}

/// Refuse each of `keys` in a job without `"radius"`, naming it.
pub(crate) fn refuse_without_radius(obj: &ObjectReader, keys: &[&str]) -> Result<(), JobError> {
    for key in keys {
        if let Some(f) = obj.optional(key) {
            return Err(JobError::new(
                f.path.clone(),
                "is only used together with \"radius\"",
            ));
        }
    }
    Ok(())
}

/// One rounding of the corner in the comparison.
struct Variant {
    /// Short name: `G1 arc`, `C2, same setbacks`, `G3 by radius`.
    name: String,
    /// Legend text of the rounding.
    label: String,
    /// `kappa(s)` through the end of P, the rounding and the start of Q.
    profile: CurvatureProfile,
    /// The pieces drawn: P's end, the rounding, Q's start.
    pieces: Vec<PathPiece>,
    /// The result's entry.
    json: Value,
}

/// P's end before `u0` and Q's start after `v0`, each of arc length `lead`
/// (at most the curve's), for the comparison's panels and graphs.
fn local_pieces(p: &Curve, u0: f64, q: &Curve, v0: f64, lead: f64) -> (PathPiece, PathPiece) {
    let part = |c: &Curve, at: f64, backwards: bool, name: &str| {
        let shape = local_part(c, at, lead, backwards)
            .map(|part| Shape::curve(&part))
            .unwrap_or_else(|| Shape::curve(c));
        PathPiece::new(shape, Role::Input, name)
    };
    (part(p, u0, true, "P"), part(q, v0, false, "Q"))
}

impl Variant {
    fn new(
        name: String,
        label: String,
        (start, rounding, end): (PathPiece, PathPiece, PathPiece),
        mut json: Value,
    ) -> Self {
        let pieces = vec![start, rounding, end];
        let profile = CurvatureProfile::new(&pieces);
        let [lo, hi] = profile.range_of(1..2);
        json["name"] = json!(name);
        json["curvature_min"] = json!(lo);
        json["curvature_max"] = json!(hi);
        json["curvature_jumps"] = json!(profile.jumps());
        Variant {
            name,
            label,
            profile,
            pieces,
            json,
        }
    }

    /// A Bezier rounding: its curve, energy and extrema as well.
    fn bezier(
        name: String,
        label: String,
        role: Role,
        (p, u0, q, v0, lead): (&Curve, f64, &Curve, f64, f64),
        blend: &BezierCurve,
        mut json: Value,
    ) -> Self {
        let (start, end) = local_pieces(p, u0, q, v0, lead);
        let rounding = PathPiece::new(Shape::Bezier(blend.clone()), role, label.clone());
        let report = fairness_report(blend);
        json["u0"] = json!(u0);
        json["v0"] = json!(v0);
        json["rounding"] = curve_json(blend);
        json["energy"] = json!(curvature_variation(blend));
        json["curvature_extrema"] = json!(report.curvature_extrema);
        json["measured_length"] = json!(sampled_length(blend));
        Variant::new(name, label, (start, rounding, end), json)
    }
}

/// The four (or five) roundings of the corner of `f`: the arc, the C^k
/// fillet with the same setbacks and automatic scale, and the G^j blends
/// by radius for `j` in {2, 3, order}.
fn comparison(
    p: &Curve,
    q: &Curve,
    f: &RadiusFillet,
    radius: f64,
    order: usize,
    corner: &CornerMeasure,
) -> Result<Vec<Variant>, CliError> {
    let lead = corner.p_setback.max(corner.q_setback);
    let mut variants = Vec::new();
    // The G1 arc.
    let (arc, arc_form) = corner_arc(&RoundedCorner::of_fillet(p, q, f), radius)
        .ok_or_else(|| JobError::new("compare", "the comparison is drawn for plane curves"))?;
    let (p_end, q_start) = local_pieces(p, f.u0, q, f.v0, lead);
    let arc_label = format!("G1 circular arc, radius {radius}");
    variants.push(Variant::new(
        "G1 arc".into(),
        arc_label.clone(),
        (
            p_end,
            PathPiece::new(arc, Role::Reference, arc_label),
            q_start,
        ),
        json!({"continuity": "G1", "u0": f.u0, "v0": f.v0, "rounding": arc_form,
               "energy": Value::Null, "curvature_extrema": 0}),
    ));
    // The C^k fillet of the same setbacks, balanced scale (one `s` left the
    // shorter edge's end with a near-kink where the edges' lengths differ).
    let options =
        FilletOptions::new(corner.p_setback, corner.q_setback, order, order).with_balanced_scale();
    let c = fillet_at(p, q, &f.corner, &options)?;
    variants.push(Variant::bezier(
        format!("C{order}, same setbacks"),
        format!(
            "C{order} fillet, same setbacks, balanced scales {:.4} / {:.4}",
            c.p_scale, c.q_scale
        ),
        Role::Modified,
        (p, c.u0, q, c.v0, lead),
        &c.blend,
        json!({"continuity": format!("C{order}"), "p_scale": c.p_scale, "q_scale": c.q_scale}),
    ));
    // The fair G^j blends by radius.
    let mut orders = vec![2, 3, order];
    orders.sort_unstable();
    orders.dedup();
    for j in orders {
        let g = if j == order {
            f.clone()
        } else {
            fillet_radius(p, q, radius, j)?
        };
        variants.push(Variant::bezier(
            format!("G{j} by radius"),
            format!("G{j} blend by radius, degree {}", g.blend.degree()),
            Role::Result,
            (p, g.u0, q, g.v0, lead),
            &g.blend,
            json!({"continuity": format!("G{j}"), "p_shape": g.p_shape, "q_shape": g.q_shape,
                   "arc_deviation": g.arc_deviation}),
        ));
    }
    Ok(variants)
}

/// A copy of `shape` moved by `dx` along x.
fn shifted(shape: &Shape, dx: f64) -> Shape {
    let move_points = |points: &[f64], dim: usize| -> Vec<f64> {
        points
            .iter()
            .enumerate()
            .map(|(i, v)| if i % dim == 0 { v + dx } else { *v })
            .collect()
    };
    match shape {
        Shape::Bezier(c) => Shape::Bezier(
            BezierCurve::new(c.dim(), c.degree(), move_points(c.points(), c.dim()))
                .expect("a moved curve keeps its shape"),
        ),
        Shape::Nurbs(c) => {
            let poles: Vec<f64> = (0..c.point_count())
                .flat_map(|i| c.point(i).to_vec())
                .collect();
            let weights = c.is_rational().then(|| {
                (0..c.point_count())
                    .map(|i| c.weight(i))
                    .collect::<Vec<_>>()
            });
            Shape::Nurbs(
                bezjoin_core::NurbsCurve::new(
                    c.dim(),
                    c.degree(),
                    move_points(&poles, c.dim()),
                    weights,
                    c.knots().to_vec(),
                )
                .expect("a moved curve keeps its shape"),
            )
        }
        Shape::Arc {
            center,
            radius,
            start_angle,
            sweep,
        } => Shape::Arc {
            center: [center[0] + dx, center[1]],
            radius: *radius,
            start_angle: *start_angle,
            sweep: *sweep,
        },
    }
}

/// Model bounds `[min_x, min_y, max_x, max_y]` of the sampled pieces.
fn pieces_bounds<'a>(pieces: impl Iterator<Item = &'a PathPiece>) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for piece in pieces {
        for [p, _, _] in piece.shape.sample_jets(64) {
            b = [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ];
        }
    }
    b
}

/// The comparison picture: the variants side by side, each with its comb
/// and a label, and a row of `kappa(s)` graphs on one common range.
fn draw_comparison(figure: &mut Figure, variants: &[Variant], corner_point: &[f64]) {
    let [x0, _, x1, y1] = pieces_bounds(variants.iter().flat_map(|v| v.pieces.iter()));
    let width = (x1 - x0).max(corner_point[0] - x0).max(1e-9);
    let pitch = 1.7 * width;
    for (i, v) in variants.iter().enumerate() {
        let dx = i as f64 * pitch;
        for (j, piece) in v.pieces.iter().enumerate() {
            let label = if j == 1 {
                v.label.clone()
            } else {
                "P and Q near the corner".to_string()
            };
            figure.curve(CurveItem {
                shape: shifted(&piece.shape, dx),
                role: piece.role,
                label,
                polygon: j == 1 && piece.role != Role::Reference,
                comb: true,
            });
        }
        let at = |p: &[f64]| [p[0] + dx, p[1]];
        figure.marker(Marker::new(
            MarkerKind::Crossing,
            &at(corner_point),
            String::new(),
        ));
        let [first, _, _] = v.pieces[1].shape.jet(0.0);
        let [last, _, _] = v.pieces[1].shape.jet(1.0);
        figure.marker(Marker::new(MarkerKind::Join, &at(&first), String::new()));
        figure.marker(Marker::new(MarkerKind::Join, &at(&last), String::new()));
        figure.marker(Marker::new(
            MarkerKind::Label,
            &[x0 + dx, y1 + 0.12 * width],
            v.name.clone(),
        ));
    }
    let mut plots: Vec<Plot> = variants
        .iter()
        .map(|v| v.profile.plot(v.name.clone()))
        .collect();
    let [lo, hi] = variants
        .iter()
        .map(|v| v.profile.range_of(0..3))
        .fold([0.0f64, 0.0f64], |[lo, hi], [a, b]| [lo.min(a), hi.max(b)]);
    let pad = 0.06 * (hi - lo).max(1e-12);
    for plot in &mut plots {
        plot.y_range = Some([lo - pad, hi + pad]);
        plot.y_label = "kappa".into();
        plot.x_label = "s".into();
    }
    figure.plots = plots;
}

/// Run a fillet job by radius (`compare`: also the comparison).
pub fn run(
    p: &Curve,
    q: &Curve,
    radius: f64,
    order: usize,
    compare: bool,
) -> Result<Outcome, CliError> {
    if compare && p.dim() != 2 {
        return Err(JobError::new(
            "compare",
            format!(
                "the comparison is drawn for plane curves; these have dimension {}",
                p.dim()
            ),
        )
        .into());
    }
    let f = fillet_radius(p, q, radius, order)?;
    let corner = CornerMeasure::new(&RoundedCorner::of_fillet(p, q, &f), radius);
    let variants = if compare {
        Some(comparison(p, q, &f, radius, order, &corner)?)
    } else {
        None
    };
    Ok(outcome(
        p,
        q,
        &f,
        radius,
        order,
        &corner,
        variants.as_deref(),
    ))
}

fn outcome(
    p: &Curve,
    q: &Curve,
    f: &RadiusFillet,
    radius: f64,
    order: usize,
    corner: &CornerMeasure,
    variants: Option<&[Variant]>,
) -> Outcome {
    let rounded = RoundedCorner::of_fillet(p, q, f);
    let joins = measure_joins(&rounded, order, ["P", "R", "Q"]);
    let checks = &joins[0];
    let x = &f.corner;
    let length = sampled_length(&f.blend);
    let fairness = &f.report;
    let report = json!({
        "mode": "radius",
        "radius": radius,
        "order": order,
        "blend_degree": f.blend.degree(),
    });
    let mut json = json!({
        "operation": "fillet",
        "p_trimmed": curve_json(&f.p_trimmed),
        "blend": curve_json(&f.blend),
        "q_trimmed": curve_json(&f.q_trimmed),
        "u0": f.u0,
        "v0": f.v0,
        "crossing": crossing_json(p, q, x),
        "report": with_fields(report, corner_fields(&rounded, corner, &joins)),
    });
    if let Some(variants) = variants {
        json["comparison"] = variants.iter().map(|v| v.json.clone()).collect();
    }

    let mut figure = Figure::new("Rounded corner by radius");
    match variants {
        Some(variants) => draw_comparison(&mut figure, variants, &x.point),
        None => draw_single(&mut figure, p, q, f, radius, order, corner),
    }
    figure.line(format!(
        "Radius {radius}: turning angle {:.4} deg, tangent length r tan(theta/2) = {:.6}",
        corner.turning_angle.to_degrees(),
        corner.tangent_length,
    ));
    figure.line(format!(
        "Cuts where the arc touches: at arc lengths {:.6} (P) and {:.6} (Q) from the {}",
        corner.p_setback,
        corner.q_setback,
        if corner.vertex { "vertex" } else { "crossing" }
    ));
    figure.line(format!(
        "Arc centre ({}) at {:.6} and {:.6} from the cuts",
        f.arc_centre
            .iter()
            .map(|c| format!("{c:.4}"))
            .collect::<Vec<_>>()
            .join(", "),
        corner.centre_distances[0],
        corner.centre_distances[1],
    ));
    figure.line(format!(
        "Blend R: degree {} = 2k + 1, G{order} at both cuts; fair shape values at P {}, at Q {}",
        f.blend.degree(),
        list(&f.p_shape),
        list(&f.q_shape),
    ));
    figure.line(format!(
        "R: L^3 int (dkappa/ds)^2 ds = {:.4}; curvature {:.4} .. {:.4} (arc: {:.4}), interior extrema: {}",
        fairness.energy,
        fairness.curvature_min,
        fairness.curvature_max,
        1.0 / radius,
        fairness.curvature_extrema,
    ));
    figure.line(format!(
        "R: length {length:.4}; largest distance from the arc's circle {:.4}",
        f.arc_deviation
    ));
    for check in checks {
        figure.line(check.describe());
    }
    if let Some(variants) = variants {
        for v in variants {
            let jumps = v.profile.jumps();
            figure.line(format!(
                "{}: curvature {:.4} .. {:.4} on the rounding; jumps at the cuts {:.1e}, {:.1e}",
                v.name,
                v.json["curvature_min"].as_f64().unwrap_or(f64::NAN),
                v.json["curvature_max"].as_f64().unwrap_or(f64::NAN),
                jumps.first().copied().unwrap_or(f64::NAN).abs(),
                jumps.get(1).copied().unwrap_or(f64::NAN).abs(),
            ));
        }
    }
    Outcome {
        json,
        figure,
        summary: Summary {
            degree: f.blend.degree(),
            worst_continuity_jump: Some(worst(checks)),
            max_deviation: Some(f.arc_deviation),
            deviation_meaning: "distance of the blend from the circle of radius r",
        },
    }
}

/// The picture of one result: P and Q (kept parts over the given curves),
/// the blend, the arc of radius `r` (plane curves), the corner, the cuts
/// and the arc's centre, and `kappa(s)` of the blend and of the arc.
fn draw_single(
    figure: &mut Figure,
    p: &Curve,
    q: &Curve,
    f: &RadiusFillet,
    radius: f64,
    order: usize,
    corner: &CornerMeasure,
) {
    draw_part(figure, p, p.domain().0, f.u0, Role::Input, "P");
    draw_part(figure, q, f.v0, q.domain().1, Role::Input, "Q");
    figure.curve(CurveItem::bezier(
        &f.blend,
        Role::Result,
        format!(
            "blend R, degree {} (G{order} | G{order}), fair shape values",
            f.blend.degree()
        ),
    ));
    let start = p.eval(f.u0);
    let end = q.eval(f.v0);
    let arc = draw_arc(figure, &RoundedCorner::of_fillet(p, q, f), radius, true);
    // Between long curves the rounding is small in the picture: its
    // markers' labels would cover each other, so they go to the caption.
    let size = |pieces: &[PathPiece]| {
        let [a, b, c, d] = pieces_bounds(pieces.iter());
        (c - a).max(d - b)
    };
    let whole = size(&[
        PathPiece::new(Shape::curve(p), Role::Input, "P"),
        PathPiece::new(Shape::curve(q), Role::Input, "Q"),
    ]);
    let rounding = size(&[PathPiece::new(
        Shape::Bezier(f.blend.clone()),
        Role::Result,
        "R",
    )]);
    let labelled = rounding >= SMALL_ROUNDING * whole;
    let x = &f.corner;
    let corner_label = if corner.vertex { "vertex" } else { "X" };
    let markers = [
        (MarkerKind::Crossing, x.point.clone(), corner_label),
        (MarkerKind::Join, start, "P(u0)"),
        (MarkerKind::Join, end, "Q(v0)"),
        (MarkerKind::Centre, f.arc_centre.clone(), "arc centre"),
    ];
    for (kind, at, label) in markers {
        figure.marker(Marker::new(kind, &at, if labelled { label } else { "" }));
    }
    figure.line(format!(
        "Corner{} at P({:.4}) = Q({:.4}); cuts P(u0), u0 = {:.4}, and Q(v0), v0 = {:.4}",
        if corner.vertex { " (vertex)" } else { " X" },
        x.u,
        x.v,
        f.u0,
        f.v0,
    ));
    if !labelled {
        figure.line(
            "The rounding is small against the curves here: \"compare\": true draws it close up",
        );
    }
    if let Some(arc) = arc {
        let lead = corner.p_setback.max(corner.q_setback);
        let (p_end, q_start) = local_pieces(p, f.u0, q, f.v0, lead);
        let blend = CurvatureProfile::new(&[
            p_end.clone(),
            PathPiece::new(Shape::Bezier(f.blend.clone()), Role::Result, "blend R"),
            q_start,
        ]);
        let mut plot = blend.plot(
            "Curvature along arc length: end of P, blend R (red), start of Q; the arc (dashed)",
        );
        let s0 = blend.joins().first().copied().unwrap_or(0.0);
        plot.series.push(arc_series(arc, s0));
        figure.plot(plot);
    }
}

/// Draw the arc of radius `radius` of the corner `c` dashed, with its comb
/// (a constant band that jumps at its ends) when `comb`, for plane curves;
/// its shape.
pub(crate) fn draw_arc(
    figure: &mut Figure,
    c: &RoundedCorner,
    radius: f64,
    comb: bool,
) -> Option<Shape> {
    let (shape, _) = corner_arc(c, radius)?;
    figure.curve(CurveItem {
        shape: shape.clone(),
        role: Role::Reference,
        label: format!("circular arc of radius {radius} (G1: curvature jumps at its ends)"),
        polygon: false,
        comb,
    });
    Some(shape)
}

/// The arc's curvature along its arc length, starting at `s0` (where the
/// blend it is compared with starts in a graph), dashed.
pub(crate) fn arc_series(arc: Shape, s0: f64) -> PlotSeries {
    let profile = CurvatureProfile::new(&[PathPiece::new(arc, Role::Reference, "arc")]);
    PlotSeries {
        role: Role::Reference,
        label: "circular arc".into(),
        points: profile.pieces[0]
            .iter()
            .map(|&[s, k]| [s0 + s, k])
            .collect(),
    }
}

/// The demo's fillets by radius, each drawn as the comparison: the G1
/// arc, the C^k fillet of the same setbacks and the fair G2 and G3 blends.
pub fn demo_scenarios() -> Vec<crate::ops::Scenario> {
    use crate::ops::{OperationKind, Scenario};
    vec![
        Scenario {
            name: "fillet-radius-lines",
            operation: OperationKind::Fillet,
            title: "G2/G3 fillet by radius: two lines at 90 degrees, edges 40 and 20, radius 2",
            description: "The corner of a 40 long and a 20 long edge, sized like the circular \
                          fillet of radius 2 (cut 2 = r tan(45 deg) from the vertex), rounded \
                          four ways: the G1 arc (its curvature jumps from 0 to 1/r at both \
                          cuts), the C2 fillet of the same setbacks with the automatic scale \
                          (continuous curvature with two humps), and the fair G2 and G3 blends \
                          by radius (the curvature rises smoothly from 0 to one maximum). Below \
                          each: the curvature along arc length through the end of P, the \
                          rounding and the start of Q, on one common scale.",
            job: json!({
                "p": [[-40.0, 0.0], [0.0, 0.0]],
                "q": [[0.0, 0.0], [0.0, 20.0]],
                "radius": 2.0,
                "order": 2,
                "compare": true
            }),
        },
        Scenario {
            name: "fillet-radius-curved",
            operation: OperationKind::Fillet,
            title: "G2/G3 fillet by radius: the corner between two cubics, radius 0.5",
            description: "The crossing of the two cubics of the fillet scenarios, sized like the \
                          circular fillet of radius 0.5 (the arc touching both curves, found on \
                          their offset curves), rounded as the G1 arc, the C2 fillet of the same \
                          setbacks (automatic scale) and the fair G2 and G3 blends by radius. The \
                          G^k blends start from the curves' own (negative) curvature; the arc \
                          jumps.",
            job: json!({
                "p": [[-4.0, -0.5], [-2.5, 0.8], [-1.0, 0.6], [1.5, -0.2]],
                "q": [[0.2, -2.0], [-0.3, -0.5], [0.6, 1.2], [-0.2, 3.0]],
                "radius": 0.5,
                "order": 2,
                "compare": true
            }),
        },
    ]
}
