//! Curve-curve intersection of Bezier and NURBS curves of any degree
//! (docs/mathematics.md#intersection and #nurbs,
//! "robust curve-curve intersection of arbitrary degree ...
//! subdivision with bounding boxes, then Newton polishing, all crossings
//! reported in order; in 3D curves must meet within a tolerance").
//!
//! # Algorithm
//!
//! 0. **Spans.** A NURBS curve is cut into its Bezier spans (knot
//!    insertion, exact); a rational span is kept in homogeneous form, halved
//!    exactly by de Casteljau there, and bounded by the box of its Cartesian
//!    poles (positive weights: the convex-hull property holds). Parameters
//!    are the curves' own, in their domains (`[0, 1]` for a Bezier curve);
//!    parameter margins below are relative to the domain's length.
//! 1. **Overlaps first.** Two polynomial (or rational) pieces that coincide
//!    along a stretch coincide up to an end of one of them, so every overlap
//!    starts and ends at a span end (a curve end or a knot) of `P` or `Q`
//!    lying on the other curve. These points are projected onto the other
//!    curve; between two such points, the longest stretches first, the
//!    curves are compared at `(2 (np + nq) + 8) (spans_P + spans_Q - 1)`
//!    interior samples. Where all lie
//!    within the distance tolerance the stretch is reported once as
//!    [`IntersectionKind::Overlap`] and excluded from the search below (so
//!    collinear or coincident pieces are reported, never looped on).
//! 2. **Subdivision.** Pairs of pieces (de Casteljau halves) whose control
//!    point bounding boxes, widened by the distance tolerance, do not meet are
//!    discarded (a Bezier piece lies in the convex hull of its control points).
//!    A pair becomes a leaf when both pieces are flat (control points within
//!    `max(1e-7 * scale, 1e-2 * chord length)` of their chord) or the depth
//!    bound is reached; each leaf gives a seed from the closest points of the
//!    two chords, or, when the chords are nearly parallel (sine of their
//!    angle below about 0.06, where flat pieces might cross twice), seeds
//!    from the four chord ends and the middle. A leaf whose chords are not
//!    nearly parallel and whose parameter box already holds a polished hit
//!    is skipped (such pieces cross at most once).
//!
//!    *Fast path* (module `clip`): for planar curves whose pieces are all
//!    of degree 1..=15 (polynomial, or rational with positive weights), when step 1 found no overlap, the pairs
//!    of spans are first searched by fat-line Bezier clipping (Sederberg
//!    and Nishita 1990) instead: a piece is cut to the parameter interval
//!    where the convex hull of its signed distances from the other piece's
//!    chord meets that piece's fat line widened by the tolerance (only
//!    parameters that provably hold no point within the tolerance of the
//!    other piece are dropped, as with the boxes), alternately on both
//!    pieces, halving the larger one when a round keeps more than 80 % of
//!    both ranges; at a transversal crossing the ranges shrink
//!    quadratically. Flat pairs are leaves with the chord seed above. The
//!    fast path works on the stack (no heap) and gives up, leaving the whole
//!    search to the subdivision, on nearly parallel leaf chords, on a
//!    polished hit whose tangents make a sine of at most `1e-3` (tangency)
//!    or that lies outside its leaf, and past its work bounds (512 rounds,
//!    32 pending pairs, `max_box_pairs`, `max_depth`); so touching points,
//!    overlaps and hard cases are the subdivision's, and a crossing found
//!    by either is the same Newton-polished point.
//! 3. **Polishing.** Each seed is polished on the original curves by
//!    Gauss-Newton on `|P(u) - Q(v)|^2` with Levenberg damping, kept inside
//!    the product of the domains (a variable at its bound is held and the
//!    other solved alone).
//!    At a transversal crossing this is Newton's method on `P(u) = Q(v)` and
//!    converges quadratically to full double precision; at a tangency the
//!    parameters are good to about the square root of the precision, which
//!    is all the data determine. The iteration stops when a full step is at
//!    the rounding level of the parameters (`4 eps` times the domain's
//!    size) or nothing moves.
//! 4. **Acceptance and merging.** A polished pair is a hit when
//!    `|P(u) - Q(v)| <= tolerance` (in 3D this is the closest-approach test:
//!    skew curves do not meet). Hits whose parameters differ by less than
//!    `1e-4` and whose midpoint on `P` also lies within the tolerance of `Q`
//!    are one hit (the one with the smaller distance is kept).
//! 5. **Kind.** In 2D a hit is a [`IntersectionKind::Crossing`] when `P`
//!    passes from one side of `Q` to the other: the tangents make an angle
//!    with `sin > 1e-3`, or else the signed distances of `P(u -+ h)` from
//!    `Q` have opposite signs (with `h` grown until both are well above the
//!    tolerance); same signs is [`IntersectionKind::Touching`]. At an end
//!    point of either curve, and in 3D and higher, only the angle can be
//!    judged: `sin > tangent_tolerance` is a crossing, otherwise touching.
//!
//! Work is bounded: at most `max_depth` subdivision levels, at most
//! `max_box_pairs` box pairs examined and `max_hits` hits; exceeding a bound
//! is an [`BezjoinError::IllConditioned`] error (it happens only when curves
//! run within the tolerance of each other without coinciding), never a hang.

mod clip;
mod track;

use crate::bezier::{BezierCurve, distance, norm};
use crate::curve::CurveRef;
use crate::error::{BezjoinError, Result, check_finite_scalar};
use crate::nurbs::NurbsCurve;
use std::rc::Rc;
use track::{Piece, Pieces, Track, boxes_meet};

/// Dimensions up to which polishing keeps its vectors on the stack.
const POLISH_STACK_DIM: usize = 8;

/// Default of [`IntersectOptions::relative_distance_tolerance`].
pub const DEFAULT_RELATIVE_DISTANCE_TOLERANCE: f64 = 1e-9;
/// Default of [`IntersectOptions::tangent_tolerance`].
pub const DEFAULT_TANGENT_TOLERANCE: f64 = 1e-6;
/// Default of [`IntersectOptions::max_depth`].
pub const DEFAULT_MAX_DEPTH: usize = 60;
/// Default of [`IntersectOptions::max_box_pairs`].
pub const DEFAULT_MAX_BOX_PAIRS: usize = 200_000;
/// Default of [`IntersectOptions::max_hits`].
pub const DEFAULT_MAX_HITS: usize = 10_000;

/// Flatness of a leaf piece, relative to the coordinate scale.
const RELATIVE_FLATNESS: f64 = 1e-7;
/// Flatness of a leaf piece, relative to its chord length.
const RELATIVE_CHORD_FLATNESS: f64 = 1e-2;
/// Above this sine of the tangent angle a 2D hit is a crossing without further tests.
const SURELY_TRANSVERSAL_SINE: f64 = 1e-3;
/// Parameter distance (relative to the domain's length) below which two
/// hits may be the same one.
const MERGE_PARAMETER_DISTANCE: f64 = 1e-4;

