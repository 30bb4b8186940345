//! Rounding the corner between two crossing curves (docs/mathematics.md#fillet;
//! Krivosheev, Mavrin, Starkova, *Bezier curve conjugation for
//! smooth curve joining and corner rounding*, Omsk Scientific Bulletin, 2025,
//! Fig. 2).
//!
//! `P` and `Q` cross at `X = P(u*) = Q(v*)`. The corner of the path "along
//! `P` up to `X`, then along `Q`" is rounded by keeping `P` on `[a, u0]`,
//! `Q` on `[v0, b]` (`[a, ..]` is P's domain, `[.., b]` Q's: `[0, 1]` for a
//! Bezier curve) and joining `P(u0)` to `Q(v0)` with the connecting curve
//! of section 1 ([`crate::connect::connect`]). The setbacks are arc lengths
//! measured from `X`: `len(P; u0..u*) = dp`, `len(Q; v*..v0) = dq`
//! (symmetric when `dp = dq`); `u0`, `v0` come from
//! [`BezierCurve::param_at_length`] / [`NurbsCurve::param_at_length`].
//!
//! P and Q may be Bezier or NURBS curves (docs/mathematics.md#nurbs-curves): the
//! trimmed pieces keep the input's kind, a NURBS piece its parameters
//! (knot insertion, exact); the blend is a Bezier curve. P's derivatives
//! at `u0` are taken from the left of a knot, Q's at `v0` from the right.
//! The orders `kp`, `kq` may exceed the degrees, as for connect. A corner
//! at a shared vertex (P ends where Q starts: a wire, a sketch) is
//! [`fillet_vertex`].
//!
//! # Guarantee
//! The three pieces `P|[a,u0]`, `R`, `Q|[v0,b]` form a C^k B-spline with
//! knot intervals `(u0 - a, alpha, (b - v0) alpha / beta)` ([`Fillet::to_bspline`]):
//! derivatives `0..=kp` agree at the first join and `0..=kq` at the second,
//! to the connect solver's checked residual (`CONNECT_RESIDUAL_LIMIT`,
//! relative). The setback lengths hold to the arc-length accuracy
//! (`relative_length_accuracy * setback`).
//!
//! # Other corners
//! A crossing has four corners; this module rounds the one between the part
//! of `P` before `X` and the part of `Q` after it. The others are reached by
//! reversing inputs: `fillet(&p, &q.reverse(), ..)` keeps the part of `Q`
//! before `X` (and the trimmed `Q` comes out reversed), `fillet(&p.reverse(),
//! &q, ..)` keeps the part of `P` after `X`, and so on.
//!
//! ```
//! use bezjoin_core::BezierCurve;
//! use bezjoin_core::{FilletOptions, fillet};
//! // Two lines crossing at the origin.
//! let p = BezierCurve::from_rows(&[[-2.0, 0.0], [2.0, 0.0]]).unwrap();
//! let q = BezierCurve::from_rows(&[[0.0, -2.0], [0.0, 2.0]]).unwrap();
//! let options = FilletOptions::symmetric(0.5, 1);
//! let near = |a: &[f64], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12;
//! // Corner between P before X (x < 0) and Q after X (y > 0).
//! let a = fillet(&p, &q, &options).unwrap();
//! assert!(near(a.blend.point(0), [-0.5, 0.0]) && near(a.blend.point(3), [0.0, 0.5]));
//! // Corner between P before X and Q before X (y < 0): reverse Q.
//! let b = fillet(&p, &q.reverse(), &options).unwrap();
//! assert!(near(b.blend.point(3), [0.0, -0.5]));
//! // Corner between P after X (x > 0) and Q after X: reverse P.
//! let c = fillet(&p.reverse(), &q, &options).unwrap();
//! assert!(near(c.blend.point(0), [0.5, 0.0]));
//! ```

mod chain;
use chain::SLIVER;
mod deviation;
mod radius;

pub use chain::{
    ChainCorner, ChainFillet, ChainFilletOptions, DEFAULT_PARALLEL_THRESHOLD, fillet_chain,
};
pub use deviation::{
    DEFAULT_RELATIVE_DEVIATION_ACCURACY, DEVIATION_SCALE_STEPS, DEVIATION_SCALE_TOLERANCE,
    DeviationFillet, DeviationFilletOptions, distance_to_curve, fillet_within_deviation,
};
pub use radius::{
    ARC_DEVIATION_SAMPLES, MAX_ARC_DEVIATION, MAX_CURVATURE_RATIO, RadiusChainFillet, RadiusCorner,
    RadiusFillet, VERTEX_TOLERANCE, fillet_radius, fillet_radius_chain,
};

