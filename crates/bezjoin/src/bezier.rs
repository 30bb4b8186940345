//! Bezier curves of any degree in any dimension, and their exact operations.
//!
//! `P(t) = sum_i B_i^n(t) P_i` (docs/mathematics.md#bezier-basics). Control points are
//! stored row-major (`point i, coordinate c` at `[i * dim + c]`), the layout
//! of the C ABI. Every operation here is exact in the sense that it
//! introduces no approximation beyond floating-point rounding: evaluation,
//! derivatives (A2.3 basis), degree elevation, subdivision, segments with
//! extrapolation (blossoming), reversal.

use nalgebra::DMatrix;

use crate::basis::bezier_basis_derivatives;
use crate::error::{BezjoinError, Result, check_closed_range, check_finite, check_finite_scalar};

/// The highest degree a curve may have: 4096.
///
/// Far above anything numerically meaningful (double precision loses the
/// shape of a Bezier curve long before; the solvers stop at degree 31) but low
/// enough that no call on a valid curve can allocate gigabytes or run for
/// minutes inside a host program: elevation to `MAX_DEGREE` costs at most
/// `MAX_DEGREE^2 * dim` operations.
pub const MAX_DEGREE: usize = 4096;

/// `InvalidArgument` naming `name` when `degree > MAX_DEGREE`.
pub(crate) fn check_degree_supported(name: &str, degree: usize) -> Result<()> {
    if degree > MAX_DEGREE {
        return Err(BezjoinError::invalid(
            name,
            format!("{degree} is above the supported maximum degree {MAX_DEGREE}"),
        ));
    }
    Ok(())
}

/// `InvalidArgument` naming `dim` when `dim == 0`.
fn check_dim(dim: usize) -> Result<()> {
    if dim == 0 {
        return Err(BezjoinError::invalid("dim", "must be at least 1"));
    }
    Ok(())
}

/// A polynomial Bezier curve of degree `n >= 0` in dimension `dim >= 1`
/// (`n <= MAX_DEGREE`).
///
/// Immutable once built; operations return new curves.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierCurve {
    degree: usize,
    dim: usize,
    points: Vec<f64>,
}

impl BezierCurve {
    /// A curve from `(degree + 1) * dim` row-major coordinates.
    ///
    /// Errors: those of [`check_shape`](Self::check_shape) (`dim == 0`,
    /// the sizes, `degree` above [`MAX_DEGREE`]), then NaN/infinity
    /// (NonFinite, naming the first bad index).
    pub fn new(dim: usize, degree: usize, points: Vec<f64>) -> Result<Self> {
        Self::check_shape(dim, degree, points.len())?;
        check_finite("points", &points)?;
        Ok(Self {
            degree,
            dim,
            points,
        })
    }

    /// The size checks of [`new`](Self::new) from the numbers alone, for
    /// callers that must refuse a bad size before reading the coordinates
    /// (the C ABI): `dim >= 1` (InvalidArgument naming `dim`),
    /// `(degree + 1) * dim` representable (InvalidArgument naming
    /// `degree, dim`), `degree` at most [`MAX_DEGREE`] (InvalidArgument
    /// naming `degree`) and `len` equal to `(degree + 1) * dim`
    /// (LengthMismatch naming `points`), in this order. Returns
    /// `(degree + 1) * dim`.
    pub fn check_shape(dim: usize, degree: usize, len: usize) -> Result<usize> {
        check_dim(dim)?;
        let expected = degree
            .checked_add(1)
            .and_then(|n| n.checked_mul(dim))
            .ok_or_else(|| {
                BezjoinError::invalid(
                    "degree, dim",
                    format!("(degree + 1) * dim = ({degree} + 1) * {dim} overflows"),
                )
            })?;
        check_degree_supported("degree", degree)?;
        if len != expected {
            return Err(BezjoinError::LengthMismatch {
                name: "points".into(),
                expected,
                actual: len,
            });
        }
        Ok(expected)
    }

    /// A curve from a list of control points (each a slice of `dim` coordinates).
    pub fn from_rows<R: AsRef<[f64]>>(rows: &[R]) -> Result<Self> {
        if rows.is_empty() {
            return Err(BezjoinError::invalid(
                "points",
                "at least one control point is needed",
            ));
        }
        let dim = rows[0].as_ref().len();
        let mut points = Vec::with_capacity(rows.len() * dim);
        for (i, r) in rows.iter().enumerate() {
            let r = r.as_ref();
            if r.len() != dim {
                return Err(BezjoinError::DimensionMismatch {
                    name: format!("points[{i}]"),
                    expected: dim,
                    actual: r.len(),
                });
            }
            points.extend_from_slice(r);
        }
        Self::new(dim, rows.len() - 1, points)
    }

    /// A curve from an `(n + 1) x dim` matrix of control points (one per row).
    pub(crate) fn from_matrix(m: &DMatrix<f64>) -> Result<Self> {
        if m.nrows() == 0 {
            return Err(BezjoinError::invalid(
                "points",
                "at least one control point is needed",
            ));
        }
        // Row-major points from the column-major storage.
        let (rows, cols) = (m.nrows(), m.ncols());
        let data = m.as_slice();
        let mut points = Vec::with_capacity(rows * cols);
        for i in 0..rows {
            for c in 0..cols {
                points.push(data[c * rows + i]);
            }
        }
        Self::new(m.ncols(), m.nrows() - 1, points)
    }

    /// Internal constructor for results of exact operations on valid curves.
    pub(crate) fn from_parts(dim: usize, degree: usize, points: Vec<f64>) -> Self {
        debug_assert_eq!(points.len(), (degree + 1) * dim);
        Self {
            degree,
            dim,
            points,
        }
    }

