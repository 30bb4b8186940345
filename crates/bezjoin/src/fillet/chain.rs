//! **\[beyond\]** Rounding every corner of a chain of curves in one call
//! (docs/mathematics.md#fillet-chains).
//!
//! Corner `i` lies between `curves[i]` and `curves[i + 1]` (and, for a closed
//! chain, between the last curve and the first). Its crossing is the hit of
//! the two curves nearest their shared end: the one with the smallest
//! `(last - u) / |P's domain| + (v - first) / |Q's domain|` (for a chain
//! whose curves meet end to end that is P's end and Q's start). Curves may
//! be Bezier or NURBS; trimmed pieces keep their kind and parameters. Every corner is rounded as [`super::fillet`] rounds one,
//! with the same options; curve `i` is then kept between the cut of corner
//! `i - 1` and the cut of corner `i`.
//!
//! Corners are independent, so when there are more than
//! `parallel_threshold` of them they are computed in parallel with rayon
//! (in the caller's rayon pool, e.g. inside `ThreadPool::install`), otherwise
//! sequentially. Every corner is computed by the same deterministic code
//! either way, and the first failing corner (in chain order) is the error
//! reported, so the result is identical bit for bit.

use rayon::prelude::*;

use crate::bezier::BezierCurve;
use crate::curve::{AsCurveRef, Curve, CurveRef};
use crate::error::{BezjoinError, Compact, Result};
use crate::intersect::{IntersectOptions, Intersection, IntersectionKind, intersect};

use super::{Fillet, FilletOptions, fillet_at_validated, short_piece_length, validate};

/// Default of [`ChainFilletOptions::parallel_threshold`].
pub const DEFAULT_PARALLEL_THRESHOLD: usize = 64;

/// Options of [`fillet_chain`].
#[derive(Debug, Clone, PartialEq)]
pub struct ChainFilletOptions {
    /// Setbacks, orders, scales and accuracies used at every corner.
    pub fillet: FilletOptions,
    /// `true`: the last curve's end joins the first curve's start as one more corner.
    pub closed: bool,
    /// Corners are computed in parallel when there are more than this many;
    /// default [`DEFAULT_PARALLEL_THRESHOLD`] (64).
    pub parallel_threshold: usize,
}

impl ChainFilletOptions {
    /// An open chain with the given corner options.
    pub fn open(fillet: FilletOptions) -> Self {
        Self {
            fillet,
            closed: false,
            parallel_threshold: DEFAULT_PARALLEL_THRESHOLD,
        }
    }

    /// A closed chain with the given corner options.
    pub fn closed(fillet: FilletOptions) -> Self {
        Self {
            closed: true,
            ..Self::open(fillet)
        }
    }
}

/// One rounded corner of a chain.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainCorner {
    /// The crossing of `curves[i]` and `curves[i + 1]` that was rounded.
    pub crossing: Intersection,
    /// Cut parameter on `curves[i]`.
    pub u0: f64,
    /// Cut parameter on `curves[i + 1]`.
    pub v0: f64,
    /// `alpha` and `beta` used.
    pub scales: (f64, f64),
    /// The connect solver's worst relative residual.
    pub max_residual: f64,
}

/// A chain with every corner rounded.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainFillet {
    /// In path order: trimmed curve 0, blend 0, trimmed curve 1, blend 1, ...
    /// An open chain of `n` curves gives `2n - 1` pieces (ending with the
    /// trimmed last curve), a closed one `2n` (ending with the blend from
    /// the last curve to the first, whose trimmed start begins the list).
    /// Trimmed curves keep their kind (a NURBS curve its parameters);
    /// blends are Bezier curves.
    pub pieces: Vec<Curve>,
    /// Corner `i`, between `curves[i]` and `curves[(i + 1) % n]`.
    pub corners: Vec<ChainCorner>,
}