/// Tolerances and work bounds of [`intersect`]. `Default` gives the
/// documented defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct IntersectOptions {
    /// Curves meet where `|P(u) - Q(v)| <= relative_distance_tolerance * scale`,
    /// `scale` the largest absolute control-point coordinate of either curve.
    /// Default [`DEFAULT_RELATIVE_DISTANCE_TOLERANCE`] (`1e-9`).
    pub relative_distance_tolerance: f64,
    /// Sine of the tangent angle below which a hit that cannot be judged by
    /// sides (at an end point, or in 3D) is touching rather than crossing.
    /// Default [`DEFAULT_TANGENT_TOLERANCE`] (`1e-6`).
    pub tangent_tolerance: f64,
    /// Largest number of subdivision levels. Default [`DEFAULT_MAX_DEPTH`] (60).
    pub max_depth: usize,
    /// Largest number of bounding-box pairs examined. Default
    /// [`DEFAULT_MAX_BOX_PAIRS`] (200 000).
    pub max_box_pairs: usize,
    /// Largest number of hits reported. Default [`DEFAULT_MAX_HITS`] (10 000).
    pub max_hits: usize,
}

impl Default for IntersectOptions {
    fn default() -> Self {
        Self {
            relative_distance_tolerance: DEFAULT_RELATIVE_DISTANCE_TOLERANCE,
            tangent_tolerance: DEFAULT_TANGENT_TOLERANCE,
            max_depth: DEFAULT_MAX_DEPTH,
            max_box_pairs: DEFAULT_MAX_BOX_PAIRS,
            max_hits: DEFAULT_MAX_HITS,
        }
    }
}

/// What a hit is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntersectionKind {
    /// The curves cross transversally (or, in 2D, `P` changes sides of `Q`).
    Crossing,
    /// The curves meet tangentially without crossing (a double point).
    Touching,
    /// The curves coincide for `u` in `u_range` and `v` in `v_range`;
    /// `v_range.0` is the parameter on `Q` of the point `P(u_range.0)`, so
    /// `v_range` is decreasing when the curves run in opposite directions.
    Overlap {
        /// Start and end parameter on `P` (`u_range.0 < u_range.1`).
        u_range: (f64, f64),
        /// Parameters on `Q` of `P(u_range.0)` and `P(u_range.1)`.
        v_range: (f64, f64),
    },
}

/// One place where two curves meet.
#[derive(Debug, Clone, PartialEq)]
pub struct Intersection {
    /// Parameter on `P` (for an overlap, its start).
    pub u: f64,
    /// Parameter on `Q`.
    pub v: f64,
    /// `P(u)`.
    pub point: Vec<f64>,
    /// `|P(u) - Q(v)|`, at most the distance tolerance.
    pub distance: f64,
    /// Crossing, touching or overlap.
    pub kind: IntersectionKind,
}

/// All places where `p` and `q` meet, ordered by `u` (then `v`).
///
/// See the module documentation for the algorithm and its guarantees.
/// Errors: curves of different dimensions (DimensionMismatch), dimension 1
/// (InvalidArgument: every pair of 1D curves overlaps in their image), bad
/// options (ParameterOutOfRange), a work bound exceeded (IllConditioned).
///
/// ```
/// use bezjoin_core::BezierCurve;
/// use bezjoin_core::{IntersectOptions, IntersectionKind, intersect};
/// let p = BezierCurve::from_rows(&[[0.0, 0.0], [2.0, 2.0]]).unwrap();
/// let q = BezierCurve::from_rows(&[[0.0, 2.0], [1.0, 0.0], [2.0, 0.0]]).unwrap();
/// let hits = intersect(&p, &q, &IntersectOptions::default()).unwrap();
/// assert_eq!(hits.len(), 1);
/// assert_eq!(hits[0].kind, IntersectionKind::Crossing);
/// let (x, y) = (p.eval(hits[0].u), q.eval(hits[0].v));
/// assert!((x[0] - y[0]).abs() < 1e-15 && (x[1] - y[1]).abs() < 1e-15);
/// ```
pub fn intersect<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    options: &IntersectOptions,
) -> Result<Vec<Intersection>> {
    let (p, q) = (p.into(), q.into());
    validate(p, q, options)?;
    // A one-span polynomial NURBS on [a, b] is its Bezier curve in
    // t = (u - a) / (b - a): searched as one (no span decomposition), its
    // parameters mapped back (exact on [0, 1]; elsewhere a few roundings
    // of u, with the ends kept exact).
    let (p_bezier, q_bezier) = (one_span(p), one_span(q));
    let (p_nurbs, q_nurbs) = (
        p_bezier.as_ref().map(|(_, n)| *n),
        q_bezier.as_ref().map(|(_, n)| *n),
    );
    let p = p_bezier.as_ref().map_or(p, |(b, _)| CurveRef::Bezier(b));
    let q = q_bezier.as_ref().map_or(q, |(b, _)| CurveRef::Bezier(b));
    let mut search = Search::new(Track::new(p), Track::new(q), options);
    search.find_overlaps();
    if !search.clip_search() {
        search.subdivide()?;
    }
    let mut hits = search.finish()?;
    let unit = |n: &NurbsCurve| n.domain() == (0.0, 1.0);
    if p_nurbs.is_some_and(|n| !unit(n)) || q_nurbs.is_some_and(|n| !unit(n)) {
        for hit in &mut hits {
            if let Some(n) = p_nurbs {
                hit.u = n.domain_parameter(hit.u);
            }
            if let Some(n) = q_nurbs {
                hit.v = n.domain_parameter(hit.v);
            }
        }
    }
    Ok(hits)
}

/// [`intersect`] by the subdivision alone (the fallback of the clipping
/// fast path, and its independent reference in tests).
#[cfg(test)]
pub(crate) fn intersect_by_subdivision<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    options: &IntersectOptions,
) -> Result<Vec<Intersection>> {
    let (p, q) = (p.into(), q.into());
    validate(p, q, options)?;
    let mut search = Search::new(Track::new(p), Track::new(q), options);
    search.find_overlaps();
    search.subdivide()?;
    search.finish()
}

/// [`intersect`] by the clipping fast path alone; `None` where it gives up.
#[cfg(test)]
pub(crate) fn intersect_by_clipping<'a>(
    p: impl Into<CurveRef<'a>>,
    q: impl Into<CurveRef<'a>>,
    options: &IntersectOptions,
) -> Option<Result<Vec<Intersection>>> {
    let (p, q) = (p.into(), q.into());
    validate(p, q, options).ok()?;
    let mut search = Search::new(Track::new(p), Track::new(q), options);
    search.find_overlaps();
    search.clip_search().then(|| search.finish())
}