    /// Degree `n`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Dimension of the space.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Row-major control points, `(n + 1) * dim` values.
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// Control point `i`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dim..(i + 1) * self.dim]
    }

    /// Number of control points, `n + 1`.
    pub fn point_count(&self) -> usize {
        self.degree + 1
    }

    /// Control points as an `(n + 1) x dim` matrix.
    pub(crate) fn control_matrix(&self) -> DMatrix<f64> {
        DMatrix::from_row_slice(self.degree + 1, self.dim, &self.points)
    }

    /// Largest absolute coordinate of any control point (a size scale for
    /// relative tolerances; at least the smallest positive normal number).
    pub fn coordinate_scale(&self) -> f64 {
        largest_magnitude(&self.points).max(f64::MIN_POSITIVE)
    }

    /// Length of the control polygon.
    pub fn polygon_length(&self) -> f64 {
        (0..self.degree)
            .map(|i| distance(self.point(i), self.point(i + 1)))
            .sum()
    }

    /// `P(t)` written into `out` (length `dim`), without allocating up to
    /// degree 512.
    ///
    /// Uses the Bernstein-Horner scheme on the shorter side of `t = 1/2`
    /// (`O(n d)`); above degree 512, where its binomials and powers leave
    /// the `f64` range, de Casteljau's algorithm. Any finite `t` is accepted.
    ///
    /// # Panics
    /// If `out.len() != dim`.
    pub fn eval_into(&self, t: f64, out: &mut [f64]) {
        assert_eq!(out.len(), self.dim);
        bernstein_horner_any(&self.points, self.degree, self.dim, t, 1.0, out);
    }

    /// `P(t_j)` for every parameter of `ts`, written parameter-major into
    /// `out` (`ts.len() * dim` values): the bits of [`Self::eval_into`] at
    /// each parameter. In dimensions 2 and 3 up to degree 8 the parameters
    /// go four at a time through one batch kernel (the same operations per
    /// parameter, packed), otherwise one [`Self::eval_into`] each.
    ///
    /// # Panics
    /// If `out.len() != ts.len() * dim`.
    pub fn eval_many_into(&self, ts: &[f64], out: &mut [f64]) {
        assert_eq!(out.len(), ts.len() * self.dim);
        let done = match self.dim {
            2 => eval_many_by_degree::<2>(&self.points, self.degree, ts, out),
            3 => eval_many_by_degree::<3>(&self.points, self.degree, ts, out),
            _ => false,
        };
        if !done {
            for (&t, value) in ts.iter().zip(out.chunks_exact_mut(self.dim)) {
                self.eval_into(t, value);
            }
        }
    }

    /// `P(t)`.
    pub fn eval(&self, t: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim];
        self.eval_into(t, &mut out);
        out
    }

    /// `P(t)` by de Casteljau's algorithm (slower, the most stable; the
    /// reference that the fast path is tested against).
    pub fn eval_de_casteljau(&self, t: f64) -> Vec<f64> {
        let mut work = Vec::with_capacity(self.points.len());
        blossom(
            &self.points,
            self.dim,
            std::iter::repeat_n(t, self.degree),
            &mut work,
        );
        // The value is the work buffer's first point: one allocation.
        work.truncate(self.dim);
        work
    }

    /// Value and derivatives `0..=max_order` at `t`, written row-major into
    /// `out` (`(max_order + 1) * dim` values; row `k` is `P^(k)(t)`).
    /// Orders above the degree are zero.
    ///
    /// Fast path, `O(n^2 d)` and allocation-free for `(n + 1) d <= 96`:
    /// `P^(k)(t) = n!/(n-k)! sum_i (Delta^k P)_i B_i^(n-k)(t)` with each sum by
    /// the Bernstein-Horner scheme. [`Self::eval_derivatives_basis`] computes
    /// the same from the A2.3 basis matrix `D(t)` (the form the solvers use);
    /// the tests hold the two together.
    ///
    /// # Panics
    /// If `out.len() != (max_order + 1) * dim`.
    pub fn eval_derivatives_into(&self, t: f64, max_order: usize, out: &mut [f64]) {
        let d = self.dim;
        let n = self.degree;
        assert_eq!(out.len(), (max_order + 1) * d);
        let top = max_order.min(n);
        let done = match d {
            2 => derivatives_by_degree::<2>(&self.points, n, t, top, out),
            3 => derivatives_by_degree::<3>(&self.points, n, t, top, out),
            _ => false,
        };
        if done {
            out[(top + 1) * d..].fill(0.0);
            return;
        }
        let len = self.points.len();
        let mut stack = [0.0f64; 96];
        let mut heap = Vec::new();
        let diff: &mut [f64] = if len <= stack.len() {
            stack[..len].copy_from_slice(&self.points);
            &mut stack[..len]
        } else {
            heap.extend_from_slice(&self.points);
            &mut heap
        };
        let mut factor = 1.0;
        for k in 0..=top {
            let m = n - k;
            bernstein_horner_any(
                &diff[..(m + 1) * d],
                m,
                d,
                t,
                factor,
                &mut out[k * d..(k + 1) * d],
            );
            if k < top {
                for i in 0..m * d {
                    diff[i] = diff[i + d] - diff[i];
                }
                factor *= m as f64;
            }
        }
        out[(top + 1) * d..].fill(0.0);
    }

    /// Value and derivatives `0..=max_order` at `t` from the A2.3 basis matrix
    /// `D(t)` times the control points (docs/mathematics.md#bezier-basics); row-major
    /// into `out` like [`Self::eval_derivatives_into`].
    ///
    /// # Panics
    /// If `out.len() != (max_order + 1) * dim`.
    pub fn eval_derivatives_basis(&self, t: f64, max_order: usize, out: &mut [f64]) {
        let d = self.dim;
        assert_eq!(out.len(), (max_order + 1) * d);
        let basis = bezier_basis_derivatives(self.degree, t, max_order.min(self.degree));
        out.fill(0.0);
        for k in 0..=max_order.min(self.degree) {
            let row = &mut out[k * d..(k + 1) * d];
            for i in 0..=self.degree {
                let b = basis[(k, i)];
                if b != 0.0 {
                    let p = &self.points[i * d..(i + 1) * d];
                    for c in 0..d {
                        row[c] += b * p[c];
                    }
                }
            }
        }
    }

    /// Value and derivatives `0..=max_order` at `t`, row-major
    /// (`(max_order + 1) * dim` values, row `k` is `P^(k)(t)`).
    pub fn eval_derivatives(&self, t: f64, max_order: usize) -> Vec<f64> {
        let mut out = vec![0.0; (max_order + 1) * self.dim];
        self.eval_derivatives_into(t, max_order, &mut out);
        out
    }

    /// The k-th derivative `P^(k)(t)`.
    pub fn derivative_at(&self, t: f64, order: usize) -> Vec<f64> {
        let mut all = self.eval_derivatives(t, order);
        all.drain(..order * self.dim);
        all
    }

    /// The hodograph `P'` as a Bezier curve of degree `n - 1`
    /// (`n (P_(i+1) - P_i)`); a degree-0 curve gives the zero curve of degree 0.
    pub fn hodograph(&self) -> BezierCurve {
        let n = self.degree;
        let d = self.dim;
        if n == 0 {
            return BezierCurve::from_parts(d, 0, vec![0.0; d]);
        }
        let mut pts = Vec::with_capacity(n * d);
        for i in 0..n {
            for c in 0..d {
                pts.push(n as f64 * (self.points[(i + 1) * d + c] - self.points[i * d + c]));
            }
        }
        BezierCurve::from_parts(d, n - 1, pts)
    }

    /// The same curve written with degree `new_degree >= n` (exact degree
    /// elevation: `Q_j = sum_i C(n,i) C(m-n,j-i) / C(m,j) P_i`).
    ///
    /// The weights are evaluated without binomial coefficients (which leave
    /// the `f64` range above degree ~1030), so any `m` works; measured
    /// relative error below `3e-14` of the coordinate scale up to `m = 1200`.
    ///
    /// Errors: `new_degree < n`, or `(new_degree + 1) * dim` coordinates that
    /// cannot be allocated (InvalidArgument).
    pub fn elevate_degree(&self, new_degree: usize) -> Result<BezierCurve> {
        let n = self.degree;
        let m = new_degree;
        if m < n {
            return Err(BezjoinError::invalid(
                "new_degree",
                format!("{m} is below the curve's degree {n}; degree reduction is not exact"),
            ));
        }
        if m == n {
            return Ok(self.clone());
        }
        check_degree_supported("new_degree", m)?;
        let d = self.dim;
        let r = m - n;
        let len = m
            .checked_add(1)
            .and_then(|k| k.checked_mul(d))
            .ok_or_else(|| BezjoinError::invalid("new_degree", format!("{m} is too large")))?;
        let mut pts = Vec::new();
        pts.try_reserve_exact(len).map_err(|_| {
            BezjoinError::invalid(
                "new_degree",
                format!("{m} is too large ({len} coordinates cannot be allocated)"),
            )
        })?;
        pts.resize(len, 0.0);
        let mut weights = vec![0.0f64; n + 1];
        for j in 0..=m {
            let lo = j.saturating_sub(r);
            let hi = j.min(n);
            // The weights C(n,i) C(r,j-i) / C(m,j), i = lo..=hi, are the
            // hypergeometric distribution: built from its mode outwards by
            // the ratio of consecutive terms (never above 1, so nothing
            // overflows even where the binomials exceed f64), then divided
            // by their sum, which is exactly 1 in exact arithmetic.
            let ratio = |i: usize| -> f64 {
                // w(i + 1) / w(i)
                ((n - i) as f64 * (j - i) as f64) / ((i + 1) as f64 * (r + i + 1 - j) as f64)
            };
            let mode =
                (((j + 1) as f64 * (n + 1) as f64 / (m + 2) as f64).floor() as usize).clamp(lo, hi);
            weights[mode] = 1.0;
            for i in mode + 1..=hi {
                weights[i] = weights[i - 1] * ratio(i - 1);
            }
            for i in (lo..mode).rev() {
                weights[i] = weights[i + 1] / ratio(i);
            }
            let total: f64 = weights[lo..=hi].iter().sum();
            for (i, weight) in weights.iter().enumerate().take(hi + 1).skip(lo) {
                let w = weight / total;
                for c in 0..d {
                    pts[j * d + c] += w * self.points[i * d + c];
                }
            }
        }
        Ok(BezierCurve::from_parts(d, m, pts))
    }

    /// Subdivision at `t in [0, 1]` by de Casteljau: the pieces on `[0, t]`
    /// and `[t, 1]`, each reparametrised to `[0, 1]`.
    pub fn split_at(&self, t: f64) -> Result<(BezierCurve, BezierCurve)> {
        check_closed_range("t", t, 0.0, 1.0)?;
        Ok(self.split_unchecked(t))
    }

    pub(crate) fn split_unchecked(&self, t: f64) -> (BezierCurve, BezierCurve) {
        let n = self.degree;
        let d = self.dim;
        // The right half is the triangle's working row itself: step
        // `level` changes points `0..=n - level` only, so point `n - level`
        // is final after it (the same values as a separate copy).
        let mut right = self.points.clone();
        let mut left = Vec::with_capacity((n + 1) * d);
        left.extend_from_slice(&right[0..d]);
        for level in 1..=n {
            de_casteljau_step(&mut right, n + 2 - level, d, t);
            left.extend_from_slice(&right[0..d]);
        }
        (
            BezierCurve::from_parts(d, n, left),
            BezierCurve::from_parts(d, n, right),
        )
    }

    /// The curve `s -> P(a + (b - a) s)` for any finite `a`, `b`
    /// (extrapolation outside `[0, 1]` and `a > b` included).
    ///
    /// Control point `i` is the blossom `P[a^(n-i), b^i]`, evaluated by de
    /// Casteljau steps with `b` then `a`. `a == b` gives the constant curve.
    ///
    /// Errors: `a` or `b` not finite (NonFiniteScalar); a segment so far
    /// outside `[0, 1]` that its control points overflow (InvalidArgument
    /// naming the larger of `a`, `b`).
    pub fn segment(&self, a: f64, b: f64) -> Result<BezierCurve> {
        check_finite_scalar("a", a)?;
        check_finite_scalar("b", b)?;
        let seg = self.segment_unchecked(a, b);
        if seg.points.iter().any(|v| !v.is_finite()) {
            let (name, value) = if a.abs() >= b.abs() {
                ("a", a)
            } else {
                ("b", b)
            };
            // The number as it reads, not 301 digits, and no Rust type name
            // (user testing, session 44).
            return Err(BezjoinError::invalid(
                format!("{name} = {}", crate::error::Compact(value)),
                "so far outside [0, 1] that the segment's control points overflow the double \
                 range",
            ));
        }
        Ok(seg)
    }

    pub(crate) fn segment_unchecked(&self, a: f64, b: f64) -> BezierCurve {
        let n = self.degree;
        let d = self.dim;
        let mut out = vec![0.0; (n + 1) * d];
        // levels_b[i] holds the points after i de Casteljau steps at b
        // (n + 1 - i points), i.e. blossom values P[b^i, ...].
        let mut level = self.points.clone();
        let mut work = Vec::with_capacity((n + 1) * d);
        for i in 0..=n {
            // n - i steps at a on the current b-level (n + 1 - i points).
            let count = n + 1 - i;
            let point = blossom(
                &level[..count * d],
                d,
                std::iter::repeat_n(a, count - 1),
                &mut work,
            );
            out[i * d..(i + 1) * d].copy_from_slice(point);
            // One more step at b.
            if i < n {
                de_casteljau_step(&mut level, count, d, b);
            }
        }
        BezierCurve::from_parts(d, n, out)
    }

    /// The same curve traversed backwards: `s -> P(1 - s)`.
    pub fn reverse(&self) -> BezierCurve {
        let d = self.dim;
        let mut pts = Vec::with_capacity(self.points.len());
        for i in (0..=self.degree).rev() {
            pts.extend_from_slice(self.point(i));
        }
        BezierCurve::from_parts(d, self.degree, pts)
    }

    /// Largest distance between this curve and `other` at `samples + 1`
    /// evenly spaced parameters (a measuring tool for reports and tests).
    pub fn max_distance_sampled(&self, other: &BezierCurve, samples: usize) -> f64 {
        let samples = samples.max(1);
        let mut a = vec![0.0; self.dim];
        let mut b = vec![0.0; other.dim];
        (0..=samples)
            .map(|s| {
                let t = s as f64 / samples as f64;
                self.eval_into(t, &mut a);
                other.eval_into(t, &mut b);
                distance(&a, &b)
            })
            .fold(0.0, f64::max)
    }
}

