//! NURBS curves: poles, optional weights and a flat knot vector; the one
//! B-spline type of the library (docs/mathematics.md#nurbs-curves).
//!
//! `C(u) = sum_i N_(i,p)(u) w_i P_i / sum_i N_(i,p)(u) w_i` on the domain
//! `[u_p, u_(n+1)]`, after The NURBS Book (Piegl & Tiller, 2nd ed.); the
//! algorithm numbers below are the book's. OpenCASCADE's `Geom_BSplineCurve`
//! holds the same data as poles, weights, knots and multiplicities
//! ([`NurbsCurve::knots_with_multiplicities`]).
//!
//! Every operation here is exact (up to rounding): derivatives of any order
//! (A2.3 on the homogeneous curve, then A4.2), knot insertion (A5.1),
//! split, trim and reversal with the original parameters, decomposition
//! into Bezier spans (A5.6; rational spans stay rational), degree elevation
//! (elevation of the spans, then removal of the knots the elevation does
//! not need, each removal checked), exact conic arcs (A7.1).
//!
//! The papers state their continuity promises for the chain
//! `P|[0,u0], R, Q|[v0,1]` read as ONE B-spline whose knot intervals are the
//! lengths of the pieces' parameter ranges (docs/mathematics.md#b-spline-chains).
//! [`NurbsCurve::from_bezier_chain`] builds exactly that curve (every
//! interior knot of full multiplicity, so it is the chain itself), and
//! [`NurbsCurve::eval_derivatives_side`] evaluates it from either side of a
//! knot with the same A2.3 basis routine as everything else: continuity is
//! judged by the derivatives of one curve, not by a formula of ours.

mod conic;
mod eval;
mod knots;
mod length;
mod spans;

pub use conic::{AXIS_TOLERANCE, ellipse_arc};
pub use length::MAX_RATIONAL_EVALUATIONS;

use crate::basis::{BasisLayout, KnotSide, basis_derivatives_inline, basis_scratch_len, find_span};
use crate::bezier::{BezierCurve, MAX_DEGREE};
use crate::curve::CurveRef;
use crate::error::{BezjoinError, Compact, Result, check_finite, check_finite_scalar};

/// A NURBS curve of degree `p >= 1`: poles, weights (`None`: all 1, a
/// polynomial B-spline) and the flat knot vector.
///
/// Invariants (checked by [`NurbsCurve::new`]): `pole_count >= p + 1`;
/// `knots.len() == pole_count + p + 1`, finite and non-decreasing; every
/// knot value has multiplicity `<= p`, except the first and last values,
/// which may have `p + 1`; the domain `[u_p, u_(n+1)]` is not empty; weights
/// finite and `> 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve {
    degree: usize,
    dim: usize,
    knots: Vec<f64>,
    points: Vec<f64>,
    weights: Option<Vec<f64>>,
    /// The Bezier spans for evaluation, built on first use
    /// (`eval.rs`; not part of the curve's value).
    span_cache: eval::SpanCache,
}

/// The error of [`NurbsCurve::check_parameter`], out of the callers' hot
/// paths.
#[cold]
#[inline(never)]
fn outside_domain(name: &str, u: f64, (a, b): (f64, f64)) -> BezjoinError {
    BezjoinError::out_of_range(name, u, format!("[{}, {}]", Compact(a), Compact(b)))
}

/// The name the chain code and older callers know the type by: a
/// polynomial B-spline is a [`NurbsCurve`] without weights.
pub type BSplineCurve = NurbsCurve;

impl NurbsCurve {
    /// The number of poles of a curve with these array lengths, or the
    /// size error [`new`](Self::new) gives for them (the same argument
    /// named, the same message), from the numbers alone: a caller can
    /// check lengths before reading any array (the C ABI does).
    /// `weights_len == 0`: no weights.
    pub fn check_shape(
        dim: usize,
        degree: usize,
        poles_len: usize,
        weights_len: usize,
        knots_len: usize,
    ) -> Result<usize> {
        if dim == 0 {
            return Err(BezjoinError::invalid("dim", "must be at least 1"));
        }
        if degree == 0 {
            return Err(BezjoinError::invalid(
                "degree",
                "must be at least 1 (a NURBS curve of degree 0 is not continuous)",
            ));
        }
        if degree > MAX_DEGREE {
            return Err(BezjoinError::invalid(
                "degree",
                format!("{degree} is above the supported maximum {MAX_DEGREE}"),
            ));
        }
        let largest = isize::MAX as usize / std::mem::size_of::<f64>();
        for (name, len) in [
            ("poles", poles_len),
            ("weights", weights_len),
            ("knots", knots_len),
        ] {
            if len > largest {
                return Err(BezjoinError::invalid(
                    name,
                    format!("{len} values are more than any array of doubles holds ({largest})"),
                ));
            }
        }
        let order = degree + 1;
        if poles_len % dim != 0 || poles_len / dim < order {
            return Err(BezjoinError::invalid(
                "poles",
                format!("{poles_len} values do not make at least {order} poles of dimension {dim}"),
            ));
        }
        let count = poles_len / dim;
        // Weights and knots that agree on another pole count: the poles are
        // the odd one out, so they are named (not the two that agree).
        let from_knots = knots_len.checked_sub(order);
        if weights_len != 0 && from_knots == Some(weights_len) && weights_len != count {
            if let Some(expected) = weights_len.checked_mul(dim) {
                return Err(BezjoinError::LengthMismatch {
                    name: "poles".into(),
                    expected,
                    actual: poles_len,
                });
            }
        }
        if weights_len != 0 && weights_len != count {
            return Err(BezjoinError::LengthMismatch {
                name: "weights".into(),
                expected: count,
                actual: weights_len,
            });
        }
        let expected = count.checked_add(order).ok_or_else(|| {
            BezjoinError::invalid(
                "poles",
                format!("{count} poles and degree {degree} need more knots than usize counts"),
            )
        })?;
        if knots_len != expected {
            return Err(BezjoinError::LengthMismatch {
                name: "knots".into(),
                expected,
                actual: knots_len,
            });
        }
        Ok(count)
    }

