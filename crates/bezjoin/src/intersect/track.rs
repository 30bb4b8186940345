//! The two curves of an intersection search as the search sees them: a
//! [`Track`] evaluates a Bezier or NURBS curve (and its tangent) on its
//! domain and cuts it into [`Piece`]s, Bezier spans whose control points
//! bound them. A rational span is kept in homogeneous form `(w P, w)`:
//! de Casteljau halves it exactly there, and with positive weights the
//! span lies in the convex hull of its Cartesian poles `P`, so the boxes
//! of the projected poles bound it as for a polynomial piece.

use std::borrow::Cow;

use crate::bezier::{BezierCurve, distance, scaled_norm};
use crate::curve::CurveRef;
use crate::nurbs::NurbsCurve;

/// One curve of the pair.
pub(super) enum Track<'a> {
    /// A Bezier curve, with its hodograph when the caller had it at hand
    /// (else tangents come from de Casteljau's scheme, no hodograph is
    /// built).
    Bezier {
        curve: &'a BezierCurve,
        hodograph: Option<&'a BezierCurve>,
    },
    /// A NURBS curve (evaluated by A2.3/A4.2).
    Nurbs(&'a NurbsCurve),
}

impl<'a> Track<'a> {
    pub(super) fn new(curve: CurveRef<'a>) -> Self {
        match curve {
            CurveRef::Bezier(curve) => Track::Bezier {
                curve,
                hodograph: None,
            },
            CurveRef::Nurbs(n) => Track::Nurbs(n),
        }
    }

    /// A Bezier curve with its hodograph already at hand.
    pub(crate) fn bezier(curve: &'a BezierCurve, hodograph: &'a BezierCurve) -> Self {
        Track::Bezier {
            curve,
            hodograph: Some(hodograph),
        }
    }

    pub(super) fn dim(&self) -> usize {
        match self {
            Track::Bezier { curve, .. } => curve.dim(),
            Track::Nurbs(n) => n.dim(),
        }
    }

    pub(super) fn degree(&self) -> usize {
        match self {
            Track::Bezier { curve, .. } => curve.degree(),
            Track::Nurbs(n) => n.degree(),
        }
    }

    pub(super) fn domain(&self) -> (f64, f64) {
        match self {
            Track::Bezier { .. } => (0.0, 1.0),
            Track::Nurbs(n) => n.domain(),
        }
    }

    pub(super) fn coordinate_scale(&self) -> f64 {
        match self {
            Track::Bezier { curve, .. } => curve.coordinate_scale(),
            Track::Nurbs(n) => n.coordinate_scale(),
        }
    }

    pub(super) fn eval_into(&self, u: f64, out: &mut [f64]) {
        match self {
            Track::Bezier { curve, .. } => curve.eval_into(u, out),
            Track::Nurbs(n) => n.point_and_tangent(u, out, None),
        }
    }

    /// [`Self::eval_into`] at a parameter of [`Self::breaks`]: a Bezier
    /// curve's ends are its first and last control points, exactly (no
    /// evaluation).
    pub(super) fn break_point_into(&self, u: f64, out: &mut [f64]) {
        match self {
            Track::Bezier { curve, .. } if u == 0.0 => out.copy_from_slice(curve.point(0)),
            Track::Bezier { curve, .. } if u == 1.0 => {
                out.copy_from_slice(curve.point(curve.degree()))
            }
            _ => self.eval_into(u, out),
        }
    }

    pub(super) fn eval(&self, u: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(u, &mut out);
        out
    }

    /// The point and the first derivative at `u` into `point` and
    /// `tangent` in one pass (a Bezier curve by de Casteljau's scheme,
    /// [`point_and_tangent`]; a NURBS curve by A2.3/A4.2).
    pub(super) fn point_and_tangent_into(&self, u: f64, point: &mut [f64], tangent: &mut [f64]) {
        match self {
            Track::Bezier { curve, .. } => point_and_tangent(curve, u, point, tangent),
            Track::Nurbs(n) => n.point_and_tangent_by_spans(u, point, tangent),
        }
    }

    /// The first derivative at `u` into `out`.
    pub(super) fn tangent_into(&self, u: f64, out: &mut [f64]) {
        match self {
            Track::Bezier {
                hodograph: Some(hodograph),
                ..
            } => hodograph.eval_into(u, out),
            Track::Bezier {
                curve,
                hodograph: None,
            } => {
                let mut point = [0.0f64; 16];
                let mut heap = Vec::new();
                let point: &mut [f64] = if curve.dim() <= point.len() {
                    &mut point[..curve.dim()]
                } else {
                    heap.resize(curve.dim(), 0.0);
                    &mut heap
                };
                point_and_tangent(curve, u, point, out);
            }
            Track::Nurbs(n) => {
                let mut point = [0.0f64; 16];
                let mut heap = Vec::new();
                let point: &mut [f64] = if n.dim() <= point.len() {
                    &mut point[..n.dim()]
                } else {
                    heap.resize(n.dim(), 0.0);
                    &mut heap
                };
                n.point_and_tangent(u, point, Some(out));
            }
        }
    }