/// Control-point coordinates up to which [`point_and_tangent_rows`] works
/// on the stack.
const DE_CASTELJAU_STACK: usize = 64;

/// `P(t)` into `point` and `P'(t)` into `tangent` for the Bezier control
/// points `points` (`n + 1` rows of `d`; also the homogeneous poles of a
/// rational span, `d = dim + 1`), `t` in `[0, 1]`, by de
/// Casteljau's scheme: the levels `(1 - t) b_i + t b_(i+1)` down to two
/// points `b_0`, `b_1` (the control points of the two halves' common
/// edge), then `P(t) = (1 - t) b_0 + t b_1` and `P'(t) = n (b_1 - b_0)`.
/// Convex combinations only (the most stable evaluation, exact at `t = 0`
/// and `t = 1`); on the stack up to [`DE_CASTELJAU_STACK`] coordinates.
#[inline]
pub(crate) fn point_and_tangent_rows(
    points: &[f64],
    d: usize,
    n: usize,
    t: f64,
    point: &mut [f64],
    tangent: &mut [f64],
) {
    // The plane and space up to degree 7: the dimension and the buffer's
    // size known at compile time (the same operations as below).
    match (d, n) {
        // Cubics with the degree as a constant as well (loops unrolled).
        (2, 3) => return point_and_tangent_fixed::<2, 4>(points, 3, t, point, tangent),
        (3, 3) => return point_and_tangent_fixed::<3, 4>(points, 3, t, point, tangent),
        (2, 1..=3) => return point_and_tangent_fixed::<2, 4>(points, n, t, point, tangent),
        (2, 4..=7) => return point_and_tangent_fixed::<2, 8>(points, n, t, point, tangent),
        (3, 1..=3) => return point_and_tangent_fixed::<3, 4>(points, n, t, point, tangent),
        (3, 4..=7) => return point_and_tangent_fixed::<3, 8>(points, n, t, point, tangent),
        // Homogeneous space cubics (rational spans in 3D).
        (4, 3) => return point_and_tangent_fixed::<4, 4>(points, 3, t, point, tangent),
        _ => {}
    }
    if n == 0 {
        point.copy_from_slice(&points[..d]);
        tangent.fill(0.0);
        return;
    }
    let mut stack = [0.0f64; DE_CASTELJAU_STACK];
    let mut heap = Vec::new();
    let work: &mut [f64] = if points.len() <= DE_CASTELJAU_STACK {
        &mut stack[..points.len()]
    } else {
        heap.extend_from_slice(points);
        &mut heap
    };
    if points.len() <= DE_CASTELJAU_STACK {
        work.copy_from_slice(points);
    }
    let s = 1.0 - t;
    for level in 1..n {
        for i in 0..(n - level + 1) * d {
            work[i] = s * work[i] + t * work[i + d];
        }
    }
    let nf = n as f64;
    for c in 0..d {
        let (b0, b1) = (work[c], work[d + c]);
        point[c] = s * b0 + t * b1;
        tangent[c] = nf * (b1 - b0);
    }
}

/// [`point_and_tangent_rows`] for `D` coordinates and degree `1 <= n < CAP`.
#[inline(always)]
pub(crate) fn point_and_tangent_fixed<const D: usize, const CAP: usize>(
    points: &[f64],
    n: usize,
    t: f64,
    point: &mut [f64],
    tangent: &mut [f64],
) {
    let n = n.min(CAP - 1);
    let mut w = [[0.0f64; D]; CAP];
    for (row, p) in w.iter_mut().zip(points.chunks_exact(D)).take(n + 1) {
        row.copy_from_slice(p);
    }
    let s = 1.0 - t;
    for level in 1..n {
        for i in 0..=n - level {
            let next = w[i + 1];
            for (x, y) in w[i].iter_mut().zip(next) {
                *x = s * *x + t * y;
            }
        }
    }
    let nf = n as f64;
    let (point, tangent) = (&mut point[..D], &mut tangent[..D]);
    for c in 0..D {
        let (b0, b1) = (w[0][c], w[1][c]);
        point[c] = s * b0 + t * b1;
        tangent[c] = nf * (b1 - b0);
    }
}

/// One de Casteljau step at `t` on the first `count` points of `points`
/// (row-major, `dim` values each), in place: point `i < count - 1` becomes
/// `(1 - t) P_i + t P_{i+1}`. Every de Casteljau evaluation, subdivision and
/// blossom of the crate is made of this step.
pub(crate) fn de_casteljau_step(points: &mut [f64], count: usize, dim: usize, t: f64) {
    for i in 0..count.saturating_sub(1) {
        for c in 0..dim {
            points[i * dim + c] = (1.0 - t) * points[i * dim + c] + t * points[(i + 1) * dim + c];
        }
    }
}