    /// A NURBS curve from row-major poles (`pole_count * dim` values),
    /// optional weights (`pole_count` values `> 0`; `None` for a polynomial
    /// B-spline) and the flat knot vector (`pole_count + degree + 1`
    /// values). The argument order is the C ABI's (`bzj_nurbs_new`).
    ///
    /// Errors name the argument: `dim`, `degree`, `poles`, `weights`,
    /// `knots` (count, order, multiplicities, an empty domain, an interval
    /// too short to invert, a span or domain too wide for doubles).
    pub fn new(
        dim: usize,
        degree: usize,
        poles: Vec<f64>,
        weights: Option<Vec<f64>>,
        knots: Vec<f64>,
    ) -> Result<Self> {
        let count = Self::check_shape(
            dim,
            degree,
            poles.len(),
            weights.as_ref().map_or(0, Vec::len),
            knots.len(),
        )?;
        if weights.as_ref().is_some_and(Vec::is_empty) {
            return Err(BezjoinError::LengthMismatch {
                name: "weights".into(),
                expected: count,
                actual: 0,
            });
        }
        let order = degree + 1;
        check_finite("poles", &poles)?;
        if let Some(w) = &weights {
            check_finite("weights", w)?;
            if let Some(i) = w.iter().position(|&x| x <= 0.0) {
                return Err(BezjoinError::out_of_range(
                    format!("weights[{i}]"),
                    w[i],
                    "> 0",
                ));
            }
            // The homogeneous poles `w P` must be normal finite numbers
            // (a subnormal weight loses the pole's digits, an overflowing
            // product makes every evaluation NaN).
            if let Some(i) = w.iter().position(|&x| x < f64::MIN_POSITIVE) {
                return Err(BezjoinError::out_of_range(
                    format!("weights[{i}]"),
                    w[i],
                    format!(">= {:e} (a normal number)", f64::MIN_POSITIVE),
                ));
            }
            let largest = poles.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            if let Some(i) = w.iter().position(|&x| !(x * largest).is_finite()) {
                return Err(BezjoinError::invalid(
                    format!("weights[{i}]"),
                    format!(
                        "{} times the largest pole coordinate {largest:e} overflows f64",
                        Compact(w[i])
                    ),
                ));
            }
        }
        check_finite("knots", &knots)?;
        if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(BezjoinError::invalid(
                "knots",
                format!(
                    "decrease at index {}: {} after {}",
                    i + 1,
                    Compact(knots[i + 1]),
                    Compact(knots[i])
                ),
            ));
        }
        // The basis (A2.2/A2.3) divides by knot differences: a non-zero one
        // whose reciprocal overflows (a subnormal interval, e.g. a chain
        // piece of length 5e-324) makes `0 * inf = NaN` of the values.
        if let Some(i) = knots
            .windows(2)
            .position(|w| w[1] > w[0] && !(1.0 / (w[1] - w[0])).is_finite())
        {
            return Err(BezjoinError::invalid(
                "knots",
                format!(
                    "the interval [{}, {}] at index {} is too short: its length {:e} has no \
                     finite reciprocal",
                    knots[i],
                    knots[i + 1],
                    i + 1,
                    knots[i + 1] - knots[i]
                ),
            ));
        }
        let (distinct, mults) = distinct_with_multiplicities(&knots);
        let last = distinct.len() - 1;
        for (i, (&value, &m)) in distinct.iter().zip(&mults).enumerate() {
            let limit = if i == 0 || i == last { order } else { degree };
            if m > limit {
                let which = if i == 0 || i == last {
                    "end"
                } else {
                    "interior"
                };
                return Err(BezjoinError::invalid(
                    "knots",
                    format!(
                        "{which} knot {value} has multiplicity {m} > {limit} (degree {degree})"
                    ),
                ));
            }
        }
        if knots[degree] >= knots[count] {
            return Err(BezjoinError::invalid(
                "knots",
                format!(
                    "the domain [knots[{degree}], knots[{count}]] = [{}, {}] is empty",
                    knots[degree], knots[count]
                ),
            ));
        }
        // Every knot difference of the basis is at most the span of the
        // vector, and `reverse` maps `u -> first + last - u`: finite knots
        // whose span or domain sum overflows would give silent infinities.
        let (lowest, highest) = (knots[0], knots[knots.len() - 1]);
        let (first, last) = (knots[degree], knots[count]);
        if !(highest - lowest).is_finite() || !(first + last).is_finite() {
            return Err(BezjoinError::invalid(
                "knots",
                format!(
                    "the knots from {lowest:e} to {highest:e} (domain [{first:e}, {last:e}]) are \
                     too far apart for doubles: the span {:e} or the sum of the domain's ends \
                     {:e} overflows",
                    highest - lowest,
                    first + last
                ),
            ));
        }
        let weights = unit_weights_dropped(weights);
        Ok(Self {
            degree,
            dim,
            knots,
            points: poles,
            weights,
            span_cache: Default::default(),
        })
    }

    /// A Bezier curve as a one-span NURBS on `[0, 1]` (knots `0^(n+1)
    /// 1^(n+1)`); a degree-0 curve (a point) is raised to degree 1.
    pub fn from_bezier(bezier: &BezierCurve) -> Self {
        let raised;
        let b = if bezier.degree() == 0 {
            raised = bezier
                .elevate_degree(1)
                .expect("degree 1 is within every limit");
            &raised
        } else {
            bezier
        };
        Self::from_span_parts(b.dim(), b.degree(), b.points().to_vec(), None, 0.0, 1.0)
    }

    /// One Bezier span on `[a, b]` (`a < b`) from its (validated) parts.
    pub(crate) fn from_span_parts(
        dim: usize,
        degree: usize,
        points: Vec<f64>,
        weights: Option<Vec<f64>>,
        a: f64,
        b: f64,
    ) -> Self {
        let mut knots = vec![a; degree + 1];
        knots.extend(std::iter::repeat_n(b, degree + 1));
        Self {
            degree,
            dim,
            knots,
            points,
            weights: unit_weights_dropped(weights),
            span_cache: Default::default(),
        }
    }

    /// The chain of Bezier `pieces` as one B-spline; piece `i` occupies a
    /// parameter interval of length `intervals[i] > 0`, starting at 0.
    ///
    /// Pieces of lower degree are elevated to the highest degree (exact);
    /// every interior knot gets multiplicity equal to the degree, so the
    /// result equals the chain with no approximation. Consecutive pieces
    /// must share their end points to within `1e-12` of the coordinate
    /// scale (otherwise InvalidArgument, naming the join).
    pub fn from_bezier_chain(pieces: &[BezierCurve], intervals: &[f64]) -> Result<Self> {
        if pieces.is_empty() {
            return Err(BezjoinError::invalid(
                "pieces",
                "at least one piece is needed",
            ));
        }
        let dim = check_chain(
            &pieces.iter().map(|p| p.dim()).collect::<Vec<_>>(),
            intervals,
        )?;
        let degree = pieces.iter().map(BezierCurve::degree).max().unwrap().max(1);
        let elevated: Vec<BezierCurve> = pieces
            .iter()
            .map(|p| p.elevate_degree(degree))
            .collect::<Result<_>>()?;
        let scale = elevated
            .iter()
            .map(BezierCurve::coordinate_scale)
            .fold(1.0, f64::max);
        let mut points: Vec<f64> = Vec::new();
        let mut knots = vec![0.0; degree + 1];
        let mut x = 0.0;
        for (i, piece) in elevated.iter().enumerate() {
            if i == 0 {
                points.extend_from_slice(piece.points());
            } else {
                let prev_end = &points[points.len() - dim..];
                let gap = crate::bezier::distance(prev_end, piece.point(0));
                if gap > 1e-12 * scale {
                    return Err(BezjoinError::invalid(
                        format!("pieces[{i}]"),
                        format!("starts {gap:e} away from the end of piece {}", i - 1),
                    ));
                }
                points.extend_from_slice(&piece.points()[dim..]);
            }
            x += intervals[i];
            let mult = if i + 1 == elevated.len() {
                degree + 1
            } else {
                degree
            };
            knots.extend(std::iter::repeat_n(x, mult));
        }
        Self::new(dim, degree, points, None, knots)
    }

    /// The same curve on the domain `[a, b]` (`a < b`, finite): the knots
    /// mapped by the affine map that takes the domain onto `[a, b]`.
    pub fn reparametrized(&self, a: f64, b: f64) -> Result<NurbsCurve> {
        check_finite_scalar("a", a)?;
        check_finite_scalar("b", b)?;
        if a >= b {
            return Err(BezjoinError::invalid(
                "b",
                format!("{b} must be greater than a = {a}"),
            ));
        }
        let (first, last) = self.domain();
        let scale = (b - a) / (last - first);
        let knots: Vec<f64> = self
            .knots
            .iter()
            .map(|&k| {
                if k == first {
                    a
                } else if k == last {
                    b
                } else {
                    a + (k - first) * scale
                }
            })
            .collect();
        NurbsCurve::new(
            self.dim,
            self.degree,
            self.points.clone(),
            self.weights.clone(),
            knots,
        )
    }

    /// The chain of `pieces` (any curves, each on its own domain) as one
    /// NURBS curve: piece `i` reparametrised onto an interval of length
    /// `intervals[i] > 0` (consecutive, from 0), all elevated to the highest
    /// degree (exact), joined end to end ([`join`](Self::join): each join a
    /// knot of multiplicity `degree`), so the result is the chain itself.
    /// Consecutive pieces must share their end points to within `1e-12` of
    /// the coordinate scale. For Bezier pieces this is
    /// [`from_bezier_chain`](Self::from_bezier_chain).
    pub fn from_curve_chain(pieces: &[CurveRef], intervals: &[f64]) -> Result<Self> {
        if pieces.iter().all(|p| matches!(p, CurveRef::Bezier(_))) {
            let beziers: Vec<BezierCurve> = pieces
                .iter()
                .filter_map(|p| match p {
                    CurveRef::Bezier(b) => Some((*b).clone()),
                    CurveRef::Nurbs(_) => None,
                })
                .collect();
            return Self::from_bezier_chain(&beziers, intervals);
        }
        check_chain(
            &pieces.iter().map(|p| p.dim()).collect::<Vec<_>>(),
            intervals,
        )?;
        let degree = pieces.iter().map(|p| p.degree()).max().unwrap_or(1).max(1);
        let mut x = 0.0;
        let mut chain: Option<NurbsCurve> = None;
        for (i, piece) in pieces.iter().enumerate() {
            let next_x = x + intervals[i];
            let nurbs = match piece {
                CurveRef::Bezier(b) => NurbsCurve::from_bezier(b),
                CurveRef::Nurbs(n) => (*n).clone(),
            };
            let piece = nurbs.reparametrized(x, next_x)?.elevate_degree(degree)?;
            chain = Some(match chain {
                None => piece,
                Some(c) => c.join(&piece).map_err(|e| match e {
                    BezjoinError::InvalidArgument { reason, .. } => {
                        BezjoinError::invalid(format!("pieces[{i}]"), reason)
                    }
                    other => other,
                })?,
            });
            x = next_x;
        }
        chain.ok_or_else(|| BezjoinError::invalid("pieces", "at least one piece is needed"))
    }

    /// Degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The full (flat) knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Row-major poles (Cartesian, not multiplied by the weights).
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// Pole `i` (Cartesian).
    pub fn point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dim..(i + 1) * self.dim]
    }

    /// Number of poles.
    pub fn point_count(&self) -> usize {
        self.points.len() / self.dim
    }

    /// The weights, `None` for a polynomial B-spline (all weights equal to
    /// 1, the form [`NurbsCurve::new`] keeps for any weights all equal to 1).
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Weight of pole `i` (1 for a polynomial curve).
    pub fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }

    /// True when the weights are not all equal (OpenCASCADE's
    /// `IsRational`): equal weights cancel and give a polynomial curve.
    pub fn is_rational(&self) -> bool {
        self.weights
            .as_ref()
            .is_some_and(|w| w.iter().any(|&x| x != w[0]))
    }

    /// The parameter domain `[u_p, u_(n+1)]`.
    pub fn domain(&self) -> (f64, f64) {
        // knots.len() == point_count + degree + 1: the same knot as
        // `knots[point_count]`, without an integer division (every
        // evaluation checks its parameter against the domain).
        (
            self.knots[self.degree],
            self.knots[self.knots.len() - self.degree - 1],
        )
    }

    /// Largest absolute pole coordinate (at least `f64::MIN_POSITIVE`).
    pub fn coordinate_scale(&self) -> f64 {
        crate::bezier::largest_magnitude(&self.points).max(f64::MIN_POSITIVE)
    }

    /// Distinct knots and their multiplicities (the form OpenCASCADE's
    /// `Geom_BSplineCurve` takes).
    pub fn knots_with_multiplicities(&self) -> (Vec<f64>, Vec<usize>) {
        distinct_with_multiplicities(&self.knots)
    }

    /// `Ok` when `u` is finite and inside the domain; otherwise the error
    /// names `name` and the domain.
    #[inline]
    pub fn check_parameter(&self, name: &str, u: f64) -> Result<()> {
        check_finite_scalar(name, u)?;
        let (a, b) = self.domain();
        if u < a || u > b {
            return Err(outside_domain(name, u, (a, b)));
        }
        Ok(())
    }

    /// Homogeneous pole `i`: `(w P, w)`, `dim + 1` values.
    pub(crate) fn homogeneous_point(&self, i: usize, out: &mut [f64]) {
        let w = self.weight(i);
        for (o, x) in out.iter_mut().zip(self.point(i)) {
            *o = w * x;
        }
        out[self.dim] = w;
    }

    /// All homogeneous poles, row-major, `dim + 1` values each.
    pub(crate) fn homogeneous_points(&self) -> Vec<f64> {
        let h = self.dim + 1;
        let mut out = vec![0.0; self.point_count() * h];
        for i in 0..self.point_count() {
            self.homogeneous_point(i, &mut out[i * h..(i + 1) * h]);
        }
        out
    }

    /// The curve from homogeneous poles (`dim + 1` values each, weights
    /// positive) and knots that are known to be valid.
    pub(crate) fn from_homogeneous(
        dim: usize,
        degree: usize,
        homogeneous: &[f64],
        knots: Vec<f64>,
        rational: bool,
    ) -> Self {
        let h = dim + 1;
        let count = homogeneous.len() / h;
        let mut points = Vec::with_capacity(count * dim);
        let mut weights = Vec::with_capacity(count);
        for row in homogeneous.chunks_exact(h) {
            let w = row[dim];
            points.extend(row[..dim].iter().map(|x| x / w));
            weights.push(w);
        }
        Self {
            degree,
            dim,
            knots,
            points,
            weights: rational.then_some(weights),
            span_cache: Default::default(),
        }
    }

    /// The point at `u` into `point` (`dim` values) and, when asked, the
    /// first derivative into `tangent`, by de Boor's algorithm on the
    /// homogeneous poles (from the right at an interior knot, as
    /// [`eval_derivatives`](Self::eval_derivatives)): no heap allocation up
    /// to `(degree + 1) (dim + 1) <= 128`. The derivative comes from the
    /// last level but one, `A' = p (d_p - d_(p-1)) / (u_(k+1) - u_k)`, and
    /// `C' = (A' - w' C) / w`.
    pub(crate) fn point_and_tangent(&self, u: f64, point: &mut [f64], tangent: Option<&mut [f64]>) {
        // Quadratics and cubics in the plane and in space with the sizes as
        // constants (loops unrolled, no bounds checks): the same operations
        // in the same order as the general case below.
        match (self.dim, self.degree) {
            (2, 3) => return self.point_and_tangent_fixed::<3, 3>(u, point, tangent),
            (3, 3) => return self.point_and_tangent_fixed::<4, 3>(u, point, tangent),
            (2, 2) => return self.point_and_tangent_fixed::<3, 2>(u, point, tangent),
            (3, 2) => return self.point_and_tangent_fixed::<4, 2>(u, point, tangent),
            _ => {}
        }
        self.point_and_tangent_any(u, point, tangent);
    }

    /// [`point_and_tangent`](Self::point_and_tangent) for any dimension and
    /// degree (the reference of the fixed sizes).
    fn point_and_tangent_any(&self, u: f64, point: &mut [f64], tangent: Option<&mut [f64]>) {
        let p = self.degree;
        let d = self.dim;
        let hd = d + 1;
        let size = (p + 1) * hd;
        let mut stack = [0.0f64; 128];
        let mut heap = Vec::new();
        let work: &mut [f64] = if size <= stack.len() {
            &mut stack[..size]
        } else {
            heap.resize(size, 0.0);
            &mut heap
        };
        let k = find_span(&self.knots, p, u, KnotSide::Right);
        for j in 0..=p {
            let i = k - p + j;
            let w = self.weight(i);
            let row = &mut work[j * hd..(j + 1) * hd];
            for (o, x) in row.iter_mut().zip(self.point(i)) {
                *o = w * x;
            }
            row[d] = w;
        }
        let knots = &self.knots;
        let level = |r: usize, work: &mut [f64]| {
            for j in (r..=p).rev() {
                let lo = knots[j + k - p];
                let alpha = (u - lo) / (knots[j + 1 + k - r] - lo);
                for c in 0..hd {
                    work[j * hd + c] =
                        (1.0 - alpha) * work[(j - 1) * hd + c] + alpha * work[j * hd + c];
                }
            }
        };
        for r in 1..p {
            level(r, work);
        }
        // Level p - 1 done: the two points left give the derivative.
        let mut derivative = [0.0f64; 16];
        let mut derivative_heap = Vec::new();
        let want_tangent = tangent.is_some();
        let dh: &mut [f64] = if hd <= derivative.len() {
            &mut derivative[..hd]
        } else {
            derivative_heap.resize(hd, 0.0);
            &mut derivative_heap
        };
        if want_tangent {
            let scale = p as f64 / (knots[k + 1] - knots[k]);
            for c in 0..hd {
                dh[c] = scale * (work[p * hd + c] - work[(p - 1) * hd + c]);
            }
        }
        level(p, work);
        let w = work[p * hd + d];
        for c in 0..d {
            point[c] = work[p * hd + c] / w;
        }
        if let Some(tangent) = tangent {
            for c in 0..d {
                tangent[c] = (dh[c] - dh[d] * point[c]) / w;
            }
        }
    }

    /// [`point_and_tangent`](Self::point_and_tangent) for `HD = dim + 1`
    /// homogeneous coordinates and degree `P >= 2` known at compile time:
    /// the same operations in the same order (so the same bits).
    #[inline(always)]
    fn point_and_tangent_fixed<const HD: usize, const P: usize>(
        &self,
        u: f64,
        point: &mut [f64],
        tangent: Option<&mut [f64]>,
    ) {
        let d = HD - 1;
        let mut work = [[0.0f64; HD]; 6];
        let work = &mut work[..=P];
        let knots = &self.knots[..];
        let k = find_span(knots, P, u, KnotSide::Right);
        for (j, row) in work.iter_mut().enumerate() {
            let i = k - P + j;
            let w = self.weight(i);
            for (o, x) in row.iter_mut().zip(self.point(i)) {
                *o = w * x;
            }
            row[d] = w;
        }
        let level = |r: usize, work: &mut [[f64; HD]]| {
            for j in (r..=P).rev() {
                let lo = knots[j + k - P];
                let alpha = (u - lo) / (knots[j + 1 + k - r] - lo);
                let (left, right) = work.split_at_mut(j);
                let (prev, cur) = (&left[j - 1], &mut right[0]);
                for c in 0..HD {
                    cur[c] = (1.0 - alpha) * prev[c] + alpha * cur[c];
                }
            }
        };
        for r in 1..P {
            level(r, work);
        }
        let mut dh = [0.0f64; HD];
        let want_tangent = tangent.is_some();
        if want_tangent {
            let scale = P as f64 / (knots[k + 1] - knots[k]);
            for c in 0..HD {
                dh[c] = scale * (work[P][c] - work[P - 1][c]);
            }
        }
        level(P, work);
        let w = work[P][d];
        for c in 0..d {
            point[c] = work[P][c] / w;
        }
        if let Some(tangent) = tangent {
            for c in 0..d {
                tangent[c] = (dh[c] - dh[d] * point[c]) / w;
            }
        }
    }

    /// [`point_and_tangent`](Self::point_and_tangent) with the tangent, for
    /// a curve with weights by de Casteljau's algorithm on the kept
    /// homogeneous Bezier rows of the span of `u` ([`Self::span_poles`],
    /// from the right at an interior knot, the end spans beyond the domain)
    /// in `t = (u - a) / (b - a)`: no knot search and no rows to weight.
    /// The same point and tangent up to rounding (the rows are the
    /// decomposition's, not the poles'); quadratics and cubics in the plane
    /// and in space, everything else by `point_and_tangent`.
    pub(crate) fn point_and_tangent_by_spans(
        &self,
        u: f64,
        point: &mut [f64],
        tangent: &mut [f64],
    ) {
        if self.weights.is_some() {
            match (self.dim, self.degree) {
                (2, 3) => return self.point_and_tangent_spans_fixed::<3, 3>(u, point, tangent),
                (3, 3) => return self.point_and_tangent_spans_fixed::<4, 3>(u, point, tangent),
                (2, 2) => return self.point_and_tangent_spans_fixed::<3, 2>(u, point, tangent),
                (3, 2) => return self.point_and_tangent_spans_fixed::<4, 2>(u, point, tangent),
                _ => {}
            }
        }
        self.point_and_tangent(u, point, Some(tangent));
    }

    /// [`point_and_tangent_by_spans`](Self::point_and_tangent_by_spans) with
    /// `HD = dim + 1` and the degree `P` constants.
    fn point_and_tangent_spans_fixed<const HD: usize, const P: usize>(
        &self,
        u: f64,
        point: &mut [f64],
        tangent: &mut [f64],
    ) {
        let d = HD - 1;
        let poles = self.span_poles();
        let breaks = &poles.breaks[..];
        let last = breaks.len() - 2;
        let mut i = 0;
        while i < last && u >= breaks[i + 1] {
            i += 1;
        }
        let (lo, hi) = (breaks[i], breaks[i + 1]);
        let Some(rows) = poles.rows.get(i * P * HD..(i * P + P + 1) * HD) else {
            // Not the layout of a decomposition (never for a valid curve).
            return self.point_and_tangent(u, point, Some(tangent));
        };
        let mut work = [[0.0f64; HD]; 6];
        let work = &mut work[..=P];
        for (j, row) in work.iter_mut().enumerate() {
            row.copy_from_slice(&rows[j * HD..(j + 1) * HD]);
        }
        let t = (u - lo) / (hi - lo);
        let s = 1.0 - t;
        let level = |r: usize, work: &mut [[f64; HD]]| {
            for j in (r..=P).rev() {
                let (left, right) = work.split_at_mut(j);
                let (prev, cur) = (&left[j - 1], &mut right[0]);
                for c in 0..HD {
                    cur[c] = s * prev[c] + t * cur[c];
                }
            }
        };
        for r in 1..P {
            level(r, work);
        }
        let scale = P as f64 / (hi - lo);
        let mut dh = [0.0f64; HD];
        for c in 0..HD {
            dh[c] = scale * (work[P][c] - work[P - 1][c]);
        }
        level(P, work);
        let w = work[P][d];
        for c in 0..d {
            point[c] = work[P][c] / w;
        }
        for c in 0..d {
            tangent[c] = (dh[c] - dh[d] * point[c]) / w;
        }
    }

    /// Value and derivatives `0..=max_order` at `u`, taken from the span on
    /// `side` of `u` when `u` is a knot; row-major, `(max_order + 1) * dim`
    /// values (row `k` is the `k`-th derivative). Any order is allowed:
    /// above the degree the derivatives of a polynomial curve vanish, those
    /// of a rational curve do not (A4.2). Outside the domain the end spans
    /// are continued; callers that must refuse such `u` use
    /// [`check_parameter`](Self::check_parameter).
    pub fn eval_derivatives_side(&self, u: f64, max_order: usize, side: KnotSide) -> Vec<f64> {
        let mut out = vec![0.0; (max_order + 1) * self.dim];
        self.eval_derivatives_into(u, max_order, side, &mut out, None);
        out
    }

    /// [`eval_derivatives_side`](Self::eval_derivatives_side) with the
    /// rounding bound of each row of
    /// [`eval_derivatives_into`](Self::eval_derivatives_into), as vectors
    /// (the tests' reference for the basis route).
    #[cfg(test)]
    pub(crate) fn eval_derivatives_with_bound(
        &self,
        u: f64,
        max_order: usize,
        side: KnotSide,
    ) -> (Vec<f64>, Vec<f64>) {
        let mut out = vec![0.0; (max_order + 1) * self.dim];
        let mut bound = vec![0.0; max_order + 1];
        self.eval_derivatives_into(u, max_order, side, &mut out, Some(&mut bound));
        (out, bound)
    }

    /// Value and derivatives `0..=max_order` at `u` into `out`
    /// (`(max_order + 1) * dim` values, row `k` the `k`-th derivative), from
    /// the span on `side` of a knot; with `bound`, also a bound on the
    /// rounding error of each row (`max_order + 1` values, absolute):
    /// `gamma * (sum |N^(k)_j| |w_j P_j| + sum_i C(k,i) |w^(i)| |C^(k-i)|) / w`
    /// with `gamma = 2 (p + k + 2) eps`.
    ///
    /// A2.3 gives the basis derivatives of the span, the homogeneous curve
    /// `A = sum N_j w_j P_j`, `w = sum N_j w_j` and their derivatives are
    /// summed from them, and A4.2 (`C^(k) = (A^(k) - sum_(i=1..k) C(k,i)
    /// w^(i) C^(k-i)) / w`) gives the Cartesian rows. No allocation up to
    /// degree 15 with `(max_order + 1) * (dim + 1) <= 128`.
    pub(crate) fn eval_derivatives_into(
        &self,
        u: f64,
        max_order: usize,
        side: KnotSide,
        out: &mut [f64],
        bound: Option<&mut [f64]>,
    ) {
        let p = self.degree;
        let m = p + 1;
        let rows = max_order + 1;
        let n = max_order.min(p);
        debug_assert_eq!(out.len(), rows * self.dim);
        // Stack buffers sized for the degree (zeroing a large buffer costs
        // more than a small curve's whole evaluation), the heap beyond 15.
        let (basis_len, work_len, jets_len) = ((n + 1) * m, basis_scratch_len(p), 3 * rows);
        let fits = |b: usize, w: usize, j: usize| basis_len <= b && work_len <= w && jets_len <= j;
        // Dimensions 2 and 3 at degrees 1 to 5 with at most 8 rows: the
        // same body with the degree and dimension constants.
        if rows <= 8 && (1..=5).contains(&p) && (self.dim == 2 || self.dim == 3) {
            match (self.dim, p) {
                (3, 1) => self.eval_rows_fixed::<3, 1, 4, 12>(u, n, side, out, bound),
                (3, 2) => self.eval_rows_fixed::<3, 2, 9, 21>(u, n, side, out, bound),
                (3, 3) => self.eval_rows_fixed::<3, 3, 16, 32>(u, n, side, out, bound),
                (3, 4) => self.eval_rows_fixed::<3, 4, 25, 45>(u, n, side, out, bound),
                (3, _) => self.eval_rows_fixed::<3, 5, 36, 60>(u, n, side, out, bound),
                (_, 1) => self.eval_rows_fixed::<2, 1, 4, 12>(u, n, side, out, bound),
                (_, 2) => self.eval_rows_fixed::<2, 2, 9, 21>(u, n, side, out, bound),
                (_, 3) => self.eval_rows_fixed::<2, 3, 16, 32>(u, n, side, out, bound),
                (_, 4) => self.eval_rows_fixed::<2, 4, 25, 45>(u, n, side, out, bound),
                (_, _) => self.eval_rows_fixed::<2, 5, 36, 60>(u, n, side, out, bound),
            }
            return;
        }
        if fits(16, basis_scratch_len(3), 48) {
            let (mut b, mut w, mut j) = ([0.0; 16], [0.0; basis_scratch_len(3)], [0.0; 48]);
            self.eval_rows(u, n, side, out, bound, &mut b, &mut w, &mut j);
        } else if fits(64, basis_scratch_len(7), 96) {
            let (mut b, mut w, mut j) = ([0.0; 64], [0.0; basis_scratch_len(7)], [0.0; 96]);
            self.eval_rows(u, n, side, out, bound, &mut b, &mut w, &mut j);
        } else if fits(256, basis_scratch_len(15), 192) {
            let (mut b, mut w, mut j) = ([0.0; 256], [0.0; basis_scratch_len(15)], [0.0; 192]);
            self.eval_rows(u, n, side, out, bound, &mut b, &mut w, &mut j);
        } else {
            let (mut b, mut w, mut j) = (
                vec![0.0; basis_len],
                vec![0.0; work_len],
                vec![0.0; jets_len],
            );
            self.eval_rows(u, n, side, out, bound, &mut b, &mut w, &mut j);
        }
    }

    /// The value at `u` (from the right at a knot) into `out` for
    /// dimensions 2 and 3 up to degree [`VALUE_FAST_MAX_DEGREE`], returning
    /// `false` (nothing written) otherwise: row 0 of
    /// [`eval_derivatives_into`](Self::eval_derivatives_into) with its
    /// operations in its order, so the same bits (tested), without the
    /// derivative machinery, its buffers and their zeroing. The basis
    /// functions by A2.2, which is the first part of A2.3 operation for
    /// operation; the homogeneous sums as `eval_rows` forms them (from
    /// `0.0`, a zero basis function skipped in the rational sums only), then
    /// one division by the weight.
    fn value_fast_into(&self, u: f64, out: &mut [f64]) -> bool {
        if self.degree > VALUE_FAST_MAX_DEGREE {
            return false;
        }
        match self.dim {
            3 => {
                if let Ok(out) = <&mut [f64; 3]>::try_from(out) {
                    self.value_small_degree(u, out);
                    return true;
                }
            }
            2 => {
                if let Ok(out) = <&mut [f64; 2]>::try_from(out) {
                    self.value_small_degree(u, out);
                    return true;
                }
            }
            _ => {}
        }
        false
    }

    /// [`value_fixed`](Self::value_fixed) with the degree a constant up to
    /// 7 (one function per degree, [`value_degree`](Self::value_degree):
    /// the loops unrolled, the scratch arrays in registers), a variable
    /// above.
    #[inline(always)]
    fn value_small_degree<const D: usize>(&self, u: f64, out: &mut [f64; D]) {
        match self.degree {
            1 => self.value_degree::<D, 1>(u, out),
            2 => self.value_degree::<D, 2>(u, out),
            3 => self.value_degree::<D, 3>(u, out),
            4 => self.value_degree::<D, 4>(u, out),
            5 => self.value_degree::<D, 5>(u, out),
            6 => self.value_degree::<D, 6>(u, out),
            7 => self.value_degree::<D, 7>(u, out),
            p => self.value_fixed::<D, { VALUE_FAST_MAX_DEGREE + 1 }>(u, p, out),
        }
    }

    /// [`value_fixed`](Self::value_fixed) at the constant degree `P < 8`.
    #[inline(never)]
    fn value_degree<const D: usize, const P: usize>(&self, u: f64, out: &mut [f64; D]) {
        self.value_fixed::<D, 8>(u, P, out);
    }

    /// [`value_fast_into`](Self::value_fast_into) for `D == dim`
    /// coordinates and `p == degree < M`.
    #[inline(always)]
    fn value_fixed<const D: usize, const M: usize>(&self, u: f64, p: usize, out: &mut [f64; D]) {
        debug_assert!(p == self.degree && p < M);
        let knots = &self.knots;
        let span = find_span(knots, p, u, KnotSide::Right);
        // A2.2: basis[r] is N_(span - p + r) of degree j after step j.
        let (mut left, mut right, mut basis) = ([0.0f64; M], [0.0f64; M], [0.0f64; M]);
        basis[0] = 1.0;
        for j in 1..=p {
            left[j] = u - knots[span + 1 - j];
            right[j] = knots[span + j] - u;
            let mut saved = 0.0;
            for r in 0..j {
                let temp = basis[r] / (right[r + 1] + left[j - r]);
                basis[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            basis[j] = saved;
        }
        let first = span - p;
        let points = &self.points[first * D..(span + 1) * D];
        let mut sum = [0.0f64; D];
        match &self.weights {
            None => {
                for (b, pole) in basis[..=p].iter().zip(points.chunks_exact(D)) {
                    for c in 0..D {
                        sum[c] += b * pole[c];
                    }
                }
                *out = sum;
            }
            Some(weights) => {
                let mut w = 0.0;
                let weights = &weights[first..=span];
                for ((&b, &wi), pole) in basis[..=p].iter().zip(weights).zip(points.chunks_exact(D))
                {
                    if b == 0.0 {
                        continue;
                    }
                    for c in 0..D {
                        sum[c] += b * (wi * pole[c]);
                    }
                    w += b * wi;
                }
                for c in 0..D {
                    out[c] = sum[c] / w;
                }
            }
        }
    }

    /// [`eval_rows`](Self::eval_rows) with the dimension `D`, the degree
    /// `P` and the buffer sizes `B = (P + 1)^2`, `W = basis_scratch_len(P)`
    /// compile-time constants, at most 8 rows: the same operations in the
    /// same order (test `fixed_degree_rows_are_the_general_rows_to_the_bit`).
    #[inline(never)]
    fn eval_rows_fixed<const D: usize, const P: usize, const B: usize, const W: usize>(
        &self,
        u: f64,
        n: usize,
        side: KnotSide,
        out: &mut [f64],
        bound: Option<&mut [f64]>,
    ) {
        debug_assert!(self.dim == D && self.degree == P && out.len() <= 8 * D);
        let (mut b, mut w, mut j) = ([0.0; B], [0.0; W], [0.0; 24]);
        // Rows up to the degree (`n == P`, `P + 1` rows: the connect's jets
        // of cubics to order 3) with the order and the row count constants
        // too: the same operations.
        if n == P && out.len() == (P + 1) * D {
            let out = &mut out[..(P + 1) * D];
            self.eval_rows_with(P, D, u, P, side, out, bound, &mut b, &mut w, &mut j);
        } else {
            self.eval_rows_with(P, D, u, n, side, out, bound, &mut b, &mut w, &mut j);
        }
    }

    /// The body of [`eval_derivatives_into`](Self::eval_derivatives_into)
    /// on buffers of at least `(n + 1) (p + 1)` (basis), `basis_scratch_len(p)`
    /// (work) and `3 (rows)` (jets) values, `n = min(max_order, p)`, where
    /// `rows = out.len() / dim`.
    #[allow(clippy::too_many_arguments)]
    fn eval_rows(
        &self,
        u: f64,
        n: usize,
        side: KnotSide,
        out: &mut [f64],
        bound: Option<&mut [f64]>,
        basis: &mut [f64],
        work: &mut [f64],
        jets: &mut [f64],
    ) {
        self.eval_rows_with(
            self.degree,
            self.dim,
            u,
            n,
            side,
            out,
            bound,
            basis,
            work,
            jets,
        );
    }

    /// [`eval_rows`](Self::eval_rows) with `p == self.degree` and
    /// `d == self.dim` given (constants where the caller knows them).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn eval_rows_with(
        &self,
        p: usize,
        d: usize,
        u: f64,
        n: usize,
        side: KnotSide,
        out: &mut [f64],
        mut bound: Option<&mut [f64]>,
        basis: &mut [f64],
        work: &mut [f64],
        jets: &mut [f64],
    ) {
        let m = p + 1;
        let rows = out.len() / d;
        let span = find_span(&self.knots, p, u, side);
        let knots = &self.knots;
        basis_derivatives_inline(
            |i| knots[i],
            p,
            span,
            u,
            n,
            BasisLayout::row_major(p),
            basis,
            work,
        );
        // Homogeneous rows: A^(k) in `out`; w^(k), the |w| sums and the |A|
        // sums in `jets`, `rows` values each.
        let jets = &mut jets[..3 * rows];
        let (w, rest) = jets.split_at_mut(rows);
        let (w_abs, a_abs) = rest.split_at_mut(rows);
        out.fill(0.0);
        let first = span - p;
        let track = bound.is_some();
        match &self.weights {
            None => {
                for k in 0..=n {
                    let row = &mut out[k * d..(k + 1) * d];
                    for (j, &b) in basis[k * m..(k + 1) * m].iter().enumerate() {
                        let pole = &self.points[(first + j) * d..(first + j + 1) * d];
                        for (o, &x) in row.iter_mut().zip(pole) {
                            *o += b * x;
                        }
                        if track && b != 0.0 {
                            let size = pole.iter().fold(0.0f64, |s, x| s.max(x.abs()));
                            a_abs[k] += b.abs() * size;
                            w_abs[k] += b.abs();
                        }
                        w[k] += b;
                    }
                }
            }
            Some(weights) => {
                // Pole by pole (its weighted coordinates and their size
                // formed once for all the orders); each order's sums still
                // take the poles in their order, so the same sums.
                for j in 0..m {
                    let wi = weights[first + j];
                    let pole = &self.points[(first + j) * d..(first + j + 1) * d];
                    let size = if track {
                        pole.iter().fold(0.0f64, |s, x| s.max((wi * x).abs()))
                    } else {
                        0.0
                    };
                    for k in 0..=n {
                        let b = basis[k * m + j];
                        if b == 0.0 {
                            continue;
                        }
                        let bw = b * wi;
                        for (o, &x) in out[k * d..(k + 1) * d].iter_mut().zip(pole) {
                            *o += b * (wi * x);
                        }
                        if track {
                            a_abs[k] += b.abs() * size;
                            w_abs[k] += b.abs() * wi;
                        }
                        w[k] += bw;
                    }
                }
            }
        }
        let rational = self.weights.is_some();
        let eps = f64::EPSILON * 0.5;
        for k in 0..rows {
            let mut row_abs = a_abs[k];
            if rational {
                // C(k, i): from the table of exact binomials up to row
                // `SPAN_FAST_MAX_DEGREE` (constants for a constant row count),
                // beyond by its recurrence, each step exact in f64 (an
                // integer times an integer, divided exactly): the same
                // values.
                let mut choose = 1.0;
                // w^(i) = 0 above the basis orders `n` (at most the degree):
                // those terms are skipped, so a row costs O(n d), not O(k d)
                // (orders far above the degree stay linear in cost).
                for i in 1..=k.min(n) {
                    choose = if k <= eval::SPAN_FAST_MAX_DEGREE {
                        eval::BINOMIALS[k * (k + 1) / 2 + i]
                    } else {
                        choose * (k + 1 - i) as f64 / i as f64
                    };
                    if w[i] == 0.0 && w_abs[i] == 0.0 {
                        continue;
                    }
                    let coef = choose * w[i];
                    let (done, current) = out.split_at_mut(k * d);
                    let prev = &done[(k - i) * d..(k - i + 1) * d];
                    let mut size = 0.0f64;
                    for (o, &x) in current[..d].iter_mut().zip(prev) {
                        *o -= coef * x;
                        size = size.max(x.abs());
                    }
                    row_abs += choose * w_abs[i] * size;
                }
                for o in &mut out[k * d..(k + 1) * d] {
                    *o /= w[0];
                }
                row_abs /= w[0];
            }
            if let Some(bound) = bound.as_deref_mut() {
                let gamma = 2.0 * (p + k + 2) as f64 * eps;
                bound[k] = gamma * row_abs * (d as f64).sqrt();
            }
        }
    }

    /// [`eval_derivatives`](Self::eval_derivatives) for callers that need
    /// an answer they can trust: `u` in the domain (the error names
    /// `name`), and every value finite; a derivative that overflows `f64`
    /// (extreme knot spacing or weights) is `NonFiniteScalar` naming its
    /// order, not an infinite number.
    pub fn eval_derivatives_checked(
        &self,
        name: &str,
        u: f64,
        max_order: usize,
    ) -> Result<Vec<f64>> {
        let mut out = vec![0.0; (max_order + 1) * self.dim];
        self.eval_derivatives_checked_into(|| name.to_owned(), u, max_order, &mut out)?;
        Ok(out)
    }

    /// [`eval_derivatives_checked`](Self::eval_derivatives_checked) into
    /// `out` (`(max_order + 1) * dim` values, row `k` the `k`-th derivative,
    /// from the right at a knot), without allocating up to degree 15 with
    /// `(max_order + 1) * (dim + 1) <= 128`: the same values to the bit as
    /// `eval_derivatives_checked`. The route: in dimensions 2 and 3 up to
    /// degree 15, the values of a curve of several spans by A2.2 (the bits
    /// of row 0 of [`eval_derivatives`](Self::eval_derivatives)); a
    /// polynomial one-span curve and the derivatives (orders up to 3 below
    /// the degree) of every curve through the curve's Bezier spans
    /// (`nurbs/eval.rs`: the bits of the Bezier curve for a polynomial
    /// one-span curve on `[0, 1]`, otherwise the values of
    /// `eval_derivatives` up to rounding, tested); the basis route
    /// (A2.3/A4.2) for everything else. `name` is
    /// called only to build an error message (a caller evaluating many
    /// parameters formats their names only when one fails). On an error
    /// from the parameter nothing is written; on an overflowing derivative
    /// `out` holds the values computed, the non-finite one included.
    ///
    /// # Panics
    /// If `out.len() != (max_order + 1) * dim`.
    pub fn eval_derivatives_checked_into(
        &self,
        name: impl Fn() -> String,
        u: f64,
        max_order: usize,
        out: &mut [f64],
    ) -> Result<()> {
        assert_eq!(out.len(), (max_order + 1) * self.dim);
        let (first, last) = self.domain();
        if !(first..=last).contains(&u) {
            // Not finite or outside: the message of `check_parameter`.
            self.check_parameter(&name(), u)?;
        }
        // Through the Bezier spans (`eval.rs`) where that applies and stays
        // finite (coordinates near the top of the f64 range can overflow its
        // sums), otherwise the basis route.
        if self.eval_fast_into(u, max_order, out) && out.iter().all(|x| x.is_finite()) {
            return Ok(());
        }
        self.eval_derivatives_into(u, max_order, KnotSide::Right, out, None);
        if let Some(i) = out.iter().position(|x| !x.is_finite()) {
            let name = name();
            return Err(BezjoinError::NonFiniteScalar {
                name: format!(
                    "derivative of order {} at {name} = {} (it overflows f64)",
                    i / self.dim,
                    Compact(u)
                ),
                value: out[i],
            });
        }
        Ok(())
    }

    /// Value and derivatives at `u` (from the right at a knot, from the
    /// left at the domain's end).
    pub fn eval_derivatives(&self, u: f64, max_order: usize) -> Vec<f64> {
        self.eval_derivatives_side(u, max_order, KnotSide::Right)
    }

    /// The point at `u` (`dim` values; de Boor's algorithm).
    pub fn eval(&self, u: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim];
        self.point_and_tangent(u, &mut out, None);
        out
    }

    /// Largest `k` such that derivatives `0..=k` from both sides of the knot
    /// at `u` agree to `relative_tolerance` (relative to the larger of the
    /// two derivative norms and 1e-300), up to the degree; `None` if even the
    /// values differ.
    pub fn continuity_at(&self, u: f64, relative_tolerance: f64) -> Option<usize> {
        let left = self.eval_derivatives_side(u, self.degree, KnotSide::Left);
        let right = self.eval_derivatives_side(u, self.degree, KnotSide::Right);
        let mut order = None;
        for k in 0..=self.degree {
            if relative_jump(
                &left[k * self.dim..(k + 1) * self.dim],
                &right[k * self.dim..(k + 1) * self.dim],
            ) > relative_tolerance
            {
                break;
            }
            order = Some(k);
        }
        order
    }
}