use crate::arclength::ArcLengthInverse;
use crate::bezier::BezierCurve;
use crate::connect::{ConnectOptions, Connection, ShapeScale, connect};
use crate::curve::{Curve, CurveRef};
use crate::error::{BezjoinError, Compact, Result, check_finite_scalar, check_positive};
use crate::intersect::{IntersectOptions, Intersection, IntersectionKind, intersect};
use crate::nurbs::NurbsCurve;

/// Default of [`FilletOptions::relative_length_accuracy`].
pub const DEFAULT_RELATIVE_LENGTH_ACCURACY: f64 = 1e-12;

/// Options of [`fillet`]. Build with [`FilletOptions::new`] or
/// [`FilletOptions::symmetric`]; the other fields have documented defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct FilletOptions {
    /// `dp > 0`: arc length along `P` back from the crossing.
    pub p_setback: f64,
    /// `dq > 0`: arc length along `Q` on from the crossing.
    pub q_setback: f64,
    /// `kp`: continuity order at `P(u0)` (any order: above a polynomial's
    /// degree its derivatives are 0).
    pub p_order: usize,
    /// `kq`: continuity order at `Q(v0)` (any order).
    pub q_order: usize,
    /// The blend's shape scales `alpha`, `beta` ([`ShapeScale`]); default
    /// `Given { p: 1.0, q: 1.0 }`, the paper. With scale 1 a blend whose ends
    /// move fast (`|P'(u0)|` large against the setback) puts its inner
    /// control points past the corner and can loop; [`ShapeScale::Auto`]
    /// keeps them near the natural `|R(1) - R(0)| / |P'(u0)|`. The scales
    /// used are reported in [`Fillet::p_scale`] and [`Fillet::q_scale`].
    pub scale: ShapeScale,
    /// The setbacks are met to `relative_length_accuracy * setback`;
    /// default [`DEFAULT_RELATIVE_LENGTH_ACCURACY`] (`1e-12`).
    pub relative_length_accuracy: f64,
    /// How the crossing is found; default [`IntersectOptions::default`].
    pub intersect: IntersectOptions,
}

impl FilletOptions {
    /// Setbacks `dp`, `dq`, orders `kp`, `kq`; scales 1 (the paper).
    pub fn new(p_setback: f64, q_setback: f64, p_order: usize, q_order: usize) -> Self {
        Self {
            p_setback,
            q_setback,
            p_order,
            q_order,
            scale: ShapeScale::default(),
            relative_length_accuracy: DEFAULT_RELATIVE_LENGTH_ACCURACY,
            intersect: IntersectOptions::default(),
        }
    }

    /// Symmetric rounding: `dp = dq = setback`, `kp = kq = order`.
    pub fn symmetric(setback: f64, order: usize) -> Self {
        Self::new(setback, setback, order, order)
    }

    /// The same options with scales `alpha`, `beta`.
    pub fn with_scales(mut self, p_scale: f64, q_scale: f64) -> Self {
        self.scale = ShapeScale::Given {
            p: p_scale,
            q: q_scale,
        };
        self
    }

    /// The same options with the scale chosen for fairness ([`ShapeScale::Auto`]).
    pub fn with_auto_scale(mut self) -> Self {
        self.scale = ShapeScale::Auto;
        self
    }

    /// The same options with both ends of the blend at one fair speed
    /// ([`ShapeScale::Balanced`]): the blend does not depend on how fast
    /// either curve runs in its own parameter.
    pub fn with_balanced_scale(mut self) -> Self {
        self.scale = ShapeScale::Balanced;
        self
    }
}

/// A rounded corner: `P|[a,u0]`, the blend `R`, `Q|[v0,b]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Fillet {
    /// `P` on `[a, u0]`: a Bezier `P` reparametrised to `[0, 1]`, a NURBS
    /// `P` with its own parameters (domain `[a, u0]`).
    pub p_trimmed: Curve,
    /// The connecting curve `R` of degree `kp + kq + 1`.
    pub blend: BezierCurve,
    /// `Q` on `[v0, b]`, of Q's kind as `p_trimmed` is of P's.
    pub q_trimmed: Curve,
    /// The crossing that was rounded.
    pub crossing: Intersection,
    /// Where `P` is cut.
    pub u0: f64,
    /// Where `Q` is cut.
    pub v0: f64,
    /// `alpha` used.
    pub p_scale: f64,
    /// `beta` used.
    pub q_scale: f64,
    /// The connect solver's worst relative residual of the end conditions.
    pub max_residual: f64,
}