/// The blossom (polar form) `P[t_1, ..., t_n]` of the degree-`n` Bezier
/// control points `points` (`n + 1` rows of `dim` values; `args` yields the
/// `n` arguments): de Casteljau with argument `t_k` at level `k`. With every
/// argument `t` it is `P(t)`. `work` is scratch space; the result is its
/// first `dim` values.
pub(crate) fn blossom<'w>(
    points: &[f64],
    dim: usize,
    args: impl IntoIterator<Item = f64>,
    work: &'w mut Vec<f64>,
) -> &'w [f64] {
    work.clear();
    work.extend_from_slice(points);
    let count = points.len() / dim;
    for (level, t) in args.into_iter().enumerate() {
        de_casteljau_step(work, count - level, dim, t);
    }
    &work[..dim]
}

/// Highest degree evaluated by the Bernstein-Horner scheme: `C(n, n/2)` and
/// `2^-n` stay well inside the `f64` range.
const HORNER_MAX_DEGREE: usize = 512;

/// Degrees whose binomials [`bernstein_horner`] reads from [`BINOMIALS`].
const BINOMIAL_TABLE_DEGREE: usize = 32;

/// Rows `0..=BINOMIAL_TABLE_DEGREE` of Pascal's triangle, row `n` starting
/// at `n (n + 1) / 2`: exact (the largest entry, `C(32, 16)`, is far below
/// `2^53`).
static BINOMIALS: [f64; 561] = binomial_rows();

const fn binomial_rows() -> [f64; 561] {
    let mut table = [0.0; 561];
    let mut n = 0;
    while n <= BINOMIAL_TABLE_DEGREE {
        let row = n * (n + 1) / 2;
        table[row] = 1.0;
        table[row + n] = 1.0;
        let mut k = 1;
        while k < n {
            // row n - 1 starts at row - n
            table[row + k] = table[row - n + k - 1] + table[row - n + k];
            k += 1;
        }
        n += 1;
    }
    table
}

/// `scale * sum_i B_i^n(t) P_i` for `n + 1` row-major points of dimension
/// `dim`, written into `out`, by the Bernstein-Horner scheme:
/// `P(t) = s^n sum_i C(n,i) (t/s)^i P_i = t^n sum_i C(n,i) (s/t)^(n-i) P_i`,
/// `s = 1 - t`, with Horner in whichever ratio is at most 1 on `[0, 1]`.
///
/// Above [`HORNER_MAX_DEGREE`] the binomials and powers would leave the
/// `f64` range, so de Casteljau's algorithm (allocating) is used instead.
#[inline]
pub(crate) fn bernstein_horner(
    points: &[f64],
    n: usize,
    dim: usize,
    t: f64,
    scale: f64,
    out: &mut [f64],
) {
    let d = dim;
    if n > HORNER_MAX_DEGREE {
        de_casteljau_into(points, n, d, t, scale, out);
        return;
    }
    let s = 1.0 - t;
    let (ratio, factor, first, step): (f64, f64, usize, isize) = if t > 0.5 {
        (s / t, t.powi(n as i32), 0, 1)
    } else {
        (t / s, s.powi(n as i32), n, -1)
    };
    out.copy_from_slice(&points[first * d..(first + 1) * d]);
    let mut idx = first as isize;
    if n <= BINOMIAL_TABLE_DEGREE {
        // The binomials from the table: the same values (the recurrence
        // below is exact at these degrees) without a division per term.
        let row = &BINOMIALS[n * (n + 1) / 2..][..=n];
        for &coef in &row[1..] {
            idx += step;
            let p = &points[idx as usize * d..(idx as usize + 1) * d];
            for c in 0..d {
                out[c] = out[c] * ratio + coef * p[c];
            }
        }
    } else {
        let mut coef = 1.0;
        for i in 1..=n {
            coef = coef * (n - i + 1) as f64 / i as f64;
            idx += step;
            let p = &points[idx as usize * d..(idx as usize + 1) * d];
            for c in 0..d {
                out[c] = out[c] * ratio + coef * p[c];
            }
        }
    }
    let factor = factor * scale;
    for v in out.iter_mut() {
        *v *= factor;
    }
    // Coordinates near the top of the f64 range overflow the binomial-
    // weighted Horner sums (degree 40, coordinates 1e291: `C(40, 20) P_i`
    // is infinite, then `inf - inf` is NaN) although the value itself, a
    // convex combination for `t` in `[0, 1]`, is finite. The same sums on
    // the points scaled by `2^-(n+1)` cannot overflow; where the result is
    // really out of range (far extrapolation, huge derivatives) they
    // overflow when scaled back, and de Casteljau, which never leaves the
    // hull of the points, decides (it overflows too there). A NaN parameter
    // gives NaN whatever the scheme (callers' Newton steps on overflowing
    // dot products produce one; `O(n^2)` for nothing).
    if out.iter().any(|v| !v.is_finite()) && !t.is_nan() {
        horner_rescaled(points, n, d, t, scale, out);
        if out.iter().any(|v| !v.is_finite()) {
            de_casteljau_into(points, n, d, t, scale, out);
        }
    }
}

/// `scale * sum_i B_i^n(t) P_i` into `out` as [`bernstein_horner`] computes
/// it, choosing the unrolled form for dimensions 2 and 3 up to degree
/// [`BINOMIAL_TABLE_DEGREE`] ([`bernstein_horner_fixed`], the same
/// operations in the same order: bit-identical) and the general one
/// otherwise. The evaluation entry points of [`BezierCurve`] go through it.
#[inline(always)]
pub(crate) fn bernstein_horner_any(
    points: &[f64],
    n: usize,
    dim: usize,
    t: f64,
    scale: f64,
    out: &mut [f64],
) {
    if n <= BINOMIAL_TABLE_DEGREE {
        match dim {
            3 => {
                if let Ok(out) = <&mut [f64; 3]>::try_from(&mut *out) {
                    return bernstein_horner_small_degree(points, n, t, scale, out);
                }
            }
            2 => {
                if let Ok(out) = <&mut [f64; 2]>::try_from(&mut *out) {
                    return bernstein_horner_small_degree(points, n, t, scale, out);
                }
            }
            _ => {}
        }
    }
    bernstein_horner(points, n, dim, t, scale, out);
}

/// [`bernstein_horner_fixed`] with the degree a constant up to 8 (one
/// function per degree, [`bernstein_horner_degree`], the Horner loop and
/// the power unrolled), a variable above.
#[inline(always)]
fn bernstein_horner_small_degree<const D: usize>(
    points: &[f64],
    n: usize,
    t: f64,
    scale: f64,
    out: &mut [f64; D],
) {
    match n {
        0 => bernstein_horner_degree::<D, 0>(points, t, scale, out),
        1 => bernstein_horner_degree::<D, 1>(points, t, scale, out),
        2 => bernstein_horner_degree::<D, 2>(points, t, scale, out),
        3 => bernstein_horner_degree::<D, 3>(points, t, scale, out),
        4 => bernstein_horner_degree::<D, 4>(points, t, scale, out),
        5 => bernstein_horner_degree::<D, 5>(points, t, scale, out),
        6 => bernstein_horner_degree::<D, 6>(points, t, scale, out),
        7 => bernstein_horner_degree::<D, 7>(points, t, scale, out),
        8 => bernstein_horner_degree::<D, 8>(points, t, scale, out),
        _ => bernstein_horner_variable_degree(points, n, t, scale, out),
    }
}

/// [`bernstein_horner_fixed`] out of line for the degrees above 8, so that
/// its loop's registers do not make every caller of
/// [`bernstein_horner_any`] save and restore them.
#[inline(never)]
fn bernstein_horner_variable_degree<const D: usize>(
    points: &[f64],
    n: usize,
    t: f64,
    scale: f64,
    out: &mut [f64; D],
) {
    bernstein_horner_fixed(points, n, t, scale, out);
}

/// [`bernstein_horner_fixed`] at the constant degree `N`: the same
/// operations in the same order (so the same bits), with the points read
/// as `P_j` forwards or `P_(N-j)` backwards by a select on an index the
/// compiler knows to be at most `N` (no bounds check, no stride
/// arithmetic). Evaluation is mostly throughput-bound: a host's loop of
/// calls overlaps their latency chains, so the instructions are what a call
/// costs (issue 20). Not every saving is one: testing the finiteness with
/// one comparison (a sum of `v - v`, NaN for a value that is not finite)
/// took fewer instructions but lengthened the chain the branch waits for,
/// and the derivatives (three kernels a call) got 5 % slower.
#[inline(never)]
fn bernstein_horner_degree<const D: usize, const N: usize>(
    points: &[f64],
    t: f64,
    scale: f64,
    out: &mut [f64; D],
) {
    let points = &points[..(N + 1) * D];
    let s = 1.0 - t;
    let forward = t > 0.5;
    let (numerator, base) = if forward { (s, t) } else { (t, s) };
    let ratio = numerator / base;
    let factor = power(base, N) * scale;
    let point = |i: usize| -> [f64; D] { std::array::from_fn(|c| points[i * D + c]) };
    let sum = horner_steps(point, N, forward, ratio);
    for c in 0..D {
        out[c] = sum[c] * factor;
    }
    // Not finite somewhere (NaN `t` aside): the general scheme's fallbacks.
    if out.iter().any(|v| !v.is_finite()) && !t.is_nan() {
        bernstein_horner(points, N, D, t, scale, out);
    }
}

