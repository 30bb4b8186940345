//! Fillets by radius with G^k blends (docs/mathematics.md#fillet-by-radius;
//! the specification's section 7): the corner is sized like the circular
//! G1 fillet of radius `r` in the same corner, and rounded by a G^k blend
//! with fair shape parameters.
//!
//! The arc's touching points `u_t` on `P` and `v_t` on `Q` are where the
//! offset curves at distance `r` on the inner side of the corner meet:
//! `P(u) + r N_P(u) = Q(v) + r N_Q(v)`, `N` the unit normal in the corner's
//! plane (spanned by the two tangents at the corner) on the side the path
//! turns to. Newton's method in `(u, v)` solves it from the touching points
//! of two straight edges with the corner's tangents (tangent length
//! `r tan(theta / 2)`, `theta` the turning angle). For lines this is the
//! arc itself; for curved edges it is the arc `ChFi2d` would build. Then
//! `P` is cut at `u_t`, `Q` at `v_t` (kinds and parameters kept) and
//! [`connect_geometric`] joins the cuts with G^k and fair shape values.

use crate::basis::KnotSide;
use crate::bezier::BezierCurve;
use crate::curve::{AsCurveRef, Curve, CurveJet, CurveRef};
use crate::error::{BezjoinError, Compact, Result, check_finite_scalar};
use crate::geometric::{FairnessReport, GeometricOptions, MAX_GEOMETRIC_ORDER, connect_geometric};
use crate::intersect::{IntersectOptions, Intersection, IntersectionKind, intersect};

use rayon::prelude::*;

use super::chain::{
    DEFAULT_PARALLEL_THRESHOLD, chain_crossing, chain_pieces, chain_refs, in_corner,
};
use super::first_crossing;

/// Newton steps of the touching-point search.
const TOUCH_NEWTON_STEPS: usize = 60;

/// A corner at a shared vertex when P's last and Q's first point are this
/// close, relative to the curves' coordinate scale (the contract's 1e-9).
pub const VERTEX_TOLERANCE: f64 = 1e-9;

/// Samples of the blend behind [`RadiusFillet::arc_deviation`].
pub const ARC_DEVIATION_SAMPLES: usize = 256;

/// Largest distance of a blend by radius from its arc, in units of `r`
/// ([`RadiusFillet::arc_deviation`]); beyond, the corner is refused.
pub const MAX_ARC_DEVIATION: f64 = 1.0;

/// Largest curvature of a blend by radius, in units of the larger of `1/r`
/// and the blend's end curvatures; beyond, the corner is refused.
pub const MAX_CURVATURE_RATIO: f64 = 4.0;

/// A corner rounded like the arc of radius `r`, with a G^k blend.
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusFillet {
    /// `P` on `[first, u_t]`, of P's kind and parameters.
    pub p_trimmed: Curve,
    /// The G^k blend.
    pub blend: BezierCurve,
    /// `Q` on `[v_t, last]`.
    pub q_trimmed: Curve,
    /// The corner rounded (the vertex, or the first crossing).
    pub corner: Intersection,
    /// The arc's touching point on `P`.
    pub u0: f64,
    /// The arc's touching point on `Q`.
    pub v0: f64,
    /// The arc's centre.
    pub arc_centre: Vec<f64>,
    /// Largest distance of the blend from the circle of the arc (sampled at
    /// [`ARC_DEVIATION_SAMPLES`]` + 1` parameters).
    pub arc_deviation: f64,
    /// Shape values used at `P` and `Q`.
    pub p_shape: Vec<f64>,
    /// Shape values used at `Q`.
    pub q_shape: Vec<f64>,
    /// Energy, curvature range and extrema of the blend.
    pub report: FairnessReport,
}

/// Orthonormal basis of the corner's plane and coordinates in it.
struct Plane {
    origin: Vec<f64>,
    e1: Vec<f64>,
    e2: Vec<f64>,
}

impl Plane {
    fn point(&self, x: &[f64]) -> [f64; 2] {
        let relative: Vec<f64> = x.iter().zip(&self.origin).map(|(a, o)| a - o).collect();
        self.vector(&relative)
    }