/// Highest degree whose values [`NurbsCurve::eval_derivatives_checked_into`]
/// computes without the derivative machinery (stack arrays of this size
/// plus one).
const VALUE_FAST_MAX_DEGREE: usize = 15;

/// The checks shared by the chain builders: one interval `> 0` per piece,
/// pieces of one dimension (returned). `dims` is not empty.
fn check_chain(dims: &[usize], intervals: &[f64]) -> Result<usize> {
    if intervals.len() != dims.len() {
        return Err(BezjoinError::LengthMismatch {
            name: "intervals".into(),
            expected: dims.len(),
            actual: intervals.len(),
        });
    }
    check_finite("intervals", intervals)?;
    if let Some(i) = intervals.iter().position(|&h| h <= 0.0) {
        return Err(BezjoinError::out_of_range(
            format!("intervals[{i}]"),
            intervals[i],
            "> 0",
        ));
    }
    let dim = dims[0];
    if let Some(i) = dims.iter().position(|&d| d != dim) {
        return Err(BezjoinError::DimensionMismatch {
            name: format!("pieces[{i}]"),
            expected: dim,
            actual: dims[i],
        });
    }
    Ok(dim)
}

/// `None` for weights that are all exactly 1 (the polynomial form).
pub(crate) fn unit_weights_dropped(weights: Option<Vec<f64>>) -> Option<Vec<f64>> {
    weights.filter(|w| w.iter().any(|&x| x != 1.0))
}