/// Round every corner of the chain `curves` (module documentation).
///
/// Errors: fewer than 2 curves; curves of different dimensions (naming
/// `curves[i]`); the option errors of [`super::fillet`]; at a corner, no
/// crossing, a tangential (smooth) joint, a setback too long, or an
/// intersection search or connection that cannot be trusted
/// (IllConditioned, e.g. a work bound of [`FilletOptions::intersect`]
/// reached) — the message starts with `corner i` (for InvalidArgument the
/// argument name does); two cuts on one curve that pass each other
/// (InvalidArgument naming the curve).
///
/// ```
/// use bezjoin_core::BezierCurve;
/// use bezjoin_core::{ChainFilletOptions, FilletOptions, fillet_chain};
/// // A closed triangle of lines.
/// let a = BezierCurve::from_rows(&[[0.0, 0.0], [4.0, 0.0]]).unwrap();
/// let b = BezierCurve::from_rows(&[[4.0, 0.0], [0.0, 3.0]]).unwrap();
/// let c = BezierCurve::from_rows(&[[0.0, 3.0], [0.0, 0.0]]).unwrap();
/// let options = ChainFilletOptions::closed(FilletOptions::symmetric(0.5, 1));
/// let rounded = fillet_chain(&[a, b, c], &options).unwrap();
/// assert_eq!(rounded.pieces.len(), 6);
/// ```
pub fn fillet_chain<C: AsCurveRef + Sync>(
    curves: &[C],
    options: &ChainFilletOptions,
) -> Result<ChainFillet> {
    let curves = chain_refs(curves)?;
    let n = curves.len();
    for i in 0..n {
        validate(curves[i], curves[(i + 1) % n], &options.fillet)?;
    }
    let corner_count = if options.closed { n } else { n - 1 };
    let one = |i: usize| round_corner(i, curves[i], curves[(i + 1) % n], &options.fillet);
    let results: Vec<Result<Fillet>> = if corner_count > options.parallel_threshold {
        (0..corner_count).into_par_iter().map(one).collect()
    } else {
        (0..corner_count).map(one).collect()
    };
    let mut fillets = Vec::with_capacity(corner_count);
    for r in results {
        fillets.push(r?);
    }
    let cuts: Vec<(f64, f64)> = fillets.iter().map(|f| (f.u0, f.v0)).collect();
    let blends: Vec<&BezierCurve> = fillets.iter().map(|f| &f.blend).collect();
    let pieces = chain_pieces(&curves, options.closed, &cuts, &blends)?;
    let corners = fillets
        .into_iter()
        .map(|f| ChainCorner {
            crossing: f.crossing,
            u0: f.u0,
            v0: f.v0,
            scales: (f.p_scale, f.q_scale),
            max_residual: f.max_residual,
        })
        .collect();
    Ok(ChainFillet { pieces, corners })
}

/// The curves of a chain as references, checked: at least 2, one dimension.
pub(crate) fn chain_refs<C: AsCurveRef>(curves: &[C]) -> Result<Vec<CurveRef<'_>>> {
    let curves: Vec<CurveRef> = curves.iter().map(AsCurveRef::as_curve_ref).collect();
    let n = curves.len();
    if n < 2 {
        return Err(BezjoinError::invalid(
            "curves",
            format!("a chain needs at least 2 curves, {n} given"),
        ));
    }
    let dim = curves[0].dim();
    if let Some(i) = curves.iter().position(|c| c.dim() != dim) {
        return Err(BezjoinError::DimensionMismatch {
            name: format!("curves[{i}]"),
            expected: dim,
            actual: curves[i].dim(),
        });
    }
    Ok(curves)
}

/// Largest part of a curve's length that a kept piece of a chain (or of a
/// single rounded corner, by radius or by setbacks) may have and still be
/// refused as a sliver: cuts
/// this close have met up to the rounding of their arc-length and
/// tangent-point solves (the same relative tolerance as a shared vertex).
pub(super) const SLIVER: f64 = 1e-9;

/// InvalidArgument naming `curves[i]` when its kept piece `[start, end]`
/// is at most [`SLIVER`] of its length: the corners' cuts use the whole
/// curve (a radius or setbacks that fit exactly), and the few ulps left
/// would be an edge no CAD kernel takes ([`check_kept_piece`]).
fn check_not_a_sliver(
    curve: CurveRef,
    i: usize,
    domain: (f64, f64),
    piece: (f64, f64),
) -> Result<()> {
    check_kept_piece(
        curve,
        &format!("curves[{i}]"),
        "the cuts of its two corners leave",
        domain,
        piece,
    )
}

/// The length of `curve` (over its whole domain, to its default accuracy;
/// `name` for the error of an overflowing control polygon) and the
/// longest piece of it that is still a sliver, [`SLIVER`] of that length:
/// the one rule for the pieces that chains, radius fillets and setbacks
/// keep.
pub(crate) fn sliver_length(curve: CurveRef, name: &str) -> Result<(f64, f64)> {
    let (first, last) = curve.domain();
    let whole = curve.arc_length(first, last, curve.checked_default_length_accuracy(name)?)?;
    Ok((whole, SLIVER * whole))
}

/// InvalidArgument naming `name` when the kept piece `[start, end]` of
/// `curve` (domain `(first, last)`) is at most [`SLIVER`] of its length;
/// the message starts with `what` (the cut or cuts that leave it). The
/// lengths are measured only when the piece is within 1e-6 of the domain
/// in parameter ([`short_piece_length`]).
pub(crate) fn check_kept_piece(
    curve: CurveRef,
    name: &str,
    what: &str,
    (first, last): (f64, f64),
    (start, end): (f64, f64),
) -> Result<()> {
    let Some(kept) = short_piece_length(curve, (start, end), last - first, || name.to_string())?
    else {
        return Ok(());
    };
    let (whole, sliver) = sliver_length(curve, name)?;
    if kept > sliver {
        return Ok(());
    }
    Err(BezjoinError::invalid(
        name,
        format!(
            "{what} {kept:e} of its length {} (at most {SLIVER:e} of it): the setbacks (or the \
             radius) use the whole curve",
            Compact(whole)
        ),
    ))
}

