//! Curve-curve intersection of Bezier curves of any degree (docs/mathematics.md#intersection,
//! "robust curve-curve intersection of arbitrary degree ...
//! subdivision with bounding boxes, then Newton polishing, all crossings
//! reported in order; in 3D curves must meet within a tolerance").
//!
//! # Algorithm
//!
//! 1. **Overlaps first.** Two polynomial curves that coincide along a stretch
//!    coincide up to an end of one of them, so every overlap starts and ends at
//!    an end point of `P` or `Q` lying on the other curve. The end points of
//!    each curve are projected onto the other; between two such points the
//!    curves are compared at `2 (np + nq) + 8` interior samples. Where all lie
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
//! 3. **Polishing.** Each seed is polished on the original curves by
//!    Gauss-Newton on `|P(u) - Q(v)|^2` with Levenberg damping, kept inside
//!    `[0, 1]^2` (a variable at its bound is held and the other solved alone).
//!    At a transversal crossing this is Newton's method on `P(u) = Q(v)` and
//!    converges quadratically to full double precision; at a tangency the
//!    parameters are good to about the square root of the precision, which
//!    is all the data determine.
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

use crate::bezier::{BezierCurve, distance, norm};
use crate::error::{BezjoinError, Result, check_finite_scalar};

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
/// Parameter distance below which two hits may be the same one.
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
pub fn intersect(
    p: &BezierCurve,
    q: &BezierCurve,
    options: &IntersectOptions,
) -> Result<Vec<Intersection>> {
    validate(p, q, options)?;
    let mut search = Search::new(p, q, options);
    search.find_overlaps();
    search.subdivide()?;
    search.finish()
}

fn validate(p: &BezierCurve, q: &BezierCurve, options: &IntersectOptions) -> Result<()> {
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

/// A piece `curve = original|[lo, hi]` with its control-point bounding box.
#[derive(Clone)]
struct Piece {
    curve: BezierCurve,
    lo: f64,
    hi: f64,
    min: Vec<f64>,
    max: Vec<f64>,
}

impl Piece {
    fn new(curve: BezierCurve, lo: f64, hi: f64) -> Self {
        let d = curve.dim();
        let mut min = vec![f64::INFINITY; d];
        let mut max = vec![f64::NEG_INFINITY; d];
        for row in curve.points().chunks_exact(d) {
            for c in 0..d {
                min[c] = min[c].min(row[c]);
                max[c] = max[c].max(row[c]);
            }
        }
        Self {
            curve,
            lo,
            hi,
            min,
            max,
        }
    }

    fn split(&self) -> (Piece, Piece) {
        let (a, b) = self.curve.split_unchecked(0.5);
        let mid = 0.5 * (self.lo + self.hi);
        (Piece::new(a, self.lo, mid), Piece::new(b, mid, self.hi))
    }

    /// Flat enough to seed Newton from the chord: control points within
    /// `max(absolute, RELATIVE_CHORD_FLATNESS * chord)` of the chord.
    fn is_flat(&self, absolute: f64) -> bool {
        let n = self.curve.degree();
        let chord = distance(self.curve.point(0), self.curve.point(n));
        self.deviation_from_chord() <= absolute.max(RELATIVE_CHORD_FLATNESS * chord)
    }

    fn contains(&self, x: &[f64], margin: f64) -> bool {
        (0..x.len()).all(|c| x[c] >= self.min[c] - margin && x[c] <= self.max[c] + margin)
    }

    fn diagonal(&self) -> f64 {
        distance(&self.min, &self.max)
    }

    /// Largest distance of a control point from the chord (from the first
    /// point when the chord is degenerate).
    fn deviation_from_chord(&self) -> f64 {
        let n = self.curve.degree();
        let a = self.curve.point(0);
        let b = self.curve.point(n);
        let chord: Vec<f64> = b.iter().zip(a).map(|(x, y)| x - y).collect();
        let len2: f64 = chord.iter().map(|x| x * x).sum();
        let mut worst = 0.0f64;
        for i in 1..n {
            let p = self.curve.point(i);
            let rel: Vec<f64> = p.iter().zip(a).map(|(x, y)| x - y).collect();
            let dev = if len2 > 0.0 {
                let s = rel.iter().zip(&chord).map(|(x, y)| x * y).sum::<f64>() / len2;
                let perp: f64 = rel
                    .iter()
                    .zip(&chord)
                    .map(|(x, y)| (x - s * y) * (x - s * y))
                    .sum::<f64>();
                // Points beyond the chord's ends also count as deviation.
                let beyond = if s < 0.0 {
                    -s
                } else if s > 1.0 {
                    s - 1.0
                } else {
                    0.0
                };
                (perp + beyond * beyond * len2).sqrt()
            } else {
                norm(&rel)
            };
            worst = worst.max(dev);
        }
        worst
    }
}

fn boxes_meet(a: &Piece, b: &Piece, margin: f64) -> bool {
    (0..a.min.len()).all(|c| a.min[c] <= b.max[c] + margin && b.min[c] <= a.max[c] + margin)
}

/// The curves with their hodographs, for evaluation during polishing.
struct CurvePair<'a> {
    p: &'a BezierCurve,
    q: &'a BezierCurve,
    dp: BezierCurve,
    dq: BezierCurve,
}

