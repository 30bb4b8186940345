//! Rounding the corner between two crossing curves (docs/mathematics.md#fillet;
//! Krivosheev, Mavrin, Starkova, *Bezier curve conjugation for
//! smooth curve joining and corner rounding*, Omsk Scientific Bulletin, 2025,
//! Fig. 2).
//!
//! `P` and `Q` cross at `X = P(u*) = Q(v*)`. The corner of the path "along
//! `P` up to `X`, then along `Q`" is rounded by keeping `P` on `[0, u0]`,
//! `Q` on `[v0, 1]` and joining `P(u0)` to `Q(v0)` with the connecting curve
//! of section 1 ([`crate::connect::connect`]). The setbacks are arc lengths
//! measured from `X`: `len(P; u0..u*) = dp`, `len(Q; v*..v0) = dq`
//! (symmetric when `dp = dq`); `u0`, `v0` come from
//! [`BezierCurve::param_at_length`].
//!
//! # Guarantee
//! The three pieces `P|[0,u0]`, `R`, `Q|[v0,1]` form a C^k B-spline with knot
//! intervals `(u0, alpha, (1 - v0) alpha / beta)` ([`Fillet::to_bspline`]):
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
mod deviation;

pub use chain::{
    ChainCorner, ChainFillet, ChainFilletOptions, DEFAULT_PARALLEL_THRESHOLD, fillet_chain,
};
pub use deviation::{
    DEFAULT_RELATIVE_DEVIATION_ACCURACY, DeviationFillet, DeviationFilletOptions,
    distance_to_curve, fillet_within_deviation,
};

use crate::arclength::ArcLengthInverse;
use crate::bezier::BezierCurve;
use crate::bspline::BSplineCurve;
use crate::connect::{ConnectOptions, Connection, ShapeScale, connect};
use crate::error::{BezjoinError, Result, check_finite_scalar, check_positive};
use crate::intersect::{IntersectOptions, Intersection, IntersectionKind, intersect};

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
    /// `kp <= degree of P`: continuity order at `P(u0)`.
    pub p_order: usize,
    /// `kq <= degree of Q`: continuity order at `Q(v0)`.
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
}

/// A rounded corner: `P|[0,u0]`, the blend `R`, `Q|[v0,1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Fillet {
    /// `P` on `[0, u0]`, reparametrised to `[0, 1]`.
    pub p_trimmed: BezierCurve,
    /// The connecting curve `R` of degree `kp + kq + 1`.
    pub blend: BezierCurve,
    /// `Q` on `[v0, 1]`, reparametrised to `[0, 1]`.
    pub q_trimmed: BezierCurve,
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
    /// Knot intervals `(u0, alpha, (1 - v0) alpha / beta)` of the C^k chain.
    pub fn knot_intervals(&self) -> [f64; 3] {
        [
            self.u0,
            self.p_scale,
            (1.0 - self.v0) * self.p_scale / self.q_scale,
        ]
    }

    /// The three pieces as one B-spline with [`Self::knot_intervals`].
    pub fn to_bspline(&self) -> Result<BSplineCurve> {
        BSplineCurve::from_bezier_chain(
            &[
                self.p_trimmed.clone(),
                self.blend.clone(),
                self.q_trimmed.clone(),
            ],
            &self.knot_intervals(),
        )
    }
}

/// Round the corner at the first crossing of `p` and `q` (smallest `u` on
/// `P`; touching points and overlaps are skipped).
///
/// Errors (each names the argument): curves of different dimensions;
/// non-finite or non-positive setback, scale or accuracy; `p_order` or
/// `q_order` above the curve's degree (OrderAboveDegree); no crossing, or
/// only touching points (NoIntersection, saying which); a setback not
/// shorter than the part of the curve before / after the crossing
/// (InvalidArgument naming `p_setback` / `q_setback` with both lengths);
/// an ill-conditioned connection (IllConditioned, from the connect solver).
pub fn fillet(p: &BezierCurve, q: &BezierCurve, options: &FilletOptions) -> Result<Fillet> {
    validate(p, q, options)?;
    let hits = intersect(p, q, &options.intersect)?;
    let crossing = first_crossing(&hits)?;
    fillet_at_validated(p, q, crossing, options)
}