/// `|a - b| / max(|a|, |b|)`, 0 when both vanish.
pub fn relative_jump(a: &[f64], b: &[f64]) -> f64 {
    let diff = crate::bezier::distance(a, b);
    let size = crate::bezier::norm(a).max(crate::bezier::norm(b));
    if size == 0.0 { 0.0 } else { diff / size }
}

/// Distinct values of a sorted knot vector and how often each occurs.
pub(crate) fn distinct_with_multiplicities(knots: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut distinct = Vec::new();
    let mut mults: Vec<usize> = Vec::new();
    for &k in knots {
        if distinct.last() == Some(&k) {
            *mults.last_mut().unwrap() += 1;
        } else {
            distinct.push(k);
            mults.push(1);
        }
    }
    (distinct, mults)
}

/// Relative jumps of the derivatives `0..=max_order` across the join of two
/// Bezier pieces, each read in a global parameter where `left` spans an
/// interval of length `left_interval` and `right` one of `right_interval`:
/// entry `k` is `|L^(k)(1)/hl^k - R^(k)(0)/hr^k|` relative to the larger norm.
pub fn join_jumps(
    left: &BezierCurve,
    left_interval: f64,
    right: &BezierCurve,
    right_interval: f64,
    max_order: usize,
) -> Vec<f64> {
    let d = left.dim();
    let l = left.eval_derivatives(1.0, max_order);
    let r = right.eval_derivatives(0.0, max_order);
    (0..=max_order)
        .map(|k| {
            let sl = left_interval.powi(k as i32);
            let sr = right_interval.powi(k as i32);
            let a: Vec<f64> = l[k * d..(k + 1) * d].iter().map(|v| v / sl).collect();
            let b: Vec<f64> = r[k * d..(k + 1) * d].iter().map(|v| v / sr).collect();
            relative_jump(&a, &b)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_curve_is_c_infinity_as_a_chain() {
        let c =
            BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [5.0, 1.0]])
                .unwrap();
        let (a, b) = c.split_at(0.3).unwrap();
        let s = NurbsCurve::from_bezier_chain(&[a, b], &[0.3, 0.7]).unwrap();
        assert_eq!(s.continuity_at(0.3, 1e-12), Some(4));
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let v = s.eval_derivatives(t, 0);
            let w = c.eval(t);
            assert!((v[0] - w[0]).abs() < 1e-13 && (v[1] - w[1]).abs() < 1e-13);
        }
    }

    #[test]
    fn a_kink_is_c0_only() {
        let a = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 0.0]]).unwrap();
        let b = BezierCurve::from_rows(&[[1.0, 0.0], [1.0, 1.0]]).unwrap();
        let s = NurbsCurve::from_bezier_chain(&[a, b], &[1.0, 1.0]).unwrap();
        assert_eq!(s.continuity_at(1.0, 1e-12), Some(0));
        let (k, m) = s.knots_with_multiplicities();
        assert_eq!(k, vec![0.0, 1.0, 2.0]);
        assert_eq!(m, vec![2, 1, 2]);
    }
}