/// The Bezier curve of a clamped one-span polynomial NURBS on `[a, b]`
/// (the curve is that Bezier curve in `t = (u - a) / (b - a)`) and the
/// NURBS curve itself; `None` otherwise.
fn one_span<'a>(curve: CurveRef<'a>) -> Option<(BezierCurve, &'a NurbsCurve)> {
    match curve {
        CurveRef::Nurbs(n) => n.one_span_bezier().map(|b| (b, n)),
        CurveRef::Bezier(_) => None,
    }
}

fn validate(p: CurveRef, q: CurveRef, options: &IntersectOptions) -> Result<()> {
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
            "curve intersection needs dimension 2 or more (1D curves overlap in their image)",
        ));
    }
    check_finite_scalar(
        "relative_distance_tolerance",
        options.relative_distance_tolerance,
    )?;
    if !(options.relative_distance_tolerance > 0.0 && options.relative_distance_tolerance < 1.0) {
        return Err(BezjoinError::out_of_range(
            "relative_distance_tolerance",
            options.relative_distance_tolerance,
            "(0, 1)",
        ));
    }
    check_finite_scalar("tangent_tolerance", options.tangent_tolerance)?;
    if !(options.tangent_tolerance >= 0.0 && options.tangent_tolerance < 1.0) {
        return Err(BezjoinError::out_of_range(
            "tangent_tolerance",
            options.tangent_tolerance,
            "[0, 1)",
        ));
    }
    if options.max_box_pairs == 0 {
        return Err(BezjoinError::invalid("max_box_pairs", "must be at least 1"));
    }
    Ok(())
}

/// The two curves, for evaluation during polishing.
struct CurvePair<'a> {
    p: Track<'a>,
    q: Track<'a>,
}

impl CurvePair<'_> {
    /// Gauss-Newton with Levenberg damping on `|P(u) - Q(v)|^2` in the
    /// product of the domains.
    fn polish(&self, u: f64, v: f64) -> (f64, f64, f64) {
        let (u, v, f, _) = self.polish_with_tangents(u, v, &mut []);
        (u, v, f)
    }

    /// `P(u) - Q(v)` into `gap` and the tangents `P'(u)`, `Q'(v)` into `a`,
    /// `b`, each curve in one pass ([`Track::point_and_tangent_into`];
    /// `work` is scratch of length `dim`).
    fn gap_and_tangents_into(
        &self,
        u: f64,
        v: f64,
        gap: &mut [f64],
        a: &mut [f64],
        b: &mut [f64],
        work: &mut [f64],
    ) {
        self.p.point_and_tangent_into(u, gap, a);
        self.q.point_and_tangent_into(v, work, b);
        for (o, w) in gap.iter_mut().zip(work.iter()) {
            *o -= w;
        }
    }

    /// [`Self::polish`], also handing out the tangents `P'(u)`, `Q'(v)` at
    /// the returned `(u, v)` (computed with each point: every accepted step
    /// brings the tangents at its end): `tangents`, of length `2 dim` (else
    /// left alone), holds `P'(u)` then `Q'(v)`. The flag is `false` when
    /// the result is no point (a non-finite parameter or gap).
    fn polish_with_tangents(&self, u: f64, v: f64, tangents: &mut [f64]) -> (f64, f64, f64, bool) {
        // The plane with the dimension as a constant (the vectors' splits
        // and dot products unrolled); the same operations as the general
        // case.
        match self.p.dim() {
            2 => self.polish_sized(2, u, v, tangents),
            d => self.polish_sized(d, u, v, tangents),
        }
    }

    /// [`Self::polish_with_tangents`] in dimension `d` (the curves').
    #[inline(always)]
    fn polish_sized(
        &self,
        d: usize,
        mut u: f64,
        mut v: f64,
        tangents: &mut [f64],
    ) -> (f64, f64, f64, bool) {
        let (u_lo, u_hi) = self.p.domain();
        let (v_lo, v_hi) = self.q.domain();
        // Seven vectors of length `d`: on the stack for small dimensions.
        let mut stack = [0.0f64; 7 * POLISH_STACK_DIM];
        let mut heap = Vec::new();
        let scratch: &mut [f64] = if d <= POLISH_STACK_DIM {
            &mut stack[..7 * d]
        } else {
            heap.resize(7 * d, 0.0);
            &mut heap
        };
        let (r, rest) = scratch.split_at_mut(d);
        let (trial, rest) = rest.split_at_mut(d);
        let (work, rest) = rest.split_at_mut(d);
        let (a, rest) = rest.split_at_mut(d);
        let (b, rest) = rest.split_at_mut(d);
        let (trial_a, trial_b) = rest.split_at_mut(d);
        let (mut r, mut trial, work) = (r, trial, work);
        let (mut a, mut b, mut trial_a, mut trial_b) = (a, b, trial_a, trial_b);
        u = u.clamp(u_lo, u_hi);
        v = v.clamp(v_lo, v_hi);
        self.gap_and_tangents_into(u, v, r, a, b, work);
        let mut f = norm(r);
        // Steps below this are at the rounding level of the parameters.
        let resolution = 4.0
            * f64::EPSILON
            * (u_hi - u_lo)
                .max(v_hi - v_lo)
                .max(u_hi.abs().max(v_hi.abs()).max(u_lo.abs().max(v_lo.abs())));
        for _ in 0..60 {
            if f == 0.0 {
                break;
            }
            let (a_ref, b_ref) = (&*a, &*b);
            let aa = dot(a_ref, a_ref);
            let bb = dot(b_ref, b_ref);
            let ab = dot(a_ref, b_ref);
            let ar = dot(a_ref, r);
            let br = dot(b_ref, r);
            // Normal equations of J = [a, -b]: [aa, -ab; -ab, bb] d = [-ar, br].
            let damping = 1e-15 * (aa + bb) + f64::MIN_POSITIVE;
            let (mut du, mut dv) = solve2(aa + damping, -ab, bb + damping, -ar, br);
            // Hold a variable at its bound if the step leaves the domain, and
            // solve for the other alone.
            let u_out = (u <= u_lo && du < 0.0) || (u >= u_hi && du > 0.0);
            let v_out = (v <= v_lo && dv < 0.0) || (v >= v_hi && dv > 0.0);
            if u_out && v_out {
                break;
            } else if u_out {
                du = 0.0;
                dv = if bb > 0.0 { br / bb } else { 0.0 };
            } else if v_out {
                dv = 0.0;
                du = if aa > 0.0 { -ar / aa } else { 0.0 };
            }
            // A full step at the rounding level of the parameters cannot
            // move them (the backtracking below would only halve it 16
            // times at two evaluations each): converged.
            if du.abs().max(dv.abs()) <= resolution {
                break;
            }
            // Backtracking: accept the first step length that decreases the gap.
            let mut step = 1.0;
            let mut moved = 0.0f64;
            for _ in 0..16 {
                let nu = (u + step * du).clamp(u_lo, u_hi);
                let nv = (v + step * dv).clamp(v_lo, v_hi);
                self.gap_and_tangents_into(nu, nv, trial, trial_a, trial_b, work);
                let nf = norm(trial);
                if nf < f {
                    moved = (nu - u).abs().max((nv - v).abs());
                    u = nu;
                    v = nv;
                    std::mem::swap(&mut r, &mut trial);
                    std::mem::swap(&mut a, &mut trial_a);
                    std::mem::swap(&mut b, &mut trial_b);
                    f = nf;
                    break;
                }
                step *= 0.5;
            }
            // Stop when nothing moves, or the step is at the rounding level.
            if moved <= resolution {
                break;
            }
        }
        // A parameter or gap that is not finite (overflow in the inputs'
        // arithmetic, or a non-finite seed) is no point of either curve: no
        // hit, whatever the gap's comparisons would say.
        if !(u.is_finite() && v.is_finite() && f.is_finite()) {
            return (u, v, f64::INFINITY, false);
        }
        if tangents.len() == 2 * d {
            tangents[..d].copy_from_slice(a);
            tangents[d..].copy_from_slice(b);
        }
        (u, v, f, true)
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solve `[a, b; b, c] x = [r, s]` (symmetric); zero for a singular matrix.
fn solve2(a: f64, b: f64, c: f64, r: f64, s: f64) -> (f64, f64) {
    let det = a * c - b * b;
    if det == 0.0 || !det.is_finite() {
        return (0.0, 0.0);
    }
    ((r * c - b * s) / det, (a * s - b * r) / det)
}

/// Closest points of the chord lines `a0 + s (a1 - a0)` and `b0 + t (b1 -
/// b0)` (minimising `|w + s da - t db|^2`, `w = a0 - b0`), clamped to
/// `[0, 1]^2`; `None` when the chords are nearly parallel
/// (`det <= 4e-3 |da|^2 |db|^2`, a sine below about 0.06, or NaN): flat
/// pieces (within 1e-2 of their chords) can cross twice only then.
fn chord_crossing(a0: &[f64], a1: &[f64], b0: &[f64], b1: &[f64]) -> Option<(f64, f64)> {
    let (mut aa, mut bb, mut ab, mut wa, mut wb) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for c in 0..a0.len() {
        let (da, db, w) = (a1[c] - a0[c], b1[c] - b0[c], a0[c] - b0[c]);
        aa += da * da;
        bb += db * db;
        ab += da * db;
        wa += w * da;
        wb += w * db;
    }
    let det = aa * bb - ab * ab;
    if det <= 4e-3 * aa * bb || det.is_nan() {
        return None;
    }
    let s = ((-wa) * bb + ab * wb) / det;
    let t = (aa * wb - ab * wa) / det;
    Some((s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)))
}

