//! One type for every curve the library takes ([`Curve`]: a Bezier curve
//! or a NURBS curve) and the one thing connect needs of any curve
//! ([`CurveJet`]: its derivatives at a parameter, from a chosen side).

use nalgebra::DMatrix;

use crate::basis::KnotSide;
use crate::bezier::BezierCurve;
use crate::error::{Result, check_closed_range};
use crate::nurbs::NurbsCurve;

/// A curve of either kind. Bezier curves live on `[0, 1]`; NURBS curves on
/// their domain (`NurbsCurve::domain`).
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// A polynomial Bezier curve on `[0, 1]`.
    Bezier(BezierCurve),
    /// A NURBS curve (polynomial or rational, one or many spans).
    Nurbs(NurbsCurve),
}

impl From<BezierCurve> for Curve {
    fn from(c: BezierCurve) -> Self {
        Curve::Bezier(c)
    }
}

impl From<NurbsCurve> for Curve {
    fn from(c: NurbsCurve) -> Self {
        Curve::Nurbs(c)
    }
}

impl Curve {
    /// Dimension.
    pub fn dim(&self) -> usize {
        match self {
            Curve::Bezier(c) => c.dim(),
            Curve::Nurbs(c) => c.dim(),
        }
    }

    /// Degree.
    pub fn degree(&self) -> usize {
        match self {
            Curve::Bezier(c) => c.degree(),
            Curve::Nurbs(c) => c.degree(),
        }
    }

    /// The parameter domain: `[0, 1]` for a Bezier curve.
    pub fn domain(&self) -> (f64, f64) {
        match self {
            Curve::Bezier(_) => (0.0, 1.0),
            Curve::Nurbs(c) => c.domain(),
        }
    }

    /// Control points (Bezier) or poles (NURBS), Cartesian, row-major.
    pub fn points(&self) -> &[f64] {
        match self {
            Curve::Bezier(c) => c.points(),
            Curve::Nurbs(c) => c.points(),
        }
    }

    /// Number of control points or poles.
    pub fn point_count(&self) -> usize {
        match self {
            Curve::Bezier(c) => c.point_count(),
            Curve::Nurbs(c) => c.point_count(),
        }
    }

    /// True for a NURBS curve whose weights are not all equal.
    pub fn is_rational(&self) -> bool {
        matches!(self, Curve::Nurbs(c) if c.is_rational())
    }

    /// The curve as a NURBS curve (a Bezier: one span on `[0, 1]`).
    pub fn to_nurbs(&self) -> NurbsCurve {
        match self {
            Curve::Bezier(c) => NurbsCurve::from_bezier(c),
            Curve::Nurbs(c) => c.clone(),
        }
    }

    /// Arc length from `a` to `b` (signed) to the default accuracy
    /// (`BezierCurve::arc_length_default`, `NurbsCurve::arc_length_default`).
    pub fn arc_length_default(&self, a: f64, b: f64) -> Result<f64> {
        match self {
            Curve::Bezier(c) => c.arc_length_default(a, b),
            Curve::Nurbs(c) => c.arc_length_default(a, b),
        }
    }

    /// The absolute accuracy of [`arc_length_default`](Self::arc_length_default).
    pub fn default_length_accuracy(&self) -> f64 {
        match self {
            Curve::Bezier(c) => c.default_length_accuracy(),
            Curve::Nurbs(c) => c.default_length_accuracy(),
        }
    }

    /// The parameter at signed arc length `length` from `start`, in the
    /// domain (`BezierCurve::param_at_length`, `NurbsCurve::param_at_length`).
    pub fn param_at_length(&self, start: f64, length: f64, accuracy: f64) -> Result<f64> {
        match self {
            Curve::Bezier(c) => c.param_at_length(start, length, accuracy),
            Curve::Nurbs(c) => c.param_at_length(start, length, accuracy),
        }
    }

    /// The piece on `[a, b]`: a Bezier curve reparametrised to `[0, 1]`
    /// (`BezierCurve::segment`), a NURBS curve with its own parameters
    /// (`NurbsCurve::segment`, `first <= a < b <= last`).
    pub fn segment(&self, a: f64, b: f64) -> Result<Curve> {
        CurveRef::from(self).segment(a, b)
    }