    fn vector(&self, x: &[f64]) -> [f64; 2] {
        let along = |e: &[f64]| x.iter().zip(e).map(|(a, b)| a * b).sum::<f64>();
        [along(&self.e1), along(&self.e2)]
    }

    fn lift(&self, p: [f64; 2]) -> Vec<f64> {
        (0..self.origin.len())
            .map(|c| self.origin[c] + p[0] * self.e1[c] + p[1] * self.e2[c])
            .collect()
    }
}

/// The offset point `C(u) + r N(u)` (plane coordinates) and its derivative
/// in `u`, `N` the left normal (the corner turns left in the plane's
/// orientation).
fn offset(curve: CurveRef, plane: &Plane, u: f64, r: f64, side: KnotSide) -> ([f64; 2], [f64; 2]) {
    let (jet, _) = curve.jet(u, 2, side);
    let row = |k: usize| -> Vec<f64> { jet.row(k).iter().copied().collect() };
    let x = plane.point(&row(0));
    let d1 = plane.vector(&row(1));
    let d2 = plane.vector(&row(2));
    let speed = (d1[0] * d1[0] + d1[1] * d1[1]).sqrt();
    let t = [d1[0] / speed, d1[1] / speed];
    let along = d2[0] * t[0] + d2[1] * t[1];
    let dt = [
        (d2[0] - along * t[0]) / speed,
        (d2[1] - along * t[1]) / speed,
    ];
    // N = (-t_y, t_x), dN/du = (-dt_y, dt_x)
    (
        [x[0] - r * t[1], x[1] + r * t[0]],
        [d1[0] - r * dt[1], d1[1] + r * dt[0]],
    )
}

/// Round the corner of `p` and `q` like the circular fillet of radius
/// `radius`, with a G^`order` blend of fair shape values (module
/// documentation). The corner is the shared vertex when P's last point is
/// Q's first point (within [`VERTEX_TOLERANCE`] of the coordinate scale),
/// else the first crossing. Planar curves (2D, or 3D curves whose corner
/// plane holds both arcs' touching points).
///
/// Errors: curves of different dimensions or dimension 1; `radius` not
/// finite and positive, `order` 0 or above [`MAX_GEOMETRIC_ORDER`]
/// (InvalidArgument naming them); no corner (NoIntersection, as
/// [`super::fillet`]), tangents parallel at the corner (NoIntersection:
/// nothing to round); an arc of that radius that does not fit on the
/// curves (InvalidArgument naming `radius`, with the touching point found
/// outside the curve); the touching points not found (IllConditioned); the
/// errors of [`connect_geometric`].
pub fn fillet_radius<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    radius: f64,
    order: usize,
) -> Result<RadiusFillet> {
    let (p, q) = (p.into(), q.into());
    let scale = check_arguments(p, q, radius, order)?;
    let corner = match vertex_corner(p, q, scale) {
        Ok(corner) => corner,
        Err(gap) => first_crossing(&intersect(p, q, &IntersectOptions::default())?)
            .map_err(|e| note_near_vertex(e, gap, scale))?,
    };
    let (rounded, blend) = round_radius_corner(p, q, corner, radius, order, scale)?;
    let (p_first, _) = p.domain();
    let (_, q_last) = q.domain();
    // A radius whose arc uses a whole side leaves a few ulps of it: refused,
    // as in a chain (user testing, session 39: a 3.55e-15 mm edge).
    let what = "the arc's touching point leaves";
    super::chain::check_kept_piece(p, "p", what, p.domain(), (p_first, rounded.u0))?;
    super::chain::check_kept_piece(q, "q", what, q.domain(), (rounded.v0, q_last))?;
    Ok(RadiusFillet {
        p_trimmed: p.segment(p_first, rounded.u0)?,
        blend,
        q_trimmed: q.segment(rounded.v0, q_last)?,
        corner: rounded.corner,
        u0: rounded.u0,
        v0: rounded.v0,
        arc_centre: rounded.arc_centre,
        arc_deviation: rounded.arc_deviation,
        p_shape: rounded.p_shape,
        q_shape: rounded.q_shape,
        report: rounded.report,
    })
}