/// The Horner steps of the Bernstein-Horner scheme at degree `m` on the
/// rows `point(i)`, `i = 0..=m`: from `P_0` up in `(1 - t) / t` when
/// `forward`, from `P_m` down in `t / (1 - t)` otherwise, each step
/// `sum * ratio + C(m, j) P` (the sum before its power of `t` or `1 - t`).
/// The one loop of the constant-degree value kernel and of every order of
/// the derivatives ([`bernstein_horner_degree`], [`derivatives_degree`]).
#[inline(always)]
fn horner_steps<const D: usize>(
    point: impl Fn(usize) -> [f64; D],
    m: usize,
    forward: bool,
    ratio: f64,
) -> [f64; D] {
    let row = m * (m + 1) / 2;
    let at = |j: usize| if forward { j } else { m - j };
    let mut sum = point(at(0));
    for j in 1..=m {
        let coef = BINOMIALS[row + j];
        let p = point(at(j));
        for c in 0..D {
            sum[c] = sum[c] * ratio + coef * p[c];
        }
    }
    sum
}

/// [`derivatives_degree`] for the degree `n` when it is at most 8; `false`
/// (nothing written) otherwise.
#[inline(always)]
fn derivatives_by_degree<const D: usize>(
    points: &[f64],
    n: usize,
    t: f64,
    top: usize,
    out: &mut [f64],
) -> bool {
    match n {
        0 => derivatives_degree::<D, 0>(points, t, top, out),
        1 => derivatives_degree::<D, 1>(points, t, top, out),
        2 => derivatives_degree::<D, 2>(points, t, top, out),
        3 => derivatives_degree::<D, 3>(points, t, top, out),
        4 => derivatives_degree::<D, 4>(points, t, top, out),
        5 => derivatives_degree::<D, 5>(points, t, top, out),
        6 => derivatives_degree::<D, 6>(points, t, top, out),
        7 => derivatives_degree::<D, 7>(points, t, top, out),
        8 => derivatives_degree::<D, 8>(points, t, top, out),
        _ => return false,
    }
    true
}

/// Rows `0..=top` (`top <= N`) of `BezierCurve::eval_derivatives_into` for
/// `N + 1` points of dimension `D`: row `k` is
/// `N!/(N-k)! sum_i (Delta^k P)_i B_i^(N-k)(t)`, each sum by the operations
/// of [`bernstein_horner_degree`] at degree `N - k` with scale
/// `N!/(N-k)!` (so the same bits as one such call per order, tested), but
/// with the ratio `t / (1 - t)` or its inverse divided once for all the
/// orders, the differences kept in an array of the degree's size (not a
/// zeroed 96-value block), and no call or dispatch per order (issue 20: a
/// value with two derivatives took 882 instructions through the C ABI).
/// An order whose row is not finite is computed again by
/// [`bernstein_horner`], whose fallbacks decide, as in the kernel.
#[inline(never)]
fn derivatives_degree<const D: usize, const N: usize>(
    points: &[f64],
    t: f64,
    top: usize,
    out: &mut [f64],
) {
    const ROWS: usize = 9;
    debug_assert!(N < ROWS && top <= N);
    let mut diff = [[0.0f64; D]; ROWS];
    for (row, point) in diff.iter_mut().zip(points[..(N + 1) * D].chunks_exact(D)) {
        row.copy_from_slice(point);
    }
    let out = &mut out[..(top + 1) * D];
    let s = 1.0 - t;
    let forward = t > 0.5;
    let (numerator, base) = if forward { (s, t) } else { (t, s) };
    let ratio = numerator / base;
    let mut scale = 1.0;
    // Over `0..=N` with a break, not `0..=top`: the constant bound lets the
    // compiler unroll the orders, each with its degree `m` a constant (31
    // against 49 ns for a cubic's value and two derivatives).
    for k in 0..=N {
        if k > top {
            break;
        }
        let m = N - k;
        let factor = power(base, m) * scale;
        let sum = horner_steps(|i| diff[i], m, forward, ratio);
        let target = &mut out[k * D..(k + 1) * D];
        for c in 0..D {
            target[c] = sum[c] * factor;
        }
        if target.iter().any(|v| !v.is_finite()) && !t.is_nan() {
            let flat = diff.as_flattened();
            bernstein_horner(&flat[..(m + 1) * D], m, D, t, scale, target);
        }
        if k < top {
            for i in 0..m {
                let next = diff[i + 1];
                for (x, later) in diff[i].iter_mut().zip(next) {
                    *x = later - *x;
                }
            }
            scale *= m as f64;
        }
    }
}

/// `P(t_j)` for every parameter of `ts` into `out` (`ts.len() * D`,
/// parameter-major) for the `N + 1` points of dimension `D`: the operations
/// of [`bernstein_horner_degree`] (scale 1) on four parameters at a time,
/// lanes innermost so that the compiler packs them (the division, the
/// power and the Horner steps; each lane's direction is a select of the
/// point it reads), hence the same bits as one evaluation per parameter. A
/// lane whose value is not finite is evaluated again by the one-parameter
/// path, whose fallbacks decide.
#[inline(never)]
fn eval_many_horner<const D: usize, const N: usize>(points: &[f64], ts: &[f64], out: &mut [f64]) {
    const L: usize = 4;
    let points = &points[..(N + 1) * D];
    let row = &BINOMIALS[N * (N + 1) / 2..][..=N];
    let mut t_chunks = ts.chunks_exact(L);
    let mut out_chunks = out.chunks_exact_mut(L * D);
    for (tc, oc) in (&mut t_chunks).zip(&mut out_chunks) {
        let mut ratio = [0.0f64; L];
        let mut factor = [0.0f64; L];
        let mut forward = [false; L];
        for l in 0..L {
            let t = tc[l];
            let s = 1.0 - t;
            forward[l] = t > 0.5;
            let (numerator, base) = if forward[l] { (s, t) } else { (t, s) };
            ratio[l] = numerator / base;
            // `factor * scale` of the one-parameter path, scale 1: exact.
            factor[l] = power(base, N);
        }
        let mut sum = [[0.0f64; L]; D];
        for c in 0..D {
            for l in 0..L {
                sum[c][l] = if forward[l] {
                    points[c]
                } else {
                    points[N * D + c]
                };
            }
        }
        for j in 1..=N {
            let coef = row[j];
            let ahead = &points[j * D..][..D];
            let behind = &points[(N - j) * D..][..D];
            for c in 0..D {
                for l in 0..L {
                    let p = if forward[l] { ahead[c] } else { behind[c] };
                    sum[c][l] = sum[c][l] * ratio[l] + coef * p;
                }
            }
        }
        let mut finite = true;
        for l in 0..L {
            for c in 0..D {
                let v = sum[c][l] * factor[l];
                oc[l * D + c] = v;
                finite &= v.is_finite();
            }
        }
        if !finite {
            for (l, &t) in tc.iter().enumerate() {
                let value: &mut [f64; D] = (&mut oc[l * D..(l + 1) * D]).try_into().unwrap();
                if value.iter().any(|v| !v.is_finite()) {
                    bernstein_horner_degree::<D, N>(points, t, 1.0, value);
                }
            }
        }
    }
    for (&t, value) in t_chunks
        .remainder()
        .iter()
        .zip(out_chunks.into_remainder().chunks_exact_mut(D))
    {
        let value: &mut [f64; D] = value.try_into().unwrap();
        bernstein_horner_degree::<D, N>(points, t, 1.0, value);
    }
}