#[cfg(test)]
mod de_boor_tests {
    use super::*;

    /// de Boor's point and tangent equal A2.3/A4.2's value and first
    /// derivative (two independent routes) on rational multi-span curves,
    /// at knots too (both from the right), and in a dimension above the
    /// stack buffers.
    #[test]
    fn point_and_tangent_agree_with_the_basis_derivatives() {
        let cases = [
            (
                2,
                2,
                vec![0.0, 0.0, 0.0, 1.0, 2.5, 4.0, 4.0, 4.0],
                Some(vec![1.0, 2.0, 0.5, 1.5, 1.0]),
            ),
            (3, 3, (0..10).map(f64::from).collect(), None),
            (
                20,
                1,
                vec![0.0, 0.0, 0.3, 1.0, 1.0],
                Some(vec![1.0, 3.0, 0.2]),
            ),
        ];
        for (dim, degree, knots, weights) in cases {
            let count = knots.len() - degree - 1;
            let poles: Vec<f64> = (0..count * dim)
                .map(|i| ((i * 7919) % 13) as f64 - 6.0)
                .collect();
            let c = NurbsCurve::new(dim, degree, poles, weights, knots.clone()).unwrap();
            let (a, b) = c.domain();
            let mut us: Vec<f64> = (0..=40).map(|i| a + (b - a) * i as f64 / 40.0).collect();
            us.extend(knots.iter().copied().filter(|&k| k >= a && k <= b));
            for u in us {
                let mut point = vec![0.0; dim];
                let mut tangent = vec![0.0; dim];
                c.point_and_tangent(u, &mut point, Some(&mut tangent));
                let jet = c.eval_derivatives(u, 1);
                let size = jet.iter().fold(1.0f64, |m, x| m.max(x.abs()));
                for i in 0..dim {
                    assert!((point[i] - jet[i]).abs() <= 1e-13 * size, "u {u}");
                    assert!((tangent[i] - jet[dim + i]).abs() <= 1e-12 * size, "u {u}");
                }
            }
        }
    }
}