/// Check the arguments of a fillet by radius; the curves' coordinate scale.
fn check_arguments(p: CurveRef, q: CurveRef, radius: f64, order: usize) -> Result<f64> {
    if q.dim() != p.dim() {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: p.dim(),
            actual: q.dim(),
        });
    }
    if p.dim() < 2 {
        return Err(BezjoinError::invalid(
            "p",
            "a fillet needs dimension 2 or more",
        ));
    }
    check_finite_scalar("radius", radius)?;
    if radius <= 0.0 {
        return Err(BezjoinError::invalid(
            "radius",
            format!("{} must be positive", Compact(radius)),
        ));
    }
    if order == 0 || order > MAX_GEOMETRIC_ORDER {
        return Err(BezjoinError::invalid(
            "order",
            format!("{order} is not a geometric order 1..={MAX_GEOMETRIC_ORDER}"),
        ));
    }
    let scale = p
        .coordinate_scale()
        .max(q.coordinate_scale())
        .max(f64::MIN_POSITIVE);
    // A radius within the vertex tolerance of the coordinates cannot be
    // told from the corner itself; its blend was an edge of 1.65e-12 mm
    // (user testing, session 39).
    if radius <= VERTEX_TOLERANCE * scale {
        return Err(super::below_vertex_tolerance(
            "radius", radius, scale, "the arc",
        ));
    }
    Ok(scale)
}

/// The shared vertex as the corner, when P's last point is Q's first
/// (within [`VERTEX_TOLERANCE`] of `scale`); otherwise the distance
/// between them.
fn vertex_corner(p: CurveRef, q: CurveRef, scale: f64) -> std::result::Result<Intersection, f64> {
    let (_, p_last) = p.domain();
    let (q_first, _) = q.domain();
    let end = p.eval(p_last);
    let start = q.eval(q_first);
    let gap = crate::bezier::distance(&end, &start);
    if gap <= VERTEX_TOLERANCE * scale {
        Ok(Intersection {
            u: p_last,
            v: q_first,
            point: end,
            distance: gap,
            kind: IntersectionKind::Crossing,
        })
    } else {
        Err(gap)
    }
}

/// A corner without a crossing whose P ends near Q's start (within 1e-3 of
/// the coordinate scale) but farther than the vertex tolerance: the
/// NoIntersection message says how far apart the ends are and what a
/// shared vertex needs (a sketch's ends that missed by a little).
fn note_near_vertex(error: BezjoinError, gap: f64, scale: f64) -> BezjoinError {
    match error {
        BezjoinError::NoIntersection { reason } if gap <= 1e-3 * scale => {
            BezjoinError::NoIntersection {
                reason: format!(
                    "{reason} (P ends {gap:e} from Q's start; a shared vertex needs at most \
                     {:e}, {VERTEX_TOLERANCE:e} of the coordinate scale {scale:e})",
                    VERTEX_TOLERANCE * scale
                ),
            }
        }
        other => other,
    }
}