    /// The curve traversed backwards on the same domain.
    pub fn reverse(&self) -> Curve {
        match self {
            Curve::Bezier(c) => Curve::Bezier(c.reverse()),
            Curve::Nurbs(c) => Curve::Nurbs(c.reverse()),
        }
    }

    /// The point at `u`.
    pub fn eval(&self, u: f64) -> Vec<f64> {
        CurveRef::from(self).eval(u)
    }

    /// The Bezier curve, when this is one.
    pub fn as_bezier(&self) -> Option<&BezierCurve> {
        match self {
            Curve::Bezier(c) => Some(c),
            Curve::Nurbs(_) => None,
        }
    }

    /// The NURBS curve, when this is one.
    pub fn as_nurbs(&self) -> Option<&NurbsCurve> {
        match self {
            Curve::Bezier(_) => None,
            Curve::Nurbs(c) => Some(c),
        }
    }

    /// Borrow as a [`CurveRef`].
    pub fn as_curve_ref(&self) -> CurveRef<'_> {
        CurveRef::from(self)
    }

    /// Value and derivatives `0..=max_order` at `u` (any order), from
    /// `side` at a knot of a NURBS curve; row-major.
    pub fn eval_derivatives_side(&self, u: f64, max_order: usize, side: KnotSide) -> Vec<f64> {
        match self {
            Curve::Bezier(c) => c.eval_derivatives(u, max_order),
            Curve::Nurbs(c) => c.eval_derivatives_side(u, max_order, side),
        }
    }
}

/// What [`connect`](fn@crate::connect) needs of a curve: its dimension, its
/// domain and its derivative jet at a parameter, from one side, with a
/// bound on the rounding error of each derivative.
pub trait CurveJet {
    /// Dimension.
    fn dim(&self) -> usize;
    /// `Ok` when `u` is finite and in the domain; the error names `name`.
    fn check_parameter(&self, name: &str, u: f64) -> Result<()>;
    /// Largest absolute coordinate of the control points or poles.
    fn coordinate_scale(&self) -> f64;
    /// Derivatives `0..=order` at `u` (rows of a `(order + 1) x dim`
    /// matrix; any order: above a polynomial's degree they vanish) and a
    /// bound on the absolute rounding error of each row.
    fn jet(&self, u: f64, order: usize, side: KnotSide) -> (DMatrix<f64>, Vec<f64>);
    /// [`jet`](Self::jet) written into caller storage: row `k` of the
    /// derivatives at `values[k * dim..(k + 1) * dim]` (`(order + 1) * dim`
    /// values), the bound of row `k` at `errors[k]` (`order + 1` values);
    /// the same numbers bit for bit. The default copies from `jet`; a
    /// Bezier curve computes it without allocating for small degrees, the
    /// hot path of [`connect`](fn@crate::connect).
    ///
    /// # Panics
    /// If the lengths are not as stated.
    fn jet_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        let (jet, bound) = self.jet(u, order, side);
        let dim = jet.ncols();
        assert_eq!(values.len(), (order + 1) * dim);
        for k in 0..=order {
            for c in 0..dim {
                values[k * dim + c] = jet[(k, c)];
            }
        }
        errors.copy_from_slice(&bound);
    }

    /// [`jet_into`](Self::jet_into)'s values, bit for bit, with bounds
    /// never below its bounds (to first order) that may cost less: the
    /// screen of the connect's curve-only path, which falls back to the
    /// full check whenever the screen does not pass. `scale` is
    /// [`coordinate_scale`](Self::coordinate_scale), passed in so that it is
    /// formed once. The default is `jet_into`; a Bezier curve bounds the
    /// de Casteljau triangle a priori instead of running its sizes.
    ///
    /// # Panics
    /// If the lengths are not as stated.
    fn jet_screen_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        scale: f64,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        let _ = scale;
        self.jet_into(u, order, side, values, errors);
    }
}

impl CurveJet for BezierCurve {
    fn dim(&self) -> usize {
        BezierCurve::dim(self)
    }

    fn check_parameter(&self, name: &str, u: f64) -> Result<()> {
        check_closed_range(name, u, 0.0, 1.0)
    }