#[cfg(test)]
mod degenerate_input_tests {
    use super::*;

    #[test]
    fn new_rejects_an_impossible_degree_without_panicking() {
        for degree in [usize::MAX, usize::MAX - 1] {
            let r = NurbsCurve::new(1, degree, vec![0.0, 1.0], None, vec![0.0, 1.0]);
            assert!(
                matches!(&r, Err(BezjoinError::InvalidArgument { name, .. }) if name == "degree" || name == "points"),
                "{r:?}"
            );
        }
    }

    #[test]
    fn continuity_at_a_smooth_join_of_curves_with_vanishing_derivatives() {
        // A straight line split at 0.5: all derivatives above the first
        // vanish on both sides, so the chain is C^degree at the join.
        let c = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]]).unwrap();
        let (a, b) = c.split_at(0.5).unwrap();
        let s = NurbsCurve::from_bezier_chain(&[a, b], &[0.5, 0.5]).unwrap();
        assert_eq!(s.continuity_at(0.5, 1e-12), Some(3));
        // A point that is not a knot is inside one polynomial piece.
        assert_eq!(s.continuity_at(0.25, 1e-12), Some(3));
    }
}

#[cfg(test)]
mod value_fast_path_tests {
    use super::*;

    use crate::test_values::Values;

    /// A clamped curve of `spans` spans with one double interior knot,
    /// uneven knot spacing, poles in `[-2, 2)` and (when `rational`)
    /// weights in `[0.3, 3.3)`.
    fn curve(values: &mut Values, dim: usize, degree: usize, rational: bool) -> NurbsCurve {
        let spans = 4;
        let mut knots = vec![-1.0; degree + 1];
        let mut u = -1.0;
        for s in 1..spans {
            u += 0.2 + values.unit();
            knots.push(u);
            if s == 2 && degree > 1 {
                knots.push(u);
            }
        }
        u += 0.2 + values.unit();
        knots.extend(std::iter::repeat_n(u, degree + 1));
        let count = knots.len() - degree - 1;
        let poles = (0..count * dim)
            .map(|_| 4.0 * values.unit() - 2.0)
            .collect();
        let weights = rational.then(|| (0..count).map(|_| 0.3 + 3.0 * values.unit()).collect());
        NurbsCurve::new(dim, degree, poles, weights, knots).unwrap()
    }