impl CurvePair<'_> {
    /// `P(u) - Q(v)` into `out` (`work` is scratch of length `dim`).
    fn gap_into(&self, u: f64, v: f64, out: &mut [f64], work: &mut [f64]) {
        self.p.eval_into(u, out);
        self.q.eval_into(v, work);
        for (o, w) in out.iter_mut().zip(work.iter()) {
            *o -= w;
        }
    }

    /// Gauss-Newton with Levenberg damping on `|P(u) - Q(v)|^2` in `[0,1]^2`.
    fn polish(&self, mut u: f64, mut v: f64) -> (f64, f64, f64) {
        let d = self.p.dim();
        let mut r = vec![0.0; d];
        let mut trial = vec![0.0; d];
        let mut work = vec![0.0; d];
        let mut a = vec![0.0; d];
        let mut b = vec![0.0; d];
        u = u.clamp(0.0, 1.0);
        v = v.clamp(0.0, 1.0);
        self.gap_into(u, v, &mut r, &mut work);
        let mut f = norm(&r);
        for _ in 0..60 {
            if f == 0.0 {
                break;
            }
            self.dp.eval_into(u, &mut a);
            self.dq.eval_into(v, &mut b);
            let aa = dot(&a, &a);
            let bb = dot(&b, &b);
            let ab = dot(&a, &b);
            let ar = dot(&a, &r);
            let br = dot(&b, &r);
            // Normal equations of J = [a, -b]: [aa, -ab; -ab, bb] d = [-ar, br].
            let damping = 1e-15 * (aa + bb) + f64::MIN_POSITIVE;
            let (mut du, mut dv) = solve2(aa + damping, -ab, bb + damping, -ar, br);
            // Hold a variable at its bound if the step leaves the square, and
            // solve for the other alone.
            let u_out = (u <= 0.0 && du < 0.0) || (u >= 1.0 && du > 0.0);
            let v_out = (v <= 0.0 && dv < 0.0) || (v >= 1.0 && dv > 0.0);
            if u_out && v_out {
                break;
            } else if u_out {
                du = 0.0;
                dv = if bb > 0.0 { br / bb } else { 0.0 };
            } else if v_out {
                dv = 0.0;
                du = if aa > 0.0 { -ar / aa } else { 0.0 };
            }
            // Backtracking: accept the first step length that decreases the gap.
            let mut step = 1.0;
            let mut moved = 0.0f64;
            for _ in 0..16 {
                let nu = (u + step * du).clamp(0.0, 1.0);
                let nv = (v + step * dv).clamp(0.0, 1.0);
                self.gap_into(nu, nv, &mut trial, &mut work);
                let nf = norm(&trial);
                if nf < f {
                    moved = (nu - u).abs().max((nv - v).abs());
                    u = nu;
                    v = nv;
                    std::mem::swap(&mut r, &mut trial);
                    f = nf;
                    break;
                }
                step *= 0.5;
            }
            // Stop when nothing moves, or the step is at the rounding level.
            if moved <= 4.0 * f64::EPSILON {
                break;
            }
        }
        (u, v, f)
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

/// Closest parameter on `curve` to `x`, starting from samples and refined by
/// Gauss-Newton; returns `(t, distance)`.
pub(crate) fn project(
    curve: &BezierCurve,
    hodograph: &BezierCurve,
    x: &[f64],
    start: Option<f64>,
) -> (f64, f64) {
    let mut buf = vec![0.0; curve.dim()];
    let mut t = match start {
        Some(t) => t.clamp(0.0, 1.0),
        None => {
            let samples = 8 * (curve.degree() + 1);
            let mut best = (0.0, f64::INFINITY);
            for i in 0..=samples {
                let s = i as f64 / samples as f64;
                curve.eval_into(s, &mut buf);
                let d = distance(&buf, x);
                if d < best.1 {
                    best = (s, d);
                }
            }
            best.0
        }
    };
    curve.eval_into(t, &mut buf);
    let mut r: Vec<f64> = buf.iter().zip(x).map(|(a, b)| a - b).collect();
    let mut f = norm(&r);
    let mut tangent = vec![0.0; curve.dim()];
    for _ in 0..60 {
        hodograph.eval_into(t, &mut tangent);
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
        let mut step = 1.0;
        let mut moved = 0.0f64;
        for _ in 0..16 {
            let nt = (t + step * dt).clamp(0.0, 1.0);
            curve.eval_into(nt, &mut buf);
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
        if moved <= 4.0 * f64::EPSILON {
            break;
        }
    }
    (t, f)
}

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
    fn contains_hit(&self, u: f64, v: f64, margin: f64) -> bool {
        u >= self.u.0 - margin
            && u <= self.u.1 + margin
            && v >= self.v_min() - margin
            && v <= self.v_max() + margin
    }
}

struct Candidate {
    u: f64,
    v: f64,
    distance: f64,
}

struct Search<'a> {
    pair: CurvePair<'a>,
    options: &'a IntersectOptions,
    tolerance: f64,
    flatness: f64,
    overlaps: Vec<Overlap>,
    candidates: Vec<Candidate>,
}