    fn coordinate_scale(&self) -> f64 {
        BezierCurve::coordinate_scale(self)
    }

    /// Basis rows (closed form at the ends, A2.3 elsewhere) times the
    /// control points; the bound is `gamma * |D(t)| |P|` row by row,
    /// `gamma = 2 (n + k + 2) eps`.
    fn jet(&self, t: f64, order: usize, _side: KnotSide) -> (DMatrix<f64>, Vec<f64>) {
        crate::connect::derivatives_with_error(self, t, order)
    }

    fn jet_into(
        &self,
        t: f64,
        order: usize,
        _side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        crate::connect::derivatives_with_error_into(self, t, order, values, errors)
    }

    fn jet_screen_into(
        &self,
        t: f64,
        order: usize,
        _side: KnotSide,
        scale: f64,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        crate::connect::derivatives_with_screen_into(self, t, order, scale, values, errors)
    }
}

impl CurveJet for NurbsCurve {
    fn dim(&self) -> usize {
        NurbsCurve::dim(self)
    }

    fn check_parameter(&self, name: &str, u: f64) -> Result<()> {
        NurbsCurve::check_parameter(self, name, u)
    }

    fn coordinate_scale(&self) -> f64 {
        NurbsCurve::coordinate_scale(self)
    }

    /// [`jet_into`](CurveJet::jet_into) into a matrix and a vector.
    fn jet(&self, u: f64, order: usize, side: KnotSide) -> (DMatrix<f64>, Vec<f64>) {
        let dim = NurbsCurve::dim(self);
        let mut values = vec![0.0; (order + 1) * dim];
        let mut bound = vec![0.0; order + 1];
        self.jet_into(u, order, side, &mut values, &mut bound);
        (DMatrix::from_row_slice(order + 1, dim, &values), bound)
    }

    /// A clamped one-span polynomial curve (a Bezier curve as a NURBS
    /// handle): the Bezier curve's de Casteljau jet of its poles, scaled to
    /// the domain (`NurbsCurve::bezier_span_jet_into`; on `[0, 1]` the
    /// jet of the Bezier curve itself). A polynomial curve of several
    /// spans: the same from its span's poles in the kept decomposition,
    /// with their rounding in the bound (`NurbsCurve::spans_jet_into`). A
    /// rational curve of dimension at most 3: the homogeneous jet of its
    /// span's rows, then the quotient rule, its bound carried through
    /// (`NurbsCurve::rational_spans_jet_into`). Any other curve: A2.3
    /// (the rows and bounds of `NurbsCurve::eval_derivatives_into`).
    fn jet_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        if self.bezier_span_jet_into(u, order, values, errors)
            || self.spans_jet_into(u, order, side, values, errors)
            || self.rational_spans_jet_into(u, order, side, values, errors)
        {
            return;
        }
        // The A2.3 rows and bounds (every value and bound written there:
        // the rows are zeroed before they are summed).
        self.eval_derivatives_into(u, order, side, values, Some(errors));
    }

    /// A polynomial curve (dimension 2 to 4, degree 1 to 15): the same
    /// de Casteljau values as [`jet_into`](CurveJet::jet_into), the
    /// triangle's bound a priori (`NurbsCurve::span_jet_screen_into`).
    /// Any other curve: [`jet_into`](CurveJet::jet_into).
    fn jet_screen_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        scale: f64,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        if !self.span_jet_screen_into(u, order, side, scale, values, errors) {
            self.jet_into(u, order, side, values, errors);
        }
    }
}

impl CurveJet for Curve {
    fn dim(&self) -> usize {
        Curve::dim(self)
    }

    fn check_parameter(&self, name: &str, u: f64) -> Result<()> {
        match self {
            Curve::Bezier(c) => CurveJet::check_parameter(c, name, u),
            Curve::Nurbs(c) => NurbsCurve::check_parameter(c, name, u),
        }
    }

    fn coordinate_scale(&self) -> f64 {
        match self {
            Curve::Bezier(c) => c.coordinate_scale(),
            Curve::Nurbs(c) => c.coordinate_scale(),
        }
    }