    /// The order-0 path of `eval_derivatives_checked_into` (the value of
    /// `bzj_curve_eval` and `bzj_curve_eval_many` on a NURBS handle) gives
    /// the bits of row 0 of the general A2.3 path it bypasses, at random
    /// parameters, at every knot (from the right) and at both ends, for
    /// polynomial and rational curves of dimensions 1 to 4 (1 and 4 take
    /// the general path) and degrees 1 to 17 (above 15 the general path).
    #[test]
    fn value_fast_path_is_the_general_path_to_the_bit() {
        let mut values = Values(2024);
        for dim in 1..=4 {
            for degree in 1..=17 {
                for rational in [false, true] {
                    let c = curve(&mut values, dim, degree, rational);
                    let (first, last) = c.domain();
                    let mut us: Vec<f64> = c.knots().to_vec();
                    us.extend((0..30).map(|_| first + (last - first) * values.unit()));
                    for u in us {
                        let mut fast = vec![0.0; dim];
                        c.eval_derivatives_checked_into(|| "u".into(), u, 0, &mut fast)
                            .unwrap();
                        let mut general = vec![0.0; dim];
                        c.eval_derivatives_into(u, 0, KnotSide::Right, &mut general, None);
                        let same = fast
                            .iter()
                            .zip(&general)
                            .all(|(a, b)| a.to_bits() == b.to_bits());
                        assert!(
                            same,
                            "dim {dim}, degree {degree}, rational {rational}, u {u}: \
                             {fast:?} vs {general:?}"
                        );
                    }
                }
            }
        }
    }