/// Closest parameter on the Bezier `curve` to `x` (with its `hodograph`),
/// starting from samples or from `start`, refined by Gauss-Newton;
/// returns `(t, distance)`.
pub(crate) fn project(
    curve: &BezierCurve,
    hodograph: &BezierCurve,
    x: &[f64],
    start: Option<f64>,
) -> (f64, f64) {
    project_on(&Track::bezier(curve, hodograph), x, start, &[])
}

/// Closest parameter on `track` to `x` (see [`project`]). Without `start`
/// the curve is sampled before Newton: `8 (p + 1)` points per span, or,
/// given the track's `pieces` (a NURBS curve's spans), `2 (p + 1)` points
/// per span with the spans visited nearest box first, skipping those whose
/// box is farther than the best sample so far (they cannot hold a closer
/// point).
fn project_on(track: &Track, x: &[f64], start: Option<f64>, pieces: &[Piece]) -> (f64, f64) {
    let (lo, hi) = track.domain();
    let mut buf = vec![0.0; track.dim()];
    let t = match start {
        Some(t) => t.clamp(lo, hi),
        None if pieces.len() > 1 => {
            let per_span = 2 * (track.degree() + 1);
            let mut order: Vec<(f64, &Piece)> = pieces
                .iter()
                .map(|piece| (piece.box_distance(x), piece))
                .collect();
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut best = (lo, f64::INFINITY);
            for (box_distance, piece) in order {
                if box_distance > best.1 {
                    break;
                }
                sample_piece(track, piece, x, per_span, &mut buf, &mut best);
            }
            best.0
        }
        None => {
            let samples = 8 * (track.degree() + 1) * track.span_count();
            let mut best = (lo, f64::INFINITY);
            for i in 0..=samples {
                let s = (lo + (hi - lo) * i as f64 / samples as f64).min(hi);
                track.eval_into(s, &mut buf);
                let d = distance(&buf, x);
                if d < best.1 {
                    best = (s, d);
                }
            }
            best.0
        }
    };
    newton_within(track, x, t, (lo, hi), false, &mut buf)
}

/// Newton on the squared distance from `x` to `track`, from `t` inside
/// `[lo, hi]`, every step clamped to `[lo, hi]` and accepted only when it
/// brings the point closer (halved up to 16 times): the parameter and the
/// distance where it stops. `inside`: `[lo, hi]` is a piece between
/// breaks, whose tangent at an end is taken a few ulps inside (at a knot
/// the track's own tangent may be the next span's, which would hold Newton
/// at the end). `buf`: scratch of the track's dimension.
fn newton_within(
    track: &Track,
    x: &[f64],
    t: f64,
    (lo, hi): (f64, f64),
    inside: bool,
    buf: &mut [f64],
) -> (f64, f64) {
    let mut t = t;
    track.eval_into(t, buf);
    let mut r: Vec<f64> = buf.iter().zip(x).map(|(a, b)| a - b).collect();
    let mut f = norm(&r);
    let mut tangent = vec![0.0; track.dim()];
    let resolution = 4.0 * f64::EPSILON * (hi - lo).max(lo.abs()).max(hi.abs());
    for _ in 0..60 {
        let at = if inside && hi - lo > 4.0 * resolution {
            t.clamp(lo + resolution, hi - resolution)
        } else {
            t
        };
        track.tangent_into(at, &mut tangent);
        let tt = dot(&tangent, &tangent);
        if tt == 0.0 || f == 0.0 {
            break;
        }
        let dt = -dot(&tangent, &r) / tt;
        if dt.is_nan() {
            // Overflowing dot products (coordinates near 1e300): every trial
            // step below would evaluate at NaN and be refused.
            break;
        }
        if dt.abs() <= resolution {
            // A step at the rounding level of `t`: converged (see `polish`).
            break;
        }
        let mut step = 1.0;
        let mut moved = 0.0f64;
        for _ in 0..16 {
            let nt = (t + step * dt).clamp(lo, hi);
            track.eval_into(nt, buf);
            for (ri, (a, b)) in r.iter_mut().zip(buf.iter().zip(x)) {
                *ri = a - b;
            }
            let nf = norm(&r);
            if nf < f {
                moved = (nt - t).abs();
                t = nt;
                f = nf;
                break;
            }
            step *= 0.5;
        }
        // On acceptance `r` holds the gap at the new `t`; otherwise stop.
        if moved <= resolution {
            break;
        }
    }
    (t, f)
}