    fn jet(&self, u: f64, order: usize, side: KnotSide) -> (DMatrix<f64>, Vec<f64>) {
        match self {
            Curve::Bezier(c) => c.jet(u, order, side),
            Curve::Nurbs(c) => c.jet(u, order, side),
        }
    }

    fn jet_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        match self {
            Curve::Bezier(c) => c.jet_into(u, order, side, values, errors),
            Curve::Nurbs(c) => c.jet_into(u, order, side, values, errors),
        }
    }

    fn jet_screen_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        scale: f64,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        match self {
            Curve::Bezier(c) => c.jet_screen_into(u, order, side, scale, values, errors),
            Curve::Nurbs(c) => c.jet_screen_into(u, order, side, scale, values, errors),
        }
    }
}

/// A borrowed curve of either kind: what the operations that take "any
/// curve" accept (`&BezierCurve`, `&NurbsCurve` and `&Curve` convert into
/// it with `into()`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CurveRef<'a> {
    /// A Bezier curve on `[0, 1]`.
    Bezier(&'a BezierCurve),
    /// A NURBS curve on its domain.
    Nurbs(&'a NurbsCurve),
}

impl<'a> From<&'a BezierCurve> for CurveRef<'a> {
    fn from(c: &'a BezierCurve) -> Self {
        CurveRef::Bezier(c)
    }
}

impl<'a> From<&'a NurbsCurve> for CurveRef<'a> {
    fn from(c: &'a NurbsCurve) -> Self {
        CurveRef::Nurbs(c)
    }
}

impl<'a> From<&'a Curve> for CurveRef<'a> {
    fn from(c: &'a Curve) -> Self {
        match c {
            Curve::Bezier(b) => CurveRef::Bezier(b),
            Curve::Nurbs(n) => CurveRef::Nurbs(n),
        }
    }
}

impl CurveRef<'_> {
    /// Dimension.
    pub fn dim(&self) -> usize {
        match self {
            CurveRef::Bezier(c) => c.dim(),
            CurveRef::Nurbs(c) => c.dim(),
        }
    }

    /// Degree.
    pub fn degree(&self) -> usize {
        match self {
            CurveRef::Bezier(c) => c.degree(),
            CurveRef::Nurbs(c) => c.degree(),
        }
    }

    /// The parameter domain (`[0, 1]` for a Bezier curve).
    pub fn domain(&self) -> (f64, f64) {
        match self {
            CurveRef::Bezier(_) => (0.0, 1.0),
            CurveRef::Nurbs(c) => c.domain(),
        }
    }

    /// Largest absolute coordinate of the control points or poles.
    pub fn coordinate_scale(&self) -> f64 {
        match self {
            CurveRef::Bezier(c) => c.coordinate_scale(),
            CurveRef::Nurbs(c) => c.coordinate_scale(),
        }
    }

    /// The point at `u` into `out` (`dim` values).
    pub fn eval_into(&self, u: f64, out: &mut [f64]) {
        match self {
            CurveRef::Bezier(c) => c.eval_into(u, out),
            CurveRef::Nurbs(c) => c.point_and_tangent(u, out, None),
        }
    }

    /// The point at `u`.
    pub fn eval(&self, u: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(u, &mut out);
        out
    }

    /// The point and the first derivative at `u` (`dim` values each; a
    /// NURBS curve from the right at an interior knot, so at the domain's
    /// ends from inside): de Casteljau's or de Boor's scheme without a
    /// rounding bound and, for small sizes, without a heap allocation.
    pub(crate) fn point_and_tangent_into(&self, u: f64, point: &mut [f64], tangent: &mut [f64]) {
        match self {
            CurveRef::Bezier(c) => crate::bezier::point_and_tangent_rows(
                c.points(),
                c.dim(),
                c.degree(),
                u,
                point,
                tangent,
            ),
            CurveRef::Nurbs(c) => c.point_and_tangent(u, point, Some(tangent)),
        }
    }

    /// Arc length from `a` to `b` (signed) to the absolute `accuracy`.
    pub fn arc_length(&self, a: f64, b: f64, accuracy: f64) -> Result<f64> {
        match self {
            CurveRef::Bezier(c) => c.arc_length(a, b, accuracy),
            CurveRef::Nurbs(c) => c.arc_length(a, b, accuracy),
        }
    }

    /// The default absolute accuracy of arc lengths of this curve.
    pub fn default_length_accuracy(&self) -> f64 {
        match self {
            CurveRef::Bezier(c) => c.default_length_accuracy(),
            CurveRef::Nurbs(c) => c.default_length_accuracy(),
        }
    }

    /// [`default_length_accuracy`](Self::default_length_accuracy), or
    /// `NonFiniteScalar` naming the control polygon length of `curve` when
    /// that overflows `f64`.
    pub(crate) fn checked_default_length_accuracy(&self, curve: &str) -> Result<f64> {
        match self {
            CurveRef::Bezier(c) => c.checked_default_length_accuracy(curve),
            CurveRef::Nurbs(c) => c.checked_default_length_accuracy(curve),
        }
    }

    /// The parameter at signed arc length `length` from `start`.
    pub fn param_at_length(&self, start: f64, length: f64, accuracy: f64) -> Result<f64> {
        match self {
            CurveRef::Bezier(c) => c.param_at_length(start, length, accuracy),
            CurveRef::Nurbs(c) => c.param_at_length(start, length, accuracy),
        }
    }

    /// The piece on `[a, b]` (see [`Curve::segment`]).
    pub fn segment(&self, a: f64, b: f64) -> Result<Curve> {
        Ok(match self {
            CurveRef::Bezier(c) => Curve::Bezier(c.segment(a, b)?),
            CurveRef::Nurbs(c) => Curve::Nurbs(c.segment(a, b)?),
        })
    }

    /// An owned copy.
    pub fn to_curve(&self) -> Curve {
        match self {
            CurveRef::Bezier(c) => Curve::Bezier((*c).clone()),
            CurveRef::Nurbs(c) => Curve::Nurbs((*c).clone()),
        }
    }
}