    /// The allocation-free checked evaluation names the parameter as
    /// `eval_derivatives_checked` does, and writes nothing when the
    /// parameter is refused.
    #[test]
    fn checked_into_refuses_parameters_like_the_allocating_form() {
        let mut values = Values(5);
        let c = curve(&mut values, 3, 3, true);
        let (first, last) = c.domain();
        for u in [first - 1.0, last + 1e-9, f64::NAN, f64::INFINITY] {
            let mut out = [7.0; 6];
            let err = c
                .eval_derivatives_checked_into(|| "ts[4]".into(), u, 1, &mut out)
                .unwrap_err();
            let expected = c.eval_derivatives_checked("ts[4]", u, 1).unwrap_err();
            assert_eq!(err.to_string(), expected.to_string());
            assert!(err.to_string().contains("ts[4]"), "{err}");
            assert_eq!(out, [7.0; 6]);
        }
        let mut out = [0.0; 6];
        c.eval_derivatives_checked_into(|| unreachable!("no error, no name"), last, 1, &mut out)
            .unwrap();
        assert_eq!(
            out.to_vec(),
            c.eval_derivatives_checked("u", last, 1).unwrap()
        );
    }
}

#[cfg(test)]
mod fixed_de_boor_tests {
    use super::NurbsCurve;

    /// The fixed-size de Boor evaluations (plane and space, degrees 2 and
    /// 3) give the general path's bits, point and tangent, on random
    /// curves with and without weights, at random parameters and at the
    /// knots.
    #[test]
    fn fixed_sizes_are_the_general_path_bit_for_bit() {
        let mut next = crate::test_values::unit_generator(71);
        for case in 0..120 {
            let dim = 2 + case % 2;
            let degree = 2 + (case / 2) % 2;
            let count = degree + 1 + case % 5;
            let mut knots = vec![0.0; degree + 1];
            let mut inner: Vec<f64> = (0..count - degree - 1).map(|_| next()).collect();
            inner.sort_by(f64::total_cmp);
            knots.extend(inner);
            knots.extend(std::iter::repeat_n(1.0, degree + 1));
            let knots: Vec<f64> = knots.iter().map(|k| 2.0 + 3.0 * k).collect();
            let poles: Vec<f64> = (0..count * dim).map(|_| 4.0 * next() - 2.0).collect();
            let weights = (case % 3 == 0).then(|| (0..count).map(|_| 0.5 + next()).collect());
            let c = NurbsCurve::new(dim, degree, poles, weights, knots.clone()).unwrap();
            let mut us: Vec<f64> = (0..30).map(|_| 2.0 + 3.0 * next()).collect();
            us.extend(knots.iter().copied());
            for u in us {
                let (mut p1, mut t1) = ([0.0; 3], [0.0; 3]);
                let (mut p2, mut t2) = ([0.0; 3], [0.0; 3]);
                c.point_and_tangent(u, &mut p1[..dim], Some(&mut t1[..dim]));
                c.point_and_tangent_any(u, &mut p2[..dim], Some(&mut t2[..dim]));
                assert_eq!(
                    p1.map(f64::to_bits),
                    p2.map(f64::to_bits),
                    "case {case} u {u}"
                );
                assert_eq!(
                    t1.map(f64::to_bits),
                    t2.map(f64::to_bits),
                    "case {case} u {u}"
                );
                let mut p3 = [0.0; 3];
                c.point_and_tangent(u, &mut p3[..dim], None);
                assert_eq!(
                    p1.map(f64::to_bits),
                    p3.map(f64::to_bits),
                    "case {case} u {u}"
                );
            }
        }
    }
}