/// Round `corner` of `p` and `q` (module documentation): the corner's data
/// and the blend.
fn round_radius_corner(
    p: CurveRef,
    q: CurveRef,
    corner: Intersection,
    radius: f64,
    order: usize,
    scale: f64,
) -> Result<(RadiusCorner, BezierCurve)> {
    // The radius as messages print it (1e300 in exponent form, not 301 digits).
    let shown = Compact(radius);
    let (p_first, _) = p.domain();
    let (_, q_last) = q.domain();
    // The corner's plane: P's arriving tangent and Q's leaving one.
    let (pj, _) = p.jet(corner.u, 1, KnotSide::Left);
    let (qj, _) = q.jet(corner.v, 1, KnotSide::Right);
    let unit = |v: Vec<f64>| -> Option<Vec<f64>> {
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (n > 0.0 && n.is_finite()).then(|| v.iter().map(|x| x / n).collect())
    };
    let no_corner = |why: &str| BezjoinError::NoIntersection {
        reason: format!(
            "no corner to round at u = {}, v = {}: {why}",
            corner.u, corner.v
        ),
    };
    let tp = unit(pj.row(1).iter().copied().collect())
        .ok_or_else(|| no_corner("P's tangent is zero"))?;
    let tq = unit(qj.row(1).iter().copied().collect())
        .ok_or_else(|| no_corner("Q's tangent is zero"))?;
    let cos = tp.iter().zip(&tq).map(|(a, b)| a * b).sum::<f64>();
    let e2 = unit(tq.iter().zip(&tp).map(|(b, a)| b - cos * a).collect())
        .filter(|_| (1.0 - cos.abs()) > 1e-12)
        .ok_or_else(|| no_corner("the tangents are parallel"))?;
    let plane = Plane {
        origin: corner.point.clone(),
        e1: tp.clone(),
        e2,
    };
    let theta = (tq.iter().zip(&plane.e2).map(|(a, b)| a * b).sum::<f64>()).atan2(cos);
    let tangent_length = radius * (0.5 * theta).tan();
    let p_speed = pj.row(1).norm();
    let q_speed = qj.row(1).norm();
    let mut u = (corner.u - tangent_length / p_speed).max(p_first);
    let mut v = (corner.v + tangent_length / q_speed).min(q_last);
    // Newton on F(u, v) = P(u) + r N_P(u) - Q(v) - r N_Q(v) (plane coordinates).
    let tolerance = 1e-12 * scale.max(radius);
    let mut converged = false;
    for _ in 0..TOUCH_NEWTON_STEPS {
        let (fp, dp) = offset(p, &plane, u, radius, KnotSide::Left);
        let (fq, dq) = offset(q, &plane, v, radius, KnotSide::Right);
        let f = [fp[0] - fq[0], fp[1] - fq[1]];
        if (f[0] * f[0] + f[1] * f[1]).sqrt() <= tolerance {
            converged = true;
            break;
        }
        // [dp, -dq] [du, dv]^T = -f
        let det = dp[0] * (-dq[1]) - (-dq[0]) * dp[1];
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let du = (-f[0] * (-dq[1]) + dq[0] * (-f[1])) / det;
        let dv = (dp[0] * (-f[1]) - dp[1] * (-f[0])) / det;
        u = (u + du).clamp(p_first, corner.u);
        v = (v + dv).clamp(corner.v, q_last);
        if !(u.is_finite() && v.is_finite()) {
            break;
        }
    }
    if !converged && (u <= p_first || v >= q_last) {
        return Err(BezjoinError::invalid(
            "radius",
            format!(
                "the arc of radius {shown} does not fit: its touching point would lie beyond \
                 {} (the search stopped at u = {u}, v = {v})",
                if u <= p_first { "P's start" } else { "Q's end" }
            ),
        ));
    }
    if !converged {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "fillet by radius: the touching points of the arc of radius {shown} were not \
                 found (Newton on the offset curves did not converge; the arc may not fit)"
            ),
            estimate: f64::INFINITY,
            limit: tolerance,
        });
    }
    if u <= p_first || u >= corner.u {
        return Err(BezjoinError::invalid(
            "radius",
            format!(
                "the arc of radius {shown} would touch P at u = {u}, outside (first = \
                 {p_first}, corner = {}): it does not fit",
                corner.u
            ),
        ));
    }
    if v >= q_last || v <= corner.v {
        return Err(BezjoinError::invalid(
            "radius",
            format!(
                "the arc of radius {shown} would touch Q at v = {v}, outside (corner = {}, \
                 last = {q_last}): it does not fit",
                corner.v
            ),
        ));
    }
    let (centre_plane, _) = offset(p, &plane, u, radius, KnotSide::Left);
    let arc_centre = plane.lift(centre_plane);
    let g = connect_geometric(&p, u, &q, v, &GeometricOptions::new(order, order))?;
    // The samples in one batch evaluation (the bits of `eval` at each
    // parameter, no allocation per sample).
    let ts: Vec<f64> = (0..=ARC_DEVIATION_SAMPLES)
        .map(|i| i as f64 / ARC_DEVIATION_SAMPLES as f64)
        .collect();
    let mut samples = vec![0.0; ts.len() * g.curve.dim()];
    g.curve.eval_many_into(&ts, &mut samples);
    let arc_deviation = samples
        .chunks_exact(g.curve.dim())
        .map(|x| (crate::bezier::distance(x, &arc_centre) - radius).abs())
        .fold(0.0f64, f64::max);
    check_blend_follows_the_arc(&g, radius, arc_deviation)?;
    Ok((
        RadiusCorner {
            corner,
            u0: u,
            v0: v,
            arc_centre,
            arc_deviation,
            p_shape: g.p_shape,
            q_shape: g.q_shape,
            report: g.report,
        },
        g.curve,
    ))
}