impl Fillet {
    /// Knot intervals `(u0 - a, alpha, (b - v0) alpha / beta)` of the C^k
    /// chain (`[a, u0]` and `[v0, b]` the trimmed pieces' domains; for
    /// Bezier curves `(u0, alpha, (1 - v0) alpha / beta)`).
    pub fn knot_intervals(&self) -> [f64; 3] {
        let (a, _) = match &self.p_trimmed {
            Curve::Bezier(_) => (0.0, 1.0),
            Curve::Nurbs(_) => self.p_trimmed.domain(),
        };
        let b = match &self.q_trimmed {
            Curve::Bezier(_) => 1.0,
            Curve::Nurbs(_) => self.q_trimmed.domain().1,
        };
        [
            self.u0 - a,
            self.p_scale,
            (b - self.v0) * self.p_scale / self.q_scale,
        ]
    }

    /// The three pieces as one B-spline (NURBS when a piece is rational)
    /// with [`Self::knot_intervals`].
    pub fn to_bspline(&self) -> Result<NurbsCurve> {
        NurbsCurve::from_curve_chain(
            &[
                (&self.p_trimmed).into(),
                (&self.blend).into(),
                (&self.q_trimmed).into(),
            ],
            &self.knot_intervals(),
        )
    }
}

/// Round the corner at the first crossing of `p` and `q` (smallest `u` on
/// `P`; touching points and overlaps are skipped). `p`, `q`: Bezier or
/// NURBS curves (`&BezierCurve`, `&NurbsCurve`, `&Curve`).
///
/// Errors (each names the argument): curves of different dimensions;
/// non-finite or non-positive setback, scale or accuracy; no crossing, or
/// only touching points (NoIntersection, saying which); a setback not
/// shorter than the part of the curve before / after the crossing
/// (InvalidArgument naming `p_setback` / `q_setback` with both lengths);
/// an ill-conditioned connection (IllConditioned, from the connect solver).
pub fn fillet<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    options: &FilletOptions,
) -> Result<Fillet> {
    let (p, q) = (p.into(), q.into());
    validate(p, q, options)?;
    let mut hits = intersect(p, q, &options.intersect)?;
    // The first crossing, taken out of the hits (not copied).
    let crossing = match hits
        .iter()
        .position(|h| h.kind == IntersectionKind::Crossing)
    {
        Some(first) => hits.swap_remove(first),
        None => first_crossing(&hits)?,
    };
    fillet_at_validated(p, q, crossing, options)
}

/// Round the corner at a crossing the caller chose (from
/// [`crate::intersect::intersect`]; its `u`, `v` are used). Same errors as
/// [`fillet`] except the search; a hit that is not a crossing is
/// NoIntersection.
pub fn fillet_at<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    crossing: &Intersection,
    options: &FilletOptions,
) -> Result<Fillet> {
    let (p, q) = (p.into(), q.into());
    validate(p, q, options)?;
    if crossing.kind != IntersectionKind::Crossing {
        return Err(BezjoinError::NoIntersection {
            reason: format!(
                "the hit at u = {}, v = {} is {:?}, not a crossing",
                crossing.u, crossing.v, crossing.kind
            ),
        });
    }
    fillet_at_validated(p, q, crossing.clone(), options)
}

/// Round the corner at the vertex where `p` ends and `q` starts (a wire's
/// or a sketch's vertex), whatever other crossings `p` and `q` have: the
/// corner point is `P(last)`, and the setbacks are measured back from P's
/// end and on from Q's start. `gap >= 0` (absolute) is how far apart P's
/// last point and Q's first point may be (sketch solvers leave 1e-7 and
/// more); a larger gap is NoIntersection naming it. A path that doubles
/// back at the vertex (Q leaves along P's arrival direction reversed: the
/// sine of the tangents' angle at most `options.intersect.tangent_tolerance`
/// and their cosine negative) has no corner to round, only a cusp: also
/// NoIntersection. The pieces keep the inputs' kinds; everything else is as
/// in [`fillet`].
pub fn fillet_vertex<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    options: &FilletOptions,
    gap: f64,
) -> Result<Fillet> {
    let (p, q) = (p.into(), q.into());
    validate(p, q, options)?;
    check_finite_scalar("gap", gap)?;
    if gap < 0.0 {
        return Err(BezjoinError::out_of_range("gap", gap, ">= 0"));
    }
    let (_, u) = p.domain();
    let (v, _) = q.domain();
    // P's end and Q's start with their tangents, in one pass each (at a
    // domain's end the point is `eval`'s, bit for bit); on the stack up to
    // dimension 8.
    let dim = p.dim();
    let mut stack = [0.0f64; 32];
    let mut heap = Vec::new();
    let work: &mut [f64] = if 4 * dim <= stack.len() {
        &mut stack[..4 * dim]
    } else {
        heap.resize(4 * dim, 0.0);
        &mut heap
    };
    let (p_rows, q_rows) = work.split_at_mut(2 * dim);
    let (end, p_tangent) = p_rows.split_at_mut(dim);
    let (start, q_tangent) = q_rows.split_at_mut(dim);
    p.point_and_tangent_into(u, end, p_tangent);
    q.point_and_tangent_into(v, start, q_tangent);
    let distance = crate::bezier::distance(end, start);
    if distance.is_nan() || distance > gap {
        return Err(BezjoinError::NoIntersection {
            reason: format!(
                "P's end and Q's start are {distance:e} apart, more than gap = {gap:e}; \
                 they do not meet at a vertex"
            ),
        });
    }
    check_not_doubling_back(
        (u, p_tangent),
        (v, q_tangent),
        options.intersect.tangent_tolerance,
    )?;
    let crossing = Intersection {
        u,
        v,
        point: end.to_vec(),
        distance,
        kind: IntersectionKind::Crossing,
    };
    fillet_at_validated(p, q, crossing, options)
}