/// The sample of `piece` (`per_span + 1` parameters spread evenly over
/// its domain) closest to `x`, into `best` (parameter, distance) when it is
/// closer than `best`.
fn sample_piece(
    track: &Track,
    piece: &Piece,
    x: &[f64],
    per_span: usize,
    buf: &mut [f64],
    best: &mut (f64, f64),
) {
    for i in 0..=per_span {
        let s = (piece.lo + (piece.hi - piece.lo) * i as f64 / per_span as f64)
            .clamp(piece.lo, piece.hi);
        track.eval_into(s, buf);
        let d = distance(buf, x);
        if d < best.1 {
            *best = (s, d);
        }
    }
}

/// [`project_on`] for a point that may lie on `track` (an overlap's end
/// candidate). When the projection from the best sample of all the pieces
/// ends farther than `tol`, the pieces are searched by branch and bound:
/// de Casteljau halves at `1/2` are kept while they may come within `tol`
/// of `x` ([`Piece::may_come_within`], a proof when it says no), and
/// Newton runs inside each kept half that is flat (or at depth
/// [`NEAR_SEARCH_DEPTH`]), from its middle, until one ends within `tol`
/// (at most [`NEAR_SEARCH_NEWTONS`] runs). The one start from the closest
/// sample can be caught by a farther local minimum (weights far apart
/// sample one span densely and the next sparsely; a loop passes near the
/// point); a point of the curve within `tol` is then still found.
fn project_near(track: &Track, x: &[f64], pieces: &[Piece], tol: f64) -> (f64, f64) {
    let mut best = project_on(track, x, None, pieces);
    if best.1 <= tol {
        return best;
    }
    let mut buf = vec![0.0; track.dim()];
    let mut stack: Vec<(Piece, u32)> = pieces.iter().rev().map(|p| (p.clone(), 0)).collect();
    let mut newtons = 0;
    while let Some((piece, depth)) = stack.pop() {
        if !piece.may_come_within(x, tol) {
            continue;
        }
        if depth >= NEAR_SEARCH_DEPTH || piece.is_flat(tol, RELATIVE_CHORD_FLATNESS) {
            let middle = 0.5 * (piece.lo + piece.hi);
            let found = newton_within(track, x, middle, (piece.lo, piece.hi), true, &mut buf);
            if found.1 < best.1 {
                best = found;
                if best.1 <= tol {
                    break;
                }
            }
            newtons += 1;
            if newtons >= NEAR_SEARCH_NEWTONS {
                break;
            }
            continue;
        }
        let (left, right) = piece.split();
        stack.push((right, depth + 1));
        stack.push((left, depth + 1));
    }
    best
}

/// Halving depth of [`project_near`]'s search.
const NEAR_SEARCH_DEPTH: u32 = 24;
/// Newton runs of [`project_near`]'s search.
const NEAR_SEARCH_NEWTONS: usize = 64;

struct Overlap {
    u: (f64, f64),
    v: (f64, f64),
}

impl Overlap {
    fn v_min(&self) -> f64 {
        self.v.0.min(self.v.1)
    }
    fn v_max(&self) -> f64 {
        self.v.0.max(self.v.1)
    }
    fn contains_box(&self, a: &Piece, b: &Piece) -> bool {
        a.lo >= self.u.0 && a.hi <= self.u.1 && b.lo >= self.v_min() && b.hi <= self.v_max()
    }
    /// `(u, v)` within the overlap widened by `margin` of each domain's length.
    fn contains_hit(&self, u: f64, v: f64, margin: f64, units: (f64, f64)) -> bool {
        let (mu, mv) = (margin * units.0, margin * units.1);
        u >= self.u.0 - mu && u <= self.u.1 + mu && v >= self.v_min() - mv && v <= self.v_max() + mv
    }
}

struct Candidate {
    u: f64,
    v: f64,
    distance: f64,
    /// `P'(u)` and `Q'(v)` of a planar hit when already computed (by
    /// [`Track::tangent_into`], so [`Search::classify`] takes them as they
    /// are).
    tangents: Option<[f64; 4]>,
}

struct Search<'a> {
    pair: CurvePair<'a>,
    options: &'a IntersectOptions,
    tolerance: f64,
    flatness: f64,
    /// Lengths of the two domains (1 for Bezier curves): parameter margins
    /// are relative to them.
    units: (f64, f64),
    /// The curves' Bezier spans (computed once).
    p_pieces: Pieces<'a>,
    q_pieces: Pieces<'a>,
    overlaps: Vec<Overlap>,
    candidates: Vec<Candidate>,
}

impl<'a> Search<'a> {
    fn new(p: Track<'a>, q: Track<'a>, options: &'a IntersectOptions) -> Self {
        let scale = p.coordinate_scale().max(q.coordinate_scale());
        let tolerance = options.relative_distance_tolerance * scale;
        Self {
            units: (p.domain().1 - p.domain().0, q.domain().1 - q.domain().0),
            p_pieces: p.pieces(),
            q_pieces: q.pieces(),
            pair: CurvePair { p, q },
            options,
            tolerance,
            flatness: (RELATIVE_FLATNESS * scale).max(tolerance),
            overlaps: Vec::new(),
            candidates: Vec::new(),
        }
    }