/// A blend "sized like the arc" strays from it by at most
/// [`MAX_ARC_DEVIATION`] `r` (lines at every angle: 0.503 r at most, for a
/// 177-degree turn) and bends at most [`MAX_CURVATURE_RATIO`] times the
/// larger of `1/r` and its own end curvatures (those of the inputs, for
/// G2 and above; lines at every angle: 1.53 at most). A blend beyond
/// either is not a rounded corner: a loop around a second crossing of the
/// curves near the vertex (18.9 r away), or a turn of more than 180 degrees
/// through a curvature peak of 17.6 / r (user testing, session 39). Such a
/// corner is IllConditioned, with the larger of the two ratios as the
/// estimate, instead of an answer that looks valid.
fn check_blend_follows_the_arc(
    g: &crate::geometric::GeometricConnection,
    radius: f64,
    arc_deviation: f64,
) -> Result<()> {
    let end_curvature = |t: f64| crate::geometric::curvature_at(&g.curve, t);
    let reference = (1.0 / radius)
        .max(end_curvature(0.0))
        .max(end_curvature(1.0));
    let peak = g
        .report
        .curvature_max
        .abs()
        .max(g.report.curvature_min.abs());
    let bending = peak / (MAX_CURVATURE_RATIO * reference);
    let straying = arc_deviation / (MAX_ARC_DEVIATION * radius);
    let worst = bending.max(straying);
    if worst <= 1.0 {
        return Ok(());
    }
    Err(BezjoinError::IllConditioned {
        what: format!(
            "fillet by radius: the blend does not follow the arc of radius {radius:.6e}: it strays \
             {arc_deviation:.3e} from it ({:.3} r, at most {MAX_ARC_DEVIATION} r) and bends to \
             curvature {peak:.3e} ({:.3} times the larger of 1/r and its end curvatures, at \
             most {MAX_CURVATURE_RATIO}); the curves may cross again near the corner or turn \
             by more than 180 degrees there (a smaller radius may fit)",
            arc_deviation / radius,
            peak / reference,
        ),
        estimate: worst,
        limit: 1.0,
    })
}

/// One corner of a chain rounded by radius ([`fillet_radius_chain`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusCorner {
    /// The corner rounded (the shared vertex, or the crossing nearest the
    /// curves' shared end).
    pub corner: Intersection,
    /// The arc's touching point on the corner's first curve (its cut).
    pub u0: f64,
    /// The arc's touching point on the corner's second curve (its cut).
    pub v0: f64,
    /// The arc's centre.
    pub arc_centre: Vec<f64>,
    /// Largest distance of the blend from the arc's circle (as
    /// [`RadiusFillet::arc_deviation`]).
    pub arc_deviation: f64,
    /// Shape values used at the first curve.
    pub p_shape: Vec<f64>,
    /// Shape values used at the second curve.
    pub q_shape: Vec<f64>,
    /// Energy, curvature range and extrema of the blend.
    pub report: FairnessReport,
}

/// A chain with every corner rounded by radius.
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusChainFillet {
    /// In path order, as [`super::ChainFillet::pieces`]: trimmed curve 0,
    /// blend 0, trimmed curve 1, ...; `2n - 1` pieces for an open chain of
    /// `n` curves, `2n` for a closed one. Trimmed curves keep their kind
    /// and parameters; blends are Bezier curves.
    pub pieces: Vec<Curve>,
    /// Corner `i`, between `curves[i]` and `curves[(i + 1) % n]`.
    pub corners: Vec<RadiusCorner>,
}