    pub(super) fn tangent(&self, u: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim()];
        self.tangent_into(u, &mut out);
        out
    }

    /// The parameters where pieces meet: the domain's ends and, for a
    /// NURBS curve, its interior knots (where two polynomial pieces can
    /// start or stop coinciding).
    pub(super) fn breaks(&self) -> Cow<'a, [f64]> {
        match *self {
            // A Bezier curve's domain is [0, 1]: nothing to allocate.
            Track::Bezier { .. } => Cow::Borrowed(&[0.0, 1.0]),
            // The span decomposition's breaks (kept with the curve): the
            // same values (the domain's ends around `interior_knots`).
            Track::Nurbs(n) => Cow::Borrowed(&n.span_poles().breaks),
        }
    }

    /// For a NURBS curve: a bound on the distance between its point at a
    /// break (an interior knot or an end), as [`Self::break_point_into`]
    /// evaluates it (de Boor, `p` levels of convex combinations), and the
    /// end control point of the piece there (knot insertion: at most `p`
    /// insertions at each of the `p + 1` knots whose insertions reach that
    /// pole, each a convex combination). Every convex combination of values
    /// at most `S` (the largest pole coordinate) adds at most `2 eps S` per
    /// coordinate, so both lie within `2 (p + 1)^2 eps S sqrt(d)` of the
    /// exact point; the bound returned is four times that. With weights
    /// both are combined in homogeneous coordinates `(w x, w)` (entries up
    /// to `w_max S` and `w_max`) and divided by a weight `W >= w_min`: the
    /// Cartesian error `(|dX| + |x| |dW|) / W` plus the division's rounding
    /// is at most `2 (p + 1)^2 eps S (2 w_max / w_min + 1)` per coordinate,
    /// so the bound grows by the factor `2 w_max / w_min + 2`. `None` for
    /// Bezier curves (their breaks are tested as evaluated).
    pub(super) fn break_slack(&self) -> Option<f64> {
        match self {
            Track::Nurbs(n) => {
                let p = (n.degree() + 1) as f64;
                let slack =
                    8.0 * p * p * f64::EPSILON * n.coordinate_scale() * (n.dim() as f64).sqrt();
                Some(match n.weights() {
                    None => slack,
                    Some(w) => {
                        let (w_min, w_max) =
                            w.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &w| {
                                (lo.min(w), hi.max(w))
                            });
                        slack * (2.0 * (w_max / w_min) + 2.0)
                    }
                })
            }
            _ => None,
        }
    }

    /// Number of Bezier spans.
    pub(super) fn span_count(&self) -> usize {
        match self {
            Track::Bezier { .. } => 1,
            Track::Nurbs(n) => n.span_count(),
        }
    }

    /// The curve as Bezier pieces over its domain (a Bezier curve's one
    /// piece borrows the curve: no copy).
    pub(super) fn pieces(&self) -> Pieces<'a> {
        match self {
            Track::Bezier { curve, .. } => {
                Pieces::One([Piece::new(Cow::Borrowed(*curve), false, 0.0, 1.0)])
            }
            // Without weights the spans' Bezier poles straight from the
            // decomposition's buffer (the poles `bezier_spans` gives, bit
            // for bit, without building a curve per span).
            Track::Nurbs(n) if n.weights().is_none() => {
                let poles = n.span_poles();
                Pieces::Many(
                    (0..poles.count())
                        .map(|i| {
                            let (lo, hi) = poles.domain(i);
                            Piece::new(Cow::Borrowed(&poles.beziers[i]), false, lo, hi)
                        })
                        .collect(),
                )
            }
            // With weights: a span whose weights are all 1 is polynomial
            // (its Cartesian poles, `x / 1`); the others borrow their
            // homogeneous curves from the decomposition.
            Track::Nurbs(n) => {
                let poles = n.span_poles();
                let dim = n.dim();
                Pieces::Many(
                    (0..poles.count())
                        .map(|i| {
                            let (lo, hi) = poles.domain(i);
                            let rows = poles.rows(i);
                            if rows.chunks_exact(dim + 1).all(|r| r[dim] == 1.0) {
                                let points = rows
                                    .chunks_exact(dim + 1)
                                    .flat_map(|r| r[..dim].iter().copied())
                                    .collect();
                                let curve = BezierCurve::from_parts(dim, n.degree(), points);
                                Piece::new(Cow::Owned(curve), false, lo, hi)
                            } else {
                                Piece::with_projected(
                                    Cow::Borrowed(poles.span_curve(i)),
                                    Some(Cow::Borrowed(poles.projected(i))),
                                    lo,
                                    hi,
                                )
                            }
                        })
                        .collect(),
                )
            }
        }
    }
}