impl CurveJet for CurveRef<'_> {
    fn dim(&self) -> usize {
        CurveRef::dim(self)
    }

    fn check_parameter(&self, name: &str, u: f64) -> Result<()> {
        match self {
            CurveRef::Bezier(c) => CurveJet::check_parameter(*c, name, u),
            CurveRef::Nurbs(c) => NurbsCurve::check_parameter(c, name, u),
        }
    }

    fn coordinate_scale(&self) -> f64 {
        CurveRef::coordinate_scale(self)
    }

    fn jet(&self, u: f64, order: usize, side: KnotSide) -> (DMatrix<f64>, Vec<f64>) {
        match self {
            CurveRef::Bezier(c) => c.jet(u, order, side),
            CurveRef::Nurbs(c) => c.jet(u, order, side),
        }
    }

    fn jet_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        match self {
            CurveRef::Bezier(c) => c.jet_into(u, order, side, values, errors),
            CurveRef::Nurbs(c) => c.jet_into(u, order, side, values, errors),
        }
    }

    fn jet_screen_into(
        &self,
        u: f64,
        order: usize,
        side: KnotSide,
        scale: f64,
        values: &mut [f64],
        errors: &mut [f64],
    ) {
        match self {
            CurveRef::Bezier(c) => c.jet_screen_into(u, order, side, scale, values, errors),
            CurveRef::Nurbs(c) => c.jet_screen_into(u, order, side, scale, values, errors),
        }
    }
}

/// Curves that can be borrowed as a [`CurveRef`]: what the operations on
/// slices of curves ([`fillet_chain`](crate::fillet_chain)) take.
pub trait AsCurveRef {
    /// Borrow as a [`CurveRef`].
    fn as_curve_ref(&self) -> CurveRef<'_>;
}

impl AsCurveRef for BezierCurve {
    fn as_curve_ref(&self) -> CurveRef<'_> {
        CurveRef::Bezier(self)
    }
}

impl AsCurveRef for NurbsCurve {
    fn as_curve_ref(&self) -> CurveRef<'_> {
        CurveRef::Nurbs(self)
    }
}

impl AsCurveRef for Curve {
    fn as_curve_ref(&self) -> CurveRef<'_> {
        CurveRef::from(self)
    }
}