/// The pieces of a rounded chain in path order: curve `i` between the cut
/// `v0` of corner `i - 1` and the cut `u0` of corner `i` (`cuts[i] = (u0,
/// v0)`), each followed by its corner's blend ([`ChainFillet::pieces`]).
///
/// Errors: two cuts on one curve that pass each other, or leave at most
/// [`SLIVER`] of its length (InvalidArgument naming the curve).
pub(crate) fn chain_pieces(
    curves: &[CurveRef],
    closed: bool,
    cuts: &[(f64, f64)],
    blends: &[&BezierCurve],
) -> Result<Vec<Curve>> {
    let n = curves.len();
    let corner_count = cuts.len();
    let mut pieces = Vec::with_capacity(2 * n);
    for i in 0..n {
        let (first, last) = curves[i].domain();
        let start = if i > 0 {
            cuts[i - 1].1
        } else if closed {
            cuts[corner_count - 1].1
        } else {
            first
        };
        let end = if i < corner_count { cuts[i].0 } else { last };
        if start >= end || start.is_nan() || end.is_nan() {
            return Err(BezjoinError::invalid(
                format!("curves[{i}]"),
                format!(
                    "the cuts of its two corners pass each other (start {start} >= end {end}); \
                     the setbacks (or the radius) are too long for this curve"
                ),
            ));
        }
        check_not_a_sliver(curves[i], i, (first, last), (start, end))?;
        pieces.push(curves[i].segment(start, end)?);
        if i < corner_count {
            pieces.push(Curve::Bezier(blends[i].clone()));
        }
    }
    Ok(pieces)
}

/// The crossing of corner `index` (`p` then `q` in the chain): the hit
/// nearest the curves' shared end (module documentation).
///
/// Errors: NoIntersection when there is none or the nearest is a tangency
/// or an overlap (the message starts with `corner index`); the search's
/// errors, prefixed likewise.
pub(crate) fn chain_crossing(
    index: usize,
    p: CurveRef,
    q: CurveRef,
    options: &IntersectOptions,
) -> Result<Intersection> {
    let hits = intersect(p, q, options).map_err(|e| in_corner(e, index))?;
    // Distance from the shared end, in units of each domain's length.
    let (p_first, p_last) = p.domain();
    let (q_first, q_last) = q.domain();
    let from_end = |h: &Intersection| {
        (p_last - h.u) / (p_last - p_first) + (h.v - q_first) / (q_last - q_first)
    };
    let nearest = hits
        .into_iter()
        .min_by(|a, b| from_end(a).total_cmp(&from_end(b)));
    match nearest {
        Some(h) if h.kind == IntersectionKind::Crossing => Ok(h),
        Some(h) if h.kind == IntersectionKind::Touching => Err(BezjoinError::NoIntersection {
            reason: format!(
                "corner {index}: the curves meet tangentially at u = {}, v = {} \
                     (a smooth joint), there is no corner to round",
                h.u, h.v
            ),
        }),
        Some(_) => Err(BezjoinError::NoIntersection {
            reason: format!("corner {index}: the curves overlap near their shared end"),
        }),
        None => Err(BezjoinError::NoIntersection {
            reason: format!("corner {index}: the curves do not cross"),
        }),
    }
}

fn round_corner(index: usize, p: CurveRef, q: CurveRef, options: &FilletOptions) -> Result<Fillet> {
    let crossing = chain_crossing(index, p, q, &options.intersect)?;
    fillet_at_validated(p, q, crossing, options).map_err(|e| in_corner(e, index))
}

/// Prefix the argument name (or reason) of an error with its corner.
pub(crate) fn in_corner(error: BezjoinError, index: usize) -> BezjoinError {
    match error {
        BezjoinError::InvalidArgument { name, reason } => BezjoinError::InvalidArgument {
            name: format!("corner {index} {name}"),
            reason,
        },
        BezjoinError::IllConditioned {
            what,
            estimate,
            limit,
        } => BezjoinError::IllConditioned {
            what: format!("corner {index}: {what}"),
            estimate,
            limit,
        },
        BezjoinError::NoIntersection { reason } if !reason.starts_with("corner ") => {
            BezjoinError::NoIntersection {
                reason: format!("corner {index}: {reason}"),
            }
        }
        other => other,
    }
}