    fn find_overlaps(&mut self) {
        let pair = &self.pair;
        let tol = self.tolerance;
        let mut ends: Vec<(f64, f64)> = Vec::new();
        let (p_pieces, q_pieces) = (&self.p_pieces, &self.q_pieces);
        // A break point is projected onto the other curve only when a piece of
        // that curve may come within the tolerance of it (boxes of de
        // Casteljau halves, [`Piece::may_come_within`]): otherwise the
        // projection could not find it within the tolerance.
        let near = |pieces: &[Piece], x: &[f64]| pieces.iter().any(|b| b.may_come_within(x, tol));
        let near_widened = |pieces: &[Piece], x: &[f64], margin: f64| {
            pieces.iter().any(|b| b.may_come_within(x, margin))
        };
        // The end points: on the stack for small dimensions.
        let dim = pair.p.dim();
        let mut stack = [0.0f64; POLISH_STACK_DIM];
        let mut heap = Vec::new();
        let x: &mut [f64] = if dim <= POLISH_STACK_DIM {
            &mut stack[..dim]
        } else {
            heap.resize(dim, 0.0);
            &mut heap
        };
        let (p_breaks, q_breaks) = (pair.p.breaks(), pair.q.breaks());
        // A NURBS curve's break point is first tried at its
        // pieces' end control point (the same point in exact arithmetic:
        // both it and the evaluation are within `slack` of it), with the
        // tolerance widened by twice that; only a point that passes is
        // evaluated and tested as before. Since widening the margin by
        // `2 slack` covers every point within `slack` of the evaluated
        // point, this skips only points the old test refuses.
        let approximate = |slack: Option<f64>,
                           pieces: &[Piece],
                           other: &[Piece],
                           i: usize,
                           x: &mut [f64]|
         -> bool {
            let Some(slack) = slack else {
                return true;
            };
            let (piece, end) = if i < pieces.len() {
                (&pieces[i], 0)
            } else {
                (&pieces[pieces.len() - 1], pieces[pieces.len() - 1].degree())
            };
            x.copy_from_slice(piece.point(end));
            !slack.is_finite() || near_widened(other, x, tol + 2.0 * slack)
        };
        let (p_slack, q_slack) = (pair.p.break_slack(), pair.q.break_slack());
        for (i, &u) in p_breaks.iter().enumerate() {
            if p_breaks.len() == p_pieces.len() + 1
                && !approximate(p_slack, p_pieces, q_pieces, i, x)
            {
                continue;
            }
            pair.p.break_point_into(u, x);
            if near(q_pieces, x) {
                let (v, d) = project_near(&pair.q, x, q_pieces, tol);
                if d <= tol {
                    ends.push((u, v));
                }
            }
        }
        for (i, &v) in q_breaks.iter().enumerate() {
            if q_breaks.len() == q_pieces.len() + 1
                && !approximate(q_slack, q_pieces, p_pieces, i, x)
            {
                continue;
            }
            pair.q.break_point_into(v, x);
            if near(p_pieces, x) {
                let (u, d) = project_near(&pair.p, x, p_pieces, tol);
                if d <= tol {
                    ends.push((u, v));
                }
            }
        }
        if ends.len() < 2 {
            return;
        }
        ends.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let per_span = 2 * (pair.p.degree() + pair.q.degree()) + 8;
        let units = self.units;
        // Candidate stretches between two ends. Few ends (Bezier curves have
        // at most four): every pair, longest first, so that a stretch across
        // several spans is found whole and its parts are not reported. Many
        // ends (a multi-span curve lying along the other): consecutive ends
        // only, merged below; a longer overlap is a chain of them, since
        // every break inside it is an end too.
        let mut stretches: Vec<((f64, f64), (f64, f64))> = Vec::new();
        let all_pairs = ends.len() <= 8;
        for i in 0..ends.len() {
            let last = if all_pairs {
                ends.len()
            } else {
                (i + 2).min(ends.len())
            };
            for j in i + 1..last {
                let (u0, v0) = ends[i];
                let (u1, v1) = ends[j];
                if u1 - u0 > 1e-9 * units.0 && (v1 - v0).abs() > 1e-9 * units.1 {
                    stretches.push(((u0, v0), (u1, v1)));
                }
            }
        }
        stretches.sort_by(|a, b| (b.1.0 - b.0.0).total_cmp(&(a.1.0 - a.0.0)));
        for ((u0, v0), (u1, v1)) in stretches {
            if self
                .overlaps
                .iter()
                .any(|o| o.contains_hit(u0, v0, 1e-9, units) && o.contains_hit(u1, v1, 1e-9, units))
            {
                continue;
            }
            // Samples in proportion to the spans the stretch crosses.
            let (v_lo, v_hi) = (v0.min(v1), v0.max(v1));
            let crossed = p_breaks.iter().filter(|&&b| b > u0 && b < u1).count()
                + q_breaks.iter().filter(|&&b| b > v_lo && b < v_hi).count();
            let samples = per_span * (crossed + 1);
            let coincide = (1..samples).all(|s| {
                let w = s as f64 / samples as f64;
                let u = u0 + w * (u1 - u0);
                let guess = v0 + w * (v1 - v0);
                let (v, d) = project_on(&pair.q, &pair.p.eval(u), Some(guess), &[]);
                d <= tol && v >= v_lo - 1e-9 * units.1 && v <= v_hi + 1e-9 * units.1
            });
            if coincide {
                self.overlaps.push(Overlap {
                    u: (u0, u1),
                    v: (v0, v1),
                });
            }
        }
        // Overlaps that continue each other (one's end is the next one's
        // start, in both parameters) are one overlap.
        self.overlaps.sort_by(|a, b| a.u.0.total_cmp(&b.u.0));
        let mut merged: Vec<Overlap> = Vec::with_capacity(self.overlaps.len());
        for o in self.overlaps.drain(..) {
            match merged.last_mut() {
                Some(m) if m.u.1 == o.u.0 && m.v.1 == o.v.0 => {
                    m.u.1 = o.u.1;
                    m.v.1 = o.v.1;
                }
                _ => merged.push(o),
            }
        }
        self.overlaps = merged;
    }