/// NoIntersection when P's tangent `a` arriving at `u` (the end of its
/// domain) and Q's `b` leaving `v` (the start of its) point in opposite
/// directions, within `tangent_tolerance` (the sine of their angle): the
/// path turns back on itself there. Zero tangents are left to the fillet's
/// own checks.
fn check_not_doubling_back(
    (u, a): (f64, &[f64]),
    (v, b): (f64, &[f64]),
    tangent_tolerance: f64,
) -> Result<()> {
    let (na, nb) = (crate::bezier::norm(a), crate::bezier::norm(b));
    if !(na > 0.0 && nb > 0.0 && na.is_finite() && nb.is_finite()) {
        return Ok(());
    }
    let dot: f64 = a.iter().zip(b.iter()).map(|(x, y)| x * y).sum();
    let cos = dot / (na * nb);
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    if cos < 0.0 && sin <= tangent_tolerance {
        return Err(BezjoinError::NoIntersection {
            reason: format!(
                "P and Q double back at the vertex (P(u = {}) then Q(v = {}): their tangents \
                 are opposite, the sine of their angle {} is within tangent_tolerance = {}): \
                 there is no corner to round, only a cusp",
                Compact(u),
                Compact(v),
                Compact(sin),
                Compact(tangent_tolerance)
            ),
        });
    }
    Ok(())
}

/// The first crossing, or the error that says what was found instead.
pub(crate) fn first_crossing(hits: &[Intersection]) -> Result<Intersection> {
    if let Some(c) = hits.iter().find(|h| h.kind == IntersectionKind::Crossing) {
        return Ok(c.clone());
    }
    let touching: Vec<String> = hits
        .iter()
        .filter(|h| h.kind == IntersectionKind::Touching)
        .map(|h| format!("(u = {}, v = {})", h.u, h.v))
        .collect();
    let overlaps: Vec<String> = hits
        .iter()
        .filter_map(|h| match h.kind {
            IntersectionKind::Overlap { u_range, .. } => {
                Some(format!("u in [{}, {}]", u_range.0, u_range.1))
            }
            _ => None,
        })
        .collect();
    let reason = if !touching.is_empty() {
        format!(
            "P and Q only touch (tangentially, without crossing) at {}; there is no corner to round",
            touching.join(", ")
        )
    } else if !overlaps.is_empty() {
        format!(
            "P and Q do not cross; they overlap for {}",
            overlaps.join(", ")
        )
    } else {
        "P and Q do not cross".to_string()
    };
    Err(BezjoinError::NoIntersection { reason })
}

pub(crate) fn validate(p: CurveRef, q: CurveRef, options: &FilletOptions) -> Result<()> {
    if q.dim() != p.dim() {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: p.dim(),
            actual: q.dim(),
        });
    }
    let scale = p.coordinate_scale().max(q.coordinate_scale());
    for (name, setback) in [
        ("p_setback", options.p_setback),
        ("q_setback", options.q_setback),
    ] {
        check_positive(name, setback)?;
        // A setback of 1e-300 gave a blend 4e-15 long (user testing,
        // session 40): the rule of a radius too small.
        if setback <= VERTEX_TOLERANCE * scale {
            return Err(below_vertex_tolerance(name, setback, scale, "the cut"));
        }
    }
    validate_shape(options)
}

/// InvalidArgument naming `name` (a radius or setback, `value`) at most
/// [`VERTEX_TOLERANCE`] of the curves' coordinate size `scale`: `what` (the
/// arc, the cut) could not be told from the corner.
#[cold]
pub(crate) fn below_vertex_tolerance(
    name: &str,
    value: f64,
    scale: f64,
    what: &str,
) -> BezjoinError {
    BezjoinError::invalid(
        name,
        format!(
            "{value:e} is at most {VERTEX_TOLERANCE:e} of the curves' coordinate size \
             {scale:e}: {what} could not be told from the corner (its blend would be an edge \
             no CAD kernel takes)"
        ),
    )
}