/// Round the corner at a crossing the caller chose (from
/// [`crate::intersect::intersect`]; its `u`, `v` are used). Same errors as
/// [`fillet`] except the search; a hit that is not a crossing is
/// NoIntersection.
pub fn fillet_at(
    p: &BezierCurve,
    q: &BezierCurve,
    crossing: &Intersection,
    options: &FilletOptions,
) -> Result<Fillet> {
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

pub(crate) fn validate(p: &BezierCurve, q: &BezierCurve, options: &FilletOptions) -> Result<()> {
    if q.dim() != p.dim() {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: p.dim(),
            actual: q.dim(),
        });
    }
    check_positive("p_setback", options.p_setback)?;
    check_positive("q_setback", options.q_setback)?;
    validate_shape(p, q, options)
}

/// Everything but the setbacks (shared with the deviation mode).
pub(crate) fn validate_shape(
    p: &BezierCurve,
    q: &BezierCurve,
    options: &FilletOptions,
) -> Result<()> {
    if options.p_order > p.degree() {
        return Err(BezjoinError::OrderAboveDegree {
            name: "p_order".into(),
            order: options.p_order,
            degree: p.degree(),
            curve: "P".into(),
        });
    }
    if options.q_order > q.degree() {
        return Err(BezjoinError::OrderAboveDegree {
            name: "q_order".into(),
            order: options.q_order,
            degree: q.degree(),
            curve: "Q".into(),
        });
    }
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
    p: &BezierCurve,
    q: &BezierCurve,
    crossing: &Intersection,
) -> Result<(f64, f64)> {
    let before = p.arc_length(0.0, crossing.u, p.default_length_accuracy())?;
    let after = q.arc_length(crossing.v, 1.0, q.default_length_accuracy())?;
    Ok((before, after))
}

pub(crate) fn fillet_at_validated(
    p: &BezierCurve,
    q: &BezierCurve,
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
pub(crate) struct SetbackInverses {
    p: ArcLengthInverse,
    q: ArcLengthInverse,
}

impl SetbackInverses {
    pub(crate) fn new(p: &BezierCurve, q: &BezierCurve, crossing: &Intersection) -> Self {
        SetbackInverses {
            p: ArcLengthInverse::new(p, crossing.u),
            q: ArcLengthInverse::new(q, crossing.v),
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
    p: &BezierCurve,
    q: &BezierCurve,
    crossing: &Intersection,
    options: &FilletOptions,
    inverses: &mut SetbackInverses,
) -> Result<Blend> {
    let (dp, dq) = (options.p_setback, options.q_setback);
    let accuracy = options.relative_length_accuracy;
    // The inversion itself refuses a length beyond the curve's end; the
    // lengths for the message are computed only on that path.
    let too_long_p = || -> Result<BezjoinError> {
        let (before, _) = available_lengths(p, q, crossing)?;
        Ok(BezjoinError::invalid(
            "p_setback",
            format!(
                "{dp} is not shorter than the arc length {before} of P before the crossing at u = {}",
                crossing.u
            ),
        ))
    };
    let too_long_q = || -> Result<BezjoinError> {
        let (_, after) = available_lengths(p, q, crossing)?;
        Ok(BezjoinError::invalid(
            "q_setback",
            format!(
                "{dq} is not shorter than the arc length {after} of Q after the crossing at v = {}",
                crossing.v
            ),
        ))
    };
    let u0 = match inverses.p.param_at_length(-dp, accuracy * dp) {
        Ok(u0) if u0 > 0.0 && u0 < crossing.u => u0,
        Ok(_) | Err(BezjoinError::InvalidArgument { .. }) => return Err(too_long_p()?),
        Err(e) => return Err(e),
    };
    let v0 = match inverses.q.param_at_length(dq, accuracy * dq) {
        Ok(v0) if v0 < 1.0 && v0 > crossing.v => v0,
        Ok(_) | Err(BezjoinError::InvalidArgument { .. }) => return Err(too_long_q()?),
        Err(e) => return Err(e),
    };
    let mut connect_options = ConnectOptions::new(options.p_order, options.q_order);
    connect_options.scale = options.scale;
    let connection = connect(p, u0, q, v0, &connect_options)?;
    Ok(Blend { u0, v0, connection })
}

/// The [`Fillet`] of a [`Blend`]: `P` trimmed to `[0, u0]`, `Q` to `[v0, 1]`.
pub(crate) fn assemble(
    p: &BezierCurve,
    q: &BezierCurve,
    crossing: Intersection,
    blend: Blend,
) -> Result<Fillet> {
    let Blend { u0, v0, connection } = blend;
    Ok(Fillet {
        p_trimmed: p.segment(0.0, u0)?,
        blend: connection.curve,
        q_trimmed: q.segment(v0, 1.0)?,
        crossing,
        u0,
        v0,
        p_scale: connection.p_scale,
        q_scale: connection.q_scale,
        max_residual: connection.max_residual,
    })
}