/// [`eval_many_horner`] with the degree a constant (up to 8, as
/// [`bernstein_horner_small_degree`]); `false` above, where the caller
/// evaluates parameter by parameter.
fn eval_many_by_degree<const D: usize>(
    points: &[f64],
    n: usize,
    ts: &[f64],
    out: &mut [f64],
) -> bool {
    match n {
        0 => eval_many_horner::<D, 0>(points, ts, out),
        1 => eval_many_horner::<D, 1>(points, ts, out),
        2 => eval_many_horner::<D, 2>(points, ts, out),
        3 => eval_many_horner::<D, 3>(points, ts, out),
        4 => eval_many_horner::<D, 4>(points, ts, out),
        5 => eval_many_horner::<D, 5>(points, ts, out),
        6 => eval_many_horner::<D, 6>(points, ts, out),
        7 => eval_many_horner::<D, 7>(points, ts, out),
        8 => eval_many_horner::<D, 8>(points, ts, out),
        _ => return false,
    }
    true
}

/// [`bernstein_horner`] for `D` coordinates known at compile time and
/// `n <= BINOMIAL_TABLE_DEGREE`, with no call and no branch on `t` inside:
/// the coordinate loop unrolled, `t^n` or `(1 - t)^n` by [`power`] (the
/// products of `f64::powi`), the direction of the Horner sum chosen by
/// index arithmetic. Every floating-point operation is the one
/// [`bernstein_horner`] performs, in the same order, so the result is the
/// same to the bit (tested); a sum that is not finite is handed to
/// [`bernstein_horner`], whose rescaled and de Casteljau fallbacks decide.
#[inline(always)]
fn bernstein_horner_fixed<const D: usize>(
    points: &[f64],
    n: usize,
    t: f64,
    scale: f64,
    out: &mut [f64; D],
) {
    debug_assert!(n <= BINOMIAL_TABLE_DEGREE);
    let points = &points[..(n + 1) * D];
    let s = 1.0 - t;
    // t > 1/2: Horner in s / t from P_0 up, times t^n; otherwise in t / s
    // from P_n down, times s^n.
    let forward = t > 0.5;
    let (numerator, base) = if forward { (s, t) } else { (t, s) };
    let ratio = numerator / base;
    let factor = power(base, n);
    let row = n * (n + 1) / 2;
    // Point j of the sum is P_j forwards, P_(n-j) backwards: as an offset
    // and a stride chosen once (selects, not a branch the loop is split on:
    // the direction follows `t`, which a caller sweeping a curve's
    // parameters makes unpredictable).
    let (start, stride) = if forward {
        (0, D as isize)
    } else {
        ((n * D) as isize, -(D as isize))
    };
    let at = |j: usize| (start + j as isize * stride) as usize;
    let mut sum = [0.0f64; D];
    sum.copy_from_slice(&points[at(0)..][..D]);
    for j in 1..=n {
        let coef = BINOMIALS[row + j];
        let p = &points[at(j)..][..D];
        for c in 0..D {
            sum[c] = sum[c] * ratio + coef * p[c];
        }
    }
    let factor = factor * scale;
    for c in 0..D {
        out[c] = sum[c] * factor;
    }
    if out.iter().any(|v| !v.is_finite()) && !t.is_nan() {
        bernstein_horner(points, n, D, t, scale, out);
    }
}

/// `base^n` by binary powering: the products of `f64::powi` in the same
/// order (the runtime routine `__powidf2` multiplies the running result by
/// the running square at each set bit), inlined instead of a library call.
#[inline(always)]
fn power(mut base: f64, mut n: usize) -> f64 {
    let mut result = 1.0;
    loop {
        if n & 1 != 0 {
            result *= base;
        }
        n >>= 1;
        if n == 0 {
            return result;
        }
        base *= base;
    }
}

/// [`bernstein_horner`] again on the coordinates of `out` that are not
/// finite, with the points scaled by `2^-(n+1)` (exactly, a power of two)
/// and the sum scaled back at the end: with `|ratio| <= 1` the partial sums
/// are at most `(1 + |ratio|)^n 2^-(n+1) max|P_i| <= max|P_i| / 2`, so they
/// cannot overflow. `O(n)` per coordinate where de Casteljau is `O(n^2)`
/// (a degree-60 curve with coordinates near `1e300` overflows the plain sums
/// at every parameter: its arc length, projections and intersections
/// evaluate it thousands of times). Finite coordinates are left as they
/// are; only a coordinate that overflows the plain sums is scaled, and its
/// points are that large, so the scaling loses nothing of its accuracy
/// (`n eps max|P_i|`, as unscaled).
#[cold]
#[inline(never)]
fn horner_rescaled(points: &[f64], n: usize, d: usize, t: f64, scale: f64, out: &mut [f64]) {
    let s = 1.0 - t;
    let (ratio, factor, first, step): (f64, f64, usize, isize) = if t > 0.5 {
        (s / t, t.powi(n as i32), 0, 1)
    } else {
        (t / s, s.powi(n as i32), n, -1)
    };
    // n <= HORNER_MAX_DEGREE = 512: both powers are normal numbers.
    let down = 2f64.powi(-(n as i32 + 1));
    let up = 2f64.powi(n as i32 + 1);
    let factor = factor * scale;
    for c in 0..d {
        if out[c].is_finite() {
            continue;
        }
        let mut sum = points[first * d + c] * down;
        let mut coef = 1.0;
        let mut idx = first as isize;
        for i in 1..=n {
            coef = coef * (n - i + 1) as f64 / i as f64;
            idx += step;
            sum = sum * ratio + coef * (points[idx as usize * d + c] * down);
        }
        out[c] = sum * factor * up;
    }
}

/// `scale * P(t)` by de Casteljau's algorithm (allocating), for
/// [`bernstein_horner`] above [`HORNER_MAX_DEGREE`] or when even its
/// rescaled sums overflow.
#[cold]
#[inline(never)]
fn de_casteljau_into(points: &[f64], n: usize, d: usize, t: f64, scale: f64, out: &mut [f64]) {
    let mut work = Vec::with_capacity((n + 1) * d);
    let value = blossom(
        &points[..(n + 1) * d],
        d,
        std::iter::repeat_n(t, n),
        &mut work,
    );
    for c in 0..d {
        out[c] = value[c] * scale;
    }
}

/// Euclidean distance between two points of equal dimension, without
/// overflow or underflow of the squares: when the plain sum of squares is
/// not a normal number the differences are scaled by the largest one first.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    let square = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>();
    if square.is_normal() {
        return square.sqrt();
    }
    scaled_norm(a.iter().zip(b).map(|(x, y)| x - y))
}

/// Euclidean norm.
pub(crate) fn norm(a: &[f64]) -> f64 {
    let square = a.iter().map(|x| x * x).sum::<f64>();
    if square.is_normal() {
        return square.sqrt();
    }
    scaled_norm(a.iter().copied())
}

/// The Euclidean norm of `values` computed as `m |values / m|`, `m` the
/// largest magnitude: the path of [`distance`] and [`norm`] when the plain
/// sum of squares is not a normal number, i.e. overflows (components above
/// about `1e154`) or underflows (components below about `1e-154`) although
/// the norm itself is in range. Zero when every value is zero; infinite when
/// one is; NaN when one is NaN (as the plain sum).
pub(crate) fn scaled_norm(values: impl Iterator<Item = f64> + Clone) -> f64 {
    if values.clone().any(f64::is_nan) {
        return f64::NAN;
    }
    let largest = values.clone().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest == 0.0 || !largest.is_finite() {
        return largest;
    }
    largest
        * values
            .map(|v| (v / largest) * (v / largest))
            .sum::<f64>()
            .sqrt()
}