/// Everything but the curves and the setbacks (shared with the deviation mode).
pub(crate) fn validate_shape(options: &FilletOptions) -> Result<()> {
    options.scale.checked()?;
    check_finite_scalar("relative_length_accuracy", options.relative_length_accuracy)?;
    if !(options.relative_length_accuracy > 0.0 && options.relative_length_accuracy < 1.0) {
        return Err(BezjoinError::out_of_range(
            "relative_length_accuracy",
            options.relative_length_accuracy,
            "(0, 1)",
        ));
    }
    Ok(())
}

/// Arc lengths of `P` before the crossing and of `Q` after it.
pub(crate) fn available_lengths(
    p: CurveRef,
    q: CurveRef,
    crossing: &Intersection,
) -> Result<(f64, f64)> {
    let before = p.arc_length(
        p.domain().0,
        crossing.u,
        p.checked_default_length_accuracy("p")?,
    )?;
    let after = q.arc_length(
        crossing.v,
        q.domain().1,
        q.checked_default_length_accuracy("q")?,
    )?;
    Ok((before, after))
}

pub(crate) fn fillet_at_validated(
    p: CurveRef,
    q: CurveRef,
    crossing: Intersection,
    options: &FilletOptions,
) -> Result<Fillet> {
    let mut inverses = SetbackInverses::new(p, q, &crossing);
    let blend = blend_at(p, q, &crossing, options, &mut inverses)?;
    assemble(p, q, crossing, blend)
}

/// The arc-length inversions of a corner: along `P` backwards and along `Q`
/// forwards from the crossing. They keep their quadrature between calls,
/// so [`blend_at`] with the same inverses and other setbacks (the deviation
/// search's trials) does not integrate the curves anew; each call's
/// parameters are the ones a fresh inversion gives, bit for bit.
pub(crate) struct SetbackInverses<'a> {
    p: SetbackInverse<'a>,
    q: SetbackInverse<'a>,
}

/// One side's inversion: a Bezier curve keeps its quadrature
/// ([`ArcLengthInverse`]); a NURBS curve inverts span by span
/// ([`NurbsCurve::param_at_length`]) each time.
///
/// The Bezier variant is kept inline (no allocation per fillet): a
/// `SetbackInverses` lives on the stack of one fillet call.
#[allow(clippy::large_enum_variant)]
enum SetbackInverse<'a> {
    Bezier(ArcLengthInverse<'a>),
    Nurbs { curve: &'a NurbsCurve, start: f64 },
}

impl SetbackInverse<'_> {
    fn param_at_length(&mut self, length: f64, accuracy: f64) -> Result<f64> {
        match self {
            SetbackInverse::Bezier(inverse) => inverse.param_at_length(length, accuracy),
            SetbackInverse::Nurbs { curve, start } => {
                curve.param_at_length(*start, length, accuracy)
            }
        }
    }
}

impl<'a> SetbackInverses<'a> {
    pub(crate) fn new(p: CurveRef<'a>, q: CurveRef<'a>, crossing: &Intersection) -> Self {
        let side = |c: CurveRef<'a>, start: f64| match c {
            CurveRef::Bezier(b) => SetbackInverse::Bezier(ArcLengthInverse::new(b, start)),
            CurveRef::Nurbs(curve) => SetbackInverse::Nurbs { curve, start },
        };
        SetbackInverses {
            p: side(p, crossing.u),
            q: side(q, crossing.v),
        }
    }
}

/// Where the setbacks cut the curves, and the connection between the cuts:
/// a [`Fillet`] before its trimmed pieces are built ([`assemble`]).
pub(crate) struct Blend {
    pub(crate) u0: f64,
    pub(crate) v0: f64,
    pub(crate) connection: Connection,
}