    fn subdivide(&mut self) -> Result<()> {
        // Pieces are shared by the pairs on the stack (a split piece meets
        // both halves of the other): reference-counted, never copied.
        // Every pair of spans, pushed in reverse so that small u comes first.
        let p_pieces: Vec<Rc<Piece>> = self.p_pieces.iter().cloned().map(Rc::new).collect();
        let q_pieces: Vec<Rc<Piece>> = self.q_pieces.iter().cloned().map(Rc::new).collect();
        let mut stack = Vec::with_capacity(p_pieces.len() * q_pieces.len() + 16);
        for a in p_pieces.iter().rev() {
            for b in q_pieces.iter().rev() {
                stack.push((Rc::clone(a), Rc::clone(b), 0usize));
            }
        }
        let mut examined = 0usize;
        let margin = self.tolerance;
        fn halves<'p>(piece: &Piece<'p>) -> (Rc<Piece<'p>>, Rc<Piece<'p>>) {
            let (h0, h1) = piece.split();
            (Rc::new(h0), Rc::new(h1))
        }
        while let Some((a, b, depth)) = stack.pop() {
            examined += 1;
            if examined > self.options.max_box_pairs {
                return Err(BezjoinError::IllConditioned {
                    what: format!(
                        "curve intersection: more than max_box_pairs = {} bounding-box pairs \
                         (the curves run within the tolerance of each other without coinciding)",
                        self.options.max_box_pairs
                    ),
                    estimate: examined as f64,
                    limit: self.options.max_box_pairs as f64,
                });
            }
            if !boxes_meet(&a, &b, margin) {
                continue;
            }
            if self.overlaps.iter().any(|o| o.contains_box(&a, &b)) {
                continue;
            }
            let flat_a = a.is_flat(self.flatness, RELATIVE_CHORD_FLATNESS);
            let flat_b = b.is_flat(self.flatness, RELATIVE_CHORD_FLATNESS);
            if (flat_a && flat_b) || depth >= self.options.max_depth {
                self.leaf(&a, &b);
                // Saturating: any max_hits is valid, up to usize::MAX.
                let threshold = self.options.max_hits.saturating_mul(4).saturating_add(64);
                if self.candidates.len() > threshold {
                    self.merge_candidates();
                }
                continue;
            }
            // Split what is not flat; when both are curved, split both.
            let split_a = !flat_a && (flat_b || a.diagonal() >= 0.25 * b.diagonal());
            let split_b = !flat_b && (flat_a || b.diagonal() >= 0.25 * a.diagonal());
            match (split_a, split_b) {
                (true, true) => {
                    let (a0, a1) = halves(&a);
                    let (b0, b1) = halves(&b);
                    // Pushed in reverse so that small u is examined first.
                    stack.push((Rc::clone(&a1), Rc::clone(&b1), depth + 1));
                    stack.push((a1, Rc::clone(&b0), depth + 1));
                    stack.push((Rc::clone(&a0), b1, depth + 1));
                    stack.push((a0, b0, depth + 1));
                }
                (true, false) => {
                    let (a0, a1) = halves(&a);
                    stack.push((a1, Rc::clone(&b), depth + 1));
                    stack.push((a0, b, depth + 1));
                }
                _ => {
                    let (b0, b1) = halves(&b);
                    stack.push((Rc::clone(&a), b1, depth + 1));
                    stack.push((a, b0, depth + 1));
                }
            }
        }
        Ok(())
    }

    /// Seeds from the chords of a leaf pair, polished on the whole curves.
    fn leaf(&mut self, a: &Piece, b: &Piece) {
        let na = a.degree();
        let nb = b.degree();
        let a0 = a.point(0);
        let a1 = a.point(na);
        let b0 = b.point(0);
        let b1 = b.point(nb);
        let mut seeds: Vec<(f64, f64)> = Vec::with_capacity(5);
        if let Some(seed) = chord_crossing(a0, a1, b0, b1) {
            if self.known_in(a.lo, a.hi, b.lo, b.hi) {
                // Chords that are not nearly parallel cross at most once: this
                // leaf's crossing is already known.
                return;
            }
            seeds.push(seed);
        } else {
            let da: Vec<f64> = a1.iter().zip(a0).map(|(x, y)| x - y).collect();
            let db: Vec<f64> = b1.iter().zip(b0).map(|(x, y)| x - y).collect();
            let (aa, bb) = (dot(&da, &da), dot(&db, &db));
            let proj = |x: &[f64], origin: &[f64], dir: &[f64], len2: f64| -> f64 {
                if len2 > 0.0 {
                    let rel: Vec<f64> = x.iter().zip(origin).map(|(p, o)| p - o).collect();
                    (dot(&rel, dir) / len2).clamp(0.0, 1.0)
                } else {
                    0.5
                }
            };
            seeds.push((0.0, proj(a0, b0, &db, bb)));
            seeds.push((1.0, proj(a1, b0, &db, bb)));
            seeds.push((proj(b0, a0, &da, aa), 0.0));
            seeds.push((proj(b1, a0, &da, aa), 1.0));
            seeds.push((0.5, 0.5));
        }
        for (s, t) in seeds {
            let u = a.lo + s * (a.hi - a.lo);
            let v = b.lo + t * (b.hi - b.lo);
            let (mut u, mut v, d) = self.pair.polish(u, v);
            // A constant curve (degree 0) has no preferred parameter: report
            // the start of its domain.
            if self.pair.p.degree() == 0 {
                u = self.pair.p.domain().0;
            }
            if self.pair.q.degree() == 0 {
                v = self.pair.q.domain().0;
            }
            if d <= self.tolerance {
                self.candidates.push(Candidate {
                    u,
                    v,
                    distance: d,
                    tangents: None,
                });
            }
        }
    }

    /// Whether one of the last few hits lies in the parameter box
    /// `[u_lo, u_hi] x [v_lo, v_hi]`.
    fn known_in(&self, u_lo: f64, u_hi: f64, v_lo: f64, v_hi: f64) -> bool {
        self.candidates
            .iter()
            .rev()
            .take(8)
            .any(|c| c.u >= u_lo && c.u <= u_hi && c.v >= v_lo && c.v <= v_hi)
    }

    /// Sort the candidates and merge those that are one hit.
    fn merge_candidates(&mut self) {
        if self.candidates.len() <= 1 && self.overlaps.is_empty() {
            // Nothing to sort, merge or drop.
            return;
        }
        let mut cands = std::mem::take(&mut self.candidates);
        cands.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
        let mut merged: Vec<Candidate> = Vec::with_capacity(cands.len());
        for c in cands {
            if self
                .overlaps
                .iter()
                .any(|o| o.contains_hit(c.u, c.v, 1e-9, self.units))
            {
                continue;
            }
            let same = merged.iter().rposition(|m| self.same_hit(m, &c));
            match same {
                Some(i) => {
                    if c.distance < merged[i].distance {
                        merged[i] = c;
                    }
                }
                None => merged.push(c),
            }
        }
        merged.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
        self.candidates = self.without_seam_repeats(merged);
    }

    /// A closed curve's two ends are one point (a full circle at `0` and
    /// `2 pi`): a hit found at its domain's end that is the same hit as one
    /// at its start ([`Self::same_hit`] with the end's parameter moved to the
    /// start) is dropped, the other hit kept (in the order of `hits`). A
    /// curve is closed when its ends are within the distance tolerance of
    /// each other.
    fn without_seam_repeats(&self, hits: Vec<Candidate>) -> Vec<Candidate> {
        if hits.len() < 2 {
            return hits;
        }
        let closed = |track: &Track, unit: f64| {
            let (first, last) = track.domain();
            let ends = distance(&track.eval(first), &track.eval(last));
            // Domains shorter than the merge distance hold one hit anyway.
            (ends <= self.tolerance && last - first > 2.0 * MERGE_PARAMETER_DISTANCE * unit)
                .then_some((first, last))
        };
        let p_seam = closed(&self.pair.p, self.units.0);
        let q_seam = closed(&self.pair.q, self.units.1);
        if p_seam.is_none() && q_seam.is_none() {
            return hits;
        }
        let to_start = |x: f64, seam: Option<(f64, f64)>, unit: f64| match seam {
            Some((first, last)) if (last - x).abs() <= MERGE_PARAMETER_DISTANCE * unit => first,
            _ => x,
        };
        let mut dropped = vec![false; hits.len()];
        for (i, c) in hits.iter().enumerate() {
            let moved = Candidate {
                u: to_start(c.u, p_seam, self.units.0),
                v: to_start(c.v, q_seam, self.units.1),
                distance: c.distance,
                tangents: None,
            };
            if moved.u == c.u && moved.v == c.v {
                continue;
            }
            dropped[i] = hits
                .iter()
                .enumerate()
                .any(|(j, d)| j != i && !dropped[j] && self.same_hit(d, &moved));
        }
        hits.into_iter()
            .zip(dropped)
            .filter_map(|(c, dropped)| (!dropped).then_some(c))
            .collect()
    }

    fn same_hit(&self, a: &Candidate, b: &Candidate) -> bool {
        if (a.u - b.u).abs() > MERGE_PARAMETER_DISTANCE * self.units.0
            || (a.v - b.v).abs() > MERGE_PARAMETER_DISTANCE * self.units.1
        {
            return false;
        }
        if a.u == b.u && a.v == b.v {
            return true;
        }
        let mid_u = 0.5 * (a.u + b.u);
        let mid_v = 0.5 * (a.v + b.v);
        let x = self.pair.p.eval(mid_u);
        let (_, d) = project_on(&self.pair.q, &x, Some(mid_v), &[]);
        d <= self.tolerance
    }

    fn finish(mut self) -> Result<Vec<Intersection>> {
        self.merge_candidates();
        let hit_count = self.candidates.len() + self.overlaps.len();
        if hit_count > self.options.max_hits {
            return Err(BezjoinError::IllConditioned {
                what: format!(
                    "curve intersection: more than max_hits = {} hits",
                    self.options.max_hits
                ),
                estimate: hit_count as f64,
                limit: self.options.max_hits as f64,
            });
        }
        let mut hits: Vec<Intersection> = Vec::with_capacity(hit_count);
        for (i, c) in self.candidates.iter().enumerate() {
            let (first, last) = self.pair.p.domain();
            let lower = if i > 0 {
                self.candidates[i - 1].u
            } else {
                first
            };
            let upper = self.candidates.get(i + 1).map_or(last, |n| n.u);
            let kind = self.classify(c, lower, upper);
            hits.push(Intersection {
                u: c.u,
                v: c.v,
                point: self.pair.p.eval(c.u),
                distance: c.distance,
                kind,
            });
        }
        for o in &self.overlaps {
            let point = self.pair.p.eval(o.u.0);
            let distance = distance(&point, &self.pair.q.eval(o.v.0));
            hits.push(Intersection {
                u: o.u.0,
                v: o.v.0,
                point,
                distance,
                kind: IntersectionKind::Overlap {
                    u_range: o.u,
                    v_range: o.v,
                },
            });
        }
        hits.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
        Ok(hits)
    }

    /// Crossing or touching (module documentation, step 5). `lower`,
    /// `upper`: parameters on `P` of the neighbouring hits (or the ends).
    fn classify(&self, c: &Candidate, lower: f64, upper: f64) -> IntersectionKind {
        // The two tangents: on the stack for small dimensions.
        let d = self.pair.p.dim();
        let mut stack = [0.0f64; 2 * POLISH_STACK_DIM];
        let mut heap = Vec::new();
        let scratch: &mut [f64] = if d <= POLISH_STACK_DIM {
            &mut stack[..2 * d]
        } else {
            heap.resize(2 * d, 0.0);
            &mut heap
        };
        let (a, b) = scratch.split_at_mut(d);
        match c.tangents {
            Some(known) if d == 2 => {
                a.copy_from_slice(&known[..2]);
                b.copy_from_slice(&known[2..]);
            }
            _ => {
                self.pair.p.tangent_into(c.u, a);
                self.pair.q.tangent_into(c.v, b);
            }
        }
        let (a, b) = (&*a, &*b);
        let na = norm(a);
        let nb = norm(b);
        let sine = if na > 0.0 && nb > 0.0 {
            let cos = dot(a, b) / (na * nb);
            (1.0 - cos * cos).max(0.0).sqrt()
        } else {
            0.0
        };
        let by_angle = if sine > self.options.tangent_tolerance {
            IntersectionKind::Crossing
        } else {
            IntersectionKind::Touching
        };
        let dim = self.pair.p.dim();
        let (u_lo, u_hi) = self.pair.p.domain();
        let (v_lo, v_hi) = self.pair.q.domain();
        let interior = c.u > u_lo && c.u < u_hi && c.v > v_lo && c.v < v_hi;
        if dim != 2 || !interior {
            return by_angle;
        }
        if sine > SURELY_TRANSVERSAL_SINE {
            return IntersectionKind::Crossing;
        }
        // Side test: signed distance of P(u -+ h) from Q.
        let room = (0.5 * (c.u - lower)).min(0.5 * (upper - c.u));
        let mut h = (1e-7 * self.units.0).min(room);
        while h > 0.0 && h <= room {
            let before = self.signed_side(c.u - h, c.v);
            let after = self.signed_side(c.u + h, c.v);
            if let (Some(before), Some(after)) = (before, after) {
                let noise = 16.0 * self.tolerance;
                if before.abs() > noise && after.abs() > noise {
                    return if before.signum() != after.signum() {
                        IntersectionKind::Crossing
                    } else {
                        IntersectionKind::Touching
                    };
                }
            } else {
                break;
            }
            h *= 4.0;
        }
        by_angle
    }

    /// Signed distance of `P(u)` from `Q` near `v` (positive to the left of
    /// `Q`'s direction); `None` if the foot point is at an end of `Q`.
    fn signed_side(&self, u: f64, v: f64) -> Option<f64> {
        let x = self.pair.p.eval(u);
        let (w, d) = project_on(&self.pair.q, &x, Some(v), &[]);
        let (lo, hi) = self.pair.q.domain();
        if w <= lo || w >= hi {
            return None;
        }
        let tangent = self.pair.q.tangent(w);
        let foot = self.pair.q.eval(w);
        let cross = tangent[0] * (x[1] - foot[1]) - tangent[1] * (x[0] - foot[0]);
        Some(if cross >= 0.0 { d } else { -d })
    }
}