/// The largest `|v|` of `values` (0 for none): the value of
/// `fold(0.0, |m, v| m.max(v.abs()))` (max is exact; a NaN `|v|` fails `>`
/// as `f64::max` ignores it; all terms are `>= +0`), by four running maxima
/// by comparison, then their maximum: a quarter of the dependent steps and
/// without maxnum's NaN handling (the curves' coordinate scales, on the hot
/// path of connect).
pub(crate) fn largest_magnitude(values: &[f64]) -> f64 {
    let larger = |m: f64, v: f64| if v > m { v } else { m };
    let mut lanes = [0.0f64; 4];
    let chunks = values.chunks_exact(4);
    let rest = chunks.remainder();
    for chunk in chunks {
        for (m, v) in lanes.iter_mut().zip(chunk) {
            *m = larger(*m, v.abs());
        }
    }
    for (m, v) in lanes.iter_mut().zip(rest) {
        *m = larger(*m, v.abs());
    }
    larger(larger(lanes[0], lanes[1]), larger(lanes[2], lanes[3]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table holds exactly what the division recurrence of the higher
    /// degrees computes (so both paths of `bernstein_horner` agree bit for
    /// bit), and every entry is the integer `C(n, k)`.
    #[test]
    fn binomial_table_is_the_recurrence() {
        for n in 0..=BINOMIAL_TABLE_DEGREE {
            let row = &BINOMIALS[n * (n + 1) / 2..][..=n];
            let mut coef = 1.0;
            assert_eq!(row[0], 1.0);
            for (i, &entry) in row.iter().enumerate().skip(1) {
                coef = coef * (n - i + 1) as f64 / i as f64;
                assert_eq!(entry, coef, "C({n}, {i})");
                assert_eq!(entry, crate::basis::binomial(n, i));
            }
        }
    }

    fn cubic() -> BezierCurve {
        BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap()
    }

    #[test]
    fn horner_matches_de_casteljau() {
        let c = cubic();
        for s in -10..=30 {
            let t = s as f64 / 20.0;
            let a = c.eval(t);
            let b = c.eval_de_casteljau(t);
            assert!(distance(&a, &b) < 1e-12, "t={t}");
        }
    }

    #[test]
    fn endpoints_and_derivative_at_zero() {
        let c = cubic();
        assert_eq!(c.eval(0.0), vec![0.0, 0.0]);
        assert_eq!(c.eval(1.0), vec![4.0, 0.0]);
        let d = c.derivative_at(0.0, 1);
        assert!((d[0] - 3.0).abs() < 1e-14 && (d[1] - 6.0).abs() < 1e-14);
    }

    #[test]
    fn constructor_errors_name_the_argument() {
        assert_eq!(
            BezierCurve::new(2, 1, vec![0.0; 3]).unwrap_err(),
            BezjoinError::LengthMismatch {
                name: "points".into(),
                expected: 4,
                actual: 3
            }
        );
        assert!(matches!(
            BezierCurve::new(0, 1, vec![]),
            Err(BezjoinError::InvalidArgument { .. })
        ));
        assert!(matches!(
            BezierCurve::new(1, 1, vec![0.0, f64::INFINITY]),
            Err(BezjoinError::NonFinite { index: 1, .. })
        ));
    }

    #[test]
    fn no_control_points_is_an_error_naming_points() {
        let expected = BezjoinError::InvalidArgument {
            name: "points".into(),
            reason: "at least one control point is needed".into(),
        };
        let no_rows: [[f64; 2]; 0] = [];
        assert_eq!(BezierCurve::from_rows(&no_rows).unwrap_err(), expected);
        let no_slices: Vec<Vec<f64>> = Vec::new();
        assert_eq!(BezierCurve::from_rows(&no_slices).unwrap_err(), expected);
        for cols in [0, 1, 3] {
            assert_eq!(
                BezierCurve::from_matrix(&DMatrix::zeros(0, cols)).unwrap_err(),
                expected,
                "0 x {cols} matrix"
            );
        }
        // Rows without coordinates: dimension 0, refused by the constructor.
        assert!(matches!(
            BezierCurve::from_matrix(&DMatrix::zeros(3, 0)),
            Err(BezjoinError::InvalidArgument { ref name, .. }) if name == "dim"
        ));
        let empty_rows: [[f64; 0]; 2] = [[], []];
        assert!(matches!(
            BezierCurve::from_rows(&empty_rows),
            Err(BezjoinError::InvalidArgument { ref name, .. }) if name == "dim"
        ));
        // One row is enough: a degree-0 curve (a point).
        let point = BezierCurve::from_matrix(&DMatrix::from_row_slice(1, 2, &[1.0, 2.0])).unwrap();
        assert_eq!((point.degree(), point.dim()), (0, 2));
        assert_eq!(point.eval(0.7), vec![1.0, 2.0]);
    }

    #[test]
    fn check_shape_gives_the_size_errors_of_new() {
        assert_eq!(BezierCurve::check_shape(2, 3, 8).unwrap(), 8);
        // The degree cap too: the C ABI must refuse it before reading
        // `(degree + 1) * dim` coordinates the caller may not have.
        for (dim, degree, len) in [
            (0, 3, 8),
            (usize::MAX, 3, 8),
            (2, 3, 7),
            (2, MAX_DEGREE + 1, 8194),
        ] {
            let shape = BezierCurve::check_shape(dim, degree, len).unwrap_err();
            let new = BezierCurve::new(dim, degree, vec![0.0; len]).unwrap_err();
            assert_eq!(shape.to_string(), new.to_string());
        }
    }

    #[test]
    fn degrees_above_the_maximum_are_refused_before_any_work() {
        let line = BezierCurve::from_rows(&[[0.0], [1.0]]).unwrap();
        let err = line.elevate_degree(1 << 30).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("new_degree: 1073741824 is above the supported maximum degree {MAX_DEGREE}")
        );
        assert!(line.elevate_degree(MAX_DEGREE).is_ok());
        let err = BezierCurve::new(1, MAX_DEGREE + 1, vec![0.0; MAX_DEGREE + 2]).unwrap_err();
        assert!(
            err.to_string().starts_with("degree: 4097 is above"),
            "{err}"
        );
    }

    #[test]
    fn segment_handles_reversal_and_degenerate() {
        let c = cubic();
        let r = c.segment(1.0, 0.0).unwrap();
        assert!(r.max_distance_sampled(&c.reverse(), 20) < 1e-14);
        let p = c.segment(0.3, 0.3).unwrap();
        let x = c.eval(0.3);
        for i in 0..=3 {
            assert!(distance(p.point(i), &x) < 1e-14);
        }
    }
}

#[cfg(test)]
mod high_degree_elevation_tests {
    use super::*;

    fn wiggly(degree: usize) -> BezierCurve {
        let pts: Vec<f64> = (0..=degree)
            .flat_map(|i| {
                let x = i as f64;
                [x, (x * 1.7).sin() * 3.0 + 0.25 * x]
            })
            .collect();
        BezierCurve::new(2, degree, pts).unwrap()
    }

    /// Largest distance between the curve and its elevation at parameters
    /// in [0, 1], by de Casteljau (convex combinations only), relative to
    /// the coordinate scale.
    fn elevation_error(c: &BezierCurve, m: usize) -> f64 {
        let e = c.elevate_degree(m).unwrap();
        assert_eq!(e.degree(), m);
        let mut worst = 0.0f64;
        for s in 0..=32 {
            let t = s as f64 / 32.0;
            let d = distance(&c.eval_de_casteljau(t), &e.eval_de_casteljau(t));
            worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
        }
        worst / c.coordinate_scale()
    }

    #[test]
    fn elevation_to_high_degree_keeps_the_curve() {
        let c = wiggly(5);
        for &m in &[60usize, 100, 300, 1100] {
            let err = elevation_error(&c, m);
            eprintln!("elevate 5 -> {m}: relative error {err:e}");
            assert!(err < 1e-13, "m = {m}: error {err:e}");
        }
        // From a high degree, too (binomials of the source degree beyond 2^53).
        let c = wiggly(70);
        for &m in &[71usize, 100, 1200] {
            let err = elevation_error(&c, m);
            eprintln!("elevate 70 -> {m}: relative error {err:e}");
            assert!(err < 1e-12, "m = {m}: error {err:e}");
        }
    }

    #[test]
    fn elevated_points_are_convex_combinations() {
        // Degree elevation weights are a probability distribution: every new
        // control point lies in the bounding box of the old ones.
        let c = BezierCurve::new(1, 0, vec![3.5]).unwrap();
        let e = c.elevate_degree(1500).unwrap();
        assert!(
            e.points().iter().all(|&v| v == 3.5),
            "constant curve changed"
        );
    }
}

#[cfg(test)]
mod high_degree_evaluation_tests {
    use super::*;

    /// Degree 60 with x coordinates up to 9e300 (the binomial-weighted
    /// Horner sums overflow) and y coordinates near 1e-300: the rescaled
    /// sums agree with de Casteljau to the rounding level of each
    /// coordinate's own scale, and a value that is really out of range
    /// (far extrapolation) still overflows as de Casteljau's does.
    #[test]
    fn overflowing_sums_are_rescaled_per_coordinate() {
        let n = 60;
        let points: Vec<f64> = (0..=n)
            .flat_map(|i| {
                let s = (i as f64 * 0.731).sin();
                [9e300 * s, 1e-300 * (i as f64 * 0.37).cos()]
            })
            .collect();
        let c = BezierCurve::new(2, n, points).unwrap();
        for &t in &[0.0, 1e-9, 0.3, 0.5, 0.77, 1.0 - 1e-12, 1.0] {
            let fast = c.eval(t);
            let reference = c.eval_de_casteljau(t);
            for (k, scale) in [9e300, 1e-300].into_iter().enumerate() {
                let bound = 8.0 * n as f64 * f64::EPSILON * scale;
                assert!(
                    (fast[k] - reference[k]).abs() <= bound,
                    "t = {t}, coordinate {k}: {} vs {}",
                    fast[k],
                    reference[k]
                );
            }
            let d = c.eval_derivatives(t, 2);
            assert!(d.iter().all(|v| v.is_finite()), "t = {t}: {d:?}");
        }
        let far = c.eval(50.0);
        let reference = c.eval_de_casteljau(50.0);
        assert!(!far[0].is_finite() && !reference[0].is_finite());
    }

    #[test]
    fn fast_evaluation_matches_de_casteljau_at_high_degree() {
        // Bernstein-Horner multiplies C(n, i) (beyond f64 above n ~ 1030)
        // by (1 - t)^n (below f64 near t = 1/2): both ends must still agree
        // with de Casteljau, which uses convex combinations only.
        for &n in &[200usize, 1100] {
            let pts: Vec<f64> = (0..=n).map(|i| (i as f64 * 0.37).sin()).collect();
            let c = BezierCurve::new(1, n, pts).unwrap();
            for &t in &[0.0, 0.25, 0.5, 0.7, 1.0] {
                let fast = c.eval(t)[0];
                let reference = c.eval_de_casteljau(t)[0];
                assert!(
                    (fast - reference).abs() <= 1e-12,
                    "n = {n}, t = {t}: {fast} vs {reference}"
                );
                let d = c.eval_derivatives(t, 1);
                let mut basis = vec![0.0; 2];
                c.eval_derivatives_basis(t, 1, &mut basis);
                assert!((d[0] - reference).abs() <= 1e-12, "n = {n}, t = {t}");
                assert!((basis[0] - reference).abs() <= 1e-12, "n = {n}, t = {t}");
                assert!(
                    (basis[1] - d[1]).abs() <= 1e-12 * basis[1].abs().max(n as f64),
                    "n = {n}, t = {t}: {} vs {}",
                    basis[1],
                    d[1]
                );
                assert!(d[1].is_finite(), "n = {n}, t = {t}: {}", d[1]);
            }
        }
    }
}

#[cfg(test)]
mod fixed_dimension_evaluation_tests {
    use super::*;

    use crate::test_values::Values;

    /// Parameters that exercise both Horner directions, the switch at 1/2
    /// to the last bit, the ends, extrapolation and NaN.
    fn parameters(values: &mut Values) -> Vec<f64> {
        let half = 0.5f64;
        let mut ts = vec![
            0.0,
            1.0,
            half,
            f64::from_bits(half.to_bits() + 1),
            f64::from_bits(half.to_bits() - 1),
            1e-300,
            1.0 - f64::EPSILON,
            -0.3,
            1.7,
            -40.0,
            1e3,
            f64::NAN,
        ];
        ts.extend((0..40).map(|_| 0.5 + 0.5 * values.signed()));
        ts
    }

    fn same_bits(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
    }

    /// The products of `power` are those of `f64::powi`: equal to the bit.
    #[test]
    fn power_is_powi_to_the_bit() {
        let mut values = Values(7);
        for _ in 0..500 {
            let base = 1.5 * values.signed();
            for n in 0..=64usize {
                assert_eq!(
                    power(base, n).to_bits(),
                    base.powi(n as i32).to_bits(),
                    "{base}^{n}"
                );
            }
        }
    }

    /// The unrolled dimension-2 and dimension-3 scheme (the path of
    /// `eval_into`, `eval_derivatives_into` and so of `bzj_curve_eval`)
    /// gives the bits of the general scheme it replaced, for every degree
    /// of the binomial table, scale factors (the derivative rows), and
    /// coordinates so large that the plain sums overflow (the fallbacks).
    #[test]
    fn fixed_dimension_scheme_is_the_general_scheme_to_the_bit() {
        let mut values = Values(20);
        for dim in [2usize, 3] {
            for n in 0..=BINOMIAL_TABLE_DEGREE {
                for magnitude in [1.0, 1e3, 1e-200, 9e300] {
                    let points: Vec<f64> = (0..(n + 1) * dim)
                        .map(|_| magnitude * values.signed())
                        .collect();
                    for t in parameters(&mut values) {
                        for scale in [1.0, 3.0, 42.0 * 41.0] {
                            let mut general = vec![0.0; dim];
                            bernstein_horner(&points, n, dim, t, scale, &mut general);
                            let mut fast = vec![0.0; dim];
                            bernstein_horner_any(&points, n, dim, t, scale, &mut fast);
                            assert!(
                                same_bits(&fast, &general),
                                "dim {dim}, n {n}, |P| {magnitude}, t {t}, scale {scale}: \
                                 {fast:?} vs {general:?}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// `eval_many_into` gives the bits of `eval_into` at every parameter:
    /// every length up to a few batches (the remainder path), both
    /// dimensions of the batch kernel and others, degrees with and without
    /// it, NaN and overflowing lanes among finite ones.
    #[test]
    fn eval_many_is_eval_at_each_parameter_to_the_bit() {
        let mut values = Values(22);
        for dim in [1usize, 2, 3, 4] {
            for n in [0usize, 1, 2, 3, 5, 8, 9, 15] {
                for magnitude in [1.0, 1e300] {
                    let points: Vec<f64> = (0..(n + 1) * dim)
                        .map(|_| magnitude * values.signed())
                        .collect();
                    let curve = BezierCurve::new(dim, n, points).unwrap();
                    let mut ts = parameters(&mut values);
                    ts.extend([1e3, -1e3, 0.25, f64::NAN, 0.75]);
                    for len in 0..ts.len() {
                        let ts = &ts[..len];
                        let mut many = vec![0.0; len * dim];
                        curve.eval_many_into(ts, &mut many);
                        for (j, &t) in ts.iter().enumerate() {
                            let mut one = vec![0.0; dim];
                            curve.eval_into(t, &mut one);
                            assert!(
                                same_bits(&many[j * dim..(j + 1) * dim], &one),
                                "dim {dim}, n {n}, |P| {magnitude}, len {len}, t[{j}] = {t}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// `eval_into` and `eval_derivatives_into` on curves of dimensions 1 to
    /// 4 give the bits of the general scheme applied by hand (the old
    /// path: differences of the points, one general sum per order), for
    /// every order count up to past the degree, every degree of the
    /// specialised rows (0 to 8) and some above, and poles near `1e306`
    /// (whose sums and derivatives overflow: the fallbacks' bits).
    #[test]
    fn curve_evaluation_is_the_general_scheme_to_the_bit() {
        let mut values = Values(33);
        for dim in [1usize, 2, 3, 4] {
            for n in [0usize, 1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 32] {
                for magnitude in [4.0, 1e306] {
                    let points: Vec<f64> = (0..(n + 1) * dim)
                        .map(|_| magnitude * values.signed())
                        .collect();
                    let curve = BezierCurve::new(dim, n, points.clone()).unwrap();
                    for t in parameters(&mut values) {
                        let mut value = vec![0.0; dim];
                        curve.eval_into(t, &mut value);
                        let mut general = vec![0.0; dim];
                        bernstein_horner(&points, n, dim, t, 1.0, &mut general);
                        assert!(same_bits(&value, &general), "dim {dim}, n {n}, t {t}");

                        // Every order count, up to past the degree: the
                        // degree-specialised rows stop at `top`.
                        for max_order in 0..=n + 1 {
                            let mut rows = vec![f64::NAN; (max_order + 1) * dim];
                            curve.eval_derivatives_into(t, max_order, &mut rows);
                            let mut expected = vec![0.0; (max_order + 1) * dim];
                            let mut diff = points.clone();
                            let mut factor = 1.0;
                            for k in 0..=max_order.min(n) {
                                let m = n - k;
                                bernstein_horner(
                                    &diff[..(m + 1) * dim],
                                    m,
                                    dim,
                                    t,
                                    factor,
                                    &mut expected[k * dim..(k + 1) * dim],
                                );
                                for i in 0..m * dim {
                                    diff[i] = diff[i + dim] - diff[i];
                                }
                                factor *= m as f64;
                            }
                            assert!(
                                same_bits(&rows, &expected),
                                "dim {dim}, n {n}, |P| {magnitude}, t {t}, order {max_order}: \
                                 {rows:?} vs {expected:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}