/// The cut parameters `u0`, `v0` of the setbacks in `options` (inverted with
/// `inverses`, made for `p`, `q` and `crossing`) and the blend between them.
pub(crate) fn blend_at(
    p: CurveRef,
    q: CurveRef,
    crossing: &Intersection,
    options: &FilletOptions,
    inverses: &mut SetbackInverses,
) -> Result<Blend> {
    let (dp, dq) = (options.p_setback, options.q_setback);
    let accuracy = options.relative_length_accuracy;
    // What a setback must leave of its curve: more than its own accuracy
    // allows for, and more than a sliver by the chains' rule.
    let shortest_kept = |c: CurveRef, setback: f64, name: &str| -> Result<f64> {
        Ok((2.0 * accuracy * setback).max(chain::sliver_length(c, name)?.1))
    };
    // The inversion itself refuses a length beyond the curve's end; the
    // lengths for the message are computed only on that path.
    let too_long_p = || -> Result<BezjoinError> {
        let (before, _) = available_lengths(p, q, crossing)?;
        Ok(BezjoinError::invalid(
            "p_setback",
            format!(
                "{} is not shorter than the arc length {} of P before the crossing at \
                 u = {} by more than {:e} (the larger of twice the \
                 setback's length accuracy and {SLIVER:e} of P's length)",
                Compact(dp),
                Compact(before),
                crossing.u,
                shortest_kept(p, dp, "p")?
            ),
        ))
    };
    let too_long_q = || -> Result<BezjoinError> {
        let (_, after) = available_lengths(p, q, crossing)?;
        Ok(BezjoinError::invalid(
            "q_setback",
            format!(
                "{} is not shorter than the arc length {} of Q after the crossing at \
                 v = {} by more than {:e} (the larger of twice the \
                 setback's length accuracy and {SLIVER:e} of Q's length)",
                Compact(dq),
                Compact(after),
                crossing.v,
                shortest_kept(q, dq, "q")?
            ),
        ))
    };
    let (p_first, _) = p.domain();
    let (_, q_last) = q.domain();
    // A setback within its accuracy of the whole length would leave a
    // sliver of the curve (a few ulps long, or none, as rounding falls): the
    // piece kept must be longer than `shortest_kept`. Its length is
    // measured only when the cut is within 1e-6 of the curve's end in
    // parameter.
    let sliver =
        |c: CurveRef, a: f64, b: f64, whole: f64, setback: f64, name: &str| -> Result<bool> {
            match short_piece_length(c, (a, b), whole, || name.to_owned())? {
                Some(kept) => Ok(kept <= shortest_kept(c, setback, name)?),
                None => Ok(false),
            }
        };
    let u0 = match inverses.p.param_at_length(-dp, accuracy * dp) {
        Ok(u0)
            if u0 > p_first
                && u0 < crossing.u
                && !sliver(p, p_first, u0, crossing.u - p_first, dp, "p")? =>
        {
            u0
        }
        Ok(_) | Err(BezjoinError::InvalidArgument { .. }) => return Err(too_long_p()?),
        Err(e) => return Err(e),
    };
    let v0 = match inverses.q.param_at_length(dq, accuracy * dq) {
        Ok(v0)
            if v0 < q_last
                && v0 > crossing.v
                && !sliver(q, v0, q_last, q_last - crossing.v, dq, "q")? =>
        {
            v0
        }
        Ok(_) | Err(BezjoinError::InvalidArgument { .. }) => return Err(too_long_q()?),
        Err(e) => return Err(e),
    };
    let mut connect_options = ConnectOptions::new(options.p_order, options.q_order);
    connect_options.scale = options.scale;
    let connection = connect(&p, u0, &q, v0, &connect_options)?;
    Ok(Blend { u0, v0, connection })
}

/// The arc length of `c` on `[a, b]` (to the curve's default accuracy)
/// when that piece spans at most 1e-6 of `whole` in parameter: a candidate
/// sliver, which the fillets (a setback as long as its curve) and the
/// chains (cuts that use a whole curve) refuse. `None` for a longer piece,
/// whose length is not needed. `name` (of the curve, for the error of an
/// overflowing control polygon) is formed only for a candidate.
pub(crate) fn short_piece_length(
    c: CurveRef,
    (a, b): (f64, f64),
    whole: f64,
    name: impl FnOnce() -> String,
) -> Result<Option<f64>> {
    if b - a > 1e-6 * whole {
        return Ok(None);
    }
    let accuracy = c.checked_default_length_accuracy(&name())?;
    Ok(Some(c.arc_length(a, b, accuracy)?))
}