/// The pieces of a [`Track`]: a Bezier curve's one piece inline (no
/// allocation), a NURBS curve's spans in a vector. Used as a slice.
pub(super) enum Pieces<'a> {
    One([Piece<'a>; 1]),
    Many(Vec<Piece<'a>>),
}

impl<'a> std::ops::Deref for Pieces<'a> {
    type Target = [Piece<'a>];

    fn deref(&self) -> &[Piece<'a>] {
        match self {
            Pieces::One(one) => one,
            Pieces::Many(many) => many,
        }
    }
}

/// A piece `curve = original|[lo, hi]` (homogeneous when `rational`) with
/// its Cartesian control points and their bounding box; a whole Bezier
/// curve is borrowed, a span or a half owned.
#[derive(Clone)]
pub(super) struct Piece<'a> {
    curve: Cow<'a, BezierCurve>,
    /// Cartesian control points of a rational piece, row-major (a
    /// polynomial piece's are the curve's own: no copy).
    projected: Option<Cow<'a, [f64]>>,
    dim: usize,
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// The bounding box of the Cartesian control points: `dim` minima,
    /// then `dim` maxima (inline up to dimension [`INLINE_BOUNDS_DIM`],
    /// else one allocation).
    bounds: Bounds,
}

/// Dimensions up to which a piece's box is kept inline.
const INLINE_BOUNDS_DIM: usize = 4;

/// A piece's box: `dim` minima then `dim` maxima.
#[derive(Clone)]
enum Bounds {
    Inline([f64; 2 * INLINE_BOUNDS_DIM]),
    Heap(Vec<f64>),
}

impl Bounds {
    fn as_slice(&self) -> &[f64] {
        match self {
            Bounds::Inline(b) => b,
            Bounds::Heap(b) => b,
        }
    }

    fn as_mut_slice(&mut self) -> &mut [f64] {
        match self {
            Bounds::Inline(b) => b,
            Bounds::Heap(b) => b,
        }
    }
}

impl<'a> Piece<'a> {
    fn new(curve: Cow<'a, BezierCurve>, rational: bool, lo: f64, hi: f64) -> Self {
        let projected = rational.then(|| {
            let d = curve.dim() - 1;
            Cow::Owned(
                curve
                    .points()
                    .chunks_exact(d + 1)
                    .flat_map(|row| row[..d].iter().map(move |x| x / row[d]))
                    .collect(),
            )
        });
        Self::with_projected(curve, projected, lo, hi)
    }

    /// A piece of the homogeneous curve `curve` whose Cartesian poles
    /// (`(w x) / w` of each row) are `projected`, or of the polynomial
    /// `curve` (`None`). Inlined, so that a piece is built where it is kept
    /// (a span's in the pieces' vector) instead of copied there.
    #[inline(always)]
    fn with_projected(
        curve: Cow<'a, BezierCurve>,
        projected: Option<Cow<'a, [f64]>>,
        lo: f64,
        hi: f64,
    ) -> Self {
        let dim = if projected.is_some() {
            curve.dim() - 1
        } else {
            curve.dim()
        };
        // The plane with the dimension as a constant (the box loops
        // unrolled); the same comparisons as the general case.
        if dim == 2 {
            Self::new_sized(curve, projected, 2, lo, hi)
        } else {
            Self::new_sized(curve, projected, dim, lo, hi)
        }
    }

    /// [`Self::with_projected`] for Cartesian dimension `dim`.
    #[inline(always)]
    fn new_sized(
        curve: Cow<'a, BezierCurve>,
        projected: Option<Cow<'a, [f64]>>,
        dim: usize,
        lo: f64,
        hi: f64,
    ) -> Self {
        let mut bounds = if dim <= INLINE_BOUNDS_DIM {
            Bounds::Inline([0.0; 2 * INLINE_BOUNDS_DIM])
        } else {
            Bounds::Heap(vec![0.0; 2 * dim])
        };
        let b = bounds.as_mut_slice();
        b[..dim].fill(f64::INFINITY);
        b[dim..2 * dim].fill(f64::NEG_INFINITY);
        for row in projected
            .as_deref()
            .unwrap_or(curve.points())
            .chunks_exact(dim)
        {
            // Comparisons (a NaN is skipped, as by `f64::min` / `max`).
            for (c, &x) in row.iter().enumerate() {
                if x < b[c] {
                    b[c] = x;
                }
                if x > b[dim + c] {
                    b[dim + c] = x;
                }
            }
        }
        Self {
            curve,
            projected,
            dim,
            lo,
            hi,
            bounds,
        }
    }

    /// Lower corner of the bounding box.
    pub(super) fn min(&self) -> &[f64] {
        &self.bounds.as_slice()[..self.dim]
    }

    /// Upper corner of the bounding box.
    pub(super) fn max(&self) -> &[f64] {
        &self.bounds.as_slice()[self.dim..2 * self.dim]
    }

    pub(super) fn degree(&self) -> usize {
        self.curve.degree()
    }

    /// Cartesian control point `i`.
    pub(super) fn point(&self, i: usize) -> &[f64] {
        let points = self.projected.as_deref().unwrap_or(self.curve.points());
        &points[i * self.dim..(i + 1) * self.dim]
    }

    pub(super) fn split(&self) -> (Piece<'a>, Piece<'a>) {
        let (a, b) = self.curve.split_unchecked(0.5);
        let mid = 0.5 * (self.lo + self.hi);
        (
            Piece::new(Cow::Owned(a), self.projected.is_some(), self.lo, mid),
            Piece::new(Cow::Owned(b), self.projected.is_some(), mid, self.hi),
        )
    }

    /// Flat enough to seed Newton from the chord: control points within
    /// `max(absolute, relative_chord * chord)` of the chord.
    pub(super) fn is_flat(&self, absolute: f64, relative_chord: f64) -> bool {
        is_flat(
            self.points(),
            self.degree(),
            self.dim,
            absolute,
            relative_chord,
        )
    }

    /// Whether a point of the piece may lie within `margin` of `x`: its box
    /// widened by `margin` holds `x` ([`Self::contains`]) and, for a
    /// polynomial piece of degree <= [`NEAR_MAX_DEGREE`] in dimension <=
    /// [`NEAR_MAX_DIM`], so does the widened box of one of its halves, and
    /// of one of their halves, down to [`NEAR_LEVELS`] de Casteljau
    /// halvings at `1/2` (each half lies in the convex hull of its control
    /// points). `false` proves that every point of the piece is farther
    /// than `margin + slack` from `x`, `slack` a bound on the rounding of
    /// the halvings (`8 (n + 1) (levels + 1) eps` times the largest
    /// coordinate of the piece and `x`): an evaluated point of the curve
    /// (within a few `eps` of the curve) is then farther than `margin`
    /// too, so a projection of `x` onto the curve would not find it within
    /// `margin`. A rational piece (positive weights) is halved in its
    /// homogeneous rows, each half boxed by its Cartesian points, with the
    /// slack grown by the ratio of its weights.
    pub(super) fn may_come_within(&self, x: &[f64], margin: f64) -> bool {
        if !self.contains(x, margin) {
            return false;
        }
        let (n, d) = (self.degree(), self.dim);
        let rational = self.is_rational();
        // Row width: homogeneous rows `(w x, w)` for a rational piece.
        let width = d + usize::from(rational);
        if n > NEAR_MAX_DEGREE || width > NEAR_MAX_DIM || n == 0 {
            return true;
        }
        let points = self.curve.points();
        let cartesian = self.projected.as_deref().unwrap_or(points);
        let scale = cartesian
            .iter()
            .chain(x)
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let mut slack = 8.0 * (n + 1) as f64 * (NEAR_LEVELS + 1) as f64 * f64::EPSILON * scale;
        if rational {
            // The halvings round the homogeneous rows (entries up to
            // `w_max |x|`) and the division by a weight (>= `w_min`) carries
            // that over to the Cartesian points: the slack grows by
            // `w_max / w_min`, doubled for the weight's own rounding and the
            // division.
            let (w_min, w_max) = points
                .chunks_exact(width)
                .fold((f64::INFINITY, 0.0f64), |(lo, hi), row| {
                    (lo.min(row[d]), hi.max(row[d]))
                });
            slack *= 2.0 * (w_max / w_min) + 2.0;
        }
        let widened = margin + slack;
        if !widened.is_finite() {
            return true;
        }
        // Cubics in the plane and in space, with and without weights, with
        // the sizes as constants: the same operations in the same order.
        match (n, d, rational) {
            (3, 2, true) => return halves_fixed::<4, 2, 3>(points, x, widened, NEAR_LEVELS),
            (3, 2, false) => return halves_fixed::<4, 2, 2>(points, x, widened, NEAR_LEVELS),
            (3, 3, true) => return halves_fixed::<4, 3, 4>(points, x, widened, NEAR_LEVELS),
            (3, 3, false) => return halves_fixed::<4, 3, 3>(points, x, widened, NEAR_LEVELS),
            _ => {}
        }
        let mut work = [0.0f64; (NEAR_MAX_DEGREE + 1) * NEAR_MAX_DIM];
        work[..points.len()].copy_from_slice(points);
        halves_come_within(&work, n, d, rational, x, widened, NEAR_LEVELS)
    }

    pub(super) fn contains(&self, x: &[f64], margin: f64) -> bool {
        let (min, max) = (self.min(), self.max());
        (0..x.len()).all(|c| x[c] >= min[c] - margin && x[c] <= max[c] + margin)
    }

    /// Distance from `x` to the box (0 inside): no point of the piece is
    /// closer to `x`.
    pub(super) fn box_distance(&self, x: &[f64]) -> f64 {
        let gaps = || {
            x.iter()
                .zip(self.min().iter().zip(self.max()))
                .map(|(x, (lo, hi))| (lo - x).max(x - hi).max(0.0))
        };
        // `norm` of the gaps, without a temporary vector
        let square = gaps().map(|g| g * g).sum::<f64>();
        if square.is_normal() {
            square.sqrt()
        } else {
            scaled_norm(gaps())
        }
    }

    pub(super) fn diagonal(&self) -> f64 {
        distance(self.min(), self.max())
    }

    /// Whether the piece is a span of a rational curve.
    pub(super) fn is_rational(&self) -> bool {
        self.projected.is_some()
    }

    /// Cartesian dimension.
    pub(super) fn dim(&self) -> usize {
        self.dim
    }

    /// The homogeneous control points `(w P, w)` of a rational piece,
    /// row-major (`None` for a polynomial piece).
    pub(super) fn homogeneous(&self) -> Option<&[f64]> {
        self.projected.as_ref().map(|_| self.curve.points())
    }

    /// The Cartesian control points, row-major.
    pub(super) fn points(&self) -> &[f64] {
        self.projected.as_deref().unwrap_or(self.curve.points())
    }
}

/// Largest degree [`Piece::may_come_within`] refines.
const NEAR_MAX_DEGREE: usize = 15;
/// Largest dimension [`Piece::may_come_within`] refines.
const NEAR_MAX_DIM: usize = 4;
/// Halving levels of [`Piece::may_come_within`].
const NEAR_LEVELS: u32 = 6;

/// Whether `x` lies in the box of the control points `points` (`n + 1`
/// rows of `d`, the first of a buffer) widened by `margin`, and, while
/// `levels > 0`, in the widened box of one of the two de Casteljau halves
/// at `1/2`.
fn halves_come_within(
    points: &[f64; (NEAR_MAX_DEGREE + 1) * NEAR_MAX_DIM],
    n: usize,
    d: usize,
    rational: bool,
    x: &[f64],
    margin: f64,
    levels: u32,
) -> bool {
    let width = d + usize::from(rational);
    for c in 0..d {
        let values = (0..=n).map(|i| {
            if rational {
                points[i * width + c] / points[i * width + d]
            } else {
                points[i * d + c]
            }
        });
        if coordinate_rules_out(values, x[c], margin) {
            return false;
        }
    }
    if levels == 0 {
        return true;
    }
    // Left half in `left` (its point r is the first point of level r),
    // right half in `right` (its point n - r the last point of level r).
    let d_row = width;
    let mut left = *points;
    let mut right = *points;
    for r in 1..=n {
        for i in (r..=n).rev() {
            for c in 0..d_row {
                left[i * d_row + c] = 0.5 * (left[(i - 1) * d_row + c] + left[i * d_row + c]);
            }
        }
    }
    for r in 1..=n {
        for i in 0..=n - r {
            for c in 0..d_row {
                right[i * d_row + c] = 0.5 * (right[i * d_row + c] + right[(i + 1) * d_row + c]);
            }
        }
    }
    halves_come_within(&left, n, d, rational, x, margin, levels - 1)
        || halves_come_within(&right, n, d, rational, x, margin, levels - 1)
}

/// Whether the coordinate `x` lies more than `margin` outside the range of
/// `values` (a piece's control-point coordinates, taken in order for the
/// minimum and maximum): the test of [`halves_come_within`] and
/// [`halves_fixed_rows`]. A NaN coordinate (of the piece or of `x`) proves
/// nothing (`false`).
#[inline(always)]
fn coordinate_rules_out(values: impl Iterator<Item = f64>, x: f64, margin: f64) -> bool {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    let inside = x >= lo - margin && x <= hi + margin;
    !(inside || lo.is_nan() || x.is_nan())
}

/// [`halves_come_within`] for `R` rows of `W` values in dimension `D`
/// (`W = D + 1`: homogeneous rows of a rational piece), the rows given
/// row-major in `points`: the same comparisons on the same values.
fn halves_fixed<const R: usize, const D: usize, const W: usize>(
    points: &[f64],
    x: &[f64],
    margin: f64,
    levels: u32,
) -> bool {
    let mut rows = [[0.0f64; W]; R];
    for (row, values) in rows.iter_mut().zip(points.chunks_exact(W)) {
        row.copy_from_slice(values);
    }
    let mut at = [0.0f64; D];
    at.copy_from_slice(&x[..D]);
    halves_fixed_rows::<R, D, W>(&rows, &at, margin, levels)
}

/// The recursion of [`halves_fixed`].
#[allow(clippy::needless_range_loop)] // rows `i - 1` and `i` in one statement
fn halves_fixed_rows<const R: usize, const D: usize, const W: usize>(
    points: &[[f64; W]; R],
    x: &[f64; D],
    margin: f64,
    levels: u32,
) -> bool {
    let rational = W > D;
    for c in 0..D {
        let values = points
            .iter()
            .map(|row| if rational { row[c] / row[D] } else { row[c] });
        if coordinate_rules_out(values, x[c], margin) {
            return false;
        }
    }
    if levels == 0 {
        return true;
    }
    let mut left = *points;
    let mut right = *points;
    for r in 1..R {
        for i in (r..R).rev() {
            for c in 0..W {
                left[i][c] = 0.5 * (left[i - 1][c] + left[i][c]);
            }
        }
    }
    for r in 1..R {
        for i in 0..R - r {
            for c in 0..W {
                right[i][c] = 0.5 * (right[i][c] + right[i + 1][c]);
            }
        }
    }
    halves_fixed_rows::<R, D, W>(&left, x, margin, levels - 1)
        || halves_fixed_rows::<R, D, W>(&right, x, margin, levels - 1)
}

/// `P(t)` and `P'(t)` of a Bezier curve by de Casteljau's scheme
/// ([`crate::bezier::point_and_tangent_rows`] on its control points).
#[inline]
pub(super) fn point_and_tangent(
    curve: &BezierCurve,
    t: f64,
    point: &mut [f64],
    tangent: &mut [f64],
) {
    crate::bezier::point_and_tangent_rows(
        curve.points(),
        curve.dim(),
        curve.degree(),
        t,
        point,
        tangent,
    );
}

/// [`Piece::is_flat`] for the degree-`n` polygon `points` (row-major,
/// `dim` coordinates).
pub(super) fn is_flat(
    points: &[f64],
    n: usize,
    dim: usize,
    absolute: f64,
    relative_chord: f64,
) -> bool {
    let chord = distance(&points[..dim], &points[n * dim..(n + 1) * dim]);
    deviation_from_chord(points, n, dim) <= absolute.max(relative_chord * chord)
}

/// Largest distance of a control point of the degree-`n` polygon `points`
/// (row-major, `dim` coordinates) from its chord (from the first point when
/// the chord is degenerate); points beyond the chord's ends count their
/// distance from the nearer end.
fn deviation_from_chord(points: &[f64], n: usize, dim: usize) -> f64 {
    let point = |i: usize| &points[i * dim..(i + 1) * dim];
    let a = point(0);
    let b = point(n);
    let len2: f64 = b.iter().zip(a).map(|(x, y)| (x - y) * (x - y)).sum();
    let mut worst = 0.0f64;
    for i in 1..n {
        let p = point(i);
        // |p - a|^2 and (p - a).(b - a), without temporaries
        let (rel2, along) = p
            .iter()
            .zip(a)
            .zip(b)
            .fold((0.0, 0.0), |(r, s), ((x, y), z)| {
                let rel = x - y;
                (r + rel * rel, s + rel * (z - y))
            });
        let dev = if len2 > 0.0 {
            let s = along / len2;
            let perp: f64 = p
                .iter()
                .zip(a)
                .zip(b)
                .map(|((x, y), z)| {
                    let d = (x - y) - s * (z - y);
                    d * d
                })
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
            rel2.sqrt()
        };
        worst = worst.max(dev);
    }
    worst
}

pub(super) fn boxes_meet(a: &Piece, b: &Piece, margin: f64) -> bool {
    let (a_min, a_max, b_min, b_max) = (a.min(), a.max(), b.min(), b.max());
    (0..a_min.len()).all(|c| a_min[c] <= b_max[c] + margin && b_min[c] <= a_max[c] + margin)
}

#[cfg(test)]
mod tests {
    use super::{Track, point_and_tangent};
    use crate::bezier::BezierCurve;
    use crate::curve::CurveRef;

    /// The one-pass point and tangent are the curve's value (Horner,
    /// `BezierCurve::eval`) and its hodograph's value, to rounding, on
    /// fixed-seed random curves of degrees 0 to 12 in dimensions 1 to 4
    /// (the fixed-size paths of the plane and space up to degree 7, and
    /// the general path), at random parameters and at both ends (where
    /// the point is the end control point exactly); a track without a
    /// hodograph gives the same tangent.
    #[test]
    fn point_and_tangent_match_the_value_and_the_hodograph() {
        let mut values = crate::test_values::Values(26);
        let mut next = || values.unit();
        for case in 0..400 {
            let degree = case % 13;
            let dim = 1 + (case / 13) % 4;
            let points: Vec<f64> = (0..dim * (degree + 1))
                .map(|_| 20.0 * next() - 10.0)
                .collect();
            let curve = BezierCurve::new(dim, degree, points).unwrap();
            let hodograph = curve.hodograph();
            let track = Track::new(CurveRef::Bezier(&curve));
            let scale = curve.coordinate_scale().max(1.0) * (1u64 << degree) as f64;
            for t in [0.0, 1.0, next(), next(), next()] {
                let (mut point, mut tangent) = (vec![0.0; dim], vec![0.0; dim]);
                point_and_tangent(&curve, t, &mut point, &mut tangent);
                let value = curve.eval(t);
                let slope = hodograph.eval(t);
                for c in 0..dim {
                    let what = format!("case {case}, degree {degree}, dim {dim}, t {t}");
                    assert!((point[c] - value[c]).abs() <= 1e-14 * scale, "{what}");
                    let tol = 1e-14 * scale * (degree.max(1) as f64);
                    assert!((tangent[c] - slope[c]).abs() <= tol, "{what}");
                }
                if t == 0.0 || t == 1.0 {
                    let end = if t == 0.0 { 0 } else { degree };
                    assert_eq!(point, curve.point(end), "case {case}");
                }
                let mut again = vec![0.0; dim];
                track.tangent_into(t, &mut again);
                assert_eq!(again, tangent, "case {case}");
            }
        }
    }

    /// The cubic's point and tangent with the degree as a constant (the
    /// dispatch of `point_and_tangent` in 2D and 3D) are the fixed-buffer
    /// loop run with the degree unknown at compile time, to the bit, on
    /// fixed-seed random cubics at random parameters.
    #[test]
    fn cubic_point_and_tangent_are_the_general_loop_to_the_bit() {
        use crate::bezier::point_and_tangent_fixed;
        use std::hint::black_box;
        let mut values = crate::test_values::Values(27);
        for case in 0..400 {
            let dim = 2 + case % 2;
            let points: Vec<f64> = (0..4 * dim).map(|_| 4.0 * values.unit() - 2.0).collect();
            let curve = BezierCurve::new(dim, 3, points.clone()).unwrap();
            let t = values.unit();
            let (mut p, mut d) = ([0.0; 3], [0.0; 3]);
            let (mut q, mut e) = ([0.0; 3], [0.0; 3]);
            point_and_tangent(&curve, t, &mut p[..dim], &mut d[..dim]);
            if dim == 2 {
                point_and_tangent_fixed::<2, 4>(&points, black_box(3), t, &mut q, &mut e);
            } else {
                point_and_tangent_fixed::<3, 4>(&points, black_box(3), t, &mut q, &mut e);
            }
            assert_eq!(
                p.map(f64::to_bits),
                q.map(f64::to_bits),
                "case {case}: point"
            );
            assert_eq!(
                d.map(f64::to_bits),
                e.map(f64::to_bits),
                "case {case}: tangent"
            );
        }
    }
}

#[cfg(test)]
mod near_tests {
    use super::Piece;
    use crate::bezier::{BezierCurve, distance};
    use std::borrow::Cow;

    /// A rational NURBS curve's pieces borrow the decomposition's
    /// Cartesian poles: the same bits and the same box as a piece that
    /// projects its homogeneous rows itself ([`Piece::new`]).
    #[test]
    fn kept_cartesian_poles_are_the_projected_rows() {
        let mut next = crate::test_values::unit_generator(23);
        for case in 0..40 {
            let (p, dim) = (1 + case % 4, 2 + case % 2);
            let count = p + 1 + case % 3;
            let poles: Vec<f64> = (0..count * dim).map(|_| 4.0 * next() - 2.0).collect();
            let weights: Vec<f64> = (0..count).map(|_| 0.2 + 3.0 * next()).collect();
            let mut knots = vec![0.0; p + 1];
            knots.extend((1..count - p).map(|k| k as f64 + 0.5 * next()));
            knots.extend(vec![(count - p) as f64 + 1.0; p + 1]);
            let curve = crate::NurbsCurve::new(dim, p, poles, Some(weights), knots).unwrap();
            let track = super::Track::Nurbs(&curve);
            for (i, piece) in track.pieces().iter().enumerate() {
                let poles = curve.span_poles();
                let own = Piece::new(Cow::Borrowed(poles.span_curve(i)), true, piece.lo, piece.hi);
                let bits = crate::test_values::bits;
                assert_eq!(
                    bits(piece.points()),
                    bits(own.points()),
                    "case {case} span {i}"
                );
                assert_eq!(bits(piece.min()), bits(own.min()), "case {case} span {i}");
                assert_eq!(bits(piece.max()), bits(own.max()), "case {case} span {i}");
            }
        }
    }

    /// `may_come_within` is conservative: whenever it says no, every point
    /// of the piece (dense samples) is farther than the margin from `x`;
    /// and it says no for points off the curve that the box alone lets
    /// through (the refinement does prune). Random polynomial pieces of
    /// degrees 1 to 6 in 2D and 3D, points near the curve and in its box.
    #[test]
    fn may_come_within_refuses_only_far_points() {
        let pruned = refusals_are_far(false);
        assert!(pruned > 100, "the halves pruned only {pruned} points");
    }

    /// The same for rational pieces (weights in `[0.3, 3]`, halved in
    /// their homogeneous rows), the dense samples projected.
    #[test]
    fn may_come_within_refuses_only_far_points_rational() {
        let pruned = refusals_are_far(true);
        assert!(pruned > 100, "the halves pruned only {pruned} points");
    }

    /// The cubics' fixed-size halvings answer as the general ones: random
    /// cubics in the plane and in space, with and without weights, points
    /// near the curve and anywhere in its box, several margins; both
    /// answers occur.
    #[test]
    fn fixed_halvings_answer_as_the_general_ones() {
        let mut next = crate::test_values::unit_generator(23);
        let (mut yes, mut no) = (0, 0);
        for case in 0..400 {
            let dim = 2 + case % 2;
            let rational = case % 4 < 2;
            let width = dim + usize::from(rational);
            let points = random_rows(&mut next, 4, dim, rational);
            let mut work = [0.0f64; (super::NEAR_MAX_DEGREE + 1) * super::NEAR_MAX_DIM];
            work[..points.len()].copy_from_slice(&points);
            for trial in 0..10 {
                let x: Vec<f64> = (0..dim).map(|_| 2.0 * next() - 1.0).collect();
                let margin = [1e-9, 1e-3, 3e-2, 0.1, 0.3][trial % 5];
                let levels = [super::NEAR_LEVELS, 2, 0][trial % 3];
                let general =
                    super::halves_come_within(&work, 3, dim, rational, &x, margin, levels);
                let fixed = match (dim, rational) {
                    (2, true) => super::halves_fixed::<4, 2, 3>(&points, &x, margin, levels),
                    (2, false) => super::halves_fixed::<4, 2, 2>(&points, &x, margin, levels),
                    (3, true) => super::halves_fixed::<4, 3, 4>(&points, &x, margin, levels),
                    _ => super::halves_fixed::<4, 3, 3>(&points, &x, margin, levels),
                };
                assert_eq!(fixed, general, "case {case} trial {trial} width {width}");
                if general {
                    yes += 1;
                } else {
                    no += 1;
                }
            }
        }
        assert!(yes > 400 && no > 400, "{yes} {no}");
    }

    /// `rows` random control points of dimension `dim` in `[-1, 1]`,
    /// row-major; with `rational`, homogeneous (`w x`, then `w`, the weight
    /// `w` in `[0.3, 3]`, drawn before the coordinates).
    fn random_rows(
        next: &mut impl FnMut() -> f64,
        rows: usize,
        dim: usize,
        rational: bool,
    ) -> Vec<f64> {
        (0..rows)
            .flat_map(|_| {
                let w = if rational { 0.3 + 2.7 * next() } else { 1.0 };
                let mut row: Vec<f64> = (0..dim).map(|_| w * (2.0 * next() - 1.0)).collect();
                if rational {
                    row.push(w);
                }
                row
            })
            .collect()
    }

    /// The check of the two tests above; the count of points refused that
    /// the box alone lets through.
    fn refusals_are_far(rational: bool) -> usize {
        let mut next = crate::test_values::unit_generator(17);
        let mut pruned = 0;
        for case in 0..80 {
            let degree = 1 + case % 6;
            let dim = 2 + case % 2;
            let width = dim + usize::from(rational);
            let points = random_rows(&mut next, degree + 1, dim, rational);
            let curve = BezierCurve::new(width, degree, points).unwrap();
            let piece = Piece::new(Cow::Borrowed(&curve), rational, 0.0, 1.0);
            let point_at = |t: f64| {
                let row = curve.eval(t);
                if rational {
                    row[..dim].iter().map(|v| v / row[dim]).collect()
                } else {
                    row
                }
            };
            for trial in 0..20 {
                // A point on the curve moved by a small offset, or anywhere
                // in the box.
                let x: Vec<f64> = if trial % 2 == 0 {
                    let t = next();
                    let scale = [1e-9, 1e-4, 1e-2][trial % 3];
                    point_at(t)
                        .iter()
                        .map(|v| v + scale * (2.0 * next() - 1.0))
                        .collect()
                } else {
                    (0..dim)
                        .map(|c| {
                            let (lo, hi) = (piece.min()[c], piece.max()[c]);
                            lo + (hi - lo) * next()
                        })
                        .collect()
                };
                let margin = [1e-9, 1e-6, 1e-3][trial % 3];
                if piece.may_come_within(&x, margin) {
                    continue;
                }
                if piece.contains(&x, margin) {
                    pruned += 1;
                }
                let closest = (0..=10_000)
                    .map(|i| distance(&point_at(i as f64 / 10_000.0), &x))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    closest > margin,
                    "case {case} trial {trial}: {closest} <= {margin}"
                );
            }
        }
        pruned
    }
}