impl<'a> Search<'a> {
    fn new(p: &'a BezierCurve, q: &'a BezierCurve, options: &'a IntersectOptions) -> Self {
        let scale = p.coordinate_scale().max(q.coordinate_scale());
        let tolerance = options.relative_distance_tolerance * scale;
        Self {
            pair: CurvePair {
                p,
                q,
                dp: p.hodograph(),
                dq: q.hodograph(),
            },
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
        let p_box = Piece::new(pair.p.clone(), 0.0, 1.0);
        let q_box = Piece::new(pair.q.clone(), 0.0, 1.0);
        for &u in &[0.0, 1.0] {
            let x = pair.p.eval(u);
            if q_box.contains(&x, tol) {
                let (v, d) = project(pair.q, &pair.dq, &x, None);
                if d <= tol {
                    ends.push((u, v));
                }
            }
        }
        for &v in &[0.0, 1.0] {
            let x = pair.q.eval(v);
            if p_box.contains(&x, tol) {
                let (u, d) = project(pair.p, &pair.dp, &x, None);
                if d <= tol {
                    ends.push((u, v));
                }
            }
        }
        if ends.len() < 2 {
            return;
        }
        ends.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let samples = 2 * (pair.p.degree() + pair.q.degree()) + 8;
        for i in 0..ends.len() {
            for j in i + 1..ends.len() {
                let (u0, v0) = ends[i];
                let (u1, v1) = ends[j];
                if u1 - u0 <= 1e-9 || (v1 - v0).abs() <= 1e-9 {
                    continue;
                }
                if self
                    .overlaps
                    .iter()
                    .any(|o| o.contains_hit(u0, v0, 1e-9) && o.contains_hit(u1, v1, 1e-9))
                {
                    continue;
                }
                let coincide = (1..samples).all(|s| {
                    let w = s as f64 / samples as f64;
                    let u = u0 + w * (u1 - u0);
                    let guess = v0 + w * (v1 - v0);
                    let (v, d) = project(pair.q, &pair.dq, &pair.p.eval(u), Some(guess));
                    d <= tol && v >= v0.min(v1) - 1e-9 && v <= v0.max(v1) + 1e-9
                });
                if coincide {
                    self.overlaps.push(Overlap {
                        u: (u0, u1),
                        v: (v0, v1),
                    });
                }
            }
        }
    }

    fn subdivide(&mut self) -> Result<()> {
        let p = Piece::new(self.pair.p.clone(), 0.0, 1.0);
        let q = Piece::new(self.pair.q.clone(), 0.0, 1.0);
        let mut stack = vec![(p, q, 0usize)];
        let mut examined = 0usize;
        let margin = self.tolerance;
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
            let flat_a = a.is_flat(self.flatness);
            let flat_b = b.is_flat(self.flatness);
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
                    let (a0, a1) = a.split();
                    let (b0, b1) = b.split();
                    // Pushed in reverse so that small u is examined first.
                    stack.push((a1.clone(), b1.clone(), depth + 1));
                    stack.push((a1, b0.clone(), depth + 1));
                    stack.push((a0.clone(), b1, depth + 1));
                    stack.push((a0, b0, depth + 1));
                }
                (true, false) => {
                    let (a0, a1) = a.split();
                    stack.push((a1, b.clone(), depth + 1));
                    stack.push((a0, b, depth + 1));
                }
                _ => {
                    let (b0, b1) = b.split();
                    stack.push((a.clone(), b1, depth + 1));
                    stack.push((a, b0, depth + 1));
                }
            }
        }
        Ok(())
    }

    /// Seeds from the chords of a leaf pair, polished on the whole curves.
    fn leaf(&mut self, a: &Piece, b: &Piece) {
        let na = a.curve.degree();
        let nb = b.curve.degree();
        let a0 = a.curve.point(0);
        let a1 = a.curve.point(na);
        let b0 = b.curve.point(0);
        let b1 = b.curve.point(nb);
        let da: Vec<f64> = a1.iter().zip(a0).map(|(x, y)| x - y).collect();
        let db: Vec<f64> = b1.iter().zip(b0).map(|(x, y)| x - y).collect();
        let w: Vec<f64> = a0.iter().zip(b0).map(|(x, y)| x - y).collect();
        // Closest points of the chord lines: minimise |w + s da - t db|^2.
        let aa = dot(&da, &da);
        let bb = dot(&db, &db);
        let ab = dot(&da, &db);
        let det = aa * bb - ab * ab;
        let mut seeds: Vec<(f64, f64)> = Vec::with_capacity(5);
        // Flat pieces (within 1e-2 of their chords) can cross twice only when
        // the chords make an angle below about 4e-2: seed from all ends then.
        let nearly_parallel = det <= 4e-3 * aa * bb || det.is_nan();
        if !nearly_parallel
            && self
                .candidates
                .iter()
                .rev()
                .take(8)
                .any(|c| c.u >= a.lo && c.u <= a.hi && c.v >= b.lo && c.v <= b.hi)
        {
            // Chords that are not nearly parallel cross at most once: this
            // leaf's crossing is already known.
            return;
        }
        if !nearly_parallel {
            let s = ((-dot(&w, &da)) * bb + ab * dot(&w, &db)) / det;
            let t = (aa * dot(&w, &db) - ab * dot(&w, &da)) / det;
            seeds.push((s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)));
        } else {
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
            // A constant curve (degree 0) has no preferred parameter: report 0.
            if self.pair.p.degree() == 0 {
                u = 0.0;
            }
            if self.pair.q.degree() == 0 {
                v = 0.0;
            }
            if d <= self.tolerance {
                self.candidates.push(Candidate { u, v, distance: d });
            }
        }
    }

    /// Sort the candidates and merge those that are one hit.
    fn merge_candidates(&mut self) {
        let mut cands = std::mem::take(&mut self.candidates);
        cands.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
        let mut merged: Vec<Candidate> = Vec::with_capacity(cands.len());
        for c in cands {
            if self.overlaps.iter().any(|o| o.contains_hit(c.u, c.v, 1e-9)) {
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
        self.candidates = merged;
    }

    fn same_hit(&self, a: &Candidate, b: &Candidate) -> bool {
        if (a.u - b.u).abs() > MERGE_PARAMETER_DISTANCE
            || (a.v - b.v).abs() > MERGE_PARAMETER_DISTANCE
        {
            return false;
        }
        if a.u == b.u && a.v == b.v {
            return true;
        }
        let mid_u = 0.5 * (a.u + b.u);
        let mid_v = 0.5 * (a.v + b.v);
        let x = self.pair.p.eval(mid_u);
        let (_, d) = project(self.pair.q, &self.pair.dq, &x, Some(mid_v));
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
            let lower = if i > 0 { self.candidates[i - 1].u } else { 0.0 };
            let upper = self.candidates.get(i + 1).map_or(1.0, |n| n.u);
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
        let a = self.pair.dp.eval(c.u);
        let b = self.pair.dq.eval(c.v);
        let na = norm(&a);
        let nb = norm(&b);
        let sine = if na > 0.0 && nb > 0.0 {
            let cos = dot(&a, &b) / (na * nb);
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
        let interior = c.u > 0.0 && c.u < 1.0 && c.v > 0.0 && c.v < 1.0;
        if dim != 2 || !interior {
            return by_angle;
        }
        if sine > SURELY_TRANSVERSAL_SINE {
            return IntersectionKind::Crossing;
        }
        // Side test: signed distance of P(u -+ h) from Q.
        let room = (0.5 * (c.u - lower)).min(0.5 * (upper - c.u));
        let mut h = 1e-7f64.min(room);
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
        let (w, d) = project(self.pair.q, &self.pair.dq, &x, Some(v));
        if w <= 0.0 || w >= 1.0 {
            return None;
        }
        let tangent = self.pair.dq.eval(w);
        let foot = self.pair.q.eval(w);
        let cross = tangent[0] * (x[1] - foot[1]) - tangent[1] * (x[0] - foot[0]);
        Some(if cross >= 0.0 { d } else { -d })
    }
}