/// The [`Fillet`] of a [`Blend`]: `P` trimmed to `[first, u0]`, `Q` to
/// `[v0, last]` (each of its own kind).
pub(crate) fn assemble(
    p: CurveRef,
    q: CurveRef,
    crossing: Intersection,
    blend: Blend,
) -> Result<Fillet> {
    let Blend { u0, v0, connection } = blend;
    let (p_first, _) = p.domain();
    let (_, q_last) = q.domain();
    let p_trimmed = match p {
        CurveRef::Bezier(b) => bezier_trim(b, u0, true).map(Curve::Bezier),
        CurveRef::Nurbs(n) => n
            .one_span_trim(u0, true)
            .or_else(|| n.clamped_trim(u0, true))
            .map(Curve::Nurbs),
    };
    let p_trimmed = match p_trimmed {
        Some(piece) => piece,
        None => p.segment(p_first, u0)?,
    };
    let q_trimmed = match q {
        CurveRef::Bezier(b) => bezier_trim(b, v0, false).map(Curve::Bezier),
        CurveRef::Nurbs(n) => n
            .one_span_trim(v0, false)
            .or_else(|| n.clamped_trim(v0, false))
            .map(Curve::Nurbs),
    };
    let q_trimmed = match q_trimmed {
        Some(piece) => piece,
        None => q.segment(v0, q_last)?,
    };
    Ok(Fillet {
        p_trimmed,
        blend: connection.curve,
        q_trimmed,
        crossing,
        u0,
        v0,
        p_scale: connection.p_scale,
        q_scale: connection.q_scale,
        max_residual: connection.max_residual,
    })
}

/// A Bezier curve on `[0, t]` (`left`) or on `[t, 1]`, by one de Casteljau
/// pass in place on a copy of the control points (one allocation).
/// [`BezierCurve::segment`] gives the same control points bit for bit (up
/// to the sign of a zero): its de Casteljau steps at 0 and at 1 are exact
/// (`1 * x + 0 * y = x`, `0 * x + 1 * y = y`), and what remains are the
/// same steps `(1 - t) x + t y` at `t` on the same points, taken here once
/// instead of once per control point. `None` when a control point is not
/// finite (the caller then takes the segment path and its error).
pub(crate) fn bezier_trim(curve: &BezierCurve, t: f64, left: bool) -> Option<BezierCurve> {
    let (n, d) = (curve.degree(), curve.dim());
    let mut points = curve.points().to_vec();
    // The common sizes with the degree and dimension as constants (the
    // loops unrolled, no bounds checks); the same operations in the same
    // order as the general case.
    match (n, d) {
        (3, 2) => trim_in_place(&mut points, 3, 2, t, left),
        (2, 2) => trim_in_place(&mut points, 2, 2, t, left),
        (3, 3) => trim_in_place(&mut points, 3, 3, t, left),
        (n, d) => trim_in_place(&mut points, n, d, t, left),
    }
    points
        .iter()
        .all(|x| x.is_finite())
        .then(|| BezierCurve::from_parts(d, n, points))
}