/// Round every corner of the chain `curves` (a wire: open, or `closed`
/// with one more corner from the last curve to the first) like the
/// circular fillet of radius `radius`, each with a G^`order` blend of fair
/// shape values, as [`fillet_radius`] rounds one corner. Corner `i` is the
/// shared vertex of `curves[i]` and `curves[i + 1]` when they meet there
/// (within [`VERTEX_TOLERANCE`]), else their crossing nearest the shared
/// end (as [`super::fillet_chain`] chooses it). Corners are independent;
/// above [`super::DEFAULT_PARALLEL_THRESHOLD`] of them they are computed in
/// parallel (the same result bit for bit).
///
/// Errors: fewer than 2 curves, different dimensions (naming `curves[i]`);
/// the errors of [`fillet_radius`] at a corner (InvalidArgument names
/// `corner i radius`, the other messages start with `corner i`); two
/// touching points on one curve that pass each other (InvalidArgument
/// naming the curve: the radius is too large for it). Every join must be a
/// corner: one where the curves meet tangent (a slot's line into its arc)
/// has nothing to round and is NoIntersection naming it, so a wire with
/// tangent joins is rounded in its runs between them (the FreeCAD
/// workbench does so, leaving joins that turn by less than 1e-3 degrees).
///
/// ```
/// use bezjoin_core::{BezierCurve, fillet_radius_chain};
/// // A closed square of side 4, every corner rounded with radius 1.
/// let side = |a: [f64; 2], b: [f64; 2]| BezierCurve::from_rows(&[a, b]).unwrap();
/// let square = [
///     side([0.0, 0.0], [4.0, 0.0]),
///     side([4.0, 0.0], [4.0, 4.0]),
///     side([4.0, 4.0], [0.0, 4.0]),
///     side([0.0, 4.0], [0.0, 0.0]),
/// ];
/// let rounded = fillet_radius_chain(&square, 1.0, 2, true).unwrap();
/// assert_eq!(rounded.pieces.len(), 8);
/// // Each side keeps its middle 2 units: the arcs touch 1 from each vertex.
/// assert!((rounded.corners[0].u0 - 0.75).abs() < 1e-12);
/// ```
pub fn fillet_radius_chain<C: AsCurveRef + Sync>(
    curves: &[C],
    radius: f64,
    order: usize,
    closed: bool,
) -> Result<RadiusChainFillet> {
    let curves = chain_refs(curves)?;
    let n = curves.len();
    check_arguments(curves[0], curves[1], radius, order)?;
    let corner_count = if closed { n } else { n - 1 };
    let one = |i: usize| -> Result<(RadiusCorner, BezierCurve)> {
        let (p, q) = (curves[i], curves[(i + 1) % n]);
        let scale = p
            .coordinate_scale()
            .max(q.coordinate_scale())
            .max(f64::MIN_POSITIVE);
        let corner = match vertex_corner(p, q, scale) {
            Ok(corner) => corner,
            Err(gap) => chain_crossing(i, p, q, &IntersectOptions::default())
                .map_err(|e| note_near_vertex(e, gap, scale))?,
        };
        round_radius_corner(p, q, corner, radius, order, scale).map_err(|e| in_corner(e, i))
    };
    let results: Vec<Result<(RadiusCorner, BezierCurve)>> =
        if corner_count > DEFAULT_PARALLEL_THRESHOLD {
            (0..corner_count).into_par_iter().map(one).collect()
        } else {
            (0..corner_count).map(one).collect()
        };
    let mut corners = Vec::with_capacity(corner_count);
    let mut blends = Vec::with_capacity(corner_count);
    for r in results {
        let (corner, blend) = r?;
        corners.push(corner);
        blends.push(blend);
    }
    let cuts: Vec<(f64, f64)> = corners.iter().map(|c| (c.u0, c.v0)).collect();
    let blend_refs: Vec<&BezierCurve> = blends.iter().collect();
    let pieces = chain_pieces(&curves, closed, &cuts, &blend_refs)?;
    Ok(RadiusChainFillet { pieces, corners })
}