/// The de Casteljau pass of [`bezier_trim`] on `points` (`n + 1` rows of
/// `d`), inlined so that constant `n`, `d` unroll it.
#[inline(always)]
fn trim_in_place(points: &mut [f64], n: usize, d: usize, t: f64, left: bool) {
    let points = &mut points[..(n + 1) * d];
    if left {
        // After step `r`, point `i >= r` holds level `r`'s point `i - r`:
        // point `r` is final (the left piece's point `r`).
        for r in 1..=n {
            for i in (r..=n).rev() {
                for c in 0..d {
                    points[i * d + c] = (1.0 - t) * points[(i - 1) * d + c] + t * points[i * d + c];
                }
            }
        }
    } else {
        // After step `r`, point `n - r` is final (the right piece's): the
        // step of `bezier::de_casteljau_step` on the first `n + 2 - r` points.
        for r in 1..=n {
            for i in 0..=n - r {
                for c in 0..d {
                    points[i * d + c] = (1.0 - t) * points[i * d + c] + t * points[(i + 1) * d + c];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::bezier_trim;
    use crate::bezier::BezierCurve;

    /// The one-pass trims are the segments, bit for bit, on fixed-seed
    /// random curves of degrees 1 to 9 in 2D and 3D.
    #[test]
    fn trims_are_the_segments_bit_for_bit() {
        let mut state = 24u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..200 {
            let degree = 1 + case % 9;
            let dim = 2 + case % 2;
            let points: Vec<f64> = (0..dim * (degree + 1))
                .map(|_| 10.0 * next() - 5.0)
                .collect();
            let curve = BezierCurve::new(dim, degree, points).unwrap();
            let t = next();
            let left = bezier_trim(&curve, t, true).unwrap();
            let right = bezier_trim(&curve, t, false).unwrap();
            assert_eq!(left, curve.segment(0.0, t).unwrap(), "case {case}");
            assert_eq!(right, curve.segment(t, 1.0).unwrap(), "case {case}");
        }
    }
}

#[cfg(test)]
mod multi_span_tests {
    use super::{FilletOptions, fillet};
    use crate::bezier::BezierCurve;
    use crate::curve::Curve;
    use crate::nurbs::NurbsCurve;

    /// The demo's two cubics as B-splines with knots inserted (`knots`,
    /// each once), on `[a, a + h]`, with `weights` (then rational) when
    /// given.
    fn demo(knots: &[f64], a: f64, h: f64, weights: Option<[f64; 4]>) -> (NurbsCurve, NurbsCurve) {
        let p = [[0.0, 0.0], [0.8, 0.3], [1.5, -0.2], [2.2, 0.4]];
        let q = [[1.0, -1.0], [1.3, -0.2], [0.8, 0.6], [1.2, 1.4]];
        let make = |rows: [[f64; 2]; 4], w: Option<[f64; 4]>| {
            let poles: Vec<f64> = rows.iter().flatten().copied().collect();
            let mut k = vec![a; 4];
            k.extend(std::iter::repeat_n(a + h, 4));
            let mut c =
                NurbsCurve::new(2, 3, poles, w.map(|w| w.to_vec()), k).expect("a valid cubic");
            for &u in knots {
                c = c.insert_knot(a + h * u, 1).unwrap();
            }
            c
        };
        let wq = weights.map(|w| [w[0], w[2], w[1], w[3]]);
        (make(p, weights), make(q, wq))
    }

    /// Multi-span fillets meet their setbacks: the arc length of `P` from
    /// `u0` to the crossing and of `Q` from the crossing to `v0`, by the
    /// adaptive span-by-span quadrature at a thousandth of the accuracy,
    /// are the setbacks within `relative_length_accuracy * setback`. Two
    /// and three spans (knots where the setback crosses a span boundary
    /// and where it does not), shifted domains, rational spans, setbacks
    /// 0.05 to 0.6. The trimmed pieces are `segment`s of the inputs, and
    /// on `[0, 1]` the cuts are the Bezier fillet's within 1e-12 (the same
    /// geometry).
    #[test]
    fn multi_span_fillets_meet_their_setbacks() {
        let bez_p =
            BezierCurve::from_rows(&[[0.0, 0.0], [0.8, 0.3], [1.5, -0.2], [2.2, 0.4]]).unwrap();
        let bez_q =
            BezierCurve::from_rows(&[[1.0, -1.0], [1.3, -0.2], [0.8, 0.6], [1.2, 1.4]]).unwrap();
        let layouts: [&[f64]; 5] = [&[0.5], &[0.4, 0.7], &[0.3], &[0.2, 0.45, 0.55], &[0.52]];
        let mut crossed = 0;
        for (l, knots) in layouts.iter().enumerate() {
            for (a, h) in [(0.0, 1.0), (2.0, 3.0), (-7.5, 0.25)] {
                for weights in [None, Some([1.0, 1.3, 0.8, 1.0])] {
                    let (p, q) = demo(knots, a, h, weights);
                    for setback in [0.05, 0.1, 0.3, 0.45, 0.6] {
                        let options = FilletOptions::new(setback, 0.8 * setback, 3, 3);
                        let f = fillet(&p, &q, &options).unwrap();
                        let (u, v) = (f.crossing.u, f.crossing.v);
                        let accuracy = options.relative_length_accuracy;
                        let dp = p.arc_length(f.u0, u, 1e-3 * accuracy * setback).unwrap();
                        let dq = q.arc_length(v, f.v0, 1e-3 * accuracy * setback).unwrap();
                        assert!(
                            (dp - setback).abs() <= accuracy * setback,
                            "layout {l} [{a}, +{h}] {weights:?} setback {setback}: P {dp}"
                        );
                        assert!(
                            (dq - 0.8 * setback).abs() <= accuracy * 0.8 * setback,
                            "layout {l} [{a}, +{h}] {weights:?} setback {setback}: Q {dq}"
                        );
                        let inside = |k: f64, x: f64, y: f64| (k - x) * (k - y) < 0.0;
                        if knots.iter().any(|&k| inside(a + h * k, f.u0, u))
                            || knots.iter().any(|&k| inside(a + h * k, v, f.v0))
                        {
                            crossed += 1;
                        }
                        let (first, _) = p.domain();
                        let (_, last) = q.domain();
                        assert_eq!(f.p_trimmed, Curve::Nurbs(p.segment(first, f.u0).unwrap()));
                        assert_eq!(f.q_trimmed, Curve::Nurbs(q.segment(f.v0, last).unwrap()));
                        if (a, h) == (0.0, 1.0) && weights.is_none() {
                            let b = fillet(&bez_p, &bez_q, &options).unwrap();
                            assert!((b.u0 - f.u0).abs() <= 1e-12, "layout {l} {setback}");
                            assert!((b.v0 - f.v0).abs() <= 1e-12, "layout {l} {setback}");
                        }
                    }
                }
            }
        }
        assert!(crossed >= 30, "only {crossed} setbacks crossed a knot");
    }
}
